"""Hostile but fair input at the command line's edge (issue 20): every failure a user can cause
is one ``fewear: error:`` line naming the file, key or column, the bad value (shortened) and
what is allowed; exit status 2; no traceback; nothing written."""

import subprocess
import sys

import pytest

from fewear.cli import main
from fewear.errors import FewearInputError, one_line, shorten


def cli(*args, cwd=None):
    """``fewear ARGS`` in a fresh process: (exit status, stderr)."""
    process = subprocess.run([sys.executable, "-m", "fewear.cli", *map(str, args)], cwd=cwd,
                             capture_output=True, text=True, timeout=120)
    return process.returncode, process.stderr


def assert_one_error_line(status, err, *needles):
    assert status == 2, err
    assert "Traceback" not in err
    lines = [line for line in err.splitlines() if line.startswith("fewear: error:")]
    assert len(lines) == 1, err
    for needle in needles:
        assert needle in lines[0], lines[0]
    return lines[0]


@pytest.mark.parametrize("content", [b"# caf\xe9\n[mesh]\nradial_element_count = 4\n",
                                     bytes(range(256)) * 2], ids=["latin-1", "binary"])
def test_a_config_that_is_not_utf8_is_named_with_its_line(tmp_path, capsys, content):
    path = tmp_path / "bad.toml"
    path.write_bytes(content)
    for command in (["config"], ["dynamics"], ["run"], ["contact", "--force", "0", "1"]):
        if command == ["config"]:
            continue  # prints the defaults: reads no config
        assert main([*command, "--config", str(path), "--out", str(tmp_path / "out")]) == 2
        line = assert_one_error_line(2, capsys.readouterr().err, str(path), "UTF-8", " line ")
        assert len(line) < 300
    assert not (tmp_path / "out").exists()


def test_a_long_string_value_is_shortened_in_the_error(tmp_path, capsys):
    path = tmp_path / "long.toml"
    path.write_text('[mechanism]\nrod = "' + "x" * 500_000 + '"\n')
    assert main(["dynamics", "--config", str(path), "--out", str(tmp_path / "out")]) == 2
    line = assert_one_error_line(2, capsys.readouterr().err, f"config {path}", "[mechanism] rod",
                                 "500,001 characters", "expected rigid or flexible")
    assert len(line) < 400


def test_a_stage_check_names_the_config_file(tmp_path, capsys):
    path = tmp_path / "soft.toml"
    path.write_text("[bushing]\nyoungs_modulus_Pa = -1.0\n")
    assert main(["contact", "--force", "0", "1", "--config", str(path),
                 "--out", str(tmp_path / "out")]) == 2
    assert_one_error_line(2, capsys.readouterr().err, f"config {path}", "youngs_modulus_Pa = -1.0")


@pytest.mark.parametrize("where", ["cell", "header"])
@pytest.mark.parametrize("kind", ["pin_on_disc", "joint"])
def test_a_csv_field_beyond_the_csv_limit_is_an_input_error(tmp_path, capsys, where, kind):
    header = ("test_id,pressure_Pa,velocity_m_s,sliding_distance_m,wear_volume_m3"
              if kind == "pin_on_disc" else "cycles,angle_deg,wear_depth_m")
    row = "a,1e6,1,100,1e-9" if kind == "pin_on_disc" else "0,10,1e-6"
    big = "9" * 200_000 if where == "cell" else "x" * 1_000_000
    lines = [header + ("," + big if where == "header" else ""),
             (row.replace("1e6", big) if kind == "pin_on_disc" else row.replace("10", big))
             if where == "cell" else row]
    path = tmp_path / "data.csv"
    path.write_text("\n".join(lines) + "\n")
    assert main(["diagnose", str(path), "--out", str(tmp_path / "out")]) == 2
    line = assert_one_error_line(2, capsys.readouterr().err, str(path),
                                 "line 2" if where == "cell" else "line 1", "131,072 characters")
    assert len(line) < 400
    assert not (tmp_path / "out").exists()


def test_a_csv_that_is_not_text_is_an_input_error(tmp_path, capsys):
    path = tmp_path / "data.csv"
    path.write_bytes(b"cycles,angle_deg,wear_depth_m\n0,1,\x00\xff\n")
    assert main(["diagnose", str(path), "--out", str(tmp_path / "out")]) == 2
    assert_one_error_line(2, capsys.readouterr().err, str(path), "line 2")


def test_a_config_folder_or_missing_file_is_named(tmp_path, capsys):
    assert main(["dynamics", "--config", str(tmp_path), "--out", str(tmp_path / "o")]) == 2
    assert_one_error_line(2, capsys.readouterr().err, str(tmp_path), "is a folder")
    assert main(["dynamics", "--config", str(tmp_path / "none.toml")]) == 2
    assert_one_error_line(2, capsys.readouterr().err, "none.toml", "No such file")


def test_an_os_error_at_the_edge_is_one_line_naming_the_path(monkeypatch, capsys):
    """A permission, disk or I/O error the stages do not catch (e.g. PyVista writing the plot)."""
    import errno

    import fewear.cli

    def refused(args):
        raise PermissionError(errno.EACCES, "Permission denied", "/ro/worn_bushing.png")

    monkeypatch.setitem(fewear.cli.HANDLERS, "config", "tests.io.test_hostile_input:_refused")
    monkeypatch.setattr(sys.modules[__name__], "_refused", refused, raising=False)
    assert main(["config"]) == 2
    assert_one_error_line(2, capsys.readouterr().err, "/ro/worn_bushing.png", "Permission denied")

    def full(args):
        raise OSError(errno.ENOSPC, "No space left on device", "/out/summary.json")

    monkeypatch.setattr(sys.modules[__name__], "_refused", full)
    assert main(["config"]) == 2
    assert_one_error_line(2, capsys.readouterr().err, "No space left", "free some space")


def test_plot_into_a_folder_it_cannot_write(tmp_path):
    """As an unprivileged user (root writes anywhere): skipped where there is none."""
    import os
    import shutil

    if os.geteuid() != 0 or shutil.which("setpriv") is None:
        pytest.skip("needs root to drop to an unprivileged user")
    folder = tmp_path / "ro"
    folder.mkdir()
    (folder / "rigid.xdmf").write_text("<Xdmf/>")
    folder.chmod(0o555)
    tmp_path.chmod(0o755)
    env = {**os.environ, "MPLCONFIGDIR": str(tmp_path), "HOME": str(tmp_path)}
    process = subprocess.run(
        ["setpriv", "--reuid=65534", "--regid=65534", "--clear-groups", sys.executable, "-m",
         "fewear.cli", "plot", str(folder)], capture_output=True, text=True, env=env,
        timeout=120)
    assert_one_error_line(process.returncode, process.stderr, str(folder))


def test_shorten_and_one_line():
    assert shorten("abc") == "abc"
    long = shorten("y" * 10_000)
    assert len(long) < 100 and "10,000 characters" in long
    assert one_line("columns:\n  a\n  b") == "columns: a; b"
    assert len(one_line("v = '" + "z" * 50_000 + "': expected x")) < 200
    assert one_line("v = '" + "z" * 50_000 + "': expected x").endswith("': expected x")
    assert len(one_line("word " * 10_000)) <= 1100
    with pytest.raises(FewearInputError):
        raise FewearInputError("x")


def test_a_joint_diagnosis_without_config_says_which_model_it_runs(tmp_path, monkeypatch,
                                                                   capsys):
    """The embedded default is the paper's full case (minutes per forward run): the diagnosis
    says so before it starts, and the forward runs report their progress."""
    import fewear.diagnose.joint.command

    def stop(*args, **kwargs):
        raise KeyboardInterrupt

    monkeypatch.setattr(fewear.diagnose.joint.command, "diagnose_joint", stop)
    path = tmp_path / "profiles.csv"
    path.write_text("cycles,angle_deg,wear_depth_m\n1000,0,1e-6\n1000,90,2e-6\n1000,180,1e-6\n")
    assert main(["diagnose", str(path), "--out", str(tmp_path / "out")]) == 130
    err = capsys.readouterr().err
    assert "no --config: the believed model is the embedded default config" in err
    assert "1,872 quadrilaterals" in err and "--config" in err
    assert err.strip().splitlines()[-1].startswith("fewear: interrupted: Ctrl-C: nothing")


def test_a_forward_run_reports_its_progress(monkeypatch, capsys):
    from types import SimpleNamespace

    import fewear.diagnose.joint.forward as forward

    monkeypatch.setattr(forward, "PROGRESS_INTERVAL_S", 0.0)
    progress = forward._BlockProgress("believed model", 40_000, True)
    progress(SimpleNamespace(state=SimpleNamespace(cycles=8000, blocks=2)))
    assert "forward run believed model: 8,000/40,000 cycles, block 2" in capsys.readouterr().err


@pytest.mark.parametrize("force", ["1e-300", "1e-12"])
def test_a_vanishing_force_is_refused_before_the_solve(tmp_path, capsys, force):
    """It ended in a ZeroDivisionError traceback (1e-300) or a 'cannot carry it' (1e-12)."""
    assert main(["contact", "--force", force, "0", "--out", str(tmp_path / "out")]) == 2
    assert_one_error_line(2, capsys.readouterr().err, f"--force {float(force)!r} 0.0",
                          "below 0.001 N", "0 0 for no load")
    assert not (tmp_path / "out").exists()


def test_a_mechanism_the_integrator_cannot_carry_is_an_input_error(tmp_path, capsys):
    """A valid but absurd model (gravity 1e12 m/s^2) collapsed the integrator's step: it was a
    RuntimeError traceback."""
    path = tmp_path / "heavy.toml"
    path.write_text("[mechanism]\ngravity_m_s2 = 1e12\n")
    assert main(["dynamics", "--config", str(path), "--out", str(tmp_path / "out")]) == 2
    assert_one_error_line(2, capsys.readouterr().err, f"config {path}",
                          "cannot integrate this mechanism", "min_step_s")
    assert not (tmp_path / "out").exists()


def test_an_interruption_while_outputs_move_in_waits_until_all_are_in(tmp_path, monkeypatch):
    """All or nothing also against Ctrl-C: the signal that arrives while the staged files move
    into the output folder is delivered after the last one. The signal's arrival is the call of
    the Python handler in place at that moment, as the interpreter makes it on the main thread
    (called here directly). Ctrl-C raises KeyboardInterrupt as in a terminal: a process started
    in the background by a shell inherits SIGINT ignored, and Python then keeps it ignored."""
    import signal

    from fewear.io import output

    moved = []
    original = output.Path.replace

    def replace(self, target):
        if not moved:
            signal.getsignal(signal.SIGINT)(signal.SIGINT, None)  # held: no KeyboardInterrupt
        moved.append(self.name)
        return original(self, target)

    monkeypatch.setattr(output.Path, "replace", replace)
    inherited = signal.signal(signal.SIGINT, signal.default_int_handler)
    try:
        with pytest.raises(KeyboardInterrupt):
            with output.staged_output(tmp_path / "out") as stage:
                for name in ("a.csv", "b.csv", "c.csv"):
                    (stage / name).write_text(name)
    finally:
        signal.signal(signal.SIGINT, inherited)
    assert sorted(path.name for path in (tmp_path / "out").iterdir()) == ["a.csv", "b.csv",
                                                                          "c.csv"]


@pytest.mark.parametrize("size, name", [("1", "SIGTERM"),
                                        ("2", "SIGTERM (which mpirun also sends on Ctrl-C)")],
                         ids=["serial", "mpirun"])
def test_sigterm_is_named_as_mpirun_sends_it(monkeypatch, capsys, size, name):
    """Open MPI's mpirun answers Ctrl-C with SIGTERM to every rank: under it a SIGTERM is named
    as either; the exit status is SIGTERM's, 143, as in a serial run (issue 57)."""
    import fewear.commands.config
    from fewear.errors import Terminated

    def stop(args):
        raise Terminated("SIGTERM")

    monkeypatch.setattr(fewear.commands.config, "main", stop)
    monkeypatch.setenv("OMPI_COMM_WORLD_RANK", "0")
    monkeypatch.setenv("OMPI_COMM_WORLD_SIZE", size)
    assert main(["config"]) == 143
    assert capsys.readouterr().err == (f"fewear: interrupted: {name}: nothing was written: the "
                                       "output folder is as it was\n")
