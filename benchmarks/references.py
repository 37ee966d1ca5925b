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
    ``(a, b, x, k)`` with ``b = None`` for a spring to the ground and ``x``
    strictly inside ``(0, L)`` (a number or an exact string such as ``"3/10"``).
    Beam ``i`` has the wave number ``nu_i = beta_i L = ratio_i Omega`` with
    ``Omega = beta_1 L``.
    """

    def __init__(self, beams, springs, L=1):
        self.beams = [(Fraction(str(EI)), Fraction(str(m)), left, right)
                      for EI, m, left, right in beams]
        self.L = Fraction(str(L))
        self.springs = [(a, b, Fraction(str(x)) / self.L, Fraction(str(k)))
                        for a, b, x, k in springs]
        if any(not 0 < x < 1 for _, _, x, _ in self.springs):
            raise ValueError("springs must lie strictly inside the span")
        cuts = sorted({x for _, _, x, _ in self.springs})
        self.points = [Fraction(0), *cuts, Fraction(1)]
        self.lengths = [b - a for a, b in zip(self.points, self.points[1:])]
        self.size = 4 * len(self.beams) * len(self.lengths)
        EI1, m1 = self.beams[0][:2]
        #: ``ratio_i**4``, from ``beta_i**4 = m_i omega**2 / EI_i``
        self.ratio4 = [(m * EI1) / (m1 * EI) for EI, m, _, _ in self.beams]

    def omega(self, Omega):
        """``omega = Omega**2 sqrt(EI_1/m_1) / L**2`` (mpmath)."""
        EI1, m1 = self.beams[0][:2]
        return Omega ** 2 * mpmath.sqrt(_mpf(EI1) / _mpf(m1)) / _mpf(self.L) ** 2

    def _column(self, beam: int, segment: int) -> int:
        return 4 * (beam * len(self.lengths) + segment)

    def entries(self, rows_at, kappa) -> list:
        """``(row, column, value)`` of the matrix.

        ``rows_at(i, xi)`` gives the :func:`_basis_rows` of beam ``i`` at the
        local coordinate ``xi`` (a fraction of ``L``), ``kappa(i, k)`` a spring
        ``k`` in beam ``i``'s units, ``k L**3 / (EI_i nu_i**3)``.
        """
        out, r = [], 0
        last = len(self.lengths) - 1
        for i, (_, _, left, right) in enumerate(self.beams):
            for seg, xi, kind in ((0, Fraction(0), left), (last, self.lengths[-1], right)):
                at = rows_at(i, xi)
                for d in _END_ROWS[kind]:
                    out += [(r, self._column(i, seg) + j, at[d][j]) for j in range(4)]
                    r += 1
        for s in range(1, last + 1):
            for i in range(len(self.beams)):
                minus, plus = rows_at(i, self.lengths[s - 1]), rows_at(i, Fraction(0))
                for d in range(4):
                    # Y, Y', Y'' continuous; the shear row also balances the springs
                    out += [(r, self._column(i, s - 1) + j, -minus[d][j]) for j in range(4)]
                    out += [(r, self._column(i, s) + j, plus[d][j]) for j in range(4)]
                    if d == 3:
                        out += self._spring_terms(r, i, s, rows_at, kappa)
                    r += 1
        if r != self.size:
            raise AssertionError("equations and unknowns differ in number")
        return out

    def _spring_terms(self, r, i, s, rows_at, kappa) -> list:
        """The springs at cut ``s`` in beam ``i``'s shear row.

        ``EI_i (Y_i'''(x+) - Y_i'''(x-)) = F_i`` with ``F_i = k (Y_other - Y_i)``
        (``-k Y_i`` to the ground), so the row gets ``+kappa Y_i - kappa Y_other``;
        each ``Y`` is taken at the right end of its beam's segment left of the cut.
        """
        out = []
        for a, b, x, k in self.springs:
            if x != self.points[s] or i not in (a, b):
                continue
            other = b if i == a else a
            kk = kappa(i, k)
            for beam, sign in ((i, 1), (other, -1)):
                if beam is None:
                    continue
                y = rows_at(beam, self.lengths[s - 1])[0]
                out += [(r, self._column(beam, s - 1) + j, sign * kk * y[j]) for j in range(4)]
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
