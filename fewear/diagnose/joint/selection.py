"""The selection of the joint diagnosis: each cause's fit judged against the model it would
extend (:func:`verdict`), the accepted causes ordered (:func:`select_causes`, pairs:
:func:`select_pairs`) and the first confirmed on realizations of its extended model
(:func:`confirm_first`). The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import copy
from dataclasses import dataclass, replace

from fewear.diagnose.core.evidence import Evidence
from fewear.diagnose.core.statistics import nested_f_test_p
from fewear.diagnose.joint.catalogue import CAUSES
from fewear.diagnose.joint.confirmation import (
    Realizations,
    confirm,
    confirm_no_worse,
    extended_config,
    realizations,
)
from fewear.diagnose.joint.fitting import Fit, Observations
from fewear.diagnose.joint.pairs import causes_of, fit_pairs, pair_candidates
from fewear.diagnose.joint.settings import JointDiagnoseSettings

UNEXPLAINED_SCATTERS = 3.0
"""With no cause named, a believed model missing the training data by more than this many times
the instrument's scatter is reported as unexplained, not as right."""


def f_test_p(nested: Fit, fuller: Fit) -> float:
    """Extra-sum-of-squares F-test of two nested least-squares fits on the training data."""
    return nested_f_test_p(nested.sse_train, fuller.sse_train, fuller.n_params - nested.n_params,
                           fuller.n_train - fuller.n_params)


@dataclass(frozen=True, eq=False)
class CauseVerdict:
    """One cause's ``fit`` (its form, fitted parameters and errors) judged against the model
    named ``against``: the ``evidence`` and whether the cause is ``accepted``."""

    fit: Fit
    against: str
    evidence: Evidence
    accepted: bool

    @property
    def cause(self) -> str:
        """The cause's name."""
        return self.fit.name


def verdict(fit_: Fit, reference: Fit, settings: JointDiagnoseSettings,
            tried: int) -> CauseVerdict:
    """The evidence for a cause against the reference model and whether it is accepted."""
    evidence = Evidence(p_value=f_test_p(reference, fit_),
                        gain=fit_.held_out_gain(reference),
                        aicc_improvement=reference.aicc - fit_.aicc)
    return CauseVerdict(fit_, reference.name, evidence,
                        settings.acceptance.rule(tried).accepts(evidence))


def testable(config: dict, settings: JointDiagnoseSettings) -> tuple[list[str], list[dict]]:
    """The causes the believed model can be extended by, and why the others cannot."""
    names, untestable = [], []
    for name in settings.candidates:
        why = CAUSES[name].cause.why_untestable(config)
        if why is None:
            names.append(name)
        else:
            untestable.append({"cause": name, "untestable_reason": why})
    return names, untestable


def select_causes(baseline: Fit, fits: dict[str, Fit], settings,
            noise_m: float | None = None) -> tuple[list[str], list[CauseVerdict]]:
    """The accepted causes in the order they are to be named (the richer ones by held-out
    error, then ``wear_coefficient``) and the verdict on every cause tried. None is accepted
    when the believed model already predicts the held-out data within
    :data:`UNEXPLAINED_SCATTERS` times ``noise_m``, the larger of the instrument's scatter and
    the model's own noise (what 'none' means): a relative gain on an error at the noise is no
    evidence of a cause."""
    tried = sum(f.forms_tried for f in fits.values())
    at_noise = within_noise(baseline, noise_m)
    verdicts = []
    reference = baseline
    chosen: list[str] = []
    if "wear_coefficient" in fits:
        entry = _judged(fits["wear_coefficient"], baseline, settings, tried, at_noise)
        verdicts.append(entry)
        if entry.accepted:
            reference, chosen = fits["wear_coefficient"], ["wear_coefficient"]
    richer = [_judged(f, reference, settings, tried, at_noise)
              for name, f in fits.items() if name != "wear_coefficient"]
    verdicts += richer
    return _by_held_out_error(richer) + chosen, verdicts


def within_noise(baseline: Fit, noise_m: float | None) -> bool:
    """Whether the believed model predicts the held-out data within
    :data:`UNEXPLAINED_SCATTERS` times ``noise_m`` (:func:`select_causes`)."""
    return noise_m is not None and baseline.held_out_rms_m <= UNEXPLAINED_SCATTERS * noise_m


def _judged(fit_: Fit, reference: Fit, settings, tried: int, at_noise: bool) -> CauseVerdict:
    """:func:`verdict`, none accepted ``at_noise`` (:func:`within_noise`)."""
    entry = verdict(fit_, reference, settings, tried)
    return replace(entry, accepted=entry.accepted and not at_noise)


def _by_held_out_error(verdicts: list[CauseVerdict]) -> list[str]:
    """The accepted causes of ``verdicts``, the best on the held-out data first."""
    return [e.cause for e in sorted((e for e in verdicts if e.accepted),
                                    key=lambda e: e.fit.held_out_rms_m)]


def select_pairs(candidates: dict, fits: dict[str, Fit], obs: Observations, baseline: Fit,
                  settings: JointDiagnoseSettings, noise_m: float | None):
    """With no single cause accepted on the believed model: running-in fitted together with each
    cause that, as running-in, fits the training data better than the believed model beyond
    chance (F-test p < ``significance`` / forms tried; :mod:`fewear.diagnose.joint.pairs`). A
    pair is accepted by :func:`verdict` against the believed model (every pair counted among the
    forms tried) and when it fits the training data better than each of its causes alone
    (F-test of the nested fits, p < ``significance``). Returns the accepted pairs, the best on
    the held-out data first, the verdicts on all pairs and their fits."""
    tried = sum(f.forms_tried for f in fits.values())
    pairs = pair_candidates(
        candidates, fits,
        lambda f: f_test_p(baseline, f) < settings.acceptance.significance / tried)
    pair_fits = fit_pairs(pairs, fits, obs, float(baseline.x[0]), settings)
    verdicts = []
    for name, fitted in pair_fits.items():
        entry = _judged(fitted, baseline, settings, tried + len(pairs),
                        within_noise(baseline, noise_m))
        beyond_each = all(f_test_p(fits[cause], fitted) < settings.acceptance.significance
                          for cause in causes_of(name))
        verdicts.append(replace(entry, accepted=entry.accepted and beyond_each))
    return _by_held_out_error(verdicts), verdicts, pair_fits


def confirm_first(config: dict, accepted: list[str], fits: dict[str, Fit], baseline: Fit,
             obs: Observations, settings: JointDiagnoseSettings, label: str,
             by_traces: str | None = None):
    """The first accepted cause (or pair) confirmed on realizations of its extended model
    (:mod:`fewear.diagnose.joint.confirmation`): a richer cause against the k level's when that
    was accepted, else against the round's model ``config`` (named ``label``). A cause's
    realizations are run beside its reference's, and a later cause's only when those before it
    were not confirmed (the first usually is: running every accepted cause's at once had four
    causes' twelve runs to confirm the first, 36 s of a 252 s diagnosis). Returns (the
    accepted name confirmed, None if none is; the extended config; its fit, the realization
    started at the config's crank angle; its depths at the observations; the confirmations up
    to the named cause; its realizations, None if none is)."""
    extended = {cause: extended_config(config, cause, fits[cause]) for cause in accepted}
    models = {label: config, **extended}
    runs: dict[str, Realizations] = {}
    confirmations = []
    for cause in accepted:
        against = ("wear_coefficient" if "wear_coefficient" in accepted
                   and cause != "wear_coefficient" else label)
        missing = [name for name in dict.fromkeys((cause, against)) if name not in runs]
        runs.update(zip(missing, realizations([models[name] for name in missing], missing, obs,
                                              float(baseline.x[0]), settings.max_offset_deg)))
        judge = confirm_no_worse if cause == by_traces else confirm
        confirmations.append(judge(cause, runs[cause], runs[against], against, settings))
        if confirmations[-1].confirmed:
            final = runs[cause].fits[0]
            return (cause, extended[cause], final, obs.depth_m - final.residuals_m,
                    confirmations, runs[cause])
    return (None, copy.deepcopy(config), baseline, obs.depth_m - baseline.residuals_m,
            confirmations, None)


def confounded_verdicts(verdicts: list[CauseVerdict], accepted: list[str],
                named: str | None) -> tuple[CauseVerdict, ...]:
    """The verdicts on the richer causes accepted after the ``named`` one (not run in full)."""
    later = accepted[accepted.index(named) + 1:] if named else []
    return tuple(e for e in verdicts if e.cause in later and e.cause != "wear_coefficient")
