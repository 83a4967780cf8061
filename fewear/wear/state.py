"""The worn bore: one frozen state from which the dynamics' clearance and the mesh's bore follow.

The wear depth h (m) at the bore nodes' angles gives the worn bore r(theta) = R_b + h(theta), the
dynamics' clearance c0 + h(theta) and every bore node's radius, plus each node's sliding history
for :mod:`fewear.wear.extensions`. :class:`FlatWearState` is the same bookkeeping along a flat.
Method notes: docs/run.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError
from fewear.mbd.contact import ClearanceProfile, periodic_cubic, pin_reach_m
from fewear.mesh.profile import periodic_linear
from fewear.wear.extensions import SlidingState

CLEARANCE_QUANTUM_M = 1e-10
"""The resolution of the clearance handed to the dynamics (0.1 nm: far below the wear of a block,
microns, and the integrator's gap tolerance, 0.1 um; see :meth:`WearState.clearance_profile`)."""

CLEARANCE_DIRECTIONS = 2880
"""Directions (every 0.125 deg) in which the dynamics' clearance c(theta) is sampled, independent
of the bore mesh (:meth:`WearState.clearance_profile`)."""


@dataclass(frozen=True)
class WearState:
    """Wear depth and sliding history at the bore nodes after ``cycles`` crank cycles.

    ``angle_rad`` (n,): increasing node angles in [0, 2 pi); ``depth_m`` (n,): radial wear depth;
    ``sliding`` : the nodes' :class:`SlidingState` (arrays of shape (n,)); ``cycles``: crank cycles
    done (real cycles, the extrapolation included); ``blocks``: wear blocks done.
    """

    angle_rad: np.ndarray
    depth_m: np.ndarray
    sliding: SlidingState
    cycles: int = 0
    blocks: int = 0

    def __post_init__(self):
        angle = np.asarray(self.angle_rad, dtype=float)
        depth = np.asarray(self.depth_m, dtype=float)
        if angle.ndim != 1 or depth.shape != angle.shape or angle.size < 3:
            raise ValueError("wear state: angle_rad and depth_m must be equal-length 1-D arrays")
        if np.any(np.diff(angle) <= 0.0) or angle[0] < 0.0 or angle[-1] >= 2.0 * math.pi:
            raise ValueError("wear state: node angles must increase strictly within [0, 2 pi)")
        if not np.all(np.isfinite(depth)) or np.any(depth < 0.0):
            raise ValueError("wear state: depths must be finite and >= 0")

    @classmethod
    def unworn(cls, angle_rad: np.ndarray) -> WearState:
        """No wear and no sliding yet at the nodes ``angle_rad``."""
        zeros = np.zeros(np.size(angle_rad))
        return cls(np.asarray(angle_rad, dtype=float), zeros,
                   SlidingState(zeros.copy(), zeros.copy(), zeros.copy()))

    def depth_at(self, angle_rad) -> np.ndarray:
        """h(theta) at any angles (rad): periodic linear interpolation between the nodes."""
        return periodic_linear(self.angle_rad, self.depth_m)(angle_rad)

    def smooth_depth_at(self, angle_rad) -> np.ndarray:
        """h(theta) through the nodes by a periodic cubic spline (C2): the bore as the dynamics
        see it. Linear interpolation kinks the bore at every node, and the contact normal,
        which leans with the clearance's slope, would turn abruptly there (c'' 17 times a
        conforming lobe's h'' at the nodes, against 2.5 times with the spline)."""
        return periodic_cubic(self.angle_rad, self.depth_m)(angle_rad)

    def bore_radius_m(self, inner_radius_m: float, angle_rad) -> np.ndarray:
        """r(theta) = R_b + h(theta), the worn bore's radius at ``angle_rad``."""
        return inner_radius_m + self.depth_at(angle_rad)

    def clearance_profile(self, inner_radius_m: float, pin_radius_m: float):
        """The clearance joint's c(theta) for the dynamics: the pin's reach
        (:func:`fewear.mbd.contact.pin_reach_m`) in ``CLEARANCE_DIRECTIONS`` equally spaced
        directions against the worn bore R_b + h(theta) at the same angles (h through the nodes
        by :meth:`smooth_depth_at`), whatever the mesh. Where a pocket has worn narrower than the
        pin, c(theta) has a cusp (the pin rests on both flanks); a spline through c at the nodes
        only rounded it off by tens of microns on the default mesh (44 um after 300,000 cycles),
        and on that rounded bottom the rigid rod's orbit chattered (50-90 impacts per cycle, 50 %
        more wear) where on finer meshes it did not: the bore mesh decided the rigid rod's wear
        after 100,000 cycles. Rounded to ``CLEARANCE_QUANTUM_M``: the impact dynamics with
        step-size control is discontinuous in its input (an accepted or rejected step), so wear
        depths that differ in the last bits (the FE solve's rounding differs between process
        counts, by about 1e-14 m on the tests' case) would otherwise send serial and ``mpirun``
        runs along different step sequences. A value that differs by d falls on the other side of
        a rounding boundary with probability d / quantum: 1e-4 per direction at 0.1 nm (with
        2,880 directions, 1 pm let a serial and an ``mpirun`` run part in the tests' first
        block)."""
        angles = 2.0 * math.pi * np.arange(CLEARANCE_DIRECTIONS) / CLEARANCE_DIRECTIONS
        clearance = pin_reach_m(angles, angles, inner_radius_m + self.smooth_depth_at(angles),
                                pin_radius_m)
        return ClearanceProfile(angles,
                                np.round(clearance / CLEARANCE_QUANTUM_M) * CLEARANCE_QUANTUM_M)

    def worn_area_m2(self, inner_radius_m: float) -> float:
        """Area removed from the bore cross-section (m^2, the worn volume per unit width):
        1/2 integral of (r^2 - R_b^2) dtheta over the periodic profile (trapezoid in theta)."""
        theta = np.append(self.angle_rad, self.angle_rad[0] + 2.0 * math.pi)
        r = inner_radius_m + np.append(self.depth_m, self.depth_m[0])
        integrand = 0.5 * (r**2 - inner_radius_m**2)
        return float(np.sum(0.5 * (integrand[1:] + integrand[:-1]) * np.diff(theta)))

    def checked_against_wall(self, inner_radius_m: float, outer_radius_m: float,
                             max_wall_fraction: float) -> None:
        """Raise :class:`FewearInputError` when the wear would eat more than ``max_wall_fraction``
        of the bushing wall (the FE bushing and the clearance joint would no longer be valid)."""
        wall = outer_radius_m - inner_radius_m
        peak = int(np.argmax(self.depth_m))
        if self.depth_m[peak] > max_wall_fraction * wall:
            raise FewearInputError(
                f"wear depth {self.depth_m[peak]:.3e} m at {math.degrees(self.angle_rad[peak]):.1f}"
                f" deg after {self.cycles} cycles exceeds {max_wall_fraction:g} of the "
                f"{wall:.3e} m bushing wall ([wear_loop] max_wall_fraction): the bushing is worn "
                "through; lower [wear_loop] total_cycles or the wear coefficient")


@dataclass(frozen=True)
class FlatWearState:
    """Wear depth at the top nodes of a flat worn by a cylinder (:mod:`fewear.mesh.flat`), after
    sliding ``sliding_distance_m`` (m) in ``steps`` wear steps.

    ``x_m`` (n,): the top nodes' x, strictly increasing; ``depth_m`` (n,): their wear depth h >= 0
    along -y (m). Not periodic: the worn top is y_top(x) = y0 - h(x), h linear in x between the
    nodes and held at its end values beyond them (:meth:`depth_at`), the counterpart of the
    bore's r(theta) = R_b + h(theta).
    """

    x_m: np.ndarray
    depth_m: np.ndarray
    sliding_distance_m: float = 0.0
    steps: int = 0

    def __post_init__(self):
        x = np.asarray(self.x_m, dtype=float)
        depth = np.asarray(self.depth_m, dtype=float)
        if x.ndim != 1 or depth.shape != x.shape or x.size < 2:
            raise ValueError("flat wear state: x_m and depth_m must be equal-length 1-D arrays")
        if not np.all(np.isfinite(x)) or np.any(np.diff(x) <= 0.0):
            raise ValueError("flat wear state: node x must be finite and increase strictly")
        if not np.all(np.isfinite(depth)) or np.any(depth < 0.0):
            raise ValueError("flat wear state: depths must be finite and >= 0")

    @classmethod
    def unworn(cls, x_m: np.ndarray) -> FlatWearState:
        """No wear yet at the top nodes ``x_m``."""
        return cls(np.asarray(x_m, dtype=float), np.zeros(np.size(x_m)))

    def depth_at(self, x_m) -> np.ndarray:
        """h(x) at any x (m): linear between the nodes, exact at them."""
        return np.interp(x_m, self.x_m, self.depth_m)

    def top_y_m(self, unworn_top_y_m: float, x_m) -> np.ndarray:
        """y_top(x) = y0 - h(x), the worn top (m) over the unworn one at y0."""
        return unworn_top_y_m - self.depth_at(x_m)

    def worn_by(self, increment_m: np.ndarray, sliding_m: float) -> FlatWearState:
        """The state after one wear step: depths deeper by ``increment_m`` (per node, m) and
        ``sliding_m`` (m) more slid."""
        return FlatWearState(self.x_m, self.depth_m + increment_m,
                             self.sliding_distance_m + sliding_m, self.steps + 1)

    def worn_area_m2(self) -> float:
        """Area removed from the flat's cross-section, integral of h dx (m^2, the worn volume
        per unit length; trapezoid rule between the nodes)."""
        return float(np.trapz(self.depth_m, self.x_m))
