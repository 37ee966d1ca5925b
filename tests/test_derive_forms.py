"""derive's forms: both closed forms with the constant each needs, as text, unicode and
LaTeX; and what python-flint would add."""

from __future__ import annotations

import json
import sys
from pathlib import Path

import mpmath
import pytest
import sympy as sp
from cli_contract import assert_contract, run_cli

from symtmm import api


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc", "timoshenko_beam", "tuned_mass_damper"])
def test_each_constant_belongs_to_its_form(examples_dir, name):
    """det R = constant * Delta(variable) = constant_Omega * Delta(Omega, ...): both products
    agree at a point, the definitions substituted (Omega and wave numbers of omega)."""
    model = api.load(examples_dir / f"{name}.toml")
    if model.damped:
        model = model.with_parameters(zeta=0)
    ce = api.derive(model)
    w = sp.Rational(23, 10)
    subs = {ce.variable: w}
    lhs = ce.constant * ce.delta.subs(subs)
    omega_form = ce.delta_Omega.xreplace(
        {s: v.subs(subs) for s, v in ce.definitions.items()}).subs(subs)
    rhs = ce.constant_Omega * omega_form
    a, b = complex(sp.N(lhs, 30)), complex(sp.N(rhs, 30))
    assert abs(a - b) <= 1e-20 * max(abs(a), 1e-300), (a, b)
    data = ce.to_dict()
    assert sp.sympify(data["constant_Omega"]) == ce.constant_Omega


def test_latex_and_pretty_print_both_forms(examples_dir):
    path = examples_dir / "paper_ex1_ff_cc.toml"
    run = run_cli(["derive", path, "--latex", "--set", "K=0"])
    assert_contract(run)
    lines = run.stdout.strip().splitlines()
    assert lines[0].startswith(r"\Delta(\omega) = ") and lines[3].startswith(r"\Delta(\Omega) = ")
    assert lines[1] == r"\det R = \frac{1}{4}\,\Delta(\omega)"
    assert lines[4] == r"\det R = \frac{1}{4}\,\Delta(\Omega)"
    run = run_cli(["derive", path, "--pretty", "--set", "K=0"])
    assert run.code == 0 and "cos(Ω)⋅cosh(Ω) - 1" in run.stdout and "det R = (1/4)" in run.stdout


def test_without_flint_the_output_says_what_would_factor(monkeypatch, examples_dir):
    monkeypatch.setitem(sys.modules, "flint", None)
    ce = api.derive(api.load(examples_dir / "paper_ex1_ff_cc.toml"))
    assert any("python-flint" in n for n in ce.notes)
    # the closed form is the same function: it vanishes at the first frequency
    f = sp.lambdify(ce.variable, ce.delta, "mpmath")
    # the first frequency from the global coefficient matrix of benchmarks/references.py
    # (no transfer matrices, no symtmm)
    sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
    from benchmarks.references import ex1_omegas
    with mpmath.workdps(30):
        w1 = mpmath.mpf(ex1_omegas(1, dps=30)[0])
        assert abs(f(w1)) < 1e-8 * abs(f(w1 * (1 + mpmath.mpf(10) ** -6)))


def test_json_names_both_constants(examples_dir):
    run = run_cli(["derive", examples_dir / "paper_ex1_ff_cc.toml", "--json"])
    data = json.loads(run.stdout)
    assert {"constant", "constant_Omega", "latex", "latex_Omega"} <= set(data)


def test_a_large_form_is_printed_with_named_subexpressions(examples_dir):
    """Substituting the names back gives the Omega form itself."""
    ce = api.derive(api.load(examples_dir / "rayleigh_axial_force.toml"))
    definitions, reduced = ce.subexpressions()
    assert len(str(reduced)) < len(str(ce.delta_Omega)) / 5
    for name, value in reversed(definitions):
        reduced = reduced.xreplace({name: value})
    assert reduced == ce.delta_Omega or sp.expand(reduced - ce.delta_Omega) == 0
    data = ce.to_dict()
    assert data["subexpressions"][0][0] == str(definitions[0][0])
    run = run_cli(["derive", examples_dir / "rayleigh_axial_force.toml"], limit=60)
    assert run.code == 0 and "  where x0 = " in run.stdout


def test_double_angles_come_back_as_products(monkeypatch, examples_dir):
    """Example 1's part without the springs reads (cos Omega cosh Omega - 1)**2, and the
    rewritten form is the same function as the one with double angles."""
    from symtmm.characteristic import equation
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml")
    ce = api.derive(model)
    Om = equation.OMEGA_DIMLESS
    assert (sp.cos(Om) * sp.cosh(Om) - 1) ** 2 in ce.delta_Omega.atoms(sp.Pow)
    monkeypatch.setattr(equation, "_single_angles", lambda f, Om: f)
    plain = api.derive(model)
    for value in (sp.Rational(7, 10), sp.Rational(33, 10), sp.Rational(71, 10)):
        a = sp.N(ce.constant_Omega * ce.delta_Omega.subs(Om, value), 30)
        b = sp.N(plain.constant_Omega * plain.delta_Omega.subs(Om, value), 30)
        assert abs(a - b) <= 1e-25 * abs(b)


def test_the_papers_damped_example_derives_within_the_budgets(examples_dir):
    """Example 4 in closed form (it needs more terms than the memory budget once
    allowed); its Delta(lam) vanishes at the decoupled-family reference eigenvalues."""
    from damped_reference import ex4_reference
    ce = api.derive(api.load(examples_dir / "paper_ex4_damped.toml"))
    assert str(ce.variable) == "lam"
    f = sp.lambdify(ce.variable, ce.delta, "mpmath")
    with mpmath.workdps(40):
        for lam, _ in ex4_reference(dps=30)[:4]:
            h = abs(lam) * mpmath.mpf(10) ** -10
            assert abs(f(lam)) < 1e-6 * max(abs(f(lam + h)), abs(f(lam - h)))
