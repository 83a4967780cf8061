"""Errors that the command line reports as a message (no traceback, exit status 2)."""

import math


class FewearInputError(ValueError):
    """Bad input from the user: a config value, a data file, an argument or an output folder.

    The message names the bad value and says what is allowed.
    """


def require(ok: bool, message: str) -> None:
    """Raise :class:`FewearInputError` with ``message`` (naming the value and what is allowed)
    unless ``ok``."""
    if not ok:
        raise FewearInputError(message)


def require_finite_positive(name: str, value: float) -> None:
    """``value`` must be a finite number > 0, else :class:`FewearInputError` naming ``name``."""
    require(
        isinstance(value, (int, float)) and math.isfinite(value) and value > 0.0,
        f"{name} = {value!r}: must be a finite number > 0",
    )
