"""The joint-history CSV (fewear.io.joint_history): units and frames converted against values
worked by hand, and every malformed file refused in one line naming the file, the line or
column, and what is allowed."""

import math

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.io.joint_history import read_joint_history, write_joint_history
from fewear.mbd.history import JointHistory

PERIOD_S = 0.05


def one_cycle(n=201):
    """A load turning once around the bore (one period) with a rod swinging +-0.3 rad."""
    time = np.linspace(0.0, PERIOD_S, n)
    phase = 2 * math.pi * time / PERIOD_S
    return time, 1000 * np.cos(phase), 1000 * np.sin(phase), 0.3 * np.sin(phase)


def write(tmp_path, header, columns, name="history.csv", text=None):
    path = tmp_path / name
    if text is None:
        rows = [",".join(f"{v:.17g}" for v in row) for row in np.column_stack(columns)]
        text = ",".join(header) + "\n" + "\n".join(rows) + "\n"
    path.write_text(text)
    return path


def test_bushing_frame_si_and_the_relative_angle_differentiated(tmp_path):
    time, fx, fy, angle = one_cycle()
    history = read_joint_history(write(tmp_path, ["time_s", "force_x_N", "force_y_N",
                                                  "relative_angle_rad"], [time, fx, fy, angle]))
    # the file's load presses the pin into the bore: minus the bushing's reaction on the pin
    np.testing.assert_array_equal(history.reaction_force_N, -np.column_stack([fx, fy]))
    # d/dt 0.3 sin(2 pi t / T) = 0.3 (2 pi / T) cos(...); np.gradient is second order
    omega = 0.3 * 2 * math.pi / PERIOD_S * np.cos(2 * math.pi * time / PERIOD_S)
    np.testing.assert_allclose(history.rel_omega_rad_s, omega, atol=2e-3 * np.abs(omega).max())
    # no impact columns: no impact episodes, no penetration, the normal force |F|
    assert history.impacts == 0 and not np.any(history.penetration_m)
    np.testing.assert_allclose(history.normal_force_N, 1000.0)
    assert set(history.mode) == {2}


def test_global_frame_kilonewtons_milliseconds_and_rpm(tmp_path):
    """A bushing body turned by 30 deg: the global load (1 kN, 0) is (cos 30, -sin 30) kN in its
    frame; rpm and ms convert to rad/s and s."""
    time, _, _, _ = one_cycle(5)
    ones = np.ones(5)
    history = read_joint_history(write(
        tmp_path, ["time_ms", "global_force_x_kN", "global_force_y_kN", "bushing_angle_deg",
                   "relative_omega_rpm"],
        [1e3 * time, ones, 0 * ones, 30 * ones, 0 * ones]))
    np.testing.assert_allclose(history.time_s, time, rtol=1e-15)
    np.testing.assert_allclose(-history.reaction_force_N,
                               np.tile([1e3 * math.cos(math.pi / 6), -1e3 * 0.5], (5, 1)),
                               rtol=1e-12)
    assert not np.any(history.rel_omega_rad_s)
    path = write(tmp_path, ["time_s", "force_x_N", "force_y_N", "relative_omega_rpm"],
                 [time, ones, ones, 60 * ones], name="turning.csv")
    with pytest.raises(FewearInputError, match="turns by 18 deg"):
        read_joint_history(path)  # 1 turn per second for 0.05 s is not a whole turn


def test_what_fewear_dynamics_writes_reads_back_to_the_same_floats(tmp_path):
    time, fx, fy, angle = one_cycle(50)
    rng = np.random.default_rng(1)
    mode = rng.integers(0, 3, time.size)
    history = JointHistory(time, 2 * math.pi * time / PERIOD_S, np.zeros(50), np.zeros(50),
                           rng.normal(size=(50, 2)) * 1e-4, rng.random(50) * 1e-6,
                           rng.random(50) * 1e3, rng.normal(size=50),
                           -np.column_stack([fx, fy]), 0.1 * np.cos(time), mode)
    write_joint_history(history, tmp_path / "h.csv")
    back = read_joint_history(tmp_path / "h.csv")
    for name in ("time_s", "eccentricity_m", "penetration_m", "normal_force_N",
                 "friction_force_N", "reaction_force_N", "rel_omega_rad_s", "mode"):
        np.testing.assert_array_equal(getattr(back, name), getattr(history, name), err_msg=name)
    # the crank angle goes through degrees (for the reader of the file): to rounding
    np.testing.assert_allclose(back.crank_angle_rad, history.crank_angle_rad, rtol=1e-15)


@pytest.mark.parametrize("unit, turn", [("rad", 2 * math.pi), ("deg", 360.0)])
def test_a_joint_turning_once_per_cycle_in_either_unit(tmp_path, unit, turn):
    """A crank pin: the relative angle grows by one turn over the cycle, in rad or deg."""
    time, fx, fy, _ = one_cycle(11)
    history = read_joint_history(write(
        tmp_path, ["time_s", "force_x_N", "force_y_N", f"relative_angle_{unit}"],
        [time, fx, fy, turn * time / PERIOD_S]))
    np.testing.assert_allclose(history.rel_omega_rad_s, 2 * math.pi / PERIOD_S, rtol=1e-9)


GOOD = "time_s,force_x_N,force_y_N,relative_angle_rad\n"


@pytest.mark.parametrize("text, expected", [
    ("", "no header line"),
    (GOOD, "no data rows"),
    (GOOD + "0,1,0,0\n0.02,0,1,0.3\n0.02,-1,0,0\n0.05,1,0,0\n",
     "line 4, column time_s: time 0.02 after 0.02; expected strictly increasing"),
    (GOOD + "0,1,0,0\n0.02,nan,1,0.3\n0.05,1,0,0\n", "line 3, column force_x_N: nan"),
    (GOOD + "0,1,0,0\n0.02,inf,1,0.3\n0.05,1,0,0\n", "line 3, column force_x_N: inf"),
    ("time_s,force_x_lbf,force_y_N,relative_angle_rad\n0,1,0,0\n",
     "column 'force_x_lbf' is not a known quantity with a unit suffix; allowed: time_<s|ms>"),
    ("time_s,force_x,force_y_N,relative_angle_rad\n0,1,0,0\n", "column 'force_x' is not"),
    ("time_s,force_y_N,relative_angle_rad\n0,1,0\n", "missing column(s) force_x_<N|kN>"),
    ("time_s,force_x_N,force_y_N\n0,1,0\n", "neither relative_angle_<rad|deg> nor"),
    (GOOD + "0,1,0,0\n0.02,0,1,0.3\n0.05,0.5,0,0\n",
     "the last load differs from the first by 0.5 N, 50.0% of the peak 1 N"),
    ("time_s,force_x_N,force_y_N,relative_angle_deg\n0,1,0,0\n0.02,0,1,0.3\n0.05,1,0,0\n",
     "the pin swings only 0.3 deg relative to the bushing: the values look like radians"),
    (GOOD + "0,1,0,0\n0.02,0,1,17\n0.03,0,1,-17\n0.05,1,0,0\n",
     "the pin swings 34 rad relative to the bushing besides whole turns, more than one turn: "
     "the values look like degrees"),
    (GOOD.replace("\n", ",crank_angle_deg\n") + "0,1,0,0,0\n0.02,0,1,0.3,90\n0.05,1,0,0,180\n",
     "the crank turns by 180 deg over the history; expected 1 cycle(s)"),
    (GOOD.replace("\n", ",mode\n") + "0,1,0,0,contact\n0.02,0,1,0.3,hit\n0.05,1,0,0,free\n",
     "line 3, column mode: 'hit'; expected one of free, impact, contact"),
])
def test_a_malformed_history_is_refused_naming_the_place(tmp_path, text, expected):
    path = write(tmp_path, None, None, text=text)
    with pytest.raises(FewearInputError) as error:
        read_joint_history(path)
    message = str(error.value)
    assert expected in message and str(path) in message and "\n" not in message


def test_impact_wear_needs_the_impact_columns(tmp_path):
    time, fx, fy, angle = one_cycle(20)
    path = write(tmp_path, ["time_s", "force_x_N", "force_y_N", "relative_angle_rad"],
                 [time, fx, fy, angle])
    with pytest.raises(FewearInputError, match="missing column.s. penetration, normal_force, mode"):
        read_joint_history(path, impacts=True)


def test_fewear_run_refuses_a_bad_history_in_one_line_writing_nothing(tmp_path, capsys):
    from fewear.cli import main

    path = write(tmp_path, None, None, text=GOOD + "0,1,0,0\n0.02,0,1,0.3\n0.05,0.5,0,0\n")
    assert main(["run", "--joint-history", str(path), "--out", str(tmp_path / "out")]) == 2
    error = capsys.readouterr().err
    assert error.startswith("fewear: error: ") and "the last load differs" in error
    assert len(error.strip().splitlines()) == 1 and not (tmp_path / "out").exists()
