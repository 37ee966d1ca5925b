"""Determinant evaluations per second, every backend beside the naive product.

Backends, all evaluating ``Delta(lam)`` of the same model at the same points
``lam = -sigma + i omega`` spread over ``0 <= sigma <= 50``,
``1 <= omega <= 300``:

* ``symtmm`` -- :meth:`symtmm.compile.Evaluator.delta` on the whole array
  (vectorised numpy, double precision);
* ``naive_numpy`` -- :class:`benchmarks.baselines.NaiveTransfer`, one point
  at a time;
* ``mpmath_30``, ``mpmath_60`` -- :meth:`Evaluator.delta_mp` at 30 and 60
  digits, one point at a time;
* ``generated_c`` -- the C evaluator of :mod:`symtmm.codegen`, ``gcc -O2``,
  the loop over points inside C; ``generated_c_ctypes`` -- the same library
  called once per point from Python through ctypes.

Each rate is the best of a few repetitions (the machine is shared).
"""

from __future__ import annotations

import time

import mpmath
import numpy as np

from symtmm.compile import Evaluator

from .baselines import NaiveTransfer
from .cbench import compile_c
from .models import chain, example

__all__ = ["run", "points"]


def points(n: int, seed: int = 0) -> np.ndarray:
    """``n`` eigenvalues ``-sigma + i omega``, ``sigma`` in [0, 50], ``omega`` in [1, 300]."""
    rng = np.random.default_rng(seed)
    return -50 * rng.random(n) + 1j * (1 + 299 * rng.random(n))


def _best_rate(fn, n_points: int, repeat: int, budget: float) -> float:
    """Points per second of ``fn()`` (which evaluates ``n_points``), best of ``repeat``."""
    best = np.inf
    start = time.perf_counter()
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
        if time.perf_counter() - start > budget:
            break
    return n_points / best


def _mp_rate(ev: Evaluator, lam, dps: int, budget: float) -> float:
    """Points per second of ``delta_mp`` at ``dps`` digits, as many points as fit ``budget``."""
    done = 0
    start = time.perf_counter()
    with mpmath.workdps(dps):
        for z in lam:
            ev.delta_mp(mpmath.mpc(z.real, z.imag))
            done += 1
            if time.perf_counter() - start > budget:
                break
    return done / (time.perf_counter() - start)


def measure(model, name: str, quick: bool) -> dict:
    """Rates of every backend on ``model``."""
    n_vec = 10_000
    lam = points(n_vec)
    ev = Evaluator(model)
    reference = ev.delta(lam)
    scale = np.max(np.abs(reference))
    rates, agreement = {}, {}
    rates["symtmm"] = _best_rate(lambda: ev.delta(lam), n_vec, 3 if quick else 7,
                                 2 if quick else 10)
    naive = NaiveTransfer(model)
    n_naive = 200 if quick else 1000
    rates["naive_numpy"] = _best_rate(lambda: naive.delta(lam[:n_naive]), n_naive, 1 if quick
                                      else 3, 5)
    agreement["naive_numpy"] = float(np.max(np.abs(naive.delta(lam[:50]) - reference[:50]))
                                     / scale)
    for dps in (30, 60):
        rates[f"mpmath_{dps}"] = _mp_rate(ev, lam, dps, 1.0 if quick else 5.0)
    c = compile_c(model)
    if c is None:
        rates["generated_c"] = rates["generated_c_ctypes"] = None
    else:
        best_loop = np.inf
        for _ in range(3 if quick else 7):
            values, seconds = c.delta_loop(lam)
            best_loop = min(best_loop, seconds)
        rates["generated_c"] = n_vec / best_loop
        agreement["generated_c"] = float(np.max(np.abs(values - reference)) / scale)
        best_ct = np.inf
        for _ in range(2 if quick else 5):
            _, seconds = c.delta_ctypes(lam)
            best_ct = min(best_ct, seconds)
        rates["generated_c_ctypes"] = n_vec / best_ct
    rates = {k: (round(v, 1) if v is not None else None) for k, v in rates.items()}
    ratios = {k: (v / rates["naive_numpy"] if v else None) for k, v in rates.items()}
    return dict(model=name, levels=len(model.beams), springs=len(model.springs),
                points_per_second=rates,
                ratio_to_naive_numpy={k: round(v, 2) if v else v for k, v in ratios.items()},
                max_abs_difference_relative_to_max_delta=agreement)


def run(quick: bool = False, progress=print) -> dict:
    """Rates on example 1 (the headline figures), example 3 and a 10-level random chain."""
    models = [("paper_ex1_ff_cc", example("paper_ex1_ff_cc")),
              ("paper_ex3_three_pp_coupled", example("paper_ex3_three_pp_coupled"))]
    if not quick:
        models.append(("chain_10_levels_2_springs", chain(10, 2)))
    results = []
    for name, model in models:
        progress(f"evaluator: {name}")
        results.append(measure(model, name, quick))
    head = results[0]
    ratio = head["ratio_to_naive_numpy"]["symtmm"]
    return dict(model=head["model"], points_per_second=head["points_per_second"],
                ratio_to_naive_numpy=head["ratio_to_naive_numpy"], models=results,
                target=dict(text="the compiled (vectorised numpy) evaluator is at least 100 "
                                 "times the naive per-point product",
                            ratio=ratio, met=bool(ratio >= 100),
                            by_model={r["model"]: r["ratio_to_naive_numpy"]["symtmm"]
                                      for r in results}))
