"""The third joint-wear generator's own invariants (not the diagnosis), against facts found
independently of it: closed-form geometry of a ball on a slot, Hertz's line contact, the integral
of the running-in multiplier, and the believed model's own forward run.

That a hidden effect exceeds the noise is checked by default for running-in (a longer run of the
believed model); the slow variant (`make slow`) checks the causes whose truth is a forward run of
its own: wear coefficient, friction, flexible link, impact wear (20-60 s each).

Two-cause data sets: their seeds, draws and the way one truth carries both causes are checked by
default on a synthetic stand-in for the forward runs (no FE); the slow variant runs each pair's
truth on the believed coarse model."""

import math
import re
from dataclasses import replace

import numpy as np
import pytest

from fewear.diagnose.joint.forward import model_config, simulate_wear
from fewear.diagnose.joint.measured import read_joint_measurements
from tests.diagnose.joint.generators import third as gen
from tests.diagnose.joint.generators.truth_numerics import with_truth_numerics

R = 0.010  # bore radius of the default bushing (m)


def _believed(tmp_path):
    path = tmp_path / "believed.toml"
    path.write_text(gen.BELIEVED_TOML)
    return gen.believed_config(path)


def _truth(cause, index=0):
    rng = np.random.default_rng(gen.data_set_seed(cause, index))
    lab = gen.draw_lab(rng)
    return lab, gen.draw_params(cause, rng)


# --- seeds, plans, draws (no forward runs) ----------------------------------------------------

def test_seeds_distinct_and_apart_from_small_seeds():
    seeds = [gen.data_set_seed(cause, index) for cause in gen.CAUSES for index in range(100)]
    assert len(set(seeds)) == len(seeds)
    assert min(seeds) > 1000
    with pytest.raises(ValueError):
        gen.data_set_seed("thermal", 0)


def test_measuring_plans_within_the_brief():
    for seed in range(7000, 7060):
        lab = gen.draw_lab(np.random.default_rng(seed))
        counts = lab.profile_cycles
        assert 3 <= len(counts) <= 5 and list(counts) == sorted(set(counts))
        assert 2000 <= counts[0] and counts[-1] <= 22000
        assert not set(lab.max_wear_cycles) & set(counts)
        assert all(0 < c <= counts[-1] for c in lab.max_wear_cycles)
        assert 0.5e-3 <= lab.stylus_radius_m <= 1.5e-3 and 0.3e-6 <= lab.noise_m <= 1.0e-6
        assert abs(lab.origin_deg) <= 30.0


def test_truth_configs_change_only_their_cause(tmp_path):
    config = _believed(tmp_path)

    def changed(cause, params):
        truth = gen.truth_config(cause, params, config)
        return {(section, key) for section in config for key in config[section]
                if truth[section][key] != config[section][key]}

    assert changed("wear_coefficient", {"k_factor": 1.7}) == {("wear", "rbf")}
    truth = gen.truth_config("wear_coefficient", {"k_factor": 1.7}, config)
    assert truth["wear"]["rbf"]["tail"][0] - config["wear"]["rbf"]["tail"][0] == pytest.approx(
        math.log(1.7))
    assert changed("friction", {"friction_coefficient": 0.2}) == {("joint",
                                                                   "friction_coefficient")}
    _, flexible = _truth("flexible_link")
    assert ("wear_loop", "rod_models") in changed("flexible_link", flexible)
    assert {section for section, _ in changed("flexible_link", flexible)} <= {"wear_loop",
                                                                               "mechanism"}
    assert changed("none", {"model": "believed"}) == set()


def test_running_in_time_is_the_integral_of_the_multiplier():
    factor, cycles_r = 2.1, 9000.0
    n = np.linspace(0.0, 20000.0, 200001)
    rate = gen.running_in_multiplier(n, factor, cycles_r)
    integral = np.concatenate([[0.0], np.cumsum(0.5 * (rate[1:] + rate[:-1]) * np.diff(n))])
    assert np.allclose(gen.running_in_time(n, factor, cycles_r), integral, atol=1e-3)
    assert rate[0] == pytest.approx(factor) and gen.running_in_multiplier(
        cycles_r, factor, cycles_r) == pytest.approx(1.0)
    assert gen.running_in_time(20000.0, factor, cycles_r) == pytest.approx(
        20000.0 + (factor - 1.0) * cycles_r / 2.0)


def test_running_in_lifts_the_first_count_by_30_to_150_percent():
    for index in range(60):
        lab, params = _truth("running_in", index)
        first = lab.profile_cycles[0]
        tau = gen.running_in_time(float(first), params["initial_rate_factor"],
                                  params["running_in_cycles"])
        assert 0.3 <= tau / first - 1.0 <= 1.5  # believed depth linear in N over the first block


def test_hertz_line_contact_and_the_pocket_volume(tmp_path):
    config = _believed(tmp_path)
    force = 5000.0
    half_width, peak = gen.hertz_line_contact(force, config)
    r_star = 0.0095 * R / (R - 0.0095)
    e_star = 1.0 / ((1 - 0.27**2) / 207e9 + (1 - 0.32**2) / 90e9)
    assert peak == pytest.approx(math.sqrt(force * e_star / (math.pi * 0.018 * r_star)))
    assert half_width * peak * math.pi * 0.018 / 2.0 == pytest.approx(force)  # the load carried
    grid = gen.fine_grid()
    for scatter in (0.0, math.radians(3.0)):
        damage = gen.impact_damage(grid, R, [(0.3, float(half_width), float(peak))], 0.0, scatter)
        integral = R * damage.sum() * (grid[1] - grid[0])  # int p0^2 (1 - x^2/b^2) dx
        assert integral == pytest.approx(4.0 / 3.0 * peak**2 * half_width, rel=0.01)
    below = gen.impact_damage(grid, R, [(0.3, float(half_width), float(peak))], 1.01 * peak, 0.0)
    assert not below.any()


# --- the instruments --------------------------------------------------------------------------

def test_impact_wear_is_taken_from_the_running_mechanism(tmp_path):
    """The cycles the truth's impact wear is taken from are those of the running mechanism: the
    same motion from the ideal state as the start-up's (the config's own two settling cycles),
    continued past :data:`IMPACT_SETTLING_CYCLES`, not a restart. The start-up impacts; how
    often the settled orbit impacts is not asserted: the clearance joint is chaotic and its
    attractor on the unworn bore depends on the machine's rounding (continuous contact on one,
    seven impacts a cycle on another)."""
    from fewear.diagnose.joint.forward import cycle_on_worn_bore

    config = with_truth_numerics(_believed(tmp_path))
    own_settling = config["mechanism"]["settling_cycles"]
    assert gen.IMPACT_SETTLING_CYCLES > own_settling
    start_up = cycle_on_worn_bore(config)
    assert len(start_up.impact_episodes()) >= 3
    through = cycle_on_worn_bore(config, recorded_cycles=gen.IMPACT_SETTLING_CYCLES - own_settling
                                 + gen.IMPACT_RECORDED_CYCLES)
    running = cycle_on_worn_bore(gen.settled(config), recorded_cycles=gen.IMPACT_RECORDED_CYCLES)
    tail = slice(through.time_s.size - running.time_s.size, None)
    period_s = start_up.time_s[0] / own_settling
    assert running.time_s[0] == pytest.approx(gen.IMPACT_SETTLING_CYCLES * period_s, rel=1e-9)
    np.testing.assert_allclose(running.time_s, through.time_s[tail], rtol=1e-12)
    np.testing.assert_allclose(running.reaction_force_N, through.reaction_force_N[tail],
                               rtol=1e-9, atol=1e-9)
    np.testing.assert_array_equal(running.mode, through.mode[tail])


def test_ball_on_the_unworn_circle_reports_no_depth():
    grid = gen.fine_grid()
    at = np.radians(np.linspace(0.0, 359.0, 97))
    for ball in (0.5e-3, 1.5e-3):
        assert np.abs(gen.ball_probe_depth_m(grid, np.zeros_like(grid), R, at, ball)).max() < 1e-12


def test_ball_never_reports_more_than_the_surface():
    grid = gen.fine_grid()
    rng = np.random.default_rng(1)
    depth = np.zeros_like(grid)
    for _ in range(30):  # pits and pockets of many widths
        centre, width, height = rng.uniform(0, 2 * math.pi), rng.uniform(0.002, 0.3), \
            rng.uniform(1e-6, 150e-6)
        depth += height * np.exp(-0.5 * (gen.wrapped(grid - centre) / width) ** 2)
    at = np.sort(rng.uniform(0.0, 2 * math.pi, 500))
    true = np.interp(at, grid, depth, period=2 * math.pi)
    for ball in (0.5e-3, 1.0e-3, 1.5e-3):
        seen = gen.ball_probe_depth_m(grid, depth, R, at, ball)
        assert np.all(seen <= true + 1e-12)
        assert np.any(seen < true - 1e-6)  # the narrow pits are bridged


def test_ball_follows_a_wide_smooth_pocket():
    """Where the worn surface curves less than the ball, the ball reaches it everywhere; the
    reported depth is then the true one less the cosine error of compensating the ball radius
    along the ray, r (1 / cos beta - 1), beta the surface's tilt (zero at the pocket's bottom),
    up to the pocket's curvature over the ball's off-ray contact (< 0.1 um here)."""
    grid = gen.fine_grid()
    width, height = math.radians(20.0), 100e-6

    def pocket(angle):
        offset = gen.wrapped(angle - 2.0)
        depth = height * np.exp(-0.5 * (offset / width) ** 2)
        return depth, -offset / width**2 * depth  # h and dh/dtheta

    at = np.radians(np.linspace(0.0, 359.0, 181))
    true, slope = pocket(at)
    tilt = np.arctan(slope / (R + true))
    for ball in (0.5e-3, 1.5e-3):
        seen = gen.ball_probe_depth_m(grid, pocket(grid)[0], R, at, ball)
        cosine_error = ball * (1.0 / np.cos(tilt) - 1.0)
        surface = np.interp(at, grid, pocket(grid)[0], period=2 * math.pi)  # as sampled
        assert np.all(seen <= surface + 1e-15)
        assert np.abs(seen - (true - cosine_error)).max() < 0.1e-6
        bottom = np.argmin(np.abs(gen.wrapped(at - 2.0)))
        assert abs(seen[bottom] - true[bottom]) < 0.02e-6 and true[bottom] > 0.99 * height


def test_ball_bridges_a_narrow_slot_as_geometry_says():
    grid = gen.fine_grid()
    step = grid[1]
    centre_index, half = 1000, 14  # slot edges (the last unworn points) at +- 14 grid steps
    depth = np.zeros_like(grid)
    depth[centre_index - half + 1:centre_index + half] = 100e-6
    ball, alpha = 1.0e-3, half * step
    centre = R * math.cos(alpha) - math.sqrt(ball**2 - (R * math.sin(alpha)) ** 2)
    expected = centre + ball - R  # the ball resting on both edges of a slot narrower than itself
    seen = gen.ball_probe_depth_m(grid, depth, R, np.array([grid[centre_index]]), ball)
    assert seen[0] == pytest.approx(expected, abs=1e-10)
    assert 20e-6 < expected < 100e-6


def test_centre_offset_is_removed_on_the_unworn_arcs():
    angle = np.radians(np.sort(np.random.default_rng(2).uniform(0.0, 360.0, 240)))

    def scar(centre, half_width, depth):  # a wear scar with edges: zero outside
        x = np.clip(np.abs(gen.wrapped(angle - centre)) / half_width, 0.0, 1.0)
        return depth * (1.0 - x**2) ** 1.5

    wear = scar(0.2, 0.9, 150e-6) + scar(3.3, 0.7, 80e-6)
    raw = wear + 14e-6 * np.cos(angle) - 9e-6 * np.sin(angle)  # a 17 um centre offset
    # the scars' edges shallower than the acceptance band (4 sigma + 1 um) join the fit: a
    # fraction of a micrometre is left
    assert np.abs(gen.remove_centre_offset(angle, raw, 0.5e-6) - wear).max() < 0.5e-6
    noisy = raw + np.random.default_rng(3).normal(0.0, 0.5e-6, angle.size)
    assert np.abs(gen.remove_centre_offset(angle, noisy, 0.5e-6) - (noisy - raw + wear)).max() \
        < 0.6e-6


# --- data sets (forward runs of the rigid believed model: seconds each) -----------------------

@pytest.mark.slow  # 12 s of forward runs; the fourth generator's files parse by default
def test_files_parse_with_the_reader(tmp_path):
    data = gen.write_data_set("none", gen.data_set_seed("none", 0), tmp_path)
    assert data.believed_toml.read_text() == gen.BELIEVED_TOML
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    assert measured.profile_cycles == data.lab.profile_cycles
    assert tuple(int(c) for c in measured.max_wear[0]) == data.lab.max_wear_cycles
    for profile in measured.profiles:
        assert profile.angle_rad.size >= 0.8 * data.lab.point_count
        assert profile.depth_m.max() > 10e-6
    depth = measured.max_wear[1]
    assert np.all(depth > 0.0) and depth.max() < 1e-3


def test_noiseless_none_is_the_believed_run_within_the_stylus_effect(tmp_path):
    """The believed model run with the truths' converged numerics (truth_numerics.py)."""
    data = gen.write_data_set("none", gen.data_set_seed("none", 0), tmp_path, noise=False)
    config = with_truth_numerics(gen.believed_config(data.believed_toml))
    history = simulate_wear(model_config(config, "rigid", data.lab.profile_cycles[-1]))
    grid = gen.fine_grid()
    for profile in read_joint_measurements(data.profiles_csv).profiles:
        theta = profile.angle_rad + math.radians(data.lab.origin_deg)  # undo the origin shift
        believed = history.depth_at(profile.cycles, theta)
        stylus = believed - gen.ball_probe_depth_m(
            grid, history.depth_at(profile.cycles, grid), R, theta, data.lab.stylus_radius_m)
        assert np.all(stylus >= -1e-12)
        assert np.all(np.abs(profile.depth_m - believed) <= stylus + 0.5e-6)
        assert np.sqrt(np.mean((profile.depth_m - believed) ** 2)) < 1e-6


@pytest.mark.slow  # 4-8 s; the default suite keeps under 6 minutes
def test_a_data_set_is_reproducible_from_its_seed(tmp_path):
    seed = gen.data_set_seed("none", 0)
    first = gen.write_data_set("none", seed, tmp_path / "a")
    again = gen.write_data_set("none", seed, tmp_path / "b")
    for name in ("profiles_csv", "max_wear_csv"):
        assert getattr(first, name).read_text() == getattr(again, name).read_text()
    assert first.params == again.params
    other = gen.write_data_set("none", gen.data_set_seed("none", 1), tmp_path / "c")
    assert other.profiles_csv.read_text() != first.profiles_csv.read_text()


@pytest.mark.parametrize("cause", [
    "running_in",
    pytest.param("wear_coefficient", marks=pytest.mark.slow),
    pytest.param("friction", marks=pytest.mark.slow),
    pytest.param("flexible_link", marks=pytest.mark.slow),
    pytest.param("impact_wear", marks=pytest.mark.slow)])
def test_each_hidden_effect_exceeds_the_noise_at_the_last_count(cause, tmp_path):
    config = _believed(tmp_path)
    lab, params = _truth(cause)
    last = lab.profile_cycles[-1]
    bore, derived = gen.true_bore(cause, params, config, last)
    history = simulate_wear(model_config(config, "rigid", last))
    grid = gen.fine_grid()
    difference = bore.depth_m(last) - history.depth_at(last, grid)
    rms = np.sqrt(np.mean(difference**2))
    assert rms > max(5.0 * lab.noise_m, 3e-6)
    if cause == "running_in":
        first = lab.profile_cycles[0]
        ratio = bore.depth_m(first).sum() / history.depth_at(first, grid).sum()
        assert 1.3 <= ratio <= 2.5
    if cause == "impact_wear":
        assert 0.15 <= derived["volume_fraction"] <= 0.40
        assert np.all(difference >= -1e-12)  # impacts only add wear


# --- two hidden causes (the forward runs replaced by a synthetic bore: no FE) -----------------

NEUTRAL = {"wear_coefficient": {"k_factor": 1.0}, "friction": {"friction_coefficient": 0.1},
           "running_in": {"initial_rate_factor": 1.0, "running_in_cycles": 8000.0},
           "impact_wear": {"pressure_threshold_Pa": 80e6, "scatter_deg": 3.0,
                           "volume_fraction_target": 0.0}}
"""Parameters with which a cause has no effect (friction at the believed 0.1)."""


def _assert_in_single_cause_range(cause, params):
    """The ranges of the module doc."""
    if cause == "wear_coefficient":
        f = params["k_factor"]
        assert 0.45 <= f <= 0.72 or 1.4 <= f <= 2.2
    elif cause == "flexible_link":
        steel = params["material"] == "steel"
        assert params["material"] in ("steel", "aluminium")
        low, high = (195e9, 215e9) if steel else (69e9, 73e9)
        assert low <= params["rod_youngs_modulus_Pa"] <= high
        low, high = (7750.0, 7900.0) if steel else (2700.0, 2810.0)
        assert low <= params["rod_density_kg_m3"] <= high
        assert params["rod_poisson_ratio"] == (0.29 if steel else 0.33)
        assert 4.5e-3 <= params["rod_height_m"] <= 6.5e-3
        assert 16e-3 <= params["rod_width_m"] <= 20e-3
        assert 1e-5 <= params["rod_damping_s"] <= 6e-5
    elif cause == "friction":
        mu = params["friction_coefficient"]
        assert 0.035 <= mu <= 0.07 or 0.15 <= mu <= 0.28
    elif cause == "impact_wear":
        assert 60e6 <= params["pressure_threshold_Pa"] <= 100e6
        assert 2.0 <= params["scatter_deg"] <= 4.0
        assert 0.15 <= params["volume_fraction_target"] <= 0.40
    else:
        assert cause == "running_in"
        assert 1.5 <= params["initial_rate_factor"] <= 2.4
        assert 5000.0 <= params["running_in_cycles"] <= 14000.0


class _SyntheticRun:
    """A stand-in for a truth's forward run: a smooth bore on 96 nodes whose depth grows
    nonlinearly in N and with the config's friction, k level (against ``base_tail``, the
    believed ln k) and rod (a flexible rod tilts it)."""

    def __init__(self, config, base_tail):
        self.angle_rad = np.arange(96) * (2 * math.pi / 96)
        flexible = config["wear_loop"]["rod_models"] == ["flexible"]
        self.scale = (config["joint"]["friction_coefficient"] / 0.1
                      * math.exp(config["wear"]["rbf"]["tail"][0] - base_tail)
                      * (1.0 + config["mechanism"]["rod_youngs_modulus_Pa"] / 1e12 if flexible
                         else 1.0))
        self.tilt = 0.3 if flexible else 0.0

    def nodal_depth_m(self, cycles):
        shape = 1.2 + np.cos(self.angle_rad - 0.7 - self.tilt)
        return 4e-9 * float(cycles) ** 0.95 * shape * self.scale

    def depth_at(self, cycles, angle_rad):
        return np.interp(angle_rad, self.angle_rad, self.nodal_depth_m(cycles), period=2 * math.pi)


@pytest.fixture
def synthetic(monkeypatch, tmp_path):
    """The truths' forward runs and crank cycles replaced by synthetic ones; returns the record
    of the runs (config, cycles) and of the crank cycles (config, depth) asked for."""
    import fewear.diagnose.joint.forward as forward

    record = {"runs": [], "cycles": []}
    base_tail = _believed(tmp_path)["wear"]["rbf"]["tail"][0]

    def run(config, total):
        record["runs"].append((config, total))
        return _SyntheticRun(config, base_tail)

    def cycle(config, angle_rad=None, depth_m=None, recorded_cycles=1):
        record["cycles"].append((config, depth_m))
        return (config["joint"]["friction_coefficient"],
                0.0 if depth_m is None else float(np.max(depth_m)))

    def hits(cycle, config):
        mu, deepest = cycle
        return [((0.4 + 2e4 * deepest) % (2 * math.pi), 3e-4, 1.1e8 + 2e8 * mu),
                (2.9, 2e-4, 1.3e8)]

    monkeypatch.setattr(gen, "_run", run)
    monkeypatch.setattr(gen, "impact_hits", hits)
    monkeypatch.setattr(forward, "cycle_on_worn_bore", cycle)
    return record


def _reference_bore(cause, params, config, last):
    """A single cause's truth as the generator computed it before it took sets of causes (its
    code, on the module's unchanged pieces)."""
    from fewear.diagnose.joint.forward import cycle_on_worn_bore

    if cause in ("none", "wear_coefficient", "flexible_link", "friction"):
        return gen.TrueBore(gen._run(gen.truth_config(cause, params, config), last), R), {}
    if cause == "running_in":
        timing = (params["initial_rate_factor"], params["running_in_cycles"])
        needed = int(math.ceil(gen.running_in_time(float(last), *timing) / 100.0)) * 100
        return gen.TrueBore(gen._run(config, needed), R, running_in=timing), {
            "believed_cycles_at_last": float(gen.running_in_time(float(last), *timing))}
    history = gen._run(config, last)
    grid = gen.fine_grid()
    counts = np.linspace(0.0, float(last), gen.IMPACT_EVALUATIONS)
    damage, impacts = [], 0
    running = gen.settled(config)
    for count in counts:
        cycle = (cycle_on_worn_bore(running, recorded_cycles=gen.IMPACT_RECORDED_CYCLES)
                 if count == 0.0 else
                 cycle_on_worn_bore(running, history.angle_rad, history.nodal_depth_m(count),
                                    recorded_cycles=gen.IMPACT_RECORDED_CYCLES))
        hits = gen.impact_hits(cycle, config)
        impacts += len(hits)
        damage.append(gen.impact_damage(grid, R, hits, params["pressure_threshold_Pa"],
                                        math.radians(params["scatter_deg"]))
                      / gen.IMPACT_RECORDED_CYCLES)
    damage = np.array(damage)
    unit = gen.TrueBore(history, R, impact_cycles=counts, impact_rate=damage)
    unit_volume = gen.worn_volume_m3(unit.impact_depth_m(last), config)
    sliding = gen.worn_volume_m3(history.depth_at(last, grid), config)
    coefficient = params["volume_fraction_target"] * sliding / unit_volume
    bore = gen.TrueBore(history, R, impact_cycles=counts, impact_rate=coefficient * damage)
    reached = gen.worn_volume_m3(bore.impact_depth_m(last), config) / sliding
    return bore, {"impact_coefficient_m_Pa2": float(coefficient),
                  "volume_fraction": float(reached), "impacts_sampled": float(impacts)}


def _pair_truth(pair, index=0):
    seed = gen.two_cause_seed(pair, index)
    return seed, gen.draw_pair_params(pair, gen.cause_streams(seed, pair))


def test_two_cause_pairs_are_the_ten_pairs_in_causes_order():
    assert len(gen.TWO_CAUSE_PAIRS) == len(set(gen.TWO_CAUSE_PAIRS)) == 10
    for first, second in gen.TWO_CAUSE_PAIRS:
        assert "none" not in (first, second)
        assert gen.CAUSES.index(first) < gen.CAUSES.index(second)


def test_two_cause_seeds_distinct_apart_from_single_ones_and_refuse_bad_input():
    seeds = [gen.two_cause_seed(pair, index) for pair in gen.TWO_CAUSE_PAIRS
             for index in range(100)]
    assert len(set(seeds)) == len(seeds) == 1000
    single = {gen.data_set_seed(cause, index) for cause in gen.CAUSES for index in range(100)}
    assert not set(seeds) & single
    assert all(isinstance(seed, int) for seed in seeds)
    good = ("friction", "running_in")
    for pair in (("running_in", "friction"), ("friction", "friction"), ("friction", "none"),
                 ("friction",), "friction+running_in", ("friction", "thermal"), None):
        with pytest.raises(ValueError, match=re.escape(repr(pair)) + ".*expected one of"):
            gen.two_cause_seed(pair, 0)
        with pytest.raises(ValueError, match=re.escape(repr(pair))):
            gen.write_two_cause_data_set(pair, 17000, "/nonexistent/never/written")
    for index in (100, -1, 1.5, "0"):
        with pytest.raises(ValueError, match=re.escape(repr(index)) + ".*0-99"):
            gen.two_cause_seed(good, index)


def test_single_cause_draws_keep_to_the_stated_ranges():
    for cause in gen.CAUSES[:-1]:
        for index in range(40):
            _assert_in_single_cause_range(cause, _truth(cause, index)[1])


@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_each_cause_of_a_pair_is_drawn_from_its_own_single_cause_distribution(pair):
    branches = set()
    for index in range(40):
        seed, params = _pair_truth(pair, index)
        names = [set(_truth(cause)[1]) for cause in pair]
        assert set(params) == names[0] | names[1] and not names[0] & names[1]
        for cause in pair:
            alone = gen.draw_params(cause, gen.cause_streams(seed, [cause])[cause])
            assert {key: params[key] for key in alone} == alone  # its own stream, any partner
            _assert_in_single_cause_range(cause, alone)
        if "friction" in pair:
            branches.add(params["friction_coefficient"] > 0.1)
    assert "friction" not in pair or branches == {False, True}


def test_pairs_draw_each_cause_independently_of_its_partner():
    seed = 17123
    friction = [gen.draw_pair_params(pair, gen.cause_streams(seed, pair))["friction_coefficient"]
                for pair in gen.TWO_CAUSE_PAIRS if "friction" in pair]
    assert len(friction) == 4 and len(set(friction)) == 1
    k = gen.draw_pair_params(("wear_coefficient", "friction"), gen.cause_streams(seed, (
        "wear_coefficient", "friction")))["k_factor"]
    assert k != friction[0]
    other = gen.draw_pair_params(("friction", "running_in"), gen.cause_streams(seed + 1, (
        "friction", "running_in")))
    assert other["friction_coefficient"] != friction[0]


def test_truth_causes_are_checked():
    assert gen.truth_causes("friction") == ("friction",)
    assert gen.truth_causes(["running_in", "friction"]) == ("friction", "running_in")
    for bad in ("thermal", ("friction", "friction"), ("none", "friction"), ()):
        with pytest.raises(ValueError):
            gen.truth_causes(bad)


@pytest.mark.parametrize("cause", [
    pytest.param(cause, marks=pytest.mark.slow) if cause == "flexible_link" else cause
    for cause in gen.CAUSES])  # the flexible rod's truth runs its own dynamics: slow
def test_single_cause_truth_and_files_are_unchanged_by_the_cause_sets(cause, synthetic,
                                                                     tmp_path):
    """Against the single-cause code as it was (on the synthetic runs): the same truth, the
    same derived values, the same files for the same seed."""
    config = _believed(tmp_path)
    lab, params = _truth(cause, 3)
    last = lab.profile_cycles[-1]
    bore, derived = gen.true_bore(cause, params, config, last)
    reference, expected = _reference_bore(cause, params, config, last)
    assert derived == expected
    for cycles in (*lab.profile_cycles, *lab.max_wear_cycles):
        np.testing.assert_array_equal(bore.depth_m(cycles), reference.depth_m(cycles))
    # the files: the data set drawn and measured as write_data_set did before the cause sets
    seed = gen.data_set_seed(cause, 3)
    data = gen.write_data_set(cause, seed, tmp_path / "set")
    assert data.cause == cause and data.causes == (cause,)
    rng = np.random.default_rng(seed)
    lab = gen.draw_lab(rng)
    params = gen.draw_params(cause, rng)
    truth = with_truth_numerics(gen.believed_config(data.believed_toml))
    bore, expected = _reference_bore(cause, params, truth, lab.profile_cycles[-1])
    traces = [gen.measure_profile(bore, lab, trace, rng)
              for trace in range(len(lab.profile_cycles))]
    gen.write_profiles_csv(tmp_path / "profiles.csv", traces, lab)
    gen.write_max_wear_csv(tmp_path / "max_wear.csv", gen.measure_max_wear(bore, lab, rng), lab)
    assert data.profiles_csv.read_bytes() == (tmp_path / "profiles.csv").read_bytes()
    assert data.max_wear_csv.read_bytes() == (tmp_path / "max_wear.csv").read_bytes()
    assert data.params == {**params, **expected, "effect_rms_um": gen.rms_difference_m(
        bore, truth, lab.profile_cycles[-1]) * 1e6}


@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_a_pair_is_one_run_carrying_both_causes(pair, synthetic, tmp_path):
    """One forward run for the truth; its config changed by every config cause of the pair;
    the impacts' cycles on that run's bore (at tau(N) with running-in) and its config."""
    config = _believed(tmp_path)
    lab = gen.draw_lab(np.random.default_rng(gen.two_cause_seed(pair, 0)))
    _, params = _pair_truth(pair)
    last = lab.profile_cycles[-1]
    bore, derived = gen.true_bore(pair, params, config, last)
    assert len(synthetic["runs"]) == 1
    run_config, total = synthetic["runs"][0]
    expected = config
    for cause in pair:
        if cause in gen.CONFIG_CAUSES:
            expected = gen.truth_config(cause, params, expected)
    assert run_config == expected
    if "running_in" in pair:
        timing = (params["initial_rate_factor"], params["running_in_cycles"])
        assert total >= gen.running_in_time(float(last), *timing) and total % 100 == 0
        assert bore.running_in == timing
    else:
        assert total == last and bore.running_in is None
    if "impact_wear" in pair:
        counts = np.linspace(0.0, float(last), gen.IMPACT_EVALUATIONS)
        assert len(synthetic["cycles"]) == counts.size
        for count, (cycle_config, depth) in zip(counts[1:], synthetic["cycles"][1:]):
            assert cycle_config == gen.settled(run_config)
            np.testing.assert_array_equal(depth, bore.history.nodal_depth_m(
                bore.sliding_cycles(count)))
        assert derived["volume_fraction"] == pytest.approx(params["volume_fraction_target"])
    else:
        assert not synthetic["cycles"] and bore.impact_rate is None


@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_a_pair_with_one_cause_switched_off_is_the_other_cause_alone(pair, synthetic,
                                                                    tmp_path):
    config = _believed(tmp_path)
    lab = gen.draw_lab(np.random.default_rng(gen.two_cause_seed(pair, 1)))
    _, params = _pair_truth(pair, 1)
    last = lab.profile_cycles[-1]
    counts = (*lab.profile_cycles, *lab.max_wear_cycles)
    for off, on in (pair, pair[::-1]):
        if off not in NEUTRAL:  # the flexible rod has no neutral value
            continue
        both, derived = gen.true_bore(pair, {**params, **NEUTRAL[off]}, config, last)
        alone, expected = gen.true_bore(on, params, config, last)
        for cycles in counts:
            np.testing.assert_allclose(both.depth_m(cycles), alone.depth_m(cycles), rtol=1e-12,
                                       atol=1e-18)
        for key, value in expected.items():
            assert derived[key] == pytest.approx(value, rel=1e-12)
    # with both on, the truth is neither cause alone
    both = gen.true_bore(pair, params, config, last)[0].depth_m(last)
    for cause in pair:
        assert np.abs(both - gen.true_bore(cause, params, config, last)[0].depth_m(last)).max() \
            > 1e-3 * both.max()


def test_two_cause_files_are_written_as_single_cause_ones(synthetic, tmp_path):
    pair = ("friction", "running_in")
    seed = gen.two_cause_seed(pair, 0)
    data = gen.write_two_cause_data_set(pair, seed, tmp_path)
    assert data.cause == "friction+running_in" and data.causes == pair
    _, params = _pair_truth(pair)
    assert {key: data.params[key] for key in params} == params
    assert "believed_cycles_at_last" in data.params and "effect_rms_um" in data.params
    assert data.believed_toml.read_text() == gen.BELIEVED_TOML
    lab = gen.draw_lab(np.random.default_rng(seed))
    assert data.lab.profile_cycles == lab.profile_cycles
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv])
    assert measured.profile_cycles == lab.profile_cycles
    assert data.profiles_csv.read_text().splitlines()[1] == "cycles,angle_deg,wear_depth_m"
    again = gen.write_two_cause_data_set(pair, seed, tmp_path / "again")
    assert again.profiles_csv.read_bytes() == data.profiles_csv.read_bytes()


@pytest.mark.slow
@pytest.mark.parametrize("pair", gen.TWO_CAUSE_PAIRS, ids="+".join)
def test_each_pair_truth_exceeds_the_noise_at_the_last_count(pair, tmp_path):
    """Each pair's truth on the believed coarse model (not the truths' numerics)."""
    config = _believed(tmp_path)
    seed, params = _pair_truth(pair)
    lab = gen.draw_lab(np.random.default_rng(seed))
    last = lab.profile_cycles[-1]
    bore, derived = gen.true_bore(pair, params, config, last)
    history = simulate_wear(model_config(config, "rigid", last))
    grid = gen.fine_grid()
    difference = bore.depth_m(last) - history.depth_at(last, grid)
    assert np.sqrt(np.mean(difference**2)) > max(5.0 * lab.noise_m, 3e-6)
    if "impact_wear" in pair:
        assert 0.15 <= derived["volume_fraction"] <= 0.40


# --- the slider accelerometer (the dynamics are real; the wear runs synthetic) ------------------

CRANK_HZ = 20.0  # 1,200 rpm
R_OMEGA2 = 0.1 * (2.0 * math.pi * CRANK_HZ) ** 2  # r omega^2 of the default crank (m/s^2)


def _acceleration_traces(path):
    """{cycles: (time_s, acceleration)} of an acceleration file; its header checked."""
    lines = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    assert lines[0] == "time_s,slider_acceleration_m_s2,cycles"
    traces = {}
    for line in lines[1:]:
        time_s, acceleration, cycles = line.split(",")
        assert cycles.isdigit()
        entry = traces.setdefault(int(cycles), ([], []))
        entry[0].append(float(time_s))
        entry[1].append(float(acceleration))
    return {cycles: (np.array(t), np.array(a)) for cycles, (t, a) in traces.items()}


def _crank_harmonics(acceleration, revolutions):
    """Amplitudes of crank harmonics 0, 1, 2, ... over whole ``revolutions``."""
    spectrum = np.abs(np.fft.rfft(acceleration)) * 2.0 / acceleration.size
    spectrum[0] /= 2.0
    return spectrum[::revolutions]


def test_acceleration_file_parses_at_three_profile_counts(synthetic, tmp_path):
    data = gen.write_data_set("friction", gen.data_set_seed("friction", 4), tmp_path)
    meter = data.accelerometer
    traces = _acceleration_traces(data.acceleration_csv)
    counts = data.lab.profile_cycles
    assert tuple(traces) == meter.trace_cycles
    assert meter.trace_cycles == (counts[0], counts[len(counts) // 2], counts[-1])
    assert meter.sample_rate_hz in (5000.0, 6400.0, 8000.0)
    for revolutions, (time_s, acceleration) in zip(meter.revolutions, traces.values()):
        assert time_s[0] == 0.0 and np.all(np.diff(time_s) > 0.0)
        np.testing.assert_allclose(np.diff(time_s), 1.0 / meter.sample_rate_hz, rtol=1e-9)
        assert acceleration.size == revolutions * meter.sample_rate_hz / CRANK_HZ
        assert 3 <= revolutions <= 4 and np.all(np.isfinite(acceleration))
    assert abs(meter.gain - 1.0) <= 0.06 and abs(meter.offset_m_s2) <= 15.0
    assert 8.0 <= meter.noise_m_s2 <= 20.0


def test_acceleration_mean_is_the_offset_and_its_first_harmonic_r_omega_squared(synthetic,
                                                                               tmp_path):
    """Over whole revolutions the slider's acceleration averages to zero; its first crank
    harmonic is r omega^2 for the ideal slider-crank (l cos beta carries even harmonics only),
    moved under 1 % by the clearance; the instrument multiplies it by its gain."""
    data = gen.write_data_set("none", gen.data_set_seed("none", 2), tmp_path)
    meter = data.accelerometer
    for revolutions, (_, acceleration) in zip(meter.revolutions,
                                              _acceleration_traces(data.acceleration_csv).values()):
        noise = meter.noise_m_s2 / math.sqrt(acceleration.size)
        assert abs(acceleration.mean() - meter.offset_m_s2) < 0.5 + 5.0 * noise
        spectrum = np.abs(np.fft.rfft(acceleration - acceleration.mean()))
        assert np.argmax(spectrum) == revolutions  # the crank's frequency dominates
        first = _crank_harmonics(acceleration, revolutions)[1]
        assert first / (meter.gain * R_OMEGA2) == pytest.approx(1.0, abs=0.015)
        assert first / R_OMEGA2 == pytest.approx(1.0, abs=0.075)


def test_acceleration_leaves_the_other_files_unchanged(synthetic, tmp_path, monkeypatch):
    seed = gen.data_set_seed("running_in", 1)
    data = gen.write_data_set("running_in", seed, tmp_path / "a")
    quiet = gen.write_data_set("running_in", seed, tmp_path / "b", noise=False)
    assert quiet.accelerometer.gain == data.accelerometer.gain
    assert quiet.accelerometer.noise_m_s2 == 0.0
    assert quiet.load_cell.gain == data.load_cell.gain
    assert quiet.load_cell.white_N == quiet.load_cell.pink_N == quiet.load_cell.quantum_N == 0.0
    for name in ("write_acceleration_csv", "measure_acceleration", "write_force_csv",
                 "record_force", "trace_dynamics"):  # neither trace, nor their dynamics
        monkeypatch.setattr(gen, name, lambda *args: None)
    without = gen.write_data_set("running_in", seed, tmp_path / "c")
    for name in ("profiles_csv", "max_wear_csv", "believed_toml"):
        assert getattr(without, name).read_bytes() == getattr(data, name).read_bytes()
    assert without.params == data.params


def _harmonic_difference(traces, meter):
    """RMS over crank harmonics 9-20 of the difference of two traces' amplitudes (each over its
    first harmonic), and the RMS the noise floor puts there (s sqrt(2 / N) per amplitude)."""
    ratios, noise = [], []
    for revolutions, acceleration in traces:
        harmonics = _crank_harmonics(acceleration, revolutions)
        ratios.append(harmonics[9:21] / harmonics[1])
        noise.append(meter.noise_m_s2 * math.sqrt(2.0 / acceleration.size) / harmonics[1])
    return float(np.sqrt(np.mean((ratios[1] - ratios[0]) ** 2))), float(math.hypot(*noise))


def test_a_flexible_rod_shows_at_harmonics_9_to_20(tmp_path):
    """The rigid rod and a flexible one of the generator's draw, on one worn bore through one
    instrument: at crank harmonics 9-20 their traces part by far more than the noise floor's
    share there (and more than the rigid rod's own trace triggered elsewhere)."""
    config = with_truth_numerics(_believed(tmp_path))
    _, params = _truth("flexible_link")
    bore = gen.TrueBore(_SyntheticRun(config, config["wear"]["rbf"]["tail"][0]), R)
    meter = gen.Accelerometer((8000,), (4,), (30.0,), 5000.0, 1.0, 0.0, 12.0)
    traces = {}
    for name, causes, trigger in (("rigid", "none", 30.0), ("flexible", "flexible_link", 30.0),
                                  ("rigid later", "none", 200.0)):
        mechanism = gen.truth_run_config(causes, params, config)
        shifted = replace(meter, trigger_deg=(trigger,))
        traces[name] = (4, gen.measure_acceleration(bore, mechanism, shifted, 0,
                                                    np.random.default_rng(len(traces)))[1])
    rods, noise = _harmonic_difference([traces["rigid"], traces["flexible"]], meter)
    scatter, _ = _harmonic_difference([traces["rigid"], traces["rigid later"]], meter)
    print(f"harmonics 9-20 (of A1): rods {rods:.4f}, rigid scatter {scatter:.4f}, noise "
          f"{noise:.5f}")
    assert rods > 10.0 * noise and rods > 2.0 * scatter


@pytest.mark.slow
def test_data_sets_of_the_two_rods_part_at_harmonics_9_to_20(tmp_path):
    """A rigid-rod (``none``) and a flexible-rod (``flexible_link``) data set with their real
    truths (minutes: the flexible truth's run): the traces at the first profile count part at
    harmonics 9-20 by more than ten times the noise floor's share there."""
    rigid = gen.write_data_set("none", gen.data_set_seed("none", 0), tmp_path / "rigid")
    flexible = gen.write_data_set("flexible_link", gen.data_set_seed("flexible_link", 0),
                                  tmp_path / "flexible")
    traces = []
    for data in (rigid, flexible):
        meter = data.accelerometer
        acceleration = _acceleration_traces(data.acceleration_csv)[meter.trace_cycles[0]][1]
        traces.append((meter.revolutions[0], acceleration, meter))
    rods, _ = _harmonic_difference([trace[:2] for trace in traces], rigid.accelerometer)
    noise = math.hypot(*(_harmonic_difference([trace[:2]] * 2, trace[2])[1] / math.sqrt(2.0)
                         for trace in traces))
    print(f"harmonics 9-20 (of A1): rods {rods:.4f}, noise {noise:.5f}")
    assert rods > 10.0 * noise


# --- the load cell (force.csv; the dynamics are real, the wear runs synthetic) ------------------

def _crank_harmonics_of(force, revolutions):
    """Complex amplitudes of crank harmonics 0-5 of each column of ``force`` (whole
    ``revolutions``)."""
    spectrum = np.fft.rfft(force, axis=0) * 2.0 / force.shape[0]
    spectrum[0] /= 2.0
    return spectrum[: 6 * revolutions: revolutions]


def _ideal(cell, **changes):
    """``cell`` without coupling, gain errors or zeros (and with ``changes``)."""
    return replace(cell, crosstalk=0.0, gain=(1.0, 1.0), zero_N=(0.0, 0.0), **changes)


def test_force_file_parses_at_the_accelerometer_counts_and_changes_no_other_file(
        synthetic, tmp_path, monkeypatch):
    seed = gen.data_set_seed("none", 2)
    data = gen.write_data_set("none", seed, tmp_path / "a")
    cell = data.load_cell
    lines = [line for line in data.force_csv.read_text().splitlines()
             if not line.startswith("#")]
    assert lines[0] == "time_s,fx_N,fy_N,cycles"
    measured = read_joint_measurements([data.profiles_csv, data.max_wear_csv, data.force_csv])
    assert tuple(trace.cycles for trace in measured.force) == cell.trace_cycles == \
        data.accelerometer.trace_cycles
    for trace in measured.force:
        assert trace.time_s[0] == 0.0 and np.all(np.diff(trace.time_s) > 0.0)
        np.testing.assert_allclose(np.diff(trace.time_s), 1.0 / 5000.0, rtol=1e-9)
        assert trace.fx_N.size == trace.fy_N.size == 4 * 250
        assert 100.0 < np.std(trace.fx_N) < 5000.0
    assert 4e3 <= cell.natural_hz <= 6e3 and 0.005 <= abs(cell.crosstalk) <= 0.03
    monkeypatch.setattr(gen, "write_force_csv", lambda *args: None)
    monkeypatch.setattr(gen, "record_force", lambda *args: None)
    without = gen.write_data_set("none", seed, tmp_path / "b")
    assert not (tmp_path / "b" / "force.csv").exists()
    for name in ("profiles_csv", "max_wear_csv", "believed_toml", "acceleration_csv"):
        assert getattr(without, name).read_bytes() == getattr(data, name).read_bytes()


def test_load_cell_keeps_an_impulse_and_passes_slow_sinusoids():
    """A 20 us rectangular pulse's impulse is the sum of the readings over the rate (through the
    ring's resonance, the exact cell impulses and the amplifier's filter; the coupling and the
    gains act on it); a crank-frequency sinusoid passes at the gain, one at 1/8 of the rate
    (625 Hz) with at most the ring's resonance rise."""
    omega = 40.0 * math.pi
    pulse_t = np.array([0.0, 0.12, 0.12 + 1e-9, 0.12 + 20e-6, 0.12 + 20e-6 + 1e-9, 0.27])
    pulse = np.zeros((6, 2))
    pulse[2:4] = [3000.0, 4500.0]
    impulse = pulse[2] * (20e-6 + 1e-9)
    meter = gen.Accelerometer((8000,), (3,), (0.0,), 5000.0, 1.0, 0.0, 12.0)
    for seed in range(3):
        cell = replace(gen.draw_load_cell(np.random.default_rng(seed), meter, noise=False),
                       zero_N=(0.0, 0.0), start_deg=(0.0,))
        _, reading = gen.measure_force(pulse_t, pulse, 0.0, omega, cell, 0, None)
        expected = np.array(cell.gain) * (cell.coupling() @ impulse)
        np.testing.assert_allclose(reading.sum(axis=0) / cell.sample_rate_hz, expected,
                                   rtol=0.01)
    ideal = _ideal(cell, natural_hz=4e3)  # the lowest resonance: the largest rise
    time_s = np.linspace(0.0, 0.27, 54001)  # a sine linear between 5 us steps
    for frequency, low, high in ((20.0, 0.999, 1.001), (625.0, 1.0, 1.026)):
        wave = np.column_stack([np.zeros_like(time_s),
                                800.0 * np.sin(2.0 * math.pi * frequency * time_s)])
        _, reading = gen.measure_force(time_s, wave, 0.0, omega, ideal, 0, None)
        amplitude = np.abs(np.fft.rfft(reading[:, 1])).max() * 2.0 / reading.shape[0]
        assert low * 800.0 <= amplitude <= high * 800.0
        assert np.abs(reading[:, 0]).max() < 1e-6


def test_noise_free_force_trace_has_the_simulated_crank_harmonics(tmp_path):
    """The real dynamics on a worn bore through the load cell without noise: the amplitudes of
    crank harmonics 1-5 are the simulated force's (the pin on the bushing), coupled and scaled by
    the cell, to 1 % of the largest (the amplifier's filter delays them: the phases move). The
    run of 6 revolutions the load cell needs gives a 3-revolution acceleration trace exactly as
    its own run of 5 did."""
    config = with_truth_numerics(_believed(tmp_path))
    bore = gen.TrueBore(_SyntheticRun(config, config["wear"]["rbf"]["tail"][0]), R)
    history = gen.trace_dynamics(config, bore.angle_rad, bore.depth_m(8000), 4)
    meter = gen.Accelerometer((8000,), (3,), (30.0,), 5000.0, 1.0, 0.0, 12.0)
    shared, own = (gen.measure_acceleration(bore, config, meter, 0, np.random.default_rng(9),
                                            run) for run in (history, None))
    np.testing.assert_array_equal(shared[0], own[0])
    np.testing.assert_array_equal(shared[1], own[1])
    force = -history.reaction_force_N
    omega = 40.0 * math.pi
    drawn = gen.draw_load_cell(np.random.default_rng(5), meter, noise=False)
    for cell in (drawn, _ideal(drawn)):
        _, reading = gen.measure_force(history.time_s, force, float(history.crank_angle_rad[0]),
                                       omega, cell, 0, None)
        lead = 2.0 * math.pi + (math.radians(cell.start_deg[0]) - history.crank_angle_rad[0]) \
            % (2.0 * math.pi)
        fine = history.time_s[0] + lead / omega + np.arange(4 * 50000) * 1e-6
        simulated = np.column_stack([np.interp(fine, history.time_s, force[:, axis])
                                     for axis in range(2)])
        expected = np.abs(_crank_harmonics_of(simulated, 4) @ cell.coupling().T
                          * np.array(cell.gain))
        recorded = np.abs(_crank_harmonics_of(reading - np.array(cell.zero_N), 4))
        scale = expected[1:].max(axis=0)
        assert np.all(np.abs(recorded[1:] - expected[1:]) <= 0.01 * scale)
        assert scale[0] > 300.0
