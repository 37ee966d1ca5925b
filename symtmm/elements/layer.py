"""A piece of several Euler–Bernoulli beams joined by continuous layers.

Over a layer the beams are one member: with ``Y = (Y_1, ..., Y_N)`` the field
equations ``EI_i Y_i'''' + (m_i lam**2 + kw_i) Y_i = sum_j kappa_ij (Y_j - Y_i)``
(``kappa_ij = k + c lam`` of the layer between beams ``i`` and ``j``, per unit
length) read

    Y'''' = X Y / l**4,   X = -l**4 EI**-1 (diag(m lam**2 + kw) + L_k + lam L_c),

with ``L_k``, ``L_c`` the Laplacians of the layers' stiffnesses and dampings.
Each beam keeps its own state ``(Y, Theta, M, Q)`` with the conventions of
:mod:`symtmm.elements.beam` (``Theta = Y'``, ``M = EI Y''``, ``Q = M'``); in the
scaled variables ``(Y, l Theta, l**2 EI**-1 M, l**3 EI**-1 Q)`` the transfer
matrix over the piece is the block matrix of the single beam's with the scalar
``x`` replaced by the matrix ``X``::

    [ c0(X)     c1(X)     c2(X)   c3(X) ]
    [ X c3(X)   c0(X)     c1(X)   c2(X) ]
    [ X c2(X)   X c3(X)   c0(X)   c1(X) ]
    [ X c1(X)   X c2(X)   X c3(X) c0(X) ]

``c_j(X) = sum_k X**k / (4k + j)!``: every block is a power series in ``X`` (they
commute), entire in ``lam``, with no eigenvalue of ``X`` to find (``X`` need not be
diagonalisable for complex ``lam``). Evaluated by :func:`symtmm.numeric.segments.coupled_matrices`.

Examples
--------
>>> seg = CoupledSegment(((1, 1, 0), (2, 3, 0)), "1/4", ((0, 1, 100, 0),))
>>> seg.size, seg.l
(2, 1/4)
"""

from __future__ import annotations

import numpy as np
import sympy as sp

__all__ = ["CoupledSegment", "joined", "member"]


class CoupledSegment:
    """``N`` Euler–Bernoulli beam pieces of one length joined by layers.

    Parameters
    ----------
    beams : sequence of (EI, m, kw)
        The beams' constants (exact).
    l : number
        Length of the piece.
    couplings : sequence of (i, j, k, c)
        A layer between beams ``i`` and ``j`` (positions in ``beams``), stiffness and
        damping per unit length.
    """

    def __init__(self, beams, l, couplings):
        self.beams = tuple(tuple(sp.sympify(v) for v in b) for b in beams)
        self.l = sp.sympify(l)
        self.couplings = tuple((int(i), int(j), sp.sympify(k), sp.sympify(c))
                               for i, j, k, c in couplings)

    @property
    def size(self) -> int:
        """The number of beams ``N`` (the state has ``4 N`` variables)."""
        return len(self.beams)

    def with_length(self, l) -> CoupledSegment:
        return CoupledSegment(self.beams, l, self.couplings)

    def laplacians(self) -> tuple:
        """``(L_k, L_c)`` as lists of lists of exact numbers."""
        n = self.size
        Lk = [[sp.Integer(0)] * n for _ in range(n)]
        Lc = [[sp.Integer(0)] * n for _ in range(n)]
        for i, j, k, c in self.couplings:
            for L, v in ((Lk, k), (Lc, c)):
                L[i][i] += v
                L[j][j] += v
                L[i][j] -= v
                L[j][i] -= v
        return Lk, Lc

    @property
    def damped(self) -> bool:
        return any(c != 0 for _, _, _, c in self.couplings)

    def wave_number(self, lam2, consts=None):
        """An upper bound on the wave numbers at ``lam2`` (floats, elementwise): the fourth
        root of ``|X| / l**4`` (infinity norm, ``|k + c lam| <= k + c |lam|``), which
        bounds every eigenvalue's."""
        lam2 = np.asarray(lam2, dtype=complex)
        lam_abs = np.sqrt(np.abs(lam2))
        best = np.zeros(lam2.shape)
        for i, (EI, m, kw) in enumerate(self.beams):
            row = np.abs(float(m) * lam2 + float(kw))
            for a, b, k, c in self.couplings:
                if i in (a, b):
                    row = row + 2 * (float(k) + float(c) * lam_abs)
            best = np.maximum(best, row / float(EI))
        return best ** 0.25

    def transfer_matrix(self, lam=None):
        from ..errors import ModelError
        raise ModelError("beams joined by a layer have no transfer matrix in lam alone: it is "
                         "a function of the matrix X, written through X's two wave numbers by "
                         "symtmm.characteristic (derive)", field="layer")

    def field_matrix(self, lam=None, lam2=None) -> sp.Matrix:
        """``X / l**4 = -EI**-1 (diag(m lam**2 + kw) + L_k + lam L_c)``, exact: the matrix
        of the field equations ``Y'''' = (X / l**4) Y``, independent of the length.

        ``lam2`` stands for ``lam**2`` where given (the closed forms write both through
        one frequency variable); ``lam`` defaults to :data:`symtmm.elements.base.LAM`.

        Examples
        --------
        >>> CoupledSegment(((1, 1, 0), (2, 3, 0)), 1, ((0, 1, 100, 0),)).field_matrix(lam2=-4)
        Matrix([
        [-96, 100],
        [ 50, -44]])
        """
        from .base import LAM
        lam = LAM if lam is None else sp.sympify(lam)
        lam2 = lam**2 if lam2 is None else sp.sympify(lam2)
        Lk, Lc = self.laplacians()
        n = self.size
        return sp.Matrix(n, n, lambda i, j: sp.expand(
            -((self.beams[i][1] * lam2 + self.beams[i][2] if i == j else 0)
              + Lk[i][j] + lam * Lc[i][j]) / self.beams[i][0]))

    @property
    def key(self) -> tuple:
        return ("coupled", self.size, self.beams, self.l, self.couplings)

    def constants(self) -> list:
        """The member's constants for generated code, exact: ``l``, ``A_i = m_i l**4/EI_i``,
        ``F_i = kw_i l**4/EI_i``, the Laplacians times ``l**4/EI_i`` row by row (``K``,
        then ``C``), ``l**2/EI_i`` and ``l**3/EI_i``."""
        l, n = self.l, self.size
        Lk, Lc = self.laplacians()
        EI = [b[0] for b in self.beams]
        out = [l]
        out += [m * l**4 / e for e, m, _ in self.beams]
        out += [kw * l**4 / e for e, _, kw in self.beams]
        out += [Lk[i][j] * l**4 / EI[i] for i in range(n) for j in range(n)]
        out += [Lc[i][j] * l**4 / EI[i] for i in range(n) for j in range(n)]
        out += [l**2 / e for e in EI] + [l**3 / e for e in EI]
        return out

    def __repr__(self):
        return f"CoupledSegment({self.beams}, {self.l}, {self.couplings})"


def joined(levels, layers, index) -> dict:
    """Per level, the beams joined to it through ``layers`` (those covering a stretch)
    and those layers: ``{level: (members, layers)}``, members sorted; a level no layer
    touches is alone. ``index`` maps beam names to levels. The layout (transfer walk)
    and the mesh (stiffness) group the beams of an interval with it.

    Examples
    --------
    >>> from symtmm.model import Layer
    >>> g = joined([0, 1, 2], [Layer("a", "b", 1)], {"a": 0, "b": 1, "c": 2})
    >>> g[0][0], g[1][0], g[2]
    ((0, 1), (0, 1), ((2,), []))
    """
    parent = {lvl: lvl for lvl in levels}

    def root(v):
        while parent[v] != v:
            v = parent[v]
        return v
    for la in layers:
        parent[root(index[la.a])] = root(index[la.b])
    members: dict = {}
    for lvl in levels:
        members.setdefault(root(lvl), []).append(lvl)
    out = {}
    for lvl in levels:
        group = tuple(sorted(members[root(lvl)]))
        out[lvl] = (group, [la for la in layers if index[la.a] in group] if len(group) > 1
                    else [])
    return out


def member(beams, levels, layers, index, length) -> CoupledSegment:
    """The piece ``length`` long of the beams ``levels`` (sorted) joined by ``layers``."""
    pos = {j: p for p, j in enumerate(levels)}
    return CoupledSegment([(beams[j].EI, beams[j].m, beams[j].kw) for j in levels], length,
                          [(pos[index[la.a]], pos[index[la.b]], la.k, la.c) for la in layers])
