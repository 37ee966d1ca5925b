"""Certified enclosures (python-flint ball arithmetic) contain independent references."""

from __future__ import annotations

import builtins
import json
from pathlib import Path

import mpmath
import pytest
from damped_reference import CROWDED_ON_FOUNDATION, ex4_reference, pp_char

from symtmm.cli import main
from symtmm.errors import ComputationError
from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load
from symtmm.roots.damped import solve_damped
from symtmm.roots.undamped import solve_undamped
from symtmm.solve import solve

flint = pytest.importorskip("flint")
from symtmm.roots.certified import certify, require_flint, to_arb

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"
EX4 = EXAMPLES / "paper_ex4_damped.toml"
PP = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))


def test_kernel_ball_encloses_the_transfer_value():
    """The stiffness kernel's ball for Delta contains the 60-digit value of the transfer
    formulation (a second formulation: the product of transfer matrices along x)."""
    from symtmm.compile import Evaluator
    from symtmm.numeric.arith import Ball
    from symtmm.numeric.evaluator import Evaluator as Kernel
    model = load(EX4).require_numeric()
    kernel, ev = Kernel(model, 1300.0), Evaluator(model)
    for z in (mpmath.mpc(-1000, 700), mpmath.mpc(-0.25, 3), mpmath.mpc(-30, 0)):
        ball = kernel.delta([z], Ball(300))[0][0]
        exact = ev.delta_mp(z, dps=60)
        assert ball.contains(flint.acb(exact.real, exact.imag)) or \
            abs(complex(ball.mid()) - complex(exact)) < 1e-40 * abs(exact)
        assert ball.rad() < 1e-50 * abs(complex(ball.mid()))


def test_rouche_proves_a_zero_alone_and_nothing_where_there_is_none():
    """A pinned-pinned beam with a dashpot: a box about its first eigenvalue (from the
    Green's-function reference) is proved; boxes beside it, or between two eigenvalues,
    are not."""
    from symtmm.roots.damped import _Problem, _Search
    model = Model(PP.beams, (Spring("b", "ground", x="3/10", k=0, c=4),)).require_numeric()
    search = _Search(_Problem(model, 60.0, certified=True), 15)
    with mpmath.workdps(50):
        sup = [(mpmath.mpf(3) / 10, 0, 4)]
        root = mpmath.findroot(lambda z: pp_char(z, 1, 1, 1, sup), mpmath.mpc(-2.7, 9.6))
        r = mpmath.mpf(10) ** -20 * abs(root)
        beside = root + 10 * r
        between = mpmath.mpc(-3, 24)
    assert search._rouche([(root, r), (beside, r), (between, r)], 60) == [True, False, False]


def test_rouche_encloses_each_square_once_where_the_first_radius_proves(monkeypatch):
    """Each disk radius is a dense ball determinant per box: a box proved by the first
    radius tried costs one enclosure, not one per radius. The reference: the roots of
    the Green's-function characteristic equation, as above."""
    from symtmm.roots.damped import _Problem, _Search
    model = Model(PP.beams, (Spring("b", "ground", x="3/10", k=0, c=4),)).require_numeric()
    search = _Search(_Problem(model, 60.0, certified=True), 15)
    enclosed = []
    enclose = type(search.p.kernel).enclose
    monkeypatch.setattr(type(search.p.kernel), "enclose",
                        lambda self, lam, ar: enclosed.append(len(lam)) or enclose(self, lam, ar))
    with mpmath.workdps(50):
        sup = [(mpmath.mpf(3) / 10, 0, 4)]
        roots = [mpmath.findroot(lambda z: pp_char(z, 1, 1, 1, sup), mpmath.mpc(*guess))
                 for guess in ((-2.7, 9.6), (-1.3, 39.3))]
        items = [(root, mpmath.mpf(10) ** -20 * abs(root)) for root in roots]
    assert search._rouche(items, 60) == [True, True]
    assert sum(enclosed) == 2           # (the first box alone, then the rest)


def test_exact_points_whose_band_balls_run_out_of_bits_take_more_bits_not_dense(monkeypatch):
    """Complex balls widen along a band geometrically (the wrapping of their products):
    at 217 bits a soft beam on a foundation (199 freedoms) loses them all, and the Rouche
    proofs' points (``retry=False``) went to Arb's dense determinant, a second each, no
    narrower. They take the bits the radii need, within the band. The reference: the
    transfer formulation at 300 digits (a second formulation)."""
    from symtmm.compile import Evaluator
    from symtmm.modelfile import loads
    from symtmm.numeric.arith import Ball
    from symtmm.numeric.evaluator import Evaluator as Kernel
    from symtmm.numeric.stiffness import Factors
    model = loads(CROWDED_ON_FOUNDATION).require_numeric()
    kernel, transfer = Kernel(model, 140.0), Evaluator(model)
    dense = []
    monkeypatch.setattr(Factors, "pivoted_delta", lambda self, points: dense.append(points))
    points = [mpmath.mpc(-1e-20, 34.0701), mpmath.mpc(0, 34.07)]
    assert not any(v.abs_upper().is_finite() for v in
                   kernel.factors(points, Ball(217), retry=False).delta())
    values, trusted = kernel.delta(points, Ball(217), retry=False)
    assert trusted.all() and not dense
    for z, ball in zip(points, values):
        exact = transfer.delta_mp(z, dps=300)
        assert ball.contains(flint.acb(exact.real, exact.imag)) or \
            abs(complex(ball.mid()) - complex(exact)) < 1e-40 * abs(exact)
        assert ball.rad() < 1e-40 * abs(complex(ball.mid()))


def test_a_band_ball_whose_last_pivot_holds_zero_still_holds_delta(monkeypatch):
    """Within 1e-55 of a root, at 200 bits, the band elimination cannot decide its last
    pivot (the one that carries the zero of Delta); its ball is finite and holds Delta,
    so it is used as it is, without the dense determinant. The reference: the root of
    the Green's-function characteristic equation, and Delta there from the transfer
    formulation at 90 digits (a second formulation)."""
    from symtmm.compile import Evaluator
    from symtmm.numeric.arith import Ball
    from symtmm.numeric.evaluator import Evaluator as Kernel
    from symtmm.numeric.stiffness import Factors
    model = Model(PP.beams, (Spring("b", "ground", x="3/10", k=0, c=4),)).require_numeric()
    with mpmath.workdps(90):
        sup = [(mpmath.mpf(3) / 10, 0, 4)]
        root = mpmath.findroot(lambda z: pp_char(z, 1, 1, 1, sup), mpmath.mpc(-2.7, 9.6))
        z = root * (1 + mpmath.mpf(10) ** -75)
    kernel = Kernel(model, 60.0)
    assert not kernel.factors([z], Ball(200), retry=False).trusted[0]
    dense = []
    monkeypatch.setattr(Factors, "pivoted_delta", lambda self, points: dense.append(points))
    [value], [trusted] = kernel.delta([z], Ball(200), retry=False)
    assert trusted and not dense and value.abs_upper().is_finite()
    exact = Evaluator(model).delta_mp(z, dps=90)
    with flint.ctx.workprec(300):
        assert value.contains(flint.acb(exact.real, exact.imag))


def test_exact_parameters_as_balls():
    import sympy as sp
    with flint.ctx.workprec(200):
        b = to_arb((sp.Rational(1462698, 10000) / sp.pi**2) ** 2, flint)
    with mpmath.workdps(50):
        exact = (mpmath.mpf("146.2698") / mpmath.pi**2) ** 2
    assert abs(float(b.mid()) - float(exact)) < 1e-12 and b.rad() < 1e-50


@pytest.mark.parametrize("balls", [True, False])
def test_example4_enclosures_contain_decoupled_references(balls):
    """Proved by the solver (Rouche's theorem on a box, in balls) or afterwards, the same
    way, from a spectrum found without balls."""
    spec = solve_damped(load(EX4), omega_max=1500, digits=15, certified=balls)
    enclosures = certify(load(EX4), spec)
    refs = ex4_reference(dps=50)      # the enclosures are about 1e-29 wide
    assert len(enclosures) == len(refs) == 9
    assert [enc.proof for enc in enclosures] == ["Rouche"] * 9
    assert not any(enc.note for enc in enclosures)
    for enc, (ref, family) in zip(enclosures, refs):
        assert enc.contains(ref), (enc, ref)
        assert enc.radius < mpmath.mpf(10) ** -17 * abs(ref)
        if family == 0:         # in-phase: Re = 0 lies inside, not proved to be exact
            assert enc.real[0] < 0 < enc.real[1]


@pytest.mark.parametrize("certified", [True, False])
def test_undamped_enclosures(certified):
    """Proved by the solver's ball counts, or from a spectrum found without balls, by
    ball counts at the ends of its brackets."""
    spec = solve_undamped(PP, count=4, digits=20, certified=certified)
    enclosures = certify(PP, spec)
    for n, enc in enumerate(enclosures, 1):
        assert enc.proof == "count"
        with mpmath.workdps(50):
            assert enc.contains(mpmath.mpc(0, (n * mpmath.pi) ** 2))
        assert enc.real == (0, 0)


def test_real_eigenvalue_sign_change_enclosure():
    model = Model(PP.beams, (Spring("b", "ground", x="1/2", k=0, c=50),))
    spec = solve(model, omega_max=100, digits=15)
    enclosures = certify(model, spec)
    real = [enc for enc in enclosures if enc.eigenvalue.lam.imag == 0]
    assert len(real) == 1 and real[0].proof == "sign change"
    with mpmath.workdps(40):
        sup = [(mpmath.mpf(1) / 2, 0, 50)]
        ref = mpmath.findroot(lambda s: mpmath.re(pp_char(mpmath.mpc(s, 0), 1, 1, 1, sup)),
                              (-1.2, -0.8), solver="anderson")
    assert real[0].contains(ref)
    assert all(enc.certified for enc in enclosures)


def test_rigid_modes_exact_and_multiple_roots_by_the_count():
    beams = tuple(Beam(n, EI=1, m=1, L=1, left="free", right="free") for n in "ab")
    model = Model(beams, (Spring("a", "b", x="1/2", k=30, c=0),))
    spec = solve(model, count=4, digits=12)
    enclosures = certify(model, spec)
    assert enclosures[0].proof == "exact" and enclosures[0].contains(0)
    triple = Model(tuple(Beam(n, EI=1, m=1, L=1, left="pinned", right="pinned") for n in "abc"))
    enc = certify(triple, solve(triple, count=6, digits=12))
    # the triple roots (n pi)**2: the count in ball arithmetic proves three eigenvalues
    # in each bracket, which holds the closed-form value
    assert [(e.certified, e.proof) for e in enc] == [(True, "count"), (True, "count")]
    with mpmath.workdps(40):
        assert all(e.contains(mpmath.mpc(0, (n * mpmath.pi) ** 2)) for e, n in zip(enc, (1, 2)))
        assert not enc[0].contains(mpmath.mpc(0, mpmath.pi**2 * (1 + mpmath.mpf(10) ** -12)))
    assert enc[0].to_dict(12)["proof"] == "count"
    # what cannot be proved says so (a damped multiple eigenvalue)
    from symtmm.roots.certified import Enclosure
    assert Enclosure(enc[0].eigenvalue, None, None, "none").to_dict(12) == {
        "certified": False, "proof": "none"}


def test_cli_certified_json(capsys):
    assert main(["solve", str(EX4), "--omega-max", "200", "--digits", "12", "--json",
                 "--certified"]) == 0
    out = json.loads(capsys.readouterr().out)
    first = out["eigenvalues"][0]
    lo, _ = (mpmath.mpf(v) for v in first["enclosure"]["imag"])
    assert first["enclosure"]["certified"] and first["enclosure"]["proof"] == "Rouche"
    # the printed 12 digits are the enclosure rounded
    assert abs(mpmath.mpf(first["imag"]) - lo) < mpmath.mpf(10) ** -10
    assert mpmath.mpf(first["enclosure"]["radius"]) < mpmath.mpf(10) ** -12


def test_without_flint_one_line_error(monkeypatch, capsys):
    real_import = builtins.__import__

    def no_flint(name, *args, **kwargs):
        if name == "flint" or name.startswith("flint."):
            raise ImportError("No module named 'flint'")
        return real_import(name, *args, **kwargs)

    monkeypatch.setattr(builtins, "__import__", no_flint)
    with pytest.raises(ComputationError, match="python-flint"):
        require_flint()
    assert main(["solve", str(EX4), "--count", "2", "--certified"]) == 1
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and "python-flint" in err
