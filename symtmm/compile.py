"""Numeric evaluators of ``R(lam)`` and ``Delta(lam) = det R(lam)``.

The evaluator is compiled once per model from its layout: the exact element
parameters are converted to numbers (double precision, or any mpmath
precision), the point-element stiffnesses are lambdified once, and the
transfer product is then evaluated on just the ``2 n`` columns of the unknown
left-end variables. Cost per evaluation is linear in the number of cuts.

Both backends share one propagation routine; numpy arrays of complex numbers
carry a whole vector of eigenvalues at once, object arrays of mpmath numbers
carry one eigenvalue at any precision.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import mpmath
import numpy as np
import sympy as sp

from .assembly import Interval, Layout
from .elements import STATE
from .elements.base import CONJUGATE, LAM
from .model import Model
from .numeric import to_mp

__all__ = ["Evaluator", "compile_model", "NU_STEP"]

#: Largest ``|beta| l`` of one propagation step of :meth:`Evaluator.log_delta`: the
#: columns grow by at most ``exp(NU_STEP)`` between two re-orthonormalisations.
NU_STEP = 4.0


@dataclass
class _PointPlan:
    rows_disp: list   # stacked rows of the displacement variables
    rows_force: list  # stacked rows of the conjugate forces
    signs: list       # sign of each force jump
    stiffness_np: object  # lam -> d x d (numpy)
    stiffness_mp: object  # lam -> d x d (mpmath)


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
        self.columns = self.layout.columns
        self.rows = self.layout.rows
        self.evaluations = 0
        self._steps = []
        for step in self.layout.steps:
            if isinstance(step, Interval):
                self._steps.append(("segments", [(lvl, seg) for lvl, seg in step.segments]))
            else:
                self._steps.append(("point", [self._plan_point(e, lv) for e, lv in step.elements]))
        self._mp_cache: dict = {}
        self.damped = self.model.damped
        # per-beam factors m/EI, length and kw/EI, for the precision estimate
        self._beam_consts = [(float(b.m) / float(b.EI), float(b.L), float(b.kw) / float(b.EI))
                             for b in self.model.beams]
        # per level (EI, m/EI, L, kw/EI): the wave number that scales the stable propagation
        self._level_scales = [(float(b.EI), float(b.m) / float(b.EI), float(b.L),
                               float(b.kw) / float(b.EI)) for b in self.model.beams]

    @staticmethod
    def _plan_point(element, levels) -> _PointPlan:
        rows_disp, rows_force, signs = [], [], []
        for lvl_local, var in element.dofs:
            lvl = levels[lvl_local]
            force, sign = CONJUGATE[var]
            rows_disp.append(4 * lvl + STATE.index(var))
            rows_force.append(4 * lvl + STATE.index(force))
            signs.append(sign)
        S = element.stiffness(LAM)
        return _PointPlan(rows_disp, rows_force, signs, _entrywise_numpy(S),
                          sp.lambdify(LAM, S, modules="mpmath"))

    # -- precision ------------------------------------------------------------------
    def digits_lost(self, lam) -> float:
        """Estimated decimal digits lost to cancellation in ``Delta`` at ``lam``.

        Entries of a segment matrix grow like ``exp(|beta| l)``; the determinant
        cancels about ``sum |beta| L / ln 10`` digits over the beams (a foundation
        ``kw`` is bounded by ``|beta|**4 <= (m |lam|**2 + kw) / EI``).
        """
        a = abs(complex(lam))
        return sum((mu * a * a + k) ** 0.25 * L for mu, L, k in self._beam_consts) / math.log(10)

    # -- numpy ----------------------------------------------------------------------
    def R(self, lam) -> np.ndarray:
        """``R(lam)`` for an array of eigenvalues: shape ``lam.shape + (2n, 2n)``."""
        lam = np.asarray(lam, dtype=complex)
        flat = lam.reshape(-1)
        self.evaluations += flat.size
        E = np.zeros((flat.size, 4 * self.n, len(self.columns)), dtype=complex)
        for j, c in enumerate(self.columns):
            E[:, c, j] = 1.0
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
                for plan in items:
                    S = plan.stiffness_np(flat)
                    disp = E[:, plan.rows_disp, :]
                    jump = S @ disp
                    for i, (row, sign) in enumerate(zip(plan.rows_force, plan.signs)):
                        E[:, row, :] += sign * jump[:, i, :]
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

    def log_delta(self, lam) -> tuple:
        """``(log|Delta|, arg Delta)`` for an array of eigenvalues, without overflow.

        The columns of the unknown left-end variables are propagated as in
        :meth:`R`, but every segment is applied in steps of ``|beta| l <=``
        :data:`NU_STEP` and the columns are re-orthonormalised after each step
        (Godunov's method for stiff boundary-value problems): ``E = Q F``
        with ``Q`` orthonormal, so ``Delta = det Q[rows] * prod det F``. Without
        it the columns grow like ``exp(|beta| l)`` and become parallel to
        working precision, and ``det R`` loses about ``sum |beta| L / ln 10``
        digits (all of them by ``beta L = 36``); with it the value keeps about
        13 significant digits away from the eigenvalues at any mode.
        """
        lam = np.asarray(lam, dtype=complex)
        flat = lam.reshape(-1)
        self.evaluations += flat.size
        N = flat.size
        lam2 = flat * flat
        # The state of level j is measured in the units of its wave number b:
        # [Y, Theta/b, M/(EI b**2), Q/(EI b**3)]. Unscaled, the rows of a high mode
        # differ by powers of b, and the orthonormal columns would carry Y and Theta
        # in their last digits.
        D = np.ones((N, 4 * self.n))
        for j, (EI, mu, L, kw) in enumerate(self._level_scales):
            b = np.maximum(np.abs(mu * lam2 + kw) ** 0.25, 1.0 / L)
            D[:, 4 * j + 1] = 1 / b
            D[:, 4 * j + 2] = 1 / (EI * b**2)
            D[:, 4 * j + 3] = 1 / (EI * b**3)
        E = np.zeros((N, 4 * self.n, len(self.columns)), dtype=complex)
        for j, c in enumerate(self.columns):
            E[:, c, j] = 1.0
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

        for kind, items in self._steps:
            if kind == "segments":
                plans = []
                n_sub = 1
                for lvl, seg in items:
                    EI, m, l, kw = self._float_consts(seg)
                    nu = np.max(np.abs((lam2 * m + kw) * (l**4 / EI)), initial=0.0) ** 0.25
                    n_sub = max(n_sub, math.ceil(nu / NU_STEP))
                    plans.append((lvl, seg, (EI, m, l, kw)))
                subs = []
                for lvl, seg, (EI, m, l, kw) in plans:
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    key = (EI, m, l / n_sub, kw)
                    U = cache.get(key)
                    if U is None:          # equal segments share their matrix in a call
                        U = cache[key] = seg.evaluate_numpy(lam2, key)
                    subs.append((blk, U * (D[:, blk, None] / D[:, None, blk])))
                for _ in range(n_sub):
                    for blk, U in subs:
                        E[:, blk, :] = U @ E[:, blk, :]
                    E = orthonormalise(E)
            else:
                for plan in items:
                    S = plan.stiffness_np(flat)
                    jump = S @ (E[:, plan.rows_disp, :] / D[:, plan.rows_disp, None])
                    for i, (row, sign) in enumerate(zip(plan.rows_force, plan.signs)):
                        E[:, row, :] += sign * D[:, row, None] * jump[:, i, :]
        if len(self.columns):
            det = np.linalg.det(E[:, self.rows, :])
            with np.errstate(divide="ignore"):
                logabs = logabs + np.log(np.abs(det))
            phase = phase + np.angle(det)
        return logabs.reshape(lam.shape), np.angle(np.exp(1j * phase)).reshape(lam.shape)

    def _float_consts(self, seg) -> tuple:
        key = ("f", id(seg))
        consts = self._mp_cache.get(key)
        if consts is None:
            consts = (float(seg.EI), float(seg.m), float(seg.l), float(seg.kw))
            self._mp_cache[key] = consts
        return consts

    # -- mpmath ---------------------------------------------------------------------
    def _consts_mp(self, seg):
        key = (id(seg), mpmath.mp.prec)
        consts = self._mp_cache.get(key)
        if consts is None:
            dps = mpmath.mp.dps
            consts = (to_mp(seg.EI, dps), to_mp(seg.m, dps), to_mp(seg.l, dps),
                      to_mp(seg.kw, dps))
            self._mp_cache[key] = consts
        return consts

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
        E = np.full((4 * self.n, len(self.columns)), zero, dtype=object)
        for j, c in enumerate(self.columns):
            E[c, j] = one
        for kind, items in self._steps:
            if kind == "segments":
                for lvl, seg in items:
                    U = seg.evaluate_mp(lam2, self._consts_mp(seg))
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    E[blk, :] = U.dot(E[blk, :])
            else:
                for plan in items:
                    S = plan.stiffness_mp(lam)
                    S = np.array(S.tolist() if hasattr(S, "tolist") else S, dtype=object)
                    if real:
                        S = np.vectorize(lambda v: mpmath.mpf(mpmath.re(v)), otypes=[object])(S)
                    jump = S.dot(E[plan.rows_disp, :])
                    for i, (row, sign) in enumerate(zip(plan.rows_force, plan.signs)):
                        E[row, :] = E[row, :] + sign * jump[i, :]
        return mpmath.matrix(E[self.rows, :].tolist())

    def delta_mp(self, lam, real: bool = False):
        """``Delta(lam)`` at the current mpmath working precision."""
        R = self.R_mp(lam, real)
        return mpmath.det(R) if R.rows > 0 else mpmath.mpf(1)

    def nullity_at_zero(self, dps: int = 60) -> int:
        """Dimension of the null space of ``R(0)``, decided at two precisions.

        For models whose exact ``R(0)`` is transcendental (a Winkler
        foundation): a singular value that is zero shrinks with the precision
        (below ``10**(-dps/2)`` of the largest at ``dps`` and ``2 dps``
        digits), a non-zero one does not.

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


def _entrywise_numpy(S: sp.Matrix):
    """``lam array -> (N, d, d)`` complex stiffness, each entry lambdified on its own.

    Entries may be constants (a mass has zero off-diagonal entries), which a
    lambdified matrix would not broadcast.
    """
    d = S.rows
    funcs = [[sp.lambdify(LAM, S[i, j], modules="numpy") for j in range(d)] for i in range(d)]

    def evaluate(lam):
        out = np.empty((lam.size, d, d), dtype=complex)
        for i in range(d):
            for j in range(d):
                out[:, i, j] = np.broadcast_to(funcs[i][j](lam), lam.shape)
        return out
    return evaluate


def compile_model(model: Model) -> Evaluator:
    """Compile ``model`` into an :class:`Evaluator` (convenience alias)."""
    return Evaluator(model)
