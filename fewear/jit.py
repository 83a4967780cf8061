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
    return os.access(path, os.W_OK)


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


def _cache_base() -> str:
    if numba.config.CACHE_DIR:
        return numba.config.CACHE_DIR
    for base in (os.path.join(HERE, "__pycache__"),
                 AppDirs(appname="numba", appauthor=False).user_cache_dir):
        if _writable(base):
            return base
    return os.path.join(tempfile.gettempdir(), "fewear-numba-cache")


def _use_cache_dir() -> None:
    base = _cache_base()
    current = os.path.join(base, f"fewear-jit-{sources_digest()}")
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
