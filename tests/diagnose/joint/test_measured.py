"""Reading wear measured on a mechanism's joint: the files round trip, angles are normalised and
sorted, files of one kind merge, the kind is told from the header, and every kind of bad data is
reported with its file line and column."""

import math
from pathlib import Path

import numpy as np
import pytest

from fewear.diagnose.joint.measured import (
    JointMeasurements,
    MeasuredProfile,
    joint_data_kind,
    read_joint_measurements,
    write_joint_profiles,
    write_max_wear,
)
from fewear.errors import FewearInputError

DATA = Path(__file__).resolve().parents[3] / "fewear" / "data"


def bump_profile(cycles, step_deg=3.0, depth_um=20.0):
    angle = np.deg2rad(np.arange(0.0, 360.0, step_deg))
    depth = depth_um * 1e-6 * np.exp(-((angle - math.pi / 2) / 0.4) ** 2) - 0.3e-6
    return MeasuredProfile(cycles, angle, depth)


def write_lines(path, *lines):
    Path(path).write_text("\n".join(lines) + "\n")
    return path


def message(paths):
    with pytest.raises(FewearInputError) as error:
        read_joint_measurements(paths if isinstance(paths, list) else [paths])
    return str(error.value)


def test_profiles_and_max_wear_round_trip(tmp_path):
    profiles = [bump_profile(50000), bump_profile(0, step_deg=5.0, depth_um=0.0)]
    write_joint_profiles(tmp_path / "bore.csv", profiles, comment="bore\nslider-crank")
    cycles, depth = np.array([0, 10000, 50000]), np.array([-0.2e-6, 4e-6, 19.7e-6])
    write_max_wear(tmp_path / "max.csv", cycles, depth, comment="gauge")
    assert (tmp_path / "bore.csv").read_text().startswith("# bore\n# slider-crank\ncycles,")
    data = read_joint_measurements([tmp_path / "bore.csv", tmp_path / "max.csv"])
    assert data.profile_cycles == (0, 50000)
    for read, written in zip(data.profiles, sorted(profiles, key=lambda p: p.cycles)):
        np.testing.assert_allclose(read.angle_rad, written.angle_rad, rtol=1e-14, atol=1e-15)
        np.testing.assert_array_equal(read.depth_m, written.depth_m)
    np.testing.assert_array_equal(data.max_wear[0], cycles)
    np.testing.assert_array_equal(data.max_wear[1], depth)
    assert data.cycle_counts == (0, 10000, 50000) and data.last_cycles == 50000
    assert data.force is None and data.acceleration is None
    assert data.sources == (str(tmp_path / "bore.csv"), str(tmp_path / "max.csv"))
    assert data.profile_at(50000) is data.profiles[1]
    notes = " ".join(data.notes)
    assert "every 3 deg, over the full circle" in notes and "every 5 deg" in notes
    assert "below zero" in notes and "kept as data" in notes


def test_angles_normalised_sorted_and_partial_coverage_noted(tmp_path):
    path = write_lines(tmp_path / "arc.csv", "# an arc, written out of order",
                       "cycles,angle_deg,wear_depth_m", "5e4,-10,1e-6", "50000.0,370,3e-6",
                       "50000,0,2e-6", "50000,20,4e-6", "50000,-20,0.5e-6")
    data = read_joint_measurements(path)
    profile = data.profiles[0]
    assert profile.cycles == 50000
    np.testing.assert_allclose(np.rad2deg(profile.angle_rad), [0, 10, 20, 340, 350])
    np.testing.assert_array_equal(profile.depth_m, [2e-6, 3e-6, 4e-6, 0.5e-6, 1e-6])
    assert "over the arc 340 to 20 deg (40 of 360 deg): partial angular coverage" in data.notes[0]
    assert f"{path}: 1 angle of 360 deg or more (highest 370 deg) taken modulo 360 deg" in (
        data.notes)
    assert not any("360 deg or more" in note
                   for note in read_joint_measurements(write_lines(
                       tmp_path / "signed.csv", "cycles,angle_deg,wear_depth_m", "5e4,-10,1e-6",
                       "5e4,0,2e-6", "5e4,10,1e-6")).notes)


def test_traces_read_with_and_without_cycles(tmp_path):
    force = write_lines(tmp_path / "force.csv", "time_s,fx_N,fy_N,cycles", "0.0,10,-5,0",
                        "0.01,12,-4,0", "0.0,9,-5,1000", "0.01,11,-3,1000")
    acceleration = write_lines(tmp_path / "acc.csv", "time_s,slider_acceleration_m_s2",
                               "0,-300.5", "0.005,-250", "0.01,-120")
    profile = tmp_path / "bore.csv"
    write_joint_profiles(profile, [bump_profile(1000)])
    data = read_joint_measurements([force, profile, acceleration])
    assert [trace.cycles for trace in data.force] == [0, 1000]
    np.testing.assert_array_equal(data.force[1].fx_N, [9, 11])
    np.testing.assert_array_equal(data.force[0].fy_N, [-5, -4])
    (trace,) = data.acceleration
    assert trace.cycles == 0
    np.testing.assert_array_equal(trace.slider_acceleration_m_s2, [-300.5, -250, -120])
    assert any("no cycles column" in note and "cycle 0" in note for note in data.notes)


def test_files_of_one_kind_merge_and_a_cycle_count_twice_is_an_error(tmp_path):
    write_joint_profiles(tmp_path / "early.csv", [bump_profile(0), bump_profile(20000)])
    write_joint_profiles(tmp_path / "late.csv", [bump_profile(60000)])
    write_max_wear(tmp_path / "max1.csv", [0, 30000], [0.0, 8e-6])
    write_max_wear(tmp_path / "max2.csv", [10000, 60000], [3e-6, 16e-6])
    data = read_joint_measurements([tmp_path / name for name in
                                    ("late.csv", "max2.csv", "early.csv", "max1.csv")])
    assert data.profile_cycles == (0, 20000, 60000)
    np.testing.assert_array_equal(data.max_wear[0], [0, 10000, 30000, 60000])
    np.testing.assert_array_equal(data.max_wear[1], [0.0, 3e-6, 8e-6, 16e-6])
    assert data.cycle_counts == (0, 10000, 20000, 30000, 60000)
    write_joint_profiles(tmp_path / "again.csv", [bump_profile(20000)])
    text = message([tmp_path / "early.csv", tmp_path / "again.csv"])
    assert "again.csv" in text and "20000 cycles is also in" in text and "early.csv" in text
    write_max_wear(tmp_path / "max3.csv", [30000], [9e-6])
    text = message([tmp_path / "max1.csv", tmp_path / "max3.csv"])
    assert "max3.csv" in text and "30000 cycles is also in" in text and "max1.csv" in text


def test_joint_data_kind(tmp_path):
    for name in ("pin_on_disc_cuzn25al6fe3mn3_42crmo.csv", "pin_on_disc_singh2016_al_sic.csv",
                 "pin_on_disc_running_in_synthetic.csv"):
        assert joint_data_kind(DATA / name) is None
    headers = {"profiles": "cycles,angle_deg,wear_depth_m", "max_wear": "cycles,max_wear_depth_m",
               "force": "time_s, fx_N, fy_N", "acceleration": "time_s,slider_acceleration_m_s2",
               "profiles ": "cycles,angle_rad,wear_depth_um"}
    for kind, header in headers.items():
        path = write_lines(tmp_path / "data.csv", "# comment", "", header, "not read, at, all")
        assert joint_data_kind(path) == kind.strip()
    path = write_lines(tmp_path / "mixed.csv", "cycles,angle_deg,max_wear_depth_m")
    with pytest.raises(FewearInputError, match="line 1: columns of bore profile and "
                                               "maximum-depth growth data in one file"):
        joint_data_kind(path)


@pytest.mark.parametrize("header, expected", [
    ("cycles,angle_deg,wear_depth_um", "column 'wear_depth_um': unknown column or unit; fewear "
     "reads SI units only: use wear_depth_m (1 um = 1e-6 m"),
    ("cycles,angle_deg,wear_depth_mm", "use wear_depth_m (1 um = 1e-6 m, 1 mm = 1e-3 m)"),
    ("cycles,angle_rad,wear_depth_m", "column 'angle_rad': unknown column or unit; fewear reads "
     "SI units only: use angle_deg (1 rad = 180/pi deg)"),
    ("cycles,max_wear_depth_um", "use max_wear_depth_m"),
    ("time_ms,fx_N,fy_N", "column 'time_ms': unknown column or unit; fewear reads SI units only:"
     " use time_s (1 ms = 1e-3 s)"),
    ("time_s,fx_kN,fy_N", "use fx_N (1 kN = 1e3 N)"),
    ("time_s,slider_acceleration_g", "use slider_acceleration_m_s2 (1 g = 9.80665 m/s^2)"),
    ("cycles,angle_deg,wear_depth_m,operator", "column 'operator': unknown column; a bore "
     "profile file has the columns cycles, angle_deg, wear_depth_m"),
    ("cycles,angle_deg", "line 2: missing required column wear_depth_m; a bore profile file has "
     "the columns cycles, angle_deg, wear_depth_m"),
    ("angle_deg,wear_depth_m", "missing required column cycles"),
    ("cycles,angle_deg,wear_depth_m,wear_depth_m", "column(s) wear_depth_m repeated"),
    ("cycles,angle_deg,fx_N", "columns of bore profile and joint force trace data in one file"),
])
def test_bad_header(tmp_path, header, expected):
    path = write_lines(tmp_path / "bad.csv", "# header on line 2", header,
                       ",".join(["1"] * len(header.split(","))))
    text = message(path)
    assert str(path) in text and expected in text


def test_tribometer_file_is_no_joint_data():
    text = message(DATA / "pin_on_disc_cuzn25al6fe3mn3_42crmo.csv")
    assert "are no joint wear data; joint data files have the columns" in text
    assert "bore profile: cycles, angle_deg, wear_depth_m\n" in text
    assert "joint force trace: time_s, fx_N, fy_N [, cycles]" in text


PROFILE = "cycles,angle_deg,wear_depth_m"


@pytest.mark.parametrize("row, expected", [
    ("100,,1e-6", "line 6, column angle_deg: empty value"),
    ("100,10,deep", "line 6, column wear_depth_m: 'deep' is not a number"),
    ("100,10,nan", "line 6, column wear_depth_m: nan; expected a finite number"),
    ("100,inf,1e-6", "line 6, column angle_deg: inf; expected a finite number"),
    ("1.5,10,1e-6", "line 6, column cycles: 1.5; expected a non-negative whole number"),
    ("-100,10,1e-6", "line 6, column cycles: -100.0; expected a non-negative whole number"),
    ("100,720,1e-6", "line 6, column angle_deg: 720.0; expected an angle in degrees in "
     "[-360, 720)"),
    ("100,-361,1e-6", "line 6, column angle_deg: -361.0; expected an angle in degrees"),
    ("100,10,12.5", "line 6, column wear_depth_m: 12.5 m is 1 cm or more, not a wear depth in "
     "metres"),
    ("100,360,1e-6", "line 6, column angle_deg: 360.0 deg is the angle 0.0 deg of "),
    ("100,-360,1e-6", "(0 deg in [0, 360)) in the bore profile at 100 cycles; each angle appears "
     "once per cycle count"),
    ("100,1,2,3", "line 6: 4 values for the 3 columns"),
])
def test_bad_profile_rows(tmp_path, row, expected):
    path = write_lines(tmp_path / "bore.csv", "# bore", PROFILE, "100,0,0.0", "100,120,1e-6",
                       "100,240,2e-6", row)
    text = message(path)
    assert str(path) in text and expected in text
    if "deg is the angle" in expected:
        assert f"{path} line 3" in text


def test_duplicate_angle_names_both_lines(tmp_path):
    path = write_lines(tmp_path / "bore.csv", PROFILE, "7,10,0.0", "7,20,1e-6", "7,-350,2e-6")
    text = message(path)
    assert (f"{path} line 4, column angle_deg: -350.0 deg is the angle 10.0 deg of {path} line 2"
            in text)


def test_too_few_angles(tmp_path):
    path = write_lines(tmp_path / "bore.csv", PROFILE, "7,10,0.0", "7,20,1e-6", "8,1,0", "8,2,0",
                       "8,3,0")
    assert "line 2, column angle_deg: the bore profile at 7 cycles has 2 angle(s)" in message(path)


@pytest.mark.parametrize("rows, expected", [
    (("0,0", "100,1e-6", "100,2e-6"), "line 4, column cycles: 100 appears again (first at "),
    (("0,0", "100,1e-6", "2.5e2,inf"), "line 4, column max_wear_depth_m: inf; expected a finite"),
    (("0,0", "100,0.002"), None),
    (("0,0", "100,", "200,1e-6"), "line 3, column max_wear_depth_m: empty value"),
])
def test_max_wear_rows(tmp_path, rows, expected):
    path = write_lines(tmp_path / "max.csv", "cycles,max_wear_depth_m", *rows)
    if expected is None:
        data = read_joint_measurements([path])
        np.testing.assert_array_equal(data.max_wear[0], [0, 100])
        return
    text = message(path)
    assert str(path) in text and expected in text


def test_max_wear_sorted_with_dips_kept(tmp_path):
    path = write_lines(tmp_path / "max.csv", "cycles,max_wear_depth_m", "20000,5e-6", "0,-0.3e-6",
                       "10000,5.5e-6", "30000,9e-6")
    data = read_joint_measurements([path])
    np.testing.assert_array_equal(data.max_wear[0], [0, 10000, 20000, 30000])
    np.testing.assert_array_equal(data.max_wear[1], [-0.3e-6, 5.5e-6, 5e-6, 9e-6])
    assert data.max_wear[0].dtype.kind == "i"
    notes = " ".join(data.notes)
    assert "1 of 4 values of max_wear_depth_m are below zero (lowest -0.3 um)" in notes
    assert "dips below the previous cycle count's 1 time(s): kept as data" in notes


@pytest.mark.parametrize("lines, expected", [
    (("time_s,fx_N,fy_N", "0,1,2", "0.01,1,2", "0.01,1,2"),
     "line 4, column time_s: 0.01 is not after 0.01 of "),
    (("time_s,fx_N,fy_N", "0,1,2", "-0.01,1,2"), "line 3, column time_s: -0.01 is not after 0.0"),
    (("time_s,fx_N,fy_N,cycles", "0,1,2,0", "0.01,1,2,0.5"), "line 3, column cycles: 0.5;"),
    (("time_s,fx_N,fy_N", "0,1,2", "0.01,1,"), "line 3, column fy_N: empty value"),
    (("time_s,slider_acceleration_m_s2", "0,1", "0.01,-inf"),
     "line 3, column slider_acceleration_m_s2: -inf; expected a finite number"),
])
def test_bad_trace_rows(tmp_path, lines, expected):
    path = write_lines(tmp_path / "trace.csv", *lines)
    write_max_wear(tmp_path / "max.csv", [0, 100], [0.0, 1e-6])
    text = message([tmp_path / "max.csv", path])
    assert str(path) in text and expected in text


def test_traces_alone_are_not_enough(tmp_path):
    path = write_lines(tmp_path / "force.csv", "time_s,fx_N,fy_N", "0,1,2", "0.01,1,2")
    text = message(path)
    assert text.startswith("joint wear data need a bore profile or a maximum-depth growth file")
    assert str(path) in text
    assert "no joint wear data files given" in message([])
    assert "cannot read measured data" in message(tmp_path / "missing.csv")


def test_dataclasses_check_their_arrays():
    with pytest.raises(FewearInputError, match="strictly increasing"):
        MeasuredProfile(0, [0.2, 0.1, 0.3], [0.0, 0.0, 0.0])
    with pytest.raises(FewearInputError, match=r"in \[0, 2 pi\)"):
        MeasuredProfile(0, [0.0, 1.0, 2 * math.pi], [0.0, 0.0, 0.0])
    with pytest.raises(FewearInputError, match="cycles 1.5"):
        MeasuredProfile(1.5, [0.0, 1.0], [0.0, 0.0])
    with pytest.raises(FewearInputError, match="bore profile or a maximum-depth"):
        JointMeasurements()
    profile = bump_profile(10)
    assert not profile.depth_m.flags.writeable
    data = JointMeasurements(profiles=(bump_profile(10), bump_profile(0)))
    assert data.profile_cycles == (0, 10) and data.max_wear is None
    with pytest.raises(FewearInputError, match="no bore profile at 5 cycles; profiles at: 0, 10"):
        data.profile_at(5)
