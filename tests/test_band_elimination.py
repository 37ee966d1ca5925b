"""The band's loops in C (symtmm/numeric/_band.c: scatter, LDL^T, bounds) against numpy.

The C loop is an optional build; where it is missing these tests are skipped and the
numpy loop runs everywhere (every other test exercises it then). Where it is present,
the numpy loop is still run here, on the same bands and in whole solves.
"""

from __future__ import annotations

import numpy as np
import pytest

from symtmm import api
from symtmm.numeric import stiffness
from symtmm.numeric.arith import DOUBLE
from symtmm.solve import solve

compiled_only = pytest.mark.skipif(stiffness._band is None, reason="C extension not built")


@pytest.fixture
def numpy_loop(monkeypatch):
    monkeypatch.setattr(stiffness, "COMPILED", False)


def _factors(monkeypatch, K, compiled: bool):
    monkeypatch.setattr(stiffness, "COMPILED", compiled)
    return stiffness._ldl(None, DOUBLE, K.copy(), np.zeros((K.shape[0], 0)))


def _random_band(rng, B, n, w, dtype):
    """Banded symmetric matrices with a dominant diagonal (no breakdown without pivoting)
    and some indefinite ones."""
    K = rng.normal(size=(B, n, w))
    if dtype == complex:
        K = K + 1j * rng.normal(size=(B, n, w))
    K[:, :, 0] += np.where(rng.random((B, n)) < 0.3, -1, 1) * 3 * w
    for j in range(1, w):
        K[:, n - j:, j] = 0          # outside the matrix
    return K


@compiled_only
@pytest.mark.parametrize("dtype", [float, complex])
@pytest.mark.parametrize("n, w", [(1, 1), (5, 1), (12, 4), (40, 9)])
def test_c_and_numpy_give_the_same_factors(monkeypatch, dtype, n, w):
    K = _random_band(np.random.default_rng(n * 100 + w), 7, n, w, dtype)
    c = _factors(monkeypatch, K, True)
    p = _factors(monkeypatch, K, False)
    # real bands: the same operations in the same order, the same bits; complex ones may
    # differ in the last bits (numpy may fuse the products of a complex multiplication)
    rtol = 0 if dtype is float else 1e-13
    np.testing.assert_allclose(c.pivots, p.pivots, rtol=rtol, atol=0)
    assert np.array_equal(c.counts(), p.counts())
    assert np.array_equal(c.decided, p.decided)         # (the bounds of |L||D||L^T| too)
    # against numpy's dense eigenvalues: the inertia
    if dtype is float:
        dense = stiffness.dense(None, K)
        negative = (np.linalg.eigvalsh(dense) < 0).sum(axis=1)
        assert np.array_equal(c.counts()[c.trusted], negative[c.trusted])


@compiled_only
def test_a_zero_pivot_gives_the_same_non_finite_values(monkeypatch):
    K = np.zeros((1, 3, 2))
    K[0, :, 0] = [0.0, 1.0, 1.0]
    K[0, 0, 1] = 1.0
    c, p = _factors(monkeypatch, K, True), _factors(monkeypatch, K, False)
    np.testing.assert_array_equal(c.pivots, p.pivots)
    np.testing.assert_array_equal(c.decided, p.decided)
    assert c.counts()[0] == p.counts()[0] == -1


@compiled_only
def test_the_c_loop_refuses_a_buffer_of_the_wrong_size():
    with pytest.raises(ValueError, match="wrong size"):
        stiffness._band.eliminate(np.zeros((2, 5, 3)), 2, 5, 3, 4, False)
    with pytest.raises(ValueError, match="wrong size"):
        stiffness._band.bounds(np.zeros((2, 7, 3)), np.zeros((2, 4, 3)), np.zeros((2, 3)),
                               2, 7, 3, 4, False)


@compiled_only
def test_the_scatter_refuses_an_index_outside_its_arrays():
    V, K = np.ones((2, 4)), np.zeros((2, 6))
    ints = lambda *v: np.array(v, dtype=np.int64)
    # two layers onto entry 5: its first term, then its second added
    stiffness._band.scatter(V, K, ints(5), ints(0), np.ones(1), 2, False, False)
    stiffness._band.scatter(V, K, ints(5), ints(3), np.ones(1), 2, True, False)
    assert K[:, 5].tolist() == [2.0, 2.0]
    for targets, source in [(ints(5, 1), ints(0, 4)),      # V has 4 columns
                            (ints(6, 1), ints(0, 1)),      # K has 6
                            (ints(5), ints(0, 1))]:        # a term without a target
        with pytest.raises(ValueError, match="do not fit"):
            stiffness._band.scatter(V, K, targets, source, np.ones(source.size), 2, True,
                                    False)


@compiled_only
@pytest.mark.parametrize("name, damped", [("paper_ex3_three_pp_coupled.toml", False),
                                          ("tuned_mass_damper.toml", True)])
def test_c_and_numpy_assemble_the_same_band(monkeypatch, examples_dir, name, damped):
    """Each entry sums its terms in the plan's order in both: the same bits, real or
    complex (dashpots)."""
    from symtmm.numeric.evaluator import Evaluator

    model = api.load(examples_dir / name).require_numeric()
    plan = Evaluator(model, 100.0).plan(100.0)
    lam = np.linspace(0.5, 95.0, 9) * (1j if not damped else (-0.05 + 1j))
    lam2 = lam * lam if damped else (lam * lam).real
    bands = []
    for compiled in (True, False):
        monkeypatch.setattr(stiffness, "COMPILED", compiled)
        bands.append(stiffness.assemble(plan, DOUBLE, lam2, lam if damped else None)[0])
    assert bands[0].dtype == (complex if damped else float)
    np.testing.assert_array_equal(bands[0], bands[1])
    assert np.count_nonzero(bands[0]) > plan.n           # (not an empty band)


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc.toml", "tuned_mass_damper.toml"])
def test_solves_with_the_numpy_loop(numpy_loop, examples_dir, name):
    """The loop that runs where no compiler built the C one: the same digits."""
    model = api.load(examples_dir / name)
    spec = solve(model, count=4, digits=15)
    assert stiffness.COMPILED is False
    with pytest.MonkeyPatch.context() as mp:
        mp.setattr(stiffness, "COMPILED", stiffness._band is not None)
        again = solve(model, count=4, digits=15)
    assert [str(e) for e in spec] == [str(e) for e in again]



def test_a_batch_factorised_in_parts_is_the_batch_factorised_at_once(monkeypatch):
    """Parts of a few points each (BAND_ENTRIES lowered) give the same pivots, signs,
    decisions and det U12 bit for bit, and the band at every untrusted point (the paper's
    example 2 at its triple roots, where pivots break down)."""
    from symtmm.numeric.evaluator import Evaluator

    model = api.load("examples/paper_ex2_three_pp.toml").require_numeric()
    ev = Evaluator(model, 60.0)
    lam = 1j * np.concatenate([np.linspace(1.0, 50.0, 37), [np.pi**2, 4 * np.pi**2]])
    whole = ev.factors(lam, DOUBLE)
    plan = whole.plan
    monkeypatch.setattr(stiffness, "BAND_ENTRIES", 3 * plan.n * plan.width)
    parts = ev.factors(lam, DOUBLE)
    assert isinstance(parts.K, stiffness.BandRows)
    for field in ("pivots", "signs", "decided", "det12"):
        np.testing.assert_array_equal(getattr(parts, field), getattr(whole, field))
    bad = np.nonzero(~whole.trusted)[0]
    assert bad.size, "the triple roots leave some pivots undecided"
    np.testing.assert_array_equal(parts.K[bad], whole.K[bad])
    assert np.allclose(np.array(parts.pivoted_delta(bad), dtype=complex),
                       np.array(whole.pivoted_delta(bad), dtype=complex), rtol=0, atol=0)
    with pytest.raises(KeyError, match="untrusted points only"):
        parts.K[[int(np.nonzero(whole.trusted)[0][0])]]


@compiled_only
@pytest.mark.parametrize("name, damped", [("paper_ex3_three_pp_coupled.toml", False),
                                          ("paper_ex2_three_pp.toml", False),
                                          ("tuned_mass_damper.toml", True)])
def test_the_one_pass_summary_reads_the_factors_as_their_bookkeeping_does(
        examples_dir, name, damped):
    """``summary`` (one compiled pass: log|Delta| through one logarithm of the pivots'
    running product, the phase, the count) against :class:`Factors` (a logarithm per
    pivot, numpy): the same counts and decisions, log|Delta| and the phase to rounding,
    at points far from and at roots (example 2's triple roots pi**2, 4 pi**2: pivots
    that break down to tiny or zero values)."""
    from symtmm.numeric.evaluator import Evaluator

    model = api.load(examples_dir / name).require_numeric()
    plan = Evaluator(model, 100.0).plan(100.0)
    omega = np.concatenate([np.linspace(0.5, 95.0, 41), [np.pi**2, 4 * np.pi**2]])
    lam = omega * (1j if not damped else (-0.05 + 1j))
    lam2 = lam * lam if damped else (lam * lam).real
    dash = lam if damped else None
    logabs, phase, counts = stiffness.summary(plan, lam2, dash)
    fa = stiffness.factor(plan, DOUBLE, lam2, lam=dash)
    want_log, want_phase = fa.log_delta()
    finite = np.isfinite(want_log)
    assert finite.sum() >= 40
    np.testing.assert_allclose(logabs[finite], want_log[finite], rtol=1e-13, atol=1e-12)
    assert np.array_equal(np.isfinite(logabs), finite)
    turn = np.angle(np.exp(1j * (phase[finite] - want_phase[finite])))
    assert np.max(np.abs(turn)) < 1e-10
    want_counts = np.where(fa.trusted, fa.counts(), -1) if not damped else \
        np.where(fa.trusted, 0, -1)
    assert np.array_equal(counts, want_counts)


@compiled_only
@pytest.mark.parametrize("dtype", [float, complex])
def test_the_summary_logarithm_holds_pivots_of_any_size(dtype):
    """Diagonal bands (no elimination: the pivots are the diagonal) whose running product
    leaves the doubles' range many times over, and pivots beyond 2**-400..2**400, subnormal
    among them: log|Delta| and the phase as the sums of each pivot's own."""
    rng = np.random.default_rng(7)
    B, n = 5, 300
    exps = rng.choice([-1000.0, -450.0, -300.0, 0.0, 300.0, 450.0, 1000.0], size=(B, n))
    exps[:, :40] = 450.0                       # runs far beyond the range, both ways
    exps[:, 40:80] = -450.0
    exps[1, 5] = -1070.0                       # subnormal
    d = np.exp2(exps) * rng.uniform(0.5, 2.0, size=(B, n)) * rng.choice([-1, 1], size=(B, n))
    if dtype is complex:
        d = d * np.exp(1j * rng.uniform(-np.pi, np.pi, size=(B, n)))
    K = np.ascontiguousarray(d[:, :, None].astype(dtype))
    Kb = np.concatenate([K, np.zeros((B, 1, 1), dtype=dtype)], axis=1)
    logabs, phase, counts = np.empty(B), np.empty(B), np.empty(B, dtype=np.int64)
    stiffness._band.summary(Kb, K, np.zeros((B, 0), dtype=dtype), np.zeros(0, dtype=np.int64),
                            logabs, phase, counts, B, n + 1, 1, n, 0, 0.0, np.inf, 0.0,
                            dtype is complex)
    want = np.log(np.abs(d)).sum(axis=1)
    np.testing.assert_allclose(logabs, want, rtol=1e-14)
    want_phase = np.angle(d).sum(axis=1) if dtype is complex else np.pi * (d < 0).sum(axis=1)
    turn = np.angle(np.exp(1j * (phase - want_phase)))
    assert np.max(np.abs(turn)) < 1e-11
    if dtype is float:
        assert np.array_equal(counts, (d < 0).sum(axis=1))


@compiled_only
@pytest.mark.parametrize("name, damped", [("paper_ex3_three_pp_coupled.toml", False),
                                          ("paper_ex2_three_pp.toml", False),
                                          ("tuned_mass_damper.toml", True)])
def test_a_point_at_a_time_summary_is_the_batch_of_bands_summary(examples_dir, name, damped):
    """The compiled kernel's summary a point at a time (each band built, factorised and read
    in cache) and the one through a batch of bands: the same bits, and the points beyond
    the series' reach (here a frequency of 1e5) taken the banded way."""
    from symtmm.numeric import multiword
    from symtmm.numeric.evaluator import Evaluator

    model = api.load(examples_dir / name).require_numeric()
    plan = Evaluator(model, 100.0).plan(100.0)
    omega = np.concatenate([np.linspace(0.5, 95.0, 41), [np.pi**2, 1e5]])
    lam = omega * (1j if not damped else (-0.05 + 1j))
    lam2 = lam * lam if damped else (lam * lam).real
    dash = lam if damped else None
    assert multiword.serves_double(plan, lam2, dash)
    fused = multiword.double_summary(plan, lam2, dash)
    assert fused[3][:-1].all() and not fused[3][-1]
    whole = stiffness.summary(plan, lam2, dash)
    banded = stiffness._banded_summary(plan, lam2, dash)
    for got, want in zip(whole, banded):
        np.testing.assert_array_equal(got, want)
