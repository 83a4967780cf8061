"""Confirming an accepted cause on realizations of its extended model: the fits interpolate
between runs or take the best of several, and runs of one model started a degree apart differ as
much as the causes, so the cause's full runs from several crank starts must predict the held-out
data better than its reference's. The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from fewear.diagnose.core.statistics import welch_lower_p
from fewear.diagnose.joint.catalogue import CAUSES
from fewear.diagnose.joint.fitting import Fit, Observations, offset_fit
from fewear.diagnose.joint.forward import model_config, simulate_wears, started_later
from fewear.diagnose.joint.pairs import is_pair, pair_config
from fewear.diagnose.joint.settings import JointDiagnoseSettings

START_OFFSETS_DEG = (0.0, 1.0, 2.0)
"""Crank angles (deg) by which the realizations of a model start later: as the resolution's runs
(:data:`fewear.diagnose.joint.resolution.MEMBER_START_OFFSETS_DEG`), so the believed model's
are those runs again."""


@dataclass(frozen=True, eq=False)
class Realizations:
    """A model run from each crank start of :data:`START_OFFSETS_DEG`, each run's ``fits``
    (angle offset only; the first, started at the config's own angle, is the model's)."""

    fits: tuple[Fit, ...]

    @property
    def held_out_rms_m(self) -> np.ndarray:
        return np.array([f.held_out_rms_m for f in self.fits])


@dataclass(frozen=True)
class Confirmation:
    """An accepted ``cause``'s realizations against its reference's (named ``against``): their
    held-out RMS errors (m), the ``gain`` of the cause's mean error over the reference's, the
    Welch ``p_value`` (that the cause predicts better; for a cause the traces named, that it
    predicts worse: :func:`confirm_no_worse`) and whether the cause is ``confirmed``."""

    cause: str
    against: str
    held_out_rms_m: tuple[float, ...]
    reference_held_out_rms_m: tuple[float, ...]
    gain: float
    p_value: float
    confirmed: bool


def realizations(configs: list[dict], labels: list[str], obs: Observations, offset_deg: float,
                 max_offset_deg: float) -> list[Realizations]:
    """Each of ``configs`` run to the last measured count from every crank start of
    :data:`START_OFFSETS_DEG` (all runs side by side), each run fitted with its angle offset
    (from ``offset_deg``, within +- ``max_offset_deg``)."""
    cycles = int(obs.cycles.max()) + 1
    requests = [(started_later(model_config(config, config["wear_loop"]["rod_models"][0],
                                            cycles), offset),
                 f"{label}, started {offset:g} deg later" if offset else label)
                for config, label in zip(configs, labels) for offset in START_OFFSETS_DEG]
    runs = iter(simulate_wears(requests))
    return [Realizations(tuple(offset_fit("extended", next(runs), obs, offset_deg,
                                          max_offset_deg) for _ in START_OFFSETS_DEG))
            for _ in configs]


def confirm(cause: str, extended: Realizations, reference: Realizations, against: str,
            settings: JointDiagnoseSettings) -> Confirmation:
    """Whether ``cause``'s ``extended`` realizations predict the held-out data better than the
    ``reference``'s (the rule of docs/diagnosis-method-notes.md)."""
    errors, reference_errors = extended.held_out_rms_m, reference.held_out_rms_m
    mean, reference_mean = float(errors.mean()), float(reference_errors.mean())
    gain = 1.0 - mean / reference_mean if reference_mean > 0.0 else -math.inf
    p_value = welch_lower_p(errors, reference_errors)
    return Confirmation(cause, against, tuple(map(float, errors)),
                        tuple(map(float, reference_errors)), gain, p_value,
                        bool(gain >= settings.acceptance.min_held_out_gain
                             and p_value < settings.acceptance.significance))


def confirm_no_worse(cause: str, extended: Realizations, reference: Realizations, against: str,
                     settings: JointDiagnoseSettings) -> Confirmation:
    """Whether ``cause``, named by other evidence (the measured traces,
    :mod:`fewear.diagnose.joint.traces`), agrees with the held-out bore data: refuted only when
    its realizations predict them worse than the ``reference``'s beyond the runs' own scatter,
    their mean error more than ``min_held_out_gain`` above the reference's and Welch's one-sided
    test of the reverse order (:func:`~fewear.diagnose.core.statistics.welch_lower_p`) giving
    p < ``significance`` (``p_value``). The bore need not tell the cause apart, only not
    contradict it: runs of a flexible rod started a degree apart differ by up to a factor of two
    on the held-out bore (the third generator's steel rod: 1.11, 1.30 and 1.82 um against the k
    level's 1.09, 1.05 and 1.39), so a fixed margin on the means refuted what the traces had
    named."""
    found = confirm(cause, extended, reference, against, settings)
    p_worse = welch_lower_p(reference.held_out_rms_m, extended.held_out_rms_m)
    accept = settings.acceptance
    worse = found.gain < -accept.min_held_out_gain and p_worse < accept.significance
    return replace(found, p_value=p_worse, confirmed=not worse)


def extended_config(config: dict, cause: str, fitted: Fit) -> dict:
    """The believed config with ``cause`` (or a pair, :mod:`fewear.diagnose.joint.pairs`) at its
    ``fitted`` parameters."""
    if is_pair(cause):
        return pair_config(config, fitted)
    return CAUSES[cause].extended_config(config, fitted.params, fitted.form or "")
