"""The interface shared by all elements.

Per beam and per point the state vector is ``z = [Y, Theta, M, Q]`` with
``Theta = Y'``, ``M = EI Y''`` and ``Q = EI Y'''`` (see ``shared/method.md``).

Field elements (a beam segment) map the state at one end to the state at the
other. Point elements (springs, dashpots, masses) sit at one coordinate and
are described by their nodal dynamic stiffness ``S(lam)`` acting on
displacement-like variables (``Y`` or ``Theta``) of the levels they join. Both
formulations symtmm uses follow from that one description:

* transfer form: ``Q+ = Q- - (S d)_Y`` and ``M+ = M- + (S d)_Theta``;
* stiffness form: ``S`` is added to the global dynamic stiffness matrix.

The signs come from the virtual work of a segment's end actions,
``[M dTheta - Q dY]`` between its ends.
"""

from __future__ import annotations

import functools
from abc import ABC, abstractmethod

import sympy as sp

__all__ = ["STATE", "Element", "FieldElement", "PointElement", "LAM", "lam_coefficients",
           "stiffness_coefficients"]

#: State variables per level, in order.
STATE = ("Y", "Theta", "M", "Q")
#: The symbol used for the eigenvalue in exact expressions.
LAM = sp.Symbol("lam")
#: The force variable conjugate to each displacement variable, and the sign of its jump.
CONJUGATE = {"Y": ("Q", -1), "Theta": ("M", +1)}


class Element(ABC):
    """Common interface of all elements."""

    #: number of levels (beams) the element acts on
    levels: int = 1

    @property
    @abstractmethod
    def parameters(self) -> dict:
        """The element's parameters as exact SymPy expressions, by name."""

    @abstractmethod
    def transfer_matrix(self, lam=LAM) -> sp.Matrix:
        """Exact transfer matrix (``4 * levels`` square) at eigenvalue ``lam``."""


class FieldElement(Element):
    """An element with extent: maps the state at its left end to its right end."""

    levels = 1


class PointElement(Element):
    """An element at one coordinate, given by its nodal dynamic stiffness."""

    #: ``(level, variable)`` pairs the stiffness acts on; level indexes ``beams``
    dofs: tuple = ()
    #: names of the beams the element joins, in level order
    beams: tuple = ()

    @abstractmethod
    def stiffness(self, lam=LAM) -> sp.Matrix:
        """Nodal dynamic stiffness on :attr:`dofs` (exact)."""

    def inertia(self) -> sp.Matrix:
        """The element's mass matrix on :attr:`dofs`: the ``lam**2`` coefficient of ``S``.

        Its kinetic energy enters the mass normalisation of mode shapes.

        Examples
        --------
        >>> from symtmm.elements import Coupling, LumpedMass
        >>> LumpedMass("a", 2, 3).inertia(), Coupling("a", "b", k=5, c=1).inertia()
        (Matrix([
        [2, 0],
        [0, 3]]), Matrix([
        [0, 0],
        [0, 0]]))
        """
        S = self.stiffness(LAM)
        return (S.diff(LAM, 2) / 2).xreplace({LAM: 0})

    def transfer_matrix(self, lam=LAM) -> sp.Matrix:
        """Transfer matrix across the point, on the stacked states of its levels.

        Examples
        --------
        >>> from symtmm.elements import Coupling
        >>> Coupling("a", "b", k=5).transfer_matrix()[3, :]
        Matrix([[-5, 0, 0, 1, 5, 0, 0, 0]])
        """
        size = 4 * self.levels
        matrix = sp.eye(size)
        S = self.stiffness(lam)
        for row, (level, var) in enumerate(self.dofs):
            force, sign = CONJUGATE[var]
            force_row = 4 * level + STATE.index(force)
            for col, (level2, var2) in enumerate(self.dofs):
                matrix[force_row, 4 * level2 + STATE.index(var2)] += sign * S[row, col]
        return matrix


@functools.lru_cache(maxsize=1024)
def lam_coefficients(S) -> list:
    """Per entry of a point element's ``S(lam)`` (an immutable matrix) its coefficients of
    ``lam**0, lam**1, ...`` (at most three: ``S`` is of degree 2 at most).

    Examples
    --------
    >>> lam_coefficients(sp.ImmutableMatrix([[3 + 2 * LAM, 0], [0, LAM**2]]))
    [[[3, 2], [0]], [[0], [0, 0, 1]]]
    """
    polys = [[sp.Poly(sp.expand(S[i, j]), LAM).all_coeffs()[::-1]
              for j in range(S.cols)] for i in range(S.rows)]
    if any(len(p) > 3 for row in polys for p in row):
        raise ValueError("a point element of degree > 2 in lam")
    return polys


#: :func:`stiffness_coefficients` by element class and parameters.
_COEFFICIENTS: dict = {}


def stiffness_coefficients(element: PointElement) -> list:
    """:func:`lam_coefficients` of a point element's ``S(lam)``, kept by its class and
    parameters, which are all ``S`` depends on: building ``S`` and hashing the matrix cost
    what the rest of a spring's share of a stiffness plan does several times over (a
    50-level chain's 100 springs: 10 ms of every plan). ``[row][col][0]`` is ``S(0)``.

    Examples
    --------
    >>> from symtmm.elements.spring import Coupling
    >>> stiffness_coefficients(Coupling("a", "b", k=5, c=2))[0]
    [[5, 2], [-5, -2]]
    """
    key = (type(element), tuple(sorted(element.parameters.items())))
    polys = _COEFFICIENTS.get(key)
    if polys is None:
        if len(_COEFFICIENTS) >= 4096:
            _COEFFICIENTS.clear()
        polys = _COEFFICIENTS[key] = lam_coefficients(sp.ImmutableMatrix(element.stiffness(LAM)))
    return polys
