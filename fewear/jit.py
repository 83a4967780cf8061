"""The decorator of fewear's compiled kernels: ``@compiled`` = ``numba.njit(cache=True,
nogil=True)``.

The machine code is cached on disk in a directory named after a digest of the sources of all
compiling packages (``PACKAGES``) and of this module, since numba keys its cache on each function's
own file while callers inline callees from other files; directories of other digests are removed.
``nogil`` lets the wear loop run dynamics in a thread. Method notes: docs/dynamics.md.
"""

from __future__ import annotations

import glob
import hashlib
import os
import shutil
import sys
import tempfile

import numba
from numba.misc.appdirs import AppDirs

HERE = os.path.dirname(os.path.abspath(__file__))
# the packages whose modules use @compiled, relative to this module's directory
PACKAGES = ("mbd", "contact")


def _writable(path: str) -> bool:
    """Whether ``path`` (or its nearest existing parent) is a directory we may write into."""
    while not os.path.exists(path):
        parent = os.path.dirname(path)
        if parent == path:
            return False
        path = parent
    return os.path.isdir(path) and os.access(path, os.W_OK)


def sources_digest() -> str:
    """A digest of the names and contents of this module and the ``PACKAGES``' Python
    sources."""
    digest = hashlib.sha256()
    paths = [os.path.abspath(__file__)] + sorted(
        path for package in PACKAGES for path in glob.glob(os.path.join(HERE, package, "*.py")))
    for path in paths:
        with open(path, "rb") as source:
            digest.update(os.path.relpath(path, HERE).encode() + b"\0" + source.read() + b"\0")
    return digest.hexdigest()[:16]


def choose_cache_dir(user_dir: str | None, digest: str) -> tuple[str | None, str]:
    """(the cache directory, a warning for the user or ""): ``fewear-jit-<digest>`` in the first
    of ``user_dir`` (``NUMBA_CACHE_DIR``), ``__pycache__`` next to this module (read-only in an
    installed package: passed over without a word), numba's user-wide cache directory and the
    temporary directory where it can be written; None when none can (numba then compiles on
    every run, about a minute, without a word of its own)."""
    bases = [os.path.join(HERE, "__pycache__"),
             AppDirs(appname="numba", appauthor=False).user_cache_dir,
             os.path.join(tempfile.gettempdir(), "fewear-numba-cache")]
    bases = [user_dir] + bases if user_dir else bases
    for base in bases:
        directory = os.path.join(base, f"fewear-jit-{digest}")
        if _writable(directory):
            if user_dir and base != user_dir:
                return directory, (
                    f"numba's cache folder {user_dir} (NUMBA_CACHE_DIR) cannot be written; "
                    f"fewear's compiled kernels are cached in {base} instead (make it "
                    "writable, or set NUMBA_CACHE_DIR to a writable folder)")
            return directory, ""
    return None, (
        f"no folder for fewear's compiled kernels can be written (tried {', '.join(bases)}): "
        "they are compiled again on every run, about a minute each; make one of them "
        "writable, or set NUMBA_CACHE_DIR to a writable folder")


WARNED = "FEWEAR_JIT_CACHE_WARNED"
"""Set in the environment once the cache's warning was shown: the worker processes and ranks
a command starts inherit it and stay quiet."""


def _use_cache_dir() -> None:
    from fewear.parallel import launcher_rank_and_size

    digest = sources_digest()
    current, warning = choose_cache_dir(numba.config.CACHE_DIR or None, digest)
    if warning and not os.environ.get(WARNED) and launcher_rank_and_size()[0] == 0:
        print(f"fewear: warning: {warning}", file=sys.stderr, flush=True)
        os.environ[WARNED] = "1"
    if current is None:
        return  # numba's own choice, which fails likewise
    base = os.path.dirname(current)
    if base == os.path.join(HERE, "__pycache__"):
        for old in glob.glob(os.path.join(base, "fewear-jit-*")):
            if old != current:
                shutil.rmtree(old, ignore_errors=True)
    numba.config.CACHE_DIR = current


_use_cache_dir()
compiled = numba.njit(cache=True, nogil=True)


def holds_compiled_code(directory: str) -> bool:
    """Whether numba's cache ``directory`` holds compiled code (its index files, ``*.nbi``)."""
    return bool(glob.glob(os.path.join(directory, "**", "*.nbi"), recursive=True))
