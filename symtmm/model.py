"""Immutable, validated description of a multilevel beam system.

A :class:`Model` holds parallel Euler–Bernoulli beams and the spring/dashpot
systems joining them (or joining a beam to the ground). Every numeric field is
an exact SymPy expression: a number, or an expression in parameters that may
still lack a value (useful for closed-form characteristic equations).

Examples
--------
>>> from symtmm.model import Beam, Spring, Model
>>> m = Model(beams=(Beam("upper", EI=1, m=1, L=1, left="free", right="free"),
...                  Beam("lower", EI=1, m=1, L=1, left="clamped", right="clamped")),
...           springs=(Spring("upper", "lower", x="3/10", k=100),))
>>> m.springs[0].x
3/10
>>> m.beam("lower").right
'clamped'
"""

from __future__ import annotations

import math
import numbers
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field, replace
from functools import cached_property

import sympy as sp

from .elements import BeamSegment, EulerBernoulliSegment
from .elements.theories import THEORIES
from .errors import ModelError
from .expr import (
    RESERVED_NAMES,
    ExpressionError,
    decades,
    exact_number,
    parameter_symbol,
    parse_expression,
    substitute,
)
from .limits import (
    FIELD_MAX,
    FIELD_MIN,
    MAX_BEAMS,
    MAX_PARAMETER_DEPTH,
    MAX_PARAMETERS,
    MAX_POINTS_ON_BEAMS,
)

__all__ = ["Beam", "Spring", "Mass", "Layer", "Attachment", "RigidBody", "BodyFrame", "body_frame", "Link", "joint", "oscillator", "rod",
           "ROD_ENDS",
           "Model",
           "BOUNDARY_CONDITIONS", "GROUND", "SPRING_KINDS"]

#: Boundary conditions and the state variables (of Y, Theta, M, Q) they set to zero.
BOUNDARY_CONDITIONS: Mapping[str, tuple[str, str]] = {
    "free": ("M", "Q"),
    "clamped": ("Y", "Theta"),
    "pinned": ("Y", "M"),
    "sliding": ("Theta", "Q"),
}
#: Name standing for the ground in :attr:`Spring.b`.
GROUND = "ground"
#: What a spring resists: the transverse displacement Y or the rotation Theta.
SPRING_KINDS = ("translational", "rotational")

# matched with fullmatch: "$" would also accept a name ending in a newline
_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")


def _exact(value, field_name: str) -> sp.Expr:
    """Turn a number, SymPy expression or restricted-expression string into SymPy."""
    try:
        if isinstance(value, sp.Basic):
            expr = value
        elif isinstance(value, str):
            expr = parse_expression(value)
        else:
            expr = exact_number(value)
    except ExpressionError as exc:
        raise ModelError(str(exc), field=field_name) from None
    if expr.has(sp.Float):
        raise ModelError("inexact floating-point number in an exact expression", field=field_name)
    if expr.is_number and not expr.is_real:
        raise ModelError("must be a real number", field=field_name)
    return expr


def short(value) -> str:
    """A number for a message: exact if short, else 6 significant digits.

    Never the full decimal expansion of a long rational (whose text may exceed
    what Python converts at all).

    Examples
    --------
    >>> short(sp.Rational(3, 10)), short(sp.Rational(1, 3)), short(sp.Integer(10)**40)
    ('3/10', '1/3', '1.00000e+40')
    """
    value = sp.sympify(value)
    if value.is_Rational and max(abs(int(value.p)), int(value.q)) < 10**12:
        return str(value)
    if value.is_number:
        return str(sp.N(value, 6))
    text = str(value)
    return text if len(text) <= 60 else text[:57] + "..."


def _check_magnitude(value: sp.Expr, field_name: str) -> None:
    """A numeric field is 0 or within ``FIELD_MIN .. FIELD_MAX`` in magnitude (:mod:`symtmm.limits`).

    Measured by :func:`symtmm.expr.decades`: a sum that cancels to almost
    nothing (``pi - 3.14159265358979``) is measured by its value, not its parts.
    """
    if not value.is_number or value.is_zero:
        return
    if value.is_real is False:
        raise ModelError("must be a real number", field=field_name)
    try:
        size = decades(value)
    except ExpressionError as exc:
        raise ModelError(str(exc), field=field_name) from None
    if not math.log10(FIELD_MIN) <= size <= math.log10(FIELD_MAX):
        raise ModelError(f"must be 0 or between {FIELD_MIN:g} and {FIELD_MAX:g} in magnitude, "
                         f"got {short(value)}", field=field_name)


def _negative(d: sp.Expr) -> bool:
    """``d < 0`` for a number (a rational by its numerator: sympy's assumptions cost a
    fraction of a millisecond on every new number, and a sweep makes many)."""
    return d.p < 0 if d.is_Rational else bool(d.is_negative)


def _check_sign(expr: sp.Expr, field_name: str, allow_zero: bool) -> None:
    if not expr.is_number:
        return
    zero = expr == 0 if expr.is_Rational else expr.is_zero
    if _negative(expr) or (zero and not allow_zero):
        raise ModelError("must be positive" if not allow_zero else "must not be negative",
                         field=field_name)


def _check_inside(x: sp.Expr, beam, field_name: str) -> None:
    """``x`` lies on ``beam`` (ends included), where both are numbers."""
    inside = [(x - beam.x0), (beam.x1 - x)]
    if all(d.is_number for d in inside) and any(_negative(d) for d in inside):
        # (how far past it, also where x rounds to the end in 6 digits: 0.87 + 1e-16)
        past, end = (-inside[0], "start") if _negative(inside[0]) else (-inside[1], "end")
        raise ModelError(f"x = {short(x)} lies outside beam '{beam.name}' "
                         f"[{short(beam.x0)}, {short(beam.x1)}], {short(past)} beyond its "
                         f"{end}", field=field_name)


@dataclass(frozen=True)
class Beam:
    """An Euler–Bernoulli beam (one level).

    Parameters
    ----------
    name : str
        Identifier, unique within a model.
    EI : number or str
        Bending stiffness.
    m : number or str
        Mass per unit length.
    L : number or str
        Length.
    x0 : number or str, optional
        Global coordinate of the left end (default 0).
    left, right : str
        Boundary conditions: ``free``, ``clamped``, ``pinned`` or ``sliding``.
    kw : number or str, optional
        Stiffness per unit length of a Winkler foundation under the beam (not
        negative, default 0): the field equation becomes
        ``EI Y'''' + (kw + m λ²) Y = 0``.
    theory : str, optional
        ``"euler-bernoulli"`` (default), ``"rayleigh"`` (rotary inertia
        ``rhoI``) or ``"timoshenko"`` (rotary inertia ``rhoI`` and shear
        stiffness ``kGA``); see :mod:`symtmm.elements.theories`.
    N : number or str, optional
        Axial force, tension positive (default 0), with any theory.
    origin : pair of numbers, optional
        The left end's point in the plane of a frame (default ``(x0, 0)``).
    axis : pair of numbers, optional
        The member's direction ``(cos a, sin a)`` in the plane (default ``(1, 0)``, the
        ``x`` axis). A member at an angle meets others through joints only
        (:func:`joint`); its coordinate ``x`` runs from ``x0`` to ``x0 + L`` as for any
        beam, its point at ``x`` is ``origin + (x - x0) axis`` (:meth:`point`), and its
        deflection ``Y`` is along the normal ``(-sin a, cos a)`` (a rod's axial motion
        along ``axis``).
    rhoI : number or str, optional
        Rotary inertia per unit length (``rho I``, not negative); needed by
        the Rayleigh and Timoshenko theories.
    kGA : number or str, optional
        Shear stiffness ``kappa G A`` (positive); needed by the Timoshenko theory.

    Examples
    --------
    >>> Beam("b", EI=1, m=1, L=1, kw="1/2").kw
    1/2
    >>> Beam("t", EI=1, m=1, L=1, theory="timoshenko", rhoI="1/1000", kGA=400).kGA
    400
    """

    name: str
    EI: sp.Expr
    m: sp.Expr
    L: sp.Expr
    x0: sp.Expr = 0  # made exact in __post_init__
    left: str = "free"
    right: str = "free"
    kw: sp.Expr = 0  # made exact in __post_init__
    theory: str = "euler-bernoulli"
    N: sp.Expr = 0  # made exact in __post_init__
    rhoI: sp.Expr = 0  # made exact in __post_init__
    kGA: sp.Expr | None = None
    origin: tuple | None = None  # made exact in __post_init__
    axis: tuple = (1, 0)  # made exact in __post_init__

    def __post_init__(self):
        where = f"{self.kind} '{self.name}'"
        self._check_geometry(where)
        if not isinstance(self.name, str) or not _IDENTIFIER.fullmatch(self.name) or self.name == GROUND:
            raise ModelError(f"invalid name {self.name!r} (an identifier other than 'ground')",
                             field=f"{self.kind}.name")
        for attr in ("EI", "m", "L", "x0", "kw", "N", "rhoI"):
            field_name = f"{where}.{self.field_name(attr)}"
            value = _exact(getattr(self, attr), field_name)
            object.__setattr__(self, attr, value)
            if attr not in ("x0", "N") or (attr == "N" and self.is_rod):
                _check_sign(value, field_name, allow_zero=attr in ("kw", "rhoI"))
        if self.theory not in THEORIES:
            raise ModelError(f"unknown theory {self.theory!r} (use one of {', '.join(THEORIES)})",
                             field=f"{where}.theory")
        if self.is_rod:
            self._check_rod(where)
            return
        if self.kGA is not None:
            if self.theory != "timoshenko":
                raise ModelError("a shear stiffness needs theory = \"timoshenko\"",
                                 field=f"{where}.kGA")
            value = _exact(self.kGA, f"{where}.kGA")
            object.__setattr__(self, "kGA", value)
            _check_sign(value, f"{where}.kGA", allow_zero=False)
        elif self.theory == "timoshenko":
            raise ModelError("a Timoshenko beam needs its shear stiffness kGA", field=f"{where}.kGA")
        if self.theory == "euler-bernoulli" and self.rhoI != 0:
            raise ModelError("rotary inertia needs theory = \"rayleigh\" or \"timoshenko\"",
                             field=f"{where}.rhoI")
        for attr in ("left", "right"):
            bc = getattr(self, attr)
            if bc not in BOUNDARY_CONDITIONS:
                raise ModelError(f"unknown boundary condition {bc!r} "
                                 f"(use one of {', '.join(BOUNDARY_CONDITIONS)})",
                                 field=f"{where}.{attr}")

    def _check_geometry(self, where: str) -> None:
        """``origin`` and ``axis`` pairs of exact numbers, ``axis`` a unit vector."""
        for attr in ("origin", "axis"):
            pair = getattr(self, attr)
            if pair is None:
                continue
            if not isinstance(pair, (tuple, list)) or len(pair) != 2:
                raise ModelError("expected a pair of numbers", field=f"{where}.{attr}")
            pair = tuple(_exact(v, f"{where}.{attr}") for v in pair)
            if not all(v.is_number for v in pair):
                raise ModelError("must be numbers (a member's place in the plane takes no "
                                 "parameter)", field=f"{where}.{attr}")
            object.__setattr__(self, attr, pair)
        axis = self.axis
        norm = sp.nsimplify(sp.expand(axis[0]**2 + axis[1]**2 - 1))
        if not (norm == 0 or sp.simplify(norm) == 0):
            raise ModelError("must be a unit vector (cos a, sin a)", field=f"{where}.axis")

    @property
    def along_x(self) -> bool:
        """True for a member along the ``x`` axis (the levels of a multilevel model)."""
        return self.axis == (1, 0)

    @property
    def direction(self) -> tuple:
        """The direction of the motion in the slot ``Y``, in the plane: a beam's deflection
        along the normal ``(-sin a, cos a)``, a rod's axial motion along its axis."""
        c, s = self.axis
        return (c, s) if self.is_rod else (-s, c)

    def point(self, x) -> tuple:
        """The point of the plane at the member's coordinate ``x`` (exact).

        Examples
        --------
        >>> Beam("c", 1, 1, 3, axis=(0, 1), origin=(0, 2)).point(3)
        (0, 5)
        """
        d = sp.sympify(x) - self.x0
        o = (self.x0, sp.Integer(0)) if self.origin is None else self.origin
        return (o[0] + d * self.axis[0], o[1] + d * self.axis[1])

    def _check_rod(self, where: str) -> None:
        """A rod's internal fields as :func:`rod` sets them: ``kGA = 0``, the state ends."""
        if self.kGA is None or sp.sympify(self.kGA) != 0:
            raise ModelError("a rod is built by symtmm.model.rod (kGA = 0)", field=where)
        object.__setattr__(self, "kGA", sp.Integer(0))
        for attr in ("left", "right"):
            bc = getattr(self, attr)
            allowed = {v[attr == "right"] for v in
                       (ROD_ENDS if self.torsion else ROD_ENDS_AXIAL).values()}
            if bc not in allowed:
                if not self.torsion and bc in {v[attr == "right"] for v in ROD_ENDS.values()}:
                    # built with GJ and rhoIp, and rhoIp came out 0 (a parameter's value)
                    raise ModelError("must be positive (a rod with GJ vibrates in torsion)",
                                     field=f"{where}.rhoIp")
                raise ModelError(f"not a rod end {bc!r} (build rods with symtmm.model.rod)",
                                 field=f"{where}.{attr}")

    @property
    def kind(self) -> str:
        """``"rod"`` for a rod, else ``"beam"`` (the word errors and output use)."""
        return "rod" if self.is_rod else "beam"

    @property
    def is_rod(self) -> bool:
        """A rod in axial (and torsional) vibration: see :func:`rod`."""
        return self.theory == "rod"

    @property
    def torsion(self) -> bool:
        """A rod that also vibrates in torsion (it has a polar inertia ``rhoIp``)."""
        return self.is_rod and self.rhoI != 0

    def field_name(self, attr: str) -> str:
        """The model-file field of an attribute: a rod's ``EI``, ``N`` and ``rhoI`` are its
        ``GJ``, ``EA`` and ``rhoIp``."""
        if self.is_rod:
            return {"EI": "GJ", "N": "EA", "rhoI": "rhoIp"}.get(attr, attr)
        return attr

    def end(self, side: str) -> str:
        """The boundary condition at ``side`` (``"left"``/``"right"``) as the model file says
        it (a rod's ``fixed``, ``free``, ...)."""
        bc = getattr(self, side)
        if not self.is_rod:
            return bc
        table = ROD_ENDS if self.torsion else ROD_ENDS_AXIAL
        return next(k for k, v in table.items() if v[side == "right"] == bc)

    @property
    def x1(self) -> sp.Expr:
        """Global coordinate of the right end."""
        return self.x0 + self.L

    @property
    def plain(self) -> bool:
        """True for an Euler–Bernoulli beam without axial force (the fast element)."""
        return self.theory == "euler-bernoulli" and self.N == 0

    def segment(self, length):
        """The element of a piece of this beam, ``length`` long.

        :class:`~symtmm.elements.beam.EulerBernoulliSegment` for a plain beam,
        :class:`~symtmm.elements.theories.BeamSegment` otherwise.
        """
        if self.plain:
            return EulerBernoulliSegment(self.EI, self.m, length, self.kw)
        return BeamSegment(self.EI, self.m, length, self.kw, self.N, self.rhoI, self.kGA)


#: The ends of a rod and the boundary conditions of the state they are. A rod's state is
#: ``(u, phi, T, -N)`` in the slots ``(Y, Theta, M, Q)``: axial displacement, twist, torque
#: and the axial force with the sign of a transverse force (see :func:`rod`).
ROD_ENDS = {"fixed": ("clamped", "clamped"), "free": ("free", "free"),
            "fixed-axial": ("pinned", "pinned"), "fixed-torsion": ("sliding", "sliding")}
#: The ends of a rod without torsion: its torsion (massless) is held at the left end.
ROD_ENDS_AXIAL = {"fixed": ("clamped", "pinned"), "free": ("sliding", "free")}


def rod(name: str, EA, m, L, x0=0, left: str = "fixed", right: str = "fixed", kw=0,
        GJ=None, rhoIp=None, origin=None, axis=(1, 0)) -> Beam:
    """A rod in axial vibration, and in torsion where ``GJ`` and ``rhoIp`` are given (one level).

    Axially ``EA u'' = (m lam**2 + kw) u``, in torsion ``GJ phi'' = rhoIp lam**2 phi``; the two
    are independent along a straight rod. Its state ``(u, phi, T, -N)`` (axial displacement,
    twist, torque ``GJ phi'``, axial force ``N = EA u'`` with the sign of a transverse force)
    is the first-order system of :class:`~symtmm.elements.theories.BeamSegment` with ``kGA = 0``
    (``Y' = b Q``, ``b = -1/EA``; ``Theta' = M / GJ``, ``M' = rhoIp lam**2 Theta``; ``Q' = -mu
    Y``), so every formulation of the package takes it as it comes: a spring (dashpot, mass)
    on it acts axially, a rotational one in torsion.

    Parameters
    ----------
    name : str
    EA, m, L : number or str
        Axial stiffness, mass per unit length, length.
    x0 : number or str, optional
        Global coordinate of the left end.
    left, right : str
        ``"fixed"`` or ``"free"``; with torsion also ``"fixed-axial"`` (``u = 0``, free to
        twist) and ``"fixed-torsion"`` (``phi = 0``, free to move axially).
    kw : number or str, optional
        An axial foundation per unit length (``kw u`` resists the motion).
    GJ, rhoIp : number or str, optional
        Torsional stiffness and polar inertia per unit length, both or neither. Without
        them the rod carries no torsion (inside, a massless twist held at its left end,
        which adds no eigenvalue: rotational springs and inertias are refused on it).
    origin, axis : optional
        Its place in the plane (:class:`Beam`), for the axial part of a frame member.

    Examples
    --------
    >>> r = rod("r", EA=2, m=1, L=1, left="fixed", right="free")
    >>> r.kind, r.end("left"), r.end("right"), r.torsion
    ('rod', 'fixed', 'free', False)
    >>> rod("t", EA=2, m=1, L=1, GJ=1, rhoIp="1/10", left="fixed-axial").end("left")
    'fixed-axial'
    """
    where = f"rod '{name}'"
    if (GJ is None) != (rhoIp is None):
        raise ModelError("torsion needs both GJ and rhoIp", field=f"{where}."
                         + ("rhoIp" if rhoIp is None else "GJ"))
    torsion = GJ is not None
    table = ROD_ENDS if torsion else ROD_ENDS_AXIAL
    ends = []
    for i, (side, bc) in enumerate((("left", left), ("right", right))):
        if not isinstance(bc, str) or bc not in table:
            raise ModelError(f"unknown rod end {bc!r} (use one of {', '.join(table)})",
                             field=f"{where}.{side}")
        ends.append(table[bc][i])
    EA_exact = _exact(EA, f"{where}.EA")
    L_exact = _exact(L, f"{where}.L")
    for value, what in ((EA_exact, "EA"), (L_exact, "L")):
        _check_sign(value, f"{where}.{what}", allow_zero=False)
    # without torsion the twist's stiffness only scales a constant factor of Delta: EA L**2
    # keeps it of the axial stiffness's order
    stiffness = GJ if torsion else EA_exact * L_exact**2
    if torsion:
        rhoIp_exact = _exact(rhoIp, f"{where}.rhoIp")
        if rhoIp_exact.is_number and not rhoIp_exact.is_positive:
            raise ModelError(f"must be positive, got {short(rhoIp_exact)}", field=f"{where}.rhoIp")
    return Beam(name, stiffness, m, L_exact, x0, left=ends[0], right=ends[1], kw=kw,
                theory="rod", N=EA_exact, rhoI=rhoIp if torsion else 0, kGA=0, origin=origin, axis=axis)


@dataclass(frozen=True)
class Spring:
    """A spring/dashpot between two beams, or between a beam and the ground.

    The force ``F = (k + c λ)(Y_b − Y_a)`` acts on beam ``a`` and ``−F`` on
    beam ``b`` at the global coordinate ``x``.

    Parameters
    ----------
    a : str
        Name of the first beam.
    b : str
        Name of the second beam, or ``"ground"``.
    x : number or str
        Global coordinate; must lie inside both beams (ends included).
    k : number or str
        Stiffness (not negative).
    c : number or str, optional
        Dashpot coefficient (not negative), default 0.
    kind : str, optional
        ``"translational"`` (default: force on Y, ``k`` in force/length) or
        ``"rotational"`` (moment on Theta, ``k`` in moment/radian): then the
        moment ``(k + c λ)(Θ_b − Θ_a)`` acts on ``a`` and its opposite on ``b``.
    """

    a: str
    b: str
    x: sp.Expr
    k: sp.Expr
    c: sp.Expr = 0  # made exact in __post_init__
    kind: str = "translational"

    def __post_init__(self):
        if self.a == GROUND and self.b != GROUND:
            a, b = self.b, self.a
            object.__setattr__(self, "a", a)
            object.__setattr__(self, "b", b)
        where = f"spring {self.a}-{self.b}"
        if self.kind not in SPRING_KINDS:
            raise ModelError(f"unknown kind {self.kind!r} (use one of {', '.join(SPRING_KINDS)})",
                             field=f"{where}.kind")
        if self.a == self.b:
            raise ModelError("a spring must join two different beams", field=f"{where}.between")
        for attr in ("x", "k", "c"):
            value = _exact(getattr(self, attr), f"{where}.{attr}")
            object.__setattr__(self, attr, value)
            if attr != "x":
                _check_sign(value, f"{where}.{attr}", allow_zero=True)

    @property
    def grounded(self) -> bool:
        """True for a spring from beam ``a`` to the ground."""
        return self.b == GROUND


@dataclass(frozen=True)
class Mass:
    """A lumped mass with rotary inertia attached to a beam.

    Its inertia forces ``−M λ² Y`` and ``−J λ² Θ`` act on the beam at ``x``.

    Parameters
    ----------
    beam : str
        Name of the beam carrying it.
    x : number or str
        Global coordinate; must lie on the beam (ends included).
    M : number or str
        Mass (not negative).
    J : number or str, optional
        Rotary inertia about the beam's neutral axis (not negative), default 0.

    Examples
    --------
    >>> Mass("a", x="1/2", M=2).J
    0
    """

    beam: str
    x: sp.Expr
    M: sp.Expr
    J: sp.Expr = 0  # made exact in __post_init__

    def __post_init__(self):
        where = f"mass on {self.beam}"
        for attr in ("x", "M", "J"):
            value = _exact(getattr(self, attr), f"{where}.{attr}")
            object.__setattr__(self, attr, value)
            if attr != "x":
                _check_sign(value, f"{where}.{attr}", allow_zero=True)


@dataclass(frozen=True)
class Layer:
    """A continuous elastic layer (with viscous damping) between two beams over ``[x0, x1]``.

    Per unit length the force ``(k + c λ)(Y_b − Y_a)`` acts on beam ``a`` and its
    opposite on beam ``b`` (Vu et al.'s elastically connected double beam; with
    ``c``, a viscoelastic layer of Kelvin–Voigt type). Over the layer the two
    beams are one coupled member whose state holds both beams' ``(Y, Θ, M, Q)``
    (:mod:`symtmm.numeric.segments`); both must be Euler–Bernoulli beams without
    axial force (a Winkler foundation is allowed).

    Parameters
    ----------
    a, b : str
        Names of the two beams.
    k : number or str
        Stiffness per unit length (not negative).
    c : number or str, optional
        Damping per unit length (not negative), default 0.
    x0, x1 : number or str, optional
        Global coordinates of the layer's ends; default the overlap of the two
        beams (set by :class:`Model`).

    Examples
    --------
    >>> Layer("upper", "lower", k=100, x0="1/4").x1 is None
    True
    """

    a: str
    b: str
    k: sp.Expr
    c: sp.Expr = 0  # made exact in __post_init__
    x0: sp.Expr | None = None
    x1: sp.Expr | None = None

    def __post_init__(self):
        where = f"layer {self.a}-{self.b}"
        if GROUND in (self.a, self.b):
            raise ModelError("a layer joins two beams (for a foundation under one beam use "
                             "the beam's kw)", field=f"{where}.between")
        if self.a == self.b:
            raise ModelError("a layer must join two different beams", field=f"{where}.between")
        for attr in ("k", "c", "x0", "x1"):
            value = getattr(self, attr)
            if value is None:
                continue
            value = _exact(value, f"{where}.{ {'x0': 'from', 'x1': 'to'}.get(attr, attr)}")
            object.__setattr__(self, attr, value)
            if attr in ("k", "c"):
                _check_sign(value, f"{where}.{attr}", allow_zero=True)


@dataclass(frozen=True)
class Attachment:
    """Where a rigid body holds a beam: the point ``x`` of beam ``beam``.

    A rigid attachment makes the beam's deflection and rotation there those
    of the body; a hinged one only its deflection (the beam turns freely); an
    elastic one (``k`` given) joins the beam's deflection to the body's point
    above it by a spring ``k`` and dashpot ``c``: the force ``(k + c lam)(Y_body
    - Y_beam)`` acts on the beam and its opposite on the body (a sprung mass).

    Examples
    --------
    >>> Attachment("a", "1/2", hinged=True).x
    1/2
    >>> Attachment("a", "1/2", k=100, c="1/10").elastic
    True
    """

    beam: str
    x: sp.Expr
    hinged: bool = False
    k: sp.Expr | None = None
    c: sp.Expr = 0  # made exact in __post_init__

    def __post_init__(self):
        where = f"attachment on {self.beam}"
        object.__setattr__(self, "x", _exact(self.x, f"{where}.x"))
        if not isinstance(self.hinged, bool):
            raise ModelError("expected true or false", field=f"{where}.hinged")
        if self.k is None:
            if self.c != 0:
                raise ModelError("a dashpot needs an elastic attachment (give k)",
                                 field=f"{where}.c")
            return
        if self.hinged:
            raise ModelError("an elastic attachment is not also hinged", field=f"{where}.hinged")
        for attr in ("k", "c"):
            value = _exact(getattr(self, attr), f"{where}.{attr}")
            object.__setattr__(self, attr, value)
            _check_sign(value, f"{where}.{attr}", allow_zero=True)

    @property
    def elastic(self) -> bool:
        """True when a spring (and dashpot) joins the beam to the body."""
        return self.k is not None


@dataclass(frozen=True)
class RigidBody:
    """A rigid body (mass ``M``, rotary inertia ``J`` about its centre of mass ``(xc, yc)``).

    It moves in the plane of the beams (a translation and a rotation ``Theta_c``
    about its centre) and holds them at its :class:`Attachment` points: carried by one
    beam, or linking several (joints of beam ends, trees, closed loops, the joints of
    a planar frame). A joint of beam ends is a massless body whose attachments meet at
    one point; a sprung mass (tuned mass damper) a body held by elastic attachments
    only (:func:`oscillator`). Which motions it has follows from where it holds what
    (:meth:`Model.body_frame`): a translation along the common direction of every
    attached motion, or both translations of the plane where members meet at an angle.

    Parameters
    ----------
    name : str
    attachments : tuple of Attachment
    M, J : number or str, optional
        Mass and rotary inertia about the centre of mass (default 0).
    xc, yc : number or str, optional
        Centre of mass in the plane (default: the first attachment's point).
    fixed : tuple of str, optional
        Freedoms a support holds at zero (``"Y"``, ``"X"``, ``"Theta"``; a node of a
        planar frame pinned or clamped); ``"X"`` makes the body translate in the plane.
    ground : tuple of (str, number or str, number or str), optional
        Springs and dashpots ``(freedom, k, c)`` from a freedom of the body to the ground:
        an elastic support (the force ``-(k + c lam) q`` on it).
    axes : pair of numbers, optional
        The direction of the body's ``X`` in the plane (default the plane's x; ``Y`` is
        ``X`` turned by 90 degrees): an inclined support holds ``Y`` along its normal.

    Examples
    --------
    >>> body = RigidBody("fork", (Attachment("trunk", 1), Attachment("branch", 1)))
    >>> [a.beam for a in body.attachments], body.M
    (['trunk', 'branch'], 0)
    """

    name: str
    attachments: tuple
    M: sp.Expr = 0  # made exact in __post_init__
    J: sp.Expr = 0  # made exact in __post_init__
    xc: sp.Expr | None = None
    yc: sp.Expr | None = None
    fixed: tuple = ()
    ground: tuple = ()
    axes: tuple | None = None

    def __post_init__(self):
        where = f"body '{self.name}'"
        if self.axes is not None:
            axes = tuple(_exact(v, f"{where}.axes") for v in self.axes)
            if len(axes) != 2 or not all(v.is_number for v in axes) \
                    or sp.simplify(axes[0]**2 + axes[1]**2 - 1) != 0:
                raise ModelError("expected a unit vector (cos a, sin a)", field=f"{where}.axes")
            object.__setattr__(self, "axes", axes)
        ground = []
        for item in self.ground:
            if not (isinstance(item, (tuple, list)) and len(item) == 3
                    and item[0] in ("X", "Y", "Theta")):
                raise ModelError("expected (freedom, k, c) with freedom X, Y or Theta",
                                 field=f"{where}.ground")
            label = item[0]
            values = []
            for what, v in zip(("k", "c"), item[1:]):
                value = _exact(v, f"{where}.{what}{label.lower()}")
                _check_sign(value, f"{where}.{what}{label.lower()}", allow_zero=True)
                values.append(value)
            ground.append((label, *values))
        if len({g[0] for g in ground}) != len(ground):
            raise ModelError("one spring per freedom", field=f"{where}.ground")
        object.__setattr__(self, "ground", tuple(ground))
        fixed = tuple(self.fixed)
        if not all(isinstance(f, str) and f in ("X", "Y", "Theta") for f in fixed) \
                or len(set(fixed)) != len(fixed):
            raise ModelError("expected some of \"X\", \"Y\", \"Theta\", once each",
                             field=f"{where}.fixed")
        object.__setattr__(self, "fixed", fixed)
        if not isinstance(self.name, str) or not _IDENTIFIER.fullmatch(self.name):
            raise ModelError(f"invalid name {self.name!r}", field="rigid.name")
        attachments = tuple(self.attachments)
        if not attachments or not all(isinstance(a, Attachment) for a in attachments):
            raise ModelError("a rigid body needs at least one attachment", field=f"{where}.attach")
        object.__setattr__(self, "attachments", attachments)
        for attr in ("M", "J"):
            value = _exact(getattr(self, attr), f"{where}.{attr}")
            object.__setattr__(self, attr, value)
            _check_sign(value, f"{where}.{attr}", allow_zero=True)
        for attr in ("xc", "yc"):
            if getattr(self, attr) is not None:
                object.__setattr__(self, attr, _exact(getattr(self, attr), f"{where}.{attr}"))


#: The mesh's number of each freedom of a body (``("b", body, number)``).
FREEDOM_INDEX = {"Y": 0, "Theta": 1, "X": 2}


@dataclass(frozen=True)
class BodyFrame:
    """How a rigid body moves the points it holds (:meth:`Model.body_frame`).

    The body's freedoms are labelled ``"Y"`` (a translation), ``"Theta"`` (its rotation,
    where anything feels it) and ``"X"`` (the second translation, where the attached
    motions are not all parallel: members of a frame at an angle). With one translation
    it is along the first attachment's motion (a beam's deflection, a rod's axial
    motion); with two, ``"Y"`` and ``"X"`` are the plane's ``y`` and ``x``.

    Attributes
    ----------
    freedoms : tuple of str
        In the order ``"Y"``, ``"Theta"``, ``"X"`` (those it has).
    directions : dict
        Translation label -> exact unit vector in the plane.
    rows : tuple of dict
        Per attachment, ``{label: coefficient}``: the attached point's motion along the
        attached member's ``Y`` direction is ``sum(coefficient * freedom)``.
    turns : tuple of bool
        Per attachment, whether the member's rotation is the body's (rigid, on a beam).
    centre : tuple
        The centre of mass ``(xc, yc)``.
    """

    freedoms: tuple
    directions: dict
    rows: tuple
    turns: tuple
    centre: tuple

    @property
    def rotates(self) -> bool:
        """Whether the body's rotation is an unknown of its own."""
        return "Theta" in self.freedoms

    @property
    def planar(self) -> bool:
        """Whether the body translates in both directions of the plane."""
        return "X" in self.freedoms

    def index(self, label: str) -> int:
        """The freedom number of a label in the mesh: Y 0, Theta 1, X 2."""
        return FREEDOM_INDEX[label]

    def mass(self, body, label: str):
        """The inertia of a freedom: ``M`` for a translation, ``J`` for the rotation."""
        return body.J if label == "Theta" else body.M


@dataclass(frozen=True)
class Link:
    """An inextensible bar: the motions of its two ends along ``axis`` are equal.

    The axial part of an inextensible frame member (:class:`symtmm.frame.Member` with
    ``EA = None``): ``a`` and ``b`` are the bodies (joints) at its ends, or ``"ground"``
    for a supported end, or ``None`` for a free end; its mass ``M`` (``m L``) moves
    along ``axis`` with them. ``t . q_a = t . q_b`` is a constraint of the stiffness
    formulation and, in the transfer walk, an unknown axial force with its equation.

    Examples
    --------
    >>> Link("bar", "j1", "ground", (0, 1), M=3).ends
    ('j1', 'ground')
    """

    name: str
    a: str | None
    b: str | None
    axis: tuple
    M: sp.Expr = 0  # made exact in __post_init__

    def __post_init__(self):
        where = f"link '{self.name}'"
        axis = tuple(_exact(v, f"{where}.axis") for v in self.axis)
        if len(axis) != 2 or not all(v.is_number for v in axis):
            raise ModelError("expected a pair of numbers", field=f"{where}.axis")
        object.__setattr__(self, "axis", axis)
        value = _exact(self.M, f"{where}.M")
        _check_sign(value, f"{where}.M", allow_zero=True)
        object.__setattr__(self, "M", value)
        if self.a is None and self.b is None:
            raise ModelError("an inextensible member needs a joint or a support at one end "
                             "(its axial motion would be held by nothing)", field=where)

    @property
    def ends(self) -> tuple:
        """``(a, b)``."""
        return (self.a, self.b)

    def bodies(self) -> list:
        """``(body name, sign)`` of the ends that are bodies: ``t . (q_a - q_b)``."""
        return [(e, sign) for e, sign in ((self.a, 1), (self.b, -1)) if e not in (None, GROUND)]


def _nonzero(expr) -> bool:
    """An exact expression that is not identically zero (a symbol's may be: assume not)."""
    expr = sp.sympify(expr)
    return expr != 0 if expr.is_Rational else sp.simplify(expr) != 0


def _tidy(expr) -> sp.Expr:
    """``expr`` expanded, a rational as it is (SymPy's expansion costs microseconds, and
    the geometry of most models is rational)."""
    return expr if isinstance(expr, sp.Rational) else sp.expand(expr)


def body_frame(body: RigidBody, beams: dict, links=()) -> BodyFrame:
    """The :class:`BodyFrame` of ``body`` among ``beams`` (name -> :class:`Beam`) and the
    :class:`Link` s of a model (those ending at the body pull along their axes).

    A freedom the body's support holds (``body.fixed``) is not one of its freedoms: the
    attached motions are held with it.

    Examples
    --------
    A joint of a column and a beam at a right angle moves in both directions:

    >>> beams = {"c": Beam("c", 1, 1, 1, axis=(0, 1)), "b": Beam("b", 1, 1, 1, origin=(0, 1))}
    >>> f = body_frame(joint("j", [("c", 1), ("b", 0)]), beams)
    >>> f.freedoms, f.rows
    (('Y', 'Theta', 'X'), ({'X': -1}, {'Y': 1}))
    """
    atts = body.attachments
    dirs = [beams[a.beam].direction for a in atts]
    points = [beams[a.beam].point(a.x) for a in atts]
    pulls = [ln.axis for ln in links if body.name in ln.ends]
    d0 = dirs[0]
    planar = "X" in body.fixed or body.axes is not None or any(_nonzero(d0[0] * d[1] - d0[1] * d[0])
                                      for d in dirs[1:] + pulls)
    if planar:
        ax = (sp.Integer(1), sp.Integer(0)) if body.axes is None else body.axes
        directions = {"Y": (-ax[1], ax[0]), "X": ax}
    else:
        directions = {"Y": d0}
    centre = (points[0][0] if body.xc is None else body.xc,
              points[0][1] if body.yc is None else body.yc)
    turns = tuple(not (a.hinged or a.elastic or beams[a.beam].is_rod) for a in atts)
    # the motion of the point P along d under a rotation Theta about C: Theta (d x (P - C))
    arms = [_tidy(d[1] * (p[0] - centre[0]) - d[0] * (p[1] - centre[1]))
            for d, p in zip(dirs, points)]
    # (a J that nothing it holds feels is refused by the model: a free rotation)
    rotates = any(turns) or any(_nonzero(a) for a in arms)
    rows = []
    for d, arm in zip(dirs, arms):
        row = {}
        for label, e in directions.items():
            coef = _tidy(d[0] * e[0] + d[1] * e[1])
            if coef.is_number and not coef.is_Rational:
                coef = sp.nsimplify(coef)
            if coef != 0:
                row[label] = coef
        if rotates and arm != 0:
            row["Theta"] = arm
        rows.append(row)
    freedoms = ("Y",) + (("Theta",) if rotates else ()) + (("X",) if planar else ())
    freedoms = tuple(f for f in freedoms if f not in body.fixed)
    rows = [{label: a for label, a in row.items() if label in freedoms} for row in rows]
    return BodyFrame(freedoms, directions, tuple(rows), turns, centre)


def joint(name: str, points, kind: str = "rigid", M=0, J=0) -> RigidBody:
    """Beam ends (or points) that meet at one ``x``, joined (``[[joint]]`` of a model file).

    Parameters
    ----------
    name : str
    points : sequence of (str, number or str)
        ``(beam, x)`` of every end joined; all at the same ``x``.
    kind : {"rigid", "hinge"}
        Deflections and rotations equal (rigid), or deflections only (every end turns
        freely).
    M, J : number or str, optional
        A mass and rotary inertia at the joint.

    Examples
    --------
    >>> j = joint("fork", [("trunk", 1), ("left", 1), ("right", 1)])
    >>> [(a.beam, a.hinged) for a in j.attachments]
    [('trunk', False), ('left', False), ('right', False)]
    >>> all(a.hinged for a in joint("pin", [("a", 1), ("b", 1)], kind="hinge").attachments)
    True
    """
    if kind not in ("rigid", "hinge"):
        raise ModelError(f"unknown kind {kind!r} (use rigid or hinge)", field=f"joint '{name}'.kind")
    return RigidBody(name, tuple(Attachment(b, x, hinged=kind == "hinge") for b, x in points),
                     M=M, J=J)


def oscillator(name: str, beams, x, M, k, c=0) -> RigidBody:
    """A sprung mass (tuned mass damper): mass ``M`` on a spring ``k`` and dashpot ``c``.

    On one beam, or between two (Gürgöze and Erol's double beam: the mass joined
    to each by its own spring and dashpot), at the global coordinate ``x``; the
    mass moves transversely only. It is a :class:`RigidBody` held by elastic
    attachments, so every formulation treats it as one: its deflection is a
    freedom of the dynamic stiffness (no pole at its own frequency ``sqrt(k/M)``
    enters the count) and a virtual state variable of the transfer walk.

    Parameters
    ----------
    name : str
    beams : str or sequence of str
        The beam carrying it, or the two it joins.
    x : number or str
    M : number or str
        The mass (positive).
    k, c : number or str, or a sequence of one per beam
        Spring stiffness and dashpot coefficient.

    Examples
    --------
    >>> tmd = oscillator("tmd", "b", x="1/2", M="1/10", k=10)
    >>> [(a.beam, a.k) for a in tmd.attachments]
    [('b', 10)]
    >>> both = oscillator("m", ("a", "b"), x=1, M=1, k=(2, 3), c=(0, "1/2"))
    >>> [(a.beam, a.k, a.c) for a in both.attachments]
    [('a', 2, 0), ('b', 3, 1/2)]
    """
    beams = (beams,) if isinstance(beams, str) else tuple(beams)
    if len(beams) not in (1, 2) or not all(isinstance(b, str) for b in beams):
        raise ModelError("expected one beam or two", field=f"body '{name}'.beam")

    def per_beam(value, what):
        values = tuple(value) if isinstance(value, (list, tuple)) else (value,) * len(beams)
        if len(values) != len(beams):
            raise ModelError(f"expected one {what} per beam ({len(beams)})",
                             field=f"body '{name}'.{what}")
        return values
    ks, cs = per_beam(k, "k"), per_beam(c, "c")
    return RigidBody(name, tuple(Attachment(b, x, k=kb, c=cb) for b, kb, cb in zip(beams, ks, cs)),
                     M=M, xc=x)


def _parallel(resolved: dict, ends, field_name: str, what: str) -> None:
    """Couplings at a coordinate ``x`` join members along the ``x`` axis only."""
    ends = [e for e in ends if e != GROUND]
    if len(ends) > 1 and any(not resolved[e].along_x for e in ends):
        name = next(e for e in ends if not resolved[e].along_x)
        raise ModelError(f"{what} joins members along the x axis at one x; '{name}' lies at "
                         "an angle (join a frame's members at their ends, by a joint)",
                         field=field_name)


@dataclass(frozen=True)
class Model:
    """A multilevel beam system.

    Parameters
    ----------
    beams : tuple of Beam
    springs : tuple of Spring
    parameters : mapping of str to value or None, optional
        Named values usable in any numeric field; ``None`` leaves the name a
        symbol. Fields refer to parameters through symbols of the same name
        (see :func:`symtmm.expr.parameter_symbol`).
    title : str, optional
    source : str, optional
        Where the model came from (a file path), used in messages.
    masses : tuple of Mass, optional
        Lumped masses on the beams.
    bodies : tuple of RigidBody, optional
        Rigid bodies carried by the beams or joining them (joints).
    layers : tuple of Layer, optional
        Continuous elastic or viscoelastic layers between beams.
    links : tuple of Link, optional
        Inextensible bars between bodies (the axial parts of inextensible frame members).
    geometry : tuple of str, optional
        Parameters whose values placed a frame's members when the model file was read
        (:mod:`symtmm.frame`): they cannot be changed afterwards (:meth:`with_parameters`
        refuses them; the model file takes them through its overrides).
    """

    beams: tuple
    springs: tuple = ()
    parameters: Mapping[str, object] = field(default_factory=dict)
    title: str = ""
    source: str | None = None
    masses: tuple = ()
    bodies: tuple = ()
    layers: tuple = ()
    links: tuple = ()
    geometry: tuple = ()

    def __post_init__(self):
        beams = tuple(self.beams)
        object.__setattr__(self, "geometry", tuple(sorted(self.geometry)))
        object.__setattr__(self, "links", tuple(self.links))
        springs = tuple(self.springs)
        object.__setattr__(self, "beams", beams)
        object.__setattr__(self, "springs", springs)
        object.__setattr__(self, "masses", tuple(self.masses))
        object.__setattr__(self, "bodies", tuple(self.bodies))
        object.__setattr__(self, "layers", tuple(self._layers_with_ends(self.layers)))
        check_size(len(beams), len(springs) + len(self.masses) + 2 * len(self.layers) + sum(
            len(getattr(b, "attachments", ())) for b in self.bodies), len(self.parameters),
            self.source)
        params = {}
        for name, value in dict(self.parameters).items():
            if not isinstance(name, str) or not _IDENTIFIER.fullmatch(name):
                raise ModelError(f"invalid parameter name {name!r}", field="parameters",
                                 source=self.source)
            if name in RESERVED_NAMES:
                # an expression reads the name as the constant or function: the
                # parameter could never be used
                raise ModelError(f"'{name}' means {name} in expressions; give the parameter "
                                 "another name", field=f"parameters.{name}", source=self.source)
            params[name] = None if value is None else _exact(value, f"parameters.{name}")
        # A read-only view keeps the model immutable.
        object.__setattr__(self, "parameters", _FrozenDict(params))
        try:
            self._substitution  # noqa: B018 - a circle among parameters is reported here
            self._validate()
        except ModelError as exc:
            raise exc.with_source(self.source) if self.source else exc from None

    def __hash__(self):
        # (a model keys the caches of plans and tables, looked up many times a search:
        # the hash of its sympy fields, 0.2 ms on a 10-level chain, is taken once)
        value = self.__dict__.get("_hash")
        if value is None:
            value = hash((self.beams, self.springs, self.parameters, self.title, self.source,
                          self.masses, self.bodies, self.layers, self.links, self.geometry))
            self.__dict__["_hash"] = value
        return value

    def __getstate__(self):
        # (a hash of strings holds for one process only: an unpickled model takes its own)
        state = dict(self.__dict__)
        state.pop("_hash", None)
        return state

    def _layers_with_ends(self, layers) -> Iterable:
        """The layers with their default ends: the overlap of the two beams."""
        beams = {b.name: b for b in self.beams if isinstance(b, Beam)}
        for layer in layers:
            if not isinstance(layer, Layer):
                raise ModelError("expected a Layer", field="layer", source=self.source)
            a, b = beams.get(layer.a), beams.get(layer.b)
            if a is not None and b is not None:
                if layer.x0 is None:
                    layer = replace(layer, x0=sp.Max(a.x0, b.x0))
                if layer.x1 is None:
                    layer = replace(layer, x1=sp.Min(a.x1, b.x1))
            yield layer

    def _validate(self):
        if not self.beams:
            raise ModelError("a model needs at least one beam", field="beam")
        names = set()
        for beam in self.beams:
            if not isinstance(beam, Beam):
                raise ModelError("expected a Beam", field="beam")
            if beam.name in names:
                raise ModelError(f"duplicate beam name '{beam.name}'", field="beam.name")
            names.add(beam.name)
        for name, expr in iter_fields(self):
            # before anything computes with the values: the limits of symtmm.limits
            _check_magnitude(self._value(expr, name), name)
        resolved = {b.name: self._resolved_beam(b) for b in self.beams}
        for beam in resolved.values():
            where = f"{beam.kind} '{beam.name}'"
            # (a rod's EI without torsion is EA L**2: EA is named first)
            for attr in ("N", "m", "L", "EI") if beam.is_rod else ("EI", "m", "L"):
                _check_sign(getattr(beam, attr), f"{where}.{beam.field_name(attr)}",
                            allow_zero=False)
            _check_sign(beam.kw, f"{where}.kw", allow_zero=True)
            _check_sign(beam.rhoI, f"{where}.{beam.field_name('rhoI')}", allow_zero=True)
            if beam.kGA is not None and not beam.is_rod:
                _check_sign(beam.kGA, f"beam '{beam.name}'.kGA", allow_zero=False)
                margin = beam.kGA + beam.N
                if margin.is_number and not margin.is_positive:
                    raise ModelError("the axial compression must stay below the shear stiffness "
                                     "kGA (kGA + N > 0)", field=f"beam '{beam.name}'.N")
        for spring in self.springs:
            where = f"spring {spring.a}-{spring.b}"
            for end in (spring.a, spring.b):
                if end != GROUND and end not in names:
                    raise ModelError(f"unknown beam '{end}'", field=f"{where}.between")
            x = self.value(spring.x)
            for end in (spring.a, spring.b):
                if end == GROUND:
                    continue
                _check_inside(x, resolved[end], f"{where}.x")
            kinds = {resolved[e].is_rod for e in (spring.a, spring.b) if e != GROUND}
            if len(kinds) > 1:
                raise ModelError("a spring joins two beams or two rods: a beam's deflection "
                                 "and a rod's axial motion are not along one line",
                                 field=f"{where}.between")
            _parallel(resolved, (spring.a, spring.b), f"{where}.between", "a spring")
            if spring.kind == "rotational":
                _no_twist(resolved, (spring.a, spring.b), f"{where}.kind",
                          "a rotational spring on a rod acts in torsion")
            for attr in ("k", "c"):
                _check_sign(self.value(getattr(spring, attr)), f"{where}.{attr}", allow_zero=True)
        for mass in self.masses:
            where = f"mass on {mass.beam}"
            if not isinstance(mass, Mass):
                raise ModelError("expected a Mass", field="mass")
            if mass.beam not in names:
                raise ModelError(f"unknown beam '{mass.beam}'", field=f"{where}.beam")
            _check_inside(self.value(mass.x), resolved[mass.beam], f"{where}.x")
            for attr in ("M", "J"):
                _check_sign(self.value(getattr(mass, attr)), f"{where}.{attr}", allow_zero=True)
            if self.value(mass.J) != 0:
                _no_twist(resolved, (mass.beam,), f"{where}.J",
                          "a mass's J on a rod is its polar inertia")
        for layer in self.layers:
            where = f"layer {layer.a}-{layer.b}"
            for end in (layer.a, layer.b):
                if end not in names:
                    raise ModelError(f"unknown beam '{end}'", field=f"{where}.between")
                beam = resolved[end]
                if beam.is_rod:
                    raise ModelError(f"a layer joins Euler-Bernoulli beams without axial force; "
                                     f"'{end}' is a rod", field=f"{where}.between")
                if not beam.plain:
                    raise ModelError(f"a layer joins Euler-Bernoulli beams without axial force; "
                                     f"beam '{end}' is {beam.theory}"
                                     + (" with an axial force" if beam.N != 0 else ""),
                                     field=f"{where}.between")
            _parallel(resolved, (layer.a, layer.b), f"{where}.between", "a layer")
            x0, x1 = self.value(layer.x0), self.value(layer.x1)
            for attr, x in (("from", x0), ("to", x1)):
                for end in (layer.a, layer.b):
                    _check_inside(x, resolved[end], f"{where}.{attr}")
            span = x1 - x0
            if span.is_number and not span.is_positive:
                raise ModelError(f"the layer needs from < to (from = {short(x0)}, to = "
                                 f"{short(x1)}; by default the overlap of the two beams)",
                                 field=f"{where}.to")
            for attr in ("k", "c"):
                _check_sign(self.value(getattr(layer, attr)), f"{where}.{attr}", allow_zero=True)
        pairs: dict = {}
        for layer in self.layers:
            # two layers over one stretch of the same pair: one layer with the sum
            key = frozenset((layer.a, layer.b))
            x0, x1 = self.value(layer.x0), self.value(layer.x1)
            for y0, y1 in pairs.get(key, []):
                gap = [x1 - y0, y1 - x0]
                if all(g.is_number for g in gap) and all(g.is_positive for g in gap):
                    raise ModelError("overlaps another layer between the same beams (write "
                                     "one layer with the sum of their k and c)",
                                     field=f"layer {layer.a}-{layer.b}")
            pairs.setdefault(key, []).append((x0, x1))
        body_names = set()
        for body in self.bodies:
            if not isinstance(body, RigidBody):
                raise ModelError("expected a RigidBody", field="rigid")
            where = f"body '{body.name}'"
            if body.name in body_names:
                raise ModelError(f"duplicate body name '{body.name}'", field="rigid.name")
            body_names.add(body.name)
            seen = set()
            for att in body.attachments:
                field_name = f"{where}.{'springs' if att.elastic else 'attach'}"
                if att.beam not in names:
                    raise ModelError(f"unknown beam '{att.beam}'", field=field_name)
                x = self.value(att.x)
                _check_inside(x, resolved[att.beam], field_name)
                if (att.beam, x) in seen:
                    raise ModelError(f"attached twice to beam '{att.beam}' at x = {x}",
                                     field=f"{where}.attach")
                seen.add((att.beam, x))
            for attr in ("M", "J"):
                _check_sign(self.value(getattr(body, attr)), f"{where}.{attr}", allow_zero=True)
            for att in body.attachments:
                target = resolved[att.beam]
                if target.torsion and not (att.hinged or att.elastic):
                    # the plane's rotation is not a twist: a body holds a rod axially only
                    raise ModelError(f"a body holds rod '{att.beam}' axially only: its twist "
                                     "stays free there (use kind 'hinge', or a torsional "
                                     "spring for a twist held elastically)",
                                     field=f"{where}.attach")
            for att in body.attachments:
                if att.elastic:
                    for attr in ("k", "c"):
                        _check_sign(self.value(getattr(att, attr)), f"{where}.{attr}",
                                    allow_zero=True)
            for label, _, _ in body.ground:
                if label not in self.body_frame(body).freedoms:
                    held = "a support holds it" if label in body.fixed else "it has no such motion"
                    raise ModelError(f"a spring on its {label}, and {held}",
                                     field=f"{where}.k{label.lower()}")
            if self.value(body.J) != 0 and not self.body_frame(body).rotates \
                    and "Theta" not in body.fixed:
                raise ModelError("nothing it holds turns with it (every attachment hinged, "
                                 "elastic or on a rod, at its centre): J would turn freely; "
                                 "give J = 0, or hold a beam rigidly", field=f"{where}.J")
            if all(a.elastic for a in body.attachments):
                M = self.value(body.M)
                if M.is_number and not M.is_positive:
                    # nothing but springs would hold a massless point: no motion of its own
                    raise ModelError("a body held by springs only needs a mass M > 0",
                                     field=f"{where}.M")
            self._check_supports(body, resolved)
        link_names = set()
        for link in self.links:
            if not isinstance(link, Link):
                raise ModelError("expected a Link", field="link")
            if link.name in link_names:
                raise ModelError(f"duplicate link name '{link.name}'", field="link.name")
            link_names.add(link.name)
            for end in link.ends:
                if end not in (None, GROUND) and end not in body_names:
                    raise ModelError(f"unknown body '{end}'", field=f"link '{link.name}'.between")
            _check_sign(self.value(link.M), f"link '{link.name}'.M", allow_zero=True)

    def _check_supports(self, body: RigidBody, resolved: dict) -> None:
        """A body held by supported beam ends no more times than it has freedoms.

        A boundary condition at a beam end attached to a body supports the body
        (a pinned trunk end pins the joint). Two supports fixing the same freedom
        leave the reactions undetermined and ``Delta`` zero for every ``lam``.
        """
        frame = body_frame(self._resolved_body(body), resolved)
        rows = []
        for att, row, turns in zip(body.attachments, frame.rows, frame.turns):
            if att.elastic:
                continue                # a spring does not pass a support on to the body
            beam, x = resolved[att.beam], self.value(att.x)
            for end, bc in ((beam.x0, beam.left), (beam.x1, beam.right)):
                d = x - end
                if not (d.is_number and d == 0):
                    continue
                zero = BOUNDARY_CONDITIONS[bc]
                if "Y" in zero:
                    rows.append([row.get(f, 0) for f in frame.freedoms])
                if "Theta" in zero and turns:
                    rows.append([int(f == "Theta") for f in frame.freedoms])
        if not rows:
            return
        matrix = sp.Matrix(rows)
        if any(not v.is_number for v in matrix):
            return
        if matrix.rank() < len(rows):
            raise ModelError("held by more supported beam ends than it has freedoms: the "
                             "reactions are not determined (leave all but one end free)",
                             field=f"body '{body.name}'.attach")

    def body_frame(self, body: RigidBody) -> BodyFrame:
        """How ``body`` moves the points it holds: its freedoms and, per attachment, the
        coefficients of the attached motion (:class:`BodyFrame`), with parameter values
        substituted.

        Examples
        --------
        >>> m = Model((Beam("a", 1, 1, 1, left="clamped"), Beam("b", 1, 1, 1, x0=1)),
        ...           bodies=(joint("j", [("a", 1), ("b", 1)]),))
        >>> m.body_frame(m.bodies[0]).freedoms
        ('Y', 'Theta')
        """
        return self._frames[body.name]

    @cached_property
    def _frames(self) -> dict:
        resolved = self.resolved()
        beams = {b.name: b for b in resolved.beams}
        # (the resolved model's bodies, in the same order: resolved once, not again here)
        return {body.name: body_frame(done, beams, resolved.links)
                for body, done in zip(self.bodies, resolved.bodies)}

    def link_rows(self, link: Link) -> list:
        """``(body, {label: coefficient})`` of each body end of ``link``: ``t . q_a - t . q_b``
        on the bodies' free translations."""
        by_name = {b.name: b for b in self.bodies}
        out = []
        for name, sign in link.bodies():
            body = by_name[name]
            frame = self.body_frame(body)
            row = {}
            for label, e in frame.directions.items():
                coef = sp.nsimplify(sp.expand(link.axis[0] * e[0] + link.axis[1] * e[1]))
                if coef != 0 and label in frame.freedoms:
                    row[label] = sign * coef
            out.append((body, row))
        return out

    # -- parameters -----------------------------------------------------------------
    @cached_property
    def _substitution(self) -> dict:
        """Parameter symbol -> value with every reference to other parameters resolved.

        A parameter may be written in terms of others (``k = "K*EI/L**3"``);
        they are resolved here, lazily, so that changing ``K`` changes ``k``.
        """
        raw = {parameter_symbol(n): v for n, v in self.parameters.items() if v is not None}
        done: dict = {}

        def resolve(sym, chain):
            if sym in done:
                return done[sym]
            if sym in chain:
                names = " -> ".join(s.name for s in chain + [sym])
                raise ModelError(f"parameters refer to each other in a circle: {names}",
                                 field=f"parameters.{sym.name}", source=self.source)
            if len(chain) >= MAX_PARAMETER_DEPTH:
                raise ModelError(f"defined through a chain of more than {MAX_PARAMETER_DEPTH} "
                                 "other parameters", field=f"parameters.{chain[0].name}",
                                 source=self.source)
            expr = raw[sym]
            subs = {s: resolve(s, chain + [sym]) for s in expr.free_symbols if s in raw}
            try:
                done[sym] = substitute(expr, subs) if subs else expr
            except ExpressionError as exc:
                raise ModelError(str(exc), field=f"parameters.{sym.name}",
                                 source=self.source) from None
            return done[sym]

        for sym in raw:
            resolve(sym, [])
        return done

    def value(self, expr) -> sp.Expr:
        """Substitute the parameters that have values into ``expr``.

        Parameters
        ----------
        expr : sympy.Expr, number or str
            A string is read by the restricted parser of model files
            (:func:`symtmm.expr.parse_expression`), never evaluated; a number
            exactly (``0.3`` is 3/10).

        Raises
        ------
        ModelError
            For a string that is no restricted expression, or another type.

        Examples
        --------
        >>> m = Model((Beam("b", EI=1, m=1, L=1),), parameters={"K": 3, "k": "2*K"})
        >>> m.value(parameter_symbol("k")), m.with_parameters(K=5).value(parameter_symbol("k"))
        (6, 10)
        >>> m.value("k/4 + 0.5")
        2
        >>> m.value("__import__('os')")
        Traceback (most recent call last):
        ...
        symtmm.errors.ModelError: cannot read "__import__('os')": unexpected character ...
        """
        if not isinstance(expr, sp.Basic):
            try:
                if isinstance(expr, str):
                    expr = parse_expression(expr)
                elif isinstance(expr, numbers.Integral) and not isinstance(expr, bool):
                    expr = sp.Integer(int(expr))
                else:
                    expr = exact_number(expr)
            except ExpressionError as exc:
                raise ModelError(f"cannot read {expr!r}: {exc}", source=self.source) from None
        return self._value(expr)

    def _value(self, expr: sp.Expr, field_name: str | None = None) -> sp.Expr:
        """:meth:`value` of a SymPy expression, errors naming ``field_name``."""
        subs = self._substitution
        if not subs:
            return expr
        try:
            return substitute(expr, subs)
        except ExpressionError as exc:
            message = str(exc) if field_name else f"cannot compute {short(expr)}: {exc}"
            raise ModelError(message, field=field_name, source=self.source) from None

    def _resolved_beam(self, beam: Beam) -> Beam:
        return replace(beam, EI=self.value(beam.EI), m=self.value(beam.m),
                       L=self.value(beam.L), x0=self.value(beam.x0), kw=self.value(beam.kw),
                       N=self.value(beam.N), rhoI=self.value(beam.rhoI),
                       kGA=None if beam.kGA is None else self.value(beam.kGA))

    def _resolved_body(self, body: RigidBody) -> RigidBody:
        def resolved(a):
            if a.elastic:
                return replace(a, x=self.value(a.x), k=self.value(a.k), c=self.value(a.c))
            return replace(a, x=self.value(a.x))
        def value(v):
            return None if v is None else self.value(v)
        return replace(body, M=self.value(body.M), J=self.value(body.J), xc=value(body.xc),
                       yc=value(body.yc),
                       ground=tuple((g, self.value(k), self.value(c)) for g, k, c in body.ground),
                       attachments=tuple(resolved(a) for a in body.attachments))

    def resolved(self) -> Model:
        """The same model with every parameter value substituted into the fields.

        Parameters without value stay symbols (see :attr:`free_symbols`).
        """
        return self._resolved

    @cached_property
    def _resolved(self) -> Model:
        if not any(v is not None for v in self.parameters.values()):
            return self             # nothing to substitute: the model is its own resolution
        beams = tuple(self._resolved_beam(b) for b in self.beams)
        springs = tuple(replace(s, x=self.value(s.x), k=self.value(s.k), c=self.value(s.c))
                        for s in self.springs)
        masses = tuple(replace(p, x=self.value(p.x), M=self.value(p.M), J=self.value(p.J))
                       for p in self.masses)
        bodies = tuple(self._resolved_body(b) for b in self.bodies)
        layers = tuple(replace(la, k=self.value(la.k), c=self.value(la.c),
                               x0=self.value(la.x0), x1=self.value(la.x1)) for la in self.layers)
        keep = {n: v for n, v in self.parameters.items() if v is None}
        links = tuple(replace(ln, M=self.value(ln.M)) for ln in self.links)
        return Model(beams, springs, keep, self.title, self.source, masses, bodies, layers, links,
                     self.geometry)

    def with_parameters(self, **values) -> Model:
        """A copy with some parameter values set or replaced.

        Examples
        --------
        >>> m = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),
        ...            Beam("c", EI=1, m=1, L=1, left="pinned", right="pinned")),
        ...           (Spring("b", "c", x="1/2", k="K"),), {"K": None})
        >>> m.free_symbols
        ('K',)
        >>> m.with_parameters(K=5).resolved().springs[0].k
        5
        """
        params = dict(self.parameters)
        for name, value in values.items():
            if name in self.geometry:
                raise ModelError(f"{name} places the members of the frame, which is fixed when "
                                 f"the model is read: give its value when loading (--set "
                                 f"{name}=...)", field=f"override {name}", source=self.source)
            params[name] = value
        return replace(self, parameters=params)

    @cached_property
    def free_symbols(self) -> tuple:
        """Names of the symbols left in the resolved fields, sorted (once per model: a solve
        asks eight times, each a walk over every field)."""
        syms = set()
        resolved = self.resolved()
        for beam in resolved.beams:
            for attr in ("EI", "m", "L", "x0", "kw", "N", "rhoI"):
                syms |= getattr(beam, attr).free_symbols
            if beam.kGA is not None:
                syms |= beam.kGA.free_symbols
        for body in resolved.bodies:
            for expr in (body.M, body.J, *(v for v in (body.xc, body.yc) if v is not None),
                         *(v for g in body.ground for v in g[1:]),
                         *(a.x for a in body.attachments),
                         *(e for a in body.attachments if a.elastic for e in (a.k, a.c))):
                syms |= expr.free_symbols
        for spring in self.resolved().springs:
            for attr in ("x", "k", "c"):
                syms |= getattr(spring, attr).free_symbols
        for mass in self.resolved().masses:
            for attr in ("x", "M", "J"):
                syms |= getattr(mass, attr).free_symbols
        for layer in resolved.layers:
            for attr in ("k", "c", "x0", "x1"):
                syms |= getattr(layer, attr).free_symbols
        for link in resolved.links:
            syms |= link.M.free_symbols
        return tuple(sorted(s.name for s in syms))

    @property
    def damped(self) -> bool:
        """True when some dashpot coefficient is not identically zero."""
        return any(not self.value(c).is_zero for c in self._dashpots())

    def _dashpots(self):
        yield from (s.c for s in self.springs)
        yield from (a.c for b in self.bodies for a in b.attachments if a.elastic)
        yield from (c for b in self.bodies for _, _, c in b.ground)
        yield from (la.c for la in self.layers)

    def with_dashpots_scaled(self, factor) -> Model:
        """A copy with every dashpot coefficient multiplied by ``factor`` (0: undamped).

        Examples
        --------
        >>> m = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),),
        ...           (Spring("b", "ground", "1/2", 1, 2),))
        >>> m.damped, m.with_dashpots_scaled(0).damped
        (True, False)
        """
        springs = tuple(replace(s, c=s.c * factor) for s in self.springs)
        bodies = tuple(replace(b, attachments=tuple(
            replace(a, c=a.c * factor) if a.elastic else a for a in b.attachments),
            ground=tuple((g, k, c * factor) for g, k, c in b.ground))
            for b in self.bodies)
        layers = tuple(replace(la, c=la.c * factor) for la in self.layers)
        return replace(self, springs=springs, bodies=bodies, layers=layers)

    def beam(self, name: str) -> Beam:
        """The beam called ``name``."""
        for beam in self.beams:
            if beam.name == name:
                return beam
        raise KeyError(name)

    def beam_index(self, name: str) -> int:
        """Position of the beam called ``name`` in :attr:`beams`."""
        return [b.name for b in self.beams].index(name)

    def require_numeric(self) -> Model:
        """The resolved model, or a :class:`ModelError` naming a parameter without value."""
        free = self.free_symbols
        if free:
            name = free[0]
            raise ModelError(f"'{name}' has no value; give it one in [parameters] or with "
                             f"with_parameters({name}=...)", field="parameters",
                             source=self.source,
                             cli_message=f"'{name}' has no value; give it one in [parameters] "
                                         f"or with --set {name}=VALUE")
        return self.resolved()


def _no_twist(resolved: dict, ends, field_name: str, what: str) -> None:
    """Refuse a torsional element on a rod without torsion (its twist is a placeholder)."""
    for end in ends:
        if end != GROUND and resolved[end].is_rod and not resolved[end].torsion:
            raise ModelError(f"{what}, and rod '{end}' has no torsion (give it GJ and rhoIp)",
                             field=field_name)


def check_size(beams: int, points: int, parameters: int, source: str | None = None) -> None:
    """The size of a model within the budgets of :mod:`symtmm.limits`."""
    levels = "levels (beams and rods; a frame member is two)"
    for count, limit, what, where in ((beams, MAX_BEAMS, levels, "beam"),
                                      (points, MAX_POINTS_ON_BEAMS,
                                       "springs, masses and rigid-body attachments", "spring"),
                                      (parameters, MAX_PARAMETERS, "parameters", "parameters")):
        if count > limit:
            raise ModelError(f"{count} {what}; a model has at most {limit}", field=where,
                             source=source)


class _FrozenDict(dict):
    """A dict that refuses to change, so that a Model stays immutable."""

    def _immutable(self, *args, **kwargs):
        raise TypeError("model parameters are immutable; use Model.with_parameters")

    __setitem__ = __delitem__ = clear = pop = popitem = setdefault = update = _immutable

    def __hash__(self):
        return hash(tuple(sorted(self.items(), key=lambda kv: kv[0])))

    def __reduce__(self):
        # unpickling a dict subclass assigns items one by one; rebuild from a plain dict
        return (_FrozenDict, (dict(self),))


def iter_fields(model: Model) -> Iterable[tuple[str, sp.Expr]]:
    """All numeric fields of ``model`` as (field name, expression) pairs."""
    for beam in model.beams:
        for attr in ("EI", "m", "L", "x0", "kw"):
            if attr == "EI" and beam.is_rod and not beam.torsion:
                continue        # EA L**2, a placeholder of EA and L (see rod)
            yield f"{beam.kind} '{beam.name}'.{beam.field_name(attr)}", getattr(beam, attr)
    for spring in model.springs:
        for attr in ("x", "k", "c"):
            yield f"spring {spring.a}-{spring.b}.{attr}", getattr(spring, attr)
    for mass in model.masses:
        for attr in ("x", "M", "J"):
            yield f"mass on {mass.beam}.{attr}", getattr(mass, attr)
    for beam in model.beams:
        for attr in ("N", "rhoI"):
            yield f"{beam.kind} '{beam.name}'.{beam.field_name(attr)}", getattr(beam, attr)
        if beam.kGA is not None and not beam.is_rod:
            yield f"beam '{beam.name}'.kGA", beam.kGA
    for body in model.bodies:
        for attr in ("M", "J", "xc", "yc"):
            if getattr(body, attr) is not None:
                yield f"body '{body.name}'.{attr}", getattr(body, attr)
        for label, k, c in body.ground:
            yield f"body '{body.name}'.k{label.lower()}", k
            yield f"body '{body.name}'.c{label.lower()}", c
        for att in body.attachments:
            yield f"body '{body.name}'.attach", att.x
            if att.elastic:
                yield f"body '{body.name}'.k", att.k
                yield f"body '{body.name}'.c", att.c
    for link in model.links:
        yield f"link '{link.name}'.M", link.M
    for layer in model.layers:
        for attr, name in (("k", "k"), ("c", "c"), ("x0", "from"), ("x1", "to")):
            if getattr(layer, attr) is not None:
                yield f"layer {layer.a}-{layer.b}.{name}", getattr(layer, attr)
