"""Exact rational references for the tests: nothing of symtmm is used."""

from __future__ import annotations

from fractions import Fraction


def exact_det(A) -> Fraction:
    """The determinant of a square matrix of rationals (a list of rows), exactly, by
    Gaussian elimination over Fractions."""
    A = [[Fraction(v) for v in row] for row in A]
    n, det = len(A), Fraction(1)
    for k in range(n):
        p = next((i for i in range(k, n) if A[i][k] != 0), None)
        if p is None:
            return Fraction(0)
        if p != k:
            A[k], A[p] = A[p], A[k]
            det = -det
        det *= A[k][k]
        for i in range(k + 1, n):
            f = A[i][k] / A[k][k]
            for j in range(k, n):
                A[i][j] -= f * A[k][j]
    return det
