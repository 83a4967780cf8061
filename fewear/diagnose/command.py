"""``fewear diagnose MEASURED.csv [--config FILE.toml] [--out DIR]``: what plain Archard gets wrong
on measured pin-on-disc data, the cause, the extended model and its gain (see
:mod:`fewear.diagnose.tribometer.diagnose`). Writes DIR/diagnosis.json, DIR/report.md (with PNG
figures) and DIR/extended_wear.toml, all or nothing.
"""

from __future__ import annotations

import argparse
import sys

from fewear.diagnose.tribometer.diagnose import diagnose
from fewear.diagnose.tribometer.measured import read_measured_wear
from fewear.diagnose.tribometer.readings import readings_from_measured
from fewear.diagnose.tribometer.report import write_outputs
from fewear.diagnose.tribometer.settings import DiagnoseSettings
from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.output import staged_output


def main(args: argparse.Namespace) -> int:
    from fewear.diagnose.joint.measured import joint_data_kind

    if joint_data_kind(args.measured[0]) is not None:
        from fewear.diagnose.joint.command import main as diagnose_joint_data

        return diagnose_joint_data(args)
    if len(args.measured) != 1:
        raise FewearInputError(
            f"{len(args.measured)} files given: tribometer data are one file "
            "(joint wear data may be several: profiles and maximum-depth growth)")
    args.measured = args.measured[0]
    config = load_config(args.config, sections=["diagnose"])
    settings = DiagnoseSettings.from_config(config["diagnose"])
    data = read_measured_wear(args.measured)
    readings = readings_from_measured(data)
    print(f"fewear diagnose: {len(data.test_names())} tests, {data.test_id.size} readings from "
          f"{args.measured}: fitting plain Archard and the causes "
          f"({', '.join(settings.candidates)})", file=sys.stderr, flush=True)
    diagnosis = diagnose(readings, settings)
    with staged_output(args.out) as stage:
        write_outputs(diagnosis, stage)
    summary = diagnosis.summary
    print(f"fewear diagnose: causes {', '.join(summary['causes']) or 'none'}, held-out error "
          f"{summary['held_out_error']['baseline']:.3g} -> "
          f"{summary['held_out_error']['extended']:.3g} (gain {summary['gain']:.0%}); "
          f"outputs in {args.out}")
    for group in summary["confounded"]:
        print(f"fewear diagnose: confounded {' / '.join(group['causes'])}: {group['reason']}")
    for sentence in summary["unexplained"]:
        print(f"fewear diagnose: unexplained: {sentence}")
    return 0
