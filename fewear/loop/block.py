"""One wear block of a case's clearance joints (stages 1-5 of the flowchart in :mod:`fewear.loop`),
and the blocks of a case until its total cycles (:func:`predict_joints`): every joint of a
mechanism worn together on one dynamics, the paper's slider-crank's one joint among them."""

from __future__ import annotations

import math
import time
from concurrent.futures import ThreadPoolExecutor
from contextlib import contextmanager
from dataclasses import dataclass, replace

import numpy as np

from fewear.contact.admissible import ContactLoadError
from fewear.errors import FewearInputError
from fewear.loop.progress import BlockRecord, CaseProgress, timed
from fewear.loop.settings import RunInputs
from fewear.loop.stages import cycle_sliding, cycle_wear, load_steps
from fewear.wear.archard import CycleSliding, block_wear
from fewear.wear.extrapolation import extrapolate_block
from fewear.wear.state import WearState


def smoothed_block_wear(per_cycle: CycleSliding, state: WearState, extension, cycles: int,
                        width_rad: float):
    """:func:`block_wear` on the bore of ``state``, the depth increment smoothed around the bore
    by a Gaussian of standard deviation ``width_rad`` (volume kept): the dwell points of the few
    recorded cycles stand for an orbit that varies from cycle to cycle over the A_j cycles of
    the block, and the bore's contact does not resolve ripples shorter than a few elements.
    The wear law's history starts from the crank cycles the wear state has run (their one
    owner)."""
    return block_wear(per_cycle, replace(state.sliding, cycles=float(state.cycles)), extension,
                      cycles, smoothing_width_rad=width_rad)


def mechanism_dynamics(case: str, dynamics, joints: dict, states: dict, mechanism):
    """Stage 1 of a block of a mechanism's clearance joints (:mod:`fewear.loop.mechanism_adapter`):
    one run of the dynamics of ``case`` (its typed inputs ``dynamics``) with every joint on the
    worn clearance of its wear state (``states``: joint name -> :class:`WearState`; ``joints``:
    joint name -> its :class:`RunInputs`), warm-started from ``mechanism`` (None: the assembled
    mechanism, settling the mechanism's own settling cycles; else ``[wear_loop]
    warm_settling_cycles``). Returns ((joint name -> history, summary, final state), wall time
    in s); a mechanism the integrator cannot carry is a :class:`FewearInputError`."""
    from fewear.loop import mechanism_adapter as adapter

    loop = next(iter(joints.values())).loop
    profiles = {name: states[name].clearance_profile(inputs.contact.geometry.inner_radius_m,
                                                     inputs.contact.geometry.pin_radius_m)
                for name, inputs in joints.items()}
    inputs = adapter.block_inputs(dynamics, loop.recorded_cycles_per_block,
                                  None if mechanism is None else loop.warm_settling_cycles)
    first = next(iter(states.values()))
    with _dynamics_failure(f"{case} case", first, joints, adapter.unintegrable_hint()):
        start = time.perf_counter()
        result = adapter.simulate(inputs, start=mechanism, profiles=profiles)
    return result, time.perf_counter() - start


@contextmanager
def _dynamics_failure(label: str, state: WearState, joints: dict, hint: str):
    """A collapse of the integrator's step size as a :class:`FewearInputError` saying why: the
    pin pushed beyond a joint's radial clearance (a jammed worn pocket), or what may get past it
    (``hint`` on the unworn clearance)."""
    from fewear.mbd.integrator import StepSizeCollapse

    try:
        yield
    except StepSizeCollapse as exc:
        clearances = {name: inputs.contact.geometry.inner_radius_m
                      - inputs.contact.geometry.pin_radius_m for name, inputs in joints.items()}
        deepest = max(delta for delta, _, _ in exc.joints) if exc.joints else 0.0
        jammed = [name for name, clearance in clearances.items() if deepest > clearance]
        if jammed:
            clearance_m = clearances[jammed[0]]
            joint = f" of joint {jammed[0]}" if jammed[0] else ""
            why = (f"the pin was pushed deeper into the bore than the joint's radial clearance"
                   f"{joint} ({clearance_m * 1e3:g} mm): the mechanism jammed it into its worn "
                   "pocket, beyond the small elastic deformation the contact law describes; the "
                   "wear cannot be predicted past this bore")
        else:
            why = ("a smaller [integrator] min_step_s (1e-11 s carried the undamped rod through "
                   "a block where its Newton iterates cycled across the friction law's kink), a "
                   "larger gap_tolerance_m or a wider [wear_loop] wear_smoothing_width_deg may "
                   "get past it" + ("" if state.blocks else f"; on the unworn clearance, {hint}"))
        raise FewearInputError(
            f"{label}, block {state.blocks + 1} at {state.cycles:,} cycles: the dynamics "
            f"on the worn clearance failed ({exc}): {why}") from None


@dataclass
class JointRun:
    """One clearance joint of a case in the loop: ``label`` names it in messages, ``inputs`` its
    typed inputs, ``bushing`` its FE bushing on the worn bore, ``case`` its progress."""

    label: str
    inputs: RunInputs
    bushing: object
    case: CaseProgress


def run_block(config: dict, joint: JointRun, added_depth_per_cycle=None) -> None:
    """One wear block of the one clearance joint of ``config``'s first case (its rod model, or
    the mechanism file's variable body's model), ``joint``'s progress updated in place: stage 1
    (:func:`mechanism_dynamics` on the joint's worn clearance, from the case's last mechanism
    state), then :func:`wear_block`. For a caller that changes the config between blocks (a
    hidden effect switched on as the run goes); ``added_depth_per_cycle`` (history, state) ->
    depth per cycle (m, per bore node): a wear source of another law added to each wear step's
    impact wear."""
    from fewear.loop import mechanism_adapter as adapter

    case = config["wear_loop"]["rod_models"][0]
    name = next(iter(adapter.joint_sections(config)))
    (histories, _, mechanism), seconds = mechanism_dynamics(
        case, adapter.dynamics_inputs(config, case), {name: joint.inputs},
        {name: joint.case.state}, joint.case.mechanism)
    wear_block({name: joint}, histories, mechanism, seconds,
               added_depth_per_cycle=None if added_depth_per_cycle is None
               else {name: added_depth_per_cycle})


def wear_block(joints: dict, histories: dict, mechanism, dynamics_s: float,
               start_next=None, added_depth_per_cycle: dict | None = None,
               ranks=None) -> None:
    """Stages 2-5 of a wear block of every joint of ``joints`` (name -> :class:`JointRun`), each
    on its recorded history of ``histories`` (name -> history), their progress updated in place:
    ``[wear_loop] wear_steps_per_block`` wear steps (:func:`joint_wear_step`), each with the
    contact solved on the bore the previous step left. The contact and wear respond to the bore
    within tens of crank cycles (a stiff process: :func:`fewear.wear.archard.block_wear`), the
    joint's dynamics to the clearance far more slowly; wear steps shorter than the dynamics'
    block buy accuracy at the price of contact solves, not of dynamics.

    The joints step together: a step covers the fewest cycles any joint's extrapolation chose (the
    next block's dynamics needs every joint at the same crank cycle); the others' increment is
    worn again over those cycles. ``mechanism``: the mechanism's state after the block's
    dynamics (the next block's warm start), ``dynamics_s`` their wall time. ``start_next``
    (joint name -> worn state), optional: called once the block's last wear step is known and
    before its mesh stage, unless the run is done (the next block's dynamics start there).
    ``added_depth_per_cycle``: joint name -> (history, state) -> depth per cycle (m), as
    :func:`run_block`'s. ``ranks``: the :class:`fewear.loop.joint_ranks.JointRanks` of a case
    whose joints are split among its ranks (``joints`` this rank's only), else None."""
    first = next(iter(joints.values()))
    loop = first.inputs.loop
    steps, starts, peaks, inner = {}, {}, {}, {name: [] for name in joints}
    for name, joint in joints.items():
        times = joint.case.stage_wall_time_s
        times["dynamics"] += dynamics_s
        joint.case.mechanism = mechanism
        starts[name], peaks[name] = joint.case.state, [0.0, 0.0]
        with timed(times, "contact"):
            steps[name] = load_steps(
                histories[name], loop.load_steps_per_cycle * loop.recorded_cycles_per_block,
                joint.inputs.joint.law, joint.inputs.impact_law)
    added = added_depth_per_cycle or {}
    previous = {name: None for name in joints}  # each joint's last (A_j, peak) in this block
    for step in range(loop.wear_steps_per_block):
        error, proposed, worn = None, {}, {}
        try:
            proposed = {name: joint_wear_step(joint, histories[name], steps[name],
                                              added.get(name), previous[name])
                        for name, joint in joints.items()}
            previous = {name: (proposal.cycles, float(proposal.increment_m.max()))
                        for name, proposal in proposed.items()}
        except FewearInputError as exc:
            if ranks is None:
                raise
            error = exc
        cycles = min([proposal.cycles for proposal in proposed.values()] or [0])
        if ranks is not None:
            cycles = min(ranks.agreed(cycles, error))
        try:
            worn = {name: proposal.worn_over(cycles, joints[name])
                    for name, proposal in proposed.items()}
        except FewearInputError as exc:
            if ranks is None:
                raise
            error = exc
        if ranks is not None:
            ranks.agreed(error=error)
        done = next(iter(worn.values())).cycles >= loop.total_cycles
        last = step == loop.wear_steps_per_block - 1 or done
        if last:
            worn = {name: replace(state, blocks=starts[name].blocks + 1)
                    for name, state in worn.items()}
            if start_next is not None and not done:
                start_next(worn)
        for name, joint in joints.items():
            with timed(joint.case.stage_wall_time_s, "mesh"):
                joint.bushing.move_to(worn[name], interior=last)
            joint.case.state = worn[name]
            joint.case.counts.dropped_steps += proposed[name].wear.dropped_steps
            peaks[name] = [max(peaks[name][0], float(proposed[name].wear.pressure_Pa.max())),
                           max(peaks[name][1], proposed[name].peak_rate_m)]
            if not last:
                inner[name].append(worn[name])
        if last:
            break
    for name, joint in joints.items():
        _record_block(joint, starts[name], histories[name], peaks[name], inner[name])


def _record_block(joint: JointRun, start: WearState, history, peaks, inner: list) -> None:
    """The mesh snapshot and the :class:`BlockRecord` of a joint's block from ``start``."""
    case, worn = joint.case, joint.case.state
    with timed(case.stage_wall_time_s, "mesh"):
        snapshot = joint.bushing.snapshot()
    case.node_ids, case.cells, case.meshed_xy_m = (snapshot.node_ids, snapshot.cells,
                                                   joint.bushing.meshed_xy_m)
    case.snapshots.append(snapshot.xy_m)
    case.records.append(BlockRecord(
        worn.cycles, worn.cycles - start.cycles, worn.depth_m.copy(),
        history.peak_contact_force_N, history.impacts, peaks[0], peaks[1],
        np.array([w.cycles for w in inner], dtype=int),
        np.array([w.depth_m for w in inner]).reshape(len(inner), worn.depth_m.size)))


@dataclass(frozen=True)
class WearProposal:
    """One joint's wear step as its own extrapolation chose it: ``cycles`` A_j, the depth
    ``increment_m`` and sliding state after them; ``per_cycle``: what one crank cycle does (to
    wear it over fewer cycles); ``wear``: the step's :class:`CycleWear`; ``peak_rate_m``: the
    largest depth per simulated cycle (m)."""

    state: WearState
    cycles: int
    increment_m: np.ndarray
    sliding: object
    per_cycle: CycleSliding
    wear: object
    peak_rate_m: float

    def worn_over(self, cycles: int, joint: JointRun) -> WearState:
        """The worn state after ``cycles`` <= ``self.cycles`` (its ``blocks`` count unchanged),
        checked against the bushing wall."""
        inputs, state = joint.inputs, self.state
        increment, sliding = self.increment_m, self.sliding
        if cycles != self.cycles:
            with timed(joint.case.stage_wall_time_s, "wear"):
                increment, sliding = smoothed_block_wear(
                    self.per_cycle, state, inputs.extension, cycles,
                    math.radians(inputs.loop.wear_smoothing_width_deg))
        worn = WearState(state.angle_rad, state.depth_m + increment, sliding,
                         state.cycles + cycles, state.blocks)
        geometry = inputs.contact.geometry
        try:
            worn.checked_against_wall(geometry.inner_radius_m, geometry.outer_radius_m,
                                      inputs.loop.max_wall_fraction)
        except FewearInputError as exc:
            raise FewearInputError(f"{joint.label}: {exc}") from None
        return worn


def joint_wear_step(joint: JointRun, history, steps, added_depth_per_cycle=None,
                    previous: tuple[int, float] | None = None) -> WearProposal:
    """Stages 2-4 of one wear step of a joint on the bore of its state: the contact at every load
    step of ``steps`` (cut from ``history``), Archard's law summed into one crank cycle, and the
    step's A_j cycles extrapolated (:func:`fewear.wear.extrapolation.extrapolate_block`, its
    search started from the ``previous`` step's (A_j, peak increment) of the block, if any: a
    block's steps depend only on the block, so a resumed run repeats them); the stage times
    added to the joint's."""
    inputs, bushing, state = joint.inputs, joint.bushing, joint.case.state
    loop, times = inputs.loop, joint.case.stage_wall_time_s
    with timed(times, "contact"):
        try:
            wear = cycle_wear(bushing, steps, inputs.wear_coefficient, loop.friction_in_contact,
                              implicit=loop.implicit_wear_step,
                              footprints=inputs.impact_law.wears_by_impacts)
        except ContactLoadError as exc:  # a force the model cannot carry, or no equilibrium
            raise FewearInputError(
                f"{joint.label}, block {state.blocks + 1} at {state.cycles:,} cycles: the FE "
                f"contact on the worn bore failed ({exc}); peak joint force "
                f"{history.peak_contact_force_N:.0f} N: a smaller [wear_loop] "
                "max_depth_increment_fraction (adaptive extrapolation) or a wider "
                "wear_smoothing_width_deg keeps the worn bore smoother") from None
    with timed(times, "wear"):
        per_cycle = cycle_sliding(wear, steps, loop.recorded_cycles_per_block,
                                  inputs.contact.contact.friction_coefficient,
                                  inputs.impact_law)
        if added_depth_per_cycle is not None:
            per_cycle = replace(per_cycle, impact_depth_m=per_cycle.impact_depth_m
                                + added_depth_per_cycle(history, state))
        cycles, increment, sliding = extrapolate_block(
            loop.extrapolation,
            lambda cycles: smoothed_block_wear(per_cycle, state, inputs.extension, cycles,
                                               math.radians(loop.wear_smoothing_width_deg)),
            bushing.element_height_m, loop.total_cycles - state.cycles, previous)
    return WearProposal(state, cycles, increment, sliding, per_cycle, wear,
                        float((per_cycle.depth_m + per_cycle.impact_depth_m).max()))


def new_case(bushing) -> CaseProgress:
    """An unworn case on the bushing's bore nodes, its first snapshot the unworn mesh; the case
    holds the counts the bushing adds to."""
    snapshot = bushing.snapshot()
    return CaseProgress(WearState.unworn(bushing.angles), snapshots=[snapshot.xy_m],
                        node_ids=snapshot.node_ids, cells=snapshot.cells,
                        meshed_xy_m=bushing.meshed_xy_m, counts=bushing.counts)


def new_bushing(inputs: RunInputs, comm, counts=None):
    """The unworn FE bushing of ``inputs`` (:class:`fewear.loop.bushing.WornBushing`) on
    ``comm``, adding to ``counts`` (None: counts of its own)."""
    from fewear.loop.bushing import WornBushing

    return WornBushing(inputs.contact, comm, counts,
                       compliance_update=inputs.loop.compliance_update)


def restored_bushing(inputs: RunInputs, case: CaseProgress, comm):
    """The FE bushing of ``case`` as its last block left it (a checkpoint's, or a case whose
    contact model changes between blocks), adding to the case's counts."""
    from fewear.mesh.snapshot import MeshSnapshot

    bushing = new_bushing(inputs, comm, case.counts)
    bushing.restore(case.meshed_xy_m,
                    MeshSnapshot(case.node_ids, case.snapshots[-1], case.cells))
    return bushing


def predict_joints(label: str, joints: dict, simulate_block, after_block, ranks=None) -> None:
    """Wear blocks of every joint of a case (joint name -> :class:`JointRun`, in step) until
    ``total_cycles``; ``after_block()`` runs after each (checkpoint, progress).
    ``simulate_block(states, mechanism)``: stage 1 for every joint's wear state (joint name ->
    :class:`WearState`) from the mechanism's last state, returning ((joint name -> history,
    summary, final state), wall time in s); it runs in a thread from the moment the previous
    block's wear is known, beside that block's mesh stage and ``after_block`` (the compiled
    dynamics release the interpreter lock; the dynamics depend only on the wear states and the
    mechanism's last state, so the result is the same). ``ranks``: a
    :class:`fewear.loop.joint_ranks.JointRanks` when the case's joints are split among its ranks
    (``joints`` this rank's only)."""
    first = next(iter(joints.values()))
    share = dict if ranks is None else ranks.all_states
    with ThreadPoolExecutor(max_workers=1, thread_name_prefix=f"fewear-{label}-dynamics") as ahead:
        following = None
        while first.case.state.cycles < first.inputs.loop.total_cycles:
            if following is None:
                following = ahead.submit(simulate_block, share(
                    {name: joint.case.state for name, joint in joints.items()}),
                    first.case.mechanism)
            (histories, _, mechanism), seconds = following.result()
            following = None

            def start_next(worn: dict, mechanism=mechanism) -> None:
                nonlocal following
                following = ahead.submit(simulate_block, share(worn), mechanism)

            wear_block(joints, histories, mechanism, seconds, start_next, ranks=ranks)
            after_block()
