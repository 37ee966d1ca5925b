"""Budgets of one derivation: symbolic work that explodes becomes a one-line error.

A wall-clock deadline and the terms of any polynomial on the way (the terms stand
for memory: python-flint aborts the interpreter when an allocation fails, so
memory must never run out). :func:`spend` is called between the steps of the
other modules; a single step is bounded by the terms it is given, and a large
factorisation, which cannot be interrupted, runs in a forked child stopped at the
deadline (:func:`factor`). Limits and their reasons: :mod:`symtmm.limits`.
"""

from __future__ import annotations

import contextvars
import time
from dataclasses import dataclass, field

from .. import forked
from ..errors import ComputationError
from ..limits import FACTOR_TERMS


@dataclass(frozen=True)
class _Budget:
    seconds: float
    deadline: float
    terms: float
    #: ``[pairs, seconds]`` of the large products so far, and the start of the last one
    #: (:func:`spend_product`): the seconds a product will take, foreseen
    products: list = field(default_factory=lambda: [0, 0.0, None])


#: Seconds per pair of terms a product is assumed to take at least (a polynomial product
#: costs about its pairs of terms; measured 1.7e-6 s on the fuzzed model whose product of
#: 784 by 14336 terms took 19 s); slower products of a derivation raise it.
_SECONDS_PER_PAIR = 1e-6
#: Products of fewer pairs are not foreseen (they take milliseconds).
_LARGE_PRODUCT = 10**5


#: Seconds per term a factorisation is assumed to take at least, growing in proportion to
#: the terms beyond :data:`_FACTOR_KNEE` (measured: 1e-5 to 1.3e-4 s per term from 10 000
#: to 98 250 terms, and minutes at 352 484).
_FACTOR_SECONDS_PER_TERM = 1e-5
_FACTOR_KNEE = 50_000

_BUDGET: contextvars.ContextVar = contextvars.ContextVar("symtmm_derive_budget", default=None)

_HINT = ("a model with fewer beams or fewer distinct positions, fewer symbolic parameters, or "
         "solve and codegen, which need no closed form")


def _over_time(budget) -> ComputationError:
    return ComputationError(f"the closed form takes longer than {budget.seconds:g} s "
                            f"(--max-seconds): allow more, {_HINT}")


def _over_terms(terms) -> ComputationError:
    return ComputationError(f"the closed form grows beyond {terms} terms in one polynomial "
                            f"(a budget on memory): {_HINT}")


def spend(*polys) -> None:
    """Stop the derivation if it is over its time budget or ``polys`` over the term budget."""
    budget = _BUDGET.get()
    if budget is None:
        return
    now = time.perf_counter()
    started = budget.products[2]
    if started is not None:             # (the large product that spend_product foresaw)
        budget.products[1] += now - started[0]
        budget.products[0] += started[1]
        budget.products[2] = None
    if now > budget.deadline:
        raise _over_time(budget)
    for p in polys:
        if len(p) > budget.terms:
            raise _over_terms(budget.terms)


def spend_product(a, b) -> None:
    """Refuse a product that could exceed the term budget many times over, before it is formed."""
    budget = _BUDGET.get()
    if budget is None:
        return
    pairs = len(a) * len(b)
    if pairs > 20 * budget.terms:
        raise _over_terms(budget.terms)
    if pairs >= _LARGE_PRODUCT:
        # a product cannot be interrupted: one that would end past the deadline is refused
        # before it starts (one of 11 million terms took 19 s of a 15 s budget)
        done_pairs, done_seconds, _ = budget.products
        # (the products so far may have been cheaper per pair: sparse ones, small
        # coefficients; the assumed rate is a floor)
        rate = max(done_seconds / done_pairs if done_pairs else 0.0, _SECONDS_PER_PAIR)
        now = time.perf_counter()
        if now + pairs * rate > budget.deadline:
            raise _over_time(budget)
        budget.products[2] = (now, pairs)


def factoring_fits(p) -> bool:
    """Whether ``p`` may be factored: at most :data:`~symtmm.limits.FACTOR_TERMS` terms,
    and, at the assumed rate (a floor), done before the deadline (a factorisation
    cannot be interrupted)."""
    terms = len(p)
    if terms > FACTOR_TERMS:
        return False
    budget = _BUDGET.get()
    if budget is None:
        return True
    seconds = _FACTOR_SECONDS_PER_TERM * terms * max(1.0, terms / _FACTOR_KNEE)
    return time.perf_counter() + seconds <= budget.deadline


def _refusal(p) -> ComputationError:
    """The line refusing to factor ``p`` where it does not fit (:func:`factoring_fits`)."""
    if len(p) > FACTOR_TERMS:
        return ComputationError(f"the closed form's determinant has {len(p)} terms, more "
                                f"than {FACTOR_TERMS} can be factored (it cannot be "
                                f"interrupted): {_HINT}")
    return _over_time(_BUDGET.get())


#: Terms from which a factorisation under a deadline runs in a forked child that is stopped
#: there (:mod:`symtmm.forked`): the fork and the result's transfer cost milliseconds, a
#: factorisation of this size tens of them.
_FORK_TERMS = 2000


def factor(ring, p, optional: bool = False):
    """``ring.factor(p)`` within the budget: ``(content, [(factor, multiplicity), ...])``.

    A factorisation cannot be interrupted and its time is not foreseeable from its terms
    (1e-5 to 6e-4 s a term). Under a deadline a large one runs in a forked child stopped
    at the deadline where the platform can fork (:func:`symtmm.forked.usable`); otherwise
    it is refused beforehand where it could not finish at the assumed rate, and beyond
    :data:`~symtmm.limits.FACTOR_TERMS` always (:func:`factoring_fits`). ``optional``:
    return None instead of raising where it does not fit (a factorisation that only
    shortens what is written).
    """
    terms = len(p)
    budget_ = _BUDGET.get()
    in_child = budget_ is not None and budget_.deadline != float("inf") \
        and _FORK_TERMS <= terms <= FACTOR_TERMS and forked.usable()
    if not in_child:
        if not factoring_fits(p):
            if optional:
                return None
            raise _refusal(p)
        return ring.factor(p)
    try:
        packed = forked.call(lambda: ring.pack_factors(ring.factor(p)), budget_.deadline)
    except forked.PastDeadline:
        if optional:
            return None
        raise _over_time(budget_) from None
    except forked.ChildFailed:
        raise ComputationError(f"the factorisation of a polynomial of {terms} terms failed "
                               f"(out of memory?): {_HINT}") from None
    return ring.unpack_factors(packed)


def budget(seconds: float | None, terms: int | None) -> _Budget:
    """A budget starting now (``None``: no limit)."""
    inf = float("inf")
    return _Budget(inf if seconds is None else float(seconds),
                   inf if seconds is None else time.perf_counter() + float(seconds),
                   inf if terms is None else int(terms))
