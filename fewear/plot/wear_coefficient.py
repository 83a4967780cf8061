"""The fitted wear coefficient k(p, v) with the test points, like the seed's Fig. 4."""

from __future__ import annotations

from pathlib import Path

import numpy as np

GRID_POINTS = 40
K_UNIT_m2_N = 1e-13


def plot_wear_coefficient(
    model,
    path: str | Path,
    *,
    pressure_Pa=None,
    velocity_m_s=None,
    k_m2_N=None,
    title: str = "Wear coefficient k(p, v)",
) -> Path:
    """Write a PNG: left, the surface k(p, v) over the model's training box in 3D with the tests
    as x markers (the seed's Fig. 4); right, the same as a contour map on log axes.

    ``model``: a callable k(p [Pa], v [m/s]) -> k [m^2/N]; the box is its ``pressure_range_Pa`` and
    ``velocity_range_m_s`` when it has them, else the range of the test points (which are then
    required). Pressures are shown in MPa, k in 1e-13 m^2/N.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    tests = None
    if pressure_Pa is not None:
        tests = [np.asarray(a, float).ravel() for a in (pressure_Pa, velocity_m_s, k_m2_N)]
    p_range, v_range = _box(model, tests)
    p = np.geomspace(*p_range, GRID_POINTS)
    v = np.geomspace(*v_range, GRID_POINTS)
    pp, vv = np.meshgrid(p, v)
    kk = np.asarray(model(pp, vv)) / K_UNIT_m2_N

    figure = plt.figure(figsize=(12.0, 5.0))
    surface = figure.add_subplot(1, 2, 1, projection="3d")
    surface.plot_surface(pp / 1e6, vv, kk, cmap="viridis", alpha=0.8, linewidth=0)
    contour = figure.add_subplot(1, 2, 2)
    filled = contour.contourf(pp / 1e6, vv, kk, levels=20, cmap="viridis")
    figure.colorbar(filled, ax=contour, label="k [1e-13 m$^2$/N]")
    if tests is not None:
        tp, tv, tk = tests
        surface.scatter(tp / 1e6, tv, tk / K_UNIT_m2_N, marker="x", color="red", s=30,
                        depthshade=False, label="tests")
        surface.legend(loc="upper left")
        contour.scatter(tp / 1e6, tv, marker="x", color="red", s=30, clip_on=False)
    surface.set_xlabel("pressure p [MPa]")
    surface.set_ylabel("velocity v [m/s]")
    surface.set_zlabel("k [1e-13 m$^2$/N]")
    contour.set_xscale("log")
    contour.set_yscale("log")
    contour.set_xlabel("pressure p [MPa]")
    contour.set_ylabel("velocity v [m/s]")
    figure.suptitle(title)
    figure.tight_layout()
    path = Path(path)
    figure.savefig(path, dpi=120)
    plt.close(figure)
    return path


def _box(model, tests):
    if hasattr(model, "pressure_range_Pa"):
        return tuple(model.pressure_range_Pa), tuple(model.velocity_range_m_s)
    if tests is None:
        raise ValueError("a model without a training box needs the test points to set the axes")
    return (tests[0].min(), tests[0].max()), (tests[1].min(), tests[1].max())
