"""How every diagnosis declares a cause it may name."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Cause:
    """A cause a diagnosis may name: ``name`` (as the config's ``candidates`` and
    ``diagnosis.json`` write it), ``meaning`` (what naming it says), ``forms`` (the names of the
    forms it is fitted in; the best-fitting one names its parameters; "" where it has one) and
    ``untestable_reason``: None where the cause can always be fitted, else a function of what
    the data kind knows before fitting (the tribometer: the quantities measured; the joint: the
    believed config; the scar: the case's wear settings) that says why it cannot be, or None."""

    name: str
    meaning: str
    forms: tuple[str, ...]
    untestable_reason: Callable[[Any], str | None] | None = None

    def why_untestable(self, known: Any) -> str | None:
        """Why the cause cannot be fitted given ``known`` (None: it can)."""
        return None if self.untestable_reason is None else self.untestable_reason(known)
