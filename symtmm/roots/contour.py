"""Counting zeros of an analytic function in rectangles (argument principle).

The number of zeros of ``f`` inside a closed contour, with multiplicity, is
the change of ``arg f`` along the contour divided by ``2 pi``. Here contours
are boundaries of axis-parallel rectangles, and ``f`` is given by
``log f = log|f| + i arg f`` on arrays of points (see :class:`LogFunction`).

Sampling. Each side of a rectangle lies on a horizontal or vertical line;
samples are cached per line, so that neighbouring rectangles and the halves
of a split rectangle share their common sides. A side starts from a grid
whose spacing a callback chooses (where ``f`` varies fast, it is dense), and
every step is then halved until, between consecutive samples, ``arg f``
changes by less than ``pi/4`` and ``log|f|`` by less than 1 (the thresholds
halve with each ``strictness`` level), and a step is accepted only if it is
half of a step that passed as well (a cluster of ``m`` zeros seen from a
step under the angle ``2 pi/m`` turns ``arg f`` by a full turn, invisible at
the ends of the step but not at its midpoint). The change of ``arg f`` over a
step is then its principal value. A sample the function flags as untrustworthy (too
close to a zero for the precision used), or steps that keep failing below a
minimum length, raise :class:`NearZero`: the caller moves the side.

Symmetric rectangles. For a function with ``f(conj z) = conj f(z)`` (real
coefficients), a rectangle symmetric about the real axis holds
``(change of arg f along its upper half boundary) / pi`` zeros; only the
upper half is sampled. A symmetric rectangle holding exactly one zero holds
a real zero: a non-real one would come with its conjugate.
"""

from __future__ import annotations

import bisect
import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

__all__ = ["ArgumentPrinciple", "CountError", "NearZero", "Rectangle"]

#: Largest change of ``arg f`` accepted between consecutive samples (strictness 0).
MAX_PHASE_STEP = math.pi / 4
#: Largest change of ``log|f|`` accepted between consecutive samples (strictness 0).
MAX_LOG_STEP = 1.0
#: Largest turn of ``arg f`` a side's end step may make by the rate the side across its
#: corner measures (strictness 0): below ``(2 pi - MAX_PHASE_STEP) / 3``, so that a step
#: three times as long cannot turn by a whole turn and pass.
CORNER_TURN = 1.5


class NearZero(Exception):
    """A side of a rectangle passes too close to a zero; move it.

    Attributes
    ----------
    z : complex
        Where the trouble was found.
    """

    def __init__(self, z):
        self.z = complex(z)
        super().__init__(f"a zero lies too close to the contour near {self.z:.6g}")


class CountError(Exception):
    """Counts of a rectangle and of its parts disagree."""


@dataclass(frozen=True)
class Rectangle:
    """``[x0, x1] x [y0, y1]`` in the complex plane (``x`` real, ``y`` imaginary part).

    With ``symmetric=True`` the rectangle is ``[x0, x1] x [-y1, y1]`` (``y0 = -y1``).

    Examples
    --------
    >>> r = Rectangle(-2.0, 0.0, 0.0, 1.0)
    >>> r.contains(-1 + 0.5j), r.contains(1j * 2)
    (True, False)
    >>> Rectangle(-2.0, 0.0, -1.0, 1.0, symmetric=True).center
    (-1+0j)
    >>> print(Rectangle(-2.0, 0.0, 0.5, 1.0))          # (as the messages show it)
    -2 <= Re lam <= 0, 0.5 <= Im lam <= 1
    """

    x0: float
    x1: float
    y0: float
    y1: float
    symmetric: bool = False

    def __post_init__(self):
        if not (self.x0 < self.x1 and self.y0 < self.y1):
            raise ValueError(f"empty rectangle {self}")
        if self.symmetric and self.y0 != -self.y1:
            raise ValueError("a symmetric rectangle needs y0 = -y1")

    def __str__(self) -> str:
        return (f"{self.x0:.6g} <= Re lam <= {self.x1:.6g}, "
                f"{self.y0:.6g} <= Im lam <= {self.y1:.6g}")

    @property
    def center(self) -> complex:
        return complex(0.5 * (self.x0 + self.x1), 0.5 * (self.y0 + self.y1))

    @property
    def width(self) -> float:
        return self.x1 - self.x0

    @property
    def height(self) -> float:
        return self.y1 - self.y0

    @property
    def size(self) -> float:
        """The longer side."""
        return max(self.width, self.height)

    def contains(self, z, margin: float = 0.0) -> bool:
        """``z`` inside (or within ``margin`` of) the rectangle."""
        z = complex(z)
        return (self.x0 - margin <= z.real <= self.x1 + margin
                and self.y0 - margin <= z.imag <= self.y1 + margin)


#: ``f`` on an array of points: ``(log|f|, arg f, trusted)`` (arrays of the same shape).
LogFunction = Callable[[np.ndarray], tuple]


class _Line:
    """Cached samples of ``log f`` on the line ``y = c`` (horizontal) or ``x = c``."""

    def __init__(self, horizontal: bool, c: float):
        self.horizontal = horizontal
        self.c = c
        self.t: list = []          # sorted positions along the line
        self.values: dict = {}     # t -> (log|f|, arg f) or None when untrustworthy
        self.verified: set = set()  # steps (t0, t1) made by halving a step that passed

    def point(self, t):
        return complex(t, self.c) if self.horizontal else complex(self.c, t)

    def between(self, a: float, b: float) -> list:
        i, j = bisect.bisect_left(self.t, a), bisect.bisect_right(self.t, b)
        return self.t[i:j]


class ArgumentPrinciple:
    """Zero counts of one analytic function in rectangles, with shared samples.

    Parameters
    ----------
    f : LogFunction
        ``f(z_array) -> (log|f|, arg f, trusted)``.
    spacing : callable
        ``spacing(z) -> float``: the initial distance between samples near
        ``z`` (a step over which ``arg f`` changes little).
    min_step : callable, optional
        ``min_step(z) -> float``: steps shorter than this that still fail the
        test raise :class:`NearZero` (default ``1e-9 * (|z| + 1)``).

    Examples
    --------
    The zeros of ``(z - 1)(z**2 + 4)(z + 2)`` are ``1, 2i, -2i, -2``:

    >>> def f(z):
    ...     v = (z - 1) * (z**2 + 4) * (z + 2)
    ...     return np.log(np.abs(v)), np.angle(v), np.ones(z.shape, dtype=bool)
    >>> ap = ArgumentPrinciple(f, spacing=lambda z: 0.25)
    >>> ap.count(Rectangle(-0.5, 3.5, -0.5, 2.5))       # 1 and 2i
    2
    >>> ap.count(Rectangle(-3.0, -1.0, -1.0, 1.0, symmetric=True))   # -2
    1
    """

    def __init__(self, f: LogFunction, spacing: Callable, min_step: Callable | None = None):
        self.f = f
        self.spacing = spacing
        self.min_step = min_step or (lambda z: 1e-9 * (abs(z) + 1.0))
        self._lines: dict = {}

    # -- sampling ---------------------------------------------------------------------
    def _line(self, horizontal: bool, c: float) -> _Line:
        key = (horizontal, float(c))
        line = self._lines.get(key)
        if line is None:
            line = self._lines[key] = _Line(horizontal, float(c))
        return line

    def _evaluate(self, requests) -> None:
        """``f`` at the new positions of every ``(line, ts)`` of ``requests``, in one call
        (a call costs far more than a point)."""
        todo, seen = [], set()
        for line, ts in requests:
            for t in ts:
                if t not in line.values and (id(line), t) not in seen:
                    seen.add((id(line), t))
                    todo.append((line, t))
        if not todo:
            return
        z = np.array([line.point(t) for line, t in todo])
        logabs, phase, ok = self.f(z)
        for (line, t), la, ph, good in zip(todo, np.atleast_1d(logabs), np.atleast_1d(phase),
                                           np.atleast_1d(ok)):
            line.values[t] = (float(la), float(ph)) if good and np.isfinite(la) else None
            bisect.insort(line.t, t)

    def _initial_grid(self, line: _Line, a: float, b: float) -> list:
        ts = [a]
        t = a
        while True:
            h = self.spacing(line.point(t))
            if not h > 0:
                raise ValueError("spacing must be positive")
            t = t + h
            if t >= b - 0.25 * h:
                break
            ts.append(t)
        ts.append(b)
        return ts

    def side(self, horizontal: bool, c: float, t0: float, t1: float,
             strictness: int = 0) -> tuple:
        """Change of ``log f`` along a side from ``t0`` to ``t1``.

        Returns ``(d_arg, moment)``: the change of ``arg f`` and the sum of
        ``z_mid * (change of log f)`` over the steps (for the centre of zeros).
        """
        return self._sides([(horizontal, c, t0, t1)], strictness)[0]

    def _sides(self, sides, strictness: int) -> list:
        """:meth:`side` of every ``(horizontal, c, t0, t1)`` of ``sides``, refined together:
        each round's new points of all of them in one call of ``f``."""
        max_phase = MAX_PHASE_STEP / 2 ** strictness
        max_log = MAX_LOG_STEP / 2 ** strictness
        work = []
        for horizontal, c, t0, t1 in sides:
            line = self._line(horizontal, c)
            a, b = (t0, t1) if t0 <= t1 else (t1, t0)
            work.append((line, a, b))
        self._evaluate([(line, self._initial_grid(line, a, b)) for line, a, b in work])
        out: list = [None] * len(sides)
        pending = list(range(len(sides)))
        while pending:
            requests, still = [], []
            for i in pending:
                line, a, b = work[i]
                mids, result = self._refine(line, a, b, max_phase, max_log)
                if mids:
                    requests.append((line, mids))
                    still.append(i)
                else:
                    d_arg, moment = result
                    out[i] = (-d_arg, -moment) if sides[i][2] > sides[i][3] else result
            self._evaluate(requests)
            pending = still
        return out

    def _refine(self, line: _Line, a: float, b: float, max_phase: float,
                max_log: float) -> tuple:
        """``(mids, None)``: the points a side ``[a, b]`` of ``line`` needs next; or
        ``(None, (d_arg, moment))`` from ``a`` to ``b`` once every step passes."""
        ts = line.between(a, b)
        vals = [line.values[t] for t in ts]
        for t, v in zip(ts, vals):
            if v is None:
                raise NearZero(line.point(t))
        la = np.array([v[0] for v in vals])
        ph = np.array([v[1] for v in vals])
        dph = np.angle(np.exp(1j * np.diff(ph)))
        dla = np.diff(la)
        passed = (np.abs(dph) <= max_phase) & (np.abs(dla) <= max_log)
        # a step more than three times as long as a neighbour is halved, passed or not: the
        # neighbour is short because f turns fast there, and a cluster of zeros beside the
        # side turns arg f by 2 pi plus a little over a long step, which then passes (a
        # fuzzed model: a triple zero 0.008 from a side, its step 0.094 next to ones of
        # 0.023, counted one zero too many)
        h = np.diff(np.asarray(ts, dtype=float))
        # At a corner the side across it has measured |f'/f| (the same in every direction:
        # f is analytic), and the end step here turns arg f by up to that times its length.
        # Where f turns at an even rate (a row of zeros beside the side, spaced below the
        # first grid), a step that turns by 4 pi and a little passes, and so do its halves:
        # a side 1.4e-3 below a crowd of modes turned by 12 radians over one step of the
        # first grid, and two rectangles below it counted a zero each that held none. An
        # end step is held to CORNER_TURN by the rate across; the steps beyond grow at most
        # threefold a step (``graded``), too little to turn by a whole turn and pass.
        limit = CORNER_TURN * max_phase / MAX_PHASE_STEP      # (halved as strictness grows)
        if h.size and h[0] * self._across(line, ts[0]) > limit:
            passed[0] = False
        if h.size and h[-1] * self._across(line, ts[-1]) > limit:
            passed[-1] = False
        graded = np.ones(h.size, dtype=bool)
        if h.size > 1:
            graded[1:] &= h[1:] <= 3 * h[:-1]
            graded[:-1] &= h[:-1] <= 3 * h[1:]
        mids = []
        for k in range(len(ts) - 1):
            lo, hi = ts[k], ts[k + 1]
            if passed[k] and (lo, hi) in line.verified and \
                    (graded[k] or hi - lo < self.min_step(line.point(lo))):
                continue        # (a step already below the least is not graded further)
            mid = 0.5 * (lo + hi)
            if not passed[k] and (hi - lo < self.min_step(line.point(mid))
                                  or not lo < mid < hi):
                raise NearZero(line.point(mid))
            if passed[k]:
                # a step that passes is accepted only once its halves pass too: a
                # cluster of m zeros seen under an angle 2 pi/m would otherwise hide
                line.verified.add((lo, mid))
                line.verified.add((mid, hi))
            mids.append(mid)
        if mids:
            return mids, None
        tz = np.array(ts)
        zmid = np.array([line.point(t) for t in 0.5 * (tz[1:] + tz[:-1])])
        dlog = dla + 1j * dph
        return None, (float(np.sum(dph)), complex(np.sum(zmid * dlog)))

    def _across(self, line: _Line, t: float) -> float:
        """``|f'/f|`` at ``line.point(t)`` as the line across it there has sampled it: the
        largest ``|change of log f| / length`` of its steps from that point (0 where no line
        crosses there or its samples do not say)."""
        other = self._lines.get((not line.horizontal, float(t)))
        here = None if other is None else other.values.get(line.c)
        if here is None:
            return 0.0
        i = bisect.bisect_left(other.t, line.c)
        rate = 0.0
        for j in (i - 1, i + 1):
            if 0 <= j < len(other.t) and other.t[j] != line.c:
                there = other.values.get(other.t[j])
                if there is not None:
                    change = complex(there[0] - here[0],
                                     math.remainder(there[1] - here[1], 2 * math.pi))
                    rate = max(rate, abs(change) / abs(other.t[j] - line.c))
        return rate

    # -- counting ---------------------------------------------------------------------
    @staticmethod
    def _sides_of(rect: Rectangle) -> list:
        """``(horizontal, c, t0, t1)`` of each side, counter-clockwise (the upper half's
        if symmetric)."""
        sides = []
        if not rect.symmetric:
            sides.append((True, rect.y0, rect.x0, rect.x1))      # bottom, left to right
        y_low = 0.0 if rect.symmetric else rect.y0
        sides += [(False, rect.x1, y_low, rect.y1),               # right, upwards
                  (True, rect.y1, rect.x1, rect.x0),              # top, right to left
                  (False, rect.x0, rect.y1, y_low)]               # left, downwards
        return sides

    def windings(self, rects, strictness: int = 0) -> list:
        """``(change of arg f, moment)`` around each of ``rects`` (upper half if
        symmetric), all their sides refined together."""
        sides = [self._sides_of(r) for r in rects]
        changes = iter(self._sides([s for group in sides for s in group], strictness))
        out = []
        for group in sides:
            d_arg, moment = 0.0, 0j
            for _ in group:
                d, mom = next(changes)
                d_arg += d
                moment += mom
            out.append((d_arg, moment))
        return out

    def winding(self, rect: Rectangle, strictness: int = 0) -> tuple:
        """``(change of arg f, moment)`` around ``rect`` (upper half if symmetric)."""
        return self.windings([rect], strictness)[0]

    def count(self, rect: Rectangle, strictness: int = 0) -> int:
        """Number of zeros inside ``rect`` with multiplicity."""
        return self.count_and_center(rect, strictness)[0]

    def count_and_center(self, rect: Rectangle, strictness: int = 0) -> tuple:
        """``(count, mean of the zeros)``; the mean is a rough estimate (None if none)."""
        return self.counts_and_centers([rect], strictness)[0]

    def counts_and_centers(self, rects, strictness: int = 0) -> list:
        """:meth:`count_and_center` of each of ``rects``, their contours sampled together."""
        out = []
        for rect, (d_arg, moment) in zip(rects, self.windings(rects, strictness)):
            turns = d_arg / (math.pi if rect.symmetric else 2 * math.pi)
            n = round(turns)
            if abs(turns - n) > 0.05 or n < 0:
                raise CountError(f"winding number {turns:.3f} around {rect} is not a count")
            if n == 0:
                out.append((0, None))
            elif rect.symmetric:
                # the lower half mirrors the upper (f real on the real axis): the whole
                # contour's moment is 2 i Im(moment), the sum of the zeros Im(moment) / pi
                mean = moment.imag / math.pi / n
                out.append((n, complex(mean) if rect.contains(mean) else rect.center))
            else:
                out.append((n, moment / (2j * math.pi) / n))
        return out

    @property
    def lines(self) -> int:
        """Number of lines sampled so far."""
        return len(self._lines)
