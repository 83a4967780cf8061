"""The wear loop's one door to the mechanism (:mod:`fewear.io.mechanism` for each clearance
joint's view of the config, :mod:`fewear.mbd.mechanism` for the dynamics): the typed inputs of a
case with its clearance joints as clearance joints, a wear block's settling and recorded cycles,
and one run on the joints' worn clearances."""

from __future__ import annotations

import math
from dataclasses import replace

from fewear.io.mechanism import joint_sections  # noqa: F401 (the loop's door to it)
from fewear.mbd.mechanism import MechanismState, simulate  # noqa: F401 (the checkpoint's state)


def dynamics_inputs(config: dict, case: str, start_offset_deg: float = 0.0):
    """The typed dynamics inputs of one case (the variable body's model ``case``), its clearance
    joints as clearance joints (a wear run wears them, whatever ``[mechanism] joint`` says), the
    driver started ``start_offset_deg`` further on (an ensemble's member): the paper's
    slider-crank's ``[mechanism] initial_crank_angle_deg`` plus it, as the wear demo's members;
    a mechanism file's constant-speed drivers each at their ``angle_deg`` plus it."""
    from fewear.io.mechanism import dynamics_inputs as mechanism_inputs
    from fewear.io.mechanism import mechanism_path

    from_file = mechanism_path(config) is not None
    if start_offset_deg and not from_file:
        section = config["mechanism"]
        config = {**config, "mechanism": {
            **section,
            "initial_crank_angle_deg": section["initial_crank_angle_deg"] + start_offset_deg}}
    inputs = replace(mechanism_inputs(config, case), ideal_joints=False)
    if start_offset_deg and from_file:
        inputs = replace(inputs, mechanism=_started_later(inputs.mechanism, start_offset_deg))
    return inputs


def _started_later(mechanism, offset_deg: float):
    """``mechanism`` with each driver's angle at t = 0 ``offset_deg`` further on."""
    from fewear.errors import FewearInputError

    tabulated = [driver.body for driver in mechanism.drivers if driver.tabulated]
    if tabulated:
        raise FewearInputError(
            f"[wear_loop] members > 1: the driver of {tabulated[0]!r} follows a table (time_s, "
            "angle_deg); the members start constant-speed drivers (speed_rpm) 1 degree apart, "
            "so run this mechanism with members = 1")
    offset_rad = math.radians(offset_deg)
    return replace(mechanism, drivers=tuple(
        replace(driver, initial_angle_rad=driver.initial_angle_rad + offset_rad)
        for driver in mechanism.drivers))


def block_inputs(inputs, recorded_cycles: int, settling_cycles: int | None):
    """``inputs`` recording ``recorded_cycles`` driver cycles after ``settling_cycles`` (None: the
    mechanism's own, for a start from the assembled mechanism)."""
    settling = inputs.settling_cycles if settling_cycles is None else settling_cycles
    return replace(inputs, recorded_cycles=recorded_cycles, settling_cycles=settling)


def unintegrable_hint() -> str:
    """What to change when the dynamics cannot integrate the unworn mechanism."""
    from fewear.mbd.slider_crank import UNINTEGRABLE_HINT

    return UNINTEGRABLE_HINT
