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
                F_t: float) -> tuple[tuple[float, float, float, float], tuple[float, float]]:
    """How the force -F_n m + F_t m_perp turns at fixed F_n, F_t: its derivatives with respect to
    the eccentricity e, the 2 x 2 matrix (a00, a01, a10, a11) row by row, and with respect to the
    bushing angle phi, (b0, b1). With s = c'/d, m~ = n - s t, dn/de = t t^T / d,
    dt/de = -n t^T / d, dtheta/de = t^T / d, dtheta/dphi = -1, ds/de = (c'' t^T / d - c' n^T) / d^2
    and ds/dphi = -c''/d: dm~/de = ((1 - c''/d) t t^T + s (t n^T + n t^T)) / d,
    dm~/dphi = c'' t / d, dm/d. = (I - m m^T) dm~/d. / |m~|. Scalar arithmetic on 2 x 2 matrices,
    each sum in index order (as a matrix product takes it)."""
    tx, ty = -ny, nx
    slope = dc / d
    rx, ry = nx - slope * tx, ny - slope * ty
    length = float(np.hypot(rx, ry))
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


# z = (e, e', omega_pin, omega_bushing, phi_bushing): the entries that depend on q, on q'; the
# columns of A (ClearanceJoint._force_jacobians) that are their derivatives
_POSITION_VARIABLES, _POSITION_COLUMNS = [0, 1, 6], [0, 1, 3]
_VELOCITY_VARIABLES = slice(2, 6)


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
        self._diagonal = np.arange(len(self.indices))
        # (f, F_t) -> (force on e, moment on the pin's angle, moment on the bushing's)
        self._moment_arms = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0],
                                      [0.0, 0.0, pin_radius_m], [0.0, 0.0, -bushing_radius_m]])

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
        ddelta = (rx, ry, 0.0, 0.0, 0.0, 0.0, dc)
        drate = (e_t * tx / d - dc * dthx - curving * tx / d,
                 e_t * ty / d - dc * dthy - curving * ty / d, rx, ry, 0.0, dc, curving)
        dF_n = [dF_ddelta * a + dF_drate * b for a, b in zip(ddelta, drate)]
        mu = self.friction.coefficient
        friction = -mu * psi
        dF_t = [friction * a for a in dF_n]
        if dpsi != 0.0:
            dslip = (-e_n * tx / d, -e_n * ty / d, tx, ty, self.pin_radius,
                     -self.bushing_radius, 0.0)
            slip = mu * F_n * dpsi
            dF_t = [a - slip * b for a, b in zip(dF_t, dslip)]
        mx, my = contact_normal(nx, ny, dc / d)
        df_1 = [-mx * a - my * b for a, b in zip(dF_n, dF_t)]
        df_2 = [-my * a + mx * b for a, b in zip(dF_n, dF_t)]
        (a00, a01, a10, a11), (b0, b1) = normal_turn(nx, ny, d, dc, ddc, F_n, F_t)
        df_1[0] += a00
        df_1[1] += a01
        df_1[6] += b0
        df_2[0] += a10
        df_2[1] += a11
        df_2[6] += b1
        return np.array([df_1, df_2, dF_t])

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
        """(dQ/dq, dQ/dq') = (B D dz/dq + geometric stiffness, B D dz/dq').

        The columns A = [E^T, g_pin, g_bushing] (k, 4) hold the derivatives of the joint's
        variables: E = de/dq = [G_pin, -G_bushing] and the points' angle gradients, each padded
        with zeros to the joint's k coordinates. B = dQ/d(f, F_t) = [E^T, R_pin g_pin - R_bushing
        g_bushing] = A R; dz/dq has the rows (E, 0, 0, 0, 0, g_bushing) and dz/dq' the rows
        (0, E, g_pin, g_bushing, 0), so only the columns of B D of the non-zero rows enter."""
        n_p = self._np
        A = np.zeros((len(self.indices), 4))
        A[:n_p, 0:2] = self.pin.jacobian(qp).T
        np.negative(self.bushing.jacobian(qb).T, out=A[n_p:, 0:2])
        A[:n_p, 2] = self.pin.angle_gradient(qp)
        A[n_p:, 3] = self.bushing.angle_gradient(qb)
        BD = (A @ self._moment_arms) @ D
        K = BD[:, _POSITION_VARIABLES] @ A[:, _POSITION_COLUMNS].T
        K[self._diagonal, self._diagonal] += np.concatenate([self.pin.hessian(qp, f),
                                                             -self.bushing.hessian(qb, f)])
        return K, BD[:, _VELOCITY_VARIABLES] @ A.T

    def begin_step(self, q, qd):
        """A step starts at (q, q'): remember the approach velocity there (the impact velocity if
        the contact begins in this step)."""
        z, _, _ = self._kinematics(q[self.indices], qd[self.indices])
        self._start_step(*self.gap(z)[:2])

    def end_step(self, q, qd):
        """The step ended at (q, q'), where the next one starts: a contact that began in the step
        gets the approach velocity at its start as impact velocity; then as :meth:`begin_step`."""
        z, _, _ = self._kinematics(q[self.indices], qd[self.indices])
        delta, rate, _, _ = self.gap(z)
        if delta > 0.0 and not self.in_contact:
            self.impact_velocity_m_s = self._candidate_velocity
        self._start_step(delta, rate)

    def _start_step(self, delta, rate):
        self.in_contact = delta > 0.0
        if not self.in_contact:
            self._candidate_velocity = rate

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
        c, s = float(np.cos(z[6])), float(np.sin(z[6]))  # A(phi_bushing)^T turns into its frame
        return {
            "eccentricity_m": (c * z[0] + s * z[1], -s * z[0] + c * z[1]),
            "penetration_m": max(delta, 0.0),
            "normal_force_N": F_n,
            "friction_force_N": F_t,
            "reaction_force_N": (c * f[0] + s * f[1], -s * f[0] + c * f[1]),
            "rel_omega_rad_s": z[4] - z[5],
        }
