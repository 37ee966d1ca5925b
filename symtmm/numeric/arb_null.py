"""The near-null space of ``R`` in Arb's matrices: one inverse, products in C.

:func:`symtmm.numeric.linalg.null_space` does block inverse iteration on
``R^H R`` and estimates how far the space stands apart from the next direction
(:func:`~symtmm.numeric.linalg.separation_ratio`): ten solves with ``R`` or
``R^H`` a shape. In object arrays of mpmath numbers each solve is Python's;
here, where python-flint is installed, the same iteration runs on Arb
matrices (``arb_mat``/``acb_mat``) at the arithmetic's precision:

* ``R^-1`` once, by Arb's approximate LU solve against the identity (midpoints,
  no error bounds: the floating-point elimination mpmath would do, in C), and
  every solve after it a product with ``R^-1`` or its adjoint. Near an
  eigenvalue each column of the computed inverse is the exact inverse of a
  matrix within rounding of ``R``: its direction is the null vector's to
  ``eps |R| / sigma_(m+1)``, as the LU solves' are;
* the products, the projections and the norms in Arb, only the result
  converted back.

The 20-span beam's ``R`` is 154 x 154 at 250 bits: the conversions to and
from mpmath alone took 0.2 s of each shape, the ten solves 0.1 s more.

:func:`null_space` returns None where it does not apply (no python-flint,
an exact zero pivot, columns that collapse); the caller then does it the
mpmath way.
"""

from __future__ import annotations

import math
import random

import numpy as np

from .arith import FLINT_LOCK, Arithmetic, _arb_exact, ball_midpoints

__all__ = ["null_space", "applies"]

#: The pseudo-random start of the iteration, as in :func:`symtmm.numeric.linalg.null_space`.
SEED = 20240607


def applies(ar: Arithmetic, R) -> bool:
    """Whether :func:`null_space` can take ``R`` (an ``object`` array of ``ar``'s numbers):
    Arb balls, or mpmath numbers where python-flint is installed."""
    if getattr(R, "dtype", None) != object or getattr(ar, "name", None) not in ("mp", "ball"):
        return False
    try:
        import flint  # noqa: F401
    except ImportError:
        return False
    return True


def null_space(ar: Arithmetic, R, mult: int, separation: bool = False):
    """``X`` (or ``(X, ratio)`` with ``separation``) as
    :func:`symtmm.numeric.linalg.null_space` returns it, numbers of ``ar``; None where the
    iteration breaks down here (see the module).

    Examples
    --------
    >>> from symtmm.numeric.arith import MP
    >>> ar = MP(200)
    >>> R = np.diag([ar.number(x) for x in ("1", "1e-3", "1e-30")])
    >>> X, ratio = null_space(ar, R, 1, separation=True)
    >>> abs(float(X[2, 0])), f"{ratio:.3g}"
    (1.0, '1e-27')
    """
    import flint

    n = R.shape[0]
    complex_ = ar.is_complex(R)           # (kernel arrays hold one kind of number)
    mat = flint.acb_mat if complex_ else flint.arb_mat
    rng = random.Random(SEED)
    with FLINT_LOCK, flint.ctx.workprec(ar.prec):
        # (balls as they are: a 154 x 154 R of the 20-span beam, 8 ms a shape to convert)
        entries = list(R.flat) if ar.name == "ball" else \
            [_to_arb(v, flint, complex_) for v in R.flat]
        M = mat(n, n, entries).mid()
        solves = _sparse_solves(flint, mat, M, n, ar.prec) or _dense_solves(mat, M, n, complex_)
        X = mat(n, mult, [_start(rng, flint) for _ in range(n * mult)])
        for _ in range(2):
            # (an exact zero pivot leaves NaN in the inverse, and so in every column)
            Y = solves[0](solves[1](X))
            X = _orthonormal(mat, Y, ar.prec, complex_) if _finite(Y, complex_) else None
            if X is None:
                return None
        ratio = _separation(flint, mat, M, solves, X, rng, complex_) if separation else None
        out = _back(ar, X, complex_)
    return (out, ratio) if separation else out


def _dense_solves(mat, M, n: int, complex_) -> tuple:
    """``(X -> R^-1 X, X -> R^-H X)`` from ``R^-1`` once, by Arb's approximate solve against
    the identity; every solve after it a product with it or its adjoint."""
    identity = mat(n, n, [1 if i == j else 0 for i in range(n) for j in range(n)])
    inverse = M.solve(identity, nonstop=True, algorithm="approx").mid()
    adjoint = _adjoint(inverse, complex_)
    return (lambda X: (inverse * X).mid()), (lambda X: (adjoint * X).mid())


def _sparse_solves(flint, mat, M, n: int, prec: int):
    """The solves of :func:`_dense_solves` by a sparse LU where ``M`` is large and nearly
    empty (beams in series: :func:`~symtmm.numeric.sparse_lu.sparse_factors`), or None."""
    from .sparse_lu import sparse_factors
    entries = M.entries()
    lu = sparse_factors(n, lambda i, j: entries[i * n + j], prec)
    if lu is None:
        return None

    def by_columns(solve):
        def apply(X):
            m = X.ncols()
            cols = [solve([X[i, c] for i in range(n)]) for c in range(m)]
            return mat(n, m, [cols[c][i] for i in range(n) for c in range(m)]).mid()
        return apply
    return by_columns(lu.solve), by_columns(lu.solve_adjoint)


def _to_arb(v, flint, complex_):
    """An entry as an Arb number (a ball as it is: only its midpoint is used)."""
    if isinstance(v, (flint.arb, flint.acb)):
        return flint.acb(v) if complex_ and isinstance(v, flint.arb) else v
    if complex_:
        return flint.acb(_arb_exact(v.real, flint), _arb_exact(v.imag, flint))
    return _arb_exact(v, flint)


def _start(rng, flint):
    """A dyadic in ``[-1, 1)``, exact: the same sequence as the mpmath iteration's."""
    return flint.arb(rng.randrange(-2**20, 2**20)) / (1 << 20)


def _finite(A, complex_) -> bool:
    parts = [p for z in A.entries() for p in (z.real, z.imag)] if complex_ else A.entries()
    return all(p.is_finite() for p in parts)


def _adjoint(A, complex_):
    return A.conjugate().transpose() if complex_ else A.transpose()


def _norm(v, complex_):
    """``|v|`` of a column matrix, the midpoint of its ball."""
    total = sum((abs(z) ** 2 for z in v.entries()), 0 * v.entries()[0].real) if complex_ \
        else sum((z * z for z in v.entries()), 0 * v.entries()[0])
    return total.mid().sqrt().mid()


def _column(mat, X, c):
    n = X.nrows()
    return mat(n, 1, [X[i, c] for i in range(n)])


def _orthonormal(mat, V, prec: int, complex_):
    """Orthonormal columns spanning ``V``'s, by modified Gram–Schmidt twice; None where a
    column depends on the previous ones (below ``2**(-prec/2)`` of its size), as
    :func:`symtmm.numeric.linalg.orthonormal` decides."""
    n, m = V.nrows(), V.ncols()
    tol = 2.0 ** -(prec // 2)
    cols: list = []
    for c in range(m):
        v = _column(mat, V, c)
        scale = max((abs(z).mid() for z in v.entries()), default=0)
        if not scale > 0:
            return None
        v = (v * (1 / scale)).mid()
        size = _norm(v, complex_)
        for _ in range(2):
            for q in cols:
                v = (v - q * (_adjoint(q, complex_) * v)[0, 0]).mid()
        norm = _norm(v, complex_)
        if not norm > size * tol:
            return None
        cols.append((v * (1 / norm)).mid())
    return mat(n, m, [cols[c][i, 0] for i in range(n) for c in range(m)])


def _separation(flint, mat, M, solves, X, rng, complex_) -> float:
    """About ``sigma_m / sigma_(m+1)`` of ``R``, as
    :func:`symtmm.numeric.linalg.separation_ratio` estimates it."""
    n, m = X.nrows(), X.ncols()
    if m >= n:
        return 0.0
    residual = max(_norm(_column(mat, M * X, c), complex_) for c in range(m))
    Xh = _adjoint(X, complex_)

    def deflate(v):
        for _ in range(2):
            v = (v - X * (Xh * v)).mid()
        return v

    x = deflate(mat(n, 1, [_start(rng, flint) for _ in range(n)]))
    growth = 0
    for _ in range(3):
        size = _norm(x, complex_)
        if not size > 0:
            return 0.0
        x = deflate(solves[0](solves[1](x * (1 / size))))
        growth = _norm(x, complex_)
    # growth is |(R^H R)^-1| on the complement: 1 / sigma_(m+1)**2
    if not growth > 0:
        return 0.0
    value = residual * growth.sqrt()
    return float(value.mid()) if value.is_finite() else math.inf


def _back(ar: Arithmetic, X, complex_):
    """The entries of ``X`` as numbers of ``ar``: exact balls (midpoints) for Arb, mpmath
    numbers rounded once to ``ar``'s precision otherwise."""
    entries = np.empty(len(X.entries()), dtype=object)
    entries[:] = X.entries()
    if ar.name == "ball":
        out = [z.mid() for z in entries]
    else:
        out = list(ball_midpoints(ar, entries))
    return ar.array(out, (X.nrows(), X.ncols()))
