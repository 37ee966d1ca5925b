"""Closed forms of the paper's multilevel examples, with K and x1 symbolic.

Derives ``Delta`` for example 1 (free-free over clamped-clamped, two springs)
and example 3 (three pinned-pinned beams in a chain, four springs) with the
spring stiffness ``K`` and the position ``x1`` kept as symbols, and reports
the size (``sympy.count_ops``) and the time. Checks:

* example 3 splits into ``sin(Omega) sinh(Omega) F(K) F(3K)``: the chain's
  coupling matrix ``K [[1,-1,0],[-1,2,-1],[0,-1,1]]`` has the eigenvalues
  0, K, 3K, so the two nontrivial factors are the same function of
  ``K`` and ``3K`` (checked exactly);
* both closed forms equal the numeric ``det R`` (``symtmm.compile``) at the
  paper's values ``K = 100, x1 = 0.3`` and ``K = 25, x1 = 0.25``.

Run: ``python derivations/paper_closed_forms.py``.
"""

from pathlib import Path

import mpmath
import sympy as sp

from symtmm.characteristic import OMEGA, characteristic_equation
from symtmm.compile import Evaluator
from symtmm.expr import parameter_symbol
from symtmm.modelfile import load

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
K, x1 = parameter_symbol("K"), parameter_symbol("x1")

for name in ("paper_ex1_ff_cc.toml", "paper_ex3_three_pp_coupled.toml"):
    model = load(EXAMPLES / name)
    eq = characteristic_equation(model, symbolic=("K", "x1"))
    sizes = ", ".join(f"{sp.count_ops(f)}^{e}" for f, e in eq.factors)
    print(f"{name}: {eq.count_ops()} operations (factors: {sizes}), "
          f"Omega**{eq.power}, {eq.seconds:.2f} s")
    values = {K: model.parameters["K"], x1: model.parameters["x1"]}
    fn = sp.lambdify(OMEGA, (eq.constant * eq.delta).xreplace(values), "mpmath")
    ev = Evaluator(model)
    with mpmath.workdps(40):
        for w in (3, 25, 90):
            ref = ev.delta_mp(mpmath.mpc(0, w))
            assert abs(fn(mpmath.mpf(w)) - ref) < mpmath.mpf(10) ** -30 * abs(ref)
    if name.startswith("paper_ex3"):
        big = [f for f, _ in eq.factors if f.has(K)]
        assert len(eq.factors) == 4 and len(big) == 2
        a, b = big
        # one is the other with K -> 3K, up to a constant factor
        ratios = (1, sp.Rational(1, 9), 9, sp.Rational(1, 3), 3)
        if not any(sp.expand(a.xreplace({K: 3 * K}) * r - b) == 0 for r in ratios):
            a, b = b, a
        assert any(sp.expand(a.xreplace({K: 3 * K}) * r - b) == 0 for r in ratios)
        print(f"  = sin(Omega) sinh(Omega) F(K) F(3K), F(K) = {a}")
