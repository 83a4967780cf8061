"""Quality of the (moved) bushing mesh and the re-mesh decision (DOLFINx).

Per cell, from the Jacobian J = dx/dX of the cell's map at a 5 x 5 lattice of reference points
(corners, edge midpoints and centre, i.e. the 9 geometry nodes, and the quarter points between):

- **scaled Jacobian** min_q det J_q / max_q |det J_q|: 1 for an affine cell, <= 0 for an inverted
  or folded one. The sign of det J is taken relative to the cell's orientation when the meter was
  built (DOLFINx's local numbering can make det J negative in a valid cell). For a Q9 cell det J is
  a polynomial of degree 3 in each reference direction; the lattice samples it (not a bound).
- **angle sine** det J / (|J e_1| |J e_2|), the sine of the angle between the cell's mapped
  reference directions, min over the lattice: 1 for a rectangle, sin(alpha) for a parallelogram
  with angle alpha (Knupp, "Achieving finite element mesh quality via optimization of the
  Jacobian matrix norm and associated quantities", IJNME 48 (2000)). It sees shear, which the scaled
  Jacobian misses.
- **bore motion ratio** of each bore-row cell: the largest distance its bore nodes have moved since
  the meter was built, over the cell's radial height then (the distance between the midpoints of
  its bore edge and of the opposite edge).

Global extremes are reduced over MPI ranks (owned cells only), so every rank gets the same figures.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from mpi4py import MPI

from fewear.mesh.bore import QUAD_EDGE_VERTICES
from fewear.mesh.bushing import BORE_TAG

# The reference lattice: 5 points per direction on the unit square (DOLFINx's reference quad).
LATTICE_1D = np.linspace(0.0, 1.0, 5)
REFERENCE_LATTICE = np.array([[s, t] for t in LATTICE_1D for s in LATTICE_1D])
# DOLFINx's reference quadrilateral: the local vertices (a, b) of edge e, the edge opposite to e,
# and the Q9 geometry node of the midpoint of edge e (4 vertices first, then one node per edge).
EDGE_MIDPOINT_NODE_OFFSET = 4
OPPOSITE_EDGE = (3, 2, 1, 0)


@dataclass(frozen=True)
class MeshQuality:
    """Worst figures over the mesh (all ranks): see the module docstring for the definitions."""

    min_scaled_jacobian: float
    min_angle_sine: float
    max_bore_motion_ratio: float


@dataclass(frozen=True)
class RemeshLimits:
    """When to re-mesh instead of moving the mesh further.

    Defaults: a scaled Jacobian below 0.5 (det J varies by more than a factor 2 within a cell), an
    angle sine below 0.5 (a corner angle outside 30..150 deg), or bore nodes that moved by more
    than half the height of their bore-row cell since the last mesh was made. With the elastic ALE
    of :mod:`fewear.mesh.ale` a 0.5 mm two-lobe wear profile keeps the scaled Jacobian at 0.946 and
    the angle sine at 0.997 on the reference mesh, so the motion limit is the one that triggers
    (every ~0.09 mm of wear there): it keeps the mesh close to the graded O-grid it was built as,
    at the price of a re-mesh that costs about as much as an ALE move.
    """

    min_scaled_jacobian: float = 0.5
    min_angle_sine: float = 0.5
    max_bore_motion_ratio: float = 0.5

    def needs_remesh(self, quality: MeshQuality) -> bool:
        """True when any figure of ``quality`` passes its limit."""
        return (quality.min_scaled_jacobian < self.min_scaled_jacobian
                or quality.min_angle_sine < self.min_angle_sine
                or quality.max_bore_motion_ratio > self.max_bore_motion_ratio)


def bore_row(mesh, facet_tags) -> tuple[np.ndarray, np.ndarray]:
    """The bore facets on this rank (owned) as ``(cells, local_edges)``: each facet's cell and the
    facet's local edge number in it."""
    tdim = mesh.topology.dim
    mesh.topology.create_connectivity(tdim - 1, tdim)
    mesh.topology.create_connectivity(tdim, tdim - 1)
    f2c = mesh.topology.connectivity(tdim - 1, tdim)
    c2f = mesh.topology.connectivity(tdim, tdim - 1)
    facets = facet_tags.find(BORE_TAG)
    facets = facets[facets < mesh.topology.index_map(tdim - 1).size_local]
    cells = np.array([f2c.links(f)[0] for f in facets], dtype=np.int32)
    edges = np.array([list(c2f.links(c)).index(f) for c, f in zip(cells, facets)], dtype=np.int32)
    return cells, edges


def bore_row_nodes(mesh, facet_tags) -> tuple[np.ndarray, np.ndarray]:
    """Geometry nodes (two vertices and the midpoint, shape (n, 3)) of this rank's owned bore
    facets, and the radial height (m) of each facet's cell: the distance from the bore edge's
    midpoint to the opposite edge's midpoint."""
    cells, bore_edges = bore_row(mesh, facet_tags)
    dofmap = mesh.geometry.dofmap.array.reshape(-1, 9)[cells]
    rows = np.arange(cells.size)
    ends = np.take(QUAD_EDGE_VERTICES, bore_edges, axis=0).reshape(-1, 2)
    midpoint = dofmap[rows, EDGE_MIDPOINT_NODE_OFFSET + bore_edges]
    opposite = dofmap[rows, EDGE_MIDPOINT_NODE_OFFSET + np.take(OPPOSITE_EDGE, bore_edges)]
    nodes = np.column_stack([dofmap[rows, ends[:, 0]], dofmap[rows, ends[:, 1]], midpoint])
    x = mesh.geometry.x[:, :2]
    return nodes, np.linalg.norm(x[opposite] - x[midpoint], axis=1)


class QualityMeter:
    """Measures :class:`MeshQuality` of ``mesh`` as its geometry moves; build once per mesh.

    The mesh as it is at construction is the reference: cell orientations, bore-row heights and
    the bore nodes' positions from which the bore motion is measured. ``facet_tags`` must tag the
    bore facets ``BORE_TAG``.
    """

    def __init__(self, mesh, facet_tags):
        import ufl
        from dolfinx import fem

        self.mesh = mesh
        self.cells = np.arange(mesh.topology.index_map(mesh.topology.dim).size_local,
                               dtype=np.int32)
        self._jacobian = fem.Expression(ufl.Jacobian(mesh), REFERENCE_LATTICE)
        self.orientation = np.sign(_determinants(self._jacobians()).mean(axis=1))
        self.bore_nodes, self.row_height_m = bore_row_nodes(mesh, facet_tags)
        self.reference_xy = mesh.geometry.x[self.bore_nodes, :2].copy()

    def _jacobians(self) -> np.ndarray:
        """J at the reference lattice of every owned cell, shape (cells, points, 2, 2)."""
        values = self._jacobian.eval(self.cells)
        return values.reshape(self.cells.size, REFERENCE_LATTICE.shape[0], 2, 2)

    def measure(self) -> MeshQuality:
        """The worst scaled Jacobian, angle sine and bore motion ratio over all ranks, now."""
        jacobian = self._jacobians()
        det = _determinants(jacobian) * self.orientation[:, None]
        scaled = det.min(axis=1) / np.abs(det).max(axis=1)
        angle_sine = det / (_column_length(jacobian, 0) * _column_length(jacobian, 1))
        comm = self.mesh.comm
        return MeshQuality(
            min_scaled_jacobian=comm.allreduce(_extreme(scaled, np.min, np.inf), op=MPI.MIN),
            min_angle_sine=comm.allreduce(_extreme(angle_sine, np.min, np.inf), op=MPI.MIN),
            max_bore_motion_ratio=self.bore_motion_ratio(),
        )

    def bore_motion_ratio(self) -> float:
        """The worst bore motion ratio over all ranks, now: from the bore nodes alone."""
        motion = np.linalg.norm(self.mesh.geometry.x[self.bore_nodes, :2] - self.reference_xy,
                                axis=2)
        ratio = motion.max(axis=1) / self.row_height_m
        return self.mesh.comm.allreduce(_extreme(ratio, np.max, 0.0), op=MPI.MAX)


def _determinants(jacobian: np.ndarray) -> np.ndarray:
    """det J of 2x2 matrices (..., 2, 2) in closed form (``np.linalg.det`` factorises each by
    LAPACK: 9 ms per mesh of the default bushing against well under 1 ms)."""
    return jacobian[..., 0, 0] * jacobian[..., 1, 1] - jacobian[..., 0, 1] * jacobian[..., 1, 0]


def _column_length(jacobian: np.ndarray, column: int) -> np.ndarray:
    """|J e_column| of 2x2 matrices (..., 2, 2), as ``np.linalg.norm(jacobian, axis=-2)`` gives
    it to the bit (the root of the two squares' sum), without its generic reduction over a
    strided axis (5 ms per mesh of the default bushing against 0.1 ms)."""
    return np.sqrt(jacobian[..., 0, column] ** 2 + jacobian[..., 1, column] ** 2)


def _extreme(values: np.ndarray, reduce, empty: float) -> float:
    """``reduce(values)`` as a float, or ``empty`` when this rank holds no values."""
    return float(reduce(values)) if values.size else empty
