"""`fewear diagnose` on joint wear with two causes hidden together (the issue's goal: both named
in at least 70 % of data sets).

The third and fourth generators (tests/diagnose/joint/generators/third.py,
fourth.py, written without reading the diagnosis) hide both causes of a pair in
one truth, each drawn as its single-cause data sets draw it. Each data set (its bore profiles,
maximum depths and the slider-acceleration and joint-force traces its generator wrote) goes
through the CSV readers to the diagnosis with the believed model and ``max_causes = 2``.
Printed: one row per data set (the causes named, the gain each round added), then per
generator and in all how often both hidden causes were named, and the wall time. Run with
``pytest tests/benchmarks/test_bench_joint_two_causes.py -m benchmark -s``; the pairs from
``FEWEAR_BENCH_TWO_CAUSE_PAIRS`` (e.g. ``friction+running_in,flexible_link+friction``; default
all ten), seed indices from ``FEWEAR_BENCH_TWO_CAUSE_SEEDS`` (default 1). The table is the
result; the only assert is that every data set was diagnosed.
"""

import importlib
import os
import time
from dataclasses import replace

import pytest

from fewear.diagnose.joint.measured import read_joint_measurements
from fewear.io.config import load_config
from fewear.loop.settings import run_sections
from tests.benchmarks.joint_files import measured_files

pytestmark = pytest.mark.benchmark

GENERATORS = ("third", "fourth")
SEEDS = int(os.environ.get("FEWEAR_BENCH_TWO_CAUSE_SEEDS", "1"))


def _pairs(generator) -> list[tuple[str, str]]:
    chosen = os.environ.get("FEWEAR_BENCH_TWO_CAUSE_PAIRS")
    if not chosen:
        return list(generator.TWO_CAUSE_PAIRS)
    return [tuple(item.split("+")) for item in chosen.split(",")]


def test_diagnose_two_hidden_causes(tmp_path):
    from fewear.diagnose.joint.diagnose import diagnose_joint
    from fewear.diagnose.joint.report import summarise
    from fewear.diagnose.joint.settings import JointDiagnoseSettings

    settings = replace(JointDiagnoseSettings.default(), max_causes=2)
    rows, start = [], time.perf_counter()
    print("\ngenerator | pair | seed | named | both | gains | wall s")
    for name in GENERATORS:
        generator = importlib.import_module(f"tests.diagnose.joint.generators.{name}")
        for pair in _pairs(generator):
            for index in range(SEEDS):
                seed = generator.two_cause_seed(pair, index)
                data = generator.write_two_cause_data_set(pair, seed,
                                                          tmp_path / f"{name}-{seed}")
                config = load_config(data.believed_toml, run_sections())
                measured = read_joint_measurements(measured_files(data))
                began = time.perf_counter()
                summary = summarise(diagnose_joint(measured, config, settings))
                both = set(pair) <= set(summary["causes"])
                gains = ", ".join(f"{g['cause']} {g['gain']:+.2f}"
                                  for g in summary["cause_gains"])
                rows.append((name, both))
                print(f"{name} | {'+'.join(pair)} | {seed} | "
                      f"{','.join(summary['causes']) or 'none'} | {both} | {gains} | "
                      f"{time.perf_counter() - began:.0f}", flush=True)
    for name in GENERATORS:
        mine = [both for generator, both in rows if generator == name]
        print(f"{name}: both named {sum(mine)}/{len(mine)}")
    hits = sum(both for _, both in rows)
    print(f"both named {hits}/{len(rows)} = {hits / max(len(rows), 1):.0%}; wall time "
          f"{time.perf_counter() - start:.0f} s")
    assert rows
