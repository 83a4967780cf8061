"""`fewear contact` and the Hertz demo under `mpirun -n 2` give the serial results to a relative
1e-8.

Both runs of each are subprocesses of the same command, so the only difference is the partition of
the mesh (assembly order, distributed LU); what remains is the Newton tolerance.

The default suite runs the demo on its two coarse meshes (`FEWEAR_DEMO_COARSE=1`: the same code,
seconds); the slow variant (`make slow`) compares the demo's full refinement study (three meshes
up to 1020 bore elements, a minute or two under MPI).
"""

import csv
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tests.mpi import MPI_ENV, mpirun_or_skip

FORCE_N = ("-450.0", "700.0")
DEMO = Path(__file__).resolve().parents[2] / "demos" / "hertz_contact.py"


def contact_command(out):
    return [sys.executable, "-m", "fewear.cli", "contact", "--force", *FORCE_N, "--out", str(out)]


def run(command, **env):
    process = subprocess.run(command, capture_output=True, text=True, timeout=300,
                             env={**os.environ, **MPI_ENV, **env})
    assert process.returncode == 0, process.stderr
    return process


def read_bore(out):
    with open(out / "contact.csv", newline="") as handle:
        rows = list(csv.DictReader(handle))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


@pytest.mark.mpi
def test_two_ranks_equal_serial(tmp_path):
    mpirun = mpirun_or_skip()
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


def read_table(path):
    with open(path, newline="") as handle:
        rows = list(csv.DictReader(handle))
    return {key: np.array([float(row[key]) for row in rows]) for key in rows[0]}


@pytest.mark.slow  # the demo on two ranks; test_two_ranks_equal_serial keeps the contact's MPI path
@pytest.mark.mpi
@pytest.mark.parametrize("coarse", ["1", "0"], ids=["coarse", "full"])
def test_hertz_demo_two_ranks_equal_serial(tmp_path, coarse):
    mpirun = mpirun_or_skip()
    serial = run([sys.executable, str(DEMO)], FEWEAR_DEMO_OUT=str(tmp_path / "serial"),
                 FEWEAR_DEMO_COARSE=coarse)
    parallel = run([mpirun, "-n", "2", sys.executable, str(DEMO)],
                   FEWEAR_DEMO_OUT=str(tmp_path / "mpi"), FEWEAR_DEMO_COARSE=coarse)
    # only rank 0 prints: the table appears once
    assert parallel.stdout.count("fitted rates") == 1
    tables = [read_table(tmp_path / name / "convergence.csv") for name in ("serial", "mpi")]
    assert np.array_equal(tables[0]["bore_element_size_m"], tables[1]["bore_element_size_m"])
    pins = [np.column_stack([table["pin_centre_x_m"], table["pin_centre_y_m"]])
            for table in tables]
    differences = {
        name: float(np.max(np.abs(tables[1][name] / tables[0][name] - 1.0)))
        for name in ("peak_pressure_Pa", "moment_half_width_m")
    }
    differences["pin_centre_m"] = float(np.max(np.linalg.norm(pins[1] - pins[0], axis=1)
                                               / np.linalg.norm(pins[0], axis=1)))
    print(f"\nHertz demo, serial vs mpirun -n 2 (largest relative difference over the meshes): "
          f"{differences}; serial output:\n{serial.stdout}")
    assert all(difference < 1e-8 for difference in differences.values())
