"""Refining a cause's fit on runs of the wear loop at its fitted parameters (the joint diagnosis,
:mod:`fewear.diagnose.joint.diagnose`): a fit that scales the cycles of runs made with the
believed k, interpolates between grid runs or maps the cycles of the believed run is not the wear
loop's run at its parameters, so a fit that could be accepted is refitted on such runs."""

from __future__ import annotations

import math
from collections.abc import Callable, Generator
from dataclasses import replace

import numpy as np

from fewear.diagnose.joint.candidates import Candidate, grid_value, lasts, running_in_extension
from fewear.diagnose.joint.fitting import (
    Fit,
    Observations,
    best_form,
    best_run,
    bounds_and_starts,
    fit,
    fit_form,
    needed_cycles,
    with_params,
)
from fewear.diagnose.joint.forward import WearHistory
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.parallel import side_by_side

REFINEMENTS = 3
"""At most this many runs refine a fit (:func:`refine_running_in`, :func:`refine_on_runs`)."""
SETTLED = 0.05
"""A refinement ends once the fit's parameters (s, r - 1, s0 or N0: in ln) are this close to those
of the run it sits on."""
GRID_SETTLED = 0.05
"""A grid refinement ends once the fit lands within this fraction of a grid step of a run."""
RunsAt = Callable[[list[tuple[Candidate, Fit]]], list[WearHistory]]
"""The runs refinements ask for, made together: each a cause's form (``candidate``) at a fit's
parameters."""
Refinement = Generator[tuple[Candidate, Fit], WearHistory, Fit]
"""A refinement in progress: it yields the run it needs next (the form and the fit at whose
parameters to run it), is sent that run, and returns the refined fit."""


def fit_causes(candidates: dict[str, tuple[Candidate, ...]], obs: Observations, baseline: Fit,
               settings: JointDiagnoseSettings, runs_at: RunsAt) -> dict[str, Fit]:
    """Each cause fitted in each of its forms (:func:`fit_form`; the forms of all causes side by
    side in worker processes, :func:`fewear.parallel.side_by_side`); for a cause whose best form
    could be accepted (held-out error at least ``min_held_out_gain`` below the believed
    model's, a condition of acceptance), each form is refined on runs at its own fitted
    parameters (:func:`refine_running_in`, :func:`refine_on_runs`). The refinements of all
    causes and forms advance together, so that the runs they ask for at each step are made
    side by side (``runs_at``); each refinement depends on its own runs only, so the result is
    that of refining one after the other. Per cause, the best form on the training data is
    kept."""
    offset = float(baseline.x[0])
    first_fits = iter(side_by_side(fit_form, [(form, obs, offset, settings)
                                              for forms in candidates.values() for form in forms]))
    fits = {name: [next(first_fits) for _ in forms] for name, forms in candidates.items()}
    promising = [name for name in candidates
                 if best_form(fits[name]).held_out_gain(baseline)
                 >= settings.acceptance.min_held_out_gain]
    refinements = {(name, index): _refinement(form, fitted, obs, settings)
                   for name in promising
                   for index, (form, fitted) in enumerate(zip(candidates[name], fits[name]))}
    for (name, index), refined in _advance_together(refinements, runs_at).items():
        fits[name][index] = refined
    return {name: best_form(cause_fits) for name, cause_fits in fits.items()}


def _advance_together(refinements: dict, runs_at: RunsAt) -> dict:
    """Run the ``refinements`` (by key) to their ends, the runs that those under way ask for at
    each step made in one call of ``runs_at``; their refined fits by key."""
    asked, done = {}, {}

    def advance(key, run: WearHistory | None) -> None:
        try:
            asked[key] = refinements[key].send(run)
        except StopIteration as end:
            done[key] = end.value

    for key in refinements:
        advance(key, None)
    while asked:
        step = dict(asked)
        asked.clear()
        for key, run in zip(step, runs_at(list(step.values())), strict=True):
            advance(key, run)
    return done


def _refinement(candidate: Candidate, fitted: Fit, obs: Observations,
                settings: JointDiagnoseSettings) -> Refinement:
    if candidate.time_map:
        return refine_running_in(candidate, fitted, obs, settings)
    return refine_on_runs(candidate, fitted, obs, settings)


def refine_running_in(candidate: Candidate, fitted: Fit, obs: Observations,
                      settings: JointDiagnoseSettings) -> Refinement:
    """Defect correction of running-in's time map. The map stretches one run's worn bores in cycles
    node by node: exact where a node's wear follows its own sliding, but a strong running-in over a
    short distance wears the young bore's shape deeper than any run without it does (on one
    third-generator data set the map's fit gained 50 % where its full run lost 73 %). So the model
    is run at the fitted parameters (yielded: :data:`Refinement`), refitted on the map from that
    run (:func:`running_in_time_map`, near the identity), and so on, until no parameter moves by
    more than :data:`SETTLED` or after :data:`REFINEMENTS` runs. At a fixed point the fit is that
    of the real run at its own parameters; the iteration is not sure to reach one (a shape the map
    cannot make is approached a step per run), so the fit that is named is run in full again
    (:func:`fewear.diagnose.joint.selection.confirm_first`). A run that stops before the
    shortest time axis the fit needs ends the refinement; the fit before it stands."""
    bounds, _ = bounds_and_starts(candidate, obs, settings)
    for _ in range(REFINEMENTS):
        run = yield candidate, fitted
        if _stops_short(run, obs, settings):
            break
        params = fitted.params
        extension = running_in_extension(candidate.form, params)
        on_run = replace(candidate, runs=(run,), run_extension=extension,
                         k_scales=(params["k_scale"],))
        refitted = with_params(fit(candidate.name, on_run, obs, [fitted.x], bounds), on_run)
        moved = float(np.max(np.abs(refitted.x[1:] - fitted.x[1:])))
        fitted = refitted
        if moved < SETTLED:
            break
    return fitted


def refine_on_runs(candidate: Candidate, fitted: Fit, obs: Observations,
                   settings: JointDiagnoseSettings) -> Refinement:
    """A fit maps the cycles of runs made with the believed k to its level s, and a grid cause
    interpolates linearly between two runs; neither is exact for the wear loop's blocks (a run with
    k x 1.59 fitted a third-generator data set 74 % better than the believed run with its cycles
    scaled), and the run at an interpolated value need not resemble the interpolation (a fit at mu
    = 0.059, between the runs at 0.05 and 0.1, gained 67 % where the run at 0.059 lost 17 %). So
    the run at the fit's parameters (yielded: :data:`Refinement`; the extended model) joins the
    runs: it replaces the run the fit sits on (the level's one run, the run a discrete choice took,
    a grid run within :data:`GRID_SETTLED` of a step) or is added to the grid between two, and the
    cause is refitted; until the fit sits on a run made at its own level (within :data:`SETTLED` in
    ln s) or after :data:`REFINEMENTS` runs. A run that stops before the shortest time axis the fit
    needs ends the refinement. If the runs leave the fit between them (the coarse loop's worn bore
    need not follow a parameter smoothly: mu = 0.060, 0.067, 0.063 on one data set), the fit is
    taken as the best of the runs made that are still among the cause's, each exactly at its own
    parameters (:func:`_on_best_run`): a fit the full run reproduces."""
    made: list[WearHistory] = []
    while True:
        at, between = _run_under_fit(candidate, fitted)
        level = float(fitted.x[1])
        if not between and abs(level - math.log(candidate.k_scale(at))) < SETTLED:
            return fitted
        if len(made) == REFINEMENTS:
            return _on_best_run(candidate, fitted, made, obs, settings)
        run = yield candidate, fitted
        if _stops_short(run, obs, settings):
            return _on_best_run(candidate, fitted, made, obs, settings) if made else fitted
        made.append(run)
        runs, grid = list(candidate.runs), list(candidate.grid)
        k_scales = [candidate.k_scale(i) for i in range(len(runs))]
        if between:
            grid.insert(at, grid_value(candidate, float(fitted.x[2])))
            runs.insert(at, run)
            k_scales.insert(at, math.exp(level))
        else:
            runs[at], k_scales[at] = run, math.exp(level)
            if grid and not candidate.discrete:
                grid[at] = grid_value(candidate, float(fitted.x[2]))
        candidate = replace(candidate, runs=tuple(runs), grid=tuple(grid),
                            k_scales=tuple(k_scales))
        fitted = _refit(candidate, fitted, at, obs, settings)


def _on_best_run(candidate: Candidate, fitted: Fit, made: list[WearHistory],
                 obs: Observations, settings: JointDiagnoseSettings) -> Fit:
    """The fit on the run of ``made`` that fits the training data best, exactly at that run's
    parameters (its level and grid value; only the angle offset fitted). Only the runs still
    among the cause's count: one the fit sat on was replaced by the next."""
    best = None
    for index, run in enumerate(candidate.runs):
        if not any(run is other for other in made):
            continue
        pinned = np.array([fitted.x[0], math.log(candidate.k_scale(index)), float(index)])
        pinned = pinned[:fitted.x.size]
        bounds = np.column_stack([pinned, pinned])
        bounds[0] = (-settings.max_offset_deg, settings.max_offset_deg)
        result = fit(candidate.name, candidate, obs, [pinned], bounds)
        if best is None or result.sse_train < best.sse_train:
            best = result
    return with_params(replace(best, n_params=fitted.n_params), candidate)


def _run_under_fit(candidate: Candidate, fitted: Fit) -> tuple[int, bool]:
    """The run a fit sits on, or (``between``) the index a run at its grid value would get."""
    if len(candidate.runs) == 1:
        return 0, False
    position = float(fitted.x[2])
    nearest = int(round(position))
    if candidate.discrete or abs(position - nearest) <= GRID_SETTLED:
        return nearest, False
    return int(position) + 1, True


def _refit(candidate: Candidate, fitted: Fit, at: int, obs: Observations,
           settings: JointDiagnoseSettings) -> Fit:
    """``candidate`` fitted again from ``fitted``, its grid position moved to run ``at``."""
    bounds, _ = bounds_and_starts(candidate, obs, settings)
    if candidate.discrete:
        start = [np.array(fitted.x[:2])]
        return with_params(best_run(candidate, obs, start, bounds), candidate)
    start = np.array(fitted.x, dtype=float)
    if start.size > 2:
        start[2] = float(at)
    return with_params(fit(candidate.name, candidate, obs, [start], bounds), candidate)


def _stops_short(run: WearHistory, obs: Observations, settings: JointDiagnoseSettings) -> bool:
    """Whether ``run`` stopped before the shortest time axis a fit needs."""
    return not lasts(run, needed_cycles(obs, settings))
