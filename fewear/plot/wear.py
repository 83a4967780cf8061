"""Figures of the wear prediction: wear depth around the bore (seed Fig. 7a) and the maximum depth
against cycles (seed Fig. 7b)."""

from __future__ import annotations

import numpy as np


def plot_wear_profiles(profiles: dict, path, cycles: float) -> None:
    """Wear depth (um) against bore angle, and the bore outline with the wear exaggerated.

    ``profiles``: label -> (angle_rad, depth_m) of nodes sorted by angle.
    """
    _profile_figure(profiles, {}, path, f"wear depth after {cycles:.0f} crank cycles",
                    "bore outline, wear exaggerated")


def _profile_figure(profiles: dict, bands: dict, path, title: str, outline_title: str) -> None:
    """The unrolled depth (um) of ``profiles`` (label -> (angle_rad, depth_m)), each with the
    bands of ``bands`` (label -> {"sd", "min", "max": depth_m}: +- sd and, lighter, the range)
    if it has one, and beside it the bore outline, the wear exaggerated."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure = plt.figure(figsize=(11, 4.5))
    unrolled = figure.add_subplot(1, 2, 1)
    polar = figure.add_subplot(1, 2, 2, projection="polar")
    peak = max(float(np.max(depth)) for _, depth in profiles.values()) or 1.0
    for label, (angle, depth) in profiles.items():
        degrees, depth_um = np.degrees(angle), 1e6 * depth
        line, = unrolled.plot(degrees, depth_um, label=label)
        if label in bands:
            sd = 1e6 * bands[label]["sd"]
            unrolled.fill_between(degrees, depth_um - sd, depth_um + sd, color=line.get_color(),
                                  alpha=0.25)
            unrolled.fill_between(degrees, 1e6 * bands[label]["min"], 1e6 * bands[label]["max"],
                                  color=line.get_color(), alpha=0.1)
        closed = np.append(angle, angle[0] + 2 * np.pi)
        polar.plot(closed, 1.0 + 0.3 * np.append(depth, depth[0]) / peak, label=label)
    polar.plot(np.linspace(0, 2 * np.pi, 361), np.ones(361), "k:", lw=0.8, label="unworn bore")
    polar.set_yticklabels([])
    polar.set_title(outline_title, fontsize=10)
    unrolled.set(xlabel="angle on the bore from the slide axis x (deg)",
                 ylabel="wear depth (um)", xlim=(0, 360), title=title)
    unrolled.set_xticks(range(0, 361, 45))
    unrolled.grid(alpha=0.3)
    unrolled.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def plot_max_wear(series: dict, path) -> None:
    """Maximum wear depth (um) against crank cycles, one line per rod model (seed Fig. 7b).

    ``series``: label -> (cycles, max_depth_m) after each block.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6, 4.5))
    for label, (cycles, depth) in series.items():
        axes.plot(np.append(0, cycles), 1e6 * np.append(0.0, depth), "o-", ms=3,
                  label=label)
    axes.set(xlabel="crank cycles", ylabel="maximum wear depth (um)",
             title="maximum wear depth at the clearance joints")
    axes.grid(alpha=0.3)
    axes.legend()
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def plot_max_wear_bands(series: dict, path) -> None:
    """Maximum wear depth (um) against crank cycles as the mean of several runs with a band of
    one standard deviation either side (and a lighter one of their range, if given), one line
    per label.

    ``series``: label -> (cycles, {"mean": [m], "sd": [m], optional "min", "max": [m]}) at the
    listed cycle counts.
    """
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(6.5, 4.5))
    for label, (cycles, depth) in series.items():
        cycles = np.append(0, cycles)
        mean = 1e6 * np.append(0.0, depth["mean"])
        sd = 1e6 * np.append(0.0, depth["sd"])
        line, = axes.plot(cycles, mean, "o-", ms=3, label=label)
        axes.fill_between(cycles, mean - sd, mean + sd, color=line.get_color(), alpha=0.25)
        if "min" in depth:
            axes.fill_between(cycles, 1e6 * np.append(0.0, depth["min"]),
                              1e6 * np.append(0.0, depth["max"]), color=line.get_color(),
                              alpha=0.1)
    ranged = any("min" in depth for _, depth in series.values())
    axes.set(xlabel="crank cycles", ylabel="maximum wear depth (um)",
             title="maximum wear depth: mean of the runs, +- one standard deviation"
             + (",\nlighter: their range" if ranged else ""))
    axes.grid(alpha=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)


def plot_wear_profile_bands(profiles: dict, path, cycles: float) -> None:
    """Wear depth (um) against bore angle as the mean of several runs, with bands of one
    standard deviation either side and (lighter) of their range, one line per label; beside
    it the bore outline of the mean, the wear exaggerated.

    ``profiles``: label -> (angle_rad, {"mean", "sd", "min", "max": depth_m}) of nodes sorted
    by angle.
    """
    _profile_figure({label: (angle, depth["mean"]) for label, (angle, depth) in profiles.items()},
                    {label: depth for label, (_, depth) in profiles.items()}, path,
                    f"wear depth after {cycles:.0f} crank cycles: mean of the members,\n"
                    "+- one standard deviation, lighter: their range",
                    "bore outline of the mean, wear exaggerated")
