"""Where a solve spends its time: seconds and calls of the library's inner routines.

The report says why a target is missed from numbers gathered in the same
run, not from a separate profile: :func:`solve_profile` wraps the routines a
solve is made of (each wrapper adds about a microsecond per call, against
milliseconds per mpmath evaluation) and returns seconds and calls of each,
the rest being everything else (bisection logic, bookkeeping, results).

The routines timed do not call one another, so their times add up:

* ``rigid_body_modes`` -- the exact rank of ``R(0)``;
* ``count`` -- :meth:`symtmm.stiffness.StiffnessModel.count`, the
  Wittrick--Williams count (double precision, mpmath where a pivot is small);
* ``delta_double`` -- :meth:`symtmm.compile.Evaluator.log_delta`, the stable
  double-precision ``Delta`` (``Evaluator.delta`` calls it);
* ``delta_mpmath`` -- :meth:`symtmm.compile.Evaluator.delta_mp`.
"""

from __future__ import annotations

import functools
import time
from contextlib import contextmanager

__all__ = ["timed_calls", "solve_profile", "ROUTINES"]


def _routines() -> dict:
    from symtmm.compile import Evaluator
    from symtmm.roots import undamped
    from symtmm.stiffness import StiffnessModel

    return {"rigid_body_modes": (undamped, "rigid_body_modes"),
            "count": (StiffnessModel, "count"),
            "delta_double": (Evaluator, "log_delta"),
            "delta_mpmath": (Evaluator, "delta_mp")}


#: Names of the routines :func:`solve_profile` times.
ROUTINES = ("rigid_body_modes", "count", "delta_double", "delta_mpmath")


def _wrap(fn, stat: dict):
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        if stat["depth"]:           # a recursive call is inside the outer one's time
            return fn(*args, **kwargs)
        stat["depth"] += 1
        t = time.perf_counter()
        try:
            return fn(*args, **kwargs)
        finally:
            stat["seconds"] += time.perf_counter() - t
            stat["calls"] += 1
            stat["depth"] -= 1
    return wrapper


@contextmanager
def timed_calls(targets: dict):
    """Seconds and calls of ``owner.attr`` for each ``name: (owner, attr)`` in the block.

    Examples
    --------
    >>> import math
    >>> class Box:
    ...     sqrt = staticmethod(math.sqrt)
    >>> with timed_calls({"sqrt": (Box, "sqrt")}) as stats:
    ...     _ = [Box.sqrt(2.0) for _ in range(3)]
    >>> stats["sqrt"]["calls"], Box.sqrt is math.sqrt
    (3, True)
    """
    stats = {name: dict(seconds=0.0, calls=0, depth=0) for name in targets}
    saved = []
    for name, (owner, attr) in targets.items():
        original = owner.__dict__[attr] if isinstance(owner, type) else getattr(owner, attr)
        saved.append((owner, attr, original))
        fn = original.__func__ if isinstance(original, staticmethod) else original
        wrapped = _wrap(fn, stats[name])
        setattr(owner, attr, staticmethod(wrapped) if isinstance(original, staticmethod)
                else wrapped)
    try:
        yield stats
    finally:
        for owner, attr, original in saved:
            setattr(owner, attr, original)
        for stat in stats.values():
            del stat["depth"]


def solve_profile(model, **solve_kw) -> tuple:
    """One default solve with its time split over :data:`ROUTINES`.

    Returns
    -------
    (dict, Spectrum)
        The profile: ``seconds`` (the whole solve), ``roots`` (with
        multiplicity), ``evaluations`` (the spectrum's count), ``routines``
        (seconds, calls and share of the time of each), ``other_seconds`` and
        ``mpmath_evaluations_per_root``; and the solve's result.
    """
    from symtmm.solve import solve

    with timed_calls(_routines()) as stats:
        start = time.perf_counter()
        spectrum = solve(model, **solve_kw)
        seconds = time.perf_counter() - start
    for stat in stats.values():
        stat["share"] = stat["seconds"] / seconds if seconds else None
    roots = sum(e.multiplicity for e in spectrum)
    profile = dict(seconds=seconds, roots=roots, evaluations=spectrum.evaluations,
                   routines=stats,
                   other_seconds=seconds - sum(s["seconds"] for s in stats.values()),
                   mpmath_evaluations_per_root=stats["delta_mpmath"]["calls"] / max(roots, 1))
    return profile, spectrum
