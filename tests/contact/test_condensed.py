"""The fast path (bore compliance G) against the full DOLFINx Newton solve and against Lame."""

import math
import sys
from pathlib import Path

import numpy as np
import pytest

from fewear.contact.condensed_newton import zero_displacement

from .test_solver import N_THETA, coarse_problem, rotate


@pytest.fixture(scope="module")
def paths():
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.solver import BushingContactSolver

    full = BushingContactSolver(coarse_problem())
    return full, CondensedBushingContact(full)


def assert_same(full, fast, tolerance=1e-6):
    scale = full.max_pressure_Pa
    assert np.abs(fast.pressure_Pa - full.pressure_Pa).max() <= tolerance * scale
    assert np.linalg.norm(fast.pin_centre_m - full.pin_centre_m) <= tolerance * np.linalg.norm(
        full.pin_centre_m)
    np.testing.assert_array_equal(fast.angle_rad, full.angle_rad)
    np.testing.assert_allclose(fast.resultant_force_N, full.resultant_force_N, rtol=tolerance,
                               atol=tolerance * np.linalg.norm(full.applied_force_N))


LOADS = [  # (force N, rotation increment rad, friction)
    ((0.0, -20.0), 0.0, False),
    ((0.0, -12000.0), 0.0, False),
    ((2500.0, 1700.0), 0.01, True),
    ((-900.0, -300.0), -0.01, True),
    ((-900.0, -350.0), -0.01, True),        # warm start from the previous load
    ((40.0, 160.0), 0.0, False),
]


@pytest.mark.parametrize("force, rotation, friction", LOADS)
def test_fast_path_reproduces_the_full_solve(paths, force, rotation, friction):
    full, fast = paths
    reference = full.solve(force, rotation, friction)
    result = fast.solve(force, rotation, friction)
    assert_same(reference, result)
    assert result.force_balance_rel_error < 1e-8


def crank_cycle(steps):
    """(force N, rotation increment rad, friction) of a slider-crank-like joint-force cycle:
    |F| from 10 N to 5 kN and back, direction swinging +-20 degrees about the rod line and
    reversing at half cycle, friction off at every 7th step."""
    loads = []
    for k in range(steps):
        φ = 2 * math.pi * k / steps
        magnitude = 10.0 * 500.0 ** (0.5 * (1.0 - math.cos(φ)))
        direction = math.radians(20.0) * math.sin(φ) + (math.pi if φ < math.pi else 0.0)
        loads.append((magnitude * np.array([math.cos(direction), math.sin(direction)]),
                      0.02 * math.cos(φ), k % 7 != 3))
    return loads


def test_a_crank_cycle_of_loads_as_the_full_solve_in_a_handful_of_iterations():
    """60 warm-started load steps, light loads and friction switching included: every step as
    the full solve to 1e-6; the active-set Newton needs a handful of iterations (measured on
    this mesh: mean 3.95, max 9, pressures within 2.3e-8 of the peak; at newton_tolerance 1e-11,
    mean 4.9 and max 10; there, with the full 2x2 Jacobian blocks, 4.2 and 8 at twice the cost
    per iteration; without the sliding term for the pin, 8.0 and 13)."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.solver import BushingContactSolver

    full = BushingContactSolver(coarse_problem())
    fast = CondensedBushingContact(full)
    iterations = []
    for force, rotation, friction in crank_cycle(60):
        result = fast.solve(force, rotation, friction)
        assert_same(full.solve(force, rotation, friction), result)
        iterations.append(result.newton_iterations)
    assert np.mean(iterations) < 4.5 and max(iterations) <= 10


def test_a_run_of_load_steps_in_one_call_as_step_after_step(paths):
    """solve_run (a cycle's load steps in one compiled call) gives each step's result to the bit
    as solve does step after step, a zero force included; it stops at a force solve refuses,
    with solve's refusal and the state reset as after it, and goes on from the next step."""
    from fewear.contact.admissible import ContactLoadError

    _, fast = paths
    cycle = crank_cycle(24)
    forces = np.array([force for force, _, _ in cycle])
    rotations = np.array([rotation for _, rotation, _ in cycle])
    forces[5] = 0.0
    forces[14] = (3e11, -4e11)
    fast.newton.reset()
    stepwise = []
    for force, rotation in zip(forces, rotations):
        try:
            stepwise.append(fast.solve(force, rotation, True))
        except ContactLoadError as refusal:
            stepwise.append(str(refusal))
    fast.newton.reset()
    before, refusal = fast.solve_run(forces, rotations, True, 0)
    assert len(before) == 14 and str(refusal) == stepwise[14]
    np.testing.assert_array_equal(fast.pin_centre_m, 0.0)
    after, none = fast.solve_run(forces, rotations, True, 15)
    assert none is None and len(after) == 9
    for run, step in zip(before + after, stepwise[:14] + stepwise[15:]):
        for name in ("angle_rad", "x_m", "y_m", "pressure_Pa", "gap_m", "slip_m", "pin_centre_m",
                     "applied_force_N", "resultant_force_N", "normal_force_N"):
            np.testing.assert_array_equal(getattr(run, name), getattr(step, name), err_msg=name)
        assert run.newton_iterations == step.newton_iterations
    assert before[5].max_pressure_Pa == 0.0 and before[6].max_pressure_Pa > 0.0


def test_zero_force(paths):
    _, fast = paths
    fast.solve((100.0, 0.0))
    result = fast.solve((0.0, 0.0))
    assert result.max_pressure_Pa == 0.0
    np.testing.assert_array_equal(result.pin_centre_m, 0.0)


def test_compliance_is_symmetric_and_positive_definite(paths):
    """Maxwell-Betti reciprocity: G = N K^-1 N^T computed column by column is symmetric."""
    _, fast = paths
    G = fast.compliance
    assert G.shape == (4 * N_THETA, 4 * N_THETA)
    assert np.abs(G - G.T).max() < 1e-9 * np.abs(G).max()
    assert np.linalg.eigvalsh(0.5 * (G + G.T)).min() > 0.0


def test_compliance_columns_are_the_elastic_response_to_unit_nodal_forces(paths):
    """G (the tabulated N, MUMPS's selected entries of K^-1) against the direct route, column by
    column: the load N^T e_k (a unit force on bore node k/2), solved with K by LU, the
    displacement evaluated at the bore nodes by Function.eval (a point search in the moved
    cells): equal to 1e-10 (measured ~1e-13; on the default mesh the former dense solve with all
    2n columns and probe-evaluated N gives the same G to 5e-13)."""
    from dolfinx import fem

    from fewear.linalg import direct_solver

    full, fast = paths
    N = fast._gathered_evaluation()
    local_dofs, columns, _ = fast._dofs
    ksp = direct_solver(full.comm)
    ksp.setOperators(full._K_elastic)
    response = fem.Function(full.V)
    load = response.vector.duplicate()
    for k in (0, 1, 75, 160, 319):
        load.set(0.0)
        load.array_w[local_dofs] = N[k, columns]
        ksp.solve(load, response.vector)
        response.x.scatter_forward()
        column = full._at_bore_nodes(response).reshape(-1)
        assert np.abs(column - fast.compliance[:, k]).max() < 1e-10 * np.abs(column).max()
    ksp.destroy()


def lame_bore_displacement_m(problem, p0):
    """Plane-strain Lame: a uniform pressure p0 on the bore of the annulus clamped at R_o.
    u_r = A r + B/r with u_r(R_o) = 0 and sigma_rr(R_b) = -p0 give
    u_r(R_b) = p0 (R_o^2 - R_b^2) / R_b / (2 (lambda + mu) + 2 mu R_o^2 / R_b^2)."""
    E, ν = problem.material.youngs_modulus_Pa, problem.material.poisson_ratio
    λ, μ = E * ν / ((1 + ν) * (1 - 2 * ν)), E / (2 * (1 + ν))
    R_b, R_o = problem.geometry.inner_radius_m, problem.geometry.outer_radius_m
    return p0 * (R_o**2 - R_b**2) / R_b / (2 * (λ + μ) + 2 * μ * R_o**2 / R_b**2)


def lame_error(fast, p0=1e6):
    """Largest relative error of the radial bore displacement under the nodal forces w_q p0 n_q,
    and the largest tangential displacement (relative)."""
    expected = lame_bore_displacement_m(fast.problem, p0)
    normal = fast.points / np.linalg.norm(fast.points, axis=1)[:, None]
    forces = (fast.weights_m * p0)[:, None] * normal
    U = (fast.compliance @ forces.reshape(-1)).reshape(-1, 2)
    radial = np.einsum("qi,qi->q", U, normal)
    return np.abs(radial / expected - 1).max(), np.abs(np.cross(normal, U)).max() / expected


def test_uniform_bore_pressure_gives_the_lame_displacement(paths):
    _, fast = paths
    radial_error, tangential = lame_error(fast)
    assert radial_error < 1e-4 and tangential < 1e-6
    R_b = fast.problem.geometry.inner_radius_m
    assert fast.weights_m.sum() == pytest.approx(2 * math.pi * R_b, rel=1e-5)


def test_lame_error_converges_at_third_order():
    """Refining the O-grid in both directions: the bore displacement error of the condensed
    quadratic elements falls as h^3 (measured 3.1: 1.4e-3, 1.5e-4, 1.8e-5 for 24/48/96 elements
    around; 2.2e-4, 2.8e-5, 3.4e-6 for 40/80/160)."""
    import dataclasses

    from fewear.contact.condensed import CondensedBushingContact

    sizes, errors = [], []
    for n_theta, radial in ((24, 2), (48, 4), (96, 8)):
        problem = coarse_problem()
        size = 2 * math.pi * problem.geometry.inner_radius_m / n_theta * (1 + 1e-9)
        mesh = dataclasses.replace(problem.mesh, bore_element_size_m=size,
                                   radial_element_count=radial)
        fast = CondensedBushingContact(dataclasses.replace(problem, mesh=mesh))
        sizes.append(1.0 / n_theta)
        errors.append(lame_error(fast)[0])
    rate = np.polyfit(np.log(sizes), np.log(errors), 1)[0]
    assert rate == pytest.approx(3.0, abs=0.2)
    assert errors[-1] < 1e-4


def test_after_moving_the_mesh_both_paths_still_agree():
    """Turn the mesh by 10 degrees (geometry.x written, as ALE will), update both paths."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.solver import BushingContactSolver

    full = BushingContactSolver(coarse_problem())
    fast = CondensedBushingContact(full)
    force = np.array([-700.0, -1900.0])
    before = fast.solve(force)
    turn = math.radians(10.0)
    x = full.mesh.geometry.x
    x[:, :2] = np.column_stack([math.cos(turn) * x[:, 0] - math.sin(turn) * x[:, 1],
                                math.sin(turn) * x[:, 0] + math.cos(turn) * x[:, 1]])
    fast.update_geometry()
    turned = rotate(force, turn)
    result = fast.solve(turned)
    assert_same(full.solve(turned), result)
    np.testing.assert_allclose(result.pin_centre_m, rotate(before.pin_centre_m, turn), rtol=1e-7)


def test_built_from_a_problem(paths):
    from fewear.contact.condensed import CondensedBushingContact

    full, _ = paths
    fast = CondensedBushingContact(coarse_problem())
    assert_same(full.solve((300.0, -3000.0)), fast.solve((300.0, -3000.0)))


MPI_SCRIPT = """
import sys
import numpy as np
from mpi4py import MPI
sys.path.insert(0, {tests!r})
from test_solver import coarse_problem
from fewear.contact.condensed import CondensedBushingContact
from fewear.contact.solver import BushingContactSolver

full = BushingContactSolver(coarse_problem(), MPI.COMM_WORLD)
fast = CondensedBushingContact(full)
out = {{}}
for k, (force, rotation, friction) in enumerate({loads!r}):
    for name, path in (("full", full), ("fast", fast)):
        result = path.solve(force, rotation, friction)
        for key in ("angle_rad", "pressure_Pa", "gap_m", "pin_centre_m", "resultant_force_N"):
            value = getattr(result, key)
            assert all(np.array_equal(value, other) for other in MPI.COMM_WORLD.allgather(value))
            out[f"{{name}}{{k}}_{{key}}"] = value
if MPI.COMM_WORLD.rank == 0:
    np.savez({out!r}, **out)
"""


@pytest.mark.slow  # the wear loop's two-rank test runs the condensed path on two ranks by default
@pytest.mark.mpi
def test_two_ranks_give_the_serial_result(tmp_path):
    """Both paths under mpirun -n 2 (every rank holding the same gathered result) equal the
    serial run to 1e-8 of the peak pressure and of the pin centre."""
    import os
    import subprocess

    from tests.mpi import MPI_ENV, mpirun_or_skip

    mpirun = mpirun_or_skip()
    loads = [((-450.0, 700.0), 0.0, False), ((0.0, -3000.0), 0.01, True)]
    env = {**os.environ, **MPI_ENV}
    results = {}
    for ranks in (1, 2):
        out = tmp_path / f"ranks{ranks}.npz"
        script = tmp_path / f"run{ranks}.py"
        script.write_text(MPI_SCRIPT.format(tests=str(Path(__file__).parent), loads=loads,
                                            out=str(out)))
        command = [sys.executable, str(script)]
        if ranks > 1:
            command = [mpirun, "-n", str(ranks), *command]
        process = subprocess.run(command, capture_output=True, text=True, timeout=600, env=env)
        assert process.returncode == 0, process.stderr[-2000:]
        results[ranks] = np.load(out)
    serial, parallel = results[1], results[2]
    for k in range(len(loads)):
        for name in ("full", "fast"):
            key = f"{name}{k}_"
            np.testing.assert_array_equal(serial[key + "angle_rad"], parallel[key + "angle_rad"])
            peak = serial[key + "pressure_Pa"].max()
            assert np.abs(serial[key + "pressure_Pa"] - parallel[key + "pressure_Pa"]).max() < (
                1e-8 * peak)
            centre = serial[key + "pin_centre_m"]
            assert np.linalg.norm(centre - parallel[key + "pin_centre_m"]) < 1e-8 * np.linalg.norm(
                centre)


def test_a_force_beyond_the_admissible_range_is_refused_by_both_paths(paths):
    """Both paths raise ContactLoadError (a FewearInputError) naming the force and the same
    admissible range (computed with G and with an LU solve of K: agree to 1e-6), and solve the
    next admissible force as from scratch."""
    from fewear.contact.admissible import ContactLoadError
    from fewear.errors import FewearInputError

    full, fast = paths
    force = (3e11, -4e11)
    for path in (full, fast):
        with pytest.raises(ContactLoadError) as caught:
            path.solve(force)
        assert isinstance(caught.value, FewearInputError)
        assert "(3e+11, -4e+11) N" in str(caught.value)
    limits = [path.admissible_force_N(force) for path in (full, fast)]
    assert limits[1] == pytest.approx(limits[0], rel=1e-6)
    assert 1e5 < limits[0] < 1e8
    assert_same(full.solve((300.0, -3000.0)), fast.solve((300.0, -3000.0)))


def test_admissible_force_moves_the_bore_by_the_limit_under_the_cosine_law(paths):
    """At |F|_max the cosine-law pressure moves the bore by a tenth of the wall (linear
    elasticity: |F|_max times the 1 N response), and the cosine-law nodal forces carry the
    force: sum f_q L = F."""
    from fewear.contact.admissible import cosine_law_nodal_forces

    _, fast = paths
    direction = np.array([0.6, -0.8])
    geometry = fast.problem.geometry
    forces = cosine_law_nodal_forces(fast.points, fast.weights_m, direction,
                                     geometry.inner_radius_m, geometry.width_m)
    np.testing.assert_allclose(forces.sum(axis=0) * geometry.width_m, direction, atol=1e-4)
    limit = fast.admissible_force_N(direction)
    U = (fast.compliance @ (limit * forces).reshape(-1)).reshape(-1, 2)
    wall = geometry.outer_radius_m - geometry.inner_radius_m
    assert np.hypot(U[:, 0], U[:, 1]).max() == pytest.approx(0.1 * wall, rel=1e-12)


def test_only_small_displacements_are_admissible():
    from fewear.contact.admissible import beyond_small_displacements

    problem = coarse_problem()
    wall = problem.geometry.outer_radius_m - problem.geometry.inner_radius_m
    assert beyond_small_displacements(problem, 0.09 * wall) is None
    assert "bore would move" in beyond_small_displacements(problem, 0.11 * wall)
    assert beyond_small_displacements(problem, float("nan")) is not None


@pytest.mark.slow  # the worn bore with friction below keeps a worn crank cycle by default
def test_on_a_worn_bore_a_crank_cycle_as_the_full_solve():
    """Pockets 20 um deep worn left and right (the paper's wear), the interior moved along:
    at light loads the pin bridges a pocket, resting on its rims (nodes far apart); every
    load step of a 40-step cycle as the full solve to 1e-6 (measured iterations: mean 11, 3 at
    light loads, up to 55 where the contact-angle fallback takes over at moderate loads)."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.solver import BushingContactSolver

    problem = coarse_problem()
    full = BushingContactSolver(problem)
    x = full.mesh.geometry.x
    r, θ = np.hypot(x[:, 0], x[:, 1]), np.arctan2(x[:, 1], x[:, 0])
    R_b, R_o = problem.geometry.inner_radius_m, problem.geometry.outer_radius_m
    depth = 20e-6 * (np.exp(-(1.0 + np.cos(θ)) / 0.02) + np.exp(-(1.0 - np.cos(θ)) / 0.02))
    x[:, :2] *= (1.0 + depth * (R_o - r) / (R_o - R_b) / r)[:, None]
    fast = CondensedBushingContact(full)
    fast.update_geometry()
    iterations, bridged = [], 0
    for force, rotation, friction in crank_cycle(40):
        result = fast.solve(force, rotation, friction)
        assert_same(full.solve(force, rotation, friction), result)
        iterations.append(result.newton_iterations)
        in_contact = np.flatnonzero(result.pressure_Pa > 0.0)
        bridged += int(in_contact.size == 2 and abs(in_contact[1] - in_contact[0]) > 1)
    assert bridged > 0
    assert np.mean(iterations) < 15.0


def two_pockets(angle_rad, depths_m=(1.5e-4, 2.0e-4), half_width_deg=30.0, smoothing_deg=5.0):
    """A worn bore's radial depth (m) at ``angle_rad``: pockets around 0 and 180 degrees, flat
    bottoms ``depths_m`` deep, +-30 degrees wide, flanks smoothed over ~5 degrees (tanh)."""
    depth = np.zeros_like(angle_rad)
    for centre, pocket in zip((0.0, math.pi), depths_m):
        distance = np.abs(np.angle(np.exp(1j * (angle_rad - centre))))
        depth += 0.5 * pocket * (1.0 - np.tanh((distance - math.radians(half_width_deg))
                                               / math.radians(smoothing_deg)))
    return depth


@pytest.fixture(scope="module")
def worn_paths():
    """Both paths on the coarse O-grid whose bore moved by :func:`two_pockets` (ALE)."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.solver import BushingContactSolver
    from fewear.mesh.ale import BoreMotion

    full = BushingContactSolver(coarse_problem())
    fast = CondensedBushingContact(full)
    BoreMotion(full.mesh, full.facet_tags).move(two_pockets)
    fast.update_geometry()
    return full, fast


def test_a_crank_cycle_on_a_worn_bore_converges_with_friction_as_the_full_solve(worn_paths):
    """The pin bridges a pocket and rests on its flanks: light loads with friction converge
    (refused before: the corner start stood in the pocket, the turned state in a flank), every
    step in force balance and as the full solve to 1e-6, in a handful of iterations (measured:
    mean 3.1, max 5)."""
    full, fast = worn_paths
    iterations = []
    for force, rotation, friction in crank_cycle(60):
        result = fast.solve(force, rotation, friction)
        assert result.force_balance_rel_error < 1e-7
        assert_same(full.solve(force, rotation, friction), result)
        iterations.append(result.newton_iterations)
    assert np.mean(iterations) < 6.0 and max(iterations) <= 20


@pytest.mark.parametrize("force", [(549.872, -134.418), (1000.0, -134.0), (-30.0, 4.0)])
def test_light_loads_with_friction_on_a_worn_bore_from_a_cold_start(worn_paths, force):
    """The loads refused on a worn bore (reproduce.py of the robustness brief), each from a cold
    start, with friction both ways: converged in a few iterations, as the full solve."""
    full, fast = worn_paths
    for rotation in (0.01, -0.01):
        fast.newton.forget()
        result = fast.solve(force, rotation, True)
        assert result.newton_iterations <= 10
        assert_same(full.solve(force, rotation, True), result)


def test_the_corner_start_on_a_worn_bore_rests_on_the_pocket_rims(worn_paths):
    """The corner of two neighbouring nodes at the bottom of a pocket lies beyond its flanks;
    the start is the vertex of the contact-free region furthest along d instead: two nodes at
    R_p (not neighbours: the pin bridges the pocket), no node closer."""
    from fewear.contact.newton_kernels import support_vertex

    _, fast = worn_paths
    R_p = fast.problem.geometry.pin_radius_m
    for angle in (0.0, 0.3, math.pi - 0.2):
        direction = np.array([math.cos(angle), math.sin(angle)])
        centre, pair = support_vertex(fast.points, direction, R_p)
        distance = np.hypot(*(fast.points - centre).T)
        assert distance.min() >= R_p * (1.0 - 1e-12)
        np.testing.assert_allclose(distance[list(pair)], R_p, rtol=1e-12)
        assert abs(pair[1] - pair[0]) > 1
        zero_displacement(fast.newton_state)
        start = fast.newton._corner(direction, np.array([1e3, 0.0]))
        assert np.count_nonzero(np.hypot(*(fast.points - start).T) < R_p) == 2


def test_the_state_is_not_turned_on_a_worn_bore(worn_paths):
    """turn_state leaves the state of a worn bore as it is (False): the turned forces would sit
    on nodes elsewhere than the turned ones by the change of the wear depth."""
    _, fast = worn_paths
    fast.newton.forget()
    fast.solve((2000.0, -300.0))
    g, centre = fast._g.copy(), fast.pin_centre_m.copy()
    assert not fast.turn_state(3.0 * 2.0 * math.pi / N_THETA)
    np.testing.assert_array_equal(fast._g, g)
    np.testing.assert_array_equal(fast.pin_centre_m, centre)


@pytest.fixture(scope="module")
def deep_paths():
    """Both paths on the coarse O-grid worn about 1 mm deep (ALE): pockets 0.8 and 1.0 mm deep,
    +-45 degrees wide, flanks smoothed over ~8 degrees, twice the radial clearance of 0.5 mm (as
    the default rigid case's bore at 210,940 cycles): the pin bridges a pocket on its rims."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.solver import BushingContactSolver
    from fewear.mesh.ale import BoreMotion

    full = BushingContactSolver(coarse_problem())
    fast = CondensedBushingContact(full)
    BoreMotion(full.mesh, full.facet_tags).move(
        lambda angle: two_pockets(angle, (0.8e-3, 1.0e-3), half_width_deg=45.0,
                                  smoothing_deg=8.0))
    fast.update_geometry()
    return full, fast


DEEP_LOADS = [  # (direction deg, |F| N, rotation increment rad, friction): refused before
    (58.0, 100.0, 0.0, False),
    (238.0, 470.0, 0.01, True),
    (34.0, 40.0, 0.0, False),
    (42.0, 6000.0, 0.01, True),
    (230.0, 6000.0, 0.0, False),
    (58.0, 6000.0, 0.0, False),     # through the fallback on the pin angle
    (234.0, 6000.0, -0.01, True),   # through the fallback on the pin angle
]


@pytest.mark.parametrize("angle, magnitude, rotation, friction", DEEP_LOADS)
def test_loads_on_a_bore_worn_a_millimetre_deep_as_the_full_solve(deep_paths, angle, magnitude,
                                                                   rotation, friction):
    """Forces like those of the refused load steps of the default rigid run at 210,940 cycles
    (e.g. 5980 N at 58 degrees, 42 to 470 N at 54 to 58 degrees) on a bore worn 1 mm deep, from
    a cold start: in force balance and as the full solve to 1e-6. Refused before: the start
    pressed the pin along the load into one rim of the wedge only, whence the Newton slid it
    along that rim, and the fallback on the pin angle stepped onto rays along which the load
    pulls the pin off the bore."""
    full, fast = deep_paths
    force = magnitude * np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
    fast.newton.forget()
    result = fast.solve(force, rotation, friction)
    assert result.force_balance_rel_error < 1e-7
    assert_same(full.solve(force, rotation, friction), result)


def test_the_start_in_a_wedge_presses_the_pin_onto_both_rims(deep_paths):
    """Where the pin bridges a pocket, its two rims' normals are far apart (a wedge): the start
    presses the pin into both so that together they carry the load (not along the load, which
    leaves one rim), and a light load converges from there in a few coupled Newton iterations,
    without the fallback on the pin angle (before: 80 to 160 iterations, or refused)."""
    from fewear.contact.newton_kernels import support_vertex

    _, fast = deep_paths
    R_p = fast.problem.geometry.pin_radius_m
    for angle in (34.0, 58.0, 238.0):
        direction = np.array([math.cos(math.radians(angle)), math.sin(math.radians(angle))])
        _, pair = support_vertex(fast.points, direction, R_p)
        zero_displacement(fast.newton_state)
        start = fast.newton._corner(direction, np.array([1e4, 0.0]))
        assert np.all(np.hypot(*(fast.points[list(pair)] - start).T) < R_p)
        fast.newton.forget()
        result = fast.solve(100.0 * direction)
        assert result.newton_iterations <= 10
        assert result.force_balance_rel_error < 1e-7


def test_the_fallback_starts_where_the_last_one_left_the_pin(deep_paths):
    """A load that needs the fallback on the pin angle after one that needed it: the pin
    rests at the same end of the pocket, so the fallback's search starts on the last one's ray
    (at the end of a deep pocket the tangential residual is steep, and the search from the
    load's ray walks tens of degrees). Same solution as from the load's ray, in fewer
    iterations (measured: 44 against 167; where the pin rests elsewhere the start can cost
    more, 70 against 58 at 119 degrees; over a late block of the default rigid run, 28 % fewer
    iterations)."""
    _, fast = deep_paths
    direction = np.array([math.cos(math.radians(120.0)), math.sin(math.radians(120.0))])
    fast.newton.geometry_changed()
    fast.newton.forget()
    fast.solve(6000.0 * direction)
    assert fast.newton.fallback_angle_rad is not None
    fast.newton.forget()
    hinted = fast.solve(5500.0 * direction)
    fast.newton.geometry_changed()
    fast.newton.forget()
    cold = fast.solve(5500.0 * direction)
    assert fast.newton.fallback_angle_rad is not None  # this load needs the fallback too
    assert_same(cold, hinted)
    assert hinted.newton_iterations < 0.5 * cold.newton_iterations


def pin_carved_pocket(angle_rad, depth_m=2e-4, radius_excess_m=1e-5):
    """A worn bore's radial depth (m): the pocket a circle ``radius_excess_m`` larger than the
    pin carves ``depth_m`` deep at 180 degrees, as a bore worn by its pin conforms to it."""
    geometry = coarse_problem().geometry
    radius = geometry.pin_radius_m + radius_excess_m
    offset = geometry.inner_radius_m - radius + depth_m  # the carving circle's centre at (-e, 0)
    along = -offset * np.cos(angle_rad)
    reach = along + np.sqrt(np.maximum(radius**2 - offset**2 + along**2, 0.0))
    return np.maximum(reach - geometry.inner_radius_m, 0.0)


@pytest.mark.parametrize("angle_deg, magnitude_N", [(170.0, 2000.0), (175.0, 8000.0)])
def test_a_conformal_pocket_from_a_cold_start_needs_no_fallback(angle_deg, magnitude_N):
    """A pin in a pocket that conforms to it (carved by a circle 10 um larger): from the corner
    start on two nodes the active set grows by a few nodes per step to 16-26 and the coupled
    Newton settles in 13-14 steps, before the fallback on the pin angle takes over (with 12
    coupled steps it did, at 76-103 iterations; on the default rigid run's deep pockets 3.9 %
    of the solves, 66 % of the contact's Newton time). Same solution as the full solve."""
    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.newton import COUPLED_ITERATIONS
    from fewear.contact.solver import BushingContactSolver
    from fewear.mesh.ale import BoreMotion

    full = BushingContactSolver(coarse_problem())
    fast = CondensedBushingContact(full)
    BoreMotion(full.mesh, full.facet_tags).move(pin_carved_pocket)
    fast.update_geometry()
    angle = math.radians(angle_deg)
    force = magnitude_N * np.array([math.cos(angle), math.sin(angle)])
    result = fast.solve(force, 0.01, True)
    assert fast.newton.fallback_angle_rad is None
    assert 12 < result.newton_iterations <= COUPLED_ITERATIONS
    assert np.count_nonzero(result.pressure_Pa > 0.0) > 10
    assert_same(full.solve(force, 0.01, True), result)
