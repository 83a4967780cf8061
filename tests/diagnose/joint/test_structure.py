"""The residual structure against the crank cycle (fewear.diagnose.joint.structure) on
constructed joint histories with known answers: a pin that presses the bore at the crank angle
itself, two impact episodes, a trace that is the simulated one seen from another time origin."""

import math

import numpy as np
import pytest

from fewear.diagnose.joint.structure import (
    crank_angle_table,
    impact_table,
    scatter_estimate_m,
    trace_table,
)
from fewear.mbd.history import JointHistory

OMEGA = 2.0 * math.pi * 20.0  # rad/s: 1200 rpm


def history(n=3600, modes=None, force=None):
    """One crank cycle in n rows; the pin presses the bore at the crank angle (contact all along,
    force 100 N unless given)."""
    t = np.linspace(0.0, 2.0 * math.pi / OMEGA, n + 1)
    phi = OMEGA * t
    direction = np.column_stack([np.cos(phi), np.sin(phi)])
    magnitude = np.full(t.size, 100.0) if force is None else force
    mode = np.full(t.size, 2) if modes is None else modes
    return JointHistory(t, phi, np.zeros(t.size), np.sin(phi), 1e-4 * direction,
                        np.full(t.size, 1e-6), magnitude, np.zeros(t.size),
                        -magnitude[:, None] * direction, np.zeros(t.size), mode)


def test_the_residual_is_read_where_the_pin_pressed_in_each_crank_sector():
    table = crank_angle_table(history(), np.cos)
    for row in table:
        lo, hi = math.radians(row["crank_from_deg"]), math.radians(row["crank_to_deg"])
        # the mean of cos over the sector's bore angles (the pin presses theta = phi)
        assert row["residual_m"] == pytest.approx((math.sin(hi) - math.sin(lo)) / (hi - lo),
                                                  abs=1e-3)  # the rows: 0.1 deg
        middle = 0.5 * (row["crank_from_deg"] + row["crank_to_deg"])
        assert row["pressed_angle_deg"] == pytest.approx(middle, abs=0.1)
        assert row["contact_share"] == pytest.approx(1.0)


def test_a_free_sector_has_no_residual():
    force = np.full(3601, 100.0)
    force[:305] = force[-1] = 0.0  # free over the first 30.5 deg (the last row: 360 deg)
    table = crank_angle_table(history(force=force), np.cos)
    assert table[0]["residual_m"] is None and table[0]["contact_share"] < 0.01
    assert table[1]["residual_m"] is not None


def test_impact_episodes_are_found_with_their_peak_and_bore_angle():
    modes = np.full(3601, 2)
    force = np.full(3601, 100.0)
    modes[900:905] = 1  # 90-90.4 deg
    force[902] = 5e3
    modes[2700:2703] = 1  # 270 deg
    force[2701] = 2e3
    residual = lambda angle: np.where(np.abs(np.sin(angle)) > 0.99, 3e-6, 1e-6)  # noqa: E731
    table = impact_table(history(modes=modes, force=force), residual, bore_rms_m=1.5e-6)
    assert table["impacts_per_cycle"] == 2
    first, second = table["largest"]
    assert (first["peak_force_N"], second["peak_force_N"]) == pytest.approx((5e3, 2e3))
    assert first["bore_angle_deg"] == pytest.approx(90.2, abs=1e-9)
    assert first["crank_angle_deg"] == pytest.approx(90.0, abs=1e-9)
    assert table["ratio"] == pytest.approx(3e-6 / 1.5e-6)


def test_a_trace_from_another_time_origin_is_aligned_and_matches():
    simulated = history(force=100.0 + 50.0 * np.cos(np.linspace(0, 2 * math.pi, 3601)) ** 3)
    # the instrument starts recording 73 deg of crank after the simulation's origin
    t = np.linspace(0.0, 2.0 * math.pi / OMEGA, 2000, endpoint=False)
    phi = OMEGA * t + math.radians(73.0)
    measured = 100.0 + 50.0 * np.cos(phi) ** 3
    row = trace_table(t, measured, simulated, "force")
    assert row["phase_deg"] == 73.0
    assert row["relative_rms_difference"] < 0.01
    assert row["measured_peak"] == pytest.approx(150.0, rel=1e-3)
    off = trace_table(t, 1.2 * measured, simulated, "force")
    assert off["relative_rms_difference"] == pytest.approx(0.2, rel=0.02)
    assert np.mean(off["difference_by_sector"]) > 0.0


def profiles_with(shape_m, noise_m, seed=0):
    """Residuals at three cycle counts, every 3 deg: a smooth shape plus white noise."""
    rng = np.random.default_rng(seed)
    angle = np.tile(np.radians(np.arange(0.0, 360.0, 3.0)), 3)
    cycles = np.repeat([4000.0, 8000.0, 12000.0], 120)
    residual = shape_m * np.sin(2.0 * angle) + rng.normal(0.0, noise_m, angle.size)
    return angle, residual, cycles


@pytest.mark.parametrize("shape_m", [0.0, 20e-6])
def test_the_instruments_scatter_is_found_under_a_smooth_misfit(shape_m):
    angle, residual, cycles = profiles_with(shape_m, 0.5e-6)
    residual[::37] -= 3e-6  # dust spikes
    assert scatter_estimate_m(angle, residual, cycles) == pytest.approx(0.5e-6, rel=0.15)


def test_a_large_misfit_without_a_cause_is_reported_unexplained():
    from fewear.diagnose.joint.fitting import Fit
    from fewear.diagnose.joint.unexplained import unexplained_sentences

    for shape_m, expected in ((0.0, 0), (20e-6, 1)):
        angle, residual, cycles = profiles_with(shape_m, 0.5e-6)
        r = residual[cycles < 12000.0]
        rms = float(np.sqrt(np.mean(r**2)))
        fit = Fit("baseline", np.zeros(1), 1, float(r @ r), r.size, rms, rms, residual)
        resolution = {"instrument_scatter_m": scatter_estimate_m(angle, residual, cycles),
                      "halved_blocks_rms_m": 0.0, "doubled_recorded_cycles_rms_m": 0.0,
                      "start_angle_spread_rms_m": 0.0}
        assert len(unexplained_sentences(fit, fit, [], resolution, [])) == expected
