"""Beam options: the Winkler foundation ``kw``.

References are independent of the transfer-matrix code: closed forms (a
uniform foundation under a uniform beam shifts every ``omega**2`` by
``kw/m``), a decoupled identical-beam family, and the finite-element model of
:mod:`symtmm.fe` with the consistent foundation matrix added.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.linalg
import sympy as sp

from symtmm.characteristic import characteristic_equation
from symtmm.codegen import generate
from symtmm.errors import ModelError
from symtmm.fe import fe_matrices
from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import loads
from symtmm.modes import mode_shapes
from symtmm.roots.count import Counter
from symtmm.solve import solve

# first roots of cos(x) cosh(x) = 1 (free-free beam), to 15 digits
FREE_FREE = [4.73004074486270, 7.85320462409584, 10.9956078380017]


def _pp(kw, EI=2, m=3, L=1):
    return Model((Beam("b", EI=EI, m=m, L=L, left="pinned", right="pinned", kw=kw),), ())


def test_pinned_pinned_closed_form():
    EI, m, L, kw = 2, 3, 1, 500
    spec = solve(_pp(kw, EI, m, L), count=5, digits=20)
    got = spec.omegas(expand=True)
    with mpmath.workdps(30):
        for n, w in enumerate(got, 1):
            ref = mpmath.sqrt((EI * (n * mpmath.pi / L) ** 4 + kw) / mpmath.mpf(m))
            assert abs(w - ref) < mpmath.mpf(10) ** -18 * ref


def test_free_free_rigid_modes_lifted():
    EI, m, L, kw = 1, 2, 1, 50
    model = Model((Beam("b", EI=EI, m=m, L=L, left="free", right="free", kw=kw),), ())
    got = [float(w) for w in solve(model, count=5, digits=15).omegas(expand=True)]
    shift = kw / m
    ref = sorted([math.sqrt(shift)] * 2
                 + [math.sqrt(EI * (r / L) ** 4 / m + shift) for r in FREE_FREE])
    np.testing.assert_allclose(got, ref, rtol=1e-13)


def test_count_matches_closed_form():
    EI, m, L, kw = 2, 3, 1, 5000
    ref = [math.sqrt((EI * (n * math.pi / L) ** 4 + kw) / m) for n in range(1, 5)]
    sm = Counter(_pp(kw, EI, m, L), 1.2 * ref[-1])
    for n, w in enumerate(ref):
        assert sm.count(w * (1 - 1e-6)) == n
        assert sm.count(w * (1 + 1e-6)) == n + 1
    # below sqrt(kw/m) nothing at all: x < 0 there
    assert sm.count(0.9 * math.sqrt(kw / m)) == 0


def _fe_with_foundation(beams, springs, elements):
    """FE matrices with each beam's foundation ``kw`` (its consistent foundation matrix)."""
    K, M, _ = fe_matrices(beams, springs, elements)
    return K, M


def test_two_beams_against_fe():
    text = """
[[beam]]
name = "upper"
EI = 1
m = 1
L = 1
left = "free"
right = "free"
kw = 200
[[beam]]
name = "lower"
EI = 2
m = "3/2"
L = 1
left = "clamped"
right = "pinned"
[[spring]]
between = ["upper", "lower"]
x = 0.3
k = 150
[[spring]]
between = ["upper", "ground"]
x = 0.8
k = 40
"""
    model = loads(text)
    got = [float(w) for w in solve(model, count=6, digits=12).omegas(expand=True)]
    beams = [dict(name="upper", EI=1.0, m=1.0, L=1.0, x0=0.0, left="free", right="free",
                  kw=200.0),
             dict(name="lower", EI=2.0, m=1.5, L=1.0, x0=0.0, left="clamped", right="pinned",
                  kw=0.0)]
    springs = [dict(between=("upper", "lower"), x=0.3, k=150.0),
               dict(between=("upper", "ground"), x=0.8, k=40.0)]
    K, M = _fe_with_foundation(beams, springs, 80)
    ref = np.sqrt(np.sort(scipy.linalg.eigh(K, M, eigvals_only=True))[:6])
    np.testing.assert_allclose(got, ref, rtol=1e-7)


def test_damped_in_phase_modes_of_identical_beams():
    # two identical beams on identical foundations, joined by a spring and dashpot:
    # the in-phase modes do not stretch the joint and are the single beam's modes
    EI, m, kw = 1, 1, 300
    beams = tuple(Beam(n, EI=EI, m=m, L=1, left="pinned", right="pinned", kw=kw)
                  for n in ("a", "b"))
    model = Model(beams, (Spring("a", "b", x="3/10", k=50, c=2),))
    spec = solve(model, count=4, digits=10)
    lams = [complex(e.lam) for e in spec for _ in range(e.multiplicity)]
    for n in (1, 2):
        w = math.sqrt((EI * (n * math.pi) ** 4 + kw) / m)
        assert min(abs(lam - 1j * w) for lam in lams) < 1e-8 * w


def test_mode_shape_is_a_sine():
    model = _pp(400, EI=1, m=1)
    modes = mode_shapes(model, count=2, points=21)
    for n, mode in enumerate(modes, 1):
        beam = mode.beams["b"]
        x = np.asarray(beam.x, dtype=float)
        Y = np.real(np.asarray(beam.Y))
        ref = np.sin(n * math.pi * x)
        scale = np.dot(Y, ref) / np.dot(ref, ref)
        np.testing.assert_allclose(Y, scale * ref, atol=1e-10 * abs(scale))
        # mass normalisation: integral m Y**2 = m scale**2 / 2 = 1
        assert abs(scale**2 / 2 - 1) < 1e-10


def test_model_file_field_and_errors():
    base = """
[parameters]
K = 12
[[beam]]
name = "b"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"
"""
    assert loads(base).beams[0].kw == 0
    assert loads(base + 'kw = "K/4"\n').resolved().beams[0].kw == 3
    with pytest.raises(ModelError, match=r"beam\[1\] \(b\)\.kw.*negative"):
        loads(base + "kw = -1\n")
    with pytest.raises(ModelError, match=r"kw"):
        loads(base + 'kw = "-K"\n')


def test_derive_on_a_foundation_vanishes_at_the_closed_form():
    """Pinned-pinned on a foundation: omega_n**2 = (EI (n pi/L)**4 + kw)/m, from the
    JSON's delta (a SymPy string in omega) parsed back."""
    import json

    EI, m, L, kw = 2, 3, 1, 500
    data = json.loads(characteristic_equation(_pp(kw, EI, m, L)).to_json())
    assert data["variable"] == "omega"
    omega = sp.Symbol("omega", positive=True)
    delta = sp.sympify(data["delta"], locals={"omega": omega})
    assert delta.free_symbols == {omega}
    with mpmath.workdps(40):
        for n in (1, 2, 3):
            w = mpmath.sqrt((EI * (n * mpmath.pi / L) ** 4 + kw) / m)
            at = abs(complex(sp.N(delta.subs(omega, sp.Float(w, 40)), 40)))
            near = abs(complex(sp.N(delta.subs(omega, sp.Float(w * (1 + mpmath.mpf(10) ** -6),
                                                               40)), 40)))
            assert at < 1e-20 * near


def test_generated_python_vanishes_at_closed_form():
    EI, m, L, kw = 2, 3, 1, 500
    ns: dict = {}
    exec(generate(_pp(kw, EI, m, L), "python"), ns)  # noqa: S102 - the generated module
    delta = ns["symtmm_delta"]
    for n in (1, 2, 3):
        w = math.sqrt((EI * (n * math.pi / L) ** 4 + kw) / m)
        at, near = (abs(complex(np.ravel(delta(np.array([1j * v])))[0]))
                    for v in (w, 1.01 * w))
        assert at < 1e-9 * near
