"""fewear's four-bar (fewear/mechanisms/four_bar*.toml) against the independent references of
tests/mbd/reference: the rigid mechanism's inverse dynamics (closed form), Exudyn's rigid and
ANCF-cable four-bars, and Exudyn's clearance joint (statistics over crank turns).

Joint reactions of ideal joints come from the Lagrange multipliers. Generalized-alpha gives them
to second order in the step without the velocity projection ([integrator] project_velocities);
with it they are first order (the projected velocity is not the one the scheme's acceleration
update assumes), so these comparisons switch it off.
"""

from dataclasses import replace

import numpy as np
import pytest

from fewear.io.config import load_config
from fewear.io.mechanism import dynamics_inputs
from fewear.mbd.mechanism import simulate
from fewear.mbd.slider_crank import SECTIONS
from tests.mbd.reference.freudenstein import FourBar, inverse_dynamics


def in_frame(force_N: np.ndarray, angle_rad: np.ndarray) -> np.ndarray:
    """Global vectors (n, 2) expressed in a body frame turned by ``angle_rad`` (n,)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.stack([c * force_N[:, 0] + s * force_N[:, 1],
                     -s * force_N[:, 0] + c * force_N[:, 1]], axis=1)


def four_bar_histories(case: str, step_s: float, ideal: bool = True, settling: int = 1,
                       recorded: int = 1, rho_inf: float = 0.9):
    """fewear's two-clearance-joint four-bar (its joints ideal when ``ideal``; the flexible
    coupler undamped): the histories of crank_coupler (bushing on the crank, pin on the coupler)
    and coupler_rocker (bushing on the rocker), each in its bushing body's frame, on fixed steps
    of ``step_s``."""
    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = "four_bar_two_joints"
    inputs = dynamics_inputs(config, case)
    bodies = tuple(replace(body, bar=replace(body.bar, damping_s=0.0)) if body.bar else body
                   for body in inputs.mechanism.bodies)
    inputs = replace(inputs, mechanism=replace(inputs.mechanism, bodies=bodies))
    settings = replace(inputs.integrator, step_s=step_s, rho_inf=rho_inf, newton_tolerance=1e-12,
                       modified_newton=False, adaptive=False, project_velocities=False)
    inputs = replace(inputs, ideal_joints=ideal, settling_cycles=settling,
                     recorded_cycles=recorded, integrator=settings)
    return simulate(inputs)[0]


def reaction_errors(histories: dict, reference: dict) -> tuple[float, float]:
    """Largest difference of fewear's joint reactions from a reference's, over the peak of the
    reference's joint forces at A and B. The reference gives force_A (crank on coupler) and
    force_B (coupler on rocker) in the global frame; fewear the bushing's force on the pin in
    the bushing body's frame: at A the crank's force on the coupler in the crank's frame, at B
    the rocker's on the coupler, -force_B, in the rocker's frame."""
    peak = max(np.max(np.hypot(*reference[key].T)) for key in ("force_A", "force_B"))
    at_a = in_frame(reference["force_A"], reference["theta2"])
    at_b = in_frame(-reference["force_B"], reference["theta4"])
    error_a = np.max(np.abs(histories["crank_coupler"].reaction_force_N - at_a)) / peak
    error_b = np.max(np.abs(histories["coupler_rocker"].reaction_force_N - at_b)) / peak
    return error_a, error_b


def test_ideal_rigid_four_bar_reactions_match_the_inverse_dynamics_to_second_order():
    """The closed-form kinematics and Newton-Euler of the three links give the reactions at A and
    B; fewear's agree to 1e-4 of the peak joint force at 2e-5 s and the error falls about
    fourfold per halved step (second order)."""
    errors = []
    for step_s in (2e-5, 1e-5):
        histories = four_bar_histories("rigid", step_s)
        reference = inverse_dynamics(FourBar(), histories["coupler_rocker"].time_s)
        errors.append(max(reaction_errors(histories, reference)))
    assert errors[0] < 1e-4
    assert 3.0 < errors[0] / errors[1] < 5.0


def _exudyn():
    return pytest.importorskip("exudyn")


def test_ideal_rigid_four_bar_reactions_match_exudyn():
    """Exudyn's index-3 generalized-alpha on the same four-bar, the same step: the reactions at
    A and B agree to 1e-4 of the peak joint force."""
    _exudyn()
    from tests.mbd.reference.exudyn_four_bar import four_bar_cycle

    step_s = 2e-5
    histories = four_bar_histories("rigid", step_s)
    exudyn = four_bar_cycle("rigid", cycles_settle=1, step_s=step_s)
    time_s = histories["coupler_rocker"].time_s
    assert np.allclose(exudyn["time_s"], time_s, atol=1e-9)
    assert max(reaction_errors(histories, exudyn)) < 1e-4


def test_ancf_coupler_four_bar_matches_exudyn_cable_over_a_turn():
    """The coupler as 4 ANCF elements (fewear's shear-deformable beam, Exudyn's Euler-Bernoulli
    cable, both undamped here): the elastic coupler vibrates at its bending modes (about 180 Hz
    and 3.9 kHz, started by the rigid initial state and never damped), so instants depend on the
    step; over a crank turn the mean reactions agree to 5e-4 of the peak joint force, and the
    rocker's angle to 1e-4 rad."""
    _exudyn()
    from tests.mbd.reference.exudyn_four_bar import four_bar_cycle

    step_s = 1e-5
    histories = four_bar_histories("flexible", step_s)
    exudyn = four_bar_cycle("cable", cycles_settle=1, step_s=step_s)
    rigid = inverse_dynamics(FourBar(), exudyn["time_s"])
    peak = max(np.max(np.hypot(*rigid[key].T)) for key in ("force_A", "force_B"))
    for name, force, angle in (("crank_coupler", exudyn["force_A"], exudyn["theta2"]),
                               ("coupler_rocker", -exudyn["force_B"], exudyn["theta4"])):
        ours = histories[name]
        theirs = in_frame(force, angle)
        mean_ours = np.trapz(ours.reaction_force_N, ours.time_s, axis=0)
        mean_theirs = np.trapz(theirs, exudyn["time_s"], axis=0)
        period = exudyn["time_s"][-1] - exudyn["time_s"][0]
        assert np.max(np.abs(mean_ours - mean_theirs)) / period < 5e-4 * peak, name


@pytest.mark.slow
def test_clearance_joint_statistics_match_exudyn_within_their_spread():
    """Rigid four-bar, frictionless clearance at B (pin 9.5 mm in 10 mm, Lankarani-Nikravesh,
    restitution 0.9): the motion is chaotic from turn to turn, so the two engines are compared
    by their statistics over turns: contact share, peak force and impacts per turn, each
    fewear mean within two of Exudyn's turn-to-turn standard deviations of Exudyn's mean."""
    _exudyn()
    from tests.mbd.reference.exudyn_four_bar import clearance_cycle_statistics, four_bar_cycle

    turns = 10
    period_s = 60.0 / 1200.0
    exudyn = clearance_cycle_statistics(
        four_bar_cycle("clearance", cycles_settle=2, step_s=2e-6, cycles_record=turns), period_s)
    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = "four_bar"
    config["joint"]["friction_coefficient"] = 0.0
    inputs = replace(dynamics_inputs(config, "rigid"), settling_cycles=2, recorded_cycles=turns)
    history = simulate(inputs)[0]["coupler_rocker"]
    ours = per_turn_statistics(history, period_s, turns)
    for key in ours:
        mean, spread = np.mean(exudyn[key]), np.std(exudyn[key])
        assert abs(np.mean(ours[key]) - mean) < 2.0 * spread + 1e-12, (key, ours[key], mean)


def per_turn_statistics(history, period_s: float, turns: int) -> dict:
    """Exudyn's statistics (``clearance_cycle_statistics``) of a fewear history: per crank turn
    the share of time in contact (penetration > 0), the peak contact force and the impacts
    (free-flight -> contact onsets)."""
    phase = (history.time_s - history.time_s[0]) / period_s
    turn = np.minimum(np.floor(phase + 1e-9).astype(int), turns - 1)
    dwell = np.diff(history.time_s, prepend=history.time_s[0])
    in_contact = history.penetration_m > 0.0
    onset = np.zeros_like(in_contact)
    onset[1:] = ~in_contact[:-1] & in_contact[1:]
    return {
        "contact_share": np.array([dwell[(turn == k) & in_contact].sum() / dwell[turn == k].sum()
                                   for k in range(turns)]),
        "peak_force_N": np.array([history.normal_force_N[turn == k].max() for k in range(turns)]),
        "impacts": np.array([np.count_nonzero(onset[turn == k]) for k in range(turns)]),
    }
