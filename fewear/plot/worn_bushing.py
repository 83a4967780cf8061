"""The worn bushing of a ``fewear run`` read back from its files (``<case>-<joint>.xdmf`` +
``.h5``, through meshio, never the model), and the view that compares the cases and joints: one
exaggeration of the displacement, so that microns of wear show on a centimetre bushing, and one
colour scale from zero (``fewear plot``, :mod:`fewear.commands.plot`, draws it in PyVista)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError

VTK_BIQUADRATIC_QUAD = 28
FIGURE = "worn_bushing.png"
"""The figure written into the run's folder off screen."""


def last_block(path: Path):
    """(points (n, 3), quad9 cells in VTK order, displacement (n, 3) m, radial (n,) m, cycles)."""
    import meshio

    try:
        with meshio.xdmf.TimeSeriesReader(str(path)) as reader:
            points, cells = reader.read_points_cells()
            for k in range(reader.num_steps):
                cycles, point_data, _ = reader.read_data(k)
    except Exception as exc:  # meshio raises many kinds on a broken file
        raise FewearInputError(f"cannot read {path}: {exc}") from None
    quads = next(block.data for block in cells if block.type == "quad9")
    return (points, quads, point_data["mesh_displacement_m"],
            point_data["radial_displacement_m"], cycles)


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
    for path in sorted(folder.glob("*.xdmf")):
        case, _, name = path.stem.partition("-")
        found.setdefault(name or case, {})[case] = path
    if not found:
        raise FewearInputError(f"{folder}: no <case>-<joint>.xdmf of a `fewear run` to plot")
    if joint is not None:
        if joint not in found:
            raise FewearInputError(f"--joint {joint}: no such joint in {folder}; its joints: "
                                   + ", ".join(found))
        found = {joint: found[joint]}
    return found

