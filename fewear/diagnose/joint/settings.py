"""The settings of the joint diagnosis: the ``[joint_diagnose]`` section of the config (its
defaults and why each value: ``fewear/defaults/diagnose.toml``)."""

from __future__ import annotations

import math
from dataclasses import dataclass

from fewear.diagnose.core.evidence import AcceptanceSettings
from fewear.diagnose.joint.catalogue import CAUSES, IMPACT_FORMS
from fewear.errors import FewearInputError
from fewear.io.config import load_config

MAX_HALVINGS = 10
"""Halving the wear blocks more often than this makes runs 2^10 times dearer: beyond any use."""
MAX_K_SCALE = 100.0
"""The level of k is fitted within this factor of the believed one (the believed run goes this
many times the last measured cycle count: 1e9 made runs of 1e9 times the data's cycles)."""
MAX_OFFSET_DEG = 180.0
"""An angular origin offset beyond half a turn either way is the same offset again."""


def _listed(value):
    """A setting's value as the config file wrote it (a tuple back to a list)."""
    return list(value) if isinstance(value, tuple) else value


def _check_positive_numbers(name: str, values, expected: str, may_be_empty: bool) -> None:
    """Refuse ``values`` unless a tuple of finite numbers > 0 (empty only if ``may_be_empty``),
    naming the setting, its value and what is ``expected``."""
    if not isinstance(values, tuple) or (not values and not may_be_empty) or any(
            isinstance(value, bool) or not isinstance(value, (int, float))
            or not 0.0 < value < math.inf for value in values):
        raise FewearInputError(f"[joint_diagnose] {name} = {_listed(values)!r}: expected "
                               f"{expected}")


@dataclass(frozen=True)
class JointDiagnoseSettings:
    """The ``[joint_diagnose]`` section (``fewear/defaults/diagnose.toml`` says why each value)."""

    candidates: tuple[str, ...]
    acceptance: AcceptanceSettings
    """significance, min_aicc_improvement and min_held_out_gain."""
    held_out_fraction: float
    max_k_scale: float
    friction_grid: tuple[float, ...]
    rod_modulus_factors: tuple[float, ...]
    rod_damping_factors: tuple[float, ...]
    impact_volume_ratios: tuple[float, ...]
    impact_forms: tuple[str, ...]
    max_offset_deg: float
    max_causes: int
    max_wear_step_halvings: int

    def __post_init__(self):
        unknown = [c for c in self.candidates if c not in CAUSES]
        if unknown or not self.candidates:
            raise FewearInputError(
                f"[joint_diagnose] candidates = {list(self.candidates)!r}: expected a non-empty "
                f"list of {', '.join(CAUSES)}")
        if not 0.0 < self.held_out_fraction < 1.0:
            raise FewearInputError(
                f"[joint_diagnose] held_out_fraction = {self.held_out_fraction!r}: expected a "
                "fraction in (0, 1)")
        for name in ("rod_modulus_factors", "friction_grid", "impact_volume_ratios"):
            _check_positive_numbers(name, getattr(self, name), "a non-empty list of positive "
                                    "numbers", may_be_empty=False)
        _check_positive_numbers("rod_damping_factors", self.rod_damping_factors,
                                "a list of positive numbers (empty: the damping form is not "
                                "tried)", may_be_empty=True)
        if not self.impact_forms or not set(self.impact_forms) <= set(IMPACT_FORMS):
            raise FewearInputError(
                f"[joint_diagnose] impact_forms = {list(self.impact_forms)!r}: expected a "
                f"non-empty list of {', '.join(map(repr, IMPACT_FORMS))}")
        if isinstance(self.max_causes, bool) or not (isinstance(self.max_causes, int)
                                                      and self.max_causes >= 1):
            raise FewearInputError(
                f"[joint_diagnose] max_causes = {self.max_causes!r}: expected a whole number "
                ">= 1")
        if isinstance(self.max_wear_step_halvings, bool) or not (
                isinstance(self.max_wear_step_halvings, int)
                and 0 <= self.max_wear_step_halvings <= MAX_HALVINGS):
            raise FewearInputError(
                f"[joint_diagnose] max_wear_step_halvings = {self.max_wear_step_halvings!r}: "
                f"expected a whole number from 0 (the config's wear blocks as they are) to "
                f"{MAX_HALVINGS}")
        if not 1.0 < self.max_k_scale <= MAX_K_SCALE:
            raise FewearInputError(
                f"[joint_diagnose] max_k_scale = {self.max_k_scale!r}: expected > 1 and <= "
                f"{MAX_K_SCALE:g} (the believed run goes max_k_scale times the last measured "
                "cycle count: a wear coefficient further off is another model, not its level)")
        if not 0.0 <= self.max_offset_deg <= MAX_OFFSET_DEG:
            raise FewearInputError(
                f"[joint_diagnose] max_offset_deg = {self.max_offset_deg!r}: expected 0 to "
                f"{MAX_OFFSET_DEG:g} degrees (the instrument's angular origin within half a turn "
                "either way of the bushing frame's)")

    @classmethod
    def from_config(cls, section: dict) -> JointDiagnoseSettings:
        """From a ``[joint_diagnose]`` section (as :func:`fewear.io.config.load_config` returns
        it)."""
        acceptance, values = AcceptanceSettings.split("[joint_diagnose]", section)
        return cls(acceptance=acceptance,
                   **{key: tuple(v) if isinstance(v, list) else v for key, v in values.items()})

    @classmethod
    def default(cls) -> JointDiagnoseSettings:
        """The embedded defaults (``fewear/defaults/diagnose.toml``)."""
        return cls.from_config(load_config(None, sections=["joint_diagnose"])["joint_diagnose"])
