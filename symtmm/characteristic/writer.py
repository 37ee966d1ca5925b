"""Back to SymPy: factors of the ring written with trigonometric and hyperbolic functions.

Step 4 of the method (:mod:`symtmm.characteristic`): each factor is written
either as a polynomial in the segment functions (:meth:`_Writer.atoms_form`)
or, by product-to-sum, with combined arguments (:meth:`_Writer.harmonic_form`,
``sin Omega`` rather than ``2 cos(a)**2 sin(b) + ...``), grouped by the
factors outside the functions or collected by function, whichever has the
fewest operations (:meth:`_Writer.best`).
"""

from __future__ import annotations

import math
from fractions import Fraction

import sympy as sp

from .algebra import _Algebra
from .budget import factor, spend
from .factor import _normalise
from .ring import _rational, _Ring


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
            if grp.rod is not None:
                trig = hyp = (grp.rod, grp.arg)
            elif grp.member is not None:
                trig = hyp = (p.members[grp.member].branches[grp.branch].symbol, grp.arg)
            elif grp.wave is None:
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
        for k, index in alg.member_index.items():
            member = p.members[k]
            forms = {"c": member.c_form, "e": member.e_form}
            for i, br in enumerate(member.branches):
                forms[f"V{i}"], forms[f"Wv{i}"] = br.symbol, 1 / br.symbol
            self.outer += [(idx, forms[key]) for key, idx in index.items()]
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
                poly = alg.from_expr(alg.problem.radicals(alg.problem.in_ring(expr)))
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
                        # (the sum grows with every factor: a monomial of high powers in
                        # several groups took seconds between two checks of the budget)
                        spend()
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
        """The polynomial in the segment functions: per outer factor, its monomials."""
        total = []
        for rest, inner in groups.items():
            spend()
            s = sp.Add(*[cf * sp.Mul(*[a ** k for a, k in zip(self.atoms, mon) if k])
                         for mon, cf in inner.items()])
            total.append(self._outer(rest) * s)
        return sp.Add(*total)

    def _coefficient(self, by_rest: dict) -> sp.Expr:
        """``sum(v * outer(rest))``, factored (by python-flint) when that is shorter."""
        spend()

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
        result = factor(ring, poly, optional=True)
        if result is None:
            return expr                 # (written out: its factors are only for reading)
        content, parts = result
        if len(parts) < 2 and all(e == 1 for _, e in parts):
            return expr
        factored = _rational(content) * sp.Mul(*[
            written({m: Fraction(int(c.numerator), int(c.denominator))
                     for m, c in ring.terms(f).items()}) ** int(e) for f, e in parts])
        return factored if sp.count_ops(factored) < sp.count_ops(expr) else expr

    def collected_forms(self, groups, harmonic_terms) -> tuple[sp.Expr, sp.Expr]:
        """The atoms and the harmonic form, each function with one coefficient.

        The forms above group by the outer factor (powers of ``Omega``, wave
        numbers, parameters); where many of those multiply the same functions
        (Timoshenko beams: polynomials in ``omega``), collecting by function is
        shorter. ``harmonic_terms`` holds :meth:`_harmonic_terms` of each group.
        """
        atoms: dict = {}
        harmonic: dict = {}
        for rest, inner in groups.items():
            for mon, cf in inner.items():
                atoms.setdefault(mon, {})[rest] = Fraction(int(cf.p), int(cf.q))
            parts = harmonic_terms[rest]
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
        spend()
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
            spend()
            scale = int(cf.p) * (den // int(cf.q)) << (top - shift)
            for kt, vt in ht.items():
                for kh, vh in hh.items():
                    key = (kt, kh)
                    acc[key] = acc.get(key, 0) + scale * vt * vh
        return {k: Fraction(v, den << top) for k, v in acc.items() if v != 0}

    def harmonic_form(self, terms) -> sp.Expr:
        """The harmonic form: per outer factor, its :meth:`_harmonic_terms` ``terms``."""
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
        builders = [lambda: self.harmonic_form(harmonic), lambda: self.atoms_form(groups)]
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
        sizes = []
        for f in forms:
            spend()
            sizes.append(sp.count_ops(f))
        return m, forms[sizes.index(min(sizes))], sp.Integer(1)
