"""A model compiled once for the dynamic-stiffness kernel.

:class:`StiffnessPlan` is the one artefact the numeric layer evaluates: the
mesh of the model (:class:`symtmm.mesh.Mesh`: nodes at beam ends, point
elements and attachments, every beam cut into pieces short enough for the
frequency range, rigid bodies and boundary conditions eliminated as exact
constraints), its freedoms renumbered for a narrow band, and tables that say
where every number goes:

* the distinct segment **kinds** (equal constants, equal matrices: the pieces of
  one span share one) with their exact constants, each family evaluated by
  :mod:`symtmm.numeric.segments`;
* a **scatter** of every segment's 4x4 stiffness, every point element's
  polynomial ``K0 + C lam + M lam**2`` and every body's inertia into the upper
  band of ``K``: ``(target, source, exact coefficient)`` triples, pre-sorted by
  target, so that assembly is one gather, one multiplication and one segmented
  sum in any arithmetic;
* a diagonal **scaling** by powers of two (exact in every arithmetic) that gives
  the static ``K`` a diagonal near 1 whatever the units, and the exact constant
  of the determinant identity ``det R = det K * prod det U12 * P``
  (:class:`symtmm.numeric.evaluator.Evaluator`).

The exact tables are converted once per arithmetic and precision
(:meth:`StiffnessPlan.tables`).

Cost. One assembly costs ``O(segments)``; the banded ``LDL^T`` costs
``O(n b**2)`` with ``n`` freedoms and half-bandwidth ``b``. The freedoms are
numbered by reverse Cuthill–McKee on the freedom graph when that narrows the
band: a beam's freedoms then come together and a spring only joins the freedoms
of the two beams it touches, so a chain of ``N`` levels has ``b`` independent of
``N`` and the whole evaluation is linear in the size of the model.
"""

from __future__ import annotations

import math
import threading
from collections import OrderedDict, deque

import numpy as np
import sympy as sp

from ..deadline import check as check_time
from ..elements import EulerBernoulliSegment
from ..elements.base import stiffness_coefficients
from ..elements.layer import CoupledSegment
from ..expr import exact_float
from .arith import DOUBLE, Arithmetic, exact_key
from .segments import Condensed, kind, kind_key, kind_order, kind_size, kind_tables

__all__ = ["StiffnessPlan", "NU_MAX", "piece_length", "piece_rule", "wave_piece", "generous_range",
           "long_piece", "condensed_piece", "layered_piece", "LONG_FROM", "NU_LONG",
           "rcm_order", "wave_number_bound", "plan_for", "design_range", "design_below",
           "clear_plans", "PLAN_MODELS", "plan_key", "crowding", "CROWDED", "CROWDED_BY_ONE_BEAM"]

#: SymPy's one (a singleton): most coefficients of the scatter are it.
ONE = sp.S.One

#: Largest ``|s| l`` of a piece (``beta l`` for Euler–Bernoulli) anywhere in the plan's range:
#: below the first clamped-clamped root ``beta l = 4.730``, so no piece has a
#: clamped-clamped eigenvalue in the range (``J0 = 0``, ``det U12 != 0``), and no
#: digit is lost to the growth of long pieces.
NU_MAX = 3.0

#: An Euler–Bernoulli stretch that pieces of :data:`NU_MAX` would cut into more than this
#: many is cut into **long pieces** (:data:`LONG_GAIN`)
#: (:func:`long_piece`): a beam whose waves are far shorter than it is (a soft beam on a
#: stiff foundation: ``kw L**4 / EI`` of ``1e9`` cut it into hundreds of pieces, and the
#: proofs' dense determinant of hundreds of freedoms cost half a second a point). Not fewer:
#: a plan with condensed pieces leaves the compiled kernels for numpy, and a beam in
#: tension cut into 26 pieces solved three times slower in 10 condensed ones (8 asked);
#: nor more: with 32 the campaign models of the stiff class solved up to 2.8 times slower
#: (a Rayleigh beam on a foundation beside a short Euler–Bernoulli one: 2.1 s and 5.8 s).
LONG_FROM = 16
#: ... and where long pieces take at most ``1 / LONG_GAIN`` as many. A plan with long pieces
#: leaves the compiled ball kernel (its series stop at a short piece's ``|x|``) for Arb; its
#: double batches stay compiled, the long kinds' values given by numpy
#: (:func:`symtmm.numeric.multiword.double_band`; before, the whole batch went to numpy, a
#: few times slower a freedom, and a campaign model cut into 745 freedoms against 1725
#: went from 31 s to past 60 s). A gain of 3 took the long pieces from two other campaign
#: models (2.7 and 3.5 s again past 60 s), and mixed plans sent the first one's damped
#: search astray (an eigenvalue of its crowded cluster refined to Re lam = +1e-6, refused
#: as not passive).
LONG_GAIN = 2.0
#: Largest ``|s| l`` of a long piece over the plan's range: its stiffness comes from the
#: closed forms in ``nu = s l`` (:func:`symtmm.numeric.stiffness.eb_closed_stiffness`),
#: whose terms grow like ``exp(1.31 |nu|)`` and stay far inside double precision's range.
NU_LONG = 120.0
#: ``beta_1 l`` of a clamped-clamped Euler–Bernoulli beam (4.7300407...), rounded down.
BETA_CLAMPED = 4.73
#: A long piece's first clamped-clamped ``omega**2`` lies at least this factor above the
#: largest ``|Im lam|**2`` the plan is evaluated at (its ``top2``, itself a design range up
#: to ``2**(1/2)`` above the batch's own): ``J0 = 0`` for the count, and ``det U12`` (zero
#: there) at least 5 % of ``omega`` away from zero where the searches evaluate. 1.5 cut a
#: soft beam on a foundation whose modes lie just below its cut-off ``sqrt(kw / m)`` (``kw /
#: m`` 1.23 times ``top2``: the foundation alone keeps the pieces' clamped modes above the
#: range) into a plan of 182 segments where their growth allows 17: a campaign model's
#: damped search, whose proofs took dense determinants of them, 59 s against about 15 s.
#: (Not in a plan for counts on the frequency axis, ``clamped``: :func:`clamped_long_piece`.)
CLAMPED_MARGIN = 1.1


def wave_number_bound(segment, radius: float) -> float:
    """An upper bound on the largest wave number of ``segment`` for all ``|lam**2| <= radius``.

    From the triangle inequality on the trace ``t`` and determinant ``d`` of the
    segment's ``G`` (see :mod:`symtmm.elements.theories`); for an Euler–Bernoulli
    segment ``((m radius + kw) / EI)**(1/4)``.

    Examples
    --------
    >>> round(wave_number_bound(EulerBernoulliSegment(1, 1, 1), 16.0), 12)
    2.0
    """
    if isinstance(segment, EulerBernoulliSegment):
        EI, m, _, kw = segment.constants()
        return ((m * radius + kw) / EI) ** 0.25
    EI, m, _, kw, N, rhoI, kGA = segment.constants()
    if math.isinf(kGA):
        a, b = 1.0, 0.0
    else:
        a, b = kGA / (kGA + N), -1.0 / (kGA + N)
    c = abs(N * a) + rhoI * radius
    mu = m * radius + kw
    t = c / EI + abs(b) * mu
    d = mu * (a * a + abs(b) * c) / EI
    return math.sqrt(t / 2 + math.sqrt(t * t / 4 + d))


def piece_length(segment, radius: float, nu_max: float = NU_MAX) -> float:
    """The longest piece of ``segment`` for ``|lam|**2 <= radius``.

    Its largest wave number keeps ``|s| l <= nu_max`` there, and (for theories
    other than Euler–Bernoulli) its clamped-clamped natural frequencies lie above
    ``sqrt(radius)`` (:meth:`~symtmm.elements.theories.BeamSegment.safe_length`).
    """
    longest = wave_piece(wave_number_bound(segment, radius), float(segment.l), nu_max)
    if not isinstance(segment, EulerBernoulliSegment):
        longest = min(longest, segment.safe_length(radius))
    return longest


def wave_piece(s: float, length: float, nu_max: float = NU_MAX) -> float:
    """The longest piece of a stretch ``length`` long whose largest wave number is ``s``
    (the rule of :func:`piece_length` for Euler–Bernoulli pieces): the stretch itself where
    ``s length <= nu_max``, else ``nu_max / s``.

    Examples
    --------
    >>> wave_piece(2.0, 1.0, 3.0), wave_piece(6.0, 1.0, 3.0)
    (1.0, 0.5)
    """
    return length if s * length <= nu_max else nu_max / s


def long_piece(segment, s: float, length: float, top2: float, nu_max: float = NU_MAX) -> float:
    """The piece an Euler–Bernoulli stretch ``length`` long is cut into, whose largest wave
    number over the plan's range is ``s``, for points with ``|Im lam|**2 <= top2``.

    Short pieces (:func:`wave_piece`) unless they would be more than :data:`LONG_FROM` and
    long ones take at most ``1 /`` :data:`LONG_GAIN` as many. A long piece keeps ``|s| l <=`` :data:`NU_LONG`
    and its first clamped-clamped ``omega**2 = (EI (beta_1 / l)**4 + kw) / m`` at least
    :data:`CLAMPED_MARGIN` times ``top2``: the zeros of its ``det U12`` (where its stiffness
    has poles) all lie on the imaginary axis there. On a foundation stiffer than the
    inertia the range asks (``kw >= CLAMPED_MARGIN m top2``) only its growth bounds it.

    Examples
    --------
    A beam on a foundation ``kw L**4 / EI = 1e8``, below its cut-off ``sqrt(kw / m)``:
    short pieces would be 34, long ones are the stretch itself.

    >>> seg = EulerBernoulliSegment(1, 1, 1, 10**8)
    >>> s = wave_number_bound(seg, 1.0)
    >>> math.ceil(1 / wave_piece(s, 1.0)), long_piece(seg, s, 1.0, top2=1.0)
    (34, 1.0)
    """
    return _long_or_short(segment, s, length, top2, wave_piece(s, length, nu_max))


def _long_or_short(segment, s: float, length: float, top2: float, short: float) -> float:
    """The long piece of an Euler–Bernoulli stretch ``length`` long of ``segment``'s
    constants, its largest wave number ``s``, where the short rule's ``short`` would cut it
    into more than :data:`LONG_FROM` and the long piece is at least :data:`LONG_GAIN` times
    longer; else ``short`` (:func:`long_piece`, :func:`layered_piece`)."""
    if length <= LONG_FROM * short:
        return short
    longest = min(length, _clamped_length(segment, top2), NU_LONG / s)
    return longest if longest >= LONG_GAIN * short else short


def piece_rule(radius: float, nu_max: float = NU_MAX, top2: float | None = None,
               clamped: bool = False):
    """``piece(beam, segment)``: :func:`piece_length` for ``|lam|**2 <= radius``, as
    :class:`~symtmm.mesh.Mesh` takes it (its ``radius`` bounds a layer's ``k + c lam``; its
    ``key`` names the rule for :meth:`~symtmm.mesh.Stretches.subdivide`'s memory). Plain
    Euler–Bernoulli stretches take :func:`long_piece` for ``|Im lam|**2 <= top2`` (by
    default ``radius``); with ``clamped``, long pieces and condensed chains past their
    clamped-clamped frequencies (:func:`clamped_long_piece`, :func:`condensed_piece`: for
    counts on the frequency axis that add ``J0``, :mod:`symtmm.numeric.clamped`). Beams
    joined by layers keep their bound (:func:`layered_piece`): passing it, measured, cost
    two identical beams under a layer 0.42 -> 1.55 s at 60 modes (their condensed chains
    in numpy where the compiled kernel takes the short pieces) for 2.6 -> 1.6 s at 150."""
    top2 = float(radius) if top2 is None else min(float(top2), float(radius))

    def piece(beam, seg):
        short = piece_length(seg, radius, nu_max)
        if isinstance(seg, EulerBernoulliSegment) or not _condensable(seg) or \
                float(seg.l) <= LONG_FROM * short:
            return short
        return max(short, condensed_piece(seg, radius, top2, clamped))

    def doublings(seg) -> int:
        """The doublings a piece ``seg`` of a stretch cut by this rule is condensed from:
        its pieces of :func:`piece_length` for the range (of beams joined by undamped
        layers, the shortest of their bounds', as :class:`~symtmm.mesh.Stretches` cuts
        them); 0 where it is one."""
        if isinstance(seg, CoupledSegment):
            short = _layered_short(seg, radius, nu_max)
        elif isinstance(seg, EulerBernoulliSegment) or not _condensable(seg):
            return 0
        else:
            short = piece_length(seg, radius, nu_max)
        ratio = float(seg.l) / short
        return 0 if ratio <= 1 + 1e-9 else math.ceil(math.log2(ratio) - 1e-9)

    piece.radius = float(radius)
    piece.key = (float(radius), float(nu_max), top2, bool(clamped))
    piece.doublings = doublings
    return piece


def clamped_long_piece(segment, s: float, length: float, nu_max: float = NU_MAX) -> float:
    """:func:`long_piece` without the clamped-clamped bound: a long Euler–Bernoulli piece
    bounded by its growth alone (``|s| l <=`` :data:`NU_LONG`), for a plan whose counts add
    its pieces' clamped-clamped eigenvalues below each frequency (``J0``,
    :func:`clamped_counts`): at the ``n``-th mode of a beam short pieces number about
    ``n``, these about ``n pi / NU_LONG``.

    Examples
    --------
    A cantilever's range at its 200th mode, ``beta L`` about ``200 pi``: 210 short pieces,
    6 such ones (each past about 38 of its clamped-clamped frequencies).

    >>> seg = EulerBernoulliSegment(1, 1, 1)
    >>> s = wave_number_bound(seg, (200 * math.pi) ** 4)
    >>> math.ceil(1 / wave_piece(s, 1.0)), math.ceil(1 / clamped_long_piece(seg, s, 1.0))
    (210, 6)
    """
    return _long_or_short(segment, s, length, 0.0, wave_piece(s, length, nu_max))


def _layered_short(seg, radius: float, nu_max: float) -> float:
    """The short rule's piece of beams joined by layers (``seg`` a
    :class:`~symtmm.elements.layer.CoupledSegment`), inf where a layer is damped (those are
    never condensed): each beam's on the foundation ``kw + 2 k + 2 c |lam|`` of the layers
    touching it (:meth:`symtmm.mesh.Stretches._longest`), the shortest."""
    if any(c != 0 for *_, c in seg.couplings):
        return math.inf
    out = math.inf
    for p, (EI, m, kw) in enumerate(seg.beams):
        k = sum((kk for i, j, kk, _ in seg.couplings if p in (i, j)), sp.Integer(0))
        bound = EulerBernoulliSegment(EI, m, seg.l, kw + 2 * k)
        out = min(out, piece_length(bound, radius, nu_max))
    return out


def layered_piece(own, bound, radius: float, top2: float, short: float) -> float:
    """The long piece of a beam ``own`` (its own segment, the stretch long) joined to others
    by undamped layers, ``bound`` the Euler–Bernoulli segment whose wave number bounds the
    joined piece's for this beam (:meth:`~symtmm.mesh.Stretches._longest`), ``short`` the
    piece the short rule allows: ``short`` where it would cut at most :data:`LONG_FROM`,
    else the longest whose clamped-clamped frequencies stay above ``CLAMPED_MARGIN`` times
    ``top2`` and ``|s| l <=`` :data:`NU_LONG`. An undamped layer adds ``k (w_i - w_j)**2
    >= 0`` to the energy, so the joined piece's first clamped-clamped ``omega**2`` is at
    least the least of its beams' own, ``(EI (beta_1 / l)**4 + kw) / m`` (each beam asked
    here for its own)."""
    if not isinstance(own, EulerBernoulliSegment):
        return short
    return _long_or_short(own, wave_number_bound(bound, radius), float(own.l), top2, short)


def _clamped_length(seg, top2: float) -> float:
    """The longest Euler–Bernoulli piece of ``seg``'s constants whose first clamped-clamped
    ``omega**2`` is at least :data:`CLAMPED_MARGIN` times ``top2``."""
    EI, m, _, kw = seg.constants()
    excess = CLAMPED_MARGIN * m * top2 - kw
    return math.inf if excess <= 0 else BETA_CLAMPED * (EI / excess) ** 0.25


def _condensable(seg) -> bool:
    """A beam of a theory other than Euler–Bernoulli (not a rod, nor beams joined by a layer):
    its long pieces are condensed chains (:class:`~symtmm.numeric.segments.Condensed`)."""
    from ..elements.theories import BeamSegment
    return isinstance(seg, BeamSegment) and not (seg.kGA is not None and seg.kGA == 0)


def condensed_piece(seg, radius: float, top2: float, clamped: bool = False) -> float:
    """The longest long piece of ``seg`` (a beam of another theory): at most ``seg``'s length
    and :data:`NU_LONG` over its largest wave number, its clamped-clamped frequencies above
    ``CLAMPED_MARGIN`` times ``top2`` (the theory's own rigorous bound,
    :meth:`~symtmm.elements.theories.BeamSegment.safe_length`, with its ``1.1`` more);
    with ``clamped`` (a plan for counts that add ``J0``, the doublings' own:
    :func:`symtmm.numeric.clamped.clamped_counts`), by its growth alone.

    Examples
    --------
    A Rayleigh beam on a foundation ``kw L**4 / EI = 1e8``, below its cut-off: short pieces
    would be 34, a long one is the whole beam, condensed from 64 of them.

    >>> from symtmm.elements.theories import BeamSegment
    >>> seg = BeamSegment(1, 1, 1, kw=10**8, rhoI="1/1000")
    >>> rule = piece_rule(1.0)
    >>> condensed_piece(seg, 1.0, 1.0), rule(None, seg), rule.doublings(seg)
    (1.0, 1.0, 6)
    """
    from ..errors import ComputationError
    growth = NU_LONG / wave_number_bound(seg, radius)
    if clamped:
        return min(float(seg.l), growth)
    try:
        below = seg.safe_length(CLAMPED_MARGIN * top2)
    except ComputationError:
        return 0.0
    return min(float(seg.l), below, growth)


def rcm_order(size: int, cliques) -> list:
    """A reverse Cuthill–McKee order of ``size`` freedoms coupled within each clique.

    Returns ``order`` with ``order[new] = old``. Each connected part starts from a
    pseudo-peripheral freedom (the far end of a breadth-first search from one of
    least degree), which keeps the levels, and so the band, narrow.

    Examples
    --------
    A path numbered 0, 2, 4, 1, 3 along its length comes back as a path:

    >>> order = rcm_order(5, [(0, 2), (2, 4), (4, 1), (1, 3)])
    >>> max(abs(order.index(a) - order.index(b)) for a, b in [(0, 2), (2, 4), (4, 1), (1, 3)])
    1
    """
    adj = [set() for _ in range(size)]
    for clique in cliques:
        for a in clique:
            adj[a].update(clique)
    for a in range(size):
        adj[a].discard(a)
    degree = [len(s) for s in adj]
    seen = [False] * size
    order: list = []

    def bfs(start):
        levels, dist = [start], {start: 0}
        queue = deque([start])
        while queue:
            v = queue.popleft()
            for w in sorted(adj[v], key=degree.__getitem__):
                if w not in dist:
                    dist[w] = dist[v] + 1
                    levels.append(w)
                    queue.append(w)
        return levels, dist

    for root in sorted(range(size), key=degree.__getitem__):
        if seen[root]:
            continue
        part, dist = bfs(root)
        far = max(part, key=lambda v: (dist[v], -degree[v]))
        part, _ = bfs(far)
        for v in part:
            seen[v] = True
        order += part[::-1]
    return order


def _nonzero(c) -> bool:
    """Whether a coefficient (a SymPy number or a Python integer) is not zero: SymPy's
    ``!=`` with a Python 0 sympifies it, a few microseconds (the points' scatter of a
    50-level chain asks it 300 times a plan)."""
    return c != 0 if isinstance(c, int) else not c.is_zero


def _bandwidth(cliques, position) -> int:
    """The half-bandwidth of freedoms coupled within each clique, numbered ``position``."""
    width = 0
    for clique in cliques:
        if clique:
            at = [position[g] for g in clique]
            width = max(width, max(at) - min(at))
    return width


class StiffnessPlan:
    """The dynamic stiffness of a numeric model, compiled for ``|lam|**2 <= radius``.

    Parameters
    ----------
    model : Model
        Numeric (every parameter with a value).
    radius : float
        Largest ``|lam|**2`` at which the plan is evaluated: pieces are cut for it.
    nu_max : float
        Largest ``|s| l`` of a piece over that range (see :data:`NU_MAX`).
    top2 : float, optional
        Largest ``|Im lam|**2`` at which the plan is evaluated (by default ``radius``):
        the long pieces' clamped-clamped eigenvalues lie above it (:func:`long_piece`).
    clamped : bool
        Long Euler–Bernoulli pieces, and condensed chains of the other theories, past
        their clamped-clamped eigenvalues, bounded by their growth alone
        (:func:`clamped_long_piece`, :func:`condensed_piece`): a plan for counts on the
        frequency axis only, which add those eigenvalues below each frequency (``J0``,
        :func:`symtmm.numeric.clamped.clamped_counts`, by :func:`~symtmm.numeric.
        stiffness.factor` and :func:`~symtmm.numeric.stiffness.summary`). ``K`` has poles
        there; ``Delta`` does not.

    Attributes
    ----------
    n, band : int
        Order of ``K`` and its half-bandwidth.
    mesh : symtmm.mesh.Mesh
    kinds : list
        ``(family, exact constants)`` of the distinct segments, ``"eb"`` ones first.
    segment_kinds : list
        The kind of every segment of the mesh, in the mesh's order.
    multiplicity : numpy.ndarray
        How many segments of the mesh share each kind.
    log_constant : float
        ``log`` of the determinant identity's constant (powers of two and ``P``).
    valid_radius : float
        The largest ``|lam|**2`` its pieces are cut short enough for (:meth:`_valid_radius`),
        at least ``radius``: where the supports and springs cut the beams finer than the
        range needs, far more.
    long : bool
        Whether some piece is long: an Euler–Bernoulli one (:func:`long_piece`), whose
        stiffness then comes from the closed forms wherever its ``|x|`` exceeds
        ``NU_MAX**4``, or a condensed chain (:func:`condensed_piece`,
        :func:`layered_piece`). The compiled ball kernel, whose series stop at a short
        piece's ``|x|``, leaves such a plan to Arb; its double batches are built by the
        compiled kernel, the long kinds' values given by numpy
        (:func:`symtmm.numeric.multiword.double_band`).

    Examples
    --------
    >>> from symtmm.model import Beam, Spring, Model
    >>> m = Model((Beam("a", 1, 1, 1, left="clamped"), Beam("b", 1, 1, 1, left="pinned",
    ...            right="pinned")), (Spring("a", "b", "1/2", 10),))
    >>> plan = StiffnessPlan(m.require_numeric(), 100.0)
    >>> plan.n, plan.band, len(plan.kinds)
    (8, 3, 1)
    """

    def __init__(self, model, radius: float, nu_max: float = NU_MAX, stretches=None,
                 top2: float | None = None, clamped: bool = False):
        from ..mesh import Mesh
        self.model = model
        self.radius = float(radius)
        self.top2 = self.radius if top2 is None else min(float(top2), self.radius)
        self.clamped = bool(clamped)
        self.damped = model.damped
        mesh = self.mesh = Mesh(model, piece_rule(self.radius, nu_max, self.top2, clamped),
                                stretches)
        n = self.n = mesh.size
        self.long = self._long(nu_max)
        self.valid_radius = self._valid_radius(nu_max)
        cliques = ([[g for c in places for g, _ in c] for places in mesh.segment_places]
                   + [[g for c in places for g, _ in c] for places, _ in mesh.point_places]
                   + [[g for c in places for g, _ in c] for places, _ in mesh.body_places])
        order = rcm_order(n, cliques)
        position = [0] * n
        for new, old in enumerate(order):
            position[old] = new
        if _bandwidth(cliques, position) >= _bandwidth(cliques, range(n)):
            position = list(range(n))       # along x is as narrow already
        self.position = position
        b = self.band = _bandwidth(cliques, position)
        self.width = w = b + 1

        # segment kinds: "eb" first, then "theory", then "coupled" (kind_order)
        # (a kind is a tuple of SymPy numbers, whose hashes are Python calls that a tuple
        # does not keep: each segment's is looked up once, its kind's index kept)
        kinds: dict = {}            # a kind's key -> its first-seen number
        distinct: list = []         # the kinds, first seen first
        member_kind = []
        first = []
        seen: dict = {}             # id(segment) -> (kind, first-seen number): a stretch's
        for _, seg, _, _ in mesh.segments:      # pieces share their segment (Mesh)
            k, f = seen.get(id(seg), (None, None))
            if k is None:
                k = kind(seg)
                key = kind_key(k)
                f = kinds.get(key)
                if f is None:
                    f = kinds[key] = len(distinct)
                    distinct.append(k)
                seen[id(seg)] = (k, f)
            first.append(f)
            member_kind.append(k)
        order = sorted(range(len(distinct)), key=lambda j: kind_order(distinct[j]))
        ordered = [distinct[j] for j in order]
        index = [0] * len(ordered)                  # first-seen number -> kind index
        for i, j in enumerate(order):
            index[j] = i
        member_index = [index[f] for f in first]
        # where each kind's flattened stiffness starts in the concatenation of them all
        offsets = np.cumsum([0] + [kind_size(k) ** 2 for k in ordered]).tolist()
        self._stiffness_length = offsets[-1]
        self.kinds = ordered
        self.segment_kinds = member_kind        # per segment of the mesh, in its order
        self.multiplicity = np.bincount(member_index, minlength=len(ordered))

        triples: list = []          # (target, source, coefficient); source: see tables()

        def entries(places):
            # (i, j, target, coefficient) of every upper-band entry (K is symmetric) that an
            # element's K[i, j] reaches through its places' combinations
            if all(len(c) == 1 and c[0][1] is ONE for c in places):
                # each end freedom a free one of its own (most pieces): the entries
                # straight, without the products of combinations (a third of a chain's plan)
                at = [position[c[0][0]] for c in places]
                for i, r in enumerate(at):
                    for j, c in enumerate(at):
                        if r <= c:
                            yield i, j, r * w + c - r, ONE
                return
            for i, ci in enumerate(places):
                for j, cj in enumerate(places):
                    for gi, ai in ci:
                        for gj, aj in cj:
                            r, c = position[gi], position[gj]
                            if r <= c:
                                # (most coefficients are 1: SymPy's products cost microseconds)
                                yield i, j, r * w + c - r, \
                                    ai if aj is ONE else aj if ai is ONE else ai * aj

        for count, (k, i, places) in enumerate(zip(member_kind, member_index,
                                                   mesh.segment_places)):
            if count % 1024 == 0:
                # (a plan of tens of thousands of pieces takes seconds: a search's budget
                # is checked along it)
                check_time()
            base, size = offsets[i], kind_size(k)
            for i_, j_, target, both in entries(places):
                triples.append((target, ("D", base + size * i_ + j_), 1 if both is ONE else both))
        points = [(places, stiffness_coefficients(element))
                  for places, element in mesh.point_places]
        # a body's masses: a diagonal of ``mass lam**2`` (its coefficients written out:
        # SymPy's diag and polynomials cost a 20-span beam's supports a fifth of its plan)
        points += [(places, [[[0, 0, sp.sympify(mass)] if i == j else [0]
                              for j in range(len(masses))] for i, mass in enumerate(masses)])
                   for places, masses in mesh.body_places]
        for places, polys in points:
            for i_, j_, target, both in entries(places):
                triples += [(target, ("lam", p), cf if both is ONE else both * cf)
                            for p, cf in enumerate(polys[i_][j_]) if _nonzero(cf)]
        # scaling by powers of two: a static diagonal near 1 (units of any size)
        diag = self._static_diagonal(triples, ordered, offsets)
        self.exponent = [0 if not (d > 0 and math.isfinite(d)) else -round(math.log2(d) / 2)
                         for d in diag]
        e = self.exponent
        self._triples = []
        powers: dict = {}       # 2**k, once per k (SymPy's power costs more than the product)
        for target, source, coef in triples:
            r = target // w
            c = r + target % w
            k = e[r] + e[c]
            if k not in powers:
                # (from Python's integers: SymPy's power of a negative exponent costs
                # tens of microseconds, thirty of them a 50-level chain's plan)
                powers[k] = sp.Integer(1 << k) if k >= 0 else sp.Rational(1, 1 << -k)
            if type(coef) is int and coef == 1:
                coef = powers[k]        # (most entries: a segment's own, SymPy's product costs)
            else:
                coef = sp.sympify(coef)
                coef = coef if k == 0 else coef * powers[k]
            self._triples.append((target, source, coef))
        self._triples.sort(key=lambda t: t[0])
        self.log_constant = (math.log(float(mesh.pivot_product))
                             - 2.0 * math.log(2.0) * sum(e))
        self.pivot_product = mesh.pivot_product

    def _long(self, nu_max: float) -> bool:
        """Whether some Euler–Bernoulli piece exceeds ``|s| l = nu_max`` in the range, or some
        piece is a condensed chain."""
        seen = set()
        for _, seg, _, _ in self.mesh.segments:
            if isinstance(seg, Condensed):
                return True
            if id(seg) in seen or not isinstance(seg, EulerBernoulliSegment):
                continue
            seen.add(id(seg))
            if wave_number_bound(seg, self.radius) * float(seg.l) > nu_max * (1 + 1e-6):
                return True
        return False

    def _valid_radius(self, nu_max: float) -> float:
        """The largest ``|lam|**2`` at which every piece keeps ``|s| l <= nu_max``: for an
        Euler–Bernoulli piece ``(EI (nu_max / l)**4 - kw) / m`` (:func:`wave_number_bound`);
        the pieces of other theories and of layers count as cut for :attr:`radius` alone
        (their rules hold more than the wave number). A chain's pieces are mostly the
        stretches between its springs, whatever the range: its plan for twice the range
        has 2 % more freedoms, and the plan of the first guess serves the top above it.
        """
        valid = math.inf
        for _, seg, _, _ in self.mesh.segments:
            if not isinstance(seg, EulerBernoulliSegment):
                return self.radius
            EI, m, l, kw = seg.constants()
            valid = min(valid, (EI * (nu_max / l) ** 4 - kw) / m if m > 0 else math.inf)
        # (the cut rounds a stretch's pieces within 1e-9 of the rule: never below radius)
        return max(self.radius, valid * (1 - 1e-9))

    def _static_diagonal(self, triples, kinds, offsets) -> list:
        """The diagonal of the unscaled ``K`` at ``lam = 0`` (floats; ``offsets``: where each
        kind's flattened stiffness starts)."""
        from .stiffness import stiffness_values
        n, w = self.n, self.width
        flat = np.zeros(offsets[-1])
        # an Euler-Bernoulli piece without a foundation has the static diagonal (12 EI / l**3,
        # 4 EI / l) at each end, in closed form; the other kinds are evaluated (numpy's
        # series of every kind cost half a millisecond of a 20-level chain's 7 ms plan;
        # only the scaling's powers of two are taken of these)
        rest = []
        for i, (family, consts) in enumerate(kinds):
            if family == "eb" and consts[3] == 0:
                EI, _, l, _ = (exact_float(c) for c in consts)
                at = offsets[i]
                flat[at] = flat[at + 10] = 12 * EI / l ** 3
                flat[at + 5] = flat[at + 15] = 4 * EI / l
            else:
                rest.append(i)
        if rest:
            D, _ = stiffness_values(DOUBLE, kind_tables(DOUBLE, [kinds[i] for i in rest]),
                                    np.zeros(1), np.zeros(1), self.long)
            D = np.real(D).reshape(-1)
            start = 0
            for i in rest:
                size = offsets[i + 1] - offsets[i]
                flat[offsets[i]:offsets[i + 1]] = D[start:start + size]
                start += size
        diag = [0.0] * n
        for target, source, coef in triples:
            if target % w:
                continue
            kind, idx = source
            if kind == "D":
                diag[target // w] += exact_float(coef) * float(flat[idx])
            elif idx == 0:
                diag[target // w] += exact_float(coef)
        return [abs(d) for d in diag]

    def tables(self, ar: Arithmetic) -> dict:
        """The plan's numbers in ``ar`` (converted once per arithmetic and precision).

        ``kinds`` (constants per family for :func:`~symtmm.numeric.segments.transfer_matrices`)
        and ``layers``: per ``q``, ``(targets, source, coef)`` of every band entry's
        ``q``-th term, ``source`` into the concatenation of the segments' flattened
        stiffnesses and the point elements' ``lam**0, lam**1, lam**2`` columns.
        """
        from .arith import memo
        return memo(self, ar, "tables", lambda: self._tables(ar))

    def _tables(self, ar: Arithmetic) -> dict:
        values, index = self.distinct_coefficients()
        # (each distinct value converted once: most are a few powers of two and the
        # springs' constants, and a SymPy number's hash costs a microsecond)
        coef = ar.array([ar.exact(v) for v in values])[index]
        return {"kinds": self._kind_tables(ar),
                "layers": [(targets, source, coef[terms])
                           for targets, source, terms in self.layer_maps()]}

    def layer_maps(self) -> list:
        """The scatter's layers, arithmetic apart: per ``q``, ``(targets, source, terms)``
        with ``terms`` the indices of the exact coefficients (of the plan's triples) of
        every band entry's ``q``-th term (:meth:`tables`). Built once."""
        cached = self.__dict__.get("_layer_maps")
        if cached is not None:
            return cached
        nd = self._stiffness_length
        col = {("lam", 0): nd, ("lam", 1): nd + 1, ("lam", 2): nd + 2}
        source = np.array([s[1] if s[0] == "D" else col[s] for _, s, _ in self._triples],
                          dtype=np.int64)
        targets = np.array([t for t, _, _ in self._triples], dtype=np.int64)
        # the sums a term at a time: layer q holds the q-th term of every entry that has
        # one (at most a few per entry; the triples are sorted by entry, in plan order)
        starts = np.flatnonzero(np.diff(targets, prepend=-1)) if targets.size else targets
        ends = np.append(starts[1:], targets.size)
        layers = []
        for q in range(int(np.max(ends - starts, initial=0))):
            terms = starts[ends - starts > q] + q
            layers.append((targets[terms], source[terms], terms))
        self.__dict__["_layer_maps"] = layers
        return layers

    def distinct_coefficients(self) -> tuple:
        """``(values, index)``: the distinct exact coefficients of the scatter and, per
        coefficient of :attr:`coefficients`, its place among them (built once)."""
        cached = self.__dict__.get("_distinct")
        if cached is None:
            places: dict = {}
            # (most coefficients are the same few objects, the powers of two the plan
            # scaled by: looked up by identity first, as a SymPy number's hash costs a
            # microsecond)
            seen: dict = {}
            index = []
            first: list = []                # the distinct values, in the order first met
            for c in self.coefficients:
                at = seen.get(id(c))
                if at is None:
                    at = places.get(exact_key(c))
                    if at is None:
                        at = places[exact_key(c)] = len(first)
                        first.append(c)
                    seen[id(c)] = at
                index.append(at)
            cached = self.__dict__["_distinct"] = (first, np.array(index, dtype=np.int64))
        return cached

    @property
    def coefficients(self) -> list:
        """The exact coefficients of the scatter, in the order of :meth:`layer_maps`'
        ``terms``."""
        return [c for _, _, c in self._triples]

    def _kind_tables(self, ar: Arithmetic) -> list:
        """The kinds' constants in ``ar`` (converted once: the static diagonal asks for
        them in double precision before the tables are made)."""
        from .arith import memo
        return memo(self, ar, "kind_tables", lambda: kind_tables(ar, self.kinds))


#: Models whose plans are kept for the next search of the same model (``solve``, then
#: ``modes``, ``certify`` or a sweep's tracking shapes ask for the same ones).
PLAN_MODELS = 4
_PLANS: OrderedDict = OrderedDict()        # model -> {(design, top): plan}, least recent first
_PLANS_LOCK = threading.Lock()
_LONG: OrderedDict = OrderedDict()         # (model, design) -> whether long pieces can be


def clear_plans():
    """Forget the plans kept for the next search (a timing of a search from scratch)."""
    with _PLANS_LOCK:
        _PLANS.clear()
        _LONG.clear()


def design_range(size: float) -> float:
    """The range ``2**(k/4) >= size`` a plan for ``|lam| <= size`` is cut for."""
    return 2.0 ** (math.ceil(4 * math.log2(max(float(size), 1e-300)) - 1e-9) / 4)


def design_below(size: float) -> float:
    """The largest range ``2**(k/4) <= size`` (0 for ``size`` 0): a plan that serves
    ``|lam| <= size`` serves the plans' lookup for it.

    Examples
    --------
    >>> design_below(45.3), design_range(45.3), design_below(0.0)
    (45.254833995939045, 53.81737057623773, 0.0)
    """
    if not size > 0:
        return 0.0
    return 2.0 ** (math.floor(4 * math.log2(float(size)) + 1e-9) / 4)


def _long_possible(model, design: float) -> bool:
    """Whether some stretch of ``model`` may take long pieces in a plan for ``|lam| <=
    design`` (:func:`long_piece`, :func:`condensed_piece`, :func:`layered_piece`): only then
    does a plan's ``top2`` change its pieces."""
    key = (model, design)
    with _PLANS_LOCK:
        known = _LONG.get(key)
    if known is None:
        from ..mesh import Stretches
        stretches = Stretches(model)
        known = False
        # (a beam under undamped layers: its waves on the foundation of their k, bounded
        # by all that touch it)
        layered = [0] * len(model.beams)
        index = {b.name: i for i, b in enumerate(model.beams)}
        for la in model.layers:
            if la.c == 0:
                for name in (la.a, la.b):
                    layered[index[name]] += 2 * exact_float(la.k)
        for whole, lengths, extra in zip(stretches._whole, stretches._lengths, layered):
            if extra and isinstance(whole, EulerBernoulliSegment):
                EI, m, l, kw = whole.constants()
                whole = EulerBernoulliSegment(EI, m, l, kw + extra)
            if isinstance(whole, EulerBernoulliSegment) or _condensable(whole):
                s = wave_number_bound(whole, design * design)
                known = known or any(s * length > LONG_FROM * NU_MAX for length in lengths)
        with _PLANS_LOCK:
            _LONG[key] = known
            while len(_LONG) > 4 * PLAN_MODELS:
                _LONG.popitem(last=False)
    return known


def plan_key(model, size: float, top: float | None = None, clamped: bool = False) -> tuple:
    """``(design, top design, clamped)``: the ranges a plan for ``|lam| <= size`` at points
    with ``|Im lam| <= top`` (by default ``size``) is cut for, :func:`design_range` of each,
    and whether its long pieces pass their clamped-clamped frequencies (asked by counts on
    the frequency axis, :class:`StiffnessPlan`); the top is the design's own, and a plan
    not ``clamped``, where no stretch takes long pieces (:func:`long_piece`), so that
    searches off the imaginary axis and counts share the plans of the others.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> soft = Model((Beam("b", "1/100", 1, 10, left="pinned", right="pinned", kw=10**4),))
    >>> plain = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    >>> plan_key(soft, 500.0, 90.0), plan_key(plain, 500.0, 90.0)
    ((512.0, 90.50966799187809, False), (512.0, 512.0, False))
    >>> plan_key(soft, 500.0, clamped=True), plan_key(plain, 500.0, clamped=True)
    ((512.0, 512.0, True), (512.0, 512.0, False))
    """
    design = design_range(size)
    if clamped and _long_possible(model, design):
        return design, design, True
    if top is None or top >= design:
        return design, design, False
    tdesign = design_range(top)
    if tdesign >= design or not _long_possible(model, design):
        return design, design, False
    return design, tdesign, False


def plan_for(model, size: float, slack: float = 4.0, top: float | None = None,
             clamped: bool = False) -> StiffnessPlan:
    """A plan of ``model`` (numeric) valid for ``|lam| <= size``, shared between searches.

    Plans are cut for the ranges ``2**(k/4)`` (at most 19 % above ``size``: pieces at
    most 9 % more than needed). One already built serves instead when its pieces are
    short enough for this range (:attr:`StiffnessPlan.valid_radius`: a plan cut for a
    smaller range then has no more pieces than one cut for this), or when it was cut
    for a larger range and its pieces are at most twice as many as needed (``slack``,
    by default ``4 x`` the range: Euler–Bernoulli pieces shorten like
    ``range**(-1/2)``), since building a plan costs tens of evaluations. The plans of
    the last :data:`PLAN_MODELS` models are kept. ``top``: the largest ``|Im lam|`` it is
    evaluated at, where that shortens long pieces' cut (:func:`plan_key`); a plan serves
    only points below its own. ``clamped``: for counts on the frequency axis, whose long
    pieces may pass their clamped-clamped frequencies (:class:`StiffnessPlan`); any plan
    serves those, a ``clamped`` one nothing else.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> m = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    >>> plan_for(m, 100.0) is plan_for(m, 90.0), plan_for(m, 100.0) is plan_for(m, 1e4)
    (True, False)
    """
    design, tdesign, clamped = key = plan_key(model, size, top, clamped)
    with _PLANS_LOCK:
        plans = _PLANS.pop(model, None) or {}
        _PLANS[model] = plans
        while len(_PLANS) > PLAN_MODELS:
            _PLANS.popitem(last=False)
        plan = plans.get(key)
        if plan is None:
            # cut for a smaller range, yet short enough for this one: no more pieces than a
            # plan cut for it (a larger plan serves under the slack rule below)
            serving = [p for p in plans.values()
                       if p.radius <= design * design <= p.valid_radius
                       and p.top2 >= tdesign * tdesign and (clamped or not p.clamped)]
            if serving:
                return min(serving, key=lambda p: p.n)
            larger = [k for k in plans if design < k[0] <= slack * design and k[1] >= tdesign
                      and (clamped or not k[2])]
            if larger:
                return plans[min(larger)]
    if plan is None:
        # (built outside the lock: another thread may build the same one meanwhile)
        from ..mesh import Stretches
        stretches = Stretches(model)
        generous = generous_range(stretches, design, clamped)
        key = (generous, generous if tdesign == design else tdesign, clamped)
        plan = StiffnessPlan(model, generous * generous, stretches=stretches,
                             top2=key[1] * key[1], clamped=clamped)
        with _PLANS_LOCK:
            plan = _PLANS.setdefault(model, {}).setdefault(key, plan)
    return plan


#: Freedoms from which a plan is named as what made a search outrun its time budget ...
CROWDED = 2000
#: ... or from which it is, where one beam holds half of them: the proofs' determinant
#: with pivoting, in balls below ``DENSE_LIMIT`` freedoms, is dense and ``O(n**3)`` (half a
#: second a point at 194 freedoms: a random damped model, one beam cut into 138 pieces).
CROWDED_BY_ONE_BEAM = 100


def crowding(model) -> str | None:
    """What made the searches of ``model`` costly, where its largest plan built so far has
    :data:`CROWDED` freedoms or more, or :data:`CROWDED_BY_ONE_BEAM` and one beam holds half
    of them: the beam cut into most pieces, and what shortens its
    waves (the foundation, the axial force, the shear; else its flexibility at the range
    asked; a layer joining it). None otherwise.
    For a spent time budget's line (:func:`symtmm.deadline.time_budget`).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> m = Model((Beam("b", "1/1000", 1, 40, left="pinned", right="free", kw=10**6),))
    >>> _ = plan_for(m, 1.0)
    >>> print(crowding(m))                         # doctest: +ELLIPSIS
    its stiffness has ... freedoms; beam 'b' is cut into ... pieces: its foundation kw is far stiffer than its EI / L**4
    """
    from collections import Counter

    from ..elements.theories import BeamSegment

    with _PLANS_LOCK:
        plans = list(_PLANS.get(model, {}).values())
    plan = max(plans, key=lambda p: p.n, default=None)
    if plan is None or plan.n < CROWDED_BY_ONE_BEAM:
        return None
    pieces, layered = Counter(), Counter()
    for b, *_ in plan.mesh.segments:
        # (a piece of beams joined by a layer counts for each of them)
        for j in b if isinstance(b, tuple) else (b,):
            pieces[j] += 1
            layered[j] += isinstance(b, tuple)
    if not pieces:
        return None
    k = max(pieces.values())
    # (of beams cut alike, the pieces of a layer joining them: the softest is the cause)
    i = min((j for j, c in pieces.items() if c == k),
            key=lambda j: float(model.beams[j].EI / model.beams[j].L ** 4))
    if plan.n < CROWDED and 4 * k < plan.n:     # (a piece brings two freedoms)
        return None
    beam = model.beams[i]

    def waves(kw, N, kGA) -> float:
        seg = EulerBernoulliSegment(beam.EI, beam.m, beam.L, kw) if beam.plain else \
            BeamSegment(beam.EI, beam.m, beam.L, kw, N, beam.rhoI, kGA)
        return wave_number_bound(seg, plan.radius)

    s = waves(beam.kw, beam.N, beam.kGA)
    if 2 * layered[i] > k and waves(beam.kw, beam.N, beam.kGA) * beam.L < 3 * k / 2:
        # (most of its pieces are a layer's, cut finer than its own waves need)
        why = "a layer joining it is far stiffer than its EI / L**4"
    elif beam.kw != 0 and waves(0, beam.N, beam.kGA) < s / 2:
        why = "its foundation kw is far stiffer than its EI / L**4"
    elif beam.N != 0 and not beam.plain and waves(beam.kw, 0, beam.kGA) < s / 2:
        why = "its axial force N is far larger than its EI / L**2"
    elif beam.kGA is not None and not beam.plain and waves(beam.kw, beam.N, None) < s / 2:
        why = "its shear stiffness kGA is far softer than its EI / L**2"
    else:
        why = "its EI / L**4 is far below m omega**2 + kw at the range asked"
    return (f"its stiffness has {plan.n} freedoms; beam '{beam.name}' is cut into {k} "
            f"pieces: {why}")


#: A plan is cut for up to twice the range asked where that adds at most this fraction of
#: pieces (:func:`generous_range`).
GENEROUS_PIECES = 0.05


def generous_range(stretches, design: float, clamped: bool = False) -> float:
    """The range a plan for ``design`` is cut for: the largest of ``design`` times ``2``
    or ``sqrt(2)`` whose pieces are at most :data:`GENEROUS_PIECES` more, else ``design``.

    A chain's pieces are mostly its stretches between springs, whatever the range, and
    its first count misses the top it needs by a few eigenvalues (:func:`symtmm.roots.
    undamped._next_top`): a plan for the next range would cost as much as the first, for
    1 to 5 % more pieces (the 20- and 50-level chains of the benchmarks built two plans a
    solve). A beam cut by its range alone gains pieces like the range's square root, and
    keeps the range asked. The pieces are counted exactly (:meth:`~symtmm.mesh.Stretches.
    subdivide`), not estimated; ``clamped``: by the rule of a plan for counts
    (:func:`clamped_long_piece`).

    Examples
    --------
    >>> from symtmm.mesh import Stretches
    >>> from symtmm.model import Beam, Model, Spring
    >>> one = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    >>> generous_range(Stretches(one), 1000.0)          # its pieces grow with the range
    1000.0
    >>> springs = tuple(Spring("b", "ground", f"{k}/20", 1) for k in range(1, 20))
    >>> generous_range(Stretches(Model(one.beams, springs)), 100.0)
    200.0
    """
    def pieces(size):
        return sum(max(1, math.ceil(r - 1e-9))
                   for r in stretches.subdivide(piece_rule(size * size, clamped=clamped))[2])
    try:
        # (a float estimate first, per stretch; then the two candidates exactly, each
        # remembered for the plan's own mesh)
        rough = stretches.estimate(design * design, NU_MAX)
        for factor in (2.0, math.sqrt(2.0)):
            larger = factor * design
            if stretches.estimate(larger * larger, NU_MAX) <= (1 + GENEROUS_PIECES) * rough \
                    and pieces(larger) <= (1 + GENEROUS_PIECES) * pieces(design):
                return larger
    except ArithmeticError:
        pass        # (a larger range past the limit on pieces: the plan's own says so)
    return design
