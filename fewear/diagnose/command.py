"""``fewear diagnose MEASURED.csv [MORE.csv ...] [--config FILE.toml] [--out DIR]``: what a wear
model gets wrong on measured data. The data kind decides which diagnosis runs: joint wear data
(bore profiles, maximum-depth growth, traces: :mod:`fewear.diagnose.joint.command`) are
recognised from their header, anything else is read as a pin-on-disc table
(:mod:`fewear.diagnose.tribometer.command`).
"""

from __future__ import annotations

import argparse

from fewear.diagnose.joint.measured import joint_data_kind


def main(args: argparse.Namespace) -> int:
    if joint_data_kind(args.measured[0]) is not None:
        from fewear.diagnose.joint.command import run
    else:
        from fewear.diagnose.tribometer.command import run
    return run(args)
