"""One wear block of a rod model (stages 1-5 of the flowchart in :mod:`fewear.loop`), and the
blocks of a case until its total cycles."""

from __future__ import annotations

import math
import time
from concurrent.futures import Executor, Future, ThreadPoolExecutor
from dataclasses import replace

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


def block_dynamics(rod: str, inputs: RunInputs, state: WearState, mechanism):
    """Stage 1 of a block: the clearance-joint dynamics of ``rod`` on the worn clearance of
    ``state``, warm-started from ``mechanism`` (None: the ideal mechanism, settling
    ``[mechanism] settling_cycles``; else ``warm_settling_cycles``). Returns (the
    :func:`fewear.mbd.slider_crank.simulate` result, its wall time in s); a mechanism the
    integrator cannot carry is a :class:`FewearInputError` (run ahead in a thread, its future
    raises it when its block comes)."""
    from fewear.mbd.integrator import StepSizeCollapse
    from fewear.mbd.slider_crank import UNINTEGRABLE_HINT, simulate

    loop = inputs.loop
    crank = replace(inputs.dynamics.crank, rod=rod, joint="clearance",
                    recorded_cycles=loop.recorded_cycles_per_block,
                    settling_cycles=(inputs.dynamics.crank.settling_cycles
                                     if mechanism is None else loop.warm_settling_cycles))
    geometry = inputs.contact.geometry
    joint = replace(inputs.dynamics.joint,
                    profile=state.clearance_profile(geometry.inner_radius_m,
                                                    geometry.pin_radius_m))
    start = time.perf_counter()
    try:
        result = simulate(replace(inputs.dynamics, crank=crank, joint=joint), start=mechanism)
    except StepSizeCollapse as exc:
        clearance_m = geometry.inner_radius_m - geometry.pin_radius_m
        if any(delta > clearance_m for delta, _, _ in exc.joints):
            why = (f"the pin was pushed deeper into the bore than the joint's radial clearance "
                   f"({clearance_m * 1e3:g} mm): the mechanism jammed it into its worn pocket, "
                   "beyond the small elastic deformation the contact law describes; the wear "
                   "cannot be predicted past this bore")
        else:
            why = ("a smaller [integrator] min_step_s (1e-11 s carried the undamped rod through "
                   "a block where its Newton iterates cycled across the friction law's kink), a "
                   "larger gap_tolerance_m or a wider [wear_loop] wear_smoothing_width_deg may "
                   "get past it" + ("" if state.blocks else f"; on the unworn clearance, "
                                    f"{UNINTEGRABLE_HINT}"))
        raise FewearInputError(
            f"{rod} rod, block {state.blocks + 1} at {state.cycles:,} cycles: the dynamics "
            f"on the worn clearance failed ({exc}): {why}") from None
    return result, time.perf_counter() - start


def run_block(rod: str, inputs: RunInputs, bushing, case: CaseProgress,
              added_depth_per_cycle=None, dynamics: Future | None = None,
              ahead: Executor | None = None) -> Future | None:
    """One wear block of ``case``, updating it in place: stage 1 (the dynamics on the worn
    clearance), then ``[wear_loop] wear_steps_per_block`` wear steps (stages 2-5,
    :func:`wear_step`) on its recorded cycles, each with the contact solved on the bore the
    previous step left. The contact and wear respond to the bore within tens of crank cycles
    (a stiff process: :func:`fewear.wear.archard.block_wear`), the joint's dynamics to the
    clearance far more slowly; wear steps shorter than the dynamics' block buy accuracy at the
    price of contact solves, not of dynamics. ``added_depth_per_cycle`` (history, state) ->
    depth per cycle (m, per bore node), optional: a wear source of another law added to each
    step's impact wear (a given source of the step, like it).

    ``dynamics``: this block's stage 1 already under way (the future of :func:`block_dynamics`,
    as returned by the previous block), else it runs here. ``ahead``: an executor on which the
    next block's stage 1 is started as soon as this block's last wear step is known, beside its
    mesh stage; its future is returned (None without ``ahead`` or after the last block). The
    dynamics depend only on the wear state and the mechanism's last state, so the result is the
    same either way."""
    loop, times = inputs.loop, case.stage_wall_time_s
    start = case.state
    if dynamics is None:
        (history, _, case.mechanism), seconds = block_dynamics(rod, inputs, start,
                                                                case.mechanism)
    else:
        (history, _, case.mechanism), seconds = dynamics.result()
    times["dynamics"] += seconds
    with timed(times, "contact"):
        steps = load_steps(history, loop.load_steps_per_cycle * loop.recorded_cycles_per_block,
                           inputs.dynamics.joint.law, inputs.impact_law)
    following, peak_pressure, peak_rate, inner = None, 0.0, 0.0, []
    for step in range(loop.wear_steps_per_block):
        worn, wear, rate = wear_step(rod, inputs, bushing, case.state, history, steps, times,
                                     added_depth_per_cycle)
        last = step == loop.wear_steps_per_block - 1 or worn.cycles >= loop.total_cycles
        if last:
            worn = replace(worn, blocks=start.blocks + 1)
            if ahead is not None and worn.cycles < loop.total_cycles:
                following = ahead.submit(block_dynamics, rod, inputs, worn, case.mechanism)
        with timed(times, "mesh"):
            bushing.move_to(worn)
        case.state = worn
        case.counts.dropped_steps += wear.dropped_steps
        peak_pressure = max(peak_pressure, float(wear.pressure_Pa.max()))
        peak_rate = max(peak_rate, rate)
        if last:
            break
        inner.append(worn)
    with timed(times, "mesh"):
        snapshot = bushing.snapshot()
    case.node_ids, case.cells, case.meshed_xy_m = (snapshot.node_ids, snapshot.cells,
                                                   bushing.meshed_xy_m)
    case.snapshots.append(snapshot.xy_m)
    case.records.append(BlockRecord(
        worn.cycles, worn.cycles - start.cycles, worn.depth_m.copy(),
        history.peak_contact_force_N, history.impacts, peak_pressure, peak_rate,
        np.array([w.cycles for w in inner], dtype=int),
        np.array([w.depth_m for w in inner]).reshape(len(inner), worn.depth_m.size)))
    return following


def wear_step(rod: str, inputs: RunInputs, bushing, state: WearState, history, steps,
              times: dict, added_depth_per_cycle=None):
    """Stages 2-4 of one wear step on the bore of ``state``: the contact at every load step of
    ``steps`` (cut from ``history``), Archard's law summed into one crank cycle, and the step's
    A_j cycles extrapolated (:func:`fewear.wear.extrapolation.extrapolate_block`). Returns (the
    worn state, its ``blocks`` count unchanged; the :class:`CycleWear`; the largest depth per
    simulated cycle, m), the stage times added to ``times``."""
    loop = inputs.loop
    with timed(times, "contact"):
        try:
            wear = cycle_wear(bushing, steps, inputs.wear_coefficient, loop.friction_in_contact,
                              implicit=loop.implicit_wear_step,
                              footprints=inputs.impact_law.wears_by_impacts)
        except ContactLoadError as exc:  # a force the model cannot carry, or no equilibrium
            raise FewearInputError(
                f"{rod} rod, block {state.blocks + 1} at {state.cycles:,} cycles: the FE contact "
                f"on the worn bore failed ({exc}); peak joint force "
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
            bushing.element_height_m, loop.total_cycles - state.cycles)
        worn = WearState(state.angle_rad, state.depth_m + increment, sliding,
                         state.cycles + cycles, state.blocks)
        geometry = inputs.contact.geometry
        worn.checked_against_wall(geometry.inner_radius_m, geometry.outer_radius_m,
                                  loop.max_wall_fraction)
    return worn, wear, float((per_cycle.depth_m + per_cycle.impact_depth_m).max())


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


def predict_case(rod: str, inputs: RunInputs, bushing, case: CaseProgress, after_block) -> None:
    """Wear blocks until ``total_cycles``; ``after_block(case)`` runs after each (checkpoint,
    progress). Each block's dynamics runs in a thread from the moment the previous block's wear
    is known, beside that block's mesh stage and ``after_block`` (:func:`run_block`; the compiled
    dynamics release the interpreter lock): on a free core the mesh stage costs no wall time.
    Stage times then overlap."""
    with ThreadPoolExecutor(max_workers=1, thread_name_prefix=f"fewear-{rod}-dynamics") as ahead:
        following = None
        while case.state.cycles < inputs.loop.total_cycles:
            following = run_block(rod, inputs, bushing, case, dynamics=following, ahead=ahead)
            after_block(case)
