"""Holonomic constraints Phi(q, t) = 0 of planar mechanisms, evaluated all at once.

The constraint classes describe rows; :class:`ConstraintSet` evaluates every row of a system in a
few vectorised NumPy operations (the Newton iteration calls it once per iteration, so the cost is
the number of NumPy calls, not the arithmetic). Every constraint here has the form

    Phi(q, t) = D q + c0 + c1 t + R w(q),   w = the rotated offsets A(phi_p) u_p of rigid points,

with constant D, c0, c1 and a constant 0/1 matrix R that adds each rotated offset to the two rows of
its joint: a revolute joint's rows are r_a - r_b with r = r0 + G0 q_b + A(phi) u (see
:mod:`fewear.mbd.points`), a linear constraint's rows are C q_b - (d0 + d1 t). With the offset
written as the complex number w_p = (u_p0 + i u_p1) exp(i phi_p):

- Jacobian Phi_q = D plus, in the column of phi_p, dw_p/dphi_p = i w_p (rows of its joint);
- d(Phi_q^T lambda)/dq is diagonal, -lambda_j . w_p in the column of phi_p (lambda_j: the joint's
  two multipliers);
- Phi_t = c1 (constant) and (dPhi_q/dt) q' = -phi_p'^2 w_p in the joint's rows (convective term of
  the acceleration constraint Phi_q q'' = -(dPhi_q/dt) q' - Phi_tt, Phi_tt = 0).
"""

from __future__ import annotations

import numpy as np


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


class PrismaticX(_LinearConstraint):
    """A rigid body sliding along the ground's x axis at height ``y_m`` without rotating."""

    n_rows = 2

    def __init__(self, first_index: int, y_m: float = 0.0, angle_rad: float = 0.0):
        self.indices = np.arange(first_index + 1, first_index + 3)
        self._set(np.eye(2), [y_m, angle_rad], [0.0, 0.0])


class DrivenAngle(_LinearConstraint):
    """A rigid body's angle follows phi(t) = phi0 + omega t (constant speed driver)."""

    n_rows = 1

    def __init__(self, first_index: int, initial_angle_rad: float, speed_rad_s: float):
        self.indices = np.array([first_index + 2])
        self.phi0, self.omega = initial_angle_rad, speed_rad_s
        self._set(np.ones((1, 1)), [initial_angle_rad], [speed_rad_s])


class ConstraintSet:
    """All constraints of a system (n coordinates) in the form of the module docstring."""

    def __init__(self, constraints, n_coordinates: int):
        self.rows = []
        start = 0
        for constraint in constraints:
            self.rows.append(slice(start, start + constraint.n_rows))
            start += constraint.n_rows
        self.n_rows = m = start
        self._D, self._c0, self.c1 = np.zeros((m, n_coordinates)), np.zeros(m), np.zeros(m)
        offsets = []  # (first row, column of phi, u) of each rigid point's rotated offset
        for constraint, rows in zip(constraints, self.rows):
            if isinstance(constraint, Revolute):
                offsets += self._add_revolute(constraint, rows)
            elif isinstance(constraint, _LinearConstraint):
                self._D[rows, constraint.indices] = constraint._C
                self._c0[rows] = -constraint.d0
                self.c1[rows] = -constraint.d1
            else:
                raise TypeError(f"unsupported constraint {constraint!r}")
        self._build_offsets(offsets, n_coordinates)
        self._jacobian = self._D.copy()
        # the columns where Phi_q can be non-zero (D's and the offsets' angles), increasing
        self.columns = np.union1d(np.flatnonzero(self._D.any(axis=0)), self._angle_columns)

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

    def _build_offsets(self, offsets, n):
        """Index arrays: the offsets' angle columns, and for w viewed as (re, im) pairs their
        rows, columns, the scatter R (rows, 2P) and the Hessian gather (n, 2P)."""
        count = len(offsets)
        self._angle_columns = np.array([col for _, col, _ in offsets], dtype=int)
        self._u = np.array([complex(u[0], u[1]) for _, _, u in offsets], dtype=complex)
        pair_rows = np.array([[row, row + 1] for row, _, _ in offsets], dtype=int).reshape(-1)
        pair_columns = np.repeat(self._angle_columns, 2)
        self._pair_rows, self._pair_columns = pair_rows, pair_columns
        self._scatter = np.zeros((self.n_rows, 2 * count))
        self._scatter[pair_rows, np.arange(2 * count)] = 1.0
        self._gather = np.zeros((n, 2 * count))
        self._gather[pair_columns, np.arange(2 * count)] = -1.0

    def _offsets(self, q):
        """w_p = u_p exp(i phi_p) (complex, P)."""
        return self._u * np.exp(1j * q[self._angle_columns])

    def values_and_jacobian(self, q, t):
        """(Phi (m,), Phi_q (m, n)); Phi_q is a buffer overwritten by the next call."""
        w = self._offsets(q)
        phi = self._D @ q + self._c0 + self.c1 * t + self._scatter @ w.view(float)
        self._jacobian[self._pair_rows, self._pair_columns] = (1j * w).view(float)
        return phi, self._jacobian

    def jacobian(self, q):
        """Phi_q (m, n) (a new array)."""
        return self.values_and_jacobian(q, 0.0)[1].copy()

    def hessian(self, q, lam):
        """The diagonal (n,) of d(Phi_q^T lambda)/dq."""
        return self._gather @ (lam[self._pair_rows] * self._offsets(q).view(float))

    def convective(self, q, qd):
        """(dPhi_q/dt) q' (m,)."""
        rates = qd[self._angle_columns]
        return self._scatter @ (-(rates * rates) * self._offsets(q)).view(float)
