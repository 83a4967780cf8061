"""Outputs of a joint diagnosis: ``diagnosis.json`` (the summary), ``report.md``,
``extended.toml`` (the config lines of the extended model that differ from the default, usable
as ``--config``) and the figure ``joint_fits.png``.
"""

from __future__ import annotations

from pathlib import Path

from fewear.diagnose.joint.figures import plot_joint_fits
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


def write_joint_outputs(diagnosis, folder: Path) -> None:
    """Write every output of ``diagnosis`` into ``folder``."""
    s = diagnosis.summary
    write_json(folder / "diagnosis.json", s)
    error = s["held_out_error"]
    header = (f"# The extended model from `fewear diagnose` on {s['source']}: causes "
              f"{', '.join(s['causes']) or 'none'}; held-out error {error['baseline']:.3g} -> "
              f"{error['extended']:.3g} m. Use it as `--config`.\n\n")
    (folder / "extended.toml").write_text(header + config_differences(diagnosis.extended_config))
    (folder / "report.md").write_text(report_markdown(s))
    plot_joint_fits(diagnosis, folder / "joint_fits.png")


def _resolution_line(resolution: dict) -> str:
    scatter = resolution["instrument_scatter_m"]
    return ("Resolution: the instrument's scatter "
            + (f"{scatter:.2g} m" if scatter is not None else "(no profiles to estimate it)")
            + "; halving the believed model's wear blocks moves its worn bore by "
            f"{resolution['halved_blocks_rms_m']:.2g} m RMS at the measured cycle counts (causes "
            "that move it less cannot be told from the block size).")


def report_markdown(s: dict) -> str:
    lines = [f"# Joint wear diagnosis: {s['source']}", "",
             f"**Cause: {s['cause']}** ({s['cause_meaning']}).", "",
             f"Held-out error (cycles {s['holdout']['held_out_cycles']}): believed model "
             f"{s['held_out_error']['baseline']:.3g} m, extended "
             f"{s['held_out_error']['extended']:.3g} m (gain {s['gain']:.0%}). "
             f"Criterion: {s['criterion']}.", "",
             _resolution_line(s["resolution"]), "",
             "| cause | against | p | held-out RMS (m) | gain | dAICc | accepted |",
             "|---|---|---|---|---|---|---|"]
    lines += [f"| {_cause_label(e)} | {e['against']} | {e['p_value']:.2g} | "
              f"{e['held_out_rms_m']:.3g} "
              f"| {e['held_out_gain']:.0%} | {e['aicc_improvement']:.1f} | {e['accepted']} |"
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
