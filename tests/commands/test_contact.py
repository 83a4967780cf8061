"""`fewear contact` end to end on the default config, and its refusals of bad input.

The good run is checked against physics the CLI does not compute for itself: the nodal pressures of
contact.csv, integrated along the bore, give back the applied force; the peak sits in the load
direction. Bad input must give exit status 2, a one-line message on stderr naming the value, no
traceback and no output folder.
"""

import csv
import json
import math
import subprocess
import sys
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np
import pytest

from fewear.cli import main
from fewear.contact.analytic import q8_bore_weights_m
from fewear.contact.params import CONFIG_SECTIONS
from fewear.io.config import default_config

FORCE_N = (300.0, -800.0)
CSV_COLUMNS = ["angle_deg", "x_m", "y_m", "pressure_Pa", "gap_m", "slip_m"]


@pytest.fixture(scope="module")
def default_run(tmp_path_factory):
    out = tmp_path_factory.mktemp("contact") / "out"
    status = main(["contact", "--force", *map(str, FORCE_N), "--out", str(out)])
    return status, out


def read_csv(path):
    with open(path, newline="") as handle:
        reader = csv.reader(handle)
        header = next(reader)
        values = np.array([[float(value) for value in row] for row in reader])
    return header, {name: values[:, k] for k, name in enumerate(header)}


def test_default_run_writes_the_four_outputs(default_run):
    status, out = default_run
    assert status == 0
    names = {path.name for path in out.iterdir()}
    assert {"contact.csv", "summary.json", "bushing.xdmf", "bushing.h5", "pressure.png"} <= names
    assert not [name for name in names if name.startswith(".fewear-staging")]
    assert (out / "pressure.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_csv_columns_and_bore_geometry(default_run):
    _, out = default_run
    header, columns = read_csv(out / "contact.csv")
    assert header == CSV_COLUMNS
    radius = default_config()["bushing"]["inner_radius_m"]
    assert np.allclose(np.hypot(columns["x_m"], columns["y_m"]), radius, rtol=1e-9)
    angles = np.radians(columns["angle_deg"])
    assert np.allclose(np.cos(angles) * radius, columns["x_m"], atol=1e-12)
    assert np.all(np.diff(columns["angle_deg"]) > 0)


def test_summary_keys_and_force_balance(default_run):
    _, out = default_run
    summary = json.loads((out / "summary.json").read_text())
    for key in ("max_pressure_Pa", "contact_half_angle_deg", "pin_centre_m",
                "force_balance_rel_error", "applied_force_N", "newton_iterations", "wall_time_s",
                "references", "config"):
        assert key in summary
    assert summary["force_balance_rel_error"] < 1e-8
    assert summary["applied_force_N"] == list(FORCE_N)
    assert summary["config"]["bushing"] == default_config()["bushing"]
    assert 0.0 < summary["contact_half_angle_deg"] < 90.0
    # the pin moves along the force, by more than the clearance (it presses into the bore)
    pin = np.array(summary["pin_centre_m"])
    clearance = default_config()["bushing"]["inner_radius_m"] - default_config()["pin"]["radius_m"]
    direction = np.array(FORCE_N) / np.hypot(*FORCE_N)
    assert pin @ direction > clearance
    assert abs(np.cross(pin, direction)) < 1e-3 * clearance


def test_csv_pressures_carry_the_applied_force(default_run):
    """The nodal pressures of contact.csv, integrated along the bore with the Q8 nodes' Simpson
    weights (l/6, 2l/3, l/6 per edge) against the normals from the pin centre, give back F. The
    solver integrates on the deformed bore; the undeformed node positions of the CSV leave a
    difference of order |u|/R_b ~ 1e-6."""
    _, out = default_run
    _, columns = read_csv(out / "contact.csv")
    summary = json.loads((out / "summary.json").read_text())
    bushing = default_config()["bushing"]
    angles = np.radians(columns["angle_deg"])
    weights = q8_bore_weights_m(angles, bushing["inner_radius_m"])
    from_pin = np.column_stack([columns["x_m"], columns["y_m"]]) - summary["pin_centre_m"]
    normals = from_pin / np.linalg.norm(from_pin, axis=1, keepdims=True)
    force = bushing["width_m"] * (weights * columns["pressure_Pa"]) @ normals
    assert np.linalg.norm(force - np.array(FORCE_N)) < 2e-5 * np.hypot(*FORCE_N)
    load_angle = math.atan2(FORCE_N[1], FORCE_N[0]) % (2 * math.pi)
    node_spacing = angles[1] - angles[0]
    assert abs(angles[np.argmax(columns["pressure_Pa"])] - load_angle) <= node_spacing


def test_xdmf_parses_and_holds_both_fields(default_run):
    h5py = pytest.importorskip("h5py")
    _, out = default_run
    root = ElementTree.parse(out / "bushing.xdmf").getroot()
    attributes = {element.get("Name"): element for element in root.iter("Attribute")}
    assert {"displacement_m", "pressure_Pa"} <= set(attributes)
    topology = next(root.iter("Topology"))
    assert topology.get("TopologyType") == "Quadrilateral_9"
    with h5py.File(out / "bushing.h5", "r") as h5:
        fields = {}
        for name, element in attributes.items():
            file_name, dataset = element.find("DataItem").text.strip().split(":")
            assert file_name == "bushing.h5"
            fields[name] = np.asarray(h5[dataset])
    summary = json.loads((out / "summary.json").read_text())
    assert np.isclose(fields["pressure_Pa"].max(), summary["max_pressure_Pa"], rtol=1e-6)
    displacement = fields["displacement_m"]
    assert np.all(np.isfinite(displacement)) and np.abs(displacement).max() > 0.0


def test_a_disk_without_room_for_the_xdmf_is_refused_before_hdf5_writes(default_run, tmp_path,
                                                                       monkeypatch, capsys):
    """Room for less than the fields' HDF5 file (its size estimated from the mesh, at least the
    default run's real one): one line naming the folder, the file and the bytes; no HDF5
    diagnostics, no traceback, no folder (issue 57; HDF5 writing onto the full disk printed
    pages of diagnostics and a RuntimeError traceback)."""
    import re

    import fewear.contact.output

    real_bytes = (default_run[1] / "bushing.h5").stat().st_size
    monkeypatch.setattr(fewear.contact.output, "_free_bytes", lambda path: real_bytes - 1)
    capsys.readouterr()
    out = tmp_path / "out"
    assert main(["contact", "--force", *map(str, FORCE_N), "--out", str(out)]) == 2
    last = capsys.readouterr().err.splitlines()[-1]
    assert last.startswith(f"fewear: error: No space left on device: the disk holding {out} is "
                           "full (writing bushing.h5 needed ")
    needed = int(re.search(r"needed ([\d,]+) bytes", last).group(1).replace(",", ""))
    assert real_bytes <= needed <= 1.05 * real_bytes
    assert not out.exists()


def test_rotation_gives_slip_and_friction_turns_the_contact(tmp_path):
    """--rotation 0.02 --friction: every node in contact slips R_p * 0.02 (the others 0), and the
    Coulomb traction p (n + mu t) turns the resultant of each loaded node by atan(mu), so the
    pressure's own resultant, int p n, must point atan(mu) behind F (mu = 0.1 from [joint])."""
    out = tmp_path / "out"
    rotation, config = 0.02, default_config()
    assert main(["contact", "--force", *map(str, FORCE_N), "--rotation", str(rotation),
                 "--friction", "--out", str(out)]) == 0
    _, columns = read_csv(out / "contact.csv")
    summary = json.loads((out / "summary.json").read_text())
    loaded = columns["pressure_Pa"] > 0.0
    assert np.allclose(columns["slip_m"][loaded], config["pin"]["radius_m"] * rotation, rtol=1e-12)
    assert np.all(columns["slip_m"][~loaded] == 0.0)
    assert summary["force_balance_rel_error"] < 1e-8 and summary["friction"] is True
    angles = np.radians(columns["angle_deg"])
    weights = q8_bore_weights_m(angles, config["bushing"]["inner_radius_m"])
    normal_resultant = (weights * columns["pressure_Pa"]) @ np.column_stack(
        [np.cos(angles), np.sin(angles)])
    lag = math.atan2(normal_resultant[1], normal_resultant[0]) - math.atan2(FORCE_N[1], FORCE_N[0])
    assert abs(lag + math.atan(config["joint"]["friction_coefficient"])) < math.radians(0.02)


# --- bad input -------------------------------------------------------------------------------


def config_file(tmp_path, changes=None, drop=(), extra=None):
    """The default contact sections as TOML with `changes` {"section.key": value}, keys `drop`ped
    ("section.key") and `extra` {"section": "key = value"} lines."""
    changes, extra = changes or {}, extra or {}
    defaults = default_config()
    lines = []
    for section in CONFIG_SECTIONS:
        lines.append(f"[{section}]")
        for key, value in defaults[section].items():
            name = f"{section}.{key}"
            if name not in drop:
                lines.append(f"{key} = {changes.get(name, value)!r}")
        if section in extra:
            lines.append(extra[section])
    path = tmp_path / "case.toml"
    path.write_text("\n".join(lines) + "\n")
    return path


BAD_CONFIGS = {
    "pin not smaller than bore": ({"changes": {"pin.radius_m": 0.0101}}, "0.0101"),
    "non-positive modulus": ({"changes": {"bushing.youngs_modulus_Pa": -90e9}}, "-90000000000"),
    "zero modulus": ({"changes": {"bushing.youngs_modulus_Pa": 0.0}}, "youngs_modulus_Pa"),
    "poisson ratio 0.5": ({"changes": {"bushing.poisson_ratio": 0.5}}, "0.5"),
    "unknown key": ({"extra": {"mesh": "bore_colour = 3.0"}}, "bore_colour"),
}


@pytest.mark.parametrize("case", list(BAD_CONFIGS))
def test_bad_config_exits_2_naming_the_value(tmp_path, capsys, case):
    options, named = BAD_CONFIGS[case]
    path = config_file(tmp_path, **options)
    out = tmp_path / "out"
    status = main(["contact", "--force", "0", "-100", "--config", str(path), "--out", str(out)])
    error = capsys.readouterr().err
    assert status == 2
    assert error.startswith("fewear: error:") and named in error
    assert "Traceback" not in error
    assert not out.exists()


@pytest.mark.parametrize("arguments, named", [
    (["--force", "0", "-100", "--rotation", "nan"], "--rotation = nan"),
    (["--force", "0", "-100", "--friction"], "--friction needs a non-zero --rotation"),
    (["--force", "0", "-100", "--rotation", "1e300"],
     "--rotation = 1e+300 rad: expected a finite increment of at most 12.6 rad (two turns)"),
    (["--force", "0", "-100", "--rotation", "-13"], "--rotation = -13.0 rad"),
])
def test_bad_rotation_exits_2(tmp_path, capsys, arguments, named):
    out = tmp_path / "out"
    assert main(["contact", *arguments, "--out", str(out)]) == 2
    error = capsys.readouterr().err
    assert error.startswith("fewear: error:") and named in error
    assert not out.exists()


@pytest.mark.parametrize("force, named", [(("nan", "0"), "FX = nan"), (("0", "inf"), "FY = inf"),
                                          (("1e999", "1"), "FX = inf")])
def test_non_finite_force_exits_2(tmp_path, capsys, force, named):
    out = tmp_path / "out"
    status = main(["contact", "--force", *force, "--out", str(out)])
    error = capsys.readouterr().err
    assert status == 2
    assert error.startswith("fewear: error: --force") and named in error
    assert not out.exists()


def test_force_the_bushing_cannot_carry_exits_2(tmp_path, capsys):
    """1e12 N: no traceback, the force and the admissible range named, nothing written; the
    range is the one the condensed path derives independently (G instead of an LU solve)."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.params import contact_problem_from_config
    from fewear.io.config import load_config

    out = tmp_path / "out"
    status = main(["contact", "--force", "1e12", "0", "--out", str(out)])
    error = capsys.readouterr().err.strip().splitlines()[-1]  # after the progress line
    assert status == 2
    assert error.startswith("fewear: error: force = (1e+12, 0) N: the bushing cannot carry it")
    assert "Traceback" not in error and not out.exists()
    admissible = float(error.split("|F| <= ")[1].split(" N")[0])
    problem = contact_problem_from_config(load_config(None, CONFIG_SECTIONS))
    fast = CondensedBushingContact(problem)
    assert admissible == pytest.approx(fast.admissible_force_N((1.0, 0.0)), rel=1e-2)


def test_unwritable_output_folder_exits_2(tmp_path, capsys):
    blocker = tmp_path / "file.txt"
    blocker.write_text("a file, not a folder")
    out = blocker / "out"
    status = main(["contact", "--force", "0", "-100", "--out", str(out)])
    error = capsys.readouterr().err
    assert status == 2
    assert str(out) in error and "Traceback" not in error
    assert blocker.read_text() == "a file, not a folder"


def test_existing_output_folder_unchanged_on_error(tmp_path, capsys):
    out = tmp_path / "out"
    out.mkdir()
    (out / "keep.txt").write_text("old result")
    status = main(["contact", "--force", "nan", "0", "--out", str(out)])
    assert status == 2
    assert [path.name for path in out.iterdir()] == ["keep.txt"]
    assert (out / "keep.txt").read_text() == "old result"


def fewear_executable():
    script = Path(sys.executable).parent / "fewear"
    return [str(script)] if script.exists() else [sys.executable, "-m", "fewear.cli"]


def test_installed_command_exit_status_and_stderr(tmp_path):
    path = config_file(tmp_path, changes={"bushing.poisson_ratio": 0.55})
    out = tmp_path / "out"
    process = subprocess.run(
        [*fewear_executable(), "contact", "--force", "10", "0", "--config", str(path),
         "--out", str(out)],
        capture_output=True, text=True, timeout=120,
    )
    assert process.returncode == 2
    assert process.stderr.startswith("fewear: error:") and "0.55" in process.stderr
    assert "Traceback" not in process.stderr and process.stdout == ""
    assert not out.exists()
