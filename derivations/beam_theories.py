"""Axial force, rotary inertia and shear: field equations and transfer matrix from the energy.

Energy per unit length (free vibration ``e^{lam t}``), as in
:mod:`symtmm.elements.theories`::

    strain   V = (EI psi'**2 + kGA (Y' - psi)**2 + N Y'**2 + kw Y**2) / 2
    kinetic  T = (m Y_t**2 + rhoI psi_t**2) / 2

``psi`` is the rotation of the cross-section; a beam rigid in shear (Euler-Bernoulli
with axial force, Rayleigh) has ``psi = Y'``.

Derived here, each step asserted:

1. the field equations, by Euler-Lagrange from ``T - V`` in ``(x, t)``; with
   ``e^{lam t}`` they are the Euler-Lagrange equations of the frequency-domain density
   ``pi = V + lam**2 T(lam -> 1)`` (``V - omega**2 T_max``);
2. what the state's ``M`` and ``Q`` are: integrating the first variation by parts
   (an identity checked for arbitrary variations) leaves ``P_Y dY + P_psi dpsi`` at a
   cut, so a point force ``F`` and couple ``C`` (work ``F dY + C dpsi``) make ``P_Y``
   jump by ``-F`` and ``P_psi`` by ``-C``. The project's convention ``Q+ - Q- = F``,
   ``M+ - M- = -C`` (``derivations/point_elements.py``) is ``Q = -P_Y``, ``M = P_psi``:
   ``M = EI psi'`` and ``Q = -(kGA (Y' - psi) + N Y')`` (Timoshenko), ``Q = EI Y''' -
   (N + rhoI lam**2) Y'`` (rigid in shear);
3. the first-order system ``z' = A z``, ``z = [Y, Theta, M, Q]``, solved from those
   definitions and the field equations, equals ``BeamSegment(...).system_matrix(lam)``
   exactly (Timoshenko, and rigid in shear);
4. ``BeamSegment.transfer_matrix`` solves ``dU/dl = A U``, ``U(0) = I``: exactly
   (symbolically in ``l``) at ``lam = 0`` and in the confluent case where the two wave
   numbers meet, and at random rational points (complex ``lam``, tension and
   compression) to 50 digits; ``det U = 1`` (``trace A = 0`` exactly, and numerically);
   the numeric evaluators (series and doubling) equal it there;
5. it reduces to ``EulerBernoulliSegment`` for ``N = rhoI = 0``, ``kGA -> oo`` (the
   limit of ``A`` exactly; the matrices at random points, and at ``kGA = 10**40``);
6. the pinned-pinned frequency equation that the tests use as a reference: ``Y = A
   sin(k x)``, ``psi = B cos(k x)`` solve the field equations with ``Y = M = 0`` at
   ``x = 0, pi/k`` iff ``det [[(kGA + N) q + kw + m lam**2, -kGA k], [-kGA k, EI q + kGA
   + rhoI lam**2]] = 0``, ``q = k**2``; rigid in shear ``omega**2 = (EI q**2 + N q +
   kw)/(m + rhoI q)``.

Run: ``python derivations/beam_theories.py``.
"""

import random

import mpmath
import numpy as np
import sympy as sp
from sympy.calculus.euler import euler_equations

from symtmm.elements import BeamSegment, EulerBernoulliSegment
from symtmm.numeric.arith import DOUBLE, MP
from symtmm.numeric.segments import segment_matrix

x, t, l = sp.symbols("x t l", real=True)
EI, m, kGA, rhoI = sp.symbols("EI m kGA rhoI", positive=True)
N, kw = sp.symbols("N k_w", real=True)
lam = sp.Symbol("lam")
Yt, Pt = sp.Function("Y")(x, t), sp.Function("psi")(x, t)
y, p = sp.Function("y")(x), sp.Function("p")(x)
dy, dp = sp.Function("dy")(x), sp.Function("dp")(x)        # arbitrary variations

# -- 1. field equations ------------------------------------------------------------------
V = (EI * Pt.diff(x)**2 + kGA * (Yt.diff(x) - Pt)**2 + N * Yt.diff(x)**2 + kw * Yt**2) / 2
T = (m * Yt.diff(t)**2 + rhoI * Pt.diff(t)**2) / 2
harmonic = {Yt: y * sp.exp(lam * t), Pt: p * sp.exp(lam * t)}


def in_frequency_domain(expr):
    """``expr`` with ``e^{lam t}`` motion substituted and the exponential divided out."""
    return sp.expand(sp.simplify(expr.subs(harmonic).doit() * sp.exp(-lam * t)))


time_domain = [in_frequency_domain(eq.lhs) for eq in euler_equations(T - V, [Yt, Pt], [x, t])]


def density(Y, P):
    """``pi = V + lam**2 T``: the frequency-domain density."""
    return (EI * P.diff(x)**2 + kGA * (Y.diff(x) - P)**2 + N * Y.diff(x)**2 + kw * Y**2
            + lam**2 * (m * Y**2 + rhoI * P**2)) / 2


pi = density(y, p)
EL = [eq.lhs for eq in euler_equations(pi, [y, p], x)]
for a, b in zip(time_domain, EL):       # the same equations (of opposite sign)
    assert sp.simplify(a + b) == 0

# -- 2. the conjugates of Y and psi at a cut ----------------------------------------------
P_Y, P_psi = pi.diff(y.diff(x)), pi.diff(p.diff(x))
first_variation = (pi.diff(y) * dy + P_Y * dy.diff(x) + pi.diff(p) * dp + P_psi * dp.diff(x))
by_parts = EL[0] * dy + EL[1] * dp + (P_Y * dy + P_psi * dp).diff(x)
# euler_equations writes d(pi)/dy - (d pi/dy')' = 0: the integrated form must match
assert sp.simplify(first_variation - by_parts) == 0
M_def, Q_def = P_psi, -P_Y
assert sp.simplify(M_def - EI * p.diff(x)) == 0
assert sp.simplify(Q_def + kGA * (y.diff(x) - p) + N * y.diff(x)) == 0

# -- 3. first-order system, Timoshenko ---------------------------------------------------
Ys, Ths, Ms, Qs = sp.symbols("Y Theta M Q")
dY, dTh = sp.symbols("dY dTheta")
# the definitions of M and Q give Y', psi'; the field equations give M', Q'
names = {y.diff(x): dY, p.diff(x): dTh, y: Ys, p: Ths}
definitions = [sp.Eq(Ms, M_def.subs(names)), sp.Eq(Qs, Q_def.subs(names))]
slopes = sp.solve(definitions, [dY, dTh], dict=True)[0]
# EL[0] = d pi/dy - (P_Y)' = 0 -> Q' = -(P_Y)' = -d pi/dy ; EL[1]: M' = (P_psi)' = d pi/dp
assert sp.simplify(EL[0] - (pi.diff(y) - P_Y.diff(x))) == 0
assert sp.simplify(EL[1] - (pi.diff(p) - P_psi.diff(x))) == 0
dQ_value = -pi.diff(y)
dM_value = pi.diff(p)
rates = [slopes[dY], slopes[dTh], dM_value.subs(names), dQ_value.subs(names)]
rates = [sp.simplify(r.subs({dY: slopes[dY], dTh: slopes[dTh]})) for r in rates]
state = [Ys, Ths, Ms, Qs]
A_timoshenko = sp.Matrix(rates).jacobian(state)
seg = BeamSegment(EI, m, l, kw=kw, N=N, rhoI=rhoI, kGA=kGA)
assert sp.simplify(A_timoshenko - seg.system_matrix(lam)) == sp.zeros(4, 4)

# -- 3'. rigid in shear: psi = Y', pi(Y, Y', Y'') -------------------------------------------
pi_r = density(y, y.diff(x))
EL_r = euler_equations(pi_r, y, x)[0].lhs
P1, P2 = pi_r.diff(y.diff(x)), pi_r.diff(y.diff(x, 2))
first_variation = pi_r.diff(y) * dy + P1 * dy.diff(x) + P2 * dy.diff(x, 2)
by_parts = EL_r * dy + ((P1 - P2.diff(x)) * dy + P2 * dy.diff(x)).diff(x)
assert sp.simplify(first_variation - by_parts) == 0
M_r, Q_r = P2, -(P1 - P2.diff(x))
assert sp.simplify(M_r - EI * y.diff(x, 2)) == 0
assert sp.simplify(Q_r - (EI * y.diff(x, 3) - (N + rhoI * lam**2) * y.diff(x))) == 0
# Theta = Y', Theta' = M/EI, M' = EI Y''' = Q + (N + rhoI lam^2) Theta, Q' from EL_r
jet = {y.diff(x, 3): sp.Symbol("Y3"), y.diff(x, 2): Ms / EI, y.diff(x): Ths, y: Ys}
Y3 = sp.solve(sp.Eq(Qs, Q_r.subs(jet)), sp.Symbol("Y3"))[0]
dQ_r = Q_r.diff(x)     # contains Y'''' : eliminate it with the field equation
Y4 = sp.solve(EL_r, y.diff(x, 4))[0]
dQ_r = dQ_r.subs(y.diff(x, 4), Y4)
rates = [Ths, Ms / EI, EI * Y3, dQ_r.subs(jet)]
A_rigid = sp.Matrix([sp.simplify(r) for r in rates]).jacobian(state)
seg_r = BeamSegment(EI, m, l, kw=kw, N=N, rhoI=rhoI)
assert sp.simplify(A_rigid - seg_r.system_matrix(lam)) == sp.zeros(4, 4)

# -- 4. the transfer matrix solves dU/dl = A U, U(0) = I ----------------------------------
assert sp.simplify(A_timoshenko.trace()) == 0 and sp.simplify(A_rigid.trace()) == 0  # det U = 1


def exactly_solves(segment, lam_value):
    """``dU/dl = A U`` and ``U(0) = I`` as exact identities in the length."""
    U = segment.transfer_matrix(lam_value)
    A = segment.system_matrix(lam_value)
    ode = (U.diff(l) - A * U).applyfunc(lambda e: sp.simplify(sp.expand(e.rewrite(sp.exp))))
    return ode == sp.zeros(4, 4) and sp.simplify(U.subs(l, 0)) == sp.eye(4)


R = sp.Rational
# lam = 0 without axial force: U is polynomial in l (confluent root 0)
assert exactly_solves(BeamSegment(2, 3, l, kw=0, rhoI=R(1, 50), kGA=7), 0)
assert exactly_solves(BeamSegment(2, 3, l, N=0), 0)
# the two wave numbers meet: EI = m = 1, N = 2, kw = 3 at lam**2 = N**2/(4 EI) - kw = -2
assert exactly_solves(BeamSegment(1, 1, l, kw=3, N=2), sp.sqrt(2) * sp.I)
# distinct roots, exactly: a taut beam on a foundation at lam = 2 i
assert exactly_solves(BeamSegment(1, 1, l, kw=1, N=1), 2 * sp.I)

rng = random.Random(7)


def rational(lo, hi):
    return R(rng.randint(round(lo * 1000), round(hi * 1000)), 1000)


def mp_matrix(matrix, length):
    """A matrix of exact expressions in ``l`` at ``l = length``, in mpmath (working precision)."""
    f = sp.lambdify(l, matrix, "mpmath")
    return mpmath.matrix(f(mpmath.mpf(length.p) / length.q))


def size(matrix):
    return mpmath.mnorm(matrix, 1)


worst = 0
with mpmath.workdps(50):
    for trial, sign in enumerate((-1, 1)):          # compression, then tension
        v = {"EI": rational(0.5, 3), "m": rational(0.5, 3), "kGA": rational(20, 400),
             "rhoI": rational(0.001, 0.05), "kw": rational(0, 50),
             "N": sign * rational(0.5, 8)}
        length = rational(0.2, 1.5)
        lam_v = rational(-3, 0) + sp.I * rational(1, 40)
        lam2 = mpmath.mpmathify(sp.re(lam_v**2)) + 1j * mpmath.mpmathify(sp.im(lam_v**2))
        for kGA_v in (v["kGA"], None):
            segment = BeamSegment(v["EI"], v["m"], l, kw=v["kw"], N=v["N"], rhoI=v["rhoI"],
                                  kGA=kGA_v)
            U = segment.transfer_matrix(lam_v)
            Un = mp_matrix(U, length)
            ode = mp_matrix(U.diff(l) - segment.system_matrix(lam_v) * U, length)
            residual = size(ode) / size(Un)
            unit = abs(mpmath.det(Un) - 1)
            worst = max(worst, residual, unit)
            assert residual < 1e-45 and unit < 1e-45, (trial, residual, unit)
            assert size(mp_matrix(U, R(0)) - mpmath.eye(4)) < 1e-50
            # the library's numeric evaluators (series in (t, d), doubling) agree with it
            piece = segment.with_length(length)
            ar = MP.from_digits(50)
            kernel_U = segment_matrix(ar, piece, ar.array([ar.number(lam2)]))[0]
            got = mpmath.matrix([[ar.to_mpmath(x) for x in row] for row in kernel_U])
            assert size(got - Un) < 1e-44 * size(Un), (trial, size(got - Un))
            numpy_U = segment_matrix(DOUBLE, piece, np.array([complex(lam2)]))[0]
            reference = np.array(Un.tolist(), dtype=complex)
            assert np.max(np.abs(numpy_U - reference)) < 1e-12 * float(size(Un))
        # -- 5. N = rhoI = 0, rigid in shear: the Euler-Bernoulli segment
        U_eb = mp_matrix(EulerBernoulliSegment(v["EI"], v["m"], l, v["kw"])
                         .transfer_matrix(lam_v), length)
        U_plain = mp_matrix(BeamSegment(v["EI"], v["m"], l, kw=v["kw"]).transfer_matrix(lam_v),
                            length)
        assert size(U_plain - U_eb) < 1e-45 * size(U_eb)
        with mpmath.workdps(80):
            stiff = BeamSegment(v["EI"], v["m"], l, kw=v["kw"], kGA=10**40)
            far = size(mp_matrix(stiff.transfer_matrix(lam_v), length) - U_eb) / size(U_eb)
        assert far < 1e-35, far

# the limit kGA -> oo of A (Timoshenko) is A rigid in shear
limit = A_timoshenko.applyfunc(lambda e: sp.limit(e, kGA, sp.oo))
assert sp.simplify(limit - A_rigid) == sp.zeros(4, 4)
assert sp.simplify(BeamSegment(EI, m, l, kw=kw).system_matrix(lam)
                   - A_rigid.subs({N: 0, rhoI: 0})) == sp.zeros(4, 4)

# -- 6. the pinned-pinned frequency equation -----------------------------------------------
k, Aa, Bb = sp.symbols("k A B", positive=True)
q = k**2
modes = {y: Aa * sp.sin(k * x), p: Bb * sp.cos(k * x)}
residual = [sp.simplify(eq.subs(modes).doit()) for eq in EL]
# Y = A sin: EL_Y ~ sin(kx), EL_psi ~ cos(kx); the amplitudes' matrix
system = sp.Matrix([sp.simplify(residual[0] / sp.sin(k * x)),
                    sp.simplify(residual[1] / sp.cos(k * x))]).jacobian([Aa, Bb])
expected = sp.Matrix([[(kGA + N) * q + kw + m * lam**2, -kGA * k],
                      [-kGA * k, EI * q + kGA + rhoI * lam**2]])
assert sp.simplify(system + expected) == sp.zeros(2) or sp.simplify(system - expected) \
    == sp.zeros(2)
# the boundary conditions hold at x = 0 and x = pi/k: Y = 0 and M = EI psi' = 0
for end in (0, sp.pi / k):
    assert sp.simplify(modes[y].subs(x, end)) == 0
    assert sp.simplify((EI * modes[p].diff(x)).subs(x, end)) == 0
# rigid in shear: Y = sin(kx) solves EL_r iff omega^2 = (EI q^2 + N q + kw)/(m + rhoI q)
w2 = sp.Symbol("omega2")
rr = sp.simplify(EL_r.subs(y, sp.sin(k * x)).doit().subs(lam**2, -w2) / sp.sin(k * x))
assert sp.simplify(sp.solve(rr, w2)[0] - (EI * q**2 + N * q + kw) / (m + rhoI * q)) == 0

print("beam theories: field equations, M = EI psi', Q = -(kGA (Y' - psi) + N Y') and the "
      "system matrix A derived from the energy equal the library's; U = exp(A l) solves "
      f"dU/dl = A U (exactly, and to {mpmath.nstr(worst, 2)} at 50 digits), det U = 1, "
      "reduces to Euler-Bernoulli; pinned-pinned frequency equation derived")
