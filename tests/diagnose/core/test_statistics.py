"""The shared statistics of the diagnoses (fewear.diagnose.core.statistics) against their
textbook formulas, computed here another way."""

from __future__ import annotations

import math

import numpy as np
import pytest
from scipy import stats

from fewear.diagnose.core.statistics import aicc, nested_f_test_p, welch_lower_p
from fewear.diagnose.joint.fitting import training_aicc


@pytest.mark.parametrize("lower, higher", [((0.97, 3.26, 1.25), (3.18, 1.35, 3.30)),
                                           ((1.0, 1.1, 0.9, 1.05), (2.0, 2.6, 1.7)),
                                           ((5.0, 6.0, 7.0), (1.0, 2.0, 3.0))])
def test_welch_p_is_the_t_distribution_at_the_welch_satterthwaite_dof(lower, higher):
    """t = (m1 - m2) / sqrt(s1^2 / n1 + s2^2 / n2), nu = (s1^2/n1 + s2^2/n2)^2 /
    ((s1^2/n1)^2 / (n1 - 1) + (s2^2/n2)^2 / (n2 - 1)) (Welch 1947), p = P(T_nu <= t)."""
    a, b = np.array(lower), np.array(higher)
    va, vb = a.var(ddof=1) / a.size, b.var(ddof=1) / b.size
    t = (a.mean() - b.mean()) / math.sqrt(va + vb)
    dof = (va + vb) ** 2 / (va**2 / (a.size - 1) + vb**2 / (b.size - 1))
    assert welch_lower_p(a, b) == pytest.approx(stats.t.cdf(t, dof), rel=1e-10)


def test_welch_p_of_samples_without_spread_is_their_order():
    assert welch_lower_p([1.0, 1.0], [2.0, 2.0]) == 0.0
    assert welch_lower_p([2.0, 2.0], [2.0, 2.0]) == 1.0
    assert welch_lower_p([3.0, 3.0], [2.0, 2.0]) == 1.0


def test_nested_f_test_of_one_extra_slope_is_the_t_test_of_that_slope():
    """A straight line against a constant on noisy data: with one extra parameter F = t^2 of
    the slope's least-squares estimate (its standard error from the residual variance)."""
    rng = np.random.default_rng(3)
    x = np.linspace(0.0, 1.0, 25)
    y = 0.3 * x + rng.normal(0.0, 0.2, x.size)
    rss_constant = float(np.sum((y - y.mean()) ** 2))
    design = np.column_stack([np.ones_like(x), x])
    coefficients, rss_line, *_ = np.linalg.lstsq(design, y, rcond=None)
    dof = x.size - 2
    slope_se = math.sqrt(rss_line[0] / dof / np.sum((x - x.mean()) ** 2))
    t = coefficients[1] / slope_se
    assert nested_f_test_p(rss_constant, float(rss_line[0]), 1, dof) == pytest.approx(
        2.0 * stats.t.sf(abs(t), dof), rel=1e-9)


def test_aicc_is_the_corrected_criterion_and_undefined_without_residual_freedom():
    # Hurvich & Tsai: n ln(RSS/n) + 2k + 2k(k+1)/(n-k-1), here n = 10, k = 3, RSS = 2
    assert aicc(2.0, 10, 3) == pytest.approx(10 * math.log(0.2) + 6 + 24 / 6)
    assert math.isnan(aicc(2.0, 4, 3)) and math.isnan(aicc(0.0, 10, 3))


def test_the_joint_training_aicc_clamps_the_correction_where_the_shared_one_is_undefined():
    assert training_aicc(2.0, 10, 3) == aicc(2.0, 10, 3)
    assert training_aicc(2.0, 4, 3) == pytest.approx(4 * math.log(0.5) + 6 + 24)
