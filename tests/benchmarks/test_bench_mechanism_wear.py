"""Wall time of the wear loop on a mechanism file (prints its figures; `make bench`): the
four-bar with two worn clearance joints (``four_bar_two_joints``), both cases, over
FEWEAR_BENCH_CYCLES cycles (default 400,000, the issue's goal: under 3 minutes on a 2-core
machine), beside the paper's default slider-crank run (the embedded config, about 1 min 45 s
before mechanism files) measured in the same run, per case, joint and stage."""

import json
import os
import time

import pytest

from fewear.cli import main

pytestmark = pytest.mark.benchmark
CYCLES = int(os.environ.get("FEWEAR_BENCH_CYCLES", "400000"))
RUNS = {
    "four-bar, two worn joints": '[mechanism]\nfile = "four_bar_two_joints"\n',
    "paper's slider-crank": "",
}


def timed_run(tmp_path, name: str, mechanism: str) -> tuple[dict, float]:
    """The summary of `fewear run` over CYCLES cycles (defaults otherwise), its wall time (s)."""
    config = tmp_path / f"{name}.toml"
    config.write_text(f"{mechanism}[wear_loop]\ntotal_cycles = {CYCLES}\n")
    start = time.perf_counter()
    assert main(["run", "--config", str(config), "--out", str(tmp_path / name)]) == 0
    return json.loads((tmp_path / name / "summary.json").read_text()), time.perf_counter() - start


def test_wall_time_of_the_four_bar_beside_the_papers_run(tmp_path):
    load, lines = os.getloadavg()[0], []
    for index, (label, mechanism) in enumerate(RUNS.items()):
        summary, wall = timed_run(tmp_path, f"run{index}", mechanism)
        lines.append(f"  {label}: {wall:.1f} s wall ({wall / 60:.2f} min)")
        for case, joints in summary["cases"].items():
            for joint, figures in joints["joints"].items():
                stages = figures["stage_wall_time_s"]
                lines.append(
                    f"    {case:8s} {joint:15s} {figures['blocks']:4d} blocks, "
                    f"{figures['wall_time_s']:6.1f} s: "
                    + ", ".join(f"{stage} {seconds:.1f} s" for stage, seconds in stages.items())
                    + f"; max depth {figures['max_wear_depth_m']:.3e} m")
    print(f"\nfewear run, both cases, {CYCLES:,} cycles, default settings otherwise "
          f"(load average before: {load:.1f}):\n" + "\n".join(lines))
