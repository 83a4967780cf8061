"""What plain Archard gets wrong on measured pin-on-disc data, which physical cause explains it,
and how much better the extended model predicts.

Model of a reading i of test j (cumulative wear volume V [m^3] after sliding distance s [m] and
time t [s] at pressure p, speed v, load F, frictional power q = mu p v):

.. math::  V_{ij} = F_j\\, k_j\\, S_{eff}(s_{ij}, t_{ij}, q_j; \\theta)\\, \\epsilon_{ij},

with S_eff = s for the baseline (the seed's Archard law, eq. 10 integrated over a test) and the
effective distance of an extension of :mod:`fewear.wear.extensions` otherwise (two parameters
theta). ``k_j`` is each test's coefficient (its level); the seed's RBF network k(p, v) (eq. 9,
:class:`fewear.wear.coefficient.RbfWearCoefficient`) is trained on the tests' k_j, exactly as the
paper trains it on its pin-on-disc tests. The levels are profiled out in closed form; theta is
found by a start grid and :func:`scipy.optimize.least_squares`.

Noise models (what the fit minimises):

- ``increments`` (default): residuals of ln(Delta V) against ln(Delta S_eff) between consecutive
  readings of a test (from zero for the first). Wear is a scattered process: the scatter of a
  cumulative history is carried from each interval into every later reading, so the cumulative
  residuals are correlated along a test and a fit to them (and its AICc) takes a wandering
  history for a curved law. The increments of such a history are independent. Readings without
  growth since the previous one are merged into the next interval (and the report says so).
- ``lognormal``: residuals of ln V (independent scatter of each cumulative reading, e.g. when
  weighing errors dominate); ``relative``: V / V_hat - 1, the same for small scatter.

Scoring (the parsimony criterion). Each candidate is fitted on a training part and predicts the
held-out part, the cumulative wear V_hat = F k_j S_eff(s) predicted from the start of the test
(held-out error: RMS of ln(V / V_hat), or of V / V_hat - 1 with ``relative``):

- ``later_readings`` (default when every test has enough readings): the last ``holdout_fraction``
  of each test's readings are held out and predicted from the earlier ones with the test's own
  level. This scores exactly what a wear simulation does, extrapolate wear to longer sliding, and
  it does not mix the shape of the wear curve (what the causes change) with the test-to-test
  scatter of k.
- ``tests``: whole tests are held out (leave-one-test-out, or 6 folds above 12 tests) and their
  level comes from the network k(p, v) trained on the other tests; used when tests have too few
  readings to split (e.g. one reading per test).

The held-out units are tests; d_j = e_base,j - e_cand,j is the difference of the mean squared
held-out residuals of test j. A candidate is *accepted* when mean(d) exceeds ``significance_z``
standard errors of that mean (with 1: the one-standard-error rule of Hastie, Tibshirani & Friedman,
*Elements of Statistical Learning*, sec. 7.10, as a paired comparison) and its held-out RMS error is
at least ``min_gain`` below the baseline's (an improvement worth a model: a candidate that only fits
noise extrapolates worse, not 15 % better) and its AICc on all readings is at least
``min_aicc_improvement`` below the baseline's (two more parameters must pay for themselves in the
fit too). The causes of the catalogue all have two parameters;
among the accepted ones the cause is the one with the smallest AICc on all readings (Hurvich &
Tsai 1989; with equal parameter counts simply the best likelihood): the held-out readings of a test
are its last ones, where every transient has died out, so they rarely separate two transients, while
the early readings do. ``none`` when no candidate is accepted. Another accepted candidate whose
AICc is within ``aicc_separation`` of the cause's and whose held-out error is within
``confound_z`` standard errors is reported as confounded with it, with the evidence for each
(Burnham & Anderson, *Model Selection and Multimodel Inference*, 2002: an AICc difference below
about 4 leaves the other model substantial support).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from scipy import optimize

from fewear.calibrate.catalogue import CATALOGUE, Candidate, Scales
from fewear.errors import FewearInputError
from fewear.io.config import load_config
from fewear.wear.coefficient import ConstantWearCoefficient, RbfWearCoefficient, wear_section
from fewear.wear.extensions import NoExtension, WearExtension, extension_to_config

HOLDOUTS = ("auto", "later_readings", "tests")
NOISE_MODELS = ("increments", "lognormal", "relative")
MAX_LEAVE_ONE_OUT_TESTS = 12
MIN_SHAPE_READINGS = 3
"""A cause changes the shape of a test's wear history: at least one test must have this many
readings (one for the test's own k, two for the shape)."""
TEST_FOLDS = 6


@dataclass(frozen=True)
class DiagnoseSettings:
    """The ``[diagnose]`` section (see ``fewear/defaults/diagnose.toml`` for why each value)."""

    holdout: str
    holdout_fraction: float
    min_readings_per_test: int
    noise_model: str
    significance_z: float
    min_gain: float
    min_aicc_improvement: float
    confound_z: float
    aicc_separation: float
    min_conditions_for_network: int
    candidates: tuple[str, ...]
    prediction_distance_factor: float

    def __post_init__(self):
        where = "[diagnose]"
        if self.holdout not in HOLDOUTS:
            raise FewearInputError(
                f"{where} holdout = {self.holdout!r}: expected one of {HOLDOUTS}"
            )
        if self.noise_model not in NOISE_MODELS:
            raise FewearInputError(
                f"{where} noise_model = {self.noise_model!r}: expected one of {NOISE_MODELS}"
            )
        if not 0.0 < self.holdout_fraction < 1.0:
            raise FewearInputError(
                f"{where} holdout_fraction = {self.holdout_fraction!r}: expected 0 < f < 1"
            )
        if self.min_readings_per_test < 3:
            raise FewearInputError(
                f"{where} min_readings_per_test = {self.min_readings_per_test!r}: expected >= 3 "
                "(two to fit a curve's shape, one to hold out)"
            )
        for name in ("significance_z", "confound_z", "min_gain", "aicc_separation",
                     "min_aicc_improvement"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 0.0):
                raise FewearInputError(f"{where} {name} = {value!r}: expected a number >= 0")
        if self.min_conditions_for_network < 4:
            raise FewearInputError(
                f"{where} min_conditions_for_network = {self.min_conditions_for_network!r}: "
                "expected >= 4 (the network needs at least 4 tests)"
            )
        unknown = [name for name in self.candidates if name not in CATALOGUE]
        if unknown:
            raise FewearInputError(
                f"{where} candidates: unknown cause(s) {unknown}; the catalogue holds "
                + ", ".join(CATALOGUE)
            )
        if not self.prediction_distance_factor > 1.0:
            raise FewearInputError(
                f"{where} prediction_distance_factor = {self.prediction_distance_factor!r}: "
                "expected a number > 1"
            )

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
    not measured.
    ``measured``: the variables present in the table; ``notes``: what was derived or dropped.
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

    def subset(self, keep: np.ndarray, note: str | None = None) -> Readings:
        """The readings in ``keep`` (tests keep their numbers; ``note`` added to the notes)."""
        def pick(array):
            return None if array is None else array[keep]

        return Readings(
            source=self.source, data_kind=self.data_kind, test_labels=self.test_labels,
            test_index=self.test_index[keep], pressure_Pa=pick(self.pressure_Pa),
            velocity_m_s=pick(self.velocity_m_s), distance_m=self.distance_m[keep],
            volume_m3=self.volume_m3[keep], time_s=pick(self.time_s), load_N=pick(self.load_N),
            friction=pick(self.friction), temperature_C=pick(self.temperature_C),
            measured=self.measured, notes=self.notes + ((note,) if note else ()),
        )

    def has(self, variable: str) -> bool:
        return {
            "sliding_distance_m": True,
            "time_s": self.time_s is not None,
            "friction_coefficient": self.friction is not None,
            "pressure_Pa": self.pressure_Pa is not None,
        }[variable]


NEEDS_TEXT = {"time_s": "time_s (or velocity_m_s, from which t = s / v)",
              "friction_coefficient": "friction_coefficient", "pressure_Pa": "pressure_Pa",
              "sliding_distance_m": "sliding_distance_m"}
OPTIONAL_COLUMNS = ("pressure_Pa", "velocity_m_s", "time_s", "normal_load_N",
                    "friction_coefficient", "temperature_C")


def readings_from_columns(
    columns: dict[str, Any], *, source: str = "table", data_kind: str = "volume",
    notes: tuple[str, ...] = (),
) -> Readings:
    """Readings from columns of the CSV schema (absent optional columns: missing or None)."""
    labels, index = np.unique(np.asarray(columns["test_id"]).astype(str), return_inverse=True)
    first_row = [int(np.flatnonzero(index == j)[0]) for j in range(len(labels))]
    order = np.argsort(first_row)
    rank = np.empty_like(order)
    rank[order] = np.arange(len(order))
    index = rank[index]
    labels = labels[order]
    get = {name: _optional(columns.get(name)) for name in OPTIONAL_COLUMNS}
    measured = ("test_id", "sliding_distance_m", "wear_volume_m3") + tuple(
        name for name in OPTIONAL_COLUMNS if get[name] is not None
    )
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
        notes.append(f"{int(np.sum(~keep))} reading(s) with zero sliding distance or zero wear "
                     "left out (no information on the rate in a multiplicative model)")
    kept_tests = np.unique(index[keep])
    remap = -np.ones(len(labels), int)
    remap[kept_tests] = np.arange(len(kept_tests))

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
        measured=measured, notes=tuple(notes),
    )


def _optional(value):
    if value is None:
        return None
    array = np.asarray(value, float)
    return None if array.size == 0 or np.all(np.isnan(array)) else array


def readings_from_measured(data) -> Readings:
    """Readings from :class:`fewear.calibrate.measured.MeasuredWear`."""
    columns = {"test_id": data.test_id, "sliding_distance_m": data.sliding_distance_m,
               "wear_volume_m3": data.wear_volume_m3}
    for name in OPTIONAL_COLUMNS:
        columns[name] = getattr(data, name, None)
    return readings_from_columns(columns, source=str(data.source), data_kind=str(data.data_kind),
                                 notes=tuple(data.notes))


# ---------------------------------------------------------------------------------------------
# Fitting


@dataclass(frozen=True)
class Fit:
    """A model fitted to some readings: the extension, each test's level ln(k_j F_j) (NaN for
    tests without training readings) and the residuals of every reading."""

    extension: WearExtension
    x: np.ndarray | None
    levels: np.ndarray
    residuals: np.ndarray


def _previous_reading(readings: Readings) -> np.ndarray:
    """Index of the previous reading (by distance) of the same test; -1 for a test's first."""
    previous = -np.ones(readings.test_index.size, int)
    for j in range(readings.n_tests):
        rows = np.flatnonzero(readings.test_index == j)
        rows = rows[np.argsort(readings.distance_m[rows], kind="stable")]
        previous[rows[1:]] = rows[:-1]
    return previous


def growing_readings(readings: Readings) -> Readings:
    """``readings`` without those that show no growth of the wear volume or of the sliding
    distance since the test's previous reading (the next increment then spans both intervals)."""
    keep = np.ones(readings.test_index.size, bool)
    while True:
        subset = readings.subset(keep)
        previous = _previous_reading(subset)
        grows = np.ones(subset.test_index.size, bool)
        has_previous = previous >= 0
        grows[has_previous] = ((subset.volume_m3[has_previous]
                                > subset.volume_m3[previous[has_previous]])
                               & (subset.distance_m[has_previous]
                                  > subset.distance_m[previous[has_previous]]))
        if np.all(grows):
            break
        keep[np.flatnonzero(keep)[~grows]] = False
    dropped = int(np.sum(~keep))
    if not dropped:
        return readings
    return readings.subset(keep, f"{dropped} reading(s) without growth of the wear volume since "
                                 "the previous reading merged into the next interval "
                                 "(noise_model = increments)")


class Problem:
    """The data of a diagnosis in the form the fits use (module docstring)."""

    def __init__(self, readings: Readings, noise_model: str):
        self.readings = readings
        self.noise_model = noise_model
        self.previous = _previous_reading(readings)
        self.log_volume = np.log(self._increments(readings.volume_m3))
        self.test = readings.test_index
        self.n_tests = readings.n_tests
        self.power = readings.power_W_m2
        final_time = None if readings.time_s is None else readings.final_per_test(readings.time_s)
        self.scales = Scales(
            distance_m=float(np.median(readings.final_per_test(readings.distance_m))),
            time_s=None if final_time is None else float(np.median(final_time)),
            power_W_m2=None if self.power is None else float(np.max(self.power)),
        )

    def log_effective(self, extension: WearExtension) -> np.ndarray:
        r = self.readings
        return np.log(self._increments(
            extension.effective_distance_m(r.distance_m, r.time_s, self.power)))

    def _increments(self, cumulative: np.ndarray) -> np.ndarray:
        """The cumulative values themselves, or with ``increments`` their growth since the test's
        previous reading (from zero for the first)."""
        if self.noise_model != "increments":
            return cumulative
        return cumulative - np.where(self.previous >= 0, cumulative[self.previous], 0.0)

    def levels(self, z: np.ndarray, mask: np.ndarray) -> np.ndarray:
        """Each test's level from the readings in ``mask`` (NaN for a test with none)."""
        counts = np.bincount(self.test[mask], minlength=self.n_tests).astype(float)
        with np.errstate(divide="ignore", invalid="ignore"):
            if self.noise_model != "relative":
                return np.bincount(self.test[mask], z[mask], self.n_tests) / counts
            ratio = np.exp(z[mask] - np.max(z))
            u = (np.bincount(self.test[mask], ratio, self.n_tests)
                 / np.bincount(self.test[mask], ratio**2, self.n_tests))
            return np.max(z) - np.log(np.where(counts > 0, u, np.nan))

    def residuals(self, z: np.ndarray, levels: np.ndarray) -> np.ndarray:
        deviation = z - levels[self.test]
        return np.expm1(deviation) if self.noise_model == "relative" else deviation

    def prediction_residuals(self, extension: WearExtension, levels: np.ndarray) -> np.ndarray:
        """Residuals of the cumulative wear predicted from the start of each test,
        V_hat = exp(level) S_eff(s), in the form of the noise model (ln V for increments)."""
        r = self.readings
        effective = extension.effective_distance_m(r.distance_m, r.time_s, self.power)
        z = np.log(r.volume_m3) - np.log(effective)
        deviation = z - levels[self.test]
        return np.expm1(deviation) if self.noise_model == "relative" else deviation

    def fit(self, candidate: Candidate | None, mask: np.ndarray) -> Fit:
        """Fit the baseline (``candidate`` None) or a candidate on the readings in ``mask``."""
        if candidate is None:
            extension = NoExtension()
            z = self.log_volume - self.log_effective(extension)
            levels = self.levels(z, mask)
            return Fit(extension, None, levels, self.residuals(z, levels))

        def training_residuals(x):
            z = self.log_volume - self.log_effective(candidate.build(x, self.scales))
            return self.residuals(z, self.levels(z, mask))[mask]

        costs = [np.sum(training_residuals(np.array(x)) ** 2) for x in candidate.starts]
        start = np.array(candidate.starts[int(np.argmin(costs))])
        lower, upper = np.array(candidate.bounds).T
        result = optimize.least_squares(training_residuals, start, bounds=(lower, upper),
                                        x_scale=1.0, xtol=1e-6, ftol=1e-8)
        extension = candidate.build(result.x, self.scales)
        z = self.log_volume - self.log_effective(extension)
        levels = self.levels(z, mask)
        return Fit(extension, result.x, levels, self.residuals(z, levels))


# ---------------------------------------------------------------------------------------------
# The baseline network k(p, v)


@dataclass(frozen=True)
class LevelModel:
    """How a test's k comes from its (p, v): ``kind`` 'rbf' (seed eq. 9) or 'constant';
    ``n_centres`` and ``ridge`` of the network as chosen by its cross-validation on all tests."""

    kind: str
    n_centres: int | None = None
    ridge: float | None = None
    reason: str = ""

    def fit(self, pressure_Pa, velocity_m_s, k_m2_N):
        """The k(p, v) model trained on tests (p_j, v_j, k_j); (model, cross-validation or None)."""
        if self.kind == "constant" or len(k_m2_N) < 4:
            return ConstantWearCoefficient(float(np.exp(np.mean(np.log(k_m2_N))))), None
        n_distinct = len({(a, b) for a, b in zip(pressure_Pa, velocity_m_s)})
        return RbfWearCoefficient.fit(
            pressure_Pa, velocity_m_s, k_m2_N, folds=min(5, len(k_m2_N)),
            n_centres=None if self.n_centres is None else min(self.n_centres, n_distinct),
            ridge=self.ridge,
        )


def _test_conditions(readings: Readings) -> tuple[np.ndarray, np.ndarray, np.ndarray, str]:
    """Per test: pressure, velocity, load (ones when not measured) and a note on what the
    network's k means."""
    note = ""
    if readings.pressure_Pa is None:
        p = np.ones(readings.n_tests)
        note = "pressure not measured: k cannot depend on p. "
    else:
        p = readings.per_test(readings.pressure_Pa)
    if readings.velocity_m_s is None:
        v = np.ones(readings.n_tests)
        note = "velocity not measured: the network is k(p) only. "
    else:
        v = readings.per_test(readings.velocity_m_s)
    if readings.load_N is None:
        load = np.ones(readings.n_tests)
        note += ("normal_load_N not measured: the network is fitted to V / s per test (m^3/m), "
                 "not to k in m^2/N. ")
    else:
        load = readings.per_test(readings.load_N)
    return p, v, load, note.strip()


def choose_level_model(readings: Readings, levels: np.ndarray, settings: DiagnoseSettings):
    """The baseline k(p, v): the RBF network when the tests cover enough distinct conditions,
    else a constant k (and why). Returns (LevelModel, fitted model, cross-validation or None)."""
    p, v, load, _ = _test_conditions(readings)
    k = np.exp(levels) / load
    n_distinct = len({(a, b) for a, b in zip(p, v)})
    if n_distinct < settings.min_conditions_for_network:
        level_model = LevelModel(
            "constant", reason=f"only {n_distinct} distinct (p, v) condition(s) (the network "
            f"needs {settings.min_conditions_for_network}): constant k, the geometric mean of "
            "the tests' k")
        model, cv = level_model.fit(p, v, k)
        return level_model, model, cv
    model, cv = LevelModel("rbf").fit(p, v, k)
    level_model = LevelModel(
        "rbf", cv.n_centres, cv.ridge,
        reason=f"RBF network k(p, v) (seed eq. 9) over {n_distinct} distinct (p, v) conditions; "
        + cv.summary())
    return level_model, model, cv


# ---------------------------------------------------------------------------------------------
# Hold-out scoring


@dataclass(frozen=True)
class Holdout:
    """The hold-out plan: ``strategy``, why, and the folds as (training mask, held-out mask)."""

    strategy: str
    why: str
    folds: tuple[tuple[np.ndarray, np.ndarray], ...]
    held_out: np.ndarray


def plan_holdout(readings: Readings, settings: DiagnoseSettings) -> Holdout:
    counts = np.bincount(readings.test_index, minlength=readings.n_tests)
    enough = bool(np.all(counts >= settings.min_readings_per_test))
    strategy = settings.holdout
    if strategy == "auto":
        strategy = "later_readings" if enough else "tests"
    if strategy == "later_readings":
        if not enough:
            raise FewearInputError(
                f"[diagnose] holdout = 'later_readings': every test needs at least "
                f"{settings.min_readings_per_test} readings (min_readings_per_test); the fewest "
                f"are {int(counts.min())} (test {readings.test_labels[int(np.argmin(counts))]}); "
                "use holdout = 'tests' or 'auto'"
            )
        held = np.zeros(readings.test_index.size, bool)
        for j in range(readings.n_tests):
            rows = np.flatnonzero(readings.test_index == j)
            rows = rows[np.argsort(readings.distance_m[rows])]
            n_held = max(1, int(round(settings.holdout_fraction * rows.size)))
            held[rows[-n_held:]] = True
        why = (f"the last {settings.holdout_fraction:.0%} of each test's readings are predicted "
               "from the earlier ones: this scores the extrapolation to longer sliding that a wear "
               "simulation makes, and keeps the tests' own k apart from the curve's shape")
        return Holdout(strategy, why, ((~held, held),), held)
    if readings.n_tests < 4:
        raise FewearInputError(
            f"cannot hold out tests: {readings.n_tests} test(s), at least 4 needed; every test "
            f"also has fewer than {settings.min_readings_per_test} readings to hold out later ones"
        )
    n_folds = readings.n_tests if readings.n_tests <= MAX_LEAVE_ONE_OUT_TESTS else TEST_FOLDS
    fold_of_test = np.arange(readings.n_tests) % n_folds
    folds = tuple((fold_of_test[readings.test_index] != f, fold_of_test[readings.test_index] == f)
                  for f in range(n_folds))
    folds_text = "leave-one-test-out" if n_folds == readings.n_tests else f"{n_folds} folds"
    reason = ("as the config asks" if settings.holdout == "tests" else
              "the tests have too few readings to hold out later ones")
    why = (f"whole tests are held out ({folds_text}) and predicted with k(p, v) from the other "
           f"tests: {reason}")
    return Holdout("tests", why, folds, np.ones(readings.test_index.size, bool))


@dataclass(frozen=True)
class Score:
    """Held-out residuals (NaN where not held out), the per-test mean squared error, the RMS
    error over all held-out readings and the fits of the folds (on their training readings)."""

    residuals: np.ndarray
    per_test: np.ndarray
    rms: float
    fold_fits: tuple[Fit, ...]


def score(problem: Problem, candidate: Candidate | None, holdout: Holdout,
          level_model: LevelModel) -> Score:
    readings = problem.readings
    held_residuals = np.full(readings.test_index.size, np.nan)
    p, v, load, _ = _test_conditions(readings)
    fold_fits = []
    for train, held in holdout.folds:
        fit = problem.fit(candidate, train)
        fold_fits.append(fit)
        levels = fit.levels
        if holdout.strategy == "tests":
            train_tests = np.unique(readings.test_index[train])
            model, _ = level_model.fit(p[train_tests], v[train_tests],
                                       np.exp(levels[train_tests]) / load[train_tests])
            levels = np.log(model(p, v) * load)
        held_residuals[held] = problem.prediction_residuals(fit.extension, levels)[held]
    mask = holdout.held_out
    squared = np.where(mask, held_residuals, 0.0) ** 2
    per_test = (np.bincount(readings.test_index, squared, readings.n_tests)
                / np.bincount(readings.test_index, mask.astype(float), readings.n_tests))
    return Score(held_residuals, per_test, float(np.sqrt(np.mean(held_residuals[mask] ** 2))),
                 tuple(fold_fits))


def paired_z(better: np.ndarray, worse: np.ndarray) -> float:
    """mean(worse - better) / its standard error over the held-out tests (inf if all equal)."""
    d = worse - better
    if d.size < 2:
        return float("nan")
    se = np.std(d, ddof=1) / np.sqrt(d.size)
    if se == 0.0:
        return float("inf") if np.mean(d) > 0 else 0.0
    return float(np.mean(d) / se)


def aicc(residuals: np.ndarray, n_parameters: int) -> float:
    """Corrected Akaike criterion of a least-squares fit (Hurvich & Tsai 1989)."""
    n = residuals.size
    if n - n_parameters - 1 <= 0:
        return float("nan")
    rss = float(np.sum(residuals**2))
    if rss <= 0.0:
        return float("nan")
    return (n * math.log(rss / n) + 2 * n_parameters
            + 2 * n_parameters * (n_parameters + 1) / (n - n_parameters - 1))


# ---------------------------------------------------------------------------------------------
# The diagnosis


@dataclass(frozen=True)
class Diagnosis:
    """Everything :func:`diagnose` found; ``summary`` is JSON-ready (see :func:`to_json`)."""

    readings: Readings
    settings: DiagnoseSettings
    holdout: Holdout
    baseline_fit: Fit
    baseline_score: Score
    extended_fit: Fit
    extended_score: Score
    fits: dict[str, Fit]
    scores: dict[str, Score]
    cause: str
    summary: dict[str, Any] = field(repr=False)
    extended_section: dict[str, Any] = field(repr=False)


def diagnose(readings: Readings, settings: DiagnoseSettings | None = None) -> Diagnosis:
    """The diagnosis of ``readings`` (module docstring for the method)."""
    from fewear.calibrate.structure import residual_structure

    settings = settings or DiagnoseSettings.default()
    if settings.noise_model == "increments":
        readings = growing_readings(readings)
    problem = Problem(readings, settings.noise_model)
    everything = np.ones(readings.test_index.size, bool)
    holdout = plan_holdout(readings, settings)
    baseline_fit = problem.fit(None, everything)
    level_model, baseline_network, baseline_cv = choose_level_model(
        readings, baseline_fit.levels, settings)
    baseline_score = score(problem, None, holdout, level_model)

    candidates, untestable = [], []
    fits: dict[str, Fit] = {}
    scores: dict[str, Score] = {}
    counts = np.bincount(readings.test_index, minlength=readings.n_tests)
    for name in settings.candidates:
        candidate = CATALOGUE[name]
        missing = [need for need in candidate.needs if not readings.has(need)]
        if counts.max() < MIN_SHAPE_READINGS:
            untestable.append({
                "name": name, "needs": ["readings along each test"],
                "message": f"could not be tested: needs at least {MIN_SHAPE_READINGS} readings "
                           f"along a test (the table has at most {int(counts.max())} per test, "
                           "and each test's own k absorbs them)"})
            continue
        if missing:
            text = " and ".join(NEEDS_TEXT[need] for need in missing)
            untestable.append({"name": name, "needs": missing,
                               "message": f"could not be tested: needs {text}"})
            continue
        fits[name] = problem.fit(candidate, everything)
        scores[name] = score(problem, candidate, holdout, level_model)
        candidates.append(_candidate_entry(name, fits[name], scores[name], baseline_score,
                                           baseline_fit, settings))

    accepted = [c for c in candidates if c["accepted"]]
    cause = min(accepted, key=lambda c: c["aicc"])["name"] if accepted else "none"
    confounded = _confounded(cause, accepted, scores, readings, settings)
    extended_fit = fits.get(cause, baseline_fit)
    extended_score = scores.get(cause, baseline_score)
    extended_network, extended_cv = level_model.fit(
        *_test_conditions(readings)[:2],
        np.exp(extended_fit.levels) / _test_conditions(readings)[2])
    extended_section = wear_section(
        extended_network, **extension_to_config(extended_fit.extension))
    gain = 1.0 - extended_score.rms / baseline_score.rms
    structure = residual_structure(readings, baseline_fit.residuals, baseline_fit.levels,
                                   baseline_network)
    summary = {
        "source": readings.source,
        "data_kind": readings.data_kind,
        "n_tests": readings.n_tests,
        "n_readings": int(readings.test_index.size),
        "variables_measured": list(readings.measured),
        "notes": list(readings.notes),
        "holdout": {"strategy": holdout.strategy, "why": holdout.why,
                    "n_held_out_readings": int(holdout.held_out.sum()),
                    "n_readings": int(readings.test_index.size)},
        "criterion": _criterion_text(settings),
        "noise_model": settings.noise_model,
        "baseline": {
            "model": "Archard V = k(p, v) F s",
            "coefficient_model": level_model.kind,
            "coefficient_reason": level_model.reason,
            "network_note": _test_conditions(readings)[3],
            "held_out_error": baseline_score.rms,
            "training_error": _rms(baseline_fit.residuals),
            "aicc": aicc(baseline_fit.residuals, readings.n_tests),
            "k_per_test_m2_N": dict(zip(readings.test_labels, _k_per_test(readings,
                                                                          baseline_fit))),
            "config": wear_section(baseline_network),
        },
        "candidates": candidates,
        "untestable": untestable,
        "cause": cause,
        "cause_meaning": CATALOGUE[cause].meaning if cause in CATALOGUE else
        "plain Archard explains the data within their noise",
        "confounded": confounded,
        "gain": gain,
        "held_out_error": {"baseline": baseline_score.rms, "extended": extended_score.rms},
        "prediction": _prediction(problem, baseline_fit, extended_fit, settings),
        "residual_structure": structure,
        "extended_config": extended_section,
    }
    return Diagnosis(readings, settings, holdout, baseline_fit, baseline_score, extended_fit,
                     extended_score, fits, scores, cause, summary, extended_section)


def predict_volume_m3(fit: Fit, readings: Readings, test: int, distance_m) -> np.ndarray:
    """Wear volume of test ``test`` after sliding ``distance_m`` under ``fit`` (the test's level
    times the effective distance at the test's own speed and frictional power)."""
    s = np.asarray(distance_m, float)
    rows = readings.test_index == test
    t = None
    if readings.time_s is not None:
        t = s * np.sum(readings.time_s[rows]) / np.sum(readings.distance_m[rows])
    power = readings.power_W_m2
    q = None if power is None else float(np.mean(power[rows]))
    return np.exp(fit.levels[test]) * fit.extension.effective_distance_m(s, t, q)


def _rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(values**2)))


def _k_per_test(readings: Readings, fit: Fit) -> list[float]:
    load = _test_conditions(readings)[2]
    return [float(k) for k in np.exp(fit.levels) / load]


def _criterion_text(settings: DiagnoseSettings) -> str:
    return (f"paired standard-error rule on held-out tests: accepted when the mean per-test "
            f"reduction of the held-out squared error exceeds {settings.significance_z:g} "
            f"standard error(s), the held-out RMS error falls by at least "
            f"{settings.min_gain:.0%} and the AICc on all readings by more than "
            f"{settings.min_aicc_improvement:g}; among accepted candidates (two parameters each) "
            "the cause is the one with the smallest AICc")


def _candidate_entry(name, fit: Fit, sc: Score, base: Score, base_fit: Fit,
                     settings: DiagnoseSettings) -> dict[str, Any]:
    z = paired_z(sc.per_test, base.per_test)
    gain = 1.0 - sc.rms / base.rms
    n_levels = fit.levels.size
    aicc_candidate = aicc(fit.residuals, n_levels + 2)
    aicc_baseline = aicc(base_fit.residuals, n_levels)
    fits_better = aicc_candidate < aicc_baseline - settings.min_aicc_improvement
    accepted = bool(z > settings.significance_z and gain >= settings.min_gain and fits_better)
    if accepted:
        verdict = "accepted: its held-out improvement stands above the noise"
    elif not fits_better and gain >= settings.min_gain:
        verdict = (f"rejected: AICc {aicc_candidate - aicc_baseline:+.1f} against the baseline "
                   f"(needs below -{settings.min_aicc_improvement:g}): two parameters more are "
                   "not worth their fit")
    elif gain < settings.min_gain:
        change = f"reduced by {gain:.0%}" if gain > 0 else f"not reduced ({-gain:+.0%})"
        verdict = (f"rejected: held-out error {change} (needs a reduction of at least "
                   f"{settings.min_gain:.0%})")
    else:
        verdict = (f"rejected: held-out improvement only {z:.1f} standard errors (needs "
                   f"{settings.significance_z:g}): it fits noise")
    return {
        "name": name,
        "meaning": CATALOGUE[name].meaning,
        "params": fit.extension.params(),
        "held_out_error": sc.rms,
        "gain": gain,
        "score": z,
        "accepted": accepted,
        "verdict": verdict,
        "training_error": _rms(fit.residuals),
        "aicc": aicc_candidate,
        "aicc_baseline": aicc_baseline,
    }


def _confounded(cause: str, accepted: list[dict], scores: dict[str, Score],
                readings: Readings, settings: DiagnoseSettings) -> list[dict[str, Any]]:
    """Accepted candidates that neither the held-out errors nor the AICc tell from the cause."""
    if cause == "none":
        return []
    best = next(entry for entry in accepted if entry["name"] == cause)
    others = []
    for entry in accepted:
        if entry["name"] == cause:
            continue
        z = paired_z(scores[cause].per_test, scores[entry["name"]].per_test)
        if not z > settings.confound_z and entry["aicc"] - best["aicc"] < settings.aicc_separation:
            others.append((entry, z))
    if not others:
        return []
    names = [cause] + [entry["name"] for entry, _ in others]
    reason = _structural_reason(readings, set(names))
    return [{
        "causes": names,
        "reason": reason or (f"their held-out errors differ by less than {settings.confound_z:g} "
                             f"standard errors and their AICc by less than "
                             f"{settings.aicc_separation:g}"),
        "held_out_z_between": {entry["name"]: z for entry, z in others},
        "aicc_difference": {entry["name"]: entry["aicc"] - best["aicc"] for entry, _ in others},
        "evidence": {e["name"]: {"held_out_error": e["held_out_error"], "score": e["score"],
                                 "gain": e["gain"], "aicc": e["aicc"], "params": e["params"]}
                     for e in [best] + [entry for entry, _ in others]},
        "to_separate": "tests at different sliding speeds (with distance and time both read)"
        if {"running_in", "time_transient"} <= set(names)
        else "tests that vary the variable that drives one cause but not the other",
    }]


def _structural_reason(readings: Readings, names: set[str]) -> str:
    if {"running_in", "time_transient"} <= names and readings.velocity_m_s is not None:
        v = readings.per_test(readings.velocity_m_s)
        if v.max() / v.min() < 1.2:
            return (f"all tests at one speed (v from {v.min():.3g} to {v.max():.3g} m/s): sliding "
                    "distance and time are proportional, so running_in (over distance) and "
                    "time_transient (over time) predict the same curves")
        return (f"speeds from {v.min():.3g} to {v.max():.3g} m/s do not separate the two within "
                "the noise")
    return ""


def _prediction(problem: Problem, baseline: Fit, extended: Fit,
                settings: DiagnoseSettings) -> dict[str, Any]:
    """Wear predicted by baseline and extended model (both fitted on all readings) after each
    test's own final distance (and time) multiplied by ``prediction_distance_factor``."""
    r = problem.readings
    factor = settings.prediction_distance_factor
    s = factor * r.final_per_test(r.distance_m)
    t = None if r.time_s is None else factor * r.final_per_test(r.time_s)
    q = None if problem.power is None else r.per_test(problem.power)
    base = np.exp(baseline.levels) * s
    ext = np.exp(extended.levels) * extended.extension.effective_distance_m(s, t, q)
    ratio = ext / base
    return {
        "distance_factor": factor,
        "what": f"wear volume after {factor:g} x each test's own sliding distance",
        "per_test": {label: {"distance_m": float(si), "baseline_m3": float(b),
                             "extended_m3": float(e), "extended_over_baseline": float(x)}
                     for label, si, b, e, x in zip(r.test_labels, s, base, ext, ratio)},
        "median_extended_over_baseline": float(np.median(ratio)),
        "range_extended_over_baseline": [float(ratio.min()), float(ratio.max())],
    }
