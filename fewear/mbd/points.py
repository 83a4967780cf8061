"""Material points of planar bodies: where joints and contacts attach.

A point maps the coordinates of its body, ``q_b`` (a slice of the system vector given by
``indices``), to a position ``r`` (m) and an angle ``theta`` (rad) of the material line through it,
with the derivatives the constraints and the Newton Jacobian need:

- ``G = dr/dq_b`` (2, k) and ``g = dtheta/dq_b`` (k,);
- ``hessian(q_b, f)``: the diagonal (k,) of d(G^T f)/dq_b for a fixed force ``f`` (geometric
  stiffness; diagonal for every planar point here);
- ``convective(q_b, qd_b) = (dG/dt) qd_b`` (2,): the velocity-product term of the acceleration.

Rigid body coordinates are ``(x, y, phi)`` of the centre of mass; a point sits at the body-fixed
offset ``u`` so ``r = R + A(phi) u`` (Nikravesh, Computer-Aided Analysis of Mechanical Systems,
1988, ch. 6). An ANCF node carries ``(r1, r2, r_y1, r_y2)``: its position is the node's ``r`` and
the cross-section's angle is that of ``r_y`` minus 90 degrees (zero for an unrotated beam).
"""

from __future__ import annotations

import math

import numpy as np


def rotation(angle_rad: float) -> np.ndarray:
    """The planar rotation matrix A(angle)."""
    c, s = np.cos(angle_rad), np.sin(angle_rad)
    return np.array([[c, -s], [s, c]])


class GroundPoint:
    """A fixed point of the ground (no coordinates)."""

    def __init__(self, x_m: float, y_m: float):
        self.indices = np.zeros(0, dtype=int)
        self._r = np.array([x_m, y_m], dtype=float)

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

    def convective(self, q_b, qd_b):
        return np.zeros(2)


class RigidPoint:
    """The point at body-fixed offset ``u_m`` from the centre of mass of a rigid body."""

    def __init__(self, first_index: int, u_m=(0.0, 0.0)):
        self.indices = np.arange(first_index, first_index + 3)
        self.u = np.asarray(u_m, dtype=float)
        self._u0, self._u1 = float(self.u[0]), float(self.u[1])
        self._cache = (math.nan, 0.0, 0.0)

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

    def convective(self, q_b, qd_b):
        au0, au1 = self._rotated(q_b[2])
        w2 = qd_b[2] ** 2
        return np.array([-au0 * w2, -au1 * w2])


_RIGID_ANGLE_GRADIENT = np.array([0.0, 0.0, 1.0])
_NODE_JACOBIAN = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]])


class NodePoint:
    """An ANCF node: coordinates ``(r1, r2, r_y1, r_y2)`` starting at ``first_index``."""

    def __init__(self, first_index: int):
        self.indices = np.arange(first_index, first_index + 4)

    def position(self, q_b):
        return q_b[:2].copy()

    def jacobian(self, q_b):
        return _NODE_JACOBIAN

    def angle(self, q_b):
        return np.arctan2(q_b[3], q_b[2]) - np.pi / 2

    def angle_gradient(self, q_b):
        r_y = q_b[2:4]
        return np.array([0.0, 0.0, -r_y[1], r_y[0]]) / (r_y @ r_y)

    def hessian(self, q_b, f):
        return np.zeros(4)

    def convective(self, q_b, qd_b):
        return np.zeros(2)
