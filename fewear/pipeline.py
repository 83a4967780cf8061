"""The wear prediction of the seed paper (Zhao, Zhang & Dai 2013, Fig. 3), stage by stage.

``fewear run`` follows the flowchart for each connecting-rod model (rigid, flexible):

1. **Dynamics** (:mod:`fewear.mbd`): the slider-crank with the revolute clearance joint, settled,
   then one recorded crank cycle: the joint reaction and the pin's rotation relative to the bushing.
2. **Load steps**: the cycle cut into n steps (seed: 200); each step carries the joint force at its
   middle and the relative rotation accumulated over it.
3. **Contact** (:mod:`fewear.contact`): the FE bushing (Q8, outer surface clamped, rigid pin on a
   pilot point) under each step's force: nodal pressures p and slips s on the bore. The condensed
   fast path is used; it equals the full DOLFINx solve to 1e-6 (tests/contact).
4. **Wear** (:mod:`fewear.wear`): Archard's law with k(p, v) from the RBF network (seed eq. 9,
   10), the sliding speed v = s / dt of each step, giving the wear depth of one simulated cycle and
   of the first block of A_j cycles.

What is *not* done yet: moving the worn bore (ALE, re-meshing) and feeding the worn clearance
c(theta) back into the dynamics for the next block (seed section 4). Until that loop exists the
depth after ``total_cycles`` is reported as the constant-geometry projection
``total_cycles * depth_per_cycle``, labelled as such: without the geometry feedback it is the
first-order estimate, not the paper's Fig. 7.
"""

from __future__ import annotations

import sys
import time
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError
from fewear.mbd.history import JointHistory
from fewear.wear.archard import advance_wear_depth_m, cycle_wear_depth_m

RUN_SECTIONS = ["wear_loop", "wear"]


@dataclass(frozen=True)
class WearLoopSettings:
    """The ``[wear_loop]`` section (seed section 5 values by default)."""

    rod_models: tuple[str, ...]
    load_steps_per_cycle: int
    extrapolation_factor: float
    total_cycles: int
    friction_in_contact: bool

    def __post_init__(self):
        unknown = [rod for rod in self.rod_models if rod not in ("rigid", "flexible")]
        if unknown or not self.rod_models:
            raise FewearInputError(
                f"[wear_loop] rod_models = {list(self.rod_models)!r}: expected a non-empty list of "
                "'rigid' and/or 'flexible'")
        if self.load_steps_per_cycle < 2:
            raise FewearInputError(
                f"[wear_loop] load_steps_per_cycle = {self.load_steps_per_cycle}: expected >= 2")
        if not self.extrapolation_factor >= 1.0:
            raise FewearInputError(
                f"[wear_loop] extrapolation_factor = {self.extrapolation_factor}: expected >= 1")
        if self.total_cycles < 1:
            raise FewearInputError(f"[wear_loop] total_cycles = {self.total_cycles}: expected >= 1")


@dataclass(frozen=True)
class LoadSteps:
    """The n load steps of one crank cycle (bushing frame).

    ``force_N`` (n, 2): joint force ON the pin pushing it into the bore (minus the bushing's
    reaction on the pin) at the middle of each step; ``rotation_rad`` (n,): rotation of the pin
    relative to the bushing over the step; ``duration_s``: the length of one step.
    """

    time_s: np.ndarray
    force_N: np.ndarray
    rotation_rad: np.ndarray
    duration_s: float


@dataclass(frozen=True)
class CycleWear:
    """Contact and wear of one simulated cycle on the bore nodes (sorted by angle).

    ``pressure_Pa``, ``slip_m``, ``k_m2_N``: (n_steps, n_nodes); ``depth_per_cycle_m`` (n_nodes,).
    """

    angle_rad: np.ndarray
    x_m: np.ndarray
    y_m: np.ndarray
    pressure_Pa: np.ndarray
    slip_m: np.ndarray
    k_m2_N: np.ndarray
    depth_per_cycle_m: np.ndarray


def load_steps(history: JointHistory, n_steps: int) -> LoadSteps:
    """Cut the recorded cycle into ``n_steps`` equal steps (stage 2).

    The force is sampled at each step's middle (linear interpolation of the variable-step history);
    the relative rotation is the trapezoidal integral of ``rel_omega_rad_s`` over the step.
    """
    t = history.time_s
    edges = np.linspace(t[0], t[-1], n_steps + 1)
    middles = 0.5 * (edges[1:] + edges[:-1])
    force_on_pin = -history.reaction_force_N
    force = np.column_stack([np.interp(middles, t, force_on_pin[:, i]) for i in range(2)])
    angle = np.concatenate(
        [[0.0], np.cumsum(0.5 * (history.rel_omega_rad_s[1:] + history.rel_omega_rad_s[:-1])
                          * np.diff(t))])
    rotation = np.diff(np.interp(edges, t, angle))
    return LoadSteps(middles, force, rotation, float(edges[1] - edges[0]))


def cycle_wear(contact_model, steps: LoadSteps, wear_coefficient, friction: bool,
               progress=None) -> CycleWear:
    """Stages 3 and 4: contact at every load step, then Archard's law summed over the cycle."""
    results = []
    for i, (force, rotation) in enumerate(zip(steps.force_N, steps.rotation_rad)):
        results.append(contact_model.solve(force, rotation, friction=friction))
        if progress is not None and (i + 1) % 50 == 0:
            progress(f"contact: load step {i + 1}/{len(steps.force_N)}")
    pressure = np.array([r.pressure_Pa for r in results])
    slip = np.array([r.slip_m for r in results])
    speed = slip / steps.duration_s
    k = np.where(slip > 0.0, wear_coefficient(pressure, np.maximum(speed, 1e-300)), 0.0)
    first = results[0]
    return CycleWear(first.angle_rad, first.x_m, first.y_m, pressure, slip, k,
                     cycle_wear_depth_m(k, pressure, slip))


def wear_volume_per_width_m2(wear: CycleWear, depth_m: np.ndarray) -> float:
    """Worn area of the bore cross-section (m^2, = volume per unit width): trapezoid in arc length
    over the closed bore."""
    x = np.append(wear.x_m, wear.x_m[0])
    y = np.append(wear.y_m, wear.y_m[0])
    h = np.append(depth_m, depth_m[0])
    ds = np.hypot(np.diff(x), np.diff(y))
    return float(np.sum(0.5 * (h[1:] + h[:-1]) * ds))


def predict_case(rod: str, config: dict, contact_model, wear_coefficient,
                 settings: WearLoopSettings, progress) -> dict:
    """Stages 1-4 for one rod model; returns the summary and the arrays for the outputs."""
    from fewear.mbd.slider_crank import simulate_slider_crank

    progress(f"{rod} rod: dynamics (settling + recorded cycle)")
    history, run = simulate_slider_crank(config, rod=rod, joint="clearance", cycles=1)
    steps = load_steps(history, settings.load_steps_per_cycle)
    progress(f"{rod} rod: {history.impacts} impacts, peak {history.peak_contact_force_N:.0f} N; "
             f"contact at {settings.load_steps_per_cycle} load steps")
    wear = cycle_wear(contact_model, steps, wear_coefficient, settings.friction_in_contact,
                      progress)
    first_block = advance_wear_depth_m(0.0, wear.depth_per_cycle_m, settings.extrapolation_factor)
    peak = int(np.argmax(wear.depth_per_cycle_m))
    summary = {
        "peak_contact_force_N": history.peak_contact_force_N,
        "impacts": history.impacts,
        "dynamics_wall_time_s": run.wall_time_s,
        "max_contact_pressure_Pa": float(wear.pressure_Pa.max()),
        "max_wear_depth_per_cycle_m": float(wear.depth_per_cycle_m[peak]),
        "max_wear_angle_deg": float(np.degrees(wear.angle_rad[peak])),
        "max_wear_depth_first_block_m": float(first_block[peak]),
        "wear_volume_per_cycle_m3": config["bushing"]["width_m"]
        * wear_volume_per_width_m2(wear, wear.depth_per_cycle_m),
        "max_wear_depth_constant_geometry_m": float(
            settings.total_cycles * wear.depth_per_cycle_m[peak]),
    }
    return {"summary": summary, "history": history, "wear": wear, "first_block_m": first_block}


def main(args) -> int:
    """``fewear run``: the prediction for every rod model of ``[wear_loop]``, written all or
    nothing into ``args.out`` (summary.json, wear_profile.csv, wear_profile.png, joint histories).
    """
    from mpi4py import MPI

    from fewear.contact.condensed import CondensedBushingContact
    from fewear.contact.params import CONFIG_SECTIONS, contact_problem_from_config
    from fewear.io.config import load_config
    from fewear.io.output import staged_output
    from fewear.mbd.slider_crank import SECTIONS as DYNAMICS_SECTIONS
    from fewear.wear.coefficient import wear_coefficient_from_config

    comm = MPI.COMM_WORLD
    sections = list(dict.fromkeys([*RUN_SECTIONS, *CONFIG_SECTIONS, *DYNAMICS_SECTIONS]))
    config = load_config(args.config, sections)
    settings = WearLoopSettings(**{**config["wear_loop"],
                                   "rod_models": tuple(config["wear_loop"]["rod_models"])})
    if config["wear"]["extension"] != "none":
        raise FewearInputError(
            f"[wear] extension = {config['wear']['extension']!r}: `fewear run` applies plain "
            "Archard until the wear loop tracks each node's sliding history; use 'none'")
    wear_coefficient = wear_coefficient_from_config(config["wear"])
    problem = contact_problem_from_config(config)

    start = time.perf_counter()

    def progress(message: str) -> None:
        if comm.rank == 0:
            print(f"fewear run [{time.perf_counter() - start:6.1f} s] {message}", file=sys.stderr,
                  flush=True)

    with staged_output(args.out, comm) as stage:
        progress("contact: meshing the bushing and condensing it onto the bore")
        contact_model = CondensedBushingContact(problem, comm)
        cases = {rod: predict_case(rod, config, contact_model, wear_coefficient, settings,
                                   progress) for rod in settings.rod_models}
        if comm.rank == 0:
            write_outputs(stage, cases, settings, config)
    progress(f"done: {args.out}")
    return 0


def write_outputs(stage, cases: dict, settings: WearLoopSettings, config: dict) -> None:
    from fewear.io.output import write_json
    from fewear.mbd.command import write_history_csv
    from fewear.plot.wear import plot_wear_profiles

    summary = {
        "what": "seed section 5: first wear block per rod model (no geometry feedback yet)",
        "load_steps_per_cycle": settings.load_steps_per_cycle,
        "extrapolation_factor": settings.extrapolation_factor,
        "total_cycles": settings.total_cycles,
        "cases": {rod: case["summary"] for rod, case in cases.items()},
        "config": config,
    }
    write_json(stage / "summary.json", summary)
    first = next(iter(cases.values()))["wear"]
    columns = {"angle_deg": np.degrees(first.angle_rad), "x_m": first.x_m, "y_m": first.y_m}
    for rod, case in cases.items():
        columns[f"depth_per_cycle_{rod}_m"] = case["wear"].depth_per_cycle_m
        columns[f"depth_first_block_{rod}_m"] = case["first_block_m"]
        write_history_csv(case["history"], stage / f"joint_history_{rod}.csv")
    np.savetxt(stage / "wear_profile.csv", np.column_stack(list(columns.values())),
               delimiter=",", header=",".join(columns), comments="", fmt="%.9e")
    plot_wear_profiles({rod: (case["wear"].angle_rad, case["first_block_m"])
                        for rod, case in cases.items()},
                       stage / "wear_profile.png", settings.extrapolation_factor)

