"""``det R = constant * prod(f**e)``: factoring in the ring.

Step 3 of the method (:mod:`symtmm.characteristic`), second half: each block's
determinant is factored over the rationals before it is reduced (where
products are still visible), the waves' ``iq = 1/Dl**2`` cleared, each factor
reduced and factored again, and the factors merged, each normalised to a
primitive polynomial with a positive leading coefficient.
"""

from __future__ import annotations

import math
from fractions import Fraction

import sympy as sp

from ..errors import ComputationError
from .algebra import _Algebra
from .budget import factor, spend
from .determinant import _blocks, _decouple_pairs, _det_minors, _eliminate_constants
from .ring import _rational


def _normalise(alg: _Algebra, p):
    """``p = c * q`` with ``q`` primitive over Z and its leading coefficient positive."""
    terms = alg.ring.terms(p)
    coeffs = [_rational(c) for c in terms.values()]
    den = math.lcm(*[int(c.q) for c in coeffs])
    # integers throughout: c.p * den / c.q would go through a float (wrong beyond 2**53)
    num = math.gcd(*[int(c.p) * (den // int(c.q)) for c in coeffs])
    scale = sp.Rational(den, num)
    lead = max(terms)  # lex order on exponent tuples = the ring's order
    if _rational(terms[lead]) < 0:
        scale = -scale
    q = p * alg.ring.coefficient(scale)
    return 1 / scale, q


#: Terms of an unreduced determinant beyond which it is reduced before factoring (models
#: with beams other than plain Euler-Bernoulli ones; plain ones are always factored first).
_FACTOR_UNREDUCED = 30000

_IDENTICALLY_ZERO = ("the characteristic determinant vanishes identically "
                     "(every frequency is an eigenvalue)")


def _factorise(alg: _Algebra, R):
    """``det R = constant * prod(f**e)``, the factors reduced and merged.

    Mirrored pairs of beams are decoupled and constant pivots eliminated first
    (:mod:`~symtmm.characteristic.determinant`); each independent block of the rest
    is expanded on its own; its determinant is factored before the reduction
    (where products are still visible), ``1/disc`` cleared, each factor
    reduced and factored again. A factor of the denominators ``disc`` has a
    negative multiplicity (they cancel against the numerator's where they
    can). Without python-flint only the block structure and the monomial
    content are split off (SymPy's multivariate factoring is too slow for
    these sizes).
    """
    mirrored, R = _decouple_pairs(alg, R)
    pivots, R = _eliminate_constants(alg, R)
    sign, blocks = _blocks(R)
    if sign == 0:
        raise ComputationError(_IDENTICALLY_ZERO)
    constant = sp.Integer(sign) * pivots * mirrored
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
        spend(g)
        c2, parts = factor(alg.ring, g)
        constant *= _rational(c2) ** e
        for h, e2 in parts:
            add(h, e * int(e2))

    for block in blocks:
        det = _det_minors(block, alg.ring.zero, alg.ring.one,
                          alg.reduce if alg.problem.members else None)
        if det == 0:
            raise ComputationError(_IDENTICALLY_ZERO)
        if not alg.ring.can_factor:  # pragma: no cover
            first = [(det, 1)]
        else:
            if (alg.problem.waves or alg.problem.members) \
                    and len(det) > _FACTOR_UNREDUCED:
                # too long to factor as it is (with the waves' Dl, iq it takes minutes):
                # the normal form is far shorter, at the price of products it may hide
                det = alg.reduce(det)
            spend(det)
            content, first = factor(alg.ring, det)
            constant *= _rational(content)
        for f, e in first:
            spend(f)
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
            (mono if len(h) == 1 else pieces).append((h, int(m)))
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
