"""The count and the solvers with every beam theory and with rigid bodies, trees and loops.

References, each independent of the code under test:

* pinned-pinned beams (axial force, Rayleigh, Timoshenko, Winkler): the Fourier modes
  ``Y = A sin(k x)``, ``psi = B cos(k x)`` in the Euler–Lagrange equations of the energy
  (derived in :func:`_pinned_pinned`), ``k = n pi / L`` with ``n >= 0`` (``n = 0`` is
  the Timoshenko beam's pure-shear mode ``omega**2 = kGA / rhoI``);
* a clamped-free Timoshenko beam: its own first-order system in ``(Y, psi, M, V)``
  (``V = kGA (Y' - psi) + N Y'``, written here from the energy), ``exp(A L)`` by
  scipy and mpmath, the boundary conditions applied here;
* trees, loops and a hinge joint: symmetry decoupling into single beams whose
  frequency equations are the textbook ones (``tests/reference.py``);
* a rigid body at its centre of mass against the lumped mass element (another code
  path), and a tip body against the cantilever frequency equation derived here;
* damped models whose in-phase family leaves the dashpots idle (closed forms above),
  and whose out-of-phase family is a single beam with doubled spring and dashpot.
"""

from __future__ import annotations

import functools
import math
from dataclasses import replace
from decimal import Decimal

import mpmath
import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference import classical_roots

from symtmm import Beam, ComputationError, Model, ModelError, Spring
from symtmm.compile import Evaluator
from symtmm.fe import fe_converged
from symtmm.model import Attachment, Mass, RigidBody
from symtmm.modelfile import loads
from symtmm.numeric.evaluator import Evaluator as Kernel
from symtmm.numeric.stiffness import segment_stiffness
from symtmm.roots.count import Counter
from symtmm.roots.damped import count_in_rectangle, solve_damped
from symtmm.roots.undamped import rigid_body_modes, solve_undamped
from symtmm.solve import solve

DPS = 45


def _assert_digits(printed: str, exact, digits: int):
    """Every printed significant digit of ``printed`` is correct for ``exact``."""
    value = Decimal(printed)
    ulp = Decimal(10) ** (value.adjusted() - digits + 1)
    error = abs(value - Decimal(mpmath.nstr(exact, digits + 15, strip_zeros=False)))
    assert error <= ulp / 2 * Decimal("1.0001"), (printed, mpmath.nstr(exact, digits + 5))


def _assert_spectrum(spectrum, reference, digits):
    """The spectrum, expanded by multiplicity, is ``reference`` (ascending) digit for digit."""
    got = [e for e in spectrum for _ in range(e.multiplicity)]
    assert len(got) == len(reference)
    for e, ref in zip(got, reference):
        _assert_digits(e.to_dict()["imag"], ref, digits)


def _mp(value):
    return mpmath.mpf(sp.Rational(value).p) / sp.Rational(value).q


# -- pinned-pinned beams: closed forms ------------------------------------------------------
def _pinned_pinned(EI, m, L, N=0, rhoI=0, kGA=None, kw=0, n_max=12):
    """``omega`` of the pinned-pinned modes, from the energy.

    Energy density ``EI psi'**2 + kGA (Y' - psi)**2 + N Y'**2 + kw Y**2`` and kinetic
    ``m Y_t**2 + rhoI psi_t**2`` (halved). Euler–Lagrange:
    ``-(kGA (Y' - psi) + N Y')' + kw Y + m Y_tt = 0`` and
    ``-(EI psi')' - kGA (Y' - psi) + rhoI psi_tt = 0``. With ``Y = A sin(k x)``,
    ``psi = B cos(k x)`` (``Y = 0`` and ``M = EI psi' = 0`` at both ends), ``q = k**2``:
    ``[(kGA + N) q + kw - m w2] A - kGA k B = 0`` and ``-kGA k A + (EI q + kGA - rhoI w2) B = 0``.
    Rigid in shear (``psi = Y'``): ``w2 = (EI q**2 + N q + kw) / (m + rhoI q)``.
    """
    EI, m, L, N, rhoI, kw = (_mp(v) for v in (EI, m, L, N, rhoI, kw))
    out = []
    if kGA is not None:
        kGA = _mp(kGA)
        if rhoI > 0:
            out.append(mpmath.sqrt(kGA / rhoI))      # n = 0: Y = 0, psi constant
    for n in range(1, n_max + 1):
        q = (n * mpmath.pi / L) ** 2
        if kGA is None:
            out.append(mpmath.sqrt((EI * q * q + N * q + kw) / (m + rhoI * q)))
            continue
        a1, a2 = (kGA + N) * q + kw, EI * q + kGA
        # (a1 - m w)(a2 - rhoI w) - kGA**2 q = 0
        c2, c1, c0 = m * rhoI, -(a1 * rhoI + a2 * m), a1 * a2 - kGA**2 * q
        if c2 == 0:
            out.append(mpmath.sqrt(-c0 / c1))
        else:
            disc = mpmath.sqrt(c1 * c1 - 4 * c2 * c0)
            out += [mpmath.sqrt((-c1 - disc) / (2 * c2)), mpmath.sqrt((-c1 + disc) / (2 * c2))]
    return sorted(out)


PINNED_CASES = {
    "tension": dict(N=3),
    "compression": dict(N="-5"),                                     # N_cr = pi**2 EI / L**2
    "winkler": dict(kw=40),
    "rayleigh": dict(theory="rayleigh", rhoI="1/50"),
    "rayleigh_compression": dict(theory="rayleigh", rhoI="1/50", N=-2, kw=5),
    "timoshenko": dict(theory="timoshenko", rhoI="1/50", kGA=30),
    "timoshenko_tension": dict(theory="timoshenko", rhoI="1/50", kGA=30, N=4),
    "timoshenko_compression_winkler": dict(theory="timoshenko", rhoI="1/50", kGA=30, N=-3, kw=7),
    "timoshenko_shear_only": dict(theory="timoshenko", rhoI=0, kGA=25, N="1/2"),
}


@pytest.mark.parametrize("case", list(PINNED_CASES))
def test_pinned_pinned_beams_against_closed_forms(case):
    fields = PINNED_CASES[case]
    EI, m, L = 1, 1, 1
    beam = Beam("b", EI, m, L, left="pinned", right="pinned", **fields)
    spectrum = solve_undamped(Model((beam,)), count=6, digits=16)
    with mpmath.workdps(DPS):
        ref = _pinned_pinned(EI, m, L, fields.get("N", 0), fields.get("rhoI", 0),
                             fields.get("kGA"), fields.get("kw", 0))[:6]
        _assert_spectrum(spectrum, ref, 16)


def test_pinned_pinned_scaled_beam_twenty_digits():
    fields = dict(theory="timoshenko", rhoI="3/200", kGA=45, N="-7/4", kw=3)
    beam = Beam("b", "5/2", "3/2", "6/5", left="pinned", right="pinned", **fields)
    spectrum = solve_undamped(Model((beam,)), count=5, digits=20)
    with mpmath.workdps(DPS):
        ref = _pinned_pinned("5/2", "3/2", "6/5", "-7/4", "3/200", 45, 3)[:5]
        _assert_spectrum(spectrum, ref, 20)


# -- clamped-free Timoshenko beam: an independent first-order system -------------------------
def _timoshenko_system(EI, m, rhoI, kGA, N, kw, w2, module):
    """``A`` of ``(Y, psi, M, V)' = A (Y, psi, M, V)`` at ``omega**2 = w2``.

    ``V = kGA (Y' - psi) + N Y'`` and ``M = EI psi'`` are the actions the energy puts
    at an end (free end: ``M = V = 0``): ``Y' = (V + kGA psi)/(kGA + N)``,
    ``psi' = M/EI``, ``M' = -kGA (Y' - psi) - rhoI w2 psi``, ``V' = (kw - m w2) Y``.
    """
    s = kGA + N
    return module([[0, kGA / s, 0, 1 / s],
                   [0, 0, 1 / EI, 0],
                   [0, kGA * N / s - rhoI * w2, 0, -kGA / s],
                   [kw - m * w2, 0, 0, 0]])


def _expm(A, one, squarings, terms):
    """``exp(A)`` of a 4x4 matrix (rows of numbers, or of numpy arrays for many matrices at
    once) by its Taylor series at ``A / 2**squarings``, then squaring."""
    def mul(X, Y):
        return [[sum(X[i][k] * Y[k][j] for k in range(4)) for j in range(4)] for i in range(4)]

    h = [[a / 2**squarings for a in row] for row in A]
    E = [[one if i == j else 0 * one for j in range(4)] for i in range(4)]
    term = [row[:] for row in E]
    for n in range(1, terms):
        term = [[v / n for v in row] for row in mul(term, h)]
        E = [[e + t for e, t in zip(re, rt)] for re, rt in zip(E, term)]
    for _ in range(squarings):
        E = mul(E, E)
    return E


@functools.lru_cache
def timoshenko_clamped_free(EI, m, L, rhoI, kGA, N=0, kw=0, count=6, dps=30):
    """The first ``count`` clamped-free frequencies: ``det [exp(A L)]_{(M,V),(M,V)} = 0``.

    ``exp(A L)`` by the Taylor series and squaring (:func:`_expm`). Sign changes of the
    determinant on a grid (step 0.02, double precision, all points at once) bracket the
    roots; each is polished by the secant method in mpmath and must stay in its bracket.
    """
    floats = [float(sp.Rational(v)) for v in (EI, m, L, rhoI, kGA, N, kw)]
    vals = None

    def det(A, L, one, terms):
        # a bound on the norm of A L (of the largest, for many at once)
        norm = sum(float(np.max(np.abs(a))) if isinstance(a, np.ndarray) else float(abs(a))
                   for row in A for a in row) * float(L)
        squarings = max(0, math.ceil(math.log2(norm + 1e-300)) + 2)
        E = _expm([[a * L for a in row] for row in A], one, squarings, terms)
        return E[2][2] * E[3][3] - E[2][3] * E[3][2]

    grid = np.arange(1, 4000) * 0.02
    roots = []
    values = det(_timoshenko_system(*floats[:2], *floats[3:], grid**2, list), floats[2],
                 np.ones_like(grid), 25)
    with mpmath.workdps(dps):
        vals = [_mp(v) for v in (EI, m, L, rhoI, kGA, N, kw)]

        def f(w):
            return det(_timoshenko_system(*vals[:2], *vals[3:], w * w, list), vals[2],
                       mpmath.mpf(1), dps + 5)

        for i in np.nonzero(values[:-1] * values[1:] < 0)[0][:count]:
            a, b = mpmath.mpf(grid[i]), mpmath.mpf(grid[i + 1])
            fa, fb = f(a), f(b)
            guess = (a * fb - b * fa) / (fb - fa)
            root = mpmath.findroot(f, (guess, guess * (1 + mpmath.mpf(10) ** -6)),
                                   solver="secant", tol=mpmath.mpf(10) ** (4 - 2 * dps))
            assert a <= root <= b
            roots.append(root)
    assert len(roots) == count
    return tuple(roots)


@pytest.mark.parametrize("N", [0, 6, "-3/2"])
def test_clamped_free_timoshenko_against_its_first_order_system(N):
    beam = Beam("b", 1, 1, 1, left="clamped", right="free", theory="timoshenko",
                rhoI="1/50", kGA=20, N=N)
    spectrum = solve_undamped(Model((beam,)), count=6, digits=16)
    ref = timoshenko_clamped_free(1, 1, 1, "1/50", 20, N)
    with mpmath.workdps(DPS):
        _assert_spectrum(spectrum, ref, 16)


# -- trees, loops and hinges: symmetry decoupling -------------------------------------------
def _fork(theory_fields=None, half_fields=None, L1="2/3", L2="1/3"):
    """A clamped trunk (EI 1, m 1) forking rigidly into two branches (EI/2, m/2)."""
    L1, L2 = sp.Rational(L1), sp.Rational(L2)
    beams = (Beam("trunk", 1, 1, L1, left="clamped", right="free", **(theory_fields or {})),
             Beam("a", "1/2", "1/2", L2, x0=L1, **(half_fields or {})),
             Beam("b", "1/2", "1/2", L2, x0=L1, **(half_fields or {})))
    joint = RigidBody("fork", (Attachment("trunk", L1), Attachment("a", L1),
                               Attachment("b", L1)))
    return Model(beams, bodies=(joint,))


def test_fork_decouples_into_clamped_free_beams():
    """In phase: one clamped-free beam of length 1; opposite: each branch, clamped-free,
    length 1/3 (the trunk at rest). Both families have cos cosh = -1."""
    spectrum = solve_undamped(_fork(), count=9, digits=16)
    with mpmath.workdps(DPS):
        nu = classical_roots("clamped", "free", 9, dps=DPS)
        ref = sorted([x**2 for x in nu] + [(3 * x) ** 2 for x in nu])[:9]
        _assert_spectrum(spectrum, ref, 16)


def test_timoshenko_fork_decouples_into_clamped_free_timoshenko_beams():
    trunk = dict(theory="timoshenko", rhoI="1/50", kGA=20)
    half = dict(theory="timoshenko", rhoI="1/100", kGA=10)
    spectrum = solve_undamped(_fork(trunk, half, "1/2", "1/2"), count=6, digits=15)
    whole = timoshenko_clamped_free(1, 1, 1, "1/50", 20, 0)
    branch = timoshenko_clamped_free(1, 1, "1/2", "1/50", 20, count=3)
    with mpmath.workdps(DPS):
        _assert_spectrum(spectrum, sorted(whole + branch)[:6], 15)


def _loop():
    """Trunk, two identical branches that rejoin, tail; clamped at both ends, rigid joints."""
    q, h = sp.Rational(1, 4), sp.Rational(1, 2)
    beams = (Beam("trunk", 1, 1, q, left="clamped", right="free"),
             Beam("a", "1/2", "1/2", h, x0=q), Beam("b", "1/2", "1/2", h, x0=q),
             Beam("tail", 1, 1, q, x0=q + h, left="free", right="clamped"))
    bodies = (RigidBody("split", (Attachment("trunk", q), Attachment("a", q), Attachment("b", q))),
              RigidBody("merge", (Attachment("a", q + h), Attachment("b", q + h),
                                  Attachment("tail", q + h))))
    return Model(beams, bodies=bodies)


def test_closed_loop_decouples_into_clamped_clamped_beams():
    """In phase: one clamped-clamped beam of length 1; opposite: the joints stay at rest
    (their motion would be its own opposite), each branch clamped-clamped, length 1/2."""
    spectrum = solve_undamped(_loop(), count=5, digits=15)
    with mpmath.workdps(DPS):
        nu = classical_roots("clamped", "clamped", 5, dps=DPS)
        ref = sorted([x**2 for x in nu] + [(2 * x) ** 2 for x in nu])[:5]
        _assert_spectrum(spectrum, ref, 15)


def test_hinge_joint_of_two_cantilevers():
    """Two cantilevers pinned together at their tips, mirror images about the pin.
    Symmetric modes: the two shear forces on the massless pin are equal, so each vanishes:
    clamped-free. Antisymmetric: the pin stays at rest: clamped-pinned (tan = tanh)."""
    beams = (Beam("a", 1, 1, 1, left="clamped", right="free"),
             Beam("b", 1, 1, 1, x0=1, left="free", right="clamped"))
    pin = RigidBody("pin", (Attachment("a", 1, hinged=True), Attachment("b", 1, hinged=True)))
    model = Model(beams, bodies=(pin,))
    assert model.body_frame(pin).freedoms == ("Y",)         # no rotation of its own
    spectrum = solve_undamped(model, count=8, digits=16)
    with mpmath.workdps(DPS):
        ref = sorted([x**2 for x in classical_roots("clamped", "free", 4, dps=DPS)]
                     + [x**2 for x in classical_roots("clamped", "pinned", 4, dps=DPS)])
        _assert_spectrum(spectrum, ref, 16)


def test_hinged_attachment_is_a_pin_support():
    """A beam of two equal spans hinged at mid-span to a body held by a cantilever's clamped
    end: the body cannot move, the beam turns freely over it (a continuous beam on three pin
    supports), and the cantilever vibrates on its own. Spans moving opposite: each
    pinned-pinned; alike (zero slope over the support): each clamped-pinned."""
    beam = Beam("b", 1, 1, 2, left="pinned", right="pinned")
    stub = Beam("g", 1, 1, 1, x0=1, left="clamped", right="free")
    body = RigidBody("support", (Attachment("b", 1, hinged=True), Attachment("g", 1)))
    spectrum = solve_undamped(Model((beam, stub), bodies=(body,)), count=9, digits=16)
    with mpmath.workdps(DPS):
        ref = sorted(x**2 for ends in (("pinned", "pinned"), ("clamped", "pinned"),
                                       ("clamped", "free"))
                     for x in classical_roots(*ends, 4, dps=DPS))[:9]
        _assert_spectrum(spectrum, ref, 16)


# -- rigid bodies ------------------------------------------------------------------------------
@pytest.mark.parametrize("fields", [{}, dict(theory="timoshenko", rhoI="1/80", kGA=60, N=2)],
                         ids=["euler-bernoulli", "timoshenko"])
def test_body_at_its_centre_equals_a_lumped_mass(fields):
    beam = Beam("b", 1, 1, 1, left="clamped", right="pinned", **fields)
    body = RigidBody("r", (Attachment("b", "2/5"),), M="3/2", J="1/20")
    mass = Mass("b", "2/5", "3/2", "1/20")
    with_body = solve_undamped(Model((beam,), bodies=(body,)), count=6, digits=20)
    with_mass = solve_undamped(Model((beam,), masses=(mass,)), count=6, digits=20)
    assert [e.to_dict() for e in with_body] == [e.to_dict() for e in with_mass]


def _tip_body_equation(M, J, e):
    """Cantilever (EI = m = L = 1) with a rigid body fixed to its tip, centre of mass at
    ``1 + e``: ``f(beta) = 0``, ``omega = beta**2``.

    ``Y = A (cosh - cos) + B (sinh - sin)`` of ``beta x``; at the tip the body moves with
    ``Y_c = Y + e Y'``, ``Theta = Y'``, kinetic energy ``(M Y_c_t**2 + J Theta_t**2)/2``,
    so the variation of the energy gives ``-Y''' - w2 M (Y + e Y') = 0`` and
    ``Y'' - w2 (M e (Y + e Y') + J Y') = 0``.
    """
    def f(beta):
        ch, c, sh, s = mpmath.cosh(beta), mpmath.cos(beta), mpmath.sinh(beta), mpmath.sin(beta)
        w2 = beta**4
        Y = (ch - c, sh - s)
        Y1 = (beta * (sh + s), beta * (ch - c))
        Y2 = (beta**2 * (ch + c), beta**2 * (sh + s))
        Y3 = (beta**3 * (sh - s), beta**3 * (ch + c))
        rows = [[-Y3[k] - w2 * M * (Y[k] + e * Y1[k]) for k in (0, 1)],
                [Y2[k] - w2 * (M * e * (Y[k] + e * Y1[k]) + J * Y1[k]) for k in (0, 1)]]
        return (rows[0][0] * rows[1][1] - rows[0][1] * rows[1][0]) / ch**2
    return f


def _tip_body_roots(M, J, e, count):
    with mpmath.workdps(DPS):
        f = _tip_body_equation(_mp(M), _mp(J), _mp(e))
        roots, b, step = [], mpmath.mpf(1) / 200, mpmath.mpf(1) / 200
        fb = f(b)
        while len(roots) < count:
            fc = f(b + step)
            if fb * fc < 0:
                roots.append(mpmath.findroot(f, (b, b + step), solver="anderson") ** 2)
            b, fb = b + step, fc
    return roots


def test_tip_body_against_the_cantilever_frequency_equation():
    body = RigidBody("tip", (Attachment("b", 1),), M="1/2", J="1/30", xc="6/5")
    beam = Beam("b", 1, 1, 1, left="clamped", right="free")
    spectrum = solve_undamped(Model((beam,), bodies=(body,)), count=6, digits=16)
    with mpmath.workdps(DPS):
        _assert_spectrum(spectrum, _tip_body_roots("1/2", "1/30", "1/5", 6), 16)


def test_body_on_a_free_beam_keeps_its_two_rigid_body_modes():
    """A free-free beam carrying a body: two rigid-body modes (translation, rotation)."""
    beam = Beam("b", 1, 1, 1)
    body = RigidBody("r", (Attachment("b", "1/3"),), M=1, J=1, xc="1/2")
    model = Model((beam,), bodies=(body,))
    assert rigid_body_modes(model) == 2
    spectrum = solve_undamped(model, count=3, digits=15)
    assert spectrum.eigenvalues[0].multiplicity == 2 and spectrum.eigenvalues[0].omega == 0


def test_rigid_body_modes_with_axial_force_and_foundation():
    ff = dict(left="free", right="free", theory="timoshenko", rhoI="1/50", kGA=30)
    assert rigid_body_modes(Model((Beam("b", 1, 1, 1, **ff),))) == 2
    assert rigid_body_modes(Model((Beam("b", 1, 1, 1, N=3, **ff),))) == 1     # tension resists
    assert rigid_body_modes(Model((Beam("b", 1, 1, 1, N=-3, **ff),))) == 1    # so does compression
    assert rigid_body_modes(Model((Beam("b", 1, 1, 1, kw=3, **ff),))) == 0    # so does a foundation


def test_long_free_beam_in_tension_beside_another_beam():
    """A long free-free beam in tension (cosh(sqrt(N/EI) L) = cosh(70) in its transfer
    matrix) keeps one rigid-body mode beside a pinned-pinned beam; the spectrum is the
    union of the pinned beam's (n pi)**2 and the tension beam's (converged FE)."""
    tense = dict(name="t", EI=0.1, m=2.0, L=10.0, x0=0.0, left="free", right="free", N=5.0)
    model = Model((Beam("t", "1/10", 2, 10, N=5, left="free", right="free"),
                   Beam("p", 1, 1, 1, left="pinned", right="pinned")))
    assert rigid_body_modes(model) == 1
    spectrum = solve_undamped(model, omega_max=12, digits=12)
    got = sorted(float(e.omega) for e in spectrum for _ in range(e.multiplicity))
    fe = fe_converged([tense], [], 40, count=40)
    tension = [w for w in fe["omega"] if 0 < w <= 12]
    expected = sorted([0.0] + tension + [math.pi**2])
    assert len(got) == len(expected)
    assert np.allclose(got, expected, rtol=1e-8, atol=1e-12)


# -- rotary inertia on a foundation: the dispersion's minimum -------------------------------
# A campaign's beam (rhoI / m the square of 11 m, kw 1.7e5): ``omega**2 = (EI q**2 + kw) / (m
# + rhoI q)`` falls from kw / m to a minimum near q = sqrt(kw / EI), 232 half-waves along it.
HEAVY = dict(EI=3, m="99/20", L="473/10", theory="rayleigh", rhoI=617, kw=170000)


def test_rayleigh_beam_whose_lowest_modes_lie_at_many_half_waves():
    """The search counts near the dispersion's minimum, 100 times below the first mode's
    frequency: the lowest three at 20 digits against the closed form, under a 20 s budget
    (the first count was taken at the first mode, 148.9 rad/s, where a Weyl estimate that
    took the larger of two travelling wave numbers for the count put the range: 34,472
    pieces, past the 60 s budget)."""
    beam = Beam("b", left="pinned", right="pinned", **HEAVY)
    spectrum = solve(Model((beam,)), count=3, digits=20, max_seconds=20)
    with mpmath.workdps(DPS):
        ref = _pinned_pinned(HEAVY["EI"], HEAVY["m"], HEAVY["L"], rhoI=HEAVY["rhoI"],
                             kw=HEAVY["kw"], n_max=400)[:3]
        _assert_spectrum(spectrum, ref, 20)
    assert float(ref[0]) < 1.53 and float(ref[0]) < _pinned_pinned(
        HEAVY["EI"], HEAVY["m"], HEAVY["L"], rhoI=HEAVY["rhoI"], kw=HEAVY["kw"], n_max=1)[0] / 90


@pytest.mark.parametrize("fields, omegas, n_max", [
    (HEAVY, [1.0, 1.5215, 1.53, 2.0, 10.0, 200.0], 45000),     # a minimum, then one wave
    (dict(EI=1, m=1, L=10, theory="timoshenko", rhoI="1/50", kGA=30, kw=0),
     [3.0, 38.0, 39.0, 60.0, 200.0], 300),                      # the second spectrum at 38.7
    (dict(EI=1, m=1, L=10, N=-2, kw=5), [1.0, 3.0, 30.0], 300),  # compression on a foundation
])
def test_weyl_estimate_counts_pinned_modes(fields, omegas, n_max):
    """``counting_wave_number * L / pi`` counts the pinned-pinned modes below ``omega`` to
    within one per dispersion branch (the closed form's count)."""
    beam = Beam("b", left="pinned", right="pinned", **fields)
    seg = beam.segment(beam.L)
    with mpmath.workdps(20):
        ref = _pinned_pinned(fields["EI"], fields["m"], fields["L"], fields.get("N", 0),
                             fields.get("rhoI", 0), fields.get("kGA"), fields.get("kw", 0),
                             n_max=n_max)
    assert ref[-1] > max(omegas)                 # (every mode below the largest omega)
    for omega in omegas:
        weyl = seg.counting_wave_number(omega) * float(beam.L) / math.pi
        exact = sum(1 for w in ref if w < omega)
        assert abs(weyl - exact) <= 2, (omega, weyl, exact)


# -- damped models ----------------------------------------------------------------------------
TIMO = dict(theory="timoshenko", rhoI="1/50", kGA=30)


def test_damped_timoshenko_pair_decouples():
    """Two identical Timoshenko beams joined by a spring and a dashpot: in phase they are
    undamped (closed form); opposite, each is one beam with spring and dashpot doubled."""
    W = 30.0
    beams = tuple(Beam(n, 1, 1, 1, left="pinned", right="pinned", **TIMO) for n in "ab")
    pair = Model(beams, (Spring("a", "b", "3/10", 20, c=2),))
    single = Model(beams[:1], (Spring("a", "ground", "3/10", 40, c=4),))
    spectrum = solve_damped(pair, omega_max=W, digits=15)
    opposite = solve_damped(single, omega_max=W, digits=15)
    with mpmath.workdps(DPS):
        in_phase = [w for w in _pinned_pinned(1, 1, 1, 0, "1/50", 30) if w < W]
    assert len(in_phase) == 2 and opposite.total >= 1
    idle = [e for e in spectrum if e.to_dict()["real"] == "0"]
    assert len(idle) == 2
    for e, ref in zip(idle, in_phase):
        _assert_digits(e.to_dict()["imag"], ref, 15)
    damped = [e.to_dict() for e in spectrum if e.to_dict()["real"] != "0"]
    assert damped == [e.to_dict() for e in opposite]


def test_damped_tip_bodies_in_phase_are_the_undamped_tip_body_cantilever():
    W = 40.0
    beams = tuple(Beam(n, 1, 1, 1, x0=0, left="clamped", right="free") for n in "ab")
    bodies = tuple(RigidBody(f"tip_{n}", (Attachment(n, 1),), M="1/2", J="1/30", xc="6/5")
                   for n in "ab")
    model = Model(beams, (Spring("a", "b", 1, 15, c="3/2"),), bodies=bodies)
    spectrum = solve_damped(model, omega_max=W, digits=15)
    ref = [w for w in _tip_body_roots("1/2", "1/30", "1/5", 4) if w < W]
    idle = [e for e in spectrum if e.to_dict()["real"] == "0"]
    assert len(idle) == len(ref) >= 2
    with mpmath.workdps(DPS):
        for e, r in zip(idle, ref):
            _assert_digits(e.to_dict()["imag"], r, 15)
    assert any(e.to_dict()["real"] != "0" for e in spectrum)


@pytest.mark.parametrize("model", [
    Model((Beam("b", 1, 1, 1, left="clamped", right="free", N=-2, **TIMO),),
          (Spring("b", "ground", "1/2", 3, c=1),),
          bodies=(RigidBody("tip", (Attachment("b", 1),), M=2, J="1/10", xc="11/10"),)),
    _fork(),
    Model((Beam("p", 1, 1, 3, left="pinned", right="pinned", theory="rayleigh", rhoI="1/40"),),
          (Spring("p", "ground", 2, 5, c="1/2"),),
          bodies=(RigidBody("both", (Attachment("p", 0, True), Attachment("p", 3, True)),
                            M=1, J=1, xc=1),)),
], ids=["timoshenko-tip-body", "fork", "body-held-twice"])
def test_dynamic_stiffness_delta_equals_transfer_delta_with_bodies(model):
    """det K * prod det U12 (times the squared pivots of the constraints) is det R."""
    ds = Kernel(model, 400.0)
    ev = Evaluator(model)
    rng = np.random.default_rng(11)
    lam = rng.uniform(-300, 50, 6) + 1j * rng.uniform(-200, 300, 6)
    logabs, phase, ok = ds.log_delta(lam)
    assert ok.all()
    for z, la, ph in zip(lam, logabs, phase):
        # (mpmath's det calls a matrix singular below its norm times eps: digits for the loss)
        with mpmath.workdps(40 + int(ev.digits_lost(z))):
            exact = ev.delta_mp(mpmath.mpc(z.real, z.imag))
            ratio = mpmath.exp(mpmath.mpf(la) + 1j * mpmath.mpf(ph)) / exact
        assert abs(ratio - 1) < 1e-9, (z, ratio)


# -- the stiffness matrix itself ------------------------------------------------------------
def test_segment_and_global_stiffness_are_symmetric_for_every_theory():
    from symtmm.elements import BeamSegment

    seg = BeamSegment(2, 3, sp.Rational(1, 2), kw=1, N=-3, rhoI=sp.Rational(1, 50), kGA=40)
    for w in (0.0, 3.0, 25.0, 80.0):
        D = _kernel_stiffness(seg, -w * w)
        assert np.allclose(D, D.T, rtol=1e-12, atol=1e-12 * np.abs(D).max())
    model = Model((Beam("b", 1, 1, 1, left="clamped", right="free", N=-2, **TIMO),),
                  bodies=(RigidBody("tip", (Attachment("b", 1),), M=2, J="1/10", xc="11/10"),))
    K = Counter(model, 50.0).matrix(17.0)
    assert np.allclose(K, K.T, rtol=1e-12, atol=1e-12 * np.abs(K).max())


def test_static_timoshenko_segment_stiffness_is_the_classical_one():
    """Static stiffness of a Timoshenko element (Przemieniecki): with phi = 12 EI/(kGA l**2),
    EI/((1 + phi) l**3) [[12, 6l, -12, 6l], [6l, (4 + phi) l**2, -6l, (2 - phi) l**2], ...]."""
    from symtmm.elements import BeamSegment

    EI, kGA, l = 2.0, 30.0, 0.5
    D = _kernel_stiffness(BeamSegment(EI, 1, sp.Rational(1, 2), rhoI=sp.Rational(1, 50),
                                      kGA=30), 0.0)
    phi = 12 * EI / (kGA * l * l)
    ref = EI / ((1 + phi) * l**3) * np.array(
        [[12, 6 * l, -12, 6 * l], [6 * l, (4 + phi) * l**2, -6 * l, (2 - phi) * l**2],
         [-12, -6 * l, 12, -6 * l], [6 * l, (2 - phi) * l**2, -6 * l, (4 + phi) * l**2]])
    assert np.allclose(D, ref, rtol=1e-12)


def test_a_body_held_more_times_than_it_has_freedoms_is_refused():
    beams = (Beam("a", 1, 1, 1, left="free", right="clamped"),
             Beam("b", 1, 1, 1, x0=1, left="clamped", right="free"))
    joint = RigidBody("j", (Attachment("a", 1), Attachment("b", 1)))
    # refused when the model is built (derive, codegen and scan never mesh it)
    with pytest.raises(ModelError, match="body 'j'.attach: held by more supported beam ends"):
        Model(beams, bodies=(joint,))
    # a hinge joint of two pinned ends fixes its only freedom twice
    pins = (Beam("a", 1, 1, 1, left="free", right="pinned"),
            Beam("b", 1, 1, 1, x0=1, left="pinned", right="free"))
    hinge = RigidBody("h", (Attachment("a", 1, True), Attachment("b", 1, True)))
    with pytest.raises(ModelError, match="held by more supported beam ends"):
        Model(pins, bodies=(hinge,))


# -- buckling ---------------------------------------------------------------------------------
@pytest.mark.parametrize("beam, unstable", [
    (Beam("b", 1, 1, 1, left="pinned", right="pinned", N=-15), 1),        # pi**2 < 15 < 4 pi**2
    (Beam("b", 1, 1, 1, left="pinned", right="pinned", N=-45), 2),        # 4 pi**2 < 45 < 9 pi**2
    (Beam("b", 1, 1, 1, left="pinned", right="free", N="-1/10"), 1),      # turns about the pin
    (Beam("b", 1, 1, 1, left="free", right="free", N="-1/10"), 1),        # turns, does not shift
    (Beam("b", 1, 1, 1, left="clamped", right="free", N=-3, **TIMO), 1),  # N_cr < pi**2/4
])
def test_a_buckled_model_is_refused(beam, unstable):
    word = "mode" if unstable == 1 else "modes"
    message = f"axial compression above a buckling load: {unstable} {word} with lam\\*\\*2 > 0"
    with pytest.raises(ComputationError, match=message):
        solve_undamped(Model((beam,)), count=3)
    with pytest.raises(ComputationError, match=message):
        solve_damped(Model((beam,), (Spring("b", "ground", "1/2", 0, c=1),)), omega_max=20)


def test_stiff_shear_in_si_units_beside_a_unit_bending_stiffness():
    """A Timoshenko cantilever with EI = 1 and kGA = 7e8 (a shear stiffness in SI units
    beside a unit bending stiffness): its pieces are cut for the frequencies asked, not
    for pi sqrt(EI/kGA) (which made 8,400 of them), and the frequencies are the roots of
    Huang's clamped-free frequency equation."""
    from test_theories_derive import _huang

    from symtmm.numeric.plan import StiffnessPlan
    beam = Beam("b", 1, 1, 1, left="clamped", right="free", theory="timoshenko",
                rhoI="1/100", kGA=700000000)
    model = Model((beam,))
    assert StiffnessPlan(model.require_numeric(), 200.0**2).n < 50
    spectrum = solve_undamped(model, count=5, digits=12)
    huang = _huang({"EI": 1, "m": 1, "L": 1, "kGA": 700000000, "rhoI": sp.Rational(1, 100)})
    with mpmath.workdps(40):
        for e in spectrum:
            ref = mpmath.findroot(huang, mpmath.mpf(e.omega))
            assert e.to_dict()["imag"] == mpmath.nstr(ref, 12, strip_zeros=False)


def test_a_model_in_si_units():
    """A steel girder (Timoshenko, EI = 1.68e6 N m2, kGA = 8.1e8 N) under a deck, joined by
    springs of 2.5e6 N/m: units of every size together, against the converged FE model."""
    girder = dict(name="g", EI=1.68e6, m=47.0, L=6.0, x0=0.0, left="pinned", right="pinned",
                  rhoI=0.0376, kGA=8.1e8)
    deck = dict(name="d", EI=3.2e5, m=120.0, L=6.0, x0=0.0, left="pinned", right="pinned")
    model = Model((Beam("g", "1.68e6", 47, 6, left="pinned", right="pinned",
                        theory="timoshenko", rhoI="0.0376", kGA="8.1e8"),
                   Beam("d", "3.2e5", 120, 6, left="pinned", right="pinned")),
                  (Spring("g", "d", 2, "2.5e6"), Spring("g", "d", 4, "2.5e6")))
    spectrum = solve_undamped(model, count=4, digits=12)
    fe = fe_converged([girder, deck], [dict(between=["g", "d"], x=2.0, k=2.5e6),
                                       dict(between=["g", "d"], x=4.0, k=2.5e6)], 12, count=4)
    got = np.array([float(e.omega) for e in spectrum])
    assert np.all(np.abs(got - fe["omega"]) <= 10 * fe["error"] + 1e-10 * got)


def test_compression_just_below_buckling_is_solved():
    """A pinned-sliding beam (half a pinned-pinned one of length 2L) at 0.99 of its buckling
    load pi**2 EI / (4 L**2): Y = sin(k x), k = (n - 1/2) pi / L, omega**2 = k**4 + N k**2;
    the first frequency is a tenth of the unloaded one."""
    N = -sp.Rational(99, 100) * sp.pi**2 / 4
    beam = Beam("b", 1, 1, 1, left="pinned", right="sliding", N=N)
    spectrum = solve_undamped(Model((beam,)), count=3, digits=15)
    with mpmath.workdps(DPS):
        n_val = -mpmath.mpf(99) / 100 * mpmath.pi**2 / 4
        ref = [mpmath.sqrt(q * q + n_val * q) for q in
               (((k - mpmath.mpf(1) / 2) * mpmath.pi) ** 2 for k in (1, 2, 3))]
        _assert_spectrum(spectrum, ref, 15)


# -- random small models: the count agrees with the roots found -------------------------------
_STABLE_ENDS = [("clamped", "free"), ("clamped", "pinned"), ("pinned", "pinned"),
                ("clamped", "clamped"), ("pinned", "sliding"), ("clamped", "sliding")]
_ANY_ENDS = _STABLE_ENDS + [("free", "free"), ("pinned", "free"), ("free", "sliding")]


@st.composite
def theory_models(draw):
    n = draw(st.integers(1, 2))
    beams = []
    for i in range(n):
        fields = draw(st.sampled_from([{}, dict(theory="rayleigh", rhoI="1/40"),
                                       dict(theory="timoshenko", rhoI="1/40", kGA=25)]))
        N = draw(st.sampled_from([0, 0, 3, "-1/2"]))
        ends = draw(st.sampled_from(_STABLE_ENDS if N == "-1/2" else _ANY_ENDS))
        kw = draw(st.sampled_from([0, 0, 6]))
        x0 = sp.Integer(0) if i == 0 else beams[0].x1
        beams.append(Beam(f"b{i}", draw(st.sampled_from(["1", "2", "1/2"])),
                          draw(st.sampled_from(["1", "3/2"])),
                          draw(st.sampled_from(["1", "4/5"])), x0=x0, left=ends[0],
                          right=ends[1], N=N, kw=kw, **fields))
    bodies, springs = [], []
    if n == 2 and all(b.N >= 0 for b in beams) and draw(st.booleans()):
        # a joint of the first beam's right end and the second's left end (freeing those
        # ends may leave a mechanism: only without compression, which would buckle it)
        beams[0] = replace(beams[0], right="free")
        beams[1] = replace(beams[1], left="free")
        hinged = draw(st.booleans())
        bodies.append(RigidBody("j", (Attachment("b0", beams[0].x1, hinged),
                                      Attachment("b1", beams[0].x1, hinged)),
                                M=draw(st.sampled_from([0, "1/2"]))))
    if draw(st.booleans()):
        x = beams[0].x0 + beams[0].L * sp.Rational(draw(st.integers(1, 4)), 5)
        bodies.append(RigidBody("r", (Attachment("b0", x),), M=draw(st.sampled_from(["1/2", 2])),
                                J=draw(st.sampled_from([0, "1/20"])),
                                xc=x + sp.Rational(draw(st.integers(-2, 2)), 10)))
    if draw(st.booleans()):
        springs.append(Spring("b0", "ground", beams[0].x0 + beams[0].L / 2,
                              draw(st.sampled_from([5, 40]))))
    return Model(tuple(beams), tuple(springs), bodies=tuple(bodies))


@settings(max_examples=10, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.too_slow])
@given(theory_models())
def test_random_models_count_agrees_with_roots_found(model):
    spectrum = solve_undamped(model, count=6, digits=15)
    assert spectrum.total >= 6
    # each root is a simple zero of the transfer-matrix Delta (the refinement proved a sign
    # change); the Wittrick-Williams count agrees with them between every pair and beyond
    edges = sorted({float(e.omega) for e in spectrum})
    sm = Counter(model, 2 * edges[-1])
    for lo, hi in zip([0.0] + edges, edges + [None]):
        w = 0.5 * (lo + hi) if hi is not None else lo * 1.0000001
        if w > 0:
            assert sm.count(w) == sum(e.multiplicity for e in spectrum if float(e.omega) < w)
    # and the argument principle on det K * prod det U12 (another algorithm) finds as many
    # nonzero roots below the top one: zeros at +-i omega, plus 2 per rigid-body mode at 0
    factor = 0.05          # a top edge clear of every eigenvalue: no root between it and the last
    while sm.count(edges[-1] * (1 + factor)) != spectrum.total:
        factor /= 4
    top = edges[-1] * (1 + factor / 2)
    rigid = sum(e.multiplicity for e in spectrum if e.omega == 0)
    nonzero = sum(e.multiplicity for e in spectrum if e.omega != 0)
    assert count_in_rectangle(model, -0.3, 0.3, -top, top) == 2 * nonzero + 2 * rigid


def test_a_supported_end_supports_the_joint_two_span_beam():
    """Two spans joined rigidly over a pin (the first span's end is pinned, the joint holds
    it): antisymmetric modes are pinned-pinned spans (Omega = n pi), symmetric ones
    pinned-clamped spans (tan nu = tanh nu)."""
    text = ('[[beam]]\nname = "a"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\nright = "pinned"\n'
            '[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nx0 = 1\nleft = "free"\n'
            'right = "pinned"\n[[joint]]\nends = ["a.right", "b.left"]\n')
    spectrum = solve(loads(text), count=6, digits=15)
    with mpmath.workdps(40):
        pc = [mpmath.findroot(lambda x: mpmath.tan(x) - mpmath.tanh(x), g) for g in (3.93, 7.07,
                                                                                   10.21)]
        refs = sorted([(n * mpmath.pi) ** 2 for n in (1, 2, 3)] + [nu**2 for nu in pc])
        for e, ref in zip(spectrum, refs):
            assert e.multiplicity == 1
            assert abs(e.omega - ref) < mpmath.mpf(10) ** -14 * ref


def test_two_supports_on_one_joint_are_refused():
    text = ('[[beam]]\nname = "a"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\nright = "pinned"\n'
            '[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nx0 = 1\nleft = "pinned"\n'
            'right = "pinned"\n[[joint]]\nends = ["a.right", "b.left"]\n')
    with pytest.raises(ModelError, match="more supported beam ends than it has freedoms"):
        loads(text)


def _kernel_stiffness(seg, lam2):
    """A segment's dynamic stiffness at ``lam**2`` from the kernel's transfer matrix."""
    from symtmm.numeric.arith import DOUBLE
    from symtmm.numeric.segments import segment_matrix
    U = segment_matrix(DOUBLE, seg, np.array([lam2], dtype=float))[0]
    return segment_stiffness(U)[0].real


def test_a_timoshenko_beam_1e20_long():
    """A pinned-pinned Timoshenko beam 1e20 long with kGA = 1 (its pieces once had to be
    shorter than 1e-12 of it: the bound of their clamped-clamped modes was searched over
    too narrow a range of its splitting): the closed form, the smaller root of
    ``m rhoI w**4 - (m (EI k**2 + kGA) + rhoI kGA k**2) w**2 + EI kGA k**4 = 0`` with
    ``k = n pi / L``."""
    model = Model((Beam("a", EI=1, m=1, L="1e20", rhoI=1, kGA=1, theory="timoshenko",
                        left="pinned", right="pinned"),))
    got = solve(model, count=2, digits=15)
    ctx = mpmath.MPContext()
    ctx.dps = 60
    for n, e in enumerate(got, 1):
        k = n * ctx.pi / ctx.mpf(10) ** 20
        b, c = (k * k + 1) + k * k, k ** 4
        w2 = 2 * c / (b + ctx.sqrt(b * b - 4 * c))
        assert e.multiplicity == 1
        assert abs(e.omega - ctx.sqrt(w2)) <= ctx.mpf(10) ** -15 * ctx.sqrt(w2)
