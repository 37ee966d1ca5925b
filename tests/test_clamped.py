"""Counts whose long pieces pass their clamped-clamped frequencies, adding ``J0``.

References: the closed forms of a clamped-clamped beam (``cos b cosh b = 1``) and of a
cantilever (``1 + cos b cosh b = 0``), roots found in mpmath from ``(n + 1/2) pi``; and,
on random models, the counts of the plans of short pieces (``J0 = 0``), a second
formulation of the same count.
"""

from __future__ import annotations

import math
import random

import mpmath
import numpy as np
import pytest

from symtmm.model import Beam, Model, Spring
from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
from symtmm.numeric.clamped import clamped_counts
from symtmm.numeric.plan import StiffnessPlan, clear_plans
from symtmm.numeric.stiffness import factor, summary
from symtmm.results import decimal_string
from symtmm.roots.count import Counter
from symtmm.roots.undamped import PROOFS, solve_undamped

CLAMPED = Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),))
CANTILEVER = Model((Beam("b", 1, 1, 1, left="clamped", right="free"),))


def _roots(f, count: int, first: int, dps: int = 40) -> list:
    """``b`` of the first ``count`` roots of ``f``, each found from ``(n + 1/2) pi``, ``n``
    from ``first``: the clamped-clamped roots (``first`` 1) and the cantilever's (0) lie
    within about ``exp(-n pi)`` of there."""
    with mpmath.workdps(dps):
        return [mpmath.findroot(f, (n + mpmath.mpf(1) / 2) * mpmath.pi)
                for n in range(first, first + count)]


CLAMPED_B = _roots(lambda b: mpmath.cos(b) - 1 / mpmath.cosh(b), 80, 1)


def _arithmetics():
    return [DOUBLE, MP(200)] + ([Ball(200)] if ball_available() else [])


@pytest.mark.parametrize("ar", _arithmetics(), ids=lambda ar: ar.name)
def test_counts_of_a_clamped_beam_in_long_pieces_are_its_closed_forms(ar):
    """A clamped-clamped beam cut into a few long pieces at its 75th mode: ``J0`` of the
    pieces plus the negative eigenvalues of ``K`` count the beam's own roots below each
    frequency, in every arithmetic; ``J0`` alone is the pieces' roots below it."""
    plan = StiffnessPlan(CLAMPED, float(CLAMPED_B[75]) ** 4, clamped=True)
    pieces = int(plan.multiplicity.sum())
    assert plan.clamped and 1 < pieces <= 6 and plan.n == 2 * (pieces - 1)
    rng = random.Random(3)
    betas = sorted(rng.uniform(0.5, float(CLAMPED_B[74])) for _ in range(40))
    betas += [float(b) + d for b in CLAMPED_B[:74:7] for d in (-1e-6, 1e-6)]
    # (the pieces' own roots: nu = beta / pieces; first those of the clamped beam below)
    expected = [sum(float(r) < b for r in CLAMPED_B) for b in betas]
    expected_j0 = [pieces * sum(float(r) < b / pieces for r in CLAMPED_B) for b in betas]
    with ar:
        lam2 = ar.array([-ar.number(mpmath.mpf(b) ** 4) for b in betas]) \
            if ar is not DOUBLE else -np.array(betas) ** 4
    assert clamped_counts(plan, ar, lam2).tolist() == expected_j0
    counts = factor(plan, ar, lam2).counts()
    if ar is DOUBLE:
        # (a pivot within 1e-6 of the beam's root may be too small to trust in doubles:
        # -1, and the searches count there in their proof arithmetic)
        assert (counts >= 0).sum() >= len(betas) - 8
        assert summary(plan, lam2)[2].tolist() == counts.tolist()
        counts, expected = counts[counts >= 0], np.array(expected)[counts >= 0]
    assert counts.tolist() == list(expected)


def test_a_frequency_on_a_pieces_clamped_root_is_undecided_in_doubles():
    """Within rounding of a piece's clamped-clamped root the sign of ``1 - cosh nu cos nu``
    is not decided in doubles (``-1``: the searches move off or take more digits), and it
    is in balls of enough bits, on either side."""
    plan = StiffnessPlan(CLAMPED, float(CLAMPED_B[75]) ** 4, clamped=True)
    pieces = int(plan.multiplicity.sum())
    nu = CLAMPED_B[9]                               # (the pieces' 10th root)
    assert clamped_counts(plan, DOUBLE, -np.array([float(nu * pieces) ** 4])).tolist() == [-1]
    if not ball_available():
        return
    ar = Ball(300)
    with ar, mpmath.workdps(60):
        for shift, below in ((mpmath.mpf("-1e-30"), 9), (mpmath.mpf("1e-30"), 10)):
            beta = (nu + shift) * pieces
            lam2 = ar.array([-ar.number(beta ** 4)])
            assert clamped_counts(plan, ar, lam2).tolist() == [pieces * below]


def _random_model(rng: random.Random) -> Model:
    ends = ["clamped", "pinned", "free", "sliding"]
    beams = tuple(Beam(f"b{i}", rng.choice([1, 2, "1/3", 10]), rng.choice([1, 3, "1/2"]),
                       rng.choice([1, 2, "3/2"]), left=rng.choice(ends),
                       right=rng.choice(ends), kw=rng.choice([0, 0, 50]))
                  for i in range(rng.randint(1, 3)))
    springs = []
    for _ in range(rng.randint(1, 3)):
        a = rng.randrange(len(beams))
        other = rng.choice([b.name for b in beams if b.name != beams[a].name] + ["ground"])
        L = min([float(beams[a].L)] + [float(b.L) for b in beams if b.name == other])
        springs.append(Spring(beams[a].name, other, x=f"{rng.randint(1, 9)}/10 * {L}",
                              k=rng.choice([5, 100, 2000])))
    return Model(beams, tuple(springs))


def _both_counts(model: Model, rng: random.Random) -> tuple:
    """``(plan, short plan, counts, short counts)`` at 300 random frequencies up to about
    the 40th mode of each beam: by the counter's plans for counts (``J0`` added) and by
    plans of short pieces (``J0 = 0``)."""
    top = min(float((40 * math.pi) ** 2 * (b.EI / b.m) ** 0.5 / b.L ** 2) for b in model.beams)
    omegas = np.sort(np.array([rng.uniform(0.01, 1.0) * top for _ in range(300)]))
    clear_plans()
    long = Counter(model, top)
    short = Counter(model, top)
    short.clamped = False
    got, want = long.counts(omegas), short.counts(omegas)
    return long.plan(top), short.plan(top), got, want


@pytest.mark.parametrize("seed", [0, 2, 5, 6, 9, 11])
def test_counts_past_the_clamped_frequencies_are_those_of_short_pieces(seed):
    """On random models of beams, foundations and springs, up to about the 40th mode of
    each beam: the counts of the plans whose long pieces pass their clamped-clamped
    frequencies (adding ``J0``) equal those of the plans of short pieces (``J0 = 0``) at
    every frequency both decide. (Seeds whose beams have stretches long enough for long
    pieces; with springs every few tenths of a beam, the plans are the same.)"""
    rng = random.Random(seed)
    plan, short, got, want = _both_counts(_random_model(rng), rng)
    assert plan.clamped and plan.n < short.n
    both = (got >= 0) & (want >= 0)
    assert both.sum() >= 290
    assert got[both].tolist() == want[both].tolist()


def test_a_cantilevers_three_hundred_modes_in_few_pieces():
    """Every digit of a cantilever's first 300 frequencies against ``1 + cos b cosh b =
    0``, each proved by ball counts, on plans of long pieces (short ones took 314 pieces
    at the 300th mode, and the 300 modes 15 s)."""
    clear_plans()
    spec = solve_undamped(CANTILEVER, count=300, digits=15)
    from symtmm.numeric import plan as plans
    largest = max(p.n for p in plans._PLANS[CANTILEVER].values())
    assert largest <= 24
    if ball_available():
        assert [e.proof for e in spec] == [PROOFS["ball"]] * 300
    roots = _roots(lambda b: mpmath.cos(b) + 1 / mpmath.cosh(b), 300, 0)
    with mpmath.workdps(40):
        expected = [decimal_string(b ** 2, 15) for b in roots]
    assert [e.to_dict()["imag"] for e in spec] == expected


def test_thirty_digits_of_a_clamped_beams_high_modes():
    """Modes 1 to 100 of a clamped-clamped beam to 30 digits against ``cos b cosh b = 1``."""
    spec = solve_undamped(CLAMPED, count=100, digits=30)
    roots = _roots(lambda b: mpmath.cos(b) - 1 / mpmath.cosh(b), 100, 1, dps=60)
    with mpmath.workdps(60):
        expected = [decimal_string(b ** 2, 30) for b in roots]
    assert [e.to_dict()["imag"] for e in spec] == expected


def test_a_long_beam_on_a_soft_foundation_solves(tmp_path):
    """A beam 24,520 long of EI 2.8e-8 on a foundation (a fuzzed model whose solve ran past
    any budget in thousands of short pieces): its first three frequencies, 3e-17 apart,
    against the closed form ``omega**2 = (EI b**4 + kw) / m``, ``tan bL + tanh bL = 0``
    (clamped-sliding), each proved by ball counts."""
    import json

    from test_input_limits import LONG_BEAM_ON_A_FOUNDATION, run_file

    run = run_file(tmp_path, LONG_BEAM_ON_A_FOUNDATION, "solve", "--count", "3", "--json",
                   limit=60)
    assert run.code == 0, run.stderr
    got = json.loads(run.stdout)["eigenvalues"]
    EI, m, L, kw = (mpmath.mpf(v) for v in ("2.783e-08", "42.13", "24520.0", "9.911e-08"))
    with mpmath.workdps(40):
        expected = []
        for n in range(1, 4):
            bL = mpmath.findroot(lambda x: mpmath.tan(x) + mpmath.tanh(x),
                                 (n - mpmath.mpf(1) / 4) * mpmath.pi)
            expected.append(decimal_string(mpmath.sqrt((EI * (bL / L) ** 4 + kw) / m), 15))
    assert [e["imag"] for e in got] == expected
    if ball_available():
        assert {e["proof"] for e in got} == {PROOFS["ball"]}


def test_the_long_beam_on_a_soft_foundation_has_its_mode_shape(tmp_path):
    """Its first mode shape (``modes``), against the clamped-sliding closed form ``Y = cosh
    bx - cos bx - s (sinh bx - sin bx)``, ``s = (sinh bL + sin bL) / (cosh bL - cos bL)``:
    the same direction to 1e-12 at 21 points."""
    import json

    from test_input_limits import LONG_BEAM_ON_A_FOUNDATION, run_file

    run = run_file(tmp_path, LONG_BEAM_ON_A_FOUNDATION, "modes", "--count", "1", "--points",
                   "21", "--json", limit=60)
    assert run.code == 0, run.stderr
    beam = json.loads(run.stdout)["modes"][0]["beams"]["b"]
    x, Y = np.array(beam["x"]), np.array(beam["Y"])
    L = 24520.0
    with mpmath.workdps(30):
        bL = mpmath.findroot(lambda v: mpmath.tan(v) + mpmath.tanh(v), 3 * mpmath.pi / 4)
        s = (mpmath.sinh(bL) + mpmath.sin(bL)) / (mpmath.cosh(bL) - mpmath.cos(bL))
        want = np.array([float(mpmath.cosh(bL * t) - mpmath.cos(bL * t)
                               - s * (mpmath.sinh(bL * t) - mpmath.sin(bL * t))) for t in x / L])
    cosine = abs(Y @ want) / (np.linalg.norm(Y) * np.linalg.norm(want))
    assert 1 - cosine < 1e-12


def test_a_counters_counts_of_a_clamped_beam_up_to_its_twentieth_mode():
    """The counter's own batches (its plans, the compiled summary or the factors) on a
    clamped-clamped beam of other constants, 200 points up to the 20th mode, against the
    closed form; no warning (the series, computed and thrown away at the long pieces'
    points past their clamped frequencies, divided by a rounded zero)."""
    beam = Beam("b", "13/1000", "167/250", "171/250", left="clamped", right="clamped")
    scale = (0.013 / 0.668) ** 0.5 / 0.684 ** 2          # omega = b**2 scale
    top = float(CLAMPED_B[19]) ** 2 * scale
    rng = random.Random(42)
    omegas = np.array(sorted(rng.uniform(0.001, 1.0) * top for _ in range(200)))
    clear_plans()
    counter = Counter(Model((beam,)), top)
    got = counter.counts(omegas)
    expected = [sum(float(b) ** 2 * scale < w for b in CLAMPED_B) for w in omegas]
    assert counter.plan(top).clamped
    decided = got >= 0
    assert decided.sum() >= 195
    assert got[decided].tolist() == np.array(expected)[decided].tolist()


def _theory(rng: random.Random, EI: float, L: float) -> dict:
    kind = rng.choice(["rayleigh", "timoshenko", "tension", "compression"])
    if kind == "rayleigh":
        return dict(theory="rayleigh", rhoI=rng.choice(["1/1000", "1/100"]))
    if kind == "timoshenko":
        return dict(theory="timoshenko", rhoI=rng.choice(["1/1000", "1/100"]),
                    kGA=str(EI / L ** 2 * rng.choice([10, 100, 1000])))
    if kind == "tension":
        return dict(N=str(EI / L ** 2 * rng.choice([1, 10, 50])))
    return dict(N=str(-EI / L ** 2 * rng.choice([0.1, 0.5])))


@pytest.mark.parametrize("seed", range(6))
def test_counts_of_condensed_chains_past_their_clamped_frequencies(seed):
    """Beams of the other theories (rotary inertia, shear, axial force), whose long pieces
    are chains of short ones condensed by doubling: with ``J0`` of each doubling's middle
    node, the counts of the plans for counts equal those of the short pieces at every
    frequency both decide, up to about the 40th mode."""
    rng = random.Random(100 + seed)
    ends = ["clamped", "pinned", "free", "sliding"]
    beams = []
    for i in range(rng.randint(1, 2)):
        EI, L = rng.choice([1, 3, 20]), rng.choice([1, 2])
        beams.append(Beam(f"b{i}", EI, rng.choice([1, 2]), L, left=rng.choice(ends[:2]),
                          right=rng.choice(ends), **_theory(rng, EI, L)))
    springs = (Spring("b0", beams[-1].name if len(beams) > 1 else "ground", "1/3", 50),)
    plan, short, got, want = _both_counts(Model(tuple(beams), springs), rng)
    assert plan.clamped and any(family == "condensed" for family, _ in plan.kinds)
    assert plan.n < short.n
    # (the many short pieces leave some counts undecided in doubles, the chains fewer)
    assert (got >= 0).sum() >= (want >= 0).sum() >= 270
    both = (got >= 0) & (want >= 0)
    assert got[both].tolist() == want[both].tolist()


@pytest.mark.parametrize("theory", [dict(theory="timoshenko", rhoI="1/1000", kGA=1000),
                                    dict(theory="rayleigh", rhoI="1/1000"), dict(N=30)],
                         ids=["timoshenko", "rayleigh", "tension"])
def test_thirty_modes_of_cantilevers_of_the_other_theories_against_the_fe_model(theory):
    """A cantilever's first 30 frequencies with shear, rotary inertia or tension, counted
    on a few condensed chains past their clamped frequencies (``J0`` of the doublings),
    against the converged FE model of :mod:`symtmm.fe` (no code shared with the solver):
    within its error estimate."""
    from symtmm.fe import fe_converged
    from symtmm.numeric.clamped import clamped_counts
    from symtmm.solve import solve

    model = Model((Beam("b", 1, 1, 1, left="clamped", right="free", **theory),))
    clear_plans()
    spec = solve(model, count=30, digits=15)
    got = np.array([float(e.lam.imag) for e in spec for _ in range(e.multiplicity)])[:30]
    fe = fe_converged([dict(name="b", EI=1.0, m=1.0, L=1.0, x0=0.0, left="clamped",
                            right="free", kw=0.0, N=float(theory.get("N", 0)),
                            rhoI=float(mpmath.mpf(theory.get("rhoI", 0))),
                            kGA=theory.get("kGA"))], [], 48, 30)
    assert np.all(np.abs(got - fe["omega"]) <= 2 * fe["error"] + 1e-12 * fe["omega"])
    plan = Counter(model, got[-1]).plan(got[-1])
    assert plan.clamped and plan.n <= 8
    assert clamped_counts(plan, DOUBLE, -np.array([got[-1] * 0.999]) ** 2)[0] > 20


def test_a_free_beams_translation_on_its_foundation_has_its_shape(tmp_path):
    """A free-free Rayleigh beam on a foundation translates rigidly at ``omega**2 = kw / m``
    exactly, where ``m lam**2 + kw`` is 0: its shape is the constant ``1 / sqrt(m L)``
    (mass-normalised), its frequency the closed form. (The shapes' count of digits lost to
    that cancellation divided by the 0: a traceback.)"""
    import json

    from test_input_limits import run_file

    text = ('[[beam]]\nname = "b"\ntheory = "rayleigh"\nEI = 30970000\nm = 21.75\nL = 12.3\n'
            'left = "free"\nright = "free"\nrhoI = 1.408\nkw = 5502\n')
    run = run_file(tmp_path, text, "modes", "--count", "2", "--points", "5", "--json")
    assert run.code == 0, run.stderr
    modes = json.loads(run.stdout)["modes"]
    omega = math.sqrt(5502 / 21.75)
    [translation] = [m for m in modes if abs(float(m["eigenvalue"]["imag"]) / omega - 1) < 1e-14]
    Y = np.array(translation["beams"]["b"]["Y"])
    assert np.allclose(np.abs(Y), 1 / math.sqrt(21.75 * 12.3), rtol=1e-12, atol=0)


def test_shapes_of_a_model_without_foundation_keep_their_eigenvalues():
    """The digits a foundation takes are counted only where it takes some: a beam over
    five pinned spans has its shapes at the solve's own eigenvalues, none refined (every
    shape of every model was, once: a 20-span beam's ten shapes 0.7 s -> past 60 s)."""
    from symtmm.model import Attachment, RigidBody
    from symtmm.modes import mode_shapes
    from symtmm.solve import solve

    beams = tuple(Beam(f"s{i + 1}", 1, 1, 1, x0=i, left="pinned" if i == 0 else "free",
                       right="pinned") for i in range(5))
    joints = tuple(RigidBody(f"pin{i}", (Attachment(f"s{i}", i), Attachment(f"s{i + 1}", i)))
                   for i in range(1, 5))
    model = Model(beams, bodies=joints)
    modes = mode_shapes(model, count=6, points=5, digits=15)
    assert [m.eigenvalue.lam for m in modes] == [e.lam for e in solve(model, count=6)]


@pytest.mark.parametrize("ar", _arithmetics(), ids=lambda ar: ar.name)
def test_a_doublings_middle_node_with_a_zero_pivot_is_undecided_not_an_error(ar):
    """The inertia of a chain's middle node by its leading minors: ``[[2, 1], [1, -3]]``
    has one negative eigenvalue, ``[[-1, 0], [0, -2]]`` two, and ``[[0, 1], [1, 0]]``'s
    zero pivot leaves that point undecided (mpmath divided by it: ZeroDivisionError)."""
    from symtmm.numeric.clamped import _negative_eigenvalues
    with ar:
        def entries(*values):
            return ar.array([ar.number(mpmath.mpf(v)) for v in values]) \
                if ar is not DOUBLE else np.array(values, dtype=float)
        S = [[entries(2, -1, 0), entries(1, 0, 1)], [entries(1, 0, 1), entries(-3, -2, 0)]]
        count, decided = _negative_eigenvalues(ar, S)
    assert decided.tolist() == [True, True, False]
    assert count[:2].tolist() == [1, 2]
