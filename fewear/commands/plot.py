"""``fewear plot DIR``: the worn bushing of a ``fewear run`` in PyVista, coloured by wear depth.

Reads only the run's files (:mod:`fewear.plot.worn_bushing`); this command's process imports
neither DOLFINx nor PETSc, so VTK and DOLFINx never share a process. The mesh is drawn at its last
block: one row of panels per clearance joint, the cases (rod models) side by side, all at one
exaggeration and on one colour scale (``--joint NAME``: that joint's row only); shown on screen,
or written to ``DIR/worn_bushing.png`` off screen (``PYVISTA_OFF_SCREEN=true`` or no display;
VTK's warnings, such as the missing X server's, are switched off).
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from fewear.errors import FewearInputError
from fewear.loop.outputs import MAX_WEAR_PNG, PROFILES_PNG
from fewear.plot.worn_bushing import (
    FIGURE,
    VTK_BIQUADRATIC_QUAD,
    common_view,
    ensemble_members,
    last_block,
    panels,
)


def main(args) -> int:
    folder = Path(args.folder)
    layout = panels(folder, getattr(args, "joint", None))
    members = ensemble_members(folder)
    which = "" if members == 1 else f", member 0 of {members} (the configured start)"
    import pyvista
    import vtk

    vtk.vtkObject.GlobalWarningDisplayOff()
    off_screen = os.environ.get("PYVISTA_OFF_SCREEN", "").lower() == "true" or not (
        os.environ.get("DISPLAY"))
    blocks = {path: last_block(path) for cases in layout.values() for path in cases.values()}
    first = next(iter(blocks.values()))
    scale, clim = common_view([block[2] for block in blocks.values()],
                              [block[3] for block in blocks.values()],
                              float(np.ptp(first[0][:, 0])))
    rows, columns = len(layout), max(len(cases) for cases in layout.values())
    plotter = pyvista.Plotter(shape=(rows, columns), off_screen=off_screen,
                              window_size=(600 * columns, 600 * rows))
    for row, (joint, cases) in enumerate(layout.items()):
        for column, (case, path) in enumerate(cases.items()):
            points, quads, displacement, radial, cycles = blocks[path]
            grid = pyvista.UnstructuredGrid(
                np.column_stack([np.full(len(quads), 9), quads]).ravel(),
                np.full(len(quads), VTK_BIQUADRATIC_QUAD), points + scale * displacement)
            grid.point_data["wear depth (um)"] = 1e6 * np.maximum(radial, 0.0)
            plotter.subplot(row, column)
            plotter.add_mesh(grid, scalars="wear depth (um)", cmap="viridis", clim=clim,
                             scalar_bar_args={"fmt": "%.1f"})
            plotter.add_text(f"{case}, joint {joint}{which}, {cycles:,.0f} cycles, "
                             f"motion x{scale:g}", font_size=10)
            plotter.view_xy()
    if members > 1:
        print(f"fewear plot: {folder} holds an ensemble of {members} members: the bushing "
              f"drawn is member 0's (the configured start); the members' mean with its sd band "
              f"and range is in {PROFILES_PNG} and {MAX_WEAR_PNG} (their figures in "
              "wear_profile_ensemble.csv, max_wear_ensemble.csv)")
    if not off_screen:
        plotter.show()
        return 0
    target = folder / FIGURE
    try:
        plotter.screenshot(str(target))
    except OSError as exc:
        raise FewearInputError(f"cannot write {target}: {exc.strerror or exc}") from None
    finally:
        plotter.close()  # its render window and OpenGL context, at once (a notebook plots again)
    print(f"fewear plot: wrote {target}")
    return 0
