"""Exact dynamic stiffness and the Wittrick–Williams eigenvalue count.

For an undamped model, the number of natural frequencies below ``omega``
(counted with multiplicity, rigid-body modes included) is

    J(omega) = J0(omega) + s{K(omega)}

where ``K`` is the exact dynamic stiffness matrix of the structure with its
boundary conditions applied, ``s{K}`` the number of its negative eigenvalues,
and ``J0`` the number of natural frequencies below ``omega`` of the segments
with all their ends clamped (Wittrick & Williams 1971). This count cannot miss
a root, and it is what makes the root search certain.

The segment stiffness comes from the segment's own transfer matrix, split
into displacement and force blocks ``z = [d; f]``, ``d = (Y, Theta)``,
``f = (M, Q)``: ``f0 = U12^-1 (d1 - U11 d0)`` and ``f1 = U21 d0 + U22 f0``.
The end actions conjugate to ``(Y0, Theta0, Y1, Theta1)`` are
``(Q0, -M0, -Q1, M1)``. Beams are cut into segments with ``beta l <= NU_MAX``
at the highest frequency asked for: the clamped-clamped segments then have no
natural frequency below it (``J0 = 0``, first one at ``beta l = 4.730``), and
no digit is lost to the cancellation that long segments suffer.
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import sympy as sp

from .assembly import point_elements
from .elements import EulerBernoulliSegment
from .elements.base import LAM
from .model import Model
from .numeric import to_mp

__all__ = ["StiffnessModel", "NU_MAX", "SingularCount", "SINGULAR_DPS"]

#: A count whose pivot stays below the working precision up to this many digits is taken at
#: an eigenvalue (within 10**-SINGULAR_DPS of it): :class:`SingularCount`.
SINGULAR_DPS = 240


class SingularCount(ArithmeticError):
    """``K(omega)`` is singular: ``omega`` is an eigenvalue, and the count is not defined there.

    The count ``J(omega)`` counts the eigenvalues strictly below ``omega``; at an
    eigenvalue a pivot of ``K`` is zero and its sign undefined. Callers count at a
    point moved off it instead.
    """


#: Largest ``beta l`` of a segment at the design frequency.
NU_MAX = 2.0
# Zero-pivot guard: relative size below which a pivot's sign is not trusted in double.
_DOUBLE_TRUST = 1e-10

_BC_DOFS_REMOVED = {"free": (), "clamped": (0, 1), "pinned": (0,), "sliding": (1,)}


def segment_stiffness(U):
    """4x4 dynamic stiffness of a segment from its 4x4 transfer matrix.

    Works on numpy float arrays and on object arrays of mpmath numbers.

    Examples
    --------
    >>> U = EulerBernoulliSegment(1, 1, 1).evaluate_numpy(np.array(0.0)).real
    >>> np.round(segment_stiffness(U), 12)    # the static beam stiffness matrix
    array([[ 12.,   6., -12.,   6.],
           [  6.,   4.,  -6.,   2.],
           [-12.,  -6.,  12.,  -6.],
           [  6.,   2.,  -6.,   4.]])
    """
    U11, U12, U21, U22 = U[:2, :2], U[:2, 2:], U[2:, :2], U[2:, 2:]
    det = U12[0, 0] * U12[1, 1] - U12[0, 1] * U12[1, 0]
    inv = np.array([[U12[1, 1], -U12[0, 1]], [-U12[1, 0], U12[0, 0]]], dtype=U.dtype) / det
    A = -inv.dot(U11)
    B = inv
    C = U21 + U22.dot(A)
    E = U22.dot(B)
    f0 = np.concatenate([A, B], axis=1)   # rows: M0, Q0
    f1 = np.concatenate([C, E], axis=1)   # rows: M1, Q1
    return np.stack([f0[1], -f0[0], -f1[1], f1[0]])


class StiffnessModel:
    """Global dynamic stiffness of an undamped model, valid up to ``omega_design``.

    Parameters
    ----------
    model : Model
        Numeric and undamped.
    omega_design : float
        Highest circular frequency at which :meth:`count` will be asked.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> sm = StiffnessModel(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 100.0)
    >>> [sm.count(w) for w in (1.0, 10.0, 40.0, 90.0)]   # roots at (n pi)^2: 9.87, 39.5, 88.8
    [0, 1, 2, 3]
    """

    def __init__(self, model: Model, omega_design: float):
        model = model.require_numeric()
        if model.damped:
            raise ValueError("the stiffness count needs an undamped model")
        self.model = model
        self.omega_design = float(omega_design)
        self.evaluations = 0
        self._build()

    def _build(self):
        beams = self.model.beams
        points_el = point_elements(self.model)
        nodes = []        # (x float, beam index, exact x)
        self.segments = []  # (beam index, segment, left node id, right node id)
        beam_nodes = []
        for b_idx, beam in enumerate(beams):
            required = [beam.x0, beam.x1] + [x for x, el in points_el if beam.name in el.beams]
            xs = sorted({sp.nsimplify(x) for x in required}, key=float)
            points = [xs[0]]
            mu = (float(beam.m) / float(beam.EI)) ** 0.25 * math.sqrt(self.omega_design)
            for xa, xb in itertools.pairwise(xs):
                n_sub = max(1, math.ceil(mu * float(xb - xa) / NU_MAX))
                points += [xa + (xb - xa) * sp.Rational(k, n_sub) for k in range(1, n_sub + 1)]
            ids = []
            for x in points:
                ids.append(len(nodes))
                nodes.append((float(x), b_idx, x))
            beam_nodes.append(dict(zip(points, ids)))
            for (xa, ia), (xb, ib) in zip(zip(points, ids), zip(points[1:], ids[1:])):
                self.segments.append((b_idx, EulerBernoulliSegment(beam.EI, beam.m, xb - xa, beam.kw),
                                      ia, ib))
        removed = {}
        for b_idx, beam in enumerate(beams):
            first, last = beam_nodes[b_idx][min(beam_nodes[b_idx], key=float)], \
                beam_nodes[b_idx][max(beam_nodes[b_idx], key=float)]
            removed[(first, "left")] = _BC_DOFS_REMOVED[beam.left]
            removed[(last, "right")] = _BC_DOFS_REMOVED[beam.right]
        # Number the dofs in order of x so that the matrix is banded.
        order = sorted(range(len(nodes)), key=lambda i: (nodes[i][0], nodes[i][1]))
        self.dof = {}
        n = 0
        for node in order:
            gone = set(removed.get((node, "left"), ())) | set(removed.get((node, "right"), ()))
            for k in (0, 1):
                if k not in gone:
                    self.dof[(node, k)] = n
                    n += 1
        self.size = n
        self.points = []
        self.point_elements = []    # (dofs, element): the exact stiffness, for ball arithmetic
        index = {b.name: i for i, b in enumerate(beams)}
        for x, el in points_el:
            x = sp.nsimplify(x)
            node_ids = [beam_nodes[index[name]][x] for name in el.beams]
            dofs = [self.dof.get((node_ids[lvl], 0 if var == "Y" else 1))
                    for lvl, var in el.dofs]
            S = el.stiffness(LAM)
            self.points.append((dofs, sp.lambdify(LAM, S, "numpy"), sp.lambdify(LAM, S, "mpmath")))
            self.point_elements.append((dofs, el))
        self._seg_dofs = [[self.dof.get((ia, 0)), self.dof.get((ia, 1)),
                           self.dof.get((ib, 0)), self.dof.get((ib, 1))]
                          for _, _, ia, ib in self.segments]
        self._seg_consts = [(float(s.EI), float(s.m), float(s.l), float(s.kw))
                            for _, s, _, _ in self.segments]
        self._segment_kind = {c: seg for c, (_, seg, _, _) in zip(self._seg_consts, self.segments)}
        self._mp_consts: dict = {}
        self.bandwidth = 0
        for dofs in self._seg_dofs + [p[0] for p in self.points]:
            live = [d for d in dofs if d is not None]
            if live:
                self.bandwidth = max(self.bandwidth, max(live) - min(live))

    def _ensure(self, omega: float):
        if omega > self.omega_design * (1 + 1e-12):
            self.omega_design = 2.0 * omega
            self._build()

    # -- double precision -----------------------------------------------------------
    def matrix(self, omega: float) -> np.ndarray:
        """``K(omega)`` in double precision (dense)."""
        self._ensure(omega)
        K = np.zeros((self.size, self.size))
        lam2 = np.array(-omega * omega)
        # segments of equal properties share their matrix: evaluate each kind once
        cache: dict = {}
        for dofs, consts in zip(self._seg_dofs, self._seg_consts):
            D = cache.get(consts)
            if D is None:
                D = segment_stiffness(self._segment_kind[consts].evaluate_numpy(lam2, consts).real)
                cache[consts] = D
            _scatter(K, D, dofs)
        for dofs, f_np, _ in self.points:
            S = np.real(np.asarray(f_np(1j * omega), dtype=complex))
            _scatter(K, S, dofs)
        return K

    def count(self, omega: float, dps: int | None = None) -> int:
        """Number of natural frequencies below ``omega``, with multiplicity.

        Double precision unless the smallest eigenvalue of ``K`` is too close
        to zero to trust its sign; then (or when ``dps`` is given) the count is
        redone with mpmath at ``dps`` digits (default 30), raising the
        precision until every pivot is clear of zero.
        """
        self.evaluations += 1
        if dps is None:
            negative = _banded_inertia(self.matrix(omega), self.bandwidth)
            if negative is not None:
                return negative
            dps = 30
        while True:
            with mpmath.workdps(dps):
                result = self._count_mp(mpmath.mpf(omega) if not isinstance(omega, mpmath.mpf)
                                        else omega)
            if result is not None:
                return result
            if dps >= SINGULAR_DPS:
                raise SingularCount(f"K({omega}) is singular to {dps} digits: an eigenvalue")
            dps *= 2

    def matrix_mp(self, omega) -> list:
        """``K(omega)`` at the current mpmath precision, as a list of rows."""
        self._ensure(float(omega))
        n = self.size
        K = [[mpmath.mpf(0)] * n for _ in range(n)]
        lam2 = -omega * omega
        cache: dict = {}
        for dofs, kind in zip(self._seg_dofs, self._seg_consts):
            D = cache.get(kind)
            if D is None:
                seg = self._segment_kind[kind]
                key = (kind, mpmath.mp.prec)
                consts = self._mp_consts.get(key)
                if consts is None:
                    consts = tuple(to_mp(v, mpmath.mp.dps) for v in seg.key)
                    self._mp_consts[key] = consts
                D = cache[kind] = segment_stiffness(seg.evaluate_mp(lam2, consts))
            _scatter(K, D, dofs)
        for dofs, _, f_mp in self.points:
            S = f_mp(mpmath.mpc(0, omega))
            S = [[mpmath.re(S[i, j]) for j in range(S.cols)] for i in range(S.rows)]
            _scatter(K, np.array(S, dtype=object), dofs)
        return K

    def _count_mp(self, omega):
        """Negative pivots of banded LDL^T; None if a pivot is too small to trust.

        Without pivoting, a small pivot makes the entries it updates grow, and
        the rounding errors of every later pivot grow with them: a pivot's sign
        is trusted only if it exceeds ``n`` times the largest entry met so far
        times the working precision (with 10 digits to spare).
        """
        K = self.matrix_mp(omega)
        n, b = self.size, self.bandwidth
        # the largest entry lies on the band: scan only that
        grow = max((abs(K[i][j]) for i in range(n) for j in range(i, min(n, i + b + 1))),
                   default=mpmath.mpf(1))
        unit = (n + 1) * mpmath.mpf(10) ** (-(mpmath.mp.dps - 10))
        negative = 0
        for k in range(n):
            pivot = K[k][k]
            if abs(pivot) <= grow * unit:
                return None
            if pivot < 0:
                negative += 1
            top = min(n, k + b + 1)
            row_k = K[k]
            for i in range(k + 1, top):
                if row_k[i] == 0:
                    continue
                f = row_k[i] / pivot
                row_i = K[i]
                # only the upper triangle is read, so only it is updated
                for j in range(i, top):
                    if row_k[j] != 0:
                        row_i[j] -= f * row_k[j]
                        grow = max(grow, abs(row_i[j]))
        return negative


def _banded_inertia(K: np.ndarray, band: int) -> int | None:
    """Number of negative pivots of LDL^T of a symmetric banded matrix (double).

    By Sylvester's law of inertia this is the number of negative eigenvalues.
    Returns None when a pivot is too small, relative to the largest entry met
    so far in the elimination (growth without pivoting carries the rounding
    errors up), for its sign to be trusted: the caller then counts again in
    higher precision.
    """
    n = K.shape[0]
    if n == 0:
        return 0
    K = K.copy()
    grow = np.max(np.abs(K))
    negative = 0
    for k in range(n):
        pivot = K[k, k]
        if abs(pivot) <= _DOUBLE_TRUST * grow:
            return None
        if pivot < 0:
            negative += 1
        top = min(n, k + band + 1)
        if top > k + 1:
            row = K[k, k + 1:top]
            # rank-one update of the trailing band block (upper and lower alike)
            K[k + 1:top, k + 1:top] -= np.outer(row, row) / pivot
            grow = max(grow, float(np.max(np.abs(K[k + 1:top, k + 1:top]))))
    return negative


def _scatter(K, local, dofs):
    for i, di in enumerate(dofs):
        if di is None:
            continue
        for j, dj in enumerate(dofs):
            if dj is None:
                continue
            K[di][dj] += local[i][j] if isinstance(K, list) else local[i, j]
