"""The FE bushing as it wears: the contact operator on a mesh whose bore follows the wear state.

After every wear step the bore nodes move radially to the worn bore r(theta) = R_b + h(theta) of
the :class:`fewear.wear.state.WearState` they are given (its one source), the interior follows
(ALE mesh motion, the outer surface fixed; with the compliance kept per mesh, at a block's last
step only), and the condensed contact operator is rebuilt on the moved bore. When the motion
since the last mesh passes a set fraction of the bore element height, the bushing is re-meshed
from r(theta). Moves, re-meshes and the contact's fallbacks are counted in the case's
:class:`fewear.loop.progress.LoopCounts`.
"""

from __future__ import annotations

import numpy as np

from fewear.contact.admissible import ContactLoadError
from fewear.contact.condensed import CondensedBushingContact
from fewear.contact.params import ContactProblem
from fewear.contact.result import ContactResult
from fewear.contact.sensitivity import summed_sensitivity
from fewear.contact.solver import BushingContactSolver
from fewear.errors import FewearInputError
from fewear.loop.progress import LoopCounts
from fewear.mesh.ale import BoreMotion
from fewear.mesh.bushing import bushing_mesh, radial_progression
from fewear.mesh.profile import periodic_linear
from fewear.mesh.quality import RemeshLimits
from fewear.mesh.snapshot import MeshSnapshot, gather_nodes, scatter_nodes, take_snapshot
from fewear.parallel import release_petsc_garbage
from fewear.wear.state import WearState


def bore_element_height_m(problem: ContactProblem) -> float:
    """Radial height of the bore's element row in the unworn O-grid: the first term of the
    geometric progression of ``radial_element_count`` sizes filling the wall,
    h_1 = t (q - 1) / (q^n - 1), t = R_o - R_b (t / n when q = 1)."""
    wall = problem.geometry.outer_radius_m - problem.geometry.inner_radius_m
    n = problem.mesh.radial_element_count
    q = radial_progression(problem.mesh)
    return wall / n if q == 1.0 else wall * (q - 1.0) / (q**n - 1.0)


COMPLIANCE_UPDATES = ("move", "remesh")


class WornBushing:
    """The condensed contact model of the bushing, kept on the worn bore.

    ``contact``: the :class:`CondensedBushingContact` of the current mesh; ``angles``: the bore
    nodes' angles (rad, increasing), the same in every mesh (the O-grid puts them at k pi / n and
    the wear moves them radially); :meth:`solve` returns the nodal results in this order whatever
    the order of the moved nodes (a node at angle 0 may come out at 2 pi - 1e-16 after a move).
    ``meshed_xy_m``: the node coordinates when the current mesh was made (the reference of its
    motion); ``counts``: the case's counts, which the moves and the contact's fallbacks add to;
    ``last_quality``: after the last move.

    ``compliance_update``: when the bore compliance G of the contact operator (an LU
    factorisation and the bore block of its inverse, the dearest part of a move) is built:
    ``"move"`` after every move, ``"remesh"`` once per mesh, on the mesh as made, and kept
    (reordered) while the mesh moves: the re-mesh limit on the bore's motion (half the bore
    element's height by default) bounds how far the geometry of G lags behind the worn bore.
    Both restore exactly from a checkpoint (the mesh as made is in it).
    """

    def __init__(self, problem: ContactProblem, comm, counts: LoopCounts | None = None,
                 limits: RemeshLimits | None = None, compliance_update: str = "move"):
        if compliance_update not in COMPLIANCE_UPDATES:
            raise FewearInputError(
                f"[wear_loop] compliance_update = {compliance_update!r}: expected one of "
                f"{', '.join(map(repr, COMPLIANCE_UPDATES))}")
        self.problem, self.comm = problem, comm
        self.keep_compliance = compliance_update == "remesh"
        self.counts = LoopCounts() if counts is None else counts
        self.limits = RemeshLimits() if limits is None else limits
        self.element_height_m = bore_element_height_m(problem)
        self.last_quality = None
        self._mesh(bore_profile=None)
        self.angles = self.contact.angles.copy()
        self._node_ids = self.contact.solver.bore.global_ids.copy()
        self._order = np.arange(self.angles.size)

    def _mesh(self, bore_profile, meshed_xy_m: np.ndarray | None = None) -> None:
        """Mesh the bushing on ``bore_profile`` (None: the circle), or put the nodes at
        ``meshed_xy_m`` (a checkpoint's), and build the contact operator and mesh motion on it."""
        geometry, settings = self.problem.geometry, self.problem.mesh
        mesh_data = bushing_mesh(geometry, settings, self.comm, bore_profile=bore_profile)
        node_ids, meshed_xy = gather_nodes(mesh_data[0], self.comm)
        if meshed_xy_m is not None:
            scatter_nodes(mesh_data[0], node_ids, meshed_xy_m)
            meshed_xy = meshed_xy_m
        self.contact = CondensedBushingContact(
            BushingContactSolver(self.problem, self.comm, mesh_data=mesh_data))
        self.motion = BoreMotion(mesh_data[0], mesh_data[2], self.problem.material.poisson_ratio)
        self.meshed_xy_m = meshed_xy

    def close(self) -> None:
        """Destroy the PETSc objects of the current mesh's contact operator and mesh motion
        (collective), while the mesh, and with it its communicator, still lives; the bushing is
        not used again until :meth:`_mesh` gives it a new mesh (a re-mesh, a restore)."""
        mesh = self.mesh
        self.contact.release()
        del self.contact, self.motion
        release_petsc_garbage(mesh.comm, self.comm)

    @property
    def mesh(self):
        return self.contact.solver.mesh

    def solve(self, force_N, rotation_increment_rad: float = 0.0,
              friction: bool = False) -> ContactResult:
        """:meth:`CondensedBushingContact.solve`, nodal arrays in the order of ``angles``.

        On a worn bore the warm start from the previous load step (turned with the load) can lead
        the Newton iteration astray; a refused step is tried once more from a cold start (the
        refusal resets the state), counted in ``contact_retries``. If the step with the Coulomb
        traction still finds no equilibrium, it is solved without it (the traction tilts the
        pressure field by atan(mu), 5.7 deg for mu = 0.1), counted in ``frictionless_steps``
        and reported; a step that fails without friction too is an error."""
        try:
            return self.contact.solve(force_N, rotation_increment_rad, friction, self._order,
                                      self.angles)
        except ContactLoadError:
            return self._retried(force_N, rotation_increment_rad, friction)

    def solve_run(self, forces_N: np.ndarray, rotations_rad: np.ndarray, friction: bool,
                  first: int) -> tuple[list, Exception | None]:
        """:meth:`CondensedBushingContact.solve_run` from the load step ``first`` (one compiled
        call for the steps it solves), the step it stops at retried as :meth:`solve` retries
        it: the results of the steps solved, and the refusal of the next (or None)."""
        results, refusal = self.contact.solve_run(forces_N, rotations_rad, friction, first,
                                                  self._order, self.angles)
        if refusal is None:
            return results, None
        step = first + len(results)
        try:
            results.append(self._retried(forces_N[step], rotations_rad[step], friction))
        except ContactLoadError as again:
            return results, again
        return results, None

    def _retried(self, force_N, rotation_increment_rad: float,
                 friction: bool) -> ContactResult:
        """The retries of :meth:`solve` after its first try was refused (the state reset)."""
        order, angles = self._order, self.angles
        self.counts.contact_retries += 1
        try:
            return self.contact.solve(force_N, rotation_increment_rad, friction, order, angles)
        except ContactLoadError:
            if not friction:
                raise
            self.counts.frictionless_steps += 1
            return self.contact.solve(force_N, rotation_increment_rad, False, order, angles)

    def depth_sensitivity(self, pressure_Pa: np.ndarray, slip_m: np.ndarray, k_m2_N: np.ndarray,
                          pin_centre_m: np.ndarray) -> np.ndarray:
        """sum_s k_s s_s dp_s/dh (n, n) over the load steps of results of :meth:`solve`
        (their pressures, slips, wear coefficients (steps, n) and pin centres (steps, 2)), the
        nodes in the order of ``angles``
        (:func:`fewear.contact.sensitivity.summed_sensitivity`)."""
        contact = self.contact
        return summed_sensitivity(contact.compliance, contact.weights_m, contact.points,
                                  self.problem.penalty_stiffness_Pa_per_m(), self._order,
                                  pressure_Pa, slip_m, k_m2_N, pin_centre_m)

    def move_to(self, state: WearState, interior: bool = True) -> None:
        """Move the bore to the worn bore r(theta) = R_b + h(theta) of ``state`` (ALE,
        :class:`fewear.mesh.ale.BoreMotion`); re-mesh from r(theta) when the moved mesh passes the
        limits; rebuild the contact operator.

        ``interior`` False, with the compliance kept from the mesh as made: the bore nodes
        alone, and the bore's motion alone against its limit. The contact operator then reads
        nothing but the bore (its nodes, weights and the kept G), and a later move with
        ``interior`` (a block's last) puts the interior where moves at every step would have put
        it (the extension is from the mesh as made) and checks the cells' shape there: this
        spares the extension's solve and the quality's Jacobians at the wear steps inside a
        block, about 5 ms each on the default bushing."""
        radius = periodic_linear(state.angle_rad, state.bore_radius_m(
            self.problem.geometry.inner_radius_m, state.angle_rad))
        self.counts.ale_moves += 1
        if self.keep_compliance and not interior:
            ratio = self.motion.move_bore_to(radius)
            remesh = ratio > self.limits.max_bore_motion_ratio
        else:
            move = self.motion.move_to(radius)
            self.last_quality = move.quality
            remesh = self.limits.needs_remesh(move.quality)
        if remesh:
            self.close()
            self._mesh(bore_profile=(state.angle_rad, radius(state.angle_rad)))
            self.counts.remeshes += 1
            self._follow_node_order()
        else:
            self._rebuild_contact()
        release_petsc_garbage(self.mesh.comm)  # the stiffness the move replaced

    def _rebuild_contact(self) -> None:
        """The contact operator on the moved mesh (G kept or rebuilt: ``compliance_update``)."""
        self.contact.update_geometry(keep_compliance=self.keep_compliance)
        self._follow_node_order()

    def _follow_node_order(self) -> None:
        """The permutation from the contact's bore node order to ``angles``'."""
        current = self.contact.solver.bore.global_ids
        sorter = np.argsort(current)
        self._order = sorter[np.searchsorted(current, self._node_ids, sorter=sorter)]

    def snapshot(self) -> MeshSnapshot:
        return take_snapshot(self.mesh, self.comm)

    def restore(self, meshed_xy_m: np.ndarray, snapshot: MeshSnapshot) -> None:
        """Put the bushing back as a checkpoint saw it: the mesh as made (``meshed_xy_m``, the
        reference of its motion and quality), then moved to ``snapshot``."""
        self.close()
        self._mesh(bore_profile=None, meshed_xy_m=meshed_xy_m)
        scatter_nodes(self.mesh, snapshot.node_ids, snapshot.xy_m)
        self._rebuild_contact()
