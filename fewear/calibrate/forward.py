"""Forward models: synthetic pin-on-disc histories with a hidden departure from Archard's law.

A campaign is a matrix of tests at pressures p [Pa] and sliding speeds v [m/s] (pin of area A, load
F = p A, friction coefficient mu per test), each read at cumulative sliding distances s [m] (time
t = s / v). The wear volume of a reading is

.. math::  V = F\\, k_b(p, v)\\, \\epsilon_{test}\\, S_{eff}(s, t, \\mu p v)\\, \\epsilon_{reading},

with k_b(p, v) the smooth base law :func:`base_wear_coefficient_m2_N`, S_eff the effective distance
of the hidden extension (:mod:`fewear.wear.extensions`; S_eff = s for plain Archard) and lognormal
scatter of three kinds: a per-test factor on k (test-to-test scatter, which a per-condition k(p, v)
absorbs); a factor on the wear of each interval between readings (wear is itself a scattered
process; the readings stay cumulative and never decrease, as a real table's must); a small factor
per reading (weighing and density errors). The interval scatter makes the scatter of the cumulative
readings correlated along a test, as in real histories; with the default 0.25 per interval and the
geometric reading spacing the cumulative readings scatter by about 12 %. These data are the
questions the diagnosis must answer without being told the answer.

:func:`random_extension` draws an extension's parameters across a physical range (documented
there), so that a test over many seeds covers weak and strong effects alike.
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
    Thermal,
    TimeTransient,
    WearExtension,
)

K_BASE_m2_N = 2.0e-13
"""Base wear coefficient at P_REF_Pa, V_REF_m_s: brass on hardened steel, dimensionless Archard
K about 5e-4 at 235 HB (REFERENCES.md)."""
P_REF_Pa = 2.0e6
V_REF_m_s = 0.5
PRESSURE_EXPONENT = 0.2
VELOCITY_EXPONENT = -0.1

CAUSES = ("none", "running_in", "time_transient", "thermal")


def base_wear_coefficient_m2_N(pressure_Pa, velocity_m_s) -> np.ndarray:
    """k_b(p, v) = K_BASE (p / P_REF)^0.2 (v / V_REF)^-0.1, a smooth Archard-type power law."""
    p = np.asarray(pressure_Pa, float)
    v = np.asarray(velocity_m_s, float)
    return K_BASE_m2_N * (p / P_REF_Pa) ** PRESSURE_EXPONENT * (v / V_REF_m_s) ** VELOCITY_EXPONENT


@dataclass(frozen=True)
class Campaign:
    """A pin-on-disc test campaign (what was run, not what was measured).

    ``pressure_Pa``, ``velocity_m_s``: one entry per test, in test order. Every test slides to
    ``final_distance_m`` with ``readings_per_test`` cumulative readings spaced geometrically from
    ``first_reading_fraction`` x the final distance (denser early, where transients are: the usual
    practice of a running-in study).
    ``interval_scatter``, ``reading_scatter`` and ``test_scatter``: standard deviations of ln of the
    wear of an interval between readings, of ln V per reading and of ln k per test.
    ``friction_coefficient``: nominal mu; each test's mu is it times a lognormal factor of standard
    deviation ``friction_scatter``.
    """

    pressure_Pa: tuple[float, ...]
    velocity_m_s: tuple[float, ...]
    final_distance_m: float = 2000.0
    readings_per_test: int = 10
    first_reading_fraction: float = 1.0 / 40.0
    pin_diameter_m: float = 6.0e-3
    friction_coefficient: float = 0.3
    friction_scatter: float = 0.1
    interval_scatter: float = 0.25
    reading_scatter: float = 0.02
    test_scatter: float = 0.10

    def __post_init__(self):
        if len(self.pressure_Pa) != len(self.velocity_m_s) or len(self.pressure_Pa) < 1:
            raise ValueError("pressure_Pa and velocity_m_s: one entry per test, at least one test")
        if min(self.pressure_Pa) <= 0.0 or min(self.velocity_m_s) <= 0.0:
            raise ValueError("pressures and velocities must be positive")
        if self.readings_per_test < 1 or self.final_distance_m <= 0.0:
            raise ValueError("need at least one reading and a positive final distance")

    @property
    def n_tests(self) -> int:
        return len(self.pressure_Pa)

    @property
    def pin_area_m2(self) -> float:
        return math.pi * self.pin_diameter_m**2 / 4.0

    def reading_distances_m(self) -> np.ndarray:
        fractions = np.geomspace(self.first_reading_fraction, 1.0, self.readings_per_test)
        return self.final_distance_m * fractions


def grid_campaign(
    pressures_Pa=(1.0e6, 2.0e6, 4.0e6),
    velocities_m_s=(0.2, 0.5, 1.2),
    *,
    rng: np.random.Generator | None = None,
    **options,
) -> Campaign:
    """Every pressure with every speed, one test each, in a shuffled order when ``rng`` is given
    (a real campaign's order, so that drifts do not line up with a variable)."""
    matrix = [(p, v) for p in pressures_Pa for v in velocities_m_s]
    order = rng.permutation(len(matrix)) if rng is not None else range(len(matrix))
    return Campaign(
        pressure_Pa=tuple(matrix[i][0] for i in order),
        velocity_m_s=tuple(matrix[i][1] for i in order),
        **options,
    )


def simulate_campaign(
    extension: WearExtension, campaign: Campaign, rng: np.random.Generator
) -> dict[str, np.ndarray]:
    """The measured table of ``campaign`` with ``extension`` hidden in it: columns of the CSV schema
    (test_id, pressure_Pa, velocity_m_s, sliding_distance_m, wear_volume_m3, time_s, normal_load_N,
    friction_coefficient), one row per reading (module docstring for the law and the scatter)."""
    s = campaign.reading_distances_m()
    columns: dict[str, list] = {name: [] for name in CSV_COLUMNS}
    for number, (p, v) in enumerate(zip(campaign.pressure_Pa, campaign.velocity_m_s), start=1):
        load_N = p * campaign.pin_area_m2
        k_test = base_wear_coefficient_m2_N(p, v) * np.exp(campaign.test_scatter
                                                            * rng.standard_normal())
        mu = campaign.friction_coefficient * np.exp(campaign.friction_scatter
                                                    * rng.standard_normal())
        t = s / v
        effective = extension.effective_distance_m(s, t, mu * p * v)
        intervals = np.diff(effective, prepend=0.0) * np.exp(
            campaign.interval_scatter * rng.standard_normal(s.size))
        noise = np.exp(campaign.reading_scatter * rng.standard_normal(s.size))
        volume = load_N * k_test * np.maximum.accumulate(np.cumsum(intervals) * noise)
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


def random_extension(cause: str, campaign: Campaign, rng: np.random.Generator) -> WearExtension:
    """An extension of kind ``cause`` with parameters drawn across a physical range.

    - ``running_in``: k_initial / k_steady log-uniform in [3, 8] (break-in wear rates of metals
      are several times the steady rate, Blau 2005); distance scale s0 log-uniform in
      [0.04, 0.2] x the final distance (a few tens to a few hundred metres of a 2 km test).
    - ``time_transient``: the same ratio; time scale tau log-uniform in [0.04, 0.2] x the final
      distance / the campaign's geometric-mean speed (so the transient is seen in most tests).
    - ``thermal``: beta such that beta x (largest mu p v of the campaign) is uniform in [2, 5]
      (k several times higher in the hottest test: heating-driven wear rates several times the
      mild rate are common at high pv, Lim & Ashby 1987); thermal time constant log-uniform in
      [0.05, 0.3] x the duration of the fastest test (a pin heats up over one to a few minutes).
    - ``none``: plain Archard.
    """
    if cause == "none":
        return NoExtension()
    v = np.array(campaign.velocity_m_s)
    p = np.array(campaign.pressure_Pa)
    ratio = float(np.exp(rng.uniform(np.log(3.0), np.log(8.0))))
    fraction = float(np.exp(rng.uniform(np.log(0.04), np.log(0.2))))
    if cause == "running_in":
        return RunningIn(ratio, fraction * campaign.final_distance_m)
    if cause == "time_transient":
        mean_speed = float(np.exp(np.mean(np.log(v))))
        return TimeTransient(ratio, fraction * campaign.final_distance_m / mean_speed)
    if cause == "thermal":
        hottest = campaign.friction_coefficient * float(np.max(p * v))
        fastest_duration = campaign.final_distance_m / float(np.max(v))
        tau = float(np.exp(rng.uniform(np.log(0.05), np.log(0.3)))) * fastest_duration
        return Thermal(float(rng.uniform(2.0, 5.0)) / hottest, tau)
    raise ValueError(f"unknown cause {cause!r}; expected one of {CAUSES}")


def write_measured_csv(path: str | Path, columns: dict[str, np.ndarray], header: str) -> None:
    """Write a table in the measured-data CSV schema; ``header`` lines are written as # comments."""
    with open(path, "w", newline="") as handle:
        for line in header.strip("\n").splitlines():
            handle.write(f"# {line}".rstrip() + "\n")
        writer = csv.writer(handle, lineterminator="\n")
        names = [name for name in CSV_COLUMNS if name in columns]
        writer.writerow(names)
        for row in zip(*(columns[name] for name in names)):
            writer.writerow([value if isinstance(value, str) else f"{value:.6g}" for value in row])


def hidden_case(
    cause: str, seed: int, campaign: Campaign | None = None
) -> tuple[dict[str, np.ndarray], WearExtension, Campaign]:
    """A synthetic data set with ``cause`` hidden in it: (columns, the hidden extension, campaign).

    ``campaign`` defaults to :func:`grid_campaign` (3 pressures x 3 speeds, shuffled);
    ``numpy.random.default_rng(seed)`` draws the test order, the extension's parameters
    (:func:`random_extension`) and the scatter, in that order.
    """
    rng = np.random.default_rng(seed)
    campaign = campaign if campaign is not None else grid_campaign(rng=rng)
    extension = random_extension(cause, campaign, rng)
    return simulate_campaign(extension, campaign, rng), extension, campaign
