"""The bodies' geometry and mesh settings: plain frozen dataclasses in SI units (no DOLFINx).

The bushing (:class:`BushingGeometry`, :class:`MeshSettings`) and the flat under a rigid cylinder
(:class:`FlatGeometry`, :class:`FlatMeshSettings`). Every check lives in a ``__post_init__`` and
raises :class:`fewear.errors.FewearInputError` naming the value and the allowed range.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from fewear.errors import require, require_finite_positive


@dataclass(frozen=True)
class BushingGeometry:
    """The joint's geometry (m): bushing bore and outer radius, joint width, pin radius.

    The radial clearance is ``inner_radius_m - pin_radius_m`` (the paper: 0.5 mm).
    """

    inner_radius_m: float
    outer_radius_m: float
    width_m: float
    pin_radius_m: float

    def __post_init__(self) -> None:
        for name in ("inner_radius_m", "outer_radius_m", "width_m", "pin_radius_m"):
            require_finite_positive(name, getattr(self, name))
        require(
            self.pin_radius_m < self.inner_radius_m,
            f"pin radius_m = {self.pin_radius_m!r} must be smaller than the bushing "
            f"inner_radius_m = {self.inner_radius_m!r} (a clearance joint)",
        )
        require(
            self.inner_radius_m < self.outer_radius_m,
            f"bushing inner_radius_m = {self.inner_radius_m!r} must be smaller than "
            f"outer_radius_m = {self.outer_radius_m!r}",
        )

    @property
    def clearance_m(self) -> float:
        """Radial clearance c = R_b - R_p (m)."""
        return self.inner_radius_m - self.pin_radius_m


@dataclass(frozen=True)
class MeshSettings:
    """The structured O-grid of the bushing (see :mod:`fewear.mesh.bushing`).

    - ``bore_element_size_m``: element edge length along the bore (m); the number of elements
      around the circumference is 2 pi R_b / size rounded up to a multiple of 4.
    - ``radial_element_count``: elements across the wall (>= 2).
    - ``radial_grading_ratio``: radial size of the outermost over the innermost element (>= 1
      grades toward the bore, where the contact stresses are).
    """

    bore_element_size_m: float
    radial_element_count: int = 8
    radial_grading_ratio: float = 4.0

    def __post_init__(self) -> None:
        require_finite_positive("mesh bore_element_size_m", self.bore_element_size_m)
        require(
            isinstance(self.radial_element_count, int) and 2 <= self.radial_element_count <= 1000,
            f"mesh radial_element_count = {self.radial_element_count!r}: must be a whole "
            "number in [2, 1000]",
        )
        g = self.radial_grading_ratio
        require(
            isinstance(g, (int, float)) and math.isfinite(g) and 1.0 <= g <= 1000.0,
            f"mesh radial_grading_ratio = {g!r}: must lie in [1, 1000]",
        )

    def elements_around(self, inner_radius_m: float) -> int:
        """ceil(2 pi R_b / h): the elements of size h that cover the bore (before rounding)."""
        return math.ceil(2.0 * math.pi * inner_radius_m / self.bore_element_size_m - 1e-9)

    def circumferential_element_count(self, inner_radius_m: float) -> int:
        """Elements around the bore: ceil(2 pi R_b / h) rounded up to a multiple of 4 (>= 8; a
        config is refused below 16, :mod:`fewear.io.limits`)."""
        return max(8, 4 * math.ceil(self.elements_around(inner_radius_m) / 4))


@dataclass(frozen=True)
class FlatGeometry:
    """A rigid cylinder of radius ``cylinder_radius_m`` over an elastic flat (m).

    The flat is the rectangle |x| <= ``width_m``/2, ``top_y_m`` - ``height_m`` <= y <=
    ``top_y_m``, plane strain of out-of-plane length ``length_m`` (forces in N are line loads
    times it, as the bushing's joint width). The cylinder's centre starts at the origin, so the
    top surface lies at y = -(R + ``standoff_m``): a small positive gap the first touch closes.
    """

    cylinder_radius_m: float
    width_m: float
    height_m: float
    length_m: float
    standoff_m: float

    def __post_init__(self) -> None:
        for name in ("cylinder_radius_m", "width_m", "height_m", "length_m", "standoff_m"):
            require_finite_positive(f"flat {name}", getattr(self, name))
        require(
            self.standoff_m < self.cylinder_radius_m,
            f"flat standoff_m = {self.standoff_m!r}: must be smaller than the cylinder_radius_m "
            f"= {self.cylinder_radius_m!r} (a small gap between cylinder and flat)",
        )

    @property
    def top_y_m(self) -> float:
        """y of the flat's top surface, -(R + standoff) (m)."""
        return -(self.cylinder_radius_m + self.standoff_m)


@dataclass(frozen=True)
class FlatMeshSettings:
    """The structured mesh of the flat (see :mod:`fewear.mesh.flat`).

    - ``contact_element_size_m``: largest element edge along the top over the contact zone (m);
      the zone holds :meth:`contact_element_count` equal elements.
    - ``contact_zone_half_width_m``: the zone |x| < x_c of these elements (m), which must hold
      the contact strip.
    - ``side_element_count``: elements along the top on each side of the zone (>= 1), graded
      from the contact element size outward.
    - ``depth_element_count``: elements through the height (>= 2), graded from the contact
      element size at the top downward.
    """

    contact_element_size_m: float
    contact_zone_half_width_m: float
    side_element_count: int = 16
    depth_element_count: int = 24

    def __post_init__(self) -> None:
        require_finite_positive("flat mesh contact_element_size_m", self.contact_element_size_m)
        require_finite_positive("flat mesh contact_zone_half_width_m",
                                self.contact_zone_half_width_m)
        for name, smallest in (("side_element_count", 1), ("depth_element_count", 2)):
            count = getattr(self, name)
            require(
                isinstance(count, int) and smallest <= count <= 1000,
                f"flat mesh {name} = {count!r}: must be a whole number in [{smallest}, 1000]",
            )
        self._require_bounded_size()

    def _require_bounded_size(self) -> None:
        """At most :data:`fewear.io.limits.MAX_FLAT_MESH_CELLS` quadrilaterals, checked before
        any meshing: the message gives the estimated cells and memory, and the bound."""
        from fewear.io.limits import MAX_FLAT_MESH_CELLS, flat_mesh_memory_bytes, memory

        cells = ((self.contact_element_count() + 2 * self.side_element_count)
                 * self.depth_element_count)
        largest_along = 2 * math.floor(
            (MAX_FLAT_MESH_CELLS / self.depth_element_count - 2 * self.side_element_count) / 2)
        smallest_size = (f"contact_element_size_m >= "
                         f"{2.0 * self.contact_zone_half_width_m / largest_along * 1.001:.3g} m"
                         if largest_along >= 2 else "fewer side or depth elements")
        require(
            cells <= MAX_FLAT_MESH_CELLS,
            f"flat mesh contact_element_size_m = {self.contact_element_size_m!r} m over "
            f"contact_zone_half_width_m = {self.contact_zone_half_width_m!r} m, with "
            f"side_element_count = {self.side_element_count} and depth_element_count = "
            f"{self.depth_element_count}, makes a mesh of about {cells:,.0f} quadrilaterals "
            f"(about {memory(flat_mesh_memory_bytes(cells))} of memory to solve); expected at "
            f"most {MAX_FLAT_MESH_CELLS:,} quadrilaterals (here: {smallest_size})",
        )

    def contact_element_count(self) -> int:
        """Elements over the zone, 2 x_c / size rounded up to an even number (x = 0 a node)."""
        per_half = self.contact_zone_half_width_m / self.contact_element_size_m
        return 2 * math.ceil(per_half - 1e-9)

    def contact_element_length_m(self) -> float:
        """The edge length of the zone's elements, 2 x_c / count (m)."""
        return 2.0 * self.contact_zone_half_width_m / self.contact_element_count()

    def require_fits(self, geometry: FlatGeometry) -> None:
        """The zone and the graded elements must fit in the flat, else FewearInputError: x_c
        below W/4 (the zone widens to the middle of each half at the bottom), and the side and
        depth elements, each at least the contact element long, within W/2 - x_c and H."""
        x_c, size = self.contact_zone_half_width_m, self.contact_element_length_m()
        require(
            x_c < 0.25 * geometry.width_m,
            f"flat mesh contact_zone_half_width_m = {x_c!r}: must be below a quarter of the "
            f"flat width_m = {geometry.width_m!r}",
        )
        require(
            self.side_element_count * size < 0.5 * geometry.width_m - x_c,
            f"flat mesh side_element_count = {self.side_element_count!r} elements of at least "
            f"{size:.3g} m do not fit in the {0.5 * geometry.width_m - x_c:.3g} m beside the "
            "contact zone: fewer elements or a smaller contact_element_size_m",
        )
        require(
            self.depth_element_count * size < geometry.height_m,
            f"flat mesh depth_element_count = {self.depth_element_count!r} elements of at least "
            f"{size:.3g} m do not fit in the height_m = {geometry.height_m!r}: fewer elements or "
            "a smaller contact_element_size_m",
        )
