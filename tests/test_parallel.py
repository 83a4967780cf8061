"""Runs side by side in worker processes (fewear.parallel): a pool kept for a block of calls."""

from __future__ import annotations

import os

import pytest

from fewear import parallel

needs_two_cores = pytest.mark.skipif(parallel.usable_cores() < 2, reason="one core only")


def _workers() -> set[int]:
    """The processes that ran a batch of calls (the calls' results: their process ids)."""
    return set(parallel.side_by_side(os.getpid, [()] * 4))


@needs_two_cores
def test_a_kept_pool_runs_every_batch_of_its_block_and_is_stopped_after():
    with parallel.workers_kept():
        first = _workers()
        with parallel.workers_kept():  # a nested block shares the pool
            second = _workers()
        third = _workers()
    after = _workers()
    kept = first | second | third  # not more processes than one pool has
    assert os.getpid() not in kept and len(kept) <= parallel.usable_cores()
    assert after.isdisjoint(kept)  # a pool of its own, started and stopped for the batch
    assert parallel._kept.stack is None and parallel._kept.pool is None


@needs_two_cores
def test_without_a_kept_pool_each_batch_starts_its_own():
    assert _workers().isdisjoint(_workers())


def test_a_block_whose_calls_need_no_workers_starts_none():
    with parallel.workers_kept():
        assert parallel.side_by_side(os.getpid, [()]) == [os.getpid()]  # one call: here
        assert parallel._kept.pool is None


@needs_two_cores
def test_every_batch_of_a_kept_pool_is_prepared_here_first():
    """The pool may have been started by a batch without ``prepare`` (fits before runs): a later
    batch's ``prepare`` still runs here before its calls are handed out."""
    prepared = []
    with parallel.workers_kept():
        _workers()
        parallel.side_by_side(os.getpid, [()] * 2, prepare=lambda: prepared.append(os.getpid()))
    assert prepared == [os.getpid()]


def _alive(pid: int) -> bool:
    """Whether process ``pid`` runs (a zombie, dead but not yet reaped, does not)."""
    try:
        with open(f"/proc/{pid}/stat") as stat:
            return stat.read().rsplit(")", 1)[1].split()[0] != "Z"
    except FileNotFoundError:
        return False


@needs_two_cores
@pytest.mark.skipif(not os.path.exists("/proc/self/stat"), reason="needs Linux's /proc")
def test_workers_end_with_a_parent_killed_outright():
    """A parent killed by SIGKILL (no pool left to terminate its workers) takes its workers
    with it at once, though each is busy with a call of a minute."""
    import signal
    import subprocess
    import sys
    import time

    parent = subprocess.Popen([sys.executable, "-c", (
        "import os, time\n"
        "from fewear import parallel\n"
        "with parallel.workers_kept():\n"
        "    print(*parallel.side_by_side(os.getpid, [()] * 2), flush=True)\n"
        "    parallel._kept.pool.starmap_async(time.sleep, [(60.0,)] * 2)\n"
        "    time.sleep(60.0)\n")], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    workers = [int(pid) for pid in parent.stdout.readline().split()]
    assert len(workers) == 2 and all(map(_alive, workers))
    time.sleep(0.5)  # the workers are in their minute's call
    parent.send_signal(signal.SIGKILL)
    parent.wait()
    deadline = time.monotonic() + 10.0
    while any(map(_alive, workers)) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not any(map(_alive, workers))
