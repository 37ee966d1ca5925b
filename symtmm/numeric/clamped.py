"""``J0``: the clamped-clamped eigenvalues of a plan's pieces below a frequency.

Wittrick and Williams count the natural frequencies below ``omega`` as ``J(omega) =
J0(omega) + s{K(omega)}``: the negative eigenvalues of the dynamic stiffness ``K``, plus
the eigenvalues of every piece with both its ends held, which ``K`` does not see (their
modes leave the nodes still). The stiffness plans keep ``J0 = 0`` by cutting every piece
short of its first clamped-clamped frequency (:mod:`symtmm.numeric.plan`), which at a
beam's ``n``-th mode takes about ``n`` pieces. A plan for counts only
(:class:`~symtmm.numeric.plan.StiffnessPlan`'s ``clamped``) lets its long
Euler–Bernoulli pieces, and its chains of short pieces of the other theories condensed
by doubling, pass those frequencies, and its counts add them here.

For a uniform Euler–Bernoulli piece clamped at both ends (Williams and Wittrick, 1970),
with ``nu**4 = (m omega**2 - kw) l**4 / EI``, ``i`` the integer part of ``nu / pi`` and
``s`` the sign of ``1 - cosh nu cos nu``::

    J0 = i - (1 - (-1)**i s) / 2          (0 where nu**4 <= 0)

``J0`` is continuous where ``nu / pi`` passes an integer (``|1 - cosh nu cos nu|`` is near
``cosh nu`` there), so only the sign must be decided: it changes at the clamped-clamped
frequencies, where ``K`` has a pole and its inertia jumps by as much the other way.
Each arithmetic decides it as it decides a pivot (:meth:`~symtmm.numeric.arith.
Arithmetic.decide`): doubles and mpmath against the rounding of ``cosh nu cos nu``,
balls where the ball of ``1 - cosh nu cos nu`` keeps away from zero. A condensed
chain's ``J0`` is its doublings' own (:func:`_chain_counts`).
"""

from __future__ import annotations

import math

import numpy as np

from ..expr import exact_float
from .arith import Arithmetic
from .segments import eb_constants

__all__ = ["clamped_counts", "clamped_kinds", "BELOW_FIRST"]

#: ``nu**4`` below which a piece has no clamped-clamped eigenvalue: ``4.7``\ ``**4``, below
#: the first root ``4.7300407...`` of ``1 - cosh nu cos nu``.
BELOW_FIRST = 4.7 ** 4


def clamped_kinds(plan) -> list:
    """``(kind index, multiplicity)`` of the kinds of ``plan`` that may pass a
    clamped-clamped frequency in its range: Euler–Bernoulli ones whose ``m radius - kw``
    times ``l**4 / EI`` is at least :data:`BELOW_FIRST`, and condensed chains; empty for a
    plan that is not ``clamped``, whose pieces all stay below theirs. Kept on the plan."""
    cached = plan.__dict__.get("_clamped_kinds")
    if cached is None:
        cached = []
        if plan.clamped:
            for j, (family, consts) in enumerate(plan.kinds):
                if family == "condensed":
                    cached.append((j, int(plan.multiplicity[j])))
                    continue
                if family != "eb":
                    continue
                EI, m, l, kw = (exact_float(c) for c in consts)
                if (m * plan.radius - kw) * l ** 4 / EI >= BELOW_FIRST * (1 - 1e-9):
                    cached.append((j, int(plan.multiplicity[j])))
        plan.__dict__["_clamped_kinds"] = cached
    return cached


def clamped_counts(plan, ar: Arithmetic, lam2) -> np.ndarray | None:
    """``J0`` per point of real ``lam2 = -omega**2`` ``(B,)`` in ``ar``: the sum over the
    pieces of ``plan`` of their clamped-clamped eigenvalues below ``omega``, ``-1`` where
    ``ar`` does not decide it; None where no piece can have one in the plan's range.

    Examples
    --------
    A plan for counts of a pinned-pinned beam at its 40th mode: long pieces, each past
    several of its clamped-clamped frequencies; the counts with them are the closed form's
    ``n`` below ``(n pi)**2``.

    >>> from symtmm.model import Beam, Model
    >>> from symtmm.numeric.arith import DOUBLE
    >>> from symtmm.numeric.plan import StiffnessPlan
    >>> from symtmm.numeric.stiffness import factor
    >>> pp = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    >>> plan = StiffnessPlan(pp, (41 * math.pi) ** 4, clamped=True)
    >>> plan.n, int(plan.multiplicity.sum())      # two pieces, 64.4 pi each
    (4, 2)
    >>> w = np.array([(n + 0.3) * math.pi for n in (10, 25, 39)]) ** 2
    >>> clamped_counts(plan, DOUBLE, -w * w).tolist(), factor(plan, DOUBLE, -w * w).counts().tolist()
    ([8, 24, 38], [10, 25, 39])
    """
    kinds = clamped_kinds(plan)
    if not kinds:
        return None
    lam2 = np.asarray(lam2)
    B = lam2.shape[0]
    out = np.zeros(B, dtype=np.int64)
    undecided = np.zeros(B, dtype=bool)
    chains = [(j, mult) for j, mult in kinds if plan.kinds[j][0] == "condensed"]
    kinds = [(j, mult) for j, mult in kinds if plan.kinds[j][0] == "eb"]
    for j, mult in chains:
        j0, sure = _chain_counts(plan, ar, j, lam2)
        out += mult * j0
        undecided |= ~sure
    with ar:
        consts = eb_constants(ar, [plan.kinds[j][1] for j, _ in kinds])
        for k, (_, mult) in enumerate(kinds):
            A, F = consts["A"][k], consts["F"][k]
            x = -(A * lam2 + F)                      # nu**4 per point
            rough = ar.to_complex(np.asarray(x)).real.reshape(-1)
            at = np.nonzero(rough >= BELOW_FIRST)[0]
            if at.size == 0:
                continue
            # (x > 0 there: its real root, real cosines; mpmath's root4 is complex)
            nu = ar.sqrt(ar.sqrt(np.asarray(x)[at]))
            cos, _ = ar.cos_sin(nu)
            cosh, _ = ar.cosh_sinh(nu)
            phi = 1 - cosh * cos
            nus = ar.to_complex(nu).real.reshape(-1)
            # (the rounding of cosh nu cos nu, and of nu's cosine: nu times the ulp)
            scale = np.asarray(ar.upper(cosh), dtype=float) * (1 + nus) \
                if ar.needs_scale else np.ones(at.size)
            sign, decided = ar.decide(phi, scale, 1)
            i = np.floor(nus / math.pi).astype(np.int64)
            j0 = i - (1 - np.where(i % 2 == 0, 1, -1) * sign.astype(np.int64)) // 2
            out[at] += mult * j0
            undecided[at] |= ~decided
    return np.where(undecided, -1, out)


def _chain_counts(plan, ar: Arithmetic, j: int, lam2) -> tuple:
    """``(J0, decided)`` per point of the condensed chain of kind ``j`` of ``plan``: its
    ``2**d`` short pieces (each below its clamped-clamped frequencies) joined by doubling,
    each doubling's middle node ``S`` adding its negative eigenvalues once per pair of that
    level (``J0 = sum_j 2**(d-1-j) s{S_j}``, Wittrick–Williams on the pair clamped at both
    ends), decided as pivots are (:meth:`~symtmm.numeric.arith.Arithmetic.decide`)."""
    from .arith import memo
    from .segments import condensed_stiffness, kind_tables
    from .stiffness import stiffness_values
    [(_, table)] = memo(plan, ar, f"chain {j}", lambda: kind_tables(ar, [plan.kinds[j]]))
    B = lam2.shape[0]
    with ar:
        D, det = stiffness_values(ar, [table["inner"]], lam2, None, plan.long)
        size = math.isqrt(D.shape[1])
        middles: list = []
        condensed_stiffness(ar, D.reshape(B, size, size), det[:, 0], table["doublings"],
                            middles)
        d = len(middles)
        j0 = np.zeros(B, dtype=np.int64)
        sure = np.ones(B, dtype=bool)
        for level, S in enumerate(middles):
            negative, decided = _negative_eigenvalues(ar, S)
            j0 += 2 ** (d - 1 - level) * negative
            sure &= decided
    return j0, sure


def _negative_eigenvalues(ar: Arithmetic, S) -> tuple:
    """``(count, decided)`` per point of the negative eigenvalues of the real symmetric
    ``S`` (nested lists of arrays), by the signs of its leading minors (Sylvester): the
    pivots of its ``LDL^T``, each decided against the entries it was formed from."""
    n = len(S)
    A = [[np.asarray(v) for v in row] for row in S]
    scale = [_floats_abs(ar, A[i][i]) for i in range(n)]
    count = np.zeros(np.shape(A[0][0])[0], dtype=np.int64)
    decided = np.ones_like(count, dtype=bool)
    for k in range(n):
        pivot = A[k][k]
        sign, ok = ar.decide(pivot, np.maximum(scale[k], 1e-300), n)
        ok = np.asarray(ok, dtype=bool)
        count += (np.asarray(sign) < 0)
        decided &= ok
        # (an undecided pivot replaced by 1 to carry on with the other points, as the
        # factorisation does: that point is marked, and a zero divides nothing)
        pivot = np.where(ok, pivot, 1 + 0 * pivot)
        for i in range(k + 1, n):
            f = A[i][k] / pivot
            for c in range(k + 1, n):
                A[i][c] = A[i][c] - f * A[k][c]
            # (the rounding of the update: as large as the terms it subtracted)
            scale[i] = np.maximum(scale[i], _floats_abs(ar, f * A[k][i]))
    return count, decided


def _floats_abs(ar: Arithmetic, values) -> np.ndarray:
    """Upper bounds of ``|values|`` as floats."""
    return np.asarray(ar.upper(np.asarray(values)), dtype=float).reshape(-1)
