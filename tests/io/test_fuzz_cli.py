"""Property-based fuzzing of the command line's edge (issue 20): generated configs and CSVs,
hostile but of the shapes a user writes. Every command either accepts the input or exits 2 with
one ``fewear: error:`` line; no exception escapes ``fewear.cli.main`` (which would be a traceback).

Bounded and deterministic: a fixed number of examples, derandomized (the same examples on every
run, no example database), a deadline per example. The heavy work after the parsing (the contact
solve, the dynamics, the wear loop, the diagnoses) is replaced by a stub that stops with
:class:`Accepted` once the command has read and checked all its input: what is fuzzed is the edge.
"""

from __future__ import annotations

import math
import os
from datetime import timedelta
from pathlib import Path

import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from fewear.cli import main  # noqa: E402
from fewear.io.config import default_config  # noqa: E402

EXAMPLES = int(os.environ.get("FEWEAR_FUZZ_EXAMPLES", "40"))
"""Examples per property (more for a longer search: FEWEAR_FUZZ_EXAMPLES=1000)."""
PIN_ON_DISC_DATA = (Path(__file__).resolve().parents[2] / "fewear" / "data"
                    / "pin_on_disc_running_in_synthetic.csv")
FUZZ = settings(max_examples=EXAMPLES, derandomize=True, database=None,
                deadline=timedelta(seconds=20),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture])


class Accepted(Exception):
    """The command read and checked its input and would now start its work."""


def _accept(*args, **kwargs):
    raise Accepted


@pytest.fixture
def stubbed(monkeypatch):
    """The commands' work after their input is checked replaced by :func:`_accept`."""
    import fewear.commands.contact
    import fewear.commands.dynamics
    import fewear.commands.run
    import fewear.diagnose.joint.command
    import fewear.diagnose.tribometer.command

    monkeypatch.setattr(fewear.commands.contact, "_solve", _accept)
    monkeypatch.setattr(fewear.commands.dynamics, "simulate_mechanism", _accept)
    for name in ("run_cases", "_in_processes", "_on_ranks"):
        monkeypatch.setattr(fewear.commands.run, name, _accept)
    monkeypatch.setattr(fewear.diagnose.tribometer.command, "diagnose", _accept)
    monkeypatch.setattr(fewear.diagnose.joint.command, "diagnose_joint", _accept)


def outcome(argv, capsys) -> str:
    """Run ``fewear ARGV``; 'accepted' or 'refused', asserting the one-line error contract."""
    capsys.readouterr()
    try:
        status = main([str(arg) for arg in argv])
    except Accepted:
        status = None
    except SystemExit as exc:  # argparse: a malformed argument
        status = exc.code
    err = capsys.readouterr().err
    errors = [line for line in err.splitlines() if line.startswith("fewear: ")]
    if status is None or status == 0:
        assert not [line for line in errors if line.startswith("fewear: error:")], err
        hypothesis.event(f"{argv[0]}: accepted")
        return "accepted"
    hypothesis.event(f"{argv[0]}: refused: {_cause(errors[0] if errors else '')}")
    assert status == 2, (status, err)
    assert len(errors) == 1 and errors[0].startswith("fewear: error: "), err
    assert len(errors[0]) <= 1200, errors[0][:300]
    return "refused"


def _cause(line: str) -> str:
    """A coarse class of a refusal, for the statistics (--hypothesis-show-statistics)."""
    for needle in ("UTF-8", "not valid TOML", "unknown", "expected a", "argument", "limit",
                   "at most", "at least", "column", "line"):
        if needle in line:
            return needle
    return "other"


# --- configs --------------------------------------------------------------------------------

DEFAULTS = default_config()
KEYS = [(section, key) for section, table in DEFAULTS.items() for key in table]

texts = st.text(alphabet=st.characters(blacklist_categories=("Cs",), blacklist_characters="\x00"),
                max_size=30)
floats = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True),
    st.sampled_from([0.0, -0.0, 1e-300, 1e300, -1.0, 1.0, 1e-7, 0.05, 1e9, 5e-324]))
values = st.one_of(
    floats, st.integers(min_value=-(2**63), max_value=2**63 - 1), st.booleans(), texts,
    st.lists(st.one_of(floats, st.integers(-5, 5), texts), max_size=4),
    st.just("x" * 5000))


def toml_value(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, float):
        if math.isnan(value):
            return "nan"
        if math.isinf(value):
            return "inf" if value > 0 else "-inf"
        return repr(value)
    if isinstance(value, int):
        return str(value)
    if isinstance(value, str):
        return '"' + "".join(c if c.isprintable() and c not in '"\\' else f"\\u{ord(c):04x}"
                             for c in value) + '"'
    return "[" + ", ".join(toml_value(item) for item in value) + "]"


def typed_values(default):
    """Values of the default's type, from plausible (near the default) to hostile."""
    if isinstance(default, bool):
        return st.booleans()
    if isinstance(default, float):
        near = st.tuples(st.floats(-3.0, 3.0), st.sampled_from([1.0, -1.0])).map(
            lambda pair: pair[1] * (default or 1.0) * 10.0 ** pair[0])
        return st.one_of(near, near, floats)
    if isinstance(default, int):
        return st.one_of(st.integers(-2, 3 * max(default, 1)), st.integers(-(2**63), 2**63 - 1))
    if isinstance(default, list):
        items = typed_values(default[0]) if default else st.floats(-1.0, 1.0)
        return st.one_of(st.lists(items, max_size=5), st.just(default))
    return st.one_of(st.just(default), texts)


@st.composite
def configs(draw) -> bytes:
    """A config file: keys of the defaults (a plausible value or a hostile one), sometimes an
    unknown key or section, sometimes broken TOML or bytes that are not UTF-8."""
    lines: dict[str, list[str]] = {}
    for section, key in draw(st.lists(st.sampled_from(KEYS), max_size=4, unique=True)):
        default = DEFAULTS[section][key]
        value = draw(st.one_of(typed_values(default), typed_values(default), values)
                     if not isinstance(default, dict) else st.just({}))
        text = "{}" if isinstance(value, dict) else toml_value(value)
        lines.setdefault(section, []).append(f"{key} = {text}")
    if draw(st.integers(0, 9)) == 0:
        lines.setdefault(draw(st.sampled_from(["mesh", "nonsense"])), []).append("typo = 1")
    body = "".join(f"[{section}]\n" + "\n".join(entries) + "\n"
                   for section, entries in lines.items()).encode()
    damage = draw(st.integers(0, 11))
    if damage == 0:
        body += draw(st.binary(min_size=1, max_size=40))
    elif damage == 1:
        body = body.replace(b"=", b"", 1) + b"[unclosed\n"
    elif damage == 2:
        body = b"# caf\xe9\n" + body
    return body


def _config_path(tmp_path, content: bytes):
    path = tmp_path / "fuzz.toml"
    path.write_bytes(content)
    return path


@FUZZ
@given(content=configs(), command=st.sampled_from(["contact", "dynamics", "run", "diagnose"]))
def test_every_command_accepts_or_refuses_a_config_in_one_line(tmp_path, capsys, stubbed,
                                                               content, command):
    path = _config_path(tmp_path, content)
    out = tmp_path / "out"
    argv = {"contact": ["contact", "--force", "0", "1000"], "dynamics": ["dynamics"],
            "run": ["run", "--jobs", "1"],
            "diagnose": ["diagnose", PIN_ON_DISC_DATA]}[command]
    outcome([*argv, "--config", path, "--out", out], capsys)
    assert not out.exists()  # the stubs stop before any output; a refusal writes nothing


# --- CSVs ---------------------------------------------------------------------------------

PIN_ON_DISC = ["test_id", "pressure_Pa", "velocity_m_s", "sliding_distance_m", "wear_volume_m3",
               "time_s", "mass_loss_kg", "density_kg_m3", "material", "wear_volume_mm3"]
JOINT = ["cycles", "angle_deg", "wear_depth_m", "max_wear_depth_m", "time_s", "fx_N", "fy_N"]
cells = st.one_of(
    st.sampled_from(["0", "1", "-1", "1e-9", "-1e-9", "2e-6", "1e6", "90", "360", "1e300", "nan",
                     "inf", "", "a", '"q,uoted"', '"unclosed', "5e4", "1.5", "-0"]),
    floats.map(repr), st.integers(-10**6, 10**6).map(str), texts.filter(lambda t: "\n" not in t
                                                                      and "\r" not in t))


SCHEMAS = [("test_id", "pressure_Pa", "velocity_m_s", "sliding_distance_m", "wear_volume_m3"),
           ("test_id", "normal_load_N", "sliding_distance_m", "specific_wear_rate_m3_N_m"),
           ("cycles", "angle_deg", "wear_depth_m"), ("cycles", "max_wear_depth_m")]
NUMBERS = {
    "test_id": st.sampled_from(["a", "b", "c"]),
    "pressure_Pa": st.floats(1e5, 1e8).map(repr),
    "velocity_m_s": st.floats(0.01, 5.0).map(repr),
    "sliding_distance_m": st.floats(0.0, 1e4).map(repr),
    "wear_volume_m3": st.floats(-1e-9, 1e-7).map(repr),
    "normal_load_N": st.floats(1.0, 1e3).map(repr),
    "specific_wear_rate_m3_N_m": st.floats(0.0, 1e-12).map(repr),
    "cycles": st.sampled_from(["0", "1000", "5000", "20000"]),
    "angle_deg": st.floats(-360.0, 719.0).map(lambda a: f"{a:.1f}"),
    "wear_depth_m": st.floats(-1e-6, 5e-5).map(repr),
    "max_wear_depth_m": st.floats(-1e-6, 5e-5).map(repr),
}
"""Cells of plausible readings, per column."""


@st.composite
def csvs(draw) -> bytes:
    """A measured-data CSV: a header drawn from the pin-on-disc or joint columns (sometimes an
    unknown or repeated one), a few rows of hostile cells, sometimes ragged, commented, with a
    byte-order mark, a huge cell, or bytes that are not UTF-8."""
    names = draw(st.sampled_from([PIN_ON_DISC, JOINT]))
    header = draw(st.lists(st.sampled_from(names), min_size=1, max_size=6))
    schema = draw(st.sampled_from(SCHEMAS + [None]))
    if schema is not None:
        header = list(schema)
    width = len(header)
    if schema is not None and draw(st.booleans()):  # well-formed rows of plausible numbers
        rows = draw(st.lists(st.tuples(*[NUMBERS.get(name, cells) for name in header]).map(list),
                             min_size=1, max_size=8))
    else:
        rows = draw(st.lists(st.lists(cells, min_size=max(width - 1, 0), max_size=width + 1),
                             max_size=6))
    lines = [",".join(header)] + [",".join(row) for row in rows]
    if draw(st.integers(0, 5)) == 0:
        lines.insert(draw(st.integers(0, len(lines))), "# a comment")
    body = "\n".join(lines).encode("utf-8", "surrogatepass")
    damage = draw(st.integers(0, 13))
    if damage == 0:
        body = b"\xef\xbb\xbf" + body
    elif damage == 1:
        body += b"\n" + b"9" * 200_000
    elif damage == 2:
        body += b"\n\xff\xfe"
    elif damage == 3:
        body = draw(st.binary(max_size=60))
    return body


@FUZZ
@given(content=csvs())
def test_diagnose_accepts_or_refuses_a_csv_in_one_line(tmp_path, capsys, stubbed, content):
    path = tmp_path / "measured.csv"
    path.write_bytes(content)
    outcome(["diagnose", path, "--out", tmp_path / "out"], capsys)
    assert not (tmp_path / "out").exists()


@FUZZ
@given(force=st.tuples(floats, floats), rotation=floats, friction=st.booleans(),
       cycles=st.one_of(st.none(), st.integers(-10, 10**7)),
       jobs=st.one_of(st.none(), st.integers(-3, 10**6)))
def test_arguments_are_accepted_or_refused_in_one_line(tmp_path, capsys, stubbed, force,
                                                       rotation, friction, cycles, jobs):
    out = tmp_path / "out"
    outcome(["contact", "--force", repr(force[0]), repr(force[1]), "--rotation", repr(rotation),
             *(["--friction"] if friction else []), "--out", out], capsys)
    outcome(["dynamics", *(["--cycles", cycles] if cycles is not None else []), "--out", out],
            capsys)
    outcome(["run", *(["--jobs", jobs] if jobs is not None else []), "--out", out], capsys)
    assert not out.exists()
