"""Wall time of an ensemble (issue 56's goal: 3 members of the default run in at most 2 minutes
with `--jobs 2`), and the paper's result as the members' mean and spread (prints its figures;
`make bench`).

`fewear run --members 3 --jobs 2` on the default config (both rods) over FEWEAR_BENCH_CYCLES
cycles (default: the paper's 400,000), the 6 members in 2 worker processes.
"""

import json
import os
import time

import numpy as np
import pytest

from fewear.cli import main

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_CYCLES", "400000"))
MEMBERS, JOBS, GOAL_S = 3, 2, 120.0


def test_ensemble_of_the_default_run(tmp_path):
    config = tmp_path / "ensemble.toml"
    config.write_text(f"[wear_loop]\ntotal_cycles = {CYCLES}\n")
    out = tmp_path / "out"
    start = time.perf_counter()
    assert main(["run", "--config", str(config), "--out", str(out), "--members", str(MEMBERS),
                 "--jobs", str(JOBS)]) == 0
    wall_s = time.perf_counter() - start
    ensemble = json.loads((out / "summary.json").read_text())["ensemble"]["cases"]
    print(f"\nfewear run --members {MEMBERS} --jobs {JOBS}, both rods, {CYCLES:,} cycles: "
          f"{wall_s:.1f} s (goal {GOAL_S:.0f} s)")
    depth = {}
    for rod, case in ensemble.items():
        joint = case["joints"]["rod_slider"]
        depth[rod] = np.array([member["max_wear_depth_m"] for member in joint["members"]])
        peak, volume = joint["max_wear_depth_m"], joint["worn_volume_m3"]
        print(f"  {rod:8s} max depth {1e6 * peak['mean']:.2f} +- {1e6 * peak['sd']:.2f} um "
              f"(sd/mean {100 * peak['sd'] / peak['mean']:.1f} %, range "
              f"{1e6 * peak['min']:.2f} to {1e6 * peak['max']:.2f}); worn volume "
              f"{1e9 * volume['mean']:.3f} +- {1e9 * volume['sd']:.3f} mm^3; members' wall "
              "times " + ", ".join(f"{member['wall_time_s']:.0f} s"
                                   for member in joint["members"]))
    if {"rigid", "flexible"} <= set(depth):
        ratio = depth["rigid"] / depth["flexible"]
        print(f"  rigid/flexible member by member: {', '.join(f'{r:.3f}' for r in ratio)} "
              f"(mean {ratio.mean():.3f} +- {ratio.std(ddof=1):.3f})")
