"""Closed-form characteristic equations of beams beyond Euler-Bernoulli, rigid bodies and joints.

References, independent of the transfer matrices (derived from the field
equations in ``derivations/theory_frequency_equations.py``):

- pinned-pinned beams: ``b L = n pi`` and ``omega**2 = (EI q**2 + N q + kw) /
  (m + rhoI q)``, ``q = (n pi / L)**2`` (Rayleigh, axial force, foundation);
  Timoshenko: the two roots of ``det [[kGA q + N q + kw - m w2, -kGA sqrt q],
  [-kGA sqrt q, EI q + kGA - rhoI w2]] = 0``, and the shear mode at
  ``omega**2 = kGA/rhoI``;
- Euler-Bernoulli on a foundation, clamped-clamped: ``cos(bL) cosh(bL) = 1``,
  ``b**4 = (m omega**2 - kw)/EI``;
- Timoshenko clamped-free: Huang's (1961) frequency equation;
- symmetry decoupling of trees and loops (brief and ``tests/test_decoupling.py``):
  a clamped trunk forking rigidly into two identical branches (EI/2, m/2) is a
  clamped-free beam of length L1 + L2 (in phase) or a clamped-free branch
  (opposite); a loop rejoining into a tail: one clamped-free beam, or each
  branch clamped-clamped; a clamped-hinge-clamped pair: clamped-free or
  clamped-pinned halves;
- a rigid body rigidly attached at its centre of mass is a lumped mass with
  rotary inertia (a second formulation in the model).

Every check parses ``delta`` back from the JSON (the contract) and asks that
it vanish at the reference roots and not a percent away.
"""

from __future__ import annotations

import json
from itertools import pairwise

import mpmath
import pytest
import sympy as sp

from symtmm.characteristic import OMEGA, characteristic_equation
from symtmm.cli import main
from symtmm.elements.base import LAM
from symtmm.expr import parameter_symbol
from symtmm.model import Attachment, Beam, Mass, Model, RigidBody, Spring
from symtmm.modelfile import loads

L = sp.Rational(3, 2)
EI, M = 2, 3


def _delta(eq):
    """``Delta`` of the JSON, parsed back, as an mpmath function of the variable."""
    out = json.loads(eq.to_json())
    var = sp.Symbol(out["variable"], positive=out["variable"] == "omega")
    expr = sp.sympify(out["delta"], locals={out["variable"]: var})
    assert expr.free_symbols <= {var}
    return sp.lambdify(var, expr, "mpmath")


def _vanishes(fn, w, digits=20) -> bool:
    """``fn(w)`` is ``digits`` below its size a percent either side (and that is not 0)."""
    w = mpmath.mpf(w)
    near = min(abs(fn(w * mpmath.mpf("1.01"))), abs(fn(w * mpmath.mpf("0.99"))))
    return near > 0 and abs(fn(w)) < mpmath.mpf(10) ** -digits * near


def _pp(**options):
    theory = options.pop("theory", "euler-bernoulli")
    return Model((Beam("b", EI, M, L, left="pinned", right="pinned", theory=theory, **options),))


@pytest.mark.parametrize("options", [
    dict(kw=40), dict(N=5), dict(N=-3), dict(theory="rayleigh", rhoI=sp.Rational(1, 50)),
    dict(theory="rayleigh", rhoI=sp.Rational(1, 50), N=4, kw=7)])
def test_pinned_pinned_reduces_to_sin_bL(options):
    eq = characteristic_equation(_pp(**dict(options)))
    assert eq.variable == OMEGA
    (b,) = [s for s in eq.definitions if s.name == "b_b"]
    # sin(b L) times factors that do not vanish for real b, a
    assert sp.sin(b * L) in [f for f, _ in eq.factors]
    fn = _delta(eq)
    N, kw, rhoI = (sp.sympify(options.get(k, 0)) for k in ("N", "kw", "rhoI"))
    with mpmath.workdps(40):
        for n in (1, 2, 3, 7):
            q = (n * sp.pi / L) ** 2
            w = mpmath.sqrt(sp.N((EI * q**2 + N * q + kw) / (M + rhoI * q), 40))
            assert _vanishes(fn, w), n
            # the definition of b there is n pi / L
            assert abs(sp.N(eq.definitions[b].subs(OMEGA, sp.Float(w, 40)) - sp.sqrt(q), 30)) \
                < 1e-25


def test_pinned_pinned_timoshenko_both_branches_and_the_shear_mode():
    rhoI, kGA = sp.Rational(1, 40), 60
    eq = characteristic_equation(_pp(theory="timoshenko", rhoI=rhoI, kGA=kGA))
    fn = _delta(eq)
    w2 = sp.Symbol("w2")
    with mpmath.workdps(40):
        for n in (1, 2, 3):
            q = (n * sp.pi / L) ** 2
            det = sp.Matrix([[kGA * q - M * w2, -kGA * sp.sqrt(q)],
                             [-kGA * sp.sqrt(q), EI * q + kGA - rhoI * w2]]).det()
            roots = sp.solve(det, w2)
            assert len(roots) == 2
            for root in roots:
                assert _vanishes(fn, mpmath.sqrt(sp.N(root, 40))), (n, root)
        # Y = 0, psi constant: the pure shear mode of pinned ends
        assert _vanishes(fn, mpmath.sqrt(sp.N(sp.Integer(kGA) / rhoI, 40)))
        assert not _vanishes(fn, mpmath.mpf(17))


def test_foundation_clamped_clamped_is_cos_cosh():
    kw = 40
    model = Model((Beam("b", EI, M, L, kw=kw, left="clamped", right="clamped"),))
    eq = characteristic_equation(model)
    (b,) = eq.definitions
    assert sp.simplify(eq.equation - (sp.cos(L * b) * sp.cosh(L * b) - 1)) == 0
    assert sp.simplify(eq.definitions[b] ** 4 - (M * OMEGA**2 - kw) / EI) == 0
    fn = _delta(eq)
    with mpmath.workdps(40):
        for guess in (4.73, 7.85, 11.0, 14.1):
            bl = mpmath.findroot(lambda z: mpmath.cos(z) * mpmath.cosh(z) - 1, guess)
            bn = bl / L
            assert _vanishes(fn, mpmath.sqrt((EI * bn**4 + kw) / M)), guess
        # below sqrt(kw/m) nothing vanishes
        assert not _vanishes(fn, mpmath.sqrt(mpmath.mpf(kw) / M) / 2)


def _huang(values):
    """Huang's clamped-free Timoshenko equation as a function of omega (mpmath)."""
    def f(w):
        # the constants at the working precision of the call
        EIv, m, Lv, kGA, rhoI = (mpmath.mpf(sp.Rational(values[k]).p) / sp.Rational(values[k]).q
                                 for k in ("EI", "m", "L", "kGA", "rhoI"))
        B2 = m * w**2 * Lv**4 / EIv
        r2, s2 = rhoI / (m * Lv**2), EIv / (kGA * Lv**2)
        # wave numbers: (a L)**2, -(b L)**2 roots of z**2 + B2 (r2 + s2) z - B2 (1 - B2 r2 s2)
        p, qq = B2 * (r2 + s2), -B2 * (1 - B2 * r2 * s2)
        root = mpmath.sqrt(p**2 - 4 * qq)
        aL, bL = mpmath.sqrt((-p + root) / 2), mpmath.sqrt((p + root) / 2)
        return mpmath.re(2 + (B2 * (r2 - s2) ** 2 + 2) * mpmath.cosh(aL) * mpmath.cos(bL)
                         - mpmath.sqrt(B2) * (r2 + s2) / mpmath.sqrt(1 - B2 * r2 * s2)
                         * mpmath.sinh(aL) * mpmath.sin(bL))
    return f


def test_timoshenko_clamped_free_is_huangs_equation():
    values = {"EI": EI, "m": M, "L": L, "kGA": 60, "rhoI": sp.Rational(1, 40)}
    model = Model((Beam("b", EI, M, L, left="clamped", right="free", theory="timoshenko",
                        rhoI=values["rhoI"], kGA=values["kGA"]),))
    eq = characteristic_equation(model)
    fn, huang = _delta(eq), _huang(values)
    with mpmath.workdps(40):
        grid = [mpmath.mpf(i) / 4 for i in range(1, 160)]
        signs = [(g, huang(g)) for g in grid]
        roots = [mpmath.findroot(huang, (u, v), solver="anderson")
                 for (u, fu), (v, fv) in pairwise(signs) if fu * fv < 0]
        assert len(roots) >= 4
        for w in roots:
            assert _vanishes(fn, w), w


def test_symbolic_timoshenko_contract():
    beam = Beam("b", "EI", "m", "L", left="clamped", right="free", theory="timoshenko",
                rhoI="rhoI", kGA="kGA")
    eq = characteristic_equation(Model((beam,)))
    out = eq.to_dict()
    names = {"omega": OMEGA, **{n: parameter_symbol(n) for n in ("EI", "m", "L", "rhoI", "kGA")}}
    delta = sp.sympify(out["delta"], locals=names)
    assert delta.free_symbols == set(names.values())
    assert set(out["definitions"]) == {"a_b", "b_b"}
    values = {"EI": 2, "m": 3, "L": L, "kGA": 60, "rhoI": sp.Rational(1, 40)}
    fn = sp.lambdify(OMEGA, delta.xreplace({names[k]: v for k, v in values.items()}), "mpmath")
    huang = _huang(values)
    with mpmath.workdps(40):
        w = mpmath.findroot(huang, (mpmath.mpf(1), mpmath.mpf("1.5")), solver="anderson")
        assert _vanishes(fn, w)


def _fork():
    """Clamped trunk (EI, m, L1) forking rigidly into two identical branches (EI/2, m/2, L2)."""
    L1, L2 = 1, sp.Rational(3, 5)
    half = sp.Rational(1, 2)
    beams = (Beam("t", 1, 1, L1, left="clamped", right="free"),
             Beam("u", half, half, L2, x0=L1, left="free", right="free"),
             Beam("v", half, half, L2, x0=L1, left="free", right="free"))
    body = RigidBody("j", (Attachment("t", L1), Attachment("u", L1), Attachment("v", L1)))
    return Model(beams, bodies=(body,)), L1, L2


def _cf_roots(count):
    return [mpmath.findroot(lambda z: mpmath.cos(z) * mpmath.cosh(z) + 1, g)
            for g in (1.875, 4.694, 7.855, 10.996)[:count]]


def test_fork_families_and_report():
    model, L1, L2 = _fork()
    eq = characteristic_equation(model)
    assert eq.seconds > 0 and eq.count_ops() > 0
    out = eq.to_dict()
    assert out["count_ops"] == eq.count_ops() and out["seconds"] >= 0
    fn = _delta(eq)
    with mpmath.workdps(40):
        for bl in _cf_roots(4):
            # in phase: one clamped-free beam L1 + L2; opposite: a clamped-free branch L2
            for length in (L1 + L2, L2):
                assert _vanishes(fn, (bl / mpmath.mpf(sp.N(length, 40))) ** 2), (bl, length)
        assert not _vanishes(fn, mpmath.mpf(10))


def test_loop_families():
    L1, L2 = 1, sp.Rational(3, 5)
    half = sp.Rational(1, 2)
    beams = (Beam("t", 1, 1, L1, left="clamped", right="free"),
             Beam("u", half, half, L2, x0=L1, left="free", right="free"),
             Beam("v", half, half, L2, x0=L1, left="free", right="free"),
             Beam("w", 1, 1, L1, x0=L1 + L2, left="free", right="free"))
    bodies = (RigidBody("j", (Attachment("t", L1), Attachment("u", L1), Attachment("v", L1))),
              RigidBody("k", (Attachment("u", L1 + L2), Attachment("v", L1 + L2),
                              Attachment("w", L1 + L2))))
    eq = characteristic_equation(Model(beams, bodies=bodies))
    fn = _delta(eq)
    with mpmath.workdps(40):
        for bl in _cf_roots(3):       # in phase: clamped-free of length 2 L1 + L2
            assert _vanishes(fn, (bl / mpmath.mpf(sp.N(2 * L1 + L2, 40))) ** 2), bl
        for g in (4.73, 7.853, 10.996):  # opposite: each branch clamped-clamped
            bl = mpmath.findroot(lambda z: mpmath.cos(z) * mpmath.cosh(z) - 1, g)
            assert _vanishes(fn, (bl / mpmath.mpf(sp.N(L2, 40))) ** 2), g


def test_hinge_between_clamped_beams():
    model = loads("""
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "clamped"
right = "free"
[[beam]]
name = "b"
EI = 1
m = 1
L = 1
x0 = 1
left = "free"
right = "clamped"
[[joint]]
ends = ["a.right", "b.left"]
kind = "hinge"
""")
    fn = _delta(characteristic_equation(model))
    with mpmath.workdps(40):
        for bl in _cf_roots(3):        # symmetric: clamped-free halves
            assert _vanishes(fn, bl**2), bl
        for g in (3.927, 7.069, 10.21):  # antisymmetric: clamped-pinned halves, tan = tanh
            bl = mpmath.findroot(lambda z: mpmath.tan(z) - mpmath.tanh(z), g)
            assert _vanishes(fn, bl**2), g


@pytest.mark.parametrize("timoshenko", [False, True])
def test_body_at_its_centre_is_a_lumped_mass(timoshenko):
    opts = dict(theory="timoshenko", rhoI=sp.Rational(1, 100), kGA=50) if timoshenko else {}
    beam = Beam("a", 1, 1, 1, left="clamped", right="free", **opts)
    x, Mb, J = sp.Rational(7, 10), 2, sp.Rational(1, 5)
    body = Model((beam,), bodies=(RigidBody("r", (Attachment("a", x),), M=Mb, J=J),))
    mass = Model((beam,), masses=(Mass("a", x, Mb, J),))
    f_body = _delta(characteristic_equation(body))
    f_mass = _delta(characteristic_equation(mass))
    with mpmath.workdps(40):
        ratios = [f_body(w) / f_mass(w) for w in (mpmath.mpf("0.9"), mpmath.mpf("13.1"),
                                                 mpmath.mpf("47.3"))]
    assert all(abs(r / ratios[0] - 1) < mpmath.mpf(10) ** -25 for r in ratios)


def test_two_timoshenko_beams_in_phase_family_and_report():
    """Identical pinned-pinned Timoshenko beams joined by a spring (and a dashpot): the
    in-phase family is one beam (undamped, lam = i omega at its closed form)."""
    T = dict(theory="timoshenko", rhoI=sp.Rational(1, 100), kGA=50)
    beams = (Beam("a", 1, 1, 1, left="pinned", right="pinned", **T),
             Beam("b", 1, 1, 1, left="pinned", right="pinned", **T))
    for c, variable in ((0, OMEGA), (1, LAM)):
        eq = characteristic_equation(Model(beams, (Spring("a", "b", sp.Rational(2, 5), 30, c),)))
        assert eq.variable == variable
        assert eq.seconds > 0 and eq.count_ops() > 0
        fn = _delta(eq)
        w2 = sp.Symbol("w2")
        with mpmath.workdps(40):
            for n in (1, 2):
                q = (n * sp.pi) ** 2
                det = sp.Matrix([[50 * q - w2, -50 * sp.sqrt(q)],
                                 [-50 * sp.sqrt(q), q + 50 - w2 / 100]]).det()
                w = mpmath.sqrt(sp.N(min(sp.solve(det, w2)), 40))
                if variable == OMEGA:
                    assert _vanishes(fn, w), n
                else:
                    at, near = abs(fn(mpmath.mpc(0, w))), abs(fn(mpmath.mpc(0, w * 1.01)))
                    assert at < mpmath.mpf(10) ** -20 * near, n


def test_cli_json_has_definitions(tmp_path, capsys):
    path = tmp_path / "w.toml"
    path.write_text("""
[[beam]]
name = "b"
EI = 2
m = 3
L = 1.5
kw = 40
left = "clamped"
right = "clamped"
""")
    assert main(["derive", str(path), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["variable"] == "omega" and set(out["definitions"]) == {"b_b"}
    b = sp.Symbol("b_b", positive=True)
    definition = sp.sympify(out["definitions"]["b_b"], locals={"omega": OMEGA})
    assert sp.simplify(definition**4 - (3 * OMEGA**2 - 40) / 2) == 0
    form = sp.sympify(out["delta_Omega"], locals={"b_b": b})
    ratio = sp.simplify(form.xreplace({b: definition})
                        / sp.sympify(out["delta"], locals={"omega": OMEGA}))
    assert ratio.is_number and ratio != 0
    assert main(["derive", str(path)]) == 0
    text = capsys.readouterr().out
    assert "b_b" in text and "omega" in text
