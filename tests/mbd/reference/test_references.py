"""Checks of the independent four-bar references: loop closure, derivatives against finite
differences, link equilibrium, the energy balance, and Exudyn against the inverse dynamics."""

import math

import numpy as np
import pytest

from tests.mbd.reference import freudenstein as fr

PARAMS = fr.FourBar()


def _cycle_times(n=721):
    return np.linspace(0.0, PARAMS.period_s(), n)


def test_grashof_cases():
    assert fr.grashof(PARAMS) == {"case": "crank-rocker", "grashof": True,
                                  "crank_turns_fully": True}
    assert fr.grashof(fr.FourBar(ground_m=0.05))["case"] == "double-crank"
    assert fr.grashof(fr.FourBar(coupler_m=0.05, crank_m=0.2))["case"] == "double-rocker"
    non_grashof = fr.grashof(fr.FourBar(crank_m=0.2, coupler_m=0.4, rocker_m=0.12))
    assert non_grashof == {"case": "triple-rocker", "grashof": False, "crank_turns_fully": False}


def test_loop_closes_on_the_upper_branch():
    kin = fr.kinematics(PARAMS, _cycle_times())
    a, b, c, d = PARAMS.crank_m, PARAMS.coupler_m, PARAMS.rocker_m, PARAMS.ground_m
    closure_x = (a * np.cos(kin["theta2"]) + b * np.cos(kin["theta3"])
                 - c * np.cos(kin["theta4"]) - d)
    closure_y = a * np.sin(kin["theta2"]) + b * np.sin(kin["theta3"]) - c * np.sin(kin["theta4"])
    assert np.max(np.abs(closure_x)) < 1e-12 and np.max(np.abs(closure_y)) < 1e-12
    assert np.min(c * np.sin(kin["theta4"])) > 0.0  # y_B > 0 over the whole turn


def test_derivatives_match_central_differences():
    times = _cycle_times(97)[:-1]
    h = 1e-6 * PARAMS.period_s()
    kin = fr.kinematics(PARAMS, times)
    plus, minus = fr.kinematics(PARAMS, times + h), fr.kinematics(PARAMS, times - h)
    for link in "34":
        rate = np.unwrap(np.stack([minus["theta" + link], plus["theta" + link]]), axis=0)
        finite_omega = (rate[1] - rate[0]) / (2 * h)
        finite_alpha = (plus["omega" + link] - minus["omega" + link]) / (2 * h)
        scale_omega = np.max(np.abs(kin["omega" + link]))
        scale_alpha = np.max(np.abs(kin["alpha" + link]))
        assert np.max(np.abs(finite_omega - kin["omega" + link])) < 1e-7 * scale_omega
        assert np.max(np.abs(finite_alpha - kin["alpha" + link])) < 1e-7 * scale_alpha


def test_each_link_is_in_dynamic_equilibrium():
    """Newton-Euler residuals of every link, and the whole mechanism's momentum balance (the ground
    forces alone carry the weight and the centres' accelerations)."""
    result = fr.inverse_dynamics(PARAMS, _cycle_times())
    points = fr.centre_kinematics(PARAMS, result)
    masses, inertias = PARAMS.masses_kg(), PARAMS.inertias_kg_m2()
    weight = np.array([0.0, -PARAMS.gravity_m_s2])
    f_o2, f_a, f_b, f_o4 = (result[f"force_{j}"] for j in ("O2", "A", "B", "O4"))
    origin = np.zeros_like(f_a)
    links = [
        ("G2", [(f_o2, origin), (-f_a, points["A"][0])], result["torque_crank"], "2"),
        ("G3", [(f_a, points["A"][0]), (-f_b, points["B"][0])], 0.0, "3"),
        ("G4", [(f_b, points["B"][0]), (f_o4, points["O4"][0])], 0.0, "4"),
    ]
    scale = np.max(np.linalg.norm(f_a, axis=1))
    for k, (centre, loads, torque, link) in enumerate(links):
        position, _, acceleration = points[centre]
        force = sum(f for f, _ in loads) + masses[k] * weight - masses[k] * acceleration
        moment = (sum(fr._cross(where - position, f) for f, where in loads) + torque
                  - inertias[k] * result["alpha" + link])
        assert np.max(np.abs(force)) < 1e-10 * scale
        assert np.max(np.abs(moment)) < 1e-10 * scale * PARAMS.coupler_m
    momentum_rate = sum(masses[k] * points[g][2] for k, g in enumerate(("G2", "G3", "G4")))
    external = f_o2 + f_o4 + masses.sum() * weight
    assert np.max(np.abs(external - momentum_rate)) < 1e-10 * scale


def test_driving_power_equals_the_energy_rate():
    """T w2 = d/dt (kinetic + potential): against the kinematic energy rate and against the
    central difference of the energy, and the cycle's net work is zero."""
    times = _cycle_times(2001)
    result = fr.inverse_dynamics(PARAMS, times)
    power = result["torque_crank"] * PARAMS.crank_speed_rad_s
    scale = np.max(np.abs(power))
    assert np.max(np.abs(power - fr.mechanical_energy_rate_W(PARAMS, times))) < 1e-10 * scale
    h = 1e-6 * PARAMS.period_s()
    energy_difference = (fr.mechanical_energy_J(PARAMS, times + h)
                         - fr.mechanical_energy_J(PARAMS, times - h)) / (2 * h)
    assert np.max(np.abs(power - energy_difference)) < 1e-6 * scale
    work = np.trapz(power, times)
    assert abs(work) < 1e-6 * scale * PARAMS.period_s()


def test_static_limit_matches_virtual_work():
    """At vanishing speed the driving torque holds the weight: T = sum m_i g dy_Gi/dtheta2, with
    dy/dtheta2 by central differences of the closed-form positions."""
    slow = fr.FourBar(crank_speed_rad_s=1e-6)
    theta2 = np.linspace(0.0, 2 * math.pi, 73)
    times = theta2 / slow.crank_speed_rad_s
    torque = fr.inverse_dynamics(slow, times)["torque_crank"]

    def centre_heights(angle):
        theta3, theta4 = fr.positions(slow, angle)
        a, b, c = slow.crank_m, slow.coupler_m, slow.rocker_m
        return np.stack([a / 2 * np.sin(angle), a * np.sin(angle) + b / 2 * np.sin(theta3),
                         c / 2 * np.sin(theta4)])

    dtheta = 1e-6
    slope = (centre_heights(theta2 + dtheta) - centre_heights(theta2 - dtheta)) / (2 * dtheta)
    expected = slow.gravity_m_s2 * slow.masses_kg() @ slope
    assert np.max(np.abs(torque - expected)) < 1e-7 * np.max(np.abs(expected))


def _exudyn():
    return pytest.importorskip("exudyn", reason="Exudyn (PyPI) is not installed")


def test_exudyn_rigid_four_bar_matches_the_inverse_dynamics():
    """Exudyn's ideal rigid four-bar after one settling turn against the closed form and the
    Newton-Euler inverse dynamics: angles to 1e-9 rad, every joint force and the driving torque
    to 1e-4 of the peak joint force (of the torque)."""
    _exudyn()
    from tests.mbd.reference.exudyn_four_bar import four_bar_cycle

    result = four_bar_cycle("rigid", cycles_settle=1, step_s=2e-5)
    reference = fr.inverse_dynamics(PARAMS, result["time_s"])
    assert result["time_s"][-1] - result["time_s"][0] == pytest.approx(PARAMS.period_s())
    for angle in ("theta2", "theta3", "theta4"):
        assert np.max(np.abs(result[angle] - reference[angle])) < 1e-9
    peak = max(np.max(np.linalg.norm(reference[f"force_{j}"], axis=1))
               for j in ("O2", "A", "B", "O4"))
    for joint in ("O2", "A", "B", "O4"):
        error = np.max(np.abs(result[f"force_{joint}"] - reference[f"force_{joint}"]))
        assert error < 1e-4 * peak, joint
    torque_error = np.max(np.abs(result["torque_crank"] - reference["torque_crank"]))
    assert torque_error < 1e-4 * np.max(np.abs(reference["torque_crank"]))


def _peak_joint_force(reference):
    return max(np.max(np.linalg.norm(reference[f"force_{j}"], axis=1))
               for j in ("O2", "A", "B", "O4"))


def test_exudyn_cable_coupler_follows_the_rigid_mechanism_on_average():
    """The stiff elastic coupler (ANCF cable) keeps the angles within 1e-3 rad of the rigid closed
    form, and its undamped vibration averages out: each joint force's mean over two turns is the
    rigid mechanism's to 2e-3 of the peak joint force."""
    _exudyn()
    from tests.mbd.reference.exudyn_four_bar import four_bar_cycle

    result = four_bar_cycle("cable", cycles_settle=2, cycles_record=2, step_s=1e-5)
    reference = fr.inverse_dynamics(PARAMS, result["time_s"])
    for angle in ("theta2", "theta3", "theta4"):
        assert np.max(np.abs(result[angle] - reference[angle])) < 1e-3
    peak = _peak_joint_force(reference)
    for joint in ("O2", "A", "B", "O4"):
        mean_error = np.mean(result[f"force_{joint}"][:-1] - reference[f"force_{joint}"][:-1],
                             axis=0)
        assert np.linalg.norm(mean_error) < 2e-3 * peak, joint


@pytest.mark.slow
def test_exudyn_clearance_joint_tends_to_the_ideal_joint():
    """With a 1 um clearance the pin stays in contact nearly all the turn, the contact force pushes
    the bushing outward (force_B along e, never adhesive), and the joint forces approach the ideal
    mechanism's: rms difference below 3 % of the peak, turn means to 1e-3 of it."""
    _exudyn()
    from tests.mbd.reference.exudyn_four_bar import ClearanceJoint, four_bar_cycle

    joint = ClearanceJoint(pin_radius_m=10e-3 - 1e-6)
    result = four_bar_cycle("clearance", cycles_settle=1, cycles_record=1, step_s=2e-6,
                            clearance=joint)
    reference = fr.inverse_dynamics(PARAMS, result["time_s"])
    assert np.mean(result["penetration_m"] > 0) > 0.95
    assert np.min(result["contact_force_N"]) >= 0.0
    along_e = np.linalg.norm(result["force_B"], axis=1)
    assert np.allclose(result["contact_force_N"], along_e, rtol=1e-9, atol=1e-9)
    peak = _peak_joint_force(reference)
    for name in ("O2", "A", "B", "O4"):
        difference = result[f"force_{name}"][:-1] - reference[f"force_{name}"][:-1]
        assert np.sqrt(np.mean(np.sum(difference**2, axis=1))) < 0.03 * peak, name
        assert np.linalg.norm(np.mean(difference, axis=0)) < 1e-3 * peak, name


def test_clearance_cycle_statistics_count_a_known_signal():
    """Two turns of 10 samples: contact in samples 2-4 and 7 of the first turn (two impacts, share
    0.4, peak 5 N), in 12-19 of the second (one impact, share 0.8, peak 9 N)."""
    from tests.mbd.reference.exudyn_four_bar import clearance_cycle_statistics

    time_s = np.arange(21) * 0.1
    in_contact = np.zeros(21, dtype=bool)
    in_contact[[2, 3, 4, 7]] = True
    in_contact[12:20] = True
    force = np.where(in_contact, 1.0, 0.0)
    force[3], force[15] = 5.0, 9.0
    result = {"time_s": time_s, "penetration_m": np.where(in_contact, 1e-6, -1e-6),
              "contact_force_N": force}
    stats = clearance_cycle_statistics(result, period_s=1.0)
    assert np.allclose(stats["contact_share"], [0.4, 0.8])
    assert np.allclose(stats["peak_force_N"], [5.0, 9.0])
    assert list(stats["impacts"]) == [2, 1]


def test_contact_stiffness_and_friction_forces():
    """Lankarani-Nikravesh K of the steel pin in the brass bushing by hand; the friction's
    generalized forces are tangential, at most mu F_n, dissipative, and their power equals the
    friction force times the slip speed of the two contact points (moment arms right)."""
    from tests.mbd.reference.exudyn_four_bar import ClearanceJoint, generalized_friction_N

    joint = ClearanceJoint(friction_coefficient=0.1, friction_ramp_velocity_m_s=1e-2)
    h_pin = (1 - 0.27**2) / (math.pi * 207e9)
    h_bushing = (1 - 0.32**2) / (math.pi * 90e9)
    stiffness = 4 / (3 * math.pi * (h_pin + h_bushing)) * math.sqrt(9.5e-3 * 10e-3 / 0.5e-3)
    assert joint.stiffness_N_m15() == pytest.approx(stiffness, rel=1e-12)
    rng = np.random.default_rng(7)
    b, c = PARAMS.coupler_m, PARAMS.rocker_m
    in_contact = 0
    for _ in range(50):
        coupler = np.concatenate([rng.uniform(-0.2, 0.2, 2), rng.uniform(-3, 3, 1),
                                  rng.uniform(-5, 5, 2), rng.uniform(-80, 80, 1)])
        rocker_angle, offset_angle = rng.uniform(-3, 3, 2)
        distance = joint.clearance_m() * (1 + rng.uniform(-0.005, 0.02))
        pin = coupler[:2] + b / 2 * np.array([math.cos(coupler[2]), math.sin(coupler[2])])
        normal = np.array([math.cos(offset_angle), math.sin(offset_angle)])
        rocker_centre = (pin - distance * normal
                         - c / 2 * np.array([math.cos(rocker_angle), math.sin(rocker_angle)]))
        rocker = np.concatenate([rocker_centre, [rocker_angle], rng.uniform(-5, 5, 2),
                                 rng.uniform(-80, 80, 1)])
        forces = generalized_friction_N(PARAMS, joint, coupler, rocker, 0.5)
        if distance <= joint.clearance_m():
            assert not forces.any()
            continue
        in_contact += 1
        tangent = np.array([-normal[1], normal[0]])
        slip = (_contact_point_velocity(coupler, b / 2, joint.pin_radius_m, normal)
                - _contact_point_velocity(rocker, c / 2, joint.bushing_radius_m, normal)
                ) @ tangent
        penetration = distance - joint.clearance_m()
        rate = (coupler[3:5] - rocker[3:5]
                + b / 2 * coupler[5] * np.array([-math.sin(coupler[2]), math.cos(coupler[2])])
                - c / 2 * rocker[5] * np.array([-math.sin(rocker_angle), math.cos(rocker_angle)])
                ) @ normal
        normal_force = max(stiffness * penetration**1.5
                           * (1 + 3 * (1 - 0.9**2) / 4 * rate / 0.5), 0.0)
        friction = forces[:2]
        assert abs(friction @ normal) < 1e-12 * (1 + np.linalg.norm(friction))
        assert np.linalg.norm(friction) <= 0.1 * normal_force * (1 + 1e-9)
        if abs(slip) > 1e-2:  # full sliding beyond the regularisation speed
            assert np.linalg.norm(friction) == pytest.approx(0.1 * normal_force, rel=1e-9)
        velocities = np.concatenate([coupler[3:], rocker[3:]])
        power = forces @ velocities
        assert power == pytest.approx((friction @ tangent) * slip, rel=1e-9, abs=1e-12)
        assert power <= 1e-12
    assert in_contact > 25


def _contact_point_velocity(state, half_length, radius, normal):
    """Velocity (m/s) of the point at radius * normal from the link end at half_length from the
    centre of a link with state (x, y, theta, vx, vy, omega)."""
    direction = np.array([math.cos(state[2]), math.sin(state[2])])
    arm = half_length * direction + radius * normal
    return state[3:5] + state[5] * np.array([-arm[1], arm[0]])
