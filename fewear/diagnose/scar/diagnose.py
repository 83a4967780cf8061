"""Is the believed scar model wrong on a measured scar, and by which cause? Each cause is one
log-scale factor on a wear coefficient, fitted to the profile points with a few forward runs and
judged on held-out folds of the profile against the believed model, on effective observations
(neighbouring points are correlated). The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, replace

import numpy as np

from fewear.diagnose.core.evidence import Evidence
from fewear.diagnose.core.statistics import aicc, nested_f_test_p
from fewear.diagnose.scar.catalogue import SCALED
from fewear.diagnose.scar.fitting import FactorFit, ForwardRuns, fit_log_factor
from fewear.diagnose.scar.measured import MeasuredScar
from fewear.diagnose.scar.settings import ScarDiagnoseSettings
from fewear.errors import FewearInputError
from fewear.parallel import side_by_side


@dataclass(frozen=True, eq=False)
class CauseTrial:
    """One cause fitted and judged: the fit on all points and per fold (``fold_fits``), the
    prediction at the fit (``fitted_m``, per point) and each point's held-out prediction
    (``held_out_m``), the held-out RMS errors (m) of the believed model and the cause, the
    effective observations, the evidence, whether the rule ``accepted`` it, the factors run
    and their wall time (s)."""

    cause: str
    fit: FactorFit
    fold_fits: tuple[FactorFit, ...]
    fitted_m: np.ndarray
    held_out_m: np.ndarray
    held_out_rms_before_m: float
    held_out_rms_after_m: float
    effective_observations: int
    evidence: Evidence
    accepted: bool
    factors_run: tuple[float, ...]
    run_wall_time_s: float

    @property
    def converged(self) -> bool:
        return self.fit.converged and all(fit.converged for fit in self.fold_fits)


@dataclass(frozen=True, eq=False)
class ScarDiagnosis:
    """What :func:`diagnose_scar` found: the believed prediction per point (``believed_m``),
    the trials, the causes named (largest held-out gain first), the causes not testable in the
    case (name -> why), how points were held out, notes (a fit that did not converge or stopped
    at the search's bound) and the wall time (s)."""

    measured: MeasuredScar
    settings: ScarDiagnoseSettings
    believed_m: np.ndarray
    holdout: str
    trials: tuple[CauseTrial, ...]
    causes: tuple[str, ...]
    untestable: dict
    notes: tuple[str, ...]
    wall_time_s: float

    @property
    def best_trial(self) -> CauseTrial | None:
        """The named cause's trial, else the trial of the largest held-out gain."""
        named = [trial for trial in self.trials if trial.cause in self.causes[:1]]
        return (named or sorted(self.trials, key=lambda trial: -trial.evidence.gain) or [None])[0]


def held_out_folds(measured: MeasuredScar, blocks: int) -> tuple[tuple[np.ndarray, str], ...]:
    """The folds as boolean masks of the FITTED points (the rest held out), each point held out
    once, and what the folds are (docs/diagnosis-method-notes.md)."""
    profile = measured.profile_of_point
    if len(measured.names) > 1:
        return tuple((profile != index, f"{name} held out, fitted on the other profiles")
                     for index, name in enumerate(measured.names))
    block_of = np.concatenate([np.full(part.size, block) for block, part in
                               enumerate(np.array_split(np.arange(measured.x_m.size), blocks))])
    even = block_of % 2 == 0
    return ((even, f"odd blocks of {blocks} held out, fitted on the even"),
            (~even, f"even blocks of {blocks} held out, fitted on the odd"))


def effective_observations(residual_m: np.ndarray, profile: np.ndarray) -> int:
    """N_eff = sum over profiles of n_p (1 - r_p) / (1 + r_p), rounded down (module
    docstring)."""
    total = 0.0
    for index in np.unique(profile):
        r = residual_m[profile == index] - residual_m[profile == index].mean()
        lag_one = float(np.sum(r[1:] * r[:-1]) / np.sum(r**2)) if np.any(r) else 0.0
        lag_one = min(max(lag_one, 0.0), 1.0 - 1e-12)
        total += r.size * (1.0 - lag_one) / (1.0 + lag_one)
    return int(math.floor(total))


def nested_evidence(measured_m: np.ndarray, believed_m: np.ndarray, fitted_m: np.ndarray,
                    n_effective: int, gain: float) -> Evidence:
    """The F-test's p and the AICc improvement of the one-parameter fit against the believed
    model on ``n_effective`` observations (the method notes), with the held-out ``gain``."""
    n = measured_m.size
    rss_believed = float(np.sum((believed_m - measured_m) ** 2))
    rss_fitted = float(np.sum((fitted_m - measured_m) ** 2))
    p_value = nested_f_test_p(rss_believed, rss_fitted, 1, n_effective - 1)
    improvement = (aicc(rss_believed * n_effective / n, n_effective, 0)
                   - aicc(rss_fitted * n_effective / n, n_effective, 1))
    return Evidence(p_value, gain, improvement)


def _rms(values: np.ndarray) -> float:
    return float(np.sqrt(np.mean(values**2)))


def try_cause(cause: str, measured: MeasuredScar, believed_m: np.ndarray, predict,
              folds, settings: ScarDiagnoseSettings, report=None) -> CauseTrial:
    """Fit ``cause`` on all points and on each fold (``predict(factor)``: the depths at the
    points, one forward run) and judge it against the believed model (the method notes)."""
    measured_m, scales_area = measured.depth_points_m, SCALED[cause].scales_worn_area
    runs = ForwardRuns(believed_m, predict, report)
    every = np.ones(measured_m.size, dtype=bool)
    fit = fit_log_factor(runs, measured_m, every, settings, scales_area)
    fold_fits, held_out_m = [], np.empty_like(measured_m)
    for fitted, _ in folds:
        fold_fits.append(fit_log_factor(runs, measured_m, fitted, settings, scales_area))
        held_out_m[~fitted] = runs.depth_m(fold_fits[-1].log_factor)[~fitted]
    fitted_m = runs.depth_m(fit.log_factor)
    before, after = _rms(believed_m - measured_m), _rms(held_out_m - measured_m)
    n_effective = effective_observations(fitted_m - measured_m, measured.profile_of_point)
    evidence = nested_evidence(measured_m, believed_m, fitted_m, n_effective, 1.0 - after / before)
    return CauseTrial(cause, fit, tuple(fold_fits), fitted_m, held_out_m, before, after,
                      n_effective, evidence, False, runs.factors, runs.wall_time_s)


def diagnose_scar(measured: MeasuredScar, model, settings: ScarDiagnoseSettings,
                  progress: bool = True) -> ScarDiagnosis:
    """The diagnosis of ``measured`` against ``model`` (a
    :class:`fewear.diagnose.scar.forward.ScarModel`, or anything with its ``depth_on`` and
    ``untestable_reason``), a progress line per forward run on stderr when ``progress``. The
    believed model is run here; the causes' fits, independent of one another, side by side in
    worker processes (:func:`fewear.parallel.side_by_side`; a picklable ``model`` then), each
    the same runs as alone."""
    start = time.perf_counter()
    untestable = {cause: reason for cause in settings.candidates
                  if (reason := model.untestable_reason(cause)) is not None}
    tried = [cause for cause in settings.candidates if cause not in untestable]
    if not tried:
        raise FewearInputError(
            f"[scar_diagnose] candidates = {list(settings.candidates)!r}: none can be fitted in "
            "this case (" + "; ".join(f"{cause}: {why}" for cause, why in untestable.items())
            + ")")
    believed_m = _predictor(model, measured, tried[0])(1.0)
    folds = held_out_folds(measured, settings.profile_blocks)
    rule = settings.acceptance.rule(len(tried))
    trials = [replace(trial, accepted=rule.accepts(trial.evidence)) for trial in side_by_side(
        fitted_cause, [(cause, measured, believed_m, model, folds, settings, progress)
                       for cause in tried])]
    causes = tuple(trial.cause for trial in sorted(trials, key=lambda trial: -trial.evidence.gain)
                   if trial.accepted)
    return ScarDiagnosis(measured, settings, believed_m, "; ".join(text for _, text in folds),
                         tuple(trials), causes, untestable, tuple(_fit_notes(trials, settings)),
                         time.perf_counter() - start)


def fitted_cause(cause: str, measured: MeasuredScar, believed_m: np.ndarray, model, folds,
                 settings: ScarDiagnoseSettings, progress: bool) -> CauseTrial:
    """:func:`try_cause` of ``cause`` with ``model``'s forward runs, a progress line per run on
    this process's stderr when ``progress``: one cause's whole fit, a call that
    :func:`diagnose_scar` hands to a worker process."""
    return try_cause(cause, measured, believed_m, _predictor(model, measured, cause), folds,
                     settings, _reporter(cause) if progress else None)


def _predictor(model, measured: MeasuredScar, cause: str):
    """``predict(factor)``: the model's depths at every measured point (m), one forward run."""
    profiles = len(measured.names)
    return lambda factor: np.tile(model.depth_on(measured.x_m, cause, factor), profiles)


def _reporter(cause: str):
    """``report(factor, seconds)``: a forward run's progress line on stderr."""
    def report(factor, seconds):
        print(f"fewear diagnose: {cause} x{factor:.4g}: forward run in {seconds:.1f} s",
              file=sys.stderr, flush=True)
    return report


def _fit_notes(trials, settings: ScarDiagnoseSettings) -> list[str]:
    """A sentence per fit that did not converge or stopped at the search's bound."""
    notes = []
    for trial in trials:
        for label, fit in [("all points", trial.fit)] + [
                (f"fold {index + 1}", fit) for index, fit in enumerate(trial.fold_fits)]:
            if not fit.converged:
                notes.append(f"{trial.cause} ({label}): NOT converged after "
                             f"{len(trial.factors_run)} forward runs (max_forward_runs = "
                             f"{settings.max_forward_runs}): factor {fit.factor:.4g} is the "
                             "surrogate's between runs, not a run's")
            if fit.at_bound:
                notes.append(f"{trial.cause} ({label}): factor {fit.factor:.4g} at the "
                             f"search's bound (max_k_factor = {settings.max_k_factor:g})")
    return notes
