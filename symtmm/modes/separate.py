"""The null space of ``R`` at an eigenvalue, apart from a close neighbour's.

The shape of an eigenvalue comes from the near-null space of ``R(lam)`` at its
estimate (:func:`~symtmm.numeric.linalg.null_space`). With the estimate ``delta``
from the root and the next root ``gap`` away, that space takes in about ``delta /
gap`` of the neighbour's vector: nothing to see where roots are far apart, the
whole of it where they agree to about as many digits as the estimate has. Two
nearly equal uncoupled beams are the plain case: their eigenvalues 1e-20 apart,
estimated to 1e-21, and one shape spread over both beams (and not orthogonal to
its neighbour's) although each mode moves one beam alone.

:func:`null_space_apart` measures that share (:func:`~symtmm.numeric.linalg.
separation_ratio`, about ``sigma_m / sigma_(m+1)`` of ``R``) and, where it exceeds
``10**-(D + MARGIN)``, refines the eigenvalue until it does not: inside its proved
bracket by regula falsi with the Anderson–Björck rule on ``Delta = det R`` (a simple
root changes its sign), else by the secant method from the estimate, in a private
mpmath context whose precision follows the digits the refinement needs. A multiple
eigenvalue (its roots agree to ``D + 20`` digits) is left as it is: its shapes are a
basis of the whole cluster's space.

Examples
--------
Two free-free beams, ``EI`` 1 and ``1 + 1e-10``, each held at mid-span by a weak spring:
the shapes of their two close eigenvalues near 22.37 each move one beam only.

>>> from symtmm.model import Beam, Model, Spring
>>> beams = (Beam("a", 1, 1, 1, left="free", right="free"),
...          Beam("b", "1 + 1e-10", 1, 1, left="free", right="free"))
>>> springs = (Spring("a", "ground", "1/2", "1e-8"), Spring("b", "ground", "1/2", "1e-8"))
>>> from symtmm.modes import mode_shapes
>>> modes = mode_shapes(Model(beams, springs=springs), count=6, points=11)
>>> [[round(float(max(abs(m.beams[b].Y))), 6) for b in "ab"] for m in modes][2:]
[[1.0, 0.0], [0.0, 1.0], [2.0, 0.0], [0.0, 2.0]]
"""

from __future__ import annotations

import math

from ..errors import ComputationError
from ..limits import MAX_DIGITS
from ..numeric import transfer
from ..numeric.arith import MP
from ..numeric.linalg import det, null_space

__all__ = ["null_space_apart", "foundation_digits", "MARGIN"]

#: Digits beyond the shape's own by which the neighbour's share must be below them.
MARGIN = 1

#: Digits a foundation may take from the wave numbers before the eigenvalue is refined
#: for them (:func:`foundation_digits`): below, as before it was counted, a shape's error
#: stays within a hundred rounding errors of the eigenvalue's digits.
FOUNDATION_DIGITS = 2.0

#: Rounds of refinement (each one as many digits further as the last one's share asks).
ROUNDS = 6


def null_space_apart(tp, eigenvalue, digits: int, real: bool, working_digits) -> tuple:
    """``(dps, ar, V, value)``: the null space ``V`` of ``R`` at ``value``, the eigenvalue
    refined as far as the shape's ``digits`` need, in the arithmetic ``ar`` of ``dps``
    digits.

    Parameters
    ----------
    tp : TransferPlan
    eigenvalue : Eigenvalue
    digits : int
        Digits the shape should carry.
    real : bool
        An undamped eigenvalue on the frequency axis (a real walk in ``lam**2``).
    working_digits : callable
        ``working_digits(tp, lam, k)``: the precision a walk at ``lam`` needs for ``k``
        digits (:func:`symtmm.modes.shapes.working_digits`).

    Raises
    ------
    ComputationError
        Where the eigenvalue cannot be refined inside its bracket, or would need more
        than :data:`~symtmm.limits.MAX_DIGITS` digits to tell the shape from its
        neighbour's.
    """
    mult = eigenvalue.multiplicity
    value = eigenvalue.lam
    known = max(int(eigenvalue.digits), 1)       # digits the current value is good to
    target = 10.0 ** -(digits + MARGIN)
    lost = foundation_digits(tp.model, value)
    for _ in range(ROUNDS):
        dps = working_digits(tp, value, max(digits, known))
        ar = MP.from_digits(dps)
        # (R and its null space where it was walked: Arb's matrices, where python-flint
        # is installed; only the null vectors come back to mpmath)
        walk, R = transfer.boundary_walked(tp, ar, value, real)
        with walk:
            V, ratio = null_space(walk, R, mult, separation=True)
        V = transfer.convert(walk, ar, V)
        # (and the shape's own error through the wave numbers, where a foundation takes
        # more than a few of the eigenvalue's digits from them: about 10**(lost - known);
        # counted below that, it refined every shape of every model, a 20-span beam's
        # ten 0.7 s -> past 60 s)
        if lost > FOUNDATION_DIGITS:
            ratio = max(ratio, 10.0 ** (lost - known))
        if ratio <= target or mult > 1 or value == 0:
            return dps, ar, V, value
        # the share falls with the estimate's error: as many more digits as it is above
        # the target, and a guard; the neighbour lies about 10**-known / ratio away, and
        # Delta between the two (a product of the distances to both) needs those digits too
        more = known + math.ceil(math.log10(ratio / target)) + 2
        apart = max(known + math.floor(math.log10(ratio)), 0)
        if more + apart > MAX_DIGITS:
            raise ComputationError(
                f"the mode shape at {eigenvalue} is not told apart from a neighbouring "
                f"eigenvalue's within {MAX_DIGITS} digits")
        value = _refined(tp, eigenvalue, value, more, real, working_digits, known, apart)
        known = more
    raise ComputationError(f"the mode shape at {eigenvalue} is not told apart from a "
                           "neighbouring eigenvalue's")


def foundation_digits(model, lam) -> float:
    """Digits of ``lam`` lost to the beams' wave numbers where a foundation nearly balances
    the inertia: ``m lam**2 + kw`` of each beam, whose error is ``2 |m lam**2|`` times
    ``lam``'s relative one, against ``|m lam**2 + kw|`` or ``EI / L**4``, the larger; 0
    where no beam cancels so.

    The null space's separation (:func:`~symtmm.numeric.linalg.separation_ratio`) does not
    see it: a beam 24,520 long of ``EI`` 2.8e-8 on a foundation (``kw / (EI b**4)`` of
    8e15) has its first three frequencies 3.5e-16 apart, and its shape at the 15-digit
    eigenvalue, from a well separated ``R``, was another combination of its waves (2 % off
    the closed form).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> b = Beam("b", "2.783e-8", "42.13", 24520, left="clamped", right="sliding", kw="9.911e-8")
    >>> round(foundation_digits(Model((b,)), 4.8502375382599245e-5j), 1)
    16.2
    >>> foundation_digits(Model((Beam("c", 1, 1, 1, left="clamped", right="free"),)), 3.5j)
    0.0
    """
    lam2 = complex(lam) ** 2
    worst = 0.0
    for beam in model.beams:
        kw = float(beam.kw)
        if kw == 0:
            continue
        inertia = float(beam.m) * lam2
        # (against EI / L**4 at least: a shape along the beam feels x = (m lam**2 + kw) L**4
        # / EI to within its error however small |x|, and a free beam's rigid modes on a
        # foundation sit at x = 0 exactly)
        total = max(abs(inertia + kw), float(beam.EI) / float(beam.L) ** 4)
        worst = max(worst, 2 * abs(inertia) / total)
    return math.log10(worst) if worst > 1 else 0.0


def _refined(tp, eigenvalue, value, k: int, real: bool, working_digits, known: int,
             apart: int):
    """The eigenvalue to ``k`` digits from ``value`` good to ``known``, a neighbour about
    ``10**-apart`` away (relative): regula falsi in its bracket, else the secant method."""
    ar = MP.from_digits(working_digits(tp, value, k + apart) + 5)
    ctx = ar.ctx
    tol = ctx.mpf(10) ** -k
    # (R walked as the shapes' own: in Arb balls where flint is installed, the midpoints
    # taken back; the determinant in the arithmetic)
    if real:
        def f(w):
            R = transfer.boundary_at(tp, ar, ctx.mpc(0, w), True)
            with ar:
                return det(ar, R)

        lo, hi = (eigenvalue.bracket or (None, None))
        if lo is not None and lo < hi:
            w = _regula_falsi(ctx, f, ctx.mpf(lo), ctx.mpf(hi), ctx.mpf(value.imag), tol)
            if w is not None:
                return ctx.mpc(0, w)
        z = _secant(ctx, f, ctx.mpf(value.imag), tol, eigenvalue, known)
        return ctx.mpc(0, z)

    def g(z):
        R = transfer.boundary_at(tp, ar, z, False)
        with ar:
            return det(ar, R)

    z = _secant(ctx, g, ctx.mpc(value), tol, eigenvalue, known)
    if eigenvalue.lam.real == 0 and abs(z.real) <= tol * abs(z):
        # (an eigenvalue the search put on the imaginary axis, a mode that does not move
        # the dashpots or one of an undamped part: a real part within the refinement's
        # error is its rounding, not a decay rate to print)
        z = ctx.mpc(0, z.imag)
    return z


def _regula_falsi(ctx, f, a, b, start, tol, steps: int = 200):
    """The root of ``f`` in ``[a, b]`` to relative ``tol`` (Anderson–Björck), first
    probing ``start``; None where ``f`` does not change sign over the bracket."""
    fa, fb = f(a), f(b)
    if fa == 0:
        return a
    if fb == 0:
        return b
    if (fa > 0) == (fb > 0):
        return None
    c = start if a < start < b else (a + b) / 2
    side = 0
    for _ in range(steps):
        fc = f(c)
        if fc == 0:
            return c
        if (fc > 0) == (fb > 0):
            if side > 0:
                m = 1 - fc / fb
                fa = fa * (m if m > 0 else ctx.mpf(0.5))
            b, fb, side = c, fc, 1
        else:
            if side < 0:
                m = 1 - fc / fa
                fb = fb * (m if m > 0 else ctx.mpf(0.5))
            a, fa, side = c, fc, -1
        if b - a <= tol * abs(c):
            return c
        c = b - fb * (b - a) / (fb - fa)
        # (a step onto an end closes nothing: a quarter of the width inside it)
        guard = (b - a) / 4
        c = min(max(c, a + min(guard, tol * abs(c) / 4)), b - min(guard, tol * abs(c) / 4))
    raise ComputationError("the refinement of an eigenvalue for its mode shape did not "
                           "converge")


def _secant(ctx, f, z, tol, eigenvalue, known: int, steps: int = 60):
    """The root of ``f`` next to ``z`` (good to ``known`` digits) to relative ``tol`` by the
    secant method."""
    # (a first step as long as the estimate's error: not across to the neighbour)
    h = abs(z) * ctx.mpf(10) ** -(known + 1) or tol
    z0, z1 = z, z + h
    f0, f1 = f(z0), f(z1)
    for _ in range(steps):
        if f1 == f0:
            return z1
        step = f1 * (z1 - z0) / (f1 - f0)
        z0, f0, z1 = z1, f1, z1 - step
        # (a value given with more digits than it holds may move by more than they
        # say; as far as another root, it may not)
        if abs(z1 - z) > abs(z) * ctx.mpf(10) ** -min(int(eigenvalue.digits) - 1, 8):
            raise ComputationError(f"the refinement of {eigenvalue} for its mode shape left "
                                   "the digits it is known to")
        if abs(step) <= tol * abs(z1):
            return z1
        f1 = f(z1)
    raise ComputationError("the refinement of an eigenvalue for its mode shape did not "
                           "converge")
