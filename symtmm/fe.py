"""Finite-element model of beam systems: an independent reference for the exact solver.

This module shares no code with the rest of :mod:`symtmm` and depends only on
numpy and scipy, so that agreement between the two is meaningful evidence of
correctness. Its input is plain dicts.

Beams
    Dicts with keys ``name``, ``EI``, ``m`` (mass per unit length), ``L``,
    ``x0`` (global coordinate of the left end), ``left`` and ``right``
    (boundary conditions ``"free"``, ``"clamped"``, ``"pinned"`` or
    ``"sliding"``), and optionally ``kw`` (Winkler foundation), ``N`` (axial
    force, tension positive), ``rhoI`` (rotary inertia per unit length) and
    ``kGA`` (shear stiffness; absent or None for a beam rigid in shear). The
    energy per unit length is the one of :mod:`symtmm.elements.theories`::

        strain   (EI psi'**2 + kGA (Y' - psi)**2 + N Y'**2 + kw Y**2) / 2
        kinetic  (m Y_t**2 + rhoI psi_t**2) / 2

    with ``psi = Y'`` when ``kGA`` is None. Each node carries ``Y`` and
    ``Theta`` (``Y'``, or ``psi`` for a shear-flexible beam).
Rods
    Dicts with ``"rod": True`` and keys ``name``, ``EA`` (axial stiffness),
    ``m``, ``L``, ``x0``, ``left`` and ``right``, and optionally ``kw`` (an
    axial foundation) and ``GJ`` and ``rhoIp`` (torsional stiffness and polar
    inertia per unit length, both or neither: without them the rod has no
    torsion). The axial displacement ``u`` and the twist ``phi`` are
    independent, with the energy per unit length::

        strain   (EA u'**2 + kw u**2 + GJ phi'**2) / 2
        kinetic  (m u_t**2 + rhoIp phi_t**2) / 2

    Each node carries ``u`` and ``phi`` in the slots of ``Y`` and ``Theta``, so a
    translational spring, a mass's ``M`` and a body act axially, a rotational
    spring and a mass's ``J`` in torsion. Ends are ``"fixed"`` (``u = phi =
    0``) or ``"free"``, with torsion also ``"fixed-axial"`` (``u = 0``, free to
    twist) and ``"fixed-torsion"`` (``phi = 0``, free to move axially). Beam
    keys (``EI``, ``N``, ``rhoI``, ``kGA``) are refused on a rod.
Springs
    Dicts with keys ``between`` (a pair of beam names, one of which may be
    ``"ground"``), ``x`` (global coordinate) and ``k``; ``kind`` is
    ``"translational"`` (default, on ``Y``) or ``"rotational"`` (on
    ``Theta``), on rods also ``"axial"`` (translational) or ``"torsional"``
    (rotational); an optional dashpot ``c`` must be zero (the model is undamped).
    A spring joins two beams or two rods (a beam to a rod is refused: the
    deflection and the axial motion are not along one line).
Masses
    Dicts with keys ``beam``, ``x``, ``M`` and optionally ``J`` (rotary
    inertia acting on ``Theta``; on a rod the polar inertia, which needs torsion).
Rigid bodies
    Dicts with keys ``attach`` (a list of dicts ``{"beam", "x", "hinged", "k"}``,
    ``hinged`` optional and False by default; with ``k`` a spring joins the beam
    to the body's point there instead: a sprung mass) and optionally ``name``, ``M``,
    ``J`` (about the centre of mass) and ``xc`` (the centre of mass, default
    the first attachment's ``x``). The body moves as ``Y(x) = Y_c + (x - xc)
    Theta_c``; at each attachment the beam's ``Y`` is the body's, and so is its
    ``Theta`` unless the attachment is hinged. A joint of beam ends (a tree, a
    closed loop) is a massless body whose attachments share one ``x``.
    A body on rods joins rods only and moves along them without turning (every
    attachment hinged or elastic and at ``xc``, ``J = 0``: an oscillator or a hinge
    joint of rod ends); each rod's ``u`` there is the body's ``Y_c``.
Layers
    Dicts with keys ``between`` (a pair of distinct beam names, not rods and not
    ``"ground"``: a foundation under one beam is its ``kw``) and ``k`` (stiffness
    per unit length), optionally ``x0`` and ``x1`` (the global interval of the
    layer, by default the overlap of the two beams); an optional damping ``c``
    must be zero (the model is undamped). The strain energy per unit length
    over ``[x0, x1]`` is ``k (Y_a - Y_b)**2 / 2``. Both beams get nodes at the
    layer's ends and the same element boundaries inside it (every point
    required on one is required on the other, and the intervals between are
    split alike), so the layer's element matrix ``k int (N_a - N_b)^T (N_a -
    N_b) dx`` (``N`` the shape functions of ``Y``) is exact:
    ``[[Kf, -Kf], [-Kf, Kf]]`` with ``Kf`` the Winkler foundation matrix of the
    element.

Elements
    Rigid in shear, cubic Hermite elements (``Y`` and ``Y'`` at the nodes).
    Shear-flexible, two-node mixed elements with ``Y`` cubic and ``psi``
    quadratic: the nodal ``Y, psi`` interpolated linearly plus three internal
    bubble dofs per element; they contain every static solution (condensed,
    the stiffness is the exact Timoshenko one) and the shear strain ``Y' -
    psi`` can vanish, so they do not lock. (The interdependent interpolation
    element, four dofs with ``Y' - psi`` constant per element, converges only
    as ``h**2`` in frequency.) Element matrices integrate the energy exactly
    (4-point Gauss), so axial force gives the consistent geometric stiffness and
    ``rhoI`` the consistent rotary-inertia matrix. Both are conforming
    Rayleigh-Ritz models: the frequencies are upper bounds (also under
    compression) and converge as ``h**4``; :func:`fe_converged` extrapolates.
    Dofs without mass (``psi`` where ``rhoI = 0``) are condensed statically.
    Rods, cubic hierarchical bar elements for ``u`` and for ``phi``: the nodal
    values interpolated linearly plus two internal bubble dofs per element and
    motion, ``xi (1 - xi)`` and ``xi (1 - xi)(1 - 2 xi)`` (the space of the
    four-node Lagrange element), consistent mass and foundation, integrated
    exactly. Conforming too, the frequencies are upper bounds and converge as
    ``h**6`` (``2 p`` for elements of degree ``p = 3``); a rod without torsion has
    no twist dofs (its nodal ``phi`` are constrained to zero).

Constraints
    Boundary conditions and the bodies' attachments are homogeneous linear
    constraints ``C u = 0`` on the nodal dofs and the bodies' ``Y_c,
    Theta_c``; the model is reduced to a basis of their null space (master-slave
    elimination): dofs not named by any constraint are kept as they are, dofs a
    support fixes (a constraint on one dof) are dropped, the others are replaced
    by an orthonormal basis of the constraints' null space among them.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Mapping, Sequence

import numpy as np
import scipy.linalg

__all__ = ["fe_frequencies", "fe_matrices", "fe_dashpots", "fe_converged"]

GROUND = "ground"

# Which local dofs (0 = Y, 1 = Theta) each boundary condition removes.
_CONSTRAINED_DOFS = {
    "free": (),
    "clamped": (0, 1),
    "pinned": (0,),
    "sliding": (1,),
}

# The same for the ends of a rod (0 = u, 1 = phi); without torsion only "fixed", "free".
_ROD_CONSTRAINED_DOFS = {
    "fixed": (0, 1),
    "free": (),
    "fixed-axial": (0,),
    "fixed-torsion": (1,),
}
_ROD_ENDS_AXIAL = ("fixed", "free")

# Keys of a beam that a rod does not have (a rod's are EA, GJ, rhoIp).
_BEAM_ONLY_KEYS = ("EI", "N", "rhoI", "kGA")

_SPRING_KINDS = {"translational": 0, "rotational": 1}
# On rods the kinds also go by their model-file names.
_ROD_SPRING_KINDS = {"axial": 0, "torsional": 1}

# Relative tolerance used to decide whether a point lies on a beam and
# whether two mesh points coincide; it absorbs rounding in user coordinates
# such as ``x0 + L`` without merging genuinely distinct positions.
_POSITION_RTOL = 1e-9

# Eigenvalues below this multiple of (machine epsilon * largest stiffness to
# mass ratio) are indistinguishable from rounding noise and are reported as
# exact zeros (rigid-body modes).
_ZERO_EIGENVALUE_FACTOR = 100.0

# 4-point Gauss-Legendre integrates polynomials of degree 7 exactly: Y**2 is of degree 6.
_GAUSS_X, _GAUSS_W = np.polynomial.legendre.leggauss(4)


# ---------------------------------------------------------------------------
# Input validation
# ---------------------------------------------------------------------------

def _number(value, what):
    try:
        number = float(value)
    except (TypeError, ValueError):
        raise ValueError(f"{what} must be a number, got {value!r}") from None
    if not math.isfinite(number):
        raise ValueError(f"{what} must be finite, got {value!r}")
    return number


def _positive_float(value, what):
    number = _number(value, what)
    if number <= 0.0:
        raise ValueError(f"{what} must be finite and positive, got {value!r}")
    return number


def _nonnegative_float(value, what):
    number = _number(value, what)
    if number < 0.0:
        raise ValueError(f"{what} must be non-negative, got {value!r}")
    return number



def _require_keys(item, keys, what):
    if not isinstance(item, Mapping):
        raise ValueError(f"{what} must be a dict, got {type(item).__name__}")
    missing = [key for key in keys if key not in item]
    if missing:
        raise ValueError(f"{what} is missing key(s) {', '.join(map(repr, missing))}")


def _list_of(items, what):
    if items is None:
        return []
    if isinstance(items, (Mapping, str)) or not isinstance(items, Sequence):
        raise ValueError(f"{what} must be a list of dicts")
    return list(items)


def _boundary_condition(value, what):
    if not isinstance(value, str) or value.lower() not in _CONSTRAINED_DOFS:
        allowed = ", ".join(map(repr, _CONSTRAINED_DOFS))
        raise ValueError(
            f"unknown boundary condition {value!r} for {what}; expected one of {allowed}"
        )
    return value.lower()


def _rod_end(value, what, torsion):
    allowed = tuple(_ROD_CONSTRAINED_DOFS) if torsion else _ROD_ENDS_AXIAL
    if not isinstance(value, str) or value.lower() not in allowed:
        raise ValueError(
            f"unknown rod end {value!r} for {what}; expected one of "
            f"{', '.join(map(repr, allowed))}"
            + ("" if torsion else " (the others need torsion: GJ and rhoIp)")
        )
    return value.lower()


def _normalise_rod(rod, what):
    """Validate a rod dict (``"rod": True``) and return its properties as floats."""
    _require_keys(rod, ("EA", "m", "L", "x0", "left", "right"), what)
    extra = [key for key in _BEAM_ONLY_KEYS if rod.get(key) is not None]
    if extra:
        raise ValueError(f"{what} is a rod: it has EA, GJ and rhoIp, not "
                         f"{', '.join(map(repr, extra))}")
    GJ, rhoIp = rod.get("GJ"), rod.get("rhoIp")
    if (GJ is None) != (rhoIp is None):
        raise ValueError(f"torsion of {what} needs both GJ and rhoIp")
    torsion = GJ is not None
    return {
        "rod": True,
        "torsion": torsion,
        "EA": _positive_float(rod["EA"], f"EA of {what}"),
        "m": _positive_float(rod["m"], f"m of {what}"),
        "L": _positive_float(rod["L"], f"L of {what}"),
        "x0": _number(rod["x0"], f"x0 of {what}"),
        "left": _rod_end(rod["left"], f"the left end of {what}", torsion),
        "right": _rod_end(rod["right"], f"the right end of {what}", torsion),
        "kw": _nonnegative_float(rod.get("kw", 0.0) or 0.0, f"kw of {what}"),
        "GJ": _positive_float(GJ, f"GJ of {what}") if torsion else 0.0,
        "rhoIp": _positive_float(rhoIp, f"rhoIp of {what}") if torsion else 0.0,
    }


def _normalise_beams(beams):
    """Validate beam and rod dicts and return their properties as floats, keyed by name."""
    if isinstance(beams, Mapping) or not isinstance(beams, Sequence) or not beams:
        raise ValueError("beams must be a non-empty list of beam dicts")
    parsed = {}
    for index, beam in enumerate(beams):
        what = f"beam #{index}"
        _require_keys(beam, ("name",), what)
        is_rod = beam.get("rod", False)
        if not isinstance(is_rod, (bool, np.bool_)):
            raise ValueError(f"'rod' of {what} must be True or False, got {is_rod!r}")
        name = beam["name"]
        if not isinstance(name, str) or not name:
            raise ValueError(f"{what} must have a non-empty string name, got {name!r}")
        what = f"{'rod' if is_rod else 'beam'} {name!r}"
        if name == GROUND:
            raise ValueError(f"{GROUND!r} is reserved for springs to ground and cannot name a beam")
        if name in parsed:
            raise ValueError(f"duplicate beam name {name!r}")
        if is_rod:
            parsed[name] = _normalise_rod(beam, what)
            continue
        _require_keys(beam, ("EI", "m", "L", "x0", "left", "right"), what)
        EI = _positive_float(beam["EI"], f"EI of {what}")
        kGA = beam.get("kGA")
        kGA = None if kGA is None else _positive_float(kGA, f"kGA of {what}")
        N = _number(beam.get("N", 0.0) or 0.0, f"N of {what}")
        if kGA is not None and kGA + N <= 0.0:
            raise ValueError(f"N of {what}: the compression must stay below kGA (kGA + N > 0)")
        parsed[name] = {
            "rod": False,
            "EI": EI,
            "m": _positive_float(beam["m"], f"m of {what}"),
            "L": _positive_float(beam["L"], f"L of {what}"),
            "x0": _number(beam["x0"], f"x0 of {what}"),
            "left": _boundary_condition(beam["left"], f"the left end of {what}"),
            "right": _boundary_condition(beam["right"], f"the right end of {what}"),
            "kw": _nonnegative_float(beam.get("kw", 0.0) or 0.0, f"kw of {what}"),
            "N": N,
            "rhoI": _nonnegative_float(beam.get("rhoI", 0.0) or 0.0, f"rhoI of {what}"),
            # shear flexibility EI/kGA: 0 for a beam rigid in shear (psi = Y')
            "g": 0.0 if kGA is None else EI / kGA,
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


def _known_beam(name, beams, what):
    if not isinstance(name, str) or name not in beams:
        raise ValueError(f"{what} refers to unknown beam name {name!r}")
    return name


def _normalise_springs(springs, beams):
    """Validate spring dicts and return (name_a, name_b_or_None, x, k, dof) tuples."""
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
            if name != GROUND:
                _known_beam(name, beams, what)
        if name_a == GROUND:
            raise ValueError(f"{what} connects ground to ground")
        if name_a == name_b:
            raise ValueError(f"{what} connects beam {name_a!r} to itself")
        x = _number(spring["x"], f"x of {what}")
        k = _nonnegative_float(spring["k"], f"k of {what}")
        c = _number(spring.get("c", 0.0) or 0.0, f"c of {what}")
        if c != 0.0:
            raise ValueError(f"{what} has a dashpot c={spring['c']!r}; the FE model is undamped")
        members = [beams[name] for name in (name_a, name_b) if name != GROUND]
        rods = {member["rod"] for member in members}
        if len(rods) > 1:
            raise ValueError(f"{what} joins a beam to a rod: a spring joins two beams or two "
                             "rods (a beam's deflection and a rod's axial motion are not "
                             "along one line)")
        on_rods = rods == {True}
        kinds = _SPRING_KINDS | (_ROD_SPRING_KINDS if on_rods else {})
        kind = spring.get("kind", "translational")
        if not isinstance(kind, str) or kind not in kinds:
            raise ValueError(f"kind of {what} must be one of {', '.join(map(repr, kinds))}, "
                             f"got {kind!r}")
        if on_rods and kinds[kind] == 1:
            _require_torsion((name_a, name_b), beams, f"{what} acts in torsion")
        for name in (name_a, name_b):
            if name != GROUND:
                _check_on_beam(x, name, beams[name], what)
        parsed.append((name_a, None if name_b == GROUND else name_b, x, k, kinds[kind]))
    return parsed


def _require_torsion(names, beams, what):
    """Refuse a torsional element on a rod without torsion (it has no twist dofs)."""
    for name in names:
        if name != GROUND and beams[name]["rod"] and not beams[name]["torsion"]:
            raise ValueError(f"{what}, and rod {name!r} has no torsion (give it GJ and rhoIp)")


def _normalise_masses(masses, beams):
    """Validate mass dicts and return (beam, x, M, J) tuples."""
    parsed = []
    for index, mass in enumerate(_list_of(masses, "masses")):
        what = f"mass #{index}"
        _require_keys(mass, ("beam", "x", "M"), what)
        name = _known_beam(mass["beam"], beams, what)
        x = _number(mass["x"], f"x of {what}")
        _check_on_beam(x, name, beams[name], what)
        J = _nonnegative_float(mass.get("J", 0.0) or 0.0, f"J of {what}")
        if J != 0.0:
            _require_torsion((name,), beams, f"J of {what} is a polar inertia on a rod")
        parsed.append((name, x, _nonnegative_float(mass["M"], f"M of {what}"), J))
    return parsed


def _normalise_bodies(bodies, beams):
    """Validate body dicts: ``{"attach": [(beam, x, hinged)], "M", "J", "xc", "rotates"}``."""
    parsed = []
    for index, body in enumerate(_list_of(bodies, "bodies")):
        what = f"body #{index}"
        _require_keys(body, ("attach",), what)
        what = f"body {body.get('name', index)!r}"
        raw = body["attach"]
        if isinstance(raw, (Mapping, str)) or not isinstance(raw, Sequence) or not raw:
            raise ValueError(f"'attach' of {what} must be a non-empty list of dicts")
        attach = []
        for point in raw:
            _require_keys(point, ("beam", "x"), f"an attachment of {what}")
            name = _known_beam(point["beam"], beams, f"an attachment of {what}")
            x = _number(point["x"], f"x of an attachment of {what}")
            _check_on_beam(x, name, beams[name], f"an attachment of {what}")
            hinged = point.get("hinged", False)
            if not isinstance(hinged, (bool, np.bool_)):
                raise ValueError(f"'hinged' of an attachment of {what} must be True or False")
            k = point.get("k")
            if k is not None:
                k = _nonnegative_float(k, f"k of an attachment of {what}")
                if _nonnegative_float(point.get("c", 0.0) or 0.0, "c") != 0.0:
                    raise ValueError(f"c of an attachment of {what} must be zero (the finite-"
                                     "element model is undamped)")
            if any(n == name and abs(x - x2) <= _position_tolerance(beams[name])
                   for n, x2, _, _ in attach):
                raise ValueError(f"{what} is attached twice to beam {name!r} at x={x!r}")
            attach.append((name, x, bool(hinged) and k is None, k))
        M = _nonnegative_float(body.get("M", 0.0) or 0.0, f"M of {what}")
        J = _nonnegative_float(body.get("J", 0.0) or 0.0, f"J of {what}")
        xc = body.get("xc")
        xc = attach[0][1] if xc is None else _number(xc, f"xc of {what}")
        # The rotation is a dof of its own unless nothing feels or fixes it (a pin joint).
        rotates = J != 0.0 or any((not h and k is None) or x != xc for _, x, h, k in attach)
        rods = {beams[name]["rod"] for name, _, _, _ in attach}
        if True in rods and (len(rods) > 1 or rotates):
            # a turning body moves the points of a beam by its lever arms; along a rod every
            # point of it moves alike
            raise ValueError(f"{what} is on rods: it must join rods only and move along them "
                             "without turning (every attachment hinged or elastic, at xc, "
                             "and J = 0)")
        parsed.append({"attach": attach, "M": M, "J": J, "xc": xc, "rotates": rotates,
                       "what": what})
    return parsed


def _normalise_layers(layers, beams):
    """Validate layer dicts and return (name_a, name_b, x0, x1, k) tuples."""
    parsed = []
    for index, layer in enumerate(_list_of(layers, "layers")):
        what = f"layer #{index}"
        _require_keys(layer, ("between", "k"), what)
        pair = layer["between"]
        if isinstance(pair, str) or not isinstance(pair, Sequence) or len(pair) != 2:
            raise ValueError(f"'between' of {what} must be a pair of names, got {pair!r}")
        if GROUND in pair:
            raise ValueError(f"{what} must join two beams, not {GROUND!r} (a foundation "
                             "under one beam is its kw)")
        name_a, name_b = (_known_beam(name, beams, what) for name in pair)
        if name_a == name_b:
            raise ValueError(f"{what} connects beam {name_a!r} to itself")
        for name in (name_a, name_b):
            if beams[name]["rod"]:
                raise ValueError(f"{what} must join two beams, and {name!r} is a rod")
        k = _nonnegative_float(layer["k"], f"k of {what}")
        c = _number(layer.get("c", 0.0) or 0.0, f"c of {what}")
        if c != 0.0:
            raise ValueError(f"{what} has a damping c={layer['c']!r}; the FE model is undamped")
        a, b = beams[name_a], beams[name_b]
        x0, x1 = layer.get("x0"), layer.get("x1")
        x0 = max(a["x0"], b["x0"]) if x0 is None else _number(x0, f"x0 of {what}")
        x1 = (min(a["x0"] + a["L"], b["x0"] + b["L"]) if x1 is None
              else _number(x1, f"x1 of {what}"))
        for name in (name_a, name_b):
            _check_on_beam(x0, name, beams[name], f"the start of {what}")
            _check_on_beam(x1, name, beams[name], f"the end of {what}")
        if x1 - x0 <= max(_position_tolerance(a), _position_tolerance(b)):
            raise ValueError(f"{what} needs x0 < x1, got x0={x0!r}, x1={x1!r} (by default "
                             "the overlap of the two beams)")
        parsed.append((name_a, name_b, x0, x1, k))
    return parsed


def _check_positive_int(value, what):
    if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
        raise ValueError(f"{what} must be an integer, got {value!r}")
    if value < 1:
        raise ValueError(f"{what} must be at least 1, got {value!r}")
    return int(value)


# ---------------------------------------------------------------------------
# Mesh
# ---------------------------------------------------------------------------

def _required_points(beam, positions):
    """Sorted beam ends and required positions, merging near-duplicates."""
    left, right = beam["x0"], beam["x0"] + beam["L"]
    tol = _position_tolerance(beam)
    # Snap to the ends so that rounding never creates a sliver element there.
    inner = [x for x in positions if left + tol < x < right - tol]
    points = [left]
    for x in sorted(inner):
        if x - points[-1] > tol:
            points.append(x)
    points.append(right)
    return np.array(points)


def _interval_counts(beam, points, elements_per_beam):
    """Elements of the base mesh between consecutive required points.

    The element budget is shared in proportion to length so the mesh stays
    roughly uniform whatever the layout of the points; at least one each.
    """
    return [max(1, round(elements_per_beam * (stop - start) / beam["L"]))
            for start, stop in itertools.pairwise(points)]


def _subdivide(points, counts, refine):
    """Node coordinates: ``points`` plus ``refine * count`` equal elements between each two.

    ``refine`` splits every element of the base mesh into that many equal ones,
    so meshes ``refine = 1, 2, 4`` are nested and their element sizes halve
    exactly (Richardson extrapolation needs that).
    """
    pieces = [np.linspace(start, stop, refine * count + 1)[:-1]
              for (start, stop), count in zip(itertools.pairwise(points), counts)]
    pieces.append(points[-1:])
    return np.concatenate(pieces)


def _layer_tolerance(beams, a, b):
    return max(_position_tolerance(beams[a]), _position_tolerance(beams[b]))


def _layer_span(points, x0, x1, tol):
    """Indices of the first and the last of ``points`` in ``[x0, x1]`` (the layer's ends)."""
    inside = np.flatnonzero((points >= x0 - tol) & (points <= x1 + tol))
    return int(inside[0]), int(inside[-1])


def _meshes(beams, positions, layers, elements_per_beam, refine):
    """Node coordinates of every beam, the elements of the beams of each layer aligned.

    Each beam has nodes at its ends and the ``positions`` (merged when closer than
    the position tolerance), the intervals between split into equal elements
    (:func:`_interval_counts`, :func:`_subdivide`). A layer's ends are
    required points of both its beams, and so is, inside the layer, every point
    required on either (repeated until nothing changes: layers chain); the
    intervals between those points, the same on both beams, get the larger of the
    two beams' element counts. Inside a layer both beams then have the same nodes.
    """
    positions = {name: list(positions[name]) for name in beams}
    for a, b, x0, x1, _ in layers:
        positions[a] += [x0, x1]
        positions[b] += [x0, x1]
    points = {name: _required_points(beams[name], positions[name]) for name in beams}
    changed = bool(layers)
    while changed:                   # the point sets only grow: this ends
        changed = False
        for a, b, x0, x1, _ in layers:
            tol = _layer_tolerance(beams, a, b)
            for source, target in ((a, b), (b, a)):
                inside = [x for x in points[source] if x0 - tol <= x <= x1 + tol]
                more = _required_points(beams[target], list(points[target]) + inside)
                if len(more) > len(points[target]):
                    points[target], changed = more, True
    counts = {name: _interval_counts(beams[name], points[name], elements_per_beam)
              for name in beams}
    pairs = []                       # (beam a, interval index, beam b, interval index)
    for a, b, x0, x1, _ in layers:
        tol = _layer_tolerance(beams, a, b)
        (i0, i1), (j0, j1) = (_layer_span(points[n], x0, x1, tol) for n in (a, b))
        if i1 - i0 != j1 - j0 or np.any(np.abs(points[a][i0:i1 + 1] - points[b][j0:j1 + 1])
                                        > tol):
            raise ValueError(f"the meshes of beams {a!r} and {b!r} cannot be aligned under "
                             f"their layer on [{x0!r}, {x1!r}]: points closer together than "
                             "the position tolerance")
        pairs += [(a, i, b, j) for i, j in zip(range(i0, i1), range(j0, j1))]
    changed = True
    while changed:                   # the counts only grow, to the largest: this ends
        changed = False
        for a, i, b, j in pairs:
            count = max(counts[a][i], counts[b][j])
            if counts[a][i] != count or counts[b][j] != count:
                counts[a][i] = counts[b][j] = count
                changed = True
    return {name: _subdivide(points[name], counts[name], refine) for name in beams}


def _nearest_node(nodes, x):
    return int(np.argmin(np.abs(nodes - x)))


# ---------------------------------------------------------------------------
# The elements: cubic Hermite (rigid in shear), cubic/quadratic mixed (Timoshenko),
# cubic hierarchical bars (rods)
# ---------------------------------------------------------------------------

def _element_dofs(beam):
    """Local dofs of an element: 4 nodal ones, plus 3 internal ones when shear-flexible;
    on a rod 2 internal ones for ``u`` and, with torsion, 2 for ``phi``."""
    if beam["rod"]:
        return 8 if beam["torsion"] else 6
    return 4 if beam["g"] == 0.0 else 7


def _bar(start, stop, bubbles, l, xi):
    """A cubic bar field and its derivative: the linear interpolation of the nodal values
    ``start``, ``stop`` plus the hierarchical bubbles ``xi (1 - xi)`` and ``xi (1 - xi)(1 - 2
    xi)`` with the amplitudes ``bubbles`` (none: linear)."""
    value = start + (stop - start) * xi
    slope = (stop - start) / l
    if bubbles:
        b2, b3 = bubbles
        bubble = xi * (1.0 - xi)
        value = value + b2 * bubble + b3 * bubble * (1.0 - 2.0 * xi)
        slope = slope + (b2 * (1.0 - 2.0 * xi) + b3 * (1.0 - 6.0 * xi + 6.0 * xi * xi)) / l
    return value, slope


def _rod_fields(beam, values, l, s):
    """``(u, u', phi, phi')`` of a rod element from its local values ``(u0, phi0, u1, phi1,
    a2, a3)`` and, with torsion, ``(b2, b3)`` (the bubbles of ``u``, then of ``phi``).

    Both fields are cubic (:func:`_bar`), written through differences of nodal values; the
    twist of a rod without torsion is the linear interpolation of its nodal values, which
    are constrained to zero.
    """
    xi = s / l
    u, du = _bar(values[0], values[2], values[4:6], l, xi)
    phi, dphi = _bar(values[1], values[3], values[6:8] if beam["torsion"] else (), l, xi)
    return u, du, phi, dphi


def _fields(beam, values, l, s):
    """``(Y, Y', psi, psi')`` at the local coordinates ``s`` from an element's local values.

    ``values`` are ``(Y0, Theta0, Y1, Theta1)`` and, shear-flexible, the internal
    ``(w2, w3, p2)``; arrays broadcasting with ``l`` and ``s``. Both elements are
    written through differences of nodal values (a chord ``(Y1 - Y0)/l``, rotations
    relative to it) so that the curvature of a smooth mode on a fine mesh is not lost
    to cancellation.

    Rigid in shear: the cubic Hermite ``Y`` with ``psi = Y'``. Shear-flexible: ``Y``
    cubic and ``psi`` quadratic, each the linear interpolation of its nodal values
    plus hierarchical bubbles ``xi (1 - xi)``, ``xi (1 - xi)(1 - 2 xi)`` (``xi = s/l``);
    the shear strain ``Y' - psi`` can vanish exactly (no shear locking), and the
    element's error in ``omega`` is ``O(h**4)`` like Hermite's. (The
    interdependent interpolation element, four dofs with ``Y' - psi`` constant per
    element, only reaches ``O(h**2)`` in frequency.)

    On a rod, ``(u, u', phi, phi')`` (:func:`_rod_fields`).
    """
    if beam["rod"]:
        return _rod_fields(beam, values, l, s)
    w0, t0, w1, t1 = values[:4]
    chord = (w1 - w0) / l
    if beam["g"] == 0.0:
        u1, u2 = t0 - chord, t1 - chord
        b2 = 3.0 * (u1 + u2) / (l * l)
        b1 = (-4.0 * u1 - 2.0 * u2) / l
        dY = t0 + b1 * s + b2 * s * s
        return (w0 + t0 * s + b1 * s * s / 2.0 + b2 * s**3 / 3.0, dY, dY,
                b1 + 2.0 * b2 * s)
    w2, w3, p2 = values[4:]
    xi = s / l
    bubble, bubble3 = xi * (1.0 - xi), xi * (1.0 - xi) * (1.0 - 2.0 * xi)
    Y = w0 + (w1 - w0) * xi + w2 * bubble + w3 * bubble3
    dY = chord + (w2 * (1.0 - 2.0 * xi) + w3 * (1.0 - 6.0 * xi + 6.0 * xi * xi)) / l
    psi = t0 + (t1 - t0) * xi + p2 * bubble
    dpsi = ((t1 - t0) + p2 * (1.0 - 2.0 * xi)) / l
    return Y, dY, psi, dpsi


def _gauss(l):
    """Gauss points and weights on elements of lengths ``l`` (shape (..., 4))."""
    l = np.asarray(l)[..., None]
    return l * (1.0 + _GAUSS_X) / 2.0, l * _GAUSS_W / 2.0


def _energy_densities(beam, fields):
    """Twice the strain and the kinetic energy densities (``omega**2`` factored out)."""
    Y, dY, psi, dpsi = fields
    if beam["rod"]:
        return (beam["EA"] * dY**2 + beam["kw"] * Y**2 + beam["GJ"] * dpsi**2,
                beam["m"] * Y**2 + beam["rhoIp"] * psi**2)
    strain = beam["EI"] * dpsi**2 + beam["N"] * dY**2 + beam["kw"] * Y**2
    if beam["g"] != 0.0:
        strain = strain + beam["EI"] / beam["g"] * (dY - psi) ** 2
    return strain, beam["m"] * Y**2 + beam["rhoI"] * psi**2


def _element_matrices(beam, lengths):
    """Stiffness and mass of each element, shape (n, d, d), local dofs as in :func:`_fields`.

    The energy integrated exactly (4-point Gauss; the integrands are polynomials of
    degree 6 at most) on the local unit vectors: the bilinear forms of ``K = EI
    psi'psi' + kGA gamma gamma + N Y'Y' + kw Y Y`` and ``M = m Y Y + rhoI psi psi``
    (``gamma = Y' - psi``); on a rod of ``K = EA u'u' + kw u u + GJ phi'phi'`` and ``M = m u
    u + rhoIp phi phi`` (the integrands of degree 6 at most as well).
    """
    d = _element_dofs(beam)
    unit = np.eye(d)[None, :, :, None]              # (1, d unit vectors, d values, 1)
    s, w = _gauss(lengths)                          # (n, 4)
    l = lengths[:, None, None]
    fields = _fields(beam, [unit[:, :, i] for i in range(d)], l, s[:, None, :])
    fields = [np.broadcast_to(f, (len(lengths), d, len(_GAUSS_W))) for f in fields]
    Y, dY, psi, dpsi = fields

    def gram(f, coefficient):
        return coefficient * np.einsum("nig,njg,ng->nij", f, f, w)

    if beam["rod"]:
        # EA u'u' + kw u u + GJ phi'phi',  m u u + rhoIp phi phi
        K = gram(dY, beam["EA"]) + gram(Y, beam["kw"]) + gram(dpsi, beam["GJ"])
        return K, gram(Y, beam["m"]) + gram(psi, beam["rhoIp"])
    K = gram(dpsi, beam["EI"]) + gram(dY, beam["N"]) + gram(Y, beam["kw"])
    if beam["g"] != 0.0:
        K = K + gram(dY - psi, beam["EI"] / beam["g"])
    M = gram(Y, beam["m"]) + gram(psi, beam["rhoI"])
    return K, M


def _layer_matrices(beam_a, beam_b, lengths, k):
    """Stiffness of a layer over aligned elements of two beams, shape (n, d_a + d_b, ...).

    ``k int (N_a - N_b)^T (N_a - N_b) dx`` on the local dofs of beam ``a``'s element
    followed by those of beam ``b``'s (``N`` the shape functions of ``Y``):
    ``[[Kf_a, -Kf_ab], [-Kf_ba, Kf_b]]``, each block a Winkler foundation matrix.
    Integrated exactly (4-point Gauss, ``Y`` is cubic).
    """
    s, w = _gauss(lengths)
    l = lengths[:, None, None]
    shapes = []
    for beam, sign in ((beam_a, 1.0), (beam_b, -1.0)):
        d = _element_dofs(beam)
        unit = np.eye(d)[None, :, :, None]
        Y = _fields(beam, [unit[:, :, i] for i in range(d)], l, s[:, None, :])[0]
        shapes.append(sign * np.broadcast_to(Y, (len(lengths), d, len(_GAUSS_W))))
    N = np.concatenate(shapes, axis=1)
    return k * np.einsum("nig,njg,ng->nij", N, N, w)


def _layer_strain_energy(beam_a, beam_b, lengths, local_a, local_b, k):
    """Twice the strain energy of a layer for each column of the elements' local values."""
    s, w = _gauss(lengths)
    l = lengths[:, None, None]
    Y = [_fields(beam, [local[:, i, :, None] for i in range(local.shape[1])], l,
                 s[:, None, :])[0]
         for beam, local in ((beam_a, local_a), (beam_b, local_b))]
    return k * np.einsum("nmg,ng->m", (Y[0] - Y[1]) ** 2, w)


def _beam_strain_energy(beam, lengths, local):
    """Twice the strain energy of each column of the elements' local values.

    ``local`` has shape (elements, d, modes). Sums of squares of fields computed
    from differences of nodal values (see :func:`_fields`): every term keeps its
    relative accuracy on a fine mesh.
    """
    s, w = _gauss(lengths)
    l = lengths[:, None, None]
    values = [local[:, i, :, None] for i in range(local.shape[1])]   # (n, modes, 1)
    strain, _ = _energy_densities(beam, _fields(beam, values, l, s[:, None, :]))
    return np.einsum("nmg,ng->m", strain, w)


# ---------------------------------------------------------------------------
# Assembly and constraints
# ---------------------------------------------------------------------------

def _beam_element_dofs(beam, nodes, first_dof):
    """Global dof of each element's local dofs, shape (elements, d).

    A beam's dofs are ``Y, Theta`` (a rod's ``u, phi``) of each node, then the internal
    ones of each element.
    """
    n = len(nodes) - 1
    dofs = first_dof + 2 * np.arange(n)[:, None] + np.arange(4)[None, :]
    k = _element_dofs(beam) - 4
    if k == 0:
        return dofs
    internal = first_dof + 2 * len(nodes) + k * np.arange(n)[:, None] + np.arange(k)[None, :]
    return np.hstack([dofs, internal])


def _beam_dof_count(beam, nodes):
    return 2 * len(nodes) + (_element_dofs(beam) - 4) * (len(nodes) - 1)


def _assemble_beam(K, M, beam, nodes, element_dofs):
    Ke, Me = _element_matrices(beam, np.diff(nodes))
    _add_elements(K, element_dofs, Ke)
    _add_elements(M, element_dofs, Me)


def _add_elements(K, element_dofs, Ke):
    """Scatter element matrices ``Ke`` (n, d, d) into ``K`` at ``element_dofs`` (n, d)."""
    n, d = element_dofs.shape
    rows = np.repeat(element_dofs, d, axis=1)
    cols = np.tile(element_dofs, (1, d))
    np.add.at(K, (rows, cols), Ke.reshape(n, d * d))


def _add_spring(K, stretch, k):
    """``K += k v v^T`` for the stretch ``v . u`` given as ``{dof: coefficient}``."""
    for a, ca in stretch.items():
        for b, cb in stretch.items():
            K[a, b] += k * ca * cb


def _boundary_constraints(beam, first_dof, n_nodes):
    """The dofs the ends fix, each a constraint ``{dof: 1}``; on a rod without torsion also
    every nodal ``phi`` (the rod has no twist)."""
    last_node_dof = first_dof + 2 * (n_nodes - 1)
    table = _ROD_CONSTRAINED_DOFS if beam["rod"] else _CONSTRAINED_DOFS
    dofs = [first_dof + local for local in table[beam["left"]]]
    dofs += [last_node_dof + local for local in table[beam["right"]]]
    if beam["rod"] and not beam["torsion"]:
        dofs = sorted(set(dofs) | {first_dof + 1 + 2 * i for i in range(n_nodes)})
    return [{dof: 1.0} for dof in dofs]


def _reduction(constraints, total):
    """Basis ``T`` (total x n) of the null space of the constraints, and the kept dofs.

    Dofs no constraint names are kept as they are (the first columns, in order);
    the named ones are replaced by an orthonormal basis of the constraints' null
    space among them (the last columns). Returns ``(T, kept)``, ``kept[i]`` the
    column of dof ``i`` or -1.

    A constraint naming a single dof (a support) fixes it: it is dropped, and from
    the other constraints too, before the null space of the rest is computed.
    """
    fixed = {dof for row in constraints if len(row) == 1
             for dof, value in row.items() if value != 0.0}
    rows = [{dof: value for dof, value in row.items() if dof not in fixed}
            for row in constraints]
    rows = [row for row in rows if row]
    involved = sorted({dof for row in rows for dof in row})
    free = np.setdiff1d(np.arange(total), sorted(fixed.union(involved)))
    basis = np.zeros((len(involved), 0))
    if involved:
        position = {dof: i for i, dof in enumerate(involved)}
        C = np.zeros((len(rows), len(involved)))
        for r, row in enumerate(rows):
            for dof, value in row.items():
                C[r, position[dof]] += value
        basis = scipy.linalg.null_space(C)
    T = np.zeros((total, len(free) + basis.shape[1]))
    T[free, np.arange(len(free))] = 1.0
    if involved:
        T[np.asarray(involved), len(free):] = basis
    kept = np.full(total, -1)
    kept[free] = np.arange(len(free))
    return T, kept


def _build(beams, springs, elements_per_beam, masses=None, bodies=None, refine=1,
           layers=None):
    """Validate input, mesh, assemble and reduce by the constraints.

    Returns ``(K, M, dof_info, energy_terms)``; ``energy_terms`` lists what
    :func:`_strain_energy` needs to evaluate the strain energy without ``K``.
    """
    beams = _normalise_beams(beams)
    springs = _normalise_springs(springs, beams)
    masses = _normalise_masses(masses, beams)
    bodies = _normalise_bodies(bodies, beams)
    layers = _normalise_layers(layers, beams)
    elements_per_beam = _check_positive_int(elements_per_beam, "elements_per_beam")
    refine = _check_positive_int(refine, "refine")

    positions = {}
    for name in beams:
        positions[name] = [x for a, b, x, _, _ in springs if name in (a, b)]
        positions[name] += [x for n, x, _, _ in masses if n == name]
        positions[name] += [x for body in bodies for n, x, _, _ in body["attach"] if n == name]
    nodes = _meshes(beams, positions, layers, elements_per_beam, refine)
    first_dof, total = {}, 0
    for name, beam in beams.items():
        first_dof[name] = total
        total += _beam_dof_count(beam, nodes[name])
    body_dofs = []
    for body in bodies:
        body_dofs.append((total, total + 1 if body["rotates"] else None))
        total += 2 if body["rotates"] else 1

    K = np.zeros((total, total))
    M = np.zeros((total, total))
    constraints = []
    element_dofs = {}
    for name, beam in beams.items():
        element_dofs[name] = _beam_element_dofs(beam, nodes[name], first_dof[name])
        _assemble_beam(K, M, beam, nodes[name], element_dofs[name])
        constraints += _boundary_constraints(beam, first_dof[name], len(nodes[name]))

    def node_dof(name, x, local):
        return first_dof[name] + 2 * _nearest_node(nodes[name], x) + local

    spring_dofs = []               # (stretch {dof: coefficient}, k) of every spring
    for name_a, name_b, x, k, local in springs:
        stretch = {node_dof(name_a, x, local): 1.0}
        if name_b is not None:
            stretch[node_dof(name_b, x, local)] = -1.0
        spring_dofs.append((stretch, k))
    for name, x, mass, inertia in masses:
        M[node_dof(name, x, 0), node_dof(name, x, 0)] += mass
        M[node_dof(name, x, 1), node_dof(name, x, 1)] += inertia
    for body, (yc, tc) in zip(bodies, body_dofs):
        M[yc, yc] += body["M"]
        if tc is not None:
            M[tc, tc] += body["J"]
        for name, x, hinged, k in body["attach"]:
            # Y_beam - Y_c - (x - xc) Theta_c: zero, or the stretch of a spring k
            row = {node_dof(name, x, 0): 1.0, yc: -1.0}
            if tc is not None and x != body["xc"]:
                row[tc] = -(x - body["xc"])
            if k is not None:
                spring_dofs.append((row, k))
                continue
            constraints.append(row)
            if not hinged:
                constraints.append({node_dof(name, x, 1): 1.0, tc: -1.0})
    for stretch, k in spring_dofs:
        _add_spring(K, stretch, k)
    layer_terms = []            # (beam a, beam b, lengths, element dofs on a, on b, k)
    for a, b, x0, x1, k in layers:
        # the elements of both beams between the layer's end nodes (aligned by _meshes)
        i0, i1 = (_nearest_node(nodes[a], x) for x in (x0, x1))
        j0, j1 = (_nearest_node(nodes[b], x) for x in (x0, x1))
        assert i1 - i0 == j1 - j0 > 0
        lengths = np.diff(nodes[a])[i0:i1]
        dofs_a, dofs_b = element_dofs[a][i0:i1], element_dofs[b][j0:j1]
        _add_elements(K, np.hstack([dofs_a, dofs_b]),
                      _layer_matrices(beams[a], beams[b], lengths, k))
        layer_terms.append((beams[a], beams[b], lengths, dofs_a, dofs_b, k))

    T, kept = _reduction(constraints, total)
    K = T.T @ K @ T
    M = T.T @ M @ T
    # symmetrise: the products above are symmetric only to rounding
    K, M = (K + K.T) / 2.0, (M + M.T) / 2.0
    info = {
        "nodes": nodes,
        "dofs": {name: kept[first_dof[name]: first_dof[name] + 2 * len(nodes[name])]
                 .reshape(-1, 2) for name in beams},
        "n_dofs": T.shape[1],
        "full_dofs": {name: first_dof[name] + np.arange(2 * len(nodes[name])).reshape(-1, 2)
                      for name in beams},
        "body_dofs": body_dofs,
        "transform": T,
    }
    energy_terms = {
        "beams": [(beam, np.diff(nodes[name]), element_dofs[name])
                  for name, beam in beams.items()],
        "springs": spring_dofs,
        "layers": layer_terms,
        "T": T,
    }
    return K, M, info, energy_terms


# ---------------------------------------------------------------------------
# Eigenvalues
# ---------------------------------------------------------------------------

def _strain_energy(energy_terms, vectors):
    """Twice the strain energy, ``v.T K v``, of each column without using K.

    For smooth modes on a fine mesh ``K v`` suffers cancellation of order
    ``h**-4``; summing element energies written as squares of fields computed
    from differences keeps every term accurate.
    """
    full = energy_terms["T"] @ vectors
    energy = np.zeros(vectors.shape[1])
    for beam, lengths, dofs in energy_terms["beams"]:
        energy += _beam_strain_energy(beam, lengths, full[dofs])
    for beam_a, beam_b, lengths, dofs_a, dofs_b, k in energy_terms["layers"]:
        energy += _layer_strain_energy(beam_a, beam_b, lengths, full[dofs_a], full[dofs_b], k)
    for terms, k in energy_terms["springs"]:
        stretch = sum(c * full[dof] for dof, c in terms.items())
        energy += k * stretch * stretch
    return energy


def _zero_threshold(K, M):
    """Eigenvalue magnitude below which rounding noise dominates."""
    ratio = np.max(np.abs(np.diag(K)) / np.diag(M)) if K.size else 0.0
    return _ZERO_EIGENVALUE_FACTOR * np.finfo(float).eps * ratio


def _condensed(K, M):
    """Eliminate the dofs without mass (``psi`` of a beam with ``rhoI = 0``) statically.

    Returns ``(K_c, M_c, expand)``: the problem on the dofs with mass, and the map
    from its eigenvectors to all dofs (``u_b = -K_bb**-1 K_ba u_a``). Exact: a
    massless dof is in equilibrium at every instant.
    """
    massless = np.all(M == 0.0, axis=1)
    if not massless.any():
        return K, M, lambda vectors: vectors
    a, b = ~massless, massless
    try:
        factor = scipy.linalg.cho_factor(K[np.ix_(b, b)])
    except np.linalg.LinAlgError:
        raise ValueError("some motion has neither mass nor stiffness (a massless mechanism)") \
            from None
    X = scipy.linalg.cho_solve(factor, K[np.ix_(b, a)])
    Kc = K[np.ix_(a, a)] - K[np.ix_(a, b)] @ X

    def expand(vectors):
        out = np.zeros((len(massless), vectors.shape[1]))
        out[a] = vectors
        out[b] = -X @ vectors
        return out
    return (Kc + Kc.T) / 2.0, M[np.ix_(a, a)], expand


def _subset(count, n):
    """``subset_by_index`` of the lowest ``count`` of ``n`` modes (None: all), checked."""
    if count is None:
        return None
    if isinstance(count, bool) or not isinstance(count, (int, np.integer)):
        raise ValueError(f"count must be an integer, got {count!r}")
    if not 1 <= count <= n:
        raise ValueError(f"count must be between 1 and the number of modes ({n}), "
                         f"got {count!r}")
    return (0, int(count) - 1)


def _refined_eigenvalues(K, M, energy_terms, subset, strain_energy=None):
    """Eigenvalues ``omega**2`` with rigid-body modes exactly zero.

    The dense solver's absolute error is about ``eps * largest eigenvalue``,
    which swamps the lowest modes of a fine mesh.  The Rayleigh quotient of
    each computed eigenvector, with the energy evaluated accurately, has only
    second-order error in the eigenvector and restores the lowest modes.
    ``strain_energy(energy_terms, vectors)``: the beams' (default) or the frames'.
    """
    strain_energy = strain_energy or _strain_energy
    Kc, Mc, expand = _condensed(K, M)
    try:
        eigenvalues, vectors = scipy.linalg.eigh(Kc, Mc, subset_by_index=subset)
    except np.linalg.LinAlgError:
        raise ValueError("the mass matrix is singular: some motion has no inertia "
                         "(a massless body free to move?)") from None
    threshold = _zero_threshold(Kc, Mc)
    if np.any(eigenvalues < -threshold):
        raise ValueError(f"the model is unstable (omega**2 = {eigenvalues[0]:.6g} < 0): "
                         "an axial compression above the buckling load?")
    rigid = eigenvalues < threshold
    vectors = expand(vectors)
    mass = np.einsum("ij,ij->j", vectors, M @ vectors)
    quotients = strain_energy(energy_terms, vectors) / mass
    return np.sort(np.where(rigid, 0.0, np.maximum(quotients, 0.0)))


# ---------------------------------------------------------------------------
# Public API
# ---------------------------------------------------------------------------

def fe_matrices(beams, springs, elements_per_beam, masses=None, bodies=None, refine=1,
                layers=None):
    """Assemble the finite-element stiffness and mass matrices.

    Parameters
    ----------
    beams : list of dict
        Beams with keys ``name``, ``EI``, ``m``, ``L``, ``x0``, ``left`` and
        ``right``, optionally ``kw``, ``N``, ``rhoI``, ``kGA`` (see the module
        docstring); boundary conditions are ``"free"``, ``"clamped"`` (``Y =
        Theta = 0``), ``"pinned"`` (``Y = 0``) or ``"sliding"`` (``Theta = 0``).
        Rods among them: ``{"rod": True, "name", "EA", "m", "L", "x0", "left",
        "right"}`` with optional ``kw``, ``GJ`` and ``rhoIp``; ends ``"fixed"``,
        ``"free"``, with torsion also ``"fixed-axial"`` and ``"fixed-torsion"``.
    springs : list of dict or None
        Springs with keys ``between`` (pair of beam names, either may be
        ``"ground"``), ``x`` (global coordinate on every connected beam,
        possibly at a beam end) and ``k`` (stiffness, non-negative); optional
        ``kind`` (``"translational"`` or ``"rotational"``; between rods, or a rod
        and the ground, axial or torsional, also named ``"axial"`` and
        ``"torsional"``). An optional ``c`` must be zero; other keys are ignored.
    elements_per_beam : int
        Approximate number of elements per beam.  Every beam gets nodes at
        its ends and at each point where something acts on it; the intervals
        in between are split into equal elements, their number proportional to
        the interval length and at least one.
    masses : list of dict, optional
        Lumped masses ``{"beam", "x", "M", "J"}`` (``J`` optional).
    bodies : list of dict, optional
        Rigid bodies ``{"attach": [{"beam", "x", "hinged"}, ...], "M", "J", "xc"}``
        (all but ``attach`` optional).
    refine : int, optional
        Split every element of that mesh into ``refine`` equal elements.
    layers : list of dict, optional
        Elastic layers ``{"between": (a, b), "k", "x0", "x1"}`` between two beams
        (``x0``, ``x1`` optional, by default the overlap of the beams; an optional
        ``c`` must be zero). Both beams get the same nodes inside a layer.

    Returns
    -------
    K, M : numpy.ndarray
        Dense symmetric stiffness and mass matrices of the constrained
        system, shape ``(n, n)``.
    dof_info : dict
        ``"nodes"`` maps each beam name to its node coordinates (global
        ``x``); ``"dofs"`` maps each beam name to an integer array of shape
        ``(n_nodes, 2)`` giving the row of ``K``/``M`` holding ``Y`` and
        ``Theta`` (on a rod ``u`` and ``phi``) at each node, or ``-1`` where a
        boundary condition removed the dof (every ``phi`` of a rod without
        torsion) or a body's constraint made it a combination of others (the
        rows no node holds are the elements' internal dofs and the bodies');
        ``"n_dofs"`` is ``n``. ``"transform"`` is ``T`` with ``u = T q`` from
        the reduced dofs ``q`` to all dofs ``u`` (the beams' nodal dofs, rows
        ``"full_dofs"``, then each body's ``Y_c`` and ``Theta_c``, rows
        ``"body_dofs"``, None where the body does not rotate).

    Raises
    ------
    ValueError
        On malformed input, an unknown boundary condition or beam name, a
        point outside its beam, a layer to ground or of no length, or a non-zero
        dashpot or layer damping.

    Examples
    --------
    >>> from symtmm.fe import fe_matrices
    >>> beam = dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned")
    >>> K, M, info = fe_matrices([beam], [], 4)
    >>> K.shape, info["n_dofs"]
    ((8, 8), 8)
    >>> info["dofs"]["a"][0].tolist()  # Y removed at the pinned left end
    [-1, 0]

    A rigid joint of two beam ends leaves one Y and one Theta of the three nodes'
    (the two ends and the joint's own):

    >>> a = dict(beam, name="a", left="clamped", right="free")
    >>> b = dict(beam, name="b", x0=1.0, left="free", right="free")
    >>> joint = {"attach": [{"beam": "a", "x": 1.0}, {"beam": "b", "x": 1.0}]}
    >>> K, M, info = fe_matrices([a, b], [], 4, bodies=[joint])
    >>> info["n_dofs"]      # 2 * (5 + 5) + 2 dofs, 2 at the clamp, 4 tied by the joint
    16

    A layer over ``[0.3, 0.7]`` between beams of different lengths: nodes at its ends
    on both, and the same ones in between:

    >>> c = dict(beam, name="c", L=2.0)
    >>> layer = {"between": ("a", "c"), "k": 50.0, "x0": 0.3, "x1": 0.7}
    >>> K, M, info = fe_matrices([a, c], [], 4, layers=[layer])
    >>> info["nodes"]["a"].round(2).tolist()
    [0.0, 0.3, 0.5, 0.7, 1.0]
    >>> info["nodes"]["c"].round(2).tolist()
    [0.0, 0.3, 0.5, 0.7, 1.13, 1.57, 2.0]

    A rod fixed at the left, without torsion: ``u`` and two bubbles per element, no ``phi``:

    >>> r = dict(rod=True, name="r", EA=1.0, m=1.0, L=1.0, x0=0.0, left="fixed", right="free")
    >>> K, M, info = fe_matrices([r], [], 4)
    >>> info["n_dofs"], info["dofs"]["r"][:2].tolist()     # 4 nodal u, 8 bubbles
    (12, [[-1, -1], [0, -1]])
    """
    K, M, info, _ = _build(beams, springs, elements_per_beam, masses, bodies, refine, layers)
    return K, M, info


def fe_dashpots(info, dashpots):
    """The damping matrix ``C`` of translational dashpots on a mesh of :func:`fe_matrices`.

    Parameters
    ----------
    info : dict
        The ``dof_info`` of :func:`fe_matrices`.
    dashpots : iterable of (str, str, float, float)
        ``(beam, other beam or "ground", x, c)``: a dashpot ``c`` between the
        deflections of the two beams at ``x`` (each at its node nearest ``x``;
        put a node there, as :func:`fe_matrices` does at every spring).

    Returns
    -------
    numpy.ndarray
        Dense symmetric ``C``, shape ``(n, n)``, ``n = info["n_dofs"]``; a dof removed by
        a boundary condition takes no part.

    Examples
    --------
    >>> beam = dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="free")
    >>> K, M, info = fe_matrices([beam], [{"between": ["a", "ground"], "x": 0.5, "k": 0.0}], 2)
    >>> C = fe_dashpots(info, [("a", "ground", 0.5, 3.0)])
    >>> row = info["dofs"]["a"][1][0]
    >>> float(C[row, row]), float(C.sum())
    (3.0, 3.0)
    """
    n = info["n_dofs"]
    C = np.zeros((n, n))

    def dof(beam, x):
        if beam == "ground":
            return -1
        node = _nearest_node(np.asarray(info["nodes"][beam]), x)
        return int(info["dofs"][beam][node][0])

    for a, b, x, c in dashpots:
        i, j = dof(a, x), dof(b, x)
        for p, q, s in ((i, i, c), (j, j, c), (i, j, -c), (j, i, -c)):
            if p >= 0 and q >= 0:
                C[p, q] += s
    return C


def fe_frequencies(beams, springs, elements_per_beam, count=None, masses=None, bodies=None,
                   refine=1, layers=None):
    """Natural circular frequencies of the finite-element model.

    Parameters
    ----------
    beams, springs, elements_per_beam, masses, bodies, refine, layers
        As for :func:`fe_matrices`.
    count : int, optional
        Number of lowest frequencies to return; all of them by default.

    Returns
    -------
    numpy.ndarray
        Natural circular frequencies ``omega`` (rad/s) in ascending order.
        Rigid-body modes appear as exact zeros: eigenvalues ``omega**2``
        within rounding noise of zero are set to 0.

    Raises
    ------
    ValueError
        On invalid input (see :func:`fe_matrices`), if ``count`` is not an
        integer between 1 and the number of degrees of freedom, if some motion
        has no mass (singular mass matrix) or if the model is unstable (an
        eigenvalue ``omega**2`` clearly below zero, e.g. a beam buckled by
        compression).

    Notes
    -----
    The generalized problem ``K v = omega**2 M v`` is solved densely with
    :func:`scipy.linalg.eigh`, which is practical up to a few thousand
    degrees of freedom.  With consistent mass the frequencies converge from
    above with error ``O(h**4)`` in the element size ``h`` (a rod's as
    ``O(h**6)``).

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

    A tension ``N`` raises ``omega**2`` of the pinned-pinned beam by ``N (n pi)**2``:

    >>> taut = dict(beam, N=10.0)
    >>> print(np.round(fe_frequencies([taut], [], 20, count=1) ** 2 - np.pi**4, 3))
    [98.696]

    A fixed-free rod with ``c = sqrt(EA/m) = 2``, also in torsion with ``c = 1`` and
    free to twist at the left (``fixed-axial``): ``(2n - 1) pi c / 2`` and ``n pi c``
    with a rigid twist:

    >>> shaft = dict(rod=True, name="s", EA=4.0, m=1.0, L=1.0, x0=0.0, GJ=1.0, rhoIp=1.0,
    ...              left="fixed-axial", right="free")
    >>> print(np.round(fe_frequencies([shaft], [], 8, count=4) / np.pi, 5))
    [0. 1. 1. 2.]
    """
    K, M, _, energy_terms = _build(beams, springs, elements_per_beam, masses, bodies, refine,
                                   layers)
    n = int(np.count_nonzero(np.any(M != 0.0, axis=1)))     # dofs with mass: the modes
    subset = _subset(count, n)
    if n == 0:
        return np.zeros(0)
    return np.sqrt(_refined_eigenvalues(K, M, energy_terms, subset))


def fe_converged(beams, springs, elements_per_beam, count, masses=None, bodies=None,
                 rate=4, levels=3, layers=None):
    """Frequencies extrapolated from nested meshes, with an error estimate.

    The meshes ``refine = 1, 2, 4, ...`` (``levels`` of them) halve every
    element. The error of these elements is a series ``C4 h**4 + C6 h**6 + ...``
    in the element size (even powers: the elements are symmetric), so Romberg's
    scheme removes one term per mesh: Richardson's extrapolation with ``2**rate``,
    then ``2**(rate + 2)``, and so on. A rod's series starts at ``h**6``: with the
    default ``rate`` its modes lose that term in the second column (its
    ``"rate"`` reads 6), or ``rate=6`` suits a model of rods only.

    Parameters
    ----------
    beams, springs, elements_per_beam, masses, bodies, layers
        As for :func:`fe_matrices` (the coarsest mesh).
    count : int
        Number of lowest frequencies.
    rate : float, optional
        The order of the leading error term in ``omega`` (4 for these elements).
    levels : int, optional
        Number of meshes, at least 3 (the observed rate needs three).

    Returns
    -------
    dict
        ``"omega"`` the extrapolated frequencies; ``"error"`` an estimate of
        their error (the last correction of the scheme, which bounds it while the
        series converges, plus a rounding floor of ``1e-12 omega``); ``"rate"`` the
        observed order ``log2(d1/d2)`` of the differences between the last three
        meshes per mode (nan where they vanish); ``"raw"`` the frequencies on each
        mesh (levels x count); ``"zero"`` which modes are rigid-body zeros.

    Examples
    --------
    >>> import numpy as np
    >>> beam = dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="clamped", right="free")
    >>> out = fe_converged([beam], [], 8, count=2)
    >>> Omega = np.array([1.87510406871196, 4.69409113297418])    # cos x cosh x = -1
    >>> print(np.round(out["omega"] / Omega**2, 11), np.round(out["rate"], 1))
    [1. 1.] [4. 4.]
    >>> bool(np.all(np.abs(out["omega"] / Omega**2 - 1) < out["error"] / out["omega"]))
    True
    """
    levels = _check_positive_int(levels, "levels")
    if levels < 3:
        raise ValueError(f"levels must be at least 3, got {levels!r}")
    raw = np.array([fe_frequencies(beams, springs, elements_per_beam, count, masses, bodies,
                                   refine=2**j, layers=layers) for j in range(levels)])
    return _romberg(raw, rate)


# ---------------------------------------------------------------------------
# Planar frames
# ---------------------------------------------------------------------------
#
# Members of a plane frame, each a beam in bending and a bar along its axis, from the
# textbook (Przemieniecki, *Theory of matrix structural analysis*, ch. 5 and 11; Cook et
# al., *Concepts and applications of finite element analysis*, 2-D frame element):
#
# * in the member's own axes (``e`` from start to end, ``n`` = ``e`` turned by +90
#   degrees) every element has the Hermite bending element of the beams above on ``(w0,
#   theta0, w1, theta1)`` and the cubic hierarchical bar of the rods above on ``(u0, u1)``
#   and two bubbles; consistent mass for both;
# * the nodal translations ``u``, ``w`` are the components of the global ``(X, Y)``
#   along ``e`` and ``n`` (the rotation is the same in both frames): ``u = e . U``, ``w =
#   n . U``. Inner nodes of a member keep local dofs ``(u, w, theta)``; the points where
#   member ends lie (merged by their coordinates) carry global ``X, Y, Theta``;
# * a hinge gives every member end at its node a rotation of its own; a support drops the
#   dofs it holds (pinned ``X, Y``, clamped also ``Theta``, rollers and sliding supports
#   as in :data:`symtmm.frame.SUPPORTS`); a node's ``M`` acts on both translations, its
#   ``J`` on the rotation (at a hinge a rotation of the node's own, which nothing else
#   turns);
# * an inextensible member (``EA`` None) has no bubbles and a single axial dof ``a``: the
#   axial displacement of all its points, its mass ``m L`` moving with it; both ends obey
#   ``e . U_end = a`` exactly, eliminated with the other constraints by the null-space
#   reduction above (:func:`_reduction`).

_FRAME_SUPPORTS = {"free": (), "pinned": (0, 1), "clamped": (0, 1, 2),
                   "roller-x": (1,), "roller-y": (0,), "sliding-x": (1, 2),
                   "sliding-y": (0, 2)}

# The element's local vector: bending (w0, theta0, w1, theta1), then the bar (u0, phi0, u1,
# phi1, a2, a3) as :func:`_rod_fields` orders it (its phi never used).
_FRAME_LOCAL = 10


def _frame_point(value, what):
    if isinstance(value, (str, Mapping)) or not isinstance(value, Sequence) or len(value) != 2:
        raise ValueError(f"{what} must be a point (x, y), got {value!r}")
    return np.array([_number(v, what) for v in value])


def _normalise_frame(members, nodes):
    """Validate member and node dicts: members with floats, their ends' point indices, the
    points' coordinates and the node attached to each point (or None)."""
    if isinstance(members, Mapping) or not isinstance(members, Sequence) or not members:
        raise ValueError("members must be a non-empty list of member dicts")
    parsed = []
    for index, member in enumerate(members):
        what = f"member {member.get('name', index)!r}" if isinstance(member, Mapping) \
            else f"member #{index}"
        _require_keys(member, ("start", "end", "EI", "EA", "m"), what)
        start = _frame_point(member["start"], f"start of {what}")
        end = _frame_point(member["end"], f"end of {what}")
        L = float(np.hypot(*(end - start)))
        if L == 0.0:
            raise ValueError(f"the two ends of {what} are one point")
        EA = member["EA"]
        parsed.append({"what": what, "start": start, "end": end, "L": L,
                       "e": (end - start) / L,
                       "EI": _positive_float(member["EI"], f"EI of {what}"),
                       "EA": None if EA is None else _positive_float(EA, f"EA of {what}"),
                       "m": _positive_float(member["m"], f"m of {what}")})
    size = max(max(np.abs(mb["start"]).max(), np.abs(mb["end"]).max(), mb["L"])
               for mb in parsed)
    tol = _POSITION_RTOL * size
    points = []

    def point_index(p):
        for i, q in enumerate(points):
            if np.max(np.abs(p - q)) <= tol:
                return i
        points.append(p)
        return len(points) - 1

    for mb in parsed:
        mb["ends"] = (point_index(mb["start"]), point_index(mb["end"]))
    count = len(points)
    node_at = [None] * count
    for index, node in enumerate(_list_of(nodes, "nodes")):
        what = f"node #{index}"
        _require_keys(node, ("at",), what)
        at = _frame_point(node["at"], f"'at' of {what}")
        i = point_index(at)
        if i >= count:
            raise ValueError(f"{what} at {tuple(at)} lies at no member end")
        if node_at[i] is not None:
            raise ValueError(f"two nodes at {tuple(at)}")
        support = node.get("support", "free")
        if support not in _FRAME_SUPPORTS:
            raise ValueError(f"unknown support {support!r} of {what}; expected one of "
                             f"{', '.join(map(repr, _FRAME_SUPPORTS))}")
        hinge = node.get("hinge", False)
        if not isinstance(hinge, (bool, np.bool_)):
            raise ValueError(f"'hinge' of {what} must be True or False")
        node_at[i] = {"support": support, "hinge": bool(hinge),
                      "M": _nonnegative_float(node.get("M", 0.0) or 0.0, f"M of {what}"),
                      "J": _nonnegative_float(node.get("J", 0.0) or 0.0, f"J of {what}")}
    bare = {"support": "free", "hinge": False, "M": 0.0, "J": 0.0}
    return parsed, np.array(points[:count]), [n or dict(bare) for n in node_at]


def _frame_build(members, nodes, elements, refine=1):
    """Assemble and reduce a frame: ``(K, M, info, energy)``, ``energy`` what
    :func:`_frame_strain_energy` needs (the elements' maps from the full dofs)."""
    members, points, node_at = _normalise_frame(members, nodes)
    elements = _check_positive_int(elements, "elements")
    refine = _check_positive_int(refine, "refine")
    n_el = elements * refine
    total = 0

    def new(k):
        nonlocal total
        out = list(range(total, total + k))
        total += k
        return out

    # every point: X, Y and (unless a hinge) Theta; a hinge's own Theta only to carry J
    point_dofs = []
    for node in node_at:
        xy = new(2)
        theta = None if node["hinge"] and node["J"] == 0.0 else new(1)[0]
        point_dofs.append((xy, theta))
    constraints = []
    for (xy, theta), node in zip(point_dofs, node_at):
        for held in _FRAME_SUPPORTS[node["support"]]:
            dof = theta if held == 2 else xy[held]
            if dof is not None:
                constraints.append({dof: 1.0})

    def end_maps(p, e, n):
        """A member end at point ``p``: its ``u``, ``w``, ``theta`` as [(dof, coefficient)]."""
        (X, Y), theta = point_dofs[p]
        if node_at[p]["hinge"]:
            theta = new(1)[0]            # the member end turns by itself
            if 2 in _FRAME_SUPPORTS[node_at[p]["support"]]:
                constraints.append({theta: 1.0})
        return ([(X, e[0]), (Y, e[1])], [(X, n[0]), (Y, n[1])], [(theta, 1.0)])

    maps = []           # per member: (index (n_el, 10, 2), coefficient (n_el, 10, 2))
    for mb in members:
        e = mb["e"]
        n = np.array([-e[1], e[0]])
        inner = [new(3) for _ in range(n_el - 1)]          # (u, w, theta) of inner nodes
        inextensible = mb["EA"] is None
        axial = new(1)[0] if inextensible else None
        if inextensible:
            constraints += [{d[0]: 1.0} for d in inner]     # their u is the member's a
        index = np.zeros((n_el, _FRAME_LOCAL, 2), dtype=int)
        coef = np.zeros((n_el, _FRAME_LOCAL, 2))

        ends = [end_maps(p, e, n) for p in mb["ends"]]
        if inextensible:
            for u, _, _ in ends:
                row = {axial: -1.0}
                for dof, c in u:
                    row[dof] = row.get(dof, 0.0) + c
                constraints.append(row)
        nodal = [ends[0]] + [([(d[0], 1.0)], [(d[1], 1.0)], [(d[2], 1.0)]) for d in inner] \
            + [ends[1]]
        for k in range(n_el):
            left, right = nodal[k], nodal[k + 1]
            slots = {0: left[1], 1: left[2], 2: right[1], 3: right[2]}
            if inextensible:
                slots |= {4: [(axial, 1.0)], 6: [(axial, 1.0)]}
            else:
                a2, a3 = new(2)
                slots |= {4: left[0], 6: right[0], 8: [(a2, 1.0)], 9: [(a3, 1.0)]}
            for slot, terms in slots.items():
                for j, (dof, c) in enumerate(terms):
                    index[k, slot, j], coef[k, slot, j] = dof, c
        maps.append((index, coef))

    K = np.zeros((total, total))
    M = np.zeros((total, total))
    energy = []
    for mb, (index, coef) in zip(members, maps):
        lengths = np.full(n_el, mb["L"] / n_el)
        bend = {"rod": False, "EI": mb["EI"], "m": mb["m"], "N": 0.0, "kw": 0.0,
                "rhoI": 0.0, "g": 0.0}
        bar = {"rod": True, "torsion": False, "EA": mb["EA"] or 0.0, "m": mb["m"],
               "kw": 0.0, "GJ": 0.0, "rhoIp": 0.0}
        Kb, Mb = _element_matrices(bend, lengths)
        Ka, Ma = _element_matrices(bar, lengths)
        Ke = np.zeros((n_el, _FRAME_LOCAL, _FRAME_LOCAL))
        Me = np.zeros_like(Ke)
        Ke[:, :4, :4], Me[:, :4, :4] = Kb, Mb
        Ke[:, 4:, 4:], Me[:, 4:, 4:] = Ka, Ma
        # local = G full: G[k, i, 2 i + j] = coef[k, i, j]
        G = np.zeros((n_el, _FRAME_LOCAL, 2 * _FRAME_LOCAL))
        rows = np.arange(_FRAME_LOCAL)
        for j in range(2):
            G[:, rows, 2 * rows + j] = coef[:, :, j]
        dofs = index.reshape(n_el, -1)
        _add_elements(K, dofs, np.einsum("nia,nij,njb->nab", G, Ke, G))
        _add_elements(M, dofs, np.einsum("nia,nij,njb->nab", G, Me, G))
        energy.append((bend, bar, lengths, index, coef))
    for (xy, theta), node in zip(point_dofs, node_at):
        for dof in xy:
            M[dof, dof] += node["M"]
        if theta is not None:
            M[theta, theta] += node["J"]
    T, _ = _reduction(constraints, total)
    K, M = T.T @ K @ T, T.T @ M @ T
    K, M = (K + K.T) / 2.0, (M + M.T) / 2.0
    info = {"points": points, "point_dofs": point_dofs, "n_dofs": T.shape[1],
            "transform": T, "elements": n_el}
    return K, M, info, {"T": T, "members": energy}


def _frame_strain_energy(energy, vectors):
    """Twice the strain energy of each column of ``vectors`` (reduced dofs), summed element
    by element from the fields (:func:`_beam_strain_energy`), without ``K``."""
    full = energy["T"] @ vectors
    out = np.zeros(vectors.shape[1])
    for bend, bar, lengths, index, coef in energy["members"]:
        local = np.einsum("nij,nijm->nim", coef, full[index])
        out += _beam_strain_energy(bend, lengths, local[:, :4])
        if bar["EA"]:
            out += _beam_strain_energy(bar, lengths, local[:, 4:])
    return out


def fe_frame_matrices(members, nodes, elements, refine=1):
    """Stiffness and mass matrices of the finite-element model of a planar frame.

    Parameters
    ----------
    members : list of dict
        Members ``{"start": (x, y), "end": (x, y), "EI", "EA", "m"}`` (optionally
        ``"name"``): bending and axial stiffness, mass per unit length; ``EA`` None for an
        inextensible member (its axial motion one rigid translation, exactly).
    nodes : list of dict or None
        Nodes ``{"at": (x, y), "support", "hinge", "M", "J"}`` (all but ``at``
        optional), each at a member end: ``support`` ``"free"`` (default), ``"pinned"``,
        ``"clamped"``, ``"roller-x"``, ``"roller-y"``, ``"sliding-x"``, ``"sliding-y"``
        (as in :data:`symtmm.frame.SUPPORTS`); ``hinge`` True lets every member end there
        turn by itself (a support holding the rotation then holds each end's); ``M`` a
        mass on both translations, ``J`` a rotary inertia (at a hinge on a rotation of
        the node's own, which no member turns: a zero mode). Member
        ends at one point (within a relative ``1e-9`` of the frame's size) are joined
        there; a member end at no node is free.
    elements : int
        Elements per member (all of the same length on a member).
    refine : int, optional
        Multiplies ``elements`` (nested meshes for :func:`fe_frame_converged`).

    Returns
    -------
    K, M : numpy.ndarray
        Dense symmetric matrices on the reduced dofs.
    info : dict
        ``"points"`` the joined points (coordinates, in order of first appearance),
        ``"point_dofs"`` each point's ``([X, Y], Theta)`` rows of the full dofs (Theta
        None at a hinge without ``J``), ``"transform"`` ``T`` (full = ``T`` reduced),
        ``"n_dofs"``, ``"elements"`` per member.

    Examples
    --------
    A clamped column of two elements: per element 2 axial bubbles; an inner node (3 dofs)
    and the free top (3):

    >>> from symtmm.fe import fe_frame_matrices
    >>> col = dict(start=(0, 0), end=(0, 2), EI=1.0, EA=100.0, m=1.0)
    >>> K, M, info = fe_frame_matrices([col], [dict(at=(0, 0), support="clamped")], 2)
    >>> info["n_dofs"]
    10
    """
    K, M, info, _ = _frame_build(members, nodes, elements, refine)
    return K, M, info


def fe_frame_frequencies(members, nodes, elements, count=None, refine=1):
    """Natural circular frequencies of the finite-element model of a planar frame.

    Two-node frame elements in each member's axes, turned to the plane's: cubic Hermite
    bending (``O(h**4)`` in ``omega``) and cubic hierarchical bars (``O(h**6)``), the
    elements of :func:`fe_frequencies`, consistent mass; see :func:`fe_frame_matrices`
    for the input. Conforming: upper bounds. Each ``omega**2`` is the Rayleigh quotient of
    its eigenvector with the strain energy summed element by element, as in
    :func:`fe_frequencies`; rigid-body modes read as exact zeros.

    Parameters
    ----------
    members, nodes, elements, refine
        As for :func:`fe_frame_matrices`.
    count : int, optional
        Number of lowest frequencies; all by default.

    Returns
    -------
    numpy.ndarray
        ``omega`` (rad/s) ascending, zero modes included as 0.

    Raises
    ------
    ValueError
        On malformed input (a node at no member end, two nodes at one point, an unknown
        support), or a ``count`` out of range.

    Examples
    --------
    Two collinear members clamped at their far ends, rigidly joined: one fixed-fixed rod
    of length 2 axially (``pi sqrt(EA/m) / 2``), one clamped-clamped beam in bending
    (``beta L = 4.7300``):

    >>> import numpy as np
    >>> from symtmm.fe import fe_frame_frequencies
    >>> a = dict(start=(0, 0), end=(1, 0), EI=1.0, EA=4.0, m=1.0)
    >>> b = dict(a, start=(1, 0), end=(2, 0))
    >>> ends = [dict(at=(0, 0), support="clamped"), dict(at=(2, 0), support="clamped")]
    >>> omega = fe_frame_frequencies([a, b], ends, 8, count=2)
    >>> print(np.round(omega / [np.pi, 4.730040745 ** 2 / 4], 4))
    [1. 1.]

    Free in the plane: three rigid-body modes:

    >>> print(np.round(fe_frame_frequencies([a, b], None, 4, count=4), 3))
    [0.    0.    0.    3.142]
    """
    K, M, _, energy = _frame_build(members, nodes, elements, refine)
    n = K.shape[0]
    subset = _subset(count, n)
    if n == 0:
        return np.zeros(0)
    return np.sqrt(_refined_eigenvalues(K, M, energy, subset, _frame_strain_energy))


def fe_frame_converged(members, nodes, elements, count, rate=4, levels=3):
    """Frame frequencies extrapolated from nested meshes (Romberg, as :func:`fe_converged`).

    Meshes of ``elements``, ``2 elements``, ... per member (``levels`` of them, at
    least 3); the error series ``C4 h**4 + C6 h**6 + ...`` loses one term per mesh.

    Returns
    -------
    dict
        ``"omega"``, ``"error"`` (the last correction plus ``1e-12 omega``), ``"rate"``
        (observed), ``"raw"`` (levels x count), ``"zero"``; as :func:`fe_converged`.

    Examples
    --------
    >>> import numpy as np
    >>> from symtmm.fe import fe_frame_converged
    >>> col = dict(start=(0, 0), end=(0, 1), EI=1.0, EA=1e4, m=1.0)
    >>> out = fe_frame_converged([col], [dict(at=(0, 0), support="clamped")], 4, count=1)
    >>> print(np.round(out["omega"] / 1.87510406871196**2, 10))
    [1.]
    """
    levels = _check_positive_int(levels, "levels")
    if levels < 3:
        raise ValueError(f"levels must be at least 3, got {levels!r}")
    raw = np.array([fe_frame_frequencies(members, nodes, elements, count, refine=2**j)
                    for j in range(levels)])
    return _romberg(raw, rate)



def _romberg(raw: np.ndarray, rate: float) -> dict:
    """Romberg extrapolation of frequencies on meshes refined by 2 (rows of ``raw``),
    errors falling as ``h**rate`` then ``h**(rate + 2)``, ...: the estimate, its error
    (the last two columns' difference), the observed rate; zero frequencies stay 0."""
    levels = len(raw)
    column = raw
    for j in range(levels - 1):
        factor = 2.0 ** (rate + 2 * j)
        previous, column = column, (factor * column[1:] - column[:-1]) / (factor - 1.0)
    best = column[-1]
    error = np.abs(best - previous[-1]) + 1e-12 * np.abs(best)
    d1, d2 = raw[-3] - raw[-2], raw[-2] - raw[-1]
    with np.errstate(divide="ignore", invalid="ignore"):
        observed = np.where((d1 > 0) & (d2 > 0), np.log2(d1 / d2), np.nan)
    zero = raw[-1] == 0.0
    return {"omega": np.where(zero, 0.0, best), "error": np.where(zero, 0.0, error),
            "rate": observed, "raw": raw, "zero": zero}

__all__ += ["fe_frame_matrices", "fe_frame_frequencies", "fe_frame_converged"]
