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
MAX_DEPTH_OVER_WIDTH = 0.5
"""A scar deeper than this times its width (at half depth) is in the wrong units."""
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
    """Whether the header of ``path`` marks a measured scar: a first column ``x_mm`` or ``x_m``,
    or a position in another unit (``x_in``, ``x``: refused by the reader naming the units)."""
    _, header = read_header(Path(path))
    return bool(header) and (header[0] == "x" or header[0].startswith("x_"))


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
    for name, depth in zip(header[1:], depth_m):
        _require_wider_than_deep(source, header[0], name, x_m, depth)
    return MeasuredScar(source, x_m, depth_m, names)


def _require_wider_than_deep(source, x_name, name, x_m, depth_m) -> None:
    """A wear scar is far wider than deep: a flat worn by a cylinder of radius R to depth d is
    w = 2 sqrt(2 R d) wide, d / w = w / (8 R) (at most about 1/8 for a scar as wide as R).
    A profile deeper than :data:`MAX_DEPTH_OVER_WIDTH` times its width at half its depth has
    its position or its heights in the wrong unit."""
    deepest = float(depth_m.max())
    worn = x_m[depth_m >= 0.5 * deepest]
    width = float(worn.max() - worn.min()) if worn.size > 1 else float(np.min(np.diff(x_m)))
    if deepest <= MAX_DEPTH_OVER_WIDTH * width:
        return
    likely = (f"heights in um under {name} (1 um = 1e-6 m)" if name.endswith("_m") else
              f"positions in m under {x_name} (1 mm = 1e-3 m)" if x_name == "x_mm" else
              f"positions in mm under {x_name}")
    raise FewearInputError(
        f"{source}, column {name}: the scar is {deepest:.3g} m deep and {width:.3g} m wide at "
        f"half its depth; a wear scar is far wider than deep (depth <= {MAX_DEPTH_OVER_WIDTH:g} "
        f"x width): {likely}?")


def _height_scales(source: str, line: int, header: list[str]) -> list[float]:
    """Each height column's scale to m, every column name checked."""
    if header[0] not in POSITION_UNITS:
        raise FewearInputError(
            f"{source} line {line}, column {header[0]!r}: a scar's position is in mm or m "
            "(SI units: 1 in = 25.4 mm): a scar file starts with the position x_mm (heights "
            "<profile>_um) or x_m (heights <profile>_m)")
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
