"""Holonomic constraints Phi(q, t) = 0 of planar mechanisms, with analytic Jacobians.

Each constraint has ``n_rows``, the system ``indices`` it touches, and for its local coordinates
``q_b``: ``value(q_b, t)``, ``jacobian(q_b)`` (rows x k), ``value_and_jacobian(q_b, t)``,
``time_derivative(t)`` (Phi_t), ``hessian(q_b, lam)`` = the diagonal (k,) of d(Phi_q^T lam)/dq_b
(diagonal for these planar constraints) and ``convective(q_b, qd_b)`` = (dPhi_q/dt) qd_b, so that
the acceleration constraint reads Phi_q qdd = -convective - Phi_tt (Phi_tt = 0 here).
"""

from __future__ import annotations

import numpy as np


class Revolute:
    """Ideal revolute joint: the points ``a`` and ``b`` coincide, Phi = r_a - r_b (2 rows)."""

    n_rows = 2
    nonlinear = True

    def __init__(self, a, b):
        self.a, self.b = a, b
        self._na = len(a.indices)
        self.indices = np.concatenate([a.indices, b.indices])
        self._jac = np.zeros((2, len(self.indices)))

    def _split(self, q_b):
        return q_b[: self._na], q_b[self._na:]

    def value(self, q_b, t):
        qa, qb = self._split(q_b)
        return self.a.position(qa) - self.b.position(qb)

    def value_and_jacobian(self, q_b, t):
        qa, qb = self._split(q_b)
        jac = self._jac
        jac[:, : self._na] = self.a.jacobian(qa)
        jac[:, self._na:] = -self.b.jacobian(qb)
        return self.a.position(qa) - self.b.position(qb), jac

    def jacobian(self, q_b):
        qa, qb = self._split(q_b)
        jac = self._jac
        jac[:, : self._na] = self.a.jacobian(qa)
        jac[:, self._na:] = -self.b.jacobian(qb)
        return jac

    def time_derivative(self, t):
        return np.zeros(2)

    def hessian(self, q_b, lam):
        qa, qb = self._split(q_b)
        return np.concatenate([self.a.hessian(qa, lam), -self.b.hessian(qb, lam)])

    def convective(self, q_b, qd_b):
        qa, qb = self._split(q_b)
        qda, qdb = self._split(qd_b)
        return self.a.convective(qa, qda) - self.b.convective(qb, qdb)


class _LinearConstraint:
    """Constraints linear in q: Phi = C q_b - d(t)."""

    nonlinear = False

    def hessian(self, q_b, lam):
        return np.zeros(len(self.indices))

    def convective(self, q_b, qd_b):
        return np.zeros(self.n_rows)

    def jacobian(self, q_b):
        return self._C

    def value_and_jacobian(self, q_b, t):
        return self.value(q_b, t), self._C


class PrismaticX(_LinearConstraint):
    """A rigid body sliding along the ground's x axis at height ``y_m`` without rotating."""

    n_rows = 2

    def __init__(self, first_index: int, y_m: float = 0.0, angle_rad: float = 0.0):
        self.indices = np.arange(first_index + 1, first_index + 3)
        self._target = np.array([y_m, angle_rad])
        self._C = np.eye(2)

    def value(self, q_b, t):
        return q_b - self._target

    def time_derivative(self, t):
        return np.zeros(2)


class DrivenAngle(_LinearConstraint):
    """A rigid body's angle follows phi(t) = phi0 + omega t (constant speed driver)."""

    n_rows = 1

    def __init__(self, first_index: int, initial_angle_rad: float, speed_rad_s: float):
        self.indices = np.array([first_index + 2])
        self.phi0, self.omega = initial_angle_rad, speed_rad_s
        self._C = np.ones((1, 1))

    def value(self, q_b, t):
        return q_b - (self.phi0 + self.omega * t)

    def time_derivative(self, t):
        return np.array([-self.omega])
