"""The ordinary models of the reliability issue: the verified solve against a sparse FE model.

The reliability issue asks that ordinary models -- an axial force, rotary inertia,
shear stiffness in SI-like units, dashpots beside springs, a dashpot alone -- solve
within the speed target of section 1: ``time(symtmm) / time(sparse FE at 1e-6) <=
1``. This section measures that ratio on the issue's models (:data:`CASES`), side by
side in one run. It is reported beside the numbered targets, not one of them.

symtmm
    ``solve(model, count=10, digits=15)`` (undamped) or ``solve(model,
    omega_max=W, digits=12)`` (damped: the eigenvalues in ``0 <= Im lam <= W``,
    ``-2 W <= Re lam <= 0``), the best of :data:`REPEAT` solves, each after
    ``benchmarks.models.from_scratch`` (a new model object, no plan reused); one more solve is profiled
    (:mod:`benchmarks.profiling`). A solve that stops with an error or runs past
    :data:`TIME_LIMIT` seconds is recorded with its message, and the run goes on.
FE
    :mod:`symtmm.fe` (it shares no code with the solver) assembles ``K`` and ``M``
    on a uniform mesh (elements per beam); each dashpot ``c`` adds ``[[c, -c], [-c,
    c]]`` on the deflections of the nodes it joins (``C``). The user solves with
    sparse matrices: undamped ``eigsh(K, k=10, M=M, sigma=0, which="LM")`` (no
    model here has a rigid-body mode); damped the state-space pencil ``A = [[0,
    I], [-K, -C]]``, ``B = [[I, 0], [0, M]]`` (``A z = lam B z``, ``B`` symmetric
    semi-definite) by ``eigs(A, k, M=B, sigma=-W/100, which="LM")``, keeping the
    eigenvalues in the region with ``Im lam >= 0``. ``k`` is the number of
    eigenvalues the region holds, conjugates counted, plus :data:`K_MARGIN`, known
    from the reference, which favours the FE; the ``k`` whose disk around the shift
    reaches the region's far corner (what a user needs to be sure of the region,
    :func:`covering_k`) is timed too and reported. The time is the conversion of the
    matrices to ``scipy.sparse`` CSC and the eigensolver, the best of :data:`REPEAT`
    runs, with the default BLAS threads and with one (a child process, as section 1
    times its FE), the faster counting (the eigensolver's alone is reported too); the
    assembly (dense in :mod:`symtmm.fe`) is not timed, unlike section 1's, which also
    favours the FE: the ratio is conservative.
Mesh
    The coarsest uniform elements per beam whose wanted eigenvalues are all within
    :data:`TOLERANCE` relative of the reference, found as section 1 finds it
    (:func:`benchmarks.fe_compare.coarsest`). Where rounding stops the FE error
    above the tolerance (the Timoshenko beam with ``kGA / EI = 7e8``), the mesh of
    the smallest error is timed and the report says so.

References, none computed by symtmm's solver:

* undamped -- :func:`symtmm.fe.fe_converged`: the dense FE (frequencies from
  Rayleigh quotients with the strain energy summed without cancellation) on
  nested meshes, Romberg-extrapolated, with its error estimate. Where a beam is so
  stiff in shear that the FE loses digits to it, the frequencies are interpolated
  in ``EI / kGA`` through values where it does not (:func:`shear_extrapolated`);
* damped -- the same state-space FE on nested meshes, each solved with a ``k``
  that covers the region, the eigenvalues Romberg-extrapolated in ``h**4``,
  ``h**6``, ... (:func:`romberg`; the observed order is reported). Rounding in the
  pencil grows like ``h**-4``, so the meshes stop before it overtakes the
  discretisation error, and the error estimate is one that holds either way;
* the pure dashpot -- the values the issue publishes (:data:`PUBLISHED`), against
  which the extrapolated FE is checked as well.
"""

from __future__ import annotations

import json
import math
import signal
import sys
import threading
import time
from dataclasses import dataclass, field

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

from .compare import match
from .fe_compare import best_seconds, coarsest, one_thread, rel_error

__all__ = ["run", "measure", "CASES", "PUBLISHED", "model", "fe_input", "fe_system",
           "undamped_omegas", "state_space", "damped_eigenvalues", "in_region", "match_errors",
           "covering_k", "romberg", "aligned", "shear_extrapolated", "reference"]

COUNT = 10
DIGITS = 15
DAMPED_DIGITS = 12
TOLERANCE = 1e-6
#: Timed runs per measurement (``--quick``: :data:`QUICK_REPEAT`); the best counts (as
#: :data:`benchmarks.fe_compare.REPEAT`).
REPEAT = 10
QUICK_REPEAT = 2
#: Seconds a single symtmm solve may take before it is recorded as a failure.
TIME_LIMIT = 60.0
#: Shift of ``eigsh``: none of the undamped models has a rigid-body mode (``K`` is regular).
SHIFT = 0.0
#: Shift of ``eigs`` on the damped models, as a fraction of ``W``: just left of the origin
#: (``lam = 0`` may be an eigenvalue, a rigid-body mode), inside the region.
DAMPED_SHIFT = -0.01
#: Eigenvalues ``eigs`` is asked for beyond those the region holds.
K_MARGIN = 2
#: A beam with ``EI / (kGA L**2)`` below this is stiff in shear: its reference is
#: interpolated in ``EI / kGA`` (:func:`shear_extrapolated`) through these multiples of it.
STIFF_SHEAR = 1e-6
SHEAR_SCALES = (1000.0, 2000.0)
#: Relative error of the published values (15 significant digits).
PUBLISHED_ERROR = 5e-15
#: A found and a reference eigenvalue further apart than this (relative) are no pair.
MATCH = 1e-2
#: An FE eigenvalue within this fraction of the largest one returned is a rigid-body 0.
ZERO = 1e-9

#: The eigenvalues the issue publishes for the pure dashpot model.
PUBLISHED = (0, -2.19141315549854, complex(-0.623622447176967, 15.3310074918209),
             complex(-1.43788429657287, 49.8554523918882),
             complex(-0.056570866708691, 104.245191761378))


@dataclass(frozen=True)
class Case:
    """One model: its title, model file text and what is asked of it.

    ``omega_max`` None: the first :data:`COUNT` frequencies; otherwise the damped
    region ``0 <= Im lam <= omega_max``, ``-sigma_max <= Re lam <= 0`` (``sigma_max``
    None: the solver's default, ``2 omega_max``). The reference's FE meshes: elements
    per beam of the coarsest, and how many nested meshes (one fewer, at least 3, with
    ``--quick``); the damped ones stop where rounding in the state-space pencil
    (``eps`` times ``h**-4``) would overtake the discretisation error.
    """

    title: str
    text: str
    omega_max: float | None = None
    sigma_max: float | None = None
    published: tuple = field(default=())
    reference_elements: int = 16
    reference_levels: int = 4

    @property
    def damped(self) -> bool:
        return self.omega_max is not None

    @property
    def region(self) -> tuple:
        """``(W, S)`` of a damped case."""
        W = float(self.omega_max)
        return W, 2 * W if self.sigma_max is None else float(self.sigma_max)


def _beam(name, left, right, **fields) -> str:
    lines = [f'name = "{name}"'] + [f"{k} = {v}" for k, v in fields.items()]
    return "[[beam]]\n" + "\n".join(lines) + f'\nleft = "{left}"\nright = "{right}"\n'


def _spring(a, b, x, k, c=None) -> str:
    return (f'[[spring]]\nbetween = ["{a}", "{b}"]\nx = {x}\nk = {k}\n'
            + ("" if c is None else f"c = {c}\n"))


#: name: the model (a model file), first frequencies or a damped region
CASES = {
    "tension": Case(
        "free-free beam in tension (N = 5) beside a pinned-pinned beam, one spring",
        _beam("taut", "free", "free", EI=0.1, m=2, L=10, N=5)
        + _beam("pp", "pinned", "pinned", EI=1, m=1, L=10) + _spring("taut", "pp", 5, 1),
        reference_elements=32),
    "rayleigh": Case(
        "Rayleigh cantilever and an Euler-Bernoulli cantilever, one spring",
        _beam("rayleigh", "clamped", "free", theory='"rayleigh"', EI=10, m=1, L=2, rhoI=0.3)
        + _beam("eb", "clamped", "free", EI='"2**(1/3)"', m=1, L=2)
        + _spring("rayleigh", "eb", 1, 5)),
    "timoshenko_si": Case(
        "Timoshenko cantilever, kGA = 7e8 beside EI = 1, and an Euler-Bernoulli "
        "cantilever, a spring at the tips",
        _beam("timoshenko", "clamped", "free", theory='"timoshenko"', EI=1, m=1, L=1,
              rhoI=0.01, kGA=7e8)
        + _beam("eb", "clamped", "free", EI=1, m=1, L=1) + _spring("timoshenko", "eb", 1, 10)),
    "damped_timoshenko": Case(
        "Timoshenko beam and two Euler-Bernoulli beams (pinned-pinned, L = 40, m = 500), "
        "springs with dashpots between neighbours",
        _beam("timoshenko", "pinned", "pinned", theory='"timoshenko"', EI=1e4, m=500, L=40,
              rhoI=5, kGA=1e6)
        + _beam("eb1", "pinned", "pinned", EI=1e4, m=500, L=40)
        + _beam("eb2", "pinned", "pinned", EI=1e4, m=500, L=40)
        + _spring("timoshenko", "eb1", 12, 2000, 1000) + _spring("eb1", "eb2", 28, 2000, 1000),
        omega_max=0.3, reference_elements=12),
    "pure_dashpot": Case(
        "pinned-free beam with one dashpot to the ground (k = 0, c = 2 at x = 0.6)",
        _beam("b", "pinned", "free", EI=1, m=1, L=1) + _spring("b", "ground", 0.6, 0, 2),
        omega_max=110.0, published=PUBLISHED, reference_elements=8, reference_levels=3),
}


def model(name: str):
    """The :class:`symtmm.model.Model` of a case."""
    from symtmm.api import loads

    return loads(CASES[name].text)


# -- the FE model --------------------------------------------------------------------------------
def fe_input(model) -> tuple:
    """``(beams, springs, dashpots)``: the model as :mod:`symtmm.fe`'s plain dicts (floats),
    the dashpots apart as ``(beam, other beam or "ground", x, c)``.

    Examples
    --------
    >>> beams, springs, dashpots = fe_input(model("pure_dashpot"))
    >>> beams[0]["left"], springs, dashpots
    ('pinned', [{'between': ['b', 'ground'], 'x': 0.6, 'k': 0.0}], [('b', 'ground', 0.6, 2.0)])
    """
    model = model.resolved()
    beams = []
    for b in model.beams:
        beam = dict(name=b.name, EI=float(b.EI), m=float(b.m), L=float(b.L), x0=float(b.x0),
                    left=b.left, right=b.right, kw=float(b.kw), N=float(b.N),
                    rhoI=float(b.rhoI))
        if b.kGA is not None:
            beam["kGA"] = float(b.kGA)
        beams.append(beam)
    springs = [dict(between=[s.a, s.b], x=float(s.x), k=float(s.k)) for s in model.springs]
    dashpots = [(s.a, s.b, float(s.x), float(s.c)) for s in model.springs if s.c != 0]
    return beams, springs, dashpots


def fe_system(fe, elements: int, refine: int = 1) -> tuple:
    """Dense ``(K, M, C)`` of the mesh (:func:`symtmm.fe.fe_matrices`, ``C`` the dashpots',
    :func:`symtmm.fe.fe_dashpots`)."""
    from symtmm.fe import fe_dashpots, fe_matrices

    beams, springs, dashpots = fe
    K, M, info = fe_matrices(beams, springs, elements, refine=refine)
    return K, M, fe_dashpots(info, dashpots)


def undamped_omegas(K, M, count: int = COUNT) -> np.ndarray:
    """The lowest ``count`` frequencies: CSC matrices and ``eigsh`` in shift-invert mode."""
    K, M = scipy.sparse.csc_matrix(K), scipy.sparse.csc_matrix(M)
    values = scipy.sparse.linalg.eigsh(K, k=count, M=M, sigma=SHIFT, which="LM",
                                       return_eigenvectors=False)
    return np.sqrt(np.clip(np.sort(values), 0.0, None))


def state_space(K, M, C) -> tuple:
    """The sparse pencil ``(A, B)`` of ``lam**2 M + lam C + K``: ``A = [[0, I], [-K, -C]]``,
    ``B = [[I, 0], [0, M]]`` (CSC)."""
    n = K.shape[0]
    eye = scipy.sparse.identity(n, format="csc")
    A = scipy.sparse.bmat([[None, eye], [-scipy.sparse.csc_matrix(K),
                                         -scipy.sparse.csc_matrix(C)]], format="csc")
    B = scipy.sparse.block_diag((eye, scipy.sparse.csc_matrix(M)), format="csc")
    return A, B


def damped_eigenvalues(K, M, C, k: int, shift: float) -> np.ndarray:
    """The ``k`` eigenvalues nearest ``shift``: the sparse pencil and ``eigs`` in shift-invert
    mode; those within :data:`ZERO` of the largest one's magnitude are rigid-body zeros."""
    A, B = state_space(K, M, C)
    lam = scipy.sparse.linalg.eigs(A, k=k, M=B, sigma=shift, which="LM",
                                   return_eigenvectors=False)
    return np.where(np.abs(lam) < ZERO * np.max(np.abs(lam)), 0.0, lam)


def in_region(lam, W: float, S: float, slack: float = 0.0) -> np.ndarray:
    """The eigenvalues with ``Im >= 0`` in ``-S <= Re <= 0``, ``Im <= W``, the edges moved
    out by ``slack`` times the region's size (rounding puts real ones a hair off the axis).

    Examples
    --------
    >>> in_region(np.array([-1 + 2j, -1 - 2j, -3 + 0j, 1e-13 + 5j, -1 + 20j]), 10, 20,
    ...           slack=1e-9).tolist()
    [(-1+2j), (-3+0j), (1e-13+5j)]
    """
    lam = np.asarray(lam, dtype=complex)
    tol = slack * max(W, S)
    keep = (lam.real <= tol) & (lam.real >= -S - tol) & (lam.imag >= -tol) & \
        (lam.imag <= W + tol)
    return lam[keep]


def match_errors(found, reference) -> dict:
    """One-to-one pairs of found and reference eigenvalues, nearest first: the largest
    ``|found - reference| / |reference|`` (a reference 0, a rigid-body mode, relative to
    the largest ``|reference|``), reference values left unpaired (missed) and found
    values left over (spurious).

    Examples
    --------
    >>> m = match_errors([0.0, 1j + 1e-7, 3.0], [0, 1j, 2j])
    >>> round(m["max_rel_error"], 12), m["missed"], m["spurious"]
    (1e-07, 1, 1)
    """
    m = match(found, reference, tol=MATCH)
    return dict(max_rel_error=m.max_rel_error, missed=m.missed, spurious=m.spurious)


def _wanted(reference) -> int:
    """Eigenvalues a region with these (``Im >= 0``) holds, conjugates counted."""
    return sum(1 if z.imag == 0 else 2 for z in map(complex, reference))


def _damped_fe(fe, n: int, case: Case, k: int, refine: int = 1) -> np.ndarray:
    W, S = case.region
    K, M, C = fe_system(fe, n, refine)
    if 2 * K.shape[0] <= k + 1:
        raise ValueError(f"{2 * K.shape[0]} states: too few for {k} eigenvalues by eigs")
    return in_region(damped_eigenvalues(K, M, C, k, DAMPED_SHIFT * W), W, S, slack=1e-9)


def covering_k(K, M, C, case: Case, k: int) -> int:
    """The smallest ``k`` (from ``k``, growing by half) whose eigenvalues nearest the shift
    reach past the region's farthest corner: every eigenvalue of the region among them."""
    W, S = case.region
    shift = DAMPED_SHIFT * W
    reach = math.hypot(S + shift, W)
    while True:
        lam = damped_eigenvalues(K, M, C, k, shift)
        if np.max(np.abs(lam - shift)) > reach or k >= 2 * K.shape[0] - 2:
            return k
        k = min(2 * K.shape[0] - 2, k + max(2, k // 2))


# -- references ----------------------------------------------------------------------------------
def romberg(raw: np.ndarray, rate: int = 4) -> tuple:
    """Romberg's scheme on values from meshes refined by 2 (rows of ``raw``), errors falling
    as ``h**rate``, ``h**(rate + 2)``, ...: ``(best, error, observed order)``.

    The error is the difference between the two extrapolations from one mesh fewer (the
    coarser meshes' and the finer meshes'), the last correction times ``2**(rate + 2 (levels
    - 2)) - 1``: an estimate that still holds where rounding, not the mesh, limits the
    finest values (the last correction alone is then too small). The order is ``log2`` of
    the ratio of the last two differences of the raw values.

    Examples
    --------
    >>> h = 0.5 ** np.arange(4)
    >>> best, error, order = romberg(np.array([1 + h**4 + h**6]).T)
    >>> round(float(best[0]), 12), bool(error[0] < 1e-12), round(float(order[0]), 1)
    (1.0, True, 4.2)
    """
    raw = np.asarray(raw)
    column = previous = raw
    for j in range(len(raw) - 1):
        factor = 2.0 ** (rate + 2 * j)
        previous, column = column, (factor * column[1:] - column[:-1]) / (factor - 1.0)
    best = column[-1]
    d1, d2 = np.abs(raw[-3] - raw[-2]), np.abs(raw[-2] - raw[-1])
    with np.errstate(divide="ignore", invalid="ignore"):
        order = np.where(d2 > 0, np.log2(d1 / d2), np.nan)
    return best, np.abs(previous[-1] - previous[-2]), order


def aligned(values, to) -> list:
    """``values`` reordered to pair one to one with ``to``, nearest pairs first.

    Examples
    --------
    >>> aligned([2.1j, -1.0, 1.1j], [-1.0, 1j, 2j])
    [-1.0, 1.1j, 2.1j]
    """
    pairs = sorted((abs(v - t), i, j) for i, t in enumerate(to) for j, v in enumerate(values))
    out, used = [None] * len(to), set()
    for _, i, j in pairs:
        if out[i] is None and j not in used:
            out[i] = values[j]
            used.add(j)
    return out


def _meshes(elements: int, levels: int) -> str:
    return (f"{levels} nested meshes, {elements} to {elements * 2 ** (levels - 1)} elements "
            "per beam")


def _converged(beams, springs, elements: int, levels: int) -> tuple:
    """``(omega, relative error estimate)`` of :func:`symtmm.fe.fe_converged`."""
    from symtmm.fe import fe_converged

    out = fe_converged(beams, springs, elements, COUNT, levels=levels)
    return out["omega"], out["error"] / out["omega"]


def _stiff_in_shear(beam) -> bool:
    return beam.get("kGA") is not None and beam["EI"] / (beam["kGA"] * beam["L"] ** 2) < STIFF_SHEAR


def shear_extrapolated(beams, springs, elements: int, levels: int) -> tuple:
    """``(omega, relative error estimate)`` of a model whose shear stiffness is so high that the
    FE loses digits to it: the frequencies as functions of ``g = EI / kGA`` (scaled alike on
    every such beam), interpolated in ``g`` through the FE at ``g = 0`` (rigid in shear, a
    Rayleigh beam) and at :data:`SHEAR_SCALES` times the model's ``g``, where the FE is well
    conditioned, evaluated at the model's. The error estimate adds the FE's at ``g = 0`` and
    the change from the linear to the quadratic interpolant."""
    def scaled(factor):
        out = []
        for b in beams:
            if _stiff_in_shear(b):
                b = {k: v for k, v in b.items() if k != "kGA"} if factor == 0 else \
                    dict(b, kGA=b["kGA"] / factor)
            out.append(b)
        return out

    points = [0.0, *SHEAR_SCALES]
    # the FE's errors at g != 0 enter with weights of about 1/1000: fewer meshes do there
    runs = [_converged(scaled(f), springs, elements, levels if f == 0 else max(3, levels - 1))
            for f in points]
    values = np.array([w for w, _ in runs])
    # Lagrange interpolation in g (in units of the model's g) at g = 1
    weights = [np.prod([(1 - b) / (a - b) for b in points if b != a]) for a in points]
    quadratic = np.tensordot(weights, values, axes=1)
    linear = values[0] + (values[1] - values[0]) / points[1]
    error = runs[0][1] + np.abs(quadratic - linear) / quadratic
    return quadratic, error


def undamped_reference(fe, elements: int, levels: int) -> dict:
    """The first :data:`COUNT` frequencies, extrapolated over nested dense meshes (and in the
    shear flexibility where it is tiny, :func:`shear_extrapolated`)."""
    beams, springs, _ = fe
    text = ("symtmm.fe (dense, no code shared with the solver) on "
            f"{_meshes(elements, levels)}, Romberg-extrapolated (fe_converged)")
    if any(_stiff_in_shear(b) for b in beams):
        omega, error = shear_extrapolated(beams, springs, elements, levels)
        text += (", at g = EI/kGA = 0 (rigid in shear) and at "
                 + " and ".join(f"{f:g}" for f in SHEAR_SCALES) + " times the model's g "
                 "(where the FE does not lose digits to the shear stiffness; one mesh "
                 "fewer), interpolated in g at the model's")
    else:
        omega, error = _converged(beams, springs, elements, levels)
    return dict(values=[float(w) for w in omega], max_rel_error=float(np.max(error)),
                method=text)


def damped_reference(fe, case: Case, levels: int) -> dict:
    """The region's eigenvalues (``Im >= 0``), extrapolated over nested state-space meshes."""
    W, S = case.region
    elements, raw = case.reference_elements, []
    for j in range(levels):
        K, M, C = fe_system(fe, elements, 2**j)
        k = covering_k(K, M, C, case, 4 * K_MARGIN + (_wanted(raw[-1]) if raw else 0))
        raw.append(in_region(damped_eigenvalues(K, M, C, k, DAMPED_SHIFT * W), W, S,
                             slack=1e-9))
    if len({len(r) for r in raw}) != 1:
        raise ArithmeticError("the nested meshes hold different numbers of eigenvalues in "
                              f"the region: {[len(r) for r in raw]}")
    finest = sorted(raw[-1], key=lambda z: (z.imag, z.real))
    best, error, order = romberg(np.array([aligned(r, finest) for r in raw]))
    scale = np.where(np.abs(best) > 0, np.abs(best), np.max(np.abs(best)))
    return dict(values=[complex(z) for z in best],
                max_rel_error=float(np.max(error / scale)),
                observed_order=[None if np.isnan(o) else float(o) for o in order],
                method=(f"state-space symtmm.fe on {_meshes(elements, levels)}, eigs "
                        "covering the region, Romberg-extrapolated (h**4, h**6, ...)"))


def reference(name: str, fe, levels: int) -> dict:
    """The case's reference: ``values`` (frequencies, or eigenvalues with ``Im >= 0``),
    ``method``, ``max_rel_error`` (estimated); for the pure dashpot the published values,
    the extrapolated FE beside them (``fe_check``)."""
    case = CASES[name]
    if not case.damped:
        return undamped_reference(fe, case.reference_elements, levels)
    extrapolated = damped_reference(fe, case, levels)
    if not case.published:
        return extrapolated
    check = match_errors(extrapolated["values"], case.published)
    return dict(values=[complex(z) for z in case.published], max_rel_error=PUBLISHED_ERROR,
                method="the values published in the issue (15 digits)",
                fe_check=dict(extrapolated, **check))


# -- measurements ----------------------------------------------------------------------------------
class _Overtime(BaseException):
    """A solve past its time (a BaseException: no ``except Exception`` in the code it
    interrupts holds it up)."""


def _limited(fn, seconds: float):
    """``fn()``, stopped by :class:`_Overtime` after ``seconds`` (where SIGALRM exists, in
    the main thread; elsewhere without a limit)."""
    if not hasattr(signal, "setitimer") or \
            threading.current_thread() is not threading.main_thread():
        return fn()

    def stop(signum, frame):
        raise _Overtime(f"took longer than {seconds:g} s")

    old = signal.signal(signal.SIGALRM, stop)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        return fn()
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def _solve_kw(case: Case) -> dict:
    if case.damped:
        return dict(omega_max=case.omega_max, sigma_max=case.sigma_max, digits=DAMPED_DIGITS)
    return dict(count=COUNT, digits=DIGITS)


def _printed(spectrum) -> list:
    """The eigenvalues as printed (their digits), each repeated by its multiplicity."""
    out = []
    for e in spectrum:
        d = e.to_dict()
        out += [complex(float(d["real"]), float(d["imag"]))] * e.multiplicity
    return out


def _failure(exc: Exception) -> str:
    text = str(exc) if isinstance(exc, _Overtime) else f"{type(exc).__name__}: {exc}"
    return text[:300]


def _symtmm(name: str, ref: dict, repeat: int, fe_once=None) -> dict:
    """Best time of ``repeat`` solves (no plan reused), evaluations, the printed values and
    their errors, and one more solve profiled (:mod:`benchmarks.profiling`); on a failure or
    a solve past :data:`TIME_LIMIT` s, the message. ``fe_once``: a function timing one FE
    solve, run after each of symtmm's (both sides of the ratio in the same minutes: the
    machine's speed drifts); the best of those is ``fe_seconds``."""
    from symtmm.solve import solve

    from .models import from_scratch
    from .profiling import solve_profile

    case, m, kw = CASES[name], model(name), _solve_kw(CASES[name])
    best, best_fe, spectrum = np.inf, np.inf, None
    for _ in range(repeat):
        fresh = from_scratch(m)         # each solve as a user's first one
        start = time.perf_counter()
        try:
            spectrum = _limited(lambda m=fresh: solve(m, **kw), TIME_LIMIT)
        except (Exception, _Overtime) as exc:  # noqa: BLE001 - reported, the run goes on
            return dict(error=_failure(exc), seconds=time.perf_counter() - start)
        best = min(best, time.perf_counter() - start)
        if fe_once is not None:
            best_fe = min(best_fe, fe_once())
    printed = _printed(spectrum)
    out = dict(seconds=best, evaluations=spectrum.evaluations, digits=spectrum.digits,
               found=len(printed), values=[e.to_dict() for e in spectrum],
               fe_seconds=best_fe)
    if case.damped:
        out.update(match_errors(printed, ref["values"]))
    else:
        out["max_rel_error"] = rel_error([z.imag for z in printed][:COUNT], ref["values"])
    try:
        out["profile"] = _limited(lambda: solve_profile(m, **kw)[0], TIME_LIMIT)
    except (Exception, _Overtime) as exc:  # noqa: BLE001 - the timings stand without it
        out["profile_error"] = _failure(exc)
    return out


def _coarsest(error) -> tuple:
    """``(n, tried, note)``: :func:`benchmarks.fe_compare.coarsest` within :data:`TOLERANCE`,
    or, where the FE error stops falling above it, the mesh of the smallest error and why."""
    tried = {}

    def recorded(n):
        tried[n] = error(n)
        return tried[n]

    try:
        n, _ = coarsest(recorded, TOLERANCE)
        return n, tried, None
    except ArithmeticError as exc:
        return min(tried, key=tried.get), tried, str(exc)


def _undamped_mesh(fe, ref: dict) -> tuple:
    def error(n):
        K, M, _ = fe_system(fe, n)
        if K.shape[0] <= COUNT + 1:
            return np.inf                   # too few dofs for eigsh
        try:
            return rel_error(undamped_omegas(K, M), ref["values"])
        except scipy.sparse.linalg.ArpackError:
            return np.inf

    return _coarsest(error)


def _damped_mesh(fe, case: Case, ref: dict, k: int) -> tuple:
    def error(n):
        try:
            found = _damped_fe(fe, n, case, k)
        except (ValueError, scipy.sparse.linalg.ArpackError):
            return np.inf                   # too few states for eigs, or no convergence
        m = match_errors(found, ref["values"])
        return np.inf if m["missed"] or m["spurious"] else m["max_rel_error"]

    return _coarsest(error)


def _fe(name: str, fe, ref: dict, repeat: int) -> dict:
    """The sparse FE on the coarsest mesh within :data:`TOLERANCE`: mesh, dofs, error,
    seconds (CSC conversion and eigensolver) and the eigensolver's alone."""
    case = CASES[name]
    if case.damped:
        k = _wanted(ref["values"]) + K_MARGIN
        n, tried, note = _damped_mesh(fe, case, ref, k)
    else:
        k = COUNT
        n, tried, note = _undamped_mesh(fe, ref)
    K, M, C = fe_system(fe, n)
    out = dict(elements_per_beam=n, dofs=K.shape[0], k=k, within_tolerance=note is None,
               seconds_default_threads=fe_seconds(name, K, M, C, k, repeat),
               note=note,
               tried=[dict(elements_per_beam=t, max_rel_error=None if e == np.inf else e)
                      for t, e in sorted(tried.items())])
    if case.damped:
        shift = DAMPED_SHIFT * case.region[0]
        found = _damped_fe(fe, n, case, k)
        out.update(match_errors(found, ref["values"]), found=len(found))
        A, B = state_space(K, M, C)
        out["solver_seconds"] = best_seconds(lambda: scipy.sparse.linalg.eigs(
            A, k=k, M=B, sigma=shift, which="LM", return_eigenvectors=False), repeat)
        cover = covering_k(K, M, C, case, k)
        out["covering_k"] = cover
        out["covering_seconds"] = best_seconds(lambda: damped_eigenvalues(K, M, C, cover, shift),
                                        repeat)
    else:
        out["max_rel_error"] = rel_error(undamped_omegas(K, M), ref["values"])
        Ks, Ms = scipy.sparse.csc_matrix(K), scipy.sparse.csc_matrix(M)
        out["solver_seconds"] = best_seconds(lambda: scipy.sparse.linalg.eigsh(
            Ks, k=COUNT, M=Ms, sigma=SHIFT, which="LM", return_eigenvectors=False), repeat)
    return out


def fe_seconds(name: str, K, M, C, k: int, repeat: int = REPEAT) -> float:
    """The FE's time on its mesh: conversion to CSC and the eigensolver, the best of
    ``repeat`` runs."""
    case = CASES[name]
    if case.damped:
        shift = DAMPED_SHIFT * case.region[0]
        return best_seconds(lambda: damped_eigenvalues(K, M, C, k, shift), repeat)
    return best_seconds(lambda: undamped_omegas(K, M), repeat)


def _one_thread(cases: list, repeat: int):
    """:func:`fe_seconds` of the measured cases with one BLAS thread (a child process, as
    section 1 times its FE); None if it fails."""
    jobs = [[c["name"], c["fe"]["elements_per_beam"], c["fe"]["k"], repeat] for c in cases]
    return one_thread("benchmarks.ordinary", json.dumps(jobs)) if jobs else []


def _jsonable(values) -> list:
    """Eigenvalues as ``[re, im]`` pairs (frequencies as they are)."""
    return [[z.real, z.imag] if isinstance(z, complex) else z for z in values]


def measure(name: str, quick: bool = False, progress=print) -> dict:
    """One case: reference, FE mesh and time, symtmm's time, errors and the ratio."""
    case = CASES[name]
    repeat = QUICK_REPEAT if quick else REPEAT
    fe = fe_input(model(name))
    progress(f"ordinary: {name}: reference")
    start = time.perf_counter()
    levels = case.reference_levels
    ref = reference(name, fe, max(3, levels - 1) if quick else levels)
    ref_seconds = time.perf_counter() - start
    progress(f"ordinary: {name}: coarsest FE mesh within {TOLERANCE:g}")
    fe_row = _fe(name, fe, ref, repeat)
    progress(f"ordinary: {name}: symtmm, and the FE model in turns")
    K, M, C = fe_system(fe, fe_row["elements_per_beam"])
    sym = _symtmm(name, ref, repeat,
                  lambda: fe_seconds(name, K, M, C, fe_row["k"], 1))
    fe_row["seconds_default_threads"] = min(fe_row["seconds_default_threads"],
                                            sym.pop("fe_seconds", np.inf))
    out = dict(name=name, title=case.title, damped=case.damped, beams=len(fe[0]),
               request={k: v for k, v in _solve_kw(case).items() if v is not None},
               reference=dict(ref, values=_jsonable(ref["values"]), seconds=ref_seconds),
               fe=fe_row, symtmm=sym, ratio=None)      # the ratio once the FE is timed in full
    if case.damped:
        out["region"] = dict(zip(("omega_max", "sigma_max"), case.region))
        if "fe_check" in ref:
            out["reference"]["fe_check"]["values"] = _jsonable(ref["fe_check"]["values"])
    return out


def run(quick: bool = False, progress=print) -> dict:
    cases = []
    for name, case in CASES.items():
        try:
            cases.append(measure(name, quick, progress))
        except Exception as exc:  # noqa: BLE001 - a failed case is reported, the run goes on
            progress(f"ordinary: {name}: failed: {type(exc).__name__}: {exc}")
            cases.append(dict(name=name, title=case.title,
                              error=f"{type(exc).__name__}: {exc}"[:300]))
    progress("ordinary: FE timings with one BLAS thread (child process)")
    measured = [c for c in cases if "error" not in c]
    single = _one_thread(measured, QUICK_REPEAT if quick else REPEAT)
    for i, c in enumerate(measured):
        f = c["fe"]
        f["seconds_one_thread"] = single[i] if single else None
        f["seconds"] = min(f["seconds_default_threads"],
                           f["seconds_one_thread"] if single else np.inf)
        if "error" not in c["symtmm"]:
            c["ratio"] = c["symtmm"]["seconds"] / f["seconds"]
    ratios = {c["name"]: c.get("ratio") for c in cases}
    return dict(count=COUNT, digits=DIGITS, damped_digits=DAMPED_DIGITS, tolerance=TOLERANCE,
                shift=SHIFT, damped_shift=DAMPED_SHIFT, one_thread_ok=single is not None,
                repeat=QUICK_REPEAT if quick else REPEAT, time_limit=TIME_LIMIT,
                k_margin=K_MARGIN, cases=cases, ratios=ratios,
                within=all(r is not None and r <= 1 for r in ratios.values()))


if __name__ == "__main__" and len(sys.argv) == 3 and sys.argv[1] == "one-thread":
    # worker: python -m benchmarks.ordinary one-thread '[["tension", 40, 10, 5], ...]' (BLAS
    # threads set by the environment)
    print(json.dumps([fe_seconds(name, *fe_system(fe_input(model(name)), n), k, repeat)
                      for name, n, k, repeat in json.loads(sys.argv[2])]))
