"""The fourth joint-wear generator (tests/diagnose/joint/generators/fourth.py): each piece against
closed forms or independent computations, the instrument on known shapes, and (slow) the forward
runs it layers its hidden causes on. Two-cause data sets: seeds, draws, the warped loop's laws and
the one run that carries both causes (on synthetic stand-ins for the forward runs, no FE); slow:
one written data set per pair."""

import math
import re
import time
from dataclasses import replace

import numpy as np
import pytest
from scipy.integrate import quad

from fewear.diagnose.joint.measured import read_joint_measurements
from fewear.io.config import load_config
from fewear.loop.settings import run_sections
from fewear.mbd.history import JointHistory, classify_modes
from tests.diagnose.joint.generators import fourth as gen
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

R_BORE = 0.010  # m, the believed bore radius
NODES = np.arange(96) * (2.0 * math.pi / 96)  # the believed bore nodes (rad)
ALPHA = math.sqrt(math.log(2.0) / math.pi)


@pytest.fixture(scope="module")
def believed():
    """The believed config (defaults + believed.toml), no forward run."""
    return _believed_config()


def _believed_config() -> dict:
    import tempfile
    from pathlib import Path

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "believed.toml"
        path.write_text(gen.BELIEVED_TOML)
        return load_config(path, run_sections())


def synthetic_truth(cycles: float) -> tuple[np.ndarray, np.ndarray]:
    """A smooth known bore: depth (m) = 2e-9 m per cycle times (1.2 + cos(theta - 0.7))."""
    return NODES, 2e-9 * cycles * (1.2 + np.cos(NODES - 0.7))


def plan(profiles=(2000, 6000, 20000), max_wear=(4000, 20000), origin=7.0, shrinkage=0.004,
         parting=100.0, tears=None) -> gen.LabPlan:
    tears = (None,) * len(profiles) if tears is None else tears
    return gen.LabPlan(tuple(profiles), tuple(max_wear), origin, shrinkage, parting, tears)


# --- seeds, draws -----------------------------------------------------------------------------

def test_seeds_follow_the_numbering_and_refuse_bad_input():
    assert gen.data_set_seed("wear_coefficient", 0) == 9000
    assert gen.data_set_seed("none", 99) == 9599
    assert gen.data_set_seed("running_in", 7) == 9407
    seeds = {gen.data_set_seed(c, i) for c in gen.CAUSES for i in range(100)}
    assert len(seeds) == 600
    for cause, index in (("wear", 0), ("none", 100), ("none", -1), ("none", 1.5)):
        with pytest.raises(ValueError):
            gen.data_set_seed(cause, index)
    with pytest.raises(ValueError):
        gen.draw_truth("thermal", np.random.default_rng(0))


def test_truth_parameters_keep_to_their_stated_ranges():
    soft = hard = 0
    for seed in range(300):
        rng = np.random.default_rng(seed)
        k = gen.draw_truth("wear_coefficient", rng)
        assert k["k_factor"] == pytest.approx(235.0 / k["hardness_HB"], rel=1e-14)
        if 150.0 <= k["hardness_HB"] <= 195.0:
            soft += 1
            assert 1.205 <= k["k_factor"] <= 1.567
        else:
            hard += 1
            assert 285.0 <= k["hardness_HB"] <= 370.0 and 0.635 <= k["k_factor"] <= 0.825
        rod = gen.draw_truth("flexible_link", rng)
        assert rod["rod_elements"] == 6.0
        assert 1.0e-5 <= rod["rod_damping_s"] <= 1.2e-4
        assert 195e9 <= rod["rod_youngs_modulus_Pa"] <= 215e9
        mu = gen.draw_truth("friction", rng)
        assert 0.085 <= mu["mu_0"] <= 0.115 and 0.24 <= mu["mu_dry"] <= 0.38
        assert 4000.0 <= mu["n_g_cycles"] <= 15000.0
        impact = gen.draw_truth("impact_wear", rng)
        assert 3e-15 <= impact["volume_at_v_ref_m3"] <= 1e-14 and impact["v_ref_m_s"] == 0.2
        run_in = gen.draw_truth("running_in", rng)
        assert 2.5 <= run_in["ratio"] <= 6.0 and 500.0 <= run_in["n_r_cycles"] <= 1600.0
        assert all(isinstance(v, (float, str)) for v in {**k, **rod, **mu, **impact}.values())
    assert 110 < soft < 190 and 110 < hard < 190  # each side with probability 1/2


def test_log_uniform_draws_are_uniform_in_the_logarithm():
    rng = np.random.default_rng(3)
    values = np.array([gen._log_uniform(rng, (10.0, 1000.0)) for _ in range(4000)])
    # median of a log-uniform on [10, 1000] is the geometric mean 100; quartiles at 10^1.5, 10^2.5
    assert np.median(values) == pytest.approx(100.0, rel=0.08)
    assert np.mean(values < 10**1.5) == pytest.approx(0.25, abs=0.03)


def test_draws_are_deterministic_per_seed_and_differ_between_seeds():
    def draws(seed):
        truth, lab, noise = gen._streams(seed)
        return gen.draw_truth("friction", truth), gen.draw_lab(lab), noise.normal(size=3)

    first, again, other = draws(9200), draws(9200), draws(9201)
    assert first[0] == again[0] and first[1] == again[1]
    np.testing.assert_array_equal(first[2], again[2])
    assert first[0] != other[0] and first[1] != other[1]


def test_lab_plans_keep_to_the_stated_schedule():
    counts = set()
    for seed in range(300):
        lab = gen.draw_lab(np.random.default_rng(seed))
        n = len(lab.profile_cycles)
        counts.add(n)
        assert 4 <= n <= 6 and len(lab.tears) == n
        assert 1500 <= lab.profile_cycles[0] <= 2600 and 19000 <= lab.profile_cycles[-1] <= 25000
        assert np.all(np.diff(lab.profile_cycles) > 0)
        assert all(count % 10 == 0 for count in lab.profile_cycles)
        assert np.all(np.diff(lab.max_wear_cycles) > 0)
        assert len(lab.max_wear_cycles) == 4 and lab.max_wear_cycles[-1] == lab.profile_cycles[-1]
        assert lab.last_cycles == lab.profile_cycles[-1]
        assert -12.0 <= lab.origin_deg <= 12.0 and 0.002 <= lab.shrinkage <= 0.006
    assert counts == {4, 5, 6}


# --- the causes' laws ---------------------------------------------------------------------------

def test_running_in_cycles_are_the_integral_of_the_multiplier():
    ratio, n_r = 4.2, 900.0
    assert gen.running_in_multiplier(0.0, ratio, n_r) == pytest.approx(ratio)
    assert gen.running_in_multiplier(1e9, ratio, n_r) == pytest.approx(1.0, abs=1e-9)
    assert gen.running_in_multiplier(n_r, ratio, n_r) == pytest.approx(1.0 + (ratio - 1.0) / 4)
    for cycles in (300.0, 2500.0, 24000.0):
        integral, _ = quad(gen.running_in_multiplier, 0.0, cycles, args=(ratio, n_r))
        assert float(gen.running_in_cycles(cycles, ratio, n_r)) == pytest.approx(integral,
                                                                                 rel=1e-10)
    # the extra wear saturates at (r - 1) N_r equivalent cycles
    extra = float(gen.running_in_cycles(1e10, ratio, n_r)) - 1e10
    assert extra == pytest.approx((ratio - 1.0) * n_r, rel=1e-5)
    assert float(gen.running_in_cycles(0.0, ratio, n_r)) == 0.0


def test_friction_rises_from_its_start_to_the_dry_value():
    mu_0, dry, n_g = 0.1, 0.3, 5000.0
    assert float(gen.friction_coefficient(0.0, mu_0, dry, n_g)) == pytest.approx(mu_0)
    assert float(gen.friction_coefficient(n_g, mu_0, dry, n_g)) == pytest.approx(
        dry - (dry - mu_0) / math.e)
    assert float(gen.friction_coefficient(1e7, mu_0, dry, n_g)) == pytest.approx(dry)
    assert np.all(np.diff(gen.friction_coefficient(np.linspace(0, 3e4, 50), mu_0, dry, n_g)) > 0)


def test_hertz_half_width_matches_the_hand_calculation(believed):
    # R* = 9.5 mm x 10 mm / 0.5 mm = 0.19 m; 1/E* = (1 - 0.27^2)/207 GPa + (1 - 0.32^2)/90 GPa
    e_star = 1.0 / ((1 - 0.27**2) / 207e9 + (1 - 0.32**2) / 90e9)
    b = gen.hertz_half_width_m(1000.0, believed)
    assert b == pytest.approx(math.sqrt(4 * 1000.0 * 0.19 / (math.pi * 0.018 * e_star)), rel=1e-9)
    assert b == pytest.approx(4.4e-4, rel=0.02, abs=0.0)
    # Johnson: the peak pressure 2F/(pi b w) equals E* b / (2 R*)
    assert 2 * 1000.0 / (math.pi * b * 0.018) == pytest.approx(e_star * b / (2 * 0.19), rel=1e-9)
    assert gen.hertz_half_width_m(4000.0, believed) == pytest.approx(2 * b, rel=1e-12)


@pytest.mark.parametrize("centre_deg,width_deg", [(0.0, 2.5), (359.0, 10.0), (181.9, 0.4),
                                                  (45.0, 60.0)])
def test_semi_ellipse_cells_keep_the_volume(centre_deg, width_deg):
    density = gen.semi_ellipse_cell_means(NODES, math.radians(centre_deg), math.radians(width_deg))
    assert np.all(density >= 0.0)
    assert density.sum() * (2 * math.pi / NODES.size) == pytest.approx(1.0, rel=1e-12)
    nearest = np.argmin(np.abs(np.mod(NODES - math.radians(centre_deg) + math.pi, 2 * math.pi)
                               - math.pi))
    assert np.argmax(density) == nearest


def test_semi_ellipse_cells_follow_the_hertz_shape_on_a_fine_grid():
    nodes = np.arange(3600) * (2 * math.pi / 3600)
    a = math.radians(20.0)
    density = gen.semi_ellipse_cell_means(nodes, math.pi, a)
    x = nodes - math.pi
    analytic = 2.0 * np.sqrt(np.maximum(a * a - x * x, 0.0)) / (math.pi * a * a)
    inside = np.abs(x) < 0.95 * a
    np.testing.assert_allclose(density[inside], analytic[inside], rtol=2e-4)
    assert np.all(density[np.abs(x) > a + 2 * math.pi / 3600] == 0.0)


def test_impact_depth_carries_the_cubic_volume(believed):
    impacts = [gen.Impact(0.2, 0.3, 800.0), gen.Impact(0.5, 3.5, 2500.0)]
    v_ref = 5e-15
    depth = gen.impact_depth_per_cycle_m(impacts, NODES, believed, v_ref)
    volume = 0.018 * R_BORE * depth.sum() * (2 * math.pi / NODES.size)
    assert volume == pytest.approx(v_ref * (1.0 + 2.5**3), rel=1e-10, abs=0.0)
    # doubling the speed wears 8 times the volume
    slow = gen.impact_depth_per_cycle_m([gen.Impact(0.1, 1.0, 500.0)], NODES, believed, v_ref)
    fast = gen.impact_depth_per_cycle_m([gen.Impact(0.2, 1.0, 500.0)], NODES, believed, v_ref)
    np.testing.assert_allclose(fast, 8.0 * slow, rtol=1e-12)
    assert gen.impact_depth_per_cycle_m([], NODES, believed, v_ref).max() == 0.0


def test_impacts_are_found_with_their_speed_place_and_force():
    """A synthetic history: one impact at 0.35 m/s approach (penetration rising linearly, then
    falling) in the direction 100 deg, a long contact later (not an impact)."""
    t = np.arange(0.0, 0.01, 1e-5)
    penetration = np.full(t.size, -1e-6)
    rise = (t >= 0.002) & (t < 0.0022)
    penetration[rise] = 0.35 * (t[rise] - 0.002) + 1e-9
    fall = (t >= 0.0022) & (t < 0.0024)
    penetration[fall] = 0.35 * 0.0002 - 0.2 * (t[fall] - 0.0022)
    long = (t >= 0.005) & (t < 0.008)
    penetration[long] = 1e-6
    force = 1e9 * np.maximum(penetration, 0.0) ** 1.5
    angle = np.where(t < 0.004, math.radians(100.0), math.radians(-30.0))
    radius = 5e-4 + penetration
    eccentricity = np.column_stack([radius * np.cos(angle), radius * np.sin(angle)])
    zeros = np.zeros(t.size)
    history = JointHistory(t, t * 125.0, zeros, zeros, eccentricity, penetration, force, zeros,
                           np.zeros((t.size, 2)), zeros, classify_modes(t, force, 1e-3))
    impacts = gen.impacts_of(history)
    assert len(impacts) == 1
    assert impacts[0].speed_m_s == pytest.approx(0.35, rel=1e-6)
    assert impacts[0].angle_rad == pytest.approx(math.radians(100.0), rel=1e-9)
    assert impacts[0].peak_force_N == pytest.approx(force.max(), rel=1e-12)


def test_truth_config_scales_k_everywhere_and_builds_the_flexible_rod(believed):
    from fewear.wear.coefficient import wear_coefficient_from_config

    params = {"k_factor": 0.7}
    changed = gen.truth_config("wear_coefficient", params, believed)
    k_believed = wear_coefficient_from_config(believed["wear"])
    k_true = wear_coefficient_from_config(changed["wear"])
    p, v = np.array([1e6, 5e6, 3e7, 1e5]), np.array([0.1, 0.6, 3.0, 0.01])
    np.testing.assert_allclose(k_true(p, v) / k_believed(p, v), 0.7, rtol=1e-12)
    assert believed["wear"]["rbf"]["tail"][0] != changed["wear"]["rbf"]["tail"][0]  # no aliasing
    constant = {**believed, "wear": {**believed["wear"], "coefficient_model": "constant"}}
    assert gen.truth_config("wear_coefficient", params, constant)["wear"][
        "constant_k_m2_N"] == pytest.approx(0.7 * believed["wear"]["constant_k_m2_N"], abs=0.0)
    rod = gen.truth_config("flexible_link", {"rod_elements": 6.0, "rod_damping_s": 5e-5,
                                             "rod_youngs_modulus_Pa": 2.0e11}, believed)
    assert rod["wear_loop"]["rod_models"] == ["flexible"]
    assert rod["mechanism"]["rod_elements"] == 6 and rod["mechanism"]["rod_damping_s"] == 5e-5
    assert rod["mechanism"]["rod_youngs_modulus_Pa"] == 2.0e11
    assert believed["wear_loop"]["rod_models"] == ["rigid"]


def test_believed_toml_gives_the_believed_model(believed):
    # the brief's value (its comment says 2*pi*0.010/48*(1+1e-9); the number is 2*pi*0.010/48
    # to the last digit): 48 elements round the bore
    assert believed["mesh"]["bore_element_size_m"] == 0.0013089969389957472
    assert 2 * math.pi * 0.010 / believed["mesh"]["bore_element_size_m"] == pytest.approx(48.0)
    assert believed["mesh"]["radial_element_count"] == 4
    assert believed["wear_loop"]["rod_models"] == ["rigid"]
    assert believed["wear_loop"]["load_steps_per_cycle"] == 40
    assert believed["joint"]["friction_coefficient"] == 0.1
    assert believed["wear"]["coefficient_model"] == "rbf"


# --- the instrument -----------------------------------------------------------------------------

@pytest.mark.parametrize("wavelength_deg", [3.0, 4.5837, 10.0, 45.0])
def test_profile_filter_transmits_a_sine_as_iso_16610_21(wavelength_deg):
    """The Gaussian filter's transmission of a sine of wavelength lambda (arc) is
    exp(-pi (alpha lambda_c / lambda)^2): 50 % at the cutoff (0.8 mm = 4.5837 deg here). Read
    on the filter's own 0.25 deg grid (between its points the filtered profile is linear)."""
    nodes = np.arange(1440) * (2 * math.pi / 1440)
    waves = round(360.0 / wavelength_deg)
    wavelength_m = 2 * math.pi * R_BORE / waves
    profile = 1e-5 + 1e-6 * np.sin(waves * nodes)
    filtered = gen.filtered_profile(nodes, profile, R_BORE)(nodes)
    expected = math.exp(-math.pi * (ALPHA * 0.8e-3 / wavelength_m) ** 2)
    amplitude = 2 * np.abs(np.fft.rfft(filtered - filtered.mean())[waves]) / nodes.size
    assert amplitude / 1e-6 == pytest.approx(expected, rel=0.01, abs=2e-4)
    assert filtered.mean() == pytest.approx(1e-5, rel=1e-9, abs=0.0)
    if abs(wavelength_deg - 4.5837) < 0.01:
        assert expected == pytest.approx(0.5, abs=0.01)


def test_noiseless_profile_is_the_shrunk_filtered_truth_in_the_instrument_frame():
    lab = plan(origin=-8.5, shrinkage=0.005)
    profiles = gen.measure_profiles(lab, synthetic_truth, R_BORE, None)
    one_turn = 2 * math.pi * R_BORE
    transmission = math.exp(-math.pi * (ALPHA * 0.8e-3 / one_turn) ** 2)
    for (cycles, angle_deg, depth), expected_cycles in zip(profiles, lab.profile_cycles):
        assert cycles == expected_cycles
        theta = np.radians(angle_deg - 8.5)  # bushing frame = instrument + origin
        exact = 0.995 * 2e-9 * cycles * (1.2 + transmission * np.cos(theta - 0.7))
        # periodic-linear nodes (3.75 deg) and 0.25 deg grid: within 0.1 % of the amplitude
        np.testing.assert_allclose(depth, exact, atol=1e-3 * 2e-9 * cycles)


def test_coverage_has_the_parting_gap_and_the_tear():
    lab = plan(parting=355.0, tears=(None, (100.0, 9.0), None))
    profiles = gen.measure_profiles(lab, synthetic_truth, R_BORE, None)
    full, torn = profiles[0][1], profiles[1][1]
    assert full.size == gen.SCAN_POINTS == 234
    assert np.unique(full).size == full.size and np.all((full >= 0) & (full < 360))
    gap = np.mod(full - 355.0 + 180.0, 360.0) - 180.0
    assert np.all(np.abs(gap) >= 5.0 - 1e-9)
    assert np.min(np.abs(gap)) == pytest.approx(5.0, abs=1e-6)
    assert not np.any(np.mod(torn - 100.0, 360.0) < 9.0)
    assert torn.size == full.size - 6  # 1.5 deg spacing: 6 readings in a 9 deg sector
    np.testing.assert_allclose(np.diff(np.sort(full))[np.diff(np.sort(full)) < 5], 1.5, atol=1e-6)


def test_noise_has_the_stated_levels_and_a_shared_reference_pattern():
    """Differences along the scan remove the smooth centring and drift terms: what is left of
    two profiles' residuals has the white noise and reference noise variances, the reference
    part shared, so the residual differences of two profiles correlate by
    sigma_b^2 / (sigma_b^2 + sigma_w^2)."""
    counts = tuple(range(1000, 61000, 1000))
    lab = plan(profiles=counts, max_wear=(counts[-1],))
    noisy = gen.measure_profiles(lab, synthetic_truth, R_BORE, np.random.default_rng(5))
    clean = gen.measure_profiles(lab, synthetic_truth, R_BORE, None)
    residual = np.array([n[2] - c[2] for n, c in zip(noisy, clean)])
    steps = np.diff(residual, axis=1)
    robust_sd = 1.4826 * np.median(np.abs(steps - np.median(steps)))
    sigma = math.hypot(gen.WHITE_NOISE_M, gen.REFERENCE_NOISE_M)
    quantum = gen.PROFILE_QUANTUM_M**2 / 12.0
    assert robust_sd == pytest.approx(math.sqrt(2 * (sigma**2 + quantum)), rel=0.1, abs=0.0)
    mild = np.where(np.abs(steps) < 5 * robust_sd, steps, np.nan)
    pairs = [np.ma.corrcoef(np.ma.masked_invalid(mild[i]), np.ma.masked_invalid(mild[i + 1]))[0, 1]
             for i in range(len(counts) - 1)]
    share = gen.REFERENCE_NOISE_M**2 / sigma**2
    assert float(np.mean(pairs)) == pytest.approx(share, abs=0.07)
    # bubbles: about one reading per profile lowered by 1-4 um
    lowered = np.sum(residual < -2.5e-6)
    assert 0.3 * len(counts) < lowered < 1.2 * len(counts)
    # quantised to 0.05 um
    values = np.concatenate([n[2] for n in noisy]) / gen.PROFILE_QUANTUM_M
    np.testing.assert_allclose(values, np.round(values), atol=1e-6)


def test_max_depth_readings_are_the_deepest_filtered_point():
    lab = plan(max_wear=(3000, 10000, 20000), shrinkage=0.003)
    transmission = math.exp(-math.pi * (ALPHA * 0.8e-3 / (2 * math.pi * R_BORE)) ** 2)
    clean = gen.measure_max_depths(lab, synthetic_truth, R_BORE, None)
    exact = 0.997 * 2e-9 * np.array(lab.max_wear_cycles) * (1.2 + transmission)
    np.testing.assert_allclose(clean, exact, rtol=1e-3)
    noisy = np.array([gen.measure_max_depths(lab, synthetic_truth, R_BORE,
                                             np.random.default_rng(s)) for s in range(400)])
    assert np.std(noisy - clean) == pytest.approx(0.6e-6, rel=0.1, abs=0.0)
    np.testing.assert_allclose(noisy / 1e-7, np.round(noisy / 1e-7), atol=1e-6)


def test_written_files_parse_with_the_workbench_reader(tmp_path):
    lab = plan(tears=(None, (30.0, 8.0), None))
    profiles_csv, max_wear_csv = gen.write_measurements(tmp_path, lab, synthetic_truth, R_BORE,
                                                        np.random.default_rng(1))
    assert profiles_csv.read_text().startswith("# ")
    measured = read_joint_measurements([profiles_csv, max_wear_csv])
    assert measured.profile_cycles == lab.profile_cycles
    assert tuple(int(c) for c in measured.max_wear[0]) == lab.max_wear_cycles
    assert [p.angle_rad.size for p in measured.profiles] == [234, 234 - 6, 234]
    written = gen.measure_profiles(lab, synthetic_truth, R_BORE, np.random.default_rng(1))
    for profile, (_, angle_deg, depth) in zip(measured.profiles, written):
        order = np.argsort(angle_deg)
        np.testing.assert_allclose(np.degrees(profile.angle_rad), angle_deg[order], atol=1e-6)
        np.testing.assert_allclose(profile.depth_m, depth[order], rtol=1e-9, atol=1e-15)
    again = tmp_path / "again"
    again.mkdir()
    gen.write_measurements(again, lab, synthetic_truth, R_BORE, np.random.default_rng(1))
    assert (again / "profiles.csv").read_text() == profiles_csv.read_text()


# --- forward runs (slow) ------------------------------------------------------------------------

@pytest.mark.slow
def test_layered_run_without_effect_is_the_believed_run(believed):
    """The layered loop, with no effect and with a friction held at the believed 0.1 (the FE
    bushing rebuilt and restored at every block), reproduces simulate_wear block for block."""
    from fewear.diagnose.joint.forward import model_config, simulate_wear

    run = simulate_wear(model_config(believed, "rigid", 12000))
    plain = gen.layered_run(believed, 12000)
    held = gen.layered_run(believed, 12000, {"mu_0": 0.1, "mu_dry": 0.1, "n_g_cycles": 5000.0})
    for layered in (plain, held):
        np.testing.assert_array_equal(layered.cycles, run.cycles)
        np.testing.assert_allclose(layered.depth_m, run.depth_m, rtol=0, atol=1e-15)


@pytest.mark.slow
@pytest.mark.parametrize("cause", gen.CAUSES)
def test_one_data_set_of_each_cause_is_written_with_a_measurable_effect(cause, tmp_path):
    seed = gen.data_set_seed(cause, 0)
    start = time.perf_counter()
    data = gen.write_data_set(cause, seed, tmp_path / "noisy")
    wall = time.perf_counter() - start
    assert wall < 120.0
    clean = gen.write_data_set(cause, seed, tmp_path / "clean", noise=False)
    assert clean.params == data.params and clean.lab == data.lab
    assert data.lab.profile_cycles == tuple(sorted(data.lab.profile_cycles))
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    noiseless = read_joint_measurements([clean.profiles_csv, clean.max_wear_csv])
    assert measured.profile_cycles == data.lab.profile_cycles
    config = load_config(data.believed_toml, run_sections())
    last = data.lab.profile_cycles[-1]
    truth = gen.true_depth(cause, data.params, config, data.lab.last_cycles)(last)[1]
    belief = gen.believed_depth(config, data.lab.last_cycles)(last)[1]
    effect = float(np.sqrt(np.mean((truth - belief) ** 2)))
    noise = float(np.sqrt(np.mean((measured.profiles[-1].depth_m
                                   - noiseless.profiles[-1].depth_m) ** 2)))
    assert noise < 4e-6  # mostly the replica's seating error on the pocket's flanks
    assert 1e-5 < belief.max() < 3e-4  # the believed model wears tens to hundreds of um
    if cause == "none":
        assert effect == 0.0
    else:
        assert 3e-6 < effect < 1e-4 and effect > 4 * noise


# --- two hidden causes --------------------------------------------------------------------------

NEUTRAL = {"wear_coefficient": {"hardness_HB": 235.0, "k_factor": 1.0},
           "friction": {"mu_0": 0.1, "mu_dry": 0.1, "n_g_cycles": 5000.0},
           "impact_wear": {"volume_at_v_ref_m3": 0.0},
           "running_in": {"ratio": 1.0, "n_r_cycles": 900.0}}
"""Parameters with which a cause has no effect (friction held at the believed 0.1)."""


def _check_single_cause_range(cause, params):
    """The ranges of the module doc (as test_truth_parameters_keep_to_their_stated_ranges)."""
    if cause == "wear_coefficient":
        assert params["k_factor"] == pytest.approx(235.0 / params["hardness_HB"], rel=1e-14)
        assert 150.0 <= params["hardness_HB"] <= 195.0 or 285.0 <= params["hardness_HB"] <= 370.0
    elif cause == "flexible_link":
        assert params["rod_elements"] == 6.0
        assert 1.0e-5 <= params["rod_damping_s"] <= 1.2e-4
        assert 195e9 <= params["rod_youngs_modulus_Pa"] <= 215e9
    elif cause == "friction":
        assert 0.085 <= params["mu_0"] <= 0.115 and 0.24 <= params["mu_dry"] <= 0.38
        assert 4000.0 <= params["n_g_cycles"] <= 15000.0
    elif cause == "impact_wear":
        assert 3e-15 <= params["volume_at_v_ref_m3"] <= 1e-14 and params["v_ref_m_s"] == 0.2
    else:
        assert cause == "running_in"
        assert 2.5 <= params["ratio"] <= 6.0 and 500.0 <= params["n_r_cycles"] <= 1600.0


def _pair_truth(pair, index=0):
    seed = gen.two_cause_seed(pair, index)
    return seed, gen.draw_pair_truth(pair, gen.cause_streams(seed, pair))


def test_two_cause_pairs_are_the_ten_pairs_in_causes_order():
    assert len(gen.TWO_CAUSE_PAIRS) == len(set(gen.TWO_CAUSE_PAIRS)) == 10
    for first, second in gen.TWO_CAUSE_PAIRS:
        assert "none" not in (first, second)
        assert gen.CAUSES.index(first) < gen.CAUSES.index(second)


def test_two_cause_seeds_follow_their_numbering_and_refuse_bad_input():
    assert gen.two_cause_seed(("wear_coefficient", "flexible_link"), 0) == 19000
    assert gen.two_cause_seed(("impact_wear", "running_in"), 99) == 19999
    seeds = {gen.two_cause_seed(pair, i) for pair in gen.TWO_CAUSE_PAIRS for i in range(100)}
    assert len(seeds) == 1000
    assert not seeds & {gen.data_set_seed(c, i) for c in gen.CAUSES for i in range(100)}
    for pair in (("running_in", "friction"), ("friction", "friction"), ("friction", "none"),
                 ("friction",), "friction+running_in", ("friction", "thermal"), None):
        with pytest.raises(ValueError, match=re.escape(repr(pair)) + ".*expected one of"):
            gen.two_cause_seed(pair, 0)
        with pytest.raises(ValueError, match=re.escape(repr(pair))):
            gen.write_two_cause_data_set(pair, 19000, "/nonexistent/never/written")
    for index in (100, -1, 1.5, "0"):
        with pytest.raises(ValueError, match=re.escape(repr(index)) + ".*0-99"):
            gen.two_cause_seed(("friction", "running_in"), index)


@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_each_cause_of_a_pair_is_drawn_from_its_own_single_cause_distribution(pair):
    for index in range(60):
        seed, params = _pair_truth(pair, index)
        laws = []
        for cause in pair:
            alone = gen.draw_truth(cause, gen.cause_streams(seed, [cause])[cause])
            _check_single_cause_range(cause, alone)
            laws.append(alone.pop("law"))
            assert {key: params[key] for key in alone} == alone  # its own stream, any partner
        assert params["law"] == "; ".join(laws)
        assert len(params) == 1 + sum(len(gen.draw_truth(c, np.random.default_rng(0))) - 1
                                      for c in pair)


def test_pairs_draw_each_cause_independently_of_its_partner_and_the_single_stream():
    seed = 19321
    drawn = [gen.draw_pair_truth(pair, gen.cause_streams(seed, pair))["mu_dry"]
             for pair in gen.TWO_CAUSE_PAIRS if "friction" in pair]
    assert len(drawn) == 4 and len(set(drawn)) == 1
    assert drawn[0] != gen.draw_truth("friction", gen._streams(seed)[0])["mu_dry"]
    again = gen.draw_pair_truth(("friction", "running_in"),
                                gen.cause_streams(seed + 1, ("friction", "running_in")))
    assert again["mu_dry"] != drawn[0]


def test_truth_causes_are_checked():
    assert gen.truth_causes("friction") == ("friction",)
    assert gen.truth_causes(["running_in", "friction"]) == ("friction", "running_in")
    for bad in ("thermal", ("friction", "friction"), ("none", "friction"), ()):
        with pytest.raises(ValueError):
            gen.truth_causes(bad)


def test_running_in_real_cycles_invert_the_warp():
    for ratio, n_r in ((2.5, 500.0), (6.0, 1600.0), (4.0, 900.0), (1.0, 900.0)):
        n = np.array([0.0, 1e-3, 1.0, 120.0, n_r, 3000.0, 25000.0, 1e7])
        tau = gen.running_in_cycles(n, ratio, n_r)
        np.testing.assert_allclose(gen.running_in_real_cycles(tau, ratio, n_r), n, rtol=1e-12,
                                   atol=0.0)
    assert float(gen.running_in_real_cycles(0.0, 3.0, 700.0)) == 0.0
    np.testing.assert_allclose(gen.running_in_real_cycles(np.array([5.0, 4e4]), 1.0, 900.0),
                               [5.0, 4e4], rtol=1e-13)


def test_the_warped_loop_takes_mu_and_the_impacts_at_the_real_count():
    friction = {"mu_0": 0.09, "mu_dry": 0.3, "n_g_cycles": 6000.0}
    ratio, n_r = 4.0, 1000.0
    for tau in (0.0, 800.0, 5000.0, 26000.0):
        real = float(gen.running_in_real_cycles(tau, ratio, n_r))
        assert gen.block_friction_coefficient(friction, tau) == pytest.approx(
            float(gen.friction_coefficient(tau, 0.09, 0.3, 6000.0)), rel=1e-15)
        assert gen.block_friction_coefficient(friction, tau, (ratio, n_r)) == pytest.approx(
            float(gen.friction_coefficient(real, 0.09, 0.3, 6000.0)), rel=1e-14)
        assert gen.block_friction_coefficient(friction, tau, (1.0, n_r)) == pytest.approx(
            gen.block_friction_coefficient(friction, tau), rel=1e-13)
        assert gen.impact_volume_per_warped_cycle_m3(5e-15, tau, (1.0, n_r)) == pytest.approx(
            5e-15, rel=1e-15)
    assert gen.impact_volume_per_warped_cycle_m3(5e-15, 0.0, (ratio, n_r)) == pytest.approx(
        5e-15 / ratio, rel=1e-14)
    # the impacts of N real cycles, spread over the warped cycles, are N cycles' worth
    for cycles in (300.0, 2000.0, 20000.0):
        warped = float(gen.running_in_cycles(cycles, ratio, n_r))
        total, _ = quad(lambda t: gen.impact_volume_per_warped_cycle_m3(1.0, t, (ratio, n_r)),
                        0.0, warped, limit=200)
        assert total == pytest.approx(cycles, rel=1e-8)


class _SyntheticRun:
    """A stand-in for a forward run (no FE): a bore on the believed nodes worn in 1000-cycle
    blocks of the loop's count, each at the rate of the config (k level against ``base_tail``,
    a flexible rod tilts the bore) times mu / 0.1 of the block (the block law with friction)
    plus the impacts' volume of the block (the warped law with running-in), like the loop."""

    def __init__(self, config, base_tail, friction=None, impact=0.0, running_in=None):
        flexible = config["wear_loop"]["rod_models"] == ["flexible"]
        self.angle_rad = NODES
        self.rate = 2e-9 * math.exp(config["wear"]["rbf"]["tail"][0] - base_tail) * (
            1.0 + config["mechanism"]["rod_youngs_modulus_Pa"] / 1e12 if flexible else 1.0)
        self.shape = 1.2 + np.cos(NODES - 0.7 - (0.3 if flexible else 0.0))
        self.mu = config["joint"]["friction_coefficient"]
        self.friction, self.impact, self.running_in = friction, impact, running_in

    def nodal_depth_m(self, cycles):
        ends = np.append(np.arange(0.0, cycles, 1000.0), cycles)
        depth = np.zeros(NODES.size)
        for start, end in zip(ends[:-1], ends[1:]):
            mu = (self.mu if self.friction is None else
                  gen.block_friction_coefficient(self.friction, start, self.running_in))
            volume = (self.impact if self.running_in is None or self.impact == 0.0 else
                      gen.impact_volume_per_warped_cycle_m3(self.impact, start, self.running_in))
            depth += (end - start) * (self.rate * mu / 0.1 * self.shape
                                      + volume * 1e6 * (1.0 + np.sin(NODES)))
        return depth


@pytest.fixture
def synthetic(monkeypatch, believed):
    """The forward runs replaced by :class:`_SyntheticRun`; returns the record of the runs:
    ("simulate", config, rod, cycles) or ("layered", config, cycles, friction, impact,
    running_in)."""
    record = []
    base_tail = believed["wear"]["rbf"]["tail"][0]

    def model_config(config, rod, total):
        return config, rod, total

    def simulate_wear(model):
        record.append(("simulate", *model))
        return _SyntheticRun(model[0], base_tail)

    def layered_run(config, last_cycles, friction=None, impact_volume_m3=0.0, running_in=None):
        record.append(("layered", config, last_cycles, friction, impact_volume_m3, running_in))
        return _SyntheticRun(config, base_tail, friction, impact_volume_m3, running_in)

    monkeypatch.setattr(gen, "model_config", model_config)
    monkeypatch.setattr(gen, "simulate_wear", simulate_wear)
    monkeypatch.setattr(gen, "layered_run", layered_run)
    return record


def _reference_truth(cause, params, believed, last_cycles):
    """A single cause's truth as the generator computed it before it took sets of causes (its
    code, on the module's unchanged pieces)."""
    rod = believed["wear_loop"]["rod_models"][0]
    if cause == "running_in":
        ratio, n_r = params["ratio"], params["n_r_cycles"]
        total = int(math.ceil(float(gen.running_in_cycles(last_cycles, ratio, n_r))))
        run = gen.simulate_wear(gen.model_config(believed, rod, total))
        return lambda cycles: (run.angle_rad, run.nodal_depth_m(
            float(gen.running_in_cycles(cycles, ratio, n_r))))
    if cause == "friction":
        run = gen.layered_run(believed, int(last_cycles), {
            key: params[key] for key in ("mu_0", "mu_dry", "n_g_cycles")})
    elif cause == "impact_wear":
        run = gen.layered_run(believed, int(last_cycles),
                              impact_volume_m3=params["volume_at_v_ref_m3"])
    else:
        config = gen.truth_config(cause, params, believed)
        run = gen.simulate_wear(gen.model_config(config, config["wear_loop"]["rod_models"][0],
                                                 int(last_cycles)))
    return lambda cycles: (run.angle_rad, run.nodal_depth_m(cycles))


@pytest.mark.parametrize("cause", gen.CAUSES)
def test_single_cause_truth_and_files_are_unchanged_by_the_cause_sets(cause, synthetic, believed,
                                                                     tmp_path):
    """Against the single-cause code as it was (on the synthetic runs): the same runs asked
    for, the same truth, the same files for the same seed."""
    seed = gen.data_set_seed(cause, 4)
    truth_rng, lab_rng, noise_rng = gen._streams(seed)
    params = gen.draw_truth(cause, truth_rng)
    lab = gen.draw_lab(lab_rng)
    truth = gen.true_depth(cause, params, believed, lab.last_cycles)
    reference = _reference_truth(cause, params, believed, lab.last_cycles)
    assert synthetic[0] == synthetic[1]
    for cycles in (*lab.profile_cycles, *lab.max_wear_cycles):
        np.testing.assert_array_equal(truth(cycles)[1], reference(cycles)[1])
    data = gen.write_data_set(cause, seed, tmp_path / "set")
    assert data.cause == cause and data.causes == (cause,) and data.params == params
    numerics = with_truth_numerics(load_config(data.believed_toml, run_sections()))
    (tmp_path / "reference").mkdir()
    profiles_csv, max_wear_csv = gen.write_measurements(
        tmp_path / "reference", lab, _reference_truth(cause, params, numerics, lab.last_cycles),
        R_BORE, noise_rng)
    assert data.profiles_csv.read_bytes() == profiles_csv.read_bytes()
    assert data.max_wear_csv.read_bytes() == max_wear_csv.read_bytes()


@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_a_pair_is_one_run_carrying_both_causes(pair, synthetic, believed):
    """One forward run: its config changed by every config cause of the pair, friction and
    impacts layered on it together, running-in as its warped count."""
    _, params = _pair_truth(pair)
    last = 21000
    truth = gen.true_depth(pair, params, believed, last)
    assert len(synthetic) == 1
    expected = believed
    for cause in pair:
        if cause in gen.CONFIG_CAUSES:
            expected = gen.truth_config(cause, params, expected)
    warp = (params["ratio"], params["n_r_cycles"]) if "running_in" in pair else None
    total = last if warp is None else math.ceil(float(gen.running_in_cycles(last, *warp)))
    friction = ({key: params[key] for key in ("mu_0", "mu_dry", "n_g_cycles")}
                if "friction" in pair else None)
    impact = params.get("volume_at_v_ref_m3", 0.0)
    if friction is None and impact == 0.0:
        assert synthetic[0] == ("simulate", expected, expected["wear_loop"]["rod_models"][0],
                                total)
    else:
        assert synthetic[0] == ("layered", expected, total, friction, impact, warp)
    run = _SyntheticRun(expected, believed["wear"]["rbf"]["tail"][0], friction, impact, warp)
    for cycles in (1500, 7000, last):
        read = cycles if warp is None else float(gen.running_in_cycles(cycles, *warp))
        np.testing.assert_array_equal(truth(cycles)[1], run.nodal_depth_m(read))


@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_a_pair_with_one_cause_switched_off_is_the_other_cause_alone(pair, synthetic, believed):
    _, params = _pair_truth(pair, 1)
    counts = (1800, 4000, 9000, 22000)
    for off, on in (pair, pair[::-1]):
        if off not in NEUTRAL:  # the flexible rod has no neutral value
            continue
        both = gen.true_depth(pair, {**params, **NEUTRAL[off]}, believed, 22000)
        alone = gen.true_depth(on, params, believed, 22000)
        for cycles in counts:
            np.testing.assert_allclose(both(cycles)[1], alone(cycles)[1], rtol=1e-11, atol=0.0)
    both = gen.true_depth(pair, params, believed, 22000)(22000)[1]
    for cause in pair:
        alone = gen.true_depth(cause, params, believed, 22000)(22000)[1]
        assert np.abs(both - alone).max() > 1e-3 * both.max()


def test_two_cause_files_are_written_as_single_cause_ones(synthetic, tmp_path):
    pair = ("friction", "running_in")
    seed = gen.two_cause_seed(pair, 0)
    data = gen.write_two_cause_data_set(pair, seed, tmp_path)
    assert data.cause == "friction+running_in" and data.causes == pair
    assert data.params == _pair_truth(pair)[1]
    assert data.lab == gen.draw_lab(gen._streams(seed)[1])
    assert data.believed_toml.read_text() == gen.BELIEVED_TOML
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    assert measured.profile_cycles == data.lab.profile_cycles
    assert tuple(int(c) for c in measured.max_wear[0]) == data.lab.max_wear_cycles
    assert "cycles,angle_deg,wear_depth_m" in data.profiles_csv.read_text().splitlines()
    assert gen.truth_text(data).startswith("friction+running_in: mu_0=")
    again = gen.write_two_cause_data_set(pair, seed, tmp_path / "again")
    assert again.profiles_csv.read_bytes() == data.profiles_csv.read_bytes()


@pytest.mark.slow
@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_one_two_cause_data_set_of_each_pair_is_written_with_a_measurable_effect(pair, tmp_path):
    seed = gen.two_cause_seed(pair, 0)
    start = time.perf_counter()
    data = gen.write_two_cause_data_set(pair, seed, tmp_path / "noisy")
    assert time.perf_counter() - start < 240.0
    assert data.causes == pair
    for cause in pair:
        alone = gen.draw_truth(cause, gen.cause_streams(seed, [cause])[cause])
        _check_single_cause_range(cause, alone)
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    assert measured.profile_cycles == data.lab.profile_cycles
    config = load_config(data.believed_toml, run_sections())
    last = data.lab.profile_cycles[-1]
    truth = gen.true_depth(pair, data.params, config, data.lab.last_cycles)(last)[1]
    belief = gen.believed_depth(config, data.lab.last_cycles)(last)[1]
    assert float(np.sqrt(np.mean((truth - belief) ** 2))) > 3e-6


# --- the slider accelerometer (real dynamics on synthetic bores; no FE) --------------------------

R_OMEGA2 = 0.1 * (2.0 * math.pi * 20.0) ** 2  # r omega^2 of the 1,200 rpm, 0.1 m crank (m/s^2)


def read_acceleration(path) -> dict[int, tuple[np.ndarray, np.ndarray]]:
    """{cycles: (time_s, acceleration)} of acceleration.csv, its header checked."""
    rows = [line.split(",") for line in path.read_text().splitlines()
            if not line.startswith("#")]
    assert rows[0] == ["time_s", "slider_acceleration_m_s2", "cycles"]
    traces: dict[int, tuple[list, list]] = {}
    for time_s, value, cycles in rows[1:]:
        assert re.fullmatch(r"\d+", cycles)
        traces.setdefault(int(cycles), ([], []))
        traces[int(cycles)][0].append(float(time_s))
        traces[int(cycles)][1].append(float(value))
    return {c: (np.array(t), np.array(a)) for c, (t, a) in traces.items()}


def crank_orders(acceleration: np.ndarray, revolutions: int) -> np.ndarray:
    """Amplitude of each crank order (0, 1, 2, ...) over whole revolutions."""
    spectrum = 2.0 * np.abs(np.fft.rfft(acceleration)) / acceleration.size
    spectrum[0] /= 2.0
    return spectrum[::revolutions]


def test_acceleration_traces_parse_at_the_second_and_last_profile_counts(synthetic, tmp_path):
    data = gen.write_data_set("friction", gen.data_set_seed("friction", 2), tmp_path)
    plan = data.accelerometer
    traces = read_acceleration(data.acceleration_csv)
    assert tuple(traces) == plan.trace_cycles == (data.lab.profile_cycles[1],
                                                  data.lab.profile_cycles[-1])
    for time_s, acceleration in traces.values():
        assert time_s[0] == 0.0 and np.all(np.diff(time_s) > 0.0)
        np.testing.assert_allclose(np.diff(time_s), 1.0 / 25600.0, atol=2e-9)
        assert acceleration.size == plan.revolutions * 1280 == 4 * 1280
        assert np.all(np.isfinite(acceleration))
    assert abs(plan.zero_m_s2) <= 8.0 and 1.0 <= plan.hum_m_s2 <= 5.0


def test_acceleration_mean_is_the_zero_and_the_first_order_r_omega_squared(synthetic,
                                                                           tmp_path):
    """The slider's acceleration averages to zero over whole revolutions (and the hum over its
    10 periods); its first crank order is r omega^2 for the ideal mechanism (l cos beta has even
    orders only), moved under 1 % by the clearance, times the sensitivity."""
    for index in (0, 3):
        data = gen.write_data_set("running_in", gen.data_set_seed("running_in", index),
                                  tmp_path / str(index))
        plan = data.accelerometer
        for _, acceleration in read_acceleration(data.acceleration_csv).values():
            noise = plan.noise_fraction * np.sqrt(np.mean(acceleration**2))
            assert abs(acceleration.mean() - plan.zero_m_s2) < 0.5 + 5.0 * noise / math.sqrt(
                acceleration.size)
            spectrum = np.abs(np.fft.rfft(acceleration - acceleration.mean()))
            assert np.argmax(spectrum) == plan.revolutions  # the crank's frequency
            first = crank_orders(acceleration, plan.revolutions)[1]
            assert first / ((1.0 + plan.sensitivity_error) * R_OMEGA2) == pytest.approx(
                1.0, abs=0.015)
            assert first / R_OMEGA2 == pytest.approx(1.0, abs=0.06)


def test_acceleration_leaves_the_other_files_and_follows_the_truths_friction(synthetic,
                                                                             tmp_path,
                                                                             monkeypatch):
    seed = gen.data_set_seed("friction", 5)
    data = gen.write_data_set("friction", seed, tmp_path / "a")
    params = data.params
    for cycles in data.accelerometer.trace_cycles:
        mechanism = gen.trace_mechanism("friction", params, {"joint": {}}, cycles)
        assert mechanism["joint"]["friction_coefficient"] == pytest.approx(
            gen.friction_coefficient(cycles, params["mu_0"], params["mu_dry"],
                                     params["n_g_cycles"]))
    quiet = gen.write_data_set("friction", seed, tmp_path / "q", noise=False)
    assert quiet.accelerometer.hum_m_s2 == quiet.accelerometer.noise_fraction == 0.0
    assert quiet.accelerometer.zero_m_s2 == data.accelerometer.zero_m_s2
    assert quiet.load_cell.noise_N == quiet.load_cell.quantum_N == 0.0
    assert quiet.load_cell.static_matrix().tolist() == data.load_cell.static_matrix().tolist()
    for name in ("write_acceleration", "write_force", "trace_dynamics"):  # nor their dynamics
        monkeypatch.setattr(gen, name, lambda *args: None)
    without = gen.write_data_set("friction", seed, tmp_path / "b")
    for name in ("profiles_csv", "max_wear_csv", "believed_toml"):
        assert getattr(without, name).read_bytes() == getattr(data, name).read_bytes()


def order_difference(first, second, plan):
    """RMS over crank orders 9-20 of the difference of two traces' amplitudes (each over its
    first order: the sensitivity drops out), and the RMS the white noise puts there
    (sigma sqrt(2 / N) on an amplitude)."""
    ratios, noise = [], []
    for acceleration in (first, second):
        orders = crank_orders(acceleration, plan.revolutions)
        ratios.append(orders[9:21] / orders[1])
        sigma = plan.noise_fraction * np.sqrt(np.mean(acceleration**2))
        noise.append(sigma * math.sqrt(2.0 / acceleration.size) / orders[1])
    return float(np.sqrt(np.mean((ratios[1] - ratios[0]) ** 2))), float(math.hypot(*noise))


@pytest.mark.slow  # 4-8 s; the default suite keeps under 6 minutes
def test_a_flexible_rod_parts_from_the_rigid_one_at_orders_9_to_20(believed):
    """The believed rigid rod and a flexible rod of the generator's draw on one synthetic worn
    bore through one analyser: at crank orders 9-20 the traces part by far more than the noise
    there, and by more than the rigid rod's trace started at another crank angle."""
    numerics = with_truth_numerics(believed)
    params = gen.draw_truth("flexible_link", gen._streams(gen.data_set_seed("flexible_link", 0))[0])
    plan = gen.AccelerometerPlan((8000,), (40.0,), (0.3,), 0.0, 0.0, 3.0)
    traces = {}
    for name, cause, start in (("rigid", "none", 40.0), ("flexible", "flexible_link", 40.0),
                               ("rigid later", "none", 220.0)):
        mechanism = gen.trace_mechanism(cause, params, numerics, 8000)
        shifted = gen.AccelerometerPlan((8000,), (start,), (0.3,), 0.0, 0.0, 3.0)
        traces[name] = gen.measure_acceleration(mechanism, synthetic_truth(8000), shifted, 0,
                                                np.random.default_rng(len(traces)))[1]
    rods, noise = order_difference(traces["rigid"], traces["flexible"], plan)
    scatter, _ = order_difference(traces["rigid"], traces["rigid later"], plan)
    print(f"orders 9-20 (of A1): rods {rods:.4f}, rigid scatter {scatter:.4f}, noise {noise:.5f}")
    assert rods > 10.0 * noise and rods > 2.0 * scatter


@pytest.mark.slow
def test_data_sets_of_the_two_rods_part_at_orders_9_to_20(tmp_path):
    """A rigid-rod (``none``) and a flexible-rod (``flexible_link``) data set with their real
    truths (minutes: the flexible truth's run): each pair of traces (second and last profile
    count) parts at crank orders 9-20 by more than ten times the noise there."""
    rigid = gen.write_data_set("none", gen.data_set_seed("none", 0), tmp_path / "rigid")
    flexible = gen.write_data_set("flexible_link", gen.data_set_seed("flexible_link", 0),
                                  tmp_path / "flexible")
    pairs = zip(read_acceleration(rigid.acceleration_csv).values(),
                read_acceleration(flexible.acceleration_csv).values())
    for (_, first), (_, second) in pairs:
        rods, noise = order_difference(first, second, rigid.accelerometer)
        print(f"orders 9-20 (of A1): rods {rods:.4f}, noise {noise:.5f}")
        assert rods > 10.0 * noise


# --- the force ring (force.csv; real dynamics on synthetic bores, no FE) ------------------------

def crank_orders_of(force: np.ndarray, revolutions: int) -> np.ndarray:
    """Complex amplitudes of crank orders 0-5 of each column of ``force`` (whole
    ``revolutions``)."""
    spectrum = 2.0 * np.fft.rfft(force, axis=0) / force.shape[0]
    spectrum[0] /= 2.0
    return spectrum[: 6 * revolutions: revolutions]


def ideal_ring(cell: "gen.LoadCellPlan", **changes) -> "gen.LoadCellPlan":
    """``cell`` with its axes aligned, no cross-talk and no sensitivity error."""
    return replace(cell, misalignment_deg=0.0, crosstalk=(0.0, 0.0),
                   sensitivity_error=(0.0, 0.0), **changes)


def test_force_traces_parse_at_the_accelerometer_counts_and_change_no_other_file(
        synthetic, tmp_path, monkeypatch):
    seed = gen.data_set_seed("running_in", 1)
    data = gen.write_data_set("running_in", seed, tmp_path / "a")
    cell = data.load_cell
    lines = [line for line in data.force_csv.read_text().splitlines()
             if not line.startswith("#")]
    assert lines[0] == "time_s,fx_N,fy_N,cycles"
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv, data.force_csv])
    assert tuple(trace.cycles for trace in measured.force) == cell.trace_cycles == \
        data.accelerometer.trace_cycles
    for trace in measured.force:
        assert trace.time_s[0] == 0.0 and np.all(np.diff(trace.time_s) > 0.0)
        np.testing.assert_allclose(np.diff(trace.time_s), 1.0 / 8000.0, atol=2e-9)
        assert trace.fx_N.size == trace.fy_N.size == 4 * 400
        assert 100.0 < np.std(trace.fx_N) < 5000.0
        assert abs(trace.fx_N.mean()) < 20.0  # AC-coupled: the mean is not measured
    assert 6e3 <= cell.natural_hz <= 9e3 and abs(cell.misalignment_deg) <= 2.5
    monkeypatch.setattr(gen, "write_force", lambda *args: None)
    without = gen.write_data_set("running_in", seed, tmp_path / "b")
    assert not (tmp_path / "b" / "force.csv").exists()
    for name in ("profiles_csv", "max_wear_csv", "believed_toml", "acceleration_csv"):
        assert getattr(without, name).read_bytes() == getattr(data, name).read_bytes()


def test_force_ring_keeps_an_impulse_and_passes_slow_sinusoids():
    """A 20 us rectangular pulse 10 ms before the trace's end: the readings' integral is its
    impulse through M, less what the coupling's high-pass has let decay since,
    exp(-10 ms w_c); a crank-frequency sinusoid passes at the coupling's gain (the mean-free
    ring), one at 1/8 of the rate (1 kHz) with at most the resonance's rise."""
    omega = 40.0 * math.pi
    at = 0.24  # the trace runs from 0.05 s (one revolution in) to 0.25 s
    pulse_t = np.array([0.0, at, at + 1e-9, at + 20e-6, at + 20e-6 + 1e-9, 0.26])
    pulse = np.zeros((6, 2))
    pulse[2:4] = [3500.0, -5000.0]
    impulse = pulse[2] * (20e-6 + 1e-9)
    plan = gen.AccelerometerPlan((8000,), (40.0,), (0.3,), 0.0, 0.0, 3.0)
    for seed in range(3):
        cell = replace(gen.draw_load_cell(np.random.default_rng(seed), plan, noise=False),
                       start_deg=(0.0,))
        _, reading = gen.measure_force(pulse_t, pulse, 0.0, omega, cell, 0, None)
        decay = math.exp(-2.0 * math.pi * cell.coupling_hz * (0.25 - at))
        np.testing.assert_allclose(reading.sum(axis=0) / cell.rate_hz,
                                   cell.static_matrix() @ impulse * decay, rtol=0.01)
    ideal = ideal_ring(cell, natural_hz=6e3, damping=0.05)  # the largest rise
    for frequency, low, high, step in ((20.0, 0.999, 1.001, 50e-6), (1000.0, 1.0, 1.029, 10e-6)):
        time_s = np.linspace(0.0, 0.26, int(round(0.26 / step)) + 1)  # a sine linear between
        wave = np.column_stack([900.0 * np.sin(2.0 * math.pi * frequency * time_s),
                                np.zeros_like(time_s)])
        _, reading = gen.measure_force(time_s, wave, 0.0, omega, ideal, 0, None)
        amplitude = np.abs(np.fft.rfft(reading[:, 0])).max() * 2.0 / reading.shape[0]
        assert low * 900.0 <= amplitude <= high * 900.0
        assert np.abs(reading[:, 1]).max() < 1e-6


def test_noise_free_force_trace_has_the_simulated_crank_orders(believed):
    """The real dynamics on a synthetic worn bore through the force ring without noise: crank
    orders 1-5 of the readings are the simulated force's (the pin on the bushing) through M, to
    1 % of the largest in amplitude (the filter delays them and the coupling leads the first);
    with an ideal ring, the force's own; the mean is not measured."""
    numerics = with_truth_numerics(believed)
    history = gen.trace_dynamics(numerics, *synthetic_truth(8000), 4)
    force = -history.reaction_force_N
    omega = 40.0 * math.pi
    plan = gen.AccelerometerPlan((8000,), (40.0,), (0.3,), 0.0, 0.0, 3.0)
    drawn = gen.draw_load_cell(np.random.default_rng(4), plan, noise=False)
    for cell in (drawn, ideal_ring(drawn)):
        _, reading = gen.measure_force(history.time_s, force, float(history.crank_angle_rad[0]),
                                       omega, cell, 0, None)
        lead = 2.0 * math.pi + (math.radians(cell.start_deg[0]) - history.crank_angle_rad[0]) \
            % (2.0 * math.pi)
        fine = history.time_s[0] + lead / omega + np.arange(4 * 50000) * 1e-6
        simulated = np.column_stack([np.interp(fine, history.time_s, force[:, axis])
                                     for axis in range(2)])
        expected = np.abs(crank_orders_of(simulated, 4) @ cell.static_matrix().T)
        recorded = np.abs(crank_orders_of(reading, 4))
        scale = expected[1:].max(axis=0)
        assert np.all(np.abs(recorded[1:] - expected[1:]) <= 0.01 * scale)
        assert np.all(recorded[0] < 0.005 * scale) and scale[0] > 300.0
