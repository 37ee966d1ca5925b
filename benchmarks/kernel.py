"""The one place the benchmarks reach into symtmm's internals.

The public API (:func:`symtmm.solve.solve`, :func:`symtmm.sweep.sweep`,
:func:`symtmm.modelfile.load`, :mod:`symtmm.model`) is stable; the numeric
kernel and the search routines behind it are not. Everything the benchmarks
need from them -- an evaluation of ``Delta`` or of the eigenvalue count at a
batch of frequencies in a given arithmetic, the size of the compiled model,
the routines a profile times -- comes from :func:`internals`, so a rename
inside symtmm is a one-line fix here.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

__all__ = ["internals"]


def internals() -> SimpleNamespace:
    """symtmm's internals as the benchmarks use them.

    Returns
    -------
    SimpleNamespace
        ``kernel(model, omega_design)``: evaluations of an undamped model on the
        frequency axis, with ``counts(omegas, digits=None)`` (eigenvalues below
        each ``omega``; ``-1`` where undecided), ``delta(omegas, digits=None)``
        (``(log|Delta|, sign)`` arrays in double precision, else ``Delta`` per
        point as mpmath numbers: a ball's midpoint), ``elimination(omegas)`` (a call
        that runs the double-precision band elimination alone on ``K`` at those
        points, on a fresh copy each time: for timing), ``size(omega)`` (pieces, distinct
        segment kinds, freedoms and half-bandwidth of the compiled model at that
        range) and ``evaluations()``; ``digits=None`` is double precision, a
        number the proof arithmetic at that many digits.
        ``arithmetic_name(digits)``, ``certified`` (whether proofs use balls).
        ``transfer_delta(model)``: the vectorised transfer-matrix ``Delta(lam)``
        (what the generated code evaluates; the search baselines call it).
        ``profiled``: ``{name: (owner, attribute, key)}`` of the routines a
        profile times (:mod:`benchmarks.profiling`), ``key(args, kwargs)`` giving
        ``(suffix, points)`` of a call or None.
    """
    from symtmm import modes
    from symtmm.compile import Evaluator as TransferEvaluator
    from symtmm.numeric import evaluator as evaluator_module
    from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
    from symtmm.numeric.evaluator import Evaluator
    from symtmm.numeric.plan import StiffnessPlan
    from symtmm.numeric.stiffness import assemble, eliminate
    from symtmm.roots import undamped
    from symtmm.roots.count import Counter

    def arithmetic(digits):
        if digits is None:
            return DOUBLE
        return (Ball if ball_available() else MP).from_digits(digits)

    def kernel(model, omega_design):
        counter = Counter(model, omega_design)

        def delta(omegas, digits=None):
            if digits is None:
                logabs, sign, _ = counter.signed_log_delta(omegas)
                return logabs, sign
            ar = arithmetic(digits)
            return [ar.to_mpmath(v) for v in counter.delta(omegas, ar)[0]]

        def elimination(omegas):
            w = np.asarray(omegas, dtype=float)
            plan = counter.plan(float(np.max(w)), w.size)
            K, _ = assemble(plan, DOUBLE, -(w * w))
            B, n, b = K.shape
            band = np.concatenate([K, np.zeros((B, b, b), dtype=K.dtype)], axis=1)
            work = np.empty_like(band)

            def run():
                np.copyto(work, band)
                with np.errstate(all="ignore"):
                    eliminate(plan, DOUBLE, work, n)
            return run

        def size(omega):
            plan = counter.plan(omega)
            return dict(pieces=len(plan.mesh.segments), kinds=len(plan.kinds),
                        freedoms=plan.n, band=plan.band)

        return SimpleNamespace(
            counts=lambda omegas, digits=None: counter.counts(omegas, arithmetic(digits)),
            delta=delta, elimination=elimination, size=size,
            evaluations=lambda: counter.evaluations)

    def summary_key(args, kwargs):
        # Counter._summary(self, omegas); stiffness.summary(plan, lam2, lam=None): a double
        # batch read in one compiled pass, what most double factorizations now are
        return "double", len(args[1])

    def factor_key(args, kwargs):
        # Counter.factors(self, omegas, ar=DOUBLE, ...), Evaluator.factors(self, lam, ar=DOUBLE,
        # ...), Evaluator.enclose(self, lam, ar)
        ar = args[2] if len(args) > 2 else kwargs.get("ar", DOUBLE)
        return ar.name, len(args[1])

    return SimpleNamespace(
        kernel=kernel,
        arithmetic_name=lambda digits: arithmetic(digits).name,
        certified=ball_available(),
        transfer_delta=lambda model: TransferEvaluator(model).delta,
        profiled={
            "plan": (StiffnessPlan, "__init__", None),
            "factor": (Counter, "factors", factor_key),
            # the damped search: the same kernel at complex points (Counter overrides
            # factors without calling it), and Arb enclosures over boxes
            "complex_factor": (Evaluator, "factors", factor_key),
            "summary": (Counter, "_summary", summary_key, "factor"),
            "complex_summary": (evaluator_module, "summary", summary_key, "complex_factor"),
            "enclose": (Evaluator, "enclose", factor_key),
            "rigid_body_modes": (undamped, "rigid_body_modes", None),
            "mode_shapes": (modes, "shapes_at", None),
        })
