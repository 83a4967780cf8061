"""The demo demos/diagnose_tribometer.py runs and finds the running-in hidden in its data set."""

import json
import runpy
from pathlib import Path

import pytest

from fewear.data import make_running_in_pin_on_disc as made
from fewear.io.config import load_config
from fewear.wear.extensions import RunningIn, wear_extension_from_config

DEMO = Path(__file__).resolve().parents[2] / "demos" / "diagnose_tribometer.py"


def test_demo_finds_the_hidden_running_in(tmp_path, monkeypatch):
    monkeypatch.setenv("FEWEAR_DEMO_OUT", str(tmp_path))
    monkeypatch.setenv("MPLBACKEND", "Agg")
    runpy.run_path(str(DEMO), run_name="__main__")
    summary = json.loads((tmp_path / "diagnosis.json").read_text())
    assert summary["cause"] == "running_in"
    assert summary["gain"] > 0.5
    for name in ("fits.png", "residuals.png", "candidates.png", "report.md"):
        assert (tmp_path / name).stat().st_size > 0
    extension = wear_extension_from_config(
        load_config(tmp_path / "extended_wear.toml", sections=["wear"])["wear"])
    assert isinstance(extension, RunningIn)
    # the parameters the data were made with (the data set's header), recovered within the scatter:
    # the extra wear of running-in, (r - 1) s0, to 30 %; r and s0 each to a factor 2
    truth = RunningIn(made.K_INITIAL_OVER_STEADY, made.DISTANCE_SCALE_m)
    extra = (extension.k_initial_over_steady - 1) * extension.distance_scale_m
    assert extra == pytest.approx((truth.k_initial_over_steady - 1) * truth.distance_scale_m,
                                  rel=0.3)
    assert 0.5 < extension.k_initial_over_steady / truth.k_initial_over_steady < 2.0
    assert 0.5 < extension.distance_scale_m / truth.distance_scale_m < 2.0


def test_shipped_data_set_is_what_its_script_makes(tmp_path):
    """The shipped CSV is reproducible from its script (the header says how it was made)."""
    regenerated = tmp_path / "again.csv"
    from fewear.calibrate.forward import write_measured_csv

    write_measured_csv(regenerated, made.make(), made.HEADER)
    assert regenerated.read_text() == made.OUTPUT.read_text()
