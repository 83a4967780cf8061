"""The compiled kernels that sum only the non-zero terms of their products, against the dense
formulas they replace, computed here with numpy: the ANCF strain operator's products, the point
tangents and B^T T B, the LU of the iteration matrix and its solve (bit for bit against the dense
loops written out below), the Newton residual's M q'' and a clearance joint's coordinates as
views."""

import numpy as np
import pytest
import scipy.linalg

from fewear.mbd import ancf
from fewear.mbd.ancf import AncfBeam, BeamSection
from fewear.mbd.clearance import ClearanceJoint, _local_coordinates, joint_data
from fewear.mbd.contact import ClearanceProfile, ContactLaw, Friction
from fewear.mbd.integrator import _scaled_residual, lu_factor, lu_solve
from fewear.mbd.points import GroundPoint, NodePoint, RigidPoint
from fewear.mbd.system import MultibodySystem

STEEL = {"youngs_modulus_Pa": 2.1e11, "poisson_ratio": 0.3, "density_kg_m3": 7800.0}
ROUNDING = 1e-13  # relative: the dense products sum in another order (BLAS)


def beam_point_states(tau_s=0.0):
    """A deformed, moving 3-element beam: per (element, point) its B, H, z, z' (all 5 points:
    2 Gauss points with the axial, bending and shear energy, 3 nodal ones with the thickness
    energy alone)."""
    beam = AncfBeam(0.34, 3, BeamSection(height_m=0.005, width_m=0.018, damping_time_s=tau_s,
                                         **STEEL))
    rng = np.random.default_rng(11)
    q = beam.reference_coordinates(0.1, 0.2, 0.9)
    q = q + 0.02 * beam.element_length_m * rng.standard_normal(q.size)
    qd = 50.0 * beam.element_length_m * rng.standard_normal(q.size)
    dofs, B, H, _, _ = beam.kernel_data(tau_s, 0.0)
    for e in range(dofs.shape[0]):
        for p in range(B.shape[1]):
            yield B[e, p], H[e, p], B[e, p] @ q[dofs[e]], B[e, p] @ qd[dofs[e]]


def close(actual, expected):
    return np.allclose(actual, expected, rtol=0.0, atol=ROUNDING * np.abs(expected).max())


def test_strain_operator_products_are_the_dense_ones():
    rng = np.random.default_rng(1)
    for B, _, _, _ in beam_point_states():
        x, f = rng.standard_normal(12), rng.standard_normal(6)
        z, forces = np.empty(6), np.empty(12)
        ancf._strain_operator_times(B, x, z)
        ancf._strain_operator_transposed_times(f, B, forces)
        assert close(z, B @ x)
        assert close(forces, B.T @ f)


@pytest.mark.parametrize("tau_s", [0.0, 2e-5])
def test_point_tangents_are_the_dense_formulas(tau_s):
    """G = sum_i (H s)_i S_i + (S z)^T H (S z), X = (H S z)^T (S z'),
    R = (tau + beta) (sum_i (H s')_i S_i + X) + beta X^T, M = (S z)^T H (S z)."""
    beta = 3e-5
    for _, H, z, z_dot in beam_point_states(tau_s):
        s_z = z[ancf._SZ_INDEX] * ancf._SZ_FACTOR
        s_dot_z = z_dot[ancf._SZ_INDEX] * ancf._SZ_FACTOR
        stress = H @ (0.5 * s_z @ z + ancf._S0)
        stress_rate = H @ (s_z @ z_dot)
        material = s_z.T @ H @ s_z
        cross = (H @ s_z).T @ s_dot_z
        elastic = np.einsum("i,iab->ab", stress, ancf._S) + material
        rate = (tau_s + beta) * (np.einsum("i,iab->ab", stress_rate, ancf._S) + cross) \
            + beta * cross.T
        out = [np.full((6, 6), np.nan) for _ in range(3)]
        ancf._point_tangents(s_z, s_dot_z, stress, stress_rate, H, tau_s, beta, *out)
        for actual, expected in zip(out, (elastic, rate, material)):
            assert close(actual, expected)


def test_projection_is_the_dense_product():
    """target + B^T T B, for the points' tangents (at the nodal points T has the d block alone)
    and for a dense T."""
    rng = np.random.default_rng(2)
    zero_rows = 0
    for B, H, z, _ in beam_point_states():
        s_z = z[ancf._SZ_INDEX] * ancf._SZ_FACTOR
        elastic = s_z.T @ H @ s_z
        zero_rows += np.sum(~elastic.any(axis=1))
        for T in (elastic, rng.standard_normal((6, 6))):
            start = rng.standard_normal((12, 12))
            target, work = start.copy(), np.empty((6, 12))
            ancf._add_projected(B, T, work, target)
            assert close(target, start + B.T @ T @ B)
    assert zero_rows > 0  # the rows the kernel skips were met


def dense_elimination(A):
    """Golub & Van Loan alg. 3.4.1 as lu_factor's loops were before they skipped zeros: every
    row below the pivot, every column right of it."""
    A = A.copy()
    size = A.shape[0]
    pivots = np.zeros(size, dtype=np.int64)
    for k in range(size):
        pivot = k
        for i in range(k + 1, size):
            if abs(A[i, k]) > abs(A[pivot, k]):
                pivot = i
        pivots[k] = pivot
        A[[k, pivot]] = A[[pivot, k]]
        inverse = 1.0 / A[k, k]
        for i in range(k + 1, size):
            A[i, k] *= inverse
            factor = A[i, k]
            if factor != 0.0:
                for c in range(k + 1, size):
                    A[i, c] -= factor * A[k, c]
    return A, pivots


def sparse_kkt_matrix(n=30, m=5, band=6, seed=4):
    """[[S, J^T], [J, 0]]: S banded (plus a dense corner block), J sparse."""
    rng = np.random.default_rng(seed)
    S = np.zeros((n, n))
    for r in range(n):
        for c in range(max(0, r - band), min(n, r + band + 1)):
            S[r, c] = rng.standard_normal() * (10.0 if r == c else 1.0)
    S[-3:, -3:] += rng.standard_normal((3, 3))
    J = np.zeros((m, n))
    for row in range(m):
        J[row, rng.choice(n, 3, replace=False)] = rng.standard_normal(3)
    return np.block([[S, J.T], [J, np.zeros((m, m))]])


def dense_substitution(factors, pivots, b):
    """lu_solve's loops before they skipped zeros."""
    b = b.copy()
    size = b.size
    for k in range(size):
        b[[k, pivots[k]]] = b[[pivots[k], k]]
    for i in range(size):
        for c in range(i):
            b[i] -= factors[i, c] * b[c]
    for i in range(size - 1, -1, -1):
        for c in range(i + 1, size):
            b[i] -= factors[i, c] * b[c]
        b[i] /= factors[i, i]
    return b


@pytest.mark.parametrize("seed", [4, 5, 6])
def test_lu_is_bit_for_bit_the_dense_elimination_and_substitution(seed):
    A = sparse_kkt_matrix(seed=seed)
    expected, expected_pivots = dense_elimination(A)
    factors, structure = A.copy(), np.zeros((A.shape[0], A.shape[0] + 3), dtype=np.int64)
    assert lu_factor(factors, structure)
    assert np.array_equal(factors, expected)
    assert np.array_equal(structure[:, 0], expected_pivots)
    assert structure[:, 1:3].sum() < 0.6 * A.size  # the non-zeros it visits
    b = np.random.default_rng(seed).standard_normal(A.shape[0])
    x = b.copy()
    lu_solve(factors, structure, x)
    assert np.array_equal(x, dense_substitution(expected, expected_pivots, b))
    assert np.allclose(x, scipy.linalg.solve(A, b), rtol=1e-10, atol=0.0)


def test_lu_factor_reports_a_singular_matrix():
    A = sparse_kkt_matrix()
    A[:, 3] = 0.0
    assert not lu_factor(A, np.zeros((A.shape[0], A.shape[0] + 3), dtype=np.int64))


def test_newton_residual_is_the_dense_formula():
    """beta h^2 (M q'' + Phi_q^T lambda - Q) with M's non-zero entries only (a beam and two
    rigid bodies)."""
    system = MultibodySystem()
    system.add_rigid_body(0.3, 1e-3)
    system.add_beam(AncfBeam(0.34, 3, BeamSection(height_m=0.005, width_m=0.018, **STEEL)))
    system.add_rigid_body(0.5, 2e-3)
    system.finalize()
    n, m = system.n_coordinates, 4
    rng = np.random.default_rng(3)
    qdd, Q, lam = rng.standard_normal(n), rng.standard_normal(n), rng.standard_normal(m)
    jac = rng.standard_normal((m, n))
    out = np.full(n + m, np.nan)
    _scaled_residual(system.data, qdd, jac, lam, Q, 2.5e-10, out)
    expected = 2.5e-10 * (system.mass @ qdd + jac.T @ lam - Q)
    assert close(out[:n], expected)
    assert system.data.mass_columns.size < 0.5 * n * n  # the sparsity it uses


def test_joint_coordinates_are_the_points_entries_of_q():
    law, friction = ContactLaw("lankarani-nikravesh", 4.0e10), Friction(0.1)
    joints = [ClearanceJoint(NodePoint(7), RigidPoint(2), 0.0095, 0.010,
                             ClearanceProfile.constant(5e-4), law, friction),
              ClearanceJoint(RigidPoint(11), GroundPoint(0.1, 0.2), 0.0095, 0.010,
                             ClearanceProfile.constant(5e-4), law, friction)]
    data = joint_data(joints)
    q = np.random.default_rng(8).standard_normal(16)
    for j, joint in enumerate(joints):
        pin, bushing = _local_coordinates(data, j, q)
        assert np.array_equal(pin, q[joint.pin.indices])
        assert np.array_equal(bushing, q[joint.bushing.indices])
    apart = RigidPoint(2)
    apart.indices = np.array([2, 3, 5])
    with pytest.raises(ValueError, match="apart"):
        joint_data([ClearanceJoint(NodePoint(7), apart, 0.0095, 0.010,
                                   ClearanceProfile.constant(5e-4), law, friction)])
