"""The wear loop of `fewear run` on a small case: Archard's volume, the ALE bore, the outputs,
resume = uninterrupted, and bad checkpoints (fewear.loop)."""

import json
import math

import numpy as np
import pytest

from fewear.cli import main
from tests.mpi import mpirun_fewear

R_B = 0.010
SMALL = """
[mesh]
bore_element_size_m = {size}
radial_element_count = 4
[wear]
coefficient_model = "constant"
{extension}
[wear_loop]
rod_models = ["rigid"]
load_steps_per_cycle = 40
total_cycles = 4000
extrapolation = "fixed"
extrapolation_factor = 2000.0
wear_steps_per_block = 1
implicit_wear_step = {implicit}
wear_smoothing_width_deg = {smoothing}
""".format(size=2 * math.pi * R_B / 48 * (1 + 1e-9), implicit="{implicit}",
           smoothing="{smoothing}", extension="{extension}")
RUNNING_IN_BY_CYCLES = ('extension = "running_in_cycles"\n'
                        'extension_params = {k_initial_over_steady = 4.0, scale_cycles = 1500.0}')


def write_config(tmp_path, implicit=True, smoothing=5.0, name="case.toml", extension=""):
    path = tmp_path / name
    path.write_text(SMALL.format(implicit=str(implicit).lower(), smoothing=smoothing,
                                 extension=extension))
    return path


def run(config, out, *extra):
    return main(["run", "--config", str(config), "--out", str(out), *extra])


@pytest.fixture(scope="module")
def explicit_run(tmp_path_factory):
    folder = tmp_path_factory.mktemp("explicit")
    assert run(write_config(folder, implicit=False, smoothing=0.0), folder / "out") == 0
    return folder / "out"


def test_worn_volume_is_the_integral_of_depth_and_outputs_exist(explicit_run):
    summary = json.loads((explicit_run / "summary.json").read_text())
    case = summary["cases"]["rigid"]["joints"]["rod_slider"]
    assert case["cycles"] == 4000 and case["blocks"] == 2 and case["ale_moves"] == 2
    profile = np.genfromtxt(explicit_run / "wear_profile.csv", delimiter=",", names=True,
                            dtype=None, encoding=None)
    last = profile[profile["cycles"] == 4000]
    theta = np.radians(last["angle_deg"])
    # worn area = integral of (R_b h + h^2 / 2) dtheta, by the trapezoid rule here
    area = np.sum(R_B * last["wear_depth_m"] + 0.5 * last["wear_depth_m"] ** 2) * (
        2 * math.pi / theta.size)
    assert case["worn_volume_m3"] == pytest.approx(0.018 * area, rel=1e-9)
    assert case["max_wear_depth_m"] == pytest.approx(last["wear_depth_m"].max())
    maxima = np.genfromtxt(explicit_run / "max_wear.csv", delimiter=",", names=True,
                           dtype=None, encoding=None)
    assert list(maxima["cycles"]) == [0, 2000, 4000]
    assert np.all(np.diff(maxima["max_wear_depth_m"]) >= 0)
    assert set(profile["joint"]) == {"rod_slider"} and set(maxima["joint"]) == {"rod_slider"}
    for name in ("rigid-rod_slider.xdmf", "rigid-rod_slider.h5", "wear_profiles.png",
                 "max_wear.png"):
        assert (explicit_run / name).stat().st_size > 0
    assert set(case["stage_wall_time_s"]) == {"dynamics", "contact", "wear", "mesh"}


def test_wear_sits_left_and_right_of_the_bore(explicit_run):
    """The paper's claim (section 5.2): in the slider-crank the contact, hence the wear, sits on
    the left and right of the bushing (the slide axis, 0 and 180 deg), where the rod pushes and
    pulls the slider at the dead positions."""
    profile = np.genfromtxt(explicit_run / "wear_profile.csv", delimiter=",", names=True,
                            dtype=None, encoding=None)
    for cycles, half_width in ((2000, 30), (4000, 45)):  # the worn pockets widen
        block = profile[profile["cycles"] == cycles]
        depth, angle = block["wear_depth_m"], block["angle_deg"]
        near_axis = np.abs((angle + 90) % 180 - 90)  # degrees from the slide axis
        assert np.sum(depth[near_axis < half_width]) > 0.9 * np.sum(depth)
        right = depth[(angle < half_width) | (angle > 360 - half_width)].sum()
        left = depth[np.abs(angle - 180) < half_width].sum()
        assert min(left, right) > 0.25 * (left + right)


def test_ale_moved_the_bore_nodes_exactly_to_the_worn_radius(explicit_run):
    """The checkpoint's last mesh: every node that was on the bore now sits at R_b + h(theta)."""
    folder = explicit_run / "fewear-checkpoint"
    data = np.load(folder / "rigid.npz")
    assert sorted(path.name for path in folder.glob("rigid-rod_slider-mesh-*.npy")) == [
        f"rigid-rod_slider-mesh-0000{block}.npy" for block in range(3)]
    unworn, moved = (np.load(folder / f"rigid-rod_slider-mesh-0000{block}.npy")
                     for block in (0, 2))
    on_bore = np.isclose(np.hypot(*unworn.T), R_B, rtol=1e-9)
    angle = np.mod(np.arctan2(unworn[on_bore, 1], unworn[on_bore, 0]), 2 * math.pi)
    depth = np.interp(angle, data["rod_slider/angle_rad"], data["rod_slider/depth_m"],
                      period=2 * math.pi)
    np.testing.assert_allclose(np.hypot(*moved[on_bore].T), R_B + depth, atol=1e-15)
    radial = np.hypot(*moved[on_bore].T) / np.hypot(*unworn[on_bore].T)
    np.testing.assert_allclose(moved[on_bore], unworn[on_bore] * radial[:, None], atol=1e-15)


def _interrupted_and_resumed(config, out, monkeypatch) -> np.ndarray:
    """Stop ``config``'s run after its first block, resume it; the final wear depths."""
    import fewear.commands.run

    original = fewear.commands.run.Progress.block

    def interrupt(self, *args):
        original(self, *args)
        raise KeyboardInterrupt

    monkeypatch.setattr(fewear.commands.run.Progress, "block", interrupt)
    assert run(config, out) == 130  # Ctrl-C: reported in one line, the checkpoint kept
    assert not (out / "summary.json").exists()  # all or nothing
    monkeypatch.setattr(fewear.commands.run.Progress, "block", original)
    assert run(config, out, "--resume") == 0
    return _final_depth_m(out)


def _final_depth_m(out) -> np.ndarray:
    return np.genfromtxt(out / "wear_profile.csv", delimiter=",", names=True, dtype=None,
                         encoding=None)["wear_depth_m"]


def test_resumed_run_equals_the_uninterrupted_one(tmp_path, monkeypatch, explicit_run):
    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    resumed = _interrupted_and_resumed(config, tmp_path / "out", monkeypatch)
    np.testing.assert_array_equal(resumed, _final_depth_m(explicit_run))


def test_a_running_in_by_cycles_resumes_at_the_cycles_it_had_run(tmp_path, monkeypatch,
                                                                 explicit_run):
    """k falls with the crank cycles run: a resumed run must carry them over (a restart at N = 0
    would wear the second block at the initial 4 k again)."""
    config = write_config(tmp_path, implicit=False, smoothing=0.0, extension=RUNNING_IN_BY_CYCLES)
    assert run(config, tmp_path / "whole") == 0
    whole = _final_depth_m(tmp_path / "whole")
    resumed = _interrupted_and_resumed(config, tmp_path / "resumed", monkeypatch)
    np.testing.assert_array_equal(resumed, whole)
    # and it ran in: worn deeper than plain Archard, by less than the initial 4 k would give
    assert np.max(_final_depth_m(explicit_run)) < np.max(whole) < 4.0 * np.max(
        _final_depth_m(explicit_run))


def test_resume_with_another_config_or_a_corrupt_checkpoint_is_an_input_error(
        tmp_path, capsys, explicit_run):
    other = write_config(tmp_path, implicit=True, smoothing=0.0)
    assert run(other, explicit_run, "--resume") == 2
    assert "another config ([wear_loop] implicit_wear_step" in capsys.readouterr().err
    broken = tmp_path / "broken"
    (broken / "fewear-checkpoint").mkdir(parents=True)
    (broken / "fewear-checkpoint" / "rigid.npz").write_bytes(b"not a checkpoint")
    assert run(other, broken, "--resume") == 2
    assert "unreadable" in capsys.readouterr().err
    assert run(other, tmp_path / "empty", "--resume") == 2
    assert "no checkpoint" in capsys.readouterr().err


def test_a_checkpoint_of_another_format_is_refused_by_name(tmp_path, capsys, explicit_run):
    """A checkpoint written by another version (here the single-joint format before the cases
    kept several clearance joints) is refused with the format it has, the one read, and what to
    do."""
    import shutil

    old = tmp_path / "old"
    shutil.copytree(explicit_run / "fewear-checkpoint", old / "fewear-checkpoint")
    case = old / "fewear-checkpoint" / "rigid.npz"
    with np.load(case, allow_pickle=False) as archive:
        arrays = {key: archive[key] for key in archive.files}
    meta = json.loads(str(arrays["meta"]))
    arrays["meta"] = np.array(json.dumps({**meta, "format": "fewear-run-checkpoint-3"}))
    with open(case, "wb") as handle:
        np.savez(handle, **arrays)
    assert run(write_config(tmp_path, implicit=False, smoothing=0.0), old, "--resume") == 2
    error = capsys.readouterr().err
    assert "'fewear-run-checkpoint-3', this fewear reads 'fewear-run-checkpoint-5'" in error
    assert "run without --resume into another --out" in error


def test_wear_through_the_wall_is_an_input_error(tmp_path, capsys):
    config = write_config(tmp_path)
    config.write_text(config.read_text().replace(
        'coefficient_model = "constant"', 'coefficient_model = "constant"\n'
        'constant_k_m2_N = 1e-9'))
    assert run(config, tmp_path / "out") == 2
    error = capsys.readouterr().err
    assert "fewear: error:" in error and "worn through" in error and "Traceback" not in error
    assert not (tmp_path / "out" / "summary.json").exists()


@pytest.mark.mpi
def test_two_ranks_give_the_serial_wear(tmp_path, explicit_run):
    """`mpirun -n 2 fewear run` on the small case: the same profile as serial to 1e-8 of the
    maximum depth (the dynamics run identically on every rank on a clearance rounded to 0.1 nm,
    so the FE solve's rounding, which differs with the process count, cannot switch the
    step-size control onto another path; the condensed contact is solved redundantly from the
    same compliance; only rank 0 writes). Measured: bit-identical (2e-4 without the rounding;
    0.7 % apart after the first block with a 1 pm rounding of the 2,880 sampled directions)."""
    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    process = mpirun_fewear("run", "--config", str(config), "--out", str(tmp_path / "mpi"))
    assert process.returncode == 0, process.stderr
    serial, parallel = (np.genfromtxt(folder / "wear_profile.csv", delimiter=",", names=True,
                                      dtype=None, encoding=None)
                        for folder in (explicit_run, tmp_path / "mpi"))
    scale = serial["wear_depth_m"].max()
    np.testing.assert_allclose(parallel["wear_depth_m"], serial["wear_depth_m"],
                               atol=1e-8 * scale)


def two_rods_config(tmp_path):
    """The small case, one block of each rod model."""
    config = write_config(tmp_path, implicit=False, smoothing=0.0, name="two_rods.toml")
    config.write_text(config.read_text().replace('rod_models = ["rigid"]',
                                                 'rod_models = ["rigid", "flexible"]')
                      .replace("total_cycles = 4000", "total_cycles = 2000"))
    return config


@pytest.fixture(scope="module")
def two_rods_one_after_the_other(tmp_path_factory):
    folder = tmp_path_factory.mktemp("two_rods")
    assert run(two_rods_config(folder), folder / "out", "--jobs", "1") == 0
    return (folder / "out" / "wear_profile.csv").read_text()


def test_rods_side_by_side_in_processes_give_the_serial_result(tmp_path,
                                                              two_rods_one_after_the_other):
    """A plain `fewear run` runs the rod models in worker processes: each computes exactly what
    the serial run does, so the files are the same, byte for byte."""
    assert run(two_rods_config(tmp_path), tmp_path / "out", "--jobs", "2") == 0
    profile = (tmp_path / "out" / "wear_profile.csv").read_text()
    assert profile == two_rods_one_after_the_other
    assert {line.split(",")[0] for line in profile.splitlines()[1:]} == {"rigid", "flexible"}


@pytest.mark.slow  # test_two_ranks_give_the_serial_wear keeps the loop's MPI path by default
@pytest.mark.mpi
def test_ranks_split_among_the_rods_give_the_serial_result(tmp_path,
                                                          two_rods_one_after_the_other):
    """`mpirun -n 2 fewear run` with two rod models: one rank per rod model, the same files as
    the serial run, byte for byte."""
    process = mpirun_fewear("run", "--config", str(two_rods_config(tmp_path)), "--out",
                            str(tmp_path / "mpi"))
    assert process.returncode == 0, process.stderr
    assert (tmp_path / "mpi" / "wear_profile.csv").read_text() == two_rods_one_after_the_other


def test_jobs_must_be_positive(tmp_path, capsys):
    assert run(write_config(tmp_path), tmp_path / "out", "--jobs", "0") == 2
    assert "--jobs 0: expected a number of processes >= 1" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()


def test_fewear_plot_renders_the_worn_bushing_off_screen(explicit_run):
    """`fewear plot DIR` in its own process (PyVista, no DOLFINx): a PNG of the worn bushing."""
    import os
    import subprocess
    import sys

    process = subprocess.run([sys.executable, "-m", "fewear.cli", "plot", str(explicit_run)],
                             capture_output=True, text=True, timeout=300,
                             env={**os.environ, "PYVISTA_OFF_SCREEN": "true"})
    assert process.returncode == 0, process.stderr
    assert "X server" not in process.stderr and "Warning" not in process.stderr
    assert (explicit_run / "worn_bushing.png").stat().st_size > 10_000
    assert main(["plot", str(explicit_run / "absent")]) == 2


def test_compared_panels_share_one_exaggeration_and_one_colour_range():
    """Two rods worn 3 um and 6 um deep: one factor for both (the deeper at a tenth of the
    bushing, rounded down to 1, 2 or 5 x 10^k) and a colour range from 0 to 6 um, whatever the
    rounding noise below zero."""
    from fewear.plot.worn_bushing import common_view

    shallow, deep = np.full((4, 3), 3e-6), np.full((4, 3), 6e-6)
    scale, clim = common_view([shallow, deep], [np.array([-2.45e-12, 3e-6]),
                                                np.array([0.0, 6e-6])], 0.03)
    assert scale == 500.0  # 0.003 m / 6e-6 m = 500 exactly
    assert clim == (0.0, pytest.approx(6.0))
    scale, _ = common_view([deep * 1.1], [np.array([6.6e-6])], 0.03)
    assert scale == 200.0  # 454.5 rounds down to 2 x 10^2
