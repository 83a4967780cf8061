"""General mechanisms in motion: energy of an undamped double pendulum and of a pendulum hanging in
an elastic clearance joint, a tabulated driver's angle, velocity and acceleration, and a fixed
joint that welds two bars into one."""

import math
import tomllib

import numpy as np
import pytest
from scipy.interpolate import CubicSpline

from fewear.io.mechanism import parse_mechanism
from fewear.mbd.contact import (
    ClearanceProfile,
    ContactLaw,
    Friction,
    lankarani_nikravesh_stiffness,
)
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings
from fewear.mbd.mechanism import JointModel, MechanismModel

STEEL_BAR = 'density_kg_m3 = 7800.0\nheight_m = 0.005\nwidth_m = 0.018\n'
GROUND = '[ground]\npoints = { O = [0.0, 0.0] }\n'


def bar(name, length, position, angle_deg=0.0, points=None):
    points = points or {"A": -length / 2, "B": length / 2}
    listed = ", ".join(f"{key} = [{x!r}, 0.0]" for key, x in points.items())
    return (f'[[bodies]]\nname = "{name}"\nlength_m = {length!r}\n{STEEL_BAR}'
            f'position_m = [{position[0]!r}, {position[1]!r}]\nangle_deg = {angle_deg!r}\n'
            f'points = {{ {listed} }}\n')


def joint(name, kind, first, second, extra=""):
    if kind == "revolute":
        where = f'pin_point = "{first}"\nbushing_point = "{second}"\n'
    else:
        where = f'points = ["{first}", "{second}"]\n'
    return f'[[joints]]\nname = "{name}"\ntype = "{kind}"\n{where}{extra}'


def mechanism(text):
    return parse_mechanism(tomllib.loads(text), "test.toml")[0]


def run(model, settings, end_s, q=None, qd=None):
    integrator = GeneralizedAlpha(model.system, settings)
    if q is None:
        q, qd = model.initial_conditions()
    state = integrator.initial_state(q, qd)
    return state, integrator.run_recorded(state, end_s)[1]


def energy(model, path):
    system = model.system
    return np.array([system.kinetic_energy(qd) + system.gravity_potential(q)
                     for q, qd in zip(path.q, path.qd)])


def test_double_pendulum_energy_error_falls_with_the_step_squared():
    """Released from horizontal, undriven, undamped; generalized-alpha with rho_inf = 1 (no
    numerical dissipation) keeps the energy to an error of order h^2."""
    double = mechanism(GROUND + bar("upper", 0.25, (0.125, 0.0)) + bar("lower", 0.25, (0.375, 0.0))
                       + joint("shoulder", "revolute", "upper.A", "ground.O")
                       + joint("elbow", "revolute", "lower.A", "upper.B"))
    errors = []
    for step in (4e-4, 2e-4, 1e-4):
        model = MechanismModel(double, {})
        settings = IntegratorSettings(rho_inf=1.0, step_s=step, min_step_s=step, adaptive=False,
                                      newton_tolerance=1e-12)
        state, path = run(model, settings, 0.5)
        assert np.allclose(state.qd, 0.0)  # assembled at rest
        errors.append(np.max(np.abs(energy(model, path) - energy(model, path)[:1])))
    swing = 2 * 0.702 * 0.25 * 9.81 * 0.25  # the energy scale m g L of the two bars
    assert errors[0] < 1e-4 * swing
    for coarse, fine in zip(errors, errors[1:]):
        assert 3.0 < coarse / fine < 5.0


def test_pendulum_in_an_elastic_clearance_joint_keeps_its_energy():
    """A bar hanging in a clearance joint (bushing on the ground), released at 40 degrees with the
    pin on the bore: Hunt-Crossley with c_e = 1 has no hysteresis, no friction, so the contact is
    conservative (potential K delta^2.5 / 2.5) and, the pin staying in contact, the energy is kept
    to the integrator's error."""
    angle = math.radians(-50.0)
    text = (GROUND + bar("bar", 0.25, (0.125 * math.cos(angle), 0.125 * math.sin(angle)), -50.0,
                         {"O": -0.125})
            + joint("pivot", "revolute", "bar.O", "ground.O", "clearance = true\n"))
    stiffness = lankarani_nikravesh_stiffness(0.0095, 0.010, 207e9, 0.27, 90e9, 0.32)
    law = ContactLaw("hunt-crossley", stiffness, restitution=1.0)
    joints = {"pivot": JointModel(0.0095, 0.010, ClearanceProfile.constant(5e-4), law,
                                  Friction(0.0))}
    model = MechanismModel(mechanism(text), joints)
    q, qd = model.initial_conditions()
    q[1] -= 5e-4  # the pin down onto the bore
    settings = IntegratorSettings(rho_inf=1.0, step_s=2e-5, min_step_s=2e-5, adaptive=False,
                                  newton_tolerance=1e-12)
    _, path = run(model, settings, 0.1, q, qd)
    measures = model.measure(path)["pivot"]
    assert np.all(measures["normal_force_N"] > 0.0)  # persistent contact
    total = energy(model, path) + stiffness * measures["penetration_m"] ** 2.5 / 2.5
    kinetic = max(model.system.kinetic_energy(qd) for qd in path.qd)
    assert kinetic > 0.01  # it swings
    assert np.max(np.abs(total - total[0])) < 1e-6 * kinetic


def test_tabulated_driver_follows_its_spline_with_its_rates():
    """A bar pinned at its centre, its angle driven by a table of 30 sin(2 pi t / T + 1)
    degrees: the angle is the periodic spline's, the velocity its derivative (Phi_t) and the
    start's acceleration its second derivative (Phi_tt)."""
    period, samples = 0.1, 24
    times = np.linspace(0.0, period, samples + 1)
    angles = 30.0 * np.sin(2 * math.pi * times / period + 1.0)
    angles[-1] = angles[0]
    text = (GROUND + bar("bar", 0.2, (0.0, 0.0), points={"C": 0.0})
            + joint("pivot", "revolute", "bar.C", "ground.O")
            + f'[[drivers]]\nbody = "bar"\ntime_s = {times.tolist()}\n'
              f'angle_deg = {angles.tolist()}\n')
    model = MechanismModel(mechanism(text), {})
    settings = IntegratorSettings(rho_inf=0.5, step_s=1e-4, min_step_s=1e-4, adaptive=False,
                                  newton_tolerance=1e-12)
    state, path = run(model, settings, 1.5 * period)
    spline = CubicSpline(times, np.radians(angles), bc_type="periodic")
    wrapped = path.time_s % period
    np.testing.assert_allclose(path.q[:, 2], spline(wrapped), atol=1e-11)
    np.testing.assert_allclose(path.qd[:, 2], spline(wrapped, 1), rtol=1e-9, atol=1e-9)
    assert state.qd[2] == pytest.approx(spline(0.0, 1), rel=1e-12)
    assert state.qdd[2] == pytest.approx(spline(0.0, 2), rel=1e-9)


def test_fixed_joint_welds_two_bars_into_one():
    """Two 0.2 m bars welded end to end swing as one 0.4 m bar."""
    welded = mechanism(GROUND + bar("inner", 0.2, (0.1, 0.0)) + bar("outer", 0.2, (0.3, 0.0))
                       + joint("pivot", "revolute", "inner.A", "ground.O")
                       + joint("weld", "fixed", "inner.B", "outer.A"))
    single = mechanism(GROUND + bar("whole", 0.4, (0.2, 0.0))
                       + joint("pivot", "revolute", "whole.A", "ground.O"))
    settings = IntegratorSettings(rho_inf=1.0, step_s=1e-4, min_step_s=1e-4, adaptive=False,
                                  newton_tolerance=1e-12)
    welded_model, single_model = MechanismModel(welded, {}), MechanismModel(single, {})
    _, two = run(welded_model, settings, 0.3)
    _, one = run(single_model, settings, 0.3)
    np.testing.assert_allclose(two.q[:, 2], one.q[:, 2], atol=1e-9)
    np.testing.assert_allclose(two.q[:, 5], one.q[:, 2], atol=1e-9)
    assert np.ptp(one.q[:, 2]) > 1.0  # it swung


def test_block_slides_down_an_inclined_prismatic_joint():
    """A block on a frictionless line at 30 degrees through (0.1, 0.05), its point u = (0.05,
    0.02) on the line, its angle held at 10 degrees: from rest it moves s = -g sin(30) t^2 / 2
    along the line (constant acceleration, which the scheme integrates exactly)."""
    direction = (math.cos(math.radians(30.0)), math.sin(math.radians(30.0)))
    angle = math.radians(10.0)
    u = np.array([0.05, 0.02])
    turned = np.array([[math.cos(angle), -math.sin(angle)], [math.sin(angle), math.cos(angle)]])
    start = np.array([0.1, 0.05]) + 0.02 * np.array(direction) - turned @ u
    text = ('[ground]\npoints = { P = [0.1, 0.05] }\n[[bodies]]\nname = "block"\nmass_kg = 2.0\n'
            f'inertia_kg_m2 = 1e-3\nposition_m = [{start[0]!r}, {start[1] + 0.003!r}]\n'
            f'angle_deg = 10.0\npoints = {{ C = [0.05, 0.02] }}\n'
            + joint("slide", "prismatic", "ground.P", "block.C",
                    f"direction = [{direction[0]!r}, {direction[1]!r}]\n"))
    model = MechanismModel(mechanism(text), {})
    settings = IntegratorSettings(rho_inf=0.8, step_s=1e-3, min_step_s=1e-3, adaptive=False,
                                  newton_tolerance=1e-13)
    state, path = run(model, settings, 0.2)
    normal = np.array([-direction[1], direction[0]])
    start = start + np.array([0.0, 0.003]) - normal * normal[1] * 0.003  # the nearest on the line
    np.testing.assert_allclose(state.q, [*start, angle], atol=1e-12)  # assembled onto the line
    travel = -9.81 * 0.5 * path.time_s**2 / 2
    np.testing.assert_allclose(path.q[:, :2], start + np.outer(travel, direction), atol=1e-12)
    np.testing.assert_allclose(path.q[:, 2], angle, atol=1e-13)


def test_clearance_profile_and_history_are_in_the_rotating_bushing_frame():
    """A bar hangs (angle -90 degrees) with its bushing on a pin fixed to the ground; the worn
    profile c(theta) = 0.3, 0.5, 0.7, 0.5 mm at 0, 90, 180, 270 degrees of the BAR's frame. The
    pin touches the bore on the bar's -x side (globally above the bore centre), where c = 0.7 mm:
    at rest the eccentricity in the bar's frame is (-(0.7 mm + delta), 0), delta = (m g / K)^(2/3)
    the static penetration, and the force on the pin (m g, 0) points along the bar. Read in the
    global frame the profile would give 0.5 mm there, and the bar would fall by 0.2 mm."""
    length = 0.25
    text = (GROUND + bar("bar", length, (0.0, -length / 2), -90.0, {"O": -length / 2})
            + joint("hang", "revolute", "ground.O", "bar.O", "clearance = true\n"))
    stiffness = lankarani_nikravesh_stiffness(0.0095, 0.010, 207e9, 0.27, 90e9, 0.32)
    profile = ClearanceProfile(np.radians([0.0, 90.0, 180.0, 270.0]),
                               np.array([0.3e-3, 0.5e-3, 0.7e-3, 0.5e-3]))
    joints = {"hang": JointModel(0.0095, 0.010, profile,
                                 ContactLaw("hunt-crossley", stiffness, restitution=0.5),
                                 Friction(0.0))}
    model = MechanismModel(mechanism(text), joints)
    weight = 0.702 * length * 9.81
    eccentricity = 0.7e-3 + (weight / stiffness) ** (2.0 / 3.0)
    q = np.array([0.0, -eccentricity - length / 2, -math.pi / 2])
    settings = IntegratorSettings(rho_inf=0.5, step_s=1e-5, min_step_s=1e-5, adaptive=False,
                                  newton_tolerance=1e-13)
    _, path = run(model, settings, 0.02, q, np.zeros(3))
    measures = model.measure(path)["hang"]
    np.testing.assert_allclose(measures["eccentricity_m"][:, 0], -eccentricity, atol=1e-9)
    np.testing.assert_allclose(measures["eccentricity_m"][:, 1], 0.0, atol=1e-9)
    np.testing.assert_allclose(measures["reaction_force_N"][:, 0], weight, rtol=1e-6)
    np.testing.assert_allclose(measures["reaction_force_N"][:, 1], 0.0, atol=1e-6 * weight)


@pytest.mark.parametrize("points", [("ground.O", "bar.A"), ("bar.A", "ground.O")])
def test_body_fixed_to_the_ground_stays(points):
    """A bar welded to the ground at one end (either way round) does not move under gravity."""
    text = (GROUND + bar("bar", 0.2, (0.1, 0.0), 20.0) + joint("weld", "fixed", *points))
    model = MechanismModel(mechanism(text), {})
    settings = IntegratorSettings(rho_inf=0.8, step_s=1e-3, min_step_s=1e-3, adaptive=False,
                                  newton_tolerance=1e-13)
    state, path = run(model, settings, 0.05)
    angle = math.radians(20.0)
    expected = [0.1 * math.cos(angle), 0.1 * math.sin(angle), angle]  # assembled about O
    np.testing.assert_allclose(path.q, np.tile(expected, (path.q.shape[0], 1)), atol=1e-12)
