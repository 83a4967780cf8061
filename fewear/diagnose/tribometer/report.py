"""Outputs of a diagnosis: the JSON-ready summary, ``diagnosis.json``, ``report.md`` (with PNG
figures) and ``extended_wear.toml`` (the ``[wear]`` section of the extended model, loadable by
:func:`fewear.io.config.load_config` and :func:`fewear.wear.extensions.wear_extension_from_config`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

import numpy as np

from fewear.diagnose.core.report import verdict
from fewear.diagnose.core.statistics import paired_improvement_p
from fewear.diagnose.tribometer.catalogue import CAUSES
from fewear.diagnose.tribometer.diagnose import Diagnosis
from fewear.diagnose.tribometer.figures import plot_candidates, plot_fits, plot_residuals
from fewear.diagnose.tribometer.fitting import Trial
from fewear.diagnose.tribometer.stages import log_k_per_test, predict_log_volume, untestable_causes
from fewear.diagnose.tribometer.structure import residual_structure
from fewear.io.output import write_json
from fewear.wear.coefficient import wear_section_toml

FIGURES = {"fits": "fits.png", "residuals": "residuals.png", "candidates": "candidates.png"}


# ---------------------------------------------------------------------------------------------
# The summary


def summarise(diagnosis: Diagnosis) -> dict[str, Any]:
    """The JSON-ready summary of a diagnosis (``diagnosis.json``)."""
    readings, settings, form = diagnosis.readings, diagnosis.settings, diagnosis.form
    stages, causes, extended = diagnosis.stages, diagnosis.causes, diagnosis.extended_section
    reading_stage = stages[0]
    across = stages[1] if len(stages) > 1 else None
    before = residual_structure(readings, reading_stage.baseline.residuals,
                                None if across is None else across.baseline.residuals)
    after = residual_structure(readings, reading_stage.final.residuals,
                               None if across is None else across.final.residuals)
    scored = next((st for st in stages if causes and causes[0] in st.chosen), reading_stage)
    baseline_error = scored.baseline_rms
    extended_error = scored.final_rms
    test_group, group_names = readings.test_groups()
    log_k = log_k_per_test(readings, reading_stage.stage, reading_stage.baseline)
    return {
        "source": readings.source,
        "data_kind": readings.data_kind,
        "n_tests": readings.n_tests,
        "n_readings": int(readings.test_index.size),
        "variables_measured": list(readings.measured),
        "notes": list(readings.notes) + _form_notes(readings, form),
        "data_form": form,
        "material_groups": {name: int(np.sum(test_group == i))
                            for i, name in enumerate(group_names)},
        "holdout": {"strategy": "tests", "why": _holdout_why(form)},
        "criterion": _criterion_text(settings),
        "stages": [_stage_summary(st) for st in stages],
        "baseline": {
            "model": "Archard V = k F s, one k per material group"
            if len(group_names) > 1 else "Archard V = k F s, one k for all tests",
            "held_out_error": baseline_error,
            "training_error": _rms(reading_stage.baseline.residuals),
            "k_per_test_m2_N": {label: float(np.exp(value))
                                for label, value in zip(readings.test_labels, log_k)},
        },
        "candidates": [trial_entry(trial) for st in stages
                       for trial in (st.steps[0] if st.steps else ())],
        "untestable": untestable_causes(readings, settings),
        **verdict(causes, CAUSES[causes[0]].meaning if causes else _none_meaning(after),
                  _confounded(stages, readings, settings), baseline_error, extended_error),
        "prediction": _prediction(readings, reading_stage, settings),
        "residual_structure": before,
        "unexplained": after["unexplained"],
        "extended_config": extended,
        "extended_config_notes": _config_notes(readings, extended),
    }


def _rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(values**2)))


def trial_entry(trial: Trial) -> dict[str, Any]:
    """A cause tried, as ``diagnosis.json`` lists it (docs/diagnosis-json.md)."""
    return {
        "cause": trial.cause, "form": trial.form, "stage": trial.stage, "params": trial.params,
        "held_out_error": trial.held_out_error,
        "held_out_error_before": trial.held_out_error_before,
        "gain": trial.evidence.gain, "test": trial.test, "p_value": trial.evidence.p_value,
        "forms_tried": trial.forms_tried, "tests_improved": trial.tests_improved,
        "aicc_improvement": trial.evidence.aicc_improvement, "training_error": trial.training_error,
        "accepted": trial.accepted, "verdict": trial.verdict,
    }


def _stage_summary(result) -> dict[str, Any]:
    return {"name": result.stage.name, "rows": int(result.stage.y.size),
            "held_out_tests": int(np.sum(np.isfinite(result.baseline_errors))),
            "baseline_held_out_error": result.baseline_rms,
            "final_held_out_error": result.final_rms,
            "chosen": list(result.chosen),
            "final_params": {form.cause: law.params()
                             for form, law in zip(result.final.forms, result.final.laws)},
            "steps": [[trial_entry(trial) for trial in step] for step in result.steps]}


def _form_notes(readings, form: str) -> list[str]:
    if form == "histories":
        return []
    counts = np.bincount(readings.test_index)
    notes = [f"A table ({int(counts.max())} reading(s) at most per test): tests of one material "
             "group that differ in sliding distance form the wear curve V(s) across tests"]
    if readings.velocity_m_s is not None:
        ls, lv = np.log(readings.distance_m), np.log(readings.velocity_m_s)
        if np.ptp(ls) > 0 and np.ptp(lv) > 0 and abs(np.corrcoef(ls, lv)[0, 1]) > 0.99:
            notes.append("sliding distance and speed vary together (same test time): an effect "
                         "of distance cannot be told from an effect of speed")
    if readings.pressure_Pa is None and readings.load_N is not None:
        notes.append("no contact pressure: the load laws use the normal load F in its place")
    return notes


def _config_notes(readings, extended) -> list[str]:
    """What the extended [wear] section stands for when the table cannot give the seed's k(p, v)
    for every material."""
    test_group, names = readings.test_groups()
    notes = []
    if len(names) > 1:
        main = names[int(np.bincount(test_group).argmax())]
        notes.append(f"k of the extended config: the tests of the largest material group ({main})")
    if extended["coefficient_model"] == "constant":
        why = ("no contact pressure or speed, so no network k(p, v) for the simulation"
               if readings.pressure_Pa is None or readings.velocity_m_s is None
               else "too few distinct (p, v) conditions for the network")
        notes.append(f"k of the extended config is one constant (geometric mean): {why}")
    return notes


def _holdout_why(form: str) -> str:
    if form == "histories":
        return ("leave-one-test-out: each test's curve predicted with the laws fitted on the other "
                "tests and the test's own level (shape causes); each test's level predicted from "
                "the other tests (level causes)")
    return ("leave-one-test-out: each test predicted from the other tests of its material group "
            "with the laws fitted on them")


def _criterion_text(settings) -> str:
    return (f"forward selection: a cause joins when it predicts the held-out tests better (paired "
            "t-test over tests along tests, F-test where each test is one row; p < "
            f"{settings.acceptance.significance:g} / number of forms tried at that step) "
            "and its AICc on all rows falls by at least "
            f"{settings.acceptance.min_aicc_improvement:g}")


def _none_meaning(after: dict[str, Any]) -> str:
    if after["unexplained"]:
        return ("no cause of the catalogue explains what plain Archard leaves; unexplained: "
                + "; ".join(after["unexplained"]))
    return "plain Archard explains the data within their noise"


def _confounded(stages, readings, settings) -> list[dict[str, Any]]:
    """Per stage: causes accepted at the first step that the held-out errors do not tell apart
    from the one chosen first (paired p >= significance that the chosen predicts the held-out
    tests better)."""
    groups = []
    for result in stages:
        if not result.chosen:
            continue
        first = result.steps[0]
        best = next(trial for trial in first if trial.cause == result.chosen[0])
        others = [trial for trial in first if trial.accepted and trial.cause != best.cause
                  and paired_improvement_p(trial.errors, best.errors)
                  >= settings.acceptance.significance]
        if others:
            groups.append(_confounded_group(best, others, readings, settings))
    return groups


def _confounded_group(best: Trial, others: list[Trial], readings, settings) -> dict[str, Any]:
    names = {best.cause} | {trial.cause for trial in others}
    return {
        "causes": [best.cause] + [trial.cause for trial in others],
        "reason": _structural_reason(readings, names) or (
            "their held-out errors do not differ significantly (paired p >= "
            f"{settings.acceptance.significance:g})"),
        "evidence": {trial.cause: {"held_out_error": trial.held_out_error,
                                   "gain": trial.evidence.gain,
                                   "p_value": trial.evidence.p_value, "params": trial.params}
                     for trial in [best] + others},
        "to_separate": "tests at different sliding speeds (with distance and time both read)"
        if {"running_in", "time_transient"} <= names
        else "tests that vary the variable that drives one cause but not the other",
    }


def _structural_reason(readings, names: set[str]) -> str:
    if {"running_in", "time_transient"} <= names and readings.velocity_m_s is not None:
        v = readings.per_test(readings.velocity_m_s)
        if v.max() / v.min() < 1.2:
            return (f"all tests at one speed (v from {v.min():.3g} to {v.max():.3g} m/s): sliding "
                    "distance and time are proportional, so running_in (over distance) and "
                    "time_transient (over time) predict the same curves")
        return (f"speeds from {v.min():.3g} to {v.max():.3g} m/s do not separate the two within "
                "the noise")
    return ""


def _prediction(readings, result, settings) -> dict[str, Any]:
    """Wear after ``prediction_distance_factor`` x each test's own final distance (and time),
    extended over baseline model (both fitted on all readings)."""
    factor = settings.prediction_distance_factor
    s = factor * readings.final_per_test(readings.distance_m)
    per_test = {}
    for j, label in enumerate(readings.test_labels):
        base = float(np.exp(predict_log_volume(readings, result.stage, result.baseline, j,
                                               s[j])[0]))
        ext = float(np.exp(predict_log_volume(readings, result.stage, result.final, j, s[j])[0]))
        per_test[label] = {"distance_m": float(s[j]), "baseline_m3": base, "extended_m3": ext,
                           "extended_over_baseline": ext / base}
    ratio = np.array([row["extended_over_baseline"] for row in per_test.values()])
    return {"distance_factor": factor,
            "what": f"wear volume after {factor:g} x each test's own sliding distance",
            "per_test": per_test,
            "median_extended_over_baseline": float(np.median(ratio)),
            "range_extended_over_baseline": [float(ratio.min()), float(ratio.max())]}


# ---------------------------------------------------------------------------------------------
# Files


def write_outputs(diagnosis: Diagnosis, summary: dict[str, Any], folder: Path) -> dict[str, Path]:
    """Write every output of ``diagnosis`` (its ``summary``: :func:`summarise`) into
    ``folder``; returns their paths by name."""
    folder = Path(folder)
    paths = {
        "fits": plot_fits(diagnosis, folder / FIGURES["fits"]),
        "residuals": plot_residuals(diagnosis, summary, folder / FIGURES["residuals"]),
        "candidates": plot_candidates(diagnosis, summary, folder / FIGURES["candidates"]),
    }
    paths["json"] = folder / "diagnosis.json"
    write_json(paths["json"], summary)
    paths["toml"] = folder / "extended_wear.toml"
    paths["toml"].write_text(extended_toml(diagnosis, summary))
    paths["report"] = folder / "report.md"
    paths["report"].write_text(report_markdown(summary))
    return paths


def extended_toml(diagnosis: Diagnosis, s: dict[str, Any]) -> str:
    """``extended_wear.toml``: the extended model's [wear] section under a header saying where
    it comes from (``s``: the summary)."""
    header = (f"# The extended wear model from `fewear diagnose {s['source']}`.\n"
              f"# Causes: {', '.join(s['causes']) or 'none'} ({s['cause_meaning']}).\n"
              f"# Held-out error: baseline {s['held_out_error']['baseline']:.3g}, extended "
              f"{s['held_out_error']['extended']:.3g} (gain {s['gain']:.0%}).\n"
              "# The extension is the shape cause; k(p, v) carries the level causes.\n"
              "# Use it as the [wear] section of a fewear config (see `fewear config`).\n\n")
    if "normal_load_N" not in s["variables_measured"]:
        header += ("# NOT IN m^2/N: the data held no normal_load_N, so V / (p s) was fitted and\n"
                   "# k(p, v) below is k times the pins' apparent contact area A (m^2); divide\n"
                   "# its level by A before using it, or diagnose again with normal_load_N.\n\n")
    return header + wear_section_toml(diagnosis.extended_section)


def _number(x: Any, fmt: str = ".3g") -> str:
    return "n/a" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, fmt)


def report_markdown(s: dict[str, Any]) -> str:
    """The plain-language report of a diagnosis summary."""
    lines = [f"# Wear diagnosis of `{s['source']}`", ""]
    lines += [f"{s['n_tests']} tests, {s['n_readings']} readings ({s['data_kind']}, "
              f"{s['data_form']}). Measured: " + ", ".join(s["variables_measured"]) + "."]
    lines += [f"- {note}" for note in s["notes"]]
    if len(s["material_groups"]) > 1:
        lines.append("- material groups (one k each): " + ", ".join(
            f"{name} ({n} tests)" for name, n in s["material_groups"].items()))
    lines += ["", "## Verdict", ""]
    if s["cause"] == "none":
        lines.append(f"**Causes: none.** {s['cause_meaning'][0].upper()}"
                     f"{s['cause_meaning'][1:]}.")
    else:
        lines.append(f"**Causes: {', '.join(s['causes'])}** (by held-out gain). First: "
                     f"{s['cause']}: {s['cause_meaning']}. Held-out error "
                     f"{s['held_out_error']['baseline']:.3g} (baseline) -> "
                     f"{s['held_out_error']['extended']:.3g} (extended): "
                     f"**gain {s['gain']:.0%}**.")
        if s["unexplained"]:
            lines.append("Still unexplained after these causes: " + "; ".join(s["unexplained"])
                         + ".")
    for group in s["confounded"]:
        lines += ["", f"**Confounded: {' / '.join(group['causes'])}.** {group['reason']}. "
                  f"To separate them: {group['to_separate']}. Evidence:"]
        for name, ev in group["evidence"].items():
            lines.append(f"- {name}: held-out error {ev['held_out_error']:.3g}, gain "
                         f"{ev['gain']:.0%}, p {ev['p_value']:.1e}, params {_params(ev['params'])}")
    for entry in s["untestable"]:
        lines.append(f"- {entry['cause']}: {entry['untestable_reason']}")
    lines += ["", "## Baseline", "", f"{s['baseline']['model']}. Hold-out: {s['holdout']['why']}.",
              "", f"Criterion: {s['criterion']}.", ""]
    lines += ["## What the baseline gets wrong", "", "![fits](fits.png)", "",
              "![residuals](residuals.png)", ""]
    lines += [f"- {sentence}." if not sentence.endswith(".") else f"- {sentence}"
              for sentence in s["residual_structure"]["sentences"]]
    lines += ["", "## Candidates", "", "![candidates](candidates.png)", "",
              "| stage | step | cause (form) | params | held-out error | gain | p | "
              "AICc improvement | verdict |", "|---|---|---|---|---|---|---|---|---|"]
    for stage in s["stages"]:
        for number, step in enumerate(stage["steps"], start=1):
            for c in step:
                lines.append(
                    f"| {stage['name']} | {number} | {c['cause']} ({c['form']}) | "
                    f"{_params(c['params'])} | {c['held_out_error']:.3g} | {c['gain']:+.0%} | "
                    f"{c['p_value']:.1e} | {_number(c['aicc_improvement'], '+.1f')} | "
                    f"{c['verdict']} |")
    p = s["prediction"]
    lines += ["", "## What the extension changes in a prediction", "",
              f"{p['what']}: extended / baseline = {p['median_extended_over_baseline']:.3g} "
              f"(median over tests; range {p['range_extended_over_baseline'][0]:.3g} to "
              f"{p['range_extended_over_baseline'][1]:.3g}).", ""]
    lines += ["## Extended model", "",
              "`extended_wear.toml` holds the `[wear]` section (extension = \""
              f"{s['extended_config']['extension']}\", k(p, v) refitted under it); paste it into a "
              "config to simulate with it.", ""]
    lines += [f"- {note}" for note in s["extended_config_notes"]]
    return "\n".join(lines) + "\n"


def _params(params: dict[str, float]) -> str:
    return ", ".join(f"{key} = {value:.3g}" for key, value in params.items()) or "-"

