"""ALE motion of the bushing mesh: the bore moves radially by the wear, the outer surface stays
fixed, the interior follows a linear-elastic extension (DOLFINx).

Total-Lagrangian: each move solves on the mesh as made, whose operator is factorised once, so the
interior depends on the bore's position only. A uniform increment gives the Lame field of a
thick-walled cylinder (Timoshenko & Goodier, Theory of Elasticity, sec. 28); elastic rather
than harmonic because it resists the shear of the bore-row cells. Method notes: docs/run.md.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
import ufl
from dolfinx import fem
from dolfinx.fem import petsc as fem_petsc
from mpi4py import MPI

from fewear.linalg import direct_solver
from fewear.mesh.bushing import BORE_TAG, OUTER_TAG
from fewear.mesh.profile import polar_angle
from fewear.mesh.quality import MeshQuality, QualityMeter

Q9_NODES_PER_CELL = 9


@dataclass(frozen=True)
class BoreMove:
    """What one :meth:`BoreMotion.move` did (all ranks agree).

    ``max_bore_increment_m``: the largest |dr| prescribed at a bore node; ``max_displacement_m``:
    the largest displacement of any node in this move; ``quality``: the mesh after the move, with
    the bore motion counted from the mesh the :class:`BoreMotion` was built on.
    """

    max_bore_increment_m: float
    max_displacement_m: float
    quality: MeshQuality


class BoreMotion:
    """Moves the bore of ``mesh`` (9-node quadrilateral geometry, bore facets tagged ``BORE_TAG``,
    outer ``OUTER_TAG`` in ``facet_tags``) and the interior with it. Build once per mesh, on the
    mesh as made: the extension operator is assembled and LU-factorised here, on that mesh, and
    every :meth:`move` solves with it for the displacement from it (method notes)."""

    def __init__(self, mesh, facet_tags, poisson_ratio: float = 0.3):
        if mesh.geometry.dofmap.links(0).size != Q9_NODES_PER_CELL:
            raise ValueError("BoreMotion needs the 9-node (second-order) quadrilateral geometry")
        self.mesh = mesh
        self.space = fem.VectorFunctionSpace(mesh, ("Q", 2))
        self.node_dof = node_to_dof(mesh, self.space)
        self.dof_node = np.argsort(self.node_dof)
        fdim = mesh.topology.dim - 1
        self.bore_dofs = fem.locate_dofs_topological(self.space, fdim, facet_tags.find(BORE_TAG))
        self.outer_dofs = fem.locate_dofs_topological(self.space, fdim, facet_tags.find(OUTER_TAG))
        self.made_xy = mesh.geometry.x[:, :2].copy()
        self._bore_total = None  # the bore dofs' displacement from the mesh as made, once moved
        self._factorise(elastic_extension_form(self.space, poisson_ratio))
        self.quality_meter = QualityMeter(mesh, facet_tags)

    def _factorise(self, form) -> None:
        """Assemble the operator A on the mesh as made, without (``_operator``) and with the
        Dirichlet rows and columns replaced by the identity (LU-factorised in ``solver``)."""
        form = fem.form(form)
        boundary = fem.dirichletbc(fem.Function(self.space),
                                   np.concatenate([self.bore_dofs, self.outer_dofs]))
        self._operator = fem_petsc.assemble_matrix(form)
        self._operator.assemble()
        constrained = fem_petsc.assemble_matrix(form, bcs=[boundary])
        constrained.assemble()
        # PETSc's own LU on one rank: its solves take 1 ms on the default bushing against
        # MUMPS's 8 ms (its factorisation 0.05 s dearer, once per mesh); the constrained
        # operator is symmetric positive definite (identity rows and columns on the boundary),
        # so LU without pivoting is stable
        comm = self.mesh.comm
        self.solver = direct_solver(comm, package="petsc" if comm.size == 1 else "mumps")
        self.solver.setOperators(constrained)
        self.solver.setUp()
        self._prescribed = fem.Function(self.space)
        self._displacement = fem.Function(self.space)
        self._rhs = self._prescribed.vector.duplicate()
        owned = self.space.dofmap.index_map.size_local
        self._owned_boundary = [dofs[dofs < owned] for dofs in (self.bore_dofs, self.outer_dofs)]

    def bore_displacement(self, increment_m: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """Displacement (m) of this rank's bore dofs, shape (n, 2): ``increment_m(theta)`` along
        the radial direction at each bore node's angle theta in [0, 2 pi)."""
        return self._radial_displacement(lambda angle, radius: increment_m(angle))

    def _radial_displacement(self, increment_m) -> np.ndarray:
        """The bore dofs' displacement (n, 2) by ``increment_m(theta, r)`` (m) along the radial
        direction of each bore node, at its angle theta and radius r now."""
        xy = self.mesh.geometry.x[self.dof_node[self.bore_dofs], :2]
        angle = polar_angle(xy)
        increment = np.asarray(increment_m(angle, np.hypot(xy[:, 0], xy[:, 1])), dtype=float)
        if increment.shape != angle.shape or not np.all(np.isfinite(increment)):
            raise ValueError(f"increment_m must map {angle.size} angles to as many finite radial "
                             f"increments (m), got shape {increment.shape}")
        return increment[:, None] * np.column_stack([np.cos(angle), np.sin(angle)])

    def move(self, increment_m: Callable[[np.ndarray], np.ndarray]) -> BoreMove:
        """Move every bore node radially by ``increment_m(theta)`` (m, theta the node's angle in
        [0, 2 pi) from the bushing centre; vectorised, e.g. :func:`fewear.mesh.profile.
        periodic_linear` of a table), the interior by the elastic extension, the outer nodes not.
        """
        return self._move(self.bore_displacement(increment_m))

    def move_to(self, radius_m: Callable[[np.ndarray], np.ndarray]) -> BoreMove:
        """Move every bore node radially onto the bore r = ``radius_m(theta)`` (m), the interior
        by the elastic extension, the outer nodes not: :meth:`move` by r(theta) minus each
        node's radius now."""
        return self._move(self._displacement_onto(radius_m))

    def move_bore_to(self, radius_m: Callable[[np.ndarray], np.ndarray]) -> float:
        """Move the bore nodes alone onto r = ``radius_m(theta)`` (m), as :meth:`move_to` moves
        them, and leave the interior where it is until :meth:`extend_interior`; return the
        largest bore motion ratio since the mesh was made (all ranks): for a caller that reads
        only the bore between moves."""
        self._move_bore(self._displacement_onto(radius_m))
        return self.quality_meter.bore_motion_ratio()

    def _displacement_onto(self, radius_m: Callable[[np.ndarray], np.ndarray]) -> np.ndarray:
        """The bore dofs' radial displacement (n, 2) onto r = ``radius_m(theta)`` (m) from where
        they are now."""
        return self._radial_displacement(
            lambda angle, radius: np.asarray(radius_m(angle), dtype=float) - radius)

    def extend_interior(self) -> MeshQuality:
        """Every node to X_0 + d, d the elastic extension of the bore's displacement from the
        mesh as made (the interior as a :meth:`move` to the bore's present place puts it); the
        mesh's quality after."""
        x = self.mesh.geometry.x
        if self._bore_total is None:  # never moved here: the bore as it was put (a restore)
            bore_nodes = self.dof_node[self.bore_dofs]
            self._bore_total = x[bore_nodes, :2] - self.made_xy[bore_nodes]
        prescribed = self._prescribed.x.array.reshape(-1, 2)
        prescribed[self.bore_dofs] = self._bore_total
        self._operator.mult(self._prescribed.vector, self._rhs)
        self._rhs.scale(-1.0)
        rhs = self._rhs.array_w.reshape(-1, 2)
        for dofs in self._owned_boundary:
            rhs[dofs] = prescribed[dofs]
        self.solver.solve(self._rhs, self._displacement.vector)
        self._displacement.x.scatter_forward()
        displacement = self._displacement.x.array.reshape(-1, 2).copy()
        displacement[self.outer_dofs] = 0.0
        displacement[self.bore_dofs] = self._bore_total
        x[:, :2] = self.made_xy + displacement[self.node_dof]
        return self.quality_meter.measure()

    def _move_bore(self, bore: np.ndarray) -> None:
        """Move the bore dofs by ``bore`` (this move, (n, 2)): X_0 + D_b, D_b their total
        displacement from the mesh as made."""
        x = self.mesh.geometry.x
        bore_nodes = self.dof_node[self.bore_dofs]
        self._bore_total = x[bore_nodes, :2] - self.made_xy[bore_nodes] + bore
        x[bore_nodes, :2] = self.made_xy[bore_nodes] + self._bore_total

    def _move(self, bore: np.ndarray) -> BoreMove:
        """Move the bore dofs by ``bore`` (this move, (n, 2)) and every node to X_0 + d, d the
        extension of the bore's total displacement D_b from the mesh as made: A d = b with
        b = -A D_b off the boundary (the lifting of the prescribed values) and D_b, 0 on it."""
        before = self.mesh.geometry.x[:, :2].copy()
        self._move_bore(bore)
        quality = self.extend_interior()
        comm = self.mesh.comm
        return BoreMove(
            max_bore_increment_m=comm.allreduce(_max_norm(bore), op=MPI.MAX),
            max_displacement_m=comm.allreduce(
                _max_norm(self.mesh.geometry.x[:, :2] - before), op=MPI.MAX),
            quality=quality,
        )


def elastic_extension_form(space, poisson_ratio: float):
    """a(d, v) = int 2 eps(d) : eps(v) + lambda div d div v dx, shear modulus 1,
    lambda = 2 nu / (1 - 2 nu) (plane strain)."""
    if not -1.0 < poisson_ratio < 0.5:
        raise ValueError(f"poisson_ratio = {poisson_ratio!r}: must lie in (-1, 0.5)")
    lame_lambda = 2.0 * poisson_ratio / (1.0 - 2.0 * poisson_ratio)
    d, v = ufl.TrialFunction(space), ufl.TestFunction(space)

    def eps(w):
        return ufl.sym(ufl.grad(w))

    return (2.0 * ufl.inner(eps(d), eps(v)) + lame_lambda * ufl.div(d) * ufl.div(v)) * ufl.dx


def node_to_dof(mesh, space) -> np.ndarray:
    """For each local geometry node, its (block) dof in ``space``, the vector Lagrange space of the
    geometry's degree: cell by cell the two dofmaps list the same nodes in the same order."""
    geometry_dofs = mesh.geometry.dofmap.array
    space_dofs = space.dofmap.list.array
    node_dof = np.empty(mesh.geometry.x.shape[0], dtype=np.int64)
    node_dof[geometry_dofs] = space_dofs
    return node_dof


def _max_norm(vectors: np.ndarray) -> float:
    """Largest Euclidean norm of the rows of ``vectors`` (0 when there are none)."""
    return float(np.linalg.norm(vectors, axis=1).max()) if vectors.size else 0.0
