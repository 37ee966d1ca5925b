"""LU with partial pivoting within a band (symtmm/numeric/band_lu.py) and where it serves.

References: numpy's dense LAPACK determinant, solves and 1-norm condition number;
exact rational determinants (Fractions) that the balls must enclose; the classic
tridiagonal closed forms; Arb's dense preconditioned determinant of the same
stiffness. And the pivoted determinants of a plan too long to be made dense: in the
double search (the condition number by estimate) and in balls.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest
from exact import exact_det

from symtmm.model import Beam, Model, Spring
from symtmm.numeric import evaluator, multiword, stiffness
from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
from symtmm.numeric.band_lu import BandLU, condition_estimate
from symtmm.numeric.plan import StiffnessPlan

needs_flint = pytest.mark.skipif(not ball_available(), reason="python-flint not installed")


def _dense(upper, b):
    n = len(upper)
    A = np.zeros((n, n), dtype=np.asarray(upper).dtype)
    for r in range(n):
        for j in range(min(b + 1, n - r)):
            A[r, r + j] = A[r + j, r] = upper[r][j]
    return A


@pytest.mark.parametrize("complex_", [False, True])
def test_determinant_solves_and_condition_against_lapack(complex_):
    """Random bands, a third of them with a zero diagonal (no leading minor regular:
    every column needs its pivot from below)."""
    rng = np.random.default_rng(7)
    for trial in range(120):
        n, b = int(rng.integers(1, 40)), int(rng.integers(1, 6))
        upper = rng.standard_normal((n, b + 1))
        if complex_:
            upper = upper + 1j * rng.standard_normal((n, b + 1))
        if trial % 3 == 0:
            upper[:, 0] = 0
        A = _dense(upper, b)
        lu = BandLU(upper, b, keep=True)
        want = np.linalg.det(A)
        assert abs(lu.det - want) <= 1e-9 * max(1.0, abs(want))
        cond = np.linalg.cond(A, 1)
        if cond > 1e8:
            continue
        x = rng.standard_normal(n) + (1j * rng.standard_normal(n) if complex_ else 0)
        tol = 1e-12 * cond * np.abs(x).max()
        assert np.abs(A @ np.array(lu.solve(list(x))) - x).max() <= tol
        assert np.abs(A.conj().T @ np.array(lu.solve_adjoint(list(x))) - x).max() <= tol
        # Hager's estimate: a lower bound, within a small factor
        assert cond / 10 <= condition_estimate(lu, upper, b) <= cond * (1 + 1e-9)


def test_tridiagonal_closed_forms_in_mpmath():
    """det tridiag(-1, 2, -1) = n + 1; det tridiag(1, 0, 1) = (-1)**(n/2) for even n and 0
    for odd n (a zero at every diagonal: each column's pivot is the one below)."""
    ctx = mpmath.mp.clone()
    ctx.prec = 120
    for n in (1, 2, 5, 8, 13):
        laplace = [[ctx.mpf(2), ctx.mpf(-1)] for _ in range(n)]
        assert abs(BandLU(np.array(laplace, dtype=object), 1).det - (n + 1)) < 1e-30
        swap = [[ctx.mpf(0), ctx.mpf(1)] for _ in range(n)]
        assert BandLU(np.array(swap, dtype=object), 1).det == (0 if n % 2 else (-1) ** (n // 2))


def _exact_band_det(rows, b):
    n = len(rows)
    A = [[0] * n for _ in range(n)]
    for r in range(n):
        for j in range(min(b + 1, n - r)):
            A[r][r + j] = A[r + j][r] = rows[r][j]
    return exact_det(A)


@needs_flint
@pytest.mark.parametrize("complex_", [False, True])
def test_balls_enclose_the_exact_determinant(complex_):
    """Integer bands, widened by a relative radius, at few bits: every finite result holds
    the exact determinant, and most are finite; a result is never a false exact zero."""
    import flint

    rng = np.random.default_rng(11)
    finite = 0
    saved = flint.ctx.prec
    try:
        for trial in range(60):
            n, b = int(rng.integers(2, 30)), int(rng.integers(1, 5))
            rows = rng.integers(-9, 10, size=(n, b + 1)).tolist()
            if trial % 2:
                for r in rows:
                    r[0] = 0
            exact = _exact_band_det(rows, b)
            flint.ctx.prec = 30 + trial
            widen = 1 + flint.arb(0, 2.0 ** -(30 + trial))
            balls = [[flint.arb(v) * widen for v in r] for r in rows]
            if complex_:
                balls = [[flint.acb(v) for v in r] for r in balls]
            got = BandLU(np.array(balls, dtype=object), b).det
            if not got.is_finite():
                continue
            finite += 1
            assert got.contains(flint.arb(exact.numerator) / exact.denominator)
            assert exact == 0 or not (got == 0)  # noqa: SIM201 (balls: exactly 0)
    finally:
        flint.ctx.prec = saved
    assert finite >= 40


def _long_beam() -> Model:
    """A beam 40 long on springs, cut into many short pieces by its plan (124 freedoms
    at |lam| <= 400, half-bandwidth 3), a sub-span nearly held by a stiff spring."""
    beam = Beam("b", 1, 1, 40, left="pinned", right="pinned")
    springs = (Spring("b", "ground", "31/2", "1e5"), Spring("b", "ground", "27", 3))
    return Model((beam,), springs)


@needs_flint
def test_band_and_dense_arb_determinants_agree_on_a_long_stiffness(monkeypatch):
    """K of a long beam in balls at complex points (the numpy ball path, which keeps K at
    every point): Factors.pivoted_delta takes Arb's dense preconditioned determinant
    below DENSE_LIMIT (tight: the band's interval elimination widens the radii by the
    dependency of its updates), the banded one beyond it; they overlap."""
    plan = StiffnessPlan(_long_beam(), 400.0)
    assert stiffness.BANDED_DET * plan.band < plan.n <= stiffness.DENSE_LIMIT
    monkeypatch.setattr(multiword, "ENABLED", False)
    ar = Ball(200)
    with ar:
        lam = ar.array([ar.number(mpmath.mpc(-0.5, w)) for w in (3.0, 77.7, 301.0)])
        fa = stiffness.factor(plan, ar, lam * lam, lam)
        dense = fa.pivoted_delta(np.arange(3))
        monkeypatch.setattr(stiffness, "DENSE_LIMIT", plan.n - 1)
        banded = fa.pivoted_delta(np.arange(3))
    for x, y in zip(banded, dense):
        assert x.is_finite() and y.is_finite() and x.overlaps(y)
        assert y.rad() < 1e-40 * abs(y).mid()


def test_mpmath_determinants_within_the_band_agree_with_dense_ones(monkeypatch):
    """mpmath's numbers carry no radius: a long band goes within the band from
    BANDED_DET freedoms per half-bandwidth on, and agrees with the dense elimination."""
    from symtmm.numeric.arith import MP

    plan = StiffnessPlan(_long_beam(), 400.0)
    ar = MP(150)
    with ar:
        lam = ar.array([ar.ctx.mpc(-0.5, w) for w in (3.0, 77.7)])
        fa = stiffness.factor(plan, ar, lam * lam, lam)
        banded = fa.pivoted_delta(np.arange(2))
        monkeypatch.setattr(stiffness, "BANDED_DET", 10 ** 9)
        dense = fa.pivoted_delta(np.arange(2))
    for x, y in zip(banded, dense):
        assert abs(x - y) <= 1e-35 * abs(y)


def test_double_pivoted_values_in_the_band_agree_with_lapack(monkeypatch):
    """The double search's pivoted fallback: within the band (log|Delta|, phase, the
    condition number by estimate) as LAPACK gives them densely, near and away from a
    sub-span's eigenvalue."""
    plan = StiffnessPlan(_long_beam(), 400.0)
    lam = 1j * np.array([3.0, 77.7, 150.2, 301.0]) - 0.01
    fa = stiffness.factor(plan, DOUBLE, lam * lam, lam)
    dense = evaluator._pivoted_log_delta(fa)
    monkeypatch.setattr(stiffness, "DENSE_LIMIT", plan.n - 1)
    band = evaluator._pivoted_log_delta(fa)
    assert np.allclose(band[0], dense[0], rtol=0, atol=1e-9)
    assert np.allclose(np.exp(1j * band[1]), np.exp(1j * dense[1]), atol=1e-9)
    assert band[2].tolist() == dense[2].tolist()


@pytest.mark.parametrize("complex_", [False, True])
def test_dense_pivoted_condition_numbers_against_the_svd(complex_):
    """The dense fallback's condition number: LAPACK's 2-norm one (SVD) wherever it is
    below the limit asked; elsewhere a lower bound of it that reaches the limit, so that
    the same points are trusted as with the SVD everywhere. Random matrices of
    condition 1 to 1e16, singular ones among them."""
    rng = np.random.default_rng(11)
    B, n = 60, 24
    def unitary():
        X = rng.standard_normal((B, n, n))
        return np.linalg.qr(X + 1j * rng.standard_normal((B, n, n)) if complex_ else X)[0]
    s = 10.0 ** -np.linspace(0, rng.uniform(0, 16, (B, 1)), n, axis=-1).reshape(B, n)
    s[::15, -1] = 0.0                                   # (singular but for rounding)
    A = unitary() @ (s[:, :, None] * unitary())
    limit = 1e8
    sign, logdet, cond = evaluator._pivoted(A, limit)
    ref_sign, ref_logdet = np.linalg.slogdet(A)
    ref = np.linalg.cond(A)
    assert np.array_equal(sign, ref_sign) and np.array_equal(logdet, ref_logdet)
    below = ref < limit
    assert 0 < below.sum() < B                          # (both kinds drawn)
    assert np.allclose(cond[below], ref[below], rtol=1e-12)
    assert np.all(cond[~below] >= limit)
    # a lower bound (where the SVD's condition number is more than rounding's noise)
    meaningful = ~below & (ref < 1e14)
    assert meaningful.any() and np.all(cond[meaningful] <= ref[meaningful] * (1 + 1e-6))
    assert np.array_equal(cond < limit, below)


def test_a_plan_beyond_the_dense_limit_is_never_made_dense(monkeypatch):
    """Beyond DENSE_LIMIT freedoms neither the double fallback nor the ball determinants
    build K densely (a beam on a stiff foundation in 6561 freedoms spent minutes in one
    dense SVD, past the search's time budget)."""
    plan = StiffnessPlan(_long_beam(), 400.0)
    monkeypatch.setattr(stiffness, "DENSE_LIMIT", plan.n - 1)

    def refuse(*args):
        raise AssertionError("K made dense")
    monkeypatch.setattr(stiffness, "dense", refuse)
    lam = 1j * np.array([77.7, 301.0])
    fa = stiffness.factor(plan, DOUBLE, lam * lam, lam)
    logabs, _, trusted = evaluator._pivoted_log_delta(fa)
    assert np.isfinite(logabs).all() and trusted.all()


@needs_flint
def test_a_large_ball_batch_in_parts_is_the_batch_at_once(monkeypatch):
    """Evaluator.factors splits a ball batch larger than BALL_ENTRIES into parts, the
    budget checked before each (Arb's bands of thousands of points on a long plan had
    taken 3.9 GB in one piece): the same Delta and counts as the batch at once, also where
    the compiled balls decline and Arb's band rows are kept (the pivoted determinants).
    The parts are eliminated on the batch's plan (a part's own plan had other freedoms,
    and joining the parts raised a ValueError)."""
    from symtmm.numeric.evaluator import Evaluator

    model = _long_beam()
    ar = Ball(160)
    # (the parts' largest |lam| far apart, the last part a single point: each part is
    # eliminated on the batch's plan, not on one of its own range and size)
    lam = [mpmath.mpc(-0.3, w) for w in (301.0, 222.2, 150.2, 77.7, 20.5, 3.0, 0.5)]
    for compiled in (True, False):
        monkeypatch.setattr(multiword, "ENABLED", compiled)
        whole = Evaluator(model, 400.0).delta(lam, ar)
        plan = Evaluator(model, 400.0).plan(301.0, len(lam), ar)
        monkeypatch.setattr(evaluator, "BALL_ENTRIES", 5 * plan.n * plan.width)  # 5 a part
        # (a plan cut for the small range of the last part, built by another search: a
        # part of few points alone would take it, the others the batch's plan)
        Evaluator(model, 400.0).delta([mpmath.mpc(-0.3, w) for w in (1, 1.5, 2, 2.5, 3)], ar)
        parts = Evaluator(model, 400.0).delta(lam, ar)
        monkeypatch.setattr(evaluator, "BALL_ENTRIES", 1 << 18)
        for x, y in zip(whole[0], parts[0]):
            assert x.overlaps(y) and y.rad() < 1e-10 * abs(y).mid()
        assert list(whole[1]) == list(parts[1])


@needs_flint
def test_the_counters_ball_batch_in_parts_is_the_batch_at_once(monkeypatch):
    """The undamped counts in balls go in parts as well (a proof's hundred points on a
    shear-soft beam of 47,000 freedoms had grown past 24 GB, past a 60 s budget by
    minutes): the same counts and Delta as the batch at once."""
    from symtmm.roots.count import Counter

    model = _long_beam()
    ar = Ball(160)
    omegas = [mpmath.mpf(w) for w in (301.0, 222.2, 150.2, 77.7, 20.5, 3.0, 0.5)]
    ctx = MP(200).ctx
    whole = Counter(model, 400.0).midpoints(omegas, ar, ctx)
    plan = Counter(model, 400.0).plan(301.0, len(omegas), ar)
    monkeypatch.setattr(evaluator, "BALL_ENTRIES", 3 * plan.n * plan.width)  # 3 a part
    calls = []
    factor = evaluator.Evaluator._factor
    monkeypatch.setattr(evaluator.Evaluator, "_factor",
                        lambda self, *a, **k: calls.append(1) or factor(self, *a, **k))
    parts = Counter(model, 400.0).midpoints(omegas, ar, ctx)
    assert len(calls) == 3
    assert list(whole[1]) == list(parts[1]) and min(whole[1]) >= 0
    for x, y, rx, ry in zip(whole[0], parts[0], whole[2], parts[2]):
        assert abs(x - y) <= rx + ry
