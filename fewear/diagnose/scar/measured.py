"""A measured wear scar: profiles of the worn flat's surface across the scar, read from CSV,
``x_mm, <profile>_um [, ...]`` or ``x_m, <profile>_m [, ...]``, heights NEGATIVE where worn (the
form of the measured scars in ``fewear/data``). The full rules, and what is refused:
docs/diagnosis-method-notes.md (input files)."""

from __future__ import annotations

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

POSITION_UNITS = {"x_mm": 1e-3, "x_m": 1.0}
"""The position column's names and their scale to m."""
HEIGHT_UNITS = {"_um": 1e-6, "_m": 1.0}
"""A height column's unit suffixes and their scale to m."""
MIN_POINTS = 10
"""A profile of fewer positions is no profile of a scar (the shipped ones have 171 and 391)."""


@dataclass(frozen=True, eq=False)
class MeasuredScar:
    """Measured profiles of one scar on a shared grid: ``x_m`` (n,) strictly increasing, m;
    ``depth_m`` (profiles, n), the wear depth (m, positive: worn); ``names`` of the profiles."""

    source: str
    x_m: np.ndarray
    depth_m: np.ndarray
    names: tuple[str, ...]

    @property
    def profile_of_point(self) -> np.ndarray:
        """The profile index of every point of the flattened ``depth_m`` (row-major)."""
        return np.repeat(np.arange(len(self.names)), self.x_m.size)

    @property
    def depth_points_m(self) -> np.ndarray:
        """The depths of all profiles, flattened (row-major: profile by profile)."""
        return self.depth_m.ravel()


def is_scar_file(path: str | Path) -> bool:
    """Whether the header of ``path`` marks a measured scar (first column ``x_mm`` or ``x_m``)."""
    _, header = read_header(Path(path))
    return bool(header) and header[0] in POSITION_UNITS


def read_measured_scar(path: str | Path) -> MeasuredScar:
    """Read a measured-scar CSV (module docstring)."""
    path = Path(path)
    source = str(path)
    header_line, header, rows = read_rows(path)
    scales = _height_scales(source, header_line, header)
    line_number = [number for number, _ in rows]

    def where(index: int) -> str:
        return f"{source} line {line_number[index]}"

    columns = [numeric_column(name, [row[position] for _, row in rows], where)
               for position, name in enumerate(header)]
    for name, values in zip(header, columns):
        require_finite_column(name, values, where)
    x_m = POSITION_UNITS[header[0]] * columns[0]
    _require_increasing(header[0], x_m, where)
    if x_m.size < MIN_POINTS:
        raise FewearInputError(f"{source}: {x_m.size} positions; a scar's profile has at least "
                               f"{MIN_POINTS}")
    depth_m = -np.array([scale * values for scale, values in zip(scales, columns[1:])])
    names = tuple(_profile_name(name) for name in header[1:])
    for name, depth in zip(header[1:], depth_m):
        if not depth.max() > 0.0:
            raise FewearInputError(f"{source}, column {name}: no point below the surface (the "
                                   "heights are negative where worn); no scar to diagnose")
    return MeasuredScar(source, x_m, depth_m, names)


def _height_scales(source: str, line: int, header: list[str]) -> list[float]:
    """Each height column's scale to m, every column name checked."""
    if header[0] not in POSITION_UNITS:
        raise FewearInputError(
            f"{source} line {line}, column {header[0]!r}: no measured scar; a scar file starts "
            "with the position x_mm (heights <profile>_um) or x_m (heights <profile>_m)")
    if len(header) < 2:
        raise FewearInputError(f"{source} line {line}: no height column after {header[0]}; a "
                               "scar file has x_mm, <profile>_um [, ...] or x_m, <profile>_m")
    repeated = sorted({name for name in header if header.count(name) > 1})
    if repeated:
        raise FewearInputError(f"{source} line {line}: column(s) {', '.join(repeated)} repeated")
    scales = []
    for name in header[1:]:
        unit = next((suffix for suffix in HEIGHT_UNITS
                     if name.endswith(suffix) and len(name) > len(suffix)), None)
        if unit is None:
            raise FewearInputError(
                f"{source} line {line}, column {name!r}: expected a surface height in um "
                "(<profile>_um) or m (<profile>_m), negative where worn")
        scales.append(HEIGHT_UNITS[unit])
    return scales


def _profile_name(column: str) -> str:
    return next(column.removesuffix(suffix) for suffix in HEIGHT_UNITS if column.endswith(suffix))


def _require_increasing(name: str, x_m: np.ndarray, where) -> None:
    bad = np.flatnonzero(np.diff(x_m) <= 0.0)
    if bad.size:
        raise FewearInputError(f"{where(bad[0] + 1)}, column {name}: the position does not "
                               "increase; expected the rows in increasing x")
