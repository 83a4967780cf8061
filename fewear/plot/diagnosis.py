"""Figures of a wear diagnosis (:mod:`fewear.calibrate.diagnose`): measurement against baseline
and extended model, the baseline's residuals against every measured variable, the candidates'
held-out errors. matplotlib with the Agg backend; each function writes one PNG and returns its path.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

MAX_PANELS = 12


def _pyplot():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    return plt


def plot_fits(diagnosis, path: str | Path) -> Path:
    """Wear volume [mm^3] against sliding distance [m], one panel per test (at most 12): readings
    (filled: training, open: held out), baseline and extended model fitted on the training part
    (on all readings when whole tests are held out), extrapolated to twice the test's distance."""
    from fewear.calibrate.diagnose import predict_volume_m3

    plt = _pyplot()
    d = diagnosis
    r = d.readings
    later = d.holdout.strategy == "later_readings"
    base = d.baseline_score.fold_fits[0] if later else d.baseline_fit
    ext = d.extended_score.fold_fits[0] if later else d.extended_fit
    n = min(r.n_tests, MAX_PANELS)
    cols = min(4, n)
    rows = int(np.ceil(n / cols))
    fig, axes = plt.subplots(rows, cols, figsize=(3.2 * cols, 2.6 * rows), squeeze=False,
                             sharex=False)
    for j in range(n):
        ax = axes.flat[j]
        mask = r.test_index == j
        held = mask & d.holdout.held_out if later else np.zeros_like(mask)
        train = mask & ~held
        s_max = r.distance_m[mask].max()
        grid = np.linspace(0.0, d.settings.prediction_distance_factor * s_max, 120)[1:]
        ax.plot(r.distance_m[train], 1e9 * r.volume_m3[train], "o", ms=4, color="k",
                label="readings (fit)")
        if held.any():
            ax.plot(r.distance_m[held], 1e9 * r.volume_m3[held], "o", ms=4, mfc="none",
                    color="k", label="readings (held out)")
        ax.plot(grid, 1e9 * predict_volume_m3(base, r, j, grid), "--", color="tab:blue",
                label="baseline (Archard)")
        if d.cause != "none":
            ax.plot(grid, 1e9 * predict_volume_m3(ext, r, j, grid), "-", color="tab:red",
                    label=f"extended ({d.cause})")
        ax.axvline(s_max, color="0.7", lw=0.8)
        title = r.test_labels[j]
        if r.pressure_Pa is not None:
            title += f": {r.per_test(r.pressure_Pa)[j] / 1e6:.3g} MPa"
        if r.velocity_m_s is not None:
            title += f", {r.per_test(r.velocity_m_s)[j]:.3g} m/s"
        ax.set_title(title, fontsize=8)
        ax.tick_params(labelsize=7)
    for ax in list(axes.flat)[n:]:
        ax.axis("off")
    axes.flat[0].legend(fontsize=6)
    fig.supxlabel("sliding distance s [m]", fontsize=9)
    fig.supylabel("wear volume V [mm$^3$]", fontsize=9)
    fig.suptitle("Measured wear, baseline and extended model (fitted on the training readings)",
                 fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def plot_residuals(diagnosis, path: str | Path) -> Path:
    """The baseline's residuals (all readings, each test's own k) against sliding distance and
    time within tests, and each test's ln k minus the network's against the test variables;
    grey points, black binned means with standard errors (quartiles)."""
    plt = _pyplot()
    structure = diagnosis.summary["residual_structure"]
    r = diagnosis.readings
    residuals = diagnosis.baseline_fit.residuals
    panels = []
    for entry in structure["within_tests"]:
        x = r.distance_m if entry["variable"] == "sliding distance" else r.time_s
        panels.append((entry, x, residuals, f"residual ({diagnosis.settings.noise_model})"))
    offsets = np.array(structure["per_test_offset"])
    for entry in structure["across_tests"]:
        panels.append((entry, _test_variable(r, entry["variable"]), offsets,
                       "ln k - ln k_network(p, v)"))
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


def plot_candidates(diagnosis, path: str | Path) -> Path:
    """Held-out RMS error of the baseline and of every tested candidate (accepted ones in red)."""
    plt = _pyplot()
    summary = diagnosis.summary
    names = ["baseline"] + [c["name"] for c in summary["candidates"]]
    errors = [summary["baseline"]["held_out_error"]] + [c["held_out_error"]
                                                        for c in summary["candidates"]]
    colours = ["tab:blue"] + ["tab:red" if c["accepted"] else "0.6"
                              for c in summary["candidates"]]
    fig, ax = plt.subplots(figsize=(5.0, 3.0))
    ax.bar(names, errors, color=colours)
    ax.set_ylabel(f"held-out RMS error ({summary['noise_model']})", fontsize=8)
    ax.set_title(f"cause: {summary['cause']} (held-out: {summary['holdout']['strategy']})",
                 fontsize=9)
    ax.tick_params(labelsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return Path(path)


def _test_variable(r, name: str) -> np.ndarray:
    if name == "pressure":
        return r.per_test(r.pressure_Pa)
    if name == "sliding speed":
        return r.per_test(r.velocity_m_s)
    if name == "frictional power mu p v":
        return r.per_test(r.power_W_m2)
    if name == "temperature":
        return r.per_test(r.temperature_C)
    return np.arange(r.n_tests, dtype=float)
