"""The stages of fewear.loop.stages on their own: load steps, contact and Archard over a cycle."""

import dataclasses

import numpy as np
import pytest

from fewear.loop.stages import CycleWear, cycle_wear, load_steps
from fewear.mbd.history import JointHistory
from fewear.wear.coefficient import ConstantWearCoefficient
from fewear.wear.state import WearState


def synthetic_history(n=401, period=0.05, omega=30.0):
    """A cycle with a rotating 1 kN reaction and a known relative rotation rate."""
    t = np.linspace(0.0, period, n)
    angle = 2 * np.pi * t / period
    reaction = -1000.0 * np.column_stack([np.cos(angle), np.sin(angle)])
    zeros = np.zeros(n)
    return JointHistory(t, angle, zeros, zeros, np.zeros((n, 2)), zeros, zeros, zeros, reaction,
                        omega * np.cos(angle), np.zeros(n, dtype=int))


def test_load_steps_integrate_the_relative_rotation_and_the_force_over_each_step():
    history = synthetic_history()
    steps = load_steps(history, 20)
    edges = np.linspace(0.0, 0.05, 21)
    exact = 30.0 * 0.05 / (2 * np.pi) * np.diff(np.sin(2 * np.pi * edges / 0.05))
    np.testing.assert_allclose(steps.rotation_rad, exact, atol=1e-4 * np.abs(exact).max())
    # the force turns at a constant 1 kN: the slip-weighted mean magnitude is 1 kN (the plain
    # mean vector, 1 kN sinc(pi / 20) = 0.9959 kN, is shorter), pointing within the step
    np.testing.assert_allclose(np.linalg.norm(steps.force_N, axis=1), 1000.0, rtol=1e-4)
    angle = np.arctan2(steps.force_N[:, 1], steps.force_N[:, 0]) % (2 * np.pi)
    assert np.all((angle > 2 * np.pi * edges[:-1] / 0.05) & (angle < 2 * np.pi * edges[1:] / 0.05))
    assert steps.duration_s == pytest.approx(0.05 / 20)


@pytest.mark.parametrize("n_steps", [7, 20, 64])
def test_load_steps_keep_archards_load_slip_product(n_steps):
    """Archard's worn volume of the steps, k R sum |F_i| |rotation_i|, is the history's
    k R int |F| |omega| dt at any number of steps, the force turning and pulsing within a step
    and the slip rate unsteady but of one sign (the closed form: |F| = 1000 (2 + sin 3 phi) N,
    omega = 30 (1.5 + cos phi) rad/s, phi = 2 pi t / T: the integral is 1000 * 30 * T * 3)."""
    period, t = 0.05, np.linspace(0.0, 0.05, 20001)
    phi = 2 * np.pi * t / period
    size = 1000.0 * (2.0 + np.sin(3 * phi))
    reaction = -size[:, None] * np.column_stack([np.cos(phi), np.sin(phi)])
    zeros = np.zeros_like(t)
    history = JointHistory(t, phi, zeros, zeros, np.zeros((t.size, 2)), zeros, zeros, zeros,
                           reaction, 30.0 * (1.5 + np.cos(phi)), np.zeros(t.size, dtype=int))
    steps = load_steps(history, n_steps)
    load_slip = np.sum(np.linalg.norm(steps.force_N, axis=1) * np.abs(steps.rotation_rad))
    assert load_slip == pytest.approx(1000.0 * 30.0 * period * 3.0, rel=1e-6)


def test_an_impact_between_step_middles_keeps_its_impulse():
    """A 1 ms, 100 kN impact spike inside a step: a mid-step sample misses it or takes its peak;
    the step's mean force carries its impulse (100 N s) at any number of steps."""
    t = np.linspace(0.0, 0.05, 5001)
    spike = np.where(np.abs(t - 0.0213) < 0.0005, 1.0e5, 0.0)
    reaction = -np.column_stack([spike, np.zeros_like(t)])
    zeros = np.zeros_like(t)
    history = JointHistory(t, zeros, zeros, zeros, np.zeros((t.size, 2)), zeros, zeros, zeros,
                           reaction, zeros, np.zeros(t.size, dtype=int))
    for n in (20, 50, 200):
        steps = load_steps(history, n)
        assert np.sum(steps.force_N[:, 0]) * steps.duration_s == pytest.approx(100.0, rel=0.02)


def test_worn_volume_is_archards_k_F_s(coarse_contact):
    """With constant k, the worn area per cycle is k * sum_i (integral of p over the bore) s_i,
    and the integral of p over the contact arc is |F|/L up to its curvature (1/cos of the
    half-angle, a few percent at 1 kN): the volume must match k sum |F_i| s_i / L to that."""
    k = 2e-13
    steps = load_steps(synthetic_history(), 40)
    wear: CycleWear = cycle_wear(coarse_contact, steps, ConstantWearCoefficient(k), friction=False)
    state = WearState.unworn(wear.angle_rad)
    worn = dataclasses.replace(state, depth_m=wear.depth_per_cycle_m).worn_area_m2(0.010)
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


def test_a_light_step_without_equilibrium_wears_nothing_and_a_loaded_one_stops(coarse_contact):
    """On a deeply worn bore the contact Newton may find no equilibrium for a near-zero force:
    such a step (within 1% of the cycle's load-slip product) is dropped and counted; a loaded
    one is an error."""
    from fewear.contact.admissible import ContactLoadError
    from fewear.loop.stages import LoadSteps

    class Refusing:
        def __init__(self, refused):
            self.refused = np.array(refused)

        def solve(self, force, rotation, friction=False):
            if np.allclose(force, self.refused):
                raise ContactLoadError(force, "no equilibrium", 5e-4, 1e6)
            return coarse_contact.solve(force, rotation, friction=friction)

    forces = np.array([[0.0, -2000.0], [0.0, -10.0], [0.0, -1000.0]])  # 10 N: 0.3% of the sum
    steps = LoadSteps(np.arange(3) * 1e-3, forces, np.full(3, 0.01), 1e-3, np.zeros(3))
    k = ConstantWearCoefficient(2e-13)
    wear = cycle_wear(Refusing(forces[1]), steps, k, friction=False)
    assert wear.dropped_steps == 1
    assert wear.pressure_Pa[1].max() == 0.0 and wear.slip_m[1].max() == 0.0
    assert wear.pressure_Pa[0].max() > 0.0 and wear.pressure_Pa[2].max() > 0.0
    with pytest.raises(ContactLoadError):
        cycle_wear(Refusing(forces[2]), steps, k, friction=False)
