"""Euler–Bernoulli beam segment.

Field equation ``EI Y'''' + (kw + m lam**2) Y = 0`` (``kw``: stiffness per unit
length of an optional Winkler foundation, default 0). With
``beta**4 = -(m lam**2 + kw) / EI``
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

import functools

import numpy as np
import sympy as sp

from ..expr import exact_float
from .base import LAM, FieldElement

__all__ = ["EulerBernoulliSegment", "stv_matrix"]


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
class EulerBernoulliSegment(FieldElement):
    """A uniform Euler–Bernoulli beam segment.

    Parameters
    ----------
    EI, m, l : sympy.Expr or number
        Bending stiffness, mass per unit length, length.
    kw : sympy.Expr or number, optional
        Winkler foundation stiffness per unit length (default 0). It enters
        only through ``x = -(m lam**2 + kw) l**4 / EI``: the segment at ``lam``
        is the bare segment at ``lam**2 + kw/m``.

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

    def __init__(self, EI, m, l, kw=0):
        self.EI = sp.sympify(EI)
        self.m = sp.sympify(m)
        self.l = sp.sympify(l)
        self.kw = sp.sympify(kw)

    @property
    def parameters(self) -> dict:
        if self.kw == 0:
            return {"EI": self.EI, "m": self.m, "l": self.l}
        return {"EI": self.EI, "m": self.m, "l": self.l, "kw": self.kw}

    @property
    def key(self) -> tuple:
        """The constants that fix the segment's matrix (equal keys, equal matrices)."""
        return (self.EI, self.m, self.l, self.kw)

    def with_length(self, l) -> EulerBernoulliSegment:
        """The same beam over another length."""
        return EulerBernoulliSegment(self.EI, self.m, l, self.kw)

    def constants(self) -> tuple:
        """``(EI, m, l, kw)`` as floats (wave-number bounds and piece lengths)."""
        return self._constants

    @functools.cached_property
    def _constants(self) -> tuple:
        # (once per segment: its constants never change)
        return (exact_float(self.EI), exact_float(self.m), exact_float(self.l),
                exact_float(self.kw))

    def wave_number(self, lam2, consts=None):
        """``|beta| = |(m lam**2 + kw)/EI|**(1/4)`` (numpy arrays or floats)."""
        EI, m, _, kw = (consts if consts is not None else self.constants())[:4]
        return np.abs((m * np.asarray(lam2, dtype=complex) + kw) / EI) ** 0.25

    def counting_wave_number(self, omega: float, consts=None) -> float:
        """``pi`` times the modes per unit length below ``omega`` (Weyl): the wave number
        ``((m omega**2 - kw) / EI)**(1/4)`` of the waves that travel at ``omega``, 0 below
        the foundation's cut-off (every wave evanescent there).

        Examples
        --------
        >>> EulerBernoulliSegment(1, 1, 1).counting_wave_number(9.0)
        3.0
        >>> EulerBernoulliSegment(1, 1, 1, kw=100).counting_wave_number(9.0)
        0.0
        """
        EI, m, _, kw = (consts if consts is not None else self.constants())[:4]
        travelling = m * float(omega) ** 2 - kw
        return (travelling / EI) ** 0.25 if travelling > 0 else 0.0

    def safe_length(self, omega2: float, nu_max: float = 2.0) -> float:
        """A piece length with ``beta l <= nu_max`` at ``omega**2`` (at most the segment's).

        With ``nu_max`` below the first clamped-clamped root ``beta l = 4.730``, such
        a piece has no clamped-clamped natural frequency below ``omega`` (a
        foundation only raises them); and it loses no digit to cancellation.
        """
        beta = (float(self.m) * max(omega2, 0.0) / float(self.EI)) ** 0.25
        length = float(self.l)
        return length if beta * length <= nu_max else nu_max / beta

    def beta(self, lam=LAM):
        """``beta = (-(m lam**2 + kw) / EI)**(1/4)`` (any branch gives the same matrix)."""
        return (-(self.m * lam**2 + self.kw) / self.EI) ** sp.Rational(1, 4)

    def transfer_matrix(self, lam=LAM) -> sp.Matrix:
        """Exact transfer matrix at ``lam`` (closed form; at ``x = 0`` the static one)."""
        if self.m * lam**2 + self.kw == 0:
            return self.static_matrix()
        if lam == 0:
            return self.foundation_static_matrix()
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

    def foundation_static_matrix(self) -> sp.Matrix:
        """Transfer matrix at ``lam = 0`` on a foundation, in real functions.

        With ``x = -4 s**4``, ``s = l (kw / (4 EI))**(1/4)``, the fourth root of
        ``x`` is ``s (1 + i)`` and the ``c_j`` become ``cosh s cos s``,
        ``(cosh s sin s + sinh s cos s) / (2 s)``, ``sinh s sin s / (2 s**2)`` and
        ``(cosh s sin s - sinh s cos s) / (4 s**3)``: real, which keeps exact
        rank decisions (rigid-body modes) simple.

        Examples
        --------
        >>> seg = EulerBernoulliSegment(1, 1, 1, kw=4)
        >>> seg.foundation_static_matrix()[0, 0]
        cos(1)*cosh(1)
        """
        s = self.l * (self.kw / (4 * self.EI)) ** sp.Rational(1, 4)
        ch, co, sh, si = sp.cosh(s), sp.cos(s), sp.sinh(s), sp.sin(s)
        cs = [ch * co, (ch * si + sh * co) / (2 * s), sh * si / (2 * s**2),
              (ch * si - sh * co) / (4 * s**3)]
        return sp.Matrix(_c_matrix(*cs, -4 * s**4, self.l, self.EI))

    def static_matrix(self) -> sp.Matrix:
        """Transfer matrix at ``x = 0`` (``lam = 0`` without foundation): ``c_j(0) = 1/j!``."""
        cs = [sp.Integer(1), sp.Integer(1), sp.Rational(1, 2), sp.Rational(1, 6)]
        return sp.Matrix(_c_matrix(*cs, sp.Integer(0), self.l, self.EI))
