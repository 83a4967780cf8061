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

from fewear.errors import FewearInputError


class BeamElasticity:
    """The elastic forces of an ANCF beam as a force element, with optional stiffness-proportional
    damping: Q = -F(q) - beta K(q) q', K = dF/dq.

    beta K q' = beta dF/dt vanishes for rigid-body motion (F is invariant under it) and gives a
    mode of frequency omega the damping ratio beta omega / 2 (Rayleigh damping without the mass
    term). Newton uses dQ/dq = -K (the term -beta (dK/dq) q' is left out) and dQ/dq' = -beta K.
    """

    def __init__(self, beam, first_index: int, damping_s: float = 0.0):
        if not (damping_s >= 0.0 and math.isfinite(damping_s)):
            raise FewearInputError(f"beam damping {damping_s!r} s: expected a number >= 0")
        self.beam = beam
        self.damping_s = damping_s
        self.indices = np.arange(first_index, first_index + beam.n_coordinates)

    def evaluate(self, q_b, qd_b, t):
        forces, stiffness = self.beam.elastic_forces_and_stiffness(q_b)
        if self.damping_s == 0.0:
            return -forces, -stiffness, None
        damping = self.damping_s * stiffness
        return -forces - damping @ qd_b, -stiffness, -damping


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
        """Assemble the constant mass matrix and gravity forces; fix the constraint row layout."""
        n = self.n_coordinates
        self.mass = np.zeros((n, n))
        self.gravity_forces = np.zeros(n)
        for first, block in self._mass_blocks:
            k = block.shape[0]
            self.mass[first:first + k, first:first + k] = block
        for first, block in self._gravity_blocks:
            self.gravity_forces[first:first + len(block)] += block
        rows, start = [], 0
        for constraint in self.constraints:
            rows.append(slice(start, start + constraint.n_rows))
            start += constraint.n_rows
        self._rows = rows
        self.n_constraints = start
        self._nonlinear = [(c, rows) for c, rows in zip(self.constraints, rows) if c.nonlinear]
        self._force_blocks = [(e, np.ix_(e.indices, e.indices)) for e in self.force_elements]
        n, m = self.n_coordinates, self.n_constraints
        self._jacobian = np.zeros((m, n))
        self._kkt = np.zeros((n + m, n + m))
        self._kkt[:n, :n] = self.mass
        self._kkt_rhs = np.zeros(n + m)
        return self

    # --- evaluation -------------------------------------------------------------------------
    def constraint_values(self, q, t):
        """Phi(q, t) (m rows)."""
        phi = np.empty(self.n_constraints)
        for c, rows in zip(self.constraints, self._rows):
            phi[rows] = c.value(q[c.indices], t)
        return phi

    def constraint_jacobian(self, q):
        """Phi_q (m, n) (a new array; the sparsity pattern is fixed, so a buffer is refilled)."""
        jac = self._jacobian
        for c, rows in zip(self.constraints, self._rows):
            jac[rows, c.indices] = c.jacobian(q[c.indices])
        return jac.copy()

    def constraint_values_and_jacobian(self, q, t):
        """(Phi, Phi_q) in one pass over the constraints (the Newton iteration needs both)."""
        phi = np.empty(self.n_constraints)
        jac = self._jacobian
        for c, rows in zip(self.constraints, self._rows):
            phi[rows], jac[rows, c.indices] = c.value_and_jacobian(q[c.indices], t)
        return phi, jac.copy()

    def constraint_time_derivative(self, t):
        """Phi_t (m,)."""
        out = np.empty(self.n_constraints)
        for c, rows in zip(self.constraints, self._rows):
            out[rows] = c.time_derivative(t)
        return out

    def constraint_hessian(self, q, lam):
        """d(Phi_q^T lambda)/dq, which is diagonal for these constraints: its diagonal (n,)."""
        H = np.zeros(self.n_coordinates)
        for c, rows in self._nonlinear:
            H[c.indices] += c.hessian(q[c.indices], lam[rows])
        return H

    def constraint_convective(self, q, qd):
        """(dPhi_q/dt) q' (m,)."""
        out = np.empty(self.n_constraints)
        for c, rows in zip(self.constraints, self._rows):
            out[rows] = c.convective(q[c.indices], qd[c.indices])
        return out

    def forces(self, q, qd, t):
        """Q(q, q', t), dQ/dq and dQ/dq' (dense)."""
        n = self.n_coordinates
        Q = self.gravity_forces.copy()
        K = np.zeros((n, n))
        C = np.zeros((n, n))
        for element, block in self._force_blocks:
            idx = element.indices
            Q_b, K_b, C_b = element.evaluate(q[idx], qd[idx], t)
            Q[idx] += Q_b
            if K_b is not None:
                K[block] += K_b
            if C_b is not None:
                C[block] += C_b
        return Q, K, C

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

    def project_velocities(self, q, qd, t):
        """The M-orthogonal projection of q' onto Phi_q q' + Phi_t = 0."""
        jac = self.constraint_jacobian(q)
        n = self.n_coordinates
        A, rhs = self._kkt, self._kkt_rhs
        A[:n, n:] = jac.T
        A[n:, :n] = jac
        rhs[n:] = -(jac @ qd + self.constraint_time_derivative(t))
        return qd + np.linalg.solve(A, rhs)[:n]
