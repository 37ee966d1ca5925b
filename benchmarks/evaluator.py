"""Determinant evaluations per second, every backend beside the naive product.

Backends, all evaluating ``Delta(lam)`` of the same model at the same points
``lam = -sigma + i omega`` spread over ``0 <= sigma <= 50``,
``1 <= omega <= 300``:

* ``symtmm`` -- :meth:`symtmm.compile.Evaluator.delta` on the whole array:
  vectorised numpy, double precision, the columns re-orthonormalised along
  the span (stable at any mode);
* ``symtmm_plain`` -- ``np.linalg.det(Evaluator.R(lam))`` on the whole
  array: the plain transfer product, vectorised, without re-orthonormalisation;
* ``naive_numpy`` -- :class:`benchmarks.baselines.NaiveTransfer`, one point
  at a time;
* ``mpmath_30``, ``mpmath_60`` -- :meth:`Evaluator.delta_mp` at 30 and 60
  digits, one point at a time;
* ``generated_c`` -- the C evaluator of :mod:`symtmm.codegen` as generated,
  ``gcc -O2``, the loop over points inside C; ``generated_c_ctypes`` -- the
  same library called once per point from Python through ctypes.

Every rate is the minimum time of several repetitions of a fixed batch (the
machine is shared: the minimum is the run least disturbed by other work);
a call over 5 s is timed once, and the C loop, timed inside C, runs on as
many points of the batch as fit in about a second.
Accuracy: each backend's relative error against ``Evaluator.delta_mp`` at
60 digits on the first :data:`SIZES` ``["accuracy"]`` points (the plain product in
mpmath loses about ``sum |beta| L / ln 10`` digits, at most
``digits_lost_max`` of the 60 here). The profile of one vectorised
``Evaluator.delta`` call (cProfile, own time per function) says where its
time goes.
"""

from __future__ import annotations

import cProfile
import pstats
import time

import mpmath
import numpy as np

from symtmm.compile import Evaluator

from .baselines import NaiveTransfer
from .cbench import compile_c
from .models import chain, example

__all__ = ["run", "points", "SIZES"]

#: Per run (full, quick): points of a vectorised batch, of a naive batch, of an mpmath
#: batch; points at which every backend is compared with 60-digit mpmath; repetitions
#: of a batch (its minimum time is the rate's).
SIZES = {"vector": (10_000, 5000), "naive": (1000, 300), "mpmath": (10, 10),
         "accuracy": (40, 20), "repeat": (7, 3)}


def points(n: int, seed: int = 0) -> np.ndarray:
    """``n`` eigenvalues ``-sigma + i omega``, ``sigma`` in [0, 50], ``omega`` in [1, 300]."""
    rng = np.random.default_rng(seed)
    return -50 * rng.random(n) + 1j * (1 + 299 * rng.random(n))


def _min_seconds(fn, repeat: int, enough: float = 5.0) -> float:
    """The smallest wall time of ``repeat`` calls of ``fn()``; a call longer than
    ``enough`` seconds is not repeated (the full run's 10-level chain)."""
    best = np.inf
    for _ in range(repeat):
        t = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t)
        if best > enough:
            break
    return best


def _mp_values(ev: Evaluator, lam, dps: int) -> list:
    with mpmath.workdps(dps):
        return [ev.delta_mp(mpmath.mpc(z.real, z.imag)) for z in lam]


def _rel_errors(values, reference) -> dict:
    """Median and largest ``|value - reference| / |reference|`` (60-digit reference)."""
    with mpmath.workdps(60):
        errs = [float(abs(mpmath.mpmathify(v if isinstance(v, mpmath.mpc) else complex(v)) - r)
                      / abs(r)) for v, r in zip(values, reference)]
    return dict(median=float(np.median(errs)), max=float(np.max(errs)))


def _delta_profile(ev: Evaluator, lam) -> dict:
    """Own time of the functions of one vectorised ``Evaluator.delta`` call (cProfile)."""
    prof = cProfile.Profile()
    prof.enable()
    ev.delta(lam)
    prof.disable()
    stats = pstats.Stats(prof).stats
    total = sum(tt for _, _, tt, _, _ in stats.values())
    rows = sorted(((tt, f"{file.rsplit('/', 1)[-1]}:{func}") for (file, _, func), (_, _, tt, _, _)
                   in stats.items()), reverse=True)[:5]
    return dict(points=len(lam), seconds=total,
                own_time={name: dict(seconds=tt, share=tt / total) for tt, name in rows})


def _single_point_seconds(fn, lam, repeat: int = 30) -> float:
    """Seconds of one call of the vectorised ``fn`` on a single point (the default
    search's refinement calls ``log_delta`` one point at a time)."""
    return _min_seconds(lambda: fn(lam[:1]), repeat)


def _c_rates(model, lam, n_acc: int, repeat: int, rates: dict, values: dict) -> None:
    c = compile_c(model)
    if c is None:
        rates["generated_c"] = rates["generated_c_ctypes"] = None
        return
    # the loop is timed inside C, so the batch size does not change the rate: take as many
    # points as fit in about a second (the full run's 10-level chain costs ms per point)
    per_point = c.delta_loop(lam[:100])[1] / 100
    n = int(min(lam.size, max(100, n_acc, 1.0 / max(per_point, 1e-9))))
    best = np.inf
    for _ in range(repeat):
        out, seconds = c.delta_loop(lam[:n])
        best = min(best, seconds)
    rates["generated_c"] = n / best
    values["generated_c"] = out[:n_acc]
    rates["generated_c_ctypes"] = n / _min_seconds(lambda: c.delta_ctypes(lam[:n]),
                                                   max(2, repeat // 2))


def measure(model, name: str, quick: bool) -> dict:
    """Rates, accuracy and the profile of ``Evaluator.delta`` on ``model``."""
    n_vec, n_naive, n_mp, n_acc, repeat = (SIZES[k][quick] for k in
                                           ("vector", "naive", "mpmath", "accuracy", "repeat"))
    lam = points(n_vec)
    acc = lam[:n_acc]
    ev = Evaluator(model)
    naive = NaiveTransfer(model)
    rates, values = {}, {}
    rates["symtmm"] = n_vec / _min_seconds(lambda: ev.delta(lam), repeat)
    rates["symtmm_plain"] = n_vec / _min_seconds(lambda: np.linalg.det(ev.R(lam)), repeat)
    rates["naive_numpy"] = n_naive / _min_seconds(lambda: naive.delta(lam[:n_naive]), 3)
    values["symtmm"] = ev.delta(acc)
    values["symtmm_plain"] = np.linalg.det(ev.R(acc))
    values["naive_numpy"] = naive.delta(acc)
    batch = lam[n_acc:n_acc + n_mp]
    for dps in (30, 60):
        rates[f"mpmath_{dps}"] = n_mp / _min_seconds(lambda d=dps: _mp_values(ev, batch, d), 3)
    _c_rates(model, lam, n_acc, repeat, rates, values)
    reference = _mp_values(ev, acc, 60)
    values["mpmath_30"] = _mp_values(ev, acc, 30)
    accuracy = {k: _rel_errors(v, reference) for k, v in values.items()}
    ratios = {k: (round(v / rates["naive_numpy"], 2) if v else None) for k, v in rates.items()}
    single = dict(symtmm=_single_point_seconds(ev.delta, lam),
                  symtmm_plain=_single_point_seconds(lambda z: np.linalg.det(ev.R(z)), lam))
    return dict(model=name, levels=len(model.beams), springs=len(model.springs),
                points=dict(vector=n_vec, naive=n_naive, mpmath=n_mp, accuracy=n_acc,
                            repeat=repeat),
                points_per_second={k: (round(v, 1) if v else None) for k, v in rates.items()},
                ratio_to_naive_numpy=ratios, relative_error_vs_mpmath_60=accuracy,
                digits_lost_max=max(ev.digits_lost(z) for z in acc),
                seconds_per_single_point_call=single,
                delta_profile=_delta_profile(ev, lam))


def run(quick: bool = False, progress=print) -> dict:
    """Rates on example 1 (the headline figures), and in the full run example 3 and a
    10-level random chain."""
    models = [("paper_ex1_ff_cc", example("paper_ex1_ff_cc"))]
    if not quick:
        models += [("paper_ex3_three_pp_coupled", example("paper_ex3_three_pp_coupled")),
                   ("chain_10_levels_2_springs", chain(10, 2))]
    results = []
    for name, model in models:
        progress(f"evaluator: {name}")
        results.append(measure(model, name, quick))
    head = results[0]
    ratio = head["ratio_to_naive_numpy"]["symtmm"]
    return dict(model=head["model"], points_per_second=head["points_per_second"],
                ratio_to_naive_numpy=head["ratio_to_naive_numpy"],
                relative_error_vs_mpmath_60=head["relative_error_vs_mpmath_60"], models=results,
                target=dict(text="the compiled (vectorised numpy) evaluator, Evaluator.delta, "
                                 "is at least 100 times the naive per-point product",
                            ratio=ratio, met=bool(ratio >= 100),
                            by_model={r["model"]: r["ratio_to_naive_numpy"]["symtmm"]
                                      for r in results}))
