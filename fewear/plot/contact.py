"""Pictures of a bore contact field: pressure against angle with the analytic references, and the
bushing with the pressure on its bore (matplotlib, Agg). An optional PyVista view of the FE field is
imported lazily (:func:`render_field_pyvista`).
"""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from fewear.contact.analytic import HertzLineContact, cosine_law_pressure_Pa, wrap_angle_rad


def load_angle_rad(result) -> float:
    """Direction of the force on the pin (rad); 0 for a zero force."""
    force_x, force_y = result.applied_force_N
    return math.atan2(force_y, force_x) if (force_x or force_y) else 0.0


def plot_contact_pressure(
    path: Path, result, hertz: HertzLineContact, title: str = "pin-in-bushing contact"
) -> None:
    """Two panels: p(theta - theta_F) of the FE nodes with the Hertz and cosine-law curves, and the
    bushing cross-section with the bore pressure drawn as a coloured band and outward bars."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, (profile, section) = plt.subplots(1, 2, figsize=(11.0, 4.6))
    _pressure_profile(profile, result, hertz)
    _cross_section(figure, section, result, hertz)
    figure.suptitle(title)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def _pressure_profile(axes, result, hertz: HertzLineContact) -> None:
    load_angle = load_angle_rad(result)
    relative = wrap_angle_rad(result.angle_rad - load_angle)
    order = np.argsort(relative)
    relative_deg = np.degrees(relative[order])
    axes.plot(relative_deg, result.pressure_Pa[order] / 1e6, "o-", markersize=3, label="FE nodes")
    fine = np.linspace(-math.pi, math.pi, 4001)
    axes.plot(np.degrees(fine), hertz.pressure_on_bore_Pa(fine + load_angle, load_angle) / 1e6,
              "k--", label="Hertz (small load)")
    loaded = np.abs(relative_deg[result.pressure_Pa[order] > 0.0])
    span = max(3.0 * math.degrees(hertz.contact_half_angle_rad),
               1.5 * (loaded.max() if loaded.size else 0.0), 5.0)
    if span > 30.0:
        cosine = cosine_law_pressure_Pa(fine, 0.0, hertz.force_N, hertz.bore_radius_m,
                                        hertz.width_m)
        axes.plot(np.degrees(fine), cosine / 1e6, ":", color="grey",
                  label="cosine law (conformal limit)")
    axes.set_xlim(-min(span, 180.0), min(span, 180.0))
    axes.set_xlabel("angle from the load direction (deg)")
    axes.set_ylabel("contact pressure (MPa)")
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8)


def _cross_section(figure, axes, result, hertz: HertzLineContact) -> None:
    from matplotlib.collections import LineCollection

    circle = np.linspace(0.0, 2.0 * math.pi, 361)
    bore = hertz.bore_radius_m
    axes.plot(bore * np.cos(circle), bore * np.sin(circle), "k-", linewidth=0.8)
    pin_x, pin_y = result.pin_centre_m
    axes.plot(pin_x + hertz.pin_radius_m * np.cos(circle),
              pin_y + hertz.pin_radius_m * np.sin(circle), "-", color="grey", linewidth=0.8,
              label="pin (rigid)")
    points = np.column_stack([result.x_m, result.y_m])
    closed = np.vstack([points, points[:1]])
    segments = np.stack([closed[:-1], closed[1:]], axis=1)
    pressure = np.asarray(result.pressure_Pa)
    segment_pressure = 0.5 * (pressure + np.roll(pressure, -1))
    band = LineCollection(segments, array=segment_pressure / 1e6, cmap="inferno_r", linewidth=4)
    axes.add_collection(band)
    figure.colorbar(band, ax=axes, label="contact pressure (MPa)")
    peak = pressure.max()
    if peak > 0.0:
        normal = points / np.linalg.norm(points, axis=1, keepdims=True)
        tips = points + 0.3 * bore * (pressure / peak)[:, None] * normal
        loaded = pressure > 0.0
        axes.add_collection(LineCollection(
            np.stack([points[loaded], tips[loaded]], axis=1), colors="tab:red", linewidth=0.6))
    axes.set_aspect("equal")
    limit = 1.4 * bore
    axes.set_xlim(-limit, limit)
    axes.set_ylim(-limit, limit)
    axes.set_xlabel("x (m)")
    axes.set_ylabel("y (m)")
    axes.set_title("bore pressure (bars scaled to the peak)", fontsize=9)


def render_field_pyvista(path: Path, displacement, pressure, scale: float = 0.0) -> None:
    """Off-screen PyVista picture of the pressure on the bushing mesh (optional; needs pyvista).

    ``displacement`` and ``pressure`` are DOLFINx functions on the bushing mesh; the mesh is drawn
    deformed by ``scale`` times the displacement (0: undeformed). Serial only.
    """
    import pyvista
    from dolfinx import fem, plot

    mesh = displacement.function_space.mesh
    nodal = fem.Function(fem.VectorFunctionSpace(mesh, ("Lagrange", 1)))
    nodal.interpolate(displacement)
    nodal_pressure = fem.Function(fem.FunctionSpace(mesh, ("Lagrange", 1)))
    nodal_pressure.interpolate(pressure)
    topology, cell_types, geometry = plot.create_vtk_mesh(nodal.function_space)
    grid = pyvista.UnstructuredGrid(topology, cell_types, geometry)
    values = nodal.x.array.reshape(-1, 2)
    grid.points[:, :2] += scale * values
    grid.point_data["pressure_MPa"] = nodal_pressure.x.array / 1e6
    plotter = pyvista.Plotter(off_screen=True, window_size=(800, 800))
    plotter.add_mesh(grid, scalars="pressure_MPa", cmap="inferno_r", show_edges=True)
    plotter.view_xy()
    plotter.screenshot(str(path))
    plotter.close()
