"""Transfer matrices of beam segments, for many eigenvalues and many segments at once.

Two families, each written once for every arithmetic (:mod:`symtmm.numeric.arith`):

* **Euler–Bernoulli** (:func:`eb_matrices`): the entire functions
  ``c_j(x) = sum_k x**k / (4k+j)!`` of ``x = -(m lam**2 + kw) l**4 / EI``
  (:mod:`symtmm.elements.beam`): their series below ``|x| = 1`` (with a rigorous
  tail for balls), the closed forms in ``nu = x**(1/4)`` above, and for a real
  ``x <= -1`` (a foundation stiffer than the inertia) the real forms in
  ``s = (-x/4)**(1/4)``, so that real arithmetic stays real;
* **any other theory** (:func:`theory_matrices`: axial force, Rayleigh,
  Timoshenko): ``exp(A l)`` from the series of ``alpha, beta`` in ``(t, d)``
  (trace and determinant of ``G = B C``, :mod:`symtmm.elements.theories`) on a
  piece ``h = l / 2**j`` with ``max|r| h**2 <= 1/2``, then ``j`` doublings;
* **beams joined by layers** (:func:`coupled_matrices`, family ``"coupled"``): the
  ``c_j`` series with the matrix ``X`` of :mod:`symtmm.elements.layer` in place
  of ``x`` (pieces keep ``|X|`` below ``NU_MAX**4``, where the series is short and
  free of cancellation), with a rigorous tail for balls.

Arrays: ``lam2`` has shape ``(B,)`` (points), every constant shape ``(S,)``
(segments); results have shape ``(B, S, 4, 4)`` in the state order
``[Y, Theta, M, Q]`` (``(B, S, 4N, 4N)`` for ``N`` coupled beams, in the order
``[Y_1..Y_N, Theta_1.., M_1.., Q_1..]``).

Examples
--------
>>> import numpy as np
>>> from symtmm.numeric.arith import DOUBLE
>>> consts = eb_constants(DOUBLE, [(1, 1, 1, 0)])        # EI, m, l, kw
>>> U = eb_matrices(DOUBLE, consts, np.array([0.0, -np.pi**4]))
>>> U.shape, float(U[0, 0, 0, 3].real)                    # static: l**3 / (6 EI)
((2, 1, 4, 4), 0.16666666666666666)
"""

from __future__ import annotations

import functools
import math

import numpy as np
import sympy as sp

from ..elements import EulerBernoulliSegment
from ..elements.layer import CoupledSegment
from ..elements.theories import static_coefficients
from .arith import Arithmetic, exact_key

__all__ = ["eb_exact", "eb_constants", "eb_matrices", "theory_constants", "theory_matrices", "rod_constants",
           "rod_matrices", "f_functions", "kind_inertia",
           "coupled_constants", "coupled_matrices", "transfer_matrices", "family_matrices", "cut_tables",
           "stack_matrix", "kind", "kind_key", "kind_order", "kind_size", "kind_tables",
           "segment_matrix", "Condensed", "condensed_stiffness"]


def stack_matrix(rows) -> np.ndarray:
    """A nested list of equally shaped arrays as one array with two trailing axes.

    Written entry by entry into one array: nested ``np.stack`` calls copy every entry
    twice, which cost half of a double-precision batch's stiffness tables.
    """
    first = np.asarray(rows[0][0])
    dtype = first.dtype if first.dtype == object else \
        np.result_type(*(np.asarray(v).dtype for r in rows for v in r))
    out = np.empty(first.shape + (len(rows), len(rows[0])), dtype=dtype)
    for i, r in enumerate(rows):
        for j, v in enumerate(r):
            out[..., i, j] = v
    return out


def _log2_inverse_factorial(n: int) -> float:
    """``log2(1/n!)`` (no overflow for large ``n``)."""
    return -math.lgamma(n + 1) / math.log(2)


def _inverse_factorials(ar: Arithmetic, n: int) -> list:
    """``1/k!`` for ``k < n`` in the arithmetic (exact rationals converted once)."""
    return ar.cached(("1/k!", n),
                     lambda: [ar.exact(sp.Rational(1, math.factorial(k))) for k in range(n)])


# -- Euler–Bernoulli --------------------------------------------------------------------
@functools.lru_cache(maxsize=1 << 14)
def eb_exact(EI, m, l, kw) -> tuple:
    """``(EI, l, A, F)`` of a segment, exact: ``A = m l**4 / EI``, ``F = kw l**4 / EI``
    (kept by value: SymPy's products cost a 20-level chain's 98 segment kinds a millisecond
    in every plan, and a model's plans share most of them)."""
    EI, m, l, kw = (sp.sympify(v) for v in (EI, m, l, kw))
    return EI, l, m * l**4 / EI, kw * l**4 / EI


def eb_constants(ar: Arithmetic, segments) -> dict:
    """Constant arrays for :func:`eb_matrices` from ``(EI, m, l, kw)`` per segment (exact).

    ``A = m l**4 / EI`` and ``F = kw l**4 / EI`` give ``x = -(A lam**2 + F)``.
    """
    def build(*seg):
        return tuple(ar.exact(v) for v in eb_exact(*seg))
    # (each segment's numbers once per arithmetic: a chain's plans for two ranges share
    # most of their segments, and SymPy's products cost tens of microseconds)
    rows = [ar.cached(kind_key(("eb", seg)), lambda seg=seg: build(*seg)) for seg in segments]
    return {k: ar.array([r[j] for r in rows]) for j, k in enumerate(("EI", "l", "A", "F"))}


def _factorial_series(ar: Arithmetic, x, p: int) -> list:
    """``sum_k x**k / (p k + j)!`` for ``j = 0 .. p - 1``, for ``|x| < 1`` elementwise
    (``x`` flat), each with its rigorous tail: the entire functions of the segment
    families (``p = 4``: the Euler–Bernoulli ``c_j``; ``p = 2``: a rod's ``cosh sqrt x``
    and ``sinh sqrt x / sqrt x``)."""
    # 1/(pK)! below the precision; consecutive terms shrink at least 2x for |x| <= 1,
    # so the tail beyond K is at most twice the first omitted term
    K = ar.series_terms(lambda k: _log2_inverse_factorial(p * k))
    inv = _inverse_factorials(ar, p * K + p)
    out = []
    sums = ar.polynomials([[inv[p * k + j] for k in range(K)] for j in range(p)], x)
    for j, acc in enumerate(sums):
        radius, slope, curve, third = _series_tail(p, K, j)
        out.append(ar.widen(acc, radius, wrt=x, slope=slope, curve=curve, third=third))
    return out


@functools.lru_cache(maxsize=256)
def _series_tail(p: int, K: int, j: int) -> tuple:
    """Bounds on the tail of ``sum_k x**k / (p k + j)!`` beyond ``K`` terms for ``|x| <= 1``
    and on the tails of its first three derivatives in ``x`` (exact rationals; once per
    ``(p, K, j)``: a hot path's doubles need none of them, only the same call)."""
    # the terms k x**(k-1)/(pk+j)!, k(k-1) x**(k-2)/(pk+j)! and k(k-1)(k-2) x**(k-3)/(pk+j)!
    # shrink 2x as well, so their sums are below 2K/(pK+j)!, 2K(K-1)/(pK+j)! and
    # 2K(K-1)(K-2)/(pK+j)!
    f = math.factorial(p * K + j)
    # (the k-th derivative's terms vanish below k = 2, 3: their sums start there)
    K2, K3 = max(K, 2), max(K, 3)
    return (sp.Rational(2, f), sp.Rational(2 * K, f),
            sp.Rational(2 * K2 * (K2 - 1), math.factorial(p * K2 + j)),
            sp.Rational(2 * K3 * (K3 - 1) * (K3 - 2), math.factorial(p * K3 + j)))


def _c_closed(ar: Arithmetic, x):
    """``c_0..c_3`` by their closed forms in ``nu = x**(1/4)`` (``x`` flat, ``|x| >= 1``)."""
    nu = ar.root4(x)
    (ch, sh), (co, si) = ar.cosh_sinh(nu), ar.cos_sin(nu)
    nu2 = nu * nu
    return [(ch + co) / 2, (sh + si) / (2 * nu), (ch - co) / (2 * nu2), (sh - si) / (2 * nu2 * nu)]


def _c_negative(ar: Arithmetic, x):
    """``c_0..c_3`` of a real ``x <= -1`` in real functions: ``x = -4 s**4``, ``nu = s (1 + i)``."""
    s = ar.root4(-x / 4)
    s = ar.real(s)
    (ch, sh), (co, si) = ar.cosh_sinh(s), ar.cos_sin(s)
    s2 = s * s
    return [ch * co, (ch * si + sh * co) / (2 * s), sh * si / (2 * s2),
            (ch * si - sh * co) / (4 * s2 * s)]


def _by_form(ar: Arithmetic, x, p: int, closed) -> list:
    """The ``p`` entire functions of a family at every element of ``x`` (any shape): the
    series (:func:`_factorial_series`) where ``|x| < 1``, ``closed(ar, xb)`` elsewhere, which
    returns ``[(mask over xb, values), ...]``."""
    shape = np.shape(x)
    flat = np.asarray(x).reshape(-1)
    big = ar.upper(flat) >= 1.0
    out = [ar.zeros(flat.shape, like=flat) for _ in range(p)]
    small = ~big
    if small.any():
        for o, v in zip(out, _factorial_series(ar, flat[small], p)):
            o[small] = v
    if big.any():
        idx = np.nonzero(big)[0]
        for mask, values in closed(ar, flat[big]):
            for o, v in zip(out, values):
                o[idx[mask]] = v
    return [o.reshape(shape) for o in out]


def _c_big(ar: Arithmetic, xb) -> list:
    """``c_0..c_3`` where ``|x| >= 1``: the closed forms, in real functions for real ``x``."""
    if ar.is_complex(xb):
        return [(np.ones(xb.shape, dtype=bool), _c_closed(ar, xb))]
    positive = ar.positive(xb)
    parts = []
    if positive.any():
        parts.append((positive, [ar.real(c) for c in _c_closed(ar, xb[positive])]))
    if (~positive).any():
        parts.append((~positive, _c_negative(ar, xb[~positive])))
    return parts


def c_functions(ar: Arithmetic, x) -> list:
    """``c_0..c_3`` of every element of ``x`` (any shape), each piece by its best form."""
    return _by_form(ar, x, 4, _c_big)


def eb_matrices(ar: Arithmetic, consts: dict, lam2) -> np.ndarray:
    """Transfer matrices ``(B, S, 4, 4)`` of Euler–Bernoulli segments at ``lam2`` ``(B,)``."""
    lam2 = np.asarray(lam2)[:, None]
    EI, l, A, F = consts["EI"], consts["l"], consts["A"], consts["F"]
    x = -(lam2 * A + F)
    c0, c1, c2, c3 = c_functions(ar, x)
    l2 = l * l
    l3 = l2 * l
    return stack_matrix([
        [c0, l * c1, l2 * c2 / EI, l3 * c3 / EI],
        [x * c3 / l, c0, l * c1 / EI, l2 * c2 / EI],
        [EI * x * c2 / l2, EI * x * c3 / l, c0, l * c1],
        [EI * x * c1 / l3, EI * x * c2 / l2, x * c3 / l, c0],
    ])


# -- other theories ----------------------------------------------------------------------
def theory_constants(ar: Arithmetic, segments) -> dict:
    """Constant arrays for :func:`theory_matrices` from ``(EI, a, b, cN, rhoI, m, kw, l)``.

    ``c = cN + rhoI lam**2`` and ``mu = m lam**2 + kw`` (see
    :meth:`symtmm.elements.theories.BeamSegment.coefficients`).
    """
    names = ("EI", "a", "b", "cN", "rhoI", "m", "kw", "l")
    cols = {k: [] for k in names}
    for values in segments:
        for k, v in zip(names, values):
            cols[k].append(ar.exact(v))
    return {k: ar.array(v) for k, v in cols.items()}


def _series(ar, t, d, h):
    """``(alpha0, beta0, alpha1, beta1)`` of ``F0, F1`` at length ``h``, by the series in ``(t, d)``.

    ``q_k = p_k h**(2(k-1))`` with ``p_k = (r1**k - r2**k)/(r1 - r2)``:
    ``q_0 = 0``, ``q_1 = 1``, ``q_k = T q_(k-1) - D q_(k-2)`` (``T = t h**2``, ``D = d h**4``);
    ``beta0 = h**2 sum q_k/(2k)!``, ``alpha0 = 1 - D sum q_(k-1)/(2k)!`` and likewise with
    ``(2k+1)!`` for ``F1``. With ``max|r| h**2 <= 1``, ``|q_k| <= k``: the tails beyond ``K``
    are below ``2K/(2K)!`` and ``2K/(2K+1)!`` (consecutive bounds shrink at least 2x).
    """
    K = ar.series_terms(lambda k: math.log2(k) + _log2_inverse_factorial(2 * k))
    inv = _inverse_factorials(ar, 2 * K + 2)
    T, D = t * h * h, d * h ** 4
    q_prev, q = 0 * T, 1 + 0 * T
    s0b, s0a, s1b, s1a = 0 * T, 0 * T, 0 * T, 0 * T
    for k in range(1, K):
        s0b = s0b + q * inv[2 * k]
        s0a = s0a + q_prev * inv[2 * k]
        s1b = s1b + q * inv[2 * k + 1]
        s1a = s1a + q_prev * inv[2 * k + 1]
        q_prev, q = q, T * q - D * q_prev
    even = sp.Rational(2 * K, math.factorial(2 * K))
    odd = sp.Rational(2 * K, math.factorial(2 * K + 1))
    s0b, s0a = ar.widen(s0b, even), ar.widen(s0a, even)
    s1b, s1a = ar.widen(s1b, odd), ar.widen(s1a, odd)
    return (1 - D * s0a, h * h * s0b, h * (1 - D * s1a), h * h * h * s1b)


def _double(coef, t, d):
    """``F0, F1`` at twice the length: ``F0(2h) = 2 F0**2 - I``, ``F1(2h) = 2 F0 F1``."""
    a0, b0, a1, b1 = coef
    return (2 * (a0 * a0 - d * b0 * b0) - 1, 2 * (2 * a0 * b0 + t * b0 * b0),
            2 * (a0 * a1 - d * b0 * b1), 2 * (a0 * b1 + a1 * b0 + t * b0 * b1))


def _assemble(coef, a, b, c, mu, EI) -> np.ndarray:
    """``U`` in the order ``[Y, Theta, M, Q]`` from ``alpha, beta`` of ``F0`` and ``F1``.

    ``G = B C`` on ``(Y, M)``, ``G' = C B`` on ``(Theta, Q)``; ``U = [[F0(G), B F1(G')],
    [C F1(G), F0(G')]]`` with ``B = [[a, b], [c, a]]``, ``C = [[0, 1/EI], [-mu, 0]]``.
    """
    a0, b0, a1, b1 = coef
    g00, g01, g10, g11 = -b * mu, a / EI, -a * mu, c / EI          # G on (Y, M)
    p00, p01, p10, p11 = c / EI, a / EI, -mu * a, -mu * b          # G' on (Theta, Q)
    h00, h01, h10, h11 = a1 + b1 * p00, b1 * p01, b1 * p10, a1 + b1 * p11   # F1(G')
    k00, k01, k10, k11 = a1 + b1 * g00, b1 * g01, b1 * g10, a1 + b1 * g11   # F1(G)
    return stack_matrix([
        [a0 + b0 * g00, a * h00 + b * h10, b0 * g01, a * h01 + b * h11],
        [k10 / EI, a0 + b0 * p00, k11 / EI, b0 * p01],
        [b0 * g10, c * h00 + a * h10, a0 + b0 * g11, c * h01 + a * h11],
        [-mu * k00, b0 * p10, -mu * k01, a0 + b0 * p11],
    ])


def theory_matrices(ar: Arithmetic, consts: dict, lam2) -> np.ndarray:
    """Transfer matrices ``(B, S, 4, 4)`` of general beam segments at ``lam2`` ``(B,)``."""
    lam2 = np.asarray(lam2)[:, None]
    EI, a, b, l = consts["EI"], consts["a"], consts["b"], consts["l"]
    c = consts["cN"] + consts["rhoI"] * lam2
    mu = consts["m"] * lam2 + consts["kw"]
    t = c / EI - b * mu
    d = mu * (a * a - b * c) / EI
    # rho >= max|r|, the eigenvalues of G: pieces h with rho h**2 <= 1/2 (a margin for
    # the float rounding of this bound), the same number of doublings over the batch
    tu, du = ar.upper(t), ar.upper(d)
    rho = tu / 2 + np.sqrt(tu * tu / 4 + du)
    grow = np.sqrt(2.0 * np.max(rho, axis=0, initial=0.0)) * ar.upper(l)
    steps = np.where(grow > 1.0, np.ceil(np.log2(np.maximum(grow, 1.0))), 0).astype(int)
    U = None
    for j in np.unique(steps):
        cols = np.nonzero(steps == j)[0]
        sub = slice(None) if len(cols) == steps.size else cols
        coef = _series(ar, t[:, sub], d[:, sub], l[sub] * (0.5 ** int(j)))
        for _ in range(int(j)):
            coef = _double(coef, t[:, sub], d[:, sub])
        part = _assemble(coef, a[sub], b[sub], c[:, sub], mu[:, sub], EI[sub])
        if U is None:
            if len(cols) == steps.size:
                return part
            U = np.empty((part.shape[0], steps.size, 4, 4), dtype=part.dtype)
        U[:, cols] = part
    return U


# -- rods ------------------------------------------------------------------------------------
def rod_constants(ar: Arithmetic, segments) -> dict:
    """Constant arrays for :func:`rod_matrices` from ``(EA, GJ, m, kw, rhoIp, l)`` per segment.

    ``A = m l**2 / EA``, ``F = kw l**2 / EA`` and ``R = rhoIp l**2 / GJ`` give the arguments
    ``z_u = A lam**2 + F`` and ``z_t = R lam**2`` of the axial and the torsional motion.
    """
    cols = {"EA": [], "GJ": [], "m": [], "kw": [], "rhoIp": [], "l": [], "A": [], "F": [],
            "R": []}
    for EA, GJ, m, kw, rhoIp, l in segments:
        EA, GJ, m, kw, rhoIp, l = (sp.sympify(v) for v in (EA, GJ, m, kw, rhoIp, l))
        for k, v in (("EA", EA), ("GJ", GJ), ("m", m), ("kw", kw), ("rhoIp", rhoIp), ("l", l),
                     ("A", m * l**2 / EA), ("F", kw * l**2 / EA), ("R", rhoIp * l**2 / GJ)):
            cols[k].append(ar.exact(v))
    return {k: ar.array(v) for k, v in cols.items()}


def _real_part(v) -> float:
    """The real part of a number of any arithmetic as a float (a jet's value's, a ball's
    midpoint's): only to choose a branch, never a bound."""
    v = v.c[0] if hasattr(v, "c") else v
    try:
        return complex(v).real
    except TypeError:
        return float(v)


def _f_big(ar: Arithmetic, zb) -> list:
    """``F0, F1`` where ``|z| >= 1``: ``cos, sin`` of ``sqrt(-z)`` where ``Re z < 0``, else
    ``cosh, sinh`` of ``sqrt(z)`` (each root's cut away from its ``z``)."""
    centre = np.array([_real_part(v) for v in zb])
    parts = []
    for mask, wave in ((centre < 0, True), (centre >= 0, False)):
        if not mask.any():
            continue
        if wave:
            t = ar.sqrt(-zb[mask])
            co, si = ar.cos_sin(t)
            values = [co, si / t]
        else:
            t = ar.sqrt(zb[mask])
            ch, sh = ar.cosh_sinh(t)
            values = [ch, sh / t]
        if not ar.is_complex(zb):
            values = [ar.real(v) for v in values]
        parts.append((mask, values))
    return parts


def f_functions(ar: Arithmetic, z) -> list:
    """``F0 = cosh(sqrt z)``, ``F1 = sinh(sqrt z) / sqrt z`` of every element of ``z`` (any
    shape): entire in ``z``, so any square root serves; the closed forms take the one whose
    cut is away from ``z`` (``i sqrt(-z)`` where ``Re z < 0``: ``cos`` and ``sin``)."""
    return _by_form(ar, z, 2, _f_big)


def rod_matrices(ar: Arithmetic, consts: dict, lam2) -> np.ndarray:
    """Transfer matrices ``(B, S, 4, 4)`` of rod segments at ``lam2`` ``(B,)``.

    The state ``[Y, Theta, M, Q] = [u, phi, T, -N]``: ``Y' = -Q/EA``, ``Q' = -mu Y`` and
    ``Theta' = M/GJ``, ``M' = rhoIp lam**2 Theta`` (:func:`symtmm.model.rod`), so ``exp(A l)``
    is ``F0 I + l F1 A`` on each pair, at ``z_u = mu l**2/EA`` and ``z_t = rhoIp lam**2
    l**2/GJ``.
    """
    lam2 = np.asarray(lam2)[:, None]
    EA, GJ, l = consts["EA"], consts["GJ"], consts["l"]
    zu = lam2 * consts["A"] + consts["F"]
    zt = lam2 * consts["R"]
    u0, u1 = f_functions(ar, zu)
    t0, t1 = f_functions(ar, zt)
    mu = consts["m"] * lam2 + consts["kw"]
    c = consts["rhoIp"] * lam2
    zero = 0 * u0
    return stack_matrix([
        [u0, zero, zero, -l * u1 / EA],
        [zero, t0, l * t1 / GJ, zero],
        [zero, c * l * t1, t0, zero],
        [-mu * l * u1, zero, zero, u0],
    ])


# -- beams joined by layers -----------------------------------------------------------------
def coupled_constants(ar: Arithmetic, segments) -> dict:
    """Constant arrays for :func:`coupled_matrices` from ``(N, l, beams, couplings)`` per
    segment (all with the same ``N``; see :class:`symtmm.elements.layer.CoupledSegment`).

    Per segment ``A_i = m_i l**4 / EI_i``, ``F_i = kw_i l**4 / EI_i``, ``Kl = l**4 EI**-1 L_k``,
    ``Cl = l**4 EI**-1 L_c`` (so ``X = -(diag(A lam**2 + F) + Kl + lam Cl)``) and the
    unscaling factors ``l``, ``l**2 / EI_i``, ``l**3 / EI_i``.
    """
    from ..elements.layer import CoupledSegment
    n = segments[0][0]
    cols: dict = {"l": [], "damped": False}
    for key in ("A", "F", "sM", "sQ"):
        cols[key] = [[] for _ in range(n)]
    for key in ("Kl", "Cl"):
        cols[key] = [[[] for _ in range(n)] for _ in range(n)]
    for size, l, beams, couplings in segments:
        seg = CoupledSegment(beams, l, couplings)
        Lk, Lc = seg.laplacians()
        l = sp.sympify(l)
        cols["l"].append(ar.exact(l))
        cols["damped"] = cols["damped"] or seg.damped
        for i, (EI, m, kw) in enumerate(seg.beams):
            cols["A"][i].append(ar.exact(m * l**4 / EI))
            cols["F"][i].append(ar.exact(kw * l**4 / EI))
            cols["sM"][i].append(ar.exact(l**2 / EI))
            cols["sQ"][i].append(ar.exact(l**3 / EI))
            for j in range(n):
                cols["Kl"][i][j].append(ar.exact(Lk[i][j] * l**4 / EI))
                cols["Cl"][i][j].append(ar.exact(Lc[i][j] * l**4 / EI))
    out = {"N": n, "damped": cols["damped"], "l": ar.array(cols["l"])}
    for key in ("A", "F", "sM", "sQ"):
        out[key] = [ar.array(v) for v in cols[key]]
    for key in ("Kl", "Cl"):
        out[key] = [[ar.array(v) for v in row] for row in cols[key]]
    return out


def _matmul(X, Y):
    """Product of square matrices given as nested lists of arrays."""
    n = len(X)
    return [[sum((X[i][k] * Y[k][j] for k in range(1, n)), X[i][0] * Y[0][j])
             for j in range(n)] for i in range(n)]


def _coupled_terms(ar: Arithmetic, rho: float) -> int:
    """Terms ``K`` of ``c_j(X) = sum_k X**k / (4k+j)!`` for ``|X| <= rho``: the tail is
    below the precision and beyond ``K`` every term is at most half the one before (also
    in the series of its first three derivatives), so the tail is at most ``2 rho**K /
    (4K + j)!``."""
    log_rho = math.log2(max(rho, 1e-300))
    K = max(3, ar.series_terms(lambda k: k * log_rho + _log2_inverse_factorial(4 * k)))
    # consecutive terms shrink at least 2x also for the derivatives' series (jets: their
    # terms carry an extra factor of at most (k + 1)/(k - 2) <= 4 from k = 3 on)
    while rho > (4 * K + 1) * (4 * K + 2) * (4 * K + 3) * (4 * K + 4) / 8:
        K += 1
    return K


def coupled_matrices(ar: Arithmetic, consts: dict, lam2, lam=None) -> np.ndarray:
    """Transfer matrices ``(B, S, 4N, 4N)`` of coupled pieces at ``lam2`` ``(B,)``.

    ``lam`` (the eigenvalue itself) is needed when a layer has damping.
    """
    n = consts["N"]
    lam2 = np.asarray(lam2)[:, None]
    if consts["damped"]:
        if lam is None:
            raise ValueError("a damped layer needs lam, not only lam**2")
        lam = np.asarray(lam)[:, None]
    X = [[None] * n for _ in range(n)]
    for i in range(n):
        for j in range(n):
            v = consts["Kl"][i][j] + 0 * lam2
            if consts["damped"]:
                v = v + lam * consts["Cl"][i][j]
            if i == j:
                v = v + lam2 * consts["A"][i] + consts["F"][i]
            X[i][j] = -v
    # |X| (the infinity norm) over the whole batch: one series length for all points
    rho = float(np.max(sum(ar.upper(X[i][j]) for j in range(n) for i in range(n)),
                       initial=0.0)) if n else 0.0
    rho = math.nextafter(rho, math.inf)
    K = _coupled_terms(ar, rho)
    inv = _inverse_factorials(ar, 4 * K + 4)
    one = 1 + 0 * X[0][0]
    zero = 0 * X[0][0]
    identity = [[one if i == j else zero for j in range(n)] for i in range(n)]
    powers = [identity]
    for _ in range(1, K):
        powers.append(_matmul(powers[-1], X))
    rho_exact = sp.Rational(rho)
    # for jets: the derivatives of X bounded in norm, as the tail's variable (the tail of
    # sum X**k/(4k+j)! has derivatives below k |X|**(k-1) |X'| and k(k-1) |X|**(k-2) |X'|**2
    # + k |X|**(k-1) |X''| per term, which shrink 2x as the terms do)
    wrt = ar.norm_variable(X)
    c = []
    for j in range(4):
        cj = [[sum((P[r][q] * inv[4 * k + j] for k, P in enumerate(powers) if k), powers[0][r][q]
                   * inv[j]) for q in range(n)] for r in range(n)]
        f = math.factorial(4 * K + j)
        tail = 2 * rho_exact**K / f
        slope = 2 * K * rho_exact ** (K - 1) / f
        # (the k-th derivative's terms vanish below k = 2, 3: their sums start there)
        K2, K3 = max(K, 2), max(K, 3)
        curve = 2 * K2 * (K2 - 1) * rho_exact ** (K2 - 2) / math.factorial(4 * K2 + j)
        third = 2 * K3 * (K3 - 1) * (K3 - 2) * rho_exact ** (K3 - 3) / math.factorial(4 * K3 + j)
        c.append([[ar.widen(v, tail, wrt=wrt, slope=slope, curve=curve, third=third)
                   for v in row] for row in cj])
    Xc = [None, _matmul(X, c[1]), _matmul(X, c[2]), _matmul(X, c[3])]
    # scaled blocks V[a][b]: c_(b-a) above the diagonal, X c_(4+b-a) below
    l = consts["l"]
    scale = [[one] * n, [l + zero] * n, [consts["sM"][i] + zero for i in range(n)],
             [consts["sQ"][i] + zero for i in range(n)]]
    rows = []
    for a in range(4):
        for i in range(n):
            row = []
            for b in range(4):
                block = c[b - a] if b >= a else Xc[4 + b - a]
                for j in range(n):
                    v = block[i][j]
                    if a != b or (i != j and a >= 2):
                        # (M and Q are scaled by each beam's own EI)
                        v = v * scale[b][j] / scale[a][i]
                    row.append(v)
            rows.append(row)
    return stack_matrix(rows)


def family_matrices(ar: Arithmetic, kinds, lam2, lam=None) -> list:
    """The transfer matrices of segment kinds, one array per family group, in order:
    ``(B, S, 4, 4)`` for ``"eb"`` and ``"theory"``, ``(B, S, 4N, 4N)`` for ``"coupled"``."""
    out = []
    for family, consts in kinds:
        if family == "coupled":
            out.append(coupled_matrices(ar, consts, lam2, lam))
        else:
            out.append(_MATRICES[family](ar, consts, lam2))
    return out


def transfer_matrices(ar: Arithmetic, kinds, lam2) -> np.ndarray:
    """``(B, S, 4, 4)`` for segment kinds ``[(family, constants), ...]`` in order.

    ``family`` is ``"eb"`` or ``"theory"``; each family's segments are evaluated together.
    """
    parts = [_MATRICES[family](ar, consts, lam2) for family, consts in kinds]
    return parts[0] if len(parts) == 1 else np.concatenate(parts, axis=1)


# -- long pieces of the other theories ------------------------------------------------------
class Condensed:
    """A long piece made of ``2**doublings`` equal pieces ``inner`` (a beam of a theory other
    than Euler–Bernoulli, or beams joined by undamped layers:
    :func:`symtmm.numeric.plan.condensed_piece`, :func:`~symtmm.numeric.plan.layered_piece`):
    its dynamic stiffness is
    that of the chain with its inner nodes condensed out, by doubling
    (:func:`condensed_stiffness`), and no transfer matrix grows across it.

    Examples
    --------
    >>> from symtmm.elements.theories import BeamSegment
    >>> Condensed(BeamSegment(1, 1, sp.Rational(1, 8), rhoI=1), 3).l
    1
    """

    __slots__ = ("doublings", "inner", "l")

    def __init__(self, inner, doublings: int):
        self.inner, self.doublings = inner, int(doublings)
        self.l = inner.l * 2 ** self.doublings


def condensed_stiffness(ar: Arithmetic, D, det, doublings: int, middles: list | None = None):
    """``(D, det U12)`` of ``2**doublings`` equal pieces in a row, their inner nodes condensed
    out, from one piece's ``D`` ``(B, 2h, 2h)`` (``h`` freedoms an end: 2, or ``2 N`` for
    ``N`` beams joined by a layer) and ``det U12`` ``(B,)``.

    Two pieces ``[[P, Q], [Q', R]]`` joined at a node give ``[[P, Q, 0], [Q', R + P, Q], [0,
    Q', R]]``; with ``S = R + P`` the node's own block, the pair's stiffness is ``[[P - Q
    S**-1 Q', -Q S**-1 Q], [-Q' S**-1 Q', R - Q' S**-1 Q]]`` and its ``det U12 = det S *
    det U12**2`` (``Delta = det K * prod det U12 * P`` of the two and of the one, with
    ``det`` of the three-node ``K`` equal to ``det S`` times the pair's). ``S`` is the
    stiffness at the middle of the pair clamped at both ends: nonsingular (and positive
    definite on the frequency axis, so the count is the whole chain's) below the pair's
    first clamped-clamped frequency, which the long piece's rule keeps above the range.
    Only products of the pieces' blocks, each to rounding of its row: an evanescent
    piece's far-end coupling ``exp(-|s| l)`` keeps its digits. ``middles``: a list that
    receives each doubling's ``S`` (nested lists of arrays), whose inertia a count past the
    chain's clamped frequencies adds (:func:`symtmm.numeric.clamped.clamped_counts`).
    """
    from .stiffness import _inverse
    h = D.shape[1] // 2

    def minus(X, Y):
        return [[x - y for x, y in zip(rx, ry)] for rx, ry in zip(X, Y)]

    def block(D, r, c):
        return [[D[:, r + i, c + k] for k in range(h)] for i in range(h)]

    for _ in range(doublings):
        P, Q, Qt, R = block(D, 0, 0), block(D, 0, h), block(D, h, 0), block(D, h, h)
        S = [[p + r for p, r in zip(rp, rr)] for rp, rr in zip(P, R)]
        if middles is not None:
            middles.append(S)
        inv, dS = _inverse(S)
        SQt, SQ = _matmul(inv, Qt), _matmul(inv, Q)
        zero = [[0 * v for v in row] for row in P]
        top = minus(P, _matmul(Q, SQt)), minus(zero, _matmul(Q, SQ))
        bottom = minus(zero, _matmul(Qt, SQt)), minus(R, _matmul(Qt, SQ))
        D = stack_matrix([a + b for a, b in zip(*top)] + [a + b for a, b in zip(*bottom)])
        det = dS * det * det
    return D, det


# -- one segment element --------------------------------------------------------------------
def kind(seg) -> tuple:
    """``(family, exact constants)`` of a segment element: equal kinds have equal matrices.

    ``"eb"``: ``(EI, m, l, kw)``; ``"theory"``: ``(EI, a, b, cN, rhoI, m, kw, l)`` (see
    :func:`theory_constants`); ``"rod"``: ``(EA, GJ, m, kw, rhoIp, l)``.
    """
    if isinstance(seg, EulerBernoulliSegment):
        return ("eb", (seg.EI, seg.m, seg.l, seg.kw))
    if isinstance(seg, Condensed):
        return ("condensed", (kind(seg.inner), seg.doublings))
    if isinstance(seg, CoupledSegment):
        return ("coupled", (seg.size, seg.l, seg.beams, seg.couplings))
    if seg.kGA is not None and seg.kGA == 0:
        # a rod (symtmm.model.rod): its two motions by their own closed forms
        return ("rod", (seg.N, seg.EI, seg.m, seg.kw, seg.rhoI, seg.l))
    a, b, cN = static_coefficients(seg.N, seg.kGA)
    return ("theory", (seg.EI, a, b, cN, seg.rhoI, seg.m, seg.kw, seg.l))


def kind_key(kind_) -> tuple:
    """A dictionary key of a segment kind: equal keys, equal kinds. An Euler–Bernoulli
    kind's rational constants by their integers (:func:`~symtmm.numeric.arith.exact_key`:
    a SymPy number's hash costs a microsecond, four a kind, and a chain's plan looks up a
    kind per piece); the other kinds as they are.

    Examples
    --------
    >>> kind_key(("eb", (sp.Integer(2), sp.Rational(1, 2), sp.Integer(1), sp.Integer(0))))
    ('eb', (2, 1), (1, 2), (1, 1), (0, 1))
    """
    family, consts = kind_
    if family == "condensed":
        return (family, kind_key(consts[0]), consts[1])
    return (family,) + tuple(exact_key(v) for v in consts) if family == "eb" else kind_


def kind_order(kind_) -> tuple:
    """Sort key of segment kinds: the order of :func:`kind_tables`' groups (``"eb"``, then
    ``"theory"``, ``"rod"``, ``"condensed"``, then ``"coupled"`` by the number of beams)."""
    family, consts = kind_
    return {"eb": (0, 0), "theory": (1, 0), "rod": (1, 1),
            "condensed": (1, 2)}.get(family) or (2, consts[0])


def kind_inertia(kind_) -> tuple:
    """``(m, rhoI)`` of a 4-state segment kind: the mass and the rotary (a rod's polar)
    inertia per unit length, for the kinetic energy ``m Y**2 + rhoI Theta**2``."""
    family, consts = kind_
    if family == "condensed":
        return kind_inertia(consts[0])
    if family == "eb":
        return consts[1], 0
    if family == "rod":
        return consts[2], consts[4]
    if family == "theory":
        return consts[5], consts[4]
    raise ValueError(f"no inertia pair for a {family!r} segment")


def kind_size(kind_) -> int:
    """The number of state variables at one end of a segment of this kind (4 per beam)."""
    family, consts = kind_
    if family == "condensed":
        return kind_size(consts[0])
    return 4 * consts[0] if family == "coupled" else 4


def kind_tables(ar: Arithmetic, kinds) -> list:
    """The constants of segment kinds in ``ar``, grouped by family (``kinds`` sorted by
    :func:`kind_order`: the groups come in that order)."""
    if [kind_order(k) for k in kinds] != sorted(kind_order(k) for k in kinds):
        raise ValueError("segment kinds must be sorted by kind_order")
    eb = [c for f, c in kinds if f == "eb"]
    th = [c for f, c in kinds if f == "theory"]
    rods = [c for f, c in kinds if f == "rod"]
    out = []
    if eb:
        out.append(("eb", eb_constants(ar, eb)))
    if th:
        out.append(("theory", theory_constants(ar, th)))
    if rods:
        out.append(("rod", rod_constants(ar, rods)))
    for inner, doublings in (c for f, c in kinds if f == "condensed"):
        # (one table each: few in a plan, each its own chain of doublings)
        out.append(("condensed", {"inner": kind_tables(ar, [inner])[0], "doublings": doublings}))
    sizes = sorted({c[0] for f, c in kinds if f == "coupled"})
    for n in sizes:
        out.append(("coupled", coupled_constants(ar, [c for f, c in kinds
                                                      if f == "coupled" and c[0] == n])))
    return out


def cut_tables(ar: Arithmetic, kinds, tables, k, lengths) -> dict:
    """The constants of 4-state kind ``k`` of ``kinds`` cut to each of ``lengths`` (an
    array of numbers of ``ar``): one segment per length, for :func:`family_matrices`.

    ``k`` may also be a sequence, the kind of each length (all of one family): the
    pieces of many kinds in one table, evaluated in one call (the samples of a shape).
    ``tables`` are the kinds' own (:func:`kind_tables`); only the length and what
    scales with it change.
    """
    many = not isinstance(k, (int, np.integer))
    ks = list(k) if many else [k]
    family = kinds[ks[0]][0]
    place = np.cumsum([f == family for f, _ in kinds]) - 1     # each kind in its family
    if any(kinds[i][0] != family for i in ks):
        raise ValueError("cut_tables: the kinds of one table must be of one family")
    columns = dict(tables)[family]
    if many:
        at = place[ks]
        one = {name: column[at] for name, column in columns.items()}
        out = dict(one)
    else:
        one = {name: column[place[k]] for name, column in columns.items()}
        out = {name: ar.array([value] * len(lengths)) for name, value in one.items()}
    out["l"] = lengths
    r = lengths / one["l"]
    if family == "eb":
        # A = m l**4 / EI and F = kw l**4 / EI scale with the fourth power of the length
        r4 = (r * r) * (r * r)
        out["A"], out["F"] = r4 * one["A"], r4 * one["F"]
    elif family == "rod":
        # A, F, R (the arguments' factors) scale with its square
        for name in ("A", "F", "R"):
            out[name] = (r * r) * one[name]
    return out


def segment_matrix(ar: Arithmetic, seg, lam2) -> np.ndarray:
    """The transfer matrices ``(B, 4, 4)`` of one segment element at ``lam2`` ``(B,)``.

    Examples
    --------
    >>> import numpy as np
    >>> from symtmm.elements import EulerBernoulliSegment
    >>> from symtmm.numeric.arith import DOUBLE
    >>> U = segment_matrix(DOUBLE, EulerBernoulliSegment(1, 1, 1), np.array([0.0]))
    >>> float(U[0, 0, 3].real)                 # static: l**3 / (6 EI)
    0.16666666666666666
    """
    with ar:
        return transfer_matrices(ar, kind_tables(ar, [kind(seg)]), lam2)[:, 0]


#: The transfer matrices of each family of 4-state segments.
_MATRICES = {"eb": eb_matrices, "theory": theory_matrices, "rod": rod_matrices}
