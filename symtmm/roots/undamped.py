"""Natural frequencies of undamped models, none missed, to any number of digits.

1. **Count.** The Wittrick–Williams count ``J(omega)`` (:mod:`symtmm.stiffness`)
   gives the number of natural frequencies below any ``omega``, with
   multiplicity, rigid-body modes included. Rigid-body modes are the null
   space of the exact static ``R(0)``.
2. **Isolate.** Bisection on ``J`` splits ``(0, omega_max]`` into brackets
   holding one root each; brackets that still hold several roots when they
   are narrower than double precision can resolve go to step 4.
3. **Refine** each simple root on ``Delta(i omega) = det R`` (the transfer
   formulation, real on the frequency axis) with the Anderson–Björck
   bracketing method: first in double precision on the stable evaluator, to
   a bracket of relative width about 1e-9 that mpmath must confirm (a sign
   change at its ends), then in mpmath at ``D + loss + 10`` digits, where ``loss``
   estimates the cancellation in ``Delta`` (``sum beta L / ln 10``). The
   final bracket, of relative width below ``10**-(D+2)`` and with both ends
   rounding to the same ``D`` digits, is then checked at 15 more digits:
   ``Delta`` must still change sign strictly across it, or the precision is
   raised and the refinement repeated.
4. **Clusters.** A bracket holding ``k`` roots is first tried as one exact
   ``k``-fold root: ``|Delta|**(1/k)`` is a V about it, whose vertex, found in a
   few steps, gives a bracket of width ``10**-(D + 2 + SEPARATION_DIGITS)`` that
   two counts in mpmath then prove to hold all ``k``. Otherwise (distinct close
   roots) brackets are bisected with the count
   in mpmath until each holds one root (then step 3) or is narrower than
   ``10**-(D + 2 + SEPARATION_DIGITS)`` relative with both ends printing the
   same ``D`` digits: the roots it holds agree to ``D + SEPARATION_DIGITS``
   digits and are reported once with their multiplicity (exact multiple roots
   end there). Distinct roots closer than ``10**-D`` are reported separately,
   with a note that they print alike.
"""

from __future__ import annotations

import itertools
import math
import time
from dataclasses import replace

import mpmath
import numpy as np
import sympy as sp

from ..assembly import boundary_matrix
from ..compile import Evaluator
from ..errors import ComputationError
from ..model import Model
from ..results import Eigenvalue, Spectrum
from ..stiffness import SingularCount, StiffnessModel
from .bracket import SEPARATION_DIGITS, anderson_bjorck, bracket_done

__all__ = ["solve_undamped", "rigid_body_modes", "check_stable", "omega_scale"]

#: Relative width below which a double-precision count is not asked to split a bracket.
_DOUBLE_WIDTH = 1e-11
#: Largest precision (decimal digits) the refinement may climb to.
MAX_DPS = 3000



def rigid_body_modes(model: Model) -> int:
    """Number of rigid-body (zero-frequency) modes: the nullity of ``R(0)``.

    Exact rank over the rationals when ``R(0)`` is rational (Euler–Bernoulli,
    Rayleigh and Timoshenko beams without axial force or foundation: the
    segments' static transfer matrices are polynomial; rigid bodies add
    rational entries). An axial force or a foundation makes ``R(0)``
    transcendental: its nullity is then decided numerically at two precisions
    (:meth:`Evaluator.nullity_at_zero`).

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
    model = model.require_numeric()
    if any(b.kw != 0 or b.N != 0 for b in model.beams):
        return Evaluator(model).nullity_at_zero()
    R = boundary_matrix(model, lam=sp.Integer(0))
    if R.shape[1] == 0:
        return 0
    # exact elimination in the smallest domain holding the entries (the rationals for
    # numeric models): Matrix.rank's fraction-free elimination takes minutes at 10 levels
    from sympy.polys.matrices import DomainMatrix
    dm = DomainMatrix.from_Matrix(R)
    if dm.domain.is_EX:
        return R.shape[1] - R.rank(simplify=True)
    return R.shape[1] - dm.rank()


def check_stable(model: Model, rigid: int, sm: StiffnessModel | None = None) -> int:
    """Raise :class:`ComputationError` if an axial compression has buckled the model.

    Above a buckling load the static stiffness is indefinite: eigenvalues with
    ``lam**2 > 0`` (real ``lam``, a motion growing without bound), which the
    search for natural frequencies would not report. Only a compressed beam
    can cause them; dashpots do not change the static stiffness. ``sm`` is the
    stiffness model to count with (default: one of ``model`` without dashpots).
    Returns the number of counts spent when ``sm`` was not given (else 0).

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
    own = sm is None
    if own:
        undamped = replace(model, springs=tuple(replace(s, c=0) for s in model.springs))
        sm = StiffnessModel(undamped, _first_guess(model))
    k = sm.unstable_modes(rigid, _first_guess(model))
    if k:
        raise ComputationError(f"axial compression above a buckling load: {k} mode"
                               f"{'s' if k > 1 else ''} with lam**2 > 0")
    return sm.evaluations if own else 0


def omega_scale(model: Model):
    """``(name, sqrt(EI/(m L^4)))`` of the first beam: ``omega = Omega**2 * scale``."""
    b = model.resolved().beams[0]
    return b.name, sp.sqrt(b.EI / (b.m * b.L**4))


def _pinned_omega2(beam) -> float:
    """``omega**2`` of the first pinned-pinned mode of ``beam`` in its own theory.

    With ``q = (pi/L)**2``: ``(EI q**2 + N q + kw) / (m + rhoI q)`` rigid in shear;
    a Timoshenko beam's is the smaller root of
    ``(a1 - m w)(a2 - rhoI w) = kGA**2 q``, ``a1 = (kGA + N) q + kw``, ``a2 = EI q + kGA``.
    """
    EI, m, L = float(beam.EI), float(beam.m), float(beam.L)
    N, rhoI, kw = float(beam.N), float(beam.rhoI), float(beam.kw)
    q = (math.pi / L) ** 2
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


def _first_guess(model: Model) -> float:
    """A frequency of the order of the lowest natural frequency.

    The lowest first pinned-pinned frequency of the beams, each in its own
    theory; a beam compressed beyond that mode's buckling load gives its
    Euler–Bernoulli value instead.
    """
    best = math.inf
    for b in model.resolved().beams:
        w2 = _pinned_omega2(b)
        if not w2 > 0:
            w2 = float(b.EI) / float(b.m) * (math.pi / float(b.L)) ** 4
        best = min(best, math.sqrt(w2))
    return best


class _Search:
    def __init__(self, model: Model, digits: int, omega_hi: float, rigid: int = 0):
        self.model = model
        self.digits = digits
        self.rigid = rigid
        self.ev = Evaluator(model)
        self.sm = StiffnessModel(model, omega_hi)

    @property
    def evaluations(self) -> int:
        return self.ev.evaluations + self.sm.evaluations

    def count(self, omega, dps=None) -> int:
        return self.sm.count(omega, dps=dps)

    def count_off(self, omega, toward, dps=None):
        """``(point, count)``: the count at ``omega``, or, if ``omega`` is exactly an
        eigenvalue (the count is not defined there), at a point moved a little
        toward ``toward``. Any point serves where this is used (a bisection point,
        an upper bound), as long as it is not an eigenvalue.
        """
        step = (toward - omega) * 1e-7
        for k in range(12):
            try:
                return omega, self.count(omega, dps=dps)
            except SingularCount:
                omega = omega + step * 4**k
        raise ComputationError(f"cannot find a point near {float(omega):.6g} rad/s that is "
                               "not an eigenvalue")

    # -- isolation ------------------------------------------------------------------
    def isolate(self, lo, c_lo, hi, c_hi, needed=None):
        """Brackets ``(a, b, k)`` with ``k`` roots in ``(a, b]``, ascending.

        Stops once ``needed`` roots (with multiplicity) are bracketed.
        """
        out, found = [], 0
        stack = [(lo, c_lo, hi, c_hi)]
        while stack:
            a, ca, b, cb = stack.pop()
            k = cb - ca
            if k <= 0:
                continue
            if needed is not None and found >= needed:
                break
            # Delta vanishes at 0 when there are rigid-body modes, so a bracket to be
            # refined on Delta must not start there
            at_rigid_zero = a == 0 and self.rigid > 0
            if (k == 1 and not at_rigid_zero) or (b - a) <= _DOUBLE_WIDTH * b:
                out.append((a, b, k))
                found += k
                continue
            mid, cm = self.count_off(0.5 * (a + b), b)
            # left half first: push it last
            stack.append((mid, cm, b, cb))
            stack.append((a, ca, mid, cm))
        return out

    # -- clusters ---------------------------------------------------------------------
    def split_cluster(self, a, b, k):
        """Separate the ``k`` roots in ``(a, b]`` by bisection on high-precision counts.

        Returns brackets ``(lo, hi, m)``, ascending: ``m == 1`` for a root of its
        own, ``m > 1`` for roots that still share a bracket of relative width
        ``10**-(D + 2 + SEPARATION_DIGITS)``: they agree to ``D + SEPARATION_DIGITS``
        digits and are reported as one eigenvalue of multiplicity ``m``. Exact
        multiple roots (identical beams, symmetric couplings) end there; distinct
        roots are told apart however close, down to that resolution.
        """
        resolution = self.digits + 2 + SEPARATION_DIGITS
        dps = resolution + 15
        with mpmath.workdps(dps):
            a, b = mpmath.mpf(a), mpmath.mpf(b)
            a, ca = self.count_off(a, b, dps=dps)
            cb = ca + k
            tol = mpmath.mpf(10) ** (-resolution)
            zoomed = self._zoom(a, b, k, resolution)
            if zoomed is not None:
                lo, hi = zoomed
                # the proof: two counts, as at the end of the bisection below
                if (bracket_done(lo, hi, self.digits) and self.count_off(lo, a, dps=dps)
                        == (lo, ca) and self.count_off(hi, b, dps=dps) == (hi, cb)):
                    return [(lo, hi, k)]
            out, stack = [], [(a, ca, b, cb)]
            while stack:
                a, ca, b, cb = stack.pop()
                m = cb - ca
                if m <= 0:
                    continue
                if m == 1 or ((b - a) <= tol * b and bracket_done(a, b, self.digits)):
                    out.append((a, b, m))
                    continue
                mid, cm = self.count_off((a + b) / 2, b, dps=dps)
                stack.append((mid, cm, b, cb))
                stack.append((a, ca, mid, cm))
            return out

    def _zoom(self, a, b, k, resolution):
        """A guess for an exact ``k``-fold root in ``(a, b)``, or None.

        Near a ``k``-fold root ``Delta ~ C (omega - omega0)**k``, so ``|Delta|**(1/k)``
        is a symmetric V about ``omega0``: the V through two points either side of
        it puts its vertex at ``(a f(b) + b f(a)) / (f(a) + f(b))``, with an error
        of second order in the bracket. A few such steps in enough precision for
        ``|Delta|`` to keep its digits ``10**-resolution`` from the root give the
        bracket ``omega0 (1 -+ 10**-resolution / 2)``. Nothing is concluded here: the
        caller proves the bracket with two counts, and bisects as before when the
        roots are not one multiple root (distinct close roots, a poor guess). Two
        counts replace the ~3.3 counts per digit of a bisection to the same width.
        """
        dps = k * resolution + math.ceil(self.ev.digits_lost(1j * float(b))) + 20
        if dps > MAX_DPS:
            return None
        with mpmath.workdps(dps):
            half = mpmath.mpf(10) ** (-resolution) / 2
            power = mpmath.mpf(1) / k

            def v(w):      # the V: |Delta|**(1/k)
                return abs(self._f(w)) ** power

            lo, hi = mpmath.mpf(a), mpmath.mpf(b)
            f_lo, f_hi = v(lo), v(hi)
            for _ in range(8):
                if not f_lo + f_hi > 0:
                    return None
                slope = (f_lo + f_hi) / (hi - lo)
                guess = (lo * f_hi + hi * f_lo) / (f_lo + f_hi)
                f_guess = v(guess)
                # |omega0 - guess| ~ f(guess) / slope: a bracket twice that wide
                reach = 2 * f_guess / slope
                if reach <= half * guess / 4:
                    return guess * (1 - half), guess * (1 + half)
                lo, hi = guess - reach, guess + reach
                if not a <= lo < hi <= b:
                    return None
                f_lo, f_hi = v(lo), v(hi)
        return None

    # -- refinement --------------------------------------------------------------------
    def _double_bracket(self, a: float, b: float):
        """The root's bracket narrowed to ~1e-11 relative on the double-precision Delta.

        The stable evaluator (:meth:`Evaluator.log_delta`) keeps about 13 digits, so
        the sign it shows is right except within about ``1e-13 |lam|`` of the root.
        Nothing is concluded from it: the narrowed bracket, padded, must show the
        sign change again in mpmath before it replaces ``(a, b]``. Returns None when
        double precision shows no sign change.
        """
        ref = []

        def f(w):
            logabs, phase = self.ev.log_delta(np.array([1j * float(w)]))
            if not np.isfinite(logabs[0]):
                return 0.0
            if not ref:
                ref.append(logabs[0])
            return math.copysign(math.exp(min(logabs[0] - ref[0], 700.0)), math.cos(phase[0]))

        fa, fb = f(a), f(b)
        if fa == 0 or fb == 0 or (fa > 0) == (fb > 0):
            return None
        lo, hi = anderson_bjorck(f, a, b, fa, fb, lambda lo, hi: hi - lo <= 1e-11 * hi,
                                 1e-11 * b)
        return float(lo), float(hi)

    def refine(self, a, b) -> Eigenvalue:
        """One simple root in ``(a, b]`` to ``digits`` significant digits."""
        extra = 0
        # a bracket from a separated cluster may be far narrower than double precision
        width = mpmath.mpf(b - a) / b
        resolved = max(0, -int(mpmath.floor(mpmath.log10(width)))) if width > 0 else 0
        narrow = self._double_bracket(float(a), float(b)) if width > 1e-9 else None
        if narrow is not None:
            pad = 1e-9 * narrow[1]
            narrow = (max(float(a), narrow[0] - pad), min(float(b), narrow[1] + pad))
        while True:
            dps = (max(self.digits, resolved) + math.ceil(self.ev.digits_lost(1j * float(b)))
                   + 10 + extra)
            if dps > MAX_DPS:
                raise ComputationError(
                    f"cannot reach {self.digits} digits for the root near {float(b):.6g} rad/s "
                    f"within {MAX_DPS} working digits")
            with mpmath.workdps(dps):
                lo = None
                if narrow is not None:
                    # the double-precision bracket, if mpmath confirms its sign change
                    lo, hi = self._bracket_refine(mpmath.mpf(narrow[0]), mpmath.mpf(narrow[1]))
                    narrow = None if lo is None else narrow
                if lo is None:
                    lo, hi = self._bracket_refine(mpmath.mpf(a), mpmath.mpf(b))
            if lo is not None and self._verify(lo, hi, dps + 15):
                # build the result inside the context: mpc() rounds to the working precision
                with mpmath.workdps(dps):
                    return Eigenvalue(mpmath.mpc(0, (lo + hi) / 2), 1, self.digits, (lo, hi))
            extra += max(10, dps // 2)

    def _f(self, omega):
        value = self.ev.delta_mp(mpmath.mpc(0, omega), real=True)
        if value == 0:
            # mpmath.det returns an exact 0 for a matrix singular at the working
            # precision: that is no sign, so look again with more digits
            with mpmath.workdps(2 * mpmath.mp.dps):
                value = self.ev.delta_mp(mpmath.mpc(0, omega), real=True)
        return value

    def _bracket_refine(self, a, b):
        """Anderson–Björck on Delta; None if Delta shows no sign change (precision)."""
        fa, fb = self._f(a), self._f(b)
        if fa == 0:
            return a, a
        if fb == 0:
            return b, b
        if (fa > 0) == (fb > 0):
            return None, None
        tol = mpmath.mpf(10) ** (-(self.digits + 2)) * abs(a)
        return anderson_bjorck(self._f, a, b, fa, fb,
                               lambda lo, hi: bracket_done(lo, hi, self.digits), tol)

    def _verify(self, lo, hi, dps) -> bool:
        """Delta changes sign strictly across [lo, hi] at a higher precision too."""
        if lo == hi:
            with mpmath.workdps(dps):
                eps = mpmath.mpf(10) ** (-(self.digits + 3)) * abs(lo)
                lo, hi = lo - eps, hi + eps
        with mpmath.workdps(dps):
            f_lo, f_hi = self._f(mpmath.mpf(lo)), self._f(mpmath.mpf(hi))
        return f_lo != 0 and f_hi != 0 and (f_lo > 0) != (f_hi > 0)


def solve_undamped(model: Model, count: int | None = None, omega_max=None,
                   digits: int = 15) -> Spectrum:
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

    Returns
    -------
    Spectrum
        Eigenvalues ``lam = i omega``, ascending.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> spec = solve_undamped(pp, count=3, digits=20)
    >>> [str(e) for e in spec]            # (n pi)^2
    ['9.8696044010893586188i', '39.478417604357434475i', '88.826439609804227570i']
    """
    if count is None and omega_max is None:
        raise ValueError("give count or omega_max")
    if digits < 1:
        raise ValueError("digits must be positive")
    model = model.require_numeric()
    if model.damped:
        raise ValueError("model is damped: use the damped solver")
    start = time.perf_counter()
    rigid = rigid_body_modes(model)
    if omega_max is not None:
        hi = float(omega_max)
        if hi < 0:
            raise ValueError("omega_max must not be negative")
        search = _Search(model, digits, max(hi, 1e-300), rigid)
    else:
        hi = _first_guess(model)
        search = _Search(model, digits, hi, rigid)
    check_stable(model, rigid, search.sm)
    if omega_max is None:
        while rigid < count:
            hi, c_hi = search.count_off(hi, 2 * hi)
            if c_hi >= count:
                break
            hi *= 2.0
    eigen = []
    if rigid:
        eigen.append(Eigenvalue(mpmath.mpc(0, 0), rigid, digits, (0.0, 0.0)))
    wanted = None if count is None else count - rigid
    if hi > 0 and (wanted is None or wanted > 0):
        # include a root sitting exactly on omega_max
        top, c_top = search.count_off(hi * (1 + 4e-16), 2 * hi)
        for a, b, k in search.isolate(0.0, rigid, top, c_top, wanted):
            parts = [(a, b, k)] if k == 1 else search.split_cluster(a, b, k)
            for pa, pb, pk in parts:
                if pk == 1:
                    eigen.append(search.refine(pa, pb))
                else:
                    with mpmath.workdps(digits + 2 + SEPARATION_DIGITS + 15):
                        mid = (mpmath.mpf(pa) + mpmath.mpf(pb)) / 2
                        eigen.append(Eigenvalue(mpmath.mpc(0, mid), pk, digits, (pa, pb)))
    eigen.sort(key=lambda e: e.omega)
    if count is not None:
        kept, total = [], 0
        for e in eigen:
            if total >= count:
                break
            kept.append(e)
            total += e.multiplicity
        eigen = kept
    elif omega_max is not None:
        eigen = [e for e in eigen if e.omega <= mpmath.mpf(omega_max) * (1 + mpmath.mpf(4e-16))]
    name, scale = omega_scale(model)
    with mpmath.workdps(digits + 20):
        scale_mp = mpmath.mpf(sp.N(scale, digits + 20)._to_mpmath(mpmath.mp.prec))
    # (+1: the exact R(0) that gave the rigid-body modes)
    return Spectrum(tuple(eigen), digits, "default", search.evaluations + 1,
                    time.perf_counter() - start, model.title or (model.source or ""),
                    (name, scale_mp), _notes(eigen, digits))


def _notes(eigen, digits) -> tuple:
    """What a reader of the printed values should know: roots alike in print, multiples."""
    notes = []
    for i, (e, f) in enumerate(itertools.pairwise(eigen), 1):
        if e.omega != 0 and str(e) == str(f):
            notes.append(f"eigenvalues {i} and {i + 1} are distinct but agree to {digits} "
                         "digits; more digits (--digits) tell them apart")
    if any(e.multiplicity > 1 and e.omega != 0 for e in eigen):
        notes.append(f"a multiplicity m > 1: m eigenvalues agree to {digits + SEPARATION_DIGITS} "
                     "digits (exact multiple roots, or closer than that)")
    return tuple(notes)
