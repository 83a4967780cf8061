"""The measured wear scars shipped in fewear/data (issue 22's validation cases) read back as the
published tests describe them: McColl, Ding & Leen (2004) report a fretting scar about 2.9 um deep
and 0.65 mm wide after 18,000 cycles at 185 N; Cruzado et al. (2010) about 45 um deep and 2.7 mm
wide after 3,600 m at 65 N, in three repeated tests. A check of the transcription (columns,
units, sign) against the papers' own figures, independent of any fewear computation."""

import numpy as np
import pytest

from fewear.data import BLOCK_ON_RING_CRUZADO2010_CSV, FRETTING_MCCOLL2004_CSV

EDGE_SHARE = 0.05  # the scar's edges: where the depth first exceeds this share of its maximum


def read(path):
    """The table below the file's comment header (source, licence) as named columns."""
    rows = [line for line in path.read_text().splitlines() if not line.startswith("#")]
    return np.genfromtxt(rows, delimiter=",", names=True)


def depth_and_width(x_mm, height_um):
    """Maximum depth (um) and width (mm) of a scar given as surface heights (negative: worn)."""
    depth = -height_um
    worn = np.flatnonzero(depth > EDGE_SHARE * depth.max())
    return depth.max(), x_mm[worn[-1]] - x_mm[worn[0]]


def test_the_fretting_scar_has_the_published_depth_and_width():
    table = read(FRETTING_MCCOLL2004_CSV)
    depth_um, width_mm = depth_and_width(table["x_mm"], table["y_um"])
    assert depth_um == pytest.approx(2.9, rel=0.05)
    assert width_mm == pytest.approx(0.65, rel=0.1)


@pytest.mark.parametrize("test", ["test1_um", "test2_um", "test3_um"])
def test_each_block_on_ring_scar_has_the_published_depth_and_width(test):
    table = read(BLOCK_ON_RING_CRUZADO2010_CSV)
    depth_um, width_mm = depth_and_width(table["x_mm"], table[test])
    assert depth_um == pytest.approx(45.0, rel=0.1)
    assert width_mm == pytest.approx(2.7, rel=0.1)
