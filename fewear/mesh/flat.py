"""The flat's mesh: a structured quadrilateral mesh of a rectangle under a rigid cylinder (gmsh).

Three transfinite patches (a trapezoid under the contact zone, graded sides), 9-node quadrilaterals
with every top node on the flat's top; :func:`worn_node_y_m` moves the nodes onto a worn top.
Facet tags ``CONTACT_TAG`` on the top, ``CLAMPED_TAG`` on the bottom; gmsh runs on rank 0.
Method notes: docs/scar.md.
"""

from __future__ import annotations

import gmsh
import numpy as np
from mpi4py import MPI
from scipy.optimize import brentq

from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings
from fewear.mesh.gmsh_model import distributed_mesh
from fewear.mesh.tags import CLAMPED_TAG, CONTACT_TAG

FLAT_TAG = 3


def progression_ratio(first_size_m: float, length_m: float, count: int) -> float:
    """The ratio r >= 1 of a geometric progression of ``count`` sizes that starts at
    ``first_size_m`` and adds up to ``length_m``: h (r^n - 1)/(r - 1) = L (1 when n h = L)."""
    excess = length_m / first_size_m - count
    if excess <= 0.0:
        return 1.0

    def shortfall(ratio: float) -> float:
        return sum(ratio**k for k in range(count)) - length_m / first_size_m

    return brentq(shortfall, 1.0, (length_m / first_size_m) ** (1.0 / max(count - 1, 1)) + 1.0,
                  xtol=1e-14, rtol=1e-14)


def flat_mesh(geometry: FlatGeometry, mesh_settings: FlatMeshSettings, comm=MPI.COMM_WORLD):
    """Mesh the flat (method notes); returns ``(mesh, cell_tags, facet_tags)`` on ``comm``."""
    mesh_settings.require_fits(geometry)
    return distributed_mesh(comm, "flat", lambda: _build_patches(geometry, mesh_settings))


def _build_patches(geometry: FlatGeometry, mesh_settings: FlatMeshSettings) -> None:
    """Create the three transfinite patches in the current gmsh model and mesh them."""
    geo = gmsh.model.geo
    half_width, x_c = 0.5 * geometry.width_m, mesh_settings.contact_zone_half_width_m
    x_bottom = 0.5 * (x_c + half_width)  # the middle patch's bottom corners, |x|
    top, bottom = geometry.top_y_m, geometry.top_y_m - geometry.height_m
    top_points = [geo.addPoint(x, top, 0.0) for x in (-half_width, -x_c, x_c, half_width)]
    bottom_points = [geo.addPoint(x, bottom, 0.0)
                     for x in (-half_width, -x_bottom, x_bottom, half_width)]
    # along the top and bottom from the middle outward (the side sizes grow outward), and down
    top_lines, bottom_lines = ([geo.addLine(points[1], points[0]),
                                geo.addLine(points[1], points[2]),
                                geo.addLine(points[2], points[3])]
                               for points in (top_points, bottom_points))
    downs = [geo.addLine(t, b) for t, b in zip(top_points, bottom_points)]
    loops = [[top_lines[0], downs[0], -bottom_lines[0], -downs[1]],
             [bottom_lines[1], -downs[2], -top_lines[1], downs[1]],
             [bottom_lines[2], -downs[3], -top_lines[2], downs[2]]]
    surfaces = [geo.addPlaneSurface([geo.addCurveLoop(loop)]) for loop in loops]
    geo.synchronize()
    _set_grading(geometry, mesh_settings, top_lines, bottom_lines, downs, surfaces)
    gmsh.model.addPhysicalGroup(2, surfaces, FLAT_TAG)
    gmsh.model.addPhysicalGroup(1, top_lines, CONTACT_TAG)
    gmsh.model.addPhysicalGroup(1, bottom_lines, CLAMPED_TAG)
    gmsh.model.setPhysicalName(2, FLAT_TAG, "flat")
    gmsh.model.setPhysicalName(1, CONTACT_TAG, "top")
    gmsh.model.setPhysicalName(1, CLAMPED_TAG, "bottom")
    gmsh.option.setNumber("Mesh.SecondOrderIncomplete", 0)
    gmsh.model.mesh.generate(2)
    gmsh.model.mesh.setOrder(2)


def _set_grading(geometry: FlatGeometry, mesh_settings: FlatMeshSettings, top_lines,
                 bottom_lines, downs, surfaces) -> None:
    """Transfinite node counts and gradings of the patches' curves (method notes)."""
    mesh = gmsh.model.mesh
    size = mesh_settings.contact_element_length_m()
    n_contact, n_side = mesh_settings.contact_element_count(), mesh_settings.side_element_count
    n_depth = mesh_settings.depth_element_count
    side_length = 0.5 * geometry.width_m - mesh_settings.contact_zone_half_width_m
    side_ratio = progression_ratio(size, side_length, n_side)
    depth_ratio = progression_ratio(size, geometry.height_m, n_depth)
    for side in (0, 2):
        mesh.setTransfiniteCurve(top_lines[side], n_side + 1, "Progression", side_ratio)
        mesh.setTransfiniteCurve(bottom_lines[side], n_side + 1)
    for line in (top_lines[1], bottom_lines[1]):
        mesh.setTransfiniteCurve(line, n_contact + 1)
    for line in downs:  # the slanted ones too: the same fractions of the height
        mesh.setTransfiniteCurve(line, n_depth + 1, "Progression", depth_ratio)
    for surface in surfaces:
        mesh.setTransfiniteSurface(surface)
        mesh.setRecombine(2, surface)


def worn_node_y_m(made_xy_m, geometry: FlatGeometry, depth_at) -> np.ndarray:
    """y (m) of the flat's nodes on the worn flat: the counterpart of the bushing's radial map
    (:mod:`fewear.mesh.bushing`) along -y, x kept. A node made at (x, y) goes to

        y' = y_b + (y - y_b) (H - h(x)) / H,    y_b = y_top - H the bottom,

    so top nodes land on y_top - h(x) exactly, the bottom stays, and every element of a column
    shrinks by the same factor (H - h)/H. ``made_xy_m`` (n, 2): the nodes as meshed by
    :func:`flat_mesh`; ``depth_at``: h(x) (m), vectorised (e.g.
    :meth:`fewear.wear.state.FlatWearState.depth_at`). Write the result to ``mesh.geometry.x``
    and update the contact solver's geometry."""
    x, y = made_xy_m[:, 0], made_xy_m[:, 1]
    bottom = geometry.top_y_m - geometry.height_m
    return bottom + (y - bottom) * (geometry.height_m - depth_at(x)) / geometry.height_m
