"""The readings the tribometer diagnosis fits: the measured table's columns in SI units, the
readings without information on the rate left out, and what was derived from what."""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property
from typing import Any

import numpy as np

NO_GROUP = "all tests"


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
    left_out: tuple[int, int, int] = (0, 0, 0)
    """Readings left out: (with zero sliding distance, with zero or negative wear, all)."""

    def why_left_out(self) -> str:
        """Why readings were left out, for a message ("" when none were)."""
        no_distance, no_wear, total = self.left_out
        if not total:
            return ""
        return (f"({total} reading(s) left out: {no_distance} with zero sliding distance, "
                f"{no_wear} with zero or negative wear volume; both are needed for a rate)")

    @property
    def n_tests(self) -> int:
        return len(self.test_labels)

    def per_test(self, values: np.ndarray) -> np.ndarray:
        """Mean of a per-reading array over each test."""
        counts = np.bincount(self.test_index, minlength=self.n_tests)
        return np.bincount(self.test_index, weights=values, minlength=self.n_tests) / counts

    def final_per_test(self, values: np.ndarray) -> np.ndarray:
        """The value at each test's longest sliding distance."""
        return np.asarray(values)[self.final_rows]

    @cached_property
    def final_rows(self) -> np.ndarray:
        """Each test's reading at its longest sliding distance (the first of equal ones): one
        sort, not a scan of the readings per test (a table of thousands of tests)."""
        rows = np.arange(self.test_index.size)
        order = np.lexsort((-rows, self.distance_m, self.test_index))
        last = np.flatnonzero(np.diff(np.append(self.test_index[order], self.n_tests)) != 0)
        return order[last]

    @property
    def power_W_m2(self) -> np.ndarray | None:
        """Frictional power mu p v per reading, with each test's mean mu (constant in a test)."""
        if self.friction is None or self.velocity_m_s is None or self.pressure_Pa is None:
            return None
        mu = self.per_test(self.friction)[self.test_index]
        return mu * self.pressure_Pa * self.velocity_m_s

    @cached_property
    def campaign_scales(self) -> dict[str, float | None]:
        """The laws' scales: the median final distance [m] and time [s], the largest mu p v
        [W/m^2] (None without it); computed once (a prediction per test reads them)."""
        power = self.power_W_m2
        return {
            "scale_distance_m": float(np.median(self.final_per_test(self.distance_m))),
            "scale_time_s": None if self.time_s is None
            else float(np.median(self.final_per_test(self.time_s))),
            "scale_power_W_m2": None if power is None else float(np.max(power)),
        }

    @property
    def load_variable(self) -> tuple[np.ndarray | None, str]:
        """What the level laws read: the pressure [Pa] when measured, else the normal load [N]."""
        if self.pressure_Pa is not None:
            return self.pressure_Pa, "pressure"
        return self.load_N, "normal load"

    def test_groups(self) -> tuple[np.ndarray, tuple[str, ...]]:
        """Each test's material group (index) and the groups' labels, in order of appearance."""
        first = np.full(self.n_tests, self.test_index.size)
        np.minimum.at(first, self.test_index, np.arange(self.test_index.size))
        labels_per_test = [str(label) for label in self.group_labels[first]]
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
    labels, first_row, index = np.unique(np.asarray(columns["test_id"]).astype(str),
                                         return_index=True, return_inverse=True)
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
        left_out=(int(np.sum(~(s > 0.0))), int(np.sum(~(volume > 0.0))), int(np.sum(~keep))),
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
