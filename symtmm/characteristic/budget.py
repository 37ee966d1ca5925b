"""Budgets of one derivation: symbolic work that explodes becomes a one-line error.

A wall-clock deadline and the terms of any polynomial on the way (the terms stand
for memory: python-flint aborts the interpreter when an allocation fails, so
memory must never run out). :func:`spend` is called between the steps of the
other modules; a single step is bounded by the terms it is given. Limits and
their reasons: :mod:`symtmm.limits`.
"""

from __future__ import annotations

import contextvars
import time
from dataclasses import dataclass

from ..errors import ComputationError


@dataclass(frozen=True)
class _Budget:
    seconds: float
    deadline: float
    terms: float


_BUDGET: contextvars.ContextVar = contextvars.ContextVar("symtmm_derive_budget", default=None)

_HINT = ("a model with fewer beams or fewer distinct positions, fewer symbolic parameters, or "
         "solve and codegen, which need no closed form")


def _over_terms(terms) -> ComputationError:
    return ComputationError(f"the closed form grows beyond {terms} terms in one polynomial "
                            f"(a budget on memory): {_HINT}")


def spend(*polys) -> None:
    """Stop the derivation if it is over its time budget or ``polys`` over the term budget."""
    budget = _BUDGET.get()
    if budget is None:
        return
    if time.perf_counter() > budget.deadline:
        raise ComputationError(f"the closed form takes longer than {budget.seconds:g} s "
                               f"(--max-seconds): allow more, {_HINT}")
    for p in polys:
        if len(p) > budget.terms:
            raise _over_terms(budget.terms)


def spend_product(a, b) -> None:
    """Refuse a product that could exceed the term budget many times over, before it is formed."""
    budget = _BUDGET.get()
    if budget is not None and len(a) * len(b) > 20 * budget.terms:
        raise _over_terms(budget.terms)


def budget(seconds: float | None, terms: int | None) -> _Budget:
    """A budget starting now (``None``: no limit)."""
    inf = float("inf")
    return _Budget(inf if seconds is None else float(seconds),
                   inf if seconds is None else time.perf_counter() + float(seconds),
                   inf if terms is None else int(terms))
