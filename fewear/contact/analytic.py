"""Analytic contact of a rigid pin in the bore of an elastic bushing (NumPy only).

Two limits that bracket the FE contact of :mod:`fewear.contact.solver`: Hertz line contact of a
cylinder in a hole at small loads (Johnson, *Contact Mechanics*, 1985, ch. 4), and the cosine law
p(theta) = 2F/(pi R_b L) cos(theta) of conformal contact (Persson 1964; Ciavarella & Decuzzi,
Int. J. Solids Struct. 38 (2001) 4507-4523). The pin is rigid: 1/E* = (1 - nu_b^2)/E_b.
Method notes: docs/contact.md.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError


def plane_strain_contact_modulus_Pa(youngs_modulus_Pa: float, poisson_ratio: float) -> float:
    """E* of an elastic body against a rigid one: 1/E* = (1 - nu^2)/E (Johnson 1985, ch. 4)."""
    return youngs_modulus_Pa / (1.0 - poisson_ratio**2)


def internal_relative_radius_m(bore_radius_m: float, pin_radius_m: float) -> float:
    """Relative radius of a pin in a hole: R = R_b R_p/(R_b - R_p) (Johnson 1985, ch. 4)."""
    if not 0.0 < pin_radius_m < bore_radius_m:
        raise FewearInputError(
            f"pin radius {pin_radius_m} m must be positive and smaller than the bore radius "
            f"{bore_radius_m} m"
        )
    return bore_radius_m * pin_radius_m / (bore_radius_m - pin_radius_m)


@dataclass(frozen=True)
class HertzLineContact:
    """Hertz's two-dimensional contact of a rigid pin in an elastic bore (Johnson 1985, ch. 4).

    With P = F/L (N/m), R = R_b R_p/(R_b - R_p) and 1/E* = (1 - nu_b^2)/E_b:

    - half-width of the contact strip  a = sqrt(4 P R/(pi E*))
    - peak pressure                    p0 = 2P/(pi a) = sqrt(P E*/(pi R))
    - pressure                         p(x) = p0 sqrt(1 - x^2/a^2), |x| <= a
    - contact half-angle on the bore   a/R_b (valid while a << R_b: the small-load limit)

    Only pressures, widths and angles are given: in two dimensions the approach of the bodies
    depends on their size (logarithmic terms), so it is not a property of the contact alone.
    """

    force_N: float
    width_m: float
    bore_radius_m: float
    pin_radius_m: float
    youngs_modulus_Pa: float
    poisson_ratio: float

    def __post_init__(self) -> None:
        checks = {
            "force_N": self.force_N >= 0.0,
            "width_m": self.width_m > 0.0,
            "youngs_modulus_Pa": self.youngs_modulus_Pa > 0.0,
            "poisson_ratio": -1.0 < self.poisson_ratio < 0.5,
        }
        for name, ok in checks.items():
            value = getattr(self, name)
            if not (ok and math.isfinite(value)):
                raise FewearInputError(f"Hertz contact: {name} = {value!r} is out of range")
        internal_relative_radius_m(self.bore_radius_m, self.pin_radius_m)

    @property
    def line_load_N_per_m(self) -> float:
        """P = F/L (N/m)."""
        return self.force_N / self.width_m

    @property
    def contact_modulus_Pa(self) -> float:
        """E* with a rigid pin (Pa)."""
        return plane_strain_contact_modulus_Pa(self.youngs_modulus_Pa, self.poisson_ratio)

    @property
    def relative_radius_m(self) -> float:
        """R = R_b R_p/(R_b - R_p) (m)."""
        return internal_relative_radius_m(self.bore_radius_m, self.pin_radius_m)

    @property
    def half_width_m(self) -> float:
        """a = sqrt(4 P R/(pi E*)) (m)."""
        return math.sqrt(
            4.0 * self.line_load_N_per_m * self.relative_radius_m
            / (math.pi * self.contact_modulus_Pa)
        )

    @property
    def peak_pressure_Pa(self) -> float:
        """p0 = sqrt(P E*/(pi R)) (Pa)."""
        return math.sqrt(
            self.line_load_N_per_m * self.contact_modulus_Pa / (math.pi * self.relative_radius_m)
        )

    @property
    def contact_half_angle_rad(self) -> float:
        """a/R_b (rad): the arc of the bore covered by the Hertz strip, each side of the load."""
        return self.half_width_m / self.bore_radius_m

    def pressure_Pa(self, x_m: np.ndarray) -> np.ndarray:
        """p(x) = p0 sqrt(1 - x^2/a^2) inside the strip, 0 outside (x from the centre, m)."""
        x_m = np.asarray(x_m, dtype=float)
        a = self.half_width_m
        if a == 0.0:
            return np.zeros_like(x_m)
        return self.peak_pressure_Pa * np.sqrt(np.clip(1.0 - (x_m / a) ** 2, 0.0, None))

    def pressure_on_bore_Pa(self, angle_rad: np.ndarray, load_angle_rad: float) -> np.ndarray:
        """p on the bore at ``angle_rad``, with x = R_b (theta - theta_load) the arc length (Pa)."""
        x_m = self.bore_radius_m * wrap_angle_rad(np.asarray(angle_rad) - load_angle_rad)
        return self.pressure_Pa(x_m)


def cosine_law_pressure_Pa(
    angle_rad: np.ndarray, load_angle_rad: float, force_N: float, radius_m: float, width_m: float
) -> np.ndarray:
    """Conformal (zero-clearance) limit: p = 2F/(pi R L) cos(theta - theta_load) on the loaded half.

    Its resultant over |theta - theta_load| <= pi/2 is F (the integral of cos^2 is pi/2); the
    contact half-angle is 90 degrees. Persson (1964); Ciavarella & Decuzzi, IJSS 38 (2001), part I.
    """
    relative = np.cos(wrap_angle_rad(np.asarray(angle_rad) - load_angle_rad))
    return 2.0 * force_N / (math.pi * radius_m * width_m) * np.clip(relative, 0.0, None)


def wrap_angle_rad(angle_rad: np.ndarray) -> np.ndarray:
    """Angle folded into [-pi, pi)."""
    return (np.asarray(angle_rad) + math.pi) % (2.0 * math.pi) - math.pi


def hertz_reference(problem, force_N: float) -> HertzLineContact:
    """The Hertz contact of a :class:`fewear.contact.params.ContactProblem` under |F| (N)."""
    geometry, material = problem.geometry, problem.material
    return HertzLineContact(
        force_N=float(force_N),
        width_m=geometry.width_m,
        bore_radius_m=geometry.inner_radius_m,
        pin_radius_m=geometry.pin_radius_m,
        youngs_modulus_Pa=material.youngs_modulus_Pa,
        poisson_ratio=material.poisson_ratio,
    )


@dataclass(frozen=True)
class EllipseFit:
    """Hertz ellipse p(s) = p0 sqrt(1 - (s - s0)^2/a^2) fitted to nodal pressures on the bore."""

    peak_pressure_Pa: float
    half_width_m: float
    centre_m: float


def fit_hertz_ellipse(arc_m: np.ndarray, pressure_Pa: np.ndarray) -> EllipseFit:
    """Least-squares fit of the Hertz ellipse to the nodes in contact (p > 0).

    p^2 = p0^2 - (p0/a)^2 (s - s0)^2 is a quadratic in the arc length s, so a linear least-squares
    fit of p^2 = c0 + c1 s + c2 s^2 over the loaded nodes gives s0 = -c1/(2 c2),
    p0^2 = c0 - c1^2/(4 c2) and a^2 = -p0^2/c2. Every loaded node contributes, so the half-width is
    not tied to where the discrete p > 0 zone happens to end between two nodes; the nodes next to
    the edge carry the load of their tributary length, which biases it by a fraction of a percent
    (measured in tests/contact/test_hertz.py).
    """
    arc_m = np.asarray(arc_m, dtype=float)
    pressure_Pa = np.asarray(pressure_Pa, dtype=float)
    loaded = pressure_Pa > 0.0
    if np.count_nonzero(loaded) < 3:
        raise ValueError("an ellipse fit needs at least 3 loaded nodes")
    scale = np.max(pressure_Pa)
    s = arc_m[loaded]
    c2, c1, c0 = np.polyfit(s, (pressure_Pa[loaded] / scale) ** 2, 2)
    if c2 >= 0.0:
        raise ValueError("the loaded nodes do not form a pressure hump")
    centre = -c1 / (2.0 * c2)
    peak_squared = c0 - c1**2 / (4.0 * c2)
    return EllipseFit(
        peak_pressure_Pa=float(scale * math.sqrt(peak_squared)),
        half_width_m=float(math.sqrt(-peak_squared / c2)),
        centre_m=float(centre),
    )


def q8_bore_weights_m(angle_rad: np.ndarray, radius_m: float) -> np.ndarray:
    """Quadrature weights (m) of the bore nodes of an O-grid of 8-node quadrilaterals.

    The nodes, sorted by angle, alternate element vertex (even index, the first at angle 0) and
    edge midpoint; Simpson's rule on each bore edge of arc length l gives l/6 to each of its two
    vertices and 2l/3 to its midpoint (the 3-point Gauss-Lobatto rule of the solver's contact
    integral), so a vertex, shared by two edges, weighs l/3. Then sum_i w_i p_i n_i L is the
    resultant that balances the joint force.
    """
    count = np.asarray(angle_rad).size
    if count % 2:
        raise ValueError("an O-grid of 8-node quadrilaterals has an even number of bore nodes")
    edge_length_m = 2.0 * math.pi * radius_m / (count // 2)
    return np.where(np.arange(count) % 2 == 0, edge_length_m / 3.0, 2.0 * edge_length_m / 3.0)


def moment_half_width_m(arc_m: np.ndarray, pressure_Pa: np.ndarray, weights_m: np.ndarray) -> float:
    """a_m = 2 sqrt(int p s^2 ds / int p ds), the half-width of the Hertz ellipse of the same
    second moment (for p = p0 sqrt(1 - s^2/a^2): int p s^2 ds / int p ds = a^2/4).

    An integral of the field with the solver's own quadrature: every node contributes, and the
    value does not jump when the discrete edge of the contact moves from one node to the next.
    ``arc_m`` is measured from the centre of the contact.
    """
    zeroth = float(np.sum(weights_m * pressure_Pa))
    second = float(np.sum(weights_m * pressure_Pa * np.asarray(arc_m) ** 2))
    return 2.0 * math.sqrt(second / zeroth) if zeroth > 0.0 else 0.0


@dataclass(frozen=True)
class HertzComparison:
    """An FE bore field beside the Hertz solution of the same load (relative errors signed).

    - peak pressure: the largest nodal pressure (the CLI's ``max_pressure_Pa``);
    - half-width, three ways: the second-moment width (:func:`moment_half_width_m`), the Hertz
      ellipse fitted to all loaded nodes (:func:`fit_hertz_ellipse`), and R_b times the half-angle
      of the p > 0 arc with interpolated ends (``ContactResult.contact_half_angle_rad``; its ends
      sit within about half a node spacing of the last loaded node, so it converges as O(h)).
    """

    hertz: HertzLineContact
    peak_pressure_Pa: float
    moment_half_width_m: float
    fit: EllipseFit
    zone_half_width_m: float

    @property
    def peak_pressure_rel_error(self) -> float:
        return self.peak_pressure_Pa / self.hertz.peak_pressure_Pa - 1.0

    @property
    def moment_half_width_rel_error(self) -> float:
        return self.moment_half_width_m / self.hertz.half_width_m - 1.0

    @property
    def fit_half_width_rel_error(self) -> float:
        return self.fit.half_width_m / self.hertz.half_width_m - 1.0

    @property
    def zone_half_width_rel_error(self) -> float:
        return self.zone_half_width_m / self.hertz.half_width_m - 1.0


def compare_with_hertz(result, hertz: HertzLineContact) -> HertzComparison:
    """Compare a :class:`fewear.contact.result.ContactResult` on the O-grid bore with the Hertz
    strip of its load; the arc length is measured from the load direction, s = R_b (theta -
    theta_F)."""
    force_x, force_y = result.applied_force_N
    arc_m = hertz.bore_radius_m * wrap_angle_rad(result.angle_rad - math.atan2(force_y, force_x))
    weights_m = q8_bore_weights_m(result.angle_rad, hertz.bore_radius_m)
    return HertzComparison(
        hertz=hertz,
        peak_pressure_Pa=float(np.max(result.pressure_Pa)),
        moment_half_width_m=moment_half_width_m(arc_m, result.pressure_Pa, weights_m),
        fit=fit_hertz_ellipse(arc_m, result.pressure_Pa),
        zone_half_width_m=hertz.bore_radius_m * result.contact_half_angle_rad,
    )
