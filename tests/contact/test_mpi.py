"""`fewear contact` under `mpirun -n 2` gives the serial result to a relative 1e-8.

Both runs are subprocesses of the same command on the default config, so the only difference is
the partition of the mesh (assembly order, distributed LU).
"""

import csv
import json
import os
import shutil
import subprocess
import sys

import numpy as np
import pytest

FORCE_N = ("-450.0", "700.0")
MPI_ENV = {"OMPI_ALLOW_RUN_AS_ROOT": "1", "OMPI_ALLOW_RUN_AS_ROOT_CONFIRM": "1",
           "OMPI_MCA_rmaps_base_oversubscribe": "1", "MPLBACKEND": "Agg"}


def contact_command(out):
    return [sys.executable, "-m", "fewear.cli", "contact", "--force", *FORCE_N, "--out", str(out)]


def run(command):
    process = subprocess.run(command, capture_output=True, text=True, timeout=300,
                             env={**os.environ, **MPI_ENV})
    assert process.returncode == 0, process.stderr
    return process


def read_bore(out):
    with open(out / "contact.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


@pytest.mark.mpi
def test_two_ranks_equal_serial(tmp_path):
    mpirun = shutil.which("mpirun")
    if mpirun is None:
        pytest.skip("mpirun not found on PATH (Open MPI is installed with python3-dolfinx)")
    run(contact_command(tmp_path / "serial"))
    run([mpirun, "-n", "2", *contact_command(tmp_path / "mpi")])

    serial, parallel = read_bore(tmp_path / "serial"), read_bore(tmp_path / "mpi")
    assert np.array_equal(serial["angle_deg"], parallel["angle_deg"])
    peak = np.abs(serial["pressure_Pa"]).max()
    assert peak > 0.0
    pressure_difference = np.abs(parallel["pressure_Pa"] - serial["pressure_Pa"]).max() / peak
    gap_difference = (np.abs(parallel["gap_m"] - serial["gap_m"]).max()
                      / np.abs(serial["gap_m"]).max())

    summaries = [json.loads((tmp_path / name / "summary.json").read_text())
                 for name in ("serial", "mpi")]
    assert [summary["mpi_ranks"] for summary in summaries] == [1, 2]
    pins = [np.array(summary["pin_centre_m"]) for summary in summaries]
    pin_difference = np.linalg.norm(pins[1] - pins[0]) / np.linalg.norm(pins[0])
    print(f"\nserial vs mpirun -n 2: pressure {pressure_difference:.2e}, gap {gap_difference:.2e},"
          f" pin centre {pin_difference:.2e} (relative)")
    assert pressure_difference < 1e-8
    assert gap_difference < 1e-8
    assert pin_difference < 1e-8
    assert (tmp_path / "mpi" / "bushing.h5").exists()
