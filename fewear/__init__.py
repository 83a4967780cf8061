"""fewear: finite-element wear workbench for revolute clearance joints.

Stages (one subpackage each, data passed between them as frozen dataclasses in SI units):

- :mod:`fewear.mbd`        planar multibody dynamics (NumPy): rigid and ANCF bodies, clearance joint
- :mod:`fewear.contact`    bushing contact model (DOLFINx + PETSc), pressures and slips on the bore
- :mod:`fewear.wear`       Archard wear law and the wear coefficient k(p, v)
- :mod:`fewear.mesh`       bushing meshes (gmsh), ALE motion and re-meshing
- :mod:`fewear.diagnose`   measured data, diagnosis of what the model gets wrong
- :mod:`fewear.io`         configuration, outputs
- :mod:`fewear.plot`       figures (matplotlib; PyVista imported lazily)

Only modules that need DOLFINx import it.
"""

import os

# OpenBLAS (installed by .ci/setup) on one thread: fewear spreads its work over processes and MPI
# ranks, and the wear loop runs a block's dynamics in a thread beside the mesh stage, both calling
# BLAS/LAPACK; the threaded build is safe for such concurrent calls (the serial build is not: it
# crashed the dynamics on a run under cProfile), and more than one thread per call would only
# oversubscribe the cores. Read by OpenBLAS when it loads, i.e. with the first import of numpy.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__version__ = "0.7.0"
