"""Input data of the contact model: plain frozen dataclasses in SI units (no DOLFINx).

``contact_problem_from_config`` turns the config sections ``[bushing]``, ``[pin]``, ``[joint]``,
``[mesh]`` and ``[contact]`` (see ``fewear/defaults/joint.toml`` and ``contact.toml``) into one
:class:`ContactProblem`, the pin in the bushing. :class:`FlatContactProblem` is a rigid cylinder
on an elastic flat. What the contact solver asks of a body beyond its mesh, both answer: the
indenter's radius, the out-of-plane length, the penalty stiffness and the
:class:`ContactSurface` (how the Newton may move the indenter along the surface). Every physical
check lives in a ``__post_init__`` and raises :class:`fewear.errors.FewearInputError` naming the
value and the allowed range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import NamedTuple

from fewear.errors import require, require_finite_positive, require_poisson_ratio
from fewear.mesh.geometry import BushingGeometry, FlatGeometry, FlatMeshSettings, MeshSettings


@dataclass(frozen=True)
class BushingMaterial:
    """Linear elastic, isotropic bushing material: Young's modulus (Pa), Poisson ratio (-)."""

    youngs_modulus_Pa: float
    poisson_ratio: float

    def __post_init__(self) -> None:
        require_finite_positive("bushing youngs_modulus_Pa", self.youngs_modulus_Pa)
        require_poisson_ratio("bushing poisson_ratio", self.poisson_ratio)

    @property
    def plane_strain_modulus_Pa(self) -> float:
        """E' = E / (1 - nu^2), the modulus of plane strain (and E* of a rigid counterpart)."""
        return self.youngs_modulus_Pa / (1.0 - self.poisson_ratio**2)


@dataclass(frozen=True)
class ContactSettings:
    """Penalty contact, Coulomb friction and Newton settings.

    - ``penalty_factor`` (-): the penalty stiffness is k = penalty_factor * E' / h (Pa/m), with
      E' = E/(1-nu^2) the plane-strain modulus and h the bore element size; the contact pressure
      is p = k <-g>_+ for a gap g (m).
    - ``friction_coefficient`` (-): Coulomb mu; the tangential traction is mu*p when friction is on.
    - ``newton_tolerance`` (-): Newton stops when the last update of the pin centre is below
      this fraction of the penetration (of the displacement: 1000 times it) and the pin is in
      force balance (:func:`fewear.contact.newton_kernels.converged`).
    - ``newton_max_iterations``: more iterations (in the contact-angle fallback) refuse the
      force (:class:`fewear.contact.admissible.ContactLoadError`).
    """

    penalty_factor: float = 100.0
    friction_coefficient: float = 0.1
    newton_tolerance: float = 1e-4
    newton_max_iterations: int = 60

    def __post_init__(self) -> None:
        require_finite_positive("contact penalty_factor", self.penalty_factor)
        μ = self.friction_coefficient
        require(
            isinstance(μ, (int, float)) and math.isfinite(μ) and 0.0 <= μ <= 2.0,
            f"friction_coefficient = {μ!r}: must lie in [0, 2]",
        )
        tol = self.newton_tolerance
        require(
            isinstance(tol, (int, float)) and math.isfinite(tol) and 0.0 < tol < 1e-3,
            f"contact newton_tolerance = {tol!r}: must lie in (0, 1e-3)",
        )
        require(
            isinstance(self.newton_max_iterations, int) and self.newton_max_iterations >= 1,
            f"contact newton_max_iterations = {self.newton_max_iterations!r}: must be a whole "
            "number >= 1",
        )


class ContactSurface(NamedTuple):
    """The contact surface as the Newton's step rules see it (:func:`fewear.contact.newton.
    pin_update`, :func:`~fewear.contact.newton.slide_limit`): its radius about the origin
    ``radius_m`` (m), the element size along it ``element_size_m`` (m) and the angle between
    neighbouring nodes about the origin ``node_spacing_rad``. A move of the indenter along the
    surface by more than one node spacing is a turn about the origin, and one step turns it by
    at most h / radius; a straight surface has radius and node spacing inf (moves along it are
    translations, by at most h per step)."""

    radius_m: float
    element_size_m: float
    node_spacing_rad: float


@dataclass(frozen=True)
class ContactProblem:
    """Everything the contact solver needs: geometry, material, mesh and contact settings."""

    geometry: BushingGeometry
    material: BushingMaterial
    mesh: MeshSettings
    contact: ContactSettings

    def penalty_stiffness_Pa_per_m(self) -> float:
        """k = penalty_factor * E/(1-nu^2) / h_bore (Pa/m)."""
        return (
            self.contact.penalty_factor
            * self.material.plane_strain_modulus_Pa
            / self.mesh.bore_element_size_m
        )

    @property
    def indenter_radius_m(self) -> float:
        """The rigid circle's radius: the pin's, R_p (m)."""
        return self.geometry.pin_radius_m

    @property
    def out_of_plane_length_m(self) -> float:
        """The plane-strain thickness forces are divided by: the joint width L (m)."""
        return self.geometry.width_m

    def contact_surface(self) -> ContactSurface:
        """The bore: radius R_b, element size h, 2 n_theta nodes around (two per element)."""
        elements = self.mesh.circumferential_element_count(self.geometry.inner_radius_m)
        return ContactSurface(self.geometry.inner_radius_m, self.mesh.bore_element_size_m,
                              math.pi / elements)


@dataclass(frozen=True)
class FlatContactProblem:
    """A rigid cylinder pressed on an elastic flat (:class:`FlatGeometry`, meshed by
    :mod:`fewear.mesh.flat`); ``material`` is the flat's. Checks that the mesh fits the flat."""

    geometry: FlatGeometry
    material: BushingMaterial
    mesh: FlatMeshSettings
    contact: ContactSettings

    def __post_init__(self) -> None:
        self.mesh.require_fits(self.geometry)

    def penalty_stiffness_Pa_per_m(self) -> float:
        """k = penalty_factor * E/(1-nu^2) / h with h the contact zone's element length (Pa/m)."""
        return (
            self.contact.penalty_factor
            * self.material.plane_strain_modulus_Pa
            / self.mesh.contact_element_length_m()
        )

    @property
    def indenter_radius_m(self) -> float:
        """The rigid circle's radius: the cylinder's, R (m)."""
        return self.geometry.cylinder_radius_m

    @property
    def out_of_plane_length_m(self) -> float:
        """The plane-strain thickness forces are divided by: the flat's length L (m)."""
        return self.geometry.length_m

    def contact_surface(self) -> ContactSurface:
        """The top, a straight surface: radius and node spacing infinite, elements of length
        h. The Newton's step rules then move the cylinder along the top as they find it (no
        turn about the origin, which lies only R + standoff above the top while the cylinder's
        centre stays within microns of it) by at most h per step (the frictional steps of
        :mod:`fewear.contact.flat`); pressed on its ray it has no move along the top."""
        return ContactSurface(math.inf, self.mesh.contact_element_length_m(), math.inf)


CONFIG_SECTIONS = ["bushing", "pin", "joint", "mesh", "contact"]


def contact_problem_from_config(cfg: dict) -> ContactProblem:
    """Build the :class:`ContactProblem` from ``load_config(path, CONFIG_SECTIONS)``."""
    bushing, pin, mesh, contact = cfg["bushing"], cfg["pin"], cfg["mesh"], cfg["contact"]
    return ContactProblem(
        geometry=BushingGeometry(
            inner_radius_m=bushing["inner_radius_m"],
            outer_radius_m=bushing["outer_radius_m"],
            width_m=bushing["width_m"],
            pin_radius_m=pin["radius_m"],
        ),
        material=BushingMaterial(
            youngs_modulus_Pa=bushing["youngs_modulus_Pa"],
            poisson_ratio=bushing["poisson_ratio"],
        ),
        mesh=MeshSettings(
            bore_element_size_m=mesh["bore_element_size_m"],
            radial_element_count=mesh["radial_element_count"],
            radial_grading_ratio=mesh["radial_grading_ratio"],
        ),
        contact=ContactSettings(
            penalty_factor=contact["penalty_factor"],
            friction_coefficient=cfg["joint"]["friction_coefficient"],
            newton_tolerance=contact["newton_tolerance"],
            newton_max_iterations=contact["newton_max_iterations"],
        ),
    )
