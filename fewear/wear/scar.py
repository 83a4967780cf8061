"""A wear scar's measures, and the closed form of a flat worn by an unworn ring (no DOLFINx).

Block on ring with the ring unworn: the block's scar is the ring's arc sunk by the depth d, a
circular segment of the ring (radius R) whose area, the worn area per unit length, is

    A(d) = R^2 acos((R - d)/R) - (R - d) sqrt(2 R d - d^2)     (~ (4/3) sqrt(2 R d) d),

and whose chord, the scar's width, is 2 sqrt(2 R d - d^2); the depth at x is
h(x) = d - R + sqrt(R^2 - x^2). By Archard's law (J. Appl. Phys. 24 (1953) 981) the area after
sliding S under the line load P' is A = k P' S whatever the pressure distribution, so d follows
from A by inverting A(d) (:func:`ring_arc_depth_m`).

Measured scars are summed up as published (Cruzado et al., Rev. Metal. 46 (2010) 106-114, as
read by LevelSetWear's ``extractBOR``): the depth is the largest wear, the width the extent where
the wear exceeds a share of it (5 %), its ends interpolated linearly between the nodes.
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import brentq

EDGE_SHARE = 0.05
"""The scar's edges: where the wear first exceeds this share of its depth."""


def ring_arc_area_m2(radius_m: float, depth_m: float) -> float:
    """A(d): area (m^2) of the ring's segment of depth d (module docstring)."""
    rest = radius_m - depth_m
    return radius_m**2 * math.acos(rest / radius_m) - rest * math.sqrt(
        2.0 * radius_m * depth_m - depth_m**2)


def ring_arc_depth_m(radius_m: float, area_m2: float) -> float:
    """The depth d (m) of the ring's segment of area ``area_m2`` (m^2): A(d) inverted, d <= R."""
    if area_m2 <= 0.0:
        return 0.0
    return brentq(lambda depth: ring_arc_area_m2(radius_m, depth) - area_m2, 0.0, radius_m,
                  xtol=1e-16, rtol=1e-14)


def ring_arc_width_m(radius_m: float, depth_m: float, edge_share: float = 0.0) -> float:
    """Width (m) of the ring's segment of depth d where its depth exceeds ``edge_share`` d:
    2 sqrt(2 R e - e^2), e = (1 - edge_share) d (the chord for 0)."""
    sunk = (1.0 - edge_share) * depth_m
    return 2.0 * math.sqrt(2.0 * radius_m * sunk - sunk**2)


def scar_depth_and_width_m(x_m, depth_m, edge_share: float = EDGE_SHARE) -> tuple[float, float]:
    """The scar's largest depth (m) and width (m): from the first to the last crossing of
    ``edge_share`` times that depth, each interpolated linearly between the nodes (the
    profile's ends if it exceeds the share there)."""
    x, depth = np.asarray(x_m, dtype=float), np.asarray(depth_m, dtype=float)
    deepest = float(depth.max())
    if deepest <= 0.0:
        return 0.0, 0.0
    level = edge_share * deepest
    worn = np.flatnonzero(depth > level)

    def crossing(inside: int, outside: int) -> float:
        if outside < 0 or outside >= x.size:
            return float(x[inside])
        share = (depth[inside] - level) / (depth[inside] - depth[outside])
        return float(x[inside] + share * (x[outside] - x[inside]))

    return deepest, crossing(worn[-1], worn[-1] + 1) - crossing(worn[0], worn[0] - 1)


MIDDLE_SHARE = 0.9
"""A scar is a W where its middle is shallower than this share of its depth, else a U."""


def scar_shape(x_m, depth_m, edge_share: float = EDGE_SHARE) -> str:
    """"U" or "W": the depth half way between the scar's edges (:func:`scar_depth_and_width_m`)
    against ``MIDDLE_SHARE`` of the largest. A gross-slip fretting scar is a U (deepest in the
    middle), a partial-slip one a W (the stick zone in the middle unworn; Vingsbo & Soderberg,
    Wear 126 (1988) 131)."""
    x, depth = np.asarray(x_m, dtype=float), np.asarray(depth_m, dtype=float)
    deepest = float(depth.max())
    worn = x[depth > edge_share * deepest]
    middle = float(np.interp(0.5 * (worn[0] + worn[-1]), x, depth))
    return "W" if middle < MIDDLE_SHARE * deepest else "U"
