"""fewear.io.config rules: typos and wrong types are errors, gaps take the defaults."""

import tomllib

import pytest

from fewear.errors import FewearInputError
from fewear.io.config import default_config, default_config_text, load_config

SECTIONS = ["bushing", "pin"]


def write(tmp_path, text):
    path = tmp_path / "case.toml"
    path.write_text(text)
    return path


def full_sections_text(**overrides):
    """The default [bushing] and [pin] sections as TOML, with some values replaced."""
    defaults = default_config()
    lines = []
    for section in SECTIONS:
        lines.append(f"[{section}]")
        for key, value in defaults[section].items():
            lines.append(f"{key} = {overrides.get(f'{section}.{key}', value)!r}")
    return "\n".join(lines) + "\n"


def test_default_text_parses_to_default_config():
    assert tomllib.loads(default_config_text()) == default_config()


def test_defaults_are_the_papers_joint():
    config = load_config(None, SECTIONS)
    assert config["bushing"]["inner_radius_m"] == 0.010
    assert config["pin"]["radius_m"] == 0.0095
    assert config["bushing"]["youngs_modulus_Pa"] == 90e9


def test_complete_file_overrides_defaults_and_ints_become_floats(tmp_path):
    path = write(tmp_path, full_sections_text(**{"bushing.youngs_modulus_Pa": 100_000_000_000}))
    config = load_config(path, SECTIONS)
    assert config["bushing"]["youngs_modulus_Pa"] == 1e11
    assert isinstance(config["bushing"]["youngs_modulus_Pa"], float)


@pytest.mark.parametrize(
    ("text", "names"),
    [
        ("[bushing]\ninner_radius = 0.01\n", ["inner_radius", "inner_radius_m"]),
        ("[bushingg]\n", ["[bushingg]", "[bushing]"]),
        ("[bushing\n", ["not valid TOML"]),
    ],
)
def test_bad_files_name_what_is_wrong(tmp_path, text, names):
    with pytest.raises(FewearInputError) as caught:
        load_config(write(tmp_path, text), SECTIONS)
    for name in names:
        assert name in str(caught.value)


def test_a_file_holds_only_what_differs_and_the_rest_is_the_default(tmp_path):
    """One key in one section: that value is the user's, every other key and section (even of the
    same section) is the default's, so the config a command uses is complete."""
    config = load_config(write(tmp_path, "[bushing]\ninner_radius_m = 0.0102\n"), SECTIONS)
    defaults = load_config(None, SECTIONS)
    assert config["bushing"]["inner_radius_m"] == 0.0102
    assert config["bushing"]["outer_radius_m"] == defaults["bushing"]["outer_radius_m"]
    assert {name: config[name] for name in SECTIONS if name != "bushing"} == {
        name: defaults[name] for name in SECTIONS if name != "bushing"}
    assert set(config["bushing"]) == set(defaults["bushing"])


def test_a_typo_in_a_section_this_command_does_not_use_is_still_an_error(tmp_path):
    with pytest.raises(FewearInputError, match="wear_loop.*rod_model"):
        load_config(write(tmp_path, "[wear_loop]\nrod_model = ['rigid']\n"), SECTIONS)


@pytest.mark.parametrize(
    ("value", "message"),
    [
        ("'ten'", "expected a number"),
        ("nan", "expected a finite number"),
        ("true", "expected a number"),
    ],
)
def test_wrong_type_and_nan_are_rejected(tmp_path, value, message):
    text = full_sections_text().replace("radius_m = 0.0095", f"radius_m = {value}")
    with pytest.raises(FewearInputError, match=rf"\[pin\] radius_m = .*{message}"):
        load_config(write(tmp_path, text), SECTIONS)


def test_missing_file_is_an_input_error(tmp_path):
    with pytest.raises(FewearInputError, match="cannot read config file"):
        load_config(tmp_path / "absent.toml", SECTIONS)


@pytest.mark.parametrize("text, message", [
    ("total_cycles = 5\n[wear_loop]\n",
     "a top-level key total_cycles; keys belong in a section such as [wear_loop] (a line "
     "[section] above them): total_cycles is a key of [wear_loop]"),
    ("colour = 5\n", "a top-level key colour; keys belong in a section such as [mesh]"),
])
def test_a_top_level_key_is_named_as_a_key(tmp_path, text, message):
    path = tmp_path / "top.toml"
    path.write_text(text)
    with pytest.raises(FewearInputError) as error:
        load_config(path, ["wear_loop"])
    assert message in str(error.value)


def test_underscores_between_digits_are_read_as_toml_says():
    """Issue 57 reported ``1_0e-9`` read as 1e-8: TOML joins digits across an underscore, so
    1_0e-9 is 10e-9 = 1e-8 exactly as written (not a misreading; nothing to refuse)."""
    assert tomllib.loads("k = 1_0e-9")["k"] == 10e-9 == 1e-8


def test_a_section_name_given_a_value_is_named_as_a_section(tmp_path):
    path = tmp_path / "section.toml"
    path.write_text("wear_loop = 5\n")
    with pytest.raises(FewearInputError, match=r"\[wear_loop\] must be a table of keys"):
        load_config(path, ["wear_loop"])
