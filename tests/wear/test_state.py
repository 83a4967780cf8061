"""The wear state: the one source of the worn bore, the dynamics' clearance and extrapolation."""

import math

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.mbd.contact import pin_reach_m
from fewear.wear.extrapolation import MAX_TRIALS, ExtrapolationSettings, extrapolate_block
from fewear.wear.state import WearState

R_B, R_P, N = 0.010, 0.0095, 288
ANGLES = 2 * math.pi * np.arange(N) / N


def worn(depth):
    return WearState(ANGLES, depth, WearState.unworn(ANGLES).sliding)


def test_unworn_clearance_is_c0_to_the_chord_sag():
    """Bore nodes on the circle: c = R_b - R_p at the node directions, the pin touching a node
    exactly (the sag between nodes is R_b R_p dtheta^2 / (8 c0) ~ 0.03 um, not sampled here)."""
    c = pin_reach_m(ANGLES, ANGLES, np.full(N, R_B), R_P)
    np.testing.assert_allclose(c, R_B - R_P, rtol=1e-12)


def test_clearance_fed_back_is_c0_plus_h_where_the_bore_conforms():
    """A wide worn lobe (30 deg, the pin's contact arc is narrower): c(theta) = c0 + h(theta)
    to well within a micron at the lobe's bottom, and never more than c0 + h anywhere."""
    depth = 1e-4 * np.exp(-0.5 * ((ANGLES - math.pi) / math.radians(30)) ** 2)
    c = pin_reach_m(ANGLES, ANGLES, R_B + depth, R_P)
    bottom = np.argmax(depth)
    assert c[bottom] == pytest.approx(R_B - R_P + depth[bottom], abs=2e-7)
    assert np.all(c <= R_B - R_P + depth + 1e-12)


def test_a_single_node_dent_is_bridged_by_the_pin():
    depth = np.zeros(N)
    depth[100] = 5e-5
    c = pin_reach_m(ANGLES, ANGLES, R_B + depth, R_P)
    assert c[100] - (R_B - R_P) < 1e-6  # the pin cannot sink into a 0.2 mm wide dent


def test_dynamics_clearance_follows_the_cusp_of_a_pocket_narrower_than_the_pin():
    """A 1 mm deep pocket (Gaussian, sd 30 deg) narrower than the pin, its bottom between two of
    288 nodes: where the pin rests on both flanks c(theta) has a cusp. The profile handed to the
    dynamics against a brute-force reach over 48,001 points of the same bore (h through the
    nodes by the periodic cubic spline) in 801 directions around the cusp: within 1 um (0.5 um
    measured; a spline through c at the nodes only was 10.8 um off, and the rigid rod's orbit
    on the rounded bottom chattered where on a finer mesh it did not)."""
    centre = math.pi + math.pi / N
    state = worn(1e-3 * np.exp(-0.5 * ((ANGLES - centre) / math.radians(30)) ** 2))
    profile = state.clearance_profile(R_B, R_P)
    directions = centre + np.radians(np.linspace(-4.0, 4.0, 801))
    points = centre + np.radians(np.linspace(-60.0, 60.0, 48001))
    radius = R_B + state.smooth_depth_at(points)
    along = radius * np.cos(points[None, :] - directions[:, None])
    discriminant = along**2 - radius**2 + R_P**2
    reach = along - np.sqrt(np.maximum(discriminant, 0.0))
    exact = np.where((discriminant >= 0.0) & (reach >= 0.0), reach, np.inf).min(axis=1)
    assert exact.max() - exact[[0, -1]].max() > 5e-5  # a cusp, not a conforming bottom
    sampled = np.array([profile(theta)[0] for theta in directions])
    np.testing.assert_allclose(sampled, exact, rtol=0.0, atol=1e-6)


def test_dynamics_clearance_is_smooth_across_the_nodes_of_a_conforming_lobe():
    """A wide lobe (0.1 mm, sd 30 deg, 288 nodes): the curvature c'' of the dynamics' clearance
    (which turns the contact normal) stays within 3 times the lobe's largest |h''| (2.5 times
    measured: the contact point moves along the lobe); h linear between the nodes kinks the
    bore at every node and gives 17 times (the contact normal would turn abruptly there)."""
    width = math.radians(30)
    state = worn(1e-4 * np.exp(-0.5 * ((ANGLES - math.pi) / width) ** 2))
    profile = state.clearance_profile(R_B, R_P)
    theta = math.pi + np.radians(np.arange(-40.0, 40.0, 1.25 / 16))
    largest_h2 = 1e-4 / width**2  # max |h''| of the Gaussian, at its bottom
    assert np.abs([profile(t)[2] for t in theta]).max() < 3.0 * largest_h2


def test_worn_area_of_a_uniform_depth_is_the_annulus():
    state = worn(np.full(N, 1e-4))
    assert state.worn_area_m2(R_B) == pytest.approx(math.pi * ((R_B + 1e-4) ** 2 - R_B**2))


def test_wall_break_through_is_an_input_error():
    with pytest.raises(FewearInputError, match="worn through"):
        worn(np.full(N, 3e-3)).checked_against_wall(R_B, 0.015, 0.5)


@pytest.mark.parametrize("bad", [np.full(N, -1e-6), np.full(N, np.nan)])
def test_bad_depths_are_rejected(bad):
    with pytest.raises(ValueError):
        worn(bad)


def test_adaptive_block_bounds_the_largest_increment():
    settings = ExtrapolationSettings(mode="adaptive", max_factor=50000,
                                     max_depth_increment_fraction=0.2)
    rate = np.array([1e-9, 4e-9])  # depth per cycle (m)
    cycles, increment = extrapolate_block(settings, lambda a: (a * rate,), 1e-4, 400000)
    assert increment.max() <= 0.2 * 1e-4
    assert increment.max() > 0.9 * 0.2 * 1e-4  # not needlessly short
    fixed = ExtrapolationSettings(mode="fixed", factor=5000)
    assert extrapolate_block(fixed, lambda a: (a * rate,), 1e-4, 3000)[0] == 3000


def test_adaptive_block_finds_the_bound_of_an_increment_that_grows_faster_than_the_block():
    """An increment r A exp(A / 2000) (a linearisation used far beyond its validity grows
    faster than A_j) is astronomically large at A_max = 50,000: one proportional shrink from
    there gives A_j = 1. The search brackets the bound instead and returns a block within it
    that fills at least 80 % of it."""
    settings = ExtrapolationSettings(mode="adaptive", max_factor=50000.0,
                                     max_depth_increment_fraction=0.1)
    limit = 0.1 * 1e-4
    rate = limit / (1000.0 * math.exp(0.5))  # the increment reaches the bound at A = 1000

    def increment_for(cycles):
        return (np.array([rate * cycles * math.exp(cycles / 2000.0)]),)

    cycles, increment = extrapolate_block(settings, increment_for, 1e-4, 400000)
    assert 0.8 * limit <= increment[0] <= limit
    assert 850 <= cycles <= 1000


def counted(increment_for):
    """``increment_for`` that counts its calls in ``.calls``."""
    def wrapped(cycles):
        wrapped.calls += 1
        return increment_for(cycles)
    wrapped.calls = 0
    return wrapped


@pytest.mark.parametrize("peak_at", [
    lambda a: (a / 49.0) ** 1.9,  # superlinear: proportional guesses zig-zag
    lambda a: a / 1000.0 if a <= 5000 else math.nan,  # the step overflows beyond 5,000 cycles
    lambda a: a / 1000.0 if a <= 5000 else math.inf,
])
def test_adaptive_search_fills_the_bound_of_awkward_increments(peak_at):
    """Peaks in units of f h_e: a power law steeper than linear, and an increment that is not
    finite beyond some block: within MAX_TRIALS calls the search returns a finite block within
    the bound that fills at least 80 % of it."""
    settings = ExtrapolationSettings(mode="adaptive", max_factor=50000.0,
                                     max_depth_increment_fraction=0.1)
    limit = 0.1 * 1e-4
    increment_for = counted(lambda cycles: (np.array([limit * peak_at(cycles)]),))
    cycles, increment = extrapolate_block(settings, increment_for, 1e-4, 400000)
    assert 0.8 * limit <= increment[0] <= limit
    assert increment_for.calls <= MAX_TRIALS


@pytest.mark.parametrize("previous_rate_factor, most_calls", [
    (1.0, 1),  # the same rate as the previous step: its block, scaled, fills the bound at once
    (1.08, 1),  # the rate fell by 8 %: the first trial still fills 80-100 % of the bound
    (3.0, 3),  # the rate fell to a third: up from the first trial
    (0.2, 3),  # the rate grew fivefold: down from it
])
def test_adaptive_search_from_the_previous_steps_block(previous_rate_factor, most_calls):
    """Given the previous wear step's (A_j, peak), the search starts where that step's rate
    reaches 0.95 f h_e: with the rate unchanged (or changed by less than the band [0.8, 1]
    allows) one trial fills the bound; a rate that changed by several times is found within a
    few trials, up or down, and the block returned fills at least 80 % of the bound, as from
    the cap."""
    settings = ExtrapolationSettings(mode="adaptive", max_factor=50000.0,
                                     max_depth_increment_fraction=0.1)
    limit = 0.1 * 1e-4
    rate = limit / 3000.0  # this step's peak per cycle: the bound at A = 3,000
    increment_for = counted(lambda cycles: (np.array([rate * cycles]),))
    previous_cycles = 2000
    previous = (previous_cycles, previous_rate_factor * rate * previous_cycles)
    cycles, increment = extrapolate_block(settings, increment_for, 1e-4, 400000, previous)
    assert 0.8 * limit <= increment[0] <= limit
    assert increment_for.calls <= most_calls
    near_cap = extrapolate_block(settings, counted(lambda cycles: (np.array([rate * cycles]),)),
                                 1e-4, 2500, (2000, 1e-30))  # a rate 1e-25 of the step's
    assert near_cap[0] == 2500  # capped by the cycles remaining


def test_adaptive_search_returns_the_largest_block_within_the_bound():
    """A peak that jumps from half the bound to twice it beyond 1,000 cycles: every later trial
    overshoots, and the block returned is the largest found within the bound, not the last
    tried."""
    settings = ExtrapolationSettings(mode="adaptive", max_factor=50000.0,
                                     max_depth_increment_fraction=0.1)
    limit = 0.1 * 1e-4
    increment_for = counted(lambda cycles: (
        np.array([limit * (cycles / 2000.0 if cycles <= 1000 else 2.0)]), cycles))
    cycles, increment, evaluated_at = extrapolate_block(settings, increment_for, 1e-4, 400000)
    assert increment[0] <= limit and cycles == evaluated_at <= 1000
    assert cycles >= 500
    assert increment_for.calls <= MAX_TRIALS


def test_a_block_whose_increment_never_gets_small_enough_keeps_its_own_increment():
    """An increment that levels off with A_j (2 f h_e (1 - exp(-A / 5))) stays above f h_e until
    A_j < 3.5, beyond the 12 trials from A_max = 50,000: the block returned is the last one
    tried, with that block's own increment."""
    settings = ExtrapolationSettings(mode="adaptive", max_factor=50000.0,
                                     max_depth_increment_fraction=0.1)
    limit = 0.1 * 1e-4

    def increment_for(cycles):
        return (np.array([2.0 * limit * -math.expm1(-cycles / 5.0)]), cycles)

    cycles, increment, evaluated_at = extrapolate_block(settings, increment_for, 1e-4, 400000)
    assert increment[0] > limit  # the 12 trials ran out
    assert cycles == evaluated_at
