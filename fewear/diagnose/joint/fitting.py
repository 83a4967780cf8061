"""Fitting a cause's runs of the wear loop to the measured depths (the joint diagnosis,
:mod:`fewear.diagnose.joint.diagnose`): the observations, a cause's form as runs
(:class:`Candidate`), its fit (:class:`Fit`: angle offset, level of k, its own parameters) by
least squares on the training data, scored on the held-out data.

A model of the depths is h(theta, N) = H(theta + phi, s tau(N)) (the method's module docstring):
a level-only candidate maps one run's cycles by s; a grid candidate interpolates between its runs
(or, ``discrete``, chooses one); a running-in candidate maps the cycles node by node through its
form's effective distance (:func:`running_in_time_map`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace
from functools import cached_property

import numpy as np
from scipy import optimize

from fewear.diagnose.core.statistics import aicc
from fewear.diagnose.joint.candidates import (
    RUNNING_IN_FORMS,
    Candidate,
    grid_value,
)
from fewear.diagnose.joint.forward import WearHistory
from fewear.diagnose.joint.measured import JointMeasurements
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.errors import FewearInputError
from fewear.mesh.profile import periodic_linear_rows
from fewear.wear.extensions import (
    NoExtension,
    RunningInCycles,
    distance_at_effective_m,
)

RUNNING_IN_REACH = 3
"""The believed model runs this many times further than the other candidates (running-in)."""


@dataclass(frozen=True, eq=False)
class Observations:
    """The measured depths as one vector: profile points (angle in the instrument's frame) and
    maximum depths (angle NaN), each with its cycle count and whether it trains."""

    cycles: np.ndarray
    angle_rad: np.ndarray
    depth_m: np.ndarray
    train: np.ndarray

    @cached_property
    def is_profile(self) -> np.ndarray:
        return np.isfinite(self.angle_rad)

    @cached_property
    def counts(self) -> np.ndarray:
        """The cycle counts measured at, ascending."""
        return np.unique(self.cycles)

    @cached_property
    def count_row(self) -> np.ndarray:
        """Each observation's row in :attr:`counts`."""
        return np.searchsorted(self.counts, self.cycles)


def observations(data: JointMeasurements, held_out_fraction: float) -> Observations:
    """Stack the profiles and maximum depths; the last ``held_out_fraction`` of the cycle counts
    (at least one, leaving at least one) are held out."""
    counts = sorted(set(data.cycle_counts) - {0})
    if len(counts) < 2:
        raise FewearInputError(
            f"joint wear data at {len(counts)} cycle count(s) > 0: a life-prediction diagnosis "
            "needs measurements at >= 2 cycle counts (the later ones are held out)")
    n_held = min(max(1, round(held_out_fraction * len(counts))), len(counts) - 1)
    first_held = counts[len(counts) - n_held]
    cycles, angle, depth = [], [], []
    for profile in data.profiles:
        cycles.append(np.full(profile.angle_rad.size, float(profile.cycles)))
        angle.append(profile.angle_rad)
        depth.append(profile.depth_m)
    if data.max_wear is not None:
        cycles.append(np.asarray(data.max_wear[0], dtype=float))
        angle.append(np.full(len(data.max_wear[0]), np.nan))
        depth.append(np.asarray(data.max_wear[1], dtype=float))
    cycles = np.concatenate(cycles)
    keep = cycles > 0
    cycles = cycles[keep]
    return Observations(cycles, np.concatenate(angle)[keep], np.concatenate(depth)[keep],
                        cycles < first_held)


@dataclass(frozen=True, eq=False)
class Fit:
    """A model fitted on the training data: parameters x = (phi_deg[, ln s, extra...]), by
    name in ``params``; ``form``: the cause's form; ``running_in_form``: the form of running-in
    on top of it (a pair, :mod:`fewear.diagnose.joint.pairs`)."""

    name: str
    x: np.ndarray
    n_params: int
    sse_train: float
    n_train: int
    held_out_rms_m: float
    train_rms_m: float
    residuals_m: np.ndarray
    params: dict = field(default_factory=dict)
    form: str | None = None
    forms_tried: int = 1
    running_in_form: str | None = None

    @property
    def aicc(self) -> float:
        """AICc on the training data (:func:`training_aicc`)."""
        return training_aicc(self.sse_train, self.n_train, self.n_params)

    def held_out_gain(self, reference: Fit) -> float:
        """1 - (held-out RMS error) / (``reference``'s): how much better this fit predicts the
        held-out data."""
        return 1.0 - self.held_out_rms_m / reference.held_out_rms_m


def training_aicc(rss: float, n_observations: int, n_parameters: int) -> float:
    """The AICc of :func:`fewear.diagnose.core.statistics.aicc`, but where n - k - 1 <= 0 the
    small-sample correction's denominator is clamped to 1 rather than the criterion undefined:
    a joint's few training profiles may hold no more points than a pair's parameters, and its
    fits are still compared."""
    n, k = n_observations, n_parameters
    if n - k - 1 > 0:
        return aicc(rss, n, k)
    return n * math.log(rss / n) + 2 * k + 2 * k * (k + 1)


def _mixed_depth(candidate: Candidate, position: float, scale: float, cycles: np.ndarray,
                 time_map: tuple[float, float] | None = None) -> np.ndarray:
    """The worn bore (m, n) at level ``scale`` after each of ``cycles`` (m,), interpolated at
    ``position`` between the runs (each run's cycles mapped by :func:`_run_depths`)."""
    runs = candidate.runs
    if len(runs) == 1:
        return _run_depths(candidate, 0, scale, cycles, time_map)
    position = min(max(float(position), 0.0), len(runs) - 1.0)
    k = min(int(position), len(runs) - 2)
    w = position - k
    return ((1 - w) * _run_depths(candidate, k, scale, cycles, time_map)
            + w * _run_depths(candidate, k + 1, scale, cycles, time_map))


def _run_depths(candidate: Candidate, index: int, scale: float, cycles: np.ndarray,
                time_map: tuple[float, float] | None) -> np.ndarray:
    """Run ``index``'s worn bore (m, n) at level ``scale`` after each of ``cycles`` (m,): its
    cycles mapped by the ratio of the levels (Archard's depth along the loop is a function of
    k N) or, with ``time_map`` = (r - 1, s0 or N0), node by node through the running-in
    form's (:func:`running_in_time_map`)."""
    run = candidate.runs[index]
    if time_map is None:
        return run.nodal_depths_m(scale / candidate.k_scale(index) * cycles)
    return run.nodal_depth_each_m(running_in_time_map(
        cycles[:, None], run, candidate.map_form, *time_map, scale, candidate.run_extension,
        candidate.k_scale(index)))


def running_in_time_map(cycles, run: WearHistory, form: str, extra: float,
                        scale: float, k_scale: float = 1.0,
                        run_extension=None, run_k_scale: float = 1.0) -> np.ndarray:
    """Per node a, the cycles of ``run`` after which the node has worn what the model with the
    running-in ``form`` (r - 1 = ``extra``, s0 or N0 = ``scale``) and the wear coefficient's
    level s = ``k_scale`` wears after ``cycles`` N: s S_eff(N d_a) = s_run S_eff,run(N' d_a),
    N' = S_eff,run^-1(s S_eff(N d_a) / s_run) / d_a, with d_a the node's advance per cycle on the
    form's axis (:func:`_advance_per_cycle`) and the run made with level s_run = ``run_k_scale``
    and running-in ``run_extension`` of the same form (None: the believed run, N' = s tau_a(N),
    tau_a of the module docstring). ``cycles``: a number, or a column (m, 1) of counts for
    (m, n) at once."""
    per_cycle = _advance_per_cycle(run, form)
    extension = _on_node_axis(RUNNING_IN_FORMS[form](1.0 + extra, scale))
    effective = k_scale / run_k_scale * extension.effective_distance_m(cycles * per_cycle)
    return distance_at_effective_m(_on_node_axis(run_extension or NoExtension()),
                                   effective) / per_cycle


def _advance_per_cycle(run: WearHistory, form: str) -> np.ndarray:
    """How far each node moves per crank cycle along the axis the running-in ``form`` falls on:
    its sliding distance (m), or one cycle for the forms driven by the crank cycles."""
    if issubclass(RUNNING_IN_FORMS[form], RunningInCycles):
        return np.ones_like(run.sliding_m_per_cycle)
    return np.maximum(run.sliding_m_per_cycle, 1e-300)


def _on_node_axis(extension):
    """The extension as a law of the node's advance along its axis: a form driven by the crank
    cycles is its law of the sliding distance with the cycles for the distance."""
    if isinstance(extension, RunningInCycles):
        return extension.on_cycle_axis()
    return extension


def _nodal_predictions(candidate: Candidate, x: np.ndarray, cycles: np.ndarray) -> np.ndarray:
    """The cause's nodal depths after each of ``cycles`` (m,) at the parameters x (s tau(N) on
    the runs): (m, n), all counts at once (a fit evaluates the model tens of thousands of
    times)."""
    if x.size < 2:
        return candidate.runs[0].nodal_depths_m(cycles)
    scale = math.exp(x[1])
    time_map = (math.exp(x[2]), math.exp(x[3])) if candidate.time_map else None
    position = x[candidate.position_index] if len(candidate.runs) > 1 else 0.0
    return _mixed_depth(candidate, position, scale, cycles, time_map)


def predict(obs: Observations, x: np.ndarray, candidate: Candidate) -> np.ndarray:
    """The model's depth at every observation for the parameters x."""
    out = np.empty(obs.depth_m.size)
    nodal = _nodal_predictions(candidate, x, obs.counts)
    profile, maximum = obs.is_profile, ~obs.is_profile
    # the loop's node angles: a valid periodic table
    out[profile] = periodic_linear_rows(candidate.runs[0].angle_rad, nodal,
                                        obs.angle_rad[profile] + math.radians(x[0]),
                                        obs.count_row[profile])
    out[maximum] = nodal.max(axis=1)[obs.count_row[maximum]]
    return out


def _sse(x, obs: Observations, candidate: Candidate, mask: np.ndarray, bounds) -> float:
    clipped = np.minimum(np.maximum(x, bounds[:, 0]), bounds[:, 1])
    r = obs.depth_m[mask] - predict(obs, clipped, candidate)[mask]
    return float(r @ r) * (1.0 + float(np.sum((x - clipped) ** 2)))


def fit(name: str, candidate: Candidate, obs: Observations, starts: list[np.ndarray],
        bounds: np.ndarray) -> Fit:
    """Least squares on the training observations from each start; scored on the held-out.
    Nelder-Mead stops when its simplex spans at most 1e-4 in every parameter (deg, ln s, ...);
    the spread of its SSE values is not a criterion (``fatol`` inf; scipy stops only when both
    hold, and an SSE in m^2 has no scale of its own: a fatol of 1e-24 m^2 had the simplex shrink
    to about 1e-7 in x, twice the evaluations for nothing the data resolve)."""
    best = None
    for start in starts:
        result = optimize.minimize(_sse, start, args=(obs, candidate, obs.train, bounds),
                                   method="Nelder-Mead",
                                   options={"xatol": 1e-4, "fatol": math.inf, "maxiter": 2000})
        if best is None or result.fun < best.fun:
            best = result
    x = np.clip(best.x, bounds[:, 0], bounds[:, 1])
    residuals = obs.depth_m - predict(obs, x, candidate)
    train, held = residuals[obs.train], residuals[~obs.train]
    n_params = x.size - (0 if candidate.level_free or x.size < 2 else 1)
    return Fit(name, x, n_params, float(train @ train), int(train.size),
               float(np.sqrt(np.mean(held**2))), float(np.sqrt(np.mean(train**2))), residuals)


def offset_fit(name: str, run: WearHistory, obs: Observations, start_deg: float,
               max_offset_deg: float) -> Fit:
    """The model of one ``run`` fitted with its angular offset only (from ``start_deg``, within
    +- ``max_offset_deg``; the level of k as run)."""
    return fit(name, Candidate(name, (run,)), obs, [np.array([start_deg])],
               np.array([(-max_offset_deg, max_offset_deg)]))


def offset_start(obs: Observations, base: Candidate, max_offset_deg: float) -> float:
    """The offset (deg) that best aligns the training profiles with the believed model scaled to
    the measured depth (a scan in 1 deg steps)."""
    offsets = np.arange(-max_offset_deg, max_offset_deg + 0.5, 1.0)
    profile = obs.train & obs.is_profile
    if not profile.any():
        return 0.0
    errors = []
    for offset in offsets:
        model = predict(obs, np.array([offset]), base)[profile]
        scale = float(model @ obs.depth_m[profile]) / max(float(model @ model), 1e-300)
        errors.append(np.sum((obs.depth_m[profile] - scale * model) ** 2))
    return float(offsets[int(np.argmin(errors))])


def fit_candidate(forms: tuple[Candidate, ...], obs: Observations, offset_deg: float,
                  settings: JointDiagnoseSettings) -> Fit:
    """Fit a cause (s free, plus its own parameters) from a few starts, in each of its
    ``forms``; the best on the training data is kept."""
    return best_form([fit_form(form, obs, offset_deg, settings) for form in forms])


def best_form(fits: list[Fit]) -> Fit:
    """The form's fit best on the training data, counting the forms tried."""
    return replace(min(fits, key=lambda f: f.sse_train), forms_tried=len(fits))


def fit_form(candidate: Candidate, obs: Observations, offset_deg: float,
             settings: JointDiagnoseSettings, starts: list[np.ndarray] | None = None) -> Fit:
    """:func:`fit_candidate` for one form, from ``starts`` (x without a discrete choice's run
    index) or from each level of (1, e^-0.5, e^0.5) times the form's own starts (the level 1
    alone where it is not free)."""
    bounds, extra_starts = bounds_and_starts(candidate, obs, settings)
    if starts is None:
        starts = [np.array([offset_deg, ln_s, *extra])
                  for ln_s in ((0.0, -0.5, 0.5) if candidate.level_free else (0.0,))
                  for extra in extra_starts]
    if candidate.discrete:
        result = best_run(candidate, obs, starts, bounds)
    else:
        result = fit(candidate.name, candidate, obs, starts, bounds)
    return with_params(result, candidate)


def bounds_and_starts(candidate: Candidate, obs: Observations,
                      settings: JointDiagnoseSettings) -> tuple[np.ndarray, list[tuple]]:
    """The bounds of x = (phi_deg, ln s, extra...) and the starts of the extra parameters (a
    discrete choice's run index is not among them: :func:`best_run`)."""
    last_train = float(obs.cycles[obs.train].max())
    ln_max = math.log(settings.max_k_scale) if candidate.level_free else 0.0
    phi = settings.max_offset_deg
    bounds = [(-phi, phi), (-ln_max, ln_max)]
    extra_starts: list[tuple[float, ...]] = [()]
    if candidate.time_map:
        advance = _advance_per_cycle(candidate.runs[0], candidate.map_form)
        typical = float(np.median(advance[advance > 1e-300])) * last_train  # m slid or cycles
        bounds += [(math.log(0.05), math.log(2.0 * RUNNING_IN_REACH - 1.0)),
                   (math.log(1e-3 * typical), math.log(10.0 * typical))]
        extra_starts = [(math.log(r), math.log(f * typical)) for r in (0.5, 3.0)
                        for f in (0.03, 0.3)]
    if len(candidate.runs) > 1 and not candidate.discrete:
        top = len(candidate.runs) - 1.0
        bounds += [(0.0, top)]
        extra_starts = [(*extra, p) for extra in extra_starts
                        for p in np.linspace(0.0, top, len(candidate.runs))]
    return np.array(bounds), extra_starts


def best_run(candidate: Candidate, obs: Observations, starts, bounds) -> Fit:
    """The discrete choice: each run fitted alone (offset, level and a time map's parameters),
    the best on the training data kept; its x gets the run's index, and the choice counts as
    one parameter."""
    best, best_index = None, 0
    for index, run in enumerate(candidate.runs):
        alone = replace(candidate, runs=(run,), grid=(), k_scales=(candidate.k_scale(index),))
        result = fit(candidate.name, alone, obs, starts, np.asarray(bounds))
        if best is None or result.sse_train < best.sse_train:
            best, best_index = result, index
    return replace(best, x=np.append(best.x, float(best_index)), n_params=best.n_params + 1)


def with_params(result: Fit, candidate: Candidate) -> Fit:
    """``result`` with its parameters by name (``params``) and its forms."""
    x = result.x
    params = {"angle_offset_deg": float(x[0])}
    if x.size > 1:
        params["k_scale"] = float(math.exp(x[1]))
    if candidate.time_map:
        params.update(RUNNING_IN_FORMS[candidate.map_form](1.0 + float(math.exp(x[2])),
                                                           float(math.exp(x[3]))).params())
    if len(candidate.runs) > 1:
        value = grid_value(candidate, float(x[candidate.position_index]))
        if candidate.parameter_scales_with_level:  # s rescales the cycle axis: all wear
            value *= params["k_scale"]
        params[candidate.parameter] = value
    return replace(result, params=params, form=candidate.form or None,
                   running_in_form=candidate.running_in_form or None)


def needed_cycles(obs: Observations, settings: JointDiagnoseSettings) -> float:
    """The shortest time axis a fit needs: the last count / max_k_scale."""
    return float(obs.cycles.max()) / settings.max_k_scale


