"""Forward runs of the wear loop for the joint diagnosis: the worn bore against cycles.

A run is ``fewear run``'s wear loop (:func:`fewear.loop.block.predict_joints`) for one rod model of
a complete config (a model the user believes, or one with a cause switched on), without checkpoint
or outputs. Its result, a
:class:`WearHistory`, holds the depth at the bore nodes after every wear step (a block's dynamics
serve ``wear_steps_per_block`` of them); between steps the depth is interpolated linearly in cycles
(the steps bound the depth increment, so this is the loop's own resolution). Runs are memoised by
their config: a diagnosis asks for the same candidate runs many times, and diagnoses of several
data sets against one model share them.
"""

from __future__ import annotations

import copy
import json
import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError
from fewear.mesh.profile import periodic_linear
from fewear.wear import impact

_RUNS: dict[str, WearHistory] = {}
_IMPACT_MEASURES: dict[str, dict[str, float]] = {}
PROGRESS_INTERVAL_S = 10.0
"""A long forward run reports its progress on stderr at most this often."""
DEPTH_REACH = 3.0
"""A candidate run stops once it is this many times deeper than the deepest measured wear."""


@dataclass(frozen=True, eq=False)
class WearHistory:
    """The simulated worn bore after every wear step: ``cycles`` (m + 1,) from 0, ``depth_m``
    (m + 1, n) at the node angles ``angle_rad`` (n,); ``sliding_m_per_cycle`` (n,): each node's
    mean sliding distance per crank cycle; ``stopped``: why the run ended early ('' if not)."""

    angle_rad: np.ndarray
    cycles: np.ndarray
    depth_m: np.ndarray
    sliding_m_per_cycle: np.ndarray
    stopped: str = ""
    wall_time_s: float = 0.0

    def nodal_depth_m(self, cycles: float) -> np.ndarray:
        """Depth at the nodes after ``cycles`` (linear between wear steps; beyond the last one
        extrapolated with its rate)."""
        return self.nodal_depths_m(np.array([float(cycles)]))[0]

    def nodal_depths_m(self, cycles: np.ndarray) -> np.ndarray:
        """:meth:`nodal_depth_m` after each of ``cycles`` (m,): (m, n)."""
        return self.nodal_depth_each_m(np.asarray(cycles, dtype=float)[:, None])

    def nodal_depth_each_m(self, cycles: np.ndarray) -> np.ndarray:
        """Depth at each node after its own cycle count: ``cycles`` (n,), or (m, n) for m
        counts at once (a column (m, 1): the same count at every node), as
        :meth:`nodal_depth_m` node by node."""
        k = np.minimum(np.maximum(np.searchsorted(self.cycles, cycles) - 1, 0),
                       self.cycles.size - 2)
        weight = (cycles - self.cycles[k]) / (self.cycles[k + 1] - self.cycles[k])
        nodes = np.arange(self.angle_rad.size)
        return np.maximum((1.0 - weight) * self.depth_m[k, nodes]
                          + weight * self.depth_m[k + 1, nodes], 0.0)

    def depth_at(self, cycles: float, angle_rad: np.ndarray) -> np.ndarray:
        """Depth at any angles (periodic linear between the nodes) after ``cycles``."""
        return periodic_linear(self.angle_rad, self.nodal_depth_m(cycles))(angle_rad)


def model_config(config: dict, rod: str, total_cycles: int) -> dict:
    """``config`` set to run ``rod`` alone for ``total_cycles``."""
    changed = copy.deepcopy(config)
    changed["wear_loop"]["rod_models"] = [rod]
    changed["wear_loop"]["total_cycles"] = int(total_cycles)
    return changed


def started_later(config: dict, offset_deg: float) -> dict:
    """``config`` with its crank starting ``offset_deg`` later: another realization of a model
    whose impacting orbit differs from cycle to cycle."""
    changed = copy.deepcopy(config)
    changed["mechanism"]["initial_crank_angle_deg"] += offset_deg
    return changed


def with_halved_wear_steps(config: dict) -> dict:
    """``config`` with its wear steps halved: the fixed extrapolation factor A, or the adaptive
    A_max and depth-increment fraction f (:mod:`fewear.wear.extrapolation`), and twice the wear
    steps per dynamics block up to :data:`BLOCK_WEAR_STEPS` (the block's length in cycles
    kept)."""
    changed = copy.deepcopy(config)
    loop = changed["wear_loop"]
    if loop["extrapolation"] == "fixed":
        loop["extrapolation_factor"] = max(loop["extrapolation_factor"] / 2.0, 1.0)
    else:
        loop["max_extrapolation_factor"] = max(loop["max_extrapolation_factor"] / 2.0, 1.0)
        loop["max_depth_increment_fraction"] /= 2.0
    loop["wear_steps_per_block"] = max(loop["wear_steps_per_block"],
                                       min(2 * loop["wear_steps_per_block"], BLOCK_WEAR_STEPS))
    return changed


BLOCK_WEAR_STEPS = 8
"""The wear steps per dynamics block that halving the wear steps doubles towards. The bore's
error follows the wear step, not how often the dynamics are renewed: on the tests' believed
rigid model, at 4,300-16,100 cycles against f = 0.00098 with one step per block, f = 0.0039 with
1, 4 and 8 steps per block (73, 17 and 9 blocks) was 0.72, 0.47 and 0.75 um off, f = 0.00195
with 4 and 8 (32 and 16 blocks) 0.29 and 0.28 um, at 7.1, 2.9, 1.7, 3.9 and 2.7 s a run (the
runs' own spread 0.3 um). A config with more steps per block keeps them (the default has 16:
``fewear/defaults/run.toml``)."""


def with_doubled_recorded_cycles(config: dict) -> dict:
    """``config`` with twice the crank cycles recorded per block (the wear of a block is their
    mean: an orbit that varies from cycle to cycle is sampled by more of them)."""
    changed = copy.deepcopy(config)
    changed["wear_loop"]["recorded_cycles_per_block"] *= 2
    return changed


def simulate_wear(config: dict, label: str = "", comm=None) -> WearHistory:
    """The wear loop of the config's (single) rod model up to its ``total_cycles``, as ``fewear
    run`` makes it (:func:`fewear.loop.block.predict_joints` on the case's dynamics). A run that
    wears through the wall or whose contact fails ends there (``stopped`` says why)."""
    key = _key(config)
    if key in _RUNS:
        return _RUNS[key]
    from mpi4py import MPI

    from fewear.loop.block import JointRun, new_bushing, new_case, predict_joints
    from fewear.loop.plan import Member, run_plan

    comm = MPI.COMM_WORLD if comm is None else comm
    plan = run_plan(config)
    rod, (name, inputs) = plan.cases[0], next(iter(plan.joints.items()))
    start = time.perf_counter()
    bushing = new_bushing(inputs, comm)
    joint = JointRun(f"{rod} rod", inputs, bushing, new_case(bushing))
    stopped = ""
    progress = _BlockProgress(label or rod, inputs.loop.total_cycles, comm.rank == 0)
    try:
        predict_joints(rod, {name: joint}, plan.simulate_block(config, Member(rod)),
                       lambda: progress(joint.case))
    except FewearInputError as exc:
        stopped = str(exc)
    finally:
        bushing.close()
    case = joint.case
    if not case.records:
        raise FewearInputError(f"forward run {label or rod}: no wear block completed ({stopped})")
    state = case.state
    cycles, depth_m = wear_step_ends(case.records, state.depth_m.size)
    history = WearHistory(
        state.angle_rad.copy(), cycles, depth_m,
        np.asarray(state.sliding.distance_m) / max(state.cycles, 1), stopped,
        time.perf_counter() - start)
    if comm.rank == 0:
        print(f"fewear diagnose: forward run {label or rod}: {state.cycles:,} cycles, "
              f"{state.blocks} blocks, {history.wall_time_s:.1f} s"
              + (" (stopped early)" if stopped else ""), file=sys.stderr, flush=True)
    _RUNS[key] = history
    return history


def wear_step_ends(records, nodes: int) -> tuple[np.ndarray, np.ndarray]:
    """The cycles (m + 1,) from 0 and the depth (m + 1, ``nodes``) after every wear step of the
    block ``records`` (a block of several wear steps wears its bore in as many increments;
    its end alone would leave a straight line across a bending curve)."""
    cycles, depth_m = [np.zeros(1)], [np.zeros((1, nodes))]
    for record in records:
        cycles += [record.inner_cycles.astype(float), np.array([float(record.cycles)])]
        depth_m += [record.inner_depth_m, record.depth_m[None, :]]
    return np.concatenate(cycles), np.vstack(depth_m)


class _BlockProgress:
    """A forward run's progress on stderr: a line every :data:`PROGRESS_INTERVAL_S` at most (the
    candidate runs of a diagnosis are many; a line per block would drown the terminal)."""

    def __init__(self, label: str, total_cycles: int, show: bool):
        self.label, self.total, self.show = label, total_cycles, show
        self.start = self.last = time.perf_counter()

    def __call__(self, case) -> None:
        now = time.perf_counter()
        if self.show and now - self.last >= PROGRESS_INTERVAL_S:
            self.last = now
            print(f"fewear diagnose: forward run {self.label}: {case.state.cycles:,}/"
                  f"{self.total:,} cycles, block {case.state.blocks}, {now - self.start:.0f} s",
                  file=sys.stderr, flush=True)


def simulate_wears(requests: list[tuple[dict, str]]) -> list[WearHistory]:
    """:func:`simulate_wear` of each ``(config, label)``: the runs not made yet side by side in
    worker processes (spawned, one per CPU core, each BLAS on one thread), the longest expected
    first (:func:`expected_cost`: a worker that takes the next run as it finishes one then ends
    the batch on short runs, not one core on a long run while the other idles), then all from
    the memo. Serial under ``mpirun`` (the ranks share each run) or on one core."""
    from fewear.kernels import compile_kernels_unless_cached
    from fewear.parallel import side_by_side

    missing = sorted({_key(config): (config, label) for config, label in requests
                      if _key(config) not in _RUNS}.values(),
                     key=lambda request: _handed_out_before(request[0]))
    # compiled once here, not in every worker at once, on an empty cache
    histories = side_by_side(simulate_wear, missing, prepare=compile_kernels_unless_cached)
    _RUNS.update({_key(config): history for (config, _), history in zip(missing, histories)})
    return [_RUNS[_key(config)] for config, _ in requests]


FLEXIBLE_ROD_COST = 4.0
"""A flexible rod's crank cycle costs about this many rigid ones (its ANCF dynamics: 39,000
cycles of the tests' mechanism in 20-25 s against 7.5 s rigid, wear steps included)."""


def expected_cost(config: dict) -> float:
    """A run's cost in rigid-rod crank cycles (for the order runs are handed out in)."""
    loop = config["wear_loop"]
    return loop["total_cycles"] * (FLEXIBLE_ROD_COST if loop["rod_models"][0] == "flexible"
                                   else 1.0)


def _handed_out_before(config: dict) -> tuple:
    """The sort key of a batch's runs: the dearest (:func:`expected_cost`) first and, among runs
    of equal cost, those with more impact wear (an impact-worn pocket draws more impacts, so
    more, shorter wear blocks: on an independent-generator data set the impact grid's runs of
    39,000 cycles took 31, 58 and 140 blocks, 9, 16 and 43 s, against 27-29 blocks for the
    friction grid's; handed out last, the 43 s run ended the batch on one core)."""
    wear = config.get("wear", {})
    return (-expected_cost(config),
            tuple(-float(wear.get(key, 0.0)) for key in impact.FORM_CONFIG_KEYS.values()))


RunMaker = Callable[[list[tuple[dict, str]]], list[WearHistory]]
"""Makes the runs of ``[(config, label), ...]`` (:func:`candidate_runner`)."""


def candidate_config(changed: dict, cycles: int, deepest_m: float) -> dict:
    """A candidate's ``changed`` config as it is run: ``cycles`` long, stopping once it wears
    :data:`DEPTH_REACH` to twice that times deeper than the deepest measured wear ``deepest_m``
    (it explains nothing beyond, and an impact-worn pocket that draws ever more impacts would
    otherwise run on in ever shorter blocks)."""
    changed = model_config(changed, changed["wear_loop"]["rod_models"][0], cycles)
    loop, bushing = changed["wear_loop"], changed["bushing"]
    if deepest_m > 0.0:  # rounded up to a power of 2: data sets of about one depth share runs
        wall = bushing["outer_radius_m"] - bushing["inner_radius_m"]
        loop["max_wall_fraction"] = min(loop["max_wall_fraction"], 2.0 ** math.ceil(
            math.log2(DEPTH_REACH * deepest_m / wall)))
    return changed


def candidate_runner(cycles: int, deepest_m: float) -> RunMaker:
    """How candidates' configs are run: as :func:`candidate_config`, side by side
    (:func:`simulate_wears`)."""

    def run(requests: list[tuple[dict, str]]) -> list[WearHistory]:
        return simulate_wears([(candidate_config(changed, cycles, deepest_m), label)
                               for changed, label in requests])

    return run


def _key(config: dict) -> str:
    return json.dumps(config, sort_keys=True, default=str)


def cycle_on_worn_bore(config: dict, angle_rad: np.ndarray | None = None,
                       depth_m: np.ndarray | None = None, recorded_cycles: int = 1):
    """``recorded_cycles`` crank cycles of the config's rod model (after its settling cycles)
    on the bore worn by ``depth_m`` at the node angles ``angle_rad`` (None: the unworn bore, the
    joint's nominal clearance): the :class:`fewear.mbd.history.JointHistory` the wear stage
    would see (the case's dynamics of :mod:`fewear.loop.mechanism_adapter`)."""
    from dataclasses import replace

    from fewear.loop import mechanism_adapter as adapter
    from fewear.loop.plan import run_plan
    from fewear.wear.state import WearState

    plan = run_plan(config)
    rod, (name, inputs) = plan.cases[0], next(iter(plan.joints.items()))
    profiles = None
    if depth_m is not None:
        state = replace(WearState.unworn(angle_rad), depth_m=np.asarray(depth_m, dtype=float))
        geometry = inputs.contact.geometry
        profiles = {name: state.clearance_profile(geometry.inner_radius_m,
                                                  geometry.pin_radius_m)}
    histories, _, _ = adapter.simulate(adapter.block_inputs(
        adapter.dynamics_inputs(config, rod), recorded_cycles, None), profiles=profiles)
    return histories[name]


def impact_measures_per_cycle(config: dict) -> dict[str, float]:
    """What the impacts of one crank cycle on the unworn joint wear by (:mod:`fewear.wear.impact`):
    ``energy``, the contact law's hysteresis work (J; of the continuous contact over the steps that
    carry a force, and of the impacts), ``impulse``, the impacts' normal impulse (N s, those above
    the config's force threshold), and ``speed``, the sum of the impacts' v^n ((m/s)^n, the config's
    exponent). Memoised by the config, as the runs are (a round asks for them when it makes the
    impact grid's runs and again when it fits them)."""
    from fewear.loop.settings import run_inputs_from_config
    from fewear.loop.stages import load_steps

    key = _key(config)
    if key not in _IMPACT_MEASURES:
        inputs = run_inputs_from_config(config)
        steps = load_steps(cycle_on_worn_bore(config), inputs.loop.load_steps_per_cycle,
                           inputs.dynamics.joint.law, inputs.impact_law)
        loaded = np.linalg.norm(steps.force_N, axis=1) > 0.0
        hits = steps.impacts
        _IMPACT_MEASURES[key] = {
            "energy": float(steps.hysteresis_work_J[loaded].sum() + hits.work_J.sum()),
            "impulse": float(hits.impulse_N_s.sum()), "speed": float(hits.speed_power.sum())}
    return dict(_IMPACT_MEASURES[key])


def worn_volume_per_cycle_m3(history: WearHistory, config: dict) -> float:
    """The sliding wear volume of one cycle early in the run (its first wear step, on the
    unworn bore), for scaling."""
    inner = config["bushing"]["inner_radius_m"]
    depth = history.depth_m[1]
    area = float(np.sum(inner * depth) * 2.0 * math.pi / depth.size)
    return config["bushing"]["width_m"] * area / history.cycles[1]


def unworn_volume_per_cycle_m3(config: dict) -> float:
    """:func:`worn_volume_per_cycle_m3` of the config's rod model from a run of one crank cycle
    (one wear step on the unworn bore: the rate of a longer run's first step, which is made on
    the same bore), so that runs scaled by it need not wait for the config's own run."""
    rod = config["wear_loop"]["rod_models"][0]
    first_step = model_config(config, rod, 1)
    run, = simulate_wears([(first_step, f"{rod} rod, first wear step")])
    return worn_volume_per_cycle_m3(run, first_step)
