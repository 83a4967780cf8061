"""Material points of planar bodies: where joints and contacts attach.

A point maps its body's coordinates to a position (m) and an angle (rad), with the derivatives
the constraints and the Newton Jacobian need, compiled (numba) for the clearance joint's kernels
and split as r = r0 + G0 q_b + A(phi) u for :class:`fewear.mbd.constraints.ConstraintSet`.
Rigid bodies after Nikravesh (Computer-Aided Analysis of Mechanical Systems, 1988, ch. 6); ANCF
nodes carry (r1, r2, r_y1, r_y2). Method notes: docs/dynamics.md.
"""

from __future__ import annotations

import math

import numpy as np

from fewear.jit import compiled


class GroundPoint:
    """A fixed point of the ground (no coordinates)."""

    rotating_offset = None

    def __init__(self, x_m: float, y_m: float):
        self.indices = np.zeros(0, dtype=int)
        self._r = np.array([x_m, y_m], dtype=float)
        self.affine = (np.zeros((2, 0)), self._r.copy())
        self.kind, self.offset = GROUND, self._r.copy()

    def position(self, q_b):
        return self._r.copy()


class RigidPoint:
    """The point at body-fixed offset ``u_m`` from the centre of mass of a rigid body."""

    def __init__(self, first_index: int, u_m=(0.0, 0.0)):
        self.indices = np.arange(first_index, first_index + 3)
        self.u = np.asarray(u_m, dtype=float)
        self.affine = (np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]), np.zeros(2))
        self.rotating_offset = (2, self.u.copy())
        self.kind, self.offset = RIGID, self.u.copy()

    def position(self, q_b):
        """r = R + A(phi) u."""
        return np.array(point_motion(RIGID, self.offset, np.asarray(q_b, dtype=float),
                                     np.zeros(3))[:2])


class NodePoint:
    """An ANCF node: coordinates ``(r1, r2, r_y1, r_y2)`` starting at ``first_index``."""

    rotating_offset = None

    def __init__(self, first_index: int):
        self.indices = np.arange(first_index, first_index + 4)
        self.affine = (np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0]]), np.zeros(2))
        self.kind, self.offset = NODE, np.zeros(2)

    def position(self, q_b):
        return np.array([q_b[0], q_b[1]], dtype=float)


# -- compiled point kinematics --------------------------------------------------------------------
# A point in compiled code: its kind, its number of coordinates and ``offset`` (the ground point's
# position, the rigid point's body-fixed u; unused for a node).
GROUND, RIGID, NODE = 0, 1, 2
POINT_COORDINATES = (0, 3, 4)


@compiled
def point_motion(kind, offset, q_b, qd_b):
    """(x, y, x', y', theta, theta') of a point: r = R + A(phi) u, r' = R' + phi' k x A u for a
    rigid point; for a node theta = atan2(r_y) - pi/2, theta' = (r_y x r_y') / |r_y|^2."""
    if kind == GROUND:
        return offset[0], offset[1], 0.0, 0.0, 0.0, 0.0
    if kind == RIGID:
        phi, omega = q_b[2], qd_b[2]
        c, s = math.cos(phi), math.sin(phi)
        au0, au1 = c * offset[0] - s * offset[1], s * offset[0] + c * offset[1]
        return (q_b[0] + au0, q_b[1] + au1, qd_b[0] - omega * au1, qd_b[1] + omega * au0, phi,
                omega)
    a, b = q_b[2], q_b[3]
    omega = (a * qd_b[3] - b * qd_b[2]) / (a * a + b * b)
    return q_b[0], q_b[1], qd_b[0], qd_b[1], math.atan2(b, a) - math.pi / 2, omega


@compiled
def point_derivatives(kind, offset, q_b, sign, G, g):
    """Fill ``G`` (2, k) with sign dr/dq_b and ``g`` (k,) with dtheta/dq_b (k = the point's
    coordinates): G = [I, k x A u] and g = (0, 0, 1) for a rigid point, G = [I, 0] and
    g = (0, 0, -r_y2, r_y1) / |r_y|^2 for a node."""
    if kind == RIGID:
        c, s = math.cos(q_b[2]), math.sin(q_b[2])
        au0, au1 = c * offset[0] - s * offset[1], s * offset[0] + c * offset[1]
        G[0, 0], G[0, 1], G[0, 2] = sign, 0.0, -sign * au1
        G[1, 0], G[1, 1], G[1, 2] = 0.0, sign, sign * au0
        g[0], g[1], g[2] = 0.0, 0.0, 1.0
    elif kind == NODE:
        a, b = q_b[2], q_b[3]
        norm2 = a * a + b * b
        for i in range(2):
            for j in range(4):
                G[i, j] = sign if i == j else 0.0
        g[0], g[1], g[2], g[3] = 0.0, 0.0, -b / norm2, a / norm2


@compiled
def add_point_force(kind, offset, q_b, fx, fy, moment, out):
    """out += G^T f + moment g: (fx, fy, (A u) x f + moment) on a rigid point, (fx, fy,
    -moment r_y2, moment r_y1) / |r_y|^2 on a node (in the slope entries)."""
    if kind == RIGID:
        c, s = math.cos(q_b[2]), math.sin(q_b[2])
        au0, au1 = c * offset[0] - s * offset[1], s * offset[0] + c * offset[1]
        out[0] += fx
        out[1] += fy
        out[2] += au0 * fy - au1 * fx + moment
    elif kind == NODE:
        a, b = q_b[2], q_b[3]
        scale = moment / (a * a + b * b)
        out[0] += fx
        out[1] += fy
        out[2] += -scale * b
        out[3] += scale * a


@compiled
def add_point_hessian(kind, offset, q_b, fx, fy, out):
    """out += the diagonal of d(G^T f)/dq_b at fixed f: -(A u) . f in phi for a rigid point (zero
    for the others)."""
    if kind == RIGID:
        c, s = math.cos(q_b[2]), math.sin(q_b[2])
        au0, au1 = c * offset[0] - s * offset[1], s * offset[0] + c * offset[1]
        out[2] -= fx * au0 + fy * au1
