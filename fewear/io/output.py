"""Command outputs written all-or-nothing.

A command writes into a staging folder beside its outputs; only when every file is written are they
moved into the output folder. A failure part-way leaves the output folder as it was (created empty
folders are removed again), so a user never finds a half-written result.
"""

from __future__ import annotations

import errno
import json
import math
import os
import shutil
import tempfile
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np

from fewear.errors import DiskFull, FewearInputError
from fewear.io.signals import signals_held


@contextmanager
def staged_output(out_dir: str | Path, comm=None) -> Iterator[Path]:
    """Yield a staging folder; on success move its files into ``out_dir``, on failure discard it.

    ``comm``: an mpi4py communicator when the command runs under MPI. Rank 0 makes and moves the
    folders; every rank gets the same staging path (collective writers such as XDMF need it) and
    every rank raises together if the folder cannot be made.
    """
    out = Path(out_dir).resolve()
    rank = 0 if comm is None else comm.rank
    result: tuple[str | None, str | None, bool] = (None, None, False)
    if rank == 0:
        result = _make_staging(out)
    if comm is not None:
        result = comm.bcast(result, root=0)
    staging_name, error, created_out = result
    if error is not None:
        raise FewearInputError(error)
    staging = Path(staging_name)
    try:
        yield staging
        if comm is not None:
            comm.barrier()
    except BaseException:
        if rank == 0:
            shutil.rmtree(staging, ignore_errors=True)
            if created_out and not any(out.iterdir()):
                out.rmdir()
        raise
    if rank == 0:
        _record_command(staging)
        with signals_held():  # Ctrl-C or SIGTERM waits until every file is in place
            for item in staging.iterdir():
                target = out / item.name
                if target.is_dir() and not target.is_symlink():
                    shutil.rmtree(target)
                item.replace(target)
            staging.rmdir()
    if comm is not None:
        comm.barrier()


def _record_command(staging: Path) -> None:
    """Name the command that made the outputs in their ``summary.json`` (key ``command``), by
    which another command recognises them (:mod:`fewear.io.transaction`)."""
    from fewear.io.transaction import SUMMARY, current_command

    command, summary = current_command(), staging / SUMMARY
    if command is None or not summary.is_file():
        return
    data = json.loads(summary.read_text())
    if isinstance(data, dict) and "command" not in data:
        summary.write_text(json.dumps({"command": command, **data}, indent=2) + "\n")


def _make_staging(out: Path) -> tuple[str | None, str | None, bool]:
    """(staging path, error message, whether ``out`` was created here)."""
    if out.exists() and not out.is_dir():
        return None, f"output folder {out} exists and is not a folder", False
    created = not out.exists()
    try:
        out.mkdir(parents=True, exist_ok=True)
        staging = tempfile.mkdtemp(prefix=".fewear-staging-", dir=out)
    except OSError as exc:
        return None, f"cannot write to output folder {out}: {exc.strerror or exc}", False
    return staging, None, created


def jsonable(value: Any) -> Any:
    """``value`` with NumPy scalars and arrays as Python numbers and lists, and non-finite floats
    as None (strict JSON has no NaN or infinity)."""
    if isinstance(value, dict):
        return {str(key): jsonable(item) for key, item in value.items()}
    if isinstance(value, (list, tuple)):
        return [jsonable(item) for item in value]
    if isinstance(value, np.ndarray):
        return jsonable(value.tolist())
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value) if math.isfinite(value) else None
    return value


def write_json(path: str | Path, data: Any) -> None:
    """Strict JSON (indented, NumPy values converted, non-finite numbers as null)."""
    Path(path).write_text(json.dumps(jsonable(data), indent=2, allow_nan=False) + "\n")


def write_file_whole(path: str | Path, data: bytes) -> None:
    """``data`` into ``path``, whole or not at all: written to a temporary file beside it, then
    renamed. A full disk raises ENOSPC naming ``path`` and the bytes it needed (a library writing
    straight into the file, HDF5 or zip, left half-closed objects that printed tracebacks or
    crashed at exit after the command's message)."""
    path = Path(path)
    temporary = path.parent / f".{path.name}.{os.getpid()}.tmp"
    try:
        with open(temporary, "wb") as handle:
            handle.write(data)
        os.replace(temporary, path)
    except BaseException as exc:
        temporary.unlink(missing_ok=True)
        if isinstance(exc, OSError) and exc.errno == errno.ENOSPC:
            raise DiskFull(path, len(data)) from None
        raise
