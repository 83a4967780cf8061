"""`fewear diagnose` on joint wear from a third, separately designed generator.

tests/diagnose/joint/generators/third.py draws a hidden cause (its own forms and ranges: a
smoothstep running-in, impact wear from the squared Hertz-pressure excess, flexible steel or
aluminium rods, ...) and measures the worn bore with its own lab (a CMM with a ball stylus and an
unknown angular origin, a bore gauge). For each cause and seed index the data set (profiles,
maximum depths, the slider-acceleration and joint-force traces) goes through the CSV readers to
the diagnosis with the believed coarse rigid model. Printed: one row per data set,
then per cause how often the hidden cause was named first, false positives on ``none`` (any cause
named), the total accuracy and wall time. Run with
``pytest tests/benchmarks/test_bench_joint_third.py -m benchmark -s`` (SEEDS per cause from
``FEWEAR_BENCH_JOINT_THIRD_SEEDS``, default 2). The table is the result; the only assert is that
every data set was diagnosed.
"""

import os
import time

import pytest

from fewear.diagnose.joint.measured import read_joint_measurements
from fewear.io.config import load_config
from fewear.loop.settings import run_sections
from tests.benchmarks.joint_files import measured_files
from tests.diagnose.joint.generators.third import CAUSES, data_set_seed, write_data_set

pytestmark = pytest.mark.benchmark

SEEDS = int(os.environ.get("FEWEAR_BENCH_JOINT_THIRD_SEEDS", "2"))


def _truth_text(params: dict) -> str:
    return " ".join(f"{name}={value:.4g}" if isinstance(value, float) else f"{name}={value}"
                    for name, value in params.items())


def test_diagnose_third_generator(tmp_path):
    from fewear.diagnose.joint.diagnose import diagnose_joint
    from fewear.diagnose.joint.report import summarise

    rows, config, start = [], None, time.perf_counter()
    print("\ncause | seed | first named | named | gain | wall s | unexplained | profile counts"
          " | truth")
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
            row = (cause, seed, summary["cause"], ",".join(summary["causes"]),
                   float(summary["gain"] or 0.0), wall,
                   "unexplained" if summary["unexplained"] else "",
                   data.lab.profile_cycles, _truth_text(data.params))
            rows.append(row)
            print(f"{row[0]} | {row[1]} | {row[2]} | {row[3]} | {row[4]:.3f} | {row[5]:.0f} | "
                  f"{row[6]} | {','.join(str(c) for c in row[7])} | {row[8]}", flush=True)
    print("\nper cause: named first / data sets")
    correct = 0
    for cause in CAUSES:
        mine = [row for row in rows if row[0] == cause]
        if cause == "none":
            hits = sum(not row[3] for row in mine)
            positives = len(mine) - hits
            print(f"  none: nothing named {hits}/{len(mine)}; false positives {positives}")
        else:
            hits = sum(row[2] == cause for row in mine)
            print(f"  {cause}: {hits}/{len(mine)}")
        correct += hits
    print(f"total accuracy {correct}/{len(rows)} = {correct / max(len(rows), 1):.0%}; "
          f"wall time {time.perf_counter() - start:.0f} s")
    assert len(rows) == SEEDS * len(CAUSES)
