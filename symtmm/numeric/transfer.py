"""The transfer-matrix walk along the layout, written once for every arithmetic.

The layout of a model (:class:`symtmm.assembly.Layout`) is a sequence of
intervals, each spanned by beam segments, and stations where point elements
act. :class:`TransferPlan` compiles it once: the distinct segment kinds
(evaluated together by :mod:`symtmm.numeric.segments`) and, per station, the
entries of its jump ``G`` as exact coefficient lists. :func:`propagate` then
carries the columns of the unknowns from the left to the right end,
``E <- U E`` per segment and ``E[row] += g E[col]`` per jump, in any
arithmetic of :mod:`symtmm.numeric.arith`, for a batch of eigenvalues at once;
``R`` is the rows of the conditions, ``Delta = det R``.

An undamped model's jumps are polynomials in ``lam**2`` (springs, masses): they
are evaluated in ``lam**2``, so that on the frequency axis (``lam**2 = -omega**2``
real) the whole walk stays in real arithmetic.

The plain product loses about ``sum |beta| L / ln 10`` digits to the growth of
its columns (entries grow like ``exp(|beta| l)``): high precision absorbs that.
In double precision :func:`log_delta` walks in steps of ``|beta| l <=``
:data:`NU_STEP` with the state in wave-number units and re-orthonormalises the
columns as they grow (Godunov's method for stiff boundary-value problems), which
keeps about 13 significant digits at any mode (less about ``log10(k L / EI)``
beside a rotational spring far stiffer than its beams, ``log10(k L**3 / EI)``
beside a translational one).

Examples
--------
>>> import numpy as np
>>> from symtmm.model import Beam, Model
>>> from symtmm.numeric.arith import DOUBLE, MP
>>> cc = TransferPlan(Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),)))
>>> Om = np.array([30.0, 60.0])               # cos(Om) cosh(Om) - 1, over 2 Om**4
>>> logabs, phase = log_delta(cc, 1j * Om**2)
>>> exact = (1 - np.cos(Om) * np.cosh(Om)) / (2 * Om**4)
>>> bool(np.all(abs(np.exp(logabs + 1j * phase) / exact - 1) < 1e-12))
True
>>> ar = MP(200)
>>> value = delta(cc, ar, ar.array([ar.number(-500)]), real=True)[0]   # lam**2 = -500
>>> Om = ar.ctx.root(500, 4)
>>> abs(value / ((1 - ar.ctx.cos(Om) * ar.ctx.cosh(Om)) / (2 * Om**4)) - 1) < 1e-55
True
"""

from __future__ import annotations

import bisect
import itertools
import math
from fractions import Fraction

import numpy as np
import sympy as sp

from ..assembly import Interval, Layout, state_rows
from ..deadline import check as check_time
from ..elements import EulerBernoulliSegment
from ..elements.base import LAM
from ..errors import ComputationError
from ..limits import MAX_PIECES
from .arith import DOUBLE, Arithmetic, Ball, Batch, ball_available, ball_midpoints, memo
from .linalg import det
from .plan import wave_number_bound
from .segments import cut_tables, family_matrices, kind_order, kind_size, kind_tables
from .segments import kind as segment_kind

__all__ = ["TransferPlan", "propagate", "boundary", "boundary_at", "boundary_walked", "delta",
           "log_delta", "NU_STEP", "digits_lost", "growth_by_beam", "Sampling", "sample",
           "convert"]

#: Largest ``|beta| l`` of one step of :func:`log_delta`: the columns grow by at most
#: ``exp(NU_STEP)`` between two re-orthonormalisations.
NU_STEP = 4.0


#: where each family keeps a segment's length among its constants
_LENGTH_AT = {"eb": 2, "theory": 7, "rod": 5, "coupled": 1}


def _with_length(kind, length):
    """A segment kind ``(family, constants)`` with its length replaced."""
    family, consts = kind
    consts = list(consts)
    consts[_LENGTH_AT[family]] = length
    return family, tuple(consts)


def _length(kind):
    return kind[1][_LENGTH_AT[kind[0]]]


def block(levels):
    """The rows of a segment's state in the extended state: a slice for one beam, an index
    array for beams joined by layers (:func:`symtmm.assembly.state_rows`)."""
    if isinstance(levels, int):
        return slice(4 * levels, 4 * levels + 4)
    return np.array(state_rows(levels))


def kind_matrices(ar: Arithmetic, tables, lam2, lam=None) -> list:
    """The transfer matrices of every kind, one array ``(B, s, s)`` per kind in order."""
    out = []
    for U in family_matrices(ar, tables, lam2, lam):
        out += [U[:, j] for j in range(U.shape[1])]
    return out


class TransferPlan:
    """A model's layout compiled for the transfer walk.

    Parameters
    ----------
    model : Model
        Numeric.

    Attributes
    ----------
    size : int
        Length of the extended state (four per beam, then the bodies' variables).
    columns, rows : list
        The unknowns at the left end, the conditions at the right end.
    steps : list
        ``("segments", [(level, kind index)])`` or ``("jumps", [(row, col, index)])``, in the
        order of ``layout.steps`` (which holds their coordinates).
    kinds : list
        Distinct segment kinds ``(family, exact constants)``, ``"eb"`` first.
    kind_segments : list
        A segment element of each kind (for its wave numbers).
    segments_of : list
        Per interval, the segment elements of its ``"segments"`` step, in order.
    even : bool
        Every jump is a polynomial in ``lam**2`` (no dashpot).
    """

    def __init__(self, model):
        self.model = model.require_numeric()
        layout = self.layout = Layout(self.model)
        self.size = layout.size
        self.columns = list(layout.columns)
        self.rows = list(layout.rows)
        self.units = list(layout.units)
        self.levels = [(b.segment(b.L), float(b.EI), float(b.L)) for b in self.model.beams]
        found: dict = {}
        raw = []
        for step in layout.steps:
            if isinstance(step, Interval):
                items = []
                for lvl, seg in step.segments:
                    items.append((lvl, found.setdefault(segment_kind(seg), len(found)), seg))
                raw.append(("segments", items))
            else:
                raw.append(("jumps", [(r, c, sp.Poly(sp.expand(v), LAM).all_coeffs()[::-1])
                                      for r, c, v in step.terms]))
        order = sorted(found, key=lambda k: (kind_order(k), found[k]))
        index = {found[k]: i for i, k in enumerate(order)}
        self.kinds = order
        self.kind_segments = [None] * len(order)     # an element of each kind (wave numbers)
        for kind, items in raw:
            for _, i, seg in items if kind == "segments" else ():
                self.kind_segments[index[i]] = seg
        self.even = all(all(c == 0 for c in cs[1::2]) for kind, items in raw if kind == "jumps"
                        for _, _, cs in items)
        self.coefficients: list = []       # per jump entry: exact coefficients
        self.steps = []
        for kind, items in raw:
            if kind == "segments":
                self.steps.append(("segments", [(lvl, index[i]) for lvl, i, _ in items]))
                continue
            entries = []
            for r, c, cs in items:
                if self.even:
                    cs = cs[::2]            # in lam**2
                entries.append((r, c, len(self.coefficients)))
                self.coefficients.append([sp.sympify(v) for v in cs])
            self.steps.append(("jumps", entries))
        self.segments_of = [[seg for _, _, seg in items] for kind, items in raw
                            if kind == "segments"]
        #: every segment carries one beam's four rows (no beams joined by layers)
        self.single_beams = all(isinstance(lvl, int) and kind_size(self.kinds[k]) == 4
                                for kind, items in self.steps if kind == "segments"
                                for lvl, k in items)

    # -- numbers ----------------------------------------------------------------------------
    def kind_tables(self, ar: Arithmetic, divide: int = 1):
        """The kinds' constants in ``ar`` for pieces ``1/divide`` of their length."""

        def build():
            kinds = [_with_length(k, _length(k) / divide)
                     for k in self.kinds] if divide != 1 else self.kinds
            return kind_tables(ar, kinds)
        return memo(self, ar, f"kinds/{divide}", build)

    def piece_tables(self, ar: Arithmetic, k: int, lengths) -> list:
        """Kind ``k`` cut to each of ``lengths`` (an array of numbers of ``ar``): the tables
        of :func:`~symtmm.numeric.segments.transfer_matrices`, one segment per length."""
        family = self.kinds[k][0]
        if family == "coupled":
            return [("coupled", self._coupled_piece_tables(ar, k, lengths))]
        return [(family, cut_tables(ar, self.kinds, self.kind_tables(ar), k, lengths))]

    def _coupled_piece_tables(self, ar: Arithmetic, k: int, lengths) -> dict:
        """The constants of coupled kind ``k`` cut to each of ``lengths``."""
        from .segments import coupled_constants
        one = memo(self, ar, f"coupled/{k}", lambda: coupled_constants(ar, [self.kinds[k][1]]))
        r = lengths / one["l"][0]
        r2 = r * r
        powers = {"A": r2 * r2, "F": r2 * r2, "Kl": r2 * r2, "Cl": r2 * r2, "sM": r2,
                  "sQ": r2 * r}
        out = {"N": one["N"], "damped": one["damped"], "l": lengths}
        for name in ("A", "F", "sM", "sQ"):
            out[name] = [powers[name] * v[0] for v in one[name]]
        for name in ("Kl", "Cl"):
            out[name] = [[powers[name] * v[0] for v in row] for row in one[name]]
        return out

    def piece_matrices(self, ar: Arithmetic, k: int, lam2, lengths, lam=None) -> np.ndarray:
        """Transfer matrices ``(B, P, s, s)`` of kind ``k`` over each of ``lengths`` ``(P,)``
        (``lam`` for a damped layer)."""
        with ar:
            return family_matrices(ar, self.piece_tables(ar, k, lengths), lam2, lam)[0]

    def jump_coefficients(self, ar: Arithmetic) -> list:
        return memo(self, ar, "jumps", lambda: [[ar.exact(c) for c in cs]
                                                 for cs in self.coefficients])

    def jump_values(self, ar: Arithmetic, lam, lam2) -> list:
        """Every jump entry at the points (arrays ``(B,)``), Horner in ``lam`` or ``lam**2``."""
        x = lam2 if self.even else lam
        out = []
        for cs in self.jump_coefficients(ar):
            v = 0 * x + cs[-1]          # the array on the left (see segments._factorial_series)
            for c in cs[-2::-1]:
                v = v * x + c
            out.append(v)
        return out


def point(ar: Arithmetic, lam, real: bool) -> tuple:
    """``(lam, lam2)`` as arrays of one number of ``ar`` for :func:`propagate`; ``real``:
    ``lam = i omega`` of an undamped model, walked in real arithmetic in ``lam**2 =
    -omega**2`` alone (squared in ``ar``, at its precision)."""
    if real:
        w = ar.number(lam.imag)
        with ar:
            return None, ar.array([-(w * w)])
    return ar.array([ar.number(lam)]), None


def propagate(plan: TransferPlan, ar: Arithmetic, lam=None, lam2=None, start=None,
              observe=None) -> np.ndarray:
    """The columns of the unknowns at the right end: ``(B, size, len(columns))``.

    ``lam`` ``(B,)`` (complex for double, numbers of ``ar`` otherwise); or, for an
    undamped model, ``lam2`` alone (``lam**2``, real on the frequency axis).

    ``start`` ``(B, size, k)``: other columns to carry, given as extended states
    at the left (default the unit columns of the unknowns). ``observe(i, before,
    after)`` is called after every step ``i`` of ``plan.steps`` with the states
    before and after it (``after`` is the walk's own array: read it during the
    call, do not keep or change it); the states at sample points
    (:func:`sample`) and the mode shapes' energy integrals are read that way.
    """
    with ar:
        if lam2 is None:
            lam2 = lam * lam
        B = len(lam2)
        like = lam2 if lam is None else lam
        if start is None:
            E = ar.zeros((B, plan.size, len(plan.columns)), like=like)
            one = ar.exact(1)
            for j, c in enumerate(plan.columns):
                E[:, c, j] = one
        else:
            E = np.array(start, copy=True)
        U = kind_matrices(ar, plan.kind_tables(ar), lam2, lam) if plan.kinds else None
        values = plan.jump_values(ar, lam, lam2) if plan.coefficients else []
        state = _ArbBlocks(plan, ar, E, U, values) if observe is None and B == 1 and \
            isinstance(ar, Ball) and plan.single_beams else _Columns(E)
        for i, (kind, items) in enumerate(plan.steps):
            before = state.E.copy() if observe is not None else None
            if kind == "segments":
                for lvl, k in items:
                    state.segment(lvl, k, U[k])
            else:
                for row, col, j in items:
                    state.jump(row, col, values[j])
            if observe is not None:
                observe(i, before, state.E)
        return state.array()


class _Columns:
    """The walk's state as one array ``(B, size, k)`` of numbers of any arithmetic."""

    def __init__(self, E):
        self.E = E

    def segment(self, lvl, k: int, Uk):
        blk = block(lvl)
        self.E[:, blk, :] = Uk @ self.E[:, blk, :]

    def jump(self, row: int, col: int, value):
        self.E[:, row, :] = self.E[:, row, :] + value[:, None] * self.E[:, col, :]

    def array(self):
        return self.E


class _ArbBlocks:
    """The state of one point's unobserved walk in Arb balls, each beam's four rows one
    ``arb_mat`` (``acb_mat``), a body's row a ``1 x k`` one: a segment is one product in
    C where numpy's object ``matmul`` calls Python per entry (4 x 4 by 4 x 40, the
    20-level chain's R walk: 19 against 85 microseconds), a jump a row picked and added
    back by products with unit vectors. The same steps as :class:`_Columns`, the same
    balls up to the rounding of Arb's dot products."""

    def __init__(self, plan: TransferPlan, ar: Ball, E, U, values):
        flint = ar.flint
        complex_ = ar.is_complex(E) or any(ar.is_complex(u) for u in (U or ())) or \
            any(ar.is_complex(v) for v in values)
        mat = self.mat = flint.acb_mat if complex_ else flint.arb_mat
        self.shape = E.shape
        self.beams = levels = plan.layout.levels
        C = E.shape[2]
        self.blocks = [mat(4, C, list(E[0, 4 * lvl:4 * lvl + 4, :].flat))
                       for lvl in range(levels)]
        self.extras = {r: mat(1, C, list(E[0, r, :])) for r in range(4 * levels, plan.size)}
        self.pick = [mat(1, 4, [int(i == j) for j in range(4)]) for i in range(4)]
        self.put = [mat(4, 1, [int(i == j) for j in range(4)]) for i in range(4)]
        self.kinds: dict = {}

    def segment(self, lvl: int, k: int, Uk):
        M = self.kinds.get(k)
        if M is None:
            M = self.kinds[k] = self.mat(4, 4, list(Uk[0].flat))
        self.blocks[lvl] = M * self.blocks[lvl]

    def _row(self, r: int):
        if r < 4 * self.beams:
            return self.pick[r % 4] * self.blocks[r // 4]
        return self.extras[r]

    def jump(self, row: int, col: int, value):
        term = self._row(col) * value[0]
        if row < 4 * self.beams:
            self.blocks[row // 4] = self.blocks[row // 4] + self.put[row % 4] * term
        else:
            self.extras[row] = self.extras[row] + term

    def array(self):
        C = self.shape[2]
        out = np.empty(self.shape, dtype=object)
        for lvl, blk in enumerate(self.blocks):
            out[0, 4 * lvl:4 * lvl + 4, :] = np.array(blk.entries(), dtype=object).reshape(4, C)
        for r, vec in self.extras.items():
            out[0, r, :] = vec.entries()
        return out


def boundary(plan: TransferPlan, ar: Arithmetic, lam=None, lam2=None) -> np.ndarray:
    """``R`` at the points: ``(B, k, k)``."""
    return propagate(plan, ar, lam, lam2)[:, plan.rows, :]


def walk_arithmetic(ar: Arithmetic) -> Arithmetic:
    """The arithmetic to walk in for results wanted in ``ar``, taken back as midpoints:
    Arb balls at ``ar``'s precision for an mpmath arithmetic where python-flint is
    installed (Arb rounds a midpoint as mpmath rounds, in C: several times faster),
    else ``ar`` itself."""
    if getattr(ar, "name", None) == "mp" and ball_available():
        return Ball(ar.prec)
    return ar


def boundary_at(plan: TransferPlan, ar: Arithmetic, value, real: bool) -> np.ndarray:
    """``R`` at one value ``value`` of ``lam`` (an mpmath number), as numbers of ``ar``.

    For an mpmath arithmetic where python-flint is installed, the walk runs in Arb balls at
    the same precision and ``R`` is their midpoints: each operation rounded as mpmath's
    (Arb rounds a midpoint as floating point does, the radius apart), in C, eight times
    faster on the 20-level chain (0.69 s -> 0.08 s at 75 digits). Otherwise in ``ar``.
    """
    walk, R = boundary_walked(plan, ar, value, real)
    return convert(walk, ar, R)


def boundary_walked(plan: TransferPlan, ar: Arithmetic, value, real: bool) -> tuple:
    """``(walk, R)``: :func:`boundary_at`'s ``R`` as numbers of the arithmetic it was
    walked in (:func:`walk_arithmetic`), for work that goes on there."""
    walk = walk_arithmetic(ar)
    lam, lam2 = point(walk, value, real)
    with walk:
        return walk, boundary(plan, walk, lam, lam2)[0]


def delta(plan: TransferPlan, ar: Arithmetic, lam=None, lam2=None, real: bool = False):
    """``Delta = det R`` at the points, as numbers of ``ar`` (``(B,)``).

    ``real=True``: ``lam`` holds ``lam**2`` values (an undamped model on the frequency
    axis), so the walk runs in real arithmetic.
    """
    if real:
        lam, lam2 = None, lam
    R = boundary(plan, ar, lam, lam2)
    with ar:
        return ar.array([det(ar, R[p]) for p in range(R.shape[0])])


def digits_lost(plan: TransferPlan, lam) -> float:
    """Estimated decimal digits the plain product loses to cancellation at ``lam``.

    Entries of a segment matrix grow like ``exp(|beta| l)``; the columns cancel
    at most about ``sum |beta| L / ln 10`` digits over the beams.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = TransferPlan(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)))
    >>> round(digits_lost(pp, 1j * (12 * np.pi) ** 2), 2)       # 12 pi / ln 10
    16.37
    """
    return sum(growth_by_beam(plan, lam)) / math.log(10)


def growth_by_beam(plan: TransferPlan, lam) -> list:
    """``|beta| L`` of each level of ``plan`` (each beam) at ``lam``, in their order: the
    natural logarithm of its matrices' growth (:func:`digits_lost`).

    Over a layer the beam's waves are the coupled member's, bounded by those of the beam
    on the foundation ``kw + 2 |k + c lam|`` of the layers it touches (as the meshes bound
    them: :meth:`symtmm.mesh.Stretches._longest`): a soft beam held between two stiff
    layers grows by ``exp(627)`` along its length where its own waves say ``exp(3)``, and
    a mode shape walked at the digits of the latter refined noise."""
    lam = complex(lam)
    lam2 = lam * lam
    model = plan.model
    out = []
    for beam, (seg, _, L) in zip(model.beams, plan.levels):
        own = float(np.max(seg.wave_number(lam2)))
        layers = [(float(la.x0), float(la.x1), abs(float(la.k) + float(la.c) * lam))
                  for la in model.layers if beam.name in (la.a, la.b)]
        if not layers:
            out.append(own * L)
            continue
        a, b = float(beam.x0), float(beam.x0) + L
        ends = sorted({a, b} | {min(max(x, a), b) for x0, x1, _ in layers for x in (x0, x1)})
        total = 0.0
        for xa, xb in itertools.pairwise(ends):
            middle = (xa + xb) / 2
            held = sum(2 * k for x0, x1, k in layers if x0 <= middle <= x1)
            s = own if not held else max(own, wave_number_bound(
                EulerBernoulliSegment(beam.EI, beam.m, xb - xa, beam.kw + held), abs(lam2)))
            total += s * (xb - xa)
        out.append(total)
    return out


# -- states at sample points -----------------------------------------------------------------
def _fraction(value):
    """An exact value as a ``Fraction`` when rational (fast to split), else as it is."""
    value = sp.sympify(value)
    return Fraction(int(value.p), int(value.q)) if value.is_Rational else value


def _rational(value):
    """A rational SymPy number as a ``Fraction``; None for any other value."""
    if getattr(value, "is_Rational", False):
        return Fraction(int(value.p), int(value.q))
    return None


def _split(f, n: int) -> tuple:
    """``(j, r)`` with ``f = j/n + r``, ``0 <= j < n``: the anchor below ``f`` and the rest."""
    if isinstance(f, Fraction):
        j = min(f.numerator * n // f.denominator, n - 1)
        return j, f - Fraction(j, n)
    j = min(int(sp.floor(f * n)), n - 1)
    return j, f - sp.Rational(j, n)


def _number(ar: Arithmetic, f):
    """An exact fraction as a number of ``ar``, rounded once (in double not memoised: the
    double arithmetic lives as long as the process, and offsets are many)."""
    if isinstance(ar, Batch):
        return f.numerator / f.denominator if isinstance(f, Fraction) else float(f)
    return ar.exact(sp.Rational(f.numerator, f.denominator) if isinstance(f, Fraction) else f)


def convert(ar: Arithmetic, target: Arithmetic, x):
    """An array of numbers of ``ar`` as numbers of ``target`` (double: real where ``x`` is)."""
    if target is ar:
        return x
    if isinstance(target, Batch):
        z = ar.to_complex(x)
        return z if ar.is_complex(x) else z.real
    if isinstance(ar, Ball) and getattr(target, "name", None) == "mp":
        return ball_midpoints(target, x)
    return np.frompyfunc(lambda v: target.number(ar.to_mpmath(v)), 1, 1)(x)


class Sampling:
    """Where sample points sit along the walk of a plan: exact, the same at every ``lam``.

    Parameters
    ----------
    plan : TransferPlan
    points : list
        Per beam (level), a list of ``(x, side)``: ``x`` an exact global coordinate,
        ``side`` ``"-"`` (the state before the jumps of the point elements at ``x``)
        or ``"+"`` (after them).

    The state at a beam's left end before its jumps is the one at its left (the
    unknowns there); at its right end after its jumps the one the conditions
    constrain; at a point without a station both sides are the same.

    Attributes
    ----------
    slots : list
        ``(level, i)`` of every sample, in order (the axis of :func:`sample`'s states).
    ends : dict
        Step index -> ``[(slot, level, "before" | "after")]``: samples at a cut.
    inside : dict
        Step index -> ``[(position in the step, segment, [(slot, fraction of its length)])]``:
        samples strictly inside a segment.

    Raises
    ------
    ValueError
        If a point is not on its beam.
    """

    def __init__(self, plan: TransferPlan, points):
        from ..assembly import _before, _same

        points = [[(sp.sympify(x), side) for x, side in level] for level in points]
        self.slots = [(lvl, i) for lvl, level in enumerate(points) for i in range(len(level))]
        index = {key: n for n, key in enumerate(self.slots)}
        # (rational coordinates compared as Fractions: SymPy's comparisons of every sample
        # with every segment took 0.5 s of the 20-level chain's 101 points a beam)
        exact = [[_rational(x) for x, _ in level] for level in points]
        # (per beam, its rational points sorted: an interval looks up the ones it holds by
        # bisection, where every interval of a 20-level chain went through every point)
        ordered = [sorted((fx, n) for n, fx in enumerate(level) if fx is not None)
                   for level in exact]
        keys = [[fx for fx, _ in level] for level in ordered]
        others = [[n for n, fx in enumerate(level) if fx is None] for level in exact]
        where: dict = {}
        segments = iter(plan.segments_of)
        for i, ((kind, items), step) in enumerate(zip(plan.steps, plan.layout.steps)):
            if kind == "segments":
                xs, xe = step.x_start, step.x_end
                fs, fe = _rational(xs), _rational(xe)
                segs = next(segments)
                for pos, (levels, _k) in enumerate(items):
                    for lvl in (levels,) if isinstance(levels, int) else levels:
                        if fs is not None and fe is not None:
                            lo = bisect.bisect_left(keys[lvl], fs)
                            hi = bisect.bisect_right(keys[lvl], fe)
                            candidates = [n for _, n in ordered[lvl][lo:hi]] + others[lvl]
                        else:
                            candidates = range(len(points[lvl]))
                        for n in candidates:
                            x = points[lvl][n][0]
                            fx = exact[lvl][n]
                            if fx is not None and fs is not None and fe is not None:
                                if fx < fs or fx > fe:
                                    continue
                                at_start, at_end = fx == fs, fx == fe
                                inside = not (at_start or at_end)
                            else:
                                at_start = _same(x, xs)
                                at_end = not at_start and _same(x, xe)
                                inside = not (at_start or at_end) and _before(xs, x) and \
                                    _before(x, xe)
                            slot = index[(lvl, n)]
                            if at_start:
                                where.setdefault(slot, ("end", i, "before", lvl))
                            elif at_end:
                                where[slot] = ("end", i, "after", lvl)
                            elif inside:
                                frac = (fx - fs) / (fe - fs) if fx is not None and \
                                    fs is not None and fe is not None else \
                                    _fraction((x - xs) / (xe - xs))
                                where[slot] = ("inside", i, (pos, segs[pos]), frac)
                continue
            levels = sorted({row // 4 for row, _, _ in items if row < 4 * plan.layout.levels})
            for lvl in levels:
                for n, (x, side) in enumerate(points[lvl]):
                    if _same(x, step.x):
                        slot = index[(lvl, n)]
                        if side == "+":
                            where[slot] = ("end", i, "after", lvl)
                        else:
                            where.setdefault(slot, ("end", i, "before", lvl))
        missing = [key for key, n in index.items() if n not in where]
        if missing:
            lvl, n = missing[0]
            raise ValueError(f"x = {points[lvl][n][0]} is not on beam "
                             f"'{plan.model.beams[lvl].name}'")
        self.ends: dict = {}
        inside: dict = {}
        for slot, (what, i, a, b) in sorted(where.items()):
            if what == "end":
                self.ends.setdefault(i, []).append((slot, b, a))
            else:
                inside.setdefault(i, {}).setdefault(a, []).append((slot, b))
        self.inside = {i: [(pos, seg, items) for (pos, seg), items in groups.items()]
                       for i, groups in inside.items()}
        #: per segment with samples inside and number of anchors: their anchors and the
        #: lengths left (:func:`_inside`), the same at every eigenvalue of that number
        self.splits: dict = {}

    def __len__(self):
        return len(self.slots)


def sample(plan: TransferPlan, ar: Arithmetic, sampling: Sampling, lam=None, lam2=None,
           start=None, inner: Arithmetic | None = None, observe=None) -> tuple:
    """The walk of :func:`propagate`, and the states at the points of ``sampling`` on the way.

    Parameters
    ----------
    plan, ar, lam, lam2, start, observe
        As for :func:`propagate` (one walk: ``observe`` sees every step too).
    sampling : Sampling
    inner : Arithmetic, optional
        The arithmetic of the last short step to a point inside a segment (default
        ``ar``). The walk reaches anchors ``h`` apart with ``|s| h <= 1`` (``s`` the
        largest wave number at the points) in ``ar``; from an anchor on, a transfer
        matrix over less than ``h`` loses at most a factor ``e`` in relative accuracy,
        so double precision (:data:`~symtmm.numeric.arith.DOUBLE`) gives every sample
        to about 15 digits however many digits the walk needs.

    Returns
    -------
    E : numpy.ndarray
        The columns at the right end, as :func:`propagate` returns them.
    states : numpy.ndarray
        ``(B, len(sampling), 4, k)``: ``[Y, Theta, M, Q]`` of the sample's beam for
        each column, numbers of ``inner``.

    Examples
    --------
    The first pinned-pinned mode, ``Y = sin(pi x)``, from its left state
    ``(0, pi, 0, -pi**3)`` in mpmath, sampled in double precision:

    >>> from symtmm.model import Beam, Model
    >>> from symtmm.numeric.arith import MP
    >>> pp = TransferPlan(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)))
    >>> ar = MP(100)
    >>> pi = ar.ctx.pi
    >>> start = ar.array([ar.number(v) for v in (0, pi, 0, -pi**3)], (1, 4, 1))
    >>> where = Sampling(pp, [[(sp.Rational(1, 6), "+"), (sp.Rational(1, 2), "+")]])
    >>> _, states = sample(pp, ar, where, lam2=ar.array([-pi**4]), start=start, inner=DOUBLE)
    >>> np.round(states[0, :, 0, 0], 12) + 0.0                   # sin(pi/6), sin(pi/2)
    array([0.5, 1. ])
    """
    inner = ar if inner is None else inner
    with ar:
        if lam2 is None:
            lam2 = lam * lam
    lam2_c = ar.to_complex(lam2)
    lam2_in = convert(ar, inner, lam2)
    lam_in = None if lam is None else convert(ar, inner, lam)
    out: dict = {}
    # the last short steps of 4-state pieces in double precision wait for the end of the
    # walk and go in one call per family (one call a segment cost the 20-level chain's
    # shapes 640 small evaluations each, three quarters of their time)
    pending = [] if isinstance(inner, Batch) else None
    anchors: dict = {}                  # per kind: its number of anchors at this lam
    steps: dict = {}                    # per kind: the transfer matrix from one to the next

    def watch(i, before, after):
        for slot, lvl, when in sampling.ends.get(i, ()):
            state = before if when == "before" else after
            # a copy: the walk goes on changing ``after`` in place
            out[slot] = convert(ar, inner, state[:, 4 * lvl:4 * lvl + 4, :].copy())
        for pos, seg, items in sampling.inside.get(i, ()):
            levels, k = plan.steps[i][1][pos]
            n = anchors.get(k)
            if n is None:
                n = anchors[k] = _anchors(seg, lam2_c)
            _inside(plan, ar, inner, k, n, lam, lam2, lam2_in, lam_in,
                    before[:, block(levels), :], items, out,
                    None if isinstance(levels, int) else
                    [levels.index(sampling.slots[slot][0]) for slot, _ in items],
                    pending, sampling.splits.setdefault((i, pos, inner.key), {}), steps)
        if observe is not None:
            observe(i, before, after)

    E = propagate(plan, ar, lam, lam2, start, watch)
    _take_pending(plan, ar, inner, pending, lam2_in, lam_in, out)
    if not len(sampling):
        return E, inner.zeros((E.shape[0], 0, 4, E.shape[2]))
    return E, np.stack([out[n] for n in range(len(sampling))], axis=1)


def _anchors(seg, lam2_c) -> int:
    """Anchors of a segment at ``lam**2 = lam2_c``: ``|s| h <= 1`` between them (at least
    one, its start)."""
    return max(1, math.ceil(float(np.max(seg.wave_number(lam2_c), initial=0.0))
                            * float(seg.l)))


def _inside(plan, ar, inner, k, n, lam, lam2, lam2_in, lam_in, Z0, items, out,
            positions=None, pending=None, splits=None, steps=None):
    """States at points strictly inside one segment (kind ``k``, ``n`` anchors:
    :func:`_anchors`) from its start ``Z0``.

    ``positions``: for beams joined by layers, each item's beam among them (its state is
    picked from the coupled one). ``pending``: where given, the last short steps of a
    4-state kind are not taken but kept there, the states as they are, for
    :func:`_take_pending` to convert and take all at once. ``splits``: a dict that keeps
    the anchors of this segment's samples between eigenvalues (exact fractions split
    once per number of anchors, not once a shape); ``steps``, per kind, the matrix from
    one anchor to the next (the same for every segment of a kind in one walk)."""
    groups = None if splits is None else splits.get(n)
    if groups is None:
        length = _length(plan.kinds[k])
        l_in = inner.exact(length)
        groups = {}
        for q, (slot, f) in enumerate(items):
            j, r = _split(f, n)
            groups.setdefault(j, []).append(
                (slot, None if r == 0 else _number(inner, r) * l_in,
                 None if positions is None else positions[q]))
        groups = sorted(groups.items())
        if splits is not None:
            splits[n] = groups
    far = {j for j, _ in groups if j > 0}
    reached = {0: Z0}
    if far:
        with ar:
            # (anchor by anchor with the matrix of one step, l / n: one evaluation of the
            # kind's functions where each anchor took its own; the rounding of up to n
            # products is far inside the guard digits of the walk's arithmetic)
            step = None if steps is None else steps.get(k)
            if step is None:
                l_ar = ar.exact(_length(plan.kinds[k]))
                step = plan.piece_matrices(ar, k, lam2, ar.array([l_ar / n]), lam)[:, 0]
                if steps is not None:
                    steps[k] = step
            Z = Z0
            for j in range(1, max(far) + 1):
                Z = step @ Z
                if j in far:
                    reached[j] = Z
    N = Z0.shape[1] // 4

    def own(Z, p):
        # the sample's beam's [Y, Theta, M, Q] from a coupled state (variable by variable)
        return Z if p is None else Z[..., [v * N + p for v in range(4)], :]
    family = plan.kinds[k][0]
    if pending is not None and family != "coupled":
        for j, members in groups:
            for slot, h, _ in members:
                pending.append((slot, k, h, reached[j]))
        return
    slots, lengths, sources = [], [], []
    for j, members in groups:
        Zj = convert(ar, inner, reached[j])
        for slot, h, p in members:
            if h is None:
                out[slot] = own(Zj, p)
            else:
                slots.append((slot, p))
                lengths.append(h)
                sources.append(Zj)
    if not slots:
        return
    with inner:
        U = plan.piece_matrices(inner, k, lam2_in, inner.array(lengths), lam_in)
        states = U @ np.stack(sources, axis=1)
    for q, (slot, p) in enumerate(slots):
        out[slot] = own(states[:, q], p)


def _take_pending(plan, ar, inner, pending, lam2_in, lam_in, out):
    """The samples :func:`_inside` kept, ``(slot, kind, length or None, state)``: the
    states converted to ``inner`` in one call, then one evaluation of the last short
    steps per family of kinds."""
    if not pending:
        return
    states = convert(ar, inner, np.stack([z for *_, z in pending], axis=1))
    families: dict = {}
    for q, (slot, k, h, _) in enumerate(pending):
        if h is None:
            out[slot] = states[:, q]
        else:
            families.setdefault(plan.kinds[k][0], []).append((q, slot, k, h))
    for family, group in families.items():
        with inner:
            tables = [(family, cut_tables(inner, plan.kinds, plan.kind_tables(inner),
                                          [k for _, _, k, _ in group],
                                          inner.array([h for *_, h in group])))]
            U = family_matrices(inner, tables, lam2_in, lam_in)[0]
            moved = U @ states[:, [q for q, *_ in group]]
        for c, (_, slot, _, _) in enumerate(group):
            out[slot] = moved[:, c]


# -- double precision, stable at any mode ---------------------------------------------------
def _units(plan: TransferPlan, lam2) -> np.ndarray:
    """Per point and index of the extended state, the unit it is measured in.

    The state of beam ``j`` in units of its wave number ``b``: ``[Y, Theta/b,
    M/(EI b**2), Q/(EI b**3)]``; a body's variables in those of the beam
    they act on. Unscaled, the rows of a high mode differ by powers of ``b``
    and the orthonormal columns would carry ``Y`` and ``Theta`` in their last
    digits.
    """
    N = lam2.size
    per_level = []
    for seg, EI, L in plan.levels:
        b = np.maximum(seg.wave_number(lam2), 1.0 / L)
        per_level.append({"Y": np.ones(N), "Theta": 1 / b, "M": 1 / (EI * b**2),
                          "Q": 1 / (EI * b**3)})
    D = np.empty((N, plan.size))
    for i, (lvl, var) in enumerate(plan.units):
        D[:, i] = per_level[lvl][var]
    return D


def too_many_waves(where: str) -> str:
    """The message where the beams hold more waves than :data:`~symtmm.limits.MAX_PIECES`
    pieces serve (as :class:`~symtmm.mesh.Mesh` says it of one beam)."""
    return (f"the model would need more than {MAX_PIECES} pieces at {where}: its waves are "
            "far shorter than its beams (a foundation kw or a layer k far stiffer than a "
            "beam's EI / L**4, or a range far above its first modes); soften them or lower "
            "the range")


def _step_counts(plan: TransferPlan, lam2) -> np.ndarray:
    """Per point, the number of steps of ``|beta| l <= NU_STEP`` of every interval."""
    out = np.ones((lam2.size, len(plan.segments_of)), dtype=int)
    for col, segs in enumerate(plan.segments_of):
        for seg in segs:
            nu = seg.wave_number(lam2) * float(seg.l)
            out[:, col] = np.maximum(out[:, col], np.ceil(nu / NU_STEP).astype(int))
    return out


def log_delta(plan: TransferPlan, lam) -> tuple:
    """``(log|Delta|, arg Delta)`` at complex points, double precision, without overflow.

    The columns of the unknowns are propagated as in :func:`propagate`, but every
    segment is applied in steps of ``|beta| l <=`` :data:`NU_STEP`, the state
    measured in wave-number units, and the columns re-orthonormalised whenever
    they may have grown by ``exp(NU_STEP)`` since the last time: ``E = Q F`` with
    ``Q`` orthonormal, so ``Delta = det Q[rows] * prod det F``. Points are
    propagated together when they take the same steps (a batch stepped for its
    highest mode would cost its low modes digits).
    """
    check_time()        # (a search's wall-clock budget: symtmm.deadline)
    lam = np.asarray(lam, dtype=complex)
    flat = lam.reshape(-1)
    logabs = np.empty(flat.size)
    phase = np.empty(flat.size)
    steps = _step_counts(plan, flat * flat)
    if steps.size and not np.max(np.sum(steps, axis=1)) <= MAX_PIECES:
        # (the stiffness kernel's meshes refuse the same; a walk of millions of steps per
        # point would run for hours)
        raise ComputationError(too_many_waves(f"|lam| = {float(np.max(np.abs(flat))):.6g}"))
    groups: dict = {}
    for i, key in enumerate(map(tuple, steps)):
        groups.setdefault(key, []).append(i)
    for key, idx in groups.items():
        check_time()    # (between groups: a scan of a model whose points take many steps)
        idx = np.array(idx)
        # (a segment's series overflows at a point far beyond its pieces' reach, as in a
        # scan of an extreme model: that point's value is not finite, and says so; numpy's
        # warnings would reach the user's terminal)
        with np.errstate(all="ignore"):
            logabs[idx], phase[idx] = _log_delta(plan, flat[idx], key)
    return logabs.reshape(lam.shape), phase.reshape(lam.shape)


def _log_delta(plan: TransferPlan, flat, steps) -> tuple:
    """:func:`log_delta` of points that take the same ``steps`` in every interval."""
    N = flat.size
    lam2 = flat * flat
    D = _units(plan, lam2)
    E = np.zeros((N, plan.size, len(plan.columns)), dtype=complex)
    for j, c in enumerate(plan.columns):
        E[:, c, j] = 1.0
    # E holds D * (true columns) / D[columns]: det R = det E[rows] * prod D[cols] / prod D[rows]
    logabs = np.sum(np.log(D[:, plan.columns]), axis=-1) - np.sum(np.log(D[:, plan.rows]),
                                                                   axis=-1)
    phase = np.zeros(N)

    def orthonormalise(E):
        Q, F = np.linalg.qr(E)
        diag = np.diagonal(F, axis1=-2, axis2=-1)
        with np.errstate(divide="ignore"):
            logabs[:] += np.sum(np.log(np.abs(diag)), axis=-1)
        phase[:] += np.sum(np.angle(diag), axis=-1)
        return Q

    values = plan.jump_values(DOUBLE, flat, lam2) if plan.coefficients else []
    matrices: dict = {}

    def pieces(divide):
        if divide not in matrices:
            matrices[divide] = kind_matrices(DOUBLE, plan.kind_tables(DOUBLE, divide), lam2,
                                             flat)
        return matrices[divide]

    interval = 0
    grown = 0.0        # sum of |beta| l applied since the columns were last orthonormal
    for kind, items in plan.steps:
        if kind == "segments":
            n_sub = int(steps[interval])
            segs = plan.segments_of[interval]
            interval += 1
            nu = max((float(np.max(seg.wave_number(lam2), initial=0.0)) * float(seg.l)
                      for seg in segs), default=0.0) / n_sub
            U = pieces(n_sub)
            subs = []
            for lvl, k in items:
                blk = block(lvl)
                subs.append((blk, U[k] * (D[:, blk, None] / D[:, None, blk])))
            for _ in range(n_sub):
                # orthonormalise only once the columns may have grown by exp(NU_STEP)
                if grown + nu > NU_STEP:
                    E = orthonormalise(E)
                    grown = 0.0
                for blk, Us in subs:
                    E[:, blk, :] = Us @ E[:, blk, :]
                grown += nu
        else:
            for row, col, i in items:
                E[:, row, :] += (values[i] * D[:, row] / D[:, col])[:, None] * E[:, col, :]
    if len(plan.columns):
        value = np.linalg.det(E[:, plan.rows, :])
        with np.errstate(divide="ignore"):
            logabs = logabs + np.log(np.abs(value))
        phase = phase + np.angle(value)
    return logabs, np.angle(np.exp(1j * phase))
