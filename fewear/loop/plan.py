"""What a ``fewear run`` wears, parsed once from the config at the command's edge: its cases,
its clearance joints with their typed inputs, and where each block's joint histories come from
(the case's dynamics on the worn clearances, or one imported history, the same every block)."""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import partial
from pathlib import Path
from typing import NamedTuple

from fewear.errors import FewearInputError
from fewear.loop.settings import RunInputs, WearLoopSettings, joint_inputs_from_config

IMPORTED_CASE, IMPORTED_JOINT = "imported", "joint"
"""The one case and joint of a run on an imported joint history."""
MEMBER_START_STEP_DEG = 1.0
"""How far on the driver starts in each member after the first (deg of its cycle)."""


class Member(NamedTuple):
    """One run of an ensemble: its ``case`` and its ``index``, whose start is the driver
    ``index * MEMBER_START_STEP_DEG`` degrees further on (member 0: the configured start, the
    single run). A run's work items are its members, each run alone on its process or ranks."""

    case: str
    index: int = 0

    @property
    def key(self) -> str:
        """Its name in the checkpoint and the messages: member 0 by its case alone."""
        return self.case if self.index == 0 else f"{self.case}-member{self.index}"

    @property
    def start_offset_deg(self) -> float:
        return self.index * MEMBER_START_STEP_DEG


@dataclass(frozen=True)
class RunPlan:
    """``cases``: the case names (the rod models; one ``IMPORTED_CASE`` for an imported
    history); ``joints``: clearance joint name -> its :class:`RunInputs`, in file order;
    ``imported``: the imported :class:`fewear.mbd.history.JointHistory` (None: the dynamics
    make the histories) read from ``history_file``, whose bytes have ``history_sha256``."""

    cases: tuple[str, ...]
    joints: dict
    imported: object = None
    history_file: str = ""
    history_sha256: str = ""  # of the imported history's file (a resume checks it)

    @property
    def loop(self) -> WearLoopSettings:
        return next(iter(self.joints.values())).loop

    @property
    def members(self) -> tuple[Member, ...]:
        """The work items: ``[wear_loop] members`` members of every case, case by case."""
        return tuple(Member(case, index) for case in self.cases
                     for index in range(self.loop.members))

    @property
    def history_source(self) -> str:
        """Where the joint histories come from, in words (summary.json, the progress lines)."""
        if self.imported is None:
            return "the dynamics of the case on the worn clearances, every block"
        return (f"imported from {self.history_file} (SHA-256 {self.history_sha256}): the same "
                "history every block, no feedback of the wear to the dynamics")

    def simulate_block(self, config: dict, member: Member):
        """Stage 1 of a member's blocks: (states, mechanism) -> ((joint name -> history, summary,
        final state), wall time in s) (:func:`fewear.loop.block.predict_joints`)."""
        if self.imported is not None:
            return partial(_imported_block, self.imported)
        from fewear.loop import mechanism_adapter as adapter
        from fewear.loop.block import mechanism_dynamics

        return partial(mechanism_dynamics, member.case, adapter.dynamics_inputs(
            config, member.case, member.start_offset_deg), self.joints)


def _imported_block(history, states: dict, mechanism):
    """The imported history for the one joint, whatever its wear: no dynamics, no time."""
    return ({IMPORTED_JOINT: history}, None, None), 0.0


def run_plan(config: dict) -> RunPlan:
    """The :class:`RunPlan` of a complete ``fewear run`` config (``[wear_loop] joint_history``
    given: the config's own joint sections worn with that history)."""
    from fewear.io.joint_history import read_joint_history
    from fewear.loop import mechanism_adapter as adapter

    history_file = config["wear_loop"].get("joint_history", "")
    if history_file:
        inputs: RunInputs = joint_inputs_from_config(config)
        if inputs.loop.members > 1:
            raise FewearInputError(
                f"[wear_loop] members = {inputs.loop.members}: the members of an ensemble differ "
                "in the start of the dynamics, and an imported joint history has none; "
                "members = 1")
        history = read_joint_history(Path(history_file), inputs.loop.recorded_cycles_per_block,
                                     impacts=inputs.impact_law.wears_by_impacts)
        digest = hashlib.sha256(Path(history_file).read_bytes()).hexdigest()
        return RunPlan((IMPORTED_CASE,), {IMPORTED_JOINT: inputs}, history, history_file,
                       digest)
    joints = {name: joint_inputs_from_config(view)
              for name, view in adapter.joint_sections(config).items()}
    cases = tuple(next(iter(joints.values())).loop.rod_models)
    last_start_deg = (joints[next(iter(joints))].loop.members - 1) * MEMBER_START_STEP_DEG
    for case in cases:  # their input errors here, at the edge
        adapter.dynamics_inputs(config, case)
        if last_start_deg:
            adapter.dynamics_inputs(config, case, last_start_deg)
    return RunPlan(cases, joints)
