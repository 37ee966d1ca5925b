"""A Euler-Bernoulli segment on a Winkler foundation, derived from its field equation.

Field equation ``EI Y'''' + (kw + m lam**2) Y = 0``: the foundation reaction
``kw Y`` per unit length adds to the inertia force. With
``beta**4 = -(m lam**2 + kw) / EI`` it is again ``Y'''' = beta**4 Y``, so the
transfer matrix is the bare segment's with that ``beta``; equivalently, the
bare segment's at ``lam**2 + kw/m``.

Checks (exact SymPy identities):

1. ``Y = S(beta x)`` built from the library matrix's first row satisfies the
   field equation with the foundation term;
2. ``EulerBernoulliSegment(EI, m, l, kw).transfer_matrix(lam)`` equals the bare
   segment's at ``lam2 = lam**2 + kw/m`` (same ``beta**4``);
3. the real form used at ``lam = 0`` (``foundation_static_matrix``) equals the
   closed form with ``beta**4 = -kw/EI`` (compared at a sample to 40 digits);
4. the numeric evaluator at ``lam = i omega`` equals the closed form with
   ``beta**4 = (m omega**2 - kw) / EI``, and the bare segment at ``lam**2 + kw/m``.

Run: ``python derivations/winkler_foundation.py``.
"""

import mpmath
import numpy as np
import sympy as sp

from symtmm.elements import EulerBernoulliSegment
from symtmm.elements.beam import stv_matrix
from symtmm.numeric.arith import DOUBLE
from symtmm.numeric.segments import segment_matrix

x = sp.Symbol("x", real=True)
l, EI, m, kw, beta = sp.symbols("l EI m kw beta", positive=True)
lam = sp.Symbol("lam")

# 1. every column of the library matrix, as a function of the length, solves the field equation
U = stv_matrix(beta, x, EI)
lam2 = -(EI * beta**4 + kw) / m          # beta**4 = -(m lam**2 + kw)/EI
for j in range(4):
    Y = U[0, j]
    residual = EI * Y.diff(x, 4) + (kw + m * lam2) * Y
    assert sp.simplify(residual.rewrite(sp.exp)) == 0
    # and the state is [Y, Y', EI Y'', EI Y''']
    assert sp.simplify((U[1, j] - Y.diff(x)).rewrite(sp.exp)) == 0
    assert sp.simplify((U[2, j] - EI * Y.diff(x, 2)).rewrite(sp.exp)) == 0
    assert sp.simplify((U[3, j] - EI * Y.diff(x, 3)).rewrite(sp.exp)) == 0

# 2. foundation = shift of lam**2 by kw/m
seg = EulerBernoulliSegment(EI, m, l, kw)
assert sp.simplify(seg.beta(lam) ** 4 - (-(m * lam**2 + kw) / EI)) == 0
bare = EulerBernoulliSegment(EI, m, l)
assert sp.simplify(seg.beta(lam) ** 4 - bare.beta(sp.sqrt(lam**2 + kw / m)) ** 4) == 0

# 3. the real form at lam = 0
sample = EulerBernoulliSegment(2, 3, sp.Rational(7, 5), 11)
real_form = sample.foundation_static_matrix()
closed = stv_matrix(sample.beta(sp.Integer(0)), sample.l, sample.EI)
with mpmath.workdps(40):
    gap = max(abs(complex(sp.N(real_form[i, j] - closed[i, j], 40)))
              for i in range(4) for j in range(4))
assert gap < 1e-30, gap

# 4. the evaluator at lam = i omega is the closed form at beta**4 = (m omega**2 - kw)/EI
omega = 5.0
num = segment_matrix(DOUBLE, EulerBernoulliSegment(2, 3, sp.Rational(7, 5), kw=11),
                     np.array([-omega**2]))[0].real
beta_expected = ((3 * sp.Integer(5) ** 2 - 11) / sp.Integer(2)) ** sp.Rational(1, 4)
ref = np.array(sp.N(stv_matrix(beta_expected, sp.Rational(7, 5), 2), 20).tolist(), dtype=float)
assert np.allclose(num, ref, rtol=1e-13, atol=0), (num, ref)
# and it is the bare segment at lam**2 + kw/m
bare = segment_matrix(DOUBLE, EulerBernoulliSegment(2, 3, sp.Rational(7, 5)),
                      np.array([-omega**2 + 11.0 / 3.0]))[0].real
assert np.allclose(num, bare, rtol=1e-14, atol=0), (num, bare)

print("Winkler foundation segment: field equation, lam**2 shift, real static form and "
      "evaluator checked.")
