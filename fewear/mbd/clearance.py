"""The revolute clearance joint as a force element between a pin and a bushing (seed eq. 5-6).

Geometry (Flores & Ambrosio, Comput. Struct. 82, 2004): e = r_pin - r_bushing (centres, global),
d = |e|, n = e/d (from the bushing centre towards the pin centre), t = k x n. The direction of n in
the bushing frame, theta = atan2(n) - phi_bushing, gives the clearance c(theta)
(:class:`fewear.mbd.contact.ClearanceProfile`); the penetration is delta = d - c(theta) and its rate
delta_dot = e'.n - c'(theta) theta_dot.

Forces: the bushing pushes the pin with f = -F_n m + F_t m_perp at the contact point (pin surface
point r_pin + R_pin n, bore point r_bushing + R_bushing n); the bushing gets -f. m is the normal
of the clearance curve, the unit gradient of delta (:func:`contact_normal`): n on a circular bore,
tilted against the slope c'(theta) of a worn one. The slip velocity
of the pin relative to the bushing at the contact point is v_t = e'.t + R_pin omega_pin
- R_bushing omega_bushing; friction F_t = -mu c_d F_n sign(v_t). Moments: R_pin F_t on the pin,
-R_bushing F_t on the bushing.

Newton Jacobian: dQ/dq and dQ/dq' are analytic in the joint's kinematic variables
z = (e, e', omega_pin, omega_bushing, phi_bushing) (tested against finite differences), chained with
dz/dq, dz/dq' and the points' geometric stiffness d(G^T f)/dq. Left out (second order in the
Newton step, the iteration still converges, only not quadratically in contact): the dependence of
e' and the angular velocities on q through the points' Jacobians.

Impact velocity: v_imp = delta_dot at the start of the step in which the contact begins (the
step controller makes that step end at a penetration below its gap tolerance, so this is the
approach velocity at impact); it is kept for the whole contact episode.
"""

from __future__ import annotations

import math

import numpy as np

from fewear.mbd.contact import ClearanceProfile, ContactLaw, Friction
from fewear.mbd.points import rotation


def contact_normal(nx: float, ny: float, slope: float) -> tuple[float, float]:
    """The unit normal m of the clearance curve |e| = c(theta) at the direction n (pointing
    from the bushing centre to the pin centre): the gradient of the penetration
    delta = |e| - c(theta(e)), n - (c'(theta) / |e|) t, normalised (``slope`` = c'/|e|). On a
    circular bore m = n; on a worn bore whose clearance varies with the angle the contact force
    leans against the slope, so a pin sliding out of a worn pocket climbs its edge instead of
    running into it (the elastic part F(delta) m is then the gradient of a potential)."""
    mx, my = nx + slope * ny, ny - slope * nx
    length = math.hypot(mx, my)
    return mx / length, my / length


def normal_turn(nx: float, ny: float, d: float, dc: float, ddc: float, F_n: float,
                F_t: float) -> tuple[np.ndarray, np.ndarray]:
    """How the force -F_n m + F_t m_perp turns at fixed F_n, F_t: its derivatives (2, 2) with
    respect to the eccentricity e and (2,) with respect to the bushing angle phi. With
    s = c'/d, m~ = n - s t, dn/de = t t^T / d, dt/de = -n t^T / d, dtheta/de = t^T / d,
    dtheta/dphi = -1, ds/de = (c'' t^T / d - c' n^T) / d^2 and ds/dphi = -c''/d:
    dm~/de = ((1 - c''/d) t t^T + s (t n^T + n t^T)) / d, dm~/dphi = c'' t / d,
    dm/d. = (I - m m^T) dm~/d. / |m~|."""
    n, t = np.array([nx, ny]), np.array([-ny, nx])
    slope = dc / d
    raw = n - slope * t
    length = float(np.hypot(*raw))
    m = raw / length
    project = (np.eye(2) - np.outer(m, m)) / length
    turn_e = project @ ((1.0 - ddc / d) * np.outer(t, t)
                        + slope * (np.outer(t, n) + np.outer(n, t))) / d
    turn_phi = project @ (ddc / d * t)
    force_turn = -F_n * np.eye(2) + F_t * np.array([[0.0, -1.0], [1.0, 0.0]])
    return force_turn @ turn_e, force_turn @ turn_phi


class ClearanceJoint:
    """Pin (any point) in a bushing fixed to a rigid body (a :class:`RigidPoint`)."""

    def __init__(self, pin, bushing, pin_radius_m: float, bushing_radius_m: float,
                 profile: ClearanceProfile, law: ContactLaw, friction: Friction):
        self.pin, self.bushing = pin, bushing
        self.pin_radius, self.bushing_radius = pin_radius_m, bushing_radius_m
        self.profile, self.law, self.friction = profile, law, friction
        self._np = len(pin.indices)
        self.indices = np.concatenate([pin.indices, bushing.indices])
        self.impact_velocity_m_s = 0.0
        self.in_contact = False
        self._candidate_velocity = 0.0

    # --- kinematics ---------------------------------------------------------------------------
    def _kinematics(self, q_b, qd_b):
        """(z, pin coordinates, bushing coordinates): z = (e, e', omega_pin, omega_bushing,
        phi_bushing) as floats, the coordinates as lists of floats (scalar arithmetic)."""
        q, qd = q_b.tolist(), qd_b.tolist()
        n = self._np
        qp, qb = q[:n], q[n:]
        xp, yp, vxp, vyp, _, omega_p = self.pin.motion(qp, qd[:n])
        xb, yb, vxb, vyb, phi_b, omega_b = self.bushing.motion(qb, qd[n:])
        return (xp - xb, yp - yb, vxp - vxb, vyp - vyb, omega_p, omega_b, phi_b), qp, qb

    def gap(self, z):
        """(delta, delta_dot, theta, d): penetration (m, > 0 in contact), its rate, direction."""
        ex, ey, edx, edy, omega_b, phi_b = z[0], z[1], z[2], z[3], z[5], z[6]
        d = math.hypot(ex, ey)
        theta = math.atan2(ey, ex) - phi_b
        c, dc, _ = self.profile(theta)
        if d == 0.0:
            return -c, 0.0, theta, d
        nx, ny = ex / d, ey / d
        theta_dot = (-edx * ny + edy * nx) / d - omega_b
        return d - c, edx * nx + edy * ny - dc * theta_dot, theta, d

    def local_forces(self, z, impact_velocity_m_s: float, derivatives: bool = True):
        """((f1, f2), F_n, F_t, D): the force on the pin, and D = d(f1, f2, F_t)/dz (3, 7), None
        if not ``derivatives``. Scalar arithmetic (this runs in every Newton iteration)."""
        ex, ey, edx, edy, omega_p, omega_b, phi_b = z
        d = math.hypot(ex, ey)
        delta = -1.0
        if d > 0.0:
            c, dc, ddc = self.profile(math.atan2(ey, ex) - phi_b)
            delta = d - c
        if delta <= 0.0:
            return (0.0, 0.0), 0.0, 0.0, np.zeros((3, 7)) if derivatives else None
        nx, ny = ex / d, ey / d
        tx, ty = -ny, nx
        e_n, e_t = edx * nx + edy * ny, edx * tx + edy * ty
        rate = e_n - dc * (e_t / d - omega_b)
        F_n, dF_ddelta, dF_drate = self.law.normal_force(delta, rate, impact_velocity_m_s)
        psi, dpsi = self.friction.factor(e_t + self.pin_radius * omega_p
                                         - self.bushing_radius * omega_b)
        F_t = -self.friction.coefficient * psi * F_n
        mx, my = contact_normal(nx, ny, dc / d)
        f = (-F_n * mx - F_t * my, -F_n * my + F_t * mx)
        if not derivatives:
            return f, F_n, F_t, None
        D = self._force_derivatives((d, nx, ny, e_n, e_t, dc, ddc, omega_b), F_n, F_t,
                                    dF_ddelta, dF_drate, psi, dpsi)
        return f, F_n, F_t, D

    def _force_derivatives(self, geometry, F_n, F_t, dF_ddelta, dF_drate, psi, dpsi):
        """D = d(f1, f2, F_t)/dz (3, 7) at the contact ``geometry`` = (d, n, e'.n, e'.t, c', c'',
        omega_bushing).

        Derivatives of delta and rate = e_n - c'(theta) theta_dot with respect to z:
        dn/de = t t^T / d, dt/de = -n t^T / d, dtheta/de = t^T / d, dtheta/dphi = -1,
        dtheta_dot/de = -(e_n t + e_t n) / d^2 (theta_dot = e_t / d - omega_bushing)."""
        d, nx, ny, e_n, e_t, dc, ddc, omega_b = geometry
        tx, ty = -ny, nx
        rx, ry = nx - dc * tx / d, ny - dc * ty / d
        dthx, dthy = -(e_n * tx + e_t * nx) / d**2, -(e_n * ty + e_t * ny) / d**2
        curving = ddc * (e_t / d - omega_b)  # c'' theta_dot: how c' theta_dot moves with theta
        ddelta = np.array([rx, ry, 0.0, 0.0, 0.0, 0.0, dc])
        drate = np.array([e_t * tx / d - dc * dthx - curving * tx / d,
                          e_t * ty / d - dc * dthy - curving * ty / d, rx, ry, 0.0, dc,
                          curving])
        dF_n = dF_ddelta * ddelta + dF_drate * drate
        mu = self.friction.coefficient
        dF_t = -mu * psi * dF_n
        if dpsi != 0.0:
            dslip = np.array([-e_n * tx / d, -e_n * ty / d, tx, ty, self.pin_radius,
                              -self.bushing_radius, 0.0])
            dF_t -= mu * F_n * dpsi * dslip
        mx, my = contact_normal(nx, ny, dc / d)
        D = np.empty((3, 7))
        D[0] = -mx * dF_n - my * dF_t
        D[1] = -my * dF_n + mx * dF_t
        D[2] = dF_t
        turn_e, turn_phi = normal_turn(nx, ny, d, dc, ddc, F_n, F_t)
        D[0:2, 0:2] += turn_e
        D[0:2, 6] += turn_phi
        return D

    # --- force element interface -------------------------------------------------------------
    def evaluate(self, q_b, qd_b, t, jacobian: bool = True):
        """(Q, dQ/dq, dQ/dq'); the derivatives are None without contact force or ``jacobian``."""
        z, qp, qb = self._kinematics(q_b, qd_b)
        v_imp = self.impact_velocity_m_s if self.in_contact else self._candidate_velocity
        f, F_n, F_t, D = self.local_forces(z, v_imp, jacobian)
        if F_n == 0.0:
            return np.zeros(len(self.indices)), None, None
        fx, fy = f
        Q = np.array(self.pin.generalized_force(qp, fx, fy, self.pin_radius * F_t)
                     + self.bushing.generalized_force(qb, -fx, -fy, -self.bushing_radius * F_t))
        if not jacobian:
            return Q, None, None
        K, C = self._force_jacobians(qp, qb, f, D)
        return Q, K, C

    def _force_jacobians(self, qp, qb, f, D):
        """(dQ/dq, dQ/dq') = (B D dz/dq + geometric stiffness, B D dz/dq') with B = dQ/d(f, F_t)."""
        G_p, G_b = self.pin.jacobian(qp), self.bushing.jacobian(qb)
        g_p, g_b = self.pin.angle_gradient(qp), self.bushing.angle_gradient(qb)
        n_p = self._np
        k = len(self.indices)
        B = np.zeros((k, 3))
        B[:n_p, :2], B[:n_p, 2] = G_p.T, self.pin_radius * g_p
        B[n_p:, :2], B[n_p:, 2] = -G_b.T, -self.bushing_radius * g_b
        Z_q = np.zeros((7, k))
        Z_q[0:2, :n_p], Z_q[0:2, n_p:], Z_q[6, n_p:] = G_p, -G_b, g_b
        Z_qd = np.zeros((7, k))
        Z_qd[2:4, :n_p], Z_qd[2:4, n_p:] = G_p, -G_b
        Z_qd[4, :n_p], Z_qd[5, n_p:] = g_p, g_b
        BD = B @ D
        K = BD @ Z_q
        diagonal = np.arange(k)
        K[diagonal, diagonal] += np.concatenate([self.pin.hessian(qp, f),
                                                 -self.bushing.hessian(qb, f)])
        return K, BD @ Z_qd

    def begin_step(self, q, qd):
        """Remember the approach velocity at the start of a step (the impact velocity if the
        contact begins in this step)."""
        z, _, _ = self._kinematics(q[self.indices], qd[self.indices])
        delta, rate, _, _ = self.gap(z)
        self.in_contact = delta > 0.0
        if not self.in_contact:
            self._candidate_velocity = rate

    def end_step(self, q, qd):
        z, _, _ = self._kinematics(q[self.indices], qd[self.indices])
        delta = self.gap(z)[0]
        if delta > 0.0 and not self.in_contact:
            self.impact_velocity_m_s = self._candidate_velocity

    def step_error(self, q_old, qdd_old, q_new, qdd_new, h):
        """(local error estimate of e (m), delta at step start, delta at step end).

        The estimate is h^2/6 |e''_{n+1} - e''_n|, i.e. h^3 |e'''| / 6, the size of the leading
        local error term of a second-order scheme on the pin-centre eccentricity; e'' is taken as
        G_pin q''_pin - G_bushing q''_bushing (the kinematics with q'' in place of q')."""
        idx = self.indices
        z_old, _, _ = self._kinematics(q_old[idx], qdd_old[idx])
        z_new, _, _ = self._kinematics(q_new[idx], qdd_new[idx])
        error = h * h / 6.0 * math.hypot(z_new[2] - z_old[2], z_new[3] - z_old[3])
        return error, self.gap(z_old)[0], self.gap(z_new)[0]

    # --- output ---------------------------------------------------------------------------------
    def measure(self, q, qd):
        """Joint quantities in the bushing frame at (q, q'): see :class:`JointHistory`."""
        z, _, _ = self._kinematics(q[self.indices], qd[self.indices])
        v_imp = self.impact_velocity_m_s if self.in_contact else self._candidate_velocity
        f, F_n, F_t, _ = self.local_forces(z, v_imp, derivatives=False)
        delta = self.gap(z)[0]
        to_bushing = rotation(z[6]).T
        return {
            "eccentricity_m": to_bushing @ np.array(z[0:2]),
            "penetration_m": max(delta, 0.0),
            "normal_force_N": F_n,
            "friction_force_N": F_t,
            "reaction_force_N": to_bushing @ np.array(f),
            "rel_omega_rad_s": z[4] - z[5],
        }
