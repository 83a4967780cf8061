"""The compiled dynamics against the NumPy code before it (prints, never asserts times).

Each case (rigid and flexible rod; clearance and ideal joint) runs one settling and two recorded
crank cycles of the default config in a fresh process, alternately with this tree's fewear.mbd
and with the tree of ``PRE_NUMBA`` (``git archive`` into a temporary folder, so this needs the
repository's history), ROUNDS times; each process first runs a cycle that is not counted (numba
compiles or loads its cache there). Printed per case: the median seconds per cycle of each, their
ratio, the steps per cycle and microseconds per step. The clearance joint is chaotic (an impact
more or less changes the steps), so its ratio per step is the steadier figure; the ideal joint's
steps are the same in both.
"""

import json
import os
import statistics
import subprocess
import sys
from pathlib import Path

import pytest

pytestmark = pytest.mark.benchmark
PRE_NUMBA = "58b9d27"  # the last commit before fewear.mbd was compiled with numba
ROUNDS = int(os.environ.get("FEWEAR_BENCH_ROUNDS", "3"))
CASES = (("rigid", "clearance"), ("flexible", "clearance"), ("rigid", "ideal"),
         ("flexible", "ideal"))
REPOSITORY = Path(__file__).resolve().parents[2]
CYCLE = """
import json, sys
from fewear.mbd.slider_crank import simulate_slider_crank
rod, joint = sys.argv[1], sys.argv[2]
simulate_slider_crank(rod=rod, joint=joint, cycles=1, settling_cycles=0)  # not counted
history, summary = simulate_slider_crank(rod=rod, joint=joint, cycles=2, settling_cycles=1)
print(json.dumps({"cycle_s": summary.wall_time_per_cycle_s,
                  "steps_per_cycle": summary.steps / summary.cycles,
                  "step_us": 1e6 * summary.wall_time_per_cycle_s * summary.cycles / summary.steps}))
"""


def _tree_of(commit: str, folder: Path) -> Path:
    archive = subprocess.run(["git", "-C", str(REPOSITORY), "archive", commit, "fewear"],
                             capture_output=True, check=False)
    if archive.returncode != 0:
        pytest.skip(f"no git history with {commit}: {archive.stderr.decode().strip()}")
    subprocess.run(["tar", "-x", "-C", str(folder)], input=archive.stdout, check=True)
    return folder


def _cycle(tree: Path, rod: str, joint: str) -> dict:
    environment = {**os.environ, "PYTHONPATH": str(tree), "OMP_NUM_THREADS": "1",
                   "OPENBLAS_NUM_THREADS": "1"}
    done = subprocess.run([sys.executable, "-c", CYCLE, rod, joint], capture_output=True,
                          text=True, env=environment, check=True, cwd=tree)
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_compiled_against_numpy_dynamics(tmp_path):
    old_tree = _tree_of(PRE_NUMBA, tmp_path)
    print(f"\nfewear.mbd now against {PRE_NUMBA} (NumPy), medians of {ROUNDS} alternating rounds:"
          "\ncase                 s/cycle now  before   ratio   steps/cycle now  before"
          "   us/step now  before   ratio")
    for rod, joint in CASES:
        runs = {"now": [], "before": []}
        for _ in range(ROUNDS):
            runs["now"].append(_cycle(REPOSITORY, rod, joint))
            runs["before"].append(_cycle(old_tree, rod, joint))
        median = {version: {key: statistics.median(run[key] for run in rows) for key in rows[0]}
                  for version, rows in runs.items()}
        now, before = median["now"], median["before"]
        print(f"{rod:8s} {joint:10s}  {now['cycle_s']:10.3f} {before['cycle_s']:7.3f} "
              f"{before['cycle_s'] / now['cycle_s']:6.1f}x  {now['steps_per_cycle']:15.0f} "
              f"{before['steps_per_cycle']:7.0f}  {now['step_us']:12.0f} {before['step_us']:7.0f} "
              f"{before['step_us'] / now['step_us']:6.1f}x")
