"""The four-bar of fewear/mechanisms/four_bar.toml: Freudenstein's closed form, and the clear
errors of a crank that cannot turn (Grashof) and of links that cannot close."""

import math
from dataclasses import replace

import numpy as np
import pytest

from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.io.mechanism import EXAMPLES_DIR, dynamics_inputs, parse_mechanism, read_mechanism
from fewear.mbd.integrator import GeneralizedAlpha
from fewear.mbd.mechanism import MechanismModel, assemble, check_cycle
from fewear.mbd.slider_crank import SECTIONS

GROUND_M, CRANK_M, COUPLER_M, ROCKER_M = 0.30, 0.10, 0.25, 0.25


def freudenstein(theta2, a=CRANK_M, b=COUPLER_M, c=ROCKER_M, d=GROUND_M):
    """Coupler and rocker angles (theta3, theta4) of the branch with the coupler-rocker joint
    above the ground line, from the loop closure a e^{i theta2} + b e^{i theta3} = d +
    c e^{i theta4}: eliminating theta3 gives Freudenstein's equation
    K1 cos theta4 - K2 cos theta2 + K3 = cos(theta2 - theta4), K1 = d/a, K2 = d/c,
    K3 = (a^2 - b^2 + c^2 + d^2) / (2 a c), i.e. A cos theta4 + B sin theta4 = C with
    A = K1 - (1 + K2) cos theta2 + K3 ... solved by the half-angle tangent."""
    k1, k2, k3 = d / a, d / c, (a * a - b * b + c * c + d * d) / (2 * a * c)
    # (K1 - cos theta2) cos theta4 - sin theta2 sin theta4 = K2 cos theta2 - K3
    p, q, r = k1 - np.cos(theta2), -np.sin(theta2), k2 * np.cos(theta2) - k3
    # p cos + q sin = r with t = tan(theta4 / 2): (r + p) t^2 - 2 q t + (r - p) = 0
    roots = [(q + sign * np.sqrt(q * q - (r + p) * (r - p))) / (r + p) for sign in (1, -1)]
    theta4 = [2 * np.arctan(t) for t in roots]
    y_b = [c * np.sin(t) for t in theta4]
    theta4 = np.where(y_b[0] > 0, theta4[0], theta4[1])
    bx = d + c * np.cos(theta4) - a * np.cos(theta2)
    by = c * np.sin(theta4) - a * np.sin(theta2)
    return np.arctan2(by, bx), theta4


def four_bar_text(**replacements):
    text = (EXAMPLES_DIR / "four_bar.toml").read_text()
    for old, new in replacements.items():
        assert old in text
        text = text.replace(old, new)
    return text


def test_ideal_four_bar_follows_freudenstein():
    """Positions satisfy the constraints at every step: with Newton converged to 1e-13, the
    coupler and rocker angles equal the closed form's to 1e-9 of a link length."""
    config = load_config(None, SECTIONS)
    config["mechanism"]["file"] = "four_bar"
    inputs = dynamics_inputs(config, "rigid")
    model = MechanismModel(inputs.mechanism, inputs.joints, ideal_joints=True)
    settings = replace(inputs.integrator, newton_tolerance=1e-13, modified_newton=False)
    integrator = GeneralizedAlpha(model.system, settings)
    state = integrator.initial_state(*model.initial_conditions())
    _, path = integrator.run_recorded(state, inputs.period_s)
    crank = path.q[:, model.first["crank"] + 2]
    assert crank[-1] == pytest.approx(2 * math.pi, rel=1e-12)
    theta3, theta4 = freudenstein(crank)
    coupler = path.q[:, model.first["coupler"] + 2]
    rocker = path.q[:, model.first["rocker"] + 2]
    wrap = lambda angle: (angle + math.pi) % (2 * math.pi) - math.pi  # noqa: E731
    assert np.max(np.abs(wrap(coupler - theta3))) * COUPLER_M < 1e-9 * COUPLER_M
    assert np.max(np.abs(wrap(rocker - theta4))) * ROCKER_M < 1e-9 * ROCKER_M
    # and the rocker really rocks: between its two extreme positions, not a full turn
    assert np.ptp(rocker) < math.pi


def test_assembly_corrects_the_approximate_poses_onto_the_upper_branch():
    mechanism = read_mechanism(EXAMPLES_DIR / "four_bar.toml")[0]
    q, qd = assemble(mechanism)
    theta3, theta4 = freudenstein(np.array([0.0]))
    assert q[5] == pytest.approx(theta3[0], abs=1e-12) and q[8] == pytest.approx(theta4[0],
                                                                                 abs=1e-12)
    assert qd[2] == pytest.approx(1200 * math.pi / 30)


def test_crank_against_grashof_is_refused_with_the_joint_and_angle():
    """Rocker 0.10 m: s + l = 0.10 + 0.30 > p + q = 0.10 + 0.25 (Grashof violated); it assembles
    at crank angle 0 but the coupler cannot reach the rocker near 180 degrees."""
    text = four_bar_text(**{
        'position_m = [0.25, 0.115]\nangle_deg = 113.6\npoints = { O4 = [-0.125, 0.0], '
        'B = [0.125, 0.0] }': 'position_m = [0.316, 0.0475]\nangle_deg = 71.8\npoints = '
        '{ O4 = [-0.05, 0.0], B = [0.05, 0.0] }',
        'name = "rocker"\nlength_m = 0.25': 'name = "rocker"\nlength_m = 0.10',
        'position_m = [0.15, 0.115]\nangle_deg = 66.4': 'position_m = [0.216, 0.0475]\n'
        'angle_deg = 22.3'})
    import tomllib

    mechanism = parse_mechanism(tomllib.loads(text), "short_rocker.toml")[0]
    assemble(mechanism)  # closes at t = 0
    with pytest.raises(FewearInputError, match=r"driver of 'crank' cannot turn a full cycle.*"
                                               r"joint '(crank_coupler|coupler_rocker|"
                                               r"rocker_ground)' cannot close.*Grashof") as error:
        check_cycle(mechanism)
    angle = float(str(error.value).split("at its angle ")[1].split(" deg")[0])
    # the coupler reaches no further than b + c = 0.35 m from O4: |A - O4| > 0.35 m from here on
    first = math.degrees(math.acos((CRANK_M**2 + GROUND_M**2 - 0.35**2) / (2 * CRANK_M
                                                                             * GROUND_M)))
    assert first - 3.0 <= angle <= first + 3.0
    assert "\n" not in str(error.value)


def test_links_that_cannot_close_name_a_joint():
    """Rocker 0.05 m, coupler 0.10 m: b + c = 0.15 m < |A - O4| = 0.20 m at crank angle 0."""
    text = four_bar_text(**{
        'name = "rocker"\nlength_m = 0.25': 'name = "rocker"\nlength_m = 0.05',
        'points = { O4 = [-0.125, 0.0], B = [0.125, 0.0] }':
            'points = { O4 = [-0.025, 0.0], B = [0.025, 0.0] }',
        'name = "coupler"\nmodel = "rigid"\nlength_m = 0.25':
            'name = "coupler"\nmodel = "rigid"\nlength_m = 0.10',
        'points = { A = [-0.125, 0.0], B = [0.125, 0.0] }':
            'points = { A = [-0.05, 0.0], B = [0.05, 0.0] }'})
    import tomllib

    mechanism = parse_mechanism(tomllib.loads(text), "short_links.toml")[0]
    with pytest.raises(FewearInputError, match=r"mechanism .four_bar.: the bodies cannot be "
                                               r"assembled.*joint '(crank_coupler|coupler_rocker"
                                               r"|rocker_ground)' stays open"):
        assemble(mechanism)
