"""Long pieces: Euler–Bernoulli stretches whose waves are far shorter than they are.

A soft beam on a stiff foundation (``kw L**4 / EI`` of ``1e8`` and more) is cut into
long pieces (:func:`symtmm.numeric.plan.long_piece`) whose stiffness comes from the
closed forms (:func:`symtmm.numeric.stiffness.eb_closed_stiffness`). References: the
transfer matrix of the same piece at high precision (the ``U`` path, which loses
digits to the growth of the exponentials and is given far more than it loses), the
transfer-matrix walk's ``det R`` (the other formulation), the closed-form natural
frequencies of a pinned-pinned beam on a Winkler foundation, and the undamped search
on the frequency axis for a model whose dashpot cannot move.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from symtmm.elements import EulerBernoulliSegment
from symtmm.modelfile import loads
from symtmm.numeric import multiword
from symtmm.numeric import plan as plan_module
from symtmm.numeric.arith import DOUBLE, MP, Ball, ball_available
from symtmm.numeric.plan import NU_MAX, StiffnessPlan, plan_for
from symtmm.numeric.segments import condensed_stiffness, eb_constants, segment_matrix
from symtmm.numeric.stiffness import assemble, eb_closed_stiffness, factor, segment_stiffness
from symtmm.numeric.transfer import TransferPlan
from symtmm.numeric.transfer import delta as transfer_delta
from symtmm.results import decimal_string
from symtmm.solve import solve

# (EI, m, l, kw) and lam**2 of pieces far longer than NU_MAX: on a foundation below its
# cut-off (real x = -4 q**4, q = 20 and 60), above it (real x > 0, nu = 4.2), and off the
# axis (complex x, |nu| of about 40 and 110)
PIECES = [((1, 1, 1, 4 * 20**4), -1.0), ((2, 3, "1/2", 4 * 120**4 * 2 * 16), -5.0),
          ((1, 1, 1, 100), -(4.2**4 + 100)), ((1, 1, 1, 2 * 10**6), complex(3e5, 4e5)),
          ((1, 1, 1, 10**8), complex(-1e8, 1.4e8))]


def _reference(consts, lam2):
    """The piece's stiffness and det U12 from its transfer matrix at 1200 bits."""
    ar = MP(1200)
    with ar:
        point = ar.array([ar.number(mpmath.mpmathify(lam2))])
        U = segment_matrix(ar, EulerBernoulliSegment(*consts), point)[0]
        return segment_stiffness(U)


@pytest.mark.parametrize("consts, lam2", PIECES)
def test_a_long_piece_holds_every_digit_in_double_precision(consts, lam2):
    D, det = eb_closed_stiffness(DOUBLE, eb_constants(DOUBLE, [consts]),
                                 np.array([lam2]), threshold=NU_MAX**4)
    E, det_ref = _reference(consts, lam2)
    for i in range(4):
        row = max(abs(complex(E[i, j])) for j in range(4))
        for j in range(4):
            assert abs(complex(D[0, 0, i, j]) - complex(E[i, j])) <= 1e-13 * row
    assert abs(complex(det[0, 0]) / complex(det_ref) - 1) < 1e-12


@pytest.mark.parametrize("consts, lam2", [p for p in PIECES if isinstance(p[1], float)])
def test_a_long_piece_on_the_axis_stays_real_in_mpmath(consts, lam2):
    """A real point gives real mpmath numbers (the LDL^T counts their signs), also above
    the cut-off, where mpmath's fourth root is complex."""
    ar = MP(200)
    with ar:
        point = ar.array([ar.number(mpmath.mpf(lam2))])
        D, det = eb_closed_stiffness(ar, eb_constants(ar, [consts]), point, threshold=NU_MAX**4)
    _, det_ref = _reference(consts, lam2)
    assert all(isinstance(v, ar.ctx.mpf) for v in list(D.reshape(-1)) + [det[0, 0]])
    assert abs(det[0, 0] / mpmath.re(det_ref) - 1) < mpmath.mpf(10) ** -50


@pytest.mark.skipif(not ball_available(), reason="python-flint is not installed")
@pytest.mark.parametrize("consts, lam2", PIECES)
def test_a_long_piece_in_balls_holds_its_value(consts, lam2):
    ar = Ball(200)
    with ar:
        point = ar.array([ar.number(mpmath.mpmathify(lam2))])
        D, det = eb_closed_stiffness(ar, eb_constants(ar, [consts]), point,
                                     threshold=NU_MAX**4)
    E, det_ref = _reference(consts, lam2)
    mpmath.mp.prec = 400
    flint = ar.flint

    def holds(ball, exact):
        # the ball holds the 1200-bit value (within its rounding to 400 bits), and is
        # narrow: 200 bits lose a few to the exponentials
        ball = flint.acb(ball)
        mid = mpmath.mpc(mpmath.mpf(ball.real.mid().str(120, radius=False)),
                         mpmath.mpf(ball.imag.mid().str(120, radius=False)))
        rad = mpmath.mpf(ball.real.rad()) + mpmath.mpf(ball.imag.rad())
        exact = mpmath.mpmathify(exact)
        return abs(mid - exact) <= rad + abs(exact) * mpmath.mpf(2) ** -300 and \
            rad <= abs(exact) * mpmath.mpf(10) ** -45

    for i in range(4):
        row = max(abs(mpmath.mpmathify(E[i, j])) for j in range(4))
        for j in range(4):
            # (an entry exp(-|nu|) of its row's largest: narrow beside the row)
            assert holds(D[0, 0, i, j], E[i, j]) or abs(mpmath.mpmathify(E[i, j])) < 1e-30 * row
    assert holds(det[0, 0], det_ref)


SOFT_ON_FOUNDATION = """
[[beam]]
name = "soft"
EI = {EI}
m = 1.0
L = 10.0
left = "pinned"
right = "pinned"
kw = 10000.0

[[spring]]
between = ["soft", "ground"]
x = 0.0
k = 0
c = 3.0
"""


def _winkler(EI, n):
    """omega_n of a pinned-pinned beam on a Winkler foundation (m = 1, L = 10, kw = 1e4)."""
    with mpmath.workdps(40):
        return +mpmath.sqrt(mpmath.mpf(EI) * (n * mpmath.pi / 10) ** 4 + 10000)


def _on_the_axis(got, references):
    """Simple eigenvalues on the imaginary axis, ``i`` times the references to 15 digits."""
    assert [e.multiplicity for e in got] == [1] * len(references)
    for e, ref in zip(got, references):
        lam = complex(e.lam)
        assert lam.real == 0
        assert abs(lam.imag / float(ref) - 1) < 2e-15


def _check_winkler(EI, count):
    model = loads(SOFT_ON_FOUNDATION.format(EI=EI), source="soft.toml")
    _on_the_axis(solve(model, count=count, digits=15),
                 [_winkler(EI, n) for n in range(1, count + 1)])


def test_long_pieces_cut_a_soft_beam_on_a_stiff_foundation(monkeypatch):
    """The plan of its damped search (|Im lam| up to its cut-off) has long pieces and at
    most half the freedoms of short ones; the plan of an ordinary beam has none."""
    model = loads(SOFT_ON_FOUNDATION.format(EI="0.1"), source="soft.toml").require_numeric()
    plan_module.clear_plans()
    long = plan_for(model, 400.0, top=100.4)
    assert long.long and long.top2 < long.radius
    monkeypatch.setattr(plan_module, "LONG_FROM", float("inf"))
    short = StiffnessPlan(model, long.radius, top2=long.top2)
    assert not short.long and 2 * long.n <= short.n
    plain = loads(SOFT_ON_FOUNDATION.format(EI=1).replace("kw = 10000.0", ""), source="p.toml")
    assert not plan_for(plain.require_numeric(), 400.0, top=100.4).long


@pytest.mark.skipif(not multiword.ENABLED, reason="the compiled kernel was not built")
@pytest.mark.parametrize("damped", [False, True])
def test_the_compiled_kernel_builds_long_plans_in_double_precision(damped, monkeypatch):
    """A double batch of a plan with long pieces is built by the compiled kernel, the long
    kinds' values given by numpy's closed forms: its band is numpy's, and its counts about
    the closed-form frequencies (kw L**4 / EI = 1e9) are the modes below each point."""
    text = SOFT_ON_FOUNDATION.format(EI="0.1")
    model = loads(text if damped else text.replace("c = 3.0\n", "c = 0\n"),
                  source="soft.toml").require_numeric()
    plan = plan_for(model, 400.0, top=100.4)
    assert plan.long
    assert multiword._double_tables(plan)["given"] is not None
    omega = np.array([float(_winkler("0.1", n)) * (1 + s * 1e-9)
                      for n in (1, 2, 3, 8) for s in (-1, 1)] + [50.0, 100.3])
    lam = (-0.5 + 1j) * omega if damped else 1j * omega
    lam2 = lam * lam if damped else (lam * lam).real
    dash = lam if damped else None
    assert multiword.serves_double(plan, lam2, dash)
    K, det12, ok = multiword.double_band(plan, lam2, dash)
    K0, det0 = assemble(plan, DOUBLE, lam2, dash)
    assert ok.all()
    scale = np.abs(K0).max(axis=(1, 2))[:, None, None]
    assert np.all(np.abs(K - K0) <= 1e-12 * scale)
    assert np.all(np.abs(det12 - det0) <= 1e-12 * np.abs(det0))
    logabs, _, counts, ok = multiword.double_summary(plan, lam2, dash)
    assert ok.all()
    if not damped:
        # (the plan serves |Im lam| <= 100.4: beyond, its pieces' clamped modes)
        below = [sum(1 for n in range(1, 40) if _winkler("0.1", n) < w) for w in omega]
        assert counts.tolist() == below and below[-1] > 10
    monkeypatch.setattr(multiword, "ENABLED", False)
    numpy_fa = factor(plan, DOUBLE, lam2, dash)
    assert counts.tolist() == numpy_fa.counts().tolist()
    assert np.allclose(logabs, numpy_fa.log_delta()[0], rtol=1e-12)


def _agrees_with_det_r(model, plan, points, bits: int = 1500, digits: int = 45):
    """Delta of ``plan`` at ``points`` (mpmath at 200 bits) against det R of the transfer
    walk at ``bits``, to ``digits``."""
    ar = MP(200)
    with ar:
        lam = ar.array([ar.number(z) for z in points])
        got = factor(plan, ar, lam * lam, lam).delta()
    ref_ar = MP(bits)
    with ref_ar:
        lam = ref_ar.array([ref_ar.number(z) for z in points])
        ref = transfer_delta(TransferPlan(model), ref_ar, lam=lam, lam2=lam * lam)
    for g, r in zip(got, ref):
        assert abs(mpmath.mpc(g) / mpmath.mpc(r) - 1) < mpmath.mpf(10) ** -digits


def test_delta_of_long_pieces_is_det_r_of_the_transfer_walk():
    """Delta of the stiffness plan with long pieces, at complex points, against det R of
    the transfer-matrix walk (the other formulation) at 1000 bits."""
    model = loads(SOFT_ON_FOUNDATION.format(EI="0.1"), source="soft.toml").require_numeric()
    plan = plan_for(model, 400.0, top=100.4)
    assert plan.long
    _agrees_with_det_r(model, plan, [mpmath.mpc(-300, 40), mpmath.mpc(-2, 100.2),
                                     mpmath.mpc(-0.5, 99.9)], bits=1000, digits=50)


def test_an_inert_dashpot_on_a_soft_beam_on_a_stiff_foundation():
    """The damped search (its dashpot at a pinned end never moves) gives the beam's
    closed-form natural frequencies, kw L**4 / EI = 1e8."""
    _check_winkler("1", 4)


@pytest.mark.slow
def test_an_inert_dashpot_on_a_softer_beam_on_a_stiff_foundation():
    """kw L**4 / EI = 1e10: its first modes within 1e-9 of one another (relative); the
    search ran past a 100 s budget with short pieces, now about 20 s."""
    _check_winkler("0.01", 4)


# a campaign's model (seed 21226): a soft heavy beam on a foundation (b2) whose modes
# crowd at its cut-off, its dashpot between two fixed points; 57 s of a 60 s budget in
# dense determinants of 283 freedoms
CAMPAIGN_21226 = """
[[beam]]
name = "b0"
EI = 0.0132
m = 0.408
L = 0.72
left = "pinned"
right = "clamped"
kw = 46.3

[[beam]]
name = "b1"
EI = 53.4
m = 2.37
L = 0.0917
left = "sliding"
right = "sliding"
kw = 3.85

[[beam]]
name = "b2"
EI = 0.0184
m = 3180.0
L = 9.92
left = "clamped"
right = "sliding"
kw = 2080.0

[[spring]]
between = ["b2", "ground"]
x = 9.92
k = 1850000.0

[[spring]]
between = ["b2", "b0"]
x = 0.0
k = 0
c = 6.0

[[spring]]
between = ["b2", "b1"]
x = 0.00917
k = 459000000.0
"""


@pytest.mark.slow
def test_a_campaign_model_of_crowded_modes_at_a_cut_off():
    """Reference: the same model without its dashpot, on the frequency axis."""
    from symtmm.deadline import time_budget

    damped = loads(CAMPAIGN_21226, source="m21226.toml")
    undamped = loads(CAMPAIGN_21226.replace("c = 6.0\n", ""), source="m21226.toml")
    with time_budget(20.0):
        got = solve(damped, count=2, digits=15)
    ref = solve(undamped, count=2, digits=15)
    assert [(str(e), e.multiplicity) for e in got] == [(str(e), e.multiplicity) for e in ref]


# a campaign's model (seed 25056, its unjoined beams left out): a soft long beam on a
# foundation (b0, kw / m = 315) joined by a spring with a dashpot to a heavy beam whose
# modes lie just below b0's cut-off: b0's pieces, their clamped modes held above the range
# by the foundation alone, were cut 15 times shorter than their growth asks, and the
# proofs' dense determinants of them ran past the 60 s budget
CAMPAIGN_25056 = """
[[beam]]
name = "b0"
EI = 0.0092
m = 2.26
L = 72.9
left = "sliding"
right = "sliding"
kw = 711.0

[[beam]]
name = "b3"
EI = 24400.0
m = 859.0
L = 5.79
left = "pinned"
right = "free"
kw = 209000.0

[[spring]]
between = ["b3", "b0"]
x = 5.79
k = 121000000.0
c = 0.266
"""


@pytest.mark.slow
def test_a_campaign_model_of_modes_just_below_a_cut_off():
    """Reference: the model without its dashpot, on the frequency axis (the dashpot's
    damping ratios are about 1e-18: the frequencies agree far beyond 15 digits)."""
    damped = loads(CAMPAIGN_25056, source="m25056.toml")
    undamped = loads(CAMPAIGN_25056.replace("c = 0.266\n", ""), source="m25056.toml")
    got = solve(damped, count=3, digits=15)
    ref = solve(undamped, count=3, digits=15)
    assert [e.multiplicity for e in got] == [e.multiplicity for e in ref] == [1, 1, 1]
    for e, r in zip(got, ref):
        lam = complex(e.lam)
        assert -1e-12 * abs(lam) < lam.real <= 0
        assert decimal_string(e.lam.imag, 15) == decimal_string(r.omega, 15)


# -- long pieces of the other theories: chains of short ones, condensed -------------------------
@pytest.mark.parametrize("kw, lam2", [(0, complex(-3e4, 2e3)), (4 * 20**4, -5.0),
                                      (2 * 10**6, complex(3e5, 4e5))])
def test_a_condensed_chain_is_the_whole_piece(kw, lam2):
    """2**5 Euler–Bernoulli pieces of 1/32, condensed by doubling, against the closed forms
    of the piece of length 1 (its stiffness and its det U12), in doubles and in balls."""
    D1, d1 = eb_closed_stiffness(DOUBLE, eb_constants(DOUBLE, [(1, 1, 1, kw)]),
                                 np.array([lam2]), threshold=NU_MAX**4)
    Ds, ds = eb_closed_stiffness(DOUBLE, eb_constants(DOUBLE, [(1, 1, "1/32", kw)]),
                                 np.array([lam2]), threshold=NU_MAX**4)
    Dc, dc = condensed_stiffness(DOUBLE, Ds[:, 0], ds[:, 0], 5)
    for i in range(4):
        row = np.max(np.abs(D1[0, 0, i]))
        assert np.max(np.abs(Dc[0, i] - D1[0, 0, i])) <= 1e-11 * row
    assert abs(dc[0] / d1[0, 0] - 1) < 1e-10
    ar = Ball(200)
    with ar:
        point = ar.array([ar.number(mpmath.mpmathify(lam2))])
        Ds, ds = eb_closed_stiffness(ar, eb_constants(ar, [(1, 1, "1/32", kw)]), point,
                                     threshold=NU_MAX**4)
        Dc, dc = condensed_stiffness(ar, Ds[:, 0], ds[:, 0], 5)
        D1, d1 = eb_closed_stiffness(ar, eb_constants(ar, [(1, 1, 1, kw)]), point,
                                     threshold=NU_MAX**4)
        flint = ar.flint
        for i in range(4):
            for j in range(4):
                assert flint.acb(Dc[0, i, j]).overlaps(flint.acb(D1[0, 0, i, j]))
        assert flint.acb(dc[0]).overlaps(flint.acb(d1[0, 0]))
        assert float(abs(flint.acb(dc[0])).rad()) < 1e-40 * float(abs(flint.acb(d1[0, 0])).mid())


SHEAR_ON_FOUNDATION = """
[[beam]]
name = "beam"
EI = 1.0
m = 1.0
L = 10.0
left = "pinned"
right = "pinned"
theory = "{theory}"
rhoI = 0.01
{kGA}
kw = 10000.0
{dashpot}
"""

_DASHPOT = """
[[spring]]
between = ["beam", "ground"]
x = 0.0
k = 0
c = 3.0
"""


def _simply_supported(n, kGA=None):
    """omega_n of a pinned-pinned Rayleigh (kGA None) or Timoshenko beam on a Winkler
    foundation (EI = m = 1, rhoI = 1/100, L = 10, kw = 1e4): the mode ``sin(k x)``,
    ``k = n pi / L``; Timoshenko's the lower root of the 2x2 determinant in ``omega**2``."""
    with mpmath.workdps(40):
        k = n * mpmath.pi / 10
        EI, m, rhoI, kw = 1, 1, mpmath.mpf(1) / 100, 10000
        if kGA is None:
            return +mpmath.sqrt((EI * k**4 + kw) / (m + rhoI * k**2))
        kGA = mpmath.mpf(kGA)
        # (kGA k**2 + kw - m w2)(EI k**2 + kGA - rhoI w2) - (kGA k)**2 = 0
        a = m * rhoI
        b = -(m * (EI * k**2 + kGA) + rhoI * (kGA * k**2 + kw))
        c = (kGA * k**2 + kw) * (EI * k**2 + kGA) - (kGA * k) ** 2
        return +mpmath.sqrt((-b - mpmath.sqrt(b * b - 4 * a * c)) / (2 * a))


# beams of other theories on foundations: Rayleigh, Timoshenko, in tension and compression
SPECTRUM_BOTTOMS = [dict(EI=1.0, m=1.0, kw=1e4, rhoI=0.01),
                    dict(EI=1.0, m=1.0, kw=1e4, rhoI=0.01, kGA=500.0),
                    dict(EI=0.1, m=2.0, kw=500.0, rhoI=0.003, kGA=2.0, N=3.0),
                    dict(EI=1.0, m=1.0, kw=1e3, rhoI=0.02, N=-5.0)]


def _dispersion_bottom(EI, m, kw, rhoI, kGA=None, N=0.0):
    """``(omega**2, k)`` at the bottom of the infinite beam's spectrum: the least eigenvalue
    of the waves ``exp(i k x)``' symbol (``M**-1/2 A(k) M**-1/2``, numpy's ``eigvalsh``)
    over a fine grid of ``k``, refined about the grid's least by scipy."""
    from scipy.optimize import minimize_scalar

    def least(k):
        if kGA is None:
            return (EI * k**4 + N * k**2 + kw) / (m + rhoI * k**2)
        A = np.array([[(kGA + N) * k**2 + kw, -1j * kGA * k], [1j * kGA * k, kGA + EI * k**2]])
        s = np.diag([m ** -0.5, rhoI ** -0.5])
        return np.linalg.eigvalsh(s @ A @ s)[0]

    grid = np.concatenate([[0.0], np.geomspace(1e-3, 1e4, 20001)])
    values = np.array([least(k) for k in grid])
    i = int(np.argmin(values))
    lo, hi = grid[max(i - 1, 0)], grid[min(i + 1, grid.size - 1)]
    best = minimize_scalar(least, bounds=(lo, hi), method="bounded",
                           options={"xatol": 1e-12 * max(hi, 1e-9)})
    return (best.fun, best.x) if best.fun < values[i] else (values[i], grid[i])


@pytest.mark.parametrize("beam", SPECTRUM_BOTTOMS)
def test_the_length_free_bound_is_the_bottom_of_the_infinite_beams_spectrum(beam):
    """The bound of a piece of any length (the symbol positive definite below it) against
    the least frequency of the infinite beam's waves, minimised over their wave number."""
    from symtmm.elements.theories import BeamSegment

    bottom, _ = _dispersion_bottom(**beam)
    bound = BeamSegment(beam["EI"], beam["m"], 1, kw=beam["kw"], N=beam.get("N", 0),
                        rhoI=beam["rhoI"], kGA=beam.get("kGA")).length_free_bound
    assert bottom * (1 - 1e-4) <= bound <= bottom * (1 + 1e-12)


@pytest.mark.slow
@pytest.mark.parametrize("beam", SPECTRUM_BOTTOMS)
def test_clamped_pieces_of_any_length_have_no_mode_below_the_length_free_bound(beam):
    """A converged finite-element model (an independent code) of clamped-clamped pieces
    half a wave to twenty waves (of the spectrum's bottom) long: the first mode never below
    the bound, and the long pieces' within 2 % above it (the bound is the one their modes
    crowd to)."""
    from symtmm.elements.theories import BeamSegment
    from symtmm.fe import fe_converged

    _, k = _dispersion_bottom(**beam)
    wave = 2 * np.pi / k if k > 0 else 10.0
    bound = BeamSegment(beam["EI"], beam["m"], 1, kw=beam["kw"], N=beam.get("N", 0),
                        rhoI=beam["rhoI"], kGA=beam.get("kGA")).length_free_bound
    for waves in (0.5, 4, 20):
        L = waves * wave
        piece = dict(name="p", L=L, x0=0.0, left="clamped", right="clamped", **beam)
        out = fe_converged([piece], [], max(6, int(6 * waves)), count=1)
        omega2 = out["omega"][0] ** 2
        assert omega2 * (1 + 4 * out["error"][0] / out["omega"][0]) >= bound
        if waves == 20:
            assert omega2 <= 1.02 * bound


@pytest.mark.parametrize("theory, kGA, damped", [("rayleigh", None, True),
                                                 ("timoshenko", 500, False)])
def test_a_beam_of_another_theory_on_a_stiff_foundation(theory, kGA, damped):
    """Rayleigh (with a dashpot at a pinned end, which never moves: the damped search) and
    Timoshenko (undamped) pinned-pinned beams on a foundation, kw L**4 / EI = 1e8, against
    their closed forms; their plans hold condensed long pieces."""
    text = SHEAR_ON_FOUNDATION.format(theory=theory, kGA="" if kGA is None else f"kGA = {kGA}",
                                      dashpot=_DASHPOT if damped else "")
    model = loads(text, source="beam.toml")
    # (the rotary inertia lowers the modes of short waves below the foundation's cut-off,
    # 100: the lowest are those of about 20 half-waves, at 91.03)
    _on_the_axis(solve(model, count=3, digits=15),
                 sorted(_simply_supported(n, kGA) for n in range(1, 200))[:3])
    # (a plan of each search: the damped one's rectangle reaches Re lam = -250)
    plan = plan_for(model.require_numeric(), 250.0 if damped else 100.0, top=100.0)
    assert any(family == "condensed" for family, _ in plan.kinds)


@pytest.mark.skipif(not multiword.ENABLED, reason="the compiled kernel was not built")
@pytest.mark.parametrize("theory, kGA", [("rayleigh", None), ("timoshenko", 500)])
def test_the_compiled_kernel_builds_condensed_plans_in_double_precision(theory, kGA,
                                                                       monkeypatch):
    """A double batch of a plan with condensed pieces is built by the compiled kernel,
    their values given by numpy: its band is numpy's, and its counts about the closed-form
    frequencies are the modes below each point."""
    text = SHEAR_ON_FOUNDATION.format(theory=theory, kGA="" if kGA is None else f"kGA = {kGA}",
                                      dashpot="")
    model = loads(text, source="beam.toml").require_numeric()
    plan = plan_for(model, 100.0, top=100.0)
    assert any(family == "condensed" for family, _ in plan.kinds)
    modes = sorted(float(_simply_supported(n, kGA)) for n in range(1, 200))
    omega = np.array([w * (1 + s * 1e-9) for w in modes[:3] for s in (-1, 1)] + [50.0, 99.0])
    lam2 = -omega * omega
    assert multiword.serves_double(plan, lam2, None)
    K, det12, ok = multiword.double_band(plan, lam2)
    K0, det0 = assemble(plan, DOUBLE, lam2)
    assert ok.all()
    scale = np.abs(K0).max(axis=(1, 2))[:, None, None]
    assert np.all(np.abs(K - K0) <= 1e-12 * scale)
    assert np.all(np.abs(det12 - det0) <= 1e-12 * np.abs(det0))
    _, _, counts, ok = multiword.double_summary(plan, lam2)
    below = [sum(1 for w in modes if w < x) for x in omega]
    assert ok.all() and counts.tolist() == below and below[-1] > 3
    monkeypatch.setattr(multiword, "ENABLED", False)
    assert factor(plan, DOUBLE, lam2).counts().tolist() == below


def test_delta_of_condensed_pieces_is_det_r_of_the_transfer_walk():
    model = loads(SHEAR_ON_FOUNDATION.format(theory="timoshenko", kGA="kGA = 500",
                                             dashpot=_DASHPOT), source="beam.toml")
    model = model.require_numeric()
    plan = plan_for(model, 400.0, top=100.4)
    assert any(family == "condensed" for family, _ in plan.kinds)
    _agrees_with_det_r(model, plan, [mpmath.mpc(-300, 40), mpmath.mpc(-2, 100.2),
                                     mpmath.mpc(-0.5, 99.9)])


# a campaign's model (seed 22015): a Rayleigh beam on a foundation, kw L**4 / EI = 7e9,
# joined to a short beam by a stiff spring with a dashpot and by a pure dashpot: 33 s in
# dense determinants of about 240 freedoms, now a few seconds
CAMPAIGN_22015 = """
[[beam]]
name = "b0"
EI = 1.63
m = 0.128
L = 23.1
left = "free"
right = "free"
theory = "rayleigh"
rhoI = 0.00325
kw = 41400.0

[[beam]]
name = "b1"
EI = 0.00389
m = 133.0
L = 0.766
left = "pinned"
right = "clamped"
kw = 159000.0

[[spring]]
between = ["b0", "b1"]
x = 0.5898
k = 0.0263
kind = "rotational"

[[spring]]
between = ["b0", "b1"]
x = 0.0766
k = 17800000.0
c = 0.0344

[[spring]]
between = ["b0", "b1"]
x = 0.5898
k = 0
c = 0.0557
"""


@pytest.mark.slow
def test_a_campaign_model_of_a_rayleigh_beam_on_a_stiff_foundation():
    """Each eigenvalue a zero of det R of the transfer walk (the other formulation) at 1500
    bits: |det R| there below 1e-5 of its value a relative 1e-9 away (a simple zero: the
    eigenvalue within 1e-14 of it, relative)."""
    from symtmm.deadline import time_budget

    model = loads(CAMPAIGN_22015, source="m22015.toml")
    with time_budget(20.0):
        got = solve(model, count=2, digits=15)
    assert len(got) == 2
    ar = MP(1500)
    plan = TransferPlan(model.require_numeric())
    with ar:
        for e in got:
            z = mpmath.mpc(e.lam)
            near = [z, z + abs(z) * mpmath.mpf("1e-9"), z + 1j * abs(z) * mpmath.mpf("1e-9")]
            lam = ar.array([ar.number(p) for p in near])
            at, *beside = transfer_delta(plan, ar, lam=lam, lam2=lam * lam)
            assert abs(at) < mpmath.mpf("1e-5") * min(abs(b) for b in beside)


JOINED_BY_A_STIFF_LAYER = """
[[beam]]
name = "a"
EI = 1.0
m = 1.0
L = 10.0
left = "pinned"
right = "pinned"

[[beam]]
name = "b"
EI = 1.0
m = 1.0
L = 10.0
left = "pinned"
right = "pinned"

[[layer]]
between = ["a", "b"]
k = 1000000.0
{dashpot}
"""


@pytest.mark.parametrize("damped", [False, True])
def test_two_beams_joined_by_a_stiff_layer(damped):
    """Two equal pinned-pinned beams joined by a layer 2e10 times their EI / L**4: the
    modes in phase leave the layer idle, omega_n = (n pi / L)**2 (closed form), those in
    opposition lie above sqrt(2 k). With a dashpot at a pinned end (which never moves) the
    damped search finds the same. The plans hold condensed pieces of the joined beams."""
    dashpot = '[[spring]]\nbetween = ["a", "ground"]\nx = 0.0\nk = 0\nc = 2.0\n'
    model = loads(JOINED_BY_A_STIFF_LAYER.format(dashpot=dashpot if damped else ""),
                  source="layer.toml")
    _on_the_axis(solve(model, count=4, digits=15), [(n * mpmath.pi / 10) ** 2 for n in range(1, 5)])
    plan = plan_for(model.require_numeric(), 2.0)
    assert [family for family, _ in plan.kinds] == ["condensed"]
    assert plan.kinds[0][1][0][0] == "coupled"


def test_delta_of_condensed_layered_pieces_is_det_r_of_the_transfer_walk():
    model = loads(JOINED_BY_A_STIFF_LAYER.format(dashpot=""), source="layer.toml")
    model = model.require_numeric()
    plan = plan_for(model, 2.0)
    assert plan.kinds[0][0] == "condensed"
    _agrees_with_det_r(model, plan, [mpmath.mpc(-1, 0.5), mpmath.mpc(0, 1.3),
                                     mpmath.mpc(-0.01, 0.2)])


@pytest.mark.parametrize("damped", [False, True])
def test_free_beams_joined_by_a_stiff_layer_keep_their_rigid_modes(damped):
    """The same pair free-free: the static null space of its condensed joined pieces (a
    traceback before) holds the two rigid motions in phase, then the free-free modes in
    phase, (beta_n / L)**2 with beta_1, beta_2 = 4.7300407448627, 7.8532046240958 (the roots
    of cos b cosh b = 1). A dashpot between the beams, which moves in opposition only,
    leaves them to the damped search as they are."""
    dashpot = '[[spring]]\nbetween = ["a", "b"]\nx = 3.0\nk = 0\nc = 2.0\n'
    text = JOINED_BY_A_STIFF_LAYER.format(dashpot=dashpot if damped else "")
    model = loads(text.replace('"pinned"', '"free"'), source="layer.toml")
    got = solve(model, count=4, digits=15)        # (the rigid motions count twice)
    assert [e.multiplicity for e in got] == [2, 1, 1]
    assert complex(got[0].lam) == 0
    mpmath.mp.dps = 30
    roots = [mpmath.findroot(lambda b: mpmath.cos(b) * mpmath.cosh(b) - 1, b0) for b0 in (4.73, 7.85)]
    _on_the_axis(got[1:], [(b / 10) ** 2 for b in roots])
