"""A call that cannot be interrupted, run in a forked child and stopped at a deadline.

Some library calls hold the interpreter until they return: python-flint's
multivariate factorisation runs in C for seconds to minutes, and how long is not
foreseeable from its input (measured: 1e-5 to 6e-4 s a term). In a child process
made by ``fork`` it inherits its arguments for free (the memory is shared until
written), and the parent, waiting on a pipe, can stop it at the deadline. Only the
result travels, pickled: the function returns it in plain data (numbers, bytes).

Other threads of the process do not matter to such a call: the child runs the one
function, self-contained C work and plain data (no lock another thread may hold is
taken there; the allocator's are made safe across fork by the C library), and leaves
by ``os._exit``. :func:`usable` says only whether the platform can fork; where it
cannot, callers fall back to a guard that refuses calls foreseen to be too long. A
child that dies (an allocation python-flint cannot make aborts the process) costs the
parent nothing but the answer: :class:`ChildFailed`. Running arbitrary work in
forked processes, as a sweep's workers do, is another matter:
:func:`no_other_threads`.

Examples
--------
>>> if usable():
...     print(call(lambda: sum(range(10)), deadline=time.perf_counter() + 10))
... else:
...     print(45)
45
"""

from __future__ import annotations

import faulthandler
import os
import pickle
import select
import signal
import sys
import threading
import time
import warnings

__all__ = ["usable", "no_other_threads", "call", "ChildFailed", "PastDeadline"]


class PastDeadline(Exception):
    """The child was stopped at the deadline."""


class ChildFailed(Exception):
    """The child ended without a result (killed by a signal, or the call raised)."""


def usable() -> bool:
    """Whether :func:`call` can fork here (the platform has ``fork``)."""
    return hasattr(os, "fork")


def no_other_threads() -> bool:
    """Whether this process runs no other thread than the kernel's idle workers
    (:func:`symtmm.numeric.parallel.only_idle_workers`, left from an earlier batch: they
    hold no lock), so that a forked child may run anything (a sweep's worker processes).
    A thread holding a lock at the fork would leave the child's copy locked forever."""
    from .numeric.parallel import only_idle_workers
    return threading.active_count() == 1 or only_idle_workers()


def _child(fn, write_end: int) -> None:
    """Run ``fn`` and write its pickled result; never returns."""
    code = 1
    try:
        # (what the child might print, python-flint's last words on an allocation it could
        # not make among them, is not the program's output: the parent says what failed)
        quiet = os.open(os.devnull, os.O_WRONLY)
        os.dup2(quiet, 1)
        os.dup2(quiet, 2)
        faulthandler.disable()          # (it may write to a copy of the parent's stderr)
        data = pickle.dumps(fn(), protocol=pickle.HIGHEST_PROTOCOL)
        with os.fdopen(write_end, "wb") as out:
            out.write(data)
        code = 0
    finally:
        # (no interpreter shutdown: the parent's buffers, handlers and files stay its own)
        os._exit(code)


def call(fn, deadline: float):
    """``fn()`` computed in a forked child; :class:`PastDeadline` if it has not returned by
    ``deadline`` (a :func:`time.perf_counter` time), :class:`ChildFailed` if the child died.

    ``fn`` must be self-contained (C work on data it holds, results in plain data): it
    may run beside a copy of another thread's locks. The caller checks :func:`usable`.
    """
    # (anything still buffered would be written twice: once by each process)
    sys.stdout.flush()
    sys.stderr.flush()
    read_end, write_end = os.pipe()
    with warnings.catch_warnings():
        # (Python 3.12 warns of any fork beside other threads: the child runs only fn,
        # which takes none of their locks)
        warnings.simplefilter("ignore", DeprecationWarning)
        pid = os.fork()
    if pid == 0:  # pragma: no cover - runs in the child, which never returns
        os.close(read_end)
        _child(fn, write_end)
    os.close(write_end)
    chunks = []
    done = False
    try:
        with os.fdopen(read_end, "rb", buffering=0) as pipe:
            while True:
                left = deadline - time.perf_counter()
                if left <= 0:
                    raise PastDeadline
                ready, _, _ = select.select([pipe], [], [], left)
                if not ready:
                    continue
                chunk = pipe.read(1 << 20)
                if not chunk:
                    break
                chunks.append(chunk)
        _, status = os.waitpid(pid, 0)
        done = True
    finally:
        if not done:            # (past the deadline, or interrupted: the child goes too)
            os.kill(pid, signal.SIGKILL)
            os.waitpid(pid, 0)
    if not os.WIFEXITED(status) or os.WEXITSTATUS(status) != 0 or not chunks:
        raise ChildFailed
    return pickle.loads(b"".join(chunks))
