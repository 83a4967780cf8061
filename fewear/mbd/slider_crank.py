"""The paper's slider-crank (seed section 5) built from the config, and its simulation.

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
:class:`fewear.mbd.ancf.AncfBeam` of ``rod_elements`` elements (pin at its last node).
Rod-slider joint: ideal revolute, or :class:`fewear.mbd.clearance.ClearanceJoint` with the
bushing/pin radii and materials of [bushing]/[pin] and the friction coefficient of [joint].
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, replace

import numpy as np

from fewear.errors import FewearInputError
from fewear.io.config import Config, load_config
from fewear.mbd.clearance import ClearanceJoint, measure_rows
from fewear.mbd.constraints import DrivenAngle, PrismaticX, Revolute
from fewear.mbd.contact import ClearanceProfile, ContactLaw, Friction, lankarani_nikravesh_stiffness
from fewear.mbd.history import JointHistory, classify_modes
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings, State, Trajectory
from fewear.mbd.points import GroundPoint, NodePoint, RigidPoint, point_motion
from fewear.mbd.system import MultibodySystem

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
class JointModel:
    """The clearance joint's data ([bushing], [pin], [joint], [clearance_joint])."""

    pin_radius_m: float
    bushing_radius_m: float
    profile: ClearanceProfile
    law: ContactLaw
    friction: Friction
    impact_max_duration_s: float = 1.0e-3

    @property
    def nominal_clearance_m(self) -> float:
        return self.bushing_radius_m - self.pin_radius_m


@dataclass(frozen=True)
class DynamicsInputs:
    """Everything the dynamics stage needs, parsed once from the config: the mechanism
    ([mechanism]), the clearance joint ([bushing], [pin], [joint], [clearance_joint]) and the
    integrator settings ([integrator])."""

    crank: SliderCrank
    joint: JointModel
    integrator: IntegratorSettings


@dataclass(frozen=True)
class MechanismState:
    """Positions ``q`` and velocities ``qd`` (generalized coordinates) at time ``time_s``: where a
    later simulation of the same mechanism can start (a warm start)."""

    time_s: float
    q: np.ndarray
    qd: np.ndarray


def dynamics_inputs_from_config(config: Config) -> DynamicsInputs:
    """The :class:`DynamicsInputs` of the config sections of ``SECTIONS``."""
    return DynamicsInputs(SliderCrank(**config["mechanism"]), joint_model_from_config(config),
                          IntegratorSettings(**config["integrator"]))


def joint_model_from_config(config: Config) -> JointModel:
    bushing, pin, cj = config["bushing"], config["pin"], config["clearance_joint"]
    for name, section in (("bushing", bushing), ("pin", pin)):
        for key in ("youngs_modulus_Pa",):
            if not section[key] > 0.0:
                raise FewearInputError(f"[{name}] {key} = {section[key]!r}: expected > 0")
    clearance = bushing["inner_radius_m"] - pin["radius_m"]
    if not (pin["radius_m"] > 0.0 and clearance > 0.0):
        raise FewearInputError(
            f"radial clearance = [bushing] inner_radius_m - [pin] radius_m = {clearance!r} m "
            f"(pin radius {pin['radius_m']!r} m): expected a pin radius > 0 and a clearance > 0")
    angles = [math.radians(a) for a in _numbers(cj, "clearance_angles_deg")]
    values = _numbers(cj, "clearance_values_m")
    if len(angles) != len(values):
        raise FewearInputError(
            "[clearance_joint] clearance_angles_deg and clearance_values_m must have the same "
            f"length (got {len(angles)} and {len(values)})")
    profile = (ClearanceProfile(np.array(angles), np.array(values)) if angles
               else ClearanceProfile.constant(clearance))
    stiffness = lankarani_nikravesh_stiffness(
        pin["radius_m"], bushing["inner_radius_m"], pin["youngs_modulus_Pa"],
        pin["poisson_ratio"], bushing["youngs_modulus_Pa"], bushing["poisson_ratio"])
    law = ContactLaw(
        law=cj["contact_law"], stiffness_N_m1_5=stiffness,
        restitution=cj["restitution_coefficient"],
        min_impact_velocity_m_s=cj["min_impact_velocity_m_s"],
        penetration_m=np.array(_numbers(cj, "tabulated_penetration_m")),
        force_N=np.array(_numbers(cj, "tabulated_force_N")))
    friction = Friction(config["joint"]["friction_coefficient"], cj["friction_v0_m_s"],
                        cj["friction_v1_m_s"])
    duration = config["dynamics_output"]["impact_max_duration_s"]
    if not duration > 0.0:
        raise FewearInputError(
            f"[dynamics_output] impact_max_duration_s = {duration!r}: expected > 0")
    return JointModel(pin["radius_m"], bushing["inner_radius_m"], profile, law, friction,
                      duration)


def _numbers(section: dict, key: str) -> list[float]:
    values = section[key]
    if not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        raise FewearInputError(f"[clearance_joint] {key} = {values!r}: expected a list of numbers")
    return [float(v) for v in values]


class SliderCrankModel:
    """The assembled system with the indices needed to set it up and read it out."""

    def __init__(self, crank: SliderCrank, joint: JointModel):
        self.crank, self.joint = crank, joint
        system = MultibodySystem((0.0, -crank.gravity_m_s2))
        r, rod = crank.crank_length_m, crank.rod_length_m
        self.i_crank = system.add_rigid_body(crank.crank_mass_kg, crank.crank_inertia_kg_m2,
                                             "crank")
        if crank.rod == "rigid":
            m_rod = crank.rod_mass_kg
            self.i_rod = system.add_rigid_body(m_rod, m_rod * rod * rod / 12.0, "rod")
            rod_a = RigidPoint(self.i_rod, (-rod / 2.0, 0.0))
            rod_b = RigidPoint(self.i_rod, (rod / 2.0, 0.0))
            self.beam = None
        else:
            from fewear.mbd.ancf import AncfBeam, BeamSection

            section = BeamSection(crank.rod_youngs_modulus_Pa, crank.rod_poisson_ratio,
                                  crank.rod_density_kg_m3, crank.rod_height_m, crank.rod_width_m)
            self.beam = AncfBeam(rod, crank.rod_elements, section)
            self.i_rod = system.add_beam(self.beam, crank.rod_damping_s)
            rod_a = NodePoint(self.i_rod + self.beam.node_index(0).start)
            rod_b = NodePoint(self.i_rod + self.beam.node_index(self.beam.n_nodes - 1).start)
        self.i_slider = system.add_rigid_body(crank.slider_mass_kg,
                                              crank.slider_mass_kg * 1e-4, "slider")
        system.add_constraint(Revolute(RigidPoint(self.i_crank, (-r / 2.0, 0.0)),
                                       GroundPoint(0.0, 0.0)))
        system.add_constraint(Revolute(RigidPoint(self.i_crank, (r / 2.0, 0.0)), rod_a))
        system.add_constraint(DrivenAngle(self.i_crank, math.radians(crank.initial_crank_angle_deg),
                                          crank.omega_rad_s))
        system.add_constraint(PrismaticX(self.i_slider, 0.0))
        bushing = RigidPoint(self.i_slider)
        if crank.joint == "ideal":
            system.add_constraint(Revolute(rod_b, bushing))
            self.clearance = None
        else:
            self.clearance = ClearanceJoint(rod_b, bushing, joint.pin_radius_m,
                                            joint.bushing_radius_m, joint.profile, joint.law,
                                            joint.friction)
            system.add_force(self.clearance)
        self.rod_b = rod_b
        self.system = system.finalize()
        self._joint_rows = system._rows[-1] if crank.joint == "ideal" else None

    def initial_conditions(self):
        """Positions and velocities of the ideal rigid mechanism at t = 0 (pin centred)."""
        c = self.crank
        r, rod, omega = c.crank_length_m, c.rod_length_m, c.omega_rad_s
        theta = math.radians(c.initial_crank_angle_deg)
        _, x_b, v_b = c.closed_form(0.0)
        beta = math.asin(-r * math.sin(theta) / rod)
        beta_dot = -r * omega * math.cos(theta) / (rod * math.cos(beta))
        a = r * np.array([math.cos(theta), math.sin(theta)])
        v_a = r * omega * np.array([-math.sin(theta), math.cos(theta)])
        axis = np.array([math.cos(beta), math.sin(beta)])
        normal = np.array([-math.sin(beta), math.cos(beta)])
        n = self.system.n_coordinates
        q, qd = np.zeros(n), np.zeros(n)
        q[self.i_crank:self.i_crank + 3] = [a[0] / 2, a[1] / 2, theta]
        qd[self.i_crank:self.i_crank + 3] = [v_a[0] / 2, v_a[1] / 2, omega]
        if self.beam is None:
            q[self.i_rod:self.i_rod + 3] = [*(a + rod / 2 * axis), beta]
            qd[self.i_rod:self.i_rod + 3] = [*(v_a + rod / 2 * beta_dot * normal), beta_dot]
        else:
            k = self.beam.n_coordinates
            q_rod = self.beam.reference_coordinates(a[0], a[1], beta)
            nodes = q_rod.reshape(-1, 4)
            qd_nodes = np.zeros_like(nodes)
            arc = nodes[:, 0:2] - a
            qd_nodes[:, 0:2] = v_a + beta_dot * np.stack([-arc[:, 1], arc[:, 0]], axis=1)
            qd_nodes[:, 2:4] = beta_dot * np.stack([-nodes[:, 3], nodes[:, 2]], axis=1)
            q[self.i_rod:self.i_rod + k] = q_rod
            qd[self.i_rod:self.i_rod + k] = qd_nodes.ravel()
        q[self.i_slider] = x_b
        qd[self.i_slider] = float(v_b)
        return q, qd

    def measure(self, trajectory: Trajectory) -> dict:
        """The joint quantities at each row of a trajectory (arrays, see JointHistory)."""
        if self.clearance is not None:
            columns = measure_rows(self.system.data.joints, 0, trajectory.q, trajectory.qd,
                                   trajectory.joint_memory)
            return {"eccentricity_m": columns[:, 0:2], "penetration_m": columns[:, 2],
                    "normal_force_N": columns[:, 3], "friction_force_N": columns[:, 4],
                    "reaction_force_N": columns[:, 5:7], "rel_omega_rad_s": columns[:, 7]}
        force = -trajectory.lam[:, self._joint_rows]  # the constraint force on the pin
        point, idx = self.rod_b, self.rod_b.indices
        omega_pin = [point_motion(point.kind, point.offset, q[idx], qd[idx])[5]
                     for q, qd in zip(trajectory.q, trajectory.qd)]
        return {
            "eccentricity_m": np.zeros((force.shape[0], 2)),
            "penetration_m": np.zeros(force.shape[0]),
            "normal_force_N": np.hypot(force[:, 0], force[:, 1]),
            "friction_force_N": np.zeros(force.shape[0]),
            "reaction_force_N": force,
            "rel_omega_rad_s": np.array(omega_pin),
        }


@dataclass(frozen=True)
class RunSummary:
    """Counts and timings of a simulation."""

    steps: int
    rejected_steps: int
    newton_iterations: int
    wall_time_s: float
    wall_time_per_cycle_s: float
    smallest_step_s: float
    cycles: int


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
    """Compile, or load from numba's cache, every kernel a dynamics run calls (the same for both
    rods and joints: the arrays only change size) by a few steps of the default clearance
    mechanism; worker processes started afterwards load the cached code instead of each compiling
    it (:mod:`fewear.jit`)."""
    inputs = dynamics_inputs_from_config(load_config(None, SECTIONS))
    model = SliderCrankModel(replace(inputs.crank, joint="clearance"), inputs.joint)
    integrator = GeneralizedAlpha(model.system, inputs.integrator)
    state = integrator.initial_state(*model.initial_conditions())
    _, trajectory = integrator.run_recorded(state, state.t + 3 * inputs.integrator.step_s)
    model.measure(_joined([trajectory]))


def simulate(inputs: DynamicsInputs, start: MechanismState | None = None,
             progress: bool = False) -> tuple[JointHistory, RunSummary, MechanismState]:
    """Simulate ``inputs.crank.settling_cycles`` + ``recorded_cycles`` crank cycles.

    ``start``: begin from this state (e.g. the end of the previous wear block, on the same
    mechanism with another clearance profile) instead of the ideal mechanism at t = 0; the time
    continues from ``start.time_s`` so the driven crank angle stays consistent. Returns the
    history of the recorded cycles, the run's counts and timings, and the final state.
    """
    crank, joint_model, settings = inputs.crank, inputs.joint, inputs.integrator
    model = SliderCrankModel(crank, joint_model)
    integrator = GeneralizedAlpha(model.system, settings)
    if start is None:
        state = integrator.initial_state(*model.initial_conditions())
    else:
        state = integrator.initial_state(start.q, start.qd, start.time_s)
    t0, period = state.t, crank.period_s
    recorded: list[Trajectory] = []
    total = crank.settling_cycles + crank.recorded_cycles
    clock = time.perf_counter()
    for cycle in range(total):
        recording = cycle >= crank.settling_cycles
        t_end = t0 + (cycle + 1) * period
        if recording and not recorded:
            recorded.append(_single_row(state, model.system))
        if recording:
            state, trajectory = integrator.run_recorded(state, t_end)
            recorded.append(trajectory)
        else:
            state = integrator.run(state, t_end)
        if progress:
            print(f"fewear dynamics: cycle {cycle + 1}/{total} "
                  f"({'recorded' if recording else 'settling'}), t = {state.t:.4f} s, "
                  f"{integrator.stats.steps} steps, {time.perf_counter() - clock:.1f} s",
                  file=sys.stderr, flush=True)
    wall = time.perf_counter() - clock
    history = _history(model, _joined(recorded), joint_model.impact_max_duration_s,
                       crank.joint == "ideal")
    stats = integrator.stats
    summary = RunSummary(stats.steps, stats.rejected, stats.newton_iterations, wall, wall / total,
                         stats.smallest_step_s, total)
    return history, summary, MechanismState(state.t, state.q.copy(), state.qd.copy())


def _joined(parts: list[Trajectory]) -> Trajectory:
    """The trajectories one after the other (contiguous arrays, as the kernels are compiled
    for)."""
    return Trajectory(*(np.concatenate([getattr(part, name) for part in parts])
                        for name in Trajectory.__dataclass_fields__))


def _single_row(state: State, system) -> Trajectory:
    """The trajectory of one row: ``state`` with the joints' memory now."""
    return Trajectory(np.array([state.t]), np.zeros(1), state.q[None], state.qd[None],
                      state.qdd[None], state.a[None], state.lam[None],
                      system.data.joints.memory[None].copy())


def _history(model: SliderCrankModel, trajectory: Trajectory, impact_max_duration_s: float,
             ideal: bool) -> JointHistory:
    measures = model.measure(trajectory)
    time_s = trajectory.time_s
    if ideal:
        mode = np.full(time_s.size, 2, dtype=int)
    else:
        mode = classify_modes(time_s, measures["normal_force_N"], impact_max_duration_s)
    return JointHistory(
        time_s=time_s,
        crank_angle_rad=trajectory.q[:, model.i_crank + 2],
        slider_x_m=trajectory.q[:, model.i_slider],
        slider_velocity_m_s=trajectory.qd[:, model.i_slider],
        mode=mode,
        **measures,
    )
