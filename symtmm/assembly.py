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

Rigid bodies (and joints, which are massless bodies) join beams at points:
chains of beams, trees, closed loops. Each brings *virtual* state variables
after the ``4 n`` of the beams, constant along ``x``: its own deflection and
rotation and the force (and couple) it exerts at each attachment, all
unknowns (columns of ``R``); and one accumulator per equation it must satisfy
(compatibility at each attachment, its equations of motion), which gathers
that equation's terms at the stations and must vanish at the right (rows of
``R``). So the overall transfer equation of any topology is one product along
``x``, and ``R`` stays square. At a station every element adds ``G`` to the
identity (the transfer matrix there is ``I + G``); its entries are exact
polynomials in ``lam`` (:attr:`Station.terms`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import sympy as sp

from .elements import (
    STATE,
    Coupling,
    GroundSpring,
    LumpedMass,
    RotationalCoupling,
    RotationalGroundSpring,
)
from .elements.base import CONJUGATE, LAM
from .model import BOUNDARY_CONDITIONS, GROUND, Model

__all__ = ["Layout", "Interval", "Station", "BodyLayout", "overall_transfer_matrix", "state_rows",
           "boundary_matrix", "characteristic_determinant", "point_elements"]


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
    #: ``(level, segment)`` for every beam spanning the interval; beams joined there by
    #: layers come as one ``(levels, CoupledSegment)`` (see :func:`state_rows`)
    segments: tuple


@dataclass(frozen=True)
class Station:
    """A cut, with the point elements acting there.

    ``terms`` are the entries ``(row, col, value)`` of ``G`` on the extended
    state (beams, then the bodies' virtual variables): across the station the
    state goes to ``(I + G) z``. Rows written are never columns read at the
    same station (forces read displacements), so the elements' ``G`` add up.
    """

    x: sp.Expr
    #: ``(element, levels)``: levels maps the element's own levels to beam indices
    elements: tuple
    #: ``(row, col, value)`` entries of G, value exact in ``lam``
    terms: tuple = ()


@dataclass(frozen=True)
class BodyLayout:
    """Where a rigid body's virtual variables sit in the extended state.

    ``unknowns`` and ``equations`` map labels (``"Y"``, ``"Theta"``,
    ``("F", i)``, ``("C", i)`` / ``("Y", i)``, ``("Theta", i)``, ``"force"``,
    ``"moment"``) to indices; ``units`` gives each index the ``(level, variable)``
    whose physical unit it has (for scaling).
    """

    body: object
    unknowns: dict
    equations: dict
    levels: tuple      # level of each attachment's beam
    frame: object = None   # its BodyFrame


@dataclass(frozen=True)
class LinkLayout:
    """Where an inextensible bar's force and equation sit (None for a bar with a free end:
    only its mass acts), and its ends' rows ``(BodyLayout, {label: coefficient})``."""

    link: object
    force: int | None
    equation: int | None
    rows: tuple


#: The equation of motion of each freedom of a body.
_EQUATION = {"Y": "force", "Theta": "moment", "X": "force X"}


def _before(a: sp.Expr, b: sp.Expr, sample: dict | None = None) -> bool | None:
    """True if a < b, False if a >= b, None if it cannot be decided.

    ``sample`` (symbol -> number) decides what the symbols alone cannot.
    """
    if a.is_Rational and b.is_Rational:     # the usual case, and a cheap one
        return bool(a < b)
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


def _same(a: sp.Expr, b: sp.Expr) -> bool:
    """Exactly equal coordinates (rationals compare at once; others by simplification)."""
    if a.is_Rational and b.is_Rational:
        return a == b
    return sp.simplify(a - b) == 0


def _sorted_unique(points: list, sample: dict | None = None) -> list:
    """Sort exact coordinates; undecidable pairs keep the order they were given in."""
    result: list = []
    for p in map(sp.sympify, points):
        if any(_same(p, q) for q in result):
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
        self.bodies = self._place_bodies()
        points += [a.x for bl in self.bodies for a in bl.body.attachments]
        points += [x for la in self.model.layers for x in (la.x0, la.x1)]
        xs = _sorted_unique(points, sample)
        stations, steps = [], []
        for i, x in enumerate(xs):
            elements = tuple(self._point_elements_at(x))
            terms = tuple(self._terms_at(x, elements))
            station = Station(x, elements, terms)
            stations.append(station)
            if terms:
                steps.append(station)
            if i + 1 < len(xs):
                x_end = xs[i + 1]
                segs = tuple(
                    (lvl, b.segment(x_end - x))
                    for lvl, b in enumerate(beams)
                    if _before(x, b.x0, sample) is not True
                    and _before(b.x1, x_end, sample) is not True
                )
                steps.append(Interval(x, x_end, self._coupled(segs, x, x_end, sample)))
        self.stations = tuple(stations)
        self.steps = tuple(steps)

    def _coupled(self, segs, x, x_end, sample) -> tuple:
        """The segments of an interval with the beams joined there by layers made one
        ``(levels, CoupledSegment)`` entry (levels in increasing order)."""
        if not self.model.layers:
            return segs
        index = {b.name: i for i, b in enumerate(self.model.beams)}
        cover = [la for la in self.model.layers
                 if _before(x, la.x0, sample) is not True
                 and _before(la.x1, x_end, sample) is not True]
        if not cover:
            return segs
        from .elements.layer import joined, member
        groups = joined([lvl for lvl, _ in segs], cover, index)
        out, done = [], set()
        for lvl, seg in segs:
            members, used = groups[lvl]
            if len(members) == 1:
                out.append((lvl, seg))
            elif members not in done:
                done.add(members)
                out.append((members, member(self.model.beams, members, used, index,
                                            x_end - x)))
        return tuple(out)

    # -- rigid bodies -------------------------------------------------------------------
    def _place_bodies(self) -> tuple:
        index = {b.name: i for i, b in enumerate(self.model.beams)}
        out, nxt = [], 4 * self.levels
        units = {}
        for body in self.model.bodies:
            levels = tuple(index[a.beam] for a in body.attachments)
            frame = self.model.body_frame(body)
            unknowns, equations = {}, {}

            def new(table, label, level, var):
                nonlocal nxt
                table[label] = nxt
                units[nxt] = (level, var)
                nxt += 1
            # the freedoms Y, Theta, X (a translation in the unit of the first attachment's
            # deflection, the rotation in that of its rotation)
            for label in frame.freedoms:
                new(unknowns, label, levels[0], "Theta" if label == "Theta" else "Y")
            # (an elastic attachment's force follows from the two deflections: no unknown
            # of its own and no compatibility equation)
            for i, (att, lvl) in enumerate(zip(body.attachments, levels)):
                if att.elastic:
                    continue
                new(unknowns, ("F", i), lvl, "Q")
                if frame.turns[i]:
                    new(unknowns, ("C", i), lvl, "M")
            for i, (att, lvl) in enumerate(zip(body.attachments, levels)):
                if att.elastic:
                    continue
                new(equations, ("Y", i), lvl, "Y")
                if frame.turns[i]:
                    new(equations, ("Theta", i), lvl, "Theta")
            for label in frame.freedoms:
                new(equations, _EQUATION[label], levels[0], "M" if label == "Theta" else "Q")
            out.append(BodyLayout(body, unknowns, equations, levels, frame))
        # an inextensible bar between bodies (or a body and the ground): its axial force
        # is an unknown, the equality of its ends' motions along it an equation
        self.links = []
        placed = {bl.body.name: bl for bl in out}
        for link in self.model.links:
            ends = [(placed[body.name], row) for body, row in self.model.link_rows(link)]
            rows = tuple((bl, row) for bl, row in ends if row)
            if not rows:
                continue                # held at both ends: nothing moves along it
            # an end on the ground, or on a body held along the bar, holds it
            held = GROUND in link.ends or len(rows) < len(ends)
            if len(rows) == 2 or held:
                level = rows[0][0].levels[0]
                units[nxt], units[nxt + 1] = (level, "Q"), (level, "Y")
                self.links.append(LinkLayout(link, nxt, nxt + 1, rows))
                nxt += 2
            else:
                self.links.append(LinkLayout(link, None, None, rows))   # a free end: its mass
        self.size = nxt
        self._units = units
        return tuple(out)

    def _body_terms_at(self, x):
        """Entries of G of the bodies at ``x``: attachments, and each body's equations of
        motion at the station of its first attachment.

        Attachment ``i`` moves its member's ``Y`` by ``a_i . q`` (``q`` the body's freedoms,
        ``a_i`` the row of :class:`~symtmm.model.BodyFrame`); the force ``F_i`` it exerts
        there (``Q+ - Q- = F_i``) enters the body's equation of each freedom with the same
        coefficient, by virtual work: ``m_q lam**2 q + sum_i a_i[q] F_i (+ C_i) = 0``.
        """
        lam2 = LAM**2
        for bl in self.bodies:
            body, u, e, frame = bl.body, bl.unknowns, bl.equations, bl.frame
            for i, (att, lvl) in enumerate(zip(body.attachments, bl.levels)):
                if not _same(att.x, x):
                    continue
                row = frame.rows[i]
                if att.elastic:
                    # F = (k + c lam)(a_i . q - Y) on the beam (Q+ - Q- = F), and into the
                    # body's equations of motion where it is
                    s = att.k + att.c * LAM
                    force = [(u[label], s * a) for label, a in row.items()] + [(4 * lvl, -s)]
                    for col, value in force:
                        yield (4 * lvl + 3, col, value)
                        for label, a in row.items():
                            yield (e[_EQUATION[label]], col, a * value)
                    continue
                # the body's force and couple on the beam: Q+ - Q- = F, M+ - M- = -C
                yield (4 * lvl + 3, u[("F", i)], sp.Integer(1))
                # compatibility: the beam's deflection (and rotation) are the body's there
                yield (e[("Y", i)], 4 * lvl, sp.Integer(1))
                for label, a in row.items():
                    yield (e[("Y", i)], u[label], -a)
                if frame.turns[i]:
                    yield (4 * lvl + 2, u[("C", i)], sp.Integer(-1))
                    yield (e[("Theta", i)], 4 * lvl + 1, sp.Integer(1))
                    if "Theta" in u:
                        yield (e[("Theta", i)], u["Theta"], sp.Integer(-1))
            if not _same(body.attachments[0].x, x):
                continue
            # m_q lam^2 q + sum a_i[q] F_i (+ C_i) = 0: the reactions -F_i, -C_i of the
            # beams accelerate the body (moments about its centre)
            for label in frame.freedoms:
                mass = frame.mass(body, label)
                if mass != 0:
                    yield (e[_EQUATION[label]], u[label], mass * lam2)
            for label, k, c in body.ground:
                # a spring and dashpot to the ground on the freedom: (k + c lam) q
                if k != 0 or c != 0:
                    yield (e[_EQUATION[label]], u[label], k + c * LAM)
            for i, att in enumerate(body.attachments):
                if att.elastic:
                    continue                        # (added at its own station)
                for label, a in frame.rows[i].items():
                    yield (e[_EQUATION[label]], u[("F", i)], a)
                if frame.turns[i]:
                    yield (e["moment"], u[("C", i)], sp.Integer(1))
        for ll in self.links:
            first = ll.rows[0][0]
            if not _same(first.body.attachments[0].x, x):
                continue
            # the bar's force N pulls its ends: t . (q_a - q_b) = 0, and N enters each end's
            # equations with the same coefficients (virtual work); its mass M moves with the
            # first end along t: M lam**2 (t . q_a) t in that end's equations
            for bl, row in ll.rows:
                for label, a in row.items():
                    if ll.force is not None:
                        yield (ll.equation, bl.unknowns[label], a)
                        yield (bl.equations[_EQUATION[label]], ll.force, a)
            bl, row = ll.rows[0]
            if ll.link.M != 0:
                for label, a in row.items():
                    for label2, a2 in row.items():
                        yield (bl.equations[_EQUATION[label]], bl.unknowns[label2],
                               ll.link.M * a * a2 * lam2)

    def _terms_at(self, x, elements):
        """Every entry of G at the station ``x``: point elements, then bodies; summed."""
        out: dict = {}
        for element, levels in elements:
            S = element.stiffness(LAM)
            for i, (li, var_i) in enumerate(element.dofs):
                force, sign = CONJUGATE[var_i]
                row = 4 * levels[li] + STATE.index(force)
                for k, (lk, var_k) in enumerate(element.dofs):
                    value = sp.expand(sign * S[i, k])
                    if value != 0:
                        col = 4 * levels[lk] + STATE.index(var_k)
                        out[(row, col)] = out.get((row, col), 0) + value
        for row, col, value in self._body_terms_at(x):
            out[(row, col)] = out.get((row, col), 0) + value
        return [(r, c, v) for (r, c), v in out.items() if v != 0]

    @property
    def units(self) -> list:
        """``(level, variable)`` whose unit each index of the extended state has."""
        out = [(lvl, v) for lvl in range(self.levels) for v in STATE]
        return out + [self._units[i] for i in range(4 * self.levels, self.size)]

    def _point_elements_at(self, x):
        index = {b.name: i for i, b in enumerate(self.model.beams)}
        for xe, element in self._points:
            if not _same(sp.sympify(xe), x):
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
        """Indices (extended state) of the unknowns: beams' left-end variables, then bodies'."""
        out = [4 * lvl + STATE.index(v) for lvl, v in self.unknowns]
        return (out + [i for bl in self.bodies for i in bl.unknowns.values()]
                + [ll.force for ll in self.links if ll.force is not None])

    @property
    def rows(self) -> list:
        """Indices (extended state) of the conditions: beams' right ends, then the bodies'
        equations (accumulators)."""
        out = [4 * lvl + STATE.index(v) for lvl, v in self.conditions]
        return (out + [i for bl in self.bodies for i in bl.equations.values()]
                + [ll.equation for ll in self.links if ll.equation is not None])


def _step_matrix(step, size: int, lam, segment_matrix) -> sp.Matrix:
    out = sp.eye(size)
    if isinstance(step, Station):
        for row, col, value in step.terms:
            out[row, col] += value.xreplace({LAM: lam}) if lam is not LAM else value
        return out
    for lvl, seg in step.segments:
        rows = state_rows(lvl)
        U = segment_matrix(seg)
        for i, r in enumerate(rows):
            for j, c in enumerate(rows):
                out[r, c] = U[i, j]
    return out


def state_rows(levels) -> list:
    """Indices in the extended state of a segment's state variables: ``[Y, Theta, M, Q]``
    of a beam (``levels`` an int), or of several beams joined by layers, variable by
    variable (``[Y_1..Y_N, Theta_1.., M_1.., Q_1..]``)."""
    if isinstance(levels, int):
        return [4 * levels + v for v in range(4)]
    return [4 * lvl + v for v in range(4) for lvl in levels]


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
    if segment_matrix is None:
        def segment_matrix(seg):
            return seg.transfer_matrix(lam)
    T = sp.eye(layout.size)
    for step in layout.steps:
        T = _step_matrix(step, layout.size, lam, segment_matrix) * T
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
