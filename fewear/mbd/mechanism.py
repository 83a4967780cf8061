"""Any planar mechanism of a description (:mod:`fewear.mbd.description`): its multibody system,
initial assembly and simulation, with one joint-load history per clearance joint.

Build (:class:`MechanismModel`): rigid bodies (x, y, phi) and ANCF beams, in file order;
constraints in the joints' file order, each driver's row after those of its body's last joint
(an order of rows only; any would do); the clearance joints are force
elements (:class:`fewear.mbd.clearance.ClearanceJoint`, the pin and the bushing as the joint
names them), or ideal revolute joints when the run asks for ideal joints.

Initial state (:func:`assemble`): every body taken as rigid at its pose (x, y, angle) and every
clearance joint as ideal (pin centred), Newton on Phi(q, t0) = 0 from the file's approximate poses
(minimum-norm steps, so an under-constrained mechanism stays near its poses), then velocities
from Phi_q q' = -Phi_t (minimum norm: an undriven mechanism starts at rest). A beam starts
straight and unstressed, moving rigidly with its pose. Before the first run the assembly is
followed over one driver period (:func:`check_cycle`): a crank that cannot turn a full cycle (a
four-bar against Grashof's condition) is found at the first crank angle where a joint opens.
"""

from __future__ import annotations

import math
import sys
import time
from dataclasses import dataclass, replace

import numpy as np

from fewear.errors import FewearInputError
from fewear.mbd.clearance import ClearanceJoint, measure_rows
from fewear.mbd.constraints import (
    ConstraintSet,
    DrivenAngle,
    FixedAngle,
    PrescribedAngle,
    Prismatic,
    Revolute,
)
from fewear.mbd.contact import ClearanceProfile, ContactLaw, Friction, lankarani_nikravesh_stiffness
from fewear.mbd.description import GROUND, Mechanism, PointRef, beam_node
from fewear.mbd.history import JointHistory, classify_modes
from fewear.mbd.integrator import GeneralizedAlpha, IntegratorSettings, State, Trajectory
from fewear.mbd.points import GroundPoint, NodePoint, RigidPoint, point_motion
from fewear.mbd.system import MultibodySystem

ASSEMBLY_TOLERANCE = 1e-12
"""Largest constraint residual (m, rad) of an assembled position."""
CYCLE_SAMPLES = 120
"""Driver positions over a period at which :func:`check_cycle` assembles the mechanism."""


@dataclass(frozen=True)
class JointModel:
    """A clearance joint's data ([bushing], [pin], [joint], [clearance_joint] of its config view,
    :func:`fewear.io.mechanism.joint_sections`)."""

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
class MechanismState:
    """Positions ``q`` and velocities ``qd`` (generalized coordinates) at time ``time_s``: where a
    later simulation of the same mechanism can start (a warm start)."""

    time_s: float
    q: np.ndarray
    qd: np.ndarray


@dataclass(frozen=True)
class MechanismInputs:
    """Everything the dynamics of one case needs, parsed once from the config: the mechanism
    (the case's variant), each clearance joint's data by name, the integrator settings and the
    cycles to settle and record; ``ideal_joints``: the clearance joints made ideal."""

    mechanism: Mechanism
    joints: dict[str, JointModel]
    integrator: IntegratorSettings
    settling_cycles: int = 2
    recorded_cycles: int = 1
    ideal_joints: bool = False
    initial_state: MechanismState | None = None  # exact, when known in closed form; else None

    def __post_init__(self):
        missing = [joint.name for joint in self.mechanism.clearance_joints
                   if joint.name not in self.joints]
        if missing:
            raise FewearInputError(f"clearance joint(s) {', '.join(missing)} without joint data")

    @property
    def period_s(self) -> float:
        return self.mechanism.period_s


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


def joint_model_from_config(config: dict) -> JointModel:
    """A clearance joint's :class:`JointModel` from [bushing], [pin], [joint], [clearance_joint]
    and [dynamics_output] impact_max_duration_s."""
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


# -- the model -------------------------------------------------------------------------------------
def _constraints(mechanism: Mechanism, point, first: dict, clearance: bool):
    """The constraints of the joints (file order) and drivers, each with its owner's name for
    messages, and the clearance joints as (joint, pin point, bushing point) if ``clearance``
    (else they are ideal revolute joints among the constraints). ``point(ref)``: a point object,
    ``first[body]``: the body's first coordinate."""
    constraints, forces = [], []
    for joint in mechanism.joints:
        if joint.type == "revolute" and joint.clearance and clearance:
            forces.append((joint, point(joint.first), point(joint.second)))
        else:
            constraints += [(row, f"joint {joint.name!r}")
                            for row in _joint_rows(mechanism, joint, point, first)]
    for driver in mechanism.drivers:
        if driver.tabulated:
            row = PrescribedAngle(first[driver.body], driver.table_time_s,
                                  driver.table_angle_rad)
        else:
            row = DrivenAngle(first[driver.body], driver.initial_angle_rad, driver.speed_rad_s)
        holding = [f"joint {joint.name!r}" for joint in mechanism.joints
                   if driver.body in (joint.first.body, joint.second.body)]
        rows = [k for k, (_, owner) in enumerate(constraints) if owner in holding]
        constraints.insert(rows[-1] + 1 if rows else len(constraints),
                           (row, f"driver of {driver.body!r}"))
    return constraints, forces


def _joint_rows(mechanism: Mechanism, joint, point, first: dict) -> list:
    """The constraints of an ideal joint: revolute; prismatic (the body's angle held at its
    pose's); fixed = revolute + the relative angle of the poses held."""
    if joint.type == "revolute":
        return [Revolute(point(joint.first), point(joint.second))]
    if joint.type == "prismatic":
        body = mechanism.body(joint.second.body)
        return [Prismatic(first[body.name], mechanism_point(mechanism, joint.first),
                          joint.direction, body.point(joint.second.point), body.angle_rad)]
    base, moving = ((joint.second, joint.first) if joint.second.body == GROUND
                    else (joint.first, joint.second))
    body = mechanism.body(moving.body)
    if base.body == GROUND:
        held = FixedAngle(first[body.name], body.angle_rad)
    else:
        other = mechanism.body(base.body)
        held = FixedAngle(first[body.name], body.angle_rad - other.angle_rad, first[other.name])
    return [Revolute(point(joint.first), point(joint.second)), held]


def mechanism_point(mechanism: Mechanism, ref: PointRef) -> tuple[float, float]:
    """A point's coordinates in its body's frame (the ground's: global)."""
    if ref.body == GROUND:
        return dict(mechanism.ground_points)[ref.point]
    return mechanism.body(ref.body).point(ref.point)


class MechanismModel:
    """The multibody system of a mechanism, with the indices to set it up and read it out."""

    def __init__(self, mechanism: Mechanism, joints: dict[str, JointModel],
                 ideal_joints: bool = False):
        from fewear.mbd.ancf import AncfBeam, BeamSection

        self.mechanism, self.joints = mechanism, joints
        system = MultibodySystem((0.0, -mechanism.gravity_m_s2))
        self.first, self.beams = {}, {}
        for body in mechanism.bodies:
            if body.model == "rigid":
                self.first[body.name] = system.add_rigid_body(body.mass_kg, body.inertia_kg_m2,
                                                              body.name)
            else:
                bar = body.bar
                section = BeamSection(bar.youngs_modulus_Pa, bar.poisson_ratio,
                                      bar.density_kg_m3, bar.height_m, bar.width_m)
                self.beams[body.name] = AncfBeam(bar.length_m, bar.elements, section)
                self.first[body.name] = system.add_beam(self.beams[body.name], bar.damping_s)

        def point(ref: PointRef):
            x, y = mechanism_point(mechanism, ref)
            if ref.body == GROUND:
                return GroundPoint(x, y)
            if ref.body in self.beams:
                node = beam_node(mechanism.body(ref.body), ref.point)
                return NodePoint(self.first[ref.body]
                                 + self.beams[ref.body].node_index(node).start)
            return RigidPoint(self.first[ref.body], (x, y))

        constraints, forces = _constraints(mechanism, point, self.first, not ideal_joints)
        for constraint, _ in constraints:
            system.add_constraint(constraint)
        self.clearance = {}  # name -> (index in the system's JointData, pin, bushing)
        for joint, pin, bushing in forces:
            model = joints[joint.name]
            system.add_force(ClearanceJoint(pin, bushing, model.pin_radius_m,
                                            model.bushing_radius_m, model.profile, model.law,
                                            model.friction))
            self.clearance[joint.name] = (len(self.clearance), pin, bushing)
        self.system = system.finalize()
        self.ideal = {}  # name -> (constraint rows, pin, bushing) of clearance joints made ideal
        owners = [owner for _, owner in constraints]
        for joint in mechanism.clearance_joints:
            if joint.name not in self.clearance:
                k = owners.index(f"joint {joint.name!r}")
                constraint = constraints[k][0]
                self.ideal[joint.name] = (system.constraint_set.rows[k], constraint.a,
                                          constraint.b)

    def initial_conditions(self, t0: float = 0.0):
        """(q, q') of the assembled mechanism at ``t0`` (module docstring)."""
        pose_q, pose_qd = assemble(self.mechanism, t0)
        return self.coordinates(pose_q, pose_qd)

    def coordinates(self, pose_q, pose_qd):
        """(q, q') of the system from every body's rigid pose (x, y, phi) and its rate."""
        n = self.system.n_coordinates
        q, qd = np.zeros(n), np.zeros(n)
        for k, body in enumerate(self.mechanism.bodies):
            pose, rate = pose_q[3 * k:3 * k + 3], pose_qd[3 * k:3 * k + 3]
            first = self.first[body.name]
            if body.name not in self.beams:
                q[first:first + 3], qd[first:first + 3] = pose, rate
                continue
            beam = self.beams[body.name]
            axis = np.array([math.cos(pose[2]), math.sin(pose[2])])
            start = pose[:2] - beam.length_m / 2.0 * axis
            nodes = beam.reference_coordinates(start[0], start[1], pose[2]).reshape(-1, 4)
            arm = nodes[:, 0:2] - pose[:2]
            velocity = np.zeros_like(nodes)
            velocity[:, 0:2] = rate[:2] + rate[2] * np.stack([-arm[:, 1], arm[:, 0]], axis=1)
            velocity[:, 2:4] = rate[2] * np.stack([-nodes[:, 3], nodes[:, 2]], axis=1)
            q[first:first + beam.n_coordinates] = nodes.ravel()
            qd[first:first + beam.n_coordinates] = velocity.ravel()
        return q, qd

    def measure(self, trajectory: Trajectory) -> dict[str, dict]:
        """Each clearance joint's quantities at each row of a trajectory, in its bushing body's
        frame (arrays, see JointHistory)."""
        measures = {}
        for joint in self.mechanism.clearance_joints:
            if joint.name in self.clearance:
                j = self.clearance[joint.name][0]
                columns = measure_rows(self.system.data.joints, j, trajectory.q, trajectory.qd,
                                       trajectory.joint_memory)
                measures[joint.name] = {
                    "eccentricity_m": columns[:, 0:2], "penetration_m": columns[:, 2],
                    "normal_force_N": columns[:, 3], "friction_force_N": columns[:, 4],
                    "reaction_force_N": columns[:, 5:7], "rel_omega_rad_s": columns[:, 7]}
            else:
                measures[joint.name] = self._ideal_measures(joint.name, trajectory)
        return measures

    def _ideal_measures(self, name: str, trajectory: Trajectory) -> dict:
        """An ideal joint's reaction on the pin (-lambda of its rows) in the bushing frame."""
        rows, pin, bushing = self.ideal[name]
        force = -trajectory.lam[:, rows]
        pin_motion = np.array([point_motion(pin.kind, pin.offset, q[pin.indices],
                                            qd[pin.indices])
                               for q, qd in zip(trajectory.q, trajectory.qd)])
        bushing_motion = np.array([point_motion(bushing.kind, bushing.offset,
                                                q[bushing.indices], qd[bushing.indices])
                                   for q, qd in zip(trajectory.q, trajectory.qd)])
        c, s = np.cos(bushing_motion[:, 4]), np.sin(bushing_motion[:, 4])
        local = np.column_stack([c * force[:, 0] + s * force[:, 1],
                                 -s * force[:, 0] + c * force[:, 1]])
        size = force.shape[0]
        return {"eccentricity_m": np.zeros((size, 2)), "penetration_m": np.zeros(size),
                "normal_force_N": np.hypot(force[:, 0], force[:, 1]),
                "friction_force_N": np.zeros(size), "reaction_force_N": local,
                "rel_omega_rad_s": pin_motion[:, 5] - bushing_motion[:, 5]}

    def history(self, trajectory: Trajectory) -> dict[str, JointHistory]:
        """The :class:`JointHistory` of each clearance joint (file order): the angle of the first
        driver's body as crank angle, the bushing body's x and x' as the slider's."""
        crank = self.first[self.mechanism.drivers[0].body] + 2
        histories = {}
        for name, measures in self.measure(trajectory).items():
            joint = next(j for j in self.mechanism.joints if j.name == name)
            if name in self.clearance:
                duration = self.joints[name].impact_max_duration_s
                mode = classify_modes(trajectory.time_s, measures["normal_force_N"], duration)
            else:
                mode = np.full(trajectory.time_s.size, 2, dtype=int)
            body = joint.bushing.body
            x, v = ((trajectory.q[:, self.first[body]], trajectory.qd[:, self.first[body]])
                    if body != GROUND else (np.zeros(mode.size), np.zeros(mode.size)))
            histories[name] = JointHistory(
                time_s=trajectory.time_s, crank_angle_rad=trajectory.q[:, crank],
                slider_x_m=x, slider_velocity_m_s=v, mode=mode, **measures)
        return histories


# -- assembly ------------------------------------------------------------------------------------
def _skeleton(mechanism: Mechanism):
    """Every body rigid at its pose coordinates (3 per body), the clearance joints ideal: the
    :class:`ConstraintSet` of the assembly, each row's owner and the poses."""
    first = {body.name: 3 * k for k, body in enumerate(mechanism.bodies)}

    def point(ref: PointRef):
        x, y = mechanism_point(mechanism, ref)
        return GroundPoint(x, y) if ref.body == GROUND else RigidPoint(first[ref.body], (x, y))

    constraints, _ = _constraints(mechanism, point, first, clearance=False)
    owners = [owner for constraint, owner in constraints for _ in range(constraint.n_rows)]
    poses = np.array([[*body.position_m, body.angle_rad] for body in mechanism.bodies],
                     dtype=float).ravel()
    return ConstraintSet([c for c, _ in constraints], poses.size), owners, poses


def _newton(constraints: ConstraintSet, q, t: float, iterations: int = 50):
    """Newton with minimum-norm steps on Phi(q, t) = 0 from q; (q, converged, residual)."""
    q = q.copy()
    for _ in range(iterations):
        phi = constraints.values(q, t)
        if not np.all(np.isfinite(phi)):
            break
        if np.max(np.abs(phi), initial=0.0) <= ASSEMBLY_TOLERANCE:
            return q, True, phi
        q = q + np.linalg.lstsq(constraints.jacobian(q), -phi, rcond=None)[0]
    return q, False, constraints.values(q, t)


def assemble(mechanism: Mechanism, t0: float = 0.0):
    """(pose q, pose q') of every body (x, y, phi each) assembled at ``t0`` (module docstring);
    a :class:`FewearInputError` naming the joint (or driver) of the largest residual if the
    joints cannot close."""
    constraints, owners, poses = _skeleton(mechanism)
    q, converged, phi = _newton(constraints, poses, t0)
    if not converged:
        row = int(np.nanargmax(np.abs(np.nan_to_num(phi, nan=np.inf))))
        raise FewearInputError(
            f"mechanism {mechanism.name!r}: the bodies cannot be assembled at t = {t0:g} s: "
            f"{owners[row]} stays open by {abs(phi[row]):.3g} (m or rad); check the bodies' "
            "points, lengths and approximate poses")
    jacobian = constraints.jacobian(q)
    qd = np.linalg.lstsq(jacobian, -constraints.time_derivative(t0), rcond=None)[0]
    return q, qd


def check_cycle(mechanism: Mechanism, t0: float = 0.0) -> None:
    """Follow the assembly over one period of the first driver from ``t0``
    (:data:`CYCLE_SAMPLES` positions, each Newton from the last): a joint that cannot close on
    the way (a crank that cannot turn a full cycle: a four-bar violating Grashof's condition)
    is a :class:`FewearInputError` naming it and the driven angle there."""
    constraints, owners, poses = _skeleton(mechanism)
    q, converged, _ = _newton(constraints, poses, t0)
    if not converged:
        assemble(mechanism, t0)  # raises with the joint that cannot close
    driver = mechanism.drivers[0]
    for t in t0 + mechanism.period_s * np.arange(1, CYCLE_SAMPLES + 1) / CYCLE_SAMPLES:
        q, converged, phi = _newton(constraints, q, t)
        if not converged:
            row = int(np.nanargmax(np.abs(np.nan_to_num(phi, nan=np.inf))))
            angle = constraints.values(np.zeros_like(q), t)[owners.index(
                f"driver of {driver.body!r}")]
            raise FewearInputError(
                f"mechanism {mechanism.name!r}: the driver of {driver.body!r} cannot turn a full "
                f"cycle: at its angle {math.degrees(-angle) % 360.0:.1f} deg (t = {t:.4g} s) "
                f"{owners[row]} cannot close (open by {abs(phi[row]):.3g} m or rad): the links "
                "cannot reach (a four-bar violating Grashof's condition for a crank)")


# -- simulation ----------------------------------------------------------------------------------
def simulate(inputs: MechanismInputs, start: MechanismState | None = None,
             profiles: dict[str, ClearanceProfile] | None = None, progress: bool = False
             ) -> tuple[dict[str, JointHistory], RunSummary, MechanismState]:
    """Simulate ``inputs.settling_cycles`` + ``recorded_cycles`` driver periods.

    ``start``: begin from this state (e.g. the end of the previous wear block, on the same
    mechanism with other clearance profiles) instead of ``inputs.initial_state`` or else the
    assembled mechanism at t = 0 (whose full cycle is checked first, :func:`check_cycle`); the
    time continues from ``start.time_s``
    so the driven angles stay consistent. ``profiles``: a worn clearance c(theta) per joint name
    (theta in the bushing body's frame). Returns each clearance joint's history of the recorded
    cycles (file order), the run's counts and timings, and the final state."""
    joints = dict(inputs.joints)
    for name, profile in (profiles or {}).items():
        if name not in joints:
            raise FewearInputError(f"clearance profile for {name!r}: the mechanism's clearance "
                                   f"joints are {', '.join(joints)}")
        joints[name] = replace(joints[name], profile=profile)
    model = MechanismModel(inputs.mechanism, joints, inputs.ideal_joints)
    integrator = GeneralizedAlpha(model.system, inputs.integrator)
    if start is None:
        check_cycle(inputs.mechanism)
        start = inputs.initial_state
    if start is None:
        state = integrator.initial_state(*model.initial_conditions())
    else:
        state = integrator.initial_state(start.q, start.qd, start.time_s)
    t0, period = state.t, inputs.period_s
    recorded: list[Trajectory] = []
    total = inputs.settling_cycles + inputs.recorded_cycles
    clock = time.perf_counter()
    for cycle in range(total):
        recording = cycle >= inputs.settling_cycles
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
    histories = model.history(_joined(recorded))
    stats = integrator.stats
    summary = RunSummary(stats.steps, stats.rejected, stats.newton_iterations, wall, wall / total,
                         stats.smallest_step_s, total)
    return histories, summary, MechanismState(state.t, state.q.copy(), state.qd.copy())


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
