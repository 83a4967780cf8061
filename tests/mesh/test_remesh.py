"""Re-meshing from the worn bore: same O-grid, bore nodes exactly on r(theta) at the reference
mesh's node angles, outer circle kept, grading kept, every element valid."""

import math

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.mesh.profile import periodic_linear, polar_angle
from tests.mesh.cases import GEOMETRY, bore_node_angles, coarse_settings, two_lobes

N_THETA, N_R = 48, 4
R_B, R_O = GEOMETRY.inner_radius_m, GEOMETRY.outer_radius_m


def worn_mesh(bore_profile, grading=2.0):
    from fewear.mesh.bushing import bushing_mesh

    return bushing_mesh(GEOMETRY, coarse_settings(N_THETA, N_R, grading),
                        bore_profile=bore_profile)


def tagged_nodes(msh, facet_tags, tag):
    """Local geometry nodes (vertices and edge midpoints) of the facets tagged ``tag``."""
    from dolfinx import fem

    from fewear.mesh.ale import node_to_dof

    space = fem.VectorFunctionSpace(msh, ("Q", 2))
    dof_node = np.argsort(node_to_dof(msh, space))
    return np.unique(dof_node[fem.locate_dofs_topological(space, 1, facet_tags.find(tag))])


def bore_polar(msh, facet_tags):
    from fewear.mesh.bushing import BORE_TAG

    x = msh.geometry.x[tagged_nodes(msh, facet_tags, BORE_TAG)]
    angle = polar_angle(x)
    order = np.argsort(angle)
    return angle[order], np.hypot(x[:, 0], x[:, 1])[order]


def test_circular_mesh_has_bore_nodes_at_uniform_angles():
    msh, _, facet_tags = worn_mesh(None)
    angle, radius = bore_polar(msh, facet_tags)
    np.testing.assert_allclose(angle, bore_node_angles(N_THETA), rtol=0, atol=1e-15)
    np.testing.assert_allclose(radius, R_B, rtol=1e-15)


def test_worn_bore_nodes_sit_exactly_on_the_profile_at_the_reference_angles():
    from fewear.mesh.bushing import OUTER_TAG
    from fewear.mesh.quality import QualityMeter

    angles = bore_node_angles(N_THETA)
    worn_radius = R_B + two_lobes(angles)
    msh, _, facet_tags = worn_mesh((angles, worn_radius))
    angle, radius = bore_polar(msh, facet_tags)
    np.testing.assert_allclose(angle, angles, rtol=0, atol=1e-15)
    np.testing.assert_allclose(radius, worn_radius, rtol=2e-16)
    outer = msh.geometry.x[tagged_nodes(msh, facet_tags, OUTER_TAG)]
    np.testing.assert_allclose(np.hypot(outer[:, 0], outer[:, 1]), R_O, rtol=1e-13)
    assert msh.topology.index_map(2).size_local == N_THETA * N_R
    quality = QualityMeter(msh, facet_tags).measure()
    print(f"\nre-meshed on 0.5 mm lobes: {quality}")
    assert quality.min_scaled_jacobian > 0.85
    assert quality.min_angle_sine > 0.98


def test_coarser_table_is_interpolated_linearly_and_periodically():
    table_angles = np.linspace(0.1, 2 * math.pi - 0.3, 7)      # not at node angles, uneven wrap
    table_radius = R_B + 1e-4 * np.array([3.0, 0.0, 1.0, 4.0, 1.0, 5.0, 2.0])
    msh, _, facet_tags = worn_mesh((table_angles, table_radius))
    angle, radius = bore_polar(msh, facet_tags)
    expected = periodic_linear(table_angles, table_radius)(bore_node_angles(N_THETA))
    np.testing.assert_allclose(radius, expected, rtol=2e-16)


def test_radial_grading_runs_from_the_worn_bore_to_the_outer_circle():
    """On the ray theta = 0 the radial sizes are those of the circular mesh scaled by
    (R_o - r_b) / (R_o - R_b): the grading ratio is kept."""
    wear = 0.4e-3
    angles = bore_node_angles(N_THETA)
    sizes = []
    for profile in (None, (angles, np.full_like(angles, R_B + wear))):
        msh, _, _ = worn_mesh(profile, grading=3.0)
        x = msh.geometry.x
        on_ray = (np.abs(x[:, 1]) < 1e-12) & (x[:, 0] > 0)
        sizes.append(np.diff(np.sort(x[on_ray, 0])))
    np.testing.assert_allclose(sizes[1], sizes[0] * (R_O - R_B - wear) / (R_O - R_B), rtol=1e-12)


@pytest.mark.parametrize("profile, message", [
    ((np.linspace(0, 6, 5), np.full(5, 0.015)), "worn through"),
    ((np.linspace(0, 6, 5), np.full(4, 0.011)), "equal length"),
    ((np.array([0.0, 1.0, 2 * math.pi]), np.full(3, 0.011)), "distinct modulo 2 pi"),
    ((np.linspace(0, 6, 5), np.array([0.011, np.inf, 0.011, 0.011, 0.011])), "finite"),
])
def test_bad_profiles_are_refused_before_meshing(profile, message):
    with pytest.raises(FewearInputError, match=message):
        worn_mesh(profile)
