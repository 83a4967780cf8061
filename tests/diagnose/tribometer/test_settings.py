"""The [diagnose] settings: bad values named; too few tests refused."""

import dataclasses

import numpy as np
import pytest

from fewear.diagnose.tribometer.diagnose import diagnose
from fewear.diagnose.tribometer.readings import readings_from_columns
from fewear.diagnose.tribometer.settings import DiagnoseSettings
from fewear.errors import FewearInputError
from fewear.io.config import load_config
from tests.diagnose.tribometer.campaign_generator import grid_campaign, hidden_case


@pytest.mark.parametrize("key, value, word", [
    ("significance", 0.9, "significance"),
    ("min_aicc_improvement", -1.0, "min_aicc_improvement"),
    ("candidates", ("friction",), "friction"),
    ("min_readings_along_test", 2, "min_readings_along_test"),
    ("min_conditions_for_network", 3, "min_conditions_for_network"),
    ("prediction_distance_factor", 0.5, "prediction_distance_factor"),
    ("min_effect_over_scatter", -1.0, "min_effect_over_scatter"),
])
def test_bad_setting_is_named(key, value, word):
    section = load_config(None, ["diagnose"])["diagnose"]
    with pytest.raises(FewearInputError, match=word):
        DiagnoseSettings.from_config({**section, key: value})


def test_two_tests_are_too_few():
    campaign = grid_campaign(pressures_Pa=(1e6, 2e6), velocities_m_s=(0.5,))
    columns, _, _ = hidden_case("none", 1, campaign)
    with pytest.raises(FewearInputError, match="2 test.*at least 3"):
        diagnose(readings_from_columns(columns))


def k_step_table(ratio: float, noise: float, repeats: int = 20, seed: int = 3) -> dict:
    """One reading per test (a table) of 6 pressures x 2 speeds x ``repeats``: k rises by
    ``ratio`` above 2.5 MPa (a mild-to-severe step), each reading scattered by ``noise``."""
    rng = np.random.default_rng(seed)
    pressure, speed = np.meshgrid([1e6, 1.5e6, 2e6, 3e6, 4e6, 5e6], [0.5, 1.0])
    pressure = np.repeat(pressure.ravel(), repeats)
    speed = np.repeat(speed.ravel(), repeats)
    k = 1e-14 * np.where(pressure > 2.5e6, ratio, 1.0)
    distance = np.full(pressure.size, 1000.0)
    load = pressure * 1e-5
    return {"test_id": np.arange(pressure.size), "pressure_Pa": pressure,
            "velocity_m_s": speed, "sliding_distance_m": distance, "normal_load_N": load,
            "wear_volume_m3": k * load * distance * np.exp(noise * rng.standard_normal(
                pressure.size))}


def test_the_effect_floor_refuses_a_significant_effect_inside_the_scatter():
    """k rising by 2 % under 3 % scatter over 240 tests: the step is significant, so without
    the floor it is named; it changes no reading by a scatter, so with the floor at one
    scatter it is refused, and a step of 30 % is named with it."""
    settings = dataclasses.replace(DiagnoseSettings.default(), candidates=("mild_to_severe",))
    without, floor = (dataclasses.replace(settings, acceptance=dataclasses.replace(
        settings.acceptance, min_effect_over_scatter=value)) for value in (0.0, 1.0))
    small = readings_from_columns(k_step_table(1.02, 0.03))
    assert diagnose(small, without).causes == ("mild_to_severe",)
    refused = diagnose(small, floor)
    assert refused.causes == ()
    (trial,) = refused.stages[0].steps[0]
    assert trial.evidence.p_value < 1e-3 and trial.evidence.effect_over_scatter < 1.0
    assert "do not resolve" in trial.verdict
    assert diagnose(readings_from_columns(k_step_table(1.3, 0.03)), floor).causes == (
        "mild_to_severe",)
