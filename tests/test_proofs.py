"""Every undamped eigenvalue says what backs its printed digits."""

import json

import pytest

from symtmm.cli import main
from symtmm.model import Beam, Model
from symtmm.numeric.arith import DOUBLE, ball_available
from symtmm.roots.undamped import PROOFS, solve_undamped

FREE_FREE = Model((Beam("b", 1, 1, 1, left="free", right="free"),))
PINNED = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_balls_prove_every_root_where_flint_is_installed():
    spec = solve_undamped(PINNED, count=4, digits=20)
    assert [e.proof for e in spec] == [PROOFS["ball"]] * 4
    assert "proved by count (ball arithmetic)" in spec.table()


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_balls_prove_a_cantilevers_sixty_modes():
    """High modes cut the beam into many pieces, along which the ball elimination widens
    its radii: counts undecided at the proof's bits are decided with more bits (modes 17,
    39 and 50 fell back to two precisions), and every digit agrees with the closed form
    ``1 + cosh b cos b = 0``, ``omega = b**2``."""
    import mpmath

    from symtmm.results import decimal_string
    cantilever = Model((Beam("b", 1, 1, 1, left="clamped", right="free"),))
    spec = solve_undamped(cantilever, count=60, digits=15)
    assert [e.proof for e in spec] == [PROOFS["ball"]] * 60
    with mpmath.workdps(60):
        # (cos b = -1/cosh b: b = (n - 1/2) pi -+ a tiny correction, found from there)
        roots = [mpmath.findroot(lambda b: mpmath.cos(b) + 1 / mpmath.cosh(b),
                                 (n - mpmath.mpf(1) / 2) * mpmath.pi) ** 2
                 for n in range(1, 61)]
        expected = [decimal_string(r, 15) for r in roots]
    assert [e.to_dict()["imag"] for e in spec] == expected


def test_two_precisions_without_balls():
    spec = solve_undamped(PINNED, count=3, digits=15, certified=False)
    assert [e.proof for e in spec] == [PROOFS["mp"]] * 3


def test_rigid_body_modes_are_exact():
    spec = solve_undamped(FREE_FREE, count=4, digits=15, certified=False)
    assert spec.eigenvalues[0].multiplicity == 2 and spec.eigenvalues[0].proof == PROOFS["exact"]
    assert spec.proofs() == {PROOFS["exact"]: [1], PROOFS["mp"]: [2, 3]}


def test_json_names_the_proof(tmp_path, capsys):
    path = tmp_path / "pp.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\n'
                    'right = "pinned"\n')
    assert main(["solve", str(path), "--count", "2", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert all(e["proof"] in PROOFS.values() for e in data["eigenvalues"])


def test_thirty_triple_roots_of_three_identical_beams():
    """Example 2: three identical uncoupled pinned-pinned beams, every root (n pi)**2 three
    times; close to a triple root, double-precision counts under some meshes flip sign
    (a tiny pivot before a huge one), and must be redone rather than trusted."""
    from pathlib import Path

    import mpmath

    from symtmm.modelfile import load
    from symtmm.results import decimal_string
    example = Path(__file__).resolve().parent.parent / "examples" / "paper_ex2_three_pp.toml"
    spec = solve_undamped(load(example), count=30, digits=15)
    assert [e.multiplicity for e in spec] == [3] * 10
    with mpmath.workdps(40):
        expected = [decimal_string((n * mpmath.pi) ** 2, 15) for n in range(1, 11)]
    assert [e.to_dict()["imag"] for e in spec] == expected


def _proof_batches(monkeypatch) -> list:
    """The sizes of the batches the proof arithmetic evaluates, as they come."""
    from symtmm.roots.count import Counter
    calls = []
    original = Counter.delta

    def counted(self, points, ar):
        calls.append(len(points))
        return original(self, points, ar)
    monkeypatch.setattr(Counter, "delta", counted)
    return calls


@pytest.mark.parametrize("certified", [True, False])
def test_proof_stage_takes_one_point_and_one_pair_per_root(monkeypatch, certified):
    """The proof arithmetic evaluates one point per root (a Newton step from the double
    estimate) and then one pair that proves it: 3 points per root at 15 digits, in two
    batches, where a first pair at 1e-11 took 4. Reference: the pinned-pinned
    beam's (n pi)**2."""
    if certified and not ball_available():
        pytest.skip("needs python-flint")
    import mpmath

    calls = _proof_batches(monkeypatch)
    spec = solve_undamped(PINNED, count=8, digits=15, certified=certified)
    for n, e in enumerate(spec, start=1):
        assert mpmath.almosteq(e.omega, (n * mpmath.pi) ** 2, rel_eps=1e-15)
    # (a pair that misses costs one more: allowed once, whatever the last bits of this
    # machine's sines; the old first pair at 1e-11 took 32 points)
    assert sum(calls) <= 3 * 8 + 2 and len(calls) <= 3, calls


@pytest.mark.parametrize("certified", [True, False])
def test_twelve_digits_take_one_point_beyond_the_newton_start(monkeypatch, certified):
    """At 12 digits the Newton start's point, a proved end of its root's bracket about
    1e-13 from the root, prints alike with the point as far again beyond the root: one
    evaluation there proves the root, not a pair (2 points per root, not 3, where no
    rounding boundary lies between). The digits and the proof stay those of the pair's:
    the pinned-pinned beam's (n pi)**2 to 12 digits, every root proved by its counts."""
    if certified and not ball_available():
        pytest.skip("needs python-flint")
    import mpmath

    calls = _proof_batches(monkeypatch)
    spec = solve_undamped(PINNED, count=8, digits=12, certified=certified)
    for n, e in enumerate(spec, start=1):
        exact = (n * mpmath.pi) ** 2
        assert e.bracket[0] <= exact <= e.bracket[1]          # the proved bracket holds it
        assert mpmath.almosteq(e.omega, exact, rel_eps=1e-12)
        assert e.proof == PROOFS["ball" if certified else "mp"]
    # one point per root and one more for most: a pair where a boundary intervenes
    assert sum(calls) < 3 * 8 and len(calls) <= 3, calls


@pytest.mark.parametrize("x1", ["0", "3/20", "1/2"])
def test_low_digits_agree_with_thirty_digit_proofs(examples_dir, x1):
    """The one-point proofs at 8 and 12 digits against the pairs of a 30-digit solve
    (another path through the proof stage, at another precision): every bracket holds
    the 30-digit one, and the printed digits are the 30-digit value's rounding. Example 1
    with its springs at the ends, between, and at mid-span (double roots there)."""
    import mpmath

    from symtmm.modelfile import load
    from symtmm.results import decimal_string
    from symtmm.solve import solve
    model = load(examples_dir / "paper_ex1_ff_cc.toml").with_parameters(x1=x1)
    ref = solve(model, count=10, digits=30)
    for digits in (8, 12):
        got = solve(model, count=10, digits=digits)
        assert [e.multiplicity for e in got] == [e.multiplicity for e in ref]
        for e, r in zip(got, ref):
            assert e.bracket[0] <= r.bracket[0] and r.bracket[1] <= e.bracket[1], (e, r)
            with mpmath.workdps(40):
                assert decimal_string(r.omega, digits) == decimal_string(e.omega, digits)


@pytest.mark.parametrize("x1", ["3/20", "3/10"])
def test_low_digit_proofs_hold_the_global_matrix_roots(examples_dir, x1):
    """The one-point proofs at 8 and 12 digits against an independent reference: example
    1's global coefficient matrix (no transfer matrices, no symtmm), its roots polished
    at 40 digits (benchmarks/references.py). Every bracket holds its root and the printed
    digits are its rounding."""
    from fractions import Fraction

    import mpmath

    from benchmarks.references import EX1_BEAMS, global_matrix_omegas
    from symtmm.modelfile import load
    from symtmm.results import decimal_string
    from symtmm.solve import solve
    springs = ((0, 1, x1, 100), (0, 1, str(1 - Fraction(x1)), 100))     # at x1 and L - x1
    ref = global_matrix_omegas(EX1_BEAMS, springs, 10, dps=40)
    model = load(examples_dir / "paper_ex1_ff_cc.toml").with_parameters(x1=x1)
    for digits in (8, 12):
        got = solve(model, count=10, digits=digits)
        assert [e.multiplicity for e in got] == [1] * 10
        with mpmath.workdps(40):
            for e, r in zip(got, ref):
                assert e.bracket[0] <= r <= e.bracket[1], (digits, e, r)
                assert decimal_string(r, digits) == decimal_string(e.omega, digits)


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_high_digits_take_few_proof_rounds(monkeypatch):
    """At high digits the secant steps are carried in the bookkeeping precision (values of
    the ambient mpmath context rounded them to 15 digits, a round lost each time) and
    corrected by a parabola through an earlier point: at 100 digits 5 batches of the
    proof arithmetic here, where 8 were taken (one more allowed: the start is the double
    estimate, whose last bits may differ on another CPU). Reference: the pinned-pinned
    beam's (n pi)**2."""
    import mpmath

    calls = _proof_batches(monkeypatch)
    spec = solve_undamped(PINNED, count=6, digits=100)
    with mpmath.workdps(110):
        for n, e in enumerate(spec, start=1):
            assert mpmath.almosteq(e.omega, (n * mpmath.pi) ** 2, rel_eps=mpmath.mpf(10)**-100)
    assert len(calls) <= 6, calls


def test_search_range_of_a_chain_costs_one_miss_at_most(monkeypatch):
    """Springs lift a chain's eigenvalues above Weyl's estimate: the first guess counts
    8, 6 and 1 of 10 on chains of 10, 20 and 50 levels. The next count is taken where
    Weyl's estimate has grown by the missing ones and one more (or first where the plan
    already built still serves), which holds the 10th eigenvalue and few beyond: at most
    one more plan, where a jump by ``(10 / k)**2`` (capped at 4) reached 16, 29 and 61
    eigenvalues and a plan with up to twice the pieces. The count at the top is checked
    against a finite-element upper bound on the 10th eigenvalue."""
    import numpy as np

    from benchmarks import sparse_fe
    from benchmarks.models import chain
    from symtmm.numeric import plan as plan_module
    from symtmm.roots import undamped

    counted, built = [], []
    original = undamped._Search.count_off
    original_plan = plan_module.StiffnessPlan

    def count_off(self, omega, toward, digits=None):
        counted.append(original(self, omega, toward, digits))
        return counted[-1]

    def plan(*args, **kwargs):
        built.append(args[1])
        return original_plan(*args, **kwargs)
    monkeypatch.setattr(undamped._Search, "count_off", count_off)
    monkeypatch.setattr(plan_module, "StiffnessPlan", plan)
    for levels in (10, 20, 50):
        model = chain(levels, 2)
        counted.clear()
        built.clear()
        plan_module.clear_plans()
        search = undamped._Search(model, 15, undamped._first_guess(model))
        top, k = search.top_for(10)
        assert len(built) <= 2 and len(counted) <= 3 and 10 <= k <= 14, (levels, counted)
        # the 10th eigenvalue lies under the top: below it lies the 10th of a conforming
        # finite-element model (cubic Hermite, consistent mass: each eigenvalue an upper
        # bound of the exact one, Rayleigh-Ritz)
        tenth = float(np.sqrt(sparse_fe.frequencies(sparse_fe.fe_input(model), 16, 10)[-1]))
        assert tenth < top, (levels, tenth, top)


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_fifty_level_chain_decides_its_ball_batches_at_once(monkeypatch):
    """Ball ``LDL^T`` without pivoting widens the radii along the band: at 15 digits
    (144 bits) a 50-level chain (450 freedoms) decided half of its first batch and the
    rest of the search's batches were redone with about 300 bits. Its plan now starts
    with a quarter of a bit per freedom more, and every ball batch is decided at once
    (46 bits to spare at the narrowest pivot here). Reference: none needed, the
    proofs' own counts decide (an undecided pivot is what is counted)."""
    from benchmarks.models import chain
    from symtmm.numeric import evaluator

    batches = []
    original = evaluator.factor

    def factor(plan, ar, lam2, lam=None, reverse=False):
        fa = original(plan, ar, lam2, lam, reverse)
        if ar.rigorous:
            batches.append((ar.prec, reverse, int((~fa.trusted).sum())))
        return fa
    monkeypatch.setattr(evaluator, "factor", factor)
    solve_undamped(chain(50, 2), count=10, digits=15)
    assert batches and all(not rev and bad == 0 for _, rev, bad in batches), batches
    assert len({prec for prec, _, _ in batches}) == 1, batches


def test_a_plan_serves_the_range_its_pieces_are_short_enough_for():
    """A chain's pieces are mostly the stretches between its springs: the plan cut for the
    first guess (38 rad/s on 10 levels) keeps every Euler–Bernoulli piece within
    ``|s| l <= 3`` up to its ``valid_radius`` (here about 51 rad/s), and serves there. Its
    counts agree with those of plans cut for each point (other pieces, the same
    eigenvalues below), and the search of 10 eigenvalues builds one plan, not two."""
    import math

    import numpy as np

    from benchmarks.models import chain
    from symtmm.numeric import plan as plan_module
    from symtmm.numeric.plan import NU_MAX, StiffnessPlan, clear_plans, design_range
    from symtmm.numeric.stiffness import factor

    model = chain(10, 2).require_numeric()
    small = StiffnessPlan(model, design_range(37.0) ** 2)
    top = math.sqrt(small.valid_radius)
    assert top > 1.2 * math.sqrt(small.radius)
    for _, seg, _, _ in small.mesh.segments:             # the rule, checked piece by piece
        EI, m, l, kw = seg.constants()
        assert ((m * small.valid_radius + kw) / EI) ** 0.25 * l <= NU_MAX * (1 + 1e-12)
    omegas = np.linspace(1.0, top, 40)
    own = [factor(StiffnessPlan(model, design_range(w) ** 2), DOUBLE, np.array([-w * w]))
           .counts()[0] for w in omegas]
    served = factor(small, DOUBLE, -omegas**2).counts()
    # (a point within rounding of an eigenvalue may stay undecided in either: not compared)
    both = [(s, o) for s, o in zip(served.tolist(), own) if s >= 0 and o >= 0]
    assert len(both) >= 35 and all(s == o for s, o in both), list(zip(served.tolist(), own))
    built = []
    original = plan_module.StiffnessPlan

    def counted(*args, **kwargs):
        built.append(args[1])
        return original(*args, **kwargs)
    clear_plans()
    try:
        plan_module.StiffnessPlan = counted
        solve_undamped(model, count=10, digits=12)
    finally:
        plan_module.StiffnessPlan = original
    assert len(built) == 1, built


@pytest.mark.parametrize("digits", [8, 15, 30])
def test_omega_ends_are_widened_by_the_scales_margin(digits):
    """The ends of ``Omega = sqrt(omega / scale)`` a bracket is tested with lie
    ``10**-(digits + 8)`` outside the exact values (the margin for the scale's rounding,
    which is carried to ``digits + 10`` digits): against mpmath at twice the bits, for a
    beam whose scale is irrational. (The margin once rounded away to 1 at 53 bits.)"""
    import mpmath

    from symtmm.numeric.arith import MP
    from symtmm.roots.undamped import _Search

    model = Model((Beam("b", 2, 3, 1, left="pinned", right="pinned"),))
    search = _Search(model, digits, 100.0)
    ctx = MP(search.book_prec).ctx
    omega = ctx.mpf(10) * ctx.pi
    with mpmath.workprec(2 * search.book_prec):
        exact = mpmath.sqrt(mpmath.mpf(omega) / mpmath.sqrt(mpmath.mpf(2) / 3))
        margin = mpmath.mpf(10) ** -(digits + 8)
        for side in (-1, 0, 1):
            got = search._big(omega, side)
            assert got.context is ctx
            want = exact * (1 + side * margin)
            assert abs(got - want) <= mpmath.mpf(10) ** -(digits + 10) * exact
        assert search._big(omega, -1) < exact * (1 - margin / 2)
        assert search._big(omega, 1) > exact * (1 + margin / 2)
