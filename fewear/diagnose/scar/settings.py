"""The settings of the scar diagnosis: the ``[scar_diagnose]`` section of the config (its
defaults and why each value: ``fewear/defaults/diagnose.toml``)."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from fewear.diagnose.core.evidence import AcceptanceSettings
from fewear.diagnose.scar.catalogue import CAUSES
from fewear.errors import FewearInputError, require_whole_number
from fewear.io.config import load_config

WHERE = "[scar_diagnose]"


def _require_fraction(name: str, value: float, low: float, high: float) -> None:
    if not (isinstance(value, (int, float)) and low < value < high):
        raise FewearInputError(f"{WHERE} {name} = {value!r}: expected a number in "
                               f"({low:g}, {high:g})")


@dataclass(frozen=True)
class ScarDiagnoseSettings:
    """The ``[scar_diagnose]`` section (``fewear/defaults/diagnose.toml`` says why each value)."""

    candidates: tuple[str, ...]
    acceptance: AcceptanceSettings
    """significance, min_held_out_gain and min_aicc_improvement."""
    max_k_factor: float
    max_forward_runs: int
    factor_tolerance: float
    profile_blocks: int

    def __post_init__(self):
        unknown = [name for name in self.candidates if name not in CAUSES]
        if unknown or not self.candidates:
            raise FewearInputError(f"{WHERE} candidates = {list(self.candidates)!r}: expected a "
                                   f"non-empty list of {', '.join(CAUSES)}")
        _require_fraction("factor_tolerance", self.factor_tolerance, 0.0, 0.1)
        if not (isinstance(self.max_k_factor, (int, float)) and 1.0 < self.max_k_factor <= 100.0):
            raise FewearInputError(f"{WHERE} max_k_factor = {self.max_k_factor!r}: expected a "
                                   "number in (1, 100]")
        require_whole_number(f"{WHERE} max_forward_runs", self.max_forward_runs, 1, 100)
        require_whole_number(f"{WHERE} profile_blocks", self.profile_blocks, 2, 1000)

    @property
    def log_factor_bound(self) -> float:
        """The search's bound on ln(factor): ln ``max_k_factor``."""
        return math.log(self.max_k_factor)

    @property
    def log_factor_tolerance(self) -> float:
        """A fit is converged when its ln(factor) lies within ln(1 + ``factor_tolerance``) of a
        run's."""
        return math.log1p(self.factor_tolerance)

    @classmethod
    def from_config(cls, section: dict[str, Any]) -> ScarDiagnoseSettings:
        """From a ``[scar_diagnose]`` section (as :func:`fewear.io.config.load_config` gives)."""
        acceptance, values = AcceptanceSettings.split(WHERE, section)
        return cls(acceptance=acceptance, **{**values, "candidates": tuple(values["candidates"])})

    @classmethod
    def default(cls) -> ScarDiagnoseSettings:
        """The embedded defaults."""
        return cls.from_config(load_config(None, ["scar_diagnose"])["scar_diagnose"])
