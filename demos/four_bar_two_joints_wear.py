# # Two worn clearance joints in a four-bar, and how much each changes the other's wear
#
# The crank-rocker of `demos/four_bar_wear.py` (`fewear/mechanisms/four_bar_two_joints.toml`,
# docs/mechanisms.md) with two clearance joints worn together: `crank_coupler` (the bushing on
# the crank, the pin on the coupler) and `coupler_rocker` (the bushing on the rocker). Both take
# the run config's bushing and pin (c = 0.5 mm). Every wear block runs the one dynamics with
# both worn clearances, then each joint's own FE contact, wear and re-mesh; each joint's profile
# lives in its bushing body's frame (the crank's, the rocker's).
#
# **The coupling.** Does a second worn joint change the first's wear? Each joint's wear in the
# two-joint mechanism is set against the same mechanism with the *other* joint ideal:
# `four_bar.toml` for `coupler_rocker` alone, and the two-joint file with `coupler_rocker` made
# ideal for `crank_coupler` alone, at the same cycles; the ratios two-joint/one-joint of the
# maximum depth and of the worn volume, per joint. The runs are nearly chaotic (a clearance
# joint's orbit is), so one run is one sample: each configuration is run `MEMBERS` times with
# the crank starting at 0, 1, 2, ... degrees (the steady cycle cannot depend on it), the ratio
# taken member by member, and the coupling read against the members' spread.
#
# **Why 20,000 cycles.** The crank's joint turns a full revolution in its bushing every cycle
# (a sliding distance of about 60 mm), and with the paper's wear coefficients it wears several
# times faster than the other joint: well before the paper's 400,000 cycles its bushing would
# be worn through (`[wear_loop] max_wall_fraction`, half the 5 mm wall) and the run stop there.
#
# Environment: `FEWEAR_DEMO_TOTAL_CYCLES` (default 20,000), `FEWEAR_DEMO_MEMBERS` (default 3),
# `FEWEAR_DEMO_COARSE=1` (a 48-element bore and 40 load steps, for the test),
# `FEWEAR_DEMO_OUT` (the output folder). Runs already complete in it with the same config are
# read, not repeated. Depths in m, volumes in m^3, angles in degrees.

# +
import json
import math
import os
from pathlib import Path

import numpy as np

import fewear
from fewear.io.mechanism import EXAMPLES_DIR

OUT = Path(os.environ.get("FEWEAR_DEMO_OUT", "out/demos/four_bar_two_joints_wear"))
TOTAL_CYCLES = int(os.environ.get("FEWEAR_DEMO_TOTAL_CYCLES", "20000"))
MEMBERS = int(os.environ.get("FEWEAR_DEMO_MEMBERS", "3"))
COARSE = os.environ.get("FEWEAR_DEMO_COARSE") == "1"
JOINTS = ("crank_coupler", "coupler_rocker")
CASES = ("rigid", "flexible")       # the coupler rigid, or an ANCF beam
COUPLING_CASE = "rigid"             # the case of the coupling study
BORE_RADIUS_M = 0.010
DRIVER_START = "angle_deg = 0.0                  # at t = 0"  # the crank's angle at t = 0
RECORDED_CYCLES = 2                 # of the dynamics, after two settling ones

OUT.mkdir(parents=True, exist_ok=True)
# -

# ## The mechanisms
#
# The shipped files, edited: the crank's start angle, and for `crank_coupler` alone the
# `coupler_rocker` joint without its clearance.


# +
def edited(text: str, old: str, new: str) -> str:
    """``text`` with its one ``old`` replaced by ``new``."""
    if text.count(old) != 1:
        raise ValueError(f"{old!r} is not in the mechanism file exactly once")
    return text.replace(old, new)


TWO_JOINTS = (EXAMPLES_DIR / "four_bar_two_joints.toml").read_text()
MECHANISMS = {
    "two joints": TWO_JOINTS,
    "coupler_rocker alone": (EXAMPLES_DIR / "four_bar.toml").read_text(),
    "crank_coupler alone": edited(
        TWO_JOINTS, 'bushing_point = "rocker.B"\nclearance = true', 'bushing_point = "rocker.B"'),
}
WORN = {"two joints": JOINTS, "coupler_rocker alone": ("coupler_rocker",),
        "crank_coupler alone": ("crank_coupler",)}


def config_text(mechanism_file: Path, cases: tuple[str, ...]) -> str:
    sections = {"mechanism": {"file": str(mechanism_file)},
                "wear_loop": {"total_cycles": TOTAL_CYCLES, "rod_models": list(cases)}}
    if COARSE:
        sections["wear_loop"]["load_steps_per_cycle"] = 40
        sections["mesh"] = {"bore_element_size_m": 2 * math.pi * BORE_RADIUS_M / 48 * (1 + 1e-9),
                            "radial_element_count": 4}
    return "".join(f"[{section}]\n"
                   + "".join(f"{key} = {json.dumps(value)}\n" for key, value in table.items())
                   for section, table in sections.items())


def run(label: str, member: int, cases: tuple[str, ...]) -> dict:
    """summary.json of the run of ``MECHANISMS[label]`` with the crank starting at ``member``
    degrees: read when a run of the same config is complete in its folder, else run."""
    name = f"{label.replace(' ', '_')}-member{member}"
    mechanism = OUT / f"{name}-mechanism.toml"
    mechanism.write_text(edited(MECHANISMS[label], DRIVER_START,
                                f"angle_deg = {float(member)!r}"))
    config, folder = OUT / f"{name}.toml", OUT / name
    text = config_text(mechanism, cases)
    if not (config.exists() and config.read_text() == text
            and (folder / "summary.json").exists()):
        config.write_text(text)
        fewear.run(config, out=folder, overwrite=folder.exists())
    return json.loads((folder / "summary.json").read_text())
# -

# ## Both joints worn, both cases
#
# The peak force of each unworn joint (two settling crank cycles, two recorded), then the wear.

# +
peak_force_N = {}
for case in CASES:
    histories = fewear.dynamics({"mechanism": {"file": "four_bar_two_joints",
                                               "settling_cycles": 2}},
                                rod=case, cycles=RECORDED_CYCLES).histories
    peak_force_N[case] = {joint: float(np.linalg.norm(histories[joint].reaction_force_N,
                                                      axis=1).max()) for joint in JOINTS}

both = run("two joints", 0, CASES)
frame = {"crank_coupler": "crank", "coupler_rocker": "rocker"}
for case in CASES:
    for joint in JOINTS:
        figures = both["cases"][case]["joints"][joint]
        print(f"{case:8s} coupler, {joint:14s}: peak force {peak_force_N[case][joint]:7.1f} N "
              f"unworn; after {figures['cycles']:,} cycles worn "
              f"{1e6 * figures['max_wear_depth_m']:.2f} um deep at "
              f"{figures['max_wear_angle_deg']:.0f} deg in the {frame[joint]}'s frame, "
              f"{figures['worn_volume_m3']:.3e} m^3")
# -

# ## The coupling, with the members' spread
#
# Per joint and member: two-joint over one-joint, of the maximum depth and of the worn volume;
# the members' mean and sample standard deviation. The one-joint runs' own spread (sd over mean)
# is the noise a coupling must exceed to be told apart from chance.


# +
def figures(summary: dict, joint: str) -> tuple[float, float]:
    joint_figures = summary["cases"][COUPLING_CASE]["joints"][joint]
    return joint_figures["max_wear_depth_m"], joint_figures["worn_volume_m3"]


def mean_sd(values) -> dict:
    values = np.asarray(values, dtype=float)
    return {"mean": float(values.mean()),
            "sd": float(values.std(ddof=1)) if values.size > 1 else 0.0}


summaries = {label: [both if (label == "two joints" and member == 0)
                     else run(label, member, (COUPLING_CASE,)) for member in range(MEMBERS)]
             for label in MECHANISMS}
coupling = {}
for joint in JOINTS:
    together = np.array([figures(s, joint) for s in summaries["two joints"]])
    alone = np.array([figures(s, joint) for s in summaries[f"{joint} alone"]])
    ratio = together / alone
    coupling[joint] = {
        "two_joint_max_depth_m": mean_sd(together[:, 0]),
        "one_joint_max_depth_m": mean_sd(alone[:, 0]),
        "two_joint_worn_volume_m3": mean_sd(together[:, 1]),
        "one_joint_worn_volume_m3": mean_sd(alone[:, 1]),
        "max_depth_ratio": mean_sd(ratio[:, 0]),
        "worn_volume_ratio": mean_sd(ratio[:, 1]),
        "one_joint_relative_sd": {"max_depth": mean_sd(alone[:, 0])["sd"] / alone[:, 0].mean(),
                                  "worn_volume": mean_sd(alone[:, 1])["sd"] / alone[:, 1].mean()},
    }
    c = coupling[joint]
    print(f"\n{joint} ({COUPLING_CASE} coupler, {TOTAL_CYCLES:,} cycles, {MEMBERS} members):")
    for what, unit, scale in (("max_depth", "um", 1e6), ("worn_volume", "1e-9 m^3", 1e9)):
        key = "m" if what == "max_depth" else "m3"
        two, one = c[f"two_joint_{what}_{key}"], c[f"one_joint_{what}_{key}"]
        print(f"  {what:11s}: two joints {scale * two['mean']:8.3f} +- {scale * two['sd']:.3f}, "
              f"alone {scale * one['mean']:8.3f} +- {scale * one['sd']:.3f} {unit}; ratio "
              f"{c[f'{what}_ratio']['mean']:.3f} +- {c[f'{what}_ratio']['sd']:.3f} (the one-joint "
              f"members' spread {100 * c['one_joint_relative_sd'][what]:.1f} %)")

(OUT / "results.json").write_text(json.dumps(
    {"total_cycles": TOTAL_CYCLES, "members": MEMBERS, "coupling_case": COUPLING_CASE,
     "peak_force_N": peak_force_N, "two_joints": both["cases"], "coupling": coupling,
     "runs": {label: [str(OUT / f"{label.replace(' ', '_')}-member{m}") for m in range(MEMBERS)]
              for label in MECHANISMS}}, indent=2))
# -

# The figures of the two-joint run are in `OUT/two_joints-member0`: `wear_profiles.png`,
# `max_wear.png` (both joints), `rigid-crank_coupler.xdmf`, `rigid-coupler_rocker.xdmf`, ...;
# `fewear plot OUT/two_joints-member0 --joint crank_coupler` draws one joint's.
