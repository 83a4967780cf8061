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

FIRST_TRIAL_SHARE = 0.95
"""Given the previous wear step's block, the search starts where its peak rate reaches this share
of f h_e, the search's own aim: one trial while the rate changed by -16 % to +5 % (0.9, the
band's middle, took 3 % more wear steps: the blocks filled less of the bound)."""


def extrapolate_block(settings: ExtrapolationSettings, increment_for, element_height_m: float,
                      remaining_cycles: int, previous: tuple[int, float] | None = None):
    """Choose A_j and return ``(A_j, *increment_for(A_j))``; ``increment_for(A)`` gives the block's
    depth increment (m, per node) first in what it returns.

    "fixed": A_j = min(A, remaining). "adaptive": a large A_j <= min(A_max, remaining) whose
    largest depth increment (its peak) stays within f h_e, searched from the cap or, given the
    ``previous`` wear step's (A_j, peak) on the same orbit, from the A_j at which that step's
    peak rate reaches ``FIRST_TRIAL_SHARE`` of f h_e (the rate changes little from one wear step
    to the next: 1.2 trials a step where the cap took 2.8, on the paper's rigid rod). The
    linearised step's increment is not linear in A_j (it levels off in the stiff modes and can
    grow far faster than A_j beyond its validity, up to overflow), so the search brackets the
    bound between the largest block found within it and the smallest found beyond it: the next
    trial aims at 0.95 f h_e on the power law through the bracket's two ends (with one end
    only, in proportion to the peak: exact for a linear increment; upwards while no block was
    beyond), and where that guess is not strictly inside the bracket, or a peak is zero or not
    finite, it takes the bracket's geometric mean. It stops at a block within the bound that
    fills at least ``FILLED_SHARE`` of it or is the cap, when the bracket closes (within 10 %),
    or after ``MAX_TRIALS`` trials, and returns the largest block found within the bound; if
    none is, the last one tried, with its own increment.
    """
    if settings.mode == "fixed":
        cycles = int(min(max(math.floor(settings.factor), 1), remaining_cycles))
        return (cycles, *increment_for(cycles))
    limit = settings.max_depth_increment_fraction * element_height_m
    cap = int(min(max(math.floor(settings.max_factor), 1), remaining_cycles))
    cycles = cap if previous is None else _first_trial(previous, limit, cap)
    within = beyond = None  # (cycles, peak, outcome) of the largest block within; (cycles, peak)
    for trial in range(MAX_TRIALS):
        outcome = increment_for(cycles)
        peak = float(np.max(outcome[0]))
        if peak <= limit:  # False for NaN: a step that overflowed is beyond the bound
            within = (cycles, peak, outcome)
            if peak >= FILLED_SHARE * limit or cycles == cap:
                break
        else:
            beyond = (cycles, peak)
        lower = within[0] if within else 0
        if beyond is not None and ((within is None and cycles == 1)
                                   or beyond[0] - lower <= max(1, 0.1 * lower)):
            break
        if trial < MAX_TRIALS - 1:
            cycles = _next_trial(within, beyond, limit, cap)
    if within is None:
        return (cycles, *outcome)
    return (within[0], *within[2])


def _first_trial(previous: tuple[int, float], limit: float, cap: int) -> int:
    """The block at which the ``previous`` step's (cycles, peak) rate reaches
    ``FIRST_TRIAL_SHARE`` ``limit``, within [1, ``cap``] (the cap for a peak that is not a
    positive number)."""
    cycles, peak = previous
    if not (math.isfinite(peak) and peak > 0.0):
        return cap
    return int(min(max(math.floor(cycles * FIRST_TRIAL_SHARE * limit / peak), 1), cap))


def _next_trial(within, beyond, limit: float, cap: int) -> int:
    """The next block size of the adaptive search between ``within`` (cycles, peak, ...) of the
    largest block within the bound (None: none yet) and ``beyond`` (cycles, peak) of the smallest
    beyond it: 0.95 ``limit`` on the power law peak = a A^b through both ends (b = 1 with one
    end), if strictly inside the bracket, else the bracket's geometric mean (with no block
    within: a tenth of ``beyond``). With none beyond yet: up from ``within`` in proportion to
    its peak, by at least one cycle and at most to ``cap``."""
    target = 0.95 * limit
    if beyond is None:
        low, low_peak = within[0], within[1]
        guess = cap if low_peak <= 0.0 else math.floor(low * target / low_peak)
        return int(min(max(guess, low + 1), cap))
    high, high_peak = beyond
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
