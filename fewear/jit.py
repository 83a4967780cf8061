"""The decorator of fewear's compiled kernels: ``@compiled`` = ``numba.njit(cache=True,
nogil=True)``.

Compiled are the multibody dynamics (:mod:`fewear.mbd`, the whole step loop) and the contact
Newton's kernels (:mod:`fewear.contact`: the free region's corners and vertices, gaps, the line
search, and on the condensed path the whole coupled Newton iteration and the wear step's
pressure sensitivity). The machine code is cached on disk, so only the
first process after a change of the sources pays the compile (see README, "Dynamics");
:func:`compile_kernels` compiles before worker processes start, so that they load the code
instead of each compiling it. The kernels release Python's global interpreter lock
(``nogil``): the wear loop runs the next block's dynamics in a thread while this block's mesh
stage and checkpoint run (:func:`fewear.loop.block.predict_case`).

numba keys each function's cache on its own source file only, but a compiled caller inlines its
callees from other files (the integrator's step loop holds the whole dynamics), so a change of
``fewear/mbd/contact.py`` would leave a stale step loop in the cache. The cache therefore lives
in a directory named after a digest of the sources of all packages that compile
(``PACKAGES``) and of this module, ``__pycache__/fewear-jit-<digest>`` next to this module or,
when that is read-only (an installed package), in numba's user-wide cache directory or else the
temporary directory; ``NUMBA_CACHE_DIR``, if set, takes the place of ``__pycache__``. The
directories of other digests in ``__pycache__`` (older versions of this source tree) are removed.
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


def compile_kernels(report=None) -> None:
    """Compile, or load from the cache, the kernels of a wear run: the dynamics'
    (:func:`fewear.mbd.slider_crank.compile_dynamics`) and the contact's
    (:func:`fewear.contact.condensed_newton.compile_contact`). ``report(text)``, if given, is
    told first when the cache holds no compiled code (the first run after a change of the
    sources compiles for about a minute: 30 s the dynamics, 37 s the contact, on a 2-core
    machine), so that the user is not left without a word."""
    from fewear.contact.condensed_newton import compile_contact
    from fewear.mbd.slider_crank import compile_dynamics

    if report is not None and not holds_compiled_code(numba.config.CACHE_DIR):
        report("compiling the dynamics and contact kernels (once after a change of fewear's "
               "sources, about a minute; later runs load them)")
    compile_dynamics()
    compile_contact()
