"""Normalisation of mode shapes: the kinetic energy of the columns a walk carries.

Undamped shapes are real and mass-normalised in the full kinetic energy: over
the beams the integral of ``m Y**2 + rhoI Theta**2`` (``Theta`` the section's
rotation: rotary inertia of Rayleigh and Timoshenko beams), plus
``M Y**2 + J Theta**2`` of every lumped mass and ``M Y_c**2 + J Theta_c**2``
of every rigid body (its unknowns in the extended state), which keeps the
shapes of distinct frequencies orthogonal. :class:`Energy` gathers the Gram
matrix of that energy for all columns at once, as an observer of the transfer
walk (:func:`symtmm.numeric.transfer.propagate`):

* an Euler–Bernoulli segment's integral has the closed form
  ``[F]/(4 kappa)``, ``kappa = beta**4``,
  ``F = x (kappa Y**2 - 2 Y' Y''' + Y''**2) + 3 Y Y''' - Y' Y''`` (from
  ``Y'''' = kappa Y``), from the states at its two ends; over a run of segments
  of one beam with the same constants and no jump of its state between them
  (the cuts of other beams' springs) the integrals telescope into one ``[F]``;
* every other segment (and an Euler–Bernoulli one where ``kappa l**4`` is
  small, where the closed form would cancel) is integrated by Gauss–Legendre
  quadrature on pieces with ``|s| h <= 1``, with as many nodes as the digits
  asked for need (:func:`~symtmm.numeric.quadrature.gauss_legendre_nodes`).

The ``m`` shapes of a multiple eigenvalue are then made mass-orthonormal with
the Cholesky factor of their Gram matrix (:func:`mass_orthonormaliser`).
Damped shapes are complex and scaled so that the largest ``|Y|`` over all
beams is ``1`` (:func:`complex_scaler`). Everything runs in the arithmetic of
the walk (:mod:`symtmm.numeric.arith`).
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

from ..assembly import Station
from ..elements import STATE
from ..errors import ComputationError
from ..numeric.arith import Arithmetic
from ..numeric.linalg import cholesky, lower_inverse
from ..numeric.quadrature import gauss_legendre, gauss_legendre_nodes
from ..numeric.segments import kind_inertia
from ..numeric.transfer import block

__all__ = ["Inertia", "Energy", "mass_orthonormaliser", "complex_scaler"]

#: Below this ``|kappa| l**4`` the closed-form integral would cancel; use quadrature (unless
#: the arithmetic holds the digits the cancellation costs: :func:`segment_gram`).
CLOSED_FORM_MIN = 1e-2

#: Digits kept beyond the cancellation of the closed form where it is used below
#: :data:`CLOSED_FORM_MIN`.
_CLOSED_FORM_GUARD = 10


class Inertia:
    """Where a plan's lumped inertia sits: exact tables, the same at every eigenvalue.

    Attributes
    ----------
    stations : dict
        Step index -> ``[(displacement indices, exact mass matrix)]`` of the point
        elements there with inertia (masses).
    bodies : list
        ``(indices, coefficients, exact M or J)``: the inertia ``M (sum c_i z_i)**2`` of
        the rigid bodies' translations and rotations, and of inextensible bars moving
        along their axes with the bodies at their ends.
    """

    def __init__(self, plan):
        self.plan = plan
        self.stations: dict = {}
        for i, step in enumerate(plan.layout.steps):
            if not isinstance(step, Station):
                continue
            for element, levels in step.elements:
                inertia = element.inertia()
                if not inertia.is_zero_matrix:
                    disp = [4 * levels[lvl] + STATE.index(var) for lvl, var in element.dofs]
                    self.stations.setdefault(i, []).append((disp, inertia))
        self.bodies = []
        for bl in plan.layout.bodies:
            for label in bl.frame.freedoms:
                mass = bl.frame.mass(bl.body, label)
                if mass != 0:
                    self.bodies.append(((bl.unknowns[label],), (1,), mass))
        for ll in plan.layout.links:
            bl, row = ll.rows[0]
            if ll.link.M != 0:
                self.bodies.append((tuple(bl.unknowns[label] for label in row),
                                    tuple(row.values()), ll.link.M))


class Energy:
    """The kinetic-energy Gram matrix of the columns of one real walk, step by step.

    Pass the instance as ``observe`` to :func:`~symtmm.numeric.transfer.propagate`
    (or :func:`~symtmm.numeric.transfer.sample`), then read :meth:`gram` with the
    left state.

    Parameters
    ----------
    inertia : Inertia
    ar : Arithmetic
        The walk's arithmetic.
    lam2 : array
        ``(1,)``: the walk's ``lam**2`` (real).
    digits : int
        Correct digits the integrals must carry.
    """

    def __init__(self, inertia: Inertia, ar: Arithmetic, lam2, digits: int):
        self.inertia = inertia
        self.plan = inertia.plan
        self.ar = ar
        self.lam2 = lam2
        self.lam2_c = complex(ar.to_complex(lam2)[0])
        self.digits = digits
        self.G = None
        self._levels: dict = {}
        self._runs: dict = {}
        self._beams = 4 * self.plan.layout.levels      # rows of the beams' states

    def _add(self, part, level: int):
        self.G = part if self.G is None else self.G + part
        self._levels[level] = part if level not in self._levels else self._levels[level] + part

    def __call__(self, i, before, after):
        kind, items = self.plan.steps[i]
        if kind == "segments":
            for lvl, k in items:
                if not isinstance(lvl, int):
                    for level in lvl:
                        self._close(level)
                    parts = coupled_gram(self.plan, self.ar, k, self.lam2, self.lam2_c,
                                         before[0, block(lvl), :], self.digits)
                    for level, part in zip(lvl, parts):
                        self._add(part, level)
                    continue
                blk = slice(4 * lvl, 4 * lvl + 4)
                family, consts = self.plan.kinds[k]
                if family != "eb":
                    self._close(lvl)
                    self._add(segment_gram(self.plan, self.ar, k, self.lam2, self.lam2_c,
                                           before[0, blk, :], after[0, blk, :], self.digits),
                              lvl)
                    continue
                # an Euler-Bernoulli run: its segments' integrals telescope (see _Run)
                key = (consts[0], consts[1], consts[3])
                run = self._runs.get(lvl)
                if run is not None and run.key != key:
                    self._close(lvl)
                    run = None
                if run is None:
                    run = self._runs[lvl] = _Run(key)
                # (``after`` is the walk's own array, changed in place as it goes on)
                run.extend(self.ar, k, consts[2], before[0, blk, :], after[0, blk, :].copy())
            return
        # the state of a beam jumps here: its run ends
        for level in sorted({row // 4 for row, _, _ in items if row < self._beams}):
            self._close(level)
        ar = self.ar
        # lumped masses: d^T M d (displacements do not jump at the station)
        for disp, inertia in self.inertia.stations.get(i, ()):
            Mi = ar.array([ar.exact(v) for v in inertia], inertia.shape)
            D = before[0, disp, :]
            self._add(D.T @ Mi @ D, disp[0] // 4)

    def _close(self, level: int):
        run = self._runs.pop(level, None)
        if run is not None:
            self._add(run.gram(self.plan, self.ar, self.lam2, self.lam2_c, self.digits), level)

    def _finish(self):
        for level in sorted(self._runs):
            self._close(level)

    def gram(self, start):
        """The Gram matrix, the bodies' energy added from the left state ``start``
        (``size x k``: the bodies' unknowns are constant along ``x``)."""
        self._finish()
        G = self.G
        for part in self._bodies(start):
            G = G + part
        return G

    def parts(self, start) -> list:
        """The Gram matrix in parts that sum to :meth:`gram`: one per beam (its segments
        and the masses on it), then one per inertia of a body."""
        self._finish()
        return [self._levels[lvl] for lvl in sorted(self._levels)] + self._bodies(start)

    def _bodies(self, start) -> list:
        ar, out = self.ar, []
        for indices, coefs, value in self.inertia.bodies:
            v = sum(start[i, :] * ar.exact(c) for i, c in zip(indices, coefs))
            out.append(np.outer(v, v) * ar.exact(value))
        return out


class _Run:
    """Consecutive Euler–Bernoulli segments of one beam with the same ``EI``, ``m`` and
    ``kw``, and no jump of its state between them (the cuts of other beams' springs).

    ``F`` of the closed form (:func:`_bilinear_F`) has ``dF/dx = 4 kappa Y**2`` with the
    state continuous, so the segments' integrals telescope: one ``[F]`` over the run
    from its two end states, where a 20-level chain cut every beam at 40 points and
    paid for each piece. Where the run is too short for the closed form it is summed
    piece by piece (:func:`segment_gram`), as before.
    """

    __slots__ = ("end", "key", "kinds", "length", "starts")

    def __init__(self, key):
        self.key = key
        self.kinds: list = []
        self.starts: list = []
        self.end = None
        self.length = None

    def extend(self, ar, k: int, length, Z0, Z1):
        self.kinds.append(k)
        self.starts.append(Z0)
        self.end = Z1
        piece = ar.exact(length)
        self.length = piece if self.length is None else self.length + piece

    def gram(self, plan, ar: Arithmetic, lam2, lam2_c: complex, digits: int):
        EI, m, kw = (ar.exact(v) for v in self.key)
        kappa = -(lam2[0] * m + kw) / EI
        if len(self.kinds) > 1 and _closed_form_holds(ar, kappa, self.length, digits):
            F1 = _bilinear_F(ar, self.length, kappa, EI, self.end)
            F0 = _bilinear_F(ar, None, kappa, EI, self.starts[0])
            return (F1 - F0) * (m / (4 * kappa))
        ends = self.starts[1:] + [self.end]
        out = None
        for k, Z0, Z1 in zip(self.kinds, self.starts, ends):
            part = segment_gram(plan, ar, k, lam2, lam2_c, Z0, Z1, digits)
            out = part if out is None else out + part
        return out


def _closed_form_holds(ar: Arithmetic, kappa, length, digits: int) -> bool:
    """Whether ``[F]/(4 kappa)`` over ``length`` keeps ``digits`` in ``ar``: it loses about
    ``log10(1 / |kappa| l**4)`` digits to cancellation, which the walk's arithmetic may
    hold beyond the integrals' own (the digits of a shape's walk are its cancellation's,
    two to five times the shape's)."""
    size = float(ar.upper(ar.array([kappa * length ** 4]))[0])
    spare = ar.digits - digits - _CLOSED_FORM_GUARD
    return size > 0 and size >= min(CLOSED_FORM_MIN, 10.0 ** -max(spare, 0))


def _bilinear_F(ar, x, kappa, EI, Z):
    """The boundary form whose difference is ``4 kappa`` times the integrals of ``Y_a Y_b``
    for all pairs of columns of ``Z`` (``4 x k``); ``x`` None at the segment's start.

    Arrays stay on the left of numbers: an mpmath number on the left first tries to
    convert the whole array (and prints it for the error it then swallows)."""
    Y, T, M, Q = Z
    d2, d3 = M / EI, Q / EI

    def sym(a, b):
        out = np.outer(a, b)
        return out + out.T
    out = sym(Y, d3) * ar.exact(sp.Rational(3, 2)) - sym(T, d2) / 2
    if x is not None:
        out = out + (np.outer(Y, Y) * kappa - sym(T, d3) + np.outer(d2, d2)) * x
    return out


def segment_gram(plan, ar: Arithmetic, k: int, lam2, lam2_c: complex, Z0, Z1, digits: int):
    """``integral of m Y_i Y_j + rhoI Theta_i Theta_j`` over one segment of kind ``k`` for
    the columns of ``Z0`` (states at its start; ``Z1`` at its end).

    Euler–Bernoulli segments (on a foundation too) use the closed form
    ``[F]/(4 kappa)``, ``Y'''' = kappa Y``, unless ``|kappa| l**4`` is so small that
    it would cancel; every other segment Gauss–Legendre quadrature (:func:`_quadrature`).
    """
    family, consts = plan.kinds[k]
    if family == "eb":
        EI, m, length, kw = (ar.exact(v) for v in consts)
        kappa = -(lam2[0] * m + kw) / EI
        # (quadrature on the short pieces of a chain cost two thirds of its shapes)
        if _closed_form_holds(ar, kappa, length, digits):
            F1 = _bilinear_F(ar, length, kappa, EI, Z1)
            F0 = _bilinear_F(ar, None, kappa, EI, Z0)
            return (F1 - F0) * (m / (4 * kappa))
        return _quadrature(plan, ar, k, lam2, lam2_c, Z0, m, None, digits)
    m, rhoI = kind_inertia(plan.kinds[k])
    return _quadrature(plan, ar, k, lam2, lam2_c, Z0, ar.exact(m), ar.exact(rhoI), digits)


def _quadrature(plan, ar, k, lam2, lam2_c, Z0, m, rhoI, digits):
    """The kinetic-energy Gram matrix of one segment by Gauss–Legendre quadrature.

    The segment is cut into pieces with ``|s| h <= 1``, each integrated by the rule
    of :func:`~symtmm.numeric.quadrature.gauss_legendre_nodes`; the transfer matrices
    to the nodes are the same on every piece and are computed once.
    """
    seg = plan.kind_segments[k]
    pieces = max(1, math.ceil(float(np.max(seg.wave_number(lam2_c))) * float(seg.l)))
    h = ar.exact(seg.l) / pieces
    nodes, weights = gauss_legendre(ar, gauss_legendre_nodes(digits))
    U = plan.piece_matrices(ar, k, lam2, ar.array(list(nodes * h) + [h]))[0]
    to_nodes, step = U[:-1, :2, :], U[-1]
    w = weights * h
    out = None
    Z = Z0
    for p in range(pieces):
        z = to_nodes @ Z                        # (nodes, 2, k): Y and Theta at the nodes
        part = (z[:, 0, :].T * w) @ z[:, 0, :] * m
        if rhoI is not None and rhoI != 0:
            part = part + (z[:, 1, :].T * w) @ z[:, 1, :] * rhoI
        out = part if out is None else out + part
        if p + 1 < pieces:
            Z = step @ Z
    return out


def coupled_gram(plan, ar: Arithmetic, k: int, lam2, lam2_c: complex, Z0, digits: int) -> list:
    """Per beam of a coupled piece (kind ``k``, beams joined by layers; the layers are
    massless), ``integral of m Y_i Y_j`` for the columns of ``Z0`` (the coupled state at
    its start), by Gauss–Legendre quadrature as :func:`_quadrature`."""
    seg = plan.kind_segments[k]
    N = seg.size
    pieces = max(1, math.ceil(float(np.max(seg.wave_number(lam2_c))) * float(seg.l)))
    h = ar.exact(seg.l) / pieces
    nodes, weights = gauss_legendre(ar, gauss_legendre_nodes(digits))
    U = plan.piece_matrices(ar, k, lam2, ar.array(list(nodes * h) + [h]))[0]
    to_nodes, step = U[:-1, :N, :], U[-1]          # Y of every beam at the nodes
    w = weights * h
    masses = [ar.exact(m) for _, m, _ in seg.beams]
    out = [None] * N
    Z = Z0
    for p in range(pieces):
        z = to_nodes @ Z                             # (nodes, N, k)
        for i in range(N):
            part = (z[:, i, :].T * w) @ z[:, i, :] * masses[i]
            out[i] = part if out[i] is None else out[i] + part
        if p + 1 < pieces:
            Z = step @ Z
    return out


def mass_orthonormaliser(ar: Arithmetic, G):
    """``T`` with ``T^T G T = I`` (``G`` symmetric positive definite): ``T = L^-T``, ``G = L L^T``.

    Examples
    --------
    >>> import numpy as np
    >>> from symtmm.numeric.arith import MP
    >>> ar = MP(100)
    >>> G = ar.array([ar.number(v) for v in (4, 2, 2, 5)], (2, 2))
    >>> T = mass_orthonormaliser(ar, G)
    >>> bool(abs(T.T @ G @ T - np.eye(2)).max() < 1e-28)
    True
    """
    try:
        L = cholesky(ar, G)
    except ComputationError:
        raise ComputationError("mode shape with zero mass (null vector lost)") from None
    return lower_inverse(ar, L).T


def complex_scaler(ar: Arithmetic, Y):
    """Diagonal ``T`` making each damped shape's largest ``|Y|`` equal to 1 (real).

    ``Y``: ``(points, k)`` complex samples of the displacement of every column.
    """
    k = Y.shape[1]
    T = ar.zeros((k, k), like=ar.array([ar.number(1j)]))
    for c in range(k):
        # (the first of the largest within rounding: ties, as at the two peaks of a
        # symmetric mode, would let rounding choose the phase)
        size = np.abs(Y[:, c])
        best = Y[int(np.argmax(size >= size.max() * (1 - 1e-9))), c]
        if best == 0:
            raise ComputationError("mode shape vanishes (null vector lost)")
        T[c, c] = 1 / ar.number(complex(best))
    return T
