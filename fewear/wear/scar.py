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
the wear exceeds a share of it (5 %), its ends interpolated linearly between the nodes; the
extent is the contiguous one about the deepest point, so that a dip beside the scar is left out
(:func:`scar_edges`).
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


def scar_edges(x_m, depth_m, edge_share: float = EDGE_SHARE, noise_floor_m: float = 0.0
               ) -> tuple[float, float, float, int, int]:
    """The scar of a profile: its largest depth (m), its left and right edges (m) and the first
    and last node inside it. The scar is the contiguous run of nodes around the deepest one
    whose depth exceeds the edge level, the larger of ``edge_share`` times the largest depth
    and ``noise_floor_m`` (a dip elsewhere, apart from the scar, is not part of it); each edge
    is interpolated linearly between the last node inside and the first outside (the profile's
    end where the scar reaches it). (0, 0, 0, -1, -1) for a profile without wear."""
    x, depth = np.asarray(x_m, dtype=float), np.asarray(depth_m, dtype=float)
    deepest_node = int(np.argmax(depth))
    deepest = float(depth[deepest_node])
    if deepest <= 0.0:
        return 0.0, 0.0, 0.0, -1, -1
    level = max(edge_share * deepest, noise_floor_m)
    below = np.flatnonzero(depth <= level)
    first = int(below[below < deepest_node].max(initial=-1)) + 1
    last = int(below[below > deepest_node].min(initial=x.size)) - 1

    def crossing(inside: int, outside: int) -> float:
        if outside < 0 or outside >= x.size:
            return float(x[inside])
        share = (depth[inside] - level) / (depth[inside] - depth[outside])
        return float(x[inside] + share * (x[outside] - x[inside]))

    return deepest, crossing(first, first - 1), crossing(last, last + 1), first, last


def scar_depth_and_width_m(x_m, depth_m, edge_share: float = EDGE_SHARE,
                           noise_floor_m: float = 0.0) -> tuple[float, float]:
    """The scar's largest depth (m) and width (m), between its edges (:func:`scar_edges`)."""
    deepest, left, right, _, _ = scar_edges(x_m, depth_m, edge_share, noise_floor_m)
    return deepest, right - left


def scar_worn_area_m2(x_m, depth_m, edge_share: float = EDGE_SHARE,
                      noise_floor_m: float = 0.0) -> float:
    """The scar's worn area per unit length (m^2): the depth, linear between the nodes,
    integrated between the scar's edges (:func:`scar_edges`; the edge level at an edge)."""
    x, depth = np.asarray(x_m, dtype=float), np.asarray(depth_m, dtype=float)
    deepest, left, right, first, last = scar_edges(x, depth, edge_share, noise_floor_m)
    if deepest <= 0.0:
        return 0.0
    level = max(edge_share * deepest, noise_floor_m)
    xs = np.concatenate([[left], x[first:last + 1], [right]])
    ds = np.concatenate([[level if left < x[first] else depth[first]], depth[first:last + 1],
                         [level if right > x[last] else depth[last]]])
    return float(np.sum(0.5 * (ds[1:] + ds[:-1]) * np.diff(xs)))


MIDDLE_SHARE = 0.9
"""A scar is a W where its middle is shallower than this share of its depth, else a U."""
MIDDLE_WINDOW_SHARE = 0.2
"""The scar's middle: the central part of its width of this share."""


def scar_shape(x_m, depth_m, edge_share: float = EDGE_SHARE) -> str:
    """"U" or "W": the depth of the scar's middle, the median of the nodes' depths within the
    central :data:`MIDDLE_WINDOW_SHARE` of the width about the scar's centre (half way between
    its edges, :func:`scar_edges`: a single node there is at the mercy of a profile's noise),
    against :data:`MIDDLE_SHARE` of the largest. A gross-slip fretting scar is a U (deepest in
    the middle), a partial-slip one a W (the stick zone in the middle unworn; Vingsbo &
    Soderberg, Wear 126 (1988) 131)."""
    x, depth = np.asarray(x_m, dtype=float), np.asarray(depth_m, dtype=float)
    deepest, left, right, _, _ = scar_edges(x, depth, edge_share)
    centre, half_window = 0.5 * (left + right), 0.5 * MIDDLE_WINDOW_SHARE * (right - left)
    middle_nodes = np.abs(x - centre) <= half_window
    middle = (float(np.median(depth[middle_nodes])) if middle_nodes.any()
              else float(np.interp(centre, x, depth)))
    return "W" if middle < MIDDLE_SHARE * deepest else "U"
