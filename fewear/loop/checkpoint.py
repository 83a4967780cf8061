"""The checkpoint of ``fewear run``: everything needed to continue after any wear block.

One folder, ``OUT/fewear-checkpoint/``, with per case (each case is saved by the ranks or the
process that runs it, so cases run side by side; an ensemble's member m > 0 of a case is saved
as the case ``<case>-member<m>``, :class:`fewear.loop.plan.Member`):

- ``<case>.npz``: the complete config the run used, the mechanism's final state (the next
  block's warm start; none for an imported joint history) and, per clearance joint
  (``<joint>/<array>``), the wear state, the block records, the mesh as made (the reference of
  its motion), the counts and the stage times; rewritten atomically (a temporary file renamed
  over it) after every block, so an interrupted run (Ctrl-C, a crash, a killed job) loses at
  most the block in progress, and the joints of a case are always saved at the same block;
- ``<case>-<joint>-mesh-<block>.npy``: a joint's moved mesh node coordinates after each block
  (block 0: the unworn mesh), each written once, before the ``.npz`` that counts it: the I/O per
  block stays the same however long the run.

``fewear run --resume`` rebuilds the same objects and continues; since every block starts from
exactly these arrays, the resumed run ends with the result of an uninterrupted one. A checkpoint
made with another config, another imported joint history (its SHA-256) or another version, or one
that cannot be read, is an input error naming the cause: resuming it would silently mix two
different runs. So is one altered or damaged since it was written: the ``.npz`` carries the
SHA-256 of its other arrays (``sha256``), its metadata the SHA-256 of every mesh snapshot, both
checked on load; and a non-finite value (NaN, inf), which no run saves, is refused whatever the
digest says (it would surface blocks later as a failed dynamics or contact, blaming a setting).
"""

from __future__ import annotations

import hashlib
import io
import json
import math
import tokenize
import zipfile
from dataclasses import asdict, fields
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.output import write_file_whole
from fewear.io.text import not_a_regular_file
from fewear.loop.progress import BlockRecord, CaseProgress, LoopCounts
from fewear.wear.extensions import SlidingState
from fewear.wear.state import WearState

FOLDER = "fewear-checkpoint"
FORMAT = "fewear-run-checkpoint-5"  # 5: with the SHA-256 digests (4: without)
DIGEST = "sha256"  # the .npz entry holding the SHA-256 of the other entries
LOOP_COUNT_NAMES = [count.name for count in fields(LoopCounts)]
UNREADABLE = (OSError, ValueError, KeyError, zipfile.BadZipFile, json.JSONDecodeError, EOFError,
              SyntaxError, tokenize.TokenError)  # the last: numpy parsing a corrupt array header


class CheckpointDamaged(FewearInputError):
    """A checkpoint altered or damaged since it was written (its SHA-256 does not match, or it
    holds values no run saves)."""


class Checkpoint:
    """The checkpoint folder of a run writing into ``out_dir`` with ``config``."""

    def __init__(self, out_dir, config: dict, history_sha256: str = ""):
        self.path = Path(out_dir).resolve() / FOLDER
        self.config = json.loads(json.dumps(config))
        self.history_sha256 = history_sha256  # of an imported joint history ("": none)

    def case_path(self, case: str) -> Path:
        return self.path / f"{case}.npz"

    def mesh_path(self, case: str, joint: str, block: int) -> Path:
        return self.path / f"{case}-{joint}-mesh-{block:05d}.npy"

    def save(self, case: str, joints: dict) -> None:
        """Write a case's progress after a block (``joints``: joint name ->
        :class:`CaseProgress`, all at the same block): the new mesh snapshots, then the case."""
        self.path.mkdir(parents=True, exist_ok=True)
        arrays, meta = {}, {}
        for joint, progress in joints.items():
            last = len(progress.snapshots) - 1  # new, or left by a block that did not finish
            for block in range(last + 1):
                if block == last or not self.mesh_path(case, joint, block).exists():
                    np.save(self.mesh_path(case, joint, block), progress.snapshots[block])
            arrays.update({f"{joint}/{key}": value
                           for key, value in _case_arrays(progress).items()})
            meta[joint] = {**_case_meta(progress),
                           "mesh_sha256": [array_sha256(mesh) for mesh in progress.snapshots]}
        first = next(iter(joints.values()))
        mechanism = first.mechanism
        if mechanism is not None:
            arrays.update(q=mechanism.q, qd=mechanism.qd)
        arrays["meta"] = np.array(json.dumps({
            "format": FORMAT, "config": self.config, "history_sha256": self.history_sha256,
            "case": {
                "cycles": int(first.state.cycles), "blocks": int(first.state.blocks),
                "time_s": None if mechanism is None else float(mechanism.time_s),
                "joints": meta}}))
        arrays[DIGEST] = np.array(payload_sha256(arrays))
        write_npz(self.case_path(case), arrays)

    def saved_cycles(self) -> dict:
        """case -> crank cycles of each case saved in the folder (read from the cases' metadata
        only, whatever config made them; an unreadable case is left out)."""
        found = {}
        for path in sorted(self.path.glob("*.npz")) if self.path.is_dir() else []:
            try:
                if not_a_regular_file(path):
                    continue  # reading a FIFO would block
                with np.load(path, allow_pickle=False) as archive:
                    found[path.stem] = int(json.loads(str(archive["meta"]))["case"]["cycles"])
            except (*UNREADABLE, TypeError):
                continue
        return found

    def remove_temporary_files(self) -> None:
        """Drop the half-written ``.<case>.npz.<pid>.tmp`` files of a process that was killed while
        it saved (the case files themselves are replaced atomically)."""
        for path in self.path.glob(".*.tmp") if self.path.is_dir() else []:
            path.unlink(missing_ok=True)

    def load(self, cases, joints) -> dict:
        """The saved cases among ``cases`` (case -> joint name -> :class:`CaseProgress`, the
        joints of ``joints`` in order); an input error when there is none, or one is unreadable,
        made with another config or version, or holds other joints."""
        saved = {case: self._load_case(case, list(joints)) for case in cases
                 if self.case_path(case).exists()}
        if not saved:
            raise FewearInputError(
                f"--resume: no checkpoint in {self.path} (a run writes it after its first "
                "block); run without --resume to start")
        return saved

    def _load_case(self, case: str, joints: list) -> dict:
        path = self.case_path(case)
        try:
            if not_a_regular_file(path):
                raise ValueError(f"it is {not_a_regular_file(path)}, not a regular file")
            if path.stat().st_size == 0:
                raise ValueError("the file is empty (0 bytes): a write cut short")
            with np.load(path, allow_pickle=False) as archive:
                data = {key: archive[key] for key in archive.files}
            meta = json.loads(str(data["meta"]))
            if not isinstance(meta, dict):
                raise ValueError("its metadata is not a table")
        except UNREADABLE as exc:
            reason = ("not a checkpoint file (.npz)" if "pickled" in str(exc) else str(exc))
            raise FewearInputError(
                f"--resume: checkpoint {path} is unreadable ({reason}); delete {self.path} to "
                "start again") from None
        if meta.get("format") != FORMAT:
            raise FewearInputError(
                f"--resume: checkpoint {path} has format {meta.get('format')!r}, this fewear "
                f"reads {FORMAT!r} (it was written by another version); run without --resume "
                f"into another --out, or delete {self.path} to start again")
        if str(data.get(DIGEST, "")) != payload_sha256(data):
            raise CheckpointDamaged(_damaged(path, "its contents do not match the SHA-256 saved "
                                                  "with them", self.path))
        difference = _first_difference(meta.get("config"), self.config)
        if difference:
            raise FewearInputError(
                f"--resume: checkpoint {path} was made with another config ({difference}); "
                "resume with the same config, or run without --resume into another --out")
        if meta.get("history_sha256", "") != self.history_sha256:
            raise FewearInputError(
                f"--resume: checkpoint {path} was made with another joint history (its file "
                f"{self.config['wear_loop'].get('joint_history')} has changed since); resume "
                "with the same history, or run without --resume into another --out")
        saved = list(meta.get("case", {}).get("joints", {}))
        if saved != joints:
            raise FewearInputError(
                f"--resume: checkpoint {path} holds the clearance joints {saved}, the run has "
                f"{joints}; run without --resume into another --out")
        try:
            _require_finite(path, data, meta["case"]["time_s"], self.path)
            mechanism = None
            if meta["case"]["time_s"] is not None:
                from fewear.loop.mechanism_adapter import MechanismState

                mechanism = MechanismState(meta["case"]["time_s"], data["q"], data["qd"])
            progress = {}
            for joint in joints:
                snapshots = self._snapshots(case, joint, meta["case"])
                arrays = {key.split("/", 1)[1]: value for key, value in data.items()
                          if key.startswith(f"{joint}/")}
                progress[joint] = _case_from(meta["case"], meta["case"]["joints"][joint],
                                             arrays, snapshots, mechanism)
            return progress
        except CheckpointDamaged:
            raise
        except (*UNREADABLE, TypeError) as exc:
            raise FewearInputError(
                f"--resume: checkpoint {path} is incomplete ({exc}); delete {self.path} to "
                "start again") from None

    def _snapshots(self, case: str, joint: str, case_meta: dict) -> list[np.ndarray]:
        """A joint's mesh snapshots, each checked against the SHA-256 and for finite values."""
        digests = case_meta["joints"][joint]["mesh_sha256"]
        snapshots = []
        for block in range(case_meta["blocks"] + 1):
            path = self.mesh_path(case, joint, block)
            mesh = np.load(path, allow_pickle=False)
            if array_sha256(mesh) != digests[block]:
                raise CheckpointDamaged(_damaged(
                    path, "its contents do not match the SHA-256 saved in the case file",
                    self.path))
            _require_finite(path, {"coordinates": mesh}, 0.0, self.path)
            snapshots.append(mesh)
        return snapshots


def payload_sha256(arrays: dict) -> str:
    """The SHA-256 of a case file's entries (names, dtypes, shapes and bytes, in name order),
    its own entry :data:`DIGEST` left out."""
    digest = hashlib.sha256()
    for name in sorted(set(arrays) - {DIGEST}):
        _add_array(digest, name, arrays[name])
    return digest.hexdigest()


def array_sha256(array: np.ndarray) -> str:
    """The SHA-256 of one array (dtype, shape and bytes): a mesh snapshot's."""
    digest = hashlib.sha256()
    _add_array(digest, "", array)
    return digest.hexdigest()


def _add_array(digest, name: str, value) -> None:
    value = np.asarray(value)
    digest.update(f"{name}\0{value.dtype.str}\0{value.shape}\0".encode())
    digest.update(value.tobytes())


def _require_finite(path: Path, arrays: dict, time_s, folder: Path) -> None:
    """Refuse a checkpoint with a NaN or inf in an array of ``arrays`` or in its time."""
    for name, value in arrays.items():
        if value.dtype.kind in "fc" and not np.all(np.isfinite(value)):
            raise CheckpointDamaged(_damaged(
                path, f"{name} holds non-finite values (NaN or inf), which no run saves", folder))
    if time_s is not None and not (isinstance(time_s, (int, float)) and math.isfinite(time_s)):
        raise CheckpointDamaged(_damaged(path, f"its time {time_s!r} s is not a finite number",
                                        folder))


def _damaged(path: Path, why: str, folder: Path) -> str:
    return (f"--resume: checkpoint {path} was altered or damaged since it was written ({why}); "
            f"start afresh with --overwrite instead of --resume, or run into another --out "
            f"(or delete {folder})")


def _case_meta(case: CaseProgress) -> dict:
    return {**{name: int(value) for name, value in asdict(case.counts).items()},
            "stage_wall_time_s": dict(case.stage_wall_time_s)}


def _case_arrays(case: CaseProgress) -> dict:
    state, records = case.state, case.records
    return {
        "angle_rad": state.angle_rad, "depth_m": state.depth_m,
        "sliding_distance_m": state.sliding.distance_m, "sliding_time_s": state.sliding.time_s,
        "lagged_power_W_m2": state.sliding.lagged_power_W_m2,
        "node_ids": case.node_ids, "cells": case.cells,
        "meshed_xy_m": case.meshed_xy_m,
        "record_cycles": np.array([r.cycles for r in records]),
        "record_block_cycles": np.array([r.block_cycles for r in records]),
        "record_depth_m": np.array([r.depth_m for r in records]),
        "record_impacts": np.array([r.impacts for r in records]),
        "record_values": np.array([[r.peak_contact_force_N, r.max_contact_pressure_Pa,
                                    r.max_depth_per_cycle_m] for r in records]),
        # each block's inner wear steps, concatenated (their counts split them again)
        "record_inner_counts": np.array([r.inner_cycles.size for r in records], dtype=int),
        "record_inner_cycles": np.concatenate(
            [np.zeros(0, dtype=int)] + [r.inner_cycles for r in records]),
        "record_inner_depth_m": np.vstack(
            [np.zeros((0, state.depth_m.size))]
            + [r.inner_depth_m for r in records]),
    }


def _case_from(meta: dict, joint_meta: dict, data: dict, snapshots: list[np.ndarray],
               mechanism) -> CaseProgress:
    def array(key):
        return data[key]

    state = WearState(array("angle_rad"), array("depth_m"),
                      SlidingState(array("sliding_distance_m"), array("sliding_time_s"),
                                   array("lagged_power_W_m2"), float(meta["cycles"])),
                      meta["cycles"], meta["blocks"])
    ends = np.cumsum(array("record_inner_counts"))
    inner_cycles = np.split(array("record_inner_cycles"), ends[:-1])
    inner_depth_m = np.split(array("record_inner_depth_m"), ends[:-1])
    records = [BlockRecord(int(c), int(a), d, float(v[0]), int(i), float(v[1]), float(v[2]),
                           ic, idm)
               for c, a, d, i, v, ic, idm in zip(
                   array("record_cycles"), array("record_block_cycles"),
                   array("record_depth_m"), array("record_impacts"), array("record_values"),
                   inner_cycles, inner_depth_m)]
    return CaseProgress(
        state=state, mechanism=mechanism,
        records=records, snapshots=snapshots, node_ids=array("node_ids"),
        cells=array("cells"), meshed_xy_m=array("meshed_xy_m"),
        counts=LoopCounts(**{name: joint_meta[name] for name in LOOP_COUNT_NAMES}),
        stage_wall_time_s=dict(joint_meta["stage_wall_time_s"]))


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


def write_npz(path: Path, arrays: dict) -> None:
    """``arrays`` as an .npz at ``path``, whole or not at all: zipped in memory, then written by
    :func:`fewear.io.output.write_file_whole` (zipping straight into the file left, on a full
    disk, a half-closed ZipFile whose ``__del__`` printed "Exception ignored ... ValueError"
    after the command's message)."""
    buffer = io.BytesIO()
    np.savez(buffer, **arrays)
    write_file_whole(path, buffer.getbuffer())
