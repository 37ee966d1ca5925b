"""Rods in the finite-element reference, and the exact solver against it.

The rod elements of :mod:`symtmm.fe` (cubic hierarchical bars for the axial motion ``u``
and the twist ``phi``: the nodal values interpolated linearly plus two bubbles per
element and motion) are checked first against references that owe nothing to them or to
symtmm:

* the classical four-node Lagrange bar (``EA/(40 l) [[148, -189, 54, -13], ...]``, ``m
  l/1680 [[128, 99, -36, 19], ...]``) spans the same space: one element has its
  eigenvalues, and its nodal block is the two-node bar ``EA/l [[1, -1], [-1, 1]]``, ``m l/6
  [[2, 1], [1, 2]]`` (the bubbles are hierarchical);
* a uniform rod's closed forms for every pair of ends, per motion (fixed-fixed ``n pi
  c/L``, fixed-free ``(2n - 1) pi c/(2 L)``, free-free ``n pi c/L`` and a rigid mode, ``c =
  sqrt(EA/m)`` or ``sqrt(GJ/rhoIp)``), on an axial foundation ``omega**2 = c**2 beta**2 +
  kw/m``: the frequencies are upper bounds and converge as ``h**6`` (elements of degree
  ``p = 3``: ``h**(2p)``), the observed rate within 0.3 of 6;
* a disc (mass ``M``, polar inertia ``J``) at a shaft's tip, ``beta L tan(beta L) = m L/M``
  (``rhoIp L/J``), and a sprung mass at a rod's tip, ``EA beta cos(beta L) (k - M w**2) = k
  M w**2 sin(beta L)`` (roots by mpmath);
* two rods joined end to end by a hinge joint: axially one rod of their total length, in
  torsion two rods free at the joint;
* symmetry: two identical rods joined by springs ``k`` have the spectrum of one rod (in
  phase) and of one rod held by grounded springs ``2 k`` (out of phase), mesh for mesh.

Richardson's extrapolation of two nested meshes (``h`` and ``h/2``) at the elements'
rate, ``(64 w_fine - w_coarse)/63``, leaves an ``h**8`` term; the fine mesh's own error,
``|w_fine - w_coarse|/63``, bounds it with room to spare (measured on every model here,
closed forms, symtmm, damped: the extrapolated values lie within 6 % of it from the exact
ones, away from the rounding floor), so it is the tolerance below, with a floor of
``1e-11`` relative for rounding; each check also requires that error below ``1e-7``
relative (below ``1e-8`` where the meshes allow), so that it means something.

Then :func:`symtmm.solve.solve` against the extrapolated FE where no closed form exists:
seeded random models of two or three rods (some with torsion, random ends, axial springs
between them and to the ground, torsional springs, masses with polar inertia, axial
foundations, sprung masses), Kukla's example, a hinge joint of rods with a mass and an
oscillator across them, a beam and a rod in one model (through
:func:`symtmm.fe.fe_converged`), and a damped model against the FE state-space model. The
slow suite repeats the random models on 64 more seeds and random damped ones on 12.
"""

from __future__ import annotations

import itertools
import math
import random
from dataclasses import replace
from fractions import Fraction

import mpmath
import numpy as np
import pytest
import scipy.linalg
from rod_reference import family, tip_roots

from symtmm.fe import fe_converged, fe_frequencies, fe_matrices
from symtmm.model import Beam, Mass, Model, Spring, joint, oscillator, rod
from symtmm.modelfile import load
from symtmm.solve import solve

# The leading error term of the rod elements in omega: h**6.
RATE = 6
FACTOR = 2.0**RATE

# -- helpers ------------------------------------------------------------------------------


def fe_input(model: Model, stiffness: str = "k") -> dict:
    """The FE model's dicts for a :class:`~symtmm.model.Model` (its data, read as numbers).

    A rod is ``{"rod": True, "EA", "m", "L", "x0", "left", "right", "kw"}`` with its ends as
    the model file names them and, with torsion, ``GJ`` and ``rhoIp`` (a rod keeps ``EA``
    in ``N``, ``GJ`` in ``EI`` and ``rhoIp`` in ``rhoI``). ``stiffness`` is what the springs
    and the elastic attachments get as their ``k``: ``"k"``, their dashpot ``"c"`` (the
    damping matrix is then the stiffness matrix less the one of ``"zero"``) or ``"zero"``.
    """
    model = model.require_numeric()

    def value(item):
        return 0.0 if stiffness == "zero" else float(getattr(item, stiffness))

    beams = []
    for b in model.beams:
        if b.is_rod:
            d = dict(rod=True, name=b.name, EA=float(b.N), m=float(b.m), L=float(b.L),
                     x0=float(b.x0), left=b.end("left"), right=b.end("right"), kw=float(b.kw))
            if b.torsion:
                d.update(GJ=float(b.EI), rhoIp=float(b.rhoI))
        else:
            d = dict(name=b.name, EI=float(b.EI), m=float(b.m), L=float(b.L), x0=float(b.x0),
                     left=b.left, right=b.right, kw=float(b.kw), N=float(b.N),
                     rhoI=float(b.rhoI), kGA=None if b.kGA is None else float(b.kGA))
        beams.append(d)
    springs = [dict(between=(s.a, s.b), x=float(s.x), k=value(s), kind=s.kind)
               for s in model.springs]
    masses = [dict(beam=p.beam, x=float(p.x), M=float(p.M), J=float(p.J)) for p in model.masses]
    bodies = [dict(attach=[dict(beam=a.beam, x=float(a.x), hinged=a.hinged)
                           | ({"k": value(a)} if a.elastic else {})
                           for a in b.attachments], M=float(b.M), J=float(b.J),
                           xc=None if b.xc is None else float(b.xc))
              for b in model.bodies]
    return dict(beams=beams, springs=springs, masses=masses, bodies=bodies)


def fe(d: dict, count: int, elements: int, refine: int = 1) -> np.ndarray:
    return fe_frequencies(d["beams"], d["springs"], elements, count, masses=d["masses"],
                          bodies=d["bodies"], refine=refine)


def richardson(d: dict, count: int, elements: int = 16):
    """The first ``count`` FE frequencies on ``elements`` per rod and on every element
    halved, extrapolated at the rate ``h**6``, and the fine mesh's error (which bounds the
    extrapolated one)."""
    coarse, fine = fe(d, count, elements), fe(d, count, elements, refine=2)
    return (FACTOR * fine - coarse) / (FACTOR - 1.0), np.abs(fine - coarse) / (FACTOR - 1.0)


def exact(model: Model, count: int) -> np.ndarray:
    return np.array([float(w) for w in solve(model, count=count, digits=14)
                     .omegas(expand=True)])


def assert_agrees_with_fe(model: Model, count: int, elements: int = 16,
                          meaningful: float = 1e-7) -> None:
    """symtmm's first ``count`` frequencies within the fine mesh's error (itself below
    ``meaningful`` relative) of the extrapolated FE ones, with a rounding floor of 1e-11."""
    got = exact(model, count)
    ref, error = richardson(fe_input(model), count, elements)
    scale = np.maximum(ref, ref[-1] * 1e-3)
    assert np.all(error <= meaningful * scale), error / scale
    tolerance = error + 1e-11 * scale
    assert np.all(np.abs(got - ref) <= tolerance), (got, ref, (got - ref) / scale,
                                                    error / scale)


def bar(name="r", EA=1.0, m=1.0, L=1.0, x0=0.0, left="fixed", right="fixed", **extra):
    return dict(rod=True, name=name, EA=EA, m=m, L=L, x0=x0, left=left, right=right, **extra)



# -- the rod element ------------------------------------------------------------------------


def _lagrange_bar(l):
    """The classical four-node (nodes at 0, l/3, 2 l/3, l) Lagrange bar: unit stiffness and
    unit mass matrices."""
    K = np.array([[148, -189, 54, -13], [-189, 432, -297, 54], [54, -297, 432, -189],
                  [-13, 54, -189, 148]]) / (40 * l)
    M = np.array([[128, 99, -36, 19], [99, 648, -81, -36], [-36, -81, 648, 99],
                  [19, -36, 99, 128]]) * l / 1680
    return K, M


def test_fe_rod_element_is_the_four_node_lagrange_bar():
    """One free-free element, axial (EA 3, m 2, kw 5) and torsional (GJ 0.7, rhoIp 0.4):
    the eigenvalues of the pencil are those of the Lagrange bar's (the same cubic space),
    axial ``EA K + kw M, m M`` and torsional ``GJ K, rhoIp M``; its nodal block is the
    two-node bar."""
    l, EA, m, kw, GJ, rhoIp = 0.7, 3.0, 2.0, 5.0, 0.7, 0.4
    r = bar(EA=EA, m=m, L=l, left="free", right="free", kw=kw, GJ=GJ, rhoIp=rhoIp)
    K, M, info = fe_matrices([r], [], 1)
    assert K.shape == (8, 8)
    KL, ML = _lagrange_bar(l)
    ref = np.concatenate([scipy.linalg.eigh(EA * KL + kw * ML, m * ML, eigvals_only=True),
                          scipy.linalg.eigh(GJ * KL, rhoIp * ML, eigvals_only=True)])
    got = scipy.linalg.eigh(K, M, eigvals_only=True)
    np.testing.assert_allclose(np.sort(got), np.sort(ref), rtol=1e-12, atol=1e-12)
    # the nodal u and phi: the linear bar, the bubbles added on top of it
    for motion, stiff, inertia, foundation in ((0, EA, m, kw), (1, GJ, rhoIp, 0.0)):
        nodal = info["dofs"]["r"][:, motion]
        two = np.array([[1.0, -1.0], [-1.0, 1.0]])
        mass = np.array([[2.0, 1.0], [1.0, 2.0]]) * l / 6
        np.testing.assert_allclose(K[np.ix_(nodal, nodal)], stiff / l * two + foundation * mass,
                                   rtol=1e-13)
        np.testing.assert_allclose(M[np.ix_(nodal, nodal)], inertia * mass, rtol=1e-13)


def test_fe_rod_without_torsion_has_no_twist():
    """Without GJ and rhoIp the rod has only ``u``: one nodal and two bubble dofs per
    element, every ``phi`` removed."""
    _, _, info = fe_matrices([bar(left="free", right="free")], [], 5)
    assert info["n_dofs"] == 6 + 2 * 5
    assert np.all(info["dofs"]["r"][:, 1] == -1)
    assert np.all(info["dofs"]["r"][:, 0] >= 0)


@pytest.mark.parametrize("left, right, axial, torsion", [
    ("fixed", "fixed", "fixed-fixed", "fixed-fixed"),
    ("fixed", "free", "fixed-free", "fixed-free"),
    ("free", "free", "free-free", "free-free"),
    ("fixed-axial", "free", "fixed-free", "free-free"),
    ("fixed-torsion", "fixed", "free-fixed", "fixed-fixed"),
    ("free", "fixed-axial", "free-fixed", "free-free"),
])
def test_fe_rod_ends_per_motion_converge_at_h6(left, right, axial, torsion):
    """Reference: the closed forms, ``c = 2`` axially and ``c = sqrt(7)`` in torsion over
    L = 1.5, on 8, 16, 32 elements: upper bounds, the observed rate within 0.3 of 6, and
    the extrapolation within the fine mesh's error (below 1e-7 relative) of the closed
    forms."""
    L, count = 1.5, 8
    r = bar(EA=4.0, m=1.0, L=L, left=left, right=right, GJ=7.0, rhoIp=1.0)
    ref = np.array(sorted(family(axial, 2.0, L, count) + family(torsion, math.sqrt(7), L,
                                                                 count))[:count])
    raw = np.array([fe_frequencies([r], [], 8, count, refine=j) for j in (1, 2, 4)])
    assert np.all(raw >= ref * (1 - 1e-13))
    positive = ref > 0
    d1, d2 = (raw[0] - raw[1])[positive], (raw[1] - raw[2])[positive]
    assert np.all(np.abs(np.log2(d1 / d2) - RATE) < 0.3), np.log2(d1 / d2)
    extrapolated = (FACTOR * raw[2] - raw[1]) / (FACTOR - 1)
    error = np.abs(raw[2] - raw[1]) / (FACTOR - 1)
    assert np.all(error <= 1e-7 * np.maximum(ref, 1.0))
    assert np.all(np.abs(extrapolated - ref) <= error + 1e-12 * ref)


def test_fe_axial_foundation():
    """Reference: free-free on an axial foundation, ``omega**2 = (n pi c/L)**2 + kw/m`` (no
    rigid mode), EA 3, m 2, kw 6, L 1.2, on 16 and 32 elements (the fine mesh's error
    below 1e-7 relative)."""
    EA, m, kw, L = 3.0, 2.0, 6.0, 1.2
    r = bar(EA=EA, m=m, L=L, left="free", right="free", kw=kw)
    ref = np.sqrt(np.array(family("free-free", math.sqrt(EA / m), L, 6)) ** 2 + kw / m)
    d = dict(beams=[r], springs=[], masses=[], bodies=[])
    extrapolated, error = richardson(d, 6, 16)
    assert np.all(error <= 1e-7 * ref)
    assert np.all(np.abs(extrapolated - ref) <= error + 1e-12 * ref)


def test_fe_shaft_with_a_disc():
    """Reference: examples/shaft_with_disc.toml (through :func:`fe_input`) against the two
    tip-mass frequency equations, the disc's M on ``u`` and J on ``phi``."""
    model = load("examples/shaft_with_disc.toml")
    E, G, rho, dia, L, M, J = 2.1e11, 8.1e10, 7850, 0.05, 1.5, 20, 0.4
    A, Ip = math.pi * dia**2 / 4, math.pi * dia**4 / 32
    axial = [x / L * math.sqrt(E / rho) for x in tip_roots(rho * A * L / M, 5)]
    torsion = [x / L * math.sqrt(G / rho) for x in tip_roots(rho * Ip * L / J, 5)]
    ref = np.array(sorted(axial + torsion)[:6])
    d = fe_input(model)
    shaft = d["beams"][0]
    assert (shaft["rod"], shaft["left"], shaft["right"], shaft["L"]) == (True, "fixed", "free",
                                                                        1.5)
    assert (shaft["EA"], shaft["m"], shaft["GJ"], shaft["rhoIp"]) == pytest.approx(
        (E * A, rho * A, G * Ip, rho * Ip), rel=1e-15)
    assert d["masses"] == [dict(beam="shaft", x=1.5, M=20.0, J=0.4)]
    extrapolated, error = richardson(d, 6, 16)
    assert np.all(error <= 1e-8 * ref)
    assert np.all(np.abs(extrapolated - ref) <= error + 1e-12 * ref)


def test_fe_sprung_mass_at_a_rod_tip():
    """Reference: a mass M 0.5 on a spring k 3 at the free end of a fixed-free rod (EA = m =
    L = 1): ``beta cos(beta) (k - M w**2) = k M w**2 sin(beta)``, ``beta = w``."""
    M, k = 0.5, 3.0

    def f(w):
        return w * mpmath.cos(w) * (k - M * w**2) - k * M * w**2 * mpmath.sin(w)

    grid = np.linspace(0.01, 12, 4000)
    ref = np.array([float(mpmath.findroot(f, (a, b), solver="anderson"))
                    for a, b in itertools.pairwise(grid) if f(a) * f(b) < 0])
    assert len(ref) == 5
    d = dict(beams=[bar(left="fixed", right="free")], springs=[], masses=[],
             bodies=[dict(attach=[dict(beam="r", x=1.0, k=k)], M=M)])
    extrapolated, error = richardson(d, len(ref), 16)
    assert np.all(error <= 1e-8 * ref)
    assert np.all(np.abs(extrapolated - ref) <= error + 1e-12 * ref)


def test_fe_hinge_joint_of_rod_ends():
    """Reference: rods of lengths 0.6 and 0.9 (EA 4, m 1, GJ 1, rhoIp 1), fixed at the far
    ends and joined by a hinge: axially one fixed-fixed rod of length 1.5, ``n pi 2/1.5``;
    in torsion each rod fixed-free (a hinge leaves the twists free)."""
    a = bar("a", EA=4.0, L=0.6, left="fixed", right="free", GJ=1.0, rhoIp=1.0)
    b = bar("b", EA=4.0, L=0.9, x0=0.6, left="free", right="fixed", GJ=1.0, rhoIp=1.0)
    hinge = dict(attach=[dict(beam="a", x=0.6, hinged=True), dict(beam="b", x=0.6,
                                                                   hinged=True)])
    ref = np.array(sorted(family("fixed-fixed", 2.0, 1.5, 8) + family("fixed-free", 1.0, 0.6, 8)
                          + family("fixed-free", 1.0, 0.9, 8))[:8])
    d = dict(beams=[a, b], springs=[], masses=[], bodies=[hinge])
    extrapolated, error = richardson(d, 8, 16)
    assert np.all(error <= 1e-8 * ref)
    assert np.all(np.abs(extrapolated - ref) <= error + 1e-12 * ref)


def test_fe_identical_rods_joined_by_springs_decouple():
    """Reference: the FE model's own symmetry, mesh for mesh. Two identical fixed-free rods
    joined by axial springs k at 0.5, 1.2, 2 (Kukla's system, examples/kukla_rods.toml):
    the spectrum of one rod (in phase) with that of one rod held by grounded springs 2 k
    at the same points (out of phase)."""
    d = fe_input(load("examples/kukla_rods.toml"))
    one = dict(d["beams"][0])
    grounded = [dict(s, between=("a", "ground"), k=2 * s["k"]) for s in d["springs"]]
    idle = [dict(s, k=0.0) for s in grounded]          # nodes at the same points
    assert [s["kind"] for s in d["springs"]] == ["translational"] * 3
    both = fe_frequencies(d["beams"], d["springs"], 12, count=12)
    parts = np.sort(np.concatenate([fe_frequencies([one], idle, 12, count=12),
                                    fe_frequencies([one], grounded, 12, count=12)]))[:12]
    np.testing.assert_allclose(both, parts, rtol=1e-11)


@pytest.mark.parametrize("change, message", [
    (dict(EI=1.0), "is a rod"),
    (dict(GJ=1.0), "needs both GJ and rhoIp"),
    (dict(left="clamped"), "unknown rod end"),
    (dict(left="fixed-axial"), "need torsion"),
    (dict(EA=0.0), "positive"),
    (dict(rod="yes"), "True or False"),
])
def test_fe_rod_input_is_validated(change, message):
    with pytest.raises(ValueError, match=message):
        fe_matrices([bar() | change], [], 4)


BEAM = dict(name="b", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned")


@pytest.mark.parametrize("extra, message", [
    (dict(springs=[dict(between=("r", "b"), x=0.5, k=1.0)]), "joins a beam to a rod"),
    (dict(springs=[dict(between=("r", "ground"), x=0.5, k=1.0, kind="rotational")]),
     "has no torsion"),
    (dict(springs=[dict(between=("b", "ground"), x=0.5, k=1.0, kind="axial")]), "kind of"),
    (dict(masses=[dict(beam="r", x=0.5, M=1.0, J=1.0)]), "has no torsion"),
    (dict(bodies=[dict(attach=[dict(beam="r", x=0.5)], M=1.0)]), "without turning"),
    (dict(bodies=[dict(attach=[dict(beam="r", x=0.5, hinged=True)], M=1.0, J=1.0)]),
     "without turning"),
    (dict(bodies=[dict(attach=[dict(beam="r", x=0.5, hinged=True),
                               dict(beam="b", x=0.5, hinged=True)])]), "join rods only"),
    (dict(layers=[dict(between=("r", "b"), k=1.0)]), "is a rod"),
])
def test_fe_elements_on_rods_are_validated(extra, message):
    springs = extra.pop("springs", [])
    with pytest.raises(ValueError, match=message):
        fe_matrices([bar(), BEAM], springs, 4, **extra)


def test_fe_torsional_springs_on_rods():
    """Reference: a fixed-free shaft (GJ = rhoIp = L = 1) held at its free end by a
    torsional spring k 2 to the ground, ``beta cos(beta) + k sin(beta) = 0``, named by
    either kind; the axial motion (c = 3) keeps its fixed-free family."""
    k = 2.0
    torsion = [float(mpmath.findroot(lambda x: x * mpmath.cos(x) + k * mpmath.sin(x),
                                     (n * math.pi + math.pi / 2 + 1e-9,
                                      (n + 1) * math.pi - 1e-9), solver="anderson"))
               for n in range(6)]
    ref = np.array(sorted(torsion + family("fixed-free", 3.0, 1.0, 6))[:6])
    for kind in ("rotational", "torsional"):
        d = dict(beams=[bar(EA=9.0, left="fixed", right="free", GJ=1.0, rhoIp=1.0)],
                 springs=[dict(between=("ground", "r"), x=1.0, k=k, kind=kind)], masses=[],
                 bodies=[])
        extrapolated, error = richardson(d, 6, 16)
        assert np.all(error <= 1e-8 * ref)
        assert np.all(np.abs(extrapolated - ref) <= error + 1e-12 * ref)


# -- the exact solver against the FE model ---------------------------------------------------


def _q(rng: random.Random, lo: float, hi: float, den: int = 20) -> str:
    return str(Fraction(rng.randint(round(lo * den), round(hi * den)), den))


def random_rods(seed: int) -> Model:
    """Two or three rods (own lengths, offsets and ends, some with torsion, some on an
    axial foundation), joined by axial springs (and torsional ones between rods with
    torsion), held by springs to the ground, carrying masses (with a polar inertia where
    the rod twists) and a sprung mass: exact rationals from ``random.Random(seed)``."""
    rng = random.Random(seed)
    n = rng.choice((2, 3))
    rods, twisting = [], []
    for i in range(n):
        torsion = rng.random() < 0.5
        ends = ("fixed", "free", "fixed-axial", "fixed-torsion") if torsion else ("fixed", "free")
        extra = dict(GJ=_q(rng, 0.5, 3), rhoIp=_q(rng, 0.25, 1.5)) if torsion else {}
        rods.append(rod(f"r{i}", EA=_q(rng, 1, 4), m=_q(rng, 0.5, 2), L=_q(rng, 0.8, 1.2),
                        x0=_q(rng, 0, 0.2), left=rng.choice(ends), right=rng.choice(ends),
                        kw=_q(rng, 1, 30) if rng.random() < 0.3 else 0, **extra))
        if torsion:
            twisting.append(f"r{i}")

    def on(name, lo=0.0, hi=1.0):
        """A point of rod ``name`` (a twentieth), between fractions lo and hi of it."""
        r = next(r for r in rods if r.name == name)
        x0, L = Fraction(str(r.x0)), Fraction(str(r.L))
        return str(x0 + L * Fraction(rng.randint(round(20 * lo), round(20 * hi)), 20))

    springs = []
    for i in range(n - 1):                  # the overlap of any two contains [0.2, 0.8]
        for _ in range(rng.choice((1, 2))):
            springs.append(Spring(f"r{i}", f"r{i + 1}", x=_q(rng, 0.2, 0.8), k=_q(rng, 2, 60)))
    for _ in range(rng.choice((1, 2))):
        name = f"r{rng.randrange(n)}"
        springs.append(Spring(name, "ground", x=on(name), k=_q(rng, 2, 60)))
    if len(twisting) >= 2 and rng.random() < 0.7:
        springs.append(Spring(twisting[0], twisting[1], x=_q(rng, 0.2, 0.8), k=_q(rng, 1, 10),
                              kind="rotational"))
    if twisting and rng.random() < 0.5:
        springs.append(Spring(twisting[-1], "ground", x=on(twisting[-1]), k=_q(rng, 1, 10),
                              kind="rotational"))
    masses = []
    for r in rods:
        if rng.random() < 0.5:
            masses.append(Mass(r.name, on(r.name), M=_q(rng, 0.1, 0.6),
                               J=_q(rng, 0.05, 0.3) if r.torsion else 0))
    bodies = []
    if rng.random() < 0.5:
        name = f"r{rng.randrange(n)}"
        bodies.append(oscillator("o", name, on(name, 0.3, 1.0), M=_q(rng, 0.1, 0.5),
                                 k=_q(rng, 5, 40)))
    return Model(tuple(rods), tuple(springs), masses=tuple(masses), bodies=tuple(bodies))


@pytest.mark.parametrize("seed", range(4))
def test_random_rod_models_against_the_fe_model(seed):
    """Seeded random models: symtmm's first eight frequencies against the FE model
    extrapolated from 16 and 32 elements per rod, within the fine mesh's error."""
    model = random_rods(seed)
    assert_agrees_with_fe(model, 8)


def test_random_models_cover_every_element():
    """The default seeds hold rods with and without torsion, every rod end, axial springs
    between rods and to ground, torsional springs, masses with J, foundations, an
    oscillator."""
    models = [random_rods(seed) for seed in range(4)]
    rods = [r for m in models for r in m.beams]
    assert {r.torsion for r in rods} == {True, False}
    assert {r.end(side) for r in rods for side in ("left", "right")} == {
        "fixed", "free", "fixed-axial", "fixed-torsion"}
    assert any(r.kw != 0 for r in rods)
    springs = [s for m in models for s in m.springs]
    assert {(s.kind, s.grounded) for s in springs} == {
        ("translational", False), ("translational", True), ("rotational", False),
        ("rotational", True)}
    assert any(p.J != 0 for m in models for p in m.masses)
    assert any(m.bodies for m in models)


def test_the_kukla_example_against_the_fe_model():
    """examples/kukla_rods.toml (EA 2.1e8, k 5e7: stiff springs): its first eight."""
    assert_agrees_with_fe(load("examples/kukla_rods.toml"), 8)


def test_hinged_rods_with_an_oscillator_against_the_fe_model():
    """A hinge joint of two rod ends carrying a mass, an oscillator across both rods, a
    torsional spring between their twists: the FE model's bodies on rods."""
    model = Model((rod("a", EA=2, m=1, L="3/5", left="fixed", right="free", GJ=1, rhoIp="1/2"),
                   rod("b", EA=3, m="3/2", L="4/5", x0="3/5", left="free", right="fixed-axial",
                       GJ="3/2", rhoIp=1, kw=4)),
                  (Spring("a", "ground", x="3/10", k=5),),
                  bodies=(joint("j", [("a", "3/5"), ("b", "3/5")], kind="hinge", M="1/4"),
                          oscillator("o", ("a", "b"), x="3/5", M="1/3",
                                     k=(6, 9))))
    assert_agrees_with_fe(model, 8)


def test_a_beam_and_a_rod_in_one_model_through_fe_converged():
    """A clamped-free beam and a fixed-free rod with a tip mass, independent: symtmm against
    :func:`symtmm.fe.fe_converged` with its default rate (``h**4``, the beam's), which the
    rod's ``h**6`` modes pass through (its second Romberg column removes ``h**6``): within
    ten times its estimate."""
    model = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="free"),
                   rod("r", EA=40, m=1, L=1, left="fixed", right="free")),
                  (Spring("b", "ground", x="1/2", k=10),), masses=(Mass("r", 1, "1/2"),))
    got = exact(model, 8)
    d = fe_input(model)
    out = fe_converged(d["beams"], d["springs"], 16, 8, masses=d["masses"])
    assert np.all(out["error"] <= 1e-8 * out["omega"])
    rates = np.round(out["rate"])
    assert set(rates) == {4.0, 6.0}, out["rate"]
    assert np.all(np.abs(got - out["omega"]) <= 10 * out["error"]), (got - out["omega"])


# -- a damped model ------------------------------------------------------------------------------


def _fe_damped_eigenvalues(model: Model, elements: int, refine: int) -> np.ndarray:
    """Eigenvalues of ``lam**2 M + lam C + K`` on one FE mesh; the damping matrix ``C`` is
    the stiffness matrix with every spring's and elastic attachment's ``k`` replaced by its
    ``c``, less the one with ``k = 0`` (the mesh does not depend on the values)."""
    def matrices(stiffness):
        d = fe_input(model, stiffness)
        return fe_matrices(d["beams"], d["springs"], elements, masses=d["masses"],
                           bodies=d["bodies"], refine=refine)[:2]

    K, M = matrices("k")
    C = matrices("c")[0] - matrices("zero")[0]
    n = K.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    lam = scipy.linalg.eig(A, B, right=False)
    return lam[np.isfinite(lam)]


def _damped_eigenvalues_agree(model: Model, W: float, elements: int) -> int:
    """symtmm's eigenvalues with ``0 <= Im lam <= W`` (and ``Re lam >= -2 W``) against the
    FE state-space model's on ``elements`` per rod and on every element halved, extrapolated
    at ``h**6``, one for one in the order of ``Im lam``, within the fine mesh's error
    (itself below ``1e-7``); returns their number."""
    got = []
    for e in solve(model, omega_max=W, digits=12):
        got += [complex(e.lam)] * e.multiplicity

    def region(lam):
        lam = lam[(lam.imag >= -1e-9) & (lam.imag <= W) & (lam.real >= -2 * W)]
        return lam[np.argsort(lam.imag)]

    coarse, fine = (region(_fe_damped_eigenvalues(model, elements, r)) for r in (1, 2))
    assert len(coarse) == len(fine) == len(got), (coarse, fine, got)
    # (a motion that no dashpot reaches keeps Re lam = 0)
    assert all(z.real <= 1e-12 * abs(z) for z in got)
    extrapolated = (FACTOR * fine - coarse) / (FACTOR - 1)
    error = np.abs(fine - coarse) / (FACTOR - 1)
    assert np.all(error <= 1e-7 * np.abs(fine)), error / np.abs(fine)
    got = np.array(sorted(got, key=lambda z: z.imag))
    np.testing.assert_array_less(np.abs(got - extrapolated), error + 1e-11 * np.abs(fine))
    return len(got)


def test_damped_rods_against_the_state_space_fe():
    """Reference: the FE state-space model on 12 and 24 elements per rod, Richardson-
    extrapolated (``h**6``); the difference of the meshes bounds the error. Two rods, one
    twisting, joined by an axial spring-dashpot, held by a grounded one, a torsional
    spring-dashpot to the ground, an oscillator with a dashpot: every FE eigenvalue with
    ``0 <= Im lam <= W``, ``-2 W <= Re lam <= 0`` is one of symtmm's and vice versa."""
    model = Model((rod("a", EA=2, m=1, L=1, left="fixed", right="free", GJ=1, rhoIp="1/2"),
                   rod("b", EA=3, m="3/2", L="6/5", left="free", right="fixed", kw=2)),
                  (Spring("a", "b", x="1/2", k=8, c="3/10"),
                   Spring("a", "ground", x=1, k=3, c="1/5"),
                   Spring("a", "ground", x="7/10", k=1, c="1/10", kind="rotational")),
                  bodies=(oscillator("o", "b", x="3/10", M="1/2", k=10, c="1/4"),))
    assert _damped_eigenvalues_agree(model, 12.0, 12) == 10
    assert all(e.lam.real < 0 for e in solve(model, omega_max=12.0, digits=12))


# -- the larger campaign ------------------------------------------------------------------------


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(4, 68))
def test_random_rod_models_against_the_fe_model_campaign(seed):
    """More seeds, twelve frequencies, 24 and 48 elements per rod."""
    assert_agrees_with_fe(random_rods(seed), 12, elements=24)


def random_damped_rods(seed: int) -> tuple:
    """A random model of :func:`random_rods` with a dashpot beside every spring and in the
    sprung mass, ``c`` up to a tenth of ``sqrt(k)`` (light damping: no overdamped modes);
    and a search bound ``W`` in the widest gap between its undamped frequencies 6 to 10.
    Models with a rigid-body mode (a double root at 0) are passed over: the seeds ``seed +
    1000 j`` are drawn until one has none."""
    for attempt in range(100):
        model = random_rods(seed + 1000 * attempt)
        undamped = exact(model, 10)
        if undamped[0] > 0:
            break
    rng = random.Random(10_000 + seed)

    def c(k):
        return str(Fraction(rng.randint(1, 10), 100) * Fraction(
            math.sqrt(float(Fraction(str(k))))).limit_denominator(20))

    springs = tuple(replace(s, c=c(s.k)) for s in model.springs)
    bodies = tuple(replace(b, attachments=tuple(replace(a, c=c(a.k)) for a in b.attachments))
                   for b in model.bodies)
    gaps = np.diff(undamped[5:])
    j = 5 + int(np.argmax(gaps))
    W = float((undamped[j] + undamped[j + 1]) / 2)
    return Model(model.beams, springs, masses=model.masses, bodies=bodies), W


@pytest.mark.slow
@pytest.mark.parametrize("seed", range(12))
def test_random_damped_rod_models_against_the_state_space_fe(seed):
    """Seeded random damped models (:func:`random_damped_rods`) against the FE state-space
    model on 16 and 32 elements per rod."""
    model, W = random_damped_rods(seed)
    assert _damped_eigenvalues_agree(model, W, 16) >= 6
