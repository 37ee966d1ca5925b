"""Point elements beyond the translational spring: lumped masses and rotational springs.

Each is given, like every point element, by its nodal dynamic stiffness
``S(lam)`` on ``(level, variable)`` pairs (see :mod:`symtmm.elements.base`);
derivations in ``derivations/point_elements.py``.

* :class:`LumpedMass`: a mass ``M`` with rotary inertia ``J`` attached to one
  beam. Its inertia forces ``-M lam**2 Y`` and ``-J lam**2 Theta`` act on the
  beam, so ``S = diag(M lam**2, J lam**2)`` on ``(Y, Theta)``.
* :class:`RotationalCoupling`: a rotational spring/dashpot between two beams,
  moment ``(k + c lam)(Theta_b - Theta_a)`` on ``a`` and its opposite on ``b``.
* :class:`RotationalGroundSpring`: a rotational spring/dashpot from a beam to
  the ground, ``M+ = M- + (k + c lam) Theta``.

At a beam end whose boundary condition leaves the displacement free, a spring
to the ground is an elastic support: ``Q(0) = -k Y(0)`` at a left end,
``Q(L) = k Y(L)`` at a right end, ``M(0) = k_r Theta(0)``, ``M(L) = -k_r Theta(L)``.
"""

from __future__ import annotations

import sympy as sp

from .base import LAM, PointElement
from .spring import SpringBetween, SpringToGround

__all__ = ["LumpedMass", "RotationalCoupling", "RotationalGroundSpring"]


class LumpedMass(PointElement):
    """A lumped mass ``M`` with rotary inertia ``J`` on level ``a``.

    Examples
    --------
    >>> lam = sp.Symbol("lam")
    >>> LumpedMass("a", M=2, J=3).stiffness(lam)
    Matrix([
    [2*lam**2,        0],
    [       0, 3*lam**2]])
    >>> LumpedMass("a", M=2).dofs          # no rotary inertia: the rotation is not touched
    ((0, 'Y'),)
    """

    levels = 1

    def __init__(self, a: str, M, J=0):
        self.beams = (a,)
        self.M = sp.sympify(M)
        self.J = sp.sympify(J)
        self.dofs = ((0, "Y"), (0, "Theta")) if not self.J.is_zero else ((0, "Y"),)

    @property
    def parameters(self) -> dict:
        return {"M": self.M, "J": self.J}

    def stiffness(self, lam=LAM) -> sp.Matrix:
        if len(self.dofs) == 1:
            return sp.Matrix([[self.M * lam**2]])
        return sp.diag(self.M * lam**2, self.J * lam**2)


class RotationalCoupling(SpringBetween):
    """Rotational spring/dashpot between level ``a`` and level ``b``.

    Carries the moment ``(k + c lam)(Theta_b - Theta_a)`` on ``a`` and its
    opposite on ``b``.

    Examples
    --------
    >>> RotationalCoupling("a", "b", k=5).transfer_matrix()[2, :]
    Matrix([[0, 5, 1, 0, 0, -5, 0, 0]])
    """

    dofs = ((0, "Theta"), (1, "Theta"))


class RotationalGroundSpring(SpringToGround):
    """Rotational spring/dashpot from level ``a`` to the ground: ``M+ = M- + (k + c lam) Theta``.

    Examples
    --------
    >>> RotationalGroundSpring("a", k=3).transfer_matrix()[2, 1]
    3
    """

    dofs = ((0, "Theta"),)
