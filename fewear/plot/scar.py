"""The predicted wear scar beside the measured ones (matplotlib, Agg; plain data in)."""

from __future__ import annotations

from pathlib import Path

import numpy as np


def plot_scar(path: Path, predicted: tuple[np.ndarray, np.ndarray],
              measured: dict[str, tuple[np.ndarray, np.ndarray]], title: str) -> None:
    """Surface height (um, negative: worn) against x (mm): each measured profile
    ``measured[name] = (x_m, depth_m)`` thin, the ``predicted`` (x_m, depth_m) thick, over the
    measured profiles' span."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    figure, axes = plt.subplots(figsize=(7.0, 4.0))
    for name, (x, depth) in measured.items():
        axes.plot(1e3 * x, -1e6 * depth, linewidth=0.8, label=f"measured, {name}")
    span = [1e3 * f(np.concatenate([x for x, _ in measured.values()])) for f in (np.min, np.max)]
    x, depth = predicted
    axes.plot(1e3 * x, -1e6 * depth, color="black", linewidth=2.0, label="fewear FE")
    axes.set_xlim(*span)
    axes.set_xlabel("x (mm)")
    axes.set_ylabel("surface height (um)")
    axes.set_title(title)
    axes.grid(True, linewidth=0.3)
    axes.legend(fontsize=8)
    figure.tight_layout()
    figure.savefig(path, dpi=120)
    plt.close(figure)
