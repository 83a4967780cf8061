"""The joint diagnosis finds an effect hidden in measured joint wear (fewear.calibrate.
joint_diagnose): each cause of the catalogue switched on in the wear loop at random parameters,
measured by an independent profilometer model (unknown angular origin, 0.5 um noise), diagnosed
without the answer; the believed model's own data give no cause."""

import json

import numpy as np
import pytest

from fewear.calibrate.joint_diagnose import diagnose_joint
from fewear.calibrate.joint_measured import write_joint_profiles, write_max_wear
from fewear.cli import main
from fewear.io.config import load_config
from fewear.loop.settings import run_sections
from tests.calibrate.joint_cases import believed_text, hidden_joint_case


@pytest.fixture(scope="module")
def believed(tmp_path_factory):
    path = tmp_path_factory.mktemp("joint") / "believed.toml"
    path.write_text(believed_text())
    return path, load_config(path, run_sections())


SLOW = pytest.mark.slow  # each hidden-cause case costs its own forward runs (~20-60 s)


# The default suite hides friction; the demo (demos/diagnose_joint.py) hides a flexible rod whose
# modulus lies between the candidate's grid points; the other causes are slow.
@pytest.mark.parametrize("cause, seed", [
    ("friction", 13),
    pytest.param("wear_coefficient", 11, marks=SLOW), pytest.param("flexible_link", 12, marks=SLOW),
    pytest.param("impact_wear", 14, marks=SLOW), pytest.param("running_in", 15, marks=SLOW)])
def test_the_hidden_cause_is_named_and_the_prediction_improves(believed, cause, seed):
    data, truth, offset = hidden_joint_case(believed[1], cause, seed)
    summary = diagnose_joint(data, believed[1]).summary
    assert summary["cause"] == cause, (truth, summary["candidates"])
    assert summary["gain"] > 0.25  # held-out error of the extended run at most 3/4
    assert summary["data_kind"] == "joint"


@pytest.mark.parametrize("seed", [21, pytest.param(22, marks=SLOW)])
def test_the_believed_models_own_data_give_no_cause_and_the_origin_is_found(believed, seed):
    data, _, offset = hidden_joint_case(believed[1], "none", seed, force_start_deg=117.0)
    summary = diagnose_joint(data, believed[1]).summary
    assert summary["causes"] == [] and summary["cause"] == "none"
    assert summary["unexplained"] == []  # the misfit is the instrument's scatter
    # which the diagnosis estimates from neighbouring points: the profilometer's 0.5 um
    assert 0.35e-6 < summary["resolution"]["instrument_scatter_m"] < 0.7e-6
    # the instrument's origin: measured angle + offset = bushing angle
    assert summary["baseline"]["angle_offset_deg"] == pytest.approx(offset, abs=1.0)
    # the held-out error is the profilometer's noise (0.5 um), not a model error
    assert summary["held_out_error"]["baseline"] < 1.5e-6
    # the load cell's trace is the believed model's own: its crank phase is found
    trace, = summary["residual_structure"]["traces"]
    assert trace["phase_deg"] == pytest.approx(117.0, abs=1.0)
    assert summary["residual_structure"]["crank_cycle"]["impacts"]["impacts_per_cycle"] > 0


def test_fewear_diagnose_reads_joint_files_and_writes_its_outputs(believed, tmp_path):
    data, _, _ = hidden_joint_case(believed[1], "none", 21)
    profiles, growth = tmp_path / "profiles.csv", tmp_path / "max_wear.csv"
    write_joint_profiles(profiles, data.profiles)
    write_max_wear(growth, *data.max_wear)
    out = tmp_path / "out"
    assert main(["diagnose", str(profiles), str(growth), "--config", str(believed[0]),
                 "--out", str(out)]) == 0
    summary = json.loads((out / "diagnosis.json").read_text())
    assert summary["data_kind"] == "joint" and summary["cause"] == "none"
    for name in ("report.md", "joint_fits.png", "extended.toml"):
        assert (out / name).stat().st_size > 0


def test_one_cycle_count_is_a_clear_error(believed, tmp_path, capsys):
    data, _, _ = hidden_joint_case(believed[1], "none", 21, with_growth=False)
    path = tmp_path / "one.csv"
    write_joint_profiles(path, data.profiles[:1])
    assert main(["diagnose", str(path), "--config", str(believed[0]),
                 "--out", str(tmp_path / "out")]) == 2
    assert ">= 2 cycle counts" in capsys.readouterr().err
    assert not (tmp_path / "out").exists()
    assert np.isfinite(data.profiles[0].depth_m).all()
