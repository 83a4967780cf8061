"""A rigid cylinder pressed on an elastic flat, in the bushing's contact solver (DOLFINx, PETSc).

Model (plane strain, per unit length; forces in N are line loads times the flat's out-of-plane
length L = ``length_m``, as the bushing's are times its width):

- Flat: the rectangle of :class:`fewear.mesh.geometry.FlatGeometry`, isotropic linear elastic,
  small strain, serendipity degree 2 on the 9-node quadrilaterals of :mod:`fewear.mesh.flat`;
  the bottom clamped, u = 0, the sides free.
- Cylinder: a rigid circle of radius R whose centre c starts at the origin, above the flat's top
  y = -(R + standoff).
- Contact: :mod:`fewear.contact.solver` as it is. Its gap g = |X + u - c| - R serves a convex
  indenter on a flat as it serves the pin in the bore (the body's points lie outside the circle
  in both), with the same penalty law p = k <-g>_+, k = penalty_factor E/(1-nu^2)/h (h the
  contact zone's element length), and the same node-based (Gauss-Lobatto) quadrature.
- Load: the normal force P (N) on the cylinder along -y, its x held at 0: the solver's coupled
  Newton with the centre on the ray c = e (0, -1) (:meth:`fewear.contact.newton.ContactNewton.
  solve_on_ray`), force control of P/L; the first touch along the ray closes the standoff.
  Frictionless. The x component of the contact resultant is what the flat returns (zero on the
  symmetric mesh, to rounding): it is not balanced.

Wear: an implicit (backward Euler) Archard step of slide ds wears every node by k p ds with p at
the step's end, so the flat recedes by c p (c = k ds, m/Pa) while the contact is solved; this is
the penalty law with c in series, p = <-g>_+ / (1/k + c), g the gap to the flat at the step's
start (``solve(..., wear_compliance_m_per_Pa=c)``; :mod:`fewear.loop.flat_wear`).

Admissible loads: the contact strip must lie inside the contact zone |x| < x_c that the mesh
resolves with its contact elements. By Hertz line contact (Johnson, *Contact Mechanics*, 1985,
sec. 4.3), a = sqrt(4 P' R / (pi E*)) with E* = E/(1-nu^2) against a rigid cylinder, a reaches
x_c at P = L pi E* x_c^2 / (4 R) (:meth:`FlatContactSolver.admissible_force_N`); a solution whose
loaded nodes reach x_c is refused (:class:`FlatLoadError`).
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import replace

import numpy as np
from mpi4py import MPI

from fewear.contact.newton import ContactNotConverged, newton_settings
from fewear.contact.params import FlatContactProblem
from fewear.contact.result import ContactResult
from fewear.contact.solver import BushingContactSolver
from fewear.errors import FewearInputError
from fewear.mesh.flat import flat_mesh

PRESS_DIRECTION = np.array([0.0, -1.0])  # the cylinder's ray and the normal force's direction


class FlatLoadError(FewearInputError):
    """A normal force the flat's contact model cannot carry (see the module docstring)."""

    def __init__(self, normal_force_N: float, reason: str, admissible_N: float,
                 zone_half_width_m: float):
        self.normal_force_N = float(normal_force_N)
        self.admissible_N = admissible_N
        super().__init__(
            f"normal force = {self.normal_force_N:g} N: the flat cannot carry it: {reason}. "
            f"Allowed are forces whose contact strip stays inside the mesh's contact zone "
            f"|x| < {zone_half_width_m:g} m: P <= {admissible_N:.3g} N (Hertz line contact, "
            "a = x_c)")


def checked_normal_force(normal_force_N) -> float:
    """The normal force as a finite number >= 0 (N), else FewearInputError."""
    try:
        value = float(normal_force_N)
    except (TypeError, ValueError):
        value = math.nan
    if not (math.isfinite(value) and value >= 0.0):
        raise FewearInputError(
            f"normal force = {normal_force_N!r} N: expected a finite number >= 0")
    return value


class FlatContactSolver(BushingContactSolver):
    """The rigid cylinder on the elastic flat (module docstring): the bushing's solver on the
    flat's mesh and problem, solved with the cylinder on its ray.

    ``problem``: the :class:`FlatContactProblem`; ``comm``: MPI communicator; ``mesh_data``: an
    existing ``(mesh, cell_tags, facet_tags)`` from :func:`fewear.mesh.flat.flat_mesh` (built
    from the problem when omitted). ``bore`` holds the flat's top nodes, sorted by x.
    """

    def __init__(self, problem: FlatContactProblem, comm=MPI.COMM_WORLD, mesh_data=None):
        if mesh_data is None:
            mesh_data = flat_mesh(problem.geometry, problem.mesh, comm)
        super().__init__(problem, comm, mesh_data)

    def solve(self, normal_force_N: float, wear_compliance_m_per_Pa: float = 0.0
              ) -> ContactResult:
        """Press the cylinder on the flat with ``normal_force_N`` (N, along -y), x held at 0;
        frictionless. The result's nodes are the top's, in the order of x.

        ``wear_compliance_m_per_Pa``: c >= 0, a wear step solved implicitly (backward Euler):
        over the step every node recedes by c p (Archard: c = k ds), which puts c in series
        with the penalty law, p = <-g>_+ / (1/k + c), g the gap to the flat as it is
        (:meth:`_series_penalty`); 0, the plain contact."""
        normal = checked_normal_force(normal_force_N)
        force = normal * PRESS_DIRECTION
        self.friction.value = 0.0
        if normal == 0.0:
            return self._no_contact_result(force, 0.0)
        with self._series_penalty(wear_compliance_m_per_Pa):
            try:
                iterations = self.newton.solve_on_ray(
                    force / self.problem.out_of_plane_length_m, PRESS_DIRECTION)
            except ContactNotConverged:
                self._refuse(force, "the contact Newton found no equilibrium")
            return self._equilibrium_result(force, 0.0, iterations)

    @contextmanager
    def _series_penalty(self, compliance_m_per_Pa: float):
        """Within the ``with`` block the penalty is k' = 1 / (1/k + c) for the compliance c
        (m/Pa): in the weak form, the Newton's constants and the nodal pressures (the problem's
        penalty factor scaled by k'/k); the problem as given afterwards."""
        if not (math.isfinite(compliance_m_per_Pa) and compliance_m_per_Pa >= 0.0):
            raise FewearInputError(f"wear compliance = {compliance_m_per_Pa!r} m/Pa: expected "
                                   "a finite number >= 0")
        if compliance_m_per_Pa == 0.0:  # the plain contact, its penalty untouched to the bit
            yield
            return
        problem = self.problem
        penalty = problem.penalty_stiffness_Pa_per_m()
        series = 1.0 / (1.0 / penalty + compliance_m_per_Pa)
        self.problem = replace(problem, contact=replace(
            problem.contact, penalty_factor=problem.contact.penalty_factor * series / penalty))
        self.penalty.value = series
        self.newton.settings = newton_settings(self.problem)
        try:
            yield
        finally:
            self.problem = problem
            self.penalty.value = penalty
            self.newton.settings = newton_settings(problem)

    def _inadmissible(self, result: ContactResult, displacement: np.ndarray) -> str | None:
        """Why the solution is not admissible (its loaded nodes reach the contact zone's edge
        x_c), or None."""
        loaded = np.abs(result.x_m[result.pressure_Pa > 0.0])
        zone = self.problem.mesh.contact_zone_half_width_m
        if loaded.size and loaded.max() >= zone * (1.0 - 1e-9):
            return f"the contact strip would reach |x| = {loaded.max():.3g} m"
        return None

    def _refuse(self, force: np.ndarray, reason: str) -> None:
        """Raise :class:`FlatLoadError` for ``force`` (N); the next solve starts afresh."""
        self.newton.reset()
        raise FlatLoadError(-force[1], reason, self.admissible_force_N(force),
                            self.problem.mesh.contact_zone_half_width_m)

    def admissible_force_N(self, force_N=PRESS_DIRECTION) -> float:
        """The largest admissible normal force (N; the flat takes forces along -y only): the
        Hertz force at which the half-width a reaches the contact zone's x_c,
        L pi E* x_c^2 / (4 R) (module docstring)."""
        problem = self.problem
        x_c = problem.mesh.contact_zone_half_width_m
        return (problem.out_of_plane_length_m * math.pi * problem.material.plane_strain_modulus_Pa
                * x_c**2 / (4.0 * problem.indenter_radius_m))
