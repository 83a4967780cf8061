"""fewear runs OpenBLAS on one thread (fewear/__init__.py): its work is spread over processes and
ranks, and a block's dynamics call LAPACK in a thread beside the mesh stage."""

import os
import subprocess
import sys

import pytest

PROBE = """
import ctypes
import fewear, numpy
blas = ctypes.CDLL("libblas.so.3")
print(blas.openblas_get_num_threads() if hasattr(blas, "openblas_get_num_threads") else -1)
"""


def test_importing_fewear_first_sets_one_blas_thread():
    env = {key: value for key, value in os.environ.items() if key != "OPENBLAS_NUM_THREADS"}
    threads = int(subprocess.run([sys.executable, "-c", PROBE], env=env, check=True,
                                 capture_output=True, text=True).stdout)
    if threads == -1:
        pytest.skip("libblas.so.3 is not OpenBLAS")
    assert threads == 1
