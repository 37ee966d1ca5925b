"""Spring/dashpot point elements (paper eqs. 11–12)."""

from __future__ import annotations

import sympy as sp

from .base import LAM, PointElement

__all__ = ["Coupling", "GroundSpring"]


class SpringBetween(PointElement):
    """A spring ``k`` and a dashpot ``c`` in parallel between one freedom (``dofs``, set by
    a subclass) of level ``a`` and the same freedom of level ``b``: ``S = (k + c lam)
    [[1, -1], [-1, 1]]``."""

    levels = 2

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


class SpringToGround(PointElement):
    """A spring ``k`` and a dashpot ``c`` in parallel from one freedom (``dofs``, set by a
    subclass) of level ``a`` to the ground: ``S = [[k + c lam]]``."""

    levels = 1

    def __init__(self, a: str, k, c=0):
        self.beams = (a,)
        self.k = sp.sympify(k)
        self.c = sp.sympify(c)

    @property
    def parameters(self) -> dict:
        return {"k": self.k, "c": self.c}

    def stiffness(self, lam=LAM) -> sp.Matrix:
        return sp.Matrix([[self.k + self.c * lam]])


class Coupling(SpringBetween):
    """Spring/dashpot between level ``a`` and level ``b``.

    Carries ``F = (k + c lam)(Y_b - Y_a)`` on ``a`` and ``-F`` on ``b``.

    Examples
    --------
    >>> Coupling("a", "b", k=2, c=1).stiffness(sp.Symbol("lam"))
    Matrix([
    [ lam + 2, -lam - 2],
    [-lam - 2,  lam + 2]])
    """

    dofs = ((0, "Y"), (1, "Y"))


class GroundSpring(SpringToGround):
    """Spring/dashpot from level ``a`` to the ground: ``Q+ = Q- - (k + c lam) Y``.

    Examples
    --------
    >>> GroundSpring("a", k=3).transfer_matrix()[3, 0]
    -3
    """

    dofs = ((0, "Y"),)
