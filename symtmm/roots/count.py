"""The Wittrick–Williams count and ``Delta`` on the frequency axis, on the numeric kernel.

For an undamped model the number of natural frequencies below ``omega``
(with multiplicity, rigid-body modes included) is ``J(omega) = J0 + s{K(omega)}``
(Wittrick & Williams 1971): ``s{K}`` the number of negative eigenvalues of the
exact dynamic stiffness, read off the signs of the ``LDL^T`` pivots
(:func:`symtmm.numeric.stiffness.factor`), and ``J0 = 0`` because the plan's
pieces stay below their own clamped-clamped frequencies
(:data:`symtmm.numeric.plan.NU_MAX`). One factorisation gives both the count and
``Delta(i omega)``, for a whole batch of frequencies.

:class:`Counter` keeps one plan per frequency range and evaluates in any
arithmetic: double batches to search, mpmath or Arb balls to decide and to prove.
A count whose pivots cannot all be trusted at one precision is redone at a higher
one; a point where a pivot stays undecided to :data:`SINGULAR_DIGITS` digits is
taken for an eigenvalue (:class:`SingularCount`): the count is not defined there.
"""

from __future__ import annotations

import math

import numpy as np

from ..deadline import check as check_time
from ..errors import ComputationError
from ..numeric.arith import DOUBLE, MP, Arithmetic, Ball, ball_available
from ..numeric.evaluator import Evaluator, exact_mpf
from ..numeric.stiffness import factor, summary

__all__ = ["Counter", "SingularCount", "SINGULAR_DIGITS", "proof_arithmetic"]

#: A count whose pivots stay undecided up to this many digits is taken at an eigenvalue.
SINGULAR_DIGITS = 240


class SingularCount(ArithmeticError):
    """``K(omega)`` is singular: ``omega`` is an eigenvalue, where the count is not defined.

    ``J(omega)`` counts the eigenvalues strictly below ``omega``; at an eigenvalue a
    pivot of ``K`` is zero and its sign undefined. Callers count at a point moved off it.
    """


def proof_arithmetic(digits: int, certified: bool | None = None) -> Arithmetic:
    """The arithmetic that decides and proves at ``digits`` decimal digits.

    Arb balls where python-flint is installed (``certified`` None or True), else
    mpmath (``certified`` False, or no flint): then results are checked at two
    precisions instead of proved.
    """
    if certified is None:
        certified = ball_available()
    return Ball.from_digits(digits) if certified else MP.from_digits(digits)


class Counter(Evaluator):
    """Counts and ``Delta(i omega)`` of an undamped model, any arithmetic, in batches.

    Parameters
    ----------
    model : Model
        Numeric; dashpots are ignored (the count of the model without them, on the
        model's own plans).
    omega_design : float
        Highest frequency expected; a higher one gets a plan of its own.

    Attributes
    ----------
    evaluations : int
        Frequencies evaluated (one per point of every batch, every arithmetic).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> c = Counter(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 100.0)
    >>> c.counts(np.array([1.0, 10.0, 40.0, 90.0])).tolist()   # roots (n pi)^2
    [0, 1, 2, 3]
    """

    def __init__(self, model, omega_design: float):
        model = model.require_numeric()
        super().__init__(model, omega_design)
        # a damped model is counted on its own plans, its dashpots still: their column of
        # the stiffness (lam) set to 0, as the model without them would have it (a model of
        # its own built its own plans: a third of a damped search's estimates)
        self._still = model.damped
        # an undamped model's counts add the pieces' clamped-clamped eigenvalues below each
        # frequency (J0): its long pieces pass them, a beam's n-th mode in about n pi /
        # NU_LONG pieces where short ones take n (a cantilever's 300 modes: 314 pieces)
        self.clamped = not model.damped

    def _lam(self, count: int, ar: Arithmetic = DOUBLE):
        """The dashpots' ``lam`` at ``count`` points: zeros for a damped model, else None."""
        if not self._still:
            return None
        return np.zeros(count) if ar is DOUBLE else ar.zeros(count)

    # -- batches ------------------------------------------------------------------------
    def factors(self, omegas, ar: Arithmetic = DOUBLE, positive: bool = False):
        """:class:`~symtmm.numeric.stiffness.Factors` at ``lam**2 = -omega**2`` for every omega.

        ``omegas``: floats (double) or numbers with an ``_mpf_`` (exact inputs for the other
        arithmetics). ``positive``: at ``lam**2 = +omega**2`` instead (a real, growing
        ``lam``; buckling checks).
        """
        check_time()        # (a search's wall-clock budget: symtmm.deadline)
        if ar is DOUBLE:
            w = np.asarray(omegas, dtype=float)
            self.evaluations += w.size
            return factor(self.plan(float(np.max(w, initial=0.0)), w.size), ar,
                          w * w if positive else -(w * w), lam=self._lam(w.size))
        points = [exact_mpf(v) for v in omegas]
        self.evaluations += len(points)

        def build(work, chosen):
            if not positive:
                return work.negated_squares(chosen), self._lam(len(chosen), work)
            return work.square(work.array([work.number(v) for v in chosen])), \
                self._lam(len(chosen), work)
        return self._in_parts(self.plan(max((float(v) for v in points), default=0.0),
                                        len(points), ar), ar, points, build)

    def matrix(self, omega: float) -> np.ndarray:
        """The dense ``K(omega)`` in double precision (scaled by powers of two: its inertia,
        and so the count, is that of the unscaled one)."""
        from ..numeric.stiffness import assemble, dense
        w = float(omega)
        K, _ = assemble(self.plan(w), DOUBLE, np.array([-w * w]), self._lam(1))
        return dense(self.plan(w), K)[0].real

    def counts(self, omegas, ar: Arithmetic = DOUBLE) -> np.ndarray:
        """``J(omega)`` per point, ``-1`` where the arithmetic cannot decide it."""
        if len(omegas) == 0:
            return np.zeros(0, dtype=int)
        if ar is DOUBLE:
            got = self._summary(omegas)
            if got is not None:
                return got[2]
        return self.factors(omegas, ar).counts()

    def _summary(self, omegas):
        """:func:`~symtmm.numeric.stiffness.summary` at ``lam**2 = -omega**2`` (floats),
        counted as evaluations; None where the compiled kernel does not serve."""
        check_time()
        w = np.asarray(omegas, dtype=float)
        got = summary(self.plan(float(np.max(w, initial=0.0)), w.size), -(w * w),
                      self._lam(w.size))
        if got is not None:
            self.evaluations += w.size
        return got

    def nonsingular_static(self, plan) -> bool:
        """Whether ``K(0)`` of ``plan`` is proved nonsingular: one ball factorisation at
        ``lam = 0`` with every pivot decided, so the model has no rigid-body mode. False
        where python-flint is missing or a pivot stays undecided (a rigid-body mode, or
        too few bits): the exact static null space decides then
        (:func:`~symtmm.mesh.static_nullity`, a few milliseconds of SymPy on a chain).

        Examples
        --------
        >>> from symtmm.model import Beam, Model
        >>> pf = Counter(Model((Beam("b", 1, 1, 1, left="pinned", right="free"),)), 10.0)
        >>> pp = Counter(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 10.0)
        >>> [c.nonsingular_static(c.plan(10.0)) for c in (pf, pp)] == [False,
        ...                                                            ball_available()]
        True
        """
        if not ball_available() or plan.n == 0:
            return False
        # (two words and the quarter bit per freedom the radii's growth takes)
        ar = Ball(128 + plan.n // 4)
        with ar:
            lam2 = ar.array([ar.exact(0)])
        self.evaluations += 1
        return bool(factor(plan, ar, lam2, self._lam(1, ar)).trusted[0])

    # -- one point, decided ---------------------------------------------------------------
    def count(self, omega, digits: int | None = None, positive: bool = False) -> int:
        """``J(omega)``: double precision unless a pivot is too small to trust; then (or with
        ``digits``) in the proof arithmetic (balls where python-flint is installed, else
        mpmath) from ``digits`` (default 30) digits, doubled until decided."""
        if digits is None:
            # (the compiled summary where it serves: the factors' numpy bookkeeping costs a
            # single point ten times its elimination)
            c = self.factors([float(omega)], DOUBLE, positive).counts()[0] if positive \
                else self.counts([float(omega)])[0]
            if c >= 0:
                return int(c)
            digits = 30
        while True:
            c = self.factors([omega], proof_arithmetic(digits), positive).counts()[0]
            if c >= 0:
                return int(c)
            if digits >= SINGULAR_DIGITS:
                raise SingularCount(f"K({float(omega):.17g}) is singular to {digits} digits: "
                                    "an eigenvalue")
            digits *= 2

    def count_off(self, omega: float, toward: float, digits: int | None = None):
        """``(point, J(point))``: at ``omega``, or moved a little toward ``toward`` when
        ``omega`` is an eigenvalue (any point serves where this is used)."""
        step = (toward - omega) * 1e-7
        for k in range(12):
            try:
                return omega, self.count(omega, digits)
            except SingularCount:
                omega = omega + step * 4**k
        raise ComputationError(f"cannot find a point near {float(omega):.6g} rad/s that is "
                               "not an eigenvalue")

    def unstable_modes(self, rigid: int, omega_ref: float) -> int:
        """Eigenvalues with ``omega**2 < 0``: modes buckled by an axial compression.

        ``J`` extends to ``omega**2 < 0`` (``K`` at the real ``lam = w`` counts the
        eigenvalues below ``-w**2``; the pieces' clamped-clamped ones all lie above
        zero). Without rigid-body modes this is the count of the static ``K(0)``; with
        ``rigid`` of them (``omega = 0`` exactly) the counts at ``omega**2 = -w**2`` and
        ``+w**2`` must differ by ``rigid`` alone, for a ``w`` from ``1e-3 omega_ref`` down,
        so that no eigenvalue near zero is taken for a buckled or a rigid one.
        """
        if rigid == 0:
            try:
                return self.count(0.0)
            except SingularCount:
                pass
        w = 1e-3 * float(omega_ref)
        for _ in range(6):
            try:
                below, above = self.count(w, positive=True), self.count(w)
            except SingularCount:
                below = above = None
            if below is not None and above - below == rigid:
                return below
            w *= 1e-3
        raise ComputationError("cannot tell whether the axial compression is above a buckling "
                               f"load: eigenvalues with |omega| below {w * 1e3:.3g} rad/s besides "
                               "the rigid-body modes")

    # -- Delta ------------------------------------------------------------------------------
    def signed_log_delta(self, omegas):
        """``(log|Delta|, sign Delta, counts)`` of ``Delta(i omega)`` (real), double, batched."""
        got = self._summary(omegas)
        if got is None:
            fa = self.factors(omegas, DOUBLE)
            got = fa.log_delta() + (fa.counts(),)
        logabs, phase, counts = got
        return logabs, np.where(np.cos(phase) < 0, -1.0, 1.0), counts

    def delta(self, omegas, ar: Arithmetic):
        """``(Delta(i omega), counts)`` in ``ar`` (mpmath numbers or balls)."""
        fa = self.factors(omegas, ar)
        return fa.delta(), fa.counts()

    def midpoints(self, omegas, ar: Arithmetic, ctx):
        """``(Delta(i omega), counts, radii)``: ``Delta`` evaluated in ``ar`` as numbers of
        the mpmath context ``ctx`` (None where the count is undecided) and bounds of their
        errors (:meth:`~symtmm.numeric.stiffness.Factors.midpoints`)."""
        fa = self.factors(omegas, ar)
        values, radii = fa.midpoints(ctx)
        return values, fa.counts(), radii


def digits_for(digits: int) -> int:
    """Working digits of the high-precision stage for ``digits`` correct digits.

    The stiffness formulation loses no digit to the growth of long segments; what is
    needed beyond the result's digits is the resolution of a pivot ``10**-(digits+3)``
    of the scale (a bracket end that close to a root) and guard digits.
    """
    return digits + 25 + math.ceil(math.log10(max(digits, 1)))
