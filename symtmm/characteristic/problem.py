"""The scaled transfer problem: the boundary problem in SymPy terms, ready for the ring.

Step 1 of the method (:mod:`symtmm.characteristic`): each plain level's state
is scaled by ``diag(1, beta_j, EI_j beta_j**2, EI_j beta_j**3)`` so that its
segment matrices hold only ``S, T, U, V`` of ``beta_j l``; every distinct
argument becomes a :class:`_Group` of atoms (``c, s, ch, sh``), every kind of
beam whose wave numbers are not proportional to ``Omega`` a :class:`_Wave`,
and the point elements' entries are written in ``W = 1/Omega``. Numeric
radicals become symbols with their defining relation, so that everything is
a polynomial over the rationals.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import sympy as sp

from ..assembly import Interval, Layout
from ..elements import STATE
from ..elements.base import LAM
from ..elements.theories import BeamSegment, _assemble
from ..errors import ComputationError, ModelError
from ..model import Model
from .order import _check_order

__all__ = ["OMEGA", "OMEGA_DIMLESS"]

#: Circular frequency (rad/s) of an undamped model, ``lam = I*omega``.
OMEGA = sp.Symbol("omega", positive=True)
#: Dimensionless frequency ``Omega = beta_1 L_1`` of the first beam.
OMEGA_DIMLESS = sp.Symbol("Omega", positive=True)


_W = sp.Dummy("W", positive=True)  # stands for 1/Omega inside the polynomial ring


def _canonical_radicals(exprs):
    """Replace numeric radicals ``b**(p/q)`` by powers of one symbol per base.

    Returns the new expressions and ``{symbol: (base, Q)}`` with
    ``symbol**Q == base``.
    """
    pows = set()
    for e in exprs:
        pows |= {p for p in sp.sympify(e).atoms(sp.Pow)
                 if p.base.is_Rational and p.exp.is_Rational and not p.exp.is_Integer}
    by_base: dict = {}
    for p in pows:
        by_base.setdefault(p.base, []).append(p)
    subs, roots = {}, {}
    for base, items in by_base.items():
        Q = math.lcm(*[int(p.exp.q) for p in items])
        t = sp.Dummy(f"root{Q}_{base}", positive=True)
        roots[t] = (base, Q)
        for p in items:
            subs[p] = t ** int(p.exp * Q)
    return [sp.sympify(e).xreplace(subs) for e in exprs], roots


@dataclass
class _Wave:
    """One kind of beam whose wave numbers are not proportional to Omega.

    ``t``, ``d`` (trace and determinant of ``G``) and ``disc = t**2 - 4 d =
    (a**2 + b**2)**2`` are SymPy expressions in ``Omega``; ``Dl`` and ``iq``
    are the dummies standing for ``a**2 + b**2`` and ``1/disc``.
    """

    name: str
    t: sp.Expr
    d: sp.Expr
    a: sp.Symbol
    b: sp.Symbol
    beam: object
    Dl: sp.Dummy = field(default_factory=lambda: sp.Dummy("Dl"))
    iq: sp.Dummy = field(default_factory=lambda: sp.Dummy("iq"))
    t_ring: sp.Expr = None     # t and disc in W (set with the ring's generators)
    disc_ring: sp.Expr = None
    #: Euler-Bernoulli on a foundation: the state is scaled by diag(1, b, EI b**2, EI b**3)
    #: as a plain beam's, the atoms are those of b l and ``Wb = 1/b`` a generator
    scaled: bool = False
    Wb: sp.Dummy = field(default_factory=lambda: sp.Dummy("Wb", positive=True))

    @property
    def disc(self) -> sp.Expr:
        return sp.expand(self.t**2 - 4 * self.d)

    @property
    def equal(self) -> bool:
        """``a == b`` (``t == 0``: Euler–Bernoulli on a foundation)."""
        return self.t == 0


@dataclass
class _Group:
    """Atoms of one argument: ``Omega * arg`` (plain) or ``b l``, ``a l`` of a wave kind."""

    arg: sp.Expr              # plain: argument / Omega; wave: the length l
    wave: int | None = None   # index into _Problem.waves, None for plain
    dummies: tuple = field(default_factory=lambda: tuple(sp.Dummy(n) for n in
                                                          ("c", "s", "ch", "sh")))


@dataclass
class _Problem:
    """Everything the polynomial stage needs, in SymPy terms."""

    layout: Layout
    groups: list          # _Group per distinct argument
    waves: list           # _Wave per kind of non-plain beam
    steps: list           # ("segments", [(level, group)]) | ("point", {(row, col): expr in W})
    matrices: dict        # (group, level) -> 4x4 SymPy entries of a wave segment
    prefactor: sp.Expr    # prod D[rows] / prod D[cols], in Omega
    extra: list           # generators besides atoms, W and the waves' dummies
    relations: dict       # radical symbol -> (base, Q) with symbol**Q == base
    omega_of: dict        # how Omega relates to the model's variable
    damped: bool
    sample: dict          # values ordering the symbolic positions

    def in_ring(self, expr) -> sp.Expr:
        """``expr`` in Omega written for the ring (``Omega -> 1/W``)."""
        return sp.expand(sp.sympify(expr).xreplace({OMEGA_DIMLESS: 1 / _W}))

    def radicals(self, expr) -> sp.Expr:
        """``expr`` with numeric radicals written in the symbols of :attr:`relations`.

        For expressions built after those symbols were chosen (``b**(p/q)`` becomes
        ``t**(p Q/q)`` where ``t**Q == b``); other radicals are left as they are.
        """
        subs = {}
        for p in sp.sympify(expr).atoms(sp.Pow):
            for t, (base, Q) in self.relations.items():
                if p.base == base and p.exp.is_Rational and (p.exp * Q).is_Integer:
                    subs[p] = t ** int(p.exp * Q)
        return sp.expand(sp.sympify(expr).xreplace(subs)) if subs else expr


def _is_founded(beam) -> bool:
    """Euler–Bernoulli on a foundation without axial force: ``a = b``, scaled like plain."""
    return beam.theory == "euler-bernoulli" and beam.N == 0 and beam.kw != 0


def _is_plain(beam) -> bool:
    """Euler–Bernoulli without foundation or axial force: wave number ``~ Omega``."""
    return beam.theory == "euler-bernoulli" and beam.N == 0 and beam.kw == 0


def _wave_segment(beam, l=1) -> BeamSegment:
    return BeamSegment(beam.EI, beam.m, l, beam.kw, beam.N, beam.rhoI, beam.kGA)


def _wave_symbols(name: str, taken: set) -> tuple[sp.Symbol, sp.Symbol]:
    a, b = f"a_{name}", f"b_{name}"
    while a in taken or b in taken:
        a, b = a + "_", b + "_"
    return sp.Symbol(a, positive=True), sp.Symbol(b, positive=True)


def _wave_matrix(problem: _Problem, g: int, level: int) -> list:
    """``exp(A l)`` of a non-plain segment, entries polynomial in the group's atoms.

    ``F0(r) = cosh(sqrt(r) l)``, ``F1(r) = sinh(sqrt(r) l)/sqrt(r)`` at ``r1 = a**2``,
    ``r2 = -b**2``: ``f(G) = alpha I + beta G`` with ``beta = (f(r1) - f(r2))/Dl``,
    ``alpha = (r1 f(r2) - r2 f(r1))/Dl`` and ``1/Dl = Dl * iq``.
    """
    group = problem.groups[g]
    wave = problem.waves[group.wave]
    beam = problem.layout.model.beams[level]
    lam2 = problem.omega_of["lam2"]
    a_, b_, c_, mu_ = _wave_segment(beam).coefficients(lam2)
    c, Sn, ch, Sh = group.dummies
    Dl, iq, t = wave.Dl, wave.iq, wave.t
    A, B = (t + Dl) / 2, (Dl - t) / 2
    coef = ((A * c + B * ch) * Dl * iq, (ch - c) * Dl * iq,
            (A * Sn + B * Sh) * Dl * iq, (Sh - Sn) * Dl * iq)
    U = _assemble(coef, a_, b_, c_, mu_, beam.EI, None, None)
    return [[problem.in_ring(U[i][k]) for k in range(4)] for i in range(4)]


def _build_problem(model: Model, sample: dict) -> _Problem:
    model.refuse_layers("derive")
    layout = Layout(model, sample)
    _check_order(layout, sample, model.source)
    model = layout.model
    Om = OMEGA_DIMLESS
    beams = model.beams
    plain = [_is_plain(b) for b in beams]
    ref = plain.index(True) if any(plain) else 0
    mu = [(b.m / b.EI) ** sp.Rational(1, 4) for b in beams]
    L1 = beams[ref].L
    # lam in terms of Omega: beta_ref**4 = -m lam**2 / EI  =>  lam = -I Omega**2 / (mu L)**2
    lam_of_Omega = -sp.I * Om**2 / (mu[ref] * L1) ** 2
    lam2 = sp.expand(-Om**4 * beams[ref].EI / (beams[ref].m * L1**4))
    taken = set(model.parameters) | {"Omega", "omega", "lam", "I", "E", "pi"}
    waves: list = []
    level_wave: dict = {}
    r: dict = {}
    D = []
    for j, b in enumerate(beams):
        if plain[j]:
            r[j] = sp.simplify(mu[j] / mu[ref])
            beta = r[j] * Om / L1
            D += [sp.Integer(1), beta, b.EI * beta**2, b.EI * beta**3]
            continue
        t, d = (sp.expand(v) for v in _wave_segment(b).invariants(lam2))
        for k, w in enumerate(waves):
            if sp.expand(w.t - t) == 0 and sp.expand(w.d - d) == 0:
                break
        else:
            a_sym, b_sym = _wave_symbols(b.name, taken)
            taken |= {a_sym.name, b_sym.name}
            waves.append(_Wave(b.name, t, d, b_sym if t == 0 else a_sym, b_sym, b,
                               scaled=_is_founded(b)))
            k = len(waves) - 1
        level_wave[j] = k
        if waves[k].scaled:
            bk = waves[k].b
            D += [sp.Integer(1), bk, b.EI * bk**2, b.EI * bk**3]
        else:
            D += [sp.Integer(1)] * 4
    units = layout.units
    D_ext = [D[4 * lvl + STATE.index(var)] for lvl, var in units]
    groups: list = []
    steps: list = []
    for step in layout.steps:
        if isinstance(step, Interval):
            segs = []
            for lvl, seg in step.segments:
                if plain[lvl]:
                    arg, wave = sp.expand(sp.simplify(r[lvl] * seg.l / L1)), None
                else:
                    arg, wave = sp.expand(seg.l), level_wave[lvl]
                if arg.is_number and not arg.is_positive:
                    raise ModelError(f"segment of length {seg.l} is not positive",
                                     field="spring.x", source=model.source)
                for g, grp in enumerate(groups):
                    if grp.wave == wave and sp.expand(grp.arg - arg) == 0:
                        break
                else:
                    groups.append(_Group(arg, wave))
                    g = len(groups) - 1
                segs.append((lvl, g))
            steps.append(("segments", segs))
            continue
        entries = {}
        for row, col, value in step.terms:
            # masses (lam**2) enter undamped models too: lam**2 = -Omega**4/(mu_1 L_1)**4
            v = sp.sympify(value).xreplace({LAM: lam_of_Omega}) * D_ext[col] / D_ext[row]
            entries[(row, col)] = sp.expand(sp.powsimp(sp.expand(v)).xreplace(
                {Om: 1 / _W, **{w.b: 1 / w.Wb for w in waves if w.scaled}}))
        steps.append(("point", entries))
    prefactor = sp.powsimp(sp.Mul(*[D_ext[i] for i in layout.rows])
                           / sp.Mul(*[D_ext[i] for i in layout.columns]))
    problem = _Problem(layout=layout, groups=groups, waves=waves, steps=steps, matrices={},
                       prefactor=prefactor, extra=[], relations={},
                       omega_of={"mu1": mu[ref], "L1": L1, "lam2": lam2},
                       damped=model.damped, sample=sample)
    for kind, data in steps:
        if kind == "segments":
            for lvl, g in data:
                wave = groups[g].wave
                if wave is not None and not waves[wave].scaled and (g, lvl) not in problem.matrices:
                    problem.matrices[(g, lvl)] = _wave_matrix(problem, g, lvl)
    # every expression the ring must hold: radicals become symbols, the rest generators
    slots = [(kind, data, key) for kind, data in steps if kind == "point" for key in data]
    point_exprs = [data[key] for _, data, key in slots]
    matrix_exprs = [e for U in problem.matrices.values() for row in U for e in row]
    general = [w for w in waves if not w.scaled]
    rule_exprs = [problem.in_ring(e) for w in general for e in (w.t, w.disc)]
    exprs, roots = _canonical_radicals(point_exprs + matrix_exprs + rule_exprs)
    for (_, data, key), e in zip(slots, exprs):
        data[key] = e
    for i, w in enumerate(general):
        w.t_ring, w.disc_ring = exprs[len(exprs) - 2 * len(general) + 2 * i:][:2]
    it = iter(exprs[len(point_exprs):len(point_exprs) + len(matrix_exprs)])
    for U in problem.matrices.values():
        for row in U:
            row[:] = [next(it) for _ in row]
    known = {_W} | {d for grp in groups for d in grp.dummies} | {
        s for w in general for s in (w.Dl, w.iq)} | {w.Wb for w in waves if w.scaled}
    extra = []
    nonzero = [e for e in exprs if e != 0]
    if nonzero:
        _, info = sp.parallel_poly_from_expr(nonzero + [_W], domain=sp.QQ)
        extra = [g for g in info["gens"] if g not in known]
    for g in extra:
        allowed = {_W} | {w.Wb for w in waves if w.scaled}
        if g.free_symbols & ({Om} | known - allowed) or not (g.is_Symbol or g.is_Pow or g.is_number):
            raise ComputationError(f"unexpected term {g} in the transfer matrices")
    problem.extra = extra
    problem.relations = roots
    return problem
