"""`fewear diagnose`: outputs that exist and parse, readings that dip kept and counted, bad data
and bad config refused with a message naming the place (exit 2) and nothing written."""

import json
import re
from pathlib import Path

import numpy as np
import pytest

from fewear.cli import main
from fewear.io.config import DEFAULTS_DIR, load_config
from fewear.wear.coefficient import wear_coefficient_from_config
from fewear.wear.extensions import RunningIn, wear_extension_from_config
from tests.diagnose.shared_keys import assert_shared_keys
from tests.diagnose.tribometer.campaign_generator import hidden_case, write_measured_csv
from tests.mpi import mpirun_fewear


@pytest.fixture(scope="module")
def running_in_csv(tmp_path_factory) -> Path:
    path = tmp_path_factory.mktemp("data") / "running_in.csv"
    columns, _, _ = hidden_case("running_in", 7)
    write_measured_csv(path, columns,
                       "SYNTHETIC: running-in hidden (tests/diagnose/tribometer/test_cli.py)")
    return path


@pytest.fixture(scope="module")
def outputs(running_in_csv, tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("run") / "diagnosis"
    assert main(["diagnose", str(running_in_csv), "--out", str(out)]) == 0
    return out


def test_outputs_exist_and_parse(outputs):
    summary = json.loads((outputs / "diagnosis.json").read_text())
    for key in ("data_kind", "baseline", "candidates", "causes", "cause", "gain",
                "extended_config", "unexplained"):
        assert key in summary
    assert summary["data_kind"] == "cumulative_volume"
    assert summary["cause"] == "running_in" == summary["causes"][0]
    assert summary["baseline"]["held_out_error"] > summary["held_out_error"]["extended"]
    assert_shared_keys(summary)
    for candidate in summary["candidates"]:
        assert {"cause", "form", "params", "held_out_error", "p_value", "verdict"} <= set(candidate)
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
    assert type(extension) is RunningIn
    summary = json.loads((outputs / "diagnosis.json").read_text())
    assert extension.params() == pytest.approx(summary["extended_config"]["extension_params"])
    k = wear_coefficient_from_config(section)
    # the network's steady k sits inside the range of the tests' steady k (bounded by the data)
    assert 1e-14 < float(k(2e6, 0.5)) < 1e-12


def _with_cell(path: Path, reading: int, column: str, value: str) -> tuple[str, int]:
    """The CSV text with ``column`` of the ``reading``-th data row set to ``value``, and the
    file line of that row."""
    lines = path.read_text().splitlines()
    header_index = next(i for i, line in enumerate(lines) if line.startswith("test_id"))
    header = lines[header_index].split(",")
    row = lines[header_index + reading].split(",")
    row[header.index(column)] = value
    lines[header_index + reading] = ",".join(row)
    return "\n".join(lines) + "\n", header_index + reading + 1


def test_a_reading_that_dips_is_kept_and_counted(tmp_path, running_in_csv):
    """The 3rd reading of the first test below the 2nd: data (scatter), not an error."""
    text, _ = _with_cell(running_in_csv, 3, "wear_volume_m3", "1e-12")
    dipped = tmp_path / "dipped.csv"
    dipped.write_text(text)
    out = tmp_path / "out"
    assert main(["diagnose", str(dipped), "--out", str(out)]) == 0
    summary = json.loads((out / "diagnosis.json").read_text())
    assert any(note.startswith("1 reading(s) of wear_volume_m3 dip") for note in summary["notes"])
    rows = [line for line in text.splitlines() if line and not line.startswith(("#", "test_id"))]
    assert summary["n_readings"] == len(rows)


def test_bad_data_exit_2_names_line_and_column(tmp_path, running_in_csv, capsys):
    """The sliding distance of the 3rd reading of the first test less than the 2nd's."""
    text, line = _with_cell(running_in_csv, 3, "sliding_distance_m", "1")
    bad = tmp_path / "decreasing.csv"
    bad.write_text(text)
    out = tmp_path / "out"
    assert main(["diagnose", str(bad), "--out", str(out)]) == 2
    message = capsys.readouterr().err
    assert message.startswith("fewear: error:")
    assert f"line {line}" in message and "sliding_distance_m" in message
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
    config.write_text(text.replace("significance = 0.05", "significance = 0.7"))
    out = tmp_path / "out"
    assert main(["diagnose", str(running_in_csv), "--config", str(config), "--out",
                 str(out)]) == 2
    assert "significance = 0.7" in capsys.readouterr().err
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
    assert {c["cause"] for c in summary["candidates"]} == {"running_in", "load_exponent",
                                                          "mild_to_severe"}
    assert {e["cause"] for e in summary["untestable"]} == {"time_transient", "thermal"}
    report = (out / "report.md").read_text()
    assert "could not be tested: needs time_s" in report
    assert np.isfinite(summary["baseline"]["held_out_error"])


@pytest.mark.slow  # the pin-on-disc diagnosis on two ranks; the serial command tests stay
@pytest.mark.mpi
def test_two_ranks_diagnose_tribometer_data_once(running_in_csv, outputs, tmp_path):
    """`mpirun -n 2 fewear diagnose` on a pin-on-disc table: the serial diagnosis runs on rank 0
    alone (one verdict; before, each rank ran it and both wrote the folder) and writes what the
    serial command writes: the same files, diagnosis.json the same to the byte."""
    out = tmp_path / "mpi"
    process = mpirun_fewear("diagnose", str(running_in_csv), "--out", str(out))
    assert process.returncode == 0, process.stderr
    assert process.stdout.count("fewear diagnose: causes running_in") == 1
    assert "rank 0 runs it, the other 1 rank(s)" in process.stderr
    assert sorted(p.name for p in out.iterdir()) == sorted(p.name for p in outputs.iterdir())
    assert (out / "diagnosis.json").read_text() == (outputs / "diagnosis.json").read_text()
    assert [p.name for p in tmp_path.iterdir()] == ["mpi"]  # no staging folder left
