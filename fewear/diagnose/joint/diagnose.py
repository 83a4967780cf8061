"""The joint diagnosis in rounds: what the believed joint model gets wrong on measured joint
wear, which cause explains it and how much better the extended model predicts the later
measurements. Each round fits the causes (:mod:`fewear.diagnose.joint.refinement`), selects and
confirms one (:mod:`fewear.diagnose.joint.selection`); the rounds continue on the model it
extends. The method: docs/diagnosis-method-notes.md."""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import Any

import numpy as np

from fewear.diagnose.joint.candidates import Candidate
from fewear.diagnose.joint.catalogue import CAUSES, Believed
from fewear.diagnose.joint.confirmation import (
    Confirmation,
    Realizations,
    confirm,
    realizations,
)
from fewear.diagnose.joint.fitting import (
    RUNNING_IN_REACH,
    Fit,
    Observations,
    fit_form,
    needed_cycles,
    observations,
)
from fewear.diagnose.joint.forward import (
    RunMaker,
    WearHistory,
    candidate_config,
    candidate_runner,
    model_config,
    simulate_wears,
)
from fewear.diagnose.joint.measured import JointMeasurements
from fewear.diagnose.joint.pairs import causes_of
from fewear.diagnose.joint.refinement import RunsAt, fit_causes
from fewear.diagnose.joint.resolution import (
    baseline_fit,
    model_noise_m,
    resolve_wear_step,
)
from fewear.diagnose.joint.selection import (
    CauseVerdict,
    confirm_first,
    confounded_verdicts,
    select_causes,
    select_pairs,
    testable,
    verdict,
)
from fewear.diagnose.joint.settings import JointDiagnoseSettings
from fewear.diagnose.joint.traces import (
    TRACE_KINDS,
    MechanismOption,
    TraceEvidence,
    combined_misfits,
    crank_period_s,
    harmonics_readable,
    measured_signature,
    readable_traces,
    simulated_signatures,
    trace_kind,
    trace_misfit,
    trace_verdict,
)
from fewear.diagnose.joint.unexplained import (
    cycle_structure,
    origin_at_bound,
    unexplained_sentences,
)
from fewear.errors import FewearInputError
from fewear.parallel import side_by_side, workers_kept


@dataclass(frozen=True)
class NamedCause:
    """The cause a round named, for the judgement of the level of k beside it
    (:func:`_level_round`): its ``fit`` (whose parameters make the round's extended config), the
    ``form`` it was named in as a candidate (refitted there at the believed level: nested in the
    fit), and its ``realizations`` (:mod:`fewear.diagnose.joint.confirmation`)."""

    fit: Fit
    form: Candidate
    realizations: Realizations | None


@dataclass(frozen=True, eq=False)
class Round:
    """One round of the selection on a model (the believed config, or the extended model of the
    causes named so far): the model's ``baseline`` fit, the ``verdicts`` on every cause tried
    against it, the ``accepted`` causes in the order they are to be named, the cause ``named``
    (none or one), those ``confounded`` with it, those ``not_confirmed`` by their full run, the
    ``untestable`` ones, and the model extended by the named cause (``extended_config``, its
    ``extended_fit``, ``extended_depth_m`` at the observations and its held-out ``gain`` over
    the baseline); without a cause the extended model is the round's own."""

    baseline: Fit
    base_run: WearHistory | None
    verdicts: tuple[CauseVerdict, ...]
    accepted: tuple[str, ...]
    named: tuple[str, ...]
    confounded: tuple[CauseVerdict, ...]
    confirmations: tuple[Confirmation, ...]
    untestable: tuple[dict[str, str], ...]
    extended_config: dict
    extended_fit: Fit
    extended_depth_m: np.ndarray
    trace_evidence: TraceEvidence | None = None
    named_cause: NamedCause | None = None
    """The one cause the round named, as the level's judgement needs it (None: none, or a
    pair)."""
    level_of: str | None = None
    """Set on the round that asks whether the level of k is a cause beside the first round's
    cause of this name (:func:`_level_round`): the round's model is that cause at the believed
    level."""

    @property
    def not_confirmed(self) -> tuple[Confirmation, ...]:
        """The accepted causes whose realizations did not hold up."""
        return tuple(entry for entry in self.confirmations if not entry.confirmed)

    @property
    def gain(self) -> float:
        """The named cause's held-out gain over the round's model (0 without one)."""
        return self.extended_fit.held_out_gain(self.baseline) if self.named else 0.0


@dataclass(frozen=True, eq=False)
class JointDiagnosis:
    """Everything :func:`diagnose_joint` found (:func:`fewear.diagnose.joint.report.summarise`
    makes the JSON-ready summary): the ``data`` and ``settings``, the ``observations``, the
    ``rounds`` of the selection (the first on the believed config, each further one on the
    model the causes named so far extend; the last names none unless ``max_causes`` or the
    catalogue ended the rounds), the believed model's ``residual_structure``
    (:func:`cycle_structure`), the ``resolution`` (:func:`resolve_wear_step`) and what stays
    ``unexplained``, in sentences. The rest are views of the rounds: the believed model's
    ``baseline``, every cause's verdict, the ``causes`` named (in the order they joined) with
    the ``gains`` each added, and the final extended model."""

    data: JointMeasurements
    settings: JointDiagnoseSettings
    observations: Observations
    rounds: tuple[Round, ...]
    residual_structure: dict[str, Any]
    resolution: dict[str, Any]
    unexplained: tuple[str, ...]
    trace_notes: tuple[str, ...] = ()
    """A sentence on each measured trace the evidence on the mechanism leaves out."""

    @property
    def baseline(self) -> Fit:
        return self.rounds[0].baseline

    @property
    def verdicts(self) -> tuple[CauseVerdict, ...]:
        return tuple(entry for r in self.rounds for entry in r.verdicts)

    @property
    def accepted(self) -> tuple[str, ...]:
        return tuple(cause for r in self.rounds for cause in r.accepted)

    @property
    def causes(self) -> tuple[str, ...]:
        return _named(self.rounds)

    @property
    def gains(self) -> tuple[float, ...]:
        """Per round that named a cause (or a pair, both at once), its held-out gain over the
        model before it."""
        return tuple(r.gain for r in self.rounds if r.named)

    @property
    def confounded(self) -> tuple[CauseVerdict, ...]:
        return tuple(entry for r in self.rounds for entry in r.confounded)

    @property
    def confirmations(self) -> tuple[Confirmation, ...]:
        return tuple(entry for r in self.rounds for entry in r.confirmations)

    @property
    def not_confirmed(self) -> tuple[Confirmation, ...]:
        return tuple(entry for r in self.rounds for entry in r.not_confirmed)

    @property
    def untestable(self) -> tuple[dict[str, str], ...]:
        return self.rounds[0].untestable

    @property
    def extended_config(self) -> dict:
        return _final(self.rounds).extended_config

    @property
    def extended_fit(self) -> Fit:
        return _final(self.rounds).extended_fit

    @property
    def extended_depth_m(self) -> np.ndarray:
        return _final(self.rounds).extended_depth_m

    @property
    def baseline_depth_m(self) -> np.ndarray:
        """The believed model's depths at the observations."""
        return self.observations.depth_m - self.baseline.residuals_m


def diagnose_joint(data: JointMeasurements, config: dict,
                   settings: JointDiagnoseSettings | None = None) -> JointDiagnosis:
    """The method (the method notes) on ``data`` against the believed ``config``: a round
    of selection on it, and, while a round names a cause and fewer than ``max_causes`` are
    named, another on the model they extend (the causes named left out)."""
    settings = settings or JointDiagnoseSettings.default()
    obs = observations(data, settings.held_out_fraction)
    _check_run_length(data, obs, _believed_config(config, obs, settings))
    with workers_kept():
        config, resolution = resolve_wear_step(config, obs, settings.max_wear_step_halvings,
                                               settings.max_offset_deg)
        floor_m = _noise_floor_m(resolution)
        rounds = [_round(data, obs, config, settings, (), floor_m)]
        if _level_asked(rounds[0], settings):
            rounds.append(_level_round(obs, config, rounds[0], settings))
        while (rounds[-1].named or rounds[-1].level_of) and _another_round(rounds, settings):
            rounds.append(_round(data, obs, _final(rounds).extended_config, settings,
                                 _named(rounds), floor_m))
    first, final = rounds[0], _final(rounds)
    return JointDiagnosis(
        data=data, settings=settings, observations=obs, rounds=tuple(rounds),
        residual_structure=cycle_structure(data, config, obs, first.baseline, first.base_run),
        resolution=resolution,
        unexplained=tuple(
            unexplained_sentences(first.baseline, final.extended_fit, _named(rounds), resolution,
                                  [e for r in rounds for e in r.not_confirmed])
            + origin_at_bound(final.extended_fit, settings.max_offset_deg)),
        trace_notes=_trace_notes(data, config))


def _another_round(rounds: list[Round], settings: JointDiagnoseSettings) -> bool:
    """Whether fewer than ``max_causes`` are named and a cause is left to try on the model
    they extend."""
    named = _named(rounds)
    return (len(named) < settings.max_causes
            and bool(_to_try(_final(rounds).extended_config, settings, named)[0]))


def _level_asked(first: Round, settings: JointDiagnoseSettings) -> bool:
    """Whether the level of k is tried as a cause beside the first round's (:func:`_level_round`):
    with ``max_causes`` >= 2, after a first round that named one cause other than the level."""
    return (settings.max_causes >= 2 and first.named_cause is not None
            and first.named[0] != "wear_coefficient"
            and "wear_coefficient" in settings.candidates)


def _level_round(obs: Observations, config: dict, first: Round,
                 settings: JointDiagnoseSettings) -> Round:
    """Whether the level of k is a cause beside the ``first`` round's named cause. Every cause's fit
    has the level free, so a k level hidden beside a cause is carried inside that cause's fit and
    never named apart (on the third generator's pairs: k x 0.55 + running-in named running-in at
    level 0.70; k + friction named friction). So the named cause is fitted again in its named form
    with the level fixed at the believed one, its own parameters free and refined on runs as the
    cause's were (:func:`fit_at_believed_level`: nested in its fit), and the level is judged as a
    cause against that fit by the rule of a round (one cause tried) and, if accepted, confirmed on
    realizations: the cause's (those of the first round) against those of its model at the believed
    level (:mod:`fewear.diagnose.joint.confirmation`). Named, the level adds that gain, and the
    extended model stays the first round's. Unrefined, the fit at the believed level is the weaker
    for it and the level makes up the difference: on a power-law running-in alone (the independent
    generator's), running-in named in the exponential form at k x 1.42 had the level named beside it
    (gain 34 %, confirmed); refined, the level's gain is -12 %."""
    cause, named = first.named[0], first.named_cause
    pinned = replace(fit_at_believed_level(cause, named.form, obs, first.baseline, config,
                                           settings),
                     name=f"{cause} at the believed level of k")
    judged = verdict(replace(named.fit, name="wear_coefficient"), pinned, settings, 1)
    confirmations: tuple[Confirmation, ...] = ()
    baseline = pinned
    if judged.accepted:
        at_believed_level = CAUSES[cause].extended_config(config, pinned.params,
                                                          pinned.form or "")
        reference = realizations([at_believed_level], [pinned.name], obs, float(pinned.x[0]),
                                 settings.max_offset_deg)[0]
        baseline = reference.fits[0]
        confirmations = (confirm("wear_coefficient", named.realizations, reference,
                                 pinned.name, settings),)
    level_named = ("wear_coefficient",) if confirmations and confirmations[0].confirmed else ()
    return Round(baseline=baseline, base_run=None, verdicts=(judged,),
                 accepted=("wear_coefficient",) if judged.accepted else (), named=level_named,
                 confounded=(), confirmations=confirmations, untestable=(),
                 extended_config=first.extended_config, extended_fit=first.extended_fit,
                 extended_depth_m=first.extended_depth_m, level_of=cause)


def fit_at_believed_level(cause: str, form: Candidate, obs: Observations, baseline: Fit,
                          config: dict, settings: JointDiagnoseSettings) -> Fit:
    """``cause`` fitted in its ``form`` with the level of k fixed at the believed one, its own
    parameters free, and refined on runs of the believed ``config`` extended at its fitted
    parameters, as the cause was (:func:`fewear.diagnose.joint.refinement.fit_causes`,
    ``baseline`` the believed model's fit)."""
    pinned = (replace(form, level_free=False),)
    runs_at = _refinement_runs(config, candidate_runner(_reach(obs, CAUSE_RUN_REACH),
                                                        float(obs.depth_m.max())))
    return fit_causes({cause: pinned}, obs, baseline, settings, runs_at)[cause]


def _trace_notes(data: JointMeasurements, config: dict) -> tuple[str, ...]:
    """A sentence on each measured trace the evidence on the mechanism leaves out."""
    if not (data.acceleration or data.force):
        return ()
    return tuple(readable_traces(data, crank_period_s(config))[1])


def _final(rounds) -> Round:
    """The last round that named a cause (the first round without one): its extended model is
    the diagnosis's."""
    return next((r for r in reversed(rounds) if r.named), rounds[0])


def _named(rounds) -> tuple[str, ...]:
    """The causes the ``rounds`` named, in order."""
    return tuple(cause for r in rounds for cause in r.named)


def _to_try(config: dict, settings: JointDiagnoseSettings,
            named: tuple[str, ...]) -> tuple[list[str], list[dict]]:
    """The causes a round on ``config`` tries, and why the others cannot be: the testable ones
    (:func:`testable`) but those ``named`` so far and, after the first round,
    ``wear_coefficient`` (every cause's fit has the level of k free, so the model a round starts
    from carries its level already)."""
    names, untestable = testable(config, settings)
    return ([name for name in names
             if name not in named and not (named and name == "wear_coefficient")], untestable)


def _noise_floor_m(resolution: dict[str, Any]) -> float | None:
    """The larger of the instrument's scatter (estimated once, by the resolution) and the
    believed model's own noise (:func:`fewear.diagnose.joint.resolution.model_noise_m`); None
    without profiles to estimate the scatter from."""
    scatter = resolution["instrument_scatter_m"]
    return None if scatter is None else max(scatter, model_noise_m(resolution))


def _round(data: JointMeasurements, obs: Observations, config: dict,
           settings: JointDiagnoseSettings, named: tuple[str, ...],
           floor_m: float | None) -> Round:
    """One round of selection on the model ``config`` (the believed one, or the one the causes
    ``named`` so far extend) over the causes :func:`_to_try`; ``floor_m``: the noise below
    which no cause is named (:func:`_noise_floor_m`)."""
    reach, deepest_m = _reach(obs, CAUSE_RUN_REACH), float(obs.depth_m.max())
    label = " + ".join(("believed model",) + named)
    names, untestable = _to_try(config, settings, named)
    ahead = [(candidate_config(changed, reach, deepest_m), run_label)
             for name in names for changed, run_label in CAUSES[name].runs_asked(config, settings)]
    # the candidates' runs that do not need the believed run are made beside it
    base = simulate_wears([(_believed_config(config, obs, settings), label)] + ahead)[0]
    baseline = baseline_fit("baseline" if not named else label, base, obs,
                            settings.max_offset_deg)
    make_runs = candidate_runner(reach, deepest_m)
    believed_model = Believed(config, base, needed_cycles(obs, settings), make_runs)
    candidates = {name: CAUSES[name].forms(believed_model, settings) for name in names}
    untestable += [{"cause": name,
                    "untestable_reason": "every run with it switched on stops (far deeper than "
                    "the data, worn through or contact lost) before the cycles the fit needs"}
                   for name, forms in candidates.items() if not forms]
    candidates = {name: forms for name, forms in candidates.items() if forms}
    fits = fit_causes(candidates, obs, baseline, settings, _refinement_runs(config, make_runs))
    accepted, verdicts = select_causes(baseline, fits, settings, floor_m)
    if not accepted and not named and settings.max_causes >= 2:
        accepted, pair_verdicts, pair_fits = select_pairs(candidates, fits, obs, baseline,
                                                           settings, floor_m)
        verdicts, fits = verdicts + pair_verdicts, {**fits, **pair_fits}
    evidence = None if named else _trace_evidence(data, config, candidates, fits, base,
                                                   settings)
    by_traces = evidence.named.cause if evidence and evidence.named else None
    if by_traces:
        fits = {**fits, by_traces: _fit_on_trace_choice(candidates[by_traces], evidence.named,
                                                        obs, baseline, settings)}
        accepted = [by_traces] + [cause for cause in accepted if cause != by_traces]
    entry, extended, final_fit, extended_depth, confirmations, realized = confirm_first(
        config, accepted, fits, baseline, obs, settings, label, by_traces)
    return Round(baseline=baseline, base_run=base, verdicts=tuple(verdicts),
                 accepted=tuple(accepted), named=causes_of(entry) if entry else (),
                 confounded=confounded_verdicts(verdicts, accepted, entry),
                 confirmations=tuple(confirmations), untestable=tuple(untestable),
                 extended_config=extended, extended_fit=final_fit,
                 extended_depth_m=extended_depth, trace_evidence=evidence,
                 named_cause=_named_cause(entry, fits, candidates, realized))


def _named_cause(entry: str | None, fits: dict[str, Fit], candidates: dict,
                 realized: Realizations | None) -> NamedCause | None:
    """The round's :class:`NamedCause` for the ``entry`` it named (None: none, or a pair, whose
    forms are not among the ``candidates``)."""
    if entry not in candidates:
        return None
    fit = fits[entry]
    return NamedCause(fit, next(c for c in candidates[entry] if c.form == (fit.form or "")),
                      realized)


def _trace_evidence(data: JointMeasurements, config: dict, candidates: dict, fits: dict,
                    base: WearHistory, settings: JointDiagnoseSettings) -> TraceEvidence | None:
    """What the measured slider-acceleration and joint force traces say of the mechanism
    (:mod:`fewear.diagnose.joint.traces`): the believed mechanism and each grid run of the
    causes that change the dynamics, simulated on the bore the believed model wears by each
    trace's count at the k level fitted on the bore data (one run per model and count, side by
    side). None without traces of at least
    :data:`~fewear.diagnose.joint.traces.MIN_REVOLUTIONS` revolutions and three harmonics to
    read (:func:`~fewear.diagnose.joint.traces.readable_traces`)."""
    period = crank_period_s(config)
    usable, _ = readable_traces(data, period)
    if not usable:
        return None
    harmonics = min(harmonics_readable(trace.time_s, period) for trace in usable)
    level = fits["wear_coefficient"].params["k_scale"] if "wear_coefficient" in fits else 1.0
    counts = sorted({trace.cycles for trace in usable})
    kinds_at = {count: tuple(trace_kind(t) for t in usable if t.cycles == count)
                for count in counts}
    models = [("believed model", None, "", 0, config)] + _dynamics_options(config, candidates)
    runs = iter(side_by_side(simulated_signatures, [
        (model[4], base.angle_rad, base.nodal_depth_m(level * count), count, harmonics,
         kinds_at[count]) for model in models for count in counts]))
    simulated = []  # per model: {(count, kind): signature}
    for _ in models:
        signatures = {}
        for count in counts:
            signatures.update(zip(((count, kind) for kind in kinds_at[count]), next(runs)))
        simulated.append(signatures)
    kinds = [kind for kind in TRACE_KINDS if any(trace_kind(t) == kind for t in usable)]
    by_kind = []
    for kind in kinds:
        mine = [trace for trace in usable if trace_kind(trace) == kind]
        measured = [measured_signature(trace, period, harmonics) for trace in mine]
        by_kind.append([trace_misfit(measured, [model[(t.cycles, kind)] for t in mine])
                        for model in simulated])
    misfits, dispersions = combined_misfits(by_kind)
    options = [MechanismOption(label, cause, form, index, misfit)
               for (label, cause, form, index, _), misfit in zip(models[1:], misfits[1:])]
    return trace_verdict(misfits[0], options, harmonics, settings.acceptance.significance,
                         settings.acceptance.min_held_out_gain, tuple(zip(kinds, dispersions)))


def _dynamics_options(config: dict, candidates: dict) -> list[tuple]:
    """(label, cause, form, grid index, config) of each grid run of the candidate causes that
    change the dynamics, but the run whose config is the believed one."""
    models = []
    for name, forms in candidates.items():
        if not CAUSES[name].changes_dynamics:
            continue
        for candidate in forms:
            for index, value in enumerate(candidate.grid):
                changed = CAUSES[name].switched_on(config, value, candidate.form)
                if changed == config:
                    continue  # the grid's believed value (friction's grid holds it)
                models.append((f"{name}{' (' + candidate.form + ')' if candidate.form else ''}"
                               f", {candidate.parameter} = {value:g}", name, candidate.form,
                               index, changed))
    return models


def _fit_on_trace_choice(forms: tuple[Candidate, ...], option: MechanismOption,
                         obs: Observations, baseline: Fit,
                         settings: JointDiagnoseSettings) -> Fit:
    """The cause fitted on the bore data on the one run the traces chose (its level and angle
    offset free), its parameter the run's."""
    candidate = next(c for c in forms if c.form == option.form)
    alone = replace(candidate, runs=(candidate.runs[option.index],),
                    grid=(candidate.grid[option.index],))
    fitted = fit_form(alone, obs, float(baseline.x[0]), settings)
    return replace(fitted, params={**fitted.params,
                                   candidate.parameter: candidate.grid[option.index]})


CAUSE_RUN_REACH = 1.25
"""A cause's runs go this many times the last measured count: its grid's runs, made at the
believed k, and a refinement's, made at its fit's level. A fit's level s maps the data's N to
s N cycles of a run; beyond the run's last wear step the depth goes on at that step's rate
(:meth:`fewear.diagnose.joint.forward.WearHistory.nodal_depths_m`; on a bore whose depth grows as
N^0.7, 2 % too deep at s = 1.8), and a fit that could be accepted is refined on a run at its own
level. Fits at s up to 1.25 are those of longer runs (a run's wear blocks do not depend on
where it ends, but its last, shortened to end there). Not ``max_k_scale`` times (the level's bound):
on nine data sets of three generators every grid cause's fitted level was 0.90-1.26 but on a
running-in set (at the bound, and refuted), and the flexible grid's runs are the dearest of a
diagnosis."""


def _reach(obs: Observations, times: float) -> int:
    """``times`` the last measured count, in whole cycles: how far a round's runs go (the
    believed run's ``max_k_scale`` times, a cause's :data:`CAUSE_RUN_REACH` times)."""
    return int(math.ceil(times * obs.cycles.max()))


def _believed_config(config: dict, obs: Observations, settings: JointDiagnoseSettings) -> dict:
    """``config``'s rod run as far as the fits may need: ``max_k_scale`` times the last count
    (the level of k's bound), and further still, as running-in maps N to up to r N cycles of
    it."""
    return model_config(config, config["wear_loop"]["rod_models"][0],
                        RUNNING_IN_REACH * _reach(obs, settings.max_k_scale))


def _check_run_length(data, obs, believed_config: dict) -> None:
    """The forward runs go a few times the last measured cycle count: a count that makes them
    longer than a run may be (:data:`fewear.io.limits.MAX_WEAR_STEPS`) at the config's wear
    blocks is refused before any run, naming the count, the wear steps it would take and what
    would do."""
    from fewear.io.limits import MAX_WEAR_STEPS, SECONDS_PER_WEAR_STEP, duration, wear_steps

    loop = believed_config["wear_loop"]
    steps = wear_steps(loop)
    if steps > MAX_WEAR_STEPS:
        key = ("extrapolation_factor" if loop["extrapolation"] == "fixed"
               else "max_extrapolation_factor")
        raise FewearInputError(
            f"{', '.join(data.sources) or 'the measured data'}: the last measured cycle count "
            f"{int(obs.cycles.max()):,} makes each forward run of the believed model go to "
            f"{loop['total_cycles']:,} cycles, at least {steps:,} wear steps (about "
            f"{duration(steps * SECONDS_PER_WEAR_STEP)} per run); expected at most "
            f"{MAX_WEAR_STEPS:,}: check the cycles column (crank revolutions), or raise "
            f"[wear_loop] {key} in --config")


def _refinement_runs(config: dict, make_runs: RunMaker) -> RunsAt:
    """The runs the refinements ask for (made together by ``make_runs``): the extended model
    at each fit's parameters, its level included."""
    def runs_at(asked: list[tuple[Candidate, Fit]]) -> list[WearHistory]:
        requests = []
        for candidate, fitted in asked:
            cause, form = CAUSES[candidate.name], fitted.form or ""
            requests.append((cause.extended_config(config, fitted.params, form),
                             cause.run_label(fitted.params, form)))
        return make_runs(requests)

    return runs_at


