"""Transfer matrix of an Euler-Bernoulli segment, derived from its field equation.

Field equation ``EI Y'''' + m lam**2 Y = 0`` (free vibration ``Y(x) e^{lam t}``).
With ``beta**4 = -m lam**2 / EI`` it reads ``Y'''' = beta**4 Y``. The state is
``z = [Y, Theta, M, Q] = [Y, Y', EI Y'', EI Y''']``. Writing the general
solution as ``Y = sum_i C_i phi_i(x)``, ``z(x) = B(x) C``; the transfer matrix
from ``x = 0`` to ``x = l`` is ``U = B(l) B(0)**-1``.

Checks (each an exact SymPy identity):

1. the solution found by ``dsolve`` satisfies the field equation;
2. ``U`` equals ``EulerBernoulliSegment(EI, m, l).transfer_matrix_beta(beta)``;
3. ``U`` equals ``transfer_matrix(lam)`` once ``beta**4 = -m lam**2 / EI``;
4. ``det U = 1``;
5. every entry is the series of the entire functions ``c_j(x) = sum_k
   x**k/(4k+j)!`` of ``x = (beta l)**4`` that the numeric evaluators use
   (compared term by term up to ``beta**24``).

Run: ``python derivations/euler_bernoulli.py``.
"""

import sympy as sp

from symtmm.elements import EulerBernoulliSegment

x = sp.Symbol("x", real=True)
l, EI, m, beta = sp.symbols("l EI m beta", positive=True)
lam = sp.Symbol("lam")

# 1. the general solution of Y'''' = beta**4 Y
Y = sp.Function("Y")
solution = sp.dsolve(sp.Eq(Y(x).diff(x, 4), beta**4 * Y(x)), Y(x)).rhs
constants = sorted(solution.free_symbols - {x, beta}, key=lambda s: s.name)
assert len(constants) == 4
residual = EI * solution.diff(x, 4) + m * (-EI * beta**4 / m) * solution  # m lam^2 = -EI beta^4
assert sp.expand(residual) == 0

# 2. z(x) = B(x) C and U = B(l) B(0)^-1
state = sp.Matrix([solution, solution.diff(x), EI * solution.diff(x, 2),
                   EI * solution.diff(x, 3)])
B = state.jacobian(constants)
B0_inv = B.subs(x, 0).inv()
U = B.subs(x, l) * B0_inv


def exp_form(e):
    """Exponentials only, expanded: identical functions cancel term by term."""
    return sp.expand(sp.sympify(e).rewrite(sp.exp))


segment = EulerBernoulliSegment(EI, m, l)
library = segment.transfer_matrix_beta(beta)
difference = (U - library).applyfunc(exp_form)
assert difference == sp.zeros(4, 4), difference

# 3. in terms of lam: the same matrix for beta = (-m lam^2/EI)^(1/4)
b_lam = segment.beta(lam)
assert sp.simplify(b_lam**4 - (-m * lam**2 / EI)) == 0
by_lam = segment.transfer_matrix(lam)
assert (by_lam - segment.transfer_matrix_beta(b_lam)) == sp.zeros(4, 4)

# 4. det U = 1 (the transfer of a conservative segment preserves volume)
assert exp_form(library.det(method="berkowitz")) == 1

# 5. the entire functions c_j of x = (beta l)^4
ORDER = 6  # terms compared: beta**0 .. beta**(4*ORDER)
xs = (beta * l) ** 4
cs = [sum(xs**k / sp.factorial(4 * k + j) for k in range(ORDER + 1)) for j in range(4)]
series_form = segment.transfer_matrix_series(sp.Symbol("X")).subs(
    {sp.Function(f"c{j}")(sp.Symbol("X")): cs[j] for j in range(4)}).subs(sp.Symbol("X"), xs)
closed = segment.transfer_matrix_beta(beta)
for i in range(4):
    for j in range(4):
        exact = sp.series(closed[i, j], beta, 0, 4 * ORDER + 1).removeO()
        truncated = sp.expand(series_form[i, j])
        truncated = sum(t for t in sp.Add.make_args(truncated)
                        if sp.degree(t, beta) <= 4 * ORDER)
        assert sp.expand(exact - truncated) == 0, (i, j)

print("Euler-Bernoulli segment: U = B(l) B(0)^-1 equals the library's matrix "
      "(beta and lam forms, det U = 1, c_j series).")
print("U[0, :] =", list(library[0, :]))
