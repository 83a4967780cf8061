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

    "fixed": A_j = min(A, remaining). "adaptive": a large A_j <= min(A_max, remaining) whose
    largest depth increment (its peak) stays within f h_e, searched from the cap. The
    linearised step's increment is not linear in A_j (it levels off in the stiff modes and can
    grow far faster than A_j beyond its validity, up to overflow), so the search brackets the
    bound between the largest block found within it and the smallest found beyond it: the next
    trial aims at 0.95 f h_e on the power law through the bracket's two ends (with one end
    only, in proportion to the peak: exact for a linear increment), and where that guess is
    not strictly inside the bracket, or a peak is zero or not finite, it takes the bracket's
    geometric mean. It stops at a block within the bound that fills at least ``FILLED_SHARE``
    of it, when the bracket closes (within 10 %), or after ``MAX_TRIALS`` trials, and returns
    the largest block found within the bound; if none is, the last one tried, with its own
    increment.
    """
    if settings.mode == "fixed":
        cycles = int(min(max(math.floor(settings.factor), 1), remaining_cycles))
        return (cycles, *increment_for(cycles))
    limit = settings.max_depth_increment_fraction * element_height_m
    cycles = int(min(max(math.floor(settings.max_factor), 1), remaining_cycles))
    within = beyond = None  # (cycles, peak, outcome) of the largest block within; (cycles, peak)
    for trial in range(MAX_TRIALS):
        outcome = increment_for(cycles)
        peak = float(np.max(outcome[0]))
        if peak <= limit:  # False for NaN: a step that overflowed is beyond the bound
            within = (cycles, peak, outcome)
            if peak >= FILLED_SHARE * limit or beyond is None:
                break
        else:
            beyond = (cycles, peak)
        lower = within[0] if within else 0
        if (within is None and cycles == 1) or beyond[0] - lower <= max(1, 0.1 * lower):
            break
        if trial < MAX_TRIALS - 1:
            cycles = _next_trial(within, beyond, limit)
    if within is None:
        return (cycles, *outcome)
    return (within[0], *within[2])


def _next_trial(within, beyond, limit: float) -> int:
    """The next block size of the adaptive search between ``within`` (cycles, peak, ...) of the
    largest block within the bound (None: none yet) and ``beyond`` (cycles, peak) of the smallest
    beyond it: 0.95 ``limit`` on the power law peak = a A^b through both ends (b = 1 with one
    end), if strictly inside the bracket, else the bracket's geometric mean (with no block
    within: a tenth of ``beyond``)."""
    (high, high_peak), target = beyond, 0.95 * limit
    low, low_peak = (within[0], within[1]) if within else (0, 0.0)
    guess = 0
    if math.isfinite(high_peak) and high_peak > 0.0:
        exponent = 1.0
        if low_peak > 0.0:
            exponent = math.log(high_peak / low_peak) / math.log(high / low)
        if exponent > 0.0:
            guess = math.floor(high * (target / high_peak) ** (1.0 / exponent))
    if low < guess < high:
        return guess
    middle = math.sqrt(low * high) if low else 0.1 * high
    return int(min(max(math.floor(middle), low + 1, 1), high - 1))
