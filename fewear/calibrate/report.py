"""Outputs of a diagnosis: ``diagnosis.json``, ``report.md`` (with PNG figures) and
``extended_wear.toml`` (the ``[wear]`` section of the extended model, loadable by
:func:`fewear.io.config.load_config` and :func:`fewear.wear.extensions.wear_extension_from_config`).
"""

from __future__ import annotations

import math
from pathlib import Path
from typing import Any

from fewear.io.output import write_json
from fewear.wear.coefficient import wear_section_toml

FIGURES = {"fits": "fits.png", "residuals": "residuals.png", "candidates": "candidates.png"}


def write_outputs(diagnosis, folder: Path) -> dict[str, Path]:
    """Write every output of ``diagnosis`` into ``folder``; returns their paths by name."""
    from fewear.plot.diagnosis import plot_candidates, plot_fits, plot_residuals

    folder = Path(folder)
    paths = {
        "fits": plot_fits(diagnosis, folder / FIGURES["fits"]),
        "residuals": plot_residuals(diagnosis, folder / FIGURES["residuals"]),
        "candidates": plot_candidates(diagnosis, folder / FIGURES["candidates"]),
    }
    paths["json"] = folder / "diagnosis.json"
    write_json(paths["json"], diagnosis.summary)
    paths["toml"] = folder / "extended_wear.toml"
    paths["toml"].write_text(extended_toml(diagnosis))
    paths["report"] = folder / "report.md"
    paths["report"].write_text(report_markdown(diagnosis.summary))
    return paths


def extended_toml(diagnosis) -> str:
    s = diagnosis.summary
    header = (f"# The extended wear model from `fewear diagnose {s['source']}`.\n"
              f"# Cause: {s['cause']} ({s['cause_meaning']}).\n"
              f"# Held-out error: baseline {s['held_out_error']['baseline']:.3g}, extended "
              f"{s['held_out_error']['extended']:.3g} (gain {s['gain']:.0%}).\n"
              "# Use it as the [wear] section of a fewear config (see `fewear config`).\n\n")
    return header + wear_section_toml(diagnosis.extended_section)


def _number(x: Any, fmt: str = ".3g") -> str:
    return "n/a" if x is None or (isinstance(x, float) and not math.isfinite(x)) else format(x, fmt)


def report_markdown(s: dict[str, Any]) -> str:
    """The plain-language report of a diagnosis summary."""
    lines = [f"# Wear diagnosis of `{s['source']}`", ""]
    lines += [f"{s['n_tests']} tests, {s['n_readings']} readings ({s['data_kind']}). Measured: "
              + ", ".join(s["variables_measured"]) + "."]
    lines += [f"- {note}" for note in s["notes"]]
    lines += ["", "## Verdict", ""]
    if s["cause"] == "none":
        lines.append("**Cause: none.** Plain Archard with k(p, v) explains the data within their "
                     "noise: no candidate improved the held-out prediction enough.")
    else:
        lines.append(f"**Cause: {s['cause']}**: {s['cause_meaning']}. Held-out error "
                     f"{s['held_out_error']['baseline']:.3g} (baseline) -> "
                     f"{s['held_out_error']['extended']:.3g} (extended): "
                     f"**gain {s['gain']:.0%}**.")
    for group in s["confounded"]:
        lines += ["", f"**Confounded: {' / '.join(group['causes'])}.** {group['reason']}. "
                  f"To separate them: {group['to_separate']}. Evidence:"]
        for name, ev in group["evidence"].items():
            lines.append(f"- {name}: held-out error {ev['held_out_error']:.3g}, gain "
                         f"{ev['gain']:.0%}, AICc {ev['aicc']:.1f}, params {_params(ev['params'])}")
    for entry in s["untestable"]:
        lines.append(f"- {entry['name']}: {entry['message']}")
    lines += ["", "## Baseline", "",
              f"{s['baseline']['model']}; {s['baseline']['coefficient_reason']}.",
              s["baseline"]["network_note"],
              f"Held-out error {s['baseline']['held_out_error']:.3g}, training error "
              f"{s['baseline']['training_error']:.3g} ({s['noise_model']} residuals).", "",
              f"Hold-out: **{s['holdout']['strategy']}**: {s['holdout']['why']} "
              f"({s['holdout']['n_held_out_readings']} of {s['holdout']['n_readings']} readings "
              "held out).", "", f"Criterion: {s['criterion']}.", ""]
    lines += ["## What the baseline gets wrong", "", "![fits](fits.png)", "",
              "![residuals](residuals.png)", ""]
    lines += [f"- {sentence}." if not sentence.endswith(".") else f"- {sentence}"
              for sentence in s["residual_structure"]["sentences"]]
    lines += ["", "## Candidates", "", "![candidates](candidates.png)", "",
              "| cause | params | held-out error | gain | score (SE) | AICc | verdict |",
              "|---|---|---|---|---|---|---|"]
    for c in s["candidates"]:
        lines.append(f"| {c['name']} | {_params(c['params'])} | {c['held_out_error']:.3g} | "
                     f"{c['gain']:+.0%} | {_number(c['score'], '.1f')} | "
                     f"{_number(c['aicc'], '.1f')} | {c['verdict']} |")
    for entry in s["untestable"]:
        lines.append(f"| {entry['name']} | - | - | - | - | - | {entry['message']} |")
    p = s["prediction"]
    lines += ["", "## What the extension changes in a prediction", "",
              f"{p['what']}: extended / baseline = {p['median_extended_over_baseline']:.3g} "
              f"(median over tests; range {p['range_extended_over_baseline'][0]:.3g} to "
              f"{p['range_extended_over_baseline'][1]:.3g}).", "",
              "| test | distance [m] | baseline [mm^3] | extended [mm^3] | ratio |",
              "|---|---|---|---|---|"]
    for name, row in p["per_test"].items():
        lines.append(f"| {name} | {row['distance_m']:.4g} | {1e9 * row['baseline_m3']:.4g} | "
                     f"{1e9 * row['extended_m3']:.4g} | {row['extended_over_baseline']:.3g} |")
    lines += ["", "## Extended model", "",
              "`extended_wear.toml` holds the `[wear]` section (k(p, v) refitted with the "
              f"extension, extension = \"{s['extended_config']['extension']}\"); paste it into a "
              "config to simulate with it.", ""]
    return "\n".join(lines) + "\n"


def _params(params: dict[str, float]) -> str:
    return ", ".join(f"{key} = {value:.3g}" for key, value in params.items()) or "-"
