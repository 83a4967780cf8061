"""Material points of planar bodies: where joints and contacts attach.

A point maps the coordinates of its body, ``q_b`` (a slice of the system vector given by
``indices``; an array or a list of floats), to a position ``r`` (m) and an angle ``theta`` (rad) of
the material line through it, with the derivatives the constraints and the Newton Jacobian need:

- ``G = dr/dq_b`` (2, k) and ``g = dtheta/dq_b`` (k,);
- ``hessian(q_b, f)``: the diagonal (k,) of d(G^T f)/dq_b for a fixed force ``f`` (geometric
  stiffness; diagonal for every planar point here);
- ``motion(q_b, qd_b)``: position, velocity ``G qd_b``, angle and angular velocity ``g . qd_b`` as
  floats (scalar arithmetic: the clearance joint calls it in every Newton iteration);
- ``generalized_force(q_b, fx, fy, moment)``: the generalised force G^T f + moment g (a list);
- ``affine = (G0, r0)`` and ``rotating_offset``: the split r = r0 + G0 q_b + A(phi) u with a
  constant G0, used by :class:`fewear.mbd.constraints.ConstraintSet` to evaluate all revolute
  joints at once; ``rotating_offset`` is ``(local index of phi, u)`` for a rigid-body point, else
  None.

Rigid body coordinates are ``(x, y, phi)`` of the centre of mass; a point sits at the body-fixed
offset ``u`` so ``r = R + A(phi) u`` (Nikravesh, Computer-Aided Analysis of Mechanical Systems,
1988, ch. 6). An ANCF node carries ``(r1, r2, r_y1, r_y2)``: its position is the node's ``r`` and
the cross-section's angle is that of ``r_y`` minus 90 degrees (zero for an unrotated beam).
"""

from __future__ import annotations

import math

import numpy as np


class GroundPoint:
    """A fixed point of the ground (no coordinates)."""

    rotating_offset = None

    def __init__(self, x_m: float, y_m: float):
        self.indices = np.zeros(0, dtype=int)
        self._r = np.array([x_m, y_m], dtype=float)
        self._x, self._y = float(x_m), float(y_m)
        self.affine = (np.zeros((2, 0)), self._r.copy())

    def position(self, q_b):
        return self._r.copy()

    def jacobian(self, q_b):
        return np.zeros((2, 0))

    def angle(self, q_b):
        return 0.0

    def angle_gradient(self, q_b):
        return np.zeros(0)

    def hessian(self, q_b, f):
        return np.zeros(0)

    def motion(self, q_b, qd_b):
        return self._x, self._y, 0.0, 0.0, 0.0, 0.0

    def generalized_force(self, q_b, fx, fy, moment):
        return []


class RigidPoint:
    """The point at body-fixed offset ``u_m`` from the centre of mass of a rigid body."""

    def __init__(self, first_index: int, u_m=(0.0, 0.0)):
        self.indices = np.arange(first_index, first_index + 3)
        self.u = np.asarray(u_m, dtype=float)
        self._u0, self._u1 = float(self.u[0]), float(self.u[1])
        self._cache = (math.nan, 0.0, 0.0)
        self.affine = (np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), np.zeros(2))
        self.rotating_offset = (2, self.u.copy())

    def _rotated(self, phi):
        """A(phi) u as two floats (scalar maths, cached: these run in every Newton iteration)."""
        cached_phi, au0, au1 = self._cache
        if phi != cached_phi:
            c, s = math.cos(phi), math.sin(phi)
            au0, au1 = c * self._u0 - s * self._u1, s * self._u0 + c * self._u1
            self._cache = (phi, au0, au1)
        return au0, au1

    def position(self, q_b):
        au0, au1 = self._rotated(q_b[2])
        return np.array([q_b[0] + au0, q_b[1] + au1])

    def jacobian(self, q_b):
        au0, au1 = self._rotated(q_b[2])
        return np.array([[1.0, 0.0, -au1], [0.0, 1.0, au0]])

    def angle(self, q_b):
        return q_b[2]

    def angle_gradient(self, q_b):
        return _RIGID_ANGLE_GRADIENT

    def hessian(self, q_b, f):
        au0, au1 = self._rotated(q_b[2])
        return np.array([0.0, 0.0, -(f[0] * au0 + f[1] * au1)])

    def motion(self, q_b, qd_b):
        """(x, y, x', y', phi, phi'): r = R + A u, r' = R' + phi' k x A u."""
        phi, omega = q_b[2], qd_b[2]
        au0, au1 = self._rotated(phi)
        return q_b[0] + au0, q_b[1] + au1, qd_b[0] - omega * au1, qd_b[1] + omega * au0, phi, omega

    def generalized_force(self, q_b, fx, fy, moment):
        """(fx, fy, (A u) x f + moment)."""
        au0, au1 = self._rotated(q_b[2])
        return [fx, fy, au0 * fy - au1 * fx + moment]


_RIGID_ANGLE_GRADIENT = np.array([0.0, 0.0, 1.0])
_NODE_JACOBIAN = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]])


class NodePoint:
    """An ANCF node: coordinates ``(r1, r2, r_y1, r_y2)`` starting at ``first_index``."""

    rotating_offset = None

    def __init__(self, first_index: int):
        self.indices = np.arange(first_index, first_index + 4)
        self.affine = (_NODE_JACOBIAN.copy(), np.zeros(2))

    def position(self, q_b):
        return np.array([q_b[0], q_b[1]], dtype=float)

    def jacobian(self, q_b):
        return _NODE_JACOBIAN

    def angle(self, q_b):
        return math.atan2(q_b[3], q_b[2]) - math.pi / 2

    def angle_gradient(self, q_b):
        """dtheta/dq_b = (0, 0, -r_y2, r_y1) / |r_y|^2."""
        a, b = q_b[2], q_b[3]
        norm2 = a * a + b * b
        return np.array([0.0, 0.0, -b / norm2, a / norm2])

    def hessian(self, q_b, f):
        return np.zeros(4)

    def motion(self, q_b, qd_b):
        """(x, y, x', y', theta, theta') with theta' = (r_y x r_y') / |r_y|^2."""
        a, b = q_b[2], q_b[3]
        omega = (a * qd_b[3] - b * qd_b[2]) / (a * a + b * b)
        return q_b[0], q_b[1], qd_b[0], qd_b[1], math.atan2(b, a) - math.pi / 2, omega

    def generalized_force(self, q_b, fx, fy, moment):
        """(fx, fy, -moment r_y2, moment r_y1) / |r_y|^2 in the slope entries."""
        a, b = q_b[2], q_b[3]
        scale = moment / (a * a + b * b)
        return [fx, fy, -scale * b, scale * a]
