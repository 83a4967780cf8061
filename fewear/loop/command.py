"""``fewear run``: the prediction for every rod model, a checkpoint after every block, a progress
line per block, the outputs written all or nothing."""

from __future__ import annotations

import math
import sys
import time

from fewear.loop.block import new_bushing, new_case, predict_case, restored_bushing
from fewear.loop.progress import CaseProgress
from fewear.loop.settings import run_inputs_from_config, run_sections


class Progress:
    """One line per block on stderr (rank 0): a bar of the cycles done, depth, ETA."""

    def __init__(self, comm, total_cycles: int, n_cases: int):
        self.comm, self.total, self.n_cases = comm, total_cycles, n_cases
        self.start = time.perf_counter()
        self.resumed_fraction = 0.0  # of the whole run, done before this process (--resume)

    def message(self, text: str) -> None:
        if self.comm.rank == 0:
            print(f"fewear run [{time.perf_counter() - self.start:6.1f} s] {text}",
                  file=sys.stderr, flush=True)

    def block(self, rod: str, index: int, case: CaseProgress, done_before: float) -> None:
        fraction = case.state.cycles / self.total
        overall = (done_before + fraction) / self.n_cases
        elapsed = time.perf_counter() - self.start
        done_here = overall - self.resumed_fraction
        eta = elapsed * (1.0 - overall) / done_here if done_here > 0 else math.inf
        bar = "#" * int(20 * fraction) + "." * (20 - int(20 * fraction))
        self.message(f"{rod} [{bar}] block {case.state.blocks}, {case.state.cycles:,}/"
                     f"{self.total:,} cycles, max depth {case.state.depth_m.max():.3e} m, "
                     f"ETA {eta:.0f} s")


def main(args) -> int:
    """``fewear run``: the prediction for every rod model of ``[wear_loop]``, written all or
    nothing into ``args.out``; a checkpoint after every block (``--resume`` continues it)."""
    from mpi4py import MPI

    from fewear.io.config import load_config
    from fewear.io.output import staged_output
    from fewear.loop import checkpoint
    from fewear.loop.outputs import write_run_outputs

    comm = MPI.COMM_WORLD
    config = load_config(args.config, run_sections())
    inputs = run_inputs_from_config(config)
    progress = Progress(comm, inputs.loop.total_cycles, len(inputs.loop.rod_models))
    store = checkpoint.Checkpoint(args.out, config, comm)
    cases = store.load() if args.resume else {}
    if cases:
        progress.resumed_fraction = sum(
            case.state.cycles / inputs.loop.total_cycles for case in cases.values()) / len(
            inputs.loop.rod_models)
        progress.message(f"resuming from {store.path}: " + ", ".join(
            f"{rod} at {case.state.cycles:,} cycles" for rod, case in cases.items()))
    with staged_output(args.out, comm) as stage:
        for index, rod in enumerate(inputs.loop.rod_models):
            case = cases.get(rod)
            if case is not None and case.state.cycles >= inputs.loop.total_cycles:
                continue  # finished before an interruption: nothing to mesh or solve
            progress.message(f"{rod} rod: meshing the bushing and condensing it onto the bore")
            if case is None:
                bushing = new_bushing(inputs, comm)
                case = cases[rod] = new_case(bushing)
            else:
                bushing = restored_bushing(inputs, case, comm)

            def after_block(case, rod=rod, index=index):
                store.save(cases)
                progress.block(rod, index, case, index)

            predict_case(rod, inputs, bushing, case, after_block)
        if comm.rank == 0:
            write_run_outputs(stage, cases, inputs, config)
    progress.message(f"done: {args.out}")
    return 0
