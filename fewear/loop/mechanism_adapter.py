"""The wear loop's one door to the mechanism (:mod:`fewear.io.mechanism` for each clearance
joint's view of the config, :mod:`fewear.mbd.mechanism` for the dynamics): the typed inputs of a
case with its clearance joints as clearance joints, a wear block's settling and recorded cycles,
and one run on the joints' worn clearances."""

from __future__ import annotations

from dataclasses import replace

from fewear.io.mechanism import joint_sections  # noqa: F401 (the loop's door to it)
from fewear.mbd.mechanism import MechanismState, simulate  # noqa: F401 (the checkpoint's state)

JOINT = "rod_slider"
"""The paper's slider-crank's one clearance joint (between the connecting rod and the slider)."""


def dynamics_inputs(config: dict, case: str):
    """The typed dynamics inputs of one case (the variable body's model ``case``), its clearance
    joints as clearance joints (a wear run wears them, whatever ``[mechanism] joint`` says)."""
    from fewear.io.mechanism import dynamics_inputs as mechanism_inputs

    return replace(mechanism_inputs(config, case), ideal_joints=False)


def block_inputs(inputs, recorded_cycles: int, settling_cycles: int | None):
    """``inputs`` recording ``recorded_cycles`` driver cycles after ``settling_cycles`` (None: the
    mechanism's own, for a start from the assembled mechanism)."""
    settling = inputs.settling_cycles if settling_cycles is None else settling_cycles
    return replace(inputs, recorded_cycles=recorded_cycles, settling_cycles=settling)


def unintegrable_hint() -> str:
    """What to change when the dynamics cannot integrate the unworn mechanism."""
    from fewear.mbd.slider_crank import UNINTEGRABLE_HINT

    return UNINTEGRABLE_HINT
