# # Wear at the coupler-rocker clearance joint of a four-bar crank-rocker
#
# A four-bar linkage described by a mechanism file (`fewear/mechanisms/four_bar.toml`,
# docs/mechanisms.md): ground pivots O2 = (0, 0) and O4 = (0.30, 0) m, crank a = 0.10 m driven
# at 1200 rpm, coupler b = 0.25 m, rocker c = 0.25 m, each a steel bar 5 mm x 18 mm. Grashof's
# condition s + l = 0.40 m <= p + q = 0.50 m holds with the crank the shortest link: the crank
# turns fully, the rocker swings. The joint between coupler and rocker has the run config's
# radial clearance (pin 9.5 mm in a 10 mm bore, c = 0.5 mm); its **bushing sits on the rocker**,
# which turns, so the joint force, the pin's relative rotation and the worn profile are all taken
# in the rocker's frame (x axis from the ground pivot O4 to the joint B).
#
# First the dynamics of the unworn joint (rigid coupler and the coupler as an ANCF beam): the
# joint's peak force, the share of the cycle in contact, the impacts. Then `fewear run`: the
# bushing worn block by block (Archard, seed eq. 10), the worn bore fed back into the contact
# and the dynamics after every block, and where on the bushing the wear sits.
#
# The wear must sit where the pin slides under load: from the dynamics alone, the load-slip
# product F_n R_pin |omega_rel| dt of the unworn joint's cycles gathered by the direction of the
# pin's eccentricity in the rocker frame into 15-degree sectors; the fullest sector is printed
# beside the FE wear's deepest point. (Not the load-slip weighted mean direction: the load-slip
# is spread over two arcs of the bore, and their mean points between them, where nothing
# wears.)
#
# Environment: `FEWEAR_DEMO_TOTAL_CYCLES` (default 400,000, as the paper's slider-crank),
# `FEWEAR_DEMO_COARSE=1` (a 48-element bore and 40 load steps, for the test),
# `FEWEAR_DEMO_OUT` (the output folder). Depths in m, forces in N, angles in degrees.

# +
import json
import math
import os
from pathlib import Path

import numpy as np

import fewear
from fewear.mbd.history import loaded_sectors

OUT = Path(os.environ.get("FEWEAR_DEMO_OUT", "out/demos/four_bar_wear"))
TOTAL_CYCLES = int(os.environ.get("FEWEAR_DEMO_TOTAL_CYCLES", "400000"))
COARSE = os.environ.get("FEWEAR_DEMO_COARSE") == "1"
MECHANISM = "four_bar"
JOINT = "coupler_rocker"          # the clearance joint; its bushing is on the rocker
CASES = ("rigid", "flexible")     # the coupler rigid, or a 4-element ANCF beam
BORE_RADIUS_M = 0.010
PIN_RADIUS_M = 0.0095
CRANK_PERIOD_S = 60.0 / 1200.0
SETTLING_CYCLES = 2               # of the dynamics before the recorded ones
SECTOR_DEG = 15.0                 # the sectors of the bore the load-slip is gathered in
LOADED_SHARE = 0.8                # the fullest sectors holding this share of it: the loaded arc
RECORDED_CYCLES = 2 if COARSE else 5

OUT.mkdir(parents=True, exist_ok=True)


def config(**sections) -> dict:
    """The run config: the four-bar file, the demo's cycles (and the coarse mesh), ``sections``
    merged over it."""
    values = {"mechanism": {"file": MECHANISM, "settling_cycles": SETTLING_CYCLES},
              "wear_loop": {"total_cycles": TOTAL_CYCLES}}
    if COARSE:
        values["wear_loop"]["load_steps_per_cycle"] = 40
        values["mesh"] = {"bore_element_size_m": 2 * math.pi * BORE_RADIUS_M / 48 * (1 + 1e-9),
                          "radial_element_count": 4}
    for section, table in sections.items():
        values.setdefault(section, {}).update(table)
    return values
# -

# ## The dynamics of the unworn joint
#
# Per recorded crank cycle: the peak joint force |F| (on the pin, N), the share of the cycle in
# contact, the impacts, and the direction in the rocker frame where the pin slides under load.


# +
def mechanics(history) -> dict:
    by_sector, edges = history.load_slip_by_direction(PIN_RADIUS_M, SECTOR_DEG)
    fullest = int(np.argmax(by_sector))
    dt = np.diff(history.time_s, prepend=history.time_s[0])
    return {"peak_force_N": float(np.linalg.norm(history.reaction_force_N, axis=1).max()),
            "contact_share": float(dt[history.normal_force_N > 0.0].sum()
                                   / (RECORDED_CYCLES * CRANK_PERIOD_S)),
            "impacts_per_cycle": history.impacts / RECORDED_CYCLES,
            "load_slip_J_per_cycle": float(by_sector.sum() / RECORDED_CYCLES),
            "most_load_slip_angle_deg": float(0.5 * (edges[fullest] + edges[fullest + 1])),
            "loaded_sectors": loaded_sectors(by_sector, LOADED_SHARE)}


dynamics = {case: mechanics(fewear.dynamics(config(), rod=case, cycles=RECORDED_CYCLES)
                            .histories[JOINT]) for case in CASES}
for case, values in dynamics.items():
    print(f"{case:8s} coupler: peak joint force {values['peak_force_N']:.1f} N, in contact "
          f"{100 * values['contact_share']:.0f} % of the cycle, "
          f"{values['impacts_per_cycle']:.1f} impacts per cycle, the pin slides "
          f"most under load at {values['most_load_slip_angle_deg']:.0f} deg (rocker frame)")
# -

# ## The wear
#
# Both cases side by side (`fewear run`); the outputs in `OUT/run`: summary.json,
# wear_profile.csv and max_wear.csv (with a joint column), `<case>-coupler_rocker.xdmf`.

# +
result = fewear.run(config(), out=OUT / "run", overwrite=(OUT / "run").exists())
wear = {}
for case in CASES:
    figures = result.summary["cases"][case]["joints"][JOINT]
    state = result.wear[case][JOINT]
    deepest = int(np.argmax(state.depth_m))
    sector = (np.degrees(state.angle_rad) % 360.0 // SECTOR_DEG).astype(int)
    on_arc = np.isin(sector, dynamics[case]["loaded_sectors"])
    wear[case] = {"max_depth_m": figures["max_wear_depth_m"],
                  "loaded_arc_share": float(state.depth_m[on_arc].sum() / state.depth_m.sum()),
                  "max_depth_angle_deg": float(np.degrees(state.angle_rad[deepest]) % 360.0),
                  "worn_volume_m3": figures["worn_volume_m3"], "cycles": figures["cycles"],
                  "blocks": figures["blocks"], "wall_time_s": figures["wall_time_s"]}
    print(f"{case:8s} coupler, {figures['cycles']:,} cycles in {figures['blocks']} blocks: "
          f"worn {1e6 * figures['max_wear_depth_m']:.2f} um deep at "
          f"{wear[case]['max_depth_angle_deg']:.0f} deg in the rocker's frame (the most load-slip "
          f"at {dynamics[case]['most_load_slip_angle_deg']:.0f} deg), worn volume "
          f"{figures['worn_volume_m3']:.3e} m^3, {100 * wear[case]['loaded_arc_share']:.0f} % of "
          f"the worn depth on the loaded arc")

(OUT / "results.json").write_text(json.dumps(
    {"total_cycles": TOTAL_CYCLES, "dynamics": dynamics, "wear": wear,
     "run": str(OUT / "run")}, indent=2))
# -

# The figures: `OUT/run/wear_profiles.png` (the worn bore per block, in the rocker's frame) and
# `OUT/run/max_wear.png`; `fewear plot OUT/run --joint coupler_rocker` draws them again.
