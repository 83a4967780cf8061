"""The four-bar crank-rocker of ``freudenstein`` simulated in Exudyn (PyPI), three variants.

Frame, angles and force signs as in ``freudenstein``: global x right, y up, gravity along -y;
theta2..4 from +x counter-clockwise (rad; theta2 is not wrapped, it grows as omega t); joint
forces in the global frame (N), exerted BY the joint's first body ON its second body:
    force_O2: ground on crank, force_A: crank on coupler, force_B: coupler on rocker,
    force_O4: ground on rocker; torque_crank: driving torque of the ground on the crank (N m).

Model: crank and rocker are ObjectRigidBody2D (nodes at the midpoints, inertia m L^2/12), joined to
the ground by RevoluteJoint2D; the crank speed is held by a velocity-level CoordinateConstraint
theta2' = omega (its multiplier is the driving torque). Variants of the coupler and of joint B:
- "rigid": the coupler an ObjectRigidBody2D, all four joints ideal (RevoluteJoint2D).
- "cable": the coupler as ``cable_elements`` ObjectANCFCable2D elements (axial stiffness E A,
  bending stiffness E I, no damping) pinned at its end nodes. Exudyn's ANCF cable is an
  Euler-Bernoulli beam (no shear deformation, no cross-section rotation); fewear's ANCF beam is
  shear-deformable. For the coupler (L/h = 50) shear adds about (h/L)^2 to the bending
  compliance, so the two should agree to that order. The coupler angle is the chord angle A -> B.
- "clearance": rigid links, joint B a clearance joint: pin centre on the coupler at B, bushing
  centre on the rocker at B, an ObjectConnectorSpringDamper between the two centres (zero
  reference length) whose Python force function is the Lankarani-Nikravesh law
      F_n = K delta^1.5 [1 + 3 (1 - c_e^2) delta' / (4 delta'^(-))],  delta = |e| - c > 0,
  e = pin centre - bushing centre, c = bushing radius - pin radius, F_n >= 0 (no adhesion). The
  impact velocity delta'^(-) is the radial velocity at the start of the last step before contact
  (updated in a pre-step function from the accepted state), not less than
  ``min_impact_velocity_m_s``. force_B = F_n e / |e| (the pin pushes the bushing outward) plus,
  if ``friction_coefficient`` > 0, the regularised Coulomb friction on the bushing
  (``_pin_friction``, applied by ``_friction_element``); default frictionless.

Solver: Exudyn's index-3 generalized-alpha at a fixed step, spectral radius ``rho_inf``; initial
positions and velocities of the ideal mechanism from the closed form (``freudenstein``).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from tests.mbd.reference.freudenstein import FourBar, kinematics

DEFAULT_FOUR_BAR = FourBar()


@dataclass(frozen=True)
class ClearanceJoint:
    """Clearance at the coupler-rocker joint (m, Pa): pin (coupler) in a bushing (rocker).
    Materials as the paper's joint: 42CrMo pin, CuZn25Al6Fe3Mn3 bushing."""

    pin_radius_m: float = 9.5e-3
    bushing_radius_m: float = 10.0e-3
    pin_youngs_modulus_Pa: float = 207e9
    pin_poisson_ratio: float = 0.27
    bushing_youngs_modulus_Pa: float = 90e9
    bushing_poisson_ratio: float = 0.32
    restitution: float = 0.9
    min_impact_velocity_m_s: float = 1e-3
    friction_coefficient: float = 0.0  # 0: frictionless
    friction_ramp_velocity_m_s: float = 1e-3  # slip speed of full Coulomb friction

    def clearance_m(self) -> float:
        """Radial clearance c = R_bushing - R_pin."""
        return self.bushing_radius_m - self.pin_radius_m

    def stiffness_N_m15(self) -> float:
        """Lankarani-Nikravesh K = 4 / (3 pi (h_i + h_j)) sqrt(R_i R_j / (R_j - R_i)) with
        h_k = (1 - nu_k^2) / (pi E_k) (N/m^1.5)."""
        h_pin = (1 - self.pin_poisson_ratio**2) / (math.pi * self.pin_youngs_modulus_Pa)
        h_bushing = (1 - self.bushing_poisson_ratio**2) / (math.pi * self.bushing_youngs_modulus_Pa)
        r_i, r_j = self.pin_radius_m, self.bushing_radius_m
        return 4.0 / (3.0 * math.pi * (h_pin + h_bushing)) * math.sqrt(r_i * r_j / (r_j - r_i))


@dataclass(frozen=True)
class CouplerBeam:
    """The elastic coupler's section and material (m, Pa); density from ``FourBar``."""

    youngs_modulus_Pa: float = 211e9
    height_m: float = 0.005  # in the plane of motion
    width_m: float = 0.018


def four_bar_cycle(variant: str = "rigid", cycles_settle: int = 2, step_s: float = 1e-5,
                   cycles_record: int = 1, params: FourBar = DEFAULT_FOUR_BAR, rho_inf: float = 0.9,
                   newton_tolerance: float | None = None, cable_elements: int = 4,
                   beam: CouplerBeam = CouplerBeam(),
                   clearance: ClearanceJoint = ClearanceJoint()) -> dict:
    """Simulate ``cycles_settle + cycles_record`` crank turns from theta2(0) and return the last
    ``cycles_record`` turns (both ends included) as a dict of arrays (module docstring for signs):
    time_s (n,), theta2, theta3, theta4 (rad), force_O2, force_A, force_B, force_O4 (n, 2; N),
    torque_crank (n,; N m). The clearance variant adds eccentricity_m (n, 2) = pin centre -
    bushing centre, penetration_m (n,) = |e| - c and contact_force_N (n,) = F_n, and with friction
    friction_force_N (n, 2), the friction force on the bushing (included in force_B). The
    clearance run starts from the ideal mechanism with the rocker turned so that |e| = c/5.
    ``step_s`` is rounded so that a turn is a whole number of steps. ``newton_tolerance``
    (default 1e-10, relative and absolute; 1e-8 relative only for the cable and the clearance,
    whose stiff axial or contact forces keep Exudyn's absolute residual above 1e-10).
    """
    if variant not in ("rigid", "cable", "clearance"):
        raise ValueError(f"variant {variant!r}: use 'rigid', 'cable' or 'clearance'")
    steps_per_cycle = max(1, round(params.period_s() / step_s))
    step_s = params.period_s() / steps_per_cycle
    total_steps = steps_per_cycle * (cycles_settle + cycles_record)
    if newton_tolerance is None:
        newton_tolerance = 1e-10 if variant == "rigid" else 1e-8
    model = _build(variant, params, cable_elements, beam, clearance)
    _solve(model["mbs"], model["exu"], step_s, total_steps, rho_inf, newton_tolerance,
           relative_only=(variant != "rigid"))
    records = {name: model["mbs"].GetSensorStoredData(sensor)
               for name, sensor in model["sensors"].items()}
    keep = slice(steps_per_cycle * cycles_settle, None)
    result = {"time_s": records["crank"][keep, 0]}
    result.update(_outputs(variant, records, model, params, keep))
    return result


def _build(variant, params, cable_elements, beam, clearance):
    import exudyn as exu
    from exudyn import itemInterface as items

    start = kinematics(params, 0.0)
    theta2, theta3, theta4 = (float(start[k]) for k in ("theta2", "theta3", "theta4"))
    omega2, omega3, omega4 = (float(start[k]) for k in ("omega2", "omega3", "omega4"))
    a, b, c, d = params.crank_m, params.coupler_m, params.rocker_m, params.ground_m
    masses, inertias = params.masses_kg(), params.inertias_kg_m2()
    gravity = [0.0, -params.gravity_m_s2, 0.0]

    def e(t):
        return np.array([math.cos(t), math.sin(t)])

    def n(t):
        return np.array([-math.sin(t), math.cos(t)])

    joint_a = a * e(theta2)
    velocity_a = a * omega2 * n(theta2)
    o4 = np.array([d, 0.0])

    container = exu.SystemContainer()
    mbs = container.AddSystem()
    ground = mbs.AddObject(items.ObjectGround())
    ground_node = mbs.AddNode(items.NodePointGround())

    def add_gravity(body):
        marker = mbs.AddMarker(items.MarkerBodyMass(bodyNumber=body))
        mbs.AddLoad(items.LoadMassProportional(markerNumber=marker, loadVector=gravity))

    def rigid_link(k, start_point, start_velocity, angle, omega):
        centre = start_point + params.link_lengths_m()[k] / 2 * e(angle)
        centre_velocity = start_velocity + params.link_lengths_m()[k] / 2 * omega * n(angle)
        node = mbs.AddNode(items.NodeRigidBody2D(
            referenceCoordinates=[*centre, angle], initialVelocities=[*centre_velocity, omega]))
        body = mbs.AddObject(items.ObjectRigidBody2D(
            physicsMass=masses[k], physicsInertia=inertias[k], nodeNumber=node))
        add_gravity(body)
        return node, body

    def end_marker(body, x_local):
        return mbs.AddMarker(items.MarkerBodyRigid(bodyNumber=body,
                                                   localPosition=[x_local, 0.0, 0.0]))

    crank_node, crank = rigid_link(0, np.zeros(2), np.zeros(2), theta2, omega2)
    rocker_angle = theta4
    if variant == "clearance":  # start the pin off the bushing centre: |e| = c / 5, no contact
        rocker_angle = theta4 - clearance.clearance_m() / (5 * c)
    rocker_node, rocker = rigid_link(2, o4, np.zeros(2), rocker_angle, omega4)
    sensors = {}
    model = {"mbs": mbs, "exu": exu, "sensors": sensors}
    if variant == "cable":
        element_length = b / cable_elements
        nodes = [mbs.AddNode(items.NodePoint2DSlope1(
            referenceCoordinates=[*(joint_a + k * element_length * e(theta3)), *e(theta3)],
            initialVelocities=[*(velocity_a + k * element_length * omega3 * n(theta3)),
                               *(omega3 * n(theta3))]))
            for k in range(cable_elements + 1)]
        area, second_moment = beam.height_m * beam.width_m, beam.width_m * beam.height_m**3 / 12
        for k in range(cable_elements):
            add_gravity(mbs.AddObject(items.ObjectANCFCable2D(
                physicsLength=element_length, physicsMassPerLength=params.mass_per_length_kg_m,
                physicsBendingStiffness=beam.youngs_modulus_Pa * second_moment,
                physicsAxialStiffness=beam.youngs_modulus_Pa * area,
                nodeNumbers=[nodes[k], nodes[k + 1]])))
        coupler_start = mbs.AddMarker(items.MarkerNodePosition(nodeNumber=nodes[0]))
        coupler_end = mbs.AddMarker(items.MarkerNodePosition(nodeNumber=nodes[-1]))
        for name, node in (("coupler_start", nodes[0]), ("coupler_end", nodes[-1])):
            sensors[name] = mbs.AddSensor(items.SensorNode(
                nodeNumber=node, storeInternal=True, writeToFile=False,
                outputVariableType=exu.OutputVariableType.Position))
    else:
        coupler_node, coupler = rigid_link(1, joint_a, velocity_a, theta3, omega3)
        coupler_start, coupler_end = end_marker(coupler, -b / 2), end_marker(coupler, b / 2)
        sensors["coupler"] = _rotation_sensor(mbs, exu, items, coupler_node)

    joints = {
        "O2": mbs.AddObject(items.RevoluteJoint2D(
            markerNumbers=[end_marker(ground, 0.0), end_marker(crank, -a / 2)])),
        "A": mbs.AddObject(items.RevoluteJoint2D(
            markerNumbers=[end_marker(crank, a / 2), coupler_start])),
        "O4": mbs.AddObject(items.RevoluteJoint2D(markerNumbers=[
            mbs.AddMarker(items.MarkerBodyRigid(bodyNumber=ground, localPosition=[d, 0, 0])),
            end_marker(rocker, -c / 2)])),
    }
    if variant == "clearance":
        joints["B"] = _clearance_connector(mbs, exu, items, coupler_end,
                                           end_marker(rocker, c / 2), clearance, model)
        if clearance.friction_coefficient > 0.0:
            _friction_element(mbs, items, coupler_node, rocker_node, params, clearance, model)
            for name, node in (("coupler_velocity", coupler_node),
                               ("rocker_velocity", rocker_node)):
                sensors[name] = mbs.AddSensor(items.SensorNode(
                    nodeNumber=node, storeInternal=True, writeToFile=False,
                    outputVariableType=exu.OutputVariableType.Coordinates_t))
    else:
        joints["B"] = mbs.AddObject(items.RevoluteJoint2D(
            markerNumbers=[coupler_end, end_marker(rocker, c / 2)]))
    drive = mbs.AddObject(items.CoordinateConstraint(
        markerNumbers=[mbs.AddMarker(items.MarkerNodeCoordinate(nodeNumber=ground_node,
                                                                coordinate=0)),
                       mbs.AddMarker(items.MarkerNodeCoordinate(nodeNumber=crank_node,
                                                                coordinate=2))],
        offset=params.crank_speed_rad_s, velocityLevel=True))
    sensors["crank"] = _rotation_sensor(mbs, exu, items, crank_node)
    sensors["rocker"] = _rotation_sensor(mbs, exu, items, rocker_node)
    for name, joint in joints.items():
        sensors["force_" + name] = mbs.AddSensor(items.SensorObject(
            objectNumber=joint, storeInternal=True, writeToFile=False,
            outputVariableType=exu.OutputVariableType.Force))
    sensors["torque"] = mbs.AddSensor(items.SensorObject(
        objectNumber=drive, storeInternal=True, writeToFile=False,
        outputVariableType=exu.OutputVariableType.Force))
    mbs.Assemble()
    return model


def _rotation_sensor(mbs, exu, items, node):
    return mbs.AddSensor(items.SensorNode(nodeNumber=node, storeInternal=True, writeToFile=False,
                                          outputVariableType=exu.OutputVariableType.CoordinatesTotal))


def _clearance_connector(mbs, exu, items, pin_marker, bushing_marker, clearance, model):
    """Lankarani-Nikravesh contact between the pin and bushing centres (module docstring).
    Markers [pin, bushing]: Exudyn's spring force is positive in tension (pulls the centres
    together), which is the contact force pushing the pin back into the bushing."""
    gap = clearance.clearance_m()
    state = {"impact_velocity": clearance.min_impact_velocity_m_s}

    def contact_force(mbs, t, item, distance, distance_rate, *unused):
        return _normal_force(clearance, distance - gap, distance_rate, state["impact_velocity"])

    connector = mbs.AddObject(items.ObjectConnectorSpringDamper(
        markerNumbers=[pin_marker, bushing_marker], referenceLength=0.0,
        springForceUserFunction=contact_force))

    def pre_step(mbs, t):
        offset = np.asarray(mbs.GetObjectOutput(connector, exu.OutputVariableType.Displacement))
        velocity = np.asarray(mbs.GetObjectOutput(connector, exu.OutputVariableType.Velocity))
        distance = float(np.linalg.norm(offset))
        if distance <= gap:
            radial_rate = float(offset @ velocity) / distance if distance > 0 else 0.0
            state["impact_velocity"] = max(radial_rate, clearance.min_impact_velocity_m_s)
        return True

    mbs.SetPreStepUserFunction(pre_step)
    model["clearance"] = clearance
    model["contact_state"] = state
    return connector


def _normal_force(clearance, penetration, penetration_rate, impact_velocity):
    """Lankarani-Nikravesh F_n = K delta^1.5 [1 + 3 (1 - c_e^2) delta' / (4 delta'^(-))] for
    delta > 0, else 0; never negative (N)."""
    if penetration <= 0.0:
        return 0.0
    hysteresis = 3.0 * (1.0 - clearance.restitution**2) / 4.0
    factor = 1.0 + hysteresis * penetration_rate / impact_velocity
    return max(clearance.stiffness_N_m15() * penetration**1.5 * factor, 0.0)


def _friction_element(mbs, items, coupler_node, rocker_node, params, clearance, model):
    """Friction at the clearance contact as an ObjectGenericODE2 on the coupler and rocker nodes
    (zero mass matrix) whose Python force function gives the generalized forces of the friction
    force on the pin and its reaction on the bushing (``_pin_friction``); Exudyn differentiates it
    numerically for the Jacobian."""
    state = model["contact_state"]
    references = [np.asarray(mbs.GetNodeParameter(node, "referenceCoordinates"), dtype=float)
                  for node in (coupler_node, rocker_node)]

    def generalized_friction(mbs, t, item, q, q_t):
        coupler = np.concatenate([references[0] + q[:3], q_t[:3]])
        rocker = np.concatenate([references[1] + q[3:], q_t[3:]])
        return generalized_friction_N(params, clearance, coupler, rocker,
                                      state["impact_velocity"])

    mbs.AddObject(items.ObjectGenericODE2(nodeNumbers=[coupler_node, rocker_node],
                                          massMatrix=np.zeros((6, 6)),
                                          forceUserFunction=generalized_friction))


def generalized_friction_N(params, clearance, coupler, rocker, impact_velocity_m_s):
    """Generalized forces (N, N, N m per link) of the contact friction on the coupler and rocker
    centre coordinates (x, y, theta), for link states (x, y, theta, vx, vy, omega): the friction
    force F_t at the pin centre plus the moment R_pin (F_t . t), and -F_t at the bushing centre
    plus -R_bushing (F_t . t); zero out of contact. Their power is (F_t . t) v_t <= 0."""
    gap = clearance.clearance_m()
    e, e_rate = _pin_offset(params, coupler, rocker)
    distance = float(np.linalg.norm(e))
    if distance <= gap:
        return np.zeros(6)
    normal_force = _normal_force(clearance, distance - gap, float(e @ e_rate) / distance,
                                 impact_velocity_m_s)
    force, along_t = _pin_friction(params, clearance, coupler, rocker, normal_force)
    arm_pin = params.coupler_m / 2 * np.array([math.cos(coupler[2]), math.sin(coupler[2])])
    arm_bushing = params.rocker_m / 2 * np.array([math.cos(rocker[2]), math.sin(rocker[2])])
    moment_pin = _cross2(arm_pin, force) + clearance.pin_radius_m * along_t
    moment_bushing = -_cross2(arm_bushing, force) - clearance.bushing_radius_m * along_t
    return np.array([*force, moment_pin, *(-force), moment_bushing])


def _cross2(r, f):
    return float(r[0] * f[1] - r[1] * f[0])


def _pin_offset(params, coupler, rocker):
    """e = pin centre - bushing centre (m) and its rate (m/s) from the link states
    (x, y, theta, vx, vy, omega) of the coupler and rocker centres."""
    def end(state, half_length):
        direction = np.array([math.cos(state[2]), math.sin(state[2])])
        normal = np.array([-direction[1], direction[0]])
        return (state[:2] + half_length * direction,
                state[3:5] + half_length * state[5] * normal)

    pin, pin_velocity = end(coupler, params.coupler_m / 2)
    bushing, bushing_velocity = end(rocker, params.rocker_m / 2)
    return pin - bushing, pin_velocity - bushing_velocity


def _pin_friction(params, clearance, coupler, rocker, normal_force):
    """Regularised Coulomb friction on the pin (N) and its component along t: with n = e/|e|,
    t = n rotated +90 deg, the slip speed of the contact points
    v_t = e' . t + w_coupler R_pin - w_rocker R_bushing, and
    F_t = -mu F_n min(|v_t| / v_s, 1) sign(v_t) t (linear ramp through zero slip, v_s =
    ``friction_ramp_velocity_m_s``). The bushing carries -F_t."""
    e, e_rate = _pin_offset(params, coupler, rocker)
    normal = e / np.linalg.norm(e)
    tangent = np.array([-normal[1], normal[0]])
    slip = (float(e_rate @ tangent) + coupler[5] * clearance.pin_radius_m
            - rocker[5] * clearance.bushing_radius_m)
    along_t = (-clearance.friction_coefficient * normal_force
               * float(np.clip(slip / clearance.friction_ramp_velocity_m_s, -1.0, 1.0)))
    return along_t * tangent, along_t


def _solve(mbs, exu, step_s, total_steps, rho_inf, newton_tolerance, relative_only):
    settings = exu.SimulationSettings()
    integration = settings.timeIntegration
    integration.numberOfSteps = total_steps
    integration.endTime = total_steps * step_s
    integration.automaticStepSize = False
    integration.adaptiveStep = False
    integration.verboseMode = 0
    integration.newton.relativeTolerance = newton_tolerance
    if not relative_only:
        integration.newton.absoluteTolerance = newton_tolerance
    integration.generalizedAlpha.spectralRadius = rho_inf
    integration.generalizedAlpha.useIndex2Constraints = False
    integration.generalizedAlpha.useNewmark = False
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step_s
    settings.show.computationTime = False
    settings.show.statistics = False
    mbs.SolveDynamic(settings)


def _outputs(variant, records, model, params, keep):
    out = {"theta2": records["crank"][keep, 3], "theta4": records["rocker"][keep, 3]}
    if variant == "cable":
        chord = records["coupler_end"][keep, 1:3] - records["coupler_start"][keep, 1:3]
        out["theta3"] = np.arctan2(chord[:, 1], chord[:, 0])
    else:
        out["theta3"] = records["coupler"][keep, 3]
    # Exudyn reports a joint's force on its first marker's body: negate for the second body's.
    for name in ("O2", "A", "B", "O4"):
        out["force_" + name] = -records["force_" + name][keep, 1:3]
    out["torque_crank"] = -records["torque"][keep, 1]
    if variant == "clearance":
        clearance = model["clearance"]
        pin = records["coupler"][keep, 1:3] + params.coupler_m / 2 * np.stack(
            [np.cos(out["theta3"]), np.sin(out["theta3"])], axis=1)
        bushing = records["rocker"][keep, 1:3] + params.rocker_m / 2 * np.stack(
            [np.cos(out["theta4"]), np.sin(out["theta4"])], axis=1)
        eccentricity = pin - bushing
        distance = np.linalg.norm(eccentricity, axis=1)
        out["eccentricity_m"] = eccentricity
        out["penetration_m"] = distance - clearance.clearance_m()
        out["contact_force_N"] = np.sum(out["force_B"] * eccentricity, axis=1) / distance
        if clearance.friction_coefficient > 0.0:
            coupler = np.hstack([records["coupler"][keep, 1:4],
                                 records["coupler_velocity"][keep, 1:4]])
            rocker = np.hstack([records["rocker"][keep, 1:4],
                                records["rocker_velocity"][keep, 1:4]])
            on_pin = np.array([_pin_friction(params, clearance, c, r, f)[0] if f > 0 else (0, 0)
                               for c, r, f in zip(coupler, rocker, out["contact_force_N"])])
            out["friction_force_N"] = -on_pin  # on the bushing (rocker)
            out["force_B"] = out["force_B"] + out["friction_force_N"]
    return out


def clearance_cycle_statistics(result: dict, period_s: float) -> dict:
    """Per crank turn of a clearance run (``four_bar_cycle(variant="clearance")``): contact share
    (fraction of the turn's samples with penetration > 0), peak contact force (N) and number of
    impacts (free-flight -> contact transitions, sample to sample). Turns are the half-open
    intervals [k T, (k + 1) T) from the first sample; the closing sample of the last turn is left
    out. Returns one array entry per whole turn."""
    phase = (result["time_s"] - result["time_s"][0]) / period_s
    turns = int(round(phase[-1]))
    turn = np.floor(phase + 1e-9).astype(int)
    in_contact = result["penetration_m"] > 0.0
    onset = np.zeros_like(in_contact)
    onset[1:] = ~in_contact[:-1] & in_contact[1:]
    return {
        "contact_share": np.array([in_contact[turn == k].mean() for k in range(turns)]),
        "peak_force_N": np.array([result["contact_force_N"][turn == k].max()
                                  for k in range(turns)]),
        "impacts": np.array([np.count_nonzero(onset[turn == k]) for k in range(turns)]),
    }
