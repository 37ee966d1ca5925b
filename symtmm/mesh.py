"""The mesh of a model for the dynamic-stiffness formulation: nodes, pieces, freedoms.

Every beam is cut at its ends, its point elements and the attachments of rigid
bodies, then each part into equal pieces no longer than a length rule asks
(short enough for the frequency range, :func:`symtmm.numeric.plan.piece_length`).
Each node carries ``Y`` and ``Theta``, each rigid body ``Y_c`` and (if it rotates)
``Theta_c``. Boundary conditions and attachments are linear constraints among
them, eliminated exactly: every freedom becomes a combination of the free ones
(master-slave elimination), which makes ``K = T^T K_full T`` the stiffness of
the constrained structure, for which the Wittrick-Williams count holds unchanged.
Nothing here is numeric: coordinates and coefficients stay exact.
"""

from __future__ import annotations

import functools
import itertools
import math
from fractions import Fraction

import sympy as sp
from sympy.polys.domains import QQ
from sympy.polys.polyerrors import CoercionFailed

from .assembly import point_elements
from .deadline import check as check_time
from .elements import Coupling, EulerBernoulliSegment, GroundSpring
from .elements.base import stiffness_coefficients
from .elements.layer import joined, member
from .errors import ComputationError, ModelError
from .expr import exact_float
from .limits import MAX_PIECES
from .model import FREEDOM_INDEX, GROUND, Model
from .numeric.plan import (
    clamped_long_piece,
    layered_piece,
    long_piece,
    wave_number_bound,
    wave_piece,
)
from .numeric.segments import Condensed

__all__ = ["Mesh", "Stretches", "BC_FREEDOMS_FIXED", "static_nullity", "zero_order"]

#: The node freedoms (0 = Y, 1 = Theta) each boundary condition fixes.
BC_FREEDOMS_FIXED = {"free": (), "clamped": (0, 1), "pinned": (0,), "sliding": (1,)}


def _canonical(x) -> sp.Expr:
    """An exact coordinate in one canonical form (a dictionary key)."""
    x = sp.sympify(x)
    return x if x.is_Rational else sp.expand(x)


class Stretches:
    """The parts every beam of ``model`` is cut into, whatever the frequency range: between
    its ends, point elements and rigid bodies' attachments, and over a layer at the
    layer's ends and every such point of a beam it joins. :class:`Mesh` cuts each part
    into equal pieces; :meth:`subdivide` says into how many.

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> m = Model((Beam("a", 1, 1, 2, left="pinned", right="pinned"),),
    ...           (Spring("a", "ground", "1/2", 5),))
    >>> st = Stretches(m)
    >>> [[str(x) for x in xs] for xs in st.xs_of]
    [['0', '1/2', '2']]
    >>> st.subdivide(lambda beam, seg: 0.4)[2]          # (lengths over the longest piece)
    [1.25, 3.75]
    """

    def __init__(self, model: Model):
        self.model = model
        index = {b.name: i for i, b in enumerate(model.beams)}
        points_el = point_elements(model)
        layers = [(index[la.a], index[la.b], _canonical(la.x0), _canonical(la.x1), la)
                  for la in model.layers]
        at: dict = {b.name: [b.x0, b.x1] for b in model.beams}     # beam -> its points
        for x, el in points_el:
            for name in el.beams:
                at[name].append(x)
        for body in model.bodies:
            for a in body.attachments:
                at[a.beam].append(a.x)
        required = [{_canonical(x) for x in at[beam.name]} for beam in model.beams]
        for a, b, x0, x1, _ in layers:
            required[a] |= {x0, x1}
            required[b] |= {x0, x1}
        changed = True
        while changed:      # a beam's points over a layer are its partner's too (chains)
            changed = False
            for a, b, x0, x1, _ in layers:
                for i, j in ((a, b), (b, a)):
                    extra = {x for x in required[i] if exact_float(x0) <= exact_float(x) <= exact_float(x1)
                             and x not in required[j]}
                    if extra:
                        required[j] |= extra
                        changed = True
        #: per beam, its required points ascending (exact)
        self.xs_of = [sorted(r, key=exact_float) for r in required]
        self._layers, self._index = layers, index
        # per beam and stretch its length as a float, and its group (members, layers):
        # neither depends on the piece rule, and the exact subtraction and the layers'
        # cover cost a 20-level chain's every subdivision (two more a plan than the
        # plan's own, generous_range's) 0.6 ms of SymPy
        self._lengths = [[exact_float(xb - xa) for xa, xb in itertools.pairwise(xs)]
                         for xs in self.xs_of]
        self._groups = [[self.group(i, xa, xb) for xa, xb in itertools.pairwise(xs)]
                        for i, xs in enumerate(self.xs_of)]
        # per beam and stretch, the stretch of each member of its group that starts there
        # too (a layer's points are its beams' alike): (beam, stretch index) pairs
        starts = [None] * len(self.xs_of)     # per beam of a group, start -> its stretch

        def slot(j, x):
            if starts[j] is None:
                starts[j] = {v: k for k, v in enumerate(self.xs_of[j][:-1])}
            return (j, starts[j][x]) if x in starts[j] else None
        self._slots = [[[(i, k)] if len(members) == 1 else
                        [sl for sl in (slot(j, xs[k]) for j in members) if sl is not None]
                        for k, (members, _) in enumerate(groups)]
                       for i, (xs, groups) in enumerate(zip(self.xs_of, self._groups))]
        self._memory: dict = {}         # piece rule's key -> subdivide's answer
        self._waves: dict = {}          # (beam, radius) -> its largest wave number

    @functools.cached_property
    def _whole(self) -> list:
        """Per beam, the beam as one segment (its constants as floats are kept on it)."""
        return [beam.segment(beam.L) for beam in self.model.beams]

    def group(self, i, xa, xb):
        """The beams joined to ``i`` over ``[xa, xb]`` through layers, and those layers."""
        model, layers = self.model, self._layers
        cover = [la for la in layers
                 if exact_float(la[2]) <= exact_float(xa) and exact_float(xb) <= exact_float(la[3])]
        if not cover:
            return [i], []
        members, used = joined(range(len(model.beams)), [la[4] for la in cover],
                               self._index)[i]
        return list(members), [la for la in cover if la[4] in used]

    def _longest(self, piece, i, xa, xb, used, size, s):
        """The longest piece ``piece`` allows of beam ``i`` over the stretch ``[xa, xb]``
        (``size`` long) under the layers ``used``; ``s`` the beam's largest wave number
        for the rule's range (:meth:`_wave_number`) or None."""
        beam = self.model.beams[i]
        k = c = 0
        if used:
            k = sum((la[4].k for la in used if i in la[:2]), sp.Integer(0))
            c = sum((la[4].c for la in used if i in la[:2]), sp.Integer(0))
        if k == 0 and c == 0:
            if s is not None:
                # the plans' rule on an Euler-Bernoulli beam, whose largest wave number is
                # the beam's: a segment per stretch cost most of a chain's cut (the beam's
                # whole segment tells a long piece its constants)
                if piece.key[3]:
                    # (a plan whose counts add J0: past the clamped-clamped frequencies)
                    return clamped_long_piece(self._whole[i], s, size, piece.key[1])
                return long_piece(self._whole[i], s, size, piece.key[2], piece.key[1])
            return piece(beam, beam.segment(xb - xa))
        # |X| of the coupled piece is at most that of a beam on the foundation
        # kw + 2 |k + c lam| <= kw + 2 k + 2 c |lam|: with the range |lam|**2 <= radius
        # the piece rule knows (plans tell it), else through 2 c |lam| <= m |lam|**2 +
        # c**2 / m (a beam of mass 2 m)
        length = xb - xa
        radius = getattr(piece, "radius", None)
        if radius is not None:
            lam = sp.Rational(math.sqrt(max(float(radius), 0.0))) * (1 + sp.Rational(1, 10**9))
            bound = EulerBernoulliSegment(beam.EI, beam.m, length, beam.kw + 2 * k + 2 * c * lam)
            short = piece(beam, bound)
            if all(la[4].c == 0 for la in used) and hasattr(piece, "key"):
                # undamped layers: long pieces, condensed chains of short ones
                return max(short, layered_piece(beam.segment(length), bound, radius,
                                                piece.key[2], short))
            return short
        m = beam.m * (2 if c != 0 else 1)
        return piece(beam, EulerBernoulliSegment(beam.EI, m, length,
                                                 beam.kw + 2 * k + c**2 / beam.m))

    def _wave_number(self, i: int, radius: float):
        """The largest wave number of beam ``i`` for ``|lam|**2 <= radius`` if it is an
        Euler-Bernoulli beam (:func:`~symtmm.numeric.plan.wave_number_bound`), else None."""
        if (i, radius) not in self._waves:
            seg = self._whole[i]
            self._waves[(i, radius)] = wave_number_bound(seg, radius) \
                if isinstance(seg, EulerBernoulliSegment) else None
        return self._waves[(i, radius)]

    def estimate(self, radius: float, nu_max: float) -> int:
        """About the pieces a plan for ``|lam|**2 <= radius`` cuts: every stretch into
        pieces of at most ``nu_max`` over its beam's largest wave number
        (:func:`~symtmm.numeric.plan.wave_number_bound`), layers and the other theories'
        rules left out. One float per stretch: :meth:`subdivide` makes a segment per
        stretch, and tells the pieces exactly."""
        total = 0
        for whole, lengths in zip(self._whole, self._lengths):
            s = wave_number_bound(whole, radius)
            for length in lengths:
                total += max(1, math.ceil(length / wave_piece(s, length, nu_max) - 1e-9))
        return total

    def subdivide(self, piece) -> tuple:
        """``(subdivisions, groups, ratios)`` for the length rule ``piece(beam, segment)``:
        the pieces per ``(beam, stretch)`` (the stretch's index along the beam); per coupled
        stretch ``(beam, stretch)`` of its group's first beam, ``(beams, layers)``; and per
        stretch (a group's once
        per beam) its length over the longest piece the rule allows (the pieces are
        ``ceil`` of it), in the order of the beams and their stretches. Remembered per
        rule that has a ``key`` (:func:`~symtmm.numeric.plan.piece_rule`)."""
        key = getattr(piece, "key", None)
        if key is not None and key in self._memory:
            return self._memory[key]
        model = self.model
        subdivisions: dict = {}          # (beam, stretch) -> number of pieces
        groups: dict = {}                # (beam, stretch) -> (beams, layers), coupled ones
        ratios = []
        total = 0
        waves = [None if key is None else self._wave_number(i, key[0])
                 for i in range(len(model.beams))]
        for i, xs in enumerate(self.xs_of):
            for k, ((xa, xb), size, (members, used)) in enumerate(
                    zip(itertools.pairwise(xs), self._lengths[i], self._groups[i])):
                ratio = max(size / self._longest(piece, j, xa, xb, used, size, waves[j])
                            for j in members)
                ratios.append(ratio)
                total += ratio
                if not total <= MAX_PIECES:
                    # (before the exact coordinates of millions of pieces are made)
                    raise ComputationError(
                        f"beam '{model.beams[i].name}' would need more than {MAX_PIECES} "
                        "pieces for this frequency range: its waves are far shorter than it "
                        "(a foundation kw or a layer k far stiffer than its EI / L**4, or a "
                        "range far above its first modes); soften them or lower the range")
                n_sub = max(1, math.ceil(ratio - 1e-9))
                for slot in self._slots[i][k]:
                    subdivisions[slot] = max(subdivisions.get(slot, 1), n_sub)
                if len(members) > 1:
                    groups[(i, k)] = (members, used)
        if key is not None:
            self._memory[key] = (subdivisions, groups, ratios)
        return subdivisions, groups, ratios


class Mesh:
    """Nodes, segments and freedoms of a model for a dynamic-stiffness assembly.

    Every beam is cut at its ends, its point elements and the attachments of
    rigid bodies, then each part into equal pieces no longer than
    ``piece(beam, segment)`` (``segment`` the part as one element). Each node
    has the freedoms ``Y`` and ``Theta``, each rigid body ``Y_c`` and (if it
    rotates) ``Theta_c``. Boundary conditions and attachments are linear
    constraints among them; they are eliminated exactly, and every freedom
    becomes a *combination* ``((index, coefficient), ...)`` of the free ones
    (numbered ``0 .. size - 1`` along ``x``; the empty combination is a fixed
    freedom).

    Parameters
    ----------
    model : Model
        Resolved and numeric.
    piece : callable
        ``piece(beam, segment) -> float``: the longest piece allowed.
    stretches : Stretches, optional
        The model's :class:`Stretches` where made already.

    Attributes
    ----------
    stretch_ratios : list
        Per stretch, its length over the longest piece (:meth:`Stretches.subdivide`).
    node_x : list
        The exact coordinate of every node (along its beam's axis).
    segments : list
        ``(beam index, segment, left node, right node)``; for a piece of beams joined by
        layers ``(beam indices, CoupledSegment, left nodes, right nodes)`` (tuples).
    segment_places : list
        Per segment, the combinations of ``(Y0, Theta0, Y1, Theta1)`` (of a coupled
        piece: ``Y0`` of each beam, then ``Theta0``, ``Y1``, ``Theta1`` of each).
    point_places : list
        ``(combinations, element)`` per point element, on the element's ``dofs``.
    body_places : list
        ``(combinations, masses)`` per rigid body: ``(Y_c[, Theta_c])`` and
        ``(M[, J])`` (exact).
    size, bandwidth : int
        Number of free freedoms and half-bandwidth of the assembled matrix.
    rotation_length : list
        Per free freedom, a length scale if it is a rotation (the longest
        segment at its node), else None.

    Examples
    --------
    A fork: a clamped trunk whose free end is joined rigidly to two branches.
    The joint's two freedoms replace the three beam ends' six:

    >>> from symtmm.model import Attachment, Beam, Model, RigidBody
    >>> beams = (Beam("t", 1, 1, 1, left="clamped"), Beam("a", 1, 1, 1, x0=1),
    ...          Beam("b", 1, 1, 1, x0=1))
    >>> joint = RigidBody("j", (Attachment("t", 1), Attachment("a", 1), Attachment("b", 1)))
    >>> mesh = Mesh(Model(beams, bodies=(joint,)), lambda beam, seg: float(seg.l))
    >>> mesh.size, mesh.segment_places[1]     # (Y0, Theta0) of branch a are the joint's
    (6, (((0, 1),), ((1, 1),), ((2, 1),), ((3, 1),)))
    """

    def __init__(self, model: Model, piece, stretches: Stretches | None = None):
        self.model = model
        self._index = {b.name: i for i, b in enumerate(model.beams)}
        self._cut(piece, stretches)
        subs = self._eliminate()
        number = self._number(subs)

        def combo(v):
            if v not in subs:
                return ((number[v], sp.Integer(1)),)
            return tuple(sorted((number[w], c) for w, c in subs[v].items()))

        def places(ia, ib):
            if not isinstance(ia, tuple):
                return tuple(combo(("n", n, k)) for n in (ia, ib) for k in (0, 1))
            # a coupled piece: Y0 of every beam, Theta0 of every beam, then Y1, Theta1
            return tuple(combo(("n", n, k)) for ends in (ia, ib) for k in (0, 1) for n in ends)
        self.segment_places = [places(ia, ib) for _, _, ia, ib in self.segments]
        self.point_places = []
        for x, el in point_elements(model):
            at = [self._node(name, x) for name in el.beams]
            self.point_places.append(
                (tuple(combo(("n", at[lvl], 0 if var == "Y" else 1)) for lvl, var in el.dofs), el))
        self.body_places = []
        for bi, body in enumerate(model.bodies):
            frame = model.body_frame(body)
            ks = [frame.index(label) for label in frame.freedoms]
            masses = tuple(frame.mass(body, label) for label in frame.freedoms)
            self.body_places.append((tuple(combo(("b", bi, k)) for k in ks), masses))
            for label, k, c in body.ground:
                # an elastic support of the body: a grounded spring on its freedom
                if k != 0 or c != 0:
                    self.point_places.append(((combo(("b", bi, frame.index(label))),),
                                              GroundSpring(body.name, k, c)))
            for att, row in zip(body.attachments, frame.rows):
                if att.elastic:
                    # a spring from the beam's motion to the body's point there, a_i . q:
                    # a coupling on those two combinations
                    at = {}
                    for label, f in row.items():
                        for i, c in combo(("b", bi, frame.index(label))):
                            at[i] = at.get(i, 0) + _canonical(f) * c
                    point = tuple(sorted((i, c) for i, c in at.items() if c != 0))
                    beam = combo(("n", self._node(att.beam, att.x), 0))
                    self.point_places.append(
                        ((beam, point), Coupling(att.beam, body.name, att.k, att.c)))
        body_index = {b.name: bi for bi, b in enumerate(model.bodies)}
        for link in model.links:
            ends = [(body_index[body.name], row) for body, row in model.link_rows(link) if row]
            if link.M == 0 or not ends:
                continue
            # the bar's mass moves with its first end along it: M (t . q)**2
            bi, row = ends[0]
            at = {}
            for label, a in row.items():
                for i, c in combo(("b", bi, FREEDOM_INDEX[label])):
                    at[i] = at.get(i, 0) + _canonical(a) * c
            point = tuple(sorted((i, c) for i, c in at.items() if c != 0))
            if point:
                self.body_places.append(((point,), (link.M,)))
        self.bandwidth = 0
        for places in (self.segment_places + [p for p, _ in self.point_places]
                       + [p for p, _ in self.body_places]):
            live = [i for c in places for i, _ in c]
            if live:
                self.bandwidth = max(self.bandwidth, max(live) - min(live))

    def _node(self, beam_name: str, x) -> int:
        return self._beam_nodes[self._index[beam_name]][_canonical(x)]

    def _cut(self, piece, stretches=None):
        """Nodes along every beam and the segments between them.

        Beams joined by layers are cut at the same points over each layer (the ends of
        the layer and every point of either beam there), into the same number of pieces:
        each piece of the group is one coupled segment
        (:class:`~symtmm.elements.layer.CoupledSegment`).
        """
        model = self.model
        self._nodes = []                 # (x float, beam index) per node
        self.node_x = []                 # exact x per node
        self._node_length = []           # the longest segment at each node
        self.segments = []
        self._beam_nodes = []            # per beam: exact x -> node
        stretches = stretches or Stretches(model)
        xs_of = stretches.xs_of
        subdivisions, groups, self.stretch_ratios = stretches.subdivide(piece)
        doublings = getattr(piece, "doublings", None)
        first_of = []                    # per beam, per stretch its first node (in points)
        for b_idx, beam in enumerate(model.beams):
            xs = xs_of[b_idx]
            points, first = [xs[0]], []
            for k, (xa, xb) in enumerate(itertools.pairwise(xs)):
                n_sub = subdivisions[(b_idx, k)]
                first.append(len(points) - 1)
                if n_sub > 1:
                    step = xb - xa
                    points += [xa + step * sp.Rational(j, n_sub) for j in range(1, n_sub)]
                points.append(xb)           # (the stretch's end as it is: most have one piece)
            first.append(len(points) - 1)
            first_of.append(first)
            ids = list(range(len(self._nodes), len(self._nodes) + len(points)))
            self._nodes += [(exact_float(x), b_idx) for x in points]
            self.node_x += points
            self._node_length += [0.0] * len(points)
            self._beam_nodes.append(dict(zip(points, ids)))
        base = 0
        for b_idx, beam in enumerate(model.beams):
            first = first_of[b_idx]
            points = self.node_x[base:base + first[-1] + 1]
            for k in range(len(first) - 1):
                members, used = groups.get((b_idx, k), ([b_idx], []))
                if members[0] != b_idx:
                    continue                # the group's first beam makes the coupled piece
                seg = seg_length = None
                for p in range(first[k], first[k + 1]):
                    if p % 1024 == 0:
                        check_time()    # (tens of thousands of pieces take seconds)
                    xa_node, xb_node = points[p], points[p + 1]
                    length = xb_node - xa_node
                    # (a stretch's pieces are alike: one segment serves them all)
                    if seg is None or length != seg_length:
                        seg_length, size = length, exact_float(length)

                        seg = self._piece(beam, members, used, length)
                        j = doublings(seg) if doublings else 0
                        if j:
                            # a long piece of another theory or of beams joined by a
                            # layer: a chain of 2**j short ones
                            seg = Condensed(self._piece(beam, members, used, length / 2**j), j)
                    if len(members) == 1:
                        ia, ib = (base + p,), (base + p + 1,)
                        self.segments.append((b_idx, seg, base + p, base + p + 1))
                    else:
                        ia = tuple(self._beam_nodes[j][xa_node] for j in members)
                        ib = tuple(self._beam_nodes[j][xb_node] for j in members)
                        self.segments.append((tuple(members), seg, ia, ib))
                    for i in ia + ib:
                        self._node_length[i] = max(self._node_length[i], size)
            base += first[-1] + 1

    def _piece(self, beam, members, used, length):
        """The element of a piece ``length`` long of ``beam`` alone, or of the beams
        ``members`` joined by the layers ``used``."""
        if len(members) == 1:
            return beam.segment(length)
        return member(self.model.beams, tuple(members), [la[4] for la in used], self._index,
                      length)

    def _number(self, subs) -> dict:
        """Number the free freedoms along ``x``; a body's next to its first attachment's node.

        Sets :attr:`size` and :attr:`rotation_length`; returns freedom -> index.
        """
        nodes, index = self._nodes, self._index
        place = {}
        for node, (x, b_idx) in enumerate(nodes):
            for k in (0, 1):
                place[("n", node, k)] = (x, b_idx, node, k)
        body_node = []
        for bi, body in enumerate(self.model.bodies):
            first = min(body.attachments, key=lambda a: (exact_float(a.x), index[a.beam]))
            node = self._node(first.beam, first.x)
            body_node.append(node)
            frame = self.model.body_frame(body)
            for label in frame.freedoms:
                k = frame.index(label)
                place[("b", bi, k)] = nodes[node] + (node, 2 + 3 * bi + k)
        free = sorted((v for v in place if v not in subs), key=place.get)
        self.size = len(free)
        self.rotation_length = [
            None if v[2] != 1 else
            self._node_length[v[1] if v[0] == "n" else body_node[v[1]]] or 1.0 for v in free]
        return {v: i for i, v in enumerate(free)}

    def _constraints(self) -> list:
        """``(body name or None, {freedom: coefficient})``: every ``sum = 0`` to eliminate.

        Attachments first (``Y - a_i . q``: the member's motion there is the body's, see
        :class:`~symtmm.model.BodyFrame`; and ``Theta - Theta_c`` when rigid), then the boundary
        conditions (a freedom that is zero).
        """
        constraints = []
        for bi, body in enumerate(self.model.bodies):
            frame = self.model.body_frame(body)
            for att, row, turns in zip(body.attachments, frame.rows, frame.turns):
                if att.elastic:
                    continue                # a spring, not a constraint (see point_places)
                node = self._node(att.beam, att.x)
                c = {("n", node, 0): sp.Integer(1)}
                for label, a in row.items():
                    c[("b", bi, frame.index(label))] = -_canonical(a)
                constraints.append((body.name, c))
                if turns:
                    # (a support that holds the body's rotation holds the member's)
                    c = {("n", node, 1): sp.Integer(1)}
                    if "Theta" in frame.freedoms:
                        c[("b", bi, 1)] = sp.Integer(-1)
                    constraints.append((body.name, c))
        index = {b.name: bi for bi, b in enumerate(self.model.bodies)}
        for link in self.model.links:
            ends = self.model.link_rows(link)
            held = GROUND in link.ends or any(not row for _, row in ends)
            if len([row for _, row in ends if row]) == 2 or held:
                c = {}
                for body, row in ends:
                    for label, a in row.items():
                        c[("b", index[body.name], FREEDOM_INDEX[label])] = \
                            _canonical(a)
                if c:
                    constraints.append((ends[0][0].name if ends else None, c))
        for beam, nodes in zip(self.model.beams, self._beam_nodes):
            ends = sorted(nodes, key=exact_float)
            for x, bc in ((ends[0], beam.left), (ends[-1], beam.right)):
                for k in BC_FREEDOMS_FIXED[bc]:
                    constraints.append((None, {("n", nodes[x], k): sp.Integer(1)}))
        return constraints

    def _eliminate(self) -> dict:
        """Eliminate the constraints: ``{freedom: {free freedom: exact coefficient}}``.

        Constraints are taken in turn, each with the current eliminations
        substituted; a node freedom goes first (a slave, coefficient 1), then a
        body's ``Y_c``, then its ``Theta_c``. :attr:`pivot_product` is the product
        of the squared coefficients of the freedoms eliminated:
        ``det R = det K * prod det U12 * pivot_product``. A constraint reduced to
        ``0 = 0`` means a body held more times than it has freedoms (e.g. joining
        two clamped ends): its reactions are statically indeterminate and
        ``det R`` vanishes for every ``lam``; that model is refused.
        """
        constraints = self._constraints()
        # (in Python's integers and fractions where the coefficients are rational, as
        # mostly they are, 1 and -1: SymPy's arithmetic cost a 20-span beam's supports
        # 0.9 ms of its 2.6 ms mesh; back to SymPy numbers at the end)
        constraints = [(name, {v: _fast(c) for v, c in c_.items()}) for name, c_ in constraints]
        subs: dict = {}
        users: dict = {}        # freedom -> the eliminated ones whose expressions hold it
        pivot_product = 1
        for name, constraint in constraints:
            expr: dict = {}
            for v, c in constraint.items():
                for w, cw in subs.get(v, {v: 1}).items():
                    expr[w] = expr.get(w, 0) + c * cw
            expr = {w: c for w, c in expr.items() if c != 0}
            if not expr:
                # (boundary conditions come after the attachments: a redundant one falls
                # on a node held by a body)
                body = name or next(n for n, c in constraints if n and set(c) & set(constraint))
                hint = ("; inextensible members that hold a joint along one line twice "
                        "(collinear between supports, a star of them) are not supported: "
                        "give one of them EA instead of inextensible = true"
                        if self.model.links else "")
                raise ModelError("held more times than it has freedoms (statically "
                                 "indeterminate: its reactions are not determined and the "
                                 "characteristic determinant vanishes identically)" + hint,
                                 field=f"body '{body}'.attach", source=self.model.source)
            # a node's freedom first, then a body's translations, then its rotation
            pivot = min(expr, key=lambda v: (v[0] == "b", v[2] == 1, v[2], v[1]))
            cp = expr.pop(pivot)
            pivot_product *= cp**2
            value = {w: -_ratio(c, cp) for w, c in expr.items()}
            # (only the expressions that hold the pivot: scanning all of them made this
            # quadratic in the constraints, 1.2 ms of a 20-span beam's 3 ms mesh)
            for held in users.pop(pivot, ()):
                ex = subs[held]
                c = ex.pop(pivot)
                for w, cw in value.items():
                    sum_ = ex.get(w, 0) + c * cw
                    if sum_ == 0:
                        ex.pop(w, None)
                        users[w].discard(held)
                    else:
                        ex[w] = sum_
                        users.setdefault(w, set()).add(held)
            subs[pivot] = value
            for w in value:
                users.setdefault(w, set()).add(pivot)
        self.pivot_product = _sympy(pivot_product)
        return {v: {w: _sympy(c) for w, c in ex.items()} for v, ex in subs.items()}


def _fast(c):
    """A SymPy rational as a Python integer or Fraction (exact, and a hundred times
    faster to add and multiply); any other number as it is."""
    if isinstance(c, sp.Integer):
        return int(c)
    if isinstance(c, sp.Rational):
        return Fraction(int(c.p), int(c.q))
    return c


def _ratio(c, cp):
    """``c / cp`` exactly: a fraction of integers (an integer where it divides)."""
    if isinstance(c, int) and isinstance(cp, int):
        q = Fraction(c, cp)
        return int(q) if q.denominator == 1 else q
    return c / cp


def _sympy(c):
    """The SymPy number of a :func:`_fast` one (SymPy's own ``1`` for 1: callers test
    ``is S.One``)."""
    if isinstance(c, int):
        return sp.Integer(c)
    if isinstance(c, Fraction):
        return sp.Rational(c.numerator, c.denominator)
    return c


def _segment_null_rows(beam, length) -> list:
    """Rows ``r`` with ``r . (Y0, Theta0, Y1, Theta1) = 0`` exactly on the static null space
    of one piece of ``beam`` (its motions without strain energy).

    Without axial force or foundation a piece moves rigidly (``Theta1 = Theta0``,
    ``Y1 = Y0 + l Theta0``; for a shear-flexible piece ``Theta`` is the section's
    rotation, which a rigid motion turns with the line); an axial force
    resists every turn (its energy ``N Y'**2``), leaving the translation; a
    foundation resists every motion. A rod (:func:`symtmm.model.rod`) translates and
    twists rigidly, each on its own.
    """
    one, zero = sp.Integer(1), sp.Integer(0)
    if beam.is_rod:
        # axial motion and twist are independent: each is rigid (a foundation holds the
        # axial one), and neither turns the other
        rows = [[zero, -one, zero, one]]
        if beam.kw != 0:
            return rows + [[one, zero, zero, zero], [zero, zero, one, zero]]
        return rows + [[-one, zero, one, zero]]
    if beam.kw != 0:
        return [[one, zero, zero, zero], [zero, one, zero, zero],
                [zero, zero, one, zero], [zero, zero, zero, one]]
    if beam.N != 0:
        return [[zero, one, zero, zero], [zero, zero, zero, one], [-one, zero, one, zero]]
    return [[zero, -one, zero, one], [-one, -length, one, zero]]


def _coupled_null_rows(model: Model, beams, seg) -> list:
    """Rows on the local freedoms of a coupled piece (``Y0``, ``Theta0``, ``Y1``, ``Theta1`` of
    each beam in turn) vanishing on its static null space: each beam's own, and equal
    deflections at both ends of two beams joined by a layer of stiffness ``k != 0`` (its
    energy ``k (Y_i - Y_j)**2`` stops every relative motion of the rigid pieces)."""
    n = len(beams)
    rows = []
    for p, b in enumerate(beams):
        for local in _segment_null_rows(model.beams[b], seg.l):
            row = [sp.Integer(0)] * (4 * n)
            for q, v in enumerate(local):
                row[q * n + p] = v
            rows.append(row)
    for i, j, k, _ in seg.couplings:
        if k != 0:
            for end in (0, 2):
                row = [sp.Integer(0)] * (4 * n)
                row[end * n + i], row[end * n + j] = sp.Integer(1), sp.Integer(-1)
                rows.append(row)
    return rows


def _coupled_damping(seg) -> sp.Matrix:
    """The layers' damping matrix of a coupled piece on rigid motions of its beams:
    ``c int_0^l (u_i - u_j)**2`` with ``u(s) = Y0 + s Theta0`` (what :func:`zero_order`
    needs: it only ever meets the static null space, where every piece is rigid)."""
    n = seg.size
    C = sp.zeros(4 * n, 4 * n)
    l = seg.l
    for i, j, _, c in seg.couplings:
        if c == 0:
            continue
        a = sp.zeros(4 * n, 1)
        b = sp.zeros(4 * n, 1)
        a[i], a[j] = 1, -1
        b[n + i], b[n + j] = 1, -1
        C += c * (l * a * a.T + l**2 / 2 * (a * b.T + b * a.T) + l**3 / 3 * b * b.T)
    return C


def _static_null_space(model: Model, mesh: Mesh | None = None, basis: bool = True):
    """``(mesh, basis)``: the exact null space of the static ``K(0)``, one basis vector
    (a list over the free freedoms) per rigid-body mode (see :func:`static_nullity`);
    on ``mesh`` where given (a mesh of ``model`` cut any finer, as a plan's is: cutting a
    piece in two adds a node, not a null motion), else on one cut at the required points
    only. ``basis=False``: ``(mesh, nullity)`` only, from the sparse rank (the dense null
    space of a plan's mesh of 11,000 freedoms took 76 s and 4.9 GB, uninterruptible)."""
    from sympy.polys.constructor import construct_domain
    from sympy.polys.matrices import DomainMatrix

    def coarse():
        return Mesh(model.require_numeric().resolved(), lambda beam, seg: exact_float(seg.l))

    own = mesh is None
    if own:
        mesh = coarse()
    try:
        # rational models (most): the rows in QQ's numbers, each SymPy number converted
        # once (SymPy's arithmetic was two thirds of a 10-level chain's null space)
        rows, domain = _null_rows(_local_null_rows(mesh), _to_qq), QQ
    except CoercionFailed:
        # an algebraic field's rank grows steeply with the size (a frame with an inclined
        # member: 0.25 s on its own mesh, 12 s on a plan's of 87 freedoms): the coarse mesh
        if not own:
            mesh = coarse()
        rows, domain = _null_rows(_local_null_rows(mesh), lambda c: c), None
    n = mesh.size
    if not rows:
        return mesh, [[sp.Integer(int(i == j)) for i in range(n)] for j in range(n)] \
            if basis else n
    # each row scaled by its first entry: springs of irrational stiffness give rational rows
    rows = [{i: c / row[min(row)] for i, c in row.items()} for row in rows]
    if domain is None:
        domain, values = construct_domain([c for row in rows for c in row.values()])
        it = iter(values)
        rows = [{i: next(it) for i in row} for row in rows]
    dm = DomainMatrix(dict(enumerate(rows)), (len(rows), n), domain)
    rank = dm.rank()
    if not basis:
        return mesh, n - rank
    if rank == n:
        return mesh, []
    basis = dm.to_dense().nullspace().to_Matrix()
    return mesh, [list(basis.row(k)) for k in range(basis.rows)]


def _whole(seg):
    """A piece of beams joined by layers as one element: a condensed chain of them
    (:class:`~symtmm.numeric.segments.Condensed`) as the joined piece of its length, whose
    static null space and damping it has."""
    return seg.inner.with_length(seg.l) if isinstance(seg, Condensed) else seg


def _local_null_rows(mesh: Mesh) -> list:
    """``(places, rows)`` per element of ``mesh``: the conditions of its static null space
    on its local freedoms."""
    model = mesh.model
    out = []
    for (b_idx, seg, _, _), places in zip(mesh.segments, mesh.segment_places):
        if isinstance(b_idx, tuple):
            out.append((places, _coupled_null_rows(model, b_idx, _whole(seg))))
        else:
            out.append((places, _segment_null_rows(model.beams[b_idx], seg.l)))
    for places, element in mesh.point_places:
        out.append((places, [[c[0] for c in row] for row in stiffness_coefficients(element)]))
    return out


@functools.lru_cache(maxsize=4096)
def _to_qq(c):
    """``c`` (an exact number) in QQ, once per number; ``CoercionFailed`` if irrational."""
    return QQ.from_sympy(sp.sympify(c))


def _null_rows(local_rows, number) -> list:
    """The rows of the null space conditions on the free freedoms (``{index: coefficient}``,
    zeros dropped) from ``(places, rows over the places)``, in the numbers ``number`` makes
    of SymPy's."""
    rows = []
    for places, local in local_rows:
        combos = [[(i, number(c)) for i, c in combo] for combo in places]
        for coefs in local:
            row: dict = {}
            for coef, combo in zip(coefs, combos):
                if coef == 0:
                    continue
                coef = number(coef)
                for index, c in combo:
                    row[index] = row.get(index, 0) + coef * c
            row = {i: c for i, c in row.items() if c != 0}
            if row:
                rows.append(row)
    return rows


def static_nullity(model: Model, mesh: Mesh | None = None) -> int:
    """The number of rigid-body (zero-frequency) modes: the nullity of the static ``K(0)``.

    ``K(0)`` is the sum of the elements' static stiffnesses, each positive
    semi-definite in a model that is not buckled, so its null space is the
    intersection of theirs: the freedoms on which every piece moves without
    strain energy (:func:`_segment_null_rows`) and every spring is unstretched
    (the rows of its exact static stiffness). The rank of those rows is exact
    (rational arithmetic where the model is rational), whatever the axial force
    or foundation: only the structure of each null space enters, never the
    transcendental values of a stiffness.

    Under a compression short of buckling a piece's static stiffness is indefinite;
    its null space is still the translation, and the model's is the same unless the
    compression is critical (which the buckling check, counting at ``omega**2 < 0``,
    reports).

    ``mesh``: a mesh of ``model`` to work on (a plan's, already built for the search:
    the 20-span beam's null space costs half as much on it as with a mesh of its own);
    a model with irrational coefficients (an inclined member, a spring of stiffness
    ``sqrt(2)``) is taken on its own coarse mesh.

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> ff = dict(left="free", right="free")
    >>> static_nullity(Model((Beam("b", 1, 1, 1, **ff),)))
    2
    >>> static_nullity(Model((Beam("b", 1, 1, 1, N=3, **ff),)))     # tension resists turning
    1
    >>> static_nullity(Model((Beam("a", 1, 1, 1, **ff), Beam("b", 1, 1, 1, **ff)),
    ...                      (Spring("a", "b", "1/2", 10),)))         # joined at one point
    3
    """
    return _static_null_space(model, mesh, basis=False)[1]


def zero_order(model: Model) -> tuple:
    """``(r, order)``: the rigid-body modes and the order of the zero of ``Delta`` at ``lam = 0``.

    With ``Z`` a basis of the ``r`` rigid-body motions (the null space of ``K(0)``)
    and ``C`` the dashpots' matrix, ``Delta(lam) = det(K(0) + C lam + M lam**2 + ...)``
    vanishes at 0 to the order ``2 r - rank(Z^T C Z)``: a Schur complement on the
    rigid motions leaves ``lam**r det(Z^T C Z + lam Z^T M Z + ...)``, and ``Z^T M Z``
    is positive definite on the null space of ``Z^T C Z`` (every rigid motion moves
    mass). A free rigid motion is a double zero; one resisted by a dashpot alone is
    a simple zero, beside a real negative eigenvalue (``M lam + c = 0``).

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> pf = Beam("b", 1, 1, 1, left="pinned", right="free")
    >>> zero_order(Model((pf,)))
    (1, 2)
    >>> zero_order(Model((pf,), (Spring("b", "ground", "3/5", 0, 2),)))   # a pure dashpot
    (1, 1)
    """
    from .elements.base import stiffness_coefficients

    mesh, basis = _static_null_space(model)
    r = len(basis)
    if r == 0:
        return 0, 0
    CZ = sp.zeros(r, r)
    # (C: each point element's coefficients of lam**1, kept by its class and parameters;
    # differentiating its S(lam) in SymPy cost a damped example a tenth of its solve)
    dampers = [(places, sp.Matrix([[p[1] if len(p) > 1 else 0 for p in row]
                                   for row in stiffness_coefficients(element)]))
               for places, element in mesh.point_places]
    dampers += [(places, _coupled_damping(_whole(seg))) for (b, seg, _, _), places
                in zip(mesh.segments, mesh.segment_places) if isinstance(b, tuple)]
    for places, C in dampers:
        if C.is_zero_matrix:
            continue
        local = [[sum((c * z[i] for i, c in combo), sp.Integer(0)) for combo in places]
                 for z in basis]
        for a in range(r):
            for b in range(r):
                CZ[a, b] += sum(local[a][i] * C[i, j] * local[b][j]
                                for i in range(C.rows) for j in range(C.cols))
    return r, 2 * r - CZ.rank()
