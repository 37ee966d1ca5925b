"""Rods in axial and torsional vibration: ``[[rod]]`` and :func:`symtmm.model.rod`.

References, none of them from symtmm:

* a uniform rod's closed forms: fixed-fixed ``omega_n = n pi c / L``, fixed-free
  ``(2n - 1) pi c / (2 L)``, free-free ``n pi c / L`` and a rigid mode, ``c = sqrt(EA/m)``
  (``sqrt(GJ/rhoIp)`` in torsion); on an axial foundation ``omega**2 = c**2 beta**2 + kw/m``;
* a rod with a tip mass ``M`` (inertia ``J``): ``beta L tan(beta L) = m L / M``
  (``rhoIp L / J``), roots by mpmath;
* Kukla's two identical rods joined by springs ``k``: in phase one rod, out of phase one
  rod held by grounded springs ``2 k``, whose frequency equation comes from the rod's
  Green's function ``G(x, s) = sin(beta min) cos(beta (L - max)) / (EA beta cos(beta L))``:
  ``det(I + K G(x_i, x_j)) = 0``, roots by sign changes and mpmath, no transfer matrix;
* a damped rod with a grounded spring-dashpot ``K = k + c lam`` at ``x0``:
  ``EA beta cos(beta L) + K sin(beta x0) cos(beta (L - x0)) = 0``, ``beta**2 = -m lam**2/EA``,
  roots followed from the undamped ones by mpmath;
* a beam and a rod in one model are independent: its spectrum is the union of theirs
  (the beam's closed form ``(n pi)**2`` pinned-pinned).
"""

from __future__ import annotations

import itertools
import math

import mpmath
import numpy as np
import pytest
from cli_contract import assert_contract, run_cli
from rod_reference import family, tip_roots

from symtmm.errors import ModelError
from symtmm.model import Beam, Mass, Model, Spring, joint, oscillator, rod
from symtmm.modelfile import load, loads
from symtmm.modes.shapes import mode_shapes
from symtmm.solve import solve


def _omegas(spectrum) -> list:
    out = []
    for e in spectrum:
        out += [float(e.omega)] * e.multiplicity
    return out


@pytest.mark.parametrize("left, right, kind", [
    ("fixed", "fixed", "fixed-fixed"), ("fixed", "free", "fixed-free"),
    ("free", "fixed", "fixed-free"), ("free", "free", "free-free"),
])
def test_uniform_rod_against_its_closed_forms(left, right, kind):
    EA, m, L = 4, "1/4", 3           # c = 4
    model = Model((rod("r", EA=EA, m=m, L=L, left=left, right=right),))
    got = _omegas(solve(model, count=6))
    ref = family(kind, 4.0, 3.0, 6)
    np.testing.assert_allclose(got, ref, rtol=1e-14, atol=1e-14)


def test_axial_and_torsional_families_meet_with_exact_multiplicity():
    """Axially ``c = 2``, in torsion ``sqrt(GJ/rhoIp) = 2`` too: every root is double."""
    model = Model((rod("s", EA=4, m=1, L=1, GJ=1, rhoIp="1/4", left="fixed", right="free"),))
    spectrum = solve(model, count=6)
    assert [e.multiplicity for e in spectrum] == [2, 2, 2]
    np.testing.assert_allclose(_omegas(spectrum), np.repeat([math.pi, 3 * math.pi,
                                                             5 * math.pi], 2), rtol=1e-14)


@pytest.mark.parametrize("left, right, axial, torsion", [
    # (fixed-axial: u = 0, free to twist; fixed-torsion: phi = 0, free to move axially)
    ("fixed-axial", "free", "fixed-free", "free-free"),
    ("fixed-torsion", "fixed", "free-fixed", "fixed-fixed"),
    ("free", "free", "free-free", "free-free"),
])
def test_ends_per_motion(left, right, axial, torsion):
    """``c = 1`` axially and ``c = 3`` in torsion (L = 1): the union of the two families."""
    model = Model((rod("s", EA=1, m=1, L=1, GJ=9, rhoIp=1, left=left, right=right),))
    ref = sorted(family(axial, 1.0, 1.0, 8) + family(torsion, 3.0, 1.0, 8))[:8]
    got = _omegas(solve(model, count=8))
    np.testing.assert_allclose(got, ref, rtol=1e-14, atol=1e-12)


def test_axial_foundation():
    """Free-free on an axial foundation: ``omega**2 = (n pi)**2 + kw/m``, no rigid mode."""
    model = Model((rod("r", EA=1, m=2, L=1, kw=6, left="free", right="free"),))
    ref = [math.sqrt(((n * math.pi) ** 2 + 6) / 2) for n in range(5)]
    np.testing.assert_allclose(_omegas(solve(model, count=5)), ref, rtol=1e-14)


def test_shaft_with_a_disc_example():
    """examples/shaft_with_disc.toml against the two tip-mass frequency equations."""
    model = load("examples/shaft_with_disc.toml")
    E, G, rho, d, L, M, J = 2.1e11, 8.1e10, 7850, 0.05, 1.5, 20, 0.4
    A, Ip = math.pi * d**2 / 4, math.pi * d**4 / 32
    axial = [x / L * math.sqrt(E / rho) for x in tip_roots(rho * A * L / M, 4)]
    torsion = [x / L * math.sqrt(G / rho) for x in tip_roots(rho * Ip * L / J, 4)]
    ref = sorted(axial + torsion)[:6]
    np.testing.assert_allclose(_omegas(solve(model, count=6)), ref, rtol=1e-13)


def _green_roots(EA, m, L, springs, omega_max):
    """Roots of ``cos(beta L) det(I + K G)`` for a fixed-free rod held by grounded springs
    ``(x_i, K_i)``: sign changes on a fine grid, then mpmath (30 digits)."""
    def f(w):
        b = w * mpmath.sqrt(mpmath.mpf(m) / EA)
        n = len(springs)
        A = mpmath.matrix(n, n)
        for i, (xi, Ki) in enumerate(springs):
            for j, (xj, _) in enumerate(springs):
                lo, hi = min(xi, xj), max(xi, xj)
                # cos(beta L) G, which has no pole
                A[i, j] = (1 if i == j else 0) * mpmath.cos(b * L) \
                    + Ki * mpmath.sin(b * lo) * mpmath.cos(b * (L - hi)) / (EA * b)
        return mpmath.det(A) * mpmath.cos(b * L) ** (1 - n)

    with mpmath.workdps(30):
        grid = np.linspace(1e-3, omega_max, 4000)
        values = [f(mpmath.mpf(w)) for w in grid]
        roots = []
        for a, b, fa, fb in zip(grid, grid[1:], values, values[1:]):
            if fa * fb < 0:
                roots.append(float(mpmath.findroot(f, (mpmath.mpf(a), mpmath.mpf(b)),
                                                   solver="anderson")))
    return roots


def test_kukla_rods_example_against_the_decoupled_families():
    """examples/kukla_rods.toml: in phase the fixed-free rod, out of phase the rod held by
    grounded springs of 2 k at the same points (Green's function)."""
    model = load("examples/kukla_rods.toml")
    EA, m, L, k = 2.1e8, 7.85, 2.0, 5e7
    c = math.sqrt(EA / m)
    W = 30000.0
    in_phase = [(2 * n - 1) * math.pi / (2 * L) * c for n in range(1, 10)]
    out = _green_roots(EA, m, L, [(0.5, 2 * k), (1.2, 2 * k), (2.0, 2 * k)], W)
    ref = sorted([w for w in in_phase if w <= W] + out)
    got = _omegas(solve(model, omega_max=W))
    assert len(got) == len(ref) == 8
    np.testing.assert_allclose(got, ref, rtol=1e-13)


def test_damped_rod_against_its_frequency_equation():
    """Every root to 1e-12, and the count of the region proved (winding number in balls,
    the rod's closed forms on Taylor jets)."""
    EA, m, L, x0, k, c = 1, 1, 1, mpmath.mpf(3) / 10, 2, mpmath.mpf(1) / 2

    def f(lam, cc):
        beta = mpmath.sqrt(-m * lam**2 / EA)
        K = k + cc * lam
        return EA * beta * mpmath.cos(beta * L) + K * mpmath.sin(beta * x0) * \
            mpmath.cos(beta * (L - x0))

    model = Model((rod("r", EA=EA, m=m, L=L, left="fixed", right="free"),),
                  (Spring("r", "ground", "3/10", k=2, c="1/2"),))
    spectrum = solve(model, omega_max=12, prove_count=True)
    assert any("count in the search region is proved" in n for n in spectrum.notes)
    got = sorted((complex(e.lam) for e in spectrum), key=lambda z: z.imag)
    with mpmath.workdps(30):
        undamped = [w for w in _green_roots(EA, m, L, [(0.3, 2.0)], 12.5)]
        ref = []
        for w in undamped:
            z = mpmath.mpc(0, w)
            for s in np.linspace(0, 1, 21)[1:]:           # the dashpot grows to c
                z = mpmath.findroot(lambda lam, s=s: f(lam, s * c), z)
            ref.append(complex(z))
    assert len(got) == len(ref) == 4
    for g, r in zip(got, ref):
        assert abs(g - r) <= 1e-12 * abs(r), (g, r)


def test_a_beam_and_a_rod_are_independent():
    """Pinned-pinned beam ``(n pi)**2``, fixed-fixed rod ``n pi c``, c = 5: the union."""
    model = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),
                   rod("r", EA=25, m=1, L=1)),
                  (Spring("b", "ground", "1/3", k=0),))
    ref = sorted([(n * math.pi) ** 2 for n in range(1, 8)] + [5 * n * math.pi
                                                               for n in range(1, 8)])[:8]
    np.testing.assert_allclose(_omegas(solve(model, count=8)), ref, rtol=1e-14)


def test_a_sprung_mass_on_a_rod():
    """A mass M on a spring k at the free end of a fixed-free rod (``u = sin(beta x)``):
    ``EA beta cos(beta L) = K_eff sin(beta L)``, ``K_eff = k M w**2 / (k - M w**2)`` the
    oscillator seen from the rod's end."""
    EA, m, L, M, k = 1.0, 1.0, 1.0, 0.5, 3.0
    model = Model((rod("r", EA=EA, m=m, L=L, left="fixed", right="free"),),
                  bodies=(oscillator("o", "r", 1, "1/2", 3),))

    def f(w):
        b = w
        return EA * b * mpmath.cos(b * L) * (k - M * w**2) - k * M * w**2 * mpmath.sin(b * L)

    with mpmath.workdps(30):
        grid = np.linspace(0.01, 9, 3000)
        ref = [float(mpmath.findroot(f, (mpmath.mpf(a), mpmath.mpf(b)), solver="anderson"))
               for a, b in itertools.pairwise(grid) if f(a) * f(b) < 0]
    got = _omegas(solve(model, omega_max=9))
    assert len(got) == len(ref) >= 3
    np.testing.assert_allclose(got, ref, rtol=1e-13)


def test_axial_mode_shape_of_a_fixed_free_rod():
    """``u(x) = sin(beta x)``, mass-normalised: ``int m u**2 = 1``, so ``u = sqrt(2/(m L))
    sin(beta x)`` up to its sign."""
    model = Model((rod("r", EA=1, m=2, L=1, left="fixed", right="free"),))
    modes = mode_shapes(model, count=2, points=11)
    for n, mode in enumerate(modes.modes, 1):
        shape = mode.beams["r"]
        beta = (2 * n - 1) * math.pi / 2
        ref = math.sqrt(2 / 2) * np.sin(beta * np.asarray(shape.x, dtype=float))
        u = np.asarray(shape.Y, dtype=complex).real
        sign = np.sign(u[-1]) * np.sign(ref[-1])
        np.testing.assert_allclose(sign * u, ref, atol=1e-10)


# -- the model file and its errors ----------------------------------------------------------

ROD = """
[[rod]]
name = "r"
EA = 1
m = 1
L = 1
left = "fixed"
right = "free"
"""


def test_model_file_rods_and_axial_springs():
    model = loads(ROD + ROD.replace('"r"', '"s"') + """
[[spring]]
between = ["r", "s"]
x = 0.4
k = 5
kind = "axial"
""")
    assert [b.kind for b in model.beams] == ["rod", "rod"]
    assert model.springs[0].kind == "translational"
    # one fixed-free rod and the out-of-phase family (grounded 2k = 10 at 0.4)
    ref = sorted([(2 * n - 1) * math.pi / 2 for n in range(1, 4)]
                 + _green_roots(1.0, 1.0, 1.0, [(0.4, 10.0)], 8.5))
    got = _omegas(solve(model, omega_max=8.5))
    np.testing.assert_allclose(got, ref, rtol=1e-13)

BEAM = '[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\nright = "pinned"\n'


@pytest.mark.parametrize("text, field, message", [
    (ROD.replace('right = "free"', 'right = "pinned"'), "rod[1] (r).right", "unknown rod end"),
    (ROD.replace("EA = 1", "EA = -1"), "EA", "positive"),
    (ROD + "GJ = 1\n", "rhoIp", "torsion needs both GJ and rhoIp"),
    (ROD.replace("EA = 1\n", ""), "rod[1]", "EA"),
    (ROD + '[[spring]]\nbetween = ["r", "ground"]\nx = 0.5\nk = 1\nkind = "rotational"\n',
     "kind", "no torsion"),
    (ROD + '[[mass]]\nbeam = "r"\nx = 0.5\nM = 1\nJ = 1\n', "J", "no torsion"),
    (ROD + BEAM + '[[spring]]\nbetween = ["r", "b"]\nx = 0.5\nk = 1\n', "between",
     "two beams or two rods"),
    (BEAM + '[[spring]]\nbetween = ["b", "ground"]\nx = 0.5\nk = 1\nkind = "axial"\n', "kind",
     "springs on rods"),
    (ROD + ROD.replace('"r"', '"s"') + '[[layer]]\nbetween = ["r", "s"]\nk = 1\n', "between",
     "'r' is a rod"),
    (ROD + '[[rigid]]\nattach = ["r@0.5"]\nM = 1\nJ = 1\n', "J", "nothing it holds turns"),
    # a polar inertia that a parameter makes 0, on a rod free to twist at both ends
    ("[parameters]\np = 0\n" + ROD.replace('left = "fixed"', 'left = "free"')
     + 'GJ = 1\nrhoIp = "p"\n', "rhoIp", "must be positive"),
])
def test_bad_rods_get_one_line_errors(text, field, message):
    with pytest.raises(ModelError) as info:
        loads(text)
    assert field in str(info.value.field or "") + str(info.value), str(info.value)
    assert message in str(info.value)
    assert "\n" not in str(info.value)


def test_rod_api_errors():
    with pytest.raises(ModelError, match="unknown rod end"):
        rod("r", EA=1, m=1, L=1, left="clamped")
    with pytest.raises(ModelError, match="fixed-axial"):
        rod("r", EA=1, m=1, L=1, GJ=1, rhoIp=1, left="pinned")
    with pytest.raises(ModelError, match="built by symtmm.model.rod"):
        Beam("r", 1, 1, 1, theory="rod", N=1)
    # a hinge joint of rod ends (no J) moves along the rods: allowed
    Model((rod("a", EA=1, m=1, L=1, right="free"), rod("b", EA=1, m=1, L=1, x0=1,
                                                       left="free")),
          bodies=(joint("j", [("a", 1), ("b", 1)], kind="hinge"),))
    with pytest.raises(ModelError, match="no torsion"):
        Model((rod("a", EA=1, m=1, L=1),), masses=(Mass("a", "1/2", 1, J=1),))


@pytest.mark.parametrize("command", [
    ["solve", "--count", "3"],
    ["solve", "--count", "3", "--json"],
    ["modes", "--count", "2", "--points", "5"],
    ["sweep", "--param", "k", "--from", "1e7", "--to", "5e7", "--steps", "3", "--count", "3"],
    ["scan", "--omega-max", "10000", "--points", "40"],
    ["codegen", "--lang", "python"],
])
def test_every_command_takes_the_rod_example(command):
    result = run_cli(command[:1] + ["examples/kukla_rods.toml"] + command[1:])
    assert_contract(result)
    assert result.code == 0, result.stderr


def test_rod_matrices_agree_with_the_theories_series():
    """The rod family's closed forms and series against the theories' series in ``(t, d)``
    with doubling (:func:`symtmm.numeric.segments.theory_matrices`, ``kGA = 0``) at 50
    digits, on both sides of ``|z| = 1`` and off the axes."""
    import sympy as sp

    from symtmm.numeric.arith import MP
    from symtmm.numeric.segments import (
        rod_constants,
        rod_matrices,
        theory_constants,
        theory_matrices,
    )
    ar = MP.from_digits(50)
    EA, GJ, m, kw, rhoIp, l = 3, 2, sp.Rational(1, 2), 1, sp.Rational(1, 5), sp.Rational(7, 10)
    # (a batch is all real or all complex)
    for points in ((-0.3, -40.0, 25.0), ((0.5 + 9j) ** 2, (-3 + 2j) ** 2, 0.2j)):
        with ar:
            lam2 = ar.array([ar.number(v) for v in points])
            U1 = rod_matrices(ar, rod_constants(ar, [(EA, GJ, m, kw, rhoIp, l)]), lam2)
            U2 = theory_matrices(ar, theory_constants(ar, [(GJ, 0, sp.Rational(-1, EA), 0,
                                                            rhoIp, m, kw, l)]), lam2)
        for a, b in zip(U1.reshape(-1), U2.reshape(-1)):
            assert abs(complex(a - b)) <= 1e-40 * max(1.0, abs(complex(b))), (a, b)
