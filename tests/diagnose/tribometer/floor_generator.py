"""Pin-on-disc wear data with no cause or a SMALL cause, for calibrating the diagnosis' floor.

Written from a brief only (numpy; nothing imported from ``fewear``), without reading the
diagnosis or the project's other generators: these data are independent of how the tool was
built and tuned. ``make_dataset(kind, seed, noise, sampling)`` returns ``(columns, truth)``;
``write_csv(path, columns)`` writes the CSV ``fewear diagnose`` reads (one row per cumulative
reading; SI units).

Kinds
-----
``null``
    Plain Archard: V = k_t F s exactly before noise, k_t = k_material * exp(sigma z_t), one draw
    z_t ~ N(0, 1) per test; the test-to-test scatter sigma is uniform in [0.02, 0.15] per seed.
    40 % of the seeds have two materials whose k differ by a factor 1.5-5.
``small_running_in`` (same k_t scatter; so for every small kind)
    V = k_t F (s + X(s)), an excess sliding distance X of one of two forms per seed:
    ``hyperbolic``, excess rate A/(1 + s/s0)^2 so X = A s0 s/(s + s0); ``stretched``,
    X = B (1 - exp(-sqrt(s/s0))). s0 is 2-30 % of the median test length L_med; A or B are set so
    that X(L_med)/L_med = r, the excess wear of the median-length test as a fraction of its steady
    wear; r log-uniform in [0.01, 0.30].
``small_load_exponent``
    ``power``: V = k_t F_ref (F/F_ref)^a s; ``loglinear``: V = k_t F s (1 + (a - 1) ln(F/F_ref));
    F_ref the geometric mean of the tests' loads; |a - 1| log-uniform in [0.005, 0.25] above 1
    or [0.005, 0.20] below 1 (a in 1.005-1.25 or 0.80-0.995).
``small_mild_to_severe``
    k_t times a factor m: ``load_step``, m = R above a load threshold between two adjacent design
    loads, 1 below; ``pv_ramp``, m rising linearly from 1 to R as the nominal p v goes from pv1 to
    pv2 (two quantiles of the design's p v), flat outside. R - 1 log-uniform in [0.01, 0.5].
``small_thermal``
    The contact heats: T(t) = T_amb + dT_t (1 - exp(-t/tau)), dT_t = beta mu_t p v (steady rise
    proportional to the frictional power per area, the hottest test 25-120 K above ambient, tau
    120-900 s, t = s/v), and k follows T: ``linear``, k = k_t (1 + g (T - T_amb)); ``hinge``,
    k = k_t (1 + g max(0, T - T_c)), T_c at 20-60 % of the largest rise any test reaches. Wear is
    the exact integral of k F ds. The contrast C, the ratio of the largest to the smallest
    test-mean k factor (V_end / (k_t F L) over the design's tests, heating transient included),
    has C - 1 log-uniform in [0.01, 0.5]; g follows from C. The temperature column is always
    written for this kind (and for half of the seeds of the other kinds, where the contact heats
    the same way but k ignores it).

``size=`` overrides the drawn size (r, a, R or C) and ``scatter=`` the sigma of k; the neutral
size (0, 1, 1, 1) gives the null data of the same seed (to rounding).

Designs (drawn per seed; the same seed gives the same design for every kind)
-------
Pin diameter 3-10 mm (nominal pressure p = F / pin area); 3-5 loads log-spaced from 5-20 N to
80-200 N; 2-4 speeds log-spaced from 0.05-0.2 m/s to 0.8-2 m/s; test lengths log-uniform in
[L_lo, L_hi] within 100-5000 m. ``histories``: per material 6 (or all) to all load x speed cells
plus 0-2 repeats, each test read 5-12 times, the first at 8-20 % of its length, the last at its
end. ``doe``: per material the full factorial plus 2 to half the cells repeated, one reading per
test at its (test-specific) distance. Run order random (test ids T001, ... in run order).
Friction coefficient per test mu_material (0.15-0.5) times a lognormal 8 %, clipped to
[0.12, 0.58]. time_s = s / v.

Instrument (``noise`` = n; n = 0 gives the noise-free values exactly)
----------
Mass-loss weighing converted to volume with the material's density. A reading of true volume V
in a test of final (noise-free) volume V_f is
    V + n (0.8 V e1 + 0.5 V_f e2 + 0.332 V_f e3_test)  [+ outlier]
(e ~ N(0, 1): a multiplicative part, an additive part per reading and a zero offset per test,
e.g. debris or a transfer layer; the coefficients' squares sum to 1, so a test's final reading
has relative sd n exactly), then the mass loss is rounded to the balance resolution, a power of
ten in kg at most 0.3 n times the smallest final mass loss of the data set. An outlier (2 % of the
readings, flagged in ``truth["outlier"]``) adds +-(4 to 8) n V_f. Friction readings:
mu_t (1 + n e), rounded to 0.001; temperature readings T + 10 K n e, rounded to 0.1 K. Loads,
pressures, speeds, distances and times are exact. Noisy readings may dip below the previous one
or below zero; they are kept.

Effect size (``truth["effect_size"]``, independent of the tool)
-----------
The largest relative difference |V_i - k_m F_i s_i| / V_i over all readings between the
noise-free wear V_i and the least-squares plain-Archard fit on the noise-free data, one k per
material (k_m = sum V F s / sum (F s)^2). For null data it is the test-to-test scatter only,
max |1 - k_m / k_t|. Also given: ``effect_size_cause_only`` (same definition, k scatter set to
0) and ``effect_size_scatter_only`` (the cause removed), and ``cause_size`` (r, a, R or C).
Every kind carries the k scatter, so ``effect_size`` of a small kind is mostly the scatter's;
``effect_size_cause_only`` is the size of the cause alone (over seeds from below 1 % to tens of
per cent). ``archard_effect_size`` computes the definition.
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

KINDS = ("null", "small_running_in", "small_load_exponent", "small_mild_to_severe",
         "small_thermal")
SAMPLINGS = ("histories", "doe")
FORMS = {
    "small_running_in": ("hyperbolic", "stretched"),
    "small_load_exponent": ("power", "loglinear"),
    "small_mild_to_severe": ("load_step", "pv_ramp"),
    "small_thermal": ("linear", "hinge"),
}
# Ranges of the cause sizes (r; a; R; C), the drawn excess (size - neutral) log-uniform.
SIZE_RANGES = {
    "small_running_in": (0.01, 0.30),
    "small_load_exponent": (0.80, 1.25),
    "small_mild_to_severe": (1.01, 1.5),
    "small_thermal": (1.01, 1.5),
}
NEUTRAL_SIZE = {"small_running_in": 0.0, "small_load_exponent": 1.0,
                "small_mild_to_severe": 1.0, "small_thermal": 1.0}
SCATTER_RANGE = (0.02, 0.15)

# Instrument: relative sds of the multiplicative part, the additive part (x final wear) and the
# zero offset per test (x final wear); their squares sum to 1.
C_MULT = 0.8
C_ADD = 0.5
C_OFFSET = math.sqrt(1.0 - C_MULT**2 - C_ADD**2)
OUTLIER_PROBABILITY = 0.02
OUTLIER_SIZE = (4.0, 8.0)
TEMPERATURE_NOISE_K = 10.0

# name, density kg/m3
_MATERIALS = (("CuSn12", 8700.0), ("CuZn37", 8400.0), ("AlSi12", 2650.0),
              ("Ti6Al4V", 4430.0), ("100Cr6", 7810.0), ("CuZn25Al5", 8200.0))
_STREAM = {"design": 0, "noise": 1, **{kind: 10 + i for i, kind in enumerate(KINDS)}}

COLUMN_ORDER = ("test_id", "material", "pressure_Pa", "velocity_m_s", "sliding_distance_m",
                "time_s", "normal_load_N", "friction_coefficient", "temperature_C",
                "wear_volume_m3")


def _rng(seed: int, stream: str) -> np.random.Generator:
    return np.random.default_rng(np.random.SeedSequence([int(seed), _STREAM[stream]]))


def _log_uniform(rng: np.random.Generator, lo: float, hi: float, size=None):
    return np.exp(rng.uniform(math.log(lo), math.log(hi), size))


def _design(seed: int, sampling: str) -> dict:
    """Materials, tests, readings, friction and heating of a seed (the same for every kind)."""
    rng = _rng(seed, "design")
    n_mat = 2 if rng.random() < 0.4 else 1
    mat_idx = rng.choice(len(_MATERIALS), n_mat, replace=False)
    k1 = float(_log_uniform(rng, 5e-15, 2e-13))
    k_mat = [k1]
    if n_mat == 2:
        k_mat.append(k1 * float(_log_uniform(rng, 1.5, 5.0)) ** rng.choice([-1.0, 1.0]))
    mu_mat = rng.uniform(0.15, 0.5, n_mat)
    pin_d = float(rng.choice([3e-3, 4e-3, 5e-3, 6e-3, 8e-3, 10e-3]))
    area = math.pi * pin_d**2 / 4.0

    n_loads = int(rng.integers(3, 6))
    n_speeds = int(rng.integers(2, 5))
    loads = np.round(np.geomspace(float(_log_uniform(rng, 5.0, 20.0)),
                                  float(_log_uniform(rng, 80.0, 200.0)), n_loads), 1)
    speeds = np.round(np.geomspace(float(_log_uniform(rng, 0.05, 0.2)),
                                   float(_log_uniform(rng, 0.8, 2.0)), n_speeds), 3)
    l_lo = float(_log_uniform(rng, 100.0, 600.0))
    l_hi = float(_log_uniform(rng, max(3.0 * l_lo, 1500.0), 5000.0))
    cells = [(i, j) for i in range(n_loads) for j in range(n_speeds)]
    n_cells = len(cells)

    test_cell, test_mat = [], []
    for m in range(n_mat):
        if sampling == "doe":
            chosen = list(range(n_cells))
            n_rep = int(rng.integers(2, max(2, n_cells // 2) + 1))
            chosen += list(rng.choice(n_cells, n_rep, replace=False))
        else:
            n = int(rng.integers(min(6, n_cells), n_cells + 1))
            chosen = list(rng.choice(n_cells, n, replace=False))
            n_rep = int(rng.integers(0, 3))
            chosen += list(rng.choice(chosen, n_rep, replace=False))
        test_cell += [cells[c] for c in chosen]
        test_mat += [m] * len(chosen)
    n_tests = len(test_cell)
    order = rng.permutation(n_tests)
    test_cell = [test_cell[i] for i in order]
    test_mat = np.array([test_mat[i] for i in order])
    load = np.array([loads[i] for i, _ in test_cell])
    speed = np.array([speeds[j] for _, j in test_cell])
    length = np.round(_log_uniform(rng, l_lo, l_hi, n_tests), 0)
    z_k = rng.standard_normal(n_tests)
    sigma_k = float(rng.uniform(*SCATTER_RANGE))
    mu = np.clip(mu_mat[test_mat] * np.exp(0.08 * rng.standard_normal(n_tests)), 0.12, 0.58)

    row_test, dist = [], []
    for t in range(n_tests):
        if sampling == "doe":
            s = np.array([length[t]])
        else:
            n_r = int(rng.integers(5, 13))
            first = rng.uniform(0.08, 0.20)
            gaps = rng.uniform(0.5, 1.5, n_r - 1)
            frac = first + (1.0 - first) * np.concatenate([[0.0], np.cumsum(gaps)]) / gaps.sum()
            s = np.round(length[t] * frac, 1)
            s[-1] = length[t]
        row_test.append(np.full(s.size, t))
        dist.append(s)

    t_amb = float(rng.uniform(18.0, 26.0))
    rise_max = float(rng.uniform(25.0, 120.0))
    tau = float(rng.uniform(120.0, 900.0))
    pressure = load / area
    power = mu * pressure * speed
    rise = rise_max * power / power.max()
    with_temperature = bool(rng.random() < 0.5)
    with_material = n_mat == 2 or bool(rng.random() < 0.5)
    return dict(
        n_mat=n_mat, materials=[_MATERIALS[i][0] for i in mat_idx],
        density=np.array([_MATERIALS[i][1] for i in mat_idx]), k_material=np.array(k_mat),
        mu_material=mu_mat, pin_diameter_m=pin_d, area=area, loads=loads, speeds=speeds,
        test_mat=test_mat, load=load, speed=speed, pressure=pressure, length=length,
        z_k=z_k, sigma_k=sigma_k, mu=mu, row_test=np.concatenate(row_test),
        distance=np.concatenate(dist), t_amb=t_amb, rise=rise, tau=tau,
        with_temperature=with_temperature, with_material=with_material,
    )


def _draw_cause(kind: str, seed: int, design: dict) -> dict:
    """Form, size and shape parameters of the cause (from the kind's own random stream)."""
    if kind == "null":
        return {"form": "none", "size": None}
    rng = _rng(seed, kind)
    form = str(rng.choice(FORMS[kind]))
    if kind == "small_running_in":
        size = float(_log_uniform(rng, 0.01, 0.30))
        return {"form": form, "size": size, "s0_fraction": float(rng.uniform(0.02, 0.30))}
    if kind == "small_load_exponent":
        if rng.random() < 0.5:
            size = 1.0 + float(_log_uniform(rng, 0.005, 0.25))
        else:
            size = 1.0 - float(_log_uniform(rng, 0.005, 0.20))
        return {"form": form, "size": size}
    if kind == "small_mild_to_severe":
        size = 1.0 + float(_log_uniform(rng, 0.01, 0.5))
        n_loads = design["loads"].size
        q1 = float(rng.uniform(0.1, 0.5))
        return {"form": form, "size": size, "step_index": int(rng.integers(1, n_loads)),
                "pv_quantiles": (q1, min(0.95, q1 + float(rng.uniform(0.2, 0.45))))}
    if kind == "small_thermal":
        size = 1.0 + float(_log_uniform(rng, 0.01, 0.5))
        return {"form": form, "size": size, "hinge_fraction": float(rng.uniform(0.2, 0.6))}
    raise ValueError(f"unknown kind {kind!r}; expected one of {KINDS}")


def _temperature(design: dict) -> np.ndarray:
    """Noise-free contact temperature at every reading (deg C)."""
    ti = design["row_test"]
    time = design["distance"] / design["speed"][ti]
    return design["t_amb"] + design["rise"][ti] * (1.0 - np.exp(-time / design["tau"]))


def _wear(kind: str, design: dict, cause: dict, scatter: bool) -> tuple[np.ndarray, dict]:
    """Noise-free cumulative wear volume at every reading, and the cause's derived parameters."""
    ti = design["row_test"]
    s = design["distance"]
    k_t = design["k_material"][design["test_mat"]]
    if scatter:
        k_t = k_t * np.exp(design["sigma_k"] * design["z_k"])
    k = k_t[ti]
    force = design["load"][ti]
    derived: dict = {}
    if kind == "null":
        return k * force * s, derived
    size = cause["size"]
    form = cause["form"]
    if kind == "small_running_in":
        l_med = float(np.median(design["length"]))
        s0 = cause["s0_fraction"] * l_med
        if form == "hyperbolic":
            amp = size * (l_med + s0) / s0
            excess = amp * s0 * s / (s + s0)
        else:
            amp = size * l_med / (1.0 - math.exp(-math.sqrt(l_med / s0)))
            excess = amp * (1.0 - np.exp(-np.sqrt(s / s0)))
        derived.update(s0_m=s0, amplitude=amp, median_length_m=l_med)
        return k * force * (s + excess), derived
    if kind == "small_load_exponent":
        f_ref = float(np.exp(np.mean(np.log(design["load"]))))
        derived["reference_load_N"] = f_ref
        if form == "power":
            return k * f_ref * (force / f_ref) ** size * s, derived
        return k * force * s * (1.0 + (size - 1.0) * np.log(force / f_ref)), derived
    if kind == "small_mild_to_severe":
        if form == "load_step":
            i = cause["step_index"]
            threshold = math.sqrt(design["loads"][i - 1] * design["loads"][i])
            factor = np.where(design["load"] > threshold, size, 1.0)
            derived["load_threshold_N"] = threshold
        else:
            pv = design["pressure"] * design["speed"]
            pv1, pv2 = np.quantile(pv, cause["pv_quantiles"])
            if pv2 <= pv1:
                pv2 = pv1 * 1.0001
            factor = 1.0 + (size - 1.0) * np.clip((pv - pv1) / (pv2 - pv1), 0.0, 1.0)
            derived["pv_ramp_Pa_m_s"] = (float(pv1), float(pv2))
        derived["factor_per_test"] = factor
        return k * force * s * factor[ti], derived
    if kind == "small_thermal":
        rise_t = design["rise"]
        lam_t = design["speed"] * design["tau"]  # heating length of every test, m
        length = design["length"]
        if form == "linear":
            h = 0.0
        else:
            reached = rise_t * (1.0 - np.exp(-length / lam_t))
            h = cause["hinge_fraction"] * float(reached.max())

        def excess(dist, rise, lam):
            """integral over [0, dist] of max(0, T - T_amb - h) ds' (K m), exact."""
            hot = rise > h
            s_c = np.where(hot, -lam * np.log(1.0 - np.where(hot, h / rise, 0.0)), np.inf)
            after = dist > s_c
            sc = np.where(after, s_c, 0.0)
            return np.where(
                after,
                (rise - h) * (dist - sc)
                - rise * lam * (np.exp(-sc / lam) - np.exp(-dist / lam)),
                0.0)

        # k = k_t (1 + g max(0, T - T_amb - h)); g from the contrast C of the tests' mean k.
        mean_excess = excess(length, rise_t, lam_t) / length
        e_max, e_min = float(mean_excess.max()), float(mean_excess.min())
        if e_max <= size * e_min:
            raise ValueError("the design's heating cannot give this contrast")
        gain = (size - 1.0) / (e_max - size * e_min)
        derived.update(hinge_K=h, gain_per_K=gain,
                       mean_k_factor_per_test=1.0 + gain * mean_excess)
        return k * force * (s + gain * excess(s, rise_t[ti], lam_t[ti])), derived
    raise ValueError(f"unknown kind {kind!r}; expected one of {KINDS}")


def archard_effect_size(wear: np.ndarray, force: np.ndarray, distance: np.ndarray,
                        material: np.ndarray) -> float:
    """max_i |V_i - k_m F_i s_i| / V_i, k_m the least-squares plain-Archard k of each material."""
    x = force * distance
    worst = 0.0
    for m in np.unique(material):
        sel = material == m
        k_m = float(wear[sel] @ x[sel]) / float(x[sel] @ x[sel])
        worst = max(worst, float(np.max(np.abs(wear[sel] - k_m * x[sel]) / np.abs(wear[sel]))))
    return worst


def make_dataset(kind: str, seed: int, noise: float, sampling: str = "histories", *,
                 size: float | None = None,
                 scatter: float | None = None) -> tuple[dict[str, np.ndarray], dict]:
    """One data set: ``columns`` (name -> array, rows grouped by test in run order) and ``truth``.

    ``size`` overrides the cause size drawn for the seed (r, a, R or C), ``scatter`` the
    test-to-test sd of ln k. See the module docstring for the model.
    """
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r}; expected one of {KINDS}")
    if sampling not in SAMPLINGS:
        raise ValueError(f"unknown sampling {sampling!r}; expected one of {SAMPLINGS}")
    if noise < 0:
        raise ValueError("noise must be >= 0")
    design = _design(seed, sampling)
    if scatter is not None:
        design["sigma_k"] = float(scatter)
    cause = _draw_cause(kind, seed, design)
    if size is not None:
        if kind == "null":
            raise ValueError("null data have no cause size")
        cause["size"] = float(size)

    ti = design["row_test"]
    s = design["distance"]
    n_rows = s.size
    n_tests = design["length"].size
    force = design["load"][ti]
    mat_row = design["test_mat"][ti]
    wear, derived = _wear(kind, design, cause, scatter=True)
    temperature = _temperature(design)
    mu = design["mu"][ti]

    # Instrument: every random number drawn whatever the noise, so a seed's draws never shift.
    rng = _rng(seed, "noise")
    e_mult = rng.standard_normal(n_rows)
    e_add = rng.standard_normal(n_rows)
    e_off = rng.standard_normal(n_tests)[ti]
    is_out = rng.random(n_rows) < OUTLIER_PROBABILITY
    out_size = rng.uniform(*OUTLIER_SIZE, n_rows) * rng.choice([-1.0, 1.0], n_rows)
    e_mu = rng.standard_normal(n_rows)
    e_temp = rng.standard_normal(n_rows)
    last = np.r_[np.flatnonzero(np.diff(ti)), n_rows - 1]  # last reading of every test
    final = wear[last][ti]
    density = design["density"][mat_row]
    if noise > 0:
        error = noise * (C_MULT * wear * e_mult + C_ADD * final * e_add + C_OFFSET * final * e_off)
        error = error + np.where(is_out, noise * out_size * final, 0.0)
        mass = density * (wear + error)
        resolution = 10.0 ** math.floor(math.log10(0.3 * noise * float(np.min(density * final))))
        measured = np.round(mass / resolution) * resolution / density
        mu_measured = np.round(mu * (1.0 + noise * e_mu), 3)
        temp_measured = np.round(temperature + TEMPERATURE_NOISE_K * noise * e_temp, 1)
        outlier = is_out
    else:
        resolution = 0.0
        measured = wear.copy()
        mu_measured = mu.copy()
        temp_measured = temperature.copy()
        outlier = np.zeros(n_rows, dtype=bool)

    names = np.array([f"T{t + 1:03d}" for t in range(n_tests)])
    columns: dict[str, np.ndarray] = {"test_id": names[ti]}
    if design["with_material"]:
        columns["material"] = np.array(design["materials"])[mat_row]
    columns["pressure_Pa"] = design["pressure"][ti]
    columns["velocity_m_s"] = design["speed"][ti]
    columns["sliding_distance_m"] = s.copy()
    columns["time_s"] = s / design["speed"][ti]
    columns["normal_load_N"] = force.copy()
    columns["friction_coefficient"] = mu_measured
    with_temperature = design["with_temperature"] or kind == "small_thermal"
    if with_temperature:
        columns["temperature_C"] = temp_measured
    columns["wear_volume_m3"] = measured

    k_test = design["k_material"][design["test_mat"]] * np.exp(design["sigma_k"] * design["z_k"])
    cause_only, _ = _wear(kind, design, cause, scatter=False)
    null_wear, _ = _wear("null", design, {}, scatter=True)
    truth = {
        "kind": kind,
        "cause": "none" if kind == "null" else kind.removeprefix("small_"),
        "form": cause["form"],
        "cause_size": cause["size"],
        "size_range": SIZE_RANGES.get(kind),
        "effect_size": archard_effect_size(wear, force, s, mat_row),
        "effect_size_cause_only": archard_effect_size(cause_only, force, s, mat_row),
        "effect_size_scatter_only": archard_effect_size(null_wear, force, s, mat_row),
        "cause_parameters": {**{k: v for k, v in cause.items() if k not in ("form", "size")},
                             **derived},
        "seed": int(seed),
        "noise": float(noise),
        "sampling": sampling,
        "k_scatter_sd": design["sigma_k"],
        "k_material_m2_N": dict(zip(design["materials"], design["k_material"].tolist())),
        "k_test_m2_N": k_test,
        "material_per_row": np.array(design["materials"])[mat_row],
        "density_kg_m3": dict(zip(design["materials"], design["density"].tolist())),
        "pin_diameter_m": design["pin_diameter_m"],
        "pin_area_m2": design["area"],
        "loads_N": design["loads"],
        "speeds_m_s": design["speeds"],
        "friction_per_test": design["mu"],
        "ambient_C": design["t_amb"],
        "steady_rise_K": design["rise"],
        "heating_time_constant_s": design["tau"],
        "wear_noise_free": wear,
        "friction_noise_free": mu,
        "temperature_noise_free": temperature,
        "temperature_written": with_temperature,
        "final_wear_noise_free": final,
        "outlier": outlier,
        "balance_resolution_kg": resolution,
    }
    return columns, truth


def _format(value) -> str:
    if isinstance(value, (str, np.str_)):
        text = str(value)
        if any(c in text for c in ',"\n'):
            raise ValueError(f"text {text!r} cannot be written unquoted")
        return text
    return repr(float(value))


def write_csv(path, columns: dict[str, np.ndarray]) -> Path:
    """Write ``columns`` as a CSV (header row, then one row per reading; floats round-trip)."""
    path = Path(path)
    names = [c for c in COLUMN_ORDER if c in columns] + [c for c in columns
                                                        if c not in COLUMN_ORDER]
    n = len(columns[names[0]])
    lines = [",".join(names)]
    for i in range(n):
        lines.append(",".join(_format(columns[c][i]) for c in names))
    path.write_text("\n".join(lines) + "\n")
    return path
