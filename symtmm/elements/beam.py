"""Euler–Bernoulli beam segment.

Field equation ``EI Y'''' + m lam**2 Y = 0``. With ``beta**4 = -m lam**2 / EI``
the transfer matrix of a segment of length ``l`` is ``B(l) B(0)**-1``
(derived in ``derivations/euler_bernoulli.py``)::

    [ S        T/b       U/(EI b^2)  V/(EI b^3) ]
    [ b V      S         T/(EI b)    U/(EI b^2) ]
    [ EI b^2 U EI b V    S           T/b        ]
    [ EI b^3 T EI b^2 U  b V         S          ]

with ``S, T, U, V = (cosh+cos)/2, (sinh+sin)/2, (cosh-cos)/2, (sinh-sin)/2``
of ``b l``. Every entry is an entire function of ``x = (b l)**4``: writing
``c_j(x) = sum_k x**k / (4k+j)!`` gives ``S = c0``, ``T/b = l c1``,
``U/b**2 = l**2 c2`` and ``V/b**3 = l**3 c3``. The numeric evaluators use that
form, which has no branch of the fourth root to choose, no 0/0 at ``lam = 0``
and no cancellation for short segments.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import sympy as sp

from .base import LAM, FieldElement

__all__ = ["EulerBernoulliSegment", "stv_matrix", "c_functions_numpy", "c_functions_mp"]


def stv_matrix(beta, l, EI) -> sp.Matrix:
    """Closed-form segment transfer matrix in terms of ``beta``.

    Examples
    --------
    >>> b, l = sp.symbols("beta l", positive=True)
    >>> stv_matrix(b, l, 1)[0, 0]
    cos(beta*l)/2 + cosh(beta*l)/2
    """
    bl = beta * l
    S = (sp.cosh(bl) + sp.cos(bl)) / 2
    T = (sp.sinh(bl) + sp.sin(bl)) / 2
    U = (sp.cosh(bl) - sp.cos(bl)) / 2
    V = (sp.sinh(bl) - sp.sin(bl)) / 2
    b = beta
    return sp.Matrix([
        [S, T / b, U / (EI * b**2), V / (EI * b**3)],
        [b * V, S, T / (EI * b), U / (EI * b**2)],
        [EI * b**2 * U, EI * b * V, S, T / b],
        [EI * b**3 * T, EI * b**2 * U, b * V, S],
    ])


def _c_matrix(c0, c1, c2, c3, x, l, EI, module=np):
    """Assemble the transfer matrix from the four entire functions ``c_j(x)``."""
    return [
        [c0, l * c1, l**2 * c2 / EI, l**3 * c3 / EI],
        [x * c3 / l, c0, l * c1 / EI, l**2 * c2 / EI],
        [EI * x * c2 / l**2, EI * x * c3 / l, c0, l * c1],
        [EI * x * c1 / l**3, EI * x * c2 / l**2, x * c3 / l, c0],
    ]


# Below |x| = 1 the series converges fast (16 terms are below 1e-300) and is
# free of the cancellation the closed forms suffer for small b l.
_SERIES_TERMS = 16
_FACT = [math.factorial(n) for n in range(4 * _SERIES_TERMS + 4)]


def c_functions_numpy(x):
    """``c_0..c_3`` of a complex array ``x`` (vectorised, double precision).

    Examples
    --------
    >>> c = c_functions_numpy(np.array([0.0, 16.0]))
    >>> [complex(v[0]).real for v in c]
    [1.0, 1.0, 0.5, 0.16666666666666666]
    """
    x = np.asarray(x, dtype=complex)
    small = np.abs(x) < 1.0
    out = [np.empty_like(x) for _ in range(4)]
    if small.any():
        xs = x[small]
        for j in range(4):
            acc = np.zeros_like(xs)
            for k in reversed(range(_SERIES_TERMS)):
                acc = acc * xs + 1.0 / _FACT[4 * k + j]
            out[j][small] = acc
    big = ~small
    if big.any():
        nu = x[big] ** 0.25
        ch, co, sh, si = np.cosh(nu), np.cos(nu), np.sinh(nu), np.sin(nu)
        out[0][big] = (ch + co) / 2
        out[1][big] = (sh + si) / (2 * nu)
        out[2][big] = (ch - co) / (2 * nu**2)
        out[3][big] = (sh - si) / (2 * nu**3)
    return out


def c_functions_mp(x):
    """``c_0..c_3`` of an mpmath number at the current working precision."""
    if abs(x) < 1:
        eps = mpmath.eps
        result = []
        for j in range(4):
            term = mpmath.mpf(1) / _fact_mp(j)
            acc, k = term, 0
            while abs(term) > eps * abs(acc):
                k += 1
                term = term * x / ((4 * k + j) * (4 * k + j - 1) * (4 * k + j - 2) * (4 * k + j - 3))
                acc += term
            result.append(acc)
        return result
    nu = mpmath.root(x, 4)
    ch, co, sh, si = mpmath.cosh(nu), mpmath.cos(nu), mpmath.sinh(nu), mpmath.sin(nu)
    return [(ch + co) / 2, (sh + si) / (2 * nu), (ch - co) / (2 * nu**2), (sh - si) / (2 * nu**3)]


def _fact_mp(n):
    return mpmath.mpf(math.factorial(n))


class EulerBernoulliSegment(FieldElement):
    """A uniform Euler–Bernoulli beam segment.

    Parameters
    ----------
    EI, m, l : sympy.Expr or number
        Bending stiffness, mass per unit length, length.

    Examples
    --------
    >>> seg = EulerBernoulliSegment(1, 1, 1)
    >>> sp.simplify(seg.transfer_matrix(sp.Integer(0)) - seg.static_matrix())
    Matrix([
    [0, 0, 0, 0],
    [0, 0, 0, 0],
    [0, 0, 0, 0],
    [0, 0, 0, 0]])
    """

    def __init__(self, EI, m, l):
        self.EI = sp.sympify(EI)
        self.m = sp.sympify(m)
        self.l = sp.sympify(l)

    @property
    def parameters(self) -> dict:
        return {"EI": self.EI, "m": self.m, "l": self.l}

    def beta(self, lam=LAM):
        """``beta = (-m lam**2 / EI)**(1/4)`` (any branch gives the same matrix)."""
        return (-self.m * lam**2 / self.EI) ** sp.Rational(1, 4)

    def transfer_matrix(self, lam=LAM) -> sp.Matrix:
        """Exact transfer matrix at ``lam`` (closed form; at ``lam = 0`` the static one)."""
        if lam == 0:
            return self.static_matrix()
        return stv_matrix(self.beta(lam), self.l, self.EI)

    def transfer_matrix_beta(self, beta) -> sp.Matrix:
        """Exact transfer matrix as a function of the wave number ``beta``."""
        return stv_matrix(beta, self.l, self.EI)

    def transfer_matrix_series(self, x) -> sp.Matrix:
        """Exact transfer matrix in terms of ``x = (beta l)**4`` through ``c_j(x)``.

        ``x`` may be a symbol; the ``c_j`` are then left as undefined functions.
        """
        if x == 0:
            return self.static_matrix()
        cs = [sp.Function(f"c{j}")(x) for j in range(4)]
        return sp.Matrix(_c_matrix(*cs, x, self.l, self.EI))

    def static_matrix(self) -> sp.Matrix:
        """Transfer matrix at ``lam = 0``: ``c_j(0) = 1/j!``."""
        cs = [sp.Integer(1), sp.Integer(1), sp.Rational(1, 2), sp.Rational(1, 6)]
        return sp.Matrix(_c_matrix(*cs, sp.Integer(0), self.l, self.EI))

    def evaluate_numpy(self, lam2, consts=None) -> np.ndarray:
        """Transfer matrices for an array of ``lam**2`` values: shape ``(..., 4, 4)``."""
        EI, m, l = consts if consts is not None else (float(self.EI), float(self.m), float(self.l))
        lam2 = np.asarray(lam2, dtype=complex)
        x = -lam2 * (m * l**4 / EI)
        c0, c1, c2, c3 = c_functions_numpy(x)
        rows = _c_matrix(c0, c1, c2, c3, x, l, EI)
        return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)

    def evaluate_mp(self, lam2, consts) -> np.ndarray:
        """Transfer matrix for one mpmath ``lam**2`` at the working precision.

        ``consts`` are ``(EI, m, l)`` as mpmath numbers at that precision.
        Returns a 4x4 object array.
        """
        EI, m, l = consts
        x = -lam2 * (m * l**4 / EI)
        c0, c1, c2, c3 = c_functions_mp(x)
        rows = _c_matrix(c0, c1, c2, c3, x, l, EI)
        out = np.empty((4, 4), dtype=object)
        for i in range(4):
            for j in range(4):
                out[i, j] = rows[i][j]
        return out

    def nu(self, omega: float) -> float:
        """``beta l`` at circular frequency ``omega`` (undamped), as a float."""
        return (float(self.m) / float(self.EI)) ** 0.25 * math.sqrt(abs(omega)) * float(self.l)
