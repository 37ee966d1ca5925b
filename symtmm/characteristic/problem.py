"""The scaled transfer problem: the boundary problem in SymPy terms, ready for the ring.

Step 1 of the method (:mod:`symtmm.characteristic`): each plain level's state
is scaled by ``diag(1, beta_j, EI_j beta_j**2, EI_j beta_j**3)`` so that its
segment matrices hold only ``S, T, U, V`` of ``beta_j l``; every distinct
argument becomes a :class:`_Group` of atoms (``c, s, ch, sh``), every kind of
beam whose wave numbers are not proportional to ``Omega`` a :class:`_Wave`,
and the point elements' entries are written in ``W = 1/Omega``. Numeric
radicals become symbols with their defining relation, so that everything is
a polynomial over the rationals.

Two beams joined by a layer over a piece are one member (a :class:`_Member` per
distinct matrix ``X / l**4``, see :func:`_member_matrix`): its ``8 x 8`` matrix is
written through the two wave numbers ``p, q`` of ``X`` (``p**4, q**4`` its
eigenvalues) and the coupling ``C`` between them; a beam that is nowhere outside
such members keeps its physical state (scaled by ``diag(1, 1, EI, EI)`` only).

A rod (:func:`symtmm.model.rod`) is two independent oscillators, axial on ``(Y, Q) = (u,
-N)`` and torsional on ``(Theta, M) = (phi, T)``, with the wave numbers ``beta_u**2 = -(m
lam**2 + kw) / EA`` and ``beta_t**2 = -rhoIp lam**2 / GJ``. Its state is scaled by
``diag(1, 1, GJ beta_t, EA beta_u)`` so that a segment holds only ``cos, sin`` of ``beta
l``: a rod's groups are those atoms of ``arg`` times its :attr:`_Group.rod` frequency,
``Omega**2`` beside plain beams, ``Omega`` itself in a model without plain beams (then
``Omega = beta_u L`` of the first rod), or the symbol ``b_<rod>`` of rods on an axial
foundation (a :class:`_RodWave`, with ``1/b`` a generator like ``W``). A rod without
torsion keeps its massless twist: ``Theta' = M / GJ``, ``M' = 0``, a constant block.
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
#: Dimensionless frequency ``Omega = beta_1 L_1`` of the first plain beam (in a model
#: without plain beams but with rods, of the first rod: ``beta_u L``).
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
class _Branch:
    """One wave number ``nu`` of a layered member (``nu**4`` an eigenvalue of ``X / l**4``).

    ``kind`` says how the ring holds it: ``"free"``, its own generator ``V`` (printed as
    :attr:`symbol`) and ``Wv = 1/V``, a Laurent pair like ``W`` and ``Omega``;
    ``"plain"``, ``nu = ratio * Omega`` (``mu = ratio**4 Omega**4``: the atoms are a
    plain beam's); ``"founded"``, ``nu = b`` of the founded wave ``wave`` (``mu = b**4``).
    ``mu`` (in ``Omega``) is known where it is a polynomial.
    """

    symbol: sp.Symbol
    mu: sp.Expr | None = None
    kind: str = "free"
    ratio: sp.Expr = None
    wave: int | None = None
    V: sp.Dummy = field(default_factory=lambda: sp.Dummy("V"))
    Wv: sp.Dummy = field(default_factory=lambda: sp.Dummy("Wv", positive=True))

    def value(self, waves) -> sp.Expr:
        """``nu`` in the terms of the problem (``Omega``, a founded ``b``, or ``V``)."""
        if self.kind == "plain":
            return self.ratio * OMEGA_DIMLESS
        if self.kind == "founded":
            return waves[self.wave].b
        return self.V

    def printed(self, waves, Omega=OMEGA_DIMLESS) -> sp.Expr:
        """``nu`` as the closed form writes it: its symbol, ``ratio Omega`` or ``b``."""
        if self.kind == "free":
            return self.symbol
        return self.value(waves).xreplace({OMEGA_DIMLESS: Omega})

    def power(self, e: int, waves) -> sp.Expr:
        """``nu**e``, a negative power of a free branch through ``Wv``."""
        if e < 0 and self.kind == "free":
            return self.Wv ** (-e)
        return self.value(waves) ** e


@dataclass
class _Member:
    """Two beams joined by a layer: one kind per pair of levels and matrix ``Xh = X / l**4``.

    Over a piece of length ``l`` the member's transfer matrix is a matrix function of
    ``Xh`` (:mod:`symtmm.elements.layer`), and a matrix function of a ``2 x 2`` matrix
    is ``f(Xh) = f(p**4) E1 + f(q**4) E2`` with ``p**4, q**4`` its eigenvalues (the
    roots of ``mu**2 - t mu + d``) and the projectors ``E1, E2 = 1/2 +- C``,

        C = (Xh - t/2) / (p**4 - q**4) = [[c, e], [rho e, -c]],   c**2 + rho e**2 = 1/4

    (``C**2 = I/4``; ``rho = X_21 / X_12 = EI_a / EI_b``). So the member is written as
    two beams with the wave numbers ``p`` and ``q`` (two :class:`_Branch`, Laurent
    generators: ``sin(p l)/p**3`` needs ``1/p``) and the coupling ``c, e``, generators
    with that one relation, printed as what they stand for. Nothing ties ``p, q, c, e``
    to ``Omega`` in the ring: the relations of the projectors are what make ``det R``
    factor, and ``Delta`` is an entire function of ``t, d`` for any branch of the roots.
    Where ``disc = t**2 - 4 d`` is the square of a polynomial (:attr:`root`: identical
    beams, ``(2 k/EI)**2``) the eigenvalues are polynomials and ``C`` is rational:
    ``c = 0``, ``e = 1/2`` for identical beams, and an eigenvalue ``c Omega**4`` (their
    in-phase motion) or ``b**4`` of a founded wave is that wave number itself, so that
    its family is the single beam's. ``t``, ``d`` and :attr:`X` are in ``Omega``.
    """

    name: str
    levels: tuple
    X: sp.Matrix
    t: sp.Expr
    d: sp.Expr
    segment: object            # a CoupledSegment of this kind (its X in any variable)
    branches: tuple = ()       # (p, q)
    root: sp.Expr | None = None
    rho: sp.Expr = None
    #: ``c``, ``e`` of ``C``: a number, or None where the generator stands for ``*_form``
    c_value: sp.Expr | None = None
    e_value: sp.Expr | None = None
    c_form: sp.Expr = None
    e_form: sp.Expr = None
    stretches: list = field(default_factory=list)   # (x_start, x_end) of its pieces
    c: sp.Dummy = field(default_factory=lambda: sp.Dummy("c"))
    e: sp.Dummy = field(default_factory=lambda: sp.Dummy("e"))
    rule_ring: sp.Expr = None  # c**2 (or e**2) in the ring's terms

    @property
    def disc(self) -> sp.Expr:
        return sp.expand(self.t**2 - 4 * self.d)

    def coupling(self) -> sp.Matrix:
        """``C = (Xh - t/2) / (p**4 - q**4)`` in numbers and the generators ``c, e``."""
        c = self.c if self.c_value is None else self.c_value
        e = self.e if self.e_value is None else self.e_value
        return sp.Matrix([[c, e], [self.rho * e, -c]])

    def relation(self):
        """``(generator, value of its square)`` from ``c**2 + rho e**2 = 1/4``, or None."""
        quarter = sp.Rational(1, 4)
        if self.c_value is None:
            e = self.e if self.e_value is None else self.e_value
            return self.c, quarter - self.rho * e**2
        if self.e_value is None:
            return self.e, (quarter - self.c_value**2) / self.rho
        return None


@dataclass
class _RodWave:
    """The axial wave number of rods on a foundation, ``b**2 = -(m lam**2 + kw) / EA``.

    Not proportional to ``Omega``: its own generator :attr:`symbol` (printed ``b_<rod>``,
    after the first rod of the kind) and ``1/b``, a Laurent pair like ``W`` and ``Omega``.
    Rods with the same ``m / EA`` and ``kw / EA`` share it.
    """

    name: str
    symbol: sp.Symbol
    inertia: sp.Expr       # m / EA
    foundation: sp.Expr    # kw / EA

    def squared(self, lam2) -> sp.Expr:
        """``b**2`` at ``lam**2``."""
        return sp.expand(-(self.inertia * lam2 + self.foundation))


@dataclass
class _Group:
    """Atoms of one argument: ``Omega * arg`` (plain), ``b l``, ``a l`` of a wave kind,
    ``p l`` (``branch`` 0), ``q l`` (``branch`` 1) of a layered member, or ``rod * arg`` of
    rods (``rod`` ``Omega``, ``Omega**2`` or the ``b`` of a :class:`_RodWave`; only
    ``cos``, ``sin``)."""

    arg: sp.Expr              # plain: argument / Omega; wave, member: the length l;
                              # rod: argument / rod
    wave: int | None = None   # index into _Problem.waves, None for plain
    dummies: tuple = field(default_factory=lambda: tuple(sp.Dummy(n) for n in
                                                          ("c", "s", "ch", "sh")))
    member: int | None = None  # index into _Problem.members
    branch: int = 0
    rod: sp.Expr | None = None  # the frequency of a rod's atoms (argument = rod * arg)

    @property
    def plain(self) -> bool:
        """Atoms of ``Omega * arg``."""
        return self.wave is None and self.member is None and self.rod is None


@dataclass
class _Problem:
    """Everything the polynomial stage needs, in SymPy terms."""

    layout: Layout
    groups: list          # _Group per distinct argument
    waves: list           # _Wave per kind of non-plain beam
    #: ("segments", [(level, group)]) | ("point", {(row, col): expr in W}); a layered
    #: member is ((level_a, level_b), ("layer", member, group_p, group_q)), a rod's
    #: segment (level, ("rod", group_u, group_t, l)) (``group_t`` None without torsion)
    steps: list
    #: (group, level) -> 4x4 SymPy entries of a wave segment; for a member
    #: (("layer", member, gp, gq), levels) -> 8x8 in the rows of
    #: :func:`symtmm.assembly.state_rows`; for a rod (("rod", ...), level) -> 4x4
    matrices: dict
    prefactor: sp.Expr    # prod D[rows] / prod D[cols], in Omega
    extra: list           # generators besides atoms, W and the waves' dummies
    relations: dict       # radical symbol -> (base, Q) with symbol**Q == base
    omega_of: dict        # how Omega relates to the model's variable
    damped: bool
    sample: dict          # values ordering the symbolic positions
    members: list = field(default_factory=list)   # _Member per kind of layered member
    scale: list = field(default_factory=list)     # D: the state's scaling, 4 per level
    rods: list = field(default_factory=list)      # _RodWave per kind of rod on a foundation

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


def _is_rod(beam) -> bool:
    """A rod (:func:`symtmm.model.rod`): axial and torsional oscillators, atoms ``cos, sin``."""
    return beam.theory == "rod"


def _fresh_symbol(name: str, taken: set) -> sp.Symbol:
    """A positive symbol ``name`` (underscores added while taken), marked taken."""
    while name in taken:
        name += "_"
    taken.add(name)
    return sp.Symbol(name, positive=True)


def _rod_matrix(problem: _Problem, key, level: int) -> list:
    """``exp(A l)`` of a rod segment in the scaled state ``(Y, Theta, M / (GJ beta_t), Q /
    (EA beta_u))``: a rotation by ``beta_u l`` on ``(Y, Q)`` and one by ``beta_t l`` on
    ``(Theta, M)``.

    Axially ``Y' = -Q / EA``, ``Q' = EA beta_u**2 Y``: ``Y = c Y0 - s q0``, ``q = s Y0 + c
    q0``; in torsion ``Theta' = M / GJ``, ``M' = -GJ beta_t**2 Theta``: ``Theta = c Theta0 +
    s m0``, ``m = -s Theta0 + c m0``. Without torsion the twist is massless (``M' = 0``):
    ``Theta = Theta0 + l M0 / GJ``, ``M = M0``.
    """
    _, gu, gt, length = key
    c, s = problem.groups[gu].dummies[:2]
    zero, one = sp.Integer(0), sp.Integer(1)
    U = [[zero] * 4 for _ in range(4)]
    U[0][0], U[0][3], U[3][0], U[3][3] = c, -s, s, c
    if gt is None:
        GJ = problem.layout.model.beams[level].EI
        U[1][1], U[1][2], U[2][2] = one, problem.in_ring(length / GJ), one
    else:
        ct, st = problem.groups[gt].dummies[:2]
        U[1][1], U[1][2], U[2][1], U[2][2] = ct, st, -st, ct
    return U


def _wave_segment(beam, l=1) -> BeamSegment:
    return BeamSegment(beam.EI, beam.m, l, beam.kw, beam.N, beam.rhoI, beam.kGA)


def _wave_symbols(name: str, taken: set, letters=("a", "b")) -> tuple[sp.Symbol, sp.Symbol]:
    a, b = f"{letters[0]}_{name}", f"{letters[1]}_{name}"
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


def _member_symbols(names, taken: set) -> tuple[sp.Symbol, sp.Symbol]:
    """``p_<a>_<b>``, ``q_<a>_<b>`` after the member's beams (underscores added if taken)."""
    return _wave_symbols("_".join(names), taken, letters=("p", "q"))


def _interval_segments(layout: Layout, step: Interval) -> list:
    """The segments of an interval for the closed form: a member whose layers have
    neither stiffness nor damping is its beams' own segments; one of more than two
    beams is refused (one line, naming a layer that joins them)."""
    out = []
    model = layout.model
    for lvl, seg in step.segments:
        if not isinstance(lvl, tuple):
            out.append((lvl, seg))
            continue
        if all(k == 0 and c == 0 for _, _, k, c in seg.couplings):
            out += [(j, model.beams[j].segment(seg.l)) for j in lvl]
            continue
        if len(lvl) > 2:
            names = [model.beams[j].name for j in lvl]
            i = next(i for i, la in enumerate(model.layers) if {la.a, la.b} <= set(names))
            raise ModelError(f"derive takes layers between two beams only: {', '.join(names)} "
                             f"are joined over [{step.x_start}, {step.x_end}] (solve, modes "
                             "and codegen take them)", field=f"layer[{i + 1}]",
                             source=model.source)
        out.append((lvl, seg))
    return out


def _member_matrix(problem: _Problem, key, levels) -> list:
    """The member's ``8 x 8`` transfer matrix in the scaled state, entries polynomial in
    the atoms of its two branches, their ``V`` and ``1/V``, and the coupling ``c, e``.

    In ``u = (Y, Y', Y'', Y''')`` (each a pair) the transfer matrix over ``l`` has the
    blocks ``psi_ik(Xh)``, ``psi_ik(nu) = nu**(i - k) f_((k - i) mod 4)(nu l)`` with
    ``f = ((cosh + cos)/2, (sinh + sin)/2, (cosh - cos)/2, (sinh - sin)/2)`` (the
    derivatives of the single beam's ``c_j``: the blocks ``c_j(X)`` of
    :mod:`symtmm.elements.layer`, each even in ``nu``), and with ``psi(p), psi(q)`` at the
    two wave numbers ``psi(Xh) = psi(p) E1 + psi(q) E2 = (psi(p) + psi(q))/2 + (psi(p) -
    psi(q)) C`` (:class:`_Member`).
    The state ``z = (Y, Theta, M, Q) = diag(1, 1, EI, EI) u`` is then scaled by the
    levels' ``D``.
    """
    _, k_member, gp, gq = key
    groups, waves = problem.groups, problem.waves
    member = problem.members[k_member]
    p, q = member.branches
    coupling = member.coupling()

    def f(group):
        c, s, ch, sh = groups[group].dummies
        return ((ch + c) / 2, (sh + s) / 2, (ch - c) / 2, (sh - s) / 2)

    fp, fq = f(gp), f(gq)
    beams = problem.layout.model.beams
    e = [(1, 1, beams[j].EI, beams[j].EI) for j in levels]
    D = [problem.scale[4 * j:4 * j + 4] for j in levels]
    subs = {OMEGA_DIMLESS: 1 / _W, **{w.b: 1 / w.Wb for w in waves if w.scaled}}
    out = [[None] * 8 for _ in range(8)]
    for i in range(4):
        for k in range(4):
            psi_p = p.power(i - k, waves) * fp[(k - i) % 4]
            psi_q = q.power(i - k, waves) * fq[(k - i) % 4]
            for a in range(2):
                for b in range(2):
                    phi = (psi_p - psi_q) * coupling[a, b]
                    if a == b:
                        phi += (psi_p + psi_q) / 2
                    value = e[a][i] / D[a][i] * phi * D[b][k] / e[b][k]
                    out[2 * i + a][2 * k + b] = sp.expand(
                        sp.powsimp(sp.expand(value)).xreplace(subs))
    return out


def _shared_branch(members: list, member: _Member, branch: _Branch, sign: int):
    """A free branch of an earlier member with the same wave number (a chain of like
    layers: its two members move alike), or None."""
    if branch.kind != "free":
        return None
    for other in members:
        for i, br in enumerate(other.branches):
            if br.kind != "free":
                continue
            if member.root is not None and other.root is not None:
                if sp.expand(br.mu - branch.mu) == 0:
                    return br
            elif member.root is None and other.root is None and i == (sign < 0) \
                    and sp.expand(other.t - member.t) == 0 \
                    and sp.expand(other.d - member.d) == 0:
                return br
    return None


def _identify(branch: _Branch, waves: list) -> None:
    """A polynomial eigenvalue ``mu = c Omega**4`` (``c > 0``) is ``(c**(1/4) Omega)**4``,
    one equal to ``b**4`` of a founded wave that ``b``: any fourth root serves, and this
    one writes the branch in the atoms of the beams it moves like."""
    c = sp.simplify(branch.mu / OMEGA_DIMLESS**4)
    if not c.has(OMEGA_DIMLESS) and c.is_positive:
        branch.kind, branch.ratio = "plain", sp.simplify(c ** sp.Rational(1, 4))
        return
    for k, wave in enumerate(waves):
        if wave.scaled and sp.expand(branch.mu + wave.d) == 0:
            branch.kind, branch.wave = "founded", k
            return


def _square_root(expr):
    """A rational function whose square is ``expr`` (in the symbols it has), or None.

    Examples
    --------
    >>> k, EI, W = sp.symbols("k EI W", positive=True)
    >>> _square_root(4 * k**2 / EI**2), _square_root(-36 * W**4), _square_root(W**4 + 1)
    (2*k/EI, 6*I*W**2, None)
    """
    expr = sp.together(sp.expand(expr))
    if expr == 0:
        return None
    out = sp.Integer(1)
    for part, sign in zip(sp.fraction(expr), (1, -1)):
        content, factors = sp.factor_list(sp.expand(part))
        root = sp.sqrt(content)
        # (a Gaussian content: damped models hold I)
        if not (root.is_Rational or (root / sp.I).is_Rational) \
                or any(m % 2 for _, m in factors):
            return None
        out *= (root * sp.Mul(*[f ** (m // 2) for f, m in factors])) ** sign
    return sp.expand(out)


def _build_problem(model: Model, sample: dict) -> _Problem:
    layout = Layout(model, sample)
    _check_order(layout, sample, model.source)
    model = layout.model
    Om = OMEGA_DIMLESS
    beams = model.beams
    plain = [_is_plain(b) for b in beams]
    rods = [_is_rod(b) for b in beams]
    # the reference: the first plain beam, else the first rod (one without foundation first)
    order = [j for j in range(len(beams)) if plain[j]] \
        + [j for j, b in enumerate(beams) if rods[j] and b.kw == 0] \
        + [j for j in range(len(beams)) if rods[j]]
    ref = order[0] if order else 0
    mu = [(b.m / b.EI) ** sp.Rational(1, 4) for b in beams]
    L1 = beams[ref].L
    if rods[ref]:
        # no plain beam: Omega = beta_u L of the first rod, beta_u**2 = -m lam**2 / EA
        # (Omega = kappa omega undamped; Omega = I kappa lam damped, which writes cos(Omega)
        # as cosh(kappa lam); either branch gives the same Delta)
        kappa = sp.simplify(L1 * sp.sqrt(beams[ref].m / beams[ref].N))
        sign = -1 if model.damped else 1
        lam_of_Omega = sign * sp.I * Om / kappa
        lam2 = sp.expand(-Om**2 / kappa**2)
        rod_power = 1
        omega_of = {"undamped": kappa * OMEGA, "damped": sp.I * kappa * LAM}
    else:
        # lam in terms of Omega: beta_ref**4 = -m lam**2 / EI  =>  lam = -I Omega**2 / (mu L)**2
        lam_of_Omega = -sp.I * Om**2 / (mu[ref] * L1) ** 2
        lam2 = sp.expand(-Om**4 * beams[ref].EI / (beams[ref].m * L1**4))
        rod_power = 2
        omega_of = {"undamped": L1 * mu[ref] * sp.sqrt(OMEGA),
                    "damped": L1 * mu[ref] * sp.sqrt(sp.I * LAM)}
    taken = set(model.parameters) | {"Omega", "omega", "lam", "I", "E", "pi"}
    intervals = {id(step): _interval_segments(layout, step) for step in layout.steps
                 if isinstance(step, Interval)}
    # a beam with a segment of its own (not only inside layered members)
    outside = [False] * len(beams)
    for segments in intervals.values():
        for lvl, _ in segments:
            if not isinstance(lvl, tuple):
                outside[lvl] = True
    waves: list = []
    level_wave: dict = {}
    r: dict = {}
    rod_waves: list = []
    # level -> ((frequency, ratio) axial, (frequency, ratio) torsional or None): a rod's
    # wave numbers beta = ratio * frequency, the frequency Omega**rod_power or a b_<rod>
    rod_beta: dict = {}

    def rod_ratio(inertia, stiffness):
        """``beta / Omega**rod_power`` of ``beta**2 = -inertia lam**2 / stiffness``."""
        return sp.sqrt(sp.factor(-inertia * lam2 / (stiffness * Om**(2 * rod_power))))

    D = []
    for j, b in enumerate(beams):
        if rods[j]:
            if b.kw == 0:
                axial = (Om**rod_power, rod_ratio(b.m, b.N))
            else:
                inertia, foundation = sp.simplify(b.m / b.N), sp.simplify(b.kw / b.N)
                for rw in rod_waves:
                    if sp.simplify(rw.inertia - inertia) == 0 \
                            and sp.simplify(rw.foundation - foundation) == 0:
                        break
                else:
                    rw = _RodWave(b.name, _fresh_symbol(f"b_{b.name}", taken), inertia,
                                  foundation)
                    rod_waves.append(rw)
                axial = (rw.symbol, sp.Integer(1))
            torsion = (Om**rod_power, rod_ratio(b.rhoI, b.EI)) if b.torsion else None
            rod_beta[j] = (axial, torsion)
            beta_u = axial[0] * axial[1]
            D += [sp.Integer(1), sp.Integer(1),
                  b.EI * torsion[0] * torsion[1] if torsion else sp.Integer(1), b.N * beta_u]
            continue
        if not outside[j]:
            # only inside members: the physical state (M, Q over EI as the member has them)
            D += [sp.Integer(1), sp.Integer(1), b.EI, b.EI]
            continue
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
    members: list = []
    steps: list = []

    def group(arg, wave=None, member=None, branch=0, rod=None) -> int:
        for g, grp in enumerate(groups):
            if (grp.wave, grp.member, grp.branch) == (wave, member, branch) \
                    and (grp.rod is None) == (rod is None) \
                    and (rod is None or grp.rod == rod) \
                    and sp.expand(grp.arg - arg) == 0:
                return g
        groups.append(_Group(arg, wave, member=member, branch=branch, rod=rod))
        return len(groups) - 1

    def rod_key(lvl, length):
        """A rod segment: its axial group, its torsional group (None without), length."""
        (fu, ru), torsion = rod_beta[lvl]
        gu = group(sp.expand(ru * length), rod=fu)
        if torsion is None:
            return ("rod", gu, None, length)
        ft, rt = torsion
        return ("rod", gu, group(sp.expand(rt * length), rod=ft), None)

    def member_kind(levels, seg) -> int:
        X = seg.field_matrix(lam=lam_of_Omega, lam2=lam2).applyfunc(sp.expand)
        for k, mb in enumerate(members):
            if mb.levels == levels and all(sp.expand(v) == 0 for v in mb.X - X):
                return k
        t, d = sp.expand(X.trace()), sp.expand(X.det())
        mb = _Member("-".join(beams[j].name for j in levels), levels, X, t, d, seg)
        mb.root = _square_root(mb.disc)
        mb.rho = sp.simplify(X[1, 0] / X[0, 1])
        names = _member_symbols([beams[j].name for j in levels], taken)
        branches = []
        for sign, symbol in zip((1, -1), names):
            branch = _Branch(symbol)
            if mb.root is not None:
                branch.mu = sp.expand((t + sign * mb.root) / 2)
                _identify(branch, waves)
            shared = _shared_branch(members, mb, branch, sign)
            if shared is not None:
                branch = shared
            elif branch.kind == "free":
                taken.add(symbol.name)
            branches.append(branch)
        mb.branches = tuple(branches)
        half_delta, off = (X[0, 0] - X[1, 1]) / 2, X[0, 1]
        if mb.root is not None:
            mb.c_form, mb.e_form = (sp.factor(v / mb.root) for v in (half_delta, off))
            mb.c_value, mb.e_value = (v if v.is_number else None
                                      for v in (mb.c_form, mb.e_form))
        else:
            p4, q4 = (br.symbol**4 for br in branches)
            mb.c_form, mb.e_form = (sp.factor(v) / (p4 - q4) for v in (half_delta, off))
        members.append(mb)
        return len(members) - 1

    def branch_group(k, i, arg) -> int:
        branch = members[k].branches[i]
        if branch.kind == "plain":
            return group(sp.expand(sp.simplify(branch.ratio * arg)))
        if branch.kind == "founded":
            return group(arg, wave=branch.wave)
        # (a wave number shared by members: the atoms of the first that has it)
        k, i = next((k2, i2) for k2, mb in enumerate(members)
                    for i2, br in enumerate(mb.branches) if br is branch)
        return group(arg, member=k, branch=i)

    for step in layout.steps:
        if isinstance(step, Interval):
            segs = []
            for lvl, seg in intervals[id(step)]:
                if isinstance(lvl, tuple) or rods[lvl]:
                    arg = sp.expand(seg.l)
                else:
                    arg = sp.expand(sp.simplify(r[lvl] * seg.l / L1)) if plain[lvl] \
                        else sp.expand(seg.l)
                if arg.is_number and not arg.is_positive:
                    raise ModelError(f"segment of length {seg.l} is not positive",
                                     field="spring.x", source=model.source)
                if isinstance(lvl, tuple):
                    k = member_kind(lvl, seg)
                    members[k].stretches.append((step.x_start, step.x_end))
                    segs.append((lvl, ("layer", k, branch_group(k, 0, arg),
                                       branch_group(k, 1, arg))))
                elif rods[lvl]:
                    segs.append((lvl, rod_key(lvl, arg)))
                elif plain[lvl]:
                    segs.append((lvl, group(arg)))
                else:
                    segs.append((lvl, group(arg, wave=level_wave[lvl])))
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
                       omega_of={"lam2": lam2, **omega_of},
                       damped=model.damped, sample=sample, members=members, scale=D,
                       rods=rod_waves)
    for kind, data in steps:
        if kind == "segments":
            for lvl, g in data:
                if isinstance(g, tuple) and g[0] == "rod":
                    if (g, lvl) not in problem.matrices:
                        problem.matrices[(g, lvl)] = _rod_matrix(problem, g, lvl)
                    continue
                if isinstance(lvl, tuple):
                    if (g, lvl) not in problem.matrices:
                        problem.matrices[(g, lvl)] = _member_matrix(problem, g, lvl)
                    continue
                wave = groups[g].wave
                if wave is not None and not waves[wave].scaled and (g, lvl) not in problem.matrices:
                    problem.matrices[(g, lvl)] = _wave_matrix(problem, g, lvl)
    # every expression the ring must hold: radicals become symbols, the rest generators
    slots = [(kind, data, key) for kind, data in steps if kind == "point" for key in data]
    point_exprs = [data[key] for _, data, key in slots]
    matrix_exprs = [e for U in problem.matrices.values() for row in U for e in row]
    general = [w for w in waves if not w.scaled]
    rule_exprs = [problem.in_ring(e) for w in general for e in (w.t, w.disc)]
    relations = [mb.relation() for mb in members]
    member_exprs = [problem.in_ring(r[1]) for r in relations if r is not None]
    exprs, roots = _canonical_radicals(point_exprs + matrix_exprs + rule_exprs + member_exprs)
    for (_, data, key), e in zip(slots, exprs):
        data[key] = e
    rules_at = len(point_exprs) + len(matrix_exprs)
    for i, w in enumerate(general):
        w.t_ring, w.disc_ring = exprs[rules_at + 2 * i:rules_at + 2 * i + 2]
    it = iter(exprs[rules_at + len(rule_exprs):])
    for mb, r in zip(members, relations):
        if r is not None:
            mb.rule_ring = next(it)
    it = iter(exprs[len(point_exprs):rules_at])
    for U in problem.matrices.values():
        for row in U:
            row[:] = [next(it) for _ in row]
    known = {_W} | {d for grp in groups for d in grp.dummies} | {
        s for w in general for s in (w.Dl, w.iq)} | {w.Wb for w in waves if w.scaled} | {
        s for mb in members for s in (mb.c, mb.e)} | {
        s for mb in members for br in mb.branches for s in (br.V, br.Wv)}
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
