"""Closed-form kinematics and rigid inverse dynamics of the planar four-bar (SI units).

Frame and angles: global x to the right, y up, gravity g along -y. Ground pivots O2 = (0, 0) and
O4 = (d, 0); crank O2-A of length a, coupler A-B of length b, rocker O4-B of length c. Link angles
are measured from +x counter-clockwise (rad): A = a e(theta2), B = A + b e(theta3),
B = O4 + c e(theta4), with e(t) = (cos t, sin t) and n(t) = (-sin t, cos t).

Position (loop closure a e2 + b e3 - c e4 - d ex = 0): with f = O4 - A, the triangle A-B-O4 gives
the angle at A, alpha = acos((b^2 + |f|^2 - c^2) / (2 b |f|)); the branch with B to the left of
the direction A -> O4 (B above the ground line for the crank-rocker used here) is
theta3 = atan2(f_y, f_x) + alpha, and theta4 = atan2(B_y, B_x - d).

Velocities and accelerations: the first and second time derivatives of the loop closure,
    b w3 n3 - c w4 n4 = -a w2 n2,
    b al3 n3 - c al4 n4 = -a al2 n2 + a w2^2 e2 + b w3^2 e3 - c w4^2 e4,
are 2x2 linear systems in (w3, w4) and (al3, al4) (rad/s, rad/s^2); at constant crank speed al2 = 0.

Inverse dynamics (Newton-Euler of the three uniform links, centres of mass at the midpoints):
joint forces are those exerted BY the joint's first body ON its second body, global frame (N):
    O2: ground -> crank,  A: crank -> coupler,  B: coupler -> rocker,  O4: ground -> rocker,
and T (N m) is the driving torque of the ground on the crank (counter-clockwise positive).
Per link i (mass m_i, centroidal inertia J_i, centre G_i): sum F = m_i a_Gi and
sum (r - G_i) x F + torques = J_i al_i, nine linear equations in nine unknowns per instant.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class FourBar:
    """The four-bar's geometry and drive (m, kg, rad/s). Default: the crank-rocker of the
    mechanism-file checks, uniform steel bars of 5 mm x 18 mm section (0.702 kg per metre)."""

    ground_m: float = 0.30  # d = |O2 O4|, O4 = (d, 0)
    crank_m: float = 0.10  # a
    coupler_m: float = 0.25  # b
    rocker_m: float = 0.25  # c
    mass_per_length_kg_m: float = 7800.0 * 0.005 * 0.018
    crank_speed_rad_s: float = 1200.0 * 2.0 * math.pi / 60.0
    initial_crank_angle_rad: float = 0.0
    gravity_m_s2: float = 9.81

    def link_lengths_m(self) -> np.ndarray:
        """(a, b, c) of crank, coupler and rocker."""
        return np.array([self.crank_m, self.coupler_m, self.rocker_m])

    def masses_kg(self) -> np.ndarray:
        """Masses of crank, coupler, rocker (uniform bars)."""
        return self.mass_per_length_kg_m * self.link_lengths_m()

    def inertias_kg_m2(self) -> np.ndarray:
        """Centroidal moments of inertia m L^2 / 12 of crank, coupler, rocker."""
        return self.masses_kg() * self.link_lengths_m() ** 2 / 12.0

    def period_s(self) -> float:
        """One crank revolution 2 pi / omega."""
        return 2.0 * math.pi / self.crank_speed_rad_s


def grashof(params: FourBar = FourBar()) -> dict:
    """Grashof classification of the linkage (crank a, coupler b, rocker c, ground d).

    With s and l the shortest and longest of (a, b, c, d) and p, q the others, the linkage is
    Grashof if s + l < p + q (change point if equal). Then: shortest is the ground -> double-crank,
    shortest adjacent to the ground -> crank-rocker (that link turns fully), shortest is the coupler
    -> double-rocker. Non-Grashof: triple-rocker, no link turns fully relative to the ground.
    Returns {"case": str, "grashof": bool, "crank_turns_fully": bool} where the last one tells
    whether the input crank (a) makes full turns.
    """
    lengths = {"ground": params.ground_m, "crank": params.crank_m,
               "coupler": params.coupler_m, "rocker": params.rocker_m}
    ordered = sorted(lengths.values())
    s_plus_l, p_plus_q = ordered[0] + ordered[3], ordered[1] + ordered[2]
    shortest = min(lengths, key=lengths.get)
    tolerance = 1e-12 * p_plus_q
    if abs(s_plus_l - p_plus_q) <= tolerance:
        return {"case": "change-point", "grashof": True,
                "crank_turns_fully": shortest in ("crank", "ground")}
    if s_plus_l > p_plus_q:
        return {"case": "triple-rocker", "grashof": False, "crank_turns_fully": False}
    case = {"ground": "double-crank", "crank": "crank-rocker", "rocker": "rocker-crank",
            "coupler": "double-rocker"}[shortest]
    return {"case": case, "grashof": True, "crank_turns_fully": shortest in ("crank", "ground")}


def crank_angle_rad(params: FourBar, time_s) -> np.ndarray:
    """theta2(t) = theta2(0) + omega t (rad)."""
    return params.initial_crank_angle_rad + params.crank_speed_rad_s * np.asarray(time_s, float)


def positions(params: FourBar, theta2_rad) -> tuple[np.ndarray, np.ndarray]:
    """Coupler and rocker angles theta3, theta4 (rad) at crank angles ``theta2_rad`` on the branch
    with B left of A -> O4 (module docstring). Raises ValueError where the loop cannot close."""
    theta2 = np.asarray(theta2_rad, dtype=float)
    a, b, c, d = params.crank_m, params.coupler_m, params.rocker_m, params.ground_m
    f_x, f_y = d - a * np.cos(theta2), -a * np.sin(theta2)
    f = np.hypot(f_x, f_y)
    cos_alpha = (b**2 + f**2 - c**2) / (2.0 * b * f)
    if np.any(np.abs(cos_alpha) > 1.0):
        raise ValueError("the four-bar cannot be assembled at some crank angle")
    theta3 = np.arctan2(f_y, f_x) + np.arccos(cos_alpha)
    b_x = a * np.cos(theta2) + b * np.cos(theta3)
    b_y = a * np.sin(theta2) + b * np.sin(theta3)
    theta4 = np.arctan2(b_y, b_x - d)
    return theta3, theta4


def velocities(params: FourBar, theta2_rad, theta3_rad, theta4_rad, omega2_rad_s):
    """Coupler and rocker angular velocities (rad/s) from the derivative of the loop closure:
    w3 = a w2 sin(t4 - t2) / (b sin(t3 - t4)), w4 = a w2 sin(t3 - t2) / (c sin(t3 - t4))."""
    t2, t3, t4 = (np.asarray(x, dtype=float) for x in (theta2_rad, theta3_rad, theta4_rad))
    a, b, c = params.crank_m, params.coupler_m, params.rocker_m
    denominator = np.sin(t3 - t4)
    omega3 = a * omega2_rad_s * np.sin(t4 - t2) / (b * denominator)
    omega4 = a * omega2_rad_s * np.sin(t3 - t2) / (c * denominator)
    return omega3, omega4


def accelerations(params: FourBar, theta2, theta3, theta4, omega2, omega3, omega4, alpha2=0.0):
    """Coupler and rocker angular accelerations (rad/s^2) from the second derivative of the loop
    closure (module docstring), solved by Cramer's rule on the 2x2 system in (al3, al4)."""
    t2, t3, t4 = (np.asarray(x, dtype=float) for x in (theta2, theta3, theta4))
    a, b, c = params.crank_m, params.coupler_m, params.rocker_m
    # right-hand side r = -a al2 n2 + a w2^2 e2 + b w3^2 e3 - c w4^2 e4
    r_x = (a * alpha2 * np.sin(t2) + a * omega2**2 * np.cos(t2) + b * omega3**2 * np.cos(t3)
           - c * omega4**2 * np.cos(t4))
    r_y = (-a * alpha2 * np.cos(t2) + a * omega2**2 * np.sin(t2) + b * omega3**2 * np.sin(t3)
           - c * omega4**2 * np.sin(t4))
    # columns: b n3 and -c n4
    m11, m21 = -b * np.sin(t3), b * np.cos(t3)
    m12, m22 = c * np.sin(t4), -c * np.cos(t4)
    determinant = m11 * m22 - m12 * m21
    alpha3 = (r_x * m22 - m12 * r_y) / determinant
    alpha4 = (m11 * r_y - m21 * r_x) / determinant
    return alpha3, alpha4


def kinematics(params: FourBar, time_s) -> dict:
    """Angles (rad), angular velocities (rad/s) and accelerations (rad/s^2) of the three links at
    ``time_s`` for constant crank speed; keys theta2..4, omega2..4, alpha2..4."""
    time_s = np.asarray(time_s, dtype=float)
    theta2 = crank_angle_rad(params, time_s)
    omega2 = np.full_like(theta2, params.crank_speed_rad_s)
    alpha2 = np.zeros_like(theta2)
    theta3, theta4 = positions(params, theta2)
    omega3, omega4 = velocities(params, theta2, theta3, theta4, omega2)
    alpha3, alpha4 = accelerations(params, theta2, theta3, theta4, omega2, omega3, omega4, alpha2)
    return {"theta2": theta2, "theta3": theta3, "theta4": theta4,
            "omega2": omega2, "omega3": omega3, "omega4": omega4,
            "alpha2": alpha2, "alpha3": alpha3, "alpha4": alpha4}


def _unit(angle):
    return np.stack([np.cos(angle), np.sin(angle)], axis=-1)


def _normal(angle):
    return np.stack([-np.sin(angle), np.cos(angle)], axis=-1)


def centre_kinematics(params: FourBar, kin: dict) -> dict:
    """Positions (m), velocities (m/s) and accelerations (m/s^2) of the link centres G2, G3, G4 and
    of the joints A, B, each an (n, 2) array. A point at distance s along a link from its start P
    moves as r = P + s e, r' = P' + s w n, r'' = P'' + s al n - s w^2 e."""
    a, b, c, d = params.crank_m, params.coupler_m, params.rocker_m, params.ground_m

    def along(start, start_v, start_a, length, theta, omega, alpha):
        e, n = _unit(theta), _normal(theta)
        w, al = omega[..., None], alpha[..., None]
        return (start + length * e, start_v + length * w * n,
                start_a + length * (al * n - w**2 * e))

    zero = np.zeros(np.shape(kin["theta2"]) + (2,))
    o4 = zero + np.array([d, 0.0])
    t2, t3, t4 = kin["theta2"], kin["theta3"], kin["theta4"]
    w2, w3, w4 = kin["omega2"], kin["omega3"], kin["omega4"]
    a2, a3, a4 = kin["alpha2"], kin["alpha3"], kin["alpha4"]
    joint_a = along(zero, zero, zero, a, t2, w2, a2)
    g2 = along(zero, zero, zero, a / 2, t2, w2, a2)
    g3 = along(*joint_a, b / 2, t3, w3, a3)
    joint_b = along(*joint_a, b, t3, w3, a3)
    g4 = along(o4, zero, zero, c / 2, t4, w4, a4)
    return {"A": joint_a, "B": joint_b, "G2": g2, "G3": g3, "G4": g4, "O4": (o4, zero, zero)}


def _cross(r, f):
    """z component of the planar cross product r x f for (..., 2) arrays."""
    return r[..., 0] * f[..., 1] - r[..., 1] * f[..., 0]


def inverse_dynamics(params: FourBar, time_s) -> dict:
    """Joint reaction forces (N, global frame) and driving torque (N m) of the ideal rigid four-bar
    at ``time_s`` (module docstring for the sign conventions).

    Unknowns per instant x = (F_O2, F_A, F_B, F_O4, T) (9); equations, per link, Newton
    (sum F = m a_G, with gravity m g (0, -1)) and Euler about the centre (sum M_G = J al):
        crank:   F_O2 - F_A + m2 g = m2 a_G2,   (O2-G2) x F_O2 - (A-G2) x F_A + T = J2 al2
        coupler: F_A - F_B + m3 g = m3 a_G3,    (A-G3) x F_A - (B-G3) x F_B = J3 al3
        rocker:  F_B + F_O4 + m4 g = m4 a_G4,   (B-G4) x F_B + (O4-G4) x F_O4 = J4 al4
    Returns a dict of arrays: time_s, the kinematics (theta2.., omega2.., alpha2..), and
    force_O2, force_A, force_B, force_O4 (n, 2), torque_crank (n,).
    """
    time_s = np.atleast_1d(np.asarray(time_s, dtype=float))
    kin = kinematics(params, time_s)
    points = centre_kinematics(params, kin)
    masses, inertias = params.masses_kg(), params.inertias_kg_m2()
    weight = np.array([0.0, -params.gravity_m_s2])
    n = time_s.size
    matrix = np.zeros((n, 9, 9))
    rhs = np.zeros((n, 9))
    o2 = np.zeros((n, 2))
    columns = {"O2": slice(0, 2), "A": slice(2, 4), "B": slice(4, 6), "O4": slice(6, 8)}
    # (link row offset, centre, [(joint, sign, point of application)], angular acceleration)
    links = [
        (0, "G2", [("O2", 1.0, o2), ("A", -1.0, points["A"][0])], kin["alpha2"]),
        (3, "G3", [("A", 1.0, points["A"][0]), ("B", -1.0, points["B"][0])], kin["alpha3"]),
        (6, "G4", [("B", 1.0, points["B"][0]), ("O4", 1.0, points["O4"][0])], kin["alpha4"]),
    ]
    for k, (row, centre, joints, alpha) in enumerate(links):
        g_pos, _, g_acc = points[centre]
        for joint, sign, where in joints:
            col = columns[joint]
            arm = where - g_pos
            matrix[:, row, col.start] = sign
            matrix[:, row + 1, col.start + 1] = sign
            matrix[:, row + 2, col.start] = -sign * arm[:, 1]  # (r x F)_z = r_x F_y - r_y F_x
            matrix[:, row + 2, col.start + 1] = sign * arm[:, 0]
        rhs[:, row:row + 2] = masses[k] * (g_acc - weight)
        rhs[:, row + 2] = inertias[k] * alpha
    matrix[:, 2, 8] = 1.0  # driving torque acts on the crank only
    solution = np.linalg.solve(matrix, rhs[..., None])[..., 0]
    result = {"time_s": time_s, **kin}
    for joint, col in columns.items():
        result[f"force_{joint}"] = solution[:, col]
    result["torque_crank"] = solution[:, 8]
    return result


def mechanical_energy_rate_W(params: FourBar, time_s) -> np.ndarray:
    """d/dt (kinetic + potential energy) of the rigid four-bar (W), from the kinematics alone:
    sum_i m_i v_Gi . a_Gi + J_i w_i al_i + m_i g vy_Gi. Equals the driving power T w2 of the ideal
    (lossless) mechanism."""
    kin = kinematics(params, np.atleast_1d(np.asarray(time_s, dtype=float)))
    points = centre_kinematics(params, kin)
    masses, inertias = params.masses_kg(), params.inertias_kg_m2()
    rate = 0.0
    for k, (centre, link) in enumerate([("G2", "2"), ("G3", "3"), ("G4", "4")]):
        _, velocity, acceleration = points[centre]
        rate = rate + masses[k] * np.sum(velocity * acceleration, axis=-1)
        rate = rate + inertias[k] * kin["omega" + link] * kin["alpha" + link]
        rate = rate + masses[k] * params.gravity_m_s2 * velocity[:, 1]
    return rate


def mechanical_energy_J(params: FourBar, time_s) -> np.ndarray:
    """Kinetic plus potential energy (J, zero level y = 0) of the rigid four-bar at ``time_s``."""
    kin = kinematics(params, np.atleast_1d(np.asarray(time_s, dtype=float)))
    points = centre_kinematics(params, kin)
    masses, inertias = params.masses_kg(), params.inertias_kg_m2()
    energy = 0.0
    for k, (centre, link) in enumerate([("G2", "2"), ("G3", "3"), ("G4", "4")]):
        position, velocity, _ = points[centre]
        energy = energy + 0.5 * masses[k] * np.sum(velocity**2, axis=-1)
        energy = energy + 0.5 * inertias[k] * kin["omega" + link] ** 2
        energy = energy + masses[k] * params.gravity_m_s2 * position[:, 1]
    return energy
