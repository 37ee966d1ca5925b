"""Mode shapes of the beam theories (axial force, Rayleigh, Timoshenko, Winkler) and of rigid
bodies and joints (tip bodies, trees, closed loops).

References, all independent of the transfer-matrix code:

* pinned-pinned beams of every theory: ``Y = A sin(k x)``, ``psi = B cos(k x)``,
  ``k = n pi / L``; stationarity of the energy (strain ``EI psi'**2 + kGA (Y' - psi)**2 +
  N Y'**2 + kw Y**2``, kinetic ``m Y**2 + rhoI psi**2``) gives ``omega**2`` and ``B/A``, and
  the kinetic energy ``(L/2)(m A**2 + rhoI B**2) = 1`` the amplitude;
* a cantilever carrying a rigid body at an arm ``e``: its own 2x2 frequency equation;
* trees and loops with identical branches: symmetry decoupling into single beams;
* the equations of a body (brief): compatibility ``Y_beam = Y_c + d Theta_c``, and the
  jumps of ``Q`` summing to ``M omega**2 Y_c``;
* orthogonality of distinct modes in the kinetic energy, by Romberg integration of the
  sampled shapes written in JSON.
"""

from __future__ import annotations

import itertools
import json
import math

import mpmath
import numpy as np
import pytest
import scipy.integrate

from symtmm.compile import Evaluator
from symtmm.model import BOUNDARY_CONDITIONS, Attachment, Beam, Mass, Model, RigidBody, Spring
from symtmm.modelfile import loads
from symtmm.modes import evaluate_mode, mode_shapes, shapes_at
from symtmm.results import Eigenvalue, Spectrum

STATE = ("Y", "Theta", "M", "Q")


# -- references ----------------------------------------------------------------------------

def pinned_pinned_reference(EI, m, L, n, N=0, rhoI=0, kGA=None, kw=0, dps=40):
    """``[(omega**2, A, B)]`` of the pinned-pinned modes with ``k = n pi / L``, mass-normalised.

    Timoshenko: the energy with ``Y = A sin kx``, ``psi = B cos kx`` (``q = k**2``) is
    stationary where ``[[kGA q + N q + kw - m w2, -kGA k], [-kGA k, EI q + kGA - rhoI w2]]``
    is singular: two roots per n (one, ``w2 = kGA/rhoI`` with ``A = 0``, for n = 0).
    Rayleigh / Euler-Bernoulli: ``psi = Y'``, ``B = k A``, ``w2 = (EI q**2 + N q + kw) /
    (m + rhoI q)``.
    """
    mp = mpmath.mpf
    with mpmath.workdps(dps):
        EI, m, L, N, rhoI, kw = (mpmath.mpmathify(v) for v in (EI, m, L, N, rhoI, kw))
        k = n * mpmath.pi / L
        q = k * k
        out = []
        if kGA is None:
            w2s = [(EI * q * q + N * q + kw) / (m + rhoI * q)]
            ratios = [k]
        else:
            kGA = mpmath.mpmathify(kGA)
            a11, a12, a22 = kGA * q + N * q + kw, -kGA * k, EI * q + kGA
            if n == 0:
                w2s, ratios = [kGA / rhoI], [None]
            else:
                c2, c1, c0 = m * rhoI, -(m * a22 + rhoI * a11), a11 * a22 - a12 * a12
                disc = mpmath.sqrt(c1 * c1 - 4 * c2 * c0)
                w2s = sorted([(-c1 - disc) / (2 * c2), (-c1 + disc) / (2 * c2)])
                ratios = [(a11 - m * w2) / (kGA * k) for w2 in w2s]
        for w2, ratio in zip(w2s, ratios):
            if ratio is None:                       # Y = 0, psi constant
                out.append((w2, mp(0), 1 / mpmath.sqrt(rhoI * L)))
                continue
            A = mpmath.sqrt(2 / (L * (m + rhoI * ratio**2)))
            out.append((w2, A, A * ratio))
        return out


def pinned_pinned_state(x, k, A, B, w2, EI, N=0, rhoI=0, kGA=None):
    """``[Y, Theta, M, Q]`` of a pinned-pinned mode: ``Q = -kGA (Y' - psi) - N Y'`` (Timoshenko)
    or ``Q = EI Y''' - N Y' + rhoI w2 Y'`` (Rayleigh), both ``-`` the flux of the energy in Y."""
    N, rhoI = float(N), float(rhoI)
    kGA = None if kGA is None else float(kGA)
    s, c = np.sin(k * x), np.cos(k * x)
    Y, Theta, M = A * s, B * c, -EI * B * k * s
    if kGA is None:
        Q = (-EI * k**3 - N * k + rhoI * w2 * k) * A * c
    else:
        Q = (kGA * B - (kGA + N) * A * k) * c
    return {"Y": Y, "Theta": Theta, "M": M, "Q": Q}


def cantilever_betas(count, dps=40):
    """Roots of ``cos b cosh b + 1 = 0`` (clamped-free)."""
    with mpmath.workdps(dps):
        return [mpmath.findroot(lambda b: mpmath.cos(b) * mpmath.cosh(b) + 1,
                                (2 * j - 1) * mpmath.pi / 2) for j in range(1, count + 1)]


def clamped_clamped_betas(count, dps=40):
    """Roots of ``cos b cosh b - 1 = 0`` (b > 0)."""
    with mpmath.workdps(dps):
        return [mpmath.findroot(lambda b: mpmath.cos(b) * mpmath.cosh(b) - 1,
                                (2 * j + 1) * mpmath.pi / 2) for j in range(1, count + 1)]


def clamped_pinned_betas(count, dps=40):
    """Roots of ``tan b = tanh b`` (b > 0)."""
    with mpmath.workdps(dps):
        return [mpmath.findroot(lambda b: mpmath.sin(b) * mpmath.cosh(b)
                                - mpmath.cos(b) * mpmath.sinh(b), (4 * j + 1) * mpmath.pi / 4)
                for j in range(1, count + 1)]


def clamped_shape(beta, L, right):
    """Unnormalised mode of a beam clamped at 0 (Euler-Bernoulli): a function of x (numpy).

    ``cosh - cos - sigma (sinh - sin)`` of ``beta x / L``, sigma fixed by the right end;
    in mpmath, since the terms grow like ``cosh(beta)`` and cancel.
    """
    with mpmath.workdps(40):
        b = mpmath.mpmathify(beta)
        if right == "free":
            sigma = (mpmath.cosh(b) + mpmath.cos(b)) / (mpmath.sinh(b) + mpmath.sin(b))
        else:                                  # clamped or pinned: Y(L) = 0
            sigma = (mpmath.cosh(b) - mpmath.cos(b)) / (mpmath.sinh(b) - mpmath.sin(b))

    def one(x):
        with mpmath.workdps(40):
            t = b * mpmath.mpf(float(x)) / L
            return float(mpmath.cosh(t) - mpmath.cos(t) - sigma * (mpmath.sinh(t) - mpmath.sin(t)))

    def f(x):
        return np.array([one(v) for v in np.atleast_1d(x)])
    return f


def l2_norm2(f, a, b):
    t, w = np.polynomial.legendre.leggauss(80)
    x = (a + b) / 2 + (b - a) / 2 * t
    return float(np.sum(w * f(x) ** 2) * (b - a) / 2)


def scan_roots(model, omega_max, count, steps=800, dps=40):
    """The first ``count`` eigenvalues by sign changes of Delta(i omega), refined in mpmath.

    Used only where the eigenvalue itself is not the reference (orthogonality, jump
    conditions): the shapes must satisfy those at any true eigenvalue.
    """
    ev = Evaluator(model)
    w = np.linspace(omega_max / steps, omega_max, steps)
    d = ev.delta(1j * w).real
    out = []
    for a, b, da, db in zip(w[:-1], w[1:], d[:-1], d[1:]):
        if da * db < 0:
            with mpmath.workdps(dps):
                out.append(mpmath.findroot(ev.delta_omega_mp, (a, b), solver="anderson"))
            if len(out) == count:
                break
    assert len(out) == count, f"found {len(out)} roots below {omega_max}"
    return out


def eigen(omega, digits=25):
    with mpmath.workdps(digits + 10):
        return Eigenvalue(mpmath.mpc(0, omega), 1, digits)


def spectrum_of(omegas, digits=25):
    return Spectrum(tuple(eigen(w, digits) for w in omegas), digits, "test", 0, 0.0)


# -- pinned-pinned beams of every theory ---------------------------------------------------

THEORIES = {
    # name: (Beam keywords, exact float values for the reference, mode numbers)
    "tension": (dict(N=5), dict(N="5"), (1, 2, 3, 6)),
    "compression": (dict(N=-3), dict(N="-3"), (1, 2, 3)),      # buckling at EI (pi/L)^2 = 8.8
    "rayleigh": (dict(theory="rayleigh", rhoI="1/50", N=2), dict(rhoI="0.02", N="2"), (1, 2, 5)),
    "timoshenko": (dict(theory="timoshenko", rhoI="1/100", kGA=80, N=5, kw=7),
                   dict(rhoI="0.01", kGA="80", N="5", kw="7"), (0, 1, 2, 5)),
}
EI, MASS, LENGTH = 2.0, 3.0, 1.5


def pp_model(keywords):
    return Model((Beam("b", EI=2, m=3, L="3/2", left="pinned", right="pinned", **keywords),))


@pytest.mark.parametrize("name", THEORIES)
def test_pinned_pinned_shapes_are_the_closed_form(name):
    keywords, values, numbers = THEORIES[name]
    model = pp_model(keywords)
    for n in numbers:
        for w2, A, B in pinned_pinned_reference(EI, MASS, LENGTH, n, **values):
            (shape,) = shapes_at(model, eigen(mpmath.sqrt(w2)), points=25)
            s = shape.beams["b"]
            ref = pinned_pinned_state(s.x, n * math.pi / LENGTH, float(A), float(B), float(w2),
                                      EI, values.get("N", 0), values.get("rhoI", 0),
                                      values.get("kGA"))
            sign = np.sign(np.dot(s.Y, ref["Y"]) + np.dot(s.Theta, ref["Theta"]))
            # a variable that vanishes (Y and M of the n = 0 mode) is measured in the units
            # of the mode's rotation
            T = np.max(np.abs(ref["Theta"]))
            units = {"Y": T * LENGTH, "Theta": T, "M": EI * T / LENGTH,
                     "Q": EI * T / LENGTH**2}
            for var in STATE:
                scale = max(np.max(np.abs(ref[var])), 1e-3 * units[var])
                err = np.max(np.abs(sign * s[var] - ref[var]))
                assert err < 1e-10 * scale, (name, n, float(w2), var, err / scale)


def test_timoshenko_normalisation_carries_the_digits_asked_for():
    # the left-end state at 30 digits: Theta(0) = B and Q(0) = kGA B - (kGA + N) k A
    keywords, values, _ = THEORIES["timoshenko"]
    model = pp_model(keywords)
    for w2, A, B in pinned_pinned_reference(EI, MASS, LENGTH, 3, **values):
        with mpmath.workdps(45):
            e = Eigenvalue(mpmath.mpc(0, mpmath.sqrt(w2)), 1, 30)
        (shape,) = shapes_at(model, e, points=3)
        with mpmath.workdps(40):
            k = 3 * mpmath.pi / mpmath.mpf(LENGTH)
            Y0, T0, M0, Q0 = shape.left_state[:4]
            sign = 1 if T0 * B > 0 else -1
            Qref = 80 * B - 85 * k * A
            assert abs(sign * T0 - B) < mpmath.mpf(10) ** -28 * abs(B)
            assert abs(sign * Q0 - Qref) < mpmath.mpf(10) ** -27 * abs(Qref)
            assert abs(Y0) < mpmath.mpf(10) ** -30 and abs(M0) < mpmath.mpf(10) ** -28


def test_cli_modes_json_on_a_timoshenko_beam(tmp_path, capsys):
    from symtmm.cli import main
    path = tmp_path / "timo.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 2\nm = 3\nL = 1.5\nleft = "pinned"\n'
                    'right = "pinned"\ntheory = "timoshenko"\nrhoI = 0.01\nkGA = 80\n')
    assert main(["modes", str(path), "--count", "2", "--points", "9", "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert list(data)[-1] == "modes" and len(data["modes"]) == 2
    for n, mode in zip((1, 2), data["modes"]):
        ((w2, A, B), _) = pinned_pinned_reference(EI, MASS, LENGTH, n, rhoI="0.01", kGA=80)
        assert set(mode) == {"eigenvalue", "beams"}          # no bodies in this model
        assert float(mode["eigenvalue"]["imag"]) == pytest.approx(float(mpmath.sqrt(w2)),
                                                                  rel=1e-13)
        beam = mode["beams"]["b"]
        x = np.array(beam["x"])
        ref = pinned_pinned_state(x, n * math.pi / LENGTH, float(A), float(B), float(w2), EI,
                                  0, 0.01, 80)
        sign = np.sign(np.dot(beam["Y"], ref["Y"]))
        for var in STATE:
            assert np.allclose(sign * np.array(beam[var]), ref[var],
                               atol=1e-10 * np.max(np.abs(ref[var])), rtol=0), var


# -- orthogonality in the full kinetic energy -------------------------------------------------

def romberg_gram(data, model):
    """Kinetic-energy Gram matrix of the JSON modes by Romberg integration of the samples.

    Point elements and bodies sit at beam ends only, so each beam's shape is smooth inside.
    """
    modes = data["modes"]
    k = len(modes)
    G = np.zeros((k, k))
    for beam in model.beams:
        m, rhoI = float(beam.m), float(beam.rhoI)
        Y = np.array([mode["beams"][beam.name]["Y"] for mode in modes])
        T = np.array([mode["beams"][beam.name]["Theta"] for mode in modes])
        x = np.array(modes[0]["beams"][beam.name]["x"])
        dx = x[1] - x[0]
        for i in range(k):
            for j in range(k):
                f = m * Y[i] * Y[j] + rhoI * T[i] * T[j]
                G[i, j] += scipy.integrate.romb(f, dx)
    for mass in model.masses:
        x = float(mass.x)
        for i, mi in enumerate(modes):
            for j, mj in enumerate(modes):
                zi = _at(mi["beams"][mass.beam], x)
                zj = _at(mj["beams"][mass.beam], x)
                G[i, j] += float(mass.M) * zi[0] * zj[0] + float(mass.J) * zi[1] * zj[1]
    for body in model.bodies:
        for i, mi in enumerate(modes):
            for j, mj in enumerate(modes):
                bi, bj = mi["bodies"][body.name], mj["bodies"][body.name]
                G[i, j] += float(body.M) * bi["Y"] * bj["Y"]
                if "Theta" in bi:
                    G[i, j] += float(body.J) * bi["Theta"] * bj["Theta"]
    return G


def _at(beam, x):
    i = int(np.argmin(np.abs(np.array(beam["x"]) - x)))
    assert abs(beam["x"][i] - x) < 1e-12
    return beam["Y"][i], beam["Theta"][i]


MIXED = """
[[beam]]
name = "t"
EI = 2
m = 3
L = 1.5
left = "clamped"
right = "free"
theory = "timoshenko"
rhoI = 0.02
kGA = 60
N = 4
kw = 5
[[beam]]
name = "r"
EI = 1
m = 2
L = 1.5
left = "pinned"
right = "free"
theory = "rayleigh"
rhoI = 0.05
N = -1
[[spring]]
between = ["t", "r"]
x = 1.5
k = 30
[[mass]]
beam = "t"
x = 1.5
M = 0.7
J = 0.05
"""

LOOP_WITH_BODY = """
[[beam]]
name = "trunk"
EI = 1
m = 1
L = 1
left = "clamped"
right = "free"
theory = "timoshenko"
rhoI = 0.01
kGA = 200
[[beam]]
name = "up"
EI = 0.5
m = 0.5
L = 1
x0 = 1
left = "free"
right = "free"
theory = "rayleigh"
rhoI = 0.004
[[beam]]
name = "down"
EI = 0.7
m = 0.3
L = 1
x0 = 1
left = "free"
right = "free"
N = 2
[[beam]]
name = "tail"
EI = 1
m = 1
L = 0.8
x0 = 2
left = "free"
right = "pinned"
[[rigid]]
name = "hub"
attach = ["trunk.right", "up.left", "down.left"]
M = 0.5
J = 0.02
xc = 1.05
[[joint]]
name = "knot"
ends = ["up.right", "down.right", "tail.left"]
kind = "hinge"
"""


@pytest.mark.parametrize("text, omega_max", [(MIXED, 120.0), (LOOP_WITH_BODY, 60.0)],
                         ids=["theories", "loop-with-body"])
def test_distinct_modes_are_orthonormal_in_the_kinetic_energy(text, omega_max):
    model = loads(text).require_numeric()
    omegas = scan_roots(model, omega_max, 4, steps=500)
    modes = mode_shapes(model, spectrum=spectrum_of(omegas, digits=15), points=129)
    data = json.loads(modes.to_json())
    if model.bodies:
        assert set(data["modes"][0]["bodies"]) == {b.name for b in model.bodies}
        assert "Theta" not in data["modes"][0]["bodies"]["knot"]      # a pin: no rotation
    G = romberg_gram(data, model)
    assert np.max(np.abs(G - np.eye(len(omegas)))) < 1e-9, G


# -- rigid bodies: closed forms, compatibility, equilibrium -----------------------------------

def tip_body_model(e, M, J, theory=None):
    extra = theory or {}
    beam = Beam("b", EI=1, m=1, L=1, left="clamped", right="free", **extra)
    body = RigidBody("tip", (Attachment("b", 1),), M=M, J=J, xc=1 + sp_rational(e))
    return Model((beam,), bodies=(body,))


def sp_rational(text):
    import sympy as sp
    return sp.Rational(text)


def tip_body_reference(e, M, J, count, dps=40):
    """Cantilever (EI = m = L = 1) with a rigid body at arm ``e``: ``omega`` and the shape.

    ``Y = a (cosh - cos) + b (sinh - sin)`` of ``beta x`` (clamped at 0); at ``x = 1``
    the body's equations (force and moment about its centre, ``d = -e``):
    ``-Y''' = M w2 (Y + e Y')`` and ``Y'' + e Y''' = J w2 Y'``.
    """
    with mpmath.workdps(dps):
        e, M, J = (mpmath.mpf(sp_rational(v).p) / sp_rational(v).q for v in (e, M, J))

        def rows(b):
            w2 = b**4
            ch, co, sh, si = mpmath.cosh(b), mpmath.cos(b), mpmath.sinh(b), mpmath.sin(b)
            # derivatives of the two basis functions at x = 1
            f = [[ch - co, b * (sh + si), b**2 * (ch + co), b**3 * (sh - si)],
                 [sh - si, b * (ch - co), b**2 * (sh + si), b**3 * (ch + co)]]
            r1 = [-g[3] - M * w2 * (g[0] + e * g[1]) for g in f]
            r2 = [g[2] + e * g[3] - J * w2 * g[1] for g in f]
            return r1, r2

        def det(b):
            r1, r2 = rows(b)
            return r1[0] * r2[1] - r1[1] * r2[0]

        grid = [mpmath.mpf(j) / 20 for j in range(1, 400)]
        out = []
        for a, b in itertools.pairwise(grid):
            if det(a) * det(b) < 0:
                beta = mpmath.findroot(det, (a, b), solver="anderson")
                r1, _ = rows(beta)
                coef = (r1[1], -r1[0])              # null vector of the first row
                out.append((beta, coef, e))
                if len(out) == count:
                    break
        return out


def cantilever_functions(b, ca, cb):
    """``Y`` and ``Y'`` of ``ca (cosh - cos) + cb (sinh - sin)`` of ``b x``."""
    def Y(x):
        t = b * x
        return ca * (np.cosh(t) - np.cos(t)) + cb * (np.sinh(t) - np.sin(t))

    def dY(x):
        t = b * x
        return b * (ca * (np.sinh(t) + np.sin(t)) + cb * (np.cosh(t) - np.cos(t)))
    return Y, dY


def test_tip_body_shapes_are_the_closed_form():
    e, M, J = "1/5", "1/2", "1/50"
    model = tip_body_model(e, M, J)
    for beta, (ca, cb), arm in tip_body_reference(e, M, J, 4):
        arm = float(arm)
        Y, dY = cantilever_functions(float(beta), float(ca), float(cb))
        Yc, Tc = Y(1.0) + arm * dY(1.0), dY(1.0)
        energy = l2_norm2(Y, 0, 1) + 0.5 * Yc**2 + 0.02 * Tc**2
        scale = 1 / math.sqrt(energy)
        (shape,) = shapes_at(model, eigen(beta**2), points=17)
        s = shape.beams["b"]
        sign = np.sign(np.dot(s.Y, Y(s.x)))
        ref_Y, ref_T = scale * Y(s.x), scale * dY(s.x)
        assert np.max(np.abs(sign * s.Y - ref_Y)) < 1e-11 * np.max(np.abs(ref_Y))
        assert np.max(np.abs(sign * s.Theta - ref_T)) < 1e-11 * np.max(np.abs(ref_T))
        body = shape.bodies["tip"]
        assert sign * body["Y"] == pytest.approx(scale * Yc, rel=1e-10)
        assert sign * body["Theta"] == pytest.approx(scale * Tc, rel=1e-10)


LINKED = """
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "clamped"
right = "free"
theory = "timoshenko"
rhoI = 0.01
kGA = 150
N = 3
[[beam]]
name = "b"
EI = 2
m = 1.5
L = 1.2
x0 = 0.6
left = "free"
right = "pinned"
theory = "rayleigh"
rhoI = 0.02
[[rigid]]
name = "link"
attach = ["a.right", "b@0.8"]
hinged = ["b@0.8"]
M = 0.4
J = 0.03
xc = 0.93
"""


def test_bodies_satisfy_compatibility_and_equilibrium():
    model = loads(LINKED).require_numeric()
    body = model.bodies[0]
    xc = float(body.xc)
    for omega in scan_roots(model, 80.0, 4):
        (mode,) = shapes_at(model, eigen(omega), points=9)
        w2 = float(omega) ** 2
        Yc, Tc = mode.bodies["link"]["Y"], mode.bodies["link"]["Theta"]
        scale = max(np.max(np.abs(s.Q)) for s in mode.beams.values())
        force = moment = 0.0
        for att in body.attachments:
            x = float(att.x)
            before = evaluate_mode(model, mode, att.beam, [att.x], side="-")[:, 0]
            after = evaluate_mode(model, mode, att.beam, [att.x], side="+")[:, 0]
            # compatibility: the beam moves with the body there (and turns with it if rigid)
            assert before[0] == pytest.approx(Yc + (x - xc) * Tc, abs=1e-11)
            assert after[0] == pytest.approx(before[0], abs=1e-12)
            if not att.hinged:
                assert before[1] == pytest.approx(Tc, abs=1e-11)
            else:
                assert after[2] - before[2] == pytest.approx(0, abs=1e-11 * scale)
            F = after[3] - before[3]                 # the body's force on the beam
            C = -(after[2] - before[2])              # and its couple
            force += F
            moment += (x - xc) * F + C
        # equations of motion: sum F = M w2 Y_c, sum (d F + C) = J w2 Theta_c
        assert force == pytest.approx(float(body.M) * w2 * Yc, abs=1e-10 * scale)
        assert moment == pytest.approx(float(body.J) * w2 * Tc, abs=1e-10 * scale)
        # the free end of a and the pinned end of b
        for beam in model.beams:
            s = mode.beams[beam.name]
            for end, idx in ((beam.left, 0), (beam.right, -1)):
                for var in BOUNDARY_CONDITIONS[end]:
                    assert abs(s[var][idx]) < 1e-10 * max(1.0, np.max(np.abs(s[var])))


def test_body_at_its_centre_is_a_lumped_mass():
    # a rigid body held at its centre of mass is the [[mass]] element (M, J); Timoshenko beam
    beam = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned", theory="timoshenko",
                rhoI="1/100", kGA=120)
    lumped = Model((beam,), masses=(Mass("b", "3/5", "2/5", "1/30"),))
    body = Model((beam,), bodies=(RigidBody("r", (Attachment("b", "3/5"),), M="2/5", J="1/30"),))
    for omega in scan_roots(lumped, 120.0, 4):
        (a,) = shapes_at(lumped, eigen(omega), points=21)
        (b,) = shapes_at(body, eigen(omega), points=21)
        for var in ("Y", "Theta", "M"):
            ref = a.beams["b"][var]
            assert np.max(np.abs(b.beams["b"][var] - ref)) < 1e-10 * np.max(np.abs(ref)), var
        ya = evaluate_mode(lumped, a, "b", [0.6])[0, 0]
        assert b.bodies["r"]["Y"] == pytest.approx(ya, rel=1e-10)


# -- trees and closed loops by symmetry ---------------------------------------------------------

FORK = """
[[beam]]
name = "trunk"
EI = 1
m = 1
L = 1
left = "clamped"
right = "free"
[[beam]]
name = "b1"
EI = 0.5
m = 0.5
L = 0.75
x0 = 1
left = "free"
right = "free"
[[beam]]
name = "b2"
EI = 0.5
m = 0.5
L = 0.75
x0 = 1
left = "free"
right = "free"
[[joint]]
name = "fork"
ends = ["trunk.right", "b1.left", "b2.left"]
kind = "rigid"
"""

LOOP = """
[[beam]]
name = "trunk"
EI = 1
m = 1
L = 1
left = "clamped"
right = "free"
[[beam]]
name = "b1"
EI = 0.5
m = 0.5
L = 1
x0 = 1
left = "free"
right = "free"
[[beam]]
name = "b2"
EI = 0.5
m = 0.5
L = 1
x0 = 1
left = "free"
right = "free"
[[beam]]
name = "tail"
EI = 1
m = 1
L = 1
x0 = 2
left = "free"
right = "pinned"
[[joint]]
name = "split"
ends = ["trunk.right", "b1.left", "b2.left"]
[[joint]]
name = "merge"
ends = ["b1.right", "b2.right", "tail.left"]
"""


def fork_families(count=3, dps=40):
    """``(omega, family, beta, length)``: in-phase = clamped-free (1, 1, 7/4), opposite =
    each branch clamped-free (1/2, 1/2, 3/4)."""
    out = []
    with mpmath.workdps(dps):
        for beta in cantilever_betas(count, dps):
            out.append(((beta / mpmath.mpf("1.75")) ** 2, "in-phase", beta, 1.75))
            out.append(((beta / mpmath.mpf("0.75")) ** 2, "opposite", beta, 0.75))
    return sorted(out, key=lambda t: t[0])


def loop_families(count=3, dps=40):
    """In-phase = clamped-pinned (1, 1, 3); opposite = each branch clamped-clamped (1/2, 1/2, 1)."""
    out = []
    with mpmath.workdps(dps):
        for beta in clamped_pinned_betas(count + 2, dps):
            out.append(((beta / 3) ** 2, "in-phase", beta, 3.0))
        for beta in clamped_clamped_betas(count, dps):
            out.append((beta**2, "opposite", beta, 1.0))
    return sorted(out, key=lambda t: t[0])


def test_fork_modes_decouple_by_symmetry():
    model = loads(FORK).require_numeric()
    for omega, family, beta, length in fork_families():
        (mode,) = shapes_at(model, eigen(omega), points=13)
        f = clamped_shape(beta, length, "free")
        s = {name: mode.beams[name] for name in ("trunk", "b1", "b2")}
        joint = mode.bodies["fork"]
        if family == "in-phase":
            # the single clamped-free beam (EI, m, 7/4), mass-normalised: int m Y^2 = 1
            scale = 1 / math.sqrt(l2_norm2(f, 0, length))
            sign = np.sign(np.dot(s["trunk"].Y, f(s["trunk"].x)))
            for name, shape in s.items():
                ref = scale * f(shape.x)
                assert np.max(np.abs(sign * shape.Y - ref)) < 1e-11 * scale, (omega, name)
            assert np.max(np.abs(s["b1"].Y - s["b2"].Y)) < 1e-12
            assert np.max(np.abs(s["b1"].M - s["b2"].M)) < 1e-11
            assert joint["Y"] == pytest.approx(s["trunk"].Y[-1], abs=1e-12)
        else:
            # trunk at rest, each branch a clamped-free (1/2, 1/2, 3/4): 2 (1/2) int Y^2 = 1
            scale = 1 / math.sqrt(l2_norm2(f, 0, length))
            for var in STATE:
                assert np.max(np.abs(s["trunk"][var])) < 1e-11 * (1 + np.max(np.abs(s["b1"][var])))
            ref = scale * f(s["b1"].x - 1)
            sign = np.sign(np.dot(s["b1"].Y, ref))
            assert np.max(np.abs(sign * s["b1"].Y - ref)) < 1e-11 * scale
            assert np.max(np.abs(s["b1"].Y + s["b2"].Y)) < 1e-11 * scale
            assert abs(joint["Y"]) < 1e-11 and abs(joint["Theta"]) < 1e-11


def test_loop_modes_decouple_by_symmetry():
    model = loads(LOOP).require_numeric()
    for omega, family, beta, length in loop_families():
        (mode,) = shapes_at(model, eigen(omega), points=13)
        s = mode.beams
        if family == "in-phase":
            # one clamped-pinned beam (EI, m, 3) through trunk, either branch and tail
            f = clamped_shape(beta, length, "pinned")
            scale = 1 / math.sqrt(l2_norm2(f, 0, length))
            sign = np.sign(np.dot(s["trunk"].Y, f(s["trunk"].x)) + np.dot(s["tail"].Y,
                                                                         f(s["tail"].x)))
            for name in ("trunk", "b1", "b2", "tail"):
                ref = scale * f(s[name].x)
                assert np.max(np.abs(sign * s[name].Y - ref)) < 1e-10 * scale, (omega, name)
        else:
            # trunk and tail at rest; the branches clamped-clamped (1/2, 1/2, 1), opposite
            f = clamped_shape(beta, length, "clamped")
            scale = 1 / math.sqrt(l2_norm2(f, 0, length))
            for name in ("trunk", "tail"):
                assert np.max(np.abs(s[name].Y)) < 1e-10 * scale
                assert np.max(np.abs(s[name].Q)) < 1e-9 * np.max(np.abs(s["b1"].Q))
            ref = scale * f(s["b1"].x - 1)
            sign = np.sign(np.dot(s["b1"].Y, ref))
            assert np.max(np.abs(sign * s["b1"].Y - ref)) < 1e-10 * scale
            assert np.max(np.abs(s["b1"].Y + s["b2"].Y)) < 1e-10 * scale
            for joint in ("split", "merge"):
                assert abs(mode.bodies[joint]["Y"]) < 1e-10


def test_timoshenko_fork_in_phase_modes_are_the_pinned_pinned_beam():
    # trunk (EI, m, rhoI, kGA) forking into two branches with all of them halved, pinned at
    # both far ends: the in-phase modes are the pinned-pinned Timoshenko beam of length 2
    text = FORK.replace('left = "clamped"', 'left = "pinned"').replace(
        'L = 0.75\nx0 = 1\nleft = "free"\nright = "free"',
        'L = 1\nx0 = 1\nleft = "free"\nright = "pinned"')
    text = text.replace('EI = 1\nm = 1\n', 'EI = 1\nm = 1\ntheory = "timoshenko"\nrhoI = 0.01\n'
                        'kGA = 100\n')
    text = text.replace('EI = 0.5\nm = 0.5\n', 'EI = 0.5\nm = 0.5\ntheory = "timoshenko"\n'
                        'rhoI = 0.005\nkGA = 50\n')
    model = loads(text).require_numeric()
    assert all(b.theory == "timoshenko" for b in model.beams)
    for n in (1, 2, 3):
        w2, A, B = pinned_pinned_reference(1, 1, 2, n, rhoI=0.01, kGA=100)[0]
        (mode,) = shapes_at(model, eigen(mpmath.sqrt(w2)), points=11)
        trunk = mode.beams["trunk"]
        sign = np.sign(np.dot(trunk.Y, np.sin(n * math.pi * trunk.x / 2)) + np.dot(
            trunk.Theta, np.cos(n * math.pi * trunk.x / 2)))
        for name, s in mode.beams.items():
            ref = pinned_pinned_state(s.x, n * math.pi / 2, float(A), float(B), float(w2), 1.0,
                                      kGA=100.0 if name == "trunk" else 50.0)
            for var in ("Y", "Theta"):
                err = np.max(np.abs(sign * s[var] - ref[var]))
                assert err < 1e-10 * np.max(np.abs(ref[var])), (n, name, var)


# -- damped ----------------------------------------------------------------------------------

def test_damped_timoshenko_beam_with_a_body_and_a_dashpot():
    beam = Beam("b", EI=1, m=1, L=1, left="clamped", right="free", theory="timoshenko",
                rhoI="1/100", kGA=90, N=2)
    body = RigidBody("tip", (Attachment("b", 1),), M="1/4", J="1/100", xc="11/10")
    model = Model((beam,), (Spring("b", "ground", x="1/2", k=10, c="3/2"),), bodies=(body,))
    ev = Evaluator(model)
    with mpmath.workdps(40):
        lam = mpmath.findroot(ev.delta_mp, mpmath.mpc(-0.3, 3.0))
        assert lam.real < 0 and lam.imag > 0
        e = Eigenvalue(mpmath.mpc(lam), 1, 25)
    (mode,) = shapes_at(model, e, points=21)
    s = mode.beams["b"]
    assert mode.damped and np.max(np.abs(s.Y)) == pytest.approx(1.0)
    assert abs(s.Y[0]) < 1e-12 and abs(s.Theta[0]) < 1e-12
    lam_c = complex(lam)
    jump = (evaluate_mode(model, mode, "b", [0.5], "+")[3, 0]
            - evaluate_mode(model, mode, "b", [0.5], "-")[3, 0])
    y = evaluate_mode(model, mode, "b", [0.5])[0, 0]
    assert jump == pytest.approx(-(10 + 1.5 * lam_c) * y, rel=1e-10)
    Yc, Tc = mode.bodies["tip"]["Y"], mode.bodies["tip"]["Theta"]
    assert isinstance(Yc, complex)
    assert s.Y[-1] == pytest.approx(Yc - 0.1 * Tc, rel=1e-10)
    assert s.Theta[-1] == pytest.approx(Tc, rel=1e-10)
    before = evaluate_mode(model, mode, "b", [1], "-")[:, 0]
    # the free end after the body: Q+ = 0, so the jump -Q- is the body's force -M lam^2 Y_c
    assert -before[3] == pytest.approx(-0.25 * lam_c**2 * Yc, rel=1e-9)
    data = mode.to_dict()
    assert set(data["bodies"]["tip"]["Y"]) == {"real", "imag"}
