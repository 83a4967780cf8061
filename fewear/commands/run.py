"""``fewear run``: the prediction for every case (rod model) and its clearance joints, a checkpoint
after every block, a progress line per block, the outputs written all or nothing.

The work items are the members of the cases (``--members N``, :class:`fewear.loop.plan.Member`:
N runs of each case whose starts differ, an ensemble; 1 by default), independent runs, so they
run side by side: under ``mpirun -n N`` the ranks are split into one sub-communicator per member
(a member with several ranks splits its FE work among them); a plain ``fewear run`` runs them in
worker processes, up to the CPU cores (``--jobs``). A member on one rank or in one process
computes exactly what the serial run does, so the results are the same, bit for bit. The joints
of a member share its dynamics every block, and every wear step of the block covers the same
crank cycles for all of them (:func:`fewear.loop.block.wear_block`); a member on several ranks
splits its joints among them (:mod:`fewear.loop.joint_ranks`), else they are worn one after the
other.
"""

from __future__ import annotations

import math
import shlex
import sys
import time
from pathlib import Path

from fewear.errors import FewearInputError, set_interrupt_note
from fewear.loop.block import JointRun, new_bushing, new_case, predict_joints, restored_bushing
from fewear.loop.checkpoint import FOLDER, Checkpoint
from fewear.loop.joint_ranks import JointRanks
from fewear.loop.plan import Member, run_plan
from fewear.loop.settings import run_sections
from fewear.parallel import usable_cores


class Progress:
    """One line per block of a case on stderr (the first rank of its communicator): a bar of its
    cycles done, each joint's depth, its ETA (and that its history is imported, if it is)."""

    def __init__(self, comm, case: str, total_cycles: int, start_cycles: int = 0,
                 note: str = ""):
        self.comm, self.case, self.total, self.note = comm, case, total_cycles, note
        self.start_cycles = start_cycles  # done before this process (--resume)
        self.start = time.perf_counter()

    def message(self, text: str) -> None:
        if self.comm.rank == 0:
            print(f"fewear run [{time.perf_counter() - self.start:6.1f} s] {self.case}: {text}",
                  file=sys.stderr, flush=True)

    def block(self, joints: dict) -> None:
        """After a block of ``joints`` (joint name -> :class:`CaseProgress`, at the same block)."""
        state = next(iter(joints.values())).state
        cycles = state.cycles
        done_here = cycles - self.start_cycles
        elapsed = time.perf_counter() - self.start
        eta = elapsed * (self.total - cycles) / done_here if done_here > 0 else math.inf
        bar = "#" * int(20 * cycles / self.total) + "." * (20 - int(20 * cycles / self.total))
        depths = ", ".join(f"{progress.state.depth_m.max():.3e} m"
                           + (f" ({joint})" if len(joints) > 1 else "")
                           for joint, progress in joints.items())
        self.message(f"[{bar}] block {state.blocks}, {cycles:,}/{self.total:,} cycles, "
                     f"max depth {depths}, ETA {eta:.0f} s{self.note}")


def _say(text: str) -> None:
    print(f"fewear run: {text}", file=sys.stderr, flush=True)


def run_cases(members, config: dict, out_dir, resumed: dict, comm) -> dict:
    """The wear prediction of each :class:`Member` of ``members`` in turn on ``comm`` (its joints
    split among the ranks, :class:`fewear.loop.joint_ranks.JointRanks`), continuing the members
    of ``resumed`` (member -> joint name -> :class:`CaseProgress`), a checkpoint after every
    block; member -> joint name -> progress (complete on the first rank)."""
    plan = run_plan(config)
    store = Checkpoint(out_dir, config, plan.history_sha256)
    note = "" if plan.imported is None else " (imported joint history: no feedback)"
    cases = {}
    for member in members:
        case, saved = member.case, resumed.get(member)
        start_cycles = 0 if saved is None else next(iter(saved.values())).state.cycles
        progress = Progress(comm, _member_label(plan, member), plan.loop.total_cycles,
                            start_cycles, note)
        if start_cycles >= plan.loop.total_cycles:
            cases[member] = saved  # finished before an interruption: nothing to mesh or solve
            continue
        progress.message("meshing the bushing and condensing it onto the bore"
                         + ("s" if len(plan.joints) > 1 else ""))
        ranks = JointRanks(list(plan.joints), comm)
        joints, whole = {}, dict(saved or {})
        try:
            for name in ranks.mine:
                inputs, label = plan.joints[name], _joint_label(plan, member, name)
                if saved is None:
                    bushing = new_bushing(inputs, ranks.sub)
                    joints[name] = JointRun(label, inputs, bushing, new_case(bushing))
                else:
                    joints[name] = JointRun(label, inputs, restored_bushing(
                        inputs, saved[name], ranks.sub), saved[name])

            def after_block(member=member, joints=joints, whole=whole, progress=progress,
                            ranks=ranks):
                ranks.gathered({name: joint.case for name, joint in joints.items()}, whole)
                if comm.rank == 0:
                    ordered = {name: whole[name] for name in plan.joints}
                    store.save(member.key, ordered)
                    progress.block(ordered)

            predict_joints(case, joints, plan.simulate_block(config, member), after_block,
                           ranks if ranks.split else None)
        finally:
            for joint in joints.values():
                joint.bushing.close()
            ranks.close()
        cases[member] = ({name: whole[name] for name in plan.joints} if comm.rank == 0
                         else whole)
    return cases


def _member_label(plan, member: Member) -> str:
    """How the progress lines name a member: by its case alone when it is the only one."""
    if plan.loop.members == 1:
        return member.case
    return f"{member.case} member {member.index} (start +{member.start_offset_deg:g} deg)"


def _joint_label(plan, member: Member, joint: str) -> str:
    """How the messages name a joint of a member: the slider-crank's one joint by its rod
    model."""
    of = "" if plan.loop.members == 1 else f" member {member.index}"
    if len(plan.joints) > 1:
        return f"{member.case} case{of}, joint {joint}"
    return f"{member.case} rod{of}" if plan.imported is None else "imported joint history"


def _run_in_worker(member: Member, config: dict, out_dir, resumed: dict) -> dict:
    """:func:`run_cases` of one member in a worker process, on its own (singleton) MPI
    communicator."""
    from mpi4py import MPI

    return run_cases([member], config, out_dir, resumed, MPI.COMM_WORLD)


def _in_processes(members, config: dict, out_dir, resumed: dict, jobs: int) -> dict:
    """The members in ``jobs`` worker processes (:func:`fewear.parallel.worker_pool`), each
    taking the next member when it is free; a worker's error stops the others at once (their
    checkpoints stay)."""
    from fewear.kernels import compile_kernels_unless_cached
    from fewear.parallel import worker_pool

    cases = {}
    compile_kernels_unless_cached(_say)  # here, not in every worker at once on an empty cache
    with worker_pool(jobs) as pool:
        results = [pool.apply_async(_run_in_worker, (member, config, out_dir, {
            member: resumed[member]} if member in resumed else {})) for member in members]
        for result in results:
            cases.update(result.get())
    return cases


def _on_ranks(members, config: dict, out_dir, resumed: dict, world) -> dict:
    """The ranks of ``world`` split into one sub-communicator per group of members; the
    members gathered on rank 0 (the other ranks get an empty dict). An input error in one
    group is raised on every rank, after the other groups have finished."""
    import fewear.contact.condensed  # noqa: F401 (PETSc starts on every rank, collectively)
    from fewear.kernels import compile_kernels_unless_cached

    if world.rank == 0:  # the other ranks then load the kernels instead of compiling them at once
        compile_kernels_unless_cached(_say)
    world.Barrier()
    groups = min(world.size, len(members))
    color = world.rank % groups
    group_comm = world.Split(color, world.rank)
    mine, error = {}, None
    try:
        mine = run_cases(members[color::groups], config, out_dir, resumed, group_comm)
    except FewearInputError as exc:
        error = str(exc)
    finally:
        group_comm.Free()
    errors = [message for message in world.allgather(error) if message]
    if errors:
        raise FewearInputError(errors[0])
    gathered = world.gather(mine if world.rank == color else {}, root=0)
    return {} if world.rank else {member: case for part in gathered
                                  for member, case in part.items()}


def main(args) -> int:
    """``fewear run``: the prediction for every rod model of ``[wear_loop]`` (or for the joint
    history of ``--joint-history`` / ``[wear_loop] joint_history``), written all or nothing into
    ``args.out``; a checkpoint after every block (``--resume`` continues it)."""
    from fewear.io.config import load_config

    if args.resume and getattr(args, "overwrite", False):
        raise FewearInputError("--resume and --overwrite: choose one (--resume continues the run "
                               "in --out, --overwrite replaces it with a new one)")
    config = load_config(args.config, run_sections())
    if getattr(args, "joint_history", None):
        config["wear_loop"]["joint_history"] = str(args.joint_history)
    if getattr(args, "members", None) is not None:
        config["wear_loop"]["members"] = args.members
    predict_and_write(config, args)
    return 0


def predict_and_write(config: dict, args) -> dict:
    """The prediction of ``config`` (loaded) for every case, written into ``args.out`` as
    :func:`main` says (``args``: ``out``, ``resume``, ``overwrite``, ``jobs``, and ``config``, the
    file named in messages; ``members``, optional: ``[wear_loop] members`` set already); case ->
    joint -> progress (member 0's) on rank 0 ({} on the others). :func:`fewear.api.run` calls it
    too."""
    from mpi4py import MPI

    from fewear.io.output import staged_output
    from fewear.io.transaction import run_replaced
    from fewear.loop.outputs import write_run_outputs

    world = MPI.COMM_WORLD
    plan = run_plan(config)
    members = list(plan.members)
    keys = [member.key for member in members]
    jobs = _jobs(args.jobs, len(members))
    store = Checkpoint(args.out, config, plan.history_sha256)
    saved = store.load(keys, plan.joints) if args.resume else {}
    resumed = {member: saved[member.key] for member in members if member.key in saved}
    if resumed and world.rank == 0:
        _say(f"resuming from {store.path}: " + ", ".join(
            f"{member.key} at {next(iter(case.values())).state.cycles:,} cycles"
            for member, case in resumed.items()))
    overwrite = getattr(args, "overwrite", False)
    with run_replaced(args.out, earlier_run, store, args.resume, overwrite,
                      resume_command(args).replace(" --resume", " --overwrite"), world):
        set_interrupt_note(lambda: interrupt_note(args, store, keys, plan.loop.total_cycles))
        with staged_output(args.out, world) as stage:
            if world.size > 1:
                runs = _on_ranks(members, config, args.out, resumed, world)
            elif jobs > 1:
                runs = _in_processes(members, config, args.out, resumed, jobs)
            else:
                runs = run_cases(members, config, args.out, resumed, world)
            cases = {}
            if world.rank == 0:
                cases = {case: runs[Member(case)] for case in plan.cases}
                ensemble = None if plan.loop.members == 1 else {
                    case: [runs[Member(case, index)] for index in range(plan.loop.members)]
                    for case in plan.cases}
                write_run_outputs(stage, cases, plan.joints, config, plan.history_source,
                                  ensemble)
                write_run_figures(stage, cases, plan.loop.total_cycles, ensemble)
    if world.rank == 0:
        _say(f"done: {args.out}")
    return cases if world.rank == 0 else {}


def write_run_figures(folder: Path, cases: dict, total_cycles: int,
                      ensemble: dict | None = None) -> None:
    """``wear_profiles.png`` (seed Fig. 7a) and ``max_wear.png`` (seed Fig. 7b) of the cases'
    joints (case -> joint -> :class:`fewear.loop.progress.CaseProgress`); of an ensemble
    (case -> its members' joint -> progress, :mod:`fewear.loop.ensemble`), the members' mean
    with bands of one standard deviation either side and of their range."""
    import numpy as np

    from fewear.loop.outputs import MAX_WEAR_PNG, PROFILES_PNG
    from fewear.plot.wear import plot_max_wear, plot_wear_profiles

    if ensemble is not None:
        _write_ensemble_figures(folder, ensemble, total_cycles)
        return
    labelled = {case if len(joints) == 1 else f"{case}, {joint}": progress
                for case, joints in cases.items() for joint, progress in joints.items()}
    plot_wear_profiles({label: (progress.state.angle_rad, progress.state.depth_m)
                        for label, progress in labelled.items()}, folder / PROFILES_PNG,
                       total_cycles)
    plot_max_wear({label: (np.array([r.cycles for r in progress.records]),
                           np.array([r.depth_m.max() for r in progress.records]))
                   for label, progress in labelled.items()}, folder / MAX_WEAR_PNG)


def _write_ensemble_figures(folder: Path, ensemble: dict, total_cycles: int) -> None:
    """The figures of :func:`write_run_figures` of an ensemble: the final profile's and the
    maximum depth's statistics over the members (:mod:`fewear.loop.ensemble`)."""
    from fewear.loop.ensemble import max_depth_statistics, statistics
    from fewear.loop.outputs import MAX_WEAR_PNG, PROFILES_PNG
    from fewear.plot.wear import plot_max_wear_bands, plot_wear_profile_bands

    members = len(next(iter(ensemble.values())))
    joints = next(iter(ensemble.values()))[0]
    labels = {(case, joint): (case if len(joints) == 1 else f"{case}, {joint}")
              + f", {members} members" for case in ensemble for joint in joints}
    profiles, maxima = {}, {}
    for (case, joint), label in labels.items():
        runs = [member[joint] for member in ensemble[case]]
        profiles[label] = (runs[0].state.angle_rad,
                           statistics([run.state.depth_m for run in runs]))
        maxima[label] = max_depth_statistics(runs)
    plot_wear_profile_bands(profiles, folder / PROFILES_PNG, total_cycles)
    plot_max_wear_bands(maxima, folder / MAX_WEAR_PNG)


def resume_command(args) -> str:
    """The command line that continues this run."""
    config = "" if args.config is None else f" --config {shlex.quote(str(args.config))}"
    history = getattr(args, "joint_history", None)
    history = "" if not history else f" --joint-history {shlex.quote(str(history))}"
    members = getattr(args, "members", None)
    members = "" if members is None else f" --members {members}"
    return f"fewear run --resume{config}{history}{members} --out {shlex.quote(str(args.out))}"


def interrupt_note(args, store: Checkpoint, rods, total_cycles: int) -> str:
    """What an interrupted run kept (the cycles of its members, by their keys ``rods``, in the
    checkpoint) and how to go on."""
    found = store.saved_cycles()
    saved = {rod: found[rod] for rod in rods if rod in found}
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
    """Worker processes: ``--jobs`` (at least 1), by default one per member (``n_rods`` of them)
    up to the cores."""
    if requested is None:
        return max(1, min(n_rods, usable_cores()))
    if requested < 1:
        raise FewearInputError(f"--jobs {requested}: expected a number of processes >= 1")
    return min(requested, n_rods)
