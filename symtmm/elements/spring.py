"""Spring/dashpot point elements (paper eqs. 11–12)."""

from __future__ import annotations

import sympy as sp

from .base import LAM, PointElement

__all__ = ["Coupling", "GroundSpring"]


class Coupling(PointElement):
    """Spring/dashpot between level ``a`` and level ``b``.

    Carries ``F = (k + c lam)(Y_b - Y_a)`` on ``a`` and ``-F`` on ``b``.

    Examples
    --------
    >>> Coupling("a", "b", k=2, c=1).stiffness(sp.Symbol("lam"))
    Matrix([
    [ lam + 2, -lam - 2],
    [-lam - 2,  lam + 2]])
    """

    levels = 2
    dofs = ((0, "Y"), (1, "Y"))

    def __init__(self, a: str, b: str, k, c=0):
        self.beams = (a, b)
        self.k = sp.sympify(k)
        self.c = sp.sympify(c)

    @property
    def parameters(self) -> dict:
        return {"k": self.k, "c": self.c}

    def stiffness(self, lam=LAM) -> sp.Matrix:
        kc = self.k + self.c * lam
        return sp.Matrix([[kc, -kc], [-kc, kc]])


class GroundSpring(PointElement):
    """Spring/dashpot from level ``a`` to the ground: ``Q+ = Q- - (k + c lam) Y``.

    Examples
    --------
    >>> GroundSpring("a", k=3).transfer_matrix()[3, 0]
    -3
    """

    levels = 1
    dofs = ((0, "Y"),)

    def __init__(self, a: str, k, c=0):
        self.beams = (a,)
        self.k = sp.sympify(k)
        self.c = sp.sympify(c)

    @property
    def parameters(self) -> dict:
        return {"k": self.k, "c": self.c}

    def stiffness(self, lam=LAM) -> sp.Matrix:
        return sp.Matrix([[self.k + self.c * lam]])
