"""The settings of the tribometer diagnosis: the ``[diagnose]`` section of the config."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from fewear.diagnose.core.evidence import AcceptanceRule
from fewear.diagnose.core.statistics import bonferroni_threshold
from fewear.diagnose.tribometer.catalogue import CAUSES
from fewear.errors import FewearInputError
from fewear.io.config import load_config


@dataclass(frozen=True)
class DiagnoseSettings:
    """The ``[diagnose]`` section (see ``fewear/defaults/diagnose.toml`` for why each value)."""

    significance: float
    min_aicc_improvement: float
    min_readings_along_test: int
    min_conditions_for_network: int
    candidates: tuple[str, ...]
    prediction_distance_factor: float
    min_effect_over_scatter: float

    def __post_init__(self):
        where = "[diagnose]"
        if not 0.0 < self.significance < 0.5:
            raise FewearInputError(
                f"{where} significance = {self.significance!r}: expected 0 < alpha < 0.5")
        if not (math.isfinite(self.min_aicc_improvement) and self.min_aicc_improvement >= 0.0):
            raise FewearInputError(f"{where} min_aicc_improvement = "
                                   f"{self.min_aicc_improvement!r}: expected a number >= 0")
        if self.min_readings_along_test < 3:
            raise FewearInputError(
                f"{where} min_readings_along_test = {self.min_readings_along_test!r}: expected "
                ">= 3 (one for the test's own k, two for the curve's shape)")
        if self.min_conditions_for_network < 4:
            raise FewearInputError(
                f"{where} min_conditions_for_network = {self.min_conditions_for_network!r}: "
                "expected >= 4 (the network needs at least 4 tests)")
        if not (math.isfinite(self.min_effect_over_scatter)
                and self.min_effect_over_scatter >= 0.0):
            raise FewearInputError(f"{where} min_effect_over_scatter = "
                                   f"{self.min_effect_over_scatter!r}: expected a number >= 0")
        unknown = [name for name in self.candidates if name not in CAUSES]
        if unknown:
            raise FewearInputError(f"{where} candidates: unknown cause(s) {unknown}; the "
                                   "catalogue holds " + ", ".join(CAUSES))
        if not self.prediction_distance_factor > 1.0:
            raise FewearInputError(
                f"{where} prediction_distance_factor = {self.prediction_distance_factor!r}: "
                "expected a number > 1")

    def acceptance(self, forms_tried: int) -> AcceptanceRule:
        """The rule a cause must meet at a step where ``forms_tried`` forms were fitted: p below
        the Bonferroni threshold, a held-out gain above 0, AICc ``min_aicc_improvement`` lower
        and an effect of at least ``min_effect_over_scatter`` scatters of a reading."""
        return AcceptanceRule(max_p=bonferroni_threshold(self.significance, forms_tried),
                              min_gain=0.0, gain_strictly_above=True,
                              min_aicc_improvement=self.min_aicc_improvement,
                              min_effect_over_scatter=self.min_effect_over_scatter)

    @classmethod
    def from_config(cls, section: dict[str, Any]) -> DiagnoseSettings:
        """From a ``[diagnose]`` section (as :func:`fewear.io.config.load_config` returns it)."""
        values = dict(section)
        values["candidates"] = tuple(values["candidates"])
        return cls(**values)

    @classmethod
    def default(cls) -> DiagnoseSettings:
        """The embedded defaults (``fewear/defaults/diagnose.toml``)."""
        return cls.from_config(load_config(None, sections=["diagnose"])["diagnose"])
