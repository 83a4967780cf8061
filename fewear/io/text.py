"""Reading a user's text file (a config, a CSV of measured data) with every way it can fail
turned into a :class:`~fewear.errors.FewearInputError` naming the file and what is allowed."""

from __future__ import annotations

from pathlib import Path

from fewear.errors import FewearInputError, shorten

MAX_TEXT_FILE_BYTES = 200 * 1024 * 1024
"""A config or measured-data file larger than this (200 MB) is no such file."""


def read_text_file(path: str | Path, what: str) -> str:
    """The text of ``path`` (UTF-8, an optional byte-order mark dropped); ``what`` names the kind
    of file in the errors ("config file", "measured data")."""
    path = Path(path)
    try:
        if path.is_dir():
            raise FewearInputError(f"{what} {path} is a folder; expected a file")
        size = path.stat().st_size
        if size > MAX_TEXT_FILE_BYTES:
            raise FewearInputError(
                f"{what} {path} has {size:,} bytes; a {what} has at most "
                f"{MAX_TEXT_FILE_BYTES:,}")
        data = path.read_bytes()
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
