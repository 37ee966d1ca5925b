"""Closed-form characteristic equations ``Delta = det R = 0``.

The variable
------------
Every beam ``j`` has the wave number ``beta_j = (-m_j lam**2 / EI_j)**(1/4)``.
All of them are expressed through one dimensionless frequency, the paper's
``Omega = beta_1 L_1`` of the first beam::

    beta_j = r_j Omega / L_1,   r_j = ((m_j / EI_j) / (m_1 / EI_1))**(1/4).

For an undamped model ``lam = i omega`` and ``Omega**4 = m_1 omega**2 L_1**4 / EI_1``;
the result is given in ``omega`` (circular frequency, rad/s, ``variable ==
"omega"``) and in ``Omega``. A damped model is given in ``lam`` itself
(``variable == "lam"``), through ``Omega = L_1 (m_1/EI_1)**(1/4) sqrt(I lam)``
(any branch gives the same ``Delta``).

The form
--------
``det R = constant * Omega**power * prod(f_i**e_i)`` where the constant does
not depend on the frequency (it is dropped from :attr:`~CharacteristicEquation.delta`
and kept in :attr:`~CharacteristicEquation.constant`), ``Omega**power`` carries
the roots at zero (rigid-body modes) and cancels the spurious ones of the
transcendental factors, and the factors ``f_i`` are sums of products of
trigonometric and hyperbolic functions; a repeated factor (``e_i > 1``)
exposes roots of that multiplicity. A clamped-clamped beam gives
``Omega**-4 (cos Omega cosh Omega - 1)``.

How it is computed
------------------
Exactly, without simplifying general SymPy expressions, which is what makes
multilevel models tractable:

1. The state of level ``j`` is scaled by ``diag(1, beta_j, EI_j beta_j**2,
   EI_j beta_j**3)``; the transfer matrix of a segment of length ``l`` then
   has the entries ``S, T, U, V`` of ``beta_j l`` only, and a spring enters as
   ``k / (EI_a beta_a**3)``.
2. ``c, s, ch, sh = cos, sin, cosh, sinh`` of each distinct argument
   ``beta_j l`` are independent variables of a polynomial ring over the
   rationals (with ``1/Omega`` and the symbolic parameters). The ``2 n``
   columns of the unknown left-end variables are propagated through the
   cuts, each product reduced with ``s**2 = 1 - c**2`` and
   ``sh**2 = ch**2 - 1``.
3. ``det R`` is expanded by minors (no division), factored over the
   rationals, each factor reduced again and refactored. Factoring before the
   reduction keeps products intact: identical beams coupled symmetrically
   give one factor per mode family.
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
from .elements.base import CONJUGATE, LAM
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

    def factor(self, p):
        """``(constant, [(factor, multiplicity), ...])``."""
        if self._flint is not None:
            return p.factor()
        return p.factor_list()  # pragma: no cover


def _rational(c) -> sp.Rational:
    return sp.Rational(int(c.numerator), int(c.denominator))


# --------------------------------------------------------------------------------------
# the scaled transfer problem


@dataclass
class _Problem:
    """Everything the polynomial stage needs, in SymPy terms."""

    layout: Layout
    args: list            # atom arguments: beta_j l = Omega * args[g]
    steps: list           # ("segments", [(level, group)]) | ("point", {(row, col): expr in W})
    prefactor: sp.Expr    # prod D[rows] / prod D[cols], in Omega
    extra: list           # generators besides atoms and W: SymPy expressions
    relations: dict       # generator index -> (power q, replacement dict) for gen**q
    omega_of: dict        # how Omega relates to the model's variable
    damped: bool
    sample: dict          # values ordering the symbolic positions


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


def _build_problem(model: Model, sample: dict) -> _Problem:
    for b in model.beams:
        if b.kw != 0:
            # beta_j**4 = -(m_j lam**2 + kw_j)/EI_j is not proportional to Omega**4
            raise ModelError("the closed-form characteristic equation does not support a "
                             "Winkler foundation (kw); solve the model numerically instead",
                             field=f"beam '{b.name}'.kw", source=model.source)
    layout = Layout(model, sample)
    _check_order(layout, sample, model.source)
    model = layout.model
    n = layout.levels
    Om = OMEGA_DIMLESS
    beams = model.beams
    mu = [(b.m / b.EI) ** sp.Rational(1, 4) for b in beams]
    L1 = beams[0].L
    r = [sp.simplify(m / mu[0]) for m in mu]
    beta = [r[j] * Om / L1 for j in range(n)]
    D = []
    for j, b in enumerate(beams):
        D += [sp.Integer(1), beta[j], b.EI * beta[j] ** 2, b.EI * beta[j] ** 3]
    damped = model.damped
    # lam in terms of Omega: beta_1**4 = -m_1 lam**2 / EI_1  =>  lam = -I Omega**2 / (mu_1 L_1)**2
    lam_of_Omega = -sp.I * Om**2 / (mu[0] * L1) ** 2
    args: list = []
    steps: list = []
    point_exprs = []
    for step in layout.steps:
        if isinstance(step, Interval):
            segs = []
            for lvl, seg in step.segments:
                phi = sp.expand(sp.simplify(r[lvl] * seg.l / L1))
                if phi.is_number and not phi.is_positive:
                    raise ModelError(f"segment of length {seg.l} is not positive",
                                     field="spring.x", source=model.source)
                for g, a in enumerate(args):
                    if sp.expand(a - phi) == 0:
                        break
                else:
                    args.append(phi)
                    g = len(args) - 1
                segs.append((lvl, g))
            steps.append(("segments", segs))
            continue
        entries: dict = {}
        for element, levels in step.elements:
            # masses (lam**2) enter undamped models too: lam**2 = -Omega**4/(mu_1 L_1)**4
            S = element.stiffness(LAM).xreplace({LAM: lam_of_Omega})
            for i, (li, var_i) in enumerate(element.dofs):
                force, sign = CONJUGATE[var_i]
                row = 4 * levels[li] + STATE.index(force)
                for k, (lk, var_k) in enumerate(element.dofs):
                    col = 4 * levels[lk] + STATE.index(var_k)
                    value = sign * S[i, k] * D[col] / D[row]
                    entries[(row, col)] = entries.get((row, col), 0) + value
        keys = list(entries)
        exprs = [sp.expand(sp.powsimp(entries[k]).xreplace({Om: 1 / _W})) for k in keys]
        point_exprs += exprs
        steps.append(("point", dict(zip(keys, exprs))))
    prefactor = sp.powsimp(sp.Mul(*[D[i] for i in layout.rows])
                           / sp.Mul(*[D[i] for i in layout.columns]))
    exprs, roots = _canonical_radicals(point_exprs)
    it = iter(exprs)
    for kind, data in steps:
        if kind == "point":
            for key in data:
                data[key] = next(it)
    extra = []
    if exprs:
        _, info = sp.parallel_poly_from_expr(exprs + [_W], domain=sp.QQ)
        extra = [g for g in info["gens"] if g != _W]
    for g in extra:
        if g.free_symbols & {Om} or not (g.is_Symbol or g.is_Pow or g == sp.I):
            raise ComputationError(f"unexpected term {g} in a point element")
    return _Problem(layout=layout, args=args, steps=steps, prefactor=prefactor,
                    extra=extra, relations=roots, omega_of={"mu1": mu[0], "L1": L1},
                    damped=damped, sample=sample)


# --------------------------------------------------------------------------------------
# the polynomial stage


class _Algebra:
    """The ring of atoms ``c, s, ch, sh`` per argument, ``W = 1/Omega`` and parameters."""

    def __init__(self, problem: _Problem):
        self.problem = problem
        self.groups = len(problem.args)
        names = []
        for g in range(self.groups):
            names += [f"c{g}", f"s{g}", f"ch{g}", f"sh{g}"]
        self.w = len(names)
        names.append("W")
        self.extra_index = {}
        for e in problem.extra:
            self.extra_index[e] = len(names)
            names.append(f"p{len(names)}")
        self.ring = _Ring(names)
        self.nvars = len(names)
        # reductions gen**q -> replacement, beyond the atoms: I**2 = -1, root**Q = base
        self.power_rules = {}
        for e, idx in self.extra_index.items():
            if e == sp.I:
                self.power_rules[idx] = (2, sp.Integer(-1))
            elif e in problem.relations:
                base, Q = problem.relations[e]
                self.power_rules[idx] = (Q, base)
        # Omega = 1/W as a generator of its own (lumped masses); W * Omega -> 1 in reduce
        self.inv_w = self.extra_index.get(1 / _W)
        half = self.ring.coefficient(sp.Rational(1, 2))
        self.N = []
        G = self.ring.gens
        for g in range(self.groups):
            c, s, ch, sh = G[4 * g:4 * g + 4]
            S, T, U, V = (ch + c) * half, (sh + s) * half, (ch - c) * half, (sh - s) * half
            self.N.append([[S, T, U, V], [V, S, T, U], [U, V, S, T], [T, U, V, S]])

    def from_expr(self, expr):
        gens = [_W] + list(self.extra_index)
        poly = sp.Poly(expr, *gens, domain=sp.QQ)
        out = {}
        for mon, cf in poly.as_dict().items():
            key = [0] * self.nvars
            key[self.w] = mon[0]
            for e, k in zip(self.extra_index, mon[1:]):
                key[self.extra_index[e]] = k
            out[tuple(key)] = self.ring.coefficient(_rational(cf))
        return self.ring.from_dict(out)

    def reduce(self, p):
        """Normal form: ``s**2 -> 1 - c**2``, ``sh**2 -> ch**2 - 1``, ``I**2 -> -1``, ..."""
        terms = self.ring.terms(p)
        odd = [(4 * g + 1, 4 * g, -1) for g in range(self.groups)]   # s: s^2 = 1 - c^2
        odd += [(4 * g + 3, 4 * g + 2, +1) for g in range(self.groups)]  # sh: sh^2 = ch^2 - 1
        iw = self.inv_w
        if not any(mon[i] >= 2 for mon in terms for i, _, _ in odd) and not any(
                mon[i] >= q for mon in terms for i, (q, _) in self.power_rules.items()) and (
                iw is None or not any(mon[iw] and mon[self.w] for mon in terms)):
            return p
        out: dict = {}
        for mon, cf in terms.items():
            partial = {tuple(mon): cf}
            for i, j, sign in odd:
                k = mon[i] // 2
                if not k:
                    continue
                nxt: dict = {}
                for m2, c2 in partial.items():
                    m2 = list(m2)
                    m2[i] -= 2 * k
                    # (1 - c^2)^k or (c^2 - 1)^k by the binomial theorem
                    for t in range(k + 1):
                        coef = math.comb(k, t) * (-1) ** t
                        if sign > 0:
                            coef *= (-1) ** k  # (c^2 - 1)^k = (-1)^k (1 - c^2)^k
                        m3 = list(m2)
                        m3[j] += 2 * t
                        key = tuple(m3)
                        nxt[key] = nxt.get(key, 0) + c2 * coef
                partial = nxt
            for i, (q, value) in self.power_rules.items():
                nxt = {}
                for m2, c2 in partial.items():
                    k = m2[i] // q
                    m3 = list(m2)
                    m3[i] -= q * k
                    key = tuple(m3)
                    nxt[key] = nxt.get(key, 0) + c2 * self.ring.coefficient(value ** k)
                partial = nxt
            for key, c2 in partial.items():
                if iw is not None and key[iw] and key[self.w]:
                    key = list(key)
                    k = min(key[iw], key[self.w])
                    key[iw] -= k
                    key[self.w] -= k
                    key = tuple(key)
                out[key] = out.get(key, 0) + c2
        return self.ring.from_dict({k: v for k, v in out.items() if v != 0})

    def boundary_matrix(self) -> list:
        """The scaled ``R`` as a list of rows of polynomials (entries reduced)."""
        layout = self.problem.layout
        n = layout.levels
        ring = self.ring
        E = [[ring.zero] * (2 * n) for _ in range(4 * n)]
        for j, c in enumerate(layout.columns):
            E[c][j] = ring.one
        for kind, data in self.problem.steps:
            if kind == "segments":
                for lvl, g in data:
                    N = self.N[g]
                    blk = E[4 * lvl:4 * lvl + 4]
                    E[4 * lvl:4 * lvl + 4] = [
                        [self.reduce(sum((N[i][k] * blk[k][j] for k in range(4) if blk[k][j] != 0),
                                         ring.zero)) for j in range(2 * n)]
                        for i in range(4)]
            else:
                new = [row[:] for row in E]
                for (row, col), expr in data.items():
                    v = self.from_expr(expr)
                    for j in range(2 * n):
                        if E[col][j] != 0:
                            new[row][j] = new[row][j] + v * E[col][j]
                E = [[self.reduce(x) for x in r] for r in new]
        return [E[i] for i in layout.rows]


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


def _factorise(alg: _Algebra, R):
    """``det R = constant * prod(f**e)``, the factors reduced and merged.

    Each independent block of ``R`` is expanded on its own; its determinant
    is factored before the reduction (where products are still visible),
    each factor reduced and factored again. Without python-flint only the
    block structure and the monomial content are split off (SymPy's
    multivariate factoring is too slow for these sizes).
    """
    sign, blocks = _blocks(R)
    if sign == 0:
        raise ComputationError("the characteristic determinant vanishes identically "
                               "(every frequency is an eigenvalue)")
    constant = sp.Integer(sign)
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

    for block in blocks:
        det = _det_minors(block, alg.ring.zero, alg.ring.one)
        if det == 0:
            raise ComputationError("the characteristic determinant vanishes identically "
                                   "(every frequency is an eigenvalue)")
        if not alg.ring.can_factor:
            for h, e in _monomial_content(alg, alg.reduce(det)):
                add(h, e)
            continue
        content, first = alg.ring.factor(det)
        constant *= _rational(content)
        for f, e in first:
            e = int(e)
            g = alg.reduce(f)
            if g == 0:
                raise ComputationError("the characteristic determinant vanishes identically "
                                       "(every frequency is an eigenvalue)")
            if g == f:
                add(f, e)
                continue
            c2, second = alg.ring.factor(g)
            constant *= _rational(c2) ** e
            for h, e2 in second:
                add(h, e * int(e2))
    return constant, [tuple(v) for v in found.values()]


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
        self.arguments = [sp.Mul(Omega, a) for a in p.args]
        self.atoms = []
        for arg in self.arguments:
            self.atoms += [sp.cos(arg), sp.sin(arg), sp.cosh(arg), sp.sinh(arg)]
        self.extra = []
        for e in alg.extra_index:
            if e in p.relations:
                base, Q = p.relations[e]
                self.extra.append(base ** sp.Rational(1, Q))
            else:
                # 1/W (lumped masses bring positive powers of Omega) is Omega itself
                self.extra.append(e.xreplace({_W: 1 / Omega}))
        self._trig_cache: dict = {}

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
        """``(sign, f(Omega * sum(freq * args)))``, the argument positive at the sample."""
        value = sp.expand(sum(k * a for k, a in zip(freq, self.alg.problem.args)))
        sample = self.alg.problem.sample
        at = value.xreplace(sample) if sample else value
        sign = 1
        if at.is_number and at.is_negative:
            value, sign = -value, (-1 if kind == 1 else 1)
        fn = ((sp.cos, sp.sin), (sp.cosh, sp.sinh))[hyperbolic][kind]
        return sign, fn(sp.Mul(self.Omega, value))

    def split(self, poly):
        """``poly = W**d * sum_k Omega**k * (...)``: returns ``d`` and groups by the rest."""
        alg = self.alg
        terms = alg.ring.terms(poly)
        d = max(m[alg.w] for m in terms)
        groups: dict = {}
        for mon, cf in terms.items():
            rest = (d - mon[alg.w],) + tuple(mon[alg.w + 1:])
            groups.setdefault(rest, {})[mon[:alg.w]] = _rational(cf)
        return d, groups

    def _outer(self, rest):
        out = self.Omega ** rest[0]
        for e, k in zip(self.extra, rest[1:]):
            out *= e ** k
        return out

    def atoms_form(self, groups) -> sp.Expr:
        total = []
        for rest, inner in groups.items():
            s = sp.Add(*[cf * sp.Mul(*[a ** k for a, k in zip(self.atoms, mon) if k])
                         for mon, cf in inner.items()])
            total.append(self._outer(rest) * s)
        return sp.Add(*total)

    def harmonic_form(self, groups) -> sp.Expr:
        total = []
        G = self.alg.groups
        for rest, inner in groups.items():
            # integer arithmetic on a common denominator den * 2**top
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
            parts = []
            for ((tk, tf), (hk, hf)), v in acc.items():
                if v == 0:
                    continue
                v = Fraction(v, den << top)
                st, t = self._function(tk, tf, False) if any(tf) else (1, sp.Integer(1))
                sh, h = self._function(hk, hf, True) if any(hf) else (1, sp.Integer(1))
                parts.append(st * sh * sp.Rational(v.numerator, v.denominator) * t * h)
            total.append(self._outer(rest) * sp.Add(*parts))
        return sp.Add(*total)

    def best(self, poly):
        """``(d, expr)`` with ``poly = W**d * expr``; the shorter of the two forms."""
        d, groups = self.split(poly)
        a = self.atoms_form(groups)
        h = self.harmonic_form(groups)
        return d, (h if sp.count_ops(h) <= sp.count_ops(a) else a)


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

    @property
    def equation(self) -> sp.Expr:
        """``prod(f**e)`` in ``Omega``: the textbook frequency equation ``= 0``."""
        return sp.Mul(*[f**e for f, e in self.factors])

    def count_ops(self) -> int:
        """Size of :attr:`delta_Omega` as SymPy counts operations."""
        return int(sp.count_ops(self.delta_Omega))

    def latex(self) -> str:
        """LaTeX of ``delta`` in :attr:`variable`."""
        return sp.latex(self.delta)

    def to_dict(self) -> dict:
        """The JSON contract ``{"variable", "delta", "latex"}`` plus the Omega form.

        ``delta`` parses with :func:`sympy.sympify` into the function of
        ``variable``; ``delta_Omega`` with ``Omega`` likewise.
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
    pre_c, pre_p = _split_power(problem.prefactor, Om)
    power = pre_p
    out_factors = []
    for poly, e in factors:
        d, expr = writer.best(poly)
        power -= d * e
        if expr.is_number:
            constant *= expr ** e
            continue
        if expr == Om:
            power += e
            continue
        out_factors.append((expr, e))
    out_factors.sort(key=lambda fe: (sp.count_ops(fe[0]), str(fe[0])))
    constant_Omega = sp.simplify(pre_c * constant)
    delta_Omega = Om ** power * sp.Mul(*[f**e for f, e in out_factors])
    mu1, L1 = problem.omega_of["mu1"], problem.omega_of["L1"]
    if problem.damped:
        variable = LAM
        Omega_of_var = L1 * mu1 * sp.sqrt(sp.I * LAM)
    else:
        variable = OMEGA
        Omega_of_var = L1 * mu1 * sp.sqrt(OMEGA)
    delta = delta_Omega.xreplace({Om: Omega_of_var})
    # what xreplace leaves as a constant factor in front of the power of the variable
    scale, rest = delta.as_independent(variable, as_Add=False)
    delta = rest
    constant = sp.simplify(constant_Omega * scale)
    symbols = tuple(sorted(s.name for s in sp.sympify(delta).free_symbols
                           if s not in (variable,)))
    notes = []
    if len(out_factors) > 1 or any(e > 1 for _, e in out_factors):
        notes.append("kept factored: " + ", ".join(
            f"{sp.count_ops(f)} ops x{e}" for f, e in out_factors))
    return CharacteristicEquation(
        variable=variable, delta=delta, constant=constant, delta_Omega=delta_Omega,
        constant_Omega=constant_Omega, Omega=Omega_of_var, power=int(power),
        factors=tuple(out_factors), symbols=symbols,
        seconds=time.perf_counter() - start, notes=tuple(notes),
        model_name=model_in.source or model_in.title or None)


def _split_power(expr, x):
    """``expr = c * x**p`` with ``c`` free of ``x``."""
    expr = sp.powsimp(sp.expand_power_base(sp.sympify(expr), force=True))
    c, p = expr.as_coeff_exponent(x)
    if c.has(x):
        raise ComputationError(f"cannot separate the power of {x} in {expr}")
    return c, int(p)
