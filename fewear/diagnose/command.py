"""``fewear diagnose MEASURED.csv [MORE.csv ...] [--config FILE.toml] [--out DIR]``: what a wear
model gets wrong on measured data. The data kind decides which diagnosis runs: a measured wear
scar (first column ``x_mm`` or ``x_m``: :mod:`fewear.diagnose.scar.command`) is recognised
first, then joint wear data (bore profiles, maximum-depth growth, traces:
:mod:`fewear.diagnose.joint.command`), both from their header; anything else is read as a
pin-on-disc table
(:mod:`fewear.diagnose.tribometer.command`).
"""

from __future__ import annotations

import argparse

from fewear.diagnose.joint.measured import joint_data_kind
from fewear.diagnose.scar.measured import is_scar_file


def main(args: argparse.Namespace) -> int:
    if is_scar_file(args.measured[0]):
        from fewear.diagnose.scar.command import run
    elif joint_data_kind(args.measured[0]) is not None:
        from fewear.diagnose.joint.command import run
    else:
        from fewear.diagnose.tribometer.command import run
    return run(args)
