"""Gauss–Legendre quadrature at any precision (:mod:`symtmm.numeric.arith`).

The nodes are the double-precision nodes of numpy's ``leggauss`` refined by
Newton's method on ``P_n`` in a private mpmath context a little above the
arithmetic's precision, then rounded once into the arithmetic; the rules are
kept per arithmetic (:meth:`~symtmm.numeric.arith.Arithmetic.cached`).

Examples
--------
>>> from symtmm.numeric.arith import MP
>>> ar = MP(200)
>>> nodes, weights = gauss_legendre(ar, gauss_legendre_nodes(50))
>>> abs(sum(w * x**10 for x, w in zip(nodes, weights)) - ar.ctx.mpf(1) / 11) < 1e-58
True
"""

from __future__ import annotations

import math

import mpmath
import numpy as np

from .arith import MP, Arithmetic, Batch

__all__ = ["gauss_legendre", "gauss_legendre_nodes"]


def gauss_legendre_nodes(digits: int) -> int:
    """Nodes of a Gauss–Legendre rule exact to ``10**-digits`` on a piece with ``|s| h <= 1``.

    On such a piece the integrand (a product of two states) is a combination
    of ``exp(c t)``, ``t`` in ``[-1, 1]``, ``|c| <= 1``; the ``n``-point rule's
    error is at most ``2**(2n+1) (n!)**4 / ((2n+1) ((2n)!)**3)`` times
    ``max |f^(2n)| <= e``. A further 5 digits cover the combination's
    coefficients exceeding its values.

    Examples
    --------
    >>> gauss_legendre_nodes(15), gauss_legendre_nodes(50)
    (9, 19)
    """
    target = -(digits + 5) * math.log(10)
    n = 2
    while ((2 * n + 1) * math.log(2) + 4 * math.lgamma(n + 1) - math.log(2 * n + 1)
           - 3 * math.lgamma(2 * n + 1) + 1) > target:
        n += 1
    return n


def gauss_legendre(ar: Arithmetic, n: int) -> tuple:
    """Nodes and weights of the ``n``-point rule on ``[0, 1]``, as arrays of ``ar``."""
    def build():
        nodes, weights = _rule(n, max(ar.prec, 53) + 20)
        if isinstance(ar, Batch):
            return (np.array([float(x) for x in nodes]), np.array([float(w) for w in weights]))
        return (ar.array([ar.number(mpmath.mp.make_mpf(x._mpf_)) for x in nodes]),
                ar.array([ar.number(mpmath.mp.make_mpf(w._mpf_)) for w in weights]))
    return ar.cached(("gauss-legendre", n), build)


def _rule(n: int, prec: int) -> tuple:
    """Nodes and weights on ``[0, 1]`` in a private context of ``prec`` bits."""
    ctx = MP(prec).ctx
    eps = ctx.ldexp(1, 2 - prec)
    nodes, weights = [], []
    for x0 in np.polynomial.legendre.leggauss(n)[0]:
        x = ctx.mpf(float(x0))
        for _ in range(12):
            p, dp = _legendre(ctx, n, x)
            dx = p / dp
            x -= dx
            if abs(dx) < eps:
                break
        p, dp = _legendre(ctx, n, x)
        nodes.append((x + 1) / 2)
        weights.append(1 / ((1 - x * x) * dp * dp))    # 2/((1-x^2)P'^2), halved for [0, 1]
    return nodes, weights


def _legendre(ctx, n: int, x) -> tuple:
    """``P_n(x)`` and ``P_n'(x)`` by the three-term recurrence."""
    p0, p1 = ctx.mpf(1), x
    for k in range(2, n + 1):
        p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
    return p1, n * (x * p1 - p0) / (x * x - 1)
