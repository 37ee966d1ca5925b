"""Classical frequency equations of single beams, derived from the boundary conditions.

Independently of the transfer matrices: the general solution
``Y = A cos(beta x) + B sin(beta x) + C cosh(beta x) + D sinh(beta x)`` of
``EI Y'''' + m lam**2 Y = 0`` (``beta**4 = -m lam**2 / EI``) must make two
of ``Y, Y', EI Y'', EI Y'''`` vanish at each end (free: M, Q; clamped: Y,
Theta; pinned: Y, M; sliding: Theta, Q). Nontrivial ``A..D`` exist when the
4 x 4 determinant of those conditions vanishes.

Checks, for every pair of end conditions and with ``EI, m, L`` symbols:

1. the determinant is the textbook frequency equation (Blevins, *Formulas
   for Natural Frequency and Mode Shape*, table 8-1) times a constant and a
   power of ``beta``;
2. ``symtmm.characteristic`` gives the same equation (in ``Omega = beta L``)
   from the transfer matrices.

Run: ``python derivations/frequency_equations.py``.
"""

import itertools

import sympy as sp

from symtmm.characteristic import OMEGA_DIMLESS as Om
from symtmm.characteristic import characteristic_equation
from symtmm.model import BOUNDARY_CONDITIONS, Beam, Model

x = sp.Symbol("x", real=True)
beta, EI, L = sp.symbols("beta EI L", positive=True)
A, B, C, D = sp.symbols("A B C D")
Y = A * sp.cos(beta * x) + B * sp.sin(beta * x) + C * sp.cosh(beta * x) + D * sp.sinh(beta * x)
assert sp.expand(Y.diff(x, 4) - beta**4 * Y) == 0
STATE = {"Y": Y, "Theta": Y.diff(x), "M": EI * Y.diff(x, 2), "Q": EI * Y.diff(x, 3)}

bl = beta * L
c, s, ch, sh = sp.cos(bl), sp.sin(bl), sp.cosh(bl), sp.sinh(bl)
TEXTBOOK = {
    frozenset(["clamped"]): c * ch - 1,                 # clamped-clamped
    frozenset(["free"]): c * ch - 1,                    # free-free
    frozenset(["clamped", "free"]): c * ch + 1,
    frozenset(["pinned"]): s * sh,                      # sin(beta L) = 0
    frozenset(["clamped", "pinned"]): c * sh - s * ch,  # tan = tanh
    frozenset(["pinned", "free"]): c * sh - s * ch,     # tan = tanh
    frozenset(["clamped", "sliding"]): s * ch + c * sh,  # tan = -tanh
    frozenset(["sliding", "free"]): s * ch + c * sh,    # tan = -tanh
    frozenset(["pinned", "sliding"]): c * ch,           # cos(beta L) = 0
    frozenset(["sliding"]): s * sh,                     # sin(beta L) = 0
}


def exp_form(e):
    return sp.expand(sp.sympify(e).rewrite(sp.exp))


for left, right in itertools.combinations_with_replacement(BOUNDARY_CONDITIONS, 2):
    rows = [sp.Matrix([STATE[v].subs(x, 0)]).jacobian([A, B, C, D])
            for v in BOUNDARY_CONDITIONS[left]]
    rows += [sp.Matrix([STATE[v].subs(x, L)]).jacobian([A, B, C, D])
             for v in BOUNDARY_CONDITIONS[right]]
    det = sp.Matrix.vstack(*rows).det(method="berkowitz")
    textbook = TEXTBOOK[frozenset([left, right])]
    ratio = sp.simplify(exp_form(det) / exp_form(textbook))
    assert not ratio.has(sp.exp, sp.cos, sp.sin, sp.cosh, sp.sinh), (left, right, ratio)
    assert ratio != 0 and ratio.free_symbols <= {beta, EI, L}, (left, right, ratio)

    # the transfer-matrix closed form of symtmm, with EI, m, L symbols
    model = Model((Beam("b", EI="EI", m="m", L="L", left=left, right=right),))
    eq = characteristic_equation(model)
    mine = eq.equation.xreplace({Om: bl})
    check = sp.simplify(exp_form(mine) / exp_form(textbook))
    assert check.is_number and check != 0, (left, right, check)
    print(f"{left:8s}-{right:8s} {textbook!s:32s} Delta ~ Omega**{eq.power} * "
          f"({eq.equation})")

print("single-beam frequency equations: boundary-condition determinant = textbook "
      "= symtmm.characteristic, for every pair of end conditions.")
