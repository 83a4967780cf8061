"""Outputs of a joint diagnosis: the summary (:func:`summarise`, ``diagnosis.json``),
``report.md``, ``extended.toml`` (the config lines of the extended model that differ from the
default, usable as ``--config``) and the figure ``joint_fits.png``.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from fewear.diagnose.core import report
from fewear.diagnose.joint.catalogue import CAUSES, NONE_MEANING
from fewear.diagnose.joint.diagnose import CauseVerdict, JointDiagnosis
from fewear.diagnose.joint.figures import plot_joint_fits
from fewear.diagnose.joint.fitting import Fit, Observations
from fewear.diagnose.joint.resolution import MEMBER_START_OFFSETS_DEG
from fewear.io.config import default_config
from fewear.io.output import write_json
from fewear.wear.coefficient import wear_section_toml


def config_differences(config: dict) -> str:
    """The TOML lines of ``config`` that differ from the embedded default, by section."""
    defaults = default_config()
    blocks = []
    for section, table in config.items():
        changed = {key: value for key, value in table.items()
                   if defaults.get(section, {}).get(key) != value}
        if changed:
            blocks.append(wear_section_toml(changed, section))
    return "\n".join(blocks)


def summarise(diagnosis: JointDiagnosis) -> dict[str, Any]:
    """The JSON-ready summary of ``diagnosis`` (``diagnosis.json``)."""
    d, obs, accept = diagnosis, diagnosis.observations, diagnosis.settings.acceptance
    causes = list(d.causes)
    return {
        "source": ", ".join(d.data.sources),
        "data_kind": "joint",
        "notes": list(d.data.notes) + list(d.trace_notes),
        "cycle_counts": sorted(int(c) for c in np.unique(obs.cycles)),
        "holdout": {"strategy": "later cycle counts",
                    "held_out_cycles": sorted(int(c) for c in np.unique(obs.cycles[~obs.train])),
                    "why": "life prediction: the model is fitted on the earlier measurements and "
                           "judged on how it predicts the later ones"},
        "criterion": (f"F-test p < {accept.significance:g} / forms tried, held-out RMS at "
                      f"least {accept.min_held_out_gain:.0%} lower, AICc at least "
                      f"{accept.min_aicc_improvement:g} lower"),
        "baseline": {"model": "the believed config at the resolved wear blocks",
                     "held_out_error": d.baseline.held_out_rms_m,
                     "training_error": d.baseline.train_rms_m,
                     "angle_offset_deg": float(d.baseline.x[0])},
        "candidates": [_candidate(entry) for entry in d.verdicts],
        "untestable": list(d.untestable),
        **report.verdict(causes, CAUSES[causes[0]].meaning if causes else NONE_MEANING,
                         [{"cause": e.cause, "held_out_rms_m": e.fit.held_out_rms_m}
                          for e in d.confounded],
                         d.baseline.held_out_rms_m, d.extended_fit.held_out_rms_m),
        "prediction": {"baseline": _prediction(obs, d.baseline),
                       "extended": _prediction(obs, d.extended_fit)},
        "residual_structure": d.residual_structure,
        "resolution": d.resolution,
        "cause_gains": _cause_gains(d),
        "trace_evidence": (d.rounds[0].trace_evidence.summary()
                           if d.rounds[0].trace_evidence else None),
        "confirmations": [vars(entry) for entry in d.confirmations],
        "not_confirmed": [entry.cause for entry in d.not_confirmed],
        "unexplained": list(d.unexplained),
    }


def _cause_gains(d: JointDiagnosis) -> list[dict[str, Any]]:
    """Per round that named a cause (or a pair, both at once): the held-out gain it adds to the
    model of the causes before it."""
    entries, before = [], []
    for named_round in (r for r in d.rounds if r.named):
        against = "the believed config" + "".join(f" + {c}" for c in before)
        if named_round.level_of:
            against += " at the believed level of k"
        entries.append({"cause": " + ".join(named_round.named),
                        "gain": named_round.gain, "against": against})
        before += named_round.named
    return entries


def _candidate(entry: CauseVerdict) -> dict[str, Any]:
    """A cause's verdict as a summary entry."""
    fit_, evidence = entry.fit, entry.evidence
    return {"cause": fit_.name, "form": fit_.form, "against": entry.against,
            "p_value": evidence.p_value, "held_out_rms_m": fit_.held_out_rms_m,
            "training_rms_m": fit_.train_rms_m, "gain": evidence.gain,
            "aicc_improvement": evidence.aicc_improvement, "accepted": entry.accepted,
            "params": fit_.params}


def _prediction(obs: Observations, fit_: Fit) -> dict[str, float]:
    """Measured and predicted maximum depth at the last cycle count."""
    last = obs.cycles == obs.cycles.max()
    predicted = obs.depth_m[last] - fit_.residuals_m[last]
    return {"cycles": int(obs.cycles.max()), "measured_max_depth_m": float(obs.depth_m[last].max()),
            "predicted_max_depth_m": float(predicted.max())}


def write_joint_outputs(diagnosis: JointDiagnosis, summary: dict[str, Any], folder: Path) -> None:
    """Write every output of ``diagnosis``, its ``summary`` included, into ``folder``."""
    write_json(folder / "diagnosis.json", summary)
    error = summary["held_out_error"]
    header = (f"# The extended model from `fewear diagnose` on {summary['source']}: causes "
              f"{', '.join(summary['causes']) or 'none'}; held-out error "
              f"{error['baseline']:.3g} -> {error['extended']:.3g} m. Use it as `--config`.\n\n")
    (folder / "extended.toml").write_text(header + config_differences(diagnosis.extended_config))
    (folder / "report.md").write_text(report_markdown(summary))
    plot_joint_fits(diagnosis, folder / "joint_fits.png")


def _resolution_lines(resolution: dict) -> list[str]:
    """The resolution as a sentence and a table of the wear-step levels measured."""
    scatter = resolution["instrument_scatter_m"]
    chosen = resolution["wear_step"]
    keys = list(chosen)
    rows = ["| " + " | ".join(f"{level['blocks'][key]:g}" for key in keys)
            + " | " + ("one run" if level["spread_rms_m"] is None
                       else f"{level['spread_rms_m']:.2g}") + " | "
            + ("-" if level["change_from_coarser_rms_m"] is None
               else f"{level['change_from_coarser_rms_m']:.2g}"
               + (" at most" if level["spread_rms_m"] is None else ""))
            + f" | {'**chosen**' if level['blocks'] == chosen else ''} |"
            for level in resolution["wear_step_levels"]]
    return [("Resolution: the instrument's scatter "
             + (f"{scatter:.2g} m" if scatter is not None else "(no profiles to estimate it)")
             + "; the believed model's wear steps halved until its runs whose crank starts up "
             f"to {max(MEMBER_START_OFFSETS_DEG):g} deg later part, and the next halving moves "
             "their mean, by at most the scatter (RMS at the measured cycle counts)"
             + ("" if resolution["resolved"] else
                "; the runs part by more than the halvings left could bring within the scatter "
                "even if each halved it, so the ladder stopped there"
                if resolution["out_of_reach"] else
                "; not met within [joint_diagnose] max_wear_step_halvings, the finest allowed "
                "is taken")
             + "; twice the crank cycles recorded per block move the chosen model's bore by "
             f"{resolution['doubled_recorded_cycles_rms_m']:.2g} m. Causes that move the bore "
             "less than these cannot be told from the model's own noise."), "",
            f"| {' | '.join(keys)} | runs apart (m) | moved from the coarser (m) | |",
            "|" + "---|" * (len(keys) + 3), *rows]


def report_markdown(s: dict) -> str:
    lines = [f"# Joint wear diagnosis: {s['source']}", "",
             f"**Cause: {s['cause']}** ({s['cause_meaning']}).", "",
             *[f"- {e['cause']} adds a held-out gain of {e['gain']:.0%} to "
               f"{e['against']}" for e in s["cause_gains"][1:]], "",
             f"Held-out error (cycles {s['holdout']['held_out_cycles']}): believed model "
             f"{s['held_out_error']['baseline']:.3g} m, extended "
             f"{s['held_out_error']['extended']:.3g} m (gain {s['gain']:.0%}). "
             f"Criterion: {s['criterion']}.", "",
             *_resolution_lines(s["resolution"]), "",
             "| cause | against | p | held-out RMS (m) | gain | dAICc | accepted |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {_cause_label(e)} | {e['against']} | {e['p_value']:.2g} | "
              f"{e['held_out_rms_m']:.3g} "
              f"| {e['gain']:.0%} | {e['aicc_improvement']:.1f} | {e['accepted']} |"
              for e in s["candidates"]]
    b, x = s["prediction"]["baseline"], s["prediction"]["extended"]
    lines += ["", f"Maximum depth at {b['cycles']:,} cycles: measured "
              f"{b['measured_max_depth_m']:.3g} m, believed model {b['predicted_max_depth_m']:.3g}"
              f" m, extended {x['predicted_max_depth_m']:.3g} m.", "",
              *[f"**Unexplained:** {sentence}." for sentence in s["unexplained"]], "",
              "## Where the believed model misses", "",
              *s["residual_structure"]["sentences"], "", "![fits](joint_fits.png)", ""]
    return "\n".join(lines)


def _cause_label(entry: dict) -> str:
    """A candidate's name, with its form where it has several (running-in)."""
    return f"{entry['cause']} ({entry['form']})" if entry["form"] else entry["cause"]
