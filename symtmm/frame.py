"""Planar frames: members at any angle in the plane, joined where their ends meet.

A member is a beam in bending and a rod in axial vibration along the same line (two
levels of the model: ``name`` and ``name_axial``), placed by its two end points. Wherever
member ends meet at one point they are joined by a joint (a massless
:class:`~symtmm.model.RigidBody`): rigid (every end turns with it) or a hinge (each end
turns freely); a node may also carry a support and a mass. The joint's freedoms are both
translations of the plane and, where anything turns with it, its rotation
(:class:`~symtmm.model.BodyFrame`), so the axial motion of one member and the bending of
another meet there exactly: the axial-bending coupling of a frame.

Nothing here computes: a frame is written out as beams, rods and joints, and every
formulation of the package takes those as they come.
"""

from __future__ import annotations

from dataclasses import dataclass

import sympy as sp

from .errors import ModelError
from .model import (
    _IDENTIFIER,
    GROUND,
    Attachment,
    Beam,
    Link,
    Model,
    RigidBody,
    _check_sign,
    _exact,
    rod,
    short,
)

__all__ = ["Member", "Node", "frame", "frame_parts", "SUPPORTS", "AXIAL_SUFFIX"]

#: A node's supports: the freedoms of the plane each holds (``X``, ``Y`` the translations
#: along the plane's x and y, ``Theta`` the rotation). A roller moves along the named axis,
#: a sliding support too and does not turn.
SUPPORTS = {"free": (), "pinned": ("Y", "X"), "clamped": ("Y", "X", "Theta"),
            "roller-x": ("Y",), "roller-y": ("X",), "sliding-x": ("Y", "Theta"),
            "sliding-y": ("X", "Theta"), "roller": ("Y",), "sliding": ("Y", "Theta")}

#: The supports that move along a node's ``angle``.
_INCLINED = ("roller", "sliding")

#: The supports a single member end takes as its own end conditions (beam end, rod end):
#: they hold both translations, whatever the member's direction.
_END_SUPPORTS = {"free": ("free", "free"), "pinned": ("pinned", "fixed"),
                 "clamped": ("clamped", "fixed")}

#: The name of a member's axial level: ``name + AXIAL_SUFFIX``.
AXIAL_SUFFIX = "_axial"


def _key(point) -> tuple:
    """A point in one canonical exact form (where member ends meet is decided by it)."""
    return tuple(sp.radsimp(sp.expand(v)) for v in point)


def _point(value, field_name: str) -> tuple:
    if not isinstance(value, (list, tuple)) or len(value) != 2:
        raise ModelError("expected a point [x, y]", field=field_name)
    point = tuple(_exact(v, field_name) for v in value)
    if not all(v.is_number and v.is_real is not False for v in point):
        raise ModelError("expected two numbers (a frame's geometry takes no parameter)",
                         field=field_name)
    return point


@dataclass(frozen=True)
class Member:
    """A straight member of a planar frame: bending ``EI``, axial ``EA``, mass ``m``.

    Parameters
    ----------
    name : str
    start, end : pair of numbers or str
        Its end points in the plane (exact).
    EI, EA, m : number or str
        Bending and axial stiffness, mass per unit length; ``EA = None`` for an
        inextensible member (its length kept exactly: a :class:`~symtmm.model.Link`
        between its end joints carrying its mass ``m L`` along it, in place of a rod).

    Examples
    --------
    >>> c = Member("col", (0, 0), (0, 3), EI=1, EA=100, m=2)
    >>> c.L, c.axis
    (3, (0, 1))
    """

    name: str
    start: tuple
    end: tuple
    EI: object
    EA: object
    m: object

    def __post_init__(self):
        where = f"member '{self.name}'"
        object.__setattr__(self, "start", _point(self.start, f"{where}.from"))
        object.__setattr__(self, "end", _point(self.end, f"{where}.to"))
        if not isinstance(self.name, str) or not _IDENTIFIER.fullmatch(self.name) \
                or self.name == GROUND:
            raise ModelError(f"invalid name {self.name!r} (an identifier other than 'ground')",
                             field=f"{where}.name")
        for attr in ("EI", "EA", "m"):
            if getattr(self, attr) is not None:
                value = _exact(getattr(self, attr), f"{where}.{attr}")
                _check_sign(value, f"{where}.{attr}", allow_zero=False)
                object.__setattr__(self, attr, value)
        if self.L == 0:
            raise ModelError("its two ends are one point", field=f"{where}.to")

    @property
    def inextensible(self) -> bool:
        """True when the axial stiffness is infinite (``EA = None``)."""
        return self.EA is None

    @property
    def L(self) -> sp.Expr:
        """The length (exact)."""
        d = [b - a for a, b in zip(self.start, self.end)]
        return sp.sqrt(sp.expand(d[0]**2 + d[1]**2))

    @property
    def axis(self) -> tuple:
        """The unit vector from ``start`` to ``end`` (exact)."""
        L = self.L
        return tuple(sp.radsimp((b - a) / L) for a, b in zip(self.start, self.end))


@dataclass(frozen=True)
class Node:
    """A point of a frame: a support, a hinge, a mass.

    Parameters
    ----------
    at : pair of numbers or str
    support : str
        ``"free"``; ``"pinned"`` holds both translations, ``"clamped"`` the rotation
        too; ``"roller-x"`` moves along the plane's x only (holds y), ``"roller-y"``
        along y only; ``"sliding-x"``, ``"sliding-y"`` likewise without turning
        (:data:`SUPPORTS`); ``"roller"`` and ``"sliding"`` move along ``angle``.
    angle : number or str, optional
        The direction an inclined roller or sliding support moves along, in degrees from
        the plane's x (only with ``"roller"`` and ``"sliding"``; then the node's ``x`` and
        ``y`` of its springs and mode shapes are along and across that direction).
    hinge : bool
        The member ends there turn freely (a pin joint); else they turn together.
    M, J : number or str
        A mass and rotary inertia at the point.
    name : str, optional
    springs : dict, optional
        An elastic support: ``{"X": (k, c), "Y": (k, c), "Theta": (k, c)}``, springs and
        dashpots from the point's motions along the plane's x and y and its rotation to
        the ground.
    """

    at: tuple
    support: str = "free"
    hinge: bool = False
    M: object = 0
    J: object = 0
    name: str | None = None
    springs: dict | None = None
    angle: object = None

    def __post_init__(self):
        where = f"node '{self.name}'" if self.name else "node"
        object.__setattr__(self, "at", _point(self.at, f"{where}.at"))
        if self.support not in SUPPORTS:
            raise ModelError(f"unknown support {self.support!r} (use one of "
                             f"{', '.join(SUPPORTS)})", field=f"{where}.support")
        if not isinstance(self.hinge, bool):
            raise ModelError("expected true or false", field=f"{where}.hinge")
        if (self.angle is None) == (self.support in _INCLINED):
            raise ModelError(f"a {self.support} support moves along an angle: give angle"
                             if self.angle is None else
                             "angle belongs to a roller or sliding support",
                             field=f"{where}.angle")
        if self.angle is not None:
            angle = _exact(self.angle, f"{where}.angle")
            if not angle.is_number:
                raise ModelError("must be a number", field=f"{where}.angle")
            object.__setattr__(self, "angle", angle)


def frame_parts(members, nodes=()) -> tuple:
    """The beams, rods, joints and links of a frame: ``(levels, bodies, links)`` for a
    :class:`~symtmm.model.Model`.

    Each member gives a beam ``name`` and a rod ``name + "_axial"`` along the same line
    (both with ``x`` from 0 to ``L``); every point where two or more member ends meet, or
    where a node puts a mass, becomes a joint ``node1, node2, ...`` (or the node's name)
    which the node's support holds (:attr:`~symtmm.model.RigidBody.fixed`); a support
    of a single member end is that end's condition (its beam end and its rod end). A
    member end at no node is free. An inextensible member has no rod: a
    :class:`~symtmm.model.Link` joins the joints at its ends (or the ground at a
    supported end).

    Examples
    --------
    An L-frame: a clamped column, a beam pinned at its far end, joined rigidly:

    >>> col = Member("col", (0, 0), (0, 3), EI=1, EA=100, m=1)
    >>> top = Member("top", (0, 3), (4, 3), EI=1, EA=100, m=1)
    >>> levels, bodies, links = frame_parts([col, top], [Node((0, 0), "clamped"),
    ...                                                  Node((4, 3), "pinned")])
    >>> [(b.name, b.end("left"), b.end("right")) for b in levels]   # doctest: +NORMALIZE_WHITESPACE
    [('col', 'clamped', 'free'), ('col_axial', 'fixed', 'free'),
     ('top', 'free', 'pinned'), ('top_axial', 'free', 'fixed')]
    >>> [(a.beam, a.x, a.hinged) for a in bodies[0].attachments]
    [('col', 3, False), ('col_axial', 3, True), ('top', 0, False), ('top_axial', 0, True)]
    """
    members, nodes = list(members), list(nodes)
    names = set()
    for mb in members:
        if not isinstance(mb, Member):
            raise ModelError("expected a Member", field="member")
        if mb.name in names:
            raise ModelError(f"duplicate member name '{mb.name}'", field="member.name")
        names.add(mb.name)
    for mb in members:
        if mb.name + AXIAL_SUFFIX in names:
            raise ModelError(f"'{mb.name + AXIAL_SUFFIX}' names the axial part of member "
                             f"'{mb.name}': give the member another name",
                             field=f"member '{mb.name + AXIAL_SUFFIX}'.name")
    # the points where member ends lie, in order of first appearance
    points: list = []
    ends_at: dict = {}
    for mb in members:
        for side, p in (("left", mb.start), ("right", mb.end)):
            key = _key(p)
            if key not in ends_at:
                points.append(key)
                ends_at[key] = []
            ends_at[key].append((mb, side))
    node_at: dict = {}
    for node in nodes:
        if not isinstance(node, Node):
            raise ModelError("expected a Node", field="node")
        key = _key(node.at)
        if key in node_at:
            raise ModelError(f"two nodes at ({short(key[0])}, {short(key[1])})",
                             field="node.at")
        if key not in ends_at:
            raise ModelError(f"no member end lies at ({short(key[0])}, {short(key[1])})",
                             field=f"node{' ' + repr(node.name) if node.name else ''}.at")
        node_at[key] = node
    bcs = {(mb.name, side): ("free", "free") for mb in members for side in ("left", "right")}
    # where each inextensible member's ends are held: a joint's name, the ground, or None
    held = {(mb.name, side): None for mb in members if mb.inextensible
            for side in ("left", "right")}
    bodies = []
    for i, key in enumerate(points, 1):
        ends = ends_at[key]
        node = node_at.get(key, Node(key))
        where = f"node at ({short(key[0])}, {short(key[1])})"
        if node.hinge and "Theta" in SUPPORTS[node.support] and len(ends) > 1:
            raise ModelError(f"a {node.support} support holds the rotation of every end "
                             "there: not a hinge", field=f"{where}.support")
        massive = (_exact(node.M, f"{where}.M") != 0 or _exact(node.J, f"{where}.J") != 0
                   or bool(node.springs))
        if len(ends) == 1 and not massive and node.support in _END_SUPPORTS:
            mb, side = ends[0]
            bcs[(mb.name, side)] = _END_SUPPORTS[node.support]
            if mb.inextensible and node.support != "free":
                held[(mb.name, side)] = GROUND
            continue
        name = node.name or f"node{i}"
        attachments = []
        for mb, side in ends:
            x = 0 if side == "left" else mb.L
            attachments.append(Attachment(mb.name, x, hinged=node.hinge))
            if mb.inextensible:
                held[(mb.name, side)] = name
            else:
                attachments.append(Attachment(mb.name + AXIAL_SUFFIX, x, hinged=True))
        fixed = SUPPORTS[node.support]
        if node.hinge:
            fixed = tuple(f for f in fixed if f != "Theta")
        ground = tuple((label, *kc) for label, kc in (node.springs or {}).items())
        axes = None
        if node.angle is not None:
            a = node.angle * sp.pi / 180
            axes = (sp.cos(a), sp.sin(a))
        bodies.append(RigidBody(name, tuple(attachments), M=node.M, J=node.J,
                                xc=key[0], yc=key[1], fixed=fixed, ground=ground, axes=axes))
    for mb in members:
        if mb.inextensible and held[(mb.name, "left")] is None \
                and held[(mb.name, "right")] is None:
            # both ends free and bare: nothing would carry the member's axial motion, so
            # its left end becomes a joint of its own
            name = f"{mb.name}_end"
            bodies.append(RigidBody(name, (Attachment(mb.name, 0),), xc=mb.start[0],
                                    yc=mb.start[1]))
            held[(mb.name, "left")] = name
    levels, links = [], []
    for mb in members:
        left, right = bcs[(mb.name, "left")], bcs[(mb.name, "right")]
        levels.append(Beam(mb.name, mb.EI, mb.m, mb.L, left=left[0], right=right[0],
                           origin=mb.start, axis=mb.axis))
        if mb.inextensible:
            links.append(Link(mb.name + AXIAL_SUFFIX, held[(mb.name, "left")],
                              held[(mb.name, "right")], mb.axis, M=mb.m * mb.L))
        else:
            levels.append(rod(mb.name + AXIAL_SUFFIX, mb.EA, mb.m, mb.L, left=left[1],
                              right=right[1], origin=mb.start, axis=mb.axis))
    return tuple(levels), tuple(bodies), tuple(links)


def frame(members, nodes=(), title: str = "") -> Model:
    """A :class:`~symtmm.model.Model` of a planar frame (:func:`frame_parts`).

    Examples
    --------
    A free L-frame has three rigid-body modes:

    >>> from symtmm import api
    >>> m = frame([Member("a", (0, 0), (0, 1), EI=1, EA=100, m=1),
    ...            Member("b", (0, 1), (1, 1), EI=1, EA=100, m=1)])
    >>> api.solve(m, count=3).eigenvalues[0].multiplicity
    3
    """
    levels, bodies, links = frame_parts(members, nodes)
    return Model(levels, bodies=bodies, links=links, title=title)
