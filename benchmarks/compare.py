"""Matching found eigenvalues with reference values: accuracy, missed, spurious."""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

__all__ = ["Match", "match"]

#: A found value further than this (relative to |reference|) from every reference
#: value is not a root at all.
MATCH_TOL = 1e-3


@dataclass
class Match:
    """Outcome of comparing a list of found eigenvalues with the reference list.

    ``max_rel_error`` is the largest ``|found - reference| / |reference|`` over
    the reference values that were found (None if none was); ``missed``
    counts reference values (with multiplicity) that no found value matches;
    ``spurious`` counts found values that match none.
    """

    found: int
    reference: int
    matched: int
    missed: int
    spurious: int
    max_rel_error: float | None

    def to_dict(self) -> dict:
        return dict(found=self.found, reference=self.reference, matched=self.matched,
                    missed=self.missed, spurious=self.spurious,
                    max_rel_error=self.max_rel_error)


def match(found, reference, tol: float = MATCH_TOL, zero_scale=None) -> Match:
    """Pair found values with reference values one to one, nearest first.

    Both are sequences of complex numbers (mpmath or Python); a value of
    multiplicity ``k`` appears ``k`` times. A pair counts if the two are
    within ``tol`` relative to the reference value; a reference 0 (a rigid-body
    mode) counts relative to ``zero_scale`` (None: the largest ``|reference|``).

    Examples
    --------
    >>> m = match([1.0, 2.0000001, 7.0], [1.0, 2.0, 2.0, 3.0])
    >>> (m.matched, m.missed, m.spurious, m.max_rel_error < 1e-7)
    (2, 2, 1, True)
    """
    pairs = []
    # in mpmath at 50 digits: the default method's errors lie far below double rounding
    with mpmath.workdps(50):
        ref = [mpmath.mpmathify(r) for r in reference]
        got = [mpmath.mpmathify(f) for f in found]
        if zero_scale is None:
            zero_scale = max((abs(r) for r in ref), default=1)
        for i, r in enumerate(ref):
            scale = abs(r) or max(mpmath.mpmathify(zero_scale), mpmath.mpf(1e-300))
            for j, f in enumerate(got):
                d = float(abs(f - r) / scale)
                if d <= tol:
                    pairs.append((d, i, j))
    pairs.sort()
    used_r, used_f, errors = set(), set(), []
    for d, i, j in pairs:
        if i in used_r or j in used_f:
            continue
        used_r.add(i)
        used_f.add(j)
        errors.append(d)
    return Match(len(got), len(ref), len(errors), len(ref) - len(errors),
                 len(got) - len(used_f), max(errors) if errors else None)
