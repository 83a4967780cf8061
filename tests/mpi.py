"""Commands under ``mpirun -n 2`` from the tests (skipped where mpirun is missing): Open MPI as
root, more ranks than cores allowed, figures drawn off screen."""

import os
import shutil
import subprocess
import sys

import pytest

MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1", "MPLBACKEND": "Agg"}


def mpirun_or_skip() -> str:
    """The path of mpirun; the test is skipped without it."""
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        pytest.skip("mpirun not found on PATH (Open MPI is installed with python3-dolfinx)")
    return mpirun


def mpirun_fewear(*args: str, timeout_s: float = 600) -> subprocess.CompletedProcess:
    """``mpirun -n 2 python -m fewear.cli ARGS``, its output captured."""
    return subprocess.run([mpirun_or_skip(), "-n", "2", sys.executable, "-m", "fewear.cli", *args],
                          capture_output=True, text=True, timeout=timeout_s,
                          env={**os.environ, **MPI_ENV})
