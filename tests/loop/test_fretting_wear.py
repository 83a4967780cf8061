"""Fretting wear blocks on the flat and the cylinder (fewear.loop.fretting.run_fretting_wear)
against Archard's global estimate and the scar's symmetry.

The case: McColl, Ding & Leen 2004 as the scar command models it (rigid cylinder R = 6 mm on a
flat of E = 100 GPa, nu = 0.3: the steel pair's E*; P = 185 N over 10 mm, mu = 0.9, stroke
+-25 um, k = 2.9e-14 m^2/N on the flat, k_c = 1.9e-14 m^2/N on the cylinder), on a small flat
(2 x 1 mm, contact elements of 20 um over |x| < 0.2 mm): 2 blocks of 1000 cycles, 8 increments
per cycle.

Archard (J. Appl. Phys. 24 (1953) 981): the worn area is k times the integral of p s over the
top and the cycles; flat and cylinder share p and s, so their areas stand as k : k_c (measured
to 1e-5), and together they are (k + k_c) times the integral. Every slipping node carries
|tau| = mu p, so that integral is the friction work over mu, N sum_blocks E_d / (mu L), E_d the
energy a cycle dissipates. In gross slip E_d = 4 Q* (d - d_stick)
(tests/loop/test_fretting_cycle.py), so the area is (k + k_c) P' 4 (d - d_stick) N_total to the
normals' tilt: measured 0.973 of (k + k_c) P' 4 d N_total (d_stick about 0.7 um). The scar is a
U (gross slip): deepest in the middle, its mirrored flanks 13 % of the depth apart (the
increments wear in turn, each block lopsided towards its first sense, the blocks alternating
it: coarse here, 8 increments and blocks of 1000).
"""

import numpy as np
import pytest

from fewear.contact.params import BushingMaterial, ContactSettings, FlatContactProblem
from fewear.errors import FewearInputError
from fewear.loop.settings import FrettingWearSettings
from fewear.mesh.geometry import FlatGeometry, FlatMeshSettings
from fewear.wear.scar import scar_depth_and_width_m

FORCE_N, LENGTH_M, FRICTION, STROKE_M, K_M2_N = 185.0, 0.010, 0.9, 25e-6, 2.9e-14
K_CYLINDER_M2_N = 1.9e-14


@pytest.fixture(scope="module")
def run():
    from fewear.loop.fretting import run_fretting_wear

    geometry = FlatGeometry(0.006, 2e-3, 1e-3, LENGTH_M, 6e-6)
    mesh = FlatMeshSettings(20e-6, 0.2e-3, 12, 16)
    problem = FlatContactProblem(geometry, BushingMaterial(100e9, 0.3), mesh,
                                 ContactSettings(friction_coefficient=FRICTION))
    blocks = []
    result = run_fretting_wear(problem, FrettingWearSettings(
        FORCE_N, STROKE_M, 8, 2000, 1000, K_M2_N, K_CYLINDER_M2_N), report=blocks.append)
    return result, blocks


def test_worn_area_is_archards_on_the_friction_work(run):
    result, blocks = run
    area, cylinder = result.state.worn_area_m2(), result.cylinder.worn_area_m2()
    archard = (K_M2_N + K_CYLINDER_M2_N) * FORCE_N / LENGTH_M * 4.0 * STROKE_M * 2000
    print(f"\nworn areas {area:.5g} + {cylinder:.5g} m^2 = {(area + cylinder) / archard:.4f} of "
          f"(k + k_c) P' 4 d N, ratio {area / cylinder:.5f}; blocks "
          f"{[round(b.max_depth_m * 1e9) for b in blocks]} nm")
    assert 0.95 < (area + cylinder) / archard < 1.0
    assert area / cylinder == pytest.approx(K_M2_N / K_CYLINDER_M2_N, rel=2e-3)
    # the first cycle (unworn flat) dissipates what the wear of its N cycles says
    first = result.first_cycle
    assert first.dissipated_energy_J == pytest.approx(
        FRICTION * first.length_m * np.sum(first.weights_m * first.pressure_slip_Pa_m),
        rel=1e-6)
    assert [b.cycles for b in blocks] == [1000, 2000]
    assert blocks[1].max_depth_m > blocks[0].max_depth_m > 0.0


def test_the_scar_is_a_symmetric_u(run):
    result, _ = run
    x, depth = result.state.x_m, result.state.depth_m
    deepest, width = scar_depth_and_width_m(x, depth)
    mirrored = np.interp(-x, x, depth)
    assert np.max(np.abs(depth - mirrored)) < 0.15 * deepest
    assert result.state.depth_at(0.0) > 0.95 * deepest
    assert 2 * STROKE_M < width < 0.4e-3


def stiffness_factorised_solver():
    """The flat's solver with the bushing's Newton direction (K = K_el + J factorised at every
    Newton step): the reference of the flat's own (K_el once per geometry, Woodbury)."""
    from fewear.contact.flat import FlatContactSolver
    from fewear.contact.solver import BushingContactSolver

    class StiffnessFactorised(FlatContactSolver):
        _bordered_step = BushingContactSolver._bordered_step

    return StiffnessFactorised


def test_newton_steps_by_the_elastic_factorisation_are_the_stiffness_factorisations(
        monkeypatch):
    """The flat's Newton directions by K_el factorised once per geometry and the Woodbury
    identity on the top (fewear.contact.flat) against the bushing's, K = K_el + J factorised at
    every Newton step: one block of 1000 cycles (8 frictional increments, each wearing flat
    and cylinder and moving the mesh) ends in the same scar to 1e-9 of its depth, by the same
    Newton iterations and tangential forces."""
    import fewear.loop.fretting
    from fewear.contact.flat import FlatContactSolver

    geometry = FlatGeometry(0.006, 2e-3, 1e-3, LENGTH_M, 6e-6)
    problem = FlatContactProblem(geometry, BushingMaterial(100e9, 0.3),
                                 FlatMeshSettings(20e-6, 0.2e-3, 12, 16),
                                 ContactSettings(friction_coefficient=FRICTION))
    settings = FrettingWearSettings(FORCE_N, STROKE_M, 8, 1000, 1000, K_M2_N, K_CYLINDER_M2_N)
    runs = []
    for solver in (FlatContactSolver, stiffness_factorised_solver()):
        monkeypatch.setattr(fewear.loop.fretting, "FlatContactSolver", solver)
        runs.append(fewear.loop.fretting.run_fretting_wear(problem, settings))
    fast, reference = runs
    depth = reference.state.depth_m
    assert depth.max() > 0.0
    assert np.abs(fast.state.depth_m - depth).max() < 1e-9 * depth.max()
    assert np.abs(fast.cylinder.depth_m - reference.cylinder.depth_m).max() < (
        1e-9 * reference.cylinder.depth_m.max())
    assert np.array_equal(fast.first_cycle.newton_iterations,
                          reference.first_cycle.newton_iterations)
    assert fast.first_cycle.tangential_force_N == pytest.approx(
        reference.first_cycle.tangential_force_N, rel=1e-9)


@pytest.mark.parametrize("changes, message", [
    ({"increments_per_cycle": 10}, "multiple of 4"),
    ({"cycles_per_block": 7}, "must divide cycles"),
    ({"stroke_amplitude_m": -1.0}, "stroke_amplitude_m"),
    ({"cycles": 0}, r"cycles = 0: must be a whole number"),
    ({"cylinder_wear_coefficient_m2_N": -1e-14}, "cylinder_wear_coefficient_m2_N = -1e-14"),
])
def test_settings_refuse_bad_values(changes, message):
    values = dict(normal_force_N=FORCE_N, stroke_amplitude_m=STROKE_M, increments_per_cycle=8,
                  cycles=2000, cycles_per_block=1000, wear_coefficient_m2_N=K_M2_N)
    with pytest.raises(FewearInputError, match=message):
        FrettingWearSettings(**{**values, **changes})
