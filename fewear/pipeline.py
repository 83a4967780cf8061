"""The wear prediction of the seed paper (Zhao, Zhang & Dai 2013, Fig. 3), block by block.

``fewear run`` follows the flowchart for each connecting-rod model (rigid, flexible). Every wear
block j:

1. **Dynamics** (:mod:`fewear.mbd`): the slider-crank with the revolute clearance joint on the worn
   clearance c(theta) = c0 + h(theta) of the wear state; the first block settles from the ideal
   mechanism, later ones start from the previous block's final state (a warm start: the orbit
   only adapts to the slightly larger clearance). Then ``recorded_cycles_per_block`` crank cycles
   are recorded: the joint reaction and the pin's rotation relative to the bushing.
2. **Load steps**: each recorded cycle cut into n steps (seed: 200); each step carries the joint
   force at its middle and the relative rotation accumulated over it.
3. **Contact** (:mod:`fewear.contact`): the FE bushing on the worn bore (Q8, outer surface clamped,
   rigid pin on a pilot point) under each step's force: nodal pressures p and slips s.
4. **Wear** (:mod:`fewear.wear`): Archard's law with k(p, v) (seed eq. 9-10) and the wear law's
   history multiplier, per node, averaged over the recorded cycles; the block extrapolates it over
   A_j real cycles (fixed, or adaptive: bounded depth increment per block). Optionally impacts
   wear too: ``[wear] impact_wear_coefficient_m3_J`` k_imp > 0 adds k_imp times each step's
   hysteresis work of the contact law, spread in proportion to the step's pressure
   (:mod:`fewear.wear.impact`; default 0, none).
5. **Geometry update**: the bore nodes move by the block's depth increment, the mesh follows (ALE)
   or is re-meshed from the worn bore, and the contact operator is rebuilt: the next block runs
   on the worn joint.

The worn bore has one source, :class:`fewear.wear.state.WearState`; the dynamics' clearance and the
mesh's bore are both derived from it. A checkpoint is written after every block
(:mod:`fewear.io.checkpoint`): ``--resume`` continues an interrupted run to the same result.
"""

from __future__ import annotations

import math
import sys
import time
from contextlib import contextmanager
from dataclasses import dataclass, field, replace

import numpy as np
from scipy.integrate import cumulative_trapezoid

from fewear.contact.admissible import ContactLoadError
from fewear.errors import FewearInputError
from fewear.mbd.history import JointHistory
from fewear.wear.archard import (
    CycleSliding,
    block_wear,
    cycle_wear_depth_m,
    smoothed_periodic,
)
from fewear.wear.extrapolation import ExtrapolationSettings, extrapolate_block
from fewear.wear.impact import hysteresis_work_J, impact_impulse_N_s, impact_wear_depth_m
from fewear.wear.state import WearState

RUN_SECTIONS = ["wear_loop", "wear"]
STAGES = ("dynamics", "contact", "wear", "mesh")
DROPPABLE_SHARE = 0.01
"""Load steps that find no contact equilibrium on a worn bore are dropped (counted, no wear)
while together they carry at most this share of the cycle's load-slip product; beyond it the
run stops with an error."""


@dataclass(frozen=True)
class WearLoopSettings:
    """The ``[wear_loop]`` section (seed section 5 values by default)."""

    rod_models: tuple[str, ...]
    load_steps_per_cycle: int
    total_cycles: int
    friction_in_contact: bool
    extrapolation: ExtrapolationSettings
    recorded_cycles_per_block: int
    warm_settling_cycles: int
    max_wall_fraction: float
    implicit_wear_step: bool
    wear_smoothing_width_deg: float

    def __post_init__(self):
        unknown = [rod for rod in self.rod_models if rod not in ("rigid", "flexible")]
        if unknown or not self.rod_models or len(set(self.rod_models)) != len(self.rod_models):
            raise FewearInputError(
                f"[wear_loop] rod_models = {list(self.rod_models)!r}: expected a non-empty list of "
                "'rigid' and/or 'flexible', each once")
        if self.load_steps_per_cycle < 2:
            raise FewearInputError(
                f"[wear_loop] load_steps_per_cycle = {self.load_steps_per_cycle}: expected >= 2")
        if self.total_cycles < 1:
            raise FewearInputError(f"[wear_loop] total_cycles = {self.total_cycles}: expected >= 1")
        if self.recorded_cycles_per_block < 1 or self.warm_settling_cycles < 0:
            raise FewearInputError(
                f"[wear_loop] recorded_cycles_per_block = {self.recorded_cycles_per_block}, "
                f"warm_settling_cycles = {self.warm_settling_cycles}: expected >= 1 and >= 0")
        if not 0.0 < self.max_wall_fraction < 1.0:
            raise FewearInputError(
                f"[wear_loop] max_wall_fraction = {self.max_wall_fraction}: expected a fraction "
                "of the bushing wall in (0, 1)")

    @classmethod
    def from_config(cls, section: dict) -> WearLoopSettings:
        values = dict(section)
        extrapolation = ExtrapolationSettings(
            mode=values.pop("extrapolation"), factor=values.pop("extrapolation_factor"),
            max_factor=values.pop("max_extrapolation_factor"),
            max_depth_increment_fraction=values.pop("max_depth_increment_fraction"))
        return cls(**{**values, "rod_models": tuple(values["rod_models"]),
                      "extrapolation": extrapolation})


@dataclass(frozen=True)
class RunInputs:
    """Everything ``fewear run`` needs, parsed once from the config at the command's edge."""

    dynamics: object  # fewear.mbd.slider_crank.DynamicsInputs
    contact: object  # fewear.contact.params.ContactProblem
    wear_coefficient: object  # k(p, v), fewear.wear.coefficient
    extension: object  # the wear law's history multiplier, fewear.wear.extensions
    loop: WearLoopSettings
    impact_wear_coefficient_m3_J: float = 0.0  # k_imp, fewear.wear.impact
    impact_impulse_wear_coefficient_m3_Ns: float = 0.0  # c_J, fewear.wear.impact


def run_sections() -> list[str]:
    from fewear.contact.params import CONFIG_SECTIONS
    from fewear.mbd.slider_crank import SECTIONS as DYNAMICS_SECTIONS

    return list(dict.fromkeys([*RUN_SECTIONS, *CONFIG_SECTIONS, *DYNAMICS_SECTIONS]))


def run_inputs_from_config(config: dict) -> RunInputs:
    from fewear.contact.params import contact_problem_from_config
    from fewear.mbd.slider_crank import dynamics_inputs_from_config
    from fewear.wear.coefficient import wear_coefficient_from_config
    from fewear.wear.extensions import wear_extension_from_config
    from fewear.wear.impact import (
        impact_impulse_wear_coefficient_from_config,
        impact_wear_coefficient_from_config,
    )

    return RunInputs(dynamics_inputs_from_config(config), contact_problem_from_config(config),
                     wear_coefficient_from_config(config["wear"]),
                     wear_extension_from_config(config["wear"]),
                     WearLoopSettings.from_config(config["wear_loop"]),
                     impact_wear_coefficient_from_config(config["wear"]),
                     impact_impulse_wear_coefficient_from_config(config["wear"]))


@dataclass(frozen=True)
class LoadSteps:
    """The load steps of the recorded cycles (bushing frame).

    ``force_N`` (n, 2): joint force ON the pin pushing it into the bore (minus the bushing's
    reaction on the pin), the mean over each step; ``rotation_rad`` (n,): rotation of the pin
    relative to the bushing over the step; ``duration_s``: the length of one step;
    ``hysteresis_work_J`` (n,): the work W_i the contact law's hysteresis dissipates over the step
    (:func:`fewear.wear.impact.hysteresis_work_J`); ``impact_impulse_N_s`` (n,): the normal
    impulse J_i of the impacts within the step (:func:`fewear.wear.impact.impact_impulse_N_s`).
    """

    time_s: np.ndarray
    force_N: np.ndarray
    rotation_rad: np.ndarray
    duration_s: float
    hysteresis_work_J: np.ndarray
    impact_impulse_N_s: np.ndarray


@dataclass(frozen=True)
class CycleWear:
    """Contact and wear of the recorded cycles on the bore nodes (sorted by angle).

    ``pressure_Pa``, ``slip_m``, ``k_m2_N``: (n_steps, n_nodes); ``depth_per_cycle_m`` (n_nodes,):
    plain Archard depth summed over all the steps; ``depth_sensitivity`` (n_nodes, n_nodes) its
    derivative with respect to the bore's wear depth, or None; ``dropped_steps``: steps
    that found no contact equilibrium on the worn bore, dropped within ``DROPPABLE_SHARE``.
    """

    angle_rad: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    pressure_Pa: np.ndarray
    slip_m: np.ndarray
    k_m2_N: np.ndarray
    depth_per_cycle_m: np.ndarray
    depth_sensitivity: np.ndarray | None = None
    dropped_steps: int = 0


def load_steps(history: JointHistory, n_steps: int, law=None) -> LoadSteps:
    """Cut the recorded history into ``n_steps`` equal steps (stage 2).

    The force of a step is its mean over the step, the impulse over the step's length (the seed
    samples it at one instant: an impact peak lasting microseconds is then hit or missed by the
    sample, and the maximum depth after 10,000 cycles moved by 20 % between n = 200 and 400).
    Archard's worn volume of a step, k |F| s, is linear in the force, so the mean keeps it for a
    steady slip rate whatever n. The relative rotation is the integral of ``rel_omega_rad_s``
    over the step, the hysteresis work W_i that of the dissipated power of ``law`` (the
    clearance joint's :class:`fewear.mbd.contact.ContactLaw`; None: no work and no impacts, as
    for the ideal joint) and the impact impulse J_i that of F_n over the impacts. All four
    integrals are trapezoidal on the history, interpolated linearly at the step edges.
    """
    t = history.time_s
    edges = np.linspace(t[0], t[-1], n_steps + 1)
    middles = 0.5 * (edges[1:] + edges[:-1])
    duration = float(edges[1] - edges[0])
    impulse = cumulative_trapezoid(-history.reaction_force_N, t, axis=0, initial=0.0)  # ON pin
    force = np.diff(np.column_stack([np.interp(edges, t, impulse[:, i]) for i in range(2)]),
                    axis=0) / duration
    rotation = np.diff(np.interp(edges, t, cumulative_trapezoid(history.rel_omega_rad_s, t,
                                                                initial=0.0)))
    work = impulse = np.zeros(n_steps)
    if law is not None:
        work = np.diff(np.interp(
            edges, t, hysteresis_work_J(law, history.penetration_m, history.normal_force_N)))
        impulse = np.diff(np.interp(
            edges, t, impact_impulse_N_s(t, history.normal_force_N, history.mode)))
    return LoadSteps(middles, force, rotation, duration, work, impulse)


def cycle_wear(contact_model, steps: LoadSteps, wear_coefficient, friction: bool,
               implicit: bool = False) -> CycleWear:
    """Stages 3 and 4: contact at every load step, then Archard's law summed over the steps.

    ``implicit``: also sum the steps' sensitivities k s dp/dh (``contact_model`` must offer
    ``pressure_sensitivity(result)``, as :class:`fewear.contact.worn_bushing.WornBushing` does)
    for the linearly implicit block step of :func:`fewear.wear.archard.block_wear`.
    """
    results = _solve_steps(contact_model, steps, friction)
    solved = next(r for r in results if r is not None)  # the heaviest step is never dropped
    dropped = sum(r is None for r in results)
    empty = replace(solved, pressure_Pa=np.zeros_like(solved.pressure_Pa),
                    slip_m=np.zeros_like(solved.slip_m))
    results = [empty if r is None else r for r in results]
    pressure = np.array([r.pressure_Pa for r in results])
    slip = np.array([r.slip_m for r in results])
    speed = slip / steps.duration_s
    k = np.where(slip > 0.0, wear_coefficient(pressure, np.maximum(speed, 1e-300)), 0.0)
    sensitivity = None
    if implicit:
        sensitivity = np.zeros((pressure.shape[1], pressure.shape[1]))
        for result, k_step, slip_step in zip(results, k, slip):
            if np.any(slip_step > 0.0) and np.any(result.pressure_Pa > 0.0):
                active, J = contact_model.pressure_sensitivity(result)
                sensitivity[np.ix_(active, active)] += (k_step * slip_step)[active, None] * J
    return CycleWear(solved.angle_rad, solved.x_m, solved.y_m, pressure, slip, k,
                     cycle_wear_depth_m(k, pressure, slip), sensitivity, dropped)


def _solve_steps(contact_model, steps: LoadSteps, friction: bool) -> list:
    """The contact of every load step; None for a step that finds no equilibrium on the worn
    bore while the steps dropped so far carry at most ``DROPPABLE_SHARE`` of the cycle's
    sum of |F| |rotation| (the load-slip product Archard's wear grows with)."""
    load_slip = np.linalg.norm(steps.force_N, axis=1) * np.abs(steps.rotation_rad)
    allowance = DROPPABLE_SHARE * load_slip.sum()
    results = []
    for force, rotation, share in zip(steps.force_N, steps.rotation_rad, load_slip):
        try:
            results.append(contact_model.solve(force, rotation, friction=friction))
        except ContactLoadError:
            if share > allowance:
                raise
            allowance -= share
            results.append(None)
    return results


def cycle_sliding(wear: CycleWear, steps: LoadSteps, cycles: int, friction_coefficient: float,
                  impact_wear_coefficient_m3_J: float = 0.0,
                  impact_impulse_wear_coefficient_m3_Ns: float = 0.0) -> CycleSliding:
    """What one crank cycle does at each node, averaged over the ``cycles`` recorded cycles:
    Archard depth, sliding distance, time in sliding contact, mean frictional power mu p v, the
    depth's sensitivity to the wear, and the impact wear depth of k_imp =
    ``impact_wear_coefficient_m3_J`` on the hysteresis work plus c_J =
    ``impact_impulse_wear_coefficient_m3_Ns`` on the impact impulse
    (:func:`fewear.wear.impact.impact_wear_depth_m`)."""
    sliding = wear.slip_m > 0.0
    distance = wear.slip_m.sum(axis=0) / cycles
    time_s = steps.duration_s * sliding.sum(axis=0) / cycles
    energy = friction_coefficient * (wear.pressure_Pa * wear.slip_m).sum(axis=0) / cycles
    power = np.divide(energy, time_s, out=np.zeros_like(energy), where=time_s > 0.0)
    sensitivity = None if wear.depth_sensitivity is None else wear.depth_sensitivity / cycles
    impact_volume_m3 = (impact_wear_coefficient_m3_J * steps.hysteresis_work_J
                        + impact_impulse_wear_coefficient_m3_Ns * steps.impact_impulse_N_s)
    impact = impact_wear_depth_m(1.0, impact_volume_m3, steps.force_N, wear.pressure_Pa) / cycles
    return CycleSliding(wear.depth_per_cycle_m / cycles, distance, time_s, power, sensitivity,
                        impact)


@dataclass(frozen=True)
class BlockRecord:
    """One wear block: cycles at its end, its A_j, the depth profile after it (at the state's
    node angles), and what its simulated cycles saw (the depth per cycle: Archard's plus the
    impacts')."""

    cycles: int
    block_cycles: int
    depth_m: np.ndarray
    peak_contact_force_N: float
    impacts: int
    max_contact_pressure_Pa: float
    max_depth_per_cycle_m: float


@dataclass
class CaseProgress:
    """A rod model's run so far: what a checkpoint stores and the outputs are written from."""

    state: WearState
    mechanism: object = None  # fewear.mbd.slider_crank.MechanismState of the last block
    records: list[BlockRecord] = field(default_factory=list)
    snapshots: list[np.ndarray] = field(default_factory=list)  # mesh node coordinates per block
    node_ids: np.ndarray | None = None
    cells: np.ndarray | None = None
    meshed_xy_m: np.ndarray | None = None  # the current mesh's nodes as made (motion reference)
    ale_moves: int = 0
    remeshes: int = 0
    contact_retries: int = 0  # load steps solved again from a cold start
    frictionless_steps: int = 0  # load steps solved without the Coulomb traction
    dropped_steps: int = 0  # load steps without contact equilibrium, dropped (no wear)
    stage_wall_time_s: dict = field(default_factory=lambda: dict.fromkeys(STAGES, 0.0))

    @property
    def wall_time_s(self) -> float:
        return float(sum(self.stage_wall_time_s.values()))


@contextmanager
def timed(times: dict, stage: str):
    """Add the wall time of the ``with`` block to ``times[stage]`` (s)."""
    start = time.perf_counter()
    try:
        yield
    finally:
        times[stage] += time.perf_counter() - start


def smoothed_block_wear(per_cycle: CycleSliding, state: WearState, extension, cycles: int,
                        width_rad: float):
    """:func:`block_wear` with the depth increment smoothed around the bore by a Gaussian of
    standard deviation ``width_rad`` (volume kept; :func:`smoothed_periodic`): the dwell points of
    the few recorded cycles stand for an orbit that varies from cycle to cycle over the A_j cycles
    of the block, and the bore's contact does not resolve ripples shorter than a few elements.
    The wear law's history starts from the crank cycles the wear state has run (their one
    owner)."""
    increment, sliding = block_wear(per_cycle, replace(state.sliding, cycles=float(state.cycles)),
                                    extension, cycles)
    step = 2.0 * math.pi / state.angle_rad.size
    # the FFT convolution leaves rounding noise (~1e-21 m) where nothing wears: clip it
    return np.maximum(smoothed_periodic(increment, step, width_rad), 0.0), sliding


def run_block(rod: str, inputs: RunInputs, bushing, case: CaseProgress,
              added_depth_per_cycle=None) -> None:
    """One wear block of ``case`` (stages 1-5), updating it in place. ``added_depth_per_cycle``
    (history, state) -> depth per cycle (m, per bore node), optional: a wear source of another
    law added to the block's impact wear (a given source of the block step, like it)."""
    from fewear.mbd.slider_crank import simulate

    loop, times = inputs.loop, case.stage_wall_time_s
    state = case.state
    crank = replace(inputs.dynamics.crank, rod=rod, joint="clearance",
                    recorded_cycles=loop.recorded_cycles_per_block,
                    settling_cycles=(inputs.dynamics.crank.settling_cycles
                                     if case.mechanism is None else loop.warm_settling_cycles))
    joint = replace(inputs.dynamics.joint,
                    profile=state.clearance_profile(inputs.contact.geometry.inner_radius_m,
                                                    inputs.contact.geometry.pin_radius_m))
    with timed(times, "dynamics"):
        try:
            history, _, case.mechanism = simulate(
                replace(inputs.dynamics, crank=crank, joint=joint), start=case.mechanism)
        except RuntimeError as exc:  # the integrator's step size collapsed
            raise FewearInputError(
                f"{rod} rod, block {state.blocks + 1} at {state.cycles:,} cycles: the dynamics "
                f"on the worn clearance failed ({exc}). The checkpoint holds the blocks done: a "
                "smaller [integrator] min_step_s, a larger gap_tolerance_m or a wider [wear_loop] "
                "wear_smoothing_width_deg may get past it") from None
    with timed(times, "contact"):
        steps = load_steps(history, loop.load_steps_per_cycle * loop.recorded_cycles_per_block,
                           inputs.dynamics.joint.law)
        try:
            wear = cycle_wear(bushing, steps, inputs.wear_coefficient, loop.friction_in_contact,
                              implicit=loop.implicit_wear_step)
        except ContactLoadError as exc:  # a force the model cannot carry, or no equilibrium
            raise FewearInputError(
                f"{rod} rod, block {state.blocks + 1} at {state.cycles:,} cycles: the FE contact "
                f"on the worn bore failed ({exc}); peak joint force "
                f"{history.peak_contact_force_N:.0f} N. The checkpoint holds the blocks done: "
                "a smaller [wear_loop] max_depth_increment_fraction (adaptive extrapolation) or "
                "a wider wear_smoothing_width_deg keeps the worn bore smoother") from None
    with timed(times, "wear"):
        per_cycle = cycle_sliding(wear, steps, loop.recorded_cycles_per_block,
                                  inputs.contact.contact.friction_coefficient,
                                  inputs.impact_wear_coefficient_m3_J,
                                  inputs.impact_impulse_wear_coefficient_m3_Ns)
        if added_depth_per_cycle is not None:
            per_cycle = replace(per_cycle, impact_depth_m=per_cycle.impact_depth_m
                                + added_depth_per_cycle(history, state))
        cycles, increment, sliding = extrapolate_block(
            loop.extrapolation,
            lambda cycles: smoothed_block_wear(per_cycle, state, inputs.extension, cycles,
                                               math.radians(loop.wear_smoothing_width_deg)),
            bushing.element_height_m, loop.total_cycles - state.cycles)
        worn = WearState(state.angle_rad, state.depth_m + increment, sliding,
                         state.cycles + cycles, state.blocks + 1)
        geometry = inputs.contact.geometry
        worn.checked_against_wall(geometry.inner_radius_m, geometry.outer_radius_m,
                                  loop.max_wall_fraction)
    with timed(times, "mesh"):
        bushing.apply_wear(worn, increment)
        snapshot = bushing.snapshot()
    case.state = worn
    case.node_ids, case.cells, case.meshed_xy_m = (snapshot.node_ids, snapshot.cells,
                                                   bushing.meshed_xy_m)
    case.snapshots.append(snapshot.xy_m)
    case.ale_moves, case.remeshes = bushing.ale_moves, bushing.remeshes
    case.contact_retries += bushing.cold_retries
    case.frictionless_steps += bushing.frictionless_steps
    case.dropped_steps += wear.dropped_steps
    bushing.cold_retries = bushing.frictionless_steps = 0
    case.records.append(BlockRecord(
        worn.cycles, cycles, worn.depth_m.copy(), history.peak_contact_force_N, history.impacts,
        float(wear.pressure_Pa.max()),
        float((per_cycle.depth_m + per_cycle.impact_depth_m).max())))


def new_case(bushing) -> CaseProgress:
    """An unworn case on the bushing's bore nodes, its first snapshot the unworn mesh."""
    snapshot = bushing.snapshot()
    return CaseProgress(WearState.unworn(bushing.angles), snapshots=[snapshot.xy_m],
                        node_ids=snapshot.node_ids, cells=snapshot.cells,
                        meshed_xy_m=bushing.meshed_xy_m)


def predict_case(rod: str, inputs: RunInputs, bushing, case: CaseProgress, after_block) -> None:
    """Wear blocks until ``total_cycles``; ``after_block(case)`` runs after each (checkpoint,
    progress)."""
    while case.state.cycles < inputs.loop.total_cycles:
        run_block(rod, inputs, bushing, case)
        after_block(case)


def case_summary(case: CaseProgress, inputs: RunInputs) -> dict:
    """The numbers of one rod model for ``summary.json``."""
    state, geometry = case.state, inputs.contact.geometry
    peak = int(np.argmax(state.depth_m))
    first = case.records[0]
    return {
        "max_wear_depth_m": float(state.depth_m[peak]),
        "max_wear_angle_deg": float(np.degrees(state.angle_rad[peak])),
        "worn_volume_m3": geometry.width_m * state.worn_area_m2(geometry.inner_radius_m),
        "cycles": int(state.cycles),
        "blocks": int(state.blocks),
        "ale_moves": int(case.ale_moves),
        "remeshes": int(case.remeshes),
        "contact_cold_retries": int(case.contact_retries),
        "contact_frictionless_steps": int(case.frictionless_steps),
        "contact_dropped_steps": int(case.dropped_steps),
        "first_block": {"cycles": first.block_cycles,
                        "max_wear_depth_per_cycle_m": first.max_depth_per_cycle_m,
                        "peak_contact_force_N": first.peak_contact_force_N,
                        "impacts": first.impacts,
                        "max_contact_pressure_Pa": first.max_contact_pressure_Pa},
        "last_block": {"cycles": case.records[-1].block_cycles,
                       "max_wear_depth_per_cycle_m": case.records[-1].max_depth_per_cycle_m,
                       "max_contact_pressure_Pa": case.records[-1].max_contact_pressure_Pa},
        "wall_time_s": case.wall_time_s,
        "stage_wall_time_s": dict(case.stage_wall_time_s),
    }


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

    from fewear.contact.worn_bushing import WornBushing
    from fewear.io import checkpoint
    from fewear.io.config import load_config
    from fewear.io.output import staged_output
    from fewear.mesh.snapshot import MeshSnapshot

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
            bushing = WornBushing(inputs.contact, comm)
            if case is None:
                case = cases[rod] = new_case(bushing)
            else:
                bushing.restore(case.meshed_xy_m,
                                MeshSnapshot(case.node_ids, case.snapshots[-1], case.cells),
                                case.ale_moves, case.remeshes)

            def after_block(case, rod=rod, index=index):
                store.save(cases)
                progress.block(rod, index, case, index)

            predict_case(rod, inputs, bushing, case, after_block)
        if comm.rank == 0:
            from fewear.io.run_output import write_run_outputs

            write_run_outputs(stage, cases, inputs, config)
    progress.message(f"done: {args.out}")
    return 0
