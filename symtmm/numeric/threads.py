"""One BLAS thread for symtmm's small dense matrices.

The dense matrices symtmm hands to LAPACK (a mode's dynamic stiffness, whose null space
is its shape; the bases a sweep's branch tracking compares) have tens to a few hundred
rows. OpenBLAS splits such calls over its threads all the same, and where the cores are
busy with other work its threads wait on each other: measured on two cores with one
other process running, numpy's ``eigh`` of a 40x40 matrix took 9.6 ms on two threads
and 0.13 ms on one, and example 1's 51-step sweep (mode shapes included) 2.2 s against
0.6 s. Where threadpoolctl is installed (the ``fast`` extra), the routines that call
LAPACK on such matrices (:func:`one_blas_thread`) run with the BLAS libraries loaded
limited to one thread, restored afterwards; without it, BLAS runs as configured
(``OPENBLAS_NUM_THREADS=1`` in the environment does the same for the whole process).

Examples
--------
>>> import numpy as np
>>> @one_blas_thread
... def smallest(A):
...     return float(np.linalg.eigvalsh(A)[0])
>>> smallest(np.diag([3.0, 1.0, 2.0]))
1.0
"""

from __future__ import annotations

import functools
import threading

try:        # an optional extra: without it BLAS keeps its own number of threads
    from threadpoolctl import ThreadpoolController
except ImportError:  # pragma: no cover - tested by switching it off
    ThreadpoolController = None

__all__ = ["one_blas_thread", "ENABLED"]

#: Whether the BLAS threads are limited (threadpoolctl installed); tests switch it off.
ENABLED = ThreadpoolController is not None

_LOCK = threading.Lock()
_state = {"depth": 0, "limiter": None, "controller": None}


def _enter() -> None:
    with _LOCK:
        _state["depth"] += 1
        if _state["depth"] == 1:
            if _state["controller"] is None:
                # (a scan of the loaded libraries, 5 ms: once per process)
                _state["controller"] = ThreadpoolController()
            _state["limiter"] = _state["controller"].limit(limits=1, user_api="blas")


def _leave() -> None:
    with _LOCK:
        _state["depth"] -= 1
        if _state["depth"] == 0 and _state["limiter"] is not None:
            _state["limiter"].restore_original_limits()
            _state["limiter"] = None


def one_blas_thread(fn):
    """``fn`` run with BLAS limited to one thread (where threadpoolctl is installed).

    Nested and concurrent calls share one limit: the first to enter sets it, the last to
    leave restores the libraries' own numbers of threads.
    """
    @functools.wraps(fn)
    def limited(*args, **kwargs):
        if not ENABLED:
            return fn(*args, **kwargs)
        _enter()
        try:
            return fn(*args, **kwargs)
        finally:
            _leave()
    return limited
