"""`fewear run --joint-history`: the slider-crank's own first-block history, exported by
`fewear dynamics`' writer and imported, wears the bushing as the coupled run's first block does
(the same contact and wear law; only the history's source differs)."""

import hashlib
import json

import numpy as np
import pytest

from fewear.io.config import load_config
from fewear.io.joint_history import write_joint_history
from fewear.loop import mechanism_adapter as adapter
from fewear.loop.settings import run_sections
from fewear.mbd.slider_crank import CLEARANCE_JOINT
from fewear.wear.state import WearState
from tests.loop.test_wear_loop import run, write_config


def one_block_config(tmp_path):
    """The tests' small case (coarse bushing, fixed A_j = 2,000), one block of the rigid rod."""
    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    config.write_text(config.read_text().replace("total_cycles = 4000", "total_cycles = 2000"))
    return config


def first_block_history(config_path):
    """The rigid slider-crank's first-block history, as the loop's stage 1 makes it: settled
    from the ideal mechanism, the unworn clearance (any bore nodes: no wear yet)."""
    config = load_config(config_path, run_sections())
    loop = config["wear_loop"]
    inputs = adapter.block_inputs(adapter.dynamics_inputs(config, "rigid"),
                                  loop["recorded_cycles_per_block"], None)
    unworn = WearState.unworn(np.linspace(0.0, 6.0, 7))
    profile = unworn.clearance_profile(config["bushing"]["inner_radius_m"],
                                       config["pin"]["radius_m"])
    histories, _, _ = adapter.simulate(inputs, profiles={CLEARANCE_JOINT: profile})
    return histories[CLEARANCE_JOINT]


def depth_by_node(out, case, joint):
    table = np.genfromtxt(out / "wear_profile.csv", delimiter=",", names=True, dtype=None,
                          encoding=None)
    rows = table[(table["case"] == case) & (table["joint"] == joint)]
    return rows["angle_deg"], rows["wear_depth_m"]


@pytest.fixture(scope="module")
def coupled_and_imported(tmp_path_factory):
    folder = tmp_path_factory.mktemp("imported")
    config = one_block_config(folder)
    write_joint_history(first_block_history(config), folder / "history.csv")
    assert run(config, folder / "coupled") == 0
    assert run(config, folder / "imported", "--joint-history", str(folder / "history.csv")) == 0
    return folder


def test_the_imported_history_wears_as_the_coupled_first_block(coupled_and_imported):
    angle, coupled = depth_by_node(coupled_and_imported / "coupled", "rigid", "rod_slider")
    same_angle, imported = depth_by_node(coupled_and_imported / "imported", "imported", "joint")
    np.testing.assert_array_equal(same_angle, angle)
    assert coupled.max() > 1e-6  # it wore
    np.testing.assert_allclose(imported, coupled, rtol=1e-12, atol=1e-12 * coupled.max())


def test_the_outputs_say_the_history_was_imported_without_feedback(coupled_and_imported):
    summary = json.loads((coupled_and_imported / "imported" / "summary.json").read_text())
    case = summary["cases"]["imported"]
    assert "no feedback of the wear to the dynamics" in case["history_source"]
    assert str(coupled_and_imported / "history.csv") in case["history_source"]
    assert hashlib.sha256((coupled_and_imported / "history.csv").read_bytes()).hexdigest() in (
        case["history_source"])
    assert summary["config"]["wear_loop"]["joint_history"] == str(
        coupled_and_imported / "history.csv")
    assert case["joints"]["joint"]["cycles"] == 2000
    assert (coupled_and_imported / "imported" / "imported-joint.xdmf").is_file()


def test_an_imported_run_resumes_and_wears_the_same_history_every_block(tmp_path, monkeypatch,
                                                                        capsys,
                                                                        coupled_and_imported):
    """Two blocks on the imported history, interrupted after the first and resumed: the same
    profile as uninterrupted, and the second block worn by the same history (the same peak
    force recorded)."""
    import fewear.commands.run

    config = write_config(tmp_path, implicit=False, smoothing=0.0)
    history = str(coupled_and_imported / "history.csv")
    assert run(config, tmp_path / "whole", "--joint-history", history) == 0
    original = fewear.commands.run.Progress.block

    def interrupt(self, *args):
        original(self, *args)
        raise KeyboardInterrupt

    monkeypatch.setattr(fewear.commands.run.Progress, "block", interrupt)
    assert run(config, tmp_path / "cut", "--joint-history", history) == 130
    monkeypatch.setattr(fewear.commands.run.Progress, "block", original)
    assert run(config, tmp_path / "cut", "--joint-history", history, "--resume") == 0
    np.testing.assert_array_equal(depth_by_node(tmp_path / "cut", "imported", "joint")[1],
                                  depth_by_node(tmp_path / "whole", "imported", "joint")[1])
    summary = json.loads((tmp_path / "whole" / "summary.json").read_text())
    joint = summary["cases"]["imported"]["joints"]["joint"]
    assert joint["blocks"] == 2 and joint["cycles"] == 4000
    # a history file changed since the checkpoint is refused by --resume, however alike
    changed = tmp_path / "changed.csv"
    changed.write_text((coupled_and_imported / "history.csv").read_text() + "# edited\n")
    monkeypatch.setattr(fewear.commands.run.Progress, "block", interrupt)
    assert run(config, tmp_path / "again", "--joint-history", str(changed)) == 130
    monkeypatch.setattr(fewear.commands.run.Progress, "block", original)
    changed.write_text(changed.read_text() + "# edited again\n")
    assert run(config, tmp_path / "again", "--joint-history", str(changed), "--resume") == 2
    assert "another joint history" in capsys.readouterr().err
