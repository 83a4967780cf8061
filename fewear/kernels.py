"""The compile of fewear's kernels, kept out of :mod:`fewear.jit` (the decorator every kernel
module imports) so that the kernels and their compile form no import circle."""

from __future__ import annotations

import numba

from fewear.contact.condensed_newton import compile_contact
from fewear.contact.flat_newton import compile_flat
from fewear.jit import holds_compiled_code
from fewear.mbd.slider_crank import compile_dynamics


def compile_kernels(report=None) -> None:
    """Compile, or load from the cache, the kernels of a wear run: the dynamics'
    (:func:`fewear.mbd.slider_crank.compile_dynamics`), the bushing's contact
    (:func:`fewear.contact.condensed_newton.compile_contact`) and the flat's of a scar
    (:func:`fewear.contact.flat_newton.compile_flat`). ``report(text)``, if given, is
    told first when the cache holds no compiled code (the first run after a change of the
    sources compiles for one to a few minutes), so that the user is not left without a word;
    with no cache that can be written (:func:`fewear.jit.choose_cache_dir`), every run compiles."""
    cache = numba.config.CACHE_DIR
    if report is not None and not _cached():
        report("compiling the dynamics and contact kernels (" + (
            "once after a change of fewear's sources, one to a few minutes; later runs load them)"
            if cache else "one to a few minutes, on every run: no cache folder can be written)"))
    compile_dynamics()
    compile_contact()
    compile_flat()


def compile_kernels_unless_cached(report=None) -> None:
    """:func:`compile_kernels` where the cache holds no compiled code for these sources yet, so
    that the worker processes or ranks started afterwards load the kernels instead of all
    compiling them at once; nothing where it does: each worker loads what it uses, and loading
    them here as well held the run's start back by about 2 s."""
    if not _cached():
        compile_kernels(report)


def _cached() -> bool:
    """Whether numba's cache folder holds compiled code for these sources."""
    cache = numba.config.CACHE_DIR
    return bool(cache) and holds_compiled_code(cache)
