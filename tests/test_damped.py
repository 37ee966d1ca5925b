"""Damped models: eigenvalues in the complex plane, none missed, every digit correct.

Reference values come from outside the solver:

* identical-beam decoupling: the three-beam chain of the paper's example 4
  splits (eigenvalues 0, 1, 3 of the graph Laplacian of the path P3) into
  single pinned-pinned beams with grounded spring/dashpots ``mu (k + c lam)``
  at ``x1`` and ``L - x1``. Each is solved from its own closed form
  (``damped_reference.py``): the Green's function of the pinned-pinned beam
  gives the characteristic
  function ``det(I + mu (k + c lam)/EI G(x_i, x_j))``; its undamped roots
  are bracketed on the frequency axis, then followed with mpmath.findroot
  as the dashpots grow from 0 to ``c`` (every damped root starts as an
  undamped one). The ``mu = 0`` family is the bare pinned-pinned beam:
  ``lam = i (n pi)**2 sqrt(EI/m) / L**2``, exactly imaginary.
* the cubic-Hermite finite-element model (:mod:`symtmm.fe`) with a damping
  matrix added here, solved as a linearised quadratic eigenproblem;
* the transfer-matrix ``Delta`` in mpmath (a second formulation of the
  double-precision function the count uses);
* the undamped solver (Wittrick–Williams count on the frequency axis) for
  models without dashpots.
"""

from __future__ import annotations

import json
import math
from decimal import Decimal
from fractions import Fraction
from pathlib import Path

import damped_reference
import mpmath
import numpy as np
import pytest
import scipy.linalg
from damped_reference import (
    CROWDED_ON_FOUNDATION,
    beam_char,
    pp_char,
    pp_damped_roots,
    pp_roots_from_modes,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from symtmm.cli import main
from symtmm.compile import Evaluator
from symtmm.fe import fe_dashpots, fe_matrices
from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load, loads
from symtmm.numeric.arith import ball_available
from symtmm.numeric.evaluator import Evaluator as Kernel
from symtmm.results import decimal_string
from symtmm.roots.contour import Rectangle
from symtmm.roots.damped import DAMPED_PROOFS, count_in_rectangle, default_sigma_max, solve_damped
from symtmm.roots.undamped import PROOFS, solve_undamped
from symtmm.solve import METHODS, solve

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
EX4 = EXAMPLES / "paper_ex4_damped.toml"


def assert_digits_correct(printed: str, exact, digits: int):
    """Every printed significant digit of ``printed`` is correct for ``exact``."""
    if printed == "0":
        assert exact == 0, f"printed 0 for {exact}"
        return
    value = Decimal(printed)
    exponent = value.adjusted()       # position of the leading digit
    ulp = Decimal(10) ** (exponent - digits + 1)
    error = abs(value - Decimal(mpmath.nstr(exact, digits + 15, strip_zeros=False)))
    assert error <= ulp / 2 * Decimal("1.0001"), (printed, mpmath.nstr(exact, digits + 5), digits)


@pytest.fixture(scope="module")
def ex4_reference():
    return damped_reference.ex4_reference()


@pytest.fixture(scope="module")
def ex4_spectrum():
    return solve(load(EX4), omega_max=1500, digits=15)


# -- the double-precision Delta ---------------------------------------------------------------
def _mixed_model():
    return Model((Beam("a", EI=2, m="3/2", L=1, left="clamped", right="free"),
                  Beam("b", EI=1, m=1, L="3/2", x0="-1/4", left="sliding", right="pinned"),
                  Beam("c", EI="1/2", m=1, L="1/2", x0="1/4", left="free", right="free")),
                 (Spring("a", "b", x="1/2", k=40, c=3),
                  Spring("b", "c", x="1/4", k=5, c="1/2"),
                  Spring("c", "ground", x="3/4", k=7, c=1),
                  Spring("a", "ground", x="1", k=0, c=2)))


@pytest.mark.parametrize("model", [load(EX4), load(EXAMPLES / "paper_ex1_ff_cc.toml"),
                                   _mixed_model()], ids=["ex4", "ex1", "mixed"])
def test_dynamic_stiffness_delta_equals_transfer_delta(model):
    """det K * prod det U12 (the kernel, in double precision) is the transfer-matrix Delta
    (the product along x, at 60 digits), anywhere."""
    ds = Kernel(model, 4000.0)
    ev = Evaluator(model)
    rng = np.random.default_rng(7)
    lam = np.concatenate([rng.uniform(-2800, 100, 6) + 1j * rng.uniform(-1400, 2800, 6),
                          [-37.5 + 0j, 3j, 0.5 - 0.25j]])
    logabs, phase, ok = ds.log_delta(lam)
    assert ok.all()
    with mpmath.workdps(60):
        for z, la, ph in zip(lam, logabs, phase):
            exact = ev.delta_mp(mpmath.mpc(z.real, z.imag), dps=60)
            ratio = mpmath.exp(mpmath.mpf(la) + 1j * mpmath.mpf(ph)) / exact
            assert abs(ratio - 1) < 1e-9, (z, ratio)
    assert ds.evaluations == lam.size


# -- example 4 (paper table 2) ------------------------------------------------------------------
def test_example4_against_decoupled_families(ex4_spectrum, ex4_reference):
    """Table 2: all eigenvalues in the region, each to 15 correct digits."""
    spec = ex4_spectrum
    assert spec.total == len(ex4_reference) == 9
    for e, (ref, family) in zip(spec, ex4_reference):
        d = e.to_dict()
        assert e.multiplicity == 1
        assert_digits_correct(d["imag"], ref.imag, 15)
        if family == 0:
            assert d["real"] == "0"          # in-phase modes: exactly imaginary
        else:
            assert_digits_correct(d["real"], ref.real, 15)


def test_example4_in_phase_modes_are_exact(ex4_spectrum):
    """Beams moving together leave the dashpots idle: lam = i (n pi)^2 sqrt(EI/m)."""
    idle = [e for e in ex4_spectrum if e.lam.real == 0]
    assert [e.to_dict()["imag"] for e in idle] == [
        "146.269800000000", "585.079200000000", "1316.42820000000"]
    assert any("Re lam = 0 for 3" in n for n in ex4_spectrum.notes)


def test_example4_region_and_stats(ex4_spectrum):
    spec = ex4_spectrum
    assert all(-3000 <= e.lam.real <= 0 and 0 < e.lam.imag <= 1500 for e in spec)
    assert [e.lam.imag for e in spec] == sorted(e.lam.imag for e in spec)
    assert spec.evaluations > 100 and spec.method == "default"
    assert default_sigma_max(1500) == 3000


def test_example4_count_mode(ex4_reference):
    spec = solve(load(EX4), count=4, digits=10)
    assert spec.total == 4
    for e, (ref, _) in zip(spec, ex4_reference[:4]):
        assert_digits_correct(e.to_dict()["imag"], ref.imag, 10)


def test_example4_cli_json(capsys, ex4_reference):
    assert main(["solve", str(EX4), "--omega-max", "600", "--digits", "8", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    eig = out["eigenvalues"]
    assert out["digits"] == 8 and out["stats"]["method"] == "default"
    assert [e["real"] for e in eig if e["real"] == "0"] == ["0", "0"]
    assert len(eig) == 6      # 40.1, 146.3, 165.2, 461.6, 585.1, 586.2
    ref, _ = ex4_reference[0]
    assert_digits_correct(eig[0]["real"], ref.real, 8)
    assert_digits_correct(eig[0]["imag"], ref.imag, 8)
    assert eig[0]["multiplicity"] == 1
    assert eig[0]["proof"] == DAMPED_PROOFS["rouche" if ball_available() else "agree"]


# -- digits -----------------------------------------------------------------------------------
@pytest.mark.parametrize("ambient", [None, 8, 400], ids=["default", "8 bits", "400 bits"])
@pytest.mark.parametrize("digits", [6, 15, 30])
def test_every_printed_digit_correct(digits, ambient):
    """A pinned-pinned beam with a spring and a dashpot to the ground at 3/10; whatever
    the ambient mpmath precision (the search never reads it)."""
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="3/10", k=20, c=4),))
    if ambient is None:
        spec = solve_damped(model, omega_max=100, digits=digits)
    else:
        with mpmath.workprec(ambient):
            spec = solve_damped(model, omega_max=100, digits=digits)
    refs = pp_damped_roots(1, 1, 1, [(Fraction(3, 10), 20, 4)], 200, dps=60)
    refs = sorted((z for z in refs if z.imag <= 100), key=lambda z: z.imag)
    assert len(spec) == len(refs) == 3
    for e, ref in zip(spec, refs):
        d = e.to_dict()
        assert_digits_correct(d["real"], ref.real, digits)
        assert_digits_correct(d["imag"], ref.imag, digits)


def test_a_box_straddling_a_rounding_boundary_is_not_accepted():
    """Re z = 1 + 5e-20 -+ 1e-22 straddles the 20-digit rounding boundary: the ends of
    the box print differently, also under the default (53-bit) ambient precision."""
    from symtmm.roots.damped import _box, _prints_alike
    with mpmath.workdps(60):
        z = mpmath.mpc(1 + mpmath.mpf("5e-20"), 2)
        r = mpmath.mpf("1e-22")
    re_ends, im_ends = _box(z, r)
    assert not _prints_alike(re_ends, 20) and _prints_alike(im_ends, 20)
    assert _prints_alike(re_ends, 19)


# -- finite elements with a damping matrix -----------------------------------------------------
def _fe_damped(elements, x, c):
    beam = {"name": "a", "EI": 1.0, "m": 1.0, "L": 1.0, "x0": 0.0, "left": "pinned", "right": "pinned"}
    K, M, info = fe_matrices([beam], [{"between": ["a", "ground"], "x": x, "k": 0.0}], elements)
    n = K.shape[0]
    C = fe_dashpots(info, [("a", "ground", x, c)])
    # lam^2 M + lam C + K = 0 as a 2n linear pencil
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    lam = scipy.linalg.eig(A, B, right=False)
    lam = lam[lam.imag > 1e-9]
    return lam[np.argsort(lam.imag)]


def test_single_dashpot_against_finite_elements():
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="3/10", k=0, c=4),))
    spec = solve_damped(model, count=4, digits=12)
    exact = np.array([complex(e.lam) for e in spec])
    coarse, fine = _fe_damped(30, 0.3, 4.0)[:4], _fe_damped(60, 0.3, 4.0)[:4]
    err_c, err_f = np.abs(coarse - exact) / np.abs(exact), np.abs(fine - exact) / np.abs(exact)
    assert np.all(err_f < 2e-6)
    assert np.all(err_f < err_c / 8)     # converging to it at the FE rate h^4


def test_midspan_dashpot_leaves_even_modes_undamped():
    """Even pinned-pinned modes have a node at midspan: lam = i (2 pi)^2 exactly."""
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="1/2", k=0, c=3),))
    spec = solve_damped(model, omega_max=170, digits=15)
    even = [e for e in spec if e.lam.real == 0]
    assert [e.to_dict()["imag"] for e in even] == [
        mpmath.nstr((2 * mpmath.pi) ** 2, 15, strip_zeros=False),
        mpmath.nstr((4 * mpmath.pi) ** 2, 15, strip_zeros=False)]
    fe = _fe_damped(60, 0.5, 3.0)[:4]
    odd = [complex(e.lam) for e in spec if e.lam.real != 0]
    assert np.allclose(odd, fe[[0, 2]], rtol=2e-6)


# -- the undamped eigenvalues as estimates --------------------------------------------------------
LIGHT = [(Fraction(3, 10), 20, Fraction(1, 5)), (Fraction(7, 10), 5, Fraction(1, 10))]


def test_light_damping_is_solved_from_the_undamped_eigenvalues(monkeypatch):
    """Light dashpots move the eigenvalues little: the rectangle above the real axis is
    solved from the undamped eigenvalues, with no subdivision, and every printed digit
    agrees with the Green's-function reference."""
    from symtmm.roots import damped
    isolated = []
    isolate = damped._Search.isolate
    monkeypatch.setattr(damped._Search, "isolate",
                        lambda self, cells, tiny: isolated.extend(cells) or
                        isolate(self, cells, tiny))
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  tuple(Spring("a", "ground", x=str(x), k=k, c=str(c)) for x, k, c in LIGHT))
    spec = solve_damped(model, omega_max=200, digits=15)
    assert not [rect for rect, n, _ in isolated if not rect.symmetric and n]
    refs = sorted(pp_damped_roots(1, 1, 1, LIGHT, 200, dps=40), key=lambda z: z.imag)
    assert len(spec) == len(refs) == 4
    for e, ref in zip(spec, refs):
        assert_digits_correct(e.to_dict()["real"], ref.real, 15)
        assert_digits_correct(e.to_dict()["imag"], ref.imag, 15)
        assert e.proof == DAMPED_PROOFS["rouche"]


@pytest.mark.skipif(not ball_available(), reason="Rouche's proofs need python-flint")
@pytest.mark.parametrize("share", [0.0, None], ids=["cut-at-once", "default-share"])
def test_rouche_proofs_cut_short_leave_their_boxes_to_two_precisions(monkeypatch, share):
    """Rouche's proofs take a share of the search's time (a crowd of nearly undamped modes
    made them 71 of a search's 77 s, past its budget); cut short, the boxes they leave are
    backed by two precisions, every digit still right. The reference: the Green's-function
    roots of the pinned-pinned beam with its dashpots."""
    from symtmm.roots import damped
    if share is not None:
        monkeypatch.setattr(damped, "_PROOF_SHARE", share)
        monkeypatch.setattr(damped, "_PROOF_FLOOR", share)
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  tuple(Spring("a", "ground", x=str(x), k=k, c=str(c)) for x, k, c in LIGHT))
    spec = solve_damped(model, omega_max=200, digits=15)
    refs = sorted(pp_damped_roots(1, 1, 1, LIGHT, 200, dps=40), key=lambda z: z.imag)
    assert len(spec) == len(refs) == 4
    for e, ref in zip(spec, refs):
        assert_digits_correct(e.to_dict()["real"], ref.real, 15)
        assert_digits_correct(e.to_dict()["imag"], ref.imag, 15)
    expected = DAMPED_PROOFS["agree"] if share == 0.0 else DAMPED_PROOFS["rouche"]
    assert [e.proof for e in spec] == [expected] * 4


def test_estimates_that_do_not_give_every_zero_leave_the_rectangle_to_the_isolation():
    """Two estimates of one zero, or fewer estimates than zeros: None, nothing is taken
    on trust (the caller isolates); good estimates: the zeros themselves."""
    from symtmm.roots.damped import _Problem, _Search
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  tuple(Spring("a", "ground", x=str(x), k=k, c=str(c)) for x, k, c in LIGHT))
    refs = sorted(pp_damped_roots(1, 1, 1, LIGHT, 60, dps=30), key=lambda z: z.imag)
    assert len(refs) == 2
    search = _Search(_Problem(model, 80.0), 12)
    rect = Rectangle(-1.0, 1.0, 5.0, 60.0)
    w1, w2 = (float(z.imag) for z in refs)
    assert search.from_estimates(rect, 2, [1j * w1, 1j * w1 * (1 + 1e-9)]) is None
    assert search.from_estimates(rect, 2, [1j * w1]) is None
    assert search.from_estimates(rect, 3, [1j * w1, 1j * w2]) is None
    got = search.from_estimates(rect, 2, [1j * w1 * 1.001, 1j * w2 * 0.999])
    assert got is not None
    for e, ref in zip(sorted(got, key=lambda e: e.lam.imag), refs):
        assert_digits_correct(e.to_dict()["imag"], ref.imag, 12)
        assert_digits_correct(e.to_dict()["real"], ref.real, 12)


# -- real (overdamped) eigenvalues ----------------------------------------------------------------
def test_overdamped_real_eigenvalue():
    """A strong dashpot at midspan: a real eigenvalue, found with Im lam = 0 exactly."""
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="1/2", k=0, c=50),))
    spec = solve_damped(model, omega_max=100, digits=15)
    real = [e for e in spec if e.lam.imag == 0]
    assert len(real) == 1
    with mpmath.workdps(40):
        sup = [(mpmath.mpf(1) / 2, 0, 50)]

        def f(s):
            return mpmath.re(pp_char(mpmath.mpc(s, 0), 1, 1, 1, sup))

        ref = mpmath.findroot(f, (-1.2, -0.8), solver="anderson")
    assert_digits_correct(real[0].to_dict()["real"], ref, 15)
    lo, hi = real[0].bracket
    assert lo <= ref <= hi
    assert real[0].to_dict()["imag"] == "0"


# -- multiple eigenvalues and rigid-body modes ----------------------------------------------------
def test_double_eigenvalues_of_identical_undamped_beams():
    """Beams a and c are identical and free of springs: every (n pi)^2 i is double."""
    beams = tuple(Beam(n, EI=1, m=1, L=1, left="pinned", right="pinned") for n in "abc")
    model = Model(beams, (Spring("b", "ground", x="1/3", k=10, c=2),))
    spec = solve_damped(model, omega_max=45, digits=15)
    double = [e for e in spec if e.multiplicity == 2]
    assert [e.to_dict()["imag"] for e in double] == [
        mpmath.nstr((n * mpmath.pi) ** 2, 15, strip_zeros=False) for n in (1, 2)]
    assert all(e.to_dict()["real"] == "0" for e in double)
    assert spec.total == 6      # plus one damped root of beam b per mode


@pytest.mark.slow
def test_triple_eigenvalues_of_example3_by_both_methods():
    """At 16 pi^2 the pinned-pinned mode has nodes at both springs: triple in example 3."""
    model = load(EXAMPLES / "paper_ex3_three_pp_coupled.toml")
    a = METHODS["contour"](model.require_numeric(), None, 200.0, None, 15)
    b = solve_undamped(model, omega_max=200.0, digits=15)
    values = ("real", "imag", "multiplicity")
    assert [{k: e.to_dict()[k] for k in values} for e in a] == \
        [{k: e.to_dict()[k] for k in values} for e in b]
    assert a[-1].to_dict() == {"real": "0", "imag": mpmath.nstr(16 * mpmath.pi**2, 15,
                                                                strip_zeros=False),
                               "multiplicity": 3}


@pytest.mark.slow
def test_triple_eigenvalue():
    """At 9 pi^2 beam b's mode has a node at its dashpot (x = 1/3): a triple eigenvalue."""
    beams = tuple(Beam(n, EI=1, m=1, L=1, left="pinned", right="pinned") for n in "abc")
    model = Model(beams, (Spring("b", "ground", x="1/3", k=10, c=2),))
    spec = solve_damped(model, omega_max=100, digits=15)
    triple = [e for e in spec if e.multiplicity == 3]
    assert len(triple) == 1
    assert triple[0].to_dict() == {"real": "0", "imag": mpmath.nstr(
        9 * mpmath.pi**2, 15, strip_zeros=False), "multiplicity": 3}


def test_rigid_body_modes_of_free_beams():
    """Two free-free beams joined by springs and dashpots: lam = 0 twice (rigid modes),
    in-phase modes undamped at the free-free frequencies."""
    beams = tuple(Beam(n, EI=1, m=1, L=1, left="free", right="free") for n in "ab")
    model = Model(beams, (Spring("a", "b", x="1/4", k=30, c=3),
                          Spring("a", "b", x="3/4", k=30, c=3)))
    spec = solve_damped(model, omega_max=60, digits=15)
    assert spec[0].to_dict() == {"real": "0", "imag": "0", "multiplicity": 2,
                                 "proof": PROOFS["exact"]}
    with mpmath.workdps(30):
        Omega1 = mpmath.findroot(lambda x: mpmath.cos(x) - mpmath.sech(x), 4.73)
    in_phase = [e for e in spec if e.lam.real == 0 and e.lam.imag > 0]
    assert [e.to_dict()["imag"] for e in in_phase] == [mpmath.nstr(Omega1**2, 15,
                                                                    strip_zeros=False)]
    # the out-of-phase family: one free-free beam with grounded 2 (k + c lam) at 1/4, 3/4
    single = Evaluator(Model((Beam("s", EI=1, m=1, L=1, left="free", right="free"),),
                             (Spring("s", "ground", x="1/4", k=60, c=6),
                              Spring("s", "ground", x="3/4", k=60, c=6))))
    damped = [e for e in spec if e.lam.real != 0]
    assert len(damped) == 3
    with mpmath.workdps(40):
        for e in damped:
            lam = mpmath.mpc(e.lam)
            h = abs(lam) * mpmath.mpf(10) ** -20
            f0 = single.delta_mp(lam)
            newton_step = f0 * h / (single.delta_mp(lam + h) - f0)
            assert abs(newton_step) < abs(lam) * 1e-14


# -- a dashpot alone on a rigid-body motion ------------------------------------------------------
PURE_DASHPOT = {
    # a pinned-free beam turning about its pin, a dashpot at 0.6: lam = 0 is a simple zero
    # beside a real eigenvalue; the values in the issue that reported it (an independent
    # state-space FE polished on an exact determinant) are reproduced by beam_char
    "pinned-free": (("pinned", "free"), [("3/5", 0, 2)],
                    [("-2.19141315549854", "0"), ("-0.623622447176967", "15.3310074918209"),
                     ("-1.43788429657287", "49.8554523918882"),
                     ("-0.056570866708691", "104.245191761378")]),
    # a free-free beam held by a spring at midspan turns about it; a dashpot at 0.2
    "free-free": (("free", "free"), [("1/2", 50, 0), ("1/5", 0, 2)], None),
}


@pytest.mark.parametrize("digits", [15, 30])
@pytest.mark.parametrize("name", list(PURE_DASHPOT))
def test_dashpot_alone_on_a_rigid_body_motion(name, digits):
    (left, right), supports, published = PURE_DASHPOT[name]
    model = Model((Beam("b", 1, 1, 1, left=left, right=right),),
                  tuple(Spring("b", "ground", x, k, c) for x, k, c in supports))
    spec = solve_damped(model, omega_max=110, digits=digits)
    zero = [e for e in spec if e.lam == 0]
    others = [e for e in spec if e.lam != 0]
    assert len(zero) == 1 and zero[0].multiplicity == 1
    assert "order 1" in " ".join(spec.notes)
    with mpmath.workdps(digits + 30):
        sup = [(Fraction(x), k, c) for x, k, c in supports]
        sup = [(mpmath.mpf(x.numerator) / x.denominator, k, c) for x, k, c in sup]
        for e in others:
            ref = mpmath.findroot(lambda z: beam_char(z, 1, 1, 1, left, right, sup),
                                  mpmath.mpc(e.lam))
            assert_digits_correct(e.to_dict()["real"], ref.real, digits)
            if e.lam.imag == 0:
                assert abs(ref.imag) < mpmath.mpf(10) ** -(digits + 20)
            else:
                assert_digits_correct(e.to_dict()["imag"], ref.imag, digits)
    if published and digits == 15:
        assert [(Decimal(e.to_dict()["real"]), Decimal(e.to_dict()["imag"])) for e in others] \
            == [(Decimal(a), Decimal(b)) for a, b in published]
    real = [e for e in others if e.lam.imag == 0]
    assert len(real) == 1 and real[0].lam.real < 0
    if digits == 15:
        # by count, and by the contour method: the same first three
        first = [(e.to_dict()["real"], e.to_dict()["imag"]) for e in spec][:3]
        for method in ("default", "contour"):
            again = solve(model, count=3, digits=15, method=method)
            assert [(e.to_dict()["real"], e.to_dict()["imag"]) for e in again] == first


def test_a_strip_with_lam_zero_and_one_real_zero_is_cut_between_them():
    """The mean of the strip's zeros (its contour's moment) places the real zero beside
    lam = 0, and one cut midway parts them: a count of 1 each side (halving the strip
    took seven generations). The real zero: the published value of the pinned-free case."""
    from symtmm.mesh import zero_order
    from symtmm.roots.damped import _Problem, _Search
    (left, right), supports, published = PURE_DASHPOT["pinned-free"]
    real = float(published[0][0])
    model = Model((Beam("b", 1, 1, 1, left=left, right=right),),
                  tuple(Spring("b", "ground", x, k, c) for x, k, c in supports))
    search = _Search(_Problem(model, 300.0), 15)
    search.zero_order = zero_order(model)[1]
    assert search.zero_order == 1
    strip = Rectangle(-220.0, 4.4, -4.4, 4.4, True)
    n, center = search.ap.count_and_center(strip)
    assert n == 2
    assert abs(center - real / 2) < 0.01 * abs(real)
    [kids] = search._split_all([(strip, n, center)])
    assert [k for _, k, _, _ in kids] == [1, 1]
    assert kids[0][0].x1 < real / 2 * 0.9 and kids[0][0].contains(real)


# -- undamped models: the contour search agrees with the Wittrick-Williams search ---------------
def test_contour_method_on_undamped_model_matches_undamped_solver():
    model = load(EXAMPLES / "paper_ex3_three_pp_coupled.toml")
    a = METHODS["contour"](model.require_numeric(), None, 100.0, None, 15)
    b = solve_undamped(model, omega_max=100.0, digits=15)
    assert a.total == b.total == 9
    assert a.method == "contour"
    values = ("real", "imag", "multiplicity")
    assert [{k: e.to_dict()[k] for k in values} for e in a] == \
        [{k: e.to_dict()[k] for k in values} for e in b]


def test_count_in_rectangle():
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="3/10", k=0, c=4),))
    assert count_in_rectangle(model, -10.0, 1.0, 0.0, 100.0) == 3
    assert count_in_rectangle(model, -10.0, 1.0, -100.0, 100.0) == 6
    assert count_in_rectangle(model, -10.0, -3.0, 0.0, 100.0) == 1   # -3.58 + 38.9i


def test_default_method_routes_damped_models():
    model = Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="3/10", k=0, c=4),))
    spec = solve(model, count=1, digits=8)
    assert spec[0].to_dict()["real"] == "-2.6916884"
    assert math.isclose(float(spec[0].lam.imag), 9.644173516, rel_tol=1e-9)


# -- properties on random damped two-beam models ---------------------------------------------
_ENDS = [("pinned", "pinned"), ("clamped", "clamped"), ("clamped", "free"),
         ("pinned", "clamped"), ("clamped", "sliding"), ("pinned", "sliding")]


@st.composite
def damped_two_beam_models(draw):
    """Two beams (no rigid-body mode), one or two spring/dashpots between them, maybe one
    to the ground; exact rational data."""
    beams = []
    for name in ("a", "b"):
        left, right = draw(st.sampled_from(_ENDS))
        EI = Fraction(draw(st.integers(2, 8)), 4)
        m = Fraction(draw(st.integers(2, 8)), 4)
        beams.append(Beam(name, EI=str(EI), m=str(m), L=1, left=left, right=right))
    springs = []
    for _ in range(draw(st.integers(1, 2))):
        x = Fraction(draw(st.integers(1, 15)), 16)
        springs.append(Spring("a", "b", x=str(x), k=draw(st.integers(0, 40)),
                              c=str(Fraction(draw(st.integers(1, 40)), 4))))
    if draw(st.booleans()):
        x = Fraction(draw(st.integers(1, 15)), 16)
        springs.append(Spring(draw(st.sampled_from("ab")), "ground", x=str(x),
                              k=draw(st.integers(0, 20)),
                              c=str(Fraction(draw(st.integers(0, 20)), 4))))
    return Model(tuple(beams), tuple(springs))


@settings(max_examples=5, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(damped_two_beam_models())
def test_random_models_count_matches_roots_and_digits_are_stable(model):
    W = 40.0
    low = solve_damped(model, omega_max=W, digits=8)
    high = solve_damped(model, omega_max=W, digits=16)
    # the same eigenvalues at both precisions: the 16-digit ones round to the 8-digit ones
    assert [e.multiplicity for e in low] == [e.multiplicity for e in high]
    for a, b in zip(low, high):
        with mpmath.workdps(40):
            for part_a, part_b in ((a.lam.real, b.lam.real), (a.lam.imag, b.lam.imag)):
                assert decimal_string(part_b, 8) == decimal_string(part_a, 8)
    # an independent count over the reported region, mirrored below the real axis
    S = default_sigma_max(W)
    counted = count_in_rectangle(model, -S, 0.37, -W, W)
    found = sum(e.multiplicity * (1 if e.lam.imag == 0 else 2) for e in high)
    assert counted == found
    # every eigenvalue is a zero of the transfer-matrix Delta at 40 digits
    ev = Evaluator(model)
    with mpmath.workdps(40):
        for e in high:
            if e.multiplicity > 1:
                continue
            lam = mpmath.mpc(e.lam)
            h = max(abs(lam), 1) * mpmath.mpf(10) ** -20
            f0 = ev.delta_mp(lam)
            step = f0 * h / (ev.delta_mp(lam + h) - f0) if f0 != 0 else 0
            assert abs(step) <= mpmath.mpf(10) ** -15 * abs(lam)


@pytest.mark.slow
def test_example4_thirty_digits():
    """Table 2 at 30 digits against the decoupled families computed at 50."""
    spec = solve(load(EX4), omega_max=1500, digits=30)
    refs = damped_reference.ex4_reference(dps=50)
    assert spec.total == len(refs) == 9
    for e, (ref, family) in zip(spec, refs):
        d = e.to_dict()
        assert_digits_correct(d["imag"], ref.imag, 30)
        if family == 0:
            assert d["real"] == "0"
        else:
            assert_digits_correct(d["real"], ref.real, 30)


# -- the engineer's quantities ----------------------------------------------------------------


def _right_digits(text: str, value) -> bool:
    """Every digit of ``text`` is right: ``value`` rounds to it at its own length."""
    digits = len(text.lstrip("-0.").replace(".", ""))
    return text != "?" and decimal_string(value, digits) == text


def test_damping_ratio_frequency_and_modulus_of_example_4(ex4_spectrum, ex4_reference):
    """zeta = -Re lam / |lam|, |lam| and Im lam / 2 pi of every eigenvalue, each digit right
    against the decoupled-family reference, and at least 14 of the 15 digits shown."""
    found = ex4_spectrum.to_dict()["eigenvalues"]
    assert len(found) == len(ex4_reference)
    with mpmath.workdps(40):
        for got, (ref, _) in zip(found, ex4_reference):
            quantities = {"abs": abs(ref), "hz": ref.imag / (2 * mpmath.pi),
                          "zeta": -ref.real / abs(ref)}
            for name, value in quantities.items():
                text = got[name]
                if value == 0:
                    assert text == "0"
                    continue
                assert _right_digits(text, value), (name, text, value)
                assert len(text.lstrip("-0.").replace(".", "")) >= 14, (name, text)


def test_damped_table_shows_modulus_and_damping_ratio(ex4_spectrum):
    head = ex4_spectrum.table().splitlines()[0]
    assert "|lam| [rad/s]" in head and "zeta" in head
    assert r"\zeta" in ex4_spectrum._repr_latex_()


def test_contour_sides_and_rectangles_are_sampled_together():
    """The argument principle refines all sides of a rectangle, and the rectangles of a
    split, together: each round's new points in one call of ``f`` (one call per side and
    round took 12 calls here and 18 for the two halves; the same points, fewer calls).
    Reference: the zeros 1, 2i, -2i, -2 and 3 + i of the polynomial."""
    from symtmm.roots.contour import ArgumentPrinciple, Rectangle
    calls = []

    def f(z):
        calls.append(len(z))
        v = (z - 1) * (z**2 + 4) * (z + 2) * (z - 3 - 1j)
        return np.log(np.abs(v)), np.angle(v), np.ones(z.shape, dtype=bool)
    ap = ArgumentPrinciple(f, spacing=lambda z: 0.5)
    assert ap.count(Rectangle(-0.5, 3.5, -0.5, 2.5)) == 3          # 1, 2i, 3 + i
    assert len(calls) <= 4
    calls.clear()
    ap = ArgumentPrinciple(f, spacing=lambda z: 0.5)
    halves = [Rectangle(-3, 0.5, -1, 2.5), Rectangle(0.5, 3.5, -1, 2.5)]
    assert [n for n, _ in ap.counts_and_centers(halves)] == [2, 2]   # -2, 2i | 1, 3 + i
    assert len(calls) <= 8


@pytest.mark.parametrize("rect", [Rectangle(-3.0, 0.0, 1.0, 5.0),
                                  Rectangle(-9.0, 0.0, -2.0, 2.0, True),
                                  Rectangle(-1.0, 0.0, -6.0, 6.0, True)],
                         ids=["upper", "wide symmetric", "tall symmetric"])
def test_quarters_count_every_zero_of_the_rectangle_once(rect):
    """A rectangle of three zeros or more is cut into quarters in one generation. With the
    mirrored parts counted twice (a symmetric rectangle's count is of the whole, mirror
    included), the quarters hold every zero of the rectangle exactly once: checked with
    the zeros of a polynomial spread over it, counted by the argument principle."""
    from symtmm.roots.contour import ArgumentPrinciple
    from symtmm.roots.damped import _Search
    zs = [complex(rect.x0 + (rect.x1 - rect.x0) * u, rect.y0 + (rect.y1 - rect.y0) * v)
          for u, v in ((0.13, 0.21), (0.71, 0.33), (0.37, 0.86), (0.88, 0.92), (0.52, 0.61))]
    if rect.symmetric:
        zs = [complex(z.real, abs(z.imag) * 0.999) for z in zs]
        zs += [z.conjugate() for z in zs]

    def f(z):
        v = np.prod([z - r for r in zs], axis=0)
        return np.log(np.abs(v)), np.angle(v), np.ones(z.shape, dtype=bool)
    ap = ArgumentPrinciple(f, spacing=lambda z: 0.05)
    quarters = _Search._quarters(rect)
    assert len(quarters) == 4
    counts = [n for n, _ in ap.counts_and_centers([q for q, _ in quarters])]
    assert sum(n * w for n, (_, w) in zip(counts, quarters)) == ap.count(rect) == len(zs)



@pytest.mark.parametrize("turns", [2, 4, 20, 40])
def test_a_side_beside_a_row_of_zeros_is_not_taken_in_whole_turns(turns):
    """``sin(pi (z - s/2 - 0.1 i) / s)``: a row of zeros ``s`` apart at ``Im z = 0.1``,
    inside the unit square. Along its bottom and top sides ``arg f`` turns at an even
    rate, ``pi / s``; with a first grid of the whole side (a spacing that misses the
    crowd), ``s`` is chosen so that a side turns by ``turns`` whole turns and a little:
    the principal value of the step passes, and so did both its halves for every even
    ``turns`` (4 to 80 zeros counted 0). The vertical sides, along which ``log|f|``
    changes as fast, measure the rate at the corners (Cauchy-Riemann), and the end
    steps are held to it. Reference: the zeros, placed."""
    from symtmm.roots.contour import ArgumentPrinciple
    s = math.pi / (2 * math.pi * turns + 0.1)

    def f(z):
        v = np.log(np.sin(np.pi * (np.asarray(z, dtype=complex) - s / 2 - 0.1j) / s))
        return v.real, v.imag, np.ones(np.shape(z), dtype=bool)
    placed = sum(1 for j in range(1000) if s / 2 + j * s < 1)
    ap = ArgumentPrinciple(f, spacing=lambda z: 1.0)
    assert ap.count(Rectangle(0.0, 1.0, 0.0, 1.0)) == placed == 2 * turns


#: A Rayleigh beam whose rotary inertia on its foundation bends the dispersion down to a
#: minimum near omega = 1.5215: hundreds of modes crowd above it, the lowest 1e-5 apart,
#: a pure dashpot damps them lightly.
HEAVY_RAYLEIGH_DASHPOT = """
[[beam]]
name = "b1"
EI = 3.0
m = 4.95
L = 47.3
left = "pinned"
right = "pinned"
theory = "rayleigh"
rhoI = 617.0
kw = 170000.0

[[spring]]
between = ["b1", "ground"]
x = 11.0
k = 0
c = 0.5
"""


@pytest.mark.slow
def test_lightly_damped_modes_at_a_dispersion_minimum():
    """A side 1.4e-3 below the crowd turned arg Delta by 12 radians over one step of the
    first grid, which passed with its halves: two rectangles counted a zero each that
    held none, and the search stopped ("cannot split the search rectangle"); the end
    steps of a side are now held to the rate the side across measures. Reference: each
    eigenvalue lies within 1e-9 of a frequency of the beam without its dashpot, a plain
    pinned-pinned Rayleigh beam on its foundation: ``omega**2 = (EI q**2 + kw) / (m +
    rhoI q)``, ``q = (n pi / L)**2``, the least three over ``n`` (the closed form)."""
    model = loads(HEAVY_RAYLEIGH_DASHPOT)
    damped = solve(model, count=3, digits=12)
    with mpmath.workdps(30):
        EI, m, L, rhoI, kw = 3, mpmath.mpf("4.95"), mpmath.mpf("47.3"), 617, 170000
        undamped = sorted(mpmath.sqrt((EI * q * q + kw) / (m + rhoI * q))
                          for q in ((n * mpmath.pi / L) ** 2 for n in range(1, 600)))[:3]
    assert len(damped) == 3
    for d, u in zip(damped, undamped):
        assert -1e-7 < float(d.lam.real) < 0
        assert abs(float(d.lam.imag) - float(u)) < 1e-9


#: Four beams, one of them holding a damped sprung mass; the others alone, so that their
#: modes are eigenvalues on the imaginary axis, three of them within 0.22 rad/s of 11.6
#: (a fuzzed model). The contour sampling took a step of 0.094 beside steps of 0.023
#: along a side 0.008 from them, over which arg Delta turned by 2 pi and a little: one
#: zero counted too many, and the search stopped ("cannot split the search rectangle").
FOUR_BEAMS_AND_A_SPRUNG_MASS = """
[[beam]]
name = "b0"
EI = 1
m = 1
L = 1
left = "free"
right = "free"

[[beam]]
name = "b2"
EI = 1.368
m = 1.9
L = 1.29
left = "sliding"
right = "pinned"
N = 0.6098

[[beam]]
name = "b3"
EI = 0.97
m = 1.713
L = 0.6
left = "clamped"
right = "sliding"

[[beam]]
name = "b4"
EI = 1
m = 0.564
L = 1.7
left = "free"
right = "free"
N = 1.0356

[[oscillator]]
name = "osc"
beam = "b0"
x = 1
M = 1
k = 1
c = 1
"""


@pytest.mark.parametrize("method", ["default", "contour"])
def test_zeros_beside_a_side_are_not_counted_through_it(method):
    from symtmm.api import loads
    from symtmm.solve import solve
    found = solve(loads(FOUR_BEAMS_AND_A_SPRUNG_MASS), omega_max=50, digits=12, method=method)
    # b3 alone, clamped-sliding: omega = x**2 / L**2 sqrt(EI / m), tan x + tanh x = 0
    with mpmath.workdps(30):
        x = mpmath.findroot(lambda t: mpmath.tan(t) + mpmath.tanh(t), 2.365)
        b3 = x**2 / mpmath.mpf("0.36") * mpmath.sqrt(mpmath.mpf("0.97") / mpmath.mpf("1.713"))
    near = [e for e in found if abs(float(e.lam.imag) - 11.69) < 0.01]
    assert len(near) == 1 and abs(near[0].lam.real) == 0
    assert abs(near[0].lam.imag - b3) < 1e-11 * b3
    # its two neighbours on the axis and the damped modes: every eigenvalue once
    assert sum(e.multiplicity for e in found if 11.4 < float(e.lam.imag) < 11.8) == 3


def test_a_damped_model_is_counted_without_its_dashpots_on_its_own_plans(monkeypatch):
    """The undamped estimates of a damped search count the model without its dashpots on
    the damped model's plans (the dashpots' column set to 0): the same counts as the model
    with its dashpots removed, in double precision and in the proof arithmetic, about the
    closed-form (n pi)**2 of the pinned-pinned beam a pure dashpot leaves undamped, and
    no plan of a model of its own."""
    from symtmm.numeric import plan as plan_module
    from symtmm.numeric.arith import MP, Ball
    from symtmm.roots.count import Counter

    damped = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                   (Spring("b", "ground", x="1/4", k=0, c="1/2"),))
    bare = damped.with_dashpots_scaled(0)
    omegas = [1.0, 9.8, 10.0, 39.4, 39.6, 88.0, 89.0, 150.0]
    arithmetics = [MP(120)] + ([Ball(120)] if ball_available() else [])
    pts = [mpmath.mpf(w) for w in omegas]
    want = Counter(bare, 160.0)
    expected = [want.counts(omegas).tolist()] + [want.factors(pts, ar).counts().tolist()
                                                 for ar in arithmetics]
    plan_module.clear_plans()
    built = []
    original = plan_module.StiffnessPlan.__init__

    def counting(self, model, *args, **kwargs):
        built.append(model.damped)
        original(self, model, *args, **kwargs)
    monkeypatch.setattr(plan_module.StiffnessPlan, "__init__", counting)
    got = Counter(damped, 160.0)
    counted = [got.counts(omegas).tolist()] + [got.factors(pts, ar).counts().tolist()
                                               for ar in arithmetics]
    assert counted == expected
    assert expected[0] == [0, 0, 1, 1, 2, 2, 3, 3]
    assert built and all(built), built          # (its plans are the damped model's)


def test_damped_pair_closer_than_double_precision_is_split_and_shaped():
    """Two equal pinned-pinned beams, each with a dashpot (c = 0.1) to the ground at x =
    0.7, joined by a spring of 1e-25 at x = 0.3: each pair of eigenvalues lies about 1e-27
    apart (relative). Decoupled (``damped_reference``): the in-phase ones are the single
    beam's with its dashpot, the anti-phase ones those with a grounded spring of 2e-25
    added; all print alike at 15 digits. The pair's rectangle, cut in floats about its
    centre, had no cut between the two zeros (``cannot split the search rectangle``),
    and each shape must then move the beams alike or opposite."""
    from symtmm.modes import mode_shapes

    beams = (Beam("a", 1, 1, 1, left="pinned", right="pinned"),
             Beam("b", 1, 1, 1, left="pinned", right="pinned"))
    model = Model(beams, (Spring("a", "b", "3/10", "1e-25"),
                          Spring("a", "ground", "7/10", 0, c="1/10"),
                          Spring("b", "ground", "7/10", 0, c="1/10")))
    modes = mode_shapes(model, count=4, points=11)
    got = [m.eigenvalue for m in modes]
    assert [e.multiplicity for e in got] == [1, 1, 1, 1]
    inphase = pp_roots_from_modes([1, 2], [("0.7", 0, "0.1")])
    anti = pp_roots_from_modes([1, 2], [("0.7", 0, "0.1"), ("0.3", "2e-25", 0)])
    for pair, a, b in zip((got[0:2], got[2:4]), inphase, anti):
        for e in pair:
            for ref in (a, b):
                assert decimal_string(e.lam.imag, 15) == decimal_string(ref.imag, 15)
                assert decimal_string(e.lam.real, 15) == decimal_string(ref.real, 15)
    for pair in (modes[0:2], modes[2:4]):
        ratios = sorted(complex(m.beams["b"].Y[3] / m.beams["a"].Y[3]).real for m in pair)
        np.testing.assert_allclose(ratios, [-1, 1], atol=1e-12)
        for m in pair:
            np.testing.assert_allclose(np.abs(m.beams["b"].Y), np.abs(m.beams["a"].Y),
                                       atol=1e-12)


def test_real_zero_a_billionth_beside_the_rigid_body_zero():
    """Two pinned-free beams, each with a pure dashpot (c = 0.1 at x = 0.7) on its rigid
    rotation about the pin, joined by a spring of 1e-10 at x = 0.37: lam = 0 (the
    rotation in phase, the spring unstretched) and a real zero 5.6e-10 beside it (the
    rotation against the spring). The rigid bodies' equation ``J th'' + c a**2 th' + 2 k
    b**2 th = 0`` (``J = m L**3 / 3``) gives it to about k / EI (the beams' flexibility),
    and ``-c a**2 / J`` twice to about (0.15 / 15.4)**2. The rectangle about lam = 0,
    2e-9 across, was cut with contour steps no shorter than 1e-10 |lam_ref|: 'cannot
    split the search rectangle'."""
    beams = tuple(Beam(n, 1, 1, 1, left="pinned", right="free") for n in "ab")
    model = Model(beams, (Spring("a", "b", "37/100", "1e-10"),
                          Spring("a", "ground", "7/10", 0, c="1/10"),
                          Spring("b", "ground", "7/10", 0, c="1/10")))
    spec = solve_damped(model, count=4, digits=15)
    values = sorted((e.lam for e in spec), key=lambda z: -float(z.real))
    assert [e.multiplicity for e in spec] == [1, 1, 1, 1]
    assert values[0] == 0 and all(z.imag == 0 for z in values)
    J, c, a, k, b = mpmath.mpf(1) / 3, mpmath.mpf("0.1"), mpmath.mpf("0.7"), \
        mpmath.mpf("1e-10"), mpmath.mpf("0.37")
    small = (-c * a**2 + mpmath.sqrt((c * a**2) ** 2 - 8 * J * k * b**2)) / (2 * J)
    assert abs(values[1].real / small - 1) < 1e-8
    for z in values[2:]:
        assert abs(z.real / (-c * a**2 / J) - 1) < 1e-3


@pytest.mark.skipif(not ball_available(), reason="needs python-flint")
def test_close_damped_pair_is_proved_by_rouche_in_its_sub_search():
    """Two equal pinned-free beams (EI = m = 2) with pure dashpots (c = 0.1 at x = 0.7)
    joined by a spring of 1e-6 at x = 0.37: a pair 6e-8 apart near 15.418i, isolated in
    a sub-search about their cluster, whose boxes Rouche's theorem in balls now proves
    (it did only at the search's top level: 'two precisions'). Values: the in-phase root
    of the single beam with its dashpot, the anti-phase one with a grounded spring of
    2e-6 added (``damped_reference.beam_char``, nothing of symtmm), to the printed digits."""
    beams = tuple(Beam(n, 2, 2, 1, left="pinned", right="free") for n in "ab")
    model = Model(beams, (Spring("a", "b", "37/100", "1e-6"),
                          Spring("a", "ground", "7/10", 0, c="1/10"),
                          Spring("b", "ground", "7/10", 0, c="1/10")))
    spec = solve_damped(model, count=6, digits=15)
    pair = [e for e in spec if 15 < float(e.lam.imag) < 16]
    assert len(pair) == 2
    assert all(e.proof == DAMPED_PROOFS["rouche"] for e in pair)
    with mpmath.workdps(40):
        refs = []
        for supports in ([("0.7", 0, "0.1")], [("0.7", 0, "0.1"), ("0.37", "2e-6", 0)]):
            sup = [(mpmath.mpf(x), mpmath.mpf(k), mpmath.mpf(c)) for x, k, c in supports]
            refs.append(mpmath.findroot(
                lambda z, sup=sup: beam_char(z, 2, 2, 1, "pinned", "free", sup),
                mpmath.mpc(pair[0].lam)))
    for e, ref in zip(sorted(pair, key=lambda e: float(e.lam.imag)),
                      sorted(refs, key=lambda z: float(z.imag))):
        assert decimal_string(e.lam.imag, 15) == decimal_string(ref.imag, 15)
        assert decimal_string(e.lam.real, 15) == decimal_string(ref.real, 15)


_LONG_BEAM_ON_FOUNDATION = """
[[beam]]
name = "b0"
EI = 5.09
m = 0.731
L = 46.3
left = "clamped"
right = "clamped"
kw = 410.0

[[spring]]
between = ["b0", "ground"]
x = 0.0
k = 1130000.0
kind = "rotational"
c = 0.0259

[[spring]]
between = ["b0", "ground"]
x = 35.65
k = 14300000.0

[[spring]]
between = ["b0", "ground"]
x = 23.15
k = 0.0437

[[spring]]
between = ["b0", "ground"]
x = 23.15
k = 159.0

[[mass]]
beam = "b0"
x = 3.357
M = 761.0
"""


def test_a_count_in_a_dense_spectrum_proves_few_eigenvalues(tmp_path, monkeypatch):
    """A long beam on a foundation (found by a campaign of random models): its modes
    crowd just above sqrt(kw / m), where the count's first guess lands, and doubling the
    region took in 57 eigenvalues for the 2 asked, each proved by dense determinants of
    148 freedoms: past the time budget. The region's top is lowered while it holds the
    count, and a Rouche disk no larger disk can rescue is given up. Reference: the
    same model without its dashpot, which sits at a clamped end and never moves
    (the undamped search, on the frequency axis)."""
    from symtmm.numeric import evaluator

    boxes = []
    enclose = evaluator.Evaluator.enclose

    def counted(self, lam, ar):
        boxes.extend(lam)
        return enclose(self, lam, ar)
    monkeypatch.setattr(evaluator.Evaluator, "enclose", counted)
    path = tmp_path / "long.toml"
    path.write_text(_LONG_BEAM_ON_FOUNDATION)
    damped = solve(load(path), count=2, digits=15)
    path.write_text(_LONG_BEAM_ON_FOUNDATION.replace("c = 0.0259\n", ""))
    undamped = solve(load(path), count=2, digits=15)
    def printed(spectrum):
        return [(d["real"], d["imag"], d["multiplicity"])
                for d in (e.to_dict() for e in spectrum)]
    assert printed(damped) == printed(undamped)
    region = next(n for n in damped.notes if n.startswith("search region"))
    top = float(region.split("Im lam <=")[1].split()[0])
    assert top < 1.02 * 23.6830887813572         # (the doubling's top: 47.4)
    # (the eigenvalues its Rouche proofs enclosed, each maybe more than once: the model's
    # long pieces make a box's enclosure cheap, and wider, so some boxes take a second disk)
    assert len({complex(b.mid()) for b in boxes}) <= 12


# a campaign's model: a short stiff beam, a heavy soft one on a foundation and a light one
# free to slide, held by a spring and a dashpot: a real eigenvalue near -k / c
_SLIDING_ON_A_DASHPOT = """
[[beam]]
name = "b0"
EI = 69200000.0
m = 0.0209
L = 0.0661
left = "sliding"
right = "clamped"

[[beam]]
name = "b1"
EI = 0.00771
m = 1620.0
L = 93.2
left = "clamped"
right = "free"
theory = "rayleigh"
rhoI = 65.7
kw = 40.1

[[beam]]
name = "b2"
EI = 0.0808
m = 0.031
L = 17.8
left = "free"
right = "sliding"

[[spring]]
between = ["b2", "b1"]
x = 17.8
k = 0.789
c = 10.9

[[spring]]
between = ["b1", "b0"]
x = 0.0
k = 0.00899
kind = "rotational"

[[spring]]
between = ["b0", "b1"]
x = 0.0661
k = 11700000.0
c = 1.94
"""


def test_a_real_eigenvalue_reaches_30_digits_when_its_secant_steps_crawl():
    """The pairs proving a real zero were placed 1e-33 apart about each secant estimate,
    which here closed in on the zero by 1/60 a round from one side: no pair straddled it
    within the rounds, at any precision ("cannot reach 30 digits"). The next pair is as
    wide as twice the last step. Reference: the transfer formulation (a second one) at
    200 digits (its walk along the soft beam on a foundation loses about 50) changes
    sign between the printed value's neighbours in its 30th digit."""
    model = loads(_SLIDING_ON_A_DASHPOT)
    spectrum = solve(model, count=3, digits=30)
    real = [e for e in spectrum if e.lam.imag == 0 and e.lam.real != 0]
    assert len(real) == 1
    ev = Evaluator(model.require_numeric())
    with mpmath.workdps(200):
        x = mpmath.mpf(decimal_string(real[0].lam.real, 30))
        ulp = abs(x) * mpmath.mpf(10) ** -29
        ends = [mpmath.re(ev.delta_mp(mpmath.mpc(x + d, 0), dps=200)) for d in (-ulp, ulp)]
    assert ends[0] * ends[1] < 0


_STIFF_PIN = """
[[beam]]
name = "stiff"
EI = 157000000.0
m = 0.00915
L = 0.0414
x0 = 0.5
left = "pinned"
right = "free"

[[beam]]
name = "b"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[spring]]
between = ["stiff", "b"]
x = 0.5
k = 100
c = 0.5
"""


def test_points_no_pivoting_can_trust_go_to_the_balls_without_it(monkeypatch):
    """A stiff short beam free to turn about its pin (from a campaign model): its static
    stiffness cancels to a pivot 1e-15 of the others at every point, which no double
    factorisation trusts, with pivoting or without. Once a plan's pivoted factorisations
    have trusted none of their first points, its untrusted points go to the balls without
    them, with the same digits. References: the spring and dashpot sit on the stiff beam's
    pin, so the model is the pinned-pinned beam on a grounded spring and dashpot at
    mid-span (its Green's-function characteristic equation; its second mode, 4 pi**2,
    does not move them) beside the stiff beam's turning about its pin (lam = 0). (The
    whole model's damped search: ``solve`` takes the two beams apart, the spring at the
    pin grounding the other, and never meets the mechanism's pivots.)"""
    from symtmm.numeric import evaluator

    rescued = []
    pivoted = evaluator._pivoted_log_delta

    def counted(fa, points=None):
        out = pivoted(fa, points)
        rescued.append(len(out[2]))
        return out
    monkeypatch.setattr(evaluator, "_pivoted_log_delta", counted)
    model = loads(_STIFF_PIN)
    spectrum = solve_damped(model, count=3, digits=15)
    with_record = sum(rescued)
    monkeypatch.setattr(evaluator, "RESCUE_TRIAL", 10**9)
    rescued.clear()
    again = solve_damped(loads(_STIFF_PIN), count=3, digits=15)
    assert with_record < sum(rescued) / 2
    with mpmath.workdps(40):
        root = mpmath.findroot(lambda z: pp_char(z, 1, 1, 1, [(mpmath.mpf("0.5"), 100,
                                                               mpmath.mpf("0.5"))]),
                               mpmath.mpc(-0.47, 17.06))
        refs = [mpmath.mpc(0), root, mpmath.mpc(0, 4 * mpmath.pi ** 2)]
    for spec in (spectrum, again):
        assert [e.multiplicity for e in spec] == [1, 1, 1]
        for e, ref in zip(spec, refs):
            for part, want in ((e.lam.real, ref.real), (e.lam.imag, ref.imag)):
                assert decimal_string(part, 15) == decimal_string(want, 15)


def test_a_count_keeps_the_eigenvalues_counted_above_a_lowered_top(tmp_path, monkeypatch):
    """A soft beam on a foundation whose modes crowd 1e-6 and 6e-6 above its first (a
    campaign model's two beams): the count's region was lowered onto the first, its
    rectangles, a little taller than the top they are counted for, held the three, and
    the answer cut the two above that top (1 eigenvalue printed for ``--count 3``). Its
    Rouche boxes miss by 1e200 (the dense enclosure's preconditioner inverts a nearly
    singular ``K``): the first box's miss gives up the others, one enclosure where each
    box took two. Reference: the same model without its dashpot, which moves the
    frequencies by under 1e-28 (the two agree to 29 digits): the undamped search, on the
    frequency axis, and the transfer formulation's Delta of it (a second formulation, at
    220 digits: its walk along the soft beam loses about 160), which changes sign across
    each printed frequency."""
    from symtmm.numeric import evaluator

    enclosed = []
    enclose = evaluator.Evaluator.enclose
    monkeypatch.setattr(evaluator.Evaluator, "enclose",
                        lambda self, lam, ar: enclosed.append(len(lam)) or enclose(self, lam, ar))
    path = tmp_path / "crowded.toml"
    path.write_text(CROWDED_ON_FOUNDATION)
    damped = solve(load(path), count=3, digits=15)
    path.write_text(CROWDED_ON_FOUNDATION.replace("c = 0.308\n", ""))
    undamped = solve(load(path), count=3, digits=15)
    assert [decimal_string(e.lam.imag, 15) for e in damped] == \
        [decimal_string(e.lam.imag, 15) for e in undamped]
    assert all(-1e-18 < float(e.lam.real) < 0 for e in damped)
    assert sum(enclosed) <= 1
    transfer = Evaluator(load(path).require_numeric())
    with mpmath.workdps(220):
        for e in damped:
            w = mpmath.mpf(decimal_string(e.lam.imag, 15))
            ends = [transfer.delta_omega_mp(w * (1 + d), dps=220) for d in (-1e-14, 1e-14)]
            assert ends[0] * ends[1] < 0


# a campaign's model: a very stiff short beam (b1) on soft springs beside a long soft beam
# on a foundation; the radii of its balls grow by about 10**55 along the band
_STIFF_SHORT_BEAM = """
[[beam]]
name = "b0"
EI = 0.0027
m = 647.0
L = 5.22
left = "free"
right = "sliding"
kw = 459.0

[[beam]]
name = "b1"
EI = 480000000.0
m = 34.2
L = 0.0772
left = "free"
right = "pinned"

[[beam]]
name = "b2"
EI = 69.5
m = 37.3
L = 0.224
left = "sliding"
right = "sliding"
theory = "timoshenko"
rhoI = 0.000112
kGA = 69700000.0

[[spring]]
between = ["b0", "b2"]
x = 0.224
k = 70.7

[[spring]]
between = ["b0", "b1"]
x = 0.05944
k = 18.3
c = 0.23

[[spring]]
between = ["b1", "b0"]
x = 0.0
k = 52.5
c = 10.6
"""


def test_values_reach_their_digits_where_the_compiled_balls_round_the_precision(
        monkeypatch):
    """A point whose compiled balls decide every pivot but carry its value to 2 digits
    only, at 30, 40 and 50 digits alike (the words round the precision up to a tier that
    the growth of the radii eats): the contour found no trusted value there, and the
    model's search failed with "a zero lies too close to the contour". The values now
    come with radii under a thousandth of them (what the contours ask); reference: Arb's
    own elimination at 120 digits (the compiled balls switched off)."""
    from symtmm.numeric import multiword
    from symtmm.roots.damped import _Problem

    model = loads(_STIFF_SHORT_BEAM)
    # (a side of the contour beside the region's corner: the batch's largest |lam| picks
    # the plan, on which these points' balls grow so)
    points = [mpmath.mpc(0.0336910356580728, y) for y in np.linspace(0.70, 0.80, 40)]
    points.append(mpmath.mpc(-1.68455195135882, 0.842276059906997))
    got = _Problem(model, 1.9775557).values(points, 30)
    monkeypatch.setattr(multiword, "ENABLED", False)
    reference = _Problem(model, 1.9775557).values(points, 120)
    for a, b in zip(got, reference):
        assert a is not None and b is not None
        assert abs(a - b) <= abs(b) / 1024


@pytest.mark.slow
def test_a_stiff_short_beam_on_soft_springs_is_solved():
    """The campaign's model whose search failed ("a zero lies too close to the contour"):
    solved. Reference: the undamped search of the model without its dashpots (the
    Wittrick-Williams count on the frequency axis); the damping ratios are 7e-6 and
    2e-11, and move the frequencies by less than 1e-7 of them."""
    damped = solve(loads(_STIFF_SHORT_BEAM), count=2, digits=15)
    undamped = solve(loads(_STIFF_SHORT_BEAM.replace("c = 0.23\n", "")
                           .replace("c = 10.6\n", "")), count=2, digits=15)
    assert len(damped.eigenvalues) == len(undamped.eigenvalues) == 2
    for d, u in zip(damped.eigenvalues, undamped.eigenvalues):
        lam, omega = complex(d.lam), float(u.omega)
        assert -1e-5 * omega < lam.real < 0
        assert abs(lam.imag - omega) < 1e-7 * omega


_TIMOSHENKO_ON_STIFF_FOUNDATION = """
[[beam]]
name = "b0"
EI = 0.225
m = 0.0707
L = 22.2
left = "sliding"
right = "free"

[[beam]]
name = "b1"
EI = 11.4
m = 9.71
L = 60.2
left = "sliding"
right = "pinned"
theory = "timoshenko"
rhoI = 9.35
kGA = 11.8
kw = 48800.0

[[spring]]
between = ["b1", "b0"]
x = 11.1
k = 15900000.0
c = 4460.0
"""


def test_a_timoshenko_beam_on_a_stiff_foundation_is_counted_on_a_coarse_grid():
    """A campaign's model (kw L**4 / EI = 6e10): the contours' first grid followed the
    foundation's evanescent wave number, 75,000 points a side, and the search stopped at
    its 60 s budget (which a solve stops at with an error). The foundation is left out
    of that wave number, as a plain beam's leaves it. Reference: the undamped search of the model without its dashpot (the
    beam on the foundation barely moves the dashpot: damping ratios below 1e-14)."""
    damped = solve(loads(_TIMOSHENKO_ON_STIFF_FOUNDATION), count=3, digits=15)
    undamped = solve(loads(_TIMOSHENKO_ON_STIFF_FOUNDATION.replace("c = 4460.0\n", "")),
                     count=3, digits=15)
    assert [e.to_dict()["imag"] for e in damped] == [e.to_dict()["imag"] for e in undamped]


@pytest.mark.skipif(not ball_available(), reason="python-flint not installed")
def test_box_enclosures_in_fewer_bits_hold_delta_and_bound_it_as_tightly():
    """A Rouche disk's square is enclosed with the bits its relative width leaves and a
    guard, not the proof's (a dense determinant of 38 freedoms: 13 ms at 181 bits, 8 at
    110). The enclosure holds Delta at the square's centre and corners (Arb at 300 bits,
    at exact points) and bounds |Delta| over it within a few per cent of the enclosure at
    the proof's precision: the proof's M is as good."""
    import flint

    from symtmm.numeric.arith import Ball
    from symtmm.roots.damped import _box_arithmetic

    ar = Ball.from_digits(50)
    z, half = complex(-0.00125, 0.0597), 1e-14       # (near the first zero of EX4's model)
    narrow = _box_arithmetic(ar, half / abs(z))
    assert narrow.prec < ar.prec
    kernel = Kernel(load(EX4), 1.0)
    box = flint.acb(flint.arb(z.real, half), flint.arb(z.imag, half))
    wide_bits = kernel.enclose([box], ar)[0]
    few_bits = kernel.enclose([box], narrow)[0]
    fine = Ball(300)
    corners = [z + half * complex(a, b) for a in (-1, 0, 1) for b in (-1, 0, 1)]
    exact, trusted = kernel.delta([mpmath.mpc(c) for c in corners], fine)
    assert trusted.all()
    for v in exact:
        assert few_bits.contains(v) and wide_bits.contains(v)
    assert float(few_bits.abs_upper()) <= 1.05 * float(wide_bits.abs_upper())
    assert float(few_bits.rad()) <= 1.05 * float(wide_bits.rad()) < 1e-9 * abs(exact[4])


def test_a_winding_number_that_is_no_count_is_sampled_again(monkeypatch):
    """A part's winding number of -2 (a campaign's model, its sampling missed turns of
    arg Delta near a dense cluster) escaped as a traceback from the subdivision; it is
    now taken as a split whose counts disagree: the same split at a stricter sampling.
    Here the first count of every split is made to fail so: the solve is the one without
    (the pure dashpot's published values of the reliability issue)."""
    from symtmm.roots import contour

    counts = contour.ArgumentPrinciple.counts_and_centers
    failed = set()

    def once(self, rects, strictness=0):
        key = (tuple(rects), strictness)
        if len(rects) > 1 and strictness == 0 and key not in failed:
            failed.add(key)
            raise contour.CountError("winding number -2.000 around a part is not a count")
        return counts(self, rects, strictness)
    monkeypatch.setattr(contour.ArgumentPrinciple, "counts_and_centers", once)
    model = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="free"),),
                  (Spring("b", "ground", x="3/5", k=0, c=2),))
    spectrum = solve_damped(model, omega_max=110, digits=12)
    assert failed
    published = [0, -2.19141315549854, -0.623622447176967 + 15.3310074918209j,
                 -1.43788429657287 + 49.8554523918882j, -0.056570866708691 + 104.245191761378j]
    got = sorted((complex(e.lam) for e in spectrum), key=lambda z: (z.imag, z.real))
    assert len(got) == len(published)
    for z, ref in zip(got, sorted(published, key=lambda z: (complex(z).imag, complex(z).real))):
        assert abs(z - ref) <= 1e-11 * max(abs(ref), 1.0)


def _fake_search(values):
    """A search whose ``_real_values`` are ``values(x, ctx)`` at real points: what
    :meth:`symtmm.roots.damped._Search._pairs` reads, and nothing else."""
    from types import SimpleNamespace

    from symtmm.numeric.arith import MP
    from symtmm.roots.damped import _Search
    calls = []

    def real_values(points, digits):
        calls.append(len(points))
        ctx = MP.from_digits(digits + 30).ctx
        return [values(ctx.mpf(p.real), ctx) for p in points]
    fake = SimpleNamespace(digits=15, floor=15, p=SimpleNamespace(lam_ref=1.0, balls=True),
                           _real_values=real_values)
    fake._digits_for = lambda z, small=None: _Search._digits_for(fake, z, small)
    return fake, calls


def test_a_real_zero_far_from_its_estimate_is_reached_by_halving():
    """Delta grows like an exponential along the real axis: secant steps from an estimate
    far from the zero crawled (0.09 a round across a bracket of 78, the contour's midpoint
    of a pure-dashpot beam's rectangle), and the search failed ("cannot reach 15 digits
    for the real eigenvalue near -40.03"). Where two rounds do not halve the bracket, its
    midpoint. Reference: the zero of exp(-20 x) - exp(-20 r) is r."""
    from symtmm.roots.damped import _Search
    r = "-2.19141315549854061840715649358"
    fake, calls = _fake_search(lambda x, ctx: ctx.exp(-20 * x) - ctx.exp(-20 * ctx.mpf(r)))
    (e,) = _Search._pairs(fake, [-40.03], [(-78.96, -1.0957)])
    lo, hi = e.bracket
    with mpmath.workdps(30):
        assert lo <= mpmath.mpf(r) <= hi and hi - lo < 1e-15
    assert e.to_dict()["real"] == "-2.19141315549854"
    assert sum(calls) < 200


def test_a_real_count_that_the_signs_refute_fails_at_once():
    """Signs that are certain and equal at both ends of a rectangle said to hold one real
    zero: more digits cannot change them (it looped to 1500 digits); the count was
    misled, and the line says so."""
    from symtmm.errors import ComputationError
    from symtmm.roots.damped import _Search
    fake, calls = _fake_search(lambda x, ctx: 1 + x * x)
    with pytest.raises(ComputationError, match="same sign at both ends"):
        _Search._pairs(fake, [0.5], [(0.0, 1.0)])
    assert len(calls) == 1


def test_a_real_bracket_whose_ends_differ_by_a_thousand_e_folds_is_shrunk_in_double():
    """The double bracketing of a real zero took the product of its ends' scaled values as
    the sign change; an end 1500 e-folds below the other scales to a signed zero, the
    product was -0, and the zero went to the proofs from the rectangle's midpoint, 38 from
    it (the contour method on a pure-dashpot beam). The sides come from the signs.
    Reference: the zero of exp(-20 x) - exp(-20 r) is r."""
    import types

    import numpy as np

    from symtmm.roots.contour import Rectangle
    from symtmm.roots.damped import _Search
    r = -2.19141315549854

    def log_delta(z):
        x = np.asarray(z).real
        with np.errstate(over="ignore", divide="ignore"):
            # log|f| and its phase for f = exp(-20 x) - exp(-20 r), without overflow
            big = np.maximum(-20 * x, -20 * r)
            small = np.minimum(-20 * x, -20 * r)
            la = big + np.log1p(-np.exp(small - big))
        return la, np.where(x < r, 0.0, np.pi), np.ones(x.shape, dtype=bool)

    got = []
    fake = types.SimpleNamespace(origin=None, p=types.SimpleNamespace(
        log_delta=log_delta, kernel=types.SimpleNamespace(log_delta=log_delta)),
        _pairs=lambda estimates, outer: got.append(estimates) or [])
    fake._at = lambda u, ctx=None: _Search._at(fake, u, ctx)
    _Search.refine_real(fake, [Rectangle(-78.96, -1.0957, -1.0, 1.0)])
    assert abs(got[0][0] - r) < 1e-10


@pytest.fixture
def searched(monkeypatch):
    """The tops of the damped count's region searches, as they are made."""
    from symtmm.roots import damped
    tops = []
    real = damped._search_region

    def recording(model, W, *args):
        tops.append(W)
        return real(model, W, *args)

    monkeypatch.setattr(damped, "_search_region", recording)
    return tops


def test_a_count_starts_its_region_between_the_undamped_modes(searched):
    """A lightly damped pinned-pinned beam on a foundation, its modes crowding above the
    cut-off ``sqrt(kw / m) = 100``: the top of the count's region is taken in a gap of
    the undamped modes above the third (the first 2 % wide: between the fourth and the
    fifth), and one region search serves (doubling
    from the lowest pinned mode went to 200, 12 eigenvalues, and four searches lowered
    it again). Reference: the Green's function of the beam on its foundation
    (tests/damped_reference.py), followed from the undamped roots as the dashpot grows."""
    beam = Beam("b", 1, 1, 3, left="pinned", right="pinned", kw=10**4)
    model = Model((beam,), (Spring("b", "ground", "7/10", 20, c=1),))
    spectrum = solve_damped(model, count=3, digits=12)
    refs = sorted(pp_damped_roots(1, 1, 3, [(Fraction(7, 10), 20, 1)], 125, kw=10**4,
                                  points=20000, steps=64, dps=30), key=lambda z: z.imag)[:3]
    assert len(spectrum) == 3
    for e, ref in zip(spectrum, refs):
        assert abs(e.lam - ref) <= 1e-11 * abs(ref), (e.lam, ref)
    assert len(searched) == 1 and 101.53 < searched[0] < 103.69      # between modes 4 and 5


def test_a_real_zero_beside_a_rigid_turning_counts_in_the_first_region(searched):
    """A pinned-free beam with a pure dashpot (the issue's model): its two lowest
    eigenvalues, the turning about the pin and the real one the dashpot makes, lie in the
    strip about the real axis of the first region. That region's count had halved the
    strip's two zeros to one (the zero at 0 among them) and doubled the region. Reference:
    the values published with the issue (an independent state-space FE and an exact
    determinant): 0 and -2.19141315549854."""
    beam = Beam("b", 1, 1, 1, left="pinned", right="free")
    spectrum = solve_damped(Model((beam,), (Spring("b", "ground", "3/5", 0, c=2),)),
                            count=2, digits=15)
    lams = sorted((complex(e.lam) for e in spectrum), key=lambda z: z.real)
    assert len(searched) == 1 and len(lams) == 2
    assert abs(lams[0] - (-2.19141315549854)) < 1e-13 and lams[1] == 0
