"""Archard's law (seed eq. 10) per node and its extrapolation over a block, against exact cases."""

import math

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.wear.archard import (
    CycleSliding,
    block_wear,
    cycle_wear_depth_m,
    exponential_euler_increment,
    smoothed_periodic,
)
from fewear.wear.extensions import NoExtension, RunningIn, RunningInCycles, SlidingState


def test_uniform_sliding_gives_k_p_s_times_steps():
    k, p, s, steps = 2e-13, 5e6, 1e-4, 200
    depth = cycle_wear_depth_m(k, np.full((steps, 3), p), np.full((steps, 3), s))
    np.testing.assert_allclose(depth, steps * k * p * s, rtol=1e-14)


def test_no_pressure_or_no_slip_means_no_wear():
    pressure = np.array([[0.0, 1e6], [3e6, 0.0]])
    slip = np.array([[1e-3, 0.0], [0.0, 1e-3]])
    np.testing.assert_array_equal(cycle_wear_depth_m(1e-13, pressure, slip), [0.0, 0.0])


def test_negative_pressure_is_rejected():
    with pytest.raises(FewearInputError, match="pressure"):
        cycle_wear_depth_m(1e-13, [[-1.0]], [[1e-3]])


def cycle(depth, distance=1e-3, sensitivity=None):
    depth = np.asarray(depth, dtype=float)
    ones = np.ones_like(depth)
    return CycleSliding(depth, distance * ones, 0.01 * ones, 0.0 * ones, sensitivity)


def unworn(n):
    zeros = np.zeros(n)
    return SlidingState(zeros, zeros, zeros)


def test_plain_archard_block_is_seed_eq_10_and_blocks_add_up():
    """m = 1: each block adds A_j h_cycle exactly; 80 blocks of 5000 = 400,000 cycles."""
    one_cycle = np.array([1e-12, 3e-12])
    depth, sliding = np.zeros(2), unworn(2)
    for _ in range(80):
        increment, sliding = block_wear(cycle(one_cycle), sliding, NoExtension(), 5000)
        depth = depth + increment
    np.testing.assert_allclose(depth, 400_000 * one_cycle, rtol=1e-12)
    np.testing.assert_allclose(sliding.distance_m, 400_000 * 1e-3, rtol=1e-12)


def test_running_in_block_matches_the_closed_form_effective_distance():
    """Constant p and s: the depth is k p times the effective distance S_eff(s1) - S_eff(s0) of
    the running-in law (closed form in fewear.wear.extensions); the midpoint rule over 32
    sub-blocks is within (A ds / s0)^2 / (24 * 32^2) of it."""
    law = RunningIn(k_initial_over_steady=5.0, distance_scale_m=4.0)
    per_cycle, ds = 2e-12, 1e-3  # depth of plain Archard per cycle (m), slid distance per cycle
    increment, after = block_wear(cycle([per_cycle], ds), unworn(1), law, 5000)
    exact = per_cycle / ds * (law.effective_distance_m(5.0) - law.effective_distance_m(0.0))
    assert increment[0] == pytest.approx(exact, rel=(5000 * ds / 4.0) ** 2 / (24 * 32**2) * 5)
    assert after.distance_m[0] == pytest.approx(5.0)


def test_running_in_by_cycles_over_blocks_is_the_effective_cycles():
    """Blocks of 300, 700 and 4000 cycles, each point sliding differently: every point wears
    h_cycle times N_eff(5000) = N + (r - 1) N0 (1 - exp(-N / N0)) (the block's own crank cycles
    carry the state from block to block), within the midpoint rule's error."""
    law = RunningInCycles(k_initial_over_steady=3.0, scale_cycles=600.0)
    one_cycle = np.array([1e-12, 4e-12])
    depth, sliding = np.zeros(2), unworn(2)
    for cycles in (300, 700, 4000):
        step = CycleSliding(one_cycle, np.array([1e-4, 5e-2]), np.full(2, 0.01), np.zeros(2))
        increment, sliding = block_wear(step, sliding, law, cycles)
        depth = depth + increment
    exact = 5000.0 + 2.0 * 600.0 * -math.expm1(-5000.0 / 600.0)
    np.testing.assert_allclose(depth, one_cycle * exact, rtol=(4000 / 32 / 600) ** 2 / 24)
    assert sliding.cycles == 5000.0


def test_linearised_step_is_exact_for_a_linear_rate_and_damps_a_ripple():
    """With dh/dN = h_c - lambda h (a node that sheds its load as it recedes) the step gives the
    exact h_c (1 - exp(-lambda A)) / lambda, which approaches the equilibrium h_c / lambda from
    below however long the block; explicit extrapolation overshoots it (A h_c)."""
    h_c, decay = 1e-9, 0.01
    for cycles in (30, 5000):
        step, _ = block_wear(cycle([h_c], sensitivity=np.array([[-decay]])), unworn(1),
                             NoExtension(), cycles)
        exact = h_c * -math.expm1(-decay * cycles) / decay
        assert step[0] == pytest.approx(exact, rel=1e-12)
        assert step[0] <= h_c / decay
    assert cycles * h_c > h_c / decay


class NodeMultiplier:
    """A wear-law extension whose multiplier m is fixed per node (a stand-in for a running-in
    state that does not change over the block)."""

    def __init__(self, multiplier):
        self.values = np.asarray(multiplier, dtype=float)

    def advance(self, state, *_):
        return state

    def multiplier(self, _):
        return self.values


@pytest.mark.parametrize("varying_multiplier", [False, True])
def test_smoothing_and_multiplier_enter_the_linearised_step(varying_multiplier):
    """The bore changes by the smoothed increment, so the step integrates dh/dN = G m (w + S h)
    (S couples a few nodes in contact, G the Gaussian, m the wear law's multiplier per node;
    they do not commute): against an independent integration (scipy's solve_ivp, Radau, tight
    tolerances) the step is exact for a linear rate, while solving with S and smoothing
    afterwards (the former step) is not."""
    from scipy.integrate import solve_ivp

    n, width, cycles = 72, math.radians(5.0), 400
    angle = 2 * math.pi * np.arange(n) / n
    rate = 1e-9 * np.exp(-0.5 * ((angle - math.pi) / 0.15) ** 2)
    contact = np.flatnonzero(np.abs(angle - math.pi) < 0.3)
    sensitivity = np.zeros((n, n))
    # a receding node sheds its load to its neighbours (rows sum to zero: the load is kept)
    for a in contact:
        sensitivity[a, a] = -0.5
        for b in (a - 1, a + 1):
            sensitivity[a, b] = 0.25
    multiplier = 1.0 + (0.8 * np.sin(3.0 * angle) if varying_multiplier else 0.0 * angle)
    step, _ = block_wear(cycle(rate, sensitivity=sensitivity), unworn(n),
                         NodeMultiplier(multiplier), cycles, smoothing_width_rad=width)
    smooth = np.column_stack([smoothed_periodic(e, 2 * math.pi / n, width) for e in np.eye(n)])
    exact = solve_ivp(lambda _, h: smooth @ (multiplier * (rate + sensitivity @ h)),
                      (0.0, cycles), np.zeros(n), method="Radau", rtol=1e-10,
                      atol=1e-16).y[:, -1]
    np.testing.assert_allclose(step, exact, rtol=1e-6, atol=1e-6 * exact.max())
    former = smoothed_periodic(np.linalg.solve(np.eye(n) - cycles * sensitivity, cycles * rate),
                               2 * math.pi / n, width)
    assert np.abs(former - exact).max() > 0.05 * exact.max()


def test_smoothing_keeps_the_volume_and_removes_node_scale_ripple():
    n = 288
    angle = 2 * math.pi * np.arange(n) / n
    lobe = 5e-5 * np.exp(-0.5 * ((angle - math.pi) / 0.3) ** 2)
    ripple = 5e-6 * (-1.0) ** np.arange(n)
    smoothed = smoothed_periodic(lobe + ripple, 2 * math.pi / n, math.radians(5.0))
    assert smoothed.sum() == pytest.approx((lobe + ripple).sum(), rel=1e-12)
    # the lobe (sigma 17 deg) widens to sqrt(17^2 + 5^2) deg; the ripple is gone
    widened = 5e-5 * 0.3 / math.hypot(0.3, math.radians(5.0)) * np.exp(
        -0.5 * ((angle - math.pi) / math.hypot(0.3, math.radians(5.0))) ** 2)
    np.testing.assert_allclose(smoothed, widened, atol=1e-3 * 5e-5)
    np.testing.assert_array_equal(smoothed_periodic(lobe, 0.1, 0.0), lobe)


def test_bad_block_size():
    with pytest.raises(FewearInputError, match="extrapolation factor"):
        block_wear(cycle([1e-12]), unworn(1), NoExtension(), 0)


def test_exponential_step_on_the_nodes_in_contact_equals_the_full_exponential():
    """Nodes outside the contact (zero columns of A J) follow the others: the increment from
    the small bordered matrix equals phi_1(A J) c read from the exponential of the full one."""
    from scipy.linalg import expm

    rng = np.random.default_rng(1)
    n = 40
    step_jacobian = rng.normal(size=(n, n)) * 0.5
    step_jacobian[:, rng.choice(n, 25, replace=False)] = 0.0
    explicit = rng.normal(size=n)
    bordered = np.zeros((n + 1, n + 1))
    bordered[:n, :n], bordered[:n, n] = step_jacobian, explicit
    coupled = np.flatnonzero(np.any(step_jacobian != 0.0, axis=0))
    np.testing.assert_allclose(
        exponential_euler_increment(step_jacobian[:, coupled], coupled, explicit),
        expm(bordered)[:n, n], rtol=1e-12, atol=1e-12)
