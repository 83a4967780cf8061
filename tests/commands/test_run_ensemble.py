"""`fewear run --members N` (issue 56): N runs of every case whose starts differ (member m with
the crank m degrees on). Member 0 is the single run, member m the single run started m degrees
on; the statistics files are numpy's of the members' files; an interrupted ensemble resumes
every member to the uninterrupted result; worker processes and MPI ranks give the serial files."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from fewear.cli import main
from tests.mpi import mpirun_fewear

R_B = 0.010
# The small case of tests/loop/test_wear_loop.py with an adaptive wear step bounded tightly
# enough that the members' blocks end at different cycles (the statistics interpolate).
SMALL = f"""
[mesh]
bore_element_size_m = {2 * math.pi * R_B / 48 * (1 + 1e-9)}
radial_element_count = 4
[wear]
coefficient_model = "constant"
[wear_loop]
rod_models = ["rigid"]
load_steps_per_cycle = 40
total_cycles = 4000
extrapolation = "adaptive"
max_extrapolation_factor = 1500.0
max_depth_increment_fraction = 0.008
wear_steps_per_block = 2
"""
MEMBERS = 3
FILES = ("wear_profile.csv", "max_wear.csv", "wear_profile_members.csv", "max_wear_members.csv",
         "wear_profile_ensemble.csv", "max_wear_ensemble.csv")


def write_config(tmp_path, crank_angle_deg=None, name="ensemble.toml"):
    path = tmp_path / name
    start = ("" if crank_angle_deg is None
             else f"[mechanism]\ninitial_crank_angle_deg = {crank_angle_deg}\n")
    path.write_text(SMALL + start)
    return path


def run(config, out, *extra):
    return main(["run", "--config", str(config), "--out", str(out), *extra])


def table(path):
    return np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding=None)


def texts(folder) -> dict:
    return {name: (folder / name).read_text() for name in FILES}


@pytest.fixture(scope="module")
def ensemble(tmp_path_factory):
    folder = tmp_path_factory.mktemp("ensemble")
    assert run(write_config(folder), folder / "out", "--members", str(MEMBERS),
               "--jobs", "1") == 0
    return folder / "out"


def without_wall_times(value):
    if isinstance(value, dict):
        return {key: without_wall_times(item) for key, item in value.items()
                if key not in ("wall_time_s", "stage_wall_time_s")}
    return value


def test_member_0_is_the_single_run_and_member_2_the_run_started_2_degrees_on(tmp_path,
                                                                              ensemble):
    assert run(write_config(tmp_path), tmp_path / "single", "--jobs", "1") == 0
    for name in ("wear_profile.csv", "max_wear.csv"):
        assert (ensemble / name).read_text() == (tmp_path / "single" / name).read_text()
    single, whole = (json.loads((folder / "summary.json").read_text())
                     for folder in (tmp_path / "single", ensemble))
    assert without_wall_times(whole["cases"]) == without_wall_times(single["cases"])
    assert whole["config"]["wear_loop"]["members"] == MEMBERS
    assert "ensemble" not in single and single["config"]["wear_loop"]["members"] == 1
    # member 2: the single run with the crank started 2 degrees on, row for row
    assert run(write_config(tmp_path, 2.0, "later.toml"), tmp_path / "later", "--jobs", "1") == 0
    members = (ensemble / "wear_profile_members.csv").read_text().splitlines()[1:]
    later = [line for line in members if line.split(",")[2] == "2"]
    assert [",".join(line.split(",")[:2] + line.split(",")[3:]) for line in later] == (
        tmp_path / "later" / "wear_profile.csv").read_text().splitlines()[1:]
    # and the starts matter: the members' block ends and depths differ
    rows = table(ensemble / "max_wear_members.csv")
    ends = [tuple(rows["cycles"][rows["member"] == m]) for m in range(MEMBERS)]
    assert len(set(ends)) == MEMBERS


def member_profiles(rows, cycles, angles):
    """Each member's depth at ``cycles`` per node (members, cycles, nodes), linear in the cycles
    between its rows, zero at cycle 0."""
    found = np.zeros((MEMBERS, cycles.size, angles.size))
    for m in range(MEMBERS):
        mine = rows[rows["member"] == m]
        for node, angle in enumerate(angles):
            at = mine[mine["angle_deg"] == angle]
            order = np.argsort(at["cycles"])
            found[m, :, node] = np.interp(cycles, np.append(0, at["cycles"][order]),
                                          np.append(0.0, at["wear_depth_m"][order]))
    return found


def assert_statistics(found: dict, values, scale):
    """``found`` (columns of mean, sd, min, max) against numpy's over axis 0 of ``values``, to
    the files' printed digits."""
    expected = {"mean": values.mean(axis=0), "sd": values.std(axis=0, ddof=1),
                "min": values.min(axis=0), "max": values.max(axis=0)}
    for name, value in expected.items():
        np.testing.assert_allclose(found[name], value, rtol=0, atol=1e-8 * scale, err_msg=name)


def test_the_statistics_files_are_numpys_of_the_members_files(ensemble):
    rows = table(ensemble / "wear_profile_members.csv")
    statistics = table(ensemble / "wear_profile_ensemble.csv")
    cycles, angles = np.unique(rows["cycles"]), np.unique(rows["angle_deg"])
    assert np.array_equal(np.unique(statistics["cycles"]), cycles)
    order = np.lexsort((statistics["angle_deg"], statistics["cycles"]))
    shape = (cycles.size, angles.size)
    values = member_profiles(rows, cycles, angles)
    assert_statistics({name: statistics[f"{name}_wear_depth_m"][order].reshape(shape)
                       for name in ("mean", "sd", "min", "max")}, values, values.max())
    maxima = table(ensemble / "max_wear_members.csv")
    ensemble_maxima = table(ensemble / "max_wear_ensemble.csv")
    grid = ensemble_maxima["cycles"]
    assert np.array_equal(grid, np.append(0, cycles))
    by_member = np.array([np.interp(grid, maxima["cycles"][maxima["member"] == m],
                                    maxima["max_wear_depth_m"][maxima["member"] == m])
                          for m in range(MEMBERS)])
    assert_statistics({name: ensemble_maxima[f"{name}_max_wear_depth_m"]
                       for name in ("mean", "sd", "min", "max")}, by_member, values.max())
    # summary.json: the final figures of the members, and their statistics
    summary = json.loads((ensemble / "summary.json").read_text())["ensemble"]
    joint = summary["cases"]["rigid"]["joints"]["rod_slider"]
    assert summary["members"] == MEMBERS and summary["start_offsets_deg"] == [0.0, 1.0, 2.0]
    assert without_wall_times(joint["members"][0]) == without_wall_times(
        json.loads((ensemble / "summary.json").read_text())["cases"]["rigid"]["joints"][
            "rod_slider"])
    for key in ("max_wear_depth_m", "worn_volume_m3"):
        each = np.array([member[key] for member in joint["members"]])
        assert_statistics({name: joint[key][name] for name in ("mean", "sd", "min", "max")},
                          each, each.max() * 1e-7)  # to rounding
    final = values[:, -1, :]
    np.testing.assert_allclose([member["max_wear_depth_m"] for member in joint["members"]],
                               final.max(axis=1), rtol=1e-8)
    angle = np.radians([member["max_wear_angle_deg"] for member in joint["members"]])
    mean = np.degrees(np.angle(np.exp(1j * angle).mean())) % 360.0
    assert joint["max_wear_angle_deg"]["mean"] == pytest.approx(mean, abs=1e-9)


def test_an_interrupted_ensemble_resumes_every_member(tmp_path, monkeypatch, capsys, ensemble):
    """Stopped after member 1's first block (member 0 done, member 2 not started): the resume
    finishes member 1 from its checkpoint and runs member 2, to the uninterrupted files."""
    import fewear.commands.run

    original = fewear.commands.run.Progress.block

    def interrupt(self, *args):
        original(self, *args)
        if "member 1" in self.case:
            raise KeyboardInterrupt

    config, out = write_config(tmp_path), tmp_path / "out"
    monkeypatch.setattr(fewear.commands.run.Progress, "block", interrupt)
    assert run(config, out, "--members", str(MEMBERS), "--jobs", "1") == 130
    note = capsys.readouterr().err.strip().splitlines()[-1]
    assert "rigid at 4,000/4,000 cycles, rigid-member1 at " in note, note
    assert "--members 3" in note and "rigid-member2" not in note
    monkeypatch.setattr(fewear.commands.run.Progress, "block", original)
    assert run(config, out, "--members", str(MEMBERS), "--resume", "--jobs", "1") == 0
    err = capsys.readouterr().err
    assert "resuming" in err and "rigid-member1 at" in err
    assert texts(out) == texts(ensemble)


@pytest.mark.slow  # the rods side by side in tests/loop keep the worker processes by default
def test_members_in_worker_processes_give_the_serial_files(tmp_path, ensemble):
    assert run(write_config(tmp_path), tmp_path / "out", "--members", str(MEMBERS),
               "--jobs", "2") == 0
    assert texts(tmp_path / "out") == texts(ensemble)


@pytest.mark.mpi
@pytest.mark.slow  # the ranks' split of work items is tested on cases in tests/loop
def test_members_on_two_ranks_give_the_serial_files(tmp_path, ensemble):
    process = mpirun_fewear("run", "--config", str(write_config(tmp_path)), "--out",
                            str(tmp_path / "mpi"), "--members", str(MEMBERS))
    assert process.returncode == 0, process.stderr
    assert texts(tmp_path / "mpi") == texts(ensemble)


@pytest.mark.parametrize("members", ["0", "361"])
def test_members_must_be_a_whole_number_from_1_to_360(tmp_path, capsys, members):
    assert run(write_config(tmp_path), tmp_path / "out", "--members", members) == 2
    assert f"[wear_loop] members = {members}: expected a whole number" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_an_imported_joint_history_has_no_members(tmp_path, capsys):
    assert run(write_config(tmp_path), tmp_path / "out", "--members", "2",
               "--joint-history", str(tmp_path / "history.csv")) == 2
    assert "an imported joint history has none" in capsys.readouterr().err


def test_the_members_start_the_drivers_further_on():
    """The paper's slider-crank: [mechanism] initial_crank_angle_deg + the offset, in the
    closed-form start too; a mechanism file: each constant-speed driver's angle + the offset,
    nothing else changed; a tabulated driver is refused."""
    from fewear.errors import FewearInputError
    from fewear.io.config import load_config
    from fewear.loop import mechanism_adapter as adapter
    from fewear.loop.settings import run_sections
    from fewear.mbd.description import Driver

    config = load_config(None, run_sections())
    crank = adapter.dynamics_inputs(config, "rigid", 2.0)
    assert crank.mechanism.drivers[0].initial_angle_rad == pytest.approx(math.radians(2.0))
    started = {**config, "mechanism": {**config["mechanism"], "initial_crank_angle_deg": 2.0}}
    same = adapter.dynamics_inputs(started, "rigid")
    np.testing.assert_array_equal(crank.initial_state.q, same.initial_state.q)
    config["mechanism"]["file"] = "four_bar"
    base, later = (adapter.dynamics_inputs(config, "rigid", offset) for offset in (0.0, 3.0))
    drivers = tuple(replace(driver, initial_angle_rad=driver.initial_angle_rad
                            + math.radians(3.0)) for driver in base.mechanism.drivers)
    assert later.mechanism == replace(base.mechanism, drivers=drivers)
    tabulated = replace(base.mechanism, drivers=(Driver(
        base.mechanism.drivers[0].body, 0.0, 0.0, (0.0, 0.02, 0.05), (0.0, 0.1, 0.0)),))
    with pytest.raises(FewearInputError, match="follows a table"):
        adapter._started_later(tabulated, 1.0)


def test_fewear_plot_of_an_ensemble_says_whose_bushing_it_draws(ensemble):
    """The mesh files of an ensemble are member 0's: `fewear plot` says so and names the figures
    of the members' mean and spread (its own process: PyVista, off screen)."""
    import os
    import subprocess
    import sys

    process = subprocess.run([sys.executable, "-m", "fewear.cli", "plot", str(ensemble)],
                             capture_output=True, text=True, timeout=300,
                             env={**os.environ, "PYVISTA_OFF_SCREEN": "true"})
    assert process.returncode == 0, process.stderr
    said = process.stdout
    assert f"an ensemble of {MEMBERS} members" in said and "member 0's" in said
    assert all(name in said for name in ("wear_profiles.png", "max_wear.png"))
    assert (ensemble / "worn_bushing.png").stat().st_size > 10_000
