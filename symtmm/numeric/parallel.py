"""Batches of compiled work over the machine's cores.

The compiled kernel (:mod:`symtmm.numeric.multiword`) builds, factorises and reads each
point of a batch on its own, and releases Python's lock while it does: a batch whose
work is large enough runs in parts on :data:`WORKERS` threads, one part in the calling
thread (a 20-level chain's proofs: about half a millisecond a point in balls of two
words, ten to twenty points a batch). Small batches run whole where they are called:
a thread's start and join cost tens of microseconds, a point of the paper's example 1
ten.

The number of threads is the CPUs this process may run on (at most
:data:`MOST_WORKERS`), or ``SYMTMM_THREADS`` in the environment (``1``: no threads).
The parts' results are the same bits as one call's: every point is computed alone.

Examples
--------
>>> run_ranges(lambda lo, hi: list(range(lo, hi)), 5, work=0.0)
[[0, 1, 2, 3, 4]]
"""

from __future__ import annotations

import itertools
import os
import threading
from concurrent.futures import ThreadPoolExecutor

__all__ = ["WORKERS", "SPLIT_SECONDS", "run_ranges", "only_idle_workers"]

#: At most this many threads, whatever the machine.
MOST_WORKERS = 8


def _workers() -> int:
    env = os.environ.get("SYMTMM_THREADS", "").strip()
    if env.isdigit() and int(env) >= 1:
        return min(int(env), MOST_WORKERS)
    try:
        cpus = len(os.sched_getaffinity(0))
    except AttributeError:                  # (not Linux)
        cpus = os.cpu_count() or 1
    return max(1, min(cpus, MOST_WORKERS))


#: Threads a large batch is split over (the calling one included).
WORKERS = _workers()
#: A batch whose estimated work (seconds) is below this runs whole.
SPLIT_SECONDS = 1e-3

_pool: ThreadPoolExecutor | None = None
_pool_lock = threading.Lock()
#: Batches whose parts are running on the pool now.
_running = 0


def _executor() -> ThreadPoolExecutor:
    global _pool
    with _pool_lock:
        if _pool is None:
            _pool = ThreadPoolExecutor(max_workers=max(1, WORKERS - 1),
                                       thread_name_prefix="symtmm")
        return _pool


def _forget_pool() -> None:
    """In a forked child: the pool's threads stayed in the parent; a batch there would
    wait for them forever. The child makes a pool of its own when it needs one."""
    global _pool, _pool_lock, _running
    _pool, _pool_lock, _running = None, threading.Lock(), 0


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_pool)


def only_idle_workers() -> bool:
    """Whether every thread of this process but the calling one is a worker of this
    module's pool, and none is running a part of a batch (so a fork copies no lock that
    a thread holds: an idle worker waits on its queue, which the child never touches)."""
    with _pool_lock:
        if _running:
            return False
        workers = set(_pool._threads) if _pool is not None else set()
    me = threading.current_thread()
    return all(t is me or t in workers for t in threading.enumerate())


def run_ranges(fn, count: int, work: float) -> list:
    """``[fn(lo, hi), ...]`` over consecutive ranges covering ``0 .. count``, in order: one
    range where ``work`` (the batch's estimated seconds) is below :data:`SPLIT_SECONDS`
    or one thread serves, else up to :data:`WORKERS` ranges run at once (the first in
    the calling thread). ``fn`` must release Python's lock for its compiled part and
    touch nothing shared but its own range of the outputs."""
    parts = min(WORKERS, count) if work >= SPLIT_SECONDS else 1
    if parts <= 1:
        return [fn(0, count)]
    global _running
    bounds = [count * k // parts for k in range(parts + 1)]
    pool = _executor()
    with _pool_lock:
        _running += 1
    try:
        futures = [pool.submit(fn, lo, hi) for lo, hi in itertools.pairwise(bounds[1:])]
        first = fn(bounds[0], bounds[1])
        return [first] + [f.result() for f in futures]
    finally:
        with _pool_lock:
            _running -= 1
