"""`fewear dynamics` on a mechanism file: a history per clearance joint, and a bad file as a
one-line error (exit 2, nothing written)."""

import csv
import json
import math

from fewear.cli import main


def test_two_joint_four_bar_writes_a_history_per_joint(tmp_path, capsys):
    config = tmp_path / "config.toml"
    config.write_text('[mechanism]\nfile = "four_bar_two_joints"\nsettling_cycles = 0\n')
    out = tmp_path / "out"
    assert main(["dynamics", "--config", str(config), "--rod", "rigid", "--cycles", "1",
                 "--out", str(out)]) == 0
    summary = json.loads((out / "summary.json").read_text())
    assert list(summary["joints"]) == ["crank_coupler", "coupler_rocker"]
    for name in summary["joints"]:
        with open(out / f"joint_history_{name}.csv") as handle:
            rows = list(csv.DictReader(handle))
        assert math.isclose(float(rows[-1]["crank_angle_deg"]), 360.0, rel_tol=1e-9)
        largest = max(float(row["penetration_m"]) for row in rows)
        # the pin centre stays within the clearance circle, plus the deepest penetration
        eccentricity = max(math.hypot(float(row["eccentricity_x_m"]),
                                      float(row["eccentricity_y_m"])) for row in rows)
        assert eccentricity <= 5e-4 + largest + 1e-12
        assert (out / f"orbit_{name}.png").stat().st_size > 0
    assert summary["peak_contact_force_N"] == summary["joints"]["crank_coupler"][
        "peak_contact_force_N"]


def test_bad_mechanism_file_exits_2_naming_the_joint(tmp_path, capsys):
    from fewear.io.mechanism import EXAMPLES_DIR

    text = (EXAMPLES_DIR / "four_bar.toml").read_text().replace('bushing_point = "rocker.B"',
                                                                 'bushing_point = "rocker.C"')
    mechanism = tmp_path / "bad.toml"
    mechanism.write_text(text)
    config = tmp_path / "config.toml"
    config.write_text(f'[mechanism]\nfile = "{mechanism}"\n')
    assert main(["dynamics", "--config", str(config), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert err.startswith("fewear: error:") and "joint 'coupler_rocker'" in err
    assert "rocker.C" in err and err.count("\n") == 1 and "Traceback" not in err
    assert not (tmp_path / "out").exists()
