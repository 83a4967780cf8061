"""STAND-IN for the mechanism branch (CONTRACT.md items 1-3): the wear loop's only door to the
mechanism, today the paper's slider-crank with its one clearance joint, "rod_slider".

When fewear.io.mechanism and fewear.mbd.mechanism exist, this module is replaced by them:
``joint_sections`` by :func:`fewear.io.mechanism.joint_sections`, ``dynamics_inputs`` and
``simulate`` by :func:`fewear.mbd.mechanism.dynamics_inputs` and
:func:`fewear.mbd.mechanism.simulate`, ``MechanismState`` by the mechanism's state type; the
loop's own needs that the contract leaves open are the last two functions here
(``block_inputs``: the recorded and settling cycles of one wear block; ``unintegrable_hint``).
"""

from __future__ import annotations

from dataclasses import replace

from fewear.mbd.slider_crank import MechanismState  # noqa: F401 (the checkpoint rebuilds it)

JOINT = "rod_slider"
"""The slider-crank's one clearance joint (between the connecting rod and the slider)."""


def joint_sections(config: dict) -> dict[str, dict]:
    """Every clearance joint's view of the config, by name in file order (CONTRACT.md item 1):
    the slider-crank's one joint sees the run's config."""
    return {JOINT: config}


def dynamics_inputs(config: dict, case: str):
    """The typed dynamics inputs of one case (CONTRACT.md item 3): the slider-crank with the
    connecting-rod model ``case`` ("rigid" or "flexible") and its clearance joint."""
    from fewear.mbd.slider_crank import dynamics_inputs_from_config

    inputs = dynamics_inputs_from_config(config)
    return replace(inputs, crank=replace(inputs.crank, rod=case, joint="clearance"))


def block_inputs(inputs, recorded_cycles: int, settling_cycles: int | None):
    """``inputs`` recording ``recorded_cycles`` crank cycles after ``settling_cycles`` (None: the
    mechanism's own, for a start from the ideal mechanism)."""
    settling = inputs.crank.settling_cycles if settling_cycles is None else settling_cycles
    return replace(inputs, crank=replace(inputs.crank, recorded_cycles=recorded_cycles,
                                         settling_cycles=settling))


def simulate(inputs, start=None, profiles: dict | None = None):
    """(histories: joint name -> :class:`fewear.mbd.history.JointHistory`, summary, final
    state) of one run of the mechanism (CONTRACT.md item 2), each joint on its clearance
    profile of ``profiles`` (None: the config's)."""
    from fewear.mbd.slider_crank import simulate as simulate_slider_crank

    if profiles:
        inputs = replace(inputs, joint=replace(inputs.joint, profile=profiles[JOINT]))
    history, summary, state = simulate_slider_crank(inputs, start=start)
    return {JOINT: history}, summary, state


def unintegrable_hint() -> str:
    """What to change when the dynamics cannot integrate the unworn mechanism."""
    from fewear.mbd.slider_crank import UNINTEGRABLE_HINT

    return UNINTEGRABLE_HINT
