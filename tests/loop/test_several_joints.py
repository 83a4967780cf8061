"""Several clearance joints worn together (fewear.loop.block.wear_block through `fewear run`):
with a fake two-joint dynamics (the slider-crank's first-block history for joint "a", the same
turned by 90 deg and scaled by 0.7 for joint "b"), each joint wears exactly as a run of that
joint alone on its own history (given the histories the joints are independent, and with a
fixed A_j they step alike), the outputs name the joints, and an interrupted run resumes both."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from fewear.loop import mechanism_adapter as adapter
from tests.loop.test_imported_history import depth_by_node, first_block_history
from tests.loop.test_wear_loop import run, write_config


def turned(history, angle_rad, scale):
    """``history`` with every vector turned by ``angle_rad`` and every force scaled."""
    c, s = math.cos(angle_rad), math.sin(angle_rad)
    rotation = np.array([[c, -s], [s, c]])
    return replace(history, eccentricity_m=history.eccentricity_m @ rotation.T,
                   reaction_force_N=scale * history.reaction_force_N @ rotation.T,
                   normal_force_N=scale * history.normal_force_N,
                   friction_force_N=scale * history.friction_force_N)


def two_histories(folder):
    """Joint "a": the slider-crank's first-block history; "b": it turned by 90 deg, scaled by
    0.7."""
    first = first_block_history(write_config(folder, implicit=False, smoothing=0.0))
    return {"a": first, "b": turned(first, math.pi / 2, 0.7)}


@pytest.fixture(scope="module")
def histories(tmp_path_factory):
    return two_histories(tmp_path_factory.mktemp("history"))


def fake_mechanism(monkeypatch, histories, joints):
    """The stand-in adapter with the clearance joints ``joints``, each on its fixed history
    whatever the wear (the warm start is a mechanism state, saved and restored)."""
    from fewear.mbd.slider_crank import MechanismState

    monkeypatch.setattr(adapter, "joint_sections",
                        lambda config: {name: config for name in joints})

    def simulate(inputs, start=None, profiles=None):
        assert sorted(profiles) == sorted(joints)  # every joint's worn clearance fed back
        time = 0.0 if start is None else start.time_s + 0.05
        return ({name: histories[name] for name in joints}, None,
                MechanismState(time, np.arange(3.0), np.zeros(3)))

    monkeypatch.setattr(adapter, "simulate", simulate)


@pytest.fixture(scope="module")
def two_joints(tmp_path_factory, histories):
    folder = tmp_path_factory.mktemp("two_joints")
    config = write_config(folder, implicit=False, smoothing=0.0)
    with pytest.MonkeyPatch.context() as monkeypatch:
        fake_mechanism(monkeypatch, histories, ["a", "b"])
        assert run(config, folder / "both") == 0
        for name in ("a", "b"):
            fake_mechanism(monkeypatch, histories, [name])
            assert run(config, folder / name) == 0
    return folder


def test_each_joint_wears_as_it_would_alone(two_joints):
    for name in ("a", "b"):
        angle, together = depth_by_node(two_joints / "both", "rigid", name)
        same_angle, alone = depth_by_node(two_joints / name, "rigid", name)
        assert together.size == alone.size == 2 * 48 * 2  # 2 blocks, 96 bore nodes
        np.testing.assert_array_equal(angle, same_angle)
        np.testing.assert_array_equal(together, alone)
    # the joints differ: b's load is turned by 90 deg, its wear too
    a, b = (depth_by_node(two_joints / "both", "rigid", name)[1] for name in ("a", "b"))
    assert not np.allclose(a, b)


def test_the_outputs_name_each_joint(two_joints):
    out = two_joints / "both"
    summary = json.loads((out / "summary.json").read_text())
    joints = summary["cases"]["rigid"]["joints"]
    assert list(joints) == ["a", "b"]
    assert all(joint["cycles"] == 4000 and joint["blocks"] == 2 for joint in joints.values())
    maxima = np.genfromtxt(out / "max_wear.csv", delimiter=",", names=True, dtype=None,
                           encoding=None)
    assert list(maxima["joint"]) == ["a"] * 3 + ["b"] * 3
    for name in ("a", "b"):
        assert joints[name]["max_wear_depth_m"] == pytest.approx(
            depth_by_node(out, "rigid", name)[1][-96:].max(), rel=1e-9)
        assert (out / f"rigid-{name}.xdmf").is_file()


def test_an_interrupted_two_joint_run_resumes_both(tmp_path, monkeypatch, histories,
                                                   two_joints):
    import fewear.commands.run

    fake_mechanism(monkeypatch, histories, ["a", "b"])
    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    original = fewear.commands.run.Progress.block
    lines = []

    def interrupt(self, joints):
        lines.append(list(joints))
        original(self, joints)
        raise KeyboardInterrupt

    monkeypatch.setattr(fewear.commands.run.Progress, "block", interrupt)
    assert run(config, tmp_path / "out") == 130
    monkeypatch.setattr(fewear.commands.run.Progress, "block", original)
    saved = np.load(tmp_path / "out" / "fewear-checkpoint" / "rigid.npz")
    assert {"a/depth_m", "b/depth_m", "q", "qd"} <= set(saved.files)
    assert run(config, tmp_path / "out", "--resume") == 0
    for name in ("a", "b"):
        np.testing.assert_array_equal(depth_by_node(tmp_path / "out", "rigid", name)[1],
                                      depth_by_node(two_joints / "both", "rigid", name)[1])
    # a checkpoint of other joints is refused by name
    fake_mechanism(monkeypatch, histories, ["a"])
    assert run(config, tmp_path / "out", "--resume") == 2


def test_fewear_plot_draws_a_row_per_joint_or_the_one_asked_for(two_joints, tmp_path):
    """`fewear plot` (its own process: PyVista, no DOLFINx) on the two-joint run; the layout
    read from the file names, and an unknown --joint refused naming the joints there are."""
    import os
    import subprocess
    import sys

    from fewear.errors import FewearInputError
    from fewear.plot.worn_bushing import panels

    out = two_joints / "both"
    assert {joint: list(cases) for joint, cases in panels(out).items()} == {
        "a": ["rigid"], "b": ["rigid"]}
    assert list(panels(out, "b")) == ["b"]
    with pytest.raises(FewearInputError, match="--joint c: no such joint .* its joints: a, b"):
        panels(out, "c")
    process = subprocess.run([sys.executable, "-m", "fewear.cli", "plot", str(out)],
                             capture_output=True, text=True, timeout=300,
                             env={**os.environ, "PYVISTA_OFF_SCREEN": "true"})
    assert process.returncode == 0, process.stderr
    assert (out / "worn_bushing.png").stat().st_size > 10_000


@pytest.mark.slow  # the worn-through joint below splits the joints over two ranks by default
@pytest.mark.mpi
def test_two_ranks_split_the_joints_and_give_the_serial_result(tmp_path, two_joints):
    """`mpirun -n 2 fewear run` with one case and two joints: a joint per rank, each wearing
    on its own communicator what it wears in the serial run, the dynamics run on both ranks from
    the shared worn states: the same files as the serial run, byte for byte."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    from tests.mpi import MPI_ENV, mpirun_or_skip

    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    root = Path(__file__).resolve().parents[2]
    process = subprocess.run(
        [mpirun_or_skip(), "-n", "2", sys.executable, "-m", "tests.loop.fake_two_joint_run",
         str(config), str(tmp_path / "mpi")], capture_output=True, text=True, timeout=600,
        cwd=root, env={**os.environ, **MPI_ENV, "PYTHONPATH": str(root)})
    assert process.returncode == 0, process.stderr
    for name in ("wear_profile.csv", "max_wear.csv"):
        assert (tmp_path / "mpi" / name).read_text() == (two_joints / "both" / name).read_text()


def test_adaptive_steps_cover_the_fewest_cycles_any_joint_chose(tmp_path, monkeypatch,
                                                                histories):
    """Adaptive A_j (each step's largest depth increment bounded): the joints step together,
    over the fewest cycles either chooses. Joint b, loaded 0.7 times as hard, takes longer steps
    alone, so a sets the first steps and a wears as it would alone; should b's wear jump at a
    dwell point later (no smoothing here), b sets that step: a shorter one than a alone took."""
    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    config.write_text(config.read_text().replace('extrapolation = "fixed"',
                                                 'extrapolation = "adaptive"'))
    fake_mechanism(monkeypatch, histories, ["a", "b"])
    assert run(config, tmp_path / "both") == 0
    for name in ("a", "b"):
        fake_mechanism(monkeypatch, histories, [name])
        assert run(config, tmp_path / name) == 0

    def cycles(out, name):
        table = np.genfromtxt(out / "max_wear.csv", delimiter=",", names=True, dtype=None,
                              encoding=None)
        return list(table["cycles"][table["joint"] == name])

    together, a_alone, b_alone = (cycles(tmp_path / "both", "a"), cycles(tmp_path / "a", "a"),
                                  cycles(tmp_path / "b", "b"))
    assert cycles(tmp_path / "both", "b") == together
    assert together[1] == a_alone[1] < b_alone[1]  # a sets the first step
    assert len(b_alone) < len(together)  # alone, b steps longer
    same = next((i for i, (x, y) in enumerate(zip(together, a_alone)) if x != y), None)
    if same is not None:  # b set block ``same``: shorter than a alone's
        assert together[same] - together[same - 1] < a_alone[same] - a_alone[same - 1]
    nodes = 96 * ((same or len(together)) - 1)  # the depth records of the blocks before it
    np.testing.assert_array_equal(depth_by_node(tmp_path / "both", "rigid", "a")[1][:nodes],
                                  depth_by_node(tmp_path / "a", "rigid", "a")[1][:nodes])
    assert nodes >= 96 * 3  # the comparison covers a few blocks at least


@pytest.mark.mpi
def test_a_joint_worn_through_on_one_rank_stops_every_rank(tmp_path):
    """Joint a wears through its wall in the first block (k 87.5 times the small case's: 2.9 mm
    of the 2.5 mm allowed) on its rank while b, loaded 0.7 times as hard, does not:
    the input error reaches both ranks (no rank waits for the other), one line, exit status 2."""
    import os
    import subprocess
    import sys
    from pathlib import Path

    from tests.mpi import MPI_ENV, mpirun_or_skip

    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    config.write_text(config.read_text().replace(
        'coefficient_model = "constant"', 'coefficient_model = "constant"\n'
        'constant_k_m2_N = 1.75e-11'))
    root = Path(__file__).resolve().parents[2]
    process = subprocess.run(
        [mpirun_or_skip(), "-n", "2", sys.executable, "-m", "tests.loop.fake_two_joint_run",
         str(config), str(tmp_path / "mpi")], capture_output=True, text=True, timeout=600,
        cwd=root, env={**os.environ, **MPI_ENV, "PYTHONPATH": str(root)})
    assert process.returncode == 2, process.stderr
    assert "rigid case, joint a: wear depth" in process.stderr
    assert "worn through" in process.stderr and "Traceback" not in process.stderr
