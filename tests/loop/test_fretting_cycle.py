"""The stroke cycle of the cylinder on the flat (fewear.loop.fretting) against closed forms.

The case: McColl, Ding & Leen 2004's pair with a rigid cylinder, as in
tests/contact/test_flat_mindlin.py (R = 6 mm, E = 200 GPa, nu = 0.3, P = 185 N over 10 mm,
mu = 0.9: a = 25.4 um); the flat 40 a wide and high, contact elements of a/8 over |x| < 3 a.

Gross slip (strokes d = 4 and 8 um, far above the elastic displacement at gross slip, 0.65 um
at Q = 0.99 mu P): every node slips in every increment, |Q| = mu P less the normals' tilt
(the pressure's x component, bounded by a/R = 0.42 %; measured 0.24 %), and a steady cycle
(the second: the first starts from no shear and sticks over d_stick once more) dissipates
4 Q* (d - d_stick) (the Coulomb loop: Q = +-Q* except over 2 d_stick after each reversal,
Masing's rule: the effective d_stick is (2/Q*) times the integral of x dQ on loading). The
stroke d = 4 um gives d_stick = 0.642 um, 8 um 0.646 um (the same stick: 0.65 um is the
force-controlled x at Q = 0.99 mu P). The difference of two strokes, 4 Q* (d2 - d1), holds
whatever d_stick: measured 0.99670 of 4 mu P (d2 - d1), Q*/mu P being 0.99757 (slow: 14 s).

Partial slip (d = 0.3 um, Q* = 0.47 mu P): the centre sticks throughout, Q < mu P, and on the
steady (second) cycle the energy friction dissipates, sum over nodes and increments of |tau| s,
equals the hysteresis loop's area, the integral of Q dx (conservation: the cycle returns the
elastic energy it stores); 16 increments per cycle, the loop integrated by the trapezoid rule,
agree to 3.6 % (the trapezoid's error on the curved branches, 4 increments each).
"""

import math

import numpy as np
import pytest

from fewear.contact.params import BushingMaterial, ContactSettings, FlatContactProblem
from fewear.errors import FewearInputError
from fewear.loop.fretting import stroke_cycle, stroke_positions_m
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings

RADIUS_M, YOUNGS_MODULUS_PA, POISSON_RATIO = 0.006, 200e9, 0.3
FORCE_N, LENGTH_M, FRICTION = 185.0, 0.010, 0.9
HALF_WIDTH_M = math.sqrt(4.0 * FORCE_N / LENGTH_M * RADIUS_M
                         / (math.pi * YOUNGS_MODULUS_PA / (1.0 - POISSON_RATIO**2)))


@pytest.fixture(scope="module")
def solver():
    from fewear.contact.flat import FlatContactSolver

    a = HALF_WIDTH_M
    geometry = FlatGeometry(RADIUS_M, 40.0 * a, 40.0 * a, LENGTH_M, 1e-3 * RADIUS_M)
    mesh = FlatMeshSettings(contact_element_size_m=a / 8, contact_zone_half_width_m=3.0 * a)
    return FlatContactSolver(FlatContactProblem(
        geometry, BushingMaterial(YOUNGS_MODULUS_PA, POISSON_RATIO), mesh,
        ContactSettings(friction_coefficient=FRICTION)))


def steady_cycle(solver, amplitude_m, increments):
    """The second cycle after a fresh solve(P), and the first's last Q (N)."""
    solver.solve(FORCE_N)
    first = stroke_cycle(solver, FORCE_N, amplitude_m, increments)
    return stroke_cycle(solver, FORCE_N, amplitude_m, increments), first.tangential_force_N[-1]


def test_stroke_is_the_triangle_in_equal_increments():
    d = 25e-6
    np.testing.assert_allclose(stroke_positions_m(d, 8) / d, [0.5, 1, 0.5, 0, -0.5, -1, -0.5, 0],
                               atol=1e-15)
    for bad in (6, 0, 8.0, True):
        with pytest.raises(FewearInputError, match="multiple of 4"):
            stroke_positions_m(d, bad)
    with pytest.raises(FewearInputError, match="amplitude"):
        stroke_positions_m(-d, 8)


def gross_slip_cycle(solver, amplitude_m):
    """The steady cycle of stroke ``amplitude_m`` in 4 increments, checked for gross slip in
    every increment (Q = +-mu P less the normals' tilt; every loaded node slips), and its
    d_stick = d - E / (4 Q*) (m)."""
    mu_p = FRICTION * FORCE_N
    cycle, _ = steady_cycle(solver, amplitude_m, 4)
    ratio = np.abs(cycle.tangential_force_N) / mu_p
    assert np.all((1.0 - HALF_WIDTH_M / RADIUS_M < ratio) & (ratio < 1.0))
    assert np.all(cycle.slip_m[cycle.pressure_slip_Pa_m > 0.0] > 0.0)
    stick = amplitude_m - cycle.dissipated_energy_J / (4.0 * np.abs(
        cycle.tangential_force_N).mean())
    print(f"\nd = {amplitude_m * 1e6:g} um: E = {cycle.dissipated_energy_J:.6g} J = 4 mu P "
          f"{cycle.dissipated_energy_J / (4 * mu_p) * 1e6:.4f} um; d_stick {stick * 1e6:.3f} um")
    return cycle, stick


def test_gross_slip_dissipates_four_q_over_the_stroke_less_the_stick(solver):
    _, stick = gross_slip_cycle(solver, 4e-6)
    assert 0.6e-6 < stick < 0.7e-6  # the force-controlled x(0.99 mu P): 0.65 um


@pytest.mark.slow
def test_gross_slip_dissipates_four_mu_p_per_stroke_length(solver):
    (short, short_stick), (long, long_stick) = (gross_slip_cycle(solver, amplitude)
                                                for amplitude in (4e-6, 8e-6))
    assert long_stick == pytest.approx(short_stick, rel=0.02)
    slope = ((long.dissipated_energy_J - short.dissipated_energy_J)
             / (4.0 * FRICTION * FORCE_N * 4e-6))
    print(f"E(8 um) - E(4 um) = {slope:.5f} of 4 mu P (d2 - d1)")
    assert 1.0 - HALF_WIDTH_M / RADIUS_M < slope < 1.0


@pytest.mark.slow  # 4-8 s; the default suite keeps under 6 minutes
def test_partial_slip_loop_area_is_the_dissipated_energy(solver):
    cycle, start_force = steady_cycle(solver, 0.3e-6, 16)
    mu_p = FRICTION * FORCE_N
    assert np.abs(cycle.tangential_force_N).max() < 0.6 * mu_p
    centre = np.argmin(np.abs(cycle.x_m))
    assert cycle.slip_m[centre] < 1e-12
    loop, dissipated = cycle.loop_area_J(0.0, start_force), cycle.dissipated_energy_J
    print(f"\npartial slip: loop {loop:.5g} J, dissipated {dissipated:.5g} J")
    assert loop == pytest.approx(dissipated, rel=0.05)
