"""The worn bore: one frozen state from which the dynamics' clearance and the mesh's bore follow.

The wear depth h >= 0 (m) is kept at the bore nodes, identified by their angle theta in [0, 2 pi)
from the bushing centre (measured from the slide axis x). The bore wears radially outward: the
worn bore is the periodic curve

    r(theta) = R_b + h(theta),

h interpolated linearly in theta between the nodes (periodic). A re-meshed bushing puts its bore
nodes at the same angles (k pi / n) exactly on r(theta), so the state carries over unchanged.
From it:

- the dynamics' clearance c(theta): how far the rigid pin's centre can move in the direction
  theta before the pin touches r(theta); c0 + h(theta) where the worn bore conforms to the pin
  (:meth:`WearState.clearance_profile`, a :class:`fewear.mbd.contact.ClearanceProfile`);
- the mesh's bore: every bore node at angle theta sits at radius r(theta) (:meth:`bore_radius_m`).

Each node also carries its sliding history (accumulated sliding distance, time in sliding contact,
lagged frictional power) for the history-dependent wear laws of :mod:`fewear.wear.extensions`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError
from fewear.mesh.profile import periodic_linear
from fewear.wear.extensions import SlidingState

CLEARANCE_QUANTUM_M = 1e-12
"""The resolution of the clearance handed to the dynamics (1 pm, far below any wear)."""


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

    def bore_radius_m(self, inner_radius_m: float, angle_rad) -> np.ndarray:
        """r(theta) = R_b + h(theta), the worn bore's radius at ``angle_rad``."""
        return inner_radius_m + self.depth_at(angle_rad)

    def pin_clearance_m(self, inner_radius_m: float, pin_radius_m: float) -> np.ndarray:
        """c(theta) at the node angles: how far the centre of the rigid pin (radius R_p) can move
        from the bushing centre in the direction theta before the pin touches the worn bore.

        With the bore points q_k = r(theta_k) e_k and the direction u, the pin centre s u touches
        q_k where |q_k - s u| = R_p, at s_k = q_k.u - sqrt((q_k.u)^2 - |q_k|^2 + R_p^2); the
        clearance is the smallest s_k. For a circular bore it is c0 = R_b - R_p (to
        R_b R_p dtheta^2 / (8 c0) between nodes, 0.03 um on the reference mesh); for a worn bore
        that conforms to the pin it is c0 + h(theta); a groove narrower than the pin's contact
        arc is bridged, as by the real pin, so the dynamics never sees the single-node dents of
        a jagged profile.
        """
        radius = inner_radius_m + self.depth_m
        points = radius[:, None] * np.column_stack([np.cos(self.angle_rad),
                                                    np.sin(self.angle_rad)])
        directions = np.column_stack([np.cos(self.angle_rad), np.sin(self.angle_rad)])
        along = directions @ points.T  # (direction j, point k): q_k . u_j
        discriminant = along**2 - radius[None, :] ** 2 + pin_radius_m**2
        reach = along - np.sqrt(np.maximum(discriminant, 0.0))
        return np.where((discriminant >= 0.0) & (reach >= 0.0), reach, np.inf).min(axis=1)

    def clearance_profile(self, inner_radius_m: float, pin_radius_m: float):
        """The clearance joint's c(theta) (:meth:`pin_clearance_m`) for the dynamics, rounded to
        ``CLEARANCE_QUANTUM_M``: the impact dynamics with step-size control is discontinuous in
        its input (an accepted or rejected step), so wear depths that differ in the last bits
        (the FE solve's rounding differs between process counts) would otherwise send serial and
        ``mpirun`` runs along different step sequences."""
        from fewear.mbd.contact import ClearanceProfile

        clearance = self.pin_clearance_m(inner_radius_m, pin_radius_m)
        return ClearanceProfile(self.angle_rad.copy(),
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
