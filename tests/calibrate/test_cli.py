"""`fewear diagnose`: outputs that exist and parse, bad data and bad config refused with a message
naming the place (exit 2) and nothing written."""

import json
import re
from pathlib import Path

import numpy as np
import pytest

from fewear.calibrate.forward import hidden_case, write_measured_csv
from fewear.cli import main
from fewear.io.config import DEFAULTS_DIR, load_config
from fewear.wear.coefficient import wear_coefficient_from_config
from fewear.wear.extensions import RunningIn, wear_extension_from_config


@pytest.fixture(scope="module")
def running_in_csv(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("data") / "running_in.csv"
    columns, _, _ = hidden_case("running_in", 7)
    write_measured_csv(path, columns, "SYNTHETIC: running-in hidden (tests/calibrate/test_cli.py)")
    return path


@pytest.fixture(scope="module")
def outputs(running_in_csv, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("run") / "diagnosis"
    assert main(["diagnose", str(running_in_csv), "--out", str(out)]) == 0
    return out


def test_outputs_exist_and_parse(outputs):
    summary = json.loads((outputs / "diagnosis.json").read_text())
    for key in ("data_kind", "baseline", "candidates", "cause", "gain", "extended_config"):
        assert key in summary
    assert summary["data_kind"] == "cumulative_volume"
    assert summary["cause"] == "running_in"
    assert summary["baseline"]["held_out_error"] > summary["held_out_error"]["extended"]
    for candidate in summary["candidates"]:
        assert {"name", "params", "held_out_error", "score"} <= set(candidate)
    gain = summary["gain"]
    assert gain == pytest.approx(1 - summary["held_out_error"]["extended"]
                                 / summary["baseline"]["held_out_error"])
    report = (outputs / "report.md").read_text()
    figures = re.findall(r"!\[[^\]]*\]\(([^)]+)\)", report)
    assert len(figures) == 3
    for name in figures:
        assert (outputs / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "running_in" in report


def test_extended_config_is_what_the_simulation_loads(outputs):
    section = load_config(outputs / "extended_wear.toml", sections=["wear"])["wear"]
    extension = wear_extension_from_config(section)
    assert isinstance(extension, RunningIn)
    summary = json.loads((outputs / "diagnosis.json").read_text())
    assert extension.params() == pytest.approx(summary["extended_config"]["extension_params"])
    k = wear_coefficient_from_config(section)
    # the network's steady k sits inside the range of the tests' steady k (bounded by the data)
    assert 1e-14 < float(k(2e6, 0.5)) < 1e-12


def test_bad_data_exit_2_names_line_and_column(tmp_path, running_in_csv, capsys):
    lines = running_in_csv.read_text().splitlines()
    header_index = next(i for i, line in enumerate(lines) if line.startswith("test_id"))
    row = lines[header_index + 3].split(",")
    row[4] = "1e-12"  # the 3rd reading of the first test less than the 2nd: volume decreases
    lines[header_index + 3] = ",".join(row)
    bad = tmp_path / "decreasing.csv"
    bad.write_text("\n".join(lines) + "\n")
    out = tmp_path / "out"
    assert main(["diagnose", str(bad), "--out", str(out)]) == 2
    message = capsys.readouterr().err
    assert message.startswith("fewear: error:")
    assert f"line {header_index + 4}" in message and "wear_volume_m3" in message
    assert not out.exists()


def test_missing_required_column_exit_2(tmp_path, running_in_csv, capsys):
    text = running_in_csv.read_text().replace("wear_volume_m3", "wear_depth_m")
    bad = tmp_path / "no_volume.csv"
    bad.write_text(text)
    out = tmp_path / "out"
    assert main(["diagnose", str(bad), "--out", str(out)]) == 2
    message = capsys.readouterr().err
    assert "line" in message and "wear" in message
    assert not out.exists()


def test_bad_config_exit_2(tmp_path, running_in_csv, capsys):
    text = (DEFAULTS_DIR / "diagnose.toml").read_text()
    config = tmp_path / "config.toml"
    config.write_text(text.replace('holdout = "auto"', 'holdout = "first_readings"'))
    out = tmp_path / "out"
    assert main(["diagnose", str(running_in_csv), "--config", str(config), "--out",
                 str(out)]) == 2
    assert "holdout = 'first_readings'" in capsys.readouterr().err
    assert not out.exists()


def test_missing_variables_are_reported_not_invented(tmp_path):
    columns, _, _ = hidden_case("none", 8)
    kept = {name: values for name, values in columns.items()
            if name not in ("time_s", "velocity_m_s", "friction_coefficient")}
    path = tmp_path / "sparse.csv"
    write_measured_csv(path, kept, "SYNTHETIC: no speed, time or friction")
    out = tmp_path / "out"
    assert main(["diagnose", str(path), "--out", str(out)]) == 0
    summary = json.loads((out / "diagnosis.json").read_text())
    assert [c["name"] for c in summary["candidates"]] == ["running_in"]
    assert {e["name"] for e in summary["untestable"]} == {"time_transient", "thermal"}
    report = (out / "report.md").read_text()
    assert "could not be tested: needs time_s" in report
    assert np.isfinite(summary["baseline"]["held_out_error"])
