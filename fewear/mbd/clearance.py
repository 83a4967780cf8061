"""The revolute clearance joint as a force element between a pin and a bushing (seed eq. 5-6).

Geometry after Flores & Ambrosio (Comput. Struct. 82, 2004): penetration delta = |e| - c(theta)
on a clearance profile that may be worn, the contact force along the clearance curve's normal
with the laws of :mod:`fewear.mbd.contact`, its analytic Newton Jacobian, and the impact velocity
kept per contact episode. Compiled (numba) on all joints of a system at once (:class:`JointData`).
Method notes: docs/dynamics.md.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from fewear.jit import compiled
from fewear.mbd.contact import (
    ClearanceProfile,
    ContactLaw,
    Friction,
    clearance_at,
    friction_factor,
    normal_force,
)
from fewear.mbd.points import (
    POINT_COORDINATES,
    add_point_force,
    add_point_hessian,
    point_derivatives,
    point_motion,
)

JointData = namedtuple("JointData", [
    "pin_kind", "pin_offset", "bushing_kind", "bushing_offset",  # (J,), (J, 2): points.py
    "n_pin", "n_coordinates", "indices",  # pin coordinates, all, their indices in q (J, 8)
    "radii_m",  # (J, 2): pin, bushing
    "power_law", "law", "table", "table_size",  # contact.normal_force: (J,), (J, 3), (J, 2, T)
    "friction",  # (J, 3): mu, v0, v1
    "profile_angle", "profile_cubic", "profile_size",  # contact.clearance_at: (J, P), (J, P, 4)
    "memory",  # (J, 3): in contact (1/0), impact velocity, approach velocity at the step's start
])
MEASURES = ("ex_m", "ey_m", "penetration_m", "normal_force_N", "friction_force_N", "fx_N", "fy_N",
            "rel_omega_rad_s")


def joint_data(joints, global_indices: bool = True) -> JointData:
    """The :class:`JointData` of ``joints`` (their coordinates at their ``indices`` in q, or at
    0 .. k-1 of the joint's own coordinate vector if not ``global_indices``)."""
    count = len(joints)
    table_size = max([j.law.kernel_data[2].shape[1] for j in joints], default=1)
    profile_size = max([j.profile.angle_rad.size for j in joints], default=1)

    def integers(*shape):
        return np.zeros((count, *shape), dtype=np.int64)

    def floats(*shape):
        return np.zeros((count, *shape))

    data = JointData(
        pin_kind=integers(), pin_offset=floats(2), bushing_kind=integers(),
        bushing_offset=floats(2), n_pin=integers(), n_coordinates=integers(),
        indices=integers(8), radii_m=floats(2), power_law=np.zeros(count, dtype=bool),
        law=floats(3), table=floats(2, table_size), table_size=integers(), friction=floats(3),
        profile_angle=floats(profile_size), profile_cubic=floats(profile_size, 4),
        profile_size=integers(), memory=floats(3))
    for j, joint in enumerate(joints):
        data.pin_kind[j], data.pin_offset[j] = joint.pin.kind, joint.pin.offset
        data.bushing_kind[j], data.bushing_offset[j] = joint.bushing.kind, joint.bushing.offset
        k = len(joint.indices)
        data.n_pin[j], data.n_coordinates[j] = POINT_COORDINATES[joint.pin.kind], k
        for point in (joint.pin, joint.bushing):
            if np.any(np.diff(point.indices) != 1):
                raise ValueError(f"a clearance joint's point with coordinates {point.indices} "
                                 "apart in q (_local_coordinates takes each point's as a slice)")
        data.indices[j, :k] = joint.indices if global_indices else np.arange(k)
        data.radii_m[j] = joint.pin_radius, joint.bushing_radius
        power_law, parameters, table = joint.law.kernel_data
        data.power_law[j], data.law[j] = power_law, parameters
        data.table[j, :, :table.shape[1]], data.table_size[j] = table, table.shape[1]
        data.friction[j] = (joint.friction.coefficient, joint.friction.v0_m_s,
                            joint.friction.v1_m_s)
        size = joint.profile.angle_rad.size
        data.profile_angle[j, :size] = joint.profile.angle_rad
        data.profile_cubic[j, :size] = joint.profile.cubic
        data.profile_size[j] = size
    return data


@compiled
def contact_normal(nx, ny, slope):
    """The unit normal m of the clearance curve |e| = c(theta) at the direction n (pointing
    from the bushing centre to the pin centre): the gradient of the penetration
    delta = |e| - c(theta(e)), n - (c'(theta) / |e|) t, normalised (``slope`` = c'/|e|). On a
    circular bore m = n; on a worn bore whose clearance varies with the angle the contact force
    leans against the slope, so a pin sliding out of a worn pocket climbs its edge instead of
    running into it (the elastic part F(delta) m is then the gradient of a potential)."""
    mx, my = nx + slope * ny, ny - slope * nx
    length = math.hypot(mx, my)
    return mx / length, my / length


@compiled
def normal_turn(nx, ny, d, dc, ddc, F_n, F_t):
    """How the force -F_n m + F_t m_perp turns at fixed F_n, F_t: its derivatives with respect to
    the eccentricity e, the 2 x 2 matrix (a00, a01, a10, a11) row by row, and with respect to the
    bushing angle phi, (b0, b1). With s = c'/d, m~ = n - s t, dn/de = t t^T / d,
    dt/de = -n t^T / d, dtheta/de = t^T / d, dtheta/dphi = -1, ds/de = (c'' t^T / d - c' n^T) / d^2
    and ds/dphi = -c''/d: dm~/de = ((1 - c''/d) t t^T + s (t n^T + n t^T)) / d,
    dm~/dphi = c'' t / d, dm/d. = (I - m m^T) dm~/d. / |m~|."""
    tx, ty = -ny, nx
    slope = dc / d
    rx, ry = nx - slope * tx, ny - slope * ty
    length = math.hypot(rx, ry)
    mx, my = rx / length, ry / length
    # P = (I - m m^T) / |m~| (symmetric)
    p00, p01, p11 = (1.0 - mx * mx) / length, -mx * my / length, (1.0 - my * my) / length
    # X = (1 - c''/d) t t^T + s (t n^T + n t^T)
    w = 1.0 - ddc / d
    x00 = w * (tx * tx) + slope * (tx * nx + nx * tx)
    x01 = w * (tx * ty) + slope * (tx * ny + nx * ty)
    x10 = w * (ty * tx) + slope * (ty * nx + ny * tx)
    x11 = w * (ty * ty) + slope * (ty * ny + ny * ty)
    # dm/de = P X / d, dm/dphi = P v with v = c'' t / d
    e00, e01 = (p00 * x00 + p01 * x10) / d, (p00 * x01 + p01 * x11) / d
    e10, e11 = (p01 * x00 + p11 * x10) / d, (p01 * x01 + p11 * x11) / d
    curvature = ddc / d
    v0, v1 = curvature * tx, curvature * ty
    b0, b1 = p00 * v0 + p01 * v1, p01 * v0 + p11 * v1
    # the force turns with m: d(-F_n m + F_t m_perp) = [[-F_n, -F_t], [F_t, -F_n]] dm
    turn_e = (-F_n * e00 + -F_t * e10, -F_n * e01 + -F_t * e11,
              F_t * e00 + -F_n * e10, F_t * e01 + -F_n * e11)
    return turn_e, (-F_n * b0 + -F_t * b1, F_t * b0 + -F_n * b1)


@compiled
def _profile(data, j, theta):
    return clearance_at(data.profile_angle[j], data.profile_cubic[j], data.profile_size[j], theta)


@compiled
def _local_coordinates(data, j, q):
    """(pin coordinates, bushing coordinates) of joint j: views of q, each point's coordinates
    being consecutive (checked by :func:`joint_data`)."""
    n_pin, n_bushing = data.n_pin[j], data.n_coordinates[j] - data.n_pin[j]
    first_pin, first_bushing = data.indices[j, 0], data.indices[j, n_pin]
    return (q[first_pin:first_pin + n_pin],
            q[first_bushing:first_bushing + n_bushing])


@compiled
def kinematics(data, j, q, qd):
    """z = (e, e', omega_pin, omega_bushing, phi_bushing) (7,) of joint j at (q, q')."""
    qp, qb = _local_coordinates(data, j, q)
    qdp, qdb = _local_coordinates(data, j, qd)
    xp, yp, vxp, vyp, _, omega_p = point_motion(data.pin_kind[j], data.pin_offset[j], qp, qdp)
    xb, yb, vxb, vyb, phi_b, omega_b = point_motion(data.bushing_kind[j], data.bushing_offset[j],
                                                    qb, qdb)
    return np.array([xp - xb, yp - yb, vxp - vxb, vyp - vyb, omega_p, omega_b, phi_b])


@compiled
def gap(data, j, z):
    """(delta, delta_dot): penetration (m, > 0 in contact) and its rate."""
    ex, ey, edx, edy, omega_b, phi_b = z[0], z[1], z[2], z[3], z[5], z[6]
    d = math.hypot(ex, ey)
    c, dc, _ = _profile(data, j, math.atan2(ey, ex) - phi_b)
    if d == 0.0:
        return -c, 0.0
    nx, ny = ex / d, ey / d
    theta_dot = (-edx * ny + edy * nx) / d - omega_b
    return d - c, edx * nx + edy * ny - dc * theta_dot


@compiled
def _impact_velocity(data, j):
    """v_imp: the episode's impact velocity in contact, else the approach velocity."""
    memory = data.memory[j]
    return memory[1] if memory[0] > 0.0 else memory[2]


@compiled
def local_forces(data, j, z, impact_velocity_m_s, derivatives):
    """(f1, f2, F_n, F_t, D): the force on the pin and D = d(f1, f2, F_t)/dz (3, 7) (zeros
    without contact or ``derivatives``)."""
    ex, ey, edx, edy, omega_p, omega_b, phi_b = z[0], z[1], z[2], z[3], z[4], z[5], z[6]
    D = np.zeros((3, 7))
    d = math.hypot(ex, ey)
    delta, dc, ddc = -1.0, 0.0, 0.0
    if d > 0.0:
        c, dc, ddc = _profile(data, j, math.atan2(ey, ex) - phi_b)
        delta = d - c
    if delta <= 0.0:
        return 0.0, 0.0, 0.0, 0.0, D
    nx, ny = ex / d, ey / d
    tx, ty = -ny, nx
    e_n, e_t = edx * nx + edy * ny, edx * tx + edy * ty
    rate = e_n - dc * (e_t / d - omega_b)
    F_n, dF_ddelta, dF_drate = normal_force(data.power_law[j], data.law[j], data.table[j],
                                            data.table_size[j], delta, rate, impact_velocity_m_s)
    pin_radius, bushing_radius = data.radii_m[j, 0], data.radii_m[j, 1]
    mu, v0, v1 = data.friction[j, 0], data.friction[j, 1], data.friction[j, 2]
    psi, dpsi = friction_factor(v0, v1, e_t + pin_radius * omega_p - bushing_radius * omega_b)
    F_t = -mu * psi * F_n
    mx, my = contact_normal(nx, ny, dc / d)
    if derivatives:
        _force_derivatives(d, nx, ny, e_n, e_t, dc, ddc, omega_b, F_n, F_t, dF_ddelta, dF_drate,
                           mu * psi, mu * F_n * dpsi, pin_radius, bushing_radius, D)
    return -F_n * mx - F_t * my, -F_n * my + F_t * mx, F_n, F_t, D


@compiled
def _force_derivatives(d, nx, ny, e_n, e_t, dc, ddc, omega_b, F_n, F_t, dF_ddelta, dF_drate,
                       friction, slip, pin_radius, bushing_radius, D):
    """Fill D = d(f1, f2, F_t)/dz (3, 7) at the contact geometry (d, n, e'.n, e'.t, c', c'',
    omega_bushing); ``friction`` = mu psi, ``slip`` = mu F_n dpsi/dv.

    Derivatives of delta and rate = e_n - c'(theta) theta_dot with respect to z:
    dn/de = t t^T / d, dt/de = -n t^T / d, dtheta/de = t^T / d, dtheta/dphi = -1,
    dtheta_dot/de = -(e_n t + e_t n) / d^2 (theta_dot = e_t / d - omega_bushing)."""
    tx, ty = -ny, nx
    rx, ry = nx - dc * tx / d, ny - dc * ty / d
    dthx, dthy = -(e_n * tx + e_t * nx) / d**2, -(e_n * ty + e_t * ny) / d**2
    curving = ddc * (e_t / d - omega_b)  # c'' theta_dot: how c' theta_dot moves with theta
    ddelta = (rx, ry, 0.0, 0.0, 0.0, 0.0, dc)
    drate = (e_t * tx / d - dc * dthx - curving * tx / d,
             e_t * ty / d - dc * dthy - curving * ty / d, rx, ry, 0.0, dc, curving)
    dslip = (-e_n * tx / d, -e_n * ty / d, tx, ty, pin_radius, -bushing_radius, 0.0)
    mx, my = contact_normal(nx, ny, dc / d)
    for k in range(7):
        dF_n = dF_ddelta * ddelta[k] + dF_drate * drate[k]
        dF_t = -friction * dF_n
        if slip != 0.0:
            dF_t = dF_t - slip * dslip[k]
        D[0, k] = -mx * dF_n - my * dF_t
        D[1, k] = -my * dF_n + mx * dF_t
        D[2, k] = dF_t
    (a00, a01, a10, a11), (b0, b1) = normal_turn(nx, ny, d, dc, ddc, F_n, F_t)
    D[0, 0] += a00
    D[0, 1] += a01
    D[0, 6] += b0
    D[1, 0] += a10
    D[1, 1] += a11
    D[1, 6] += b1


@compiled
def add_joint_forces(data, j, q, qd, jacobian, Q, K, C):
    """Add joint j's generalized force to Q and, if ``jacobian``, dQ/dq to K and dQ/dq' to C
    (global arrays); False if there is no contact force.

    The pin gets f = -F_n m + F_t m_perp and the moment R_pin F_t, the bushing -f and
    -R_bushing F_t. dQ/dq = B D dz/dq + the points' geometric stiffness, dQ/dq' = B D dz/dq':
    with the columns A = [E^T, g_pin, g_bushing] (k, 4), E = de/dq = [G_pin, -G_bushing],
    B = dQ/d(f, F_t) = [E^T, R_pin g_pin - R_bushing g_bushing]; dz/dq has the rows
    (E, 0, 0, 0, 0, g_bushing) and dz/dq' the rows (0, E, g_pin, g_bushing, 0). Left out: the
    dependence of e' and the angular velocities on q through the points' Jacobians."""
    z = kinematics(data, j, q, qd)
    fx, fy, F_n, F_t, D = local_forces(data, j, z, _impact_velocity(data, j), jacobian)
    if F_n == 0.0:
        return False
    k, n_pin, index = data.n_coordinates[j], data.n_pin[j], data.indices[j]
    pin_radius, bushing_radius = data.radii_m[j, 0], data.radii_m[j, 1]
    qp, qb = _local_coordinates(data, j, q)
    Q_b = np.zeros(k)
    add_point_force(data.pin_kind[j], data.pin_offset[j], qp, fx, fy, pin_radius * F_t,
                    Q_b[:n_pin])
    add_point_force(data.bushing_kind[j], data.bushing_offset[j], qb, -fx, -fy,
                    -bushing_radius * F_t, Q_b[n_pin:])
    for r in range(k):
        Q[index[r]] += Q_b[r]
    if not jacobian:
        return True
    A = np.zeros((k, 4))
    G = np.zeros((2, k))
    point_derivatives(data.pin_kind[j], data.pin_offset[j], qp, 1.0, G[:, :n_pin],
                      A[:n_pin, 2])
    point_derivatives(data.bushing_kind[j], data.bushing_offset[j], qb, -1.0, G[:, n_pin:],
                      A[n_pin:, 3])
    A[:, 0:2] = G.T
    BD = np.zeros((k, 7))  # B D = A R D, R: (f, F_t) -> (force on e, moments on the angles)
    for r in range(k):
        arm = pin_radius * A[r, 2] - bushing_radius * A[r, 3]
        for c in range(7):
            BD[r, c] = A[r, 0] * D[0, c] + A[r, 1] * D[1, c] + arm * D[2, c]
    geometric = np.zeros(k)
    add_point_hessian(data.pin_kind[j], data.pin_offset[j], qp, fx, fy, geometric[:n_pin])
    add_point_hessian(data.bushing_kind[j], data.bushing_offset[j], qb, -fx, -fy,
                      geometric[n_pin:])
    for r in range(k):
        K[index[r], index[r]] += geometric[r]
        for c in range(k):
            K[index[r], index[c]] += BD[r, 0] * A[c, 0] + BD[r, 1] * A[c, 1] + BD[r, 6] * A[c, 3]
            C[index[r], index[c]] += (BD[r, 2] * A[c, 0] + BD[r, 3] * A[c, 1]
                                      + BD[r, 4] * A[c, 2] + BD[r, 5] * A[c, 3])
    return True


@compiled
def begin_step(data, j, q, qd):
    """A step starts at (q, q'): remember the approach velocity there (the impact velocity if
    the contact begins in this step)."""
    delta, rate = gap(data, j, kinematics(data, j, q, qd))
    _start_step(data, j, delta, rate)


@compiled
def end_step(data, j, q, qd):
    """The step ended at (q, q'), where the next one starts: a contact that began in the step
    gets the approach velocity at its start as impact velocity; then as :func:`begin_step`."""
    delta, rate = gap(data, j, kinematics(data, j, q, qd))
    memory = data.memory[j]
    if delta > 0.0 and memory[0] == 0.0:
        memory[1] = memory[2]
    _start_step(data, j, delta, rate)


@compiled
def _start_step(data, j, delta, rate):
    memory = data.memory[j]
    memory[0] = 1.0 if delta > 0.0 else 0.0
    if delta <= 0.0:
        memory[2] = rate


@compiled
def step_error(data, j, q_old, qdd_old, q_new, qdd_new, h):
    """(local error estimate of e (m), delta at step start, delta at step end).

    The estimate is h^2/6 |e''_{n+1} - e''_n|, i.e. h^3 |e'''| / 6, the size of the leading
    local error term of a second-order scheme on the pin-centre eccentricity; e'' is taken as
    G_pin q''_pin - G_bushing q''_bushing (the kinematics with q'' in place of q')."""
    z_old = kinematics(data, j, q_old, qdd_old)
    z_new = kinematics(data, j, q_new, qdd_new)
    error = h * h / 6.0 * math.hypot(z_new[2] - z_old[2], z_new[3] - z_old[3])
    return error, gap(data, j, z_old)[0], gap(data, j, z_new)[0]


@compiled
def measure_rows(data, j, q_rows, qd_rows, memory_rows):
    """Joint j's quantities (rows, ``MEASURES``) in the bushing frame at each row of (q, q') with
    the joints' memory of that row (rows, J, 3): see :class:`fewear.mbd.history.JointHistory`."""
    out = np.empty((q_rows.shape[0], 8))
    for row in range(q_rows.shape[0]):
        memory = memory_rows[row, j]
        impact_velocity = memory[1] if memory[0] > 0.0 else memory[2]
        z = kinematics(data, j, q_rows[row], qd_rows[row])
        fx, fy, F_n, F_t, _ = local_forces(data, j, z, impact_velocity, False)
        delta = gap(data, j, z)[0]
        c, s = math.cos(z[6]), math.sin(z[6])  # A(phi_bushing)^T turns into its frame
        out[row, 0], out[row, 1] = c * z[0] + s * z[1], -s * z[0] + c * z[1]
        out[row, 2], out[row, 3], out[row, 4] = max(delta, 0.0), F_n, F_t
        out[row, 5], out[row, 6] = c * fx + s * fy, -s * fx + c * fy
        out[row, 7] = z[4] - z[5]
    return out


class ClearanceJoint:
    """Pin (any point) in a bushing fixed to a rigid body or the ground (a :class:`RigidPoint`
    or :class:`GroundPoint`); the profile's angle and the measured quantities are in the
    bushing body's frame, which may rotate.

    The joint's memory (in contact, impact velocity, approach velocity) becomes a row of its
    system's :class:`JointData` when the system is finalized (:meth:`share_memory`); the methods
    evaluate the joint alone on its own coordinates (``indices`` of the system's q)."""

    def __init__(self, pin, bushing, pin_radius_m: float, bushing_radius_m: float,
                 profile: ClearanceProfile, law: ContactLaw, friction: Friction):
        self.pin, self.bushing = pin, bushing
        self.pin_radius, self.bushing_radius = pin_radius_m, bushing_radius_m
        self.profile, self.law, self.friction = profile, law, friction
        self.indices = np.concatenate([pin.indices, bushing.indices])
        self.data = joint_data([self], global_indices=False)

    def share_memory(self, memory: np.ndarray) -> None:
        """Keep the joint's memory in ``memory`` (1, 3) (its row of the system's JointData)."""
        memory[:] = self.data.memory
        self.data = self.data._replace(memory=memory)

    def local_forces(self, z, impact_velocity_m_s: float, derivatives: bool = True):
        """((f1, f2), F_n, F_t, D): the force on the pin, and D = d(f1, f2, F_t)/dz (3, 7), None
        if not ``derivatives``."""
        f1, f2, F_n, F_t, D = local_forces(self.data, 0, np.asarray(z, dtype=float),
                                           float(impact_velocity_m_s), derivatives)
        return (f1, f2), F_n, F_t, (D if derivatives else None)

    def evaluate(self, q_b, qd_b, t, jacobian: bool = True):
        """(Q, dQ/dq, dQ/dq') on the joint's coordinates; the derivatives are None without
        contact force or ``jacobian``."""
        k = len(self.indices)
        Q, K, C = np.zeros(k), np.zeros((k, k)), np.zeros((k, k))
        q_b, qd_b = np.asarray(q_b, dtype=float), np.asarray(qd_b, dtype=float)
        if not add_joint_forces(self.data, 0, q_b, qd_b, jacobian, Q, K, C) or not jacobian:
            return Q, None, None
        return Q, K, C

    def begin_step(self, q, qd):
        """A step starts at (q, q') (the system's vectors): see :func:`begin_step`."""
        begin_step(self.data, 0, np.asarray(q, dtype=float)[self.indices],
                   np.asarray(qd, dtype=float)[self.indices])
