"""How often `fewear diagnose` names a hidden cause, and how often it invents one (issue 8).

Two independently written generators (tests/diagnose/tribometer/generators.py: ours and
tests/diagnose/tribometer/independent_generator.py),
swept over a grid: the effect's length as a fraction of
the test (``scale`` 0.01, 0.1, 0.5; for the level causes the independent generator maps it to the
effect's strength), the relative noise of every cumulative reading (0.01, 0.03, 0.1; dips kept)
and the sampling (histories: many readings per test; table: one reading per test). Per cell,
SEEDS data sets of each of the five causes and NULL_SEEDS plain-Archard data sets go to the
diagnosis with the default settings, through the CSV reader. Printed per cell:

- ``first``: the hidden cause is the first cause named (the strict figure);
- ``named``: the hidden cause is among the causes named, or confounded with the first by the
  report (the report then says the data cannot tell the two apart);
- ``family``: ``named``, or heating hidden and a p v threshold named or the reverse (one law
  family, see tests/diagnose/tribometer/generators.named_as_power_law);
- ``fp``: plain-Archard data sets for which any cause was named.

Goals of the issue: >= 90 % of hidden causes named, fp <= 5 % in every cell. Run with
``pytest tests/benchmarks/test_bench_diagnose.py -m benchmark -s`` (about 1000 diagnoses). The
asserts are loose floors over the whole grid so that a regression fails; the printed table is
the result.
"""

import os
import time
from collections import Counter
from itertools import product

import numpy as np
import pytest

from fewear.diagnose.tribometer.diagnose import diagnose
from fewear.diagnose.tribometer.report import summarise
from tests.diagnose.tribometer.generators import (
    CAUSES,
    GENERATORS,
    SAMPLINGS,
    dataset,
    named,
    named_as_power_law,
)

SCALES = (0.01, 0.1, 0.5)
NOISES = (0.01, 0.03, 0.1)
SEEDS = int(os.environ.get("FEWEAR_BENCH_SEEDS", "4"))
NULL_SEEDS = 2 * SEEDS


def run_cell(generator, sampling, scale, noise, folder):
    """Rates of ``first``, ``named``, ``family`` and ``fp`` in one cell, the misses (hidden ->
    first named) and the causes of the false positives."""
    counts, misses, false_positives = Counter(), Counter(), []
    for cause, seed in product(CAUSES, range(SEEDS)):
        summary = summarise(diagnose(dataset(generator, cause, 100 + seed, folder, scale=scale,
                                   noise=noise, sampling=sampling)))
        counts["first"] += summary["cause"] == cause
        counts["named"] += named(summary, cause)
        counts["family"] += named_as_power_law(summary, cause)
        if not named(summary, cause):
            misses[f"{cause}->{summary['cause']}"] += 1
    for seed in range(NULL_SEEDS):
        summary = summarise(diagnose(dataset(generator, "none", 500 + seed, folder, scale=scale,
                                   noise=noise, sampling=sampling)))
        if summary["causes"]:
            false_positives.append(summary["cause"])
    n = len(CAUSES) * SEEDS
    rates = [counts[key] / n for key in ("first", "named", "family")]
    return rates + [len(false_positives) / NULL_SEEDS], misses, false_positives


@pytest.mark.benchmark
def test_accuracy_and_false_positives_over_the_grid(tmp_path):
    start = time.perf_counter()
    totals = {}
    for generator in GENERATORS:
        print(f"\n{generator} generator: {SEEDS} data sets per cause and cell, {NULL_SEEDS} null")
        print(f"{'sampling':10s} {'scale':>5s} {'noise':>5s} {'first':>6s} {'named':>6s} "
              f"{'family':>6s} {'fp':>5s}  misses (hidden->first named) / false positives")
        rows = []
        for sampling, scale, noise in product(SAMPLINGS, SCALES, NOISES):
            rates, misses, fps = run_cell(generator, sampling, scale, noise, tmp_path)
            rows.append(rates)
            print(f"{sampling:10s} {scale:5.2f} {noise:5.2f} "
                  + " ".join(f"{rate:6.0%}" for rate in rates[:3])
                  + f" {rates[3]:5.0%}  {dict(misses)} {fps}")
        first, hit, family, fp = np.mean(rows, axis=0)
        totals[generator] = (hit, fp)
        print(f"{generator} over the grid: first {first:.0%}, named {hit:.0%}, family "
              f"{family:.0%}, false positives {fp:.0%}")
    print(f"{time.perf_counter() - start:.0f} s")
    for generator, (hit, fp) in totals.items():
        assert hit >= 0.75 and fp <= 0.10, generator
