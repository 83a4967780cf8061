"""The output folder's lock (fewear/io/lock.py): a second process is refused with the owner's
pid, a lock whose owner died (kill -9) is taken over with a note, and none is left behind."""

import json
import os
import signal
import subprocess
import sys

import pytest

from fewear.cli import main
from fewear.io.lock import LOCK_NAME, FolderInUse, lock_folder

HOLDER = """
import sys, time
from fewear.io.lock import lock_folder
lock_folder(sys.argv[1], "run")
print("locked", flush=True)
time.sleep(60)
"""


@pytest.fixture
def holder(tmp_path):
    """Another process that holds the lock of ``tmp_path / 'out'``."""
    out = tmp_path / "out"
    out.mkdir()
    process = subprocess.Popen([sys.executable, "-c", HOLDER, str(out)], stdout=subprocess.PIPE,
                               text=True)
    assert process.stdout.readline().strip() == "locked"
    yield out, process
    process.kill()
    process.wait(timeout=10)


def dead_pid() -> int:
    """The pid of a process that has ended (and been reaped)."""
    process = subprocess.Popen(["true"])
    process.wait()
    return process.pid


def test_a_second_process_is_refused_with_the_owners_pid(holder):
    out, process = holder
    with pytest.raises(FolderInUse, match=rf"is in use by pid {process.pid} \(fewear run, "
                                          r"started \d{4}-\d\d-\d\d"):
        lock_folder(out, "contact")


def test_the_command_line_names_the_process_that_holds_the_folder(holder, capsys):
    out, process = holder
    before = sorted(path.name for path in out.iterdir())
    assert main(["dynamics", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fewear: error: {out} is in use by pid {process.pid} "), err
    assert sorted(path.name for path in out.iterdir()) == before  # its lock file untouched


def test_the_lock_of_a_killed_process_is_taken_over_with_a_note(holder):
    out, process = holder
    process.send_signal(signal.SIGKILL)
    process.wait(timeout=10)
    assert json.loads((out / LOCK_NAME).read_text())["pid"] == process.pid  # left behind
    lock = lock_folder(out, "contact")
    assert f"took over the lock of pid {process.pid}" in lock.stale_note
    assert json.loads((out / LOCK_NAME).read_text())["pid"] == os.getpid()
    lock.release()
    assert not (out / LOCK_NAME).exists()


def test_a_stale_lock_file_is_reported_and_removed_by_the_next_command(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    pid = dead_pid()
    (out / LOCK_NAME).write_text(json.dumps({"pid": pid, "host": os.uname().nodename,
                                             "command": "run", "started": 0.0}))
    assert main(["diagnose", str(tmp_path / "missing.csv"), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"fewear diagnose: took over the lock of pid {pid} (fewear run, started " in err
    assert list(out.iterdir()) == []


def test_a_lock_is_released_when_its_command_ends(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["diagnose", str(tmp_path / "missing.csv"), "--out", str(out)]) == 2
    assert "missing.csv" in capsys.readouterr().err
    assert not out.exists()  # made for the command, removed again (nothing was written)
    lock_folder(tmp_path, "run").release()
    lock_folder(tmp_path, "run").release()


@pytest.mark.parametrize("owner, in_use", [("live", True), ("dead", False), ("elsewhere", True)])
def test_without_flock_the_recorded_owner_decides(tmp_path, monkeypatch, owner, in_use):
    """A file system without flock (some network ones): the lock is held while its recorded
    owner runs; one on another host is assumed to run (and the message says how to clear it)."""
    import fewear.io.lock

    monkeypatch.setattr(fewear.io.lock, "_try_flock", lambda descriptor: None)
    sleeper = subprocess.Popen(["sleep", "30"])
    try:
        pid = {"live": sleeper.pid, "dead": dead_pid(), "elsewhere": 12345}[owner]
        host = "another-host" if owner == "elsewhere" else os.uname().nodename
        (tmp_path / LOCK_NAME).write_text(json.dumps({"pid": pid, "host": host}))
        if in_use:
            with pytest.raises(FolderInUse, match=f"in use by pid {pid}") as raised:
                lock_folder(tmp_path, "run")
            assert ("delete" in str(raised.value)) == (owner == "elsewhere")
        else:
            lock = lock_folder(tmp_path, "run")
            assert f"took over the lock of pid {pid}" in lock.stale_note
            lock.release()
    finally:
        sleeper.kill()
        sleeper.wait()
