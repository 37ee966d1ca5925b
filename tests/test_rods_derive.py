"""Closed-form characteristic equations of rods (``derive`` with ``[[rod]]``).

References, none of them from symtmm:

* a uniform rod in axial vibration: ``omega_n = n pi/L sqrt(EA/m)`` fixed-fixed and
  free-free (the latter with its rigid motion at 0), ``(2n - 1) pi/(2L) sqrt(EA/m)``
  fixed-free; in torsion the same with ``GJ/rhoIp``; on an axial foundation ``kw``,
  ``m omega**2 = kw + EA (n pi/L)**2`` fixed-fixed;
* a fixed-free rod held at ``x0`` by a grounded spring and dashpot ``K = k + c lam``:
  continuity and the force jump at ``x0`` give ``EA beta cos(beta L) + K sin(beta x0)
  cos(beta (L - x0)) = 0``, ``beta**2 = -(m lam**2 + kw)/EA`` (in torsion ``GJ``,
  ``rhoIp``, a rotational spring); its roots by ``mpmath.findroot`` on that closed form,
  from the undamped ones (sign changes on the frequency axis);
* two identical fixed-free rods joined by a spring ``k`` at ``x0``: in phase the single
  rod's ``cos(beta L) = 0``, out of phase the rod above with ``K = 2k``;
* a clamped-free Euler-Bernoulli beam: ``cos(Omega) cosh(Omega) + 1 = 0``, ``Omega**4 =
  m omega**2 L**4/EI``.

Each derived Delta vanishes at these roots and not between them.
"""

from __future__ import annotations

import json
from itertools import pairwise

import mpmath
import pytest
import sympy as sp
from cli_contract import assert_contract, run_cli

from symtmm import api
from symtmm.characteristic import OMEGA, OMEGA_DIMLESS, characteristic_equation
from symtmm.elements.base import LAM
from symtmm.expr import parameter_symbol
from symtmm.model import Beam, Model, Spring, rod
from symtmm.modelfile import loads

Om = OMEGA_DIMLESS
R = sp.Rational

KUKLA = """
title = "two rods coupled by axial springs"
[parameters]
k = 5
[[rod]]
name = "a"
EA = 1
m = 1
L = 1
left = "fixed"
right = "free"
[[rod]]
name = "b"
EA = 1
m = 1
L = 1
left = "fixed"
right = "free"
[[spring]]
between = ["a", "b"]
x = 0.4
k = "k"
kind = "axial"
"""


def _delta(eq, values=None):
    """``Delta`` of the JSON contract, parsed back, as an mpmath function of the variable."""
    out = json.loads(eq.to_json())
    var = sp.Symbol(out["variable"], positive=out["variable"] == "omega")
    names = {name: parameter_symbol(name) for name in out["symbols"]}
    expr = sp.sympify(out["delta"], locals={out["variable"]: var, **names})
    assert "nan" not in out["delta"] and "nan" not in out["constant"]
    if values:
        expr = expr.xreplace({names[k]: v for k, v in values.items()})
    assert expr.free_symbols <= {var}
    return sp.lambdify(var, expr, "mpmath")


def _vanishes(fn, z, digits=20) -> bool:
    """``|fn(z)|`` is ``digits`` below its size a percent either side (and that is not 0)."""
    near = min(abs(fn(z * mpmath.mpf("1.01"))), abs(fn(z * mpmath.mpf("0.99"))))
    return near > 0 and abs(fn(z)) < mpmath.mpf(10) ** -digits * near


def _check_roots(fn, roots, digits=20):
    """``fn`` vanishes at every root and at no point halfway between two of them."""
    for z in roots:
        assert _vanishes(fn, z, digits), z
    for u, v in pairwise(roots):
        mid = (u + v) / 2
        assert abs(fn(mid)) > mpmath.mpf(10) ** -6 * max(abs(fn(u * mpmath.mpf("1.01"))),
                                                        abs(fn(v * mpmath.mpf("0.99")))), mid


def _sign_change_roots(g, top, count, steps=4000):
    """The first ``count`` roots of the real function ``g`` on ``(0, top)``: sign changes on
    a grid, refined by ``mpmath.findroot`` (bisection on each bracket)."""
    roots = []
    grid = [top * mpmath.mpf(i) / steps for i in range(1, steps + 1)]
    values = [g(w) for w in grid]
    for (a, fa), (b, fb) in pairwise(zip(grid, values)):
        if fa * fb < 0:
            roots.append(mpmath.findroot(g, (a, b), solver="anderson"))
            if len(roots) == count:
                break
    assert len(roots) == count
    return roots


def _spring_equation(stiffness, inertia, length, x0, k, c=0, kw=0):
    """``EA cos(beta L) + K sin(beta x0) cos(beta (L - x0)) / beta`` (the closed form over
    ``beta``, even in it: entire in ``lam``), ``K = k + c lam``, ``beta**2 = -(m lam**2 +
    kw)/EA``: a fixed-free rod held at ``x0`` by a grounded spring and dashpot."""
    def f(lam):
        beta = mpmath.sqrt(-(inertia * lam**2 + kw) / mpmath.mpf(stiffness))
        K = k + c * lam
        return stiffness * mpmath.cos(beta * length) \
            + K * mpmath.sin(beta * x0) * mpmath.cos(beta * (length - x0)) / beta
    return f


# -- one rod --------------------------------------------------------------------------------

#: ends -> (the n-th frequency in units of pi/L sqrt(EA/m), a rigid motion at 0)
ENDS = {("fixed", "fixed"): (lambda n: n, False),
        ("fixed", "free"): (lambda n: n - R(1, 2), False),
        ("free", "fixed"): (lambda n: n - R(1, 2), False),
        ("free", "free"): (lambda n: n, True)}


@pytest.mark.parametrize("ends", list(ENDS))
def test_single_rod_textbook_frequencies(ends):
    """Symbolic ``EA, m, L``: Delta in ``omega`` vanishes at the textbook frequencies,
    nowhere between, at 0 only with a rigid motion."""
    model = Model((rod("r", "EA", "m", "L", left=ends[0], right=ends[1]),),
                  parameters={"EA": None, "m": None, "L": None})
    eq = characteristic_equation(model)
    assert eq.variable == OMEGA and set(eq.symbols) == {"EA", "m", "L"}
    values = {"EA": 3, "m": 2, "L": R(5, 4)}
    fn = _delta(eq, values)
    nth, rigid = ENDS[ends]
    with mpmath.workdps(40):
        unit = mpmath.pi / mpmath.mpf(5) * 4 * mpmath.sqrt(mpmath.mpf(3) / 2)
        _check_roots(fn, [unit * mpmath.mpf(nth(n)) for n in range(1, 7)])
        small = abs(fn(mpmath.mpf("1e-12")))
        assert (small < mpmath.mpf("1e-10")) == rigid


@pytest.mark.parametrize("ends, form", [
    (("fixed", "free"), sp.cos(OMEGA)), (("free", "fixed"), sp.cos(OMEGA)),
    (("fixed", "fixed"), sp.sin(OMEGA) / OMEGA), (("free", "free"), OMEGA * sp.sin(OMEGA))])
def test_rod_without_torsion_is_the_classical_equation(ends, form):
    """``EA = m = L = 1``: Delta is the textbook equation up to a nonzero constant, with no
    factor (nor ``nan``) of the twist a rod without torsion carries inside."""
    model = Model((rod("r", 1, 1, 1, left=ends[0], right=ends[1]),))
    eq = characteristic_equation(model)
    ratio = sp.simplify(eq.delta / form)
    assert ratio.is_number and ratio != 0 and ratio.is_finite
    assert eq.constant.is_finite and eq.constant != 0 and not eq.constant.has(sp.nan)
    assert len(eq.factors) == 1 and eq.delta_Omega.xreplace({Om: OMEGA}) == eq.delta


#: torsion ends -> (axial, torsional) n-th frequency in units of pi/L sqrt(EA/m), sqrt(GJ/rhoIp)
TORSION_ENDS = {("fixed", "free"): (lambda n: n - R(1, 2), lambda n: n - R(1, 2)),
                ("fixed-axial", "fixed"): (lambda n: n, lambda n: n - R(1, 2)),
                ("fixed-torsion", "free"): (lambda n: n, lambda n: n - R(1, 2)),
                ("fixed", "fixed-axial"): (lambda n: n, lambda n: n - R(1, 2))}


@pytest.mark.parametrize("ends", list(TORSION_ENDS))
def test_rod_with_torsion_both_families(ends):
    """Axial and torsional frequencies are both roots of Delta, and nothing between."""
    EA, m, L, GJ, rhoIp = 2, 1, R(3, 2), 3, R(1, 5)
    model = Model((rod("r", EA, m, L, GJ=GJ, rhoIp=rhoIp, left=ends[0], right=ends[1]),))
    eq = characteristic_equation(model)
    fn = _delta(eq)
    axial, torsional = TORSION_ENDS[ends]
    with mpmath.workdps(40):
        u = mpmath.pi / mpmath.mpf(L.p) * L.q * mpmath.sqrt(mpmath.mpf(EA) / m)
        t = mpmath.pi / mpmath.mpf(L.p) * L.q * mpmath.sqrt(GJ / (mpmath.mpf(rhoIp.p) / rhoIp.q))
        roots = sorted([u * mpmath.mpf(axial(n)) for n in range(1, 5)]
                       + [t * mpmath.mpf(torsional(n)) for n in range(1, 3)])
        _check_roots(fn, roots)


def test_rod_on_a_foundation():
    """``m omega**2 = kw + EA (n pi/L)**2`` fixed-fixed, written in ``b_r`` with its definition."""
    EA, m, L, kw = 2, 3, 1, 12
    eq = characteristic_equation(Model((rod("r", EA, m, L, kw=kw),)))
    (b,) = eq.definitions
    assert b.name == "b_r"
    assert sp.simplify(eq.definitions[b] ** 2 - (m * OMEGA**2 - kw) / EA) == 0
    assert eq.equation.has(b)
    fn = _delta(eq)
    with mpmath.workdps(40):
        _check_roots(fn, [mpmath.sqrt((kw + EA * (n * mpmath.pi / L) ** 2) / m)
                          for n in range(1, 6)])


# -- springs and dashpots -------------------------------------------------------------------

SPRING_CASES = {
    # name: (torsion, k, c, kw)
    "axial": (False, 10, 0, 0),
    "axial damped": (False, 10, R(1, 2), 0),
    "axial damped on a foundation": (False, 10, R(1, 2), 3),
    "torsional damped": (True, 4, R(1, 3), 0),
}


@pytest.mark.parametrize("case", list(SPRING_CASES))
def test_grounded_spring_and_dashpot(case):
    """A fixed-free rod held at ``x0`` by a grounded spring (dashpot): Delta vanishes at the
    roots of ``EA beta cos(beta L) + K sin(beta x0) cos(beta (L - x0))`` and not between."""
    torsion, k, c, kw = SPRING_CASES[case]
    EA, m, L, x0 = 2, 1, 1, R(2, 5)
    GJ, rhoIp = 3, R(1, 2)
    fields = dict(GJ=GJ, rhoIp=rhoIp) if torsion else {}
    model = Model((rod("r", EA, m, L, kw=kw, left="fixed", right="free", **fields),),
                  springs=(Spring("r", "ground", x0, k=k, c=c,
                                  kind="rotational" if torsion else "translational"),))
    eq = characteristic_equation(model)
    assert eq.variable == (LAM if c else OMEGA)
    fn = _delta(eq)
    stiffness, inertia = (GJ, rhoIp) if torsion else (EA, m)
    with mpmath.workdps(40):
        x, length = mpmath.mpf(2) / 5, mpmath.mpf(L)
        inertia = mpmath.mpf(inertia.p) / inertia.q if torsion else mpmath.mpf(inertia)
        undamped = _spring_equation(stiffness, inertia, length, x, k, kw=kw)
        omegas = _sign_change_roots(lambda w: undamped(mpmath.mpc(0, w)).real, 30, 4)
        if not c:
            _check_roots(fn, omegas)
            return
        damped = _spring_equation(stiffness, inertia, length, x, k, c=mpmath.mpf(c.p) / c.q,
                                  kw=kw)
        roots = [mpmath.findroot(damped, mpmath.mpc(0, w)) for w in omegas]
        assert all(r.real < 0 for r in roots)
        assert len({mpmath.nstr(r, 10) for r in roots}) == len(roots)
        _check_roots(fn, roots)


def test_two_rods_joined_by_a_spring_in_and_out_of_phase(tmp_path):
    """The example: ``cos(omega)`` (in phase) times the out-of-phase family ``omega
    cos(omega) + 2k sin(2 omega/5) cos(3 omega/5)``; the command line prints it."""
    model = loads(KUKLA)
    eq = characteristic_equation(model)
    assert eq.variable == OMEGA
    assert (sp.cos(Om), 1) in eq.factors          # the single rod's: the in-phase family
    fn = _delta(eq)
    with mpmath.workdps(40):
        def out_of_phase(w):
            return w * mpmath.cos(w) + 10 * mpmath.sin(2 * w / 5) * mpmath.cos(3 * w / 5)
        in_phase = [(2 * n - 1) * mpmath.pi / 2 for n in range(1, 5)]
        out = _sign_change_roots(out_of_phase, 12, 3)
        # 5 pi/2 is a root of both families (cos(3 omega/5) = 0 there too): a double root
        assert abs(out[2] - in_phase[2]) < mpmath.mpf(10) ** -30
        _check_roots(fn, sorted(in_phase + out[:2]))
        assert abs(mpmath.diff(fn, in_phase[2])) < mpmath.mpf(10) ** -20 \
            * abs(mpmath.diff(fn, in_phase[1]))
    assert api.derive(model).delta == eq.delta
    path = tmp_path / "kukla.toml"
    path.write_text(KUKLA)
    run = run_cli(["derive", path], limit=60)
    assert_contract(run, 60)
    assert "nan" not in run.stdout and "Delta(omega) = 1\n" not in run.stdout
    assert f"Delta(omega) = {eq.delta}" in run.stdout
    run = run_cli(["derive", path, "--json"], limit=60)
    assert_contract(run, 60)
    out = json.loads(run.stdout)
    assert out["variable"] == "omega" and out["symbols"] == []


def test_symbolic_spring_between_rods():
    """``k``, ``x`` and the rods' ``EA, m`` symbolic: the out-of-phase roots for values of
    them (the closed form with ``K = 2k``) and the in-phase ones."""
    model = Model((rod("a", "EA", "m", 1, right="free"), rod("b", "EA", "m", 1, right="free")),
                  springs=(Spring("a", "b", "x", k="k"),),
                  parameters={"EA": None, "m": None, "x": R(1, 3), "k": None})
    eq = characteristic_equation(model, symbolic=("x",))
    assert set(eq.symbols) == {"EA", "m", "k", "x"}
    values = {"EA": 2, "m": 3, "k": 4, "x": R(1, 3)}
    fn = _delta(eq, values)
    with mpmath.workdps(40):
        scale = mpmath.sqrt(mpmath.mpf(2) / 3)     # omega = beta sqrt(EA/m)
        spring = _spring_equation(2, 3, 1, mpmath.mpf(1) / 3, 8)
        out = _sign_change_roots(lambda w: spring(mpmath.mpc(0, w)).real, 20, 3)
        roots = sorted(out + [(2 * n - 1) * mpmath.pi / 2 * scale for n in range(1, 5)])
        _check_roots(fn, roots)


def test_rods_on_and_off_a_foundation_joined_by_a_spring():
    """Rod ``a`` on a foundation, rod ``b`` without, both fixed-free, joined at ``x0`` by a
    spring ``k``: the roots of the ``4 x 4`` determinant of the two rods' pieces
    ``u = A sin(beta x)/beta`` before ``x0`` and ``C cos(beta (L - x))`` after (continuity,
    force jumps ``EA [u'] = k (u - u_other)``). ``Omega`` is rod ``b``'s ``beta L``."""
    kw, k, x0 = 2, 3, R(1, 2)
    model = Model((rod("a", 1, 1, 1, kw=kw, right="free"), rod("b", 1, 1, 1, right="free")),
                  springs=(Spring("a", "b", x0, k=k),))
    eq = characteristic_equation(model)
    assert eq.definitions[Om] == OMEGA
    (b,) = [s for s in eq.definitions if s != Om]
    assert sp.simplify(eq.definitions[b] ** 2 - (OMEGA**2 - kw)) == 0
    fn = _delta(eq)

    def determinant(w):
        x = mpmath.mpf(x0.p) / x0.q
        betas = (mpmath.sqrt(w**2 - kw), w)
        M = mpmath.zeros(4, 4)
        for r, beta in enumerate(betas):
            other = betas[1 - r]
            M[2 * r, 2 * r] = mpmath.sin(beta * x) / beta
            M[2 * r, 2 * r + 1] = -mpmath.cos(beta * (1 - x))
            M[2 * r + 1, 2 * r] = -mpmath.cos(beta * x) - k * mpmath.sin(beta * x) / beta
            M[2 * r + 1, 2 * r + 1] = beta * mpmath.sin(beta * (1 - x))
            M[2 * r + 1, 2 * (1 - r)] = k * mpmath.sin(other * x) / other
        return mpmath.re(mpmath.det(M))

    with mpmath.workdps(40):
        # (every entry even in beta: real also where rod a's beta is imaginary)
        _check_roots(fn, _sign_change_roots(determinant, 10, 5, steps=2000))


# -- beams and rods in one model ------------------------------------------------------------

@pytest.mark.parametrize("damped", [False, True])
def test_beam_beside_a_rod(damped):
    """A clamped-free beam and a rod (a spring and, damped, a dashpot on the rod): Delta is
    the product of the beam's ``cos Omega cosh Omega + 1`` and the rod's factor."""
    EI, mb, Lb = 2, 3, R(3, 2)
    EA, m, L, x0, k, c = 5, 2, 1, R(1, 2), 3, (R(1, 4) if damped else 0)
    model = Model((Beam("b", EI, mb, Lb, left="clamped", right="free"),
                   rod("r", EA, m, L, left="fixed", right="free")),
                  springs=(Spring("r", "ground", x0, k=k, c=c),))
    eq = characteristic_equation(model)
    assert eq.variable == (LAM if damped else OMEGA)
    for f, _ in eq.factors:     # beam's and rod's arguments never meet in one factor
        arguments = {a.args[0] for a in f.atoms(sp.sin, sp.cos, sp.sinh, sp.cosh)}
        assert len({a.has(Om**2) for a in arguments}) <= 1, f
    fn = _delta(eq)
    with mpmath.workdps(40):
        beam = [mpmath.findroot(lambda s: mpmath.cos(s) * mpmath.cosh(s) + 1, guess)
                for guess in (1.875, 4.694, 7.855)]
        beam = [s**2 / Lb**2 * mpmath.sqrt(mpmath.mpf(EI) / mb) for s in beam]
        spring = _spring_equation(EA, m, L, mpmath.mpf(1) / 2, k)
        rods = _sign_change_roots(lambda w: spring(mpmath.mpc(0, w)).real, 20, 3)
        if not damped:
            _check_roots(fn, sorted(beam + rods))
            return
        damped_spring = _spring_equation(EA, m, L, mpmath.mpf(1) / 2, k, c=mpmath.mpf(1) / 4)
        rods = [mpmath.findroot(damped_spring, mpmath.mpc(0, w)) for w in rods]
        assert all(r.real < 0 for r in rods)
        _check_roots(fn, [mpmath.mpc(0, w) for w in beam])
        _check_roots(fn, rods)
