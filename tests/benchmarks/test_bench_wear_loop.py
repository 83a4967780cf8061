"""Benchmarks of the wear loop (print their figures; `make bench`).

1. Convergence of the worn profile and the maximum depth of the rigid rod after a fixed number of
   cycles in the load steps per cycle n, the recorded cycles per block and the adaptive block
   bound f (hence A_j), each against the finest setting of its sweep (the others at default).
2. Wall time of `fewear run` by stage for both rods over a given number of cycles
   (FEWEAR_BENCH_CYCLES, default 20,000; the paper's 400,000 takes the time printed times
   about 400,000 / that, the blocks growing as the bore conforms).
"""

import json
import os

import numpy as np
import pytest

from fewear.cli import main

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_CYCLES", "20000"))


def run_case(tmp_path, name, rods='["rigid"]', **loop):
    lines = ["[wear_loop]", f"rod_models = {rods}", f"total_cycles = {CYCLES}"]
    lines += [f"{key} = {value}" for key, value in loop.items()]
    config = tmp_path / f"{name}.toml"
    config.write_text("\n".join(lines) + "\n")
    assert main(["run", "--config", str(config), "--out", str(tmp_path / name)]) == 0
    summary = json.loads((tmp_path / name / "summary.json").read_text())
    profile = np.genfromtxt(tmp_path / name / "wear_profile.csv", delimiter=",", names=True,
                            dtype=None, encoding=None)
    last = profile[profile["cycles"] == CYCLES]
    return summary, last["wear_depth_m"]


SWEEPS = {
    "load_steps_per_cycle": [100, 200, 400],
    "recorded_cycles_per_block": [1, 2, 4],
    "max_depth_increment_fraction": [0.5, 0.25, 0.125],
}


@pytest.mark.parametrize("key", list(SWEEPS))
def test_convergence(tmp_path, key):
    results = {value: run_case(tmp_path, f"{key}_{value}", **{key: value})
               for value in SWEEPS[key]}
    reference = results[SWEEPS[key][-1]]
    print(f"\nconvergence in {key} (rigid rod, {CYCLES:,} cycles; vs {SWEEPS[key][-1]}):")
    print(f"{key:>30s} {'blocks':>6s} {'max depth m':>12s} {'max err':>9s} {'profile L2 err':>15s}")
    for value, (summary, depth) in results.items():
        case = summary["cases"]["rigid"]
        peak_error = abs(depth.max() - reference[1].max()) / reference[1].max()
        profile_error = np.linalg.norm(depth - reference[1]) / np.linalg.norm(reference[1])
        print(f"{value:>30} {case['blocks']:>6d} {depth.max():>12.4e} {peak_error:>9.2%} "
              f"{profile_error:>15.2%}")


def test_wall_time_by_stage(tmp_path):
    summary, _ = run_case(tmp_path, "both", rods='["rigid", "flexible"]')
    print(f"\nfewear run, both rods, {CYCLES:,} cycles (default config otherwise):")
    total = 0.0
    for rod, case in summary["cases"].items():
        stages = case["stage_wall_time_s"]
        total += case["wall_time_s"]
        print(f"  {rod:8s} {case['blocks']:4d} blocks, {case['wall_time_s']:7.1f} s: "
              + ", ".join(f"{stage} {seconds:.1f} s" for stage, seconds in stages.items())
              + f"; max depth {case['max_wear_depth_m']:.3e} m")
    print(f"  total {total:.1f} s")
