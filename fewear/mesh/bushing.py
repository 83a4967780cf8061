"""The bushing mesh: a structured O-grid of the annulus R_b <= r <= R_o, built with gmsh.

Four quarter-annulus patches, each transfinite (n_theta/4 elements along the arcs, n_r across the
wall, a geometric progression of radial sizes so the elements get finer toward the bore) and
recombined into quadrilaterals. The geometry is second order (9-node quadrilaterals, gmsh type 10:
DOLFINx 0.5.2 cannot use gmsh's 8-node type 16 as geometry), so every bore node, vertex or edge
midpoint, lies on the circle to rounding. The displacement field on top is serendipity degree 2
(the paper's 8-node quadrilateral), see :mod:`fewear.contact.solver`.

gmsh runs on rank 0 only; ``dolfinx.io.gmshio.model_to_mesh`` distributes the mesh. Facet tags:
``BORE_TAG`` on the bore, ``OUTER_TAG`` on the outer surface; the cells carry ``BUSHING_TAG``.
"""

from __future__ import annotations

import math

import gmsh
from mpi4py import MPI

from fewear.contact.params import BushingGeometry, MeshSettings

BORE_TAG = 1
OUTER_TAG = 2
BUSHING_TAG = 3


def radial_progression(mesh_settings: MeshSettings) -> float:
    """Ratio of consecutive radial element sizes, from the bore outward (>= 1)."""
    n_r = mesh_settings.radial_element_count
    return mesh_settings.radial_grading_ratio ** (1.0 / (n_r - 1))


def bushing_mesh(geometry: BushingGeometry, mesh_settings: MeshSettings, comm=MPI.COMM_WORLD):
    """Mesh the bushing annulus; returns ``(mesh, cell_tags, facet_tags)`` on ``comm``.

    The element size along the bore is ``2 pi R_b / n_theta`` with n_theta from
    :meth:`MeshSettings.circumferential_element_count` (at most ``bore_element_size_m``).
    """
    from dolfinx.io import gmshio

    model_rank = 0
    if comm.rank == model_rank:
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add("fewear_bushing")
        try:
            _build_o_grid(geometry, mesh_settings)
            mesh, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, comm, model_rank, gdim=2)
        finally:
            gmsh.finalize()
    else:
        mesh, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, comm, model_rank, gdim=2)
    mesh.name = "bushing"
    return mesh, cell_tags, facet_tags


def _build_o_grid(geometry: BushingGeometry, mesh_settings: MeshSettings) -> None:
    """Create the four transfinite quarter-annulus patches in the current gmsh model."""
    geo = gmsh.model.geo
    r_in, r_out = geometry.inner_radius_m, geometry.outer_radius_m
    n_theta = mesh_settings.circumferential_element_count(r_in)
    n_r = mesh_settings.radial_element_count
    centre = geo.addPoint(0.0, 0.0, 0.0)
    angles = [0.5 * math.pi * k for k in range(4)]
    inner = [geo.addPoint(r_in * math.cos(a), r_in * math.sin(a), 0.0) for a in angles]
    outer = [geo.addPoint(r_out * math.cos(a), r_out * math.sin(a), 0.0) for a in angles]
    inner_arcs = [geo.addCircleArc(inner[k], centre, inner[(k + 1) % 4]) for k in range(4)]
    outer_arcs = [geo.addCircleArc(outer[k], centre, outer[(k + 1) % 4]) for k in range(4)]
    radials = [geo.addLine(inner[k], outer[k]) for k in range(4)]
    surfaces = []
    for k in range(4):
        loop = geo.addCurveLoop([inner_arcs[k], radials[(k + 1) % 4], -outer_arcs[k], -radials[k]])
        surfaces.append(geo.addPlaneSurface([loop]))
    geo.synchronize()
    mesh = gmsh.model.mesh
    for arc in inner_arcs + outer_arcs:
        mesh.setTransfiniteCurve(arc, n_theta // 4 + 1)
    for line in radials:
        mesh.setTransfiniteCurve(line, n_r + 1, "Progression", radial_progression(mesh_settings))
    for surface in surfaces:
        mesh.setTransfiniteSurface(surface)
        mesh.setRecombine(2, surface)
    gmsh.model.addPhysicalGroup(2, surfaces, BUSHING_TAG)
    gmsh.model.addPhysicalGroup(1, inner_arcs, BORE_TAG)
    gmsh.model.addPhysicalGroup(1, outer_arcs, OUTER_TAG)
    gmsh.model.setPhysicalName(2, BUSHING_TAG, "bushing")
    gmsh.model.setPhysicalName(1, BORE_TAG, "bore")
    gmsh.model.setPhysicalName(1, OUTER_TAG, "outer")
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    mesh.generate(2)
    mesh.setOrder(2)
