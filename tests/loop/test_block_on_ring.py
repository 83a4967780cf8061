"""Block on ring through the FE wear loop on the flat (fewear.loop.flat_wear), against Archard's
volume and the ring-arc closed form.

The case (Cruzado et al., Rev. Metal. 46 (2010) 106-114, as the issue 22 research note reads
it): a rigid, unworn ring of R = 20 mm pressed with P = 65 N on a steel block (E = 210 GPa,
nu = 0.3) L = 6 mm wide, sliding S = 3600 m, frictionless, k = 2e-15 m^2/N on the block.
Archard (J. Appl. Phys. 24 (1953) 981) makes the worn area A = k P' S (P' = P/L) whatever the
pressure; the ring unworn makes the scar its arc sunk by d, A = R^2 acos((R - d)/R) -
(R - d) sqrt(2 R d - d^2) (fewear.wear.scar): A = 0.0780 mm^2, d = 44.07 um, chord 2.654 mm, and
2.587 mm where the depth exceeds 5 % of d (the measured scars' criterion).

Default: a coarse flat (8 x 4 mm, contact elements of 100 um) in 15 and 30 steps, seconds each.
Measured (this mesh): area +8e-5 / +6e-5, depth -0.014 % / -0.017 %, 5 % width +0.000 / +0.001 %
of the closed form at N = 15 / 30. The slow study at 20 um elements prints the table over
N = 15, 30, 60, 120. The unworn contact of the loop's first solve is the plain
FlatContactSolver.solve, checked against Hertz in tests/contact/test_flat_hertz.py.
"""

import math
import sys

import numpy as np
import pytest

from fewear.contact.params import BushingMaterial, ContactSettings, FlatContactProblem
from fewear.errors import FewearInputError
from fewear.loop.settings import SlidingWearSettings
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings
from fewear.wear.scar import (
    EDGE_SHARE,
    ring_arc_depth_m,
    ring_arc_width_m,
    scar_depth_and_width_m,
)

RING_RADIUS_M, LENGTH_M, FORCE_N = 0.020, 0.006, 65.0
SLIDING_M, WEAR_COEFFICIENT_M2_N = 3600.0, 2e-15
COARSE_ELEMENT_M, FINE_ELEMENT_M = 100e-6, 20e-6


def block_on_ring_problem(element_size_m):
    """The block under the ring: 8 mm wide, 4 mm high, contact elements over |x| < 1.6 mm (the
    scar's half-width is 1.33 mm)."""
    geometry = FlatGeometry(cylinder_radius_m=RING_RADIUS_M, width_m=8e-3, height_m=4e-3,
                            length_m=LENGTH_M, standoff_m=2e-5)
    mesh = FlatMeshSettings(contact_element_size_m=element_size_m,
                            contact_zone_half_width_m=1.6e-3, side_element_count=12,
                            depth_element_count=20)
    return FlatContactProblem(geometry, BushingMaterial(210e9, 0.3), mesh, ContactSettings())


def wear_settings(steps):
    return SlidingWearSettings(FORCE_N, SLIDING_M, WEAR_COEFFICIENT_M2_N, steps)


def archard_area_m2():
    """k P' S (m^2)."""
    return WEAR_COEFFICIENT_M2_N * FORCE_N / LENGTH_M * SLIDING_M


def run(element_size_m, steps, report=None):
    from fewear.loop.flat_wear import run_flat_wear

    return run_flat_wear(block_on_ring_problem(element_size_m), wear_settings(steps),
                         report=report)


def figures(flat_run):
    """(area, depth, width at 5 %) of a run relative to the closed form, minus 1."""
    depth = ring_arc_depth_m(RING_RADIUS_M, archard_area_m2())
    deepest, width = scar_depth_and_width_m(flat_run.state.x_m, flat_run.state.depth_m)
    return (flat_run.state.worn_area_m2() / archard_area_m2() - 1.0, deepest / depth - 1.0,
            width / ring_arc_width_m(RING_RADIUS_M, depth, EDGE_SHARE) - 1.0)


@pytest.fixture(scope="module")
def coarse_runs():
    return {steps: run(COARSE_ELEMENT_M, steps) for steps in (15, 30)}


@pytest.mark.parametrize("steps", [15, 30])
def test_worn_area_depth_and_width_are_the_closed_forms(coarse_runs, steps):
    area, depth, width = figures(coarse_runs[steps])
    print(f"\nN = {steps}: area {area:+.2e}, depth {depth:+.3%}, width {width:+.3%}")
    assert abs(area) < 1e-3
    assert abs(depth) < 5e-3
    assert abs(width) < 5e-3
    assert coarse_runs[steps].state.sliding_distance_m == pytest.approx(SLIDING_M, rel=1e-12)
    assert coarse_runs[steps].state.steps == steps


def test_the_scar_is_the_rings_arc(coarse_runs):
    """Every node's depth on the ring's arc sunk by the run's own depth, to 1 % of it: the
    shape, not only the largest depth and the width."""
    state = coarse_runs[30].state
    d = state.depth_m.max()
    arc = np.maximum(d - RING_RADIUS_M + np.sqrt(RING_RADIUS_M**2 - state.x_m**2), 0.0)
    assert np.max(np.abs(state.depth_m - arc)) < 0.01 * d
    assert abs(state.x_m[np.argmax(state.depth_m)]) < 1e-12      # deepest under the ring


def test_depth_converges_with_the_step_count(coarse_runs):
    depths = [coarse_runs[steps].state.depth_m for steps in (15, 30)]
    assert np.max(np.abs(depths[0] - depths[1])) < 1e-3 * depths[1].max()
    # the scar grows as the arc of the area slid so far: d(s) from k P' s at every step
    for step in coarse_runs[30].steps:
        expected = ring_arc_depth_m(RING_RADIUS_M, archard_area_m2() * step.sliding_distance_m
                                    / SLIDING_M)
        assert step.max_depth_m == pytest.approx(expected, rel=0.01)


def test_worn_mesh_top_on_the_worn_flat_and_cells_as_good_as_made(coarse_runs):
    flat_run = coarse_runs[30]
    top_y = block_on_ring_problem(COARSE_ELEMENT_M).geometry.top_y_m
    np.testing.assert_array_equal(flat_run.worn_top_xy_m[:, 0], flat_run.state.x_m)
    np.testing.assert_allclose(flat_run.worn_top_xy_m[:, 1],
                               flat_run.state.top_y_m(top_y, flat_run.state.x_m),
                               rtol=0, atol=1e-15)
    # 44 um of wear on a column 4 mm high: the cells shrink by 1 %, their angles turn by the
    # scar's slope (b/R = 0.07): the worst figures, elsewhere in the graded mesh, stay
    assert flat_run.quality.min_angle_sine >= flat_run.unworn_quality.min_angle_sine - 1e-3
    assert (flat_run.quality.min_scaled_jacobian
            >= flat_run.unworn_quality.min_scaled_jacobian - 1e-3)


def test_pressure_falls_from_hertz_to_the_conformal_scars(coarse_runs):
    """The unworn contact (Hertz: p0 = 199 MPa) carries P; the worn scar carries it at about
    P' / (2 b), 4 MPa over b = 1.3 mm (b the outermost loaded node: a little short), the
    peak nearly uniform (the step's end lowers the arc uniformly)."""
    flat_run = coarse_runs[30]
    assert flat_run.unworn_contact.force_balance_rel_error < 1e-8
    assert flat_run.unworn_contact.max_pressure_Pa > 100e6
    last = flat_run.steps[-1]
    mean = FORCE_N / LENGTH_M / (2.0 * last.contact_half_width_m)
    assert 0.9 * mean < last.max_pressure_Pa < 2.0 * mean


# The coarse 15-step run by the flat's contact on the whole field, which the condensed contact
# replaced (commit 54de567: K_el factorised once per wear step, the Newton steps by the Woodbury
# identity on the contact's dofs, themselves equal to the steps by K_el + J factorised, the
# bushing's): the depth at these x and the largest (m), the loaded half-width (m) and largest
# nodal pressure (Pa) of every step.
WHOLE_FIELD_X_M = np.linspace(-1.2e-3, 1.2e-3, 7)
WHOLE_FIELD_DEPTH_M = np.array([
    8.0445813062073763e-06, 2.8064340386555115e-05, 4.0067736154116568e-05,
    4.4067378716019255e-05, 4.0067736154109081e-05, 2.8064340386555277e-05,
    8.0445813062067580e-06])
WHOLE_FIELD_MAX_DEPTH_M = 4.40673787160245e-05
WHOLE_FIELD_HALF_WIDTH_NODES = [10, 13, 15, 17, 18, 19, 20, 21, 22, 23, 23, 24, 25, 25, 26]
WHOLE_FIELD_PRESSURE_PA = [
    15080669.685825162, 8852944.458435602, 7440543.888851515, 6678689.827694664,
    6062614.287229857, 5705658.228056437, 5404004.6118996665, 5137085.416686888,
    4932058.35608326, 4781591.5702768, 4579375.197152055, 4463360.534490369, 4341492.220137719,
    4222062.639418694, 4124888.069478999]


def test_the_condensed_contact_wears_as_the_whole_fields_did(coarse_runs):
    """The coarse 15-step run by the flat condensed onto its top (fewear.contact.flat) against
    the same run by the whole field's Newton it replaced (the figures above): the same scar to
    1e-9 of its depth, the same contact in every step (its half-width in node spacings of
    50 um, its largest pressure to 1e-9)."""
    fast = coarse_runs[15]
    tolerance = 1e-9 * WHOLE_FIELD_MAX_DEPTH_M
    assert np.abs(fast.state.depth_at(WHOLE_FIELD_X_M) - WHOLE_FIELD_DEPTH_M).max() < tolerance
    assert abs(fast.state.depth_m.max() - WHOLE_FIELD_MAX_DEPTH_M) < tolerance
    spacing = 0.5 * COARSE_ELEMENT_M
    assert [round(step.contact_half_width_m / spacing) for step in fast.steps] == (
        WHOLE_FIELD_HALF_WIDTH_NODES)
    assert [step.max_pressure_Pa for step in fast.steps] == pytest.approx(
        WHOLE_FIELD_PRESSURE_PA, rel=1e-9)


def test_series_compliance_is_a_softer_penalty_and_is_undone():
    """solve with the wear compliance c: p = <-g>_+ / (1/k + c) at the nodes; afterwards the
    solver's problem and penalty are as given and the plain solve repeats."""
    from fewear.contact.flat import FlatContactSolver
    from fewear.contact.flat_newton import PENALTY

    solver = FlatContactSolver(block_on_ring_problem(COARSE_ELEMENT_M))
    plain = solver.solve(FORCE_N)
    penalty = solver.problem.penalty_stiffness_Pa_per_m()
    compliance = WEAR_COEFFICIENT_M2_N * 240.0
    worn = solver.solve(FORCE_N, wear_compliance_m_per_Pa=compliance)
    np.testing.assert_allclose(worn.pressure_Pa,
                               np.maximum(-worn.gap_m, 0.0) / (1.0 / penalty + compliance),
                               rtol=1e-12, atol=0.0)
    assert worn.force_balance_rel_error < 1e-8
    assert np.count_nonzero(worn.pressure_Pa) > 5 * np.count_nonzero(plain.pressure_Pa)
    assert solver.problem.penalty_stiffness_Pa_per_m() == penalty
    assert solver.newton_state[6][PENALTY] == penalty
    np.testing.assert_allclose(solver.solve(FORCE_N).pressure_Pa, plain.pressure_Pa,
                               rtol=1e-8, atol=1e-8 * plain.max_pressure_Pa)
    for bad in (-1e-12, math.inf):
        with pytest.raises(FewearInputError, match="wear compliance = .* expected a finite"):
            solver.solve(FORCE_N, wear_compliance_m_per_Pa=bad)


@pytest.mark.parametrize("field, value, message", [
    ("normal_force_N", 0.0, "normal_force_N = 0.0: must be a finite number > 0"),
    ("sliding_distance_m", math.nan, "sliding_distance_m = nan"),
    ("wear_steps", 0, r"wear_steps = 0: must be a whole number in \[1, 10000\]"),
    ("wear_steps", 2.5, "wear_steps = 2.5"),
])
def test_bad_settings_are_refused(field, value, message):
    values = dict(normal_force_N=FORCE_N, sliding_distance_m=SLIDING_M,
                  wear_coefficient_m2_N=WEAR_COEFFICIENT_M2_N, wear_steps=15)
    values[field] = value
    with pytest.raises(FewearInputError, match=message):
        SlidingWearSettings(**values)


@pytest.mark.slow
def test_fine_mesh_convergence_table():
    """Contact elements of 20 um (LevelSetWear's), N = 15, 30, 60, 120: the figures and the
    run time of each, printed; each within the default test's tolerances."""
    print(f"\nblock on ring, elements {FINE_ELEMENT_M * 1e6:.0f} um: closed form d = "
          f"{ring_arc_depth_m(RING_RADIUS_M, archard_area_m2()) * 1e6:.3f} um")
    for steps in (15, 30, 60, 120):
        flat_run = run(FINE_ELEMENT_M, steps, report=lambda step: print(
            f"  {step.sliding_distance_m:7.1f} m: depth {step.max_depth_m * 1e6:7.3f} um",
            file=sys.stderr))
        area, depth, width = figures(flat_run)
        deepest, span = scar_depth_and_width_m(flat_run.state.x_m, flat_run.state.depth_m)
        print(f"N = {steps:3d}: area {area:+.2e}, depth {deepest * 1e6:.3f} um ({depth:+.3%}), "
              f"width {span * 1e3:.4f} mm ({width:+.3%}), {flat_run.wall_time_s:.1f} s")
        assert abs(area) < 1e-3 and abs(depth) < 5e-3 and abs(width) < 5e-3
