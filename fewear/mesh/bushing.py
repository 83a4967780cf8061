"""The bushing mesh: a structured O-grid of the annulus R_b <= r <= R_o, built with gmsh.

Four transfinite quarter-annulus patches graded towards the bore, 9-node quadrilaterals (DOLFINx
0.5.2 cannot use gmsh's 8-node type as geometry) with the bore nodes at the uniform angles
k pi / n_theta; a worn bore is the circular grid with every node moved along its ray.
Facet tags ``BORE_TAG`` and ``OUTER_TAG``; gmsh runs on rank 0. Method notes: docs/run.md.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import gmsh
import numpy as np
from mpi4py import MPI

from fewear.errors import FewearInputError
from fewear.mesh.geometry import BushingGeometry, MeshSettings
from fewear.mesh.gmsh_model import distributed_mesh
from fewear.mesh.profile import checked_periodic_table, periodic_linear, polar_angle
from fewear.mesh.tags import CLAMPED_TAG, CONTACT_TAG

BORE_TAG = CONTACT_TAG
OUTER_TAG = CLAMPED_TAG
BUSHING_TAG = 3


def radial_progression(mesh_settings: MeshSettings) -> float:
    """Ratio of consecutive radial element sizes, from the bore outward (>= 1)."""
    n_r = mesh_settings.radial_element_count
    return mesh_settings.radial_grading_ratio ** (1.0 / (n_r - 1))


def bushing_mesh(geometry: BushingGeometry, mesh_settings: MeshSettings, comm=MPI.COMM_WORLD,
                 bore_profile: tuple | None = None):
    """Mesh the bushing annulus; returns ``(mesh, cell_tags, facet_tags)`` on ``comm``.

    The element size along the bore is ``2 pi R_b / n_theta`` with n_theta from
    :meth:`MeshSettings.circumferential_element_count` (at most ``bore_element_size_m``), R_b =
    ``geometry.inner_radius_m`` also for a worn bore. ``bore_profile``: ``(angle_rad, radius_m)``,
    the worn bore r_b(theta) as a periodic table (linear between its angles, every radius in
    (0, R_o)); ``None``, the circle R_b.
    """
    bore_radius_m = _bore_radius_function(geometry, bore_profile)
    mesh_data = distributed_mesh(comm, "bushing", lambda: _build_o_grid(geometry, mesh_settings))
    _fit_nodes_to_bore(mesh_data[0].geometry.x, geometry, mesh_settings, bore_radius_m)
    return mesh_data


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


def _bore_radius_function(geometry: BushingGeometry,
                          bore_profile: tuple | None) -> Callable[[np.ndarray], np.ndarray]:
    """r_b(theta) (m) of the bore: the circle R_b, or the periodic table ``bore_profile``."""
    if bore_profile is None:
        return lambda angle_rad: np.full_like(angle_rad, geometry.inner_radius_m)
    angles, radii = checked_periodic_table(*bore_profile, name="bore_profile")
    if not np.all((radii > 0.0) & (radii < geometry.outer_radius_m)):
        raise FewearInputError(
            f"bore_profile: radii from {radii.min():.6g} to {radii.max():.6g} m; every radius must "
            f"lie in (0, {geometry.outer_radius_m:.6g}) m, the outer radius (the wall is worn "
            "through)")
    return periodic_linear(angles, radii)


def _fit_nodes_to_bore(x: np.ndarray, geometry: BushingGeometry, mesh_settings: MeshSettings,
                       bore_radius_m: Callable[[np.ndarray], np.ndarray]) -> None:
    """Snap the bore nodes of the O-grid's node coordinates ``x`` (this rank's, (n, 3), in place)
    to the angles k pi / n_theta and move every node along its ray to the bore ``bore_radius_m``
    (the map in the method notes). The bore nodes are the nodes on the circle R_b (gmsh puts
    them there to rounding; the next ring lies a bore element height further out). Done on the
    mesh each rank holds: node by node through gmsh's API it cost 80 ms per mesh."""
    r_in, r_out = geometry.inner_radius_m, geometry.outer_radius_m
    bore_node_count = 2 * mesh_settings.circumferential_element_count(r_in)
    node_spacing_rad = 2.0 * math.pi / bore_node_count
    xy = x[:, :2]
    angle = polar_angle(xy)
    radius = np.hypot(xy[:, 0], xy[:, 1])
    on_bore = np.abs(radius - r_in) <= 1e-9 * r_in
    index = np.mod(np.round(angle[on_bore] / node_spacing_rad), bore_node_count)
    angle[on_bore] = node_spacing_rad * index
    radius[on_bore] = r_in
    bore = bore_radius_m(angle)
    radius = bore + (radius - r_in) * (r_out - bore) / (r_out - r_in)
    # the C library's cos and sin, as gmsh's mesh had them (NumPy's may differ in the last bit)
    x[:, 0] = radius * np.array([math.cos(a) for a in angle])
    x[:, 1] = radius * np.array([math.sin(a) for a in angle])
    x[:, 2] = 0.0
