"""The simulated profilometer does what its specification says: noise of the stated size, the
angular offset with the stated sign, sampling and arcs, quantisation, the profile filter; and its
profiles go through the joint data reader like a user's file."""

import math

import numpy as np
import pytest

from fewear.diagnose.joint.measured import read_joint_measurements, write_joint_profiles
from tests.diagnose.joint.profilometer import (
    NOISE_m,
    RESOLUTION_m,
    filtered_profile,
    max_wear_growth,
    measure_profile,
)

FLAT_rad = np.deg2rad([0.0, 120.0, 240.0])


def bump(centre_deg, width_deg=6.0, depth_m=40e-6):
    """A single smooth bump of the true depth (the Gaussian is wide against the 1 deg filter)."""
    angle = np.deg2rad(np.arange(0.0, 360.0, 0.25))
    distance = np.angle(np.exp(1j * (angle - math.radians(centre_deg))))
    return angle, depth_m * np.exp(-0.5 * (distance / math.radians(width_deg)) ** 2)


def test_noise_statistics_on_a_zero_profile():
    rng = np.random.default_rng(1)
    depths = np.concatenate([
        measure_profile(FLAT_rad, np.zeros(3), rng, step_deg=0.5).profile.depth_m
        for _ in range(5)])
    assert depths.size == 3600
    assert abs(np.std(depths) - NOISE_m) < 0.2 * NOISE_m
    assert abs(np.mean(depths)) < 4.0 * NOISE_m / math.sqrt(depths.size)


def test_depths_are_quantised_to_the_resolution():
    rng = np.random.default_rng(2)
    depth = measure_profile(*bump(100.0), rng).profile.depth_m
    steps = depth / RESOLUTION_m
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-6)


@pytest.mark.parametrize("offset_deg", [12.0, -15.0, None])
def test_offset_shifts_a_bump_to_the_true_angle_minus_the_offset(offset_deg):
    rng = np.random.default_rng(3)
    measured = measure_profile(*bump(100.0), rng, step_deg=0.5, offset_deg=offset_deg)
    if offset_deg is not None:
        assert measured.offset_deg == offset_deg
    assert -20.0 <= measured.offset_deg <= 20.0
    profile = measured.profile
    peak_deg = math.degrees(profile.angle_rad[np.argmax(profile.depth_m)])
    assert abs(peak_deg - (100.0 - measured.offset_deg)) <= 1.0


def test_default_sampling_is_a_full_circle_every_2_to_5_degrees():
    rng = np.random.default_rng(4)
    for _ in range(20):
        measured = measure_profile(FLAT_rad, np.zeros(3), rng)
        angle_deg = np.rad2deg(measured.profile.angle_rad)
        gaps = np.diff(np.append(angle_deg, angle_deg[0] + 360.0))
        assert 2.0 - 0.1 <= measured.step_deg <= 5.0 + 0.1
        np.testing.assert_allclose(gaps, measured.step_deg, atol=1e-9)
        assert np.all((angle_deg >= 0.0) & (angle_deg < 360.0))


def test_an_arc_covers_only_its_angles():
    rng = np.random.default_rng(5)
    measured = measure_profile(FLAT_rad, np.zeros(3), rng, start_deg=330.0, coverage_deg=90.0,
                               step_deg=3.0, offset_deg=0.0)
    angle_deg = np.rad2deg(measured.profile.angle_rad)
    assert angle_deg.size == 31
    assert np.all((angle_deg >= 330.0 - 1e-9) | (angle_deg <= 60.0 + 1e-9))


def test_the_profile_filter_passes_long_waves_and_attenuates_the_cutoff_to_half():
    angle = np.linspace(0.0, 2.0 * math.pi, 7200, endpoint=False)
    for harmonic, transmission in ((1, 1.0), (360, 0.5)):  # 360 deg and 1 deg wavelengths
        fine_rad, fine = filtered_profile(angle, np.cos(harmonic * angle), 1.0)
        assert np.max(np.abs(fine)) == pytest.approx(transmission, abs=2e-3)
    _, unfiltered = filtered_profile(angle, np.cos(360 * angle), 0.0)
    assert np.max(np.abs(unfiltered)) == pytest.approx(1.0)


def test_max_wear_growth_noise():
    rng = np.random.default_rng(6)
    cycles = np.arange(0, 4000) * 100
    truth = 1e-10 * cycles
    counts, depth = max_wear_growth(cycles, truth, rng)
    assert counts.dtype.kind == "i"
    np.testing.assert_array_equal(counts, cycles)
    assert abs(np.std(depth - truth) - NOISE_m) < 0.1 * NOISE_m


def test_simulated_profiles_read_back_through_the_joint_reader(tmp_path):
    rng = np.random.default_rng(7)
    profiles = [measure_profile(*bump(80.0, depth_m=scale * 30e-6), rng, cycles=cycles).profile
                for cycles, scale in ((0, 0.0), (25000, 0.5), (50000, 1.0))]
    write_joint_profiles(tmp_path / "bore.csv", profiles, comment="simulated profilometer")
    data = read_joint_measurements([tmp_path / "bore.csv"])
    assert data.profile_cycles == (0, 25000, 50000)
    for read, written in zip(data.profiles, profiles):
        np.testing.assert_array_equal(read.depth_m, written.depth_m)
    assert any("below zero" in note for note in data.notes)
