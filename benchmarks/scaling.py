"""Cost against model size: levels (beams in a chain) and springs per level.

Models are :func:`benchmarks.models.chain`: random beams over ``[0, 1]``,
level ``i`` joined to level ``i + 1`` (the last to the ground) by
``springs_per_level`` springs at random positions, distinct over the model,
so a chain of ``n`` levels with ``s`` springs per level is cut at ``n s``
points on every level: ``n (n s + 1)`` beam segments, ``2 n`` columns carried
through them. Per evaluation of ``Delta`` the work therefore grows like
``n**3 s`` in the number of levels and linearly in the springs.

Measured:

* time per evaluation of ``Delta``: the vectorised numpy evaluator (per
  point, over a batch) and ``Evaluator.delta_mp`` at 30 digits (what the
  refinement of the default search uses);
* time per full solve (first 10 natural frequencies, 15 digits, default
  method), each in its own process with a time limit;
* exponents fitted by least squares on log-log.

Full solves are limited to the sizes listed in :data:`SIZES` (the default
search's mpmath evaluations at 50 levels cost about 20 s each).
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

__all__ = ["run", "SIZES", "fit_exponent"]

#: Sizes per measurement, (full run, quick run).
SIZES = {
    "eval_levels": ((1, 2, 3, 5, 10, 20, 50), (1, 2, 5, 10)),
    "eval_springs": ((1, 2, 5, 10, 20, 50, 100), (1, 2, 5, 10, 20)),
    "solve_levels": ((1, 2, 3, 5, 7, 10), (1, 2, 3)),
    "solve_springs": ((1, 2, 5, 10, 20, 50), (1, 2, 4)),
}
#: Springs per level when the levels vary; levels when the springs vary.
FIXED_SPRINGS = 2
FIXED_LEVELS = 2
#: Time limit of one full solve (seconds), (full run, quick run).
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


def _eval_times(levels: int, springs: int, quick: bool) -> dict:
    from symtmm.compile import Evaluator

    from .models import chain

    model = chain(levels, springs)
    ev = Evaluator(model)
    segments = sum(len(items) for kind, items in ev._steps if kind == "segments")
    n_pts = 2000 if segments < 200 else 200
    lam = -5 + 1j * np.linspace(1, 300, n_pts)
    best = np.inf
    for _ in range(3):
        t = time.perf_counter()
        ev.delta(lam)
        best = min(best, time.perf_counter() - t)
    numpy_per_point = best / n_pts
    # mpmath: as many points as fit in about a second (at least one)
    mp_times = []
    budget = 0.5 if quick else 2.0
    start = time.perf_counter()
    with mpmath.workdps(30):
        for w in np.linspace(10, 300, 8):
            t = time.perf_counter()
            ev.delta_mp(mpmath.mpc(-5, w))
            mp_times.append(time.perf_counter() - t)
            if time.perf_counter() - start > budget:
                break
    return dict(levels=levels, springs_per_level=springs, segments=segments,
                numpy_seconds_per_point=numpy_per_point,
                mpmath30_seconds_per_evaluation=float(np.median(mp_times)))


def _solve_in_process(levels: int, springs: int, exact_rank: bool) -> dict:
    """One full solve (run in a child process by :func:`_solve_times`)."""
    from symtmm.roots import undamped
    from symtmm.solve import solve

    from .models import chain

    model = chain(levels, springs)
    if exact_rank:
        undamped.rigid_body_modes = _rigid_body_modes_qq
    t = time.perf_counter()
    rigid = undamped.rigid_body_modes(model)
    rigid_seconds = time.perf_counter() - t
    t = time.perf_counter()
    spectrum = solve(model, count=10, digits=15)
    seconds = time.perf_counter() - t
    return dict(levels=levels, springs_per_level=springs, status="ok", seconds=seconds,
                evaluations=spectrum.evaluations, rigid_body_modes_seconds=rigid_seconds,
                rigid=rigid)


def _rigid_body_modes_qq(model) -> int:
    """The nullity of the exact ``R(0)`` by elimination over the rationals (DomainMatrix):
    the proposed replacement for ``Matrix.rank(simplify=True)``."""
    import sympy as sp
    from sympy.polys.matrices import DomainMatrix

    from symtmm.assembly import boundary_matrix

    R = boundary_matrix(model.require_numeric(), lam=sp.Integer(0))
    return R.shape[1] - DomainMatrix.from_Matrix(R).rank()


def _solve_times(levels: int, springs: int, limit: float, exact_rank: bool = False) -> dict:
    cmd = [sys.executable, "-m", "benchmarks.scaling", "solve", str(levels), str(springs)]
    if exact_rank:
        cmd.append("--exact-rank")
    start = time.perf_counter()
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=limit, cwd=ROOT,
                             check=False)
    except subprocess.TimeoutExpired:
        return dict(levels=levels, springs_per_level=springs, status=f"timeout ({limit:g} s)",
                    seconds=None)
    if out.returncode != 0:
        return dict(levels=levels, springs_per_level=springs,
                    status="error: " + (out.stderr.strip().splitlines() or ["?"])[-1],
                    seconds=None, wall=time.perf_counter() - start)
    return json.loads(out.stdout.strip().splitlines()[-1])


def run(quick: bool = False, progress=print) -> dict:
    pick = 1 if quick else 0
    limit = SOLVE_LIMIT[pick]
    out = {"model": "benchmarks.models.chain (random beams and spring positions, seeded)",
           "fixed_springs_per_level": FIXED_SPRINGS, "fixed_levels": FIXED_LEVELS,
           "sizes": {k: v[pick] for k, v in SIZES.items()}, "solve_limit_seconds": limit}
    rows = []
    for n in SIZES["eval_levels"][pick]:
        progress(f"scaling: Delta, {n} levels")
        rows.append(_eval_times(n, FIXED_SPRINGS, quick))
    out["eval_levels"] = rows
    rows = []
    for s in SIZES["eval_springs"][pick]:
        progress(f"scaling: Delta, {s} springs per level")
        rows.append(_eval_times(FIXED_LEVELS, s, quick))
    out["eval_springs"] = rows
    rows = []
    for n in SIZES["solve_levels"][pick]:
        progress(f"scaling: solve, {n} levels")
        rows.append(_solve_times(n, FIXED_SPRINGS, limit))
    out["solve_levels"] = rows
    if not quick:
        # the same sizes with the exact rank over the rationals (the proposed fix)
        rows = []
        for n in SIZES["solve_levels"][pick]:
            if n < 5:
                continue
            progress(f"scaling: solve, {n} levels, rank over QQ")
            rows.append(_solve_times(n, FIXED_SPRINGS, limit, exact_rank=True))
        out["solve_levels_exact_rank"] = rows
    rows = []
    for s in SIZES["solve_springs"][pick]:
        progress(f"scaling: solve, {s} springs per level")
        rows.append(_solve_times(FIXED_LEVELS, s, limit))
    out["solve_springs"] = rows

    def exps(rows, key, size):
        return fit_exponent([r[size] for r in rows], [r.get(key) for r in rows])

    out["exponents"] = {
        "eval_numpy_vs_levels": exps(out["eval_levels"], "numpy_seconds_per_point", "levels"),
        "eval_mpmath_vs_levels": exps(out["eval_levels"], "mpmath30_seconds_per_evaluation",
                                      "levels"),
        "eval_numpy_vs_springs": exps(out["eval_springs"], "numpy_seconds_per_point",
                                      "springs_per_level"),
        "eval_mpmath_vs_springs": exps(out["eval_springs"], "mpmath30_seconds_per_evaluation",
                                       "springs_per_level"),
        "solve_vs_levels": exps(out["solve_levels"], "seconds", "levels"),
        "solve_vs_springs": exps(out["solve_springs"], "seconds", "springs_per_level"),
    }
    # the largest three sizes only: where the per-call overheads no longer dominate
    out["exponents_largest_three"] = {
        "eval_numpy_vs_levels": exps(out["eval_levels"][-3:], "numpy_seconds_per_point",
                                     "levels"),
        "eval_mpmath_vs_levels": exps(out["eval_levels"][-3:],
                                      "mpmath30_seconds_per_evaluation", "levels"),
        "eval_numpy_vs_springs": exps(out["eval_springs"][-3:], "numpy_seconds_per_point",
                                      "springs_per_level"),
        "eval_mpmath_vs_springs": exps(out["eval_springs"][-3:],
                                       "mpmath30_seconds_per_evaluation", "springs_per_level"),
    }
    if "solve_levels_exact_rank" in out:
        out["exponents"]["solve_vs_levels_exact_rank"] = exps(
            [r for r in out["solve_levels"] if r["levels"] < 5 and r.get("seconds")]
            + out["solve_levels_exact_rank"], "seconds", "levels")
    e = out["exponents_largest_three"]["eval_numpy_vs_springs"]
    e_mp = out["exponents_largest_three"]["eval_mpmath_vs_springs"]
    out["target"] = dict(text="cost per evaluation grows linearly with springs (exponent "
                              "fitted over the largest three sizes at most 1.15)",
                         exponent_numpy=e, exponent_mpmath=e_mp,
                         met=bool(e is not None and e_mp is not None
                                  and e <= 1.15 and e_mp <= 1.15))
    return out


if __name__ == "__main__" and len(sys.argv) >= 4 and sys.argv[1] == "solve":
    # worker: python -m benchmarks.scaling solve LEVELS SPRINGS [--exact-rank]
    print(json.dumps(_solve_in_process(int(sys.argv[2]), int(sys.argv[3]),
                                       "--exact-rank" in sys.argv)))
