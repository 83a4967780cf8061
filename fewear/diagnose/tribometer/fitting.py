"""Fitting the causes' laws in a stage of the tribometer diagnosis (a regression of ln V or of the
tests' levels), scoring them on whole tests held out, and the forward selection of causes (the
method is in :mod:`fewear.diagnose.tribometer.diagnose`)."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np
from scipy import optimize

from fewear.diagnose.core.evidence import AcceptanceRule, Evidence
from fewear.diagnose.core.statistics import aicc, nested_f_test_p, paired_improvement_p
from fewear.diagnose.tribometer.catalogue import Context, Form, forms_of
from fewear.diagnose.tribometer.settings import DiagnoseSettings


@dataclass(frozen=True)
class Stage:
    """One regression of the diagnosis: ``y`` per row (ln V - ln F - ln s for readings, or a
    test's level), an intercept ``group`` per row, the held-out ``unit`` (test) of each row, what
    the laws read (``context``) and the forms that can be tested here."""

    name: str
    y: np.ndarray
    group: np.ndarray
    unit: np.ndarray
    context: Context
    forms: tuple[Form, ...]

    @property
    def n_groups(self) -> int:
        return int(self.group.max()) + 1


@dataclass(frozen=True)
class StageFit:
    """Fitted forms (with their search vectors and laws), intercepts per group, residuals."""

    forms: tuple[Form, ...]
    x: tuple[np.ndarray, ...]
    laws: tuple[Any, ...]
    intercepts: np.ndarray
    residuals: np.ndarray

    @property
    def n_parameters(self) -> int:
        return sum(v.size for v in self.x)

    @property
    def rss(self) -> float:
        """The residual sum of squares."""
        return float(np.sum(self.residuals**2))


def _log_model(stage: Stage, forms, xs) -> tuple[np.ndarray, tuple]:
    laws = tuple(form.law(x, stage.context) for form, x in zip(forms, xs))
    total = np.zeros(stage.y.size)
    for law in laws:
        total = total + law.log_multiplier(stage.context)
    return total, laws


def _intercepts(stage: Stage, z: np.ndarray, rows: np.ndarray) -> np.ndarray:
    counts = np.bincount(stage.group[rows], minlength=stage.n_groups).astype(float)
    with np.errstate(invalid="ignore", divide="ignore"):
        return np.bincount(stage.group[rows], z[rows], stage.n_groups) / counts


def _split(x: np.ndarray, forms) -> tuple[np.ndarray, ...]:
    sizes = np.cumsum([len(form.bounds) for form in forms])[:-1]
    return tuple(np.split(np.asarray(x, float), sizes))


def fit_stage(stage: Stage, forms: tuple[Form, ...], starts: list[np.ndarray],
              rows: np.ndarray | None = None) -> StageFit:
    """Least-squares fit of ``forms`` on ``rows`` (all by default): intercepts profiled in closed
    form (group means), the laws' parameters by :func:`scipy.optimize.least_squares` from the best
    of ``starts`` (each a concatenated search vector)."""
    rows = np.ones(stage.y.size, bool) if rows is None else rows

    def residuals(x):
        f, _ = _log_model(stage, forms, _split(x, forms))
        z = stage.y - f
        return (z - _intercepts(stage, z, rows)[stage.group])[rows]

    if forms:
        costs = [np.sum(residuals(start) ** 2) for start in starts]
        start = starts[int(np.argmin(costs))]
        lower, upper = np.array([b for form in forms for b in form.bounds]).T
        x = optimize.least_squares(residuals, np.clip(start, lower, upper), bounds=(lower, upper),
                                   xtol=1e-6, ftol=1e-8).x
    else:
        x = np.zeros(0)
    xs = _split(x, forms) if forms else ()
    f, laws = _log_model(stage, forms, xs)
    z = stage.y - f
    intercepts = _intercepts(stage, z, rows)
    return StageFit(forms, xs, laws, intercepts, z - intercepts[stage.group])


def scatter_weights(residuals: np.ndarray, log_volume: np.ndarray,
                    test: np.ndarray) -> np.ndarray:
    """Weights 1 / var(ln V_i), mean 1, of readings of the wear volume V along tests (``test``
    per reading), from a model's ``residuals`` in ln V and fitted ``log_volume`` ln V.

    A weighing or a profile reads V with errors of three sizes: in proportion to V (sd
    a^1/2 V), of their own size (balance resolution: b^1/2 V_m, V_m the median reading), and in
    proportion to the test's wear as a whole (debris, a transfer layer, a zero offset of the
    test: c^1/2 V_T, V_T the test's largest reading). In ln V (delta method)
    var_i = a + b (V_m / V_i)^2 + c (V_T / V_i)^2: an early reading, or one near the resolution,
    says little about its test's level. a, b and c by maximum likelihood (Gaussian), with the
    model's fitted volumes (the measured ones would weight a reading by its own error); b = c = 0
    gives equal weights. The residuals must be those of a model that holds the shape of the wear
    curves (else the variance model takes a misfit of the early readings for their scatter)."""
    residual_sq = residuals**2
    mean_sq = float(np.mean(residual_sq))
    if not mean_sq > 0.0:
        return np.ones(residuals.size)
    largest = np.full(int(test.max()) + 1, -np.inf)
    np.maximum.at(largest, test, log_volume)
    sizes = np.exp(2.0 * np.array([np.zeros(residuals.size), np.median(log_volume) - log_volume,
                                   largest[test] - log_volume]))

    def variance(theta):
        return mean_sq * (np.exp(theta) @ sizes)

    def negative_log_likelihood(theta):
        v = variance(theta)
        return float(np.sum(np.log(v) + residual_sq / v))

    theta = optimize.minimize(negative_log_likelihood, np.array([0.0, -4.0, -4.0]),
                              method="L-BFGS-B", bounds=[(-12.0, 3.0), (-30.0, 3.0),
                                                         (-30.0, 3.0)]).x
    weight = 1.0 / variance(theta)
    return weight / weight.mean()


MAX_HELD_OUT_FOLDS = 200
"""Up to this many tests each is held out alone; more are held out in this many folds (every
test once), so that a table of 20,000 tests costs 200 refits per model, not 20,000."""


def held_out_errors(stage: Stage, fit: StageFit) -> np.ndarray:
    """Held-out mean squared error of each unit (NaN where it cannot be predicted): leave one
    test out, or with more than :data:`MAX_HELD_OUT_FOLDS` tests leave a fold of tests out.

    The laws are refitted without the fold (from the full fit's parameters); a unit's intercept
    comes from the trained tests of its group, or, where the intercept is the unit's own (a
    test's level), from the held-out rows: the same nuisance level for every model compared."""
    start = [np.concatenate(fit.x)] if fit.forms else []
    errors = np.full(int(stage.unit.max()) + 1, np.nan)
    units = np.unique(stage.unit)
    fold_of_unit = np.zeros(errors.size, int)
    fold_of_unit[units] = np.arange(units.size) % min(units.size, MAX_HELD_OUT_FOLDS)
    fold = fold_of_unit[stage.unit]
    for k in np.unique(fold):
        held = fold == k
        train = ~held
        if not train.any():
            continue
        trained = fit_stage(stage, fit.forms, start, train)
        f, _ = _log_model(stage, fit.forms, trained.x)
        z = stage.y - f
        own = _intercepts(stage, z, held)
        level = np.where(np.isfinite(trained.intercepts), trained.intercepts, own)
        squared = (z - level[stage.group]) ** 2
        held_units = np.unique(stage.unit[held])
        counts = np.bincount(stage.unit[held], minlength=errors.size)
        sums = np.bincount(stage.unit[held], squared[held], minlength=errors.size)
        errors[held_units] = sums[held_units] / counts[held_units]
    return errors


# ---------------------------------------------------------------------------------------------
# Forward selection in a stage


@dataclass(frozen=True, eq=False)
class Trial:
    """One cause tried at a step of a stage: its best ``form`` (of ``forms_tried``) fitted jointly
    with the current model (``fit``, the form's ``params``), each test's held-out mean squared
    error (``errors``) and the current model's RMS one (``held_out_error_before``), the nested
    ``test`` ("F" or "paired t") and the evidence, whether it is ``accepted`` and why
    (``verdict``)."""

    cause: str
    form: str
    stage: str
    params: dict[str, float]
    fit: StageFit
    errors: np.ndarray
    held_out_error_before: float
    test: str
    forms_tried: int
    tests_improved: str
    training_error: float
    evidence: Evidence
    accepted: bool = False
    verdict: str = ""

    @property
    def held_out_error(self) -> float:
        """RMS held-out error over the tests that could be predicted."""
        return held_out_rms(self.errors)


@dataclass(frozen=True)
class StageResult:
    """What a stage found: its baseline and final fits with their held-out errors per test, the
    chosen causes (in the order they joined), every step's trials and each chosen
    cause's held-out gain when it joined."""

    stage: Stage
    baseline: StageFit
    baseline_errors: np.ndarray
    final: StageFit
    final_errors: np.ndarray
    chosen: tuple[str, ...]
    steps: tuple[tuple[Trial, ...], ...]
    gains: dict[str, float]

    @property
    def baseline_rms(self) -> float:
        return held_out_rms(self.baseline_errors)

    @property
    def final_rms(self) -> float:
        return held_out_rms(self.final_errors)


def select_causes(stage: Stage, causes: tuple[str, ...], settings: DiagnoseSettings,
                  progress=None) -> StageResult:
    """Forward selection of ``causes`` in ``stage`` (module docstring for the rule);
    ``progress(text)``, when given, hears of each cause tried (a large table takes minutes)."""
    progress = progress or (lambda text: None)
    current = fit_stage(stage, (), [])
    baseline, current_errors = current, held_out_errors(stage, current)
    baseline_errors = current_errors
    chosen, steps, gains = [], [], {}
    while True:
        untried = [c for c in causes if c not in chosen
                   and any(form in stage.forms for form in forms_of(c))]
        if not untried:
            break
        tried = []
        for cause in untried:
            progress(f"{stage.name}: step {len(steps) + 1}, trying {cause}")
            if (trial := _try_cause(stage, current, current_errors, cause)) is not None:
                tried.append(trial)
        if not tried:
            break
        rule = settings.acceptance.rule(sum(trial.forms_tried for trial in tried))
        judged = tuple(_judged(trial, rule) for trial in tried)
        steps.append(judged)
        accepted = [trial for trial in judged if trial.accepted]
        if not accepted:
            break
        best = min(accepted, key=lambda trial: -trial.evidence.aicc_improvement if trial.test == "F"
                   else trial.held_out_error)
        gains[best.cause] = best.evidence.gain
        chosen.append(best.cause)
        current, current_errors = best.fit, best.errors
    return StageResult(stage, baseline, baseline_errors, current, current_errors, tuple(chosen),
                       tuple(steps), gains)


def held_out_rms(errors: np.ndarray) -> float:
    """RMS held-out error over the tests that could be predicted (errors: mean squares per test)."""
    return float(np.sqrt(np.nanmean(errors)))


def _try_cause(stage: Stage, current: StageFit, current_errors: np.ndarray,
               cause: str) -> Trial | None:
    """The cause's best form fitted jointly with ``current``, its held-out errors and evidence
    (None when no form has a start, e.g. a threshold without two distinct values)."""
    fits = []
    for form in (f for f in forms_of(cause) if f in stage.forms):
        fixed = np.concatenate(current.x) if current.forms else np.zeros(0)
        starts = [np.concatenate([fixed, np.array(s, float)]) for s in form.starts(stage.context)]
        if starts:
            fits.append(fit_stage(stage, current.forms + (form,), starts))
    if not fits:
        return None
    fit = min(fits, key=lambda f: float(np.sum(f.residuals**2)))
    errors = held_out_errors(stage, fit)
    n_base = current.n_parameters + stage.n_groups
    n_fuller = n_base + fit.x[-1].size
    one_row_per_unit = np.unique(stage.unit).size == stage.unit.size
    if one_row_per_unit:
        test, p_value = "F", nested_f_test_p(current.rss, fit.rss, n_fuller - n_base,
                                             stage.y.size - n_fuller)
    else:
        test, p_value = "paired t", paired_improvement_p(current_errors, errors)
    aicc_improvement = (aicc(current.rss, stage.y.size, n_base)
                        - aicc(fit.rss, stage.y.size, n_fuller))
    return Trial(
        cause=cause, form=fit.forms[-1].name, stage=stage.name, params=fit.laws[-1].params(),
        fit=fit, errors=errors, held_out_error_before=held_out_rms(current_errors), test=test,
        forms_tried=len(fits),
        tests_improved=f"{int(np.sum(errors < current_errors))} of "
                       f"{int(np.sum(np.isfinite(errors)))}",
        training_error=float(np.sqrt(np.mean(fit.residuals**2))),
        evidence=Evidence(p_value=p_value,
                          gain=1.0 - held_out_rms(errors) / held_out_rms(current_errors),
                          aicc_improvement=aicc_improvement,
                          effect_over_scatter=effect_over_scatter(current, fit)))


def effect_over_scatter(current: StageFit, fit: StageFit) -> float:
    """The largest change ``fit`` makes to a fitted ln V (the difference of the two fits'
    residuals on the same rows) over ``fit``'s RMS residual, the scatter of a reading once the
    cause is in the model (``current``'s residuals hold the effect itself: against them a cause
    that explains most of the misfit could never stand out)."""
    scatter = float(np.sqrt(np.mean(fit.residuals**2)))
    change = float(np.max(np.abs(current.residuals - fit.residuals)))
    return change / scatter if scatter > 0.0 else math.inf


def _judged(trial: Trial, rule: AcceptanceRule) -> Trial:
    """``trial`` accepted or not by ``rule``, with the verdict in words."""
    judged = replace(trial, accepted=rule.accepts(trial.evidence))
    return replace(judged, verdict=_verdict(judged, rule))


def _verdict(trial: Trial, rule: AcceptanceRule) -> str:
    evidence = trial.evidence
    shown = (f"{trial.test} p = {evidence.p_value:.2g}, held-out tests improved "
             f"{trial.tests_improved}, held-out gain {evidence.gain:+.0%}")
    if trial.accepted:
        return (f"accepted: {shown} (p < {rule.max_p:.2g}), AICc improvement "
                f"{evidence.aicc_improvement:+.1f}")
    if evidence.p_value >= rule.max_p:
        return f"rejected: not significant ({shown}; needs p < {rule.max_p:.2g})"
    if not rule.predicts_better(evidence):
        return f"rejected: predicts held-out tests no better ({shown})"
    if not rule.resolved(evidence):
        return (f"rejected: an effect the data do not resolve ({shown}): it changes no fitted "
                f"reading by more than {evidence.effect_over_scatter:.2g} times the scatter of "
                f"a reading (needs {rule.min_effect_over_scatter:g})")
    return (f"rejected: AICc improvement {evidence.aicc_improvement:+.1f} (needs >= "
            f"{rule.min_aicc_improvement:g}): the extra parameters do not pay for "
            "themselves in the fit")
