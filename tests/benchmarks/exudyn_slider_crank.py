"""The paper's ideal-joint rigid slider-crank in Exudyn (PyPI), the peer of fewear's benchmark.

Mechanism (seed section 5): crank of length r about the ground pivot O = (0, 0), driven at constant
speed omega (phi = omega t), rigid connecting rod of length l, slider on the x axis through O.
All joints ideal; gravity -y. Closed form of the slider position and velocity:

    x(phi)  = r cos(phi) + sqrt(l^2 - r^2 sin^2 phi),
    x'(phi) = -r omega sin(phi) - r^2 omega sin(phi) cos(phi) / sqrt(l^2 - r^2 sin^2 phi).

Exudyn model: three ObjectRigidBody2D (nodes at the centres of mass), RevoluteJoint2D at O, at the
crank pin and at the wrist pin, a PrismaticJoint2D (with rotation constrained) for the slider, and a
velocity-level CoordinateConstraint phi' = omega as the drive (no Python callback in the loop).
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
    slider_mass_kg: float = 0.5
    crank_speed_rad_s: float = 1200.0 * 2.0 * math.pi / 60.0
    gravity_m_s2: float = 9.81


def slider_closed_form(params: SliderCrankParameters, time_s: np.ndarray):
    """Slider x (m) and x' (m/s) at ``time_s`` for phi = omega t (module docstring)."""
    r, l, omega = params.crank_length_m, params.rod_length_m, params.crank_speed_rad_s
    phi = omega * np.asarray(time_s, dtype=float)
    root = np.sqrt(l**2 - (r * np.sin(phi)) ** 2)
    x = r * np.cos(phi) + root
    x_dot = -r * omega * np.sin(phi) - r**2 * omega * np.sin(phi) * np.cos(phi) / root
    return x, x_dot


def run_exudyn_slider_crank(step_s: float, end_time_s: float,
                            params: SliderCrankParameters = SliderCrankParameters(),
                            rho_inf: float = 0.9, newton_tolerance: float = 1e-10):
    """Simulate in Exudyn; returns (time_s, slider_x_m, wall_time_s) at every step.

    ``wall_time_s`` is the time of ``SolveDynamic`` only (model building excluded).
    """
    import exudyn as exu
    from exudyn.itemInterface import (
        CoordinateConstraint, MarkerBodyRigid, MarkerNodeCoordinate, NodePointGround,
        NodeRigidBody2D, ObjectGround, PrismaticJoint2D, RevoluteJoint2D, RigidBody2D,
        LoadMassProportional, MarkerBodyMass, SensorNode,
    )

    r, l, omega = params.crank_length_m, params.rod_length_m, params.crank_speed_rad_s
    # Start at phi = 0 (top dead centre): consistent positions and velocities.
    pin_velocity = np.array([0.0, r * omega])
    rod_omega = -r * omega / l

    system_container = exu.SystemContainer()
    mbs = system_container.AddSystem()
    ground = mbs.AddObject(ObjectGround())
    ground_node = mbs.AddNode(NodePointGround())

    def body(mass, inertia, position, angle, velocity, angular_velocity):
        node = mbs.AddNode(NodeRigidBody2D(
            referenceCoordinates=[position[0], position[1], angle],
            initialVelocities=[velocity[0], velocity[1], angular_velocity],
        ))
        number = mbs.AddObject(RigidBody2D(physicsMass=mass, physicsInertia=inertia,
                                           nodeNumber=node))
        mass_marker = mbs.AddMarker(MarkerBodyMass(bodyNumber=number))
        mbs.AddLoad(LoadMassProportional(markerNumber=mass_marker,
                                         loadVector=[0.0, -params.gravity_m_s2, 0.0]))
        return node, number

    crank_node, crank = body(params.crank_mass_kg, params.crank_inertia_kg_m2, (r / 2, 0.0), 0.0,
                             pin_velocity / 2, omega)
    _, rod = body(params.rod_mass_kg, params.rod_inertia_kg_m2, (r + l / 2, 0.0), 0.0,
                  pin_velocity / 2, rod_omega)
    slider_node, slider = body(params.slider_mass_kg, 1e-4, (r + l, 0.0), 0.0, (0.0, 0.0), 0.0)

    def marker(body_number, x_local):
        return mbs.AddMarker(MarkerBodyRigid(bodyNumber=body_number,
                                             localPosition=[x_local, 0.0, 0.0]))

    mbs.AddObject(RevoluteJoint2D(markerNumbers=[marker(ground, 0.0), marker(crank, -r / 2)]))
    mbs.AddObject(RevoluteJoint2D(markerNumbers=[marker(crank, r / 2), marker(rod, -l / 2)]))
    mbs.AddObject(RevoluteJoint2D(markerNumbers=[marker(rod, l / 2), marker(slider, 0.0)]))
    mbs.AddObject(PrismaticJoint2D(markerNumbers=[marker(ground, 0.0), marker(slider, 0.0)],
                                   axisMarker0=[1.0, 0.0, 0.0], normalMarker1=[0.0, 1.0, 0.0],
                                   constrainRotation=True))
    mbs.AddObject(CoordinateConstraint(
        markerNumbers=[mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=ground_node, coordinate=0)),
                       mbs.AddMarker(MarkerNodeCoordinate(nodeNumber=crank_node, coordinate=2))],
        offset=omega, velocityLevel=True,
    ))
    sensor = mbs.AddSensor(SensorNode(nodeNumber=slider_node, storeInternal=True,
                                      writeToFile=False,
                                      outputVariableType=exu.OutputVariableType.Position))
    mbs.Assemble()

    settings = exu.SimulationSettings()
    n_steps = int(round(end_time_s / step_s))
    integration = settings.timeIntegration
    integration.numberOfSteps = n_steps
    integration.endTime = n_steps * step_s
    integration.automaticStepSize = False
    integration.adaptiveStep = False
    integration.verboseMode = 0
    integration.newton.relativeTolerance = newton_tolerance
    integration.newton.absoluteTolerance = newton_tolerance
    integration.generalizedAlpha.spectralRadius = rho_inf
    integration.generalizedAlpha.useIndex2Constraints = False
    integration.generalizedAlpha.useNewmark = False
    settings.solutionSettings.writeSolutionToFile = False
    settings.solutionSettings.sensorsWritePeriod = step_s
    settings.displayComputationTime = False
    settings.displayStatistics = False

    start = time.perf_counter()
    mbs.SolveDynamic(settings)
    wall_time_s = time.perf_counter() - start
    data = mbs.GetSensorStoredData(sensor)
    return data[:, 0], data[:, 1], wall_time_s

