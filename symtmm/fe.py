"""Cubic-Hermite finite-element model of parallel beams joined by springs.

This module is an independent reference for the exact solver: it shares no
code with the rest of :mod:`symtmm` and depends only on numpy and scipy, so
that agreement between the two is meaningful evidence of correctness.

The system is a set of parallel Euler--Bernoulli beams, each described by a
dict with keys ``name``, ``EI``, ``m`` (mass per unit length), ``L``, ``x0``
(global coordinate of the left end), ``left`` and ``right`` (boundary
conditions ``"free"``, ``"clamped"``, ``"pinned"`` or ``"sliding"``).  Linear
springs act on the transverse displacement and are dicts with keys
``between`` (a pair of beam names, one of which may be ``"ground"``), ``x``
(global coordinate) and ``k``; an optional dashpot ``c`` must be zero because
the model is undamped.

Each beam is discretised with standard two-node Hermite elements (dofs
``Y`` and ``Y'`` at every node) and consistent mass matrices, so computed
frequencies converge from above at rate ``h**4``.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np
import scipy.linalg

__all__ = ["fe_frequencies", "fe_matrices"]

GROUND = "ground"

# Which local dofs (0 = Y, 1 = Y') each boundary condition removes.
_CONSTRAINED_DOFS = {
    "free": (),
    "clamped": (0, 1),
    "pinned": (0,),
    "sliding": (1,),
}

# Relative tolerance used to decide whether a spring lies on a beam and
# whether two mesh points coincide; it absorbs rounding in user coordinates
# such as ``x0 + L`` without merging genuinely distinct positions.
_POSITION_RTOL = 1e-9

# Eigenvalues below this multiple of (machine epsilon * largest stiffness to
# mass ratio) are indistinguishable from rounding noise and are reported as
# exact zeros (rigid-body modes).
_ZERO_EIGENVALUE_FACTOR = 100.0


# ---------------------------------------------------------------------------
# Input validation
# ---------------------------------------------------------------------------

def _positive_float(value, what):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(number) or number <= 0.0:
        raise ValueError(f"{what} must be finite and positive, got {value!r}")
    return number


def _finite_float(value, what):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{what} must be finite, got {value!r}")
    return number


def _require_keys(item, keys, what):
    if not isinstance(item, Mapping):
        raise ValueError(f"{what} must be a dict, got {type(item).__name__}")
    missing = [key for key in keys if key not in item]
    if missing:
        raise ValueError(f"{what} is missing key(s) {', '.join(map(repr, missing))}")


def _boundary_condition(value, what):
    if not isinstance(value, str) or value.lower() not in _CONSTRAINED_DOFS:
        allowed = ", ".join(map(repr, _CONSTRAINED_DOFS))
        raise ValueError(
            f"unknown boundary condition {value!r} for {what}; expected one of {allowed}"
        )
    return value.lower()


def _normalise_beams(beams):
    """Validate beam dicts and return their properties as floats, keyed by name."""
    if isinstance(beams, Mapping) or not isinstance(beams, Sequence) or not beams:
        raise ValueError("beams must be a non-empty list of beam dicts")
    parsed = {}
    for index, beam in enumerate(beams):
        what = f"beam #{index}"
        _require_keys(beam, ("name", "EI", "m", "L", "x0", "left", "right"), what)
        name = beam["name"]
        if not isinstance(name, str) or not name:
            raise ValueError(f"{what} must have a non-empty string name, got {name!r}")
        what = f"beam {name!r}"
        if name == GROUND:
            raise ValueError(f"{GROUND!r} is reserved for springs to ground and cannot name a beam")
        if name in parsed:
            raise ValueError(f"duplicate beam name {name!r}")
        parsed[name] = {
            "EI": _positive_float(beam["EI"], f"EI of {what}"),
            "m": _positive_float(beam["m"], f"m of {what}"),
            "L": _positive_float(beam["L"], f"L of {what}"),
            "x0": _finite_float(beam["x0"], f"x0 of {what}"),
            "left": _boundary_condition(beam["left"], f"the left end of {what}"),
            "right": _boundary_condition(beam["right"], f"the right end of {what}"),
        }
    return parsed


def _position_tolerance(beam):
    return _POSITION_RTOL * max(beam["L"], abs(beam["x0"]), abs(beam["x0"] + beam["L"]))


def _check_on_beam(x, name, beam, what):
    tol = _position_tolerance(beam)
    left, right = beam["x0"], beam["x0"] + beam["L"]
    if not left - tol <= x <= right + tol:
        raise ValueError(
            f"{what} at x={x!r} lies outside beam {name!r}, which spans [{left!r}, {right!r}]"
        )


def _normalise_springs(springs, beams):
    """Validate spring dicts and return (name_a, name_b_or_None, x, k) tuples."""
    if springs is None:
        return []
    if isinstance(springs, Mapping) or not isinstance(springs, Sequence):
        raise ValueError("springs must be a list of spring dicts")
    parsed = []
    for index, spring in enumerate(springs):
        what = f"spring #{index}"
        _require_keys(spring, ("between", "x", "k"), what)
        pair = spring["between"]
        if isinstance(pair, str) or not isinstance(pair, Sequence) or len(pair) != 2:
            raise ValueError(f"'between' of {what} must be a pair of names, got {pair!r}")
        name_a, name_b = pair
        if name_a == GROUND:
            # A ground spring is symmetric; accept the ground on either side.
            name_a, name_b = name_b, name_a
        for name in (name_a, name_b):
            if name != GROUND and name not in beams:
                raise ValueError(f"{what} refers to unknown beam name {name!r}")
        if name_a == GROUND:
            raise ValueError(f"{what} connects ground to ground")
        if name_a == name_b:
            raise ValueError(f"{what} connects beam {name_a!r} to itself")
        x = _finite_float(spring["x"], f"x of {what}")
        k = _finite_float(spring["k"], f"k of {what}")
        if k < 0.0:
            raise ValueError(f"k of {what} must be non-negative, got {spring['k']!r}")
        c = _finite_float(spring.get("c", 0.0) or 0.0, f"c of {what}")
        if c != 0.0:
            raise ValueError(f"{what} has a dashpot c={spring['c']!r}; the FE model is undamped")
        for name in (name_a, name_b):
            if name != GROUND:
                _check_on_beam(x, name, beams[name], what)
        parsed.append((name_a, None if name_b == GROUND else name_b, x, k))
    return parsed


def _check_elements_per_beam(elements_per_beam):
    if isinstance(elements_per_beam, bool) or not isinstance(elements_per_beam, (int, np.integer)):
        raise ValueError(f"elements_per_beam must be an integer, got {elements_per_beam!r}")
    if elements_per_beam < 1:
        raise ValueError(f"elements_per_beam must be at least 1, got {elements_per_beam!r}")
    return int(elements_per_beam)


# ---------------------------------------------------------------------------
# Mesh
# ---------------------------------------------------------------------------

def _required_points(beam, spring_positions):
    """Sorted beam ends and spring positions, merging near-duplicates."""
    left, right = beam["x0"], beam["x0"] + beam["L"]
    tol = _position_tolerance(beam)
    # Snap to the ends so that rounding never creates a sliver element there.
    inner = [x for x in spring_positions if left + tol < x < right - tol]
    points = [left]
    for x in sorted(inner):
        if x - points[-1] > tol:
            points.append(x)
    points.append(right)
    return np.array(points)


def _beam_nodes(beam, spring_positions, elements_per_beam):
    """Node coordinates: required points plus equal subdivisions in between."""
    points = _required_points(beam, spring_positions)
    pieces = []
    for start, stop in itertools.pairwise(points):
        # Share the element budget in proportion to length so the mesh stays
        # roughly uniform whatever the spring layout.
        count = max(1, round(elements_per_beam * (stop - start) / beam["L"]))
        pieces.append(np.linspace(start, stop, count + 1)[:-1])
    pieces.append(points[-1:])
    return np.concatenate(pieces)


def _nearest_node(nodes, x):
    return int(np.argmin(np.abs(nodes - x)))


# ---------------------------------------------------------------------------
# Element matrices and assembly
# ---------------------------------------------------------------------------

def _element_stiffness(EI, lengths):
    """Hermite beam stiffness for each element length, shape (n, 4, 4)."""
    l = lengths[:, None, None]
    base = np.array([
        [12.0, 6.0, -12.0, 6.0],
        [6.0, 4.0, -6.0, 2.0],
        [-12.0, -6.0, 12.0, -6.0],
        [6.0, 2.0, -6.0, 4.0],
    ])
    # Rows/columns of rotation dofs carry one extra power of l each.
    power = np.array([0, 1, 0, 1])
    return EI / l**3 * base * l ** (power[:, None] + power[None, :])


def _element_mass(m, lengths):
    """Consistent Hermite beam mass for each element length, shape (n, 4, 4)."""
    l = lengths[:, None, None]
    base = np.array([
        [156.0, 22.0, 54.0, -13.0],
        [22.0, 4.0, 13.0, -3.0],
        [54.0, 13.0, 156.0, -22.0],
        [-13.0, -3.0, -22.0, 4.0],
    ])
    power = np.array([0, 1, 0, 1])
    return m * l / 420.0 * base * l ** (power[:, None] + power[None, :])


def _assemble_beam(K, M, beam, nodes, first_dof):
    lengths = np.diff(nodes)
    element_dofs = first_dof + 2 * np.arange(len(lengths))[:, None] + np.arange(4)[None, :]
    rows = np.repeat(element_dofs, 4, axis=1)
    cols = np.tile(element_dofs, (1, 4))
    np.add.at(K, (rows, cols), _element_stiffness(beam["EI"], lengths).reshape(len(lengths), 16))
    np.add.at(M, (rows, cols), _element_mass(beam["m"], lengths).reshape(len(lengths), 16))


def _add_spring(K, dof_a, dof_b, k):
    K[dof_a, dof_a] += k
    if dof_b is not None:
        K[dof_b, dof_b] += k
        K[dof_a, dof_b] -= k
        K[dof_b, dof_a] -= k


def _constrained_dofs(beam, first_dof, n_nodes):
    last_node_dof = first_dof + 2 * (n_nodes - 1)
    dofs = [first_dof + local for local in _CONSTRAINED_DOFS[beam["left"]]]
    dofs += [last_node_dof + local for local in _CONSTRAINED_DOFS[beam["right"]]]
    return dofs


def _build(beams, springs, elements_per_beam):
    """Validate input, mesh, assemble and eliminate constrained dofs.

    Returns ``(K, M, dof_info, energy_terms)``; ``energy_terms`` lists the
    beam elements and springs in reduced dof numbering so that strain energy
    can be evaluated without forming ``K`` (see :func:`_strain_energy`).
    """
    beams = _normalise_beams(beams)
    springs = _normalise_springs(springs, beams)
    elements_per_beam = _check_elements_per_beam(elements_per_beam)

    nodes = {}
    first_dof = {}
    total = 0
    for name, beam in beams.items():
        positions = [x for a, b, x, _ in springs if name in (a, b)]
        nodes[name] = _beam_nodes(beam, positions, elements_per_beam)
        first_dof[name] = total
        total += 2 * len(nodes[name])

    K = np.zeros((total, total))
    M = np.zeros((total, total))
    constrained = []
    for name, beam in beams.items():
        _assemble_beam(K, M, beam, nodes[name], first_dof[name])
        constrained += _constrained_dofs(beam, first_dof[name], len(nodes[name]))

    def displacement_dof(name, x):
        return first_dof[name] + 2 * _nearest_node(nodes[name], x)

    spring_dofs = []
    for name_a, name_b, x, k in springs:
        dof_a = displacement_dof(name_a, x)
        dof_b = None if name_b is None else displacement_dof(name_b, x)
        _add_spring(K, dof_a, dof_b, k)
        spring_dofs.append((dof_a, dof_b, k))

    # Constraints are homogeneous, so eliminating rows/columns is exact.
    keep = np.ones(total, dtype=bool)
    keep[constrained] = False
    new_index = np.full(total, -1)
    new_index[keep] = np.arange(int(keep.sum()))
    dofs = {
        name: new_index[first_dof[name] : first_dof[name] + 2 * len(nodes[name])].reshape(-1, 2)
        for name in beams
    }
    K = K[np.ix_(keep, keep)]
    M = M[np.ix_(keep, keep)]
    info = {"nodes": nodes, "dofs": dofs, "n_dofs": int(keep.sum())}
    energy_terms = {
        "beams": [(beam["EI"], np.diff(nodes[name]), dofs[name]) for name, beam in beams.items()],
        "springs": [
            (new_index[a], -1 if b is None else new_index[b], k) for a, b, k in spring_dofs
        ],
    }
    return K, M, info, energy_terms


# ---------------------------------------------------------------------------
# Eigenvalues
# ---------------------------------------------------------------------------

def _nodal_values(vectors, dofs):
    """Gather nodal values of each column of `vectors`; removed dofs are 0."""
    padded = np.vstack([vectors, np.zeros((1, vectors.shape[1]))])
    # Index -1 selects the appended zero row, i.e. a constrained dof.
    return padded[dofs[:, 0]], padded[dofs[:, 1]]


def _strain_energy(energy_terms, vectors):
    """Twice the strain energy, ``v.T K v``, of each column without using K.

    For smooth modes on a fine mesh ``K v`` suffers cancellation of order
    ``h**-4``; writing the element energy in terms of the rotations relative
    to the chord slope keeps every term non-negative and the result accurate.
    """
    energy = np.zeros(vectors.shape[1])
    for EI, lengths, dofs in energy_terms["beams"]:
        Y, T = _nodal_values(vectors, dofs)
        chord = (Y[1:] - Y[:-1]) / lengths[:, None]
        u1, u2 = T[:-1] - chord, T[1:] - chord
        # EI * integral of the (linear) curvature squared over a Hermite element.
        energy += np.sum(4.0 * EI / lengths[:, None] * (u1 * u1 + u1 * u2 + u2 * u2), axis=0)
    padded = np.vstack([vectors, np.zeros((1, vectors.shape[1]))])
    for dof_a, dof_b, k in energy_terms["springs"]:
        stretch = padded[dof_a] - padded[dof_b]
        energy += k * stretch * stretch
    return energy


def _zero_threshold(K, M):
    """Eigenvalue magnitude below which rounding noise dominates."""
    ratio = np.max(np.abs(np.diag(K)) / np.diag(M)) if K.size else 0.0
    return _ZERO_EIGENVALUE_FACTOR * np.finfo(float).eps * ratio


def _refined_eigenvalues(K, M, energy_terms, subset):
    """Eigenvalues ``omega**2`` with rigid-body modes exactly zero.

    The dense solver's absolute error is about ``eps * largest eigenvalue``,
    which swamps the lowest modes of a fine mesh.  The Rayleigh quotient of
    each computed eigenvector, with the energy evaluated accurately, has only
    second-order error in the eigenvector and restores the lowest modes.
    """
    eigenvalues, vectors = scipy.linalg.eigh(K, M, subset_by_index=subset)
    rigid = eigenvalues < _zero_threshold(K, M)
    mass = np.einsum("ij,ij->j", vectors, M @ vectors)
    quotients = _strain_energy(energy_terms, vectors) / mass
    return np.sort(np.where(rigid, 0.0, quotients))


# ---------------------------------------------------------------------------
# Public API
# ---------------------------------------------------------------------------

def fe_matrices(beams, springs, elements_per_beam):
    """Assemble the finite-element stiffness and mass matrices.

    Parameters
    ----------
    beams : list of dict
        Beams with keys ``name``, ``EI``, ``m``, ``L``, ``x0``, ``left`` and
        ``right``; boundary conditions are ``"free"``, ``"clamped"``
        (``Y = Y' = 0``), ``"pinned"`` (``Y = 0``) or ``"sliding"``
        (``Y' = 0``).
    springs : list of dict or None
        Springs with keys ``between`` (pair of beam names, either may be
        ``"ground"``), ``x`` (global coordinate on every connected beam,
        possibly at a beam end) and ``k`` (stiffness, non-negative).  An
        optional ``c`` must be zero; other keys are ignored.
    elements_per_beam : int
        Approximate number of elements per beam.  Every beam gets nodes at
        its ends and at each of its spring positions; the intervals in
        between are split into equal elements, their number proportional to
        the interval length and at least one.

    Returns
    -------
    K, M : numpy.ndarray
        Dense symmetric stiffness and mass matrices of the constrained
        system, shape ``(n, n)``.  ``M`` is positive definite; ``K`` is
        positive semi-definite.
    dof_info : dict
        ``"nodes"`` maps each beam name to its node coordinates (global
        ``x``); ``"dofs"`` maps each beam name to an integer array of shape
        ``(n_nodes, 2)`` giving the row of ``K``/``M`` holding ``Y`` and
        ``Y'`` at each node, or ``-1`` where a boundary condition removed the
        dof; ``"n_dofs"`` is ``n``.

    Raises
    ------
    ValueError
        On malformed beams or springs, an unknown boundary condition or beam
        name, a spring outside a beam it connects, or a non-zero dashpot.

    Examples
    --------
    >>> from symtmm.fe import fe_matrices
    >>> beam = dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned")
    >>> K, M, info = fe_matrices([beam], [], 4)
    >>> K.shape, info["n_dofs"]
    ((8, 8), 8)
    >>> info["dofs"]["a"][0].tolist()  # Y removed at the pinned left end
    [-1, 0]
    """
    K, M, info, _ = _build(beams, springs, elements_per_beam)
    return K, M, info


def fe_frequencies(beams, springs, elements_per_beam, count=None):
    """Natural circular frequencies of the finite-element model.

    Parameters
    ----------
    beams, springs, elements_per_beam
        As for :func:`fe_matrices`.
    count : int, optional
        Number of lowest frequencies to return; all of them by default.

    Returns
    -------
    numpy.ndarray
        Natural circular frequencies ``omega`` (rad/s) in ascending order.
        Rigid-body modes appear as exact zeros: eigenvalues ``omega**2``
        that are negative or within rounding noise of zero are set to 0.

    Raises
    ------
    ValueError
        On invalid input (see :func:`fe_matrices`) or if ``count`` is not an
        integer between 1 and the number of degrees of freedom.

    Notes
    -----
    The generalized problem ``K v = omega**2 M v`` is solved densely with
    :func:`scipy.linalg.eigh`, which is practical up to a few thousand
    degrees of freedom.  With consistent mass the frequencies converge from
    above with error ``O(h**4)`` in the element size ``h``.

    The dense solver alone loses the lowest modes of fine meshes to rounding
    (absolute error about ``eps`` times the largest eigenvalue, which grows
    like ``h**-4``).  Each returned ``omega**2`` is therefore the Rayleigh
    quotient of its computed eigenvector, with the strain energy summed
    element by element in a cancellation-free form; this keeps the
    ``h**4`` convergence visible down to relative errors near ``1e-12``.
    Eigenvalues within the solver's noise floor (about ``1e-14`` times the
    largest diagonal ratio ``K_ii / M_ii``) are reported as rigid-body zeros,
    so a genuinely non-zero but that tiny ``omega**2`` also reads as 0.

    Examples
    --------
    A pinned-pinned beam with ``EI = m = L = 1`` has ``omega_n = (n pi)**2``:

    >>> import numpy as np
    >>> from symtmm.fe import fe_frequencies
    >>> beam = dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned")
    >>> omega = fe_frequencies([beam], [], 20, count=3)
    >>> print(np.round(omega / np.pi**2, 3))
    [1. 4. 9.]

    A free-free beam has two rigid-body modes:

    >>> free = dict(beam, left="free", right="free")
    >>> print(np.round(fe_frequencies([free], [], 20, count=3), 2))
    [ 0.    0.   22.37]
    """
    K, M, info, energy_terms = _build(beams, springs, elements_per_beam)
    n = info["n_dofs"]
    if count is None:
        subset = None
    else:
        if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
            raise ValueError(f"count must be an integer, got {count!r}")
        if not 1 <= count <= n:
            raise ValueError(f"count must be between 1 and the number of dofs ({n}), got {count!r}")
        subset = (0, int(count) - 1)
    if n == 0:
        return np.zeros(0)
    return np.sqrt(_refined_eigenvalues(K, M, energy_terms, subset))
