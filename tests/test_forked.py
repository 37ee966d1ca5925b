"""A call that cannot be interrupted, in a forked child stopped at a deadline
(:mod:`symtmm.forked`), and the factorisations of ``derive`` that use it."""

from __future__ import annotations

import os
import pickle
import resource
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


def test_no_fork_while_another_thread_runs():
    stop = threading.Event()
    other = threading.Thread(target=stop.wait)
    other.start()
    try:
        assert not forked.usable()
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
