"""The catalogue of the joint diagnosis: each cause declared by a
:class:`fewear.diagnose.core.cause.Cause` (untestable by the believed config) and fitted by a
:class:`CauseModel`: the runs of the wear loop it is fitted on, one :class:`Candidate` per form,
and what the believed config becomes at a fit's parameters."""

from __future__ import annotations

import copy
import math
from dataclasses import dataclass
from typing import Protocol

from fewear.diagnose.core.cause import Cause
from fewear.diagnose.joint.candidates import (
    RUNNING_IN_FORMS,
    Candidate,
    lasting,
    running_in_extension,
)
from fewear.diagnose.joint.forward import (
    RunMaker,
    WearHistory,
    impact_measures_per_cycle,
    unworn_volume_per_cycle_m3,
)
from fewear.wear import impact
from fewear.wear.extensions import extension_to_config

IMPACT_FORMS = impact.FORM_CONFIG_KEYS
"""The forms of ``impact_wear``: the [wear] key of each (:mod:`fewear.wear.impact`)."""
NONE_MEANING = "the believed model predicts the held-out measurements within their scatter"
"""What naming no cause means."""


class RunGrids(Protocol):
    """What the causes' runs are made at (of the ``[joint_diagnose]`` settings)."""

    friction_grid: tuple[float, ...]
    rod_modulus_factors: tuple[float, ...]
    rod_damping_factors: tuple[float, ...]
    impact_volume_ratios: tuple[float, ...]
    impact_forms: tuple[str, ...]


@dataclass(frozen=True, eq=False)
class Believed:
    """The believed model as the causes see it: its ``config`` and its ``run``;
    ``needed_cycles``, the shortest run a fit can use (a run that stops before is left out);
    ``make_runs``, how a cause's runs are made from ``[(config, label), ...]``."""

    config: dict
    run: WearHistory
    needed_cycles: float
    make_runs: RunMaker


class CauseModel:
    """How a departure from the believed model (``cause``) is fitted, the base of the
    catalogue's models: the level of k is always free, so every cause must beat
    :class:`WearCoefficient`, the cheapest explanation."""

    cause: Cause
    changes_dynamics = False
    """Whether the cause changes the mechanism's dynamics (what measured traces can show)."""

    @property
    def name(self) -> str:
        return self.cause.name

    @property
    def meaning(self) -> str:
        return self.cause.meaning

    def forms(self, believed: Believed, settings: RunGrids) -> tuple[Candidate, ...]:
        """The runs the cause is fitted on, one candidate per form (none: untestable)."""
        raise NotImplementedError

    def runs_asked(self, config: dict, settings: RunGrids) -> list[tuple[dict, str]]:
        """The runs ``[(config, label), ...]`` that :meth:`forms` asks for on the believed
        ``config`` and do not depend on its run (made beside it, in one batch)."""
        return []

    def extended_config(self, config: dict, params: dict, form: str) -> dict:
        """The believed ``config`` with the cause at a fit's ``params`` (in its ``form``), k
        scaled by the fitted level."""
        extended = copy.deepcopy(config)
        _scale_wear_coefficient(extended, params["k_scale"])
        return extended

    def run_label(self, params: dict, form: str) -> str:
        """How a run at a fit's ``params`` is named in the progress lines."""
        return f"{self.name} refined: k x {params['k_scale']:.3g}"


def _scale_wear_coefficient(config: dict, k_scale: float) -> None:
    """Scale the config's wear coefficient k(p, v) by ``k_scale`` in place."""
    wear = config["wear"]
    if wear["coefficient_model"] == "constant":
        wear["constant_k_m2_N"] = wear["constant_k_m2_N"] * k_scale
    else:  # the RBF network's ln k has the constant tail[0]
        wear["rbf"]["tail"] = [wear["rbf"]["tail"][0] + math.log(k_scale),
                               *wear["rbf"]["tail"][1:]]


def _extension_present(config: dict) -> str | None:
    extension = config["wear"]["extension"]
    if extension != "none":
        return f"the believed model has a [wear] extension ({extension}) already"
    return None


def _rod_flexible(config: dict) -> str | None:
    if config["wear_loop"]["rod_models"][0] == "flexible":
        return "the believed model's rod is flexible"
    return None


class WearCoefficient(CauseModel):
    """Only the level s of k is off: the believed run with its cycles scaled by s."""

    cause = Cause("wear_coefficient", "only the level of the wear coefficient k is off", ("",))

    def forms(self, believed: Believed, settings: RunGrids) -> tuple[Candidate, ...]:
        return (Candidate(self.name, (believed.run,)),)


class RunningIn(CauseModel):
    """k falls from r k to k over each node's first metres of sliding or over the first crank
    cycles: the believed run's cycles mapped node by node, one form per [wear] extension of
    :data:`RUNNING_IN_FORMS`."""

    cause = Cause("running_in", "the joint runs in: k is higher over the first cycles and falls "
                  "to its steady value", tuple(RUNNING_IN_FORMS), _extension_present)

    def forms(self, believed: Believed, settings: RunGrids) -> tuple[Candidate, ...]:
        return tuple(self.candidate(believed.run, form) for form in RUNNING_IN_FORMS)

    def candidate(self, run: WearHistory, form: str) -> Candidate:
        """The form ``form`` on the time map of ``run``."""
        return Candidate(self.name, (run,), form=form, time_map=True)

    def extended_config(self, config: dict, params: dict, form: str) -> dict:
        extended = super().extended_config(config, params, form)
        extended["wear"].update(extension_to_config(running_in_extension(form, params)))
        return extended

    def run_label(self, params: dict, form: str) -> str:
        law = running_in_extension(form, params).params()
        return (f"running-in ({form}), "
                + ", ".join(f"{key} = {value:.3g}" for key, value in law.items())
                + f", k x {params['k_scale']:.3g}")


class GridCause(CauseModel):
    """A cause fitted on runs with it switched on at a grid of values of one parameter, the runs
    interpolated between (or, ``discrete``, one of them chosen); ``parameter_scales_with_level``:
    the fitted level s scales the parameter too (it is a wear rate)."""

    parameter: str
    discrete = False
    parameter_scales_with_level = False

    def parameter_of(self, form: str) -> str:
        """The name of the parameter the runs of ``form`` are on (as in a fit's ``params``)."""
        return self.parameter

    def switched_on(self, config: dict, value: float, form: str = "") -> dict:
        """The believed ``config`` with the cause at ``value``."""
        raise NotImplementedError

    def candidate(self, runs, grid, form: str = "") -> Candidate:
        """The form ``form`` on ``runs`` made at the parameter values ``grid``."""
        return Candidate(self.name, tuple(runs), tuple(grid), form, discrete=self.discrete,
                         parameter=self.parameter_of(form),
                         parameter_scales_with_level=self.parameter_scales_with_level)

    def extended_config(self, config: dict, params: dict, form: str) -> dict:
        changed = self.switched_on(config, params[self.parameter_of(form)], form)
        return super().extended_config(changed, params, form)

    def run_label(self, params: dict, form: str) -> str:
        key = self.parameter_of(form)
        return f"{super().run_label(params, form)}, {key} = {params[key]:.3g}"


class FlexibleLink(GridCause):
    """The believed rigid rod is a flexible ANCF rod, its Young's modulus one of a grid of
    factors on the believed one (the form "", at the believed damping) or, the form "damping",
    its structural damping ``rod_damping_s`` one of a grid of factors on the believed one (at the
    believed modulus; only where ``rod_damping_factors`` is not empty): the worn bore does not
    follow either smoothly, so the runs are not interpolated; the best on the training data is
    taken (a discrete choice)."""

    cause = Cause("flexible_link", "the connecting rod modelled rigid is flexible: its "
                  "compliance changes the impacts and the continuous-contact sliding in the joint",
                  ("", "damping"), _rod_flexible)
    discrete = True
    changes_dynamics = True

    def parameter_of(self, form: str) -> str:
        return "rod_damping_factor" if form == "damping" else "rod_youngs_modulus_factor"

    def switched_on(self, config: dict, value: float, form: str = "") -> dict:
        changed = copy.deepcopy(config)
        changed["wear_loop"]["rod_models"] = ["flexible"]
        key = "rod_damping_s" if form == "damping" else "rod_youngs_modulus_Pa"
        changed["mechanism"][key] *= float(value)
        return changed

    def forms(self, believed: Believed, settings: RunGrids) -> tuple[Candidate, ...]:
        runs = iter(believed.make_runs(self.runs_asked(believed.config, settings)))
        forms = []
        for form, grid in self._grids(settings):
            made = [next(runs) for _ in grid]
            forms += lasting(self.candidate(made, grid, form), believed.needed_cycles)
        return tuple(forms)

    def runs_asked(self, config: dict, settings: RunGrids) -> list[tuple[dict, str]]:
        return [(self.switched_on(config, f, form),
                 f"flexible rod, {'damping' if form else 'E'} x {f:g}")
                for form, grid in self._grids(settings) for f in grid]

    @staticmethod
    def _grids(settings: RunGrids) -> list[tuple[str, list[float]]]:
        """(form, its sorted factors) of the forms with factors to run."""
        return [(form, sorted(grid)) for form, grid in (("", settings.rod_modulus_factors),
                                                        ("damping", settings.rod_damping_factors))
                if grid]


class Friction(GridCause):
    """The friction coefficient differs: runs on a grid of mu (the believed one is the believed
    run), the worn bore interpolated linearly between neighbouring runs."""

    cause = Cause("friction", "the friction coefficient in the joint differs from the assumed one",
                  ("",))
    parameter = "friction_coefficient"
    changes_dynamics = True

    def switched_on(self, config: dict, value: float, form: str = "") -> dict:
        changed = copy.deepcopy(config)
        changed["joint"]["friction_coefficient"] = float(value)
        return changed

    def forms(self, believed: Believed, settings: RunGrids) -> tuple[Candidate, ...]:
        assumed = believed.config["joint"]["friction_coefficient"]
        grid = sorted(set(settings.friction_grid) | {assumed})
        others = iter(believed.make_runs(self.runs_asked(believed.config, settings)))
        runs = [believed.run if mu == assumed else next(others) for mu in grid]
        return lasting(self.candidate(runs, grid), believed.needed_cycles)

    def runs_asked(self, config: dict, settings: RunGrids) -> list[tuple[dict, str]]:
        """The grid's values but the believed one (its run is the believed run)."""
        assumed = config["joint"]["friction_coefficient"]
        return [(self.switched_on(config, mu), f"mu = {mu:g}")
                for mu in sorted(set(settings.friction_grid) | {assumed}) if mu != assumed]


class ImpactWear(GridCause):
    """The impacts wear too (:mod:`fewear.wear.impact`), by energy, by impulse (above the
    believed config's force threshold) or by a power of the impact speed (the believed config's
    exponent; one form each, :data:`IMPACT_FORMS`): runs at coefficients such that the impact
    volume is a set multiple of the sliding volume on the unworn joint, interpolated. The level
    s scales both wear rates, so the coefficient reported and written to the extended config is
    s times the grid's."""

    cause = Cause("impact_wear", "the impacts remove material too (wear in proportion to the "
                  "energy the contact dissipates, to the impacts' impulse or to a power of their "
                  "speed), not only the sliding", tuple(IMPACT_FORMS))
    parameter_scales_with_level = True

    def parameter_of(self, form: str) -> str:
        return IMPACT_FORMS[form]

    def switched_on(self, config: dict, value: float, form: str = "") -> dict:
        changed = copy.deepcopy(config)
        changed["wear"][IMPACT_FORMS[form]] = float(value)
        return changed

    def forms(self, believed: Believed, settings: RunGrids) -> tuple[Candidate, ...]:
        grids = self._grids(believed.config, settings)
        runs = iter(believed.make_runs(self._requests(believed.config, grids)))
        forms = []
        for form, grid in grids:
            made = [believed.run] + [next(runs) for _ in grid[1:]]
            forms += lasting(self.candidate(made, grid, form), believed.needed_cycles)
        return tuple(forms)

    def runs_asked(self, config: dict, settings: RunGrids) -> list[tuple[dict, str]]:
        return self._requests(config, self._grids(config, settings))

    def _requests(self, config: dict, grids: list[tuple[str, list[float]]]):
        """The grids' runs but the believed coefficient's (the believed run)."""
        return [(self.switched_on(config, c, form), f"{IMPACT_FORMS[form]} = {c:.3g}")
                for form, grid in grids for c in grid[1:]]

    def _grids(self, config: dict, settings: RunGrids) -> list[tuple[str, list[float]]]:
        """(form, [the believed coefficient, then one per ``impact_volume_ratios``]) of each
        form whose measure the unworn joint's impacts reach (none above a force threshold: not
        tried). The scale, sliding volume over impact measure per cycle on the unworn bore, comes
        from a run of the believed config's first wear step and a cycle of its dynamics."""
        measures = impact_measures_per_cycle(config)
        volume = unworn_volume_per_cycle_m3(config)
        grids = []
        for form in settings.impact_forms:
            if not measures[form] > 0.0:
                continue
            assumed = config["wear"].get(IMPACT_FORMS[form], 0.0)
            per_unit = volume / measures[form]
            grids.append((form, [assumed] + [assumed + ratio * per_unit
                                             for ratio in sorted(settings.impact_volume_ratios)]))
        return grids


CAUSES: dict[str, CauseModel] = {cause.name: cause for cause in (
    WearCoefficient(), FlexibleLink(), Friction(), ImpactWear(), RunningIn())}
"""The catalogue, by name, in the order the causes are listed."""
