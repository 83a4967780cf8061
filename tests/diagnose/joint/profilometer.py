"""A simulated profilometer for tests: what a real instrument gives for a known ("true") wear depth
profile of a bushing's bore, and a simulated gauge of the maximum wear depth.

Written from its specification only (numpy; it builds a
:class:`fewear.diagnose.joint.measured.MeasuredProfile`), independently of the diagnosis.

The instrument, in order:

1. the true depth, a periodic function of the bushing-frame angle, interpolated linearly (and
   periodically) between the given points;
2. the stylus and the profile filter: a Gaussian profile filter (ISO 16610-21) of cutoff
   ``filter_cutoff_deg`` (default 1 deg; 50 % transmission at that wavelength; the weighting
   function's standard deviation is alpha cutoff / sqrt(2 pi) with alpha = sqrt(ln 2 / pi), about
   0.19 deg for 1 deg), applied to the continuous profile before sampling;
3. sampling at instrument angles start, start + step, ... (``step_deg``, default uniform random in
   [2, 5] deg; over the full circle the step is adjusted so that a whole number of steps closes
   the circle; over an arc of ``coverage_deg`` the points from start to start + coverage);
4. the instrument's angular origin differs from the bushing frame's by ``offset_deg`` (default
   uniform random in [-20, 20] deg): the reported angle is the bushing angle minus the offset, so
   a point at instrument angle m is the bushing's angle m + offset;
5. Gaussian noise of standard deviation ``noise_m`` (default 0.5 um);
6. quantisation of the depths to the resolution ``resolution_m`` (default 0.01 um).

Reported angles are normalised to [0, 360) deg and sorted, as the reader gives them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fewear.diagnose.joint.measured import MeasuredProfile

NOISE_m = 0.5e-6
RESOLUTION_m = 0.01e-6
FILTER_CUTOFF_deg = 1.0
STEP_RANGE_deg = (2.0, 5.0)
OFFSET_RANGE_deg = (-20.0, 20.0)
FINE_POINTS = 7200
"""Points of the fine grid (0.05 deg) on which the continuous profile is filtered."""
GAUSSIAN_ALPHA = math.sqrt(math.log(2.0) / math.pi)


@dataclass(frozen=True, eq=False)
class SimulatedMeasurement:
    """A simulated bore profile and the instrument settings that made it (the truth for tests)."""

    profile: MeasuredProfile
    offset_deg: float
    """The instrument's origin relative to the bushing frame: reported angle = bushing - offset."""
    step_deg: float
    start_deg: float
    coverage_deg: float


def measure_profile(angle_rad, depth_m, rng: np.random.Generator, *, cycles: int = 0,
                    step_deg: float | None = None, start_deg: float | None = None,
                    coverage_deg: float = 360.0, offset_deg: float | None = None,
                    noise_m: float = NOISE_m, filter_cutoff_deg: float = FILTER_CUTOFF_deg,
                    resolution_m: float = RESOLUTION_m) -> SimulatedMeasurement:
    """What the profilometer reports for the true bore profile ``depth_m(angle_rad)`` (module
    doc). ``start_deg`` (instrument frame) defaults to uniform random in [0, 360)."""
    if step_deg is None:
        step_deg = float(rng.uniform(*STEP_RANGE_deg))
    if offset_deg is None:
        offset_deg = float(rng.uniform(*OFFSET_RANGE_deg))
    if start_deg is None:
        start_deg = float(rng.uniform(0.0, 360.0))
    instrument_deg, step_deg = sampling_angles_deg(start_deg, step_deg, coverage_deg)
    fine_rad, fine_depth_m = filtered_profile(angle_rad, depth_m, filter_cutoff_deg)
    bushing_rad = np.deg2rad(instrument_deg + offset_deg)
    depth = np.interp(bushing_rad, fine_rad, fine_depth_m, period=2.0 * math.pi)
    depth = depth + rng.normal(0.0, noise_m, depth.size) if noise_m > 0.0 else depth
    if resolution_m > 0.0:
        depth = np.round(depth / resolution_m) * resolution_m
    reported_deg = np.mod(instrument_deg, 360.0)
    reported_deg[reported_deg >= 360.0] = 0.0
    order = np.argsort(reported_deg)
    profile = MeasuredProfile(cycles, np.deg2rad(reported_deg[order]), depth[order])
    return SimulatedMeasurement(profile, offset_deg, step_deg, start_deg, coverage_deg)


def sampling_angles_deg(start_deg: float, step_deg: float,
                        coverage_deg: float) -> tuple[np.ndarray, float]:
    """The instrument angles of the samples (deg, from ``start_deg`` on) and the step used."""
    if not 0.0 < step_deg < coverage_deg <= 360.0:
        raise ValueError(f"need 0 < step_deg ({step_deg}) < coverage_deg ({coverage_deg}) <= 360")
    if coverage_deg >= 360.0:
        count = max(3, round(360.0 / step_deg))
        step_deg = 360.0 / count
    else:
        count = int(math.floor(coverage_deg / step_deg + 1e-9)) + 1
    return start_deg + step_deg * np.arange(count), step_deg


def filtered_profile(angle_rad, depth_m, cutoff_deg: float) -> tuple[np.ndarray, np.ndarray]:
    """The true profile on a fine periodic grid (rad), Gaussian-filtered with cutoff
    ``cutoff_deg`` (0: unfiltered), the filter applied exactly as a circular convolution."""
    angle = np.mod(np.asarray(angle_rad, dtype=float), 2.0 * math.pi)
    order = np.argsort(angle)
    fine_rad = np.linspace(0.0, 2.0 * math.pi, FINE_POINTS, endpoint=False)
    fine = np.interp(fine_rad, angle[order], np.asarray(depth_m, float)[order],
                     period=2.0 * math.pi)
    if cutoff_deg <= 0.0:
        return fine_rad, fine
    sigma_rad = math.radians(GAUSSIAN_ALPHA * cutoff_deg / math.sqrt(2.0 * math.pi))
    harmonics = np.arange(FINE_POINTS // 2 + 1)
    transfer = np.exp(-0.5 * (sigma_rad * harmonics) ** 2)
    return fine_rad, np.fft.irfft(np.fft.rfft(fine) * transfer, n=FINE_POINTS)


def max_wear_growth(cycles, true_max_depth, rng: np.random.Generator, noise_m: float = NOISE_m,
                    resolution_m: float = RESOLUTION_m) -> tuple[np.ndarray, np.ndarray]:
    """Gauged maximum wear depths (m) at ``cycles``: the true ones plus Gaussian noise of standard
    deviation ``noise_m``, quantised to ``resolution_m``; cycles as integers, as given."""
    cycles = np.asarray(cycles).astype(np.int64)
    depth = np.asarray(true_max_depth, dtype=float) + rng.normal(0.0, noise_m, cycles.size)
    if resolution_m > 0.0:
        depth = np.round(depth / resolution_m) * resolution_m
    return cycles, depth
