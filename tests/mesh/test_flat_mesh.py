"""The flat's mesh (fewear.mesh.flat): top on y_top, graded sizes, tags; its settings' checks."""

import math
import re

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings

GEOMETRY = FlatGeometry(cylinder_radius_m=0.006, width_m=1e-3, height_m=8e-4, length_m=0.01,
                        standoff_m=6e-6)
SETTINGS = FlatMeshSettings(contact_element_size_m=5e-6, contact_zone_half_width_m=6e-5,
                            side_element_count=10, depth_element_count=12)


@pytest.fixture(scope="module")
def flat():
    from mpi4py import MPI

    from fewear.mesh.bore import BoreNodes, bore_node_weights
    from fewear.mesh.flat import flat_mesh

    msh, cell_tags, facet_tags = flat_mesh(GEOMETRY, SETTINGS)
    top = BoreNodes(msh, facet_tags, MPI.COMM_WORLD)
    return msh, cell_tags, facet_tags, top, bore_node_weights(msh, top)


def test_counts_tags_and_second_order_cells(flat):
    from fewear.mesh.tags import CLAMPED_TAG, CONTACT_TAG

    msh, cell_tags, facet_tags, _, _ = flat
    n_contact = SETTINGS.contact_element_count()
    assert n_contact == 24
    along = n_contact + 2 * SETTINGS.side_element_count
    assert msh.topology.index_map(2).size_local == along * SETTINGS.depth_element_count
    assert msh.geometry.dofmap.links(0).size == 9
    assert facet_tags.find(CONTACT_TAG).size == along
    bottom = facet_tags.find(CLAMPED_TAG)
    assert bottom.size == along
    msh.topology.create_connectivity(1, 0)
    y = msh.geometry.x[:, 1]
    assert np.all(y >= GEOMETRY.top_y_m - GEOMETRY.height_m - 1e-18)
    assert np.all(y <= GEOMETRY.top_y_m + 1e-18)
    assert np.all(cell_tags.values == cell_tags.values[0])


def test_top_nodes_on_the_line_sorted_by_x_with_uniform_contact_zone(flat):
    _, _, _, top, weights = flat
    x, y = top.points.T
    assert x.size == 2 * (SETTINGS.contact_element_count() + 2 * SETTINGS.side_element_count) + 1
    np.testing.assert_array_equal(y, GEOMETRY.top_y_m)
    assert np.all(np.diff(x) > 0.0)                    # angle order is x order below the origin
    assert x[0] == pytest.approx(-0.5 * GEOMETRY.width_m, rel=1e-14)
    assert x[-1] == pytest.approx(0.5 * GEOMETRY.width_m, rel=1e-14)
    zone = np.abs(x) <= SETTINGS.contact_zone_half_width_m * (1 + 1e-12)
    np.testing.assert_allclose(np.diff(x[zone]), 0.5 * SETTINGS.contact_element_length_m(),
                               rtol=1e-9)
    assert np.abs(x).min() < 1e-12 * GEOMETRY.width_m   # x = 0 is a vertex (to gmsh's rounding)
    # the side elements grow outward from the contact element length, and are larger
    outside = np.diff(x[x >= SETTINGS.contact_zone_half_width_m * (1 - 1e-12)][::2])
    assert outside[0] == pytest.approx(SETTINGS.contact_element_length_m(), rel=1e-9)
    assert np.all(np.diff(outside) > 0.0)
    # Gauss-Lobatto weights: l/6 + l/6 at the vertices, 2l/3 at the midpoints; they sum to W
    assert weights.sum() == pytest.approx(GEOMETRY.width_m, rel=1e-12)
    zone_weights = weights[zone][1:-1]
    length = SETTINGS.contact_element_length_m()
    np.testing.assert_allclose(zone_weights[::2], 2 * length / 3, rtol=1e-9)
    np.testing.assert_allclose(zone_weights[1::2], length / 3, rtol=1e-9)


def test_depth_grading_starts_at_the_contact_element_length(flat):
    msh = flat[0]
    x, y = msh.geometry.x[:, 0], msh.geometry.x[:, 1]
    column = np.sort(y[np.abs(x) < 1e-15])[::-1]       # vertices and midpoints under x = 0
    steps = -np.diff(column)[::2] - np.diff(column)[1::2]  # element heights, top down
    assert steps[0] == pytest.approx(SETTINGS.contact_element_length_m(), rel=1e-9)
    assert np.all(np.diff(steps) > 0.0)
    assert steps.sum() == pytest.approx(GEOMETRY.height_m, rel=1e-12)


def test_progression_ratio_sums_to_the_length():
    from fewear.mesh.flat import progression_ratio

    ratio = progression_ratio(1.0, 100.0, 12)
    assert sum(ratio**k for k in range(12)) == pytest.approx(100.0, rel=1e-12)
    assert progression_ratio(1.0, 12.0, 12) == 1.0


@pytest.mark.parametrize("field, value, message", [
    ("cylinder_radius_m", 0.0, "cylinder_radius_m = 0.0: must be a finite number > 0"),
    ("width_m", math.inf, "width_m = inf: must be a finite number > 0"),
    ("standoff_m", 0.01, "standoff_m = 0.01: must be smaller than the cylinder_radius_m"),
])
def test_geometry_refuses_bad_values(field, value, message):
    values = dict(cylinder_radius_m=0.006, width_m=1e-3, height_m=8e-4, length_m=0.01,
                  standoff_m=6e-6)
    values[field] = value
    with pytest.raises(FewearInputError, match=message):
        FlatGeometry(**values)


@pytest.mark.parametrize("settings, message", [
    (dict(contact_element_size_m=-1e-6), "contact_element_size_m = -1e-06"),
    (dict(side_element_count=0), "side_element_count = 0: must be a whole number in"),
    (dict(depth_element_count=2.5), "depth_element_count = 2.5: must be a whole number in"),
])
def test_mesh_settings_refuse_bad_values(settings, message):
    values = dict(contact_element_size_m=5e-6, contact_zone_half_width_m=6e-5)
    with pytest.raises(FewearInputError, match=message):
        FlatMeshSettings(**{**values, **settings})


def test_the_mesh_size_is_bounded_before_meshing_with_the_estimate_in_the_message():
    """(2 x_c / h + 2 side) depth quadrilaterals: (2 x 1.6e-3 / 1e-8 + 24) x 20 = 6,400,480,
    refused with their memory; the size the message suggests is taken, a smaller one not."""
    from fewear.io.limits import MAX_FLAT_MESH_CELLS

    with pytest.raises(FewearInputError) as error:
        FlatMeshSettings(1e-8, 1.6e-3, side_element_count=12, depth_element_count=20)
    message = str(error.value)
    assert "about 6,400,480 quadrilaterals (about 160.4 GB of memory" in message
    assert f"expected at most {MAX_FLAT_MESH_CELLS:,} quadrilaterals" in message
    suggested = float(re.search(r"contact_element_size_m >= (\S+) m", message).group(1))
    FlatMeshSettings(suggested, 1.6e-3, side_element_count=12, depth_element_count=20)
    with pytest.raises(FewearInputError):
        FlatMeshSettings(suggested * 0.99, 1.6e-3, side_element_count=12, depth_element_count=20)


@pytest.mark.parametrize("settings, message", [
    (FlatMeshSettings(5e-6, 3e-4), "below a quarter of the flat width_m"),
    (FlatMeshSettings(5e-6, 6e-5, side_element_count=100), "do not fit in the"),
    (FlatMeshSettings(5e-6, 6e-5, depth_element_count=200), "do not fit in the height_m"),
])
def test_mesh_must_fit_the_flat(settings, message):
    with pytest.raises(FewearInputError, match=message):
        settings.require_fits(GEOMETRY)


def test_worn_map_puts_the_top_on_the_worn_flat_and_keeps_the_bottom():
    from fewear.mesh.flat import worn_node_y_m

    top, bottom = GEOMETRY.top_y_m, GEOMETRY.top_y_m - GEOMETRY.height_m
    made = np.array([[-1e-4, top], [2e-4, top], [2e-4, bottom], [2e-4, 0.5 * (top + bottom)],
                     [-1e-4, top - 0.25 * GEOMETRY.height_m]])

    def depth_at(x):
        return 1e-5 + 1e-2 * x  # 9 um at x = -0.1 mm, 12 um at 0.2 mm

    y = worn_node_y_m(made, GEOMETRY, depth_at)
    np.testing.assert_allclose(y[:2], top - np.array([9e-6, 12e-6]), rtol=0, atol=1e-18)
    assert y[2] == bottom
    # interior: the column shrinks in proportion, y' - y_b = (y - y_b) (H - h) / H
    assert y[3] - bottom == pytest.approx(0.5 * (GEOMETRY.height_m - 12e-6), rel=1e-12)
    assert y[4] - bottom == pytest.approx(0.75 * (GEOMETRY.height_m - 9e-6), rel=1e-12)
