"""What the joint generators share: the seeds of their data sets (one per cause and index, one per
pair of causes and index) and the believed config they load. Each generator keeps its own laws,
lab and instruments, written without reading the others'."""

from __future__ import annotations

from dataclasses import dataclass
from itertools import combinations
from pathlib import Path

import numpy as np


def _checked_index(index) -> int:
    """``index`` as a data set's number, 0-99; a ValueError naming it otherwise."""
    if isinstance(index, bool) or not (isinstance(index, (int, np.integer)) and 0 <= index <= 99):
        raise ValueError(f"data set index {index!r}: expected a whole number in 0-99")
    return int(index)


@dataclass(frozen=True)
class SeedPlan:
    """A generator's seeds: data set ``index`` of cause ``causes[i]`` has the seed
    ``base`` + 100 i + index; of the pair ``pairs[j]``, ``pair_base`` + 100 j + index (bases far
    enough apart that no two data sets of any generator share a seed)."""

    causes: tuple[str, ...]
    base: int
    pair_base: int | None = None

    @property
    def pairs(self) -> tuple[tuple[str, str], ...]:
        """The pairs of distinct hidden causes (not "none"), each in :attr:`causes` order."""
        return tuple(combinations([cause for cause in self.causes if cause != "none"], 2))

    def seed(self, cause: str, index: int) -> int:
        """The seed of data set ``index`` (0-99) of ``cause``."""
        if cause not in self.causes:
            raise ValueError(f"unknown cause {cause!r}; expected one of {', '.join(self.causes)}")
        return self.base + 100 * self.causes.index(cause) + _checked_index(index)

    def checked_pair(self, pair) -> tuple[str, str]:
        """``pair`` as a tuple of :attr:`pairs`; a ValueError naming it otherwise."""
        candidate = tuple(pair) if isinstance(pair, (tuple, list)) else None
        if candidate not in self.pairs:
            raise ValueError(f"cause pair {pair!r}: expected one of {self.pairs} (two distinct "
                             "causes other than 'none', in CAUSES order)")
        return candidate

    def pair_seed(self, pair, index: int) -> int:
        """The seed of two-cause data set ``index`` (0-99) of ``pair``."""
        pair = self.checked_pair(pair)
        return self.pair_base + 100 * self.pairs.index(pair) + _checked_index(index)


def believed_config(path: Path) -> dict:
    """The believed config (``path`` merged onto the defaults) with the run sections."""
    from fewear.io.config import load_config
    from fewear.loop.settings import run_sections

    return load_config(path, run_sections())
