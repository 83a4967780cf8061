"""``fewear scar [--config FILE.toml] [--out DIR]``: a wear scar predicted by the FE wear loop on
the flat beside the measured one(s) (:func:`fewear.loop.scar.predict_scar`); ``[scar] case``
chooses the case. A progress line per wear step or block goes to stderr; written, all or nothing
(:func:`fewear.io.output.staged_output`), by rank 0 (runs under ``mpirun -n N``):

- ``profiles.csv``: x_m on the measured profiles' grid, the predicted depth there (linear between
  the FE nodes) and the measured depths (m, positive: worn; the measured heights negated);
- ``predicted_nodes.csv``: x_m and depth_m at the FE top nodes;
- ``summary.json``: the largest depth, the width (where the depth exceeds 5 % of it, crossings
  interpolated: :func:`fewear.wear.scar.scar_depth_and_width_m`) and the worn area, predicted and
  measured (block on ring: each test, their mean, least and largest, and the ring-arc closed
  form; fretting: the shapes U or W, Archard's global area and the cylinder's wear), the RMS of
  predicted less measured depth on the measured grid, the run's steps or blocks, mesh quality and
  wall time; the config used;
- ``scar.png``: the profiles.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import numpy as np

from fewear.loop.scar import ScarResult


def main(args: argparse.Namespace) -> int:
    from mpi4py import MPI

    from fewear.io.config import load_config
    from fewear.loop.scar import SCAR_SECTIONS

    predict_and_write(load_config(args.config, SCAR_SECTIONS), args.out, MPI.COMM_WORLD)
    return 0


def predict_and_write(config: dict, out, comm) -> ScarResult:
    """The scar of ``config`` (loaded) predicted on ``comm`` and written into ``out`` (rank 0);
    progress on stderr. :func:`fewear.api.scar` calls it too."""
    from fewear.io.output import staged_output
    from fewear.loop.scar import predict_scar, scar_case_from_config

    def say(text: str) -> None:
        if comm.rank == 0:
            print(f"fewear scar: {text}", file=sys.stderr, flush=True)

    inputs = scar_case_from_config(config)  # bad input refused before the folder is staged
    with staged_output(out, comm) as stage:
        result = predict_scar(inputs, config, comm, say)
        if comm.rank == 0:
            write_outputs(stage, result)
    return result


def write_outputs(stage: Path, result: ScarResult) -> None:
    """The files of the module docstring into the folder ``stage``."""
    from fewear.io.output import write_json
    from fewear.plot.scar import plot_scar

    state = result.state
    if result.case == "fretting":
        (x, measured), = result.measured.values()
        columns, names = [x, state.depth_at(x), measured], ["measured"]
    else:
        x = next(iter(result.measured.values()))[0]
        columns = [x, state.depth_at(x)] + [depth for _, depth in result.measured.values()]
        names = list(result.measured)
    header = ",".join(["x_m", "predicted_depth_m"] + [f"{name}_depth_m" for name in names])
    np.savetxt(stage / "profiles.csv", np.column_stack(columns), delimiter=",", header=header,
               comments="", fmt="%.9g")
    np.savetxt(stage / "predicted_nodes.csv", np.column_stack([state.x_m, state.depth_m]),
               delimiter=",", header="x_m,depth_m", comments="", fmt="%.12g")
    write_json(stage / "summary.json", result.summary)
    plot_scar(stage / "scar.png", (state.x_m, state.depth_m), result.measured, result.title)
