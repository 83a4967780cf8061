"""The scar measures of fewear.wear.scar on the two measured profiles shipped in fewear/data:
the scar contiguous about its deepest point (a dip beside it left out), its width and worn area
computed here by a plain walk over the points, and the U/W rule's middle at the scar's centre."""

import numpy as np
import pytest

from fewear.data import BLOCK_ON_RING_CRUZADO2010_CSV, FRETTING_MCCOLL2004_CSV
from fewear.diagnose.scar.measured import read_measured_scar
from fewear.wear.scar import EDGE_SHARE, scar_depth_and_width_m, scar_shape, scar_worn_area_m2


def profiles():
    for path in (FRETTING_MCCOLL2004_CSV, BLOCK_ON_RING_CRUZADO2010_CSV):
        measured = read_measured_scar(path)
        for name, depth in zip(measured.names, measured.depth_m):
            yield pytest.param(measured.x_m, depth, id=f"{path.stem}-{name}")


def walked_scar(x, depth):
    """Left and right edges and area of the scar by walking out from the deepest point while the
    depth exceeds 5 % of it, the edges and the area's end pieces interpolated linearly."""
    deepest = 0
    for i in range(len(x)):
        if depth[i] > depth[deepest]:
            deepest = i
    level = EDGE_SHARE * depth[deepest]
    ends, area = [], 0.0
    for step in (-1, 1):
        i = deepest
        while 0 <= i + step < len(x) and depth[i + step] > level:
            area += 0.5 * (depth[i] + depth[i + step]) * abs(x[i + step] - x[i])
            i += step
        end = x[i]
        if 0 <= i + step < len(x):  # the crossing of the level, and the piece up to it
            share = (depth[i] - level) / (depth[i] - depth[i + step])
            end = x[i] + share * (x[i + step] - x[i])
            area += 0.5 * (depth[i] + level) * abs(end - x[i])
        ends.append(end)
    return ends[0], ends[1], area


@pytest.mark.parametrize("x, depth", profiles())
def test_width_and_area_are_those_of_the_contiguous_scar(x, depth):
    left, right, area = walked_scar(x, depth)
    width = right - left
    assert scar_depth_and_width_m(x, depth) == pytest.approx((depth.max(), width), rel=1e-12)
    assert scar_worn_area_m2(x, depth) == pytest.approx(area, rel=1e-12)


def test_the_dip_beside_the_fretting_scar_is_left_out():
    """The fretting profile dips 0.5 um deep at 0.36-0.40 mm, beyond a point at the surface
    (0.32 mm): taking every point deeper than 5 % of the depth would widen the scar to it."""
    measured = read_measured_scar(FRETTING_MCCOLL2004_CSV)
    x, depth = measured.x_m, measured.depth_m[0]
    every = np.flatnonzero(depth > EDGE_SHARE * depth.max())
    width, area = scar_depth_and_width_m(x, depth)[1], scar_worn_area_m2(x, depth)
    assert x[every[-1]] > 0.4e-3 and width < 0.57e-3 < x[every[-1]] - x[every[0]]
    beside = np.trapz(depth[every], x[every])
    assert area < beside - 0.02e-9


@pytest.mark.parametrize("x, depth", profiles())
def test_the_measured_scars_are_u_shaped_by_the_median_of_their_middle(x, depth):
    """Each measured scar is a gross-slip U: the median depth of the central fifth of the
    scar, computed here about its centre, is at least 90 % of the largest."""
    left, right, _ = walked_scar(x, depth)
    centre, width = 0.5 * (left + right), right - left
    middle = [d for xi, d in zip(x, depth) if abs(xi - centre) <= 0.1 * width]
    assert np.median(middle) >= 0.9 * depth.max()
    assert scar_shape(x, depth) == "U"
