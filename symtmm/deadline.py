"""A wall-clock budget for a search: an input whose evaluations explode ends in one line.

Some valid models cost far more per evaluation than any ordinary one: a beam of
``kw L**4 / EI ~ 1e25`` is cut into tens of thousands of pieces, and a cluster of distinct
eigenvalues 1e-16 apart needs counts at thousands of bits there (the radii of a band of
``n`` freedoms grow by about ``n / 4`` bits). Such a search would run for minutes or
hours; under :func:`time_budget` it stops at the first evaluation past the deadline
with a :class:`~symtmm.errors.ComputationError` naming the budget and how to change it.
Evaluations call :func:`check` (:mod:`symtmm.numeric.evaluator`); a single evaluation
is not interrupted. Budgets nest: the inner one ends no later than the outer.

Examples
--------
>>> import time
>>> with time_budget(0.0):
...     time.sleep(0.001)
...     check()
Traceback (most recent call last):
  ...
symtmm.errors.OverBudget: the search takes longer than 0 s (--max-seconds): allow more, or ask for fewer eigenvalues, fewer digits or a lower range
"""

from __future__ import annotations

import contextlib
import contextvars
import time

from .errors import OverBudget

__all__ = ["time_budget", "check"]

#: ``(seconds, deadline)`` of the innermost budget, or None.
_DEADLINE: contextvars.ContextVar = contextvars.ContextVar("symtmm_search_deadline",
                                                            default=None)


@contextlib.contextmanager
def time_budget(seconds: float | None, explain=None):
    """Searches inside stop after ``seconds`` of wall-clock time (None: no limit of this
    one; an outer budget still holds).

    ``explain``: a function of no arguments that may say, once the budget is spent, what
    made the search costly (:func:`symtmm.numeric.plan.crowding`); added to the error's
    line by the outermost budget that has one."""
    if seconds is None:
        yield
        return
    outer = _DEADLINE.get()
    deadline = time.perf_counter() + float(seconds)
    budget = (float(seconds), deadline)
    if outer is not None and outer[1] < deadline:
        budget = outer
    token = _DEADLINE.set(budget)
    try:
        yield
    except OverBudget as exc:
        why = None
        if explain is not None and not exc.explained:
            try:
                why = explain()
            except (ArithmeticError, AttributeError, IndexError, KeyError, TypeError,
                    ValueError):
                why = None      # (an explanation never takes the error's place)
        if not why:
            raise
        more = OverBudget(f"{exc}; {why}")
        more.explained = True
        raise more from None
    finally:
        _DEADLINE.reset(token)


def check() -> None:
    """Raise :class:`~symtmm.errors.OverBudget` where the budget is spent."""
    budget = _DEADLINE.get()
    if budget is not None and time.perf_counter() > budget[1]:
        raise OverBudget(f"the search takes longer than {budget[0]:g} s "
                         "(--max-seconds): allow more, or ask for fewer eigenvalues, "
                         "fewer digits or a lower range")
