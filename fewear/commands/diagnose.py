"""``fewear diagnose MEASURED.csv [MORE.csv ...] [--config FILE.toml] [--out DIR]``: what a wear
model gets wrong on measured data. The data kind decides which diagnosis runs: a measured wear
scar (first column ``x_mm`` or ``x_m``: :mod:`fewear.diagnose.scar.command`) is recognised
first, then joint wear data (bore profiles, maximum-depth growth, traces:
:mod:`fewear.diagnose.joint.command`), both from their header; anything else is read as a
pin-on-disc table
(:mod:`fewear.diagnose.tribometer.command`).

Under ``mpirun`` the joint diagnosis runs on every rank (its forward runs share the FE contact
among them) and rank 0 writes; the scar and tribometer diagnoses are serial: rank 0 runs them
alone and the other ranks end at once (before, every rank ran the whole diagnosis and wrote
the same folder).
"""

from __future__ import annotations

import argparse
import sys
from importlib import import_module

from fewear.diagnose.joint.measured import joint_data_kind
from fewear.diagnose.scar.measured import is_scar_file
from fewear.parallel import launcher_rank_and_size


def data_kind(path) -> str:
    """Which diagnosis the measured file ``path`` asks for: "scar", "joint" or "tribometer"."""
    return ("scar" if is_scar_file(path) else
            "joint" if joint_data_kind(path) is not None else "tribometer")


def main(args: argparse.Namespace) -> int:
    kind = data_kind(args.measured[0])
    if kind != "joint":  # serial: rank 0 alone
        rank, size = launcher_rank_and_size()
        if rank > 0:
            return 0
        if size > 1:
            print(f"fewear diagnose: the {kind} diagnosis is serial: rank 0 runs it, the other "
                  f"{size - 1} rank(s) have nothing to do", file=sys.stderr, flush=True)
    room = import_module(f"fewear.diagnose.{kind}.command")
    return room.run(args)
