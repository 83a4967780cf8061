"""The loop's inputs: the ``[wear_loop]`` settings and everything ``fewear run`` needs, parsed once
from the config at the command's edge into typed stage inputs."""

from __future__ import annotations

import math
from dataclasses import dataclass

from fewear.errors import FewearInputError, require_finite_positive, require_whole_number
from fewear.wear.extrapolation import ExtrapolationSettings
from fewear.wear.impact import NO_IMPACT_WEAR, ImpactWearLaw

RUN_SECTIONS = ["wear_loop", "wear"]
MAX_WEAR_STEPS_PER_BLOCK = 64
"""Each wear step solves the contact of every load step of the recorded cycles once more."""
MAX_SMOOTHING_WIDTH_DEG = 90.0
"""A Gaussian of this standard deviation spreads a contact's wear over the whole bore."""
MAX_MEMBERS = 360
"""Members start 1 degree of the driver's cycle apart: 360 of them cover the cycle."""


@dataclass(frozen=True)
class WearLoopSettings:
    """The ``[wear_loop]`` section (seed section 5 values by default)."""

    rod_models: tuple[str, ...]
    load_steps_per_cycle: int
    total_cycles: int
    friction_in_contact: bool
    extrapolation: ExtrapolationSettings
    recorded_cycles_per_block: int
    wear_steps_per_block: int
    warm_settling_cycles: int
    max_wall_fraction: float
    implicit_wear_step: bool
    wear_smoothing_width_deg: float
    compliance_update: str
    joint_history: str = ""  # a joint-history CSV worn with, no dynamics ("": none)
    members: int = 1  # runs per case, their starts 1 deg apart (fewear.loop.plan.Member)

    def __post_init__(self):
        unknown = [rod for rod in self.rod_models if rod not in ("rigid", "flexible")]
        if unknown or not self.rod_models or len(set(self.rod_models)) != len(self.rod_models):
            raise FewearInputError(
                f"[wear_loop] rod_models = {list(self.rod_models)!r}: expected a non-empty list of "
                "'rigid' and/or 'flexible', each once")
        if self.load_steps_per_cycle < 2:
            raise FewearInputError(
                f"[wear_loop] load_steps_per_cycle = {self.load_steps_per_cycle}: expected >= 2")
        if self.total_cycles < 1:
            raise FewearInputError(f"[wear_loop] total_cycles = {self.total_cycles}: expected >= 1")
        if self.recorded_cycles_per_block < 1 or self.warm_settling_cycles < 0:
            raise FewearInputError(
                f"[wear_loop] recorded_cycles_per_block = {self.recorded_cycles_per_block}, "
                f"warm_settling_cycles = {self.warm_settling_cycles}: expected >= 1 and >= 0")
        if not 1 <= self.wear_steps_per_block <= MAX_WEAR_STEPS_PER_BLOCK:
            raise FewearInputError(
                f"[wear_loop] wear_steps_per_block = {self.wear_steps_per_block}: expected 1 to "
                f"{MAX_WEAR_STEPS_PER_BLOCK} wear steps on each block's recorded cycles")
        if not 0.0 <= self.wear_smoothing_width_deg <= MAX_SMOOTHING_WIDTH_DEG:
            raise FewearInputError(
                f"[wear_loop] wear_smoothing_width_deg = {self.wear_smoothing_width_deg!r}: "
                f"expected 0 (no smoothing) to {MAX_SMOOTHING_WIDTH_DEG:g} degrees of the bore")
        if isinstance(self.members, bool) or not isinstance(self.members, int) \
                or not 1 <= self.members <= MAX_MEMBERS:
            raise FewearInputError(
                f"[wear_loop] members = {self.members!r}: expected a whole number of ensemble "
                f"members from 1 to {MAX_MEMBERS} (runs of each case, their starts 1 deg apart)")
        if not 0.0 < self.max_wall_fraction < 1.0:
            raise FewearInputError(
                f"[wear_loop] max_wall_fraction = {self.max_wall_fraction}: expected a fraction "
                "of the bushing wall in (0, 1)")

    @classmethod
    def from_config(cls, section: dict) -> WearLoopSettings:
        values = dict(section)
        extrapolation = ExtrapolationSettings(
            mode=values.pop("extrapolation"), factor=values.pop("extrapolation_factor"),
            max_factor=values.pop("max_extrapolation_factor"),
            max_depth_increment_fraction=values.pop("max_depth_increment_fraction"))
        return cls(**{**values, "rod_models": tuple(values["rod_models"]),
                      "extrapolation": extrapolation})


@dataclass(frozen=True)
class RunInputs:
    """What the wear loop needs for one clearance joint, parsed once from the config (or the
    joint's view of it, :func:`joint_inputs_from_config`) at the command's edge.

    ``dynamics``: the slider-crank's inputs (None for a joint of a mechanism, whose dynamics the
    run's case owns); ``joint``: the clearance joint's model (its contact law, for the
    hysteresis work of the load steps)."""

    dynamics: object  # fewear.mbd.slider_crank.DynamicsInputs or None
    contact: object  # fewear.contact.params.ContactProblem
    wear_coefficient: object  # k(p, v), fewear.wear.coefficient
    extension: object  # the wear law's history multiplier, fewear.wear.extensions
    loop: WearLoopSettings
    impact_law: ImpactWearLaw = NO_IMPACT_WEAR  # the impacts' wear (fewear.wear.impact)
    joint: object = None  # fewear.mbd.slider_crank.JointModel (default: the dynamics')

    def __post_init__(self):
        if self.joint is None and self.dynamics is not None:
            object.__setattr__(self, "joint", self.dynamics.joint)


def run_sections() -> list[str]:
    """The config sections ``fewear run`` reads."""
    from fewear.contact.params import CONFIG_SECTIONS
    from fewear.mbd.slider_crank import SECTIONS as DYNAMICS_SECTIONS

    return list(dict.fromkeys([*RUN_SECTIONS, *CONFIG_SECTIONS, *DYNAMICS_SECTIONS]))


def run_inputs_from_config(config: dict) -> RunInputs:
    """The :class:`RunInputs` of the slider-crank's one clearance joint, its dynamics included."""
    from fewear.mbd.slider_crank import dynamics_inputs_from_config

    dynamics = dynamics_inputs_from_config(config)
    return _with_dynamics(joint_inputs_from_config(config), dynamics)


def joint_inputs_from_config(view: dict) -> RunInputs:
    """The :class:`RunInputs` of one clearance joint from its view of the config (the run's
    config with the joint's own [bushing], [pin], [joint], [clearance_joint], [wear], [mesh] and
    [contact]), without dynamics: the case's mechanism owns them."""
    from fewear.contact.params import contact_problem_from_config
    from fewear.mbd.slider_crank import joint_model_from_config
    from fewear.wear.coefficient import wear_coefficient_from_config
    from fewear.wear.extensions import wear_extension_from_config

    return RunInputs(None, contact_problem_from_config(view),
                     wear_coefficient_from_config(view["wear"]),
                     wear_extension_from_config(view["wear"]),
                     WearLoopSettings.from_config(view["wear_loop"]),
                     ImpactWearLaw.from_config(view["wear"]), joint_model_from_config(view))


def _with_dynamics(inputs: RunInputs, dynamics) -> RunInputs:
    from dataclasses import replace

    return replace(inputs, dynamics=dynamics, joint=dynamics.joint)


@dataclass(frozen=True)
class SlidingWearSettings:
    """A flat worn by a cylinder sliding over it at constant normal force (block on ring,
    :mod:`fewear.loop.flat_wear`).

    ``normal_force_N``: P (N); ``sliding_distance_m``: S (m), imposed at every node in contact;
    ``wear_coefficient_m2_N``: Archard's dimensional k of the flat (m^2/N = 1/Pa);
    ``wear_steps``: N, the wear steps of S/N each (a whole number in [1, 10000]).
    """

    normal_force_N: float
    sliding_distance_m: float
    wear_coefficient_m2_N: float
    wear_steps: int = 30

    def __post_init__(self):
        for name in ("normal_force_N", "sliding_distance_m", "wear_coefficient_m2_N"):
            require_finite_positive(name, getattr(self, name))
        require_whole_number("wear_steps", self.wear_steps, 1, 10000)

    @property
    def slide_m(self) -> float:
        """The slide of one wear step, S/N (m)."""
        return self.sliding_distance_m / self.wear_steps


@dataclass(frozen=True)
class FrettingWearSettings:
    """A flat worn by a cylinder fretting over it at constant normal force
    (:mod:`fewear.loop.fretting`).

    ``normal_force_N``: P (N); ``stroke_amplitude_m``: d (m), the centre's stroke +-d;
    ``increments_per_cycle``: n, the stroke cycle's frictional steps (a whole multiple of 4);
    ``cycles``: the test's cycles; ``cycles_per_block``: the cycles one solved cycle stands for
    (a divisor of ``cycles``); ``wear_coefficient_m2_N``: Archard's dimensional k of the flat
    (m^2/N = 1/Pa); ``cylinder_wear_coefficient_m2_N``: the cylinder's (>= 0; 0: it does not
    wear).
    """

    normal_force_N: float
    stroke_amplitude_m: float
    increments_per_cycle: int
    cycles: int
    cycles_per_block: int
    wear_coefficient_m2_N: float
    cylinder_wear_coefficient_m2_N: float = 0.0

    def __post_init__(self):
        for name in ("normal_force_N", "stroke_amplitude_m", "wear_coefficient_m2_N"):
            require_finite_positive(name, getattr(self, name))
        cylinder = self.cylinder_wear_coefficient_m2_N
        if not (isinstance(cylinder, (int, float)) and math.isfinite(cylinder) and cylinder >= 0):
            raise FewearInputError(f"cylinder_wear_coefficient_m2_N = {cylinder!r}: must be a "
                                   "finite number >= 0")
        for name, largest in (("increments_per_cycle", 10000), ("cycles", 10**9),
                              ("cycles_per_block", 10**9)):
            require_whole_number(name, getattr(self, name), 1, largest)
        if self.increments_per_cycle % 4:
            raise FewearInputError(
                f"increments_per_cycle = {self.increments_per_cycle!r}: must be a whole "
                "multiple of 4 (the stroke's ends and middle at increments)")
        if self.cycles % self.cycles_per_block:
            raise FewearInputError(
                f"cycles_per_block = {self.cycles_per_block!r}: must divide cycles = "
                f"{self.cycles!r} (every block stands for the same number of cycles)")

    @property
    def blocks(self) -> int:
        """The wear blocks, cycles / cycles_per_block."""
        return self.cycles // self.cycles_per_block
