"""Pictures of a bore contact field: pressure against angle with the analytic references, and the
bushing with the pressure on its bore (matplotlib, Agg; plain data in, no DOLFINx).

The full FE fields (displacement, pressure) go to ``bushing.xdmf`` for ParaView instead of a
PyVista view: in one process with DOLFINx, VTK 9.7's scalar bar aborts (std::bad_alloc in
std::regex, a libstdc++ clash), and the contact zone is too narrow to see on the whole bushing.
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
