"""The kernel parts mode shapes stand on: sampling the transfer walk, pieces of segments,
linear algebra, quadrature, and precision kept local.

References, independent of the code under test:

* the exact transfer matrices of the elements (SymPy closed forms,
  :meth:`~symtmm.elements.beam.EulerBernoulliSegment.transfer_matrix`) and the jump
  of a spring from its definition, ``Q+ - Q- = -k Y``;
* SymPy's exact linear algebra on rational matrices (null space, Cholesky, solve);
* ``integral of x**k over [0, 1] = 1/(k + 1)`` and numpy's Gauss–Legendre rule;
* the pinned-pinned beam's mass-normalised first mode ``sqrt(2/(m L)) sin(pi x / L)``.
"""

from __future__ import annotations

import random
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp

from symtmm.elements import EulerBernoulliSegment
from symtmm.errors import ComputationError
from symtmm.model import Beam, Mass, Model, Spring
from symtmm.modes import evaluate_mode, shapes_at
from symtmm.numeric import linalg
from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
from symtmm.numeric.quadrature import gauss_legendre, gauss_legendre_nodes
from symtmm.numeric.transfer import Sampling, TransferPlan, sample
from symtmm.results import Eigenvalue

R = sp.Rational


# -- sampling the walk --------------------------------------------------------------------

SPRING_BEAM = Model((Beam("b", EI=2, m=3, L=1, left="pinned", right="free"),),
                    (Spring("b", "ground", x="1/2", k=40),))
LAM2 = -49                                   # lam = 7i, not an eigenvalue: any state will do
START = (0, 1, 0, 2)                         # [Y, Theta, M, Q] at the pinned end
POINTS = [(R(0), "-"), (R(3, 10), "+"), (R(1, 2), "-"), (R(1, 2), "+"), (R(17, 20), "+"),
          (R(1), "+")]


def spring_beam_reference(dps=40):
    """The states at POINTS from the exact segment matrices and the spring's jump."""
    seg = EulerBernoulliSegment(2, 3, 1)
    lam = sp.sqrt(sp.Integer(LAM2))

    def carry(z, length):
        if length == 0:
            return z
        return seg.with_length(length).transfer_matrix(lam) * z
    z0 = sp.Matrix(START)
    half = carry(z0, R(1, 2))
    after = half.copy()
    after[3] -= 40 * half[0]                 # Q+ = Q- - k Y
    out = []
    for x, side in POINTS:
        if x < R(1, 2) or (x == R(1, 2) and side == "-"):
            z = carry(z0, x)
        else:
            z = carry(after, x - R(1, 2))
        out.append([complex(sp.N(v, dps)).real for v in z])
    return np.array(out)


@pytest.mark.parametrize("walk, inner, tol", [
    ("double", "double", 1e-13), ("mp", "double", 1e-14), ("mp", "mp", 1e-30),
    pytest.param("ball", "ball", 1e-30, marks=pytest.mark.skipif(
        not ball_available(), reason="python-flint not installed"))])
def test_sampled_states_are_the_exact_ones(walk, inner, tol):
    plan = TransferPlan(SPRING_BEAM)
    arith = {"double": DOUBLE, "mp": MP(200), "ball": Ball(200)}
    ar, inner_ar = arith[walk], arith[inner]
    inner_ar = ar if walk == inner else inner_ar
    start = ar.array([ar.exact(v) for v in START], (1, 4, 1))
    _, states = sample(plan, ar, Sampling(plan, [POINTS]), lam2=ar.array([ar.exact(LAM2)]),
                       start=start, inner=inner_ar)
    ref = spring_beam_reference()
    got = states[0, :, :, 0]
    if inner == "ball":
        for value, exact in zip(got.reshape(-1), ref.reshape(-1)):
            # a ball that must hold the exact value: wider than the float reference only
            assert abs(float(value.mid()) - exact) <= float(value.rad()) + 1e-14 * (1 + abs(exact))
            assert float(value.rad()) < tol * (1 + abs(exact))
        return
    got = inner_ar.to_complex(got).real if got.dtype == object else got
    assert np.max(np.abs(got - ref) / (1 + np.abs(ref))) < tol


def test_samples_off_the_beam_are_refused():
    plan = TransferPlan(SPRING_BEAM)
    with pytest.raises(ValueError, match="not on beam 'b'"):
        Sampling(plan, [[(R(6, 5), "+")]])


PIECES = Model((Beam("e", EI=2, m=3, L=1, left="pinned", right="free"),
                Beam("t", EI=1, m=1, L="6/5", left="clamped", right="free", theory="timoshenko",
                     rhoI="1/50", kGA=60, N="-1/2", kw=5),
                Beam("w", EI=1, m=2, L="3/4", left="free", right="free", kw=30)),
               (Spring("e", "t", x="1/2", k=10),), masses=(Mass("w", "1/4", 1),))


@pytest.mark.parametrize("lam", [7 * sp.I, R(-3, 2) + 4 * sp.I], ids=["axis", "damped"])
def test_pieces_of_every_kind_are_the_exact_matrices(lam):
    plan = TransferPlan(PIECES)
    ar = MP(200)
    lam2 = ar.array([ar.number(complex(sp.N(lam**2, 60)))])
    lengths = [R(1, 7), R(1, 2)]
    for k, seg in enumerate(plan.kind_segments):
        U = plan.piece_matrices(ar, k, lam2, ar.array([ar.exact(v) for v in lengths]))[0]
        for q, length in enumerate(lengths):
            exact = seg.with_length(length).transfer_matrix(lam)
            ref = np.array(sp.N(exact, 30).tolist(), dtype=complex)
            got = ar.to_complex(U[q])
            assert np.max(np.abs(got - ref)) < 1e-13 * np.max(np.abs(ref)), (k, length)


@pytest.mark.parametrize("arith", ["double", "mp"])
def test_pieces_of_many_kinds_in_one_table_are_the_exact_matrices(arith):
    # cut_tables with a kind per length (the samples of a shape, one call per family)
    from symtmm.numeric.segments import cut_tables, family_matrices
    plan = TransferPlan(PIECES)
    ar = DOUBLE if arith == "double" else MP(200)
    lam = R(-3, 2) + 4 * sp.I
    lam2 = ar.array([ar.number(complex(sp.N(lam**2, 60)))])
    families: dict = {}
    for k, (family, _) in enumerate(plan.kinds):
        families.setdefault(family, []).append(k)
    assert sorted(families) == ["eb", "theory"] and len(families["eb"]) >= 2
    for family, ks in families.items():
        pieces = [(k, length) for length in (R(1, 7), R(1, 2), R(2, 3)) for k in ks[::-1]]
        with ar:
            table = cut_tables(ar, plan.kinds, plan.kind_tables(ar), [k for k, _ in pieces],
                               ar.array([ar.exact(v) for _, v in pieces]))
            U = family_matrices(ar, [(family, table)], lam2)[0][0]
        for q, (k, length) in enumerate(pieces):
            exact = plan.kind_segments[k].with_length(length).transfer_matrix(lam)
            ref = np.array(sp.N(exact, 30).tolist(), dtype=complex)
            got = ar.to_complex(U[q])
            assert np.max(np.abs(got - ref)) < 1e-12 * np.max(np.abs(ref)), (family, k, length)


# -- precision stays local ------------------------------------------------------------------

def pinned_pinned_eigenvalue(digits):
    with mpmath.workdps(digits + 20):
        return Eigenvalue(mpmath.mpc(0, mpmath.pi**2), 1, digits)


PP = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))


def test_ambient_precision_is_neither_read_nor_set():
    e = pinned_pinned_eigenvalue(35)
    with mpmath.workprec(12):                # 3.6 digits: a shape read from it would show
        (shape,) = shapes_at(PP, e, points=5, digits=35)
        z = evaluate_mode(PP, shape, "b", ["1/4"])
        assert mpmath.mp.prec == 12
    with mpmath.workdps(50):
        theta0 = shape.left_state[1]         # sqrt(2) pi: Y = sqrt(2) sin(pi x)
        assert abs(abs(theta0) / (mpmath.sqrt(2) * mpmath.pi) - 1) < mpmath.mpf(10) ** -33
    assert abs(abs(z[0, 0]) - 1) < 1e-14      # sqrt(2) sin(pi/4)
    assert abs(shape.beams["b"].Y[2] - np.sqrt(2)) < 1e-14


def test_explicit_digits_of_the_evaluator_ignore_the_ambient_precision():
    """Delta of a pinned-pinned beam at its first eigenvalue, pi**2 given to 70 digits,
    vanishes to about 60 digits whatever the ambient precision (it was 1e-16 when the
    point was squared in the ambient context)."""
    from symtmm.compile import Evaluator
    ev = Evaluator(PP)
    with mpmath.workdps(70):
        w = +mpmath.pi ** 2
        lam = mpmath.mpc(0, w)
    for value in (ev.delta_mp(lam, real=True, dps=60), ev.delta_omega_mp(w, dps=60),
                  ev.delta_mp(lam, dps=60), ev.delta_omega_mp(mpmath.nstr(w, 70), dps=60)):
        assert abs(value) < 1e-55
    assert abs(ev.delta_mp(mpmath.mpc(0, 10), real=True, dps=60)) > 1e-3


def test_threads_compute_shapes_independently():
    two = Model((Beam("a", EI=1, m=1, L=1, left="clamped", right="free"),
                 Beam("b", EI=2, m=1, L="3/4", left="pinned", right="pinned")),
                (Spring("a", "b", x="1/2", k=25),))
    jobs = [(PP, pinned_pinned_eigenvalue(d)) for d in (15, 30, 45)]
    from symtmm.solve import solve
    jobs += [(two, e) for e in solve(two, count=3, digits=20)]
    serial = [shapes_at(m, e, points=9)[0] for m, e in jobs]
    with ThreadPoolExecutor(max_workers=3) as pool:
        threaded = list(pool.map(lambda job: shapes_at(job[0], job[1], points=9)[0], jobs * 2))
    for a, b in zip(serial * 2, threaded):
        assert a.left_state == b.left_state
        for name in a.beams:
            assert np.array_equal(a.beams[name].Y, b.beams[name].Y)


# -- linear algebra --------------------------------------------------------------------------

def _mp_matrix(ar, M):
    return np.array([[ar.exact(v) for v in row] for row in M.tolist()], dtype=object)


def test_null_space_spans_the_exact_one():
    # rank 3 of 5: the exact null space from SymPy's rational elimination
    A = sp.Matrix([[1, 2, 0, -1, 3], [2, -1, 1, 0, 1], [0, 1, 1, 2, -2]])
    M = sp.Matrix.vstack(A, A[0, :] + 2 * A[1, :], A[2, :] - A[1, :])
    exact = sp.Matrix.hstack(*M.nullspace())
    P_exact = exact * (exact.T * exact).inv() * exact.T         # projector onto it
    ar = MP(200)
    V = linalg.null_space(ar, _mp_matrix(ar, M), 2)
    assert ar.to_complex(V.T @ V).real == pytest.approx(np.eye(2), abs=1e-50)
    P = ar.to_complex(V @ V.T).real
    assert np.max(np.abs(P - np.array(P_exact.tolist(), dtype=float))) < 1e-50
    with pytest.raises(ComputationError):
        linalg.null_space(ar, _mp_matrix(ar, M), 6)


def _householder(v):
    """``I - 2 v v^H / (v^H v)``: unitary (an mpmath matrix at the working precision)."""
    v = mpmath.matrix(v)
    return mpmath.eye(len(v)) - 2 * v * v.H / (v.H * v)[0]


def _arithmetics():
    yield "mp", MP(200)
    if ball_available():
        yield "ball", Ball(200)


@pytest.fixture(params=["flint", "no flint"])
def flint(request, monkeypatch):
    """Null spaces in Arb's matrices (python-flint installed), or kept from them."""
    from symtmm.numeric import arb_null
    if request.param == "no flint":
        monkeypatch.setattr(arb_null, "applies", lambda ar, R: False)
    elif not ball_available():
        pytest.skip("python-flint is not installed")
    return request.param


@pytest.mark.parametrize("kind", ["real", "complex"])
def test_null_space_of_a_large_matrix_and_its_separation(kind, flint):
    # R = H1 diag(s) H2, unitary Householder factors (at 80 digits, R rounded once to the
    # arithmetic's 60): its smallest singular values are s[-2:], their right singular
    # vectors the last columns of H2^H. 20 rows take Arb's matrices where python-flint is
    # installed (linalg.ARB_SOLVE_SIZE), mpmath's LU else.
    n = 20
    assert n >= linalg.ARB_SOLVE_SIZE
    im = 1j if kind == "complex" else 0
    with mpmath.workdps(80):
        H1 = _householder([(i % 5) - 2 + im * (i % 3) for i in range(n)])
        H2 = _householder([(i % 7) - 3 + im * ((i + 1) % 2) for i in range(n)])
        J = mpmath.eye(n)                           # swaps the last two rows
        J[n - 2, n - 2] = J[n - 1, n - 1] = 0
        J[n - 2, n - 1] = J[n - 1, n - 2] = 1
        for mult, small, left in ((1, ["1e-3", "1e-30"], H1), (2, ["1e-3", "1e-25", "1e-30"], H1),
                                  (1, ["1e-3", "1e-30"], H2.H * J)):
            # (the last: R = H2^H J S H2, whose R^-2 = H2^H S^-1 J S^-1 J H2 favours neither
            # of the last two directions, as a rod's [[0, 1], [t, 0]]: R^H R must be used)
            s = [1 + mpmath.mpf(i) / n for i in range(n - len(small))] + \
                [mpmath.mpf(v) for v in small]
            R = left * mpmath.diag(s) * H2
            E = np.array(H2.H[:, n - mult:].tolist(), dtype=complex)   # the wanted space
            for name, ar in _arithmetics():
                if name == "ball" and flint == "no flint":
                    continue
                with ar:
                    M = np.array([[ar.number(R[i, j]) for j in range(n)] for i in range(n)],
                                 dtype=object)
                    X, ratio = linalg.null_space(ar, M, mult, separation=True)
                Xc = np.array([[complex(ar.to_mpmath(v)) for v in row] for row in X])
                # the same space: the projectors agree, and X is orthonormal
                assert np.abs(Xc.conj().T @ Xc - np.eye(mult)).max() < 1e-14, name
                assert np.abs(Xc @ Xc.conj().T - E @ E.conj().T).max() < 1e-14, name
                # sigma_m / sigma_(m+1)
                want = float(s[-1] / s[-2]) if mult == 1 else float(s[-2] / s[-3])
                assert want / 2 < ratio < 2 * want, (name, mult, ratio)


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
@pytest.mark.parametrize("kind", ["real", "complex"])
def test_sparse_lu_solves_as_the_dense_solve(kind):
    # a sparse 60 x 60 matrix (its diagonal and two entries a row, rows shuffled): the
    # solves with A and A^H against Arb's dense solve of the same midpoints
    import flint

    from symtmm.numeric.sparse_lu import SparseLU
    rng = random.Random(3)
    n = 60
    with flint.ctx.workprec(200):
        def number():
            x = flint.arb(rng.randrange(1, 2**20)) / (1 << 20)
            return flint.acb(x, flint.arb(rng.randrange(1, 2**10)) / (1 << 10)) \
                if kind == "complex" else x
        perm = list(range(n))
        rng.shuffle(perm)
        nonzeros = {}
        for i in range(n):
            for j in (i, (i + 1) % n, (i + 7) % n):
                nonzeros[(perm[i], j)] = number()
        lu = SparseLU(n, nonzeros, 200)
        assert lu.ok
        mat = flint.acb_mat if kind == "complex" else flint.arb_mat
        A = mat(n, n)
        for (i, j), v in nonzeros.items():
            A[i, j] = v
        AH = A.conjugate().transpose() if kind == "complex" else A.transpose()
        b = [number() for _ in range(n)]
        B = mat(n, 1, b)
        for M, x in ((A, lu.solve(b)), (AH, lu.solve_adjoint(b))):
            exact = M.solve(B, algorithm="approx")
            worst = max(abs(x[i] - exact[i, 0]).mid() for i in range(n))
            assert worst < 1e-50 * max(abs(exact[i, 0]).mid() for i in range(n))


@pytest.mark.parametrize("kind", ["real", "complex"])
def test_null_space_of_a_large_sparse_matrix(kind, flint, monkeypatch):
    # R = A S, A sparse and well conditioned, S = diag(1, ..., 1, 1e-30): the right null
    # vector is e_(n-1) to about 1e-30, sigma_n / sigma_(n-1) about 1e-30 |A|; R of 48
    # rows and 3 nonzeros a row is factored sparsely (sparse_lu.SPARSE_SIZE), in Arb
    # numbers where python-flint is installed, in mpmath's otherwise
    from symtmm.numeric import sparse_lu
    used = []
    real_init = sparse_lu.SparseLU.__init__

    def spy(self, *args):
        used.append(True)
        real_init(self, *args)
    monkeypatch.setattr(sparse_lu.SparseLU, "__init__", spy)
    n = 48
    assert n >= sparse_lu.SPARSE_SIZE
    im = 1j if kind == "complex" else 0
    for ar in (Ball(200), MP(200)) if flint == "flint" else (MP(200),):
        with ar:
            zero = ar.number(im * 0) if im else ar.exact(0)
            R = np.array([[zero] * n for _ in range(n)], dtype=object)
            for i in range(n):
                R[i, i] = ar.number(4 + i % 3 + im)
                R[i, (i + 1) % n] = ar.number(1 - im)
                R[(i + 5) % n, i] = ar.number(-1)
            for i in range(n):
                R[i, n - 1] = R[i, n - 1] * ar.number("1e-30")
            used.clear()
            X, ratio = linalg.null_space(ar, R, 1, separation=True)
        assert used, "the sparse LU was not used"
        x = np.array([complex(ar.to_mpmath(v)) for v in X[:, 0]])
        assert abs(abs(x[-1]) - 1) < 1e-20 and np.abs(x[:-1]).max() < 1e-20
        assert 1e-32 < ratio < 1e-28


def test_a_sparse_matrix_with_an_empty_column_is_left_to_the_dense_lu():
    # the zero column is the null space (e_3); the sparse LU declines it, the dense one,
    # guarded, finds it
    from symtmm.numeric.sparse_lu import SparseLU
    n = 40
    ar = MP(200)
    with ar:
        R = np.array([[ar.exact(0)] * n for _ in range(n)], dtype=object)
        for i in range(n):
            if i != 3:
                R[i, i] = ar.exact(2)
                R[i, (i + 1) % n] = ar.exact(1) if (i + 1) % n != 3 else ar.exact(0)
        R[3, 0] = ar.exact(1)
        nonzeros = {(i, j): R[i, j] for i in range(n) for j in range(n) if R[i, j] != 0}
        assert not SparseLU(n, nonzeros, ar.prec).ok
        X = linalg.null_space(ar, R, 1)
    x = np.array([abs(complex(ar.to_mpmath(v))) for v in X[:, 0]])
    assert abs(x[3] - 1) < 1e-50 and np.delete(x, 3).max() < 1e-50


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_an_exact_zero_pivot_in_arb_falls_back_to_the_guarded_lu():
    # R = I with its last row replaced by e_0: exactly singular, its null vector e_(n-1);
    # Arb's approximate LU meets an exact zero pivot (NaN), and the mpmath LU with its
    # guard pivot serves instead, in balls and in mpmath numbers alike
    from symtmm.numeric import arb_null
    n = 20
    for ar in (Ball(200), MP(200)):
        with ar:
            R = np.array([[ar.exact(int(i == j and i < n - 1)) for j in range(n)]
                          for i in range(n)], dtype=object)
            R[n - 1, 0] = ar.exact(1)
            assert arb_null.null_space(ar, R, 1) is None
            X, ratio = linalg.null_space(ar, R, 1, separation=True)
        x = np.array([complex(ar.to_mpmath(v)) for v in X[:, 0]])
        assert abs(abs(x[-1]) - 1) < 1e-50 and np.abs(x[:-1]).max() < 1e-50
        assert ratio < 1e-50


def test_lu_solve_cholesky_and_triangular_inverse_are_exact_to_working_precision():
    A = sp.Matrix([[4, -2, 1], [3, 6, -4], [2, 1, 8]])
    B = sp.Matrix([[1, 0], [R(1, 3), 2], [-1, R(5, 7)]])
    ar = MP(200)
    X = linalg.lu_solve(ar, linalg.lu(ar, _mp_matrix(ar, A)), _mp_matrix(ar, B))
    assert np.max(np.abs(ar.to_complex(X) - np.array(A.solve(B).tolist(), dtype=float))) < 1e-15
    G = A.T * A                                                  # symmetric positive definite
    L = linalg.cholesky(ar, _mp_matrix(ar, G))
    L_exact = G.cholesky(hermitian=False)
    with mpmath.workdps(60):
        for got, want in zip(L.reshape(-1), L_exact):
            assert abs(ar.to_mpmath(got) - mpmath.mpf(sp.N(want, 70))) < mpmath.mpf(10) ** -55
    Linv = linalg.lower_inverse(ar, L)
    assert np.max(np.abs(ar.to_complex(Linv @ L) - np.eye(3))) < 1e-50
    with pytest.raises(ComputationError):
        linalg.cholesky(ar, _mp_matrix(ar, sp.Matrix([[1, 2], [2, 1]])))


def test_gram_schmidt_in_double_and_mpmath():
    V = np.array([[1.0, 1.0, 2.0], [0.0, 1.0, 1.0], [1.0, 0.0, 1.0], [0.0, 2.0, 2.0]])
    assert linalg.orthonormal(DOUBLE, V) is None                  # third = first + second
    Q = linalg.orthonormal(DOUBLE, V, complete=True)
    assert Q.T @ Q == pytest.approx(np.eye(3), abs=1e-15)
    # the first two span what numpy's QR spans
    Q2, _ = np.linalg.qr(V[:, :2])
    assert np.abs(Q[:, :2].T @ Q2) @ np.abs(Q[:, :2].T @ Q2).T == pytest.approx(np.eye(2))
    ar = MP(150)
    C = np.array([[ar.number(complex(1, 1)), ar.number(2)], [ar.number(1j), ar.number(-1)],
                  [ar.number(3), ar.number(complex(0, 2))]], dtype=object)
    Qc = linalg.orthonormal(ar, C)
    gram = np.conj(ar.to_complex(Qc)).T @ ar.to_complex(Qc)
    assert gram == pytest.approx(np.eye(2), abs=1e-15)


# -- quadrature -------------------------------------------------------------------------------

def test_gauss_legendre_integrates_polynomials_to_working_precision():
    ar = MP(330)
    n = gauss_legendre_nodes(80)
    nodes, weights = gauss_legendre(ar, n)
    for k in (0, 1, 7, 2 * n - 1):
        value = sum(weights * nodes**k)
        assert abs(value - ar.ctx.mpf(1) / (k + 1)) < ar.ctx.mpf(10) ** -90, k
    x, w = np.polynomial.legendre.leggauss(n)
    nodes_d, weights_d = gauss_legendre(DOUBLE, n)
    assert nodes_d == pytest.approx((x + 1) / 2, abs=1e-15)
    assert weights_d == pytest.approx(w / 2, abs=1e-15)


def test_energy_of_short_segments_closed_form_against_quadrature(monkeypatch):
    """The kinetic-energy Gram of an Euler–Bernoulli piece with ``|kappa| l**4`` far below
    1e-2 (a piece 1/100 long between two springs at omega = 10: 1e-6), where the closed
    form ``[F]/(4 kappa)`` loses about six digits: in a walk that holds them (60 digits
    for 20), the closed form is used and agrees with Gauss–Legendre quadrature of the
    same states (the second formulation) to the digits asked; in one that does not,
    quadrature is used."""
    from symtmm.modes import normalise

    model = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),),
                  (Spring("b", "ground", "1/2", 3), Spring("b", "ground", "51/100", 5)))
    tp = TransferPlan(model)
    short = [k for k, seg in enumerate(tp.kind_segments) if abs(float(seg.l) - 0.01) < 1e-12]
    assert short
    k = short[0]
    quadrature, calls = normalise._quadrature, []

    def counted(*args):
        calls.append(args)
        return quadrature(*args)
    monkeypatch.setattr(normalise, "_quadrature", counted)
    for digits, spare, closed in ((20, 60, True), (20, 25, False)):
        calls.clear()
        ar = MP.from_digits(spare)
        with ar:
            lam2 = ar.array([ar.number(-100)])
            Z0 = ar.array([ar.number(v) for v in (1, -2, "0.5", 3, "0.25", 1, -1, 2)], (4, 2))
            U = tp.piece_matrices(ar, k, lam2, ar.array([tp.kind_segments[k].l]))[0][0]
            Z1 = U @ Z0
            got = normalise.segment_gram(tp, ar, k, lam2, -100.0, Z0, Z1, digits)
            assert (not calls) == closed
            ref = quadrature(tp, ar, k, lam2, -100.0, Z0, ar.exact(1), None, digits)
            error = float(abs(got - ref).max() / abs(ref).max())
        assert error < 10.0 ** -digits, (spare, error)


@pytest.mark.parametrize("complex_", [False, True], ids=["real", "complex"])
def test_solver_in_arb_and_in_mpmath_agree_with_the_exact_solve(complex_, monkeypatch):
    """``linalg.solver`` on a 20 x 20 matrix of Gaussian rationals (Arb's LU where
    python-flint is installed, mpmath's without), for ``A`` and for its conjugate
    transpose (``adjoint``: Arb's on ``A^H``, mpmath's from ``A``'s own factors): the exact
    solutions from SymPy's elimination over QQ or QQ<I> to 55 digits every way; an
    exactly singular matrix (Arb: NaN) falls back to the guarded LU, whose solves stay
    finite."""
    import random
    import sys

    from sympy.polys.matrices import DomainMatrix
    rng = random.Random(5)
    n = 20
    unit = sp.I if complex_ else 0
    A = sp.Matrix(n, n, lambda i, j: R(rng.randint(-50, 50), rng.randint(1, 9))
                  + unit * R(rng.randint(-5, 5), 3) + (10 if i == j else 0))
    B = sp.Matrix(n, 2, lambda i, j: R(rng.randint(-9, 9), 2))
    domain = sp.QQ_I if complex_ else sp.QQ
    exact = DomainMatrix.from_Matrix(A).convert_to(domain).lu_solve(
        DomainMatrix.from_Matrix(B).convert_to(domain)).to_Matrix()
    ar = MP(200)

    def as_mp(M):
        if not complex_:
            return _mp_matrix(ar, M)
        return np.array([[ar.ctx.mpc(ar.exact(sp.re(v)), ar.exact(sp.im(v))) for v in row]
                         for row in M.tolist()], dtype=object)

    # the adjoint system A^H x = B, exactly: the conjugate transpose over the same domain
    exact_adjoint = DomainMatrix.from_Matrix(A.H).convert_to(domain).lu_solve(
        DomainMatrix.from_Matrix(B).convert_to(domain)).to_Matrix()
    for without_flint in (False, True):
        if without_flint:
            monkeypatch.setitem(sys.modules, "flint", None)
        for adjoint, reference in ((False, exact), (True, exact_adjoint)):
            X = linalg.solver(ar, as_mp(A), adjoint=adjoint)(as_mp(B))
            with mpmath.workdps(70):
                for got, want in zip(X.reshape(-1), reference):
                    want = mpmath.mpc(sp.N(sp.re(want), 70), sp.N(sp.im(want), 70))
                    assert abs(mpmath.mpc(got) - want) < mpmath.mpf(10) ** -55 * abs(want)
    monkeypatch.undo()
    # (i j + 1: rank 2, exact zero pivots in any elimination)
    singular = as_mp(sp.Matrix(n, n, lambda i, j: i * j + 1))
    X = linalg.solver(ar, singular)(as_mp(B))
    assert all(ar.ctx.isfinite(v) for v in X.reshape(-1))


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
@pytest.mark.parametrize("name, value", [
    ("rigid_body_on_beam", mpmath.mpc(0, 40.5)), ("kukla_rods", mpmath.mpc(0, 300.5)),
    ("paper_ex4_damped", mpmath.mpc(-70, 170)), ("portal_frame", mpmath.mpc(0, 12.5)),
    ("tuned_mass_damper", mpmath.mpc(-0.5, 20.5))])
def test_the_walk_in_arb_matrices_is_the_walk_in_object_arrays(name, value):
    """An unobserved walk of one point in balls keeps each beam's rows in one ``arb_mat``
    (``transfer._ArbBlocks``); an observer keeps the walk in numpy object
    arrays. Both are enclosures of the same columns: they overlap entry by entry, and
    their midpoints agree to the precision. (Rigid bodies and frames: rows beyond the
    beams'; rods; damped jumps in ``lam``.)"""
    from symtmm.modelfile import load
    from symtmm.numeric import transfer
    model = load(Path(__file__).resolve().parent.parent / "examples" / f"{name}.toml")
    tp = TransferPlan(model)
    ar = Ball(200)
    real = not model.damped
    with ar:
        lam, lam2 = transfer.point(ar, value, real)
        fast = transfer.propagate(tp, ar, lam, lam2)
        slow = transfer.propagate(tp, ar, lam, lam2, observe=lambda *_: None)
    assert fast.shape == slow.shape and tp.single_beams
    scale = max(abs(complex(v.mid())) for v in slow.reshape(-1))
    assert scale > 0
    for a, b in zip(fast.reshape(-1), slow.reshape(-1)):
        assert a.overlaps(b)
        assert abs(complex(a.mid()) - complex(b.mid())) <= 1e-50 * scale


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
@pytest.mark.parametrize("value", [mpmath.mpc(0, 61.5), mpmath.mpc(-0.5, 61.5)],
                         ids=["undamped", "damped"])
def test_boundary_walked_in_balls_is_the_mpmath_walk(value, monkeypatch):
    """``transfer.boundary_at`` walks an mpmath arithmetic's ``R`` in Arb balls (midpoints,
    the same rounding): the same matrix to the working precision, relative to its
    largest entry, as the walk in mpmath itself."""
    from symtmm.numeric import transfer
    real = value.real == 0
    model = Model((Beam("a", 1, 1, 1, left="clamped", right="free"),
                   Beam("b", 2, "3/2", 1, left="pinned", right="pinned")),
                  (Spring("a", "b", "3/10", 40),
                   Spring("a", "ground", "7/10", 15, c=0 if real else "1/5")),
                  masses=(Mass("b", "1/2", "1/4"),))
    tp = TransferPlan(model)
    ar = MP.from_digits(50)
    fast = transfer.boundary_at(tp, ar, value, real)
    monkeypatch.setattr(transfer, "ball_available", lambda: False)
    slow = transfer.boundary_at(tp, ar, value, real)
    scale = max(abs(ar.to_mpmath(v)) for v in slow.reshape(-1))
    worst = max(abs(ar.to_mpmath(a) - ar.to_mpmath(b)) for a, b in
                zip(fast.reshape(-1), slow.reshape(-1)))
    assert worst < mpmath.mpf(10) ** -45 * scale


@pytest.mark.parametrize("scale", ["1e-400", "1e-200", "1", "1e200", "1e400"])
def test_determinants_at_any_magnitude(scale):
    """linalg.det in mpmath and in balls chooses its pivots at any magnitude: entries
    beyond the doubles' range had all compared as inf (or 0, and the matrix had
    determinant 0), with numpy's overflow warning on stderr (a model with N = 7e10
    beside EI = 0.001). Reference: the exact rational determinant times scale**n."""
    from exact import exact_det

    rng = random.Random(5)
    rows = [[rng.randint(-9, 9) for _ in range(5)] for _ in range(5)]
    rows[0][0] = 0                                  # (a pivot from below at once)
    whole = exact_det(rows)
    assert whole.denominator == 1 and whole != 0
    with mpmath.workprec(300):
        reference = mpmath.mpf(whole.numerator) * mpmath.mpf(scale) ** 5
    ar = MP(120)
    s = ar.ctx.mpf(scale)
    with np.errstate(all="raise"):
        got = linalg.det(ar, np.array([[ar.number(v) * s for v in row] for row in rows],
                                      dtype=object))
    with mpmath.workprec(300):
        assert abs(mpmath.mpf(got) - reference) <= mpmath.mpf(2) ** -100 * abs(reference)
    if ball_available():
        import flint
        b = Ball(120)
        with b, np.errstate(all="raise"):
            sb = flint.arb(scale)
            got = linalg.det(b, np.array([[flint.arb(v) * sb for v in row] for row in rows],
                                         dtype=object))
        assert got.overlaps(flint.arb(whole.numerator) * sb ** 5)
        assert got.rad() < abs(got.mid()) * 2.0 ** -90


@pytest.mark.skipif(not ball_available(), reason="python-flint not installed")
def test_a_determinant_of_balls_that_hold_zero_is_never_an_exact_zero():
    """Balls that all hold 0 (and the NaN balls their quotients make): the determinant
    must hold every member's, never be the exact 0 that "every candidate pivot is an
    exact zero" gives (which a Rouche or sign proof would take as a value)."""
    import flint

    b = Ball(100)
    with b:
        z = flint.arb(0, 1e-3)
        got = linalg.det(b, np.array([[z, z], [z, z]], dtype=object))
        assert not got.is_zero()
        for member in (0, 1e-6, -1e-6):            # (det [[a, b], [c, d]] of members)
            assert got.contains(member)
        exact = linalg.det(b, np.array([[flint.arb(0), flint.arb(0)],
                                        [flint.arb(0), flint.arb(1)]], dtype=object))
        assert exact.is_zero()
