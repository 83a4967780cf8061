"""Archard's law (seed eq. 10) against hand-computed cases."""

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.wear.archard import advance_wear_depth_m, cycle_wear_depth_m


def test_uniform_sliding_gives_k_p_s_times_steps():
    k, p, s, steps = 2e-13, 5e6, 1e-4, 200
    depth = cycle_wear_depth_m(k, np.full((steps, 3), p), np.full((steps, 3), s))
    np.testing.assert_allclose(depth, steps * k * p * s, rtol=1e-14)


def test_no_pressure_or_no_slip_means_no_wear():
    pressure = np.array([[0.0, 1e6], [3e6, 0.0]])
    slip = np.array([[1e-3, 0.0], [0.0, 1e-3]])
    np.testing.assert_array_equal(cycle_wear_depth_m(1e-13, pressure, slip), [0.0, 0.0])


def test_extrapolation_over_blocks_is_linear_in_cycles():
    one_cycle = np.array([1e-12, 3e-12])
    depth = np.zeros(2)
    for _ in range(80):
        depth = advance_wear_depth_m(depth, one_cycle, 5000)
    np.testing.assert_allclose(depth, 400_000 * one_cycle, rtol=1e-12)


@pytest.mark.parametrize("factor", [0.5, float("nan")])
def test_bad_extrapolation_factor(factor):
    with pytest.raises(FewearInputError, match="extrapolation factor"):
        advance_wear_depth_m(0.0, 1e-12, factor)


def test_negative_pressure_is_rejected():
    with pytest.raises(FewearInputError, match="pressure"):
        cycle_wear_depth_m(1e-13, [[-1.0]], [[1e-3]])
