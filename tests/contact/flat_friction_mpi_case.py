"""Frictional steps on the flat (tests/contact/test_flat_mindlin.py's case at h = a/8), run by
tests/contact/test_flat_mpi.py as
``[mpirun -n 2] python -m tests.contact.flat_friction_mpi_case OUT.npz`` from the repository
root: the uncoupled and the coupled step to Q = mu P/2, each after a plain solve of P, then a
3 um shift (gross slip). Rank 0 writes each step's nodal shear and Q, and the number of ranks."""

import sys

import numpy as np
from mpi4py import MPI

from tests.contact.test_flat_mindlin import FORCE_N, FRICTION, flat_solver


def main(out_path):
    solver = flat_solver(8)
    half = 0.5 * FRICTION * FORCE_N
    solver.solve(FORCE_N)
    uncoupled = solver.solve_tangential_force(half, FORCE_N, uncoupled=True)
    solver.solve(FORCE_N)
    coupled = solver.solve_tangential_force(half, FORCE_N)
    shifted = solver.solve_tangential_shift(3e-6, FORCE_N)
    if MPI.COMM_WORLD.rank == 0:
        steps = {"uncoupled": uncoupled, "coupled": coupled, "shifted": shifted}
        np.savez(out_path, ranks=MPI.COMM_WORLD.size,
                 **{f"{name}_shear_Pa": step.shear_Pa for name, step in steps.items()},
                 **{f"{name}_Q_N": step.tangential_force_N for name, step in steps.items()})


if __name__ == "__main__":
    main(sys.argv[1])
