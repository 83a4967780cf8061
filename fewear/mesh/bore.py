"""The bore's Q8 nodes: which geometry nodes lie on the bore, gathered over the ranks, and their
contact weights.

A bore facet of the 9-node geometry has three nodes, two vertices and the edge midpoint; these are
the Q8 (serendipity) nodes on the bore and the points of the 3-point Gauss-Lobatto rule with which
the contact integral is computed (:mod:`fewear.contact.solver`). :class:`BoreNodes` finds them on
each rank and gathers their union, sorted by angle, on every rank; :func:`bore_node_weights` gives
their Gauss-Lobatto weights.

The same serves any contact surface tagged ``CONTACT_TAG``: on the flat below the origin
(:mod:`fewear.mesh.flat`) every node's angle lies in (pi, 2 pi), and the angle order is the order
in x.
"""

from __future__ import annotations

import math

import numpy as np
from mpi4py import MPI

from fewear.mesh.tags import CONTACT_TAG

# DOLFINx reference quadrilateral: local edge e joins these vertices; geometry node 4 + e is the
# edge's midpoint node of the 9-node geometry.
QUAD_EDGE_VERTICES = ((0, 1), (0, 2), (1, 3), (2, 3))


class BoreNodes:
    """The bore's facets and Q8 nodes on this rank, and their gathered, angle-sorted union.

    Attributes (local): ``facets``, ``cells`` (a cell of each facet), ``facet_nodes`` (n_f, 3)
    geometry nodes (vertex, vertex, midpoint). Gathered on every rank: ``global_ids`` (the gmsh node
    numbers), ``points`` (n, 2) undeformed coordinates, ``angles`` in [0, 2 pi).
    ``local_index`` maps the local node list into the gathered order.
    """

    def __init__(self, msh, facet_tags, comm):
        tdim = msh.topology.dim
        msh.topology.create_connectivity(tdim - 1, tdim)
        msh.topology.create_connectivity(tdim, tdim - 1)
        n_owned = msh.topology.index_map(tdim - 1).size_local
        facets = facet_tags.find(CONTACT_TAG)
        self.facets = facets[facets < n_owned].astype(np.int32)
        f2c = msh.topology.connectivity(tdim - 1, tdim)
        c2f = msh.topology.connectivity(tdim, tdim - 1)
        self.cells = np.array([f2c.links(f)[0] for f in self.facets], dtype=np.int32)
        nodes = []
        for facet, cell in zip(self.facets, self.cells):
            local = list(c2f.links(cell)).index(facet)
            dofs = msh.geometry.dofmap.links(cell)
            a, b = QUAD_EDGE_VERTICES[local]
            nodes.append((dofs[a], dofs[b], dofs[4 + local]))
        self.facet_nodes = np.array(nodes, dtype=np.int32).reshape(-1, 3)
        self.msh = msh
        self.comm = comm
        self.local_nodes, first = np.unique(self.facet_nodes, return_index=True)
        self.local_node_cells = self.cells[first // 3]
        self._local_ids = np.asarray(msh.geometry.input_global_indices,
                                     dtype=np.int64)[self.local_nodes]
        self.update_geometry()

    def update_geometry(self) -> None:
        """Re-read node coordinates (after the mesh moved) and rebuild the gathered node list."""
        ids, xy = self._local_ids, self.msh.geometry.x[self.local_nodes, :2]
        all_ids = np.concatenate(self.comm.allgather(ids))
        all_xy = np.concatenate(self.comm.allgather(xy)).reshape(-1, 2)
        unique_ids, first = np.unique(all_ids, return_index=True)
        points = all_xy[first]
        angles = np.mod(np.arctan2(points[:, 1], points[:, 0]), 2.0 * math.pi)
        order = np.lexsort((unique_ids, angles))
        self.global_ids = unique_ids[order]
        self.points = points[order]
        self.angles = angles[order]
        position = np.empty_like(order)  # of each unique id in the angle order
        position[order] = np.arange(order.size)
        self.local_index = position[np.searchsorted(unique_ids, ids)]

    def gather(self, local_values: np.ndarray) -> np.ndarray:
        """Values at the local nodes (n_local, ...) -> the same on every rank in gathered order."""
        shape = (self.global_ids.size,) + local_values.shape[1:]
        out = np.zeros(shape)
        count = np.zeros(self.global_ids.size)
        out[self.local_index] = local_values
        count[self.local_index] = 1.0
        out = self.comm.allreduce(out, op=MPI.SUM)
        count = self.comm.allreduce(count, op=MPI.SUM)
        return out / count.reshape((-1,) + (1,) * (out.ndim - 1))


def bore_node_weights(msh, bore) -> np.ndarray:
    """Gauss-Lobatto weights of the bore nodes (m), gathered order: per facet with nodes
    (vertex, vertex, midpoint) and the quadratic map x(s), s in [0, 1], the weights
    (1/6 |x'(0)|, 1/6 |x'(1)|, 2/3 |x'(1/2)|) -- what FFCx integrates with for the GLL rule."""
    x = msh.geometry.x[:, :2]
    v0, v1, mid = (x[bore.facet_nodes[:, k]] for k in range(3))
    d0 = np.linalg.norm(-3.0 * v0 - v1 + 4.0 * mid, axis=1)
    d1 = np.linalg.norm(v0 + 3.0 * v1 - 4.0 * mid, axis=1)
    dm = np.linalg.norm(v1 - v0, axis=1)
    weights = np.zeros(bore.local_nodes.size)
    for column, values in ((0, d0 / 6.0), (1, d1 / 6.0), (2, 2.0 * dm / 3.0)):
        # added facet after facet, as a loop would (np.add.at is unbuffered)
        np.add.at(weights, np.searchsorted(bore.local_nodes, bore.facet_nodes[:, column]),
                  values)
    total = np.zeros(bore.global_ids.size)
    total[bore.local_index] = weights
    return bore.comm.allreduce(total, op=MPI.SUM)
