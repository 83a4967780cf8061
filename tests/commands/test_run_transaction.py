"""`fewear run --overwrite` as a transaction (issue 57): the earlier complete run is kept until
the new one completes, whatever interrupts it (SIGTERM, SIGHUP, kill -9), and the next command
restores or cleans what a killed one left, saying so."""

import hashlib
import os
import shutil
import signal
import subprocess
import sys

import pytest

from tests.loop.test_wear_loop import run, write_config


def contents(folder):
    """Every file under ``folder`` (hidden ones too) with its SHA-256."""
    return {str(path.relative_to(folder)): hashlib.sha256(path.read_bytes()).hexdigest()
            for path in sorted(folder.rglob("*")) if path.is_file()}


@pytest.fixture(scope="module")
def complete_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("complete")
    assert run(write_config(folder), folder / "out") == 0
    return folder / "out"


def start_run(config, out, *extra):
    """`fewear run` in its own process group (as a terminal starts it), stderr piped."""
    return subprocess.Popen(
        [sys.executable, "-m", "fewear.cli", "run", "--config", str(config), "--out", str(out),
         *extra], stderr=subprocess.PIPE, text=True, start_new_session=True)


def signal_at(process, marker: str, signum) -> str:
    """Send ``signum`` to the process group when a stderr line holds ``marker``; all stderr."""
    err = ""
    for line in process.stderr:
        err += line
        if marker in line:
            os.killpg(process.pid, signum)
            break
    err += process.stderr.read()
    process.wait(timeout=120)
    return err


def longer_config(folder):
    config = write_config(folder, name="longer.toml")
    config.write_text(config.read_text().replace("total_cycles = 4000", "total_cycles = 6000"))
    return config


@pytest.mark.parametrize("signum", [signal.SIGTERM, signal.SIGHUP], ids=["sigterm", "sighup"])
def test_an_interrupted_overwrite_keeps_the_earlier_run_beside_the_new_one(tmp_path,
                                                                          complete_run, signum):
    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    earlier = contents(out)
    process = start_run(longer_config(tmp_path), out, "--overwrite")
    err = signal_at(process, "block 1,", signum)
    assert process.returncode == 128 + signum, err
    assert "Traceback" not in err and "PETSC" not in err.upper().replace("PETSC4PY", ""), err
    last = err.strip().splitlines()[-1]
    assert last.startswith(f"fewear: interrupted: {signal.Signals(signum).name}: "), err
    assert "keeps rigid at 2,000/6,000 cycles" in last and "the earlier run stays in" in last
    [aside] = [path for path in out.iterdir() if path.name.startswith(".fewear-")]
    assert aside.name.startswith(".fewear-previous-")
    assert contents(aside) == earlier  # the complete earlier run, whole
    # going back to it: delete the new run's checkpoint; the next command restores it
    shutil.rmtree(out / "fewear-checkpoint")
    assert run(write_config(tmp_path), out) == 2  # restored, then refused: it holds a run
    assert contents(out) == earlier


def test_a_resumed_overwrite_removes_the_earlier_run_when_it_completes(tmp_path, complete_run,
                                                                       capsys):
    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    process = start_run(longer_config(tmp_path), out, "--overwrite")
    signal_at(process, "block 1,", signal.SIGTERM)
    assert run(longer_config(tmp_path), out, "--resume") == 0
    err = capsys.readouterr().err
    assert "keeps the earlier run that the unfinished run in the folder is to replace" in err
    assert not [path for path in out.iterdir() if path.name.startswith(".fewear-")]
    assert '"total_cycles": 6000' in (out / "summary.json").read_text()


def test_the_leftovers_of_a_killed_overwrite_are_restored_and_said(tmp_path, complete_run,
                                                                  capsys):
    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    earlier = contents(out)
    process = start_run(longer_config(tmp_path), out, "--overwrite")
    signal_at(process, "meshing the bushing", signal.SIGKILL)
    left = sorted(path.name.rsplit("-", 1)[0] for path in out.iterdir())
    assert left == [".fewear", ".fewear-previous", ".fewear-staging"], left  # lock, aside, stage
    assert run(write_config(tmp_path), out) == 2
    err = capsys.readouterr().err
    assert f"took over the lock of pid {process.pid}" in err
    assert "removed .fewear-staging-" in err and "restored the earlier run" in err
    assert "holds an earlier run" in err.strip().splitlines()[-1]
    assert contents(out) == earlier


def test_a_second_run_into_a_folder_being_written_is_refused(tmp_path, capsys):
    out = tmp_path / "out"
    process = start_run(longer_config(tmp_path), out)
    try:
        for line in process.stderr:
            if "meshing the bushing" in line:
                break
        assert run(write_config(tmp_path), out, "--overwrite") == 2
        err = capsys.readouterr().err
        assert err.startswith(f"fewear: error: {out} is in use by pid {process.pid} "
                              "(fewear run, started "), err
    finally:
        os.killpg(process.pid, signal.SIGTERM)
        process.communicate(timeout=120)


def test_an_overwrite_interrupted_before_its_first_block_says_the_earlier_run_is_kept(
        tmp_path, complete_run, monkeypatch, capsys):
    import fewear.commands.run

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    earlier = contents(out)
    monkeypatch.setattr(fewear.commands.run, "new_bushing", interrupt)
    assert run(longer_config(tmp_path), out, "--overwrite") == 130
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert last == (f"fewear: interrupted: Ctrl-C: no wear block had finished; the earlier run in "
                    f"{out} is kept as it was; start the new run again with: fewear run "
                    f"--overwrite --config {tmp_path / 'longer.toml'} --out {out}")
    assert contents(out) == earlier


def test_a_run_into_another_commands_folder_names_that_command(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "profiles.csv").write_text("x_m,depth_m\n")
    (out / "summary.json").write_text('{"max_depth_m": 1e-6}')
    assert run(write_config(tmp_path), out) == 2
    err = capsys.readouterr().err
    assert "holds the results of `fewear scar` (summary.json, profiles.csv)" in err
    assert "--resume" not in err


def test_a_full_disk_during_an_overwrite_keeps_both_runs(tmp_path, complete_run, monkeypatch,
                                                        capsys):
    import errno

    import fewear.loop.outputs

    def full(folder, *args):
        raise OSError(errno.ENOSPC, "No space left on device", str(folder / "summary.json"))

    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    earlier = contents(out)
    monkeypatch.setattr(fewear.loop.outputs, "write_run_outputs", full)
    assert run(write_config(tmp_path), out, "--overwrite") == 2
    last = capsys.readouterr().err.strip().splitlines()[-1]
    assert "No space left on device" in last and "keeps rigid at 4,000/4,000 cycles" in last
    assert "the earlier run stays in" in last
    [aside] = [path for path in out.iterdir() if path.name.startswith(".fewear-previous-")]
    assert contents(aside) == earlier
