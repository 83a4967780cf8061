"""Every diagnosis declares its causes one way (fewear.diagnose.core.cause.Cause): its name as
the config and diagnosis.json write it, its meaning, its forms and why it may be untestable."""

from types import SimpleNamespace

import pytest

from fewear.diagnose.core.cause import Cause
from fewear.diagnose.joint import catalogue as joint
from fewear.diagnose.scar import catalogue as scar
from fewear.diagnose.tribometer import catalogue as tribometer
from fewear.io.config import default_config


@pytest.mark.parametrize("declared", [
    tribometer.CAUSES,
    {name: model.cause for name, model in joint.CAUSES.items()},
    scar.CAUSES,
], ids=["tribometer", "joint", "scar"])
def test_every_cause_is_declared_by_the_core_type(declared):
    for name, cause in declared.items():
        assert isinstance(cause, Cause) and cause.name == name
        assert cause.meaning and cause.forms


def test_the_tribometer_causes_list_their_forms_and_what_the_data_lack():
    assert tribometer.CAUSES["running_in"].forms == ("exponential", "power_law")
    assert tribometer.CAUSES["mild_to_severe"].forms == ("load_threshold",
                                                          "load_speed_threshold")
    # its steady form lacks only a varying load x speed, its lagged form time, friction, pressure
    lacking = tribometer.CAUSES["thermal"].why_untestable({"distance", "load"})
    assert lacking == ("could not be tested: needs normal_load_N or pressure_Pa, and "
                       "velocity_m_s, whose product varies between tests")
    assert tribometer.CAUSES["thermal"].why_untestable({"distance", "power"}) is None
    assert tribometer.CAUSES["running_in"].why_untestable({"distance"}) is None


def test_the_joint_causes_are_untestable_by_the_believed_config():
    config = default_config()
    assert all(model.cause.why_untestable(config) is None for model in joint.CAUSES.values())
    config["wear"]["extension"] = "running_in"
    assert "running_in" in joint.CAUSES["running_in"].cause.why_untestable(config)
    config["wear_loop"]["rod_models"] = ["flexible"]
    assert "flexible" in joint.CAUSES["flexible_link"].cause.why_untestable(config)
    assert joint.CAUSES["friction"].cause.why_untestable(config) is None


def test_the_scar_causes_are_untestable_by_the_case_settings():
    settings = SimpleNamespace(wear_coefficient_m2_N=1e-15, cylinder_wear_coefficient_m2_N=0.0)
    assert scar.CAUSES["wear_coefficient"].why_untestable(settings) is None
    assert "changes nothing" in scar.CAUSES["cylinder_wear_coefficient"].why_untestable(settings)
    assert "has no" in scar.CAUSES["cylinder_wear_coefficient"].why_untestable(
        SimpleNamespace(wear_coefficient_m2_N=1e-15))
