"""Joint wear data whose units or cycle counts cannot be right (issue 57): radians under
angle_deg, profiles whose wear shrinks with cycles, a maximum depth that falls 4x; each refused
at the command line in one line naming the likely error; a dip within scatter kept."""

import math

import numpy as np
import pytest

from fewear.cli import main
from fewear.diagnose.joint.measured import (
    MAX_FALL,
    MeasuredProfile,
    read_joint_measurements,
    write_joint_profiles,
    write_max_wear,
)


def bump(cycles, depth_um, step_deg=5.0):
    angle = np.deg2rad(np.arange(0.0, 360.0, step_deg))
    return MeasuredProfile(cycles, angle,
                           depth_um * 1e-6 * np.exp(-((angle - math.pi / 2) / 0.4) ** 2))


def one_error_line(capsys, paths, tmp_path) -> str:
    out = tmp_path / "out"
    assert main(["diagnose", *map(str, paths), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    lines = [line for line in err.splitlines() if line.startswith("fewear: error:")]
    assert len(lines) == 1 and "Traceback" not in err and not out.exists()
    return lines[0]


def test_radians_under_angle_deg_are_refused(tmp_path, capsys):
    angle_rad = np.linspace(0.0, 2.0 * math.pi, 72, endpoint=False)
    lines = ["cycles,angle_deg,wear_depth_m"]
    lines += [f"10000,{a!r},{1e-5 * math.exp(-((a - 1.5) / 0.4) ** 2)!r}" for a in angle_rad]
    path = tmp_path / "radians.csv"
    path.write_text("\n".join(lines) + "\n")
    line = one_error_line(capsys, [path], tmp_path)
    assert "column angle_deg: every angle lies within +-6.28 deg" in line
    assert "radians under angle_deg" in line


def test_profiles_whose_wear_shrinks_5x_are_refused(tmp_path, capsys):
    path = tmp_path / "bore.csv"
    write_joint_profiles(path, [bump(10000, 20.0), bump(50000, 4.0)])
    line = one_error_line(capsys, [path], tmp_path)
    assert "the deepest wear of the bore profile falls from 20 um at 10000 cycles to 4 um at " \
           "50000 cycles (5x less)" in line
    assert "check the cycles column" in line


def test_a_maximum_depth_that_falls_4x_is_refused(tmp_path, capsys):
    path = tmp_path / "max.csv"
    write_max_wear(path, np.array([0, 10000, 20000, 30000]), np.array([0.0, 4e-6, 8e-6, 2e-6]))
    line = one_error_line(capsys, [path], tmp_path)
    assert "the maximum wear depth falls from 8 um at 20000 cycles to 2 um at 30000 cycles " \
           "(4x less)" in line


@pytest.mark.parametrize("fall", [1.5, 0.9 * MAX_FALL])
def test_a_dip_within_scatter_is_kept(tmp_path, fall):
    path = tmp_path / "max.csv"
    write_max_wear(path, np.array([0, 10000, 20000]), np.array([0.0, 8e-6, 8e-6 / fall]))
    data = read_joint_measurements([path])
    assert data.max_wear[1][-1] == pytest.approx(8e-6 / fall)
    assert any("dips below" in note for note in data.notes)


def test_depths_1000x_too_shallow_are_refused(tmp_path, capsys):
    """A 20 um deep wear written 1000x too small (20 nm): below a profilometer's resolution."""
    path = tmp_path / "bore.csv"
    write_joint_profiles(path, [bump(0, 0.0), bump(50000, 20.0e-3)])
    line = one_error_line(capsys, [path], tmp_path)
    assert "the deepest wear is 2e-08 m, within a profilometer's resolution (1e-07 m)" in line
    assert "depths in the wrong unit" in line
