"""The evidence for a cause against the model it would extend, and the rule that accepts it.

Both data kinds accept a cause on three counts: its nested test is significant (p below a
Bonferroni threshold), it predicts what was held out better (held-out gain
1 - e_cause / e_reference), and its extra parameters pay for themselves (AICc lower by a minimum).
The kinds differ in how much held-out gain they ask for (:class:`AcceptanceRule`).
"""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Evidence:
    """What one cause's fit shows against its reference: ``p_value`` of the nested test,
    held-out ``gain`` (1 - held-out error / the reference's) and ``aicc_improvement`` (the
    reference's AICc minus the cause's: positive favours the cause; NaN where undefined)."""

    p_value: float
    gain: float
    aicc_improvement: float


@dataclass(frozen=True)
class AcceptanceRule:
    """A cause is accepted when p < ``max_p``, its held-out gain exceeds ``min_gain`` (strictly
    when ``gain_strictly_above``, else at least equals it) and its AICc improvement is at least
    ``min_aicc_improvement``."""

    max_p: float
    min_gain: float
    gain_strictly_above: bool
    min_aicc_improvement: float

    def accepts(self, evidence: Evidence) -> bool:
        return bool(evidence.p_value < self.max_p and self.predicts_better(evidence)
                    and evidence.aicc_improvement >= self.min_aicc_improvement)

    def predicts_better(self, evidence: Evidence) -> bool:
        """Whether the held-out gain meets the rule."""
        if self.gain_strictly_above:
            return evidence.gain > self.min_gain
        return evidence.gain >= self.min_gain
