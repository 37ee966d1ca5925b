"""BLAS limited to one thread inside the routines that factorise small dense matrices."""

from __future__ import annotations

import threading

import numpy as np
import pytest

from symtmm.numeric import threads

threadpoolctl = pytest.importorskip("threadpoolctl")


def _blas_threads() -> list:
    return [lib["num_threads"] for lib in threadpoolctl.threadpool_info()
            if lib["user_api"] == "blas"]


@pytest.fixture
def two_threads():
    """BLAS on two threads around the test (a machine of one core has one anyway)."""
    with threadpoolctl.threadpool_limits(limits=2, user_api="blas"):
        before = _blas_threads()
        if not before or max(before) < 2:
            pytest.skip("BLAS runs one thread here already")
        yield before


def test_inside_one_thread_and_restored_after(two_threads):
    seen = []

    @threads.one_blas_thread
    def inner():
        seen.append(_blas_threads())
        return np.linalg.eigvalsh(np.diag([2.0, 1.0]))

    @threads.one_blas_thread
    def outer():
        inner()
        seen.append(_blas_threads())       # (still limited: the outer call holds it)

    outer()
    assert seen == [[1] * len(two_threads)] * 2
    assert _blas_threads() == two_threads


def test_an_exception_restores_the_threads(two_threads):
    @threads.one_blas_thread
    def fails():
        raise ValueError("no")

    with pytest.raises(ValueError):
        fails()
    assert _blas_threads() == two_threads


def test_concurrent_calls_share_one_limit(two_threads):
    inside = threading.Barrier(3)
    seen = []

    @threads.one_blas_thread
    def work():
        inside.wait(timeout=10)            # all three inside at once
        seen.append((threads._state["depth"], threads._state["limiter"] is not None))
        inside.wait(timeout=10)

    workers = [threading.Thread(target=work) for _ in range(3)]
    for t in workers:
        t.start()
    for t in workers:
        t.join()
    # (OpenBLAS reports its number of threads per calling thread: the shared state tells)
    assert seen == [(3, True)] * 3
    assert threads._state["depth"] == 0 and threads._state["limiter"] is None
    assert _blas_threads() == two_threads


def test_switched_off_leaves_blas_alone(two_threads, monkeypatch):
    monkeypatch.setattr(threads, "ENABLED", False)

    @threads.one_blas_thread
    def inner():
        return _blas_threads()

    assert inner() == two_threads
