"""Numeric evaluators of ``R(lam)`` and ``Delta(lam) = det R(lam)``.

The evaluator is compiled once per model from its layout
(:class:`symtmm.assembly.Layout`): the exact element parameters are converted
to numbers (double precision, or any mpmath precision), the entries of every
station's jump matrix ``G`` (springs, dashpots, masses, rigid bodies: exact
polynomials in ``lam``) become coefficient arrays, and the transfer product
is then evaluated on just the columns of the unknowns. Cost per evaluation is
linear in the number of cuts.

Three evaluations share that plan: :meth:`Evaluator.R` (numpy, the plain
product), :meth:`Evaluator.log_delta` (numpy, orthonormalised columns: stable
at any mode) and :meth:`Evaluator.R_mp` (mpmath, any precision). Numpy arrays
of complex numbers carry a whole vector of eigenvalues at once, object arrays
of mpmath numbers carry one eigenvalue at any precision.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import sympy as sp

from .assembly import Interval, Layout
from .elements.base import LAM
from .model import Model
from .numeric import to_mp

__all__ = ["Evaluator", "compile_model", "NU_STEP"]

#: Largest ``|beta| l`` of one propagation step of :meth:`Evaluator.log_delta`: the
#: columns grow by at most ``exp(NU_STEP)`` between two re-orthonormalisations.
NU_STEP = 4.0


class _Jumps:
    """The entries ``(row, col, value)`` of a station's ``G``, values as polynomials in lam."""

    def __init__(self, terms):
        self.rows = [r for r, _, _ in terms]
        self.cols = [c for _, c, _ in terms]
        self.coeffs = []        # per term: exact coefficients of lam**0, lam**1, ...
        for _, _, value in terms:
            poly = sp.Poly(sp.expand(value), LAM)
            self.coeffs.append([sp.sympify(c) for c in reversed(poly.all_coeffs())])
        self._float = [[complex(sp.N(c, 20)) for c in cs] for cs in self.coeffs]
        self._mp: dict = {}

    def values_numpy(self, lam) -> list:
        out = []
        for cs in self._float:
            v = np.zeros_like(lam)
            for c in reversed(cs):
                v = v * lam + c
            out.append(v)
        return out

    def values_mp(self, lam, real: bool) -> list:
        key = (mpmath.mp.prec, real)
        coeffs = self._mp.get(key)
        if coeffs is None:
            dps = mpmath.mp.dps
            coeffs = [[to_mp(c, dps) if c.is_real else mpmath.mpmathify(complex(sp.N(c, dps)))
                       for c in cs] for cs in self.coeffs]
            self._mp[key] = coeffs
        out = []
        for cs in coeffs:
            v = mpmath.mpf(0)
            for c in reversed(cs):
                v = v * lam + c
            out.append(mpmath.re(v) if real else v)
        return out


class Evaluator:
    """Evaluates ``R(lam)`` and ``Delta(lam)`` of a model with numeric fields.

    Parameters
    ----------
    model : Model
        All fields must have values (see :meth:`Model.require_numeric`).

    Attributes
    ----------
    evaluations : int
        Number of eigenvalues at which R has been evaluated (one per point).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> ev = Evaluator(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)))
    >>> import numpy as np
    >>> bool(abs(ev.delta(1j * np.pi**2)) < 1e-12)      # first pinned-pinned mode
    True
    >>> import mpmath
    >>> with mpmath.workdps(40):
    ...     abs(ev.delta_mp(mpmath.mpc(0, mpmath.pi**2))) < mpmath.mpf(10)**-38
    True
    """

    def __init__(self, model: Model):
        self.model = model.require_numeric()
        self.layout = Layout(self.model)
        self.n = self.layout.levels
        self.size = self.layout.size
        self.columns = self.layout.columns
        self.rows = self.layout.rows
        self.evaluations = 0
        self._steps = []
        for step in self.layout.steps:
            if isinstance(step, Interval):
                self._steps.append(("segments", list(step.segments)))
            else:
                self._steps.append(("point", _Jumps(step.terms)))
        self._cache: dict = {}
        self.damped = self.model.damped
        # per level: the beam as one segment (its wave number scales the stable
        # propagation and estimates the cancellation), and its EI and length
        self._levels = [(b.segment(b.L), float(b.EI), float(b.L)) for b in self.model.beams]
        self._units = self.layout.units

    # -- constants ------------------------------------------------------------------
    def _float_consts(self, seg) -> tuple:
        key = ("f", id(seg))
        consts = self._cache.get(key)
        if consts is None:
            consts = self._cache[key] = seg.constants()
        return consts

    # -- precision ------------------------------------------------------------------
    def wave_numbers(self, lam) -> np.ndarray:
        """Per beam, a bound on the largest wave number ``|beta|`` at ``lam`` (1/length)."""
        lam2 = np.asarray(lam, dtype=complex) ** 2
        return np.array([seg.wave_number(lam2) for seg, _, _ in self._levels])

    def digits_lost(self, lam) -> float:
        """Estimated decimal digits lost to cancellation in ``Delta`` at ``lam``.

        Entries of a segment matrix grow like ``exp(|beta| l)``; the determinant
        cancels at most about ``sum |beta| L / ln 10`` digits over the beams.
        """
        b = self.wave_numbers(complex(lam))
        return float(sum(bj * L for bj, (_, _, L) in zip(b, self._levels))) / math.log(10)

    # -- numpy ----------------------------------------------------------------------
    def _start(self, N):
        E = np.zeros((N, self.size, len(self.columns)), dtype=complex)
        for j, c in enumerate(self.columns):
            E[:, c, j] = 1.0
        return E

    def R(self, lam) -> np.ndarray:
        """``R(lam)`` for an array of eigenvalues: shape ``lam.shape + (k, k)``.

        The plain product: fine at low modes; at high ones (``sum |beta| L``
        beyond about 20) its determinant loses digits, see :meth:`log_delta`.
        """
        lam = np.asarray(lam, dtype=complex)
        flat = lam.reshape(-1)
        self.evaluations += flat.size
        E = self._start(flat.size)
        lam2 = flat * flat
        cache: dict = {}
        for kind, items in self._steps:
            if kind == "segments":
                for lvl, seg in items:
                    key = self._float_consts(seg)
                    U = cache.get(key)
                    if U is None:          # equal segments share their matrix in a call
                        U = cache[key] = seg.evaluate_numpy(lam2, key)
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    E[:, blk, :] = U @ E[:, blk, :]
            else:
                values = items.values_numpy(flat)
                for row, col, v in zip(items.rows, items.cols, values):
                    E[:, row, :] += v[:, None] * E[:, col, :]
        R = E[:, self.rows, :]
        return R.reshape(lam.shape + R.shape[1:])

    def delta(self, lam) -> np.ndarray:
        """``Delta(lam) = det R(lam)``, vectorised, double precision, stable at high modes.

        Computed as :meth:`log_delta` does; overflows to ``inf`` only where
        ``|Delta|`` itself exceeds the double range (``sum |beta| L`` above about 700).

        Examples
        --------
        >>> from symtmm.model import Beam, Model
        >>> cc = Evaluator(Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),)))
        >>> Om = np.array([30.0, 60.0])               # cos(Om) cosh(Om) - 1, over Om**4
        >>> exact = (1 - np.cos(Om) * np.cosh(Om)) / (2 * Om**4)
        >>> bool(np.all(abs(cc.delta(1j * Om**2) / exact - 1) < 1e-12))
        True
        """
        logabs, phase = self.log_delta(lam)
        return np.exp(logabs + 1j * phase)

    def _units_numpy(self, lam2) -> np.ndarray:
        """Per point and index of the extended state, the unit it is measured in.

        The state of beam ``j`` in units of its wave number ``b``: ``[Y, Theta/b,
        M/(EI b**2), Q/(EI b**3)]``; a body's variables in those of the beam
        they act on. Unscaled, the rows of a high mode differ by powers of ``b``
        and the orthonormal columns would carry ``Y`` and ``Theta`` in their last
        digits.
        """
        N = lam2.size
        per_level = []
        for seg, EI, L in self._levels:
            b = np.maximum(seg.wave_number(lam2), 1.0 / L)
            per_level.append({"Y": np.ones(N), "Theta": 1 / b, "M": 1 / (EI * b**2),
                              "Q": 1 / (EI * b**3)})
        D = np.empty((N, self.size))
        for i, (lvl, var) in enumerate(self._units):
            D[:, i] = per_level[lvl][var]
        return D

    def log_delta(self, lam) -> tuple:
        """``(log|Delta|, arg Delta)`` for an array of eigenvalues, without overflow.

        The columns of the unknowns are propagated as in :meth:`R`, but every
        segment is applied in steps of ``|beta| l <=`` :data:`NU_STEP`, the state
        measured in wave-number units, and the columns re-orthonormalised whenever
        they may have grown by ``exp(NU_STEP)`` since the last time (Godunov's
        method for stiff boundary-value problems): ``E = Q F``
        with ``Q`` orthonormal, so ``Delta = det Q[rows] * prod det F``. Without
        it the columns grow like ``exp(|beta| l)`` and become parallel to working
        precision, and ``det R`` loses about ``sum |beta| L / ln 10`` digits (all
        of them by ``beta L = 36``); with it the value keeps about 13
        significant digits away from the eigenvalues at any mode.
        """
        lam = np.asarray(lam, dtype=complex)
        flat = lam.reshape(-1)
        self.evaluations += flat.size
        logabs = np.empty(flat.size)
        phase = np.empty(flat.size)
        # Points are propagated together only when they take the same steps: a batch
        # stepped for its highest mode would cost its low modes digits.
        steps = self._step_counts(flat * flat)
        groups = {}
        for i, key in enumerate(map(tuple, steps)):
            groups.setdefault(key, []).append(i)
        for key, idx in groups.items():
            idx = np.array(idx)
            logabs[idx], phase[idx] = self._log_delta(flat[idx], key)
        return logabs.reshape(lam.shape), phase.reshape(lam.shape)

    def _step_counts(self, lam2) -> np.ndarray:
        """Per point, the number of steps of ``|beta| l <= NU_STEP`` of every interval."""
        out = np.ones((lam2.size, sum(k == "segments" for k, _ in self._steps)), dtype=int)
        col = 0
        for kind, items in self._steps:
            if kind != "segments":
                continue
            for _, seg in items:
                consts = self._float_consts(seg)
                nu = seg.wave_number(lam2, consts) * float(consts[2])
                out[:, col] = np.maximum(out[:, col], np.ceil(nu / NU_STEP).astype(int))
            col += 1
        return out

    def _log_delta(self, flat, steps) -> tuple:
        """:meth:`log_delta` of points that take the same ``steps`` in every interval."""
        N = flat.size
        lam2 = flat * flat
        D = self._units_numpy(lam2)
        E = self._start(N)
        # E holds D * (true columns) / D[columns]: det R = det E[rows] * prod D[cols] / prod D[rows]
        logabs = np.sum(np.log(D[:, self.columns]), axis=-1) - np.sum(np.log(D[:, self.rows]),
                                                                       axis=-1)
        phase = np.zeros(N)
        cache: dict = {}

        def orthonormalise(E):
            Q, F = np.linalg.qr(E)
            diag = np.diagonal(F, axis1=-2, axis2=-1)
            logabs[:] += np.sum(np.log(np.abs(diag)), axis=-1)
            phase[:] += np.sum(np.angle(diag), axis=-1)
            return Q

        interval = 0
        grown = 0.0        # sum of |beta| l applied since the columns were last orthonormal
        for kind, items in self._steps:
            if kind == "segments":
                n_sub = int(steps[interval])
                interval += 1
                plans = [(lvl, seg, self._float_consts(seg)) for lvl, seg in items]
                nu = max((float(np.max(seg.wave_number(lam2, c), initial=0.0)) * float(c[2])
                          for _, seg, c in plans), default=0.0) / n_sub
                subs = []
                for lvl, seg, consts in plans:
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    key = (consts, n_sub)
                    U = cache.get(key)
                    if U is None:          # equal segments share their matrix in a call
                        U = cache[key] = seg.evaluate_numpy(lam2, consts,
                                                            l=float(consts[2]) / n_sub)
                    subs.append((blk, U * (D[:, blk, None] / D[:, None, blk])))
                for _ in range(n_sub):
                    # orthonormalise only once the columns may have grown by exp(NU_STEP)
                    if grown + nu > NU_STEP:
                        E = orthonormalise(E)
                        grown = 0.0
                    for blk, U in subs:
                        E[:, blk, :] = U @ E[:, blk, :]
                    grown += nu
            else:
                values = items.values_numpy(flat)
                for row, col, v in zip(items.rows, items.cols, values):
                    E[:, row, :] += (v * D[:, row] / D[:, col])[:, None] * E[:, col, :]
        if len(self.columns):
            det = np.linalg.det(E[:, self.rows, :])
            with np.errstate(divide="ignore"):
                logabs = logabs + np.log(np.abs(det))
            phase = phase + np.angle(det)
        return logabs, np.angle(np.exp(1j * phase))

    # -- mpmath ---------------------------------------------------------------------
    def R_mp(self, lam, real: bool = False) -> mpmath.matrix:
        """``R(lam)`` at one eigenvalue, at the current mpmath working precision.

        With ``real=True`` (undamped model, ``lam = i omega``) the arithmetic is
        done in real numbers, which is exact there and twice as fast.
        """
        self.evaluations += 1
        lam = mpmath.mpmathify(lam)
        if real:
            if self.damped:
                raise ValueError("real arithmetic needs an undamped model")
            lam2 = -(lam.imag ** 2) if isinstance(lam, mpmath.mpc) else lam * lam
            lam2 = mpmath.mpf(lam2)
        else:
            lam2 = lam * lam
        zero, one = mpmath.mpf(0), mpmath.mpf(1)
        E = np.full((self.size, len(self.columns)), zero, dtype=object)
        for j, c in enumerate(self.columns):
            E[c, j] = one
        for kind, items in self._steps:
            if kind == "segments":
                for lvl, seg in items:
                    U = seg.evaluate_mp(lam2, seg.mp_constants())
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    E[blk, :] = U.dot(E[blk, :])
            else:
                values = items.values_mp(lam, real)
                for row, col, v in zip(items.rows, items.cols, values):
                    E[row, :] = E[row, :] + v * E[col, :]
        return mpmath.matrix(E[self.rows, :].tolist())

    def delta_mp(self, lam, real: bool = False):
        """``Delta(lam)`` at the current mpmath working precision.

        ``mpmath.det`` returns 0 for a matrix it finds singular, except when a
        whole pivot column is exactly zero (mirrored beams at an eigenvalue cancel
        exactly): its pivot search then raises ``TypeError``. That is the same
        verdict, 0; callers read an exact 0 as "no sign here, look again with
        more digits".
        """
        R = self.R_mp(lam, real)
        if R.rows == 0:
            return mpmath.mpf(1)
        try:
            return mpmath.det(R)
        except TypeError:
            return mpmath.mpf(0)

    def nullity_at_zero(self, dps: int = 60) -> int:
        """Dimension of the null space of ``R(0)``, decided at two precisions.

        For models whose exact ``R(0)`` is transcendental (a Winkler
        foundation, an axial force): a singular value that is zero shrinks with
        the precision (below ``10**(-dps/2)`` of the largest at ``dps`` and
        ``2 dps`` digits), a non-zero one does not.

        Examples
        --------
        >>> from symtmm.model import Beam, Model
        >>> ff = Beam("b", EI=1, m=1, L=1, left="free", right="free")
        >>> Evaluator(Model((ff,))).nullity_at_zero()
        2
        >>> from dataclasses import replace
        >>> Evaluator(Model((replace(ff, kw=3),))).nullity_at_zero()
        0
        """
        counts = []
        for d in (dps, 2 * dps):
            with mpmath.workdps(d):
                R = self.R_mp(mpmath.mpf(0), real=not self.damped)
                if R.rows == 0:
                    return 0
                s = mpmath.svd_r(R, compute_uv=False) if not self.damped else \
                    mpmath.svd_c(R, compute_uv=False)
                top = max(abs(v) for v in s)
                if top == 0:
                    counts.append(R.rows)
                    continue
                counts.append(sum(1 for v in s if abs(v) < top * mpmath.mpf(10) ** (-d / 2)))
        if counts[0] != counts[1]:
            raise ArithmeticError("the rank of R(0) is not decided at "
                                  f"{dps} and {2 * dps} digits")
        return counts[0]

    def delta_omega_mp(self, omega):
        """``Delta(i omega)`` of an undamped model, real, at the working precision."""
        return self.delta_mp(mpmath.mpc(0, omega), real=True)


def compile_model(model: Model) -> Evaluator:
    """Compile ``model`` into an :class:`Evaluator` (convenience alias)."""
    return Evaluator(model)

