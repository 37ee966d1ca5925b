"""Digits on demand, close and multiple roots, and the count that cannot miss."""

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import classical_roots

from symtmm import Beam, Model, Spring
from symtmm.errors import ComputationError
from symtmm.solve import solve
from symtmm.stiffness import StiffnessModel

pp = dict(EI=1, m=1, L=1, left="pinned", right="pinned")


def _chain(K, xs=("0.25", "0.75")):
    beams = tuple(Beam(n, **pp) for n in ("a", "b", "c"))
    return Model(beams, tuple(Spring(p, q, x, K) for p, q in (("a", "b"), ("b", "c"))
                              for x in xs))


def _decoupled(K, factor, xs=("0.25", "0.75")):
    springs = tuple(Spring("b", "ground", x, f"{factor}*{K}") for x in xs) if factor else ()
    return Model((Beam("b", **pp),), springs)


def test_three_roots_within_5e_10_of_pi_are_resolved():
    """K = 1e-8: the three families 0, K, 3K split Omega = pi by < 5e-10."""
    spectrum = solve(_chain("1e-8"), count=3, digits=25)
    assert [e.multiplicity for e in spectrum] == [1, 1, 1]
    refs = [solve(_decoupled("1e-8", f), count=1, digits=30)[0].omega for f in (0, 1, 3)]
    with mpmath.workdps(40):
        Omegas = [mpmath.sqrt(e.omega) for e in spectrum]
        assert all(abs(x - mpmath.pi) < 5e-10 for x in Omegas)
        for got, ref in zip(spectrum, sorted(refs)):
            assert abs(got.omega - ref) < mpmath.mpf(10) ** -24 * ref
    assert refs[0] == solve(_decoupled("1e-8", 0), count=1, digits=30)[0].omega


def test_fifty_digits():
    model = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="free"),))
    spectrum = solve(model, count=3, digits=50)
    expected = classical_roots("clamped", "free", 3, dps=80)
    with mpmath.workdps(80):
        for nu, e in zip(expected, spectrum):
            assert abs(e.omega - nu**2) < mpmath.mpf(10) ** -49 * nu**2
            assert len(e.to_dict()["imag"].replace(".", "")) >= 50


def test_hundred_clamped_clamped_modes_at_20_digits():
    """High modes: Delta loses ~137 digits at mode 100; every digit must still be right."""
    model = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
    spectrum = solve(model, count=100, digits=20)
    assert len(spectrum) == 100
    with mpmath.workdps(60):
        for e in spectrum:
            nu = mpmath.findroot(lambda x: mpmath.cos(x) - mpmath.sech(x), mpmath.sqrt(e.omega))
            assert abs(e.omega - nu**2) < mpmath.mpf(10) ** -19 * nu**2


def test_unreachable_digits_are_refused(monkeypatch):
    import symtmm.roots.undamped as und

    monkeypatch.setattr(und, "MAX_DPS", 40)
    model = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
    with pytest.raises(ComputationError, match="cannot reach 30 digits"):
        solve(model, count=12, digits=30)


def test_banded_count_equals_dense_eigenvalue_count():
    model = _chain(25, ("0.3", "0.8"))
    sm = StiffnessModel(model, 2000.0)
    for w in np.linspace(1.0, 2000.0, 60):
        dense = int(np.sum(np.linalg.eigvalsh(sm.matrix(w)) < 0))
        assert sm.count(w) == dense == sm.count(w, dps=30)


def test_same_roots_at_two_precisions():
    model = _chain(25, ("0.3", "0.8"))
    low, high = solve(model, count=9, digits=15), solve(model, count=9, digits=40)
    with mpmath.workdps(50):
        for a, b in zip(low, high):
            assert abs(a.omega - b.omega) <= mpmath.mpf(10) ** -14 * b.omega


# -- random multilevel models against the independent finite-element model ---------------
BCS = ["free", "clamped", "pinned", "sliding"]


@st.composite
def models(draw):
    n = draw(st.integers(1, 3))
    beams = []
    for i in range(n):
        beams.append(Beam(f"b{i}", EI=draw(st.sampled_from(["1", "2", "0.5"])),
                          m=draw(st.sampled_from(["1", "1.5"])),
                          L=draw(st.sampled_from(["1", "1.2", "0.8"])),
                          left=draw(st.sampled_from(BCS)), right=draw(st.sampled_from(BCS))))
    springs = []
    for _ in range(draw(st.integers(0, 3))):
        a = draw(st.integers(0, n - 1))
        b = draw(st.integers(-1, n - 1))
        if b == a:
            b = -1
        length = min(float(beams[a].L), float(beams[b].L)) if b >= 0 else float(beams[a].L)
        x = draw(st.integers(1, 19)) * length / 20
        springs.append(Spring(f"b{a}", f"b{b}" if b >= 0 else "ground", f"{x:.6f}",
                              draw(st.sampled_from(["5", "40", "300"]))))
    return Model(tuple(beams), tuple(springs))


def _plain(model):
    beams = [dict(name=b.name, EI=float(b.EI), m=float(b.m), L=float(b.L), x0=float(b.x0),
                  left=b.left, right=b.right) for b in model.beams]
    springs = [dict(between=(s.a, s.b), x=float(s.x), k=float(s.k)) for s in model.springs]
    return beams, springs


@settings(max_examples=12, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(models())
def test_random_models_agree_with_finite_elements(model):
    pytest.importorskip("scipy")
    from symtmm.fe import fe_frequencies

    spectrum = solve(model, count=8, digits=15)
    tmm = np.array([float(w) for w in spectrum.omegas(expand=True)])[:8]
    beams, springs = _plain(model)
    fe40, fe80 = (fe_frequencies(beams, springs, n, count=8) for n in (40, 80))
    fe = (16 * fe80 - fe40) / 15        # Richardson: cubic Hermite errors fall as h^4
    # nothing missed or invented: the FE spectrum matches one for one, within FE error
    assert len(tmm) == 8
    scale = max(tmm.max(), 1.0)
    assert np.all(np.abs(fe - tmm) <= 1e-6 * np.maximum(tmm, 1e-3 * scale))
