"""Fitting one log-scale factor on a wear coefficient by a few forward runs of the scar model:
between runs the depths are taken linear in ln(factor), and the surrogate's minimiser is run
until it lies within the tolerance of a run. The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import math
import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from scipy.optimize import minimize_scalar

from fewear.diagnose.scar.settings import ScarDiagnoseSettings

FIRST_STEP_TOLERANCES = 10.0
"""The first run's ln(factor) lies at least this many tolerances from the believed model's."""


class ForwardRuns:
    """The runs of the model for one cause, by ln(factor): the believed one (theta = 0) given,
    the others made by ``predict(factor)`` (the depths at the measured points, m) and counted."""

    def __init__(self, believed_m: np.ndarray, predict: Callable[[float], np.ndarray],
                 report: Callable[[float, float], None] | None = None):
        self._log_factors, self._depths = [0.0], [np.asarray(believed_m, dtype=float)]
        self._predict, self._report = predict, report
        self.wall_time_s = 0.0

    @property
    def factors(self) -> tuple[float, ...]:
        """The factors run, the believed model's (1) not counted, in the order run."""
        return tuple(math.exp(theta) for theta in self._log_factors[1:])

    def run(self, log_factor: float) -> None:
        start = time.perf_counter()
        self._depths.append(np.asarray(self._predict(math.exp(log_factor)), dtype=float))
        self._log_factors.append(float(log_factor))
        seconds = time.perf_counter() - start
        self.wall_time_s += seconds
        if self._report is not None:
            self._report(math.exp(log_factor), seconds)

    def distance_to_run(self, log_factor: float) -> float:
        """|theta - the nearest run's theta|."""
        return float(np.min(np.abs(np.array(self._log_factors) - log_factor)))

    def depth_m(self, log_factor: float) -> np.ndarray:
        """The surrogate's depths at theta (the method notes); the believed ones with one run."""
        order = np.argsort(self._log_factors)
        thetas, depths = np.array(self._log_factors)[order], [self._depths[i] for i in order]
        if thetas.size == 1:
            return depths[0]
        upper = int(np.clip(np.searchsorted(thetas, log_factor), 1, thetas.size - 1))
        share = (log_factor - thetas[upper - 1]) / (thetas[upper] - thetas[upper - 1])
        return depths[upper - 1] + share * (depths[upper] - depths[upper - 1])


@dataclass(frozen=True)
class FactorFit:
    """A fit of ln(factor) on some points: ``log_factor``, whether it ``converged`` (module
    docstring) and whether it stopped at the search's bound (``at_bound``)."""

    log_factor: float
    converged: bool
    at_bound: bool

    @property
    def factor(self) -> float:
        return math.exp(self.log_factor)


def fit_log_factor(runs: ForwardRuns, measured_m: np.ndarray, fitted: np.ndarray,
                   settings: ScarDiagnoseSettings, scales_worn_area: bool) -> FactorFit:
    """The least-squares ln(factor) on the points ``fitted`` (a boolean mask) of ``measured_m``,
    running the model while it has not converged and fewer than ``max_forward_runs`` runs were
    made (docs/diagnosis-method-notes.md)."""
    bound, tolerance = settings.log_factor_bound, settings.log_factor_tolerance
    runs_allowed = settings.max_forward_runs
    if len(runs.factors) == 0:
        runs.run(_first_step(runs.depth_m(0.0), measured_m, fitted, settings, scales_worn_area))
    while True:
        theta = _surrogate_minimiser(runs, measured_m, fitted, bound)
        converged = runs.distance_to_run(theta) <= tolerance
        if converged or len(runs.factors) >= runs_allowed:
            return FactorFit(theta, converged, abs(theta) >= bound - tolerance)
        runs.run(theta)


def _first_step(believed_m, measured_m, fitted, settings, scales_worn_area: bool) -> float:
    """theta_1: Archard's area ratio where it applies, at least FIRST_STEP_TOLERANCES
    tolerances from 0, within the bound."""
    least = FIRST_STEP_TOLERANCES * settings.log_factor_tolerance
    measured, predicted = float(np.sum(measured_m[fitted])), float(np.sum(believed_m[fitted]))
    guess = math.log(measured / predicted) if (scales_worn_area and measured > 0.0
                                               and predicted > 0.0) else least
    step = math.copysign(max(abs(guess), least), guess)
    return float(np.clip(step, -settings.log_factor_bound, settings.log_factor_bound))


def _surrogate_minimiser(runs: ForwardRuns, measured_m, fitted, bound: float) -> float:
    def rss(theta: float) -> float:
        return float(np.sum((runs.depth_m(theta)[fitted] - measured_m[fitted]) ** 2))

    return float(minimize_scalar(rss, bounds=(-bound, bound), method="bounded",
                                 options={"xatol": 1e-7}).x)
