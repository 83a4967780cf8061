"""A flat worn by a rigid cylinder sliding over it: block on ring with the ring unworn (DOLFINx).

The flat of :mod:`fewear.contact.flat` under the normal force P, the ring sliding over every node
in contact by an imposed distance (Cruzado et al., Rev. Metal. 46 (2010) 106-114), in wear steps:
Archard's law (J. Appl. Phys. 24 (1953) 981) taken implicitly (backward Euler, stable at any step
because conformal wear is stiff), then the top moved to the worn flat without re-meshing.
Method notes: docs/scar.md.
"""

from __future__ import annotations

import time
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from mpi4py import MPI

from fewear.contact.flat import FlatContactSolver
from fewear.contact.params import FlatContactProblem
from fewear.contact.result import ContactResult
from fewear.loop.settings import SlidingWearSettings
from fewear.mesh.flat import worn_node_y_m
from fewear.mesh.quality import MeshQuality, QualityMeter
from fewear.parallel import release_petsc_garbage
from fewear.wear.archard import cycle_wear_depth_m
from fewear.wear.state import FlatWearState


@dataclass(frozen=True)
class FlatWearStep:
    """One wear step: the distance slid at its end (m), its contact (largest nodal pressure, Pa;
    the loaded strip's half-width, m: the outermost loaded node's |x|) and the largest depth at
    its end (m)."""

    sliding_distance_m: float
    max_pressure_Pa: float
    contact_half_width_m: float
    max_depth_m: float


@dataclass(frozen=True)
class FlatWearRun:
    """The worn flat after the run: ``state``; ``steps`` (a :class:`FlatWearStep` each);
    ``unworn_contact``: the contact on the unworn flat (no wear compliance: Hertz);
    ``worn_top_xy_m`` (n, 2): the worn mesh's top nodes, in the order of x;
    ``unworn_quality``, ``quality``: the mesh's :class:`MeshQuality` as made and worn;
    ``wall_time_s``."""

    state: FlatWearState
    steps: tuple[FlatWearStep, ...]
    unworn_contact: ContactResult
    worn_top_xy_m: np.ndarray
    unworn_quality: MeshQuality
    quality: MeshQuality
    wall_time_s: float


def loaded_half_width_m(result: ContactResult) -> float:
    """The outermost loaded node's |x| (m); 0 without contact."""
    loaded = np.abs(result.x_m[result.pressure_Pa > 0.0])
    return float(loaded.max()) if loaded.size else 0.0


def run_flat_wear(problem: FlatContactProblem, settings: SlidingWearSettings,
                  comm=MPI.COMM_WORLD,
                  report: Callable[[FlatWearStep], None] | None = None) -> FlatWearRun:
    """Wear the flat of ``problem`` by ``settings`` (module docstring); ``report`` is called with
    every step (e.g. a progress line)."""
    start = time.perf_counter()
    solver = FlatContactSolver(problem, comm)
    meter = QualityMeter(solver.mesh, solver.facet_tags)
    unworn_quality = meter.measure()
    made_xy = solver.mesh.geometry.x[:, :2].copy()
    unworn_contact = solver.solve(settings.normal_force_N)
    state = FlatWearState.unworn(solver.bore.points[:, 0])
    k, slide = settings.wear_coefficient_m2_N, settings.slide_m
    steps = []
    for _ in range(settings.wear_steps):
        result = solver.solve(settings.normal_force_N, wear_compliance_m_per_Pa=k * slide)
        state = state.worn_by(cycle_wear_depth_m(k, result.pressure_Pa[None, :], slide), slide)
        solver.mesh.geometry.x[:, 1] = worn_node_y_m(made_xy, problem.geometry, state.depth_at)
        solver.update_geometry()
        release_petsc_garbage(solver.mesh.comm)  # the stiffness the move replaced
        steps.append(FlatWearStep(state.sliding_distance_m, result.max_pressure_Pa,
                                  loaded_half_width_m(result), float(state.depth_m.max())))
        if report is not None:
            report(steps[-1])
    return FlatWearRun(state, tuple(steps), unworn_contact, solver.bore.points.copy(),
                       unworn_quality, meter.measure(),
                       time.perf_counter() - start)
