"""Figures of a wear diagnosis (:mod:`fewear.diagnose.tribometer.diagnose`): measurement against
baseline and extended model, the baseline's residuals against every measured variable, the causes'
held-out errors. matplotlib with the Agg backend; each function writes one PNG and returns its path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from fewear.diagnose.tribometer.stages import predict_log_volume

MAX_PANELS = 12


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_fits(diagnosis, path: str | Path) -> Path:
    """Histories: wear volume [mm^3] against sliding distance [m], one panel per test (at most
    12): readings, baseline and extended model (fitted on all readings) extrapolated to twice the
    test's distance. Tables: measured against predicted wear volume of every test, baseline and
    extended model."""
    plt = _pyplot()
    if diagnosis.form == "table":
        return _plot_table_fits(diagnosis, path, plt)
    d = diagnosis
    r = d.readings
    result = d.reading_stage
    n = min(r.n_tests, MAX_PANELS)
    cols = min(4, n)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 2.6 * rows), squeeze=False)
    for j in range(n):
        ax = axes.flat[j]
        mask = r.test_index == j
        s_max = r.distance_m[mask].max()
        grid = np.linspace(0.0, d.settings.prediction_distance_factor * s_max, 120)[1:]
        ax.plot(r.distance_m[mask], 1e9 * r.volume_m3[mask], "o", ms=4, color="k",
                label="readings")
        ax.plot(grid, 1e9 * np.exp(predict_log_volume(r, result.stage, result.baseline, j, grid)),
                "--", color="tab:blue", label="baseline (Archard)")
        if result.chosen:
            ax.plot(grid, 1e9 * np.exp(predict_log_volume(r, result.stage, result.final, j,
                                                          grid)),
                    "-", color="tab:red", label=f"extended ({', '.join(result.chosen)})")
        ax.axvline(s_max, color="0.7", lw=0.8)
        ax.set_title(_test_title(r, j), fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=6)
    fig.supxlabel("sliding distance s [m]", fontsize=9)
    fig.supylabel("wear volume V [mm$^3$]", fontsize=9)
    fig.suptitle("Measured wear, baseline and extended model", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def _test_title(r, j: int) -> str:
    title = r.test_labels[j]
    if r.pressure_Pa is not None:
        title += f": {r.per_test(r.pressure_Pa)[j] / 1e6:.3g} MPa"
    elif r.load_N is not None:
        title += f": {r.per_test(r.load_N)[j]:.3g} N"
    if r.velocity_m_s is not None:
        title += f", {r.per_test(r.velocity_m_s)[j]:.3g} m/s"
    return title


def _plot_table_fits(diagnosis, path, plt) -> Path:
    r = diagnosis.readings
    result = diagnosis.reading_stage
    measured = 1e9 * r.volume_m3
    fig, ax = plt.subplots(figsize=(4.6, 4.2))
    fits = [("baseline (Archard)", result.baseline, "tab:blue")]
    if result.chosen:
        fits.append((f"extended ({', '.join(result.chosen)})", result.final, "tab:red"))
    for label, fit, colour in fits:
        predicted = np.array([
            np.exp(predict_log_volume(r, result.stage, fit, j, r.distance_m[i])[0])
            for i, j in enumerate(r.test_index)]) * 1e9
        ax.loglog(predicted, measured, "o", ms=4, mfc="none" if colour == "tab:blue" else colour,
                  color=colour, label=label)
    low, high = measured.min() / 1.5, measured.max() * 1.5
    ax.plot([low, high], [low, high], color="0.6", lw=0.8)
    ax.set_xlabel("predicted wear volume [mm$^3$]", fontsize=8)
    ax.set_ylabel("measured wear volume [mm$^3$]", fontsize=8)
    ax.set_title("Every test: measured against predicted (fitted on all tests)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def plot_residuals(diagnosis, summary: dict, path: str | Path) -> Path:
    """The baseline's residuals against every measured variable: per reading (within tests for
    histories) and, for histories, each test's level; grey points, black binned means with
    standard errors (quartiles)."""
    plt = _pyplot()
    structure = summary["residual_structure"]
    r = diagnosis.readings
    panels = [(entry, _variable(r, entry["variable"], per_test=False),
               diagnosis.reading_stage.baseline.residuals, "ln V residual")
              for entry in structure["readings"]]
    if len(diagnosis.stages) > 1:
        panels += [(entry, _variable(r, entry["variable"], per_test=True),
                    diagnosis.stages[1].baseline.residuals, "ln k residual")
                   for entry in structure["across_tests"]]
    cols = 3
    rows = int(np.ceil(len(panels) / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.6 * cols, 2.8 * rows), squeeze=False)
    for ax, (entry, x, y, ylabel) in zip(axes.flat, panels):
        ax.plot(x, y, ".", color="0.6", ms=4)
        for b in entry.get("bins", []):
            centre = 0.5 * (b["from"] + b["to"])
            ax.errorbar(centre, b["mean"], yerr=b["standard_error"] or 0.0, fmt="s", color="k",
                        ms=4, capsize=2)
        ax.axhline(0.0, color="tab:blue", lw=0.8)
        rho = entry.get("rho")
        stats_text = "" if rho is None else f"  rho={rho:+.2f}, p={entry['p_value']:.1e}"
        ax.set_title(f"{entry['variable']}{stats_text}", fontsize=8)
        ax.set_xlabel(f"{entry['variable']} [{entry['unit']}]", fontsize=8)
        ax.set_ylabel(ylabel, fontsize=7)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[len(panels):]:
        ax.axis("off")
    fig.suptitle("What plain Archard gets wrong: residuals of the baseline", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def plot_candidates(diagnosis, summary: dict, path: str | Path) -> Path:
    """Held-out RMS error of each stage's baseline and of every cause tried at its first step
    (accepted ones in red)."""
    plt = _pyplot()
    names, errors, colours = [], [], []
    for stage in summary["stages"]:
        names.append(f"{stage['name']}: baseline")
        errors.append(stage["baseline_held_out_error"])
        colours.append("tab:blue")
        for entry in stage["steps"][0] if stage["steps"] else []:
            names.append(f"{stage['name']}: {entry['cause']}")
            errors.append(entry["held_out_error"])
            colours.append("tab:red" if entry["accepted"] else "0.6")
    fig, ax = plt.subplots(figsize=(6.0, 0.4 * len(names) + 1.2))
    ax.barh(names[::-1], errors[::-1], color=colours[::-1])
    ax.set_xlabel("held-out RMS error of ln V (leave one test out)", fontsize=8)
    ax.set_title(f"causes: {', '.join(diagnosis.causes) or 'none'}", fontsize=9)
    ax.tick_params(labelsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def _variable(r, name: str, per_test: bool) -> np.ndarray:
    load, _ = r.load_variable
    values = {"sliding distance": r.distance_m, "time": r.time_s, "pressure": load,
              "normal load": load, "sliding speed": r.velocity_m_s,
              "frictional power mu p v": r.power_W_m2, "temperature": r.temperature_C,
              "test order": r.test_index.astype(float)}[name]
    return r.per_test(values) if per_test else values
