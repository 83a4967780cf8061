"""The clearance joint in motion: restitution of one impact, and the limit of zero clearance."""

import math

import numpy as np
import pytest

from fewear.io.config import load_config
from fewear.mbd.clearance import ClearanceJoint
from fewear.mbd.contact import ClearanceProfile, ContactLaw, Friction
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings
from fewear.mbd.points import GroundPoint, RigidPoint
from fewear.mbd.slider_crank import SECTIONS, simulate_slider_crank
from fewear.mbd.system import MultibodySystem

CLEARANCE_M = 5.0e-4
# LN's hysteresis damping is derived for c_e near 1 (the energy loss per impact is small, so the
# approach velocity stands for the whole impact); at c_e = 0.9 the measured restitution should
# match within a few percent (at c_e = 0.5 it overshoots by ~15%: Flores et al. 2011).
RESTITUTION = 0.9


def free_pin_rebound(restitution, law="lankarani-nikravesh", speed_m_s=1.0, angle_rad=0.3):
    """A 1 kg pin moving from the centre of a fixed bushing hits the wall once (no friction, no
    gravity); return (approach speed, rebound speed) along the normal."""
    system = MultibodySystem((0.0, 0.0))
    body = system.add_rigid_body(1.0, 1e-4)
    contact = ContactLaw(law, 4.0e10, restitution=restitution)
    joint = ClearanceJoint(RigidPoint(body), GroundPoint(0.0, 0.0), 0.0095, 0.010,
                           ClearanceProfile.constant(CLEARANCE_M), contact, Friction(0.0))
    system.add_force(joint)
    system.finalize()
    integrator = GeneralizedAlpha(system, IntegratorSettings(
        rho_inf=1.0, step_s=1e-5, gap_tolerance_m=1e-9))
    direction = np.array([math.cos(angle_rad), math.sin(angle_rad)])
    state = integrator.initial_state(np.zeros(3), np.array([*(speed_m_s * direction), 0.0]))
    state = integrator.run(state, 2 * CLEARANCE_M / speed_m_s + 5e-4)
    return speed_m_s, -state.qd[:2] @ direction


@pytest.mark.parametrize("law", ["lankarani-nikravesh", "hunt-crossley", "flores"])
def test_one_impact_reproduces_the_restitution_coefficient(law):
    approach, rebound = free_pin_rebound(RESTITUTION, law)
    measured = rebound / approach
    tolerance = 0.03 if law == "lankarani-nikravesh" else 0.06
    assert measured == pytest.approx(RESTITUTION, rel=tolerance)


def test_elastic_impact_conserves_energy():
    approach, rebound = free_pin_rebound(1.0)
    assert rebound == pytest.approx(approach, rel=1e-3)


def test_small_clearance_approaches_the_ideal_joint():
    """The rms difference of the joint force from the ideal joint's falls with the clearance."""
    config = load_config(None, SECTIONS)
    ideal, _ = simulate_slider_crank(config, rod="rigid", joint="ideal", cycles=1,
                                     settling_cycles=1)
    ideal_force = np.linalg.norm(ideal.reaction_force_N, axis=1)
    rms = []
    for clearance in (1e-4, 1e-5, 1e-6):
        history, _ = simulate_slider_crank(
            config, rod="rigid", joint="clearance", cycles=1, settling_cycles=1,
            clearance_profile=ClearanceProfile.constant(clearance))
        force = np.interp(ideal.time_s, history.time_s,
                          np.linalg.norm(history.reaction_force_N, axis=1))
        rms.append(np.sqrt(np.mean((force - ideal_force) ** 2)))
    scale = np.sqrt(np.mean(ideal_force**2))
    assert rms[0] > rms[1] > rms[2]
    assert rms[2] < 0.1 * scale
