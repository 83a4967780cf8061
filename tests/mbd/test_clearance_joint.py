"""The clearance joint in motion: restitution of one impact, and the limit of zero clearance."""

import math
from pathlib import Path

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
# match within a few percent (measured here: +1.5%; at c_e = 0.5 it gives 0.73, +45%, the known
# failure of LN for dissipative impacts, Flores et al. 2011).
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


def test_tabulated_profile_of_a_round_bore_gives_the_constant_clearance_result():
    """c(theta) given as a table of equal values runs the profile's interpolation path; the
    motion must be that of the constant clearance (the wear stage's worn-bore entry point)."""
    config = load_config(None, SECTIONS)
    table = ClearanceProfile(np.radians([0.0, 90.0, 180.0, 270.0]), np.full(4, CLEARANCE_M))
    runs = [simulate_slider_crank(config, rod="rigid", joint="clearance", cycles=1,
                                  settling_cycles=0, clearance_profile=profile)[0]
            for profile in (ClearanceProfile.constant(CLEARANCE_M), table)]
    assert runs[0].n_steps == runs[1].n_steps
    np.testing.assert_allclose(runs[1].reaction_force_N, runs[0].reaction_force_N, atol=1e-6)


def test_a_worn_bore_lets_the_pin_travel_further_where_it_is_worn():
    """Wear on the right of the bore (theta = 0) enlarges the clearance there: the pin reaches
    further right than in the round bore, and not further left."""
    config = load_config(None, SECTIONS)
    angles = np.radians(np.arange(0.0, 360.0, 10.0))
    worn = CLEARANCE_M + 1e-4 * np.maximum(np.cos(angles), 0.0) ** 4
    runs = [simulate_slider_crank(config, rod="rigid", joint="clearance", cycles=1,
                                  settling_cycles=0, clearance_profile=profile)[0]
            for profile in (ClearanceProfile.constant(CLEARANCE_M),
                            ClearanceProfile(angles, worn))]
    round_bore, worn_bore = (run.eccentricity_m[:, 0] for run in runs)
    assert worn_bore.max() > round_bore.max() + 5e-5
    assert worn_bore.min() == pytest.approx(round_bore.min(), abs=2e-5)


# The clearance c(theta) (um, every 3.75 deg from 0) of a coarse run's flexible case after 29,000
# cycles: two worn pockets on the slide axis, the 180 deg one with a ridge where the pin bridges.
WORN_CLEARANCE_UM = [
    607.8, 588.8, 570.8, 555.0, 540.7, 529.4, 520.9, 513.0, 507.2, 503.8, 501.5, 500.4,
    500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.2, 500.6,
    501.0, 501.2, 500.9, 500.7, 500.5, 500.4, 500.3, 500.1, 500.0, 500.1, 500.3, 501.3,
    502.4, 505.9, 511.7, 517.6, 526.0, 537.2, 551.5, 569.2, 590.9, 617.4, 645.6, 671.1,
    670.1, 665.4, 663.9, 665.4, 640.3, 613.7, 591.0, 572.6, 557.8, 546.2, 536.2, 527.6,
    520.9, 515.0, 509.8, 506.4, 503.4, 502.0, 500.9, 500.3, 500.1, 500.0, 500.0, 500.0,
    500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.0, 500.1, 500.4, 500.6, 501.0, 502.1,
    503.3, 506.7, 510.8, 516.7, 525.1, 536.2, 548.3, 562.9, 581.0, 603.2, 628.2, 631.1]


def test_the_flexible_rod_runs_through_a_worn_bore_with_pockets():
    """On this profile, interpolated linearly, the flexible rod's steps collapsed below 1e-9 s
    (the contact normal jumped at every node); the C2 spline with the exact c'' Jacobian keeps
    Newton converging: the cycle completes and most steps are accepted at the first try."""
    angles = np.radians(np.arange(96) * 3.75)
    profile = ClearanceProfile(angles, np.array(WORN_CLEARANCE_UM) * 1e-6)
    config = load_config(None, SECTIONS)
    history, summary = simulate_slider_crank(config, rod="flexible", joint="clearance", cycles=1,
                                             settling_cycles=1, clearance_profile=profile)
    assert summary.rejected_steps < 0.5 * summary.steps
    assert history.normal_force_N.max() > 0.0


def _undamped_rod_on_the_pocket_it_wore(**integrator):
    """One settling and one recorded cycle of the undamped flexible rod (``rod_damping_s = 0``)
    as the wear loop's fourth block ran them: on the bore the loop had worn after 5,374 cycles,
    from the mechanism's state then (both stored from that run,
    ``data/undamped_rod_after_5374_cycles.npz``). Returns (simulate's result, the clearance
    profile, the dynamics inputs)."""
    from dataclasses import replace

    from fewear.mbd.slider_crank import MechanismState, dynamics_inputs_from_config, simulate
    from fewear.wear.state import WearState

    stored = np.load(Path(__file__).parent / "data" / "undamped_rod_after_5374_cycles.npz")
    config = load_config(None, SECTIONS)
    config["mechanism"].update(rod_density_kg_m3=2660.0, rod_damping_s=0.0)
    config["integrator"].update(integrator)
    inputs = dynamics_inputs_from_config(config)
    worn = replace(WearState.unworn(stored["angle_rad"]), depth_m=stored["depth_m"])
    profile = worn.clearance_profile(config["bushing"]["inner_radius_m"],
                                     config["pin"]["radius_m"])
    crank = replace(inputs.crank, rod="flexible", joint="clearance", settling_cycles=1,
                    recorded_cycles=1)
    start = MechanismState(float(stored["time_s"]), stored["q"], stored["qd"])
    inputs = replace(inputs, crank=crank, joint=replace(inputs.joint, profile=profile))
    return (lambda: simulate(inputs, start=start)), profile, inputs


def pocket_bottoms_rad(profile) -> np.ndarray:
    """The angles of the local maxima of c(theta) worn at least half as deep as the deepest."""
    c = profile.clearance_m
    peak = (c >= np.roll(c, 1)) & (c >= np.roll(c, -1))
    return profile.angle_rad[peak & (c - c.min() >= 0.5 * (c.max() - c.min()))]


def test_a_collapsed_step_size_reports_where_the_pin_was():
    """With min_step_s = 1e-9 s the undamped rod's steps collapse where its pin comes to rest in
    its slip under several kN in one of the two worn pockets (the Newton iterates cycle across
    the friction law's kink on the rod's end node): at t = 0.3924 s in the 184 deg pocket, or at
    t = 0.4155 s in the 354 deg one where OpenBLAS's FMA kernels round the LAPACK calls of this
    chaotic trajectory otherwise (measured on an AMD EPYC). The error carries the joint's
    state: the pin at a pocket's bottom (found here from the profile itself), pressed in
    elastically (a penetration > 0 and far below the clearance: no jam)."""
    from fewear.mbd.integrator import StepSizeCollapse

    run, profile, _ = _undamped_rod_on_the_pocket_it_wore(min_step_s=1e-9)
    with pytest.raises(StepSizeCollapse, match="clearance joint 0: penetration") as caught:
        run()
    (penetration_m, force_N, direction_rad), = caught.value.joints
    bottoms = pocket_bottoms_rad(profile)
    assert bottoms.size == 2  # the two pockets on the slide axis
    apart = np.abs(np.remainder(direction_rad - bottoms + math.pi, 2.0 * math.pi) - math.pi)
    assert apart.min() < math.radians(0.5)
    assert 0.0 < penetration_m < 0.1 * CLEARANCE_M and force_N > 1e3


def test_the_undamped_flexible_rod_runs_through_the_pocket_it_wore_with_shorter_steps():
    """[integrator] min_step_s = 1e-11 s, the remedy the wear loop's error names, carries the
    block of the test above (its smallest step measured 0.8e-9 s)."""
    run, _, inputs = _undamped_rod_on_the_pocket_it_wore(min_step_s=1e-11)
    history, summary, _ = run()
    assert history.time_s[-1] - history.time_s[0] == pytest.approx(inputs.crank.period_s)
    assert summary.smallest_step_s < 1e-9  # the block needed it
    assert history.normal_force_N.max() > 1e3  # the pocket under load, as in the loop's block
