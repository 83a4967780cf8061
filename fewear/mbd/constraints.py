"""Holonomic constraints Phi(q, t) = 0 of planar mechanisms, evaluated all at once.

Every constraint has the form Phi(q, t) = D q + c0 + c1 t + R w(q), w the rotated offsets of rigid
points, so :class:`ConstraintSet` holds all rows of a system as a few arrays that compiled
functions evaluate, with Phi_q, d(Phi_q^T lambda)/dq and the convective term in closed form; a
tabulated driver (:class:`PrescribedAngle`) adds a periodic spline of time.
Method notes: docs/dynamics.md.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from fewear.jit import compiled
from fewear.mbd.contact import clearance_at, periodic_cubic

Drives = namedtuple("Drives", [
    "rows", "phase", "cubic", "size", "timing",  # (k,), (k, P), (k, P, 4), (k,), (k, 2): t0, T
])


class Revolute:
    """Ideal revolute joint: the points ``a`` and ``b`` coincide, Phi = r_a - r_b (2 rows)."""

    n_rows = 2

    def __init__(self, a, b):
        self.a, self.b = a, b
        self.indices = np.concatenate([a.indices, b.indices])


class _LinearConstraint:
    """Constraints linear in q: Phi = C q_b - (d0 + d1 t) with constant C (rows, k), d0, d1."""

    def _set(self, C, d0, d1):
        self._C = np.asarray(C, dtype=float)
        self.d0 = np.asarray(d0, dtype=float)
        self.d1 = np.asarray(d1, dtype=float)


class Prismatic(_LinearConstraint):
    """A rigid body sliding along a fixed direction of the ground without rotating: its point u
    stays on the line through the ground point p along the unit ``direction`` d, and its angle at
    ``angle_rad``. With n = k x d: n . (R + A(angle) u - p) = 0 (linear in R because the angle is
    held), phi = angle."""

    n_rows = 2

    def __init__(self, first_index: int, ground_point_m=(0.0, 0.0), direction=(1.0, 0.0),
                 u_m=(0.0, 0.0), angle_rad: float = 0.0):
        self.indices = np.arange(first_index, first_index + 3)
        normal = np.array([-direction[1], direction[0]], dtype=float)
        c, s = math.cos(angle_rad), math.sin(angle_rad)
        rotated = np.array([c * u_m[0] - s * u_m[1], s * u_m[0] + c * u_m[1]])
        self._set([[normal[0], normal[1], 0.0], [0.0, 0.0, 1.0]],
                  [normal @ np.asarray(ground_point_m, dtype=float) - normal @ rotated, angle_rad],
                  [0.0, 0.0])


class FixedAngle(_LinearConstraint):
    """A rigid body's angle held: phi_b - phi_a = ``angle_rad`` (``first_a`` None: the ground,
    phi_b = ``angle_rad``); with a revolute joint at a common point, a fixed joint."""

    n_rows = 1

    def __init__(self, first_b: int, angle_rad: float, first_a: int | None = None):
        if first_a is None:
            self.indices = np.array([first_b + 2])
            self._set([[1.0]], [angle_rad], [0.0])
        else:
            self.indices = np.array([first_a + 2, first_b + 2])
            self._set([[-1.0, 1.0]], [angle_rad], [0.0])


class DrivenAngle(_LinearConstraint):
    """A rigid body's angle follows phi(t) = phi0 + omega t (constant speed driver)."""

    n_rows = 1

    def __init__(self, first_index: int, initial_angle_rad: float, speed_rad_s: float):
        self.indices = np.array([first_index + 2])
        self.phi0, self.omega = initial_angle_rad, speed_rad_s
        self._set(np.ones((1, 1)), [initial_angle_rad], [speed_rad_s])


class PrescribedAngle(_LinearConstraint):
    """A rigid body's angle follows a periodic table: phi = f(t), f the periodic cubic spline (C2)
    through ``angle_rad`` at ``time_s`` (one period: increasing times, the last angle equal to the
    first), so the driven velocity and acceleration f', f'' are continuous."""

    n_rows = 1

    def __init__(self, first_index: int, time_s, angle_rad):
        self.indices = np.array([first_index + 2])
        self._set(np.ones((1, 1)), [0.0], [0.0])
        time_s, angle_rad = np.asarray(time_s, dtype=float), np.asarray(angle_rad, dtype=float)
        self.start_s, self.period_s = time_s[0], time_s[-1] - time_s[0]
        self.phase = 2.0 * math.pi * (time_s[:-1] - time_s[0]) / self.period_s
        self.cubic = np.ascontiguousarray(periodic_cubic(self.phase, angle_rad[:-1]).c.T)


class ConstraintSet:
    """All constraints of a system (n coordinates) in the form of the method notes."""

    def __init__(self, constraints, n_coordinates: int):
        self.rows = []
        start = 0
        for constraint in constraints:
            self.rows.append(slice(start, start + constraint.n_rows))
            start += constraint.n_rows
        self.n_rows = m = start
        self._D, self._c0, self.c1 = np.zeros((m, n_coordinates)), np.zeros(m), np.zeros(m)
        offsets = []  # (first row, column of phi, u) of each rigid point's rotated offset
        self.drives = _drives([(constraint, rows.start) for constraint, rows
                               in zip(constraints, self.rows)
                               if isinstance(constraint, PrescribedAngle)])
        for constraint, rows in zip(constraints, self.rows):
            if isinstance(constraint, Revolute):
                offsets += self._add_revolute(constraint, rows)
            elif isinstance(constraint, _LinearConstraint):
                self._D[rows, constraint.indices] = constraint._C
                self._c0[rows] = -constraint.d0
                self.c1[rows] = -constraint.d1
            else:
                raise TypeError(f"unsupported constraint {constraint!r}")
        self._build_offsets(offsets)

    def _add_revolute(self, revolute, rows):
        offsets = []
        for point, sign in ((revolute.a, 1.0), (revolute.b, -1.0)):
            G0, r0 = point.affine
            self._D[rows, point.indices] += sign * G0
            self._c0[rows] += sign * r0
            if point.rotating_offset is not None:
                local, u = point.rotating_offset
                offsets.append((rows.start, point.indices[local], sign * u))
        if len(offsets) == 2 and offsets[0][1] == offsets[1][1]:
            raise ValueError("a revolute joint between two points of the same body")
        return offsets

    def _build_offsets(self, offsets):
        """The offsets' first rows, angle columns and u (P, 2)."""
        self.offset_rows = np.array([row for row, _, _ in offsets], dtype=np.int64)
        self.offset_columns = np.array([col for _, col, _ in offsets], dtype=np.int64)
        self.offset_u = np.array([u for _, _, u in offsets], dtype=float).reshape(-1, 2)

    @property
    def kernel_data(self):
        """(D, c0, c1, offset rows, offset columns, u): the arrays of the compiled functions."""
        return (self._D, self._c0, self.c1, self.offset_rows, self.offset_columns, self.offset_u)

    def jacobian(self, q):
        """Phi_q (m, n) (a new array)."""
        phi, jac = np.zeros(self.n_rows), np.zeros(self._D.shape)
        constraint_values_and_jacobian(*self.kernel_data, np.asarray(q, dtype=float), 0.0, phi,
                                       jac)
        return jac

    def values(self, q, t: float):
        """Phi(q, t) (m,)."""
        phi, jac = np.zeros(self.n_rows), np.zeros(self._D.shape)
        constraint_values_and_jacobian(*self.kernel_data, np.asarray(q, dtype=float), t, phi,
                                       jac)
        add_prescribed(self.drives, t, 0, phi)
        return phi

    def time_derivative(self, t: float):
        """Phi_t(t) (m,)."""
        out = self.c1.copy()
        add_prescribed(self.drives, t, 1, out)
        return out

    def convective(self, q, qd, t: float = 0.0):
        """(dPhi_q/dt) q' + Phi_tt(t) (m,): what the acceleration constraint subtracts."""
        out = np.zeros(self.n_rows)
        constraint_convective(*self.kernel_data[3:], np.asarray(q, dtype=float),
                              np.asarray(qd, dtype=float), out)
        add_prescribed(self.drives, t, 2, out)
        return out


def _drives(prescribed) -> Drives:
    """The :data:`Drives` arrays of the (PrescribedAngle, row) pairs."""
    size = max([drive.phase.size for drive, _ in prescribed], default=1)
    count = len(prescribed)
    drives = Drives(np.zeros(count, dtype=np.int64), np.zeros((count, size)),
                    np.zeros((count, size, 4)), np.zeros(count, dtype=np.int64),
                    np.zeros((count, 2)))
    for k, (drive, row) in enumerate(prescribed):
        n = drive.phase.size
        drives.rows[k], drives.size[k] = row, n
        drives.phase[k, :n], drives.cubic[k, :n] = drive.phase, drive.cubic
        drives.timing[k] = drive.start_s, drive.period_s
    return drives


@compiled
def add_prescribed(drives, t, order, out):
    """out -= the ``order``-th time derivative of the tabulated drivers' angles f(t) in their
    rows (order 0: Phi, 1: Phi_t, 2: Phi_tt)."""
    for k in range(drives.rows.size):
        start, period = drives.timing[k, 0], drives.timing[k, 1]
        rate = 2.0 * math.pi / period
        terms = clearance_at(drives.phase[k], drives.cubic[k], drives.size[k],
                             rate * (t - start))
        out[drives.rows[k]] -= terms[order] * rate**order


@compiled
def _rotated(u, phi):
    """w = A(phi) u (as the complex number (u0 + i u1) exp(i phi))."""
    c, s = math.cos(phi), math.sin(phi)
    return c * u[0] - s * u[1], s * u[0] + c * u[1]


@compiled
def constraint_values_and_jacobian(D, c0, c1, rows, columns, u, q, t, phi, jac):
    """Fill Phi = D q + c0 + c1 t + R w and Phi_q = D + (i w_p in the column of phi_p)."""
    m, n = D.shape
    for r in range(m):
        total = 0.0
        for c in range(n):
            total += D[r, c] * q[c]
            jac[r, c] = D[r, c]
        phi[r] = total + c0[r] + c1[r] * t
    for p in range(rows.size):
        w0, w1 = _rotated(u[p], q[columns[p]])
        phi[rows[p]] += w0
        phi[rows[p] + 1] += w1
        jac[rows[p], columns[p]] = -w1
        jac[rows[p] + 1, columns[p]] = w0


@compiled
def add_constraint_hessian(rows, columns, u, q, lam, scale, diagonal):
    """diagonal += scale d(Phi_q^T lambda)/dq (diagonal: -lambda_j . w_p in phi_p's column)."""
    for p in range(rows.size):
        w0, w1 = _rotated(u[p], q[columns[p]])
        diagonal[columns[p]] -= scale * (lam[rows[p]] * w0 + lam[rows[p] + 1] * w1)


@compiled
def constraint_convective(rows, columns, u, q, qd, out):
    """out = (dPhi_q/dt) q' = -phi_p'^2 w_p in the joints' rows."""
    out[:] = 0.0
    for p in range(rows.size):
        w0, w1 = _rotated(u[p], q[columns[p]])
        rate2 = qd[columns[p]] * qd[columns[p]]
        out[rows[p]] -= rate2 * w0
        out[rows[p] + 1] -= rate2 * w1
