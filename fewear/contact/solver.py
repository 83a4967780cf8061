"""The bushing contact model: a rigid pin pressed into a linear elastic bushing (DOLFINx, PETSc).

Plane strain, serendipity degree 2 (the paper's Q8) on the bushing, outer surface clamped; the
rigid pin's centre is the second unknown under force control. Penalty contact on the bore,
p = k <-g>_+, with node-based (Gauss-Lobatto) quadrature and optional Coulomb friction; each
Newton step of :mod:`fewear.contact.newton` solves the displacement system bordered by the two pin
unknowns (one LU of K and a 2x2 Schur complement). Method notes: docs/contact.md.
"""

from __future__ import annotations

import math

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI
from petsc4py import PETSc

from fewear.contact.admissible import (
    ContactLoadError,
    beyond_small_displacements,
    displacement_limit_m,
)
from fewear.contact.newton import (
    ContactNewton,
    ContactNotConverged,
    specialised,
)
from fewear.contact.newton_kernels import LineData, contact_direction, gaps
from fewear.contact.params import ContactProblem
from fewear.contact.result import ContactResult
from fewear.errors import FewearInputError
from fewear.linalg import direct_solver
from fewear.mesh.bore import BoreNodes, bore_node_weights
from fewear.mesh.bushing import bushing_mesh
from fewear.mesh.tags import CLAMPED_TAG, CONTACT_TAG

# The contact integral's quadrature: 3-point Gauss-Lobatto (Simpson) on each bore facet, whose
# points are the facet's Q8 nodes (two vertices and the edge midpoint, weights 1/6, 1/6, 2/3).
CONTACT_QUADRATURE = {"quadrature_degree": 3, "quadrature_rule": "GLL"}

def checked_force(force_N) -> np.ndarray:
    """The joint force as a finite (2,) array (N), else FewearInputError."""
    force = np.asarray(force_N, dtype=float).reshape(-1)
    if force.shape != (2,) or not (math.isfinite(force[0]) and math.isfinite(force[1])):
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
    gap = np.sqrt(deformed[:, 0] ** 2 + deformed[:, 1] ** 2) - problem.indenter_radius_m
    pressure = problem.penalty_stiffness_Pa_per_m() * np.maximum(-gap, 0.0)
    slip = np.where(pressure > 0.0, problem.indenter_radius_m * abs(rotation), 0.0)
    return ContactResult(
        angle_rad=angles.copy(), x_m=points[:, 0].copy(), y_m=points[:, 1].copy(),
        pressure_Pa=pressure, gap_m=gap, slip_m=slip, pin_centre_m=np.array(pin_centre, float),
        applied_force_N=np.array(force, float), resultant_force_N=np.array(resultant, float),
        newton_iterations=int(iterations), normal_force_N=np.array(normal, float),
    )


def elastic_stiffness_form(V, material, facet_tags):
    """The plane-strain linear elastic stiffness form of ``material`` on the vector space V
    (Hooke's law by the Lame constants) and the clamping u = 0 on the facets tagged
    ``CLAMPED_TAG``."""
    E, ν = material.youngs_modulus_Pa, material.poisson_ratio
    μ_lame = E / (2.0 * (1.0 + ν))
    λ_lame = E * ν / ((1.0 + ν) * (1.0 - 2.0 * ν))

    def ε(w):
        return ufl.sym(ufl.grad(w))

    def σ(w):
        return 2.0 * μ_lame * ε(w) + λ_lame * ufl.tr(ε(w)) * ufl.Identity(2)

    trial, test = ufl.TrialFunction(V), ufl.TestFunction(V)
    clamped = facet_tags.find(CLAMPED_TAG)
    clamped_dofs = fem.locate_dofs_topological(V, V.mesh.topology.dim - 1, clamped)
    return (fem.form(ufl.inner(σ(trial), ε(test)) * ufl.dx),
            fem.dirichletbc(fem.Function(V), clamped_dofs))


class BushingContactSolver:
    """Full Newton solve of the pin-in-bushing penalty contact (see the method notes).

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
        self._ksp = direct_solver(self.comm)
        self.pin_centre_m = np.zeros(2)
        self.newton = ContactNewton(self)
        self.last_result: ContactResult | None = None
        self.update_geometry()

    # -- set-up ------------------------------------------------------------------------------
    def _build_forms(self) -> None:
        msh, problem = self.mesh, self.problem
        self.V = fem.VectorFunctionSpace(msh, ("S", 2))
        self.displacement = fem.Function(self.V, name="displacement")
        self._du = fem.Function(self.V)
        trial, test = ufl.TrialFunction(self.V), ufl.TestFunction(self.V)
        self._a_elastic, self._bc = elastic_stiffness_form(self.V, problem.material,
                                                           self.facet_tags)

        self.pin_centre = fem.Constant(msh, np.zeros(2, dtype=PETSc.ScalarType))
        self.penalty = fem.Constant(msh, PETSc.ScalarType(problem.penalty_stiffness_Pa_per_m()))
        self.pin_radius = fem.Constant(msh, PETSc.ScalarType(problem.indenter_radius_m))
        self.friction = fem.Constant(msh, PETSc.ScalarType(0.0))  # mu * sign(rotation)
        ds = ufl.Measure("ds", domain=msh, subdomain_data=self.facet_tags,
                         metadata=CONTACT_QUADRATURE)
        self._ds = ds
        u = self.displacement
        traction = self.contact_traction(ufl.SpatialCoordinate(msh) + u)
        residual = -ufl.inner(traction, test) * ds(CONTACT_TAG)
        self._r_contact = fem.form(residual)
        self._j_contact = fem.form(ufl.derivative(residual, u, trial))
        pressure = self.contact_pressure(ufl.SpatialCoordinate(msh) + u)
        normal = self._normal(ufl.SpatialCoordinate(msh) + u)
        self._normal_force = [fem.form(pressure * normal[i] * ds(CONTACT_TAG)) for i in range(2)]
        self._cosine_law_load = None  # compiled on first use (admissible_force_N)
        self._contact_length = fem.form(ufl.conditional(ufl.gt(pressure, 0.0), 1.0, 0.0)
                                        * ds(CONTACT_TAG))

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

    def _cosine_law_load_form(self):
        """The load vector of the cosine-law pressure of a 1 N joint force along
        ``load_direction`` on the bore (:mod:`fewear.contact.admissible`), compiled on first
        use."""
        if self._cosine_law_load is None:
            geometry = self.problem.geometry
            self.load_direction = fem.Constant(self.mesh,
                                               np.array([1.0, 0.0], dtype=PETSc.ScalarType))
            x = ufl.SpatialCoordinate(self.mesh)
            radial = x / ufl.sqrt(ufl.inner(x, x))
            facing = ufl.inner(radial, self.load_direction)
            cosine_law = (2.0 / (math.pi * geometry.inner_radius_m * geometry.width_m)
                          * ufl.conditional(ufl.gt(facing, 0.0), facing, 0.0))
            test = ufl.TestFunction(self.V)
            self._cosine_law_load = fem.form(cosine_law * ufl.inner(radial, test)
                                             * self._ds(CONTACT_TAG))
        return self._cosine_law_load

    def release(self) -> None:
        """Drop the Newton iteration's reference back to this solver (a cycle): see
        :meth:`fewear.contact.condensed.CondensedBushingContact.release`."""
        self.newton = None

    def update_geometry(self) -> None:
        """Re-assemble the elastic stiffness and bore data after the mesh geometry changed."""
        self._K_elastic.zeroEntries()
        fem_petsc.assemble_matrix(self._K_elastic, self._a_elastic, bcs=[self._bc])
        self._K_elastic.assemble()
        self._K = self._K_elastic.duplicate(copy=True)
        self.update_bore()

    def update_bore(self) -> None:
        """The bore data alone after the mesh geometry changed (the stiffness left as it was
        assembled: for a caller that does not solve with it until the next
        :meth:`update_geometry`)."""
        self.bore.update_geometry()
        self.weights_m = bore_node_weights(self.mesh, self.bore)
        self.newton.geometry_changed()

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
        load = force / self.problem.out_of_plane_length_m
        try:
            iterations = self.newton.solve(load, contact_direction(force, μs))
        except ContactNotConverged:
            self._refuse(force, "the contact Newton found no equilibrium")
        return self._equilibrium_result(force, rotation, iterations)

    def _equilibrium_result(self, force: np.ndarray, rotation: float,
                            iterations: int) -> ContactResult:
        """The :class:`ContactResult` of the converged state under ``force`` (N), refused
        (:meth:`_refuse`) if :meth:`_inadmissible` gives a reason."""
        self.pin_centre.value = self.pin_centre_m
        self._assemble_contact(force / self.problem.out_of_plane_length_m)
        displacement = self.nodal_displacement()
        result = self._result(force, rotation, iterations, displacement)
        reason = self._inadmissible(result, displacement)
        if reason is not None:
            self._refuse(force, reason)
        self.last_result = result
        return result

    def _inadmissible(self, result: ContactResult, displacement: np.ndarray) -> str | None:
        """Why the solution is not admissible (:mod:`fewear.contact.admissible`: the bore moves
        by too much), or None."""
        return beyond_small_displacements(self.problem, float(np.hypot(*displacement.T).max()))

    def _refuse(self, force: np.ndarray, reason: str) -> None:
        """Raise :class:`ContactLoadError` for ``force`` (N); the next solve starts afresh."""
        self.newton.reset()
        raise ContactLoadError(force, reason, displacement_limit_m(self.problem),
                               self.admissible_force_N(force))

    def admissible_force_N(self, force_N) -> float:
        """The largest admissible |F| (N) in the direction of ``force_N``
        (:mod:`fewear.contact.admissible`): u_max / max_q |u_q| with u the elastic displacement
        under the cosine-law pressure of 1 N on the bore (one LU solve with K_el)."""
        form = self._cosine_law_load_form()
        self.load_direction.value = np.asarray(force_N, dtype=float) / np.linalg.norm(force_N)
        rhs = self._rhs[0]
        with rhs.localForm() as local:
            local.set(0.0)
        fem_petsc.assemble_vector(rhs, form)
        rhs.ghostUpdate(addv=PETSc.InsertMode.ADD, mode=PETSc.ScatterMode.REVERSE)
        rhs.array_w[self._bc_local] = 0.0
        ksp = direct_solver(self.comm)
        ksp.setOperators(self._K_elastic)
        unit_response = fem.Function(self.V)
        ksp.solve(rhs, unit_response.vector)
        unit_response.x.scatter_forward()
        ksp.destroy()
        U = self._at_bore_nodes(unit_response)
        return displacement_limit_m(self.problem) / float(np.hypot(U[:, 0], U[:, 1]).max())

    def _no_contact_result(self, force, rotation) -> ContactResult:
        self.newton.reset()
        zeros = np.zeros((self.bore.points.shape[0], 2))
        self.last_result = nodal_result(
            self.problem, self.contact_points(), self.bore.angles, zeros, self.pin_centre_m, force,
            np.zeros(2), np.zeros(2), rotation, 0)
        return self.last_result

    # -- the discretisation for ContactNewton --------------------------------------------------
    # Its operations (fewear.contact.newton.NewtonOperations) are these methods, the state the
    # solver itself. The displacement field is not turned for a warm start (no interpolation
    # between rotated meshes in DOLFINx 0.5).
    @property
    def operations(self) -> type:
        return BushingContactSolver

    @property
    def newton_state(self) -> BushingContactSolver:
        return self

    @property
    def newton_algorithm(self):
        return FULL_PATH_NEWTON

    def can_turn_state(self) -> bool:
        return False

    def turn_state(self, angle_rad: float) -> bool:
        return False

    def zero_displacement(self) -> None:
        self.displacement.x.array[:] = 0.0

    def linearise(self, load: np.ndarray) -> tuple[np.ndarray, float, None]:
        """Assemble r and J at the current state; the pin residual (N/m) and active length (m)
        (the linearisation is kept in the solver's matrices)."""
        self.pin_centre.value = self.pin_centre_m
        return self._assemble_contact(load), self._active_length(), None

    def newton_direction(self, linear, pin_residual, load, basis):
        return self._bordered_step(pin_residual, basis)

    def begin_line_search(self, linear, du, dc, pin_residual) -> tuple[LineData, None]:
        """Slope of Pi along (du, dc): (K_el u + r) . du + r_c . dc (J/m); the elastic energy
        1/2 u.K_el u along the line, 1/2 u.K_el u + s du.K_el u + s^2/2 du.K_el du; the bore
        nodes' displacement and its update (the evaluation at the nodes is linear in u)."""
        Ku, Kdu = self._rhs[1], self._rhs[2]
        u = self.displacement.vector
        self._K_elastic.mult(u, Ku)
        self._K_elastic.mult(du, Kdu)
        elastic = np.array([0.5 * u.dot(Ku), du.dot(Ku), 0.5 * du.dot(Kdu)])
        Ku.axpy(1.0, self._r)
        Ku.array_w[self._bc_local] = 0.0
        slope = Ku.dot(du) + float(pin_residual @ dc)
        self._line = (du, 0.0)  # the update and the step taken along it so far
        if du is not self._du.vector:  # the nodal update is evaluated from the function _du
            du.copy(self._du.vector)
        self._du.x.scatter_forward()
        points, displacement = self.contact_points(), np.ascontiguousarray(
            self.nodal_displacement())
        return LineData(slope, points, displacement,
                        np.ascontiguousarray(self._at_bore_nodes(self._du)), elastic,
                        gaps(points + displacement, self.pin_centre_m,
                             self.problem.indenter_radius_m)), None

    def try_step(self, base, du, step: float, pin_centre: np.ndarray) -> None:
        """Move u along the line search's update to the step (the steps taken so far kept)."""
        _, taken = self._line
        self.displacement.vector.axpy(step - taken, du)
        self.displacement.x.scatter_forward()
        self._line = (du, step)
        self.place_pin(pin_centre)

    def deformed_points(self) -> np.ndarray:
        return self.contact_points() + self.nodal_displacement()

    def contact_points(self) -> np.ndarray:
        """The bore nodes as the penalty law sees them (m): the bore's own; a worn indenter
        shifts them (:meth:`fewear.contact.flat.FlatContactSolver.contact_points`)."""
        return self.bore.points

    def node_weights(self) -> np.ndarray:
        return self.weights_m

    def pin_position(self) -> np.ndarray:
        return self.pin_centre_m

    def place_pin(self, centre: np.ndarray) -> None:
        self.pin_centre_m = np.array(centre, dtype=float)
        self.pin_centre.value = self.pin_centre_m

    def frictionless(self) -> bool:
        return float(self.friction.value) == 0.0

    def update_sizes(self, du) -> tuple[float, float]:
        return (du.norm(PETSc.NormType.NORM_INFINITY),
                self.displacement.vector.norm(PETSc.NormType.NORM_INFINITY))

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

    def _bordered_step(self, r_pin: np.ndarray, basis: np.ndarray,
                       prescribed: np.ndarray | None = None):
        """Newton direction (du, dc) of the bordered system by the Schur complement on the pin
        block (see the method notes), with dc = basis dz restricted to the span of ``basis``
        (2, k) and the pin equations projected on it, plus a ``prescribed`` move (m) across
        that span where given (displacement control: dc = p + basis dz, basis^T S basis dz =
        basis^T (rhs - S p)); needs ``_assemble_contact`` just before."""
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
        if prescribed is None:
            dc = basis @ np.linalg.solve(basis.T @ S @ basis, basis.T @ rhs_c)
        else:
            dc = prescribed + basis @ np.linalg.solve(basis.T @ S @ basis,
                                                      basis.T @ (rhs_c - S @ prescribed))
        du = self._du.vector
        y0.copy(du)
        du.axpy(-dc[0], Y[0])
        du.axpy(-dc[1], Y[1])
        return du, dc

    # -- output ------------------------------------------------------------------------------
    def nodal_displacement(self) -> np.ndarray:
        """u at the gathered bore nodes (n, 2), by evaluating the S2 field (m)."""
        return self._at_bore_nodes(self.displacement)

    def _at_bore_nodes(self, field: fem.Function) -> np.ndarray:
        """A field at the gathered bore nodes (n, b), b its block size (2 for a vector field of
        V)."""
        points = np.zeros((self.bore.local_nodes.size, 3))
        points[:, :2] = self.mesh.geometry.x[self.bore.local_nodes, :2]
        size = field.function_space.dofmap.index_map_bs
        values = np.zeros((points.shape[0], size))
        if points.shape[0]:  # a rank may own no part of the bore
            values = field.eval(points, self.bore.local_node_cells).reshape(-1, size)
        return self.bore.gather(values)

    def _result(self, force, rotation, iterations, displacement) -> ContactResult:
        L = self.problem.out_of_plane_length_m
        resultant = L * np.array([-self.uniform[i].dot(self._r) for i in range(2)])  # E^T r
        normal = L * np.array([self.comm.allreduce(fem.assemble_scalar(form), op=MPI.SUM)
                               for form in self._normal_force])
        return nodal_result(self.problem, self.contact_points(), self.bore.angles, displacement,
                            self.pin_centre_m, force, resultant, normal, rotation, iterations)

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


FULL_PATH_NEWTON = specialised(BushingContactSolver)
"""The algorithm of :mod:`fewear.contact.newton` on the solver's methods, run as Python."""
