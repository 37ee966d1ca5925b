"""What more digits cost: ``solve(model, count=10, digits=D)`` at 15, 30 and 50 digits.

Every printed digit is proved at each precision, so the cost of more digits is
the cost of the high-precision stage (the proof arithmetic at about ``D + 25``
digits, more points where a root must be separated more finely). The solves of
a model are timed in rounds -- each round solves at every precision once --
and each precision keeps its best time (a busy spell of the shared machine
then falls on one round of all precisions, not on all rounds of one); one more
solve at each precision is profiled (:mod:`benchmarks.profiling`) to say where
the extra time goes.
"""

from __future__ import annotations

import time

import numpy as np

from .models import chain, example, from_scratch
from .profiling import solve_profile

__all__ = ["run", "DIGITS", "MODELS"]

DIGITS = (15, 30, 50)
COUNT = 10
#: Rounds; each precision keeps its best. A ratio of two times takes more rounds than one
#: time to settle on a shared machine: with 3, a 15-digit solve here could come out
#: noticeably slower than the same solve timed in section 1 of the same run.
REPEAT = 7
#: name: model builder
MODELS = {"ex1": lambda: example("paper_ex1_ff_cc"),
          "ex3": lambda: example("paper_ex3_three_pp_coupled"),
          "chain10": lambda: chain(10, 2)}
QUICK = ("ex1",)
#: A precision may cost at most this multiple of the 15-digit solve.
LIMIT = 2.0


def measure(model, repeat: int = REPEAT) -> dict:
    """Best seconds per precision over ``repeat`` rounds, evaluations and profiles."""
    from symtmm.solve import solve

    best = {d: np.inf for d in DIGITS}
    evaluations = {}
    for _ in range(repeat):
        for d in DIGITS:
            fresh = from_scratch(model)     # each solve as a user's first one
            start = time.perf_counter()
            spectrum = solve(fresh, count=COUNT, digits=d)
            best[d] = min(best[d], time.perf_counter() - start)
            evaluations[d] = spectrum.evaluations
    profiles = {d: solve_profile(model, count=COUNT, digits=d)[0] for d in DIGITS}
    base = best[DIGITS[0]]
    return dict(seconds={str(d): best[d] for d in DIGITS},
                evaluations={str(d): evaluations[d] for d in DIGITS},
                ratio={str(d): best[d] / base for d in DIGITS[1:]},
                profiles={str(d): profiles[d] for d in DIGITS})


def run(quick: bool = False, progress=print) -> dict:
    names = QUICK if quick else tuple(MODELS)
    cases = {}
    for name in names:
        progress(f"precision: {name} at {', '.join(map(str, DIGITS))} digits")
        cases[name] = measure(MODELS[name](), repeat=2 if quick else REPEAT)
    worst = max(r for c in cases.values() for r in c["ratio"].values())
    return dict(digits=list(DIGITS), count=COUNT, repeat=REPEAT, cases=cases,
                target=dict(text=f"solves at {DIGITS[1]} and {DIGITS[2]} digits cost at most "
                                 f"{LIMIT:g}x the {DIGITS[0]}-digit solve",
                            ratios={n: c["ratio"] for n, c in cases.items()},
                            worst=worst, met=bool(worst <= LIMIT)))
