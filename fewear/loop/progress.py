"""A rod model's run so far: the wear state, the block records, the mesh snapshots, the counts
and the stage times. What a checkpoint stores and the outputs are written from."""

from __future__ import annotations

import time
from contextlib import contextmanager
from dataclasses import dataclass, field

import numpy as np

from fewear.wear.state import WearState

STAGES = ("dynamics", "contact", "wear", "mesh")


@dataclass(frozen=True)
class BlockRecord:
    """One wear block: cycles at its end, the cycles it covered (the sum of its wear steps'
    A_j), the depth profile after it (at the state's node angles), and the most its simulated
    cycles saw over its wear steps (contact pressure; depth per cycle: Archard's plus the
    impacts'). ``inner_cycles`` (k,) and ``inner_depth_m`` (k, n): the cycles and depth profile
    after each of its wear steps but the last (none with one step per block): the bore's
    history at the loop's own resolution, not only at the ends of the dynamics' blocks."""

    cycles: int
    block_cycles: int
    depth_m: np.ndarray
    peak_contact_force_N: float
    impacts: int
    max_contact_pressure_Pa: float
    max_depth_per_cycle_m: float
    inner_cycles: np.ndarray
    inner_depth_m: np.ndarray


@dataclass
class LoopCounts:
    """What the loop counts over a case's run (their one holder; the bushing and the block add to
    them): ALE moves and re-meshes of the bushing, load steps solved again from a cold start,
    solved without the Coulomb traction, and dropped (no contact equilibrium, no wear)."""

    ale_moves: int = 0
    remeshes: int = 0
    contact_retries: int = 0
    frictionless_steps: int = 0
    dropped_steps: int = 0


@dataclass
class CaseProgress:
    """A rod model's run so far: what a checkpoint stores and the outputs are written from.

    ``state``: the worn bore (the one source of the geometry); ``mechanism``: the mechanism's
    state after the last block (the next block's warm start); ``snapshots``: the mesh node
    coordinates after every block (the first the unworn mesh), for the node numbers ``node_ids``
    and ``cells``; ``meshed_xy_m``: the current mesh's nodes as made (the reference of its
    motion and quality)."""

    state: WearState
    mechanism: object = None  # fewear.mbd.slider_crank.MechanismState of the last block
    records: list[BlockRecord] = field(default_factory=list)
    snapshots: list[np.ndarray] = field(default_factory=list)
    node_ids: np.ndarray | None = None
    cells: np.ndarray | None = None
    meshed_xy_m: np.ndarray | None = None
    counts: LoopCounts = field(default_factory=LoopCounts)
    stage_wall_time_s: dict = field(default_factory=lambda: dict.fromkeys(STAGES, 0.0))

    @property
    def wall_time_s(self) -> float:
        return float(sum(self.stage_wall_time_s.values()))


@contextmanager
def timed(times: dict, stage: str):
    """Add the wall time of the ``with`` block to ``times[stage]`` (s)."""
    start = time.perf_counter()
    try:
        yield
    finally:
        times[stage] += time.perf_counter() - start
