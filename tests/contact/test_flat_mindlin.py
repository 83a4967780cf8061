"""The frictional step on the flat (fewear.contact.flat) against Cattaneo-Mindlin partial slip.

A rigid cylinder pressed by P and then pulled by a tangential force Q < mu P at constant P
(Johnson, *Contact Mechanics*, 1985, sec. 7.2; Hills & Nowell, *Mechanics of Fretting Fatigue*,
1994): with Hertz's a and p0 (tests/contact/test_flat_hertz.py), a central stick zone |x| < c,

    c/a = sqrt(1 - Q'/(mu P')),
    q(x) = mu p0 sqrt(1 - x^2/a^2) - mu p0 (c/a) sqrt(1 - x^2/c^2)   for |x| < c,
    q(x) = mu p0 sqrt(1 - x^2/a^2)                                    for c <= |x| <= a.

Exact for uncoupled normal and tangential problems (Dundurs beta = 0, elastically similar
bodies); the rigid cylinder on the elastic flat has beta = (1 - 2 nu)/(2 (1 - nu)) = 0.29 at
nu = 0.3. So Mindlin is checked on the uncoupled step (the pressure frozen at the normal
solve's, ``uncoupled=True``), and the coupled step only for what survives the coupling.

The case: McColl, Ding & Leen 2004's fretting test with a rigid cylinder: R = 6 mm, E = 200 GPa,
nu = 0.3, P = 185 N over L = 10 mm, mu = 0.9 (a = 25.4 um, p0 = 464 MPa); the flat 40 a wide and
high, its contact zone |x| < 2 a in elements of a/8, a/16, a/32. Q = mu P/2 (c/a = 0.707), then
on to 3 mu P/4 (c/a = 0.5) from that state: the history of the return mapping.

Then unloading to Q = mu P/4 (Mindlin & Deresiewicz; Johnson 1985, sec. 7.2): reverse slip
at the edges, the stick zone c' = a sqrt(1 - (Q* - Q)/(2 mu P)) = 0.866 a, and
q = -mu p0 e(a) + 2 mu p0 (c'/a) e(c') - mu p0 (c/a) e(c), e(b) = sqrt(1 - x^2/b^2).

Measured (uncoupled), q RMS over |x| <= a relative to mu p0 at a/8, a/16, a/32: 1.41, 0.58,
0.36 % (Q = mu P/2), 1.39, 0.71, 0.38 % (3 mu P/4) and 2.27, 0.82, 0.63 % (back to mu P/4);
largest nodal error 2-6 % (at the stick zone's edges, where q has an infinite slope). The
stick zone's measured half-width (half way between the outermost sticking node and the next)
is within half a node spacing (h/4) of c or c': the discrete bound. Coupled (nu = 0.3, a/16):
the pressure's centroid moves 0.13 a against Q, the stick zone with it; its width stays 2c to
within a node spacing.
"""

import math

import numpy as np
import pytest

from fewear.contact.params import BushingMaterial, ContactSettings, FlatContactProblem
from fewear.errors import FewearInputError
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings

RADIUS_M, YOUNGS_MODULUS_PA, POISSON_RATIO = 0.006, 200e9, 0.3
FORCE_N, LENGTH_M, FRICTION = 185.0, 0.010, 0.9
FLAT_SIZE_IN_A, ZONE_IN_A = 40.0, 2.0
ELEMENTS_PER_HALF_WIDTH = (8, 16, 32)
LOAD_RATIOS = (0.5, 0.75, 0.25)  # Q / (mu P), one after the other: loading, then unloading


def hertz():
    """(a (m), p0 (Pa)) of Hertz line contact for the rigid cylinder."""
    contact_modulus = YOUNGS_MODULUS_PA / (1.0 - POISSON_RATIO**2)
    line_load = FORCE_N / LENGTH_M
    half_width = math.sqrt(4.0 * line_load * RADIUS_M / (math.pi * contact_modulus))
    return half_width, 2.0 * line_load / (math.pi * half_width)


def ellipse(x_m, half_width_m):
    """sqrt(1 - x^2/b^2) inside |x| < b, else 0."""
    return np.sqrt(np.clip(1.0 - (x_m / half_width_m) ** 2, 0.0, None))


def mindlin_shear_Pa(x_m, load_ratio):
    """Mindlin's q(x) (Pa) at Q = load_ratio mu P (module docstring)."""
    a, p0 = hertz()
    c = stick_half_width_in_theory_m(load_ratio)
    return FRICTION * p0 * (ellipse(x_m, a) - (c / a) * ellipse(x_m, c))


def unloaded_shear_Pa(x_m, peak_ratio, load_ratio):
    """Mindlin & Deresiewicz's q(x) (Pa) after unloading from Q* = peak_ratio mu P to
    Q = load_ratio mu P: q = -mu p0 e(a) + 2 mu p0 (c'/a) e(c') - mu p0 (c/a) e(c), e(b) =
    sqrt(1 - x^2/b^2), c'/a = sqrt(1 - (Q* - Q)/(2 mu P)) (Johnson 1985, sec. 7.2)."""
    a, p0 = hertz()
    c = stick_half_width_in_theory_m(peak_ratio)
    reversed_ = stick_half_width_in_theory_m(load_ratio, peak_ratio)
    return FRICTION * p0 * (-ellipse(x_m, a) + 2.0 * (reversed_ / a) * ellipse(x_m, reversed_)
                            - (c / a) * ellipse(x_m, c))


def stick_half_width_in_theory_m(load_ratio, peak_ratio=None):
    """c = a sqrt(1 - Q/(mu P)) on loading; c' = a sqrt(1 - (Q* - Q)/(2 mu P)) on unloading
    from Q* = peak_ratio mu P (m)."""
    a, _ = hertz()
    if peak_ratio is None:
        return a * math.sqrt(1.0 - load_ratio)
    return a * math.sqrt(1.0 - 0.5 * (peak_ratio - load_ratio))


def reference(load_ratio, peak_ratio):
    """(shear function of x, stick half-width) of the step to ``load_ratio`` after the peak
    ``peak_ratio`` (None on loading)."""
    if peak_ratio is None:
        return (lambda x: mindlin_shear_Pa(x, load_ratio),
                stick_half_width_in_theory_m(load_ratio))
    return (lambda x: unloaded_shear_Pa(x, peak_ratio, load_ratio),
            stick_half_width_in_theory_m(load_ratio, peak_ratio))


def flat_solver(elements_per_half_width):
    from fewear.contact.flat import FlatContactSolver

    a, _ = hertz()
    geometry = FlatGeometry(cylinder_radius_m=RADIUS_M, width_m=FLAT_SIZE_IN_A * a,
                            height_m=FLAT_SIZE_IN_A * a, length_m=LENGTH_M,
                            standoff_m=1e-3 * RADIUS_M)
    mesh = FlatMeshSettings(contact_element_size_m=a / elements_per_half_width,
                            contact_zone_half_width_m=ZONE_IN_A * a)
    return FlatContactSolver(FlatContactProblem(
        geometry, BushingMaterial(YOUNGS_MODULUS_PA, POISSON_RATIO), mesh,
        ContactSettings(friction_coefficient=FRICTION)))


def stick_half_width_m(step):
    """Half the width of the sticking nodes' zone, each end half way to the next node (m),
    and its centre (m)."""
    x = step.contact.x_m
    stuck = np.flatnonzero(step.sticking)
    left = 0.5 * (x[stuck.min()] + x[stuck.min() - 1])
    right = 0.5 * (x[stuck.max()] + x[stuck.max() + 1])
    return 0.5 * (right - left), 0.5 * (right + left)


class MindlinComparison:
    """One uncoupled frictional step beside Mindlin (errors relative to c and mu p0)."""

    def __init__(self, solver, step, load_ratio, peak_ratio=None):
        a, p0 = hertz()
        x, w = step.contact.x_m, solver.weights_m
        self.step, self.ratio = step, load_ratio
        self.node_spacing_m = 0.5 * solver.problem.mesh.contact_element_length_m()
        shear, self.c_m = reference(load_ratio, peak_ratio)
        self.stick_half_width_m, self.stick_centre_m = stick_half_width_m(step)
        inside = np.abs(x) <= a
        error = (step.shear_Pa - shear(x))[inside]
        self.rms = math.sqrt(np.sum(w[inside] * error**2) / np.sum(w[inside])) / (FRICTION * p0)
        self.largest = np.abs(error).max() / (FRICTION * p0)


@pytest.fixture(scope="module")
def study():
    """Per mesh, the uncoupled steps to Q = mu P/2, on to 3 mu P/4 and back to mu P/4."""
    rows = []
    peaks = [None, None, max(LOAD_RATIOS)]
    for per_half_width in ELEMENTS_PER_HALF_WIDTH:
        solver = flat_solver(per_half_width)
        solver.solve(FORCE_N)
        rows.append([MindlinComparison(solver, solver.solve_tangential_force(
            ratio * FRICTION * FORCE_N, FORCE_N, uncoupled=True), ratio, peak)
            for ratio, peak in zip(LOAD_RATIOS, peaks)])
    a, _ = hertz()
    for per_half_width, row in zip(ELEMENTS_PER_HALF_WIDTH, rows):
        for m in row:
            print(f"\nh = a/{per_half_width}, Q = {m.ratio} mu P: c "
                  f"{m.stick_half_width_m / a:.4f} a (Mindlin {m.c_m / a:.4f} a); q RMS "
                  f"{m.rms:.3%}, largest {m.largest:.3%} of mu p0; "
                  f"{m.step.contact.newton_iterations} Newton")
    return rows


def test_mindlin_shear_carries_the_tangential_force():
    """The reference itself: the integral of q(x) is Q' (Simpson on a fine grid)."""
    a, _ = hertz()
    x = np.linspace(-a, a, 200001)
    for ratio in LOAD_RATIOS:
        carried = np.trapz(mindlin_shear_Pa(x, ratio), x) * LENGTH_M
        assert carried == pytest.approx(ratio * FRICTION * FORCE_N, rel=1e-6)
    unloaded = np.trapz(unloaded_shear_Pa(x, 0.75, 0.25), x) * LENGTH_M
    assert unloaded == pytest.approx(0.25 * FRICTION * FORCE_N, rel=1e-6)


def test_uncoupled_steps_give_mindlins_stick_zone_and_shear(study):
    a, _ = hertz()
    for row in study:
        for m in row:
            assert m.step.tangential_force_N == pytest.approx(
                m.ratio * FRICTION * FORCE_N, rel=1e-8)
            # the stick zone: central, its half-width within half a node spacing of c
            assert abs(m.stick_centre_m) < 1e-6 * a
            assert abs(m.stick_half_width_m - m.c_m) <= 0.5 * m.node_spacing_m + 1e-9 * a
            # slipping nodes carry mu p, sticking ones less
            p, q = m.step.contact.pressure_Pa, m.step.shear_Pa
            slipping = (p > 0.0) & ~m.step.sticking
            np.testing.assert_allclose(np.abs(q[slipping]), FRICTION * p[slipping], rtol=1e-8)
            assert np.all(np.abs(q[m.step.sticking]) < FRICTION * p[m.step.sticking])
            assert np.all(m.step.contact.slip_m[m.step.sticking] < 1e-12 * a)
    for m in study[1] + study[2]:  # a/16, a/32
        assert m.rms < 0.01 and m.largest < 0.04
    # unloading: the edges slip back (q = -mu p there), the middle sticks
    for row in study:
        unloaded = row[2].step
        edge = int(np.flatnonzero(unloaded.contact.pressure_Pa > 0.0)[0])
        assert unloaded.shear_Pa[edge] < 0.0


def test_shear_error_falls_as_the_contact_element_halves(study):
    for column in range(len(LOAD_RATIOS)):
        rms = [row[column].rms for row in study]
        assert np.all(np.diff(rms) < 0.0)
        assert rms[-1] < 0.5 * rms[0]


def test_coupled_step_shifts_the_stick_zone_but_keeps_its_width():
    """nu = 0.3: Q pushes the pressure back (Dundurs beta = 0.29); the stick zone follows and
    keeps Mindlin's width to within a node spacing."""
    a, _ = hertz()
    solver = flat_solver(16)
    solver.solve(FORCE_N)
    step = solver.solve_tangential_force(0.5 * FRICTION * FORCE_N, FORCE_N)
    assert step.contact.force_balance_rel_error < 1e-7
    x, p, w = step.contact.x_m, step.contact.pressure_Pa, solver.weights_m
    centroid = np.sum(w * p * x) / np.sum(w * p)
    half_width, centre = stick_half_width_m(step)
    print(f"\ncoupled: pressure centroid {centroid / a:+.4f} a, stick zone {half_width / a:.4f} a "
          f"about {centre / a:+.4f} a")
    assert -0.2 * a < centroid < -0.05 * a
    assert centre < 0.0
    node_spacing = 0.5 * solver.problem.mesh.contact_element_length_m()
    assert abs(half_width - math.sqrt(0.5) * a) <= node_spacing


def test_gross_slip_under_a_shift_every_node_slips():
    """The centre moved by 0.4 um: partial slip; by 3 um: gross slip, every node in contact
    at |tau| = mu p, Q = mu P to the tilt of the normals (|x|/R <= a/R); and back to -3 um:
    Q = -mu P."""
    a, _ = hertz()
    solver = flat_solver(8)
    solver.solve(FORCE_N)
    partial = solver.solve_tangential_shift(0.4e-6, FORCE_N)
    assert np.any(partial.sticking)
    assert 0.0 < partial.tangential_force_N < FRICTION * FORCE_N
    for shift_m, sense in ((3e-6, 1.0), (-3e-6, -1.0)):
        step = solver.solve_tangential_shift(shift_m, FORCE_N)
        p, q = step.contact.pressure_Pa, step.shear_Pa
        assert not np.any(step.sticking)
        np.testing.assert_allclose(q[p > 0.0], sense * FRICTION * p[p > 0.0], rtol=1e-9)
        assert step.contact.pin_centre_m[0] == pytest.approx(shift_m, rel=1e-9)
        assert abs(sense * step.tangential_force_N / (FRICTION * FORCE_N) - 1.0) < a / RADIUS_M
        assert step.contact.force_balance_rel_error < 1e-7
        assert np.all(step.contact.slip_m[p > 0.0] > 0.0)


def test_frictional_steps_refused_without_pressing_or_beyond_mu_p():
    solver = flat_solver(8)
    with pytest.raises(FewearInputError, match="needs the cylinder pressed"):
        solver.solve_tangential_force(10.0, FORCE_N)
    solver.solve(FORCE_N)
    for bad in (FRICTION * FORCE_N, math.nan):
        with pytest.raises(FewearInputError, match="force control needs"):
            solver.solve_tangential_force(bad, FORCE_N)
    # a plain solve afterwards releases the shear
    solver.solve_tangential_force(0.5 * FRICTION * FORCE_N, FORCE_N)
    again = solver.solve(FORCE_N)
    assert again.resultant_force_N[0] == pytest.approx(0.0, abs=1e-6 * FORCE_N)


def test_a_uniformly_worn_cylinder_presses_as_the_unworn_one_lowered():
    """The cylinder worn by h0 everywhere (fewear.contact.flat.set_cylinder_wear) is the circle
    of radius R - h0: the same contact with the centre h0 lower. Worn only over |s| < 4 a (zero
    beyond, out of contact): the same."""
    a, _ = hertz()
    solver = flat_solver(8)
    unworn = solver.solve(FORCE_N)
    worn_depth = 0.5e-6
    solver.set_cylinder_wear(np.array([-4 * a, 4 * a]), np.array([worn_depth, worn_depth]))
    worn = solver.solve(FORCE_N)
    assert worn.pin_centre_m[1] == pytest.approx(unworn.pin_centre_m[1] - worn_depth,
                                                 abs=1e-6 * worn_depth)
    np.testing.assert_allclose(worn.pressure_Pa, unworn.pressure_Pa, rtol=1e-6,
                               atol=1e-6 * unworn.max_pressure_Pa)
    np.testing.assert_array_equal(worn.y_m, unworn.y_m)
    # a shift carries the worn cylinder along: gross slip as before, the centre lowered
    step = solver.solve_tangential_shift(3e-6, FORCE_N)
    assert not np.any(step.sticking)
    assert step.contact.pin_centre_m[1] < unworn.pin_centre_m[1] - 0.9 * worn_depth


def test_compile_flat_covers_the_argument_types_of_the_flats_solves(study):
    """compile_flat (run by the set-up) calls the flat's kernels with the argument types of its
    solves: after it and the study's normal and frictional solves, no kernel of
    fewear.contact.flat_newton holds a second signature (a scar run would compile that one)."""
    from numba.core.registry import CPUDispatcher

    from fewear.contact import flat_newton

    flat_newton.compile_flat()
    signatures = {name: len(kernel.signatures) for name, kernel in vars(flat_newton).items()
                  if isinstance(kernel, CPUDispatcher) and kernel.signatures}
    # the solves' callees are compiled into them, without signatures of their own
    assert signatures["run_coupled_newton"] == signatures["run_solve_on_ray"] == 1
    assert max(signatures.values()) == 1
