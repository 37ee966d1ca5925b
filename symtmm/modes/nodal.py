"""Deflections along the beams from the dynamic stiffness: double precision at any mode.

The transfer walk of :mod:`symtmm.modes.shapes` carries a state along whole
beams, whose entries grow like ``exp(|s| L)``: high modes lose more digits than
double precision has and are walked in mpmath. The stiffness kernel's pieces are
short (``|s| l <= NU_MAX``, :mod:`symtmm.numeric.plan`), so nothing grows there:

1. a null vector of the scaled ``K(lam)`` (dense singular value decomposition, by
   the symmetric eigensolver for an undamped mode's real ``K``:
   the right singular vectors of the ``m`` smallest singular values, ``m`` the
   multiplicity) gives the deflection and rotation of every node;
2. each piece's end forces follow from its ends, ``f0 = U12**-1 (d1 - U11 d0)``
   (``U12`` of a short piece is the static flexibility's near relative, far from
   singular), and a sample at ``xi`` inside it is the first row of ``U(xi) [d0;
   f0]``.

Every step is backward stable in double precision, whatever the mode. This serves
the sweeps' branch tracking (:func:`symtmm.modes.shapes.displacements`), which
needs the shapes' directions to a few digits; printed mode shapes keep the
mpmath walk, whose digits are counted.

What it covers: models whose segments are single beams in a bending theory
(families ``"eb"`` and ``"theory"``; rods, beams joined by layers and plans with long
pieces, :func:`~symtmm.numeric.plan.long_piece`, walk) and
whose stiffness has at most :data:`DENSE_LIMIT` freedoms; elsewhere, and at an
eigenvalue whose null space the singular values do not separate, it returns
``None`` and the walk does the work.
"""

from __future__ import annotations

import bisect

import numpy as np

from ..expr import exact_float
from ..numeric.arith import DOUBLE
from ..numeric.plan import plan_for
from ..numeric.segments import cut_tables, family_matrices, kind_order, kind_tables
from ..numeric.stiffness import assemble, dense
from ..numeric.threads import one_blas_thread

__all__ = ["DENSE_LIMIT", "nodal_displacements"]

#: Most freedoms of ``K`` whose null vectors are found by a dense decomposition
#: (``O(n**3)``: 300 freedoms cost a few milliseconds per eigenvalue).
DENSE_LIMIT = 300
#: The ``m`` smallest singular values must lie below this fraction of the largest
#: (the eigenvalue is known to the tracking's digits or better) ...
_SINGULAR = 1e-7
#: ... and the next one this many times above them: the null space is separated.
_GAP = 1e3


def _samples(model, plan, points: int):
    """Per beam, per sample ``(segment index, offset in it)`` (floats: a shape's samples
    need no exact coordinates); ``None`` where a sample lies in a piece this module does
    not handle."""
    if plan.long:
        return None         # (a long piece's U grows like its exponentials: the walk)
    mesh = plan.mesh
    by_beam: dict = {}
    for s, (b, _, ia, _) in enumerate(mesh.segments):
        if isinstance(b, tuple) or plan.segment_kinds[s][0] not in ("eb", "theory"):
            return None
        by_beam.setdefault(b, []).append((exact_float(mesh.node_x[ia]), s))
    out = []
    for b, beam in enumerate(model.beams):
        starts = sorted(by_beam.get(b, []))
        xs = [x for x, _ in starts]
        x0, L = float(beam.x0), float(beam.L)
        row = []
        for i in range(points):
            x = x0 + L * i / (points - 1)
            j = max(0, bisect.bisect_right(xs, x) - 1)
            offset = x - xs[j]
            # (a sample on a node, to rounding: the piece's start)
            row.append((starts[j][1], offset if offset > 1e-12 * L else 0.0))
        out.append(row)
    return out


def _null_vectors(A, mult: int, eig=None):
    """The ``(n, mult)`` null space of the dense ``A`` ``(n, n)``, or ``None`` where the
    singular values do not separate it. (Not :func:`~symtmm.numeric.linalg.null_space`:
    its inverse iteration runs in Python in any arithmetic, and it does not say whether
    the null space is separated, which decides here whether the walk takes over.)
    ``eig``: ``A``'s symmetric eigendecomposition where already made (a batch's)."""
    n = A.shape[0]
    if mult > n:
        return None
    if not np.iscomplexobj(A):
        # (real and symmetric, an undamped mode's: the singular values are the moduli of
        # the eigenvalues, and the symmetric eigensolver costs two thirds of the SVD)
        w, V = np.linalg.eigh(A) if eig is None else eig
        order = np.argsort(-np.abs(w), kind="stable")
        s, Vh = np.abs(w)[order], V[:, order].T
    else:
        _, s, Vh = np.linalg.svd(A)
    if not (s[n - mult] <= _SINGULAR * s[0]
            and (mult == n or s[n - mult - 1] >= _GAP * s[n - mult])):
        return None
    return Vh[n - mult:].conj().T


@one_blas_thread
def nodal_displacements(model, eigenvalues, points: int) -> list:
    """``Y`` at ``points`` equally spaced points along every beam, per eigenvalue.

    Parameters
    ----------
    model : Model
        Numeric.
    eigenvalues : sequence of Eigenvalue
        Their ``lam`` and ``multiplicity``.
    points : int
        Samples per beam, both ends included.

    Returns
    -------
    list
        Per eigenvalue ``(multiplicity, beams * points)`` (floats for an undamped model,
        complex otherwise) in the shapes' own scale, or ``None`` where this route does
        not serve (see the module's notes, and an undamped mode of a damped model,
        whose shape the walk gives real).

    Examples
    --------
    The first mode of a pinned-pinned beam is ``sin(pi x / L)``:

    >>> import mpmath
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.results import Eigenvalue
    >>> pp = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    >>> [Y] = nodal_displacements(pp, [Eigenvalue(mpmath.mpc(0, mpmath.pi**2))], 5)
    >>> np.round(Y[0] / Y[0][2], 6) + 0.0
    array([0.      , 0.707107, 1.      , 0.707107, 0.      ])
    """
    model = model.require_numeric()
    out: list = [None] * len(eigenvalues)
    if not eigenvalues:
        return out
    top = max(abs(complex(e.lam)) for e in eigenvalues)
    plan = plan_for(model, top)          # (the solve's own, where it made one)
    if plan.n == 0 or plan.n > DENSE_LIMIT:
        return out
    mesh = plan.mesh
    samples = _samples(model, plan, points)
    if samples is None:
        return out
    real = not model.damped

    # per distinct kind of the pieces holding samples: its full length, then every
    # sample's offset in a piece of that kind (a sample on a piece's start is its d0)
    used = sorted({s for row in samples for s, _ in row})
    # (kinds by number: hashing a kind hashes its exact numbers, once per piece here where
    # the lookups per sample cost a third of the call)
    kinds = sorted({plan.segment_kinds[s] for s in used}, key=kind_order)
    kind_id = {k: j for j, k in enumerate(kinds)}
    piece_kind = {s: kind_id[plan.segment_kinds[s]] for s in used}
    lengths: list = [[] for _ in kinds]
    for s in used:
        if not lengths[piece_kind[s]]:
            lengths[piece_kind[s]].append(exact_float(mesh.segments[s][1].l))
    at: list = [[] for _ in kinds]      # per kind: (sample, index into its lengths)
    flat = [(r, i) for r in range(len(samples)) for i in range(points)]
    for t, (r, i) in enumerate(flat):
        s, xi = samples[r][i]
        if xi != 0:
            k = piece_kind[s]
            at[k].append((t, len(lengths[k])))
            lengths[k].append(float(xi))

    lam = np.array([complex(e.lam) for e in eigenvalues])
    lam2 = lam * lam
    if real:
        lam2 = lam2.real
    with DOUBLE:
        tables = kind_tables(DOUBLE, kinds)
        U = [family_matrices(DOUBLE, [(k[0], cut_tables(DOUBLE, kinds, tables, j,
                                                        np.array(lengths[j])))], lam2)[0]
             for j, k in enumerate(kinds)]                      # (B, lengths, 4, 4)
        K, _ = assemble(plan, DOUBLE, lam2, None if real else lam)
    if real:
        U, K = [u.real for u in U], K.real
    Kd = dense(plan, K)

    # the pieces' end freedoms (Y0, Theta0, Y1, Theta1) from the free ones (mesh numbering)
    gather = np.zeros((len(used), 4, mesh.size))
    for j, s in enumerate(used):
        for a, combo in enumerate(mesh.segment_places[s]):
            for g, c in combo:
                gather[j, a, g] += exact_float(c)
    full = np.stack([U[piece_kind[s]][:, 0] for s in used], axis=1)   # (B, pieces, 4, 4)
    # each sample: its piece, and the first row of U over its offset (e_0 on a piece start)
    place = {s: j for j, s in enumerate(used)}
    owner = np.array([place[samples[r][i][0]] for r, i in flat])
    rows = np.zeros((len(eigenvalues), len(flat), 4), dtype=full.dtype)
    rows[:, :, 0] = 1.0
    for k, pairs in enumerate(at):
        if pairs:
            ts, qs = zip(*pairs)
            rows[:, list(ts)] = U[k][:, list(qs), 0]
    scale = np.array([2.0 ** e for e in plan.exponent])
    position = np.array(plan.position)
    eigs: dict = {}
    finite = [p for p in range(len(eigenvalues))
              if np.isfinite(Kd[p]).all() and np.isfinite(full[p]).all()]
    if real and finite:
        # (every mode's symmetric eigendecomposition in one stacked call: numpy's call
        # cost more than a 28x28 decomposition's work)
        try:
            w, V = np.linalg.eigh(Kd[finite])
            eigs = {p: (w[j], V[j]) for j, p in enumerate(finite)}
        except np.linalg.LinAlgError:
            eigs = {}
    usable = set(finite)
    for p, e in enumerate(eigenvalues):
        if not real and e.lam.real == 0:
            continue        # (an undamped mode of a damped model: its real shape, walked)
        mult = int(e.multiplicity)
        if p not in usable:
            continue
        try:
            basis = _null_vectors(Kd[p], mult, eigs.get(p))
            if basis is None:
                continue
            x = (scale[:, None] * basis)[position]               # (mesh freedoms, mult)
            d = gather @ x                                       # (pieces, 4, mult)
            Ul = full[p]
            f0 = np.linalg.solve(Ul[:, :2, 2:], d[:, 2:] - Ul[:, :2, :2] @ d[:, :2])
        except np.linalg.LinAlgError:       # (no null space found: the walk decides)
            continue
        z0 = np.concatenate([d[:, :2], f0], axis=1)              # (pieces, 4, mult)
        out[p] = np.einsum("sj,sjm->ms", rows[p], z0[owner])
    return out
