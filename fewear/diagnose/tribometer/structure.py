"""The structure of a model's residuals, in numbers and plain words: trends against sliding
distance, time and the test's conditions (Spearman's rank correlation, binned means), and the
sentences of what stays unexplained. The views: docs/diagnosis-method-notes.md."""

from __future__ import annotations

from typing import Any

import numpy as np
from scipy import stats

SIGNIFICANT_P = 0.01
"""p-value below which a trend is called out in the summary (several variables are tested)."""
UNEXPLAINED_P = 1e-3
"""p-value below which a trend left by the final model is reported as unexplained."""


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


def residual_structure(readings, reading_residuals: np.ndarray,
                       test_residuals: np.ndarray | None) -> dict[str, Any]:
    """The views (the method notes) for a model's residuals: per reading, and (histories)
    per test. JSON-ready, with the sentences and the unexplained trends."""
    per_test = readings.n_tests == readings.test_index.size
    subject = "The residuals" if per_test else "Within tests, the residuals"
    load, load_name = readings.load_variable
    readings_view = [_trend("sliding distance", "m", readings.distance_m, reading_residuals,
                            subject)]
    if readings.time_s is not None:
        readings_view.append(_trend("time", "s", readings.time_s, reading_residuals, subject))
    across = []
    if test_residuals is None:
        readings_view += _test_variables(readings, lambda x: x, reading_residuals, subject,
                                         load, load_name)
    else:
        across = _test_variables(readings, readings.per_test, test_residuals,
                                 "Across tests, the levels ln k", load, load_name)
    not_measured = [name for name in ("pressure_Pa", "time_s", "velocity_m_s", "normal_load_N",
                                      "friction_coefficient", "temperature_C")
                    if name not in readings.measured]
    entries = readings_view + across
    sentences = [entry["sentence"] for entry in entries]
    if not_measured:
        sentences.append("Not measured, so not examined: " + ", ".join(not_measured) + ".")
    unexplained = [entry["sentence"] for entry in entries
                   if entry["p_value"] is not None and entry["p_value"] < UNEXPLAINED_P]
    return {"readings": readings_view, "across_tests": across, "not_measured": not_measured,
            "sentences": sentences, "unexplained": unexplained}


def _test_variables(readings, per, y, subject, load, load_name) -> list[dict[str, Any]]:
    """Trends of ``y`` against the variables that describe a test (``per`` maps a per-reading
    array onto ``y``'s rows)."""
    out = []
    if load is not None:
        out.append(_trend(load_name, "Pa" if load_name == "pressure" else "N", per(load), y,
                          subject))
    if readings.velocity_m_s is not None:
        out.append(_trend("sliding speed", "m/s", per(readings.velocity_m_s), y, subject))
    if readings.power_W_m2 is not None:
        out.append(_trend("frictional power mu p v", "W/m^2", per(readings.power_W_m2), y,
                          subject))
    if readings.temperature_C is not None:
        out.append(_trend("temperature", "C", per(readings.temperature_C), y, subject))
    order = readings.test_index.astype(float)
    out.append(_trend("test order", "-", per(order), y, subject))
    return out
