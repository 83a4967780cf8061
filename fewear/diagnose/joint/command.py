"""``fewear diagnose PROFILES.csv [MAX_WEAR.csv ...] --config MODEL.toml [--out DIR]`` on wear
measured on the joint: the believed model's misses, the cause, the extended config and its gain
(:mod:`fewear.diagnose.joint.diagnose`). Writes DIR/diagnosis.json, DIR/report.md,
DIR/joint_fits.png and DIR/extended.toml (the config lines that differ from the default), all or
nothing.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from fewear.diagnose.joint.diagnose import diagnose_joint
from fewear.diagnose.joint.measured import read_joint_measurements
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.io.config import default_config, load_config
from fewear.io.output import staged_output, write_json
from fewear.wear.coefficient import wear_section_toml


def main(args) -> int:
    from fewear.loop.settings import run_sections

    config = load_config(args.config, [*run_sections(), "joint_diagnose"])
    settings = JointDiagnoseSettings.from_config(config.pop("joint_diagnose"))
    data = read_joint_measurements(args.measured)
    print(f"fewear diagnose: {believed_model(args.config, config)}", file=sys.stderr, flush=True)
    diagnosis = diagnose_joint(data, config, settings)
    with staged_output(args.out) as stage:
        write_joint_outputs(diagnosis, stage)
    s = diagnosis.summary
    print(f"fewear diagnose: causes {', '.join(s['causes']) or 'none'}, held-out error "
          f"{s['held_out_error']['baseline']:.3g} m -> {s['held_out_error']['extended']:.3g} m "
          f"(gain {s['gain']:.0%}); outputs in {args.out}")
    for group in s["confounded"]:
        print(f"fewear diagnose: also accepted (confounded): {group['cause']}")
    for sentence in s["unexplained"]:
        print(f"fewear diagnose: unexplained: {sentence}")
    return 0


def believed_model(path, config: dict) -> str:
    """Which model the diagnosis takes as believed, its size, and (without ``--config``) that the
    embedded default is the full paper case, minutes per run."""
    from fewear.io.limits import mesh_size

    rod = config["wear_loop"]["rod_models"][0]
    cells = mesh_size(config)[1]
    size = (f"{rod} rod, a mesh of about {cells:,} quadrilaterals, "
            f"{config['wear_loop']['load_steps_per_cycle']} load steps per cycle")
    if path is not None:
        return f"believed model: {path} ({size}); forward runs follow, each reports its progress"
    return (f"no --config: the believed model is the embedded default config, the paper's case "
            f"({size}): each forward run of it takes minutes, and a diagnosis makes dozens; "
            "progress follows. For a quicker diagnosis give your model as --config "
            "(`fewear config` prints the default to start from; a coarser [mesh] and fewer "
            "[wear_loop] load_steps_per_cycle run much faster)")


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


def plot_joint_fits(diagnosis, path: Path) -> None:
    """Measured profiles against the believed and the extended model, one panel per count."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    obs = diagnosis.observations
    counts = np.unique(obs.cycles[obs.is_profile])
    fig, axes = plt.subplots(1, max(len(counts), 1), figsize=(3.2 * max(len(counts), 1), 3.2),
                             sharey=True, squeeze=False)
    for ax, cycles in zip(axes[0], counts):
        at = (obs.cycles == cycles) & obs.is_profile
        angle = np.degrees(obs.angle_rad[at])
        ax.plot(angle, obs.depth_m[at] * 1e6, ".", ms=3, label="measured")
        ax.plot(angle, diagnosis.baseline_depth_m[at] * 1e6, "-", label="believed model")
        ax.plot(angle, diagnosis.extended_depth_m[at] * 1e6, "--", label="extended model")
        held = "held out" if not obs.train[at][0] else "training"
        ax.set_title(f"{int(cycles):,} cycles ({held})", fontsize=9)
        ax.set_xlabel("angle (deg, instrument)")
    axes[0][0].set_ylabel("wear depth (um)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
