"""Cost against model size: levels (beams in a chain) and springs per level.

Models are :func:`benchmarks.models.chain`: random beams over ``[0, 1]``,
level ``i`` joined to level ``i + 1`` (the last to the ground) by
``springs_per_level`` springs at random positions, distinct over the model,
so a chain of ``n`` levels with ``s`` springs per level is cut at ``n s``
points on every level: ``n (n s + 1)`` beam segments, ``2 n`` columns carried
through them. Per evaluation of ``Delta`` the plain product therefore costs
about ``n**3 s`` (segments times columns); the stable evaluator also
re-orthonormalises its ``4n x 2n`` columns on each of the ``n s + 1``
intervals, ``n**3`` each, about ``n**4 s``. In the springs both are linear.

Measured, the same way in the quick and the full run (the quick run has
fewer sizes):

* time per evaluation of ``Delta``: the vectorised numpy evaluator on a batch
  of :data:`BATCH` points at every size (a batch that shrank with the model
  would put more per-call overhead on each point of the large models and fake
  a steeper exponent), and ``Evaluator.delta_mp`` at 30 digits (what the
  refinement of the default search uses) at one point; each the minimum of
  :data:`REPEAT` timings taken in rounds over all sizes (other work on the
  machine only ever adds time, and a busy spell then hits every size alike),
  one timing where a call takes over 5 s;
* time per full solve (first 10 natural frequencies, 15 digits, default
  method), each series in its own process with a time limit, split over the
  library's routines (:func:`benchmarks.profiling.solve_profile`);
* exponents: least-squares slopes on log-log of the minima, over all sizes
  and over the largest three (where fixed per-call costs weigh least); for
  the target, the median of the same fit to each round alone (see
  :func:`_target`), with the span over rounds.
"""

from __future__ import annotations

import json
import subprocess
import sys
import time
from pathlib import Path

import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parent.parent

__all__ = ["run", "SIZES", "fit_exponent", "round_exponents", "BATCH", "REPEAT"]

#: Sizes per measurement, (full run, quick run).
SIZES = {
    "eval_levels": ((1, 2, 3, 5, 10, 20, 50), (1, 2, 3, 6)),
    "eval_springs": ((1, 2, 5, 10, 20, 50, 100), (1, 2, 5, 10, 20)),
    "solve_levels": ((1, 2, 3, 5, 7, 10), (1, 2)),
    "solve_springs": ((1, 2, 5, 10, 20, 50), (1, 2)),
}
#: Springs per level when the levels vary; levels when the springs vary.
FIXED_SPRINGS = 2
FIXED_LEVELS = 2
#: Points per vectorised batch, at every size and in both runs.
BATCH = 200
#: Timings per measurement; the minimum is kept.
REPEAT = 5
#: Time limit of one full solve (seconds), (full run, quick run); a series of solves
#: gets the sum over its sizes.
SOLVE_LIMIT = (150.0, 20.0)


def fit_exponent(sizes, times) -> float | None:
    """Least-squares slope of ``log(time)`` against ``log(size)``.

    Examples
    --------
    >>> round(fit_exponent([1, 2, 4, 8], [3.0, 12.0, 48.0, 192.0]), 6)
    2.0
    """
    pts = [(s, t) for s, t in zip(sizes, times) if t is not None and t > 0]
    if len(pts) < 2:
        return None
    x = np.log([p[0] for p in pts])
    y = np.log([p[1] for p in pts])
    return float(np.polyfit(x, y, 1)[0])


def _prepare(levels: int, springs: int) -> dict:
    """The evaluator of one chain, with the sizes the report shows."""
    from symtmm.compile import Evaluator

    from .models import chain

    t = time.perf_counter()
    ev = Evaluator(chain(levels, springs))
    built = time.perf_counter() - t
    segments = [seg for kind, items in ev._steps if kind == "segments" for _, seg in items]
    # segments of equal constants share one matrix per call of the numpy evaluator
    distinct = len({ev._float_consts(seg) for seg in segments})
    row = dict(levels=levels, springs_per_level=springs, segments=len(segments),
               distinct_segments=distinct, evaluator_construction_seconds=built,
               numpy_rounds=[], mpmath_rounds=[])
    return dict(ev=ev, row=row)


def _time_once(entry: dict, enough: float = 5.0) -> None:
    """One timing of the numpy batch and of one 30-digit evaluation; none once a timing of
    this size has taken over ``enough`` seconds (other work changes such a time by a
    small fraction only)."""
    ev, row = entry["ev"], entry["row"]
    if row["numpy_rounds"] and max(row["numpy_rounds"][0] * BATCH,
                                   row["mpmath_rounds"][0]) > enough:
        return
    lam = -5 + 1j * np.linspace(1, 300, BATCH)
    t = time.perf_counter()
    ev.delta(lam)
    row["numpy_rounds"].append((time.perf_counter() - t) / BATCH)
    with mpmath.workdps(30):
        z = mpmath.mpc(-5, 150)
        t = time.perf_counter()
        ev.delta_mp(z)
        row["mpmath_rounds"].append(time.perf_counter() - t)


def _eval_series(sizes, progress) -> list:
    """Rows of :func:`_prepare` for ``(levels, springs)`` sizes, timed in rounds.

    Each of :data:`REPEAT` rounds times every size once, and each size keeps its
    minimum: a busy spell on the shared machine then falls on one round of all
    sizes rather than on all rounds of one size.
    """
    entries = []
    for n, s in sizes:
        progress(f"scaling: Delta, {n} levels, {s} springs per level")
        entries.append(_prepare(n, s))
    for _ in range(REPEAT):
        for entry in entries:
            _time_once(entry)
    rows = [e["row"] for e in entries]
    for row in rows:
        row["numpy_seconds_per_point"] = min(row["numpy_rounds"])
        row["mpmath30_seconds_per_evaluation"] = min(row["mpmath_rounds"])
    return rows


def round_exponents(rows, key: str, size: str, largest: int = 3) -> list:
    """The exponent over the ``largest`` sizes fitted to each round's timings alone (a
    size timed once gives its one timing to every round): how far the noise of the
    machine moves it.

    Examples
    --------
    >>> rows = [dict(s=1, t=[1.0, 1.2]), dict(s=2, t=[2.0, 2.0]), dict(s=4, t=[4.0])]
    >>> [round(e, 3) for e in round_exponents(rows, "t", "s")]
    [1.0, 0.868]
    """
    rows = rows[-largest:]
    rounds = max(len(r[key]) for r in rows)
    return [fit_exponent([r[size] for r in rows], [r[key][min(k, len(r[key]) - 1)]
                                                   for r in rows]) for k in range(rounds)]


def _solve_in_process(levels: int, springs: int) -> dict:
    """One full solve, profiled (run in a child process by :func:`_solve_series`)."""
    from .models import chain
    from .profiling import solve_profile

    profile, _ = solve_profile(chain(levels, springs), count=10, digits=15)
    routines = profile["routines"]
    return dict(levels=levels, springs_per_level=springs, status="ok",
                seconds=profile["seconds"], evaluations=profile["evaluations"],
                rigid_body_modes_seconds=routines["rigid_body_modes"]["seconds"],
                mpmath_share=routines["delta_mpmath"]["share"],
                mpmath_evaluations=routines["delta_mpmath"]["calls"])


def _solve_series(sizes, limit: float) -> list:
    """Solves of ``(levels, springs)`` in one child process, one JSON line each; the sizes
    not done within ``limit`` seconds are reported as timed out."""
    cmd = [sys.executable, "-m", "benchmarks.scaling", "solve",
           *[f"{n}x{s}" for n, s in sizes]]
    proc = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                            cwd=ROOT)
    try:
        out, err = proc.communicate(timeout=limit)
        status = None if proc.returncode == 0 else \
            "error: " + (err.strip().splitlines() or ["?"])[-1]
    except subprocess.TimeoutExpired:
        proc.kill()
        out, err = proc.communicate()
        status = f"timeout ({limit:g} s for the series)"
    rows = [json.loads(line) for line in out.splitlines() if line.startswith("{")]
    for n, s in sizes[len(rows):]:
        rows.append(dict(levels=n, springs_per_level=s, status=status or "not run",
                         seconds=None))
    return rows


def _exponents(out: dict, largest: int | None = None) -> dict:
    def exps(rows, key, size):
        rows = rows[-largest:] if largest else rows
        return fit_exponent([r[size] for r in rows], [r.get(key) for r in rows])

    res = {
        "eval_numpy_vs_levels": exps(out["eval_levels"], "numpy_seconds_per_point", "levels"),
        "eval_mpmath_vs_levels": exps(out["eval_levels"], "mpmath30_seconds_per_evaluation",
                                      "levels"),
        "eval_numpy_vs_springs": exps(out["eval_springs"], "numpy_seconds_per_point",
                                      "springs_per_level"),
        "eval_mpmath_vs_springs": exps(out["eval_springs"], "mpmath30_seconds_per_evaluation",
                                       "springs_per_level"),
    }
    if not largest:
        res["solve_vs_levels"] = exps(out["solve_levels"], "seconds", "levels")
        res["solve_vs_springs"] = exps(out["solve_springs"], "seconds", "springs_per_level")
    return res


def run(quick: bool = False, progress=print) -> dict:
    pick = 1 if quick else 0
    limit = SOLVE_LIMIT[pick]
    out = {"model": "benchmarks.models.chain (random beams and spring positions, seeded)",
           "fixed_springs_per_level": FIXED_SPRINGS, "fixed_levels": FIXED_LEVELS,
           "sizes": {k: v[pick] for k, v in SIZES.items()}, "solve_limit_seconds": limit,
           "batch": BATCH, "repeat": REPEAT}
    out["eval_levels"] = _eval_series([(n, FIXED_SPRINGS) for n in SIZES["eval_levels"][pick]],
                                      progress)
    out["eval_springs"] = _eval_series(
        [(FIXED_LEVELS, s) for s in SIZES["eval_springs"][pick]], progress)
    levels = [(n, FIXED_SPRINGS) for n in SIZES["solve_levels"][pick]]
    springs = [(FIXED_LEVELS, s) for s in SIZES["solve_springs"][pick]]
    done = {}
    # the size both share is solved once; in the full run two series, so that a time-out
    # among the levels leaves the springs' solves (the quick run's small sizes share one
    # child process: one start-up less)
    rest = [k for k in springs if k not in levels]
    for series in ([levels + rest] if quick else [levels, rest]):
        progress(f"scaling: {len(series)} full solves in a child process")
        done.update({(r["levels"], r["springs_per_level"]): r
                     for r in _solve_series(series, limit * len(series))})
    out["solve_levels"] = [done[k] for k in levels]
    out["solve_springs"] = [done[k] for k in springs]
    out["exponents"] = _exponents(out)
    out["exponents_largest_three"] = _exponents(out, 3)
    out["target"] = _target(out)
    return out


def _target(out: dict) -> dict:
    """The springs target on the median of the exponents fitted to single rounds.

    A round times the largest three sizes within about a second, under one state of
    the machine, whose speed was seen to change by a factor two from one second to
    the next; the per-size minima mix rounds, so a fast spell on a small size and a
    slow one on the largest move their exponent further. The median over rounds
    discards the disturbed rounds; both are reported.
    """
    rounds = {k: round_exponents(out["eval_springs"], f"{k}_rounds", "springs_per_level")
              for k in ("numpy", "mpmath")}
    median = {k: float(np.median(v)) if v else None for k, v in rounds.items()}
    minima = out["exponents_largest_three"]
    return dict(text="cost per evaluation grows linearly with springs (exponent over the "
                     "largest three sizes, median over rounds of timings, at most 1.15)",
                exponent_numpy=median["numpy"], exponent_mpmath=median["mpmath"],
                rounds_numpy=rounds["numpy"], rounds_mpmath=rounds["mpmath"],
                minima_numpy=minima["eval_numpy_vs_springs"],
                minima_mpmath=minima["eval_mpmath_vs_springs"],
                met=bool(all(v is not None and v <= 1.15 for v in median.values())))


if __name__ == "__main__" and len(sys.argv) >= 3 and sys.argv[1] == "solve":
    # worker: python -m benchmarks.scaling solve LEVELSxSPRINGS ... (one JSON line per solve)
    for arg in sys.argv[2:]:
        n, s = (int(v) for v in arg.split("x"))
        print(json.dumps(_solve_in_process(n, s)), flush=True)
