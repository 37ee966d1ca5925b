"""The numeric kernel's contract: every element through every arithmetic.

Each segment family of :mod:`symtmm.numeric.segments` (Euler–Bernoulli with and
without foundation, and the general first-order system: axial force, Rayleigh,
Timoshenko) is evaluated in double batches, in mpmath at an explicit precision and
in Arb balls, and checked against the exact SymPy matrix of the element
(:meth:`~symtmm.elements.theories.BeamSegment.transfer_matrix`, a closed form that
shares no code with the kernel), for the properties every transfer matrix must
have (``det U = 1``, ``U(a + b) = U(b) U(a)``), and the arithmetics against each
other (a ball contains the exact value). The assembled kernel (dynamic stiffness
``Delta = det K prod det U12 P``) is checked against ``det R`` of the transfer
formulation (the product of transfer matrices along x, at 90 digits), beams joined by
layers included; the jets of :mod:`symtmm.numeric.jet` against the balls.
"""

import random

import mpmath
import numpy as np
import pytest
import sympy as sp

from symtmm.compile import Evaluator
from symtmm.elements import BeamSegment, EulerBernoulliSegment
from symtmm.elements.base import LAM
from symtmm.model import Attachment, Beam, Layer, Mass, Model, RigidBody, Spring
from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
from symtmm.numeric.plan import StiffnessPlan
from symtmm.numeric.segments import kind, kind_tables, transfer_matrices
from symtmm.numeric.stiffness import factor

R = sp.Rational

ELEMENTS = {
    "euler-bernoulli": EulerBernoulliSegment(R(3, 2), R(2, 3), R(7, 10)),
    "foundation": EulerBernoulliSegment(2, 1, R(1, 2), kw=30),
    "axial force": BeamSegment(1, 1, R(9, 10), N=-3),
    "rayleigh": BeamSegment(1, R(3, 2), 1, rhoI=R(1, 40), N=2),
    "timoshenko": BeamSegment(R(4, 5), 1, R(6, 5), kw=5, N=R(-1, 2), rhoI=R(1, 50), kGA=60),
}

ARITHMETICS = ["double", "mp", pytest.param("ball", marks=pytest.mark.skipif(
    not ball_available(), reason="python-flint not installed"))]


def _arith(name):
    return {"double": DOUBLE, "mp": MP(160), "ball": Ball(160)}[name]


def _points(seed=7):
    """``lam`` at random points: on the frequency axis (small and large) and off it."""
    rng = random.Random(seed)
    return [sp.I * R(rng.randint(1, 40), 7), sp.I * rng.randint(30, 90),
            R(-rng.randint(1, 30), 10) + sp.I * rng.randint(5, 40)]


def _kernel_matrix(ar, seg, lam):
    """The kernel's matrix of one segment at the exact ``lam``."""
    family, consts = kind(seg)
    plan_like = kind_tables(ar, [(family, consts)])
    with ar:
        lam2 = ar.array([ar.number(mpmath.mpmathify(complex(sp.N(lam**2, 30))))
                         if ar.name == "double" else _exact_number(ar, lam**2)])
        return transfer_matrices(ar, plan_like, lam2)[0, 0]


def _exact_number(ar, value):
    value = sp.expand(value)
    re, im = value.as_real_imag()
    if im == 0:
        return ar.exact(re)
    if ar.name == "ball":
        return ar.flint.acb(ar.exact(re), ar.exact(im))
    return ar.ctx.mpc(ar.exact(re), ar.exact(im))


def _exact_mpc(exact):
    """An exact SymPy number as an mpmath number at 300 bits, unrounded on the way.

    Numerical evaluation of a real closed form (through complex fourth roots) leaves an
    imaginary part of order 1e-86: parts below 1e-70 of the value are zero.
    """
    parts = [sp.N(p, 90) for p in sp.expand(exact).as_real_imag()]
    size = max(abs(p) for p in parts)
    parts = [p if abs(p) > sp.Float("1e-70") * size else sp.Integer(0) for p in parts]
    re, im = (sp.Float(p, 90)._to_mpmath(300) if p != 0 else mpmath.mpf(0) for p in parts)
    return mpmath.mp.make_mpc((re._mpf_, im._mpf_))


def _close(ar, value, exact, scale):
    """``value`` (of ``ar``) agrees with the exact SymPy number to the arithmetic's accuracy:
    within ``1e-12`` (double) or ``1e-40`` (mpmath, 160 bits) of ``scale``; a ball contains it."""
    ref = _exact_mpc(exact)
    if ar.name == "ball":
        import flint
        with Ball(400) as big:
            inner = big.number(ref)
        return flint.acb(value).contains(inner)
    tol = 1e-12 if ar.name == "double" else 1e-40
    with mpmath.workprec(300):
        return abs(ar.to_mpmath(value) - ref) <= tol * scale


@pytest.mark.parametrize("arith", ARITHMETICS)
@pytest.mark.parametrize("element", list(ELEMENTS))
def test_segment_matrix_equals_the_exact_one(element, arith):
    ar, seg = _arith(arith), ELEMENTS[element]
    for lam in _points():
        U = _kernel_matrix(ar, seg, lam)
        exact = seg.transfer_matrix(lam)
        scale = max(abs(complex(sp.N(v, 20))) for v in exact) + 1
        for i in range(4):
            for j in range(4):
                assert _close(ar, U[i, j], sp.N(exact[i, j], 80), scale), (element, lam, i, j)


@pytest.mark.parametrize("arith", ARITHMETICS)
@pytest.mark.parametrize("element", list(ELEMENTS))
def test_det_one_and_composition(element, arith):
    ar, seg = _arith(arith), ELEMENTS[element]
    lam = _points()[2]
    half = seg.with_length(seg.l / 3)
    rest = seg.with_length(2 * seg.l / 3)
    U, A, B = (_kernel_matrix(ar, s, lam) for s in (seg, half, rest))
    with ar:
        product = B @ A
        if ar.name == "ball":
            # both enclose U(l): they must overlap
            assert all(ar.flint.acb(product[i, j]).overlaps(ar.flint.acb(U[i, j]))
                       for i in range(4) for j in range(4))
        else:
            to = np.vectorize(lambda v: complex(ar.to_mpmath(v)))
            scale = np.max(np.abs(to(U)))
            assert np.max(np.abs(to(product) - to(U))) <= 1e-12 * scale
        det = complex(ar.to_mpmath(_det4(U)))
        # the rounding of a 4x4 determinant is relative to Hadamard's bound, the
        # product of the row norms
        rows = np.vectorize(lambda v: abs(complex(ar.to_mpmath(v))))(U)
        hadamard = float(np.prod(np.sqrt(np.sum(rows**2, axis=1))))
    assert abs(det - 1) < (1e-13 if ar.name == "double" else 1e-30) * hadamard


def _det4(M):
    """Determinant of a 4x4 object/complex array by cofactors (any arithmetic)."""
    import itertools
    total = 0
    for perm in itertools.permutations(range(4)):
        sign = 1
        for a in range(4):
            for b in range(a + 1, 4):
                if perm[a] > perm[b]:
                    sign = -sign
        term = M[0, perm[0]] * M[1, perm[1]] * M[2, perm[2]] * M[3, perm[3]]
        total = total + (term if sign > 0 else -term)
    return total


MODELS = {
    "two levels": Model((Beam("a", 1, 1, 1, left="free", right="free"),
                         Beam("b", 1, 1, 1, left="clamped", right="clamped")),
                        (Spring("a", "b", R(3, 10), 100), Spring("a", "b", R(7, 10), 100))),
    "dashpot and mass": Model((Beam("a", 2, 1, 1, left="pinned", right="pinned", kw=3),),
                              (Spring("a", "ground", R(1, 3), 50, 2),),
                              masses=(Mass("a", R(1, 2), R(1, 5), R(1, 100)),)),
    "theories": Model((Beam("t", 1, 1, 1, left="clamped", right="free", theory="timoshenko",
                            rhoI=R(1, 100), kGA=200, N=-1),
                       Beam("r", 1, 2, 1, left="pinned", right="pinned", theory="rayleigh",
                            rhoI=R(1, 50))),
                      (Spring("t", "r", R(1, 2), 40, kind="rotational"),)),
    "fork": Model((Beam("t", 1, 1, 1, left="clamped"), Beam("u", 1, 1, 1, x0=1),
                   Beam("v", 1, 1, R(1, 2), x0=1, right="pinned")),
                  bodies=(RigidBody("j", (Attachment("t", 1), Attachment("u", 1),
                                          Attachment("v", 1, True))),)),
    # beams joined by layers: a damped patch between two, three over one stretch
    "layers": Model((Beam("a", 1, 1, 1, left="clamped", right="free"),
                     Beam("b", 2, R(3, 2), 1, left="pinned", right="pinned", kw=4),
                     Beam("c", 1, 1, R(9, 10), x0=R(1, 10), left="free", right="clamped")),
                    (Spring("a", "c", R(4, 5), 6),),
                    layers=(Layer("a", "b", 30, R(1, 2), x1=R(3, 5)),
                            Layer("b", "c", 20, x0=R(3, 10)))),
}


@pytest.mark.parametrize("arith", ARITHMETICS)
@pytest.mark.parametrize("name", list(MODELS))
def test_stiffness_delta_is_the_transfer_determinant(name, arith):
    model, ar = MODELS[name].require_numeric(), _arith(arith)
    lam = R(-1, 5) + 13 * sp.I if model.damped else 13 * sp.I
    # det R by the transfer formulation (symtmm.compile: the product of the transfer
    # matrices along x, no stiffness matrix), at 90 digits
    with mpmath.workdps(90):
        exact = sp.sympify(Evaluator(model).delta_mp(_exact_mpc(lam)))
    plan = StiffnessPlan(model, 14.0**2)
    with ar:
        if ar.name == "double":
            fa = factor(plan, ar, np.array([complex(lam**2)]) if model.damped else
                        np.array([-169.0]), np.array([complex(lam)]) if model.damped else None)
            logabs, phase = fa.log_delta()
            value = np.exp(logabs[0] + 1j * phase[0])
            assert abs(value - complex(exact)) <= 1e-11 * abs(complex(exact))
            return
        lam2 = _exact_number(ar, lam**2)
        fa = factor(plan, ar, ar.array([lam2]), ar.array([_exact_number(ar, lam)])
                    if model.damped else None)
        value = fa.delta()[0]
    assert _close(ar, value, exact, abs(complex(exact)))


@pytest.mark.skipif(not ball_available(), reason="python-flint not installed")
@pytest.mark.parametrize("name", list(MODELS))
def test_jets_hold_the_balls_values(name):
    """The kernel on first-order jets (symtmm.numeric.jet) gives, as its values, balls that
    overlap those of the ball arithmetic at the same point, for every model whose
    elements have jets; the other theories are refused, not approximated."""
    from symtmm.numeric.jet import BallJet
    from symtmm.numeric.stiffness import assemble
    model = MODELS[name].require_numeric()
    plan = StiffnessPlan(model, 14.0**2)
    ball, jet = Ball(120), BallJet(120, order=1)
    lam = R(-1, 5) + 13 * sp.I
    with ball:
        z = _exact_number(ball, lam)
        K, d12 = assemble(plan, ball, ball.array([z * z]), ball.array([z]))
    if name == "theories":
        with pytest.raises(NotImplementedError), jet:
            v = jet.variable(z)
            assemble(plan, jet, np.array([v * v], dtype=object), np.array([v], dtype=object))
        return
    with jet:
        v = jet.variable(z)
        Kj, d12j = assemble(plan, jet, np.array([v * v], dtype=object),
                            np.array([v], dtype=object))
    for a, b in zip(K.reshape(-1), Kj.reshape(-1)):
        if isinstance(b, int):
            continue
        assert ball.flint.acb(a).overlaps(b.c[0])
    for a, b in zip(d12.reshape(-1), d12j.reshape(-1)):
        assert ball.flint.acb(a).overlaps(b.c[0])


@pytest.mark.parametrize("arith", ARITHMETICS)
def test_counts_agree_across_arithmetics(arith):
    # the count below omega in every arithmetic is that of the roots of det R
    model = MODELS["two levels"].require_numeric()
    plan = StiffnessPlan(model, 130.0**2)
    omegas = [5.0, 9.5, 25.0, 65.0, 125.0]
    # the roots of example 1 (K = 100, x1 = 0.3): 8.86, 10.55, 22.37, 29.57, 61.67, 67.96,
    # 120.90, 122.07 rad/s, independently in tests/test_benchmarks.py
    expected = [0, 1, 3, 5, 8]
    ar = _arith(arith)
    with ar:
        lam2 = ar.array([ar.exact(-sp.Rational(int(w * 10), 10) ** 2) for w in omegas]) \
            if ar.name != "double" else -np.array(omegas) ** 2
        counts = factor(plan, ar, lam2).counts()
    assert list(counts) == expected


def test_mp_precision_is_the_arithmetics_own():
    # the ambient mpmath precision has no effect on the kernel's results
    model = MODELS["two levels"].require_numeric()
    plan = StiffnessPlan(model, 30.0**2)
    values = []
    for ambient in (15, 200):
        with mpmath.workdps(ambient):
            ar = MP(200)
            values.append(factor(plan, ar, ar.array([ar.exact(-400)])).delta()[0])
    assert values[0] == values[1]
    assert LAM.name == "lam"


@pytest.mark.parametrize("arith", ARITHMETICS)
def test_every_arithmetic_provides_the_kernels_functions(arith):
    """The elementwise functions Arithmetic.FUNCTIONS names, on an array of the
    arithmetic: cos**2 + sin**2 = 1, cosh**2 - sinh**2 = 1, root4(x)**4 = x, and so on."""
    ar = _arith(arith)
    with ar:
        x = ar.array([ar.exact(sp.Rational(3, 7)), ar.exact(2)])
        for name in ar.FUNCTIONS:
            assert callable(getattr(ar, name)), name
        one = ar.cos(x) ** 2 + ar.sin(x) ** 2
        hyp = ar.cosh(x) ** 2 - ar.sinh(x) ** 2
        roots = ar.root4(x) ** 4
        squares = ar.sqrt(x) ** 2
        values = [one, hyp, ar.real(roots), squares]
    for v in values:
        got = ar.to_complex(v) if arith != "double" else np.asarray(v, dtype=complex)
        assert np.allclose(got, [1, 1] if v is one or v is hyp else [3 / 7, 2], rtol=1e-14)
    assert np.all(ar.upper(x) >= [3 / 7, 2])


@pytest.mark.parametrize("arith", [a for a in ARITHMETICS if a != "double"])
def test_points_are_squared_exactly(arith):
    """``lam**2`` of the kernel's points: exact in mpmath and balls, whatever the working
    bits (here 60, for points of 140 bits, real and complex, parts of different scales):
    rounded, a point near a zero would carry an error of the size of ``Delta`` itself."""
    ar = MP(60) if arith == "mp" else Ball(60)
    big = mpmath.mpf(2) ** 70 + 1
    points = [big, mpmath.mpc(big, 3), mpmath.mpc(-mpmath.mpf(2) ** -80 - 1, big)]
    with ar:
        got = ar.square(ar.array([ar.number(z) for z in points]))
    with mpmath.workprec(1000):
        want = [z * z for z in points]
        for g, w in zip(got, want):
            value = ar.to_mpmath(g) if arith == "ball" else g
            assert value == w
            if arith == "ball":
                parts = (g.real, g.imag) if hasattr(g, "imag") else (g,)
                assert all(p.rad() == 0 for p in parts)
