"""A rigid cylinder pressed on an elastic flat (DOLFINx, PETSc), condensed onto the flat's top.

The flat's rectangle (plane strain, Q8, bottom clamped) under a rigid cylinder with the penalty
contact of :mod:`fewear.contact.solver` at the top's nodes: normal load by force control along a
ray, frictional (fretting) steps under tangential force or shift with Coulomb's law by return
mapping, a worn cylinder seen through the gap, and the implicit Archard step as a wear compliance
in series. The elastic flat enters as the top's nodal compliance G = N K_el^-1 N^T (one
factorisation of K_el per geometry, MUMPS selected inverse), as the bushing's fast path does
(:mod:`fewear.contact.condensed`); the contact Newton of :mod:`fewear.contact.newton` runs
compiled on the top's nodes (:mod:`fewear.contact.flat_newton`). Admissible loads by Hertz line
contact (Johnson, *Contact Mechanics*, 1985, sec. 4.3). Method notes: docs/contact.md.
"""

from __future__ import annotations

import math
from contextlib import contextmanager
from dataclasses import replace
from typing import NamedTuple

import numpy as np
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc
from scipy import sparse

from fewear.contact import flat_newton
from fewear.contact.condensed import (
    contact_dofs,
    gathered_evaluation,
    inverse_block,
    nodal_evaluation,
)
from fewear.contact.flat_newton import (
    FRICTION,
    FROZEN,
    OUTGROWN_X,
    PENALTY,
    RADIUS,
    STICK,
    TANGENTIAL,
    TARGET_X,
    history_parts,
    tractions,
)
from fewear.contact.newton import ContactNewton, ContactNotConverged, newton_settings
from fewear.contact.params import FlatContactProblem
from fewear.contact.result import ContactResult
from fewear.contact.solver import elastic_stiffness_form, nodal_result
from fewear.errors import FewearInputError
from fewear.linalg import direct_solver
from fewear.mesh.bore import BoreNodes, bore_node_weights
from fewear.mesh.flat import flat_mesh

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

# The compliance G is computed on the top nodes within this many contact elements beyond the
# farthest node the contact loaded so far (:meth:`FlatContactSolver._prepare`): a block-on-ring
# scar widens by about one element a wear step, a fretting contact not at all after the first
# stroke; one outgrown costs a selected inverse and the solve again.
COVER_ELEMENTS = 4


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


def _state_array(index: int, doc: str) -> property:
    """A read-only attribute that is the ``index``-th array of ``newton_state``."""
    return property(lambda self: self.newton_state[index], doc=doc)


class FlatContactSolver:
    """The rigid cylinder on the elastic flat (method notes), solved on the top's nodes with
    the flat condensed onto them; frictional steps after a normal solve (method notes).

    ``problem``: the :class:`FlatContactProblem`; ``comm``: MPI communicator; ``mesh_data``: an
    existing ``(mesh, cell_tags, facet_tags)`` from :func:`fewear.mesh.flat.flat_mesh` (built
    from the problem when omitted). ``bore`` holds the flat's top nodes
    (:class:`fewear.mesh.bore.BoreNodes`), sorted by x; ``weights_m`` their weights (m);
    ``pin_centre_m`` the cylinder's centre (m); ``last_result`` the last solve's
    :class:`ContactResult`. Call :meth:`update_geometry` after the mesh moved.
    """

    def __init__(self, problem: FlatContactProblem, comm=MPI.COMM_WORLD, mesh_data=None):
        if mesh_data is None:
            mesh_data = flat_mesh(problem.geometry, problem.mesh, comm)
        self.problem, self.comm = problem, comm
        self.mesh, self.cell_tags, self.facet_tags = mesh_data
        self.V = fem.VectorFunctionSpace(self.mesh, ("S", 2))
        self._a_elastic, self._bc = elastic_stiffness_form(self.V, problem.material,
                                                           self.facet_tags)
        self._K_elastic = fem_petsc.create_matrix(self._a_elastic)
        self._ksp = direct_solver(self.comm, "cholesky")  # K_el is SPD
        self.bore = BoreNodes(self.mesh, self.facet_tags, comm)
        dofs = contact_dofs(self.V, self.mesh, self.facet_tags, comm)
        # the top's global dof numbers, sorted: N's columns
        self._top_dof_ids = dofs[2].astype(PETSc.IntType)
        self._evaluation = sparse.csr_matrix(gathered_evaluation(
            self.bore, nodal_evaluation(self.V, self.mesh, self.bore, dofs),
            self._top_dof_ids.size, comm))  # N: a few nonzeros per row
        self.newton_state = flat_newton.new_state(self.bore.points.shape[0])
        constants = self.newton_state[6]
        constants[RADIUS] = problem.indenter_radius_m
        constants[PENALTY] = constants[TANGENTIAL] = problem.penalty_stiffness_Pa_per_m()
        constants[STICK] = STICK_TOLERANCE
        self.newton = ContactNewton(self)
        self.last_result: ContactResult | None = None
        self.last_force_N = np.zeros(2)  # (Q, -P) at the end of the last solve or step (N)
        self._cylinder_profile: tuple[np.ndarray, np.ndarray] | None = None
        self._cylinder_wear_at_nodes: np.ndarray | None = None
        self._reach_m = 0.0  # the largest |x| of a node the contact reached so far (m)
        self.update_geometry()

    # -- the state of the Newton (fewear.contact.flat_newton) ---------------------------------
    operations = flat_newton  # functions of newton_state (compiled into the solves)
    newton_algorithm = flat_newton.newton_algorithm

    _compliance = _state_array(0, "G (2n, 2n) on the covered nodes (else 0), m per N/m")
    _g = _state_array(1, "the nodal forces on the flat g (2n,), N/m")
    _U = _state_array(2, "the nodal displacements U = G g (2n,), m")
    pin_centre_m = _state_array(3, "the cylinder's centre c (2,), m")
    _points = _state_array(4, "the top nodes lowered by the cylinder's wear (n, 2), m")
    weights_m = _state_array(5, "the top nodes' weights (n,), m")
    _constants = _state_array(6, "the constants of fewear.contact.flat_newton")
    _history = _state_array(7, "the frictional step's start (fewear.contact.flat_newton)")
    _covered = _state_array(8, "1 at the nodes whose block of G is computed, else 0")

    def release(self) -> None:
        """Drop the Newton iteration's reference back to this solver (a cycle)."""
        self.newton = None

    def update_geometry(self) -> None:
        """After the mesh moved: K_el re-assembled, the top's nodes and weights read again;
        K_el factorised and the top's compliance computed at the next solve
        (:meth:`_prepare`)."""
        self._K_elastic.zeroEntries()
        fem_petsc.assemble_matrix(self._K_elastic, self._a_elastic, bcs=[self._bc])
        self._K_elastic.assemble()
        self._K_elastic.setOption(PETSc.Mat.Option.SPD, True)
        self._factorised = False
        self._covered[:] = 0.0
        self.bore.update_geometry()
        self.weights_m[:] = bore_node_weights(self.mesh, self.bore)
        self._points[:] = self.contact_points()
        self.newton.geometry_changed()

    def _prepare(self) -> None:
        """K_el factorised (once per geometry) and the block of G = N K_el^-1 N^T on the top
        nodes within ``COVER_ELEMENTS`` elements of the contact's reach in x, again whenever the
        contact outgrows them (the selected inverse grows with the entries it computes: the
        rows of every top node cost five times the time); on a new geometry the covered nodes'
        displacements of the forces as they are, U = G g (the forces act there)."""
        reach = self._reach_m + COVER_ELEMENTS * self.problem.mesh.contact_element_size_m
        covered = np.abs(self.bore.points[:, 0]) <= reach
        if self._factorised and np.all(self._covered[covered] == 1.0):
            return
        new_geometry = not self._factorised
        if new_geometry:
            self._ksp.setOperators(self._K_elastic)
            self._ksp.setUp()
            self._factorised = True
        nodes = np.flatnonzero(covered)
        rows = (2 * nodes[:, None] + np.arange(2)).reshape(-1)
        N = self._evaluation[rows]
        columns = np.unique(N.indices)
        N = N[:, columns]
        block = inverse_block(self._ksp.getPC().getFactorMatrix(), self._top_dof_ids[columns],
                              self.comm)
        G = self._compliance
        G[:] = 0.0
        G[np.ix_(rows, rows)] = N @ (N @ block).T
        self._covered[:] = covered
        if new_geometry:  # the covered nodes' U = G g; the others' U the last solve's
            support = np.flatnonzero(self._g)
            self._U[rows] = self._g[support] @ G[np.ix_(support, rows)]

    def _displace(self) -> None:
        """U = N K_el^-1 N^T g at every top node (one solve with K_el): the displacements of
        the present forces, where the Newton has G only on the covered nodes and the others'
        displacements of the last solve."""
        rhs, solution = self._K_elastic.createVecs()
        values = self._evaluation.T @ self._g
        if self.comm.rank == 0:
            rhs.setValues(self._top_dof_ids, values)
        rhs.assemble()
        self._ksp.solve(rhs, solution)
        top = self._top_dof_ids
        start, end = solution.getOwnershipRange()
        owned = (top >= start) & (top < end)
        at_top = np.zeros(top.size)
        at_top[owned] = solution.array[top[owned] - start]
        self._U[:] = self._evaluation @ self.comm.allreduce(at_top, op=MPI.SUM)
        rhs.destroy()
        solution.destroy()

    def _outgrown_x_m(self) -> float:
        """The largest |x| of a node outside the covered ones that the cylinder penetrates with
        every node's displacement as the present forces make it (:meth:`_displace`), 0 if
        none: the Newton saw the uncovered nodes' displacements of the last solve (geometry)."""
        self._displace()
        deformed = self._points + self._U.reshape(-1, 2) - self.pin_centre_m
        penetrating = ((np.hypot(deformed[:, 0], deformed[:, 1]) < self._constants[RADIUS])
                       & (self._covered == 0.0))
        return float(np.abs(self.bore.points[penetrating, 0]).max(initial=0.0))

    def _solved(self, run) -> int:
        """``run()``, a Newton solve from the present state, with the compliance it needs
        (:meth:`_prepare`): should the contact reach a node outside the covered ones (in the
        Newton, or at its solution with every node's displacement), the state restored and the
        solve run again on the wider cover. The reach grows to the nodes the converged contact
        loads."""
        start = self._g.copy(), self._U.copy(), self.pin_centre_m.copy()
        while True:
            self._prepare()
            self._constants[OUTGROWN_X] = 0.0
            try:
                iterations, failure = run(), None
            except ContactNotConverged as error:
                iterations, failure = -1, error
            outgrown = float(self._constants[OUTGROWN_X])
            if outgrown == 0.0 and failure is None:
                outgrown = self._outgrown_x_m()
            if outgrown == 0.0:
                break
            self._g[:], self._U[:], self.pin_centre_m[:] = start
            self._reach_m = max(self._reach_m, outgrown)
        if failure is not None:
            raise failure
        loaded = np.flatnonzero(np.any(self._g.reshape(-1, 2) != 0.0, axis=1))
        self._reach_m = max(self._reach_m,
                            float(np.abs(self.bore.points[loaded, 0]).max(initial=0.0)))
        return iterations

    # -- the cylinder's wear ------------------------------------------------------------------
    def set_cylinder_wear(self, position_m: np.ndarray, depth_m: np.ndarray) -> None:
        """The cylinder's worn depth h_c (m, into the cylinder) at the positions s (m, along its
        bottom from below its centre, increasing), linear between them and 0 beyond; applied
        at the centre's x of every later solve (the prescribed x of a shift, 0 for
        :meth:`solve`, the step's start for a force-controlled step)."""
        self._cylinder_profile = (np.asarray(position_m, dtype=float).copy(),
                                  np.asarray(depth_m, dtype=float).copy())

    def _place_cylinder_wear(self, centre_x_m: float) -> None:
        """The cylinder's wear under the top's nodes with its centre at x = ``centre_x_m``: the
        nodes the contact sees (:meth:`contact_points`)."""
        if self._cylinder_profile is not None:
            position, depth = self._cylinder_profile
            self._cylinder_wear_at_nodes = np.interp(self.bore.points[:, 0] - centre_x_m,
                                                     position, depth, left=0.0, right=0.0)
        self._points[:] = self.contact_points()

    def contact_points(self) -> np.ndarray:
        """The top's nodes lowered by the cylinder's wear h_c above them (m): the gap to the
        worn cylinder, |x + u - c| - (R - h_c) to first order in h_c/R, is the gap of the
        lowered point to the circle."""
        if self._cylinder_wear_at_nodes is None:
            return self.bore.points
        return self.bore.points - np.column_stack(
            [np.zeros(self.bore.points.shape[0]), self._cylinder_wear_at_nodes])

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
        self._place_cylinder_wear(0.0)
        if normal == 0.0:
            result = self._no_contact_result(force)
            self._release_shear()
            return result
        with self._series_penalty(wear_compliance_m_per_Pa):
            try:
                iterations = self._solved(lambda: self.newton.solve_on_ray(
                    force / self.problem.out_of_plane_length_m, PRESS_DIRECTION))
            except ContactNotConverged:
                self._refuse(force, "the contact Newton found no equilibrium")
            result = self._equilibrium_result(force, iterations)
        self._release_shear()
        return result

    def solve_tangential_force(self, tangential_force_N: float, normal_force_N: float,
                               uncoupled: bool = False) -> FrictionalStep:
        """A frictional step to the forces (Q, -P) on the cylinder (N) from the last solve's
        state, with Coulomb's law (:func:`fewear.contact.flat_newton.tractions`, mu the
        problem's friction coefficient) and the history of the steps since the last
        :meth:`solve`: force control of both, the centre free. Cattaneo-Mindlin partial slip
        for 0 < Q < mu P after a :meth:`solve` of P; Q >= mu P has no equilibrium under force
        control (the cylinder slides away).

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
        reaction. The result's ``applied_force_N`` is (Q, -P). The Newton's first step is the
        linearised (stick) response to the whole move: moving the centre there before the
        Newton instead started it with every node slipping (k_t |dx| > mu p already for
        |dx| ~ 1e-10 m), from which it cycled.

        ``wear_compliance_m_per_Pa``: c >= 0, the step's wear solved implicitly as in
        :meth:`solve` (the penalty law with c in series; the caller moves the top by c p
        afterwards); 0, the plain contact."""
        force = np.array([0.0, -checked_normal_force(normal_force_N)])

        def shifted(centre_x_m: np.ndarray) -> FrictionalStep:
            self._constants[TARGET_X] = float(centre_x_m[0])
            self._place_cylinder_wear(float(centre_x_m[0]))
            try:
                with self._series_penalty(wear_compliance_m_per_Pa):
                    step = self._frictional_step(force, VERTICAL_MOVES)
            finally:
                self._constants[TARGET_X] = math.nan
            applied = np.array([step.tangential_force_N, force[1]])
            return step._replace(contact=replace(step.contact, applied_force_N=applied))

        try:
            return self._in_halves(shifted, self._centre_before()[:1].copy(),
                                   np.array([float(centre_x_m)]), STEP_HALVINGS)
        except ContactNotConverged:
            self.newton.reset()
            raise FewearInputError(
                f"cylinder shifted to x = {centre_x_m:g} m under P = {-force[1]:g} N: the "
                "frictional Newton found no equilibrium; solve P afresh") from None

    def _centre_before(self) -> np.ndarray:
        """The centre at the frictional step's start, c_0 (m; a view of the history)."""
        return history_parts(self._history, self.bore.points.shape[0])[2]

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
        state = self._g.copy(), self._U.copy(), self.pin_centre_m.copy()
        try:
            return step(end)
        except ContactNotConverged:
            if halvings == 0:
                raise
            self._g[:], self._U[:], self.pin_centre_m[:] = state
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
        constants = self._constants
        constants[FRICTION] = self.problem.contact.friction_coefficient
        constants[FROZEN] = float(frozen)
        try:
            iterations = self._solved(lambda: self.newton.solve_from_here(
                force / self.problem.out_of_plane_length_m, PRESS_DIRECTION, basis,
                "in a frictional step"))
            result = self._equilibrium_result(force, iterations)
            return self._close_step(result)
        finally:
            constants[FRICTION] = constants[FROZEN] = 0.0

    def _tractions(self):
        """:func:`fewear.contact.flat_newton.tractions` at the present state."""
        return tractions(self._points, self._U.reshape(-1, 2), self.pin_centre_m,
                         self.weights_m, self._constants, self._history)

    def _close_step(self, result: ContactResult) -> FrictionalStep:
        """The converged step (:class:`FrictionalStep`): the nodal pressure of the traction,
        shear tau (Pa) and Coulomb slip |ds + (tau - tau_0)/k_t| (m, 0 off contact; ds the
        tangential motion of the node relative to the centre since the step's start, along
        the tangent of its own (not lowered) point); then its end becomes the history."""
        shear_before, U_before, centre_before, _ = history_parts(
            self._history, self.bore.points.shape[0])
        displacement = self._U.reshape(-1, 2)
        relative = (displacement - U_before.reshape(-1, 2)
                    - (self.pin_centre_m - centre_before))
        normal = self.bore.points + displacement - self.pin_centre_m
        normal /= np.hypot(normal[:, 0], normal[:, 1])[:, None]
        moved = -normal[:, 1] * relative[:, 0] + normal[:, 0] * relative[:, 1]
        pressure, shear = (array.copy() for array in self._tractions()[4:6])
        slip = np.where(pressure > 0.0, np.abs(
            moved + (shear - shear_before) / self._constants[TANGENTIAL]), 0.0)
        shear_before[:] = shear
        self._hold_state()
        self.last_force_N = result.resultant_force_N.copy()
        bound = self.problem.contact.friction_coefficient * pressure
        sticking = (pressure > 0.0) & (np.abs(shear) < bound * (1.0 - STICK_MARGIN))
        return FrictionalStep(replace(result, pressure_Pa=pressure, slip_m=slip), shear,
                              sticking, float(result.resultant_force_N[0]))

    def _release_shear(self) -> None:
        """No shear; the present state the history of the next frictional step, its penalty
        pressure the frozen one of an uncoupled step."""
        shear_before, _, _, frozen_pressure = history_parts(self._history,
                                                            self.bore.points.shape[0])
        shear_before[:] = 0.0
        self.last_force_N = self.last_result.applied_force_N.copy()
        frozen_pressure[:] = self._tractions()[3]
        self._hold_state()

    def _hold_state(self) -> None:
        """The present displacement and centre as the next step's start."""
        _, U_before, centre_before, _ = history_parts(self._history, self.bore.points.shape[0])
        U_before[:] = self._U
        centre_before[:] = self.pin_centre_m

    @contextmanager
    def _series_penalty(self, compliance_m_per_Pa: float):
        """Within the ``with`` block the penalty is k' = 1 / (1/k + c) for the compliance c
        (m/Pa): in the tractions, the Newton's constants and the nodal pressures (the problem's
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
        self._constants[PENALTY] = series
        self.newton.settings = newton_settings(self.problem)
        try:
            yield
        finally:
            self.problem = problem
            self._constants[PENALTY] = penalty
            self.newton.settings = newton_settings(problem)

    # -- results -------------------------------------------------------------------------------
    def _equilibrium_result(self, force: np.ndarray, iterations: int) -> ContactResult:
        """The :class:`ContactResult` of the converged state under ``force`` (N): the nodal
        penalty law (:func:`fewear.contact.solver.nodal_result`) with the resultant of the
        nodal forces and of their pressure part (N), y_m the top nodes' own (not lowered);
        refused (:meth:`_refuse`) if :meth:`_inadmissible` gives a reason."""
        f, _, _, penalty_pressure, _, _, _ = self._tractions()
        length = self.problem.out_of_plane_length_m
        normal = (self.weights_m * penalty_pressure)[:, None] * (
            self._points + self._U.reshape(-1, 2) - self.pin_centre_m)
        normal /= np.hypot(*(self._points + self._U.reshape(-1, 2) - self.pin_centre_m).T
                           )[:, None]
        result = nodal_result(self.problem, self.contact_points(), self.bore.angles,
                              self._U.reshape(-1, 2), self.pin_centre_m, force,
                              length * f.sum(axis=0), length * normal.sum(axis=0), 0.0,
                              iterations)
        result = replace(result, y_m=self.bore.points[:, 1].copy())
        reason = self._inadmissible(result)
        if reason is not None:
            self._refuse(force, reason)
        self.last_result = result
        return result

    def _no_contact_result(self, force: np.ndarray) -> ContactResult:
        """The result of no force: no displacement, the centre at the origin."""
        self.newton.reset()
        zeros = np.zeros((self.bore.points.shape[0], 2))
        self.last_result = replace(nodal_result(
            self.problem, self.contact_points(), self.bore.angles, zeros, self.pin_centre_m,
            force, np.zeros(2), np.zeros(2), 0.0, 0), y_m=self.bore.points[:, 1].copy())
        return self.last_result

    def _inadmissible(self, result: ContactResult) -> str | None:
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
