"""The full Newton contact solve: invariants that any correct solution must satisfy.

Coarse O-grid (80 elements around the bore, 6 across the wall): these checks do not depend on
the discretisation error. Hertz and the cosine law (the discretisation checks) are in
test_hertz.py and test_conformal.py.
"""

import dataclasses
import math

import numpy as np
import pytest

from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
from fewear.errors import FewearInputError
from fewear.io.config import load_config

N_THETA = 80


def coarse_problem(penalty_factor=None):
    problem = contact_problem_from_config(load_config(None, CONFIG_SECTIONS))
    size = 2 * math.pi * problem.geometry.inner_radius_m / N_THETA * (1 + 1e-9)
    mesh = dataclasses.replace(problem.mesh, bore_element_size_m=size, radial_element_count=6)
    contact = problem.contact
    if penalty_factor is not None:
        contact = dataclasses.replace(contact, penalty_factor=penalty_factor)
    return dataclasses.replace(problem, mesh=mesh, contact=contact)


@pytest.fixture(scope="module")
def mesh_data():
    from fewear.mesh.bushing import bushing_mesh

    problem = coarse_problem()
    return bushing_mesh(problem.geometry, problem.mesh)


@pytest.fixture(scope="module")
def solver(mesh_data):
    from fewear.contact.solver import BushingContactSolver

    return BushingContactSolver(coarse_problem(), mesh_data=mesh_data)


def rotate(vector, angle):
    c, s = math.cos(angle), math.sin(angle)
    return np.array([c * vector[0] - s * vector[1], s * vector[0] + c * vector[1]])


def pressure_at(result, angles):
    """Nodal pressure at the nodes nearest to the given angles (they are nodes of the mesh)."""
    difference = np.angle(np.exp(1j * (result.angle_rad[None, :] - np.asarray(angles)[:, None])))
    index = np.argmin(np.abs(difference), axis=1)
    assert np.abs(difference[np.arange(index.size), index]).max() < 1e-7   # gmsh: ~5e-9 rad
    return result.pressure_Pa[index]


def test_zero_force_gives_no_contact_and_a_centred_pin(solver):
    solver.solve((0.0, -800.0))
    result = solver.solve((0.0, 0.0))
    assert result.max_pressure_Pa == 0.0
    assert result.contact_half_angle_rad == 0.0
    np.testing.assert_array_equal(result.pin_centre_m, 0.0)
    np.testing.assert_allclose(result.gap_m, solver.problem.geometry.clearance_m, rtol=1e-12)
    np.testing.assert_array_equal(result.slip_m, 0.0)
    assert result.newton_iterations == 0


def test_bore_nodes_are_vertices_and_midpoints_sorted_by_angle(solver):
    result = solver.solve((300.0, 200.0))
    assert result.angle_rad.size == 2 * N_THETA
    assert np.all(np.diff(result.angle_rad) > 0) and 0 <= result.angle_rad[0] < 2 * math.pi
    np.testing.assert_allclose(np.diff(result.angle_rad), math.pi / N_THETA, rtol=1e-7)
    np.testing.assert_allclose(np.hypot(result.x_m, result.y_m), 0.010, rtol=1e-13)


@pytest.mark.parametrize("force", [(0.0, -2000.0), (1500.0, 4000.0), (-30.0, 7.0)])
@pytest.mark.parametrize("friction", [False, True])
def test_resultant_of_contact_tractions_balances_the_force(solver, force, friction):
    result = solver.solve(force, rotation_increment_rad=0.02, friction=friction)
    assert result.force_balance_rel_error < 1e-8
    assert result.max_pressure_Pa > 0.0
    # the pin moved by more than the clearance (it presses into the bore), toward the load
    assert np.linalg.norm(result.pin_centre_m) > solver.problem.geometry.clearance_m
    assert result.pin_centre_m @ np.asarray(force) > 0.99 * np.linalg.norm(
        result.pin_centre_m) * np.linalg.norm(force)


def test_symmetric_load_gives_a_symmetric_field(solver):
    """Load along -y, a symmetry axis of the O-grid: p(pi - theta) = p(theta)."""
    result = solver.solve((0.0, -9000.0))
    mirrored = pressure_at(result, math.pi - result.angle_rad)
    scale = result.max_pressure_Pa
    assert np.abs(mirrored - result.pressure_Pa).max() < 1e-8 * scale
    # gmsh places the arc nodes to ~1e-10 rad: the pin may leave the axis by ~1e-12 m
    approach = abs(result.pin_centre_m[1]) - solver.problem.geometry.clearance_m
    assert abs(result.pin_centre_m[0]) < 1e-5 * approach
    assert np.count_nonzero(result.pressure_Pa) >= 5


@pytest.mark.parametrize("quarter_turns", [1, 2, 3])
def test_rotating_the_load_rotates_the_solution(solver, quarter_turns):
    """The O-grid is invariant under quarter turns: so must the solution be."""
    force = np.array([1200.0, -2500.0])
    base = solver.solve(force)
    turn = quarter_turns * math.pi / 2
    turned = solver.solve(rotate(force, turn))
    scale = base.max_pressure_Pa
    assert np.abs(pressure_at(turned, base.angle_rad + turn) - base.pressure_Pa).max() < (
        1e-8 * scale)
    np.testing.assert_allclose(turned.pin_centre_m, rotate(base.pin_centre_m, turn),
                               rtol=0, atol=1e-9 * np.linalg.norm(base.pin_centre_m))
    assert turned.contact_half_angle_rad == pytest.approx(base.contact_half_angle_rad, rel=1e-6)


def test_results_converge_as_the_penalty_grows(mesh_data):
    """Penalty error ~ 1/k: successive differences of the peak pressure and the pin centre
    halve when k doubles (fitted rate -1), i.e. a Cauchy sequence converging as 1/k. (Below a
    factor of ~200 this coarse mesh still changes its set of loaded nodes with k.)"""
    from fewear.contact.solver import BushingContactSolver

    factors = [200.0, 400.0, 800.0, 1600.0]
    peaks, centres = [], []
    for factor in factors:
        solver = BushingContactSolver(coarse_problem(factor), mesh_data=mesh_data)
        result = solver.solve((0.0, -4000.0))
        peaks.append(result.max_pressure_Pa)
        centres.append(result.pin_centre_m[1])
    for values in (np.array(peaks), np.array(centres)):
        differences = np.abs(np.diff(values))
        rate = np.polyfit(np.log(factors[1:]), np.log(differences), 1)[0]
        assert rate == pytest.approx(-1.0, abs=0.15)
    assert abs(peaks[-1] - peaks[-2]) < 1e-3 * peaks[-1]


@pytest.mark.parametrize("sign", [1.0, -1.0])
def test_coulomb_friction_tilts_the_normal_resultant_by_atan_mu(solver, sign):
    """With a narrow arc the contact traction p (n + mu s t) has the direction of n turned by
    atan(mu s): the pressure resultant must lie atan(mu) away from the force, on the side
    against the pin's rotation; the total resultant (pressure + shear) still equals F."""
    μ = solver.problem.contact.friction_coefficient
    force = np.array([0.0, -2000.0])
    result = solver.solve(force, rotation_increment_rad=sign * 0.01, friction=True)
    normal = result.normal_force_N
    tilt = math.atan2(force[0] * normal[1] - force[1] * normal[0], force @ normal)
    assert tilt == pytest.approx(-sign * math.atan(μ), rel=0.01)
    shear = result.resultant_force_N - normal
    assert np.linalg.norm(shear) == pytest.approx(μ * np.linalg.norm(normal), rel=0.01)
    assert result.force_balance_rel_error < 1e-8


def test_slip_is_pin_radius_times_rotation_where_in_contact(solver):
    result = solver.solve((500.0, 0.0), rotation_increment_rad=-0.003)
    in_contact = result.pressure_Pa > 0
    np.testing.assert_allclose(result.slip_m[in_contact], 0.0095 * 0.003, rtol=1e-12)
    np.testing.assert_array_equal(result.slip_m[~in_contact], 0.0)


def test_converges_for_tiny_to_large_loads_in_any_direction(solver):
    rng = np.random.default_rng(7)
    for magnitude in np.geomspace(1.0, 2e4, 12):
        angle = rng.uniform(0, 2 * math.pi)
        friction = bool(rng.integers(2))
        result = solver.solve(magnitude * np.array([math.cos(angle), math.sin(angle)]),
                              rotation_increment_rad=0.01, friction=friction)
        assert result.force_balance_rel_error < 1e-6


def test_moved_mesh_is_reused_after_update_geometry(mesh_data):
    """Turn the whole mesh by 10 degrees (writing geometry.x, as ALE will) and the load with it:
    the pressure field must turn with them."""
    from fewear.contact.solver import BushingContactSolver
    from fewear.mesh.bushing import bushing_mesh

    problem = coarse_problem()
    own_mesh = bushing_mesh(problem.geometry, problem.mesh)
    solver = BushingContactSolver(problem, mesh_data=own_mesh)
    force = np.array([-700.0, -1900.0])
    base = solver.solve(force)
    turn = math.radians(10.0)
    x = solver.mesh.geometry.x
    x[:, :2] = np.column_stack([math.cos(turn) * x[:, 0] - math.sin(turn) * x[:, 1],
                                math.sin(turn) * x[:, 0] + math.cos(turn) * x[:, 1]])
    solver.update_geometry()
    turned = solver.solve(rotate(force, turn))
    assert np.abs(pressure_at(turned, base.angle_rad + turn) - base.pressure_Pa).max() < (
        1e-7 * base.max_pressure_Pa)
    np.testing.assert_allclose(turned.pin_centre_m, rotate(base.pin_centre_m, turn), rtol=1e-7)


@pytest.mark.parametrize("bad_force", [(math.nan, 1.0), (1.0, math.inf), (1.0, 2.0, 3.0)])
def test_bad_force_is_an_input_error(solver, bad_force):
    with pytest.raises(FewearInputError, match="force"):
        solver.solve(bad_force)


def test_output_functions_match_the_nodal_result(solver):
    """The Q2 (XDMF-ready) pressure and displacement equal the result at the bore nodes."""
    result = solver.solve((800.0, -800.0))
    bore = solver.bore
    points = np.zeros((bore.local_nodes.size, 3))
    points[:, :2] = solver.mesh.geometry.x[bore.local_nodes, :2]
    cells = bore.local_node_cells
    pressure = bore.gather(solver.pressure_function().eval(points, cells).reshape(-1, 1))[:, 0]
    np.testing.assert_allclose(pressure, result.pressure_Pa, rtol=0,
                               atol=1e-9 * result.max_pressure_Pa)
    displacement = bore.gather(solver.displacement_function().eval(points, cells).reshape(-1, 2))
    deformed = np.column_stack([result.x_m, result.y_m]) + displacement - result.pin_centre_m
    np.testing.assert_allclose(np.hypot(deformed[:, 0], deformed[:, 1]) - 0.0095, result.gap_m,
                               rtol=0, atol=1e-15)
