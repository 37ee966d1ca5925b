"""Multi-word balls (symtmm/numeric/_multiword.c, symtmm.numeric.multiword) against exact
references: rational arithmetic for the operations, mpmath's closed forms for the series,
closed-form natural frequencies for the counts, Arb at 400 bits for Delta.

The extension is an optional build; without it these tests are skipped and every ball
runs in Arb (as in the rest of the suite then).
"""

from __future__ import annotations

import dataclasses
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp
from exact import exact_det

from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load
from symtmm.numeric import multiword, stiffness
from symtmm.numeric.arith import DOUBLE, Ball
from symtmm.numeric.evaluator import Evaluator
from symtmm.numeric.plan import StiffnessPlan
from symtmm.results import decimal_string
from symtmm.roots.count import Counter
from symtmm.solve import solve

flint = pytest.importorskip("flint")
pytestmark = pytest.mark.skipif(multiword._multiword is None, reason="C extension not built")

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


MASK = (1 << 64) - 1


def _row(mid: Fraction, N: int, r: float = 0.0) -> list:
    """The ball of N words of an exact ``mid`` (a double-double for N = 2, else a dyadic of
    at most 64 N bits) and radius r."""
    if N == 2:
        hi = float(mid)
        lo = float(mid - Fraction(hi))
        assert Fraction(hi) + Fraction(lo) == mid
        return [int(x) for x in np.array([hi, lo, r]).view(np.uint64)]
    if mid == 0:
        return [0] * N + [0, 0, int(np.float64(r).view(np.uint64))]
    sign, a = int(mid < 0), abs(mid)
    num, den = a.numerator, a.denominator
    assert den & (den - 1) == 0
    bits = num.bit_length()
    e = bits - (den.bit_length() - 1)
    top = num << (64 * N - bits)
    words = [(top >> (64 * (N - 1 - k))) & MASK for k in range(N)]
    return words + [e & MASK, sign, int(np.float64(r).view(np.uint64))]


def _random_balls(rng, M, N, zero_radius=False):
    """(M, width) balls over 80 binary orders of magnitude: midpoints of random bits (64 N of
    them, or a double-double for N = 2; some with trailing zeros), radii from 0 to
    2**-(bits - 8) relative."""
    bits_of = 106 if N == 2 else 64 * N
    rows = []
    for _ in range(M):
        bits = int(rng.integers(1, bits_of + 1))
        a = int.from_bytes(rng.bytes(8 * 16), "little") >> (1024 - bits) | (1 << (bits - 1))
        if N == 2:              # (a double-double: two runs of 53 bits at most)
            hi_bits = min(bits, 53)
            a = (a >> (bits - hi_bits) << (bits - hi_bits)) + (a & ((1 << min(53, bits -
                                                                              hi_bits)) - 1))
        mid = Fraction(a) * Fraction(2) ** (int(rng.integers(-40, 40)) - bits)
        if rng.random() < 0.5:
            mid = -mid
        r = 0.0 if zero_radius else float(abs(mid)) * 2.0 ** -float(rng.integers(bits_of - 8,
                                                                                 bits_of + 20))
        rows.append(_row(mid, N, r))
    return np.array(rows, dtype=np.uint64)


@pytest.mark.parametrize("N", [2, 3, 5, 8, 12])
@pytest.mark.parametrize("op", [0, 1, 2, 3])
@pytest.mark.parametrize("zero_radius", [True, False])
def test_operations_enclose_the_exact_results(N, op, zero_radius):
    rng = np.random.default_rng(100 * N + 10 * op + zero_radius)
    X, Y = _random_balls(rng, 200, N, zero_radius), _random_balls(rng, 200, N, zero_radius)
    out = np.empty_like(X)
    multiword._multiword.ops(op, N, X, Y, out)
    apply = [lambda a, b: a + b, lambda a, b: a - b, lambda a, b: a * b,
             lambda a, b: a / b][op]
    for x, y, z in zip(X, Y, out):
        (mx, rx), (my, ry), (mid, r) = (multiword.decode(v) for v in (x, y, z))
        exact = apply(mx, my)
        # every value of the operands' balls (their ends and midpoints) lands in the result
        for sx in (-1, 0, 1):
            for sy in (-1, 0, 1):
                assert abs(apply(mx + sx * rx, my + sy * ry) - mid) <= r
        # and the result is tight: about 64 N bits (106 for a double-double) where the
        # operands are exact
        if zero_radius and exact != 0:
            assert r <= abs(exact) * Fraction(2) ** (-(100 if N == 2 else 64 * N - 4))


@pytest.mark.parametrize("N", [2, 3])
def test_cancellation_keeps_the_words_below(N):
    # 1 + 2**-100 - 1: exactly 2**-100
    x = np.array([_row(1 + Fraction(1, 2**100), N)], dtype=np.uint64)
    y = np.array([_row(Fraction(1), N)], dtype=np.uint64)
    out = np.empty_like(x)
    multiword._multiword.ops(1, N, x, y, out)
    mid, r = multiword.decode(out[0])
    # (exact; the double-double's bound is a priori: 2**-51 of the tails it rounded)
    assert mid == Fraction(1, 2**100) and r <= (Fraction(1, 2**140) if N == 2 else 0)


def test_a_division_by_a_ball_holding_zero_is_not_finite():
    for N in (2, 3):
        x = np.array([_row(Fraction(1), N)] * 2, dtype=np.uint64)
        y = np.array([_row(Fraction(1, 2**60), N, 1e-18), _row(Fraction(0), N)],
                     dtype=np.uint64)
        out = np.empty_like(x)
        multiword._multiword.ops(3, N, x, y, out)
        assert not np.isfinite(out[:, -1].view(np.float64)).any()


@pytest.mark.parametrize("N", [2, 3, 5, 8, 12])
def test_rationals_are_encoded_within_their_radius(N):
    rng = np.random.default_rng(N)
    values = [Fraction(1, 3), Fraction(-2, 7), Fraction(10) ** 30, Fraction(1, 10**40),
              Fraction(3, 2**70), Fraction(0), Fraction(-1)]
    values += [Fraction(int(rng.integers(-10**12, 10**12)), int(rng.integers(1, 10**12)))
               for _ in range(200)]
    bits = 106 if N == 2 else 64 * N
    for q in values:
        mid, r = multiword.decode(multiword.encode_rational(q, N))
        assert abs(mid - q) <= r
        assert r <= abs(q) * Fraction(2) ** (-bits + 2)


def _closed_c(x: mpmath.mpf) -> list:
    """c_0..c_3 of x by their closed forms (mpmath; independent of the series)."""
    if x == 0:
        return [mpmath.mpf(1), mpmath.mpf(1), mpmath.mpf(1) / 2, mpmath.mpf(1) / 6]
    if x > 0:
        nu = mpmath.root(x, 4)
        ch, sh, co, si = mpmath.cosh(nu), mpmath.sinh(nu), mpmath.cos(nu), mpmath.sin(nu)
        return [(ch + co) / 2, (sh + si) / (2 * nu), (ch - co) / (2 * nu**2),
                (sh - si) / (2 * nu**3)]
    s = mpmath.root(-x / 4, 4)
    ch, sh, co, si = mpmath.cosh(s), mpmath.sinh(s), mpmath.cos(s), mpmath.sin(s)
    return [ch * co, (ch * si + sh * co) / (2 * s), sh * si / (2 * s**2),
            (ch * si - sh * co) / (4 * s**3)]


@pytest.mark.parametrize("N", [2, 3, 5, 8, 12])
def test_series_enclose_the_closed_forms(N):
    coef, tails = multiword._series(N)
    xs = [0.0, 1e-3, -1e-3, 0.7, -0.7, 1.0, 3.3, -3.3, 25.0, -25.0, 80.9, -80.9, 81.0 / 7]
    X = np.array([_row(Fraction(x), N) for x in xs], dtype=np.uint64)
    out = np.empty((len(xs), 4, multiword.width(N)), dtype=np.uint64)
    multiword._multiword.krylov(N, X, coef, tails, multiword.TERMS, out)
    with mpmath.workdps(330):
        for x, c in zip(xs, out):
            for j, ref in enumerate(_closed_c(mpmath.mpf(x))):
                mid, r = multiword.decode(c[j])
                mid = mpmath.mpf(mid.numerator) / mid.denominator
                r = mpmath.mpf(r.numerator) / r.denominator
                assert abs(ref - mid) <= r
                bits = 106 if N == 2 else 64 * N
                if N > 10 and abs(x) > 20:
                    # (the series stops at TERMS: beyond 1/163! the words' exponents end,
                    # and the tail there, about 2**-690 at |x| = 81, stays in the radius)
                    bits = 600
                assert r <= mpmath.mpf(2) ** (-bits + 12) * max(1, abs(ref))


def _pinned(EI=2, m=3, L="3/2"):
    return Model((Beam("b", EI, m, L, left="pinned", right="pinned"),))


def _pinned_root(n, EI=2, m=3, L=1.5):
    return (n * mpmath.pi / L) ** 2 * mpmath.sqrt(mpmath.mpf(EI) / m)


@pytest.fixture
def arb_calls(monkeypatch):
    """The number of ball points factorised in Arb (not in multi-word balls)."""
    calls = []
    original = stiffness._ldl

    def spy(plan, ar, K, det12, reverse=False):
        if isinstance(ar, Ball):
            calls.append(K.shape[0])
        return original(plan, ar, K, det12, reverse)
    monkeypatch.setattr(stiffness, "_ldl", spy)
    return calls


def test_counts_about_closed_form_roots_in_multiword_balls(arb_calls):
    c = Counter(_pinned(), 300.0)
    with mpmath.workdps(60):
        points = [_pinned_root(n) * (1 + s * mpmath.mpf(10) ** -20)
                  for n in (1, 2, 3) for s in (-1, 1)]
    assert c.counts(points, Ball(150)).tolist() == [0, 1, 1, 2, 2, 3]
    assert sum(arb_calls) == 0


def test_points_within_the_balls_of_a_root_fall_back_to_arb(arb_calls, monkeypatch):
    # two words (about 100 bits) cannot tell a point 1e-40 from the root; Arb at the 200
    # bits asked can
    monkeypatch.setattr(multiword, "tiers", lambda prec, n: [2])
    c = Counter(_pinned(), 300.0)
    with mpmath.workdps(80):
        points = [_pinned_root(2) * (1 + s * mpmath.mpf(10) ** -40) for s in (-1, 1)]
        points.append(_pinned_root(2) * (1 + mpmath.mpf(10) ** -5))
    assert c.counts(points, Ball(200)).tolist() == [1, 2, 2]
    assert sum(arb_calls) == 2          # the two points 1e-40 from the root only


def _against_arb(monkeypatch, model, size, omegas, relative, bits=150, arb_bits=400):
    """Counts and Delta at ``omegas`` in balls of ``bits`` (words first) against Arb alone
    at ``arb_bits``: equal counts, Delta enclosed within ``relative`` of its value. The
    factorisation in words, returned."""
    c = Counter(model, size)
    omegas = [mpmath.mpf(w) for w in omegas]
    fast = c.factors(omegas, Ball(bits))
    with monkeypatch.context() as m:
        m.setattr(multiword, "ENABLED", False)
        slow = c.factors(omegas, Ball(arb_bits))
    assert fast.counts().tolist() == slow.counts().tolist()
    for a, b in zip(fast.delta(), slow.delta()):
        assert a.contains(b.mid()) and a.rad() < relative * abs(b.mid())
    # the midpoints read from the words (a proof's secant steps): the balls' own midpoints,
    # within their radius of Arb's value at more bits
    ctx = mpmath.MPContext()
    ctx.prec = bits + 64
    values, radii = fast.midpoints(ctx)
    for v, r, a, b in zip(values, radii, fast.delta(), slow.delta()):
        assert v == ctx.mpf(Ball(bits).to_mpmath(a))
        assert abs(v - ctx.mpf(Ball(arb_bits).to_mpmath(b))) <= r
    return fast


def test_delta_encloses_arb_at_400_bits(monkeypatch):
    # (wider than Arb's at 150 bits: about 100 bits, less what the band's radii grow)
    _against_arb(monkeypatch, load(EXAMPLES / "paper_ex1_ff_cc.toml"), 250.0,
                 (1.0, 8.86195501305, 33.3, 61.67282286792, 150.5, 199.9), 1e-3)


def test_delta_in_eight_words_encloses_arb_at_1000_bits(monkeypatch):
    """The precision of a triple root's zoom (131 digits, 470 bits): seven and eight
    words, every point decided in them, Delta within 1e-100 of Arb's at 1000 bits."""
    words = []
    decided = multiword._decided

    def spy(plan, ar, lam2, reverse, N, *rest, **options):
        out = decided(plan, ar, lam2, reverse, N, *rest, **options)
        words.append((N, None if out is None else int(out[0].sum())))
        return out
    monkeypatch.setattr(multiword, "_decided", spy)
    _against_arb(monkeypatch, load(EXAMPLES / "paper_ex3_three_pp_coupled.toml"), 200.0,
                 (1.0, 39.47841760435743, 150.5, 157.91367041742973), 1e-100, 470, 1000)
    assert words == [(7, 4)]


def test_a_tier_that_decides_nothing_is_not_tried_again_for_the_plan(monkeypatch):
    """A tier that decides none of a batch of three points or more (as two words about the
    roots of the 50-level chain at 15 digits: made so here) is skipped by the plan's later
    batches, which start at the next tier; the counts agree with Arb's alone."""
    words = []
    decided = multiword._decided

    def spy(plan, ar, lam2, reverse, N, *rest, **options):
        out = decided(plan, ar, lam2, reverse, N, *rest, **options)
        if N == 2 and out is not None:          # two words decide nothing here
            out = (np.zeros_like(out[0]),) + out[1:]
        words.append((N, len(lam2), None if out is None else int(out[0].sum())))
        return out
    monkeypatch.setattr(multiword, "_decided", spy)
    c = Counter(load(EXAMPLES / "paper_ex1_ff_cc.toml"), 250.0)
    ar = Ball(144)
    first = c.counts([mpmath.mpf(w) for w in (5.0, 20.0, 50.0, 150.0)], ar)
    small = c.counts([mpmath.mpf(w) for w in (9.5, 100.0)], ar)      # (too few to judge)
    again = c.counts([mpmath.mpf(w) for w in (30.0, 70.0, 121.0)], ar)
    assert words == [(2, 4, 0), (3, 4, 4), (3, 2, 2), (3, 3, 3)]
    with monkeypatch.context() as m:
        m.setattr(multiword, "ENABLED", False)
        arb = c.counts([mpmath.mpf(w) for w in (5.0, 20.0, 50.0, 150.0, 9.5, 100.0, 30.0,
                                                 70.0, 121.0)], ar)
    assert first.tolist() + small.tolist() + again.tolist() == arb.tolist()


def _general_beams():
    """Pinned-pinned beams of the general family with closed-form frequencies: tension,
    Rayleigh, Timoshenko (EI 2, m 3, L 3/2; k_n = n pi / L)."""
    def tension(k):            # EI k^4 + N k^2 = m w^2
        return mpmath.sqrt((2 * k**4 + 5 * k**2) / 3)

    def rayleigh(k):           # EI k^4 = w^2 (m + rhoI k^2)
        return mpmath.sqrt(2 * k**4 / (3 + mpmath.mpf("0.05") * k**2))

    def timoshenko(k):         # EI k^4 - w^2 (m + k^2 (rhoI + EI m / kGA)) + w^4 rhoI m / kGA
        rhoI, kGA = mpmath.mpf("0.05"), mpmath.mpf(40)
        A, B, C = rhoI * 3 / kGA, -(3 + k**2 * (rhoI + 2 * 3 / kGA)), 2 * k**4
        return mpmath.sqrt((-B - mpmath.sqrt(B * B - 4 * A * C)) / (2 * A))
    common = dict(left="pinned", right="pinned")
    return [(Beam("b", 2, 3, "3/2", N=5, **common), tension),
            (Beam("b", 2, 3, "3/2", theory="rayleigh", rhoI="1/20", **common), rayleigh),
            (Beam("b", 2, 3, "3/2", theory="timoshenko", rhoI="1/20", kGA=40, **common),
             timoshenko)]


@pytest.mark.parametrize("case", range(3))
def test_general_beams_count_about_closed_form_roots_in_words(case, arb_calls):
    beam, omega = _general_beams()[case]
    c = Counter(Model((beam,)), 200.0)
    with mpmath.workdps(60):
        roots = [omega(n * mpmath.pi / mpmath.mpf("1.5")) for n in (1, 2, 3)]
        points = [r * (1 + s * mpmath.mpf(10) ** -20) for r in roots for s in (-1, 1)]
    assert c.factors(points[:1], Ball(150)).plan.kinds[0][0] == "theory"
    assert c.counts(points, Ball(150)).tolist() == [0, 1, 1, 2, 2, 3]
    assert sum(arb_calls) == 0


def test_general_beams_delta_encloses_arb_at_400_bits(monkeypatch):
    beams = [b for b, _ in _general_beams()]
    model = Model((Beam("a", 1, 1, 1, left="clamped", right="free", N=-1),
                   beams[1], Beam("t", 3, 2, 1, left="free", right="clamped",
                                  theory="timoshenko", rhoI="1/30", kGA=60)),
                  (Spring("a", "b", "1/2", 40), Spring("b", "t", "1/3", 25)))
    fast = _against_arb(monkeypatch, model, 120.0, (0.7, 3.3, 11.0, 27.5, 60.1, 99.9), 1e-10)
    assert all(p is not None for p in fast.products)          # (decided in words)


def test_freedoms_the_other_way_round_give_the_same_counts_and_delta():
    model = load(EXAMPLES / "paper_ex1_ff_cc.toml")
    c = Counter(model, 250.0)
    omegas = [mpmath.mpf(w) for w in (1.0, 8.86195501305, 33.3, 120.9, 199.9)]
    plan = c.factors(omegas, Ball(150)).plan
    ar = Ball(150)
    with ar:
        lam2 = np.array([-(ar.number(w) ** 2) for w in omegas], dtype=object)
    ahead = multiword.factor(plan, ar, lam2)
    back = multiword.factor(plan, ar, lam2, reverse=True)
    assert ahead.counts().tolist() == back.counts().tolist()
    for a, b in zip(ahead.delta(), back.delta()):
        assert a.overlaps(b)


def _band(rows):
    """A symmetric tridiagonal matrix (diagonal, off-diagonal) as a band (1, n, 2) of
    exact balls of 2 words, padded as the elimination wants it."""
    diag, off = rows
    n = len(diag)
    K = np.zeros((1, n + 2, 2, 3), dtype=np.uint64)
    for k in range(n):
        K[0, k, 0] = _row(Fraction(diag[k]), 2)
        if k < n - 1:
            K[0, k, 1] = _row(Fraction(off[k]), 2)
    return np.ascontiguousarray(K)


def _fraction_det(diag, off):
    d_prev, d = Fraction(1), Fraction(diag[0])
    for k in range(1, len(diag)):
        d_prev, d = d, Fraction(diag[k]) * d - Fraction(off[k - 1]) ** 2 * d_prev
    return d


@pytest.mark.parametrize("diag, off", [
    ([2.0**-20, 1.0, 3.0, -2.0], [1.0, 0.5, 0.25]),        # a tiny pivot: det P < 0
    ([2.0**-20, 4.0, 3.0, 2.0], [2.0**-10, 0.5, 0.25]),    # det P > 0, tiny pivot first
    ([0.0, 0.0, 3.0, 1.0], [1.0, 2.0, 0.5]),               # an exact zero pivot
    ([-1.0, 2.0**-30, 5.0, 1.0], [0.5, 1.0, 0.75]),        # the block in the middle
])
def test_two_by_two_blocks_keep_the_inertia_and_the_determinant(diag, off):
    K = _band((diag, off))
    ok = np.ones(1, dtype=np.uint8)
    multiword._multiword.eliminate(2, K, 1, len(diag) + 2, 2, len(diag), ok)
    assert ok[0] == 1
    pivots = [multiword.decode(row) for row in K[0, :len(diag), 0]]
    dense = np.diag(diag) + np.diag(off, 1) + np.diag(off, -1)
    assert sum(mid < 0 for mid, _ in pivots) == (np.linalg.eigvalsh(dense) < 0).sum()
    product, radius = Fraction(1), Fraction(0)
    for mid, r in pivots:                # the product's ball from the pivots' balls
        radius = abs(product) * r + abs(mid) * radius + radius * r
        product *= mid
    assert abs(_fraction_det(diag, off) - product) <= radius


def test_an_undecided_block_stops_the_point():
    K = _band(([1.0, 1.0], [1.0]))         # singular: det P = 0 exactly
    ok = np.ones(1, dtype=np.uint8)
    multiword._multiword.eliminate(2, K, 1, 4, 2, 2, ok)
    assert ok[0] == 0


def test_solves_print_alike_with_and_without_multiword_balls(monkeypatch):
    model = Model((Beam("a", 1, 1, 1, left="clamped", right="free"),
                   Beam("b", 2, 1, 1, left="pinned", right="pinned")),
                  (Spring("a", "b", "1/3", 50),))
    fast = solve(model, count=6, digits=15)
    monkeypatch.setattr(multiword, "ENABLED", False)
    slow = solve(model, count=6, digits=15)
    # (the digits printed: str of an mpf prints at the ambient precision, another test's)
    assert [decimal_string(e.omega, 15) for e in fast] == \
        [decimal_string(e.omega, 15) for e in slow]
    assert [e.proof for e in fast] == [e.proof for e in slow]


def test_closed_form_frequencies_at_15_and_30_digits():
    for digits in (15, 30):
        found = solve(_pinned(), count=3, digits=digits)
        with mpmath.workdps(digits + 10):
            for n, e in enumerate(found, start=1):
                ref = _pinned_root(n)
                assert decimal_string(e.omega, digits) == decimal_string(ref, digits)


# -- plain doubles (one word, no radius): the double-precision batches' band -------------
def _mixed_model():
    beams = [b for b, _ in _general_beams()]
    return Model((Beam("a", 1, 1, 1, left="clamped", right="free", N=-1),
                  beams[1], Beam("t", 3, 2, 1, left="free", right="clamped",
                                 theory="timoshenko", rhoI="1/30", kGA=60)),
                 (Spring("a", "b", "1/2", 40), Spring("b", "t", "1/3", 25)))


@pytest.mark.parametrize("which", ["ex1", "mixed"])
def test_double_band_agrees_with_the_numpy_closed_forms(which):
    # the compiled kernel over doubles (the c_j by their series, general beams by theirs
    # in (t, d)) against numpy's band from the closed forms in cosh, cos of the roots
    model = load(EXAMPLES / "paper_ex1_ff_cc.toml") if which == "ex1" else _mixed_model()
    plan = Counter(model, 250.0).plan(250.0)
    lam2 = -np.linspace(0.0, 250.0, 101) ** 2
    K, det12, ok = multiword.double_band(plan, lam2)
    K0, det0 = stiffness.assemble(plan, DOUBLE, lam2)
    assert ok.all()
    scale = np.abs(K0).max(axis=(1, 2))[:, None, None]
    assert np.all(np.abs(K - K0) <= 1e-12 * scale)
    assert np.all(np.abs(det12 - det0) <= 1e-12 * np.abs(det0))


def test_double_counts_about_closed_form_roots_with_the_compiled_band(monkeypatch):
    beam, omega = _general_beams()[2]
    for model, root in ((_pinned(), _pinned_root),
                        (Model((beam,)), lambda n: omega(n * mpmath.pi / mpmath.mpf("1.5")))):
        c = Counter(model, 300.0)
        points = [float(root(n)) * (1 + s * 1e-8) for n in (1, 2, 3) for s in (-1, 1)]
        assert multiword.serves_double(c.plan(max(points)), -np.array(points) ** 2, None)
        fast = c.counts(points, DOUBLE)
        # (a point next to a sub-structure's eigenvalue may stay undecided in doubles: the
        # caller decides it otherwise; the numpy band leaves the same ones)
        assert [n for n, k in zip([0, 1, 1, 2, 2, 3], fast) if k >= 0] == \
            [k for k in fast if k >= 0]
        assert np.sum(fast >= 0) >= 4
        with monkeypatch.context() as m:
            m.setattr(multiword, "ENABLED", False)
            assert c.counts(points, DOUBLE).tolist() == fast.tolist()


def test_points_beyond_the_compiled_series_are_built_in_numpy(monkeypatch):
    # a plan cut for omega <= 10 asked at omega = 1e5: its pieces' |x| (about 3e8) leaves
    # the reach of the series' terms, and numpy's closed forms build those points' band
    plan = StiffnessPlan(load(EXAMPLES / "paper_ex1_ff_cc.toml").require_numeric(), 100.0)
    lam2 = -np.array([5.0, 1e5]) ** 2
    _, _, ok = multiword.double_band(plan, lam2)
    assert ok.tolist() == [True, False]
    fast = stiffness.factor(plan, DOUBLE, lam2)
    monkeypatch.setattr(multiword, "ENABLED", False)
    slow = stiffness.factor(plan, DOUBLE, lam2)
    assert fast.counts().tolist() == slow.counts().tolist()
    assert np.array_equal(fast.pivots[1], slow.pivots[1])
    assert np.allclose(fast.log_delta()[0], slow.log_delta()[0], rtol=1e-9)


# -- complex balls (pairs of real ones): the damped models --------------------------------
@pytest.mark.parametrize("N", [2, 3, 8])
@pytest.mark.parametrize("op", [0, 1, 2, 3])
def test_complex_operations_enclose_the_exact_results(N, op):
    # a complex ball is a rectangle: its real part's ball and its imaginary part's; every
    # point of the operands' rectangles (corners, edges' midpoints, centres) lands in it
    rng = np.random.default_rng(1000 + 10 * N + op)
    M = 60
    X = np.concatenate([_random_balls(rng, M, N), _random_balls(rng, M, N)], axis=1)
    Y = np.concatenate([_random_balls(rng, M, N), _random_balls(rng, M, N)], axis=1)
    out = np.empty_like(X)
    multiword._multiword.ops(op, multiword.COMPLEX + N, X, Y, out)
    W = multiword.width(N)

    def parts(row):
        (a, ra), (b, rb) = multiword.decode(row[:W]), multiword.decode(row[W:])
        return a, b, ra, rb

    def apply(x, y):                    # exact complex arithmetic on pairs of Fractions
        (a, b), (c, d) = x, y
        if op == 0:
            return a + c, b + d
        if op == 1:
            return a - c, b - d
        if op == 2:
            return a * c - b * d, a * d + b * c
        n = c * c + d * d
        return (a * c + b * d) / n, (b * c - a * d) / n
    for x, y, z in zip(X, Y, out):
        a, b, ra, rb = parts(x)
        c, d, rc, rd = parts(y)
        zr, zi, rzr, rzi = parts(z)
        for s in [(sa, sb, sc, sd) for sa in (-1, 0, 1) for sb in (-1, 1)
                  for sc in (-1, 0, 1) for sd in (-1, 1)]:
            re, im = apply((a + s[0] * ra, b + s[1] * rb), (c + s[2] * rc, d + s[3] * rd))
            assert abs(re - zr) <= rzr and abs(im - zi) <= rzi


def _damped_model():
    """Example 4's three beams (springs with dashpots), a Timoshenko beam in the middle."""
    model = load(EXAMPLES / "paper_ex4_damped.toml").require_numeric()
    b1, b2, b3 = model.beams
    return dataclasses.replace(model, beams=(b1, dataclasses.replace(
        b2, theory="timoshenko", rhoI=sp.Rational(1, 2000), kGA=sp.Integer(10**6)), b3))


@pytest.mark.parametrize("which", ["ex4", "timoshenko"])
def test_complex_double_band_agrees_with_numpy(which):
    model = load(EXAMPLES / "paper_ex4_damped.toml").require_numeric() \
        if which == "ex4" else _damped_model()
    plan = Evaluator(model, 1500.0).plan(1500.0)
    lam = np.array([complex(-3, 100), complex(-50, 700), complex(-1000, 1400), complex(-1, 1)])
    assert multiword.serves_double(plan, lam * lam, lam)
    K, det12, ok = multiword.double_band(plan, lam * lam, lam)
    K0, det0 = stiffness.assemble(plan, DOUBLE, lam * lam, lam)
    assert ok.all() and K.dtype == np.complex128
    scale = np.abs(K0).max(axis=(1, 2))[:, None, None]
    assert np.all(np.abs(K - K0) <= 1e-12 * scale)
    assert np.all(np.abs(det12 - det0) <= 1e-12 * np.abs(det0))


@pytest.mark.parametrize("which", ["ex4", "timoshenko"])
def test_complex_delta_encloses_arb_at_400_bits(which, monkeypatch, arb_calls):
    model = load(EXAMPLES / "paper_ex4_damped.toml").require_numeric() \
        if which == "ex4" else _damped_model()
    ev = Evaluator(model, 1500.0)
    fast_ar, slow_ar = Ball(150), Ball(400)
    with fast_ar:
        points = [fast_ar.flint.acb(x, y) for x, y in ((-3, 100), (-50, 700), (-1000, 1400))]
    fast = ev.factors(points, fast_ar)
    assert sum(arb_calls) == 0                       # (decided in complex words)
    assert all(p is not None for p in fast.products) and (fast.signs == 0).all()
    monkeypatch.setattr(multiword, "ENABLED", False)
    slow = ev.factors(points, slow_ar)
    for a, b in zip(fast.delta(), slow.delta()):
        assert a.contains(b.mid()) and a.rad() < 1e-10 * abs(b.mid())


@pytest.mark.parametrize("damped", [False, True])
def test_batches_in_parts_on_threads_give_the_same_bits(monkeypatch, damped):
    """A batch split over threads (every batch here: no work threshold, three threads)
    gives the balls, counts and double summaries of one call, bit for bit: every point is
    computed alone. Some points lie on roots (undecided) and one beyond the series' reach."""
    from symtmm.numeric import parallel

    name = "tuned_mass_damper.toml" if damped else "paper_ex3_three_pp_coupled.toml"
    model = load(EXAMPLES / name).require_numeric()
    ev = Evaluator(model, 160.0)
    omegas = [1.0, 39.47841760435743, 61.7, 88.8, 120.25, 150.5, 157.91367041742973]
    lam = [mpmath.mpc(-0.5 if damped else 0, w) for w in omegas]
    lam_d = np.array([complex(z) for z in lam] + [1e5j])

    def run():
        fa = ev.factors(lam, Ball(200))
        summary = stiffness.summary(ev.plan(160.0), lam_d * lam_d, lam_d if damped else None) \
            if damped else stiffness.summary(ev.plan(160.0), (lam_d * lam_d).real)
        return ([(v.mid().str(radius=False), v.rad()) if v is not None else None
                 for v in fa.delta()], fa.trusted.tolist(), summary)
    with monkeypatch.context() as m:
        m.setattr(parallel, "WORKERS", 1)
        whole = run()
    with monkeypatch.context() as m:
        m.setattr(parallel, "WORKERS", 3)
        m.setattr(parallel, "SPLIT_SECONDS", 0.0)
        calls = []
        original = parallel.run_ranges
        m.setattr(parallel, "run_ranges", lambda fn, count, work: calls.append(count)
                  or original(fn, count, work))
        m.setattr(multiword, "run_ranges", parallel.run_ranges)
        parts = run()
    assert calls and max(calls) >= 3                    # (split: three parts at least once)
    assert parts[0] == whole[0] and parts[1] == whole[1]
    for a, b in zip(parts[2], whole[2]):
        np.testing.assert_array_equal(a, b)


@pytest.mark.parametrize("N", [2, 3, 5, 8, 12])
def test_dyadic_points_encode_as_rationals_do(N):
    """Points (``man * 2**exp``, their squares' hundreds of bits among them) encoded by
    shifts and the doubles' conversions: the same words as the exact rational encoding,
    down to mantissas of one bit and up to the range's ends; and the words read back as
    an arb (times a power of two) hold exactly the value :func:`decode` gives."""
    import flint

    rng = np.random.default_rng(N)
    cases = [(1, 0), (-1, -5), (3, 900), (5, -1100), ((1 << 300) - 1, -310)]
    for _ in range(300):
        bits = int(rng.integers(1, 1200))
        man = int(rng.integers(1, 1 << 62)) << max(0, bits - 62) | int(rng.integers(0, 1 << 30))
        cases.append((man * int(rng.choice([-1, 1])), int(rng.integers(-1100, 900)) - bits))
    for man, exp in cases:
        ratio = (man << exp, 1) if exp >= 0 else (man, 1 << -exp)
        try:
            want = multiword._encode_ratio(*ratio, N)
        except OverflowError:
            with pytest.raises(OverflowError):
                multiword._encode_dyadic(man, exp, N)
            continue
        assert multiword._encode_dyadic(man, exp, N) == want, (man, exp)
        mid, r = multiword.decode(want)
        for shift in (0, -700, 650):
            ball = multiword._arb_of(np.array(want, dtype=np.uint64), flint, shift)
            scale = Fraction(2) ** shift
            exact_mid = mid * scale
            got_mid = Fraction(*[int(v) for v in ball.mid().man_exp()][:1]) * \
                Fraction(2) ** int(ball.mid().man_exp()[1])
            assert got_mid == exact_mid
            rm, re = (int(v) for v in ball.rad().mid().man_exp())
            assert Fraction(rm) * Fraction(2) ** re >= r * scale


def test_every_entry_point_refuses_buffers_that_do_not_fit():
    """Each call of the extension checks its buffers against each other and raises a
    ValueError naming itself (its buffers released: a second call succeeds)."""
    mw = multiword._multiword
    u64 = lambda *shape: np.zeros(shape, dtype=np.uint64)
    W = multiword.width(2)
    calls = [
        ("multi-word band", lambda: mw.eliminate(2, u64(1, 4, 1, W - 1), 1, 4, 1, 3,
                                                 np.zeros(1, dtype=np.uint8))),
        ("multi-word band", lambda: mw.eliminate_twisted(
            2, u64(1, 4, 1, W), 1, 4, 1, 3, np.zeros(2, dtype=np.int64),
            np.zeros(1, dtype=np.uint8))),
        ("peaks", lambda: multiword._band.peaks(np.zeros((1, 4, 1)), np.zeros(2, dtype=np.int64),
                                                1, 4, 1, 3)),
        ("power_product", lambda: mw.power_product(2, u64(2, 3, W), np.ones(2, dtype=np.int64),
                                                   u64(2, W + 1), np.zeros(2, dtype=np.uint8))),
        ("power_product", lambda: mw.power_product(2, u64(2, 2, W), -np.ones(2, dtype=np.int64),
                                                   u64(2, W + 1), np.zeros(2, dtype=np.uint8))),
        ("ops", lambda: mw.ops(4, 2, u64(3, W), u64(3, W), u64(3, W))),
        ("ops", lambda: mw.ops(0, 2, u64(3, W), u64(2, W), u64(3, W))),
        ("krylov", lambda: mw.krylov(2, u64(3, W), u64(4, 1, W), np.zeros((4, 2)), 1,
                                     u64(3, 4, W))),
    ]
    for name, call in calls:
        with pytest.raises(ValueError, match=name):
            call()
    x = np.array([_row(Fraction(3, 2), 2), _row(Fraction(5, 4), 2)], dtype=np.uint64)
    out = u64(2, W)
    mw.ops(2, 2, x, x, out)                 # (the same buffers, after the refusals)
    assert multiword.decode(out[0])[0] == Fraction(9, 4)


def test_midpoints_of_products_far_beyond_the_doubles():
    """A product of the words scaled far below and above the doubles' range: its midpoint
    read directly is its arb's, its radius a bound of the arb's (0 as a float where the
    arb's is below the doubles, a number of the context where it is above them: a float's
    inf left every value of a long shear-soft beam, 1e50110, unresolved; never a smaller
    number)."""
    plan = Counter(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 100.0).plan(
        100.0)
    ar = Ball(200)
    ctx = mpmath.MPContext()
    ctx.prec = 264
    n, kinds = plan.n, len(plan.multiplicity)
    for shift in (-5000, -1100, 0, 900, 4000):
        w = multiword.WordProduct((3 << 150) | 12345, -150, 2.0 ** -120, shift)
        fa = stiffness.Factors(plan, ar, np.full((1, n), None, dtype=object),
                               np.ones((1, n), dtype=np.int8), np.ones((1, n), dtype=bool),
                               np.full((1, kinds), None, dtype=object), None,
                               np.array([w], dtype=object))
        (v,), (r,) = fa.midpoints(ctx)
        ball = fa.delta()[0]
        assert v == ctx.mpf(ar.to_mpmath(ball))
        assert r >= ctx.mpf(ar.to_mpmath(ball.rad())) * (1 - 1e-8) and r > 0
        assert isinstance(r, float) or shift > 0


def test_the_other_order_is_tried_in_the_last_tier_only(monkeypatch):
    """A point two words cannot decide (1e-30 from a root of a pinned-pinned beam) goes on
    to three words as it is: the freedoms the other way round are tried in the last tier
    alone (a point no tier decides, 1e-70 from the root, is tried so there)."""
    calls = []
    eliminated = multiword._eliminated

    def spy(band, reverse, ok, N):
        calls.append((N, reverse))
        return eliminated(band, reverse, ok, N)
    monkeypatch.setattr(multiword, "_eliminated", spy)
    c = Counter(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 100.0)
    assert multiword.tiers(150, c.plan(100.0).n) == [2, 3]
    with mpmath.workdps(100):
        root = mpmath.pi ** 2
        near = [root * (1 + s * mpmath.mpf(10) ** -30) for s in (-1, 1)]
        nearer = [root * (1 + mpmath.mpf(10) ** -70)]
    assert c.counts(near, Ball(150)).tolist() == [0, 1]
    assert calls == [(2, False), (3, False)]
    calls.clear()
    c.factors(nearer, Ball(150))
    # (then more bits, as Evaluator._ball retries an undecided point)
    assert calls[:3] == [(2, False), (3, False), (3, True)]


def _fraction_band(n: int, w: int, rng) -> list:
    """A random symmetric band (rows of ``w`` entries, ``K[r][j] = K(r, r + j)``) of
    dyadic numbers, with a few tiny diagonal entries (sub-structures near singular)."""
    rows = []
    for r in range(n):
        row = [Fraction(int(rng.integers(-64, 65)), 16) if r + j < n else Fraction(0)
               for j in range(w)]
        if rng.random() < 0.2:
            row[0] = Fraction(int(rng.integers(1, 4)), 1 << 30)
        rows.append(row)
    return rows


def _dense(rows) -> list:
    n, w = len(rows), len(rows[0])
    A = [[Fraction(0)] * n for _ in range(n)]
    for r in range(n):
        for j in range(w):
            if r + j < n:
                A[r][r + j] = A[r + j][r] = rows[r][j]
    return A


@pytest.mark.parametrize("N", [2, 3])
def test_twisted_elimination_keeps_the_inertia_and_the_determinant(N):
    """Eliminated from both ends toward any freedom, a band keeps the inertia (against
    numpy's eigenvalues) and the determinant (exact, in rationals) of the matrix: the
    pivots' signs count its negative eigenvalues and their product's ball holds det K."""
    rng = np.random.default_rng(7)
    W = multiword.width(N)
    for _ in range(6):
        n, w = int(rng.integers(4, 9)), int(rng.integers(2, 5))
        rows = _fraction_band(n, w, rng)
        A = _dense(rows)
        det = exact_det(A)
        negative = int((np.linalg.eigvalsh(np.array(A, dtype=float)) < 0).sum())
        for t in range(n):
            band = np.zeros((1, n, w, W), dtype=np.uint64)
            for r in range(n):
                for j in range(w):
                    band[0, r, j] = _row(rows[r][j], N)
            ok = np.ones(1, dtype=np.uint8)
            Kb = multiword._twisted(band, np.array([t]), ok, N)
            assert ok[0] == 1
            pivots = [multiword.decode(row) for row in Kb[0, :n, 0]]
            assert sum(mid < 0 for mid, _ in pivots) == negative
            product, radius = Fraction(1), Fraction(0)
            for mid, r in pivots:
                radius = abs(product) * r + abs(mid) * radius + radius * r
                product *= mid
            assert abs(det - product) <= radius


def test_twisted_elimination_stops_at_a_zero_pivot():
    rows = [[Fraction(1), Fraction(1)], [Fraction(1), Fraction(0)]]   # singular
    band = np.array([[[_row(x, 2) for x in row] for row in rows]], dtype=np.uint64)
    for t in (0, 1):
        ok = np.ones(1, dtype=np.uint8)
        multiword._twisted(band, np.array([t]), ok, 2)
        assert ok[0] == 0


def test_peaks_are_the_largest_freedom_of_the_null_vector():
    """Shifted by one of its eigenvalues, a band is singular: the freedom where its
    double-precision L^-T e_(n-1) peaks is where numpy's eigenvector does."""
    rng = np.random.default_rng(3)
    for _ in range(20):
        n, w = int(rng.integers(6, 40)), int(rng.integers(2, 6))
        A = np.zeros((n, n))
        for j in range(w):
            v = rng.normal(size=n - j)
            A += np.diag(v, j) + (np.diag(v, -j) if j else 0)
        values, vectors = np.linalg.eigh(A)
        k = int(rng.integers(0, n))
        S = A - values[k] * np.eye(n)
        top = np.sort(np.abs(vectors[:, k]))[-2:]
        if top[1] < 1.01 * top[0]:
            continue                    # (two freedoms nearly alike: either may win)
        Kb = np.zeros((1, n + w, w))
        for j in range(w):
            Kb[0, :n - j, j] = np.diag(S, j)
        multiword._band.eliminate(Kb, 1, n + w, w, n, False)
        out = np.empty(1, dtype=np.int64)
        multiword._band.peaks(Kb, out, 1, n + w, w, n)
        assert out[0] == int(np.argmax(np.abs(vectors[:, k])))


def test_points_by_a_chain_root_are_decided_in_two_words_from_both_ends(monkeypatch):
    """About a root of a 10-level chain whose mode is small at both ends of the band,
    neither order's last pivot is decided in two words at 150 bits (three words are
    tried); eliminated from both ends toward the mode's largest freedom, two words decide
    it, and the counts are those of Arb alone at 400 bits."""
    from benchmarks.models import chain
    model = chain(10, 2)
    root = next(e for e in solve(model, count=8, digits=20)
                if abs(float(e.lam.imag) - 32.739010) < 1e-5).lam.imag
    near = [root * (1 + s * mpmath.mpf(10) ** -15) for s in (-1, 1)]
    ar = Ball(150)
    with ar:
        lam2 = np.array([-(ar.number(x) ** 2) for x in near], dtype=object)
    plan = Counter(model, 60.0).plan(40.0)
    words = []
    decided = multiword._decided

    def spy(plan, ar, lam2, reverse, N, *args, **kwargs):
        words.append(N)
        return decided(plan, ar, lam2, reverse, N, *args, **kwargs)
    monkeypatch.setattr(multiword, "_decided", spy)
    fa = multiword.factor(plan, ar, lam2)
    assert words == [2]
    with monkeypatch.context() as m:        # (from one end only: three words)
        m.setattr(multiword, "_splits", lambda plan, lam2: None)
        words.clear()
        plan.__dict__.pop("_multiword_failed", None)
        assert multiword.factor(plan, ar, lam2).counts().tolist() == fa.counts().tolist()
        assert words[:2] == [2, 3]
    monkeypatch.setattr(multiword, "ENABLED", False)
    exact = Counter(model, 60.0).counts(near, Ball(400))
    assert fa.counts().tolist() == exact.tolist()
    assert exact[1] == exact[0] + 1
