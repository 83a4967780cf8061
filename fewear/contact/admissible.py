"""Which joint forces the contact model can carry, and the error for those it cannot.

The model is linear elastic with small displacements. A force is admissible while the bore's
largest nodal displacement stays below ``WALL_FRACTION`` of the bushing wall R_o - R_b: beyond
that the strains across the wall are far from small (and the bushing material far past its
elastic range), and the solution means nothing even when Newton finds one. For a force that is not
admissible (or that Newton cannot balance), both contact paths raise :class:`ContactLoadError`,
which names the force, the reason and the admissible range.

The admissible range is derived from the model: under a large force the contact spreads over
the half of the bore facing the load and the pressure tends to the cosine law
p(theta) = 2|F| / (pi R_b L) cos(theta - theta_F) (REFERENCES.md, "Hertz line contact"). The bore
displacement under it is linear in |F|, so the largest admissible magnitude in the direction of
F is |F|_max = u_max / max_q |u_q(1 N)|, with u_max = ``WALL_FRACTION`` (R_o - R_b) and u(1 N)
the displacement under the cosine-law load of 1 N (computed by each path with its own elastic
operator).
"""

from __future__ import annotations

import math

import numpy as np

from fewear.errors import FewearInputError

# The bore may move by at most this fraction of the wall thickness R_o - R_b (small strains).
WALL_FRACTION = 0.1


class ContactLoadError(FewearInputError):
    """A joint force the bushing contact model cannot carry (see the module docstring)."""

    def __init__(self, force_N: np.ndarray, reason: str, displacement_limit_m: float,
                 admissible_N: float):
        self.force_N = np.array(force_N, dtype=float)
        self.admissible_N = admissible_N
        super().__init__(
            f"force = ({self.force_N[0]:g}, {self.force_N[1]:g}) N: the bushing cannot carry "
            f"it: {reason}. Allowed are forces under which the bore moves by less than "
            f"{displacement_limit_m:g} m ({WALL_FRACTION:g} of the wall, small strains): in "
            f"this direction |F| <= {admissible_N:.3g} N (linear elastic bushing under the "
            f"cosine-law pressure of a fully spread contact)")


def displacement_limit_m(problem) -> float:
    """The largest admissible bore displacement (m): ``WALL_FRACTION`` (R_o - R_b)."""
    geometry = problem.geometry
    return WALL_FRACTION * (geometry.outer_radius_m - geometry.inner_radius_m)


def cosine_law_nodal_forces(points_m: np.ndarray, weights_m: np.ndarray, direction: np.ndarray,
                            inner_radius_m: float, width_m: float) -> np.ndarray:
    """Nodal forces (n, 2), N/m, of the cosine-law pressure of a 1 N joint force along
    ``direction`` on the bore nodes: f_q = w_q p(theta_q) e_r(theta_q), with
    p = 2 / (pi R_b L) <cos(theta - theta_F)>_+ (their sum is direction / L)."""
    radial = points_m / np.hypot(points_m[:, 0], points_m[:, 1])[:, None]
    pressure = 2.0 / (math.pi * inner_radius_m * width_m) * np.maximum(radial @ direction, 0.0)
    return (weights_m * pressure)[:, None] * radial


def beyond_small_displacements(problem, max_displacement_m: float) -> str | None:
    """Why a solution with this largest bore displacement (m) is not admissible (a sentence),
    or None if it is."""
    if max_displacement_m < displacement_limit_m(problem):
        return None
    return f"the bore would move by {max_displacement_m:.3g} m"
