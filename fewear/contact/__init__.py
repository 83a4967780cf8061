"""Pin-in-bushing contact: the FE model of the joint's bore (DOLFINx/PETSc, imported explicitly).

- :mod:`fewear.contact.params`: material, contact settings, ``ContactProblem`` and
  ``contact_problem_from_config``, ``FlatContactProblem`` (no DOLFINx; the geometry is in
  :mod:`fewear.mesh.geometry`).
- :mod:`fewear.contact.result`: ``ContactResult``, the plain-data output (no DOLFINx).
- :mod:`fewear.contact.newton`: ``ContactNewton``, the active-set Newton both paths share, and
  :mod:`fewear.contact.newton_kernels`, its compiled kernels on the bore nodes.
- :mod:`fewear.contact.admissible`: the forces the model can carry; ``ContactLoadError``.
- :mod:`fewear.contact.solver`: ``BushingContactSolver``, the full Newton solve in DOLFINx.
- :mod:`fewear.contact.flat`: ``FlatContactSolver``, the same contact for a rigid cylinder pressed
  on an elastic flat (normal force, fretting steps with Coulomb friction), the flat condensed onto
  its top and the Newton compiled (:mod:`fewear.contact.flat_newton`).
- :mod:`fewear.contact.condensed`: ``CondensedBushingContact``, the same answer from the bushing
  condensed onto its bore (the fast path for the wear loop).
"""
