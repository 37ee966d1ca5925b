"""Mode shapes: symtmm's ``modes`` against the sparse FE model's eigenvectors.

A user who wants the first 10 mode shapes writes the FE model of section 1 and keeps
the eigenvectors ``eigsh`` returns anyway; symtmm's ``modes`` finds the eigenvalues
(the verified solve of section 1) and then each shape by the transfer walk at the
digits its cancellation needs (:mod:`symtmm.modes`). Reported beside the targets (no
target of its own): the time of each, side by side in one run, and the share of
symtmm's time the shapes take after the solve.

symtmm
    ``mode_shapes(model, count=10, points=101, digits=15)`` on a new model object
    (:func:`benchmarks.models.from_scratch`), the best of :data:`REPEAT` runs; the
    shapes' own seconds (:attr:`symtmm.modes.ModeSet.seconds`) of that run.
FE
    :mod:`benchmarks.sparse_fe` on the coarsest uniform mesh whose first 10 frequencies
    are within 1e-6 of section 1's reference (:func:`benchmarks.fe_compare.coarsest_mesh`):
    assembly and ``eigsh(K, k=10, M=M, sigma=SHIFT, which="LM")`` with its
    eigenvectors, the best of as many runs, each right after one of symtmm's. Its shapes
    are the cubic Hermite interpolants of the nodal values, good to the mesh's
    accuracy; symtmm's carry 15 digits (sampled in double precision).
"""

from __future__ import annotations

import time

import numpy as np
import scipy.sparse.linalg

from . import sparse_fe
from .fe_compare import CASES, COUNT, TOLERANCE, best_seconds, coarsest_mesh, reference
from .models import from_scratch

__all__ = ["run", "NAMES"]

#: The cases of section 1 measured here (the 50-level chain is left to section 1).
NAMES = ("ex1", "ex3", "chain10", "chain20", "multispan20")
QUICK = ("ex1", "ex3")
POINTS = 101
DIGITS = 15
#: Timed runs per side; the best counts (a 20-level chain's shapes take seconds).
REPEAT = 3


def fe_shapes(fe, n: int) -> tuple:
    """``(omega, vectors)``: the lowest :data:`COUNT` frequencies and their eigenvectors."""
    K, M = sparse_fe.matrices(fe, n)
    values, vectors = scipy.sparse.linalg.eigsh(K, k=COUNT, M=M, sigma=sparse_fe.SHIFT,
                                                which="LM")
    return np.sqrt(np.abs(values)), vectors


def measure(name: str, progress=print, repeat: int = REPEAT) -> dict:
    """One case: symtmm's shapes and the FE's eigenvectors, timed in turns."""
    from symtmm.modes import mode_shapes

    build, title, _ = CASES[name]
    model = build()
    progress(f"shapes: {name}: reference and FE mesh")
    ref, _ = reference(name, model)
    fe = sparse_fe.fe_input(model)
    n, _ = coarsest_mesh(fe, ref)
    best, shapes, best_fe = np.inf, None, np.inf
    progress(f"shapes: {name}: symtmm modes and the FE eigenvectors, in turns")
    for _ in range(repeat):
        fresh = from_scratch(model)
        start = time.perf_counter()
        modes = mode_shapes(fresh, count=COUNT, points=POINTS, digits=DIGITS)
        seconds = time.perf_counter() - start
        if seconds < best:
            best, shapes = seconds, modes.seconds
        best_fe = min(best_fe, best_seconds(lambda: fe_shapes(fe, n), 1))
    best_fe = min(best_fe, best_seconds(lambda: fe_shapes(fe, n), repeat))
    return dict(name=name, title=title, beams=len(model.beams), shapes=len(modes),
                symtmm=dict(seconds=best, shapes_seconds=shapes),
                fe=dict(elements_per_beam=n, dofs=sparse_fe.dof_count(fe, n), seconds=best_fe),
                ratio=best / best_fe)


def run(quick: bool = False, progress=print) -> dict:
    cases = [measure(name, progress) for name in (QUICK if quick else NAMES)]
    return dict(count=COUNT, points=POINTS, digits=DIGITS, tolerance=TOLERANCE,
                repeat=REPEAT, cases=cases,
                ratios={c["name"]: c["ratio"] for c in cases})
