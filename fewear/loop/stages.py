"""Stages 2-4 of a wear block on one recorded history: load steps, contact at every step, and
Archard's law summed over the steps into what one crank cycle does at each bore node."""

from __future__ import annotations

from dataclasses import dataclass, replace
from functools import partial

import numpy as np
from scipy.integrate import cumulative_trapezoid

from fewear.contact.admissible import ContactLoadError
from fewear.mbd.history import JointHistory, impact_episodes
from fewear.wear.archard import CycleSliding, cycle_wear_depth_m
from fewear.wear.impact import (
    NO_IMPACT_WEAR,
    ImpactWearLaw,
    hysteresis_work_J,
    impact_impulse_N_s,
    impact_speed_power,
    impact_wear_depth_m,
)

DROPPABLE_SHARE = 0.01
"""Load steps that find no contact equilibrium on a worn bore are dropped (counted, no wear)
while together they carry at most this share of the cycle's load-slip product; beyond it the
run stops with an error."""


@dataclass(frozen=True)
class ImpactHits:
    """The impact episodes of the recorded cycles (m of them,
    :func:`fewear.mbd.history.impact_episodes`): where each strikes and what it wears by.

    ``force_N`` (m, 2): the normal force on the pin at the episode's peak, along the pin centre's
    eccentricity (bushing frame): the FE contact at this force is the impact's footprint;
    ``work_J`` (m,): the contact law's hysteresis work over the episode; ``impulse_N_s`` (m,):
    its normal impulse (0 unless its peak exceeds the impact law's force threshold);
    ``speed_power`` (m,): v^n of its approach speed
    (:func:`fewear.wear.impact.impact_speed_power`)."""

    force_N: np.ndarray
    work_J: np.ndarray
    impulse_N_s: np.ndarray
    speed_power: np.ndarray


NO_HITS = ImpactHits(np.zeros((0, 2)), np.zeros(0), np.zeros(0), np.zeros(0))
"""No impact (the ideal joint, or a history without impact episodes)."""


@dataclass(frozen=True)
class LoadSteps:
    """The load steps of the recorded cycles (bushing frame).

    ``force_N`` (n, 2): joint force ON the pin pushing it into the bore (minus the bushing's
    reaction on the pin), over each step its slip-weighted mean (:func:`load_steps`);
    ``rotation_rad`` (n,): rotation of the pin relative to the bushing over the step;
    ``duration_s``: the length of one step; ``hysteresis_work_J`` (n,): the work W_i the contact
    law's hysteresis dissipates over the step outside the impact episodes
    (:func:`fewear.wear.impact.hysteresis_work_J`); ``impacts``: the impact episodes, each with
    its own force and measures (:class:`ImpactHits`).
    """

    time_s: np.ndarray
    force_N: np.ndarray
    rotation_rad: np.ndarray
    duration_s: float
    hysteresis_work_J: np.ndarray
    impacts: ImpactHits = NO_HITS


@dataclass(frozen=True)
class CycleWear:
    """Contact and wear of the recorded cycles on the bore nodes (sorted by angle).

    ``pressure_Pa``, ``slip_m``, ``k_m2_N``: (n_steps, n_nodes); ``depth_per_cycle_m`` (n_nodes,):
    plain Archard depth summed over all the steps; ``depth_sensitivity`` (n_nodes, n_nodes) its
    derivative with respect to the bore's wear depth, or None; ``dropped_steps``: steps
    that found no contact equilibrium on the worn bore, dropped within ``DROPPABLE_SHARE``;
    ``impact_pressure_Pa`` (m, n_nodes): the footprint of each impact (the frictionless
    contact at its peak normal force), empty unless asked for.
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
    impact_pressure_Pa: np.ndarray | None = None


def load_steps(history: JointHistory, n_steps: int, law=None,
               impact: ImpactWearLaw = NO_IMPACT_WEAR) -> LoadSteps:
    """Cut the recorded history into ``n_steps`` equal steps (stage 2).

    The force of a step is the one that drives Archard's wear over it: of magnitude the mean of
    |F| weighted by the sliding speed |omega|, int |F| |omega| dt / int |omega| dt, along
    int F |omega| dt, so that |F_i| |rotation_i| is the step's int |F| |omega| dt whatever n
    (the load-slip product Archard's worn volume k R sum |F_i| |rotation_i| grows with; with
    no reversal of the rotation inside the step, exactly). A step without relative rotation
    keeps the mean force, its impulse over its length. The seed samples the force at one
    instant: an impact peak lasting microseconds is then hit or missed (the maximum depth after
    10,000 cycles moved by 20 % between n = 200 and 400). The plain mean is no better: where
    the force turns within a step (an impact, the flexible rod's vibration) the mean vector is
    shorter than the mean magnitude, and the slip is not steady; on a late block's history the
    load-slip product of n = 200 plain means lay 8 % below (rigid) and 5 % above (flexible) the
    history's, converging as slowly as 1/n. The relative rotation is the integral of
    ``rel_omega_rad_s`` over the step, the hysteresis work W_i that of the power ``law`` (the
    clearance joint's :class:`fewear.mbd.contact.ContactLaw`; None: no work and no impacts, as
    for the ideal joint) dissipates outside the impact episodes; the episodes' own work,
    impulse and speed are the ``impacts`` (:func:`impact_hits`, ``impact``'s threshold and
    exponent). All the integrals are trapezoidal on the history, interpolated linearly at the
    step edges.
    """
    t = history.time_s
    edges = np.linspace(t[0], t[-1], n_steps + 1)
    middles = 0.5 * (edges[1:] + edges[:-1])
    duration = float(edges[1] - edges[0])

    def gained(cumulative: np.ndarray) -> np.ndarray:
        """What a cumulative quantity of the history gains over each step."""
        return np.diff(np.interp(edges, t, cumulative))

    def over_steps(values: np.ndarray) -> np.ndarray:
        """The integral of ``values`` (samples of the history) over each step."""
        return gained(cumulative_trapezoid(values, t, initial=0.0))

    on_pin = -history.reaction_force_N
    speed = np.abs(history.rel_omega_rad_s)
    force = np.column_stack([over_steps(on_pin[:, i]) for i in range(2)]) / duration
    sliding = over_steps(speed)
    along = np.column_stack([over_steps(on_pin[:, i] * speed) for i in range(2)])
    length = np.hypot(along[:, 0], along[:, 1])
    slides = (sliding > 0.0) & (length > 0.0)
    size = over_steps(np.hypot(on_pin[:, 0], on_pin[:, 1]) * speed)[slides] / sliding[slides]
    force[slides] = along[slides] / length[slides, None] * size[:, None]
    rotation = over_steps(history.rel_omega_rad_s)
    if law is None:
        return LoadSteps(middles, force, rotation, duration, np.zeros(n_steps))
    work = hysteresis_work_J(law, history.penetration_m, history.normal_force_N)
    hits, in_impacts = impact_hits(history, work, impact)
    return LoadSteps(middles, force, rotation, duration, gained(work - in_impacts), hits)


def impact_hits(history: JointHistory, work_J: np.ndarray,
                impact: ImpactWearLaw = NO_IMPACT_WEAR) -> tuple[ImpactHits, np.ndarray]:
    """The :class:`ImpactHits` of ``history``, and the share of the cumulative hysteresis work
    ``work_J`` (:func:`fewear.wear.impact.hysteresis_work_J`, J, (n,)) done within them (J,
    (n,)). An episode spans the intervals from the sample before its first row to the sample
    after its last (the force rises from and falls to zero there), as its impulse does
    (:func:`fewear.wear.impact.impact_impulse_N_s`); its force is the normal force at its
    peak, along the eccentricity there (the pin presses the bore where it is off-centre)."""
    t, normal = history.time_s, history.normal_force_N
    episodes = impact_episodes(history.mode)
    if not episodes:
        return NO_HITS, np.zeros_like(work_J)
    impulse = impact_impulse_N_s(t, normal, history.mode, impact.impulse_threshold_N)
    onsets = impact_speed_power(t, history.eccentricity_m, history.mode, impact.speed_exponent)
    within = np.zeros(t.size - 1, dtype=bool)  # the intervals inside an episode
    spans, forces = [], []
    for first, last in episodes:
        before, after = max(first - 1, 0), min(last + 1, t.size - 1)
        within[before:after] = True
        spans.append((before, after))
        peak = first + int(np.argmax(normal[first:last + 1]))
        direction = history.eccentricity_m[peak]
        if not np.any(direction):  # a pin exactly centred: the joint force's direction
            direction = -history.reaction_force_N[peak]
        forces.append(normal[peak] * direction / np.hypot(*direction))
    in_impacts = np.concatenate([[0.0], np.cumsum(np.where(within, np.diff(work_J), 0.0))])
    hits = ImpactHits(np.array(forces),
                      np.array([in_impacts[b] - in_impacts[a] for a, b in spans]),
                      np.array([impulse[b] - impulse[a] for a, b in spans]),
                      np.array([onsets[first] for first, _ in episodes]))
    return hits, in_impacts


def cycle_wear(contact_model, steps: LoadSteps, wear_coefficient, friction: bool,
               implicit: bool = False, footprints: bool = False) -> CycleWear:
    """Stages 3 and 4: contact at every load step, then Archard's law summed over the steps.

    ``implicit``: also sum the steps' sensitivities k s dp/dh (``contact_model`` must offer
    ``depth_sensitivity(pressure, slip, k, pin_centres)``, as
    :class:`fewear.loop.bushing.WornBushing` does)
    for the linearised block step of :func:`fewear.wear.archard.block_wear`. ``footprints``:
    also the contact at each impact's force (``impact_pressure_Pa``; for impact wear).
    """
    results = _solve_steps(contact_model, steps, friction)
    solved = next(r for r in results if r is not None)  # the heaviest step is never dropped
    dropped = sum(r is None for r in results)
    empty = replace(solved, pressure_Pa=np.zeros_like(solved.pressure_Pa),
                    slip_m=np.zeros_like(solved.slip_m))
    results = [empty if r is None else r for r in results]
    pressure = np.array([r.pressure_Pa for r in results])
    slip = np.array([r.slip_m for r in results])
    sliding = slip > 0.0  # k is evaluated where it wears only (a few per cent of the entries)
    k = np.zeros_like(slip)
    k[sliding] = wear_coefficient(pressure[sliding], slip[sliding] / steps.duration_s)
    sensitivity = None
    if implicit:
        sensitivity = contact_model.depth_sensitivity(
            pressure, slip, k, np.array([r.pin_centre_m for r in results]))
    struck = None
    if footprints:
        struck = np.array([contact_model.solve(force, 0.0, friction=False).pressure_Pa
                           for force in steps.impacts.force_N]).reshape(-1, pressure.shape[1])
    return CycleWear(solved.angle_rad, solved.x_m, solved.y_m, pressure, slip, k,
                     cycle_wear_depth_m(k, pressure, slip), sensitivity, dropped, struck)


def _solve_steps(contact_model, steps: LoadSteps, friction: bool) -> list:
    """The contact of every load step; None for a step that finds no equilibrium on the worn
    bore while the steps dropped so far carry at most ``DROPPABLE_SHARE`` of the cycle's
    sum of |F| |rotation| (the load-slip product Archard's wear grows with)."""
    load_slip = np.linalg.norm(steps.force_N, axis=1) * np.abs(steps.rotation_rad)
    allowance = DROPPABLE_SHARE * load_slip.sum()
    solve_run = getattr(contact_model, "solve_run", None) or partial(_solve_one, contact_model)
    results = []
    while len(results) < load_slip.size:
        solved, refusal = solve_run(steps.force_N, steps.rotation_rad, friction, len(results))
        results.extend(solved)
        if refusal is not None:
            share = load_slip[len(results)]
            if share > allowance:
                raise refusal
            allowance -= share
            results.append(None)
    return results


def _solve_one(contact_model, forces_N: np.ndarray, rotations_rad: np.ndarray, friction: bool,
               first: int) -> tuple[list, Exception | None]:
    """The load step ``first`` by ``contact_model.solve``, in the form of a ``solve_run``
    (:meth:`fewear.loop.bushing.WornBushing.solve_run`): its result, or its refusal."""
    try:
        return [contact_model.solve(forces_N[first], rotations_rad[first],
                                    friction=friction)], None
    except ContactLoadError as refusal:
        return [], refusal


def cycle_sliding(wear: CycleWear, steps: LoadSteps, cycles: int, friction_coefficient: float,
                  impact: ImpactWearLaw = NO_IMPACT_WEAR) -> CycleSliding:
    """What one crank cycle does at each node, averaged over the ``cycles`` recorded cycles:
    Archard depth, sliding distance, time in sliding contact, mean frictional power mu p v, the
    depth's sensitivity to the wear, and the impact wear depth of the ``impact`` law
    (:func:`fewear.wear.impact.impact_wear_depth_m`): the hysteresis work of the continuous
    contact under the steps' pressure, each impact's work, impulse and speed under its own
    footprint (``wear.impact_pressure_Pa``, needed when the law wears by impacts)."""
    sliding = wear.slip_m > 0.0
    distance = wear.slip_m.sum(axis=0) / cycles
    time_s = steps.duration_s * sliding.sum(axis=0) / cycles
    energy = friction_coefficient * (wear.pressure_Pa * wear.slip_m).sum(axis=0) / cycles
    power = np.divide(energy, time_s, out=np.zeros_like(energy), where=time_s > 0.0)
    sensitivity = None if wear.depth_sensitivity is None else wear.depth_sensitivity / cycles
    hits = steps.impacts
    impact_depth = impact_wear_depth_m(impact.energy_m3_J, steps.hysteresis_work_J,
                                       steps.force_N, wear.pressure_Pa)
    struck_m3 = impact.volume_m3(hits.work_J, hits.impulse_N_s, hits.speed_power)
    if np.any(struck_m3 > 0.0):
        if wear.impact_pressure_Pa is None:
            raise ValueError("the impacts wear, but their footprints were not solved: "
                             "cycle_wear(..., footprints=True)")
        impact_depth = impact_depth + impact_wear_depth_m(1.0, struck_m3, hits.force_N,
                                                          wear.impact_pressure_Pa)
    impact = impact_depth / cycles
    return CycleSliding(wear.depth_per_cycle_m / cycles, distance, time_s, power, sensitivity,
                        impact)
