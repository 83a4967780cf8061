"""ALE motion and re-mesh under `mpirun -n 2` give the serial mesh (tests/mesh/mpi_case.py).

The only difference between the runs is the partition (assembly order, distributed LU), so node
positions agree to rounding of the extension solve; copies of a node on the two ranks (owned and
ghost) agree exactly.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tests.contact.test_mpi import MPI_ENV, mpirun_or_skip

REPOSITORY = Path(__file__).resolve().parents[2]


def run_case(out, *launcher):
    command = [*launcher, sys.executable, "-m", "tests.mesh.mpi_case", str(out)]
    process = subprocess.run(command, capture_output=True, text=True, timeout=300,
                             cwd=REPOSITORY, env={**os.environ, **MPI_ENV})
    assert process.returncode == 0, process.stderr
    return np.load(out)


@pytest.mark.slow  # the wear loop's two-rank test moves and re-meshes on two ranks by default
@pytest.mark.mpi
def test_two_ranks_move_and_remesh_as_serial(tmp_path):
    mpirun = mpirun_or_skip()
    serial = run_case(tmp_path / "serial.npz")
    parallel = run_case(tmp_path / "mpi.npz", mpirun, "-n", "2")
    assert (int(serial["ranks"]), int(parallel["ranks"])) == (1, 2)
    for stage in ("ale", "remesh"):
        assert np.array_equal(serial[f"{stage}_ids"], parallel[f"{stage}_ids"])
        difference = np.abs(serial[f"{stage}_xy"] - parallel[f"{stage}_xy"]).max()
        print(f"\n{stage}: serial vs mpirun -n 2 node positions differ by {difference:.1e} m")
        assert difference < 1e-15
        assert float(parallel[f"{stage}_mismatch"]) == 0.0
        np.testing.assert_allclose(parallel[f"{stage}_quality"], serial[f"{stage}_quality"],
                                   rtol=1e-12)
    assert float(parallel["max_displacement_m"]) == pytest.approx(
        float(serial["max_displacement_m"]), rel=1e-12)
