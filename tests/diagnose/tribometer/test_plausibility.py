"""Pin-on-disc tables whose units cannot be right (issue 57): a wear coefficient k = V / (F s)
beyond what wear gives is refused naming the likely unit error, a rare one warned on screen,
a pasted duplicate row noted; tables the fitting cannot use end in one line, not a traceback."""

import numpy as np
import pytest

from fewear.cli import main
from fewear.diagnose.tribometer.plausibility import POSSIBLE_K_M2_N, USUAL_K_M2_N

LOAD_N = (20.0, 40.0, 80.0)
DISTANCES_m = (100.0, 200.0, 300.0, 400.0)
DENSITY_kg_m3 = 8000.0
PIN_AREA_m2 = 2.8e-5


def write_table(path, k_m2_N, *, wear_column="wear_volume_m3", scale=1.0, distance=None,
                material=False, repeat_first=False, force_column="normal_load_N"):
    """Nine tests of V = k F s exactly (k varied by a few percent per test), the wear column
    times ``scale`` (a unit error); a mass loss with a density column; the force as
    ``normal_load_N`` or as ``pressure_Pa`` on a pin of :data:`PIN_AREA_m2`."""
    rng = np.random.default_rng(5)
    header = ["test_id", force_column, "velocity_m_s", "sliding_distance_m", wear_column]
    header += ["density_kg_m3"] if wear_column == "mass_loss_kg" else []
    header += ["material"] if material else []
    lines = [",".join(header)]
    for test in range(9):
        load, k = LOAD_N[test % 3], k_m2_N * rng.lognormal(0.0, 0.05)
        for s in DISTANCES_m:
            volume = k * load * s
            wear = volume * (DENSITY_kg_m3 if wear_column == "mass_loss_kg" else 1.0) * scale
            force = load if force_column == "normal_load_N" else load / PIN_AREA_m2
            row = [f"T{test}", repr(force), repr(0.5 + test // 3), repr(s if distance is None
                                                                       else distance),
                   repr(wear)]
            row += [repr(DENSITY_kg_m3)] if wear_column == "mass_loss_kg" else []
            row += [f"M{test}"] if material else []
            lines.append(",".join(row))
            if repeat_first and test == 0 and s == DISTANCES_m[0]:
                lines.append(",".join(row))
    path.write_text("\n".join(lines) + "\n")
    return path


def diagnose(capsys, path, tmp_path):
    out = tmp_path / "out"
    status = main(["diagnose", str(path), "--out", str(out)])
    return status, capsys.readouterr().err, out


def test_volumes_a_billion_times_too_small_are_refused_naming_the_unit(tmp_path, capsys):
    path = write_table(tmp_path / "m3_twice.csv", 2e-13, scale=1e-9)
    status, err, out = diagnose(capsys, path, tmp_path)
    assert status == 2 and not out.exists()
    (line,) = [line for line in err.splitlines() if line.startswith("fewear: error:")]
    assert "outside what wear can give" in line and "converted to m^3 twice" in line
    median_k = float(line.split("= V / (F s) = ")[1].split()[0])
    assert median_k == pytest.approx(2e-22, rel=0.1) and median_k < POSSIBLE_K_M2_N[0]


def test_a_k_beyond_the_severest_wear_is_refused(tmp_path, capsys):
    """k = 2e-9 m^2/N (volumes below the reader's 100 cm^3 bound, e.g. mm^3 of a very mild
    wear under wear_volume_m3)."""
    path = write_table(tmp_path / "mm3.csv", 2e-9)
    status, err, _ = diagnose(capsys, path, tmp_path)
    assert status == 2 and "volume in mm^3 under wear_volume_m3" in err


def test_grams_under_mass_loss_kg_are_warned_on_screen(tmp_path, capsys):
    """k 1000x the typical 1.6e-13 m^2/N: possible (severe wear), so warned, not refused."""
    path = write_table(tmp_path / "grams.csv", 1.6e-13, wear_column="mass_loss_kg", scale=1e3)
    status, err, out = diagnose(capsys, path, tmp_path)
    assert status == 0 and (out / "diagnosis.json").exists()
    warnings = [line for line in err.splitlines() if "warning:" in line]
    assert len(warnings) == 1 and "mass in grams under mass_loss_kg" in warnings[0]
    assert float(warnings[0].split("= V / (F s) = ")[1].split()[0]) > USUAL_K_M2_N[1]


def test_a_usual_table_gives_no_warning(tmp_path, capsys):
    status, err, _ = diagnose(capsys, write_table(tmp_path / "ok.csv", 1.6e-13), tmp_path)
    assert status == 0 and "warning" not in err


def test_an_exact_duplicate_row_gets_a_note(tmp_path, capsys):
    path = write_table(tmp_path / "dup.csv", 1.6e-13, repeat_first=True)
    status, err, _ = diagnose(capsys, path, tmp_path)
    assert status == 0
    (warning,) = [line for line in err.splitlines() if "warning:" in line]
    assert "1 row(s) repeat an earlier row exactly" in warning and "line 3" in warning


def test_all_sliding_distances_zero_says_so(tmp_path, capsys):
    path = write_table(tmp_path / "no_distance.csv", 1.6e-13, distance=0.0)
    status, err, out = diagnose(capsys, path, tmp_path)
    assert status == 2 and not out.exists()
    assert "36 with zero sliding distance, 0 with zero or negative wear volume" in err


def test_every_test_its_own_material_is_one_line(tmp_path, capsys):
    path = write_table(tmp_path / "materials.csv", 1.6e-13, material=True)
    status, err, _ = diagnose(capsys, path, tmp_path)
    assert status == 2 and "Traceback" not in err
    assert "every test is its own material group (9 groups" in err


def test_a_large_table_reports_each_cause_tried(tmp_path, capsys, monkeypatch):
    """From LARGE_TABLE_TESTS tests on (here lowered to 9) each cause tried is a line on screen:
    a table of thousands of tests is minutes of fitting, no longer silent."""
    from fewear.diagnose.tribometer import command
    from fewear.diagnose.tribometer.settings import DiagnoseSettings

    monkeypatch.setattr(command, "LARGE_TABLE_TESTS", 9)
    status, err, _ = diagnose(capsys, write_table(tmp_path / "ok.csv", 1.6e-13), tmp_path)
    assert status == 0
    tried = [line for line in err.splitlines() if ": step " in line and "trying" in line]
    names = {line.rsplit("trying ", 1)[1] for line in tried}
    assert tried and names <= set(DiagnoseSettings.default().candidates)


def test_a_table_without_normal_load_says_its_k_is_not_checked_nor_k(tmp_path, capsys):
    """Pressures, no loads: k = V / (F s) cannot be computed (the fitted level is k A, here
    volumes 1e9 too small passed without a word and k A was written as k)."""
    path = write_table(tmp_path / "pressures.csv", 2e-13, scale=1e-9, force_column="pressure_Pa")
    status, err, out = diagnose(capsys, path, tmp_path)
    assert status == 0
    (warning,) = [line for line in err.splitlines() if "warning:" in line]
    assert ("no normal_load_N column: the wear coefficient k = V / (F s) cannot be computed"
            in warning)
    assert "k times the pins' apparent contact area A (F = p A), not k in m^2/N" in warning
    # the file a user would load says so too; a table with loads writes no such line
    assert "# NOT IN m^2/N" in (out / "extended_wear.toml").read_text()
    status, _, with_loads = diagnose(capsys, write_table(tmp_path / "loads.csv", 2e-13),
                                     tmp_path / "loads")
    assert status == 0 and "NOT IN" not in (with_loads / "extended_wear.toml").read_text()


def test_k_from_pressures_and_a_contact_area_is_checked(tmp_path):
    """Where k can be computed without normal_load_N (pressure x the caller's contact area), a k
    no wear gives is refused there too."""
    from fewear.diagnose.tribometer.measured import read_measured_wear, wear_coefficient_samples
    from fewear.errors import FewearInputError

    good = read_measured_wear(write_table(tmp_path / "good.csv", 2e-13,
                                          force_column="pressure_Pa"))
    _, _, k = wear_coefficient_samples(good, contact_area_m2=PIN_AREA_m2)
    assert np.median(k) == pytest.approx(2e-13, rel=0.1)
    bad = read_measured_wear(write_table(tmp_path / "bad.csv", 2e-13, scale=1e-9,
                                         force_column="pressure_Pa"))
    with pytest.raises(FewearInputError, match="outside what wear can give .* converted to m"):
        wear_coefficient_samples(bad, contact_area_m2=PIN_AREA_m2)
