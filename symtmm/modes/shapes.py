"""Mode shapes computed on the numeric kernel: null vector, walk, normalisation.

At an eigenvalue the work is done in a private mpmath context
(:class:`~symtmm.numeric.arith.MP`) at :func:`working_digits` digits:

1. ``R(lam)`` by the transfer walk (:func:`~symtmm.numeric.transfer.boundary`) and
   its near-null space by block inverse iteration
   (:func:`~symtmm.numeric.linalg.null_space`): the unknowns at the left;
2. one walk of those columns along the layout
   (:func:`~symtmm.numeric.transfer.sample`) gives the states at the sample
   points (the last short step in double precision) and, through an observer,
   the kinetic-energy Gram matrix (:class:`~symtmm.modes.normalise.Energy`);
3. normalisation (:mod:`symtmm.modes.normalise`), and the results as global
   mpmath numbers and numpy arrays (:mod:`symtmm.modes.modeset`).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time

import mpmath
import numpy as np
import sympy as sp

from .. import progress
from ..deadline import check as check_time
from ..deadline import time_budget
from ..errors import ComputationError, ModelError
from ..expr import ExpressionError, parse_expression
from ..limits import MAX_WALK_DIGITS, SEARCH_SECONDS
from ..model import Model
from ..numeric import transfer
from ..numeric.arith import DOUBLE, MP
from ..numeric.linalg import null_space
from ..numeric.plan import crowding
from ..results import Eigenvalue, Spectrum
from .localise import localising_rotation, pivoted_basis
from .modeset import BeamShape, ModeSet, ModeShape
from .nodal import nodal_displacements
from .normalise import Energy, Inertia, complex_scaler, mass_orthonormaliser
from .separate import FOUNDATION_DIGITS, foundation_digits, null_space_apart

__all__ = ["ShapePlan", "displacements", "evaluate_mode", "mode_shapes", "shapes_at",
           "working_digits"]


class ShapePlan:
    """A model compiled once for its mode shapes: transfer plan, inertia, sample grids.

    Parameters
    ----------
    model : Model
        Numeric (every parameter has a value).
    """

    def __init__(self, model: Model):
        self.model = model.require_numeric()
        self.plan = transfer.TransferPlan(self.model)
        self.inertia = Inertia(self.plan)
        self._grids: dict = {}

    def grid(self, points: int) -> tuple:
        """``points`` equally spaced exact points along every beam, both ends included (the
        left end before its jumps, every other point after them): their
        :class:`~symtmm.numeric.transfer.Sampling` and, per beam, their coordinates as floats.
        """
        if points not in self._grids:
            samples, floats = [], []
            for beam in self.model.beams:
                xs = [beam.x0 + beam.L * sp.Rational(i, points - 1) for i in range(points)]
                samples.append(list(zip(xs, ["-"] + ["+"] * (points - 1))))
                floats.append(np.array([float(x) for x in xs]))
            self._grids[points] = (transfer.Sampling(self.plan, samples), floats)
        return self._grids[points]


@functools.lru_cache(maxsize=16)
def _shape_plan(model: Model) -> ShapePlan:
    """A plan per model, kept for repeated :func:`evaluate_mode` calls."""
    return ShapePlan(model)


def working_digits(plan, lam, digits: int) -> int:
    """Decimal digits to compute a shape in: ``digits`` plus the cancellation, plus guard.

    The cancellation is that of the plain transfer product at ``lam``
    (:func:`~symtmm.numeric.transfer.digits_lost`, about ``sum |beta| L / ln 10``).

    Parameters
    ----------
    plan : TransferPlan
        Or an object that has one as ``plan`` (:class:`ShapePlan`,
        :class:`symtmm.compile.Evaluator`).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = ShapePlan(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)))
    >>> working_digits(pp, 1j * 10 * math.pi**2, 15)       # beta L = sqrt(10) pi: 4.3 digits
    35
    """
    plan = getattr(plan, "plan", plan)
    growth = transfer.growth_by_beam(plan, complex(lam))
    work = max(int(digits), 15) + math.ceil(sum(growth) / math.log(10)) + 15
    if work > MAX_WALK_DIGITS:
        worst = int(np.argmax(growth))
        raise ComputationError(
            f"the mode shape at {_value_text(lam)} would need {work} digits in the transfer "
            f"walk, more than {MAX_WALK_DIGITS}: beam '{plan.model.beams[worst].name}' loses "
            f"{growth[worst] / math.log(10):.0f} of them (its waves grow like exp(|beta| L) "
            "along it: a foundation kw, an axial force or a shear stiffness far from its EI, "
            "or an eigenvalue far above its own first modes)")
    return work


def sample_arithmetic(model, lam):
    """The arithmetic of the last short step to a sample (:func:`~symtmm.numeric.transfer.
    sample`'s ``inner``): double precision, or mpmath with the digits a foundation takes
    from the wave numbers where ``m lam**2 + kw`` cancels by more than
    :data:`~symtmm.modes.separate.FOUNDATION_DIGITS` (the eigenvalue's refinement's own
    threshold) (the step's ``x = -(m lam**2 +
    kw) h**4 / EI`` from a double ``lam``: a beam with ``kw / (EI b**4)`` of 8e15 had its
    samples 4e-6 off)."""
    lost = foundation_digits(model, lam)
    if lost <= FOUNDATION_DIGITS:
        return DOUBLE
    return MP.from_digits(20 + math.ceil(lost))


def _value_text(lam) -> str:
    """``lam`` in a line: ``omega = ...`` on the frequency axis, else ``lam = ...``."""
    z = complex(lam)
    return f"omega = {z.imag:.6g}" if z.real == 0 else f"lam = {z:.6g}"


def shapes_at(model: Model, eigenvalue: Eigenvalue, points: int = 101, digits: int | None = None,
              number: int = 1, plan: ShapePlan | None = None) -> list:
    """The mode shape(s) belonging to one eigenvalue: ``multiplicity`` of them.

    Parameters
    ----------
    model : Model
        Numeric (every parameter has a value).
    eigenvalue : Eigenvalue
        From :func:`symtmm.solve.solve`; its multiplicity sets the number of shapes.
    points : int
        Sample points per beam, both ends included (at least 2).
    digits : int, optional
        Digits the shape should carry; default the eigenvalue's.
    number : int
        Number of the first shape in its set.
    plan : ShapePlan, optional
        The model's plan, when shapes are computed at several eigenvalues.

    Returns
    -------
    list of ModeShape

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> ev = solve(pp, count=1)[0]
    >>> (shape,) = shapes_at(pp, ev, points=5)
    >>> np.round(shape.beams["b"].Y, 6) + 0.0         # sqrt(2) sin(pi x)
    array([0.      , 1.      , 1.414214, 1.      , 0.      ])
    """
    model = model.require_numeric()
    if points < 2:
        raise ValueError("points must be at least 2")
    shape_plan = plan or ShapePlan(model)
    tp = shape_plan.plan
    real = not model.damped and eigenvalue.lam.real == 0
    digits = eigenvalue.digits if digits is None else digits
    mult = eigenvalue.multiplicity
    # (the eigenvalue refined where a close neighbour would leak into its null space)
    dps, ar, V, value = null_space_apart(tp, eigenvalue, digits, real, working_digits)
    if value is not eigenvalue.lam:
        eigenvalue = dataclasses.replace(eigenvalue, lam=_global(value))
    with ar:
        E0 = ar.zeros((tp.size, mult), like=V)
        E0[tp.columns, :] = V
    grid, xs = shape_plan.grid(points)
    # (the walk to the samples, and the energy on the way, in Arb balls where flint is
    # installed, their midpoints taken back: the same rounding, a third of the time)
    walk = transfer.walk_arithmetic(ar)
    wlam, wlam2 = transfer.point(walk, value, real)
    start = transfer.convert(ar, walk, E0)
    energy = Energy(shape_plan.inertia, walk, wlam2, digits + 3) if real else None
    inner = sample_arithmetic(model, value)
    _, states = transfer.sample(tp, walk, grid, wlam, wlam2, start=start[None], inner=inner,
                                observe=energy)
    states = transfer.convert(inner, DOUBLE, states[0])     # (samples, 4, mult), double

    gram = parts = None
    if real:
        with walk:                      # (the bodies' energy added at the walk's precision)
            gram = transfer.convert(walk, ar, energy.gram(start))
            if mult > 1:
                parts = [transfer.convert(walk, ar, G) for G in energy.parts(start)]
    with ar:
        if real:
            T = mass_orthonormaliser(ar, gram)
            if parts is not None:
                T = T @ _localised(ar, T, parts)
        else:
            T = _pivoted(ar, states[:, 0, :]) if mult > 1 else None
            Y = states[:, 0, :] if T is None else states[:, 0, :] @ ar.to_complex(T)
            scale = complex_scaler(ar, Y)
            T = scale if T is None else T @ scale
        E0 = E0 @ T
    states = states @ (ar.to_complex(T).real if real else ar.to_complex(T))
    per_level = states.reshape(len(model.beams), points, 4, mult)
    shapes = []
    for c in range(mult):
        sign = 1
        if real:
            # make the largest displacement positive: the first of those equal to it
            # within rounding (sin 2 pi x peaks alike at 1/4 and 3/4, and which one the
            # rounding favoured would otherwise set the sign)
            Ys = per_level[:, :, 0, c].reshape(-1)
            size = np.abs(Ys)
            first = int(np.argmax(size >= size.max() * (1 - 1e-9)))
            sign = -1 if Ys[first] < 0 else 1
        beams = {}
        for lvl, beam in enumerate(model.beams):
            z = per_level[lvl, :, :, c] * sign
            beams[beam.name] = BeamShape(beam.name, xs[lvl], z[:, 0], z[:, 1], z[:, 2], z[:, 3])
        left = tuple(ar.to_mpmath(E0[r, c] * sign) for r in range(E0.shape[0]))
        shapes.append(ModeShape(eigenvalue, beams, left, dps, number + c,
                                _body_motion(tp.layout, left, real)))
    return shapes


def _global(z) -> mpmath.mpc:
    """A complex number of a private mpmath context as a global one, every bit kept."""
    return mpmath.mp.make_mpc((z.real._mpf_, z.imag._mpf_))


def _localised(ar, T, parts):
    """The rotation (in the arithmetic, orthogonal to its precision) that turns the
    mass-orthonormal shapes ``T`` of a multiple eigenvalue into the basis that
    concentrates each one's kinetic energy on as few beams and bodies as possible
    (:mod:`symtmm.modes.localise`)."""
    energies = [ar.to_complex(T.T @ G @ T).real for G in parts]
    Q = ar.array([ar.number(float(v)) for v in localising_rotation(energies).reshape(-1)],
                 (T.shape[1], T.shape[1]))
    # Q is orthogonal to double precision; a Cholesky step makes it so to the shape's
    return Q @ mass_orthonormaliser(ar, Q.T @ Q)


def _pivoted(ar, Y):
    """The basis change of a damped multiple eigenvalue's shapes to the one of
    :func:`~symtmm.modes.localise.pivoted_basis` (numbers of ``ar``), or None."""
    P = pivoted_basis(Y)
    if P is None:
        return None
    return ar.array([ar.number(complex(v)) for v in P.reshape(-1)], P.shape)


#: Digits a double-precision walk keeps before its cancellation (of 15.9, a guard).
_DOUBLE_DIGITS = 13


def displacements(model: Model, eigenvalues, points: int, digits: int,
                  plan: ShapePlan | None = None, nodal: bool = True) -> list:
    """``Y`` along every beam for many eigenvalues at once, unnormalised (sweeps' tracking).

    First from the dynamic stiffness (:func:`~symtmm.modes.nodal.nodal_displacements`:
    double precision at any mode) where that serves (``nodal``); the others by the
    transfer walk, the eigenvalues of one kind (undamped or not, one multiplicity)
    sharing one: their null spaces at the largest precision any of them needs, then the
    states at the samples of :meth:`ShapePlan.grid` in one batch. Returns, per
    eigenvalue, ``(multiplicity, beams * points)`` floats (complex for damped models) in
    the shapes' own scale: what a modal assurance criterion needs, no normalisation.
    """
    model = model.require_numeric()
    # the stiffness kernel's short pieces: double precision at any mode, where it serves
    out = nodal_displacements(model, eigenvalues, points) if nodal else [None] * len(eigenvalues)
    if all(Y is not None for Y in out):
        return out
    shape_plan = plan or ShapePlan(model)
    tp = shape_plan.plan
    grid, _ = shape_plan.grid(points)
    groups: dict = {}
    for i, e in enumerate(eigenvalues):
        if out[i] is not None:
            continue
        real = not model.damped and e.lam.real == 0
        # double precision where the walk's cancellation leaves the digits asked for
        # (low modes), mpmath beyond
        in_double = digits + transfer.digits_lost(tp, complex(e.lam)) <= _DOUBLE_DIGITS
        groups.setdefault((real, e.multiplicity, in_double), []).append(i)
    for (real, mult, in_double), idx in groups.items():
        if in_double:
            ar = DOUBLE
        else:
            ar = MP.from_digits(max(working_digits(tp, eigenvalues[i].lam, digits)
                                    for i in idx))
        with ar:
            pairs = [transfer.point(ar, eigenvalues[i].lam, real) for i in idx]
            lam = None if real else ar.array([p[0][0] for p in pairs])
            lam2 = ar.array([p[1][0] for p in pairs]) if real else None
            if real and ar is DOUBLE:
                lam2 = lam2.real            # (doubles are complex numbers: a real walk)
            R = transfer.boundary(tp, ar, lam, lam2)
            E0 = ar.zeros((len(idx), tp.size, mult), like=R)
            for b in range(len(idx)):
                E0[b][tp.columns, :] = null_space(ar, R[b], mult)
        _, states = transfer.sample(tp, ar, grid, lam, lam2, start=E0, inner=DOUBLE)
        for b, i in enumerate(idx):
            Y = states[b, :, 0, :]                      # (samples, mult)
            out[i] = (Y.real if real else Y).T
    return out


def _body_motion(layout, state, real: bool) -> dict:
    """Per rigid body, its ``Y``, ``Theta`` (if it rotates) and ``X`` (if it translates in
    the plane) from the extended state."""
    out = {}
    for bl in layout.bodies:
        motion = {}
        for var in bl.frame.freedoms:
            if var in bl.unknowns:
                value = complex(state[bl.unknowns[var]])
                motion[var] = value.real if real else value
        out[bl.body.name] = motion
    return out


def evaluate_mode(model: Model, mode: ModeShape, beam: str, x, side: str = "+") -> np.ndarray:
    """The state ``[Y, Theta, M, Q]`` of ``mode`` at global coordinates ``x`` on ``beam``.

    Parameters
    ----------
    model : Model
        The model the mode belongs to.
    mode : ModeShape
    beam : str
        Beam name.
    x : array_like
        Global coordinates on the beam (floats, read as the decimals they print as,
        exact values, or strings such as ``"1/3"``).
    side : {"+", "-"}
        At a station: the state after (``"+"``) or before (``"-"``) the jumps of
        the point elements there, in the direction of increasing x.

    Returns
    -------
    numpy.ndarray
        Shape ``(4, len(x))``, float for undamped modes, complex for damped.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> (shape,) = shapes_at(pp, solve(pp, count=1)[0], points=3)
    >>> z = evaluate_mode(pp, shape, "b", [0.25])
    >>> round(float(z[0, 0]), 12) == round(math.sqrt(2) * math.sin(math.pi / 4), 12)
    True
    """
    model = model.require_numeric()
    if side not in ("+", "-"):
        raise ValueError("side must be '+' or '-'")
    lvl = model.beam_index(beam)
    shape_plan = _shape_plan(model)
    tp = shape_plan.plan
    xs = [x] if np.ndim(x) == 0 else list(x)
    points = [[] for _ in model.beams]
    points[lvl] = [(_coordinate(v), side) for v in xs]
    where = transfer.Sampling(tp, points)
    real = not any(isinstance(v, mpmath.mpc) for v in mode.left_state)
    ar = MP.from_digits(mode.dps)
    lam, lam2 = transfer.point(ar, mode.lam, real)
    start = ar.array([ar.number(v) for v in mode.left_state], (1, tp.size, 1))
    inner = sample_arithmetic(model, mode.lam)
    _, states = transfer.sample(tp, ar, where, lam, lam2, start=start, inner=inner)
    out = transfer.convert(inner, DOUBLE, states[0, :, :, 0].T)
    return out.real if real else out


def _coordinate(value) -> sp.Expr:
    """A coordinate as an exact number; a float is read as the decimal it prints as.

    A string is read by the restricted parser of model files, never by ``sympify``.
    """
    if isinstance(value, mpmath.mpf):
        man, exp = value.man_exp
        return sp.Integer(int(man)) * sp.Integer(2) ** int(exp)
    if isinstance(value, (float, np.floating)):
        return sp.Rational(repr(float(value)))
    if isinstance(value, np.integer):
        return sp.Integer(int(value))
    if isinstance(value, str):
        try:
            value = parse_expression(value)
        except ExpressionError as exc:
            raise ModelError(f"cannot read {value!r}: {exc}", field="x") from None
        if not value.is_number:
            raise ModelError(f"{value} is not a number", field="x")
    return sp.sympify(value)


def mode_shapes(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
                points: int = 101, digits: int = 15, method: str = "default",
                spectrum: Spectrum | None = None,
                max_seconds: float | None = SEARCH_SECONDS) -> ModeSet:
    """Mode shapes of the first ``count`` modes (with multiplicity) of ``model``.

    Parameters
    ----------
    model : Model
        Every parameter must have a value.
    count, omega_max, sigma_max, digits, method
        Passed to :func:`symtmm.solve.solve` to find the eigenvalues.
    max_seconds : float or None
        Time budget of the search and the shapes (``--max-seconds``); None for none.
    points : int
        Sample points per beam, both ends included.
    spectrum : Spectrum, optional
        Eigenvalues already found; then no search is made.

    Returns
    -------
    ModeSet
        One :class:`ModeShape` per eigenvalue and multiplicity.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> cf = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="free"),))
    >>> modes = mode_shapes(cf, count=2, points=11)
    >>> print(modes.table())                                      # doctest: +ELLIPSIS
    #     omega [rad/s]    Omega (beam b)  max|Y| b
    -  ----------------  ----------------  --------
    1  3.51601526850015  1.87510406871196         2
    2  22.0344915646668  4.69409113297417         2
    2 mode shape(s), 11 points per beam (max|Y| over those points); mass-normalised: ...
    """
    from ..solve import solve

    model = model.require_numeric()
    with time_budget(max_seconds, explain=lambda: crowding(model)):
        if spectrum is None:
            spectrum = solve(model, count=count, omega_max=omega_max, sigma_max=sigma_max,
                             digits=digits, method=method, max_seconds=None)
        return _mode_set(model, spectrum, count, points)


def _mode_set(model, spectrum, count, points) -> ModeSet:
    start = time.perf_counter()
    plan = ShapePlan(model)
    modes, number = [], 1
    with progress.bar(total=len(spectrum), desc="mode shapes", unit="mode") as bar:
        for e in spectrum:
            check_time()
            shapes = shapes_at(model, e, points=points, number=number, plan=plan)
            modes += shapes
            number += len(shapes)
            bar.update()
    notes = []
    if count is not None and len(modes) > count:
        multiple = [e for e in spectrum if e.multiplicity > 1]
        notes.append(f"{len(modes)} shapes for {count} requested: a multiple eigenvalue "
                     f"(here {', '.join(str(e) for e in multiple)}) "
                     "is given a basis of its whole eigenspace, mass-orthonormal")
    if any(e.multiplicity > 1 and e.lam.real == 0 for e in spectrum) and not model.damped:
        notes.append("shapes of a multiple eigenvalue: the mass-orthonormal basis that "
                     "concentrates each one's kinetic energy on as few beams and bodies as "
                     "possible (a joint diagonalisation of their energies)")
    if any(e.multiplicity > 1 for e in spectrum) and model.damped:
        notes.append("shapes of a multiple damped eigenvalue: the basis in which each one "
                     "is 1 at a sample of its own, where it moves most, and 0 at the "
                     "others' (one beam each where the eigenvalue's beams move alone)")
    return ModeSet(tuple(modes), model, spectrum, time.perf_counter() - start, tuple(notes))
