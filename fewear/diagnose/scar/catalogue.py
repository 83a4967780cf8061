"""The causes the scar diagnosis tries: each one log-scale factor on a wear coefficient of the
believed scar model (the source's value times the factor)."""

from __future__ import annotations

from dataclasses import dataclass

from fewear.diagnose.core.cause import Cause


@dataclass(frozen=True)
class ScaledCoefficient:
    """What a cause scales: ``setting``, the field of the case's wear settings
    (:class:`fewear.loop.settings.SlidingWearSettings` or
    :class:`~fewear.loop.settings.FrettingWearSettings`); ``scales_worn_area``: whether the
    flat's worn area is proportional to it (Archard: A = k P' S), so that the ratio of the
    measured to the predicted area is a first guess of the factor."""

    setting: str
    scales_worn_area: bool

    def untestable_reason(self, wear_settings) -> str | None:
        """Why a factor on the coefficient cannot be fitted on a case's ``wear_settings`` (None:
        it can): the setting is absent from the case or zero (a factor on 0 changes nothing)."""
        value = getattr(wear_settings, self.setting, None)
        if value is None:
            return f"the case has no {self.setting}"
        if value <= 0.0:
            return f"{self.setting} = {value!r}: a factor on 0 changes nothing"
        return None


SCALED = {"wear_coefficient": ScaledCoefficient("wear_coefficient_m2_N", True),
          "cylinder_wear_coefficient": ScaledCoefficient("cylinder_wear_coefficient_m2_N", False)}
"""The coefficient each cause scales, by cause."""

_MEANINGS = {
    "wear_coefficient": "the flat's wear coefficient differs from the source's: the scar is the "
                        "believed model's at k times the fitted factor",
    "cylinder_wear_coefficient": "the cylinder's own wear coefficient k_c differs from the "
                                 "source's: its wear widens and flattens the flat's scar (the "
                                 "flat's worn area unchanged)",
}

CAUSES = {name: Cause(name, meaning, ("factor",), SCALED[name].untestable_reason)
          for name, meaning in _MEANINGS.items()}
"""The causes, by name; each untestable by the case's wear settings."""

NONE_MEANING = ("no cause named: the believed model with the source's wear coefficient predicts "
                "the held-out profile points as well as a fitted coefficient does")
