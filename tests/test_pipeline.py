"""The wear prediction pipeline (fewear.pipeline): load steps, contact, Archard, the main job."""

import dataclasses
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from fewear.mbd.history import JointHistory
from fewear.pipeline import CycleWear, cycle_wear, load_steps, wear_volume_per_width_m2
from fewear.wear.coefficient import ConstantWearCoefficient


def synthetic_history(n=401, period=0.05, omega=30.0):
    """A cycle with a rotating 1 kN reaction and a known relative rotation rate."""
    t = np.linspace(0.0, period, n)
    angle = 2 * np.pi * t / period
    reaction = -1000.0 * np.column_stack([np.cos(angle), np.sin(angle)])
    zeros = np.zeros(n)
    return JointHistory(t, angle, zeros, zeros, np.zeros((n, 2)), zeros, zeros, zeros, reaction,
                        omega * np.cos(angle), np.zeros(n, dtype=int))


def test_load_steps_integrate_the_relative_rotation_and_sample_mid_step():
    history = synthetic_history()
    steps = load_steps(history, 20)
    edges = np.linspace(0.0, 0.05, 21)
    exact = 30.0 * 0.05 / (2 * np.pi) * np.diff(np.sin(2 * np.pi * edges / 0.05))
    np.testing.assert_allclose(steps.rotation_rad, exact, atol=1e-4 * np.abs(exact).max())
    middle = 2 * np.pi * steps.time_s / 0.05
    np.testing.assert_allclose(steps.force_N[:, 0], 1000.0 * np.cos(middle), atol=0.2)
    assert steps.duration_s == pytest.approx(0.05 / 20)


@pytest.fixture(scope="module")
def coarse_contact():
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.io.config import load_config

    problem = contact_problem_from_config(load_config(None, CONFIG_SECTIONS))
    size = 2 * math.pi * problem.geometry.inner_radius_m / 96 * (1 + 1e-9)
    mesh = dataclasses.replace(problem.mesh, bore_element_size_m=size, radial_element_count=6)
    return CondensedBushingContact(dataclasses.replace(problem, mesh=mesh))


def test_worn_volume_is_archards_k_F_s(coarse_contact):
    """With constant k, the worn area per cycle is k * sum_i (integral of p over the bore) s_i,
    and the integral of p over the contact arc is |F|/L up to its curvature (1/cos of the
    half-angle, a few percent at 1 kN): the volume must match k sum |F_i| s_i / L to that."""
    k = 2e-13
    steps = load_steps(synthetic_history(), 40)
    wear: CycleWear = cycle_wear(coarse_contact, steps, ConstantWearCoefficient(k), friction=False)
    worn = wear_volume_per_width_m2(wear, wear.depth_per_cycle_m)
    slip = coarse_contact.problem.geometry.pin_radius_m * np.abs(steps.rotation_rad)
    archard = k * np.sum(np.linalg.norm(steps.force_N, axis=1) * slip) / 0.018
    assert 0.99 < worn / archard < 1.1
    assert np.all(wear.depth_per_cycle_m >= 0.0)
    assert np.all(wear.k_m2_N[wear.slip_m == 0.0] == 0.0)


def test_zero_rotation_means_no_wear(coarse_contact):
    history = dataclasses.replace(synthetic_history(), rel_omega_rad_s=np.zeros(401))
    wear = cycle_wear(coarse_contact, load_steps(history, 10), ConstantWearCoefficient(2e-13),
                      friction=True)
    assert wear.pressure_Pa.max() > 0.0
    np.testing.assert_array_equal(wear.depth_per_cycle_m, 0.0)


def test_main_job_wears_the_bore_left_and_right(tmp_path):
    """The paper's claim (section 5.2): in the slider-crank the contact, hence the wear, sits on
    the left and right of the bushing (the slide axis, angles 0 and 180 deg), where the rod pushes
    and pulls the slider at the dead positions."""
    out = tmp_path / "run"
    process = subprocess.run([sys.executable, "-m", "fewear.cli", "run", "--out", str(out)],
                             capture_output=True, text=True)
    assert process.returncode == 0, process.stderr
    summary = json.loads((out / "summary.json").read_text())
    profile = np.genfromtxt(out / "wear_profile.csv", delimiter=",", names=True)
    for rod in ("rigid", "flexible"):
        depth = profile[f"depth_per_cycle_{rod}_m"]
        angle = profile["angle_deg"]
        near_axis = np.abs((angle + 90) % 180 - 90)  # degrees from the slide axis
        assert np.sum(depth[near_axis < 30]) > 0.9 * np.sum(depth)
        right = depth[(angle < 30) | (angle > 330)].sum()
        left = depth[(angle > 150) & (angle < 210)].sum()
        assert min(left, right) > 0.25 * (left + right)
        assert summary["cases"][rod]["max_wear_depth_first_block_m"] == pytest.approx(
            5000 * depth.max(), rel=1e-6)
    for name in ("joint_history_rigid.csv", "joint_history_flexible.csv", "wear_profile.png"):
        assert (out / name).stat().st_size > 0
