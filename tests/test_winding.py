"""The proved count of damped eigenvalues: winding numbers in ball arithmetic, and jets.

References, none of them from symtmm:

* a pinned-pinned beam with grounded dashpots: its classical characteristic function
  (Green's function, tests/damped_reference.py) and its roots followed from the
  undamped ones in mpmath;
* the paper's example 4 from its decoupled families (tests/damped_reference.py);
* an undamped beam's eigenvalues, exactly ``(n pi)**2 i``: a contour through them must
  leave the count unproved, not wrong;
* derivatives of the dynamic stiffness by mpmath's numerical differentiation of the
  same entries at 40 digits (jets are automatic differentiation: a second method);
* the closed-form dynamic stiffness against the one through the transfer matrix at 50
  digits, and the fourth root of a ball against the roots of points inside it.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
from damped_reference import ex4_reference, pp_damped_roots

from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load
from symtmm.numeric.arith import MP, Ball
from symtmm.numeric.evaluator import Evaluator
from symtmm.numeric.segments import eb_constants
from symtmm.numeric.stiffness import eb_closed_stiffness, segment_stiffness
from symtmm.roots.contour import Rectangle
from symtmm.roots.winding import proved_count
from symtmm.solve import solve

flint = pytest.importorskip("flint")

PP = dict(left="pinned", right="pinned")
SUPPORTS = [(0.25, 0, 0.5), (0.75, 30, 2)]


def _dashpot_beam():
    return Model((Beam("b", 1, 1, 1, **PP),),
                 tuple(Spring("b", "ground", x, k, c) for x, k, c in SUPPORTS))


@pytest.fixture(scope="module")
def dashpot_roots():
    return pp_damped_roots(1, 1, 1, SUPPORTS, 130.0)


def test_counts_in_rectangles_match_the_reference(dashpot_roots):
    ev = Evaluator(_dashpot_beam(), 140.0)
    roots = [complex(z) for z in dashpot_roots]
    rects = [Rectangle(-10.0, 1.0, 0.0, 130.0), Rectangle(-10.0, 1.0, 20.0, 60.0),
             Rectangle(-10.0, 1.0, 50.0, 80.0), Rectangle(-30.0, -0.05, 30.0, 130.0)]
    for rect in rects:
        expected = sum(rect.contains(z) for z in roots)
        got = proved_count(ev, rect)
        assert got.count == expected, (rect, got, roots)
    # a strip about the real axis: none (no overdamped mode), walked on its upper half
    assert proved_count(ev, Rectangle(-60.0, 1.0, -5.0, 5.0, symmetric=True)).count == 0


def test_third_order_model_counts_alike(dashpot_roots):
    """The Taylor model of order 3 (third-order jets over the segments) proves the same."""
    ev = Evaluator(_dashpot_beam(), 140.0)
    rect = Rectangle(-10.0, 1.0, 20.0, 60.0)
    expected = sum(rect.contains(complex(z)) for z in dashpot_roots)
    assert proved_count(ev, rect, order=3).count == expected


def test_a_contour_through_a_zero_stays_unproved():
    """Undamped: the zeros (n pi)^2 i lie exactly on the line Re lam = 0."""
    ev = Evaluator(Model((Beam("b", 1, 1, 1, **PP),)), 50.0)
    got = proved_count(ev, Rectangle(-3.0, 0.0, 5.0, 15.0), max_segments=400)
    assert got.count is None and got.reason


def test_example_4_region_proved_and_complete():
    """The count of the region proved, and equal to the decoupled families' roots in it."""
    model = load("examples/paper_ex4_damped.toml")
    W, S = 400.0, 800.0
    spectrum = solve(model, omega_max=W, digits=12, prove_count=True)
    assert any("count in the search region is proved" in n for n in spectrum.notes)
    ref = [z for z, _ in ex4_reference(20) if float(z.imag) <= W and float(z.real) >= -S]
    assert sum(e.multiplicity for e in spectrum) == len(ref)
    for e, z in zip(sorted(spectrum, key=lambda e: float(e.lam.imag)), ref):
        assert abs(complex(e.lam) - complex(z)) <= 1e-9 * abs(complex(z))


def test_grid_methods_cannot_prove_a_count():
    from symtmm.errors import ModelError
    with pytest.raises(ModelError, match="grid search"):
        solve(_dashpot_beam(), omega_max=50, method="fmin2d", prove_count=True)


# -- the pieces --------------------------------------------------------------------------


def _damped_rods():
    from symtmm.model import rod
    return Model((rod("a", EA=900, m=1, L=1, left="fixed", right="free"),
                  rod("s", EA=400, m=2, L=1, GJ=300, rhoIp="1/2", left="free",
                      right="fixed-axial")),
                 (Spring("a", "s", "3/5", k=50, c=2), Spring("s", "ground", 1, 4, 1,
                                                             kind="rotational")))


@pytest.mark.parametrize("build", [_dashpot_beam, _damped_rods])
def test_jets_enclose_the_derivatives_of_the_stiffness(build):
    """K'(c) from first-order jets at a point, and K''/2 from second-order jets over a box
    holding c, against mpmath's numerical derivatives of the same entries (a beam; rods,
    their pieces on both sides of the series' |z| = 1)."""
    from symtmm.numeric.jet import BallJet
    from symtmm.numeric.stiffness import assemble, dense

    model = build().require_numeric()
    ev = Evaluator(model, 100.0)
    plan = ev.plan(100.0)
    c = complex(-2.5, 37.0)
    mp = MP(160)

    def entry(i, j):
        def f(z):
            with mp:
                w = mp.ctx.mpc(z.real, z.imag)         # (at the context's 160 bits)
                K, _ = assemble(plan, mp, mp.array([w * w]), mp.array([w]))
            return mpmath.mpmathify(mp.to_mpmath(dense(plan, K)[0][i, j]))
        return f

    point, box = BallJet(120, order=1), BallJet(120, order=2)
    with point:
        lam = np.array([point.variable(flint.acb(c.real, c.imag))], dtype=object)
        Kp = dense(plan, assemble(plan, point, lam * lam, lam)[0])[0]
    with box:
        lam = np.array([box.variable(flint.acb(flint.arb(c.real, 0.5), flint.arb(c.imag, 0.5)))],
                       dtype=object)
        Kb = dense(plan, assemble(plan, box, lam * lam, lam)[0])[0]
    n = plan.n
    checked = 0
    with mpmath.workdps(48):
        z = mpmath.mpc(c.real, c.imag)
        h = mpmath.mpf(10) ** -14
        for i in range(n):
            for j in range(i, n):
                if isinstance(Kp[i, j], int):
                    continue
                f = entry(i, j)
                lo, mid, hi = f(z - h), f(z), f(z + h)
                # central differences at 160 bits: errors ~h**2 |f(3)| and 2**-160 / h**2
                d1 = (hi - lo) / (2 * h)
                d2 = (hi - 2 * mid + lo) / (2 * h * h)
                for jet, ref in ((Kp[i, j].c[1], d1), (Kb[i, j].c[2], d2)):
                    tol = float(abs(ref)) * 1e-12 + 1e-30
                    if isinstance(jet, int):            # a coefficient known to vanish
                        assert jet == 0 and abs(ref) <= 1e-20 * float(abs(mid)), (i, j, ref)
                        continue
                    ball = flint.acb(flint.arb(float(ref.real), tol),
                                     flint.arb(float(ref.imag), tol))
                    assert jet.overlaps(ball), (i, j, jet, ref)
                checked += 1
    assert checked >= n


def test_closed_form_stiffness_is_the_transfer_one():
    """|x| >= 1 and below: the closed forms in nu against the U path, 50 digits."""
    ar = MP.from_digits(50)
    consts = eb_constants(ar, [(2, 3, "7/10", 0), (1, 1, "1/4", 5)])
    with ar:
        lam2 = ar.array([ar.number(v) for v in ((0.3 + 5j) ** 2, (2 + 40j) ** 2, -1e-3)])
        D1, d1 = segment_stiffness(__import__("symtmm.numeric.segments", fromlist=["x"])
                                   .eb_matrices(ar, consts, lam2))
        D2, d2 = eb_closed_stiffness(ar, consts, lam2)
    scale = max(abs(complex(v)) for v in D1.reshape(-1))
    assert max(abs(complex(a - b)) for a, b in zip(D1.reshape(-1), D2.reshape(-1))) < 1e-40 * scale
    assert all(abs(complex(a / b) - 1) < 1e-40 for a, b in zip(d1.reshape(-1), d2.reshape(-1)))


def test_fourth_root_of_a_ball_holds_the_roots_of_its_points():
    ar = Ball(64)
    rng = np.random.default_rng(4)
    for _ in range(40):
        m = complex(*rng.normal(size=2)) * 10 ** rng.uniform(-2, 3)
        r = abs(m) * 10 ** rng.uniform(-6, -0.5)
        with ar:
            ball = flint.acb(flint.arb(m.real, r / 2), flint.arb(m.imag, r / 2))
            root = ar.root4(np.array([ball], dtype=object))[0]
        for _ in range(5):
            p = m + complex(*rng.uniform(-r / 2, r / 2, size=2))
            # the root the ball stands for: the branch of its midpoint, continued
            ref = complex(ar.root4(np.array([flint.acb(p.real, p.imag)], dtype=object))[0].mid())
            assert any(root.overlaps(flint.acb(ref * 1j**k)) for k in range(4)), (m, r, p)
    # and it is not much wider than the ball needs: |d root| = r / (4 |m|^(3/4))
    m, r = complex(25, -0.2), 0.05
    with ar:
        root = ar.root4(np.array([flint.acb(flint.arb(m.real, r), flint.arb(m.imag, r))],
                                 dtype=object))[0]
    assert float(root.real.rad()) < 3 * math.sqrt(2) * r / (4 * abs(m) ** 0.75)


def test_fourth_root_of_a_positive_real_ball_is_a_real_ball_holding_its_points_roots():
    """Real balls above 0 (an undamped model's ``x``) keep a real root, as tight as the
    derivative allows: the closed forms of the ``c_j`` then run in real balls."""
    ar = Ball(64)
    rng = np.random.default_rng(5)
    for _ in range(40):
        m = 10 ** rng.uniform(-2, 3)
        r = m * 10 ** rng.uniform(-12, -0.3)
        with ar:
            root = ar.root4(np.array([flint.arb(m, r)], dtype=object))[0]
        assert isinstance(root, flint.arb)
        for t in (m - 0.999 * r, m - r / 3, m, m + r / 2, m + 0.999 * r):     # (inside)
            with Ball(256):         # the root of the point, in far more bits than the ball's
                ref = flint.arb(t).root(4)
            assert root.contains(ref), (m, r, t)
        # the mean value bound r / (4 (m - r)**(3/4)), within (m / (m - r))**(1/4): the
        # derivative's bound at the ball's lower end uses the midpoint's root
        bound = r / (4 * (m - r) ** 0.75) * (m / (m - r)) ** 0.25
        assert float(root.rad()) <= 1.01 * bound + 2.0**-60 * m ** 0.25, (m, r)


def test_layer_count_proved_against_the_identical_pair():
    """Two identical pinned-pinned beams on a viscoelastic layer (k, c per unit length):
    in phase the layer does not act (``lam = +-i (n pi)**2``), out of phase ``lam**2 + 2 c
    lam + (n pi)**4 + 2 k = 0``. The contour's Delta is negative real along stretches of
    it (each crossing of the cut of arg), and the coupled pieces' balls are wide there."""
    from symtmm.model import Layer
    k, c, top = 50.0, 2.0, 200.0
    beams = (Beam("a", 1, 1, 1, **PP), Beam("b", 1, 1, 1, **PP))
    model = Model(beams, layers=(Layer("a", "b", k=k, c=c),))
    roots = []
    for n in range(1, 8):
        w2 = (n * math.pi) ** 4
        roots += [complex(0, math.sqrt(w2)), complex(0, -math.sqrt(w2))]
        disc = complex(c * c - w2 - 2 * k) ** 0.5
        roots += [-c + disc, -c - disc]
    rect = Rectangle(-10.0, 1.0, -top, top, symmetric=True)
    expected = sum(rect.contains(z) for z in roots)
    assert expected == 16
    got = proved_count(Evaluator(model, top * 1.1), rect)
    assert got.count == expected, got


def test_argument_near_the_negative_real_axis_is_an_interval():
    """Where ``Delta`` is close to the negative real axis its ball straddles the cut of the
    principal argument; the interval of ``arg Delta`` on the segment must still be narrow,
    and hold the argument at both ends (mpmath at 50 digits, a second arithmetic)."""
    from symtmm.roots.winding import _Prover
    model = load("examples/double_beam_layer.toml").require_numeric()
    ev = Evaluator(model, 440.0)
    a, b = complex(16, 393.7), complex(16, 393.74)
    prover = _Prover(ev, Rectangle(-800.0, 16.0, -400.0, 400.0, True), 15)
    (got,) = prover.intervals([(a, b)])
    assert got is not None
    centre, half = got
    assert half < 0.01
    values, trusted = ev.delta([a, b], MP(170))
    assert trusted.all()
    for v in values:
        arg = float(mpmath.arg(v))
        assert abs(math.remainder(arg - centre, 2 * math.pi)) <= half
        assert abs(abs(arg) - math.pi) < 0.1        # the case meant: near the cut
