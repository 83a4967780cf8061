"""The acceptance settings the three diagnoses share: each section's keys parsed into one type,
bad values refused naming the section and key, and the rule they make."""

import pytest

from fewear.diagnose.core.evidence import AcceptanceSettings, Evidence
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.diagnose.scar.settings import ScarDiagnoseSettings
from fewear.diagnose.tribometer.settings import DiagnoseSettings
from fewear.errors import FewearInputError
from fewear.io.config import load_config

KINDS = [(DiagnoseSettings, "diagnose"), (JointDiagnoseSettings, "joint_diagnose"),
         (ScarDiagnoseSettings, "scar_diagnose")]


@pytest.mark.parametrize("settings_type, section", KINDS)
def test_each_section_parses_its_acceptance_keys(settings_type, section):
    values = load_config(None, [section])[section]
    acceptance = settings_type.from_config(values).acceptance
    assert isinstance(acceptance, AcceptanceSettings)
    assert acceptance.significance == values["significance"]
    assert acceptance.min_aicc_improvement == values["min_aicc_improvement"]
    assert acceptance.min_held_out_gain == values.get("min_held_out_gain", 0.0)
    assert acceptance.min_effect_over_scatter == values.get("min_effect_over_scatter", 0.0)


@pytest.mark.parametrize("settings_type, section", KINDS)
@pytest.mark.parametrize("key, value", [("significance", 0.7), ("significance", 0.0),
                                        ("min_aicc_improvement", -1.0),
                                        ("min_aicc_improvement", float("nan"))])
def test_bad_acceptance_value_is_named_with_its_section(settings_type, section, key, value):
    values = load_config(None, [section])[section]
    with pytest.raises(FewearInputError, match=rf"\[{section}\] {key} = "):
        settings_type.from_config({**values, key: value})


def test_the_rule_divides_the_significance_by_the_forms_tried():
    settings = AcceptanceSettings("[x]", significance=0.05, min_aicc_improvement=2.0,
                                  min_held_out_gain=0.1)
    rule = settings.rule(5)
    assert rule.max_p == pytest.approx(0.01)
    assert rule.accepts(Evidence(p_value=0.009, gain=0.1, aicc_improvement=2.0))
    assert not rule.accepts(Evidence(p_value=0.011, gain=0.5, aicc_improvement=9.0))
    assert not rule.accepts(Evidence(p_value=0.001, gain=0.09, aicc_improvement=9.0))
    assert not rule.accepts(Evidence(p_value=0.001, gain=0.5, aicc_improvement=1.9))


def test_a_strict_gain_refuses_a_gain_equal_to_the_minimum():
    settings = AcceptanceSettings("[x]", significance=0.05, min_aicc_improvement=0.0,
                                  gain_strictly_above=True)
    assert not settings.rule(1).accepts(Evidence(p_value=0.0, gain=0.0, aicc_improvement=1.0))
    assert settings.rule(1).accepts(Evidence(p_value=0.0, gain=1e-9, aicc_improvement=1.0))
