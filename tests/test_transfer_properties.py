"""Properties of the element and overall transfer matrices."""

import mpmath
import numpy as np
import pytest
import sympy as sp

from symtmm import Beam, Model, Spring
from symtmm.assembly import boundary_matrix, overall_transfer_matrix
from symtmm.compile import Evaluator
from symtmm.elements import Coupling, EulerBernoulliSegment, GroundSpring
from symtmm.elements.base import LAM
from symtmm.numeric.stiffness import segment_stiffness
from symtmm.roots.count import Counter

rng = np.random.default_rng(12345)
RANDOM_LAMS = [complex(a, b) for a, b in rng.uniform(-40, 40, size=(6, 2))]


def test_det_of_segment_is_one_symbolically():
    beta, l, EI = sp.symbols("beta l EI", positive=True)
    U = EulerBernoulliSegment(EI, 1, l).transfer_matrix_beta(beta)
    assert sp.simplify(U.det(method="berkowitz").rewrite(sp.exp)) == 1


@pytest.mark.parametrize("element", [Coupling("a", "b", 7, 2), GroundSpring("a", 3, 1)])
def test_det_of_point_elements_is_one(element):
    assert sp.simplify(element.transfer_matrix(LAM).det()) == 1


@pytest.mark.parametrize("lam", RANDOM_LAMS)
def test_segment_composition(lam):
    """U(a + b) = U(b) U(a): the kernel's segment matrices in double and in mpmath."""
    from symtmm.numeric.arith import DOUBLE, MP
    from symtmm.numeric.segments import segment_matrix
    R = sp.Rational
    a, b = EulerBernoulliSegment(2, 3, R(2, 5)), EulerBernoulliSegment(2, 3, R(7, 10))
    ab = EulerBernoulliSegment(2, 3, R(11, 10))
    lam2 = np.array([lam * lam])
    prod = segment_matrix(DOUBLE, b, lam2)[0] @ segment_matrix(DOUBLE, a, lam2)[0]
    direct = segment_matrix(DOUBLE, ab, lam2)[0]
    assert np.allclose(prod, direct, rtol=1e-12, atol=1e-12 * np.abs(prod).max())
    ar = MP.from_digits(40)
    l2 = ar.array([ar.number(mpmath.mpc(lam) ** 2)])
    prod = segment_matrix(ar, b, l2)[0].dot(segment_matrix(ar, a, l2)[0])
    direct = segment_matrix(ar, ab, l2)[0]
    err = max(abs(prod[i, j] - direct[i, j]) for i in range(4) for j in range(4))
    assert err < ar.ctx.mpf(10) ** -35 * max(abs(v) for v in direct.flat)


@pytest.mark.parametrize("lam", RANDOM_LAMS[:3] + [1e-7j, 0.3 + 0j])
def test_symbolic_equals_numeric_segment(lam):
    from symtmm.numeric.arith import DOUBLE
    from symtmm.numeric.segments import segment_matrix
    seg = EulerBernoulliSegment(sp.Rational(5, 2), sp.Rational(3, 4), sp.Rational(9, 10))
    exact = seg.transfer_matrix(LAM).subs(LAM, sp.nsimplify(lam)).evalf(40)
    exact = np.array(exact.tolist(), dtype=complex)
    num = segment_matrix(DOUBLE, seg, np.array([complex(lam * lam)]))[0]
    assert np.allclose(num, exact, rtol=1e-11, atol=1e-11 * np.abs(exact).max())


def _two_level_model(c="0.5"):
    return Model((Beam("u", "1.5", "0.8", 1, left="free", right="pinned"),
                  Beam("v", 1, 1, "1.2", x0="-0.1", left="clamped", right="sliding")),
                 (Spring("u", "v", "0.3", 40, c), Spring("v", "ground", "0.9", 7),
                  Spring("u", "v", "0.7", 12)))


def _float40(lam):
    return sp.Float(lam.real, 40) + sp.I * sp.Float(lam.imag, 40)


def _segment_at(lam40):
    # each closed-form element matrix evaluated to 40 digits before the product
    return lambda seg: seg.transfer_matrix(lam40).evalf(40)


@pytest.mark.parametrize("omega", [0.7, 13.0, 55.0])
def test_symbolic_R_equals_evaluator(omega):
    """The exact assembly on the frequency axis (real entries) against both evaluators.

    Off the axis SymPy would carry unexpanded complex products through the whole
    chain; complex lam is covered by the fully symbolic test below.
    """
    model = _two_level_model(c="0")
    lam40 = sp.I * sp.Float(omega, 40)
    exact = boundary_matrix(model, lam40, segment_matrix=_segment_at(lam40))
    exact = np.array(exact.evalf(30).tolist(), dtype=complex)
    num = Evaluator(model).R(np.array([1j * omega]))[0]
    assert np.allclose(num, exact, rtol=1e-10, atol=1e-10 * np.abs(exact).max())
    with mpmath.workdps(40):
        mp = Evaluator(model).R_mp(mpmath.mpc(0, omega))
        mp = np.array(mp.tolist(), dtype=complex)
    assert np.allclose(mp, exact, rtol=1e-13, atol=1e-13 * np.abs(exact).max())


def test_symbolic_R_with_symbol_equals_evaluator():
    """Fully symbolic R(lam) of a small model, substituted afterwards."""
    model = Model((Beam("u", 1, 2, 1, left="clamped", right="free"),
                   Beam("v", 1, 1, 1, left="pinned", right="pinned")),
                  (Spring("u", "v", "0.5", 10),))
    R = boundary_matrix(model, LAM)
    lam = 2.5 + 3j
    exact = np.array(R.subs(LAM, _float40(lam)).evalf(30).tolist(), dtype=complex)
    num = Evaluator(model).R(np.array([lam]))[0]
    assert np.allclose(num, exact, rtol=1e-11, atol=1e-11 * np.abs(exact).max())


def test_overall_transfer_matrix_has_unit_determinant():
    lam40 = sp.I * sp.Float(21, 40)
    T = overall_transfer_matrix(_two_level_model(c="0"), lam40, segment_matrix=_segment_at(lam40))
    value = T.evalf(40).det()
    assert abs(complex(value) - 1) < 1e-30


def test_dynamic_stiffness_is_symmetric_and_static_limit_is_classical():
    seg = EulerBernoulliSegment(2, 3, sp.Rational(1, 2))
    for w in (0.0, 3.0, 25.0):
        D = _kernel_stiffness(seg, -w * w)
        assert np.allclose(D, D.T, rtol=1e-12, atol=1e-12 * np.abs(D).max())
    D0 = _kernel_stiffness(seg, 0.0)
    l, EI = 0.5, 2.0
    classical = EI / l**3 * np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l**2, -6 * l, 2 * l**2],
                                      [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l**2, -6 * l, 4 * l**2]])
    assert np.allclose(D0, classical, rtol=1e-12)


def test_global_stiffness_determinant_vanishes_with_delta():
    """The two formulations share their roots: K is singular where Delta vanishes."""
    model = Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),))
    sm = Counter(model, 100.0)
    w = float(mpmath.findroot(lambda x: mpmath.cos(x) * mpmath.cosh(x) - 1, 4.73)) ** 2
    eig = np.linalg.eigvalsh(sm.matrix(w))
    assert np.min(np.abs(eig)) < 1e-10 * np.max(np.abs(eig))


def _kernel_stiffness(seg, lam2):
    """A segment's dynamic stiffness at ``lam**2`` from the kernel's transfer matrix."""
    from symtmm.numeric.arith import DOUBLE
    from symtmm.numeric.segments import segment_matrix
    U = segment_matrix(DOUBLE, seg, np.array([lam2], dtype=float))[0]
    return segment_stiffness(U)[0].real


@pytest.mark.parametrize("k", [10, 10**4, 10**7])
def test_double_delta_loses_the_digits_a_stiff_spring_costs_and_no_more(k):
    """The documented accuracy of Delta in double precision (the scans', the generated
    code's walk): about 13 digits, less about log10(k L / EI) beside a rotational spring
    far stiffer than its beams (a fuzzed model: 3e-9 relative at k = 1e7). Reference:
    the same walk at 60 digits."""
    model = Model((Beam("a", 1, 1, 1, left="clamped", right="free"),
                   Beam("b", 1, 1, 1, left="free", right="free")),
                  (Spring("a", "b", "7/10", k, kind="rotational"), Spring("a", "b", "3/10", 10)))
    ev = Evaluator(model)
    for w in (0.7, 3.3, 12.1, 40.4, 95.0):
        with mpmath.workdps(60):
            exact = complex(ev.delta_mp(mpmath.mpc(0, w)))
        error = abs(complex(ev.delta(1j * w)) - exact) / abs(exact)
        assert error <= 2e-15 * max(100, k)
