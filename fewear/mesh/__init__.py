"""Meshes of the bushing (gmsh on rank 0, distributed by DOLFINx; imported explicitly).

- :mod:`fewear.mesh.bushing`: the structured, bore-graded O-grid of the annulus with second-order
  geometry and the facet tags ``BORE_TAG`` / ``OUTER_TAG``; re-meshed on a worn bore with
  ``bore_profile``.
- :mod:`fewear.mesh.geometry`: ``BushingGeometry`` and ``MeshSettings`` (plain data, no DOLFINx).
- :mod:`fewear.mesh.bore`: ``BoreNodes`` (the bore's Q8 nodes, gathered over the ranks) and
  ``bore_node_weights`` (their Gauss-Lobatto weights).
- :mod:`fewear.mesh.profile`: the worn bore r(theta) as a periodic table (no DOLFINx).
- :mod:`fewear.mesh.ale`: ALE motion of the bore and the interior (``BoreMotion``).
- :mod:`fewear.mesh.quality`: scaled Jacobian, angle sine, bore motion; ``RemeshLimits``.
"""
