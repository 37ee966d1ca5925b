"""The language-neutral plan of a generated evaluator: what to compute, in which order.

A :class:`Plan` lists the numbers the evaluator needs as SymPy expressions
over the symbolic parameters (common subexpressions already taken out), and
the walk through the cuts as kinds and indices: the beams' units, the
segments (one entry per distinct segment), the stations' jumps (exact
polynomials in ``lam``) and the rows and columns of the unknowns. Every
language prints the same plan (:mod:`symtmm.codegen.walker`).

Examples
--------
A pinned-clamped beam: the unknowns are Theta and Q at the left end
(columns 1 and 3 of the state ``[Y, Theta, M, Q]``), the conditions Y = 0 and
Theta = 0 at the right end (rows 0 and 1):

>>> from symtmm.model import Beam, Model
>>> p = plan(Model((Beam("b", 1, 1, 1, left="pinned", right="clamped"),)))
>>> p.n, p.size, p.columns, p.rows
(1, 4, [1, 3], [0, 1])
>>> p.segments, p.steps
([('eb', 1, 1, 1, 0)], [('seg', 0, 0)])
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import sympy as sp

from ..assembly import Interval, Layout
from ..characteristic import _check_order, _prepare
from ..elements import STATE, BeamSegment
from ..elements.base import LAM
from ..elements.layer import CoupledSegment
from ..errors import ModelError

__all__ = ["Plan", "float_literal", "placeholder", "plan", "mapped"]


def float_literal(value) -> str:
    """Shortest decimal that reads back as the double nearest the exact value.

    A value beyond the double range is refused: its repr, ``inf`` or ``nan``,
    would be read as a name by every language but Octave.

    Examples
    --------
    >>> float_literal(sp.Rational(1, 3)), float_literal(2)
    ('0.3333333333333333', '2.0')
    """
    number = float(sp.N(sp.sympify(value), 30))
    if not math.isfinite(number):
        raise ModelError(f"a constant of the model, {sp.N(sp.sympify(value), 6)}, lies beyond "
                         "the range of double precision: it cannot be written as a double")
    return repr(number)


def placeholder(i: int) -> str:
    """The name parameter ``i`` has in a plan until a language gives it an identifier."""
    return f"symtmm_arg{i}"


@dataclass
class Plan:
    """Language-neutral description of the evaluation.

    Every value is a SymPy expression over the arguments and the CSE
    temporaries (numbers where it is constant); kinds and indices are Python
    strings and ints.
    """

    title: str
    source: str
    params: list                 # names of symbolic parameters (extra arguments)
    values: dict                 # parameter name -> exact value (for the header)
    n: int                       # beams
    size: int                    # length of the extended state (beams, then bodies)
    rows: list
    columns: list
    args: list = field(default_factory=list)      # argument identifier per parameter
    temps: list = field(default_factory=list)     # (name, expr over arguments and temps)
    # per beam: ("eb", EI, mu, L, k) with units b = |mu lam2 + k|^(1/4), or ("gen", th, L)
    # with b the wave-number bound of theory th
    levels: list = field(default_factory=list)
    theories: list = field(default_factory=list)  # (EI, a, b, cN, rhoI, m, kw) of a BeamSegment
    virtual: list = field(default_factory=list)   # (index, source): a body's unit is D[source]
    # ("eb", a, l, EI, s) with a = m l^4/EI, s = kw/m; ("gen", th, l); or ("coupled", nb,
    # cp) for beams joined by layers, their constants in couplings[cp]
    segments: list = field(default_factory=list)
    # per kind of member of beams joined by layers: CoupledSegment.constants()
    couplings: list = field(default_factory=list)
    guards: list = field(default_factory=list)    # lengths that must not be negative
    # ("seg", index, level) | ("point", [(row, [(sign, col, stiff index), ...]), ...])
    steps: list = field(default_factory=list)
    stiff: list = field(default_factory=list)     # (k0, k1, ...): s = k0 + k1 lam + ...

    @property
    def ncol(self) -> int:
        return len(self.columns)

    @property
    def has_eb(self) -> bool:
        """Whether some segment is a plain Euler–Bernoulli one (the c_j routine)."""
        return any(seg[0] == "eb" for seg in self.segments)

    @property
    def has_coupled(self) -> bool:
        """Whether some member is beams joined by layers (the coupled routines)."""
        return bool(self.couplings)

    @property
    def has_gen(self) -> bool:
        """Whether some segment or level needs the general beam routines."""
        return bool(self.theories)

    @property
    def logscale_terms(self) -> list:
        """``(sign, index)`` of the ``log D`` terms of the initial scale (columns minus rows)."""
        return [(1, c) for c in self.columns] + [(-1, r) for r in self.rows]


def _theory(seg: BeamSegment) -> tuple:
    """``(EI, a, b, cN, rhoI, m, kw)``: ``c = cN + rhoI lam**2``, ``mu = m lam**2 + kw``."""
    a, b, cN, _ = seg.coefficients(sp.Integer(0))
    return (seg.EI, a, b, cN, seg.rhoI, seg.m, seg.kw)


def _poly_coefficients(value) -> tuple:
    """Exact coefficients of ``lam**0, lam**1, ...`` of a station entry."""
    poly = sp.Poly(sp.expand(value), LAM)
    return tuple(sp.sympify(c) for c in reversed(poly.all_coeffs()))


def plan(model, symbolic=()) -> Plan:
    """The plan of ``model``'s evaluator, parameters as placeholders (:func:`placeholder`).

    Parameters without value, and those named in ``symbolic``, stay symbols;
    the order of the cuts is the one at the values of the model (checked).
    """
    model_in = model
    model, sample = _prepare(model, tuple(symbolic))
    layout = Layout(model, sample)
    _check_order(layout, sample, model.source)
    params = sorted(model.free_symbols)
    out = Plan(title=model_in.title or "", source=model_in.source or "",
               params=params, values=dict(model_in.parameters.items()),
               n=layout.levels, size=layout.size, rows=list(layout.rows),
               columns=list(layout.columns),
               args=[placeholder(i) for i in range(len(params))])
    raw: list = []          # expressions to go through CSE; slot i stands for raw[i]
    holders: list = []

    def slot(expr):
        expr = sp.sympify(expr)
        if expr.is_number:
            return expr
        raw.append(expr)
        holders.append(sp.Dummy(f"raw{len(raw) - 1}"))
        return holders[-1]

    theory_index: dict = {}

    def theory(seg) -> int:
        key = _theory(seg)
        if key not in theory_index:
            theory_index[key] = len(out.theories)
            out.theories.append(tuple(slot(v) for v in key))
        return theory_index[key]

    for beam in layout.model.beams:
        if beam.plain:
            out.levels.append(("eb", slot(beam.EI), slot(beam.m / beam.EI), slot(beam.L),
                               slot(beam.kw / beam.EI)))
        else:
            out.levels.append(("gen", theory(beam.segment(beam.L)), slot(beam.L)))
    units = layout.units
    for i in range(4 * layout.levels, layout.size):
        lvl, var = units[i]
        out.virtual.append((i, 4 * lvl + STATE.index(var)))
    seg_index: dict = {}
    stiff_index: dict = {}  # coefficients -> index; a coupling's entries are +-s: one variable
    for step in layout.steps:
        if isinstance(step, Interval):
            for lvl, seg in step.segments:
                key = (type(seg).__name__,) + tuple(seg.key)
                if key not in seg_index:
                    seg_index[key] = len(out.segments)
                    if isinstance(seg, CoupledSegment):
                        out.segments.append(("coupled", seg.size, len(out.couplings)))
                        out.couplings.append(tuple(slot(v) for v in seg.constants()))
                    elif isinstance(seg, BeamSegment):
                        out.segments.append(("gen", theory(seg), slot(seg.l)))
                    else:
                        # a foundation kw: the bare segment at lam**2 + kw/m
                        out.segments.append(("eb", slot(seg.m * seg.l**4 / seg.EI),
                                             slot(seg.l), slot(seg.EI), slot(seg.kw / seg.m)))
                    if not sp.sympify(seg.l).is_number:
                        out.guards.append(slot(seg.l))
                out.steps.append(("seg", seg_index[key], lvl))
            continue
        updates: dict = {}
        for row, col, value in step.terms:
            key = _poly_coefficients(value)
            if all(v == 0 for v in key):
                continue
            sign = 1
            neg = tuple(-v for v in key)
            if neg in stiff_index:
                key, sign = neg, -1
            if key not in stiff_index:
                stiff_index[key] = len(out.stiff)
                out.stiff.append(tuple(slot(v) for v in key))
            updates.setdefault(row, []).append((sign, col, stiff_index[key]))
        out.steps.append(("point", list(updates.items())))
    # common subexpressions of the parameter expressions
    lookup: dict = {}
    if raw:
        # each parameter, whatever its name and assumptions, becomes its placeholder: a
        # name only ever reaches the code as the identifier the language picks for it
        index = {name: i for i, name in enumerate(params)}
        marks = {s: sp.Symbol(placeholder(index[s.name]), **s.assumptions0)
                 for e in raw for s in e.free_symbols}
        numeric = [sp.N(e.xreplace(marks), 25) for e in raw]
        temps, reduced = sp.cse(numeric, symbols=sp.numbered_symbols("symtmm_t"))
        out.temps = list(temps)
        named: dict = {}
        for holder, e in zip(holders, reduced):
            if e.is_Symbol:          # a parameter or a CSE temporary: use it as it is
                lookup[holder] = e
                continue
            if e not in named:
                named[e] = sp.Symbol(f"symtmm_t{len(out.temps)}")
                out.temps.append((named[e], e))
            lookup[holder] = named[e]
    return mapped(out, lambda v: v.xreplace(lookup) if lookup else v)


def mapped(p: Plan, fn) -> Plan:
    """The plan with ``fn`` applied to every SymPy value (kinds and indices untouched)."""

    def sub(v):
        if isinstance(v, sp.Basic):
            return fn(v)
        if isinstance(v, tuple):
            return tuple(sub(x) for x in v)
        return v

    return replace(p,
                   temps=[(nm, sub(e)) for nm, e in p.temps],
                   levels=[sub(v) for v in p.levels],
                   theories=[sub(v) for v in p.theories],
                   segments=[sub(v) for v in p.segments],
                   couplings=[sub(v) for v in p.couplings],
                   stiff=[sub(v) for v in p.stiff],
                   guards=[sub(v) for v in p.guards])
