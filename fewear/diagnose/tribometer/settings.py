"""The settings of the tribometer diagnosis: the ``[diagnose]`` section of the config."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from fewear.diagnose.core.evidence import AcceptanceSettings
from fewear.diagnose.tribometer.catalogue import CAUSES
from fewear.errors import FewearInputError
from fewear.io.config import load_config

SECTION = "[diagnose]"


@dataclass(frozen=True)
class DiagnoseSettings:
    """The ``[diagnose]`` section (see ``fewear/defaults/diagnose.toml`` for why each value)."""

    acceptance: AcceptanceSettings
    """significance, min_aicc_improvement and min_effect_over_scatter; a cause's held-out gain
    must be above 0."""
    min_readings_along_test: int
    min_conditions_for_network: int
    candidates: tuple[str, ...]
    prediction_distance_factor: float

    def __post_init__(self):
        where = SECTION
        if self.min_readings_along_test < 3:
            raise FewearInputError(
                f"{where} min_readings_along_test = {self.min_readings_along_test!r}: expected "
                ">= 3 (one for the test's own k, two for the curve's shape)")
        if self.min_conditions_for_network < 4:
            raise FewearInputError(
                f"{where} min_conditions_for_network = {self.min_conditions_for_network!r}: "
                "expected >= 4 (the network needs at least 4 tests)")
        unknown = [name for name in self.candidates if name not in CAUSES]
        if unknown:
            raise FewearInputError(f"{where} candidates: unknown cause(s) {unknown}; the "
                                   "catalogue holds " + ", ".join(CAUSES))
        if not self.prediction_distance_factor > 1.0:
            raise FewearInputError(
                f"{where} prediction_distance_factor = {self.prediction_distance_factor!r}: "
                "expected a number > 1")

    @classmethod
    def from_config(cls, section: dict[str, Any]) -> DiagnoseSettings:
        """From a ``[diagnose]`` section (as :func:`fewear.io.config.load_config` returns it)."""
        acceptance, values = AcceptanceSettings.split(SECTION, section, gain_strictly_above=True)
        return cls(acceptance=acceptance, **{**values, "candidates": tuple(values["candidates"])})

    @classmethod
    def default(cls) -> DiagnoseSettings:
        """The embedded defaults (``fewear/defaults/diagnose.toml``)."""
        return cls.from_config(load_config(None, sections=["diagnose"])["diagnose"])
