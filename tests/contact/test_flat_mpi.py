"""The cylinder on the flat under `mpirun -n 2` gives the serial pressures
(tests/contact/flat_mpi_case.py) and the serial shear of its frictional steps
(tests/contact/flat_friction_mpi_case.py).

The only difference between the runs is the partition (assembly order, distributed LU). The
nodal pressures k <-g>_+ are computed from gaps |X + u - c| - R known to about eps R, i.e. to
k eps R ~ 20 Pa (1e-7 of p0 here): the runs may differ by a few times that, and are allowed
1e-6 of the peak (measured: equal to the bit, the cylinder's centres 5e-20 m apart); their
resultant, the integral of those pressures, is allowed as much, 1e-6 (measured: mostly equal,
once 1.2e-7 apart, -64.99999 against -65 N, a run that passed alone). The shear
of the frictional steps (a tangential penalty as stiff, and stick-slip switches) is allowed
1e-6 of its largest value (measured: 2e-8 to 4e-8).
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from tests.mpi import MPI_ENV, mpirun_or_skip

REPOSITORY = Path(__file__).resolve().parents[2]


def run_case(out, *launcher, case="tests.contact.flat_mpi_case"):
    command = [*launcher, sys.executable, "-m", case, str(out)]
    process = subprocess.run(command, capture_output=True, text=True, timeout=300,
                             cwd=REPOSITORY, env={**os.environ, **MPI_ENV})
    assert process.returncode == 0, process.stderr
    return np.load(out)


@pytest.mark.slow  # 14 s; the wear loop's and the bushing contact's two-rank tests stay by default
@pytest.mark.mpi
def test_two_ranks_press_the_flat_as_serial(tmp_path):
    mpirun = mpirun_or_skip()
    serial = run_case(tmp_path / "serial.npz")
    parallel = run_case(tmp_path / "mpi.npz", mpirun, "-n", "2")
    assert (int(serial["ranks"]), int(parallel["ranks"])) == (1, 2)
    np.testing.assert_array_equal(serial["x_m"], parallel["x_m"])
    peak = serial["pressure_Pa"].max()
    difference = np.abs(parallel["pressure_Pa"] - serial["pressure_Pa"]).max()
    rounding = float(serial["penalty_Pa_per_m"]) * np.finfo(float).eps * 0.020
    pin = np.abs(parallel["pin_centre_m"] - serial["pin_centre_m"]).max()
    print(f"\nserial vs mpirun -n 2: pressures differ by {difference:.2e} Pa "
          f"({difference / peak:.1e} of the peak; k eps R = {rounding:.1f} Pa), the cylinder's "
          f"centre by {pin:.1e} m")
    assert difference < 1e-6 * peak
    assert np.allclose(parallel["resultant_force_N"], serial["resultant_force_N"], rtol=1e-6,
                       atol=1e-9)


@pytest.mark.slow  # 7 s; the pressing case above keeps the flat's MPI path in the default suite
@pytest.mark.mpi
def test_two_ranks_shear_the_flat_as_serial(tmp_path):
    mpirun = mpirun_or_skip()
    case = "tests.contact.flat_friction_mpi_case"
    serial = run_case(tmp_path / "serial.npz", case=case)
    parallel = run_case(tmp_path / "mpi.npz", mpirun, "-n", "2", case=case)
    assert (int(serial["ranks"]), int(parallel["ranks"])) == (1, 2)
    for name in ("uncoupled", "coupled", "shifted"):
        shear, other = serial[f"{name}_shear_Pa"], parallel[f"{name}_shear_Pa"]
        difference = np.abs(other - shear).max() / np.abs(shear).max()
        print(f"\n{name}: shear differs by {difference:.1e} of its largest value")
        assert difference < 1e-6
        assert float(parallel[f"{name}_Q_N"]) == pytest.approx(float(serial[f"{name}_Q_N"]),
                                                               rel=1e-7)
