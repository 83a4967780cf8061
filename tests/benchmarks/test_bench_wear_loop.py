"""Wall time of the wear loop (prints its figures; `make bench`; the convergence of the default
setting is in test_bench_convergence.py).

`fewear run` by stage for both rods over FEWEAR_BENCH_CYCLES cycles (default 20,000; the paper's:
400000), the rods one after the other in one process (`--jobs 1`) and side by side
(`--jobs 2`), measured in the same run: the parallel scaling from 1 to 2 processes.
"""

import json
import os
import time

import pytest

from fewear.cli import main

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_CYCLES", "20000"))


def run_both_rods(tmp_path, jobs: int) -> dict:
    """The summary of `fewear run` with both rods over CYCLES cycles in ``jobs`` processes."""
    config = tmp_path / f"both_{jobs}.toml"
    config.write_text(f"[wear_loop]\ntotal_cycles = {CYCLES}\n")
    out = tmp_path / f"both_{jobs}"
    assert main(["run", "--config", str(config), "--out", str(out), "--jobs", str(jobs)]) == 0
    return json.loads((out / "summary.json").read_text())


def test_wall_time_by_stage(tmp_path):
    walls = {}
    for jobs in (1, 2):
        start = time.perf_counter()
        summary = run_both_rods(tmp_path, jobs)
        walls[jobs] = time.perf_counter() - start
    print(f"\nfewear run, both rods, {CYCLES:,} cycles (default config otherwise):")
    for rod, joints in summary["cases"].items():
        case = joints["joints"]["rod_slider"]
        stages = case["stage_wall_time_s"]
        print(f"  {rod:8s} {case['blocks']:4d} blocks, {case['wall_time_s']:7.1f} s: "
              + ", ".join(f"{stage} {seconds:.1f} s" for stage, seconds in stages.items())
              + f"; max depth {case['max_wear_depth_m']:.3e} m")
    print(f"  wall time: one process {walls[1]:.1f} s, two processes {walls[2]:.1f} s "
          f"(x{walls[1] / walls[2]:.2f})")
