"""Contact laws of the revolute clearance joint: normal force, friction, clearance profile.

Normal force F_n = F_el(delta) [1 + chi delta_dot / v_imp], clipped at 0, with the hysteresis
factors of Lankarani & Nikravesh (seed eq. 6), Hunt & Crossley or Flores et al., or a tabulated
elastic law; Coulomb friction with Ambrosio's dynamic correction near zero slip.
The table of laws: docs/dynamics.md (Method notes).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
from scipy.interpolate import CubicSpline

from fewear.errors import FewearInputError
from fewear.jit import compiled

CONTACT_LAWS = ("lankarani-nikravesh", "hunt-crossley", "flores", "tabulated")


def lankarani_nikravesh_stiffness(pin_radius_m: float, bushing_radius_m: float,
                                  pin_modulus_Pa: float, pin_poisson: float,
                                  bushing_modulus_Pa: float, bushing_poisson: float) -> float:
    """K (N/m^1.5) of the seed's eq. 6 for a pin of radius R_i in a bore of radius R_j > R_i."""
    if not 0.0 < pin_radius_m < bushing_radius_m:
        raise FewearInputError(
            f"pin radius {pin_radius_m!r} m and bushing inner radius {bushing_radius_m!r} m: "
            "expected 0 < pin radius < bushing inner radius (a positive radial clearance)")
    h_pin = (1.0 - pin_poisson**2) / (math.pi * pin_modulus_Pa)
    h_bushing = (1.0 - bushing_poisson**2) / (math.pi * bushing_modulus_Pa)
    radius_term = math.sqrt(pin_radius_m * bushing_radius_m / (bushing_radius_m - pin_radius_m))
    return 4.0 / (3.0 * math.pi * (h_pin + h_bushing)) * radius_term


def hysteresis_factor(law: str, restitution: float) -> float:
    """chi(c_e) of the table in the method notes."""
    if law in ("lankarani-nikravesh", "tabulated"):
        return 0.75 * (1.0 - restitution**2)
    if law == "hunt-crossley":
        return 1.5 * (1.0 - restitution)
    if law == "flores":
        return 1.6 * (1.0 - restitution) / restitution
    raise FewearInputError(f"contact law {law!r}: expected one of {', '.join(CONTACT_LAWS)}")


@dataclass(frozen=True)
class ContactLaw:
    """A normal contact law (see method notes).

    stiffness_N_m1_5: K of the power laws; penetration_m / force_N: the table of the tabulated
    law (increasing penetrations from 0, forces from 0, non-decreasing); restitution: c_e in (0, 1];
    min_impact_velocity_m_s: the floor of v_imp (a grazing contact would otherwise divide by ~0).
    """

    law: str = "lankarani-nikravesh"
    stiffness_N_m1_5: float = 0.0
    restitution: float = 0.9
    min_impact_velocity_m_s: float = 1.0e-3
    penetration_m: np.ndarray = field(default_factory=lambda: np.zeros(0))
    force_N: np.ndarray = field(default_factory=lambda: np.zeros(0))

    def __post_init__(self):
        if self.law not in CONTACT_LAWS:
            raise FewearInputError(
                f"contact law {self.law!r}: expected one of {', '.join(CONTACT_LAWS)}")
        if not 0.0 < self.restitution <= 1.0:
            raise FewearInputError(
                f"restitution coefficient {self.restitution!r}: expected 0 < c_e <= 1")
        if not self.min_impact_velocity_m_s > 0.0:
            raise FewearInputError(
                f"min_impact_velocity_m_s = {self.min_impact_velocity_m_s!r}: expected > 0")
        if self.law == "tabulated":
            pen = np.asarray(self.penetration_m, dtype=float)
            force = np.asarray(self.force_N, dtype=float)
            if pen.ndim != 1 or pen.shape != force.shape or pen.size < 2:
                raise FewearInputError(
                    "tabulated contact law: penetration_m and force_N must be equal-length lists "
                    f"of at least 2 numbers (got {pen.size} and {force.size})")
            if pen[0] != 0.0 or force[0] != 0.0 or np.any(np.diff(pen) <= 0.0) \
                    or np.any(np.diff(force) < 0.0):
                raise FewearInputError(
                    "tabulated contact law: expected penetration_m strictly increasing from 0 "
                    "and force_N non-decreasing from 0")
            object.__setattr__(self, "penetration_m", pen)
            object.__setattr__(self, "force_N", force)
        elif not self.stiffness_N_m1_5 > 0.0:
            raise FewearInputError(
                f"contact stiffness {self.stiffness_N_m1_5!r} N/m^1.5: expected > 0")
        object.__setattr__(self, "chi", hysteresis_factor(self.law, self.restitution))

    @property
    def kernel_data(self):
        """(power law?, (K, chi, v_imp floor), table (2, T)): the arguments of
        :func:`normal_force`."""
        table = (np.array([[0.0], [0.0]]) if self.law != "tabulated"
                 else np.stack([self.penetration_m, self.force_N]))
        return (self.law != "tabulated",
                np.array([self.stiffness_N_m1_5, self.chi, self.min_impact_velocity_m_s]), table)

    def elastic(self, delta_m: float) -> tuple[float, float]:
        """(F_el, dF_el/ddelta) for delta >= 0."""
        power_law, _, table = self.kernel_data
        return elastic_force(power_law, self.stiffness_N_m1_5, table, table.shape[1], delta_m)

    def normal_force(self, delta_m: float, rate_m_s: float, impact_velocity_m_s: float):
        """(F_n, dF_n/ddelta, dF_n/ddelta_dot) (N, N/m, N s/m); zero derivatives when clipped."""
        power_law, parameters, table = self.kernel_data
        return normal_force(power_law, parameters, table, table.shape[1], delta_m, rate_m_s,
                            impact_velocity_m_s)


@compiled
def elastic_force(power_law, stiffness, table, size, delta_m):
    """(F_el, dF_el/ddelta) for delta >= 0: K delta^1.5, or the table (2, size) of penetrations
    and forces interpolated linearly (extrapolated past its last point)."""
    if power_law:
        root = math.sqrt(delta_m)
        return stiffness * delta_m * root, 1.5 * stiffness * root
    pen, force = table[0, :size], table[1, :size]
    k = min(max(np.searchsorted(pen, delta_m) - 1, 0), size - 2)
    slope = (force[k + 1] - force[k]) / (pen[k + 1] - pen[k])
    return force[k] + slope * (delta_m - pen[k]), slope


@compiled
def normal_force(power_law, parameters, table, size, delta_m, rate_m_s, impact_velocity_m_s):
    """(F_n, dF_n/ddelta, dF_n/ddelta_dot) = F_el [1 + chi delta_dot / v_imp] clipped at 0 (module
    docstring); ``parameters`` = (K, chi, floor of v_imp)."""
    if delta_m <= 0.0:
        return 0.0, 0.0, 0.0
    stiffness, chi, min_impact_velocity = parameters[0], parameters[1], parameters[2]
    v_imp = max(impact_velocity_m_s, min_impact_velocity)
    elastic, elastic_stiffness = elastic_force(power_law, stiffness, table, size, delta_m)
    damping = 1.0 + chi * rate_m_s / v_imp
    if damping <= 0.0:
        return 0.0, 0.0, 0.0
    return elastic * damping, elastic_stiffness * damping, elastic * chi / v_imp


@dataclass(frozen=True)
class Friction:
    """Regularised Coulomb friction (method notes): mu, v0 < v1 (m/s)."""

    coefficient: float = 0.1
    v0_m_s: float = 1.0e-4
    v1_m_s: float = 1.0e-3

    def __post_init__(self):
        if not self.coefficient >= 0.0:
            raise FewearInputError(
                f"friction coefficient {self.coefficient!r}: expected a number >= 0")
        if not 0.0 <= self.v0_m_s < self.v1_m_s:
            raise FewearInputError(
                f"friction velocities v0 = {self.v0_m_s!r}, v1 = {self.v1_m_s!r} m/s: expected "
                "0 <= v0 < v1")

    def factor(self, slip_m_s: float) -> tuple[float, float]:
        """(psi, dpsi/dv) with F_t = -mu F_n psi(v_t): psi = c_d(|v|) sign(v)."""
        return friction_factor(self.v0_m_s, self.v1_m_s, slip_m_s)


@compiled
def friction_factor(v0_m_s, v1_m_s, slip_m_s):
    """(psi, dpsi/dv) of Ambrosio's regularisation (method notes): psi = c_d(|v|) sign(v)."""
    speed = abs(slip_m_s)
    if speed <= v0_m_s:
        return 0.0, 0.0
    sign = 1.0 if slip_m_s > 0.0 else -1.0
    if speed >= v1_m_s:
        return sign, 0.0
    width = v1_m_s - v0_m_s
    return sign * (speed - v0_m_s) / width, 1.0 / width


def periodic_cubic(angle_rad: np.ndarray, values: np.ndarray) -> CubicSpline:
    """The 2 pi periodic cubic spline (C2) through the table ``(angle_rad, values)`` (angles
    increasing within [0, 2 pi), unchecked), closed by the first point repeated at its angle +
    2 pi; it extrapolates periodically. The clearance and the worn bore as the dynamics see them:
    the contact normal turns continuously, where linear interpolation would kink it at every
    tabulated angle."""
    closed = np.append(angle_rad, angle_rad[0] + 2.0 * math.pi)
    return CubicSpline(closed, np.append(values, values[0]), bc_type="periodic",
                       extrapolate="periodic")


@dataclass(frozen=True)
class ClearanceProfile:
    """The radial clearance as a function of the contact direction in the bushing frame.

    ``angle_rad``: increasing angles in [0, 2 pi) of the direction from the bushing centre to the
    pin centre, measured from the bushing frame's x axis (for the slider: the slide direction);
    ``clearance_m``: the clearance c(theta) > 0 there = (local bore radius) - (pin radius). The
    profile is periodic (2 pi) and interpolated by a periodic cubic spline through the given angles
    (C2: the contact normal, which leans with the slope c', turns continuously, so the integrator
    is not kicked at the nodes of a worn profile; linear interpolation made the flexible rod's
    steps collapse on a worn bore); a single angle gives a constant. The wear stage passes the
    worn bore here: c(theta) = c0 + wear depth(theta) where it conforms to the pin.
    Penetration: delta = |e| - c(theta(e)).
    """

    angle_rad: np.ndarray
    clearance_m: np.ndarray

    @classmethod
    def constant(cls, clearance_m: float) -> ClearanceProfile:
        return cls(np.array([0.0]), np.array([clearance_m]))

    def __post_init__(self):
        angle = np.atleast_1d(np.asarray(self.angle_rad, dtype=float))
        clearance = np.atleast_1d(np.asarray(self.clearance_m, dtype=float))
        if angle.ndim != 1 or angle.shape != clearance.shape or angle.size == 0:
            raise FewearInputError(
                "clearance profile: angle_rad and clearance_m must be equal-length, non-empty")
        if np.any(np.diff(angle) <= 0.0) or angle[0] < 0.0 or angle[-1] >= 2.0 * math.pi:
            raise FewearInputError(
                "clearance profile: angles must increase strictly within [0, 2 pi)")
        if not np.all(clearance > 0.0):
            bad = clearance[clearance <= 0.0][0]
            raise FewearInputError(
                f"clearance {bad!r} m: the radial clearance must be positive (pin radius < bore)")
        object.__setattr__(self, "angle_rad", angle)
        object.__setattr__(self, "clearance_m", clearance)
        cubic = np.array([[0.0, 0.0, 0.0, clearance[0]]])  # (c3, c2, c1, c0) per piece
        if angle.size > 1:
            cubic = np.ascontiguousarray(periodic_cubic(angle, clearance).c.T)
        object.__setattr__(self, "cubic", cubic)

    def __call__(self, theta_rad: float) -> tuple[float, float, float]:
        """(c, dc/dtheta, d2c/dtheta2) at the direction theta (any real angle)."""
        return clearance_at(self.angle_rad, self.cubic, self.angle_rad.size, theta_rad)


@compiled
def clearance_at(angle_rad, cubic, size, theta_rad):
    """(c, dc/dtheta, d2c/dtheta2) of the periodic piecewise cubic with pieces (c3, c2, c1, c0)
    ``cubic`` starting at ``angle_rad`` (the first ``size``; one piece: a constant)."""
    angle = angle_rad[:size]
    theta = theta_rad % (2.0 * math.pi)
    k = np.searchsorted(angle, theta, side="right") - 1
    if k < 0:  # before the first angle: the last piece, which wraps past 2 pi
        k, theta = size - 1, theta + 2.0 * math.pi
    c3, c2, c1, c0 = cubic[k, 0], cubic[k, 1], cubic[k, 2], cubic[k, 3]
    x = theta - angle[k]
    return (((c3 * x + c2) * x + c1) * x + c0, (3.0 * c3 * x + 2.0 * c2) * x + c1,
            6.0 * c3 * x + 2.0 * c2)


@compiled
def pin_reach_m(direction_rad, point_angle_rad, point_radius_m, pin_radius_m):
    """How far the centre of a rigid pin of radius R_p can move from the bushing centre in each
    direction u(``direction_rad``) before the pin touches one of the bore points q_k (polar:
    ``point_angle_rad``, ``point_radius_m``): the smallest s_k = q_k.u - sqrt((q_k.u)^2 - |q_k|^2
    + R_p^2) over the points the pin reaches from inside (real root, s_k >= 0; inf if none).

    A circular bore gives R_b - R_p in every direction of a point; a worn lobe that conforms to
    the pin, c0 + h; a groove narrower than the pin is bridged (the pin rests on its flanks).
    Compiled: the wear loop samples thousands of directions against thousands of points per
    block (:meth:`fewear.wear.state.WearState.clearance_profile`)."""
    cos_q, sin_q = np.cos(point_angle_rad), np.sin(point_angle_rad)
    reach = np.full(direction_rad.size, np.inf)
    for j in range(direction_rad.size):
        u_x, u_y = math.cos(direction_rad[j]), math.sin(direction_rad[j])
        for k in range(point_angle_rad.size):
            radius = point_radius_m[k]
            along = radius * (cos_q[k] * u_x + sin_q[k] * u_y)
            discriminant = along * along - radius * radius + pin_radius_m * pin_radius_m
            if discriminant >= 0.0:
                s = along - math.sqrt(discriminant)
                if 0.0 <= s < reach[j]:
                    reach[j] = s
    return reach
