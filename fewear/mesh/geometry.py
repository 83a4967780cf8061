"""The bushing's geometry and its mesh settings: plain frozen dataclasses in SI units (no DOLFINx).

Every check lives in a ``__post_init__`` and raises :class:`fewear.errors.FewearInputError` naming
the value and the allowed range.
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
