"""The [diagnose] settings: bad values named, forced hold-outs checked, every noise model works."""

import dataclasses

import pytest

from fewear.calibrate.diagnose import DiagnoseSettings, diagnose, readings_from_columns
from fewear.calibrate.forward import grid_campaign, hidden_case
from fewear.errors import FewearInputError


@pytest.mark.parametrize("key, value, word", [
    ("holdout", "first", "holdout"),
    ("holdout_fraction", 1.5, "holdout_fraction"),
    ("noise_model", "gaussian", "noise_model"),
    ("candidates", ("friction",), "friction"),
    ("min_readings_per_test", 2, "min_readings_per_test"),
    ("min_gain", -0.1, "min_gain"),
    ("prediction_distance_factor", 0.5, "prediction_distance_factor"),
])
def test_bad_setting_is_named(key, value, word):
    with pytest.raises(FewearInputError, match=word):
        dataclasses.replace(DiagnoseSettings.default(), **{key: value})


def test_forced_later_readings_needs_enough_readings():
    campaign = grid_campaign(readings_per_test=3)
    columns, _, _ = hidden_case("none", 1, campaign)
    settings = dataclasses.replace(DiagnoseSettings.default(), holdout="later_readings")
    with pytest.raises(FewearInputError, match="min_readings_per_test"):
        diagnose(readings_from_columns(columns), settings)


@pytest.mark.parametrize("noise_model", ["increments", "lognormal", "relative"])
def test_every_noise_model_names_a_strong_running_in(noise_model):
    columns, _, _ = hidden_case("running_in", 3)
    settings = dataclasses.replace(DiagnoseSettings.default(), noise_model=noise_model)
    summary = diagnose(readings_from_columns(columns), settings).summary
    assert summary["cause"] == "running_in"
    assert summary["gain"] > 0.3
