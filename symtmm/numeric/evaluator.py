"""A numeric model evaluated in batches, in any arithmetic: the searches' one entry point.

:class:`Evaluator` keeps the :class:`~symtmm.numeric.plan.StiffnessPlan` of a
model for each range of ``|lam|`` it is asked about (on a quarter-octave grid,
shared with other searches of the model: :func:`~symtmm.numeric.plan.plan_for`;
a plan cut for a range serves every point inside it), factorises ``K(lam)`` at a batch
of points (:func:`~symtmm.numeric.stiffness.factor`) and counts the points it
evaluates. What a factorisation gives, per point:

* ``Delta(lam) = det K * prod det U12 * P``, equal to ``det R`` of the transfer
  formulation but with no digit lost to the growth of long segments (the pieces
  are short), as ``(log|Delta|, arg Delta)`` in double precision or as a number
  of the arithmetic;
* whether every pivot can be trusted (a posteriori, from the backward error of
  ``LDL^T``; balls decide by themselves);
* for an undamped model on the frequency axis, the Wittrick–Williams count
  (:class:`symtmm.roots.count.Counter`).

Ball arithmetic without pivoting widens the radii along the band; a factorisation
with undecided pivots is redone with the bits the radii ate
(:meth:`Evaluator._ball`), once per plan.

Examples
--------
>>> import numpy as np
>>> from symtmm.model import Beam, Model, Spring
>>> beam = Beam("b", 1, 1, 1, left="pinned", right="pinned")
>>> ev = Evaluator(Model((beam,), (Spring("b", "ground", "1/4", 0, "1/2"),)), 100.0)
>>> logabs, phase, trusted = ev.log_delta(np.array([-0.250087667713 + 9.86833681264j, 5j]))
>>> bool(logabs[0] < logabs[1] - 20), trusted.tolist()   # a zero: its pivot untrusted
(True, [False, True])
"""

from __future__ import annotations

import math

import mpmath
import numpy as np

from ..deadline import check as check_time
from .arith import DOUBLE, Arithmetic, Ball
from .plan import StiffnessPlan, design_range, plan_for, plan_key
from .stiffness import Factors, factor, summary
from .threads import one_blas_thread

__all__ = ["Evaluator", "exact_mpf", "exact_mpc"]


@one_blas_thread
def _pivoted_log_delta(fa, points=None) -> tuple:
    """``(log|Delta|, arg Delta, trusted)`` at the ``points`` of double factors ``fa`` (all
    where None) whose band elimination was not trusted: from ``K`` factorised with partial
    pivoting, trusted where its condition number leaves the phase good to ``1e-6``;
    elsewhere the band's values, untrusted. A long, narrow band within the band
    (:func:`_band_pivoted`), a short or wide one densely by LAPACK."""
    from .stiffness import dense, pivots_in_band
    points = np.arange(fa.pivots.shape[0]) if points is None else points
    logabs, phase = (x[points] for x in fa.log_delta())
    limit = 1e-6 / (fa.plan.n * 2.2e-16)     # (the condition number the phase allows)
    with np.errstate(all="ignore"):
        if pivots_in_band(fa.plan.n, fa.plan.band):
            sign, logdet, cond = _band_pivoted(fa.K[points], fa.plan.band)
        else:
            sign, logdet, cond = _pivoted(dense(fa.plan, fa.K[points]), limit)
    la12, ph12 = DOUBLE.log_abs_arg(fa.det12[points])
    mult = fa.plan.multiplicity
    good = np.isfinite(logdet) & (cond < limit)
    logabs = np.where(good, logdet + (la12 * mult).sum(axis=1) + fa.plan.log_constant, logabs)
    phase = np.where(good, np.angle(sign * np.exp(1j * (ph12 * mult).sum(axis=1))), phase)
    return logabs, phase, good


def _pointlike(z, ar) -> bool:
    """Whether ``z`` is a point (an mpmath number, or a ball no wider than the rounding of
    ``ar``'s precision), not a box of the complex plane, whose radius no bits narrow."""
    if not hasattr(z, "rad"):
        return True
    return float(z.rad()) <= abs(complex(z.mid())) * 2.0 ** (8 - ar.prec)


#: Points a plan's pivoted factorisations in double precision are tried at before their
#: record decides whether they go on (:func:`_rescue_pays`) ...
RESCUE_TRIAL = 64
#: ... and the share of them they must have trusted.
RESCUE_SHARE = 0.05


def _rescue_pays(plan) -> bool:
    """Whether the double points a plan's band leaves untrusted are worth factorising with
    pivoting (:func:`_pivoted_log_delta`): yes until :data:`RESCUE_TRIAL` have been, then
    while at least :data:`RESCUE_SHARE` of them came out trusted. Where ``K`` is
    ill-conditioned at every point (a stiff short beam free to turn about its pin: its
    static stiffness cancels to a pivot 1e-15 of the others) no pivoting mends the
    rounding: a campaign model spent 79 s of its 189 in 37,004 dense factorisations that
    trusted none. Its points go on to the balls, as they did after them."""
    tried, good = plan.__dict__.get("_rescue_record", (0, 0))
    return tried < RESCUE_TRIAL or good >= RESCUE_SHARE * tried


def _rescued(plan, result) -> tuple:
    """``result`` of :func:`_pivoted_log_delta`, recorded for :func:`_rescue_pays`."""
    tried, good = plan.__dict__.get("_rescue_record", (0, 0))
    plan.__dict__["_rescue_record"] = (tried + len(result[2]), good + int(result[2].sum()))
    return result


def _pivoted(full, limit: float = math.inf) -> tuple:
    """``(sign, log|det|, condition number)`` of dense ``(B, n, n)`` matrices by LAPACK
    (small matrices: on one BLAS thread, :mod:`symtmm.numeric.threads`).

    The condition number is the 2-norm's where it may be below ``limit``; elsewhere a
    lower bound of it, at least ``limit``: ``max_j |K_jj| |K^-1 b| / |b|`` over two fixed
    vectors ``b``, one solve where a singular value decomposition costs about eight (a
    model whose untrusted points were all ill-conditioned spent 11 of its 26 s in SVDs
    that only said so).
    """
    sign, logdet = np.linalg.slogdet(full)
    cond = np.full(sign.shape, np.inf)
    regular = np.nonzero((sign != 0) & np.isfinite(logdet))[0]
    if not regular.size:
        return sign, logdet, cond
    sub = full if regular.size == sign.size else full[regular]   # (no copy: 100 MB)
    n = sub.shape[-1]
    j = np.arange(n)
    b = np.stack([np.ones(n), np.cos(2.399963229728653 * j)], axis=1)  # (golden angle)
    try:
        x = np.linalg.solve(sub, np.broadcast_to(b, sub.shape[:1] + b.shape))
    except np.linalg.LinAlgError:       # (an exactly singular one that slogdet passed)
        cond[regular] = np.linalg.cond(sub)
        return sign, logdet, cond
    column = np.abs(np.diagonal(sub, axis1=1, axis2=2)).max(axis=1)      # <= |K|
    inverse = (np.linalg.norm(x, axis=1) / np.linalg.norm(b, axis=0)).max(axis=1)
    lower = column * inverse
    lower[~np.isfinite(lower)] = np.inf
    cond[regular] = lower
    maybe = np.nonzero(lower < limit)[0]
    if maybe.size:
        cond[regular[maybe]] = np.linalg.cond(sub[maybe])
    return sign, logdet, cond


def _band_pivoted(K, band: int) -> tuple:
    """:func:`_pivoted` of the bands ``K`` ``(B, n, band + 1)`` of long, narrow matrices,
    within the band (:class:`~symtmm.numeric.band_lu.BandLU`), the condition number in
    the 1-norm by Hager's estimate (within a small factor of it)."""
    from .band_lu import BandLU, condition_estimate
    B = K.shape[0]
    sign = np.empty(B, dtype=K.dtype)
    logdet, cond = np.empty(B), np.empty(B)
    for p in range(B):
        check_time()
        upper = K[p].tolist()
        lu = BandLU(upper, band, keep=True)
        if lu.singular:
            sign[p], logdet[p], cond[p] = 0.0, -np.inf, np.inf
            continue
        # (the determinant, a product of thousands of pivots, leaves the doubles' range:
        # its logarithm and phase are summed pivot by pivot)
        pivots = np.array(lu.pivots, dtype=K.dtype)
        sign[p] = np.prod(pivots / np.abs(pivots)) * (-1) ** lu.swaps
        logdet[p] = np.sum(np.log(np.abs(pivots)))
        cond[p] = condition_estimate(lu, upper, band)
    return sign, logdet, cond


def _tops(lam) -> tuple:
    """``(max |lam|, max |Im lam|)`` of complex points: the range of the plan they take."""
    if not lam.size:
        return 0.0, 0.0
    return float(np.max(np.abs(lam))), float(np.max(np.abs(lam.imag)))


def exact_mpf(x) -> mpmath.mpf:
    """``x`` (a float, an int or a number of any mpmath context) as a global mpmath
    number without rounding (``mpmath.mpf(x)`` rounds to the ambient precision)."""
    if hasattr(x, "_mpf_"):
        return mpmath.mp.make_mpf(x._mpf_)
    return mpmath.mp.make_mpf(mpmath.libmp.from_float(float(x)))


def exact_mpc(z) -> mpmath.mpc:
    """``z`` (a Python number or a number of any mpmath context) as a global mpmath complex
    number, unrounded."""
    if hasattr(z, "_mpc_"):
        return mpmath.mp.make_mpc(z._mpc_)
    if hasattr(z, "_mpf_"):
        return mpmath.mp.make_mpc((z._mpf_, mpmath.libmp.fzero))
    z = complex(z)
    return mpmath.mp.make_mpc((mpmath.libmp.from_float(z.real),
                               mpmath.libmp.from_float(z.imag)))


#: Entries of the band (points x freedoms x (half-bandwidth + 1)) one batch in balls or
#: mpmath builds at once (:meth:`Evaluator.factors`): a larger batch goes in parts.
BALL_ENTRIES = 1 << 18

#: Double-precision points a batch may evaluate on a plan cut for a larger range. A plan
#: costs what hundreds of points do (measured: a 10-level chain's 20 to 36 ms against 64 us
#: a point; example 1's 3 to 6 ms against 5 us), a plan for 13 times the range at most
#: twice the pieces (example 1: 28 freedoms at 362 rad/s, 12 at 27; the chain 177 and 95).
SMALL_BATCH = 64
#: The same in the proof arithmetics, whose points cost 20 to 40 times more (a ball point
#: of the 10-level chain 1.65 ms).
SMALL_PROOF_BATCH = 4


class Evaluator:
    """``K(lam)`` factorised at batches of points, with one plan per range of ``|lam|``.

    Parameters
    ----------
    model : Model
        Numeric (dashpots included: ``K`` is complex off the frequency axis).
    size : float
        The largest ``|lam|`` expected; a larger one gets a plan of its own.

    Attributes
    ----------
    evaluations : int
        Points evaluated (one per point of every batch, in every arithmetic).
    clamped : bool
        Its plans' long pieces may pass their clamped-clamped frequencies, the counts
        adding them (:class:`~symtmm.numeric.plan.StiffnessPlan`): only for points on the
        frequency axis (:class:`symtmm.roots.count.Counter` of an undamped model).
    """

    #: (False: the damped searches evaluate off the axis, where those pieces' poles of ``K``
    #: would cost the enclosures their widths)
    clamped = False

    def __init__(self, model, size: float):
        self.model = model.require_numeric()
        self.size = max(float(size), 1e-300)
        self.evaluations = 0
        self._plans: dict = {}
        self._borrowed: dict = {}       # design -> a plan cut for a larger range
        self._keys: dict = {}           # (design, top's design) -> its plans' key
        self._extra_bits: dict = {}

    def plan(self, size: float, points: int | None = None,
             ar: Arithmetic = DOUBLE, top: float | None = None) -> StiffnessPlan:
        """A plan valid for ``|lam| <= size`` (:func:`~symtmm.numeric.plan.plan_for`: shared
        with other searches of the same model; kept here by range for the batches), at
        points with ``|Im lam| <= top`` (by default ``size``: long pieces are cut for it,
        :func:`~symtmm.numeric.plan.plan_key`).

        A batch of few ``points`` (at most :data:`SMALL_BATCH` in double precision, or
        :data:`SMALL_PROOF_BATCH` in ``ar``'s other arithmetics) takes any plan of this
        search cut for a larger range rather than a plan of its own: building one costs
        what hundreds of double evaluations do, its extra pieces far less.
        """
        design = design_range(size)
        if (top is None or top >= design) and not self.clamped:
            key = (design, design, False)
        else:
            # (the shared lookup hashes the whole model: once per range and top here)
            asked = (design, None if top is None or top >= design else design_range(top))
            key = self._keys.get(asked)
            if key is None:
                key = self._keys[asked] = plan_key(self.model, size, top, self.clamped)
        plan = self._plans.get(key)
        if plan is None:
            small = SMALL_BATCH if ar is DOUBLE else SMALL_PROOF_BATCH
            if points is not None and points <= small:
                # (not kept for this range: a larger batch here gets a plan cut for it; kept
                # apart for the next small batch, as the shared lookup hashes the whole model)
                plan = self._borrowed.get(key)
                if plan is None:
                    plan = self._borrowed[key] = plan_for(self.model, size, slack=math.inf,
                                                          top=key[1], clamped=key[2])
                return plan
            plan = self._plans[key] = plan_for(self.model, size, top=key[1], clamped=key[2])
        return plan

    def _built(self) -> list:
        return list(self._plans.values()) + list(self._borrowed.values())

    def served_range(self) -> float:
        """The largest ``|lam|`` some plan this search has built serves (0 before any;
        :attr:`~symtmm.numeric.plan.StiffnessPlan.valid_radius`)."""
        return max((math.sqrt(plan.valid_radius) for plan in self._built()), default=0.0)

    def coarsest_plan(self, size: float) -> StiffnessPlan:
        """The plan with the fewest freedoms this search has built, else one for ``size``
        (for work on the model's mesh that any cut serves, such as the static null space:
        no plan is built for it alone)."""
        built = self._built()
        if built:
            return min(built, key=lambda plan: plan.n)
        return self.plan(size, 1)

    # -- batches ---------------------------------------------------------------------------
    def factors(self, lam, ar: Arithmetic = DOUBLE, retry: bool = True) -> Factors:
        """``LDL^T`` of ``K`` at the points ``lam`` (complex for double; mpmath numbers,
        floats or balls for the other arithmetics, taken exactly).

        ``retry=False``: balls are not redone with more bits when pivots stay undecided
        (for wide input balls, whose radii no precision narrows).
        """
        check_time()        # (a search's wall-clock budget: symtmm.deadline)
        if ar is DOUBLE:
            lam = np.asarray(lam, dtype=complex)
            self.evaluations += lam.size
            size, top = _tops(lam)
            return factor(self.plan(size, lam.size, top=top), ar, lam * lam, lam)
        points = [exact_mpc(z) if not hasattr(z, "mid") else z for z in lam]
        size, top = 0.0, 0.0
        for z in points:
            if hasattr(z, "mid"):
                mid, rad = complex(z.mid()), float(z.rad())
            else:
                mid, rad = complex(z), 0.0
            size, top = max(size, abs(mid) + rad), max(top, abs(mid.imag) + rad)
        plan = self.plan(size, len(points), ar, top=top)

        def build(work, chosen):
            values = work.array([work.number(z) for z in chosen])
            return work.square(values), values
        self.evaluations += len(points)
        return self._in_parts(plan, ar, points, build, retry)

    def _in_parts(self, plan, ar, points, build, retry: bool = True) -> Factors:
        """:meth:`_factor` at ``points`` (exact numbers; ``build(work, chosen) -> (lam2,
        lam)`` in ``work`` at those ``chosen``), a large batch in parts on the batch's plan
        and the budget checked before each: a part cannot be interrupted, and Arb's band of
        every point is built at once (a contour's untrusted points on a plan of thousands
        of freedoms: 3.9 GB, and 11 s past a 60 s budget; a proof's hundred points on a
        shear-soft beam of 47,000 freedoms: past 24 GB)."""
        step = max(1, BALL_ENTRIES // max(1, plan.n * plan.width))
        out = []
        for start in range(0, len(points), step):
            part = points[start:start + step]
            if out:
                check_time()

            def sub(work, idx, part=part):
                return build(work, part if idx is None else [part[i] for i in idx])
            out.append(self._factor(plan, ar, sub, retry))
        return out[0] if len(out) == 1 else Factors.joined(out)

    def _factor(self, plan, ar, build, retry: bool = True) -> Factors:
        """``factor`` at the points ``build(ar, idx) -> (lam2, lam)`` gives (``idx``: which
        of them, None for all), redone in balls with more bits while pivots stay
        undecided (:meth:`_ball`)."""
        if not ar.rigorous or not retry:
            with ar:
                lam2, lam = build(ar, None)
            return factor(plan, ar, lam2, lam)
        return self._ball(plan, ar, build)

    def _ball(self, plan, ar, build) -> Factors:
        """Ball ``LDL^T`` with the precision its radii need.

        Without pivoting, ball elimination widens the radii along the band (each update
        adds the radii of the row it subtracts): measured at ``prec`` bits as the largest
        relative radius of the pivots, that growth is roughly independent of the
        precision, so a retry with ``log2(growth)`` more bits decides most pivots not
        genuinely close to zero; the rest are redone with at least half as many extra bits
        again, until decided or at 64 times the bits (at high modes one measure can fall
        short, and some points need far more: a cantilever's 17th of 60 modes at 144 bits,
        3 of its 200 past 16 times the bits). Only the undecided points are
        redone; when most points needed it, the extra bits are kept for the plan's later
        calls.

        The first batch of a plan starts with a quarter of a bit per freedom more than
        ``ar`` asks: at 15 digits (144 bits) a 50-level chain (450 freedoms) needed about
        300 bits, and half of its first batch and most of its second were redone; the
        113 bits it now starts with decide them, and the 25 to 45 of chains of 10 and 20
        levels, which needed none, cost them little (a ball operation costs about the
        same from 144 to 300 bits). At most ``ar``'s own bits more: 47,127 freedoms would
        have asked for 11,750.
        """
        extra = self._extra_bits.get(id(plan), min(plan.n // 4, ar.prec))
        work = Ball(ar.prec + extra) if extra else ar
        with work:
            lam2, lam = build(work, None)
        fa = factor(plan, work, lam2, lam)
        bad = np.nonzero(~fa.trusted)[0]
        if bad.size and 2 * bad.size <= len(fa.trusted):
            # first the freedoms the other way round: a nearly singular leading minor (a
            # sub-structure's eigenvalue near the point) makes the radii explode, and no
            # number of bits mends that (it is the one point's; where most points of the
            # batch are undecided, the radii outgrew the precision, which the other order
            # shares: a 50-level chain spent 5 % of its solve reversing 8 of 10 in vain)
            with work:
                lam2, lam = build(work, bad)
            self.evaluations += bad.size
            fa = fa.replaced(bad, factor(plan, work, lam2, lam, reverse=True))
        while True:
            bad = np.nonzero(~fa.trusted)[0]
            if bad.size == 0 or extra >= 64 * ar.prec:
                return fa
            check_time()
            growth = 0.0
            for p in fa.pivots[bad].reshape(-1):
                mid, rad = abs(p.mid()), p.rad()
                if mid != 0 and mid.is_finite() and rad.is_finite():
                    ratio = float(rad / mid)
                    growth = max(growth, ratio) if math.isfinite(ratio) else growth
            # the bits the radii ate, measured; when they ran out entirely (an infinite
            # pivot ball) at least twice the precision
            needed = math.log2(growth) + work.prec + 8 if growth > 0 else 0
            # (and at least half as many again: a measure short of what the radii need
            # takes the next one from there, 64 times the bits within about ten rounds)
            extra = max(extra + 32, extra * 3 // 2, int(needed)) if growth > 0 else \
                max(2 * extra, ar.prec)
            if 2 * bad.size > len(fa.trusted):
                self._extra_bits[id(plan)] = extra
            work = Ball(ar.prec + extra)
            with work:
                lam2, lam = build(work, bad)
            self.evaluations += bad.size            # those points again, with more bits
            fa = fa.replaced(bad, factor(plan, work, lam2, lam))
        return fa

    # -- values ------------------------------------------------------------------------------
    def log_delta(self, lam):
        """``(log|Delta|, arg Delta, trusted)`` at complex points, double precision, batched.

        Where the band elimination is not trusted (a pivot too small beside what rounding
        can do to it), the dense ``K`` is factorised with partial pivoting and trusted if
        its condition number leaves the phase good to ``1e-6``: a point near an eigenvalue
        of a leading sub-structure, not of the model, is then as good as any other.
        """
        lam = np.asarray(lam, dtype=complex)
        size, top = _tops(lam)
        plan = self.plan(size, lam.size, top=top)
        got = summary(plan, lam * lam, lam)
        if got is not None:
            # (one compiled pass; the points it leaves undecided factorised again below,
            # for the band and the pivoted determinant)
            check_time()
            self.evaluations += lam.size
            logabs, phase, counts = got
            bad = np.nonzero(counts < 0)[0]
            trusted = counts >= 0
            if not bad.size or not plan.n or not _rescue_pays(plan):
                return logabs, phase, trusted
            self.evaluations += bad.size            # (those points again)
            fa = factor(plan, DOUBLE, lam[bad] * lam[bad], lam[bad])
            logabs[bad], phase[bad], trusted[bad] = _rescued(plan, _pivoted_log_delta(fa))
            return logabs, phase, trusted
        fa = self.factors(lam, DOUBLE)
        logabs, phase = fa.log_delta()
        trusted = fa.trusted.copy()
        bad = np.nonzero(~trusted)[0]
        if bad.size and fa.plan.n and _rescue_pays(fa.plan):
            logabs[bad], phase[bad], trusted[bad] = _rescued(fa.plan,
                                                             _pivoted_log_delta(fa, bad))
        return logabs, phase, trusted

    def enclose(self, lam, ar: Ball):
        """Enclosures of ``Delta`` over wide balls ``lam`` (a box of the complex plane).

        Elimination along the band without pivoting widens the radii geometrically
        (measured: 1e12 from end to end of a 24-freedom band); Arb's determinant of
        the dense ``K`` with preconditioning (Hansen and Smith's, in
        ``acb_mat_det``) keeps them within a factor of about ``1e5 .. 1e8`` of what
        the width of the box must cost, ``O(n**3)`` per point. A plan too large to be
        made dense (:func:`~symtmm.numeric.stiffness.pivots_in_band`) is eliminated within
        the band with partial pivoting (:class:`~symtmm.numeric.band_lu.BandLU`), whose
        enclosures are wider.
        """
        from .stiffness import assemble, pivoted_deltas

        check_time()
        points = [z for z in lam]
        self.evaluations += len(points)
        # each box in the plan of its own range: a batch's plan is cut for its farthest
        # box, and more pieces widen a near box's enclosure (a fuzzed damped model: ten of
        # its sixteen eigenvalues proved by Rouche so, five in plans of the farthest box)
        plans: dict = {}
        for p, z in enumerate(points):
            mid, rad = complex(z.mid()), float(z.rad())
            plan = self.plan(abs(mid) + rad, top=abs(mid.imag) + rad)
            plans.setdefault(id(plan), (plan, []))[1].append(p)
        out: list = [None] * len(points)
        with ar:
            for plan, idx in plans.values():
                values = ar.array([points[p] for p in idx])
                K, det12 = assemble(plan, ar, values * values, values)
                for p, value in zip(idx, pivoted_deltas(plan, ar, K, det12)):
                    out[p] = value
        return ar.array(out)

    def delta(self, lam, ar: Arithmetic, retry: bool = True):
        """``(Delta as numbers of ar, trusted)`` at the points ``lam``.

        Where the band elimination broke down (an undecided pivot), ``Delta`` comes from
        the dense ``K`` with pivoting (:meth:`~symtmm.numeric.stiffness.Factors.pivoted_delta`):
        a ball is then trusted as it comes (it holds the value), an mpmath number is
        left to the caller's check at a second precision. A ball from the band is trusted
        too wherever it is finite, decided or not: it holds ``Delta`` all the same, and
        only a pivot holding 0 that divided the rest makes it infinite. (At a point within
        a box of a root, the last pivot carries the zero of ``Delta``: the dense
        determinant there cost a fifth of the damped example 4's solve, for a ball the
        caller narrows, if it must, with more bits.)
        """
        fa = self.factors(lam, ar, retry)
        values, trusted = fa.delta(), fa.trusted.copy()
        if ar.rigorous:
            trusted |= np.array([v.abs_upper().is_finite() for v in values], dtype=bool)
        bad = np.nonzero(~trusted)[0]
        if bad.size and ar.rigorous and not retry and all(_pointlike(lam[i], ar) for i in bad):
            # exact points whose balls ran out of bits along the band (the wrapping of
            # complex balls widens the radii geometrically: 2**460 over 199 freedoms of a
            # soft beam on a foundation) take the bits the radii need (:meth:`_ball`) before
            # the dense determinant: O(n b**2) each, where Arb's dense one cost a second a
            # point and its balls came out no narrower (a campaign model's Rouche points,
            # 160 s of its 206)
            again = self.factors([lam[i] for i in bad], ar)
            redone = again.delta()
            values = values.copy()
            for i, v, ok in zip(bad, redone, again.trusted):
                if ok or v.abs_upper().is_finite():
                    values[i], trusted[i] = v, True
            bad = np.nonzero(~trusted)[0]
        if bad.size:
            values = values.copy()
            for i, v in zip(bad, fa.pivoted_delta(bad)):
                values[i] = v
                trusted[i] = not ar.rigorous or v.abs_upper().is_finite()
        return values, trusted
