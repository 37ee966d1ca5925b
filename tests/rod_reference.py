"""Closed forms of uniform rods (used by several test files); nothing of symtmm is used.

A rod's axial motion (``c = sqrt(EA/m)``) and its twist (``c = sqrt(GJ/rhoIp)``) obey
the wave equation: fixed-fixed ``n pi c / L``, fixed-free ``(2n - 1) pi c / (2 L)``,
free-free ``n pi c / L`` from ``n = 0`` (the rigid motion); a tip mass ``M`` (inertia
``J``) on a fixed-free rod gives ``beta L tan(beta L) = m L / M`` (``rhoIp L / J``).
"""

from __future__ import annotations

import math

import mpmath


def family(kind: str, c: float, L: float, count: int) -> list:
    """The first ``count`` frequencies of a uniform rod: ``kind`` its ends (``"free-free"``,
    ``"fixed-fixed"``, else fixed at one end and free at the other), ``c`` the wave speed."""
    if kind == "free-free":
        return [n * math.pi * c / L for n in range(count)]
    if kind == "fixed-fixed":
        return [n * math.pi * c / L for n in range(1, count + 1)]
    return [(2 * n - 1) * math.pi * c / (2 * L) for n in range(1, count + 1)]


def tip_roots(ratio: float, count: int) -> list:
    """``x tan x = ratio``: one root in each ``(n pi, n pi + pi/2)`` (by ``x sin x = ratio
    cos x``, which has no poles)."""
    out = []
    for n in range(count):
        lo, hi = n * math.pi + 1e-12, n * math.pi + math.pi / 2 - 1e-12
        out.append(float(mpmath.findroot(lambda x: x * mpmath.sin(x) - ratio * mpmath.cos(x),
                                         (lo, hi), solver="anderson")))
    return out
