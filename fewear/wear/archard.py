"""Archard's wear law on the bore nodes, summed over the load steps of a cycle (seed eq. 10).

    h_j^a = h_{j-1}^a + A_j * sum_i k_{j,i}^a p_{j,i}^a s_{j,i}^a

h: wear depth at bore node a (m); k: wear coefficient (m^2/N = 1/Pa); p: contact pressure (Pa);
s: incremental sliding distance of load step i (m); A_j: extrapolation factor of block j (the
number of real cycles one simulated cycle stands for; Mukras et al., Wear 266 (2009) 822-832).
Archard, J. Appl. Phys. 24 (1953) 981: wear volume V = K F s / H, i.e. a depth k p per metre slid.
"""

from __future__ import annotations

import numpy as np

from fewear.errors import FewearInputError


def cycle_wear_depth_m(k_m2_N, pressure_Pa, slip_m) -> np.ndarray:
    """Wear depth (m) of one simulated cycle at each node: sum over load steps of k p s.

    Arrays of shape (n_steps, n_nodes) (or broadcastable to it); returns shape (n_nodes,).
    """
    arrays = (np.asarray(a, dtype=float) for a in (k_m2_N, pressure_Pa, slip_m))
    k, p, s = np.broadcast_arrays(*arrays)
    for name, values in (("wear coefficient", k), ("pressure", p), ("slip", s)):
        if not np.all(np.isfinite(values)) or np.any(values < 0):
            raise FewearInputError(f"{name} must be finite and non-negative for Archard's law")
    return np.sum(k * p * s, axis=0)


def advance_wear_depth_m(previous_depth_m, cycle_depth_m,
                         extrapolation_factor: float) -> np.ndarray:
    """Seed eq. 10: the depth after block j, h_j = h_{j-1} + A_j * (one simulated cycle's depth)."""
    if not extrapolation_factor >= 1:
        raise FewearInputError(
            f"extrapolation factor A_j = {extrapolation_factor!r}: must be a number >= 1"
        )
    previous = np.asarray(previous_depth_m, dtype=float)
    return previous + extrapolation_factor * np.asarray(cycle_depth_m)
