"""Meshes of the bushing (gmsh on rank 0, distributed by DOLFINx; imported explicitly).

- :mod:`fewear.mesh.bushing`: the structured, bore-graded O-grid of the annulus with second-order
  geometry and the facet tags ``BORE_TAG`` / ``OUTER_TAG``.
"""
