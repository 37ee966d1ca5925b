"""Where a solve spends its time: seconds, calls and points of the library's inner routines.

The report says why a target is missed from numbers gathered in the same
run, not from a separate profile: :func:`profile_call` wraps the routines
:func:`benchmarks.kernel.internals` names (each wrapper adds about a
microsecond per call) and returns the *own* time of each -- a routine's time
without the timed routines it calls -- so the times add up to the whole, the
rest being everything else (search logic, bookkeeping, results). A routine
whose calls use different arithmetics is split by arithmetic
(``factor_double``, ``factor_ball``, ``factor_mp``).
"""

from __future__ import annotations

import functools
import time
from contextlib import contextmanager

__all__ = ["timed_calls", "profile_call", "solve_profile", "ROUTINE_TEXT"]

#: What each timed routine is, for the report (a name's prefix before the arithmetic).
ROUTINE_TEXT = {
    "plan": "compiling the model into a stiffness plan",
    "factor_double": "double-precision factorizations (counts and Delta)",
    "factor_ball": "ball-arithmetic factorizations (the proofs)",
    "factor_mp": "mpmath factorizations",
    "rigid_body_modes": "the exact static null space (rigid-body modes)",
    "complex_factor_double": "double-precision factorizations at complex points",
    "complex_factor_ball": "ball factorizations at complex points",
    "complex_factor_mp": "mpmath factorizations at complex points",
    "enclose_ball": "Arb enclosures of Delta over boxes (the damped proofs)",
    "mode_shapes": "mode shapes (branch tracking)",
}


def _wrap(fn, name: str, key, stats: dict, stack: list):
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        sub, points = key(args, kwargs) if key else (None, 1)
        label = f"{name}_{sub}" if sub else name
        children = [0.0]
        stack.append(children)
        start = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            elapsed = time.perf_counter() - start
            stack.pop()
            if stack:
                stack[-1][0] += elapsed
            stat = stats.setdefault(label, dict(seconds=0.0, calls=0, points=0))
            stat["seconds"] += elapsed - children[0]
            stat["calls"] += 1
            stat["points"] += points
    return wrapper


@contextmanager
def timed_calls(targets: dict):
    """Own seconds, calls and points of ``owner.attr`` for each ``name: (owner, attr, key)``
    (or ``(owner, attr, key, label)``: the statistics under ``label``, shared).

    ``key(args, kwargs)`` returns ``(suffix, points)`` of a call (None: no suffix,
    one point). The statistics are keyed by ``name`` (``label``) or ``name_suffix``.

    Examples
    --------
    >>> import math
    >>> class Box:
    ...     sqrt = staticmethod(math.sqrt)
    >>> with timed_calls({"sqrt": (Box, "sqrt", None)}) as stats:
    ...     _ = [Box.sqrt(2.0) for _ in range(3)]
    >>> stats["sqrt"]["calls"], Box.sqrt is math.sqrt
    (3, True)
    """
    stats: dict = {}
    stack: list = []
    saved = []
    for name, (owner, attr, key, *label) in targets.items():
        original = owner.__dict__[attr] if isinstance(owner, type) else getattr(owner, attr)
        saved.append((owner, attr, original))
        fn = original.__func__ if isinstance(original, staticmethod) else original
        # (a fourth entry names the statistics: two routines doing one job share them)
        wrapped = _wrap(fn, label[0] if label else name, key, stats, stack)
        setattr(owner, attr, staticmethod(wrapped) if isinstance(original, staticmethod)
                else wrapped)
    try:
        yield stats
    finally:
        for owner, attr, original in saved:
            setattr(owner, attr, original)


def profile_call(fn) -> tuple:
    """``(profile, result)`` of ``fn()`` with its time split over the routines of
    :func:`benchmarks.kernel.internals`.

    The profile: ``seconds`` (the whole call), ``routines`` (own seconds, calls,
    points and share of each routine that ran), ``other_seconds``, and
    ``evaluations`` when the result has them.
    """
    from symtmm.numeric.plan import clear_plans

    from .kernel import internals
    clear_plans()               # from scratch: no plan kept from an earlier run
    with timed_calls(internals().profiled) as stats:
        start = time.perf_counter()
        result = fn()
        seconds = time.perf_counter() - start
    for stat in stats.values():
        stat["share"] = stat["seconds"] / seconds if seconds else None
    profile = dict(seconds=seconds, routines=dict(sorted(stats.items())),
                   other_seconds=seconds - sum(s["seconds"] for s in stats.values()))
    if hasattr(result, "evaluations"):
        profile["evaluations"] = int(result.evaluations)
    return profile, result


def solve_profile(model, **solve_kw) -> tuple:
    """``(profile, spectrum)`` of one :func:`symtmm.solve.solve` (see :func:`profile_call`);
    the profile also holds ``roots`` (with multiplicity). The model is taken as a new object
    (:func:`benchmarks.models.from_scratch`), as the timed solves take it."""
    from symtmm.solve import solve

    from .models import from_scratch

    fresh = from_scratch(model)
    profile, spectrum = profile_call(lambda: solve(fresh, **solve_kw))
    profile["roots"] = sum(e.multiplicity for e in spectrum)
    return profile, spectrum
