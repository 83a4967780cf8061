"""Reading a user's text file (a config, a CSV of measured data) with every way it can fail
turned into a :class:`~fewear.errors.FewearInputError` naming the file and what is allowed."""

from __future__ import annotations

import os
import stat
from pathlib import Path

from fewear.errors import FewearInputError, shorten

KINDS = ((stat.S_ISDIR, "a folder"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
         (stat.S_ISCHR, "a character device"), (stat.S_ISBLK, "a block device"),
         (stat.S_ISSOCK, "a socket"))


def not_a_regular_file(path: str | Path) -> str:
    """'' for a regular file (or one that does not exist: its reader names that), else what it
    is ("a FIFO (named pipe)", "a folder", ...): reading one blocks, or never ends."""
    try:
        return file_kind(os.stat(path).st_mode)
    except OSError:
        return ""


def file_kind(mode: int) -> str:
    """'' for a regular file's ``st_mode``, else what the file is."""
    if stat.S_ISREG(mode):
        return ""
    return next((kind for test, kind in KINDS if test(mode)), "not a regular file")


def read_text_file(path: str | Path, what: str) -> str:
    """The text of ``path`` (UTF-8, an optional byte-order mark dropped); ``what`` names the kind
    of file in the errors ("config file", "measured data"). Refused before it is read: what is
    not a regular file, and a file beyond the size bound of its kind
    (:func:`fewear.io.limits.max_file_bytes`)."""
    path = Path(path)
    try:
        data = _read_bounded(path, what)
    except OSError as exc:
        raise FewearInputError(f"cannot read {what} {path}: {exc.strerror or exc}") from None
    try:
        text = data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        raise FewearInputError(
            f"{what} {path} line {line}: byte {shorten(data[exc.start:exc.end])} is not UTF-8 "
            "text; save the file as UTF-8 (e.g. an accented letter in another encoding)") from None
    if "\x00" in text:
        line = text.count("\n", 0, text.index("\x00")) + 1
        raise FewearInputError(
            f"{what} {path} line {line}: a NUL byte (binary data); expected a text file")
    return text


def _read_bounded(path: Path, what: str) -> bytes:
    """The bytes of a regular file within its bound; opened without blocking (a FIFO without a
    writer) and checked on the open file (no race with a rename)."""
    from fewear.io.limits import max_file_bytes

    limit = max_file_bytes(what)
    descriptor = os.open(path, os.O_RDONLY | os.O_NONBLOCK)
    try:
        status = os.fstat(descriptor)
        kind = file_kind(status.st_mode)
        if kind:
            raise FewearInputError(f"{what} {path} is {kind}; expected a regular file")
        if status.st_size > limit:
            raise FewearInputError(f"{what} {path} has {status.st_size:,} bytes; a {what} has "
                                   f"at most {limit:,} bytes")
        chunks, size = [], 0
        while size <= limit:
            chunk = os.read(descriptor, min(1 << 20, limit + 1 - size))
            if not chunk:
                break
            chunks.append(chunk)
            size += len(chunk)
    finally:
        os.close(descriptor)
    if size > limit:  # it grew while read
        raise FewearInputError(f"{what} {path} has more than {limit:,} bytes; a {what} has at "
                               f"most {limit:,} bytes")
    return b"".join(chunks)
