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
from scipy.linalg import circulant, expm

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
               substeps: int = 32, smoothing_width_rad: float = 0.0
               ) -> tuple[np.ndarray, SlidingState]:
    """Depth increment (m, per node) of a block of ``cycles`` crank cycles and the nodes' sliding
    state after it: seed eq. 10 with the wear law's history multiplier m
    (:mod:`fewear.wear.extensions`), smoothed around the bore by the Gaussian G of standard
    deviation ``smoothing_width_rad`` (:func:`smoothed_periodic`; 0: none),

        Delta h = G integral over the block of m(state) dh_cycle
               ~= G (A_j / N) sum_{i<N} m(state at the middle of sub-block i) h_cycle,

    each node's state advancing by A_j times the cycle's sliding distance, time and power
    (and its crank cycles by A_j). The midpoint rule over N = ``substeps`` sub-blocks is exact for
    plain Archard (m = 1: Delta h = A_j G h_cycle, seed eq. 10) and second-order accurate in 1/N
    otherwise. Impact wear (``cycle.impact_depth_m``, :mod:`fewear.wear.impact`) adds A_j h_imp:
    it is energy wear, not sliding, so m does not scale it.

    With ``cycle.depth_sensitivity`` S (d h_cycle / dh: the pressures redistribute as the bore
    recedes) the step integrates the linearised wear rate exactly (exponential Euler):

        dh/dN = G (m_bar h_cycle + h_imp) + J (h - h_0),   J = G diag(m_bar) S,
        Delta h = phi_1(A_j J) G Delta h_explicit,   phi_1(z) = (e^z - 1) / z,

    Delta h_explicit = A_j (m_bar h_cycle + h_imp) the unsmoothed explicit increment, evaluated
    by :func:`exponential_euler_increment`. h_imp is a given source (its own dependence on the
    wear is not linearised). J's eigenvalues have negative real parts where the linearisation
    holds; far beyond it (a step many times the bound of :mod:`fewear.wear.extrapolation`) the
    exponential can grow without bound, which the adaptive search treats as beyond the bound.
    Why: the contact's response to the wear is stiff (a bore ripple of wavelength lambda
    flattens at a rate k s pi E* / lambda per cycle, time constants of a few to tens of
    cycles), so explicit extrapolation makes node-scale ripples grow once A_j exceeds a few
    tens of cycles. The smoothing belongs inside J: the bore changes by the smoothed increment,
    and S alone is far stiffer than G S (the Gaussian removes the short wavelengths); a step
    that solved with S and smoothed afterwards damped modes that the smoothed wear does not have
    and lay 13 % below small explicit steps at A_j = 40 cycles. Exact for a linear rate, the
    step's error is the linearisation's (the active set and S held over the step), bounded by
    the depth increment (:mod:`fewear.wear.extrapolation`).
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
    explicit = cycles * mean_multiplier * cycle.depth_m + cycles * cycle.impact_depth_m
    after = extension.advance(sliding, cycles * cycle.distance_m, cycles * cycle.time_s,
                              cycle.power_W_m2, cycles)
    step_rad = 2.0 * np.pi / explicit.size
    increment = smoothed_periodic(explicit, step_rad, smoothing_width_rad)
    if cycle.depth_sensitivity is not None:
        # S has nonzero columns at the nodes in contact only: G m S is built on those
        coupled = np.flatnonzero(np.any(cycle.depth_sensitivity != 0.0, axis=0))
        rate_jacobian = smoothing_matrix(explicit.size, smoothing_width_rad) @ (
            mean_multiplier[:, None] * cycle.depth_sensitivity[:, coupled])
        increment = exponential_euler_increment(cycles * rate_jacobian, coupled, increment)
    # the FFT convolution leaves rounding noise (~1e-21 m) where nothing wears: clip it
    return np.maximum(increment, 0.0), after


def exponential_euler_increment(step_jacobian_columns: np.ndarray, coupled: np.ndarray,
                                explicit: np.ndarray) -> np.ndarray:
    """phi_1(M) c, phi_1(z) = (e^z - 1) / z, for M = A J and c = ``explicit`` (A times the rate
    at the start): the exact increment over the step of the linear ODE dh/dN = rate + J (h - h_0).
    M is given by its nonzero columns ``step_jacobian_columns`` (n, |U|), those of the nodes in
    contact U = ``coupled``.

    Only the nodes in contact feed back; the others follow them: h_U = phi_1(M_UU) c_U and
    h_R = c_R + M_RU phi_2(M_UU) c_U, both read from the exponential of [[M_UU, c_U, 0], [0, 0,
    1], [0, 0, 0]] (Higham, Functions of Matrices (2008), eq. 10.41 and its extension to phi_2;
    Al-Mohy & Higham, SIAM J. Sci. Comput. 33 (2011) 488): a matrix of |U| + 2 rows, not of all
    bore nodes."""
    m = coupled.size
    bordered = np.zeros((m + 2, m + 2))
    bordered[:m, :m] = step_jacobian_columns[coupled]
    bordered[:m, m] = explicit[coupled]
    bordered[m, m + 1] = 1.0
    exponential = expm(bordered)
    increment = explicit + step_jacobian_columns @ exponential[:m, m + 1]
    increment[coupled] = exponential[:m, m]
    return increment


def smoothing_matrix(n: int, width_rad: float) -> np.ndarray:
    """G (n, n): the matrix of :func:`smoothed_periodic` on ``n`` equally spaced bore nodes
    (circulant: its first column is the smoothed first unit vector); the identity for
    ``width_rad`` = 0."""
    unit = np.zeros(n)
    unit[0] = 1.0
    return circulant(smoothed_periodic(unit, 2.0 * np.pi / n, width_rad))


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
