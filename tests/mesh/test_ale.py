"""ALE motion of the bushing: bore nodes move exactly by the wear, the outer surface stays, the
interior follows the elastic extension (Lame's thick-walled cylinder for a uniform increment)."""

import math

import numpy as np
import pytest

from fewear.mesh.profile import periodic_linear, polar_angle
from tests.mesh.cases import GEOMETRY, bore_node_angles, coarse_settings, two_lobes

R_B, R_O = GEOMETRY.inner_radius_m, GEOMETRY.outer_radius_m


def coarse_motion(n_theta=48, radial_count=4, grading=2.0):
    from fewear.mesh.ale import BoreMotion
    from fewear.mesh.bushing import bushing_mesh

    msh, _, facet_tags = bushing_mesh(GEOMETRY, coarse_settings(n_theta, radial_count, grading))
    return BoreMotion(msh, facet_tags)


def node_sets(motion):
    """Local geometry nodes on the bore and on the outer surface."""
    return (np.unique(motion.dof_node[motion.bore_dofs]),
            np.unique(motion.dof_node[motion.outer_dofs]))


def test_space_dofs_are_the_geometry_nodes():
    motion = coarse_motion()
    x = motion.mesh.geometry.x[:, :2]
    space = motion.space
    assert np.array_equal(np.sort(motion.node_dof), np.arange(x.shape[0]))
    np.testing.assert_allclose(space.tabulate_dof_coordinates()[motion.node_dof, :2], x, rtol=0,
                               atol=1e-17)


def test_worn_profile_moves_bore_nodes_exactly_and_keeps_every_element_valid():
    """Two 0.5 mm lobes in five equal moves: after each, r = R_b + h(theta) at every bore node
    (to rounding), angles unchanged, outer nodes untouched, every Jacobian positive."""
    n_theta, moves = 48, 5
    motion = coarse_motion(n_theta)
    as_meshed = motion.quality_meter.measure()       # scaled Jacobian 0.87: det J ~ r in a cell
    bore, outer = node_sets(motion)
    x = motion.mesh.geometry.x
    angle_before, outer_before = polar_angle(x[bore]), x[outer].copy()
    node_angles = bore_node_angles(n_theta)
    increment = periodic_linear(node_angles, two_lobes(node_angles) / moves)
    for move in range(1, moves + 1):
        report = motion.move(increment)
        radius = np.hypot(x[bore, 0], x[bore, 1])
        np.testing.assert_allclose(radius, R_B + move * increment(angle_before), rtol=0,
                                   atol=4e-18 * move)
        np.testing.assert_allclose(polar_angle(x[bore]), angle_before, rtol=0, atol=1e-15)
        np.testing.assert_array_equal(x[outer], outer_before)
        assert report.max_bore_increment_m == pytest.approx(0.5e-3 / moves, rel=1e-12)
        assert report.quality.min_scaled_jacobian > as_meshed.min_scaled_jacobian - 0.01
        assert report.quality.min_angle_sine > 0.99
    print(f"\nafter 0.5 mm lobes: {report}")


def test_the_moved_mesh_depends_on_the_bore_not_on_the_path_of_moves():
    """Total-Lagrangian: the extension is solved on the mesh as made for the bore's total
    displacement, so two lobes reached in five moves leave every node where one move does."""
    node_angles = bore_node_angles(48)
    stepwise, direct = coarse_motion(), coarse_motion()
    for _ in range(5):
        stepwise.move(periodic_linear(node_angles, two_lobes(node_angles) / 5))
    direct.move(periodic_linear(node_angles, two_lobes(node_angles)))
    np.testing.assert_allclose(stepwise.mesh.geometry.x, direct.mesh.geometry.x, rtol=0,
                               atol=1e-17)


def lame_error(n_theta, radial_count, delta=1e-6):
    """Largest |d_r - (A r + B/r)| / delta over all nodes after a uniform bore increment delta,
    the largest tangential motion (m) and the move's report."""
    motion = coarse_motion(n_theta, radial_count, grading=1.0)
    x = motion.mesh.geometry.x
    before = x[:, :2].copy()
    report = motion.move(lambda angle: np.full_like(angle, delta))
    r = np.hypot(before[:, 0], before[:, 1])
    radial_unit = before / r[:, None]
    moved = x[:, :2] - before
    radial = np.sum(moved * radial_unit, axis=1)
    tangential = moved[:, 1] * radial_unit[:, 0] - moved[:, 0] * radial_unit[:, 1]
    a = delta * R_B / (R_B**2 - R_O**2)
    lame = a * r - a * R_O**2 / r
    return np.abs(radial - lame).max() / delta, np.abs(tangential).max(), report


def test_uniform_increment_gives_lame_radial_field():
    """d_r(r) = A r + B/r, A = delta R_b/(R_b^2 - R_o^2), B = -A R_o^2, to discretisation
    accuracy: the nodal error falls as h^3 (measured 8.1x per halving); no tangential motion.
    The harmonic extension's delta ln(R_o/r)/ln(R_o/R_b) differs from it by 1.4e-2 delta."""
    delta = 1e-6
    coarse, tangential, report = lame_error(32, 6, delta)
    fine, _, _ = lame_error(64, 12, delta)
    print(f"\nLame field: max nodal error {coarse:.2e} / {fine:.2e} delta (32x6 / 64x12), "
          f"tangential {tangential:.1e} m")
    assert coarse < 5e-4
    assert coarse / fine > 6.0
    assert tangential < 1e-9 * delta
    r = np.linspace(R_B, R_O, 101)
    a = R_B / (R_B**2 - R_O**2)
    assert np.abs(np.log(R_O / r) / math.log(R_O / R_B) - (a * r - a * R_O**2 / r)).max() > 1e-2
    assert report.max_displacement_m == pytest.approx(delta, rel=1e-12)
    # every bore node moved by delta; a bore-row cell's height runs from its bore edge's midpoint
    # (on R_b) to its straight outer edge's midpoint, at (R_b + (R_o - R_b)/6) cos(pi/32)
    height = (R_B + (R_O - R_B) / 6) * math.cos(math.pi / 32) - R_B
    assert report.quality.max_bore_motion_ratio == pytest.approx(delta / height, rel=1e-9)


def test_increment_of_the_wrong_shape_is_refused():
    motion = coarse_motion(n_theta=16, radial_count=2)
    with pytest.raises(ValueError, match="increment_m must map"):
        motion.move(lambda angle: np.zeros(3))
    with pytest.raises(ValueError, match="finite"):
        motion.move(lambda angle: np.full_like(angle, np.nan))


def test_many_motions_leave_petsc_options_database_as_it_was():
    """PETSc's options database holds 512 options at most: a diagnosis makes hundreds of motions
    in one process, and the 171st one failed when each left DOLFINx 0.5's LinearProblem options
    there. The motion's solver is set up without the database."""
    from petsc4py import PETSc

    before = len(PETSc.Options().getAll())
    motions = [coarse_motion(n_theta=16, radial_count=2) for _ in range(3)]
    assert len(PETSc.Options().getAll()) == before
    solver = motions[-1].solver
    assert (solver.getType(), solver.getPC().getType()) == ("preonly", "lu")
    moved = motions[-1].move(lambda angle: np.full_like(angle, 1e-6))
    assert moved.max_bore_increment_m == pytest.approx(1e-6)


def test_bore_alone_then_the_interior_puts_every_node_where_moves_do():
    """Moving the bore nodes alone (``move_bore_to``) through three worn bores and then the
    interior (``extend_interior``) leaves every node where three full moves (``move_to``) leave
    it, to the bit: the extension is from the mesh as made. Between, the interior stays, the
    bore is on r(theta), and the bore motion ratio is the full quality's."""
    full, lazy = coarse_motion(), coarse_motion()
    x_full, x_lazy = full.mesh.geometry.x, lazy.mesh.geometry.x
    bore, outer = node_sets(lazy)
    interior = np.setdiff1d(np.arange(x_lazy.shape[0]), np.concatenate([bore, outer]))
    start = x_lazy.copy()
    for depth_m in (1e-5, 4e-5, 7e-5):
        def radius(angle, depth_m=depth_m):
            return R_B + depth_m * (1.0 + np.cos(2.0 * angle))

        report = full.move_to(radius)
        ratio = lazy.move_bore_to(radius)
        assert ratio == report.quality.max_bore_motion_ratio
        np.testing.assert_array_equal(x_lazy[bore], x_full[bore])
        np.testing.assert_array_equal(x_lazy[interior], start[interior])
    quality = lazy.extend_interior()
    np.testing.assert_array_equal(x_lazy, x_full)
    assert quality == report.quality
    assert np.abs(x_lazy[interior] - start[interior]).max() > 1e-6  # the interior did follow
