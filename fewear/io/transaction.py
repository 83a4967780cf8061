"""Output folders as transactions: one command at a time, nothing of a complete result lost.

Every command that writes an output folder runs inside :func:`output_folder`:

- the folder is locked (:mod:`fewear.io.lock`); a second command on it is refused, naming the
  process that holds it;
- what a killed command left is cleaned or restored first, and said on stderr: its staging
  folder (``.fewear-staging-*``, never a complete result) is removed; an earlier run set aside
  by ``fewear run --overwrite`` (``.fewear-previous-*``) is put back when no run replaced it,
  kept while an unfinished run that is to replace it waits to be resumed, and removed once that
  run is complete;
- a folder holding another command's results is refused unless ``--overwrite``; then the other
  command's files are removed once this command has written its own, not before.

:func:`run_replaced` is ``fewear run``'s part: the earlier run it replaces stays set aside until
the new run completes, so an interruption at any moment (Ctrl-C, SIGTERM, SIGHUP, ``kill -9``,
a full disk) leaves the earlier run, or a resumable new one beside it.
"""

from __future__ import annotations

import json
import shutil
import sys
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path

from fewear.errors import FewearInputError, Terminated, add_interrupt_note, set_interrupt_note
from fewear.io.lock import FolderInUse, lock_folder
from fewear.io.signals import signals_held

STAGING_PREFIX = ".fewear-staging-"
PREVIOUS_PREFIX = ".fewear-previous-"
CHECKPOINT = "fewear-checkpoint"
SUMMARY = "summary.json"
COMMAND_FILES = {
    "run": (CHECKPOINT, "wear_profile.csv", "max_wear.csv", "wear_profiles.png", "max_wear.png",
            "worn_bushing.png"),
    "contact": ("contact.csv", "bushing.xdmf", "bushing.h5", "pressure.png"),
    "dynamics": ("joint_history.csv", "forces.png", "orbit.png"),
    "scar": ("profiles.csv", "predicted_nodes.csv", "scar.png"),
    "diagnose": ("diagnosis.json", "report.md", "extended.toml", "extended_wear.toml"),
}
"""The files each command writes besides ``summary.json`` (the run's ``<case>.xdmf`` and ``.h5``
too): the first of each that is found names the command that made a folder without a
``command`` key in its summary (folders of earlier versions)."""

_running: list[str | None] = [None]


def current_command() -> str | None:
    """The command whose output folder is open (:func:`output_folder`), None outside one."""
    return _running[0]


@contextmanager
def output_folder(out: str | Path, command: str, overwrite: bool = False, comm=None,
                  required: bool = True) -> Iterator[None]:
    """The command ``command`` writes ``out`` (made if missing) alone: locked, cleaned of what a
    killed command left, refused if it holds another command's results (unless ``overwrite``:
    they are removed after this command succeeds). ``comm``: an mpi4py communicator under MPI
    (rank 0 does the work, every rank raises its errors). ``required=False`` (``fewear plot``,
    which reads a folder it may not write): a folder that cannot be locked is used unlocked,
    a missing one left to the command."""
    rank = 0 if comm is None else comm.rank
    state, error = None, None
    if rank == 0:
        try:
            state = _open(out, command, overwrite, required)
        except FewearInputError as exc:
            error = str(exc)
        except OSError as exc:  # said on every rank, not raised on rank 0 alone
            where = f" ({exc.filename})" if exc.filename else ""
            error = f"cannot prepare output folder {out}{where}: {exc.strerror or exc}"
    if comm is not None:
        error = comm.bcast(error, root=0)
    if error is not None:
        raise FewearInputError(error)
    _running[0] = command
    try:
        yield
        if state is not None:
            _remove_unchanged(state["replaced"])
    finally:
        _running[0] = None
        if state is not None:
            _close(state)


def _open(out: str | Path, command: str, overwrite: bool, required: bool) -> dict | None:
    if not str(out).strip():
        raise FewearInputError(f"--out {str(out)!r}: an empty folder name; give the output "
                               "folder (e.g. --out results)")
    out = Path(out)
    if not required and not out.is_dir():
        return None
    _check_out_path(out)
    created = not out.exists()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise FewearInputError(f"cannot write to output folder {out}: "
                               f"{exc.strerror or exc}") from None
    try:
        lock = lock_folder(out, command)
    except FewearInputError as exc:
        if created:
            _remove_if_empty(out)
        if required or isinstance(exc, FolderInUse):
            raise
        return None
    state = {"out": out, "lock": lock, "created": created, "replaced": []}
    try:
        if lock.stale_note:
            say(command, lock.stale_note)
        for note in recover(out):
            say(command, note)
        others = results_of_other_commands(out, command)
        if others and not overwrite:
            named = "; ".join(f"`fewear {name}` ({', '.join(path.name for path in paths[:4])})"
                              for name, paths in others.items())
            raise FewearInputError(
                f"output folder {out} holds the results of {named}; replace them with "
                f"`fewear {command} --overwrite`, or choose another --out")
        if "run" in others:  # with it goes the earlier run it was to replace
            others["run"] += sorted(out.glob(PREVIOUS_PREFIX + "*"))
        state["replaced"] = [(path, _identity(path)) for paths in others.values()
                             for path in paths]
    except BaseException:
        _close(state)
        raise
    return state


def _check_out_path(out: Path) -> None:
    if CHECKPOINT in out.resolve().parts:
        raise FewearInputError(f"--out {out} is inside the checkpoint folder of a run "
                               f"({CHECKPOINT}); give a folder outside it")
    if out.exists() and not out.is_dir():
        raise FewearInputError(f"output folder {out} exists and is not a folder")


def _close(state: dict) -> None:
    state["lock"].release()
    if state["created"]:
        _remove_if_empty(state["out"])


def _remove_if_empty(folder: Path) -> None:
    try:
        folder.rmdir()
    except OSError:
        pass  # not empty: it holds results


def say(command: str, note: str) -> None:
    print(f"fewear {command}: {note}", file=sys.stderr, flush=True)


def recover(out: Path) -> list[str]:
    """Clean or restore what a command killed in ``out`` left (the module docstring); the notes
    saying what was done."""
    notes = []
    for staging in sorted(out.glob(STAGING_PREFIX + "*")):
        shutil.rmtree(staging, ignore_errors=True)
        notes.append(f"removed {staging.name} in {out}: the unfinished outputs of a command "
                     "that was killed (the folder's results are as they were before it)")
    for aside in sorted(out.glob(PREVIOUS_PREFIX + "*")):
        if not aside.is_dir():
            continue
        if (out / SUMMARY).is_file() and folder_commands(out).get("run"):
            shutil.rmtree(aside, ignore_errors=True)
            notes.append(f"removed {aside.name} in {out}: an earlier run set aside by `fewear "
                         "run --overwrite`, replaced by the complete run now in the folder")
        elif unfinished_run(out):
            notes.append(f"{aside.name} in {out} keeps the earlier run that the unfinished run "
                         "in the folder is to replace; it is removed when that run completes "
                         f"(`fewear run --resume`), and put back if you delete {CHECKPOINT}")
        else:
            restored = restore(aside, out)
            notes.append(f"restored the earlier run in {out} ({restored}) from {aside.name}, "
                         "where a `fewear run --overwrite` that was killed had set it aside")
    return notes


def unfinished_run(out: Path) -> bool:
    """Whether ``out`` holds a run's checkpoint with at least one saved case."""
    return (out / CHECKPOINT).is_dir() and any((out / CHECKPOINT).glob("*.npz"))


def restore(aside: Path, out: Path) -> str:
    """Move the files of ``aside`` back into ``out`` (a name taken there stays aside); their
    names, shortened."""
    names = []
    with signals_held():
        for item in sorted(aside.iterdir()):
            if not (out / item.name).exists():
                item.replace(out / item.name)
                names.append(item.name)
        _remove_if_empty(aside)
    return ", ".join(names[:4]) + (", ..." if len(names) > 4 else "") or "nothing to restore"


def folder_commands(out: Path) -> dict[str, list[Path]]:
    """command -> its files in ``out``, for every command whose results it holds: the
    ``command`` of its summary, and any command whose files (:data:`COMMAND_FILES`) are there."""
    found: dict[str, list[Path]] = {}
    summary_command = _summary_command(out / SUMMARY)
    for command, names in COMMAND_FILES.items():
        paths = [out / name for name in names if (out / name).exists()]
        if command == "run" and paths:
            paths += sorted(path for pattern in ("*.xdmf", "*.h5") for path in out.glob(pattern)
                            if path.name not in COMMAND_FILES["contact"])
        if paths or command == summary_command:
            found[command] = paths
    if (out / SUMMARY).is_file():
        if summary_command in found:
            found[summary_command].insert(0, out / SUMMARY)
        elif len(found) == 1:
            next(iter(found.values())).insert(0, out / SUMMARY)
    return found


def results_of_other_commands(out: Path, command: str) -> dict[str, list[Path]]:
    """The results in ``out`` of commands other than ``command`` (``fewear plot`` adds to a run's
    folder: it has none)."""
    if command == "plot":
        return {}
    return {name: paths for name, paths in folder_commands(out).items()
            if name != command and paths}


def _summary_command(path: Path) -> str | None:
    try:
        if not path.is_file() or path.stat().st_size > 10_000_000:
            return None
        summary = json.loads(path.read_text())
    except (OSError, ValueError):
        return None
    command = summary.get("command") if isinstance(summary, dict) else None
    return command if isinstance(command, str) else None


def _identity(path: Path) -> tuple[int, int] | None:
    try:
        status = path.stat()
    except OSError:
        return None
    return status.st_ino, status.st_mtime_ns


def _remove_unchanged(replaced: list[tuple[Path, tuple | None]]) -> None:
    """Remove the other commands' files that this command did not write over (same inode and
    time as before it)."""
    for path, identity in replaced:
        if identity is None or _identity(path) != identity:
            continue
        if path.is_dir() and not path.is_symlink():
            shutil.rmtree(path, ignore_errors=True)
        else:
            path.unlink(missing_ok=True)


@contextmanager
def run_replaced(out: str | Path, find_earlier: Callable[[Path], list[Path]], store,
                 resume: bool, overwrite: bool, start_again: str, world) -> Iterator[None]:
    """``fewear run``'s rules for an earlier run in ``out`` (``find_earlier(out)``: its files):
    refused unless ``resume`` (the same run, continued) or ``overwrite`` (set aside in
    ``.fewear-previous-*`` until this run completes, restored if it fails or is interrupted
    before it saved a block). ``store``: the run's :class:`fewear.loop.checkpoint.Checkpoint`;
    ``start_again``: the command line that starts this run anew (for the interruption note).

    A failed run leaves the folder as it found it: a new run's checkpoint is removed, a resumed
    run's stays (it is the same run); an interruption or an OS error (a full disk) keeps the
    checkpoint of the blocks done, and the earlier run beside it."""
    out = Path(out).resolve()
    error, aside = None, None
    if world.rank == 0:
        try:
            aside = _set_aside(out, find_earlier, store, resume, overwrite)
        except FewearInputError as exc:
            error = str(exc)
    error = world.bcast(error, root=0)
    if error:
        raise FewearInputError(error)
    try:
        yield
    except BaseException as exc:
        if world.rank == 0:
            _after_failure(exc, out, store, resume, aside, start_again)
        raise
    if world.rank == 0 and aside is not None:
        shutil.rmtree(aside, ignore_errors=True)


def _set_aside(out: Path, find_earlier, store, resume: bool, overwrite: bool) -> Path | None:
    """The folder that keeps the earlier run while this one runs (None: no earlier run)."""
    if store.path.exists() and not store.path.is_dir():
        raise FewearInputError(f"{store.path} is a file, not the checkpoint folder of a run; "
                               "move it away, or choose another --out")
    store.remove_temporary_files()
    kept = sorted(path for path in out.glob(PREVIOUS_PREFIX + "*") if path.is_dir())
    if resume:
        return kept[0] if kept else None
    earlier = find_earlier(out)
    if earlier and not overwrite:
        raise FewearInputError(
            f"output folder {out} holds an earlier run ("
            + ", ".join(path.name for path in earlier[:4]) + (", ..." if len(earlier) > 4 else "")
            + "); continue it with --resume, replace it with --overwrite, or choose another --out")
    if not earlier:
        return None
    with signals_held():  # all of the earlier run moves, or none of it
        if kept:  # the complete run is aside already; the folder's is an unfinished one
            for path in earlier:
                shutil.rmtree(path) if path.is_dir() else path.unlink()
            return kept[0]
        aside = Path(tempfile.mkdtemp(prefix=PREVIOUS_PREFIX, dir=out))
        for path in earlier:
            path.replace(aside / path.name)
    return aside


def _after_failure(exc: BaseException, out: Path, store, resume: bool, aside: Path | None,
                   start_again: str) -> None:
    # an interruption, or the OS refusing a write (a full disk), is no fault of the run: its
    # checkpoint stays, to be resumed
    interrupted = isinstance(exc, (KeyboardInterrupt, Terminated, OSError))
    with signals_held():
        if resume or (interrupted and store.saved_cycles()):
            if aside is not None:
                add_interrupt_note(
                    f"the earlier run stays in {aside} until this one completes (to go back to "
                    f"it instead, delete {store.path}: the next fewear command restores it)")
            return
        shutil.rmtree(store.path, ignore_errors=True)  # this run's, not worth keeping
        if aside is not None:
            restore(aside, out)
            shutil.rmtree(aside, ignore_errors=True)
            set_interrupt_note(lambda: (
                f"no wear block had finished; the earlier run in {out} is kept as it was; "
                f"start the new run again with: {start_again}"))
