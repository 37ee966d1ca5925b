"""High modes: a cantilever's first 100 and 300 frequencies, symtmm against sparse FE.

A count at a beam's ``n``-th mode cut it into about ``n`` short pieces, so the first
``n`` modes cost ``O(n**2)``; counts that add the pieces' clamped-clamped eigenvalues
(``J0``, :mod:`symtmm.numeric.clamped`) take long pieces instead. Reported beside the
targets (no target of its own), measured as section 1 measures:

symtmm
    ``solve(model, count=N, digits=15)`` on a new model object with no plan kept
    (:func:`benchmarks.models.from_scratch`), the best of :data:`REPEAT`; its largest
    error against the reference, and which proofs back its values.
FE
    :mod:`benchmarks.sparse_fe`'s matrices (cubic Hermite elements) and ``eigsh(K, k=N,
    M=M, sigma=SHIFT, which="LM")`` (:func:`fe_frequencies`) on the coarsest uniform mesh whose first ``N``
    frequencies are all within 1e-6 of the reference (:func:`fe_mesh`; where none is, the
    mesh of its smallest error, which favours the FE), the best of as many runs, each
    right after one of symtmm's.
Reference
    The closed form ``1 + cos b cosh b = 0``, ``omega = b**2`` (``EI = m = L = 1``), each
    root found in mpmath at 40 digits from ``(n - 1/2) pi``.
"""

from __future__ import annotations

import time

import mpmath
import numpy as np
import scipy.sparse.linalg

from . import sparse_fe
from .fe_compare import TOLERANCE, best_seconds, rel_error
from .models import from_scratch

__all__ = ["run", "COUNTS"]

COUNTS = (100, 300)
QUICK = (100,)
DIGITS = 15
#: Timed runs per side; the best counts.
REPEAT = 3


def cantilever():
    from symtmm.model import Beam, Model
    return Model((Beam("b", 1, 1, 1, left="clamped", right="free"),))


def reference(count: int) -> list:
    """The cantilever's first ``count`` frequencies (mpmath numbers, 40 digits)."""
    with mpmath.workdps(40):
        return [mpmath.findroot(lambda b: mpmath.cos(b) + 1 / mpmath.cosh(b),
                                (n - mpmath.mpf(1) / 2) * mpmath.pi) ** 2
                for n in range(1, count + 1)]


def fe_frequencies(fe, n: int, count: int) -> np.ndarray:
    """The lowest ``count`` frequencies of the FE model on ``n`` elements: assembly and
    ``eigsh`` as :func:`benchmarks.sparse_fe.frequencies` takes them, without its zeroing
    of values below a fraction of the largest (rigid-body modes, which a cantilever has
    none of: over 300 modes that fraction of the largest passes the lowest)."""
    K, M = sparse_fe.matrices(fe, n)
    values = scipy.sparse.linalg.eigsh(K, k=count, M=M, sigma=sparse_fe.SHIFT, which="LM",
                                       return_eigenvectors=False)
    return np.sqrt(np.abs(np.sort(values)))


def fe_mesh(fe, ref) -> tuple:
    """``(elements, tried)``: the coarsest uniform mesh (a ladder growing by 1.25 from two
    elements per wavelength's half at the last mode) whose frequencies are all within
    :data:`~benchmarks.fe_compare.TOLERANCE` of ``ref``; where the FE error stops falling
    above it (rounding in the shift-invert solves of the high modes), the mesh of its
    smallest error. ``tried``: ``{elements: error}``."""
    count = len(ref)
    tried: dict = {}
    n = 2 * count
    while True:
        tried[n] = rel_error([float(w) for w in fe_frequencies(fe, n, count)], ref)
        best = min(tried, key=tried.get)
        if tried[n] <= TOLERANCE or tried[n] > 2 * tried[best] or n > 1 << 15:
            break
        n = round(1.25 * n)
    within = [k for k, e in tried.items() if e <= TOLERANCE]
    return (min(within) if within else best), tried


def measure(count: int, progress=print, repeat: int = REPEAT) -> dict:
    from symtmm.solve import solve

    model = cantilever()
    ref = reference(count)
    fe = sparse_fe.fe_input(model)
    progress(f"high_modes: {count} modes: the coarsest FE mesh within {TOLERANCE:g}")
    n, tried = fe_mesh(fe, ref)
    progress(f"high_modes: {count} modes: symtmm and the FE model, in turns")
    best, best_fe, spectrum = np.inf, np.inf, None
    for _ in range(repeat):
        fresh = from_scratch(model)
        start = time.perf_counter()
        spectrum = solve(fresh, count=count, digits=DIGITS)
        best = min(best, time.perf_counter() - start)
        best_fe = min(best_fe, best_seconds(lambda: fe_frequencies(fe, n, count), 1))
    best_fe = min(best_fe, best_seconds(lambda: fe_frequencies(fe, n, count), repeat))
    printed = [e.to_dict()["imag"] for e in spectrum]
    return dict(name=f"cantilever, {count} modes", count=count,
                symtmm=dict(seconds=best, evaluations=spectrum.evaluations,
                            max_rel_error=rel_error(printed, ref),
                            proofs={p: len(v) for p, v in spectrum.proofs().items()}),
                fe=dict(elements_per_beam=n, dofs=sparse_fe.dof_count(fe, n), seconds=best_fe,
                        max_rel_error=tried[n], within=bool(tried[n] <= TOLERANCE),
                        tried={str(k): e for k, e in sorted(tried.items())}),
                ratio=best / best_fe)


def run(quick: bool = False, progress=print) -> dict:
    cases = [measure(c, progress, repeat=1 if quick else REPEAT)
             for c in (QUICK if quick else COUNTS)]
    return dict(digits=DIGITS, tolerance=TOLERANCE, repeat=REPEAT, cases=cases,
                ratios={f"{c['count']} modes": c["ratio"] for c in cases})
