"""Figures of a joint diagnosis (:mod:`fewear.diagnose.joint.diagnose`): the measured profiles
against the believed and the extended model. matplotlib with the Agg backend."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_joint_fits(diagnosis, path: Path) -> None:
    """Measured profiles against the believed and the extended model, one panel per count."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    obs = diagnosis.observations
    counts = np.unique(obs.cycles[obs.is_profile])
    fig, axes = plt.subplots(1, max(len(counts), 1), figsize=(3.2 * max(len(counts), 1), 3.2),
                             sharey=True, squeeze=False)
    for ax, cycles in zip(axes[0], counts):
        at = (obs.cycles == cycles) & obs.is_profile
        angle = np.degrees(obs.angle_rad[at])
        ax.plot(angle, obs.depth_m[at] * 1e6, ".", ms=3, label="measured")
        ax.plot(angle, diagnosis.baseline_depth_m[at] * 1e6, "-", label="believed model")
        ax.plot(angle, diagnosis.extended_depth_m[at] * 1e6, "--", label="extended model")
        held = "held out" if not obs.train[at][0] else "training"
        ax.set_title(f"{int(cycles):,} cycles ({held})", fontsize=9)
        ax.set_xlabel("angle (deg, instrument)")
    axes[0][0].set_ylabel("wear depth (um)")
    axes[0][0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
