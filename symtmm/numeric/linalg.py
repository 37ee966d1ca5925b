"""Small dense linear algebra on arrays of any arithmetic (:mod:`symtmm.numeric.arith`).

Gaussian elimination with partial pivoting, the pivot chosen by the largest
upper bound of the magnitude (for balls, their midpoints' size: a ball's radius
says nothing about which row is best).

Examples
--------
>>> import numpy as np
>>> from symtmm.numeric.arith import MP
>>> ar = MP(100)
>>> M = np.array([[ar.number(0), ar.number(2)], [ar.number(3), ar.number(4)]], dtype=object)
>>> print(det(ar, M))
-6.0
"""

from __future__ import annotations

import numpy as np

from .arith import Arithmetic

__all__ = ["det"]


def det(ar: Arithmetic, M):
    """The determinant of one square matrix (an object or complex array) in ``ar``.

    An empty matrix has determinant 1; a matrix whose every candidate pivot is an
    exact zero has determinant 0.
    """
    n = M.shape[0]
    if n == 0:
        return ar.exact(1)
    if M.dtype != object:
        return np.linalg.det(M)
    A = M.copy()
    value = ar.exact(1)
    for k in range(n):
        size = ar.upper(A[k:, k])
        p = k + int(np.argmax(size))
        if not size[p - k] > 0:
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
