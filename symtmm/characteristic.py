"""Closed-form characteristic equations ``Delta = det R = 0``.

The variable
------------
Every plain Euler–Bernoulli beam ``j`` (no foundation, no axial force) has the
wave number ``beta_j = (-m_j lam**2 / EI_j)**(1/4)``. All of them are
expressed through one dimensionless frequency, the paper's ``Omega = beta_1
L_1`` of the first beam::

    beta_j = r_j Omega / L_1,   r_j = ((m_j / EI_j) / (m_1 / EI_1))**(1/4).

For an undamped model ``lam = i omega`` and ``Omega**4 = m_1 omega**2 L_1**4 / EI_1``;
the result is given in ``omega`` (circular frequency, rad/s, ``variable ==
"omega"``) and in ``Omega``. A damped model is given in ``lam`` itself
(``variable == "lam"``), through ``Omega = L_1 (m_1/EI_1)**(1/4) sqrt(I lam)``
(any branch gives the same ``Delta``).

Other beams (a Winkler foundation ``kw``, an axial force ``N``, rotary
inertia ``rhoI``, shear ``kGA``; :mod:`symtmm.elements.theories`) have two
wave numbers that are not proportional to ``Omega``: ``a_j`` (hyperbolic) and
``b_j`` (trigonometric), ``a_j**2`` and ``-b_j**2`` the eigenvalues ``r1, r2``
of ``G = B C`` (trace ``t_j``, determinant ``d_j``, functions of ``lam``)::

    a_j = sqrt(t_j/2 + sqrt(t_j**2/4 - d_j)),   b_j = sqrt(-t_j/2 + sqrt(t_j**2/4 - d_j))

(``a_j = b_j = (-d_j)**(1/4)`` when ``t_j = 0``: Euler–Bernoulli on a
foundation, ``b**4 = (m omega**2 - kw)/EI``). Beams with the same ``t, d``
share them. The closed form is written in these symbols (``a_<beam>``,
``b_<beam>``, named after the first beam of each kind) and ``Omega`` if
there are plain beams, with the frequency left in the coefficients;
:attr:`CharacteristicEquation.definitions` gives each symbol in the
model's variable and :attr:`~CharacteristicEquation.delta` has them
substituted. ``Delta`` is an entire function of every ``t_j, d_j``, so any
branch of the roots gives the same value.

The form
--------
``det R = constant * Omega**power * prod(f_i**e_i)`` where the constant does
not depend on the frequency (it is dropped from :attr:`~CharacteristicEquation.delta`
and kept in :attr:`~CharacteristicEquation.constant`), ``Omega**power`` carries
the roots at zero (rigid-body modes) and cancels the spurious ones of the
transcendental factors, and the factors ``f_i`` are sums of products of
trigonometric and hyperbolic functions; a repeated factor (``e_i > 1``)
exposes roots of that multiplicity. A clamped-clamped beam gives
``Omega**-4 (cos Omega cosh Omega - 1)``. A negative ``e_i`` (only
``a_j**2 + b_j**2`` and its kin) is a denominator.

How it is computed
------------------
Exactly, without simplifying general SymPy expressions, which is what makes
multilevel models tractable:

1. The state of a plain level ``j`` is scaled by ``diag(1, beta_j, EI_j
   beta_j**2, EI_j beta_j**3)``; the transfer matrix of a segment of length
   ``l`` then has the entries ``S, T, U, V`` of ``beta_j l`` only, and a
   spring enters as ``k / (EI_a beta_a**3)``. A rigid body's virtual
   variables are scaled like the beam variables they stand for
   (``Layout.units``), so its equations have constant coefficients.
2. ``c, s, ch, sh = cos, sin, cosh, sinh`` of each distinct argument
   ``beta_j l`` are independent variables of a polynomial ring over the
   rationals (with ``W = 1/Omega``, ``Omega`` and the symbolic parameters),
   reduced with ``s**2 = 1 - c**2`` and ``sh**2 = ch**2 - 1``. An
   Euler–Bernoulli beam on a foundation (``a = b``) is scaled the same way
   with its own ``b`` (and ``1/b``) in place of ``beta``. The other beams
   bring per segment ``c = cos(b l)``, ``Sn = sin(b l)/b``, ``ch = cosh(a l)``,
   ``Sh = sinh(a l)/a`` and per kind of beam ``Dl = a**2 + b**2`` and ``iq =
   1/Dl**2``: with ``a**2 = (t + Dl)/2``, ``b**2 = (Dl - t)/2`` and
   ``Dl**2 = t**2 - 4 d`` (a polynomial in ``Omega``) the segment matrix
   ``exp(A l) = [[F0(G), B F1(G')], [C F1(G), F0(G')]]`` with ``f(G) = alpha I +
   beta G``, ``beta = (f(a**2) - f(-b**2))/Dl``, is polynomial, and the
   reductions ``c**2 = 1 - b**2 Sn**2``, ``ch**2 = 1 + a**2 Sh**2``,
   ``Dl**2 = t**2 - 4 d`` (leading terms in distinct variables: a normal form)
   keep it so. The columns of the unknowns are propagated through the cuts.
3. Entries of ``R`` that are nonzero rational constants (a body's
   compatibility and equilibrium) are eliminated first, exactly (Schur
   complement, the pivot and sign kept), so bodies and joints cost about as
   much as the beams they join. ``det R`` of the rest is expanded by minors
   (no division), factored over the rationals, ``iq = 1/Dl**2`` cleared, each
   factor reduced again and refactored. Factoring before the reduction keeps
   products intact: identical beams coupled symmetrically give one factor per
   mode family.
4. Each factor is written back either as a polynomial in the segment
   functions or, by product-to-sum, with combined arguments (``sin Omega``
   rather than ``2 cos(a)**2 sin(b) + ...``), whichever has fewer operations.

Examples
--------
>>> from symtmm.model import Beam, Model
>>> cc = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
>>> eq = characteristic_equation(cc)
>>> eq.variable, eq.delta_Omega
(omega, (cos(Omega)*cosh(Omega) - 1)/Omega**4)
>>> eq.delta
(cos(sqrt(omega))*cosh(sqrt(omega)) - 1)/omega**2

On a Winkler foundation the same equation holds in ``b**4 = (m omega**2 - kw)/EI``:

>>> w = Model((Beam("b", EI=1, m=1, L=1, kw=10, left="clamped", right="clamped"),))
>>> eq = characteristic_equation(w)
>>> eq.equation
cos(b_b)*cosh(b_b) - 1
>>> eq.definitions
{b_b: (omega**2 - 10)**(1/4)}
"""

from __future__ import annotations

import json
import math
import random
import time
from dataclasses import dataclass, field
from fractions import Fraction
from itertools import combinations, pairwise

import sympy as sp

from .assembly import Interval, Layout
from .elements import STATE
from .elements.base import LAM
from .elements.theories import BeamSegment, _assemble
from .errors import ComputationError, ModelError
from .expr import parameter_symbol
from .model import Model

__all__ = ["OMEGA", "OMEGA_DIMLESS", "CharacteristicEquation", "characteristic_equation"]

#: Circular frequency (rad/s) of an undamped model, ``lam = I*omega``.
OMEGA = sp.Symbol("omega", positive=True)
#: Dimensionless frequency ``Omega = beta_1 L_1`` of the first beam.
OMEGA_DIMLESS = sp.Symbol("Omega", positive=True)


# --------------------------------------------------------------------------------------
# polynomial rings over Q


class _Ring:
    """Multivariate polynomials over the rationals, lexicographic order.

    python-flint's ``fmpq_mpoly`` when it is installed (fast factoring),
    otherwise SymPy's sparse polynomials. Only the operations used here are
    wrapped.
    """

    def __init__(self, names):
        self.names = tuple(names)
        try:
            import flint
        except ImportError:  # pragma: no cover - depends on the installation
            flint = None
        if flint is not None:
            self._ctx = flint.fmpq_mpoly_ctx.get(self.names, "lex")
            self._flint = flint
            self.can_factor = True
            self.gens = self._ctx.gens()
            self.zero = self._ctx.from_dict({})
        else:  # pragma: no cover
            from sympy.polys.rings import ring
            self._ring, *gens = ring(",".join(self.names), sp.QQ, sp.lex)
            self._flint = None
            self.can_factor = False
            self.gens = tuple(gens)
            self.zero = self._ring.zero
        self.one = self.zero + 1

    def coefficient(self, value: Fraction | sp.Rational):
        value = sp.Rational(value)
        if self._flint is not None:
            return self._flint.fmpq(int(value.p), int(value.q))
        return sp.QQ(int(value.p), int(value.q))  # pragma: no cover

    def from_dict(self, terms: dict):
        if self._flint is not None:
            return self._ctx.from_dict(terms)
        return self._ring.from_dict(terms)  # pragma: no cover

    def terms(self, p) -> dict:
        """``{exponent tuple: coefficient}``."""
        if self._flint is not None:
            return p.to_dict()
        return dict(p.terms())  # pragma: no cover

    def constant_value(self, p):
        """The rational value of a constant polynomial, else None."""
        terms = self.terms(p)
        if len(terms) != 1:
            return None
        (mon, cf), = terms.items()
        return _rational(cf) if not any(mon) else None

    def factor(self, p):
        """``(constant, [(factor, multiplicity), ...])``."""
        if self._flint is not None:
            return p.factor()
        return p.factor_list()  # pragma: no cover


def _rational(c) -> sp.Rational:
    return sp.Rational(int(c.numerator), int(c.denominator))


# --------------------------------------------------------------------------------------
# the scaled transfer problem


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


def _prepare(model: Model, symbolic) -> tuple[Model, dict]:
    """Drop the values of the ``symbolic`` parameters, keep them to order the cuts."""
    sample = {}
    values = {}
    for name in symbolic:
        if name not in model.parameters:
            raise ModelError(f"'{name}' is not a parameter of this model",
                             field="--symbolic " + name, source=model.source)
        value = model.parameters[name]
        if value is not None:
            sample[parameter_symbol(name)] = value
        values[name] = None
    if values:
        model = model.with_parameters(**values)
    model = model.resolved()
    return model, _complete_sample(model, sample)


def _complete_sample(model: Model, sample: dict) -> dict:
    """Order positions whose symbols have no value, when the model allows only one order.

    Random values of the remaining symbols are tried; those that put every
    spring inside its beams are kept. If they all order the cuts alike, one of
    them orders the cuts (it does not enter the result); if they disagree the
    order is left open and :func:`_check_order` asks for a value.
    """
    positions = [p for b in model.beams for p in (b.x0, b.x1)] + [s.x for s in model.springs]
    free = set().union(*(sp.sympify(p).free_symbols for p in positions)) - set(sample)
    if not free:
        return sample
    free = sorted(free, key=lambda v: v.name)
    rng = random.Random(0)
    lengths = [b.L.xreplace(sample) for b in model.beams]
    scale = max([v for v in lengths if v.is_number] or [sp.Integer(1)])
    beams = {b.name: b for b in model.beams}
    found: dict = {}
    for _ in range(200):
        trial = dict(sample)
        trial.update({v: scale * sp.Rational(rng.randint(1, 999), 1000) for v in free})
        values = [sp.sympify(p).xreplace(trial) for p in positions]
        if not all(v.is_number for v in values):
            return sample
        if any(b.L.xreplace(trial) <= 0 for b in model.beams):
            continue
        inside = all(beams[n].x0.xreplace(trial) <= s.x.xreplace(trial)
                     <= beams[n].x1.xreplace(trial)
                     for s in model.springs for n in (s.a, s.b) if n in beams)
        if not inside:
            continue
        ranks = tuple(sorted(set(values)).index(v) for v in values)
        found.setdefault(ranks, trial)
        if len(found) > 1:
            return sample
    return next(iter(found.values())) if len(found) == 1 else sample


def _check_order(layout: Layout, sample: dict, source):
    """Positions whose order the symbols leave open must be ordered by ``sample``."""
    xs = [s.x for s in layout.stations]
    for a, b in pairwise(xs):
        d = sp.simplify(b - a)
        if d.is_positive:
            continue
        value = d.xreplace(sample) if sample else d
        names = sorted(s.name for s in d.free_symbols)
        if not (value.is_number and value > 0):
            hint = ", ".join(names) if names else "the parameters"
            raise ModelError(f"the order of the cuts along the beams depends on {hint}: give it a "
                             "value in [parameters] and keep it symbolic with --symbolic "
                             f"{hint.replace(', ', ',')}", field="parameters", source=source)




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
    level_wave: dict      # level -> wave index (non-plain levels)

    def in_ring(self, expr) -> sp.Expr:
        """``expr`` in Omega written for the ring (``Omega -> 1/W``)."""
        return sp.expand(sp.sympify(expr).xreplace({OMEGA_DIMLESS: 1 / _W}))


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
                       damped=model.damped, sample=sample, level_wave=level_wave)
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
        if g.free_symbols & ({Om} | known - allowed) or not (g.is_Symbol or g.is_Pow or g == sp.I):
            raise ComputationError(f"unexpected term {g} in the transfer matrices")
    problem.extra = extra
    problem.relations = roots
    return problem


# --------------------------------------------------------------------------------------
# the polynomial stage


class _Algebra:
    """The ring of the atoms per argument, ``W = 1/Omega``, the waves' ``Dl, iq`` and parameters.

    Every reduction rewrites a power ``x**q`` of one variable by a polynomial of
    lower degree in ``x`` (``s**2 = 1 - c**2``, ``c**2 = 1 - b**2 Sn**2``,
    ``Dl**2 = disc``, ``I**2 = -1``, ``root**Q = base``), and ``W * Omega = 1``;
    the leading terms are powers of distinct variables, so the normal form is
    unique.
    """

    def __init__(self, problem: _Problem):
        self.problem = problem
        self.groups = len(problem.groups)
        names, symbols = [], []
        def plain_like(grp):
            return grp.wave is None or problem.waves[grp.wave].scaled

        for g, grp in enumerate(problem.groups):
            kinds = ("c", "s", "ch", "sh") if plain_like(grp) else ("c", "Sn", "ch", "Sh")
            names += [f"{k}{g}" for k in kinds]
            symbols += list(grp.dummies)
        self.w = len(names)
        names.append("W")
        symbols.append(_W)
        self.wave_index = {}     # general waves: k -> (Dl, iq)
        self.scaled_index = {}   # founded waves: k -> Wb
        for k, wave in enumerate(problem.waves):
            if wave.scaled:
                self.scaled_index[k] = len(names)
                names.append(f"Wb{k}")
                symbols.append(wave.Wb)
                continue
            self.wave_index[k] = (len(names), len(names) + 1)
            names += [f"Dl{k}", f"iq{k}"]
            symbols += [wave.Dl, wave.iq]
        self.extra_index = {}
        for e in problem.extra:
            self.extra_index[e] = len(names)
            names.append(f"p{len(names)}")
            symbols.append(e)
        self.symbols = symbols
        self.ring = _Ring(names)
        self.nvars = len(names)
        # Omega = 1/W as a generator of its own (masses, waves); W * Omega -> 1 in reduce
        self.inv_w = self.extra_index.get(1 / _W)
        # pairs (W, 1/W) that cancel: Omega's and each founded wave's
        self.inverse_pairs = [(self.w, self.inv_w)] if self.inv_w is not None else []
        for k, idx in self.scaled_index.items():
            inv = self.extra_index.get(1 / problem.waves[k].Wb)
            if inv is not None:
                self.inverse_pairs.append((idx, inv))
        G = self.ring.gens
        half = self.ring.coefficient(sp.Rational(1, 2))
        self.rules = []   # (variable, power q, replacement of x**q); applied in this order
        self.N = {}
        for g, grp in enumerate(problem.groups):
            c, s, ch, sh = G[4 * g:4 * g + 4]
            if plain_like(grp):
                self.rules += [(4 * g + 1, 2, 1 - c * c), (4 * g + 3, 2, ch * ch - 1)]
                S, T, U, V = (ch + c) * half, (sh + s) * half, (ch - c) * half, (sh - s) * half
                self.N[g] = [[S, T, U, V], [V, S, T, U], [U, V, S, T], [T, U, V, S]]
            else:
                A, B = self.wave_squares(grp.wave)
                self.rules += [(4 * g, 2, 1 - B * s * s), (4 * g + 2, 2, 1 + A * sh * sh)]
        for k, (dl, _) in self.wave_index.items():
            self.rules.append((dl, 2, self.from_expr(problem.waves[k].disc_ring)))
        for e, idx in self.extra_index.items():
            if e == sp.I:
                self.rules.append((idx, 2, self.ring.one * -1))
            elif e in problem.relations:
                base, Q = problem.relations[e]
                self.rules.append((idx, Q, self.ring.one * self.ring.coefficient(base)))
        self._nf = [dict() for _ in self.rules]
        for (lvl_g, lvl), U in problem.matrices.items():
            self.N[(lvl_g, lvl)] = [[self.reduce(self.from_expr(e)) for e in row] for row in U]

    def wave_squares(self, k: int):
        """``(a**2, b**2) = ((t + Dl)/2, (Dl - t)/2)`` of wave ``k`` in the ring."""
        Dl = self.ring.gens[self.wave_index[k][0]]
        t = self.from_expr(self.problem.waves[k].t_ring)
        half = self.ring.coefficient(sp.Rational(1, 2))
        return (t + Dl) * half, (Dl - t) * half

    def from_expr(self, expr):
        poly = sp.Poly(expr, *self.symbols, domain=sp.QQ)
        return self.ring.from_dict({mon: self.ring.coefficient(_rational(cf))
                                    for mon, cf in poly.as_dict().items()})

    def _power(self, r: int, e: int):
        """Normal form of ``x**e`` under rule ``r`` alone (``e >= q``)."""
        idx, q, repl = self.rules[r]
        cache = self._nf[r]
        if e in cache:
            return cache[e]
        if e == q:
            cache[e] = repl
            return repl
        prev = self._power(r, e - 1) * self.ring.gens[idx]
        terms = self.ring.terms(prev)
        low = {m: c for m, c in terms.items() if m[idx] < q}
        top = {m[:idx] + (m[idx] - q,) + m[idx + 1:]: c for m, c in terms.items() if m[idx] >= q}
        out = self.ring.from_dict(low)
        if top:
            out = out + self.ring.from_dict(top) * repl
        cache[e] = out
        return out

    def reduce(self, p):
        """The normal form of ``p`` (see the class docstring)."""
        if p == 0:
            return p
        if self.ring.can_factor:
            return self._reduce_flint(p)
        return self._reduce_dict(p)  # pragma: no cover - depends on the installation

    def _reduce_flint(self, p):
        # division by the monomial x**q splits off the terms to rewrite (fast in C)
        gens = self.ring.gens
        for idx, q, repl in self.rules:
            while p.degrees()[idx] >= q:
                quo, rem = divmod(p, gens[idx] ** q)
                p = rem + repl * quo
        for w, iw in self.inverse_pairs:
            wv = gens[iw] * gens[w]
            while True:
                deg = p.degrees()
                if not (deg[iw] and deg[w]):
                    break
                quo, rem = divmod(p, wv)
                if quo == 0:
                    break
                p = rem + quo
        return p

    def _reduce_dict(self, p):  # pragma: no cover - without python-flint
        ring = self.ring
        for r, (idx, q, _) in enumerate(self.rules):
            terms = ring.terms(p)
            if not any(m[idx] >= q for m in terms):
                continue
            buckets: dict = {}
            for m, cf in terms.items():
                e = m[idx] if m[idx] >= q else 0
                key = m[:idx] + (0,) + m[idx + 1:] if e else m
                buckets.setdefault(e, {})[key] = cf
            out = ring.from_dict(buckets.pop(0, {}))
            for e, part in buckets.items():
                out = out + ring.from_dict(part) * self._power(r, e)
            p = out
        for w, iw in self.inverse_pairs:
            terms = ring.terms(p)
            out: dict = {}
            for m, cf in terms.items():
                if m[iw] and m[w]:
                    k = min(m[iw], m[w])
                    m = list(m)
                    m[iw] -= k
                    m[w] -= k
                    m = tuple(m)
                out[m] = out.get(m, 0) + cf
            p = ring.from_dict({m: c for m, c in out.items() if c != 0})
        return p

    def boundary_matrix(self) -> list:
        """The scaled ``R`` as a list of rows of polynomials (entries reduced)."""
        layout = self.problem.layout
        ring = self.ring
        cols = layout.columns
        E = [[ring.zero] * len(cols) for _ in range(layout.size)]
        for j, c in enumerate(cols):
            E[c][j] = ring.one
        for kind, data in self.problem.steps:
            if kind == "segments":
                for lvl, g in data:
                    N = self.N[g] if g in self.N else self.N[(g, lvl)]
                    blk = E[4 * lvl:4 * lvl + 4]
                    E[4 * lvl:4 * lvl + 4] = [
                        [self.reduce(sum((N[i][k] * blk[k][j] for k in range(4)
                                          if blk[k][j] != 0 and N[i][k] != 0), ring.zero))
                         for j in range(len(cols))]
                        for i in range(4)]
            else:
                new = {}
                for (row, col), expr in data.items():
                    v = self.from_expr(expr)
                    acc = new.get(row) or E[row][:]
                    for j in range(len(cols)):
                        if E[col][j] != 0:
                            acc[j] = acc[j] + v * E[col][j]
                    new[row] = acc
                for row, acc in new.items():
                    E[row] = [self.reduce(x) for x in acc]
        return [E[i] for i in layout.rows]

    def clear_inverse(self, p):
        """``p = q / prod disc_k**K_k``: the ``iq_k = 1/disc_k`` cleared.

        Returns ``q`` and ``[(k, K_k)]``.
        """
        ring = self.ring
        out = []
        for k, (_, iq) in self.wave_index.items():
            terms = ring.terms(p)
            K = max((m[iq] for m in terms), default=0)
            if not K:
                continue
            disc = self.from_expr(self.problem.waves[k].disc_ring)
            parts: dict = {}
            for m, cf in terms.items():
                parts.setdefault(m[iq], {})[m[:iq] + (0,) + m[iq + 1:]] = cf
            p = ring.zero
            for j, part in parts.items():
                p = p + ring.from_dict(part) * disc ** (K - j)
            out.append((k, K))
        return p, out


def _eliminate_constants(alg: _Algebra, M) -> tuple[sp.Rational, list]:
    """Eliminate on pivots that are nonzero rational constants: ``det M = factor * det M'``.

    Each step is an exact Schur complement on one pivot ``p`` (Markowitz's
    choice: fewest other entries in its row and column); ``det M = (-1)**(i+j)
    p det(M')``. The equations of rigid bodies and joints (compatibility,
    equilibrium) have such pivots in the scaled state, so they vanish before
    the expansion by minors.
    """
    ring = alg.ring
    M = [row[:] for row in M]
    factor = sp.Integer(1)
    while M:
        rows_nz = [sum(1 for x in row if x != 0) for row in M]
        cols_nz = [sum(1 for row in M if row[j] != 0) for j in range(len(M))]
        best = None
        for i, row in enumerate(M):
            for j, x in enumerate(row):
                if x == 0:
                    continue
                value = ring.constant_value(x)
                if value is None:
                    continue
                cost = (rows_nz[i] - 1) * (cols_nz[j] - 1)
                if best is None or cost < best[0]:
                    best = (cost, i, j, value)
        if best is None:
            break
        _, i, j, p = best
        factor *= p * (-1) ** (i + j)
        inv = ring.coefficient(1 / p)
        pivot_row = M[i]
        nxt = []
        for r, row in enumerate(M):
            if r == i:
                continue
            if row[j] != 0:
                f = row[j] * inv
                row = [alg.reduce(x - f * y) if y != 0 else x for x, y in zip(row, pivot_row)]
            nxt.append(row[:j] + row[j + 1:])
        M = nxt
    return factor, M


def _det_minors(M, zero, one):
    """Division-free determinant: expansion along rows with memoised minors.

    ``O(2**n n)`` products; exact in any commutative ring, and it keeps the
    product structure of block-decoupled matrices (no reduction in between).
    """
    n = len(M)
    if n == 0:
        return one
    minors = {(): one}
    for r in range(n):
        new = {}
        for cols in combinations(range(n), r + 1):
            acc = zero
            for pos, c in enumerate(cols):
                a = M[r][c]
                if a == 0:
                    continue
                m = minors.get(cols[:pos] + cols[pos + 1:])
                if m is None or m == 0:
                    continue
                acc = acc - a * m if (r - pos) % 2 else acc + a * m
            if acc != 0:
                new[cols] = acc
        minors = new
    return minors.get(tuple(range(n)), zero)


def _normalise(alg: _Algebra, p):
    """``p = c * q`` with ``q`` primitive over Z and its leading coefficient positive."""
    terms = alg.ring.terms(p)
    coeffs = [_rational(c) for c in terms.values()]
    den = math.lcm(*[int(c.q) for c in coeffs])
    num = math.gcd(*[int(c.p * den / c.q) for c in coeffs])
    scale = sp.Rational(den, num)
    lead = max(terms)  # lex order on exponent tuples = the ring's order
    if _rational(terms[lead]) < 0:
        scale = -scale
    q = p * alg.ring.coefficient(scale)
    return 1 / scale, q


def _blocks(M) -> tuple[int, list]:
    """Split ``M`` into independent square blocks (connected rows and columns).

    Returns the sign of the permutation and the blocks; ``det M = sign *
    prod(det(block))``, or ``(0, [])`` if a block is not square (then
    ``det M = 0``).
    """
    n = len(M)
    parent = list(range(2 * n))  # rows 0..n-1, columns n..2n-1

    def find(i):
        while parent[i] != i:
            parent[i] = parent[parent[i]]
            i = parent[i]
        return i

    for i in range(n):
        for j in range(n):
            if M[i][j] != 0:
                parent[find(i)] = find(n + j)
    comps: dict = {}
    for i in range(2 * n):
        comps.setdefault(find(i), ([], []))[i >= n].append(i if i < n else i - n)
    row_order, col_order, blocks = [], [], []
    for rows, cols in sorted(comps.values(), key=lambda rc: (rc[0] + rc[1])[:1]):
        if len(rows) != len(cols):
            return 0, []
        row_order += rows
        col_order += cols
        blocks.append([[M[i][j] for j in cols] for i in rows])
    return _perm_sign(row_order) * _perm_sign(col_order), blocks


def _perm_sign(perm) -> int:
    sign, seen = 1, set()
    for i in range(len(perm)):
        if i in seen:
            continue
        j, length = i, 0
        while j not in seen:
            seen.add(j)
            j = perm[j]
            length += 1
        if length % 2 == 0:
            sign = -sign
    return sign


#: Terms of an unreduced determinant beyond which it is reduced before factoring (models
#: with beams other than plain Euler-Bernoulli ones; plain ones are always factored first).
_FACTOR_UNREDUCED = 30000

_IDENTICALLY_ZERO = ("the characteristic determinant vanishes identically "
                     "(every frequency is an eigenvalue)")


def _factorise(alg: _Algebra, R):
    """``det R = constant * prod(f**e)``, the factors reduced and merged.

    Constant pivots are eliminated first; each independent block of the rest
    is expanded on its own; its determinant is factored before the reduction
    (where products are still visible), ``1/disc`` cleared, each factor
    reduced and factored again. A factor of the denominators ``disc`` has a
    negative multiplicity (they cancel against the numerator's where they
    can). Without python-flint only the block structure and the monomial
    content are split off (SymPy's multivariate factoring is too slow for
    these sizes).
    """
    pivots, R = _eliminate_constants(alg, R)
    sign, blocks = _blocks(R)
    if sign == 0:
        raise ComputationError(_IDENTICALLY_ZERO)
    constant = sp.Integer(sign) * pivots
    found: dict = {}   # key -> [poly, multiplicity]

    def add(h, e):
        nonlocal constant
        c3, h = _normalise(alg, h)
        constant *= c3 ** e
        key = tuple(sorted(alg.ring.terms(h).items()))
        if key in found:
            found[key][1] += e
        else:
            found[key] = [h, e]

    def add_factored(g, e):
        nonlocal constant
        if not alg.ring.can_factor:  # pragma: no cover - depends on the installation
            for h, e2 in _monomial_content(alg, g):
                add(h, e * e2)
            return
        c2, parts = alg.ring.factor(g)
        constant *= _rational(c2) ** e
        for h, e2 in parts:
            add(h, e * int(e2))

    for block in blocks:
        det = _det_minors(block, alg.ring.zero, alg.ring.one)
        if det == 0:
            raise ComputationError(_IDENTICALLY_ZERO)
        if not alg.ring.can_factor:  # pragma: no cover
            first = [(det, 1)]
        else:
            if alg.problem.waves and len(alg.ring.terms(det)) > _FACTOR_UNREDUCED:
                # too long to factor as it is (with the waves' Dl, iq it takes minutes):
                # the normal form is far shorter, at the price of products it may hide
                det = alg.reduce(det)
            content, first = alg.ring.factor(det)
            constant *= _rational(content)
        for f, e in first:
            e = int(e)
            q, cleared = alg.clear_inverse(f)
            g = alg.reduce(q)
            if g == 0:
                raise ComputationError(_IDENTICALLY_ZERO)
            for k, K in cleared:
                add_factored(alg.from_expr(alg.problem.waves[k].disc_ring), -K * e)
            if g == f:
                add(f, e)
            else:
                add_factored(g, e)
    regrouped = _regroup_discriminants(alg, found, add)   # add() changes constant too
    constant *= regrouped
    return constant, [tuple(v) for v in found.values() if v[1] != 0]


def _regroup_discriminants(alg: _Algebra, found: dict, add) -> sp.Rational:
    """Irreducible factors of ``disc_k`` left over in the proportions of ``disc_k`` become
    ``disc_k**j`` (written ``(a**2 + b**2)**(2 j)``); returns the constant this takes.

    ``found`` maps keys to ``[poly, multiplicity]``; ``add(poly, e)`` adds to it.
    """
    ring = alg.ring
    constant = sp.Integer(1)
    if not ring.can_factor:  # pragma: no cover - depends on the installation
        return constant
    for k in alg.wave_index:
        disc = alg.from_expr(alg.problem.waves[k].disc_ring)
        _, parts = ring.factor(disc)
        pieces, mono = [], []
        for h, m in parts:
            _, h = _normalise(alg, h)
            (mono if len(ring.terms(h)) == 1 else pieces).append((h, int(m)))
        keys = [tuple(sorted(ring.terms(h).items())) for h, _ in pieces]
        if not pieces or any(k not in found for k in keys):
            continue
        ratios = {Fraction(int(found[k][1]), m) for k, (_, m) in zip(keys, pieces)}
        if len(ratios) != 1:
            continue
        j = ratios.pop()
        if j.denominator != 1:
            continue
        j = int(j)
        product = ring.one
        for h, m in pieces + mono:
            product = product * h**m
        # disc = ratio * prod(pieces) * prod(mono)
        ratio = _rational(ring.terms(disc)[max(ring.terms(disc))]) / _rational(
            ring.terms(product)[max(ring.terms(product))])
        for k in keys:
            del found[k]
        add(disc, j)
        for h, m in mono:
            add(h, -m * j)
        constant /= ratio**j
    return constant


def _monomial_content(alg: _Algebra, p):
    """``p`` as ``[(gen, e), ..., (rest, 1)]``, splitting off the common monomial."""
    terms = alg.ring.terms(p)
    low = [min(m[i] for m in terms) for i in range(alg.nvars)]
    out = [(alg.ring.gens[i], k) for i, k in enumerate(low) if k]
    if any(low):
        shifted = {tuple(a - b for a, b in zip(m, low)): c for m, c in terms.items()}
        p = alg.ring.from_dict(shifted)
    return out + [(p, 1)]


# --------------------------------------------------------------------------------------
# back to SymPy


def _harmonic_product(a: dict, b: dict, hyperbolic: bool) -> dict:
    """Twice the product of two sums ``{(kind, freq): coeff}`` of cos/sin (cosh/sinh) terms.

    ``kind`` is 0 for cos (cosh), 1 for sin (sinh); ``freq`` an integer vector
    normalised so that its first nonzero entry is positive. Integer
    coefficients stay integers (the factor 2 of product-to-sum is left out).
    """
    out: dict = {}

    def add(kind, freq, coeff):
        if not any(freq):
            if kind == 1:
                return
        else:
            first = next(x for x in freq if x)
            if first < 0:
                freq = tuple(-x for x in freq)
                if kind == 1:
                    coeff = -coeff
        key = (kind, freq)
        out[key] = out.get(key, 0) + coeff

    for (ka, fa), ca in a.items():
        for (kb, fb), cb in b.items():
            c = ca * cb
            plus = tuple(x + y for x, y in zip(fa, fb))
            minus = tuple(x - y for x, y in zip(fa, fb))
            if ka == 0 and kb == 0:      # cos a cos b
                add(0, minus, c)
                add(0, plus, c)
            elif ka == 1 and kb == 1:    # sin a sin b; sinh a sinh b
                if hyperbolic:
                    add(0, plus, c)
                    add(0, minus, -c)
                else:
                    add(0, minus, c)
                    add(0, plus, -c)
            elif ka == 1:                # sin a cos b
                add(1, plus, c)
                add(1, minus, c)
            else:                        # cos a sin b
                add(1, plus, c)
                add(1, minus, -c)
    return {k: v for k, v in out.items() if v != 0}


class _Writer:
    """Turns factors (polynomials of the algebra) into SymPy expressions."""

    def __init__(self, alg: _Algebra, Omega: sp.Symbol):
        self.alg = alg
        self.Omega = Omega
        p = alg.problem
        self.trig_args, self.hyp_args, self.atoms = [], [], []
        for grp in p.groups:
            if grp.wave is None:
                trig = hyp = (Omega, grp.arg)
            elif p.waves[grp.wave].scaled:
                trig = hyp = (p.waves[grp.wave].b, grp.arg)
            else:
                wave = p.waves[grp.wave]
                trig, hyp = (wave.b, grp.arg), (wave.a, grp.arg)
            self.trig_args.append(trig)
            self.hyp_args.append(hyp)
            self.atoms += [sp.cos(sp.Mul(*trig)), sp.sin(sp.Mul(*trig)),
                           sp.cosh(sp.Mul(*hyp)), sp.sinh(sp.Mul(*hyp))]
        # what each variable beyond the atoms and W stands for: ("Omega", 1) for 1/W
        self.outer: list = []
        for k, (dl, iq) in alg.wave_index.items():
            wave = p.waves[k]
            self.outer += [(dl, wave.a**2 + wave.b**2), (iq, (wave.a**2 + wave.b**2) ** -2)]
        for k, idx in alg.scaled_index.items():
            self.outer.append((idx, 1 / p.waves[k].b))
        for e, idx in alg.extra_index.items():
            if idx == alg.inv_w:
                continue
            if e.is_Pow and e.exp == -1 and e.base in {w.Wb for w in p.waves if w.scaled}:
                (wave,) = [w for w in p.waves if w.scaled and w.Wb == e.base]
                self.outer.append((idx, wave.b))
            elif e in p.relations:
                base, Q = p.relations[e]
                self.outer.append((idx, base ** sp.Rational(1, Q)))
            else:
                self.outer.append((idx, e))
        # Sn = sin(b l)/b and Sh = sinh(a l)/a: the divisions go outside
        self.scaled = []
        for g, grp in enumerate(p.groups):
            if grp.wave is not None and not p.waves[grp.wave].scaled:
                wave = p.waves[grp.wave]
                self.scaled += [(4 * g + 1, wave.b), (4 * g + 3, wave.a)]
        # one divisor per wave number (Sn of every segment of a kind divides by the same b)
        by_symbol: dict = {}
        for idx, symbol in self.scaled:
            by_symbol.setdefault(symbol, []).append(idx)
        self.divisors = list(by_symbol.items())
        self.known = self._known_factors()
        self._trig_cache: dict = {}
        self._rest_ring = None
        self._outer_cache: dict = {}
        self._collected: dict = {}

    def _known_factors(self) -> dict:
        """Polynomials in Omega that are functions of one wave's ``a, b``: written so."""
        alg, out = self.alg, {}
        for wave in alg.problem.waves:
            if wave.scaled:
                continue
            a, b = wave.a, wave.b
            pairs = [(wave.disc, (a**2 + b**2) ** 2), (wave.d, -(a**2) * b**2)]
            if not wave.t.is_number:
                pairs.append((wave.t, a**2 - b**2))
            for expr, form in pairs:
                poly = alg.from_expr(alg.problem.in_ring(expr))
                if poly == 0 or alg.ring.constant_value(poly) is not None:
                    continue
                c, q = _normalise(alg, poly)
                out.setdefault(tuple(sorted(alg.ring.terms(q).items())), (form, 1 / c))
        return out

    def _harmonics(self, exps: tuple, hyperbolic: bool) -> tuple[dict, int]:
        """cos/sin (cosh/sinh) monomial -> (integer sum over combined arguments, shift).

        The monomial equals the sum divided by ``2**shift``.
        """
        key = (exps, hyperbolic)
        if key in self._trig_cache:
            return self._trig_cache[key]
        G = self.alg.groups
        acc = {(0, tuple([0] * G)): 1}
        shift = -1
        for g in range(G):
            unit = tuple(1 if i == g else 0 for i in range(G))
            for kind, power in ((0, exps[2 * g]), (1, exps[2 * g + 1])):
                for _ in range(power):
                    if shift < 0:   # the first factor needs no product-to-sum
                        acc = {(kind, unit): 1}
                    else:
                        acc = _harmonic_product(acc, {(kind, unit): 1}, hyperbolic)
                    shift += 1
        result = (acc, max(shift, 0))
        self._trig_cache[key] = result
        return result

    def _function(self, kind, freq, hyperbolic):
        """``(sign, f(sum(freq * args)))``, the argument positive at the sample."""
        args = self.hyp_args if hyperbolic else self.trig_args
        by_symbol: dict = {}
        for k, (symbol, coef) in zip(freq, args):
            if k:
                by_symbol[symbol] = by_symbol.get(symbol, 0) + k * coef
        parts = {s: sp.expand(c) for s, c in by_symbol.items()}
        sample = self.alg.problem.sample
        at = sp.Add(*[s * c for s, c in parts.items()])
        at = at.xreplace(sample) if sample else at
        sign = 1
        if at.is_negative:
            parts, sign = {s: -c for s, c in parts.items()}, (-1 if kind == 1 else 1)
        fn = ((sp.cos, sp.sin), (sp.cosh, sp.sinh))[hyperbolic][kind]
        return sign, fn(sp.Add(*[sp.Mul(s, c) for s, c in parts.items()]))

    def split(self, poly):
        """``poly = Omega**m * sum_k (outer_k) * (atoms)``: ``m`` and the terms by outer factor."""
        alg = self.alg
        terms = alg.ring.terms(poly)
        iw = alg.inv_w

        def omega(mon):
            return (mon[iw] if iw is not None else 0) - mon[alg.w]

        m = min(omega(mon) for mon in terms)
        groups: dict = {}
        for mon, cf in terms.items():
            rest = (omega(mon) - m,) + tuple(mon[i] for i, _ in self.outer) + tuple(
                sum(mon[i] for i in idx) for _, idx in self.divisors)
            groups.setdefault(rest, {})[mon[:alg.w]] = _rational(cf)
        return m, groups

    def _outer(self, rest):
        cached = self._outer_cache.get(rest)
        if cached is not None:
            return cached
        out = self.Omega ** rest[0]
        k = 1
        for _, e in self.outer:
            out *= e ** rest[k]
            k += 1
        for e, _ in self.divisors:
            out /= e ** rest[k]
            k += 1
        self._outer_cache[rest] = out
        return out

    def atoms_form(self, groups) -> sp.Expr:
        total = []
        for rest, inner in groups.items():
            s = sp.Add(*[cf * sp.Mul(*[a ** k for a, k in zip(self.atoms, mon) if k])
                         for mon, cf in inner.items()])
            total.append(self._outer(rest) * s)
        return sp.Add(*total)

    def _coefficient(self, by_rest: dict) -> sp.Expr:
        """``sum(v * outer(rest))``, factored (by python-flint) when that is shorter."""
        def written(terms):
            return sp.Add(*[sp.Rational(v.numerator, v.denominator) * self._outer(rest)
                            for rest, v in terms.items()])

        expr = written(by_rest)
        if len(by_rest) < 2 or not self.alg.ring.can_factor:
            return expr
        if self._rest_ring is None:
            self._rest_ring = _Ring([f"r{i}" for i in range(len(next(iter(by_rest))))])
        ring = self._rest_ring
        poly = ring.from_dict({k: ring.coefficient(sp.Rational(v.numerator, v.denominator))
                               for k, v in by_rest.items()})
        content, parts = ring.factor(poly)
        if len(parts) < 2 and all(e == 1 for _, e in parts):
            return expr
        factored = _rational(content) * sp.Mul(*[
            written({m: Fraction(int(c.numerator), int(c.denominator))
                     for m, c in ring.terms(f).items()}) ** int(e) for f, e in parts])
        return factored if sp.count_ops(factored) < sp.count_ops(expr) else expr

    def collected_forms(self, groups, harmonic_terms=None) -> tuple[sp.Expr, sp.Expr]:
        """The atoms and the harmonic form, each function with one coefficient.

        The forms above group by the outer factor (powers of ``Omega``, wave
        numbers, parameters); where many of those multiply the same functions
        (Timoshenko beams: polynomials in ``omega``), collecting by function is
        shorter.
        """
        atoms: dict = {}
        harmonic: dict = {}
        for rest, inner in groups.items():
            for mon, cf in inner.items():
                atoms.setdefault(mon, {})[rest] = Fraction(int(cf.p), int(cf.q))
            parts = (harmonic_terms or {}).get(rest) or self._harmonic_terms(inner)
            for key, v in parts.items():
                harmonic.setdefault(key, {})[rest] = v
        key = ("collected", tuple(sorted(groups)), id(groups))
        if self._collected.get("key") != key:
            self._collected = {"key": key}
        cache = self._collected
        if "a" not in cache:
            cache["a"] = sp.Add(*[self._coefficient(c) * sp.Mul(
                *[x ** k for x, k in zip(self.atoms, mon) if k]) for mon, c in atoms.items()])
            cache["h"] = sp.Add(*[self._coefficient(c) * self._harmonic_function(k)
                                  for k, c in harmonic.items()])
        return cache["a"], cache["h"]

    def _harmonic_function(self, key) -> sp.Expr:
        (tk, tf), (hk, hf) = key
        st, t = self._function(tk, tf, False) if any(tf) else (1, sp.Integer(1))
        sh, h = self._function(hk, hf, True) if any(hf) else (1, sp.Integer(1))
        return st * sh * t * h

    def _harmonic_terms(self, inner) -> dict:
        """``{((kind, freq) trig, (kind, freq) hyperbolic): Fraction}`` of one group."""
        G = self.alg.groups
        expanded = []
        for mon, cf in inner.items():
            trig = tuple(mon[4 * g + i] for g in range(G) for i in (0, 1))
            hyp = tuple(mon[4 * g + i] for g in range(G) for i in (2, 3))
            ht, st = self._harmonics(trig, False)
            hh, sh = self._harmonics(hyp, True)
            expanded.append((cf, ht, hh, st + sh))
        den = math.lcm(*[int(cf.q) for cf, *_ in expanded])
        top = max(s for *_, s in expanded)
        acc: dict = {}
        for cf, ht, hh, shift in expanded:
            scale = int(cf.p) * (den // int(cf.q)) << (top - shift)
            for kt, vt in ht.items():
                for kh, vh in hh.items():
                    key = (kt, kh)
                    acc[key] = acc.get(key, 0) + scale * vt * vh
        return {k: Fraction(v, den << top) for k, v in acc.items() if v != 0}

    def harmonic_form(self, groups, terms=None) -> sp.Expr:
        terms = terms or {rest: self._harmonic_terms(inner) for rest, inner in groups.items()}
        return sp.Add(*[self._outer(rest) * sp.Add(*[
            sp.Rational(v.numerator, v.denominator) * self._harmonic_function(key)
            for key, v in parts.items()]) for rest, parts in terms.items()])

    def best(self, poly):
        """``(m, expr, ratio)`` with ``poly = ratio * Omega**m * expr``; the shortest form."""
        key = tuple(sorted(self.alg.ring.terms(poly).items()))
        if key in self.known:
            form, ratio = self.known[key]
            return 0, form, ratio
        m, groups = self.split(poly)
        harmonic = {rest: self._harmonic_terms(inner) for rest, inner in groups.items()}
        # SymPy is slow on long sums: the forms are built only if their number of terms
        # is near the least; SymPy's count of operations chooses among those
        def outer(rest):
            return sum(1 for e in rest if e)

        def atom_ops(mon):
            return 1 + int(sum(mon))

        def harmonic_ops(key):
            (_, tf), (_, hf) = key
            return 1 + any(tf) + any(hf)

        estimate = [sum(outer(r) + sum(map(harmonic_ops, v)) for r, v in harmonic.items()),
                    sum(outer(r) + sum(map(atom_ops, v)) for r, v in groups.items())]
        builders = [lambda: self.harmonic_form(groups, harmonic), lambda: self.atoms_form(groups)]
        if len(groups) > 1:
            by_key: dict = {}
            for r, v in harmonic.items():
                for key in v:
                    by_key.setdefault(key, []).append(r)
            by_mon: dict = {}
            for r, v in groups.items():
                for mon in v:
                    by_mon.setdefault(mon, []).append(r)
            estimate += [sum(harmonic_ops(k) + sum(1 + outer(r) for r in rs)
                             for k, rs in by_key.items()),
                         sum(atom_ops(k) + sum(1 + outer(r) for r in rs)
                             for k, rs in by_mon.items())]
            builders += [lambda: self.collected_forms(groups, harmonic)[1],
                         lambda: self.collected_forms(groups, harmonic)[0]]
        low = min(estimate)
        forms = [build() for build, n in zip(builders, estimate) if n <= 1.5 * low]
        sizes = [sp.count_ops(f) for f in forms]
        return m, forms[sizes.index(min(sizes))], sp.Integer(1)
# --------------------------------------------------------------------------------------
# the result


@dataclass(frozen=True)
class CharacteristicEquation:
    """A characteristic function in closed form: ``det R = constant * delta``.

    Attributes
    ----------
    variable : sympy.Symbol
        ``omega`` (rad/s, ``lam = I*omega``) for undamped models, ``lam`` for damped ones.
    delta : sympy.Expr
        The characteristic function in :attr:`variable`, constant factor removed.
    constant : sympy.Expr
        ``det R(lam) = constant * delta`` (independent of the frequency).
    delta_Omega : sympy.Expr
        The same function of ``Omega = beta_1 L_1`` (the paper's frequency parameter).
    constant_Omega : sympy.Expr
        ``det R = constant_Omega * delta_Omega``.
    Omega : sympy.Expr
        ``Omega`` as a function of :attr:`variable`.
    power : int
        ``delta_Omega = Omega**power * prod(f**e for f, e in factors)``.
    factors : tuple of (sympy.Expr, int)
        Factors in ``Omega`` with their multiplicities.
    symbols : tuple of str
        Model parameters left symbolic.
    seconds : float
        Time the derivation took.
    notes : tuple of str
        How the result is structured (e.g. kept factored).
    definitions : dict
        The wave numbers ``a_<beam>``, ``b_<beam>`` of beams that are not
        plain Euler–Bernoulli beams, and ``Omega`` when the closed form uses it,
        as functions of :attr:`variable`; :attr:`delta_Omega` and
        :attr:`factors` are written in them, :attr:`delta` has them substituted.
    """

    variable: sp.Symbol
    delta: sp.Expr
    constant: sp.Expr
    delta_Omega: sp.Expr
    constant_Omega: sp.Expr
    Omega: sp.Expr
    power: int
    factors: tuple
    symbols: tuple = ()
    seconds: float = 0.0
    notes: tuple = field(default_factory=tuple)
    model_name: str | None = None
    definitions: dict = field(default_factory=dict)

    @property
    def equation(self) -> sp.Expr:
        """``prod(f**e)`` in ``Omega`` (and wave numbers): the textbook frequency equation ``= 0``.

        Powers of a single wave number (like ``Omega**power``) are left out.
        """
        return sp.Mul(*[f**e for f, e in self.factors if not f.is_Symbol])

    def count_ops(self) -> int:
        """Size of :attr:`delta_Omega` (the closed form) as SymPy counts operations."""
        return int(sp.count_ops(self.delta_Omega))

    def latex(self) -> str:
        """LaTeX of ``delta`` in :attr:`variable`."""
        return sp.latex(self.delta)

    def to_dict(self) -> dict:
        """The JSON contract ``{"variable", "delta", "latex"}`` plus the Omega form.

        ``delta`` parses with :func:`sympy.sympify` into the function of
        ``variable``; ``delta_Omega`` with ``Omega`` (and the wave numbers of
        ``definitions``, each a function of ``variable``) likewise.
        """
        return {
            "variable": str(self.variable),
            "delta": str(self.delta),
            "latex": self.latex(),
            "Omega": str(self.Omega),
            "delta_Omega": str(self.delta_Omega),
            "latex_Omega": sp.latex(self.delta_Omega),
            "power_Omega": self.power,
            "factors_Omega": [{"factor": str(f), "multiplicity": e} for f, e in self.factors],
            "constant": str(self.constant),
            "symbols": list(self.symbols),
            "count_ops": self.count_ops(),
            "seconds": round(self.seconds, 3),
            "notes": list(self.notes),
            "model": self.model_name,
            "definitions": {str(k): str(v) for k, v in self.definitions.items()},
        }

    def to_json(self) -> str:
        return json.dumps(self.to_dict(), indent=2)

    def __str__(self) -> str:
        return f"Delta({self.variable}) = {self.delta}"

    def _repr_latex_(self) -> str:
        """``Delta(variable) = ...`` typeset (Jupyter)."""
        return f"$\\Delta({sp.latex(self.variable)}) = {self.latex()}$"


def characteristic_equation(model: Model, symbolic=()) -> CharacteristicEquation:
    """The characteristic function of ``model`` in closed form.

    Parameters
    ----------
    model : Model
        Fields may contain parameters without value; they stay symbols.
    symbolic : iterable of str
        Parameters to keep symbolic although the model gives them a value;
        that value then only orders cuts that the symbols cannot (``x1`` and
        ``1 - x1``).

    Returns
    -------
    CharacteristicEquation

    Raises
    ------
    ModelError
        A named parameter does not exist, or the order of the cuts depends on
        a parameter without value.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI="EI", m="m", L="L", left="pinned", right="pinned"),))
    >>> eq = characteristic_equation(pp)
    >>> eq.delta_Omega
    sin(Omega)*sinh(Omega)/Omega**2
    >>> eq.Omega
    L*m**(1/4)*sqrt(omega)/EI**(1/4)
    """
    start = time.perf_counter()
    model_in = model
    model, sample = _prepare(model, tuple(symbolic))
    problem = _build_problem(model, sample)
    alg = _Algebra(problem)
    R = alg.boundary_matrix()
    constant, factors = _factorise(alg, R)
    Om = OMEGA_DIMLESS
    writer = _Writer(alg, Om)
    founded = [w.b for w in problem.waves if w.scaled]
    pre_c, pre_p, pre_b = _split_powers(problem.prefactor, Om, founded)
    power = pre_p
    out_factors = [(bk, p) for bk, p in pre_b.items() if p]
    frequency_symbols = [s for w in problem.waves for s in (w.a, w.b)]
    for poly, e in factors:
        m, expr, ratio = writer.best(poly)
        constant *= ratio**e
        power += m * e
        if not expr.has(Om, *frequency_symbols):
            constant *= expr ** e
            continue
        if expr == Om:
            power += e
            continue
        out_factors.append((expr, e))
    c_merge, p_merge, out_factors = _merge_factors(out_factors, Om)
    constant *= c_merge
    power += p_merge
    mu1, L1 = problem.omega_of["mu1"], problem.omega_of["L1"]
    if problem.damped:
        variable, lam = LAM, LAM
        Omega_of_var = L1 * mu1 * sp.sqrt(sp.I * LAM)
    else:
        variable, lam = OMEGA, sp.I * OMEGA
        Omega_of_var = L1 * mu1 * sp.sqrt(OMEGA)
    definitions = _wave_definitions(problem, lam)
    if problem.waves and not any(_is_plain(b) for b in problem.layout.model.beams):
        # no plain beam: the frequency left in the coefficients is the model's variable
        back = {Om: Omega_of_var}
        c_poly, out_factors = _polynomials_in(variable, [(_tidy(f.xreplace(back)), e)
                                                         for f, e in out_factors])
        constant *= c_poly
        c_disc, out_factors = _discriminants_back(problem, lam, variable, out_factors)
        constant *= c_disc
        scale = Omega_of_var ** power
        power = 0
    else:
        definitions = {Om: Omega_of_var, **definitions}
        scale = sp.Integer(1)
    out_factors.sort(key=lambda fe: (sp.count_ops(fe[0]), str(fe[0])))
    constant_Omega = sp.simplify(pre_c * constant)
    delta_Omega = Om ** power * scale * sp.Mul(*[f**e for f, e in out_factors])
    delta = delta_Omega.xreplace({Om: Omega_of_var, **definitions})
    # what xreplace leaves as a constant factor in front of the power of the variable
    c_scale, rest = delta.as_independent(variable, as_Add=False)
    delta = rest
    constant = sp.simplify(constant_Omega * c_scale)
    if power == 0 and scale != 1:
        # the closed form holds the variable's power itself; keep constant_Omega exact
        c_form, rest_form = delta_Omega.as_independent(variable, *definitions, as_Add=False)
        delta_Omega = rest_form
        constant_Omega = sp.simplify(constant_Omega * c_form)
    symbols = tuple(sorted(s.name for s in sp.sympify(delta).free_symbols
                           if s not in (variable,)))
    notes = []
    if len(out_factors) > 1 or any(e > 1 for _, e in out_factors):
        notes.append("kept factored: " + ", ".join(
            f"{sp.count_ops(f)} ops x{e}" for f, e in out_factors))
    if problem.waves:
        notes.append("wave numbers: " + ", ".join(
            f"{s} = {v}" for s, v in definitions.items() if s != Om))
    return CharacteristicEquation(
        variable=variable, delta=delta, constant=constant, delta_Omega=delta_Omega,
        constant_Omega=constant_Omega, Omega=Omega_of_var, power=int(power),
        factors=tuple(out_factors), symbols=symbols,
        seconds=time.perf_counter() - start, notes=tuple(notes),
        model_name=model_in.source or model_in.title or None, definitions=definitions)


def _merge_factors(factors, Om):
    """Numbers out, equal bases together: ``(2 b**2)**2 / (4 b**4)**2 -> b**-4 / 4``.

    Returns the constant, the power of ``Om`` and the merged ``(base, exponent)``.
    """
    constant, power, merged = sp.Integer(1), 0, {}
    for f, e in factors:
        c, parts = f.as_coeff_mul()
        constant *= c**e
        for part in parts:
            base, p = part.as_base_exp()
            if base == Om:
                power += p * e
            else:
                merged[base] = merged.get(base, 0) + p * e
    return constant, int(power), [(b, int(e)) for b, e in merged.items() if e != 0]


def _discriminants_back(problem: _Problem, lam, variable, factors):
    """A polynomial factor in ``variable`` proportional to ``t**2 - 4 d`` of a wave is
    ``(a**2 + b**2)**2``: written so, it cancels against the denominators."""
    constant, out = sp.Integer(1), []
    discs = []
    for wave in problem.waves:
        if wave.scaled:
            continue
        t, d = _wave_segment(wave.beam).invariants(sp.expand(lam**2))
        discs.append((sp.expand(t**2 - 4 * d), wave.a**2 + wave.b**2))
    for f, e in factors:
        for disc, form in discs:
            if f.free_symbols <= {variable} | disc.free_symbols and f.has(variable):
                ratio = sp.simplify(f / disc)
                if ratio.is_number and ratio != 0:
                    constant *= ratio**e
                    f, e = form, 2 * e
                    break
        out.append((f, e))
    merged: dict = {}
    for f, e in out:
        merged[f] = merged.get(f, 0) + e
    return constant, [(f, e) for f, e in merged.items() if e != 0]


def _polynomials_in(variable, factors):
    """Factors that are polynomials in ``variable`` only, multiplied and factored again in it.

    Factored in ``Omega ~ sqrt(omega)``, ``omega**2 - c`` splits into
    ``(k omega - sqrt(c)) (k omega + sqrt(c))``: refactored it is whole again.
    """
    plain, rest = [], []
    for f, e in factors:
        (plain if f.free_symbols <= {variable} and f.is_polynomial(variable) else rest).append(
            (f, e))
    if len(plain) < 2:
        return sp.Integer(1), factors
    out, constant = [], sp.Integer(1)
    for sign in (1, -1):
        product = sp.Mul(*[f ** (e * sign) for f, e in plain if e * sign > 0])
        if product == 1:
            continue
        c, parts = sp.factor_list(sp.expand(product), variable)
        constant *= c**sign
        out += [(f, sign * int(e)) for f, e in parts]
    return constant, rest + out


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Powers of the frequency gathered (``sqrt(omega)**4 -> omega**2``)."""
    return sp.powsimp(sp.expand_power_base(expr, force=True))


def _wave_definitions(problem: _Problem, lam) -> dict:
    """``{a: ..., b: ...}`` of every wave kind, in the model's variable (``lam = I omega``)."""
    out = {}
    for wave in problem.waves:
        t, d = (sp.simplify(v) for v in _wave_segment(wave.beam).invariants(sp.expand(lam**2)))
        if wave.equal:
            out[wave.b] = sp.factor(-d) ** sp.Rational(1, 4)
            continue
        root = sp.sqrt(sp.factor(t**2 / 4 - d))
        out[wave.a] = sp.sqrt(t / 2 + root)
        out[wave.b] = sp.sqrt(-t / 2 + root)
    return out


def _split_powers(expr, x, others):
    """``expr = c * x**p * prod(y**q)`` over ``others``: ``(c, p, {y: q})``."""
    expr = sp.powsimp(sp.expand_power_base(sp.sympify(expr), force=True))
    powers = {}
    for y in others:
        c, q = expr.as_coeff_exponent(y)
        powers[y] = int(q)
        expr = c
    c, p = _split_power(expr, x)
    return c, p, powers


def _split_power(expr, x):
    """``expr = c * x**p`` with ``c`` free of ``x``."""
    expr = sp.powsimp(sp.expand_power_base(sp.sympify(expr), force=True))
    c, p = expr.as_coeff_exponent(x)
    if c.has(x):
        raise ComputationError(f"cannot separate the power of {x} in {expr}")
    return c, int(p)
