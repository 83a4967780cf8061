"""fewear: finite-element wear workbench for revolute clearance joints.

Stages (one subpackage each, data passed between them as frozen dataclasses in SI units):

- :mod:`fewear.mbd`        planar multibody dynamics (NumPy): rigid and ANCF bodies, clearance joint
- :mod:`fewear.contact`    bushing contact model (DOLFINx + PETSc), pressures and slips on the bore
- :mod:`fewear.wear`       Archard wear law and the wear coefficient k(p, v)
- :mod:`fewear.mesh`       bushing meshes (gmsh), ALE motion and re-meshing
- :mod:`fewear.loop`       the wear loop joining them (``fewear run``), and the scars on a flat
- :mod:`fewear.diagnose`   measured data, diagnosis of what the model gets wrong
- :mod:`fewear.io`         configuration, outputs
- :mod:`fewear.plot`       figures (matplotlib; PyVista imported lazily)
- :mod:`fewear.commands`   the command line's subcommands (entry point :mod:`fewear.cli`)

A module imports only from its own layer or the layers below: errors, io, jit, parallel and data;
the stages (mbd, contact, mesh, wear); loop and diagnose; plot; the commands and :mod:`fewear.api`.

Only modules that need DOLFINx import it. The public Python API is :mod:`fewear.api`, its names
re-exported here (``fewear.run``, ``fewear.solve_contact``, ...) and imported on first use, so
that ``import fewear`` stays cheap; everything else is internal.
"""

import logging
import os

_API = ("ContactResult", "Diagnosis", "DynamicsResult", "RunResult", "ScarResult",
        "default_config", "diagnose_data", "dynamics", "load_config", "run", "scar",
        "solve_contact")


def __getattr__(name: str):
    """The names of :mod:`fewear.api`, imported on first use."""
    if name in _API:
        from fewear import api

        return getattr(api, name)
    raise AttributeError(f"module 'fewear' has no attribute {name!r}")


def __dir__():
    return sorted([*globals(), *_API])


class _BuildChatter(logging.Filter):
    """Drops distutils' records below WARNING: DOLFINx's form compiler builds each new form with
    cffi, which sets the root logger to INFO and logs the gcc command lines through distutils,
    and FFCx gives the root logger a handler; a first run printed dozens of ``INFO:root:`` lines.
    On the root logger (distutils logs to it), so that every process fewear runs in (a command,
    its worker processes and MPI ranks, a notebook) has it; other records pass."""

    def filter(self, record: logging.LogRecord) -> bool:
        return record.levelno >= logging.WARNING or "distutils" not in record.pathname


if not any(isinstance(each, _BuildChatter) for each in logging.getLogger().filters):
    logging.getLogger().addFilter(_BuildChatter())

# OpenBLAS (installed by .ci/setup) on one thread: fewear spreads its work over processes and MPI
# ranks, and the wear loop runs a block's dynamics in a thread beside the mesh stage, both calling
# BLAS/LAPACK; the threaded build is safe for such concurrent calls (the serial build is not: it
# crashed the dynamics on a run under cProfile), and more than one thread per call would only
# oversubscribe the cores. Read by OpenBLAS when it loads, i.e. with the first import of numpy.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__version__ = "0.7.0"
