"""Reading the rows of a measured-data CSV (``#`` comment lines and blank lines allowed anywhere,
one header line of column names), every failure a :class:`~fewear.errors.FewearInputError` naming
the file, the line and the column. Shared by the diagnosis rooms (tribometer, joint, scar)."""

from __future__ import annotations

import csv
from collections.abc import Callable
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.text import read_text_file


def read_rows(path: Path) -> tuple[int, list[str], list[tuple[int, list[str]]]]:
    """The header's line number, its column names, and the (line number, cells) of data rows."""
    text = read_text_file(path, "measured data")
    header_line, header, rows = 0, None, []
    for line_number, line in enumerate(text.splitlines(), start=1):
        stripped = line.strip()
        if not stripped or stripped.startswith("#"):
            continue
        cells = csv_cells(path, line_number, line)
        if header is None:
            header_line, header = line_number, [cell.strip() for cell in cells]
            continue
        if len(cells) != len(header):
            raise FewearInputError(
                f"{path} line {line_number}: {len(cells)} values for the {len(header)} columns "
                f"{', '.join(header)}"
            )
        rows.append((line_number, cells))
    if header is None:
        raise FewearInputError(f"{path}: no header line (column names) found")
    if not rows:
        raise FewearInputError(f"{path}: no data rows after the header (line {header_line})")
    return header_line, header, rows


def read_header(path: Path) -> tuple[int, list[str]]:
    """The line number and column names of the first line that is not blank or a comment."""
    for number, line in enumerate(read_text_file(path, "measured data").splitlines(), start=1):
        stripped = line.strip()
        if stripped and not stripped.startswith("#"):
            return number, [cell.strip() for cell in csv_cells(path, number, stripped)]
    raise FewearInputError(f"{path}: no header line (column names) found")


def csv_cells(path, line_number: int, line: str) -> list[str]:
    """The cells of one CSV line; a line the csv module refuses (a cell longer than its field
    limit, a stray quote) is an input error naming the file and line."""
    try:
        return next(csv.reader([line]))
    except csv.Error as exc:
        limit = csv.field_size_limit()
        reason = (f"a cell longer than {limit:,} characters" if "field limit" in str(exc)
                  else str(exc))
        raise FewearInputError(
            f"{path} line {line_number}: {reason}; expected comma-separated cells (numbers, "
            f"test ids, names) of at most {limit:,} characters each") from None


def numeric_column(name: str, cells: list[str], where: Callable[[int], str]) -> np.ndarray:
    """The cells of column ``name`` as floats; an empty cell or text is an input error naming
    the place (``where(row index)``: file and line), the column and the value."""
    values = np.empty(len(cells))
    for index, cell in enumerate(cells):
        text = cell.strip()
        if not text:
            raise FewearInputError(f"{where(index)}, column {name}: empty value")
        try:
            values[index] = float(text)
        except ValueError:
            raise FewearInputError(
                f"{where(index)}, column {name}: {text!r} is not a number"
            ) from None
    return values


def require_finite_column(name: str, values: np.ndarray, where: Callable[[int], str]) -> None:
    """Refuse NaN or infinity in column ``name``, naming the place (``where(row index)``), the
    column and the value."""
    bad = np.flatnonzero(~np.isfinite(values))
    if bad.size:
        raise FewearInputError(
            f"{where(bad[0])}, column {name}: {values[bad[0]]!r}; expected a finite number")
