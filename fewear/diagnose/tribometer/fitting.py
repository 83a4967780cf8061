"""Fitting the causes' laws in a stage of the tribometer diagnosis (a regression of ln V or of the
tests' levels), scoring them on whole tests held out, and the forward selection of causes (the
method is in :mod:`fewear.diagnose.tribometer.diagnose`)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np
from scipy import optimize, stats

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


def held_out_errors(stage: Stage, fit: StageFit) -> np.ndarray:
    """Leave-one-test-out mean squared error of each unit (NaN where it cannot be predicted).

    The laws are refitted without the unit (from the full fit's parameters); its intercept comes
    from the other tests of its group, or, where the intercept is the unit's own (a test's level),
    from the unit's own rows: the same nuisance level for every model compared."""
    start = [np.concatenate(fit.x)] if fit.forms else []
    errors = np.full(int(stage.unit.max()) + 1, np.nan)
    for u in np.unique(stage.unit):
        held = stage.unit == u
        train = ~held
        if not train.any():
            continue
        trained = fit_stage(stage, fit.forms, start, train)
        f, _ = _log_model(stage, fit.forms, trained.x)
        z = stage.y - f
        own = _intercepts(stage, z, held)
        level = np.where(np.isfinite(trained.intercepts), trained.intercepts, own)
        errors[u] = float(np.mean((z[held] - level[stage.group[held]]) ** 2))
    return errors


def aicc(residuals: np.ndarray, n_parameters: int) -> float:
    """Corrected Akaike criterion of a least-squares fit (Hurvich & Tsai 1989)."""
    n = residuals.size
    rss = float(np.sum(residuals**2))
    if n - n_parameters - 1 <= 0 or rss <= 0.0:
        return float("nan")
    return (n * math.log(rss / n) + 2 * n_parameters
            + 2 * n_parameters * (n_parameters + 1) / (n - n_parameters - 1))


def extra_sum_of_squares_p(nested: StageFit, fuller: StageFit, n_nested: int) -> float:
    """p-value of the extra-sum-of-squares F-test of ``fuller`` against ``nested`` (n_nested
    parameters, intercepts included): F = ((RSS0 - RSS1) / q) / (RSS1 / (n - n_nested - q))
    (e.g. Seber & Wild, *Nonlinear Regression*, 1989, sec. 5.3)."""
    q = fuller.n_parameters - nested.n_parameters
    n = nested.residuals.size
    dof = n - n_nested - q
    rss0, rss1 = float(np.sum(nested.residuals**2)), float(np.sum(fuller.residuals**2))
    if dof <= 0 or rss1 <= 0.0:
        return 1.0
    f = max(rss0 - rss1, 0.0) / q / (rss1 / dof)
    return float(stats.f.sf(f, q, dof))


def paired_improvement_p(before: np.ndarray, after: np.ndarray) -> float:
    """One-sided p-value that ``after`` predicts the held-out tests better than ``before``: a
    paired t-test (Student) of the per-test log ratios ln(e_before / e_after) of the mean squared
    held-out errors, a comparison of predictive accuracy in the manner of Diebold & Mariano,
    J. Bus. Econ. Stat. 13 (1995) 253-263, on the log scale where a ratio of two error variances
    is near-symmetric. 1 with fewer than two tests."""
    d = np.log(before / after)
    d = d[np.isfinite(d)]
    if d.size < 2:
        return 1.0
    sd = float(np.std(d, ddof=1))
    if sd == 0.0:
        return 0.0 if d.mean() > 0.0 else 1.0
    return float(stats.t.sf(d.mean() / (sd / np.sqrt(d.size)), d.size - 1))


# ---------------------------------------------------------------------------------------------
# Forward selection in a stage


@dataclass(frozen=True)
class StageResult:
    """What a stage found: its baseline and final fits with their held-out errors per test, the
    chosen causes (in the order they joined), every step's candidate entries and each chosen
    cause's held-out gain when it joined."""

    stage: Stage
    baseline: StageFit
    baseline_errors: np.ndarray
    final: StageFit
    final_errors: np.ndarray
    chosen: tuple[str, ...]
    steps: tuple[tuple[dict[str, Any], ...], ...]
    gains: dict[str, float]

    @property
    def baseline_rms(self) -> float:
        return held_out_rms(self.baseline_errors)

    @property
    def final_rms(self) -> float:
        return held_out_rms(self.final_errors)


def select_causes(stage: Stage, causes: tuple[str, ...], settings: DiagnoseSettings
                  ) -> StageResult:
    """Forward selection of ``causes`` in ``stage`` (module docstring for the rule)."""
    current = fit_stage(stage, (), [])
    baseline, current_errors = current, held_out_errors(stage, current)
    baseline_errors = current_errors
    chosen, steps, gains = [], [], {}
    while True:
        untried = [c for c in causes if c not in chosen
                   and any(form in stage.forms for form in forms_of(c))]
        if not untried:
            break
        entries = [entry for cause in untried
                   if (entry := _try_cause(stage, current, current_errors, cause)) is not None]
        if not entries:
            break
        threshold = settings.significance / sum(entry["forms_tried"] for entry in entries)
        for entry in entries:
            entry["accepted"] = bool(entry["p_value"] < threshold and entry["gain"] > 0.0 and
                                     entry["aicc_change"] <= -settings.min_aicc_improvement)
            entry["verdict"] = _verdict(entry, threshold, settings)
        steps.append(tuple(entries))
        accepted = [e for e in entries if e["accepted"]]
        if not accepted:
            break
        best = min(accepted, key=lambda e: e["aicc_change"] if e["test"] == "F"
                   else e["held_out_error"])
        gains[best["name"]] = best["gain"]
        chosen.append(best["name"])
        current, current_errors = best["_fit"], best["_errors"]
    return StageResult(stage, baseline, baseline_errors, current, current_errors, tuple(chosen),
                       tuple(steps), gains)


def held_out_rms(errors: np.ndarray) -> float:
    """RMS held-out error over the tests that could be predicted (errors: mean squares per test)."""
    return float(np.sqrt(np.nanmean(errors)))


def _try_cause(stage: Stage, current: StageFit, current_errors: np.ndarray,
               cause: str) -> dict[str, Any] | None:
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
    forms_tried = len(fits)
    errors = held_out_errors(stage, fit)
    n_base = current.n_parameters + stage.n_groups
    one_row_per_unit = np.unique(stage.unit).size == stage.unit.size
    if one_row_per_unit:
        test, p_value = "F", extra_sum_of_squares_p(current, fit, n_base)
    else:
        test, p_value = "paired t", paired_improvement_p(current_errors, errors)
    return {
        "name": cause, "form": fit.forms[-1].name, "stage": stage.name,
        "params": fit.laws[-1].params(),
        "held_out_error": held_out_rms(errors),
        "held_out_error_before": held_out_rms(current_errors),
        "gain": 1.0 - held_out_rms(errors) / held_out_rms(current_errors),
        "test": test, "p_value": p_value, "forms_tried": forms_tried,
        "tests_improved": f"{int(np.sum(errors < current_errors))} of "
                          f"{int(np.sum(np.isfinite(errors)))}",
        "aicc_change": aicc(fit.residuals, n_base + fit.x[-1].size) - aicc(current.residuals,
                                                                           n_base),
        "training_error": float(np.sqrt(np.mean(fit.residuals**2))),
        "_fit": fit, "_errors": errors,
    }


def _verdict(entry: dict[str, Any], threshold: float, settings: DiagnoseSettings) -> str:
    evidence = (f"{entry['test']} p = {entry['p_value']:.2g}, held-out tests improved "
                f"{entry['tests_improved']}, held-out gain {entry['gain']:+.0%}")
    if entry["accepted"]:
        return f"accepted: {evidence} (p < {threshold:.2g}), AICc {entry['aicc_change']:+.1f}"
    if entry["p_value"] >= threshold:
        return f"rejected: not significant ({evidence}; needs p < {threshold:.2g})"
    if entry["gain"] <= 0.0:
        return f"rejected: predicts held-out tests no better ({evidence})"
    return (f"rejected: AICc {entry['aicc_change']:+.1f} (needs <= "
            f"-{settings.min_aicc_improvement:g}): the extra parameters do not pay for "
            "themselves in the fit")
