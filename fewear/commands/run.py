"""``fewear run``: the prediction for every rod model, a checkpoint after every block, a progress
line per block, the outputs written all or nothing.

The rod models are independent runs, so they run side by side: under ``mpirun -n N`` the ranks
are split into one sub-communicator per rod model (a rod model with several ranks splits its FE
work among them); a plain ``fewear run`` starts one worker process per rod model, up to the
CPU cores (``--jobs``). A rod model on one rank or in one process computes exactly what the
serial run does, so the results are the same, bit for bit.
"""

from __future__ import annotations

import math
import shlex
import sys
import time
from pathlib import Path

from fewear.errors import FewearInputError, set_interrupt_note
from fewear.loop.block import new_bushing, new_case, predict_case, restored_bushing
from fewear.loop.checkpoint import FOLDER, Checkpoint
from fewear.loop.progress import CaseProgress
from fewear.loop.settings import run_inputs_from_config, run_sections
from fewear.parallel import usable_cores


class Progress:
    """One line per block of a rod model on stderr (the first rank of its communicator): a bar of
    its cycles done, the depth, its ETA."""

    def __init__(self, comm, rod: str, total_cycles: int, start_cycles: int = 0):
        self.comm, self.rod, self.total = comm, rod, total_cycles
        self.start_cycles = start_cycles  # done before this process (--resume)
        self.start = time.perf_counter()

    def message(self, text: str) -> None:
        if self.comm.rank == 0:
            print(f"fewear run [{time.perf_counter() - self.start:6.1f} s] {self.rod}: {text}",
                  file=sys.stderr, flush=True)

    def block(self, case: CaseProgress) -> None:
        cycles = case.state.cycles
        done_here = cycles - self.start_cycles
        elapsed = time.perf_counter() - self.start
        eta = elapsed * (self.total - cycles) / done_here if done_here > 0 else math.inf
        bar = "#" * int(20 * cycles / self.total) + "." * (20 - int(20 * cycles / self.total))
        self.message(f"[{bar}] block {case.state.blocks}, {cycles:,}/{self.total:,} cycles, "
                     f"max depth {case.state.depth_m.max():.3e} m, ETA {eta:.0f} s")


def _say(text: str) -> None:
    print(f"fewear run: {text}", file=sys.stderr, flush=True)


def run_cases(rods, config: dict, out_dir, resumed: dict, comm) -> dict:
    """The wear prediction of each of ``rods`` in turn on ``comm``, continuing the cases of
    ``resumed`` (rod -> :class:`CaseProgress`), a checkpoint after every block; rod -> case."""
    inputs = run_inputs_from_config(config)
    store = Checkpoint(out_dir, config)
    cases = {}
    for rod in rods:
        case = resumed.get(rod)
        progress = Progress(comm, rod, inputs.loop.total_cycles,
                            0 if case is None else case.state.cycles)
        if case is not None and case.state.cycles >= inputs.loop.total_cycles:
            cases[rod] = case  # finished before an interruption: nothing to mesh or solve
            continue
        progress.message("meshing the bushing and condensing it onto the bore")
        if case is None:
            bushing = new_bushing(inputs, comm)
            case = new_case(bushing)
        else:
            bushing = restored_bushing(inputs, case, comm)

        def after_block(case, rod=rod, progress=progress):
            if comm.rank == 0:
                store.save(rod, case)
            progress.block(case)

        try:
            predict_case(rod, inputs, bushing, case, after_block)
        finally:
            bushing.close()
        cases[rod] = case
    return cases


def _run_in_worker(rods, config: dict, out_dir, resumed: dict) -> dict:
    """:func:`run_cases` in a worker process, on its own (singleton) MPI communicator."""
    from mpi4py import MPI

    return run_cases(rods, config, out_dir, resumed, MPI.COMM_WORLD)


def _in_processes(rods, config: dict, out_dir, resumed: dict, jobs: int) -> dict:
    """One worker process per group of rods (``jobs`` of them, :func:`fewear.parallel.
    worker_pool`); a worker's error stops the others at once (their checkpoints stay)."""
    from fewear.kernels import compile_kernels
    from fewear.parallel import worker_pool

    groups = [rods[index::jobs] for index in range(jobs)]
    cases = {}
    compile_kernels(_say)  # once here, not in every worker at once on an empty cache
    with worker_pool(jobs) as pool:
        results = [pool.apply_async(_run_in_worker, (group, config, out_dir, {
            rod: resumed[rod] for rod in group if rod in resumed})) for group in groups]
        for result in results:
            cases.update(result.get())
    return cases


def _on_ranks(rods, config: dict, out_dir, resumed: dict, world) -> dict:
    """The ranks of ``world`` split into one sub-communicator per group of rods; the cases
    gathered on rank 0 (the other ranks get an empty dict). An input error in one group is
    raised on every rank, after the other groups have finished."""
    import fewear.contact.condensed  # noqa: F401 (PETSc starts on every rank, collectively)
    from fewear.kernels import compile_kernels

    if world.rank == 0:
        compile_kernels(_say)  # the other ranks then load it instead of compiling it at once
    world.Barrier()
    groups = min(world.size, len(rods))
    color = world.rank % groups
    group_comm = world.Split(color, world.rank)
    mine, error = {}, None
    try:
        mine = run_cases(rods[color::groups], config, out_dir, resumed, group_comm)
    except FewearInputError as exc:
        error = str(exc)
    finally:
        group_comm.Free()
    errors = [message for message in world.allgather(error) if message]
    if errors:
        raise FewearInputError(errors[0])
    gathered = world.gather(mine if world.rank == color else {}, root=0)
    return {} if world.rank else {rod: case for part in gathered for rod, case in part.items()}


def main(args) -> int:
    """``fewear run``: the prediction for every rod model of ``[wear_loop]``, written all or
    nothing into ``args.out``; a checkpoint after every block (``--resume`` continues it)."""
    from fewear.io.config import load_config

    if args.resume and getattr(args, "overwrite", False):
        raise FewearInputError("--resume and --overwrite: choose one (--resume continues the run "
                               "in --out, --overwrite replaces it with a new one)")
    predict_and_write(load_config(args.config, run_sections()), args)
    return 0


def predict_and_write(config: dict, args) -> dict[str, CaseProgress]:
    """The prediction of ``config`` (loaded) for every rod model, written into ``args.out`` as
    :func:`main` says (``args``: ``out``, ``resume``, ``overwrite``, ``jobs``, and ``config``, the
    file named in messages); rod -> case on rank 0 ({} on the others). :func:`fewear.api.run`
    calls it too."""
    from mpi4py import MPI

    from fewear.io.output import staged_output
    from fewear.io.transaction import run_replaced
    from fewear.loop.outputs import write_run_outputs

    world = MPI.COMM_WORLD
    inputs = run_inputs_from_config(config)
    rods = list(inputs.loop.rod_models)
    jobs = _jobs(args.jobs, len(rods))
    store = Checkpoint(args.out, config)
    resumed = store.load(rods) if args.resume else {}
    if resumed and world.rank == 0:
        _say(f"resuming from {store.path}: " + ", ".join(
            f"{rod} at {case.state.cycles:,} cycles" for rod, case in resumed.items()))
    overwrite = getattr(args, "overwrite", False)
    with run_replaced(args.out, earlier_run, store, args.resume, overwrite,
                      resume_command(args).replace(" --resume", " --overwrite"), world):
        set_interrupt_note(lambda: interrupt_note(args, store, rods, inputs.loop.total_cycles))
        with staged_output(args.out, world) as stage:
            if world.size > 1:
                cases = _on_ranks(rods, config, args.out, resumed, world)
            elif jobs > 1:
                cases = _in_processes(rods, config, args.out, resumed, jobs)
            else:
                cases = run_cases(rods, config, args.out, resumed, world)
            if world.rank == 0:
                cases = {rod: cases[rod] for rod in rods}
                write_run_outputs(stage, cases, inputs, config)
                write_run_figures(stage, cases, inputs.loop.total_cycles)
    if world.rank == 0:
        _say(f"done: {args.out}")
    return cases if world.rank == 0 else {}


def write_run_figures(folder: Path, cases: dict[str, CaseProgress], total_cycles: int) -> None:
    """``wear_profiles.png`` (seed Fig. 7a) and ``max_wear.png`` (seed Fig. 7b) of the cases."""
    import numpy as np

    from fewear.loop.outputs import MAX_WEAR_PNG, PROFILES_PNG
    from fewear.plot.wear import plot_max_wear, plot_wear_profiles

    plot_wear_profiles({rod: (case.state.angle_rad, case.state.depth_m)
                        for rod, case in cases.items()}, folder / PROFILES_PNG, total_cycles)
    plot_max_wear({rod: (np.array([r.cycles for r in case.records]),
                         np.array([r.depth_m.max() for r in case.records]))
                   for rod, case in cases.items()}, folder / MAX_WEAR_PNG)


def resume_command(args) -> str:
    """The command line that continues this run."""
    config = "" if args.config is None else f" --config {shlex.quote(str(args.config))}"
    return f"fewear run --resume{config} --out {shlex.quote(str(args.out))}"


def interrupt_note(args, store: Checkpoint, rods, total_cycles: int) -> str:
    """What an interrupted run kept (the rods' cycles in the checkpoint) and how to go on."""
    saved = {rod: cycles for rod, cycles in store.saved_cycles().items() if rod in rods}
    if not saved:
        return ("no wear block had finished, nothing was kept (the output folder is as it was); "
                "start again with: " + resume_command(args).replace(" --resume", ""))
    kept = ", ".join(f"{rod} at {cycles:,}/{total_cycles:,} cycles"
                     for rod, cycles in saved.items())
    return f"the checkpoint {store.path} keeps {kept}; continue with: {resume_command(args)}"


def earlier_run(out: Path) -> list[Path]:
    """The checkpoint and output files of an earlier run in ``out`` (none: []): what --overwrite
    replaces (the files :mod:`fewear.loop.outputs` writes, and ``fewear plot``'s figure)."""
    from fewear.loop.outputs import RUN_FILES
    from fewear.plot.worn_bushing import FIGURE

    if not out.is_dir():
        return []
    found = [out / FOLDER] if (out / FOLDER).is_dir() and any((out / FOLDER).iterdir()) else []
    found += [out / name for name in (*RUN_FILES, FIGURE) if (out / name).is_file()]
    if found:  # the cases' XDMF files belong to a run only beside its checkpoint or summary
        found += sorted(path for pattern in ("*.xdmf", "*.h5") for path in out.glob(pattern))
    return found


def _jobs(requested: int | None, n_rods: int) -> int:
    """Worker processes: ``--jobs`` (at least 1), by default one per rod model up to the cores."""
    if requested is None:
        return max(1, min(n_rods, usable_cores()))
    if requested < 1:
        raise FewearInputError(f"--jobs {requested}: expected a number of processes >= 1")
    return min(requested, n_rods)
