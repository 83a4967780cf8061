"""Where the believed joint model's misses sit in the mechanism's cycle: the bore's residuals
read through the believed dynamics on its own worn bore (contact direction, force and mode
against the crank angle), and measured traces against simulated ones. The method:
docs/diagnosis-method-notes.md."""

from __future__ import annotations

import math

import numpy as np

from fewear.mbd.history import JointHistory
from fewear.mesh.profile import polar_angle

SECTORS = 12
"""Sectors of the crank cycle in the tables (30 deg each)."""
MAX_LISTED_IMPACTS = 12
"""The largest impacts listed one by one (all are counted)."""
CONCENTRATED = 1.5
"""A mean |residual| at the impacts above this multiple of the bore's RMS residual is reported
as a miss concentrated at the impacts (for a residual spread evenly the ratio is about 1)."""


def _crank_deg(history: JointHistory) -> np.ndarray:
    return np.degrees(history.crank_angle_rad) % 360.0


def _step_weights_s(history: JointHistory) -> np.ndarray:
    """Each row's share of the cycle's time (trapezoid weights), s."""
    dt = np.diff(history.time_s)
    return np.concatenate([[0.5 * dt[0]], 0.5 * (dt[1:] + dt[:-1]), [0.5 * dt[-1]]])


def contact_angle_rad(history: JointHistory) -> np.ndarray:
    """The bore angle the pin presses on (direction of the eccentricity), in [0, 2 pi)."""
    return polar_angle(history.eccentricity_m)


def crank_angle_table(history: JointHistory, residual_at) -> list[dict[str, float | None]]:
    """Per crank sector: contact time share, force-weighted mean bore angle pressed (deg) and
    mean residual there (m); ``residual_at(angle_rad)`` is the residual profile."""
    crank = _crank_deg(history)
    force = np.linalg.norm(history.reaction_force_N, axis=1)
    weight = _step_weights_s(history)
    theta = contact_angle_rad(history)
    residual = residual_at(theta)
    in_contact = history.normal_force_N > 0.0
    rows = []
    for k in range(SECTORS):
        lo, hi = 360.0 * k / SECTORS, 360.0 * (k + 1) / SECTORS
        at = (crank >= lo) & (crank < hi)
        pressed = at & in_contact
        w = (force * weight)[pressed]
        total = float(w.sum())
        mean_angle = (math.degrees(math.atan2(np.sum(w * np.sin(theta[pressed])),
                                              np.sum(w * np.cos(theta[pressed])))) % 360.0
                      if total > 0.0 else None)
        rows.append({"crank_from_deg": lo, "crank_to_deg": hi,
                     "contact_share": float(weight[pressed].sum() / max(weight[at].sum(), 1e-300)),
                     "pressed_angle_deg": mean_angle,
                     "residual_m": float(w @ residual[pressed] / total) if total > 0.0 else None})
    return rows


def impact_table(history: JointHistory, residual_at, bore_rms_m: float) -> dict:
    """The believed model's impacts in the cycle and the residual at their bore angles."""
    force = np.linalg.norm(history.reaction_force_N, axis=1)
    theta, crank = contact_angle_rad(history), _crank_deg(history)
    events = []
    for first, last in history.impact_episodes():
        peak = first + int(np.argmax(force[first:last + 1]))
        events.append({"crank_angle_deg": float(crank[first]),
                       "bore_angle_deg": float(math.degrees(theta[peak])),
                       "peak_force_N": float(force[peak]),
                       "residual_m": float(residual_at(np.array([theta[peak]]))[0])})
    mean_abs = float(np.mean([abs(e["residual_m"]) for e in events])) if events else None
    return {"impacts_per_cycle": len(events), "mean_abs_residual_at_impacts_m": mean_abs,
            "bore_rms_residual_m": bore_rms_m,
            "ratio": mean_abs / bore_rms_m if events and bore_rms_m > 0.0 else None,
            "largest": sorted(events, key=lambda e: -e["peak_force_N"])[:MAX_LISTED_IMPACTS]}


def simulated_signal(history: JointHistory, quantity: str) -> np.ndarray:
    """|F| (N) on the joint or the slider's acceleration (m/s^2) at the history's rows."""
    if quantity == "force":
        return np.linalg.norm(history.reaction_force_N, axis=1)
    return np.gradient(history.slider_velocity_m_s, history.time_s)


def _on_crank_grid(crank_deg: np.ndarray, values: np.ndarray, grid_deg: np.ndarray) -> np.ndarray:
    """Mean of ``values`` in each 1 deg bin of the crank angle (empty bins interpolated)."""
    index = np.clip(np.floor(crank_deg % 360.0).astype(int), 0, grid_deg.size - 1)
    total = np.bincount(index, values, grid_deg.size)
    count = np.bincount(index, minlength=grid_deg.size)
    filled = count > 0
    return np.interp(grid_deg, grid_deg[filled], total[filled] / count[filled], period=360.0)


def trace_table(time_s: np.ndarray, measured: np.ndarray, history: JointHistory,
                quantity: str) -> dict:
    """A measured trace (|F| or slider acceleration) against the simulated one: the crank
    phase of the trace's time origin fitted by circular cross-correlation (the crank turns at
    the history's constant speed), RMS difference, peaks, and the mean difference per crank
    sector."""
    grid = np.arange(360.0)
    signal = simulated_signal(history, quantity)
    simulated = _on_crank_grid(_crank_deg(history), signal, grid)
    omega_rad_s = ((history.crank_angle_rad[-1] - history.crank_angle_rad[0])
                   / (history.time_s[-1] - history.time_s[0]))
    raw = _on_crank_grid(np.degrees(omega_rad_s * (time_s - time_s[0])), measured, grid)
    errors = [np.mean((np.roll(raw, shift) - simulated) ** 2) for shift in range(360)]
    shift = int(np.argmin(errors))
    aligned = np.roll(raw, shift)
    difference = aligned - simulated
    sim_rms = float(np.sqrt(np.mean(simulated**2)))
    sectors = difference.reshape(SECTORS, -1).mean(axis=1)
    return {"quantity": "joint force magnitude (N)" if quantity == "force"
            else "slider acceleration (m/s^2)",
            "phase_deg": float(shift), "rms_difference": float(np.sqrt(errors[shift])),
            "relative_rms_difference": float(np.sqrt(errors[shift])) / max(sim_rms, 1e-300),
            "measured_peak": float(np.max(np.abs(measured))),
            "simulated_peak": float(np.max(np.abs(signal))),
            "difference_by_sector": [float(v) for v in sectors]}


def structure_sentences(by_count: list[dict], crank: dict | None, traces: list[dict]) -> list[str]:
    """The residual structure in words, for the report."""
    sentences = []
    if by_count:
        last = by_count[-1]
        where = (f" at {last['largest_at_deg']:.0f} deg (bushing frame)"
                 if last["largest_at_deg"] is not None else "")
        sentences.append(f"At {last['cycles']:,} cycles the believed model misses by "
                         f"{last['rms_m']:.3g} m RMS, most ({last['largest_m']:.3g} m){where}.")
    if crank is not None:
        rows = [r for r in crank["by_crank_angle"] if r["residual_m"] is not None]
        if rows:
            worst = max(rows, key=lambda r: abs(r["residual_m"]))
            sentences.append(
                f"Read against the crank cycle, the largest miss ({worst['residual_m']:.3g} m) "
                f"is worn between crank angles {worst['crank_from_deg']:.0f} and "
                f"{worst['crank_to_deg']:.0f} deg, where the pin presses the bore at "
                f"{worst['pressed_angle_deg']:.0f} deg.")
        impacts = crank["impacts"]
        if impacts["ratio"] is not None:
            concentrated = "" if impacts["ratio"] > CONCENTRATED else "not "
            sentences.append(
                f"The believed model's {impacts['impacts_per_cycle']} impacts per cycle hit "
                f"where the residual is {impacts['ratio']:.2f} times the bore's RMS residual "
                f"on average: the miss is {concentrated}concentrated at the impacts.")
    for row in traces:
        sentences.append(
            f"Measured {row['quantity']} at {row['cycles']:,} cycles differs from the believed "
            f"model's by {row['relative_rms_difference']:.0%} RMS (peaks {row['measured_peak']:.3g}"
            f" measured, {row['simulated_peak']:.3g} simulated).")
    return sentences


def scatter_estimate_m(angle_rad: np.ndarray, residual_m: np.ndarray,
                       cycles: np.ndarray) -> float | None:
    """The instrument's scatter (m) from the residuals of each profile: the second difference of
    neighbouring points, r[i-1] - 2 r[i] + r[i+1], has variance 6 sigma^2 for white noise and
    removes what varies smoothly along the bore; its median absolute value / 0.6745 (a robust
    standard deviation, deaf to dust spikes) / sqrt 6. None without a profile of >= 5 points."""
    second = []
    for count in np.unique(cycles):
        at = (cycles == count) & np.isfinite(angle_rad)
        if at.sum() >= 5:
            r = residual_m[at][np.argsort(angle_rad[at])]
            second.append(r[:-2] - 2.0 * r[1:-1] + r[2:])
    if not second:
        return None
    return float(np.median(np.abs(np.concatenate(second))) / 0.6745 / math.sqrt(6.0))
