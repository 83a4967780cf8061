"""A flexible ANCF pendulum: the energy behaviour of generalized-alpha on a flexible body.

A soft beam (E = 10 MPa, rho = 1000 kg/m^3, 20 mm x 20 mm, L = 0.5 m, 2 elements: first bending
frequency about 1.3 Hz, so it bends visibly while it swings) is pinned at its left end to the ground
by an ideal revolute joint and released from rest, horizontal, under gravity. Total energy
E = T + V_gravity + U_strain.

- rho_inf = 1 (no numerical dissipation): the energy error is O(h^2) (fitted rate 2 +- 0.15) and
  small on the finest step.
- A beam released 1 % pre-stretched vibrates axially (first mode about 300 rad/s, omega h = 0.3 at
  h = 1 ms; the discrete higher modes and the thickness modes lie far above 1/h): rho_inf = 1 keeps
  that energy (to 1 % of it), rho_inf < 1 dissipates it, the more the smaller rho_inf.
"""

import numpy as np
import pytest

from fewear.mbd.ancf import AncfBeam, BeamSection
from fewear.mbd.constraints import Revolute
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings
from fewear.mbd.points import GroundPoint, NodePoint
from fewear.mbd.system import MultibodySystem

LENGTH_M = 0.5
SECTION = BeamSection(youngs_modulus_Pa=1e7, poisson_ratio=0.3, density_kg_m3=1000.0,
                      height_m=0.02, width_m=0.02)
GRAVITY_M_S2 = 9.81


def energy_history(step_s: float, rho_inf: float, end_time_s: float, stretch: float = 0.0):
    """Total energy (J) at every step of a pendulum released from rest, and the beam."""
    beam = AncfBeam(LENGTH_M, 2, SECTION)
    system = MultibodySystem((0.0, -GRAVITY_M_S2))
    first = system.add_beam(beam)
    system.add_constraint(Revolute(GroundPoint(0.0, 0.0), NodePoint(first)))
    system.finalize()
    settings = IntegratorSettings(rho_inf=rho_inf, step_s=step_s, min_step_s=step_s / 100,
                                  adaptive=False)
    integrator = GeneralizedAlpha(system, settings)
    q0 = beam.reference_coordinates(0.0, 0.0, 0.0)
    q0[0::4] *= 1.0 + stretch

    def energy(state):
        return (system.kinetic_energy(state.qd) + system.gravity_potential(state.q)
                + beam.strain_energy(state.q))

    state = integrator.initial_state(q0, np.zeros_like(q0))
    energies = [energy(state)]
    integrator.run(state, end_time_s, observer=lambda s, h: energies.append(energy(s)))
    assert integrator.stats.steps == round(end_time_s / step_s)
    return np.array(energies), beam, q0


def test_energy_error_is_second_order_without_dissipation():
    steps = np.array([4e-3, 2e-3, 1e-3])
    errors = []
    for step in steps:
        energies, _, _ = energy_history(step, rho_inf=1.0, end_time_s=0.5)
        mass = SECTION.density_kg_m3 * SECTION.area_m2 * LENGTH_M
        errors.append(np.abs(energies - energies[0]).max() / (mass * GRAVITY_M_S2 * LENGTH_M / 2))
    rate = np.polyfit(np.log(steps), np.log(errors), 1)[0]
    print(f"flexible pendulum, rho_inf = 1: energy errors {errors}, fitted rate {rate:.3f}")
    assert rate == pytest.approx(2.0, abs=0.15)
    assert errors[-1] < 5e-5


def test_dissipation_of_fast_vibrations_grows_as_rho_inf_falls():
    lost = {}
    for rho_inf in (1.0, 0.8, 0.5, 0.0):
        energies, beam, q0 = energy_history(1e-3, rho_inf, end_time_s=0.2, stretch=1e-2)
        stored = beam.strain_energy(q0)
        lost[rho_inf] = (energies[0] - energies[-1]) / stored
        if rho_inf == 1.0:
            assert np.abs(energies - energies[0]).max() < 0.01 * stored
    print(f"pre-stretched pendulum, energy lost / initial strain energy: {lost}")
    assert abs(lost[1.0]) < 0.01
    assert 0.05 < lost[0.8] < lost[0.5] < lost[0.0]
    assert lost[0.0] > 0.5
