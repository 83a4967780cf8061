"""The believed scar model run at a scaled wear coefficient (DOLFINx): ``fewear scar``'s case
(``[scar] case``) built from the config once, into its typed stage inputs
(:func:`fewear.loop.scar.block_on_ring_from_config`,
:func:`~fewear.loop.scar.fretting_from_config`), each run the same problem with the wear
settings' coefficient times a factor (:func:`dataclasses.replace`)."""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np
from mpi4py import MPI

from fewear.contact.params import FlatContactProblem
from fewear.diagnose.scar.catalogue import CAUSES, SCALED
from fewear.errors import FewearInputError
from fewear.loop.scar import (
    SCAR_CASES,
    block_on_ring_from_config,
    fretting_from_config,
    require_zone_holds_the_scar,
)
from fewear.loop.settings import FrettingWearSettings, SlidingWearSettings


@dataclass(frozen=True)
class ScarModel:
    """The believed scar model: ``case`` ("block_on_ring" or "fretting"), its contact
    ``problem`` and wear ``settings`` as the config gives them (the source's coefficients)."""

    case: str
    problem: FlatContactProblem
    settings: SlidingWearSettings | FrettingWearSettings

    @classmethod
    def from_config(cls, config: dict) -> ScarModel:
        """The model of the config's ``[scar] case`` and its sections (``fewear scar``'s)."""
        case = config["scar"]["case"]
        if case not in SCAR_CASES:
            raise FewearInputError(f"[scar] case = {case!r}: expected one of "
                                   + ", ".join(repr(name) for name in SCAR_CASES))
        build = block_on_ring_from_config if case == "block_on_ring" else fretting_from_config
        return cls(case, *build(config))

    def untestable_reason(self, cause: str) -> str | None:
        """Why ``cause`` cannot be fitted in this case (None: it can)."""
        return CAUSES[cause].why_untestable(self.settings)

    def coefficient_m2_N(self, cause: str) -> float:
        """The source's value of the coefficient ``cause`` scales (m^2/N)."""
        return float(getattr(self.settings, SCALED[cause].setting))

    def depth_on(self, x_m: np.ndarray, cause: str, factor: float) -> np.ndarray:
        """The predicted scar's depth (m) at ``x_m`` (linear between the FE top nodes) with the
        coefficient of ``cause`` times ``factor``: one forward run, on this process alone."""
        setting = SCALED[cause].setting
        settings = replace(self.settings,
                           **{setting: getattr(self.settings, setting) * factor})
        if self.case == "block_on_ring":
            from fewear.loop.flat_wear import run_flat_wear

            try:
                require_zone_holds_the_scar(self.problem, settings)
            except FewearInputError as exc:
                raise FewearInputError(f"{cause} x{factor:.4g}: {exc}") from None
            run = run_flat_wear(self.problem, settings, MPI.COMM_SELF)
        else:
            from fewear.loop.fretting import run_fretting_wear

            run = run_fretting_wear(self.problem, settings, MPI.COMM_SELF)
        return run.state.depth_at(x_m)
