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
