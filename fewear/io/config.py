"""The workbench configuration: TOML files in SI units, checked against the embedded defaults.

The defaults are the seed paper's case; they live in ``fewear/defaults/*.toml`` (one file per stage,
each owning its sections) and together form the *embedded default config*. ``fewear config`` prints
it: a user copies it and edits values.

Rules for a user's file:

- it holds only what differs from the defaults: a section or key it leaves out takes the default
  value, so the config a command uses is always complete (the outputs record it whole);
- every section and key it names must exist in the defaults (a typo is an error, not silently
  ignored);
- values have the type of their default (an integer is accepted where a float is expected);
  a default that is an inline table (dict) accepts any table, checked by the stage that reads it.

Physical checks (pin smaller than the bore, positive moduli, ...) belong to the dataclasses that the
stages build from these sections.
"""

from __future__ import annotations

import math
import tomllib
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from fewear.errors import FewearInputError

DEFAULTS_DIR = Path(__file__).resolve().parent.parent / "defaults"

Config = dict[str, dict[str, Any]]


def _default_files() -> list[Path]:
    return sorted(DEFAULTS_DIR.glob("*.toml"))


def default_config_text() -> str:
    """The embedded default config as TOML text (all stages' sections, with their comments)."""
    return "\n".join(path.read_text() for path in _default_files())


def default_config() -> Config:
    """The embedded default config as nested dicts; a section defined twice is a developer error."""
    merged: Config = {}
    for path in _default_files():
        for section, table in tomllib.loads(path.read_text()).items():
            if section in merged:
                raise RuntimeError(f"section [{section}] defined twice in {DEFAULTS_DIR}")
            merged[section] = table
    return merged


def load_config(path: str | Path | dict | None, sections: Iterable[str]) -> Config:
    """The sections a command uses: the defaults, overridden by the user's file at ``path`` (or
    by a dict of sections, as a parsed file: :mod:`fewear.api`).

    Raises :class:`FewearInputError` naming the file, section and key of any violation of the
    rules in the module docstring. Sections of the file that this command does not use are
    checked too (a typo anywhere is an error) but not returned.
    """
    sections = list(sections)
    defaults = default_config()
    from fewear.io.limits import check_limits

    source = ("the embedded default config" if path is None else
              "the config dict" if isinstance(path, dict) else str(path))
    user = {} if path is None else path if isinstance(path, dict) else read_toml(path)
    checked = check_config(user, defaults, source=source)
    config = {name: {**defaults[name], **checked.get(name, {})} for name in sections}
    check_limits(config, source)
    return config


def read_toml(path: str | Path) -> dict[str, Any]:
    """Parse a TOML file, turning I/O and syntax errors into input errors."""
    from fewear.io.text import read_text_file

    path = Path(path)
    text = read_text_file(path, "config file")
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        raise FewearInputError(f"config file {path} is not valid TOML: {exc}") from None


def check_config(user: dict[str, Any], defaults: Config, source: str) -> Config:
    """Check a parsed user config against the defaults; return the keys it gives, with floats
    where floats are expected."""
    checked: Config = {}
    for section, table in user.items():
        if not isinstance(table, dict) and section not in defaults:
            owners = [name for name, keys in defaults.items() if section in keys]
            raise FewearInputError(
                f"config {source}: a top-level key {section}; keys belong in a section such as "
                f"[{(owners or list(defaults))[0]}] (a line [section] above them)"
                + (f": {section} is a key of [{'], ['.join(owners)}]" if owners else ""))
        if section not in defaults:
            raise FewearInputError(
                f"config {source}: unknown section [{section}]; allowed sections: "
                + ", ".join(f"[{name}]" for name in defaults)
            )
        if not isinstance(table, dict):
            raise FewearInputError(f"config {source}: [{section}] must be a table of keys")
        checked[section] = _check_section(section, table, defaults[section], source)
    return checked


def _check_section(section: str, table: dict, default: dict, source: str) -> dict[str, Any]:
    unknown = [key for key in table if key not in default]
    if unknown:
        raise FewearInputError(
            f"config {source}: unknown key(s) {', '.join(unknown)} in [{section}]; allowed keys: "
            + ", ".join(default)
        )
    return {key: _check_value(section, key, value, default[key], source)
            for key, value in table.items()}


def _check_value(section: str, key: str, value: Any, default: Any, source: str) -> Any:
    where = f"config {source}: [{section}] {key} = {value!r}"
    if isinstance(default, bool):
        if not isinstance(value, bool):
            raise FewearInputError(f"{where}: expected true or false")
        return value
    if isinstance(default, float):
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            raise FewearInputError(f"{where}: expected a number")
        if not math.isfinite(value):
            raise FewearInputError(f"{where}: expected a finite number")
        return float(value)
    if isinstance(default, int):
        if isinstance(value, bool) or not isinstance(value, int):
            raise FewearInputError(f"{where}: expected a whole number")
        return value
    if not isinstance(value, type(default)):
        raise FewearInputError(f"{where}: expected a {type(default).__name__}")
    return value


def check_exact_keys(table: dict, expected: Iterable[str], where: str) -> None:
    """A free-form table of a config value (e.g. ``[wear] rbf``) must hold exactly ``expected``."""
    expected = list(expected)
    unknown = sorted(set(table) - set(expected))
    missing = [key for key in expected if key not in table]
    if unknown or missing:
        raise FewearInputError(
            f"{where}: unknown key(s) {unknown}, missing key(s) {missing}; expected keys: "
            f"{', '.join(expected) or 'none (an empty table {})'}"
        )
