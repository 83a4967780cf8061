"""Mesh quality figures on one 9-node quadrilateral with known answers, and the re-mesh rule."""

import math

import numpy as np
import pytest

from fewear.mesh.quality import MeshQuality, RemeshLimits

# DOLFINx's Q9 node order on the reference square: vertices (0,0) (1,0) (0,1) (1,1), the edge
# midpoints of edges (v0 v1) (v0 v2) (v1 v3) (v2 v3), the centre.
Q9_REFERENCE_NODES = np.array([[0, 0], [1, 0], [0, 1], [1, 1],
                               [0.5, 0], [0, 0.5], [1, 0.5], [0.5, 1], [0.5, 0.5]], dtype=float)


def unit_cell_meter():
    """A one-cell Q9 mesh of the unit square (serial), its bottom edge tagged as the bore."""
    import ufl
    from dolfinx import mesh as dmesh
    from mpi4py import MPI

    from fewear.mesh.bushing import BORE_TAG
    from fewear.mesh.quality import QualityMeter

    domain = ufl.Mesh(ufl.VectorElement("Q", ufl.quadrilateral, 2))
    cells = np.arange(9, dtype=np.int64).reshape(1, 9)
    msh = dmesh.create_mesh(MPI.COMM_SELF, cells, Q9_REFERENCE_NODES.copy(), domain)
    bottom = dmesh.locate_entities_boundary(msh, 1, lambda x: np.isclose(x[1], 0.0))
    facet_tags = dmesh.meshtags(msh, 1, bottom, np.full(bottom.size, BORE_TAG, dtype=np.int32))
    return msh, QualityMeter(msh, facet_tags)


def move_nodes(msh, mapping):
    """Replace every geometry node X by mapping(X) (X in reference coordinates here)."""
    x = msh.geometry.x
    x[:, :2] = mapping(x[:, :2].copy())


def test_square_is_perfect_and_shear_gives_the_angle_sine():
    msh, meter = unit_cell_meter()
    quality = meter.measure()
    assert quality.min_scaled_jacobian == pytest.approx(1.0, rel=1e-14)
    assert quality.min_angle_sine == pytest.approx(1.0, rel=1e-14)
    assert quality.max_bore_motion_ratio == 0.0
    shear = 0.75
    move_nodes(msh, lambda x: np.column_stack([x[:, 0] + shear * x[:, 1], x[:, 1]]))
    quality = meter.measure()
    assert quality.min_scaled_jacobian == pytest.approx(1.0, rel=1e-14)   # still affine
    assert quality.min_angle_sine == pytest.approx(1.0 / math.hypot(1.0, shear), rel=1e-14)


def test_trapezoid_scaled_jacobian_and_inversion():
    """x = X + t X Y: det J = 1 + t Y, so min/max = 1/(1 + t); mirrored, every det J flips: -1."""
    msh, meter = unit_cell_meter()
    t = 0.6
    move_nodes(msh, lambda x: np.column_stack([x[:, 0] * (1.0 + t * x[:, 1]), x[:, 1]]))
    assert meter.measure().min_scaled_jacobian == pytest.approx(1.0 / (1.0 + t), rel=1e-14)
    move_nodes(msh, lambda x: np.column_stack([-x[:, 0], x[:, 1]]))
    assert meter.measure().min_scaled_jacobian == pytest.approx(-1.0, rel=1e-14)


def test_bore_motion_is_measured_against_the_row_height():
    msh, meter = unit_cell_meter()
    lift = 0.3
    move_nodes(msh, lambda x: np.column_stack([x[:, 0], x[:, 1] + lift * (1.0 - x[:, 1])]))
    assert meter.measure().max_bore_motion_ratio == pytest.approx(lift, rel=1e-14)


@pytest.mark.parametrize("quality, expected", [
    (MeshQuality(0.9, 0.9, 0.4), False),
    (MeshQuality(0.49, 0.9, 0.4), True),
    (MeshQuality(0.9, 0.49, 0.4), True),
    (MeshQuality(0.9, 0.9, 0.51), True),
])
def test_remesh_when_any_figure_passes_its_limit(quality, expected):
    assert RemeshLimits().needs_remesh(quality) is expected
