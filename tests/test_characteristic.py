"""Closed-form characteristic equations.

References: the textbook frequency equations of single Euler-Bernoulli beams
(e.g. Blevins, *Formulas for Natural Frequency and Mode Shape*, table 8-1);
the modal decomposition of identical beams coupled in a chain (coupling
matrix K [[1,-1,0],[-1,2,-1],[0,-1,1]] with eigenvalues 0, K, 3K: one beam on
ground springs of stiffness 0, K and 3K); the numeric evaluator
``symtmm.compile.Evaluator`` at 40 digits (a different formulation: the
entire functions c_j evaluated numerically, no closed form).
"""

from __future__ import annotations

import json
import random
import subprocess
import sys
from pathlib import Path

import mpmath
import pytest
import sympy as sp

from symtmm.characteristic import OMEGA, OMEGA_DIMLESS, characteristic_equation
from symtmm.cli import main
from symtmm.compile import Evaluator
from symtmm.elements.base import LAM
from symtmm.errors import ModelError
from symtmm.expr import parameter_symbol
from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load, loads
from symtmm.roots.undamped import rigid_body_modes

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
Om = OMEGA_DIMLESS
c, s, ch, sh = sp.cos(Om), sp.sin(Om), sp.cosh(Om), sp.sinh(Om)

#: Textbook frequency equations f(beta L) = 0 (up to a constant factor).
TEXTBOOK = {
    ("clamped", "clamped"): c * ch - 1,
    ("free", "free"): c * ch - 1,
    ("clamped", "free"): c * ch + 1,
    ("pinned", "pinned"): s * sh,
    ("clamped", "pinned"): c * sh - s * ch,      # tan = tanh
    ("pinned", "free"): c * sh - s * ch,         # tan = tanh
    ("clamped", "sliding"): s * ch + c * sh,     # tan + tanh = 0
    ("sliding", "free"): s * ch + c * sh,        # tan + tanh = 0
    ("pinned", "sliding"): c * ch,               # cos = 0
    ("sliding", "sliding"): s * sh,              # sin = 0
}


def _textbook(left, right):
    return TEXTBOOK.get((left, right), TEXTBOOK.get((right, left)))


def _proportional(a, b) -> bool:
    """a / b is a nonzero constant (checked exactly)."""
    ratio = sp.simplify(a / b)
    return bool(ratio.is_number and ratio != 0)


BCS = ["free", "clamped", "pinned", "sliding"]


@pytest.mark.parametrize("left", BCS)
@pytest.mark.parametrize("right", BCS)
def test_single_beam_textbook(left, right):
    eq = characteristic_equation(Model((Beam("b", 1, 1, 1, left=left, right=right),)))
    assert eq.variable == OMEGA
    assert _proportional(eq.equation, _textbook(left, right))
    # Omega**power carries the rigid-body modes: Delta ~ Omega**(4 r) at 0
    r = rigid_body_modes(Model((Beam("b", 1, 1, 1, left=left, right=right),)))
    lead = sp.series(eq.delta_Omega, Om, 0, 4 * r + 2).removeO()
    assert sp.Poly(lead, Om).monoms()[-1][0] == 4 * r


@pytest.mark.parametrize("left,right", [("clamped", "clamped"), ("clamped", "free"),
                                        ("pinned", "pinned"), ("clamped", "pinned")])
def test_single_beam_symbolic_properties(left, right):
    beam = Beam("b", EI="EI", m="m", L="L", left=left, right=right)
    eq = characteristic_equation(Model((beam,)))
    assert _proportional(eq.equation, _textbook(left, right))
    EI, m, L = (parameter_symbol(n) for n in ("EI", "m", "L"))
    # Omega = beta L with beta**4 = m omega**2 / EI
    assert sp.simplify(eq.Omega**4 - m * OMEGA**2 * L**4 / EI) == 0
    assert set(eq.symbols) == {"EI", "m", "L"}
    assert _check_numeric(eq, Model((beam,), parameters={"EI": 3, "m": "0.5", "L": 2}))


def _check_numeric(eq, model, points=6, seed=1) -> bool:
    """``constant * delta == det R`` of the numeric evaluator at 40 digits."""
    values = {parameter_symbol(k): v for k, v in model.parameters.items() if v is not None}
    full = (eq.constant * eq.delta).xreplace(values)
    fn = sp.lambdify(eq.variable, full, "mpmath")
    ev = Evaluator(model)
    rnd = random.Random(seed)
    with mpmath.workdps(40):
        for _ in range(points):
            w = mpmath.mpf(rnd.uniform(0.5, 150))
            if eq.variable == OMEGA:
                got, ref = fn(w), ev.delta_mp(mpmath.mpc(0, w))
            else:
                lam = mpmath.mpc(-rnd.uniform(0, 20), w)
                got, ref = fn(lam), ev.delta_mp(lam)
            if abs(got - ref) > mpmath.mpf(10) ** -30 * abs(ref):
                return False
    return True


def test_paper_examples_agree_with_evaluator():
    for name in ("paper_ex1_ff_cc.toml", "paper_ex2_three_pp.toml",
                 "paper_ex3_three_pp_coupled.toml"):
        model = load(EXAMPLES / name)
        assert _check_numeric(characteristic_equation(model), model), name


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc.toml", "paper_ex3_three_pp_coupled.toml"])
def test_symbolic_K_x1_agree_with_evaluator(name):
    model = load(EXAMPLES / name)
    eq = characteristic_equation(model, symbolic=("K", "x1"))
    assert set(eq.symbols) == {"K", "x1"}
    for K, x1 in (("25", "0.25"), ("7", "0.1"), ("300", "0.45")):
        assert _check_numeric(eq, model.with_parameters(K=K, x1=x1)), (K, x1)


def test_uncoupled_identical_beams_give_repeated_factors():
    eq = characteristic_equation(load(EXAMPLES / "paper_ex2_three_pp.toml"))
    assert sorted((str(f), e) for f, e in eq.factors) == [("sin(Omega)", 3), ("sinh(Omega)", 3)]
    assert eq.power == -6


def test_chain_of_three_factors_into_mode_families():
    """Three identical pinned-pinned beams in a chain: Delta = D(0) D(K) D(3K) up to a constant,
    D(k) the characteristic function of one pinned-pinned beam on ground springs k at x1, 1 - x1."""
    eq = characteristic_equation(load(EXAMPLES / "paper_ex3_three_pp_coupled.toml"),
                                 symbolic=("K", "x1"))
    assert len(eq.factors) == 4 and all(e == 1 for _, e in eq.factors)
    single = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),),
                   (Spring("b", "ground", "x1", "kappa"), Spring("b", "ground", "1 - x1", "kappa")),
                   {"x1": "0.25", "kappa": None})
    one = characteristic_equation(single, symbolic=("x1",))
    K = parameter_symbol("K")
    family = [one.delta_Omega.xreplace({parameter_symbol("kappa"): v}) for v in (0, K, 3 * K)]
    product = sp.Mul(*family)
    # constant ratio, checked at random points (exact rationals, 30 digits)
    rnd = random.Random(5)
    ratios = []
    for _ in range(4):
        point = {Om: sp.Rational(rnd.randint(100, 900), 100), K: rnd.randint(1, 60),
                 parameter_symbol("x1"): sp.Rational(rnd.randint(5, 45), 100)}
        ratios.append(sp.N((eq.delta_Omega / product).xreplace(point), 30))
    assert all(abs(r / ratios[0] - 1) < 1e-25 for r in ratios)


def test_damped_model_is_given_in_lam():
    model = loads("""
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
between = ["a", "b"]
x = 0.3
k = 20
c = 2
""")
    eq = characteristic_equation(model)
    assert eq.variable == LAM
    assert _check_numeric(eq, model)
    # the antisymmetric family is damped, the symmetric one (sin * sinh) is not
    assert any(str(f) == "sin(Omega)" for f, _ in eq.factors)


def test_different_beams_and_ground_spring_agree_with_evaluator():
    model = loads("""
[[beam]]
name = "a"
EI = 2
m = 1
L = 1
left = "clamped"
right = "free"
[[beam]]
name = "b"
EI = 1
m = 3
L = 1.5
x0 = 0.25
left = "pinned"
right = "sliding"
[[spring]]
between = ["a", "b"]
x = 0.5
k = 7
[[spring]]
between = ["a", "ground"]
x = 1
k = 3
""")
    eq = characteristic_equation(model)
    assert _check_numeric(eq, model)


def test_delta_string_parses_back():
    eq = characteristic_equation(load(EXAMPLES / "paper_ex1_ff_cc.toml"), symbolic=("K",))
    d = eq.to_dict()
    assert d["variable"] == "omega"
    names = {"omega": OMEGA, "K": parameter_symbol("K"), "Omega": Om}
    assert sp.simplify(sp.sympify(d["delta"], locals=names) - eq.delta) == 0
    assert sp.simplify(sp.sympify(d["delta_Omega"], locals=names) - eq.delta_Omega) == 0
    assert d["latex"] == sp.latex(eq.delta)


def test_order_of_symbolic_cuts_needs_a_value():
    model = loads("""
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"
[[spring]]
between = ["a", "ground"]
x = "x1"
k = 1
[[spring]]
between = ["a", "ground"]
x = "1 - x1"
k = 1
""", source="m.toml")
    with pytest.raises(ModelError, match="x1"):
        characteristic_equation(model)
    with pytest.raises(ModelError, match="not a parameter"):
        characteristic_equation(model, symbolic=("Q",))


def test_cli_json_and_latex(capsys):
    assert main(["derive", str(EXAMPLES / "paper_ex2_three_pp.toml"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["variable"] == "omega"
    assert sp.sympify(out["delta"], locals={"omega": OMEGA}) == \
        sp.sin(sp.sqrt(OMEGA))**3 * sp.sinh(sp.sqrt(OMEGA))**3 / OMEGA**3
    assert main(["derive", str(EXAMPLES / "paper_ex2_three_pp.toml"), "--latex"]) == 0
    assert capsys.readouterr().out.strip().startswith("\\Delta(\\omega) = \\frac{\\sin^{3}")


def test_cli_bad_symbolic_is_one_line():
    proc = subprocess.run([sys.executable, "-m", "symtmm", "derive",
                           str(EXAMPLES / "paper_ex1_ff_cc.toml"), "--symbolic", "Q"],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stderr.count("\n") == 1


def test_symbolic_example_needs_no_values():
    """One spring inside identical beams: the order is fixed without values; in-phase family
    sin * sinh splits off, the other is one beam on a ground spring of stiffness 2K."""
    model = load(EXAMPLES / "two_beams_symbolic.toml")
    eq = characteristic_equation(model)
    assert set(eq.symbols) == {"EI", "K", "L", "m", "x1"}
    assert [e for f, e in eq.factors if f in (sp.sin(Om), sp.sinh(Om))] == [1, 1]
    numeric = model.with_parameters(EI=2, m=3, L="1.5", K=40, x1="0.4")
    assert _check_numeric(eq, numeric)
    ground = Model((Beam("b", "EI", "m", "L", left="pinned", right="pinned"),),
                   (Spring("b", "ground", "x1", "2*K"),))
    assert _check_numeric(characteristic_equation(ground),
                          ground.with_parameters(EI=2, m=3, L="1.5", K=40, x1="0.4"))
    other = [f for f in (f for f, _ in eq.factors) if f.has(parameter_symbol("K"))]
    mine = characteristic_equation(ground).equation
    assert len(other) == 1 and _proportional(other[0], mine)
