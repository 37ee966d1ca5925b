"""The finite-element model a competent user would write instead of symtmm.

Cubic-Hermite Euler–Bernoulli elements (``Y`` and ``Y'`` at the nodes) with
the consistent mass matrix, assembled with :mod:`scipy.sparse`; boundary
conditions remove dofs, joints of beam ends share them (a rigid joint ``Y``
and ``Y'``, a hinge ``Y`` only), springs are added into ``K``; the lowest
frequencies come from :func:`scipy.sparse.linalg.eigsh` in shift-invert mode,
``eigsh(K, k, M=M, sigma=SHIFT, which="LM")`` with a small negative shift
(:data:`SHIFT`): the eigenvalues nearest to it are the lowest, and ``K - sigma M``
is regular even where ``K`` is not (a rigid-body mode: example 1 with both
springs at mid-span turns freely about them).

The mesh is uniform per beam: nodes at the ends, the springs and the joints,
and each interval between them cut into equal elements, their number in
proportion to its length (``round(n l / L)``, at least one) for ``n``
elements per beam; ``refine`` splits every element into that many, so that
meshes are nested for Richardson extrapolation (:func:`converged`).

The input is :class:`FEInput`, plain floats (:func:`fe_input` reads a
:class:`symtmm.model.Model` through its public fields): the timed solve
(:func:`frequencies`) is what the user runs, from numbers to frequencies.
Nothing here calls symtmm's solver.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np
import scipy.sparse
import scipy.sparse.linalg

__all__ = ["FEInput", "fe_input", "frequencies", "converged", "dof_count"]

#: The shift of ``eigsh``, in (rad/s)**2: below zero, small beside the lowest nonzero
#: ``omega**2`` of the models benchmarked (10 to 1000).
SHIFT = -1.0
#: An eigenvalue below this fraction of the largest one returned is a rigid-body mode, 0.
ZERO = 1e-10
#: Local dofs (0 = Y, 1 = Y') each end condition removes.
_FIXED = {"free": (), "clamped": (0, 1), "pinned": (0,), "sliding": (1,)}


@dataclass(frozen=True)
class FEInput:
    """A beam system as plain numbers.

    ``beams``: ``(EI, m, L, x0, left, right)``; ``springs``: ``(a, b, x, k)``
    with beam indices (``b`` None for the ground); ``joints``: ``(ends, hinge)``
    with ``ends`` a tuple of ``(beam, side)``, ``side`` 0 (left) or 1 (right).
    """

    beams: tuple
    springs: tuple = ()
    joints: tuple = ()


def fe_input(model) -> FEInput:
    """The numbers of a :class:`symtmm.model.Model` with beams, springs and joints.

    Joints are the massless rigid bodies of the model whose attachments are beam
    ends at one ``x``, all rigid or all hinged (``[[joint]]`` in a model file).
    Anything else (dashpots, masses, rigid bodies, foundations, axial forces,
    other beam theories) is refused: the elements here are plain Euler–Bernoulli.

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> m = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),),
    ...           (Spring("a", "ground", "1/2", 10),))
    >>> fe_input(m).springs
    ((0, None, 0.5, 10.0),)
    """
    model = model.resolved()
    if model.masses or any(not b.plain or b.kw != 0 for b in model.beams) or \
            any(s.kind != "translational" or s.c != 0 for s in model.springs):
        raise ValueError("the sparse FE model takes plain undamped Euler-Bernoulli beams, "
                         "translational springs and joints")
    index = {b.name: i for i, b in enumerate(model.beams)}
    beams = tuple((float(b.EI), float(b.m), float(b.L), float(b.x0), b.left, b.right)
                  for b in model.beams)
    springs = tuple((index[s.a], None if s.grounded else index[s.b], float(s.x), float(s.k))
                    for s in model.springs)
    joints = []
    for body in model.bodies:
        ends = []
        for a in body.attachments:
            b = model.beams[index[a.beam]]
            side = 0 if a.x == b.x0 else 1 if a.x == b.x1 else None
            if side is None or body.M != 0 or body.J != 0:
                raise ValueError(f"body {body.name!r} is not a joint of beam ends")
            ends.append((index[a.beam], side))
        hinged = {a.hinged for a in body.attachments}
        if len(hinged) != 1:
            raise ValueError(f"joint {body.name!r} mixes rigid and hinged ends")
        joints.append((tuple(ends), hinged.pop()))
    return FEInput(beams, springs, tuple(joints))


def _nodes(model: FEInput, n: int, refine: int) -> list:
    """Node coordinates of every beam (global ``x``)."""
    out = []
    for i, (_, _, L, x0, _, _) in enumerate(model.beams):
        inner = sorted({x for a, b, x, _ in model.springs if i in (a, b)
                        and x0 + 1e-12 * L < x < x0 + L - 1e-12 * L})
        points = [x0, *inner, x0 + L]
        pieces = [np.linspace(a, b, refine * max(1, round(n * (b - a) / L)) + 1)[:-1]
                  for a, b in itertools.pairwise(points)]
        out.append(np.concatenate([*pieces, [x0 + L]]))
    return out


def _numbering(model: FEInput, nodes) -> tuple:
    """``(dof of each beam's node dofs, number of dofs)``; -1 for a removed dof.

    Joints make ends share dofs (union-find on the raw dofs), end conditions remove
    them (a pinned end at a joint pins the joint).
    """
    first = np.cumsum([0] + [2 * len(x) for x in nodes])
    parent = list(range(int(first[-1])))

    def root(d):
        while parent[d] != d:
            parent[d] = parent[parent[d]]
            d = parent[d]
        return d

    def end_dof(beam, side, local):
        return int(first[beam] + (0 if side == 0 else 2 * (len(nodes[beam]) - 1)) + local)

    for ends, hinge in model.joints:
        for local in (0,) if hinge else (0, 1):
            base = root(end_dof(*ends[0], local))
            for end in ends[1:]:
                parent[root(end_dof(*end, local))] = base
    removed = {root(end_dof(i, side, local)) for i, b in enumerate(model.beams)
               for side, bc in ((0, b[4]), (1, b[5])) for local in _FIXED[bc]}
    roots = np.array([root(d) for d in range(len(parent))])
    kept = np.array(sorted(set(roots.tolist()) - removed), dtype=int)
    number = np.full(len(parent), -1)
    number[kept] = np.arange(len(kept))
    dofs = number[roots]
    return [dofs[first[i]:first[i + 1]].reshape(-1, 2) for i in range(len(nodes))], len(kept)


def _element_matrices(EI: float, m: float, h: np.ndarray) -> tuple:
    """Stiffness and consistent mass of cubic-Hermite elements of lengths ``h``, (n, 4, 4)."""
    h = h[:, None, None]
    one = np.ones_like(h)
    K = EI / h**3 * np.block([[12 * one, 6 * h, -12 * one, 6 * h],
                              [6 * h, 4 * h**2, -6 * h, 2 * h**2],
                              [-12 * one, -6 * h, 12 * one, -6 * h],
                              [6 * h, 2 * h**2, -6 * h, 4 * h**2]])
    M = m * h / 420 * np.block([[156 * one, 22 * h, 54 * one, -13 * h],
                                [22 * h, 4 * h**2, 13 * h, -3 * h**2],
                                [54 * one, 13 * h, 156 * one, -22 * h],
                                [-13 * h, -3 * h**2, -22 * h, 4 * h**2]])
    return K, M


def matrices(model: FEInput, n: int, refine: int = 1) -> tuple:
    """Sparse ``(K, M)`` (CSC) of the mesh with ``n`` elements per beam, refined ``refine`` times."""
    nodes = _nodes(model, n, refine)
    dofs, size = _numbering(model, nodes)
    rows, cols, kv, mv = [], [], [], []
    for (EI, m, *_), x, d in zip(model.beams, nodes, dofs):
        Ke, Me = _element_matrices(EI, m, np.diff(x))
        e = np.hstack([d[:-1], d[1:]])                     # (elements, 4) dofs
        rows.append(np.repeat(e, 4, axis=1).ravel())
        cols.append(np.tile(e, (1, 4)).ravel())
        kv.append(Ke.ravel())
        mv.append(Me.ravel())
    for a, b, x, k in model.springs:
        da = dofs[a][int(np.argmin(np.abs(nodes[a] - x))), 0]
        db = -1 if b is None else dofs[b][int(np.argmin(np.abs(nodes[b] - x))), 0]
        pairs = [(da, da, k), (db, db, k), (da, db, -k), (db, da, -k)]
        rows.append(np.array([p[0] for p in pairs]))
        cols.append(np.array([p[1] for p in pairs]))
        kv.append(np.array([p[2] for p in pairs]))
        mv.append(np.zeros(4))
    r, c = np.concatenate(rows), np.concatenate(cols)
    keep = (r >= 0) & (c >= 0)                             # removed dofs drop out
    r, c = r[keep], c[keep]
    K = scipy.sparse.csc_matrix((np.concatenate(kv)[keep], (r, c)), shape=(size, size))
    M = scipy.sparse.csc_matrix((np.concatenate(mv)[keep], (r, c)), shape=(size, size))
    return K, M


def dof_count(model: FEInput, n: int, refine: int = 1) -> int:
    """Number of dofs of the mesh (after boundary conditions and joints)."""
    return _numbering(model, _nodes(model, n, refine))[1]


def frequencies(model: FEInput, n: int, count: int = 10, refine: int = 1) -> np.ndarray:
    """The lowest ``count`` natural frequencies ``omega`` (rad/s): assembly and ``eigsh``.

    Examples
    --------
    Two spans over a middle pin: pinned-pinned spans (``Omega = pi``) and
    pinned-clamped ones (``tan Omega = tanh Omega``, ``Omega = 3.9266``):

    >>> from symtmm.model import Attachment, Beam, Model, RigidBody
    >>> a = Beam("a", 1, 1, 1, left="pinned", right="pinned")
    >>> b = Beam("b", 1, 1, 1, x0=1, left="free", right="pinned")
    >>> pin = RigidBody("pin", (Attachment("a", 1), Attachment("b", 1)))
    >>> w = frequencies(fe_input(Model((a, b), bodies=(pin,))), 20, count=2)
    >>> [round(float(np.sqrt(v)), 4) for v in w]
    [3.1416, 3.9266]
    """
    K, M = matrices(model, n, refine)
    if K.shape[0] <= count + 1:
        raise ValueError(f"{K.shape[0]} dofs: too few for {count} eigenvalues by eigsh")
    values = np.sort(scipy.sparse.linalg.eigsh(K, k=count, M=M, sigma=SHIFT, which="LM",
                                               return_eigenvectors=False))
    return np.sqrt(np.where(values < ZERO * values[-1], 0.0, values))


def converged(model: FEInput, n: int, count: int = 10, levels: int = 4) -> dict:
    """Frequencies extrapolated from ``levels`` nested meshes (``refine = 1, 2, 4, ...``).

    The error of the eigenvalues ``omega**2`` of these elements is a series in even
    powers of the element size from ``h**4`` on; Romberg's scheme removes one term
    per mesh (factors ``2**4``, ``2**6``, ...). Returns ``omega`` (extrapolated),
    ``error`` (relative: the last correction of the scheme), ``raw`` (``omega`` on each
    mesh) and ``rate`` (the observed order of the last three meshes' differences).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> cc = fe_input(Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),)))
    >>> out = converged(cc, 8, count=2)
    >>> exact = [22.3732854481, 61.6728228679]           # (beta L)**2, clamped-clamped
    >>> [abs(float(w) / e - 1) < 1e-10 for w, e in zip(out["omega"], exact)]
    [True, True]

    (Not the digits themselves: ARPACK starts from a random vector, and the last
    digits of the extrapolation, about 1e-11, move with it.)
    """
    raw = np.array([frequencies(model, n, count, refine=2**j) for j in range(levels)]) ** 2
    zero = raw[-1] == 0.0
    column = raw
    for j in range(levels - 1):
        factor = 2.0 ** (4 + 2 * j)
        previous, column = column, (factor * column[1:] - column[:-1]) / (factor - 1.0)
    best = column[-1]
    d1, d2 = raw[-3] - raw[-2], raw[-2] - raw[-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        rate = np.where((d1 > 0) & (d2 > 0), np.log2(d1 / d2), np.nan)
    # relative error of omega = half that of omega**2
    with np.errstate(divide="ignore", invalid="ignore"):
        error = np.where(zero, 0.0, np.abs(best - previous[-1]) / (2 * best))
    return dict(omega=np.sqrt(np.where(zero, 0.0, best)), error=error, raw=np.sqrt(raw),
                rate=rate)
