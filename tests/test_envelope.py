"""The kernel's shortcuts against the long way round.

* The envelope elimination of balls and mpmath numbers (``stiffness.envelope_maps``)
  against a dense ``LDL^T`` of the same matrix in mpmath, on random sparse bands and
  on the plans of real models, in both orders of the freedoms.
* The Euler–Bernoulli stiffness from the ``c_j`` (``stiffness.eb_stiffness``) against
  the transfer-matrix route (``U`` of the segment, ``U12`` inverted), at 60 digits.
* Plans shared between searches (``plan.plan_for``) and forgotten (``clear_plans``).
* The bracket refinement's step count on a nearly linear function.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from benchmarks.models import chain
from symtmm.elements import EulerBernoulliSegment
from symtmm.numeric import plan as plan_module
from symtmm.numeric import stiffness
from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
from symtmm.numeric.segments import family_matrices, kind, kind_tables
from symtmm.roots.bracket import shrink


class _Pattern:
    """The attributes of a plan the envelope reads: order, band width and entries."""

    def __init__(self, n: int, w: int, mask):
        self.n, self.width = n, w
        self._triples = [(r * w + j, None, None) for r, j in zip(*np.nonzero(mask))]


def _sparse_band(rng, n: int, w: int):
    """A symmetric band with a random pattern (the diagonal always there), diagonally
    dominant and indefinite: no breakdown without pivoting."""
    mask = rng.random((n, w)) < 0.35
    mask[:, 0] = True
    for j in range(1, w):
        mask[n - j:, j] = False
    K = np.where(mask, rng.normal(size=(n, w)), 0.0)
    K[:, 0] = np.where(rng.random(n) < 0.3, -1, 1) * 3 * w
    return K, mask


def _dense_pivots(K, reverse: bool):
    """The pivots of ``LDL^T`` of the dense symmetric matrix (mpmath, 50 digits)."""
    n, w = K.shape
    with mpmath.workdps(50):
        A = mpmath.zeros(n, n)
        for r in range(n):
            for j in range(min(w, n - r)):
                A[r, r + j] = A[r + j, r] = mpmath.mpf(float(K[r, j]))
        if reverse:
            A = mpmath.matrix([[A[n - 1 - i, n - 1 - j] for j in range(n)] for i in range(n)])
        pivots = []
        for k in range(n):
            d = A[k, k]
            pivots.append(d)
            for i in range(k + 1, n):
                f = A[i, k] / d
                for j in range(k + 1, n):
                    A[i, j] -= f * A[k, j]
        return [float(p) for p in pivots]


def _arithmetics():
    out = [MP(120)]
    if ball_available():
        out.append(Ball(120))
    return out


@pytest.mark.parametrize("seed", range(6))
@pytest.mark.parametrize("reverse", [False, True])
def test_envelope_elimination_gives_the_dense_pivots(seed, reverse):
    rng = np.random.default_rng(seed)
    n, w = 23, 6
    K, mask = _sparse_band(rng, n, w)
    pattern = _Pattern(n, w, mask)
    expected = _dense_pivots(K, reverse)
    band = K[None] if not reverse else stiffness.reversed_band(K[None])
    for ar in _arithmetics():
        with ar:
            Kb = ar.array([ar.number(float(v)) for v in band.reshape(-1)], band.shape)
            f = stiffness._ldl(pattern, ar, Kb, ar.zeros((1, 0)), reverse)
            got = [float(ar.to_mpmath(p)) for p in f.pivots[0]]
        np.testing.assert_allclose(got, expected, rtol=1e-12, atol=0)


def test_envelope_skips_pairs_on_a_chain():
    """A chain's band is mostly zeros the elimination never fills: the envelope updates
    far fewer pairs than the band holds (the point of it), and only pairs inside it."""
    p = plan_module.StiffnessPlan(chain(10, 2).require_numeric(), 300.0**2)
    maps = stiffness.envelope_maps(p)
    pairs = sum(rows.size for _, rows, _, _, _ in maps)
    band = sum(len(stiffness._update_maps(min(p.width, p.n - k))[0]) for k in range(p.n))
    assert pairs < 0.5 * band
    for k, (J, rows, cols, _, _) in enumerate(maps):
        assert np.all(J >= 1) and np.all(J < p.width) and np.all(k + J < p.n)
        assert np.all(rows + cols < p.width)


def _examples():
    from pathlib import Path

    from symtmm import api
    root = Path(__file__).resolve().parent.parent / "examples"
    return [api.load(root / name).require_numeric() for name in (
        "double_beam_layer.toml", "portal_frame.toml", "paper_ex4_damped.toml",
        "rigid_body_on_beam.toml")]


@pytest.mark.parametrize("reverse", [False, True])
def test_entries_outside_the_envelope_stay_zero_in_the_full_band_elimination(reverse):
    """The envelope's claim checked by the long way round: a full-band elimination (written
    here, every pair updated) in mpmath never makes an entry outside the envelope nonzero
    before its pivot, on real plans: a chain, beams joined by a layer, a frame, a damped
    model at a complex point, a rigid body."""
    models = [chain(5, 2).require_numeric()] + _examples()
    ar = MP(80)
    for model in models:
        p = plan_module.StiffnessPlan(model, 150.0**2)
        maps = stiffness.envelope_maps(p, reverse)
        with ar:
            lam = ar.array([ar.number(mpmath.mpc(-0.5, 37.0))])
            K, _ = stiffness.assemble(p, ar, lam * lam, lam if p.damped else None)
            if reverse:
                K = stiffness.reversed_band(K)
            n, w = p.n, p.width
            Kb = [[K[0, r, j] for j in range(w)] for r in range(n)] + [[0] * w for _ in range(w)]
            for k in range(n):
                inside = set(maps[k][0].tolist())
                for j in range(1, w):
                    if j not in inside:
                        assert Kb[k][j] == 0, (model.title, k, j)
                piv = Kb[k][0]
                for i in range(1, w):
                    for j in range(i, w):
                        Kb[k + i][j - i] = Kb[k + i][j - i] - Kb[k][i] * Kb[k][j] / piv


@pytest.mark.parametrize("reverse", [False, True])
def test_object_arithmetics_agree_with_doubles_on_a_chain(reverse, monkeypatch):
    """The envelope elimination (mpmath, balls) against the full-band double loop on a
    real plan: the same pivots to double precision. (Balls of words keep no pivots, only
    the count and Delta: switched off, as without the compiled kernel.)"""
    from symtmm.numeric import multiword
    monkeypatch.setattr(multiword, "ENABLED", False)
    p = plan_module.StiffnessPlan(chain(5, 2).require_numeric(), 200.0**2)
    omegas = [3.0, 41.0, 170.0]
    lam2 = -np.array(omegas) ** 2
    doubles = stiffness.factor(p, DOUBLE, lam2, reverse=reverse).pivots.real
    for ar in _arithmetics():
        with ar:
            exact = ar.array([ar.number(mpmath.mpf(-w * w)) for w in omegas])
            f = stiffness.factor(p, ar, exact, reverse=reverse)
            got = np.array([[float(ar.to_mpmath(v).real) for v in row] for row in f.pivots])
        np.testing.assert_allclose(got, doubles, rtol=1e-9, atol=1e-12)


@pytest.mark.parametrize("EI, m, l, kw", [(1, 1, 1, 0), (2, 3, "1/2", 0), ("7/3", 1, 2, 40),
                                          (1, 5, "3/2", 2000)])
def test_eb_stiffness_from_c_functions_is_the_transfer_route(EI, m, l, kw):
    """Real and complex lam, below and above |x| = 1, a foundation stiffer than the
    inertia (x <= -1): the closed products of the c_j equal D from U and U12^-1."""
    seg = EulerBernoulliSegment(EI, m, l, kw)
    ar = MP(200)
    points = [mpmath.mpc(0, 0.3), mpmath.mpc(0, 4), mpmath.mpc(-1.5, 9), mpmath.mpc(0, 30)]
    with ar:
        [(family, consts)] = kind_tables(ar, [kind(seg)])
        lam = ar.array([ar.number(z) for z in points])
        lam2 = lam * lam
        D, det = stiffness.eb_stiffness(ar, consts, lam2)
        [U] = family_matrices(ar, [(family, consts)], lam2)
        D0, det0 = stiffness.segment_stiffness(U)
        for a, b in zip(np.ravel(D), np.ravel(D0)):
            assert abs(a - b) <= mpmath.mpf(10) ** -50 * (1 + abs(b))
        for a, b in zip(np.ravel(det), np.ravel(det0)):
            assert abs(a - b) <= mpmath.mpf(10) ** -50 * abs(b)


def _plan_builds(monkeypatch) -> list:
    """The ranges of the plans built from here on (none kept from before)."""
    built = []
    original = plan_module.StiffnessPlan.__init__

    def counting(self, *args, **kwargs):
        built.append(args[1] if len(args) > 1 else kwargs.get("radius"))
        original(self, *args, **kwargs)
    monkeypatch.setattr(plan_module.StiffnessPlan, "__init__", counting)
    plan_module.clear_plans()
    return built


def test_plans_are_shared_between_searches_and_forgotten_on_request(monkeypatch):
    from symtmm.model import Beam, Model, Spring
    from symtmm.solve import solve
    model = Model((Beam("a", 1, 1, 1, left="clamped"), Beam("b", 1, 1, 1, left="pinned",
                                                           right="pinned")),
                  (Spring("a", "b", "1/2", 10),))
    built = _plan_builds(monkeypatch)
    first = solve(model, count=4, digits=12)
    after_first = len(built)
    second = solve(model, count=4, digits=12)
    assert after_first >= 1 and len(built) == after_first          # all reused
    assert [str(e.lam) for e in first] == [str(e.lam) for e in second]
    plan_module.clear_plans()
    solve(model, count=4, digits=12)
    assert len(built) == 2 * after_first                            # built again


def test_plans_of_at_most_four_models_are_kept():
    from symtmm.model import Beam, Model
    plan_module.clear_plans()
    models = [Model((Beam("b", 1, 1, str(k + 1), left="pinned", right="pinned"),))
              for k in range(6)]
    for m in models:
        plan_module.plan_for(m, 10.0)
    assert len(plan_module._PLANS) == plan_module.PLAN_MODELS
    assert models[0] not in plan_module._PLANS and models[-1] in plan_module._PLANS


@pytest.mark.parametrize("curvature", [0.0, 3.0, -20.0, 20.0])
@pytest.mark.parametrize("noise", [0.0, 1e-17])
def test_bracket_refinement_closes_in_few_steps(curvature, noise):
    """A simple root with some curvature and rounding-sized noise, as ``Delta`` near an
    eigenvalue: every bracket closes to 1e-11 in a few steps. (Scaling the end that
    stays at every step, bisecting after two steps that had not halved the bracket and
    bisecting where a secant step rounded onto an end took 14 to 34 steps here.)"""
    roots = np.array([9.5986542925, 199.859448127, 1.0])
    steps = np.zeros(3, dtype=int)

    def f(x, idx):
        d = (x - roots[idx]) / roots[idx]
        return -0.31 * d * (1 + curvature * d) + noise * np.sin(1e9 * x)

    def probe(c, idx):
        steps[idx] += 1
        v = f(c, idx)
        return v, np.where(v < 0, 1, -1)
    a, b = roots * 0.97, roots * 1.04
    idx = np.arange(3)
    out = shrink(a, b, f(a, idx), f(b, idx), probe, 1e-11)
    np.testing.assert_allclose(out, roots, rtol=1e-11)
    assert steps.max() <= 10, steps


def test_a_settled_bracket_stops_when_its_step_is_below_the_width():
    """Around a root at the centre of a narrow bracket (a sweep's estimate), the secant
    points converge from one side and the other end stays: the bracket halves once and
    then waits for the scaling of its far end. ``settle`` stops where the step from the
    latest point is below the width, with that point as near the root as the width asks:
    never a step more, and one fewer on most curvatures."""
    roots = np.array([9.5986542925, 199.859448127, 61.6728228679])

    def run(curvature, settle):
        steps = np.zeros(3, dtype=int)

        def f(x, idx):
            d = (x - roots[idx]) / roots[idx]
            return -0.31 * d * (1 + curvature * d)

        def probe(c, idx):
            steps[np.unique(idx)] += 1
            v = f(c, idx)
            return v, np.where(v < 0, 1, -1)
        a, b = roots * (1 - 1e-3), roots * (1 + 1.1e-3)
        idx = np.arange(3)
        out = shrink(a, b, f(a, idx), f(b, idx), probe, 1e-11, settle=settle)
        np.testing.assert_allclose(out, roots, rtol=1e-11)
        return steps.max()
    pairs = [(run(c, True), run(c, False)) for c in (3.0, -20.0, 20.0, -3.0)]
    assert all(s <= p for s, p in pairs)
    assert sum(s < p for s, p in pairs) >= 2, pairs


@pytest.mark.parametrize("growth, most", [(0.3, 9), (1.0, 13), (3.0, 17)])
def test_a_crawling_bracket_shrinks_by_spread_points(growth, most):
    """A root near the left end of a wide bracket under a value growing exponentially to
    the right (as ``Delta`` under a neighbouring root): the secant crawls from the right.
    The points spread over a slow bracket shrink it fourfold a step (a bisection instead
    took 10, 14 and 21 steps here; these take 8, 12 and 15)."""
    roots = np.array([29.57, 199.86, 1.0])
    steps = np.zeros(3, dtype=int)

    def f(x, idx):
        d = (x - roots[idx]) / roots[idx]
        return d * np.exp(10 * growth * d)

    def probe(c, idx):
        steps[np.unique(idx)] += 1
        v = f(c, idx)
        return v, np.where(v > 0, 1, -1)
    a, b = roots * 0.92, roots * 1.85
    idx = np.arange(3)
    out = shrink(a, b, f(a, idx), f(b, idx), probe, 1e-11)
    np.testing.assert_allclose(out, roots, rtol=1e-11)
    assert steps.max() <= most, steps


def test_a_bracket_spanning_decades_is_spread_in_log_scale():
    """A real zero of a damped model beside lam = 0: bracket (-220, -1.1), the zero at
    -2.19 near its small end, the value growing like exp(|x|) toward the far end. Points
    spread evenly in log|x| find it in 12 steps (evenly spaced ones took 20: -165, -110,
    -55 all lie on the far side)."""
    steps = [0]

    def f(x):
        return (x + 2.19) * np.exp(-x)

    def probe(c, idx):
        steps[0] += 1
        v = f(c)
        return v, np.where(v * f(b[idx]) > 0, 1, -1)
    a, b = np.array([-220.0]), np.array([-1.1])
    out = shrink(a, b, f(a), f(b), probe, 1e-13)
    np.testing.assert_allclose(out, [-2.19], rtol=1e-12)
    assert steps[0] <= 13, steps


def test_a_string_like_beam_in_tension_builds_few_plans(monkeypatch):
    """A pinned-pinned beam in strong tension has modes like a string's (omega ~ n), so a
    first guess from the beam's largest (evanescent) wave number is low, and each count on
    the way up needs a plan cut for its range (7 plans here with steps of 1.5). The guess
    now counts the travelling waves, and a miss jumps to where the count would be
    reached. Reference: omega_n**2 = (n pi)**4 EI / m + (n pi)**2 N / m (L = 1)."""
    import mpmath

    from symtmm.model import Beam, Model
    from symtmm.solve import solve
    built = _plan_builds(monkeypatch)
    EI, N = mpmath.mpf("0.01"), 100
    model = Model((Beam("s", "1/100", 1, 1, left="pinned", right="pinned", N=N),))
    spectrum = solve(model, count=10, digits=15)
    for n, e in enumerate(spectrum, start=1):
        a = n * mpmath.pi
        assert mpmath.almosteq(e.omega, mpmath.sqrt(a**4 * EI + a**2 * N), rel_eps=1e-15)
    assert len(built) <= 2, built           # (1 here; 3 by the jumps alone, 7 by steps)


@pytest.mark.parametrize("levels", [10, 20])
def test_a_chain_is_cut_once_for_a_range_its_springs_already_cut_for(monkeypatch, levels):
    """A chain's pieces are mostly its stretches between springs: the plan of its first
    count is cut for twice that range where this adds at most 5 % of pieces (counted
    exactly, the same cut the plan makes), and serves the top its search ends at (two
    plans before). Its frequencies: the global coefficient matrix of the benchmarks'
    references (located by a finite-element model), none from symtmm."""
    from benchmarks import references, sparse_fe
    from benchmarks.models import global_input
    from symtmm.mesh import Stretches
    from symtmm.solve import solve
    model = chain(levels, 2).require_numeric()
    st = Stretches(model)

    def pieces(w):
        return sum(max(1, int(np.ceil(r - 1e-9)))
                   for r in st.subdivide(plan_module.piece_rule(w * w))[2])
    chosen = [plan_module.generous_range(st, w) for w in (8.0, 16.0, 32.0)]
    assert any(c > w for c, w in zip(chosen, (8.0, 16.0, 32.0)))
    for c, w in zip(chosen, (8.0, 16.0, 32.0)):
        assert c in (w, 2**0.5 * w, 2 * w) and pieces(c) <= 1.05 * pieces(w)
    built = _plan_builds(monkeypatch)
    spectrum = solve(model, count=10, digits=15)
    assert len(built) == 1, built
    guesses = sparse_fe.frequencies(sparse_fe.fe_input(model), 16, 10)
    ref = references.located_omegas(*global_input(model), list(guesses))
    assert np.allclose([float(e.omega) for e in spectrum], [float(w) for w in ref], rtol=1e-10)


def test_small_batches_use_a_plan_for_a_larger_range(monkeypatch, examples_dir):
    """Example 1 with its springs at the ends: the isolation's batches below a quarter of
    the top frequency took plans of their own (three plans); a small batch evaluates on
    the plan it has. Both give the same frequencies to every printed digit (other pieces,
    the same K's eigenvalues)."""
    from symtmm.modelfile import load
    from symtmm.solve import solve
    model = load(examples_dir / "paper_ex1_ff_cc.toml").with_parameters(x1="0")
    built = _plan_builds(monkeypatch)
    shared = solve(model, count=10, digits=15)
    assert len(built) == 1, built           # the top range's plan serves every batch
    from symtmm.numeric import evaluator
    monkeypatch.setattr(evaluator, "SMALL_BATCH", 0)
    monkeypatch.setattr(evaluator, "SMALL_PROOF_BATCH", 0)
    plan_module.clear_plans()
    own = solve(model, count=10, digits=15)
    assert len(built) >= 3, built
    assert [str(e.lam) for e in shared] == [str(e.lam) for e in own]


def test_undecided_cut_points_are_counted_in_batches(monkeypatch, examples_dir):
    """Example 1 with its springs at mid-span: the free beam turns about them (omega = 0)
    and both beams' antisymmetric modes, with a node there, leave the springs idle: double
    roots at beta**2 with cos(beta) cosh(beta) = 1 (beta = 7.853..., 14.137...). Cut points
    near them that double precision leaves undecided were counted in balls one call each
    (81 calls); now one batch per isolation round."""
    from symtmm.modelfile import load
    from symtmm.numeric.evaluator import Evaluator
    from symtmm.solve import solve
    model = load(examples_dir / "paper_ex1_ff_cc.toml").with_parameters(x1="1/2")
    calls = []
    original = Evaluator._ball

    def counted(self, *args):
        calls.append(1)
        return original(self, *args)
    monkeypatch.setattr(Evaluator, "_ball", counted)
    spectrum = solve(model, count=10, digits=12)
    doubles = [e for e in spectrum if e.multiplicity == 2]
    for e, guess in zip(doubles, (7.85, 14.14)):
        beta = mpmath.findroot(lambda b: mpmath.cos(b) * mpmath.cosh(b) - 1, guess)
        assert mpmath.almosteq(e.omega, beta**2, rel_eps=1e-12)
    assert len(doubles) == 2 and spectrum.eigenvalues[0].omega == 0
    assert len(calls) <= 40, len(calls)      # (28 here; 81 one point a call)


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_paired_functions_in_balls_enclose_mpmath_values():
    """cosh/sinh and cos/sin from one Arb call each, real and complex balls: both enclose
    mpmath's values at 90 digits; the jets keep their own chain rule (the pair of
    separate functions)."""
    import flint

    from symtmm.numeric.jet import BallJet
    ar = Ball(200)
    with ar, mpmath.workdps(90):
        for z in (mpmath.mpf("1.3"), mpmath.mpc("0.7", "-2.1"), mpmath.mpf("-40.25")):
            x = np.array([ar.number(z)], dtype=object)
            (ch, sh), (co, si) = ar.cosh_sinh(x), ar.cos_sin(x)
            for ball, exact in ((ch, mpmath.cosh(z)), (sh, mpmath.sinh(z)),
                                (co, mpmath.cos(z)), (si, mpmath.sin(z))):
                b = ball[0]
                mid = complex(b.mid()) if isinstance(b, flint.acb) else float(b.mid())
                assert abs(mid - complex(exact)) <= 1e-14 * max(1.0, abs(complex(exact)))
                assert b.overlaps(flint.acb(str(exact.real), str(exact.imag))
                                  if isinstance(b, flint.acb) else flint.arb(str(exact)))
    assert BallJet.cosh_sinh is not Ball.cosh_sinh and BallJet.cos_sin is not Ball.cos_sin


def test_a_bracket_end_far_below_the_other_is_not_taken_for_the_root():
    """An end whose value is far below the other's without the root being near it: the
    root at 1, a cluster of roots just beyond the bracket's right end (the value there
    1e-86 of the left end's), as a beam on a foundation beside a root of another beam in
    a campaign's model. The secant's point fell on the right end, which ``settle`` took
    for the root (4e-6 off there, and its proof did not converge). Reference: the root."""
    def f(x, idx):
        return (x - 1.0) * (x - 3.0) ** 20 * (1 + 0 * idx)

    def probe(c, idx):
        v = f(c, idx)
        return v, np.where(v > 0, 1, -1)
    a, b = np.array([0.0]), np.array([2.9999])
    for settle in (False, True):
        out = shrink(a, b, f(a, 0), f(b, 0), probe, 1e-11, settle=settle)
        np.testing.assert_allclose(out, [1.0], rtol=1e-10)
