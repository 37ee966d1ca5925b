"""References for planar frames (tests/test_frames_fe.py); nothing of symtmm's kernel is used.

* Closed forms of a uniform Euler-Bernoulli beam (Blevins, *Formulas for natural frequency
  and mode shape*, table 8-1): ``omega = (beta L)**2 sqrt(EI / (m L**4))`` with ``beta L``
  a root of ``cos x cosh x = 1`` (clamped-clamped) or ``tan x = tanh x``
  (clamped-pinned), found here by ``mpmath.findroot`` from the textbook's asymptotic
  starting points; a fixed-fixed rod, ``n pi sqrt(EA/m) / L``.
* The finite-element model of :mod:`symtmm.fe` (:func:`symtmm.fe.fe_frame_converged`:
  frame elements written from the textbook, Romberg's extrapolation over three nested
  meshes), with its error estimate held below a bound.
* Conversions: a frame given as plain data (exact strings such as ``"sqrt(3)/2"``) to
  symtmm's :class:`~symtmm.frame.Member` and :class:`~symtmm.frame.Node` and to the FE
  model's dicts (floats), and a solve's frequencies repeated by their multiplicity.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import sympy as sp

from symtmm.fe import fe_frame_converged
from symtmm.frame import Member, Node


def _roots(f, guesses, dps=30):
    with mpmath.workdps(dps):
        return [float(mpmath.findroot(f, mpmath.mpf(g))) for g in guesses]


def clamped_clamped(count: int) -> list:
    """``beta L`` of a clamped-clamped beam: ``cos x cosh x = 1`` (written ``cos x - sech
    x = 0``), roots near ``(2n + 1) pi / 2``."""
    return _roots(lambda x: mpmath.cos(x) - mpmath.sech(x),
                  [(2 * n + 1) * math.pi / 2 for n in range(1, count + 1)])


def clamped_pinned(count: int) -> list:
    """``beta L`` of a clamped-pinned beam: ``tan x = tanh x`` (written ``sin x cosh x - cos
    x sinh x`` over ``cosh x``), roots near ``(4n + 1) pi / 4``."""
    return _roots(lambda x: mpmath.sin(x) - mpmath.cos(x) * mpmath.tanh(x),
                  [(4 * n + 1) * math.pi / 4 for n in range(1, count + 1)])


def beam_omegas(roots, EI: float, m: float, L: float) -> list:
    """``omega = (beta L)**2 sqrt(EI / m) / L**2`` for each root ``beta L``."""
    return [x * x * math.sqrt(EI / m) / (L * L) for x in roots]


def rod_fixed_fixed(count: int, EA: float, m: float, L: float) -> list:
    """A fixed-fixed rod: ``n pi sqrt(EA/m) / L``, ``n = 1 .. count``."""
    return [n * math.pi * math.sqrt(EA / m) / L for n in range(1, count + 1)]


def number(value) -> float:
    """An exact value (a number or a string such as ``"sqrt(3)/2"``) as a float."""
    return float(sp.sympify(value))


def turned(point, cos, sin) -> tuple:
    """A point turned about the origin (exact: ``cos``, ``sin`` strings or numbers)."""
    x, y = (sp.sympify(v) for v in point)
    c, s = sp.sympify(cos), sp.sympify(sin)
    return (sp.nsimplify(sp.expand(c * x - s * y)), sp.nsimplify(sp.expand(s * x + c * y)))


def symtmm_frame(members, nodes):
    """symtmm's members and nodes of a frame given as data: members ``(name, start, end, EI,
    EA, m)``, nodes dicts of :class:`~symtmm.frame.Node`'s keywords."""
    return ([Member(name, start, end, EI=EI, EA=EA, m=m)
             for name, start, end, EI, EA, m in members],
            [Node(**node) for node in nodes])


def fe_frame(members, nodes):
    """The same frame as the FE model's dicts (floats)."""
    fe_members = [dict(name=name, start=tuple(map(number, start)), end=tuple(map(number, end)),
                       EI=number(EI), EA=None if EA is None else number(EA), m=number(m))
                  for name, start, end, EI, EA, m in members]
    fe_nodes = [dict(node, at=tuple(map(number, node["at"])),
                     **{k: number(node[k]) for k in ("M", "J") if k in node})
                for node in nodes]
    return fe_members, fe_nodes


def fe_reference(members, nodes, count: int, elements: int, bound: float = 1e-9):
    """The first ``count`` converged FE frequencies of a frame given as data and their
    error estimate, which must lie below ``bound`` relative (zero modes exact)."""
    fe_members, fe_nodes = fe_frame(members, nodes)
    out = fe_frame_converged(fe_members, fe_nodes, elements, count)
    assert np.all(out["error"] <= bound * out["omega"]), (out["error"], out["omega"])
    return out["omega"], out["error"]


def omegas(result) -> np.ndarray:
    """A spectrum's frequencies as floats, each repeated by its multiplicity."""
    return np.array([float(e.omega) for e in result.eigenvalues
                     for _ in range(e.multiplicity)])
