"""The structure of the baseline's residuals, in numbers and in plain words.

Three views, each tested with Spearman's rank correlation (a monotone trend, robust to outliers;
scipy.stats.spearmanr gives the two-sided p-value) and shown as binned means (quartiles of the
variable, mean residual and its standard error):

- *within tests*: the residual of each reading (its test's level removed) against sliding distance
  and time. A falling trend means the apparent wear coefficient V / (F s) falls along a test
  (running-in or a time transient); a rising one that it rises (heating);
- *the trend's size between tests*: each test's slope of residual against ln s, against the
  test's frictional power mu p v and speed v (a slope growing with mu p v points at heating);
- *across tests*: each test's ln k minus the network's ln k(p, v) against pressure, speed,
  frictional power, temperature and test order (a trend with test order is a drift of the
  campaign: disc wear, humidity, a changing counterface, none of which the catalogue models).
"""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import stats

SIGNIFICANT_P = 0.01
"""p-value below which a trend is called out in the summary (several variables are tested)."""


def _bins(x: np.ndarray, y: np.ndarray, n_bins: int = 4) -> list[dict[str, float]]:
    edges = np.unique(np.quantile(x, np.linspace(0.0, 1.0, n_bins + 1)))
    out = []
    for i in range(len(edges) - 1):
        last = i == len(edges) - 2
        inside = (x >= edges[i]) & ((x <= edges[i + 1]) if last else (x < edges[i + 1]))
        if inside.sum() == 0:
            continue
        values = y[inside]
        se = float(np.std(values, ddof=1) / np.sqrt(values.size)) if values.size > 1 else None
        out.append({"from": float(edges[i]), "to": float(edges[i + 1]), "n": int(values.size),
                    "mean": float(values.mean()), "standard_error": se})
    return out


def _trend(name: str, unit: str, x: np.ndarray, y: np.ndarray, subject: str) -> dict[str, Any]:
    entry: dict[str, Any] = {"variable": name, "unit": unit, "n": int(x.size)}
    if x.size < 3 or np.ptp(x) == 0.0 or np.ptp(y) == 0.0:
        entry.update(rho=None, p_value=None, bins=[],
                     sentence=f"{subject} against {name}: cannot be tested ({name} does not vary "
                              "or too few values)")
        return entry
    rho, p_value = stats.spearmanr(x, y)
    entry.update(rho=float(rho), p_value=float(p_value), bins=_bins(x, y))
    if p_value < SIGNIFICANT_P:
        direction = "rise" if rho > 0 else "fall"
        p_text = "p < 1e-12" if p_value < 1e-12 else f"p = {p_value:.1e}"
        entry["sentence"] = (f"{subject} {direction} with {name} "
                             f"(Spearman rho = {rho:+.2f}, {p_text})")
    else:
        entry["sentence"] = (f"{subject} show no clear trend with {name} (rho = {rho:+.2f}, "
                             f"p = {p_value:.2f})")
    return entry


def residual_structure(readings, residuals: np.ndarray, levels: np.ndarray,
                       network) -> dict[str, Any]:
    """The three views of the module docstring for the baseline fit (JSON-ready)."""
    within = [_trend("sliding distance", "m", readings.distance_m, residuals,
                     "Within tests, the residuals")]
    if readings.time_s is not None:
        within.append(_trend("time", "s", readings.time_s, residuals,
                             "Within tests, the residuals"))
    slopes = _per_test_slopes(readings, residuals)
    between = []
    power = readings.power_W_m2
    if slopes is not None:
        if power is not None:
            between.append(_trend("frictional power mu p v", "W/m^2",
                                  readings.per_test(power), slopes,
                                  "The per-test trends of the residual along ln s"))
        if readings.velocity_m_s is not None:
            between.append(_trend("sliding speed", "m/s", readings.per_test(readings.velocity_m_s),
                                  slopes, "The per-test trends of the residual along ln s"))
    ones = np.ones(readings.n_tests)
    p = None if readings.pressure_Pa is None else readings.per_test(readings.pressure_Pa)
    v = None if readings.velocity_m_s is None else readings.per_test(readings.velocity_m_s)
    load = ones if readings.load_N is None else readings.per_test(readings.load_N)
    network_level = np.log(network(ones if p is None else p, ones if v is None else v) * load)
    offsets = levels - network_level
    subject = "Across tests, ln k minus the network's ln k(p, v)"
    across = [] if p is None else [_trend("pressure", "Pa", p, offsets, subject)]
    if v is not None:
        across.append(_trend("sliding speed", "m/s", v, offsets, subject))
    if power is not None:
        across.append(_trend("frictional power mu p v", "W/m^2", readings.per_test(power), offsets,
                             subject))
    if readings.temperature_C is not None:
        across.append(_trend("temperature", "C", readings.per_test(readings.temperature_C),
                             offsets, subject))
    across.append(_trend("test order", "-", np.arange(readings.n_tests, dtype=float), offsets,
                         subject))
    not_measured = [name for name in ("pressure_Pa", "time_s", "velocity_m_s", "normal_load_N",
                                      "friction_coefficient", "temperature_C")
                    if name not in readings.measured]
    sentences = [entry["sentence"] for entry in within + between + across]
    if not_measured:
        sentences.append("Not measured, so not examined: " + ", ".join(not_measured) + ".")
    return {"within_tests": within, "trend_between_tests": between, "across_tests": across,
            "not_measured": not_measured, "sentences": sentences,
            "per_test_offset": [float(x) for x in offsets],
            "per_test_slope": None if slopes is None else [float(x) for x in slopes]}


def _per_test_slopes(readings, residuals: np.ndarray) -> np.ndarray | None:
    """Least-squares slope of residual against ln s in each test (None if a test has < 3)."""
    slopes = []
    for j in range(readings.n_tests):
        rows = readings.test_index == j
        if rows.sum() < 3:
            return None
        slopes.append(np.polyfit(np.log(readings.distance_m[rows]), residuals[rows], 1)[0])
    return np.array(slopes)
