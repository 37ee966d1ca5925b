"""Certified eigenvalue enclosures in ball arithmetic (needs python-flint).

``Delta(lam)`` and its derivative are evaluated in Arb ball arithmetic
(``flint.acb``): every operation returns a ball guaranteed to contain the
exact result, and the model's exact parameters (rationals, ``pi``, square
roots) are enclosed exactly as well. The layout is walked on its extended
state (beams, then the rigid bodies' virtual variables), the stations' exact
jump entries (springs, masses, bodies, joints) becoming balls. Euler–Bernoulli
segments use the entire functions ``c_j(x)`` of ``x = (beta l)**4``: for
``|x| <= 1`` their series with a bound on the tail, otherwise the closed
forms in ``nu = x**(1/4)`` on a branch away from the ball. Every other
segment (axial force, Rayleigh, Timoshenko) is ``U = exp(A l)`` by Arb's
rigorous matrix exponential, ``A`` the exact system matrix, and ``dU/dlam``
the top-right block of the exponential of ``[[A l, A' l], [0, A l]]``.
``Delta`` and ``Delta'`` come from one Gaussian elimination with full
pivoting on the pairs ``(R, R')``.

Proofs, per eigenvalue:

* ``exact``: ``lam = 0`` for rigid-body modes (the exact static null space, :func:`symtmm.mesh.static_nullity`).
* ``sign change``: a real function that changes sign has a zero between.
  ``Delta(i omega)`` of an undamped model and ``Delta(x)`` on the real axis
  are real; balls of opposite sign at the two ends of a bracket prove a root
  inside it (an odd number of them, counting multiplicity).
* ``Krawczyk``: for a box ``B`` around an approximation ``z``,
  ``K = z - Y Delta(z) + (1 - Y Delta'(B)) (B - z)`` with ``Y ~ 1/Delta'(z)``;
  ``K`` inside ``B`` proves exactly one simple zero in ``B``, and it lies in
  ``K``. ``z`` is first polished by Newton's method, and ``B`` is taken small
  enough (about ``10**-(digits lost + 8) |lam|``) for the enclosure of
  ``Delta'(B)`` to be tight.
* ``count``: an undamped eigenvalue of multiplicity ``m``: the
  Wittrick–Williams count in ball arithmetic (:class:`ArbCount`, every pivot's
  sign proved) differs by exactly ``m`` between the ends of its bracket, so the
  bracket holds ``m`` eigenvalues counted with multiplicity (exactly one
  eigenvalue of multiplicity ``m``, or several that agree to the bracket).
  Any beam theory, rigid bodies and joints (as :class:`symtmm.stiffness.Mesh`
  eliminates their constraints, with exact coefficients).
* ``none``: multiple eigenvalues of damped models (``Delta'`` vanishes there)
  are not certified; they are reported with ``"certified": false``.

A certified eigenvalue whose real part is printed as ``0`` (an undamped mode
of a damped model) gets an enclosure of its real part around 0: ball
arithmetic proves that the real part is tiny, never that it is exactly zero.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mpmath
import sympy as sp

from ..assembly import Interval, Layout
from ..compile import Evaluator
from ..elements import EulerBernoulliSegment
from ..elements.base import LAM
from ..errors import ComputationError
from ..model import Model
from ..results import Eigenvalue, Spectrum
from .damped import DAMPED_PROOFS
from .undamped import PROOFS

__all__ = ["ArbCount", "ArbDelta", "Enclosure", "Enclosures", "certify", "require_flint"]


def require_flint():
    """The ``flint`` module, or a one-line :class:`ComputationError` saying how to get it."""
    try:
        import flint
    except ImportError:
        raise ComputationError("certified enclosures need python-flint: "
                               "pip install 'symtmm[certified]'") from None
    return flint


# -- exact values as balls --------------------------------------------------------------
def to_arb(expr, flint):
    """An exact real SymPy number as an arb ball (at the working precision).

    Examples
    --------
    >>> import flint
    >>> with flint.ctx.workprec(100):
    ...     b = to_arb(sp.sqrt(2) * sp.pi / 3, flint)
    >>> b.contains(flint.arb("1.48096098"))
    False
    >>> abs(float(b.mid()) - 1.4809609793861218) < 1e-15
    True
    """
    arb = flint.arb
    expr = sp.sympify(expr)
    if expr.is_Integer:
        return arb(flint.fmpz(int(expr)))
    if expr.is_Rational:
        return arb(flint.fmpq(int(expr.p), int(expr.q)))
    if expr is sp.pi:
        return arb.pi()
    if expr.is_Add:
        total = arb(0)
        for term in expr.args:
            total += to_arb(term, flint)
        return total
    if expr.is_Mul:
        prod = arb(1)
        for factor in expr.args:
            prod *= to_arb(factor, flint)
        return prod
    if expr.is_Pow:
        base, exp = expr.args
        b = to_arb(base, flint)
        if exp.is_Integer:
            return b ** int(exp)
        if exp.is_Rational:
            root = b.sqrt() if exp.q == 2 else b ** arb(flint.fmpq(1, int(exp.q)))
            return root ** int(exp.p)
    raise ComputationError(f"cannot enclose {expr} in ball arithmetic")


def _arb_exact(x, flint):
    """An mpmath ``mpf`` (or int/float) as an exact arb (no rounding on the way)."""
    if not isinstance(x, mpmath.mpf):
        with mpmath.workprec(1100):     # ints and floats are exact at this precision
            x = mpmath.mpf(x)
    sign, man, exp, _ = x._mpf_
    if man == 0:
        return flint.arb(0)
    value = flint.arb(flint.fmpz(int(man))) * flint.arb(2) ** int(exp)
    return -value if sign else value


def _acb_exact(z, flint):
    """An mpmath ``mpc`` (or complex) as an exact acb (``mpc()`` would round it)."""
    if isinstance(z, mpmath.mpc):
        return flint.acb(_arb_exact(z.real, flint), _arb_exact(z.imag, flint))
    z = complex(z)
    return flint.acb(_arb_exact(z.real, flint), _arb_exact(z.imag, flint))


def _coefficient_balls(value, flint) -> list:
    """The coefficients of an exact polynomial in ``lam`` (``lam**0`` first) as arb balls."""
    value = sp.expand(value)
    if value == 0:
        return []
    return [to_arb(c, flint) for c in reversed(sp.Poly(value, LAM).all_coeffs())]


def _poly_acb(coeffs, lam, acb):
    """A polynomial (coefficient balls, ``lam**0`` first) and its derivative at ``lam``."""
    value, deriv = acb(0), acb(0)
    for degree in range(len(coeffs) - 1, -1, -1):        # Horner, derivative alongside
        deriv = deriv * lam + value
        value = value * lam + coeffs[degree]
    return value, deriv


# -- Delta and Delta' in ball arithmetic --------------------------------------------------
_FACTORIAL = [math.factorial(n) for n in range(200)]


class ArbDelta:
    """``Delta(lam)`` and ``Delta'(lam)`` of a numeric model for ``acb`` balls ``lam``.

    Works at flint's working precision (``flint.ctx.workprec``).

    Examples
    --------
    >>> import flint
    >>> from symtmm.model import Beam, Model
    >>> f = ArbDelta(Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),)))
    >>> with flint.ctx.workprec(200):
    ...     d = f.value(flint.acb(0, flint.arb.pi() ** 2))     # the first root, pi^2 i
    >>> d.contains(0)
    True
    """

    def __init__(self, model: Model):
        self.flint = require_flint()
        self.model = model.require_numeric()
        self.layout = Layout(self.model)
        self.n = self.layout.levels
        self.evaluations = 0
        self._cache: dict = {}

    def _consts(self, key, exprs):
        prec = self.flint.ctx.prec
        hit = self._cache.get((key, prec))
        if hit is None:
            hit = tuple(to_arb(e, self.flint) for e in exprs)
            self._cache[(key, prec)] = hit
        return hit

    def _c_functions(self, x):
        """``c_0..c_3`` at the ball ``x`` and their derivatives ``dc_j/dx``."""
        acb, arb = self.flint.acb, self.flint.arb
        if x.abs_upper() <= 1:
            bits = self.flint.ctx.prec
            K = 4
            while (K < 190 // 4 - 1
                   and arb(1) / _FACTORIAL[4 * K] > arb(2) ** (-bits - 10)):
                K += 1
            xm = x.abs_upper()
            cs, ds = [], []
            for j in range(4):
                c, d, p = acb(0), acb(0), acb(1)          # p = x**k
                for k in range(K):
                    c += p / _FACTORIAL[4 * k + j]
                    if k + 1 < K:
                        d += (k + 1) * p / _FACTORIAL[4 * (k + 1) + j]
                    p *= x
                # tails: consecutive terms shrink by at least 1/2 for |x| <= 1
                tail = 2 * xm ** K / _FACTORIAL[4 * K + j]
                dtail = 2 * K * xm ** (K - 1) / _FACTORIAL[4 * K + j]
                cs.append(c + acb(arb(0, tail), arb(0, tail)))
                ds.append(d + acb(arb(0, dtail), arb(0, dtail)))
            return cs, ds
        # nu = x**(1/4) on a branch whose cut is away from x: every c_j depends on nu**4 only
        mid = x.mid()
        if mid.real >= 0:
            nu = x.root(4)
        else:
            nu = (-x).root(4) * acb(arb(2).sqrt() / 2, arb(2).sqrt() / 2)
        ch, sh = nu.cosh(), nu.sinh()
        co, si = nu.cos(), nu.sin()
        c0 = (ch + co) / 2
        c1 = (sh + si) / (2 * nu)
        c2 = (ch - co) / (2 * nu ** 2)
        c3 = (sh - si) / (2 * nu ** 3)
        # d/dx [nu^j c_j] = nu^(j-1) c_(j-1) (d/dnu) / (4 nu^3) gives these:
        d0 = c3 / 4
        d1 = (c0 - c1) / (4 * x)
        d2 = (c1 - 2 * c2) / (4 * x)
        d3 = (c2 - 3 * c3) / (4 * x)
        return [c0, c1, c2, c3], [d0, d1, d2, d3]

    def _segment(self, seg, lam, derivative: bool = True):
        """Transfer matrix of a segment and its derivative in ``lam`` (4x4 lists of acb).

        Euler–Bernoulli segments through the ``c_j`` (:meth:`_segment_eb`), every
        other theory through the matrix exponential (:meth:`_segment_exp`).
        Without ``derivative`` the second matrix is None.
        """
        if isinstance(seg, EulerBernoulliSegment):
            U, dU = self._segment_eb(seg, lam)
            return U, (dU if derivative else None)
        return self._segment_exp(seg, lam, derivative)

    def _segment_eb(self, seg, lam):
        EI, m, l, kw = self._consts(("seg", id(seg)), (seg.EI, seg.m, seg.l, seg.kw))
        a = m * l ** 4 / EI
        # a Winkler foundation kw: x = -(m lam**2 + kw) l**4 / EI
        x = -(lam * lam) * a - kw * l ** 4 / EI
        dx = -2 * lam * a
        (c0, c1, c2, c3), (d0, d1, d2, d3) = self._c_functions(x)
        U = [[c0, l * c1, l ** 2 * c2 / EI, l ** 3 * c3 / EI],
             [x * c3 / l, c0, l * c1 / EI, l ** 2 * c2 / EI],
             [EI * x * c2 / l ** 2, EI * x * c3 / l, c0, l * c1],
             [EI * x * c1 / l ** 3, EI * x * c2 / l ** 2, x * c3 / l, c0]]
        # derivatives in x, then times dx/dlam
        xc1, xc2, xc3 = c1 + x * d1, c2 + x * d2, c3 + x * d3
        dU = [[d0, l * d1, l ** 2 * d2 / EI, l ** 3 * d3 / EI],
              [xc3 / l, d0, l * d1 / EI, l ** 2 * d2 / EI],
              [EI * xc2 / l ** 2, EI * xc3 / l, d0, l * d1],
              [EI * xc1 / l ** 3, EI * xc2 / l ** 2, xc3 / l, d0]]
        dU = [[v * dx for v in row] for row in dU]
        return U, dU

    def _system(self, seg):
        """``A(lam) l`` of ``z' = A z`` as exact polynomials in ``lam``: per entry the balls of
        its coefficients (``lam**0, lam**1, ...``)."""
        key = ("A", id(seg), self.flint.ctx.prec)
        polys = self._cache.get(key)
        if polys is None:
            A = seg.system_matrix(LAM) * seg.l
            polys = [[_coefficient_balls(A[i, j], self.flint) for j in range(4)]
                     for i in range(4)]
            self._cache[key] = polys
        return polys

    def _segment_exp(self, seg, lam, derivative: bool):
        """``U = exp(A l)`` and ``dU/dlam`` of any segment, by Arb's rigorous matrix exponential.

        ``exp([[X, E], [0, X]]) = [[exp X, L(X, E)], [0, exp X]]`` with ``L`` the
        Fréchet derivative of the exponential; with ``X = A l``, ``E = A' l`` the
        top-right block is ``dU/dlam``.
        """
        acb, acb_mat = self.flint.acb, self.flint.acb_mat
        polys = self._system(seg)
        X = [[_poly_acb(p, lam, acb)[0] for p in row] for row in polys]
        if not derivative:
            U = acb_mat(X).exp()
            return [[U[i, j] for j in range(4)] for i in range(4)], None
        dX = [[_poly_acb(p, lam, acb)[1] for p in row] for row in polys]
        zero = [acb(0)] * 4
        big = acb_mat([X[i] + dX[i] for i in range(4)] + [zero + X[i] for i in range(4)]).exp()
        U = [[big[i, j] for j in range(4)] for i in range(4)]
        dU = [[big[i, j + 4] for j in range(4)] for i in range(4)]
        return U, dU

    def _jumps(self, step):
        """The entries ``(row, col, coefficient balls)`` of a station's ``G`` (cached)."""
        key = ("G", id(step), self.flint.ctx.prec)
        terms = self._cache.get(key)
        if terms is None:
            terms = [(row, col, _coefficient_balls(value, self.flint))
                     for row, col, value in step.terms]
            self._cache[key] = terms
        return terms

    def matrices(self, lam, derivative: bool = True):
        """``(R, R')`` at the ball ``lam`` as ``acb_mat`` (``R'`` None without ``derivative``).

        Walks the layout's extended state (beams, then the bodies' virtual
        variables): segments, then at each station ``z -> (I + G) z`` with the
        exact entries of ``G`` (:attr:`~symtmm.assembly.Station.terms`).
        """
        self.evaluations += 1
        acb, acb_mat = self.flint.acb, self.flint.acb_mat
        cols = self.layout.columns
        k = len(cols)
        E = [[acb(1) if i == c else acb(0) for c in cols] for i in range(self.layout.size)]
        dE = [[acb(0)] * k for _ in range(self.layout.size)] if derivative else None
        for step in self.layout.steps:
            if isinstance(step, Interval):
                for lvl, seg in step.segments:
                    U, dU = self._segment(seg, lam, derivative)
                    blk = range(4 * lvl, 4 * lvl + 4)
                    old = [E[i] for i in blk]
                    dold = [dE[i] for i in blk] if derivative else None
                    for a, i in enumerate(blk):
                        E[i] = [sum((U[a][b] * old[b][j] for b in range(4)), acb(0))
                                for j in range(k)]
                        if derivative:
                            dE[i] = [sum((dU[a][b] * old[b][j] + U[a][b] * dold[b][j]
                                          for b in range(4)), acb(0)) for j in range(k)]
                continue
            # across a station z -> (I + G) z; rows written are never columns read there
            for row, col, coeffs in self._jumps(step):
                v, dv = _poly_acb(coeffs, lam, acb)
                if derivative:
                    dE[row] = [dE[row][j] + v * dE[col][j] + dv * E[col][j] for j in range(k)]
                E[row] = [E[row][j] + v * E[col][j] for j in range(k)]
        rows = self.layout.rows
        R = acb_mat([E[r] for r in rows]) if rows else acb_mat(0, 0)
        dR = (acb_mat([dE[r] for r in rows]) if rows else acb_mat(0, 0)) if derivative else None
        return R, dR

    def value(self, lam):
        """``Delta(lam)``."""
        R, _ = self.matrices(lam, derivative=False)
        if not R.nrows():
            return self.flint.acb(1)
        out = _determinant(_rows(R), None, self.flint)
        return out[0] if out is not None else R.det()

    def value_and_derivative(self, lam):
        """``(Delta(lam), Delta'(lam))`` by one elimination on pairs ``(R, R')``.

        Gaussian elimination with full pivoting carries every entry with its
        derivative (forward-mode differentiation of ``det R = prod of pivots``):
        exact calculus on balls, rigorous wherever no pivot but the last contains 0.
        Jacobi's formula column by column fails at roots whose null vector has zero
        entries (the opposite modes of symmetric trees and loops leave the trunk and
        the joints at rest: ``R`` with such a column replaced is singular twice over,
        and Arb can then only bound its determinant).
        """
        R, dR = self.matrices(lam)
        n = R.nrows()
        if n == 0:
            return self.flint.acb(1), self.flint.acb(0)
        out = _determinant(_rows(R), _rows(dR), self.flint)
        if out is None:                # a pivot not clear of 0: nothing useful to prove with
            whole = self.flint.acb(0, 0) + self.flint.acb(self.flint.arb(0, math.inf),
                                                          self.flint.arb(0, math.inf))
            return R.det(), whole
        return out


def _rows(M) -> list:
    """An ``acb_mat`` as a list of rows."""
    return [[M[i, j] for j in range(M.ncols())] for i in range(M.nrows())]


def _determinant(A, dA, flint):
    """``(det A, d det A)`` of ball matrices ``A`` and ``dA = A'`` (rows), or None.

    Full pivoting on the midpoints' magnitudes; ``dA`` None gives ``(det A, None)``.
    None when a pivot before the last contains 0 (its sign and size undecided).
    """
    n = len(A)
    A = [row[:] for row in A]
    dA = [row[:] for row in dA] if dA is not None else None
    det, ddet = flint.acb(1), flint.acb(0)
    for k in range(n):
        best, pi, pj = None, k, k
        for i in range(k, n):
            row = A[i]
            for j in range(k, n):
                size = row[j].mid().abs_upper()
                if best is None or size > best:
                    best, pi, pj = size, i, j
        if pi != k:
            A[k], A[pi] = A[pi], A[k]
            if dA is not None:
                dA[k], dA[pi] = dA[pi], dA[k]
            det, ddet = -det, -ddet
        if pj != k:
            for M in (A, dA) if dA is not None else (A,):
                for row in M:
                    row[k], row[pj] = row[pj], row[k]
            det, ddet = -det, -ddet
        p = A[k][k]
        dp = dA[k][k] if dA is not None else None
        if dA is not None:
            ddet = ddet * p + det * dp
        det = det * p
        if k == n - 1:
            break
        if p.contains(0):
            return None
        top, dtop = A[k], (dA[k] if dA is not None else None)
        for i in range(k + 1, n):
            f = A[i][k] / p
            if dA is not None:
                df = (dA[i][k] - f * dp) / p
            row = A[i]
            drow = dA[i] if dA is not None else None
            for j in range(k + 1, n):
                row[j] = row[j] - f * top[j]
                if dA is not None:
                    drow[j] = drow[j] - df * top[j] - f * dtop[j]
    return det, (ddet if dA is not None else None)


# -- the eigenvalue count in ball arithmetic -----------------------------------------------
class ArbCount:
    """The Wittrick–Williams count ``J(omega)`` of an undamped model, proved in ball arithmetic.

    The dynamic stiffness ``K(omega)`` is assembled as :class:`symtmm.stiffness.StiffnessModel`
    does (its nodes, dofs and point elements), but in Arb balls; ``s{K}`` is the
    number of negative pivots of ``LDL^T`` (Sylvester's law of inertia), proved
    when no pivot ball contains 0. ``J = s{K}`` needs segments short enough that
    none reaches a clamped-clamped natural frequency below ``omega_design``: each
    piece is the beam's own element (any theory), within its ``safe_length``, as
    :class:`symtmm.stiffness.Mesh` cuts it.

    Rigid bodies and joints enter as :class:`symtmm.stiffness.Mesh` eliminates
    them: every freedom a combination of the free ones, with exact coefficients.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> c = ArbCount(Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),)), 100.0)
    >>> [c.count(w) for w in (9.8, 9.9, 39.4, 39.5)]       # roots at (n pi)^2 = 9.87, 39.48
    [0, 1, 1, 2]
    """

    def __init__(self, model: Model, omega_design: float):
        self.flint = require_flint()
        self._mesh(model.require_numeric(), float(omega_design))

    def _mesh(self, model, omega):
        """The stiffness model's mesh for the count up to ``omega`` (pieces short enough)."""
        from ..stiffness import StiffnessModel

        self.omega_design = omega
        self.sm = StiffnessModel(model, omega)
        self.arb = ArbDelta(self.sm.model)

    def _matrix(self, omega):
        arb = self.flint.arb
        lam = self.flint.acb(0, _arb_exact(omega, self.flint))
        w = _arb_exact(omega, self.flint)
        mesh = self.sm.mesh
        n = self.sm.size
        K = [[arb(0)] * n for _ in range(n)]
        for (_, seg, _, _), places in zip(mesh.segments, mesh.segment_places):
            U, _ = self.arb._segment(seg, lam, derivative=False)
            U = [[v.real for v in row] for row in U]       # real on the frequency axis
            _scatter_arb(K, _segment_stiffness_arb(U), places, self.flint)
        for places, element in mesh.point_places:
            S = element.stiffness(LAM).xreplace({LAM: sp.I * sp.Symbol("w", real=True)})
            local = [[_poly_arb(sp.re(sp.expand(S[i, j])), w, self.flint)
                      for j in range(S.cols)] for i in range(S.rows)]
            _scatter_arb(K, local, places, self.flint)
        for places, masses in mesh.body_places:
            # a rigid body adds lam**2 diag(M, J) = -omega**2 diag(M, J) on (Y_c, Theta_c)
            local = [[-(w * w) * to_arb(mass, self.flint) if i == j else arb(0)
                      for j in range(len(masses))] for i, mass in enumerate(masses)]
            _scatter_arb(K, local, places, self.flint)
        return K

    def count(self, omega) -> int | None:
        """``J(omega)``, or None if some pivot's sign is not proved at 1000 bits."""
        if float(omega) > self.omega_design * (1 + 1e-12):
            self._mesh(self.sm.model, 2.0 * float(omega))
        for bits in (128, 256, 512, 1024):
            with self.flint.ctx.workprec(bits):
                K = self._matrix(omega)
                negative = _ldl_negative(K, self.sm.bandwidth)
            if negative is not None:
                return negative
        return None


def _segment_stiffness_arb(U):
    """4x4 segment stiffness from a 4x4 transfer matrix of arb balls (see stiffness.py)."""
    U11 = [r[:2] for r in U[:2]]
    U12 = [r[2:] for r in U[:2]]
    U21 = [r[:2] for r in U[2:]]
    U22 = [r[2:] for r in U[2:]]
    det = U12[0][0] * U12[1][1] - U12[0][1] * U12[1][0]
    inv = [[U12[1][1] / det, -U12[0][1] / det], [-U12[1][0] / det, U12[0][0] / det]]

    def mul(X, Y):
        return [[X[i][0] * Y[0][j] + X[i][1] * Y[1][j] for j in range(2)] for i in range(2)]

    A = [[-v for v in row] for row in mul(inv, U11)]
    C = [[a + b for a, b in zip(r1, r2)] for r1, r2 in zip(U21, mul(U22, A))]
    E = mul(U22, inv)
    f0 = [A[i] + inv[i] for i in range(2)]       # rows M0, Q0
    f1 = [C[i] + E[i] for i in range(2)]         # rows M1, Q1
    return [f0[1], [-v for v in f0[0]], [-v for v in f1[1]], f1[0]]


def _scatter_arb(K, local, places, flint):
    """Add ``T^T local T``: ``places[i]`` is local freedom ``i`` as ``((index, exact), ...)``."""
    for i, ci in enumerate(places):
        for gi, ai in ci:
            ai = to_arb(ai, flint)
            for j, cj in enumerate(places):
                value = local[i][j]
                for gj, aj in cj:
                    K[gi][gj] = K[gi][gj] + ai * to_arb(aj, flint) * value


def _poly_arb(expr, w, flint):
    """A polynomial in ``w`` with exact coefficients, at the ball ``w``."""
    poly = sp.Poly(expr, sp.Symbol("w", real=True))
    value = flint.arb(0)
    for (k,), cf in poly.terms():
        value += to_arb(cf, flint) * w ** k
    return value


def _ldl_negative(K, band: int) -> int | None:
    """Negative pivots of banded ``LDL^T`` in balls; None if a pivot ball holds 0."""
    n = len(K)
    negative = 0
    for k in range(n):
        pivot = K[k][k]
        if pivot.contains(0):
            return None
        if pivot < 0:
            negative += 1
        top = min(n, k + band + 1)
        for i in range(k + 1, top):
            f = K[k][i] / pivot
            for j in range(i, top):
                K[i][j] = K[i][j] - f * K[k][j]
    return negative


# -- enclosures ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Enclosure:
    """A rigorous enclosure of one eigenvalue (or the reason there is none).

    Attributes
    ----------
    eigenvalue : Eigenvalue
        The reported value.
    real, imag : tuple of mpmath.mpf or None
        ``(lower, upper)`` bounds of the real and imaginary part.
    proof : str
        ``"exact"``, ``"sign change"``, ``"Krawczyk"``, ``"Rouche"``, ``"count"`` or ``"none"``.
    note : str
        Why there is no proof, when that is known (e.g. a multiple eigenvalue
        of a model the certified count does not handle).
    """

    eigenvalue: Eigenvalue
    real: tuple | None
    imag: tuple | None
    proof: str
    note: str = ""

    @property
    def certified(self) -> bool:
        return self.proof != "none"

    @property
    def radius(self):
        """Half the larger side of the enclosing box (None when not certified)."""
        if not self.certified:
            return None
        with mpmath.workdps(60):
            return max((hi - lo) / 2 for lo, hi in (self.real, self.imag))

    def contains(self, z) -> bool:
        """``z`` lies in the enclosure."""
        if not self.certified:
            return False
        if not isinstance(z, mpmath.mpc):
            with mpmath.workprec(1100):      # exact for ints, floats and complex
                z = mpmath.mpc(z)
        return (self.real[0] <= z.real <= self.real[1]
                and self.imag[0] <= z.imag <= self.imag[1])

    def to_dict(self, digits: int) -> dict:
        """JSON-ready: outward-rounded decimal bounds with ``digits + 3`` digits."""
        if not self.certified:
            out = {"certified": False, "proof": "none"}
            if self.note:
                out["note"] = self.note
            return out
        d = digits + 3
        return {"certified": True, "proof": self.proof,
                "real": [_decimal(self.real[0], d, -1), _decimal(self.real[1], d, +1)],
                "imag": [_decimal(self.imag[0], d, -1), _decimal(self.imag[1], d, +1)],
                "radius": _decimal(self.radius, 3, +1)}


def _decimal(x, digits: int, direction: int) -> str:
    """``x`` rounded down (-1) or up (+1) to ``digits`` significant digits, as a string.

    Examples
    --------
    >>> _decimal(mpmath.mpf(2) / 3, 4, -1), _decimal(mpmath.mpf(2) / 3, 4, +1)
    ('0.6666', '0.6667')
    >>> _decimal(mpmath.mpf(0), 4, 1)
    '0'
    """
    if x == 0:
        return "0"
    with mpmath.workdps(digits + 40):
        x = mpmath.mpf(x)
        e = int(mpmath.floor(mpmath.log10(abs(x))))
        scale = mpmath.mpf(10) ** (digits - 1 - e)
        q = mpmath.floor(x * scale) if direction < 0 else mpmath.ceil(x * scale)
        places = digits - 1 - e
    if places < 0:
        return str(int(q) * 10 ** (-places))
    return _fixed(int(q), places)


def _fixed(q: int, places: int) -> str:
    """The integer ``q`` scaled by ``10**-places`` as a plain decimal string."""
    sign = "-" if q < 0 else ""
    digits = str(abs(q)).rjust(places + 1, "0")
    if places == 0:
        return sign + digits
    return f"{sign}{digits[:-places]}.{digits[-places:]}"


class _Certifier:
    def __init__(self, model: Model, digits: int):
        self.flint = require_flint()
        self.model = model.require_numeric()
        self.digits = digits
        self.f = ArbDelta(self.model)
        self.ev = Evaluator(self.model)
        self.counts = 0

    @property
    def evaluations(self) -> int:
        return self.f.evaluations + self.ev.evaluations + self.counts

    def _bits(self, lam, extra_digits) -> int:
        lost = self.ev.digits_lost(complex(lam))
        return int(3.33 * (lost + extra_digits + 20)) + 32

    # -- sign changes ------------------------------------------------------------------
    def sign_change(self, lo, hi, axis: str):
        """Opposite signs of the real function Delta at the two ends (``axis`` "imag"/"real")."""
        acb = self.flint.acb
        for extra in (self.digits + 10, 2 * self.digits + 30, 4 * self.digits + 60):
            with self.flint.ctx.workprec(self._bits(hi if axis == "real" else 1j * hi, extra)):
                values = []
                for t in (lo, hi):
                    a = _arb_exact(t, self.flint)
                    lam = acb(0, a) if axis == "imag" else acb(a, 0)
                    values.append(self.f.value(lam).real)
                if (values[0] > 0 and values[1] < 0) or (values[0] < 0 and values[1] > 0):
                    return True
        return False

    # -- Krawczyk ------------------------------------------------------------------------
    def krawczyk(self, lam):
        """``(real bounds, imag bounds)`` of a proved simple zero near ``lam``, or None."""
        acb, arb = self.flint.acb, self.flint.arb
        size = float(abs(lam)) or 1.0
        lost = self.ev.digits_lost(complex(lam))
        parts = [abs(float(p)) for p in (lam.real, lam.imag) if p != 0]
        small = math.log10(size / min(parts)) if parts else 0.0
        k = max(math.ceil(lost) + 8, self.digits + 3 + math.ceil(small))
        for attempt in range(3):
            z = self._polish(lam, k + 10 + 10 * attempt)
            if z is None:
                return None
            r = mpmath.mpf(10) ** (-k) * size
            bits = int(3.33 * (lost + k + 25 + 10 * attempt)) + 32
            with self.flint.ctx.workprec(bits):
                zc = _acb_exact(z, self.flint)
                rad = _arb_exact(r, self.flint)
                box = acb(arb(zc.real, rad), arb(zc.imag, rad))
                fz, dfz = self.f.value_and_derivative(zc)
                Y = 1 / acb(dfz.mid())
                Y = acb(Y.mid())
                _, dfB = self.f.value_and_derivative(box)
                K = zc - Y * fz + (1 - Y * dfB) * (box - zc)
                if (K.real.lower() > box.real.lower() and K.real.upper() < box.real.upper()
                        and K.imag.lower() > box.imag.lower()
                        and K.imag.upper() < box.imag.upper()):
                    return ((_to_mpf(K.real.lower()), _to_mpf(K.real.upper())),
                            (_to_mpf(K.imag.lower()), _to_mpf(K.imag.upper())))
            k += 4
        return None

    def _polish(self, lam, extra):
        """Newton to ``10**-(extra)`` relative, at enough digits.

        ``Delta`` and ``Delta'`` are the midpoints of the ball evaluation (Arb's
        determinants are far faster than mpmath's once bodies enlarge ``R``); the
        proof comes afterwards, from balls around the result.
        """
        lost = math.ceil(self.ev.digits_lost(complex(lam)))
        dps = lost + extra + 20
        with mpmath.workdps(dps), self.flint.ctx.workprec(int(3.33 * dps) + 32):
            z = lam + 0      # (a copy at this precision; mpc(lam) would round an mpc)
            tol = abs(z) * mpmath.mpf(10) ** -(extra + 5)
            for _ in range(40):
                f0, d = self.f.value_and_derivative(_acb_exact(z, self.flint))
                f0, d = _mid_mpc(f0), _mid_mpc(d)
                if f0 == 0:
                    return z
                if d == 0:
                    return None
                step = f0 / d
                z -= step
                if abs(step) < tol:
                    return z
        return None

    # -- one eigenvalue ----------------------------------------------------------------------
    def enclose(self, e: Eigenvalue) -> Enclosure:
        lam = e.lam
        zero = mpmath.mpf(0)
        # what the solvers proved already: counts in balls at the ends of an undamped
        # bracket, opposite ball signs at the ends of a real one, Rouche's theorem on a box
        if e.proof == PROOFS["ball"] and e.bracket is not None and lam.real == 0 and lam != 0:
            lo, hi = sorted(e.bracket)
            return Enclosure(e, (zero, zero), (_exact_mpf(lo), _exact_mpf(hi)), "count")
        if e.proof == DAMPED_PROOFS["ball"] and e.bracket is not None:
            lo, hi = sorted(e.bracket)
            return Enclosure(e, (_exact_mpf(lo), _exact_mpf(hi)), (zero, zero), "sign change")
        if e.proof in (DAMPED_PROOFS["rouche"], DAMPED_PROOFS["rouche_idle"]):
            (a, b), (c, d) = e.bracket
            return Enclosure(e, (_exact_mpf(a), _exact_mpf(b)), (_exact_mpf(c), _exact_mpf(d)),
                             "Rouche")
        if e.multiplicity > 1:
            if lam == 0 and e.bracket == (0.0, 0.0):
                return Enclosure(e, (zero, zero), (zero, zero), "exact")
            if not self.model.damped and e.bracket is not None and lam.real == 0:
                # an m-fold root: exactly m eigenvalues (with multiplicity) in [lo, hi]
                lo, hi = sorted(e.bracket)
                try:
                    counter = ArbCount(self.model, 1.01 * float(hi))
                except ComputationError as exc:
                    return Enclosure(e, None, None, "none", str(exc))
                below, upto = counter.count(lo), counter.count(hi)
                self.counts += 2
                if below is not None and upto is not None and upto - below == e.multiplicity:
                    return Enclosure(e, (zero, zero), (_exact_mpf(lo), _exact_mpf(hi)),
                                     "count")
            return Enclosure(e, None, None, "none")
        bracket = e.bracket if isinstance(e.bracket, tuple) and len(e.bracket) == 2 \
            and not isinstance(e.bracket[0], tuple) else None
        if lam == 0 and bracket == (0.0, 0.0):
            return Enclosure(e, (zero, zero), (zero, zero), "exact")
        if bracket is not None and lam.imag == 0 and lam.real != 0:
            lo, hi = sorted(bracket)
            if self.sign_change(lo, hi, "real"):
                return Enclosure(e, (_exact_mpf(lo), _exact_mpf(hi)), (zero, zero), "sign change")
        if bracket is not None and lam.real == 0 and not self.model.damped and lam.imag != 0:
            lo, hi = sorted(bracket)
            if lo < hi and self.sign_change(lo, hi, "imag"):
                return Enclosure(e, (zero, zero), (_exact_mpf(lo), _exact_mpf(hi)), "sign change")
        box = self.krawczyk(lam)
        if box is None:
            return Enclosure(e, None, None, "none")
        return Enclosure(e, box[0], box[1], "Krawczyk")


def _exact_mpf(x):
    """``x`` as an mpmath number without rounding (``mpf()`` rounds to the working precision)."""
    if isinstance(x, mpmath.mpf):
        return x
    with mpmath.workprec(1100):
        return mpmath.mpf(x)


def _mid_mpc(ball):
    """The midpoint of an acb ball as an mpmath number (at the working precision)."""
    mid = ball.mid()
    return mpmath.mpc(_to_mpf(mid.real), _to_mpf(mid.imag))


def _to_mpf(ball):
    """An exact arb (a bound, radius 0) as an exact mpmath number."""
    man, exp = ball.man_exp()
    with mpmath.workprec(max(int(man).bit_length(), 53) + 10):
        return mpmath.ldexp(mpmath.mpf(int(man)), int(exp))


def certify(model: Model, spectrum: Spectrum) -> list:
    """Rigorous enclosures of the eigenvalues of ``spectrum`` (one :class:`Enclosure` each).

    Parameters
    ----------
    model : Model
        The model the spectrum belongs to.
    spectrum : Spectrum

    Raises
    ------
    ComputationError
        Without python-flint.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> enc = certify(pp, solve(pp, count=2, digits=12))
    >>> with mpmath.workdps(40):                   # the roots (n pi)^2 i, to 40 digits
    ...     inside = [e.contains(mpmath.mpc(0, (n * mpmath.pi) ** 2)) for e, n in zip(enc, (1, 2))]
    >>> [e.proof for e in enc], inside             # proved by the solver's counts already
    (['count', 'count'], [True, True])
    """
    certifier = _Certifier(model, spectrum.digits)
    out = Enclosures(certifier.enclose(e) for e in spectrum)
    out.evaluations = certifier.evaluations
    return out


class Enclosures(list):
    """The enclosures of a spectrum, with :attr:`evaluations`: the evaluations of Delta,
    R or the count (in balls or in mpmath) that proving them took."""

    evaluations: int = 0
