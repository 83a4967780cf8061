"""Generalized-alpha on rigid systems: closed forms, convergence rate, energy behaviour."""

import math

import numpy as np
import pytest
from scipy.integrate import solve_ivp

from fewear.mbd.constraints import Revolute
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings
from fewear.mbd.points import GroundPoint, RigidPoint
from fewear.mbd.slider_crank import SliderCrank, simulate_slider_crank
from fewear.mbd.system import MultibodySystem

MASS_KG, LENGTH_M, G_M_S2, THETA0_RAD = 1.0, 1.0, 9.81, 0.5
INERTIA_O = MASS_KG * LENGTH_M**2 / 3.0  # bar about its end


def pendulum():
    """A uniform bar hinged at its end to the ground (absolute coordinates, 2 constraints)."""
    system = MultibodySystem((0.0, -G_M_S2))
    body = system.add_rigid_body(MASS_KG, MASS_KG * LENGTH_M**2 / 12.0)
    system.add_constraint(Revolute(RigidPoint(body, (-LENGTH_M / 2, 0.0)), GroundPoint(0, 0)))
    q0 = np.array([LENGTH_M / 2 * math.cos(THETA0_RAD), LENGTH_M / 2 * math.sin(THETA0_RAD),
                   THETA0_RAD])
    return system.finalize(), q0, np.zeros(3)


def run_pendulum(step_s, rho_inf, t_end):
    system, q0, qd0 = pendulum()
    integrator = GeneralizedAlpha(system, IntegratorSettings(rho_inf=rho_inf, step_s=step_s,
                                                             adaptive=False))
    energy = []
    state = integrator.run(integrator.initial_state(q0, qd0), t_end, lambda s, h: energy.append(
        system.kinetic_energy(s.qd) + system.gravity_potential(s.q)))
    return state, np.array(energy) - system.gravity_potential(q0)


def test_ideal_slider_crank_matches_closed_form():
    history, _ = simulate_slider_crank(rod="rigid", joint="ideal", cycles=1, settling_cycles=0)
    _, x_m, v_m_s = SliderCrank().closed_form(history.time_s)
    assert np.max(np.abs(history.slider_x_m - x_m)) < 1e-8
    assert np.max(np.abs(history.slider_velocity_m_s - v_m_s)) < 1e-8


def test_ideal_slider_crank_dead_centre_force():
    """At theta = 0 the slider's acceleration is -r omega^2 (1 + r/l); the pin must push it."""
    crank = SliderCrank()
    history, _ = simulate_slider_crank(rod="rigid", joint="ideal", cycles=1, settling_cycles=0)
    omega = crank.omega_rad_s
    expected = crank.slider_mass_kg * crank.crank_length_m * omega**2 * (
        1 + crank.crank_length_m / crank.rod_length_m)
    assert history.reaction_force_N[0, 0] == pytest.approx(expected, rel=1e-6)


def test_pendulum_second_order_convergence():
    reference = solve_ivp(
        lambda t, y: [y[1], -MASS_KG * G_M_S2 * LENGTH_M / 2 * math.cos(y[0]) / INERTIA_O],
        (0.0, 1.0), [THETA0_RAD, 0.0], rtol=1e-12, atol=1e-12).y[0, -1]
    steps = np.array([0.02, 0.01, 0.005, 0.0025])
    errors = [abs(run_pendulum(h, 0.8, 1.0)[0].q[2] - reference) for h in steps]
    rate = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    assert abs(rate - 2.0) < 0.1
    assert errors[-1] < 1e-4


def test_energy_conserved_to_second_order_without_damping():
    steps = np.array([0.02, 0.01, 0.005])
    drifts = [np.max(np.abs(run_pendulum(h, 1.0, 2.0)[1])) for h in steps]
    rate = np.polyfit(np.log(steps), np.log(drifts), 1)[0]
    assert abs(rate - 2.0) < 0.15
    # no secular drift: the energy error over 2 s is no larger at the end than at its peak early
    _, energy = run_pendulum(0.01, 1.0, 20.0)
    assert abs(energy[-200:]).max() < 1.5 * abs(energy[:200]).max()


def test_energy_dissipated_with_numerical_damping():
    """rho_inf < 1 damps: over 20 s (omega h ~ 0.1) the energy falls well below the undamped
    scheme's whole error band."""
    _, damped = run_pendulum(0.02, 0.5, 20.0)
    _, undamped = run_pendulum(0.02, 1.0, 20.0)
    assert damped[-1] < -1.5 * np.max(np.abs(undamped))


def test_stiff_flexible_rod_behaves_like_the_rigid_rod():
    """With ideal joints, the damped steel ANCF rod (axial stretch ~ F l / EA ~ 2e-5 m) must carry
    nearly the rigid rod's joint force and move the slider as the closed form does."""
    rigid, _ = simulate_slider_crank(rod="rigid", joint="ideal", cycles=1, settling_cycles=1)
    flexible, _ = simulate_slider_crank(rod="flexible", joint="ideal", cycles=1, settling_cycles=1)
    assert np.allclose(flexible.time_s, rigid.time_s)
    difference = flexible.reaction_force_N - rigid.reaction_force_N
    scale = np.sqrt(np.mean(np.sum(rigid.reaction_force_N**2, axis=1)))
    assert np.sqrt(np.mean(np.sum(difference**2, axis=1))) < 0.03 * scale
    _, x_m, _ = SliderCrank().closed_form(flexible.time_s)
    assert np.max(np.abs(flexible.slider_x_m - x_m)) < 1e-4
