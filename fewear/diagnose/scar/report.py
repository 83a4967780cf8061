"""Outputs of a scar diagnosis: the JSON-ready summary (``diagnosis.json``) and ``profiles.png``
(the measured profiles, the believed model's prediction and the fitted one)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from fewear.diagnose.core.report import verdict
from fewear.diagnose.scar.catalogue import CAUSES, NONE_MEANING
from fewear.diagnose.scar.diagnose import CauseTrial, ScarDiagnosis
from fewear.io.output import write_json

FIGURE = "profiles.png"


def summarise(diagnosis: ScarDiagnosis, case: str,
              source_coefficients_m2_N: dict[str, float]) -> dict[str, Any]:
    """The summary of ``diagnosis`` of the scar ``case`` (``diagnosis.json``), the fitted
    coefficients beside the source's (``source_coefficients_m2_N``: cause -> m^2/N)."""
    causes, trials = diagnosis.causes, diagnosis.trials
    named = next((trial for trial in trials if trial.cause in causes[:1]), None)
    before = trials[0].held_out_rms_before_m
    after = named.held_out_rms_after_m if named else before
    accept = diagnosis.settings.acceptance
    return {
        "source": diagnosis.measured.source,
        "case": case,
        "profiles": list(diagnosis.measured.names),
        "points": int(diagnosis.measured.depth_points_m.size),
        "holdout": diagnosis.holdout,
        "criterion": (f"F-test against the believed model on effective observations, p < "
                      f"{accept.significance:g} / {len(trials)} causes tried; held-out "
                      f"RMS at least {accept.min_held_out_gain:.0%} lower; AICc at least "
                      f"{accept.min_aicc_improvement:g} lower"),
        "candidates": [_trial_entry(trial, source_coefficients_m2_N[trial.cause])
                       for trial in trials],
        "untestable": [{"cause": cause, "untestable_reason": reason}
                       for cause, reason in diagnosis.untestable.items()],
        **verdict(causes, CAUSES[causes[0]].meaning if causes else NONE_MEANING,
                  list(causes[1:]), before, after),
        "unexplained": [],
        "notes": list(diagnosis.notes),
        "wall_time_s": diagnosis.wall_time_s,
    }


def _trial_entry(trial: CauseTrial, source_m2_N: float) -> dict[str, Any]:
    evidence = trial.evidence
    return {
        "cause": trial.cause,
        "fitted_factor": trial.fit.factor,
        "fitted_coefficient_m2_N": trial.fit.factor * source_m2_N,
        "source_coefficient_m2_N": source_m2_N,
        "fold_factors": [fit.factor for fit in trial.fold_fits],
        "converged": trial.converged,
        "held_out_rms_m": {"believed": trial.held_out_rms_before_m,
                           "fitted": trial.held_out_rms_after_m},
        "gain": evidence.gain,
        "p_value": evidence.p_value,
        "aicc_improvement": evidence.aicc_improvement,
        "effective_observations": trial.effective_observations,
        "accepted": trial.accepted,
        "forward_runs": len(trial.factors_run),
        "factors_run": list(trial.factors_run),
        "forward_wall_time_s": trial.run_wall_time_s,
    }


def write_outputs(diagnosis: ScarDiagnosis, summary: dict[str, Any], stage: Path) -> None:
    """diagnosis.json and profiles.png into the staging folder ``stage``."""
    write_json(stage / "diagnosis.json", summary)
    plot_profiles(stage / FIGURE, diagnosis)


def plot_profiles(path: Path, diagnosis: ScarDiagnosis) -> None:
    """Surface height (um, negative: worn) against x (mm): each measured profile thin, the
    believed model dashed, the model at the fitted factor of the named cause (else of the
    largest held-out gain, labelled not named) solid."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    measured, points = diagnosis.measured, diagnosis.measured.x_m.size
    x_mm = 1e3 * measured.x_m
    figure, axes = plt.subplots(figsize=(7.0, 4.0))
    for name, depth in zip(measured.names, measured.depth_m):
        axes.plot(x_mm, -1e6 * depth, linewidth=0.7, label=f"measured, {name}")
    axes.plot(x_mm, -1e6 * diagnosis.believed_m[:points], color="black", linestyle="--",
              linewidth=1.5, label="believed model (source's k)")
    trial = diagnosis.best_trial
    if trial is not None:
        named = "named" if trial.accepted else "not named"
        axes.plot(x_mm, -1e6 * trial.fitted_m[:points], color="tab:red", linewidth=1.5,
                  label=f"fitted {trial.cause} x{trial.fit.factor:.4g} ({named})")
    axes.set_xlabel("x (mm)")
    axes.set_ylabel("surface height (um)")
    cause = diagnosis.causes[0] if diagnosis.causes else "none"
    axes.set_title(f"{Path(measured.source).name}: cause {cause}")
    axes.grid(True, linewidth=0.3)
    axes.legend(fontsize=7)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
