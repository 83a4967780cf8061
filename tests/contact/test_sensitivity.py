"""dp/dh of fewear.contact.sensitivity against re-solving the contact with one bore node moved."""


import numpy as np

from fewear.contact.sensitivity import pressure_sensitivity


def test_sensitivity_equals_finite_differences_of_the_contact_solve(coarse_contact):
    """Recede one node in the contact by dh (its point moved outward; the compliance unchanged,
    second order in dh) and solve again under the same force: (p' - p) / dh is J's column."""
    contact = coarse_contact
    force = np.array([-1500.0, 300.0])
    base = contact.solve(force)
    active = np.flatnonzero(base.pressure_Pa > 0.0)
    assert active.size >= 3
    J = pressure_sensitivity(contact.compliance, contact.weights_m, contact.points,
                             base.pin_centre_m, active,
                             contact.problem.penalty_stiffness_Pa_per_m())
    column = active.size // 2
    node = active[column]
    dh = 2e-10
    radial = contact.points[node] / np.linalg.norm(contact.points[node])
    original = contact.points.copy()
    try:
        contact.points[node] = original[node] + dh * radial
        moved = contact.solve(force)
    finally:
        contact.points[:] = original
    finite_difference = (moved.pressure_Pa[active] - base.pressure_Pa[active]) / dh
    scale = np.abs(J[:, column]).max()
    np.testing.assert_allclose(J[:, column], finite_difference, atol=0.02 * scale)
    assert J[column, column] < 0.0  # the receding node sheds load
    # the load is kept: the pressures' change integrates to no force (sum of w dp n = 0)
    normal = contact.points[active] - base.pin_centre_m
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    shed = (contact.weights_m[active] * J[:, column]) @ normal
    assert np.linalg.norm(shed) < 1e-9 * scale * contact.weights_m[active].sum()


def test_one_node_in_contact_gives_no_redistribution():
    compliance = np.eye(6) * 1e-12
    points = np.array([[0.01, 0.0], [0.0, 0.01], [-0.01, 0.0]])
    J = pressure_sensitivity(compliance, np.full(3, 1e-4), points, np.zeros(2), np.array([0]),
                             1e16)
    assert J.shape == (1, 1) and abs(J[0, 0]) < 1e-6


def test_eliminated_form_equals_the_bordered_system():
    """J of the elimination (K = D^-1 + G_n inverted, the pin's balance as a rank-2 correction)
    against the bordered system of the module docstring solved directly in NumPy, on a random
    symmetric positive definite compliance and five nodes in contact: the same J to rounding."""
    rng = np.random.default_rng(3)
    n = 8
    angle = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    points = 0.01 * np.column_stack([np.cos(angle), np.sin(angle)])
    factor = rng.normal(size=(2 * n, 2 * n))
    compliance = 1e-11 * (factor @ factor.T / (2 * n) + np.eye(2 * n))
    weights, penalty = rng.uniform(1e-4, 3e-4, n), 1e15
    active, centre = np.array([0, 1, 2, 6, 7]), np.array([1e-5, -2e-6])
    J = pressure_sensitivity(compliance, weights, points, centre, active, penalty)
    normal = points[active] - centre
    normal /= np.linalg.norm(normal, axis=1)[:, None]
    m = active.size
    blocks = compliance.reshape(n, 2, n, 2)[np.ix_(active, [0, 1], active, [0, 1])]
    normal_compliance = np.einsum("ai,aibj,bj->ab", normal, blocks, normal)
    D = penalty * weights[active]
    system = np.zeros((m + 2, m + 2))
    system[:m, :m] = np.eye(m) + D[:, None] * normal_compliance
    system[:m, m:] = -D[:, None] * normal
    system[m:, :m] = normal.T
    rhs = np.vstack([-np.diag(D), np.zeros((2, m))])
    bordered = np.linalg.solve(system, rhs)[:m] / weights[active][:, None]
    np.testing.assert_allclose(J, bordered, rtol=0, atol=1e-10 * np.abs(bordered).max())
    # the pin stays in balance: each column's force change has no resultant
    assert np.abs((weights[active][:, None] * J).T @ normal).max() < 1e-9 * np.abs(D).max()
