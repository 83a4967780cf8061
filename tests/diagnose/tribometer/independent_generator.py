"""Independent synthetic pin-on-disc data with a hidden wear effect (validation data).

Written without reference to the diagnosis code: its own functional forms, scales and noise.
Numpy only. The data (a dict of column arrays, the tool's CSV schema) and the answer (``truth``)
are returned apart; ``write_csv`` writes the data only.

    columns, truth = make_dataset("running_in", seed=3, scale=0.1, noise=0.03,
                                  sampling="histories")
    write_csv("run.csv", columns)

Effects (``truth["cause"]``) and what ``scale`` means for each, with k a level per material:

* ``none``: plain Archard, V = k F s. ``scale`` is not used.
* ``running_in``: wear rate per metre dV/ds = k F [1 + (R - 1) h(s / s0)], initial/steady ratio
  R in 3-15, shape ``exponential`` h(x) = exp(-x) or ``power`` h(x) = (1 + x)^(-m), m in 1.2-3.
  ``scale`` = s_e / L_ref: s_e is the distance over which the excess rate falls to 1/e
  (s0 = s_e for exponential, s0 = s_e / (e^(1/m) - 1) for power), L_ref the longest test distance.
* ``time_transient``: the same decay driven by time in contact t = s / v (constant speed):
  dV/ds = k F [1 + (R - 1) h(t / t0)]. ``scale`` = t_e / T_ref, T_ref the median test duration.
* ``thermal``: k_eff = k0 g(q), q = p v or mu p v (frictional power density, W/m^2; p = F / A with
  one nominal pin area A per data set, so F v orders the tests the same way when p is absent).
  Shape ``arrhenius``: flash rise theta = theta_max q / q_max (in units of ambient absolute
  temperature), g = exp(E theta / (1 + theta)); shape ``sigmoid``: g = 1 + (G - 1) logistic(
  (ln q - ln q_c) / w), broad (w 12-20 % of the design's ln q range).
  ``scale`` sets the contrast C = g(q_max) / g(q_min) over the design: C = 1.2 (10 / 1.2)^u.
* ``load_exponent``: V = k F_ref (F / F_ref)^a s, F_ref the geometric mean design load,
  a in 1.3-2 (``superlinear``) or 0.8-0.5 (``sublinear``): |a - 1| = lo + u (hi - lo).
* ``mild_to_severe``: k_eff = k_mild [1 + (R - 1) H(x)], x = load or p v, R = 3 (20 / 3)^u,
  H a ``step`` at x_c or a ``sigmoid`` logistic((ln x - ln x_c) / w), w 5-15 % of the ln x range;
  x_c lies between two design values near the middle of the range.

For the three strength effects u = clip((scale - 0.01) / 0.49, 0, 1): the position of ``scale``
in the sweep range 0.01-0.5 maps to the weak-to-strong end of each effect's band.

Noise (instrument on the *cumulative* readings; noise = 0 gives the noise-free values exactly):
history reading V_meas = V (1 + noise e1) + 0.25 noise V_end e2 + offset, with e ~ N(0, 1),
V_end the test's final noise-free volume and offset (if ``zero_offset``) a per-test constant
N(0, (0.3 noise V_end)^2). Dips below the previous reading are kept. DOE rows carry one reading:
V (1 + noise e1) + 0.25 noise V e2 (+ 0.3 noise V e3 if offset); wear_rate_m3_m = V_meas / s.
"""

from __future__ import annotations

import csv
import io
import math
import sys
from pathlib import Path

import numpy as np

EFFECTS = ("none", "running_in", "time_transient", "thermal", "load_exponent", "mild_to_severe")
SHAPES = {
    "none": ("archard",),
    "running_in": ("exponential", "power"),
    "time_transient": ("exponential", "power"),
    "thermal": ("arrhenius", "sigmoid"),
    "load_exponent": ("superlinear", "sublinear"),
    "mild_to_severe": ("step", "sigmoid"),
}
SAMPLINGS = ("histories", "doe")
MATERIAL_NAMES = ("brass", "bronze", "steel", "aluminium", "cast_iron", "PTFE")
K_MIN, K_MAX = 1e-15, 1e-13


# ------------------------------------------------------------------------------------ helpers
def _loguniform(rng, lo, hi):
    return float(math.exp(rng.uniform(math.log(lo), math.log(hi))))


def _nice(x):
    """Round to 1, 2, 2.5 or 5 times a power of ten (set-points and reading intervals)."""
    e = math.floor(math.log10(x))
    m = x / 10**e
    best = min((1.0, 2.0, 2.5, 5.0, 10.0), key=lambda c: abs(math.log(m / c)))
    return best * 10**e


def _round_sig(x, sig=2):
    return float(f"{x:.{sig}g}")


def _logistic(z):
    return 1.0 / (1.0 + np.exp(-np.asarray(z, dtype=float)))


def _strength(scale):
    return float(np.clip((scale - 0.01) / 0.49, 0.0, 1.0))


def _h_integral(x, shape, m):
    """Integral of the decay h from 0 to x (h(0) = 1)."""
    x = np.asarray(x, dtype=float)
    if shape == "exponential":
        return -np.expm1(-x)
    return (1.0 - (1.0 + x) ** (1.0 - m)) / (m - 1.0)


def _log_levels(rng, lo, hi, n, min_ratio, sig=2):
    """n distinct rounded levels, log-spread, spanning at least min_ratio."""
    a = _loguniform(rng, lo, hi / min_ratio)
    b = _loguniform(rng, a * min_ratio, hi)
    levels = sorted({_round_sig(v, sig) for v in np.geomspace(a, b, n)})
    return [float(v) for v in levels]


# ------------------------------------------------------------------------------------ designs
def _design_histories(rng):
    n_tests = int(rng.integers(6, 13))
    loads = _log_levels(rng, 5.0, 200.0, int(rng.integers(3, 6)), 4.0)
    speeds = _log_levels(rng, 0.05, 2.0, int(rng.integers(2, 5)), 4.0)
    combos = [(f, v) for f in loads for v in speeds]
    for _ in range(500):  # a random subset of the grid that uses every level
        if n_tests <= len(combos):
            pick = rng.choice(len(combos), size=n_tests, replace=False)
        else:
            pick = np.concatenate([rng.permutation(len(combos)),
                                   rng.choice(len(combos), n_tests - len(combos))])
        chosen = [combos[i] for i in pick]
        if {c[0] for c in chosen} == set(loads) and {c[1] for c in chosen} == set(speeds):
            break
    L_ref = float(round(_loguniform(rng, 800.0, 3000.0), -2))
    if rng.random() < 0.5:
        lengths = [L_ref] * n_tests
    else:
        lengths = [L_ref * float(rng.choice([0.5, 0.75, 1.0])) for _ in range(n_tests)]
        lengths[int(rng.integers(n_tests))] = L_ref
    step = _nice(rng.uniform(0.01, 0.05) * L_ref)
    return dict(n_tests=n_tests, loads=[c[0] for c in chosen], speeds=[c[1] for c in chosen],
                lengths=lengths, L_ref=L_ref, step=step, with_zero=bool(rng.random() < 0.5))


def _design_doe(rng):
    n_rows = int(rng.integers(16, 41))
    loads = _log_levels(rng, 5.0, 200.0, int(rng.integers(2, 5)), 4.0)
    speeds = _log_levels(rng, 0.05, 2.0, int(rng.integers(2, 4)), 4.0)
    L_ref = float(round(_loguniform(rng, 800.0, 3000.0), -2))
    fractions = [(0.25, 0.5, 1.0), (0.2, 0.5, 1.0), (1 / 3, 1.0), (0.1, 0.3, 1.0)]
    dists = [float(round(L_ref * f, -1)) for f in fractions[int(rng.integers(len(fractions)))]]
    grid = [(f, v, s) for f in loads for v in speeds for s in dists]
    for _ in range(500):
        if n_rows <= len(grid):
            pick = rng.choice(len(grid), size=n_rows, replace=False)
        else:  # full factorial plus replicates
            pick = np.concatenate([np.arange(len(grid)),
                                   rng.choice(len(grid), n_rows - len(grid))])
        rows = [grid[i] for i in rng.permutation(pick)]
        if all({r[j] for r in rows} == set(lv) for j, lv in enumerate((loads, speeds, dists))):
            break
    return dict(n_tests=n_rows, loads=[r[0] for r in rows], speeds=[r[1] for r in rows],
                lengths=[r[2] for r in rows], L_ref=max(dists))


# ------------------------------------------------------------------------------------ effects
def _effect_params(effect, shape, scale, rng, F, v, q):
    """Hidden-effect parameters; F, v, q are the per-test load, speed and power-density drivers."""
    p = {}
    u = _strength(scale)
    if effect in ("running_in", "time_transient"):
        p["ratio_initial_to_steady"] = float(rng.uniform(3.0, 15.0))
        p["m"] = float(rng.uniform(1.2, 3.0)) if shape == "power" else None
    elif effect == "thermal":
        contrast = 1.2 * (10.0 / 1.2) ** u
        p["contrast"] = contrast
        qmin, qmax = float(q.min()), float(q.max())
        if shape == "arrhenius":
            th_max = float(rng.uniform(0.15, 0.8))
            th_min = th_max * qmin / qmax
            p["theta_max"] = th_max
            p["E"] = math.log(contrast) / (th_max / (1 + th_max) - th_min / (1 + th_min))
        else:
            lr = math.log(qmax / qmin)
            q_c = math.exp(math.log(qmin) + rng.uniform(0.4, 0.6) * lr)
            frac = float(rng.uniform(0.12, 0.2))
            while True:
                w = frac * lr
                smin = float(_logistic((math.log(qmin) - math.log(q_c)) / w))
                smax = float(_logistic((math.log(qmax) - math.log(q_c)) / w))
                if smax - contrast * smin > 0.05:
                    break
                frac *= 0.85
            p.update(q_c=q_c, w=w, plateau=1.0 + (contrast - 1.0) / (smax - contrast * smin))
    elif effect == "load_exponent":
        if shape == "superlinear":
            p["a"] = 1.0 + 0.3 + u * (1.0 - 0.3)
        else:
            p["a"] = 1.0 - (0.2 + u * (0.5 - 0.2))
        p["F_ref"] = float(np.exp(np.mean(np.log(F))))
    elif effect == "mild_to_severe":
        p["ratio_severe_to_mild"] = 3.0 * (20.0 / 3.0) ** u
        x = F if p.setdefault("driver", ["load", "pv"][int(rng.integers(2))]) == "load" else q
        vals = np.unique(x)
        lo = max(0, len(vals) // 2 - 1)
        i = int(rng.integers(lo, min(lo + 2, len(vals) - 1)))
        p["threshold"] = float(math.sqrt(vals[i] * vals[i + 1]))
        w = float(rng.uniform(0.05, 0.15) * math.log(vals[-1] / vals[0]))
        p["w"] = w if shape == "sigmoid" else None
    return p


def _multiplier(effect, shape, p, F, q):
    """Per-test factor on the wear coefficient (steady-state for the transients)."""
    if effect == "thermal":
        if shape == "arrhenius":
            th = p["theta_max"] * q / q.max()
            return np.exp(p["E"] * th / (1 + th))
        return 1 + (p["plateau"] - 1) * _logistic((np.log(q) - math.log(p["q_c"])) / p["w"])
    if effect == "load_exponent":
        return (F / p["F_ref"]) ** (p["a"] - 1.0)
    if effect == "mild_to_severe":
        x = F if p["driver"] == "load" else q
        if shape == "step":
            H = (x > p["threshold"]).astype(float)
        else:
            H = _logistic((np.log(x) - math.log(p["threshold"])) / p["w"])
        return 1 + (p["ratio_severe_to_mild"] - 1) * H
    return np.ones_like(F)


def _clean_volume(effect, shape, p, s, F, v, k, g):
    """Noise-free cumulative volume at distances s for one test (or row-wise arrays)."""
    if effect == "running_in":
        R, s0 = p["ratio_initial_to_steady"], p["s0"]
        return k * F * (s + (R - 1) * s0 * _h_integral(s / s0, shape, p["m"]))
    if effect == "time_transient":
        R, t0 = p["ratio_initial_to_steady"], p["t0"]
        return k * F * (s + (R - 1) * v * t0 * _h_integral(s / (v * t0), shape, p["m"]))
    if effect == "load_exponent":
        return k * p["F_ref"] * (F / p["F_ref"]) ** p["a"] * s
    return k * g * F * s


# ------------------------------------------------------------------------------------ main API
def make_dataset(effect: str, seed: int, scale: float = 0.1, noise: float = 0.03,
                 sampling: str = "histories", shape: str | None = None,
                 zero_offset: bool | None = None, materials: bool | None = None,
                 doe_quantity: str | None = None) -> tuple[dict, dict]:
    """Synthetic tribometer data with one hidden effect.

    Returns ``(columns, truth)``: ``columns`` maps CSV header names to equal-length numpy arrays
    (text columns as str arrays); ``truth`` is a JSON-serialisable dict with the cause, shape,
    parameters, k per material and the noise-free volumes. Options left ``None`` are drawn from
    the seed. ``doe_quantity`` is "volume" or "rate" (DOE only).
    """
    if effect not in EFFECTS:
        raise ValueError(f"effect must be one of {EFFECTS}, not {effect!r}")
    if sampling not in SAMPLINGS:
        raise ValueError(f"sampling must be one of {SAMPLINGS}, not {sampling!r}")
    rng = np.random.default_rng(seed)
    # the random choices are drawn even when given, so options do not shift the stream
    shapes = SHAPES[effect]
    drawn = (shapes[int(rng.integers(len(shapes)))], bool(rng.random() < 0.5),
             bool(rng.random() < 0.5), ["volume", "rate"][int(rng.integers(2))])
    shape = drawn[0] if shape is None else shape
    zero_offset = drawn[1] if zero_offset is None else bool(zero_offset)
    materials = drawn[2] if materials is None else bool(materials)
    doe_quantity = drawn[3] if doe_quantity is None else doe_quantity
    if shape not in shapes:
        raise ValueError(f"shape for {effect} must be one of {shapes}, not {shape!r}")

    d = _design_histories(rng) if sampling == "histories" else _design_doe(rng)
    n = d["n_tests"]
    F = np.array(d["loads"], dtype=float)
    v = np.array(d["speeds"], dtype=float)
    L = np.array(d["lengths"], dtype=float)

    # materials: a k level (and a friction coefficient) each
    if materials:
        n_mat = int(rng.integers(2, 4))
        names = [str(x) for x in rng.choice(MATERIAL_NAMES, size=n_mat, replace=False)]
        mat_idx = rng.permutation(np.arange(n) % n_mat)
    else:
        n_mat, names, mat_idx = 1, ["unspecified"], np.zeros(n, dtype=int)
    k_ratio = np.array([1.0] + [_loguniform(rng, 1 / 3, 3.0) for _ in range(n_mat - 1)])
    mu_mat = np.array([float(rng.uniform(0.15, 0.8)) for _ in range(n_mat)])

    # contact: one nominal pin area per data set
    pin_d = float(rng.choice([3e-3, 4e-3, 5e-3, 6e-3]))
    area = math.pi * pin_d**2 / 4
    pressure = F / area
    thermal_driver = ["pv", "mu_pv"][int(rng.integers(2))]
    q = pressure * v * (mu_mat[mat_idx] if thermal_driver == "mu_pv" else 1.0)

    p = _effect_params(effect, shape, scale, rng, F, v, q)
    if effect == "running_in":
        s_e = scale * d["L_ref"]
        p["s_e"] = s_e
        p["s0"] = s_e if shape == "exponential" else s_e / math.expm1(1.0 / p["m"])
    if effect == "time_transient":
        T_ref = float(np.median(L / v))
        t_e = scale * T_ref
        p.update(T_ref=T_ref, t_e=t_e)
        p["t0"] = t_e if shape == "exponential" else t_e / math.expm1(1.0 / p["m"])
    if effect == "thermal":
        p["driver"] = thermal_driver
    g = _multiplier(effect, shape, p, F, q)

    # k level: aim the largest final volume at 5e-10..8e-9 m^3, keep k in 1e-15..1e-13 m^2/N
    unit_end = _clean_volume(effect, shape, p, L, F, v, k_ratio[mat_idx], g)
    k_base = float(np.clip(_loguniform(rng, 5e-10, 8e-9) / unit_end.max(), K_MIN, K_MAX))
    k_mat = np.clip(k_base * k_ratio, K_MIN, K_MAX)
    k = k_mat[mat_idx]

    if sampling == "histories":
        cols, clean = _histories(rng, d, effect, shape, p, F, v, k, g, noise, zero_offset)
        row_test = cols.pop("_row_test")
    else:
        cols, clean = _doe(rng, d, effect, shape, p, F, v, k, g, noise, zero_offset,
                           doe_quantity)
        row_test = np.arange(n)

    # assemble columns in the tool's schema
    if rng.random() < 0.5:
        ids = np.array([f"T{i + 1:02d}" for i in range(n)])
    else:
        ids = np.arange(1, n + 1)
    include_pressure = sampling == "histories" and bool(rng.random() < 0.5)
    include_time = bool(rng.random() < 0.5)
    out = {"test_id": ids[row_test]}
    if materials:
        out["material"] = np.array(names)[mat_idx[row_test]]
    out["normal_load_N"] = F[row_test]
    if include_pressure:
        out["contact_pressure_Pa"] = pressure[row_test]
    out["sliding_speed_m_s"] = v[row_test]
    if include_time:
        out["time_s"] = cols["sliding_distance_m"] / v[row_test]
    out.update(cols)

    truth = {
        "cause": effect,
        "shape": shape,
        "scale": float(scale),
        "strength_u": _strength(scale),
        "sampling": sampling,
        "noise": float(noise),
        "zero_offset": bool(zero_offset),
        "params": {key: (None if val is None else (val if isinstance(val, str) else float(val)))
                   for key, val in p.items()},
        "k_m2_N": {names[i]: float(k_mat[i]) for i in range(n_mat)},
        "mu": {names[i]: float(mu_mat[i]) for i in range(n_mat)},
        "pin_area_m2": area,
        "L_ref_m": float(d["L_ref"]),
        "effect_multiplier_per_test": [float(x) for x in g],
        "contrast_over_design": float(g.max() / g.min()),
        "quantity": "wear_rate_m3_m" if "wear_rate_m3_m" in out else "wear_volume_m3",
        "wear_volume_clean_m3": [float(x) for x in clean],
        "meaning_of_scale": _SCALE_MEANING[effect],
    }
    return out, truth


_SCALE_MEANING = {
    "none": "unused",
    "running_in": "s_e / L_ref: distance for the excess wear rate to fall to 1/e, over the "
                  "longest test distance",
    "time_transient": "t_e / T_ref: contact time for the excess wear rate to fall to 1/e, over "
                      "the median test duration",
    "thermal": "u = clip((scale-0.01)/0.49): contrast g(q_max)/g(q_min) = 1.2*(10/1.2)**u",
    "load_exponent": "u = clip((scale-0.01)/0.49): |a-1| = 0.3+0.7u (superlinear) or "
                     "0.2+0.3u (sublinear)",
    "mild_to_severe": "u = clip((scale-0.01)/0.49): severe/mild ratio R = 3*(20/3)**u",
}


def _histories(rng, d, effect, shape, p, F, v, k, g, noise, zero_offset):
    step = d["step"]
    rows_s, rows_test, clean, meas = [], [], [], []
    for i in range(d["n_tests"]):
        n_read = int(math.floor(d["lengths"][i] / step + 1e-9))
        s = step * np.arange(0 if d["with_zero"] else 1, n_read + 1)
        V = _clean_volume(effect, shape, p, s, F[i], v[i], k[i], g[i])
        V_end = float(_clean_volume(effect, shape, p, d["lengths"][i], F[i], v[i], k[i], g[i]))
        e1, e2 = rng.standard_normal(s.size), rng.standard_normal(s.size)
        e3 = float(rng.standard_normal())
        offset = 0.3 * noise * V_end * e3 if zero_offset else 0.0
        Vm = V * (1 + noise * e1) + 0.25 * noise * V_end * e2 + offset if noise else V.copy()
        rows_s.append(s)
        rows_test.append(np.full(s.size, i))
        clean.append(V)
        meas.append(Vm)
    cols = {"sliding_distance_m": np.concatenate(rows_s),
            "wear_volume_m3": np.concatenate(meas),
            "_row_test": np.concatenate(rows_test)}
    return cols, np.concatenate(clean)


def _doe(rng, d, effect, shape, p, F, v, k, g, noise, zero_offset, quantity):
    s = np.array(d["lengths"], dtype=float)
    V = _clean_volume(effect, shape, p, s, F, v, k, g)
    n = s.size
    e1, e2, e3 = (rng.standard_normal(n) for _ in range(3))
    Vm = V * (1 + noise * e1 + 0.25 * noise * e2 + (0.3 * noise * e3 if zero_offset else 0.0))
    if not noise:
        Vm = V.copy()
    cols = {"sliding_distance_m": s}
    if quantity == "rate":
        cols["wear_rate_m3_m"] = Vm / s
    elif quantity == "volume":
        cols["wear_volume_m3"] = Vm
    else:
        raise ValueError(f"doe_quantity must be 'volume' or 'rate', not {quantity!r}")
    return cols, V


# ------------------------------------------------------------------------------------ output
def to_csv_text(columns: dict) -> str:
    """CSV text (header row, floats at full precision) of a column dict."""
    names = list(columns)
    n = len(columns[names[0]])
    buf = io.StringIO()
    w = csv.writer(buf, lineterminator="\n")
    w.writerow(names)
    for r in range(n):
        row = []
        for name in names:
            x = columns[name][r]
            if isinstance(x, (float, np.floating)):
                row.append(repr(float(x)))
            elif isinstance(x, (int, np.integer)):
                row.append(str(int(x)))
            else:
                row.append(str(x))
        w.writerow(row)
    return buf.getvalue()


def write_csv(path, columns: dict) -> Path:
    """Write a column dict as CSV (the data only; keep the truth elsewhere)."""
    path = Path(path)
    path.write_text(to_csv_text(columns))
    return path


if __name__ == "__main__":
    import json

    if len(sys.argv) < 2:
        sys.exit("usage: independent_generator.py OUTDIR [seed]")
    outdir = Path(sys.argv[1])
    seed0 = int(sys.argv[2]) if len(sys.argv) > 2 else 0
    outdir.mkdir(parents=True, exist_ok=True)
    for j, eff in enumerate(EFFECTS):
        for sampling in SAMPLINGS:
            cols, truth = make_dataset(eff, seed=seed0 + j, scale=0.1, noise=0.03,
                                       sampling=sampling)
            stem = f"{eff}_{sampling}"
            write_csv(outdir / f"{stem}.csv", cols)
            (outdir / f"{stem}.truth.json").write_text(json.dumps(truth, indent=1))
            print(outdir / f"{stem}.csv", truth["shape"])
