"""Independent reference for damped pinned-pinned beams (used by several test files).

A pinned-pinned beam with grounded spring/dashpots ``(x_i, k_i, c_i)``: its
characteristic function is ``det(I + diag(k_i + c_i lam) G(x_i, x_j) / EI)``
with the closed-form Green's function of the pinned-pinned beam. The undamped
roots are bracketed on the frequency axis, then followed with
``mpmath.findroot`` while the dashpots grow from 0 to their values (every
damped root starts as an undamped one). Nothing of symtmm is used.
"""

from __future__ import annotations

import math
from fractions import Fraction

import mpmath
import numpy as np


def pp_green(beta, a, b, L):
    """Green's function of ``w'''' - beta**4 w = delta(x - b)`` with w = w'' = 0 at 0, L.

    ``1/(D^4 - beta^4) = (1/(D^2 - beta^2) - 1/(D^2 + beta^2)) / (2 beta^2)`` with the
    Dirichlet Green's functions of both factors; even in beta -> i beta.
    """
    lo, hi = min(a, b), max(a, b)
    t1 = -mpmath.sinh(beta * lo) * mpmath.sinh(beta * (L - hi)) / mpmath.sinh(beta * L)
    t2 = mpmath.sin(beta * lo) * mpmath.sin(beta * (L - hi)) / mpmath.sin(beta * L)
    return (t1 + t2) / (2 * beta**3)


def pp_char(lam, EI, m, L, supports, kw=0):
    """``det(I + diag(k_i + c_i lam) G / EI)`` for grounded supports ``(x, k, c)`` (a
    foundation ``kw``: ``beta**4 = -(m lam**2 + kw) / EI``)."""
    beta = mpmath.root(-(m * lam**2 + kw) / EI, 4)
    n = len(supports)
    A = mpmath.matrix(n, n)
    for i, (xi, ki, ci) in enumerate(supports):
        for j, (xj, _, _) in enumerate(supports):
            A[i, j] = (1 if i == j else 0) + (ki + ci * lam) / EI * pp_green(beta, xi, xj, L)
    return mpmath.det(A)


def _pp_axis_function(EI, m, L, supports, kw=0):
    """The undamped characteristic function on lam = i omega in floats, without poles
    (above a foundation's cut-off ``sqrt(kw / m)``)."""
    EI, m, L, kw = float(EI), float(m), float(L), float(kw)
    sup = [(float(x), float(k)) for x, k, _ in supports]

    def green(beta, a, b):
        lo, hi = min(a, b), max(a, b)
        t1 = -math.sinh(beta * lo) * math.sinh(beta * (L - hi)) / math.sinh(beta * L)
        t2 = math.sin(beta * lo) * math.sin(beta * (L - hi))      # / sin(beta L)
        return t1, t2

    def f(w):
        beta = ((m * w * w - kw) / EI) ** 0.25
        s = math.sin(beta * L)
        A = np.empty((len(sup), len(sup)))
        for i, (xi, ki) in enumerate(sup):
            for j, (xj, _) in enumerate(sup):
                t1, t2 = green(beta, xi, xj)
                # times sin(beta L): the poles of G at sin(beta L) = 0 are gone
                A[i, j] = (s if i == j else 0.0) + ki / EI * (t1 * s + t2) / (2 * beta**3)
        return np.linalg.det(A) / s ** (len(sup) - 1)

    return f


def _mp(value):
    """An exact Fraction (or a number) as mpmath at the working precision."""
    if isinstance(value, Fraction):
        return mpmath.mpf(value.numerator) / value.denominator
    return mpmath.mpf(value)


def pp_damped_roots(EI, m, L, supports, omega_scan, steps=8, dps=30, kw=0, points=3000):
    """Roots (Im >= 0) of a pinned-pinned beam with grounded spring/dashpots ``(x, k, c)``
    (on a foundation ``kw``: its modes above the cut-off ``sqrt(kw / m)``).

    The undamped roots below ``omega_scan`` are bracketed by sign changes on the
    frequency axis (a grid of ``points``, finer than their spacing), then followed with
    mpmath.findroot while the dashpots grow from 0 to their values.
    """
    f = _pp_axis_function(EI, m, L, [(float(x), float(k), 0) for x, k, _ in supports], kw)
    low = math.sqrt(float(kw) / float(m)) * (1 + 1e-12) if kw else 1e-3
    grid = np.linspace(low, omega_scan, points)
    values = [f(w) for w in grid]
    starts = [0.5 * (a + b) for a, b, fa, fb in zip(grid, grid[1:], values, values[1:])
              if fa * fb < 0]
    roots = []
    with mpmath.workdps(dps):
        EI, m, L = _mp(EI), _mp(m), _mp(L)
        supports = [(_mp(x), _mp(k), _mp(c)) for x, k, c in supports]
        for w0 in starts:
            z = mpmath.mpc(0, w0)
            n = round(((float(m) * w0 * w0 - float(kw)) / float(EI)) ** 0.25 * float(L) / math.pi)
            if n and all(abs(mpmath.sin(n * mpmath.pi * x / L)) < 1e-12 for x, _, _ in supports):
                continue    # a pinned-pinned mode with a node at every support (G has a pole)
            for s in range(steps + 1):
                sup = [(x, k, c * mpmath.mpf(s) / steps) for x, k, c in supports]
                z = mpmath.findroot(lambda q, sup=sup: pp_char(q, EI, m, L, sup, _mp(kw)),
                                    (z, z + mpmath.mpc(1e-3, 1e-3)))
            roots.append(z)
    return roots



def ex4_numbers(dps: int = 40):
    """Example 4: ``(EI, k, c, sqrt(EI/m))`` at ``dps`` digits (m = L = 1)."""
    with mpmath.workdps(dps):
        sq = mpmath.mpf("146.2698") / mpmath.pi**2    # sqrt(EI/m)
        EI = sq**2
        return EI, 25 * EI, 5 * sq, sq


def ex4_reference(dps: int = 30):
    """Example 4 from the decoupled families (Laplacian of P3: 0, 1, 3), Im lam <= 1500:
    ``[(lam, family)]`` ascending by Im lam, to about ``dps`` digits."""
    EI, k, c, sq = ex4_numbers(dps + 10)
    with mpmath.workdps(dps + 10):
        x1 = Fraction(1, 4)
        out = []
        for n in range(1, 4):     # mu = 0: (n pi)^2 sqrt(EI/m), within 1500 for n <= 3
            out.append((mpmath.mpc(0, (n * mpmath.pi) ** 2 * sq), 0))
        for mu in (1, 3):
            sup = [(x1, mu * k, mu * c), (1 - x1, mu * k, mu * c)]
            for z in pp_damped_roots(EI, 1, 1, sup, 3000, dps=dps):
                if z.imag <= 1500 and -3000 <= z.real <= 0:
                    out.append((z, mu))
    return sorted(out, key=lambda t: t[0].imag)


def pp_root_above(n, EI, m, L, supports, dps=60):
    """The root of a pinned-pinned beam on grounded springs ``(x, k)`` just above mode ``n``.

    Springs raise the ``n``-th frequency ``(n pi)**2 sqrt(EI/m) / L**2`` by a little
    when they are weak: the root is bracketed between that frequency (a pole of the
    Green's function, excluded) and a point where the pole-free characteristic
    function has changed sign, then found by bisection-safe Anderson iteration at
    ``dps`` digits. For closely spaced roots of weakly coupled beams.
    """
    with mpmath.workdps(dps):
        EI, m, L = _mp(EI), _mp(m), _mp(L)
        sup = [(_mp(x), _mp(k)) for x, k in supports]
        w0 = (n * mpmath.pi) ** 2 * mpmath.sqrt(EI / m) / L**2

        def f(w):
            beta = mpmath.sqrt(w) * mpmath.root(m / EI, 4)
            s = mpmath.sin(beta * L)
            A = mpmath.matrix(len(sup), len(sup))
            for i, (xi, ki) in enumerate(sup):
                for j, (xj, _) in enumerate(sup):
                    lo, hi = min(xi, xj), max(xi, xj)
                    t1 = -mpmath.sinh(beta * lo) * mpmath.sinh(beta * (L - hi)) / \
                        mpmath.sinh(beta * L)
                    t2 = mpmath.sin(beta * lo) * mpmath.sin(beta * (L - hi))
                    A[i, j] = (s if i == j else 0) + ki / EI * (t1 * s + t2) / (2 * beta**3)
            return mpmath.det(A) / s ** (len(sup) - 1)

        lo = w0 * (1 + mpmath.mpf(10) ** -(dps - 8))
        f_lo = f(lo)
        t = mpmath.mpf(10) ** -(dps - 10)
        while True:
            hi = w0 * (1 + t)
            if f(hi) * f_lo < 0:
                break
            lo, f_lo = hi, f(hi)
            t *= 10
            if t > 0.1:
                raise ArithmeticError("no root above the mode")
        return mpmath.findroot(f, (lo, hi), solver="anderson")


_END_ROWS = {"free": (2, 3), "pinned": (0, 2), "clamped": (0, 1), "sliding": (1, 3)}


def beam_char(lam, EI, m, L, left, right, supports):
    """Characteristic determinant of a uniform beam with grounded supports ``(x, k, c)``.

    The classical piecewise solution: on each piece between supports ``Y = A cos bx +
    B sin bx + C cosh bx + D sinh bx`` (``b**4 = -m lam**2 / EI``, ``x`` from the piece's
    start); the end conditions (``Y, Y', Y'', Y'''`` rows, two zero at each end), and at
    each support ``Y, Y', Y''`` continuous and ``EI [Y''']`` equal to ``-(k + c lam) Y``.
    Nothing of symtmm is used; ``lam = 0`` is excluded (``b = 0``).
    """
    b = mpmath.root(-m * lam**2 / EI, 4)
    cuts = [mpmath.mpf(0)] + sorted(mpmath.mpf(x) for x, _, _ in supports) + [mpmath.mpf(L)]
    pieces = len(cuts) - 1
    n = 4 * pieces

    def rows(x):
        """Y, Y', Y'', Y''' of the four basis functions at local x."""
        c, s, ch, sh = mpmath.cos(b * x), mpmath.sin(b * x), mpmath.cosh(b * x), mpmath.sinh(b * x)
        return [[c, s, ch, sh], [-b * s, b * c, b * sh, b * ch],
                [-b**2 * c, -b**2 * s, b**2 * ch, b**2 * sh],
                [b**3 * s, -b**3 * c, b**3 * sh, b**3 * ch]]

    A = mpmath.matrix(n, n)
    r = 0
    start = rows(0)
    for k in _END_ROWS[left]:
        for j in range(4):
            A[r, j] = start[k][j]
        r += 1
    by_x = {mpmath.mpf(x): (k, c) for x, k, c in supports}
    for p in range(pieces - 1):
        end, nxt = rows(cuts[p + 1] - cuts[p]), rows(0)
        k, c = by_x[cuts[p + 1]]
        for d in range(4):
            for j in range(4):
                A[r, 4 * p + j] = end[d][j] * (EI if d == 3 else 1)
                A[r, 4 * (p + 1) + j] = -nxt[d][j] * (EI if d == 3 else 1)
            if d == 3:       # EI (Y'''(a-) - Y'''(a+)) = (k + c lam) Y(a)
                for j in range(4):
                    A[r, 4 * p + j] -= (k + c * lam) * end[0][j]
            r += 1
    end = rows(cuts[-1] - cuts[-2])
    for k in _END_ROWS[right]:
        for j in range(4):
            A[r, 4 * (pieces - 1) + j] = end[k][j]
        r += 1
    return mpmath.det(A)


def pp_roots_from_modes(modes, supports, steps=16, dps=40):
    """Roots of a pinned-pinned beam (EI = m = L = 1) with grounded ``(x, k, c)``: each
    followed from the bare beam's ``n``-th mode, ``i (n pi)**2``, as the supports grow from
    ``1/steps`` of their values, started at the modal first-order shift ``-(c + k/lam)
    phi(x)**2 / 2`` (``phi = sqrt(2) sin(n pi x)``); on ``sin(beta) det(...)``, which has no
    poles where the bare beam's modes sit."""
    out = []
    with mpmath.workdps(dps):
        sup = [(_mp(x), _mp(k), _mp(c)) for x, k, c in supports]
        for n in modes:
            w = (n * mpmath.pi) ** 2
            z = mpmath.mpc(0, w)
            for s in range(1, steps + 1):
                part = [(x, k * mpmath.mpf(s) / steps, c * mpmath.mpf(s) / steps)
                        for x, k, c in sup]
                if s == 1:
                    z = z - sum((c + k / z) * 2 * mpmath.sin(n * mpmath.pi * x) ** 2 / 2
                                for x, k, c in part)

                def f(q, part=part):
                    beta = mpmath.root(-q**2, 4)
                    return mpmath.sin(beta) * pp_char(q, 1, 1, 1, part)
                z = mpmath.findroot(f, (z, z + mpmath.mpc(1e-6, 1e-6)))
            out.append(z)
    return out


# a campaign's model (two of its beams): a soft beam on a foundation in axial tension,
# whose modes crowd 1e-6 and 6e-6 above its first, pinned near a stiff short beam whose
# spring carries the model's only dashpot; the balls of its band lose 2**460 along it
CROWDED_ON_FOUNDATION = """
[[beam]]
name = "b1"
EI = 256000.0
m = 0.00277
L = 0.0553
left = "pinned"
right = "clamped"

[[beam]]
name = "b2"
EI = 0.711
m = 3.11
L = 42.5
left = "pinned"
right = "sliding"
kw = 3610.0
N = 0.00194

[[spring]]
between = ["b1", "b2"]
x = 0.01383
k = 521000000.0
c = 0.308

[[spring]]
between = ["b1", "b2"]
x = 0.0
k = 410.0
"""
