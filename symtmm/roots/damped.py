"""Eigenvalues of damped models in a rectangle of the complex plane, none missed.

Eigenvalues ``lam = -sigma + i omega`` are the zeros of the entire function
``Delta(lam) = det R(lam)``. They come in conjugate pairs; those with
``Im lam >= 0`` are reported. The search region is

    -sigma_max <= Re lam <= 0,   0 <= Im lam <= omega_max,

``sigma_max`` defaulting to ``2 * omega_max`` (:data:`SIGMA_FACTOR`).

1. **Count.** The number of zeros in a rectangle is the change of
   ``arg Delta`` around it over ``2 pi`` (:mod:`symtmm.roots.contour`).
   ``Delta`` is evaluated in double precision without cancellation as
   ``det K * prod det U12`` (:mod:`symtmm.roots.dynamic_stiffness`); points
   where that product is ill-conditioned (very close to a zero) are
   re-evaluated with the transfer-matrix ``Delta`` in mpmath, at
   ``digits_lost + 20`` and ``+ 30`` digits, and kept only if both agree.
   The region is enlarged slightly beyond ``Re lam = 0`` (no eigenvalue of
   a passive model lies to the right of the imaginary axis, so undamped
   modes are strictly inside), and its lower part is a rectangle symmetric
   about the real axis, so that real (overdamped) eigenvalues lie strictly
   inside too; only its upper half is sampled (``Delta`` is real on the
   real axis).
2. **Isolate.** Rectangles are halved (quadtree) until each holds at most
   one zero; the counts of the halves must add up to the count of the
   whole. A symmetric rectangle holding one zero holds a real one (a
   non-real zero would bring its conjugate).
3. **Refine** in mpmath on the transfer-matrix ``Delta``: a real zero by
   the Anderson–Björck bracketing method on the real axis, a complex one by
   the secant method from the centre of the zero estimated from the contour
   samples, at ``D + digits_lost + 10`` digits plus what a small real or
   imaginary part needs. The zero must stay in its rectangle, and a second
   refinement 15 digits higher must agree to ``D + 2`` digits in each part;
   if a part lies so close to a rounding boundary that the two ends of its
   error bound print differently at ``D`` digits, more digits are computed
   (up to 30 more), so the printed digits are correctly rounded. A real
   zero's bracket is narrowed the same way.
4. **Undamped modes of damped models** (e.g. beams moving in phase, their
   dashpots idle) have ``Re lam = 0`` exactly; numerically the real part
   comes out as rounding noise. When it is below ``10**-(D+25) |lam|`` and
   the same ``lam`` is, to that accuracy, also an eigenvalue of the model
   with every dashpot removed and of the model with every dashpot doubled
   (the mode does not move the dashpots, so it dissipates nothing), the
   real part is reported as exactly ``0`` and a note says so. This is a
   numerical identification, not a proof.
5. **Multiple zeros.** A rectangle that still holds ``m >= 2`` zeros when it
   is too small for double precision is handed to mpmath: the modified
   Newton method ``z - m Delta/Delta'`` finds the cluster, and a count on a
   square of half-width ``10**-(D + 2 + SEPARATION_DIGITS) |lam|`` around it
   decides between one zero of multiplicity ``m`` (its ``m`` zeros agree to
   ``D + SEPARATION_DIGITS`` digits) and distinct zeros, separated by the same
   quadtree in mpmath and refined one by one, however close.
"""

from __future__ import annotations

import math
import time
from dataclasses import replace

import mpmath
import numpy as np
import sympy as sp

from ..compile import Evaluator
from ..errors import ComputationError
from ..model import Model
from ..results import Eigenvalue, Spectrum, decimal_string
from .bracket import SEPARATION_DIGITS, anderson_bjorck, bracket_done
from .contour import ArgumentPrinciple, CountError, NearZero, Rectangle
from .dynamic_stiffness import DynamicStiffness
from .undamped import _first_guess, check_stable, omega_scale, rigid_body_modes

__all__ = ["SIGMA_FACTOR", "count_in_rectangle", "default_sigma_max", "solve_damped"]

#: ``sigma_max`` defaults to this multiple of ``omega_max``.
SIGMA_FACTOR = 2
#: Largest working precision (decimal digits).
MAX_DPS = 1500
#: A rectangle smaller than this (relative to |lam|) that still holds several zeros is
#: left to mpmath: double precision cannot split it reliably.
_TINY = 1e-6
#: Split positions tried in turn when a split line passes too close to a zero.
_SPLITS = (0.5, 0.4427, 0.5573, 0.3711, 0.6289, 0.3019, 0.6981)
#: Guard digits above the estimated loss.
_GUARD = 10


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


def _scaled_dashpots(model: Model, factor) -> Model:
    """The same model with every dashpot coefficient multiplied by ``factor``."""
    springs = tuple(replace(s, c=s.c * factor) for s in model.springs)
    return replace(model, springs=springs)


def _rounds_alike(x, err, digits) -> bool:
    """``x - err`` and ``x + err`` print alike with ``digits`` digits (0 always does)."""
    if x == 0:
        return True
    return decimal_string(x - err, digits) == decimal_string(x + err, digits)


def _mpc(z) -> mpmath.mpc:
    return mpmath.mpc(complex(z).real, complex(z).imag)


class _Problem:
    """The function of one model, in double precision and in mpmath, with counters."""

    def __init__(self, model: Model, lam_max: float):
        self.model = model
        self.ev = Evaluator(model)
        self.ds = DynamicStiffness(model, lam_max)
        # per beam, what its wave number at |lam| comes from: (m/EI) for a plain beam,
        # else the segment (Rayleigh, Timoshenko, axial force)
        self.waves = [(None if b.plain else b.segment(b.L), float(b.m) / float(b.EI),
                       float(b.L)) for b in model.beams]
        self.lam_ref = _reference_frequency(model)
        self.extra = 0   # evaluations of auxiliary models
        self.mp_fallbacks = 0

    @property
    def evaluations(self) -> int:
        return self.ds.evaluations + self.ev.evaluations + self.extra

    def lost(self, z) -> float:
        return self.ev.digits_lost(complex(z))

    def spacing(self, z) -> float:
        a = max(abs(z), self.lam_ref)
        total = 0.0
        for seg, mu, L in self.waves:
            k = (mu * a * a) ** 0.25 if seg is None else float(np.max(seg.wave_number(-a * a)))
            total += k * L
        return 0.3 * a / (1.0 + total)

    def min_step(self, z) -> float:
        return 1e-10 * max(abs(z), self.lam_ref)

    # -- log Delta for the contour, double precision with an mpmath fallback --------------
    def log_delta(self, z):
        logabs, phase, ok = self.ds.log_delta(z)
        for i in np.nonzero(~ok)[0]:
            value = self.log_delta_mp(complex(z[i]))
            if value is not None:
                logabs[i], phase[i] = value
                ok[i] = True
        return logabs, phase, ok

    def log_delta_mp(self, z, extra_digits: int = 20, origin=None, check: bool = True):
        """``(log|Delta|, arg Delta)`` at ``origin + z`` in mpmath.

        With ``check``, also 10 digits higher, and None if the two disagree;
        without, the caller vouches that ``extra_digits`` suffice.
        """
        self.mp_fallbacks += 1
        base = math.ceil(self.lost(z if origin is None else complex(origin) + z)) + extra_digits
        values = []
        for dps in (base, base + 10)[:2 if check else 1]:
            with mpmath.workdps(dps):
                d = self.ev.delta_mp(_mpc(z) if origin is None else origin + _mpc(z))
                if d == 0:
                    return None
                values.append((float(mpmath.log(abs(d))), float(mpmath.arg(d))))
        if not check:
            return values[0]
        (la1, ph1), (la2, ph2) = values
        dph = abs(math.remainder(ph1 - ph2, 2 * math.pi))
        if abs(la1 - la2) < 1e-6 and dph < 1e-6:
            return values[1]
        return None

    def delta_mp(self, z):
        return self.ev.delta_mp(z)


class _MPFunction:
    """``log Delta(origin + u)`` evaluated only in mpmath, for local coordinates ``u``."""

    def __init__(self, problem: _Problem, extra_digits: int, origin=None, check=True):
        self.problem = problem
        self.extra_digits = extra_digits
        self.origin = origin
        self.check = check

    def __call__(self, u):
        u = np.atleast_1d(u)
        logabs = np.zeros(u.shape)
        phase = np.zeros(u.shape)
        ok = np.zeros(u.shape, dtype=bool)
        for i, ui in enumerate(u):
            value = self.problem.log_delta_mp(complex(ui), self.extra_digits, self.origin,
                                              self.check)
            if value is not None:
                logabs[i], phase[i] = value
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
        self.notes: list = []
        self.idle = 0
        self.zero_order = 0   # > 0: lam = 0 is known to be a multiple zero (rigid-body modes)

    def _global(self, u) -> mpmath.mpc:
        """The point ``origin + u`` at the working precision."""
        u = _mpc(u) if not isinstance(u, mpmath.mpc) else u
        return u if self.origin is None else self.origin + u

    def _local(self, z) -> complex:
        return complex(z if self.origin is None else z - self.origin)

    def _scale(self, u) -> float:
        with mpmath.workdps(20):
            return max(float(abs(self._global(u))), self.p.lam_ref)

    # -- counting -----------------------------------------------------------------------
    def _split(self, rect, count):
        """Children ``[(rect, count, center, weight)]`` of ``rect``; weight 2 = mirrored."""
        last_error = None
        for strictness in (0, 1, 2):
            for s in _SPLITS:
                try:
                    kids = self._children(rect, s)
                    counted = []
                    for kid, weight in kids:
                        n, center = self.ap.count_and_center(kid, strictness)
                        counted.append((kid, n, center, weight))
                except NearZero as exc:
                    last_error = exc
                    continue
                total = sum(n * w for _, n, _, w in counted)
                if total == count:
                    return counted
                last_error = CountError(f"counts {[n for _, n, _, _ in counted]} of the parts "
                                        f"of {rect} do not add up to {count}")
                break   # same split, stricter sampling
        raise ComputationError(f"cannot split the search rectangle {rect}: {last_error}")

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

    def isolate(self, cells, tiny):
        """Rectangles holding one zero, and those smaller than ``tiny`` holding several.

        ``cells``: ``[(rect, count, center)]``; ``tiny`` is relative to ``|lam|``.
        Returns ``(singles, clusters)``.
        """
        singles, clusters = [], []
        work = list(cells)
        guard = 0
        while work:
            rect, n, center = work.pop()
            guard += 1
            if guard > 20000:
                raise ComputationError("too many rectangles: the zeros could not be isolated")
            if n == 0:
                continue
            if n == 1:
                singles.append((rect, center))
                continue
            if rect.size < tiny * self._scale(rect.center) or (
                    self.zero_order and rect.symmetric and rect.size < 1e-3 * self.p.lam_ref
                    and rect.contains(self._local(mpmath.mpf(0)))):
                # (lam = 0 is a known multiple zero when there are rigid-body modes: double
                # precision is not asked to approach it closely)
                clusters.append((rect, n, center))
                continue
            for kid, k, c, _ in self._split(rect, n):
                work.append((kid, k, c))
        return singles, clusters

    # -- precision ------------------------------------------------------------------------
    def _dps(self, z, small_part=None) -> int:
        z = complex(z)
        extra = 0
        if small_part is not None and small_part > 0:
            extra = max(0, math.ceil(math.log10(abs(z) / small_part)))
        return self.digits + math.ceil(self.p.lost(z)) + _GUARD + extra

    # -- real zeros ---------------------------------------------------------------------
    def refine_real(self, rect: Rectangle) -> Eigenvalue:
        """The single real zero in a symmetric rectangle, by bracketing on the real axis."""
        with mpmath.workdps(40):
            scale = float(max(abs(self._global(rect.x0)), abs(self._global(rect.x1))))
        dps = self._dps(scale) + 5
        while dps <= MAX_DPS:
            with mpmath.workdps(dps):
                a, b = self._global(rect.x0).real, self._global(rect.x1).real
                lo, hi = self._shrink(a, b)
            bracket = None if lo is None else self._sign_change(lo, hi, dps + 15)
            if bracket is not None:
                with mpmath.workdps(dps):
                    lam = mpmath.mpc((lo + hi) / 2, 0)
                return Eigenvalue(lam, 1, self.digits, bracket)
            dps += max(10, dps // 2)
        raise ComputationError(f"cannot reach {self.digits} digits for the real eigenvalue "
                               f"near {scale:.6g}")

    def _re_delta(self, x):
        return mpmath.re(self.p.delta_mp(mpmath.mpc(x, 0)))

    def _shrink(self, a, b):
        fa, fb = self._re_delta(a), self._re_delta(b)
        if fa == 0:
            return a, a
        if fb == 0:
            return b, b
        if (fa > 0) == (fb > 0):
            return None, None
        tol = mpmath.mpf(10) ** (-(self.digits + 2)) * min(abs(a), abs(b))
        return anderson_bjorck(self._re_delta, a, b, fa, fb,
                               lambda lo, hi: bracket_done(lo, hi, self.digits, self.p.lam_ref),
                               tol if tol > 0 else None)

    def _sign_change(self, lo, hi, dps):
        """``(lo, hi)`` if ``Re Delta`` changes sign strictly across it at ``dps`` digits.

        A zero-width bracket (``Delta`` vanished to the working precision) is widened by
        ``10**-(D+3)`` relative first.
        """
        with mpmath.workdps(dps):
            if lo == hi:
                eps = mpmath.mpf(10) ** (-(self.digits + 3)) * abs(lo)
                lo, hi = lo - eps, hi + eps
            f_lo, f_hi = self._re_delta(mpmath.mpf(lo)), self._re_delta(mpmath.mpf(hi))
        # strict: mpmath.det returns an exact 0 for a matrix singular to the working
        # precision, which proves nothing (the caller then raises the precision)
        if (f_lo > 0 and f_hi < 0) or (f_lo < 0 and f_hi > 0):
            return lo, hi
        return None

    def _secant(self, f, z0, tol, maxsteps=80, multiplicity=1):
        """Secant iteration (``multiplicity`` 1) or modified Newton from ``z0``.

        Returns ``(z, last_step)`` or ``(None, None)`` when it does not converge.
        """
        if multiplicity > 1:
            return self._newton_multiple(f, z0, tol, multiplicity, maxsteps)
        z0 = mpmath.mpc(z0)
        h = max(abs(z0), mpmath.mpf(1)) * mpmath.mpf(10) ** (-(self.digits // 2 + 4))
        z1 = z0 + h * mpmath.mpc(1, 1)
        f0, f1 = f(z0), f(z1)
        for _ in range(maxsteps):
            if f1 == 0:
                return z1, mpmath.mpf(0)
            if f1 == f0:
                return None, None
            z2 = z1 - f1 * (z1 - z0) / (f1 - f0)
            step = abs(z2 - z1)
            if not mpmath.isfinite(step):
                return None, None
            if step <= tol:
                return z2, step
            z0, f0 = z1, f1
            z1, f1 = z2, f(z2)
        return None, None

    def _newton_multiple(self, f, z, tol, m, maxsteps):
        """Newton on ``f**(1/m)``: ``z - m f/f'``, quadratic at an ``m``-fold zero.

        ``f'`` is a forward difference with a step of half the working digits.
        """
        z = mpmath.mpc(z)
        for _ in range(maxsteps):
            h = max(abs(z), mpmath.mpf(self.p.lam_ref)) * mpmath.mpf(10) ** (-(mpmath.mp.dps // 2))
            f0 = f(z)
            if f0 == 0:
                return z, mpmath.mpf(0)
            deriv = (f(z + h) - f0) / h
            if deriv == 0:
                return None, None
            step = m * f0 / deriv
            z = z - step
            if not mpmath.isfinite(abs(step)):
                return None, None
            if abs(step) <= tol:
                return z, abs(step)
        return None, None

    def refine_complex(self, rect: Rectangle, center) -> Eigenvalue | None:
        """The single zero in ``rect`` (above the real axis); None if the secant strays."""
        u = complex(center) if center is not None and rect.contains(center) else rect.center
        with mpmath.workdps(self.digits + 40):
            z_est = self._global(u)
        zf = complex(z_est)
        small = min(abs(zf.real), abs(zf.imag)) or None
        margin = 1e-9 * rect.size
        extra = 0      # digits added when a part needs more
        tighter = 0    # digits added when a part sits near a rounding boundary
        conservative = not self.p.model.damped
        while True:
            dps = self._dps(zf, small) + extra + tighter
            if dps > MAX_DPS:
                raise ComputationError(f"cannot reach {self.digits} digits for the eigenvalue "
                                       f"near {zf:.6g} within {MAX_DPS} working digits")
            with mpmath.workdps(dps):
                target = min(abs(zf.real) or abs(zf), abs(zf.imag) or abs(zf))
                if conservative:
                    target = abs(zf.imag) or abs(zf)
                tol = mpmath.mpf(10) ** (-(self.digits + 4 + tighter)) * mpmath.mpf(target)
                za, _ = self._secant(self.p.delta_mp, +z_est, tol)
                if za is None or not rect.contains(self._local(za), margin):
                    return None
            with mpmath.workdps(dps + 15):
                zb, _ = self._secant(self.p.delta_mp, za, tol / 10 ** 5)
                if zb is None or not rect.contains(self._local(zb), margin):
                    return None
                size = abs(zb)
                re_b, im_b = abs(zb.real), abs(zb.imag)
                err = abs(za - zb)     # bounds the error of za; zb is far better
                rel = mpmath.mpf(10) ** (-(self.digits + 2))
                ok_re, ok_im = err <= rel * re_b, err <= rel * im_b
                if conservative:
                    # no dashpot: a conservative model, every eigenvalue is imaginary
                    zb = mpmath.mpc(0, zb.imag)
                    ok_re = True
                if ok_re and ok_im:
                    if tighter >= 30 or all(_rounds_alike(part, err, self.digits)
                                            for part in (zb.real, zb.imag)):
                        return Eigenvalue(+zb, 1, self.digits, None)
                    tighter += 10    # too close to a rounding boundary to tell yet
                    z_est, zf = zb, complex(zb)
                    continue
                floor = mpmath.mpf(10) ** (-(self.digits + 25)) * size
                if ok_im and re_b < floor and self._idle(zb, dps + 15, 1):
                    # the real part is rounding noise and the dashpots stay idle
                    self.idle += 1
                    return Eigenvalue(mpmath.mpc(0, zb.imag), 1, self.digits, None)
                # the smaller part needs more digits: aim at it
                new_small = float(max(min(re_b, im_b), floor / 10 ** 5))
            if small is None or new_small < small:
                small = new_small
            else:
                extra += 20
            z_est, zf = zb, complex(zb)

    def _idle(self, z, dps, m) -> bool:
        """``z`` is also an ``m``-fold zero of the model without and with doubled dashpots."""
        tol = mpmath.mpf(10) ** (-(self.digits + (20 if m == 1 else 2))) * abs(z)
        for factor in (0, 2):
            ev = Evaluator(_scaled_dashpots(self.p.model, factor))
            with mpmath.workdps(dps):
                zt, _ = self._secant(ev.delta_mp, z, tol / 10 ** 5,
                                     maxsteps=40, multiplicity=m)
            self.p.extra += ev.evaluations
            if zt is None or abs(zt - z) > tol:
                return False
        return True

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
        zf = complex(self._global(u))
        dps = m * res + math.ceil(self.p.lost(zf)) + _GUARD + 10
        extra = (m + 1) * res + 10
        with mpmath.workdps(dps):
            z0 = self._global(u)
            tol = mpmath.mpf(10) ** (-(res + 4)) * max(abs(z0), self.p.lam_ref)
            z, _ = self._secant(self.p.delta_mp, z0, tol, multiplicity=m)
            if rect.symmetric and z is not None:
                z = mpmath.mpc(z.real, 0)   # the cluster is closed under conjugation
        if z is not None and rect.contains(self._local(z), 1e-9 * rect.size):
            scale = max(abs(zf), self.p.lam_ref)
            r = 10.0 ** (-res) * scale
            zc = complex(z)
            for part in (zc.real, zc.imag):
                if abs(part) > 10.0 ** (-res) * scale:
                    r = min(r, 10.0 ** (-res) * abs(part))
            box = (Rectangle(-r, r, -r, r, True) if rect.symmetric
                   else Rectangle(-r, r, -r, r))
            # |Delta| ~ r**m on the box: m res digits above the loss carry its phase
            ap = ArgumentPrinciple(_MPFunction(self.p, extra, z, check=False),
                                   spacing=lambda _u: r, min_step=lambda _u: r * 1e-6)
            try:
                k = ap.count(box)
            except (NearZero, CountError):
                k = -1
            if k == m:
                return [self._cluster_eigenvalue(z, m, rect.symmetric, dps, r)]
        # the cluster separates: isolate its zeros with mpmath, around a local origin
        with mpmath.workdps(dps):
            origin = self._global(rect.center)
            if rect.symmetric:
                origin = mpmath.mpc(origin.real, 0)
            shift = self._local(origin)
        local = Rectangle(rect.x0 - shift.real, rect.x1 - shift.real,
                          rect.y0 if rect.symmetric else rect.y0 - shift.imag,
                          rect.y1 if rect.symmetric else rect.y1 - shift.imag, rect.symmetric)
        sub = _Search(self.p, self.digits,
                      ArgumentPrinciple(_MPFunction(self.p, extra, origin),
                                        spacing=lambda _u: local.size / 8,
                                        min_step=lambda _u: 1e-6 * r_min),
                      origin)
        r_min = 10.0 ** (-res) * abs(zf)
        singles, clusters = sub.isolate([(local, m, None)], 10.0 ** -res)
        out = [sub.single(r, c) for r, c in singles]
        for r, k, _ in clusters:
            with mpmath.workdps(dps):
                out.append(sub._cluster_eigenvalue(sub._global(r.center), k, r.symmetric, dps,
                                                   r.size))
        self.idle += sub.idle
        return out

    def _cluster_eigenvalue(self, z, m, symmetric, dps, radius) -> Eigenvalue:
        """An ``m``-fold eigenvalue at ``z``, known to within ``radius``."""
        with mpmath.workdps(dps):
            if not self.p.model.damped:
                return Eigenvalue(mpmath.mpc(0, abs(z.imag)), m, self.digits, None)
            if symmetric and abs(z.imag) <= radius:
                return Eigenvalue(mpmath.mpc(z.real, 0), m, self.digits, None)
            if abs(z.real) <= radius:
                if self._idle(z, dps, m):
                    self.idle += 1
                    return Eigenvalue(mpmath.mpc(0, z.imag), m, self.digits, None)
                raise ComputationError(
                    f"{m} eigenvalues agree to {self.digits + SEPARATION_DIGITS} digits near "
                    f"{complex(z):.6g} and their real part, below {float(radius):.1e}, cannot "
                    "be given to the digits asked for")
            return Eigenvalue(+z, m, self.digits, None)

    def single(self, rect, center) -> Eigenvalue:
        """Refine one isolated zero, halving its rectangle while the secant strays."""
        for _ in range(60):
            if rect.symmetric:
                return self.refine_real(rect)
            e = self.refine_complex(rect, center)
            if e is not None:
                return e
            for kid, k, c, _ in self._split(rect, 1):
                if k:
                    rect, center = kid, c
                    break
        raise ComputationError(f"the eigenvalue in {rect} could not be refined")


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


def _search_region(model, omega_max, sigma_max, digits):
    """``(search, counted cells, evaluations spent on attempts given up)``."""
    lam_ref = _reference_frequency(model)
    last = None
    spent = 0
    for attempt in range(5):
        rects = _region(omega_max, sigma_max, lam_ref, attempt)
        lam_max = 1.05 * max(abs(complex(x, y)) for r in rects for x in (r.x0, r.x1)
                             for y in (r.y0, r.y1))
        problem = _Problem(model, lam_max)
        search = _Search(problem, digits)
        try:
            return search, _count_region(search, rects), spent
        except (NearZero, CountError) as exc:
            last = exc
            spent += problem.evaluations
    raise ComputationError(f"the boundary of the search region keeps meeting eigenvalues: {last}")


def solve_damped(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
                 digits: int = 15) -> Spectrum:
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
    if count is None and omega_max is None:
        raise ValueError("give count or omega_max")
    if digits < 1:
        raise ValueError("digits must be positive")
    model = model.require_numeric()
    start = time.perf_counter()
    rigid = rigid_body_modes(model)
    evaluations = check_stable(model, rigid)
    if omega_max is not None:
        W = float(omega_max)
        S = default_sigma_max(W) if sigma_max is None else float(sigma_max)
        if W < 0 or S < 0:
            raise ValueError("omega_max and sigma_max must not be negative")
        search, cells, spent = _search_region(model, W, S, digits)
        evaluations += spent
    else:
        W = _first_guess(model)
        while True:
            S = default_sigma_max(W) if sigma_max is None else float(sigma_max)
            search, cells, spent = _search_region(model, W, S, digits)
            evaluations += spent
            # the symmetric strip counts conjugate pairs twice: at least half are above
            found = sum(n if not r.symmetric else (n + 1) // 2 for r, n, _ in cells)
            if found >= count:
                break
            evaluations += search.p.evaluations
            W *= 2.0
            if W > 1e12:
                raise ComputationError(f"fewer than {count} eigenvalues below |lam| = 1e12")
    search.zero_order = rigid
    singles, clusters = search.isolate(cells, _TINY)
    eigen = [search.single(rect, center) for rect, center in singles]
    for rect, m, center in clusters:
        eigen += search.resolve_cluster(rect, m, center)
    eigen = [e for e in eigen if e.lam.imag >= 0]
    total = sum(e.multiplicity for e in eigen)
    notes = []
    if rigid:
        # Delta(0) = 0 exactly; the zeros found within the accuracy of 0 are that zero
        near = [e for e in eigen if abs(e.lam) <= 10.0 ** -(digits + 1) * search.p.lam_ref]
        if not near:
            raise ComputationError("the rigid-body eigenvalue lam = 0 was not found")
        order = sum(e.multiplicity for e in near)
        eigen = [e for e in eigen if e not in near]
        eigen.append(Eigenvalue(mpmath.mpc(0, 0), rigid, digits, (0.0, 0.0)))
        notes.append(f"lam = 0: {rigid} rigid-body mode(s), a zero of order {order} of Delta")
    for e in eigen:
        if e.lam.real > 0:
            raise ComputationError(f"eigenvalue {e} has a positive real part: the model is "
                                   "not passive?")
    # keep the region asked for
    tol = 4e-16
    eigen = [e for e in eigen if e.lam.real >= -S * (1 + tol) - tol
             and e.lam.imag <= W * (1 + tol) + tol]
    eigen.sort(key=lambda e: (e.lam.imag, e.lam.real))
    if count is not None:
        kept, n = [], 0
        for e in eigen:
            if n >= count:
                break
            kept.append(e)
            n += e.multiplicity
        eigen = kept
    notes.insert(0, f"search region: {-S:.6g} <= Re lam <= 0, 0 <= Im lam <= {W:.6g} "
                    f"({total} eigenvalue(s) with Im lam >= 0 counted in the enlarged region)")
    if search.idle:
        notes.append(f"Re lam = 0 for {search.idle} eigenvalue(s): also eigenvalues of the "
                     f"model without dashpots and with doubled dashpots to "
                     f"{digits + 20} digits (modes that do not move the dashpots)")
    evaluations += search.p.evaluations
    name, scale = omega_scale(model)
    with mpmath.workdps(digits + 20):
        scale_mp = mpmath.mpf(sp.N(scale, digits + 20)._to_mpmath(mpmath.mp.prec))
    return Spectrum(tuple(eigen), digits, "default", evaluations, time.perf_counter() - start,
                    model.title or (model.source or ""), (name, scale_mp), tuple(notes))
