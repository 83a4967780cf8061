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


# One block of 1000 cycles (8 frictional increments, each wearing flat and cylinder and moving
# the mesh) by the flat's contact on the whole field, which the condensed contact replaced
# (commit 54de567: K_el factorised once per geometry, the Newton steps by the Woodbury identity
# on the top's dofs, themselves equal to the steps by K_el + J factorised, the bushing's): the
# flat's depth at these x (m), the largest depths of flat and cylinder (m), the first cycle's
# Newton iterations and tangential forces (N).
WHOLE_FIELD_X_M = np.array([-60e-6, -40e-6, -20e-6, 0.0, 20e-6, 40e-6, 60e-6])
WHOLE_FIELD_DEPTH_M = np.array([
    2.5273779616258117e-07, 3.2579897674640608e-07, 3.8085532001665791e-07,
    3.9976419174625300e-07, 3.8042871552297431e-07, 3.2435708111167449e-07,
    2.3170311865099278e-07])
WHOLE_FIELD_MAX_DEPTH_M, WHOLE_FIELD_CYLINDER_DEPTH_M = 3.99764191746518e-07, 2.870521175618533e-07
WHOLE_FIELD_ITERATIONS = [7, 5, 6, 5, 6, 6, 5, 5]
WHOLE_FIELD_FORCE_N = [166.23331372633922, 166.4698255162539, -166.1710436906928,
                       -166.73479890925387, -167.0850512324807, -167.37179382151174,
                       165.4992696019981, 166.8586575920956]


def test_the_condensed_contact_wears_as_the_whole_fields_did():
    """The block by the flat condensed onto its top (fewear.contact.flat) against the same
    block by the whole field's Newton it replaced (the figures above): the same scar to 1e-9
    of its depth, the same tangential forces (to 1e-9), by the same Newton iterations to one
    (the stopping test's largest displacement and update are the top nodes' now, the whole
    field's dofs' then: the first increment stops one step earlier)."""
    from fewear.loop.fretting import run_fretting_wear

    geometry = FlatGeometry(0.006, 2e-3, 1e-3, LENGTH_M, 6e-6)
    problem = FlatContactProblem(geometry, BushingMaterial(100e9, 0.3),
                                 FlatMeshSettings(20e-6, 0.2e-3, 12, 16),
                                 ContactSettings(friction_coefficient=FRICTION))
    settings = FrettingWearSettings(FORCE_N, STROKE_M, 8, 1000, 1000, K_M2_N, K_CYLINDER_M2_N)
    run = run_fretting_wear(problem, settings)
    tolerance = 1e-9 * WHOLE_FIELD_MAX_DEPTH_M
    assert np.abs(run.state.depth_at(WHOLE_FIELD_X_M) - WHOLE_FIELD_DEPTH_M).max() < tolerance
    assert abs(run.state.depth_m.max() - WHOLE_FIELD_MAX_DEPTH_M) < tolerance
    assert run.cylinder.depth_m.max() == pytest.approx(WHOLE_FIELD_CYLINDER_DEPTH_M, rel=1e-9)
    assert np.abs(run.first_cycle.newton_iterations - WHOLE_FIELD_ITERATIONS).max() <= 1
    assert run.first_cycle.tangential_force_N == pytest.approx(WHOLE_FIELD_FORCE_N, rel=1e-9)


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
