"""Models for the benchmarks: the paper's examples and generated chains."""

from __future__ import annotations

import dataclasses
import random
from fractions import Fraction
from pathlib import Path

import sympy as sp

from symtmm.model import Attachment, Beam, Layer, Model, RigidBody, Spring, oscillator, rod
from symtmm.modelfile import load

__all__ = ["EXAMPLES", "from_scratch", "example", "clamped_clamped", "chain", "fe_input", "global_input",
           "exact_global_input", "check_ex1_model", "multispan", "layered_chain",
           "sprung_chain", "rod_chain", "storey_frame"]

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def from_scratch(model: Model) -> Model:
    """``model`` as a new, equal object with nothing cached on it, and no plan kept
    (``clear_plans``): what a user's first solve of it starts from. (What the process keeps
    by value stays, as it would for a user: constants converted to an arithmetic, the
    point elements' coefficients.)

    Examples
    --------
    >>> m = example("paper_ex1_ff_cc")
    >>> m.free_symbols
    ()
    >>> fresh = from_scratch(m)
    >>> fresh == m, fresh is m, "free_symbols" in vars(fresh)
    (True, False, False)
    """
    from symtmm.numeric.plan import clear_plans
    clear_plans()
    return dataclasses.replace(model)


def example(name: str) -> Model:
    """A model of ``examples/`` by file stem, e.g. ``"paper_ex1_ff_cc"``."""
    return load(EXAMPLES / f"{name}.toml")


def clamped_clamped() -> Model:
    """One clamped-clamped beam, ``EI = m = L = 1``."""
    return Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),),
                 title="clamped-clamped beam")


def chain(levels: int, springs_per_level: int, seed: int = 1) -> Model:
    """A chain of ``levels`` random beams over ``[0, 1]`` with random spring positions.

    Level ``i`` carries ``springs_per_level`` springs to level ``i + 1`` (the
    last level: to the ground), at positions drawn from ``j/1000``, distinct
    over the whole model, so every spring adds a cut. ``EI`` and ``m`` are
    drawn from ``{1/2, ..., 2}`` in steps of ``1/10``, supports from pinned and
    clamped (no rigid-body modes), ``k`` from ``10 .. 1000``. Exact numbers
    throughout (Fractions as strings).

    Examples
    --------
    >>> m = chain(3, 2)
    >>> len(m.beams), len(m.springs), sum(s.grounded for s in m.springs)
    (3, 6, 2)
    """
    rng = random.Random(seed * 1_000_003 + levels * 1009 + springs_per_level)
    total = levels * springs_per_level
    if total > 998:
        raise ValueError("at most 998 springs")
    positions = rng.sample(range(1, 1000), total)
    beams = []
    for i in range(levels):
        beams.append(Beam(f"b{i + 1}", EI=f"{rng.randint(5, 20)}/10", m=f"{rng.randint(5, 20)}/10",
                          L=1, left=rng.choice(("pinned", "clamped")),
                          right=rng.choice(("pinned", "clamped"))))
    springs = []
    for i in range(levels):
        other = f"b{i + 2}" if i + 1 < levels else "ground"
        for _ in range(springs_per_level):
            springs.append(Spring(f"b{i + 1}", other, x=f"{positions.pop()}/1000",
                                  k=rng.randint(10, 1000)))
    return Model(tuple(beams), tuple(springs),
                 title=f"random chain, {levels} levels, {springs_per_level} springs per level")



def layered_chain(levels: int, seed: int = 1) -> Model:
    """:func:`chain` with each pair of neighbouring levels also joined by a partial layer.

    Level ``i`` and ``i + 1`` share an elastic layer (``k`` from ``100 ..
    1000`` per unit length) over ``[1/10, 2/5]`` for odd ``i`` and ``[3/5, 9/10]`` for
    even ``i``: no beam is joined by two layers at one ``x``, so every coupled piece
    holds two beams and the model grows by pieces, not by the size of one member.

    Examples
    --------
    >>> m = layered_chain(3)
    >>> [(l.a, l.b, str(l.x0), str(l.x1)) for l in m.layers]
    [('b1', 'b2', '1/10', '2/5'), ('b2', 'b3', '3/5', '9/10')]
    """
    base = chain(levels, 2, seed)
    rng = random.Random(seed * 7919 + levels)
    layers = tuple(Layer(f"b{i + 1}", f"b{i + 2}", k=rng.randint(100, 1000),
                         x0="1/10" if i % 2 == 0 else "3/5", x1="2/5" if i % 2 == 0 else "9/10")
                   for i in range(levels - 1))
    return Model(base.beams, base.springs, layers=layers,
                 title=f"random chain with partial layers, {levels} levels")


def sprung_chain(levels: int, seed: int = 1) -> Model:
    """:func:`chain` with a sprung mass (``M`` from ``1/20 .. 1/5``, tuned between 2 and
    40 rad/s) on every level, at a position of its own.

    Examples
    --------
    >>> m = sprung_chain(2)
    >>> [(b.name, len(b.attachments)) for b in m.bodies]
    [('o1', 1), ('o2', 1)]
    """
    base = chain(levels, 2, seed)
    rng = random.Random(seed * 104729 + levels)
    used = {str(s.x) for s in base.springs}
    bodies = []
    for i in range(levels):
        x = next(f"{j}/1000" for j in iter(lambda: rng.randint(1, 999), None)
                 if f"{j}/1000" not in used)
        used.add(x)
        M = Fraction(rng.randint(1, 4), 20)
        w = rng.randint(2, 40)
        bodies.append(oscillator(f"o{i + 1}", f"b{i + 1}", x=x, M=str(M),
                                 k=str(M * w * w)))
    return Model(base.beams, base.springs, bodies=tuple(bodies),
                 title=f"random chain with sprung masses, {levels} levels")


def rod_chain(levels: int, seed: int = 1) -> Model:
    """Kukla's system grown: ``levels`` rods over ``[0, 1]`` joined by axial springs.

    :func:`chain`'s pattern with rods (``EA`` from ``{1/2, ..., 2}`` times 1000, so that
    the frequencies of :data:`benchmarks.scaling.OMEGA_MAX` cover a few modes per rod;
    ends fixed or free, the last level also held by its springs to the ground).

    Examples
    --------
    >>> m = rod_chain(3)
    >>> [b.kind for b in m.beams], len(m.springs)
    (['rod', 'rod', 'rod'], 6)
    """
    base = chain(levels, 2, seed)
    rng = random.Random(seed * 15485863 + levels)
    rods = tuple(rod(b.name, EA=f"{rng.randint(5, 20) * 100}", m=b.m, L=b.L,
                     left=rng.choice(("fixed", "free")), right="fixed")
                 for b in base.beams)
    return Model(rods, base.springs, title=f"random chain of rods, {levels} levels")

def fe_input(model: Model) -> tuple:
    """``(beams, springs)`` as the plain dicts of :mod:`symtmm.fe` (floats)."""
    model = model.resolved()
    beams = [dict(name=b.name, EI=float(b.EI), m=float(b.m), L=float(b.L), x0=float(b.x0),
                  left=b.left, right=b.right) for b in model.beams]
    springs = [dict(between=[s.a, s.b], x=float(s.x), k=float(s.k), c=float(s.c))
               for s in model.springs]
    return beams, springs


def global_input(model: Model) -> tuple:
    """``(beams, springs)`` in the form of :func:`benchmarks.references.global_matrix_omegas`,
    exact (Fractions), for checking that a reference computed from plain numbers
    is the model's.

    Examples
    --------
    >>> from benchmarks.references import EX1_BEAMS, EX1_SPRINGS
    >>> global_input(example("paper_ex1_ff_cc")) == exact_global_input(EX1_BEAMS, EX1_SPRINGS)
    True
    """
    model = model.resolved()
    index = {b.name: i for i, b in enumerate(model.beams)}
    if any(b.x0 != 0 or b.L != model.beams[0].L or b.kw != 0 for b in model.beams) or \
            model.masses or any(s.kind != "translational" or s.c != 0 for s in model.springs):
        raise ValueError("the global-matrix reference takes undamped beams over one span "
                         "joined by translational springs")
    beams = [(Fraction(str(b.EI)), Fraction(str(b.m)), b.left, b.right) for b in model.beams]
    springs = [(index[s.a], None if s.grounded else index[s.b], Fraction(str(s.x)),
                Fraction(str(s.k))) for s in model.springs]
    return exact_global_input(beams, springs)


def exact_global_input(beams, springs) -> tuple:
    """``(beams, springs)`` with every number a Fraction (for comparisons)."""
    return ([(Fraction(str(EI)), Fraction(str(m)), left, right) for EI, m, left, right in beams],
            [(a, b, Fraction(str(x)), Fraction(str(k))) for a, b, x, k in springs])


def check_ex1_model(model: Model) -> None:
    """Raise unless ``model`` is the system :data:`benchmarks.references.EX1_BEAMS` and
    ``EX1_SPRINGS`` describe (the reference is computed from those plain numbers)."""
    from .references import EX1_BEAMS, EX1_SPRINGS

    if global_input(model) != exact_global_input(EX1_BEAMS, EX1_SPRINGS):
        raise ValueError("examples/paper_ex1_ff_cc.toml no longer matches "
                         "benchmarks.references.EX1_BEAMS/EX1_SPRINGS")


def multispan(spans: int = 20) -> Model:
    """A uniform beam over ``spans`` equal pinned spans: one beam per span, joined end to end.

    Beams ``s1 .. sN`` (``EI = m = L = 1``) over ``[i, i + 1]``; ``[[joint]]``-style
    rigid joints (massless bodies holding two ends) at ``x = 1 .. N - 1``, each
    pinned by the right end of the span before it; the outer ends are pinned.

    Examples
    --------
    >>> m = multispan(3)
    >>> [(b.left, b.right) for b in m.beams], len(m.bodies)
    ([('pinned', 'pinned'), ('free', 'pinned'), ('free', 'pinned')], 2)
    """
    beams = tuple(Beam(f"s{i + 1}", EI=1, m=1, L=1, x0=i,
                       left="pinned" if i == 0 else "free", right="pinned")
                  for i in range(spans))
    joints = tuple(RigidBody(f"pin{i}", (Attachment(f"s{i}", i), Attachment(f"s{i + 1}", i)))
                   for i in range(1, spans))
    return Model(beams, bodies=joints,
                 title=f"uniform beam over {spans} equal pinned spans (joints of span ends)")


def storey_frame(levels: int, seed: int = 1) -> Model:
    """A plane frame of one bay and ``levels`` storeys: two columns per storey, a beam at
    every floor, rigid joints, clamped bases (members with ``EI`` from ``{1/2, ..., 2}``,
    ``EA = 1000 EI``, storeys of heights 1/2 to 1, a bay of 1).

    Examples
    --------
    >>> m = storey_frame(2)
    >>> len(m.beams), len(m.bodies)          # 6 members, each a beam and a rod; 4 knees
    (12, 4)
    """
    from symtmm.frame import Member, Node, frame

    rng = random.Random(seed * 7919 + levels)
    members, y = [], sp.Integer(0)

    def stiffness():
        return sp.Rational(rng.randint(1, 4), 2)
    for k in range(1, levels + 1):
        top = y + sp.Rational(rng.randint(2, 4), 4)
        for side, x in (("l", 0), ("r", 1)):
            EI = stiffness()
            members.append(Member(f"c{side}{k}", (x, y), (x, top), EI=EI, EA=1000 * EI, m=1))
        EI = stiffness()
        members.append(Member(f"b{k}", (0, top), (1, top), EI=EI, EA=1000 * EI, m=1))
        y = top
    return frame(members, [Node((0, 0), "clamped"), Node((1, 0), "clamped")],
                 title=f"one-bay frame of {levels} storeys")
