"""A model's unjoined parts (:mod:`symtmm.parts`), and damped models whose undamped parts
are solved apart on the frequency axis (:mod:`symtmm.roots.apart`)."""

from __future__ import annotations

import json
from fractions import Fraction

import mpmath
import pytest
from cli_contract import assert_contract, run_cli
from damped_reference import pp_damped_roots

from symtmm.model import Attachment, Beam, Layer, Model, RigidBody, Spring
from symtmm.modelfile import loads
from symtmm.modes import mode_shapes
from symtmm.parts import beam_groups, parts
from symtmm.roots import apart
from symtmm.solve import solve


def _pp(name):
    return Beam(name, 1, 1, 1, left="pinned", right="pinned")


def test_beams_join_through_springs_layers_and_bodies_not_through_the_ground():
    beams = tuple(_pp(n) for n in "abcdef")
    model = Model(beams,
                  (Spring("ground", "a", "1/2", 1, c=1), Spring("b", "ground", "1/3", 1),
                   Spring("b", "d", "1/4", 2)),
                  layers=(Layer("c", "e", 3),),
                  bodies=(RigidBody("j", (Attachment("d", "1/2"), Attachment("f", "1/2")),
                                    M=1),))
    assert beam_groups(model) == [["a"], ["b", "d", "f"], ["c", "e"]]
    split = parts(model)
    assert [[b.name for b in p.beams] for p in split] == [["a"], ["b", "d", "f"], ["c", "e"]]
    # (each part keeps what is on its beams)
    assert [len(p.springs) for p in split] == [1, 2, 0]
    assert [len(p.layers) for p in split] == [0, 0, 1]
    assert [len(p.bodies) for p in split] == [0, 1, 0]


def test_a_joined_model_is_one_part():
    model = Model((_pp("a"), _pp("b")), (Spring("a", "b", "1/2", 1),))
    assert parts(model) == [model]


#: A pinned-free beam whose rigid rotation only a pure dashpot resists, beside a soft
#: free-sliding beam on a stiff foundation that nothing joins to it: the soft beam's modes
#: lie within 1e-8 of its cut-off sqrt(kw/m), a cluster on the imaginary axis. The damped
#: search of the whole model failed ("cannot reach 15 digits for the real eigenvalue near
#: -40.0263"; a random model of this kind: "cannot split the search rectangle").
DASHPOT_BESIDE_A_SOFT_BEAM = """
[[beam]]
name = "p"
EI = 1
m = 1
L = 1
left = "pinned"
right = "free"

[[beam]]
name = "s"
EI = 0.136
m = 55.4
L = 26.7
left = "free"
right = "sliding"
kw = 24200

[[spring]]
between = ["p", "ground"]
x = 0.6
k = 0
c = 2
"""


def _free_sliding_on_a_foundation(n: int) -> list:
    """The first ``n`` natural frequencies of beam ``s``: its rigid translation on the
    foundation, ``sqrt(kw/m)``, then ``omega**2 = (kw + EI (x/L)**4) / m`` at the roots of
    the free-sliding equation ``tan x + tanh x = 0``."""
    EI, m, L, kw = (mpmath.mpf(v) for v in ("0.136", "55.4", "26.7", "24200"))
    out = [mpmath.sqrt(kw / m)]
    for k in range(1, n):
        x = mpmath.findroot(lambda x: mpmath.tan(x) + mpmath.tanh(x), (k - 0.25) * mpmath.pi)
        out.append(mpmath.sqrt((kw + EI * (x / L) ** 4) / m))
    return out


def test_a_damped_part_beside_a_crowded_undamped_part():
    """Reference: the pinned-free beam's eigenvalues by an independent state-space FE and
    an exact determinant (published with the issue: lam = 0 simple, -2.19141315549854,
    -0.623622447176967 + 15.3310074918209i), and the soft beam's closed form."""
    spectrum = solve(loads(DASHPOT_BESIDE_A_SOFT_BEAM), count=6)
    lams = [e.lam for e in spectrum]
    assert [e.multiplicity for e in spectrum] == [1] * 6
    with mpmath.workdps(30):
        assert abs(lams[0] - mpmath.mpf("-2.19141315549854")) < 1e-13
        assert lams[1] == 0
        assert abs(lams[2] - mpmath.mpc("-0.623622447176967", "15.3310074918209")) < 1e-12
        for lam, w in zip(lams[3:], _free_sliding_on_a_foundation(3)):
            assert lam.real == 0 and abs(lam.imag - w) < 1e-12 * w
    assert any("solved apart" in n for n in spectrum.notes)


def test_the_command_line_solves_it_in_json(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(DASHPOT_BESIDE_A_SOFT_BEAM)
    run = run_cli(["solve", str(path), "--omega-max", "20.90031352", "--digits", "25",
                   "--json"], limit=120)
    assert_contract(run, 120)
    assert run.code == 0
    out = json.loads(run.stdout)["eigenvalues"]
    with mpmath.workdps(40):
        imag = [mpmath.mpf(e["imag"]) for e in out
                if mpmath.mpf(e["real"]) == 0 and e["imag"] != "0"]
        assert len(imag) == 2
        for got, w in zip(imag, _free_sliding_on_a_foundation(2)):
            assert abs(got - w) < mpmath.mpf(10) ** -24 * w


#: Two identical pinned-pinned beams, one with a pure dashpot at mid-span: its even modes
#: have a node there and do not move the dashpot, so they are undamped and equal to the
#: other beam's.
IDLE_BESIDE_ITS_TWIN = """
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[beam]]
name = "b"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[spring]]
between = ["a", "ground"]
x = 0.5
k = 0
c = 1
"""


def test_equal_eigenvalues_of_two_parts_are_one_of_their_summed_multiplicity():
    """Reference: (n pi)**2 for beam b's modes and beam a's even ones (closed forms); a's odd
    modes are damped."""
    spectrum = solve(loads(IDLE_BESIDE_ITS_TWIN), count=6)
    undamped = [(e.lam.imag, e.multiplicity) for e in spectrum if e.lam.real == 0]
    damped = [e for e in spectrum if e.lam.real != 0]
    with mpmath.workdps(30):
        for (w, mult), n in zip(undamped, (1, 2, 3)):
            assert abs(w - (n * mpmath.pi) ** 2) < 1e-13 * w
            assert mult == (2 if n % 2 == 0 else 1)
    assert len(undamped) == 3 and len(damped) == 2
    assert all(e.lam.real < 0 and e.multiplicity == 1 for e in damped)
    assert sum(e.multiplicity for e in spectrum) == 6


def test_modes_of_an_undamped_part_stay_on_the_imaginary_axis():
    """The shape of beam b's first mode, pi**2, is refined in the whole (damped) model: its
    real part is the refinement's rounding, not a decay rate (it printed as one)."""
    modes = mode_shapes(loads(IDLE_BESIDE_ITS_TWIN), count=2, points=5)
    lam = modes[1].eigenvalue.lam
    with mpmath.workdps(30):
        assert lam.real == 0 and abs(lam.imag - mpmath.pi ** 2) < 1e-13


#: A pinned-pinned beam with a spring and dashpot at 0.3 of its span (every low mode damped)
#: beside a free-free beam (two rigid-body modes, then (4.730 / L)**2 ...).
DASHPOT_BESIDE_A_FREE_BEAM = """
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[beam]]
name = "b"
EI = 1
m = 1
L = 1
left = "free"
right = "free"

[[spring]]
between = ["a", "ground"]
x = 0.3
k = 20
c = 4
"""


@pytest.mark.parametrize("count, damped_from", [(3, 1), (5, 2)])
def test_each_part_is_solved_for_the_places_it_takes(monkeypatch, count, damped_from):
    """The lowest ``count`` of both parts, each part solved for no more than it may give
    (rather than ``count`` each: a damped part whose next eigenvalues crowd took 58 s
    where two were asked and one taken from it, now a second). Reference: the damped
    beam's roots by its Green's function (tests/damped_reference.py), the free beam's
    closed form ``cos x cosh x = 1`` and its two rigid-body modes."""
    asked = []
    real_solve = apart.solve_damped

    def recording(model, count=None, **kw):
        asked.append(count)
        return real_solve(model, count=count, **kw)

    monkeypatch.setattr(apart, "solve_damped", recording)
    spectrum = solve(loads(DASHPOT_BESIDE_A_FREE_BEAM), count=count, digits=15)
    damped = pp_damped_roots(1, 1, 1, [(Fraction(3, 10), 20, 4)], 100)
    with mpmath.workdps(30):
        free = [mpmath.findroot(lambda x: mpmath.cos(x) * mpmath.cosh(x) - 1, x0) ** 2
                for x0 in (4.73, 7.85)]
    expected = sorted([(0, 0), (0, 0)] + [(float(z.imag), float(z.real)) for z in damped[:3]]
                      + [(float(w), 0.0) for w in free])[:count]
    got = [(float(e.lam.imag), float(e.lam.real)) for e in spectrum
           for _ in range(e.multiplicity)]
    assert len(got) == count
    for (gi, gr), (ei, er) in zip(got, expected):
        assert abs(gi - ei) <= 1e-12 * max(ei, 1) and abs(gr - er) <= 1e-12 * max(abs(ei), 1)
    # the damped part gives the lowest damped_from; solved for at most one more
    assert sum(1 for _, r in got if r != 0) == damped_from
    assert max(asked) <= damped_from + 1 < count


#: A pinned-free beam ``p`` whose pinned end (x = 0) meets a spring and dashpot from a
#: pinned-pinned beam ``q`` (from -0.3 to 0.7): ``p`` cannot move there, so the spring
#: grounds ``q`` and joins nothing.
SPRING_AT_A_PIN = """
[[beam]]
name = "p"
EI = 1
m = 1
L = 1
left = "pinned"
right = "free"

[[beam]]
name = "q"
EI = 1
m = 1
L = 1
x0 = -0.3
left = "pinned"
right = "pinned"

[[spring]]
between = ["p", "q"]
x = 0
k = 20
c = 4
"""


def test_a_spring_at_a_held_point_grounds_the_other_beam():
    """``p`` is a part of its own (undamped: its rigid rotation about the pin and the
    pinned-free modes, ``tan x = tanh x``), ``q`` one with a grounded spring and dashpot
    at 0.3 of its span (its Green's function, tests/damped_reference.py)."""
    model = loads(SPRING_AT_A_PIN)
    assert beam_groups(model) == [["p"], ["q"]]
    spectrum = solve(model, count=5, digits=15)
    with mpmath.workdps(30):
        free = [mpmath.findroot(lambda x: mpmath.tan(x) - mpmath.tanh(x), x0) ** 2
                for x0 in (3.93, 7.07)]
    damped = pp_damped_roots(1, 1, 1, [(Fraction(3, 10), 20, 4)], 60)
    expected = sorted([(0.0, 0.0)] + [(float(w), 0.0) for w in free]
                      + [(float(z.imag), float(z.real)) for z in damped])[:5]
    got = [(float(e.lam.imag), float(e.lam.real)) for e in spectrum
           for _ in range(e.multiplicity)]
    assert len(got) == 5
    for (gi, gr), (ei, er) in zip(got, expected):
        assert abs(gi - ei) <= 1e-12 * max(ei, 1) and abs(gr - er) <= 1e-12 * max(ei, 1)
    assert any("solved apart" in n for n in spectrum.notes)
