"""The evidence for a cause against the model it would extend, and the rule that accepts it: a
significant nested test (p below a Bonferroni threshold), a held-out gain, an AICc improvement
and, where asked, an effect larger than the scatter of a reading. One settings type,
:class:`AcceptanceSettings`, holds these thresholds for every data kind."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from fewear.diagnose.core.statistics import bonferroni_threshold
from fewear.errors import FewearInputError


@dataclass(frozen=True)
class Evidence:
    """What one cause's fit shows against its reference: ``p_value`` of the nested test,
    held-out ``gain`` (1 - held-out error / the reference's), ``aicc_improvement`` (the
    reference's AICc minus the cause's: positive favours the cause; NaN where undefined) and
    ``effect_over_scatter``: the largest change the cause makes to a fitted reading, over the
    RMS residual of the model with the cause (the scatter of a reading; inf where not
    measured)."""

    p_value: float
    gain: float
    aicc_improvement: float
    effect_over_scatter: float = math.inf


@dataclass(frozen=True)
class AcceptanceRule:
    """A cause is accepted when p < ``max_p``, its held-out gain exceeds ``min_gain`` (strictly
    when ``gain_strictly_above``, else at least equals it), its AICc improvement is at least
    ``min_aicc_improvement`` and its effect at least ``min_effect_over_scatter`` times the
    scatter of a reading."""

    max_p: float
    min_gain: float
    gain_strictly_above: bool
    min_aicc_improvement: float
    min_effect_over_scatter: float = 0.0

    def accepts(self, evidence: Evidence) -> bool:
        return bool(evidence.p_value < self.max_p and self.predicts_better(evidence)
                    and evidence.aicc_improvement >= self.min_aicc_improvement
                    and self.resolved(evidence))

    def resolved(self, evidence: Evidence) -> bool:
        """Whether the effect is at least the floor (in scatters of a reading)."""
        return evidence.effect_over_scatter >= self.min_effect_over_scatter

    def predicts_better(self, evidence: Evidence) -> bool:
        """Whether the held-out gain meets the rule."""
        if self.gain_strictly_above:
            return evidence.gain > self.min_gain
        return evidence.gain >= self.min_gain


ACCEPTANCE_KEYS = ("significance", "min_aicc_improvement", "min_held_out_gain",
                   "min_effect_over_scatter")
"""The config keys of :class:`AcceptanceSettings` (a section holds those its data kind uses)."""


@dataclass(frozen=True)
class AcceptanceSettings:
    """The acceptance thresholds of a diagnosis's config ``section`` (its name, for messages):
    ``significance``, the family-wise false-positive rate (Bonferroni over the forms tried);
    ``min_aicc_improvement``; ``min_held_out_gain``, the held-out gain a cause must reach (at
    least, or strictly above where ``gain_strictly_above``); ``min_effect_over_scatter``, the
    floor on a cause's effect in scatters of a reading (0: none)."""

    section: str
    significance: float
    min_aicc_improvement: float
    min_held_out_gain: float = 0.0
    gain_strictly_above: bool = False
    min_effect_over_scatter: float = 0.0

    def __post_init__(self):
        self._require("significance", 0.0 < self._number("significance") < 0.5,
                      "a number in (0, 0.5)")
        self._require("min_aicc_improvement", 0.0 <= self._number("min_aicc_improvement"),
                      "a number >= 0")
        self._require("min_held_out_gain", -1.0 < self._number("min_held_out_gain") < 1.0,
                      "a number in (-1, 1)")
        self._require("min_effect_over_scatter",
                      0.0 <= self._number("min_effect_over_scatter"), "a number >= 0")

    def _number(self, key: str) -> float:
        value = getattr(self, key)
        ok = isinstance(value, (int, float)) and not isinstance(value, bool)
        return float(value) if ok and math.isfinite(value) else math.nan

    def _require(self, key: str, ok: bool, expected: str) -> None:
        if not ok:
            raise FewearInputError(f"{self.section} {key} = {getattr(self, key)!r}: expected "
                                   f"{expected}")

    def rule(self, forms_tried: int) -> AcceptanceRule:
        """The rule a cause must meet at a step where ``forms_tried`` forms were fitted."""
        return AcceptanceRule(max_p=bonferroni_threshold(self.significance, forms_tried),
                              min_gain=self.min_held_out_gain,
                              gain_strictly_above=self.gain_strictly_above,
                              min_aicc_improvement=self.min_aicc_improvement,
                              min_effect_over_scatter=self.min_effect_over_scatter)

    @classmethod
    def split(cls, section: str, values: dict[str, Any], *, gain_strictly_above: bool = False
              ) -> tuple[AcceptanceSettings, dict[str, Any]]:
        """The acceptance settings of a config ``section``'s ``values`` and the other keys."""
        acceptance = {key: values[key] for key in ACCEPTANCE_KEYS if key in values}
        rest = {key: value for key, value in values.items() if key not in ACCEPTANCE_KEYS}
        return cls(section, gain_strictly_above=gain_strictly_above, **acceptance), rest
