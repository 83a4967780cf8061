"""A small planar multibody system: M q'' + Phi_q^T lambda = Q(q, q', t), Phi(q, t) = 0.

Coordinates are absolute: ``(x, y, phi)`` of each rigid body's centre of mass and the nodal
coordinates of each ANCF beam. In these coordinates the mass matrix is constant (rigid bodies:
diag(m, m, J); ANCF: the consistent mass, Shabana 2005 ch. 7) and a planar rigid body has no
velocity-product inertia terms, so M is assembled once. The forces are gravity (constant), the
beams' elastic forces with stiffness-proportional damping Q = -F(q) - beta K(q) q' (K = dF/dq:
beta K q' = beta dF/dt vanishes for rigid-body motion and gives a mode of frequency omega the
damping ratio beta omega / 2, Rayleigh damping without the mass term) and the force elements (the
clearance joints), each with the analytic derivatives dQ/dq and dQ/dq' used by the Newton
iteration.

:meth:`MultibodySystem.finalize` packs the whole system into one :data:`SystemData` of arrays,
which the compiled functions (:func:`system_forces` and the integrator's step) evaluate.
"""

from __future__ import annotations

import math
from collections import namedtuple

import numpy as np

from fewear.errors import FewearInputError
from fewear.jit import compiled
from fewear.mbd.ancf import add_beam_forces
from fewear.mbd.clearance import ClearanceJoint, add_joint_forces, joint_data
from fewear.mbd.constraints import ConstraintSet

SystemData = namedtuple("SystemData", [
    "mass", "inverse_mass", "gravity_forces",  # (n, n), (n, n), (n,)
    "mass_row_start", "mass_columns",  # the non-zero entries of M by rows (n + 1,), (nnz,)
    "beam_dofs", "beam_B", "beam_H", "beam_tau", "beam_beta",  # ancf.add_beam_forces (all beams)
    "D", "c0", "c1", "offset_rows", "offset_columns", "offset_u",  # constraints.py
    "drives",  # constraints.Drives (tabulated drivers)
    "joints",  # clearance.JointData
])


class MultibodySystem:
    """Bodies, constraints and force elements; the vectors and matrices the integrator needs."""

    def __init__(self, gravity_m_s2=(0.0, -9.81)):
        self.gravity = np.asarray(gravity_m_s2, dtype=float)
        self._mass_blocks: list[tuple[int, np.ndarray]] = []
        self._gravity_blocks: list[tuple[int, np.ndarray]] = []
        self._beams: list[tuple] = []  # the arrays of add_beam_forces of each beam
        self.constraints: list = []
        self.force_elements: list = []
        self.n_coordinates = 0

    # --- building ---------------------------------------------------------------------------
    def add_rigid_body(self, mass_kg: float, inertia_kg_m2: float, name: str = "body") -> int:
        """Add a rigid body; return the index of its first coordinate (x, y, phi follow)."""
        if not (mass_kg > 0.0 and np.isfinite(mass_kg)):
            raise FewearInputError(f"{name} mass {mass_kg!r} kg: expected a positive number")
        if not (inertia_kg_m2 > 0.0 and np.isfinite(inertia_kg_m2)):
            raise FewearInputError(
                f"{name} moment of inertia {inertia_kg_m2!r} kg m^2: expected a positive number")
        first = self.n_coordinates
        self._mass_blocks.append((first, np.diag([mass_kg, mass_kg, inertia_kg_m2])))
        self._gravity_blocks.append((first, np.array([*(mass_kg * self.gravity), 0.0])))
        self.n_coordinates += 3
        return first

    def add_beam(self, beam, damping_s: float = 0.0) -> int:
        """Add an ANCF beam (fewear.mbd.ancf.AncfBeam) with stiffness-proportional damping
        ``damping_s`` (module docstring); return the index of its first coordinate."""
        if not (damping_s >= 0.0 and math.isfinite(damping_s)):
            raise FewearInputError(f"beam damping {damping_s!r} s: expected a number >= 0")
        first = self.n_coordinates
        self._mass_blocks.append((first, np.asarray(beam.mass_matrix(), dtype=float)))
        self._gravity_blocks.append((first, np.asarray(beam.gravity_forces(self.gravity))))
        self._beams.append(beam.kernel_data(0.0, damping_s, first))
        self.n_coordinates += beam.n_coordinates
        return first

    def add_constraint(self, constraint) -> None:
        self.constraints.append(constraint)

    def add_force(self, element) -> None:
        """Add a force element (a :class:`fewear.mbd.clearance.ClearanceJoint`)."""
        if not isinstance(element, ClearanceJoint):
            raise TypeError(f"unsupported force element {element!r}")
        self.force_elements.append(element)

    def finalize(self) -> MultibodySystem:
        """Assemble the constant mass matrix (and its inverse) and gravity forces, fix the
        constraint rows and pack the system into :attr:`data`."""
        n = self.n_coordinates
        self.mass = np.zeros((n, n))
        self.gravity_forces = np.zeros(n)
        for first, block in self._mass_blocks:
            k = block.shape[0]
            self.mass[first:first + k, first:first + k] = block
        for first, block in self._gravity_blocks:
            self.gravity_forces[first:first + len(block)] += block
        self.inverse_mass = np.linalg.inv(self.mass)
        self.constraint_set = ConstraintSet(self.constraints, n)
        self._rows = self.constraint_set.rows
        self.n_constraints = self.constraint_set.n_rows
        joints = joint_data(self.force_elements)
        for j, element in enumerate(self.force_elements):
            element.share_memory(joints.memory[j:j + 1])
        rows, columns = np.nonzero(self.mass)  # row by row, the columns ascending
        self.data = SystemData(self.mass, self.inverse_mass, self.gravity_forces,
                               np.searchsorted(rows, np.arange(n + 1)), columns,
                               *self._beam_arrays(), *self.constraint_set.kernel_data,
                               self.constraint_set.drives, joints)
        return self

    def _beam_arrays(self):
        """The beams' arrays of add_beam_forces, all elements of all beams concatenated."""
        if not self._beams:
            return (np.zeros((0, 12), dtype=np.int64), np.zeros((0, 5, 6, 12)),
                    np.zeros((0, 5, 6, 6)), np.zeros(0), np.zeros(0))
        return tuple(np.concatenate(arrays) for arrays in zip(*self._beams))

    # --- evaluation -------------------------------------------------------------------------
    def forces(self, q, qd, t):
        """(Q(q, q', t), dQ/dq, dQ/dq') (:func:`system_forces`)."""
        n = self.n_coordinates
        Q, K, C = np.zeros(n), np.zeros((n, n)), np.zeros((n, n))
        system_forces(self.data, np.asarray(q, dtype=float), np.asarray(qd, dtype=float), t,
                      True, Q, K, C)
        return Q, K, C

    def kinetic_energy(self, qd):
        return 0.5 * qd @ self.mass @ qd

    def gravity_potential(self, q):
        return -self.gravity_forces @ q

    # --- consistent initial values ------------------------------------------------------------
    def consistent_accelerations(self, q, qd, t):
        """Solve M q'' + Phi_q^T lambda = Q, Phi_q q'' = -(dPhi_q/dt) q' - Phi_tt for
        (q'', lambda)."""
        Q, _, _ = self.forces(q, qd, t)
        jac = self.constraint_set.jacobian(q)
        m = self.n_constraints
        A = np.block([[self.mass, jac.T], [jac, np.zeros((m, m))]])
        rhs = np.concatenate([Q, -self.constraint_set.convective(q, qd, t)])
        sol = np.linalg.solve(A, rhs)
        return sol[: self.n_coordinates], sol[self.n_coordinates:]


@compiled
def system_forces(data, q, qd, t, jacobian, Q, K, C):
    """Fill Q(q, q', t) and, if ``jacobian``, K = dQ/dq and C = dQ/dq': gravity, the beams'
    -F - beta K q' (:func:`fewear.mbd.ancf.add_beam_forces`) and the clearance joints
    (:func:`fewear.mbd.clearance.add_joint_forces`)."""
    Q[:] = data.gravity_forces
    if jacobian:
        K[:] = 0.0
        C[:] = 0.0
    add_beam_forces(q, qd, data.beam_dofs, data.beam_B, data.beam_H, data.beam_tau,
                    data.beam_beta, -1.0, jacobian, Q, K, C)
    for j in range(data.joints.memory.shape[0]):
        add_joint_forces(data.joints, j, q, qd, jacobian, Q, K, C)
