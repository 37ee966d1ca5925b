"""Certified enclosures (Arb balls) for the beam theories and for rigid bodies and joints.

The enclosures must contain eigenvalues known independently: the pinned-pinned closed
forms of every theory (derived from the energy in ``test_theories_modes``), the decoupled
families of the fork and the loop, and the cantilever with a tip body from its own
frequency equation. The Wittrick-Williams count in balls must give the number of
closed-form eigenvalues below a frequency, with both Timoshenko spectra.
"""

from __future__ import annotations

import itertools
import json

import mpmath
import pytest
from test_theories_modes import (
    EI,
    FORK,
    LENGTH,
    LINKED,
    LOOP,
    MASS,
    THEORIES,
    cantilever_betas,
    fork_families,
    loop_families,
    pinned_pinned_reference,
    pp_model,
    tip_body_model,
    tip_body_reference,
)

from symtmm.cli import main
from symtmm.compile import Evaluator
from symtmm.model import Beam, Model
from symtmm.modelfile import loads
from symtmm.results import Eigenvalue, Spectrum
from symtmm.solve import solve

flint = pytest.importorskip("flint")
from symtmm.numeric.arith import Ball
from symtmm.numeric.evaluator import Evaluator as Kernel
from symtmm.roots.certified import certify
from symtmm.roots.count import Counter


def pp_omegas(name, numbers, dps=80):
    """Closed-form pinned-pinned frequencies of a theory, ascending."""
    _, values, _ = THEORIES[name]
    with mpmath.workdps(dps):
        return sorted(mpmath.sqrt(w2) for n in numbers
                      for w2, _, _ in pinned_pinned_reference(EI, MASS, LENGTH, n, dps=dps,
                                                              **values))


def near(omega, rel="1e-9", digits=15):
    """An approximate eigenvalue (no bracket: the proof must find the zero near it)."""
    with mpmath.workdps(30):
        return Eigenvalue(mpmath.mpc(0, omega * (1 + mpmath.mpf(rel))), 1, digits)


def spectrum(eigenvalues, digits=15):
    return Spectrum(tuple(eigenvalues), digits, "test", 0, 0.0)


BODY_MODELS = {
    "fork": lambda: loads(FORK),
    "loop": lambda: loads(LOOP),
    "linked": lambda: loads(LINKED),
    "tip": lambda: tip_body_model("1/5", "1/2", "1/50"),
}


@pytest.mark.parametrize("name", list(THEORIES) + list(BODY_MODELS))
def test_ball_delta_encloses_the_mpmath_walk(name):
    """The stiffness kernel's ball (series and doublings, exact constraints) against the
    transfer walk (the product of transfer matrices along x) in mpmath at 90 digits."""
    model = (pp_model(THEORIES[name][0]) if name in THEORIES else BODY_MODELS[name]()
             ).require_numeric()
    kernel, ev = Kernel(model, 150.0), Evaluator(model)
    for z in (mpmath.mpc(0, 7.3), mpmath.mpc(-0.4, 31.0), mpmath.mpc(0, 140.0)):
        ball = kernel.delta([z], Ball(400))[0][0]
        exact = ev.delta_mp(z, dps=90)
        assert abs(complex(ball.mid()) - complex(exact)) <= 1e-70 * abs(complex(exact)) + float(
            ball.rad())
        assert float(ball.rad()) < 1e-60 * abs(complex(ball.mid()))


@pytest.mark.parametrize("name", THEORIES)
def test_rouche_enclosures_contain_the_pinned_pinned_closed_forms(name):
    numbers = THEORIES[name][2]
    model = pp_model(THEORIES[name][0])
    refs = pp_omegas(name, numbers)
    enclosures = certify(model, spectrum(near(w) for w in refs))
    for enc, ref in zip(enclosures, refs):
        assert enc.proof == "Rouche", (name, ref)
        with mpmath.workdps(80):
            assert enc.contains(mpmath.mpc(0, ref)), (name, ref, enc.imag)
            assert enc.radius < mpmath.mpf(10) ** -16 * ref


def test_count_enclosures_of_the_timoshenko_spectra():
    # both spectra and the n = 0 shear mode at sqrt(kGA/rhoI) = 89.44
    refs = pp_omegas("timoshenko", (0, 1, 2))
    model = pp_model(THEORIES["timoshenko"][0])
    with mpmath.workdps(40):
        eigs = [Eigenvalue(mpmath.mpc(0, w), 1, 15,
                           (float(w * (1 - mpmath.mpf(10)**-12)), float(w * (1 + mpmath.mpf(10)**-12))))
                for w in refs]
    enclosures = certify(model, spectrum(eigs))
    assert [e.proof for e in enclosures] == ["count"] * 5
    with mpmath.workdps(50):
        assert all(e.contains(mpmath.mpc(0, w)) for e, w in zip(enclosures, refs))


@pytest.mark.parametrize("name, top", [("timoshenko", 130.0), ("rayleigh", 80.0),
                                       ("compression", 60.0), ("tension", 60.0)])
def test_ball_count_is_the_number_of_closed_form_roots_below(name, top):
    refs = [float(w) for w in pp_omegas(name, range(0 if name == "timoshenko" else 1, 12))]
    refs = [w for w in refs if w < 1.2 * top]
    counter = Counter(pp_model(THEORIES[name][0]), top)
    probes = [0.5 * refs[0]] + [0.5 * (a + b) for a, b in itertools.pairwise(refs)
                                if b < top]
    counts = counter.counts(probes, Ball(200))
    assert list(counts) == [sum(1 for r in refs if r < w) for w in probes], name


def test_triple_timoshenko_root_is_certified_by_the_count():
    keywords = THEORIES["timoshenko"][0]
    beams = tuple(Beam(n, EI=2, m=3, L="3/2", left="pinned", right="pinned", **keywords)
                  for n in "abc")
    model = Model(beams)
    w = pp_omegas("timoshenko", (1,))[0]           # the first bending root, triple
    with mpmath.workdps(40):
        lo, hi = float(w * (1 - mpmath.mpf(10)**-10)), float(w * (1 + mpmath.mpf(10)**-10))
        triple = Eigenvalue(mpmath.mpc(0, w), 3, 9, (lo, hi))
        beside = Eigenvalue(mpmath.mpc(0, w * (1 + mpmath.mpf(10)**-6)), 3, 9,
                            (float(w * (1 + mpmath.mpf(10)**-7)), float(w * (1 + 2 * mpmath.mpf(10)**-6))))
    enc = certify(model, spectrum([triple, beside], digits=9))
    assert enc[0].proof == "count"
    with mpmath.workdps(50):
        assert enc[0].contains(mpmath.mpc(0, w))
    assert enc[1].proof == "none"                 # no eigenvalue in that bracket


# -- rigid bodies and joints -------------------------------------------------------------------

def test_fork_and_loop_enclosures_contain_the_decoupled_families():
    for text, families in ((FORK, fork_families(3, dps=80)), (LOOP, loop_families(3, dps=80))):
        model = loads(text)
        refs = [omega for omega, *_ in families]
        enclosures = certify(model, spectrum(near(w) for w in refs))
        for enc, (omega, family, *_rest) in zip(enclosures, families):
            assert enc.proof == "Rouche", (family, omega)
            with mpmath.workdps(80):
                assert enc.contains(mpmath.mpc(0, omega)), (family, omega)
                assert enc.radius < mpmath.mpf(10) ** -16 * omega


def test_tip_body_enclosures_contain_the_frequency_equation_roots():
    model = tip_body_model("1/5", "1/2", "1/50")
    with mpmath.workdps(80):
        refs = [beta**2 for beta, _, _ in tip_body_reference("1/5", "1/2", "1/50", 4, dps=80)]
    enclosures = certify(model, spectrum(near(w) for w in refs))
    with mpmath.workdps(80):
        for enc, ref in zip(enclosures, refs):
            assert enc.proof == "Rouche" and enc.contains(mpmath.mpc(0, ref)), ref


def test_a_double_root_of_a_fork_with_three_branches_is_certified():
    # three identical branches: the opposite family (each branch clamped-free, the trunk
    # at rest) is double; the ball count over the joint's constraints proves it
    branch = 'name = "{}"\nEI = "1/3"\nm = "1/3"\nL = 0.75\nx0 = 1\nleft = "free"\nright = "free"\n'
    text = ('[[beam]]\nname = "trunk"\nEI = 1\nm = 1\nL = 1\nleft = "clamped"\nright = "free"\n'
            + "".join("[[beam]]\n" + branch.format(n) for n in ("b1", "b2", "b3"))
            + '[[joint]]\nends = ["trunk.right", "b1.left", "b2.left", "b3.left"]\n')
    three = loads(text)
    assert len(three.beams) == 4
    with mpmath.workdps(40):
        w = (cantilever_betas(1)[0] / mpmath.mpf("0.75")) ** 2
        double = Eigenvalue(mpmath.mpc(0, w), 2, 12, (float(w) * (1 - 1e-9), float(w) * (1 + 1e-9)))
    (enc,) = certify(three, spectrum([double], digits=12))
    assert enc.proof == "count" and enc.contains(mpmath.mpc(0, w))
    # and a bracket beside it holds no eigenvalue: the count does not prove it
    with mpmath.workdps(40):
        beside = Eigenvalue(mpmath.mpc(0, w * 1.01), 2, 12,
                            (float(w) * 1.005, float(w) * 1.015))
    (enc,) = certify(three, spectrum([beside], digits=12))
    assert enc.proof == "none"


# -- command line ------------------------------------------------------------------------------

@pytest.mark.parametrize("theory, extra, name", [
    ("timoshenko", "rhoI = 0.01\nkGA = 80\n", "timoshenko"),
    ("rayleigh", "rhoI = 0.02\n", "rayleigh"),
])
def test_cli_solve_certified_json(tmp_path, capsys, theory, extra, name):
    path = tmp_path / f"{theory}.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 2\nm = 3\nL = 1.5\nleft = "pinned"\n'
                    f'right = "pinned"\ntheory = "{theory}"\n{extra}')
    assert main(["solve", str(path), "--count", "2", "--digits", "12", "--json",
                 "--certified"]) == 0
    out = json.loads(capsys.readouterr().out)
    values = {"rhoI": "0.01", "kGA": "80"} if theory == "timoshenko" else {"rhoI": "0.02"}
    with mpmath.workdps(50):
        refs = sorted(mpmath.sqrt(w2) for n in (1, 2)
                      for w2, _, _ in pinned_pinned_reference(EI, MASS, LENGTH, n, dps=50,
                                                              **values))[:2]
    assert len(out["eigenvalues"]) == 2
    for e, ref in zip(out["eigenvalues"], refs):
        enc = e["enclosure"]
        assert enc["certified"] and enc["proof"] == "count"
        lo, hi = (mpmath.mpf(v) for v in enc["imag"])
        with mpmath.workdps(50):
            assert lo <= ref <= hi, (name, ref, enc["imag"])
        assert abs(mpmath.mpf(e["imag"]) - ref) < mpmath.mpf(10) ** -11 * ref


def test_a_ball_too_wide_still_encloses_the_value():
    """Over a wide ball (|lam - 20i| up to 7) the enclosure is loose but holds the value
    of every point inside it: the transfer walk's at the centre."""
    import flint
    model = loads(LOOP).require_numeric()
    kernel, ev = Kernel(model, 40.0), Evaluator(model)
    ar = Ball(200)
    with ar:
        wide = flint.acb(flint.arb(0, 5), flint.arb(20, 5))
        value = kernel.enclose([wide], ar)[0]
    exact = ev.delta_mp(mpmath.mpc(0, 20), dps=40)
    assert value.contains(flint.acb(exact.real, exact.imag))
    assert value.rad() > abs(complex(exact))          # and says nothing sharper


def test_double_roots_of_two_forks_are_certified_by_the_count():
    """Two identical uncoupled forks (a clamped trunk joined rigidly to two branches
    EI/2, m/2): every eigenvalue twice. In-phase branches: one clamped-free beam of
    length 1 (omega = nu**2); opposite branches: a clamped-free branch of length 1/2
    (omega = 4 nu**2), nu from cos nu cosh nu = -1."""
    from symtmm.model import Attachment, RigidBody

    beams, bodies = [], []
    for f in "pq":
        beams += [Beam(f"{f}t", EI=1, m=1, L="1/2", left="clamped", right="free"),
                  Beam(f"{f}u", EI="1/2", m="1/2", L="1/2", x0="1/2"),
                  Beam(f"{f}d", EI="1/2", m="1/2", L="1/2", x0="1/2")]
        bodies.append(RigidBody(f"{f}j", tuple(Attachment(f"{f}{b}", "1/2")
                                                for b in "tud")))
    model = Model(tuple(beams), bodies=tuple(bodies))
    spectrum = solve(model, count=6, digits=12)
    assert [e.multiplicity for e in spectrum] == [2, 2, 2]
    enclosures = certify(model, spectrum)
    assert [e.proof for e in enclosures] == ["count"] * 3
    with mpmath.workdps(40):
        nu = [mpmath.findroot(lambda x: mpmath.cos(x) + mpmath.sech(x), g) for g in (1.9, 4.7)]
        refs = sorted([nu[0] ** 2, nu[1] ** 2, 4 * nu[0] ** 2])
        assert all(e.contains(mpmath.mpc(0, r)) for e, r in zip(enclosures, refs))
