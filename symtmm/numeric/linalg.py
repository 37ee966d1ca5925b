"""Small dense linear algebra on arrays of any arithmetic (:mod:`symtmm.numeric.arith`).

Written once for ``object`` arrays of mpmath numbers or balls and for numpy's
own ``float64``/``complex128`` arrays: the operators and numpy's indexing do
the work, the arithmetic supplies what differs (its precision, square roots).

* :func:`det`: Gaussian elimination with partial pivoting, the pivot chosen by
  the largest upper bound of the magnitude (for balls, their midpoints' size: a
  ball's radius says nothing about which row is best);
* :func:`lu` and :func:`lu_solve`: ``P A = L U`` with partial pivoting, a
  pivot below ``eps |A|`` replaced by that guard (the classical guard of
  inverse iteration, where ``A`` is singular on purpose);
* :func:`null_space`: the near-null space of a square matrix by block inverse
  iteration;
* :func:`orthonormal`: modified Gram–Schmidt, twice;
* :func:`cholesky` and :func:`lower_inverse`: ``G = L L^T`` of a symmetric
  positive definite matrix and ``L^-1``.

Examples
--------
>>> import numpy as np
>>> from symtmm.numeric.arith import MP
>>> ar = MP(100)
>>> M = np.array([[ar.number(0), ar.number(2)], [ar.number(3), ar.number(4)]], dtype=object)
>>> print(det(ar, M))
-6.0
>>> R = np.array([[ar.number(1), ar.number(2)], [ar.number(2), ar.number(4)]], dtype=object)
>>> v = null_space(ar, R, 1)[:, 0]                 # R v = 0: v = (2, -1)/sqrt(5)
>>> print(ar.ctx.nstr(v[0] / v[1], 20), abs(R @ v).max() < 1e-28)
-2.0 True
"""

from __future__ import annotations

import math
import random

import mpmath
import numpy as np
import sympy as sp

from ..errors import ComputationError
from . import arb_null
from .arith import Arithmetic, ball_midpoints
from .sparse_lu import sparse_factors

__all__ = ["det", "lu", "lu_solve", "solver", "null_space", "separation_ratio", "orthonormal",
           "cholesky", "lower_inverse"]


def det(ar: Arithmetic, M):
    """The determinant of one square matrix (an object or complex array) in ``ar``.

    An empty matrix has determinant 1; a matrix whose every candidate pivot is an
    exact zero has determinant 0. Pivots are chosen by size at any magnitude; where
    an entry has no value (NaN, or a ball that lost it) the determinant has none.
    """
    n = M.shape[0]
    if n == 0:
        return ar.exact(1)
    if M.dtype != object:
        return np.linalg.det(M)
    A = M.copy()
    value = ar.exact(1)
    for k in range(n):
        size = _pivot_sizes(ar, A[k:, k])
        lost = np.isnan(size)
        if lost.any():
            # an entry without a value (a ball divided by one that holds 0): the
            # determinant has none either, never the exact 0 of the rule below
            return value * A[k + int(np.argmax(lost)), k]
        p = k + int(np.argmax(size))
        if size[p - k] == -math.inf:
            return 0 * value
        if p != k:
            A[[k, p], k:] = A[[p, k], k:]
            value = -value
        pivot = A[k, k]
        value = value * pivot
        if k + 1 < n:
            f = A[k + 1:, k] / pivot
            A[k + 1:, k + 1:] = A[k + 1:, k + 1:] - f[:, None] * A[k, k + 1:][None, :]
    return value


# -- helpers ---------------------------------------------------------------------------------
def _pivot_sizes(ar: Arithmetic, column) -> np.ndarray:
    """Sizes of a column's entries to choose a pivot by, ``-inf`` for an exact zero (a
    ball that merely holds 0 is a candidate: its determinant then holds 0 too): ``|x|``
    as floats, or where an entry leaves the doubles' range (an inf, or a nonzero entry
    rounded to 0: a model with ``N = 7e10`` beside ``EI = 0.001``) ``log2 |x|``."""
    size = ar.upper(column)
    zero = np.array([_is_zero(v) for v in column], dtype=bool)
    if np.isfinite(size).all() and (size[~zero] > 0).all():
        return np.where(zero, -math.inf, size)
    mag = getattr(getattr(ar, "ctx", None), "mag", mpmath.mp.mag)
    return np.array([-math.inf if z else _log2_abs(v, mag) for v, z in zip(column, zero)])


def _is_zero(v) -> bool:
    """Whether ``v`` is exactly zero (a ball: of radius 0 too)."""
    test = getattr(v, "is_zero", None)
    return bool(test()) if test is not None else v == 0


def _log2_abs(v, mag) -> float:
    """About ``log2 |v|`` (within one) of a number of any size, a ball's upper bound's;
    NaN where ``v`` is not finite."""
    if hasattr(v, "mid"):
        return float(abs(v).upper().log()) / math.log(2) if v.is_finite() else math.nan
    return float(mag(v)) if mpmath.isfinite(v) else math.nan


def _eps(ar: Arithmetic):
    """The unit roundoff ``2**-prec`` as a number of ``ar``."""
    return ar.exact(sp.Integer(2) ** -ar.prec)


def _sqrt(ar: Arithmetic, x):
    """The square root of one nonnegative number of ``ar``."""
    return ar.sqrt(np.array([x], dtype=object if not isinstance(x, float) else float))[0]


def _conj(ar: Arithmetic, x):
    """Complex conjugates (the array itself when it is real)."""
    if not ar.is_complex(x):
        return x
    if x.dtype != object:
        return np.conj(x)
    return np.frompyfunc(lambda v: v.conjugate(), 1, 1)(x)


def _norm2(v):
    """``sum |v_i|**2`` of a vector (a number of the vector's arithmetic)."""
    a = np.abs(v)
    return np.sum(a * a)


# -- LU ----------------------------------------------------------------------------------------
def lu(ar: Arithmetic, A):
    """``P A = L U`` with partial pivoting: ``(LU, perm)``, ``L`` unit lower below the diagonal.

    A pivot smaller than ``eps max|A|`` (the matrix is singular to working
    precision, as at an exact eigenvalue) is replaced by that guard with its
    phase, so that solves stay finite: what inverse iteration needs.
    """
    A = np.array(A, copy=True)
    n = A.shape[0]
    perm = np.arange(n)
    eps = _eps(ar)
    top = np.max(np.abs(A)) if A.size else 0
    guard = top * eps if top != 0 else eps
    for k in range(n):
        p = k + int(np.argmax(np.abs(A[k:, k])))
        if p != k:
            A[[k, p]] = A[[p, k]]
            perm[[k, p]] = perm[[p, k]]
        pivot = A[k, k]
        if abs(pivot) < guard:
            pivot = A[k, k] = guard if pivot == 0 else guard * (pivot / abs(pivot))
        if k + 1 < n:
            f = A[k + 1:, k] / pivot
            A[k + 1:, k] = f
            A[k + 1:, k + 1:] = A[k + 1:, k + 1:] - np.outer(f, A[k, k + 1:])
    return A, perm


def lu_solve(ar: Arithmetic, factors, B):
    """``A^-1 B`` from :func:`lu`'s ``factors`` for the columns of ``B`` (``n x m``)."""
    LU, perm = factors
    n = LU.shape[0]
    # (a real B against a complex LU, as in a damped double-precision walk, solves complex)
    y = np.array(B, copy=True, dtype=np.result_type(LU, np.asarray(B)))[perm]
    for i in range(1, n):
        y[i] = y[i] - LU[i, :i] @ y[:i]
    for i in range(n - 1, -1, -1):
        if i + 1 < n:
            y[i] = y[i] - LU[i, i + 1:] @ y[i + 1:]
        y[i] = y[i] / LU[i, i]
    return y


# -- orthonormal bases ---------------------------------------------------------------------------
def orthonormal(ar: Arithmetic, V, complete: bool = False):
    """Orthonormal columns spanning those of ``V`` (``n x m``), by modified Gram–Schmidt, twice.

    A column that depends on the previous ones (what remains of it after the
    projections is below ``2**(-prec/2)`` of its size) gives None; with
    ``complete``, it is replaced by the coordinate axis farthest from the span
    so far (as a Householder QR would), so the result always has ``m`` columns.

    Examples
    --------
    >>> import numpy as np
    >>> from symtmm.numeric.arith import DOUBLE
    >>> Q = orthonormal(DOUBLE, np.array([[3.0, 1.0], [4.0, 2.0]]))
    >>> np.round(Q.T @ Q, 12) + 0.0
    array([[1., 0.],
           [0., 1.]])
    >>> orthonormal(DOUBLE, np.array([[1.0, 2.0], [1.0, 2.0]])) is None
    True
    """
    n, m = V.shape
    tol = ar.exact(sp.Integer(2) ** -(ar.prec // 2))
    cols: list = []

    def project(v):
        for _ in range(2):
            for q in cols:
                v = v - q * (_conj(ar, q) @ v)
        return v

    for c in range(m):
        v = V[:, c]
        scale = np.max(np.abs(v)) if n else 0
        norm = size = 0
        if scale != 0:
            v = v / scale
            size = _sqrt(ar, _norm2(v))
            v = project(v)
            norm = _sqrt(ar, _norm2(v))
        if scale == 0 or not norm > size * tol:
            if not complete:
                return None
            best = None
            for i in range(n):
                e = np.zeros(n, dtype=V.dtype) if V.dtype != object else ar.zeros(n, like=V)
                e[i] = ar.exact(1) if V.dtype == object else 1
                e = project(e)
                size_e = _norm2(e)
                if best is None or size_e > best[0]:
                    best = (size_e, e)
            v, norm = best[1], _sqrt(ar, best[0])
        cols.append(v / norm)
    out = np.empty((n, m), dtype=V.dtype if V.dtype == object else np.result_type(V, float))
    for c, q in enumerate(cols):
        out[:, c] = q
    return out


def null_space(ar: Arithmetic, R, mult: int, separation: bool = False):
    """Orthonormal columns spanning the near-null space of the square ``R``: ``mult`` of them.

    Block inverse iteration on ``R^H R``: ``X <- orth(R^-1 R^-H X)`` twice from fixed
    pseudo-random columns, through one :func:`lu` (:func:`solver`). Near an eigenvalue
    the ``mult`` smallest singular values of ``R`` dominate ``(R^H R)^-1 = V S^-2 V^H``,
    so this spans the space of their right singular vectors, as the singular value
    decomposition would, at the cost of one LU factorisation; backward stable like the
    SVD, so the vectors are as accurate as the eigenvalue. (``R^-1`` alone maps the
    left null vectors to the right ones, and its square can turn them away: a rod's
    ``[[0, 1], [t, 0]]``, whose right null vector is ``e1`` and left one ``e2``, has
    ``R^-2 = I / t``.) Where the iteration collapses (fewer than ``mult`` independent
    directions), a private mpmath context's SVD decides.

    With ``separation``, returns ``(X, ratio)``: also how well the space stands apart
    from the next direction, ``ratio`` about ``sigma_mult / sigma_(mult+1)`` of ``R``
    (:func:`separation_ratio`).
    """
    n = R.shape[0]
    if n == 0:
        return ar.zeros((0, mult))
    if mult > n:
        raise ComputationError(f"multiplicity {mult} exceeds the size {n} of R")
    # (in Arb's matrices where python-flint is installed: for balls always, for mpmath
    # numbers from the size where converting them costs less than Python's solves)
    if (ar.name == "ball" or n >= ARB_SOLVE_SIZE) and arb_null.applies(ar, R):
        got = arb_null.null_space(ar, R, mult, separation)
        if got is not None:
            return got
    if ar.name == "ball":
        return _null_space_of_midpoints(ar, R, mult, separation)
    solve, adjoint = _sparse_solvers(ar, R) or (solver(ar, R), solver(ar, R, adjoint=True))
    rng = random.Random(20240607)          # fixed: the shapes are reproducible
    X = ar.array([ar.exact(sp.Rational(rng.randrange(-2**20, 2**20), 2**20))
                  for _ in range(n * mult)], (n, mult))
    for _ in range(2):
        X = orthonormal(ar, solve(adjoint(X)))
        if X is None:
            X = _svd_null_space(ar, R, mult)
            break
    if separation:
        return X, separation_ratio(ar, R, X, (solve, adjoint), rng)
    return X


def _null_space_of_midpoints(ar: Arithmetic, R, mult: int, separation: bool):
    """:func:`null_space` of balls' midpoints in mpmath at their precision, the result as
    exact balls (where Arb's matrices broke down: an exact zero pivot, a collapse)."""
    from .arith import MP
    mp = MP(ar.prec)
    with mp:
        got = null_space(mp, ball_midpoints(mp, R), mult, separation)
    X = got[0] if separation else got
    X = np.frompyfunc(ar.number, 1, 1)(X)
    return (X, got[1]) if separation else X


def _sparse_solvers(ar: Arithmetic, R):
    """``(B -> R^-1 B, B -> R^-H B)`` by one sparse LU where ``R`` is a large and nearly
    empty matrix of mpmath numbers (beams in series: :func:`symtmm.numeric.sparse_lu.
    sparse_factors`, as :mod:`symtmm.numeric.arb_null` takes it in Arb), or None."""
    n = R.shape[0]
    if getattr(ar, "name", None) != "mp" or R.dtype != object:
        return None
    lu = sparse_factors(n, lambda i, j: R[i, j], ar.prec)
    if lu is None:
        return None

    def by_columns(solve):
        def apply(B):
            B = np.asarray(B)
            columns = B.reshape(n, -1)
            out = np.empty(columns.shape, dtype=object)
            for c in range(columns.shape[1]):
                out[:, c] = solve(list(columns[:, c]))
            return out.reshape(B.shape)
        return apply
    return by_columns(lu.solve), by_columns(lu.solve_adjoint)


#: From this size of an mpmath matrix on, :func:`null_space` hands it to Arb's matrices
#: where python-flint is installed (:mod:`symtmm.numeric.arb_null`; below it, converting
#: the entries costs what it saves).
ARB_SOLVE_SIZE = 16


def solver(ar: Arithmetic, A, adjoint: bool = False):
    """``B -> A^-1 B`` (with ``adjoint``, ``B -> A^-H B``) for the columns of ``B``:
    :func:`lu` once, then :func:`lu_solve` (or :func:`lu_solve_adjoint`). (Large matrices
    take Arb's solves in :mod:`symtmm.numeric.arb_null` before they come here.)"""
    factors: list = []

    def solve(B):
        if not factors:
            factors.append(lu(ar, A))
        return (lu_solve_adjoint if adjoint else lu_solve)(ar, factors[0], B)
    return solve


def lu_solve_adjoint(ar: Arithmetic, factors, B):
    """``A^-H B`` from :func:`lu`'s factors of ``A`` (``P A = L U``: ``A^H = U^H L^H P``)."""
    LU, perm = factors
    n = LU.shape[0]
    conj = _conj(ar, LU)
    z = np.array(B, copy=True, dtype=np.result_type(LU, np.asarray(B)))
    for i in range(n):                      # U^H z = B: lower triangular
        if i:
            z[i] = z[i] - conj[:i, i] @ z[:i]
        z[i] = z[i] / conj[i, i]
    for i in range(n - 2, -1, -1):          # L^H w = z: upper, unit diagonal
        z[i] = z[i] - conj[i + 1:, i] @ z[i + 1:]
    out = np.empty_like(z)
    out[perm] = z                           # P x = w
    return out


def separation_ratio(ar: Arithmetic, R, X, solvers=None, rng=None) -> float:
    """About ``sigma_m / sigma_(m+1)`` of ``R``: how far the near-null space ``X`` (``m``
    orthonormal columns of right singular vectors) stands apart from the next direction.

    ``sigma_m`` is read as the largest residual ``|R x|`` of the columns; ``sigma_(m+1)``
    as ``|(R^H R)^-1|**(-1/2)`` on the complement of ``X``, by power iteration there
    (``solvers``: the ``(R^-1, R^-H)`` of :func:`solver`, made if not given). At an
    eigenvalue ``lam`` estimated to within ``delta`` of its root, with the next root a
    distance ``gap`` away, the ratio is about ``delta / gap``: the share of the
    neighbour's vector that the null space takes in (0 where ``X`` fills the space). A
    float; 0.0 below the double range.

    Examples
    --------
    >>> import numpy as np
    >>> from symtmm.numeric.arith import MP
    >>> ar = MP(200)
    >>> R = np.diag([ar.number(x) for x in ("1", "1e-3", "1e-30")])
    >>> X = null_space(ar, R, 1)
    >>> print(f"{separation_ratio(ar, R, X):.3g}")
    1e-27
    >>> rod = np.array([[ar.number(0), ar.number(1)], [ar.number("1e-25"), ar.number(0)]])
    >>> X = null_space(ar, rod, 1)                       # e1: rod @ e1 = (0, 1e-25)
    >>> print(f"{separation_ratio(ar, rod, X):.3g}", abs(float(X[1, 0])) < 1e-50)
    1e-25 True
    """
    n, m = X.shape
    if m >= n:
        return 0.0
    solve, adjoint = solvers or (solver(ar, R), solver(ar, R, adjoint=True))
    rng = rng or random.Random(20240607)
    residual = max(_sqrt(ar, _norm2(R @ X[:, c])) for c in range(m))
    Xh = _conj(ar, X).T

    def deflate(v):
        for _ in range(2):
            v = v - X @ (Xh @ v)
        return v

    x = deflate(ar.array([ar.exact(sp.Rational(rng.randrange(-2**20, 2**20), 2**20))
                          for _ in range(n)]))
    growth = 0
    for _ in range(3):
        size = _sqrt(ar, _norm2(x))
        if not size > 0:
            return 0.0
        x = deflate(solve(adjoint((x / size)[:, None]))[:, 0])
        growth = _sqrt(ar, _norm2(x))
    # growth is |(R^H R)^-1| on the complement: 1 / sigma_(m+1)**2
    return float(residual * _sqrt(ar, growth)) if growth > 0 else 0.0


def _svd_null_space(ar: Arithmetic, R, mult: int):
    """The right singular vectors of the ``mult`` smallest singular values (columns)."""
    ctx = getattr(ar, "ctx", None)
    if ctx is None:
        raise ComputationError("the null space of R is lost at this precision")
    complex_ = ar.is_complex(R)
    _, _, V = (ctx.svd_c if complex_ else ctx.svd_r)(ctx.matrix(R.tolist()))
    n = R.shape[0]
    # singular values come sorted by decreasing size; R = U S V, so R V^H = U S
    out = ar.zeros((n, mult), like=R)
    for c, row in enumerate(range(n - mult, n)):
        for j in range(n):
            out[j, c] = ctx.conj(V[row, j]) if complex_ else V[row, j]
    return out


# -- symmetric positive definite ---------------------------------------------------------------
def cholesky(ar: Arithmetic, G):
    """Lower triangular ``L`` with ``G = L L^T`` (``G`` real symmetric positive definite).

    Raises
    ------
    ComputationError
        If a pivot is not positive (``G`` is singular or indefinite to working precision).
    """
    n = G.shape[0]
    L = ar.zeros((n, n), like=G) if G.dtype == object else np.zeros((n, n))
    for j in range(n):
        d = G[j, j] - (L[j, :j] @ L[j, :j] if j else 0)
        if not d > 0:
            raise ComputationError("the Gram matrix is not positive definite")
        L[j, j] = _sqrt(ar, d)
        for i in range(j + 1, n):
            L[i, j] = (G[i, j] - (L[i, :j] @ L[j, :j] if j else 0)) / L[j, j]
    return L


def lower_inverse(ar: Arithmetic, L):
    """``L^-1`` of a lower triangular ``L`` (by forward substitution)."""
    n = L.shape[0]
    inv = ar.zeros((n, n), like=L) if L.dtype == object else np.zeros((n, n), L.dtype)
    one = ar.exact(1) if L.dtype == object else 1.0
    for c in range(n):
        for i in range(c, n):
            acc = (one if i == c else 0) - (L[i, c:i] @ inv[c:i, c] if i > c else 0)
            inv[i, c] = acc / L[i, i]
    return inv
