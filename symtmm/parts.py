"""A model's unjoined parts: groups of beams that nothing connects to each other.

Beams are joined by a spring or dashpot between them, a layer, a rigid body or joint
that holds both, or an inextensible link between two such bodies; the ground joins
nothing. The characteristic determinant of a model is the product of its parts'
(its stiffness matrix is block diagonal over them), so its eigenvalues are theirs,
with multiplicities adding up. A damped model may have undamped parts, whose
eigenvalues lie on the imaginary axis and are best found there, by counts
(:func:`symtmm.solve.solve`).

Examples
--------
>>> from symtmm.model import Beam, Model, Spring
>>> beams = tuple(Beam(n, 1, 1, 1, left="pinned", right="pinned") for n in "abc")
>>> m = Model(beams, (Spring("a", "ground", "1/2", 1, c=1), Spring("a", "c", "1/3", 2)))
>>> [[b.name for b in p.beams] for p in parts(m)]
[['a', 'c'], ['b']]
"""

from __future__ import annotations

from dataclasses import replace

import sympy as sp

from .model import GROUND, Model, Spring

__all__ = ["parts", "beam_groups"]

#: The end conditions that hold the freedom a spring of each kind acts on at zero.
_HOLDING = {"translational": ("pinned", "clamped"), "rotational": ("clamped", "sliding")}


def _held(beam, x, kind: str) -> bool:
    """``beam``'s end at ``x`` holds the freedom a spring of ``kind`` acts on (exactly)."""
    if beam.is_rod:
        return False
    for end, condition in ((beam.x0, beam.left), (beam.x0 + beam.L, beam.right)):
        if condition in _HOLDING[kind] and sp.sympify(x - end).is_zero is True:
            return True
    return False


def acting(model: Model, spring: Spring):
    """``spring`` as it acts: itself, or a spring to the ground on one of its beams where
    the other holds the freedom it acts on at its point (a pinned end under a spring to
    another beam: that beam's displacement there is zero, and the spring grounds the
    other), or None where both do.

    A spring at a held point joins nothing: a stiff short beam pinned where a spring
    met a soft beam's end, free to turn about its pin, was one part with the soft beams
    and its mechanism, which the dynamic stiffness cancels to a pivot ``1e-15`` of its
    others, kept every double-precision point of the damped search from being trusted.

    Examples
    --------
    >>> from symtmm.model import Beam
    >>> pin = Beam("p", 1, 1, 1, left="pinned", right="free")
    >>> soft = Beam("s", 1, 1, 2, left="free", right="free")
    >>> acting(Model((pin, soft), (Spring("p", "s", 0, 5, c=1),)), Spring("p", "s", 0, 5, c=1))
    Spring(a='s', b='ground', x=0, k=5, c=1, kind='translational')
    """
    if spring.b == GROUND:
        return spring
    beams = {b.name: b for b in model.beams}
    held_a = _held(beams[spring.a], spring.x, spring.kind)
    held_b = _held(beams[spring.b], spring.x, spring.kind)
    if held_a and held_b:
        return None
    if held_a or held_b:
        return replace(spring, a=spring.a if held_b else spring.b, b=GROUND)
    return spring


def beam_groups(model: Model) -> list:
    """The names of the beams of each unjoined part, each in the model's order, the parts by
    their first beam."""
    names = [b.name for b in model.beams]
    parent = {n: n for n in names}

    def root(n):
        while parent[n] != n:
            parent[n] = parent[parent[n]]
            n = parent[n]
        return n

    def join(group):
        group = [g for g in group if g in parent]
        for other in group[1:]:
            parent[root(other)] = root(group[0])

    for s in model.springs:
        s = acting(model, s)
        if s is not None:
            join([s.a, s.b])        # (the ground is no beam: join() leaves it out)
    for la in model.layers:
        join([la.a, la.b])
    held = {}
    for body in model.bodies:
        beams = [a.beam for a in body.attachments]
        join(beams)
        held[body.name] = beams
    for link in model.links:
        join([b for end in link.ends if end in held for b in held[end][:1]])
    groups: dict = {}
    for n in names:
        groups.setdefault(root(n), []).append(n)
    return list(groups.values())


def parts(model: Model) -> list:
    """The unjoined parts of ``model``, each a model of its own (one: the model itself).

    A part keeps the model's parameters, title and source, and the springs, masses,
    layers, bodies and links on its beams.
    """
    groups = beam_groups(model)
    if len(groups) == 1:
        return [model]
    return [part(model, g) for g in groups]


def part(model: Model, names) -> Model:
    """The model made of the beams ``names`` (an unjoined part, or a union of such parts)
    and everything on them."""
    names = set(names)
    bodies = tuple(b for b in model.bodies if b.attachments[0].beam in names)
    held = {b.name for b in bodies}
    return replace(
        model,
        beams=tuple(b for b in model.beams if b.name in names),
        springs=tuple(s for s in (acting(model, s) for s in model.springs)
                      if s is not None and (s.a in names or s.b in names)),
        masses=tuple(m for m in model.masses if m.beam in names),
        layers=tuple(la for la in model.layers if la.a in names),
        bodies=bodies,
        links=tuple(li for li in model.links if any(e in held for e in li.ends)))
