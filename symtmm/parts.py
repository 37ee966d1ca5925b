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

from .model import Model

__all__ = ["parts", "beam_groups"]


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
        join([s.a, s.b])            # (the ground is no beam: join() leaves it out)
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
        springs=tuple(s for s in model.springs if s.a in names or s.b in names),
        masses=tuple(m for m in model.masses if m.beam in names),
        layers=tuple(la for la in model.layers if la.a in names),
        bodies=bodies,
        links=tuple(li for li in model.links if any(e in held for e in li.ends)))
