"""A planar mechanism as data: bodies with named points, joints naming two points, drivers.

What a mechanism file (docs/mechanisms.md, parsed by :mod:`fewear.io.mechanism`) describes, in SI
units and radians, before any coordinates exist; :mod:`fewear.mbd.mechanism` builds the
multibody system from it. In the style of Exudyn's items: bodies carry markers (named points in
the body frame, whose origin is the centre of mass), joints name the two markers they connect.

- A body is rigid (mass, inertia) or a flexible ANCF beam; a body described as a uniform bar
  (:class:`Bar`) can be either, so a run's case may switch it (``Mechanism.variable_body``).
- Joints: ``revolute`` (pin point in bushing point; ideal, or with clearance: a force element,
  :mod:`fewear.mbd.clearance`), ``prismatic`` (a body slides along a fixed direction of the
  ground without rotating), ``fixed`` (two rigid bodies, or a body and the ground, welded).
- Drivers prescribe a body's angle: at constant speed, or a periodic table of angles.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from fewear.errors import FewearInputError

GROUND = "ground"
BODY_MODELS = ("rigid", "flexible")
JOINT_TYPES = ("revolute", "prismatic", "fixed")
CASES = BODY_MODELS
"""The run cases (``[wear_loop] rod_models``): the model of the mechanism's variable body."""


@dataclass(frozen=True)
class Bar:
    """A uniform straight bar along the body's x axis, centred on its origin: the rigid body's mass
    rho A L and inertia m L^2 / 12, or the ANCF beam's section and mesh (flexible)."""

    length_m: float
    density_kg_m3: float
    height_m: float  # in the plane of motion (bending thickness)
    width_m: float  # out of plane
    youngs_modulus_Pa: float | None = None
    poisson_ratio: float | None = None
    elements: int = 4
    damping_s: float = 0.0  # stiffness-proportional damping of the beam (fewear.mbd.system)

    @property
    def mass_kg(self) -> float:
        return self.density_kg_m3 * self.height_m * self.width_m * self.length_m

    @property
    def inertia_kg_m2(self) -> float:
        return self.mass_kg * self.length_m * self.length_m / 12.0


@dataclass(frozen=True)
class Body:
    """A body: its model, inertia, named points (body frame, origin at the centre of mass) and an
    approximate initial pose (position of the origin, angle of the x axis), which the assembly
    corrects onto the joints."""

    name: str
    model: str  # "rigid" or "flexible"
    mass_kg: float
    inertia_kg_m2: float
    points: tuple[tuple[str, tuple[float, float]], ...]
    position_m: tuple[float, float]
    angle_rad: float
    bar: Bar | None = None

    def point(self, name: str) -> tuple[float, float]:
        return dict(self.points)[name]


def beam_node(body: Body, point: str) -> int:
    """The node of a flexible body's ANCF beam at ``point`` (a point on the axis at a node:
    (s, 0) with s + L/2 a multiple of half an element)."""
    x, y = body.point(point)
    bar = body.bar
    spacing = bar.length_m / (2 * bar.elements)
    node = round((x + bar.length_m / 2.0) / spacing)
    if (abs(y) > 1e-9 * bar.length_m or not 0 <= node <= 2 * bar.elements
            or abs(node * spacing - bar.length_m / 2.0 - x) > 1e-9 * bar.length_m):
        raise FewearInputError(
            f"body {body.name!r}: point {point} = {[x, y]!r} is not at a node of the flexible "
            f"body's beam (the axis y = 0 at x = -L/2 + k L/{2 * bar.elements}, L = "
            f"{bar.length_m!r} m)")
    return node


@dataclass(frozen=True)
class PointRef:
    """A named point of a body (``body`` = ``GROUND`` for the ground)."""

    body: str
    point: str

    def __str__(self) -> str:
        return f"{self.body}.{self.point}"


@dataclass(frozen=True)
class Joint:
    """A joint between two points. Revolute: ``first`` is the pin, ``second`` the bushing (the
    clearance profile and the recorded history are in the bushing body's frame); prismatic:
    ``first`` on the ground, ``direction`` (unit, ground frame) the slide; fixed: any two."""

    name: str
    type: str
    first: PointRef
    second: PointRef
    clearance: bool = False
    direction: tuple[float, float] = (1.0, 0.0)

    @property
    def pin(self) -> PointRef:
        return self.first

    @property
    def bushing(self) -> PointRef:
        return self.second


@dataclass(frozen=True)
class Driver:
    """A body's angle prescribed: phi(t) = initial_angle_rad + speed_rad_s t (constant speed), or
    the periodic cubic spline through ``table_angle_rad`` at ``table_time_s`` (one period, the
    last angle equal to the first)."""

    body: str
    initial_angle_rad: float = 0.0
    speed_rad_s: float = 0.0
    table_time_s: tuple[float, ...] = ()
    table_angle_rad: tuple[float, ...] = ()

    @property
    def tabulated(self) -> bool:
        return bool(self.table_time_s)

    @property
    def period_s(self) -> float:
        if self.tabulated:
            return self.table_time_s[-1] - self.table_time_s[0]
        return 2.0 * math.pi / abs(self.speed_rad_s)


@dataclass(frozen=True)
class Mechanism:
    """The whole description. ``variable_body``: the body whose model (rigid/flexible) a run's
    case selects (None: the cases only name the runs). ``gravity_m_s2`` acts along -y."""

    name: str
    bodies: tuple[Body, ...]
    ground_points: tuple[tuple[str, tuple[float, float]], ...]
    joints: tuple[Joint, ...]
    drivers: tuple[Driver, ...]
    gravity_m_s2: float = 9.81
    variable_body: str | None = None

    def body(self, name: str) -> Body:
        return next(body for body in self.bodies if body.name == name)

    @property
    def clearance_joints(self) -> tuple[Joint, ...]:
        return tuple(joint for joint in self.joints if joint.clearance)

    @property
    def period_s(self) -> float:
        """One cycle of the mechanism: the first driver's period."""
        return self.drivers[0].period_s

    def with_case(self, case: str) -> Mechanism:
        """The mechanism of a run's case: the variable body's model set to ``case``."""
        if case not in CASES:
            raise FewearInputError(f"case {case!r}: expected one of {', '.join(CASES)}")
        if self.variable_body is None:
            return self
        bodies = tuple(replace(body, model=case) if body.name == self.variable_body else body
                       for body in self.bodies)
        return replace(self, bodies=bodies)

    def without_clearance(self) -> Mechanism:
        """Every clearance joint made ideal."""
        return replace(self, joints=tuple(replace(joint, clearance=False)
                                          for joint in self.joints))
