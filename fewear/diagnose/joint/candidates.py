"""A cause's form as runs of the wear loop (:class:`Candidate`), the forms of running-in, and
which runs last long enough for a fit (the joint diagnosis, :mod:`fewear.diagnose.joint.diagnose`).
"""

from __future__ import annotations

from dataclasses import dataclass, fields, replace

import numpy as np

from fewear.diagnose.joint.forward import WearHistory
from fewear.wear.extensions import (
    RunningIn,
    RunningInCycles,
    RunningInCyclesPowerLaw,
    RunningInPowerLaw,
)

RUNNING_IN_FORMS = {"exponential": RunningIn, "power_law": RunningInPowerLaw,
                    "cycles": RunningInCycles, "cycles_power_law": RunningInCyclesPowerLaw}
"""The forms of ``running_in``: the [wear] extension of each (its ``name``); the first two are
driven by each node's sliding distance, the ``cycles`` ones by the crank cycles (both
:class:`RunningInCycles`)."""


@dataclass(frozen=True, eq=False)
class Candidate:
    """One form of a cause as runs of the wear loop: ``runs`` at the values ``grid`` of its
    ``parameter`` (one run: no grid; ``discrete``: one of the runs is chosen, not interpolated
    between; ``parameter_scales_with_level``: the parameter is a wear rate, scaled by the fitted
    level s too); ``time_map``: each run's cycles are mapped node by node by the running-in form
    :attr:`map_form` (a key of :data:`RUNNING_IN_FORMS`): the cause's ``form`` for running-in
    itself, ``running_in_form`` for another cause's runs with running-in on top (a pair,
    :mod:`fewear.diagnose.joint.pairs`); ``form``: '' for a cause with one form.
    ``k_scales``: the wear coefficient's level each run was made with (empty: the believed k for
    all; a refinement's run has its fit's); ``run_extension``: the running-in its one run was made
    with (None: none). ``level_free``: False fixes the level at the believed one (s = 1: its fit
    has one parameter fewer and is nested in the cause's)."""

    name: str
    runs: tuple[WearHistory, ...]
    grid: tuple[float, ...] = ()
    form: str = ""
    discrete: bool = False
    run_extension: RunningIn | RunningInPowerLaw | RunningInCycles | None = None
    k_scales: tuple[float, ...] = ()
    parameter: str | None = None
    parameter_scales_with_level: bool = False
    time_map: bool = False
    running_in_form: str = ""
    level_free: bool = True

    @property
    def map_form(self) -> str:
        """The running-in form of the time map."""
        return self.running_in_form or self.form

    @property
    def position_index(self) -> int:
        """Where the position on the runs sits in a fit's x = (phi_deg, ln s, [ln(r - 1),
        ln s0,] position) (a discrete choice's run index alike)."""
        return 4 if self.time_map else 2

    def k_scale(self, run: int) -> float:
        """The level of k run ``run`` was made with."""
        return self.k_scales[run] if self.k_scales else 1.0

    @property
    def n_extra(self) -> int:
        """The parameters of the cause's own: r - 1 and the scale (time map) and the position
        on the grid (several runs)."""
        return 2 * self.time_map + (len(self.runs) > 1)


def running_in_extension(form: str, params: dict):
    """The [wear] extension of running-in ``form`` at a fit's ``params``."""
    extension = RUNNING_IN_FORMS[form]
    return extension(**{law.name: params[law.name] for law in fields(extension)})


def grid_value(candidate: Candidate, position: float) -> float:
    """The parameter value at a fractional ``position`` in a grid cause's runs (linear)."""
    return float(np.interp(position, np.arange(len(candidate.grid)), candidate.grid))


def lasts(run: WearHistory, needed_cycles: float) -> bool:
    """Whether ``run`` ran on (or stopped no earlier than ``needed_cycles``)."""
    return not run.stopped or run.cycles[-1] >= needed_cycles


def lasting(candidate: Candidate, needed_cycles: float) -> tuple[Candidate, ...]:
    """``candidate`` without the runs that stopped before ``needed_cycles``, as a tuple of one
    form; empty if no run is left or, for a grid interpolated between runs, only one."""
    keep = [i for i, run in enumerate(candidate.runs) if lasts(run, needed_cycles)]
    if not keep or (len(keep) < 2 and not candidate.discrete):
        return ()
    return (replace(candidate, runs=tuple(candidate.runs[i] for i in keep),
                    grid=tuple(candidate.grid[i] for i in keep)),)
