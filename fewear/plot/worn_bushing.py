"""``fewear plot DIR``: the worn bushing of a ``fewear run`` in PyVista, coloured by wear depth.

Reads only the run's files (``<case>.xdmf`` + ``.h5``, through meshio), never the model; this
command's process imports neither DOLFINx nor PETSc, so VTK and DOLFINx never share a process.
The mesh is drawn at its last block, the displacement exaggerated so that microns of wear show on
a centimetre bushing; shown on screen, or written to ``DIR/<case>_worn_bushing.png`` off screen
(``PYVISTA_OFF_SCREEN=true`` or no display).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError

VTK_BIQUADRATIC_QUAD = 28


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


def main(args) -> int:
    folder = Path(args.folder)
    files = sorted(folder.glob("*.xdmf"))
    if not files:
        raise FewearInputError(f"{folder}: no <case>.xdmf of a `fewear run` to plot")
    import pyvista

    off_screen = os.environ.get("PYVISTA_OFF_SCREEN", "").lower() == "true" or not (
        os.environ.get("DISPLAY"))
    plotter = pyvista.Plotter(shape=(1, len(files)), off_screen=off_screen,
                              window_size=(600 * len(files), 600))
    for column, path in enumerate(files):
        points, quads, displacement, radial, cycles = last_block(path)
        scale = 0.1 * np.ptp(points[:, 0]) / max(np.abs(displacement).max(), 1e-30)
        grid = pyvista.UnstructuredGrid(
            np.column_stack([np.full(len(quads), 9), quads]).ravel(),
            np.full(len(quads), VTK_BIQUADRATIC_QUAD), points + scale * displacement)
        grid.point_data["wear depth (um)"] = 1e6 * radial
        plotter.subplot(0, column)
        plotter.add_mesh(grid, scalars="wear depth (um)", cmap="viridis")
        plotter.add_text(f"{path.stem} rod, {cycles:,.0f} cycles, motion x{scale:.0f}",
                         font_size=10)
        plotter.view_xy()
    if off_screen:
        target = folder / "worn_bushing.png"
        plotter.screenshot(str(target))
        print(f"fewear plot: wrote {target}")
    else:
        plotter.show()
    return 0
