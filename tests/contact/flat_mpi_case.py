"""One cylinder-on-flat solve (tests/contact/test_flat_hertz.py's case at h = a/8), run by
tests/contact/test_flat_mpi.py as ``[mpirun -n 2] python -m tests.contact.flat_mpi_case OUT.npz``
from the repository root. Rank 0 writes the top nodes' x, the nodal pressures and gaps, the
cylinder's centre, the resultant and the number of ranks."""

import sys

import numpy as np
from mpi4py import MPI

from fewear.contact.flat import FlatContactSolver
from tests.contact.test_flat_hertz import FORCE_N, flat_problem


def main(out_path):
    solver = FlatContactSolver(flat_problem(8), MPI.COMM_WORLD)
    result = solver.solve(FORCE_N)
    if MPI.COMM_WORLD.rank == 0:
        np.savez(out_path, ranks=MPI.COMM_WORLD.size, x_m=result.x_m,
                 pressure_Pa=result.pressure_Pa, gap_m=result.gap_m,
                 pin_centre_m=result.pin_centre_m, resultant_force_N=result.resultant_force_N,
                 penalty_Pa_per_m=solver.problem.penalty_stiffness_Pa_per_m())


if __name__ == "__main__":
    main(sys.argv[1])
