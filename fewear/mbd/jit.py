"""The decorator of the compiled multibody kernels: ``@compiled`` = ``numba.njit(cache=True)``.

The machine code is cached on disk, so only the first process after a change of the sources pays
the compile (see README, "Dynamics"). numba keeps the cache in ``__pycache__`` next to the sources
or, when that is read-only (an installed package), in the user's cache directory; when neither is
writable it would fail at import, so the cache then goes to the temporary directory
(``NUMBA_CACHE_DIR``, if set, is always used).
"""

from __future__ import annotations

import os
import tempfile

import numba
from numba.misc.appdirs import AppDirs


def _writable(path: str) -> bool:
    """Whether ``path`` (or its nearest existing parent) is a directory we may write into."""
    while not os.path.exists(path):
        parent = os.path.dirname(path)
        if parent == path:
            return False
        path = parent
    return os.access(path, os.W_OK)


def _ensure_cache_dir() -> None:
    if numba.config.CACHE_DIR:
        return
    in_tree = os.path.join(os.path.dirname(os.path.abspath(__file__)), "__pycache__")
    user_wide = AppDirs(appname="numba", appauthor=False).user_cache_dir
    if not (_writable(in_tree) or _writable(user_wide)):
        numba.config.CACHE_DIR = os.path.join(tempfile.gettempdir(), "fewear-numba-cache")


_ensure_cache_dir()
compiled = numba.njit(cache=True)
