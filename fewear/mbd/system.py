"""A small planar multibody system: M q'' + Phi_q^T lambda = Q(q, q', t), Phi(q, t) = 0.

Coordinates are absolute: ``(x, y, phi)`` of each rigid body's centre of mass and the nodal
coordinates of each ANCF beam. In these coordinates the mass matrix is constant (rigid bodies:
diag(m, m, J); ANCF: the consistent mass, Shabana 2005 ch. 7) and a planar rigid body has no
velocity-product inertia terms, so M is assembled once. The forces are gravity (constant), the
beams' elastic forces and the force elements (the clearance joints); each force element returns its
generalized force and the analytic derivatives dQ/dq and dQ/dq' used by the Newton iteration.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.linalg import lapack

from fewear.errors import FewearInputError
from fewear.mbd.ancf import NO_MATRIX, add_beam_forces
from fewear.mbd.constraints import ConstraintSet


def _block_indices(indices):
    """(vector index, matrix block index) of a force element's coordinates: slices when they are
    contiguous (an ANCF beam: plain slicing is several times faster than fancy indexing)."""
    if len(indices) and np.array_equal(indices, np.arange(indices[0], indices[0] + len(indices))):
        block = slice(int(indices[0]), int(indices[0]) + len(indices))
        return block, (block, block)
    return indices, np.ix_(indices, indices)


class BeamElasticity:
    """The elastic forces of an ANCF beam as a force element, with optional stiffness-proportional
    damping: Q = -F(q) - beta K(q) q', K = dF/dq.

    beta K q' = beta dF/dt vanishes for rigid-body motion (F is invariant under it) and gives a
    mode of frequency omega the damping ratio beta omega / 2 (Rayleigh damping without the mass
    term). Newton gets the exact dQ/dq = -K - beta d(K q')/dq and dQ/dq' = -beta K
    (:meth:`fewear.mbd.ancf.AncfBeam.stiffness_proportional_forces`).
    """

    def __init__(self, beam, first_index: int, damping_s: float = 0.0):
        if not (damping_s >= 0.0 and math.isfinite(damping_s)):
            raise FewearInputError(f"beam damping {damping_s!r} s: expected a number >= 0")
        self.beam = beam
        self.damping_s = damping_s
        self.indices = np.arange(first_index, first_index + beam.n_coordinates)
        self._kernel_data = beam.kernel_data(0.0, damping_s)

    def evaluate(self, q_b, qd_b, t, jacobian: bool = True):
        """(Q, dQ/dq, dQ/dq'); the derivatives are None if not ``jacobian`` (dQ/dq' also
        without damping)."""
        k = len(q_b)
        Q = np.zeros(k)
        K, C = (np.zeros((k, k)), np.zeros((k, k))) if jacobian else (NO_MATRIX,) * 2
        add_beam_forces(q_b, qd_b, *self._kernel_data, -1.0, jacobian, Q, K, C)
        if not jacobian:
            return Q, None, None
        return Q, K, (C if self.damping_s else None)


class MultibodySystem:
    """Bodies, constraints and force elements; the vectors and matrices the integrator needs."""

    def __init__(self, gravity_m_s2=(0.0, -9.81)):
        self.gravity = np.asarray(gravity_m_s2, dtype=float)
        self._mass_blocks: list[tuple[int, np.ndarray]] = []
        self._gravity_blocks: list[tuple[int, np.ndarray]] = []
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
        ``damping_s`` (see BeamElasticity); return the index of its first coordinate."""
        first = self.n_coordinates
        self._mass_blocks.append((first, np.asarray(beam.mass_matrix(), dtype=float)))
        self._gravity_blocks.append((first, np.asarray(beam.gravity_forces(self.gravity))))
        self.force_elements.append(BeamElasticity(beam, first, damping_s))
        self.n_coordinates += beam.n_coordinates
        return first

    def add_constraint(self, constraint) -> None:
        self.constraints.append(constraint)

    def add_force(self, element) -> None:
        self.force_elements.append(element)

    def finalize(self) -> MultibodySystem:
        """Assemble the constant mass matrix (and its inverse) and gravity forces; fix the
        constraint rows."""
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
        self._constrained = self.constraint_set.columns
        self._constrained_inverse_mass = self.inverse_mass[self._constrained]
        self._rows = self.constraint_set.rows
        self.n_constraints = self.constraint_set.n_rows
        self._force_blocks = [(e, *_block_indices(e.indices)) for e in self.force_elements]
        return self

    # --- evaluation -------------------------------------------------------------------------
    def constraint_values_and_jacobian(self, q, t):
        """(Phi, Phi_q): Phi_q is a buffer, valid until the next constraint evaluation."""
        return self.constraint_set.values_and_jacobian(q, t)

    def constraint_jacobian(self, q):
        """Phi_q (m, n) (a new array)."""
        return self.constraint_set.jacobian(q)

    def constraint_time_derivative(self, t):
        """Phi_t (m,) (constant for these constraints)."""
        return self.constraint_set.c1

    def constraint_hessian(self, q, lam):
        """d(Phi_q^T lambda)/dq, which is diagonal for these constraints: its diagonal (n,)."""
        return self.constraint_set.hessian(q, lam)

    def constraint_convective(self, q, qd):
        """(dPhi_q/dt) q' (m,)."""
        return self.constraint_set.convective(q, qd)

    def forces(self, q, qd, t, jacobian: bool = True):
        """Q(q, q', t), dQ/dq and dQ/dq' (dense, or None where no element contributes; both None
        if not ``jacobian``)."""
        Q = self.gravity_forces.copy()
        K = C = None
        for element, idx, block in self._force_blocks:
            Q_b, K_b, C_b = element.evaluate(q[idx], qd[idx], t, jacobian)
            Q[idx] += Q_b
            if K_b is not None:
                K = self._zeros() if K is None else K
                K[block] += K_b
            if C_b is not None:
                C = self._zeros() if C is None else C
                C[block] += C_b
        return Q, K, C

    def _zeros(self):
        return np.zeros((self.n_coordinates, self.n_coordinates))

    def kinetic_energy(self, qd):
        return 0.5 * qd @ self.mass @ qd

    def gravity_potential(self, q):
        return -self.gravity_forces @ q

    # --- consistent initial values ------------------------------------------------------------
    def consistent_accelerations(self, q, qd, t):
        """Solve M q'' + Phi_q^T lambda = Q, Phi_q q'' = -(dPhi_q/dt) q' for (q'', lambda)."""
        Q, _, _ = self.forces(q, qd, t)
        jac = self.constraint_jacobian(q)
        m = self.n_constraints
        A = np.block([[self.mass, jac.T], [jac, np.zeros((m, m))]])
        rhs = np.concatenate([Q, -self.constraint_convective(q, qd)])
        sol = np.linalg.solve(A, rhs)
        return sol[: self.n_coordinates], sol[self.n_coordinates:]

    def project_velocities(self, q, qd, t, jacobian=None):
        """The M-orthogonal projection of q' onto Phi_q q' + Phi_t = 0.

        Through the Schur complement of the KKT system [[M, Phi_q^T], [Phi_q, 0]]:
        (Phi_q M^-1 Phi_q^T) mu = Phi_q q' + Phi_t, q' <- q' - M^-1 Phi_q^T mu. ``jacobian``: Phi_q
        if the caller has it at q (the integrator passes its last Newton Jacobian). Phi_q is zero
        outside the columns the constraints touch, so the products run over those only."""
        columns = self._constrained
        jac = (self.constraint_jacobian(q) if jacobian is None else jacobian)[:, columns]
        weighted = jac @ self._constrained_inverse_mass
        schur = weighted[:, columns] @ jac.T
        _, mu, info = lapack.dposv(schur, jac @ qd[columns] + self.constraint_time_derivative(t))
        if info != 0:
            raise np.linalg.LinAlgError("velocity projection: Phi_q has dependent rows")
        return qd - mu @ weighted
