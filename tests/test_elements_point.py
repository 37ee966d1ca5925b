"""Point elements: lumped masses with rotary inertia, rotational springs/dashpots, elastic ends.

References are independent of the transfer formulation: classical closed-form
frequency equations written out here, and the cubic-Hermite finite-element
model of :mod:`symtmm.fe` extended in this file by lumped masses and
rotational springs on its nodal freedoms.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
import scipy.linalg
import sympy as sp

from symtmm.characteristic import OMEGA_DIMLESS, characteristic_equation
from symtmm.cli import main
from symtmm.codegen import generate
from symtmm.compile import Evaluator
from symtmm.errors import ModelError
from symtmm.fe import fe_matrices
from symtmm.model import Beam, Mass, Model, Spring
from symtmm.modelfile import load, loads
from symtmm.modes import mode_shapes
from symtmm.numeric.evaluator import Evaluator as Kernel
from symtmm.roots.count import Counter
from symtmm.solve import solve

EXAMPLES = __import__("pathlib").Path(__file__).resolve().parent.parent / "examples"


def _roots(f, guesses, dps=30):
    with mpmath.workdps(dps):
        return sorted({mpmath.nstr(mpmath.findroot(f, g), 20) for g in guesses}, key=float)


def _cantilever(tip_mass=0, tip_spring=0):
    masses = (Mass("a", 1, tip_mass),) if tip_mass else ()
    springs = (Spring("a", "ground", 1, tip_spring),) if tip_spring else ()
    return Model((Beam("a", 1, 1, 1, left="clamped", right="free"),), springs, masses=masses)


@pytest.mark.parametrize("r", [sp.Rational(1, 5), 1, 5])
def test_cantilever_with_tip_mass_closed_form(r):
    # 1 + cos nu cosh nu + r nu (cos nu sinh nu - sin nu cosh nu) = 0, r = M/(m L)
    def f(n):
        return 1 + mpmath.cos(n) * mpmath.cosh(n) + float(r) * n * (
            mpmath.cos(n) * mpmath.sinh(n) - mpmath.sin(n) * mpmath.cosh(n))
    # bracket each root between sign changes of the closed form
    grid = np.linspace(0.05, 14.5, 3000)
    vals = [float(f(g)) for g in grid]
    ref = []
    with mpmath.workdps(30):
        for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:]):
            if fa * fb < 0:
                ref.append(mpmath.findroot(f, (a, b), solver="anderson"))
    spec = solve(_cantilever(tip_mass=r), count=4, digits=14)
    got = [float(mpmath.sqrt(e.omega)) for e in spec]
    assert np.allclose(got, [float(x) for x in ref[:4]], rtol=1e-12, atol=0)


def test_cantilever_with_tip_spring_closed_form():
    # EI Y''' = k Y at the free end: 1 + cos cosh - (K/nu^3)(cos sinh - sin cosh) = 0
    K = 10
    def f(n):
        return 1 + mpmath.cos(n) * mpmath.cosh(n) - K / n**3 * (
            mpmath.cos(n) * mpmath.sinh(n) - mpmath.sin(n) * mpmath.cosh(n))
    grid = np.linspace(0.3, 11.5, 2000)
    vals = [float(f(g)) for g in grid]
    ref = [mpmath.findroot(f, (a, b), solver="anderson")
           for a, b, fa, fb in zip(grid, grid[1:], vals, vals[1:]) if fa * fb < 0]
    got = [float(mpmath.sqrt(e.omega)) for e in solve(_cantilever(tip_spring=K), count=3)]
    assert np.allclose(got, [float(x) for x in ref[:3]], rtol=1e-12)


def test_derive_tip_mass_is_the_classical_equation():
    model = _cantilever(tip_mass=sp.Symbol("R", positive=True))
    model = Model(model.beams, masses=(Mass("a", 1, "R"),), parameters={"R": None})
    eq = characteristic_equation(model)
    R = sp.Symbol("R", positive=True)
    n = OMEGA_DIMLESS
    classical = 1 + sp.cos(n) * sp.cosh(n) + R * n * (sp.cos(n) * sp.sinh(n)
                                                     - sp.sin(n) * sp.cosh(n))
    got = eq.delta_Omega.subs(sp.Symbol("R", positive=True), R)
    for nv, rv in [(sp.Rational(7, 5), 2), (sp.Rational(31, 10), sp.Rational(1, 3))]:
        a = sp.N(got.subs({n: nv, R: rv}), 30)
        b = sp.N(classical.subs({n: nv, R: rv}), 30)
        assert abs(a / b - 1) < 1e-25 or abs(a + b) < 1e-25 * abs(b)


# -- finite-element reference, extended by lumped masses and rotational springs ---------

def _fe_reference(beam, masses=(), rot_springs=(), y_springs=(), elements=120, count=6):
    """FE frequencies with lumped masses (x, M, J) and springs (x, k) on Y/Theta to ground."""
    # zero springs put nodes at every point element's position
    marks = [dict(between=[beam["name"], "ground"], x=x, k=0.0)
             for x, *_ in list(masses) + list(rot_springs)]
    marks += [dict(between=[beam["name"], "ground"], x=x, k=k) for x, k in y_springs]
    K, M, info = fe_matrices([beam], marks, elements)
    nodes, dofs = info["nodes"][beam["name"]], info["dofs"][beam["name"]]

    def node(x):
        return int(np.argmin(np.abs(np.asarray(nodes) - x)))

    for x, Mass_, J in masses:
        iy, it = dofs[node(x)]
        if iy >= 0:
            M[iy, iy] += Mass_
        if it >= 0:
            M[it, it] += J
    for x, k in rot_springs:
        it = dofs[node(x)][1]
        if it >= 0:
            K[it, it] += k
    w2 = scipy.linalg.eigh(K, M, eigvals_only=True)
    return np.sqrt(np.clip(w2[:count], 0, None))


def test_pinned_beam_with_central_mass_and_rotary_inertia_vs_fe():
    beam = dict(name="a", EI=2.0, m=3.0, L=1.5, x0=0.0, left="pinned", right="pinned")
    ref = _fe_reference(beam, masses=[(0.6, 1.5, 0.05)], count=5)
    model = Model((Beam("a", 2, 3, "3/2", left="pinned", right="pinned"),),
                  masses=(Mass("a", "0.6", "1.5", "0.05"),))
    got = [float(e.omega) for e in solve(model, count=5)]
    assert np.allclose(got, ref, rtol=2e-7)


def test_rotational_end_springs_vs_fe_and_limits():
    kr = 7.0
    beam = dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned")
    ref = _fe_reference(beam, rot_springs=[(0.0, kr), (1.0, kr)], count=4)

    def model(k):
        return Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),),
                     (Spring("a", "ground", 0, k, kind="rotational"),
                      Spring("a", "ground", 1, k, kind="rotational")))
    got = [float(e.omega) for e in solve(model(7), count=4)]
    assert np.allclose(got, ref, rtol=2e-7)
    # k_r -> 0: pinned-pinned (n pi)^2; k_r -> oo: clamped-clamped 4.7300407448627^2
    soft = [float(e.omega) for e in solve(model("1e-9"), count=2)]
    assert np.allclose(soft, [np.pi**2, 4 * np.pi**2], rtol=1e-9)
    stiff = float(solve(model("1e12"), count=1)[0].omega)
    assert abs(stiff / 4.730040744862704**2 - 1) < 1e-10


def test_pinned_beam_with_equal_rotational_end_springs_symmetric_closed_form():
    # symmetric modes of a beam on rotational springs k at both ends (x from the middle):
    # Y = A cos(nu s) + B cosh(nu s); the end conditions give
    # nu (tan(nu/2) + tanh(nu/2)) = -2 K ... derived from EI Y'' = -k Y' at s = L/2, Y = 0
    K = 3.0

    def f(n):
        # Y(1/2)=0: A cos(n/2) + B cosh(n/2) = 0; EI Y''(1/2) + k Y'(1/2) = 0
        c, ch, s, sh = mpmath.cos(n / 2), mpmath.cosh(n / 2), mpmath.sin(n / 2), mpmath.sinh(n / 2)
        # det [[c, ch], [-n^2 c - K n s, n^2 ch + K n sh]]
        return c * (n**2 * ch + K * n * sh) - ch * (-n**2 * c - K * n * s)
    ref = float(mpmath.findroot(f, 3.5))
    model = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", 0, 3, kind="rotational"),
                   Spring("a", "ground", 1, 3, kind="rotational")))
    got = float(mpmath.sqrt(solve(model, count=1)[0].omega))
    assert abs(got / ref - 1) < 1e-13


def test_rotational_coupling_of_two_beams_vs_fe():
    # two cantilevers joined at their tips by a rotational spring: the in-phase family
    # (equal rotations) does not stretch it and stays that of the free cantilever
    model = Model((Beam("a", 1, 1, 1, left="clamped", right="free"),
                   Beam("b", 1, 1, 1, left="clamped", right="free")),
                  (Spring("a", "b", 1, 10, kind="rotational"),))
    spec = solve(model, count=4)
    cant = [1.8751040687119611, 4.6940911329741745]
    anti = _fe_reference(dict(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="clamped",
                              right="free"), rot_springs=[(1.0, 20.0)], count=2)
    want = sorted([c**2 for c in cant] + list(anti))
    assert np.allclose([float(e.omega) for e in spec], want, rtol=2e-7)


# -- the other formulations and features -----------------------------------------------

def _mixed(damped=False):
    c = "1/5" if damped else 0
    return Model((Beam("a", 1, 1, 1, left="free", right="pinned"),
                  Beam("b", 2, 1, "3/2", x0="-1/4", left="clamped", right="free")),
                 (Spring("a", "b", "1/2", 30, c=c, kind="rotational"),
                  Spring("a", "b", "3/4", 20, c=c),
                  Spring("a", "ground", 0, 5, c=c, kind="rotational"),
                  Spring("b", "ground", "5/4", 8)),
                 masses=(Mass("a", "1/2", "1/2", "1/20"), Mass("b", "5/4", 1)))


def test_dynamic_stiffness_identity_with_point_elements():
    # Delta = det K * prod det U12 up to a constant factor: compare ratios at two points
    for damped in (False, True):
        model = _mixed(damped)
        ev = Evaluator(model)
        ds = Kernel(model, 400.0)
        lam = np.array([-0.7 + 13.1j, -2.0 + 41.3j, -0.1 + 95.0j])
        logabs, phase, ok = ds.log_delta(lam)
        assert ok.all()
        ratio = ev.delta(lam) / np.exp(logabs + 1j * phase)
        assert np.allclose(ratio / ratio[0], 1, rtol=1e-7)


def test_count_agrees_with_fe_and_solve_with_masses():
    model = _mixed()
    spec = solve(model, count=6)
    sm = Counter(model, 2 * float(spec[5].omega))
    for e in spec:
        w = float(e.omega)
        assert sm.count(w * (1 - 1e-6)) < sm.count(w * (1 + 1e-6))


def test_damped_solver_with_point_elements():
    model = _mixed(damped=True)
    spec = solve(model, omega_max=60, sigma_max=50, digits=10)
    ev = Evaluator(model)
    assert len(spec.eigenvalues) >= 2
    with mpmath.workdps(40):
        for e in spec:
            scale = abs(ev.delta_mp(e.lam * (1 + mpmath.mpf("1e-6"))))
            assert abs(ev.delta_mp(e.lam)) < 1e-6 * scale
    # zero damping limit: the undamped solver's frequencies
    undamped = solve(_mixed(False), omega_max=60)
    assert len(undamped.eigenvalues) == len(spec.eigenvalues)


def test_codegen_python_with_masses_and_rotational_springs():
    model = _mixed(damped=True)
    ns: dict = {}
    exec(generate(model, "python"), ns)  # noqa: S102 - the generated module
    lam = np.array([0.3 + 2.0j, -1.0 + 17.5j, 0.0 + 44.0j])
    assert np.allclose(ns["symtmm_delta"](lam), Evaluator(model).delta(lam), rtol=1e-9)


def test_characteristic_agrees_with_evaluator_with_point_elements():
    model = Model((Beam("a", 1, 1, 1, left="free", right="pinned"),
                   Beam("b", 1, 1, 1, left="clamped", right="free")),
                  (Spring("a", "b", "1/2", 30, kind="rotational"),
                   Spring("a", "ground", 0, 5, kind="rotational")),
                  masses=(Mass("a", "1/2", "1/2", "1/20"), Mass("b", 1, 1)))
    eq = characteristic_equation(model)
    ev = Evaluator(model)
    f = sp.lambdify(eq.variable, eq.delta * eq.constant, "mpmath")
    with mpmath.workdps(40):
        for w in (mpmath.mpf("3.7"), mpmath.mpf("21.2")):
            a = f(w)
            b = ev.delta_mp(mpmath.mpc(0, w))
            assert abs(a / b - 1) < mpmath.mpf(10) ** -30


def test_mode_shapes_with_masses_are_orthonormal_in_the_kinetic_energy():
    model = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),),
                  masses=(Mass("a", "1/2", 2, "1/10"),))
    shapes = list(mode_shapes(model, count=3, points=401))
    mid = 200

    def inner(p, q):
        bp, bq = p.beams["a"], q.beams["a"]
        return (np.trapezoid(bp.Y * bq.Y, bp.x) + 2 * bp.Y[mid] * bq.Y[mid]
                + 0.1 * bp.Theta[mid] * bq.Theta[mid])
    G = np.array([[inner(p, q) for q in shapes] for p in shapes])
    assert np.allclose(G, np.eye(3), atol=2e-5)
    # the shear jumps by the inertia force of the mass: Q+ - Q- = M omega^2 Y
    p = shapes[0]
    w2 = float(p.eigenvalue.omega) ** 2
    Q = p.beams["a"].Q
    assert abs((Q[mid + 1] - Q[mid - 1]) / (2 * w2 * p.beams["a"].Y[mid]) - 1) < 0.02


def test_model_file_fields_and_errors(tmp_path):
    model = load(EXAMPLES / "point_elements.toml")
    assert len(model.masses) == 1 and model.springs[0].kind == "rotational"
    base = '[[beam]]\nname = "a"\nEI = 1\nm = 1\nL = 1\nleft = "free"\nright = "free"\n'
    with pytest.raises(ModelError, match=r"mass\[1\].*outside"):
        loads(base + '[[mass]]\nbeam = "a"\nx = 2\nM = 1\n')
    with pytest.raises(ModelError, match=r"mass\[1\]\.beam.*unknown beam 'b'"):
        loads(base + '[[mass]]\nbeam = "b"\nx = 0\nM = 1\n')
    with pytest.raises(ModelError, match=r"mass\[1\]\.M.*negative"):
        loads(base + '[[mass]]\nbeam = "a"\nx = 0\nM = -1\n')
    with pytest.raises(ModelError, match=r"spring\[1\]\.kind.*unknown kind"):
        loads(base + '[[spring]]\nbetween = ["a", "ground"]\nx = 0\nk = 1\nkind = "twist"\n')
    with pytest.raises(ModelError, match=r"mass\[1\]\.Q.*unknown field"):
        loads(base + '[[mass]]\nbeam = "a"\nx = 0\nM = 1\nQ = 1\n')


@pytest.mark.parametrize("name", ["point_elements.toml", "elastic_supports.toml"])
def test_examples_run_through_the_cli(name, capsys):
    path = str(EXAMPLES / name)
    assert main(["solve", path, "--count", "3", "--json"]) == 0
    assert main(["modes", path, "--count", "2", "--points", "5", "--json"]) == 0
    assert main(["sweep", path, "--param", "M", "--from", "0", "--to", "1", "--steps", "2",
                 "--count", "2", "--json"]) == 0
    capsys.readouterr()
