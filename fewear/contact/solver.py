"""The bushing contact model: a rigid pin pressed into a linear elastic bushing (DOLFINx, PETSc).

Model (plane strain, per unit thickness; forces are reported in N by multiplying by the joint width
L = ``width_m``, i.e. the bushing is a plane-strain slab of thickness L):

- Bushing: the annulus R_b <= |X| <= R_o, isotropic linear elastic, small strain, displacement u in
  serendipity degree 2 on quadrilaterals (the paper's 8-node element) over a second-order
  (9-node) geometry; the outer surface is clamped, u = 0.
- Pin: a rigid circle of radius R_p whose centre c (the pilot point) is the second unknown; the
  joint force F (N) acts on the pin (force control, as in the seed paper).
- Contact: penalty law on the bore Gamma_b. At a bore point X the deformed position is X + u(X),
  the gap g = |X + u - c| - R_p (m) and the normal n = (X + u - c)/|X + u - c|; the pressure is
  p = k <-g>_+ (Pa) with k = penalty_factor * E/(1-nu^2) / h_bore (Pa/m, see ContactProblem).
  With friction, the pin also drags the bore with the Coulomb traction mu p t, t = (-n_y, n_x), in
  the direction of the pin's rotation increment (opposing the bore's sliding relative to the pin);
  without a rotation increment there is no sliding and no friction traction.

Equations (the stationarity of the penalty potential plus the friction term):

    a(u, v) - int_Gamma_b T . v ds = 0         for all v vanishing on the outer surface,
    L int_Gamma_b T ds = F,                     T = p (n + mu s t),  s = sign(rotation),

a(u, v) = int sigma(u) : eps(v) dx (plane strain). The second line is the pin's equilibrium: the
resultant of the contact tractions on the bore equals the joint force. DOLFINx 0.5 has no Real
space, so the two pin unknowns border the displacement system; each Newton step solves

    [K   B] [du]   [-r_u]      K = K_el + J,  B = -J E,  C^T = -E^T J,  D = E^T J E,
    [C^T D] [dc] = [-r_c]      E = the two uniform unit displacement fields,

by one LU factorisation of K (MUMPS) and a 2x2 Schur complement (J is the contact Jacobian; since
the contact terms depend on u - c only, its derivatives in c follow from J applied to E). The
contact integral uses the 3-point Gauss-Lobatto (Simpson) rule on each bore facet, whose points are
the Q8 nodes of the facet (vertices and edge midpoint): a node-based penalty. (Gauss points, in
contrast, over-constrain the quadratic edge under a stiff penalty and make the nodal gaps oscillate
at the scale of the penetration.)

Nodal pressures: at each bore node of the Q8 elements (vertices and edge midpoints) the penalty law
is evaluated with the displacement evaluated at the node, p_a = k <R_p - |X_a + u(X_a) - c|>_+.
Since the nodes are the quadrature points, these are exactly the pressures whose weighted sum
(weights |dx/ds| (1/6, 2/3, 1/6) per facet) is the resultant that balances the force.

F = 0 exactly: no contact; the pin is returned centred (c = 0), u = 0, zero pressure.

Newton: semi-smooth (the active set follows the iterates), warm-started from the previous solve
(its pin centre turned onto the new contact direction); a cold start places the pin along the
expected contact direction at first touch plus a penetration that brings +-3 elements into contact.
Globalisation: the pin's tangential update is applied as a turn about the bushing centre (it
slides around the bore), by at most one bore element per step; a step never loses all contact;
Armijo backtracking on the penalty potential (frictionless); a step cap that halves when the
active set alternates (:class:`NewtonControl`, which also holds the stopping test).
When only a few nodes carry the load (light loads: the pin rests on one or two nodes) the pin's
sliding mode is nearly free within a fixed active set and this coupled iteration may not settle;
after ``COUPLED_ITERATIONS`` (or a persistent alternation) :func:`solve_by_contact_angle` takes
over: the pin angle becomes an outer unknown found by bracketing, each inner problem (pin on a
fixed ray) being a well-posed Newton problem. ``newton_iterations`` counts all iterations.

Forms are compiled once per mesh; load, pin centre, penalty and friction are ``fem.Constant``s.
After the bore has been moved (``mesh.geometry.x`` written, ALE), call :meth:`update_geometry`.
Under MPI every rank gets the same gathered bore-node arrays (duplicates removed, sorted by angle).
"""

from __future__ import annotations

import math

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from fewear.contact.params import ContactProblem
from fewear.contact.result import ContactResult
from fewear.errors import FewearInputError
from fewear.mesh.bore import BoreNodes
from fewear.mesh.bushing import BORE_TAG, OUTER_TAG, bushing_mesh

# The contact integral's quadrature: 3-point Gauss-Lobatto (Simpson) on each bore facet, whose
# points are the facet's Q8 nodes (two vertices and the edge midpoint, weights 1/6, 1/6, 2/3).
CONTACT_QUADRATURE = {"quadrature_degree": 3, "quadrature_rule": "GLL"}

# Newton starts from the previous solution when the force turned by less than this (rad).
WARM_START_MAX_ANGLE_RAD = math.radians(20.0)

# Relative force residual of the pin at which Newton may stop (see NewtonControl).
FORCE_TOLERANCE = 1e-10

# Iterations of the coupled Newton on (u, c) before the fallback on the pin angle takes over.
COUPLED_ITERATIONS = 12
# ... or as soon as its step cap against active-set alternation has fallen below this.
CYCLE_CAP = 0.2


def checked_force(force_N) -> np.ndarray:
    """The joint force as a finite (2,) array (N), else FewearInputError."""
    force = np.asarray(force_N, dtype=float).reshape(-1)
    if force.shape != (2,) or not np.all(np.isfinite(force)):
        raise FewearInputError(f"force = {force_N!r} N: expected two finite numbers FX FY")
    return force


def checked_rotation(rotation_increment_rad: float) -> float:
    value = float(rotation_increment_rad)
    if not math.isfinite(value):
        raise FewearInputError(
            f"rotation increment = {rotation_increment_rad!r} rad: expected a finite number"
        )
    return value


def nodal_result(problem: ContactProblem, points: np.ndarray, angles: np.ndarray,
                 nodal_displacement: np.ndarray, pin_centre: np.ndarray, force: np.ndarray,
                 resultant: np.ndarray, normal: np.ndarray, rotation: float,
                 iterations: int) -> ContactResult:
    """Evaluate the penalty law at the bore nodes and pack the :class:`ContactResult`."""
    deformed = points + nodal_displacement - pin_centre
    gap = np.hypot(deformed[:, 0], deformed[:, 1]) - problem.geometry.pin_radius_m
    pressure = problem.penalty_stiffness_Pa_per_m() * np.maximum(-gap, 0.0)
    slip = np.where(pressure > 0.0, problem.geometry.pin_radius_m * abs(rotation), 0.0)
    return ContactResult(
        angle_rad=angles.copy(), x_m=points[:, 0].copy(), y_m=points[:, 1].copy(),
        pressure_Pa=pressure, gap_m=gap, slip_m=slip, pin_centre_m=np.array(pin_centre, float),
        applied_force_N=np.array(force, float), resultant_force_N=np.array(resultant, float),
        newton_iterations=int(iterations), normal_force_N=np.array(normal, float),
    )


def first_touch_centre(points: np.ndarray, centre: np.ndarray, direction: np.ndarray,
                       pin_radius: float) -> np.ndarray:
    """Move the pin from ``centre`` along ``direction`` until its circle first meets ``points``.

    For a point q (relative to the centre) outside the circle, |q - s d| = R_p at
    s = q.d - sqrt((q.d)^2 - |q|^2 + R_p^2); the smallest such s over the points is the touch.
    """
    q = points - centre
    qd = q @ direction
    disc = qd**2 - np.einsum("ij,ij->i", q, q) + pin_radius**2
    s = np.where(disc >= 0.0, qd - np.sqrt(np.maximum(disc, 0.0)), np.inf)
    s = s[s >= 0.0]
    return centre + (s.min() if s.size else 0.0) * direction


class NewtonControl:
    """The stopping test and the cap on the step against active-set cycling (both paths).

    Converged when the Newton update of the pin centre is below ``newton_tolerance`` times the
    largest penetration or 64 rounding units of R_p (the level at which gaps are computed), the
    largest displacement update below 1000 ``newton_tolerance`` times the largest displacement
    (the LU solves of the penalty-stiffened system are not more accurate) or the same rounding
    level, and either the pin's force residual before the update was below
    ``FORCE_TOLERANCE`` |F| (the pin is in balance) or the pin update is at 8 rounding units
    (the residual is rounding noise: light loads on fine meshes).
    Semi-smooth Newton can alternate between two active sets around a node that is just entering
    contact; when the active set (measured by its length) returns to the one of two iterations
    before, the step cap is halved, which turns the alternation into a converging bisection; it
    is lifted again as soon as the active set stays the same (full Newton steps converge then).
    """

    def __init__(self, settings, pin_radius_m: float):
        self.tolerance = settings.newton_tolerance
        self.floor = 64.0 * np.finfo(float).eps * pin_radius_m
        self.history: list[float] = []
        self.cap = 1.0

    def step_cap(self, active: float) -> float:
        if len(self.history) >= 2 and active == self.history[-2] != self.history[-1]:
            self.cap *= 0.5
        elif self.history and active == self.history[-1]:
            self.cap = 1.0
        self.history.append(active)
        return self.cap

    def converged(self, pin_update: float, displacement_update: float, penetration: float,
                  displacement: float, force_residual: float) -> bool:
        """``force_residual``: |pin residual| / |F/L| before the update (-)."""
        small = (pin_update <= max(self.tolerance * penetration, self.floor)
                 and displacement_update <= max(1e3 * self.tolerance * displacement, self.floor))
        return small and (force_residual <= FORCE_TOLERANCE or pin_update <= self.floor / 8.0)


def unit(angle: float) -> np.ndarray:
    return np.array([math.cos(angle), math.sin(angle)])


def polar_update(centre: np.ndarray, dc: np.ndarray) -> np.ndarray:
    """The pin centre after the Newton update dc, its tangential part applied as a turn about
    the bushing centre: c' = (|c| + dc.e_r) e_r turned by (dc.e_t)/|c|. The pin then slides
    around the bore instead of along a tangent, which would change its radial position by
    (dc.e_t)^2 / (2|c|), far more than the penetrations; it equals c + dc to second order."""
    radius = float(np.linalg.norm(centre))
    if radius == 0.0:
        return centre + dc
    radial = centre / radius
    tangential = radial[0] * dc[1] - radial[1] * dc[0]
    return (radius + float(radial @ dc)) * unit(math.atan2(radial[1], radial[0])
                                               + tangential / radius)


def slide_limit(centre: np.ndarray, dc: np.ndarray, problem: ContactProblem) -> float:
    """Step factor that lets the pin turn by at most one bore element, h / R_b, per step."""
    radius = float(np.linalg.norm(centre))
    if radius == 0.0:
        return 1.0
    tangential = abs(centre[0] * dc[1] - centre[1] * dc[0]) / radius
    limit = radius * problem.mesh.bore_element_size_m / problem.geometry.inner_radius_m
    return min(1.0, limit / tangential) if tangential > 0.0 else 1.0


def solve_by_contact_angle(inner, pin_residual, direction: np.ndarray, load: np.ndarray,
                           max_iterations: int) -> int:
    """The fallback when the coupled Newton cycles: the pin angle psi as an outer unknown.

    ``inner(a)`` solves the contact with the pin centre on the ray c = e a (force control of
    the component a . F only: a Newton problem without the pin's nearly free sliding mode) and
    returns its Newton iterations; ``pin_residual()`` then gives R - F/L (N/m) for the last inner
    solution. The tangential residual tau(psi) = (R - F/L) . a_perp is continuous and grows with
    psi overall (slope about |F|/L for a rigid pin), though only piecewise between the angles
    where nodes enter contact. So: step against tau, doubling the step until tau changes sign
    (the first step is the rigid estimate -tau L/|F|, at least 1e-4 rad), then the Illinois
    variant of regula falsi on the bracket until it is 1e-12 rad wide (the pin centre to
    ~1e-15 m) or |tau| <= 1e-9 |F|/L (about the rounding level of the penalty forces). The
    state is left at the last angle evaluated (inside the final bracket). Returns the inner
    iterations.
    """
    total = 0
    tolerance = 1e-9 * float(np.linalg.norm(load))

    def tangential_residual(ψ: float) -> float:
        nonlocal total
        total += inner(unit(ψ))
        return float(pin_residual() @ unit(ψ + 0.5 * math.pi))

    ψ0 = math.atan2(direction[1], direction[0])
    τ0 = tangential_residual(ψ0)
    step = -math.copysign(max(abs(τ0) / float(np.linalg.norm(load)), 1e-4), τ0)
    iterations = 0
    while abs(τ0) > tolerance:
        ψ1 = ψ0 + step
        τ1 = tangential_residual(ψ1)
        iterations += 1
        if (τ1 > 0.0) != (τ0 > 0.0) or abs(τ1) <= tolerance:
            break
        ψ0, τ0, step = ψ1, τ1, 2.0 * step
        if abs(step) > math.pi or iterations > max_iterations:
            raise RuntimeError(f"contact angle iteration found no equilibrium (load {load} N/m)")
    else:
        return total
    ψ, τ, side = ψ1, τ1, 0
    while abs(τ) > tolerance and abs(ψ1 - ψ0) > 1e-12:
        iterations += 1
        if iterations > max_iterations:
            raise RuntimeError(f"contact angle iteration did not converge (load {load} N/m)")
        ψ = (ψ0 * τ1 - ψ1 * τ0) / (τ1 - τ0)
        τ = tangential_residual(ψ)
        if (τ > 0.0) == (τ1 > 0.0):
            ψ1, τ1 = ψ, τ
            τ0 = 0.5 * τ0 if side == 1 else τ0
            side = 1
        else:
            ψ0, τ0 = ψ, τ
            τ1 = 0.5 * τ1 if side == -1 else τ1
            side = -1
    return total


class BushingContactSolver:
    """Full Newton solve of the pin-in-bushing penalty contact (see the module docstring).

    ``problem``: the :class:`ContactProblem`; ``comm``: MPI communicator; ``mesh_data``: an
    existing ``(mesh, cell_tags, facet_tags)`` from :func:`fewear.mesh.bushing.bushing_mesh`
    (built from the problem when omitted).

    Attributes: ``mesh``, ``facet_tags``, ``V`` (the S2 vector space), ``displacement`` (u of the
    last solve), ``pin_centre_m``, ``bore`` (:class:`BoreNodes`), ``last_result``.
    """

    def __init__(self, problem: ContactProblem, comm=MPI.COMM_WORLD, mesh_data=None):
        self.problem = problem
        self.comm = comm
        if mesh_data is None:
            mesh_data = bushing_mesh(problem.geometry, problem.mesh, comm)
        self.mesh, self.cell_tags, self.facet_tags = mesh_data
        self._build_forms()
        self.bore = BoreNodes(self.mesh, self.facet_tags, comm)
        self._ksp = self._make_lu_solver()
        self.pin_centre_m = np.zeros(2)
        self._last_direction: np.ndarray | None = None
        self.last_result: ContactResult | None = None
        self.update_geometry()

    # -- set-up ------------------------------------------------------------------------------
    def _build_forms(self) -> None:
        msh, problem = self.mesh, self.problem
        self.V = fem.VectorFunctionSpace(msh, ("S", 2))
        self.displacement = fem.Function(self.V, name="displacement")
        self._du = fem.Function(self.V)
        E, ν = problem.material.youngs_modulus_Pa, problem.material.poisson_ratio
        μ_lame = E / (2.0 * (1.0 + ν))
        λ_lame = E * ν / ((1.0 + ν) * (1.0 - 2.0 * ν))

        def ε(w):
            return ufl.sym(ufl.grad(w))

        def σ(w):
            return 2.0 * μ_lame * ε(w) + λ_lame * ufl.tr(ε(w)) * ufl.Identity(2)

        trial, test = ufl.TrialFunction(self.V), ufl.TestFunction(self.V)
        self._a_elastic = fem.form(ufl.inner(σ(trial), ε(test)) * ufl.dx)
        outer = self.facet_tags.find(OUTER_TAG)
        outer_dofs = fem.locate_dofs_topological(self.V, msh.topology.dim - 1, outer)
        self._bc = fem.dirichletbc(fem.Function(self.V), outer_dofs)

        self.pin_centre = fem.Constant(msh, np.zeros(2, dtype=PETSc.ScalarType))
        self.penalty = fem.Constant(msh, PETSc.ScalarType(problem.penalty_stiffness_Pa_per_m()))
        self.pin_radius = fem.Constant(msh, PETSc.ScalarType(problem.geometry.pin_radius_m))
        self.friction = fem.Constant(msh, PETSc.ScalarType(0.0))  # mu * sign(rotation)
        ds = ufl.Measure("ds", domain=msh, subdomain_data=self.facet_tags,
                         metadata=CONTACT_QUADRATURE)
        u = self.displacement
        traction = self.contact_traction(ufl.SpatialCoordinate(msh) + u)
        residual = -ufl.inner(traction, test) * ds(BORE_TAG)
        self._r_contact = fem.form(residual)
        self._j_contact = fem.form(ufl.derivative(residual, u, trial))
        pressure = self.contact_pressure(ufl.SpatialCoordinate(msh) + u)
        normal = self._normal(ufl.SpatialCoordinate(msh) + u)
        self._normal_force = [fem.form(pressure * normal[i] * ds(BORE_TAG)) for i in range(2)]
        penetration = pressure / self.penalty
        self._penalty_energy = fem.form(0.5 * self.penalty * penetration**2 * ds(BORE_TAG))
        self._contact_length = fem.form(ufl.conditional(ufl.gt(pressure, 0.0), 1.0, 0.0)
                                        * ds(BORE_TAG))

        # E_0, E_1: uniform unit displacements (kept as Functions: their PETSc vectors wrap
        # the Functions' memory)
        self._uniform_fields = []
        for i in range(2):
            field = fem.Function(self.V)
            field.interpolate(lambda x, i=i: np.vstack([np.full(x.shape[1], float(i == j))
                                                        for j in range(2)]))
            self._uniform_fields.append(field)
        self.uniform = [field.vector for field in self._uniform_fields]

        self._K_elastic = fem_petsc.create_matrix(self._a_elastic)
        self._J = fem_petsc.create_matrix(self._j_contact)
        self._r = fem_petsc.create_vector(self._r_contact)
        self._rhs = [self._r.duplicate() for _ in range(3)]
        self._sol = [self._r.duplicate() for _ in range(3)]
        self._work = [self._r.duplicate() for _ in range(4)]
        owned_size = self.V.dofmap.index_map.size_local * self.V.dofmap.index_map_bs
        bc_dofs = self._bc.dof_indices()[0]
        self._bc_local = bc_dofs[bc_dofs < owned_size]  # owned outer dofs (unrolled)

    def _normal(self, deformed):
        d = deformed - self.pin_centre
        return d / ufl.sqrt(ufl.inner(d, d))

    def contact_pressure(self, deformed):
        """UFL: p = k <R_p - |x + u - c|>_+ for the deformed position x + u (Pa)."""
        d = deformed - self.pin_centre
        penetration = self.pin_radius - ufl.sqrt(ufl.inner(d, d))
        return self.penalty * ufl.conditional(ufl.gt(penetration, 0.0), penetration, 0.0)

    def contact_traction(self, deformed):
        """UFL: T = p (n + mu s t), the traction of the pin on the bore (Pa)."""
        n = self._normal(deformed)
        t = ufl.as_vector((-n[1], n[0]))
        return self.contact_pressure(deformed) * (n + self.friction * t)

    def _make_lu_solver(self) -> PETSc.KSP:
        ksp = PETSc.KSP().create(self.comm)
        ksp.setType("preonly")
        pc = ksp.getPC()
        pc.setType("lu")
        pc.setFactorSolverType("mumps")
        return ksp

    def update_geometry(self) -> None:
        """Re-assemble the elastic stiffness and bore data after the mesh geometry changed."""
        self._K_elastic.zeroEntries()
        fem_petsc.assemble_matrix(self._K_elastic, self._a_elastic, bcs=[self._bc])
        self._K_elastic.assemble()
        self._K = self._K_elastic.duplicate(copy=True)
        self.bore.update_geometry()

    # -- solving -----------------------------------------------------------------------------
    def solve(self, force_N, rotation_increment_rad: float = 0.0,
              friction: bool = False) -> ContactResult:
        """Solve for the joint force ``force_N`` (N, on the pin, bushing frame).

        ``rotation_increment_rad``: rotation of the pin relative to the bushing in this step; it
        sets the slip R_p |rotation| of the nodes in contact and, with ``friction``, the direction
        of the Coulomb traction mu p.
        """
        force = checked_force(force_N)
        rotation = checked_rotation(rotation_increment_rad)
        μs = self.problem.contact.friction_coefficient * np.sign(rotation) if friction else 0.0
        self.friction.value = μs
        if not np.any(force):
            return self._no_contact_result(force, rotation)
        iterations = self._newton(force)
        self.last_result = self._result(force, rotation, iterations)
        return self.last_result

    def _no_contact_result(self, force, rotation) -> ContactResult:
        self.displacement.x.array[:] = 0.0
        self.pin_centre_m = np.zeros(2)
        self.pin_centre.value = self.pin_centre_m
        self._last_direction = None
        zeros = np.zeros((self.bore.points.shape[0], 2))
        self.last_result = nodal_result(
            self.problem, self.bore.points, self.bore.angles, zeros, self.pin_centre_m, force,
            np.zeros(2), np.zeros(2), rotation, 0)
        return self.last_result

    def contact_direction(self, force: np.ndarray) -> np.ndarray:
        """Expected direction of the contact arc's centre: F turned by -atan(mu s), since the
        traction p (n + mu s t) of a narrow arc around n has the direction of n turned by
        atan(mu s)."""
        φ = math.atan2(force[1], force[0]) - math.atan(float(self.friction.value))
        return np.array([math.cos(φ), math.sin(φ)])

    def _cold_start(self, direction: np.ndarray) -> None:
        """u = 0; the pin along ``direction`` at first touch of the bore plus the penetration
        delta_0 = c theta_0^2 / 2 that puts a rigid bore in contact over +-theta_0 = +-3 elements
        (so that the tangential balance of the pin is well posed from the first step)."""
        self.displacement.x.array[:] = 0.0
        geometry = self.problem.geometry
        touch = first_touch_centre(self.bore.points, np.zeros(2), direction, geometry.pin_radius_m)
        θ0 = 3.0 * self.problem.mesh.bore_element_size_m / geometry.inner_radius_m
        self.pin_centre_m = touch + 0.5 * geometry.clearance_m * θ0**2 * direction

    def _start(self, direction: np.ndarray) -> None:
        """Initial guess: the last solution with its pin centre turned onto ``direction`` when
        the last solve was in contact within ``WARM_START_MAX_ANGLE_RAD``, else a cold start."""
        last = self._last_direction
        if last is None:
            self._cold_start(direction)
            return
        turn = math.atan2(last[0] * direction[1] - last[1] * direction[0], last @ direction)
        if abs(turn) > WARM_START_MAX_ANGLE_RAD:
            self._cold_start(direction)
            return
        rotation = np.array([[math.cos(turn), -math.sin(turn)], [math.sin(turn), math.cos(turn)]])
        self.pin_centre_m = rotation @ self.pin_centre_m

    def _newton(self, force) -> int:
        """Coupled semi-smooth Newton on (u, c), globalised by :meth:`_line_search` and
        :class:`NewtonControl`; if its active set alternates or it needs more than
        ``COUPLED_ITERATIONS``, :func:`solve_by_contact_angle` takes over from where it stopped.
        Returns the number of Newton iterations (all inner ones included)."""
        load = force / self.problem.geometry.width_m
        settings = self.problem.contact
        direction = self.contact_direction(force)
        self._start(direction)
        iterations = self._coupled_newton(load, direction, np.eye(2), COUPLED_ITERATIONS)
        if iterations is None:

            def inner(a):
                self.pin_centre_m = max(a @ self.pin_centre_m, 0.0) * a
                count = self._coupled_newton(load, a, a[:, None], settings.newton_max_iterations)
                if count is None:
                    raise RuntimeError(f"contact Newton did not converge for force {force} N")
                return count

            def pin_residual():
                self.pin_centre.value = self.pin_centre_m
                return self._assemble_contact(load, jacobian=False)

            iterations = COUPLED_ITERATIONS + solve_by_contact_angle(
                inner, pin_residual, direction, load, settings.newton_max_iterations)
        self._last_direction = direction
        self.pin_centre.value = self.pin_centre_m
        self._assemble_contact(load)
        return iterations

    def _coupled_newton(self, load, direction, basis, max_iterations) -> int | None:
        """Semi-smooth Newton on (u, c) with c moving in the span of ``basis`` (2, k); returns
        the iterations, or None when not converged within ``max_iterations`` or, for the free pin
        (k = 2), as soon as the active set alternates."""
        settings = self.problem.contact
        control = NewtonControl(settings, self.problem.geometry.pin_radius_m)
        for iteration in range(1, max_iterations + 1):
            self.pin_centre.value = self.pin_centre_m
            r_pin = self._assemble_contact(load)
            active = self._active_length()
            if active == 0.0:
                self._cold_start(direction)
                control = NewtonControl(settings, self.problem.geometry.pin_radius_m)
                continue
            cap = control.step_cap(active)
            if cap < CYCLE_CAP and basis.shape[1] == 2:
                return None
            du, dc = self._bordered_step(r_pin, basis)
            self._line_search(du, dc, r_pin, load, cap)
            if control.converged(np.linalg.norm(dc), du.norm(PETSc.NormType.NORM_INFINITY),
                                 self._max_penetration(),
                                 self.displacement.vector.norm(PETSc.NormType.NORM_INFINITY),
                                 np.linalg.norm(basis.T @ r_pin) / np.linalg.norm(load)):
                return iteration
        return None

    def _energy(self, load: np.ndarray) -> float:
        """Penalty potential per unit thickness (J/m):
        Pi = 1/2 u.K_el u + int 1/2 k <-g>_+^2 ds - F/L . c (its gradient is the residual)."""
        u = self.displacement.vector
        self._K_elastic.mult(u, self._rhs[2])
        penalty = self.comm.allreduce(fem.assemble_scalar(self._penalty_energy), op=MPI.SUM)
        return 0.5 * u.dot(self._rhs[2]) + penalty - float(load @ self.pin_centre_m)

    def _line_search(self, du, dc, r_pin, load, cap: float = 1.0) -> float:
        """Step length along the Newton direction (du, dc); updates u and c and returns it.

        The pin moves by :func:`polar_update`. Starts from the smaller of ``cap`` and
        :func:`slide_limit`, halves the step while the trial loses all contact, and, for a
        descent direction, backtracks (Armijo, at most 2^-6) on the penalty potential
        :meth:`_energy`. At rounding level near convergence, or with friction
        (not a potential), the first contact-keeping step is taken.
        """
        u = self.displacement
        c0 = self.pin_centre_m.copy()
        rhs = self._rhs[1]
        self._K_elastic.mult(u.vector, rhs)
        rhs.axpy(1.0, self._r)
        rhs.array_w[self._bc_local] = 0.0
        slope = rhs.dot(du) + float(r_pin @ dc)
        energy0 = self._energy(load)
        step, taken = min(cap, slide_limit(c0, dc, self.problem)), 0.0
        keeps_contact = None
        while True:
            u.vector.axpy(step - taken, du)
            u.x.scatter_forward()
            taken = step
            self.pin_centre_m = polar_update(c0, step * dc)
            self.pin_centre.value = self.pin_centre_m
            if step < 2.0**-10:
                return step
            if self._active_length() == 0.0:
                step *= 0.5
                continue
            if keeps_contact is None:
                keeps_contact = step
            if slope >= 0.0 or step < keeps_contact * 2.0**-6:
                break
            if self._energy(load) <= energy0 + 1e-4 * step * slope:
                return step
            step *= 0.5
        u.vector.axpy(keeps_contact - taken, du)
        u.x.scatter_forward()
        self.pin_centre_m = polar_update(c0, keeps_contact * dc)
        self.pin_centre.value = self.pin_centre_m
        return keeps_contact

    def _assemble_contact(self, load: np.ndarray, jacobian: bool = True) -> np.ndarray:
        """Assemble r (contact residual) and, if asked, J; return the pin residual
        r_c = -E^T r - F/L (N/m).

        Leaves J E_i in ``_work[i]`` and J^T E_i in ``_work[2 + i]``.
        """
        r, J = self._r, self._J
        with r.localForm() as local:
            local.set(0.0)
        fem_petsc.assemble_vector(r, self._r_contact)
        r.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        pin_residual = np.array([-self.uniform[i].dot(r) for i in range(2)]) - load
        if not jacobian:
            return pin_residual
        J.zeroEntries()
        fem_petsc.assemble_matrix(J, self._j_contact)
        J.assemble()
        for i in range(2):
            J.mult(self.uniform[i], self._work[i])
            J.multTranspose(self.uniform[i], self._work[2 + i])
        return pin_residual

    def _active_length(self) -> float:
        """Sum of the quadrature weights of the bore points in contact (m); it changes with the
        active set and is 0 without contact."""
        return self.comm.allreduce(fem.assemble_scalar(self._contact_length), op=MPI.SUM)

    def _max_penetration(self) -> float:
        deformed = self.bore.points + self.nodal_displacement() - self.pin_centre_m
        gap = np.hypot(deformed[:, 0], deformed[:, 1]) - self.problem.geometry.pin_radius_m
        return float(max(-gap.min(), 0.0))

    def _bordered_step(self, r_pin: np.ndarray, basis: np.ndarray):
        """Newton direction (du, dc) of the bordered system by the Schur complement on the pin
        block (see the module docstring), with dc = basis dz restricted to the span of ``basis``
        (2, k) and the pin equations projected on it; needs ``_assemble_contact`` just before."""
        K = self._K
        self._K_elastic.copy(K, structure=PETSc.Mat.Structure.SAME_NONZERO_PATTERN)
        K.axpy(1.0, self._J, structure=PETSc.Mat.Structure.SUBSET_NONZERO_PATTERN)
        self._ksp.setOperators(K)
        rhs = self._rhs
        self._K_elastic.mult(self.displacement.vector, rhs[0])
        rhs[0].axpy(1.0, self._r)
        rhs[0].scale(-1.0)
        for i in range(2):
            self._work[i].copy(rhs[1 + i])
            rhs[1 + i].scale(-1.0)  # B_i = -J E_i
        for vec in rhs:
            vec.array_w[self._bc_local] = 0.0
        for b, x in zip(rhs, self._sol):
            self._ksp.solve(b, x)
        y0, Y = self._sol[0], self._sol[1:]
        D = np.array([[self.uniform[i].dot(self._work[j]) for j in range(2)] for i in range(2)])
        S = D + np.array([[self._work[2 + i].dot(Y[j]) for j in range(2)] for i in range(2)])
        rhs_c = -r_pin + np.array([self._work[2 + i].dot(y0) for i in range(2)])
        dc = basis @ np.linalg.solve(basis.T @ S @ basis, basis.T @ rhs_c)
        du = self._du.vector
        y0.copy(du)
        du.axpy(-dc[0], Y[0])
        du.axpy(-dc[1], Y[1])
        return du, dc

    # -- output ------------------------------------------------------------------------------
    def nodal_displacement(self) -> np.ndarray:
        """u at the gathered bore nodes (n, 2), by evaluating the S2 field (m)."""
        points = np.zeros((self.bore.local_nodes.size, 3))
        points[:, :2] = self.mesh.geometry.x[self.bore.local_nodes, :2]
        values = np.zeros((points.shape[0], 2))
        if points.shape[0]:  # a rank may own no part of the bore
            values = self.displacement.eval(points, self.bore.local_node_cells).reshape(-1, 2)
        return self.bore.gather(values)

    def _result(self, force, rotation, iterations) -> ContactResult:
        L = self.problem.geometry.width_m
        resultant = L * np.array([-self.uniform[i].dot(self._r) for i in range(2)])  # E^T r
        normal = L * np.array([self.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)
                               for form in self._normal_force])
        return nodal_result(self.problem, self.bore.points, self.bore.angles,
                            self.nodal_displacement(), self.pin_centre_m, force, resultant,
                            normal, rotation, iterations)

    def pressure_function(self) -> fem.Function:
        """The penalty pressure p = k <R_p - |x + u - c|>_+ interpolated at the nodes of the
        9-node geometry (a degree-2 Lagrange scalar, writable to XDMF with the mesh); on the bore
        nodes it equals the result's nodal pressures."""
        space = fem.FunctionSpace(self.mesh, ("Q", 2))
        pressure = fem.Function(space, name="contact_pressure_Pa")
        expr = self.contact_pressure(ufl.SpatialCoordinate(self.mesh) + self.displacement)
        pressure.interpolate(fem.Expression(expr, space.element.interpolation_points()))
        return pressure

    def displacement_function(self) -> fem.Function:
        """The displacement interpolated into the degree-2 Lagrange vector space (XDMF-ready)."""
        space = fem.VectorFunctionSpace(self.mesh, ("Q", 2))
        out = fem.Function(space, name="displacement_m")
        out.interpolate(self.displacement)
        return out

