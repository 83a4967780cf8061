"""An advisory lock on an output folder: one fewear command writes a folder at a time.

The lock is ``OUT/.fewear-lock``, held with ``flock(2)`` for the life of the command and holding
its owner (pid, host, command, start time) for the message another command gets. The kernel
drops an ``flock`` when its owner dies, however it dies (``kill -9`` too), so a lock file that
can be locked is stale: its recorded owner ended without removing it, and the lock is taken
over with a note. Where ``flock`` is not available (some network file systems), a lock file
whose owner runs on this host is held; one whose pid is gone is stale.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import socket
import time
from dataclasses import dataclass
from pathlib import Path

from fewear.errors import FewearInputError

LOCK_NAME = ".fewear-lock"
MAX_OWNER_BYTES = 4096
"""An owner record is a line of JSON; more is no lock file of fewear's."""


class FolderInUse(FewearInputError):
    """The folder is locked by another running command."""


@dataclass
class FolderLock:
    """A held lock: its file and descriptor; ``stale_note``: the owner of a stale lock taken
    over ('' if none)."""

    path: Path
    descriptor: int
    stale_note: str = ""

    def release(self) -> None:
        """Remove the lock file, then drop the lock (in this order: a command waiting on the
        removed file sees it gone and locks a new one)."""
        try:
            self.path.unlink(missing_ok=True)
        finally:
            os.close(self.descriptor)


def lock_folder(folder: str | Path, command: str) -> FolderLock:
    """Lock ``folder`` (an existing folder) for ``command``, or raise :class:`FewearInputError`
    naming the process that holds it."""
    path = Path(folder) / LOCK_NAME
    while True:
        try:
            descriptor = os.open(path, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW, 0o644)
        except OSError as exc:
            raise FewearInputError(
                f"cannot lock output folder {folder} ({path}: {exc.strerror or exc})") from None
        try:
            held = _try_flock(descriptor)
            owner = _read_owner(descriptor)
            if held is None:  # no flock here: the recorded owner decides
                held = not _owner_alive(owner)
            if not held:
                elsewhere = owner.get("host") not in (None, socket.gethostname())
                raise FolderInUse(
                    f"{folder} is in use by {describe_owner(owner)}; wait until it ends, or "
                    "choose another --out" + (f" (if it has ended, delete {path})"
                                              if elsewhere else ""))
            if not _same_file(descriptor, path):
                os.close(descriptor)  # its owner removed it while we locked: lock the new one
                continue
            _write_owner(descriptor, command)
        except BaseException:
            _close_quietly(descriptor)
            raise
        note = f"took over the lock of {describe_owner(owner)}, which ended without releasing it" \
            if owner else ""
        return FolderLock(path, descriptor, note)


def describe_owner(owner: dict) -> str:
    """'pid N on HOST (fewear COMMAND, started TIME)' from an owner record (parts it lacks
    left out)."""
    text = f"pid {owner.get('pid', '?')}"
    if owner.get("host") and owner.get("host") != socket.gethostname():
        text += f" on {owner['host']}"
    details = []
    if owner.get("command"):
        details.append(f"fewear {owner['command']}")
    if isinstance(owner.get("started"), (int, float)):
        details.append("started " + time.strftime("%Y-%m-%d %H:%M:%S",
                                                  time.localtime(owner["started"])))
    return text + (f" ({', '.join(details)})" if details else "")


def _try_flock(descriptor: int) -> bool | None:
    """True: locked; False: another process holds it; None: this file system has no flock."""
    try:
        fcntl.flock(descriptor, fcntl.LOCK_EX | fcntl.LOCK_NB)
    except OSError as exc:
        if exc.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
            return False
        if exc.errno in (errno.ENOLCK, errno.EOPNOTSUPP, errno.ENOSYS, errno.EINVAL):
            return None
        raise
    return True


def _read_owner(descriptor: int) -> dict:
    """The owner record in the lock file ({} if empty or not one of fewear's)."""
    try:
        os.lseek(descriptor, 0, os.SEEK_SET)
        owner = json.loads(os.read(descriptor, MAX_OWNER_BYTES) or b"{}")
    except (OSError, ValueError):
        return {}
    return owner if isinstance(owner, dict) else {}


def _write_owner(descriptor: int, command: str) -> None:
    record = json.dumps({"pid": os.getpid(), "host": socket.gethostname(), "command": command,
                         "started": time.time()}).encode() + b"\n"
    os.ftruncate(descriptor, 0)
    os.pwrite(descriptor, record, 0)


def _owner_alive(owner: dict) -> bool:
    """Whether the recorded owner still runs (a process on another host: assumed so)."""
    pid = owner.get("pid")
    if not isinstance(pid, int) or pid <= 0:
        return False
    if owner.get("host") not in (None, socket.gethostname()):
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except PermissionError:
        return True
    return pid != os.getpid()


def _same_file(descriptor: int, path: Path) -> bool:
    try:
        return os.fstat(descriptor).st_ino == os.stat(path).st_ino
    except FileNotFoundError:
        return False


def _close_quietly(descriptor: int) -> None:
    try:
        os.close(descriptor)
    except OSError:
        pass
