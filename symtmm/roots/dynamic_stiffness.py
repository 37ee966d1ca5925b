"""``Delta(lam)`` in double precision without cancellation, for complex ``lam``.

The transfer-matrix determinant ``Delta = det R`` cancels about
``sum |s| L / ln 10`` digits (entries of a segment matrix grow like
``exp(|s| l)``, ``s`` the largest wave number: ``beta`` of an Euler–Bernoulli
beam), so double precision cannot follow its phase at high frequencies or
strong damping. The same function can be written as a product of
well-conditioned factors. Cut every beam into short segments with
``|s| l <= NU_MAX = 3`` over the whole region of interest (a bound from the
segment's coefficients, :func:`symtmm.stiffness.wave_number_bound`) and
assemble the exact dynamic stiffness matrix ``K(lam)`` of the structure
(:class:`symtmm.stiffness.Mesh`: segment stiffnesses from the segment transfer
matrices, springs and dashpots ``k + c lam`` and masses added on their
freedoms, boundary conditions and rigid bodies eliminated as constraints).
Then

    Delta(lam) = det K(lam) * prod_s det U12_s(lam) * P

where ``U12_s`` is the upper-right 2x2 block of segment ``s``'s transfer
matrix (it maps end forces to end displacements) and ``P`` the product of the
squared coefficients of the freedoms the constraints eliminated (1 unless a
body is held at two points, :attr:`Mesh.pivot_product`). The factors
``det U12_s`` vanish only at the clamped-clamped natural frequencies of a
segment, ``lam**2 = -omega**2`` real (the clamped-clamped segment is
self-adjoint with a positive mass): for an Euler–Bernoulli segment at
``(beta l)**4 = 500.56...``, well outside ``|beta l|**4 <= 81``; a segment of
another theory is also kept shorter than :meth:`BeamSegment.safe_length` at
``|lam|max**2``, which puts them all beyond ``|lam|max``. ``K`` is well
conditioned away from eigenvalues: rotations enter as ``l Theta`` so that
every entry scales like ``EI / l**3``, and the segments are not shorter than
they need to be. The identity is checked against the transfer-matrix
evaluator in ``tests/test_damped.py`` and, with bodies and beam theories, in
``tests/test_theories_solve.py``.

Values are returned as logarithms, ``(log|Delta|, arg Delta)``, so that
neither the exponential growth nor the size of ``K`` can overflow.
"""

from __future__ import annotations

import math

import numpy as np
import sympy as sp

try:
    from scipy.linalg.lapack import zgbcon as _zgbcon
    from scipy.linalg.lapack import zgbtrf as _zgbtrf
except ImportError:     # scipy is an extra: without it K is factored dense by numpy
    _zgbcon = _zgbtrf = None

from ..elements import EulerBernoulliSegment
from ..elements.base import LAM
from ..model import Model
from ..stiffness import Mesh, wave_number_bound

__all__ = ["NU_MAX", "DynamicStiffness"]

#: Largest ``|s| l`` (``|beta| l``) of a segment anywhere in the region of interest.
NU_MAX = 3.0
#: A value is trusted when ``size * eps * cond(K)``, a bound on the relative error of
#: the determinant, is below this (the error of its phase in radians).
_TRUST = 1e-2

_BC_DOFS_REMOVED = {"free": (), "clamped": (0, 1), "pinned": (0,), "sliding": (1,)}


def _damped_piece(segment, radius: float) -> float:
    """The longest piece of ``segment`` for ``|lam|**2 <= radius``.

    Its largest wave number keeps ``|s| l <= NU_MAX`` everywhere there
    (:func:`symtmm.stiffness.wave_number_bound`), and its clamped-clamped
    natural frequencies lie beyond ``sqrt(radius)``: ``det U12`` has no zero in
    the region (for an Euler–Bernoulli piece, ``NU_MAX < 4.730`` says so).
    """
    s = wave_number_bound(segment, radius)
    length = float(segment.l)
    longest = length if s * length <= NU_MAX else NU_MAX / s
    if not isinstance(segment, EulerBernoulliSegment):
        longest = min(longest, segment.safe_length(radius))
    return longest


def segment_stiffness_batch(U: np.ndarray) -> np.ndarray:
    """Dynamic stiffness (..., 4, 4) of segments from their transfer matrices (..., 4, 4).

    Rows are the end actions ``(Q0, -M0, -Q1, M1)`` conjugate to
    ``(Y0, Theta0, Y1, Theta1)``.

    Examples
    --------
    >>> U = EulerBernoulliSegment(1, 1, 1).evaluate_numpy(np.zeros(1))
    >>> np.round(segment_stiffness_batch(U)[0].real, 12)   # the static beam stiffness
    array([[ 12.,   6., -12.,   6.],
           [  6.,   4.,  -6.,   2.],
           [-12.,  -6.,  12.,  -6.],
           [  6.,   2.,  -6.,   4.]])
    """
    U11, U12, U21, U22 = U[..., :2, :2], U[..., :2, 2:], U[..., 2:, :2], U[..., 2:, 2:]
    det = U12[..., 0, 0] * U12[..., 1, 1] - U12[..., 0, 1] * U12[..., 1, 0]
    inv = np.empty_like(U12)
    inv[..., 0, 0] = U12[..., 1, 1]
    inv[..., 1, 1] = U12[..., 0, 0]
    inv[..., 0, 1] = -U12[..., 0, 1]
    inv[..., 1, 0] = -U12[..., 1, 0]
    inv /= det[..., None, None]
    A = -inv @ U11          # f0 = A d0 + B d1
    C = U21 + U22 @ A       # f1 = C d0 + E d1
    E = U22 @ inv
    f0 = np.concatenate([A, inv], axis=-1)   # rows M0, Q0
    f1 = np.concatenate([C, E], axis=-1)     # rows M1, Q1
    return np.stack([f0[..., 1, :], -f0[..., 0, :], -f1[..., 1, :], f1[..., 0, :]], axis=-2)


class DynamicStiffness:
    """``log Delta(lam)`` of a (possibly damped) model, vectorised, in double precision.

    Parameters
    ----------
    model : Model
        Numeric.
    lam_max : float
        Largest ``|lam|`` at which the function will be evaluated; beams are
        cut so that ``|s| l <= NU_MAX`` there. Larger ``|lam|`` raise
        ``ValueError``.

    Attributes
    ----------
    evaluations : int
        Number of ``lam`` points evaluated.
    size : int
        Order of the dynamic stiffness matrix.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> ds = DynamicStiffness(pp, 200.0)
    >>> logabs, phase, ok = ds.log_delta(np.array([1j * np.pi**2 * (1 + 1e-6), 20j]))
    >>> bool(logabs[0] < logabs[1] - 10) and bool(ok.all())   # near the root (pi)^2
    True
    """

    def __init__(self, model: Model, lam_max: float):
        self.model = model.require_numeric()
        self.lam_max = float(lam_max)
        self.evaluations = 0
        self._build()

    def _build(self):
        radius = self.lam_max ** 2
        mesh = self.mesh = Mesh(self.model, lambda beam, seg: _damped_piece(seg, radius))
        self.size = n = mesh.size
        # l * Theta is a length like Y: with it, all entries of K scale as EI/l^3
        scale = [1.0 if length is None else 1.0 / length for length in mesh.rotation_length]
        self._scale = np.array(scale)
        #: half-bandwidth of K (freedoms are numbered along x, so K is banded)
        self.band = band = mesh.bandwidth
        # LAPACK band storage with room for the fill-in of row interchanges:
        # K[i, j] lives at row 2 band + i - j of column j; stored per point as (n, rows)
        self._rows = rows = 3 * band + 1

        def at(i, j):
            return j * rows + (2 * band + i - j)

        # log det of the scaling S in K_scaled = S K S
        self._log_scale = 2.0 * float(np.sum(np.log(self._scale)))
        # constraints eliminated with a coefficient other than 1 (a body held twice)
        self._log_pivots = math.log(float(mesh.pivot_product))
        # segments grouped by their constants: identical segments are evaluated once; per
        # group, K[targets] += W @ D (D the flattened 4x4 segment stiffness): a freedom that
        # is a combination spreads its entries over several targets
        groups: dict = {}
        for (_, seg, _, _), places in zip(mesh.segments, mesh.segment_places):
            g = groups.setdefault(seg.key, {"seg": seg, "count": 0, "weights": {}})
            g["count"] += 1
            for i, ci in enumerate(places):
                for j, cj in enumerate(places):
                    for gi, ai in ci:
                        for gj, aj in cj:
                            row = g["weights"].setdefault(at(gi, gj), np.zeros(16))
                            row[4 * i + j] += float(ai * aj) * scale[gi] * scale[gj]
        self._groups = []
        for g in groups.values():
            targets = np.array(sorted(g["weights"]), dtype=int)
            W = np.array([g["weights"][t] for t in targets]).reshape(len(targets), 16)
            self._groups.append((g["seg"], g["seg"].constants(), g["count"], targets, W))
        self.segment_count = len(mesh.segments)
        # springs, dashpots, masses, bodies: K0 + c lam + M lam**2, fixed patterns
        pattern_k = np.zeros(n * rows)
        pattern_c = np.zeros(n * rows)
        pattern_m = np.zeros(n * rows)
        local = [(places, el.stiffness(LAM)) for places, el in mesh.point_places]
        local += [(places, sp.diag(*[mass * LAM**2 for mass in masses]))
                  for places, masses in mesh.body_places]
        for places, S in local:
            for i, ci in enumerate(places):
                for j, cj in enumerate(places):
                    coeffs = sp.Poly(sp.expand(S[i, j]), LAM).all_coeffs()[::-1]
                    if len(coeffs) > 3:
                        raise ValueError("point element of degree > 2 in lam")
                    for gi, ai in ci:
                        for gj, aj in cj:
                            sc = float(ai * aj) * scale[gi] * scale[gj]
                            for pattern, cf in zip((pattern_k, pattern_c, pattern_m), coeffs):
                                pattern[at(gi, gj)] += float(cf) * sc
        self._pattern_k = pattern_k
        self._pattern_c = pattern_c
        self._pattern_m = pattern_m
        self._rng = np.random.default_rng(12345)

    # -- evaluation ------------------------------------------------------------------
    def _check(self, lam):
        if lam.size and np.max(np.abs(lam)) > self.lam_max * (1 + 1e-12):
            raise ValueError(f"|lam| = {np.max(np.abs(lam)):.6g} beyond lam_max = {self.lam_max:.6g}")

    def band_matrix(self, lam) -> tuple:
        """``(K in band storage, log prod det U12)`` for an array of ``lam`` (flattened).

        ``K`` is the scaled matrix ``S K S`` (rotations as ``l Theta``), shape
        ``(N, n, 3 band + 1)``: ``[p].T`` is LAPACK's ``ab`` for ``zgbtrf``.
        """
        lam = np.asarray(lam, dtype=complex).reshape(-1)
        self._check(lam)
        N, n = lam.size, self.size
        # assembled entry-major (entries, N): adding rows is fast, columns would not be
        KT = np.empty((n * self._rows, N), dtype=complex)
        KT[:] = self._pattern_k[:, None]
        KT += self._pattern_c[:, None] * lam[None, :]
        if self._pattern_m.any():
            KT += self._pattern_m[:, None] * (lam * lam)[None, :]
        log_u12 = np.zeros(N, dtype=complex)
        lam2 = lam * lam
        for seg, consts, count, targets, W in self._groups:
            U = seg.evaluate_numpy(lam2, consts)
            u12 = U[:, 0, 2] * U[:, 1, 3] - U[:, 0, 3] * U[:, 1, 2]
            log_u12 += count * np.log(u12)
            KT[targets] += W @ segment_stiffness_batch(U).reshape(N, 16).T
        return np.ascontiguousarray(KT.T).reshape(N, n, self._rows), log_u12

    def matrix(self, lam) -> np.ndarray:
        """The scaled ``K`` as dense matrices ``(N, n, n)`` (for checks)."""
        AB, _ = self.band_matrix(lam)
        return self._dense(AB)

    def _dense(self, AB) -> np.ndarray:
        n, b = self.size, self.band
        K = np.zeros((AB.shape[0], n, n), dtype=complex)
        for j in range(n):
            for i in range(max(0, j - b), min(n, j + b + 1)):
                K[:, i, j] = AB[:, j, 2 * b + i - j]
        return K

    def log_delta(self, lam) -> tuple:
        """``(log|Delta|, arg Delta, trusted)`` for an array of ``lam``.

        ``trusted`` is False where ``K`` is too ill-conditioned (``lam`` very
        close to an eigenvalue) for the double-precision determinant to carry
        its phase; the caller should move away or use higher precision.
        """
        lam = np.asarray(lam, dtype=complex)
        shape = lam.shape
        flat = lam.reshape(-1)
        self.evaluations += flat.size
        logabs = np.zeros(flat.size)
        phase = np.zeros(flat.size)
        trusted = np.ones(flat.size, dtype=bool)
        if self.size:
            for start in range(0, flat.size, 256):
                part = slice(start, start + 256)
                logabs[part], phase[part], trusted[part] = self._log_delta(flat[part])
        return logabs.reshape(shape), phase.reshape(shape), trusted.reshape(shape)

    def _log_delta(self, lam):
        AB, log_u12 = self.band_matrix(lam)
        factor = self._banded_log_det if _zgbtrf is not None else self._dense_log_det
        logabs, phase, trusted = factor(AB)
        logabs = logabs - self._log_scale + log_u12.real + self._log_pivots
        phase = np.angle(np.exp(1j * (phase + log_u12.imag)))   # in (-pi, pi]
        return logabs, phase, trusted

    def _banded_log_det(self, AB):
        """``(log|det K|, arg det K, trusted)`` by LAPACK's banded LU and condition estimate."""
        b, n = self.band, self.size
        eps = np.finfo(float).eps
        N = AB.shape[0]
        logabs, phase, trusted = np.empty(N), np.empty(N), np.empty(N, dtype=bool)
        # 1-norm of each K: largest column sum
        anorm = np.abs(AB).sum(axis=2).max(axis=1)
        for p in range(N):
            # banded LU with partial pivoting (LAPACK), then the 1-norm condition estimate
            lu, ipiv, info = _zgbtrf(AB[p].T, b, b)
            diag = lu[2 * b]
            swaps = int(np.count_nonzero(ipiv != np.arange(n)))   # (0-based pivots)
            if info > 0 or not np.all(np.isfinite(diag)):
                logabs[p], phase[p], trusted[p] = -np.inf, 0.0, False
                continue
            logabs[p] = float(np.sum(np.log(np.abs(diag))))
            phase[p] = float(np.sum(np.angle(diag))) + np.pi * swaps
            rcond, _ = _zgbcon(b, b, lu, ipiv, anorm[p])
            # the relative error of det(K) is about n eps cond(K)
            trusted[p] = rcond > 0 and n * eps / rcond < _TRUST
        return logabs, phase, trusted

    def _dense_log_det(self, AB):
        """``(log|det K|, arg det K, trusted)`` by numpy's dense LU, where scipy is absent.

        The same quantities as the banded LAPACK path, at ``O(n**3)`` instead of
        ``O(n b**2)`` per point; the 1-norm condition number is computed exactly.
        """
        K = self._dense(AB)
        sign, logabs = np.linalg.slogdet(K)
        with np.errstate(all="ignore"):
            cond = np.linalg.cond(K, 1)
        eps = np.finfo(float).eps
        trusted = (sign != 0) & np.isfinite(cond) & (self.size * eps * cond < _TRUST)
        return np.where(sign != 0, logabs, -np.inf), np.angle(sign), trusted

    def delta(self, lam) -> np.ndarray:
        """``Delta(lam)`` itself (may overflow for large models; prefer :meth:`log_delta`)."""
        logabs, phase, _ = self.log_delta(lam)
        return np.exp(logabs + 1j * phase)
