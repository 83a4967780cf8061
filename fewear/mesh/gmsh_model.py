"""A gmsh model built on rank 0 and distributed as a DOLFINx mesh (the bushing's and the flat's).

DOLFINx 0.5.2's ``gmshio.model_to_mesh`` reads the model on one rank and distributes the mesh;
the other ranks call it too, with no model.
"""

from __future__ import annotations

from collections.abc import Callable

import gmsh


def distributed_mesh(comm, model_name: str, build: Callable[[], None]):
    """``(mesh, cell_tags, facet_tags)`` on ``comm`` of the 2-D model that ``build()`` makes in
    the current gmsh model (geometry, physical groups, generated mesh), run on rank 0 only;
    gmsh is finalised afterwards, also when ``build`` fails. The mesh is named
    ``model_name``."""
    from dolfinx.io import gmshio

    model_rank = 0
    if comm.rank == model_rank:
        gmsh.initialize()
        gmsh.option.setNumber("General.Terminal", 0)
        gmsh.model.add(f"fewear_{model_name}")
        try:
            build()
            mesh, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, comm, model_rank, gdim=2)
        finally:
            gmsh.finalize()
    else:
        mesh, cell_tags, facet_tags = gmshio.model_to_mesh(gmsh.model, comm, model_rank, gdim=2)
    mesh.name = model_name
    return mesh, cell_tags, facet_tags
