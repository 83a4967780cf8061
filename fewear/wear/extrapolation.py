"""The extrapolation factor A_j of seed eq. 10: how many real crank cycles one simulated cycle
stands for in wear block j.

- ``fixed``: A_j = A (the seed: 5000) for every block, the last block shortened to end exactly at
  the requested number of cycles.
- ``adaptive`` (after Mukras, Kim, Mauntler, Schmitz & Sawyer, Wear 266 (2009) 822-831): A_j
  bounds the largest depth increment of the block to a fraction f of the radial height h_e of
  the bore's element row, within [1, A_max]. Fast wear (a fresh, non-conforming bore) gets short
  blocks; slow wear after the bore has conformed gets long ones. The geometry, hence the
  pressure, then changes by at most f h_e between two contact analyses, which keeps the
  linearisation of the wear step (:func:`fewear.wear.archard.block_wear`) valid.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from fewear.errors import FewearInputError

EXTRAPOLATION_MODES = ("fixed", "adaptive")


@dataclass(frozen=True)
class ExtrapolationSettings:
    """``mode`` "fixed" or "adaptive"; ``factor``: A for "fixed"; ``max_factor``: A_max and
    ``max_depth_increment_fraction``: f for "adaptive" (see the module docstring)."""

    mode: str = "fixed"
    factor: float = 5000.0
    max_factor: float = 50000.0
    max_depth_increment_fraction: float = 0.1

    def __post_init__(self):
        if self.mode not in EXTRAPOLATION_MODES:
            raise FewearInputError(
                f"[wear_loop] extrapolation = {self.mode!r}: expected one of "
                f"{', '.join(map(repr, EXTRAPOLATION_MODES))}")
        for name in ("factor", "max_factor"):
            value = getattr(self, name)
            if not (math.isfinite(value) and value >= 1.0):
                raise FewearInputError(f"[wear_loop] {_KEYS[name]} = {value!r}: expected >= 1")
        fraction = self.max_depth_increment_fraction
        if not (math.isfinite(fraction) and 0.0 < fraction <= 1.0):
            raise FewearInputError(
                f"[wear_loop] max_depth_increment_fraction = {fraction!r}: expected a fraction "
                "of the bore element height in (0, 1]")


_KEYS = {"factor": "extrapolation_factor", "max_factor": "max_extrapolation_factor"}


MAX_TRIALS = 12
"""Evaluations of a block's increment that the adaptive search may make."""

FILLED_SHARE = 0.8
"""The adaptive search stops at a block whose largest increment fills this share of f h_e."""


def extrapolate_block(settings: ExtrapolationSettings, increment_for, element_height_m: float,
                      remaining_cycles: int):
    """Choose A_j and return ``(A_j, *increment_for(A_j))``; ``increment_for(A)`` gives the block's
    depth increment (m, per node) first in what it returns.

    "fixed": A_j = min(A, remaining). "adaptive": the largest A_j <= min(A_max, remaining) whose
    largest depth increment stays within f h_e, searched from the cap: each next trial A_j is
    scaled in proportion to the increment's shortfall or overshoot (0.95 A f h_e / peak: exact
    when the increment grows linearly with A_j), kept strictly between the largest block found
    within the bound and the smallest found beyond it (else their geometric mean). The
    linearised step's increment is not linear in A_j (it levels off in the stiff modes and
    can grow faster than A_j far beyond its validity), so one proportional shrink from the cap
    can land far below the bound. The search stops at a block within the bound that fills at
    least ``FILLED_SHARE`` of it, or when the bracket closes (within 10 %), after at most
    ``MAX_TRIALS`` trials; if none is within f h_e, the last one tried is returned, with its
    own increment.
    """
    if settings.mode == "fixed":
        cycles = int(min(max(math.floor(settings.factor), 1), remaining_cycles))
        return (cycles, *increment_for(cycles))
    limit = settings.max_depth_increment_fraction * element_height_m
    cycles = int(min(max(math.floor(settings.max_factor), 1), remaining_cycles))
    within, beyond = None, None  # (cycles, outcome) of the largest block within the bound; A
    outcome = increment_for(cycles)
    for _ in range(MAX_TRIALS - 1):
        peak = float(np.max(outcome[0]))
        if peak <= limit:
            within = (cycles, outcome)
            if peak >= FILLED_SHARE * limit or beyond is None:
                break
        else:
            beyond = cycles
        lower = within[0] if within else 0
        if cycles == 1 and within is None or beyond - lower <= max(1, 0.1 * lower):
            break
        cycles = _next_trial(cycles, peak, limit, lower, beyond)
        outcome = increment_for(cycles)
    else:
        if float(np.max(outcome[0])) <= limit:
            within = (cycles, outcome)
    if within is None:
        return (cycles, *outcome)
    return (within[0], *within[1])


def _next_trial(cycles: int, peak: float, limit: float, lower: int, beyond: int) -> int:
    """The next block size of the adaptive search: the proportional guess, if it lies strictly
    between ``lower`` (largest within the bound, 0: none) and ``beyond`` (smallest beyond it),
    else their geometric mean (``lower`` 0: one tenth of ``beyond``)."""
    guess = math.floor(0.95 * cycles * limit / peak) if peak > 0.0 else beyond - 1
    if lower < guess < beyond:
        return guess
    middle = math.sqrt(lower * beyond) if lower else 0.1 * beyond
    return int(min(max(math.floor(middle), lower + 1, 1), beyond - 1))
