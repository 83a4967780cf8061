"""The bushing mesh's node coordinates as one array keyed by the gmsh node numbers.

DOLFINx distributes the nodes over the ranks (with ghosts) and renumbers them; the gmsh numbers
(``mesh.geometry.input_global_indices``) are the same on every rank and across runs of the same
mesh. :func:`gather_nodes` collects (number, x, y) of every node on every rank, sorted by number,
so a checkpoint can store the moved mesh and :func:`scatter_nodes` can put it back exactly, and a
writer on rank 0 can draw the whole mesh.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class MeshSnapshot:
    """A (moved) mesh: gmsh node numbers (n,), coordinates (n, 2) in m, and its cells as node
    numbers in VTK order (:func:`gather_cells`)."""

    node_ids: np.ndarray
    xy_m: np.ndarray
    cells: np.ndarray


def take_snapshot(msh, comm) -> MeshSnapshot:
    """The :class:`MeshSnapshot` of ``msh`` now, the same on every rank."""
    return MeshSnapshot(*gather_nodes(msh, comm), gather_cells(msh, comm))


def gather_nodes(msh, comm) -> tuple[np.ndarray, np.ndarray]:
    """(gmsh node numbers (n,), coordinates (n, 2) in m), sorted by number, on every rank."""
    ids = np.asarray(msh.geometry.input_global_indices, dtype=np.int64)
    xy = msh.geometry.x[:, :2]
    all_ids = np.concatenate(comm.allgather(ids))
    all_xy = np.concatenate(comm.allgather(xy)).reshape(-1, 2)
    unique_ids, first = np.unique(all_ids, return_index=True)
    return unique_ids, all_xy[first]


def gather_cells(msh, comm) -> np.ndarray:
    """The owned cells of every rank as gmsh node numbers (n_cells, nodes per cell) in VTK's node
    order (for XDMF/ParaView: a Q9 cell as VTK_BIQUADRATIC_QUAD, corners counter-clockwise, then
    edge midpoints, then the centre), on every rank."""
    from dolfinx.cpp.io import perm_vtk

    ids = np.asarray(msh.geometry.input_global_indices, dtype=np.int64)
    n_owned = msh.topology.index_map(msh.topology.dim).size_local
    dofmap = msh.geometry.dofmap
    to_vtk = np.argsort(perm_vtk(msh.topology.cell_type, dofmap.links(0).size))
    cells = np.array([ids[dofmap.links(c)][to_vtk] for c in range(n_owned)], dtype=np.int64)
    return np.concatenate(comm.allgather(cells))


def scatter_nodes(msh, node_ids: np.ndarray, xy: np.ndarray) -> None:
    """Set this rank's nodes (ghosts included) to the coordinates ``xy`` given for the sorted gmsh
    node numbers ``node_ids`` (as :func:`gather_nodes` returns them)."""
    ids = np.asarray(msh.geometry.input_global_indices, dtype=np.int64)
    position = np.searchsorted(node_ids, ids)
    if np.any(position >= node_ids.size) or np.any(node_ids[np.minimum(
            position, node_ids.size - 1)] != ids):
        raise ValueError("mesh snapshot: the stored nodes are not the nodes of this mesh")
    msh.geometry.x[:, :2] = xy[position]
