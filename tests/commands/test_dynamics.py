"""`fewear dynamics` on the command line: outputs, and bad input as exit status 2."""

import csv
import json
import math
import re

import pytest

from fewear.cli import main
from fewear.io.config import default_config_text
from fewear.io.joint_history import read_joint_history


def config_file(tmp_path, replacements=(), extra=""):
    """The default config with (regex, replacement) edits applied, written to a file."""
    text = default_config_text()
    for pattern, replacement in replacements:
        text, count = re.subn(pattern, replacement, text, count=1, flags=re.M)
        assert count == 1, pattern
    path = tmp_path / "config.toml"
    path.write_text(text + extra)
    return str(path)


@pytest.mark.parametrize("replacements, extra, message", [
    ([(r"^radius_m = 0.0095", "radius_m = 0.0105")], "", "clearance"),
    ([(r"^slider_mass_kg = 0.5", "slider_mass_kg = 0.0")], "", "slider_mass_kg"),
    ([(r"^rod_length_m = 0.34", "rod_length_m = 0.05")], "", "rod_length_m"),
    ([(r"^step_s = 5.0e-5", "step_s = 0.0")], "", "step_s"),
    ([(r"^step_s = 5.0e-5", "step_s = -1e-5")], "", "step_s"),
    ([(r"^rho_inf = 0.5", "rho_inf = 0.5\nrho_infinity = 0.5")], "", "rho_infinity"),
    ([(r'^contact_law = "lankarani-nikravesh"', 'contact_law = "hertz"')], "", "hertz"),
    ([(r"^restitution_coefficient = 0.9", "restitution_coefficient = 1.5")], "", "restitution"),
])
def test_bad_input_exits_2_with_a_message(tmp_path, capsys, replacements, extra, message):
    path = config_file(tmp_path, replacements, extra)
    assert main(["dynamics", "--config", path, "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fewear: error:") and message in err
    assert "Traceback" not in err
    assert not (tmp_path / "out").exists()


def test_bad_cycle_count_exits_2(tmp_path, capsys):
    assert main(["dynamics", "--cycles", "0", "--out", str(tmp_path / "out")]) == 2
    assert "--cycles" in capsys.readouterr().err


def test_writes_history_summary_and_plots(tmp_path, capsys):
    path = config_file(tmp_path, [(r"^settling_cycles = \d+", "settling_cycles = 0")])
    out = tmp_path / "out"
    assert main(["dynamics", "--config", path, "--rod", "rigid", "--joint", "clearance",
                 "--cycles", "1", "--out", str(out)]) == 0
    assert "cycle 1/1" in capsys.readouterr().err
    with open(out / "joint_history.csv") as handle:
        rows = list(csv.DictReader(handle))
    assert list(rows[0]) == ["time_s", "force_x_N", "force_y_N", "relative_omega_rad_s",
                             "crank_angle_deg", "eccentricity_x_m", "eccentricity_y_m",
                             "penetration_m", "normal_force_N", "friction_force_N", "mode"]
    assert {row["mode"] for row in rows} <= {"free", "impact", "contact"}
    assert float(rows[-1]["crank_angle_deg"]) == pytest.approx(360.0)
    summary = json.loads((out / "summary.json").read_text())
    assert summary["steps"] >= len(rows) - 1
    assert summary["peak_contact_force_N"] == pytest.approx(
        max(math.hypot(float(r["force_x_N"]), float(r["force_y_N"])) for r in rows), rel=1e-6)
    assert summary["config"]["mechanism"]["rod"] == "rigid"
    # the form `fewear run --joint-history` reads (fewear.io.joint_history), to the same floats
    history = read_joint_history(out / "joint_history.csv")
    assert history.peak_contact_force_N == summary["peak_contact_force_N"]
    assert history.n_steps == len(rows) and history.impacts == summary["impacts"]
    # eccentricities stay near the clearance circle: |e| <= c + the largest penetration
    largest = max(float(r["penetration_m"]) for r in rows)
    assert max(math.hypot(float(r["eccentricity_x_m"]), float(r["eccentricity_y_m"]))
               for r in rows) <= 5e-4 + largest + 1e-12
    assert (out / "forces.png").stat().st_size > 0 and (out / "orbit.png").stat().st_size > 0
