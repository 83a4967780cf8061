"""Property-based fuzzing of the measured-data readers and the mechanism reader (issue 57
group 5): the pin-on-disc diagnosis run whole on small tables, the joint profile reader, the
scar profile reader, the joint-history CSV reader and the mechanism file reader. Each either
accepts its input or raises :class:`~fewear.errors.FewearInputError` (one line at the command
line); no other exception (a traceback), no hang.

Bounded and deterministic like tests/io/test_fuzz_readers.py: ``FEWEAR_FUZZ_EXAMPLES`` examples
per reader (the whole diagnosis a quarter of them, at least 5), derandomized, no example
database.
"""

from __future__ import annotations

import math
import os
import warnings
from datetime import timedelta
from pathlib import Path

import numpy as np
import pytest

hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from fewear.errors import FewearInputError  # noqa: E402

EXAMPLES = int(os.environ.get("FEWEAR_FUZZ_EXAMPLES", "40"))
FUZZ = settings(max_examples=EXAMPLES, derandomize=True, database=None,
                deadline=timedelta(seconds=60),
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large,
                                       HealthCheck.function_scoped_fixture,
                                       HealthCheck.filter_too_much])
FUZZ_WHOLE_DIAGNOSIS = settings(FUZZ, max_examples=max(5, EXAMPLES // 4))
MECHANISMS = Path(__file__).resolve().parents[2] / "fewear" / "mechanisms"

numbers = st.one_of(
    st.floats(allow_nan=True, allow_infinity=True, width=64),
    st.floats(min_value=1e-12, max_value=1e4),
    st.sampled_from([0.0, -0.0, 1.0, -1.0, 1e-300, 1e300, 5e-324]))
cells = st.one_of(numbers.map(repr), st.sampled_from(["", " ", "abc", "1,5", "1e", "--1", "nan",
                                                      "0x10", "1_0", "\u00a0", "\ufeff1"]))


def flipped(data: bytes, flips: list[tuple[int, int]]) -> bytes:
    """``data`` with the byte at each (position modulo its length) XORed with a non-zero mask."""
    changed = bytearray(data)
    for position, mask in flips:
        changed[position % len(changed)] ^= mask
    return bytes(changed)


FLIPS = st.lists(st.tuples(st.integers(0, 2**31), st.integers(1, 255)), min_size=1, max_size=8)


def read_or_refuse(read, *args) -> str:
    """``read(*args)``: 'accepted' or 'refused' (a FewearInputError); any other exception fails."""
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", RuntimeWarning)
        try:
            read(*args)
        except FewearInputError as exc:
            assert str(exc).strip(), "an empty message"
            return "refused"
    return "accepted"


@st.composite
def tables(draw, header, rows_min=0, rows_max=8):
    """CSV bytes: ``header`` (maybe with a column dropped, renamed or doubled), rows of cells."""
    names = list(header)
    edit = draw(st.integers(0, 6))
    if edit == 0 and len(names) > 1:
        names.pop(draw(st.integers(0, len(names) - 1)))
    elif edit == 1:
        names.append(draw(st.sampled_from(names)))
    elif edit == 2:
        names[draw(st.integers(0, len(names) - 1))] += draw(st.sampled_from(["_mm", "x", ""]))
    rows = draw(st.lists(st.lists(cells, min_size=len(names) - 1, max_size=len(names) + 1),
                         min_size=rows_min, max_size=rows_max))
    lines = [",".join(names)] + [",".join(row) for row in rows]
    body = "\n".join(lines).encode("utf-8", "surrogatepass")
    if draw(st.integers(0, 9)) == 0:
        body = draw(st.binary(max_size=80))
    return body


# --- the pin-on-disc diagnosis, whole, on small tables -----------------------------------------

@st.composite
def pin_on_disc_tables(draw):
    """3 to 5 tests of 1 to 4 readings: loads, speeds, distances and volumes drawn from wide,
    sometimes degenerate ranges (zeros, equal values, a material per test), as CSV text."""
    n_tests = draw(st.integers(3, 5))
    per_test = draw(st.integers(1, 4))
    positive = st.one_of(st.floats(1e-3, 1e3), st.sampled_from([1.0, 1e-6, 1e6]))
    material = draw(st.sampled_from([None, "same", "each", "two"]))
    lines = ["test_id,normal_load_N,velocity_m_s,sliding_distance_m,wear_volume_m3"
             + (",material" if material else "")]
    for test in range(n_tests):
        load, speed = draw(positive), draw(st.floats(1e-3, 10.0))
        k = 10.0 ** draw(st.one_of(st.floats(-16.0, -12.0), st.floats(-23.0, -7.0)))
        distance = 0.0
        for _ in range(per_test):
            distance += draw(st.sampled_from([0.0, 1.0, 100.0, 1e4]))
            scatter = draw(st.one_of(st.floats(0.5, 2.0), st.floats(-1.0, 3.0)))
            row = f"T{test},{load!r},{speed!r},{distance!r},{k * load * distance * scatter!r}"
            if material:
                label = {"same": "A", "each": f"M{test}", "two": "AB"[test % 2]}[material]
                row += f",{label}"
            lines.append(row)
    return "\n".join(lines) + "\n"


@FUZZ_WHOLE_DIAGNOSIS
@given(text=pin_on_disc_tables())
def test_the_pin_on_disc_diagnosis_runs_or_names_the_problem(tmp_path_factory, text):
    from fewear.diagnose.tribometer.diagnose import diagnose
    from fewear.diagnose.tribometer.measured import read_measured_wear
    from fewear.diagnose.tribometer.plausibility import check_plausible
    from fewear.diagnose.tribometer.readings import readings_from_measured
    from fewear.diagnose.tribometer.report import summarise

    path = tmp_path_factory.mktemp("pin_on_disc") / "table.csv"
    path.write_text(text)

    def whole(path):
        data = read_measured_wear(path)
        check_plausible(data)
        summarise(diagnose(readings_from_measured(data)))

    hypothesis.event(read_or_refuse(whole, path))


@FUZZ
@given(content=tables(["test_id", "pressure_Pa", "velocity_m_s", "sliding_distance_m",
                       "wear_volume_m3"]))
def test_the_pin_on_disc_reader_reads_or_names_the_problem(tmp_path_factory, content):
    from fewear.diagnose.tribometer.measured import read_measured_wear
    from fewear.diagnose.tribometer.plausibility import check_plausible

    path = tmp_path_factory.mktemp("pin_on_disc") / "table.csv"
    path.write_bytes(content)
    hypothesis.event(read_or_refuse(lambda p: check_plausible(read_measured_wear(p)), path))


# --- joint profiles and maximum depths -----------------------------------------------------

@FUZZ
@given(content=st.one_of(tables(["cycles", "angle_deg", "wear_depth_m"], rows_max=12),
                         tables(["cycles", "max_wear_depth_m"])))
def test_the_joint_reader_reads_or_names_the_problem(tmp_path_factory, content):
    from fewear.diagnose.joint.measured import read_joint_measurements

    path = tmp_path_factory.mktemp("joint") / "joint.csv"
    path.write_bytes(content)
    hypothesis.event(read_or_refuse(read_joint_measurements, [path]))


@FUZZ
@given(cycles=st.lists(st.integers(0, 10**6), min_size=1, max_size=3, unique=True),
       depth_um=st.lists(st.floats(-5.0, 1e3), min_size=1, max_size=3),
       step_deg=st.sampled_from([0.5, 7.0, 45.0, 120.0, 200.0]),
       unit=st.sampled_from([1.0, math.pi / 180.0]))
def test_joint_profiles_of_any_values_read_or_name_the_problem(tmp_path_factory, cycles,
                                                              depth_um, step_deg, unit):
    """Well-formed files of bump profiles of any depth (negative, growing or falling), angle
    step and angle unit (``unit``: degrees, or radians under angle_deg)."""
    from fewear.diagnose.joint.measured import read_joint_measurements

    angle = np.arange(0.0, 360.0, step_deg)
    lines = ["cycles,angle_deg,wear_depth_m"]
    for count, depth in zip(cycles, depth_um * len(cycles)):
        bump = depth * 1e-6 * np.exp(-((angle - 90.0) / 25.0) ** 2)
        lines += [f"{count},{a * unit!r},{d!r}" for a, d in zip(angle, bump)]
    path = tmp_path_factory.mktemp("joint") / "bore.csv"
    path.write_text("\n".join(lines) + "\n")
    hypothesis.event(read_or_refuse(read_joint_measurements, [path]))


# --- scar profiles -----------------------------------------------------------------------------

@FUZZ
@given(content=st.one_of(tables(["x_mm", "test1_um"], rows_max=14),
                         tables(["x_m", "a_m", "b_m"], rows_max=14)))
def test_the_scar_reader_reads_or_names_the_problem(tmp_path_factory, content):
    from fewear.diagnose.scar.measured import read_measured_scar

    path = tmp_path_factory.mktemp("scar") / "scar.csv"
    path.write_bytes(content)
    hypothesis.event(read_or_refuse(read_measured_scar, path))


@FUZZ
@given(width=st.floats(1e-9, 1e3), depth=st.floats(-1e3, 1e3), points=st.integers(10, 40),
       names=st.sampled_from([("x_mm", "t_um"), ("x_m", "t_m"), ("x_mm", "t_m")]))
def test_scar_profiles_of_any_size_read_or_name_the_problem(tmp_path_factory, width, depth,
                                                           points, names):
    from fewear.diagnose.scar.measured import read_measured_scar

    x = np.linspace(-width, width, points)
    height = -depth * np.maximum(1.0 - (x / (0.5 * width)) ** 2, 0.0)
    lines = [",".join(names)] + [f"{a!r},{h!r}" for a, h in zip(x, height)]
    path = tmp_path_factory.mktemp("scar") / "scar.csv"
    path.write_text("\n".join(lines) + "\n")
    hypothesis.event(read_or_refuse(read_measured_scar, path))


# --- the joint-history CSV -------------------------------------------------------------------

def joint_history_text(samples: int = 24) -> str:
    """One periodic cycle: a rotating load and one turn of relative rotation."""
    time = np.linspace(0.0, 0.1, samples)
    phase = 2.0 * np.pi * time / time[-1]
    lines = ["time_s,force_x_N,force_y_N,relative_angle_rad,crank_angle_deg"]
    lines += [f"{t!r},{100 * math.cos(p)!r},{100 * math.sin(p)!r},{p!r},{math.degrees(p)!r}"
              for t, p in zip(time, phase)]
    return "\n".join(lines) + "\n"


def test_the_unflipped_joint_history_is_read():
    """The fuzz's starting file is a valid history (else every flip would be refused)."""
    import tempfile

    from fewear.io.joint_history import read_joint_history

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "history.csv"
        path.write_text(joint_history_text())
        history = read_joint_history(path)
    assert history.time_s.size == 24


@FUZZ
@given(flips=FLIPS, cut=st.one_of(st.none(), st.integers(0, 2000)),
       impacts=st.booleans(), cycles=st.integers(1, 3))
def test_the_joint_history_reader_reads_or_names_the_problem(tmp_path_factory, flips, cut,
                                                             impacts, cycles):
    from fewear.io.joint_history import read_joint_history

    data = joint_history_text().encode()
    path = tmp_path_factory.mktemp("history") / "history.csv"
    path.write_bytes(flipped(data, flips)[:cut])
    hypothesis.event(read_or_refuse(read_joint_history, path, cycles, impacts))


@FUZZ
@given(content=tables(["time_s", "force_x_N", "force_y_N", "relative_omega_rpm", "mode"],
                      rows_max=10))
def test_joint_history_tables_read_or_name_the_problem(tmp_path_factory, content):
    from fewear.io.joint_history import read_joint_history

    path = tmp_path_factory.mktemp("history") / "history.csv"
    path.write_bytes(content)
    hypothesis.event(read_or_refuse(read_joint_history, path))


# --- the mechanism file ------------------------------------------------------------------------

@FUZZ
@given(name=st.sampled_from(sorted(path.name for path in MECHANISMS.glob("*.toml"))),
       flips=FLIPS, cut=st.one_of(st.none(), st.integers(0, 4000)))
def test_the_mechanism_reader_reads_or_names_the_problem(tmp_path_factory, name, flips, cut):
    from fewear.io.mechanism import read_mechanism

    path = tmp_path_factory.mktemp("mechanism") / name
    path.write_bytes(flipped((MECHANISMS / name).read_bytes(), flips)[:cut])
    hypothesis.event(read_or_refuse(read_mechanism, path))


@FUZZ
@given(name=st.sampled_from(sorted(path.name for path in MECHANISMS.glob("*.toml"))),
       value=st.one_of(numbers.map(repr), st.sampled_from(['"x"', "[]", "[1, 2]", "{}", "true",
                                                           '"crank"', "-1", "0"])),
       which=st.integers(0, 10**6))
def test_mechanism_values_replaced_read_or_name_the_problem(tmp_path_factory, name, value,
                                                           which):
    """One value of a shipped mechanism (a number, a name, a pair) replaced by another kind."""
    import re

    from fewear.io.mechanism import read_mechanism

    text = (MECHANISMS / name).read_text()
    spots = [match.span(1) for match in re.finditer(r"=\s*([^\n#]+)", text)]
    start, end = spots[which % len(spots)]
    path = tmp_path_factory.mktemp("mechanism") / name
    path.write_text(text[:start] + value + text[end:])
    hypothesis.event(read_or_refuse(read_mechanism, path))
