"""The third joint-wear generator's own invariants (not the diagnosis), against facts found
independently of it: closed-form geometry of a ball on a slot, Hertz's line contact, the integral
of the running-in multiplier, and the believed model's own forward run.

That a hidden effect exceeds the noise is checked by default for running-in (a longer run of the
believed model); the slow variant (`make slow`) checks the causes whose truth is a forward run of
its own: wear coefficient, friction, flexible link, impact wear (20-60 s each)."""

import math

import numpy as np
import pytest

from fewear.diagnose.joint.forward import model_config, simulate_wear
from fewear.diagnose.joint.measured import read_joint_measurements
from tests.calibrate import third_joint_generator as gen
from tests.calibrate.truth_numerics import with_truth_numerics

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
