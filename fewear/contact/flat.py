"""A rigid cylinder pressed on an elastic flat, in the bushing's contact solver (DOLFINx, PETSc).

The flat's rectangle (plane strain, Q8, bottom clamped) under a rigid cylinder with the penalty
contact of :mod:`fewear.contact.solver`: normal load by force control along a ray, frictional
(fretting) steps under tangential force or shift with Coulomb's law by return mapping, a worn
cylinder seen through the gap, and the implicit Archard step as a wear compliance in series.
Admissible loads by Hertz line contact (Johnson, *Contact Mechanics*, 1985, sec. 4.3).
Method notes: docs/contact.md.
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import replace
from typing import NamedTuple

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.mesh import compute_midpoints
from mpi4py import MPI
from petsc4py import PETSc
from scipy import linalg

from fewear.contact.condensed import inverse_block
from fewear.contact.newton import ContactNotConverged, newton_settings, specialised
from fewear.contact.params import FlatContactProblem
from fewear.contact.result import ContactResult
from fewear.contact.solver import BushingContactSolver
from fewear.errors import FewearInputError
from fewear.mesh.flat import flat_mesh
from fewear.mesh.tags import CONTACT_TAG

PRESS_DIRECTION = np.array([0.0, -1.0])  # the cylinder's ray and the normal force's direction
BOTH_MOVES = np.eye(2)                      # force control of Q and P: the centre free
VERTICAL_MOVES = np.array([[0.0], [1.0]])   # force control of P alone: the centre's x held
HORIZONTAL_MOVES = np.array([[1.0], [0.0]])  # force control of Q alone: the centre's y held

# A frictional step that does not converge is split in two halves, at most this many times
# (:meth:`FlatContactSolver._in_halves`).
STEP_HALVINGS = 6

# The return mapping sticks up to |tau_trial| = mu p (1 + this): a node that slipped in the last
# step starts the next at |tau_trial| = mu p to rounding, and on unloading must stick; taken
# as slipping (no tangential stiffness) at the first Newton step, the step overshot into
# reverse slip and the Newton cycled (Q from 3 mu P/4 down, h = a/16).
STICK_TOLERANCE = 1e-9

# A node in contact sticks where |tau| < mu p by more than this fraction (the slipping ones have
# |tau| = mu p to rounding).
STICK_MARGIN = 1e-9


class FrictionalStep(NamedTuple):
    """One frictional step on the flat (:meth:`FlatContactSolver.solve_tangential_force`,
    :meth:`~FlatContactSolver.solve_tangential_shift`).

    ``contact``: the :class:`ContactResult`, its ``slip_m`` the step's Coulomb slip per node
    (m, the relative tangential motion of flat and cylinder less the tangential penalty's
    elastic part); ``shear_Pa``: the tangential traction tau of the cylinder on the flat along
    t = (-n_y, n_x) (Pa; +x under the cylinder); ``sticking``: the nodes in contact that stick,
    |tau| < mu p; ``tangential_force_N``: Q, the x component of the contact resultant (N)."""

    contact: ContactResult
    shear_Pa: np.ndarray
    sticking: np.ndarray
    tangential_force_N: float


class FlatLoadError(FewearInputError):
    """A normal force the flat's contact model cannot carry (see the method notes)."""

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
    """The rigid cylinder on the elastic flat (method notes): the bushing's solver on the
    flat's mesh and problem, solved with the cylinder on its ray; frictional steps after it
    (method notes).

    ``problem``: the :class:`FlatContactProblem`; ``comm``: MPI communicator; ``mesh_data``: an
    existing ``(mesh, cell_tags, facet_tags)`` from :func:`fewear.mesh.flat.flat_mesh` (built
    from the problem when omitted). ``bore`` holds the flat's top nodes, sorted by x.
    """

    def __init__(self, problem: FlatContactProblem, comm=MPI.COMM_WORLD, mesh_data=None):
        if mesh_data is None:
            mesh_data = flat_mesh(problem.geometry, problem.mesh, comm)
        super().__init__(problem, comm, mesh_data)

    # -- Coulomb friction: the forms ----------------------------------------------------------
    def _build_forms(self) -> None:
        """The bushing's forms, with the shear of :meth:`contact_traction`; its history (the
        step's start) in degree-2 Lagrange functions, whose values at the top's nodes are the
        values at the contact integral's Gauss-Lobatto points, and the centre as a constant."""
        msh = self.mesh
        self.coulomb = fem.Constant(msh, PETSc.ScalarType(0.0))  # mu in a frictional step
        self.tangential_penalty = fem.Constant(
            msh, PETSc.ScalarType(self.problem.penalty_stiffness_Pa_per_m()))
        shear_space = fem.FunctionSpace(msh, ("Q", 2))
        self.shear_before = fem.Function(shear_space, name="shear_before_Pa")
        self._shear_now = fem.Function(shear_space)
        self.displacement_before = fem.Function(fem.VectorFunctionSpace(msh, ("Q", 2)))
        self.centre_before = fem.Constant(msh, np.zeros(2, dtype=PETSc.ScalarType))
        self.frozen = fem.Constant(msh, PETSc.ScalarType(0.0))  # 1: the pressure frozen
        self.frozen_pressure = fem.Function(shear_space, name="frozen_pressure_Pa")
        self._centre_x_target_m: float | None = None  # displacement control of the centre's x
        self.last_force_N = np.zeros(2)  # (Q, -P) at the end of the last solve or step (N)
        self._loading_now = fem.Function(shear_space)
        # the cylinder's worn depth under each point of the top, at the cylinder's position
        self.cylinder_wear = fem.Function(shear_space, name="cylinder_wear_m")
        self._cylinder_profile: tuple[np.ndarray, np.ndarray] | None = None
        self._cylinder_wear_at_nodes: np.ndarray | None = None
        self._elastic_factorised = False  # K_el of this geometry factorised in _ksp
        self._covered = np.zeros(0, dtype=int)  # the top dofs (positions in _top_dofs) and
        self._covered_compliance = np.zeros((0, 0))  # their (K_el^-1) block, this geometry's
        self._reach_m = 0.0  # the largest |x| of a dof the contact coupled so far
        super()._build_forms()
        self._top_dofs, self._top_dof_abs_x_m = self._top_dofs_and_x()
        deformed = ufl.SpatialCoordinate(msh) + self.displacement
        points = shear_space.element.interpolation_points()
        self._shear_expression = fem.Expression(self.shear(deformed), points)
        self._pressure_expression = fem.Expression(self.contact_pressure(deformed), points)
        self._loading_expression = fem.Expression(self.loading_pressure(deformed), points)
        trial, bound = self._trial_shear(deformed)
        sticking = ufl.And(ufl.gt(bound, 0.0), ufl.le(abs(trial), bound * (1.0 + STICK_TOLERANCE)))
        self._stick_length = fem.form(ufl.conditional(sticking, 1.0, 0.0)
                                      * self._ds(CONTACT_TAG))

    def _top_dofs_and_x(self) -> tuple[np.ndarray, np.ndarray]:
        """The displacement's dofs on the top (sorted, unrolled) and each one's |x| (m): the
        least of its facets' midpoints' (an S2 edge dof is no point value)."""
        facets = self.facet_tags.find(CONTACT_TAG)
        midpoints = np.abs(compute_midpoints(self.mesh, self.mesh.topology.dim - 1, facets)[:, 0])
        reach = {}
        for facet, x in zip(facets, midpoints):
            for block in fem.locate_dofs_topological(self.V, self.mesh.topology.dim - 1,
                                                     np.array([facet], dtype=np.int32)):
                reach[block] = min(reach.get(block, np.inf), x)
        blocks = np.array(sorted(reach))
        dofs = np.concatenate([2 * blocks, 2 * blocks + 1])
        order = np.argsort(dofs)
        x = np.concatenate([[reach[b] for b in blocks]] * 2)
        return dofs[order].astype(PETSc.IntType), x[order]

    def contact_traction(self, deformed):
        """UFL: T = p n + tau t, the cylinder's traction on the flat (Pa): the penalty pressure
        and the shear tau of Coulomb's law (:meth:`shear`) along t = (-n_y, n_x)."""
        n = self._normal(deformed)
        return self.loading_pressure(deformed) * n + self.shear(deformed) * ufl.as_vector(
            (-n[1], n[0]))

    def contact_pressure(self, deformed):
        """UFL: the penalty pressure against the worn cylinder (:meth:`_against_worn_cylinder`)."""
        return BushingContactSolver.contact_pressure(self, self._against_worn_cylinder(deformed))

    def _normal(self, deformed):
        return BushingContactSolver._normal(self, self._against_worn_cylinder(deformed))

    def _against_worn_cylinder(self, deformed):
        """UFL: the flat's deformed point lowered by the cylinder's worn depth h_c above it
        (:meth:`set_cylinder_wear`): the gap to the worn cylinder, |x + u - c| - (R - h_c) to
        first order in h_c/R, is the gap of the lowered point to the circle."""
        return deformed - ufl.as_vector((0.0, self.cylinder_wear))

    def set_cylinder_wear(self, position_m: np.ndarray, depth_m: np.ndarray) -> None:
        """The cylinder's worn depth h_c (m, into the cylinder) at the positions s (m, along its
        bottom from below its centre, increasing), linear between them and 0 beyond; applied
        at the centre's x of every later solve (the prescribed x of a shift, 0 for
        :meth:`solve`, the step's start for a force-controlled step)."""
        self._cylinder_profile = (np.asarray(position_m, dtype=float).copy(),
                                  np.asarray(depth_m, dtype=float).copy())

    def _place_cylinder_wear(self, centre_x_m: float) -> None:
        """The cylinder's wear under the top's points with its centre at x = ``centre_x_m``."""
        if self._cylinder_profile is None:
            return
        position, depth = self._cylinder_profile
        self.cylinder_wear.interpolate(
            lambda x: np.interp(x[0] - centre_x_m, position, depth, left=0.0, right=0.0))
        self.cylinder_wear.x.scatter_forward()
        self._cylinder_wear_at_nodes = np.interp(self.bore.points[:, 0] - centre_x_m, position,
                                                 depth, left=0.0, right=0.0)

    def contact_points(self) -> np.ndarray:
        """The top's nodes lowered by the cylinder's wear above them (m;
        :meth:`_against_worn_cylinder`), so that the Newton's nodal gaps are the forms'."""
        if self._cylinder_wear_at_nodes is None:
            return self.bore.points
        return self.bore.points - np.column_stack(
            [np.zeros(self.bore.points.shape[0]), self._cylinder_wear_at_nodes])

    def _result(self, force, rotation, iterations, displacement) -> ContactResult:
        """The bushing's result; its y_m the top nodes' own (not lowered by the cylinder's
        wear)."""
        result = BushingContactSolver._result(self, force, rotation, iterations, displacement)
        return replace(result, y_m=self.bore.points[:, 1].copy())

    def loading_pressure(self, deformed):
        """UFL: the pressure p (Pa) of the traction: the penalty law's, or in an uncoupled
        frictional step (:attr:`frozen` = 1) the one frozen at its start,
        :attr:`frozen_pressure`."""
        pressure = self.contact_pressure(deformed)
        return pressure + self.frozen * (self.frozen_pressure - pressure)

    def shear(self, deformed):
        """UFL: the shear tau (Pa) by the return mapping of a tangential penalty k_t and
        Coulomb's law (Wriggers, *Computational Contact Mechanics*, 2006, sec. 5.2.2; Simo &
        Hughes, *Computational Inelasticity*, 1998, ch. 1): with ds = t . ((u - u_0) - (c - c_0))
        the tangential motion of the flat's point relative to the cylinder since the step's
        start (u_0, c_0: :attr:`displacement_before`, :attr:`centre_before`) and tau_0 the shear
        then (:attr:`shear_before`),

            tau_trial = tau_0 - k_t ds,   tau = tau_trial if |tau_trial| <= mu p (stick),
                                          else mu p sign(tau_trial) (slip).

        The cylinder dragged along +x shears the flat along +x. mu = :attr:`coulomb`, 0
        outside a frictional step: then tau = 0."""
        trial, bound = self._trial_shear(deformed)
        return ufl.conditional(ufl.le(abs(trial), bound * (1.0 + STICK_TOLERANCE)), trial,
                               ufl.conditional(ufl.gt(trial, 0.0), bound, -bound))

    def _trial_shear(self, deformed):
        """UFL: tau_trial and the bound mu p of :meth:`shear` (Pa)."""
        n = self._normal(deformed)
        t = ufl.as_vector((-n[1], n[0]))
        moved = (deformed - ufl.SpatialCoordinate(self.mesh) - self.displacement_before
                 - (self.pin_centre - self.centre_before))
        trial = self.shear_before - self.tangential_penalty * ufl.inner(t, moved)
        return trial, self.coulomb * self.loading_pressure(deformed)

    def frictionless(self) -> bool:
        """Whether the present solve is without friction (the Newton's Armijo test on the
        penalty potential, which the return mapping's slip has not)."""
        return float(self.coulomb.value) == 0.0

    def linearise(self, load: np.ndarray) -> tuple[np.ndarray, float, None]:
        """The bushing's linearisation; in a frictional step the active length (m) counts the
        sticking nodes' weights once more, so that the Newton's step cap
        (:func:`fewear.contact.newton.step_cap`) halves when the stick set alternates as it
        does when the contact set does: a node flipping between stick (tangential stiffness
        k_t) and slip (none) made the full steps overshoot in a growing cycle (h = a/16). The
        rounding level the active length sets in the stopping test is at most doubled."""
        pin_residual, active, linear = BushingContactSolver.linearise(self, load)
        if not self.frictionless():
            active += self.comm.allreduce(fem.assemble_scalar(self._stick_length), op=MPI.SUM)
        return pin_residual, active, linear

    def newton_direction(self, linear, pin_residual, load, basis):
        """The bushing's Newton direction; under displacement control of the centre's x
        (:meth:`solve_tangential_shift`) with the move to the target x prescribed: the first
        step from the last state is the linearised (stick) response to the whole move. Moving
        the centre there before the Newton instead started it with every node slipping
        (k_t |dx| > mu p already for |dx| ~ 1e-10 m), from which it cycled."""
        if self._centre_x_target_m is None:
            return self._bordered_step(pin_residual, basis)
        move = np.array([self._centre_x_target_m - self.pin_centre_m[0], 0.0])
        return self._bordered_step(pin_residual, basis, prescribed=move)

    # -- the Newton direction: the elastic stiffness factorised once per geometry -------------
    def update_geometry(self) -> None:
        """The bushing's update after the mesh moved; the elastic factorisation and the top's
        compliance (:meth:`_bordered_step`) made afresh at the next Newton step."""
        self._elastic_factorised = False
        self._covered = np.zeros(0, dtype=int)
        super().update_geometry()

    def _bordered_step(self, r_pin: np.ndarray, basis: np.ndarray,
                       prescribed: np.ndarray | None = None):
        """The bushing's Newton direction (:meth:`BushingContactSolver._bordered_step`, the same
        to rounding), its solves with K = K_el + J by the Woodbury identity on the dofs A of the
        top that the contact couples (J and the contact residual r vanish elsewhere): K_el
        factorised once per geometry, with G = (K_el^-1)_AA (MUMPS selected inverse,
        :meth:`_compliance_of`), instead of K at every Newton step. With t = (K_el^-1 b)_A,

            K^-1 b = K_el^-1 (b - P_A z),   z = (I + J_AA G)^-1 J_AA t,

        and, K_el u known, the step du = -u - K_el^-1 P_A v for a v on A: one sparse solve per
        Newton step and a dense system of the contact's dofs (a fretting cycle's steps take
        about 7 Newton steps on each geometry: docs/performance.md). On one process; on several
        ranks the bushing's."""
        if self.comm.size > 1:
            return BushingContactSolver._bordered_step(self, r_pin, basis, prescribed)
        top = self._top_dofs
        J, r = self._J.getValues(top, top), self._r.array[top]
        active = np.flatnonzero(np.any(J != 0.0, axis=0) | np.any(J != 0.0, axis=1) | (r != 0.0))
        J, r, dofs = J[np.ix_(active, active)], r[active], top[active]
        G = self._compliance_of(active)
        factors = linalg.lu_factor(np.eye(active.size) + J @ G)

        def through_contact(t):
            """(K^-1 b)_A and z from t = (K_el^-1 b)_A."""
            z = linalg.lu_solve(factors, J @ t)
            return t - G @ z, z

        u = self.displacement.x.array[:self._r.getLocalSize()]
        uniform = [field.array[dofs] for field in self.uniform]
        moved = [-(J @ e) for e in uniform]  # the right-hand sides -J E_i
        pulled = [J.T @ e for e in uniform]  # J^T E_i
        y0, z0 = through_contact(-u[dofs] - G @ r)  # K_el^-1 (K_el u + r) = u + K_el^-1 r
        Y, Z = zip(*(through_contact(G @ rhs) for rhs in moved))
        S = np.array([[pulled[i] @ Y[j] - uniform[i] @ moved[j] for j in range(2)]
                      for i in range(2)])
        rhs_c = -r_pin + np.array([pulled[i] @ y0 for i in range(2)])
        if prescribed is None:
            dc = basis @ np.linalg.solve(basis.T @ S @ basis, basis.T @ rhs_c)
        else:
            dc = prescribed + basis @ np.linalg.solve(basis.T @ S @ basis,
                                                      basis.T @ (rhs_c - S @ prescribed))
        rhs, solution = self._rhs[0], self._sol[0]
        rhs.set(0.0)
        rhs.array_w[dofs] = (r + z0 + dc[0] * (moved[0] - Z[0]) + dc[1] * (moved[1] - Z[1]))
        self._ksp.solve(rhs, solution)
        du = self._du.vector
        du.array_w[:] = -u - solution.array
        return du, dc

    def _compliance_of(self, active: np.ndarray) -> np.ndarray:
        """(K_el^-1)_AA for the top dofs at positions ``active`` of the top's, on this geometry:
        K_el factorised at the first call (its pattern's analysis kept from the geometry
        before), the block of its inverse computed for the top dofs within 1.2 times the
        contact's reach in x (and two elements), again whenever the contact outgrows them: the
        selected inverse grows with the dofs it covers (0.3 s for the whole top of the default
        block on ring, whose scar reaches 83 % of its contact zone at the end)."""
        if not self._elastic_factorised:
            self._ksp.setOperators(self._K_elastic)
            self._ksp.setUp()
            self._elastic_factorised = True
        self._reach_m = max(self._reach_m,
                           float(self._top_dof_abs_x_m[active].max(initial=0.0)))
        if not np.all(np.isin(active, self._covered)):
            reach = 1.2 * self._reach_m + 2.0 * self.problem.mesh.contact_element_size_m
            self._covered = np.flatnonzero(self._top_dof_abs_x_m <= reach)
            factor = self._ksp.getPC().getFactorMatrix()
            self._covered_compliance = inverse_block(factor, self._top_dofs[self._covered],
                                                     self.comm)
            factor.setMumpsIcntl(30, 0)  # the selected inverse's mode off: solves again
        where = np.searchsorted(self._covered, active)
        return self._covered_compliance[np.ix_(where, where)]

    @property
    def operations(self) -> type:
        """The Newton's operations: the bushing's, with the flat's :meth:`frictionless`,
        :meth:`linearise` and :meth:`newton_direction` (the bushing's specialised Newton binds
        the base class's methods and would not see these)."""
        return FlatContactSolver

    @property
    def newton_algorithm(self):
        return FLAT_NEWTON

    # -- solving -------------------------------------------------------------------------------
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
        self._place_cylinder_wear(0.0)
        if normal == 0.0:
            result = self._no_contact_result(force, 0.0)
            self._release_shear()
            return result
        with self._series_penalty(wear_compliance_m_per_Pa):
            try:
                iterations = self.newton.solve_on_ray(
                    force / self.problem.out_of_plane_length_m, PRESS_DIRECTION)
            except ContactNotConverged:
                self._refuse(force, "the contact Newton found no equilibrium")
            result = self._equilibrium_result(force, 0.0, iterations)
        self._release_shear()
        return result

    def solve_tangential_force(self, tangential_force_N: float, normal_force_N: float,
                               uncoupled: bool = False) -> FrictionalStep:
        """A frictional step to the forces (Q, -P) on the cylinder (N) from the last solve's
        state, with Coulomb's law (:meth:`shear`, mu the problem's friction coefficient) and
        the history of the steps since the last :meth:`solve`: force control of both, the
        centre free. Cattaneo-Mindlin partial slip for 0 < Q < mu P after a :meth:`solve` of
        P; Q >= mu P has no equilibrium under force control (the cylinder slides away).

        ``uncoupled``: a PROTOTYPE of the tangential problem alone. The pressure is frozen at
        the last :meth:`solve`'s (the normal traction and Coulomb's bound; the penalty law off)
        and the centre's y held, so that only Q is controlled: Mindlin's problem exactly as
        posed, the normal and tangential problems uncoupled, which elastically similar bodies
        are (Dundurs beta = 0; Johnson 1985, sec. 7.2). The rigid cylinder on the elastic
        flat has beta = (1 - 2 nu)/(2 (1 - nu)) (0.29 at nu = 0.3): coupled, Q tilts the
        pressure (its centroid measured 0.13 a behind at nu = 0.3, Q = mu P/2)."""
        force = np.array([float(tangential_force_N), -checked_normal_force(normal_force_N)])
        μ = self.problem.contact.friction_coefficient
        if not (math.isfinite(force[0]) and abs(force[0]) < μ * -force[1]):
            raise FewearInputError(
                f"tangential force = {tangential_force_N!r} N: force control needs |Q| < mu P "
                f"= {μ * -force[1]:g} N (beyond, the cylinder slides away: shift it instead)")
        basis = HORIZONTAL_MOVES if uncoupled else BOTH_MOVES
        self._place_cylinder_wear(float(self.pin_centre_m[0]))
        try:
            return self._in_halves(lambda f: self._frictional_step(f, basis, uncoupled),
                                   self.last_force_N, force, STEP_HALVINGS)
        except ContactNotConverged:
            self.newton.reset()
            raise FewearInputError(
                f"tangential force = {force[0]:g} N under P = {-force[1]:g} N: the frictional "
                "Newton found no equilibrium (force control needs Q < mu P); solve P afresh"
            ) from None

    def solve_tangential_shift(self, centre_x_m: float, normal_force_N: float,
                               wear_compliance_m_per_Pa: float = 0.0) -> FrictionalStep:
        """A frictional step with the cylinder's centre moved to x = ``centre_x_m`` (m,
        prescribed) under the normal force P (N, force control), from the last solve's state as
        :meth:`solve_tangential_force`; Q (the step's ``tangential_force_N``) is the
        reaction. The result's ``applied_force_N`` is (Q, -P).

        ``wear_compliance_m_per_Pa``: c >= 0, the step's wear solved implicitly as in
        :meth:`solve` (the penalty law with c in series; the caller moves the top by c p
        afterwards); 0, the plain contact."""
        force = np.array([0.0, -checked_normal_force(normal_force_N)])

        def shifted(centre_x_m: np.ndarray) -> FrictionalStep:
            self._centre_x_target_m = float(centre_x_m[0])
            self._place_cylinder_wear(self._centre_x_target_m)
            try:
                with self._series_penalty(wear_compliance_m_per_Pa):
                    step = self._frictional_step(force, VERTICAL_MOVES)
            finally:
                self._centre_x_target_m = None
            applied = np.array([step.tangential_force_N, force[1]])
            return step._replace(contact=replace(step.contact, applied_force_N=applied))

        try:
            return self._in_halves(shifted, self.centre_before.value[:1].copy(),
                                   np.array([float(centre_x_m)]), STEP_HALVINGS)
        except ContactNotConverged:
            self.newton.reset()
            raise FewearInputError(
                f"cylinder shifted to x = {centre_x_m:g} m under P = {-force[1]:g} N: the "
                "frictional Newton found no equilibrium; solve P afresh") from None

    def _in_halves(self, step, start: np.ndarray, end: np.ndarray, halvings: int
                   ) -> FrictionalStep:
        """``step(end)``, a frictional step to the load ``end`` from the present state (at the
        load ``start``); should its Newton not converge, the state restored and the two
        halves one after the other, each split again at most ``halvings`` times in all
        (then :class:`ContactNotConverged`). The semi-smooth Newton on the stick-slip law can
        cycle with growing amplitude when a step turns many nodes from stick to slip (a node's
        tangential stiffness is k_t or nothing; measured at h = a/16, Q from mu P/2 to
        3 mu P/4 in one step); for a monotonic load the halves end in the same state
        (Mindlin's solution depends on the final load alone). The split step's result is the
        second half's, its Coulomb slip the two halves' sum (the whole step's, as Archard needs
        it: :mod:`fewear.loop.fretting`)."""
        centre, displacement = self.pin_centre_m.copy(), self.displacement.x.array.copy()
        try:
            return step(end)
        except ContactNotConverged:
            if halvings == 0:
                raise
            self.displacement.x.array[:] = displacement
            self.place_pin(centre)
            middle = 0.5 * (start + end)
            first = self._in_halves(step, start, middle, halvings - 1)
            second = self._in_halves(step, middle, end, halvings - 1)
            return second._replace(contact=replace(
                second.contact, slip_m=first.contact.slip_m + second.contact.slip_m))

    def _frictional_step(self, force: np.ndarray, basis: np.ndarray,
                         frozen: bool = False) -> FrictionalStep:
        """The coupled Newton from the present state with Coulomb friction on (and the
        pressure ``frozen``), the centre's moves in the span of ``basis`` (force control of
        basis^T F); the converged step's shear and slip, and its end as the next step's
        history (:meth:`_close_step`)."""
        if not np.any(self.pin_centre_m):
            raise FewearInputError("a frictional step needs the cylinder pressed on the flat "
                                   "first (solve the normal force P > 0)")
        self.coulomb.value = self.problem.contact.friction_coefficient
        self.frozen.value = float(frozen)
        try:
            iterations = self.newton.solve_from_here(
                force / self.problem.out_of_plane_length_m, PRESS_DIRECTION, basis,
                "in a frictional step")
            result = self._equilibrium_result(force, 0.0, iterations)
            return self._close_step(result)
        finally:
            self.coulomb.value = 0.0
            self.frozen.value = 0.0

    def _close_step(self, result: ContactResult) -> FrictionalStep:
        """The converged step (:class:`FrictionalStep`): the nodal pressure of the traction,
        shear tau (Pa) and Coulomb slip |ds + (tau - tau_0)/k_t| (m, 0 off contact;
        :meth:`shear`'s notation); then its end becomes the history."""
        shear_before = self._at_bore_nodes(self.shear_before)[:, 0]
        relative = (self.nodal_displacement() - self._at_bore_nodes(self.displacement_before)
                    - (self.pin_centre_m - self.centre_before.value))
        normal = (self.bore.points + self.nodal_displacement() - self.pin_centre_m)
        normal /= np.hypot(normal[:, 0], normal[:, 1])[:, None]
        moved = -normal[:, 1] * relative[:, 0] + normal[:, 0] * relative[:, 1]
        for function, expression in ((self._shear_now, self._shear_expression),
                                     (self._loading_now, self._loading_expression)):
            function.interpolate(expression)
            function.x.scatter_forward()
        shear = self._at_bore_nodes(self._shear_now)[:, 0]
        pressure = self._at_bore_nodes(self._loading_now)[:, 0]
        slip = np.where(pressure > 0.0, np.abs(
            moved + (shear - shear_before) / float(self.tangential_penalty.value)), 0.0)
        self.shear_before.x.array[:] = self._shear_now.x.array
        self._hold_state()
        self.last_force_N = result.resultant_force_N.copy()
        bound = self.problem.contact.friction_coefficient * pressure
        sticking = (pressure > 0.0) & (np.abs(shear) < bound * (1.0 - STICK_MARGIN))
        return FrictionalStep(replace(result, pressure_Pa=pressure, slip_m=slip), shear,
                              sticking, float(result.resultant_force_N[0]))

    def _release_shear(self) -> None:
        """No shear; the present state the history of the next frictional step, its pressure
        the frozen one of an uncoupled step."""
        self.shear_before.x.array[:] = 0.0
        self.last_force_N = self.last_result.applied_force_N.copy()
        self.frozen_pressure.interpolate(self._pressure_expression)
        self.frozen_pressure.x.scatter_forward()
        self._hold_state()

    def _hold_state(self) -> None:
        """The present displacement and centre as the next step's start."""
        self.displacement_before.interpolate(self.displacement)
        self.displacement_before.x.scatter_forward()
        self.centre_before.value = self.pin_centre_m

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
        L pi E* x_c^2 / (4 R) (method notes)."""
        problem = self.problem
        x_c = problem.mesh.contact_zone_half_width_m
        return (problem.out_of_plane_length_m * math.pi * problem.material.plane_strain_modulus_Pa
                * x_c**2 / (4.0 * problem.indenter_radius_m))


FLAT_NEWTON = specialised(FlatContactSolver)
"""The algorithm of :mod:`fewear.contact.newton` on the flat solver's methods."""
