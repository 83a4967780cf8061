"""`fewear run` interrupted (Ctrl-C, SIGTERM), failing, or pointed at a folder that holds another
run (issue 20): one line saying what was kept and how to go on, no staging folder left, and no
earlier result lost."""

import hashlib
import os
import shutil
import signal
import subprocess
import sys

import pytest

from fewear.cli import main
from tests.loop.test_wear_loop import run, write_config


def contents(folder):
    """Every file under ``folder`` (hidden ones too) with its SHA-256."""
    return {str(path.relative_to(folder)): hashlib.sha256(path.read_bytes()).hexdigest()
            for path in sorted(folder.rglob("*")) if path.is_file()}


@pytest.mark.parametrize("signum", [pytest.param(signal.SIGINT, marks=pytest.mark.slow),
                                    signal.SIGTERM], ids=["ctrl-c", "sigterm"])
def test_an_interrupted_run_says_what_it_kept_and_leaves_no_staging_folder(tmp_path, signum):
    config = write_config(tmp_path)
    config.write_text(config.read_text().replace("total_cycles = 4000", "total_cycles = 8000"))
    out = tmp_path / "out"
    process = subprocess.Popen(
        [sys.executable, "-m", "fewear.cli", "run", "--config", str(config), "--out", str(out)],
        stderr=subprocess.PIPE, text=True, start_new_session=True,
        preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    err = ""
    for line in process.stderr:
        err += line
        if "block 1," in line:
            os.killpg(process.pid, signum)  # as a terminal does: the whole process group
            break
    err += process.stderr.read()
    status = process.wait(timeout=120)
    assert status == (130 if signum == signal.SIGINT else 143), err
    assert "Traceback" not in err
    last = err.strip().splitlines()[-1]
    assert last.startswith("fewear: interrupted: "), err
    assert "keeps rigid at 2,000/8,000 cycles" in last and "fewear run --resume" in last
    assert [path.name for path in out.iterdir()] == ["fewear-checkpoint"]  # no .fewear-staging-*
    assert run(config, out, "--resume") == 0
    assert not [path for path in out.iterdir() if path.name.startswith(".fewear-")]


def test_an_interruption_before_the_first_block_keeps_nothing(tmp_path, monkeypatch, capsys):
    import fewear.commands.run

    def interrupt(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(fewear.commands.run, "new_bushing", interrupt)
    assert run(write_config(tmp_path), tmp_path / "out") == 130
    assert "nothing was kept" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


@pytest.fixture(scope="module")
def complete_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("complete")
    assert run(write_config(folder), folder / "out") == 0
    return folder / "out"


def test_a_run_refuses_a_folder_holding_another_run(tmp_path, complete_run, capsys):
    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    before = contents(out)
    assert run(write_config(tmp_path), out) == 2
    err = capsys.readouterr().err
    assert "holds an earlier run" in err and "--overwrite" in err and "--resume" in err
    assert contents(out) == before


def test_a_failed_overwrite_restores_the_earlier_run(tmp_path, complete_run, capsys):
    """The earlier run stays resumable and extendable: a failed run (worn through the wall in its
    first block) puts it back as it was."""
    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    (out / "notes.txt").write_text("the user's own file")
    before = contents(out)
    config = write_config(tmp_path)
    config.write_text(config.read_text().replace(
        'coefficient_model = "constant"', 'coefficient_model = "constant"\n'
        'constant_k_m2_N = 1e-9'))
    assert run(config, out, "--overwrite") == 2
    assert "worn through" in capsys.readouterr().err
    assert contents(out) == before


def test_a_failed_run_into_a_new_folder_leaves_nothing(tmp_path, capsys):
    config = write_config(tmp_path)
    config.write_text(config.read_text().replace(
        'coefficient_model = "constant"', 'coefficient_model = "constant"\n'
        'constant_k_m2_N = 1e-9'))
    assert run(config, tmp_path / "new") == 2
    assert not (tmp_path / "new").exists()
    (tmp_path / "mine").mkdir()
    assert run(config, tmp_path / "mine") == 2
    assert list((tmp_path / "mine").iterdir()) == []
    capsys.readouterr()


@pytest.mark.parametrize("content", [b"", b"PK\x03\x04 not a zip", b"\x80\x04K."],
                         ids=["empty", "truncated-zip", "pickle"])
def test_a_broken_checkpoint_names_its_cause(tmp_path, capsys, content):
    folder = tmp_path / "out" / "fewear-checkpoint"
    folder.mkdir(parents=True)
    (folder / "rigid.npz").write_bytes(content)
    assert main(["run", "--config", str(write_config(tmp_path)), "--out", str(tmp_path / "out"),
                 "--resume"]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fewear: error: --resume: checkpoint") and "unreadable" in err
    assert "pickled" not in err
    assert "empty (0 bytes)" in err if not content else True


def test_overwrite_replaces_the_earlier_run(tmp_path, complete_run):
    out = tmp_path / "out"
    shutil.copytree(complete_run, out)
    config = write_config(tmp_path)
    config.write_text(config.read_text().replace("total_cycles = 4000", "total_cycles = 2000"))
    assert run(config, out, "--overwrite") == 0
    assert "2000" in (out / "summary.json").read_text()
    assert not [path for path in out.iterdir() if path.name.startswith(".fewear-")]
    assert sorted(path.name for path in (out / "fewear-checkpoint").iterdir()) == [
        "rigid-rod_slider-mesh-00000.npy", "rigid-rod_slider-mesh-00001.npy", "rigid.npz"]


def test_a_full_disk_keeps_the_checkpoint_and_says_how_to_resume(tmp_path, monkeypatch, capsys):
    import errno

    import fewear.loop.outputs

    def full(folder, *args):
        raise OSError(errno.ENOSPC, "No space left on device", str(folder / "summary.json"))

    monkeypatch.setattr(fewear.loop.outputs, "write_run_outputs", full)
    config = write_config(tmp_path)
    assert run(config, tmp_path / "out") == 2
    err = capsys.readouterr().err
    assert "No space left on device" in err and "keeps rigid at 4,000/4,000 cycles" in err
    assert "fewear run --resume" in err and err.count("fewear: error:") == 1
    monkeypatch.undo()
    assert run(config, tmp_path / "out", "--resume") == 0
    assert (tmp_path / "out" / "summary.json").exists()


def test_resume_and_overwrite_together_are_refused(tmp_path, capsys):
    assert run(write_config(tmp_path), tmp_path / "out", "--resume", "--overwrite") == 2
    assert "choose one" in capsys.readouterr().err


@pytest.mark.slow
@pytest.mark.mpi
def test_ctrl_c_to_mpirun_is_named_as_the_sigterm_the_ranks_get(tmp_path):
    """Ctrl-C to `mpirun -n 2 fewear run` (SIGINT to mpirun; the ranks sit in their own
    process groups): mpirun sends the ranks SIGTERM, named as what mpirun sends on Ctrl-C too;
    the checkpoint is kept and said (mpirun itself exits with 1)."""
    from tests.mpi import MPI_ENV, mpirun_or_skip

    config = write_config(tmp_path)
    config.write_text(config.read_text().replace("total_cycles = 4000", "total_cycles = 40000"))
    process = subprocess.Popen(
        [mpirun_or_skip(), "-n", "2", sys.executable, "-m", "fewear.cli", "run", "--config",
         str(config), "--out", str(tmp_path / "out")],
        stderr=subprocess.PIPE, text=True, start_new_session=True, env={**os.environ, **MPI_ENV})
    err = ""
    for line in process.stderr:
        err += line
        if "block 1," in line:
            process.send_signal(signal.SIGINT)
            break
    err += process.stderr.read()
    assert process.wait(timeout=120) == 1, err
    last = err.strip().splitlines()[-1]
    assert last.startswith("fewear: interrupted: SIGTERM (which mpirun also sends on Ctrl-C): "
                           "the checkpoint "), err
    assert "fewear run --resume" in last
