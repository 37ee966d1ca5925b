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
``(Q0, -M0, -Q1, M1)``. This holds for every beam theory of
:mod:`symtmm.elements.theories` (``Theta`` the rotation of the cross-section,
``M`` and ``Q`` the actions conjugate to it and to ``Y``), and ``K`` is
symmetric. Beams are cut at their ends, point elements and attachments, and
further into pieces that reach none of their own clamped-clamped natural
frequencies below the highest frequency asked for
(``segment.safe_length(omega**2)``, rigorous for every theory; an
Euler–Bernoulli piece keeps ``beta l <= NU_MAX``, below the first
clamped-clamped root ``beta l = 4.730``), so ``J0 = 0``. Pieces are also kept
to ``|s| l <= NU_MAX`` for their largest wave number ``s``, so that no digit
is lost to the growth of long segments.

Rigid bodies (joints are massless ones) enter by master–slave elimination.
A body has the freedoms ``Y_c`` and, if it rotates, ``Theta_c`` of its
centre of mass ``xc``; at an attachment at ``x_i`` the beam's ``Y`` is
``Y_c + (x_i - xc) Theta_c`` and, if the attachment is rigid, its ``Theta`` is
``Theta_c``; the body adds ``lam**2 diag(M, J)`` on ``(Y_c, Theta_c)``. A
boundary condition at a beam end attached to a body constrains the body. These
linear constraints are eliminated exactly (:class:`Mesh`): every freedom is a
combination of the remaining ones, ``K = T^T K_full T`` is the stiffness of
the constrained structure, and the count holds for it unchanged (fixing the
remaining freedoms still clamps every segment). Body freedoms are numbered
next to the node of their first attachment, which keeps ``K`` banded.

An axial compression above a buckling load makes the static stiffness
indefinite: eigenvalues ``omega**2 < 0`` (``lam`` real, a growing motion),
which ``J`` counts below every ``omega``. :meth:`StiffnessModel.unstable_modes`
counts them.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import sympy as sp

from .elements import EulerBernoulliSegment
from .elements.base import LAM
from .errors import ComputationError
from .mesh import Mesh
from .model import Model
from .numeric import to_mp

__all__ = ["StiffnessModel", "Mesh", "NU_MAX", "SingularCount", "SINGULAR_DPS",
           "segment_stiffness", "wave_number_bound"]

#: A count whose pivot stays below the working precision up to this many digits is taken at
#: an eigenvalue (within 10**-SINGULAR_DPS of it): :class:`SingularCount`.
SINGULAR_DPS = 240


class SingularCount(ArithmeticError):
    """``K(omega)`` is singular: ``omega`` is an eigenvalue, and the count is not defined there.

    The count ``J(omega)`` counts the eigenvalues strictly below ``omega``; at an
    eigenvalue a pivot of ``K`` is zero and its sign undefined. Callers count at a
    point moved off it instead.
    """


#: Largest ``|s| l`` (``beta l`` for Euler–Bernoulli) of a segment at the design frequency.
NU_MAX = 2.0
# Zero-pivot guard: relative size below which a pivot's sign is not trusted in double.
_DOUBLE_TRUST = 1e-10



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


def wave_number_bound(segment, radius: float) -> float:
    """An upper bound on the largest wave number of ``segment`` for all ``|lam**2| <= radius``.

    From the triangle inequality on the trace ``t`` and determinant ``d`` of the
    segment's ``G`` (see :mod:`symtmm.elements.theories`); for an Euler–Bernoulli
    segment ``((m radius + kw) / EI)**(1/4)``.

    Examples
    --------
    >>> round(wave_number_bound(EulerBernoulliSegment(1, 1, 1), 16.0), 12)
    2.0
    """
    if isinstance(segment, EulerBernoulliSegment):
        EI, m, _, kw = segment.constants()
        return ((m * radius + kw) / EI) ** 0.25
    EI, m, _, kw, N, rhoI, kGA = segment.constants()
    if math.isinf(kGA):
        a, b = 1.0, 0.0
    else:
        a, b = kGA / (kGA + N), -1.0 / (kGA + N)
    c = abs(N * a) + rhoI * radius
    mu = m * radius + kw
    t = c / EI + abs(b) * mu
    d = mu * (a * a + abs(b) * c) / EI
    return math.sqrt(t / 2 + math.sqrt(t * t / 4 + d))


def _scatter(K, local, places):
    """Add ``T^T local T`` into ``K``: ``places[i]`` is local freedom ``i`` as a combination."""
    for i, ci in enumerate(places):
        for gi, ai in ci:
            row = K[gi]
            for j, cj in enumerate(places):
                value = local[i][j]
                for gj, aj in cj:
                    row[gj] += ai * aj * value


def _count_piece(segment, omega2: float) -> float:
    """The longest piece of ``segment`` for the count up to ``omega2``.

    None of its clamped-clamped natural frequencies lies below ``omega``
    (``J0 = 0``), and its largest wave number ``s`` keeps ``|s| l <= NU_MAX``.
    """
    if isinstance(segment, EulerBernoulliSegment):
        return segment.safe_length(omega2, nu_max=NU_MAX)
    longest = segment.safe_length(omega2)
    s = float(np.max(segment.wave_number(np.array(-omega2))))
    return min(longest, NU_MAX / s) if s > 0 else longest


def _lam_numpy(lam2: float) -> complex:
    """``lam`` with ``lam**2 = lam2``: ``i omega`` below zero, real above."""
    return 1j * math.sqrt(-lam2) if lam2 <= 0 else complex(math.sqrt(lam2))


class StiffnessModel:
    """Global dynamic stiffness of an undamped model, valid up to ``omega_design``.

    Parameters
    ----------
    model : Model
        Numeric and undamped.
    omega_design : float
        Highest circular frequency at which :meth:`count` will be asked (a
        higher one rebuilds the mesh).

    Attributes
    ----------
    mesh : Mesh
        Segments and the combinations of free freedoms they act on.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> sm = StiffnessModel(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 100.0)
    >>> [sm.count(w) for w in (1.0, 10.0, 40.0, 90.0)]   # roots at (n pi)^2: 9.87, 39.5, 88.8
    [0, 1, 2, 3]

    A Timoshenko beam (``omega**2`` the smaller root of a quadratic, about 9.1 here):

    >>> t = Beam("t", 1, 1, 1, left="pinned", right="pinned", theory="timoshenko",
    ...          rhoI="1/100", kGA=100)
    >>> [StiffnessModel(Model((t,)), 20.0).count(w) for w in (9.0, 9.2)]
    [0, 1]
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
        omega2 = self.omega_design ** 2
        mesh = self.mesh = Mesh(self.model, lambda beam, seg: _count_piece(seg, omega2))
        self.size = mesh.size
        self.bandwidth = mesh.bandwidth
        self.segments = mesh.segments
        # segments of equal constants share one matrix: grouped by their exact key
        self._kinds: dict = {}
        groups: dict = {}
        for (_, seg, _, _), places in zip(mesh.segments, mesh.segment_places):
            self._kinds.setdefault(seg.key, seg)
            groups.setdefault(seg.key, []).append(places)
        # double precision: per kind, flat indices into K, into the local 4x4 and coefficients
        self._seg_groups = []
        for key, group in groups.items():
            flat_k, flat_l, coef = [], [], []
            for places in group:
                for i, ci in enumerate(places):
                    for j, cj in enumerate(places):
                        for gi, ai in ci:
                            for gj, aj in cj:
                                flat_k.append(gi * self.size + gj)
                                flat_l.append(4 * i + j)
                                coef.append(float(ai * aj))
            seg = self._kinds[key]
            self._seg_groups.append((key, seg, seg.constants(), group, np.array(flat_k, dtype=int),
                                     np.array(flat_l, dtype=int), np.array(coef)))
        self._points = []
        for places, el in mesh.point_places:
            S = el.stiffness(LAM)
            self._points.append((places, _float_places(places), sp.lambdify(LAM, S, "numpy"),
                                 sp.lambdify(LAM, S, "mpmath")))
        self._bodies = [(places, _float_places(places), masses)
                        for places, masses in mesh.body_places]
        self._mp_cache: dict = {}

    def _ensure(self, omega: float):
        if omega > self.omega_design * (1 + 1e-12):
            self.omega_design = 2.0 * omega
            self._build()

    @property
    def point_elements(self) -> list:
        """``(dofs, element)`` per point element, ``dofs`` free indices or None (fixed).

        Only for models whose freedoms are not combinations (no rigid bodies);
        :attr:`mesh` holds the general form.
        """
        return [(_plain_dofs(places), el) for places, el in self.mesh.point_places]

    @property
    def _seg_dofs(self) -> list:
        """Per segment, the free indices of ``(Y0, Theta0, Y1, Theta1)`` or None (fixed).

        Only without rigid bodies (see :attr:`point_elements`).
        """
        return [_plain_dofs(places) for places in self.mesh.segment_places]

    # -- double precision -----------------------------------------------------------
    def matrix(self, omega: float) -> np.ndarray:
        """``K(omega)`` in double precision (dense)."""
        self._ensure(omega)
        return self._matrix(-float(omega) ** 2)

    def _matrix(self, lam2: float) -> np.ndarray:
        """``K`` at ``lam**2 = lam2`` (``-omega**2``; positive: a real, growing ``lam``)."""
        n = self.size
        K = np.zeros(n * n)
        lam2_np = np.array(lam2, dtype=complex)
        for _, seg, consts, _, flat_k, flat_l, coef in self._seg_groups:
            D = segment_stiffness(seg.evaluate_numpy(lam2_np, consts).real).reshape(16)
            np.add.at(K, flat_k, D[flat_l] * coef)
        K = K.reshape(n, n)
        lam = _lam_numpy(lam2)
        for _, places, f_np, _ in self._points:
            _scatter(K, np.real(np.asarray(f_np(lam), dtype=complex)), places)
        for _, places, masses in self._bodies:
            _scatter(K, np.diag([float(m) * lam2 for m in masses]), places)
        return K

    def count(self, omega: float, dps: int | None = None) -> int:
        """Number of natural frequencies below ``omega``, with multiplicity.

        Double precision unless the smallest eigenvalue of ``K`` is too close
        to zero to trust its sign; then (or when ``dps`` is given) the count is
        redone with mpmath at ``dps`` digits (default 30), raising the
        precision until every pivot is clear of zero.
        """
        self._ensure(float(omega))
        return self._count(omega, dps)

    def _count(self, omega, dps=None, sign=-1) -> int:
        """The count at ``lam**2 = sign * omega**2`` (``sign = +1``: a real ``lam``)."""
        self.evaluations += 1
        if dps is None:
            negative = _banded_inertia(self._matrix(sign * float(omega) ** 2), self.bandwidth)
            if negative is not None:
                return negative
            dps = 30
        while True:
            with mpmath.workdps(dps):
                w = omega if isinstance(omega, mpmath.mpf) else mpmath.mpf(omega)
                result = self._count_mp(sign * w * w)
            if result is not None:
                return result
            if dps >= SINGULAR_DPS:
                raise SingularCount(f"K({omega}) is singular to {dps} digits: an eigenvalue")
            dps *= 2

    def unstable_modes(self, rigid: int, omega_ref: float) -> int:
        """Number of eigenvalues with ``omega**2 < 0``: modes buckled by an axial compression.

        ``J`` extends to ``omega**2 < 0`` (``K`` at the real ``lam = w`` counts the
        eigenvalues below ``-w**2``; the segments' clamped-clamped ones all lie
        above zero). Without rigid-body modes this is the count of the static
        ``K(0)``. With ``rigid`` of them (``omega = 0`` exactly), the counts at
        ``omega**2 = -w**2`` and ``+w**2`` must differ by ``rigid`` alone, for a
        ``w`` from ``1e-3 omega_ref`` down, so that no eigenvalue near zero is
        taken for a buckled or a rigid one.

        Examples
        --------
        >>> from symtmm.model import Beam, Model
        >>> pp = Beam("b", 1, 1, 1, left="pinned", right="pinned", N="-25")  # N_cr = pi**2
        >>> StiffnessModel(Model((pp,)), 10.0).unstable_modes(0, 1.0)       # 4 pi**2 > 25
        1
        """
        if rigid == 0:
            try:
                return self._count(mpmath.mpf(0), dps=None)
            except SingularCount:
                pass
        w = 1e-3 * float(omega_ref)
        for _ in range(6):
            try:
                below, above = self._count(w, sign=+1), self.count(w)
            except SingularCount:
                below = above = None
            if below is not None and above - below == rigid:
                return below
            w *= 1e-3
        raise ComputationError("cannot tell whether the axial compression is above a buckling "
                               f"load: eigenvalues with |omega| below {w * 1e3:.3g} rad/s besides "
                               "the rigid-body modes")

    def matrix_mp(self, omega) -> list:
        """``K(omega)`` at the current mpmath precision, as a list of rows."""
        self._ensure(float(omega))
        return self._matrix_mp(-omega * omega)

    def _mp_places(self, places):
        key = (id(places), mpmath.mp.prec)
        out = self._mp_cache.get(key)
        if out is None:
            dps = mpmath.mp.dps
            out = self._mp_cache[key] = tuple(tuple((g, mpmath.mpf(1) if c == 1 else to_mp(c, dps))
                                                    for g, c in combo) for combo in places)
        return out

    def _matrix_mp(self, lam2) -> list:
        n = self.size
        zero = mpmath.mpf(0)
        K = [[zero] * n for _ in range(n)]
        for key, seg, _, group, _, _, _ in self._seg_groups:
            D = segment_stiffness(seg.evaluate_mp(lam2, seg.mp_constants()))
            for places in group:
                _scatter(K, D, self._mp_places(places))
        lam = mpmath.mpc(0, mpmath.sqrt(-lam2)) if lam2 <= 0 else mpmath.sqrt(lam2)
        for places, _, _, f_mp in self._points:
            S = f_mp(lam)
            S = [[mpmath.re(S[i, j]) for j in range(S.cols)] for i in range(S.rows)]
            _scatter(K, S, self._mp_places(places))
        for places, _, masses in self._bodies:
            diag = [to_mp(m, mpmath.mp.dps) * lam2 for m in masses]
            local = [[diag[i] if i == j else zero for j in range(len(diag))]
                     for i in range(len(diag))]
            _scatter(K, local, self._mp_places(places))
        return K

    def _count_mp(self, lam2):
        """Negative pivots of banded LDL^T; None if a pivot is too small to trust.

        Without pivoting, a small pivot makes the entries it updates grow, and
        the rounding errors of every later pivot grow with them: a pivot's sign
        is trusted only if it exceeds ``n`` times the largest entry met so far
        times the working precision (with 10 digits to spare).
        """
        K = self._matrix_mp(lam2)
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


def _float_places(places) -> tuple:
    return tuple(tuple((g, float(c)) for g, c in combo) for combo in places)


def _plain_dofs(places) -> list:
    """Free index or None per local freedom; refuses combinations (rigid bodies)."""
    out = []
    for combo in places:
        if len(combo) > 1 or (combo and combo[0][1] != 1):
            raise NotImplementedError("freedoms of a model with rigid bodies are combinations: "
                                      "use StiffnessModel.mesh")
        out.append(combo[0][0] if combo else None)
    return out


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
