"""Natural frequencies of undamped models, none missed, every printed digit proved.

One factorisation of the exact dynamic stiffness (:mod:`symtmm.roots.count`) gives
at once the Wittrick–Williams count ``J(omega)`` (natural frequencies below
``omega``, with multiplicity) and ``Delta(i omega)``, for a whole batch of
frequencies; the search pays for its points in batches:

1. **Rigid-body modes** are the null space of the static stiffness, exactly
   (:func:`symtmm.mesh.static_nullity`).
2. **Isolate.** Counts on a batch of frequencies bracket the range; every
   bracket holding ``k > 1`` roots is cut into ``k + 1`` equal parts, all
   brackets at once, until each holds one root, or is narrower than double
   precision resolves (a cluster: step 5).
3. **Refine in double**, all roots together: Anderson–Björck steps on
   ``Delta(i omega)``, one batched evaluation per step, each step's side decided
   by the count at its point, to a bracket of relative width about ``1e-13``
   (or until the point is so close to the root that its count is undecided).
4. **Prove the digits**, all roots together, in the proof arithmetic (Arb balls
   where python-flint is installed, else mpmath): a secant step from the double
   bracket gives the root to about twice the digits; the counts at the two ends of
   a bracket of relative width ``2 10**-(D+3)`` around it, ``J = i - 1`` and ``J =
   i``, prove the ``i``-th eigenvalue inside, and the estimate inside it prints
   correctly rounded once both ends round alike (else the bracket is narrowed; at
   low digits the point the Newton step started from can be one end, and a single
   evaluation beyond the root the other). Counts
   ``J(b_i) = J(a_(i+1))`` leave no eigenvalue between brackets, a count at the
   top none above the last one in range. Without python-flint every such count is
   repeated at a second, higher precision and must agree (not a proof).
5. **Clusters.** A bracket holding ``k`` roots is first tried as one exact
   ``k``-fold root: ``|Delta|**(1/k)`` is a V about it, whose vertex, found in a
   few steps, gives a bracket of width ``10**-(D + 2 + SEPARATION_DIGITS)`` that
   two counts then prove to hold all ``k``. Otherwise (distinct close roots)
   brackets are bisected on counts until each holds one root (then step 4) or is
   narrower than ``10**-(D + 2 + SEPARATION_DIGITS)`` relative with both ends
   printing the same ``D`` digits: the roots agree to ``D + SEPARATION_DIGITS``
   digits and are reported once with their multiplicity.

Each eigenvalue carries the name of what proves it (:attr:`Eigenvalue.proof`).
"""

from __future__ import annotations

import itertools
import math
import time
from typing import NamedTuple

import mpmath
import numpy as np
import sympy as sp
from mpmath.libmp import fone, mpf_add, mpf_div, mpf_mul, mpf_sqrt, mpf_sub

from .. import progress
from ..budget import checked_request
from ..errors import ComputationError
from ..mesh import static_nullity
from ..model import Model
from ..numeric.arith import MP, Ball, magnitude_parts
from ..numeric.evaluator import exact_mpf as _exact_mpf
from ..numeric.plan import design_below
from ..results import Eigenvalue, Spectrum, first, print_apart, prints_alike, rounding_room
from .bracket import SEPARATION_DIGITS, scaled, scaled_ends, shrink
from .count import Counter, digits_for, proof_arithmetic

__all__ = ["solve_undamped", "rigid_body_modes", "check_stable", "omega_scale", "PROOFS"]

#: Relative width below which double precision does not split a bracket further.
_DOUBLE_WIDTH = 1e-11
#: Relative width of the double-precision refinement: closer to a root a double count can be
#: wrong without any pivot looking small (the pivot that changes sign may be large and
#: steep), and the proof arithmetic would only have to widen the bracket again.
_DOUBLE_REFINED = 1e-11
#: Where :meth:`_Search.guided` counts above the highest estimate, relative to it.
_TOP_MARGIN = 1.05
#: Largest number of points one bracket contributes to an isolation batch.
_SPLIT_POINTS = 16
#: Largest precision (decimal digits) the refinement may climb to.
MAX_DPS = 3000

#: What backs an eigenvalue: its name in results and output.
PROOFS = {"exact": "exact (static null space)",
          "ball": "count (ball arithmetic)",
          "mp": "count (two precisions)"}


def rigid_body_modes(model: Model, mesh=None) -> int:
    """Number of rigid-body (zero-frequency) modes: the nullity of the static stiffness.

    Exact, from the structure of each element's static null space
    (:func:`symtmm.mesh.static_nullity`, on ``mesh`` where given), with or without axial
    force and foundation.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> rigid_body_modes(Model((Beam("b", 1, 1, 1, left="free", right="free"),)))
    2
    >>> rigid_body_modes(Model((Beam("b", 1, 1, 1, left="pinned", right="free"),)))
    1

    A tension resists turning about the pin (the end force ``-N Y'`` must vanish):

    >>> rigid_body_modes(Model((Beam("b", 1, 1, 1, left="pinned", right="free", N=3),)))
    0
    """
    return static_nullity(model, mesh)


def _rigid_modes(model: Model, counter: Counter, size: float) -> int:
    """:func:`rigid_body_modes` on the coarsest plan the search has built: 0 where one ball
    factorisation there proves ``K(0)`` nonsingular (most models: no rigid-body mode),
    else exactly from the static null space on its mesh."""
    plan = counter.coarsest_plan(size)
    return 0 if counter.nonsingular_static(plan) else rigid_body_modes(model, plan.mesh)


def check_stable(model: Model, rigid: int, counter: Counter | None = None) -> int:
    """Raise :class:`ComputationError` if an axial compression has buckled the model.

    Above a buckling load the static stiffness is indefinite: eigenvalues with
    ``lam**2 > 0`` (real ``lam``, a motion growing without bound), which the
    search for natural frequencies would not report. Only a compressed beam
    can cause them; dashpots do not change the static stiffness. ``counter`` is the
    :class:`~symtmm.roots.count.Counter` to count with (default: one of ``model``,
    which ignores dashpots). Returns the number of counts spent when ``counter`` was
    not given (else 0).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned", N=-15)   # N_cr = pi**2
    >>> check_stable(Model((pp,)), 0)
    Traceback (most recent call last):
    ...
    symtmm.errors.ComputationError: axial compression above a buckling load: 1 mode with lam**2 > 0
    """
    model = model.require_numeric()
    if not any(b.N < 0 for b in model.beams):
        return 0
    own = counter is None
    if own:
        counter = Counter(model, _first_guess(model))
    k = counter.unstable_modes(rigid, _first_guess(model))
    if k:
        raise ComputationError(f"axial compression above a buckling load: {k} mode"
                               f"{'s' if k > 1 else ''} with lam**2 > 0")
    return counter.evaluations if own else 0


def omega_scale(model: Model, digits: int | None = None):
    """``(name, sqrt(EI/(m L^4)))`` of the first beam: ``omega = Omega**2 * scale``.

    Exact (SymPy), or with ``digits`` a global mpmath number good to that many digits
    (what a :class:`~symtmm.results.Spectrum` carries). None for a model of rods only
    (a rod's ``beta L`` is ``omega L sqrt(m/EA)``, not the paper's ``Omega``).
    """
    b = next((b for b in model.resolved().beams if not b.is_rod), None)
    if b is None:
        return None
    scale = sp.sqrt(b.EI / (b.m * b.L**4))
    if digits is None:
        return b.name, scale
    ar = MP.from_digits(digits + 10)
    return b.name, mpmath.mp.make_mpf(ar.exact(scale)._mpf_)


def _pinned_omega2(beam, n: int = 1) -> float:
    """``omega**2`` of the ``n``-th pinned-pinned mode of ``beam`` in its own theory.

    With ``q = (n pi/L)**2``: ``(EI q**2 + N q + kw) / (m + rhoI q)`` rigid in shear;
    a Timoshenko beam's is the smaller root of
    ``(a1 - m w)(a2 - rhoI w) = kGA**2 q``, ``a1 = (kGA + N) q + kw``, ``a2 = EI q + kGA``.
    """
    EI, m, L = float(beam.EI), float(beam.m), float(beam.L)
    N, rhoI, kw = float(beam.N), float(beam.rhoI), float(beam.kw)
    q = (n * math.pi / L) ** 2
    if beam.kGA is None:
        return (EI * q * q + N * q + kw) / (m + rhoI * q)
    kGA = float(beam.kGA)
    a1, a2 = (kGA + N) * q + kw, EI * q + kGA
    c0 = a1 * a2 - kGA * kGA * q
    if rhoI == 0:
        return c0 / (a2 * m)
    b = a1 * rhoI + a2 * m
    disc = max(b * b - 4 * m * rhoI * c0, 0.0)
    return 2 * c0 / (b + math.sqrt(disc))      # the smaller root, without cancellation


def _lowest_pinned_omega2(beam) -> float:
    """The least ``omega**2`` over the pinned-pinned modes of ``beam`` (all ``n``).

    The first mode's, unless a compression (``N < 0``) or rotary inertia on a foundation
    bends the dispersion down to a minimum at many half-waves: ``(EI q**2 + kw) / (m +
    rhoI q)`` with ``rhoI q >> m`` is least at ``q = sqrt(kw / EI)``, where a beam of a
    campaign (``rhoI / m`` the square of 11 m, ``kw`` 1.7e5) has its lowest modes, 232
    half-waves along it and 100 times below its first mode's. The dispersion has one
    minimum in ``q`` (its derivative's numerator is a quadratic, positive far out):
    doubling ``n`` brackets it, halving the bracket over the integers finds it.

    Examples
    --------
    >>> from symtmm.model import Beam
    >>> plain = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
    >>> _lowest_pinned_omega2(plain) == _pinned_omega2(plain)         # pi**4
    True
    >>> heavy = Beam("b", EI=1, m=1, L=10, left="pinned", right="pinned", kw=10**4, rhoI=100,
    ...              theory="rayleigh")
    >>> round(_lowest_pinned_omega2(heavy), 3)                      # 2 at q = 100
    2.0
    """
    f = _pinned_omega2
    best = f(beam, 1)
    if not (beam.N < 0 or (beam.rhoI > 0 and beam.kw > 0)) or not best > 0:
        return best
    n = 1
    while n < 2**100:
        w2 = f(beam, 2 * n)
        if not w2 < best:
            break
        best, n = w2, 2 * n
    lo, hi = max(n // 2, 1), 2 * n                  # the minimum lies within
    while hi - lo > 2:
        a, b = lo + (hi - lo) // 3, hi - (hi - lo) // 3
        if f(beam, a) < f(beam, b):
            hi = b
        else:
            lo = a
    return min([best] + [f(beam, k) for k in range(lo, hi + 1)])


def _first_guess(model: Model) -> float:
    """A frequency of the order of the lowest natural frequency.

    The lowest pinned-pinned frequency of the beams, each in its own theory
    (:func:`_lowest_pinned_omega2`); a beam compressed beyond a mode's buckling load
    gives its first Euler–Bernoulli value instead.
    """
    best = math.inf
    for b in model.resolved().beams:
        w2 = _lowest_pinned_omega2(b)
        if not w2 > 0:
            w2 = float(b.EI) / float(b.m) * (math.pi / float(b.L)) ** 4
        best = min(best, math.sqrt(w2))
    return best


def _next_top(w: float, k: int, count: int, weyl) -> float:
    """Where to count next after ``k < count`` eigenvalues below ``w``.

    Each count needs a plan cut for its range, and the search goes on with the
    plan of the top it accepts, whose pieces shorten as the range grows: the next
    top should be just above the ``count``-th eigenvalue, neither a second miss
    nor far beyond. Above ``w`` the eigenvalues come at the rate of Weyl's
    estimate, whatever the springs and ends have shifted below it, so the count
    is taken where ``weyl`` has grown by the ``count - k`` missing and one more:
    within 1.19 times ``w`` (the next range of :func:`design_range`) and 4 times.
    (Chains of 10 to 50 beams under 2 springs each miss a first guess by 2 to 9
    eigenvalues; a jump by ``(count / k)**2`` went 3 to 4 times too high, to 16 to
    61 eigenvalues and twice the pieces.)
    """
    lo, hi = 1.19 * w, 4.0 * w
    want = weyl(w) + (count - k) + 1
    if weyl(lo) >= want:
        return lo
    if not weyl(hi) > want:
        return hi
    for _ in range(40):
        mid = math.sqrt(lo * hi)
        lo, hi = (mid, hi) if weyl(mid) < want else (lo, mid)
    return hi


def _exact_mpc_imag(w) -> mpmath.mpc:
    """``i w`` as a global mpmath number without rounding ``w`` (any mpmath number)."""
    return mpmath.mp.make_mpc((mpmath.libmp.fzero, w._mpf_))


class _Search:
    """Isolation, refinement and proof of the roots of one undamped model."""

    def __init__(self, model: Model, digits: int, omega_hi: float,
                 certified: bool | None = None):
        self.model = model
        self.digits = digits
        # the rigid-body modes: set by the solve once the top is found, on its plans' mesh
        self.rigid = 0
        self.certified = certified
        self.counter = Counter(model, omega_hi)
        self._proved: dict = {}         # (point, digits) -> count proved in balls
        self._set_precision(digits_for(digits))
        self._first_prec = self.hp.prec          # (the bits before any retry with more)
        # whether the isolation counts its cut points in balls (the double counts misled
        # the proofs once: solve_undamped)
        self.proved_cuts = False
        # the reference beam's scale: a proved bracket prints Omega = sqrt(omega / scale)
        # alike at its ends too (the spectrum's Omega column: Eigenvalue.frequency_parameter)
        self.omega_scale = omega_scale(model, digits + 10)    # (the spectrum's as well)
        # (the number as made, every bit kept: mpmath.mpf would round it to the ambient 53)
        self._scale = None if self.omega_scale is None else self.omega_scale[1]
        self._widen = mpmath.mpf(10) ** -(digits + 8)
        self._big_constants: dict = {}     # (prec, rounding) -> scale, 1 - widen, 1 + widen

    def _prints(self, lo, hi) -> bool:
        """Whether a bracket ``[lo, hi]`` proves the digits: both ends print alike, and so
        do those of ``Omega`` over it (widened for the scale's rounding)."""
        if not prints_alike(lo, hi, self.digits):
            return False
        if self._scale is None:
            return True
        return prints_alike(self._big(lo, -1), self._big(hi, 1), self.digits)

    def _big(self, x, side: int = 0):
        """``Omega = sqrt(x / scale)`` of a bookkeeping number ``x``, times ``1 - widen``
        (``side`` -1) or ``1 + widen`` (+1), each operation rounded as ``x``'s context
        rounds it: the context's own operations, on the binary values directly (through
        the context's calls, the two ends' cost most of a bracket's print test)."""
        ctx = _context_of(x)
        if not hasattr(x, "_mpf_"):
            big = ctx.sqrt(x / ctx.mpf(self._scale))
            return big if not side else big * (1 + side * ctx.mpf(self._widen))
        prec, rnd = ctx._prec_rounding
        known = self._big_constants.get((prec, rnd))
        if known is None:
            # (1 -+ widen in the context: in the global one, at 53 bits, they were 1)
            widen = ctx.mpf(self._widen)._mpf_
            known = self._big_constants[(prec, rnd)] = (
                ctx.mpf(self._scale)._mpf_, mpf_sub(fone, widen, prec, rnd),
                mpf_add(fone, widen, prec, rnd))
        s, lower, upper = known
        big = mpf_sqrt(mpf_div(x._mpf_, s, prec, rnd), prec, rnd)
        if side:
            big = mpf_mul(big, lower if side < 0 else upper, prec, rnd)
        return ctx.make_mpf(big)

    def _room(self, c) -> float:
        """Half of how far ``c`` may move and print as it does, its ``Omega`` too."""
        room = rounding_room(c, self.digits)
        if self._scale is not None and room > 0:
            big = self._big(c)
            room_big = rounding_room(big, self.digits) - float(big) * float(self._widen)
            # (d omega = 2 Omega scale d Omega)
            room = min(room, max(0.0, 2 * float(big) * float(self._scale) * room_big))
        return room / 2

    def _set_precision(self, work_digits: int):
        if work_digits > MAX_DPS:
            raise ComputationError(f"cannot reach {self.digits} digits within {MAX_DPS} "
                                   "working digits")
        self.work_digits = work_digits
        self.hp = proof_arithmetic(work_digits, self.certified)
        self.proof = PROOFS["ball" if self.hp.rigorous else "mp"]
        # bracket arithmetic (midpoints, secant steps) carries more bits than the evaluations
        self.book_prec = self.hp.prec + 64

    @property
    def evaluations(self) -> int:
        return self.counter.evaluations

    def count_off(self, omega, toward, digits=None):
        return self.counter.count_off(omega, toward, digits)

    def counts_off(self, omegas, towards, digits: int) -> list:
        """:meth:`count_off` at several points in one batch of the proof arithmetic at
        ``digits``; a point the batch leaves undecided goes through :meth:`count_off`
        alone. Counts proved in balls are remembered for :meth:`prove_cluster`."""
        ar = proof_arithmetic(digits, self.certified)
        counts = self.counter.counts(list(omegas), ar)
        out = []
        for w, t, c in zip(omegas, towards, counts):
            if c >= 0:
                if ar.rigorous:
                    self._proved[(_key(w), digits)] = int(c)
                out.append((w, int(c)))
            else:
                out.append(self.count_off(w, t, digits))
        return out

    # -- the range ------------------------------------------------------------------------
    def top_for(self, count: int):
        """``(omega, J(omega))`` with ``J(omega) >= count``: from Weyl's estimate, then up.

        Along a beam the modes come one per ``pi`` of ``s L`` (``s`` its largest wave
        number), so ``N(omega) ~ sum s L / pi`` plus about one per beam: the first
        guess is where that reaches ``count`` plus the number of beams, and a miss
        raises it to where the count would reach ``count`` growing like ``sqrt(omega)``
        (1.5 to 4 times). The plan is then cut for a range close to the one needed.
        """
        target = count + len(self.model.beams)
        # (the constants as floats once: the bisection below asks for them 40 times; beams
        # alike in all but their length once, with their lengths summed: the spans of a
        # continuous beam are)
        waves: dict = {}
        for b in self.model.beams:
            seg = b.segment(b.L)
            consts = seg.constants()
            # (the length apart: a segment's constants are EI, m, l, then the rest)
            waves.setdefault((type(seg), consts[:2], consts[3:]), [seg, consts, 0.0])[2] += \
                float(b.L)

        def weyl(w):
            # the travelling waves count the modes (under a tension or on a foundation
            # not the largest wave number)
            return sum(seg.counting_wave_number(w, consts) * L
                       for seg, consts, L in waves.values()) / math.pi

        lo = hi = max(_first_guess(self.model), 1e-300)
        while weyl(hi) < target and hi < 1e150:
            lo, hi = hi, 2 * hi
        for _ in range(40):
            mid = math.sqrt(lo * hi)
            lo, hi = (mid, hi) if weyl(mid) < target else (lo, mid)
        w = hi
        while w < 1e150:
            w, k = self.count_off(w, 2.0 * w)
            if k >= count:
                return float(w), int(k)
            nxt = _next_top(w, k, count, weyl)
            # the plans built so far may serve well above their own range (a chain's pieces
            # are mostly its stretches between springs): up to the highest range on the
            # grid they serve, a count needs no plan of its own
            grid = design_below(self.counter.served_range())
            if 1.1 * w < grid < nxt:          # (a count barely above w would not pay)
                w, k = self.count_off(grid, 2.0 * grid)
                if k >= count:
                    return float(w), int(k)
                nxt = _next_top(w, k, count, weyl)
            w = nxt
        raise ComputationError(f"fewer than {count} eigenvalues below 1e150 rad/s")

    def guided(self, guesses, count: int):
        """``((top, J(top)), cuts)`` from estimates of the eigenvalues, or None.

        ``guesses``: ``(omega, half-width)`` pairs, estimates of the first ``count``
        natural frequencies with a relative uncertainty (a sweep's previous steps
        extrapolated). The ends of every ``omega (1 -+ half-width)`` are counted in one
        double-precision batch: where an estimate was good, its root is bracketed that
        narrowly at once, with no search for the top and no isolation rounds, and the
        double-precision refinement starts close to it. Nothing is taken on trust: the
        counts partition ``[0, top]`` for :meth:`isolate` as its own cuts would (a bracket
        that holds two roots, or a gap that holds one, is split there), and every root
        is proved as without estimates. A point double precision cannot count (too near
        a root) is left out. None where the counts do not serve (a falling count, or fewer
        than ``count`` below the highest point): the search then runs as without
        estimates.
        """
        points = {float(w) * (1 + side * abs(float(d))) for w, d in guesses
                  for side in (-1, 1)}
        points = sorted(p for p in points if math.isfinite(p) and p > 0)
        if not points:
            return None
        # and a margin above them, in the same batch: where the highest estimate fell
        # short, the count there still reaches the top
        points.append(_TOP_MARGIN * points[-1])
        counts = self.counter.counts(np.array(points)).tolist()
        # (a point too near a root for a double count to be trusted is no cut)
        points, counts = [p for p, c in zip(points, counts) if c >= 0], \
            [c for c in counts if c >= 0]
        if not counts or any(b < a for a, b in itertools.pairwise(counts)) or \
                counts[-1] < count:
            return None
        # (past the first point that counts `count`, nothing more is needed)
        last = next(i for i, c in enumerate(counts) if c >= count)
        return (points[last], counts[last]), list(zip(points[:last], counts[:last]))

    # -- isolation -------------------------------------------------------------------------
    def isolate(self, top: float, c_top: int, wanted=None, cuts=()) -> list:
        """Brackets ``(a, J(a), b, J(b))`` holding ``J(b) - J(a) >= 1`` roots, ascending.

        One root each, except those narrower than double precision resolves (clusters).
        The cut points of a round are counted in one batch. ``cuts``: points
        ``(omega, J(omega))`` in ``(0, top)`` counted already, ascending with counts that
        do not fall (:meth:`guided`): the first round splits there.
        """
        limit = None if wanted is None else self.rigid + wanted
        # (a double count below the rigid-body modes, exact at 0, is wrong: no cut)
        ends = [(0.0, self.rigid)] + [(w, c) for w, c in cuts if c >= self.rigid] + \
            [(float(top), int(c_top))]
        work = [(a, ca, b, cb) for (a, ca), (b, cb) in itertools.pairwise(ends)]
        done = []
        while work:
            if limit is not None:
                work = [w for w in work if w[1] < limit]
            points, owners, split = [], [], []
            for a, ca, b, cb in work:
                k = cb - ca
                if k <= 0:
                    continue
                at_rigid_zero = a == 0 and self.rigid > 0     # Delta(0) = 0 there
                if (k == 1 and not at_rigid_zero) or (b - a) <= _DOUBLE_WIDTH * b:
                    done.append((a, ca, b, cb))
                    continue
                # two cut points per root: most brackets hold one root after a round,
                # and a batch costs little more for twice the points
                parts = min(2 * k, _SPLIT_POINTS) + 1
                for j in range(1, parts):
                    points.append(a + (b - a) * j / parts)
                    owners.append(len(split))
                split.append((a, ca, b, cb))
            if not points:
                break
            counts = self.counter.counts(np.array(points)) if not self.proved_cuts else \
                np.full(len(points), -1)
            # points double precision leaves undecided (a pivot too small to trust), in one
            # batch of the proof arithmetic (one call each cost 67 calls at a step of a
            # sweep where a rigid-body mode meets double roots)
            bad = np.nonzero(counts < 0)[0]
            for j, (p, c) in zip(bad, self.counts_off([points[j] for j in bad],
                                                      [split[owners[j]][2] for j in bad], 30)):
                points[j], counts[j] = p, c
            inside: dict = {}
            for p, c, o in zip(points, counts, owners):
                inside.setdefault(o, []).append((p, int(c)))
            work = []
            falling = [o for o, (a, ca, b, cb) in enumerate(split)
                       if any(c2 < c1 for (_, c1), (_, c2) in
                              itertools.pairwise([(a, ca)] + inside[o] + [(b, cb)]))]
            if falling:
                # counts must not fall: decide those cut points again in the proof arithmetic
                again = iter(self.counts_off([p for o in falling for p, _ in inside[o]],
                                             [split[o][2] for o in falling for _ in inside[o]],
                                             30))
                for o in falling:
                    inside[o] = [next(again) for _ in inside[o]]
            for o, (a, ca, b, cb) in enumerate(split):
                seq = [(a, ca)] + inside[o] + [(b, cb)]
                work += [(p, cp, q, cq) for (p, cp), (q, cq) in itertools.pairwise(seq)]
        return sorted(done)

    # -- refinement in double precision, all roots at once ---------------------------------
    def refine_double(self, brackets) -> list:
        """The root in each one-root bracket ``(a, J(a), b)``, estimated in double precision.

        Anderson–Björck steps on ``Delta``, one batched evaluation per step for all roots;
        the count at each new point says on which side of the root it lies (or, where a
        pivot is too small for the count, the sign of ``Delta``), ``Delta`` where in the
        bracket to put the next one. A root stops when its bracket is narrower than
        :data:`_DOUBLE_REFINED` or its side cannot be told. Returns, per bracket, the
        point of smallest ``|Delta|`` met; nothing is concluded from it (step 4 proves).
        """
        if not brackets:
            return []
        a = np.array([x[0] for x in brackets], dtype=float)
        b = np.array([x[2] for x in brackets], dtype=float)
        ca = np.array([x[1] for x in brackets], dtype=int)
        la, sg, _ = self.counter.signed_log_delta(np.concatenate([a, b]))
        fa, fb, ref = scaled_ends(la, sg)

        def probe(c, idx):
            lc, sc, kc = self.counter.signed_log_delta(c)
            fc = scaled(lc, sc, ref[idx])
            side = np.where(kc == ca[idx], -1, np.where(kc == ca[idx] + 1, 1, 0))
            # an undecided count (a pivot near zero: the point is near the root): the sign of
            # Delta tells the side (one simple root inside, so Delta changes sign once); a
            # wrong side costs the proof stage a wider bracket, never a wrong result
            FA, FB = fa0[idx], fb0[idx]
            by_sign = (kc < 0) & (FA * FB < 0) & (fc != 0) & np.isfinite(fc)
            side = np.where(by_sign, np.where(np.sign(fc) == np.sign(FB), 1, -1), side)
            return fc, side

        fa0, fb0 = fa.copy(), fb.copy()        # (their signs: the scaling keeps them)
        return shrink(a, b, fa, fb, probe, _DOUBLE_REFINED, settle=True)

    # -- the digits, proved, all roots at once -------------------------------------------------
    def _values(self, points, ctx, ar=None):
        """``(Delta(i w), J(w))`` at mpmath points in the proof arithmetic, the values as
        numbers of ``ctx`` (the refinement's bookkeeping context: a global mpmath number
        would round every secant step through it to the ambient 15 digits); None where
        the count is undecided (its ball may have no finite midpoint). Also per point a
        bound of the value's error where balls give one (floats; 0 otherwise). ``ar``: an
        arithmetic other than the proofs' (fewer bits)."""
        return self.counter.midpoints(points, ar or self.hp, ctx)

    def _evaluate(self, points, ctx, ar=None):
        """``(Delta(i w) in ctx, J(w), proved, radii)`` at mpmath points (:meth:`_values`;
        ``ar``: balls of fewer bits than the proofs', :meth:`_estimating`).

        A point whose ball count stays undecided (at high modes the ball elimination can
        widen its radii beyond any precision while the factorisation itself is sound) is
        counted again in mpmath at two precisions, and if both agree that count is used,
        not proved (``proved`` False there).
        """
        out, counts, radii = self._values(points, ctx, ar)
        proved = np.full(len(points), self.hp.rigorous)
        bad = [j for j, c in enumerate(counts) if c < 0]
        if bad and self.hp.rigorous:
            ar = MP(self.hp.prec)
            first, c1 = self.counter.delta([points[j] for j in bad], ar)
            c2 = self.counter.counts([points[j] for j in bad], MP(self.hp.prec + 64))
            counts = np.array(counts)
            for j, v, k1, k2 in zip(bad, first, c1, c2):
                if k1 >= 0 and k1 == k2:
                    counts[j], out[j], proved[j] = k1, ctx.mpf(mpmath.re(ar.to_mpmath(v))), False
        return out, counts, proved, radii

    def _checked(self, points, counts) -> bool:
        """Without balls, the counts again at a second precision must agree."""
        if self.hp.rigorous or not points:
            return True
        again = self.counter.counts(points, MP(self.hp.prec + 64))
        return bool(np.all(again == np.asarray(counts)))

    def refine_high(self, items) -> list:
        """Eigenvalues from one-root brackets ``(estimate, J(A), (A, B))``, proved by counts.

        ``estimate`` is the double-precision one (any point near the root, or None for
        the bracket's midpoint), ``(A, B)`` a bracket known to hold the root.
        """
        D = self.digits
        if not items:
            return []
        for _ in range(8):
            try:
                return self._refine_high(items)
            except _MorePrecision:
                self._set_precision(2 * self.work_digits)
        raise ComputationError(f"cannot reach {D} digits: the counts stay undecided")

    def _refine_high(self, items) -> list:
        """All roots at once: pairs of points about each root's estimate, counted.

        Every evaluation factorises ``K`` once and gives ``Delta`` and the count
        together. Each round evaluates, for every root, the pair ``c (1 -+ h)``
        about its current estimate ``c``: its counts ``J_i`` and ``J_i + 1`` prove
        the root between them, and its two values of ``Delta`` give the next
        estimate by a secant step, whose error is about the square of the last one.
        Before the pairs, one point per root and a Newton step (:meth:`_newton_start`)
        take the double estimate to about 20 digits, and the first pairs, as wide as
        that step's error, prove 15 digits: two rounds of proof evaluations, one of them
        a single point per root. Past a pair about the root, that earlier point corrects
        the secant step by a parabola (:func:`_quadratic`): three rounds for 30 and for 50
        digits. Without an estimate the first pair (``h = 1e-11``, the
        double estimate's accuracy) gives an estimate good to about 22 digits, the next
        pairs (``h = 10**-(D+3)``) prove it. A secant step that leaves the
        bracket the counts have proved is replaced by an Anderson–Björck step on it.
        A pair whose counts prove the root between its ends proves the digits once both
        ends round alike (else the next pair is taken narrower); the estimate the pair was
        placed about, inside it, prints.
        Where a root's last point is a proved end of its bracket so near the estimate that
        it and the point as far again beyond the root print alike, that one point is
        evaluated instead of a pair (:meth:`_beyond`; at 12 digits most roots, after the
        Newton start: 2 evaluations per root where a pair took 3).
        """
        D = self.digits
        ctx = MP(self.book_prec).ctx            # bookkeeping: more bits than the evaluations
        R = len(items)
        ca = [x[1] for x in items]
        a = [ctx.mpf(x[2][0]) for x in items]
        b = [ctx.mpf(x[2][1]) for x in items]
        c = [(a[i] + b[i]) / 2 if x[0] is None else min(max(ctx.mpf(x[0]), a[i]), b[i])
             for i, x in enumerate(items)]
        fa: list = [None] * R
        fb: list = [None] * R
        h = [ctx.mpf("1e-11")] * R
        target = ctx.mpf(10) ** (-(D + 3))
        done: list = [None] * R
        best: list = [None] * R                 # the value of each root once done
        by_balls = [self.hp.rigorous] * R       # the last pair of each root proved in balls
        older: list = [None] * R                # per root a third point (_Point) near it
        self._newton_start(items, a, b, c, fa, fb, h, ca, target, ctx, older)
        for _ in range(60):
            tests, owner = [], []               # owner: (root, points it evaluates)
            # per root whose pair is wider than the room its digits leave: its h
            wide: list = []
            for i in range(R):
                if done[i] is None:
                    far = self._beyond(older[i], a[i], b[i], c[i], ca[i], D)
                    if far is not None:         # one point beyond the root suffices
                        tests.append(far)
                        owner.append((i, 1))
                    else:
                        # as wide as the estimate's error needs, or wider, up to half the
                        # room the estimate has to print as it does: a pair that brackets
                        # the root then proves its digits all the same, and a pair farther
                        # from the root has larger pivots, decided in fewer words (example
                        # 1 at 15 digits: 8 of 19 points took three words at 1e-18)
                        room = self._room(c[i])
                        e = max(h[i] * c[i], room)
                        tests += [max(c[i] - e, (a[i] + c[i]) / 2),
                                  min(c[i] + e, (c[i] + b[i]) / 2)]
                        owner.append((i, 2))
                        if e > 2 * room:
                            wide.append(h[i])
            if not owner:
                break
            values, counts, proved, radii = self._evaluate(
                tests, ctx, self._estimating(wide, target) if len(wide) == len(owner) else None)
            at = 0
            for i, n in owner:
                new = [_Point(tests[j], values[j], counts[j], bool(proved[j]), radii[j])
                       for j in range(at, at + n)]
                at += n
                # a pair, or the kept point and the one beyond the root, in order
                p1, p2 = sorted(new if n == 2 else new + [older[i]], key=lambda q: q.t)
                (t1, f1, k1, _, _), (t2, f2, k2, _, _) = p1, p2
                by_balls[i] = p1.ball and p2.ball
                for t, f, k in ((t1, f1, k1), (t2, f2, k2)):
                    _tighten(i, t, f, k, ca, a, b, fa, fb)
                if (k1, k2) == (ca[i], ca[i] + 1) and self._prints(t1, t2):
                    done[i] = (t1, t2)          # (whatever h: both ends print alike)
                    # the value: the estimate the points were placed about, which prints
                    # as they do and carries the digits beyond (a bracket of one point and
                    # its mirror is as wide as the estimate's distance from that point)
                    best[i] = c[i] if t1 < c[i] < t2 else (t1 + t2) / 2
                    continue
                if (k1, k2) == (ca[i], ca[i] + 1) and h[i] <= target:
                    h[i] /= 100         # near a rounding boundary: a finer pair
                elif (k1 < 0 or k2 < 0) and h[i] <= target:
                    raise _MorePrecision()          # a proving pair must be decided
                # the next estimate: a secant through the pair, kept inside the bracket
                step = None
                # (the difference must stand above the values' errors: else the slope is
                # their rounding, and the step lands anywhere in the bracket)
                resolved = f1 is not None and f2 is not None and \
                    abs(f2 - f1) > 8 * (p1.r + p2.r)
                if resolved and f1 != f2:
                    step = t2 - f2 * (t2 - t1) / (f2 - f1)
                elif f1 is not None and f2 is not None and h[i] <= target and n == 2:
                    # the pair as narrow as the digits need, and its values do not tell
                    # it apart: the band loses more digits than the precision keeps (a
                    # piece 1e-12 long beside pieces of 0.3: 38 digits). (Not a point
                    # beside the kept one, whose value came from fewer digits, which more
                    # would not change: the next round takes a pair.)
                    raise _MorePrecision()
                if step is None or not a[i] < step < b[i]:
                    width = b[i] - a[i]
                    step = None
                    if fa[i] is not None and fb[i] is not None and fa[i] * fb[i] < 0:
                        step = b[i] - fb[i] * width / (fb[i] - fa[i])
                    if step is None or not a[i] < step < b[i]:
                        step = (a[i] + b[i]) / 2
                    h[i] = min(h[i], width / (8 * step))
                elif (k1, k2) == (ca[i], ca[i] + 1) and older[i] is not None:
                    step, h[i] = _quadratic(older[i][:2], (t1, f1), (t2, f2), step, a[i],
                                            b[i], h[i], target)
                else:
                    h[i] = min(h[i], target)
                if f1 is not None and f2 is not None:
                    older[i] = min((p1, p2), key=lambda q: abs(q.f))
                c[i] = step
        if any(d is None for d in done):
            raise _Misled(f"the refinement to {D} digits did not converge")
        if not self._checked([x for d in done for x in d],
                             [k for i in range(R) for k in (ca[i], ca[i] + 1)]):
            raise _MorePrecision()
        out = []
        for (lo_i, hi_i), value, balls in zip(done, best, by_balls):
            bracket = (mpmath.mp.make_mpf(lo_i._mpf_), mpmath.mp.make_mpf(hi_i._mpf_))
            proof = self.proof if balls else PROOFS["mp"]
            out.append(Eigenvalue(_exact_mpc_imag(value), 1, D, bracket, proof))
        return out

    def _estimating(self, widths, target):
        """Balls for a round of pairs none of which can prove its digits (each wider than
        twice the room they leave, at 30 and 50 digits the first pairs after the Newton
        start): their values serve the next estimate alone, which errs by about the
        values' relative error times the pairs' distance from the roots, ``h``. So they
        need ``log2(h / target)`` bits and a guard, not the proofs' (their counts are
        proved all the same, where decided); the words of those, or None where no fewer
        than the proofs'. (Example 1 at 50 digits: three words for these twenty points,
        not four.)
        """
        if not widths or not self.hp.rigorous:
            return None
        # (and the bits a retry added to the proofs': the band of a model with a piece far
        # shorter than the others loses digits to it, in these balls as in the proofs')
        bits = math.log2(float(max(widths)) / float(target)) + _ESTIMATE_GUARD + \
            (self.hp.prec - self._first_prec)
        # (at least three: the double-doubles' 106 bits left most of such pairs undecided,
        # example 1 at 30 digits 14 of 20, as their pivots hold the pairs' distance from the
        # roots besides the radii's growth along the band)
        words = max(3, math.ceil(bits / 64))
        return Ball(64 * words) if 64 * words < self.hp.prec else None

    def _beyond(self, kept, a, b, c, ca: int, D: int):
        """The point beyond the root from ``kept`` (a root's last :class:`_Point`) as far
        again as ``kept`` is from the estimate ``c``, where its count puts ``kept`` on one
        side of the root and the two print alike at ``D`` digits: one evaluation there then
        proves the digits (a pair costs two). None otherwise.

        After the Newton start the estimate errs by far less than its distance from the
        start (the step's relative error times the step), so ``c + 2 (c - t)`` lies beyond
        the root from ``t``. At 12 digits a double estimate ``1e-13`` away qualifies for
        most roots; at 15 digits rarely (a pair proves there, as before). Where the proof
        arithmetic is balls, ``kept`` must be proved in balls too.
        """
        if kept is None or kept.f is None or kept.k not in (ca, ca + 1) or \
                (self.hp.rigorous and not kept.ball) or kept.t == c:
            return None                 # (no side, or no proof of it)
        if (kept.t < c) != (kept.k == ca):
            return None                 # (the estimate is on the far side of the root)
        far = c + 2 * (c - kept.t)
        return far if a < far < b and self._prints(min(kept.t, far), max(kept.t, far)) \
            else None

    def _newton_start(self, items, a, b, c, fa, fb, h, ca, target, ctx, older):
        """One point per root, not a pair, before the proving pairs (in place).

        The slope of ``Delta`` at each double estimate ``c`` comes from a central
        difference in double precision over ``c (1 -+ delta)``, where the values are far
        from zero; ``Delta(c)`` itself, which double rounding hides within about 1e-13 of
        the root, comes from the proof arithmetic. One Newton step then lands within
        ``|step| eps`` of the root, ``eps`` the slope's relative error, which the double
        value at ``c`` bounds: its distance from the exact one is the rounding error of
        ``Delta`` there, and about the same at ``c (1 -+ delta)``. The next pair of each
        root is taken that wide (never narrower than ``10**-(D+3)``): it brackets the
        root and, where both ends print alike, proves it -- one proof evaluation per
        root fewer than a first pair at ``1e-11``. Roots without an estimate, with an
        undecided value or a step out of their bracket keep the pair at ``1e-11``;
        nothing here is concluded, the pairs (or one point beyond the root) prove.
        """
        first = [i for i, x in enumerate(items) if x[0] is not None]
        if not first:
            return
        # delta: inside the bracket (no other root between the points), yet wide enough
        # that the double rounding of Delta barely moves the slope; the differences over
        # delta and delta/2 give the slope by Richardson's rule and, by how far apart they
        # are, the size of the error the rule removes
        mids = np.array([float(c[i]) for i in first])
        d = np.array([min(1e-5, 0.25 * float(min(c[i] - a[i], b[i] - c[i]) / c[i]))
                      for i in first])
        n = len(first)
        logs, signs, _ = self.counter.signed_log_delta(np.concatenate(
            [mids * (1 - d), mids * (1 + d), mids * (1 - d / 2), mids * (1 + d / 2), mids]))
        # (the step needs Delta(c) to about the square of the double estimate's error: at
        # 50 digits the words of 30 serve, a third cheaper; the count there is proved all
        # the same)
        start = proof_arithmetic(min(self.work_digits, digits_for(_START_DIGITS)),
                                 self.certified)
        values, counts, radii = self._values([c[i] for i in first], ctx, start)

        for j, i in enumerate(first):
            t, f, k = c[i], values[j], counts[j]
            _tighten(i, t, f, k, ca, a, b, fa, fb)
            if f is not None:
                older[i] = _Point(t, f, k, self.hp.rigorous, radii[j])    # (counted in hp)
            near = logs[j + n * np.arange(4)]
            if f is None or d[j] <= 0 or not np.isfinite(near).all():
                continue
            # the step in floats: the values scaled by the largest of the double ones (a
            # determinant may pass the doubles' range), t's digits kept by subtracting the
            # step from it at the bookkeeping's precision (the slope errs by far more than
            # the floats round; in mpmath these lines cost a sixth of example 1's proofs)
            ref = float(near.max())
            y = signs[j + n * np.arange(4)] * np.exp(near - ref)
            at = signs[j + 4 * n] * math.exp(logs[j + 4 * n] - ref) \
                if np.isfinite(logs[j + 4 * n]) else 0.0   # (no finite value at c: a zero pivot)
            fs = _scaled_float(f, ref)
            run = float(d[j]) * float(t)
            wide, narrow = (y[1] - y[0]) / (2 * run), (y[3] - y[2]) / run
            slope = (4 * narrow - wide) / 3
            if not (slope != 0 and math.isfinite(slope) and math.isfinite(fs)):
                continue
            move = fs / slope
            step = t - ctx.mpf(move)
            if a[i] < step < b[i]:
                # the slope's error: what Richardson's rule removed, and the rounding error
                # of Delta (its distance from the exact value at c) over the difference
                # (not the ball's radius: on large models the elimination widens it far
                # beyond the midpoint's error, and a pair that misses costs one more pair)
                eps = (abs(wide - narrow) + 2 * abs(at - fs) / run) / abs(slope)
                c[i] = step
                h[i] = max(target, min(h[i], ctx.mpf(4 * eps * abs(move) / float(step))))

    # -- clusters ------------------------------------------------------------------------------
    def split_cluster(self, a, ca, b, k):
        """Separate the ``k`` roots in ``(a, b]`` (``J(a) = ca``) on high-precision counts.

        Returns brackets ``(lo, hi, J(lo), m)``, ascending: ``m == 1`` for a root of its
        own, ``m > 1`` for roots that still share a bracket of relative width
        ``10**-(D + 2 + SEPARATION_DIGITS)``: they agree to ``D + SEPARATION_DIGITS``
        digits and are reported as one eigenvalue of multiplicity ``m``. Exact
        multiple roots (identical beams, symmetric couplings) end there; distinct
        roots are told apart however close, down to that resolution.
        """
        D = self.digits
        resolution = D + 2 + SEPARATION_DIGITS
        digits = resolution + 15
        ctx = MP.from_digits(digits + 10).ctx
        limit = ctx.mpf(10) ** (-(digits - 5))       # what the counts can still resolve

        def done(lo, hi):
            width = (hi - lo) / lo
            return width <= limit or (width <= ctx.mpf(10) ** (-(D + 2)) and
                                      prints_alike(_exact_mpf(lo), _exact_mpf(hi), D))

        a, b = ctx.mpf(a), ctx.mpf(b)
        # the double-precision counts at the ends, this close to a cluster, are checked here
        # (rounding can flip the signs of pivots through zero and pass the trust test):
        # an end that holds a root the wrong side of it moves out until it does not. In
        # balls, the counts come from the zoom's first batch (its values at the ends,
        # and their counts proved as well as at fewer digits): where they are the ones
        # expected, that is one ball batch fewer (example 3's triple root: 0.7 ms of 12)
        target, ends = ca, None
        if self.hp.rigorous and k * resolution + 20 <= MAX_DPS:
            values, counts = self._deltas([a, b], k * resolution + 20,
                                          resolution + _GUIDE_DIGITS)
            if [int(c) for c in counts] == [target, target + k]:
                ends, cb = values, target + k
        if ends is None:
            (a, ca), (b, cb) = self.counts_off([a, b], [b, 2 * b - a], digits)
            step = (b - a) / 16
            while ca > target and a - step > 0:
                a, ca = self.count_off(a - step, a - 2 * step, digits)
                step *= 4
            cb_want = ca + k
            step = (b - a) / 16
            while cb < cb_want:
                b, cb = self.count_off(b + step, b + 2 * step, digits)
                step *= 4
        k = cb - ca
        tol = ctx.mpf(10) ** (-resolution)
        zoomed = self._zoom(a, b, k, resolution, ends)
        if zoomed is not None:
            lo, hi = zoomed
            if done(lo, hi) and self.counts_off([lo, hi], [a, b], digits) == [(lo, ca),
                                                                              (hi, cb)]:
                return [(lo, hi, ca, k)]
        out, stack = [], [(a, ca, b, cb)]
        while stack:
            a, ca, b, cb = stack.pop()
            m = cb - ca
            if m <= 0:
                continue
            if m == 1 or ((b - a) <= tol * b and done(a, b)):
                out.append((a, b, ca, m))
                continue
            mid, cm = self.count_off((a + b) / 2, b, digits)
            stack.append((mid, cm, b, cb))
            stack.append((a, ca, mid, cm))
        return out

    def _deltas(self, ws, dps: int, fewer: int | None = None) -> tuple:
        """``(Delta(i w), J(w))`` at each of ``ws`` at ``dps`` digits: the values as global
        mpmath numbers (the midpoints of balls where python-flint is installed: a ball costs
        a seventh of an mpmath number in the elimination, and these values only guide), the
        counts -1 where undecided.

        ``fewer``: where the proofs are balls, the digits tried first. Near a ``k``-fold
        root ``Delta`` is about the ``k``-th power of the distance, but it is the product
        of the pivots, of which each of the ``k`` small ones is about the distance itself:
        the digits that resolve the distance, and a guard, give ``Delta`` to many digits
        where ``k`` times as many were asked for (example 3's triple root, ``1e-40`` from
        it: 67 digits give ``Delta``, about ``1e-122``, to 13 digits; 131 were taken). A
        batch whose balls do not give every value to :data:`_GUIDE_ACCURACY` or leave a
        count undecided is evaluated at ``dps``.
        """
        tried = [fewer] if fewer is not None and fewer < dps and self.hp.rigorous else []
        for digits in tried + [dps]:
            ar = proof_arithmetic(digits, self.certified)
            values, counts = self.counter.delta(list(ws), ar)
            with ar:
                known = digits == dps or all(
                    c >= 0 and v.mid() != 0 and v.rad() <= _GUIDE_ACCURACY * abs(v.mid())
                    for v, c in zip(values, counts))
            if known:
                return [mpmath.re(ar.to_mpmath(v)) for v in values], counts

    def _zoom(self, a, b, k, resolution, ends=None):
        """A guess for an exact ``k``-fold root in ``(a, b)``, or None (``ends``: ``Delta``
        at ``a`` and ``b`` at the zoom's digits, where already evaluated).

        Near a ``k``-fold root ``Delta ~ C (omega - omega0)**k``, so ``|Delta|**(1/k)``
        is a symmetric V about ``omega0``: the V through two points either side of
        it puts its vertex at ``(a f(b) + b f(a)) / (f(a) + f(b))``, with an error
        of second order in the bracket. A few such steps in enough precision for
        ``|Delta|`` to keep its digits ``10**-resolution`` from the root give the
        bracket ``omega0 (1 -+ 10**-resolution / 2)``. Nothing is concluded here: the
        caller proves the bracket with two counts, and bisects as before when the
        roots are not one multiple root (distinct close roots, a poor guess).
        """
        dps = k * resolution + 20
        if dps > MAX_DPS:
            return None
        ctx = MP.from_digits(dps + 10).ctx
        half = ctx.mpf(10) ** (-resolution) / 2
        power = ctx.mpf(1) / k

        def v(*ws):      # the V: |Delta|**(1/k)
            return [abs(ctx.mpf(d)) ** power
                    for d in self._deltas(ws, dps, resolution + _GUIDE_DIGITS)[0]]

        a, b = ctx.mpf(a), ctx.mpf(b)
        lo, hi = a, b
        f_lo, f_hi = v(lo, hi) if ends is None else \
            [abs(ctx.mpf(d)) ** power for d in ends]
        for _ in range(8):
            if not f_lo + f_hi > 0:
                return None
            slope = (f_lo + f_hi) / (hi - lo)
            guess = (lo * f_hi + hi * f_lo) / (f_lo + f_hi)
            [f_guess] = v(guess)
            # |omega0 - guess| ~ f(guess) / slope: a bracket twice that wide
            reach = 2 * f_guess / slope
            if reach <= half * guess / 4:
                return guess * (1 - half), guess * (1 + half)
            lo, hi = guess - reach, guess + reach
            if not a <= lo < hi <= b:
                return None
            f_lo, f_hi = v(lo, hi)
        return None

    def prove_cluster(self, lo, hi, ca, m) -> Eigenvalue:
        """An ``m``-fold eigenvalue in ``[lo, hi]``: the counts ``ca`` and ``ca + m`` at the
        ends, in the proof arithmetic (and, without balls, at a second precision)."""
        digits = self.digits + 2 + SEPARATION_DIGITS + 15
        ar = proof_arithmetic(digits, self.certified)
        known = [self._proved.get((_key(w), digits)) for w in (lo, hi)]
        # (counts the cluster's split proved in balls at these digits stand)
        counts = known if ar.rigorous and None not in known else self.counter.counts([lo, hi], ar)
        for more in (30, 90):
            # an m-fold root's m pivots are about as small as the bracket is narrow, and a
            # stiff model's scale leaves fewer digits to decide them (the NAFEMS double
            # cross: undecided at 45 digits without balls): more digits where undecided
            if -1 not in counts:
                break
            ar = proof_arithmetic(digits + more, self.certified)
            counts = self.counter.counts([lo, hi], ar)
        if list(counts) != [ca, ca + m] or not (
                ar.rigorous or list(self.counter.counts([lo, hi], MP(ar.prec + 64)))
                == [ca, ca + m]):
            raise ComputationError(f"the counts at the ends of the {m}-fold eigenvalue near "
                                   f"{float(lo):.15g} rad/s are not {ca} and {ca + m}")
        ctx = MP(ar.prec + 64).ctx
        mid = (ctx.mpf(lo) + ctx.mpf(hi)) / 2
        proof = PROOFS["ball" if ar.rigorous else "mp"]
        return Eigenvalue(_exact_mpc_imag(mid), m, self.digits,
                          (_exact_mpf(lo), _exact_mpf(hi)), proof)


class _Point(NamedTuple):
    """A point of the proof stage: where (``t``), ``Delta`` there (``f``, None where the
    count is undecided), its count ``k`` and whether balls proved it."""

    t: object
    f: object
    k: int
    ball: bool
    r: float = 0.0          # a bound of the error of f (balls), else 0


def _tighten(i, t, f, k, ca, a, b, fa, fb):
    """Root ``i``'s bracket ``(a[i], b[i])`` (values ``fa[i], fb[i]``) narrowed to the point
    ``t`` (value ``f``) by its count ``k`` (in place): ``J(t) = J(a)`` puts the root above
    ``t``, one more below it; ``-1`` (undecided) leaves the bracket as it was."""
    if k == ca[i] and t > a[i]:
        a[i], fa[i] = t, f
    elif k == ca[i] + 1 and t < b[i]:
        b[i], fb[i] = t, f
    elif k >= 0 and k not in (ca[i], ca[i] + 1):
        raise _Misled(f"inconsistent counts near {float(t):.17g} rad/s")


def _context_of(x):
    """The mpmath context of a number of the bookkeeping's (a float: the global one)."""
    return getattr(x, "context", mpmath.mp)


def _scaled_float(x, ref: float) -> float:
    """``x * exp(-ref)`` as a float, for an mpmath number ``x`` of any size: its leading
    53 bits and its binary exponent apart (``x`` alone may pass the doubles' range)."""
    m, e = magnitude_parts(x)
    power = e * _LN2 - ref
    if not m or power < -745:
        return 0.0
    if power > 700:
        return math.inf
    return (-m if x._mpf_[0] else m) * math.exp(power)


_LN2 = math.log(2.0)


def _quadratic(p0, p1, p2, secant, a, b, h, target):
    """``(estimate, h)``: the secant step through the pair ``p1, p2`` about a root, corrected
    by the parabola through them and a third point ``p0`` near it (points ``(t, Delta)``),
    and the half-width (relative) of the next pair.

    The secant step errs by ``|f''/(2 f')| |t1 - r| |t2 - r|``; the parabola's correction
    removes that term and leaves one about ``|f''/f'| |t0 - r|`` times smaller. From the
    Newton start ``1e-13`` away and a first pair ``1e-21`` wide, about ``1e-55``: the next
    pair, as wide as the estimated error with room (never narrower than the target),
    proves 50 digits where the secant's ``1e-41`` took two more rounds. Falls back on the
    secant step and a pair at the target where the correction leaves the bracket.
    """
    (t0, f0), (t1, f1), (t2, f2) = p0, p1, p2
    if t0 in (t1, t2) or f1 is None or f2 is None or f1 == f2:
        return secant, min(h, target)
    d12 = (f2 - f1) / (t2 - t1)
    d012 = ((f2 - f1) / (t2 - t1) - (f1 - f0) / (t1 - t0)) / (t2 - t0)
    correction = d012 * (secant - t2) * (secant - t1) / d12
    estimate = secant - correction
    if not a < estimate < b:
        return secant, min(h, target)
    error = abs(correction * d012 / d12 * (t0 - estimate))
    return estimate, max(target, min(h, 16 * error / estimate))


def _key(w):
    """A point as a dictionary key, exactly (mpmath numbers by their ``_mpf_``)."""
    return w._mpf_ if hasattr(w, "_mpf_") else float(w)


#: Bits beyond ``log2(h / target)`` that a round of estimating pairs is evaluated with
#: (:meth:`_Search._estimating`): the secant's division and a margin for the values' rounding.
_ESTIMATE_GUARD = 24

#: The digits whose working precision evaluates the Newton start's point at most
#: (:meth:`_Search._newton_start`): its step from a double estimate errs by about the
#: estimate's error squared.
_START_DIGITS = 30
#: Digits beyond a zoom's resolution its values of ``Delta`` are tried in first
#: (:meth:`_Search._deltas`), and the relative accuracy they must reach there.
_GUIDE_DIGITS = 30
_GUIDE_ACCURACY = 1e-6


class _Misled(ComputationError):
    """The proofs found a bracket of the isolation not to hold the one root it was to hold
    (a count outside ``J(a), J(a) + 1``, or no pair straddling a root there): the double
    counts the isolation trusted were wrong. :func:`solve_undamped` isolates again on
    counts proved in balls."""


class _MorePrecision(Exception):
    """A count in the proof arithmetic is undecided: raise its precision."""


def estimates(model: Model, omega_max: float, rigid: int | None = None) -> tuple:
    """``(frequencies, evaluations)``: the natural frequencies of ``model`` without its
    dashpots in ``(0, omega_max]``, in double precision and not proved (estimates, e.g.
    where a damped search starts its eigenvalues); a cluster double precision does not
    split gives its midpoint once per root in it. ``frequencies`` is None where the
    counts do not serve (nothing is concluded from it either way). ``rigid``: the
    rigid-body modes where known (:func:`rigid_body_modes`).

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
    >>> w, _ = estimates(Model((b,), (Spring("b", "ground", x="1/4", k=0, c="1/2"),)), 100)
    >>> [round(x, 6) for x in w]                        # (n pi)^2
    [9.869604, 39.478418, 88.82644]
    """
    from ..deadline import check
    search = _Search(model, 15, max(float(omega_max), 1e-300))
    try:
        search.rigid = rigid if rigid is not None else \
            _rigid_modes(model, search.counter, omega_max)
        top, c_top = search.count_off(float(omega_max), 2.0 * float(omega_max))
        out = [w for w in _double_levels(search, top, c_top) if 0 < w <= omega_max]
    except ComputationError:
        check()                 # (a spent time budget ends the search, as elsewhere)
        return None, search.evaluations
    return sorted(out), search.evaluations


def _double_levels(search: _Search, top, c_top: int) -> list:
    """The frequencies in ``(0, top]`` (``J(top) = c_top``) in double precision, not
    proved: isolated and refined; a cluster double precision does not split, its midpoint
    once per root in it."""
    brackets = search.isolate(top, c_top)
    simple = [(a, ca, b) for a, ca, b, cb in brackets if cb - ca == 1]
    out = list(search.refine_double(simple))
    for a, ca, b, cb in brackets:
        if cb - ca > 1:
            out += [0.5 * (a + b)] * (cb - ca)
    return out


#: The natural frequencies beyond a count's that a damped count's top may be placed among
#: (no more than a region's count keeps before it lowers its top: 2 for small counts).
_GAP_LOOK = 2
#: A gap between natural frequencies this wide (relative to the upper) takes a top at once.
_WIDE_GAP = 0.02


def undamped_levels(model: Model, count: int) -> tuple:
    """``(frequencies, evaluations)``: the first ``count + 2`` natural frequencies (at least)
    of ``model`` without its dashpots, its rigid-body modes as zeros, ascending, in double
    precision and not proved (a cluster double precision does not split gives its midpoint
    once per root in it); None where the search cannot say.

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="free")
    >>> w, _ = undamped_levels(Model((b,), (Spring("b", "ground", x="1/2", k=0, c=1),)), 1)
    >>> w[0], round(w[1], 6)                         # the turning about the pin, 3.9266**2
    (0.0, 15.418206)
    """
    from ..deadline import check
    search = _Search(model, 15, _first_guess(model))
    try:
        top, c_top = search.top_for(count + _GAP_LOOK)
        search.rigid = _rigid_modes(model, search.counter, top)
        values = [0.0] * search.rigid + _double_levels(search, top, c_top)
    except ComputationError:
        check()                 # (a spent time budget ends the search, as elsewhere)
        return None, search.evaluations
    return sorted(values), search.evaluations


def gap_above(model: Model, count: int) -> tuple:
    """``(tops, evaluations)``: frequencies in gaps between the natural frequencies of
    ``model`` without its dashpots (:func:`undamped_levels`), where a
    damped count's region may end: midway across the first gap at or above the
    ``count``-th at least 2 % of its upper frequency wide, else the widest of the next two
    where it is over 4 times the ``count``-th's; where that gap is narrow, the last wide
    gap below it first. Empty where the frequencies cannot say.

    Where a damped search of the complex plane starts the top of its region for a
    count: lightly damped eigenvalues lie near the undamped ones, and a top in a gap
    is neither short nor far beyond (doubling from the lowest pinned mode overshot a
    crowd of nearly undamped modes into 294 where 4 were asked, and eight region
    searches lowered it again: 14 of a campaign model's 30 s). A wide gap, not the next
    midpoint: a heavy Rayleigh beam's modes lie 1e-6 apart, and a top among them puts
    the region's side beside them (5 s of isolation and proofs); the gap below first,
    since a heavy dashpot adds real eigenvalues that no undamped frequency foretells (a
    campaign model's count was met there).

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
    >>> w, _ = gap_above(Model((b,), (Spring("b", "ground", x="1/4", k=0, c="1/2"),)), 2)
    >>> [round(x / math.pi**2, 6) for x in w]           # between 4 pi**2 and 9 pi**2
    [6.5]
    """
    values, spent = undamped_levels(model, count)
    if values is None or len(values) <= count:
        return [], spent

    def gap(j):
        return (values[j + 1] - values[j]) / values[j + 1] if values[j + 1] > 0 else 0.0

    ahead = [(gap(j), j) for j in range(count - 1, min(len(values) - 1, count - 1 + _GAP_LOOK))]
    wide = [g for g in ahead if g[0] >= _WIDE_GAP]
    # (among narrow gaps one more eigenvalue in the region pays only for a far wider gap:
    # a crowd 1e-6 apart took 9 s with its fourth, 6 s without)
    width, j = wide[0] if wide else max(ahead) if max(ahead)[0] > 4 * ahead[0][0] \
        else ahead[0]
    if not width > 0:
        return [], spent
    tops = [0.5 * (values[j] + values[j + 1])]
    if j == count - 1 and width < _WIDE_GAP or j > count - 1:
        below = [i for i in range(count - 2, -1, -1) if gap(i) >= _WIDE_GAP]
        if below:
            tops.insert(0, 0.5 * (values[below[0]] + values[below[0] + 1]))
    return tops, spent


def _isolated_and_proved(search: _Search, top, c_top: int, wanted, cuts, next_stage) -> list:
    """The eigenvalues below ``top`` (``J(top) = c_top``): isolated, refined in double
    precision, multiple ones split and proved, the rest proved by pairs."""
    brackets = search.isolate(top, c_top, wanted, cuts)
    simple = [(a, ca, b) for a, ca, b, cb in brackets if cb - ca == 1]
    clusters = [(a, ca, b, cb - ca) for a, ca, b, cb in brackets if cb - ca > 1]
    next_stage("refining")
    items = [(guess, ca, (a, b)) for (a, ca, b), guess in
             zip(simple, search.refine_double(simple))]
    next_stage("multiple roots")
    eigen = []
    for a, ca, b, k in clusters:
        for lo, hi_, cl, m in search.split_cluster(a, ca, b, k):
            if m == 1:
                items.append((None, cl, (lo, hi_)))     # (its midpoint, exactly)
            else:
                eigen.append(search.prove_cluster(lo, hi_, cl, m))
    next_stage("proving the digits")
    return eigen + search.refine_high(items)


def solve_undamped(model: Model, count: int | None = None, omega_max=None,
                   digits: int = 15, certified: bool | None = None,
                   guesses=None) -> Spectrum:
    """Natural frequencies of an undamped model.

    Parameters
    ----------
    model : Model
        Numeric and undamped.
    count : int, optional
        The first ``count`` eigenvalues with multiplicity (rigid-body modes
        included; a multiple root that straddles ``count`` is reported whole).
    omega_max : float, optional
        All eigenvalues with ``0 <= omega <= omega_max``.
    digits : int
        Significant digits, all correct (default 15).
    certified : bool, optional
        Prove in ball arithmetic (needs python-flint); False: mpmath at two
        precisions; None (default): balls where python-flint is installed.
    guesses : sequence of (float, float), optional
        With ``count``: estimates ``(omega, relative half-width)`` of the natural
        frequencies (a sweep's previous steps, extrapolated). They decide where the
        search looks first, never what it proves (:meth:`_Search.guided`).

    Returns
    -------
    Spectrum
        Eigenvalues ``lam = i omega``, ascending, each with the proof behind it.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> spec = solve_undamped(pp, count=3, digits=20)
    >>> [str(e) for e in spec]            # (n pi)^2
    ['9.8696044010893586188i', '39.478417604357434475i', '88.826439609804227570i']
    """
    model = checked_request(model, count, omega_max, digits)
    if model.damped:
        raise ValueError("model is damped: use the damped solver")
    start = time.perf_counter()
    if omega_max is not None:
        hi = float(omega_max)
        if hi < 0:
            raise ValueError("omega_max must not be negative")
        search = _Search(model, digits, max(hi, 1e-300), certified)
    else:
        hi = _first_guess(model)
        search = _Search(model, digits, hi, certified)
    counted, cuts = None, []
    if omega_max is None and count > 0:
        # (the count at the top includes the rigid-body modes; the plans it builds serve
        # the static null space below, which needs no mesh of its own)
        guided = search.guided(guesses, count) if guesses else None
        counted, cuts = guided or (search.top_for(count), [])
        hi = counted[0]
    rigid = search.rigid = _rigid_modes(model, search.counter, hi)
    check_stable(model, rigid, search.counter)
    eigen = []
    if rigid:
        eigen.append(Eigenvalue(mpmath.mpc(0, 0), rigid, digits, (0.0, 0.0), PROOFS["exact"]))
    wanted = None if count is None else count - rigid
    if hi > 0 and (wanted is None or wanted > 0):
        with progress.stages("solve", ["isolating", "refining", "multiple roots",
                                       "proving the digits"]) as next_stage:
            # include a root sitting exactly on omega_max (a top the search chose is
            # counted already: no root there matters)
            top, c_top = counted or search.count_off(hi * (1 + 4e-16), 2 * hi)
            try:
                eigen += _isolated_and_proved(search, top, c_top, wanted, cuts, next_stage)
            except _Misled:
                # a double count the isolation trusted was wrong (near-rigid motions held by
                # weak springs, roots 1e-7 apart on uncoupled beams: fuzzed models): the
                # top and every cut point again, counted in balls
                search.proved_cuts = True
                (top, c_top), = search.counts_off([top], [2 * top], 30)
                eigen += _isolated_and_proved(search, top, c_top, wanted, (), next_stage)
        if omega_max is not None:
            # nothing above the last bracket and below omega_max: the count there, proved
            got = search.counter.counts([top], search.hp)
            if got[0] != c_top:
                raise ComputationError(f"the count at omega_max is {got[0]}, not {c_top}")
    eigen.sort(key=lambda e: e.omega)
    if count is not None:
        eigen = first(eigen, count)
    elif omega_max is not None:
        top = _exact_mpf(float(omega_max) * (1 + 4e-16))
        eigen = [e for e in eigen if e.omega <= top]
    return Spectrum(tuple(eigen), digits, "default", search.evaluations,
                    time.perf_counter() - start, model.source or "", search.omega_scale,
                    _notes(eigen, digits), title=model.title)


def _notes(eigen, digits) -> tuple:
    """What a reader of the printed values should know: roots alike in print, multiples."""
    notes = []
    for i, (e, f) in enumerate(itertools.pairwise(eigen), 1):
        # (the strings only where the frequencies may print alike: each costs two
        # decimal conversions, 2 % of example 1's solve for every pair)
        if e.omega != 0 and not print_apart(e.omega, f.omega, digits) and str(e) == str(f):
            notes.append(f"eigenvalues {i} and {i + 1} are distinct but agree to {digits} "
                         "digits; more digits tell them apart")
    if any(e.multiplicity > 1 and e.omega != 0 for e in eigen):
        notes.append(f"a multiplicity m > 1: m eigenvalues agree to {digits + SEPARATION_DIGITS} "
                     "digits (exact multiple roots, or closer than that)")
    return tuple(notes)
