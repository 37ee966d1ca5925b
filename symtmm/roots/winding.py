"""The number of zeros of ``Delta`` in a rectangle, proved: a winding number in ball arithmetic.

The argument principle counts the zeros inside a contour by the change of ``arg Delta``
along it; sampled in floating point (:mod:`symtmm.roots.contour`) it is a numerical
count. Here it is a proof. The contour is cut into segments ``S`` (centre ``c``,
half-length ``r``); on each, in Arb balls:

* ``K(c)`` at the centre, and ``K'`` over the whole segment from the jets of
  :mod:`symtmm.numeric.jet`, so that ``K(z) in K(c) + (z - c) K'(S)`` for every ``z``
  of ``S`` (the mean value theorem, entry by entry);
* with ``X`` the floating-point inverse of ``K(c)`` (an exact matrix of floats),
  ``X K(z) = I + F(z)`` with ``|F(z)| <= q = |X K(c) - I| + r |X K'(S)|`` (infinity
  norm). For ``q < 1`` no ``K(z)`` is singular, and the principal logarithm gives
  ``arg det(I + F(z)) = Im tr F(z) +- n (-log(1 - q) - q)`` (the series of
  ``log det(I + F) = tr log(I + F)`` beyond its first term), where
  ``tr F(z) in tr(X K(c) - I) + (z - c) tr(X K'(S))``: the argument of ``det K =
  det(I + F) / det X`` on the whole segment lies in an interval, its centre and
  half-width known;
* the factors ``det U12`` of the segment kinds (``Delta = det K prod det U12**m P``,
  :mod:`symtmm.numeric.evaluator`) likewise from their value at ``c`` and their
  derivative over ``S``.

A segment whose interval is narrower than ``pi`` (each half-width below ``pi/2``) is
accepted, another is halved. Two neighbouring segments share an end, where ``arg
Delta`` lies in both intervals: the change of the continuous argument from one centre
to the next is the principal value of their difference, and the changes add up,
around a closed contour, to ``2 pi`` times the number of zeros inside, exactly.
Nothing is sampled between points; no step rule is trusted; ``Delta`` is never
evaluated in floating point.

For a rectangle symmetric about the real axis (``Delta`` real there) the upper half
of its boundary is walked, from real point to real point: the argument at each end is
a multiple of ``pi``, the one inside the end segment's interval, and the change over
``pi`` is the count.

Cost: two evaluations of ``K`` per segment (a point and a jet over the segment) and
products of ``n x n`` ball matrices (Arb, in C); segments shorten near zeros close to
the contour, where ``|K^-1 K'|`` is large.

Examples
--------
A pinned-pinned beam with a dashpot to the ground at mid-span: one eigenvalue near
``9.87 i`` below ``Im lam = 30``, none in a strip about the real axis:

>>> from symtmm.model import Beam, Model, Spring
>>> from symtmm.numeric.evaluator import Evaluator
>>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
>>> ev = Evaluator(Model((b,), (Spring("b", "ground", x="1/2", k=0, c=1),)), 40.0)
>>> proved_count(ev, Rectangle(-5.0, 1.0, 0.0, 30.0)).count
1
>>> proved_count(ev, Rectangle(-20.0, 1.0, -1.0, 1.0, symmetric=True)).count
0
"""

from __future__ import annotations

import itertools
import math
from dataclasses import dataclass

import numpy as np

from ..numeric.arith import Ball, ball_available
from ..numeric.jet import BallJet, Jet
from ..numeric.stiffness import _ldl, assemble
from .contour import Rectangle

__all__ = ["ProvedCount", "proved_count", "MAX_SEGMENTS"]

#: Segments a proof may use before it gives up (a zero too close to the contour).
MAX_SEGMENTS = 20000
#: The largest half-width of a segment's interval of arguments (below pi/2, with room for
#: the rounding of the centres).
HALF_WIDTH = math.pi / 2 - 0.05
#: The largest ``|F|`` on a segment (the logarithm's series needs ``q < 1``).
Q_MAX = 0.5
#: The widest value of ``Delta`` at a segment's centre, relative to its modulus, taken as it
#: comes; a wider one is evaluated again (its argument would be loose): by the evaluator's
#: plain balls at the same bits, then at twice and four times as many.
REL_RADIUS = 2.0**-10
#: Order of the Taylor model of ``K`` on a segment (coefficients at the centre up to
#: ``ORDER - 1``, the last over the segment). Measured on example 4's region to 1500
#: rad/s: order 2, 327 segments in 6.0 s; order 3, 231 segments in 6.1 s (each
#: costs more, and the box's widening still sets the length).
ORDER = 2


@dataclass(frozen=True)
class ProvedCount:
    """A count of zeros and what proves it.

    ``count`` is None when the proof could not be completed (``reason`` says why).
    """

    count: int | None
    segments: int
    evaluations: int
    reason: str = ""


def _path(rect: Rectangle) -> list:
    """The sides walked: ``(start, end)`` complex points, counter-clockwise; the upper half
    of a symmetric rectangle from its right real point to its left one."""
    x0, x1, y0, y1 = rect.x0, rect.x1, rect.y0, rect.y1
    if rect.symmetric:
        return [(complex(x1, 0), complex(x1, y1)), (complex(x1, y1), complex(x0, y1)),
                (complex(x0, y1), complex(x0, 0))]
    return [(complex(x0, y0), complex(x1, y0)), (complex(x1, y0), complex(x1, y1)),
            (complex(x1, y1), complex(x0, y1)), (complex(x0, y1), complex(x0, y0))]


class _Prover:
    def __init__(self, evaluator, rect: Rectangle, digits: int, order: int = ORDER):
        self.ev = evaluator
        top = max(abs(z) for side in _path(rect) for z in side)
        self.plan = evaluator.plan(top)
        self.prec = max(64, int(digits * 3.33) + 16)
        self.order = order
        self.ball = Ball(self.prec)
        self.point = BallJet(self.prec, order=order - 1)
        self.box = BallJet(self.prec, order=order)
        self.flint = self.ball.flint
        self.evaluations = 0

    def intervals(self, segments) -> list:
        """``(centre, half-width)`` of ``arg Delta`` on each segment ``(a, b)``, or None."""
        flint, plan = self.flint, self.plan
        centres = [0.5 * (a + b) for a, b in segments]
        self.evaluations += 2 * len(segments)
        with self.point:
            lam = np.array([self.point.variable(c) for c in centres], dtype=object)
            Kp, d12p = assemble(plan, self.point, lam * lam, lam)
        values, trusted = self._delta(centres, Kp, d12p)
        boxes, steps = [], []
        with self.box:
            for (a, b), c in zip(segments, centres):
                rx, ry = abs(b.real - a.real) / 2, abs(b.imag - a.imag) / 2
                # outward by two ulps in the direction the segment runs: the float centre
                # and half-length must not leave an end of the segment out of its boxes
                pad = 2 * math.ulp(max(abs(a.real), abs(b.real), abs(a.imag), abs(b.imag)))
                rx, ry = (rx + pad if rx else 0.0), (ry + pad if ry else 0.0)
                steps.append(flint.acb(flint.arb(0, rx), flint.arb(0, ry)))
                # the top coefficient over the whole segment: its box (padded as dz)
                boxes.append(self.box.variable(flint.acb(
                    flint.arb(c.real, rx), flint.arb(c.imag, ry))))
            lam = np.array(boxes, dtype=object)
            Kb, d12b = assemble(plan, self.box, lam * lam, lam)
        top = self.order
        out = []
        with self.ball, np.errstate(all="ignore"):
            for p, dz in enumerate(steps):
                if not trusted[p] or flint.acb(values[p]).contains(0):
                    out.append(None)
                    continue
                Ktop = _split(Kb[p], top)
                dtop = [flint.acb(v.c[top]) for v in d12b[p]]
                out.append(self._interval(flint.acb(values[p]), Kp[p], Ktop, d12p[p], dtop,
                                          dz))
        return out

    def _delta(self, centres, Kp, d12p):
        """``(Delta, trusted)`` at the centres from the jets' values (their ``K`` and ``det
        U12`` are the ball arithmetic's): the ball ``LDL^T`` of that band; where it leaves a
        pivot undecided, the evaluator's own (more bits, or Arb's determinant)."""
        flint, ball = self.flint, self.ball
        with ball:
            K = np.frompyfunc(lambda v: flint.acb(v.c[0]) if isinstance(v, Jet)
                              else flint.acb(v), 1, 1)(Kp)
            det12 = np.frompyfunc(lambda v: flint.acb(v.c[0]), 1, 1)(d12p)
            fa = _ldl(self.plan, ball, K, det12)
            values, trusted = fa.delta(), fa.trusted.copy()
        values = values.copy()
        # where the elimination left a pivot undecided, or lost so many bits to a small
        # pivot (a leading sub-structure near its own eigenvalue) that the value's ball
        # is too wide for its argument, the evaluator's own (plain balls, narrower than the
        # jets' values) at the same bits, then at twice and four times as many
        bad = np.nonzero(~trusted | ~self._narrow(values))[0]
        prec = self.prec
        for _ in range(3):
            if not bad.size:
                break
            again, ok = self.ev.delta([centres[i] for i in bad], Ball(prec))
            self.evaluations += bad.size
            for i, v, good in zip(bad, again, ok):
                values[i], trusted[i] = v, good
            prec *= 2
            bad = bad[~self._narrow(values[bad])]
        return values, trusted

    def _narrow(self, values) -> np.ndarray:
        """Per ball value, whether its radius is below :data:`REL_RADIUS` of its modulus."""
        flint = self.flint
        with self.ball:
            out = []
            for v in values:
                v = flint.acb(v)
                low = float(abs(v).lower())
                out.append(low > 0 and float(abs(v).rad()) < REL_RADIUS * low)
        return np.array(out, dtype=bool)

    def _interval(self, delta_c, Kp, Ktop, d12p, dtop, dz):
        """The interval of ``arg Delta`` on one segment from the Taylor model ``K(z) in
        sum_(k < order) K_k(c) dz**k + K_order(S) dz**order`` (Taylor coefficients at the
        centre, the last over the segment: the remainder in mean-value form)."""
        flint, plan = self.flint, self.plan
        n = plan.n
        coefficients = [_split(Kp, k) for k in range(self.order)] + [Ktop]
        try:
            X = np.linalg.inv(coefficients[0][0])
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(X)):
            return None
        E = [_product(X, coefficients[0], identity=True)]
        E += [_product(X, K) for K in coefficients[1:]]
        r = float(abs(dz).abs_upper())
        q = sum(_norm(e) * r**k for k, e in enumerate(E))
        if not q < Q_MAX:
            return None
        # tr F(z) - tr F(c) over the segment, F(z) = X K(z) - I
        tau = sum((dz**k * _trace(e, flint) for k, e in enumerate(E) if k), flint.acb(0))
        half = float(abs(tau.imag).upper()) + 2 * n * (-math.log1p(-q) - q)
        # arg Delta(c) turned near 0 first: a ball about the negative real axis would
        # otherwise straddle the principal argument's cut and span (-pi, pi]
        theta = float(delta_c.mid().arg().mid())
        turned = (delta_c * flint.acb(0, -theta).exp()).arg()
        centre = theta + float(turned.mid())
        half += float(turned.rad()) + 4 * math.ulp(abs(theta) + math.pi)
        for v, vtop, m in zip(d12p, dtop, plan.multiplicity):
            d0 = flint.acb(v.c[0])
            if d0.contains(0):
                return None
            # det U12(z) / det U12(c) = 1 + w, w its Taylor model over det U12(c)
            w = sum((dz**k * flint.acb(v.c[k]) for k in range(1, self.order)),
                    dz**self.order * vtop) / d0
            rho = float(abs(w).abs_upper())
            if not rho < 0.5:
                return None
            half += int(m) * (float(abs(w.imag).upper()) + (-math.log1p(-rho) - rho))
        half = half * (1 + 1e-12) + 1e-12
        if not half < HALF_WIDTH:
            return None
        return centre, half


def _split(K, k) -> tuple:
    """``(mid, rad)`` float arrays (dense, symmetric) of Taylor coefficient ``k`` of a band of
    jets ``(n, b + 1)`` (:func:`~symtmm.numeric.stiffness.assemble`): complex midpoints and
    upper bounds of the distance to them; an entry that is the integer 0 is an exact 0."""
    n, w = K.shape
    mid = np.zeros((n, n), dtype=complex)
    rad = np.zeros((n, n))
    for r in range(n):
        for j in range(min(w, n - r)):
            v = K[r, j]
            if not isinstance(v, Jet):
                continue
            c = v.c[k]
            if isinstance(c, int):
                continue
            re, im = c.real, c.imag
            m = complex(float(re.mid()), float(im.mid()))
            mid[r, r + j] = mid[r + j, r] = m
            # the balls' radii, and the rounding of their midpoints to doubles (half an
            # ulp of each part, at most 2**-53 of it; 2**-52 of |m| bounds both)
            rad[r, r + j] = rad[r + j, r] = (float(re.rad()) + float(im.rad())
                                             + 2.0**-52 * abs(m) + 1e-300)
    return mid, rad * (1 + 1e-15)


#: Rounding of an n-term complex dot product in double precision, relative to the sum of
#: the moduli of its terms (a margin over Higham's gamma_n for complex multiplication)
def _gamma(n: int) -> float:
    return 4 * (n + 4) * 2.0**-53


def _product(X, B, identity: bool = False) -> tuple:
    """``(mid, rad)`` enclosing ``X B`` (minus ``I``) for an exact float matrix ``X`` and a
    matrix of balls ``B = (mid, rad)``: the floating product and, entrywise, ``|X| rad(B)``
    plus the rounding of the product (Higham's bound), all bounds rounded up by a margin."""
    Bm, Br = B
    n = X.shape[0]
    absX = np.abs(X)
    mid = X @ Bm
    rad = absX @ Br + _gamma(n) * (absX @ np.abs(Bm))
    if identity:
        mid = mid - np.eye(n)
        rad = rad + 2.0**-52 * np.abs(mid)
    # (the bounds themselves are sums of n nonnegative terms in floats: their own
    # relative rounding is below gamma(n))
    return mid, rad * (1 + 2 * _gamma(n) + 1e-15) + 1e-300


def _norm(E) -> float:
    """An upper bound of the infinity norm of a ``(mid, rad)`` matrix."""
    mid, rad = E
    n = mid.shape[0]
    rows = np.sum(np.abs(mid) + rad, axis=1)
    return float(np.max(rows, initial=0.0)) * (1 + 2 * _gamma(n) + 1e-15) + 1e-300


def _trace(E, flint):
    """The trace of a ``(mid, rad)`` matrix as a complex ball (the floating sum's rounding
    bounded by gamma(n) times the sum of the moduli)."""
    mid, rad = E
    n = mid.shape[0]
    t = np.trace(mid)
    d = np.diagonal(mid)
    r = (float(np.trace(rad)) + _gamma(n) * float(np.sum(np.abs(d)))) * (1 + 2 * _gamma(n)) \
        + 1e-300
    return flint.acb(flint.arb(t.real, r), flint.arb(t.imag, r))


def proved_count(evaluator, rect: Rectangle, digits: int = 15, spacing=None,
                 max_segments: int = MAX_SEGMENTS, order: int = ORDER) -> ProvedCount:
    """The number of zeros of ``Delta`` in ``rect`` with multiplicity, proved in balls.

    Parameters
    ----------
    evaluator : symtmm.numeric.evaluator.Evaluator
    rect : Rectangle
        Its boundary must avoid the zeros (a zero on it leaves the proof unfinished).
    digits : int
        Sets the working precision of the balls.
    spacing : callable, optional
        ``spacing(z)``: a first length of the segments near ``z`` (halved where needed).
    max_segments : int
        The budget.
    order : int
        Of the Taylor model of ``K`` on a segment (2 or 3, see :data:`ORDER`).

    Returns
    -------
    ProvedCount
        ``count`` None where the proof did not close: python-flint missing, an element
        without jets (a series tail whose derivative is not bounded), the budget spent.
    """
    if order not in (2, 3):
        raise ValueError(f"order must be 2 or 3, not {order!r}")
    if not ball_available():
        return ProvedCount(None, 0, 0, "python-flint is not installed")
    prover = _Prover(evaluator, rect, digits, order)
    # every side walked at once, one segment of each per batch: a segment that passes is
    # kept and the next tried 1.6 times longer, one that fails is halved
    sides = []
    for a, b in _path(rect):
        length = abs(b - a)
        h = spacing(a) if spacing is not None else length / 8
        sides.append({"a": a, "b": b, "t": 0.0, "h": min(1.0, max(h / length, 1e-9)),
                      "done": []})
    accepted = 0
    while True:
        active = [s for s in sides if s["t"] < 1.0]
        if not active:
            break
        segs = []
        for side in active:
            t1 = min(1.0, side["t"] + side["h"])
            if 1.0 - t1 < 0.05 * side["h"]:
                t1 = 1.0
            side["t1"] = t1
            a, b = side["a"], side["b"]
            segs.append((a + (b - a) * side["t"], a + (b - a) * t1 if t1 < 1.0 else b))
        try:
            found = prover.intervals(segs)
        except NotImplementedError:
            return ProvedCount(None, accepted, prover.evaluations,
                               "an element of the model has no derivative bounds (jets)")
        for side, seg, got in zip(active, segs, found):
            if got is not None:
                side["done"].append(got)
                side["t"] = side["t1"]
                side["h"] *= 1.6
                accepted += 1
                continue
            side["h"] /= 2
            a, b = seg
            if abs(b - a) < 1e-13 * max(abs(a), abs(b), 1.0):
                return ProvedCount(None, accepted, prover.evaluations,
                                   f"a zero lies on or too close to the contour near {a:.6g}")
        if accepted > max_segments:
            return ProvedCount(None, accepted, prover.evaluations,
                               "a zero lies too close to the contour (segment budget spent)")
    done = {(i, k): v for i, side in enumerate(sides) for k, v in enumerate(side["done"])}
    intervals = [done[k] for k in sorted(done)]
    total = 0.0
    for (c0, _), (c1, _) in itertools.pairwise(intervals):
        total += _principal(c1 - c0)
    if rect.symmetric:
        # the argument at each real end: the multiple of pi inside its segment's interval
        # (Delta is real on the real axis); one that is not inside means it is not real
        c_first, h_first = intervals[0]
        c_last, h_last = intervals[-1]
        start = math.pi * round(c_first / math.pi)
        end = math.pi * round(c_last / math.pi)
        if abs(c_first - start) > h_first or abs(c_last - end) > h_last:
            return ProvedCount(None, len(done), prover.evaluations,
                               "Delta is not real at the ends on the real axis")
        total += (c_first - start) + (end - c_last)
        turns = total / math.pi
    else:
        total += _principal(intervals[0][0] - intervals[-1][0])
        turns = total / (2 * math.pi)
    count = round(turns)
    if abs(turns - count) > 1e-6 or count < 0:
        return ProvedCount(None, len(done), prover.evaluations,
                           f"the winding number {turns:.6f} is not an integer")
    return ProvedCount(count, len(done), prover.evaluations)


def _principal(a: float) -> float:
    """``a`` reduced to ``(-pi, pi]``."""
    return a - 2 * math.pi * math.floor((a + math.pi) / (2 * math.pi))
