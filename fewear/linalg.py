"""PETSc's direct solvers as fewear's FE stages use them: an operator factorised once, then
solved with many times (the contact's stiffness, the flat's, the ALE extension)."""

from __future__ import annotations

from petsc4py import PETSc

FACTORISATIONS = ("lu", "cholesky")
PACKAGES = ("mumps", "petsc")


def direct_solver(comm, factorisation: str = "lu", package: str = "mumps") -> PETSc.KSP:
    """A KSP on ``comm`` that applies the ``factorisation`` of its operator ("lu"; "cholesky",
    LDL^T for a symmetric positive definite one, half the work) by ``package``: "mumps" (any
    number of ranks; its factors also give selected entries of the inverse,
    :func:`fewear.contact.condensed.inverse_block`) or "petsc" (PETSc's own, one rank, in
    nested-dissection order: its triangular solves cost a fraction of MUMPS's on the meshes
    here)."""
    if factorisation not in FACTORISATIONS or package not in PACKAGES:
        raise ValueError(f"direct_solver({factorisation!r}, {package!r}): expected one of "
                         f"{FACTORISATIONS} by one of {PACKAGES}")
    solver = PETSc.KSP().create(comm)
    solver.setType("preonly")
    factor = solver.getPC()
    factor.setType(factorisation)
    factor.setFactorSolverType(package)
    if package == "petsc":
        factor.setFactorOrdering("nd")
    return solver
