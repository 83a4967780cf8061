"""Planar shear-deformable ANCF beam: 3-node elements with r and r_,y per node (seed eq. 1-3).

Constant mass matrix; elastic forces from the Green-Lagrange strain made locking-free after
Nachbagauer, Pechstein, Irschik & Gerstmayr, Multibody Syst. Dyn. 26 (2011) 245-263 (split
energy, no Poisson coupling, Cowper's shear correction, reduced integration), with the exact
tangent, compiled (numba). In the linear limit it is the Timoshenko beam.
Method notes: docs/dynamics.md.
"""

from __future__ import annotations

import math
import numbers
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError
from fewear.jit import compiled

COORDINATES_PER_NODE = 4
COORDINATES_PER_ELEMENT = 12

_NODE_XI = np.array([0.0, 0.5, 1.0])
_GAUSS2_XI = 0.5 + np.array([-0.5, 0.5]) / math.sqrt(3.0)
_GAUSS2_WEIGHT = np.array([0.5, 0.5])
_LOBATTO3_WEIGHT = np.array([1.0, 4.0, 1.0]) / 6.0
_LAGRANGE_MASS = np.array([[4.0, 2.0, -1.0], [2.0, 16.0, 2.0], [-1.0, 2.0, 4.0]]) / 30.0
_LAGRANGE_INTEGRAL = np.array([1.0, 4.0, 1.0]) / 6.0


def _lagrange(xi: np.ndarray) -> np.ndarray:
    """Quadratic Lagrange functions N1..N3 at xi (seed eq. 3): shape (..., 3)."""
    xi = np.asarray(xi, dtype=float)
    return np.stack([1.0 - 3.0 * xi + 2.0 * xi**2, 4.0 * xi - 4.0 * xi**2, 2.0 * xi**2 - xi], -1)


def _lagrange_dxi(xi: np.ndarray) -> np.ndarray:
    """d N_a / d xi at xi: shape (..., 3)."""
    xi = np.asarray(xi, dtype=float)
    return np.stack([-3.0 + 4.0 * xi, 4.0 - 8.0 * xi, 4.0 * xi - 1.0], -1)


def cowper_shear_correction(poisson_ratio: float) -> float:
    """Cowper's shear correction of a rectangle, kappa = 10 (1 + nu) / (12 + 11 nu).

    G. R. Cowper, J. Appl. Mech. 33 (1966) 335-340.
    """
    return 10.0 * (1.0 + poisson_ratio) / (12.0 + 11.0 * poisson_ratio)


def _is_number(value) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool) and math.isfinite(value)


def _positive(name: str, value: float) -> None:
    if not (_is_number(value) and value > 0.0):
        raise FewearInputError(f"{name} = {value!r}: must be a positive finite number")


@dataclass(frozen=True)
class BeamSection:
    """Material and rectangular cross-section of a beam (SI units).

    ``height_m`` lies in the plane of motion (the bending thickness), ``width_m`` out of plane.
    ``shear_correction`` None means Cowper's kappa for a rectangle. ``damping_time_s`` tau: optional
    Kelvin-Voigt material damping, stress = H (s + tau s') (0: purely elastic; a mode of circular
    frequency omega then has the damping ratio omega tau / 2).
    """

    youngs_modulus_Pa: float
    poisson_ratio: float
    density_kg_m3: float
    height_m: float
    width_m: float
    shear_correction: float | None = None
    damping_time_s: float = 0.0

    def __post_init__(self) -> None:
        _positive("youngs_modulus_Pa", self.youngs_modulus_Pa)
        _positive("density_kg_m3", self.density_kg_m3)
        _positive("height_m", self.height_m)
        _positive("width_m", self.width_m)
        nu = self.poisson_ratio
        if not (_is_number(nu) and -1.0 < nu < 0.5):
            raise FewearInputError(f"poisson_ratio = {nu!r}: must lie in (-1, 0.5)")
        if self.shear_correction is not None:
            kappa = self.shear_correction
            if not (_is_number(kappa) and 0.0 < kappa <= 1.0):
                raise FewearInputError(f"shear_correction = {kappa!r}: must lie in (0, 1] or None")
        if not (_is_number(self.damping_time_s) and self.damping_time_s >= 0.0):
            raise FewearInputError(
                f"damping_time_s = {self.damping_time_s!r}: must be a finite number >= 0")

    @property
    def area_m2(self) -> float:
        return self.height_m * self.width_m

    @property
    def second_moment_m4(self) -> float:
        """I = b h^3 / 12 about the out-of-plane axis."""
        return self.width_m * self.height_m**3 / 12.0

    @property
    def shear_modulus_Pa(self) -> float:
        return self.youngs_modulus_Pa / (2.0 * (1.0 + self.poisson_ratio))

    @property
    def kappa(self) -> float:
        """The shear correction used: given, or Cowper's."""
        if self.shear_correction is None:
            return cowper_shear_correction(self.poisson_ratio)
        return self.shear_correction


# Strain invariants s_i = z^T S_i z / 2 + s0_i of z = (t, d, k) (each a 2-vector), in this order:
# a = (t.t - 1)/2, c = t.k, e = k.k, g = t.d, s = d.k, n = (d.d - 1)/2.
def _invariant_matrices() -> tuple[np.ndarray, np.ndarray]:
    eye = np.eye(2)
    blocks = {"t": slice(0, 2), "d": slice(2, 4), "k": slice(4, 6)}
    pairs = [("t", "t", 1.0), ("t", "k", 1.0), ("k", "k", 2.0), ("t", "d", 1.0), ("d", "k", 1.0),
             ("d", "d", 1.0)]
    matrices = np.zeros((6, 6, 6))
    for i, (u, v, factor) in enumerate(pairs):
        if u == v:
            matrices[i, blocks[u], blocks[u]] = factor * eye
        else:
            matrices[i, blocks[u], blocks[v]] = eye
            matrices[i, blocks[v], blocks[u]] = eye
    offsets = np.array([-0.5, 0.0, 0.0, 0.0, 0.0, -0.5])
    return matrices, offsets


_S, _S0 = _invariant_matrices()
# S_i z by gathering: each row of S_i has at most one non-zero entry, so (S_i z)_m = f * z[index].
_SZ_INDEX = np.argmax(_S != 0.0, axis=2)
_SZ_FACTOR = _S.max(axis=2)
# Each entry (a, b) of the S_i belongs to one invariant at most: S_i[a, b] = _S_ENTRY[a, b] for
# i = _S_INVARIANT[a, b] (-1: none), so sum_i x_i S_i[a, b] is one product.
_S_INVARIANT = np.where((_S != 0.0).any(axis=0), np.argmax(_S != 0.0, axis=0), -1)
_S_ENTRY = _S.sum(axis=0)
# The invariants whose S_i have a non-zero row a (three each): (S_i z)_a is zero for the others.
_INVARIANTS_OF_ROW = np.array([np.nonzero((_S[:, a, :] != 0.0).any(axis=1))[0] for a in range(6)])
# The pattern of an element's strain operator B (6, 12) (AncfBeam._build_strain_operators): row a
# of z = (t, d, k) holds node N's coordinate 4 N + _B_COLUMN_OFFSET[a] (t from r, d and k from
# r_,y); column c of B has the rows _B_ROWS[c % 4] (t or d and k).
_B_COLUMN_OFFSET = np.array([0, 1, 2, 3, 2, 3])
_B_ROWS = np.array([[0, -1], [1, -1], [2, 4], [3, 5]])


class AncfBeam:
    """A straight beam of ``n_elements`` equal 3-node ANCF elements (2n + 1 nodes).

    Generalised coordinates q (length ``n_coordinates`` = 4 (2n + 1)): node k's
    [r_x, r_y, r_,y x, r_,y y] at ``node_index(k)``. Equations of motion M q'' + F(q) = Q.
    """

    def __init__(self, length_m: float, n_elements: int, section: BeamSection):
        _positive("length_m", length_m)
        if not (isinstance(n_elements, (int, np.integer)) and n_elements >= 1):
            raise FewearInputError(f"n_elements = {n_elements!r}: must be an integer >= 1")
        self.length_m = float(length_m)
        self.n_elements = int(n_elements)
        self.section = section
        self.element_length_m = self.length_m / self.n_elements
        self.n_nodes = 2 * self.n_elements + 1
        self.n_coordinates = COORDINATES_PER_NODE * self.n_nodes
        self._element_dofs = (
            8 * np.arange(self.n_elements)[:, None] + np.arange(COORDINATES_PER_ELEMENT)[None, :]
        )
        self._build_strain_operators()
        self._build_assembly_indices()
        self._mass = self._assemble_matrix(
            np.broadcast_to(self._element_mass(), (self.n_elements, 12, 12))
        )

    # -- constant operators -------------------------------------------------------------------
    def _build_strain_operators(self) -> None:
        """B (points, 6, 12) mapping element coordinates to z = (t, d, k), and weights H."""
        length = self.element_length_m
        sec = self.section
        E, h, b = sec.youngs_modulus_Pa, sec.height_m, sec.width_m
        kappa_G = sec.kappa * sec.shear_modulus_Pa
        xi = np.concatenate([_GAUSS2_XI, _NODE_XI])
        weights = length * np.concatenate([_GAUSS2_WEIGHT, _LOBATTO3_WEIGHT])
        n, dn = _lagrange(xi), _lagrange_dxi(xi) / length
        operators = np.zeros((xi.size, 6, COORDINATES_PER_ELEMENT))
        for node in range(3):
            r_cols = slice(4 * node, 4 * node + 2)
            ry_cols = slice(4 * node + 2, 4 * node + 4)
            for p in range(xi.size):
                operators[p, 0:2, r_cols] = dn[p, node] * np.eye(2)
                operators[p, 2:4, ry_cols] = n[p, node] * np.eye(2)
                operators[p, 4:6, ry_cols] = dn[p, node] * np.eye(2)
        axial = b * E * np.array(
            [[h, 0.0, h**3 / 24.0], [0.0, h**3 / 12.0, 0.0], [h**3 / 24.0, 0.0, h**5 / 320.0]]
        )
        energy = np.zeros((xi.size, 6, 6))
        for p in range(2):
            energy[p, :3, :3] = weights[p] * axial
            energy[p, 3, 3] = weights[p] * b * kappa_G * h
            energy[p, 4, 4] = weights[p] * b * kappa_G * h**3 / 12.0
        for p in range(2, 5):
            energy[p, 5, 5] = weights[p] * b * E * h
        self._B = operators
        self._B_stacked_T = np.ascontiguousarray(operators.reshape(-1, COORDINATES_PER_ELEMENT).T)
        self._H = energy

    def _build_assembly_indices(self) -> None:
        dofs = self._element_dofs
        n = self.n_coordinates
        self._vector_index = dofs.ravel()
        self._matrix_index = (dofs[:, :, None] * n + dofs[:, None, :]).ravel()

    def _element_mass(self) -> np.ndarray:
        sec = self.section
        rho_b_l = sec.density_kg_m3 * sec.width_m * self.element_length_m
        mass = np.zeros((12, 12))
        for i in range(3):
            for j in range(3):
                m_ij = _LAGRANGE_MASS[i, j] * rho_b_l
                mass[4 * i : 4 * i + 2, 4 * j : 4 * j + 2] = m_ij * sec.height_m * np.eye(2)
                mass[4 * i + 2 : 4 * i + 4, 4 * j + 2 : 4 * j + 4] = (
                    m_ij * sec.height_m**3 / 12.0 * np.eye(2)
                )
        return mass

    def _assemble_vector(self, element_vectors: np.ndarray) -> np.ndarray:
        return np.bincount(
            self._vector_index, weights=element_vectors.ravel(), minlength=self.n_coordinates
        )

    def _assemble_matrix(self, element_matrices: np.ndarray) -> np.ndarray:
        n = self.n_coordinates
        flat = np.bincount(self._matrix_index, weights=element_matrices.ravel(), minlength=n * n)
        return flat.reshape(n, n)

    # -- geometry ------------------------------------------------------------------------------
    def node_index(self, node: int) -> slice:
        """Where node ``node``'s [r_x, r_y, r_,y x, r_,y y] sit in q.

        Nodes 0 .. 2n sit at arc length s = node l/2 (l the element length); negative counts from
        the end.
        """
        if not (isinstance(node, (int, np.integer)) and -self.n_nodes <= node < self.n_nodes):
            raise FewearInputError(f"node = {node!r}: must be an integer in [0, {self.n_nodes})")
        node = int(node) % self.n_nodes
        return slice(COORDINATES_PER_NODE * node, COORDINATES_PER_NODE * (node + 1))

    def reference_coordinates(self, x0_m: float, y0_m: float, angle_rad: float) -> np.ndarray:
        """The straight, unstressed beam from (x0, y0) along ``angle_rad`` (from the x axis)."""
        c, s = math.cos(angle_rad), math.sin(angle_rad)
        arc = np.arange(self.n_nodes) * (self.element_length_m / 2.0)
        q = np.empty((self.n_nodes, COORDINATES_PER_NODE))
        q[:, 0] = x0_m + c * arc
        q[:, 1] = y0_m + s * arc
        q[:, 2] = -s
        q[:, 3] = c
        return q.ravel()

    def shape_matrix(self, s_m: float, y_m: float = 0.0) -> np.ndarray:
        """S (2, N) with r(s, y) = S q for the material point at arc length s and height y."""
        if not (-1e-12 * self.length_m <= s_m <= self.length_m * (1.0 + 1e-12)):
            raise FewearInputError(f"s_m = {s_m!r}: must lie in [0, {self.length_m}]")
        element = min(int(s_m / self.element_length_m), self.n_elements - 1)
        xi = s_m / self.element_length_m - element
        n = _lagrange(xi)
        shape = np.zeros((2, self.n_coordinates))
        for a in range(3):
            start = 8 * element + 4 * a
            shape[:, start : start + 2] = n[a] * np.eye(2)
            shape[:, start + 2 : start + 4] = y_m * n[a] * np.eye(2)
        return shape

    def position(self, q: np.ndarray, s_m: float, y_m: float = 0.0) -> np.ndarray:
        """r (2,) of the material point at arc length s and height y."""
        return self.shape_matrix(s_m, y_m) @ q

    # -- inertia and gravity -------------------------------------------------------------------
    def mass_matrix(self) -> np.ndarray:
        """Constant consistent mass matrix (N, N) (a copy)."""
        return self._mass.copy()

    def gravity_forces(self, g_m_s2: tuple[float, float] = (0.0, -9.81)) -> np.ndarray:
        """Generalised gravity forces Q = int rho S^T g dV (N,); only the r coordinates load."""
        sec = self.section
        element = np.zeros((self.n_elements, 3, 4))
        weight = sec.density_kg_m3 * sec.area_m2 * self.element_length_m * _LAGRANGE_INTEGRAL
        element[:, :, 0:2] = weight[:, None] * np.asarray(g_m_s2, dtype=float)[None, :]
        return self._assemble_vector(element)

    # -- elasticity ----------------------------------------------------------------------------
    def _strain_state(self, q: np.ndarray):
        """S_i z (elements, points, 6, 6), invariants s and stresses H s (elements, points, 6)."""
        q_elements = np.asarray(q, dtype=float)[self._element_dofs]
        z = (q_elements @ self._B_stacked_T).reshape(self.n_elements, -1, 6)
        s_z = z[..., _SZ_INDEX] * _SZ_FACTOR
        invariants = 0.5 * (s_z @ z[..., None])[..., 0] + _S0
        stress = (self._H @ invariants[..., None])[..., 0]
        return s_z, invariants, stress

    def strain_energy(self, q: np.ndarray) -> float:
        """U(q) (J): the sum over points of s^T H s / 2 (method notes)."""
        _, invariants, stress = self._strain_state(q)
        return 0.5 * float(np.einsum("epi,epi->", invariants, stress))

    def elastic_forces(self, q: np.ndarray) -> np.ndarray:
        """Internal forces F(q) = dU/dq (N,), so that M q'' + F = Q."""
        return self.stiffness_proportional_forces(q, q, 0.0, jacobian=False)[0]

    def stiffness_matrix(self, q: np.ndarray) -> np.ndarray:
        """Tangent stiffness K(q) = dF/dq (N, N), exact and symmetric."""
        return self.elastic_forces_and_stiffness(q)[1]

    def elastic_forces_and_stiffness(self, q: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """F(q) and K(q) from one evaluation of the strains (for Newton iterations)."""
        forces, stiffness, _ = self.stiffness_proportional_forces(q, q, 0.0)
        return forces, stiffness

    def internal_forces(self, q: np.ndarray, qd: np.ndarray):
        """Elastic plus Kelvin-Voigt damping forces and their exact Jacobians (M q'' + F = Q).

        F = B^T sum_i [H (s + tau s')]_i S_i z with s'_i = (S_i z) . z', z' = B q'. Returns
        (F (N,), dF/dq (N, N), dF/dq' (N, N)); dF/dq' = tau B^T sum_ij H_ij (S_i z)(S_j z)^T B
        is tau times the material stiffness (at the unstrained state tau K: stiffness-proportional
        damping); dF/dq adds tau B^T sum_ij H_ij (S_i z)(S_j z')^T B (not symmetric). The damping
        forces vanish for rigid motion (s' = 0) and dissipate tau s'^T H s' >= 0.
        """
        return self._forces(q, qd, self.section.damping_time_s, 0.0, True)

    def stiffness_proportional_forces(self, q: np.ndarray, qd: np.ndarray, beta_s: float,
                                      jacobian: bool = True):
        """F(q) + beta K(q) q' (elastic plus stiffness-proportional damping forces, beta in s) and,
        if ``jacobian``, its exact derivatives d/dq = K + beta d(K q')/dq and d/dq' = beta K.

        K q' = dF/dt is formed without assembling K: with a_i = S_i z, b_i = S_i z', z' = B q' and
        s'_i = a_i . z', K q' = B^T sum_i [(H s)_i b_i + (H s')_i a_i], and
        d(K q')/dq = B^T [sum_i (H s')_i S_i + sum_ij H_ij (b_i a_j^T + a_i b_j^T)] B.
        Returns (forces (N,), d/dq (N, N) or None, d/dq' (N, N) or None).
        """
        return self._forces(q, qd, 0.0, beta_s, jacobian)

    def _forces(self, q, qd, tau_s, beta_s, jacobian):
        """(F, dF/dq, dF/dq') of :func:`add_beam_forces` (the derivatives None if not
        ``jacobian``)."""
        n = self.n_coordinates
        forces = np.zeros(n)
        d_dq, d_dqd = (np.zeros((n, n)), np.zeros((n, n))) if jacobian else (NO_MATRIX,) * 2
        add_beam_forces(np.asarray(q, dtype=float), np.asarray(qd, dtype=float),
                        *self.kernel_data(tau_s, beta_s), 1.0, jacobian, forces, d_dq, d_dqd)
        return (forces, d_dq, d_dqd) if jacobian else (forces, None, None)

    def kernel_data(self, tau_s: float, beta_s: float, first_index: int = 0):
        """(element coordinates (E, 12), B (E, points, 6, 12), H (E, points, 6, 6), tau (E,),
        beta (E,)): the arrays of :func:`add_beam_forces` for this beam at ``first_index`` of q."""
        # np.repeat copies: a broadcast view of one element is contiguous but read-only, a
        # type numba compiles the kernels for once more (tens of seconds on a first run)
        return (first_index + self._element_dofs,
                np.repeat(self._B[None], self.n_elements, axis=0),
                np.repeat(self._H[None], self.n_elements, axis=0),
                np.full(self.n_elements, float(tau_s)), np.full(self.n_elements, float(beta_s)))


# -- compiled element forces ----------------------------------------------------------------------
NO_MATRIX = np.zeros((0, 0))  # the Jacobian arguments of add_beam_forces when none is wanted


@compiled
def _matvec(A, x, out):
    """out = A x (small dense A; explicit loops, no BLAS call or allocation)."""
    for i in range(A.shape[0]):
        total = 0.0
        for j in range(A.shape[1]):
            total += A[i, j] * x[j]
        out[i] = total


@compiled
def _strain_operator_times(B, x, out):
    """out = B x for an element's strain operator B (6, 12): only its three entries a row
    (_B_COLUMN_OFFSET), in the order of the dense product (the zeros add nothing)."""
    for a in range(6):
        total = 0.0
        for node in range(3):
            c = 4 * node + _B_COLUMN_OFFSET[a]
            total += B[a, c] * x[c]
        out[a] = total


@compiled
def _strain_operator_transposed_times(x, B, out):
    """out = B^T x (12,) over the one or two entries of each column of B (_B_ROWS)."""
    for c in range(12):
        rows = _B_ROWS[c % 4]
        total = x[rows[0]] * B[rows[0], c]
        if rows[1] >= 0:
            total += x[rows[1]] * B[rows[1], c]
        out[c] = total


@compiled
def _invariants(s_z, z, z_dot, s, s_rate):
    """s = (S z) . z / 2 + s0 and s' = (S z) . z' (the rows S_i z in ``s_z``)."""
    for i in range(6):
        total, rate = 0.0, 0.0
        for m in range(6):
            total += s_z[i, m] * z[m]
            rate += s_z[i, m] * z_dot[m]
        s[i], s_rate[i] = 0.5 * total + _S0[i], rate


@compiled
def _force_in_z(s_z, s_dot_z, stress, stress_rate, damping, beta, f_z):
    """f_z = sum_i [(H s)_i + (tau + beta) (H s')_i] S_i z + beta (H s)_i S_i z' (``damping`` =
    tau + beta), over the invariants whose row m is not zero (_INVARIANTS_OF_ROW)."""
    for m in range(6):
        total = 0.0
        for n in range(3):
            i = _INVARIANTS_OF_ROW[m, n]
            total += ((stress[i] + damping * stress_rate[i]) * s_z[i, m]
                      + beta * stress[i] * s_dot_z[i, m])
        f_z[m] = total


@compiled
def _gather_invariant_rows(z, rows):
    """rows = the rows S_i z (6, 6) of the six invariants at z (each row of S_i has one entry)."""
    for i in range(6):
        for m in range(6):
            rows[i, m] = _SZ_FACTOR[i, m] * z[_SZ_INDEX[i, m]]


@compiled
def _nonzero_rows(matrix) -> int:
    """The rows of the 6 x 6 ``matrix`` that hold a non-zero entry, as bits (bit a: row a)."""
    rows = 0
    for a in range(6):
        for b in range(6):
            if matrix[a, b] != 0.0:
                rows |= 1 << a
                break
    return rows


@compiled
def _add_projected(B, T, work, target):
    """target += B^T T B for one point (B (6, 12), T (6, 6), target (12, 12); work (6, 12)),
    over the entries of B's pattern (_B_ROWS: column 4 N + k of node N has the row k, and for
    the slopes k = 2, 3 the row k + 2 too) and the rows of T that are not zero (at the nodal
    points, whose energy is that of the thickness invariant alone, two of six), each sum in the
    order of the dense product."""
    active = _nonzero_rows(T)  # bit a: row a of T is not zero
    for a in range(6):
        if active >> a & 1:
            for node in range(3):
                c = 4 * node
                work[a, c] = T[a, 0] * B[0, c]
                work[a, c + 1] = T[a, 1] * B[1, c + 1]
                work[a, c + 2] = T[a, 2] * B[2, c + 2] + T[a, 4] * B[4, c + 2]
                work[a, c + 3] = T[a, 3] * B[3, c + 3] + T[a, 5] * B[5, c + 3]
    for r in range(12):
        k = r % 4
        if active >> k & 1:
            factor = B[k, r]
            for c in range(12):
                target[r, c] += factor * work[k, c]
        if k >= 2 and active >> (k + 2) & 1:
            factor = B[k + 2, r]
            for c in range(12):
                target[r, c] += factor * work[k + 2, c]


@compiled
def _geometric_part(stress, a, b):
    """sum_i stress_i S_i[a, b]: its one term (_S_INVARIANT), or zero."""
    i = _S_INVARIANT[a, b]
    return stress[i] * _S_ENTRY[a, b] if i >= 0 else 0.0


@compiled
def _point_tangents(s_z, s_dot_z, stress, stress_rate, H, tau, beta, elastic, rate, material):
    """Fill (G, R, M) in z (6, 6 each): the elastic tangent G = sum_i (H s)_i S_i + M with the
    material part M = (S z)^T H (S z), and the rate part R = (tau + beta) (sum_i (H s')_i S_i + X)
    + beta X^T with X = (H S z)^T (S z') (AncfBeam.internal_forces and
    stiffness_proportional_forces). ``material`` holds H S z on entry.

    The sums run over their non-zero terms only (_S_INVARIANT, _INVARIANTS_OF_ROW), in their
    order; an entry (a, b) is zero unless the rows a and b of the S_i of the point's invariants
    (the rows of H not zero) are: at the nodal points, whose energy is that of the thickness
    invariant alone, only the 2 x 2 block of d."""
    invariants = _nonzero_rows(H)  # bit i: row i of H is not zero
    rows = 0  # bit a: one of the point's invariants has a non-zero row a
    for a in range(6):
        for n in range(3):
            if invariants >> _INVARIANTS_OF_ROW[a, n] & 1:
                rows |= 1 << a
    h_s_z = material
    for j in range(6):
        for b in range(6):
            total = 0.0
            if invariants >> j & 1:
                for n in range(3):
                    i = _INVARIANTS_OF_ROW[b, n]
                    total += H[j, i] * s_z[i, b]
            h_s_z[j, b] = total
    for a in range(6):
        for b in range(6):
            if not (rows >> a & 1 and rows >> b & 1):
                elastic[a, b], rate[a, b] = 0.0, 0.0
                continue
            geometric = _geometric_part(stress, a, b)
            rate_geometric = _geometric_part(stress_rate, a, b)
            material_ab, cross, cross_t = 0.0, 0.0, 0.0
            for n in range(3):
                j, k = _INVARIANTS_OF_ROW[a, n], _INVARIANTS_OF_ROW[b, n]
                material_ab += s_z[j, a] * h_s_z[j, b]
                cross_t += h_s_z[j, b] * s_dot_z[j, a]
                cross += h_s_z[k, a] * s_dot_z[k, b]
            elastic[a, b] = geometric + material_ab
            rate[a, b] = (tau + beta) * (rate_geometric + cross) + beta * cross_t
    for a in range(6):
        for b in range(6):
            material[a, b] = elastic[a, b] - _geometric_part(stress, a, b)


@compiled
def add_beam_forces(q, qd, dofs, B, H, tau, beta, scale, jacobian, forces, d_dq, d_dqd):
    """Add scale F(q, q') to ``forces`` and, if ``jacobian``, scale dF/dq to ``d_dq`` and
    scale dF/dq' to ``d_dqd``, for the ANCF elements with coordinates ``dofs`` (E, 12) of q
    (global arrays, any beams), with Kelvin-Voigt damping time ``tau`` and stiffness-proportional
    damping ``beta`` (s, per element): F = F_el(q) + beta K(q) q' + tau B^T sum_i (H s')_i S_i z.

    Per integration point: z = B q_e, z' = B q'_e, a_i = S_i z, b_i = S_i z', the invariants
    s_i = a_i . z / 2 + s0_i and their rates s'_i = a_i . z'; the force in z is
    sum_i [(H s)_i + (tau + beta) (H s')_i] a_i + beta (H s)_i b_i (K q' = dF_el/dt formed without
    assembling K), the element forces are B^T of it. dF/dq = B^T (G + R) B,
    dF/dq' = B^T (beta G + tau M) B (:func:`_point_tangents`)."""
    # the work arrays as rows of five allocations (nineteen cost about 1 us a call)
    element_vectors, point_vectors = np.empty((3, 12)), np.empty((7, 6))
    point_matrices, element_matrices = np.empty((5, 6, 6)), np.empty((3, 12, 12))
    q_e, qd_e, f_e = element_vectors[0], element_vectors[1], element_vectors[2]
    z, z_dot, s, s_rate, stress, stress_rate, f_z = (
        point_vectors[0], point_vectors[1], point_vectors[2], point_vectors[3], point_vectors[4],
        point_vectors[5], point_vectors[6])
    s_z, s_dot_z, elastic_z, rate_z, material_z = (
        point_matrices[0], point_matrices[1], point_matrices[2], point_matrices[3],
        point_matrices[4])
    work = np.empty((6, 12))
    stiffness, rate, material = element_matrices[0], element_matrices[1], element_matrices[2]
    for e in range(dofs.shape[0]):
        dofs_e, damping = dofs[e], tau[e] + beta[e]
        for r in range(12):
            q_e[r], qd_e[r] = q[dofs_e[r]], qd[dofs_e[r]]
        if jacobian:
            stiffness[:], rate[:], material[:] = 0.0, 0.0, 0.0
        for p in range(B.shape[1]):
            B_p, H_p = B[e, p], H[e, p]
            _strain_operator_times(B_p, q_e, z)
            _strain_operator_times(B_p, qd_e, z_dot)
            _gather_invariant_rows(z, s_z)
            _gather_invariant_rows(z_dot, s_dot_z)
            _invariants(s_z, z, z_dot, s, s_rate)
            _matvec(H_p, s, stress)
            _matvec(H_p, s_rate, stress_rate)
            _force_in_z(s_z, s_dot_z, stress, stress_rate, damping, beta[e], f_z)
            _strain_operator_transposed_times(f_z, B_p, f_e)
            for r in range(12):
                forces[dofs_e[r]] += scale * f_e[r]
            if jacobian:
                _point_tangents(s_z, s_dot_z, stress, stress_rate, H_p, tau[e], beta[e],
                                elastic_z, rate_z, material_z)
                _add_projected(B_p, elastic_z, work, stiffness)
                if damping != 0.0:
                    _add_projected(B_p, rate_z, work, rate)
                if tau[e] != 0.0:
                    _add_projected(B_p, material_z, work, material)
        if jacobian:
            for r in range(12):
                for c in range(12):
                    d_dq[dofs_e[r], dofs_e[c]] += scale * (stiffness[r, c] + rate[r, c])
                    d_dqd[dofs_e[r], dofs_e[c]] += scale * (beta[e] * stiffness[r, c]
                                                            + tau[e] * material[r, c])
