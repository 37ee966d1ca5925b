"""Closed-form characteristic equations of beams joined by layers (``derive`` with ``[[layer]]``).

References, none of them from symtmm's closed-form stage:

* pinned beams on a layer over their whole length keep the shapes ``sin(n pi x)``: per
  ``n`` the amplitudes solve ``(EI b**4 + k L - m omega**2) a = 0`` (``b = n pi``, ``L``
  the Laplacian ``[[1, -1], [-1, 1]]``). An identical pair: in phase the single beam's
  ``omega = (n pi)**2``, out of phase ``omega**2 = (n pi)**4 + 2 K``; two different beams:
  the roots of ``det [[EI1 b**4 + k - m1 w**2, -k], [-k, EI2 b**4 + k - m2 w**2]]``. The
  derived Delta vanishes at these roots, and its roots found by sign changes are these;
* a layer between identical mirrored beams does not act on their in-phase motion: the
  single beam's textbook equation (``cos Omega cosh Omega + 1`` clamped-free) is a
  factor, whatever the stretch of the layer and springs between the two beams;
* a layer without stiffness or damping leaves the beams uncoupled;
* the numeric transfer walk ``symtmm.compile.Evaluator`` (the series ``c_j(X)`` of the
  member's matrix, no eigenvalues, no closed form) at complex ``lam``, 40 digits: the
  same ``det R`` by a second formulation (partial layers with springs, other end
  conditions, damped layers, symbolic parameters, a mass on a layered stretch).
"""

from __future__ import annotations

import json
import random
from itertools import pairwise

import mpmath
import numpy as np
import pytest
import sympy as sp
from cli_contract import assert_contract, run_cli

from symtmm.characteristic import OMEGA, OMEGA_DIMLESS, characteristic_equation
from symtmm.compile import Evaluator
from symtmm.elements.base import LAM
from symtmm.expr import parameter_symbol
from symtmm.model import Beam, Layer, Mass, Model, Spring

PP = dict(left="pinned", right="pinned")
CF = dict(left="clamped", right="free")
CP = dict(left="clamped", right="pinned")
FF = dict(left="free", right="free")
Om = OMEGA_DIMLESS


def _pair(K, **ends):
    ends = ends or PP
    return Model((Beam("a", 1, 1, 1, **ends), Beam("b", 1, 1, 1, **ends)),
                 layers=(Layer("a", "b", k=K),))


def _delta(eq, values=None):
    """``Delta`` of the JSON contract, parsed back, as an mpmath function of the variable."""
    out = json.loads(eq.to_json())
    var = sp.Symbol(out["variable"], positive=out["variable"] == "omega")
    names = {name: parameter_symbol(name) for name in out["symbols"]}
    expr = sp.sympify(out["delta"], locals={out["variable"]: var, **names})
    if values:
        expr = expr.xreplace({names[k]: v for k, v in values.items()})
    assert expr.free_symbols <= {var}
    return sp.lambdify(var, expr, "mpmath")


def _vanishes(fn, w, digits=20) -> bool:
    """``|fn(w)|`` is ``digits`` below its size a percent either side (and that is not 0)."""
    w = mpmath.mpf(w)
    near = min(abs(fn(w * mpmath.mpf("1.01"))), abs(fn(w * mpmath.mpf("0.99"))))
    return near > 0 and abs(fn(w)) < mpmath.mpf(10) ** -digits * near


def _agrees_with_transfer_walk(eq, model, points=5, seed=3, digits=40) -> float:
    """Largest relative difference of ``constant * delta`` from the numeric ``det R`` of the
    transfer walk at complex ``lam`` (``digits`` digits)."""
    values = {parameter_symbol(k): v for k, v in model.parameters.items() if v is not None}
    full = (eq.constant * eq.delta).xreplace(values)
    fn = sp.lambdify(eq.variable, full, "mpmath")
    ev = Evaluator(model)
    rnd = random.Random(seed)
    worst = mpmath.mpf(0)
    with mpmath.workdps(digits):
        for _ in range(points):
            lam = mpmath.mpc(-rnd.uniform(0.1, 4), rnd.uniform(0.5, 80))
            got = fn(lam if eq.variable == LAM else lam / 1j)
            ref = ev.delta_mp(lam, dps=digits)
            worst = max(worst, abs(got - ref) / abs(ref))
    return worst


def test_identical_pinned_pair_in_and_out_of_phase():
    """Delta vanishes at omega = (n pi)**2 and at omega**2 = (n pi)**4 + 2K, nowhere between,
    and is the transfer walk's det R (double and 40 digits)."""
    K = 80
    model = _pair(K)
    eq = characteristic_equation(model)
    assert eq.variable == OMEGA
    # the closed form: the single beam's sin Omega sinh Omega, and the same in q
    q = [s for s in eq.definitions if s.name == "q_a_b"]
    assert len(q) == 1 and {sp.sin(Om), sp.sinh(Om), sp.sin(q[0]), sp.sinh(q[0])} \
        <= {f for f, _ in eq.factors}
    fn = _delta(eq)
    with mpmath.workdps(40):
        roots = sorted([(n * mpmath.pi) ** 2 for n in range(1, 5)]
                       + [mpmath.sqrt((n * mpmath.pi) ** 4 + 2 * K) for n in range(1, 5)])
        for w in roots:
            assert _vanishes(fn, w), w
        for u, v in pairwise(roots):
            mid = (u + v) / 2
            assert abs(fn(mid)) > 1e-6 * max(abs(fn(u * 1.01)), abs(fn(v * 0.99))), mid
    # det R = constant * Delta, against the numeric transfer walk (a second formulation)
    lams = np.array([-0.5 + 3j, -2 + 17.5j, 0.3 + 41j, -1 + 60j])
    full = sp.lambdify(OMEGA, eq.constant * eq.delta, "mpmath")
    got = np.array([complex(full(mpmath.mpc(lam) / 1j)) for lam in lams])
    ref = Evaluator(model).delta(lams)
    assert np.allclose(got, ref, rtol=1e-10, atol=0)
    assert _agrees_with_transfer_walk(eq, model) < mpmath.mpf(10) ** -30


def _quadratic_roots(EI, m, k, count):
    """Natural frequencies of pinned beams on a full layer: per n the roots w of
    det [[EI1 b**4 + k - m1 w**2, -k], [-k, EI2 b**4 + k - m2 w**2]] = 0, b = n pi."""
    w2 = sp.Symbol("w2")
    out = []
    for n in range(1, count + 1):
        b4 = (n * sp.pi) ** 4
        det = sp.Matrix([[EI[0] * b4 + k - m[0] * w2, -k],
                         [-k, EI[1] * b4 + k - m[1] * w2]]).det()
        out += [mpmath.sqrt(sp.N(r, 40)) for r in sp.solve(det, w2)]
    return sorted(out)


def test_different_pinned_pair_roots_by_sign_changes():
    """The roots of the derived Delta on the frequency axis (sign changes, then bisection)
    are those of the per-n quadratic."""
    EI, m, k = (1, 2), (1, 3), 100
    model = Model((Beam("a", EI[0], m[0], 1, **PP), Beam("b", EI[1], m[1], 1, **PP)),
                  layers=(Layer("a", "b", k=k),))
    eq = characteristic_equation(model)
    assert {s.name for s in eq.definitions} == {"p_a_b", "q_a_b"}
    fn = _delta(eq)
    top = 120

    def f(w):
        return mpmath.re(fn(w))

    found = []
    with mpmath.workdps(30):
        ref = [r for r in _quadratic_roots(EI, m, k, 4) if r < top]
        assert len(ref) == 6         # (n = 5 is above 200)
        grid = [mpmath.mpf(i) / 8 for i in range(2, 8 * top)]
        values = [f(w) for w in grid]
        for (u, fu), (v, fv) in pairwise(zip(grid, values)):
            if fu * fv < 0:
                found.append(mpmath.findroot(f, (u, v), solver="bisect", tol=1e-25))
    assert len(found) == len(ref)
    for got, want in zip(found, ref):
        assert abs(got / want - 1) < 1e-20, (got, want)


@pytest.mark.parametrize("case", ["cf_spring", "cp_spring", "ff_damped"])
def test_partial_layers_with_springs_agree_with_the_transfer_walk(case):
    """Partial layers with springs between identical beams, other end conditions, a
    dashpot: det R of the transfer walk; the in-phase family is the single beam's."""
    if case == "cf_spring":
        model = Model((Beam("a", 1, 1, 1, **CF), Beam("b", 1, 1, 1, **CF)),
                      (Spring("a", "b", "1/4", 30),), layers=(Layer("a", "b", k=200, x0="1/2"),))
        single = sp.cos(Om) * sp.cosh(Om) + 1
    elif case == "cp_spring":
        model = Model((Beam("a", 1, 1, 1, **CP), Beam("b", 1, 1, 1, **CP)),
                      (Spring("a", "b", "3/4", 30),), layers=(Layer("a", "b", k=200, x1="1/2"),))
        single = sp.cos(Om) * sp.sinh(Om) - sp.sin(Om) * sp.cosh(Om)
    else:
        model = Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, **FF)),
                      (Spring("a", "b", "3/4", 30, 1),),
                      layers=(Layer("a", "b", k=100, c=2, x1="1/2"),))
        single = sp.cos(Om) * sp.cosh(Om) - 1
    eq = characteristic_equation(model)
    assert eq.variable == (LAM if case == "ff_damped" else OMEGA)
    assert any(sp.simplify(f / single).is_number for f, _ in eq.factors)
    assert _agrees_with_transfer_walk(eq, model) < mpmath.mpf(10) ** -30


@pytest.mark.parametrize("case", ["different_damped", "identical_damped_partial", "mass",
                                  "foundation", "unlike_ends"])
def test_other_layered_models_agree_with_the_transfer_walk(case):
    models = {
        "different_damped": Model((Beam("a", 1, 1, 1, **PP), Beam("b", 2, 3, 1, **PP)),
                                  layers=(Layer("a", "b", k=100, c=2),)),
        "identical_damped_partial": Model(
            (Beam("a", 1, 1, 1, left="clamped", right="clamped"),
             Beam("b", 1, 1, 1, left="clamped", right="clamped")),
            layers=(Layer("a", "b", k=50, c=3, x0="1/4", x1="7/10"),)),
        "mass": Model((Beam("a", 1, 1, 1, **PP), Beam("b", 1, 1, 1, **PP)),
                      layers=(Layer("a", "b", k=100),), masses=(Mass("a", "1/3", 2),)),
        "foundation": Model((Beam("a", 1, 1, 1, kw=5, **PP), Beam("b", 2, 3, 1, **PP)),
                            layers=(Layer("a", "b", k=100),)),
        "unlike_ends": Model((Beam("a", 1, 1, 1, **CF), Beam("b", 1, 1, 1, **PP)),
                             layers=(Layer("a", "b", k=100),)),
    }
    model = models[case]
    eq = characteristic_equation(model)
    assert eq.variable == (LAM if model.damped else OMEGA)
    assert _agrees_with_transfer_walk(eq, model) < mpmath.mpf(10) ** -30


def test_damped_pair_is_sin_sinh_in_both_wave_numbers():
    """A damped layer between pinned beams: Delta(lam) is sin p sinh p sin q sinh q /
    (p q)**2 with p**4, q**4 the eigenvalues of X/l**4 (complex)."""
    model = Model((Beam("a", 1, 1, 1, **PP), Beam("b", 2, 3, 1, **PP)),
                  layers=(Layer("a", "b", k=100, c=2),))
    eq = characteristic_equation(model)
    p, q = sorted(eq.definitions, key=lambda s: s.name)
    assert sp.simplify(eq.delta_Omega - sp.sin(p) * sp.sinh(p) * sp.sin(q) * sp.sinh(q)
                       / (p * q) ** 2) == 0
    # p**4 + q**4 = t, p**4 q**4 = d of X/l**4 = -EI**-1 (m lam**2 + k L + c lam L)
    X = sp.Matrix([[-(LAM**2 + 100 + 2 * LAM), 100 + 2 * LAM],
                   [(100 + 2 * LAM) / 2, -(3 * LAM**2 + 100 + 2 * LAM) / 2]])
    p4, q4 = (eq.definitions[s] ** 4 for s in (p, q))
    assert sp.simplify(p4 + q4 - X.trace()) == 0
    assert sp.simplify(sp.expand(p4 * q4) - X.det()) == 0


def test_symbolic_stiffness_and_position():
    """The layer's k (and where it starts) kept symbolic: still a closed form, the in-phase
    family sin Omega sinh Omega split off, and det R at the values."""
    model = Model((Beam("a", 1, 1, 1, **PP), Beam("b", 1, 1, 1, **PP)),
                  layers=(Layer("a", "b", k="k", x0="x1"),), parameters={"k": 100, "x1": "3/10"})
    eq = characteristic_equation(model, symbolic=("k", "x1"))
    assert set(eq.symbols) == {"k", "x1"}
    assert {sp.sin(Om), sp.sinh(Om)} <= {f for f, _ in eq.factors}
    for k, x1 in ((100, "3/10"), (7, "1/10"), (400, "0.55")):
        assert _agrees_with_transfer_walk(eq, model.with_parameters(k=k, x1=x1)) \
            < mpmath.mpf(10) ** -30, (k, x1)
    different = Model((Beam("a", 1, 1, 1, **PP), Beam("b", 2, 3, 1, **PP)),
                      layers=(Layer("a", "b", k="k"),), parameters={"k": 100})
    eq = characteristic_equation(different, symbolic=("k",))
    assert eq.symbols == ("k",)
    fn = _delta(eq, {"k": 100})
    with mpmath.workdps(30):
        for w in _quadratic_roots((1, 2), (1, 3), 100, 2):
            assert _vanishes(fn, w), w


def test_a_layer_without_stiffness_leaves_the_beams_apart():
    eq = characteristic_equation(_pair(0))
    assert sorted((str(f), e) for f, e in eq.factors) == [("sin(Omega)", 2), ("sinh(Omega)", 2)]


PAIR = """
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[beam]]
name = "b"
EI = {EI}
m = {m}
L = 1
left = "pinned"
right = "pinned"

[[layer]]
between = ["a", "b"]
k = 80
"""


def test_cli_prints_the_wave_numbers(tmp_path):
    path = tmp_path / "pair.toml"
    path.write_text(PAIR.format(EI=2, m=3))
    run = run_cli(["derive", path], limit=60)
    assert_contract(run, 60)
    assert run.code == 0, run.stderr
    assert "p_a_b = " in run.stdout and "q_a_b = " in run.stdout
    assert "the eigenvalues of X/l**4" in run.stdout
    path.write_text(PAIR.format(EI=1, m=1))
    run = run_cli(["derive", path, "--json"], limit=60)
    assert_contract(run, 60)
    out = json.loads(run.stdout)
    # in phase the single beam's Omega, out of phase q**4 = omega**2 - 2 k
    assert set(out["definitions"]) == {"Omega", "q_a_b"}
    q4 = sp.sympify(out["definitions"]["q_a_b"], locals={"omega": OMEGA}) ** 4
    assert sp.simplify(q4 - (OMEGA**2 - 160)) == 0
    for flag in ("--latex", "--pretty"):
        run = run_cli(["derive", path, flag], limit=60)
        assert run.code == 0 and "q" in run.stdout


def test_cli_three_beams_over_one_stretch_is_one_line(tmp_path):
    path = tmp_path / "three.toml"
    path.write_text(PAIR.format(EI=1, m=1) + """
[[beam]]
name = "c"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[layer]]
between = ["b", "c"]
k = 50
from = 0.25
""")
    run = run_cli(["derive", path], limit=30)
    assert_contract(run, 30)
    assert run.code == 2
    assert "layer[1]: derive takes layers between two beams only" in run.stderr
