"""Independent runs side by side in worker processes (the rod models of ``fewear run``, the
candidate runs of a diagnosis).

Workers are spawned (a fresh interpreter: forking a process that holds MPI and PETSc state is
unsafe), each an MPI singleton of its own, with its BLAS on one thread so that the workers do
not oversubscribe the cores between them. A spawned worker normally imports the parent's main
script first; a script without a ``__main__`` guard (the literate demos, a user's script) would
then run again in every worker, which starts workers of its own. So while the pool lives, the
parent's ``__main__`` is a module without a file: the workers import fewear's functions only.
"""

from __future__ import annotations

import os
import sys
import types
from collections.abc import Callable
from contextlib import ExitStack, contextmanager

SINGLE_THREAD_VARIABLES = ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS")


LAUNCHER_RANK_VARIABLES = (("OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"),
                           ("PMI_RANK", "PMI_SIZE"), ("PMIX_RANK", "PMIX_SIZE"))
"""The (rank, size) environment variables of Open MPI's, MPICH's and PMIx's launchers."""


def launcher_rank_and_size() -> tuple[int, int]:
    """This process's MPI rank and the number of ranks, read from the launcher's environment
    without importing MPI: (0, 1) outside ``mpirun``."""
    for rank, size in LAUNCHER_RANK_VARIABLES:
        if rank in os.environ:
            return int(os.environ[rank]), int(os.environ.get(size, "1"))
    return 0, 1


def usable_cores() -> int:
    """The CPU cores this process may run on."""
    return len(os.sched_getaffinity(0))


@contextmanager
def worker_pool(processes: int):
    """A spawned :class:`multiprocessing.pool.Pool` of ``processes`` workers; leaving the block
    (also by an error, which stops the other workers at once) terminates them."""
    import multiprocessing

    saved = {name: os.environ.get(name) for name in SINGLE_THREAD_VARIABLES}
    os.environ.update(dict.fromkeys(SINGLE_THREAD_VARIABLES, "1"))  # read by the spawned
    main_module = sys.modules["__main__"]
    sys.modules["__main__"] = types.ModuleType("__main__")
    try:
        with multiprocessing.get_context("spawn").Pool(processes, _quiet_worker,
                                                       (os.getpid(),)) as pool:
            yield pool
    finally:
        sys.modules["__main__"] = main_module
        for name, value in saved.items():
            if value is None:
                os.environ.pop(name, None)
            else:
                os.environ[name] = value


PR_SET_PDEATHSIG = 1
"""Linux prctl(2) option: the signal a process gets when its parent dies."""


def _quiet_worker(parent_pid: int) -> None:
    """A worker ignores Ctrl-C (the terminal sends it to the whole process group): the parent
    reports the interruption once and terminates the workers when it leaves the pool, instead of
    every worker printing a ``KeyboardInterrupt`` traceback. And it ends with its parent
    (``parent_pid``): a parent killed outright (SIGTERM, SIGKILL, the out-of-memory killer)
    leaves no pool to terminate them, and a worker would finish its current run first, at the
    paper's scale minutes of both cores."""
    import ctypes
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    if sys.platform.startswith("linux"):
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, int(signal.SIGTERM))
    if os.getppid() != parent_pid:  # the parent died before the request
        os._exit(1)


def side_by_side(function: Callable, arguments: list[tuple], prepare: Callable | None = None):
    """``[function(*a) for a in arguments]``, in worker processes (those of
    :func:`workers_kept` while it is open, else a :func:`worker_pool` of one per core and at
    most one per call) when there are several calls and cores and this process is not one of
    several MPI ranks (they share each call's work instead); else here, one after the other.
    ``prepare()`` runs here before the calls are handed out (e.g. compiling what the workers
    would each compile at once; with a kept pool, before every batch that passes it: the pool
    may have been started by a batch that did not)."""
    from mpi4py import MPI

    jobs = min(len(arguments), usable_cores())
    if jobs < 2 or MPI.COMM_WORLD.size > 1:
        return [function(*args) for args in arguments]
    if prepare is not None:  # also before a kept pool's later batch: its workers may not
        prepare()            # have run what it prepares yet
    if _kept.stack is not None:
        if _kept.pool is None:
            _kept.pool = _kept.stack.enter_context(worker_pool(usable_cores()))
        return _kept.pool.starmap(function, arguments, chunksize=1)
    with worker_pool(jobs) as pool:
        return pool.starmap(function, arguments, chunksize=1)  # calls of unequal cost


class _Kept:
    """The open :func:`workers_kept` block (``stack`` None: none) and its pool, once started."""

    stack: ExitStack | None = None
    pool = None


_kept = _Kept()


@contextmanager
def workers_kept():
    """Within the block, :func:`side_by_side` hands its calls to one pool of workers (one per
    core, started at the first call that uses workers, stopped when the block is left) instead
    of starting a pool per call: a worker's start (an interpreter importing DOLFINx and PETSc,
    loading the compiled kernels and forms) costs seconds, and a joint diagnosis makes some
    fifteen batches of runs and fits. A nested block shares the outer one's pool."""
    if _kept.stack is not None:
        yield
        return
    with ExitStack() as stack:
        _kept.stack = stack
        try:
            yield
        finally:
            _kept.stack, _kept.pool = None, None


def release_petsc_garbage(*comms) -> None:
    """Destroy the PETSc objects on ``comms`` (mpi4py communicators) whose Python wrappers are
    gone. Collective: every rank of each communicator calls it at the same point.

    petsc4py 3.18 does not destroy an object on a communicator other than PETSC_COMM_SELF when
    its wrapper is collected (a destroy is collective, and each rank collects its garbage at its
    own time): it keeps it on the communicator's garbage list until
    ``PETSc.garbage_cleanup(comm)``, and a list whose communicator is freed (a DOLFINx mesh frees
    its duplicate of the communicator with it) is never cleaned. Left there, each ALE move's copy
    of the stiffness matrix and each mesh's MUMPS factors stayed in memory: a worker of a joint
    diagnosis on the default mesh grew by about 42 MB per forward run."""
    from petsc4py import PETSc

    for comm in comms:
        PETSc.garbage_cleanup(comm)
