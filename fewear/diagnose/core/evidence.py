"""The evidence for a cause against the model it would extend, and the rule that accepts it.

Both data kinds accept a cause on three counts: its nested test is significant (p below a
Bonferroni threshold), it predicts what was held out better (held-out gain
1 - e_cause / e_reference), and its extra parameters pay for themselves (AICc lower by a minimum).
The kinds differ in how much held-out gain they ask for (:class:`AcceptanceRule`). A cause may
also have to change the model's predictions by more than the scatter of a reading: with enough
readings an effect far inside the scatter (a k that rises by 2 % under 3 % noise) becomes
significant, but it is not a finding the data resolve.
"""

from __future__ import annotations

import math
from dataclasses import dataclass


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
