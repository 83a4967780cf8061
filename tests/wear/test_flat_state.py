"""The flat's wear state (fewear.wear.state.FlatWearState) and the scar's measures and ring-arc
closed form (fewear.wear.scar), against hand computations."""

import math

import numpy as np
import pytest

from fewear.wear.scar import (
    ring_arc_area_m2,
    ring_arc_depth_m,
    ring_arc_width_m,
    scar_depth_and_width_m,
)
from fewear.wear.state import FlatWearState

RING_RADIUS_M = 0.020


def test_depth_is_linear_between_the_nodes_and_exact_at_them():
    state = FlatWearState(np.array([-2.0, 0.0, 1.0]), np.array([0.0, 4.0, 1.0]))
    np.testing.assert_array_equal(state.depth_at(state.x_m), state.depth_m)
    np.testing.assert_allclose(state.depth_at([-1.0, 0.5, 5.0, -7.0]), [2.0, 2.5, 1.0, 0.0])
    np.testing.assert_allclose(state.top_y_m(-3.0, [0.0, 0.5]), [-7.0, -5.5])
    # trapezoid: 2 * 4 / 2 + 1 * (4 + 1) / 2
    assert state.worn_area_m2() == pytest.approx(6.5, rel=1e-15)


def test_a_wear_step_adds_depth_distance_and_a_step():
    unworn = FlatWearState.unworn(np.array([0.0, 1.0, 2.0]))
    worn = unworn.worn_by(np.array([0.0, 2.0, 1.0]), 80.0).worn_by(np.ones(3), 40.0)
    np.testing.assert_array_equal(worn.depth_m, [1.0, 3.0, 2.0])
    assert (worn.sliding_distance_m, worn.steps) == (120.0, 2)
    np.testing.assert_array_equal(unworn.depth_m, 0.0)


@pytest.mark.parametrize("x, depth, message", [
    ([0.0, 0.0, 1.0], [0.0, 0.0, 0.0], "increase strictly"),
    ([0.0, 1.0], [0.0, -1e-9], "finite and >= 0"),
    ([0.0, 1.0], [0.0], "equal-length"),
])
def test_bad_states_are_refused(x, depth, message):
    with pytest.raises(ValueError, match=message):
        FlatWearState(np.array(x), np.array(depth))


def test_ring_arc_area_is_the_circular_segment():
    """A(d) against the segment's area integrated numerically, and the small-depth form
    (4/3) sqrt(2 R d) d."""
    depth = 44e-6
    half_chord = math.sqrt(2 * RING_RADIUS_M * depth - depth**2)
    x = np.linspace(-half_chord, half_chord, 200001)
    sunk = depth - RING_RADIUS_M + np.sqrt(RING_RADIUS_M**2 - x**2)
    numeric = float(np.sum(0.5 * (sunk[1:] + sunk[:-1]) * np.diff(x)))
    assert ring_arc_area_m2(RING_RADIUS_M, depth) == pytest.approx(numeric, rel=1e-8)
    small = 4 / 3 * math.sqrt(2 * RING_RADIUS_M * depth) * depth
    assert ring_arc_area_m2(RING_RADIUS_M, depth) == pytest.approx(small, rel=1e-3)
    assert ring_arc_width_m(RING_RADIUS_M, depth) == pytest.approx(2 * half_chord, rel=1e-15)


def test_block_on_ring_closed_form_gives_the_research_notes_figures():
    """k P' S = 2e-15 m^2/N * 65 N / 6 mm * 3600 m = 0.0780 mm^2: d = 44.07 um, 2.654 mm wide
    (issue 22 research note, section 3.4)."""
    area = 2e-15 * 65.0 / 0.006 * 3600.0
    depth = ring_arc_depth_m(RING_RADIUS_M, area)
    assert area == pytest.approx(0.0780e-6, rel=1e-3)
    assert depth == pytest.approx(44.07e-6, rel=2e-4)
    assert ring_arc_width_m(RING_RADIUS_M, depth) == pytest.approx(2.654e-3, rel=2e-4)
    assert ring_arc_area_m2(RING_RADIUS_M, depth) == pytest.approx(area, rel=1e-12)
    assert ring_arc_depth_m(RING_RADIUS_M, 0.0) == 0.0


def test_scar_width_crosses_the_edge_share_between_nodes():
    depth = 44e-6
    x = np.linspace(-2e-3, 2e-3, 801)
    sunk = np.maximum(depth - RING_RADIUS_M + np.sqrt(RING_RADIUS_M**2 - x**2), 0.0)
    deepest, width = scar_depth_and_width_m(x, sunk)
    assert deepest == pytest.approx(depth, rel=1e-12)
    # the crossings interpolated linearly on a 5 um grid: the arc's curvature, 1e-4 relative
    assert width == pytest.approx(ring_arc_width_m(RING_RADIUS_M, depth, 0.05), rel=1e-4)
    assert width < ring_arc_width_m(RING_RADIUS_M, depth)
    assert scar_depth_and_width_m(x, np.zeros_like(x)) == (0.0, 0.0)
    # worn to the ends of the profile: the width is the profile's
    assert scar_depth_and_width_m([0.0, 1.0, 2.0], [1.0, 2.0, 1.0]) == (2.0, 2.0)
