"""Two causes at once: running-in on top of another cause, fitted on running-in's time map of
that cause's runs, for when two causes together leave neither better on its own. The method:
docs/diagnosis-method-notes.md."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from fewear.diagnose.joint.candidates import Candidate
from fewear.diagnose.joint.catalogue import CAUSES
from fewear.diagnose.joint.fitting import Fit, Observations, bounds_and_starts, fit_form
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.parallel import side_by_side

PARTNER = "running_in"
"""The cause fitted on top of the others' runs."""
SEPARATOR = " + "


def pair_name(cause: str) -> str:
    """The name of ``cause`` with running-in on top (as a candidate and in the report)."""
    return f"{cause}{SEPARATOR}{PARTNER}"


def is_pair(name: str) -> bool:
    return SEPARATOR in name


def causes_of(name: str) -> tuple[str, ...]:
    """The causes a candidate's ``name`` stands for: one, or the two of a pair."""
    return tuple(name.split(SEPARATOR))


def pair_candidates(candidates: dict[str, tuple[Candidate, ...]], fits: dict[str, Fit],
                    beats_believed) -> dict[str, Candidate]:
    """Running-in on each cause (in the form its own fit took) whose fit, as running-in's,
    ``beats_believed`` (a predicate on a fit): by pair name; none unless running-in does."""
    partner = fits.get(PARTNER)
    if partner is None or not beats_believed(partner):
        return {}
    pairs = {}
    for name, forms in candidates.items():
        if name in (PARTNER, "wear_coefficient") or not beats_believed(fits[name]):
            continue
        form = next(f for f in forms if (f.form or None) == fits[name].form)
        pairs[pair_name(name)] = replace(form, name=pair_name(name), time_map=True,
                                         running_in_form=partner.form, run_extension=None)
    return pairs


def fit_pairs(pairs: dict[str, Candidate], fits: dict[str, Fit], obs: Observations,
              offset_deg: float, settings: JointDiagnoseSettings) -> dict[str, Fit]:
    """Each pair fitted (side by side), from its two causes' own fits (:func:`pair_starts`)."""
    arguments = [(candidate, obs, offset_deg, settings,
                  pair_starts(candidate, fits[causes_of(name)[0]], fits[PARTNER], obs, settings))
                 for name, candidate in pairs.items()]
    return dict(zip(pairs, side_by_side(fit_form, arguments)))


def pair_starts(candidate: Candidate, cause_fit: Fit, partner_fit: Fit, obs: Observations,
                settings: JointDiagnoseSettings) -> list[np.ndarray]:
    """Starts of a pair's fit x = (phi_deg, ln s, ln(r - 1), ln s0[, position]): running-in's
    fitted law at the level of each cause alone, and the time map's own starts at the believed
    level; the position on a grid cause's runs at the cause's own fit."""
    position = ([float(cause_fit.x[2])]
                if len(candidate.runs) > 1 and not candidate.discrete else [])
    law = [float(v) for v in partner_fit.x[2:4]]
    starts = [[float(cause_fit.x[0]), float(level), *law, *position]
              for level in {float(cause_fit.x[1]), float(partner_fit.x[1])}]
    _, extra = bounds_and_starts(candidate, obs, settings)
    starts += [[float(cause_fit.x[0]), 0.0, *law_start, *position]
               for law_start in dict.fromkeys(tuple(e[:2]) for e in extra)]
    return [np.array(start) for start in starts]


def pair_config(config: dict, fitted: Fit) -> dict:
    """The believed ``config`` with a pair at its ``fitted`` parameters: the cause's value and
    the level of k, and running-in's law on top."""
    cause = causes_of(fitted.name)[0]
    with_cause = CAUSES[cause].extended_config(config, fitted.params, fitted.form or "")
    return CAUSES[PARTNER].extended_config(with_cause, {**fitted.params, "k_scale": 1.0},
                                           fitted.running_in_form)
