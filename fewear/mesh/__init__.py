"""Meshes of the bushing and the flat (gmsh on rank 0, distributed by DOLFINx; imported explicitly).

- :mod:`fewear.mesh.bushing`: the structured, bore-graded O-grid of the annulus with second-order
  geometry and the facet tags ``BORE_TAG`` / ``OUTER_TAG``; re-meshed on a worn bore with
  ``bore_profile``.
- :mod:`fewear.mesh.flat`: the structured, contact-graded mesh of a flat under a rigid cylinder
  (``CONTACT_TAG`` on the top, ``CLAMPED_TAG`` on the bottom).
- :mod:`fewear.mesh.gmsh_model`: a gmsh model built on rank 0, distributed as a DOLFINx mesh.
- :mod:`fewear.mesh.tags`: ``CONTACT_TAG`` / ``CLAMPED_TAG``, the facet tags the contact solver
  reads (the bushing's ``BORE_TAG`` / ``OUTER_TAG`` are these).
- :mod:`fewear.mesh.geometry`: ``BushingGeometry`` and ``MeshSettings``, ``FlatGeometry`` and
  ``FlatMeshSettings`` (plain data, no DOLFINx).
- :mod:`fewear.mesh.bore`: ``BoreNodes`` (the bore's Q8 nodes, gathered over the ranks) and
  ``bore_node_weights`` (their Gauss-Lobatto weights).
- :mod:`fewear.mesh.profile`: the worn bore r(theta) as a periodic table (no DOLFINx).
- :mod:`fewear.mesh.ale`: ALE motion of the bore and the interior (``BoreMotion``).
- :mod:`fewear.mesh.quality`: scaled Jacobian, angle sine, bore motion; ``RemeshLimits``.
"""
