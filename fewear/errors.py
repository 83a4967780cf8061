"""Errors that the command line reports as a message (no traceback, exit status 2)."""

import errno
import math
import os


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


def require_whole_number(name: str, value: int, smallest: int, largest: int) -> None:
    """``value`` must be an int (not a bool) in [``smallest``, ``largest``], else
    :class:`FewearInputError` naming ``name``."""
    require(
        isinstance(value, int) and not isinstance(value, bool) and smallest <= value <= largest,
        f"{name} = {value!r}: must be a whole number in [{smallest}, {largest}]",
    )


def require_poisson_ratio(name: str, value: float) -> None:
    """A Poisson ratio of an isotropic elastic material lies in (-1, 0.5)."""
    require(
        isinstance(value, (int, float)) and math.isfinite(value) and -1.0 < value < 0.5,
        f"{name} = {value!r}: must lie in (-1, 0.5)",
    )


SHORT_VALUE_CHARS = 80
"""A value echoed in an error message is shortened to about this many characters."""
LONG_RUN_CHARS = 120
"""At the command line's edge, any run of this many characters without a space (a pasted value,
a header name, a path) is shortened; the whole message to :data:`MAX_MESSAGE_CHARS`."""
MAX_MESSAGE_CHARS = 1000


def shorten(value, limit: int = SHORT_VALUE_CHARS) -> str:
    """``value`` (a string as it is, anything else as its repr) of at most about ``limit``
    characters: a longer one keeps its start and end and says how long it was."""
    text = value if isinstance(value, str) else repr(value)
    if len(text) <= limit:
        return text
    head, tail = text[: limit * 2 // 3], text[-(limit // 6):]
    return f"{head}...{tail} ({len(text):,} characters)"


def one_line(message: str) -> str:
    """``message`` as one line of bounded length for ``fewear: error:``: its lines joined, long
    runs of characters (a 1 MB value or header name) shortened, the whole capped."""
    import re

    lines = [line.strip() for line in str(message).splitlines() if line.strip()]
    joined = ""
    for line in lines:
        joined += line if not joined else (" " if joined.endswith(":") else "; ") + line
    joined = re.sub(rf"\S{{{LONG_RUN_CHARS},}}", _shortened_run, joined)
    return shorten(joined, MAX_MESSAGE_CHARS)


def _shortened_run(match) -> str:
    run = match.group(0)
    body = run.rstrip(":;,.'\")]")
    return shorten(body) + run[len(body):]


class DiskFull(OSError):
    """No space left on the disk while writing ``filename``, which needed ``needed_bytes``
    (None: unknown); reported at the command line's edge naming the folder and the size."""

    def __init__(self, filename, needed_bytes: int | None = None):
        super().__init__(errno.ENOSPC, os.strerror(errno.ENOSPC), str(filename))
        self.needed_bytes = needed_bytes


class Terminated(BaseException):
    """SIGTERM (or SIGHUP) as an exception, so that a stopped command cleans up (its staging
    folder) like one stopped by Ctrl-C; raised by the handler the command line installs."""


NOTHING_KEPT = "nothing was written: the output folder is as it was"
_interrupt_note: list = [None]


def set_interrupt_note(note) -> None:
    """From now until the command ends, an interruption (Ctrl-C, SIGTERM) is reported with
    ``note()``: what was kept and how to go on (None: :data:`NOTHING_KEPT`)."""
    _interrupt_note[0] = note


def add_interrupt_note(text: str) -> None:
    """Add ``text`` to the note of :func:`set_interrupt_note` (e.g. where an earlier result
    was kept)."""
    note = _interrupt_note[0]
    set_interrupt_note(lambda: f"{note() if note is not None else NOTHING_KEPT}; {text}")


def has_interrupt_note() -> bool:
    """Whether the running command said what an interruption keeps (:func:`set_interrupt_note`)."""
    return _interrupt_note[0] is not None


def interrupt_note() -> str:
    """The note of :func:`set_interrupt_note` (never raises: it must not hide the interruption)."""
    note = _interrupt_note[0]
    try:
        return (note() if note is not None else "") or NOTHING_KEPT
    except Exception:  # noqa: BLE001
        return NOTHING_KEPT
