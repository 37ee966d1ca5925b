"""Overall transfer matrix and boundary reduction (paper eqs. 3–4, 12).

The states of all beams are stacked into one vector of length ``4 n``. The
global x axis is cut at every beam end and every spring; between two cuts
the stacked transfer matrix is block-diagonal (a beam segment for each beam
spanning the interval, the identity for a beam that does not), at a cut it
is the transfer matrix of the point elements there. The product from the
leftmost to the rightmost cut is the overall transfer matrix ``T``:
``z_right = T z_left``, where ``z_left`` (``z_right``) stacks the states at
each beam's own left (right) end.

Boundary conditions zero two variables at each end: the columns of ``T`` for
the unknown left-end variables and the rows for the right-end variables that
must vanish give the square matrix ``R(lam)``; eigenvalues solve
``det R(lam) = 0``.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import sympy as sp

from .elements import (
    STATE,
    Coupling,
    EulerBernoulliSegment,
    GroundSpring,
    LumpedMass,
    PointElement,
    RotationalCoupling,
    RotationalGroundSpring,
)
from .elements.base import LAM
from .model import BOUNDARY_CONDITIONS, Model

__all__ = ["Layout", "Interval", "Station", "overall_transfer_matrix", "boundary_matrix",
           "characteristic_determinant", "point_elements"]


def point_elements(model: Model) -> list:
    """Every point element of ``model`` as ``(x, element)``, in the order of the model.

    ``element.beams`` names the beams of its levels. Springs come first (in
    file order), then masses; both formulations (transfer and stiffness) read
    the model's point elements from here only.

    Examples
    --------
    >>> from symtmm.model import Beam, Spring, Mass, Model
    >>> m = Model((Beam("a", 1, 1, 1),), (Spring("a", "ground", 0, 5, kind="rotational"),),
    ...           masses=(Mass("a", 1, 2),))
    >>> [(x, type(e).__name__) for x, e in point_elements(m)]
    [(0, 'RotationalGroundSpring'), (1, 'LumpedMass')]
    """
    out = []
    for spring in model.springs:
        rotational = spring.kind == "rotational"
        if spring.grounded:
            cls = RotationalGroundSpring if rotational else GroundSpring
            out.append((spring.x, cls(spring.a, spring.k, spring.c)))
        else:
            cls = RotationalCoupling if rotational else Coupling
            out.append((spring.x, cls(spring.a, spring.b, spring.k, spring.c)))
    for mass in model.masses:
        out.append((mass.x, LumpedMass(mass.beam, mass.M, mass.J)))
    return out


@dataclass(frozen=True)
class Interval:
    """Part of the x axis between two cuts, with the beam segments spanning it."""

    x_start: sp.Expr
    x_end: sp.Expr
    #: ``(level, segment)`` for every beam spanning the interval
    segments: tuple


@dataclass(frozen=True)
class Station:
    """A cut, with the point elements acting there."""

    x: sp.Expr
    #: ``(element, levels)``: levels maps the element's own levels to beam indices
    elements: tuple


def _before(a: sp.Expr, b: sp.Expr, sample: dict | None = None) -> bool | None:
    """True if a < b, False if a >= b, None if it cannot be decided.

    ``sample`` (symbol -> number) decides what the symbols alone cannot.
    """
    diff = sp.simplify(b - a)
    if diff.is_positive:
        return True
    if diff.is_nonpositive:
        return False
    if sample:
        value = diff.xreplace(sample)
        if value.is_number:
            return bool(value > 0)
    return None


def _sorted_unique(points: list, sample: dict | None = None) -> list:
    """Sort exact coordinates; undecidable pairs keep the order they were given in."""
    result: list = []
    for p in points:
        if any(sp.simplify(p - q) == 0 for q in result):
            continue
        pos = len(result)
        for i, q in enumerate(result):
            if _before(p, q, sample) is True:
                pos = i
                break
        result.insert(pos, p)
    return result


class Layout:
    """The cut structure of a model: stations and intervals in order along x.

    Parameters
    ----------
    model : Model
        Parameters are substituted (``model.resolved()``); fields may still be
        symbolic.
    sample : dict, optional
        Values (symbol -> number) used only to order coordinates that stay
        symbolic, e.g. ``x1`` and ``1 - x1``.

    Examples
    --------
    >>> from symtmm.model import Beam, Spring, Model
    >>> m = Model((Beam("a", 1, 1, 1, left="clamped", right="free"),
    ...            Beam("b", 1, 1, 1, left="pinned", right="pinned")),
    ...           (Spring("a", "b", "1/2", 10),))
    >>> lay = Layout(m)
    >>> [s.x for s in lay.stations]
    [0, 1/2, 1]
    >>> lay.unknowns, lay.conditions
    (((0, 'M'), (0, 'Q'), (1, 'Theta'), (1, 'Q')), ((0, 'M'), (0, 'Q'), (1, 'Y'), (1, 'M')))
    """

    def __init__(self, model: Model, sample: dict | None = None):
        self.model = model.resolved()
        beams = self.model.beams
        self.levels = len(beams)
        points = []
        for beam in beams:
            points += [beam.x0, beam.x1]
        self._points = point_elements(self.model)
        points += [x for x, _ in self._points]
        xs = _sorted_unique(points, sample)
        stations, steps = [], []
        for i, x in enumerate(xs):
            elements = tuple(self._point_elements_at(x))
            station = Station(x, elements)
            stations.append(station)
            if elements:
                steps.append(station)
            if i + 1 < len(xs):
                x_end = xs[i + 1]
                segs = tuple(
                    (lvl, EulerBernoulliSegment(b.EI, b.m, x_end - x, b.kw))
                    for lvl, b in enumerate(beams)
                    if _before(x, b.x0, sample) is not True
                    and _before(b.x1, x_end, sample) is not True
                )
                steps.append(Interval(x, x_end, segs))
        self.stations = tuple(stations)
        self.steps = tuple(steps)

    def _point_elements_at(self, x):
        index = {b.name: i for i, b in enumerate(self.model.beams)}
        for xe, element in self._points:
            if sp.simplify(xe - x) != 0:
                continue
            yield element, tuple(index[name] for name in element.beams)

    @cached_property
    def unknowns(self) -> tuple:
        """``(level, variable)`` of the unknown left-end state variables (columns of R)."""
        out = []
        for lvl, beam in enumerate(self.model.beams):
            zero = BOUNDARY_CONDITIONS[beam.left]
            out += [(lvl, v) for v in STATE if v not in zero]
        return tuple(out)

    @cached_property
    def conditions(self) -> tuple:
        """``(level, variable)`` that must vanish at the right ends (rows of R)."""
        out = []
        for lvl, beam in enumerate(self.model.beams):
            out += [(lvl, v) for v in BOUNDARY_CONDITIONS[beam.right]]
        return tuple(out)

    @property
    def columns(self) -> list:
        """Indices of :attr:`unknowns` in the stacked state vector."""
        return [4 * lvl + STATE.index(v) for lvl, v in self.unknowns]

    @property
    def rows(self) -> list:
        """Indices of :attr:`conditions` in the stacked state vector."""
        return [4 * lvl + STATE.index(v) for lvl, v in self.conditions]


def _embed_point(element: PointElement, levels: tuple, n: int, lam) -> sp.Matrix:
    """Transfer matrix of a point element on the full stacked state."""
    local = element.transfer_matrix(lam)
    full = sp.eye(4 * n)
    for i_loc, lvl_i in enumerate(levels):
        for j_loc, lvl_j in enumerate(levels):
            block = local[4 * i_loc:4 * i_loc + 4, 4 * j_loc:4 * j_loc + 4]
            full[4 * lvl_i:4 * lvl_i + 4, 4 * lvl_j:4 * lvl_j + 4] = block
    return full


def _step_matrix(step, n: int, lam, segment_matrix) -> sp.Matrix:
    if isinstance(step, Station):
        out = sp.eye(4 * n)
        for element, levels in step.elements:
            # point transfer matrices are I + G with G*G' = 0, so they compose additively
            out += _embed_point(element, levels, n, lam) - sp.eye(4 * n)
        return out
    out = sp.eye(4 * n)
    for lvl, seg in step.segments:
        out[4 * lvl:4 * lvl + 4, 4 * lvl:4 * lvl + 4] = segment_matrix(seg)
    return out


def overall_transfer_matrix(model: Model, lam=LAM, segment_matrix=None) -> sp.Matrix:
    """Exact overall transfer matrix ``T`` with ``z_right = T z_left``.

    Parameters
    ----------
    model : Model
    lam : sympy.Expr
        Eigenvalue (a symbol or a number).
    segment_matrix : callable, optional
        Maps a beam segment to its matrix; default ``seg.transfer_matrix(lam)``.
        Passing e.g. ``lambda s: s.transfer_matrix_beta(beta)`` gives ``T`` in
        another variable.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> T = overall_transfer_matrix(Model((Beam("a", 1, 1, 2),)), lam=0)
    >>> T[0, :]
    Matrix([[1, 2, 2, 4/3]])
    """
    layout = model if isinstance(model, Layout) else Layout(model)
    n = layout.levels
    if segment_matrix is None:
        def segment_matrix(seg):
            return seg.transfer_matrix(lam)
    T = sp.eye(4 * n)
    for step in layout.steps:
        T = _step_matrix(step, n, lam, segment_matrix) * T
    return T


def boundary_matrix(model: Model, lam=LAM, segment_matrix=None) -> sp.Matrix:
    """Exact square matrix ``R(lam)`` whose determinant vanishes at eigenvalues.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> beam = Beam("a", EI=1, m=1, L=1, left="clamped", right="free")
    >>> boundary_matrix(Model((beam,)), lam=0)
    Matrix([
    [1, 1],
    [0, 1]])
    """
    layout = model if isinstance(model, Layout) else Layout(model)
    T = overall_transfer_matrix(layout, lam, segment_matrix)
    return T.extract(layout.rows, layout.columns)


def characteristic_determinant(model: Model, lam=LAM, segment_matrix=None) -> sp.Expr:
    """``det R(lam)``, unsimplified (see :mod:`symtmm.characteristic` for closed forms)."""
    return boundary_matrix(model, lam, segment_matrix).det(method="berkowitz")
