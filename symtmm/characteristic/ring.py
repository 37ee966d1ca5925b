"""Multivariate polynomials over the rationals: the ring every exact step works in.

python-flint's ``fmpq_mpoly`` when it is installed (fast factoring), otherwise
SymPy's sparse polynomials; :class:`_Ring` wraps the few operations
:mod:`symtmm.characteristic` uses so that the rest reads the same on both.
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np
import sympy as sp


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

    def degree(self, p, i: int) -> int:
        """The degree of ``p`` in generator ``i`` (0 for the zero polynomial)."""
        if self._flint is not None:
            return max(int(p.degrees()[i]), 0)
        return max(p.degree(i), 0)  # pragma: no cover

    def constant_value(self, p):
        """The rational value of a constant polynomial, else None."""
        if len(p) != 1:         # (without listing the terms of a long one: seconds)
            return None
        terms = self.terms(p)
        (mon, cf), = terms.items()
        return _rational(cf) if not any(mon) else None

    def factor(self, p):
        """``(constant, [(factor, multiplicity), ...])``."""
        if self._flint is not None:
            return p.factor()
        return p.factor_list()  # pragma: no cover

    def pack_factors(self, factored) -> tuple:
        """:meth:`factor`'s result as plain data, compact (exponents as bytes; integers, not
        tuples, pickle fast): what :mod:`symtmm.forked` sends back from a child."""
        content, parts = factored
        packed = []
        for f, e in parts:
            exps = np.array(f.monoms(), dtype=np.int64).reshape(-1, len(self.names))
            coeffs = f.coeffs()
            packed.append((exps.tobytes(), [int(c.numerator) for c in coeffs],
                           [int(c.denominator) for c in coeffs], int(e)))
        return (int(content.numerator), int(content.denominator)), packed

    def unpack_factors(self, packed) -> tuple:
        """The inverse of :meth:`pack_factors`."""
        (num, den), parts = packed
        fmpq = self._flint.fmpq
        out = []
        for exps, nums, dens, e in parts:
            keys = map(tuple, np.frombuffer(exps, dtype=np.int64)
                       .reshape(-1, len(self.names)).tolist())
            out.append((self._ctx.from_dict(dict(zip(keys, map(fmpq, nums, dens)))), e))
        return fmpq(num, den), out


def _rational(c) -> sp.Rational:
    return sp.Rational(int(c.numerator), int(c.denominator))
