"""The checkpoint of ``fewear run``: everything needed to continue after any wear block.

One NumPy archive, ``OUT/fewear-checkpoint.npz``, rewritten atomically (a temporary file renamed
over it) by rank 0 after every block, so an interrupted run (Ctrl-C, a crash, a killed job) loses
at most the block in progress. It holds the complete config the run used and, per rod model, the
wear state, the mechanism's final state (the next block's warm start), the moved mesh's node
coordinates after every block, the block records, the counts and the stage times.
``fewear run --resume`` rebuilds the same objects and continues; since every block starts from
exactly these arrays, the resumed run ends with the result of an uninterrupted one.

A checkpoint made with another config, or one that cannot be read, is an input error naming
the cause: resuming it would silently mix two different runs.
"""

from __future__ import annotations

import json
import os
import zipfile
from dataclasses import asdict, fields
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError
from fewear.loop.progress import BlockRecord, CaseProgress, LoopCounts
from fewear.wear.extensions import SlidingState
from fewear.wear.state import WearState

FILENAME = "fewear-checkpoint.npz"
FORMAT = "fewear-run-checkpoint-1"
LOOP_COUNT_NAMES = [count.name for count in fields(LoopCounts)]


class Checkpoint:
    """The checkpoint file of a run writing into ``out_dir`` with ``config``."""

    def __init__(self, out_dir, config: dict, comm):
        self.path = Path(out_dir).resolve() / FILENAME
        self.config = json.loads(json.dumps(config))
        self.comm = comm

    def save(self, cases: dict) -> None:
        """Write every case's progress (rank 0; atomically)."""
        if self.comm.rank != 0:
            return
        arrays = {"meta": np.array(json.dumps({
            "format": FORMAT, "config": self.config,
            "cases": {rod: _case_meta(case) for rod, case in cases.items()}}))}
        for rod, case in cases.items():
            arrays.update({f"{rod}/{key}": value for key, value in _case_arrays(case).items()})
        temporary = self.path.with_name(f".{FILENAME}.{os.getpid()}.tmp")
        with open(temporary, "wb") as handle:
            np.savez(handle, **arrays)
        os.replace(temporary, self.path)

    def load(self) -> dict:
        """The cases of the checkpoint (rod -> :class:`fewear.loop.progress.CaseProgress`); an input
        error when it is missing, unreadable or made with another config."""
        if not self.path.exists():
            raise FewearInputError(
                f"--resume: no checkpoint {self.path} (a run writes it after its first block); "
                "run without --resume to start")
        try:
            with np.load(self.path, allow_pickle=False) as archive:
                data = {key: archive[key] for key in archive.files}
            meta = json.loads(str(data["meta"]))
        except (OSError, ValueError, KeyError, zipfile.BadZipFile, json.JSONDecodeError) as exc:
            raise FewearInputError(
                f"--resume: checkpoint {self.path} is unreadable ({exc}); delete it to start "
                "again") from None
        if meta.get("format") != FORMAT:
            raise FewearInputError(
                f"--resume: {self.path} has format {meta.get('format')!r}, expected {FORMAT!r}")
        difference = _first_difference(meta["config"], self.config)
        if difference:
            raise FewearInputError(
                f"--resume: checkpoint {self.path} was made with another config ({difference}); "
                "resume with the same config, or run without --resume into another --out")
        try:
            return {rod: _case_from(rod, case_meta, data)
                    for rod, case_meta in meta["cases"].items()}
        except (KeyError, ValueError, TypeError) as exc:
            raise FewearInputError(
                f"--resume: checkpoint {self.path} is incomplete ({exc}); delete it to start "
                "again") from None


def _case_meta(case: CaseProgress) -> dict:
    return {"cycles": int(case.state.cycles), "blocks": int(case.state.blocks),
            **{name: int(value) for name, value in asdict(case.counts).items()},
            "stage_wall_time_s": dict(case.stage_wall_time_s),
            "time_s": float(case.mechanism.time_s)}


def _case_arrays(case: CaseProgress) -> dict:
    state, records = case.state, case.records
    return {
        "angle_rad": state.angle_rad, "depth_m": state.depth_m,
        "sliding_distance_m": state.sliding.distance_m, "sliding_time_s": state.sliding.time_s,
        "lagged_power_W_m2": state.sliding.lagged_power_W_m2,
        "q": case.mechanism.q, "qd": case.mechanism.qd,
        "node_ids": case.node_ids, "cells": case.cells,
        "meshed_xy_m": case.meshed_xy_m, "snapshots": np.array(case.snapshots),
        "record_cycles": np.array([r.cycles for r in records]),
        "record_block_cycles": np.array([r.block_cycles for r in records]),
        "record_depth_m": np.array([r.depth_m for r in records]),
        "record_impacts": np.array([r.impacts for r in records]),
        "record_values": np.array([[r.peak_contact_force_N, r.max_contact_pressure_Pa,
                                    r.max_depth_per_cycle_m] for r in records]),
    }


def _case_from(rod: str, meta: dict, data: dict) -> CaseProgress:
    from fewear.mbd.slider_crank import MechanismState

    def array(key):
        return data[f"{rod}/{key}"]

    state = WearState(array("angle_rad"), array("depth_m"),
                      SlidingState(array("sliding_distance_m"), array("sliding_time_s"),
                                   array("lagged_power_W_m2"), float(meta["cycles"])),
                      meta["cycles"], meta["blocks"])
    records = [BlockRecord(int(c), int(a), d, float(v[0]), int(i), float(v[1]), float(v[2]))
               for c, a, d, i, v in zip(array("record_cycles"), array("record_block_cycles"),
                                        array("record_depth_m"), array("record_impacts"),
                                        array("record_values"))]
    return CaseProgress(
        state=state, mechanism=MechanismState(meta["time_s"], array("q"), array("qd")),
        records=records, snapshots=list(array("snapshots")), node_ids=array("node_ids"),
        cells=array("cells"), meshed_xy_m=array("meshed_xy_m"),
        counts=LoopCounts(**{name: meta[name] for name in LOOP_COUNT_NAMES}),
        stage_wall_time_s=dict(meta["stage_wall_time_s"]))


def _first_difference(stored, current, where: str = "") -> str:
    """'[section] key: stored -> current' for the first value that differs, '' if none."""
    if isinstance(stored, dict) and isinstance(current, dict):
        for key in sorted(set(stored) | set(current)):
            path = f"[{key}]" if not where else f"{where} {key}"
            found = _first_difference(stored.get(key), current.get(key), path)
            if found:
                return found
        return ""
    return "" if stored == current else f"{where}: {stored!r} in the checkpoint, {current!r} now"
