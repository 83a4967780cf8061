"""Benchmark of the joint diagnosis (prints its figures; `make bench`): identification accuracy
over seeds for every cause of the catalogue, the false-positive rate on the believed model's own
data, and the cost of a diagnosis (the first, which runs the candidate models, and the next ones
against the same believed model, which reuse them).

FEWEAR_BENCH_JOINT_SEEDS (default 4) data sets per cause and for the null case; the data are those
of tests/diagnose/joint/cases.py (random effect parameters, random profilometer sampling and
angular origin, 0.5 um noise)."""

import os
import time

import pytest

from fewear.diagnose.joint.catalogue import CAUSES
from fewear.diagnose.joint.diagnose import diagnose_joint
from fewear.diagnose.joint.report import summarise
from fewear.io.config import load_config
from fewear.loop.settings import run_sections
from tests.diagnose.joint.cases import believed_text, hidden_joint_case

pytestmark = pytest.mark.benchmark
SEEDS = int(os.environ.get("FEWEAR_BENCH_JOINT_SEEDS", "4"))


def test_identification_accuracy_and_cost(tmp_path):
    path = tmp_path / "believed.toml"
    path.write_text(believed_text())
    config = load_config(path, run_sections())
    named, gains, times, rows = {}, {}, [], []
    for cause in ("none", *CAUSES):
        named[cause], gains[cause] = 0, []
        for seed in range(SEEDS):
            data, truth, _ = hidden_joint_case(config, cause, 1000 + 17 * seed)
            start = time.perf_counter()
            summary = summarise(diagnose_joint(data, config))
            times.append(time.perf_counter() - start)
            hit = summary["cause"] == cause
            named[cause] += hit
            gains[cause].append(summary["gain"])
            rows.append(f"{cause:17s} seed {seed}: named {summary['causes'] or ['none']}, gain "
                        f"{summary['gain']:.0%}, {times[-1]:.0f} s, truth {truth}")
    print("\n".join(["", "joint diagnosis, per data set:", *rows, ""]))
    for cause in ("none", *CAUSES):
        label = "no cause (false positives)" if cause == "none" else cause
        mean_gain = sum(gains[cause]) / len(gains[cause])
        print(f"{label:28s} {named[cause]}/{SEEDS} named correctly, mean held-out gain "
              f"{mean_gain:.0%}")
    hidden = sum(named[c] for c in CAUSES)
    print(f"identification accuracy {hidden}/{SEEDS * len(CAUSES)}, false positives "
          f"{SEEDS - named['none']}/{SEEDS}; wall time of the first diagnosis {times[0]:.0f} s "
          f"(runs the candidate models), the others {sorted(times[1:])[len(times[1:]) // 2]:.0f} s "
          "median (the candidates reused)")
