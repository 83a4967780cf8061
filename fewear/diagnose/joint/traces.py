"""Measured traces as evidence on the mechanism: which rod and friction the slider's acceleration
and the joint's force say the joint runs in, by the misfit of their crank harmonics against the
believed mechanism's and each option's. The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from scipy import stats

from fewear.diagnose.joint.forward import cycle_on_worn_bore
from fewear.diagnose.joint.measured import AccelerationTrace, ForceTrace, JointMeasurements

MAX_HARMONIC = 40
"""The highest crank harmonic read (800 Hz at the tests' 1,200 rpm)."""
RATE_FRACTION = 8
"""Harmonics up to the sampling rate / this (a low-pass at 0.4 of the rate passes them to 1e-4)."""
MIN_REVOLUTIONS = 2
"""A trace needs this many whole crank revolutions (the spread is measured between them)."""
SIMULATED_REVOLUTIONS = 6
"""Crank revolutions simulated per trace (after the config's settling cycles)."""


@dataclass(frozen=True)
class Signature:
    """A trace's harmonic signature: per revolution (rows) the amplitudes of harmonics 2..H over
    the first's (columns), and the cycle count it was recorded at."""

    cycles: int
    relative_amplitudes: np.ndarray  # (revolutions, H - 1)

    @property
    def harmonics(self) -> int:
        return self.relative_amplitudes.shape[1] + 1

    @property
    def mean(self) -> np.ndarray:
        return self.relative_amplitudes.mean(axis=0)

    @property
    def variance_of_mean(self) -> np.ndarray:
        """The squared standard error of :attr:`mean` (sample variance / revolutions)."""
        rows = self.relative_amplitudes.shape[0]
        return self.relative_amplitudes.var(axis=0, ddof=1) / rows


def sampling_rate_hz(time_s: np.ndarray) -> float:
    """The mean sampling rate (S/s) of a trace sampled at ``time_s``."""
    return (time_s.size - 1) / (time_s[-1] - time_s[0])


def harmonics_readable(time_s: np.ndarray, period_s: float) -> int:
    """H for a trace sampled at ``time_s`` (:data:`MAX_HARMONIC`, :data:`RATE_FRACTION`)."""
    return int(min(MAX_HARMONIC, math.floor(sampling_rate_hz(time_s) * period_s
                                            / RATE_FRACTION)))


TRACE_KINDS = ("acceleration", "force")
"""The kinds of trace read: the slider's acceleration and the joint force."""
TRACE_NAMES = {"acceleration": "slider acceleration", "force": "joint force"}
"""How the notes name each kind."""


def whole_revolutions(time_s: np.ndarray, period_s: float) -> int:
    """The number of whole crank revolutions ``time_s`` spans."""
    return int(math.floor((time_s[-1] - time_s[0]) / period_s + 1e-9))


def readable_traces(data: JointMeasurements, period_s: float):
    """The measured traces (acceleration, then force) the evidence reads, those of at least
    :data:`MIN_REVOLUTIONS` whole crank revolutions sampled fast enough for three harmonics
    (:func:`harmonics_readable`), and a sentence on each one it leaves out."""
    kept, notes = [], []
    for trace in (*(data.acceleration or ()), *(data.force or ())):
        what = f"the {TRACE_NAMES[trace_kind(trace)]} trace at {trace.cycles} cycles"
        if whole_revolutions(trace.time_s, period_s) < MIN_REVOLUTIONS:
            revolutions = (trace.time_s[-1] - trace.time_s[0]) / period_s
            notes.append(f"{what} spans {revolutions:.2f} crank revolutions of "
                         f"{period_s * 1e3:.4g} ms, fewer than {MIN_REVOLUTIONS}: not read as "
                         "evidence on the mechanism (the spread between whole revolutions is "
                         "its yardstick)")
        elif harmonics_readable(trace.time_s, period_s) < 3:
            notes.append(f"{what} is sampled at {sampling_rate_hz(trace.time_s):.4g} S/s: "
                         "fewer than three crank harmonics below an eighth of the rate "
                         f"({RATE_FRACTION}); not read as evidence on the mechanism")
        else:
            kept.append(trace)
    return kept, notes


def revolution_amplitudes(time_s: np.ndarray, signal: np.ndarray, period_s: float,
                          harmonics: int) -> np.ndarray:
    """Amplitudes of harmonics 1..``harmonics`` of the crank period in each whole revolution
    of a sampled ``signal`` from its first sample: least squares of a constant plus cosines and
    sines (revolutions, harmonics)."""
    orders = np.arange(1, harmonics + 1)
    rows = []
    for revolution in range(whole_revolutions(time_s, period_s)):
        start = time_s[0] + revolution * period_s
        inside = (time_s >= start) & (time_s < start + period_s)
        phase = 2.0 * math.pi * np.outer(time_s[inside] - start, orders) / period_s
        design = np.hstack([np.ones((phase.shape[0], 1)), np.cos(phase), np.sin(phase)])
        coefficients = np.linalg.lstsq(design, signal[inside], rcond=None)[0]
        rows.append(np.hypot(coefficients[1:harmonics + 1], coefficients[harmonics + 1:]))
    return np.array(rows).reshape(-1, harmonics)


def _revolution_integrals(time_s: np.ndarray, signal: np.ndarray, period_s: float,
                          harmonics: int):
    """Per whole revolution from ``time_s[0]``: the signal at its start and end, and the
    integrals of signal x cos(h w t) and signal x sin(h w t) (h = 1..``harmonics``, w = 2 pi /
    T, t from the revolution's start), the signal linear between its steps (trapezoids)."""
    omega = 2.0 * math.pi / period_s
    orders = np.arange(1, harmonics + 1)
    for revolution in range(whole_revolutions(time_s, period_s)):
        start = time_s[0] + revolution * period_s
        grid = np.concatenate([[start], time_s[(time_s > start) & (time_s < start + period_s)],
                               [start + period_s]])
        values = np.interp(grid, time_s, signal)
        phase = omega * np.outer(grid - start, orders)
        yield (values[0], values[-1], np.trapz(values[:, None] * np.cos(phase), grid, axis=0),
               np.trapz(values[:, None] * np.sin(phase), grid, axis=0))


def simulated_amplitudes(time_s: np.ndarray, velocity_m_s: np.ndarray, period_s: float,
                         harmonics: int) -> np.ndarray:
    """Amplitudes of harmonics 1..``harmonics`` of the slider's acceleration v' in each whole
    revolution of a simulated velocity history, without differentiating it: over a revolution
    from t0, (2/T) int v' cos(h w t) dt = (2/T) [v(t0 + T) - v(t0) + h w int v sin(h w t) dt] and
    (2/T) int v' sin(h w t) dt = -(2/T) h w int v cos(h w t) dt (integration by parts, w =
    2 pi / T; trapezoids on the integrator's steps)."""
    omega = 2.0 * math.pi / period_s
    orders = np.arange(1, harmonics + 1)
    rows = [np.hypot((2.0 / period_s) * (end - begin + orders * omega * sine),
                     (2.0 / period_s) * orders * omega * cosine)
            for begin, end, cosine, sine in _revolution_integrals(time_s, velocity_m_s,
                                                                   period_s, harmonics)]
    return np.array(rows).reshape(-1, harmonics)


def integrated_amplitudes(time_s: np.ndarray, signal: np.ndarray, period_s: float,
                          harmonics: int) -> np.ndarray:
    """Amplitudes of harmonics 1..``harmonics`` in each whole revolution of a simulated
    ``signal`` linear between the integrator's steps: (2/T) |int signal e^(i h w t) dt|
    (trapezoids; a spike a few steps wide counts by its integral)."""
    rows = [(2.0 / period_s) * np.hypot(cosine, sine)
            for _, _, cosine, sine in _revolution_integrals(time_s, signal, period_s,
                                                             harmonics)]
    return np.array(rows).reshape(-1, harmonics)


def simulated_signatures(config: dict, angle_rad: np.ndarray, depth_m: np.ndarray, cycles: int,
                         harmonics: int, kinds: tuple[str, ...]) -> tuple[Signature, ...]:
    """The signatures of the trace ``kinds`` (:data:`TRACE_KINDS`) of one run of
    :data:`SIMULATED_REVOLUTIONS` revolutions of the config's mechanism on the bore worn by
    ``depth_m`` (at the node angles ``angle_rad``), as at ``cycles``."""
    history = cycle_on_worn_bore(config, angle_rad, depth_m, SIMULATED_REVOLUTIONS)
    period = crank_period_s(config)
    found = {
        "acceleration": lambda: simulated_amplitudes(
            history.time_s, history.slider_velocity_m_s, period, harmonics),
        "force": lambda: np.hypot(*(integrated_amplitudes(
            history.time_s, component, period, harmonics)
            for component in history.reaction_force_N.T))}
    return tuple(signature(cycles, found[kind]()) for kind in kinds)


def crank_period_s(config: dict) -> float:
    """The crank's period (s) of the config's mechanism."""
    return 60.0 / config["mechanism"]["crank_speed_rpm"]


def signature(cycles: int, amplitudes: np.ndarray) -> Signature:
    """The signature of per-revolution amplitudes of harmonics 1..H."""
    return Signature(int(cycles), amplitudes[:, 1:] / amplitudes[:, :1])


def trace_kind(trace: AccelerationTrace | ForceTrace) -> str:
    """The kind (:data:`TRACE_KINDS`) of a measured trace."""
    return "force" if isinstance(trace, ForceTrace) else "acceleration"


def measured_signature(trace: AccelerationTrace | ForceTrace, period_s: float,
                       harmonics: int) -> Signature:
    """The signature of a measured trace: the slider's acceleration, or the joint force (its
    components' amplitudes combined, docs/diagnosis-method-notes.md)."""
    def amplitudes(signal):
        return revolution_amplitudes(trace.time_s, signal, period_s, harmonics)
    if isinstance(trace, ForceTrace):
        return signature(trace.cycles, np.hypot(amplitudes(trace.fx_N), amplitudes(trace.fy_N)))
    return signature(trace.cycles, amplitudes(trace.slider_acceleration_m_s2))


@dataclass(frozen=True)
class TraceMisfit:
    """A model's misfit to the traces: ``chi2`` over ``dof`` harmonics (all traces), its
    p-value if the model were right, and the RMS difference of the relative amplitudes."""

    chi2: float
    dof: int
    rms_difference: float

    @property
    def p_value(self) -> float:
        return float(stats.chi2.sf(self.chi2, self.dof))


def trace_misfit(measured: list[Signature], simulated: list[Signature]) -> TraceMisfit:
    """(the method notes) of ``simulated`` signatures (one per measured trace, at its count)
    against the ``measured`` ones. Each harmonic's difference of means is a Welch t statistic
    (a few revolutions estimate each side's spread: Welch-Satterthwaite degrees of freedom),
    turned into the normal deviate of the same two-sided p, whose squares sum to chi-square."""
    chi2, dof, squares = 0.0, 0, []
    for seen, model in zip(measured, simulated):
        difference = seen.mean - model.mean
        seen_var, model_var = seen.variance_of_mean, model.variance_of_mean
        variance = np.maximum(seen_var + model_var, np.finfo(float).tiny)
        freedom = variance**2 / (seen_var**2 / (seen.relative_amplitudes.shape[0] - 1)
                                 + model_var**2 / (model.relative_amplitudes.shape[0] - 1)
                                 + np.finfo(float).tiny)
        p_two_sided = 2.0 * stats.t.sf(np.abs(difference) / np.sqrt(variance), freedom)
        chi2 += float(np.sum(stats.norm.isf(np.maximum(p_two_sided, 1e-300) / 2.0) ** 2))
        dof += difference.size
        squares.append(difference**2)
    return TraceMisfit(chi2, dof, float(np.sqrt(np.mean(np.concatenate(squares)))))


def combined_misfits(by_kind: list[list[TraceMisfit]]
                     ) -> tuple[list[TraceMisfit], list[float]]:
    """One misfit per model from its misfits to each kind of trace (``by_kind[k][m]``: kind
    k, model m): each kind's chi-square divided by that kind's :func:`overdispersion` over the
    models (the kinds vary alike only by chance: a load cell sees every impact, an
    accelerometer on the slider less), then summed with their degrees of freedom; the RMS
    difference pooled over all harmonics. Also the dispersions, in ``by_kind``'s order."""
    dispersions = [overdispersion(*misfits) for misfits in by_kind]
    combined = []
    for model in zip(*by_kind):
        dof = sum(m.dof for m in model)
        chi2 = sum(m.chi2 / d for m, d in zip(model, dispersions))
        squares = sum(m.rms_difference**2 * m.dof for m in model)
        combined.append(TraceMisfit(chi2, dof, math.sqrt(squares / dof)))
    return combined, dispersions


@dataclass(frozen=True)
class MechanismOption:
    """A mechanism the traces are read against: the believed one (``cause`` None) or a grid run
    of a cause that changes the dynamics (its ``form`` and the run's index in that form's
    grid), with its misfit."""

    label: str
    cause: str | None
    form: str
    index: int
    misfit: TraceMisfit


@dataclass(frozen=True)
class TraceEvidence:
    """What the traces say (:func:`trace_verdict`): the believed mechanism's and each option's
    misfit, and the option they name (None: no option explains them clearly better)."""

    harmonics: int
    believed: TraceMisfit
    options: tuple[MechanismOption, ...]
    named: MechanismOption | None
    dispersions: tuple[tuple[str, float], ...] = ()
    """The kinds of trace read, each with the overdispersion its misfits were divided by."""

    def summary(self) -> dict:
        """JSON-ready."""
        def row(label, misfit):
            return {"model": label, "chi2": misfit.chi2, "dof": misfit.dof,
                    "p_value": misfit.p_value, "rms_relative_difference": misfit.rms_difference}
        return {"harmonics": self.harmonics, "overdispersion_by_kind": dict(self.dispersions),
                "believed": row("believed model", self.believed),
                "options": [row(o.label, o.misfit) for o in self.options],
                "named": self.named.label if self.named else None}


def trace_verdict(believed: TraceMisfit, options: list[MechanismOption], harmonics: int,
                  significance: float, min_gain: float,
                  dispersions: tuple[tuple[str, float], ...] = ()) -> TraceEvidence:
    """The traces name the option with the lowest misfit when, the misfits divided by their
    :func:`overdispersion`, (1) its chi-square is below the believed mechanism's by more than
    one parameter's chi-square at ``significance`` over the options tried (a likelihood-ratio
    test, Bonferroni: the cause adds one value) and (2) its RMS difference of the relative
    amplitudes is at least ``min_gain`` below the believed mechanism's (an effect the traces
    resolve, as the bore's held-out gain). The believed mechanism's own fit is reported (its
    p-value), not required to fail: when no option is exactly the truth (the fourth
    generator's rod damped unlike any in the grid), the best option's misfit, and with it the
    dispersion, carries that option's error too, so that the believed mechanism was not rejected
    on traces that prefer a flexible rod to it by a drop of 20 over a threshold of 7.9."""
    level = significance / max(len(options), 1)
    named = None
    if options:
        best = min(options, key=lambda option: option.misfit.chi2)
        dispersion = overdispersion(believed, best.misfit)
        drop = (believed.chi2 - best.misfit.chi2) / dispersion
        gain = 1.0 - best.misfit.rms_difference / believed.rms_difference
        if drop > stats.chi2.isf(level, 1) and gain >= min_gain:
            named = best
    return TraceEvidence(harmonics, believed, tuple(options), named, dispersions)


def overdispersion(*misfits: TraceMisfit) -> float:
    """The chi-square per degree of freedom of the best of ``misfits``, at least 1: the
    revolutions of one simulated run vary less than realizations of the chaotic impacts and the
    bore they run on, so even the right model's chi-square exceeds its degrees of freedom (on
    null sets of the third generator, 362 on 117); the misfits are divided by it before they are
    tested (a quasi-likelihood's dispersion, McCullagh & Nelder, Generalized Linear Models, 2nd
    ed., section 4.5), so that the best model is never rejected and a difference counts in the
    units of its spread."""
    return max(1.0, min(m.chi2 / m.dof for m in misfits))
