"""The shared contact Newton (fewear.contact.newton): pin update, corner start, turned state."""

import math

import numpy as np
import pytest

from fewear.contact.condensed_newton import support_product, zero_displacement
from fewear.contact.newton_kernels import pin_update, unit

from .test_solver import N_THETA, coarse_problem, rotate


def test_pin_update_straight_below_a_node_spacing_and_turned_above():
    centre = 5e-4 * unit(0.3)
    spacing = math.pi / 144
    small = 0.9 * 5e-4 * spacing * unit(0.3 + 0.5 * math.pi) + 1e-9 * unit(0.3)
    np.testing.assert_array_equal(pin_update(centre, small, spacing), centre + small)
    tangential, radial = 3.0 * 5e-4 * spacing, 2e-9
    large = tangential * unit(0.3 + 0.5 * math.pi) + radial * unit(0.3)
    moved = pin_update(centre, large, spacing)
    assert np.linalg.norm(moved) == pytest.approx(5e-4 + radial, rel=1e-12)
    assert math.atan2(moved[1], moved[0]) == pytest.approx(0.3 + tangential / 5e-4, rel=1e-12)


def test_support_product_sums_the_support_rows_one_after_the_other():
    # nine rows: two passes of four and one row left over; the previous formula, row by row
    rng = np.random.default_rng(3)
    G = rng.standard_normal((40, 40))
    dg = np.zeros(40)
    dg[[0, 3, 4, 5, 9, 10, 11, 17, 39]] = rng.standard_normal(9)
    expected = np.zeros(40)
    for row in np.flatnonzero(dg):
        expected += dg[row] * G[row]
    np.testing.assert_array_equal(support_product(dg, G), expected)


@pytest.fixture(scope="module")
def fast():
    from fewear.contact.condensed import CondensedBushingContact

    return CondensedBushingContact(coarse_problem())


def test_corner_start_touches_two_neighbouring_nodes(fast):
    """The corner c_j lies R_p from both nodes of the pair furthest along d; every other node
    is further; the start presses the pin in along d by |F/L| / (k (w_j + w_j+1))."""
    direction, load = unit(2.0), 40.0 * unit(2.0)
    zero_displacement(fast.newton_state)
    centre = fast.newton._corner(direction, load)
    R_p = fast.problem.geometry.pin_radius_m
    penetration = R_p - np.hypot(*(fast.points - centre).T)
    touching = np.flatnonzero(penetration > 0.0)
    assert touching.size == 2 and abs(touching[1] - touching[0]) == 1
    expected = np.linalg.norm(load) / (fast.problem.penalty_stiffness_Pa_per_m()
                                       * fast.weights_m[touching].sum())
    # both nodes sit at R_p from the corner, the pin is pressed in along d by `expected`
    np.testing.assert_allclose(penetration[touching], expected * (
        (fast.points[touching] - centre) @ direction) / R_p, rtol=1e-6)


def test_turned_state_is_the_solution_of_the_turned_force(fast):
    """On the circular O-grid the compliance is invariant under turns by whole elements, so the
    solution for F turned by m elements (turn_state, rounding the angle to whole elements) is
    the solution for the turned force:
    equal to a fresh solve of it (pin centre to 1e-9 of |c|, nodal pressures to 1e-6 of the
    peak)."""
    force = np.array([1200.0, -2600.0])
    fast.solve(force)
    elements = 3
    fast.turn_state((elements + 0.4) * 2.0 * math.pi / N_THETA)  # to the nearest element
    turned_centre = fast.pin_centre_m.copy()
    _, turned_pressure, _, _ = fast._nodal_forces(fast._U.reshape(-1, 2), turned_centre)
    fast.newton.forget()
    result = fast.solve(rotate(force, elements * 2.0 * math.pi / N_THETA))
    assert np.linalg.norm(result.pin_centre_m - turned_centre) < 1e-9 * np.linalg.norm(
        turned_centre)
    assert np.abs(turned_pressure - result.pressure_Pa).max() < 1e-6 * result.max_pressure_Pa


def test_compile_contact_covers_the_argument_types_of_a_solve(fast):
    """compile_contact (run before worker processes start) calls each kernel with the argument
    types of a solve: after it and a solve with friction, no kernel holds a second signature
    (a worker would compile that one itself)."""
    from numba.core.registry import CPUDispatcher

    from fewear.contact import condensed_newton, newton_kernels

    condensed_newton.compile_contact()
    fast.newton.forget()
    fast.solve((300.0, -2000.0), 0.01, friction=True)
    fast.solve((350.0, -2100.0), 0.01, friction=False)
    kernels = {name: kernel for module in (newton_kernels, condensed_newton)
               for name, kernel in vars(module).items() if isinstance(kernel, CPUDispatcher)}
    assert len(kernels) >= 15
    assert {name: len(kernel.signatures) for name, kernel in kernels.items()
            if len(kernel.signatures) > 1} == {}


def test_both_paths_run_the_one_algorithm():
    """The algorithm is written once (fewear.contact.newton's TEMPLATES): the full path runs
    its code as Python on the solver's methods, the condensed path compiles the same code on its
    own operations, each copy calling the others of its own set."""
    from fewear.contact import condensed_newton, newton, solver

    for template in newton.TEMPLATES:
        full = getattr(solver.FULL_PATH_NEWTON, template.__name__)
        condensed = getattr(condensed_newton.algorithm, template.__name__)
        assert full.__code__ is template.__code__ and condensed.__code__ is template.__code__
        assert full.__globals__["discretisation"] is solver.BushingContactSolver
        assert condensed.__globals__["discretisation"] is condensed_newton
        assert full.__globals__["coupled_newton"] is solver.FULL_PATH_NEWTON.coupled_newton
