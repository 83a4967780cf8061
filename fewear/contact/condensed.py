"""The fast path: the elastic bushing condensed onto its bore nodes, once per mesh.

The bore's nodal displacements are U = G f with the nodal compliance G = N K^-1 N^T, computed
once per mesh geometry from one LU of K and the selected entries of its inverse (MUMPS
ICNTL(30)); each load step then solves the small nonlinear contact problem on the nodes with the
Newton of :mod:`fewear.contact.newton`, compiled whole (:mod:`fewear.contact.condensed_newton`).
Both paths converge to the same solution. Method notes: docs/contact.md.
"""

from __future__ import annotations

import ctypes

import numpy as np
from dolfinx import fem
from mpi4py import MPI
from petsc4py import PETSc
from scipy import sparse

from fewear.contact import condensed_newton
from fewear.contact.admissible import (
    ContactLoadError,
    beyond_small_displacements,
    cosine_law_nodal_forces,
    displacement_limit_m,
)
from fewear.contact.condensed_newton import (
    new_state,
    nodal_forces,
    run_load_steps,
)
from fewear.contact.newton import ContactNewton
from fewear.contact.params import ContactProblem
from fewear.contact.result import ContactResult
from fewear.contact.solver import (
    BushingContactSolver,
    checked_force,
    checked_rotation,
)
from fewear.linalg import direct_solver
from fewear.mesh.bore import bore_node_weights
from fewear.mesh.bushing import BORE_TAG


def _state_array(index: int, doc: str) -> property:
    """A read-only attribute that is the ``index``-th array of ``newton_state``."""
    return property(lambda self: self.newton_state[index], doc=doc)


class CondensedBushingContact:
    """Same ``solve(force_N, rotation_increment_rad=0.0, friction=False) -> ContactResult`` as
    :class:`BushingContactSolver`, from the bore compliance G (see the method notes).

    Build it from a full solver (``CondensedBushingContact(solver)``), which provides the mesh,
    the LU-factorised stiffness and the bore nodes; call :meth:`update_geometry` after the mesh
    moved (it calls the solver's and rebuilds G).

    Attributes: ``compliance`` (2n, 2n) G in m/(N/m) with rows/columns (node, direction),
    ``weights_m`` (n,), ``points`` (n, 2), ``angles`` (n,), ``pin_centre_m``: all but the angles
    are the arrays of ``newton_state`` (:func:`fewear.contact.condensed_newton.new_state`), the
    state the Newton works on.
    """

    def __init__(self, solver: BushingContactSolver | ContactProblem, comm=MPI.COMM_WORLD):
        if isinstance(solver, ContactProblem):
            solver = BushingContactSolver(solver, comm)
        self.solver = solver
        self.problem = solver.problem
        self.comm = solver.comm
        self._k = self.problem.penalty_stiffness_Pa_per_m()
        self.newton = ContactNewton(self)
        self._dofs = self._bore_dofs()
        self._table = self._nodal_evaluation()
        self.update_geometry(update_solver=False)

    # -- set-up ------------------------------------------------------------------------------
    def release(self) -> None:
        """Drop the Newton iterations' references back to this operator and its solver (cycles),
        so that their PETSc objects go to the garbage list as soon as the operator is dropped
        (:func:`fewear.parallel.release_petsc_garbage`), not at a later garbage collection."""
        self.newton = None
        self.solver.release()

    def update_geometry(self, update_solver: bool = True, keep_compliance: bool = False) -> None:
        """(Re)build the nodal compliance G, the weights and node data from the current mesh.

        ``keep_compliance``: keep the G of the geometry it was built on (its rows and columns
        follow the bore nodes, should their angular order change) and update the rest: G costs
        an LU factorisation and the selected inverse entries (0.3 s on the reference mesh), the
        rest milliseconds. An approximation the caller bounds by how far
        the bore moved since G was built (:class:`fewear.loop.bushing.WornBushing`). The full
        solver's stiffness, which only G is built from, is then not re-assembled either (18 ms
        per move on the default bushing): the next update without ``keep_compliance``
        assembles it on the mesh as it is then."""
        node_ids = self.solver.bore.global_ids.copy()
        if update_solver and keep_compliance:
            self.solver.update_bore()
        elif update_solver:
            self.solver.update_geometry()
        bore = self.solver.bore
        self.angles = bore.angles.copy()
        if keep_compliance:
            position = np.argsort(node_ids)[np.searchsorted(node_ids, bore.global_ids,
                                                            sorter=np.argsort(node_ids))]
            compliance = self.compliance  # the nodes in the same order: G as it is
            if np.any(position != np.arange(position.size)):
                rows = (2 * position[:, None] + np.arange(2)[None, :]).reshape(-1)
                compliance = compliance[np.ix_(rows, rows)]
        else:
            compliance = self._nodal_compliance()
        self.newton_state = new_state(compliance, bore.points.copy(),
                                      bore_node_weights(self.solver.mesh, bore), self._k,
                                      self.problem.geometry.pin_radius_m)
        self.newton.forget()
        self.newton.geometry_changed()

    def _bore_dofs(self):
        """:func:`contact_dofs` of the bore."""
        solver = self.solver
        return contact_dofs(solver.V, solver.mesh, solver.facet_tags, self.comm)

    def _nodal_evaluation(self) -> np.ndarray:
        """:func:`nodal_evaluation` at the local bore nodes."""
        return nodal_evaluation(self.solver.V, self.solver.mesh, self.solver.bore, self._dofs)

    def _gathered_evaluation(self) -> np.ndarray:
        """:func:`gathered_evaluation` of the bore."""
        return gathered_evaluation(self.solver.bore, self._table, self._dofs[2].size, self.comm)

    def _nodal_compliance(self) -> np.ndarray:
        """G = N (K^-1)_BB N^T with K the clamped elastic stiffness and B the bore dofs (N is
        zero elsewhere): one MUMPS LU factorisation of K and the block (K^-1)_BB of selected
        entries of its inverse (MUMPS ICNTL(30), :func:`inverse_block`). MUMPS prunes both
        triangular solves to the bore's entries; a solve with the 2n columns of N^T as dense
        right-hand sides computes the whole of K^-1 N^T and costs about 5 times as much. N, with
        at most 3 nonzeros per row, multiplies as a sparse matrix."""
        solver = self.solver
        ksp = direct_solver(self.comm)
        ksp.setOperators(solver._K_elastic)
        ksp.setUp()
        inverse = inverse_block(ksp.getPC().getFactorMatrix(), self._dofs[2], self.comm)
        ksp.destroy()
        N = sparse.csr_matrix(self._gathered_evaluation())  # a few nonzeros per row
        return np.ascontiguousarray((N @ (N @ inverse).T).T)  # C order: the kernels' signature

    # -- the per-step problem ----------------------------------------------------------------
    def solve(self, force_N, rotation_increment_rad: float = 0.0, friction: bool = False,
              node_order: np.ndarray | None = None,
              node_angles_rad: np.ndarray | None = None) -> ContactResult:
        """Solve for the joint force (N) as :meth:`BushingContactSolver.solve` does; the nodal
        arrays of the result in ``node_order`` (indices of the bore nodes, default their order
        here: by angle), its ``angle_rad`` a copy of ``node_angles_rad`` (default the nodes'
        angles in that order)."""
        force = checked_force(force_N)
        rotation = checked_rotation(rotation_increment_rad)
        results, refusal = self.solve_run(force[None, :], np.array([rotation]), friction, 0,
                                          node_order, node_angles_rad)
        if refusal is not None:
            raise refusal
        return results[0]

    def solve_run(self, forces_N: np.ndarray, rotations_rad: np.ndarray, friction: bool,
                  first: int, node_order: np.ndarray | None = None,
                  node_angles_rad: np.ndarray | None = None) -> tuple[list, Exception | None]:
        """The load steps ``first``, ``first`` + 1, ... of ``forces_N`` (steps, 2), N, with
        their rotation increments ``rotations_rad`` (steps,), in turn, in one compiled call
        (:func:`fewear.contact.condensed_newton.run_load_steps`; :meth:`solve` is one step of
        it): their results, up to the first step refused, and that refusal
        (:class:`ContactLoadError`, the state reset as after it), or None when all were
        solved."""
        forces = np.ascontiguousarray(forces_N, dtype=float)
        rotations = np.asarray(rotations_rad, dtype=float)
        for row in np.flatnonzero(~np.isfinite(forces).all(axis=1) | ~np.isfinite(rotations)):
            checked_force(forces[row])  # the messages of a single solve
            checked_rotation(rotations[row])
        problem = self.problem
        friction_values = (problem.contact.friction_coefficient * np.sign(rotations) if friction
                           else np.zeros(rotations.size))
        n, steps = self.points.shape[0], forces.shape[0]
        order = np.arange(n) if node_order is None else np.ascontiguousarray(node_order)
        fields, centres = np.empty((steps, 5, n)), np.empty((steps, 2))
        sums, iterations = np.empty((steps, 2, 2)), np.zeros(steps, dtype=np.int64)
        L = problem.geometry.width_m
        stop, largest = run_load_steps(
            *self.newton_state, self.newton.memory, tuple(self.newton.settings), forces, L,
            friction_values, problem.indenter_radius_m * np.abs(rotations), order,
            displacement_limit_m(problem), problem.contact.newton_max_iterations, first, fields,
            centres, sums, iterations)
        angles = self._angles_in(order, node_angles_rad)
        results = [ContactResult(
            angle_rad=angles.copy(), x_m=fields[s, 0], y_m=fields[s, 1],
            pressure_Pa=fields[s, 2], gap_m=fields[s, 3], slip_m=fields[s, 4],
            pin_centre_m=centres[s], applied_force_N=forces[s].copy(),
            resultant_force_N=L * sums[s, 0], newton_iterations=int(iterations[s]),
            normal_force_N=L * sums[s, 1]) for s in range(first, stop)]
        if stop == steps:
            return results, None
        reason = ("the contact Newton found no equilibrium" if iterations[stop] < 0
                  else beyond_small_displacements(problem, largest))
        try:
            self._refuse(forces[stop], reason)
        except ContactLoadError as refusal:
            return results, refusal

    def _angles_in(self, order: np.ndarray, angles_rad: np.ndarray | None) -> np.ndarray:
        """The result's ``angle_rad``: a copy of ``angles_rad``, else the nodes' in ``order``."""
        return self.angles[order] if angles_rad is None else angles_rad.copy()

    def _refuse(self, force: np.ndarray, reason: str) -> None:
        """Raise :class:`ContactLoadError` for ``force`` (N); the next solve starts afresh."""
        self.newton.reset()
        raise ContactLoadError(force, reason, displacement_limit_m(self.problem),
                               self.admissible_force_N(force))

    def admissible_force_N(self, force_N) -> float:
        """The largest admissible |F| (N) in the direction of ``force_N``
        (:mod:`fewear.contact.admissible`): u_max / max_q |u_q| under the cosine-law load of 1 N."""
        direction = np.asarray(force_N, dtype=float) / np.linalg.norm(force_N)
        geometry = self.problem.geometry
        forces = cosine_law_nodal_forces(self.points, self.weights_m, direction,
                                         geometry.inner_radius_m, geometry.width_m)
        U = (self.compliance @ forces.reshape(-1)).reshape(-1, 2)
        return displacement_limit_m(self.problem) / float(np.hypot(U[:, 0], U[:, 1]).max())

    def _nodal_forces(self, U: np.ndarray, c: np.ndarray):
        """:func:`nodal_forces` for nodal displacements U (n, 2) and pin centre c."""
        return nodal_forces(self.points, U, c, self.problem.geometry.pin_radius_m, self._k,
                            self._friction_value, self.weights_m)

    # -- the discretisation for ContactNewton --------------------------------------------------
    operations = condensed_newton  # functions of newton_state (compiled)
    newton_algorithm = condensed_newton.algorithm  # its solves run compiled in run_load_steps

    # the Newton state's arrays under their names (the state is their one holder: write into them)
    compliance = _state_array(0, "G (2n, 2n), m per N/m, rows/columns (node, direction)")
    _g = _state_array(1, "the nodal forces g (2n,), N/m")
    _U = _state_array(2, "the nodal displacements U = G g (2n,), m")
    pin_centre_m = _state_array(3, "the pin centre c (2,), m (the next solve overwrites it)")
    points = _state_array(4, "the bore nodes X (n, 2), m, angle-sorted")
    weights_m = _state_array(5, "the bore nodes' weights w (n,), m")

    @property
    def _friction_value(self) -> float:
        """mu s of the present solve (signed by the slip; 0 without friction)."""
        return self.newton_state[6][2]

    def turn_state(self, angle_rad: float) -> bool:
        """:func:`fewear.contact.condensed_newton.turn_state` on this operator's state."""
        return condensed_newton.turn_state(self.newton_state, angle_rad)


def contact_dofs(V, mesh, facet_tags, comm):
    """Local indices (unrolled) of the S2 dofs on the contact surface (``CONTACT_TAG``, the
    bushing's bore or the flat's top), their columns in the gathered, sorted list of global dof
    numbers, and that list."""
    tdim = mesh.topology.dim
    blocks = fem.locate_dofs_topological(V, tdim - 1, facet_tags.find(BORE_TAG))
    global_blocks = V.dofmap.index_map.local_to_global(blocks)
    local = np.concatenate([2 * blocks, 2 * blocks + 1])
    global_ids = np.concatenate([2 * global_blocks, 2 * global_blocks + 1])
    all_ids = np.unique(np.concatenate(comm.allgather(global_ids)))
    return local, np.searchsorted(all_ids, global_ids), all_ids


def nodal_evaluation(V, mesh, bore, dofs) -> np.ndarray:
    """N_local (2 n_local_nodes, n_columns): the S2 basis functions of the contact surface's
    dofs (``dofs``: :func:`contact_dofs`) at the local nodes of ``bore``
    (:class:`fewear.mesh.bore.BoreNodes`), rows (node, direction). A bore node is a node of the
    9-node geometry, so it sits at a fixed reference point X_k of its cell (a vertex or an edge
    midpoint: the coordinate element's k-th point) and, the S2 element being mapped by the
    identity (phi_j(x(X)) = phi_j(X)), its row holds the reference basis phi_j(X_k) of the
    cell's dofs. The basis is tabulated once at the 9 points, so N costs no point search and
    does not change when the mesh moves. Only the surface dofs' basis functions are kept: the
    others vanish on it (the trace of an H1 element on a facet is spanned by the facet's
    dofs)."""
    local_dofs, columns, all_ids = dofs
    index_map = V.dofmap.index_map
    column = np.full(2 * (index_map.size_local + index_map.num_ghosts), -1)
    column[local_dofs] = columns
    basis = reference_basis_at_geometry_nodes(mesh, V)
    geometry = mesh.geometry.dofmap
    table = np.zeros((2 * bore.local_nodes.size, all_ids.size))
    for row, (node, cell) in enumerate(zip(bore.local_nodes, bore.local_node_cells)):
        values = basis[np.flatnonzero(geometry.links(cell) == node)[0]]
        for direction in range(2):
            cell_columns = column[2 * V.dofmap.cell_dofs(cell) + direction]
            on_bore = cell_columns >= 0
            table[2 * row + direction, cell_columns[on_bore]] = values[on_bore]
    return table


def gathered_evaluation(bore, table: np.ndarray, n_columns: int, comm) -> np.ndarray:
    """N (2n, n_columns) in the gathered node order of ``bore``, the same on every rank, from
    each rank's :func:`nodal_evaluation` ``table``."""
    rows = (2 * bore.local_index[:, None] + np.arange(2)[None, :]).reshape(-1)
    local = np.zeros((2 * bore.global_ids.size, n_columns))
    local[rows] = table
    count = np.zeros(2 * bore.global_ids.size)
    count[rows] = 1.0
    return comm.allreduce(local, op=MPI.SUM) / comm.allreduce(count, op=MPI.SUM)[:, None]


def reference_basis_at_geometry_nodes(mesh, V) -> np.ndarray:
    """phi_j(X_k) (k, j): the reference basis of V's scalar element (the Basix element FFCx
    compiles V's forms with) at the reference points X_k of the coordinate element's nodes, in
    the order of the geometry dofmap."""
    from ffcx.element_interface import create_element

    element = create_element(V.ufl_element().sub_elements()[0]).element
    nodes = create_element(mesh.ufl_domain().ufl_coordinate_element()).sub_element.element
    return element.tabulate(0, nodes.points)[0, :, :, 0]


# MUMPS' blocking factor of the selected inverse's right-hand sides (ICNTL(27); its default
# -32 takes blocks of 32): blocks of 128 computed the 646 columns of the default block on ring's
# contact zone in 0.6 times the time (and its lower triangle in 0.6 times that of the whole).
INVERSE_RHS_BLOCK = 128


def inverse_block(factor: PETSc.Mat, dofs: np.ndarray, comm) -> np.ndarray:
    """The dense block (A^-1)[dofs, dofs] of a MUMPS-factorised symmetric A (``dofs`` sorted),
    the same on every rank: its lower triangle computed, mirrored.

    MUMPS computes selected entries of A^-1 (ICNTL(30)) from the sparsity pattern of a matrix on
    the host that lists them transposed (row j: the entries A^-1[i, j]), and overwrites its values;
    PETSc 3.18 calls this ``MatMumpsGetInverseTranspose``, which petsc4py 3.18 does not wrap. It is
    called here through ctypes, on the PETSc library petsc4py's extension module is linked with.
    MUMPS is left in its solve mode as it was found (sparse right-hand sides, centralised solution
    and selected inverse off again: PETSc's solves on several ranks need the distributed solution
    they factorised for)."""
    solve_mode = {icntl: factor.getMumpsIcntl(icntl) for icntl in (20, 21, 27, 30)}
    factor.setMumpsIcntl(27, INVERSE_RHS_BLOCK)
    n = factor.getSize()[0]
    host = comm.rank == 0
    local = n if host else 0  # the host holds all rows and columns of the pattern
    column, row = np.tril_indices(dofs.size)  # pattern row dofs[column] lists dofs[row <= column]
    counts = np.zeros(local, dtype=PETSc.IntType)
    if host:
        counts[dofs] = np.arange(1, dofs.size + 1)
    indptr = np.concatenate([[0], np.cumsum(counts)]).astype(PETSc.IntType)
    indices = (dofs[row] if host else np.zeros(0)).astype(PETSc.IntType)
    pattern = PETSc.Mat().createAIJ(((local, n), (local, n)), comm=comm,
                                    csr=(indptr, indices, np.zeros(indices.size)))
    _petsc_call("MatMumpsGetInverseTranspose", factor, pattern)
    block = None
    if host:
        block = np.empty((dofs.size, dofs.size))
        values = pattern.getValuesCSR()[2]
        block[row, column] = values
        block[column, row] = values
    pattern.destroy()
    for icntl, value in solve_mode.items():
        factor.setMumpsIcntl(icntl, value)
    return comm.bcast(block, root=0)


def _petsc_call(name: str, *objects) -> None:
    """Call the PETSc C function ``name`` with the handles of the petsc4py ``objects``."""
    function = getattr(ctypes.CDLL(PETSc.__file__), name)
    function.argtypes = [ctypes.c_void_p] * len(objects)
    error = function(*(item.handle for item in objects))
    if error:
        raise RuntimeError(f"PETSc {name} failed with error code {error}")
