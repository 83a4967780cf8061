"""Inputs that are not regular files, or too large, refused before they are read
(fewear/io/text.py): a FIFO blocked the reader for good, a huge file filled the memory."""

import os
import subprocess
import sys

import pytest

from fewear.cli import main
from fewear.io.limits import MAX_CONFIG_FILE_BYTES, MAX_DATA_FILE_BYTES
from fewear.io.text import read_text_file


def fewear(*args, cwd):
    """The command line in its own process, killed if it blocks (the failure these tests
    guard against); (exit status, stderr)."""
    done = subprocess.run([sys.executable, "-m", "fewear.cli", *map(str, args)], cwd=cwd,
                          capture_output=True, text=True, timeout=60,
                          env={**os.environ, "PYTHONPATH": os.getcwd()})
    return done.returncode, done.stderr


@pytest.mark.parametrize("command", [
    ["run", "--config", "{fifo}"], ["scar", "--config", "{fifo}"], ["diagnose", "{fifo}"]],
    ids=["run-config", "scar-config", "diagnose-data"])
def test_a_fifo_is_refused_not_read(tmp_path, command):
    fifo = tmp_path / "input.fifo"
    os.mkfifo(fifo)
    status, err = fewear(*[part.format(fifo=fifo) for part in command], "--out", "out",
                         cwd=tmp_path)
    assert status == 2, err
    assert err.strip().splitlines()[-1].endswith(
        f"{fifo} is a FIFO (named pipe); expected a regular file"), err
    assert "Traceback" not in err and not (tmp_path / "out").exists()


def test_a_folder_or_a_device_is_refused(tmp_path, capsys):
    assert main(["dynamics", "--config", str(tmp_path), "--out", str(tmp_path / "o")]) == 2
    assert f"config file {tmp_path} is a folder; expected a regular file" in \
        capsys.readouterr().err
    with pytest.raises(Exception, match="/dev/zero is a character device; expected a regular"):
        read_text_file("/dev/zero", "measured data")


@pytest.mark.parametrize("what, limit", [("config file", MAX_CONFIG_FILE_BYTES),
                                         ("measured data", MAX_DATA_FILE_BYTES)])
def test_a_file_beyond_its_bound_is_refused_naming_the_bound(tmp_path, what, limit):
    path = tmp_path / "big"
    with open(path, "wb") as handle:
        handle.truncate(limit + 1)  # sparse: no disk space, no time
    with pytest.raises(Exception, match=f"{what} {path} has {limit + 1:,} bytes; a {what} has "
                                        f"at most {limit:,} bytes"):
        read_text_file(path, what)


def test_an_oversize_config_is_refused_at_the_command_line(tmp_path, capsys):
    config = tmp_path / "huge.toml"
    config.write_text("# padding\n" * (MAX_CONFIG_FILE_BYTES // 10 + 1))
    assert main(["run", "--config", str(config), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fewear: error: config file {config} has 1,000,010 bytes; a config "
                          "file has at most 1,000,000 bytes"), err


def test_a_checkpoint_that_is_a_fifo_is_named_so(tmp_path):
    folder = tmp_path / "out" / "fewear-checkpoint"
    folder.mkdir(parents=True)
    os.mkfifo(folder / "rigid.npz")
    config = tmp_path / "rigid.toml"
    config.write_text('[wear_loop]\nrod_models = ["rigid"]\n')
    status, err = fewear("run", "--config", config, "--out", "out", "--resume", cwd=tmp_path)
    assert status == 2, err
    assert (f"checkpoint {folder / 'rigid.npz'} is unreadable (it is a FIFO (named pipe), not a "
            "regular file)") in err, err


def test_config_out_names_a_folder_as_a_folder(tmp_path, capsys):
    assert main(["config", "--out", str(tmp_path)]) == 2
    assert f"cannot write {tmp_path}: it is a folder" in capsys.readouterr().err


def test_a_plain_file_named_like_the_checkpoint_folder_is_refused_at_once(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "fewear-checkpoint").write_text("not a folder")
    config = tmp_path / "rigid.toml"
    config.write_text('[wear_loop]\nrod_models = ["rigid"]\n')
    assert main(["run", "--config", str(config), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert err == (f"fewear: error: {out / 'fewear-checkpoint'} is a file, not the checkpoint "
                   "folder of a run; move it away, or choose another --out\n")
