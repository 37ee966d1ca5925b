"""Reference eigenvalues from outside symtmm.

* :func:`clamped_clamped_omegas` -- the textbook frequency equation of a
  uniform clamped-clamped beam, ``cos(nu) cosh(nu) = 1`` (written here as
  ``cos(nu) - sech(nu) = 0``, which has the same roots and no exponential
  growth), solved with mpmath;
* :func:`pinned_pinned_omegas` -- ``nu = n pi``;
* :func:`chain_family_roots` -- the decoupled families of a chain of
  identical pinned-pinned beams joined by identical spring/dashpots at the
  same positions (the paper's examples 3 and 4). Writing the motion in the
  eigenvectors of the chain's graph Laplacian (eigenvalues ``mu``; 0, 1, 3
  for three beams) splits the system into single pinned-pinned beams with
  grounded spring/dashpots ``mu (k + c lam)``. Each is solved from the
  Green's function ``G`` of ``w'''' - beta**4 w = delta`` with
  ``w = w'' = 0`` at both ends: the characteristic function is
  ``det(I + (k + c lam) mu / EI G(x_i, x_j))``. Its undamped roots are
  bracketed by sign changes on a fine grid of the frequency axis and
  followed with :func:`mpmath.findroot` while the dashpots grow from 0 to
  their value (each damped root starts as an undamped one);
* :func:`global_matrix_omegas` -- natural frequencies of beams over a common
  span joined by springs, from the global coefficient matrix of the
  boundary-value problem (no transfer matrices): on every segment between
  cuts each beam's ``Y = a cos + b sin + c cosh + d sinh`` in local
  coordinates, boundary conditions at the ends, continuity of ``Y, Y', Y''``
  and the shear jump balancing the spring forces at every cut. Used for the
  paper's example 1 (:data:`EX1_BEAMS`, :data:`EX1_SPRINGS`), which has no
  closed form.

Nothing here calls symtmm: these functions take plain numbers.
"""

from __future__ import annotations

import functools
import itertools
import math
from fractions import Fraction

import mpmath
import numpy as np

__all__ = ["clamped_clamped_omegas", "pinned_pinned_omegas", "chain_family_roots",
           "laplacian_path_eigenvalues", "global_matrix_det", "global_matrix_omegas",
           "EX1_BEAMS", "EX1_SPRINGS", "EX1_METHOD", "ex1_omegas"]


def clamped_clamped_omegas(count: int, EI=1, m=1, L=1, dps: int = 40) -> list:
    """The first ``count`` natural frequencies of a clamped-clamped beam, at ``dps`` digits.

    Roots of ``cos(nu) = sech(nu)``: the n-th lies within ``sech(nu) < 1e-2`` of
    ``(n + 1/2) pi``; it is polished by the secant method from there and
    checked to lie in the bracket of its sign change.

    Examples
    --------
    >>> [mpmath.nstr(w, 12) for w in clamped_clamped_omegas(2)]   # Blevins: 22.3733, 61.6728
    ['22.3732854481', '61.6728228679']
    """
    out = []
    with mpmath.workdps(dps):
        scale = mpmath.sqrt(mpmath.mpf(EI) / m) / mpmath.mpf(L) ** 2

        def f(x):
            return mpmath.cos(x) - mpmath.sech(x)

        for n in range(1, count + 1):
            x0 = (n + mpmath.mpf(1) / 2) * mpmath.pi
            lo, hi = x0 - mpmath.mpf(1) / 2, x0 + mpmath.mpf(1) / 2
            if f(lo) * f(hi) >= 0:
                raise ArithmeticError(f"no sign change around root {n}")
            x = mpmath.findroot(f, (lo, hi), solver="anderson")
            if not lo < x < hi:
                raise ArithmeticError(f"root {n} left its bracket")
            out.append(x * x * scale)
    return out


def pinned_pinned_omegas(count: int, EI=1, m=1, L=1, dps: int = 40) -> list:
    """``(n pi)**2 sqrt(EI/m) / L**2`` for ``n = 1 .. count``.

    Examples
    --------
    >>> mpmath.nstr(pinned_pinned_omegas(1)[0], 10)
    '9.869604401'
    """
    with mpmath.workdps(dps):
        scale = mpmath.sqrt(mpmath.mpf(EI) / m) / mpmath.mpf(L) ** 2
        return [(n * mpmath.pi) ** 2 * scale for n in range(1, count + 1)]


def laplacian_path_eigenvalues(levels: int) -> list:
    """Eigenvalues of the graph Laplacian of a path with ``levels`` nodes:
    ``2 - 2 cos(j pi / levels)``, ``j = 0 .. levels - 1``.

    Examples
    --------
    >>> [round(v, 12) for v in laplacian_path_eigenvalues(3)]
    [0.0, 1.0, 3.0]
    """
    return [2 - 2 * math.cos(j * math.pi / levels) for j in range(levels)]


def _green(beta, a, b, L):
    # 1/(D^4 - beta^4) = (1/(D^2 - beta^2) - 1/(D^2 + beta^2)) / (2 beta^2), each factor
    # with its Dirichlet Green's function -sinh(beta x<) sinh(beta (L - x>))/(beta sinh beta L)
    # and -sin(beta x<) sin(beta (L - x>))/(beta sin beta L)
    lo, hi = min(a, b), max(a, b)
    t1 = -mpmath.sinh(beta * lo) * mpmath.sinh(beta * (L - hi)) / mpmath.sinh(beta * L)
    t2 = mpmath.sin(beta * lo) * mpmath.sin(beta * (L - hi)) / mpmath.sin(beta * L)
    return (t1 + t2) / (2 * beta ** 3)


def _family_function(EI, m, L, supports, mu):
    """``det(I + mu (k_j + c_j lam)/EI G(x_i, x_j)) * sin(beta L)`` (one pole removed)."""
    def f(lam):
        beta = mpmath.root(-m * lam ** 2 / EI, 4)
        n = len(supports)
        A = mpmath.matrix(n, n)
        for i, (xi, _, _) in enumerate(supports):
            for j, (xj, kj, cj) in enumerate(supports):
                A[i, j] = (1 if i == j else 0) + mu * (kj + cj * lam) / EI * _green(beta, xi, xj, L)
        return mpmath.det(A) * mpmath.sin(beta * L)
    return f


def _undamped_axis_roots(EI, m, L, supports, mu, omega_scan, points=4000):
    """Starting frequencies of the family's undamped roots below ``omega_scan``.

    The function ``det(s I + mu k/EI (s P + Q)) / s**(n-1)`` with ``s = sin(beta L)``
    (``G = P + Q/s``) is free of poles and real on the frequency axis.
    """
    EI, m, L = float(EI), float(m), float(L)
    sup = [(float(x), float(k)) for x, k, _ in supports]

    def g(w):
        beta = math.sqrt(w) * (m / EI) ** 0.25
        s = math.sin(beta * L)
        A = np.empty((len(sup), len(sup)))
        for i, (xi, _) in enumerate(sup):
            for j, (xj, kj) in enumerate(sup):
                lo, hi = min(xi, xj), max(xi, xj)
                p = -math.sinh(beta * lo) * math.sinh(beta * (L - hi)) / math.sinh(beta * L)
                q = math.sin(beta * lo) * math.sin(beta * (L - hi))
                A[i, j] = (s if i == j else 0.0) + mu * kj / EI * (s * p + q) / (2 * beta ** 3)
        return np.linalg.det(A) / s ** (len(sup) - 1)

    grid = np.linspace(omega_scan * 1e-4, omega_scan, points)
    values = [g(w) for w in grid]
    return [0.5 * (a + b) for a, b, fa, fb in zip(grid, grid[1:], values, values[1:])
            if fa * fb < 0]


def _polish(f, z):
    """A root of ``f`` near ``z`` by the secant method; the last step must be tiny."""
    z = mpmath.findroot(f, (z, z * (1 + mpmath.mpf(10) ** -6) + 1e-6j), verify=False)
    z2 = mpmath.findroot(f, (z, z * (1 + mpmath.mpf(10) ** -(mpmath.mp.dps // 2))),
                         verify=False)
    if abs(z2 - z) > mpmath.mpf(10) ** -(mpmath.mp.dps - 8) * abs(z):
        raise ArithmeticError(f"secant iteration does not settle near {z}")
    return z2


def chain_family_roots(levels: int, EI, m, L, positions, k, c, omega_max, sigma_max,
                       dps: int = 40, steps: int = 16) -> list:
    """Eigenvalues (``Im lam >= 0``) of a chain of identical pinned-pinned beams.

    Beam ``i`` and ``i + 1`` are joined by a spring ``k`` and a dashpot ``c``
    at each of ``positions``. Returns mpmath complex numbers at ``dps`` digits
    in ``-sigma_max <= Re lam <= 0``, ``0 <= Im lam <= omega_max``, sorted by
    ``Im lam``, with repetitions for eigenvalues shared by several families.

    Examples
    --------
    Example 4 of the paper, first roots:

    >>> s = (146.2698 / math.pi ** 2)
    >>> roots = chain_family_roots(3, s * s, 1, 1, [0.25, 0.75], 25 * s * s, 5 * s, 600, 1200,
    ...                            dps=20)
    >>> [mpmath.nstr(z, 8) for z in roots]     # doctest: +NORMALIZE_WHITESPACE
    ['(-246.35132 + 40.102275j)', '(0.0 + 146.2698j)', '(-74.095125 + 165.23226j)',
     '(-457.79837 + 461.55035j)', '(0.0 + 585.0792j)', '(-148.4833 + 586.17916j)']
    """
    out = []
    with mpmath.workdps(dps):
        EI_, m_, L_ = mpmath.mpf(EI), mpmath.mpf(m), mpmath.mpf(L)
        scale = mpmath.sqrt(EI_ / m_) / L_ ** 2
        for j, mu in enumerate(laplacian_path_eigenvalues(levels)):
            if abs(mu) < 1e-12:
                # in-phase family: the bare pinned-pinned beam
                n = 1
                while True:
                    w = (n * mpmath.pi) ** 2 * scale
                    if w > omega_max:
                        break
                    out.append(mpmath.mpc(0, w))
                    n += 1
                continue
            # at the working precision: the double mu is off by an ulp (2 - 2 cos(pi/3) is
            # 0.9999999999999998), which would cap the roots at 16 digits
            mu_ = 2 - 2 * mpmath.cos(j * mpmath.pi / levels)
            supports = [(mpmath.mpf(x), mpmath.mpf(k), mpmath.mpf(c)) for x in positions]
            # roots move as the dashpots grow: start from undamped roots well beyond the region
            starts = _undamped_axis_roots(EI, m, L, supports, mu,
                                          3 * max(omega_max, sigma_max))
            for w0 in starts:
                z = mpmath.mpc(0, w0)
                for s in range(steps + 1):
                    sup = [(x, kk, cc * s / steps) for x, kk, cc in supports]
                    f = _family_function(EI_, m_, L_, sup, mu_)
                    # (the function's scale varies, so findroot's absolute test on |f|
                    # is replaced by a relative one on the step: see _polish)
                    z = _polish(f, z)
                if z.imag < 0:
                    z = mpmath.conj(z)
                if -sigma_max <= z.real <= 1e-30 and 0 <= z.imag <= omega_max:
                    out.append(z)
    out.sort(key=lambda z: (float(z.imag), float(z.real)))
    return out



# -- global coefficient matrix ------------------------------------------------------------
#: The paper's example 1 (examples/paper_ex1_ff_cc.toml) as plain numbers:
#: ``(EI, m, left, right)`` per beam over ``[0, 1]`` ...
EX1_BEAMS = ((1, 1, "free", "free"), (1, 1, "clamped", "clamped"))
#: ... and ``(beam a, beam b or None for the ground, x, k)`` per spring.
EX1_SPRINGS = ((0, 1, "3/10", 100), (0, 1, "7/10", 100))

#: How :func:`ex1_omegas` obtains its values, for the report.
EX1_METHOD = (
    "global coefficient-matrix determinant, no transfer matrices and no symtmm "
    "(benchmarks/references.py: per beam and segment Y = a cos + b sin + c cosh + d sinh, "
    "end conditions, continuity of Y, Y', Y'' and the spring shear jump at each cut); roots "
    "bracketed by sign changes on a grid of step 1e-3 in Omega (the same cells at half the "
    "step), polished in mpmath at 40 digits and confirmed by a sign change at 60")

#: Derivative orders that vanish at an end of each kind.
_END_ROWS = {"free": (2, 3), "clamped": (0, 1), "pinned": (0, 2), "sliding": (1, 3)}


def _basis_rows(c, s, ch, sh):
    """Derivatives 0..3 of ``[cos, sin, cosh, sinh](nu xi)`` in ``xi``, each over ``nu**d``.

    In these wave-number units every entry is of the size of the functions
    themselves, whatever the mode.
    """
    return ((c, s, ch, sh), (-s, c, sh, ch), (-c, -s, ch, sh), (s, -c, sh, ch))


def _mpf(q: Fraction):
    """An exact fraction at the working precision."""
    return mpmath.mpf(q.numerator) / q.denominator


class _GlobalLayout:
    """Unknowns and equations of the global matrix: 4 unknowns per beam and segment.

    ``beams``: ``(EI, m, left, right)`` over ``[0, L]``; ``springs``:
    ``(a, b, x, k)`` with ``b = None`` for a spring to the ground and ``0 <= x <= L``
    (a number or an exact string such as ``"3/10"``); a spring at an end enters
    the shear condition of every end it holds there. Each beam is cut where its
    own springs act, so a chain of many levels keeps a few segments per beam. Beam
    ``i`` has the wave number ``nu_i = beta_i L = ratio_i Omega`` with
    ``Omega = beta_1 L``.
    """

    def __init__(self, beams, springs, L=1):
        self.beams = [(Fraction(str(EI)), Fraction(str(m)), left, right)
                      for EI, m, left, right in beams]
        self.L = Fraction(str(L))
        self.springs = [(a, b, Fraction(str(x)) / self.L, Fraction(str(k)))
                        for a, b, x, k in springs]
        if any(not 0 <= x <= 1 for _, _, x, _ in self.springs):
            raise ValueError("springs must lie on the span")
        #: per beam: its cut points (ends included) and its segment lengths
        self.points = [[Fraction(0), *sorted({x for a, b, x, _ in self.springs
                                              if i in (a, b) and 0 < x < 1}), Fraction(1)]
                       for i in range(len(self.beams))]
        self.lengths = [[b - a for a, b in itertools.pairwise(p)] for p in self.points]
        self._first = [0]
        for lengths in self.lengths:
            self._first.append(self._first[-1] + 4 * len(lengths))
        self.size = self._first[-1]
        EI1, m1 = self.beams[0][:2]
        #: ``ratio_i**4``, from ``beta_i**4 = m_i omega**2 / EI_i``
        self.ratio4 = [(m * EI1) / (m1 * EI) for EI, m, _, _ in self.beams]

    def omega(self, Omega):
        """``omega = Omega**2 sqrt(EI_1/m_1) / L**2`` (mpmath)."""
        EI1, m1 = self.beams[0][:2]
        return Omega ** 2 * mpmath.sqrt(_mpf(EI1) / _mpf(m1)) / _mpf(self.L) ** 2

    def _column(self, beam: int, segment: int) -> int:
        return self._first[beam] + 4 * segment

    def entries(self, rows_at, kappa) -> list:
        """``(row, column, value)`` of the matrix.

        ``rows_at(i, xi)`` gives the :func:`_basis_rows` of beam ``i`` at the
        local coordinate ``xi`` (a fraction of ``L``), ``kappa(i, k)`` a spring
        ``k`` in beam ``i``'s units, ``k L**3 / (EI_i nu_i**3)``.
        """
        out, r = [], 0
        for i, (_, _, left, right) in enumerate(self.beams):
            last = len(self.lengths[i]) - 1
            for seg, xi, kind, x, sign in ((0, Fraction(0), left, Fraction(0), 1),
                                           (last, self.lengths[i][-1], right, Fraction(1), -1)):
                at = rows_at(i, xi)
                for d in _END_ROWS[kind]:
                    out += [(r, self._column(i, seg) + j, sign * at[d][j]) for j in range(4)]
                    if d == 3:
                        # the shear at a left end is +F, at a right end -F (Q+ - Q- = F,
                        # no beam beyond the end): the interior jump with one side gone
                        out += self._spring_terms(r, i, x, rows_at, kappa)
                    r += 1
        for i in range(len(self.beams)):
            for s in range(1, len(self.lengths[i])):
                minus, plus = rows_at(i, self.lengths[i][s - 1]), rows_at(i, Fraction(0))
                for d in range(4):
                    # Y, Y', Y'' continuous; the shear row also balances the springs
                    out += [(r, self._column(i, s - 1) + j, -minus[d][j]) for j in range(4)]
                    out += [(r, self._column(i, s) + j, plus[d][j]) for j in range(4)]
                    if d == 3:
                        out += self._spring_terms(r, i, self.points[i][s], rows_at, kappa)
                    r += 1
        if r != self.size:
            raise AssertionError("equations and unknowns differ in number")
        return out

    def _spring_terms(self, r, i, x, rows_at, kappa) -> list:
        """The springs at ``x`` in beam ``i``'s shear row.

        ``EI_i (Y_i'''(x+) - Y_i'''(x-)) = F_i`` with ``F_i = k (Y_other - Y_i)``
        (``-k Y_i`` to the ground), so the row gets ``+kappa Y_i - kappa Y_other``;
        each ``Y`` is taken at the right end of its beam's segment left of the cut
        (every beam a spring touches is cut there), at a left end at the start of
        its first segment.
        """
        out = []
        for a, b, xs, k in self.springs:
            if xs != x or i not in (a, b):
                continue
            other = b if i == a else a
            kk = kappa(i, k)
            for beam, sign in ((i, 1), (other, -1)):
                if beam is None:
                    continue
                s = self.points[beam].index(x)
                seg, xi = (0, Fraction(0)) if s == 0 else (s - 1, self.lengths[beam][s - 1])
                y = rows_at(beam, xi)[0]
                out += [(r, self._column(beam, seg) + j, sign * kk * y[j]) for j in range(4)]
        return out


def _numpy_det(layout: _GlobalLayout, Omega) -> np.ndarray:
    """The global determinant on an array of ``Omega`` (real; double precision)."""
    Omega = np.atleast_1d(np.asarray(Omega, dtype=float))
    nus = [Omega * float(q) ** 0.25 for q in layout.ratio4]
    EIs = [float(b[0]) for b in layout.beams]
    L3 = float(layout.L) ** 3

    def rows_at(i, xi):
        z = nus[i] * float(xi)
        return _basis_rows(np.cos(z), np.sin(z), np.cosh(z), np.sinh(z))

    A = np.zeros((Omega.size, layout.size, layout.size))
    for r, c, v in layout.entries(rows_at, lambda i, k: float(k) * L3 / (EIs[i] * nus[i] ** 3)):
        A[:, r, c] += v
    return np.linalg.det(A)


def _mp_det(layout: _GlobalLayout, Omega):
    """The global determinant at one ``Omega``, at the working precision."""
    Omega = mpmath.mpf(Omega)
    nus = [Omega * mpmath.root(_mpf(q), 4) for q in layout.ratio4]
    EIs = [_mpf(b[0]) for b in layout.beams]
    L3 = _mpf(layout.L) ** 3
    memo = {}

    def rows_at(i, xi):
        if (i, xi) not in memo:     # each (beam, position) is asked for several times
            z = nus[i] * _mpf(xi)
            memo[i, xi] = _basis_rows(mpmath.cos(z), mpmath.sin(z), mpmath.cosh(z),
                                      mpmath.sinh(z))
        return memo[i, xi]

    A = [[mpmath.mpf(0)] * layout.size for _ in range(layout.size)]
    for r, c, v in layout.entries(rows_at, lambda i, k: _mpf(k) * L3 / (EIs[i] * nus[i] ** 3)):
        A[r][c] += v
    return _det(A)


def _det(A: list):
    """Determinant of a square list of mpmath rows by Gaussian elimination with
    partial pivoting (``A`` is overwritten).

    Written out rather than :func:`mpmath.det` because the global matrix is
    mostly zeros, which the elimination skips, and mpmath's matrix indexing
    costs more than the arithmetic at these sizes (five times faster here).

    Examples
    --------
    >>> _det([[mpmath.mpf(0), mpmath.mpf(2)], [mpmath.mpf(3), mpmath.mpf(4)]])
    mpf('-6.0')
    """
    n, det = len(A), mpmath.mpf(1)
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(A[i][k]))
        if A[p][k] == 0:
            return mpmath.mpf(0)
        if p != k:
            A[k], A[p] = A[p], A[k]
            det = -det
        pivot = A[k]
        det *= pivot[k]
        cols = [j for j in range(k + 1, n) if pivot[j] != 0]
        for i in range(k + 1, n):
            row = A[i]
            if row[k] == 0:
                continue
            f = row[k] / pivot[k]
            for j in cols:
                row[j] -= f * pivot[j]
    return det


def global_matrix_det(Omega, beams, springs, L=1):
    """The global coefficient determinant at ``Omega = beta_1 L``, in mpmath.

    ``beams`` and ``springs`` as for :func:`global_matrix_omegas`; the working
    precision is the caller's. Rows are scaled by positive factors (the
    ``d``-th derivative over ``nu**d``), so the sign is that of the plain
    determinant.

    Examples
    --------
    A clamped-clamped beam: zero where ``cos(Omega) cosh(Omega) = 1``.

    >>> with mpmath.workdps(30):
    ...     nu = mpmath.sqrt(clamped_clamped_omegas(1)[0])
    ...     bool(abs(global_matrix_det(nu, [(1, 1, "clamped", "clamped")], [])) < 1e-25)
    True
    """
    return _mp_det(_GlobalLayout(beams, springs, L), Omega)


def _sign_change_cells(layout, count: int, step: float, limit: float) -> list:
    """The first ``count`` cells ``(a, b)`` of the grid ``step, 2 step, ...`` over which
    the double-precision determinant changes sign (``Omega = 0`` is left out: the
    basis degenerates there)."""
    cells, first, chunk = [], 1, 4000
    while len(cells) < count:
        if first * step > limit:
            raise ArithmeticError(f"only {len(cells)} sign changes below Omega = {limit:g}")
        # points as step * index: the grid at half the step then holds these points exactly
        grid = step * np.arange(first, first + chunk + 1)
        values = _numpy_det(layout, grid)
        if np.any(values == 0):
            raise ArithmeticError("a grid point falls on a root: change the step")
        flips = np.nonzero(np.sign(values[:-1]) != np.sign(values[1:]))[0]
        cells += [(float(grid[i]), float(grid[i + 1])) for i in flips]
        first += chunk
    return cells[:count]


def _polish_cell(layout, a: float, b: float, dps: int):
    """The root in the grid cell ``(a, b)`` at ``dps`` digits, checked.

    Everything that decides the result is done in mpmath: the cell's sign change
    is confirmed there, the root is found by a bracketing method that cannot
    leave the cell (Anderson-Bjorck, in mpmath), 20 digits above ``dps`` for the
    cancellation in the determinant, and the determinant must change sign
    strictly across ``Omega (1 -+ 10**(8 - dps))`` at ``dps + 20`` digits. The
    double-precision grid only proposes the cell, so the value is the same on
    every machine whatever the last bits of its floating-point rounding (a
    double-precision narrowing once landed exactly on a zero of the rounded
    determinant on one machine and sent the secant method out of the cell).
    """
    with mpmath.workdps(dps + 20):
        lo, hi = mpmath.mpf(a), mpmath.mpf(b)
        f_lo, f_hi = _mp_det(layout, lo), _mp_det(layout, hi)
        if f_lo == 0 or f_hi == 0 or (f_lo > 0) == (f_hi > 0):
            raise ArithmeticError(f"no sign change over ({a}, {b}) at {dps + 20} digits")
        root = mpmath.findroot(lambda z: _mp_det(layout, z), (lo, hi), solver="anderson",
                               verify=False)
    with mpmath.workdps(dps + 20):
        eps = mpmath.mpf(10) ** (8 - dps) * root
        f_lo, f_hi = _mp_det(layout, root - eps), _mp_det(layout, root + eps)
    if not (a < root < b) or f_lo == 0 or f_hi == 0 or (f_lo > 0) == (f_hi > 0):
        raise ArithmeticError(f"the root in ({a}, {b}) is not confirmed at {dps} digits")
    with mpmath.workdps(dps):
        return +root


def global_matrix_omegas(beams, springs, count: int, L=1, dps: int = 40, step: float = 1e-3,
                         limit: float = 1e3) -> list:
    """The first ``count`` natural frequencies ``omega`` from the global coefficient matrix.

    Parameters
    ----------
    beams : sequence
        ``(EI, m, left, right)`` per beam, all over ``[0, L]``; ends ``"free"``,
        ``"clamped"``, ``"pinned"`` or ``"sliding"``.
    springs : sequence
        ``(a, b, x, k)``: a spring of stiffness ``k`` between beams ``a`` and
        ``b`` (indices; ``b = None`` for the ground) at ``0 < x < L``.
    count : int
        Frequencies wanted (non-zero ones: the grid starts at ``step``).
    dps : int
        Digits of the result.
    step : float
        Grid step in ``Omega = beta_1 L``. The grid is scanned again at half the
        step, whose sign changes must fall in the same cells: two roots in one
        cell cancel, so the step must be well below the closest pair (example
        1's closest, ``Omega`` 14.1372 and 14.1441, are seven steps apart).
    limit : float
        Largest ``Omega`` scanned.

    Returns
    -------
    list of mpmath.mpf
        ``omega = Omega**2 sqrt(EI_1/m_1) / L**2``, ascending, at ``dps`` digits.

    Notes
    -----
    Roots are bracketed by sign changes of the real determinant, so a root of
    even multiplicity (identical decoupled beams) is not seen: the method is
    for systems whose roots are simple, as example 1's are.

    Examples
    --------
    Two identical pinned-pinned beams joined by springs: the in-phase motion
    leaves the springs unstretched, ``Omega = n pi``.

    >>> pp = [(1, 1, "pinned", "pinned")] * 2
    >>> w = global_matrix_omegas(pp, [(0, 1, "3/10", 100), (0, 1, "7/10", 100)], 3, dps=30)
    >>> [mpmath.nstr(mpmath.sqrt(x) / mpmath.pi, 20) for x in w]
    ['1.0', '1.5805782374934040924', '2.0']
    """
    layout = _GlobalLayout(beams, springs, L)
    cells = _sign_change_cells(layout, count, step, limit)
    finer = _sign_change_cells(layout, count, step / 2, limit)
    if any(not (a <= fa < fb <= b) for (a, b), (fa, fb) in zip(cells, finer)):
        raise ArithmeticError("the sign changes move when the grid step is halved: "
                              "roots closer than the step")
    roots = [_polish_cell(layout, a, b, dps) for a, b in cells]
    with mpmath.workdps(dps):
        return [layout.omega(r) for r in roots]


@functools.cache
def ex1_omegas(count: int = 10, dps: int = 40) -> tuple:
    """The first ``count`` natural frequencies of the paper's example 1, at ``dps`` digits.

    :func:`global_matrix_omegas` of :data:`EX1_BEAMS` and :data:`EX1_SPRINGS`,
    computed once per process (the root-search and finite-element sections
    share it).

    Examples
    --------
    >>> [mpmath.nstr(mpmath.sqrt(w), 12) for w in ex1_omegas(10)[-2:]]   # the close pair
    ['14.1371654913', '14.1440577596']
    """
    return tuple(global_matrix_omegas(EX1_BEAMS, EX1_SPRINGS, count, dps=dps))


# -- chains of many levels: the global matrix in double precision, roots located by FE ---
def _sparse_sign_logdet(layout: _GlobalLayout, Omega: float) -> tuple:
    """``(sign, log|det|)`` of the global matrix at one real ``Omega`` (sparse LU).

    ``det A = det P_r det P_c prod diag U`` of SuperLU's ``P_r A P_c = L U`` (``L``
    with a unit diagonal); a permutation's sign is ``(-1)**(n - cycles)``.
    """
    import scipy.sparse
    import scipy.sparse.linalg

    nus = [Omega * float(q) ** 0.25 for q in layout.ratio4]
    EIs = [float(b[0]) for b in layout.beams]
    L3 = float(layout.L) ** 3
    memo = {}

    def rows_at(i, xi):
        if (i, xi) not in memo:
            z = nus[i] * float(xi)
            memo[i, xi] = _basis_rows(math.cos(z), math.sin(z), math.cosh(z), math.sinh(z))
        return memo[i, xi]

    r, c, v = zip(*layout.entries(rows_at, lambda i, k: float(k) * L3 / (EIs[i] * nus[i] ** 3)))
    A = scipy.sparse.csc_matrix((v, (r, c)), shape=(layout.size, layout.size))
    try:
        lu = scipy.sparse.linalg.splu(A)
    except RuntimeError:            # an exactly zero pivot: a root in double precision
        return 0.0, -math.inf
    d = lu.U.diagonal()
    if np.any(d == 0):
        return 0.0, -math.inf
    sign = float(np.prod(np.sign(d))) * _permutation_sign(lu.perm_r) * \
        _permutation_sign(lu.perm_c)
    return sign, float(np.sum(np.log(np.abs(d))))


def _permutation_sign(perm) -> int:
    """``+1`` or ``-1``: the sign of a permutation given as an index array.

    Examples
    --------
    >>> _permutation_sign([0, 1, 2]), _permutation_sign([1, 0, 2]), _permutation_sign([1, 2, 0])
    (1, -1, 1)
    """
    seen, cycles = [False] * len(perm), 0
    for start in range(len(perm)):
        if not seen[start]:
            cycles += 1
            j = start
            while not seen[j]:
                seen[j] = True
                j = perm[j]
    return -1 if (len(perm) - cycles) % 2 else 1


def located_omegas(beams, springs, guesses, L=1, width: float = 1e-3,
                   confirm: float = 1e-11) -> list:
    """Natural frequencies from the global matrix, each near an upper bound in ``guesses``.

    For models too large for :func:`global_matrix_omegas` (a chain of 50 levels
    has some 1000 unknowns: an mpmath determinant takes seconds, a grid scan
    thousands of them). ``guesses`` are frequencies from a conforming finite-element
    model (Rayleigh-Ritz: each is an upper bound of its exact frequency) accurate
    to well within ``width``. Each root is decided by the exact global matrix, in
    double precision (sparse LU; its segments are short, so every entry is of
    order one): a sign change over ``[g (1 - width), g (1 + 1e-6)]``, the same sign
    between consecutive brackets, Brent's method inside, and a sign change
    across ``root (1 -+ confirm)``.

    Parameters
    ----------
    beams, springs, L
        As for :func:`global_matrix_omegas`.
    guesses : sequence of float
        Frequencies ``omega``, ascending.
    width : float
        Relative width of the bracket below each guess (narrowed to half the gap
        between close guesses).
    confirm : float
        Relative half-width of the final sign change: the accuracy claimed.

    Returns
    -------
    list of mpmath.mpf
        ``omega`` of each root (as the double-precision root).

    Examples
    --------
    Two identical pinned-pinned beams joined by springs: the in-phase ones are
    ``Omega = n pi``:

    >>> pp = [(1, 1, "pinned", "pinned")] * 2
    >>> w = located_omegas(pp, [(0, 1, "3/10", 100), (0, 1, "7/10", 100)], [9.8697, 24.66])
    >>> [round(float(mpmath.sqrt(x) / mpmath.pi), 10) for x in w]
    [1.0, 1.5805782375]
    """
    import scipy.optimize

    layout = _GlobalLayout(beams, springs, L)
    EI1, m1 = (float(v) for v in layout.beams[0][:2])
    scale = math.sqrt(EI1 / m1) / float(layout.L) ** 2

    def Omega(w):
        return math.sqrt(w / scale)

    g = [Omega(w) for w in guesses]
    brackets = []
    for i, x in enumerate(g):
        lo = x * (1 - width)
        if i:
            lo = max(lo, 0.5 * (g[i - 1] + x))
        brackets.append((lo, x * (1 + 1e-6)))
    if any(a[1] >= b[0] for a, b in itertools.pairwise(brackets)):
        raise ArithmeticError("guesses closer than 1e-6: refine the finite-element model")
    signs = [[_sparse_sign_logdet(layout, e)[0] for e in b] for b in brackets]
    for i, ((sa, sb), (a, b)) in enumerate(zip(signs, brackets)):
        if sa * sb >= 0:
            raise ArithmeticError(f"no sign change below guess {i + 1} "
                                  f"(Omega in [{a:.12g}, {b:.12g}])")
        if i and signs[i - 1][1] != sa:
            raise ArithmeticError(f"a sign change between guesses {i} and {i + 1}")
    roots = []
    for a, b in brackets:
        _, ref = _sparse_sign_logdet(layout, b)

        def f(x, ref=ref):
            s, la = _sparse_sign_logdet(layout, x)
            return s * math.exp(min(la - ref, 700.0))

        x = scipy.optimize.brentq(f, a, b, xtol=1e-15 * b, rtol=1e-15)
        lo, hi = f(x * (1 - confirm)), f(x * (1 + confirm))
        if lo * hi >= 0:
            raise ArithmeticError(f"the root near Omega = {x:.15g} is not confirmed to "
                                  f"{confirm:g}")
        roots.append(x)
    with mpmath.workdps(30):
        return [layout.omega(mpmath.mpf(x)) for x in roots]


# -- a uniform beam over equal pinned spans ------------------------------------------------
def multispan_function(nu, j: int, spans: int):
    """``F_j(nu)``: zero at the frequencies of band family ``j`` of a beam over ``spans`` spans.

    A uniform beam, pinned at both ends and at ``spans - 1`` equally spaced
    intermediate supports. On a span ``0 <= x <= l`` with ``Y = 0`` at both ends
    and end slopes ``theta_0, theta_1``, the curvatures are ``Y''(0) = p theta_0 +
    q theta_1`` and ``Y''(l) = -(q theta_0 + p theta_1)``, with (``nu = beta l``)

        p = beta (sin nu cosh nu - cos nu sinh nu) / (cos nu cosh nu - 1)
        q = -beta (sin nu - sinh nu) / (cos nu cosh nu - 1)

    (solve ``Y = A cos + B sin + C cosh + D sinh`` for the four end values).
    Continuity of the slope and of the moment at support ``k`` gives
    ``q theta_(k-1) + 2 p theta_k + q theta_(k+1) = 0`` and the pinned outer ends
    ``p theta_0 + q theta_1 = 0 = q theta_(N-1) + p theta_N``, solved by
    ``theta_k = cos(k mu)`` with ``sin(N mu) = 0`` and ``cos mu = -p/q`` (the
    classical propagation constant of a periodically supported beam):
    ``mu = j pi / N``, ``j = 1 .. N - 1``, and

        F_j(nu) = sin nu cosh nu - cos nu sinh nu - cos(j pi / N) (sin nu - sinh nu).

    The remaining frequencies, one per band, are the pinned-pinned ones of a
    single span, ``nu = n pi`` (``sin nu = 0``: every span moves as a
    pinned-pinned beam, neighbours in opposite or equal phase).

    Examples
    --------
    Two spans: ``j = 1`` gives ``p = 0``, spans pinned-clamped, ``tan nu = tanh nu``:

    >>> with mpmath.workdps(20):
    ...     nu = mpmath.findroot(lambda v: multispan_function(v, 1, 2), 3.9)
    ...     print(mpmath.nstr(nu, 15), mpmath.nstr(mpmath.tan(nu) - mpmath.tanh(nu), 3))
    3.92660231204792 0.0
    """
    c = mpmath.cos(j * mpmath.pi / spans)
    return (mpmath.sin(nu) * mpmath.cosh(nu) - mpmath.cos(nu) * mpmath.sinh(nu)
            - c * (mpmath.sin(nu) - mpmath.sinh(nu)))


def multispan_omegas(spans: int, count: int, EI=1, m=1, l=1, dps: int = 40) -> list:
    """The lowest ``count`` natural frequencies of a uniform beam over equal pinned spans.

    Every band ``n pi < nu < nu_cc`` (``nu_cc`` the ``n``-th clamped-clamped root,
    where ``cos mu = (-1)**(n+1)``) holds ``nu = n pi`` and one root of each
    :func:`multispan_function`, ``j = 1 .. spans - 1``: ``spans`` roots. Each is
    bracketed by a sign change over the band and found by the Anderson-Björck
    method in mpmath; the frequencies are ``nu**2 sqrt(EI/m) / l**2``.

    Examples
    --------
    Two spans: ``pi`` (pinned-pinned spans), then pinned-clamped spans:

    >>> [mpmath.nstr(mpmath.sqrt(w), 10) for w in multispan_omegas(2, 3, dps=20)]
    ['3.141592654', '3.926602312', '6.283185307']
    """
    out = []
    with mpmath.workdps(dps):
        cc = [mpmath.findroot(lambda x: mpmath.cos(x) - mpmath.sech(x),
                              (n + mpmath.mpf(1) / 2) * mpmath.pi) for n in range(1, count + 2)]
        band = 1
        while len(out) < count:
            lo, hi = band * mpmath.pi, cc[band - 1]
            nus = [lo]
            for j in range(1, spans):
                f = functools.partial(multispan_function, j=j, spans=spans)
                a, b = lo * (1 + mpmath.mpf(10) ** (5 - dps)), hi
                if f(a) * f(b) >= 0:
                    raise ArithmeticError(f"no sign change of F_{j} in band {band}")
                nus.append(mpmath.findroot(f, (a, b), solver="anderson"))
            out += sorted(nus)
            band += 1
        scale = mpmath.sqrt(mpmath.mpf(EI) / m) / mpmath.mpf(l) ** 2
        return [nu * nu * scale for nu in out[:count]]
