"""One ALE sequence and one re-mesh on a coarse bushing, run by tests/mesh/test_mpi.py as
``[mpirun -n 2] python -m tests.mesh.mpi_case OUT.npz`` from the repository root.

Rank 0 writes the node positions keyed by gmsh node number after three ALE moves (two lobes to
0.5 mm) and after a re-mesh on that profile, the quality figures, and how far the copies of a
node on different ranks (owned and ghost) disagree.
"""

import sys

import numpy as np
from mpi4py import MPI

from fewear.mesh.ale import BoreMotion
from fewear.mesh.bushing import bushing_mesh
from fewear.mesh.profile import periodic_linear
from fewear.mesh.quality import QualityMeter
from tests.mesh.cases import GEOMETRY, bore_node_angles, coarse_settings, two_lobes

N_THETA, MOVES = 48, 3


def gathered_nodes(msh):
    """(gmsh node numbers, positions (n, 2), largest disagreement between copies of a node)."""
    ids = np.concatenate(msh.comm.allgather(np.asarray(msh.geometry.input_global_indices)))
    xy = np.concatenate(msh.comm.allgather(msh.geometry.x[:, :2].copy()))
    unique_ids, first, inverse = np.unique(ids, return_index=True, return_inverse=True)
    mismatch = np.abs(xy - xy[first][inverse]).max()
    return unique_ids, xy[first], mismatch


def main(out_path):
    settings = coarse_settings(N_THETA)
    angles = bore_node_angles(N_THETA)
    msh, _, facet_tags = bushing_mesh(GEOMETRY, settings, MPI.COMM_WORLD)
    motion = BoreMotion(msh, facet_tags)
    for _ in range(MOVES):
        report = motion.move(periodic_linear(angles, two_lobes(angles) / MOVES))
    ale_ids, ale_xy, ale_mismatch = gathered_nodes(msh)
    worn = (angles, GEOMETRY.inner_radius_m + two_lobes(angles))
    remeshed, _, remeshed_tags = bushing_mesh(GEOMETRY, settings, MPI.COMM_WORLD,
                                              bore_profile=worn)
    remesh_quality = QualityMeter(remeshed, remeshed_tags).measure()
    remesh_ids, remesh_xy, remesh_mismatch = gathered_nodes(remeshed)
    if MPI.COMM_WORLD.rank == 0:
        np.savez(out_path, ranks=MPI.COMM_WORLD.size,
                 ale_ids=ale_ids, ale_xy=ale_xy, ale_mismatch=ale_mismatch,
                 ale_quality=list(vars(report.quality).values()),
                 max_displacement_m=report.max_displacement_m,
                 remesh_ids=remesh_ids, remesh_xy=remesh_xy, remesh_mismatch=remesh_mismatch,
                 remesh_quality=list(vars(remesh_quality).values()))


if __name__ == "__main__":
    main(sys.argv[1])
