"""The finite-element alternative: cubic-Hermite beam elements (:mod:`symtmm.fe`).

For the paper's example 1, the first 10 natural frequencies of the FE model
with 10 to 1000 elements per beam (consistent mass, dense
:func:`scipy.linalg.eigh`) are compared with the independent global-matrix
reference (:func:`benchmarks.references.ex1_omegas`), beside the time
symtmm needs for 1e-12 (a 13-digit default solve), split over the library's
routines (:func:`benchmarks.profiling.solve_profile`).

The FE times are measured twice: in this process, with the BLAS threads
numpy and scipy start by default, and in a child process with one BLAS
thread (``OPENBLAS_NUM_THREADS=1`` and its kin). On a loaded two-core machine
the default threads wait on each other: a 400-unknown ``eigh`` can take a
hundred times longer than with one thread. The target compares symtmm with
the faster of the two, what a user who knows this gets.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

import mpmath
import numpy as np

from symtmm.solve import solve

from . import references
from .models import check_ex1_model, example, fe_input
from .profiling import solve_profile

__all__ = ["run", "ELEMENTS", "ELEMENTS_QUICK", "fe_times"]

ELEMENTS = (10, 20, 50, 100, 200, 500, 1000)
ELEMENTS_QUICK = (10, 20, 50, 100)
COUNT = 10
ROOT = Path(__file__).resolve().parent.parent
#: Environment variables that set the BLAS thread count of the usual builds.
_ONE_THREAD = {k: "1" for k in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")}


def _rel_errors(values, reference) -> float:
    with mpmath.workdps(40):
        return max(float(abs(mpmath.mpf(float(v)) - r) / r) for v, r in zip(values, reference))


def fe_times(elements, repeat: int = 3, enough: float = 1.0) -> list:
    """``(elements per beam, best seconds, frequencies)`` of example 1's FE model.

    The best of ``repeat`` runs; a run over ``enough`` seconds is not repeated
    (with the default BLAS threads on a loaded machine a 100-element solve can
    take seconds instead of hundredths).
    """
    from symtmm.fe import fe_frequencies

    beams, springs = fe_input(example("paper_ex1_ff_cc"))
    out = []
    for n in elements:
        best, omegas = np.inf, None
        for _ in range(repeat):
            t = time.perf_counter()
            omegas = fe_frequencies(beams, springs, n, count=COUNT)
            best = min(best, time.perf_counter() - t)
            if best > enough:
                break
        out.append((n, best, [float(w) for w in omegas]))
    return out


def _fe_times_one_thread(elements, limit: float = 300.0):
    """:func:`fe_times` in a child process with one BLAS thread; None if it fails."""
    cmd = [sys.executable, "-m", "benchmarks.fe_compare", "one-thread",
           *[str(n) for n in elements]]
    try:
        out = subprocess.run(cmd, capture_output=True, text=True, timeout=limit, cwd=ROOT,
                             env={**os.environ, **_ONE_THREAD}, check=False)
    except subprocess.TimeoutExpired:
        return None
    if out.returncode != 0:
        return None
    return json.loads(out.stdout.strip().splitlines()[-1])


def _symtmm(reference) -> dict:
    """symtmm's 13-digit default solve: plain time, error, and the profiled split."""
    model = example("paper_ex1_ff_cc")
    best = np.inf
    for _ in range(3):          # the fastest of three (shared machine)
        start = time.perf_counter()
        spec = solve(model, count=COUNT, digits=13)
        best = min(best, time.perf_counter() - start)
    with mpmath.workdps(40):
        printed = [mpmath.mpf(e.to_dict()["imag"]) for e in spec]
        error = max(float(abs(p - r) / r) for p, r in zip(printed, reference))
    profile, _ = solve_profile(model, count=COUNT, digits=13)
    return dict(digits=13, seconds=round(best, 4), max_rel_error=error,
                evaluations=spec.evaluations, profile=profile)


def _error_exponent(rows) -> tuple:
    """Fitted exponent of the FE error against elements per beam, over the meshes where
    the error still falls (finer ones meet rounding), and those meshes."""
    pts = [(rows[0]["elements_per_beam"], rows[0]["max_rel_error"])]
    for r in rows[1:]:
        if r["max_rel_error"] >= pts[-1][1]:
            break
        pts.append((r["elements_per_beam"], r["max_rel_error"]))
    if len(pts) < 2:
        return None, [p[0] for p in pts]
    slope = np.polyfit(np.log([p[0] for p in pts]), np.log([p[1] for p in pts]), 1)[0]
    return float(slope), [p[0] for p in pts]


def run(quick: bool = False, progress=print) -> dict:
    model = example("paper_ex1_ff_cc")
    check_ex1_model(model)
    progress("fe: global-matrix reference")
    reference = list(references.ex1_omegas(COUNT))
    progress("fe: symtmm to 1e-12")
    sym = _symtmm(reference)
    sizes = ELEMENTS_QUICK if quick else ELEMENTS
    progress("fe: FE model, default BLAS threads")
    default = fe_times(sizes)
    progress("fe: FE model, one BLAS thread (child process)")
    single = _fe_times_one_thread(sizes)
    rows = []
    for i, (n, seconds, omegas) in enumerate(default):
        one = single[i][1] if single else None
        rows.append(dict(elements_per_beam=n, seconds_default_threads=round(seconds, 4),
                         seconds_one_thread=round(one, 4) if one is not None else None,
                         seconds=round(min(seconds, one if one is not None else np.inf), 4),
                         max_rel_error=_rel_errors(omegas, reference)))
    reaching = [r for r in rows if r["max_rel_error"] <= 1e-6]
    fe_1e6 = min(reaching, key=lambda r: r["seconds"]) if reaching else None
    slope, slope_sizes = _error_exponent(rows)
    met = bool(sym["max_rel_error"] <= 1e-12 and fe_1e6 is not None
               and sym["seconds"] < fe_1e6["seconds"])
    return dict(
        model="paper_ex1_ff_cc", count=COUNT,
        reference=references.EX1_METHOD + " (the FE errors falling like h^4 confirm it once more)",
        blas_threads_env=sorted(_ONE_THREAD), one_thread_ok=single is not None,
        symtmm=sym, fe=rows, fe_error_exponent=slope, fe_exponent_sizes=slope_sizes,
        fe_best=min(rows, key=lambda r: r["max_rel_error"]),
        fe_fastest_to_1e6=fe_1e6,
        target=dict(text="symtmm reaches 1e-12 faster than the FE model reaches 1e-6",
                    symtmm_seconds=sym["seconds"],
                    fe_seconds=fe_1e6["seconds"] if fe_1e6 else None,
                    fe_elements=fe_1e6["elements_per_beam"] if fe_1e6 else None,
                    met=met))


if __name__ == "__main__" and len(sys.argv) >= 2 and sys.argv[1] == "one-thread":
    # worker: python -m benchmarks.fe_compare one-thread N1 N2 ... (BLAS threads set by env)
    print(json.dumps(fe_times([int(n) for n in sys.argv[2:]])))
