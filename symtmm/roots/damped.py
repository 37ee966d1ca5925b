"""Eigenvalues of damped models in a rectangle of the complex plane, none missed.

Eigenvalues ``lam = -sigma + i omega`` are the zeros of the entire function
``Delta(lam) = det K(lam) * prod det U12 * P`` (equal to ``det R``, evaluated by
the numeric kernel: :class:`symtmm.numeric.evaluator.Evaluator`). They come in
conjugate pairs; those with ``Im lam >= 0`` are reported. The search region is

    -sigma_max <= Re lam <= 0,   0 <= Im lam <= omega_max,

``sigma_max`` defaulting to ``2 * omega_max`` (:data:`SIGMA_FACTOR`).

1. **Count.** The number of zeros in a rectangle is the change of
   ``arg Delta`` around it over ``2 pi`` (:mod:`symtmm.roots.contour`), sampled
   in double precision in batches (proved on request: ``prove_count``, the winding
   number in ball arithmetic of :mod:`symtmm.roots.winding`, checked against this
   count); a point whose pivots cannot all be trusted
   (very close to a zero) is evaluated again in the proof arithmetic (Arb balls,
   or mpmath at two precisions without python-flint). The region is enlarged
   slightly beyond ``Re lam = 0`` (no eigenvalue of a passive model lies to the
   right of the imaginary axis, so undamped modes are strictly inside), and its
   lower part is a rectangle symmetric about the real axis, so that real
   (overdamped) eigenvalues lie strictly inside too; only its upper half is
   sampled (``Delta`` is real on the real axis).
2. **Isolate.** Rectangles are halved (quadtree) until each holds at most one
   zero; the counts of the halves must add up to the count of the whole. A
   symmetric rectangle holding one zero holds a real one (a non-real zero would
   bring its conjugate). With rigid-body modes ``lam = 0`` is a zero of known
   order (:func:`symtmm.mesh.zero_order`: two per free rigid motion, one per
   rigid motion only a dashpot resists): a rectangle around 0 holds that many
   zeros besides the others, and is never refined.
3. **Refine**, all zeros at once: secant steps on ``Delta`` in double precision,
   one batch per step, then in the proof arithmetic at ``D + 20`` digits (more
   for a small real or imaginary part), again one batch per step. A real zero is
   bracketed on the real axis instead (``Delta`` is real there): Anderson–Björck
   steps in double, then pairs of points about its estimate, whose signs prove it
   between them (strictly opposite balls: ``sign change``). A complex zero is
   refined once more 15 digits higher and must agree to ``D + 2`` digits in each
   part, with both ends of that error printing alike (``two precisions``).
4. **Undamped modes of damped models** (e.g. beams moving in phase, their
   dashpots idle) have ``Re lam = 0`` exactly; numerically the real part
   comes out as rounding noise. When it is below ``10**-(D+25) |lam|`` and
   the same ``lam`` is, to that accuracy, also an eigenvalue of the model
   with every dashpot removed and of the model with every dashpot doubled
   (the mode does not move the dashpots, so it dissipates nothing), the
   real part is reported as exactly ``0`` and a note says so. This is a
   numerical identification, not a proof.
5. **Multiple zeros.** A rectangle that still holds ``m >= 2`` zeros when it
   is too small for double precision is taken to high precision: the modified
   Newton method ``z - m Delta/Delta'`` finds the cluster, and a count on a
   square of half-width ``10**-(D + 2 + SEPARATION_DIGITS) |lam|`` around it
   decides between one zero of multiplicity ``m`` (its ``m`` zeros agree to
   ``D + SEPARATION_DIGITS`` digits) and distinct zeros, separated by the same
   quadtree at high precision and refined one by one, however close.

Precision is explicit throughout: every high-precision evaluation names its
digits, and the bookkeeping (secant steps, brackets) runs in private mpmath
contexts, never in the ambient ``mpmath.mp``.
"""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np

from .. import progress
from ..budget import checked_request
from ..deadline import check as check_time
from ..deadline import time_budget
from ..errors import ComputationError, OverBudget
from ..limits import MAX_PIECES
from ..mesh import zero_order
from ..model import Model
from ..numeric.arith import MP, Ball, ball_available
from ..numeric.evaluator import Evaluator
from ..numeric.evaluator import exact_mpc as _global
from ..numeric.transfer import too_many_waves
from ..results import Eigenvalue, Spectrum, first, prints_alike
from .bracket import SEPARATION_DIGITS, scaled, scaled_ends, shrink
from .contour import ArgumentPrinciple, CountError, NearZero, Rectangle
from .undamped import PROOFS, _first_guess, check_stable, estimates, gap_above, omega_scale

__all__ = ["SIGMA_FACTOR", "count_in_rectangle", "default_sigma_max", "solve_damped",
           "DAMPED_PROOFS"]

#: ``sigma_max`` defaults to this multiple of ``omega_max``.
SIGMA_FACTOR = 2
#: Largest working precision (decimal digits).
MAX_DIGITS = 1500
#: A rectangle smaller than this (relative to |lam|) that still holds several zeros is
#: left to high precision: double precision cannot split it reliably.
_TINY = 1e-6
#: The undamped eigenvalues that start a damped search reach this far beyond its region
#: (relative to its top, and to a rectangle's height): the damping lowers a frequency
#: into it.
_ESTIMATE_REACH = 0.2
#: Split positions tried in turn when a split line passes too close to a zero.
_SPLITS = (0.5, 0.4427, 0.5573, 0.3711, 0.6289, 0.3019, 0.6981)
#: Guard digits of the high-precision refinement.
_GUARD = 20
#: Relative step below which the double-precision secant stops.
_DOUBLE_STEP = 1e-13

#: What backs a damped eigenvalue: its name in results and output.
DAMPED_PROOFS = {"ball": "sign change (ball arithmetic)",
                 "mp": "sign change (two precisions)",
                 "rouche": "Rouche (ball arithmetic)",
                 "rouche_idle": "Rouche (ball arithmetic) for Im lam; Re lam = 0 identified",
                 "agree": "two precisions"}


def default_sigma_max(omega_max: float) -> float:
    """The decay-rate bound of the search region when none is given: ``2 omega_max``.

    Examples
    --------
    >>> default_sigma_max(1500.0)
    3000.0
    """
    return SIGMA_FACTOR * float(omega_max)


def _reference_frequency(model: Model) -> float:
    """Half the lowest pinned-pinned frequency of any beam: the scale near ``lam = 0``."""
    return 0.5 * _first_guess(model)


def _decades(small, big) -> int:
    """How many decimal orders ``small`` lies below ``big`` (rounded up), from their binary
    exponents: ``small`` may be far below the double range (thousands of digits asked)."""
    return math.ceil((mpmath.mag(big) - mpmath.mag(small)) * math.log10(2)) + 1


def _imaginary(z) -> mpmath.mpc:
    """``i Im z`` exactly (``mpmath.mpc(0, y)`` would round ``y`` to the ambient precision)."""
    return mpmath.mp.make_mpc((mpmath.libmp.fzero, _global(z).imag._mpf_))


#: A Rouche disk whose bound exceeds what the proof allows by more than this factor, times
#: the radius still to grow, is given up with its box (:meth:`_Search._rouche_once`).
_HOPELESS = 1e3
#: ... and where the first box of a search's Rouche proofs misses by more than this factor at
#: the first radius, the others are given up with it (:meth:`_Search._rouche_once`): the
#: enclosures of the benchmarks' and examples' boxes exceed ``|Delta|`` by ``1e5 .. 1e8``,
#: their ratios at the first radius are far below 1.
_FAR_OUT = 1e40
#: Rouche's proofs of a search take at most this many times the seconds the search took
#: before them, and at least :data:`_PROOF_FLOOR` seconds; the boxes left unproved then are
#: the other proofs' (two precisions). Each disk is a dense determinant in balls, and where
#: a crowd of nearly undamped modes makes ``K`` ill-conditioned, their enclosures miss by
#: a little and every radius is tried: a campaign model of a soft, heavy Timoshenko beam
#: took 71 of its 77 s proving 29 of 93 eigenvalues by Rouche, past the default budget
#: (now 7 s, 7 proved); another's 132 eigenvalues 38 of 61 s at twice the search's time.
_PROOF_SHARE = 1.0
_PROOF_FLOOR = 2.0
#: Boxes whose Rouche disks are enclosed in one batch.
_PROOF_PART = 16


def _real(z) -> mpmath.mpc:
    """``Re z`` as a complex number, exactly."""
    return mpmath.mp.make_mpc((_global(z).real._mpf_, mpmath.libmp.fzero))


def _box(z, r) -> tuple:
    """``((re - r, re + r), (im - r, im + r))``: the square a proof holds a zero in."""
    ctx = MP(max(int(mpmath.mag(z) - mpmath.mag(r)), 0) + 128).ctx
    re, im, r = ctx.mpf(z.real), ctx.mpf(z.imag), ctx.mpf(r)
    return ((_global(re - r).real, _global(re + r).real),
            (_global(im - r).real, _global(im + r).real))


def _prints_alike(ends, digits) -> bool:
    """The ends ``(lo, hi)`` of an interval print alike with ``digits`` digits."""
    lo, hi = ends
    return prints_alike(_global(lo).real, _global(hi).real, digits)


# Tolerances and box sizes: 64 bits are plenty for them, and building them in this
# private context keeps the ambient mpmath precision out of every decision.
_TOL = MP(64).ctx


def _tol(k: int, scale=1) -> mpmath.mpf:
    """``10**k |scale|`` to 64 bits, as a global mpmath number (unrounded)."""
    return _global(_TOL.mpf(10) ** k * abs(_TOL.mpc(scale))).real


def _log_arg(v) -> tuple:
    """``(log|v|, arg v)`` as floats, in a private context (``v`` any mpmath number)."""
    c = _TOL.mpc(v)
    return float(_TOL.log(abs(c))), float(_TOL.arg(c))


class _Problem:
    """``Delta`` of one model: double batches for contours, any precision for refinement.

    ``certified``: the high-precision arithmetic is Arb balls (python-flint),
    else mpmath checked at a second precision.
    """

    def __init__(self, model: Model, lam_max: float, certified: bool | None = None):
        self.model = model
        self.kernel = Evaluator(model, lam_max)
        self.started = time.perf_counter()      # (the proofs' share: _Search._rouche)
        # per beam, what its wave number at |lam| comes from: (m/EI) for a plain beam,
        # else the segment (Rayleigh, Timoshenko, axial force)
        # (a beam of a theory with its constants as floats once: the contours ask for the
        # spacing thousands of times, and SymPy's conversions took a fifth of a search)
        # A foundation is left out, as a plain beam's ``(m/EI)`` leaves it: under its
        # cut-off ``sqrt(kw/m)`` it makes the waves evanescent and their wave number large
        # but nearly constant, and Delta turns no faster for it (a Timoshenko beam with
        # kw L**4 / EI = 6e10: a first grid of 75,000 points, past the time budget)
        self.waves = []
        for b in model.beams:
            seg = None if b.plain else b.segment(b.L)
            consts = None
            if seg is not None:
                consts = list(seg.constants())
                consts[3] = 0.0                         # (EI, m, l, kw, N, rhoI, kGA)
                consts = tuple(consts)
            self.waves.append((seg, consts, float(b.m) / float(b.EI), float(b.L)))
        self.lam_ref = _reference_frequency(model)
        self.balls = ball_available() if certified is None else bool(certified)
        self.extra = 0          # evaluations of auxiliary models
        self._aux: dict = {}

    @property
    def evaluations(self) -> int:
        return self.kernel.evaluations + self.extra

    def spacing(self, z) -> float:
        """The contours' first grid near ``z``: ``|lam|`` over the waves the beams hold
        there (``Delta`` turns by about a radian per wave). Only a start: every step is
        then halved until ``arg Delta`` changes by less than ``pi/4`` and both halves of it
        pass as well, and until no step is more than three times as long as a neighbour
        (:mod:`symtmm.roots.contour`), so a coarser start costs passes (before the steps
        were graded, example 4's region: 7,000 evaluations at 0.3 of this, 4,300 at 0.5,
        2,800 at 0.8, 2,300 here; the damped Timoshenko model of the benchmarks 4,400 at
        0.5, 2,300 here; the same eigenvalues and proofs; graded, example 4 3,580 here).
        A count proved in balls is :mod:`symtmm.roots.winding`'s (``--certified``)."""
        a = max(abs(z), self.lam_ref)
        total = 0.0
        for seg, consts, mu, L in self.waves:
            # (a float in, a float out: numpy's max of one number cost a third of this)
            k = (mu * a * a) ** 0.25 if seg is None else seg.wave_number(-a * a, consts)
            total += k * L
        if not total <= MAX_PIECES:
            # (a side sampled at this spacing would take more points than any mesh may
            # have pieces: the kernel refuses such a range in the same words)
            raise ComputationError(too_many_waves(f"|lam| = {a:.6g}"))
        return a / (1.0 + total)

    def min_step(self, z) -> float:
        return 1e-10 * max(abs(z), self.lam_ref)

    def arithmetic(self, digits: int):
        return Ball.from_digits(digits) if self.balls else MP.from_digits(digits)

    # -- values ---------------------------------------------------------------------------
    def values(self, points, digits: int, kernel: Evaluator | None = None) -> list:
        """``Delta`` at ``points`` (mpmath numbers, exact) as global mpmath numbers, or None
        where the evaluation cannot be trusted (an undecided pivot; a ball too wide to say
        where its value is, still after the digits were doubled twice: a point that close
        to a zero)."""
        out: list = [None] * len(points)
        todo = list(range(len(points)))
        work = digits
        before = None           # the widest ball's shortfall at the last precision
        for attempt in range(3):
            if not todo:
                break
            ar = self.arithmetic(work)
            vals, trusted = (kernel or self.kernel).delta([points[i] for i in todo], ar)
            wide, short = [], 0.0
            for i, v, ok in zip(todo, vals, trusted):
                if not ok:
                    continue
                if ar.rigorous:
                    mid = abs(v.mid())
                    if not (mid.is_finite() and v.rad() < mid / 1024):
                        wide.append(i)
                        # the digits the ball lacks, where it says (a finite midpoint)
                        ratio = float(v.rad() / mid) if mid.is_finite() and mid != 0 \
                            else math.inf
                        short = max(short, math.log10(1024 * ratio) if ratio > 0 else 0.0)
                        continue
                out[i] = _global(ar.to_mpmath(v))
            todo = wide
            # the next precision: the digits the widest ball lacked and ten more (a point
            # near a zero, its value far below the terms: doubling took 45 -> 90 -> 180
            # digits there, past the compiled balls), else twice as many. Where the last
            # step gained under half the digits it added, the balls did not come from this
            # precision (the compiled words round it up to a tier, which may already have
            # held more: a model with a growth of 10^55 along its band read the same radius
            # at 30, 40 and 50 digits) and the shortfall says nothing of the next: doubled
            stalled = before is not None and short > before[0] - 0.5 * (work - before[1])
            before = (short, work)
            work = work + max(10, math.ceil(short) + 10) \
                if math.isfinite(short) and not stalled else 2 * work
        return out

    def log_delta(self, z):
        """``(log|Delta|, arg Delta, trusted)`` at complex points (the contour's function).

        Double precision in one batch; points with untrusted pivots again in the proof
        arithmetic at 30 digits (and, in mpmath, checked at 45).
        """
        logabs, phase, ok = self.kernel.log_delta(z)
        bad = np.nonzero(~ok)[0]
        if bad.size:
            points = [_global(complex(z[i])) for i in bad]
            first = self.values(points, 30)
            second = first if self.balls else self.values(points, 45)
            for i, a, b in zip(bad, first, second):
                if a is None or b is None or a == 0 or b == 0:
                    continue
                la, ph = _log_arg(a)
                lb, pb = _log_arg(b)
                if not self.balls and (abs(la - lb) > 1e-6
                                       or abs(math.remainder(ph - pb, 2 * math.pi)) > 1e-6):
                    continue
                logabs[i], phase[i], ok[i] = la, ph, True
        return logabs, phase, ok

    def auxiliary(self, factor) -> Evaluator:
        """The kernel of the model with every dashpot scaled by ``factor``."""
        if factor not in self._aux:
            self._aux[factor] = Evaluator(self.model.with_dashpots_scaled(factor),
                                          self.kernel.size)
        return self._aux[factor]


class _LocalFunction:
    """``log Delta(origin + u)`` for local coordinates ``u``, at a given precision only."""

    def __init__(self, problem: _Problem, digits: int, origin):
        self.problem, self.digits, self.origin = problem, digits, origin

    def __call__(self, u):
        u = np.atleast_1d(u)
        ctx = MP.from_digits(self.digits + 10).ctx
        points = [_global(ctx.mpc(self.origin) + ctx.mpc(complex(ui))) for ui in u]
        values = self.problem.values(points, self.digits)
        logabs = np.zeros(u.shape)
        phase = np.zeros(u.shape)
        ok = np.zeros(u.shape, dtype=bool)
        for i, v in enumerate(values):
            if v is not None and v != 0:
                logabs[i], phase[i] = _log_arg(v)
                ok[i] = True
        return logabs, phase, ok


class _Search:
    """Isolation and refinement of the zeros in one region.

    Rectangles are in coordinates relative to ``origin`` (an mpmath number,
    default 0): a rectangle of relative size ``1e-20`` around an eigenvalue
    is then still representable in double precision. A symmetric rectangle
    needs a real ``origin``.
    """

    def __init__(self, problem: _Problem, digits: int, ap=None, origin=None):
        self.p = problem
        self.digits = digits
        self.ap = ap or ArgumentPrinciple(problem.log_delta, problem.spacing, problem.min_step)
        self.origin = origin
        self.idle = 0
        #: the order of the zero of Delta at lam = 0 (rigid-body modes), known exactly
        self.zero_order = 0
        #: the fewest digits a refinement works at (a cluster's zeros: what tells them apart)
        self.floor = 0

    def _at(self, u, ctx=None):
        """The global point ``origin + u`` (in ``ctx``, default the global context)."""
        if self.origin is None:
            return _global(u) if ctx is None else ctx.mpc(complex(u))
        ctx = ctx or MP(256).ctx
        return ctx.mpc(self.origin) + ctx.mpc(complex(u))

    def _local(self, z) -> complex:
        if self.origin is None:
            return complex(z)
        ctx = MP(256).ctx
        return complex(ctx.mpc(z) - ctx.mpc(self.origin))

    def _scale(self, u) -> float:
        return max(abs(complex(self._at(u))), self.p.lam_ref)

    # -- counting -----------------------------------------------------------------------
    def _split(self, rect, count):
        """Children ``[(rect, count, center, weight)]`` of ``rect``; weight 2 = mirrored.

        A rectangle within a thousand of the contours' least step (a zero beside
        ``lam = 0``, 1e-9 from it where ``|lam|`` of the model's modes is about 1: a pure
        dashpot and a spring of 1e-10 on two rigid rotations) is cut again with steps
        down to a millionth of its own size, where the first cuts met a zero."""
        counted, last_error = self._try_splits(self.ap, rect, count)
        if counted is not None:
            return counted
        if isinstance(last_error, NearZero) and \
                rect.size < 1e3 * self.ap.min_step(rect.center):
            size = rect.size
            fine = ArgumentPrinciple(self.ap.f, self.ap.spacing,
                                     min_step=lambda _u: 1e-6 * size)
            counted, last_error = self._try_splits(fine, rect, count)
            if counted is not None:
                return counted
        where = "" if self.origin is None else f" (about {complex(self.origin):.6g})"
        raise ComputationError(f"cannot split the search rectangle {rect}{where}: "
                               f"{last_error}")

    def _try_splits(self, ap, rect, count) -> tuple:
        """``(children, None)`` from the first of :data:`_SPLITS` whose parts' counts (by
        ``ap``) add up to ``count``, each at growing strictness; else ``(None, error)``."""
        last_error = None
        for strictness in (0, 1, 2):
            for s in _SPLITS:
                try:
                    kids = self._children(rect, s)
                    found = ap.counts_and_centers([kid for kid, _ in kids], strictness)
                except NearZero as exc:
                    last_error = exc
                    continue
                except CountError as exc:
                    # (a part's winding number not a count, -2 on a campaign's model: its
                    # sampling missed turns of arg Delta) the same split, stricter sampling
                    last_error = exc
                    break
                counted = self._tally(kids, found, count)
                if counted is not None:
                    return counted, None
                last_error = CountError(f"the counts of its parts, {[n for n, _ in found]}, "
                                        f"do not add up to its {count}")
                break   # same split, stricter sampling
        return None, last_error

    @staticmethod
    def _tally(kids, found, count: int):
        """``[(rect, count, center, weight)]`` of the children ``kids`` with what was
        ``found`` in them, or None where their counts do not add up to ``count``."""
        counted = [(kid, n, center, weight) for (kid, weight), (n, center) in zip(kids, found)]
        return counted if sum(n * w for _, n, _, w in counted) == count else None

    @classmethod
    def _quarters(cls, rect: Rectangle) -> list:
        """The halves of the halves of ``rect``, as ``(rect, weight)`` like :meth:`_children`
        (a mirrored half's parts are mirrored: their weights multiply)."""
        return [(grand, w * v) for kid, w in cls._children(rect, _SPLITS[0])
                for grand, v in cls._children(kid, _SPLITS[0])]

    @staticmethod
    def _children(rect: Rectangle, s: float) -> list:
        if rect.symmetric:
            if rect.width > 2 * rect.y1:
                xm = rect.x0 + s * rect.width
                return [(Rectangle(rect.x0, xm, rect.y0, rect.y1, True), 1),
                        (Rectangle(xm, rect.x1, rect.y0, rect.y1, True), 1)]
            ym = s * rect.y1
            return [(Rectangle(rect.x0, rect.x1, -ym, ym, True), 1),
                    (Rectangle(rect.x0, rect.x1, ym, rect.y1), 2)]
        if rect.width >= rect.height:
            xm = rect.x0 + s * rect.width
            return [(Rectangle(rect.x0, xm, rect.y0, rect.y1), 1),
                    (Rectangle(xm, rect.x1, rect.y0, rect.y1), 1)]
        ym = rect.y0 + s * rect.height
        return [(Rectangle(rect.x0, rect.x1, rect.y0, ym), 1),
                (Rectangle(rect.x0, rect.x1, ym, rect.y1), 1)]

    def _holds_zero(self, rect: Rectangle) -> bool:
        """``rect`` holds ``lam = 0`` (a known zero of order :attr:`zero_order`)."""
        return bool(self.zero_order) and self.origin is None and rect.contains(0j)

    def isolate(self, cells, tiny):
        """Rectangles holding one zero, and those smaller than ``tiny`` holding several.

        ``cells``: ``[(rect, count, center)]``; ``tiny`` is relative to ``|lam|``.
        The known zero at ``lam = 0`` is not counted among them. Returns
        ``(singles, clusters)``.
        """
        singles, clusters = [], []
        work = list(cells)
        guard = 0
        while work:
            # a generation at a time: the contours of all its splits sampled together
            split = []
            for rect, n, center in work:
                guard += 1
                if guard > 20000:
                    raise ComputationError("too many rectangles: the zeros could not be "
                                           "isolated")
                at_zero = self._holds_zero(rect)
                others = n - (self.zero_order if at_zero else 0)
                if others < 0:
                    raise ComputationError(f"{n} zeros counted in {rect}, fewer than the "
                                           f"{self.zero_order} at lam = 0")
                if others == 0:
                    continue
                if others == 1 and not at_zero:
                    singles.append((rect, center))
                    continue
                if not at_zero and rect.size < tiny * self._scale(rect.center):
                    clusters.append((rect, n, center))
                    continue
                split.append((rect, n, center))
            work = [(kid, k, c) for kids in self._split_all(split) for kid, k, c, _ in kids]
        return singles, clusters

    def _first_cut(self, rect: Rectangle, n: int, center) -> float:
        """Where :meth:`_split_all` first cuts ``rect`` (a fraction of its long side):
        midway between ``lam = 0`` and the one other zero of a strip about the real axis
        that holds both (that zero is real, and the mean of the zeros, ``center``, puts
        it at ``n center``: the zero at 0 adds nothing to their sum); else halfway.

        A pure dashpot on a rigid-body motion leaves ``lam = 0`` beside a real zero a
        hundred times nearer than the strip is long: halving took seven generations of
        contours to part them (the pure dashpot of the benchmarks: 608 evaluations), a cut
        between them takes one. A poor mean costs nothing but that: counts that do not add
        up send the strip to :meth:`_split`'s cuts.
        """
        if center is None or not rect.symmetric or rect.width <= 2 * rect.y1 or \
                not self._holds_zero(rect) or n - self.zero_order != 1:
            return _SPLITS[0]
        other = n * complex(center).real / (n - self.zero_order)
        s = (0.5 * other - rect.x0) / rect.width
        return s if 0.001 < s < 0.999 else _SPLITS[0]

    def _split_all(self, items) -> list:
        """:meth:`_split` of every ``(rect, count, center)``: the first split of all of them
        counted in one sampling of their contours; where that fails (a sample near a zero, counts
        that do not add up), each alone with :meth:`_split`'s other splits.

        A rectangle holding three zeros or more is cut into quarters at once
        (:meth:`_quarters`): the lines two generations of halves would sample, refined in
        one generation's rounds of batches (the damped Timoshenko model of the benchmarks:
        160 -> 146 ms; with two zeros the second line is often not needed)."""
        if not items:
            return []
        first = [self._quarters(rect) if n >= 3 else
                 self._children(rect, self._first_cut(rect, n, c)) for rect, n, c in items]
        try:
            found = iter(self.ap.counts_and_centers([kid for kids in first for kid, _ in kids]))
        except (NearZero, CountError):
            return [self._split(rect, n) for rect, n, _ in items]
        out = []
        for (rect, n, _), kids in zip(items, first):
            counted = self._tally(kids, [next(found) for _ in kids], n)
            out.append(counted if counted is not None else self._split(rect, n))
        return out

    def from_estimates(self, rect: Rectangle, n: int, guesses) -> list | None:
        """The ``n`` zeros counted in ``rect`` (above the real axis), refined from
        ``guesses`` (complex estimates of them, e.g. the model's undamped eigenvalues), or
        None unless that gives ``n`` distinct eigenvalues in ``rect``.

        Each is refined and proved as an isolated zero is (:meth:`refine_complex`, which
        rejects a refinement that leaves ``rect``); ``n`` distinct ones are all the zeros
        ``rect`` holds, by its count, so the rectangle needs no subdivision: where the
        estimates are good (light damping) this replaces the isolation, whose contours
        cost most of a damped search (the damped Timoshenko model of the benchmarks: 2710
        of its 3309 evaluations). Two refinements closer than ``10**(2 - digits)`` relative
        are taken for one zero (and then, fewer than ``n``: None; the caller isolates).
        """
        if rect.symmetric or n <= 0 or self.origin is not None:
            return None
        guesses = [complex(g) for g in guesses]
        # the estimates within the rectangle first, where they are as many as its zeros
        # (light damping moves a frequency little; above a crowd of nearly undamped modes
        # the reach below held 109 estimates for 4 zeros, whose refinements all landed
        # inside: 2.5 s, then the isolation)
        within = [g for g in guesses if rect.y0 <= g.imag <= rect.y1]
        if len(within) == n:
            return self._from_starts(rect, n, within)
        # (an estimate a little beyond the rectangle's ends starts just inside them: the
        # damping lowers a frequency, and may lift the count's last one in)
        reach = _ESTIMATE_REACH * rect.height
        near = [g for g in guesses if rect.y0 - reach <= g.imag <= rect.y1 + reach]
        return self._from_starts(rect, n, near) if len(near) >= n else None

    def _from_starts(self, rect: Rectangle, n: int, guesses) -> list | None:
        """:meth:`from_estimates` from ``guesses`` (complex), each moved into ``rect``."""
        inside = [complex(0.0, min(max(g.imag, rect.y0), rect.y1)) + g.real for g in guesses]
        # first in double precision, all at once, and only to 1e-7: estimates that do not
        # lead to ``n`` distinct zeros in ``rect`` cost little more (heavy damping:
        # example 4's)
        # (a start whose steps had not settled when they ran out is dropped before its
        # refinement in the proof arithmetic: an estimate 8 % off, its secant steps stopped
        # at no zero, cost 2.4 s there before the rectangle went to the isolation anyway)
        ends, settled = self._double_secant(inside, 1e-7, 12)
        near = [z for z, ok in zip(map(complex, ends), settled) if ok and rect.contains(z)]
        start = []
        for z in near:
            if not any(abs(z - w) <= 1e-5 * max(abs(z), self.p.lam_ref) for w in start):
                start.append(z)
        if len(start) != n:
            return None
        found = [e for e in self.refine_complex([(rect, z) for z in start], estimated=True)
                 if e is not None]
        distinct = []
        for e in found:
            z = complex(e.lam)
            if not rect.contains(z):
                return None
            # (two refinements of one zero agree to the digits asked; distinct zeros that
            # close go to the isolation, which tells them apart)
            if any(abs(z - complex(d.lam)) <= 10.0 ** (2 - self.digits) * max(abs(z), self.p.lam_ref)
                   for d in distinct):
                continue
            distinct.append(e)
        return distinct if len(distinct) == n else None

    # -- refinement: complex zeros, all at once -----------------------------------------------
    def _double_secant(self, starts, stop: float = _DOUBLE_STEP, steps: int = 40):
        """Secant steps on the double-precision ``Delta`` from ``starts``, all at once.

        Returns the estimates (complex) and whether each one's steps ended before they
        ran out. A root stops when its step is below ``stop``
        relative, or its point is too close for double precision; all after ``steps``.
        Double precision alone: a point it does not trust (the pivoted determinant's
        condition number there was 1e13 to 1e17 on the damped models of the benchmarks:
        the zero, to double precision) ends its root's steps, where the contours' function
        evaluated it again in 30-digit balls, to the same estimate (the damped Timoshenko
        model: about a third of its solve; example 4 0.31 -> 0.25 s).
        """
        z0 = np.array([complex(s) for s in starts])
        if z0.size == 0:
            return [], []
        h = 1e-7 * np.maximum(np.abs(z0), self.p.lam_ref)
        z1 = z0 + h * (1 + 1j)
        la, ph, ok = self.p.kernel.log_delta(np.concatenate([z0, z1]))
        R = z0.size
        ref = np.where(np.isfinite(la[:R]), la[:R], 0.0)
        with np.errstate(all="ignore"):
            f0 = np.exp(la[:R] - ref + 1j * ph[:R])
            f1 = np.exp(la[R:] - ref + 1j * ph[R:])
        active = ok[:R] & ok[R:] & np.isfinite(f0) & np.isfinite(f1)
        best = z0.copy()
        failed = np.zeros(R, dtype=bool)
        for _ in range(steps):
            idx = np.nonzero(active)[0]
            if idx.size == 0:
                break
            with np.errstate(all="ignore"):
                z2 = z1[idx] - f1[idx] * (z1[idx] - z0[idx]) / (f1[idx] - f0[idx])
            good = np.isfinite(z2)
            step = np.abs(z2 - z1[idx])
            la2, ph2, ok2 = self.p.kernel.log_delta(np.where(good, z2, z1[idx]))
            with np.errstate(all="ignore"):
                f2 = np.exp(la2 - ref[idx] + 1j * ph2)
            for j, i in enumerate(idx):
                if not good[j]:
                    active[i] = False
                    failed[i] = True
                    continue
                best[i] = z2[j]
                z0[i], f0[i], z1[i], f1[i] = z1[i], f1[i], z2[j], f2[j]
                if not ok2[j] or not np.isfinite(f2[j]) or \
                        step[j] <= stop * abs(z2[j]):
                    active[i] = False
        return best.tolist(), (~(active | failed)).tolist()

    def _digits_for(self, z: complex, small=None) -> int:
        extra = 0
        if small is not None and small > 0:
            extra = max(0, math.ceil(math.log10(abs(z) / small)))
        return max(self.digits + _GUARD + extra, self.floor)

    def _secants(self, starts, digits, tols, kernel=None, maxsteps=60):
        """High-precision secant steps from ``starts`` (global mpmath numbers) at
        ``digits``, all at once; each stops below its tolerance. Returns
        ``[(z, last step) or (None, None)]``."""
        ctx = MP.from_digits(digits + 10).ctx
        R = len(starts)
        z0 = [ctx.mpc(s) for s in starts]
        h = [max(abs(z), ctx.mpf(self.p.lam_ref)) * ctx.mpf(10) ** (-(digits // 2 + 4))
             for z in z0]
        z1 = [z + hi * ctx.mpc(1, 1) for z, hi in zip(z0, h)]
        vals = self.p.values([_global(z) for z in z0 + z1], digits, kernel)
        f0, f1 = vals[:R], vals[R:]
        out: list = [(None, None)] * R
        # (no value: a point so close to a zero that the working precision cannot tell it
        # apart; it is the zero to that precision)
        for i in range(R):
            if f0[i] is None:
                out[i] = (_global(z0[i]), mpmath.mpf(0))
            elif f1[i] is None:
                out[i] = (_global(z1[i]), _global(h[i]).real)
        active = [f0[i] is not None and f1[i] is not None for i in range(R)]
        for _ in range(maxsteps):
            idx, new = [], []
            for i in range(R):
                if not active[i]:
                    continue
                if f1[i] == 0:
                    out[i], active[i] = (_global(z1[i]), mpmath.mpf(0)), False
                    continue
                a, b = ctx.mpc(f0[i]), ctx.mpc(f1[i])
                if a == b:
                    active[i] = False
                    continue
                z2 = z1[i] - b * (z1[i] - z0[i]) / (b - a)
                step = abs(z2 - z1[i])
                if not ctx.isfinite(step):
                    active[i] = False
                    continue
                if step <= tols[i]:
                    out[i], active[i] = (_global(z2), _global(step).real), False
                    continue
                idx.append(i)
                new.append(z2)
            if not idx:
                break
            vals = self.p.values([_global(z) for z in new], digits, kernel)
            for i, z2, v in zip(idx, new, vals):
                if v is None:
                    out[i], active[i] = (_global(z2), _global(abs(z2 - z1[i])).real), False
                    continue
                z0[i], f0[i], z1[i], f1[i] = z1[i], f1[i], z2, v
        return out

    def refine_complex(self, items, estimated: bool = False) -> list:
        """The zeros of one-zero rectangles ``(rect, center)`` above the real axis.

        Returns an :class:`Eigenvalue` or None (the secant strayed: split and retry)
        per item. ``estimated``: the centers are double-precision estimates already
        (:meth:`from_estimates`), which the high-precision steps start from.
        """
        if not items:
            return []
        if estimated:
            estimates = [c for _, c in items]
        elif self.origin is not None:
            # a cluster's zeros: closer than double precision tells apart, so no double
            # secant; the high-precision steps start at the rectangles' centres
            ctx = MP.from_digits(self.floor + 10).ctx
            estimates = [_global(self._at(c if c is not None and r.contains(c) else r.center,
                                          ctx)) for r, c in items]
        else:
            estimates, _ = self._double_secant([self._at(c if c is not None and r.contains(c)
                                                         else r.center) for r, c in items])
        state = []
        for (rect, _), z in zip(items, estimates):
            zf = complex(z)
            small = min(abs(zf.real), abs(zf.imag)) or None
            state.append(dict(rect=rect, z=_global(z), zf=zf, small=small, extra=0,
                              tighter=0, done=None))
        conservative = not self.p.model.damped
        for _ in range(12):
            todo = [s for s in state if s["done"] is None]
            if not todo:
                break
            # one precision per round: the largest any of them needs
            digits = max(self._digits_for(s["zf"], s["small"]) + s["extra"] + s["tighter"]
                         for s in todo)
            if digits > MAX_DIGITS:
                raise ComputationError(f"cannot reach {self.digits} digits for the eigenvalue "
                                       f"near {todo[0]['zf']:.6g} within {MAX_DIGITS} working "
                                       "digits")
            tols = []
            for s in todo:
                target = min(abs(s["zf"].real) or abs(s["zf"]), abs(s["zf"].imag) or abs(s["zf"]))
                if conservative:
                    target = abs(s["zf"].imag) or abs(s["zf"])
                s["tol"] = _tol(-(self.digits + 4 + s["tighter"]), target)
                if self.p.balls:
                    # the box Rouche's theorem proves (see _rouche), and the estimate well
                    # inside it (in a cluster's sub-search too: a close pair 6e-8 apart
                    # was left to 'two precisions' where boxes of 1e-30 prove each zero)
                    s["box"] = min(_tol(-(self.digits + 3 + s["tighter"]), target),
                                   _tol(-(self.digits + 15), s["zf"]))
                    s["tol"] = _tol(-3, s["box"])
                    digits = max(digits, _decades(s["box"], abs(s["zf"])) + 10)
                tols.append(s["tol"])
            first = self._secants([s["z"] for s in todo], digits, tols)
            ok = []
            for s, (za, _) in zip(todo, first):
                margin = 1e-9 * s["rect"].size
                if za is None or not s["rect"].contains(self._local(za), margin):
                    s["done"] = False           # strayed
                else:
                    s["za"] = za
                    ok.append(s)
            if self.p.balls:
                ok = self._prove_boxes(ok, digits, conservative)
            second = self._secants([s["za"] for s in ok], digits + 15,
                                   [s["tol"] / 10 ** 5 for s in ok])
            for s, (zb, _) in zip(ok, second):
                margin = 1e-9 * s["rect"].size
                if zb is None or not s["rect"].contains(self._local(zb), margin):
                    s["done"] = False
                    continue
                self._judge(s, zb, digits, conservative)
        out = []
        idle = [s for s in state if isinstance(s["done"], Eigenvalue) and s.get("idle")]
        if idle and self.p.balls and self.origin is None:
            # the imaginary part of an undamped mode of a damped model: a box about it
            # straddling Re lam = 0 (which itself stays a numerical identification)
            D = self.digits
            items = []
            for s in idle:
                z = s["done"].lam
                items.append((z, min(_tol(-(D + 3), z.imag), _tol(-(D + 15), z))))
            digits = max(_decades(r, abs(z)) for z, r in items) + 20
            for s, (z, r), ok in zip(idle, items, self._rouche(items, digits)):
                if ok and _prints_alike(_box(z, r)[1], D):
                    s["done"] = Eigenvalue(z, 1, D, _box(z, r), DAMPED_PROOFS["rouche_idle"])
        for s in state:
            out.append(s["done"] if isinstance(s["done"], Eigenvalue) else None)
        return out

    def _prove_boxes(self, items, digits, conservative) -> list:
        """Accept the estimates Rouche's theorem proves alone in their box; return the rest.

        A zero whose real part looks like rounding noise (an undamped mode of a
        damped model) is left to :meth:`_judge`, which identifies it.
        """
        D = self.digits
        tried, rest = [], []
        for s in items:
            z = s["za"]
            if conservative:
                z = _imaginary(z)
            elif _TOL.mpf(abs(z.real)) < _tol(-(D + 25), z):
                rest.append(s)
                continue
            tried.append((s, z))
        proved = self._rouche([(z, s["box"]) for s, z in tried], digits + 10)
        for (s, z), ok in zip(tried, proved):
            r = s["box"]
            box = _box(z, r)
            if ok and all(_prints_alike(ends, D) for part, ends in zip((z.real, z.imag), box)
                          if part != 0):
                s["done"] = Eigenvalue(z, 1, D, _box(z, r), DAMPED_PROOFS["rouche"])
            else:
                rest.append(s)
        return rest

    def _rouche(self, items, digits) -> list:
        """Prove exactly one zero of ``Delta`` in each box ``z -+ r (1 + i)``, in balls.

        With ``M`` an upper bound of ``|Delta|`` on a disk of radius ``rho`` about ``z``
        (one ball evaluation over the square holding it), Cauchy's estimate bounds
        ``|Delta''| <= 8 M / rho**2`` within ``rho / 2``. The slope ``s = (Delta(z + h) -
        Delta(z)) / h`` of two exact points then differs from ``Delta'(z)`` by at most
        ``4 M h / rho**2``, and ``L(w) = Delta(z) + s (w - z)`` from ``Delta`` by at most
        ``eps = 4 M |w - z| (h + |w - z|) / rho**2`` (Taylor with that remainder). ``L``
        has one zero ``z* = z - Delta(z) / s``; if it lies in the box and ``eps < |s|
        dist(z*, boundary)`` on the boundary, Rouche's theorem gives ``Delta`` exactly one
        zero in the box too. Every quantity is a ball; the comparisons hold for all of
        its points. ``rho`` is tried at ``1e14, 1e10, 1e18`` times ``r``, then between:
        large enough for the remainder, small enough for the ball over the disk to stay
        narrow (the square is enclosed by :meth:`symtmm.numeric.evaluator.Evaluator.enclose`,
        a dense determinant per square: each radius only for the boxes the ones before
        left unproved, and first the one that proves most: on the damped examples and
        models of the benchmarks ``1e14`` proves every box, ``1e10`` from two in seven
        to all). The proofs take at most :data:`_PROOF_SHARE` times the seconds of the
        search before them (at least :data:`_PROOF_FLOOR`); the boxes they leave are the
        other proofs'.
        """
        out = [False] * len(items)
        share = max(_PROOF_FLOOR, _PROOF_SHARE * (time.perf_counter() - self.p.started))
        try:
            with time_budget(share):
                self._rouche_rounds(items, digits, out)
        except OverBudget:
            check_time()            # (the search's own budget, if that is what is spent)
        return out

    def _rouche_rounds(self, items, digits, out) -> None:
        """:meth:`_rouche`'s rounds, each box proved set in ``out`` as it is."""
        todo = list(range(len(items)))
        given_up: set = set()
        every = (10, 12, 13, 14, 15, 16, 17, 18)
        best: dict = {}             # per box the radius that came nearest to proving it
        # the enclosure over the disk grows faster than its radius beyond some radius,
        # and its excess over |Delta| can be large (measured: 1e14 near a zero of the
        # tuned-mass-damper example): where three radii miss the window between the two,
        # the radii between; the balls of the two points must be narrow beside the box:
        # where rounding grew too much for that, the same proof with more digits. A box
        # whose points passed and whose disks all failed is tried with more digits at its
        # best radius only: there the enclosure's excess is the box's width through the
        # dense determinant, which more digits leave as it is (a fuzzed model of five
        # beams: the same bound at 52, 82 and 112 digits, 16 dense determinants a box)
        for extra, factors in ((0, (14, 10, 18)), (0, (12, 13, 15, 16, 17)), (30, every),
                               (60, every)):
            if not todo:
                break
            groups: dict = {}
            for i in todo:
                groups.setdefault((best[i],) if extra and i in best else factors, []).append(i)
            # (a group in parts: what the proofs' share of time cuts short keeps the parts
            # before; each part's first box is also its test of hopelessness)
            parts = [(radii, members[j:j + _PROOF_PART]) for radii, members in groups.items()
                     for j in range(0, len(members), _PROOF_PART)]
            for radii, members in parts:
                proved, nearest, hopeless = self._rouche_once([items[i] for i in members],
                                                              digits + extra, radii)
                for i, ok, k in zip(members, proved, nearest):
                    out[i] = ok
                    if k is not None:
                        best[i] = k
                # (more digits leave the enclosures' excess as it is: such a box is left
                # to the other proofs)
                given_up.update(members[j] for j in hopeless)
            todo = [i for i in todo if not out[i] and i not in given_up]

    def _rouche_once(self, items, digits, factors) -> tuple:
        """One attempt of :meth:`_rouche` at ``digits``, with disks of radii ``10**k r`` for
        ``k`` in ``factors``: ``(proved, nearest, hopeless)``, per box whether it is proved
        and the ``k`` whose disk came nearest to proving it (None where its points did not
        pass), and the boxes no disk can prove (:data:`_HOPELESS`)."""
        if not items:
            return [], [], set()
        import flint

        ar = Ball.from_digits(digits)
        with ar:
            centres = [(ar.number(z), ar.number(r)) for z, r in items]
            values, _ = self.p.kernel.delta([p for zc, rr in centres for p in (zc, zc + rr)],
                                            ar, retry=False)
            # per box: the slope s, the distance of z* from the boundary and the reach of
            # the boundary from z, where the linear model's zero lies inside
            model: dict = {}
            for i, (zc, rr) in enumerate(centres):
                f0, f1 = values[2 * i], values[2 * i + 1]
                # (at a point this close to the zero the pivot through it may hold 0: its
                # enclosure of Delta still holds wherever it is finite)
                if not (f0.abs_upper().is_finite() and f1.abs_upper().is_finite()):
                    continue
                s = (f1 - f0) / rr
                zs_off = -f0 / s                     # z* - z
                off = max(zs_off.real.abs_upper(), zs_off.imag.abs_upper())
                if off < rr:
                    model[i] = (s, rr - off, rr * flint.arb(2).sqrt())   # (|w - z| on it)
            # the disks one radius at a time, each for the boxes the radii before left
            # unproved: the first proves most (an enclosure is a dense determinant each)
            out = [False] * len(items)
            nearest: list = [None] * len(items)
            margin: dict = {}
            hopeless: set = set()
            todo = list(model)
            for k in factors:
                if not todo:
                    break
                tested = self._disks(todo[:1], k, centres, model, ar) \
                    if k == factors[0] and len(todo) > 1 else []
                if tested and tested[0][2] is not None and tested[0][2] > _FAR_OUT and \
                        2 * model[todo[0]][0].abs_lower() > model[todo[0]][0].abs_upper():
                    # the first box's enclosure exceeds what a disk of any radius could
                    # use by far more than the disks' range, its slope known (more digits
                    # leave the ratio as it is): K is too ill-conditioned at these points
                    # for the dense enclosure (its preconditioner, the inverse of a nearly
                    # singular midpoint, loses the digits), which the boxes of one search
                    # share (a campaign model with crowded modes of a soft beam on a
                    # foundation: every box 1e83 beyond, 60 dense determinants of 199
                    # freedoms, 55 s, in vain)
                    i, _, ratio = tested[0]
                    margin[i], nearest[i] = ratio, k
                    hopeless.update(todo)
                    break
                still = []
                done_first = {i for i, _, _ in tested}
                for i, proved, ratio in tested + self._disks(
                        [i for i in todo if i not in done_first], k, centres, model, ar):
                    if proved:
                        out[i] = True
                        continue
                    s = model[i][0]
                    if ratio is not None and (i not in margin or ratio < margin[i]):
                        margin[i], nearest[i] = ratio, k
                    # a larger disk lowers the ratio at best as its radius grows (M
                    # grows at least like the slope times the radius), and more digits
                    # leave it as it is once the slope is known: where no smaller disk
                    # is left to try, a box out of reach of the largest is given up (an
                    # ill-conditioned K, whose enclosures exceed |Delta| by 1e130: 90
                    # dense determinants of 148 freedoms in vain)
                    later = factors[factors.index(k) + 1:]
                    if i in margin and not any(q < k for q in later) and \
                            2 * s.abs_lower() > s.abs_upper() and \
                            margin[i] > _HOPELESS * 10.0 ** (max(later, default=k) - k):
                        hopeless.add(i)
                    else:
                        still.append(i)
                todo = still
            for i in model:
                if nearest[i] is None and not out[i]:
                    nearest[i] = factors[0]
        return out, nearest, hopeless

    def _disks(self, boxes, k, centres, model, ar) -> list:
        """Rouche's test of the boxes ``boxes`` (indices) with disks of radius ``10**k r``:
        per box ``(index, proved, ratio)``, ``ratio`` the test's left side over its right
        (None where the enclosure is infinite or the slope not bounded from 0)."""
        import flint

        if not boxes:
            return []
        rho = {i: centres[i][1] * 10 ** k for i in boxes}
        squares = [flint.acb(flint.arb(centres[i][0].real.mid(), rho[i]),
                             flint.arb(centres[i][0].imag.mid(), rho[i])) for i in boxes]
        # (the bits the narrowest box needs serve the wider ones too)
        narrowest = min(float(rho[q] / abs(centres[q][0]).mid()) for q in boxes)
        out = []
        for i, bound in zip(boxes, self.p.kernel.enclose(
                squares, _box_arithmetic(ar, narrowest))):
            s, dist, reach = model[i]
            rr = centres[i][1]
            M = bound.abs_upper()
            lhs, rhs = 4 * M * reach * (rr + reach) / (rho[i] * rho[i]), s.abs_lower() * dist
            if M.is_finite() and lhs < rhs:
                out.append((i, True, None))
            elif M.is_finite() and rhs > 0:
                out.append((i, False, float((lhs / rhs).mid())))
            else:
                out.append((i, False, None))
        return out

    def _judge(self, s, zb, digits, conservative):
        """Accept ``zb`` (the refinement 15 digits higher) or say what the next round needs."""
        za = s["za"]
        ctx = MP.from_digits(digits + 30).ctx
        za_c, zb_c = ctx.mpc(za), ctx.mpc(zb)
        size = abs(zb_c)
        re_b, im_b = abs(zb_c.real), abs(zb_c.imag)
        err = abs(za_c - zb_c)          # bounds the error of za; zb is far better
        rel = ctx.mpf(10) ** (-(self.digits + 2))
        ok_re, ok_im = err <= rel * re_b, err <= rel * im_b
        if conservative:
            # no dashpot: a conservative model, every eigenvalue is imaginary
            zb_c = ctx.mpc(0, zb_c.imag)
            ok_re = True
        if ok_re and ok_im:
            if s["tighter"] >= 30 or all(_prints_alike((part - err, part + err), self.digits)
                                         for part in (zb_c.real, zb_c.imag) if part != 0):
                s["done"] = Eigenvalue(_global(zb_c), 1, self.digits, None,
                                       DAMPED_PROOFS["agree"])
                return
            s["tighter"] += 10      # too close to a rounding boundary to tell yet
            s["z"], s["zf"] = _global(zb_c), complex(zb_c)
            return
        floor = ctx.mpf(10) ** (-(self.digits + 25)) * size
        if ok_im and re_b < floor and self._idle(_global(zb_c), digits + 15, 1):
            # the real part is rounding noise and the dashpots stay idle
            self.idle += 1
            s["idle"] = True
            s["done"] = Eigenvalue(_global(ctx.mpc(0, zb_c.imag)), 1, self.digits, None,
                                   DAMPED_PROOFS["agree"])
            return
        # the smaller part needs more digits: aim at it
        new_small = float(max(min(re_b, im_b), floor / 10 ** 5))
        if s["small"] is None or new_small < s["small"]:
            s["small"] = new_small
        else:
            s["extra"] += 20
        s["z"], s["zf"] = _global(zb_c), complex(zb_c)

    def _idle(self, z, digits, m) -> bool:
        """``z`` is also an ``m``-fold zero of the model without and with doubled dashpots."""
        tol = _tol(-(self.digits + (20 if m == 1 else 2)), z)
        for factor in (0, 2):
            kernel = self.p.auxiliary(factor)
            before = kernel.evaluations
            if m == 1:
                zt, _ = self._secants([z], digits, [tol / 10 ** 5], kernel, maxsteps=40)[0]
            else:
                zt, _ = self._newton_multiple(z, digits, tol / 10 ** 5, m, kernel)
            self.p.extra += kernel.evaluations - before
            if zt is None or abs(zt - z) > tol:
                return False
        return True

    def _newton_multiple(self, z, digits, tol, m, kernel=None, maxsteps=60, best=False):
        """Newton on ``f**(1/m)``: ``z - m f/f'``, quadratic at an ``m``-fold zero.

        ``f'`` is a forward difference with a step of half the working digits. Returns
        ``(z, last step)``, or ``(None, None)`` where it does not converge; with ``best``,
        then ``(z, None)`` with the iterate of smallest ``|f|``: about ``m`` distinct zeros
        closer than the start, the iterates jump about their mean (two zeros ``c +- d``:
        ``w -> d**2 / w`` about ``c``), and the smallest ``|f|`` lies nearest it.
        """
        ctx = MP.from_digits(digits + 10).ctx
        z = ctx.mpc(z)
        nearest = (None, None)
        for _ in range(maxsteps):
            h = max(abs(z), ctx.mpf(self.p.lam_ref)) * ctx.mpf(10) ** (-(digits // 2))
            f0, f1 = self.p.values([_global(z), _global(z + h)], digits, kernel)
            if f0 is None or f1 is None:
                return nearest if best and nearest[0] is not None else (None, None)
            if f0 == 0:
                return _global(z), mpmath.mpf(0)
            if best and (nearest[1] is None or abs(ctx.mpc(f0)) < nearest[1]):
                nearest = (_global(z), abs(ctx.mpc(f0)))
            deriv = (ctx.mpc(f1) - ctx.mpc(f0)) / h
            if deriv == 0:
                return None, None
            step = m * ctx.mpc(f0) / deriv
            z = z - step
            if not ctx.isfinite(abs(step)):
                return None, None
            if abs(step) <= tol:
                return _global(z), _global(abs(step)).real
        return (nearest[0], None) if best else (None, None)

    # -- refinement: real zeros, all at once ----------------------------------------------------
    def refine_real(self, rects) -> list:
        """The single real zero of each symmetric rectangle, bracketed on the real axis.

        Anderson–Björck steps on the double-precision ``Delta`` (real there), all at
        once, then pairs ``c (1 -+ h)`` about each estimate in the proof arithmetic:
        strictly opposite signs prove the zero between them, and their values give the
        next estimate by a secant step (:meth:`_pairs`).
        """
        if not rects:
            return []
        a = np.array([self._at(r.x0).real for r in rects], dtype=float)
        b = np.array([self._at(r.x1).real for r in rects], dtype=float)
        if self.origin is not None:
            # (a cluster's local search: its rectangles are far below double precision)
            a = [self._at(r.x0, MP(256).ctx).real for r in rects]
            b = [self._at(r.x1, MP(256).ctx).real for r in rects]
            return self._pairs([(x + y) / 2 for x, y in zip(a, b)], list(zip(a, b)))
        R = len(rects)
        la, ph, _ = self.p.log_delta(np.concatenate([a, b]).astype(complex))
        signs = np.where(np.cos(ph) < 0, -1.0, 1.0)
        fa, fb, ref = scaled_ends(la, signs)

        def probe(c, idx):
            # (the double values alone: a point too near the zero for them stops its
            # bracket there, and the pairs take it from that estimate; re-evaluated in
            # balls, as the contour's values are, each cost a third of a millisecond
            # and told the pairs nothing they do not find)
            lc, pc, okc = self.p.kernel.log_delta(c.astype(complex))
            sc = np.where(np.cos(pc) < 0, -1.0, 1.0)
            # (the side by the sign itself: a value far below the larger end's scales to
            # 0, and was taken as undecided, stopping the bracket there)
            side = np.where(sc == signs[R:][idx], 1, -1)
            return scaled(lc, sc, ref[idx]), np.where(okc & np.isfinite(lc), side, 0)

        # (a sign change by the signs: an end far below the other scales to a signed zero,
        # and the product of the values was -0: the contour's rectangle of a pure-dashpot
        # beam, |Delta| 1e674 and 1e338 at its ends, went to the proof stage from its
        # midpoint, 38 from the zero)
        ok = np.isfinite(la[:R]) & np.isfinite(la[R:]) & (signs[:R] != signs[R:])
        best = shrink(a[ok], b[ok], fa[ok], fb[ok], lambda c, i: probe(c, np.nonzero(ok)[0][i]),
                      1e-13) if ok.any() else []
        estimates = 0.5 * (a + b)
        estimates[ok] = best
        outer = [(self._at(r.x0).real, self._at(r.x1).real) for r in rects]
        return self._pairs(estimates.tolist(), outer)

    def _pairs(self, estimates, outer) -> list:
        """Real zeros proved by the signs of ``Delta`` at pairs about each estimate.

        ``outer``: a bracket per zero with one zero inside. Its ends' signs are taken
        first; then every round evaluates, for each zero, the pair ``c (1 -+ h)`` about
        its estimate: strictly opposite signs prove the zero between them (balls:
        ``sign change``; mpmath: the same signs again 15 digits higher), and the pair's
        values give the next estimate by a secant step (``h`` from ``1e-11`` to
        ``10**-(D+3)``; narrower where the ends would print differently).
        """
        D = self.digits
        scale = max(max(abs(float(x)), abs(float(y))) for x, y in outer)
        digits = self._digits_for(scale) + 5
        R = len(estimates)
        target = _tol(-(D + 3))
        while digits <= MAX_DIGITS:
            ctx = MP.from_digits(digits + 20).ctx
            a = [ctx.mpf(x) for x, _ in outer]
            b = [ctx.mpf(y) for _, y in outer]
            ends = self._real_values([_global(t) for t in a + b], digits)
            sa, sb = ends[:R], ends[R:]
            for i, (u, v) in enumerate(zip(sa, sb)):
                if u is not None and v is not None and (u > 0) == (v > 0):
                    # (signs that are certain: more digits cannot change them, and an odd
                    # count between them is impossible; it came from a misled count)
                    raise ComputationError(
                        f"the search counted one real eigenvalue between "
                        f"{float(outer[i][0]):.6g} and {float(outer[i][1]):.6g}, where Delta "
                        "has the same sign at both ends: the count was misled (eigenvalues "
                        "crowding near the search rectangles' edges?)")
            if any(u is None or v is None for u, v in zip(sa, sb)):
                digits += max(20, digits // 2)
                continue
            c = [min(max(ctx.mpf(e), a[i]), b[i]) for i, e in enumerate(estimates)]
            h = [ctx.mpf("1e-11")] * R
            done: list = [None] * R
            widths: list = [[] for _ in range(R)]     # each bracket's, round by round
            for _ in range(60):
                tests, owner = [], []
                for i in range(R):
                    if done[i] is None:
                        e = h[i] * max(abs(c[i]), ctx.mpf(self.p.lam_ref) * target)
                        tests += [max(c[i] - e, (a[i] + c[i]) / 2),
                                  min(c[i] + e, (c[i] + b[i]) / 2)]
                        owner.append(i)
                if not owner:
                    break
                values = self._real_values([_global(t) for t in tests], digits)
                for j, i in enumerate(owner):
                    t1, t2 = tests[2 * j:2 * j + 2]
                    s1, s2 = values[2 * j:2 * j + 2]
                    for t, sv in ((t1, s1), (t2, s2)):
                        if sv is None:
                            continue
                        if (sv > 0) == (sa[i] > 0) and t > a[i]:
                            a[i] = t
                        elif (sv > 0) == (sb[i] > 0) and t < b[i]:
                            b[i] = t
                    proved = s1 is not None and s2 is not None and (s1 > 0) != (s2 > 0)
                    if proved and h[i] <= target:
                        if _prints_alike((t1, t2), D):
                            done[i] = (t1, t2)
                            continue
                        h[i] /= 100
                    step = None
                    if s1 is not None and s2 is not None and s1 != s2:
                        step = t2 - ctx.mpf(s2) * (t2 - t1) / (ctx.mpf(s2) - ctx.mpf(s1))
                    # (a secant step on Delta, which grows like an exponential along the
                    # real axis, crawls from an estimate far from the zero: 0.09 a round
                    # across a bracket of 78 when the contour's estimate was its midpoint.
                    # Where two rounds have not halved the bracket, its midpoint)
                    widths[i].append(b[i] - a[i])
                    crawl = len(widths[i]) > 2 and widths[i][-1] > widths[i][-3] / 2
                    if step is None or not a[i] < step < b[i] or crawl:
                        step = (a[i] + b[i]) / 2
                        h[i] = min(h[i], (b[i] - a[i]) / (8 * max(abs(step), ctx.mpf(1e-300))))
                        if crawl:
                            widths[i].clear()
                    else:
                        # the next pair as wide as twice this step: the secant's next error
                        # lies within it unless it converges slower than by halves, so the
                        # pair straddles the zero and proves it. (At the digits asked: a
                        # real zero whose secant steps shrank by 1/60 a round, 1e-33 pairs
                        # on one side of it, never straddling within the rounds, at 55 to
                        # 621 digits, until the digits ran out)
                        h[i] = min(h[i], max(target, 2 * abs(step - c[i]) /
                                             max(abs(step), ctx.mpf(1e-300))))
                    c[i] = step
            if any(d is None for d in done):
                digits += max(20, digits // 2)
                continue
            if not self.p.balls:
                again = self._real_values([_global(t) for d in done for t in d], digits + 15)
                if any(v is None for v in again) or any(
                        (again[2 * i] > 0) == (again[2 * i + 1] > 0) for i in range(R)):
                    digits += max(20, digits // 2)
                    continue
            proof = DAMPED_PROOFS["ball" if self.p.balls else "mp"]
            return [Eigenvalue(_global((lo + hi) / 2), 1, D,
                               (_global(lo).real, _global(hi).real), proof) for lo, hi in done]
        raise ComputationError(f"cannot reach {D} digits for the real eigenvalue near "
                               f"{float(estimates[0]):.6g}")

    def _real_values(self, points, digits) -> list:
        """``Re Delta`` at real points, None where its sign is not certain."""
        out = []
        for v in self.p.values(points, digits):
            out.append(None if v is None or v.real == 0 else v.real)
        return out

    # -- clusters ------------------------------------------------------------------------
    def resolve_cluster(self, rect: Rectangle, m: int, center) -> list:
        """The zeros in a tiny rectangle holding ``m`` of them.

        They are one zero of multiplicity ``m`` only if a box of relative half-width
        ``10**-(D + 2 + SEPARATION_DIGITS)`` around the cluster's centre still holds
        all ``m``; otherwise they are isolated and refined one by one, however
        close, as distinct zeros.
        """
        res = self.digits + 2 + SEPARATION_DIGITS
        u = complex(center) if center is not None and rect.contains(center) else rect.center
        zf = complex(self._at(u))
        digits = m * res + _GUARD + 10
        extra = (m + 1) * res + 10
        # the contours' values: balls say where they are too wide for their phase, and
        # those points are taken again with the digits they lack (_Problem.values), so
        # they start at one resolution's digits; the worst case's m more only where the
        # zeros are that close (a campaign model's ten crowded modes 1e-7 apart, at 30
        # digits: 582 digits, 2000 bits, at every point of their contours, 40 s of 67).
        # mpmath's numbers carry no such warning: they take the worst case
        phase = res + 10 if self.p.balls else extra
        ctx = MP.from_digits(digits + 10).ctx
        z0 = self._at(u, ctx)
        tol = ctx.mpf(10) ** (-(res + 4)) * max(abs(z0), ctx.mpf(self.p.lam_ref))
        z, _ = self._newton_multiple(_global(z0), digits, tol, m, best=True)
        if rect.symmetric and z is not None:
            z = _real(z)   # the cluster is closed under conjugation
        if z is not None and rect.contains(self._local(z), 1e-9 * rect.size):
            scale = max(abs(zf), self.p.lam_ref)
            r = 10.0 ** (-res) * scale
            zc = complex(z)
            for part in (zc.real, zc.imag):
                if abs(part) > 10.0 ** (-res) * scale:
                    r = min(r, 10.0 ** (-res) * abs(part))
            box = (Rectangle(-r, r, -r, r, True) if rect.symmetric
                   else Rectangle(-r, r, -r, r))
            # |Delta| ~ r**m on the box: m res digits above the working ones carry its phase
            ap = ArgumentPrinciple(_LocalFunction(self.p, phase, z),
                                   spacing=lambda _u: r, min_step=lambda _u: r * 1e-6)
            try:
                k = ap.count(box)
            except (NearZero, CountError):
                k = -1
            if k == m:
                return [self._cluster_eigenvalue(z, m, rect.symmetric, digits, r)]
            # the cluster separates: its zeros lie about the estimate z, nearer it than to
            # the rectangle's centre by as much as they are closer than the rectangle is
            # small; local coordinates about z (floats) resolve them however close
            local = self._around(z, m, r, phase, rect)
            origin = ctx.mpc(z)
        else:
            local = None
        if local is None:
            # isolate the zeros at high precision, around the rectangle's centre
            origin = self._at(rect.center, ctx)
            if rect.symmetric:
                origin = ctx.mpc(origin.real, 0)
            shift = self._local(_global(origin))
            local = Rectangle(rect.x0 - shift.real, rect.x1 - shift.real,
                              rect.y0 if rect.symmetric else rect.y0 - shift.imag,
                              rect.y1 if rect.symmetric else rect.y1 - shift.imag,
                              rect.symmetric)
        r_min = 10.0 ** (-res) * abs(zf)
        sub = _Search(self.p, self.digits,
                      ArgumentPrinciple(_LocalFunction(self.p, phase, _global(origin)),
                                        spacing=lambda _u: local.size / 8,
                                        min_step=lambda _u: 1e-6 * r_min),
                      _global(origin))
        sub.floor = extra
        singles, clusters = sub.isolate([(local, m, None)], 10.0 ** -res)
        out = sub.refine_all(singles)
        for r, k, _ in clusters:
            out.append(sub._cluster_eigenvalue(sub._at(r.center), k, r.symmetric, digits,
                                               r.size))
        self.idle += sub.idle
        return out

    def _around(self, z, m: int, r: float, digits: int, rect: Rectangle):
        """A square about ``z`` (local coordinates about it) holding the cluster's ``m``
        zeros, wider than ``r`` by powers of 1000 up to ``rect``'s size; None if none does.

        Two zeros 1e-27 apart (relative) in a rectangle 1e-7 wide, whose centre is no
        nearer them than that: in floats about the centre, no cut falls between them
        (the contour passes within rounding of a zero), about ``z`` the first does.
        """
        rho = r
        while True:
            rho *= 1000.0
            if rho > rect.size:
                return None
            box = (Rectangle(-rho, rho, -rho, rho, True) if rect.symmetric
                   else Rectangle(-rho, rho, -rho, rho))
            ap = ArgumentPrinciple(_LocalFunction(self.p, digits, z),
                                   spacing=lambda _u, h=rho: h,
                                   min_step=lambda _u, h=rho: h * 1e-6)
            try:
                if ap.count(box) == m:
                    return box
            except (NearZero, CountError):
                continue

    def _cluster_eigenvalue(self, z, m, symmetric, digits, radius) -> Eigenvalue:
        """An ``m``-fold eigenvalue at ``z``, known to within ``radius``."""
        z = _global(z)
        if not self.p.model.damped:
            return Eigenvalue(_imaginary(z if z.imag > 0 else -z), m, self.digits, None)
        if symmetric and abs(z.imag) <= radius:
            return Eigenvalue(_real(z), m, self.digits, None)
        if abs(z.real) <= radius:
            if self._idle(z, digits, m):
                self.idle += 1
                return Eigenvalue(_imaginary(z), m, self.digits, None)
            raise ComputationError(
                f"{m} eigenvalues agree to {self.digits + SEPARATION_DIGITS} digits near "
                f"{complex(z):.6g} and their real part, below {float(radius):.1e}, cannot "
                "be given to the digits asked for")
        return Eigenvalue(z, m, self.digits, None)

    def refine_all(self, singles) -> list:
        """Refine every isolated zero; a rectangle whose secant strays is split and retried."""
        out = self.refine_real([r for r, _ in singles if r.symmetric])
        work = [(r, c) for r, c in singles if not r.symmetric]
        for _ in range(60):
            if not work:
                return out
            results = self.refine_complex(work)
            retry = []
            for (rect, center), e in zip(work, results):
                if e is not None:
                    out.append(e)
                    continue
                for kid, k, c, _ in self._split(rect, 1):
                    if k:
                        retry.append((kid, c))
                        break
            work = retry
        raise ComputationError(f"the eigenvalue in {work[0][0]} could not be refined")


def _region(omega_max: float, sigma_max: float, lam_ref: float, attempt: int):
    """Rectangles covering the search region, slightly enlarged; varied per attempt."""
    big = max(omega_max, sigma_max, lam_ref)
    jitter = (1.0, 1.37, 0.73, 1.91, 0.53)[attempt]
    delta = 0.02 * big * jitter            # beyond Re lam = 0: undamped modes inside
    half = 0.02 * big * jitter             # half-height of the symmetric strip
    left = -sigma_max - 1e-7 * big * jitter
    top = omega_max + 1e-7 * big * jitter
    rects = []
    if top > 1.5 * half:
        rects.append(Rectangle(left, delta, half, top))
    else:
        half = max(half, top)
    rects.insert(0, Rectangle(left, delta, -half, half, True))
    return rects


def _found(cells, order: int, rigid: int) -> int:
    """The eigenvalues with ``Im lam >= 0`` that counted ``cells`` hold at least: the
    symmetric strip counts conjugate pairs twice (at least half of its other zeros are
    above); the zero at ``lam = 0`` (order ``order``) counts once per rigid-body mode.
    (Halving the strip's count with the zero at 0 in it had counted a real zero beside
    a rigid turning of order 2 as nothing: the region doubled into a crowd, 4 s.)"""
    found = rigid
    for r, n, _ in cells:
        if r.symmetric:
            others = n - (order if r.contains(0j) else 0)
            found += (others + 1) // 2
        else:
            found += n
    return found


def _box_arithmetic(ar: Ball, width: float) -> Ball:
    """The balls to enclose ``Delta`` over boxes of relative half-width ``width`` in:
    ``ar``'s precision, or fewer bits where the boxes' width dominates the enclosure's
    radius (the bits the width leaves, ``_BOX_GUARD`` more for the growth of the radii in
    the dense determinant, which widens a box's enclosure some ``1e5 .. 1e8`` times:
    ``M`` need not be tighter than that). Arb's determinant of 38 freedoms: 13 ms at 181
    bits, 8 ms at 110."""
    if not 0 < width < 1:
        return ar
    bits = max(64, math.ceil(-math.log2(width)) + _BOX_GUARD)
    return Ball(bits) if bits < ar.prec else ar


#: Bits beyond those a box's relative width leaves that its enclosure is taken with.
_BOX_GUARD = 64


#: Region searches a count's search spends at most on lowering the top of its region.
_LOWER_STEPS = 8


def _lowered(model, count: int, below: float, W: float, S: float, search, cells, how):
    """``(W, search, cells, evaluations spent)``: the top ``W`` of a count's region lowered
    toward ``below`` (where the region held fewer than ``count``) by bisection, while
    the region with its strip ``-S <= Re lam <= 0`` kept still holds ``count`` and the
    doubling had overshot: every eigenvalue counted is refined and proved, and those
    beyond the ``count`` lowest are dropped. A dense spectrum above the first guess
    (a long beam on a foundation: its modes crowd above ``sqrt(kw / m)``, the first
    guess) held 57 where 2 were asked, and their proofs took a minute; the strip kept
    keeps the answer the doubled region gives (the lowest ``Im lam`` in that strip)."""
    digits, certified, order, rigid = how
    spent = 0
    found = _found(cells, order, rigid)
    for _ in range(_LOWER_STEPS):
        if found <= count + max(2, count // 4) or W - below <= 1e-3 * W:
            break
        mid = 0.5 * (below + W)
        try:
            lower, counted, wasted = _search_region(model, mid, S, digits, certified)
        except OverBudget:
            raise
        except ComputationError:
            break               # (its boundary keeps meeting eigenvalues: the higher serves)
        spent += wasted
        got = _found(counted, order, rigid)
        if got >= count:
            spent += search.p.evaluations
            W, search, cells, found = mid, lower, counted, got
        else:
            spent += lower.p.evaluations
            below = mid
    return W, search, cells, spent


def _prove_count(search: _Search, cells, digits: int) -> str:
    """The counts of the region's rectangles proved in balls (:mod:`symtmm.roots.winding`),
    checked against the double-precision ones; a note saying what was proved."""
    from .winding import proved_count
    # One contour around the whole region (the rectangles' union, symmetric about the real
    # axis, its upper half walked): the sides that separate the rectangles inside are not
    # walked, and near them (a zero close to the strip's edge) segments would be short.
    rects = [r for r, _, _ in cells]
    top = max(r.y1 for r in rects)
    whole = Rectangle(min(r.x0 for r in rects), max(r.x1 for r in rects), -top, top, True)
    n = sum(k if r.symmetric else 2 * k for r, k, _ in cells)
    res = proved_count(search.p.kernel, whole, digits, spacing=search.p.spacing)
    search.p.extra += res.evaluations
    if res.count is None:
        return f"the count in the search region is not proved: {res.reason}"
    if res.count != n:
        raise ComputationError(f"{whole} holds {res.count} zero(s) of Delta by its winding "
                               f"number in ball arithmetic, {n} by the argument principle "
                               "in double precision")
    return ("the count in the search region is proved: the winding number of Delta around "
            f"it in ball arithmetic ({res.segments} segments)")


def _count_region(search: _Search, rects):
    cells = []
    for r in rects:
        n, center = search.ap.count_and_center(r)
        cells.append((r, n, center))
    return cells


def count_in_rectangle(model: Model, re_min: float, re_max: float, im_min: float,
                       im_max: float) -> int:
    """Number of eigenvalues (with multiplicity, conjugates included) in a rectangle.

    The sides must not pass through an eigenvalue.

    Examples
    --------
    >>> from symtmm.model import Beam, Spring, Model
    >>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
    >>> m = Model((b,), (Spring("b", "ground", x="1/2", k=0, c=1),))
    >>> count_in_rectangle(m, -5.0, 1.0, 0.0, 30.0)   # the first mode, near 9.87i
    1
    """
    model = model.require_numeric()
    corners = [complex(x, y) for x in (re_min, re_max) for y in (im_min, im_max)]
    problem = _Problem(model, 1.05 * max(abs(c) for c in corners))
    ap = ArgumentPrinciple(problem.log_delta, problem.spacing, problem.min_step)
    try:
        return ap.count(Rectangle(re_min, re_max, im_min, im_max))
    except (NearZero, CountError) as exc:
        raise ComputationError(str(exc)) from None


def _search_region(model, omega_max, sigma_max, digits, certified):
    """``(search, counted cells, evaluations spent on attempts given up)``."""
    lam_ref = _reference_frequency(model)
    last = None
    spent = 0
    for attempt in range(5):
        rects = _region(omega_max, sigma_max, lam_ref, attempt)
        lam_max = 1.05 * max(abs(complex(x, y)) for r in rects for x in (r.x0, r.x1)
                             for y in (r.y0, r.y1))
        problem = _Problem(model, lam_max, certified)
        search = _Search(problem, digits)
        try:
            return search, _count_region(search, rects), spent
        except (NearZero, CountError) as exc:
            last = exc
            spent += problem.evaluations
    raise ComputationError(f"the boundary of the search region keeps meeting eigenvalues: {last}")


def solve_damped(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
                 digits: int = 15, certified: bool | None = None,
                 prove_count: bool = False, *, beyond_count: bool = False) -> Spectrum:
    """Eigenvalues ``lam = -sigma + i omega`` (``omega >= 0``) of a damped model.

    Parameters
    ----------
    model : Model
        Numeric; undamped models work too (their eigenvalues are then found
        as zeros in the complex plane, without using that they are imaginary).
    count : int, optional
        The ``count`` eigenvalues of smallest ``Im lam`` (with multiplicity)
        in ``-sigma_max <= Re lam <= 0``; ``omega_max`` is doubled from a
        first guess until the region holds that many.
    omega_max : float, optional
        All eigenvalues with ``0 <= Im lam <= omega_max``.
    sigma_max : float, optional
        Search ``-sigma_max <= Re lam <= 0``; default ``2 * omega_max``
        (:func:`default_sigma_max`).
    digits : int
        Significant digits, all correct, in both the real and the imaginary part.
    certified : bool, optional
        The high-precision arithmetic: Arb balls (python-flint; real eigenvalues are
        then proved by a sign change of ball values), or mpmath checked at a second
        precision (False); None (default): balls where python-flint is installed.
    prove_count : bool
        Also prove the number of eigenvalues in the search region: the winding number
        of ``Delta`` around each of its rectangles in ball arithmetic
        (:mod:`symtmm.roots.winding`; python-flint). Seconds to tens of seconds; a note
        says whether it closed. Without it the count is the argument principle in
        double precision (every eigenvalue found is still proved, one by one).
    beyond_count : bool
        With ``count``: every eigenvalue of the region counted (all of them proved, the
        first ``count`` among them), not only the first ``count``.

    Returns
    -------
    Spectrum
        Ascending by ``Im lam`` (then by ``Re lam``).

    Examples
    --------
    A pinned-pinned beam with a dashpot to the ground at a quarter span:

    >>> from symtmm.model import Beam, Spring, Model
    >>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
    >>> m = Model((b,), (Spring("b", "ground", x="1/4", k=0, c="1/2"),))
    >>> spec = solve_damped(m, omega_max=100, digits=12)
    >>> [str(e) for e in spec]
    ['-0.250087667713+9.86833681264i', '-0.500026143683+39.4704802552i', '-0.249930111966+88.8216723216i']
    """
    model = checked_request(model, count, omega_max, digits)
    start = time.perf_counter()
    rigid, order = zero_order(model)
    evaluations = check_stable(model, rigid)
    if omega_max is not None:
        W = float(omega_max)
        S = default_sigma_max(W) if sigma_max is None else float(sigma_max)
        if W < 0 or S < 0:
            raise ValueError("omega_max and sigma_max must not be negative")
        search, cells, spent = _search_region(model, W, S, digits, certified)
        evaluations += spent
    else:
        # the top in a gap between the undamped modes, else the lowest pinned one; a
        # region short of the count goes to the next gap, then doubles
        tops, spent = gap_above(model, count)
        evaluations += spent
        tops = tops or [_first_guess(model)]
        W, below = tops.pop(0), 0.0
        while True:
            S = default_sigma_max(W) if sigma_max is None else float(sigma_max)
            search, cells, spent = _search_region(model, W, S, digits, certified)
            evaluations += spent
            found = _found(cells, order, rigid)
            if found >= count:
                break
            evaluations += search.p.evaluations
            below, W = W, tops.pop(0) if tops else 2.0 * W
            if W > 1e12:
                raise ComputationError(f"fewer than {count} eigenvalues below |lam| = 1e12")
        W, search, cells, spent = _lowered(model, count, below, W, S, search, cells,
                                           (digits, certified, order, rigid))
        evaluations += spent
    search.zero_order = order
    count_note = _prove_count(search, cells, digits) if prove_count else None
    with progress.stages("solve", ["isolating", "refining and proving",
                                   "close and multiple roots"]) as next_stage:
        # the rectangles above the real axis from the undamped eigenvalues, where they
        # lead to as many zeros as counted there; the others isolated by subdivision
        eigen, rest = [], []
        upper = [c for c in cells if not c[0].symmetric and c[1] > 0]
        guesses = None
        if upper:
            top = max(r.y1 for r, _, _ in upper)
            guesses, spent = estimates(model, top * (1 + _ESTIMATE_REACH), rigid)
            evaluations += spent
        for cell in cells:
            got = None if guesses is None or cell not in upper else \
                search.from_estimates(cell[0], cell[1], [complex(0, w) for w in guesses])
            if got is None:
                rest.append(cell)
            else:
                eigen += got
        singles, clusters = search.isolate(rest, _TINY)
        next_stage("refining and proving")
        eigen += search.refine_all(singles)
        next_stage("close and multiple roots")
        for rect, m, center in clusters:
            eigen += search.resolve_cluster(rect, m, center)
    eigen = [e for e in eigen if e.lam.imag >= 0]
    total = sum(e.multiplicity for e in eigen) + rigid
    notes = []
    if rigid:
        eigen.append(Eigenvalue(mpmath.mpc(0, 0), rigid, digits, (0.0, 0.0), PROOFS["exact"]))
        notes.append(f"lam = 0: {rigid} rigid-body mode(s), a zero of order {order} of Delta")
    for e in eigen:
        if e.lam.real > 0:
            raise ComputationError(f"eigenvalue {e} has a positive real part: the model is "
                                   "not passive?")
    tol = 4e-16
    if count is None:
        # keep the region asked for
        eigen = [e for e in eigen if e.lam.real >= -S * (1 + tol) - tol
                 and e.lam.imag <= W * (1 + tol) + tol]
    else:
        # the lowest of those in the region counted: its rectangles reach a little beyond
        # the top (and the strip's left edge) that they were counted for, and the count
        # that says it holds ``count`` is theirs (three modes of a soft beam on a
        # foundation 1e-6 and 6e-6 above the first: the top lowered onto it, the two
        # counted above it, and cut from the answer, which held 1 where 3 were asked)
        left = min(r.x0 for r, _, _ in cells)
        eigen = [e for e in eigen if e.lam.real >= left * (1 + tol) - tol]
        S, W = -left, max(r.y1 for r, _, _ in cells)      # (the region the note names)
    eigen.sort(key=lambda e: (e.lam.imag, e.lam.real))
    if count is not None:
        if not beyond_count:
            eigen = first(eigen, count)
        if sum(e.multiplicity for e in eigen) < count:
            raise ComputationError(f"the region counted to hold {count} eigenvalue(s) gave "
                                   f"{sum(e.multiplicity for e in eigen)}")
    notes.insert(0, f"search region: {-S:.6g} <= Re lam <= 0, 0 <= Im lam <= {W:.6g} "
                    f"({total} eigenvalue(s) with Im lam >= 0 counted in the enlarged region)")
    if count_note:
        notes.append(count_note)
    if search.idle:
        notes.append(f"Re lam = 0 for {search.idle} eigenvalue(s): also eigenvalues of the "
                     f"model without dashpots and with doubled dashpots to "
                     f"{digits + 20} digits (modes that do not move the dashpots)")
    evaluations += search.p.evaluations
    return Spectrum(tuple(eigen), digits, "default", evaluations, time.perf_counter() - start,
                    model.source or "", omega_scale(model, digits + 10), tuple(notes),
                    title=model.title)
