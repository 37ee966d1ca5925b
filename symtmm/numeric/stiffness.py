"""The dynamic-stiffness kernel: segment stiffness, assembly, banded ``LDL^T``.

Written once for every arithmetic of :mod:`symtmm.numeric.arith` and vectorised
over a leading axis of points:

* :func:`segment_stiffness`: a segment's 4x4 dynamic stiffness from its transfer
  matrix, split into displacement and force blocks ``z = [d; f]``, ``d = (Y,
  Theta)``, ``f = (M, Q)``: ``f0 = U12^-1 (d1 - U11 d0)``, ``f1 = U21 d0 + U22 f0``,
  the end actions ``(Q0, -M0, -Q1, M1)`` conjugate to ``(Y0, Theta0, Y1, Theta1)``;
* :func:`eb_stiffness`: the same of Euler–Bernoulli segments straight from the
  functions ``c_j`` (no ``U``: a third of the operations);
* :func:`assemble`: the upper band of the scaled global ``K(lam)`` from a
  :class:`~symtmm.numeric.plan.StiffnessPlan`;
* :func:`factor`: ``LDL^T`` without pivoting on the band, keeping every pivot
  with its sign and whether that sign can be trusted; numbers that are Python
  objects (balls, mpmath) update the envelope's entries only
  (:func:`envelope_maps`: exact zeros skipped).

The sign test follows the backward error of ``LDL^T`` (Higham, *Accuracy and
Stability of Numerical Algorithms*, 2nd ed., chapter 10 for Cholesky; the same
argument for ``LDL^T``): the computed factors are exact for ``K + E`` with
``|E| <= c u |L||D||L^T|``, whose diagonal at ``k`` is ``|K_kk| + sum_p
|K^(p)_pk|**2 / |d_p|``. That sum is kept per freedom as the elimination goes
(``O(b)`` work per pivot), and a pivot's sign is trusted when the pivot exceeds
it by the arithmetic's margin (:meth:`~symtmm.numeric.arith.Arithmetic.decide`);
balls decide by themselves (a pivot ball holding 0 is undecided).

What the factorisation gives (:class:`Factors`):

* the **count** of negative pivots, which by Sylvester's law of inertia is the
  number of negative eigenvalues of ``K(omega)``: with no piece reaching a
  clamped-clamped eigenvalue (``J0 = 0``), the Wittrick–Williams count of the
  model's natural frequencies below ``omega``; on a plan for counts whose long
  pieces pass theirs, plus ``J0`` (:mod:`symtmm.numeric.clamped`);
* ``Delta(lam) = det K * prod det U12 * P`` (equal to ``det R`` of the transfer
  formulation): a product of pivots, in logarithms for doubles.
"""

from __future__ import annotations

import dataclasses
import functools
import math
from dataclasses import dataclass

import numpy as np

from ..deadline import check as check_time
from .arith import DOUBLE, Arithmetic, magnitude_parts
from .segments import _matmul, condensed_stiffness, family_matrices, stack_matrix

__all__ = ["segment_stiffness", "coupled_stiffness", "eb_stiffness", "stiffness_values",
           "assemble", "factor", "eliminate", "envelope_maps", "Factors", "dense"]

try:        # the elimination loop in C (setup.py); without a compiler, numpy runs it
    from . import _band
except ImportError:  # pragma: no cover - tested by switching it off
    _band = None

#: ``|x|`` beyond which a long piece's stiffness takes the closed forms: ``NU_MAX**4``, the
#: largest a short piece reaches (:mod:`symtmm.numeric.plan`), where the ``c_j`` keep their
#: digits.
LONG_X = 3.0 ** 4

#: Whether double-precision bands are eliminated by the C loop (where it was built);
#: tests switch it off to run the numpy loop, which gives the same factors.
COMPILED = _band is not None


def segment_stiffness(U):
    """``(D, det U12)``: dynamic stiffness ``(..., 4, 4)`` of segments from ``U`` ``(..., 4, 4)``.

    Rows are the end actions ``(Q0, -M0, -Q1, M1)``, columns ``(Y0, Theta0, Y1, Theta1)``.

    Examples
    --------
    >>> from symtmm.elements import EulerBernoulliSegment
    >>> from symtmm.numeric.arith import DOUBLE
    >>> from symtmm.numeric.segments import segment_matrix
    >>> U = segment_matrix(DOUBLE, EulerBernoulliSegment(1, 1, 1), np.array([0.0]))[0].real
    >>> D, _ = segment_stiffness(U)
    >>> np.round(D, 12)    # the static beam stiffness matrix
    array([[ 12.,   6., -12.,   6.],
           [  6.,   4.,  -6.,   2.],
           [-12.,  -6.,  12.,  -6.],
           [  6.,   2.,  -6.,   4.]])
    """
    return coupled_stiffness(U, 1)


def _inverse(M):
    """``(inverse, det)`` of a square matrix given as nested lists of arrays, by Gauss–Jordan
    elimination without pivoting (for the ``U12`` of short coupled pieces, whose leading
    minors are those of the static flexibility, far from singular)."""
    n = len(M)
    if n == 2:          # (one beam: the closed form, as cheap as it gets on the hot path)
        det = M[0][0] * M[1][1] - M[0][1] * M[1][0]
        return [[M[1][1] / det, -M[0][1] / det], [-M[1][0] / det, M[0][0] / det]], det
    A = [list(row) + [1 + 0 * row[0] if i == j else 0 * row[0] for j in range(n)]
         for i, row in enumerate(M)]
    det = 1 + 0 * M[0][0]
    for k in range(n):
        p = A[k][k]
        det = det * p
        A[k] = [v / p for v in A[k]]
        for i in range(n):
            if i != k:
                f = A[i][k]
                A[i] = [a - f * b for a, b in zip(A[i], A[k])]
    return [row[n:] for row in A], det


def coupled_stiffness(U, n: int):
    """``(D, det U12)``: dynamic stiffness ``(..., 4n, 4n)`` of pieces of ``n`` coupled beams.

    ``U`` ``(..., 4n, 4n)`` in the order ``[Y_1..Y_n, Theta_1.., M_1.., Q_1..]``; rows of
    ``D`` are the end actions ``(Q0, -M0, -Q1, M1)`` (each ``n`` long) conjugate to
    ``(Y0, Theta0, Y1, Theta1)``; for ``n = 1`` the one beam's (:func:`segment_stiffness`).
    """
    m = 2 * n

    def block(r, c):
        return [[U[..., r + i, c + k] for k in range(m)] for i in range(m)]
    U11, U12, U21, U22 = block(0, 0), block(0, m), block(m, 0), block(m, m)
    inv, det = _inverse(U12)
    A = [[-v for v in row] for row in _matmul(inv, U11)]      # f0 = A d0 + inv d1
    C = [[a + b for a, b in zip(r1, r2)] for r1, r2 in zip(U21, _matmul(U22, A))]
    E = _matmul(U22, inv)                                      # f1 = C d0 + E d1
    f0 = [A[i] + inv[i] for i in range(m)]                     # rows M0 (n), Q0 (n)
    f1 = [C[i] + E[i] for i in range(m)]
    rows = (f0[n:] + [[-v for v in r] for r in f0[:n]] + [[-v for v in r] for r in f1[n:]]
            + f1[:n])
    return stack_matrix(rows), det


def _eb_pattern(k11, k12, k13, k14, k22, k24) -> list:
    """The 4x4 stiffness of a uniform Euler–Bernoulli segment from its six distinct
    entries (rows ``(Q0, -M0, -Q1, M1)``, columns ``(Y0, Theta0, Y1, Theta1)``)."""
    return [[k11, k12, -k13, k14], [k12, k22, -k14, k24],
            [-k13, -k14, k11, -k12], [k14, k24, -k12, k22]]


def _closed_entries(ar: Arithmetic, xb, EI, l) -> tuple:
    """``(k11, k12, k13, k14, k22, k24), det U12`` by the closed forms in ``nu = x**(1/4)``
    (complex ``x``, or real ``x > 0``: then ``nu`` is real, and kept real: mpmath's root
    is complex)."""
    nu = ar.root4(xb) if ar.is_complex(xb) else ar.real(ar.root4(xb))
    (ch, sh), (co, si) = ar.cosh_sinh(nu), ar.cos_sin(nu)
    Phi = 1 - ch * co
    b = nu / l
    EIb2 = EI * b * b
    k = (EIb2 * b * (co * sh + si * ch) / Phi, EIb2 * (si * sh) / Phi,
         EIb2 * b * (sh + si) / Phi, EIb2 * (ch - co) / Phi,
         EI * b * (ch * si - co * sh) / Phi, EI * b * (sh - si) / Phi)
    l2 = l * l
    return k, l2 * l2 * Phi / (2 * xb * EI * EI)


def _foundation_entries(ar: Arithmetic, xb, EI, l) -> tuple:
    """As :func:`_closed_entries` for a real ``x = -4 q**4 < 0`` (a foundation stiffer than
    the inertia), in real functions of ``q``: with ``nu = q (1 + i)`` the complex forms
    reduce to ``Phi = sin(q)**2 - sinh(q)**2``, ``k11 = -4 EI q**3 (sinh q cosh q + sin q cos
    q) / (l**3 Phi)``, ``k12 = -2 EI q**2 (sinh(q)**2 + sin(q)**2) / (l**2 Phi)``, ``k13 = -4
    EI q**3 (sinh q cos q + cosh q sin q) / (l**3 Phi)``, ``k14 = -4 EI q**2 sinh q sin q /
    (l**2 Phi)``, ``k22 = 2 EI q (sin q cos q - sinh q cosh q) / (l Phi)``, ``k24 = 2 EI q
    (sinh q cos q - cosh q sin q) / (l Phi)`` and ``det U12 = -l**4 Phi / (8 q**4 EI**2)``:
    sums of like signs, so a long piece (``q`` of tens) keeps every digit (the ``c_j`` of
    :func:`eb_stiffness` cancel there like ``exp(2 q)``)."""
    q = ar.real(ar.root4(-xb / 4))
    (ch, sh), (co, si) = ar.cosh_sinh(q), ar.cos_sin(q)
    Phi = si * si - sh * sh
    g = EI * q / (l * Phi)                 # EI q / (l Phi)
    g2 = g * q / l
    g3 = g2 * q / l
    k = (-4 * g3 * (sh * ch + si * co), -2 * g2 * (sh * sh + si * si),
         -4 * g3 * (sh * co + ch * si), -4 * g2 * (sh * si),
         2 * g * (si * co - sh * ch), 2 * g * (sh * co - ch * si))
    q2, l2 = q * q, l * l
    return k, -(l2 * l2) * Phi / (8 * q2 * q2 * EI * EI)


def eb_closed_stiffness(ar: Arithmetic, consts: dict, lam2, threshold: float = 1.0):
    """``(D, det U12)`` of Euler–Bernoulli segments by the closed forms in ``nu = x**(1/4)``
    where ``|x| >= threshold`` (:func:`eb_stiffness`, from the series of the ``c_j``, elsewhere): with ``Phi = 1 -
    cosh nu cos nu``, ``k11 = EI b**3 (cos sinh + sin cosh)/Phi``, ``k12 = EI b**2 sin sinh /
    Phi``, ``k13 = EI b**3 (sinh + sin)/Phi``, ``k14 = EI b**2 (cosh - cos)/Phi``, ``k22 = EI b
    (cosh sin - cos sinh)/Phi``, ``k24 = EI b (sinh - sin)/Phi`` (``b = nu / l``) and ``det U12
    = l**4 Phi / (2 x EI**2)``; all even in ``nu``, so any fourth root serves. A real ``x < 0``
    takes the real forms of :func:`_foundation_entries`.

    The same numbers as the U path, with far less dependency among the operations: over a
    box of ``lam`` (jets, :mod:`symtmm.numeric.jet`) the enclosures stay narrow where the
    U path's inversion of ``U12`` multiplies their widths a hundredfold. And they hold
    every digit for pieces however long (``threshold = NU_MAX**4``: the long pieces of
    :func:`symtmm.numeric.plan.long_piece`), where the ``c_j`` lose digits like the
    exponentials' growth; each entry to within rounding of the largest of its row.

    Examples
    --------
    A piece ``|s| l = 40`` long on a foundation (``x = -4 * 20**4``), whose far-end
    entries are ``exp(-20)`` times its near-end ones, against the same numbers at 60
    digits:

    >>> import mpmath
    >>> from symtmm.numeric.arith import MP
    >>> from symtmm.numeric.segments import eb_constants
    >>> lam2 = np.array([0.0])
    >>> D, det = eb_closed_stiffness(DOUBLE, eb_constants(DOUBLE, [(1, 1, 1, 4 * 20**4)]), lam2)
    >>> ar = MP(200)
    >>> E, _ = eb_closed_stiffness(ar, eb_constants(ar, [(1, 1, 1, 4 * 20**4)]), ar.array([0]))
    >>> err = max(abs(float(E[0, 0, i, j]) - D[0, 0, i, j]) / abs(float(E[0, 0, i, j]))
    ...           for i in range(4) for j in range(4))
    >>> bool(err < 1e-14), bool(abs(D[0, 0, 0, 2] / D[0, 0, 0, 0]) < 1e-7)
    (True, True)
    """
    lam2 = np.asarray(lam2)
    EI, l, A, F = consts["EI"], consts["l"], consts["A"], consts["F"]
    x = -(lam2[:, None] * A + F)
    big = ar.upper(x.reshape(-1)).reshape(x.shape) >= threshold
    if not big.any():
        return eb_stiffness(ar, consts, lam2)
    D, det = ar.zeros(x.shape + (4, 4), like=x), ar.zeros(x.shape, like=x)
    if not big.all():
        # the series where it serves, and only there: at a long piece's points its c_j
        # grow like exp(|x|**(1/4)), and past the clamped frequencies its c2**2 - c1 c3 is
        # rounding (0 at times: quotients that warned, of numbers thrown away)
        small = np.nonzero(~big)
        D[small], det[small] = _series_entries(ar, x[small], EI[small[1]], l[small[1]])
    idx = np.nonzero(big)
    xb, EIb, lb = x[idx], EI[idx[1]], l[idx[1]]
    if ar.is_complex(xb):
        parts = [(np.ones(xb.shape, dtype=bool), _closed_entries)]
    else:
        positive = ar.positive(xb)
        parts = [(positive, _closed_entries), (~positive, _foundation_entries)]
    for mask, entries in parts:
        if not mask.any():
            continue
        k, d = entries(ar, xb[mask], EIb[mask], lb[mask])
        at = tuple(i[mask] for i in idx)
        rows = _eb_pattern(*k)
        for i in range(4):
            for j in range(4):
                D[at + (i, j)] = rows[i][j]
        det[at] = d
    return D, det


def eb_stiffness(ar: Arithmetic, consts: dict, lam2):
    """``(D, det U12)`` of Euler–Bernoulli segments from the entire functions ``c_j(x)``
    (:func:`~symtmm.numeric.segments.c_functions`, each in its best form) without ``U``:
    with ``dc = c2**2 - c1 c3`` (``det U12 = l**4 dc / EI**2``) and ``s = EI / (l**3 dc)``,
    ``k11 = s (c0 c1 - x c2 c3)``, ``k12 = s l (c1**2 - c0 c2)``, ``k13 = s c1``,
    ``k14 = s l c2``, ``k22 = s l**2 (c1 c2 - c0 c3)``, ``k24 = s l**2 c3`` in the pattern of
    :func:`eb_closed_stiffness` (the inverse of ``U12`` and the products of
    :func:`segment_stiffness` worked out; the other entries agree through ``c1**2 + x c3**2
    = 2 c0 c2``). A third of the operations of the ``U`` path: it is what a ball or an
    mpmath number pays one Python call each for.

    Examples
    --------
    >>> from symtmm.elements import EulerBernoulliSegment
    >>> from symtmm.numeric.segments import kind, kind_tables, segment_matrix
    >>> lam2 = np.array([-30.0])
    >>> [(_, consts)] = kind_tables(DOUBLE, [kind(EulerBernoulliSegment(2, 3, "1/2"))])
    >>> D, det = eb_stiffness(DOUBLE, consts, lam2)
    >>> U = segment_matrix(DOUBLE, EulerBernoulliSegment(2, 3, "1/2"), lam2)
    >>> D0, det0 = segment_stiffness(U)
    >>> bool(np.allclose(D[:, 0], D0, rtol=1e-13)), bool(np.allclose(det[:, 0], det0))
    (True, True)
    """
    lam2 = np.asarray(lam2)[:, None]
    EI, l = consts["EI"], consts["l"]
    return _series_entries(ar, -(lam2 * consts["A"] + consts["F"]), EI, l)


def _series_entries(ar: Arithmetic, x, EI, l):
    """:func:`eb_stiffness` at given ``x`` (any shape; ``EI`` and ``l`` broadcast to it):
    ``(D (..., 4, 4), det U12)``."""
    from .segments import c_functions
    c0, c1, c2, c3 = c_functions(ar, x)
    dc = c2 * c2 - c1 * c3
    s = EI / (l * l * l * dc)
    sl = s * l
    sl2 = sl * l
    k11 = s * (c0 * c1 - x * c2 * c3)
    k12 = sl * (c1 * c1 - c0 * c2)
    k13, k14 = s * c1, sl * c2
    k22 = sl2 * (c1 * c2 - c0 * c3)
    k24 = sl2 * c3
    D = stack_matrix(_eb_pattern(k11, k12, k13, k14, k22, k24))
    l2 = l * l
    return D, l2 * l2 * dc / (EI * EI)


def stiffness_values(ar: Arithmetic, kinds, lam2, lam=None, long: bool = False):
    """``(D, det U12)``: every segment kind's stiffness flattened and concatenated ``(B, *)``
    (kind after kind, row-major), and ``det U12`` per kind ``(B, kinds)``. ``long``: some
    Euler–Bernoulli pieces may be long (:attr:`~symtmm.numeric.plan.StiffnessPlan.long`),
    and take the closed forms beyond ``|x| = NU_MAX**4``."""
    B = np.asarray(lam2).shape[0]
    Ds, dets = [], []
    for family, consts in kinds:
        if family == "eb":
            if getattr(ar, "closed_stiffness", False):
                D, det = eb_closed_stiffness(ar, consts, lam2)
            elif long:
                D, det = eb_closed_stiffness(ar, consts, lam2, threshold=LONG_X)
            else:
                D, det = eb_stiffness(ar, consts, lam2)
        elif family == "condensed":
            D, det = stiffness_values(ar, [consts["inner"]], lam2, lam, long)
            size = math.isqrt(D.shape[1])
            D, det = condensed_stiffness(ar, D.reshape(B, size, size), det[:, 0],
                                         consts["doublings"])
            D, det = D[:, None], det[:, None]
        else:
            [U] = family_matrices(ar, [(family, consts)], lam2, lam)
            D, det = (coupled_stiffness(U, consts["N"]) if family == "coupled"
                      else segment_stiffness(U))
        Ds.append(D.reshape(B, -1))
        dets.append(det)
    if len(Ds) == 1:
        return Ds[0], dets[0]
    return np.concatenate(Ds, axis=1), np.concatenate(dets, axis=1)


def assemble(plan, ar: Arithmetic, lam2, lam=None):
    """``(K, det U12)``: the scaled ``K`` in upper band storage ``(B, n, b + 1)`` at ``lam2``.

    ``K[p, r, j]`` is ``K(lam_p)[r, r + j]``. ``det U12`` has one column per segment kind.
    ``lam`` (the eigenvalue itself) is needed only when the model has dashpots.
    """
    t = plan.tables(ar)
    lam2 = np.asarray(lam2)
    B = lam2.shape[0]
    if t["kinds"]:
        D, det12 = stiffness_values(ar, t["kinds"], lam2, lam, plan.long)
    else:
        D = ar.zeros((B, 0), like=lam2)
        det12 = ar.zeros((B, 0), like=lam2)
    if lam is None:
        if plan.damped:
            raise ValueError("a damped model needs lam, not only lam**2")
        lam_col = ar.zeros((B, 1), like=lam2)
    else:
        lam_col = np.asarray(lam)[:, None]
    V = np.concatenate([D, np.ones((B, 1), dtype=D.dtype if D.dtype == object else float),
                        lam_col, lam2[:, None]], axis=1)
    n, w = plan.n, plan.width
    K = ar.zeros((B, n * w), like=V)
    # each entry adds its terms in plan order, a layer of terms at a time (in C or numpy:
    # the same sums, the same bits)
    compiled = COMPILED and V.dtype in (np.float64, np.complex128)
    if compiled:
        V = np.ascontiguousarray(V)
    for q, (targets, source, coef) in enumerate(t["layers"]):
        if compiled and coef.dtype == np.float64:
            _band.scatter(V, K, targets, source, coef, B, q > 0, V.dtype == np.complex128)
        else:
            terms = V[:, source] * coef
            K[:, targets] = terms if q == 0 else K[:, targets] + terms
    return K.reshape(B, n, w), det12


@functools.lru_cache(maxsize=64)
def _update_maps(w: int):
    """Index arrays of the rank-one update of ``LDL^T`` on the upper band (half-bandwidth ``b``).

    Pivot ``k`` updates ``K[k + i, k + j] -= K[k, k + i] K[k, k + j] / K[k, k]`` for
    ``1 <= i <= j <= b``: in band storage, row ``k + i``, column ``j - i``.
    """
    pairs = [(i, j) for i in range(1, w) for j in range(i, w)]
    rows = np.array([i for i, _ in pairs], dtype=int)
    cols = np.array([j - i for i, j in pairs], dtype=int)
    fi = np.array([i - 1 for i, _ in pairs], dtype=int)
    fj = np.array([j - 1 for _, j in pairs], dtype=int)
    return rows, cols, fi, fj


@dataclass(frozen=True)
class Factors:
    """``LDL^T`` of ``K`` at a batch of points, and what follows from it.

    Attributes
    ----------
    pivots : numpy.ndarray
        ``(B, n)``: the ``D`` of ``LDL^T`` (of the scaled ``K``).
    signs : numpy.ndarray
        ``(B, n)``: their signs (0 for complex ``K``).
    decided : numpy.ndarray
        ``(B, n)``: whether each sign (or, complex, the pivot's distance from 0) is trusted.
    det12 : numpy.ndarray
        ``(B, kinds)``: ``det U12`` of every segment kind.
    K : numpy.ndarray or BandRows
        ``(B, n, b + 1)``: the band factorised (kept for a pivoted determinant where the
        elimination without pivoting broke down: :meth:`pivoted_delta`); of a double batch
        factorised in parts, its rows at the untrusted points only (:class:`BandRows`).
    products : numpy.ndarray or None
        ``(B,)`` where given: per point the product of its pivots and of ``det U12`` to
        the plan's multiplicities (``Delta`` but for the plan's constant), as computed by
        the factorisation at its full precision (:mod:`symtmm.numeric.multiword`); None
        entries where it did not. A point with a product has its count and ``Delta``
        and no more: its rows of ``pivots`` and ``det12`` are None.
    clamped : numpy.ndarray or None
        ``(B,)`` where the plan is ``clamped``: per point ``J0``, the clamped-clamped
        eigenvalues of its pieces below the frequency (``-1`` undecided), which
        :meth:`counts` adds (:func:`symtmm.numeric.clamped.clamped_counts`).
    """

    plan: object
    ar: Arithmetic
    pivots: np.ndarray
    signs: np.ndarray
    decided: np.ndarray
    det12: np.ndarray
    K: np.ndarray | None = None
    products: np.ndarray | None = None
    clamped: np.ndarray | None = None

    @property
    def trusted(self) -> np.ndarray:
        """Per point: every pivot decided."""
        return np.all(self.decided, axis=1)

    def counts(self) -> np.ndarray:
        """Per point the number of negative eigenvalues of ``K`` (and ``J0`` where the plan
        is ``clamped``): the eigenvalues below the point, ``-1`` where undecided."""
        negative = np.sum(self.signs < 0, axis=1)
        if self.clamped is None:
            return np.where(self.trusted, negative, -1)
        return np.where(self.trusted & (self.clamped >= 0), negative + self.clamped, -1)

    def log_delta(self):
        """``(log|Delta|, arg Delta)`` per point as floats (``arg`` in ``(-pi, pi]``)."""
        ar = self.ar
        la, ph = ar.log_abs_arg(self.pivots)
        la12, ph12 = ar.log_abs_arg(self.det12)
        mult = self.plan.multiplicity
        # (a zero pivot before an infinite one, at a point the rounding put on a
        # sub-structure's eigenvalue, gives nan: no value there, which callers read so)
        with np.errstate(invalid="ignore"):
            logabs = la.sum(axis=1) + (la12 * mult).sum(axis=1) + self.plan.log_constant
            phase = ph.sum(axis=1) + (ph12 * mult).sum(axis=1)
            return logabs, np.angle(np.exp(1j * phase))

    def replaced(self, points, other: Factors) -> Factors:
        """These factors with the rows of ``points`` taken from ``other`` (the same points
        factorised again, at another precision)."""
        def merge(mine, theirs):
            if mine is None:
                return None
            if isinstance(mine, BandRows):
                return mine.replaced(points, theirs)
            out = mine.copy() if mine.dtype == object or theirs.dtype == mine.dtype \
                else mine.astype(np.result_type(mine, theirs))
            out[points] = theirs
            return out
        products = None
        if self.products is not None or other.products is not None:
            products = (self.products.copy() if self.products is not None
                        else np.full(self.pivots.shape[0], None, dtype=object))
            products[points] = (other.products if other.products is not None
                                else np.full(np.size(points), None, dtype=object))
        clamped = None
        if self.clamped is not None or other.clamped is not None:
            clamped = merge(_zero_counts(self.clamped, self.pivots.shape[0]),
                            _zero_counts(other.clamped, np.size(points)))
        return Factors(self.plan, other.ar, merge(self.pivots, other.pivots),
                       merge(self.signs, other.signs), merge(self.decided, other.decided),
                       merge(self.det12, other.det12), merge(self.K, other.K), products,
                       clamped)

    @staticmethod
    def joined(parts) -> Factors:
        """The factors of consecutive batches as one; of ``K`` only the rows of the points
        not trusted (all a pivoted determinant needs: a whole large batch's band would be
        copied at the cost of its elimination)."""
        first = parts[0]

        def cat(field):
            return np.concatenate([getattr(p, field) for p in parts], axis=0)
        rows, offset = {}, 0
        for part in parts:
            if isinstance(part.K, BandRows):        # (a ball batch's: its untrusted rows)
                rows.update((offset + i, row) for i, row in part.K.rows.items())
            elif part.K is not None:
                for i in np.nonzero(~part.trusted)[0]:
                    rows[offset + int(i)] = part.K[i]
            offset += part.pivots.shape[0]
        products = None
        if any(p.products is not None for p in parts):
            products = np.concatenate([p.products if p.products is not None
                                       else np.full(p.pivots.shape[0], None, dtype=object)
                                       for p in parts])
        clamped = None
        if any(p.clamped is not None for p in parts):
            clamped = np.concatenate([_zero_counts(p.clamped, p.pivots.shape[0])
                                      for p in parts])
        return Factors(first.plan, first.ar, cat("pivots"), cat("signs"), cat("decided"),
                       cat("det12"), BandRows(rows), products, clamped)

    def _constant(self):
        return plan_constant(self.plan, self.ar)

    def pivoted_delta(self, points) -> list:
        """``Delta`` at the given point indices from ``K`` with partial pivoting: where a
        pivot of the band elimination is (nearly) zero without ``K`` being singular, as at
        an eigenvalue of a leading sub-structure (:func:`pivoted_deltas`)."""
        return pivoted_deltas(self.plan, self.ar, self.K[points], self.det12[points])

    def delta(self) -> np.ndarray:
        """``Delta`` per point as numbers of the arithmetic (mpmath numbers or balls)."""
        ar, plan = self.ar, self.plan
        with ar:
            const = self._constant()
            out = []
            for p in range(self.pivots.shape[0]):
                if self.products is not None and self.products[p] is not None:
                    product = self.products[p]
                    if hasattr(product, "arb"):         # (a multiword.WordProduct)
                        product = product.arb(ar.flint)
                    out.append(const * product)
                    continue
                value = const
                for v in self.pivots[p]:
                    value = value * v
                for v, m in zip(self.det12[p], plan.multiplicity):
                    value = value * v ** int(m)
                out.append(value)
        return ar.array(out)

    def midpoints(self, ctx) -> tuple:
        """``(values, radii)`` per point: ``Delta`` as a number of the mpmath context
        ``ctx`` (a ball's midpoint; None where the count is undecided) and a float bound
        of its distance from the exact value (0 where the arithmetic gives none; a number
        of ``ctx`` where it is beyond the doubles).

        Where the multi-word factorisation kept its product as words
        (:class:`~symtmm.numeric.multiword.WordProduct`), the midpoint is read from them
        and the plan's constant in ``ctx`` directly: a proof's secant steps read no more,
        and the arb of :meth:`delta` and its conversion cost a third of a small model's
        ball batch. The radius then adds the constant's and the product's rounding in
        ``ctx``.
        """
        import mpmath
        from mpmath.libmp import from_man_exp
        ar = self.ar
        counts = self.counts()
        B = self.pivots.shape[0]
        values: list = [None] * B
        radii = [0.0] * B
        words = [self.products is not None and hasattr(self.products[p], "arb")
                 for p in range(B)]
        fast = [p for p in range(B) if counts[p] >= 0 and words[p]]
        rest = [p for p in range(B) if counts[p] >= 0 and not words[p]]
        if fast:
            with ar:
                const = self._constant()
            c_mid = ctx.mpf(ar.to_mpmath(const))
            c_rad = magnitude_parts(ar.to_mpmath(const.rad())) if ar.rigorous else (0.0, 0)
            c_abs = magnitude_parts(c_mid)
            ulp = (1.0, 2 - ctx.prec)
            for p in fast:
                w = self.products[p]
                mid = ctx.make_mpf(from_man_exp(w.mantissa, w.exponent, ctx.prec, "n"))
                values[p] = value = mid * c_mid
                # |const| r + |mid| rad(const) + the rounding of the product, each from its
                # mantissa and binary exponent (either factor alone may leave the doubles)
                r_m, r_e = math.frexp(w.radius)
                parts = [(c_abs[0] * r_m, c_abs[1] + r_e + w.shift),
                         _times(magnitude_parts(value), ulp)]
                if c_rad[0]:
                    parts.append(_times(magnitude_parts(mid), c_rad))
                radii[p] = math.fsum(_join(t) for t in parts) * (1 + 2.0 ** -50)
                if math.isinf(radii[p]):
                    # (|Delta| beyond the doubles, 1e50000 on a long shear-soft beam: the
                    # bound in ctx, or the secant steps take every value for unresolved)
                    radii[p] = ctx.fsum(ctx.ldexp(m, e) for m, e in parts) * (1 + 2.0 ** -50)
        if rest:
            got = self.delta_at(rest)
            for p, v in zip(rest, got):
                values[p] = ctx.mpf(mpmath.re(ar.to_mpmath(v)))
                radii[p] = float(v.rad()) if ar.rigorous else 0.0
                if math.isinf(radii[p]):
                    radii[p] = ctx.mpf(ar.to_mpmath(v.rad())) * (1 + 2.0 ** -50)
        return values, radii

    def delta_at(self, points) -> list:
        """:meth:`delta` at the given point indices only."""
        sub = Factors(self.plan, self.ar, self.pivots[points], self.signs[points],
                      self.decided[points], self.det12[points], None,
                      None if self.products is None else self.products[points])
        return list(sub.delta())


def _zero_counts(clamped, B: int) -> np.ndarray:
    """``clamped`` of :class:`Factors`, zeros for None (a plan whose pieces have none)."""
    return np.zeros(B, dtype=np.int64) if clamped is None else clamped


def _times(a: tuple, b: tuple) -> tuple:
    """The product of two ``(mantissa, binary exponent)`` magnitudes (:func:`magnitude_parts`)."""
    return a[0] * b[0], a[1] + b[1]


def _join(a: tuple) -> float:
    """``m 2**e`` as a float, rounded up (inf beyond the doubles, the least positive double
    below them)."""
    m, e = a
    if m == 0:
        return 0.0
    try:
        x = math.ldexp(m, e)
    except OverflowError:
        return math.inf
    return math.nextafter(x, math.inf)


#: Pivots of an elimination in Python numbers between checks of the search's time budget.
_CHECK_EVERY = 256

#: Entries of the band (points x freedoms x (half-bandwidth + 1)) one double-precision
#: factorisation works on at once: a whole large batch leaves the caches and costs more
#: per point. Measured, 1000 points per call (benchmarks.models): the 50-level chain (1034
#: freedoms) 943 us per point in one part, 638 us in parts of 2**21 entries (716 at 2**20,
#: 640 at 2**18); a frame of 33 storeys (2575 freedoms) 2.8-3.1 ms in one part, 2.1-2.3 ms
#: at 2**21, 3.1-3.3 ms at 2**18 (parts of 7 points: the per-call overhead).
BAND_ENTRIES = 1 << 21


#: Freedoms beyond which ``K`` is never made dense (``n**2`` numbers): its determinants
#: with partial pivoting are taken within the band (:class:`~symtmm.numeric.band_lu.
#: BandLU`, ``O(n b**2)``). A beam on a stiff foundation in 6561 freedoms spent minutes in
#: one dense decomposition, past the search's time budget. Below it balls keep Arb's
#: dense, preconditioned determinant: interval elimination along the band widens the
#: radii by the dependency of its updates (a 124-freedom beam: 1e-55 to 1e-13, Arb's
#: 1e-52) ...
DENSE_LIMIT = 400
#: ... while mpmath's numbers, which carry no radius, go within the band from this many
#: freedoms per unit of half-bandwidth on: the dense elimination in Python is ``O(n**3)``
#: operations (148 freedoms of half-bandwidth 3: seconds a point, the band's milliseconds).
BANDED_DET = 16


def plan_constant(plan, ar: Arithmetic):
    """The factor ``Delta`` has beyond the pivots and ``det U12`` (the plan's scaling of
    the freedoms), as a number of ``ar``."""
    return ar.exact(plan.pivot_product) * ar.exact(2) ** (-2 * sum(plan.exponent))


def pivots_in_band(n: int, band: int, radii: bool = True) -> bool:
    """Whether a determinant of ``K`` (``n`` freedoms, half-bandwidth ``band``) with
    partial pivoting is taken within the band: beyond :data:`DENSE_LIMIT`, and for
    numbers without radii (``radii`` False: mpmath's) beyond :data:`BANDED_DET` times
    the half-bandwidth too."""
    return n > DENSE_LIMIT or (not radii and n > BANDED_DET * max(band, 1))


def pivoted_deltas(plan, ar: Arithmetic, K, det12) -> list:
    """``Delta`` of each band ``K[p]`` (``(B, n, b + 1)``, its ``det U12`` the row
    ``det12[p]``) by a determinant with partial pivoting: densely (Arb's preconditioned
    determinant for balls, ``O(n**3)`` in C), or within the band
    (:class:`~symtmm.numeric.band_lu.BandLU`, ``O(n b**2)``) where :func:`pivots_in_band`
    says. Balls enclose ``Delta`` over the balls of ``K``, wide ones too (a box of the
    complex plane: :meth:`~symtmm.numeric.evaluator.Evaluator.enclose`)."""
    from .band_lu import BandLU
    from .linalg import det
    n, b = plan.n, plan.band
    banded = pivots_in_band(n, b, radii=ar.rigorous)
    full = None if banded or n == 0 else dense(plan, K)
    out = []
    with ar:
        const = plan_constant(plan, ar)
        for p in range(K.shape[0]):
            if n:
                # (a point cannot be interrupted: a dense determinant of a few hundred
                # freedoms in balls takes half a second, a batch of 32 ran 16 s past a
                # search's budget)
                check_time()
            if n == 0:
                value = ar.exact(1)
            elif banded:
                value = BandLU(K[p], b).det
            elif ar.rigorous:
                value = ar.flint.acb_mat(n, n, [full[p, i, j] for i in range(n)
                                                for j in range(n)]).det()
            else:
                value = det(ar, full[p])
            value = value * const
            for v, m in zip(det12[p], plan.multiplicity):
                value = value * v ** int(m)
            out.append(value)
    return out


def factor(plan, ar: Arithmetic, lam2, lam=None, reverse: bool = False) -> Factors:
    """``LDL^T`` of ``K(lam)`` at the points ``lam2`` ``(B,)`` (``lam`` with dashpots).

    Without pivoting: the pivots are those of the leading principal minors, so
    their signs give the inertia (Sylvester). A pivot whose sign is not trusted is
    replaced by 1 to carry on with the other points; that point's results are
    marked undecided. ``reverse``: the freedoms in the opposite order (another set of
    leading minors, the same inertia and determinant): where a leading minor is nearly
    singular at a point (a sub-structure's eigenvalue), the other end's are not.
    In double precision a batch is factorised in parts of at most :data:`BAND_ENTRIES`,
    the band of a plan of beams (dashpots too) built by the compiled kernel over plain
    doubles; in balls, such a plan is first factorised in compiled multi-word balls, real
    or complex (both :mod:`symtmm.numeric.multiword`). On a ``clamped`` plan (real
    ``lam2``: points on the frequency axis) also ``J0`` per point, which the counts add
    (:attr:`Factors.clamped`).
    """
    fa = _factored(plan, ar, lam2, lam, reverse)
    if plan.clamped and fa.clamped is None:
        from .clamped import clamped_counts
        j0 = clamped_counts(plan, ar, lam2)
        if j0 is not None:
            fa = dataclasses.replace(fa, clamped=j0)
    return fa


def _factored(plan, ar: Arithmetic, lam2, lam=None, reverse: bool = False) -> Factors:
    """:func:`factor` but for ``J0``."""
    if ar is DOUBLE:
        step = max(1, BAND_ENTRIES // max(1, plan.n * plan.width))
        lam2 = np.asarray(lam2)
        if lam2.shape[0] > step:
            parts = [factor(plan, ar, lam2[i:i + step], None if lam is None else lam[i:i + step],
                            reverse) for i in range(0, lam2.shape[0], step)]
            return Factors.joined(parts)
        built = _compiled_band(plan, lam2, lam)
        if built is not None:
            K, det12 = built
            return _ldl(plan, ar, reversed_band(K) if reverse else K, det12, reverse)
    if ar.rigorous:
        from . import multiword  # (it builds on this module)
        if multiword.serves(plan, ar, lam2, lam):
            return multiword.factor(plan, ar, lam2, reverse, lam)
    with ar:
        K, det12 = assemble(plan, ar, lam2, lam)
        if reverse:
            K = reversed_band(K)
        return _ldl(plan, ar, K, det12, reverse)


def reversed_band(K) -> np.ndarray:
    """The upper band ``(B, n, b + 1)`` of ``P K P`` with ``P`` the reversal of the freedoms:
    ``K'[r, r + j] = K[n-1-r-j, n-1-r]``, stored at row ``n-1-r-j``, column ``j``. Trailing
    axes (the words of a compiled ball) are carried along."""
    n, w = K.shape[1:3]
    out = np.zeros_like(K) if K.dtype != object else K.copy()
    for j in range(w):
        rows = np.arange(n - j)
        out[:, rows, j] = K[:, n - 1 - rows - j, j]
    return out


class BandRows:
    """The band ``K`` of :class:`Factors` at some of its points (those not trusted), indexed
    like the whole ``(B, n, b + 1)`` array by arrays of those points."""

    def __init__(self, rows: dict):
        self.rows = rows

    def __getitem__(self, points) -> np.ndarray:
        missing = [int(p) for p in np.atleast_1d(points) if int(p) not in self.rows]
        if missing:
            raise KeyError(f"the band is kept at the untrusted points only, not at {missing}")
        return np.stack([self.rows[int(p)] for p in np.atleast_1d(points)])

    def replaced(self, points, theirs) -> BandRows:
        """These rows with those of ``points`` from ``theirs`` (rows in the order of
        ``points``), where it has them."""
        rows = dict(self.rows)
        for j, p in enumerate(np.atleast_1d(points)):
            rows.pop(int(p), None)
            if isinstance(theirs, BandRows):
                if j in theirs.rows:
                    rows[int(p)] = theirs.rows[j]
            elif theirs is not None:
                rows[int(p)] = theirs[j]
        return BandRows(rows)


def envelope_maps(plan, reverse: bool = False) -> list:
    """Per pivot ``k`` of the band elimination, the update restricted to the envelope:
    ``(J, rows, cols, fi, fj)`` with ``J`` the offsets ``j >= 1`` of the entries of row
    ``k`` that can be nonzero when ``k`` is eliminated, and the update maps of
    :func:`_update_maps` over the pairs of ``J``.

    ``K[k, k + j]`` is zero before pivot ``k`` unless column ``k + j`` has an entry in a
    row ``<= k`` (fill stays inside the envelope: the first entry of each column never
    moves up), so an update skips exact zeros only. A chain's band holds mostly such
    zeros (10 levels: a fifth of the band's pairs are updated); the arithmetics whose
    every operation is a Python call (balls, mpmath) pay for the pairs only.

    Examples
    --------
    Two beams joined by a spring (half-bandwidth 3): only the pivots next to the spring
    reach across the whole band.

    >>> from symtmm.model import Beam, Model, Spring
    >>> from symtmm.numeric.plan import StiffnessPlan
    >>> m = Model((Beam("a", 1, 1, 1, left="clamped"), Beam("b", 1, 1, 1, left="pinned",
    ...            right="pinned")), (Spring("a", "b", "1/2", 10),))
    >>> plan = StiffnessPlan(m, 100.0)
    >>> plan.band, [J.tolist() for J, *_ in envelope_maps(plan)]
    (3, [[1, 2, 3], [1, 2], [1], [1], [1, 2, 3], [1, 2], [1], []])
    """
    cache = plan.__dict__.setdefault("_envelopes", {})
    if reverse in cache:
        return cache[reverse]
    n, w = plan.n, plan.width
    mask = np.zeros((1, n, w), dtype=bool)
    for target, _, _ in plan._triples:
        mask[0, target // w, target % w] = True
    if reverse:
        mask = reversed_band(mask)
    first = np.full(n, n)
    for r, j in zip(*np.nonzero(mask[0])):
        first[r + j] = min(first[r + j], r)
    out = []
    for k in range(n):
        if k % _CHECK_EVERY == 0:
            check_time()        # (tens of thousands of freedoms: seconds)
        J = np.array([j for j in range(1, w) if k + j < n and first[k + j] <= k], dtype=int)
        pairs = [(a, b) for a in range(J.size) for b in range(a, J.size)]
        out.append((J, np.array([J[a] for a, _ in pairs], dtype=int),
                    np.array([J[b] - J[a] for a, b in pairs], dtype=int),
                    np.array([a for a, _ in pairs], dtype=int),
                    np.array([b for _, b in pairs], dtype=int)))
    cache[reverse] = out
    return out


def eliminate(plan, ar: Arithmetic, Kb, n: int, reverse: bool = False) -> None:
    """The band elimination without pivoting, in place on ``Kb`` ``(B, n + w, w)`` (the
    band padded with ``w`` zero rows): afterwards row ``k`` holds ``d_k`` and
    ``d_k L[k + j, k]``. Doubles in the compiled loop where it is built (else its numpy
    twin), Python numbers over the envelope's pairs only."""
    B, _, w = Kb.shape
    if COMPILED and Kb.dtype in (np.float64, np.complex128):
        _band.eliminate(Kb, B, n + w, w, n, Kb.dtype == np.complex128)
    elif Kb.dtype == object:
        exact_zero_possible = not ar.rigorous
        # numbers of Python objects: the envelope's pairs only (exact zeros skipped)
        for k, (J, rows, cols, fi, fj) in enumerate(envelope_maps(plan, reverse)):
            if k % _CHECK_EVERY == 0:
                # (one elimination of tens of thousands of freedoms at thousands of bits
                # takes seconds: the search's time budget is checked along it)
                check_time()
            piv = Kb[:, k, 0]
            if exact_zero_possible:
                zero = np.array([v == 0 for v in piv], dtype=bool)
                if zero.any():              # (mpmath refuses to divide by an exact 0)
                    piv = piv.copy()
                    piv[zero] = ar.exact(1)
            if J.size:
                row = Kb[:, k, J]
                f = row / piv[:, None]
                Kb[:, k + rows, cols] = Kb[:, k + rows, cols] - f[:, fi] * row[:, fj]
    else:
        # the numpy twin of the C loop (the same operations, the same factors)
        rows, cols, fi, fj = _update_maps(w)
        for k in range(n):
            piv = Kb[:, k, 0]
            if w > 1:
                row = Kb[:, k, 1:]
                f = row * (1.0 / piv)[:, None]
                Kb[:, k + rows, cols] = Kb[:, k + rows, cols] - f[:, fi] * row[:, fj]


def _compiled_band(plan, lam2, lam):
    """``(K, det U12)`` of a double batch built by the compiled kernel over plain doubles
    (numpy's closed forms at the points beyond its series' reach), or None where it does
    not serve the plan (:func:`symtmm.numeric.multiword.serves_double`)."""
    from . import multiword  # (it builds on this module)
    built = multiword.double_band(plan, lam2, lam) \
        if multiword.serves_double(plan, lam2, lam) else None
    if built is None:
        return None
    K, det12, ok = built
    if not ok.all():
        # (beyond the compiled series' reach, or not finite: numpy's closed forms)
        bad = np.nonzero(~ok)[0]
        K[bad], det12[bad] = assemble(plan, DOUBLE, lam2[bad],
                                      None if lam is None else np.asarray(lam)[bad])
    return K, det12


def summary(plan, lam2, lam=None):
    """``(log|Delta|, arg Delta, counts)`` of a double-precision batch, as
    :meth:`Factors.log_delta` and :meth:`Factors.counts` give them, in one compiled pass
    after the band's (``-1`` where a count is undecided; 0 for complex ``K`` where every
    pivot is decided): what the searches read of most batches, without the forty numpy
    calls of the factors' bookkeeping (two thirds of a batch of example 1, 15 points).
    None where the compiled kernel does not serve the plan (the caller takes
    :func:`factor`).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.numeric.plan import StiffnessPlan
    >>> plan = StiffnessPlan(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 1e4)
    >>> lam2 = -np.array([5.0, 12.0, 50.0]) ** 2      # roots (n pi)**2: 9.87, 39.5, 88.8
    >>> logabs, phase, counts = summary(plan, lam2)
    >>> fa = factor(plan, DOUBLE, lam2)
    >>> counts.tolist(), fa.counts().tolist()
    ([0, 1, 2], [0, 1, 2])
    >>> bool(np.allclose(logabs, fa.log_delta()[0], rtol=1e-13))
    True
    """
    if not COMPILED:
        return None
    lam2 = np.asarray(lam2)
    from . import multiword  # (it builds on this module)
    fused = multiword.double_summary(plan, lam2, lam) \
        if multiword.serves_double(plan, lam2, lam) else None
    if fused is None:
        return None         # (the compiled kernel does not build this plan's band)
    # a point at a time in the compiled kernel; the points beyond its series' reach (or
    # not finite) the banded way, with numpy's closed forms
    logabs, phase, counts, ok = fused
    if not ok.all():
        bad = np.nonzero(~ok)[0]
        rest = _banded_summary(plan, lam2[bad], None if lam is None else np.asarray(lam)[bad])
        if rest is None:
            return None
        logabs[bad], phase[bad], counts[bad] = rest
    if plan.clamped:
        from .clamped import clamped_counts
        j0 = clamped_counts(plan, DOUBLE, lam2)
        if j0 is not None:
            counts = np.where((counts >= 0) & (j0 >= 0), counts + j0, -1)
    return logabs, phase, counts


def _banded_summary(plan, lam2, lam=None):
    """:func:`summary` by a batch of bands: built (the compiled kernel's, or numpy's closed
    forms at the points beyond its reach), factorised and read by the compiled loops."""
    step = max(1, BAND_ENTRIES // max(1, plan.n * plan.width))
    if lam2.shape[0] > step:
        parts = [_banded_summary(plan, lam2[i:i + step],
                                 None if lam is None else lam[i:i + step])
                 for i in range(0, lam2.shape[0], step)]
        return None if any(p is None for p in parts) else \
            tuple(np.concatenate(x) for x in zip(*parts))
    built = _compiled_band(plan, lam2, lam)
    if built is None:
        return None
    K, det12 = built
    B, n, w = K.shape
    is_complex = K.dtype == np.complex128
    K = np.ascontiguousarray(K)
    Kb = np.concatenate([K, np.zeros((B, w, w), dtype=K.dtype)], axis=1)
    logabs, phase, counts = np.empty(B), np.empty(B), np.empty(B, dtype=np.int64)
    _band.eliminate(Kb, B, n + w, w, n, is_complex)
    _band.summary(Kb, K, np.ascontiguousarray(det12, dtype=K.dtype),
                  np.ascontiguousarray(plan.multiplicity, dtype=np.int64), logabs, phase,
                  counts, B, n + w, w, n, det12.shape[1], DOUBLE.TRUST, DOUBLE.growth_limit,
                  float(plan.log_constant), is_complex)
    return logabs, phase, counts


def _ldl(plan, ar: Arithmetic, K, det12, reverse: bool = False) -> Factors:
    B, n, w = K.shape
    if n == 0:
        return Factors(plan, ar, ar.zeros((B, 0), like=K), np.zeros((B, 0), dtype=np.int8),
                       np.ones((B, 0), dtype=bool), det12)
    # in place on a copy padded with zero rows: afterwards row k holds d_k and d_k L[k+j, k]
    Kb = np.concatenate([K, ar.zeros((B, w, w), like=K)], axis=1)
    compiled = COMPILED and Kb.dtype in (np.float64, np.complex128)
    with np.errstate(all="ignore"):
        eliminate(plan, ar, Kb, n, reverse)
        pivots = Kb[:, :n, 0]
        scale = None
        if ar.needs_scale and compiled:
            scale = np.empty((B, n))
            _band.bounds(Kb, np.ascontiguousarray(K), scale, B, n + w, w, n,
                         Kb.dtype == np.complex128)
        elif ar.needs_scale:
            # the diagonal of |L||D||L^T| bounds what rounding can do to each pivot (balls
            # carry their own bound: a float per entry of the band would cost more than
            # their whole elimination's bookkeeping)
            # (each pivot inverted once, each row's terms added from the farthest pivot to
            # the nearest: the order of _band_core.h's band_pivot_scales, the same bits)
            scale = ar.upper(K[:, :, 0]).astype(float)
            inv = 1.0 / np.maximum(ar.upper(pivots).astype(float), 1e-300)
            for j in range(min(w, n) - 1, 0, -1):
                r = ar.upper(Kb[:, :n - j, j]).astype(float)
                scale[:, j:] += r * r * inv[:, :n - j]
    signs, decided = ar.decide(pivots, scale, n)
    # Each decided pivot exceeds what the backward error E (|E| <= c u |L||D||L^T|) can do to
    # it; the inertia of K + E is K's only while E stays below K's smallest eigenvalue,
    # which a tiny pivot followed by a huge one (a nearly singular leading minor) breaks
    # without any single pivot looking small. Such growth of |L||D||L^T| beyond the
    # diagonal of K leaves the point undecided (balls need no such rule).
    if not ar.rigorous:
        base = np.max(ar.upper(K[:, :, 0]).astype(float), axis=1, initial=1e-300)
        decided = decided & (scale <= ar.growth_limit * base[:, None])
    # a pivot after an undecided one is meaningless: the point is undecided from there on
    decided = np.logical_and.accumulate(decided, axis=1)
    return Factors(plan, ar, pivots, signs, decided, det12, K)


def dense(plan, K) -> np.ndarray:
    """The symmetric ``(B, n, n)`` matrices of a band ``K`` ``(B, n, b + 1)`` (for checks).

    Examples
    --------
    >>> dense(None, np.array([[[1.0, 2.0], [3.0, 0.0]]]))[0].tolist()
    [[1.0, 2.0], [2.0, 3.0]]
    """
    B, n, w = K.shape
    rows, cols = _band_places(n, w)
    out = np.zeros((B, n, n), dtype=K.dtype)
    # (every entry of the band in one indexed copy each way; entry by entry, the copies
    # cost a mode shape's tracking a tenth of its time)
    values = K[:, rows, cols]
    out[:, rows, rows + cols] = values
    out[:, rows + cols, rows] = values
    return out


@functools.lru_cache(maxsize=64)
def _band_places(n: int, w: int) -> tuple:
    """``(rows, offsets)`` of every entry inside an ``(n, w)`` upper band."""
    r, j = np.nonzero(np.arange(n)[:, None] + np.arange(w)[None, :] < n)
    return r, j
