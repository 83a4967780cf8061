"""Mechanism files: the examples parse, bad files are one-line errors naming the body, joint or
key, and each clearance joint's config view (joint_sections)."""

import tomllib

import pytest

from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.mechanism import (
    EXAMPLES_DIR,
    dynamics_inputs,
    joint_sections,
    parse_mechanism,
    read_mechanism,
)
from fewear.mbd.slider_crank import SECTIONS

FOUR_BAR = (EXAMPLES_DIR / "four_bar.toml").read_text()


def parse(text: str):
    return parse_mechanism(tomllib.loads(text), "test.toml")


def edited(old: str, new: str, text: str = FOUR_BAR) -> str:
    assert old in text
    return text.replace(old, new, 1)


@pytest.mark.parametrize("name, clearance_joints", [
    ("four_bar", ["coupler_rocker"]),
    ("four_bar_two_joints", ["crank_coupler", "coupler_rocker"]),
    ("slider_crank", ["rod_slider"]),
    ("slider_crank_two_joints", ["crank_rod", "rod_slider"]),
])
def test_examples_parse_with_their_clearance_joints(name, clearance_joints):
    mechanism, tables = read_mechanism(EXAMPLES_DIR / f"{name}.toml")
    assert [joint.name for joint in mechanism.clearance_joints] == clearance_joints
    assert mechanism.period_s == pytest.approx(0.05)
    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = name
    assert list(joint_sections(config)) == clearance_joints


def test_four_bar_links_are_the_steel_bars():
    mechanism = read_mechanism(EXAMPLES_DIR / "four_bar.toml")[0]
    for body, length in zip(mechanism.bodies, (0.10, 0.25, 0.25)):
        assert body.mass_kg == pytest.approx(0.702 * length)
        assert body.inertia_kg_m2 == pytest.approx(0.702 * length**3 / 12)
    assert dict(mechanism.ground_points) == {"O2": (0.0, 0.0), "O4": (0.30, 0.0)}


@pytest.mark.parametrize("old, new, message", [
    ('name = "crank"\nlength_m', 'name = "crank"\nmas_kg = 1.0\nlength_m',
     r"body 'crank': unknown key\(s\) mas_kg"),
    ('pin_point = "coupler.B"', 'pin_point = "coupler.C"',
     r"joint 'coupler_rocker': pin_point = 'coupler.C': 'coupler' has no point 'C'"),
    ('bushing_point = "rocker.B"', 'bushing_point = "rockr.B"',
     r"joint 'coupler_rocker': bushing_point = 'rockr.B': unknown body 'rockr'"),
    ('length_m = 0.10', 'length_m = "0.10"', r"body 'crank': length_m = '0.10': expected a"),
    ('name = "crank"\nlength_m = 0.10', 'name = "crank"',
     r"body 'crank': missing length_m"),
    ('type = "revolute"\npin_point = "crank.O2"', 'type = "hinge"\npin_point = "crank.O2"',
     r"joint 'crank_ground': type = 'hinge'"),
    ('speed_rpm = 1200.0', 'speed_rpm = 0.0', r"driver of 'crank': speed_rpm = 0"),
    ('clearance = true', 'clearance = "yes"', r"joint 'coupler_rocker': clearance = 'yes'"),
    ('variable_body = "coupler"', 'variable_body = "crank"', r"variable_body = 'crank'"),
    ('elements = 4', 'elements = 3\nmodel_x = 1', r"body 'coupler': unknown key\(s\) model_x"),
    ('bushing_point = "rocker.B"\nclearance = true',
     'bushing_point = "rocker.B"\nclearance = true\nbushing = { inner_radius = 0.01 }',
     r"joint 'coupler_rocker'.*unknown key\(s\) inner_radius in \[bushing\]"),
])
def test_bad_file_is_a_one_line_error_naming_the_culprit(old, new, message):
    with pytest.raises(FewearInputError, match=message) as error:
        parse(edited(old, new))
    assert "\n" not in str(error.value) and "test.toml" in str(error.value)


def test_bushing_on_a_flexible_body_is_refused():
    text = edited('pin_point = "coupler.B"\nbushing_point = "rocker.B"',
                  'pin_point = "rocker.B"\nbushing_point = "coupler.B"')
    text = edited('variable_body = "coupler"\n', '', text)
    parse(text)  # the rigid coupler may carry it
    with pytest.raises(FewearInputError, match=r"bushing is on the flexible body 'coupler'"):
        parse(edited('model = "rigid"', 'model = "flexible"', text))


def test_the_variable_body_carries_no_bushing_or_driver():
    """The variable body is flexible in the flexible case: what a flexible body cannot carry is
    refused even while its file model is rigid."""
    with pytest.raises(FewearInputError, match=r"joint 'coupler_rocker': variable_body = "
                                               r"'coupler' may be flexible.*bushing"):
        parse(edited('pin_point = "coupler.B"\nbushing_point = "rocker.B"',
                     'pin_point = "rocker.B"\nbushing_point = "coupler.B"'))
    with pytest.raises(FewearInputError, match=r"variable_body = 'coupler' may be flexible, so "
                                               r"it cannot be driven"):
        parse(edited('body = "crank"\nspeed_rpm', 'body = "coupler"\nspeed_rpm'))


def test_a_flexible_body_point_off_its_nodes_is_refused():
    with pytest.raises(FewearInputError, match=r"'coupler': point B = \[0.1, 0.0\] is not at a "
                                               r"node"):
        parse(edited('A = [-0.125, 0.0], B = [0.125, 0.0]', 'A = [-0.125, 0.0], B = [0.1, 0.0]'))


def test_a_joint_s_own_tables_merge_over_the_run_config(tmp_path):
    """Only the joint's tables change its view; the other joint keeps the config's sections, and
    the joint's data (radii, friction) follow its view."""
    text = (EXAMPLES_DIR / "four_bar_two_joints.toml").read_text()
    text = edited('bushing_point = "crank.A"\nclearance = true',
                  'bushing_point = "crank.A"\nclearance = true\n'
                  'pin = { radius_m = 0.0098 }\njoint = { friction_coefficient = 0.2 }', text)
    path = tmp_path / "mine.toml"
    path.write_text(text)
    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = str(path)
    views = joint_sections(config)
    inputs = dynamics_inputs(config, "rigid")
    assert views["coupler_rocker"] is config
    crank = views["crank_coupler"]
    assert crank["pin"] == {**config["pin"], "radius_m": 0.0098}
    assert crank["joint"]["friction_coefficient"] == 0.2
    assert crank["bushing"] == config["bushing"] and set(crank) == set(config)
    assert inputs.joints["crank_coupler"].pin_radius_m == 0.0098
    assert inputs.joints["crank_coupler"].friction.coefficient == 0.2
    assert inputs.joints["coupler_rocker"].pin_radius_m == config["pin"]["radius_m"]


def test_unknown_example_name_lists_the_examples():
    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = "three_bar"
    with pytest.raises(FewearInputError, match=r"three_bar.*four_bar, four_bar_two_joints"):
        dynamics_inputs(config, "rigid")


def test_a_profile_for_an_unknown_joint_is_refused():
    from fewear.mbd.contact import ClearanceProfile
    from fewear.mbd.mechanism import simulate

    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = "four_bar"
    inputs = dynamics_inputs(config, "rigid")
    with pytest.raises(FewearInputError, match=r"'rod_slider'.*coupler_rocker"):
        simulate(inputs, profiles={"rod_slider": ClearanceProfile.constant(6e-4)})
