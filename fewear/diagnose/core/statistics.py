"""Statistics of nested least-squares fits, shared by the tribometer and the joint diagnosis.

A cause extends a reference model by q parameters; whether the data support it is asked three
ways: the extra-sum-of-squares F-test of the nested fits, the corrected Akaike criterion (AICc)
of each, and (where the held-out units are many) a paired test of their held-out errors; where
each model has several realizations (runs of a chaotic model), Welch's test of their held-out
errors.
"""

from __future__ import annotations

import math

import numpy as np
from scipy import stats


def aicc(rss: float, n_observations: int, n_parameters: int) -> float:
    """Corrected Akaike criterion of a least-squares fit with residual sum of squares ``rss``,
    AICc = n ln(RSS / n) + 2 k + 2 k (k + 1) / (n - k - 1) (Hurvich & Tsai, Biometrika 76
    (1989) 297-307; Burnham & Anderson, *Model Selection and Multimodel Inference*, 2002).

    Where n - k - 1 <= 0 or RSS <= 0 the criterion is undefined: NaN (a NaN difference accepts
    nothing)."""
    n, k = n_observations, n_parameters
    if n - k - 1 <= 0 or rss <= 0.0:
        return float("nan")
    return n * math.log(rss / n) + 2 * k + 2 * k * (k + 1) / (n - k - 1)


def nested_f_test_p(rss_nested: float, rss_fuller: float, extra_parameters: int,
                    residual_dof: int) -> float:
    """p-value of the extra-sum-of-squares F-test of a fuller fit against the nested one:
    F = ((RSS0 - RSS1) / q) / (RSS1 / dof), q the extra parameters, dof = n minus the fuller
    fit's parameters (Seber & Wild, *Nonlinear Regression*, 1989, sec. 5.3). A fuller fit that
    fits worse gives F = 0; 1 where the test is undefined (q <= 0, dof <= 0 or RSS1 <= 0)."""
    q, dof = extra_parameters, residual_dof
    if q <= 0 or dof <= 0 or rss_fuller <= 0.0:
        return 1.0
    statistic = max(rss_nested - rss_fuller, 0.0) / q / (rss_fuller / dof)
    return float(stats.f.sf(statistic, q, dof))


def paired_improvement_p(before: np.ndarray, after: np.ndarray) -> float:
    """One-sided p-value that ``after`` predicts the held-out units better than ``before``: a
    paired t-test (Student) of the per-unit log ratios ln(e_before / e_after) of the mean squared
    held-out errors, a comparison of predictive accuracy in the manner of Diebold & Mariano,
    J. Bus. Econ. Stat. 13 (1995) 253-263, on the log scale where a ratio of two error variances
    is near-symmetric. 1 with fewer than two units."""
    with np.errstate(divide="ignore", invalid="ignore"):  # units without error are left out
        d = np.log(before / after)
    d = d[np.isfinite(d)]
    if d.size < 2:
        return 1.0
    sd = float(np.std(d, ddof=1))
    if sd == 0.0:
        return 0.0 if d.mean() > 0.0 else 1.0
    return float(stats.t.sf(d.mean() / (sd / np.sqrt(d.size)), d.size - 1))


def welch_lower_p(lower: np.ndarray, higher: np.ndarray) -> float:
    """One-sided p-value that the mean of sample ``lower`` is below that of ``higher``: Welch's
    t-test, the samples' variances not taken equal (Welch, Biometrika 34 (1947) 28-35). Two
    samples without spread: 0 if the means are so ordered, else 1."""
    lower, higher = np.asarray(lower, dtype=float), np.asarray(higher, dtype=float)
    if np.ptp(lower) == 0.0 and np.ptp(higher) == 0.0:
        return 0.0 if lower.mean() < higher.mean() else 1.0
    return float(stats.ttest_ind(lower, higher, equal_var=False, alternative="less").pvalue)


def bonferroni_threshold(significance: float, forms_tried: int) -> float:
    """The p-value below which one of ``forms_tried`` tests is significant at a family-wise
    false-positive rate of ``significance`` (Bonferroni): the best form of each cause is picked,
    so every form tried counts."""
    return significance / forms_tried
