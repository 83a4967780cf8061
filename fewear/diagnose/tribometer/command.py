"""``fewear diagnose MEASURED.csv [--config FILE.toml] [--out DIR]`` on pin-on-disc data: what plain
Archard gets wrong on them, the cause, the extended model and its gain (see
:mod:`fewear.diagnose.tribometer.diagnose`). Writes DIR/diagnosis.json, DIR/report.md (with PNG
figures) and DIR/extended_wear.toml, all or nothing.
"""

from __future__ import annotations

import argparse
import sys

from fewear.diagnose.core.report import print_verdict
from fewear.diagnose.tribometer.diagnose import diagnose
from fewear.diagnose.tribometer.measured import read_measured_wear
from fewear.diagnose.tribometer.plausibility import check_plausible
from fewear.diagnose.tribometer.readings import readings_from_measured
from fewear.diagnose.tribometer.report import summarise, write_outputs
from fewear.diagnose.tribometer.settings import DiagnoseSettings
from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.output import staged_output


def run(args: argparse.Namespace) -> int:
    """The diagnosis of the one table ``args.measured``, its outputs written to ``args.out``."""
    if len(args.measured) != 1:
        raise FewearInputError(
            f"{len(args.measured)} files given: tribometer data are one file "
            "(joint wear data may be several: profiles and maximum-depth growth)")
    path = args.measured[0]
    config = load_config(args.config, sections=["diagnose"])
    settings = DiagnoseSettings.from_config(config["diagnose"])
    data = read_measured_wear(path)
    for warning in check_plausible(data):
        print(f"fewear diagnose: warning: {warning}", file=sys.stderr, flush=True)
    readings = readings_from_measured(data)
    print(f"fewear diagnose: {len(data.test_names())} tests, {data.test_id.size} readings from "
          f"{path}: fitting plain Archard and the causes "
          f"({', '.join(settings.candidates)})", file=sys.stderr, flush=True)
    diagnosis = diagnose(readings, settings, progress=_progress(readings.n_tests))
    summary = summarise(diagnosis)
    with staged_output(args.out) as stage:
        write_outputs(diagnosis, summary, stage)
    print_verdict(summary, args.out, unit="", confounded=[
        f"confounded {' / '.join(group['causes'])}: {group['reason']}"
        for group in summary["confounded"]])
    return 0


LARGE_TABLE_TESTS = 500
"""From this many tests on, the diagnosis takes minutes: each cause tried is reported."""


def _progress(n_tests: int):
    if n_tests < LARGE_TABLE_TESTS:
        return None
    return lambda text: print(f"fewear diagnose: {text}", file=sys.stderr, flush=True)
