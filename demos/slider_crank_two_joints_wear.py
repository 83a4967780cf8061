# # The paper's slider-crank with both the crank-rod and the rod-slider joint worn
#
# The seed paper's slider-crank (crank r = 0.1 m at 1200 rpm, rod l = 0.34 m, slider 0.5 kg;
# `demos/slider_crank_wear.py` wears its one clearance joint, rod-slider) with a second
# clearance joint between crank and rod (`fewear/mechanisms/slider_crank_two_joints.toml`,
# docs/mechanisms.md): `crank_rod` has its bushing on the crank, which turns, and the rod's end
# as its pin; `rod_slider` has its bushing on the slider, which does not turn. Both take the run
# config's bushing and pin (c = 0.5 mm). The rod is rigid or an ANCF beam (the run's cases);
# every wear block runs the one dynamics with both worn clearances fed back.
#
# Where should each bushing wear? The slider's, as in the paper's one-joint case, left and right
# of the bore (the slide axis, 0 and 180 degrees), where the rod pushes and pulls the slider. The
# crank's where the pin slides under load: from the dynamics alone, the load-slip product
# F_n R_pin |omega_rel| dt of the unworn joints gathered by the direction of the pin's
# eccentricity in the bushing body's frame into 15-degree sectors; the fullest sector is printed
# beside the FE wear's deepest point, and the share of the worn depth that lies on the loaded arc
# (the fullest sectors that hold 80 % of the load-slip).
#
# **Why 20,000 cycles.** The crank's joint turns a full revolution in its bushing every cycle
# (a sliding distance of about 60 mm), and with the paper's wear coefficients it wears several
# times faster than the other joint: well before the paper's 400,000 cycles its bushing would
# be worn through (`[wear_loop] max_wall_fraction`, half the 5 mm wall) and the run stop there.
#
# Environment: `FEWEAR_DEMO_TOTAL_CYCLES` (default 20,000), `FEWEAR_DEMO_COARSE=1`
# (a 48-element bore and 40 load steps, for the test), `FEWEAR_DEMO_OUT` (the output folder).
# Depths in m, forces in N, angles in degrees.

# +
import json
import math
import os
from pathlib import Path

import numpy as np

import fewear
from fewear.mbd.history import loaded_sectors

OUT = Path(os.environ.get("FEWEAR_DEMO_OUT", "out/demos/slider_crank_two_joints_wear"))
TOTAL_CYCLES = int(os.environ.get("FEWEAR_DEMO_TOTAL_CYCLES", "20000"))
COARSE = os.environ.get("FEWEAR_DEMO_COARSE") == "1"
MECHANISM = "slider_crank_two_joints"
JOINTS = {"crank_rod": "crank", "rod_slider": "slider"}  # joint -> its bushing's body
CASES = ("rigid", "flexible")
BORE_RADIUS_M = 0.010
PIN_RADIUS_M = 0.0095
SETTLING_CYCLES = 2
RECORDED_CYCLES = 2 if COARSE else 5
SECTOR_DEG = 15.0     # the sectors of the bore the load-slip is gathered in
LOADED_SHARE = 0.8    # the fullest sectors holding this share of it: the loaded arc
SLIDE_AXIS_HALF_WIDTH_DEG = 45.0

OUT.mkdir(parents=True, exist_ok=True)


def config() -> dict:
    values = {"mechanism": {"file": MECHANISM, "settling_cycles": SETTLING_CYCLES},
              "wear_loop": {"total_cycles": TOTAL_CYCLES}}
    if COARSE:
        values["wear_loop"]["load_steps_per_cycle"] = 40
        values["mesh"] = {"bore_element_size_m": 2 * math.pi * BORE_RADIUS_M / 48 * (1 + 1e-9),
                          "radial_element_count": 4}
    return values
# -

# ## The unworn joints' dynamics


# +
def mechanics(history) -> dict:
    """The peak joint force, and the centre of the sector of the bore (bushing frame) where the
    pin slides most under load."""
    by_sector, edges = history.load_slip_by_direction(PIN_RADIUS_M, SECTOR_DEG)
    fullest = int(np.argmax(by_sector))
    return {"peak_force_N": float(np.linalg.norm(history.reaction_force_N, axis=1).max()),
            "impacts_per_cycle": history.impacts / RECORDED_CYCLES,
            "most_load_slip_angle_deg": float(0.5 * (edges[fullest] + edges[fullest + 1])),
            "loaded_sectors": loaded_sectors(by_sector, LOADED_SHARE)}


dynamics = {}
for case in CASES:
    histories = fewear.dynamics(config(), rod=case, cycles=RECORDED_CYCLES).histories
    dynamics[case] = {joint: mechanics(histories[joint]) for joint in JOINTS}
    for joint, values in dynamics[case].items():
        print(f"{case:8s} rod, {joint:10s}: peak force {values['peak_force_N']:7.1f} N, "
              f"{values['impacts_per_cycle']:.1f} impacts per cycle, most load-slip at "
              f"{values['most_load_slip_angle_deg']:.0f} deg ({JOINTS[joint]}'s frame)")
# -

# ## The wear of both joints
#
# `fewear run`, both rods side by side; the outputs in `OUT/run` (each joint named: summary.json
# `cases.<case>.joints.<joint>`, wear_profile.csv with a joint column, `<case>-<joint>.xdmf`).

# +
result = fewear.run(config(), out=OUT / "run", overwrite=(OUT / "run").exists())
wear = {}
for case in CASES:
    wear[case] = {}
    for joint, body in JOINTS.items():
        figures = result.summary["cases"][case]["joints"][joint]
        state = result.wear[case][joint]
        angle_deg = np.degrees(state.angle_rad) % 360.0
        from_axis = np.abs((angle_deg + 90.0) % 180.0 - 90.0)
        on_arc = np.isin((angle_deg // SECTOR_DEG).astype(int),
                         dynamics[case][joint]["loaded_sectors"])
        wear[case][joint] = {
            "max_depth_m": figures["max_wear_depth_m"],
            "max_depth_angle_deg": float(angle_deg[np.argmax(state.depth_m)]),
            "worn_volume_m3": figures["worn_volume_m3"], "cycles": figures["cycles"],
            "loaded_arc_share": float(state.depth_m[on_arc].sum() / state.depth_m.sum()),
            "slide_axis_share": float(state.depth_m[from_axis < SLIDE_AXIS_HALF_WIDTH_DEG].sum()
                                      / state.depth_m.sum())}
        w = wear[case][joint]
        print(f"{case:8s} rod, {joint:10s}, {figures['cycles']:,} cycles: worn "
              f"{1e6 * w['max_depth_m']:.2f} um deep at {w['max_depth_angle_deg']:.0f} deg in "
              f"the {body}'s frame (most load-slip at "
              f"{dynamics[case][joint]['most_load_slip_angle_deg']:.0f} deg), "
              f"{w['worn_volume_m3']:.3e} m^3, {100 * w['loaded_arc_share']:.0f} % of the depth on "
              f"the loaded arc, {100 * w['slide_axis_share']:.0f} % within "
              f"{SLIDE_AXIS_HALF_WIDTH_DEG:.0f} deg of the x axis")

(OUT / "results.json").write_text(json.dumps(
    {"total_cycles": TOTAL_CYCLES, "dynamics": dynamics, "wear": wear, "run": str(OUT / "run")},
    indent=2))
# -

# The figures: `OUT/run/wear_profiles.png` and `OUT/run/max_wear.png` (both joints);
# `fewear plot OUT/run --joint crank_rod` draws one joint's.
