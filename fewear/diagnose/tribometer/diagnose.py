"""What plain Archard gets wrong on measured pin-on-disc data, which physical causes explain it,
and how much better the extended model predicts tests it has not seen.

Model of reading i of test j (wear volume V [m^3] after sliding distance s [m], time t [s], under
normal load F [N] or contact pressure p [Pa], speed v [m/s], frictional power q = mu p v):

.. math::  \\ln V_{ij} = \\ln F_j + c_{g(j)} + \\ln s_{ij}
           + \\sum_{\\text{causes}} \\ln m(\\ldots; \\theta) + \\epsilon_{ij},

plain Archard (the seed's eq. 10 integrated over a test, k = e^c) with one wear coefficient per
*material group* g (tests that share their material and every other declared categorical factor)
and multiplicative scatter: independent scatter of each reading (weighing, profilometry: readings
that dip below the previous one are data) and test-to-test scatter of k. The causes of
:mod:`fewear.diagnose.tribometer.catalogue` add ln m: *shape* laws bend the wear curve along sliding
(ln S_eff / s), *level* laws change k with load, pressure or p v.

The data decide how the causes are tested:

- *histories* (every test read at least ``min_readings_along_test`` times): the shape causes are
  tested along the tests with each test's own level c_j (stage "along tests": the test-to-test
  scatter of k stays out of it); the level causes then across tests on those levels (stage
  "across tests", one row per test);
- *tables* (a design of experiments, one reading per test or a few): one stage over all readings
  with the material-group levels; tests that share their conditions and differ in sliding
  distance form the wear curve V(s) across tests, so the shape causes are testable too.

Selection (forward, one cause at a time, while each still earns its place): at every step each
untried cause is fitted jointly with those already chosen (its form with the smallest residual sum
of squares) and scored on **whole tests held out**: leave-one-test-out, the cause's parameters
fitted on the other tests, the held-out test predicted from its conditions (with its own level
where the level is per test, so a transient that is over early still shows in the held-out curve).
Per held-out test u the mean squared log error e_u is compared with the current model's. The cause
is accepted when its evidence is significant at p below ``significance`` / m (Bonferroni over the
m forms tried at that step, since the best form of each cause is picked: a family-wise
false-positive rate of at most ``significance``), its
held-out error is lower than the current model's, and its AICc on all rows is at least
``min_aicc_improvement`` lower (Hurvich & Tsai 1989; Burnham & Anderson, *Model Selection and
Multimodel Inference*, 2002). The evidence is the test that is valid for the stage's scatter:

- along tests (many readings per held-out test, their scatter possibly correlated along the test,
  e.g. wear scattered interval by interval): a one-sided paired t-test over the held-out tests of
  ln(e_current,u / e_cause,u) > 0 (:func:`paired_improvement_p`), which counts tests, not
  readings, so correlated scatter cannot make a cause look significant;
- one row per test (levels across tests, tables of one reading per test): the rows are
  independent, and the extra-sum-of-squares F-test of the nested fits (Seber & Wild 1989) uses
  them all.

Of the accepted causes one joins the model: along tests the one with the smallest held-out error;
where each test is one row the one with the smallest AICc (with independent rows AICc and
leave-one-out cross-validation agree asymptotically, Stone, J. R. Stat. Soc. B 39 (1977) 44-47,
and AICc varies less between small samples).

Causes accepted at the first step of a stage that the held-out errors do not tell apart from the
one chosen (paired p >= ``significance``) are reported as confounded, with the evidence for each.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import optimize, stats

from fewear.diagnose.tribometer.catalogue import CAUSES, Context, Form, ShapeLaw, forms_of
from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.wear.coefficient import ConstantWearCoefficient, RbfWearCoefficient, wear_section
from fewear.wear.extensions import NoExtension, extension_to_config

NO_GROUP = "all tests"


@dataclass(frozen=True)
class DiagnoseSettings:
    """The ``[diagnose]`` section (see ``fewear/defaults/diagnose.toml`` for why each value)."""

    significance: float
    min_aicc_improvement: float
    min_readings_along_test: int
    min_conditions_for_network: int
    candidates: tuple[str, ...]
    prediction_distance_factor: float

    def __post_init__(self):
        where = "[diagnose]"
        if not 0.0 < self.significance < 0.5:
            raise FewearInputError(
                f"{where} significance = {self.significance!r}: expected 0 < alpha < 0.5")
        if not (math.isfinite(self.min_aicc_improvement) and self.min_aicc_improvement >= 0.0):
            raise FewearInputError(f"{where} min_aicc_improvement = "
                                   f"{self.min_aicc_improvement!r}: expected a number >= 0")
        if self.min_readings_along_test < 3:
            raise FewearInputError(
                f"{where} min_readings_along_test = {self.min_readings_along_test!r}: expected "
                ">= 3 (one for the test's own k, two for the curve's shape)")
        if self.min_conditions_for_network < 4:
            raise FewearInputError(
                f"{where} min_conditions_for_network = {self.min_conditions_for_network!r}: "
                "expected >= 4 (the network needs at least 4 tests)")
        unknown = [name for name in self.candidates if name not in CAUSES]
        if unknown:
            raise FewearInputError(f"{where} candidates: unknown cause(s) {unknown}; the "
                                   "catalogue holds " + ", ".join(CAUSES))
        if not self.prediction_distance_factor > 1.0:
            raise FewearInputError(
                f"{where} prediction_distance_factor = {self.prediction_distance_factor!r}: "
                "expected a number > 1")

    @classmethod
    def from_config(cls, section: dict[str, Any]) -> DiagnoseSettings:
        """From a ``[diagnose]`` section (as :func:`fewear.io.config.load_config` returns it)."""
        values = dict(section)
        values["candidates"] = tuple(values["candidates"])
        return cls(**values)

    @classmethod
    def default(cls) -> DiagnoseSettings:
        """The embedded defaults (``fewear/defaults/diagnose.toml``)."""
        return cls.from_config(load_config(None, sections=["diagnose"])["diagnose"])


# ---------------------------------------------------------------------------------------------
# The readings


@dataclass(frozen=True)
class Readings:
    """The readings the diagnosis uses (s > 0 and V > 0), per reading, SI units.

    ``velocity_m_s``, ``time_s``: measured or derived from each other (t = s / v), None when
    neither was measured; ``pressure_Pa``, ``load_N``, ``friction``, ``temperature_C``: None when
    not measured; ``group_labels``: each reading's material group (material and the other
    categorical factors, ``"all tests"`` without any). ``measured``: the columns present in the
    table; ``notes``: what was derived, converted or dropped.
    """

    source: str
    data_kind: str
    test_labels: tuple[str, ...]
    test_index: np.ndarray
    pressure_Pa: np.ndarray | None
    velocity_m_s: np.ndarray | None
    distance_m: np.ndarray
    volume_m3: np.ndarray
    time_s: np.ndarray | None
    load_N: np.ndarray | None
    friction: np.ndarray | None
    temperature_C: np.ndarray | None
    group_labels: np.ndarray
    measured: tuple[str, ...]
    notes: tuple[str, ...]

    @property
    def n_tests(self) -> int:
        return len(self.test_labels)

    def per_test(self, values: np.ndarray) -> np.ndarray:
        """Mean of a per-reading array over each test."""
        counts = np.bincount(self.test_index, minlength=self.n_tests)
        return np.bincount(self.test_index, weights=values, minlength=self.n_tests) / counts

    def final_per_test(self, values: np.ndarray) -> np.ndarray:
        """The value at each test's longest sliding distance."""
        out = np.empty(self.n_tests)
        for j in range(self.n_tests):
            rows = np.flatnonzero(self.test_index == j)
            out[j] = values[rows[np.argmax(self.distance_m[rows])]]
        return out

    @property
    def power_W_m2(self) -> np.ndarray | None:
        """Frictional power mu p v per reading, with each test's mean mu (constant in a test)."""
        if self.friction is None or self.velocity_m_s is None or self.pressure_Pa is None:
            return None
        mu = self.per_test(self.friction)[self.test_index]
        return mu * self.pressure_Pa * self.velocity_m_s

    @property
    def load_variable(self) -> tuple[np.ndarray | None, str]:
        """What the level laws read: the pressure [Pa] when measured, else the normal load [N]."""
        if self.pressure_Pa is not None:
            return self.pressure_Pa, "pressure"
        return self.load_N, "normal load"

    def test_groups(self) -> tuple[np.ndarray, tuple[str, ...]]:
        """Each test's material group (index) and the groups' labels, in order of appearance."""
        labels_per_test = [str(self.group_labels[np.flatnonzero(self.test_index == j)[0]])
                           for j in range(self.n_tests)]
        names = tuple(dict.fromkeys(labels_per_test))
        return np.array([names.index(label) for label in labels_per_test]), names


OPTIONAL_COLUMNS = ("pressure_Pa", "velocity_m_s", "time_s", "normal_load_N",
                    "friction_coefficient", "temperature_C")


def readings_from_columns(
    columns: dict[str, Any], *, source: str = "table", data_kind: str = "cumulative_volume",
    notes: tuple[str, ...] = (), factors: dict[str, Any] | None = None,
) -> Readings:
    """Readings from columns of the CSV schema (absent optional columns: missing or None);
    ``factors``: categorical columns (name -> one text per reading), e.g. ``material``."""
    labels, index = np.unique(np.asarray(columns["test_id"]).astype(str), return_inverse=True)
    first_row = [int(np.flatnonzero(index == j)[0]) for j in range(len(labels))]
    order = np.argsort(first_row)
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    index = rank[index]
    labels = labels[order]
    get = {name: _optional(columns.get(name)) for name in OPTIONAL_COLUMNS}
    factors = {name: np.asarray(values).astype(str) for name, values in (factors or {}).items()}
    measured = ("test_id", "sliding_distance_m", "wear_volume_m3") + tuple(
        name for name in OPTIONAL_COLUMNS if get[name] is not None) + tuple(factors)
    s = np.asarray(columns["sliding_distance_m"], float)
    volume = np.asarray(columns["wear_volume_m3"], float)
    notes = list(notes)
    velocity, time = get["velocity_m_s"], get["time_s"]
    if time is None and velocity is not None:
        time = s / velocity
        notes.append("time_s not measured: t = s / v (constant speed within a test)")
    elif velocity is None and time is not None:
        with np.errstate(divide="ignore", invalid="ignore"):
            velocity = np.where(time > 0, s / np.where(time > 0, time, 1.0), np.nan)
        notes.append("velocity_m_s not measured: v = s / t of each reading")
    keep = (s > 0.0) & (volume > 0.0)
    if velocity is not None:
        keep &= np.isfinite(velocity) & (velocity > 0.0)
    if not np.all(keep):
        notes.append(f"{int(np.sum(~keep))} reading(s) with zero sliding distance or with zero or "
                     "negative wear (the scatter of the readings) left out of the fits (no "
                     "information on the rate in a multiplicative model)")
    kept_tests = np.unique(index[keep])
    remap = -np.ones(len(labels), int)
    remap[kept_tests] = np.arange(len(kept_tests))
    group = _group_labels(factors, index.size)

    def select(array):
        return None if array is None else np.asarray(array, float)[keep]

    return Readings(
        source=source, data_kind=data_kind,
        test_labels=tuple(str(labels[j]) for j in kept_tests),
        test_index=remap[index[keep]],
        pressure_Pa=select(get["pressure_Pa"]),
        velocity_m_s=select(velocity), distance_m=s[keep], volume_m3=volume[keep],
        time_s=select(time), load_N=select(get["normal_load_N"]),
        friction=select(get["friction_coefficient"]), temperature_C=select(get["temperature_C"]),
        group_labels=group[keep], measured=measured, notes=tuple(notes),
    )


def _group_labels(factors: dict[str, np.ndarray], n: int) -> np.ndarray:
    if not factors:
        return np.full(n, NO_GROUP)
    return np.array([", ".join(f"{name} {values[i]}" for name, values in factors.items())
                     for i in range(n)])


def _optional(value):
    if value is None:
        return None
    array = np.asarray(value, float)
    return None if array.size == 0 or np.all(np.isnan(array)) else array


def readings_from_measured(data) -> Readings:
    """Readings from :class:`fewear.diagnose.tribometer.measured.MeasuredWear`."""
    columns = {"test_id": data.test_id, "sliding_distance_m": data.sliding_distance_m,
               "wear_volume_m3": data.wear_volume_m3}
    for name in OPTIONAL_COLUMNS:
        columns[name] = getattr(data, name, None)
    return readings_from_columns(columns, source=str(data.source), data_kind=str(data.data_kind),
                                 notes=tuple(data.notes), factors=dict(data.factors))


# ---------------------------------------------------------------------------------------------
# Stages: rows, levels, the laws' context


@dataclass(frozen=True)
class Stage:
    """One regression of the diagnosis: ``y`` per row (ln V - ln F - ln s for readings, or a
    test's level), an intercept ``group`` per row, the held-out ``unit`` (test) of each row, what
    the laws read (``context``) and the forms that can be tested here."""

    name: str
    y: np.ndarray
    group: np.ndarray
    unit: np.ndarray
    context: Context
    forms: tuple[Form, ...]

    @property
    def n_groups(self) -> int:
        return int(self.group.max()) + 1


@dataclass(frozen=True)
class StageFit:
    """Fitted forms (with their search vectors and laws), intercepts per group, residuals."""

    forms: tuple[Form, ...]
    x: tuple[np.ndarray, ...]
    laws: tuple[Any, ...]
    intercepts: np.ndarray
    residuals: np.ndarray

    @property
    def n_parameters(self) -> int:
        return sum(v.size for v in self.x)


def _log_model(stage: Stage, forms, xs) -> tuple[np.ndarray, tuple]:
    laws = tuple(form.law(x, stage.context) for form, x in zip(forms, xs))
    total = np.zeros(stage.y.size)
    for law in laws:
        total = total + law.log_multiplier(stage.context)
    return total, laws


def _intercepts(stage: Stage, z: np.ndarray, rows: np.ndarray) -> np.ndarray:
    counts = np.bincount(stage.group[rows], minlength=stage.n_groups).astype(float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.bincount(stage.group[rows], z[rows], stage.n_groups) / counts


def _split(x: np.ndarray, forms) -> tuple[np.ndarray, ...]:
    sizes = np.cumsum([len(form.bounds) for form in forms])[:-1]
    return tuple(np.split(np.asarray(x, float), sizes))


def fit_stage(stage: Stage, forms: tuple[Form, ...], starts: list[np.ndarray],
              rows: np.ndarray | None = None) -> StageFit:
    """Least-squares fit of ``forms`` on ``rows`` (all by default): intercepts profiled in closed
    form (group means), the laws' parameters by :func:`scipy.optimize.least_squares` from the best
    of ``starts`` (each a concatenated search vector)."""
    rows = np.ones(stage.y.size, bool) if rows is None else rows

    def residuals(x):
        f, _ = _log_model(stage, forms, _split(x, forms))
        z = stage.y - f
        return (z - _intercepts(stage, z, rows)[stage.group])[rows]

    if forms:
        costs = [np.sum(residuals(start) ** 2) for start in starts]
        start = starts[int(np.argmin(costs))]
        lower, upper = np.array([b for form in forms for b in form.bounds]).T
        x = optimize.least_squares(residuals, np.clip(start, lower, upper), bounds=(lower, upper),
                                   xtol=1e-6, ftol=1e-8).x
    else:
        x = np.zeros(0)
    xs = _split(x, forms) if forms else ()
    f, laws = _log_model(stage, forms, xs)
    z = stage.y - f
    intercepts = _intercepts(stage, z, rows)
    return StageFit(forms, xs, laws, intercepts, z - intercepts[stage.group])


def held_out_errors(stage: Stage, fit: StageFit) -> np.ndarray:
    """Leave-one-test-out mean squared error of each unit (NaN where it cannot be predicted).

    The laws are refitted without the unit (from the full fit's parameters); its intercept comes
    from the other tests of its group, or, where the intercept is the unit's own (a test's level),
    from the unit's own rows: the same nuisance level for every model compared."""
    start = [np.concatenate(fit.x)] if fit.forms else []
    errors = np.full(int(stage.unit.max()) + 1, np.nan)
    for u in np.unique(stage.unit):
        held = stage.unit == u
        train = ~held
        if not train.any():
            continue
        trained = fit_stage(stage, fit.forms, start, train)
        f, _ = _log_model(stage, fit.forms, trained.x)
        z = stage.y - f
        own = _intercepts(stage, z, held)
        level = np.where(np.isfinite(trained.intercepts), trained.intercepts, own)
        errors[u] = float(np.mean((z[held] - level[stage.group[held]]) ** 2))
    return errors


def aicc(residuals: np.ndarray, n_parameters: int) -> float:
    """Corrected Akaike criterion of a least-squares fit (Hurvich & Tsai 1989)."""
    n = residuals.size
    rss = float(np.sum(residuals**2))
    if n - n_parameters - 1 <= 0 or rss <= 0.0:
        return float("nan")
    return (n * math.log(rss / n) + 2 * n_parameters
            + 2 * n_parameters * (n_parameters + 1) / (n - n_parameters - 1))


def extra_sum_of_squares_p(nested: StageFit, fuller: StageFit, n_nested: int) -> float:
    """p-value of the extra-sum-of-squares F-test of ``fuller`` against ``nested`` (n_nested
    parameters, intercepts included): F = ((RSS0 - RSS1) / q) / (RSS1 / (n - n_nested - q))
    (e.g. Seber & Wild, *Nonlinear Regression*, 1989, sec. 5.3)."""
    q = fuller.n_parameters - nested.n_parameters
    n = nested.residuals.size
    dof = n - n_nested - q
    rss0, rss1 = float(np.sum(nested.residuals**2)), float(np.sum(fuller.residuals**2))
    if dof <= 0 or rss1 <= 0.0:
        return 1.0
    f = max(rss0 - rss1, 0.0) / q / (rss1 / dof)
    return float(stats.f.sf(f, q, dof))


def paired_improvement_p(before: np.ndarray, after: np.ndarray) -> float:
    """One-sided p-value that ``after`` predicts the held-out tests better than ``before``: a
    paired t-test (Student) of the per-test log ratios ln(e_before / e_after) of the mean squared
    held-out errors, a comparison of predictive accuracy in the manner of Diebold & Mariano,
    J. Bus. Econ. Stat. 13 (1995) 253-263, on the log scale where a ratio of two error variances
    is near-symmetric. 1 with fewer than two tests."""
    d = np.log(before / after)
    d = d[np.isfinite(d)]
    if d.size < 2:
        return 1.0
    sd = float(np.std(d, ddof=1))
    if sd == 0.0:
        return 0.0 if d.mean() > 0.0 else 1.0
    return float(stats.t.sf(d.mean() / (sd / np.sqrt(d.size)), d.size - 1))


# ---------------------------------------------------------------------------------------------
# Forward selection in a stage


@dataclass(frozen=True)
class StageResult:
    """What a stage found: its baseline and final fits with their held-out errors per test, the
    chosen causes (in the order they joined), every step's candidate entries and each chosen
    cause's held-out gain when it joined."""

    stage: Stage
    baseline: StageFit
    baseline_errors: np.ndarray
    final: StageFit
    final_errors: np.ndarray
    chosen: tuple[str, ...]
    steps: tuple[tuple[dict[str, Any], ...], ...]
    gains: dict[str, float]

    @property
    def baseline_rms(self) -> float:
        return held_out_rms(self.baseline_errors)

    @property
    def final_rms(self) -> float:
        return held_out_rms(self.final_errors)


def select_causes(stage: Stage, causes: tuple[str, ...], settings: DiagnoseSettings
                  ) -> StageResult:
    """Forward selection of ``causes`` in ``stage`` (module docstring for the rule)."""
    current = fit_stage(stage, (), [])
    baseline, current_errors = current, held_out_errors(stage, current)
    baseline_errors = current_errors
    chosen, steps, gains = [], [], {}
    while True:
        untried = [c for c in causes if c not in chosen
                   and any(form in stage.forms for form in forms_of(c))]
        if not untried:
            break
        entries = [entry for cause in untried
                   if (entry := _try_cause(stage, current, current_errors, cause)) is not None]
        if not entries:
            break
        threshold = settings.significance / sum(entry["forms_tried"] for entry in entries)
        for entry in entries:
            entry["accepted"] = bool(entry["p_value"] < threshold and entry["gain"] > 0.0 and
                                     entry["aicc_change"] <= -settings.min_aicc_improvement)
            entry["verdict"] = _verdict(entry, threshold, settings)
        steps.append(tuple(entries))
        accepted = [e for e in entries if e["accepted"]]
        if not accepted:
            break
        best = min(accepted, key=lambda e: e["aicc_change"] if e["test"] == "F"
                   else e["held_out_error"])
        gains[best["name"]] = best["gain"]
        chosen.append(best["name"])
        current, current_errors = best["_fit"], best["_errors"]
    return StageResult(stage, baseline, baseline_errors, current, current_errors, tuple(chosen),
                       tuple(steps), gains)


def held_out_rms(errors: np.ndarray) -> float:
    """RMS held-out error over the tests that could be predicted (errors: mean squares per test)."""
    return float(np.sqrt(np.nanmean(errors)))


def _try_cause(stage: Stage, current: StageFit, current_errors: np.ndarray,
               cause: str) -> dict[str, Any] | None:
    """The cause's best form fitted jointly with ``current``, its held-out errors and evidence
    (None when no form has a start, e.g. a threshold without two distinct values)."""
    fits = []
    for form in (f for f in forms_of(cause) if f in stage.forms):
        fixed = np.concatenate(current.x) if current.forms else np.zeros(0)
        starts = [np.concatenate([fixed, np.array(s, float)]) for s in form.starts(stage.context)]
        if starts:
            fits.append(fit_stage(stage, current.forms + (form,), starts))
    if not fits:
        return None
    fit = min(fits, key=lambda f: float(np.sum(f.residuals**2)))
    forms_tried = len(fits)
    errors = held_out_errors(stage, fit)
    n_base = current.n_parameters + stage.n_groups
    one_row_per_unit = np.unique(stage.unit).size == stage.unit.size
    if one_row_per_unit:
        test, p_value = "F", extra_sum_of_squares_p(current, fit, n_base)
    else:
        test, p_value = "paired t", paired_improvement_p(current_errors, errors)
    return {
        "name": cause, "form": fit.forms[-1].name, "stage": stage.name,
        "params": fit.laws[-1].params(),
        "held_out_error": held_out_rms(errors),
        "held_out_error_before": held_out_rms(current_errors),
        "gain": 1.0 - held_out_rms(errors) / held_out_rms(current_errors),
        "test": test, "p_value": p_value, "forms_tried": forms_tried,
        "tests_improved": f"{int(np.sum(errors < current_errors))} of "
                          f"{int(np.sum(np.isfinite(errors)))}",
        "aicc_change": aicc(fit.residuals, n_base + fit.x[-1].size) - aicc(current.residuals,
                                                                           n_base),
        "training_error": float(np.sqrt(np.mean(fit.residuals**2))),
        "_fit": fit, "_errors": errors,
    }


def _verdict(entry: dict[str, Any], threshold: float, settings: DiagnoseSettings) -> str:
    evidence = (f"{entry['test']} p = {entry['p_value']:.2g}, held-out tests improved "
                f"{entry['tests_improved']}, held-out gain {entry['gain']:+.0%}")
    if entry["accepted"]:
        return f"accepted: {evidence} (p < {threshold:.2g}), AICc {entry['aicc_change']:+.1f}"
    if entry["p_value"] >= threshold:
        return f"rejected: not significant ({evidence}; needs p < {threshold:.2g})"
    if entry["gain"] <= 0.0:
        return f"rejected: predicts held-out tests no better ({evidence})"
    return (f"rejected: AICc {entry['aicc_change']:+.1f} (needs <= "
            f"-{settings.min_aicc_improvement:g}): the extra parameters do not pay for "
            "themselves in the fit")


# ---------------------------------------------------------------------------------------------
# The diagnosis

NEEDS_TEXT = {"time": "time_s (or velocity_m_s, from which t = s / v)",
              "friction": "friction_coefficient", "pressure": "pressure_Pa",
              "load": "normal_load_N or pressure_Pa that varies between tests",
              "power": "normal_load_N or pressure_Pa, and velocity_m_s, whose product varies "
                       "between tests",
              "distance": "tests or readings at different sliding distances under one material"}


def data_form(readings: Readings, settings: DiagnoseSettings) -> str:
    """"histories" when every test has ``min_readings_along_test`` readings at distinct sliding
    distances, else "table" (a design of experiments)."""
    distinct = [np.unique(readings.distance_m[readings.test_index == j]).size
                for j in range(readings.n_tests)]
    return "histories" if min(distinct) >= settings.min_readings_along_test else "table"


def available_needs(readings: Readings) -> set[str]:
    """What the data hold of the forms' needs (catalogue.Form.needs, plus "distance")."""
    have = set()
    if readings.time_s is not None and np.ptp(np.log(readings.time_s)) > 0:
        have.add("time")
    if readings.friction is not None:
        have.add("friction")
    if readings.pressure_Pa is not None:
        have.add("pressure")
    load, _ = readings.load_variable
    if load is not None and np.ptp(np.log(readings.per_test(load))) > 0:
        have.add("load")
    if load is not None and readings.velocity_m_s is not None:
        power = readings.per_test(load * readings.velocity_m_s)
        if np.ptp(np.log(power)) > 0:
            have.add("power")
    groups = readings.group_labels
    if any(np.ptp(np.log(readings.distance_m[groups == g])) > 0 for g in np.unique(groups)):
        have.add("distance")
    return have


def _scales(readings: Readings) -> dict[str, float | None]:
    power = readings.power_W_m2
    return {
        "scale_distance_m": float(np.median(readings.final_per_test(readings.distance_m))),
        "scale_time_s": None if readings.time_s is None
        else float(np.median(readings.final_per_test(readings.time_s))),
        "scale_power_W_m2": None if power is None else float(np.max(power)),
    }


def reading_context(readings: Readings, distance_m=None, time_s=None, rows=None) -> Context:
    """The laws' view of the readings (or of the readings ``rows`` at other distances/times)."""
    rows = np.arange(readings.test_index.size) if rows is None else rows
    load, name = readings.load_variable
    speed = readings.velocity_m_s
    power = readings.power_W_m2

    def pick(values):
        return None if values is None else values[rows]

    return Context(
        distance_m=readings.distance_m[rows] if distance_m is None else distance_m,
        time_s=pick(readings.time_s) if time_s is None else time_s,
        power_W_m2=pick(power), load=pick(load), load_name=name,
        load_speed=None if load is None or speed is None else (load * speed)[rows],
        **_scales(readings))


def _test_context(readings: Readings) -> Context:
    load, name = readings.load_variable
    speed = readings.velocity_m_s
    per_test = None if load is None else readings.per_test(load)
    load_speed = None if load is None or speed is None else readings.per_test(load * speed)
    return Context(None, None, None, per_test, name, load_speed, **_scales(readings))


def _log_force(readings: Readings) -> np.ndarray:
    """ln F per reading (ln p without a load: F = p A, the constant A joins k; 0 without both)."""
    if readings.load_N is not None:
        return np.log(readings.load_N)
    if readings.pressure_Pa is not None:
        return np.log(readings.pressure_Pa)
    return np.zeros(readings.test_index.size)


def _testable(kind: str | None, have: set[str], causes) -> tuple[Form, ...]:
    forms = []
    for cause in causes:
        for form in forms_of(cause):
            needs = set(form.needs) | ({"distance"} if form.kind == "shape" else set())
            if (kind is None or form.kind == kind) and needs <= have:
                forms.append(form)
    return tuple(forms)


def reading_stage(readings: Readings, settings: DiagnoseSettings) -> Stage:
    """The stage whose rows are the readings: "along tests" (histories, each test its own level,
    the shape causes) or "all readings" (tables, one level per material group, every cause)."""
    have = available_needs(readings)
    causes = settings.candidates
    test_group, _ = readings.test_groups()
    y = np.log(readings.volume_m3) - np.log(readings.distance_m)
    if data_form(readings, settings) == "table":
        return Stage("all readings", y - _log_force(readings), test_group[readings.test_index],
                     readings.test_index, reading_context(readings),
                     _testable(None, have, causes))
    return Stage("along tests", y, readings.test_index, readings.test_index,
                 reading_context(readings), _testable("shape", have, causes))


def _across_stage(readings: Readings, along: StageResult, settings: DiagnoseSettings) -> Stage:
    """Histories: one row per test, its level under the along-test model minus ln F, one level
    per material group, the level causes."""
    test_group, _ = readings.test_groups()
    levels = along.final.intercepts - readings.per_test(_log_force(readings))
    return Stage("across tests", levels, test_group, np.arange(readings.n_tests),
                 _test_context(readings),
                 _testable("level", available_needs(readings), settings.candidates))


def untestable_causes(readings: Readings, settings: DiagnoseSettings) -> list[dict[str, Any]]:
    have = available_needs(readings)
    out = []
    for cause in settings.candidates:
        missing_per_form = []
        for form in forms_of(cause):
            needs = set(form.needs) | ({"distance"} if form.kind == "shape" else set())
            missing_per_form.append(sorted(needs - have))
        if all(missing_per_form):
            missing = min(missing_per_form, key=len)
            out.append({"name": cause, "needs": missing, "message": "could not be tested: needs "
                        + " and ".join(NEEDS_TEXT[need] for need in missing)})
    return out


@dataclass(frozen=True)
class Diagnosis:
    """Everything :func:`diagnose` found; ``summary`` is JSON-ready."""

    readings: Readings
    settings: DiagnoseSettings
    form: str
    stages: tuple[StageResult, ...]
    causes: tuple[str, ...]
    summary: dict[str, Any] = field(repr=False)
    extended_section: dict[str, Any] = field(repr=False)

    @property
    def cause(self) -> str:
        return self.causes[0] if self.causes else "none"

    @property
    def reading_stage(self) -> StageResult:
        """The stage whose rows are the readings ("along tests" or "all readings")."""
        return self.stages[0]

    @property
    def shape_law(self) -> ShapeLaw | None:
        laws = [law for law in self.reading_stage.final.laws if isinstance(law, ShapeLaw)]
        return laws[0] if laws else None


def diagnose(readings: Readings, settings: DiagnoseSettings | None = None) -> Diagnosis:
    """The diagnosis of ``readings`` (module docstring for the method)."""
    from fewear.diagnose.tribometer.report import summarise

    settings = settings or DiagnoseSettings.default()
    if readings.n_tests < 3:
        raise FewearInputError(f"{readings.source}: {readings.n_tests} test(s) with wear; the "
                               "diagnosis holds whole tests out and needs at least 3")
    form = data_form(readings, settings)
    stages = [select_causes(reading_stage(readings, settings), settings.candidates, settings)]
    if form == "histories":
        stages.append(select_causes(_across_stage(readings, stages[0], settings),
                                    settings.candidates, settings))
    gains = {name: gain for stage in stages for name, gain in stage.gains.items()}
    causes = tuple(sorted(gains, key=lambda name: -gains[name]))
    extended = extended_wear_section(readings, stages[0], settings)
    summary = summarise(readings, settings, form, stages, causes, extended)
    return Diagnosis(readings, settings, form, tuple(stages), causes, summary, extended)


def log_k_per_test(readings: Readings, stage: Stage, fit: StageFit) -> np.ndarray:
    """Each test's ln k [m^2/N] under a reading-stage fit's shape law (ln V - ln F - ln S_eff
    averaged over the test's readings)."""
    shape = [law for law in fit.laws if isinstance(law, ShapeLaw)]
    log_shape = shape[0].log_multiplier(stage.context) if shape else 0.0
    z = (np.log(readings.volume_m3) - np.log(readings.distance_m) - _log_force(readings)
         - log_shape)
    return readings.per_test(z)


def extended_wear_section(readings: Readings, result: StageResult,
                          settings: DiagnoseSettings) -> dict[str, Any]:
    """The ``[wear]`` section of the extended model: the shape cause as the extension, and
    k(p, v) trained on the tests' k under it (the RBF network of seed eq. 9 over the tests of the
    largest material group when they cover ``min_conditions_for_network`` distinct (p, v), else
    their geometric mean): the network carries what the level causes found."""
    log_k = log_k_per_test(readings, result.stage, result.final)
    test_group, _ = readings.test_groups()
    main = test_group == np.bincount(test_group).argmax()
    shape = [law for law in result.final.laws if isinstance(law, ShapeLaw)]
    extension = shape[0].extension if shape else NoExtension()
    model = ConstantWearCoefficient(float(np.exp(np.mean(log_k[main]))))
    if readings.pressure_Pa is not None and readings.velocity_m_s is not None:
        p = readings.per_test(readings.pressure_Pa)[main]
        v = readings.per_test(readings.velocity_m_s)[main]
        if len(set(zip(p, v))) >= settings.min_conditions_for_network:
            model, _ = RbfWearCoefficient.fit(p, v, np.exp(log_k[main]),
                                              folds=min(5, int(main.sum())))
    return wear_section(model, **extension_to_config(extension))


def predict_log_volume(readings: Readings, stage: Stage, fit: StageFit, test: int,
                       distance_m) -> np.ndarray:
    """ln V [m^3] of test ``test`` after sliding ``distance_m`` under a fit of the reading stage
    (at the test's speed, power and load; time s / v)."""
    rows = np.flatnonzero(readings.test_index == test)
    s = np.atleast_1d(np.asarray(distance_m, float))
    pick = np.full(s.size, rows[0])
    time = None
    if readings.time_s is not None:
        time = s * readings.time_s[rows[0]] / readings.distance_m[rows[0]]
    context = reading_context(readings, distance_m=s, time_s=time, rows=pick)
    total = np.log(s) + _log_force(readings)[pick] + fit.intercepts[stage.group[pick]]
    for law in fit.laws:
        total = total + law.log_multiplier(context)
    return total
