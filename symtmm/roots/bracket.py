"""Shrinking brackets on the real line, many at once: shared by the undamped and damped
searches.

:func:`shrink` runs regula falsi with the Anderson–Björck scaling of an end
that stays twice in a row (so neither end sticks; after a step to the other side
the two latest points bracket the root and the plain secant through them
converges superlinearly) on a batch of brackets, one evaluation of all the
active ones per step. A bracket that three steps together have not halved adds
:data:`SPREAD` evenly spaced points to its next secant point, in the same batch (spaced
evenly in ``log|x|`` where the bracket spans more than a factor of four on one side of 0):
superlinear near a simple root, and where the secant crawls (a root near one end,
the function there dominated by a neighbouring root) the bracket still shrinks
fourfold a step. A batch costs little more for a few more points, so the slowest
bracket no longer sets the number of batches alone (example 1: 13 batches with a
bisection instead and one cut point per root in the isolation, its root at 29.57
alone in (27.3, 54.7) taking 12 steps where most took 5 to 10; 10 batches with the
spread points and two cut points per root. Scaling the end that stays at every step, and
bisecting after two, had slowed the refinement to a constant factor per step: up
to 62 batches). Each new point lands at least a
quarter of the final width inside the bracket: once the iterate is that close to
the root, the next one falls on its other side and the bracket closes at once.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["shrink", "scaled", "scaled_ends", "SEPARATION_DIGITS"]

#: Eigenvalues are told apart down to a relative distance of ``10**-(D + 2 +
#: SEPARATION_DIGITS)`` (``D`` the digits asked for); closer ones are reported as one
#: eigenvalue with their multiplicity, as exact multiple eigenvalues are.
SEPARATION_DIGITS = 20

#: Evenly spaced points a slowly shrinking bracket adds to its secant point in a step.
SPREAD = 3


def scaled(logabs, sign, ref):
    """Values ``sign * exp(logabs - ref)`` without overflow (``ref`` per bracket)."""
    with np.errstate(all="ignore"):
        return sign * np.exp(np.minimum(logabs - ref, 700.0))


#: The most ``log|f|`` by which a bracket's ends may differ and both be scaled by the
#: larger one (``exp(-600)`` is well inside the doubles' range).
_SPREAD_E_FOLDS = 600.0


def scaled_ends(logabs, sign):
    """``(fa, fb, ref)`` from ``log|f|`` and signs at the ends ``[a..., b...]`` of ``R``
    brackets: each bracket's values scaled by its larger end, so that ``|f|`` of any size
    (a determinant far beyond the double range) fits; where they lie further apart than
    :data:`_SPREAD_E_FOLDS`, by the smaller end's ``|f|`` times ``exp(_SPREAD_E_FOLDS)``
    (the larger end capped, its sign kept), so that the smaller end and the points near
    it do not underflow to zero (a real zero's bracket whose ends'
    ``|Delta|`` were ``1e674`` and ``1e338``: every point near the zero scaled to 0, the
    "best" of them, and the bracket stayed at its small end, 1.1 from the zero).

    Examples
    --------
    >>> fa, fb, ref = scaled_ends(np.array([3.0, 5.0]), np.array([1.0, -1.0]))
    >>> float(ref[0]), float(fb[0])
    (5.0, -1.0)
    >>> fa, fb, ref = scaled_ends(np.array([1553.0, 780.0]), np.array([1.0, -1.0]))
    >>> float(ref[0]), bool(fb[0] < 0 < fa[0])
    (1380.0, True)
    """
    R = len(logabs) // 2
    low, high = np.minimum(logabs[:R], logabs[R:]), np.maximum(logabs[:R], logabs[R:])
    with np.errstate(invalid="ignore"):
        ref = np.where(high - low > _SPREAD_E_FOLDS, low + _SPREAD_E_FOLDS, high)
    ref = np.where(np.isfinite(ref), ref, np.where(np.isfinite(high), high, 0.0))
    return scaled(logabs[:R], sign[:R], ref), scaled(logabs[R:], sign[R:], ref), ref


def shrink(a, b, fa, fb, probe, width: float, steps: int = 100, settle: bool = False):
    """Shrink every bracket ``[a_i, b_i]`` (one root inside) to relative ``width``.

    Parameters
    ----------
    a, b, fa, fb : numpy.ndarray
        Float brackets and the values there (scaled alike per bracket; their signs
        differ, unless the caller's ``probe`` decides sides otherwise).
    probe : callable
        ``probe(c, idx) -> (fc, side)`` at the points ``c`` of the brackets ``idx``:
        the values there and the side of the root each lies on (``-1`` left of it:
        the new ``a``; ``+1`` right of it: the new ``b``; ``0`` undecided, which stops
        that bracket there).
    width : float
        Relative width at which a bracket is done.
    settle : bool
        Also done where the secant step from a bracket's latest point is shorter than
        half the width: the latest point is then as close to the root as a bracket of
        that width would tell, and no more steps narrow the bracket around it.

    Returns
    -------
    list
        Per bracket, the point of smallest ``|f|`` met inside its last bracket (else that
        bracket's midpoint; its first ends may sit on neighbouring roots and are no
        candidates).

    Examples
    --------
    >>> import numpy as np
    >>> f = lambda x: x * x - 2
    >>> a, b = np.array([1.0, -2.0]), np.array([2.0, -1.0])
    >>> def probe(c, idx):            # the side: where f has the sign it has at b
    ...     v = f(c)
    ...     return v, np.where(np.sign(v) == np.sign(f(b[idx])), 1, -1)
    >>> [round(x, 12) for x in shrink(a, b, f(a), f(b), probe, 1e-13)]
    [1.414213562373, -1.414213562373]
    """
    # (the brackets' state as Python lists, and each step's arithmetic on Python floats:
    # a step works on ten brackets or so, where a numpy call costs what forty float
    # operations do; the same IEEE operations in the same order as numpy's, the same bits)
    a, b = [float(x) for x in a], [float(x) for x in b]
    fa, fb = [float(x) for x in fa], [float(x) for x in fb]
    R = len(a)
    previous = [q - p for p, q in zip(a, b)]
    earlier = list(previous)
    active = [q - p > width * max(abs(p), abs(q)) for p, q in zip(a, b)]
    slow = [False] * R
    last = [0] * R                          # the side each bracket's last point fell on
    crawl = [0] * R                         # its last steps that moved an end by the guard
    met: list = [[] for _ in range(R)]     # (x, |f|) of the points met, per bracket
    tops = list(range(1, SPREAD + 1))
    for _ in range(steps):
        idx = [j for j in range(R) if active[j]]
        if not idx:
            break
        cs = []
        for j in idx:
            A, B, FA, FB = a[j], b[j], fa[j], fb[j]
            d = FB - FA
            c = B - FB * (B - A) / d if d != 0 else math.nan
            if crawl[j]:
                # the last step moved an end by the guard alone, as the secant's point fell
                # on that end: a point across the root it claims there closes the bracket;
                # where that too lands on the end's side, the end's value is far below the
                # other's without the root being near it (beside a cluster of roots |f|
                # fell 1e46-fold across a campaign's bracket, and the secant kept landing
                # on the end, 4e-6 from the root): halve
                if crawl[j] == 1:
                    step = 4 * min(0.25 * width * max(abs(A), abs(B)), (B - A) / 4)
                    c = B - step if last[j] > 0 else A + step
                else:
                    c = 0.5 * (A + B)
                cs.append((j, c))
                continue
            if settle and last[j] != 0:
                # the step from the latest point is below the width: that point is the
                # root as far as the secant tells (the other end's value, scaled down, only
                # ever lengthens the step)
                latest = B if last[j] > 0 else A
                if abs(c - latest) <= 0.5 * width * abs(latest):
                    active[j] = False
                    continue
            cs.append((j, c))
        if not cs:
            break
        xs, owners = [], []
        spread = []
        for j, c in cs:
            A, B = a[j], b[j]
            # (a step that rounds onto an end is not bad: the root is next to it, and the
            # guard below puts the point just inside, which closes the bracket)
            if not math.isfinite(c) or c < A or c > B or fa[j] * fb[j] > 0:
                c = 0.5 * (A + B)
            guard = min(0.25 * width * max(abs(A), abs(B)), (B - A) / 4)
            lo, hi = A + guard, B - guard
            xs.append(min(max(c, lo), hi))
            owners.append(j)
            if slow[j]:
                spread.append((j, lo, hi))
        # a slow bracket gets SPREAD evenly spaced points beside its secant point, in the
        # same batch: a batch costs little more for a few more points, and one bracket's
        # slow convergence would otherwise set the number of batches for all. (A bracket
        # of one sign spanning more than a factor of four: the points spaced evenly in
        # log|x|, for a root near its small end, where a real zero of a damped model lies
        # beside lam = 0 and the function grows by orders of magnitude toward the far
        # end: evenly spaced points found it only after twelve steps)
        for q in tops:
            t = q / (SPREAD + 1)
            for j, lo, hi in spread:
                A, B = a[j], b[j]
                ratio = abs(B / A) if A * B > 0 else 1.0
                x = A * ratio ** t if (ratio > 4.0 or ratio < 0.25) else A + (B - A) * t
                xs.append(min(max(x, lo), hi))
                owners.append(j)
        fx, side = probe(np.array(xs), np.array(owners, dtype=np.intp))
        # (the points' numbers as Python floats, grouped by bracket in one pass)
        fxl, sidel = np.asarray(fx, dtype=float).tolist(), np.asarray(side).tolist()
        groups: dict = {j: [] for j, _ in cs}
        for m, o in enumerate(owners):
            groups[o].append(m)
        for j, members in groups.items():
            width_before = b[j] - a[j]
            left = right = None
            stop = False
            for m in members:
                f_m = fxl[m]
                met[j].append((xs[m], abs(f_m)))
                if sidel[m] == 0 or not math.isfinite(f_m) or f_m == 0:
                    # (f = 0: the point is the root as far as f can tell; bisecting toward
                    # it from the other end would cost a step per bit)
                    stop = True
                elif sidel[m] > 0 and (right is None or xs[m] < xs[right]):
                    right = m
                elif sidel[m] < 0 and (left is None or xs[m] > xs[left]):
                    left = m
            if stop or (left is not None and right is not None and xs[left] >= xs[right]):
                active[j] = False
                continue
            # the end that stays is scaled only when it stayed the step before too: after
            # a step to the other side the two latest points bracket the root, and the
            # plain secant through them converges superlinearly (scaling them as well
            # slowed the refinement to a constant factor per step wherever the steps
            # alternate)
            # (one end moved, by no more than twice the guard, to the side it moved last)
            guard = min(0.25 * width * max(abs(a[j]), abs(b[j])), width_before / 4)
            side = 1 if right is not None and left is None else \
                -1 if left is not None and right is None else 0
            crept = (side > 0 and b[j] - xs[right] <= 2 * guard) or \
                (side < 0 and xs[left] - a[j] <= 2 * guard)
            # (counted on while the same end moves: the point across, then the halving)
            crawl[j] = crawl[j] + 1 if crept or (crawl[j] and side == last[j] != 0) else 0
            if right is not None and left is None:
                if last[j] > 0:
                    # (an end's value may have underflowed to 0 in the scaling: halve)
                    m = 1 - fxl[right] / fb[j] if fb[j] != 0 else 0.0
                    fa[j] *= m if m > 0 else 0.5
                b[j], fb[j], last[j] = xs[right], fxl[right], 1
            elif left is not None and right is None:
                if last[j] < 0:
                    m = 1 - fxl[left] / fa[j] if fa[j] != 0 else 0.0
                    fb[j] *= m if m > 0 else 0.5
                a[j], fa[j], last[j] = xs[left], fxl[left], -1
            else:                   # both ends new: a fresh bracket, nothing to scale
                a[j], fa[j], b[j], fb[j], last[j] = xs[left], fxl[left], xs[right], \
                    fxl[right], 0
            # spread points next time when three steps together have not halved the bracket
            slow[j] = (b[j] - a[j]) > 0.5 * previous[j]
            previous[j], earlier[j] = earlier[j], width_before
            active[j] = (b[j] - a[j]) > width * max(abs(a[j]), abs(b[j]))
    # The least |f| met within the last bracket, not anywhere: where |f| falls by hundreds
    # of e-folds across a bracket, a point by its small end is below every point near
    # the root (a part's second frequency, 0.0845, refined to 0.08449 in [0.08, 0.1],
    # came out as 0.0999, its first probe's point).
    out = []
    for j in range(R):
        pick, least = 0.5 * (a[j] + b[j]), math.inf
        for x, size in met[j]:
            if a[j] <= x <= b[j] and not size >= least:     # (also f = 0: at the root)
                pick, least = x, size
        out.append(pick)
    return out
