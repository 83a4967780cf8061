"""The bushing O-grid: exact circles with second-order geometry, converging area, tags, grading."""

import math

import numpy as np
import pytest

from fewear.mesh.geometry import BushingGeometry, MeshSettings

GEOMETRY = BushingGeometry(inner_radius_m=0.010, outer_radius_m=0.015, width_m=0.018,
                           pin_radius_m=0.0095)


def build(n_theta, radial_count=4, grading=1.0):
    from fewear.mesh.bushing import bushing_mesh

    size = 2 * math.pi * GEOMETRY.inner_radius_m / n_theta * (1 + 1e-9)
    return bushing_mesh(GEOMETRY, MeshSettings(size, radial_count, grading))


def facet_geometry_nodes(msh, facets):
    """Geometry nodes (vertices and edge midpoint) of each facet, by the solver's convention."""
    from fewear.mesh.bore import QUAD_EDGE_VERTICES

    tdim = msh.topology.dim
    msh.topology.create_connectivity(tdim - 1, tdim)
    msh.topology.create_connectivity(tdim, tdim - 1)
    f2c, c2f = msh.topology.connectivity(tdim - 1, tdim), msh.topology.connectivity(tdim, tdim - 1)
    nodes = []
    for facet in facets:
        cell = f2c.links(facet)[0]
        local = list(c2f.links(cell)).index(facet)
        dofs = msh.geometry.dofmap.links(cell)
        nodes.append([dofs[k] for k in QUAD_EDGE_VERTICES[local]] + [dofs[4 + local]])
    return np.array(nodes)


def test_tags_counts_and_second_order_nodes_on_both_circles():
    from fewear.mesh.bushing import BORE_TAG, OUTER_TAG

    n_theta, n_r = 40, 5
    msh, cell_tags, facet_tags = build(n_theta, n_r)
    assert msh.topology.index_map(2).size_local == n_theta * n_r
    assert msh.geometry.dofmap.links(0).size == 9            # second-order quadrilaterals
    for tag, radius in ((BORE_TAG, GEOMETRY.inner_radius_m), (OUTER_TAG, GEOMETRY.outer_radius_m)):
        facets = facet_tags.find(tag)
        assert facets.size == n_theta
        nodes = facet_geometry_nodes(msh, facets)
        x = msh.geometry.x[nodes.reshape(-1)]
        r = np.hypot(x[:, 0], x[:, 1])
        np.testing.assert_allclose(r, radius, rtol=1e-13)
        # the midpoint node halves the arc between the two vertices (gmsh places arc nodes to
        # ~1e-10 rad)
        angle = np.arctan2(x[:, 1], x[:, 0]).reshape(-1, 3)
        half = np.angle(np.exp(1j * (angle[:, 2] - angle[:, 0])))
        np.testing.assert_allclose(np.abs(half), math.pi / n_theta, rtol=1e-8)
    assert np.all(cell_tags.values == cell_tags.values[0])


def test_bore_element_size_is_at_most_the_setting_and_multiple_of_four():
    settings = MeshSettings(bore_element_size_m=0.0007)
    n = settings.circumferential_element_count(GEOMETRY.inner_radius_m)
    assert n % 4 == 0
    assert 2 * math.pi * GEOMETRY.inner_radius_m / n <= 0.0007
    assert 2 * math.pi * GEOMETRY.inner_radius_m / (n - 4) > 0.0007


def test_radial_grading_ratio_of_outermost_to_innermost_element():
    n_r, grading = 8, 5.0
    msh, _, _ = build(16, n_r, grading)
    x = msh.geometry.x
    on_axis = np.abs(x[:, 1]) < 1e-12
    radii = np.sort(x[on_axis & (x[:, 0] > 0), 0])[::2]        # vertices only (skip midpoints)
    sizes = np.diff(radii)
    assert sizes.size == n_r
    assert sizes[-1] / sizes[0] == pytest.approx(grading, rel=1e-7)   # gmsh node placement


def test_annulus_area_converges_at_fourth_order():
    """Quadratic arcs: the area error of the annulus falls as h^4 (measured 3.99)."""
    import ufl
    from dolfinx import fem
    from mpi4py import MPI

    exact = math.pi * (GEOMETRY.outer_radius_m**2 - GEOMETRY.inner_radius_m**2)
    sizes, errors = [], []
    for n_theta in (8, 16, 32):
        msh, _, _ = build(n_theta)
        area = msh.comm.allreduce(fem.assemble_scalar(fem.form(1.0 * ufl.dx(domain=msh))),
                                  op=MPI.SUM)
        sizes.append(1.0 / n_theta)
        errors.append(abs(area - exact) / exact)
    rate = np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    assert rate == pytest.approx(4.0, abs=0.15)
    assert errors[-1] < 5e-6
