"""Wear measured on the worn revolute clearance joint of a mechanism, read from CSV files, one kind
per file recognised from its header (SI units in the column names): bore profiles
(``cycles, angle_deg, wear_depth_m``), maximum-depth growth (``cycles, max_wear_depth_m``) and
optional force (``time_s, fx_N, fy_N [, cycles]``) and slider-acceleration
(``time_s, slider_acceleration_m_s2 [, cycles]``) traces. The full rules, and what is refused:
docs/diagnosis-method-notes.md (input files)."""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.csv_rows import (
    numeric_column,
    read_header,
    read_rows,
    require_finite_column,
)

KIND_COLUMNS = {
    "profiles": ("cycles", "angle_deg", "wear_depth_m"),
    "max_wear": ("cycles", "max_wear_depth_m"),
    "force": ("time_s", "fx_N", "fy_N"),
    "acceleration": ("time_s", "slider_acceleration_m_s2"),
}
"""The required columns of each kind of joint data file."""
OPTIONAL_COLUMNS = {"profiles": (), "max_wear": (), "force": ("cycles",),
                    "acceleration": ("cycles",)}
KIND_NAMES = {"profiles": "bore profile", "max_wear": "maximum-depth growth",
              "force": "joint force trace", "acceleration": "slider acceleration trace"}
KIND_STEMS = {"profiles": ("angle", "wear_depth"), "max_wear": ("max_wear_depth",),
              "force": ("fx", "fy"), "acceleration": ("slider_acceleration",)}
"""Column stems (any unit) that mark a header as one kind of joint data."""
ANGLE_RANGE_deg = (-360.0, 720.0)
MAX_CYCLES = 1e15
"""Above this a cycle count no longer fits the reader's integers (and no test runs so long)."""
IMPLAUSIBLE_DEPTH_m = 1e-2
"""A wear depth of this size (1 cm, the whole bore radius of a 10 mm bushing) is a unit mistake."""
NOISE_FLOOR_m = 1e-7
"""Depths down to -0.1 um are noise even in a file without wear (a profilometer's resolution)."""
MAX_FALL = 2.0
"""A later wear depth below 1/MAX_FALL of an earlier one is no scatter (wear only grows)."""

UNIT_HINTS = {
    "max_wear_depth": "max_wear_depth_m (1 um = 1e-6 m, 1 mm = 1e-3 m)",
    "wear_depth": "wear_depth_m (1 um = 1e-6 m, 1 mm = 1e-3 m)",
    "depth": "wear_depth_m (1 um = 1e-6 m, 1 mm = 1e-3 m)",
    "angle": "angle_deg (1 rad = 180/pi deg)",
    "cycle": "cycles (a whole number of crank revolutions, not thousands or millions)",
    "time": "time_s (1 ms = 1e-3 s)",
    "fx": "fx_N (1 kN = 1e3 N)",
    "fy": "fy_N (1 kN = 1e3 N)",
    "slider_acceleration": "slider_acceleration_m_s2 (1 g = 9.80665 m/s^2)",
    "acceleration": "slider_acceleration_m_s2 (1 g = 9.80665 m/s^2)",
}
"""Known quantities (column stems) in other units or spellings: the SI column to use instead."""


@dataclass(frozen=True, eq=False)
class MeasuredProfile:
    """One bore profile: radial wear depth (m) against the bushing-frame angle (rad) after
    ``cycles`` crank revolutions; angles strictly increasing in [0, 2 pi)."""

    cycles: int
    angle_rad: np.ndarray
    depth_m: np.ndarray

    def __post_init__(self):
        name = f"bore profile at {self.cycles!r} cycles"
        object.__setattr__(self, "cycles", _cycle_count(self.cycles, name))
        angle = _readonly_vector(self.angle_rad, f"{name}: angle_rad")
        depth = _readonly_vector(self.depth_m, f"{name}: depth_m")
        if angle.shape != depth.shape:
            raise FewearInputError(f"{name}: {angle.size} angles for {depth.size} depths")
        if not (np.all(angle >= 0.0) and np.all(angle < 2.0 * math.pi)):
            raise FewearInputError(f"{name}: angle_rad must lie in [0, 2 pi)")
        if np.any(np.diff(angle) <= 0.0):
            raise FewearInputError(f"{name}: angle_rad must be strictly increasing")
        object.__setattr__(self, "angle_rad", angle)
        object.__setattr__(self, "depth_m", depth)


@dataclass(frozen=True, eq=False)
class ForceTrace:
    """The joint force (N) in the bushing frame against time (s, strictly increasing), recorded
    after ``cycles`` crank revolutions."""

    cycles: int
    time_s: np.ndarray
    fx_N: np.ndarray
    fy_N: np.ndarray

    def __post_init__(self):
        _check_trace(self, ("fx_N", "fy_N"), "joint force trace")


@dataclass(frozen=True, eq=False)
class AccelerationTrace:
    """The slider's acceleration (m/s^2) against time (s, strictly increasing), recorded after
    ``cycles`` crank revolutions."""

    cycles: int
    time_s: np.ndarray
    slider_acceleration_m_s2: np.ndarray

    def __post_init__(self):
        _check_trace(self, ("slider_acceleration_m_s2",), "slider acceleration trace")


@dataclass(frozen=True, eq=False)
class JointMeasurements:
    """Wear measured on a joint (module doc), SI units.

    ``profiles``: bore profiles sorted by cycles (empty when none). ``max_wear``: (cycles as an int
    array, strictly increasing; maximum wear depth in m) or ``None``. ``force`` and
    ``acceleration``: traces sorted by cycles, or ``None`` when no such file was read.
    ``sources``: the files read; ``notes``: sentences on what was observed and kept.
    """

    profiles: tuple[MeasuredProfile, ...] = ()
    max_wear: tuple[np.ndarray, np.ndarray] | None = None
    force: tuple[ForceTrace, ...] | None = None
    acceleration: tuple[AccelerationTrace, ...] | None = None
    sources: tuple[str, ...] = ()
    notes: tuple[str, ...] = ()

    def __post_init__(self):
        profiles = tuple(sorted(self.profiles, key=lambda profile: profile.cycles))
        _check_unique_cycles([profile.cycles for profile in profiles], "bore profiles")
        object.__setattr__(self, "profiles", profiles)
        if self.max_wear is not None:
            object.__setattr__(self, "max_wear", _checked_max_wear(*self.max_wear))
        for name in ("force", "acceleration"):
            traces = getattr(self, name)
            if traces is not None:
                traces = tuple(sorted(traces, key=lambda trace: trace.cycles))
                _check_unique_cycles([trace.cycles for trace in traces], f"{name} traces")
                object.__setattr__(self, name, traces)
        if not profiles and self.max_wear is None:
            raise FewearInputError(
                "joint wear data need a bore profile or a maximum-depth growth file")
        object.__setattr__(self, "sources", tuple(self.sources))
        object.__setattr__(self, "notes", tuple(self.notes))

    @property
    def profile_cycles(self) -> tuple[int, ...]:
        """The cycle counts of the bore profiles, increasing."""
        return tuple(profile.cycles for profile in self.profiles)

    @property
    def cycle_counts(self) -> tuple[int, ...]:
        """All cycle counts with wear data (a bore profile or a maximum depth), increasing."""
        counts = set(self.profile_cycles)
        if self.max_wear is not None:
            counts.update(int(count) for count in self.max_wear[0])
        return tuple(sorted(counts))

    @property
    def last_cycles(self) -> int:
        """The largest cycle count with wear data."""
        return self.cycle_counts[-1]

    def profile_at(self, cycles: int) -> MeasuredProfile:
        """The bore profile measured after ``cycles`` revolutions (error if there is none)."""
        for profile in self.profiles:
            if profile.cycles == cycles:
                return profile
        have = ", ".join(str(count) for count in self.profile_cycles) or "none"
        raise FewearInputError(f"no bore profile at {cycles} cycles; profiles at: {have}")


def joint_data_kind(path: str | Path) -> str | None:
    """The kind of joint data file (``"profiles"``, ``"max_wear"``, ``"force"`` or
    ``"acceleration"``) that the header of ``path`` marks, or ``None`` if it is no joint data
    file (e.g. a tribometer file). Reads the header only; a header of two kinds is an error."""
    line, header = read_header(Path(path))
    return _kind_of_header(str(path), line, header)


def read_joint_measurements(paths: list[str | Path] | str | Path) -> JointMeasurements:
    """Read joint wear data files (module doc), one kind per file, and merge files of one kind."""
    paths = [paths] if isinstance(paths, (str, Path)) else list(paths)
    if not paths:
        raise FewearInputError("no joint wear data files given")
    found = {kind: [] for kind in KIND_COLUMNS}
    notes = []
    for path in paths:
        kind, items, file_notes = _read_joint_file(Path(path))
        found[kind].append((str(path), items))
        notes += file_notes
    profiles = _merge_by_cycles(found["profiles"], "profiles")
    max_wear = _merge_max_wear(found["max_wear"])
    if not profiles and max_wear is None:
        read = ", ".join(str(path) for path in paths)
        raise FewearInputError(
            f"joint wear data need a bore profile or a maximum-depth growth file; read only {read}"
            f" (a bore profile has the columns {', '.join(KIND_COLUMNS['profiles'])}; a "
            f"maximum-depth growth file {', '.join(KIND_COLUMNS['max_wear'])})")
    _require_measurable_wear(profiles, max_wear, paths)
    if profiles:
        _require_growth([profile.cycles for profile in profiles],
                        [float(np.max(profile.depth_m)) for profile in profiles],
                        f"{_sources(found['profiles'])}: the deepest wear of the bore profile")
    if max_wear is not None:
        _require_growth(*max_wear, f"{_sources(found['max_wear'])}: the maximum wear depth")
    traces = {kind: _merge_by_cycles(found[kind], kind) if found[kind] else None
              for kind in ("force", "acceleration")}
    return JointMeasurements(profiles=profiles, max_wear=max_wear, **traces,
                             sources=tuple(str(path) for path in paths), notes=tuple(notes))


def write_joint_profiles(path: str | Path, profiles, comment: str = "") -> None:
    """Write bore profiles (:class:`MeasuredProfile`) as ``cycles, angle_deg, wear_depth_m``
    (with ``comment`` as ``#`` header lines)."""
    lines = _comment_lines(comment) + [",".join(KIND_COLUMNS["profiles"])]
    for profile in profiles:
        for angle, depth in zip(np.rad2deg(profile.angle_rad), profile.depth_m):
            lines.append(f"{profile.cycles},{float(angle)!r},{float(depth)!r}")
    Path(path).write_text("\n".join(lines) + "\n")


def write_max_wear(path: str | Path, cycles, depth, comment: str = "") -> None:
    """Write maximum wear depths (m) against cycle counts as ``cycles, max_wear_depth_m`` (with
    ``comment`` as ``#`` header lines)."""
    cycles, depth = _checked_max_wear(cycles, depth)
    lines = _comment_lines(comment) + [",".join(KIND_COLUMNS["max_wear"])]
    lines += [f"{int(count)},{float(value)!r}" for count, value in zip(cycles, depth)]
    Path(path).write_text("\n".join(lines) + "\n")


def _comment_lines(comment: str) -> list[str]:
    return [f"# {line}".rstrip() for line in comment.splitlines()] if comment else []


# --- header ---------------------------------------------------------------------------------

def _has_stem(name: str, stem: str) -> bool:
    return name == stem or name.startswith(stem + "_")


def _kind_of_header(source: str, line: int, header: list[str]) -> str | None:
    kinds = [kind for kind, stems in KIND_STEMS.items()
             if any(_has_stem(name, stem) for name in header for stem in stems)]
    if len(kinds) > 1:
        raise FewearInputError(
            f"{source} line {line}: columns of {' and '.join(KIND_NAMES[k] for k in kinds)} data "
            f"in one file; each file holds one kind:\n{_schemas()}")
    return kinds[0] if kinds else None


def _schemas() -> str:
    return "\n".join(f"  {KIND_NAMES[kind]}: {', '.join(columns)}"
                     + "".join(f" [, {name}]" for name in OPTIONAL_COLUMNS[kind])
                     for kind, columns in KIND_COLUMNS.items())


def _check_columns(source: str, line: int, header: list[str], kind: str) -> None:
    allowed = KIND_COLUMNS[kind] + OPTIONAL_COLUMNS[kind]
    for name in header:
        if name not in allowed:
            raise FewearInputError(
                f"{source} line {line}, column {name!r}: {_unknown_column(name, kind)}")
    repeated = sorted({name for name in header if header.count(name) > 1})
    if repeated:
        raise FewearInputError(f"{source} line {line}: column(s) {', '.join(repeated)} repeated")
    for name in KIND_COLUMNS[kind]:
        if name not in header:
            raise FewearInputError(
                f"{source} line {line}: missing required column {name}; a {KIND_NAMES[kind]} "
                f"file has the columns {', '.join(allowed)}")


def _unknown_column(name: str, kind: str) -> str:
    for stem, hint in UNIT_HINTS.items():
        if _has_stem(name, stem):
            return f"unknown column or unit; fewear reads SI units only: use {hint}"
    allowed = KIND_COLUMNS[kind] + OPTIONAL_COLUMNS[kind]
    return f"unknown column; a {KIND_NAMES[kind]} file has the columns {', '.join(allowed)}"


# --- one file -------------------------------------------------------------------------------

def _read_joint_file(path: Path) -> tuple[str, list | tuple, list[str]]:
    """The kind of the file, its data (profiles, (cycles, depth) or traces) and notes."""
    source = str(path)
    header_line, header, rows = read_rows(path)
    kind = _kind_of_header(source, header_line, header)
    if kind is None:
        raise FewearInputError(
            f"{source} line {header_line}: the columns {', '.join(header)} are no joint wear "
            f"data; joint data files have the columns:\n{_schemas()}")
    _check_columns(source, header_line, header, kind)
    line_number = np.array([line for line, _ in rows], dtype=int)

    def where(index: int) -> str:
        return f"{source} line {line_number[index]}"

    columns = {}
    for position, name in enumerate(header):
        columns[name] = numeric_column(name, [row[position] for _, row in rows], where)
        require_finite_column(name, columns[name], where)
    readers = {"profiles": _profiles_from, "max_wear": _max_wear_from,
               "force": _traces_from, "acceleration": _traces_from}
    items, notes = readers[kind](source, kind, columns, where)
    return kind, items, notes


def _cycles_column(values: np.ndarray, where: Callable[[int], str]) -> np.ndarray:
    bad = np.flatnonzero((values < 0.0) | (values != np.round(values)) | (values > MAX_CYCLES))
    if bad.size:
        raise FewearInputError(
            f"{where(bad[0])}, column cycles: {values[bad[0]]!r}; expected a non-negative whole "
            "number of crank revolutions")
    return values.astype(np.int64)


def _check_depths(name: str, depth: np.ndarray, where: Callable[[int], str]) -> None:
    bad = np.flatnonzero(np.abs(depth) >= IMPLAUSIBLE_DEPTH_m)
    if bad.size:
        raise FewearInputError(
            f"{where(bad[0])}, column {name}: {depth[bad[0]]!r} m is 1 cm or more, not a wear "
            f"depth in metres: convert to metres (1 um = 1e-6 m, 1 mm = 1e-3 m)")


def _check_noise(name: str, depth: np.ndarray, where: Callable[[int], str]) -> None:
    """Depths below zero are instrument noise only while no deeper than the file's deepest wear
    (or :data:`NOISE_FLOOR_m`): a file of negative depths measured no wear, or has its sign
    flipped."""
    floor = max(float(np.max(depth)), NOISE_FLOOR_m)
    bad = np.flatnonzero(depth < -floor)
    if bad.size:
        raise FewearInputError(
            f"{where(bad[0])}, column {name}: {depth[bad[0]]!r} m; the file's deepest wear is "
            f"{max(float(np.max(depth)), 0.0):.3g} m, so depths below zero are instrument noise "
            f"only down to -{floor:.3g} m: a wear depth is the radial growth of the bore (>= 0, "
            "noise aside), check the sign")


def _negative_note(source: str, name: str, depth: np.ndarray) -> list[str]:
    negative = int(np.sum(depth < 0.0))
    if not negative:
        return []
    return [f"{source}: {negative} of {depth.size} values of {name} are below zero (lowest "
            f"{depth.min() * 1e6:.3g} um): kept as data (instrument noise)"]


def _beyond_a_turn_note(source: str, angle_deg: np.ndarray) -> list[str]:
    """A note on profile angles of 360 deg or more (read modulo 360: an instrument that counts
    on past a turn; negative angles, as of a -180 to 180 deg convention, need no note)."""
    beyond = angle_deg >= 360.0
    if not beyond.any():
        return []
    count = int(beyond.sum())
    return [f"{source}: {count} angle{'s' if count > 1 else ''} of 360 deg or more (highest "
            f"{angle_deg.max():g} deg) taken modulo 360 deg"]


def _profiles_from(source, kind, columns, where) -> tuple[list[MeasuredProfile], list[str]]:
    cycles = _cycles_column(columns["cycles"], where)
    angle_deg, depth = columns["angle_deg"], columns["wear_depth_m"]
    low, high = ANGLE_RANGE_deg
    bad = np.flatnonzero((angle_deg < low) | (angle_deg >= high))
    if bad.size:
        raise FewearInputError(
            f"{where(bad[0])}, column angle_deg: {angle_deg[bad[0]]!r}; expected an angle in "
            f"degrees in [{low:g}, {high:g})")
    _check_depths("wear_depth_m", depth, where)
    _check_noise("wear_depth_m", depth, where)
    normalised = np.mod(angle_deg, 360.0)
    normalised[normalised >= 360.0] = 0.0  # mod of a tiny negative angle rounds up to 360
    profiles, notes = [], []
    for count in np.unique(cycles):
        rows = np.flatnonzero(cycles == count)
        rows = rows[np.argsort(normalised[rows], kind="stable")]
        _check_profile_angles(rows, angle_deg, normalised, int(count), where)
        profile = MeasuredProfile(int(count), np.deg2rad(normalised[rows]), depth[rows])
        profiles.append(profile)
        notes += _sampling_notes(source, profile)
    notes += _negative_note(source, "wear_depth_m", depth)
    notes += _beyond_a_turn_note(source, angle_deg)
    if np.all(np.abs(angle_deg) <= 2.0 * math.pi):
        raise FewearInputError(
            f"{source}, column angle_deg: every angle lies within +-{2.0 * math.pi:.3g} deg "
            f"({angle_deg.min():.3g} to {angle_deg.max():.3g}): radians under angle_deg? "
            "convert to degrees (angle_deg = angle_rad * 180 / pi); a bore profile spans more")
    return profiles, notes


def _check_profile_angles(rows, angle_deg, normalised, cycles, where) -> None:
    """At least 3 angles per profile, none twice (after normalisation to [0, 360))."""
    if rows.size < 3:
        raise FewearInputError(
            f"{where(rows[0])}, column angle_deg: the bore profile at {cycles} cycles has "
            f"{rows.size} angle(s); a profile needs at least 3")
    same = np.flatnonzero(np.diff(normalised[rows]) <= 1e-9)
    if same.size:
        first, again = sorted((rows[same[0]], rows[same[0] + 1]))  # in file order
        raise FewearInputError(
            f"{where(again)}, column angle_deg: {angle_deg[again]!r} deg is the angle "
            f"{angle_deg[first]!r} deg of {where(first)} again ({normalised[again]:g} deg in "
            f"[0, 360)) in the bore profile at {cycles} cycles; each angle appears once per "
            "cycle count")


def _sampling_notes(source: str, profile: MeasuredProfile) -> list[str]:
    """The sampling step, and the arc a profile covers when it is not the full circle."""
    angle_deg = np.rad2deg(profile.angle_rad)
    gaps = np.diff(np.append(angle_deg, angle_deg[0] + 360.0))
    widest = int(np.argmax(gaps))
    step = float(np.median(np.delete(gaps, widest)))
    what = f"{source}: bore profile at {profile.cycles} cycles: {angle_deg.size} angles"
    spread = np.delete(gaps, widest)
    steps = (f"every {step:.3g} deg" if np.ptp(spread) <= 1e-6 * step + 1e-9
             else f"every {spread.min():.3g} to {spread.max():.3g} deg (median {step:.3g})")
    if gaps[widest] <= 2.0 * step + 1e-9:
        return [f"{what}, {steps}, over the full circle"]
    start, end = angle_deg[(widest + 1) % angle_deg.size], angle_deg[widest]
    return [f"{what}, {steps}, over the arc {start:.4g} to {end:.4g} deg "
            f"({360.0 - gaps[widest]:.4g} of 360 deg): partial angular coverage"]


def _max_wear_from(source, kind, columns, where) -> tuple[tuple, list[str]]:
    cycles = _cycles_column(columns["cycles"], where)
    depth = columns["max_wear_depth_m"]
    _check_depths("max_wear_depth_m", depth, where)
    _check_noise("max_wear_depth_m", depth, where)
    order = np.argsort(cycles, kind="stable")
    same = np.flatnonzero(np.diff(cycles[order]) == 0)
    if same.size:
        first, again = order[same[0]], order[same[0] + 1]
        raise FewearInputError(
            f"{where(again)}, column cycles: {cycles[again]} appears again (first at "
            f"{where(first)}); a maximum-depth growth file has one row per cycle count")
    cycles, depth = cycles[order], depth[order]
    notes = _negative_note(source, "max_wear_depth_m", depth)
    dips = int(np.sum(np.diff(depth) < 0.0))
    if dips:
        notes.append(f"{source}: the maximum wear depth dips below the previous cycle count's "
                     f"{dips} time(s): kept as data (measurement scatter)")
    return (cycles, depth), notes


def _traces_from(source, kind, columns, where) -> tuple[list, list[str]]:
    notes = []
    if "cycles" in columns:
        cycles = _cycles_column(columns["cycles"], where)
    else:
        cycles = np.zeros(columns["time_s"].size, dtype=np.int64)
        notes.append(f"{source}: no cycles column: the {KIND_NAMES[kind]} is taken as recorded "
                     "at the start (cycle 0)")
    traces = []
    for count in np.unique(cycles):
        rows = np.flatnonzero(cycles == count)
        time = columns["time_s"][rows]
        back = np.flatnonzero(np.diff(time) <= 0.0)
        if back.size:
            row, previous = rows[back[0] + 1], rows[back[0]]
            raise FewearInputError(
                f"{where(row)}, column time_s: {time[back[0] + 1]!r} is not after "
                f"{time[back[0]]!r} of {where(previous)}; time must increase strictly within "
                f"a trace")
        values = {name: columns[name][rows] for name in KIND_COLUMNS[kind][1:]}
        trace_type = ForceTrace if kind == "force" else AccelerationTrace
        traces.append(trace_type(int(count), time, **values))
    return traces, notes


# --- merging and checks ---------------------------------------------------------------------

def _merge_by_cycles(found: list[tuple[str, list]], kind: str) -> tuple:
    """The profiles or traces of all files of one kind; a cycle count in two files is an error."""
    seen, merged = {}, []
    for source, items in found:
        for item in items:
            if item.cycles in seen:
                raise FewearInputError(
                    f"{source}: the {KIND_NAMES[kind]} at {item.cycles} cycles is also in "
                    f"{seen[item.cycles]}; give each cycle count once")
            seen[item.cycles] = source
            merged.append(item)
    return tuple(sorted(merged, key=lambda item: item.cycles))


def _merge_max_wear(found: list[tuple[str, tuple]]) -> tuple[np.ndarray, np.ndarray] | None:
    if not found:
        return None
    seen = {}
    for source, (cycles, _) in found:
        for count in cycles:
            if int(count) in seen:
                raise FewearInputError(
                    f"{source}: the maximum wear depth at {int(count)} cycles is also in "
                    f"{seen[int(count)]}; give each cycle count once")
            seen[int(count)] = source
    cycles = np.concatenate([items[0] for _, items in found])
    depth = np.concatenate([items[1] for _, items in found])
    order = np.argsort(cycles)
    return cycles[order], depth[order]


def _require_measurable_wear(profiles, max_wear, paths) -> None:
    """The deepest wear of the data must exceed a profilometer's resolution
    (:data:`NOISE_FLOOR_m`): below it no wear was measured, or the depths are in the wrong unit
    (1000x too shallow read as a bushing worn through by the fit)."""
    depths = [profile.depth_m for profile in profiles] + (
        [max_wear[1]] if max_wear is not None else [])
    deepest = max(float(np.max(depth)) for depth in depths)
    if deepest <= NOISE_FLOOR_m:
        raise FewearInputError(
            f"{', '.join(map(str, paths))}: the deepest wear is {deepest:.3g} m, within a "
            f"profilometer's resolution ({NOISE_FLOOR_m:g} m): no wear measured, or depths in "
            "the wrong unit (wear_depth_m and max_wear_depth_m are metres: 1 um = 1e-6 m)")


def _sources(found: list[tuple[str, object]]) -> str:
    return ", ".join(source for source, _ in found)


def _require_growth(cycles, depth_m, what: str) -> None:
    """Wear only grows: a depth may dip below an earlier one by the scatter of a measurement,
    not fall to less than 1 / :data:`MAX_FALL` of it (and by more than :data:`NOISE_FLOOR_m`):
    such data are profiles of another joint, cycle counts swapped or mislabelled."""
    deepest, at = -math.inf, 0
    for count, depth in zip(cycles, depth_m):
        fall = deepest - depth
        if deepest > NOISE_FLOOR_m and depth * MAX_FALL < deepest and fall > NOISE_FLOOR_m:
            raise FewearInputError(
                f"{what} falls from {deepest * 1e6:.3g} um at {at} cycles to {depth * 1e6:.3g} "
                f"um at {count} cycles ({deepest / max(depth, NOISE_FLOOR_m / 10):.3g}x less); "
                f"wear only grows (a fall below 1/{MAX_FALL:g} of an earlier depth is beyond "
                "measurement scatter): "
                "check the cycles column (swapped or mislabelled counts, another joint's data)")
        if depth > deepest:
            deepest, at = depth, count


def _cycle_count(value, name: str) -> int:
    if isinstance(value, bool) or not isinstance(value, (int, np.integer, float, np.floating)):
        raise FewearInputError(f"{name}: cycles {value!r}: expected a non-negative whole number")
    if not (math.isfinite(value) and value >= 0 and value == round(value)):
        raise FewearInputError(f"{name}: cycles {value!r}: expected a non-negative whole number")
    return int(value)


def _readonly_vector(values, name: str) -> np.ndarray:
    array = np.array(values, dtype=float)
    if array.ndim != 1 or array.size == 0:
        raise FewearInputError(f"{name}: expected a non-empty 1-D array")
    if not np.all(np.isfinite(array)):
        raise FewearInputError(f"{name}: expected finite numbers")
    array.setflags(write=False)
    return array


def _check_trace(trace, value_names: tuple[str, ...], what: str) -> None:
    name = f"{what} at {trace.cycles!r} cycles"
    object.__setattr__(trace, "cycles", _cycle_count(trace.cycles, name))
    time = _readonly_vector(trace.time_s, f"{name}: time_s")
    if np.any(np.diff(time) <= 0.0):
        raise FewearInputError(f"{name}: time_s must be strictly increasing")
    object.__setattr__(trace, "time_s", time)
    for value_name in value_names:
        values = _readonly_vector(getattr(trace, value_name), f"{name}: {value_name}")
        if values.shape != time.shape:
            raise FewearInputError(f"{name}: {values.size} {value_name} for {time.size} times")
        object.__setattr__(trace, value_name, values)


def _check_unique_cycles(cycles: list[int], what: str) -> None:
    repeated = sorted({count for count in cycles if cycles.count(count) > 1})
    if repeated:
        raise FewearInputError(
            f"{what}: cycle count(s) {', '.join(map(str, repeated))} given more than once")


def _checked_max_wear(cycles, depth) -> tuple[np.ndarray, np.ndarray]:
    counts = np.array([_cycle_count(value, "maximum wear depth") for value in np.ravel(cycles)],
                      dtype=np.int64)
    depth = _readonly_vector(depth, "maximum wear depth: depth")
    if counts.shape != depth.shape:
        raise FewearInputError(
            f"maximum wear depth: {counts.size} cycle counts for {depth.size} depths")
    if np.any(np.diff(counts) <= 0):
        raise FewearInputError("maximum wear depth: cycles must be strictly increasing")
    counts.setflags(write=False)
    return counts, depth
