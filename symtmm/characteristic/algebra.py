"""The algebra of the atoms: the polynomial ring with its reductions, and ``R`` in it.

Step 2 of the method (:mod:`symtmm.characteristic`): ``cos, sin, cosh, sinh``
of each argument, ``W = 1/Omega``, the waves' ``Dl, iq``, the layered members' ``p,
1/p, q, 1/q`` and coupling ``c, e``, the wave numbers ``b, 1/b`` of rods on a foundation
and the symbolic parameters are the variables
of a polynomial ring over the rationals; the
relations between them (``s**2 = 1 - c**2``, ``Dl**2 = disc``, ...) are
rewriting rules with a unique normal form. :meth:`_Algebra.boundary_matrix`
propagates the columns of the unknowns through the cuts in that ring.
"""

from __future__ import annotations

import sympy as sp

from ..assembly import state_rows
from ..errors import ComputationError
from .budget import spend
from .problem import _W, _Problem
from .ring import _rational, _Ring


class _Algebra:
    """The ring of the atoms per argument, ``W = 1/Omega``, the waves' ``Dl, iq`` and parameters.

    Every reduction rewrites a power ``x**q`` of one variable by a polynomial of
    lower degree in ``x`` (``s**2 = 1 - c**2``, ``c**2 = 1 - b**2 Sn**2``,
    ``Dl**2 = disc``, a member's ``c**2 = 1/4 - rho e**2``, ``I**2 = -1``, ``root**Q =
    base``), and ``W * Omega = 1`` (and ``p * (1/p) = 1``, ``b * (1/b) = 1``);
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
        # layered members: V, 1/V of each free branch, the coupling's c, e unless numbers
        self.member_index = {}
        for k, mb in enumerate(problem.members):
            slots = {}
            for i, br in enumerate(mb.branches):
                if br.kind == "free" and br.V not in symbols:   # (once if members share it)
                    slots[f"V{i}"], slots[f"Wv{i}"] = br.V, br.Wv
            if mb.c_value is None:
                slots["c"] = mb.c
            if mb.e_value is None:
                slots["e"] = mb.e
            self.member_index[k] = {}
            for key, symbol in slots.items():
                self.member_index[k][key] = len(names)
                names.append(f"{key}m{k}")
                symbols.append(symbol)
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
        for k, index in self.member_index.items():
            self.inverse_pairs += [(index[f"Wv{i}"], index[f"V{i}"]) for i in range(2)
                                   if f"V{i}" in index]
        for rod in problem.rods:   # a rod's b and 1/b, where both occur
            pair = (self.extra_index.get(rod.symbol), self.extra_index.get(1 / rod.symbol))
            if None not in pair:
                self.inverse_pairs.append(pair)
        G = self.ring.gens
        half = self.ring.coefficient(sp.Rational(1, 2))
        self.rules = []   # (variable, power q, replacement of x**q); applied in this order
        self.N = {}
        for g, grp in enumerate(problem.groups):
            c, s, ch, sh = G[4 * g:4 * g + 4]
            if plain_like(grp):
                self.rules += [(4 * g + 1, 2, 1 - c * c), (4 * g + 3, 2, ch * ch - 1)]
                if grp.member is not None or grp.rod is not None:
                    continue          # a layered member's branch, a rod's: their own matrices
                S, T, U, V = (ch + c) * half, (sh + s) * half, (ch - c) * half, (sh - s) * half
                self.N[g] = [[S, T, U, V], [V, S, T, U], [U, V, S, T], [T, U, V, S]]
            else:
                A, B = self.wave_squares(grp.wave)
                self.rules += [(4 * g, 2, 1 - B * s * s), (4 * g + 2, 2, 1 + A * sh * sh)]
        for k, (dl, _) in self.wave_index.items():
            self.rules.append((dl, 2, self.from_expr(problem.waves[k].disc_ring)))
        for k, mb in enumerate(problem.members):   # c**2 + rho e**2 = 1/4
            relation = mb.relation()
            if relation is not None:
                index = self.member_index[k]["c" if relation[0] == mb.c else "e"]
                self.rules.append((index, 2, self.from_expr(mb.rule_ring)))
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
        try:
            poly = sp.Poly(expr, *self.symbols, domain=sp.QQ)
        except (sp.polys.polyerrors.CoercionFailed, sp.polys.polyerrors.PolynomialError):
            # a number the closed form cannot hold exactly (a radical or constant met only
            # here): say so rather than fail inside SymPy
            raise ComputationError("the closed form cannot hold a number of this model exactly "
                                   "(a radical or constant it meets only here); give such "
                                   "fields rational values or keep them symbolic") from None
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
        spend(p)
        if self.ring.can_factor:
            out = self._reduce_flint(p)
        else:  # pragma: no cover - depends on the installation
            out = self._reduce_dict(p)
        spend(out)
        return out

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
            spend()
            if kind == "segments":
                for lvl, g in data:
                    N = self.N[g] if g in self.N else self.N[(g, lvl)]
                    rows = state_rows(lvl)     # 4, or the 8 of a layered member
                    blk = [E[r] for r in rows]
                    n = len(rows)
                    new = [[self.reduce(sum((N[i][k] * blk[k][j] for k in range(n)
                                             if blk[k][j] != 0 and N[i][k] != 0), ring.zero))
                            for j in range(len(cols))]
                           for i in range(n)]
                    for r, row in zip(rows, new):
                        E[r] = row
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
            # (the degree first: most factors hold no iq, and listing a long one's terms
            # takes seconds no budget check interrupts)
            K = ring.degree(p, iq)
            if not K:
                continue
            terms = ring.terms(p)
            disc = self.from_expr(self.problem.waves[k].disc_ring)
            parts: dict = {}
            for m, cf in terms.items():
                parts.setdefault(m[iq], {})[m[:iq] + (0,) + m[iq + 1:]] = cf
            p = ring.zero
            for j, part in parts.items():
                p = p + ring.from_dict(part) * disc ** (K - j)
            out.append((k, K))
        return p, out
