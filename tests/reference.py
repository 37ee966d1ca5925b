"""Reference problems with independently known eigenvalues.

The classical frequency equations of a uniform Euler–Bernoulli beam, written
out from the textbooks (Blevins, *Formulas for natural frequency and mode
shape*, table 8-1), not derived by symtmm. Roots are found here with mpmath
from starting points on a grid: nothing of symtmm is used.
"""

from __future__ import annotations

import mpmath

# (left, right) -> (frequency equation f(nu) = 0 in nu = beta L, number of rigid-body modes).
# The textbook forms cos(nu)cosh(nu) = +-1 and tan(nu) = +-tanh(nu) are divided by
# cosh(nu) (and multiplied by cos(nu)): the same roots, without poles and without
# the exponential growth that would swamp high modes.
FREQUENCY_EQUATIONS = {
    ("free", "free"): (lambda x: mpmath.cos(x) - mpmath.sech(x), 2),
    ("clamped", "clamped"): (lambda x: mpmath.cos(x) - mpmath.sech(x), 0),
    ("clamped", "free"): (lambda x: mpmath.cos(x) + mpmath.sech(x), 0),
    ("pinned", "pinned"): (lambda x: mpmath.sin(x), 0),
    ("clamped", "pinned"): (lambda x: mpmath.sin(x) - mpmath.cos(x) * mpmath.tanh(x), 0),
    ("free", "pinned"): (lambda x: mpmath.sin(x) - mpmath.cos(x) * mpmath.tanh(x), 1),
    ("sliding", "sliding"): (lambda x: mpmath.sin(x), 1),
    ("pinned", "sliding"): (lambda x: mpmath.cos(x), 0),
    ("clamped", "sliding"): (lambda x: mpmath.sin(x) + mpmath.cos(x) * mpmath.tanh(x), 0),
    ("free", "sliding"): (lambda x: mpmath.sin(x) + mpmath.cos(x) * mpmath.tanh(x), 1),
}


def classical_roots(left: str, right: str, count: int, dps: int = 40) -> list:
    """The first ``count`` positive roots nu = beta L of the classical equation.

    Roots are bracketed by sign changes on a fine grid (step 1/64, far below
    the root spacing of about pi) and polished by mpmath's bracketing solver.
    """
    key = (left, right) if (left, right) in FREQUENCY_EQUATIONS else (right, left)
    f, _ = FREQUENCY_EQUATIONS[key]
    roots = []
    with mpmath.workdps(dps):
        step = mpmath.mpf(1) / 64
        x = step
        fx = f(x)
        while len(roots) < count:
            y = x + step
            fy = f(y)
            if fx == 0:
                roots.append(x)
            elif fx * fy < 0:
                roots.append(mpmath.findroot(f, (x, y), solver="anderson"))
            x, fx = y, fy
    return roots[:count]


def rigid_modes(left: str, right: str) -> int:
    key = (left, right) if (left, right) in FREQUENCY_EQUATIONS else (right, left)
    return FREQUENCY_EQUATIONS[key][1]
