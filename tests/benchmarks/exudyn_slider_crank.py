"""The paper's ideal-joint rigid slider-crank in Exudyn (PyPI), the peer of fewear's benchmark.

Mechanism (seed section 5): crank of length r about the ground pivot O = (0, 0), driven at constant
speed omega (phi = omega t), rigid connecting rod of length l, slider on the x axis through O.
All joints ideal; gravity -y. Closed form of the slider position and velocity:

    x(phi)  = r cos(phi) + sqrt(l^2 - r^2 sin^2 phi),
    x'(phi) = -r omega sin(phi) - r^2 omega sin(phi) cos(phi) / sqrt(l^2 - r^2 sin^2 phi).

Exudyn model: three ObjectRigidBody2D (nodes at the centres of mass), RevoluteJoint2D at O, at the
crank pin and at the wrist pin, a PrismaticJoint2D (with rotation constrained) for the slider, and a
velocity-level CoordinateConstraint phi' = omega as the drive (no Python callback in the loop).
Variant: the rod as Exudyn's ANCF cable (ObjectANCFCable2D, Euler-Bernoulli), to cross-check
fewear's flexible rod.
Solved with Exudyn's index-3 generalized-alpha at a fixed step (no step-size control), spectral
radius ``rho_inf``, Newton tolerance as given, no solution file: only internally stored sensors.
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class SliderCrankParameters:
    """Rigid slider-crank (SI). Inertias are about each body's centre of mass."""

    crank_length_m: float = 0.1
    crank_mass_kg: float = 0.3
    crank_inertia_kg_m2: float = 0.3 * 0.1**2 / 12.0
    rod_length_m: float = 0.34
    rod_mass_kg: float = 7800.0 * 0.34 * 0.018 * 0.005
    rod_inertia_kg_m2: float = 7800.0 * 0.34 * 0.018 * 0.005 * 0.34**2 / 12.0
    rod_youngs_modulus_Pa: float = 211.0e9  # elastic rod only
    rod_height_m: float = 0.005  # in the plane of motion
    rod_width_m: float = 0.018
    slider_mass_kg: float = 0.5
    slider_inertia_kg_m2: float = 0.5e-4
    crank_speed_rad_s: float = 1200.0 * 2.0 * math.pi / 60.0
    initial_crank_angle_rad: float = 0.0
    gravity_m_s2: float = 9.81


def parameters_from_defaults(**changes) -> SliderCrankParameters:
    """The rigid mechanism of fewear's [mechanism] defaults (``fewear/defaults/dynamics.toml``)
    with ``changes`` of [mechanism] keys: rod inertia m l^2/12 of the uniform rod, slider inertia
    1e-4 m^2 times its mass (its rotation is constrained, so the value does not matter), as in
    ``fewear.mbd.slider_crank``."""
    from fewear.io.config import load_config

    mechanism = {**load_config(None, ["mechanism"])["mechanism"], **changes}
    rod_mass = (mechanism["rod_density_kg_m3"] * mechanism["rod_height_m"]
                * mechanism["rod_width_m"] * mechanism["rod_length_m"])
    return SliderCrankParameters(
        crank_length_m=mechanism["crank_length_m"],
        crank_mass_kg=mechanism["crank_mass_kg"],
        crank_inertia_kg_m2=mechanism["crank_inertia_kg_m2"],
        rod_length_m=mechanism["rod_length_m"],
        rod_mass_kg=rod_mass,
        rod_inertia_kg_m2=rod_mass * mechanism["rod_length_m"] ** 2 / 12.0,
        rod_youngs_modulus_Pa=mechanism["rod_youngs_modulus_Pa"],
        rod_height_m=mechanism["rod_height_m"],
        rod_width_m=mechanism["rod_width_m"],
        slider_mass_kg=mechanism["slider_mass_kg"],
        slider_inertia_kg_m2=mechanism["slider_mass_kg"] * 1e-4,
        crank_speed_rad_s=mechanism["crank_speed_rpm"] * 2.0 * math.pi / 60.0,
        initial_crank_angle_rad=math.radians(mechanism["initial_crank_angle_deg"]),
        gravity_m_s2=mechanism["gravity_m_s2"],
    )


def slider_closed_form(params: SliderCrankParameters, time_s: np.ndarray):
    """Slider x (m) and x' (m/s) at ``time_s`` for phi = phi0 + omega t (module docstring)."""
    r, rod_length, omega = params.crank_length_m, params.rod_length_m, params.crank_speed_rad_s
    phi = params.initial_crank_angle_rad + omega * np.asarray(time_s, dtype=float)
    root = np.sqrt(rod_length**2 - (r * np.sin(phi)) ** 2)
    x = r * np.cos(phi) + root
    x_dot = -r * omega * np.sin(phi) - r**2 * omega * np.sin(phi) * np.cos(phi) / root
    return x, x_dot


def run_exudyn_slider_crank(step_s: float, end_time_s: float,
                            params: SliderCrankParameters = SliderCrankParameters(),
                            rho_inf: float = 0.9, newton_tolerance: float = 1e-10):
    """The rigid-rod mechanism in Exudyn; returns (time_s, slider_x_m, wall_time_s) at every step.

    ``wall_time_s`` is the time of ``SolveDynamic`` only (model building excluded).
    """
    time_s, slider_x_m, _, wall_time_s = _simulate(step_s, end_time_s, params, rho_inf,
                                                   newton_tolerance, cable_elements=0)
    return time_s, slider_x_m, wall_time_s


def run_exudyn_cable_slider_crank(step_s: float, end_time_s: float,
                                  params: SliderCrankParameters = SliderCrankParameters(),
                                  cable_elements: int = 8, rho_inf: float = 0.9,
                                  newton_tolerance: float = 1e-8):
    """The mechanism with an elastic rod of Exudyn's ObjectANCFCable2D (Euler-Bernoulli ANCF: axial
    stiffness E A, bending stiffness E I, no shear) and ideal joints: a peer for fewear's
    shear-deformable ANCF rod where shear is negligible (the paper's rod has L/h = 68).

    Returns (time_s, slider_x_m, wrist_force_N (n, 2): the rod-slider joint force, wall_time_s).
    Newton's tolerance is relative (Exudyn's absolute residual criterion cannot reach 1e-10 with the
    rod's axial stiffness in the residual).
    """
    return _simulate(step_s, end_time_s, params, rho_inf, newton_tolerance, cable_elements)


def _simulate(step_s, end_time_s, params, rho_inf, newton_tolerance, cable_elements):
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint,
        LoadMassProportional,
        MarkerBodyMass,
        MarkerBodyRigid,
        MarkerNodeCoordinate,
        MarkerNodePosition,
        NodePoint2DSlope1,
        NodePointGround,
        NodeRigidBody2D,
        ObjectANCFCable2D,
        ObjectGround,
        PrismaticJoint2D,
        RevoluteJoint2D,
        RigidBody2D,
        SensorNode,
        SensorObject,
    )

    r, rod_length, omega = params.crank_length_m, params.rod_length_m, params.crank_speed_rad_s
    # Consistent initial positions and velocities of the ideal mechanism at phi0.
    phi = params.initial_crank_angle_rad
    pin = r * np.array([math.cos(phi), math.sin(phi)])
    pin_velocity = r * omega * np.array([-math.sin(phi), math.cos(phi)])
    slider_x, slider_velocity = (float(v) for v in slider_closed_form(params, 0.0))
    rod_angle = math.asin(-r * math.sin(phi) / rod_length)
    rod_omega = -r * omega * math.cos(phi) / (rod_length * math.cos(rod_angle))
    axis = np.array([math.cos(rod_angle), math.sin(rod_angle)])
    normal = np.array([-axis[1], axis[0]])
    gravity = [0.0, -params.gravity_m_s2, 0.0]

    system_container = exu.SystemContainer()
    mbs = system_container.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    ground_node = mbs.AddNode(NodePointGround())

    def add_gravity(body_number):
        mass_marker = mbs.AddMarker(MarkerBodyMass(bodyNumber=body_number))
        mbs.AddLoad(LoadMassProportional(markerNumber=mass_marker, loadVector=gravity))

    def rigid_body(mass, inertia, position, angle, velocity, angular_velocity):
        node = mbs.AddNode(NodeRigidBody2D(
            referenceCoordinates=[position[0], position[1], angle],
            initialVelocities=[velocity[0], velocity[1], angular_velocity],
        ))
        number = mbs.AddObject(RigidBody2D(mass=mass, inertia=inertia, nodeNumber=node))
        add_gravity(number)
        return node, number

    def marker(body_number, x_local):
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_number,
                                             localPosition=[x_local, 0.0, 0.0]))

    crank_node, crank = rigid_body(params.crank_mass_kg, params.crank_inertia_kg_m2, pin / 2, phi,
                                   pin_velocity / 2, omega)
    slider_node, slider = rigid_body(params.slider_mass_kg, params.slider_inertia_kg_m2,
                                     (slider_x, 0.0), 0.0, (slider_velocity, 0.0), 0.0)
    if cable_elements == 0:
        centre_velocity = pin_velocity + rod_length / 2 * rod_omega * normal
        _, rod = rigid_body(params.rod_mass_kg, params.rod_inertia_kg_m2,
                            pin + rod_length / 2 * axis, rod_angle, centre_velocity, rod_omega)
        rod_start, rod_end = marker(rod, -rod_length / 2), marker(rod, rod_length / 2)
    else:
        element_length = rod_length / cable_elements
        nodes = []
        for k in range(cable_elements + 1):
            position = pin + k * element_length * axis
            velocity = pin_velocity + rod_omega * k * element_length * normal
            nodes.append(mbs.AddNode(NodePoint2DSlope1(
                referenceCoordinates=[*position, *axis],
                initialVelocities=[*velocity, *(rod_omega * normal)],
            )))
        E, h, b = params.rod_youngs_modulus_Pa, params.rod_height_m, params.rod_width_m
        for k in range(cable_elements):
            add_gravity(mbs.AddObject(ObjectANCFCable2D(
                length=element_length, massPerLength=params.rod_mass_kg / rod_length,
                bendingStiffness=E * b * h**3 / 12.0, axialStiffness=E * b * h,
                nodeNumbers=[nodes[k], nodes[k + 1]],
            )))
        rod_start = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[0]))
        rod_end = mbs.AddMarker(MarkerNodePosition(nodeNumber=nodes[-1]))

    mbs.AddObject(RevoluteJoint2D(markerNumbers=[marker(ground, 0.0), marker(crank, -r / 2)]))
    mbs.AddObject(RevoluteJoint2D(markerNumbers=[marker(crank, r / 2), rod_start]))
    wrist = mbs.AddObject(RevoluteJoint2D(markerNumbers=[rod_end, marker(slider, 0.0)]))
    mbs.AddObject(PrismaticJoint2D(markerNumbers=[marker(ground, 0.0), marker(slider, 0.0)],
                                   axisMarker0=[1.0, 0.0, 0.0], normalMarker1=[0.0, 1.0, 0.0],
                                   constrainRotation=True))
    mbs.AddObject(CoordinateConstraint(
        markerNumbers=[mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0)),
                       mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=crank_node, coordinate=2))],
        offset=omega, velocityLevel=True,
    ))
    position_sensor = mbs.AddSensor(SensorNode(
        nodeNumber=slider_node, storeInternal=True, writeToFile=False,
        outputVariableType=exu.OutputVariableType.Position))
    force_sensor = mbs.AddSensor(SensorObject(
        objectNumber=wrist, storeInternal=True, writeToFile=False,
        outputVariableType=exu.OutputVariableType.Force))
    mbs.Assemble()

    settings = exu.SimulationSettings()
    n_steps = round(end_time_s / step_s)
    integration = settings.timeIntegration
    integration.numberOfSteps = n_steps
    integration.endTime = n_steps * step_s
    integration.automaticStepSize = False
    integration.adaptiveStep = False
    integration.verboseMode = 0
    integration.newton.relativeTolerance = newton_tolerance
    if cable_elements == 0:
        integration.newton.absoluteTolerance = newton_tolerance
    integration.generalizedAlpha.spectralRadius = rho_inf
    integration.generalizedAlpha.useIndex2Constraints = False
    integration.generalizedAlpha.useNewmark = False
    settings.solution.file.write = False
    settings.solution.sensors.writePeriod = step_s
    settings.show.computationTime = False
    settings.show.statistics = False

    start = time.perf_counter()
    mbs.SolveDynamic(settings)
    wall_time_s = time.perf_counter() - start
    position = mbs.GetSensorStoredData(position_sensor)
    force = mbs.GetSensorStoredData(force_sensor)
    return position[:, 0], position[:, 1], force[:, 1:3], wall_time_s
