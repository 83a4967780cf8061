"""A rigid cylinder pressed on an elastic flat (fewear.contact.flat) against Hertz line contact.

Hertz line contact of a rigid cylinder of radius R on an elastic half-space, plane strain,
frictionless (Johnson, *Contact Mechanics*, 1985, sec. 4.3): with E* = E/(1 - nu^2) and the line
load P' = P/L,

    a = sqrt(4 P' R / (pi E*)),   p0 = 2 P' / (pi a),   p(x) = p0 sqrt(1 - x^2/a^2).

The case: the block-on-ring test (Cruzado et al. 2010) with a rigid ring, R = 20 mm on steel,
E = 210 GPa, nu = 0.3, P = 65 N over L = 6 mm: a = 34.6 um, p0 = 199 MPa. The flat is W = H = 40 a
wide and high, its contact zone |x| < 2 a in equal elements of a/4, a/8 and a/16.

Measured: the largest nodal pressure against p0; the half-width as the second-moment width
a_m = 2 sqrt(int p x^2 / int p) and as the Hertz ellipse fitted to the loaded nodes
(:mod:`fewear.contact.analytic`, as tests/contact/test_hertz.py does for the bushing); the RMS of
p - p_Hertz over |x| <= a (the nodal quadrature), relative to p0. At a/4, a/8, a/16: peak
+0.35, +0.08, +0.02 %; a_m -0.09, -0.004, -0.001 %; RMS 1.1, 0.54, 0.27 % (first order: the
pressure's square-root edge).

What else is in these errors (measured at h = a/8, not tested here): the finite flat, against
the half-space: W = H = 20 a, 40 a, 80 a, 160 a gave peak +0.20, +0.08, +0.05, +0.04 % and a_m
-0.13, -0.004, +0.03, +0.03 %, so at 40 a the body's size is worth about 0.05 %. The penalty
law's compliance: the penetration p/k = p h/(f E*) (k = f E*/h, f the penalty factor) is at the
peak a h/(2 f R), against the cylinder's profile depth a^2/(2 R) at the contact's edge: h/(f a) =
1/800 of it at f = 100; measured (on R = 6 mm, a = 25 um), p0 +0.045 % at f = 100 against
+0.085 % at f = 1000 and -0.34 % at f = 10. So the default f = 100 is kept and the tolerances
below are far above both effects.
"""

import math

import numpy as np
import pytest

from fewear.contact.analytic import fit_hertz_ellipse, moment_half_width_m
from fewear.contact.params import BushingMaterial, ContactSettings, FlatContactProblem
from fewear.errors import FewearInputError
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings

RADIUS_M, YOUNGS_MODULUS_PA, POISSON_RATIO = 0.020, 210e9, 0.3
FORCE_N, LENGTH_M = 65.0, 0.006
FLAT_SIZE_IN_A, ZONE_IN_A = 40.0, 2.0
ELEMENTS_PER_HALF_WIDTH = (4, 8, 16)


def hertz():
    """(a (m), p0 (Pa)) of Hertz line contact (module docstring)."""
    contact_modulus = YOUNGS_MODULUS_PA / (1.0 - POISSON_RATIO**2)
    line_load = FORCE_N / LENGTH_M
    half_width = math.sqrt(4.0 * line_load * RADIUS_M / (math.pi * contact_modulus))
    return half_width, 2.0 * line_load / (math.pi * half_width)


def flat_problem(elements_per_half_width):
    a, _ = hertz()
    geometry = FlatGeometry(cylinder_radius_m=RADIUS_M, width_m=FLAT_SIZE_IN_A * a,
                            height_m=FLAT_SIZE_IN_A * a, length_m=LENGTH_M,
                            standoff_m=1e-3 * RADIUS_M)
    mesh = FlatMeshSettings(contact_element_size_m=a / elements_per_half_width,
                            contact_zone_half_width_m=ZONE_IN_A * a)
    return FlatContactProblem(geometry, BushingMaterial(YOUNGS_MODULUS_PA, POISSON_RATIO), mesh,
                              ContactSettings())


class Comparison:
    """One FE solution beside Hertz (relative errors signed; the RMS relative to p0)."""

    def __init__(self, solver, result):
        a, p0 = hertz()
        x, p, w = result.x_m, result.pressure_Pa, solver.weights_m
        self.solver, self.result, self.weights = solver, result, w
        self.element_m = solver.problem.mesh.contact_element_length_m()
        self.peak = p.max() / p0 - 1.0
        self.moment_width = moment_half_width_m(x, p, w) / a - 1.0
        self.fit = fit_hertz_ellipse(x, p)
        inside = np.abs(x) <= a
        reference = p0 * np.sqrt(np.clip(1.0 - (x / a) ** 2, 0.0, None))
        self.rms = math.sqrt(np.sum(w[inside] * (p - reference)[inside] ** 2)
                             / np.sum(w[inside])) / p0


@pytest.fixture(scope="module")
def study():
    from fewear.contact.flat import FlatContactSolver

    comparisons = []
    for per_half_width in ELEMENTS_PER_HALF_WIDTH:
        solver = FlatContactSolver(flat_problem(per_half_width))
        comparisons.append(Comparison(solver, solver.solve(FORCE_N)))
    a, p0 = hertz()
    print(f"\nHertz: a = {a * 1e6:.2f} um, p0 = {p0 / 1e6:.1f} MPa")
    for c in comparisons:
        print(f"h = a/{a / c.element_m:.0f}: peak {c.peak:+.3%}, half-width: second moment "
              f"{c.moment_width:+.3%}, ellipse fit {c.fit.half_width_m / a - 1:+.3%}; RMS "
              f"{c.rms:.3%} of p0; {c.result.newton_iterations} Newton, balance "
              f"{c.result.force_balance_rel_error:.1e}")
    return comparisons


def test_hertz_formulas_give_the_research_notes_figures():
    a, p0 = hertz()
    assert a == pytest.approx(34.6e-6, rel=2e-3)
    assert p0 == pytest.approx(199e6, rel=3e-3)


@pytest.mark.parametrize("index", [1, 2], ids=["a/8", "a/16"])
def test_pressure_within_1_percent_of_hertz(study, index):
    a, p0 = hertz()
    comparison = study[index]
    assert abs(comparison.peak) < 0.01
    assert abs(comparison.moment_width) < 0.01
    assert comparison.fit.half_width_m == pytest.approx(a, rel=0.01)
    assert comparison.fit.peak_pressure_Pa == pytest.approx(p0, rel=0.01)
    assert abs(comparison.fit.centre_m) < 1e-3 * a       # on the cylinder's axis, x = 0
    assert comparison.rms < 0.01
    # the pressure vanishes outside the strip (beyond its last element)
    result = comparison.result
    assert np.all(result.pressure_Pa[np.abs(result.x_m) > a + comparison.element_m] == 0.0)


def test_errors_fall_as_the_contact_element_halves(study):
    sizes = np.array([c.element_m for c in study])
    rms = np.array([c.rms for c in study])
    peaks = np.array([abs(c.peak) for c in study])
    rate = np.polyfit(np.log(sizes), np.log(rms), 1)[0]
    print(f"\nRMS {rms}, fitted rate {rate:.2f}; peak errors {peaks}")
    assert np.all(np.diff(rms) < 0.0) and np.all(np.diff(peaks) < 0.0)
    assert 0.8 < rate < 1.5


def test_contact_resultant_balances_the_force(study):
    """The resultant equals the applied force to 1e-8, or to the level at which the penalty
    forces are computed where that is higher: a gap |X + u - c| - R is computed to ~eps R,
    which the penalty k turns into k eps R per unit length of contact (the Newton's own stopping
    level, fewear.contact.newton.converged)."""
    for comparison in study:
        result, problem = comparison.result, comparison.solver.problem
        np.testing.assert_array_equal(result.applied_force_N, (0.0, -FORCE_N))
        loaded = result.pressure_Pa > 0.0
        rounding = (problem.penalty_stiffness_Pa_per_m() * np.finfo(float).eps * RADIUS_M
                    * comparison.weights[loaded].sum() * LENGTH_M / FORCE_N)
        assert result.force_balance_rel_error < max(1e-8, rounding)
        assert abs(result.resultant_force_N[0]) < 1e-9 * FORCE_N   # symmetric: no x force
        # the nodal pressures with the Gauss-Lobatto weights carry the force (normals within
        # a/R = 2e-3 rad of -y: cos to 2e-6)
        carried = LENGTH_M * np.sum(comparison.weights * result.pressure_Pa)
        assert carried == pytest.approx(FORCE_N, rel=1e-5)
        # the cylinder stays on its ray, below the origin by the standoff and its approach
        assert result.pin_centre_m[0] == pytest.approx(0.0, abs=1e-20)
        assert result.pin_centre_m[1] < -problem.geometry.standoff_m


def test_no_force_no_contact_and_bad_forces_refused(study):
    from fewear.contact.flat import FlatLoadError

    solver = study[0].solver
    empty = solver.solve(0.0)
    assert np.all(empty.pressure_Pa == 0.0) and np.all(empty.pin_centre_m == 0.0)
    for bad in (-1.0, math.nan, "heavy"):
        with pytest.raises(FewearInputError, match="normal force = .*expected a finite number"):
            solver.solve(bad)
    # a strip wider than the contact zone |x| < 2a: Hertz a = x_c at 4 P
    contact_modulus = YOUNGS_MODULUS_PA / (1.0 - POISSON_RATIO**2)
    x_c = ZONE_IN_A * hertz()[0]
    admissible = LENGTH_M * math.pi * contact_modulus * x_c**2 / (4.0 * RADIUS_M)
    assert admissible == pytest.approx(ZONE_IN_A**2 * FORCE_N, rel=1e-12)
    assert solver.admissible_force_N() == pytest.approx(admissible, rel=1e-12)
    with pytest.raises(FlatLoadError, match="contact strip would reach"):
        solver.solve(1.5 * admissible)
    # and the solver solves again afterwards
    assert solver.solve(FORCE_N).max_pressure_Pa == pytest.approx(
        study[0].result.max_pressure_Pa, rel=1e-6)
