"""The independent data generator's own invariants (not any diagnosis)."""

import csv
import io
import json
import math

import numpy as np
import pytest

from tests.diagnose.tribometer.independent_generator import (
    EFFECTS,
    SAMPLINGS,
    SHAPES,
    make_dataset,
    to_csv_text,
    write_csv,
)

REQUIRED = {"test_id", "sliding_distance_m", "normal_load_N", "sliding_speed_m_s"}
ALLOWED = REQUIRED | {"wear_volume_m3", "wear_rate_m3_m", "contact_pressure_Pa", "time_s",
                      "material"}
CASES = [(e, s, seed) for e in EFFECTS for s in SAMPLINGS for seed in range(4)]


def _tests(columns):
    ids = columns["test_id"]
    _, first = np.unique(ids, return_index=True)
    return [ids == ids[i] for i in sorted(first)]


@pytest.mark.parametrize("effect,sampling,seed", CASES)
def test_columns_units_and_ranges(effect, sampling, seed):
    scale = [0.01, 0.05, 0.2, 0.5][seed]
    cols, truth = make_dataset(effect, seed, scale=scale, noise=0.05, sampling=sampling)
    names = set(cols)
    assert REQUIRED <= names <= ALLOWED
    assert ("wear_volume_m3" in names) != ("wear_rate_m3_m" in names)
    n = len(cols["test_id"])
    assert all(len(c) == n for c in cols.values())
    F, v, s = cols["normal_load_N"], cols["sliding_speed_m_s"], cols["sliding_distance_m"]
    assert np.all((F >= 5) & (F <= 200)) and len(np.unique(F)) >= 2
    assert np.all((v >= 0.05) & (v <= 2)) and len(np.unique(v)) >= 2
    assert np.all((s >= 0) & (s <= 3000))
    assert truth["cause"] == effect and truth["shape"] in SHAPES[effect]
    assert all(1e-15 <= k <= 1e-13 for k in truth["k_m2_N"].values())
    V = np.array(truth["wear_volume_clean_m3"])
    assert V.shape == (n,) and V.max() <= 3e-8
    assert np.all(V[s > 0] > 1e-14)
    if "time_s" in cols:
        np.testing.assert_allclose(cols["time_s"], s / v)
    if "contact_pressure_Pa" in cols:
        p = cols["contact_pressure_Pa"]
        assert np.all((p > 1e5) & (p < 1e8))
    json.dumps(truth)
    if sampling == "doe":
        assert 16 <= n <= 40 and len(np.unique(cols["test_id"])) == n
        assert "contact_pressure_Pa" not in cols and len(np.unique(s)) >= 2
    else:
        tests = _tests(cols)
        assert 6 <= len(tests) <= 12
        for m in tests:
            st = s[m]
            assert np.all(np.diff(st) > 0) and len(np.unique(F[m])) == 1
            steps = np.diff(st) / truth["L_ref_m"]
            assert np.all((steps >= 0.008) & (steps <= 0.06))
            assert np.all(np.diff(V[m]) >= 0)  # noise-free wear never decreases


@pytest.mark.parametrize("effect", EFFECTS)
@pytest.mark.parametrize("sampling", SAMPLINGS)
def test_deterministic_for_a_seed(effect, sampling):
    a, ta = make_dataset(effect, 11, scale=0.1, noise=0.05, sampling=sampling)
    b, tb = make_dataset(effect, 11, scale=0.1, noise=0.05, sampling=sampling)
    c, _ = make_dataset(effect, 12, scale=0.1, noise=0.05, sampling=sampling)
    assert to_csv_text(a) == to_csv_text(b) and ta == tb
    assert to_csv_text(a) != to_csv_text(c)


@pytest.mark.parametrize("sampling", SAMPLINGS)
@pytest.mark.parametrize("seed", range(6))
def test_null_case_is_exact_archard_before_noise(sampling, seed):
    cols, truth = make_dataset("none", seed, scale=0.2, noise=0.0, sampling=sampling,
                               zero_offset=True)
    F, s = cols["normal_load_N"], cols["sliding_distance_m"]
    mats = cols.get("material", np.full(len(F), "unspecified"))
    k = np.array([truth["k_m2_N"][m] for m in mats])
    V = cols["wear_volume_m3"] if "wear_volume_m3" in cols else cols["wear_rate_m3_m"] * s
    np.testing.assert_allclose(V, k * F * s, rtol=1e-12, atol=0)
    np.testing.assert_allclose(truth["wear_volume_clean_m3"], k * F * s, rtol=1e-12, atol=0)
    # with noise, the clean values kept in truth are still exact Archard
    _, noisy = make_dataset("none", seed, scale=0.2, noise=0.05, sampling=sampling)
    assert noisy["wear_volume_clean_m3"] == truth["wear_volume_clean_m3"]


def test_noise_makes_dips_and_is_of_the_asked_size():
    dips = 0
    for seed in range(5):
        cols, truth = make_dataset("none", seed, scale=0.1, noise=0.10, sampling="histories",
                                   zero_offset=False)
        V, clean = cols["wear_volume_m3"], np.array(truth["wear_volume_clean_m3"])
        for m in _tests(cols):
            dips += int(np.sum(np.diff(V[m]) < 0))
        late = clean > 0.5 * clean.max()
        rel = (V[late] - clean[late]) / clean[late]
        assert 0.03 < rel.std() < 0.3
    assert dips > 10


def test_running_in_rate_falls_to_the_steady_value():
    for shape in SHAPES["running_in"]:
        cols, truth = make_dataset("running_in", 3, scale=0.05, noise=0.0,
                                   sampling="histories", shape=shape, materials=False)
        s, F = cols["sliding_distance_m"], cols["normal_load_N"]
        k = truth["k_m2_N"]["unspecified"]
        for m in _tests(cols):
            rate = np.diff(cols["wear_volume_m3"][m]) / np.diff(s[m]) / (k * F[m][0])
            assert rate[0] > 1.5 and np.all(np.diff(rate) < 0)
            assert rate[-1] == pytest.approx(1.0, abs=0.1 if shape == "power" else 1e-3)
        assert truth["params"]["s_e"] == pytest.approx(0.05 * truth["L_ref_m"])


def test_strength_effects_follow_scale():
    lo = make_dataset("mild_to_severe", 5, scale=0.01, noise=0.0, shape="step")[1]
    hi = make_dataset("mild_to_severe", 5, scale=0.5, noise=0.0, shape="step")[1]
    assert lo["params"]["ratio_severe_to_mild"] == pytest.approx(3.0)
    assert hi["params"]["ratio_severe_to_mild"] == pytest.approx(20.0)
    for shape in SHAPES["thermal"]:
        t = make_dataset("thermal", 5, scale=0.5, noise=0.0, shape=shape)[1]
        assert t["contrast_over_design"] == pytest.approx(10.0, rel=1e-9)
    a_up = make_dataset("load_exponent", 5, scale=0.5, shape="superlinear")[1]["params"]["a"]
    a_dn = make_dataset("load_exponent", 5, scale=0.01, shape="sublinear")[1]["params"]["a"]
    assert a_up == pytest.approx(2.0) and a_dn == pytest.approx(0.8)


def test_write_csv_round_trip(tmp_path):
    cols, _ = make_dataset("time_transient", 2, scale=0.1, noise=0.03, sampling="doe",
                           doe_quantity="rate")
    path = write_csv(tmp_path / "d.csv", cols)
    rows = list(csv.DictReader(io.StringIO(path.read_text())))
    assert list(rows[0]) == list(cols) and len(rows) == len(cols["test_id"])
    got = np.array([float(r["wear_rate_m3_m"]) for r in rows])
    assert np.array_equal(got, cols["wear_rate_m3_m"])
    assert all(math.isfinite(float(r["sliding_distance_m"])) for r in rows)
