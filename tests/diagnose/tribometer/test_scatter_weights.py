"""The tribometer diagnosis's model of a reading's scatter (fewear.diagnose.tribometer.fitting.
scatter_weights): var(ln V) = a + b (V_m / V)^2 + c (V_T / V)^2, fitted by maximum likelihood,
recovers the variances it was drawn with, gives equal weights to purely proportional scatter, and
makes the tests' levels more precise where readings carry an error of the test's own size."""

import numpy as np
import pytest

from fewear.diagnose.tribometer.fitting import scatter_weights


def _tests(n_tests: int = 40, per_test: int = 8, seed: int = 3):
    """Readings along tests whose wear grows linearly in the reading's index and whose sizes
    spread over a decade from test to test: test index per reading, ln V per reading."""
    rng = np.random.default_rng(seed)
    test = np.repeat(np.arange(n_tests), per_test)
    final = np.exp(rng.uniform(0.0, np.log(10.0), n_tests))[test]
    fraction = np.tile(np.arange(1, per_test + 1) / per_test, n_tests)
    return test, np.log(final * fraction)


def _variance(log_volume, test, a, b, c):
    largest = np.array([log_volume[test == j].max() for j in range(test.max() + 1)])[test]
    return (a + b * np.exp(2.0 * (np.median(log_volume) - log_volume))
            + c * np.exp(2.0 * (largest - log_volume)))


@pytest.mark.parametrize("a, b, c", [(0.03**2, 0.0, 0.02**2), (0.02**2, 0.01**2, 0.0),
                                     (0.05**2, 0.0, 0.0)])
def test_the_weights_are_the_inverse_variances_the_residuals_were_drawn_with(a, b, c):
    test, log_volume = _tests(n_tests=250)
    variance = _variance(log_volume, test, a, b, c)
    residuals = np.random.default_rng(7).standard_normal(test.size) * np.sqrt(variance)
    weight = scatter_weights(residuals, log_volume, test)
    expected = (1.0 / variance) / np.mean(1.0 / variance)
    assert weight.mean() == pytest.approx(1.0)
    relative_error = weight / expected - 1.0
    assert np.sqrt(np.mean(relative_error**2)) < 0.1


def test_proportional_scatter_alone_gives_equal_weights():
    test, log_volume = _tests(n_tests=250)
    residuals = 0.05 * np.random.default_rng(11).standard_normal(test.size)
    weight = scatter_weights(residuals, log_volume, test)
    assert weight.max() / weight.min() < 1.1


def test_weighted_levels_are_nearer_the_truth_under_an_error_of_the_tests_size():
    """A zero offset of each test and an error per reading, both of the test's final wear's
    size (debris, a transfer layer): the early readings scatter most in ln V. The weighted mean
    of each test's residuals lies nearer its true level (0) than the plain mean, over 60
    tests."""
    test, log_volume = _tests(n_tests=60)
    rng = np.random.default_rng(5)
    volume = np.exp(log_volume)
    largest = np.array([volume[test == j].max() for j in range(60)])
    error = 0.03 * volume * rng.standard_normal(test.size) + 0.05 * largest[test] * (
        rng.standard_normal(test.size) + 0.7 * rng.standard_normal(60)[test])
    residuals = np.log(np.maximum(volume + error, 1e-3 * volume)) - log_volume
    weight = scatter_weights(residuals, log_volume, test)
    plain = np.bincount(test, residuals) / np.bincount(test)
    weighted = np.bincount(test, weight * residuals) / np.bincount(test, weight)
    assert np.sqrt(np.mean(weighted**2)) < 0.8 * np.sqrt(np.mean(plain**2))
