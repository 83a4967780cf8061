"""Forward models: synthetic pin-on-disc campaigns with a hidden departure from Archard's law.

A campaign is a set of tests at pressures p [Pa] and sliding speeds v [m/s] (pin of area A, load
F = p A, friction coefficient mu per test), each read at cumulative sliding distances s [m] (time
t = s / v): either *histories* (every test read ``readings_per_test`` times) or a *table* (a
design of experiments: one reading per test, the tests of each condition stopped at different
distances). The wear volume of a reading is

.. math::  V = F\\, k\\, m_{level}(p, q)\\, \\epsilon_{test}\\, S_{eff}(s, t, q)
           \\, (1 + \\sigma_r \\epsilon_{reading}),

with k = K_BASE_m2_N (plain Archard: one k), S_eff the effective distance of a hidden shape
extension (:mod:`fewear.wear.extensions`; S_eff = s for plain Archard), m_level a hidden level law
(:class:`LoadPower`, :class:`SevereAbove`) and scatter of three kinds: a
lognormal per-test factor on k (test-to-test scatter), optional lognormal scatter of the wear of
each interval between readings (wear scattered interval by interval), and independent relative
noise of each cumulative reading (weighing, profilometry; readings that dip below the previous one
are kept, as an instrument gives them). These data are the questions the diagnosis must answer
without being told the answer.

:func:`random_effect` draws an effect's parameters across a physical range, with the transients'
length a given fraction of the test (``effect_scale``), so that a sweep covers short and long
effects alike.
"""

from __future__ import annotations

import csv
import math
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fewear.wear.extensions import (
    NoExtension,
    RunningIn,
    RunningInPowerLaw,
    Thermal,
    TimeTransient,
    WearExtension,
)

K_BASE_m2_N = 2.0e-13
"""Wear coefficient of plain Archard: brass on hardened steel, dimensionless Archard K about 5e-4
at 235 HB (REFERENCES.md)."""

CAUSES = ("none", "running_in", "time_transient", "thermal", "load_exponent", "mild_to_severe")


@dataclass(frozen=True)
class LoadPower:
    """m = (p / reference)^(exponent - 1): wear grows as p^exponent."""

    exponent: float
    reference_Pa: float

    def multiplier(self, pressure_Pa, power_W_m2):
        return (pressure_Pa / self.reference_Pa) ** (self.exponent - 1.0)


@dataclass(frozen=True)
class SevereAbove:
    """m = jump above ``threshold_Pa``, 1 below (a mild-to-severe step in pressure)."""

    jump: float
    threshold_Pa: float

    def multiplier(self, pressure_Pa, power_W_m2):
        return np.where(pressure_Pa > self.threshold_Pa, self.jump, 1.0)


LevelLaw = LoadPower | SevereAbove


@dataclass(frozen=True)
class Campaign:
    """A pin-on-disc test campaign (what was run, not what was measured).

    ``pressure_Pa``, ``velocity_m_s``: one entry per test, in test order; ``stop_fraction``: each
    test's final distance as a fraction of ``final_distance_m`` (None: all run the full
    distance). Every test is read ``readings_per_test`` times, evenly spaced up to its final
    distance (``spacing`` "uniform", a tribometer logging every so many metres) or geometrically
    from ``first_reading_fraction`` of it ("geometric", denser early).
    ``reading_scatter``: relative noise of each cumulative reading (standard deviation);
    ``interval_scatter``: standard deviation of ln of the wear of each interval between readings;
    ``test_scatter``: of ln k per test; ``friction_coefficient``: nominal mu, each test's mu it
    times a lognormal factor of standard deviation ``friction_scatter``.
    """

    pressure_Pa: tuple[float, ...]
    velocity_m_s: tuple[float, ...]
    stop_fraction: tuple[float, ...] | None = None
    final_distance_m: float = 2000.0
    readings_per_test: int = 10
    spacing: str = "uniform"
    first_reading_fraction: float = 1.0 / 40.0
    pin_diameter_m: float = 6.0e-3
    friction_coefficient: float = 0.3
    friction_scatter: float = 0.1
    interval_scatter: float = 0.0
    reading_scatter: float = 0.03
    test_scatter: float = 0.10

    def __post_init__(self):
        if len(self.pressure_Pa) != len(self.velocity_m_s) or len(self.pressure_Pa) < 1:
            raise ValueError("pressure_Pa and velocity_m_s: one entry per test, at least one test")
        if min(self.pressure_Pa) <= 0.0 or min(self.velocity_m_s) <= 0.0:
            raise ValueError("pressures and velocities must be positive")
        if self.readings_per_test < 1 or self.final_distance_m <= 0.0:
            raise ValueError("need at least one reading and a positive final distance")
        if self.spacing not in ("uniform", "geometric"):
            raise ValueError(f"spacing {self.spacing!r}: expected 'uniform' or 'geometric'")

    @property
    def n_tests(self) -> int:
        return len(self.pressure_Pa)

    @property
    def pin_area_m2(self) -> float:
        return math.pi * self.pin_diameter_m**2 / 4.0

    def reading_distances_m(self, test: int = 0) -> np.ndarray:
        final = self.final_distance_m * (1.0 if self.stop_fraction is None
                                         else self.stop_fraction[test])
        n = self.readings_per_test
        if self.spacing == "uniform":
            return final * np.arange(1, n + 1) / n
        return final * np.geomspace(self.first_reading_fraction if n > 1 else 1.0, 1.0, n)


def grid_campaign(
    pressures_Pa=(1.0e6, 2.0e6, 4.0e6),
    velocities_m_s=(0.2, 0.5, 1.2),
    *,
    rng: np.random.Generator | None = None,
    **options,
) -> Campaign:
    """Histories: every pressure with every speed, one test each, in a shuffled order when
    ``rng`` is given (a real campaign's order, so that drifts do not line up with a variable)."""
    matrix = [(p, v) for p in pressures_Pa for v in velocities_m_s]
    order = rng.permutation(len(matrix)) if rng is not None else range(len(matrix))
    return Campaign(pressure_Pa=tuple(matrix[i][0] for i in order),
                    velocity_m_s=tuple(matrix[i][1] for i in order), **options)


def table_campaign(
    pressures_Pa=(1.0e6, 2.0e6, 4.0e6),
    velocities_m_s=(0.3, 1.0),
    stop_fractions=(0.25, 0.5, 0.75, 1.0),
    *,
    rng: np.random.Generator | None = None,
    **options,
) -> Campaign:
    """A design of experiments: every pressure x speed x sliding distance, one test each with a
    single reading at its end (shuffled order when ``rng`` is given)."""
    matrix = [(p, v, f) for p in pressures_Pa for v in velocities_m_s for f in stop_fractions]
    order = rng.permutation(len(matrix)) if rng is not None else range(len(matrix))
    return Campaign(pressure_Pa=tuple(matrix[i][0] for i in order),
                    velocity_m_s=tuple(matrix[i][1] for i in order),
                    stop_fraction=tuple(matrix[i][2] for i in order), readings_per_test=1,
                    **options)


def simulate_campaign(
    effect: WearExtension | LevelLaw, campaign: Campaign, rng: np.random.Generator
) -> dict[str, np.ndarray]:
    """The measured table of ``campaign`` with ``effect`` hidden in it: columns of the CSV schema
    (test_id, pressure_Pa, velocity_m_s, sliding_distance_m, wear_volume_m3, time_s, normal_load_N,
    friction_coefficient), one row per reading (module docstring for the law and the scatter)."""
    columns: dict[str, list] = {name: [] for name in CSV_COLUMNS}
    for number, (p, v) in enumerate(zip(campaign.pressure_Pa, campaign.velocity_m_s), start=1):
        s = campaign.reading_distances_m(number - 1)
        load_N = p * campaign.pin_area_m2
        mu = campaign.friction_coefficient * np.exp(campaign.friction_scatter
                                                    * rng.standard_normal())
        k_test = K_BASE_m2_N * np.exp(campaign.test_scatter * rng.standard_normal())
        t = s / v
        if isinstance(effect, (LoadPower, SevereAbove)):
            k_test = k_test * float(effect.multiplier(p, mu * p * v))
            effective = s
        else:
            effective = effect.effective_distance_m(s, t, mu * p * v)
        intervals = np.diff(effective, prepend=0.0) * np.exp(
            campaign.interval_scatter * rng.standard_normal(s.size))
        noise = 1.0 + campaign.reading_scatter * rng.standard_normal(s.size)
        volume = load_N * k_test * np.cumsum(intervals) * noise
        columns["test_id"] += [f"T{number:02d}"] * s.size
        columns["pressure_Pa"] += [p] * s.size
        columns["velocity_m_s"] += [v] * s.size
        columns["sliding_distance_m"] += list(s)
        columns["wear_volume_m3"] += list(volume)
        columns["time_s"] += list(t)
        columns["normal_load_N"] += [load_N] * s.size
        columns["friction_coefficient"] += [mu] * s.size
    return {name: np.array(values) for name, values in columns.items()}


CSV_COLUMNS = ("test_id", "pressure_Pa", "velocity_m_s", "sliding_distance_m", "wear_volume_m3",
               "time_s", "normal_load_N", "friction_coefficient")


def random_effect(cause: str, campaign: Campaign, rng: np.random.Generator,
                  effect_scale: float = 0.1) -> WearExtension | LevelLaw:
    """An effect of kind ``cause`` with parameters drawn across a physical range.

    - ``running_in``: exponential or power-law (hyperbolic) form with equal odds; k_initial /
      k_steady log-uniform in [3, 8] (break-in wear rates of metals are several times the steady
      rate, Blau 2005); distance scale s0 = ``effect_scale`` x the final distance, times a
      log-uniform factor in [0.7, 1.4].
    - ``time_transient``: the same ratio; time scale tau such that v_mean tau is the running-in's
      distance scale (v_mean the campaign's geometric-mean speed).
    - ``thermal``: beta such that beta x (largest mu p v) is uniform in [2, 5] (k several times
      higher in the hottest test, Lim & Ashby 1987); thermal time constant ``effect_scale`` x the
      duration of the fastest test.
    - ``load_exponent``: wear grows as p^a, a uniform in [0.5, 0.8] or [1.3, 1.8] with equal odds
      (Rhee 1970).
    - ``mild_to_severe``: k jumps by a factor uniform in [3, 8] above a pressure log-uniform
      between the campaign's lowest and highest pressure (Lim & Ashby 1987).
    - ``none``: plain Archard.
    """
    v = np.array(campaign.velocity_m_s)
    p = np.array(campaign.pressure_Pa)
    ratio = float(np.exp(rng.uniform(np.log(3.0), np.log(8.0))))
    scale = effect_scale * float(np.exp(rng.uniform(np.log(0.7), np.log(1.4))))
    if cause == "none":
        return NoExtension()
    if cause == "running_in":
        form = RunningIn if rng.uniform() < 0.5 else RunningInPowerLaw
        return form(ratio, scale * campaign.final_distance_m)
    if cause == "time_transient":
        mean_speed = float(np.exp(np.mean(np.log(v))))
        return TimeTransient(ratio, scale * campaign.final_distance_m / mean_speed)
    if cause == "thermal":
        hottest = campaign.friction_coefficient * float(np.max(p * v))
        tau = scale * campaign.final_distance_m / float(np.max(v))
        return Thermal(float(rng.uniform(2.0, 5.0)) / hottest, tau)
    if cause == "load_exponent":
        band = (0.5, 0.8) if rng.uniform() < 0.5 else (1.3, 1.8)
        return LoadPower(float(rng.uniform(*band)), float(np.exp(np.mean(np.log(p)))))
    if cause == "mild_to_severe":
        levels = np.unique(p)
        threshold = float(np.exp(rng.uniform(np.log(levels[0]), np.log(levels[-1]))))
        return SevereAbove(float(rng.uniform(3.0, 8.0)), threshold)
    raise ValueError(f"unknown cause {cause!r}; expected one of {CAUSES}")


def write_measured_csv(path: str | Path, columns: dict[str, np.ndarray], header: str) -> None:
    """Write a table in the measured-data CSV schema (other columns, e.g. ``material``, after
    the schema's); ``header`` lines are written as # comments."""
    with open(path, "w", newline="") as handle:
        for line in header.strip("\n").splitlines():
            handle.write(f"# {line}".rstrip() + "\n")
        writer = csv.writer(handle, lineterminator="\n")
        names = ([name for name in CSV_COLUMNS if name in columns]
                 + [name for name in columns if name not in CSV_COLUMNS])
        writer.writerow(names)
        for row in zip(*(columns[name] for name in names)):
            writer.writerow([value if isinstance(value, str) else f"{value:.6g}" for value in row])


def hidden_case(
    cause: str, seed: int, campaign: Campaign | None = None, effect_scale: float = 0.1
) -> tuple[dict[str, np.ndarray], WearExtension | LevelLaw, Campaign]:
    """A synthetic data set with ``cause`` hidden in it: (columns, the hidden effect, campaign).

    ``campaign`` defaults to :func:`grid_campaign` (3 pressures x 3 speeds, shuffled, 10 readings
    per test, 3 % noise per reading); ``numpy.random.default_rng(seed)`` draws the test order,
    the effect's parameters (:func:`random_effect`) and the scatter, in that order.
    """
    rng = np.random.default_rng(seed)
    campaign = campaign if campaign is not None else grid_campaign(rng=rng)
    effect = random_effect(cause, campaign, rng, effect_scale)
    return simulate_campaign(effect, campaign, rng), effect, campaign

