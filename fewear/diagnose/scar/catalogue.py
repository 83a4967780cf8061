"""The causes the scar diagnosis tries: each one log-scale factor on a wear coefficient of the
believed scar model (the source's value times the factor)."""

from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Cause:
    """A cause: ``setting``, the field of the case's wear settings
    (:class:`fewear.loop.settings.SlidingWearSettings` or
    :class:`~fewear.loop.settings.FrettingWearSettings`) it scales; ``scales_worn_area``: whether
    the flat's worn area is proportional to it (Archard: A = k P' S), so that the ratio of the
    measured to the predicted area is a first guess of the factor; ``meaning``: what a named
    cause says."""

    name: str
    setting: str
    scales_worn_area: bool
    meaning: str


CAUSES = {
    "wear_coefficient": Cause(
        "wear_coefficient", "wear_coefficient_m2_N", True,
        "the flat's wear coefficient differs from the source's: the scar is the believed model's "
        "at k times the fitted factor"),
    "cylinder_wear_coefficient": Cause(
        "cylinder_wear_coefficient", "cylinder_wear_coefficient_m2_N", False,
        "the cylinder's own wear coefficient k_c differs from the source's: its wear widens and "
        "flattens the flat's scar (the flat's worn area unchanged)"),
}

NONE_MEANING = ("no cause named: the believed model with the source's wear coefficient predicts "
                "the held-out profile points as well as a fitted coefficient does")


def untestable_reason(cause: Cause, settings) -> str | None:
    """Why ``cause`` cannot be fitted on a case's wear ``settings`` (None: it can): the setting
    is absent from the case or zero (a factor on 0 changes nothing)."""
    value = getattr(settings, cause.setting, None)
    if value is None:
        return f"the case has no {cause.setting}"
    if value <= 0.0:
        return f"{cause.setting} = {value!r}: a factor on 0 changes nothing"
    return None
