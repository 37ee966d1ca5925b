"""Frequency equations of Timoshenko, Rayleigh, axially loaded and founded beams, from the field equations.

Independently of the transfer matrices: the Euler-Lagrange equations of the
energy per unit length (harmonic motion at ``omega``, ``w2 = omega**2``)::

    Timoshenko:  EI psi'**2 + kGA (Y' - psi)**2 + N Y'**2 + kw Y**2 - w2 (m Y**2 + rhoI psi**2)
    Rayleigh:    EI Y''**2 + N Y'**2 + kw Y**2 - w2 (m Y**2 + rhoI Y'**2)   (psi = Y')

(halved) and their natural boundary conditions give the end conditions
(clamped: ``Y = psi = 0``; pinned: ``Y = M = 0``; free: ``M = Q = 0`` with ``M,
Q`` the conjugates of ``psi, Y`` in the energy). ``Y = e^{kx}`` solves them
where ``P(k**2) = 0``, a quadratic in ``s = k**2`` with the roots ``a**2 > 0``
and ``-b**2``; the general solution is ``Y = C1 cosh(a x) + C2 sinh(a x) + C3
cos(b x) + C4 sin(b x)`` (``psi`` follows from the second equation), and the
4 x 4 determinant of the end conditions is the frequency equation.

Checks:

1. pinned-pinned, every theory: the determinant is ``sin(b L) sinh(a L)``
   times a factor free of trigonometric functions, so ``b L = n pi``; with
   ``q = (n pi / L)**2``, ``P(-q) = 0`` gives ``omega**2 = (EI q**2 + N q + kw) /
   (m + rhoI q)`` (Rayleigh, axial force, foundation) and, for Timoshenko,
   the quadratic of the two-mode Galerkin ansatz ``Y = A sin, psi = B cos``
   (exact for these ends);
2. Euler-Bernoulli on a Winkler foundation, clamped-clamped: ``cos(bL)
   cosh(bL) = 1`` with ``b**4 = (m omega**2 - kw)/EI``;
3. Timoshenko clamped-free: the classical equation of Huang (1961)::

       2 + [B**2 (r**2 - s**2)**2 + 2] cosh(a L) cos(b L)
         - B (r**2 + s**2) / sqrt(1 - B**2 r**2 s**2) sinh(a L) sin(b L) = 0

   (``B**2 = m omega**2 L**4 / EI``, ``r**2 = rhoI / (m L**2)``, ``s**2 = EI /
   (kGA L**2)``), checked coefficient by coefficient at sample points;
4. ``symtmm.characteristic`` (transfer matrices) gives ``Delta`` (parsed
   back from its JSON) that vanishes at the roots of 1-3 and not near them.

Run: ``python derivations/theory_frequency_equations.py``.
"""

import json
import random
from itertools import pairwise

import mpmath
import sympy as sp
from sympy.calculus.euler import euler_equations

from symtmm.characteristic import characteristic_equation
from symtmm.model import Beam, Model

x = sp.Symbol("x", real=True)
EI, m, L, kGA, rhoI, kw, N, w2 = sp.symbols("EI m L kGA rhoI kw N w2", real=True)
k, s_ = sp.symbols("k s")
a, b = sp.symbols("a b", positive=True)
Y, psi = sp.Function("Y")(x), sp.Function("psi")(x)
C = sp.symbols("C1:5")

# -- field equations and natural end conditions -------------------------------------------
energy_t = (EI * psi.diff(x) ** 2 + kGA * (Y.diff(x) - psi) ** 2 + N * Y.diff(x) ** 2
            + kw * Y**2 - w2 * (m * Y**2 + rhoI * psi**2)) / 2
eq_Y, eq_psi = (e.lhs for e in euler_equations(energy_t, [Y, psi], x))
# the conjugate forces of Y and psi at an end (boundary terms of the first variation)
Q_t = energy_t.diff(Y.diff(x))
M_t = energy_t.diff(psi.diff(x))

energy_r = (EI * Y.diff(x, 2) ** 2 + N * Y.diff(x) ** 2 + kw * Y**2
            - w2 * (m * Y**2 + rhoI * Y.diff(x) ** 2)) / 2
eq_r = euler_equations(energy_r, [Y], x)[0].lhs
M_r = energy_r.diff(Y.diff(x, 2))                         # conjugate of Y'
Q_r = energy_r.diff(Y.diff(x)) - M_r.diff(x)              # conjugate of Y

# exponential solutions: P(k**2) = 0
A_, B_ = sp.symbols("A_ B_")
ex = sp.exp(k * x)
sub_t = {Y: A_ * ex, psi: B_ * ex}
lin = [sp.simplify(e.subs(sub_t).doit() / ex) for e in (eq_Y, eq_psi)]
Mk = sp.Matrix([[sp.diff(e, v) for v in (A_, B_)] for e in lin])
P_t = sp.Poly(sp.expand(Mk.det()).subs(k, sp.sqrt(s_)), s_).as_expr()
P_r = sp.expand(sp.simplify(eq_r.subs(Y, ex).doit() / ex)).subs(k, sp.sqrt(s_))
# psi = ratio(s) * Y' on each exponential, from the second equation
ratio = sp.simplify(sp.solve(lin[1], B_)[0] / (A_ * k))
ratio = sp.simplify(ratio.subs(k**2, s_))
assert not ratio.has(k)
# P is quadratic in s; the Euler-Bernoulli limit (kGA -> oo, rhoI = 0) is EI s**2 - N s + kw - m w2
assert sp.degree(P_t, s_) == 2 and sp.degree(P_r, s_) == 2
assert sp.expand(P_r - (EI * s_**2 - (N - rhoI * w2) * s_ + kw - m * w2)) == 0
limit = sp.limit(sp.expand(P_t / kGA), kGA, sp.oo).subs(rhoI, 0)
assert sp.expand(limit - (EI * s_**2 - N * s_ + kw - m * w2)) == 0


def general_solution(theory):
    """``(Y, psi)`` with the four constants, in ``a, b`` (``P(a**2) = P(-b**2) = 0``)."""
    basis = [sp.cosh(a * x), sp.sinh(a * x), sp.cos(b * x), sp.sin(b * x)]
    squares = [a**2, a**2, -b**2, -b**2]
    Yg = sum(c * f for c, f in zip(C, basis))
    if theory == "timoshenko":
        psig = sum(c * ratio.subs(s_, q) * f.diff(x) for c, f, q in zip(C, basis, squares))
    else:
        psig = Yg.diff(x)
    return Yg, psig, squares


def end_rows(theory, bc, at):
    """Rows of the end conditions ``bc`` at ``x = at`` in the constants ``C1..C4``."""
    Yg, psig, _ = general_solution(theory)
    if theory == "timoshenko":
        M = M_t.subs({psi.diff(x): psig.diff(x)})
        Q = Q_t.subs({Y.diff(x): Yg.diff(x), psi: psig})
    else:
        M = M_r.subs({Y.diff(x, 2): Yg.diff(x, 2)})
        Q = Q_r.subs({Y.diff(x, 3): Yg.diff(x, 3), Y.diff(x): Yg.diff(x)}).doit()
    values = {"Y": Yg, "psi": psig, "M": M, "Q": Q}
    names = {"clamped": ("Y", "psi"), "pinned": ("Y", "M"), "free": ("M", "Q")}[bc]
    return [[sp.diff(values[v], c).subs(x, at) for c in C] for v in names]


def frequency_determinant(theory, left, right):
    rows = end_rows(theory, left, 0) + end_rows(theory, right, L)
    return sp.Matrix(rows).det(method="berkowitz")


def wave_numbers(P, values, dps=40):
    """``(a, b)`` (mpmath, ``dps`` digits) from the roots ``a**2 > -b**2`` of ``P`` at ``values``."""
    p2, p1, p0 = sp.Poly(P.subs(values), s_).all_coeffs()
    with mpmath.workdps(dps):
        p2, p1, p0 = (mpmath.mpmathify(sp.N(v, dps)) for v in (p2, p1, p0))
        root = mpmath.sqrt(p1**2 - 4 * p2 * p0)
        r1, r2 = (-p1 + root) / (2 * p2), (-p1 - root) / (2 * p2)
        if mpmath.re(r1) < mpmath.re(r2):
            r1, r2 = r2, r1
        return mpmath.sqrt(r1), mpmath.sqrt(-r2)


# Timoshenko: the psi of the general solution satisfies both field equations (at sample
# parameters, a and b from the roots of P)
Yg, psig, squares = general_solution("timoshenko")
sample = {EI: 2, m: 3, kGA: 60, rhoI: sp.Rational(1, 40), N: -1, kw: 5, w2: 300}
an, bn = wave_numbers(P_t, sample)
with mpmath.workdps(40):
    at = {a: sp.Float(an.real, 40), b: sp.Float(bn.real, 40), x: sp.Rational(7, 10)}
    for i in range(4):
        for e in (eq_Y, eq_psi):
            res = e.subs({Y: Yg, psi: psig}).doit().diff(C[i])
            assert abs(complex(sp.N(res.subs(sample).subs(at), 40))) < 1e-25, (i, e)

# -- 1. pinned-pinned ---------------------------------------------------------------------
for theory in ("rayleigh", "timoshenko"):
    det = frequency_determinant(theory, "pinned", "pinned")
    rest = sp.simplify(det / (sp.sin(b * L) * sp.sinh(a * L)))
    assert not rest.has(sp.sin, sp.cos, sp.sinh, sp.cosh), (theory, rest)
    print(f"{theory:10s} pinned-pinned: det = sin(b L) sinh(a L) * ({sp.factor(rest)})")

q = sp.Symbol("q", positive=True)
w2_r = sp.solve(P_r.subs(s_, -q), w2)[0]
assert sp.simplify(w2_r - (EI * q**2 + N * q + kw) / (m + rhoI * q)) == 0
# Timoshenko with Y = A sin(sqrt(q) x), psi = B cos(sqrt(q) x): Galerkin-exact for pinned ends
Asin, Bcos = sp.sin(sp.sqrt(q) * x), sp.cos(sp.sqrt(q) * x)
sub = {Y: A_ * Asin, psi: B_ * Bcos}
galerkin = sp.Matrix([[sp.simplify(sp.diff(e.subs(sub).doit(), v) / f) for v in (A_, B_)]
                      for e, f in ((eq_Y, Asin), (eq_psi, Bcos))])
brief = sp.Matrix([[kGA * q + N * q - m * w2 + kw, -kGA * sp.sqrt(q)],
                   [-kGA * sp.sqrt(q), EI * q + kGA - rhoI * w2]])
assert sp.simplify(galerkin.det() - brief.det()) == 0
assert sp.simplify(brief.det() - sp.expand(P_t.subs(s_, -q))) == 0 or sp.simplify(
    brief.det() / P_t.subs(s_, -q)).is_number
print("pinned-pinned: b L = n pi; omega**2 = (EI q**2 + N q + kw)/(m + rhoI q) (Rayleigh); "
      "Timoshenko: the two roots of det[[kGA q + N q + kw - m w2, -kGA sqrt(q)], "
      "[-kGA sqrt(q), EI q + kGA - rhoI w2]] = 0")

# -- 2. Euler-Bernoulli on a foundation, clamped-clamped -------------------------------------
det = frequency_determinant("euler-bernoulli", "clamped", "clamped").subs(a, b)
det = det.subs({N: 0, rhoI: 0})
ratio_cc = sp.simplify((det / (sp.cos(b * L) * sp.cosh(b * L) - 1)).rewrite(sp.exp))
assert not ratio_cc.has(sp.exp) and ratio_cc != 0, ratio_cc
# and a = b: P(s) = EI s**2 + kw - m w2 has the roots s = +-sqrt((m w2 - kw)/EI)
roots_eb = sp.solve(P_r.subs({N: 0, rhoI: 0}), s_)
assert {sp.simplify(r**2) for r in roots_eb} == {sp.simplify((m * w2 - kw) / EI)}
print("Euler-Bernoulli + kw clamped-clamped: cos(bL) cosh(bL) = 1, b**4 = (m w2 - kw)/EI")

# -- 3. Timoshenko clamped-free: Huang's equation -------------------------------------------
det = sp.expand(frequency_determinant("timoshenko", "clamped", "free").subs({N: 0, kw: 0}))
ch, sh, c, s = sp.symbols("ch sh c s")
trig = {sp.cosh(a * L): ch, sp.sinh(a * L): sh, sp.cos(b * L): c, sp.sin(b * L): s}
poly = sp.Poly(sp.expand(det.xreplace(trig)), ch, sh, c, s)
reduced = sp.Poly(sp.rem(sp.rem(poly.as_expr(), sh**2 - ch**2 + 1, sh), s**2 + c**2 - 1, s),
                  ch, sh, c, s)
coef = dict(reduced.terms())
rnd = random.Random(7)
for _ in range(4):
    values = {EI: sp.Rational(rnd.randint(5, 30), 10), m: sp.Rational(rnd.randint(5, 30), 10),
              L: sp.Rational(rnd.randint(5, 20), 10), kGA: rnd.randint(20, 200),
              rhoI: sp.Rational(rnd.randint(1, 30), 1000), N: 0, kw: 0,
              w2: sp.Rational(rnd.randint(1, 4000), 10)}
    an, bn = wave_numbers(P_t, values)
    with mpmath.workdps(40):
        num = {key: mpmath.mpmathify(sp.N(v.subs(values).subs(
            {a: sp.Float(an.real, 40), b: sp.Float(bn.real, 40)}), 40)) for key, v in coef.items()}
        const = num[(0, 0, 0, 0)]
        B2 = values[m] * values[w2] * values[L] ** 4 / values[EI]
        r2 = values[rhoI] / (values[m] * values[L] ** 2)
        s2 = values[EI] / (values[kGA] * values[L] ** 2)
        huang_cc = mpmath.mpmathify(sp.N((B2 * (r2 - s2) ** 2 + 2) / 2, 40))
        huang_ss = -mpmath.mpmathify(sp.N(sp.sqrt(B2) * (r2 + s2) / sp.sqrt(1 - B2 * r2 * s2) / 2,
                                          40))
        for key, v in num.items():
            if key == (1, 0, 1, 0):
                assert abs(v / const - huang_cc) < 1e-25 * abs(huang_cc), (v / const, huang_cc)
            elif key == (0, 1, 0, 1):
                assert abs(v / const - huang_ss) < 1e-25 * abs(huang_ss), (v / const, huang_ss)
            elif key != (0, 0, 0, 0):
                assert abs(v) < 1e-25 * abs(const), (key, v)
print("Timoshenko clamped-free: 2 + [B^2 (r^2 - s^2)^2 + 2] cosh(aL) cos(bL) "
      "- B (r^2 + s^2)/sqrt(1 - B^2 r^2 s^2) sinh(aL) sin(bL) = 0 (Huang 1961)")


# -- 4. symtmm.characteristic vanishes at those roots --------------------------------------
def derived(model):
    """``Delta(omega)`` of symtmm, parsed back from its JSON, as an mpmath function."""
    out = json.loads(characteristic_equation(model).to_json())
    omega = sp.Symbol(out["variable"], positive=True)
    return sp.lambdify(omega, sp.sympify(out["delta"], locals={out["variable"]: omega}),
                       "mpmath"), out


def vanishes(fn, w, digits=20):
    """``fn(w) ~ 0`` (``digits`` below its size a percent away)."""
    w = mpmath.mpf(w)
    rel = mpmath.mpf(10) ** -digits
    near = max(abs(fn(w * 1.01)), abs(fn(w * 0.99)))
    return abs(fn(w)) < rel * near and near > 0


def pp(theory, **kw_):
    return Model((Beam("b", 2, 3, sp.Rational(3, 2), left="pinned", right="pinned",
                       theory=theory, **kw_),))


with mpmath.workdps(40):
    cases = [("rayleigh", dict(rhoI=sp.Rational(1, 50))), ("euler-bernoulli", dict(N=-3)),
             ("euler-bernoulli", dict(kw=40)), ("rayleigh", dict(rhoI=sp.Rational(1, 50), N=5, kw=7))]
    for theory, opts in cases:
        fn, _ = derived(pp(theory, **opts))
        vals = {EI: 2, m: 3, N: opts.get("N", 0), kw: opts.get("kw", 0), rhoI: opts.get("rhoI", 0)}
        for n in (1, 2, 5):
            qn = (n * sp.pi / sp.Rational(3, 2)) ** 2
            w = mpmath.sqrt(sp.N(w2_r.subs(vals).subs(q, qn), 40))
            assert vanishes(fn, w), (theory, opts, n)
    T = dict(rhoI=sp.Rational(1, 40), kGA=60)
    fn, out = derived(pp("timoshenko", **T))
    for n in (1, 2, 3):
        qn = (n * sp.pi / sp.Rational(3, 2)) ** 2
        vals = {EI: 2, m: 3, N: 0, kw: 0, rhoI: T["rhoI"], kGA: T["kGA"], q: qn}
        for root in sp.solve(brief.det().subs(vals), w2):
            assert vanishes(fn, mpmath.sqrt(sp.N(root, 40))), (n, root)
    print(f"symtmm pinned-pinned Timoshenko: Delta = {out['delta_Omega']}, {out['definitions']}")

    fn, out = derived(Model((Beam("b", 2, 3, sp.Rational(3, 2), kw=40, left="clamped",
                                  right="clamped"),)))
    for beta_l in (mpmath.findroot(lambda z: mpmath.cos(z) * mpmath.cosh(z) - 1, g)
                   for g in (4.73, 7.85, 11.0)):
        bn = beta_l / mpmath.mpf(3) * 2
        assert vanishes(fn, mpmath.sqrt((2 * bn**4 + 40) / 3)), beta_l
    print(f"symtmm clamped-clamped on a foundation: {out['delta_Omega']}, {out['definitions']}")

    values = {EI: 2, m: 3, L: sp.Rational(3, 2), kGA: 60, rhoI: sp.Rational(1, 40), N: 0, kw: 0}
    fn, out = derived(Model((Beam("b", 2, 3, sp.Rational(3, 2), left="clamped", right="free",
                                  theory="timoshenko", rhoI=values[rhoI], kGA=values[kGA]),)))

    def huang(w):
        an, bn = wave_numbers(P_t, {**values, w2: sp.Float(w, 40) ** 2})
        Lv = mpmath.mpf(3) / 2
        B2 = 3 * w**2 * Lv**4 / 2
        r2 = mpmath.mpf(1) / 40 / (3 * Lv**2)
        s2 = 2 / (60 * Lv**2)
        return mpmath.re(2 + (B2 * (r2 - s2) ** 2 + 2) * mpmath.cosh(an * Lv) * mpmath.cos(bn * Lv)
                         - mpmath.sqrt(B2) * (r2 + s2) / mpmath.sqrt(1 - B2 * r2 * s2)
                         * mpmath.sinh(an * Lv) * mpmath.sin(bn * Lv))

    grid = [mpmath.mpf(i) / 4 for i in range(1, 200)]
    signs = [(g, huang(g)) for g in grid]
    roots = [mpmath.findroot(huang, (u, v), solver="anderson")
             for (u, fu), (v, fv) in pairwise(signs) if fu * fv < 0]
    assert len(roots) >= 3
    for w in roots[:4]:
        assert vanishes(fn, w), w
    print(f"symtmm clamped-free Timoshenko vanishes at Huang's first roots "
          f"{[mpmath.nstr(r, 10) for r in roots[:4]]}: {out['delta_Omega']}")
