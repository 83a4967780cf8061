"""The [diagnose] settings: bad values named; too few tests refused."""

import dataclasses

import pytest

from fewear.diagnose.tribometer.diagnose import diagnose
from fewear.diagnose.tribometer.forward import grid_campaign, hidden_case
from fewear.diagnose.tribometer.readings import readings_from_columns
from fewear.diagnose.tribometer.settings import DiagnoseSettings
from fewear.errors import FewearInputError


@pytest.mark.parametrize("key, value, word", [
    ("significance", 0.9, "significance"),
    ("min_aicc_improvement", -1.0, "min_aicc_improvement"),
    ("candidates", ("friction",), "friction"),
    ("min_readings_along_test", 2, "min_readings_along_test"),
    ("min_conditions_for_network", 3, "min_conditions_for_network"),
    ("prediction_distance_factor", 0.5, "prediction_distance_factor"),
])
def test_bad_setting_is_named(key, value, word):
    with pytest.raises(FewearInputError, match=word):
        dataclasses.replace(DiagnoseSettings.default(), **{key: value})


def test_two_tests_are_too_few():
    campaign = grid_campaign(pressures_Pa=(1e6, 2e6), velocities_m_s=(0.5,))
    columns, _, _ = hidden_case("none", 1, campaign)
    with pytest.raises(FewearInputError, match="2 test.*at least 3"):
        diagnose(readings_from_columns(columns))
