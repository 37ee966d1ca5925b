"""Shrinking a sign-change bracket: shared by the undamped and damped searches."""

from __future__ import annotations

import mpmath

from ..results import decimal_string

__all__ = ["anderson_bjorck", "bracket_done", "SEPARATION_DIGITS"]

#: Eigenvalues are told apart down to a relative distance of ``10**-(D + 2 +
#: SEPARATION_DIGITS)`` (``D`` the digits asked for); closer ones are reported as one
#: eigenvalue with their multiplicity, as exact multiple eigenvalues are.
SEPARATION_DIGITS = 20


def bracket_done(a, b, digits: int, scale=1) -> bool:
    """``[a, b]`` (mpmath numbers) is narrow enough to print ``digits`` digits.

    True when the relative width is below ``10**-(digits+2)`` and both ends round
    to the same ``digits`` significant digits, so the midpoint prints correctly
    rounded; or when the bracket is narrower than the working precision can
    resolve. ``scale`` is the size of the numbers when the bracket holds 0.

    Examples
    --------
    >>> with mpmath.workdps(30):
    ...     bracket_done(mpmath.mpf("1.23456781"), mpmath.mpf("1.23456782"), 5)
    True
    """
    limit = mpmath.mpf(10) ** -(mpmath.mp.dps - 5)
    if a <= 0 <= b:
        return b - a <= limit * scale
    width = (b - a) / min(abs(a), abs(b))
    if width > mpmath.mpf(10) ** (-(digits + 2)):
        return False
    return width <= limit or decimal_string(a, digits) == decimal_string(b, digits)


def anderson_bjorck(f, a, b, fa, fb, done, tol=None):
    """Shrink ``[a, b]`` with ``f(a) f(b) < 0`` until ``done(a, b)``.

    Regula falsi with the Anderson–Björck scaling of the end that stays (so
    neither end sticks), and a bisection whenever two steps together fail to
    halve the bracket: superlinear near a simple root, and at worst a bisection
    every other step.
    With ``tol`` (the width ``done`` waits for), each step lands at least
    ``tol/4`` inside the bracket: once the iterate is that close to the root,
    the next step falls on its other side and the bracket closes at once.

    Returns
    -------
    (a, b)
        The final bracket, or ``(c, c)`` where ``f(c)`` came out exactly 0.

    Examples
    --------
    >>> with mpmath.workdps(30):
    ...     lo, hi = anderson_bjorck(lambda x: x * x - 2, mpmath.mpf(1), mpmath.mpf(2),
    ...                              mpmath.mpf(-1), mpmath.mpf(2),
    ...                              lambda a, b: bracket_done(a, b, 25))
    ...     print(decimal_string((lo + hi) / 2, 25))
    1.414213562373095048801689
    """
    previous = b - a               # the bracket's width at the start of the previous step
    while not done(a, b):
        width = b - a
        c = b - fb * (b - a) / (fb - fa)
        if not a < c < b:
            c = (a + b) / 2
        if tol is not None and width > tol:
            c = min(max(c, a + tol / 4), b - tol / 4)
        fc = f(c)
        if fc == 0:
            return c, c
        if (fc > 0) == (fb > 0):
            m = 1 - fc / fb
            fa = fa * (m if m > 0 else mpmath.mpf(0.5))
            b, fb = c, fc
        else:
            m = 1 - fc / fa
            fb = fb * (m if m > 0 else mpmath.mpf(0.5))
            a, fa = c, fc
        # Regula falsi approaches a simple root from one side: the bracket need not
        # halve at every step while the scaled far end catches up. Bisect only when
        # two steps together have not halved it (bisecting every time would throw
        # the far end's scaling away and cost a bisection per step).
        stalled = b - a > 0.5 * previous
        previous = width
        if stalled:
            mid = (a + b) / 2
            fm = f(mid)
            if fm == 0:
                return mid, mid
            if (fm > 0) == (fb > 0):
                b, fb = mid, fm
            else:
                a, fa = mid, fm
    return a, b
