"""Measured wear from tribometer tests (pin-on-disc), read from CSV into plain arrays: one row per
reading, cumulative within a test, SI units in the column names, ``test_id, pressure_Pa,
velocity_m_s, sliding_distance_m, wear_volume_m3 [, time_s, normal_load_N, friction_coefficient,
temperature_C, material, factor_*]``; mass loss, specific wear rate or wear per metre converted
on reading. The full rules, and what is refused: docs/diagnosis-method-notes.md (input files)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.csv_rows import numeric_column, read_rows

DATA_KINDS = ("cumulative_volume", "mass_loss", "specific_wear_rate", "wear_rate")
VARIABLES = ("pressure_Pa", "velocity_m_s", "sliding_distance_m", "wear_volume_m3", "time_s",
             "normal_load_N", "friction_coefficient", "temperature_C")
"""The measured variables of :class:`MeasuredWear`, in the order :attr:`available` lists them."""
WEAR_COLUMNS = {"wear_volume_m3": "cumulative_volume", "mass_loss_kg": "mass_loss",
                "specific_wear_rate_m3_N_m": "specific_wear_rate", "wear_rate_m3_m": "wear_rate"}
COLUMNS = ("test_id",) + VARIABLES + ("mass_loss_kg", "density_kg_m3", "specific_wear_rate_m3_N_m",
                                      "wear_rate_m3_m", "material")
FACTOR_PREFIX = "factor_"
"""Columns named factor_<name> hold a categorical factor (text), like ``material``."""
ONE_ROW_PER_TEST = ("specific_wear_rate", "wear_rate")
POSITIVE = {"pressure_Pa", "velocity_m_s", "normal_load_N", "density_kg_m3"}
CUMULATIVE = ("sliding_distance_m", "time_s")
WEAR_AMOUNTS = ("wear_volume_m3", "mass_loss_kg")
ABSOLUTE_ZERO_C = -273.15
PLAUSIBLE_RANGE = {
    "wear_volume_m3": (0.0, 1e-4, "|V| up to 100 cm^3, more than a whole pin"),
    "mass_loss_kg": (0.0, 1.0, "|m| up to 1 kg, more than a whole pin"),
    "specific_wear_rate_m3_N_m": (0.0, 1e-9, "up to 1e3 mm^3/(N m), beyond the severest wear"),
    "wear_rate_m3_m": (0.0, 1e-6, "up to 1 cm^3 per metre of sliding"),
    "pressure_Pa": (1e2, 1e10, "100 Pa to 10 GPa, beyond the hardest material"),
    "velocity_m_s": (1e-7, 1e3, "0.1 um/s to 1 km/s"),
    "normal_load_N": (1e-6, 1e6, "1 uN (a nanotribometer) to 1 MN"),
    "sliding_distance_m": (0.0, 1e8, "up to 100,000 km"),
    "time_s": (0.0, 1e9, "up to about 30 years"),
    "friction_coefficient": (0.0, 10.0, "0 to 10"),
    "temperature_C": (-273.15, 3000.0, "up to 3000 C, above any metal's melting point"),
    "density_kg_m3": (100.0, 3e4, "100 to 30,000 kg/m^3, osmium's is 22,590"),
}
"""What a tribometer can report (beyond it: a unit mistake): the range of each column's
magnitude and what it means."""

ALIASES = {"sliding_speed_m_s": "velocity_m_s", "speed_m_s": "velocity_m_s",
           "contact_pressure_Pa": "pressure_Pa", "load_N": "normal_load_N",
           "mu": "friction_coefficient", "distance_m": "sliding_distance_m"}
"""Other names of schema columns (same quantity, same SI unit), read as the schema's name."""

UNIT_HINTS = {
    "wear_volume_": "wear_volume_m3 (1 mm^3 = 1e-9 m^3)",
    "volume_": "wear_volume_m3 (1 mm^3 = 1e-9 m^3)",
    "pressure_": "pressure_Pa (1 MPa = 1e6 Pa)",
    "velocity_": "velocity_m_s (1 mm/s = 1e-3 m/s)",
    "speed_": "velocity_m_s",
    "sliding_distance_": "sliding_distance_m (1 km = 1e3 m)",
    "distance_": "sliding_distance_m",
    "mass_loss_": "mass_loss_kg (1 mg = 1e-6 kg)",
    "time_": "time_s (1 h = 3600 s)",
    "normal_load_": "normal_load_N (1 kN = 1e3 N)",
    "load_": "normal_load_N",
    "temperature_": "temperature_C",
    "density_": "density_kg_m3 (1 g/cm^3 = 1e3 kg/m^3)",
    "specific_wear_rate_": "specific_wear_rate_m3_N_m (1 mm^3/(N m) = 1e-9 m^3/(N m))",
    "wear_rate_": "wear_rate_m3_m (1 mm^3/m = 1e-9 m^3/m) or specific_wear_rate_m3_N_m",
}


@dataclass(frozen=True, eq=False)
class MeasuredWear:
    """Wear readings of tribometer tests, one entry per reading, SI units (see module doc).

    ``test_id`` (str array) names each reading's test; a variable that the data lack is ``None``.
    ``wear_volume_m3`` and ``sliding_distance_m`` are cumulative from the start of the test.
    ``line_number`` (int array), when read from a file, is each reading's line in it.
    ``factors``: categorical columns (``material``, ``factor_*``), name -> text per reading.
    """

    source: str
    data_kind: str
    test_id: np.ndarray
    pressure_Pa: np.ndarray | None = None
    velocity_m_s: np.ndarray | None = None
    sliding_distance_m: np.ndarray | None = None
    wear_volume_m3: np.ndarray | None = None
    time_s: np.ndarray | None = None
    normal_load_N: np.ndarray | None = None
    friction_coefficient: np.ndarray | None = None
    temperature_C: np.ndarray | None = None
    notes: tuple[str, ...] = ()
    line_number: np.ndarray | None = None
    factors: dict[str, np.ndarray] = field(default_factory=dict)

    def __post_init__(self):
        if self.data_kind not in DATA_KINDS:
            raise FewearInputError(
                f"{self.source}: data_kind {self.data_kind!r}: expected one of "
                + ", ".join(DATA_KINDS)
            )
        test_id = np.asarray(self.test_id).astype(str)
        if test_id.ndim != 1 or test_id.size == 0:
            raise FewearInputError(f"{self.source}: test_id must be a non-empty list of names")
        object.__setattr__(self, "test_id", test_id)
        object.__setattr__(self, "notes", tuple(self.notes))
        if self.line_number is not None:
            object.__setattr__(self, "line_number", np.asarray(self.line_number, dtype=int))
        where = self._where
        for name in VARIABLES:
            value = getattr(self, name)
            if value is None:
                continue
            array = np.array(value, dtype=float)
            if array.shape != test_id.shape:
                raise FewearInputError(
                    f"{self.source}: {name} has {array.size} values for {test_id.size} readings"
                )
            _check_values(name, array, where)
            array.setflags(write=False)
            object.__setattr__(self, name, array)
        if self.sliding_distance_m is None or self.wear_volume_m3 is None:
            raise FewearInputError(
                f"{self.source}: sliding_distance_m and wear_volume_m3 are required"
            )
        factors = {name: np.asarray(values).astype(str) for name, values in self.factors.items()}
        for name, values in factors.items():
            if values.shape != test_id.shape:
                raise FewearInputError(
                    f"{self.source}: {name} has {values.size} values for {test_id.size} readings")
            _check_constant_factor(name, values, self.tests(), test_id, where)
        object.__setattr__(self, "factors", factors)
        if self.data_kind not in ONE_ROW_PER_TEST:
            for name in CUMULATIVE:
                if getattr(self, name, None) is not None:
                    _check_cumulative(name, getattr(self, name), self.tests(), test_id, where)

    def _where(self, index: int) -> str:
        if self.line_number is not None:
            return f"{self.source} line {self.line_number[index]}"
        return f"{self.source} reading {index}"

    @property
    def available(self) -> tuple[str, ...]:
        """The names of the variables the data hold (of :data:`VARIABLES`)."""
        return tuple(name for name in VARIABLES if getattr(self, name) is not None)

    @property
    def missing(self) -> tuple[str, ...]:
        """The names of the variables the data lack."""
        return tuple(name for name in VARIABLES if getattr(self, name) is None)

    def tests(self) -> list[np.ndarray]:
        """Index arrays of each test's readings (in file order), tests in order of appearance."""
        return _tests(self.test_id)

    def test_names(self) -> list[str]:
        """The test ids in order of appearance (as :meth:`tests`)."""
        return [str(self.test_id[index[0]]) for index in self.tests()]


def read_measured_wear(path: str | Path, *, density_kg_m3: float | None = None) -> MeasuredWear:
    """Read a measured-wear CSV (module doc); convert mass loss or specific wear rate to volume."""
    path = Path(path)
    source = str(path)
    header_line, header, rows = read_rows(path)
    header, alias_notes = _resolve_aliases(header)
    _check_header(source, header_line, header)
    wear_columns = [name for name in header if name in WEAR_COLUMNS]
    if len(wear_columns) != 1:
        found = ", ".join(wear_columns) or "none"
        raise FewearInputError(
            f"{source} line {header_line}: expected exactly one wear column of "
            f"{', '.join(WEAR_COLUMNS)}; found {found}"
        )
    wear_column = wear_columns[0]
    data_kind = WEAR_COLUMNS[wear_column]
    line_number = np.array([line for line, _ in rows], dtype=int)

    def where(index: int) -> str:
        return f"{source} line {line_number[index]}"

    test_id = np.array([row[header.index("test_id")].strip() for _, row in rows])
    for index, name in enumerate(test_id):
        if not name:
            raise FewearInputError(f"{where(index)}, column test_id: empty test name")
    columns, factors = {}, {}
    for name in header:
        cells = [row[header.index(name)] for _, row in rows]
        if is_factor(name):
            factors[name] = _text_column(name, cells, where)
        elif name != "test_id":
            columns[name] = numeric_column(name, cells, where)
            _check_values(name, columns[name], where)
    notes = list(alias_notes)
    if "sliding_distance_m" not in columns:
        _derive_distance(columns, notes)
    tests = _tests(test_id)
    if data_kind in ONE_ROW_PER_TEST:
        _check_one_row_per_test(tests, test_id, where)
        if data_kind == "wear_rate":
            _wear_rate_to_volume(columns, notes)
        else:
            _specific_wear_rate_to_volume(source, header_line, columns, notes)
    else:
        for name in CUMULATIVE:
            if name in columns:
                _check_cumulative(name, columns[name], tests, test_id, where)
        _check_not_all_negative(wear_column, columns[wear_column], tests, test_id, where)
        notes += _dips(columns[wear_column], tests, wear_column)
    if data_kind == "mass_loss":
        _mass_loss_to_volume(source, header_line, columns, density_kg_m3, notes)
    elif density_kg_m3 is not None:
        notes.append(f"The density argument ({density_kg_m3} kg/m^3) was not needed and not used.")
    if "density_kg_m3" in columns and data_kind != "mass_loss":
        notes.append("The density_kg_m3 column was not needed (no mass loss) and not used.")
    return MeasuredWear(
        source=source, data_kind=data_kind, test_id=test_id,
        **{name: columns.get(name) for name in VARIABLES},
        notes=tuple(notes), line_number=line_number, factors=factors,
    )


def is_factor(name: str) -> bool:
    """Whether a column holds a categorical factor (``material`` or ``factor_<name>``)."""
    return name == "material" or (name.startswith(FACTOR_PREFIX) and len(name) > len(FACTOR_PREFIX))


def write_measured_wear(path: str | Path, data: MeasuredWear, *, comment: str = "") -> None:
    """Write ``data`` in the cumulative-volume schema (with ``comment`` as ``#`` header lines)."""
    names = ["test_id"] + list(data.available)
    lines = [f"# {line}".rstrip() for line in comment.splitlines()] if comment else []
    lines.append(",".join(names + list(data.factors)))
    for index in range(data.test_id.size):
        values = [str(data.test_id[index])]
        values += [repr(float(getattr(data, name)[index])) for name in names[1:]]
        values += [str(column[index]) for column in data.factors.values()]
        lines.append(",".join(values))
    Path(path).write_text("\n".join(lines) + "\n")


def wear_coefficient_samples(
    data: MeasuredWear, *, contact_area_m2: float | None = None
) -> tuple[np.ndarray, np.ndarray | None, np.ndarray]:
    """One (p, v, k) sample per test (tests in order of appearance), for fitting k(p, v).

    Archard's law V = k F s with the cumulative readings of a test: k is the least-squares slope
    through the origin of V against F s, k = sum(F s V) / sum((F s)^2) (for a single reading
    k = V / (F s)). The normal force F is ``normal_load_N`` when the data hold it, else
    ``pressure_Pa x contact_area_m2`` (the apparent contact area, e.g. the pin's face, given by the
    caller); without either the coefficient is not computed (error); a median k beyond what
    wear gives is refused (:func:`fewear.diagnose.tribometer.plausibility.check_wear_coefficients`,
    naming the likely unit error). The pressure is
    ``pressure_Pa``, else ``normal_load_N / contact_area_m2``. ``velocity`` is ``None`` when the
    data lack it. Pressure and velocity must be constant within a test.
    """
    force, pressure = _force_and_pressure(data, contact_area_m2)
    product = force * data.sliding_distance_m
    samples_p, samples_v, samples_k = [], [], []
    for index in data.tests():
        name = data.test_id[index[0]]
        samples_p.append(_constant_in_test(data, "pressure_Pa", pressure, index, name))
        if data.velocity_m_s is not None:
            velocity = data.velocity_m_s
            samples_v.append(_constant_in_test(data, "velocity_m_s", velocity, index, name))
        denominator = np.sum(product[index] ** 2)
        if denominator == 0.0:
            raise FewearInputError(
                f"{data.source}: test {name} has no sliding (F s = 0 in every reading); "
                "its wear coefficient is undefined"
            )
        samples_k.append(np.sum(product[index] * data.wear_volume_m3[index]) / denominator)
    velocity = np.array(samples_v) if data.velocity_m_s is not None else None
    from fewear.diagnose.tribometer.plausibility import check_wear_coefficients

    check_wear_coefficients(data, np.array(samples_k))  # refuses a k no wear gives
    return np.array(samples_p), velocity, np.array(samples_k)


def _force_and_pressure(data: MeasuredWear, contact_area_m2: float | None):
    if contact_area_m2 is not None and not (math.isfinite(contact_area_m2) and contact_area_m2 > 0):
        raise FewearInputError(f"contact_area_m2 = {contact_area_m2!r}: expected a positive area")
    force, pressure = data.normal_load_N, data.pressure_Pa
    if force is None and pressure is not None and contact_area_m2 is not None:
        force = pressure * contact_area_m2
    if pressure is None and force is not None and contact_area_m2 is not None:
        pressure = force / contact_area_m2
    if force is None or pressure is None:
        have = ", ".join(name for name in ("normal_load_N", "pressure_Pa")
                         if getattr(data, name) is not None) or "neither"
        raise FewearInputError(
            f"{data.source}: the wear coefficient k = V / (F s) at pressure p needs normal_load_N "
            f"and pressure_Pa, or one of them and the apparent contact area (contact_area_m2); "
            f"the data hold {have}"
        )
    return force, pressure


def _constant_in_test(data, name, values, index, test_name) -> float:
    spread = values[index]
    if np.ptp(spread) > 1e-9 * np.max(np.abs(spread)):
        raise FewearInputError(
            f"{data.source}: {name} varies within test {test_name} ({spread.min():g} to "
            f"{spread.max():g}); one k(p, v) sample per test needs it constant"
        )
    return float(spread[0])


def _resolve_aliases(header: list[str]) -> tuple[list[str], list[str]]:
    renamed = [ALIASES.get(name, name) for name in header]
    notes = [f"column {old} read as {new}" for old, new in zip(header, renamed) if old != new]
    return renamed, notes


def _check_header(source: str, line: int, header: list[str]) -> None:
    for name in header:
        if name not in COLUMNS and not is_factor(name):
            raise FewearInputError(
                f"{source} line {line}, column {name!r}: {_unknown_column(name)}"
            )
    duplicates = sorted({name for name in header if header.count(name) > 1})
    if duplicates:
        raise FewearInputError(f"{source} line {line}: column(s) {', '.join(duplicates)} repeated")
    if "test_id" not in header:
        raise FewearInputError(f"{source} line {line}: missing required column test_id")
    if "sliding_distance_m" not in header and not {"time_s", "velocity_m_s"} <= set(header):
        raise FewearInputError(
            f"{source} line {line}: missing required column sliding_distance_m "
            "(or time_s and velocity_m_s to derive it)"
        )


def _unknown_column(name: str) -> str:
    for prefix, hint in UNIT_HINTS.items():
        if name.startswith(prefix):
            return f"unknown column or unit; fewear reads SI units only: use {hint}"
    return "unknown column; allowed columns: " + ", ".join(COLUMNS)


def _check_values(name: str, values: np.ndarray, where: Callable[[int], str]) -> None:
    """Finite; positive (POSITIVE), above absolute zero (temperature), any sign (a wear volume or
    mass loss: a reading near zero can come out below it, and is data) or non-negative (others)."""
    if name == "temperature_C":
        bad, allowed = ~(values > ABSOLUTE_ZERO_C), "a finite temperature above -273.15 C"
    elif name in WEAR_AMOUNTS:
        bad, allowed = np.zeros(values.shape, bool), "a finite number"
    elif name in POSITIVE:
        bad, allowed = ~(values > 0.0), "a positive number"
    else:
        bad, allowed = ~(values >= 0.0), "a non-negative number"
    bad |= ~np.isfinite(values)
    if name in PLAUSIBLE_RANGE:
        low, high, meaning = PLAUSIBLE_RANGE[name]
        size = np.abs(values) if name in WEAR_AMOUNTS else values
        beyond = ((size > high) | ((size < low) & (size != 0.0))) & ~bad
        if np.any(beyond):
            index = int(np.flatnonzero(beyond)[0])
            hint = next((hint for prefix, hint in UNIT_HINTS.items() if name.startswith(prefix)),
                        name)
            raise FewearInputError(
                f"{where(index)}, column {name}: {values[index]!r} is beyond what a pin-on-disc "
                f"test gives ({meaning}); SI units: {hint}")
    if np.any(bad):
        index = int(np.flatnonzero(bad)[0])
        raise FewearInputError(
            f"{where(index)}, column {name}: {values[index]!r}; expected {allowed}"
        )


def _tests(test_id: np.ndarray) -> list[np.ndarray]:
    """Each test's rows in file order, tests in order of appearance (one sort: a table may hold
    tens of thousands of tests)."""
    _, first, inverse = np.unique(test_id, return_index=True, return_inverse=True)
    order = np.argsort(inverse, kind="stable")
    rows_of = np.split(order, np.cumsum(np.bincount(inverse))[:-1])
    return [rows_of[i] for i in np.argsort(first)]


def _check_cumulative(name, values, tests, test_id, where) -> None:
    """A cumulative quantity must not decrease from one reading of a test to the next."""
    for index in tests:
        drops = np.flatnonzero(np.diff(values[index]) < 0.0)
        if drops.size:
            previous, current = index[drops[0]], index[drops[0] + 1]
            raise FewearInputError(
                f"{where(current)}, column {name}: {values[current]!r} is less than "
                f"{values[previous]!r} of the previous reading of test {test_id[current]} "
                f"({where(previous)}); readings are cumulative and must not decrease"
            )


def _check_not_all_negative(name, values, tests, test_id, where) -> None:
    """A reading may dip below zero by the scatter of a weighing or a profile, but a test whose
    every reading is below zero measured no wear (a sign convention, a mass gain): an error."""
    for index in tests:
        if np.all(values[index] < 0.0):
            raise FewearInputError(
                f"{where(index[0])}, column {name}: every reading of test {test_id[index[0]]} is "
                f"below zero ({values[index].min()!r} to {values[index].max()!r}); wear is "
                "measured as a loss (>= 0; a reading may dip below zero by its scatter, not "
                "stay there): check the sign (before minus after)")


def _dips(values, tests, name) -> list[str]:
    """A note counting the readings that dip below their test's previous one (none: no note)."""
    dips = sum(int(np.sum(np.diff(values[index]) < 0.0)) for index in tests)
    if not dips:
        return []
    return [f"{dips} reading(s) of {name} dip below the previous reading of their test: kept as "
            "data (the scatter of each reading is modelled, not removed)"]


def _check_constant_factor(name, values, tests, test_id, where) -> None:
    for index in tests:
        changed = np.flatnonzero(values[index] != values[index[0]])
        if changed.size:
            row = index[changed[0]]
            raise FewearInputError(
                f"{where(row)}, column {name}: {values[row]!r} differs from {values[index[0]]!r} "
                f"earlier in test {test_id[row]}; a categorical factor is constant within a test")


def _text_column(name: str, cells: list[str], where: Callable[[int], str]) -> np.ndarray:
    values = np.array([cell.strip() for cell in cells])
    for index, value in enumerate(values):
        if not value:
            raise FewearInputError(f"{where(index)}, column {name}: empty value")
    return values


def _wear_rate_to_volume(columns, notes) -> None:
    rate = columns.pop("wear_rate_m3_m")
    columns["wear_volume_m3"] = rate * columns["sliding_distance_m"]
    notes.append("Wear rates per metre (wear_rate_m3_m, one row per test) were converted to wear "
                 "volumes V = (V / s) s with sliding_distance_m.")


def _check_one_row_per_test(tests, test_id, where) -> None:
    for index in tests:
        if index.size > 1:
            raise FewearInputError(
                f"{where(index[1])}, column test_id: test {test_id[index[0]]} appears again; "
                "a table of wear rates has one row per test"
            )


def _derive_distance(columns, notes) -> None:
    columns["sliding_distance_m"] = columns["velocity_m_s"] * columns["time_s"]
    notes.append("No sliding_distance_m column: the sliding distance was derived as s = v t "
                 "from velocity_m_s and time_s.")


def _specific_wear_rate_to_volume(source, line, columns, notes) -> None:
    if "normal_load_N" not in columns:
        raise FewearInputError(
            f"{source} line {line}, column normal_load_N: missing; a specific wear rate "
            "(specific_wear_rate_m3_N_m) is converted to a wear volume V = k F s with the load"
        )
    rate = columns.pop("specific_wear_rate_m3_N_m")
    columns["wear_volume_m3"] = rate * columns["normal_load_N"] * columns["sliding_distance_m"]
    notes.append("Specific wear rates (specific_wear_rate_m3_N_m, one row per test) were converted "
                 "to wear volumes V = k F s with normal_load_N and sliding_distance_m.")


def _mass_loss_to_volume(source, line, columns, density_kg_m3, notes) -> None:
    mass = columns.pop("mass_loss_kg")
    if "density_kg_m3" in columns:
        if density_kg_m3 is not None:
            raise FewearInputError(
                f"{source} line {line}, column density_kg_m3: the density is given both as a "
                f"column and as an argument ({density_kg_m3} kg/m^3); give it once"
            )
        columns["wear_volume_m3"] = mass / columns.pop("density_kg_m3")
        notes.append("Mass losses (mass_loss_kg) were converted to wear volumes V = m / rho with "
                     "the density_kg_m3 column.")
        return
    if density_kg_m3 is None:
        raise FewearInputError(
            f"{source} line {line}, column mass_loss_kg: a mass loss needs a density to become a "
            "wear volume: add a density_kg_m3 column or give the density argument"
        )
    if not (math.isfinite(density_kg_m3) and density_kg_m3 > 0.0):
        raise FewearInputError(f"density_kg_m3 = {density_kg_m3!r}: expected a positive density")
    columns["wear_volume_m3"] = mass / density_kg_m3
    notes.append(f"Mass losses (mass_loss_kg) were converted to wear volumes V = m / rho with "
                 f"the given density rho = {density_kg_m3:g} kg/m^3.")

