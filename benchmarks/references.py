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
  their value (each damped root starts as an undamped one).

Nothing here calls symtmm: these functions take plain numbers.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np

__all__ = ["clamped_clamped_omegas", "pinned_pinned_omegas", "chain_family_roots",
           "laplacian_path_eigenvalues"]


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
        for mu in laplacian_path_eigenvalues(levels):
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
            mu_ = mpmath.mpf(mu)
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
