"""Sprung masses (tuned mass dampers): ``[[oscillator]]`` and elastic body attachments.

References, none of them from symtmm:

* a pinned-pinned beam with a sprung mass ``M, k, c`` at ``x0``: its classical
  frequency equation ``(M lam^2 + s) + s M lam^2 G(x0, x0) / EI = 0``, ``s = k + c
  lam``, with the closed-form Green's function of the beam (tests/damped_reference.py);
  undamped roots by sign changes on a fine grid, polished in mpmath; damped ones
  followed from them while the dashpot grows;
* two identical pinned-pinned beams joined through one sprung mass by equal springs:
  the out-of-phase family leaves the mass still (each beam on a grounded spring ``k``),
  the in-phase family is one beam carrying a sprung mass ``M/2``;
* the finite-element model with the spring between beam and mass (test_theories_fe.py).
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import sympy as sp
from cli_contract import assert_contract, run_cli
from damped_reference import pp_char, pp_green

from symtmm import api
from symtmm.model import Attachment, Beam, Model, RigidBody, oscillator
from symtmm.roots.count import Counter
from symtmm.solve import solve

PP = dict(left="pinned", right="pinned")


def _oscillator_char(lam, x0, M, k, c=0, EI=1, m=1, L=1):
    """The pinned-pinned beam's frequency equation with a sprung mass at ``x0``."""
    s = k + c * lam
    beta = mpmath.root(-m * lam**2 / EI, 4)
    return (M * lam**2 + s) + s * M * lam**2 * pp_green(beta, x0, x0, L) / EI


def _axis_roots(f, omega_max, step=1e-3):
    """Roots of a real function of omega: sign changes of ``f(omega) sin(beta)`` on a grid
    in ``Omega = sqrt(omega)`` (no poles), polished by bisection at 30 digits."""
    def g(w):
        return f(w) * mpmath.sin(mpmath.sqrt(w))

    with mpmath.workdps(30):
        grid = [mpmath.mpf(v) ** 2 for v in np.arange(0.2, math.sqrt(omega_max), step)]
        values = [g(w) for w in grid]
        roots = []
        for a, b, fa, fb in zip(grid, grid[1:], values, values[1:]):
            if fa * fb < 0:
                roots.append(mpmath.findroot(g, (a, b), solver="anderson"))
        return [float(r) for r in roots]


def _undamped(x0, M, k):
    def f(w):
        return mpmath.re(_oscillator_char(mpmath.mpc(0, w), x0, M, k))
    return f


@pytest.mark.parametrize("x0, M, k", [("3/10", "1/20", 5), ("1/2", "1/10", 200),
                                      ("7/10", "1/5", "97/10")])
def test_sprung_mass_on_a_pinned_beam_against_its_frequency_equation(x0, M, k):
    model = Model((Beam("b", 1, 1, 1, **PP),), bodies=(oscillator("o", "b", x0, M, k),))
    got = [float(e.lam.imag) for e in solve(model, count=7, digits=15)]
    ref = _axis_roots(_undamped(float(sp.Rational(x0)), float(sp.Rational(M)),
                                float(sp.Rational(k))), got[-1] * 1.05)
    assert len(ref) == len(got)
    np.testing.assert_allclose(got, ref, rtol=1e-12)


def test_the_count_is_right_across_the_oscillators_own_frequency():
    """Nothing missed or invented at or near sqrt(k/M) (a pole of the condensed stiffness;
    here the mass is a freedom of its own)."""
    M, k = 0.05, 0.05 * math.pi**4           # tuned to the beam's first frequency
    model = Model((Beam("b", 1, 1, 1, **PP),),
                  bodies=(oscillator("o", "b", "3/10", "1/20", sp.Rational(1, 20) * sp.pi**4),))
    ref = _axis_roots(_undamped(0.3, M, k), 60.0)
    own = math.sqrt(k / M)
    probes = np.array(sorted([own * (1 + d) for d in (-1e-9, -1e-4, 0, 1e-4, 1e-9)]
                             + list(np.linspace(0.5, 59.0, 40))))
    counter = Counter(model, 60.0)
    # (double precision leaves the points next to sqrt(k/M) undecided: there the mass's
    # leading minor k - M omega^2 nearly vanishes; count() decides them in more digits)
    counts = [counter.count(w) for w in probes]
    assert counts == [sum(r < w for r in ref) for w in probes]


def test_mass_between_two_identical_beams_decouples():
    x0, M, k = "2/5", "3/10", 40
    pair = Model((Beam("a", 1, 1, 1, **PP), Beam("b", 1, 1, 1, **PP)),
                 bodies=(oscillator("m", ("a", "b"), x0, M, k),))
    got = [float(e.lam.imag) for e in solve(pair, count=8, digits=15)]
    top = got[-1] * 1.02
    # out of phase: the mass does not move, each beam sits on a grounded spring k
    spring = _axis_roots(lambda w: mpmath.re(pp_char(mpmath.mpc(0, w), 1, 1, 1,
                                                     [(0.4, 40, 0)])), top)
    # in phase: each beam carries half the mass on its spring
    carried = _axis_roots(_undamped(0.4, 0.15, 40), top)
    ref = sorted(spring + carried)[:len(got)]
    np.testing.assert_allclose(got, ref, rtol=1e-12)


def _damped_reference(x0, M, k, c, undamped, steps=16):
    """Damped roots followed from the undamped ones while the dashpot grows from 0."""
    out = []
    with mpmath.workdps(30):
        for w in undamped:
            z = mpmath.mpc(0, w)
            for j in range(1, steps + 1):
                cj = c * mpmath.mpf(j) / steps
                z = mpmath.findroot(lambda lam, cj=cj: _oscillator_char(lam, x0, M, k, cj),
                                    (z, z * (1 + mpmath.mpf(10) ** -8)))
            assert abs(z - mpmath.mpc(0, w)) < 0.1 * w          # (it stayed on its branch)
            out.append(complex(z))
    return out


def test_damped_sprung_mass_against_its_frequency_equation():
    x0, M, k, c = 0.3, 0.05, 0.05 * math.pi**4, 2 * 0.1 * 0.05 * math.pi**2
    model = Model((Beam("b", 1, 1, 1, **PP),),
                  bodies=(oscillator("o", "b", "3/10", "1/20", sp.Rational(1, 20) * sp.pi**4,
                                     sp.Rational(1, 100) * sp.pi**2),))
    spec = solve(model, omega_max=100, digits=12)
    got = sorted((complex(e.lam) for e in spec), key=lambda z: z.imag)
    ref = sorted(_damped_reference(x0, M, k, c, _axis_roots(_undamped(x0, M, k), 100.0)),
                 key=lambda z: z.imag)
    assert len(got) == len(ref)
    for g, r in zip(got, ref):
        assert abs(g - r) <= 1e-10 * abs(r), (g, r)
    assert all(e.proof for e in spec)


def test_derived_closed_form_vanishes_at_the_reference_roots():
    model = Model((Beam("b", 1, 1, 1, **PP),), bodies=(oscillator("o", "b", "3/10", "1/20", 5),))
    ce = api.derive(model, max_seconds=60)
    delta = sp.lambdify(ce.variable, ce.delta, "mpmath")
    with mpmath.workdps(30):
        for w in _axis_roots(_undamped(0.3, 0.05, 5.0), 120.0):
            w = mpmath.findroot(_undamped(mpmath.mpf("0.3"), mpmath.mpf("0.05"), 5), w)
            h = w * mpmath.mpf(10) ** -12
            assert abs(delta(w)) < 1e-6 * max(abs(delta(w - h)), abs(delta(w + h)))


def test_an_oscillator_is_a_body_on_springs():
    """The API's oscillator and a body written out with elastic attachments agree, and a
    body on one spring at its centre of mass is the same sprung mass."""
    tmd = oscillator("o", "b", "1/4", 2, 30, "1/2")
    assert tmd == RigidBody("o", (Attachment("b", "1/4", k=30, c="1/2"),), M=2, xc="1/4")
    beam = Beam("b", 1, 1, 1, **PP)
    assert Model((beam,), bodies=(tmd,)).body_frame(tmd).freedoms == ("Y",)
    rocking = RigidBody("r", (Attachment("b", "1/4", k=30), Attachment("b", "3/4", k=30)),
                        M=1, J="1/10", xc="1/2")
    frame = Model((beam,), bodies=(rocking,)).body_frame(rocking)
    assert frame.freedoms == ("Y", "Theta")
    assert frame.rows == ({"Y": 1, "Theta": sp.Rational(-1, 4)}, {"Y": 1, "Theta": sp.Rational(1, 4)})


def test_with_dashpots_scaled_reaches_the_oscillators():
    beam = Beam("b", 1, 1, 1, **PP)
    model = Model((beam,), bodies=(oscillator("o", "b", "1/2", 1, 10, 2),))
    assert model.damped
    assert not model.with_dashpots_scaled(0).damped
    assert model.with_dashpots_scaled(3).bodies[0].attachments[0].c == 6


# -- the model file ---------------------------------------------------------------------

BEAMS = """
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
left = "clamped"
right = "free"
"""


def test_model_file_oscillators():
    model = api.loads(BEAMS + """
[[oscillator]]
beam = "a"
x = 0.5
M = 0.1
k = 10
c = 0.2

[[oscillator]]
name = "link"
between = ["a", "b"]
x = 0.75
M = 0.3
k = [20, 30]
""")
    first, link = model.bodies
    assert first.name == "oscillator1" and first.M == sp.Rational(1, 10)
    assert [(a.beam, a.k, a.c) for a in first.attachments] == [("a", 10, sp.Rational(1, 5))]
    assert [(a.beam, a.k, a.c) for a in link.attachments] == [("a", 20, 0), ("b", 30, 0)]
    assert model.damped


@pytest.mark.parametrize("table, message", [
    ('beam = "a"\nbetween = ["a", "b"]\nx = 0.5\nM = 1\nk = 1', "oscillator[1]: give either"),
    ('x = 0.5\nM = 1\nk = 1', "oscillator[1]: give either"),
    ('beam = "c"\nx = 0.5\nM = 1\nk = 1', "oscillator[1].beam: unknown beam 'c'"),
    ('between = ["a", "a"]\nx = 0.5\nM = 1\nk = 1', "oscillator[1].between: the two beams"),
    ('between = ["a", "b"]\nx = 0.5\nM = 1\nk = [1, 2, 3]', "oscillator[1].k: expected one"),
    ('beam = "a"\nx = 0.5\nM = 0\nk = 1', "oscillator[1].M: a body held by springs only"),
    ('beam = "a"\nx = 0.5\nM = 1\nk = -1', "oscillator[1].k"),
    ('beam = "a"\nx = 1.5\nM = 1\nk = 1', "oscillator[1].x: x = 3/2 lies outside"),
    ('beam = "a"\nx = 0.5\nM = 1\nk = 1\nJ = 2', "oscillator[1].J: unknown field 'J'"),
])
def test_bad_oscillators_get_one_line_errors(tmp_path, table, message):
    path = tmp_path / "bad.toml"
    path.write_text(BEAMS + "\n[[oscillator]]\n" + table + "\n")
    run = run_cli(["solve", path, "--count", "1"], limit=30)
    assert_contract(run, 30)
    assert run.code == 2 and message in run.stderr, run.stderr


ROCKING = """
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[rigid]]
name = "machine"
springs = ["a@0.2", "a@0.75"]
k = [40, 60]
M = 0.3
J = 0.025
xc = 0.5
"""


def test_a_rigid_body_on_springs_in_a_model_file():
    """[[rigid]] springs = [...]: the file's body is the Python one that the finite-element
    model checks (tests/test_theories_fe.py, "body-on-springs")."""
    from_file = api.loads(ROCKING)
    in_python = Model((Beam("a", 1, 1, 1, **PP),),
                      bodies=(RigidBody("r", (Attachment("a", "1/5", k=40),
                                              Attachment("a", "3/4", k=60)),
                                        M="3/10", J="1/40", xc="1/2"),))
    assert [str(e) for e in solve(from_file, count=5)] == \
        [str(e) for e in solve(in_python, count=5)]


@pytest.mark.parametrize("change, message", [
    (("k = [40, 60]\n", ""), "rigid[1].k: missing field 'k'"),
    (('springs = ["a@0.2", "a@0.75"]\n', 'attach = ["a@0.2"]\n'), "rigid[1].k: k and c belong"),
    (("k = [40, 60]", "k = [40, 60, 70]"), "rigid[1].k: expected one value per spring (2)"),
    (('springs = ["a@0.2", "a@0.75"]', 'springs = ["a@1.2", "a@0.75"]'),
     "rigid[1].springs: "),
])
def test_bad_springs_of_a_rigid_body(tmp_path, change, message):
    path = tmp_path / "bad.toml"
    path.write_text(ROCKING.replace(*change))
    run = run_cli(["solve", path, "--count", "1"], limit=30)
    assert_contract(run, 30)
    assert run.code == 2 and message in run.stderr, run.stderr


def test_every_eigenvalue_of_the_damper_example_is_proved_in_balls():
    """Near the third eigenvalue the enclosure of Delta over a disk exceeds |Delta| by
    about 1e14: of the disks 1e10, 1e14 and 1e18 times the box none leaves Rouche's
    inequality room, a radius between them does."""
    pytest.importorskip("flint")
    from symtmm.modelfile import load
    spec = solve(load("examples/tuned_mass_damper.toml"), count=10)
    assert len(spec) == 10
    assert all("ball" in e.proof for e in spec), [e.proof for e in spec]
