"""The batched double-precision ``Delta`` against the transcendental functions it must evaluate.

The numeric kernel evaluates ``Delta(i omega)`` (and the eigenvalue count: one
factorization gives both, :func:`benchmarks.kernel.internals`) for a batch of
frequencies at once. What it cannot avoid is the transcendental functions of
its segments: ``cos, cosh, sin, sinh`` of ``beta l`` for every distinct segment
kind of the compiled model (pieces of equal constants share one), at every
point. The target compares the cost of a batch of ``Delta`` with the cost of
exactly that many numpy ``cos, cosh, sin, sinh`` calls' worth of arguments
(:data:`BATCH` points x the kinds, real arguments in ``[0, 3]`` like the
pieces' ``beta l``): at most :data:`LIMIT` times.

What it cannot avoid either is the elimination of its band: timed alone (the
kernel's own compiled loop, on a copy of ``K`` at the same points), it is
reported beside the target, and ``Delta / (transcendental + elimination)``
says how much the rest (assembly, bounds, signs, logarithms) adds to the two.

Beside it, for the same frequencies: the naive per-point numpy transfer
product a user would write (:class:`benchmarks.baselines.NaiveTransfer`), and the
C evaluator symtmm generates (``symtmm codegen --lang c``, ``gcc -O2``, the loop
over points timed inside C; the transfer-matrix algorithm), per point. Every
time is the minimum of several repetitions. The accuracy of the double
``Delta``: its ``log|Delta|`` against the 50-digit one at :data:`ACCURACY`
points. The baselines run on the models up to 10 levels (the naive product takes
seconds per point at 50 levels). The profile of three batch calls (cProfile, own
time per function) says where the time goes.
"""

from __future__ import annotations

import contextlib
import cProfile
import math
import pstats
import time

import mpmath
import numpy as np

from .baselines import NaiveTransfer
from .cbench import compile_c
from .kernel import internals
from .models import chain, example

__all__ = ["run", "measure", "BATCH", "LIMIT"]

OMEGA_MAX = 300.0
BATCH = 1000
ACCURACY = 20
LIMIT = 5.0
#: name: (model builder, time the per-point baselines on it: the naive product takes
#: seconds per point at 50 levels, the generated C minutes to compile)
MODELS = {"ex1": (lambda: example("paper_ex1_ff_cc"), True),
          "ex3": (lambda: example("paper_ex3_three_pp_coupled"), True),
          "chain10": (lambda: chain(10, 2), True),
          "chain50": (lambda: chain(50, 2), False)}
QUICK = ("ex1", "chain10")


def _min_seconds(fn, repeat: int, enough: float = 5.0) -> float:
    """The smallest wall time of ``repeat`` calls of ``fn()`` (one where a call takes over
    ``enough`` seconds)."""
    best = np.inf
    for _ in range(repeat):
        start = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - start)
        if best > enough:
            break
    return best


@contextlib.contextmanager
def _threads(count: int):
    """symtmm's compiled batches on ``count`` threads for the duration."""
    from symtmm.numeric import parallel
    saved = parallel.WORKERS
    parallel.WORKERS = count
    try:
        yield
    finally:
        parallel.WORKERS = saved


def _own_time(fn, top: int = 6, calls: int = 3) -> dict:
    """Own time of the functions of ``calls`` calls of ``fn`` (cProfile; several, so that
    one disturbed call weighs less), the largest ``top``."""
    prof = cProfile.Profile()
    prof.enable()
    for _ in range(calls):
        fn()
    prof.disable()
    stats = pstats.Stats(prof).stats
    total = sum(tt for _, _, tt, _, _ in stats.values())
    rows = sorted(((tt, f"{file.rsplit('/', 1)[-1]}:{func}", calls)
                   for (file, _, func), (_, calls, tt, _, _) in stats.items()), reverse=True)
    return dict(seconds=total, own_time={name: dict(seconds=tt, share=tt / total, calls=calls)
                                         for tt, name, calls in rows[:top]})


def _accuracy(kernel, omegas) -> dict:
    """Median and largest ``|log|Delta| - log|Delta_50||`` (about the relative error of
    ``|Delta|``) at ``omegas``; inf where the signs differ. Near an eigenvalue ``Delta``
    is small and its relative error large, so the median says more than the largest."""
    logabs, sign = kernel.delta(omegas)
    high = kernel.delta([mpmath.mpf(float(w)) for w in omegas], 50)
    errors = [math.inf if (h < 0) != (s < 0) else abs(la - float(mpmath.log(abs(h))))
              for la, s, h in zip(logabs, sign, high)]
    return dict(median=float(np.median(errors)), max=float(max(errors)))


def measure(model, quick: bool, baselines: bool) -> dict:
    """Per-point costs on one model: kernel ``Delta``, transcendental floor, naive, C."""
    repeat = 3 if quick else 7
    kernel = internals().kernel(model, OMEGA_MAX)
    omegas = np.linspace(1.0, OMEGA_MAX, BATCH)
    kernel.delta(omegas)                       # plan and tables built once, outside the timing
    size = kernel.size(OMEGA_MAX)
    # on one thread, as numpy's transcendental functions run: the target compares work with
    # work; the batch in parts on the machine's threads (symtmm.numeric.parallel) beside it
    with _threads(1):
        per = {"delta": _min_seconds(lambda: kernel.delta(omegas), repeat) / BATCH}
    per["delta_threads"] = _min_seconds(lambda: kernel.delta(omegas), repeat) / BATCH
    x = 3.0 * np.random.default_rng(0).random(BATCH * size["kinds"])
    per["transcendental"] = _min_seconds(lambda: (np.cos(x), np.cosh(x), np.sin(x), np.sinh(x)),
                                         repeat) / BATCH
    per["elimination"] = _min_seconds(kernel.elimination(omegas), repeat) / BATCH
    lam = 1j * omegas
    per["naive_numpy"] = per["generated_c"] = None
    if baselines:
        naive_points = 30 if quick else 100
        naive = NaiveTransfer(model)
        per["naive_numpy"] = _min_seconds(lambda: naive.delta(lam[:naive_points]),
                                          3) / naive_points
    if baselines and not quick:
        c = compile_c(model)
        if c is not None:
            per["generated_c"] = min(c.delta_loop(lam)[1] for _ in range(repeat)) / BATCH
    return dict(size, seconds_per_point=per,
                ratio_to_transcendental=per["delta"] / per["transcendental"],
                elimination_to_transcendental=per["elimination"] / per["transcendental"],
                ratio_to_floor=per["delta"] / (per["transcendental"] + per["elimination"]),
                log_delta_error=_accuracy(kernel, omegas[::BATCH // ACCURACY]),
                threads=_thread_count(),
                profile=_one_thread_profile(kernel, omegas))


def _one_thread_profile(kernel, omegas) -> dict:
    """:func:`_own_time` of the batch on one thread, as the target's ratio is taken (on
    several, the calling thread's wait for the others' parts shows as a lock's own time)."""
    with _threads(1):
        return _own_time(lambda: kernel.delta(omegas))


def _thread_count() -> int:
    from symtmm.numeric import parallel
    return parallel.WORKERS


def run(quick: bool = False, progress=print) -> dict:
    names = QUICK if quick else tuple(MODELS)
    models = {}
    for name in names:
        progress(f"evaluator: {name}")
        build, baselines = MODELS[name]
        models[name] = measure(build(), quick, baselines)
    ratios = {n: m["ratio_to_transcendental"] for n, m in models.items()}
    return dict(batch=BATCH, omega_max=OMEGA_MAX, accuracy_points=ACCURACY, models=models,
                target=dict(text=f"the batched double-precision Delta costs at most {LIMIT:g}x "
                                 "numpy cos, cosh, sin, sinh on its arguments (one per distinct "
                                 "segment kind and point)",
                            ratios=ratios, met=bool(all(r <= LIMIT for r in ratios.values()))))
