"""The paper's slider-crank (seed section 5): its parameters ([mechanism] keys), its description
as a general mechanism (:func:`describe`, simulated by :mod:`fewear.mbd.mechanism`) and the
single-joint entry points the commands and the wear loop call.

Layout (SI units): the crank turns about the ground point O = (0, 0) at the constant speed omega,
angle theta(t) = theta0 + omega t from the x axis; the connecting rod joins the crank pin
A = r (cos theta, sin theta) to the rod-slider joint B; the slider moves along the x axis (y = 0)
without rotating, and the bushing is fixed to it with its centre at the slider's centre of mass.
Closed form of the ideal mechanism (rigid, no clearance):
sin beta = -r sin theta / l,  x_B = r cos theta + l cos beta,
x_B' = -r omega sin theta - l beta' sin beta,  beta' = -r omega cos theta / (l cos beta).

The crank is driven (a constraint), so its inertia does not change the joint forces, only the
driving torque. Gravity acts along -y (the plane of the mechanism is vertical).

Rod: rigid (mass rho A l, inertia m l^2/12 about its centre) or an
:class:`fewear.mbd.ancf.AncfBeam` of ``rod_elements`` elements (pin at its last node): the
description's variable body. Rod-slider joint "rod_slider": ideal revolute, or a clearance joint
with the bushing on the slider and the data of [bushing], [pin], [joint], [clearance_joint].
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.config import Config, load_config
from fewear.mbd.contact import pin_reach_m
from fewear.mbd.description import GROUND, Bar, Body, Driver, Joint, Mechanism, PointRef
from fewear.mbd.history import JointHistory
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings
from fewear.mbd.mechanism import (
    JointModel,
    MechanismInputs,
    MechanismModel,
    MechanismState,
    RunSummary,
    joint_model_from_config,
)
from fewear.mbd.mechanism import simulate as simulate_mechanism

CLEARANCE_JOINT = "rod_slider"
"""The name of the joint between the connecting rod and the slider (the paper's clearance joint)."""

UNINTEGRABLE_HINT = ("a value of [mechanism], [clearance_joint] or [integrator] makes the "
                     "mechanism too stiff, too light or too fast to integrate (compare with "
                     "`fewear config`)")
"""What to check when the integrator's step size collapses on a mechanism (a RuntimeError of
:func:`simulate`), for the commands' error messages."""

SECTIONS = ("mechanism", "clearance_joint", "integrator", "dynamics_output", "bushing", "pin",
            "joint")


@dataclass(frozen=True)
class SliderCrank:
    """Mechanism parameters ([mechanism] section; SI units)."""

    crank_length_m: float = 0.1
    crank_mass_kg: float = 0.3
    crank_inertia_kg_m2: float = 2.5e-4
    crank_speed_rpm: float = 1200.0
    initial_crank_angle_deg: float = 0.0
    rod_length_m: float = 0.34
    rod_density_kg_m3: float = 7800.0
    rod_youngs_modulus_Pa: float = 211.0e9
    rod_poisson_ratio: float = 0.3
    rod_height_m: float = 0.005
    rod_width_m: float = 0.018
    rod_elements: int = 4
    rod_damping_s: float = 0.0
    slider_mass_kg: float = 0.5
    gravity_m_s2: float = 9.81
    rod: str = "flexible"
    joint: str = "clearance"
    settling_cycles: int = 2
    recorded_cycles: int = 1

    def __post_init__(self):
        for name in ("crank_length_m", "crank_mass_kg", "crank_inertia_kg_m2", "rod_length_m",
                     "rod_density_kg_m3", "rod_youngs_modulus_Pa", "rod_height_m", "rod_width_m",
                     "slider_mass_kg", "crank_speed_rpm"):
            value = getattr(self, name)
            if not (value > 0.0 and math.isfinite(value)):
                raise FewearInputError(f"[mechanism] {name} = {value!r}: expected > 0")
        if self.rod_length_m <= self.crank_length_m:
            raise FewearInputError(
                f"[mechanism] rod_length_m = {self.rod_length_m!r} must exceed crank_length_m = "
                f"{self.crank_length_m!r} (else the slider-crank cannot turn a full cycle)")
        if self.rod not in ("rigid", "flexible"):
            raise FewearInputError(f"[mechanism] rod = {self.rod!r}: expected rigid or flexible")
        if self.joint not in ("clearance", "ideal"):
            raise FewearInputError(
                f"[mechanism] joint = {self.joint!r}: expected clearance or ideal")
        if self.rod_elements < 1:
            raise FewearInputError(
                f"[mechanism] rod_elements = {self.rod_elements!r}: expected >= 1")
        if self.settling_cycles < 0 or self.recorded_cycles < 1:
            raise FewearInputError(
                f"[mechanism] settling_cycles = {self.settling_cycles!r}, recorded_cycles = "
                f"{self.recorded_cycles!r}: expected >= 0 and >= 1")
        if not self.rod_damping_s >= 0.0:
            raise FewearInputError(
                f"[mechanism] rod_damping_s = {self.rod_damping_s!r}: expected >= 0")
        if self.gravity_m_s2 < 0.0:
            raise FewearInputError(f"[mechanism] gravity_m_s2 = {self.gravity_m_s2!r}: >= 0")

    @property
    def omega_rad_s(self) -> float:
        return self.crank_speed_rpm * 2.0 * math.pi / 60.0

    @property
    def period_s(self) -> float:
        return 2.0 * math.pi / self.omega_rad_s

    @property
    def rod_mass_kg(self) -> float:
        return self.rod_density_kg_m3 * self.rod_height_m * self.rod_width_m * self.rod_length_m

    def closed_form(self, time_s):
        """(theta, x_B, x_B') of the ideal rigid mechanism at the given times."""
        r, rod, omega = self.crank_length_m, self.rod_length_m, self.omega_rad_s
        theta = math.radians(self.initial_crank_angle_deg) + omega * np.asarray(time_s)
        sin_beta = -r * np.sin(theta) / rod
        cos_beta = np.sqrt(1.0 - sin_beta**2)
        beta_dot = -r * omega * np.cos(theta) / (rod * cos_beta)
        x = r * np.cos(theta) + rod * cos_beta
        v = -r * omega * np.sin(theta) - rod * beta_dot * sin_beta
        return theta, x, v


@dataclass(frozen=True)
class DynamicsInputs:
    """The slider-crank's dynamics inputs, parsed once from the config: the mechanism
    ([mechanism]), the clearance joint ([bushing], [pin], [joint], [clearance_joint]) and the
    integrator settings ([integrator]). :func:`mechanism_inputs` turns them into the general
    :class:`fewear.mbd.mechanism.MechanismInputs`."""

    crank: SliderCrank
    joint: JointModel
    integrator: IntegratorSettings


def template_keys(section: dict) -> dict:
    """The [mechanism] keys of the slider-crank template (all but ``file``)."""
    return {key: value for key, value in section.items() if key != "file"}


def dynamics_inputs_from_config(config: Config) -> DynamicsInputs:
    """The :class:`DynamicsInputs` of the config sections of ``SECTIONS`` (the slider-crank of
    the [mechanism] keys; a mechanism file needs :func:`fewear.io.mechanism.dynamics_inputs`)."""
    if config["mechanism"].get("file"):
        raise FewearInputError(
            f"[mechanism] file = {config['mechanism']['file']!r}: this command runs the paper's "
            "slider-crank only (leave file empty); `fewear dynamics` runs any mechanism")
    return DynamicsInputs(SliderCrank(**template_keys(config["mechanism"])),
                          joint_model_from_config(config),
                          IntegratorSettings(**config["integrator"]))


def describe(crank: SliderCrank) -> Mechanism:
    """The slider-crank as a mechanism description (fewear/mechanisms/slider_crank.toml is the
    same with the default values): the bodies at the poses of the ideal mechanism's closed form,
    the rod the variable body (``crank.rod``), the rod-slider joint "rod_slider" with clearance
    (bushing on the slider)."""
    r, rod, omega = crank.crank_length_m, crank.rod_length_m, crank.omega_rad_s
    theta = math.radians(crank.initial_crank_angle_deg)
    _, x_b, _ = crank.closed_form(0.0)
    beta = math.asin(-r * math.sin(theta) / rod)
    a = r * np.array([math.cos(theta), math.sin(theta)])
    axis = np.array([math.cos(beta), math.sin(beta)])
    bar = Bar(rod, crank.rod_density_kg_m3, crank.rod_height_m, crank.rod_width_m,
              crank.rod_youngs_modulus_Pa, crank.rod_poisson_ratio, crank.rod_elements,
              crank.rod_damping_s)
    bodies = (
        Body("crank", "rigid", crank.crank_mass_kg, crank.crank_inertia_kg_m2,
             (("O", (-r / 2.0, 0.0)), ("A", (r / 2.0, 0.0))), (a[0] / 2, a[1] / 2), theta),
        Body("rod", crank.rod, bar.mass_kg, bar.inertia_kg_m2,
             (("A", (-rod / 2.0, 0.0)), ("B", (rod / 2.0, 0.0))),
             tuple(a + rod / 2 * axis), beta, bar),
        Body("slider", "rigid", crank.slider_mass_kg, crank.slider_mass_kg * 1e-4,
             (("B", (0.0, 0.0)),), (float(x_b), 0.0), 0.0),
    )
    joints = (
        Joint("crank_ground", "revolute", PointRef("crank", "O"), PointRef(GROUND, "O")),
        Joint("crank_rod", "revolute", PointRef("crank", "A"), PointRef("rod", "A")),
        Joint("slider_ground", "prismatic", PointRef(GROUND, "O"), PointRef("slider", "B")),
        Joint(CLEARANCE_JOINT, "revolute", PointRef("rod", "B"), PointRef("slider", "B"),
              clearance=True),
    )
    return Mechanism("slider_crank", bodies, (("O", (0.0, 0.0)),), joints,
                     (Driver("crank", theta, omega),), crank.gravity_m_s2, "rod")


def mechanism_inputs(inputs: DynamicsInputs) -> MechanismInputs:
    """The general inputs of the slider-crank's (joint "rod_slider"), starting from the ideal
    mechanism's closed form (:func:`closed_form_state`)."""
    crank = inputs.crank
    mechanism, joints = describe(crank), {CLEARANCE_JOINT: inputs.joint}
    return MechanismInputs(mechanism, joints, inputs.integrator, crank.settling_cycles,
                           crank.recorded_cycles, crank.joint == "ideal",
                           closed_form_state(crank, MechanismModel(mechanism, joints)))


def closed_form_state(crank: SliderCrank, model: MechanismModel) -> MechanismState:
    """The ideal rigid mechanism at t = 0 (pin centred), from the closed form; a flexible rod
    straight, moving rigidly. The general assembly (:func:`fewear.mbd.mechanism.assemble`)
    finds the same state to rounding, but the clearance joint's history is chaotic at that
    level: starting from the closed form keeps the runs what they were, to the last bit."""
    r, rod, omega = crank.crank_length_m, crank.rod_length_m, crank.omega_rad_s
    theta = math.radians(crank.initial_crank_angle_deg)
    _, x_b, v_b = crank.closed_form(0.0)
    beta = math.asin(-r * math.sin(theta) / rod)
    beta_dot = -r * omega * math.cos(theta) / (rod * math.cos(beta))
    a = r * np.array([math.cos(theta), math.sin(theta)])
    v_a = r * omega * np.array([-math.sin(theta), math.cos(theta)])
    axis = np.array([math.cos(beta), math.sin(beta)])
    normal = np.array([-math.sin(beta), math.cos(beta)])
    n = model.system.n_coordinates
    q, qd = np.zeros(n), np.zeros(n)
    i_crank, i_rod, i_slider = (model.first[name] for name in ("crank", "rod", "slider"))
    q[i_crank:i_crank + 3] = [a[0] / 2, a[1] / 2, theta]
    qd[i_crank:i_crank + 3] = [v_a[0] / 2, v_a[1] / 2, omega]
    beam = model.beams.get("rod")
    if beam is None:
        q[i_rod:i_rod + 3] = [*(a + rod / 2 * axis), beta]
        qd[i_rod:i_rod + 3] = [*(v_a + rod / 2 * beta_dot * normal), beta_dot]
    else:
        k = beam.n_coordinates
        q_rod = beam.reference_coordinates(a[0], a[1], beta)
        nodes = q_rod.reshape(-1, 4)
        qd_nodes = np.zeros_like(nodes)
        arc = nodes[:, 0:2] - a
        qd_nodes[:, 0:2] = v_a + beta_dot * np.stack([-arc[:, 1], arc[:, 0]], axis=1)
        qd_nodes[:, 2:4] = beta_dot * np.stack([-nodes[:, 3], nodes[:, 2]], axis=1)
        q[i_rod:i_rod + k] = q_rod
        qd[i_rod:i_rod + k] = qd_nodes.ravel()
    q[i_slider] = x_b
    qd[i_slider] = float(v_b)
    return MechanismState(0.0, q, qd)


def simulate_slider_crank(config: Config | None = None, rod: str | None = None,
                          joint: str | None = None, cycles: int | None = None,
                          settling_cycles: int | None = None, step_s: float | None = None,
                          adaptive: bool | None = None, progress: bool = False,
                          mechanism: dict | None = None, clearance_profile=None):
    """Simulate settling + recorded cycles; return (JointHistory of the recorded ones, RunSummary).

    ``config``: the sections of ``SECTIONS`` (default: the embedded defaults); the keyword
    arguments override single values (``mechanism``: any [mechanism] keys; ``clearance_profile``: a
    :class:`ClearanceProfile`). A convenience over :func:`simulate` for commands and studies."""
    if config is None:
        config = load_config(None, SECTIONS)
    inputs = dynamics_inputs_from_config(config)
    overrides = dict(mechanism or {})
    for key, value in (("rod", rod), ("joint", joint), ("recorded_cycles", cycles),
                       ("settling_cycles", settling_cycles)):
        if value is not None:
            overrides[key] = value
    settings = inputs.integrator
    if step_s is not None:
        settings = replace(settings, step_s=step_s, min_step_s=min(settings.min_step_s, step_s))
    if adaptive is not None:
        settings = replace(settings, adaptive=adaptive)
    joint_model = inputs.joint
    if clearance_profile is not None:
        joint_model = replace(joint_model, profile=clearance_profile)
    inputs = DynamicsInputs(replace(inputs.crank, **overrides), joint_model, settings)
    history, summary, _ = simulate(inputs, progress=progress)
    return history, summary


def compile_dynamics() -> None:
    """Compile, or load from numba's cache, every kernel a dynamics run calls (the same for any
    mechanism: the arrays only change size) by a few steps of the default clearance mechanism,
    and the worn clearance's :func:`fewear.mbd.contact.pin_reach_m`;
    worker processes started afterwards load the cached code instead of each compiling it
    (:mod:`fewear.jit`)."""
    inputs = dynamics_inputs_from_config(load_config(None, SECTIONS))
    crank = replace(inputs.crank, joint="clearance", settling_cycles=0)
    settings = inputs.integrator
    model = MechanismModel(describe(crank), {CLEARANCE_JOINT: inputs.joint})
    integrator = GeneralizedAlpha(model.system, settings)
    state = integrator.initial_state(*model.initial_conditions())
    _, trajectory = integrator.run_recorded(state, state.t + 3 * settings.step_s)
    model.history(trajectory)
    angles = np.linspace(0.0, 2.0 * math.pi, 8, endpoint=False)  # a wear run's worn clearance
    pin_reach_m(angles, angles, np.full(8, 0.01), 0.0095)


def simulate(inputs: DynamicsInputs, start: MechanismState | None = None,
             progress: bool = False) -> tuple[JointHistory, RunSummary, MechanismState]:
    """:func:`fewear.mbd.mechanism.simulate` of the slider-crank: the history of its rod-slider
    joint, the run's counts and timings, and the final state (``start``: a warm start)."""
    histories, summary, state = simulate_mechanism(mechanism_inputs(inputs), start,
                                                   progress=progress)
    return histories[CLEARANCE_JOINT], summary, state
