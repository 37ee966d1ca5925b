"""Converting exact SymPy values to numbers of a given precision (the ambient mpmath one)."""

from __future__ import annotations

import mpmath
import sympy as sp

__all__ = ["to_mp", "to_float"]


def to_mp(expr, dps: int):
    """An exact real SymPy value as an mpmath number with ``dps`` correct digits.

    Examples
    --------
    >>> import mpmath
    >>> with mpmath.workdps(30):
    ...     print(to_mp(sp.pi / 3, 30))
    1.04719755119659774615421446109
    """
    value = sp.N(sp.sympify(expr), dps + 5)
    if value.is_real is False or not value.is_number:
        raise ValueError(f"not a real number: {expr}")
    return mpmath.mpf(value._to_mpmath(mpmath.mp.prec))


def to_float(expr) -> float:
    """An exact real SymPy value as a Python float."""
    return float(sp.sympify(expr))
