"""The result of one contact solve: plain data (NumPy arrays, SI units; no DOLFINx).

The bore nodes are the nodes of the 8-node (serendipity) quadrilaterals on the bore: element
vertices AND edge midpoints, in the undeformed configuration, sorted by angle in [0, 2 pi).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np


@dataclass(frozen=True)
class ContactResult:
    """Contact field along the bore and the pin's equilibrium for one joint force.

    Per bore node (1-D arrays, same length, sorted by ``angle_rad``):

    - ``angle_rad``: polar angle of the undeformed node about the bushing centre, in [0, 2 pi).
    - ``x_m``, ``y_m``: undeformed node coordinates (m).
    - ``pressure_Pa``: contact pressure p = k <-gap>_+ (Pa).
    - ``gap_m``: normal gap g = |x + u(x) - c| - R_p (m); negative = penalty penetration.
    - ``slip_m``: sliding distance of the step, R_p * |rotation increment| where p > 0, else 0 (m).

    Pin and forces: ``pin_centre_m`` (2,), ``applied_force_N`` (2,) the joint force on the pin,
    ``resultant_force_N`` (2,) the resultant of the contact tractions (pressure and, with friction,
    Coulomb shear) that the pin exerts on the bore, integrated with the quadrature of the weak form
    (equal to the applied force at convergence), ``normal_force_N`` (2,) its part from the
    pressure alone, ``newton_iterations`` of the solve.
    """

    angle_rad: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    pressure_Pa: np.ndarray
    gap_m: np.ndarray
    slip_m: np.ndarray
    pin_centre_m: np.ndarray
    applied_force_N: np.ndarray
    resultant_force_N: np.ndarray
    newton_iterations: int
    normal_force_N: np.ndarray = field(default_factory=lambda: np.zeros(2))

    @property
    def max_pressure_Pa(self) -> float:
        """Peak nodal contact pressure (Pa); 0 without contact."""
        return float(np.max(self.pressure_Pa)) if self.pressure_Pa.size else 0.0

    @property
    def contact_half_angle_rad(self) -> float:
        """Half the angular extent of the contact arc around the peak-pressure node (rad).

        The arc runs over the consecutive nodes with p > 0 around the peak; each end is placed where
        the gap, interpolated linearly in angle between the last node in contact and the first one
        out of it, changes sign. 0 without contact, pi when the whole bore is in contact.
        """
        return contact_half_angle(self.angle_rad, self.gap_m, self.pressure_Pa)

    @property
    def force_balance_rel_error(self) -> float:
        """|resultant - applied| / |applied| (the absolute error in N when the force is zero)."""
        error = float(np.linalg.norm(self.resultant_force_N - self.applied_force_N))
        scale = float(np.linalg.norm(self.applied_force_N))
        return error / scale if scale > 0.0 else error


def contact_half_angle(angle_rad: np.ndarray, gap_m: np.ndarray, pressure_Pa: np.ndarray) -> float:
    """Half-angle of the contact arc containing the peak pressure (see ContactResult)."""
    n = angle_rad.size
    in_contact = pressure_Pa > 0.0
    if n == 0 or not in_contact.any():
        return 0.0
    if in_contact.all():
        return math.pi
    peak = int(np.argmax(pressure_Pa))
    ends = []
    for step in (1, -1):
        last = peak
        while in_contact[(last + step) % n]:
            last += step
        first_out = last + step
        θ_last = angle_rad[last % n] + 2.0 * math.pi * (last // n)
        θ_out = angle_rad[first_out % n] + 2.0 * math.pi * (first_out // n)
        g_last, g_out = gap_m[last % n], gap_m[first_out % n]
        ends.append(θ_last + (θ_out - θ_last) * g_last / (g_last - g_out))
    return 0.5 * abs(ends[0] - ends[1])
