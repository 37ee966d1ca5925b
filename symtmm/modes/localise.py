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

__all__ = ["localising_rotation"]


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
