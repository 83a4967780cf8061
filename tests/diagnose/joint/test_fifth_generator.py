"""Tests of the fifth joint-wear generator itself (tests/diagnose/joint/generators/fifth.py): its
draws, laws and instrument models on analytic cases, its truth run against the believed forward
run, and its files against the reader. Not tests of the diagnosis."""

import json
import math
from dataclasses import replace

import numpy as np
import pytest

from fewear.diagnose.joint.forward import WearHistory, model_config, simulate_wear
from fewear.diagnose.joint.measured import (
    read_joint_measurements,
    write_joint_profiles,
    write_max_wear,
)
from fewear.mbd.history import JointHistory
from fewear.wear.archard import CycleSliding, block_wear
from fewear.wear.extensions import SlidingState
from tests.diagnose.joint.generators import fifth as gen


@pytest.fixture(scope="module")
def believed(tmp_path_factory):
    path = tmp_path_factory.mktemp("believed") / "believed.toml"
    path.write_text(gen.BELIEVED_TOML)
    return gen.believed_config(path)


# --- seeds and draws ------------------------------------------------------------------------

def test_seeds_are_distinct_and_checked():
    seeds = [gen.data_set_seed(cause, index) for cause in gen.CAUSES for index in range(5)]
    assert len(set(seeds)) == len(seeds)
    assert gen.data_set_seed("wear_coefficient", 0) == 15000
    assert gen.data_set_seed("none", 3) == 15503
    with pytest.raises(ValueError, match="unknown cause"):
        gen.data_set_seed("thermal", 0)
    with pytest.raises(ValueError, match="index"):
        gen.data_set_seed("none", 100)


def test_truth_draws_stay_in_their_ranges_and_branch_by_parity():
    for cause in gen.CAUSES:
        for index in range(6):
            seed = gen.data_set_seed(cause, index)
            truth_rng, _, _ = gen._streams(seed)
            params = gen.draw_truth(cause, truth_rng, index)
            again = gen.draw_truth(cause, gen._streams(seed)[0], index)
            assert params == again  # deterministic per seed
            assert params["causes"] == list(gen.cause_names(cause))
            even = index % 2 == 0
            if "wear_coefficient" in params:
                k = params["wear_coefficient"]
                if even:
                    assert k["law"] == "scale" and k["pressure_exponent"] == 0.0
                    assert (gen.K_SCALE_LOW[0] <= k["k_factor"] <= gen.K_SCALE_LOW[1]
                            or gen.K_SCALE_HIGH[0] <= k["k_factor"] <= gen.K_SCALE_HIGH[1])
                else:
                    assert k["law"] == "pressure_exponent"
                    assert 0.3 <= abs(k["pressure_exponent"]) <= 0.7
                    assert 0.85 <= k["k_factor"] <= 1.2
            if "flexible_link" in params:
                change = abs(params["flexible_link"]["modulus_factor"] - 1.0)
                assert (0.02 <= change <= 0.06) if even else (0.10 <= change <= 0.20)
                assert 3e-6 <= params["flexible_link"]["rod_damping_s"] <= 1e-5
            if "friction" in params:
                f = params["friction"]
                assert 2500 <= f["step_cycles"] <= 10000
                bounds = gen.FRICTION_DRY if even else gen.FRICTION_SOLID_LUBRICANT
                assert bounds[0] <= f["mu_after"] <= bounds[1]
            if "impact_wear" in params:
                assert 2.2 <= params["impact_wear"]["exponent"] <= 2.6
                assert 0.1 <= params["impact_wear"]["threshold_m_s"] <= 0.2
            if "running_in" in params:
                r = params["running_in"]
                assert 2.5 <= r["ratio"] <= 5 and 0.5 <= r["exponent"] <= 0.8
                assert 0.1 <= r["distance_scale_m"] <= 0.6


def test_lab_plans_follow_the_documented_plan():
    for seed in range(40):
        lab = gen.draw_lab(np.random.default_rng(seed))
        counts = lab.profile_cycles
        assert 3 <= len(counts) <= 6 and all(c % 500 == 0 for c in counts)
        assert 2000 <= counts[0] <= 4000 and 24000 <= counts[-1] <= 30000
        assert np.ptp(np.diff(counts)) <= 500  # equally spaced, up to the rounding
        assert 2 <= len(lab.max_wear_cycles) <= 3 or len(counts) == 3
        assert all(counts[0] < c < counts[-1] for c in lab.max_wear_cycles)
        assert not set(lab.max_wear_cycles) & set(counts)
        assert lab.force_cycles in ((), (counts[0], counts[-1]))
        assert lab.points in gen.POINTS_PER_REVOLUTION and lab.filter_upr in gen.FILTER_UPR
        assert lab.tip_radius_m in gen.TIP_RADII_M and abs(lab.origin_deg) <= 45.0
        assert 0.2e-6 <= lab.noise_m <= 0.8e-6 and len(lab.deleted) == len(counts)
        assert min(abs(lab.hole_deg - 90.0), abs(lab.hole_deg - 270.0)) <= 25.0
        assert lab.last_cycles == counts[-1]


# --- laws -----------------------------------------------------------------------------------

def test_pressure_law_k_is_the_believed_k_times_a_scale_and_a_pressure_power(believed):
    from fewear.wear.coefficient import wear_coefficient_from_config

    k_b = wear_coefficient_from_config(believed["wear"])
    p = np.array([1e6, 1e7, 5e7, 1.2e8])  # in and beyond the network's box (<= 20 MPa)
    v = np.array([0.1, 0.3, 0.3, 1.0])
    assert np.allclose(gen.PressureLawK(k_b, 2.0, 0.0, 5e7)(p, v), 2.0 * k_b(p, v), rtol=1e-14)
    law = gen.PressureLawK(k_b, 0.9, 0.5, 5e7)
    assert np.allclose(law(p, v) / k_b(p, v), 0.9 * (p / 5e7) ** 0.5, rtol=1e-12)
    assert law(np.array([5e7]), np.array([0.3]))[0] == pytest.approx(0.9 * k_b(5e7, 0.3))


def test_k_scale_of_two_doubles_the_cycle_wear_at_fixed_geometry(believed):
    """At the unworn geometry the contact does not depend on k: a scale of 2 doubles Archard's
    depth (and volume) of the cycle, to rounding."""
    from mpi4py import MPI

    from fewear.diagnose.joint.forward import cycle_on_worn_bore
    from fewear.loop.block import new_bushing
    from fewear.loop.stages import cycle_wear, load_steps

    config = model_config(believed, "rigid", 1000)
    params = {"causes": ["wear_coefficient"], "wear_coefficient": {
        "law": "scale", "k_factor": 2.0, "pressure_exponent": 0.0,
        "reference_pressure_Pa": 5e7}}
    inputs, truth = gen.truth_inputs(config, {"causes": []}), gen.truth_inputs(config, params)
    bushing = new_bushing(inputs, MPI.COMM_WORLD)
    steps = load_steps(cycle_on_worn_bore(config), 40, inputs.dynamics.joint.law)
    plain = cycle_wear(bushing, steps, inputs.wear_coefficient, True).depth_per_cycle_m
    doubled = cycle_wear(bushing, steps, truth.wear_coefficient, True).depth_per_cycle_m
    assert plain.sum() > 0.0
    # the contact solved again (from its warm start) repeats the pressures to about 1e-9
    assert np.allclose(doubled, 2.0 * plain, rtol=0.0, atol=1e-8 * plain.max())
    assert doubled.sum() == pytest.approx(2.0 * plain.sum(), rel=1e-8)


def test_power_running_in_multiplier_and_its_block_wear():
    law = gen.PowerRunningIn(ratio=3.0, distance_scale_m=0.2, exponent=0.6)
    s = np.array([0.0, 0.2, 2.0, 200.0])
    m = law.multiplier(SlidingState(distance_m=s))
    assert m[0] == pytest.approx(3.0)
    assert m[1] == pytest.approx(1.0 + 2.0 * 2.0**-0.6)
    assert np.all(np.diff(m) < 0.0) and m[-1] < 1.1
    # S_eff' = m
    h = 1e-7
    slope = (law.effective_distance_m(s + h) - law.effective_distance_m(s)) / h
    assert np.allclose(slope, law.multiplier(SlidingState(distance_m=s + h / 2)), rtol=1e-5)
    # the block step: each node's depth grows with S_eff of its own sliding distance
    cycle = CycleSliding(depth_m=np.array([1e-9, 2e-9, 0.0]),
                         distance_m=np.array([1e-3, 0.5e-3, 0.0]), time_s=np.full(3, 0.01),
                         power_W_m2=np.zeros(3))
    start = SlidingState(np.zeros(3), np.zeros(3), np.zeros(3), 0.0)
    increment, after = block_wear(cycle, start, law, 2000)
    expected = cycle.depth_m[:2] / cycle.distance_m[:2] * law.effective_distance_m(
        2000 * cycle.distance_m[:2])
    assert np.allclose(increment[:2], expected, rtol=2e-3)
    assert increment[2] == 0.0
    assert np.allclose(after.distance_m, 2000 * cycle.distance_m)
    assert increment[0] > 2000 * cycle.depth_m[0]  # running-in wears more than believed


def _history(time_s, penetration, force, eccentricity, mode):
    n = time_s.size
    zeros = np.zeros(n)
    return JointHistory(time_s, zeros, zeros, zeros, eccentricity, penetration, force, zeros,
                        np.zeros((n, 2)), zeros, mode)


def test_impact_speed_and_place_from_a_history():
    t = np.linspace(0.0, 1e-3, 11)
    penetration = np.array([-2e-6, -1e-6, 0.0, 3e-5, 5e-5, 4e-5, 1e-5, -1e-6, -2e-6, -3e-6, -4e-6])
    force = np.where(penetration > 0.0, 1e8 * penetration, 0.0)
    angle = np.deg2rad(200.0)
    eccentricity = np.tile([math.cos(angle), math.sin(angle)], (11, 1)) * 5e-4
    mode = np.where(force > 0.0, 1, 0)
    (impact,) = gen.impacts_of(_history(t, penetration, force, eccentricity, mode))
    assert impact.speed_m_s == pytest.approx(3e-5 / 1e-4)  # the steepest approach rate
    assert math.degrees(impact.angle_rad) % 360.0 == pytest.approx(200.0)
    assert impact.peak_force_N == pytest.approx(5e3)


def test_impact_volumes_tent_spread_and_depth_carry_the_volume():
    volumes = gen.impact_volumes_m3([0.05, 0.15, 0.6], 2e-13, 0.15, 2.4)
    assert volumes[0] == 0.0 and volumes[1] == 0.0
    assert volumes[2] == pytest.approx(2e-13 * 0.45**2.4)
    nodes = np.arange(96) * 2.0 * math.pi / 96
    centre = math.radians(358.0)  # across the 0/360 seam
    shares = gen.tent_cell_shares(nodes, centre, math.radians(6.0))
    assert shares.sum() == pytest.approx(1.0, abs=1e-12)
    assert np.all(shares >= 0.0)
    offsets = np.mod(nodes - centre + math.pi, 2 * math.pi) - math.pi
    assert np.sum(shares * offsets) == pytest.approx(0.0, abs=math.radians(0.2))
    assert np.all(shares[np.abs(offsets) > math.radians(6.0 + 3.75)] == 0.0)
    config = {"bushing": {"inner_radius_m": 0.01, "width_m": 0.018}}
    source = gen.ImpactSpeedWear(config, 2e-13, 0.15, 2.4, math.radians(6.0))
    impacts = [gen.Impact(0.6, centre, 3e3), gen.Impact(0.1, 1.0, 1e3)]
    depth = source.depth_per_cycle_m(impacts, nodes, 3)
    volume = np.sum(depth) * 0.018 * 0.01 * 2 * math.pi / 96
    assert volume == pytest.approx(volumes[2] / 3, rel=1e-12)
    assert source.coefficient_m3 == 2e-13
    sized = gen.impact_source(config, {"exponent": 2.4, "threshold_m_s": 0.15,
                                       "reference_volume_m3": 1e-13, "half_width_deg": 6.0})
    assert gen.impact_volumes_m3([0.5], sized.coefficient_m3, 0.15, 2.4)[0] == pytest.approx(
        1e-13)


def test_impact_wear_is_taken_from_the_running_mechanism(believed, monkeypatch):
    """Started from its ideal state the mechanism goes through a start-up transient; the cycles
    the impact source takes its impacts from are those of the same motion continued past
    :data:`IMPACT_SETTLING_CYCLES`, not the cycles right after the config's own two settling
    ones. How often either motion impacts is not asserted: the clearance joint is chaotic, and
    which orbit it follows depends on the rounding (the start-up's cycles held 0 to 14 impacts
    over rounding-level changes of the integrator's Newton)."""
    from fewear.wear.state import WearState

    config = gen.truth_config(believed, {"causes": []}, 12000)
    bore = gen.true_history(believed, {"causes": []}, 12000)
    state = replace(WearState.unworn(bore.angle_rad), depth_m=bore.nodal_depth_m(12000))
    assert config["mechanism"]["settling_cycles"] == 2
    start_up, period = gen.joint_history_on(config, state.angle_rad, state.depth_m,
                                            gen.IMPACT_SAMPLE_CYCLES)
    through, _ = gen.joint_history_on(config, state.angle_rad, state.depth_m,
                                      gen.IMPACT_SETTLING_CYCLES - 2 + gen.IMPACT_SAMPLE_CYCLES)
    seen = []
    real = gen.joint_history_on

    def recording(*args, **kwargs):
        seen.append(real(*args, **kwargs)[0])
        return seen[-1], period

    monkeypatch.setattr(gen, "joint_history_on", recording)
    source = gen.impact_source(config, {"exponent": 2.4, "threshold_m_s": 0.0,
                                        "reference_volume_m3": 1e-13, "half_width_deg": 6.0})
    depth = source(None, state)
    (running,) = seen
    size = min(start_up.time_s.size, running.time_s.size)  # another motion than the start-up's
    assert not np.allclose(start_up.reaction_force_N[:size], running.reaction_force_N[:size],
                           rtol=1e-3)
    assert gen.IMPACT_SETTLING_CYCLES == 12
    assert running.time_s[0] == pytest.approx(gen.IMPACT_SETTLING_CYCLES * period)
    assert running.time_s[-1] == pytest.approx(
        (gen.IMPACT_SETTLING_CYCLES + gen.IMPACT_SAMPLE_CYCLES) * period)
    tail = slice(through.time_s.size - running.time_s.size, None)
    np.testing.assert_allclose(running.time_s, through.time_s[tail], rtol=1e-12)
    np.testing.assert_allclose(running.reaction_force_N, through.reaction_force_N[tail],
                               rtol=1e-9, atol=1e-9)
    np.testing.assert_array_equal(running.mode, through.mode[tail])
    assert np.all(np.isfinite(depth)) and np.all(depth >= 0.0)
    assert (np.any(depth > 0.0)) == bool(running.impact_episodes())


def test_friction_schedule_and_truth_config(believed):
    params = {"causes": ["friction", "flexible_link"],
              "friction": {"law": "seal_failure", "step_cycles": 4000, "mu_after": 0.35},
              "flexible_link": {"law": "small_modulus", "modulus_factor": 0.97,
                                "rod_damping_s": 5e-6}}
    assert gen.friction_phases(params, 20000, 0.1) == [(4000, 0.1), (20000, 0.35)]
    assert gen.friction_phases({"causes": []}, 20000, 0.1) == [(20000, 0.1)]
    assert gen.friction_phases(params, 3000, 0.1) == [(3000, 0.1)]
    assert gen.friction_at(params, 3999, 0.1) == 0.1 and gen.friction_at(params, 4000, 0.1) == 0.35
    config = gen.truth_config(believed, params, 4000, 0.35)
    assert config["wear_loop"]["rod_models"] == ["flexible"]
    assert config["wear_loop"]["total_cycles"] == 4000
    assert config["joint"]["friction_coefficient"] == 0.35
    mechanism = config["mechanism"]
    assert mechanism["rod_youngs_modulus_Pa"] == pytest.approx(
        0.97 * believed["mechanism"]["rod_youngs_modulus_Pa"])
    assert mechanism["rod_damping_s"] == 5e-6 and mechanism["rod_density_kg_m3"] == 7800.0
    assert believed["joint"]["friction_coefficient"] == 0.1  # not changed in place


def test_none_truth_run_is_the_believed_forward_run(believed):
    """With nothing hidden the truth's block loop is the believed forward run, bit for bit."""
    truth = gen.true_history(believed, {"causes": []}, 1500)
    run = simulate_wear(model_config(believed, "rigid", 1500))
    assert np.array_equal(truth.cycles, run.cycles)
    assert np.array_equal(truth.depth_m, run.depth_m)
    assert truth.depth_m[-1].max() > 1e-6


# --- instruments ----------------------------------------------------------------------------

def test_stylus_on_a_circle_reads_zero_and_on_a_v_groove_the_known_shortfall():
    n = 36000  # 0.01 deg
    angle = np.arange(n) * 2 * math.pi / n
    assert np.allclose(gen.stylus_depth(angle, np.zeros(n), 0.01, 2.5e-3), 0.0, atol=1e-15)
    # a V-groove of depth d and flank slope s (in arc length) at 180 deg, tip r
    radius, d, s, r = 0.01, 50e-6, 0.1, 0.1e-3
    x = radius * (angle - math.pi)
    depth = np.maximum(d - s * np.abs(x), 0.0)
    read = gen.stylus_depth(angle, depth, radius, r)
    bottom = read[n // 2]
    assert bottom == pytest.approx(d - r * (math.sqrt(1 + s * s) - 1), abs=0.01e-6)
    assert np.all(read <= depth + 1e-15)  # never deeper than the surface
    assert np.allclose(read[np.abs(x) > d / s + r], 0.0, atol=1e-15)


def test_stylus_reaches_the_bottom_of_a_round_dent_wider_than_its_ball():
    n = 36000
    angle = np.arange(n) * 2 * math.pi / n
    radius, dent, d = 0.01, 2e-3, 30e-6  # a circular dent of radius 2 mm, 30 um deep at 0 deg
    centre = radius + d - dent
    # the dent circle's radius along each ray (the farther intersection), where it is outside
    b = centre * np.cos(angle)
    disc = b * b - centre**2 + dent**2
    along = np.where(disc >= 0.0, b + np.sqrt(np.maximum(disc, 0.0)), 0.0)
    depth = np.maximum(along - radius, 0.0)
    for tip in (0.5e-3, 1.5e-3):
        read = gen.stylus_depth(angle, depth, radius, tip)
        assert read[0] == pytest.approx(d, abs=2e-9)
    read = gen.stylus_depth(angle, depth, radius, 2.5e-3)  # a ball larger than the dent
    assert read[0] < d - 1e-6


def test_stylus_rides_over_dust():
    n = 7200
    angle = np.arange(n) * 2 * math.pi / n
    read = gen.stylus_depth(angle, np.zeros(n), 0.01, 1e-3, [(1.0, -8e-6)])
    at = int(round(1.0 / (2 * math.pi / n)))
    assert read[at] == pytest.approx(-8e-6, abs=0.05e-6)
    half = math.sqrt(2 * 1e-3 * 8e-6) / 0.01  # the ball's footprint on a point 8 um proud
    far = np.abs(np.mod(angle - 1.0 + math.pi, 2 * math.pi) - math.pi) > 1.05 * half
    assert np.all(read[far] == pytest.approx(0.0, abs=1e-15))


def test_two_rc_filter_on_harmonics():
    n = 720
    phi = np.arange(n) * 2 * math.pi / n
    for m, cutoff in ((1, 50), (6, 50), (20, 150)):
        out = gen.two_rc_filter(np.cos(m * phi), cutoff)
        gain = 1.0 / (1.0 + (m / cutoff) ** 2)
        lag = 2.0 * math.atan(m / cutoff)
        assert np.allclose(out, gain * np.cos(m * phi - lag), atol=1e-12)
    assert np.allclose(gen.two_rc_filter(np.full(n, 3.0), 50), 3.0)


def test_quantisation_step_is_the_12_bit_converter_of_the_800_um_range():
    assert gen.QUANTUM_M == pytest.approx(800e-6 / 4096)
    values = gen.quantised(np.random.default_rng(1).normal(0.0, 5e-6, 500), gen.QUANTUM_M)
    steps = values / gen.QUANTUM_M
    assert np.allclose(steps, np.round(steps), atol=1e-9)
    assert np.max(np.abs(np.diff(np.sort(np.unique(values))))) >= gen.QUANTUM_M * (1 - 1e-9)


def test_circle_reference_removes_centring_and_zero_exactly():
    phi = np.arange(512) * 2 * math.pi / 512
    depth = 40e-6 * np.maximum(np.cos(phi - 1.0), 0.0) ** 4
    fit = depth == 0.0
    shifted = depth + 23e-6 + 12e-6 * np.cos(phi - 2.2)
    assert np.allclose(gen.circle_reference(phi, shifted, fit), depth, atol=1e-15)


def test_honing_reference_points_and_their_fallback():
    depth = np.zeros(360)
    depth[100:160] = 5e-6
    kept = np.ones(360, dtype=bool)
    kept[300:320] = False
    chosen = gen.honing_reference_points(depth, kept, 3e-6, 1.0)
    assert not chosen[97:163].any() and chosen[96] and chosen[163]
    assert not chosen[300:320].any()
    worn = np.full(360, 5e-6)
    worn[:10] = 0.0
    chosen = gen.honing_reference_points(worn, kept, 3e-6, 1.0)
    assert chosen.sum() == int(0.25 * 360) and chosen[:10].all()


def _lab(**changes):
    lab = gen.LabPlan(profile_cycles=(1000, 2000), max_wear_cycles=(1500,),
                      force_cycles=(), origin_deg=20.0, points=720, tip_radius_m=0.25e-3,
                      filter_upr=10**9, noise_m=0.5e-6, hole_deg=90.0, hole_width_deg=26.0,
                      deleted=(None, (200.0, 10.0)), honing_rz_m=2e-6,
                      load_cell_cutoff_hz=2000.0, load_cell_noise_n=4.0)
    return gen.LabPlan(**{**lab.__dict__, **changes})


def _pocket(centre_deg, depth_m=60e-6, half_width_deg=40.0):
    def true_depth(theta):
        offset = np.mod(np.asarray(theta) - math.radians(centre_deg) + math.pi,
                        2 * math.pi) - math.pi
        x = np.clip(offset / math.radians(half_width_deg), -1.0, 1.0)
        return depth_m * np.cos(0.5 * math.pi * x) ** 2
    return true_depth


def test_trace_without_noise_shows_the_pocket_at_the_instrument_angle():
    lab = _lab()
    angle_deg, depth = gen.measure_trace(_pocket(150.0), lab, 1, None, 0.01)
    assert np.all(np.diff(angle_deg) > 0.0) and angle_deg[0] >= 0.0 and angle_deg[-1] < 360.0
    assert angle_deg[np.argmax(depth)] == pytest.approx(150.0 - 20.0, abs=0.5)
    assert depth.max() == pytest.approx(60e-6, abs=0.05e-6)
    hole = np.mod(angle_deg - (90.0 - 20.0) + 13.0, 360.0) <= 26.0
    deleted = np.mod(angle_deg - 200.0, 360.0) <= 10.0
    assert not hole.any() and not deleted.any()
    assert angle_deg.size == pytest.approx(720 * (360 - 36) / 360, abs=3)
    truth = _pocket(150.0)(np.deg2rad(angle_deg + 20.0))
    assert np.allclose(depth, truth, atol=0.05e-6)
    # the 2RC filter at 50 upr delays the pocket by about 2 / 50 rad in the scan direction
    angle_deg, depth = gen.measure_trace(_pocket(150.0), _lab(filter_upr=50), 0, None, 0.01)
    assert angle_deg[np.argmax(depth)] - 130.0 == pytest.approx(math.degrees(2 / 50), abs=0.6)


def test_trace_noise_has_the_documented_size():
    lab = _lab(noise_m=0.5e-6, tip_radius_m=0.25e-3)
    clean_angle, clean = gen.measure_trace(_pocket(150.0), lab, 0, None, 0.01)
    scatter = []
    for seed in range(5):
        angle, noisy = gen.measure_trace(_pocket(150.0), lab, 0, np.random.default_rng(seed),
                                         0.01)
        assert np.array_equal(angle, clean_angle)
        diff = noisy - clean
        scatter.append(np.median(np.abs(diff - np.median(diff))) / 0.6745)
    # white noise 0.5 um with the 0.195 um quantum; dust and re-mounting add outliers
    assert 0.4e-6 < np.median(scatter) < 1.0e-6


def _synthetic_history():
    angle = np.arange(96) * 2 * math.pi / 96
    depth = np.vstack([np.zeros(96), _pocket(10.0, 40e-6)(angle) + _pocket(190.0, 30e-6)(angle),
                       _pocket(10.0, 120e-6)(angle) + _pocket(190.0, 90e-6)(angle)])
    return WearHistory(angle, np.array([0.0, 5000.0, 30000.0]), depth, np.full(96, 1e-3))


def test_gauge_reads_the_largest_of_24_positions_below_the_true_maximum():
    history = _synthetic_history()
    lab = _lab(max_wear_cycles=(5000, 30000), hole_deg=95.0)
    clean = gen.gauge_max_depths(history, lab, None, 0.01)
    positions = np.deg2rad(95.0 + 7.5 + 15.0 * np.arange(24))
    for cycles, value in zip(lab.max_wear_cycles, clean):
        assert value <= history.nodal_depth_m(cycles).max() + 1e-12
        assert value == pytest.approx(history.depth_at(cycles, positions).max(), abs=0.05e-6)
    noisy = gen.gauge_max_depths(history, lab, np.random.default_rng(3), 0.01)
    assert np.allclose(noisy / 1e-6, np.round(noisy / 1e-6), atol=1e-9)
    assert np.all(np.abs(noisy - clean) < 5e-6)


def test_load_cell_keeps_a_slow_force_and_samples_at_10_khz():
    period = 0.05
    t = np.linspace(0.0, 3 * period, 30001)
    force = np.column_stack([800 * np.cos(2 * math.pi * t / period),
                             300 * np.sin(2 * math.pi * t / period)])
    n = t.size
    history = JointHistory(t, np.zeros(n), np.zeros(n), np.zeros(n), np.zeros((n, 2)),
                           np.zeros(n), np.zeros(n), np.zeros(n), -force, np.zeros(n),
                           np.zeros(n, dtype=int))
    lab = _lab(load_cell_cutoff_hz=2000.0)
    time_s, measured = gen.load_cell(history, period, lab, 0.25, None)
    assert time_s[0] == 0.0 and np.allclose(np.diff(time_s), 1e-4)
    assert time_s.size == int(1.5 * period * 1e4)
    start = (1.25) * period
    expected = np.column_stack([800 * np.cos(2 * math.pi * (start + time_s) / period),
                                300 * np.sin(2 * math.pi * (start + time_s) / period)])
    # a 2 kHz second-order low-pass delays a 20 Hz force by about 1.4 / (2 pi 2 kHz)
    assert np.max(np.abs(measured - expected)) < 0.02 * 800
    _, noisy = gen.load_cell(history, period, lab, 0.25, np.random.default_rng(0))
    assert 2.0 < np.std(noisy - measured) < 40.0


def test_written_files_read_back(tmp_path):
    history = _synthetic_history()
    lab = _lab(profile_cycles=(5000, 30000), max_wear_cycles=(12000,), force_cycles=(5000,))
    rng = np.random.default_rng(7)
    profiles = gen.measure_profiles(history, lab, rng, 0.01)
    write_joint_profiles(tmp_path / "profiles.csv", profiles, "test")
    write_max_wear(tmp_path / "max_wear.csv", lab.max_wear_cycles,
                   gen.gauge_max_depths(history, lab, rng, 0.01))
    t = np.linspace(0.0, 0.15, 3001)
    force = np.column_stack([np.cos(40 * math.pi * t), np.sin(40 * math.pi * t)]) * 500
    n = t.size
    joint = JointHistory(t, np.zeros(n), np.zeros(n), np.zeros(n), np.zeros((n, 2)),
                         np.zeros(n), np.zeros(n), np.zeros(n), force, np.zeros(n),
                         np.zeros(n, dtype=int))
    time_s, measured = gen.load_cell(joint, 0.05, lab, 0.5, rng)
    gen.write_force_traces(tmp_path / "force.csv", [(5000, time_s, measured)], "load cell")
    data = read_joint_measurements([tmp_path / name
                                    for name in ("profiles.csv", "max_wear.csv", "force.csv")])
    assert data.profile_cycles == (5000, 30000)
    assert list(data.max_wear[0]) == [12000]
    assert data.force[0].cycles == 5000 and data.force[0].time_s.size == time_s.size


# --- whole data sets (slow: a truth run each) -----------------------------------------------

def _worn_volume(history: WearHistory, cycles: float) -> float:
    return float(history.nodal_depth_m(cycles).sum())


@pytest.mark.slow
@pytest.mark.parametrize("cause", gen.CAUSES)
def test_data_set_files_and_truth(cause, tmp_path, believed):
    seed = gen.data_set_seed(cause, 0)
    data = gen.write_data_set(cause, seed, tmp_path)
    measured = read_joint_measurements(data.measured_files)
    assert measured.profile_cycles == data.lab.profile_cycles
    assert tuple(measured.max_wear[0]) == data.lab.max_wear_cycles
    assert (measured.force is not None) == bool(data.lab.force_cycles)
    truth = json.loads(data.truth_json.read_text())
    assert truth["causes"] == list(gen.cause_names(cause)) and truth["seed"] == seed
    assert data.params["truth_run"]["block_cycles"][-1] == data.lab.last_cycles
    assert gen.truth_text(data).startswith(cause.split("+")[0])


@pytest.mark.slow
@pytest.mark.parametrize("cause", gen.SINGLE_CAUSES)
def test_each_cause_departs_as_documented(cause, believed):
    """The sign of each cause's departure from the believed run (index 0 and 1)."""
    for index in (0, 1):
        seed = gen.data_set_seed(cause, index)
        params, lab, truth, _ = gen.hidden_truth(cause, seed, believed)
        base = simulate_wear(model_config(believed, "rigid", lab.last_cycles))
        first, last = lab.profile_cycles[0], lab.last_cycles
        ratio_first = _worn_volume(truth, first) / _worn_volume(base, first)
        ratio_last = _worn_volume(truth, last) / _worn_volume(base, last)
        rms_last = np.sqrt(np.mean((truth.nodal_depth_m(last) - base.nodal_depth_m(last)) ** 2))
        values = params[cause]
        if cause == "wear_coefficient" and values["law"] == "scale":
            sign = np.sign(values["k_factor"] - 1.0)
            assert np.sign(ratio_first - 1.0) == sign and np.sign(ratio_last - 1.0) == sign
        elif cause == "running_in":
            assert ratio_first > 1.2 and ratio_last > 1.0
        elif cause == "friction":
            step = values["step_cycles"]
            before = [c for c in lab.profile_cycles if c < step]
            for count in before:  # nothing changes before the step, the block cut aside
                assert np.max(np.abs(truth.nodal_depth_m(count) - base.nodal_depth_m(count))) < 1e-6
            assert step in truth.cycles
        elif cause == "impact_wear":
            assert ratio_last > 1.0 and rms_last > 5e-6
        assert rms_last > 2e-6, (cause, index, rms_last)
