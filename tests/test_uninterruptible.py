"""Work that cannot be interrupted, kept within a budget: a call in a forked child stopped
at a deadline (:mod:`symtmm.forked`) and the factorisations of ``derive`` that use it,
and long steps of ``derive`` that now check the budget between their parts or no longer
list a long polynomial's terms."""

from __future__ import annotations

import math
import os
import pickle
import resource
import subprocess
import sys
import threading
import time

import numpy as np
import pytest

from symtmm import forked
from symtmm.errors import ComputationError

pytestmark = pytest.mark.skipif(not hasattr(os, "fork"), reason="the platform cannot fork")


def test_a_call_returns_its_value_from_the_child():
    data = np.arange(10.0)
    parent = os.getpid()
    out = forked.call(lambda: (os.getpid(), float(data.sum()), b"x" * 3_000_000),
                      time.perf_counter() + 60)
    assert out[0] != parent                     # (computed elsewhere)
    assert out[1] == 45.0 and out[2] == b"x" * 3_000_000   # (more than a pipe's buffer)


def test_a_call_past_its_deadline_is_stopped_there():
    start = time.perf_counter()
    with pytest.raises(forked.PastDeadline):
        forked.call(lambda: time.sleep(60), start + 0.3)
    assert time.perf_counter() - start < 30     # (not the minute the call would take)


def _abort():
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))   # (no core file)
    os.abort()                                         # (what python-flint does on no memory)


def _raise():
    raise ValueError("in the child")


@pytest.mark.parametrize("fn", [_abort, _raise])
def test_a_child_that_dies_or_raises_is_a_failure_not_a_crash(fn):
    with pytest.raises(forked.ChildFailed):
        forked.call(fn, time.perf_counter() + 60)


def test_a_call_beside_another_thread_forks_and_returns():
    """The child runs only the function: another thread (here one waiting on an event, as
    tqdm's monitor does) neither keeps the call from forking nor blocks the child."""
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert forked.usable()
        assert forked.call(lambda: 6 * 7, time.perf_counter() + 60) == 42
    finally:
        stop.set()
        other.join()


def _ring_and_product():
    from symtmm.characteristic.ring import _Ring
    ring = _Ring(["a", "b", "c", "d"])
    a, b, c, d = ring.gens
    p = ring.coefficient(3) / 7 * (a + 2 * b - c + d + 1) ** 9 * (a * b - 5 * c ** 2 + d + 2) ** 4
    return ring, p


def test_factors_packed_for_the_parent_are_the_factors():
    pytest.importorskip("flint")
    ring, p = _ring_and_product()
    content, parts = ring.factor(p)
    back, back_parts = ring.unpack_factors(pickle.loads(pickle.dumps(
        ring.pack_factors((content, parts)))))
    assert back == content
    assert [(ring.terms(f), e) for f, e in back_parts] == \
        [(ring.terms(f), e) for f, e in parts]


def _within(seconds):
    from symtmm.characteristic import budget as b
    return b, b._BUDGET.set(b.budget(seconds, None))


def test_a_factorisation_in_the_child_gives_the_factors():
    pytest.importorskip("flint")
    ring, p = _ring_and_product()
    assert len(p) >= 2000                       # (large enough to go to a child)
    b, token = _within(60.0)
    try:
        content, parts = b.factor(ring, p)
    finally:
        b._BUDGET.reset(token)
    # (the product of the factors is the polynomial)
    product = ring.one * content
    for f, e in parts:
        product = product * f ** e
    assert product == p
    assert sorted(e for _, e in parts) == [4, 9]


@pytest.mark.parametrize("can_fork", [True, False])
def test_a_factorisation_past_the_deadline_is_the_budget_line(monkeypatch, can_fork):
    """Forked, the child is stopped at the deadline; without fork, the guard refuses what
    it foresees to end past it. Either way the budget's line, or None where optional."""
    pytest.importorskip("flint")
    monkeypatch.setattr(forked, "usable", lambda: can_fork)
    ring, p = _ring_and_product()
    b, token = _within(1e-9)
    try:
        with pytest.raises(ComputationError, match="--max-seconds"):
            b.factor(ring, p)
        assert b.factor(ring, p, optional=True) is None
    finally:
        b._BUDGET.reset(token)


def test_a_long_polynomial_is_not_listed_to_learn_its_length_or_degree(monkeypatch):
    """Listing a determinant's 908 576 terms took 9.5 s no budget check interrupts (a random
    model's derive --max-seconds 5 ran 16.8 s, another's 8.7 s): whether a polynomial is
    constant, how long it is and its degree in a variable are read without listing it."""
    pytest.importorskip("flint")
    from symtmm.characteristic.ring import _Ring
    ring, p = _ring_and_product()
    listed = []
    monkeypatch.setattr(_Ring, "terms", lambda self, q: listed.append(len(q)) or q.to_dict())
    assert ring.constant_value(p) is None
    assert [ring.degree(p, i) for i in range(4)] == [13, 13, 17, 13]
    assert ring.degree(ring.zero, 0) == 0 and ring.constant_value(ring.one * 5) == 5
    assert listed == [1]                # (only the constant's one term)


@pytest.fixture
def idle_pool(monkeypatch):
    """The kernel's pool of two workers, idle after a batch split over it."""
    from symtmm.numeric import parallel
    monkeypatch.setattr(parallel, "WORKERS", 2)
    assert parallel.run_ranges(lambda lo, hi: hi - lo, 4, work=1.0) == [2, 2]
    yield parallel


_THREADS_SCRIPT = """
import threading
from symtmm import forked
from symtmm.numeric import parallel
parallel.WORKERS = 2
out = [forked.no_other_threads()]
parallel.run_ranges(lambda lo, hi: out.append(parallel.only_idle_workers()), 2, work=1.0)
out.append(threading.active_count() > 1 and forked.no_other_threads())
stop = threading.Event()
other = threading.Thread(target=stop.wait)
other.start()
out.append(forked.no_other_threads())
stop.set()
other.join()
print(out)
"""


def test_only_the_kernels_idle_workers_let_a_process_fork_for_anything():
    """A sweep forks its worker processes where no other thread runs: the kernel's idle
    workers, left from an earlier batch, hold no lock (a batch running on them does, and
    so may any other thread). In a fresh interpreter: earlier tests leave threads."""
    run = subprocess.run([sys.executable, "-c", _THREADS_SCRIPT], check=False,
                         capture_output=True, text=True, timeout=120)
    assert run.returncode == 0, run.stderr
    assert run.stdout.strip() == "[True, False, False, True, False]"


def test_a_child_forked_beside_the_pool_splits_its_own_batches(idle_pool):
    """The pool's threads stay in the parent: a batch in the child would wait for them
    forever; the child makes a pool of its own."""
    out = forked.call(lambda: idle_pool.run_ranges(lambda lo, hi: (lo, hi), 4, work=1.0),
                      time.perf_counter() + 60)
    assert out == [(0, 2), (2, 4)]


def test_a_factorisation_beside_other_threads_goes_to_a_child(idle_pool, monkeypatch):
    """A campaign's derive --max-seconds 5 ran 77 s in a process that had solved before
    (the kernel's workers alive): the factorisation was refused the child and the guard
    let it run."""
    pytest.importorskip("flint")
    calls = []
    real = forked.call
    monkeypatch.setattr(forked, "call", lambda fn, deadline: calls.append(1) or real(
        fn, deadline))
    ring, p = _ring_and_product()
    b, token = _within(60.0)
    try:
        _, parts = b.factor(ring, p)
    finally:
        b._BUDGET.reset(token)
    assert calls == [1] and sorted(e for _, e in parts) == [4, 9]


def test_the_harmonic_expansion_of_one_monomial_checks_the_budget():
    """cos/sin powers of several groups expanded by product-to-sum: the sum grows with
    every factor, and a monomial of high powers took seconds between two budget checks
    (an element-library model's derive --max-seconds 5 ran 8.7 s). The budget is checked
    between the factors."""
    from types import SimpleNamespace

    from symtmm.characteristic.writer import _Writer
    writer = _Writer.__new__(_Writer)
    writer.alg, writer._trig_cache = SimpleNamespace(groups=3), {}
    sums, shift = writer._harmonics((2, 1, 0, 2, 1, 1), False)
    # (the sum of cosines and sines of combined arguments over 2**shift is the monomial
    # cos(a)**2 sin(a) sin(b)**2 cos(c) sin(c))
    a, b, c = 0.3, 0.7, 1.1
    value = sum(v * (math.sin if kind else math.cos)(fa * a + fb * b + fc * c)
                for (kind, (fa, fb, fc)), v in sums.items()) / 2 ** shift
    assert value == pytest.approx(math.cos(a) ** 2 * math.sin(a) * math.sin(b) ** 2
                                  * math.cos(c) * math.sin(c), rel=1e-12)
    writer._trig_cache = {}
    b, token = _within(1e-9)
    try:
        with pytest.raises(ComputationError, match="--max-seconds"):
            writer._harmonics((2, 1, 0, 2, 1, 1), False)
    finally:
        b._BUDGET.reset(token)
