"""`fewear diagnose` on joint wear from a fourth, separately designed generator
(tests/diagnose/joint/generators/fourth.py): the believed coarse slider-crank model with one hidden
cause per data set, each by a law of its own (a bronze off its hardness, a 6-element damped ANCF
steel rod, a friction that rises as the grease is lost, impact wear by the cube of the impact
speed, running-in of the pin's roughness as a bore-wide warp of the cycles, or nothing), measured
from silicone replicas with a confocal scanner (Gaussian-filtered profiles every 1.5 deg with an
unknown origin, seating errors, a shared reference pattern, drift, bubbles, a parting-line gap and
torn sectors, quantised) at 4-6 counts between 1,500 and 25,000 cycles plus four maximum-depth
readings, with its slider-acceleration and joint-force traces. Run with
``pytest tests/benchmarks/test_bench_joint_fourth.py -m benchmark -s`` (SEEDS per cause from
``FEWEAR_BENCH_JOINT_FOURTH_SEEDS``, default 2)."""

import os
import time

import pytest

from fewear.diagnose.joint.measured import read_joint_measurements
from fewear.io.config import load_config
from fewear.loop.settings import run_sections
from tests.benchmarks.joint_files import measured_files
from tests.diagnose.joint.generators.fourth import (
    CAUSES,
    data_set_seed,
    truth_text,
    write_data_set,
)

pytestmark = pytest.mark.benchmark
SEEDS = int(os.environ.get("FEWEAR_BENCH_JOINT_FOURTH_SEEDS", "2"))


def test_diagnose_fourth_generator(tmp_path):
    from fewear.diagnose.joint.diagnose import diagnose_joint
    from fewear.diagnose.joint.report import summarise

    rows, config, start = [], None, time.perf_counter()
    print("\ncause | seed | first named | named | gain | wall s | unexplained | profile counts | "
          "truth")
    for cause in CAUSES:
        for index in range(SEEDS):
            seed = data_set_seed(cause, index)
            data = write_data_set(cause, seed, tmp_path / f"{cause}-{index}")
            if config is None:
                config = load_config(data.believed_toml, run_sections())
            measured = read_joint_measurements(measured_files(data))
            began = time.perf_counter()
            summary = summarise(diagnose_joint(measured, config))
            wall = time.perf_counter() - began
            row = (cause, seed, summary["cause"] or "", ",".join(summary["causes"]),
                   float(summary["gain"] or 0.0), wall,
                   "unexplained" if summary["unexplained"] else "",
                   ",".join(str(count) for count in data.lab.profile_cycles), truth_text(data),
                   list(summary["causes"]))
            rows.append(row)
            print(f"{row[0]} | {row[1]} | {row[2] or '-'} | {row[3] or '-'} | {row[4]:.3f} | "
                  f"{row[5]:.0f} | {row[6]} | {row[7]} | {row[8]}", flush=True)
    print("\ncause | named first / data sets")
    correct = 0
    for cause in CAUSES:
        mine = [row for row in rows if row[0] == cause]
        if cause == "none":
            right = sum(not row[9] for row in mine)
            false = sum(bool(row[9]) for row in mine)
            print(f"none | nothing named {right} / {len(mine)} (false positives {false})")
        else:
            right = sum(row[2] == cause for row in mine)
            print(f"{cause} | {right} / {len(mine)}")
        correct += right
    print(f"total: {correct} / {len(rows)} right, wall {time.perf_counter() - start:.0f} s")
    assert len(rows) == SEEDS * len(CAUSES)
