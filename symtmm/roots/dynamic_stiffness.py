"""``Delta(lam)`` in double precision without cancellation, for complex ``lam``.

The transfer-matrix determinant ``Delta = det R`` cancels about
``sum |beta| L / ln 10`` digits (entries of a segment matrix grow like
``exp(|beta| l)``), so double precision cannot follow its phase at high
frequencies or strong damping. The same function can be written as a product
of well-conditioned factors. Cut every beam into short segments with
``|beta| l <= NU_MAX = 3`` over the whole region of interest and assemble the
exact dynamic stiffness matrix ``K(lam)`` of the structure (segment
stiffnesses from the segment transfer matrices, springs and dashpots
``k + c lam`` added on the displacement freedoms, boundary freedoms removed).
Then

    Delta(lam) = det K(lam) * prod_s det U12_s(lam)

where ``U12_s`` is the upper-right 2x2 block of segment ``s``'s transfer
matrix (it maps end forces to end displacements). The factors ``det U12_s``
vanish only at the clamped-clamped natural frequencies of a segment,
``(beta l)**4 = 500.56...`` (real and positive: the clamped-clamped segment
is self-adjoint), well outside ``|beta l|**4 <= 81``. ``K`` is well
conditioned away from eigenvalues: rotations enter as ``l Theta`` so that
every entry scales like ``EI / l**3``, and the segments are not shorter
than they need to be. The identity is checked against the
transfer-matrix evaluator in ``tests/test_damped.py``.

Values are returned as logarithms, ``(log|Delta|, arg Delta)``, so that
neither the exponential growth nor the size of ``K`` can overflow.
"""

from __future__ import annotations

import itertools
import math

import numpy as np
import sympy as sp
from scipy.linalg.lapack import zgbcon as _zgbcon
from scipy.linalg.lapack import zgbtrf as _zgbtrf

from ..assembly import point_elements
from ..elements import EulerBernoulliSegment
from ..elements.base import LAM
from ..model import Model

__all__ = ["NU_MAX", "DynamicStiffness"]

#: Largest ``|beta| l`` of a segment anywhere in the region of interest.
NU_MAX = 3.0
#: A value is trusted when ``size * eps * cond(K)``, a bound on the relative error of
#: the determinant, is below this (the error of its phase in radians).
_TRUST = 1e-2

_BC_DOFS_REMOVED = {"free": (), "clamped": (0, 1), "pinned": (0,), "sliding": (1,)}


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
        cut so that ``|beta| l <= NU_MAX`` there. Larger ``|lam|`` raise
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
        beams = self.model.beams
        points_el = point_elements(self.model)
        nodes = []          # (x float, beam index)
        node_len = []       # a length scale for the rotation freedom of each node
        segments = []       # (segment, left node, right node)
        beam_nodes = []
        for b_idx, beam in enumerate(beams):
            required = [beam.x0, beam.x1] + [x for x, el in points_el if beam.name in el.beams]
            xs = sorted({sp.nsimplify(x) for x in required}, key=float)
            # |beta|**4 <= (m |lam|**2 + kw) / EI: a foundation enters the bound
            mu = ((float(beam.m) * self.lam_max**2 + float(beam.kw)) / float(beam.EI)) ** 0.25
            points = [xs[0]]
            for xa, xb in itertools.pairwise(xs):
                n_sub = max(1, math.ceil(mu * float(xb - xa) / NU_MAX))
                points += [xa + (xb - xa) * sp.Rational(k, n_sub) for k in range(1, n_sub + 1)]
            ids = []
            for x in points:
                ids.append(len(nodes))
                nodes.append((float(x), b_idx))
                node_len.append(0.0)
            beam_nodes.append(dict(zip(points, ids)))
            for (xa, ia), (xb, ib) in zip(zip(points, ids), zip(points[1:], ids[1:])):
                seg = EulerBernoulliSegment(beam.EI, beam.m, xb - xa, beam.kw)
                segments.append((seg, ia, ib))
                for i in (ia, ib):
                    node_len[i] = max(node_len[i], float(xb - xa))
        removed: dict = {}
        for b_idx, beam in enumerate(beams):
            ends = sorted(beam_nodes[b_idx], key=float)
            removed.setdefault(beam_nodes[b_idx][ends[0]], set()).update(
                _BC_DOFS_REMOVED[beam.left])
            removed.setdefault(beam_nodes[b_idx][ends[-1]], set()).update(
                _BC_DOFS_REMOVED[beam.right])
        # banded numbering: by x, then by beam
        order = sorted(range(len(nodes)), key=lambda i: nodes[i])
        dof, scale = {}, []
        for node in order:
            for k in (0, 1):
                if k not in removed.get(node, ()):
                    dof[(node, k)] = len(scale)
                    # l * Theta is a length like Y: with it, all entries of K scale as EI/l^3
                    scale.append(1.0 if k == 0 else 1.0 / (node_len[node] or 1.0))
        self.size = n = len(scale)
        self._scale = np.array(scale)
        pairs = []
        for seg, ia, ib in segments:
            d = [dof.get((ia, 0)), dof.get((ia, 1)), dof.get((ib, 0)), dof.get((ib, 1))]
            pairs += [abs(a - b) for a in d for b in d if a is not None and b is not None]
        index = {b.name: i for i, b in enumerate(beams)}
        # point elements: S(lam) = K0 + lam C + lam**2 M on their freedoms
        point_places = []
        for x, el in points_el:
            x = sp.nsimplify(x)
            ds = [dof.get((beam_nodes[index[el.beams[lv]]][x], 0 if var == "Y" else 1))
                  for lv, var in el.dofs]
            live = [d for d in ds if d is not None]
            pairs += [abs(a - b) for a in live for b in live]
            point_places.append((ds, el.stiffness(LAM)))
        #: half-bandwidth of K (dofs are numbered along x, so K is banded)
        self.band = band = max(pairs, default=0)
        # LAPACK band storage with room for the fill-in of row interchanges:
        # K[i, j] lives at row 2 band + i - j of column j; stored per point as (n, rows)
        self._rows = rows = 3 * band + 1

        def at(i, j):
            return j * rows + (2 * band + i - j)

        # log det of the scaling S in K_scaled = S K S
        self._log_scale = 2.0 * float(np.sum(np.log(self._scale)))
        # segments grouped by their constants: identical segments are evaluated once
        groups: dict = {}
        for seg, ia, ib in segments:
            key = seg.key
            dofs = [dof.get((ia, 0)), dof.get((ia, 1)), dof.get((ib, 0)), dof.get((ib, 1))]
            local = [i for i, d in enumerate(dofs) if d is not None]
            flat_k = [at(dofs[i], dofs[j]) for i in local for j in local]
            flat_l = [4 * i + j for i in local for j in local]
            sc = np.array([scale[dofs[i]] * scale[dofs[j]] for i in local for j in local])
            g = groups.setdefault(key, {"seg": seg, "places": []})
            g["places"].append((np.array(flat_k), np.array(flat_l), sc))
        self._groups = []
        for key, g in groups.items():
            consts = tuple(float(v) for v in key)
            self._groups.append((g["seg"], consts, g["places"]))
        self.segment_count = len(segments)
        # springs, dashpots, masses: K0 + c lam + M lam**2, fixed patterns on their freedoms
        pattern_k = np.zeros(n * rows)
        pattern_c = np.zeros(n * rows)
        pattern_m = np.zeros(n * rows)
        for ds, S in point_places:
            for i, di in enumerate(ds):
                for j, dj in enumerate(ds):
                    if di is None or dj is None:
                        continue
                    coeffs = sp.Poly(sp.expand(S[i, j]), LAM).all_coeffs()[::-1]
                    if len(coeffs) > 3:
                        raise ValueError("point element of degree > 2 in lam")
                    sc = scale[di] * scale[dj]
                    for pattern, cf in zip((pattern_k, pattern_c, pattern_m), coeffs):
                        pattern[at(di, dj)] += float(cf) * sc
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
        for seg, consts, places in self._groups:
            U = seg.evaluate_numpy(lam2, consts)
            u12 = U[:, 0, 2] * U[:, 1, 3] - U[:, 0, 3] * U[:, 1, 2]
            log_u12 += len(places) * np.log(u12)
            DT = segment_stiffness_batch(U).reshape(N, 16).T
            for flat_k, flat_l, sc in places:
                KT[flat_k] += DT[flat_l] * sc[:, None]
        return np.ascontiguousarray(KT.T).reshape(N, n, self._rows), log_u12

    def matrix(self, lam) -> np.ndarray:
        """The scaled ``K`` as dense matrices ``(N, n, n)`` (for checks)."""
        AB, _ = self.band_matrix(lam)
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
        b, n = self.band, self.size
        eps = np.finfo(float).eps
        logabs = np.empty(lam.size)
        phase = np.empty(lam.size)
        trusted = np.empty(lam.size, dtype=bool)
        # 1-norm of each K: largest column sum
        anorm = np.abs(AB).sum(axis=2).max(axis=1)
        for p in range(lam.size):
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
        logabs = logabs - self._log_scale + log_u12.real
        phase = np.angle(np.exp(1j * (phase + log_u12.imag)))   # in (-pi, pi]
        return logabs, phase, trusted

    def delta(self, lam) -> np.ndarray:
        """``Delta(lam)`` itself (may overflow for large models; prefer :meth:`log_delta`)."""
        logabs, phase, _ = self.log_delta(lam)
        return np.exp(logabs + 1j * phase)
