"""The extrapolation factor A_j of seed eq. 10: how many real crank cycles one simulated cycle
stands for in wear block j.

- ``fixed``: A_j = A (the seed: 5000) for every block, the last block shortened to end exactly at
  the requested number of cycles.
- ``adaptive`` (after Mukras, Kim, Mauntler, Schmitz & Sawyer, Wear 266 (2009) 822-831): A_j
  bounds the largest depth increment of the block to a fraction f of the radial height h_e of
  the bore's element row, within [1, A_max]. Fast wear (a fresh, non-conforming bore) gets short
  blocks; slow wear after the bore has conformed gets long ones. The geometry, hence the
  pressure, then changes by at most f h_e between two contact analyses, which keeps the
  linearisation of the implicit wear step (:func:`fewear.wear.archard.block_wear`) valid.
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


def extrapolate_block(settings: ExtrapolationSettings, increment_for, element_height_m: float,
                      remaining_cycles: int):
    """Choose A_j and return ``(A_j, *increment_for(A_j))``; ``increment_for(A)`` gives the block's
    depth increment (m, per node) first in what it returns.

    "fixed": A_j = min(A, remaining). "adaptive": the largest A_j <= min(A_max, remaining) whose
    largest depth increment stays within f h_e, found by shrinking A_j in proportion to the
    overshoot (the increment grows about linearly with A_j; at most 12 trials, A_j >= 1; if
    none is within f h_e, the last one tried, with its own increment).
    """
    if settings.mode == "fixed":
        cycles = int(min(max(math.floor(settings.factor), 1), remaining_cycles))
        return (cycles, *increment_for(cycles))
    limit = settings.max_depth_increment_fraction * element_height_m
    cycles = int(min(max(math.floor(settings.max_factor), 1), remaining_cycles))
    outcome = increment_for(cycles)
    for _ in range(11):
        peak = float(np.max(outcome[0]))
        if peak <= limit or cycles == 1:
            break
        cycles = max(1, math.floor(0.95 * cycles * limit / peak))
        outcome = increment_for(cycles)
    return (cycles, *outcome)
