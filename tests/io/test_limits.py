"""Plausibility limits (issue 20): values of the right type that are nonsense in physics or in
cost are refused before any work, naming the file, key, value, limit (and estimated cost); each
limit is stated in the default config's comments."""

import pytest

from fewear.cli import main
from fewear.errors import FewearInputError
from fewear.io import limits
from fewear.io.config import default_config_text

CASES = {
    "step_vs_crank_period": ("[integrator]\nstep_s = 1.0\n",
                             ["[integrator] step_s = 1.0", "0.05 s", "at least 100 steps"]),
    "step_too_fine": ("[integrator]\nstep_s = 1e-9\nmin_step_s = 1e-10\n",
                      ["[integrator] step_s = 1e-09", "1,000,000 steps"]),
    "min_step": ("[integrator]\nmin_step_s = 1e-300\n", ["min_step_s = 1e-300", "1e-12"]),
    "element_larger_than_bore": ("[mesh]\nbore_element_size_m = 1.0\n",
                                 ["bore_element_size_m = 1.0", "1 element(s) around the bore",
                                  "at least 16 elements"]),
    "mesh_too_fine": ("[mesh]\nbore_element_size_m = 1e-7\n",
                      ["bore_element_size_m = 1e-07", "8,168,160 quadrilaterals", "days",
                       "at most 50,000"]),
    "crank_speed": ("[mechanism]\ncrank_speed_rpm = 1e300\n",
                    ["crank_speed_rpm = 1e+300", "at most 60,000 rpm"]),
    "dynamics_cycles": ("[mechanism]\nsettling_cycles = 100000\n",
                        ["settling_cycles + recorded_cycles = 100,001", "1,000"]),
    "wear_steps": ('[wear_loop]\nextrapolation = "fixed"\nextrapolation_factor = 1.0\n',
                    ["total_cycles = 400,000", "400,000 wear steps", "56 h",
                     "raise extrapolation_factor to at least 40"]),
    "adaptive_blocks": ("[wear_loop]\nmax_extrapolation_factor = 2.0\n",
                        ["max_extrapolation_factor = 2.0", "200,000 wear steps"]),
    "cycles_per_block": ("[wear_loop]\nrecorded_cycles_per_block = 5000\n",
                         ["recorded_cycles_per_block + warm_settling_cycles = 5,001"]),
    "load_steps": ("[wear_loop]\nload_steps_per_cycle = 1000000\n",
                   ["load_steps_per_cycle = 1,000,000", "at most 10,000"]),
}


@pytest.mark.parametrize("name", CASES)
def test_a_value_beyond_a_limit_is_refused_before_any_work(tmp_path, capsys, name):
    text, needles = CASES[name]
    path = tmp_path / "limit.toml"
    path.write_text(text)
    assert main(["run", "--config", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fewear: error: config {path}: ") and err.count("\n") == 1, err
    for needle in needles:
        assert needle in err, err
    assert not (tmp_path / "out").exists()


def test_dynamics_cycles_argument_has_the_same_limit(tmp_path, capsys):
    assert main(["dynamics", "--cycles", "1000000", "--out", str(tmp_path / "out")]) == 2
    assert "--cycles 1000000" in capsys.readouterr().err


def test_every_limit_is_stated_in_the_default_config():
    text = default_config_text()
    for stated in (f"{limits.MAX_CRANK_SPEED_RPM:,.0f} rpm",
                   f"{limits.MIN_STEPS_PER_CRANK_CYCLE}", f"{limits.MAX_STEPS_PER_CRANK_CYCLE:,}",
                   f"{limits.MIN_STEP_S:g} s", f"{limits.MAX_DYNAMICS_CYCLES:,}",
                   f"at least {limits.MIN_BORE_ELEMENTS} elements",
                   f"{limits.MAX_MESH_CELLS:,} quadrilaterals",
                   f"at most {limits.MAX_LOAD_STEPS_PER_CYCLE:,}",
                   f"{limits.MAX_WEAR_STEPS:,} wear steps"):
        assert stated in text, stated


def test_the_defaults_are_within_the_limits():
    from fewear.io.config import default_config

    limits.check_limits(default_config(), "defaults")


PIN_ON_DISC = "test_id,pressure_Pa,velocity_m_s,sliding_distance_m,wear_volume_m3\n"


@pytest.mark.parametrize("name, text, needles", [
    ("all-negative test", PIN_ON_DISC + "a,1e6,1,100,-1e-9\na,1e6,1,200,-2e-9\n"
     "b,2e6,1,100,1e-9\nb,2e6,1,200,2e-9\n", ["line 2", "every reading of test a is below zero"]),
    ("volume beyond a pin", PIN_ON_DISC + "a,1e6,1,100,5.0\n", ["5.0", "up to 100 cm^3"]),
    ("pressure beyond any material", PIN_ON_DISC + "a,1e300,1,100,1e-9\n",
     ["column pressure_Pa: 1e+300", "10 GPa"]),
    ("velocity of a glacier", PIN_ON_DISC + "a,1e6,1e-300,100,1e-9\n",
     ["column velocity_m_s: 1e-300", "0.1 um/s"]),
    ("distance beyond the moon", PIN_ON_DISC + "a,1e6,1,1e300,1e-9\n",
     ["column sliding_distance_m: 1e+300", "100,000 km"]),
    ("rate beyond severe wear", "test_id,normal_load_N,sliding_distance_m,"
     "specific_wear_rate_m3_N_m\na,10,100,1e-6\n", ["specific_wear_rate_m3_N_m", "1e3 mm^3/(N m)"]),
    ("all-negative profile", "cycles,angle_deg,wear_depth_m\n1000,0,-1e-6\n1000,90,-2e-6\n"
     "1000,180,-3e-6\n", ["column wear_depth_m: -1e-06", "check the sign"]),
    ("all-negative growth", "cycles,max_wear_depth_m\n1000,-1e-6\n2000,-2e-6\n",
     ["column max_wear_depth_m", "check the sign"]),
])
def test_measured_values_no_instrument_gives_are_input_errors(tmp_path, capsys, name, text,
                                                              needles):
    path = tmp_path / "measured.csv"
    path.write_text(text)
    assert main(["diagnose", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith(f"fewear: error: {path}") and err.count("\n") == 1, err
    for needle in needles:
        assert needle in err, err


def test_negative_depths_within_the_noise_are_kept():
    from fewear.diagnose.joint.measured import read_joint_measurements

    def depths(path):
        return read_joint_measurements(path)

    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "profiles.csv"
        path.write_text("cycles,angle_deg,wear_depth_m\n0,0,-5e-8\n0,90,4e-8\n0,180,0\n"
                        "1000,0,-1e-6\n1000,90,5e-6\n1000,180,1e-6\n")
        data = depths(path)
        assert any("below zero" in note for note in data.notes)


def test_measured_cycles_that_would_make_endless_forward_runs_are_refused(tmp_path, capsys):
    path = tmp_path / "profiles.csv"
    path.write_text("cycles,angle_deg,wear_depth_m\n" + "".join(
        f"{cycles},{angle},{depth}\n" for cycles, depth in ((1000, 1e-7), (10**14, 1e-6))
        for angle in (0, 90, 180)))
    assert main(["diagnose", str(path), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith(f"fewear: error: {path}: the last measured cycle count "
                          "100,000,000,000,000") and "at most 10,000" in err, err


def _mechanism_file(tmp_path, speed_rpm):
    """The example four-bar with its crank driven at ``speed_rpm``."""
    from fewear.io.mechanism import EXAMPLES_DIR

    text = (EXAMPLES_DIR / "four_bar.toml").read_text().replace(
        "speed_rpm = 1200.0", f"speed_rpm = {speed_rpm!r}")
    path = tmp_path / "four_bar_fast.toml"
    path.write_text(text)
    return path


@pytest.mark.parametrize("speed_rpm, step_s, refused", [
    (12.0, 0.004, False),    # 5 s cycle: 1,250 steps (the template's 1200 rpm would refuse it)
    (12000.0, 0.0005, True),  # 5 ms cycle: 10 steps (the template's 1200 rpm would allow it)
])
def test_the_time_step_is_checked_against_the_mechanism_files_driver(tmp_path, speed_rpm, step_s,
                                                                     refused):
    from fewear.io.config import load_config
    from fewear.mbd.slider_crank import SECTIONS

    config = tmp_path / "config.toml"
    config.write_text(f'[mechanism]\nfile = "{_mechanism_file(tmp_path, speed_rpm)}"\n'
                      f"[integrator]\nstep_s = {step_s!r}\n")
    if not refused:
        load_config(config, SECTIONS)
        return
    with pytest.raises(FewearInputError) as raised:
        load_config(config, SECTIONS)
    period = 60.0 / speed_rpm
    for needle in (f"step_s = {step_s!r}", f"{period:.3g} s", "driver of body 'crank'",
                   "at least 100 steps"):
        assert needle in str(raised.value)
