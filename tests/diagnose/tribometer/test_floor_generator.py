"""The floor-calibration generator (tests/diagnose/tribometer/floor_generator.py) does what its
docstring says: exact Archard null data, noise of the asked size, determinism, the effect size by
its definition, small causes spanning their ranges, designs within bounds, a CSV round trip."""

import numpy as np
import pytest

from tests.diagnose.tribometer.floor_generator import (
    C_ADD,
    C_MULT,
    C_OFFSET,
    KINDS,
    NEUTRAL_SIZE,
    SAMPLINGS,
    SIZE_RANGES,
    make_dataset,
    write_csv,
)

SMALL = [k for k in KINDS if k != "null"]
NUMERIC = ("pressure_Pa", "velocity_m_s", "sliding_distance_m", "time_s", "normal_load_N",
           "friction_coefficient", "temperature_C", "wear_volume_m3")


def runs_of(columns):
    """Row indices of every test, in the order the tests appear."""
    ids = columns["test_id"]
    names = list(dict.fromkeys(ids.tolist()))
    return [np.flatnonzero(ids == name) for name in names]


def ls_effect_size(wear, force, distance, material):
    """The effect size's definition, written again with lstsq (one k per material)."""
    worst = 0.0
    for m in np.unique(material):
        sel = material == m
        x = (force[sel] * distance[sel])[:, None]
        k = np.linalg.lstsq(x, wear[sel], rcond=None)[0][0]
        worst = max(worst, np.max(np.abs(wear[sel] - k * x[:, 0]) / wear[sel]))
    return worst


@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_null_noise_free_is_exactly_archard_per_test(sampling):
    for seed in range(15):
        columns, truth = make_dataset("null", seed, 0.0, sampling)
        force = columns["normal_load_N"]
        s = columns["sliding_distance_m"]
        wear = columns["wear_volume_m3"]
        for t, rows in enumerate(runs_of(columns)):
            k_t = truth["k_test_m2_N"][t]
            np.testing.assert_array_equal(wear[rows], k_t * force[rows] * s[rows])
            k_read = wear[rows] / (force[rows] * s[rows])
            np.testing.assert_allclose(k_read, k_read[0], rtol=1e-14)
        np.testing.assert_allclose(columns["pressure_Pa"], force / truth["pin_area_m2"], rtol=1e-15)
        assert truth["effect_size_cause_only"] < 1e-12


@pytest.mark.parametrize("kind", KINDS)
def test_noise_zero_gives_the_noise_free_values(kind):
    columns, truth = make_dataset(kind, 7, 0.0, "histories")
    np.testing.assert_array_equal(columns["wear_volume_m3"], truth["wear_noise_free"])
    np.testing.assert_array_equal(columns["friction_coefficient"], truth["friction_noise_free"])
    if "temperature_C" in columns:
        np.testing.assert_array_equal(columns["temperature_C"], truth["temperature_noise_free"])
    assert not truth["outlier"].any()
    noisy, _ = make_dataset(kind, 7, 0.03, "histories")
    assert not np.array_equal(noisy["wear_volume_m3"], columns["wear_volume_m3"])


@pytest.mark.parametrize("sampling", SAMPLINGS)
@pytest.mark.parametrize("noise", [0.01, 0.03, 0.10])
def test_noise_has_the_asked_size(noise, sampling):
    z, final_rel, mu_rel, n_out, n = [], [], [], 0, 0
    for seed in range(60):
        columns, truth = make_dataset(KINDS[seed % len(KINDS)], seed, noise, sampling)
        wear, final = truth["wear_noise_free"], truth["final_wear_noise_free"]
        error = columns["wear_volume_m3"] - wear
        good = ~truth["outlier"]
        sd = noise * np.sqrt((C_MULT * wear) ** 2 + (C_ADD**2 + C_OFFSET**2) * final**2)
        z.append((error / sd)[good])
        last = np.array([rows[-1] for rows in runs_of(columns)])
        final_rel.append((error / wear)[last][good[last]])
        mu_rel.append(columns["friction_coefficient"] / truth["friction_noise_free"] - 1.0)
        n_out += truth["outlier"].sum()
        n += wear.size
    z = np.concatenate(z)
    assert 0.95 < np.std(z) < 1.05
    assert abs(np.mean(z)) < 0.05
    # a test's last reading: relative sd = noise (the parts' squares sum to 1)
    final_rel = np.concatenate(final_rel)
    assert 0.9 * noise < np.std(final_rel) < 1.1 * noise
    mu_rel = np.concatenate(mu_rel)
    assert 0.85 * noise < np.std(mu_rel) < 1.15 * noise
    assert 0.005 < n_out / n < 0.04


def test_wear_is_quantised_to_the_balance_resolution():
    columns, truth = make_dataset("null", 3, 0.03, "histories")
    rho = np.array([truth["density_kg_m3"][m] for m in truth["material_per_row"]])
    steps = columns["wear_volume_m3"] * rho / truth["balance_resolution_kg"]
    np.testing.assert_allclose(steps, np.round(steps), atol=1e-6)
    smallest_mass = np.min(rho * truth["final_wear_noise_free"])
    assert truth["balance_resolution_kg"] <= 0.3 * 0.03 * smallest_mass


@pytest.mark.parametrize("kind", KINDS)
def test_deterministic_for_a_seed(kind):
    for sampling in SAMPLINGS:
        a, ta = make_dataset(kind, 11, 0.03, sampling)
        b, tb = make_dataset(kind, 11, 0.03, sampling)
        assert a.keys() == b.keys()
        for name in a:
            np.testing.assert_array_equal(a[name], b[name])
        assert ta["effect_size"] == tb["effect_size"]
        assert ta["cause_size"] == tb["cause_size"]
        c, _ = make_dataset(kind, 12, 0.03, sampling)
        assert not np.array_equal(a["wear_volume_m3"][:3], c["wear_volume_m3"][:3])


@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_null_effect_size_is_the_test_to_test_scatter(sampling):
    for seed in range(15):
        columns, truth = make_dataset("null", seed, 0.0, sampling)
        force = columns["normal_load_N"]
        s = columns["sliding_distance_m"]
        wear = columns["wear_volume_m3"]
        material = truth["material_per_row"]
        assert truth["effect_size"] == pytest.approx(
            ls_effect_size(wear, force, s, material), rel=1e-9)
        assert truth["effect_size"] == truth["effect_size_scatter_only"]
        # the relative difference of a test is |1 - k_m / k_t|: only the k scatter
        k_t = truth["k_test_m2_N"]
        worst = 0.0
        for rows, kt in zip(runs_of(columns), k_t):
            m = material[rows[0]]
            sel = material == m
            x = force[sel] * s[sel]
            k_m = wear[sel] @ x / (x @ x)
            worst = max(worst, abs(1.0 - k_m / kt))
        assert truth["effect_size"] == pytest.approx(worst, rel=1e-9)
        assert truth["effect_size"] > 0.3 * truth["k_scatter_sd"]
        _, flat = make_dataset("null", seed, 0.0, sampling, scatter=0.0)
        assert flat["effect_size"] < 1e-12


@pytest.mark.parametrize("kind", SMALL)
def test_small_effect_size_follows_its_definition(kind):
    for seed in range(6):
        for sampling in SAMPLINGS:
            columns, truth = make_dataset(kind, seed, 0.1, sampling)
            args = (truth["wear_noise_free"], columns["normal_load_N"],
                    columns["sliding_distance_m"], truth["material_per_row"])
            assert truth["effect_size"] == pytest.approx(ls_effect_size(*args), rel=1e-9)
            _, flat = make_dataset(kind, seed, 0.0, sampling, scatter=0.0)
            assert flat["effect_size"] == pytest.approx(truth["effect_size_cause_only"], rel=1e-9)


@pytest.mark.parametrize("kind", SMALL)
def test_neutral_size_gives_the_null_data_of_the_seed(kind):
    for sampling in SAMPLINGS:
        null, _ = make_dataset("null", 5, 0.03, sampling)
        neutral, truth = make_dataset(kind, 5, 0.03, sampling, size=NEUTRAL_SIZE[kind])
        np.testing.assert_allclose(neutral["wear_volume_m3"], null["wear_volume_m3"], rtol=1e-12)
        assert truth["effect_size_cause_only"] < 1e-12


@pytest.mark.parametrize("kind", SMALL)
def test_small_sizes_span_their_ranges(kind):
    lo, hi = SIZE_RANGES[kind]
    sizes, effects, forms = [], [], set()
    for seed in range(80):
        sampling = SAMPLINGS[seed % 2]
        _, truth = make_dataset(kind, seed, 0.03, sampling)
        sizes.append(truth["cause_size"])
        effects.append(truth["effect_size_cause_only"])
        forms.add(truth["form"])
        assert truth["cause"] == kind.removeprefix("small_")
    sizes = np.array(sizes)
    assert np.all((sizes >= lo) & (sizes <= hi))
    if kind == "small_load_exponent":
        assert sizes.min() < 0.85 and sizes.max() > 1.18
        assert np.any(np.abs(sizes - 1.0) < 0.02)
    else:
        width = hi - lo
        assert sizes.min() < lo + 0.05 * width and sizes.max() > hi - 0.25 * width
    effects = np.array(effects)
    # from below what a 3 % noise can resolve to well above it
    assert effects.min() < 0.02 and effects.max() > 0.15
    assert np.all(effects > 0)
    assert len(forms) == 2


def test_null_scatter_and_materials_vary_over_seeds():
    sd, n_mat = [], []
    for seed in range(40):
        _, truth = make_dataset("null", seed, 0.03)
        sd.append(truth["k_scatter_sd"])
        n_mat.append(len(truth["k_material_m2_N"]))
        assert truth["cause"] == "none"
    assert min(sd) < 0.04 and max(sd) > 0.13 and max(sd) <= 0.15
    assert 1 in n_mat and 2 in n_mat


@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_designs_and_readings(sampling):
    for seed in range(30):
        columns, truth = make_dataset(KINDS[seed % len(KINDS)], seed, 0.1, sampling)
        s = columns["sliding_distance_m"]
        t = columns["time_s"]
        runs = runs_of(columns)
        # each test's rows are contiguous, in increasing distance and time
        assert sum(r.size for r in runs) == s.size
        for rows in runs:
            assert np.all(np.diff(rows) == 1)
            assert np.all(np.diff(s[rows]) > 0) and np.all(np.diff(t[rows]) > 0)
            for name in ("pressure_Pa", "velocity_m_s", "normal_load_N"):
                assert np.all(columns[name][rows] == columns[name][rows[0]])
            if "material" in columns:
                assert np.all(columns["material"][rows] == columns["material"][rows[0]])
        counts = np.array([r.size for r in runs])
        if sampling == "histories":
            assert counts.min() >= 5 and counts.max() <= 12
            lengths = np.array([s[r[-1]] for r in runs])
            assert np.unique(lengths).size > 1
        else:
            assert np.all(counts == 1)
            assert np.unique(s).size > s.size // 2
            cells = set(zip(columns["normal_load_N"], columns["velocity_m_s"]))
            n_loads = np.unique(columns["normal_load_N"]).size
            n_speeds = np.unique(columns["velocity_m_s"]).size
            assert 3 <= n_loads <= 5 and 2 <= n_speeds <= 4
            assert len(cells) == n_loads * n_speeds
            assert len(runs) > len(cells) * len(truth["k_material_m2_N"])  # repeats
        assert np.all((columns["normal_load_N"] >= 5) & (columns["normal_load_N"] <= 200))
        assert np.all((columns["velocity_m_s"] >= 0.05) & (columns["velocity_m_s"] <= 2))
        assert np.all((s > 0) & (s <= 5000)) and s.max() >= 100
        np.testing.assert_allclose(t, s / columns["velocity_m_s"], rtol=1e-15)
        mu = truth["friction_noise_free"]
        assert np.all((mu >= 0.1) & (mu <= 0.6))
        temp = truth["temperature_noise_free"]
        power = mu * columns["pressure_Pa"] * columns["velocity_m_s"]
        steady = np.concatenate([np.full(r.size, x) for r, x in zip(runs, truth["steady_rise_K"])])
        np.testing.assert_allclose(steady / steady.max(), power / power.max(), rtol=1e-12)
        assert np.all(temp >= truth["ambient_C"])


def test_thermal_always_writes_a_rising_temperature():
    for seed in range(10):
        columns, truth = make_dataset("small_thermal", seed, 0.0)
        assert "temperature_C" in columns
        temp = columns["temperature_C"]
        for rows in runs_of(columns):
            assert np.all(np.diff(temp[rows]) >= 0) and temp[rows[-1]] > temp[rows[0]]


@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_csv_round_trip(tmp_path, sampling):
    for seed, kind in enumerate(KINDS):
        columns, _ = make_dataset(kind, seed, 0.03, sampling)
        path = write_csv(tmp_path / f"{kind}.csv", columns)
        table = np.genfromtxt(path, delimiter=",", names=True, dtype=None, encoding="utf-8")
        assert list(table.dtype.names) == [n for n in (
            "test_id", "material", *NUMERIC) if n in columns]
        assert table.size == columns["test_id"].size
        for name in columns:
            if name in NUMERIC:
                np.testing.assert_array_equal(table[name].astype(float), columns[name])
            else:
                assert table[name].tolist() == columns[name].tolist()


def test_bad_arguments_are_refused():
    with pytest.raises(ValueError):
        make_dataset("small_time_transient", 0, 0.03)
    with pytest.raises(ValueError):
        make_dataset("null", 0, 0.03, "random")
    with pytest.raises(ValueError):
        make_dataset("null", 0, -0.01)
