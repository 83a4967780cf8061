"""The worn bushing of a ``fewear run`` read back from its files (``<case>-<joint>.xdmf`` +
``.h5``, through meshio, never the model), and the view that compares the cases and joints: one
exaggeration of the displacement, so that microns of wear show on a centimetre bushing, and one
colour scale from zero (``fewear plot``, :mod:`fewear.commands.plot`, draws it in PyVista)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError

VTK_BIQUADRATIC_QUAD = 28
FIGURE = "worn_bushing.png"
"""The figure written into the run's folder off screen."""


FIELDS = ("mesh_displacement_m", "radial_displacement_m")
"""The point data of a run's bushing file that the figure draws."""


def last_block(path: Path):
    """(points (n, 3), quad9 cells in VTK order, displacement (n, 3) m, radial (n,) m, cycles),
    checked before VTK sees them (:func:`checked_block`): VTK trusts its input, and a corrupted
    ``.h5`` (connectivity out of range) crashed it (a segmentation fault, no message)."""
    import meshio

    point_data, cycles = {}, None
    try:
        with meshio.xdmf.TimeSeriesReader(str(path)) as reader:
            points, cells = reader.read_points_cells()
            for k in range(reader.num_steps):
                cycles, point_data, _ = reader.read_data(k)
    except Exception as exc:  # meshio raises many kinds on a broken file
        raise FewearInputError(f"cannot read {path}: {exc}") from None
    return checked_block(path, points, cells, point_data, cycles)


MAX_EXTENT_M = 100.0
"""Coordinates and displacements beyond this are no bushing's (a damaged file): VTK's rendering
aborts the process on some absurd magnitudes."""


def checked_block(path: Path, points, cells, point_data: dict, cycles):
    """The block of :func:`last_block` if its arrays are what the run writes: finite points
    (n, 2 or 3) within ``MAX_EXTENT_M`` of the origin, quad9 cells whose node numbers lie in
    [0, n), fields of n rows within ``MAX_EXTENT_M``, a finite cycle count; else
    :class:`FewearInputError` naming the file and what is wrong."""
    def refuse(what: str):
        raise FewearInputError(f"{path}: {what}; the file is damaged or is no worn bushing of a "
                               "`fewear run` (rerun the run, or --resume it, to write it again)")

    missing = [name for name in FIELDS if name not in point_data]
    if missing:
        refuse(f"no {', '.join(missing)} (a `fewear contact` folder's bushing.xdmf has none)")
    points = np.asarray(points, dtype=float)
    if points.ndim != 2 or points.shape[1] not in (2, 3) or not np.all(np.isfinite(points)):
        refuse(f"its points (shape {points.shape}) are not finite 2D or 3D coordinates")
    if np.abs(points).max(initial=0.0) > MAX_EXTENT_M:
        refuse(f"its points reach {np.abs(points).max():.3g} m from the origin (a bushing's lie "
               f"within {MAX_EXTENT_M:g} m)")
    if points.shape[1] == 2:
        points = np.column_stack([points, np.zeros(len(points))])
    quads = next((np.asarray(block.data) for block in cells if block.type == "quad9"), None)
    if quads is None or quads.ndim != 2 or quads.shape[1] != 9 or quads.size == 0:
        refuse("no quad9 cells")
    if quads.dtype.kind not in "iu" or quads.min() < 0 or quads.max() >= len(points):
        refuse(f"its cells name nodes outside [0, {len(points)})")
    fields = []
    for name, columns in zip(FIELDS, (3, None)):
        values = np.asarray(point_data[name], dtype=float)
        if values.ndim == 2 and columns == 3 and values.shape[1] == 2:
            values = np.column_stack([values, np.zeros(len(values))])
        shape_ok = values.shape == ((len(points), 3) if columns else (len(points),))
        if not shape_ok or not np.all(np.abs(values) <= MAX_EXTENT_M):
            refuse(f"its {name} (shape {values.shape}) is not a finite field on its "
                   f"{len(points)} nodes within {MAX_EXTENT_M:g} m")
        fields.append(values)
    if cycles is None or not np.isfinite(float(cycles)):
        refuse(f"its time (cycles) {cycles!r} is not a finite number")
    return points, quads.astype(np.int64), fields[0], fields[1], float(cycles)


def common_view(displacements: list[np.ndarray], radials: list[np.ndarray],
                extent_m: float) -> tuple[float, tuple[float, float]]:
    """One exaggeration and one colour range (um) for panels that are compared: the largest
    displacement of any panel drawn at a tenth of ``extent_m``, the factor rounded down to 1, 2 or
    5 times a power of ten; the range from 0 to the deepest wear (rounding noise below 0 of the
    radial displacement, ~1e-12 m, is not wear)."""
    largest = max(float(np.abs(d).max()) for d in displacements)
    raw = 0.1 * extent_m / max(largest, 1e-30)
    decade = 10.0 ** math.floor(math.log10(raw))
    scale = max(step * decade for step in (1.0, 2.0, 5.0) if step * decade <= raw)
    deepest_um = 1e6 * max(float(r.max()) for r in radials)
    return scale, (0.0, max(deepest_um, 1e-6))


def panels(folder: Path, joint: str | None = None) -> dict:
    """The run's XDMF files by joint and case: joint -> case -> path (``<case>-<joint>.xdmf``;
    the case names hold no ``-``); ``joint``: that joint's only."""
    found: dict = {}
    for path in sorted(folder.glob("*-*.xdmf")):  # a contact's bushing.xdmf is no run's
        case, _, name = path.stem.partition("-")
        found.setdefault(name, {})[case] = path
    if not found:
        contact = " (bushing.xdmf is a `fewear contact` output: open it in ParaView)" if (
            folder / "bushing.xdmf").exists() else ""
        raise FewearInputError(
            f"{folder}: no <case>-<joint>.xdmf of a `fewear run` to plot{contact}")
    if joint is not None:
        if joint not in found:
            raise FewearInputError(f"--joint {joint}: no such joint in {folder}; its joints: "
                                   + ", ".join(found))
        found = {joint: found[joint]}
    return found


def ensemble_members(folder: Path) -> int:
    """The members of the run in ``folder`` (its ``summary.json``'s ensemble), 1 for a single
    run or a summary that cannot be read: an ensemble's mesh files are member 0's (the
    configured start), its figures and CSVs hold the members' mean and spread."""
    try:
        summary = json.loads((folder / "summary.json").read_text())
        return int(summary.get("ensemble", {}).get("members", 1))
    except (OSError, ValueError, TypeError, AttributeError):
        return 1
