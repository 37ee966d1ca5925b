"""A basis for the shapes of a multiple eigenvalue that shows the physics.

The shapes of an eigenvalue of multiplicity ``m`` span a space; any mass-orthonormal
basis of it is as right as another, and the one a null space gives mixes every
beam into every shape (three uncoupled beams at a triple root, each shape moving
all three). This module picks the basis that concentrates each shape's kinetic
energy on as few parts as possible (beams, and the inertia of rigid bodies): with
``E_p`` the ``m x m`` matrix of the kinetic energy on part ``p`` in a
mass-orthonormal basis (``sum_p E_p = I``), the rotation ``Q`` maximising

    sum_p sum_i ((Q^T E_p Q)_ii)**2,

a joint diagonalisation of the ``E_p`` by Jacobi rotations (Cardoso and Souloumiac,
SIAM J. Matrix Anal. Appl. 17, 1996), in the spirit of the localised orbitals of
quantum chemistry. Where the space has a basis of shapes each on one part, that is
the basis found; the shapes come ordered by the part they move most.

Examples
--------
Two parts each holding one of two mixed shapes are pulled apart:

>>> import numpy as np
>>> c = np.sqrt(0.5)
>>> E1, E2 = np.array([[0.5, 0.5], [0.5, 0.5]]), np.array([[0.5, -0.5], [-0.5, 0.5]])
>>> Q = localising_rotation([E1, E2])
>>> np.round([np.diag(Q.T @ E @ Q) for E in (E1, E2)], 12) + 0.0
array([[1., 0.],
       [0., 1.]])
"""

from __future__ import annotations

import numpy as np

from ..numeric.threads import one_blas_thread

__all__ = ["localising_rotation", "pivoted_basis"]


def _off(parts, p: int, q: int) -> float:
    """``sum_parts E_pq**2``: what a rotation in the plane (p, q) trades for diagonal."""
    return float(sum(E[p, q] ** 2 for E in parts))


@one_blas_thread
def localising_rotation(parts, sweeps: int = 50, tol: float = 1e-15) -> np.ndarray:
    """The orthogonal ``Q`` (floats) that jointly diagonalises the symmetric ``parts``.

    Parameters
    ----------
    parts : list of numpy.ndarray
        ``m x m`` symmetric matrices (the energy of each part in an orthonormal basis).
    sweeps : int
        Most Jacobi sweeps over all pairs.
    tol : float
        A rotation by less than this (in ``sin``) ends the search.

    Returns
    -------
    numpy.ndarray
        ``Q``, columns ordered by the part each one's energy is largest on.
    """
    A = [np.array(E, dtype=float) for E in parts]
    m = A[0].shape[0] if A else 0
    Q = np.eye(m)
    for _ in range(sweeps):
        largest = 0.0
        for p in range(m - 1):
            for q in range(p + 1, m):
                # the angle maximising sum (E_pp**2 + E_qq**2): the leading eigenvector of
                # sum h h^T, h = (E_pp - E_qq, 2 E_pq), gives (cos 2t, sin 2t)
                h = np.array([[E[p, p] - E[q, q], 2 * E[p, q]] for E in A])
                w, v = np.linalg.eigh(h.T @ h)
                x, y = v[:, np.argmax(w)]
                if x < 0:
                    x, y = -x, -y
                c = np.sqrt((1 + x) / 2)
                s = y / (2 * c) if c > 0 else 1.0
                if abs(s) <= tol:
                    continue
                # (the convention's sign, checked on what the rotation must shrink: the
                # pair's off-diagonal energy, which stays resolved when it is tiny)
                best, chosen = _off(A, p, q), None
                for sign in (1, -1):
                    R = np.eye(m)
                    R[p, p], R[q, q], R[p, q], R[q, p] = c, c, -sign * s, sign * s
                    trial = [R.T @ E @ R for E in A]
                    if _off(trial, p, q) < best:
                        best, chosen = _off(trial, p, q), (R, trial)
                if chosen is None:
                    continue
                largest = max(largest, abs(s))
                R, A = chosen
                Q = Q @ R
        if largest <= tol:
            break
    # each shape after the part it moves most (then by how much): a stable order
    weights = np.array([np.diag(E) for E in A]) if A else np.zeros((0, m))
    order = sorted(range(m), key=lambda i: (int(np.argmax(weights[:, i])),
                                            -float(np.max(weights[:, i]))))
    return Q[:, order]


def pivoted_basis(Y, tie: float = 1e-9):
    """``P`` (``m x m``, complex) whose basis ``Y @ P`` has each shape equal to 1 at a
    sample of its own and 0 at the other shapes' (``Y``: ``(samples, m)``, the
    displacements of any basis of the space), or None where ``Y`` does not tell ``m``
    directions apart.

    The damped counterpart of :func:`localising_rotation`: complex shapes have no
    mass-orthonormal basis to rotate, and a null space's basis is whatever its
    iteration and rounding left. The samples are chosen greedily, each the one of
    largest residual displacement once the chosen ones are projected out (the first
    within ``tie`` of it, as the sign and phase of a shape are chosen: ties between
    symmetric peaks would otherwise go to rounding). Shapes that each move one beam
    (three equal uncoupled beams) come out so, and the basis no longer depends on the
    null space's start.

    Examples
    --------
    >>> import numpy as np
    >>> Y = np.array([[1, 1], [1, -1], [0.5, 0.5]], dtype=complex)   # (a + b), (a - b)
    >>> P = pivoted_basis(Y)
    >>> np.round(Y @ P, 12) + 0.0
    array([[1. +0.j, 0. +0.j],
           [0. +0.j, 1. +0.j],
           [0.5+0.j, 0. +0.j]])
    """
    Y = np.asarray(Y, dtype=complex)
    m = Y.shape[1]
    residual = Y.copy()
    pivots: list = []
    first = None
    for _ in range(m):
        size = np.linalg.norm(residual, axis=1)
        top = float(size.max()) if size.size else 0.0
        if first is None:
            first = top
        if not top > 1e-8 * first:
            return None
        i = int(np.argmax(size >= top * (1 - tie)))
        q = residual[i] / size[i]
        residual = residual - np.outer(residual @ q.conj(), q)
        pivots.append(i)
    return np.linalg.inv(Y[pivots, :])
