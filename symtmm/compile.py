"""``R(lam)`` and ``Delta(lam) = det R(lam)`` of one model: a convenience façade.

:class:`Evaluator` bundles a model's :class:`~symtmm.numeric.transfer.TransferPlan`
with the transfer walk of :mod:`symtmm.numeric.transfer` for interactive use and
for tests that want the transfer formulation (the product of transfer matrices
along ``x``) as a reference: numpy batches (:meth:`Evaluator.R`, the stable
:meth:`Evaluator.log_delta`) and mpmath (:meth:`Evaluator.R_mp`,
:meth:`Evaluator.delta_mp`) at a precision given explicitly, or, for
interactive use only, the ambient one. The library's searches use the kernel
directly (:class:`symtmm.numeric.evaluator.Evaluator`), always at an explicit
precision.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np

from .model import Model
from .numeric import transfer
from .numeric.arith import DOUBLE, MP

__all__ = ["Evaluator", "NU_STEP"]

NU_STEP = transfer.NU_STEP


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
    ...     first = mpmath.mpc(0, mpmath.pi**2)
    >>> abs(ev.delta_mp(first, dps=40)) < mpmath.mpf(10)**-38
    True
    """

    def __init__(self, model: Model):
        self.model = model.require_numeric()
        self.plan = transfer.TransferPlan(self.model)
        self.layout = self.plan.layout
        self.n = self.layout.levels
        self.size = self.plan.size
        self.columns = self.plan.columns
        self.rows = self.plan.rows
        self.damped = self.model.damped
        self.evaluations = 0

    # -- precision ------------------------------------------------------------------
    def wave_numbers(self, lam) -> np.ndarray:
        """Per beam, a bound on the largest wave number ``|beta|`` at ``lam`` (1/length)."""
        lam2 = np.asarray(lam, dtype=complex) ** 2
        return np.array([seg.wave_number(lam2) for seg, _, _ in self.plan.levels])

    def digits_lost(self, lam) -> float:
        """Estimated decimal digits the plain product loses to cancellation at ``lam``.

        Entries of a segment matrix grow like ``exp(|beta| l)``; the determinant
        cancels at most about ``sum |beta| L / ln 10`` digits over the beams.
        """
        b = self.wave_numbers(complex(lam))
        return float(sum(bj * L for bj, (_, _, L) in zip(b, self.plan.levels))) / math.log(10)

    # -- double precision -------------------------------------------------------------
    def R(self, lam) -> np.ndarray:
        """``R(lam)`` for an array of eigenvalues: shape ``lam.shape + (k, k)`` (the plain
        product: at high modes its determinant loses digits, see :meth:`log_delta`)."""
        lam = np.asarray(lam, dtype=complex)
        flat = lam.reshape(-1)
        self.evaluations += flat.size
        R = transfer.boundary(self.plan, DOUBLE, flat)
        return R.reshape(lam.shape + R.shape[1:])

    def log_delta(self, lam) -> tuple:
        """``(log|Delta|, arg Delta)``, stable at any mode (:func:`symtmm.numeric.transfer.log_delta`)."""
        lam = np.asarray(lam, dtype=complex)
        self.evaluations += lam.size
        return transfer.log_delta(self.plan, lam)

    def delta(self, lam) -> np.ndarray:
        """``Delta(lam)``, vectorised, double precision, stable at high modes."""
        logabs, phase = self.log_delta(lam)
        return np.exp(logabs + 1j * phase)

    # -- mpmath ---------------------------------------------------------------------
    def _arith(self, dps):
        return MP.from_digits(dps if dps is not None else mpmath.mp.dps)

    def _point(self, lam, real: bool, dps):
        """``(arithmetic, lam, lam**2)`` arrays of one point for the transfer walk, built in
        the arithmetic (the ambient precision is only the default of ``dps``)."""
        ar = self._arith(dps)
        if real and self.damped:
            raise ValueError("real arithmetic needs an undamped model")
        return (ar, *transfer.point(ar, ar.number(ar.ctx.mpmathify(lam)), real))

    def R_mp(self, lam, real: bool = False, dps: int | None = None) -> mpmath.matrix:
        """``R(lam)`` at one eigenvalue in mpmath at ``dps`` digits (default: the ambient
        precision). ``real=True`` (undamped, ``lam = i omega``): in real arithmetic."""
        self.evaluations += 1
        ar, lam, lam2 = self._point(lam, real, dps)
        R = transfer.boundary(self.plan, ar, lam, lam2)[0]
        return mpmath.matrix([[ar.to_mpmath(v) for v in row] for row in R])

    def delta_mp(self, lam, real: bool = False, dps: int | None = None):
        """``Delta(lam)`` in mpmath at ``dps`` digits (default: the ambient precision)."""
        self.evaluations += 1
        ar, lam, lam2 = self._point(lam, real, dps)
        return ar.to_mpmath(transfer.delta(self.plan, ar, lam, lam2)[0])

    def delta_omega_mp(self, omega, dps: int | None = None):
        """``Delta(i omega)`` of an undamped model, real."""
        ctx = self._arith(dps).ctx
        return self.delta_mp(ctx.mpc(0, ctx.mpmathify(omega)), real=True, dps=dps)
