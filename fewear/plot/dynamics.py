"""Plots of a joint-load history (fewear.mbd.history.JointHistory): forces and pin-centre orbit."""

from __future__ import annotations

import numpy as np

from fewear.mbd.history import MODES

_MODE_COLOURS = {"free": "tab:green", "impact": "tab:red", "contact": "tab:blue"}


def plot_forces(histories: dict, path) -> None:
    """Magnitude of the joint reaction force against crank angle, one line per labelled history
    (the seed's Fig. 6a)."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(7.0, 4.0))
    for label, history in histories.items():
        angle_deg = np.degrees(history.crank_angle_rad - history.crank_angle_rad[0])
        ax.plot(angle_deg, np.linalg.norm(history.reaction_force_N, axis=1), lw=0.8, label=label)
    ax.set_xlabel("crank angle in the recorded cycle(s) (deg)")
    ax.set_ylabel("joint reaction force |F| (N)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_orbit(history, clearance_m: float, path, title: str = "pin-centre path") -> None:
    """The pin-centre path in the bushing frame inside the clearance circle, coloured by mode
    (the seed's Fig. 6b); lengths in mm."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(5.0, 5.0))
    angle = np.linspace(0.0, 2.0 * np.pi, 361)
    ax.plot(1e3 * clearance_m * np.cos(angle), 1e3 * clearance_m * np.sin(angle), "k-", lw=0.8,
            label="clearance circle")
    e_mm = 1e3 * history.eccentricity_m
    ax.plot(e_mm[:, 0], e_mm[:, 1], color="0.6", lw=0.5)
    for code, name in enumerate(MODES):
        mask = history.mode == code
        if mask.any():
            ax.plot(e_mm[mask, 0], e_mm[mask, 1], ".", ms=2.0, color=_MODE_COLOURS[name],
                    label=name)
    ax.set_aspect("equal")
    limit = 1.15e3 * clearance_m
    ax.set_xlim(-limit, limit)
    ax.set_ylim(-limit, limit)
    ax.set_xlabel("e_x (mm)")
    ax.set_ylabel("e_y (mm)")
    ax.set_title(title)
    ax.legend(loc="upper right", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
