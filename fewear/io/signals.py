"""Signals held while files move into place, so that an interruption finds all of them or
none (:mod:`fewear.io.output`, :mod:`fewear.io.transaction`)."""

from __future__ import annotations

from contextlib import contextmanager


@contextmanager
def signals_held():
    """Hold Ctrl-C, SIGTERM and SIGHUP while the outputs move into place, and deliver them right
    after: an interruption then finds the folder with all of them or none. (The Python handlers
    are swapped, not the signal mask: another thread may take a signal the main thread masks.)"""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread():
        yield
        return
    caught: list[int] = []
    previous = {signum: signal.signal(signum, lambda signum, frame: caught.append(signum))
                for signum in (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)}
    try:
        yield
    finally:
        for signum, handler in previous.items():
            signal.signal(signum, handler)
        if caught:
            handler = previous[caught[0]]
            if callable(handler):
                handler(caught[0], None)
            elif handler == signal.SIG_DFL:
                signal.raise_signal(caught[0])
