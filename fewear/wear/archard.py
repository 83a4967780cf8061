"""Archard's wear law on the bore nodes, summed over the load steps of a cycle (seed eq. 10).

    h_j^a = h_{j-1}^a + A_j * sum_i k_{j,i}^a p_{j,i}^a s_{j,i}^a

h: wear depth at bore node a (m); k: wear coefficient (m^2/N = 1/Pa); p: contact pressure (Pa);
s: incremental sliding distance of load step i (m); A_j: extrapolation factor of block j (the
number of real cycles one simulated cycle stands for; Mukras et al., Wear 266 (2009) 822-832).
Archard, J. Appl. Phys. 24 (1953) 981: wear volume V = K F s / H, i.e. a depth k p per metre slid.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError
from fewear.wear.extensions import SlidingState


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


@dataclass(frozen=True)
class CycleSliding:
    """What one simulated crank cycle does at each bore node (arrays of shape (n,)).

    ``depth_m``: plain Archard depth of the cycle, sum over load steps of k(p, v) p s;
    ``distance_m``: sliding distance (sum of the slips s); ``time_s``: time in sliding contact;
    ``power_W_m2``: mean frictional power mu p v over that time (0 where the node never slides);
    ``depth_sensitivity``: (n, n) d(depth_m)/dh, how the cycle's wear changes when the bore
    recedes by h (the contact pressures redistribute: sum over load steps of k s dp/dh), or None
    (explicit extrapolation); ``impact_depth_m``: the depth the cycle's impacts wear
    (:mod:`fewear.wear.impact`; 0 without impact wear).
    """

    depth_m: np.ndarray
    distance_m: np.ndarray
    time_s: np.ndarray
    power_W_m2: np.ndarray
    depth_sensitivity: np.ndarray | None = None
    impact_depth_m: np.ndarray | float = 0.0


def block_wear(cycle: CycleSliding, sliding: SlidingState, extension, cycles: int,
               substeps: int = 32) -> tuple[np.ndarray, SlidingState]:
    """Depth increment (m) of a block of ``cycles`` crank cycles and the nodes' sliding state
    after it: seed eq. 10 with the wear law's history multiplier m (:mod:`fewear.wear.extensions`),

        Delta h = integral over the block of m(state) dh_cycle
               ~= (A_j / N) sum_{i<N} m(state at the middle of sub-block i) h_cycle,

    each node's state advancing by A_j times the cycle's sliding distance, time and power
    (and its crank cycles by A_j). The
    midpoint rule over N = ``substeps`` sub-blocks is exact for plain Archard (m = 1: Delta h =
    A_j h_cycle, seed eq. 10) and second-order accurate in 1/N otherwise.

    With ``cycle.depth_sensitivity`` S the step is linearly implicit (backward Euler on the
    linearised wear rate, evaluated at the block's end):

        (I - A_j diag(m_bar) S) Delta h = Delta h_explicit,   m_bar: the block's mean multiplier.

    Explicit extrapolation of seed eq. 10 amplifies a bore ripple of wavelength lambda by
    |1 - A_j k s pi E* / lambda| per block (the pressure of an elastic body flattening the ripple
    grows as pi E* / lambda): on the reference mesh node-scale ripples already grow for A_j of
    about 30 cycles, so the dwell points of one recorded cycle roughen the bore block after block.
    The implicit step damps every ripple for any A_j and equals the explicit one where the
    pressures do not depend on the wear (S = 0).

    Impact wear (``cycle.impact_depth_m``, :mod:`fewear.wear.impact`) adds A_j h_imp to the
    explicit increment: it is energy wear, not sliding, so the sliding-history multiplier m does
    not scale it; and S holds only the Archard part's dp/dh (the impact depth's own dependence
    on the wear is not linearised), so the implicit step treats h_imp as a given source.
    """
    if cycles < 1:
        raise FewearInputError(
            f"extrapolation factor A_j = {cycles!r}: must be a whole number >= 1")
    share = cycles / substeps
    multiplier_sum = np.zeros_like(cycle.depth_m)
    for i in range(substeps):
        middle = extension.advance(sliding, (i + 0.5) * share * cycle.distance_m,
                                   (i + 0.5) * share * cycle.time_s, cycle.power_W_m2,
                                   (i + 0.5) * share)
        multiplier_sum += extension.multiplier(middle)
    mean_multiplier = multiplier_sum / substeps
    increment = cycles * mean_multiplier * cycle.depth_m + cycles * cycle.impact_depth_m
    after = extension.advance(sliding, cycles * cycle.distance_m, cycles * cycle.time_s,
                              cycle.power_W_m2, cycles)
    if cycle.depth_sensitivity is not None:
        system = np.eye(increment.size) - cycles * mean_multiplier[:, None] * (
            cycle.depth_sensitivity)
        increment = np.maximum(np.linalg.solve(system, increment), 0.0)
    return increment, after


def smoothed_periodic(values: np.ndarray, angle_step_rad: float, width_rad: float) -> np.ndarray:
    """``values`` at equally spaced angles (step ``angle_step_rad``) convolved around the circle
    with a Gaussian of standard deviation ``width_rad`` (normalised: the sum, hence the worn
    volume, is kept exactly; ``width_rad`` = 0 returns the values)."""
    if width_rad <= 0.0:
        return np.asarray(values, dtype=float).copy()
    n = len(values)
    offset = angle_step_rad * np.minimum(np.arange(n), n - np.arange(n))
    kernel = np.exp(-0.5 * (offset / width_rad) ** 2)
    kernel /= kernel.sum()
    return np.real(np.fft.ifft(np.fft.fft(values) * np.fft.fft(kernel)))
