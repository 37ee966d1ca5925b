"""The finite-element reference for the new elements, and the exact solver against it.

First the FE model of :mod:`symtmm.fe` itself against references that owe nothing to
it: the classical element matrices (Hermite, geometric stiffness, consistent rotary
inertia, Przemieniecki's exact Timoshenko stiffness), pinned-pinned closed forms with
axial force, rotary inertia and shear (derived from the energy in
``derivations/beam_theories.py``), the cantilever with a tip body (its end conditions
derived in ``derivations/rigid_bodies.py``), and symmetry decoupling of forks, loops and
hinges into single beams with closed-form frequencies; its convergence rate is fitted.

Then the transfer-matrix model against the converged FE where no closed form exists:
two different Timoshenko beams joined by springs, a compressed Rayleigh beam coupled to
an Euler-Bernoulli beam, a rigid body linking two beams, an asymmetric fork. The
characteristic function ``Delta(i omega)`` must change sign within ``1e-6`` of every FE
frequency and nowhere else below the last; :func:`symtmm.solve.solve` must find the same
frequencies.
"""

from __future__ import annotations

import math

import mpmath
import numpy as np
import pytest
import scipy.linalg
from scipy.optimize import brentq

from symtmm.compile import Evaluator
from symtmm.elements import BeamSegment
from symtmm.fe import fe_converged, fe_frequencies, fe_matrices
from symtmm.model import Attachment, Beam, Model, RigidBody, Spring, oscillator
from symtmm.solve import solve

# -- helpers ------------------------------------------------------------------------------


def fe_input(model: Model) -> dict:
    """The FE model's dicts for a :class:`~symtmm.model.Model` (its data, read as numbers)."""
    model = model.require_numeric()
    beams = [dict(name=b.name, EI=float(b.EI), m=float(b.m), L=float(b.L), x0=float(b.x0),
                  left=b.left, right=b.right, kw=float(b.kw), N=float(b.N),
                  rhoI=float(b.rhoI), kGA=None if b.kGA is None else float(b.kGA))
             for b in model.beams]
    springs = [dict(between=(s.a, s.b), x=float(s.x), k=float(s.k), kind=s.kind)
               for s in model.springs]
    masses = [dict(beam=p.beam, x=float(p.x), M=float(p.M), J=float(p.J)) for p in model.masses]
    bodies = [dict(attach=[dict(beam=a.beam, x=float(a.x), hinged=a.hinged)
                           | ({"k": float(a.k)} if a.elastic else {})
                           for a in b.attachments], M=float(b.M), J=float(b.J),
                           xc=None if b.xc is None else float(b.xc))
              for b in model.bodies]
    return dict(beams=beams, springs=springs, masses=masses, bodies=bodies)


def converged(model: Model, count: int, elements: int = 8) -> np.ndarray:
    """The first ``count`` FE frequencies, extrapolated, their error estimated below 1e-7."""
    d = fe_input(model)
    out = fe_converged(d["beams"], d["springs"], elements, count, masses=d["masses"],
                       bodies=d["bodies"])
    assert np.all(out["error"] <= 1e-7 * np.maximum(out["omega"], 1.0)), out["error"]
    return out["omega"]


def assert_delta_vanishes_at(model: Model, omegas, rel: float = 1e-6) -> None:
    """``Delta(i omega)`` of the transfer-matrix model changes sign within ``rel`` of each
    non-zero ``omega``, and nowhere else on a fine grid up to the last of them."""
    ev = Evaluator(model.require_numeric())
    omegas = np.asarray([w for w in omegas if w > 0])
    with mpmath.workdps(40):
        for w in omegas:
            lo, hi = (ev.delta_omega_mp(mpmath.mpf(float(w)) * (1 + s * rel)) for s in (-1, 1))
            assert lo * hi < 0, f"no root of Delta within {rel} of the FE frequency {w}"
    # between the brackets: as many sign changes as FE frequencies, no more
    grid = np.geomspace(omegas[0] * 1e-2, omegas[-1] * (1 + 2 * rel), 6000)
    grid = grid[np.all(np.abs(grid[:, None] / omegas[None, :] - 1) > 2 * rel, axis=1)]
    values = ev.delta(1j * grid)
    assert np.all(np.abs(values.imag) <= 1e-6 * np.abs(values) + 1e-300)
    changes = np.count_nonzero(np.diff(np.sign(values.real)) != 0)
    assert changes == len(omegas), (changes, len(omegas))


def tmm_frequencies(model: Model, count: int) -> np.ndarray:
    return np.array([float(w) for w in solve(model, count=count, digits=12)
                     .omegas(expand=True)])


def roots(f, count, start, step=1e-3):
    """The first ``count`` roots of ``f`` above ``start`` (sign changes on a fine grid)."""
    out, a, fa = [], start, f(start)
    while len(out) < count:
        b = a + step
        fb = f(b)
        if fa * fb < 0:
            out.append(brentq(f, a, b, xtol=1e-15, rtol=1e-15))
        a, fa = b, fb
    return np.array(out)


def cantilever_Omegas(count):               # cos x cosh x = -1
    return roots(lambda x: math.cos(x) + 1 / math.cosh(x), count, 0.5)


def clamped_clamped_Omegas(count):          # cos x cosh x = 1, x > 0
    return roots(lambda x: math.cos(x) - 1 / math.cosh(x), count, 0.5)


def pinned_free_Omegas(count):              # tan x = tanh x, x > 0
    return roots(lambda x: math.sin(x) - math.cos(x) * math.tanh(x), count, 0.5)


def omega(Omega, EI, m, L):
    return np.asarray(Omega) ** 2 / L**2 * math.sqrt(EI / m)


def plain(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned", **extra):
    return dict(name=name, EI=EI, m=m, L=L, x0=x0, left=left, right=right, **extra)


def pinned_pinned(EI, m, L, N=0.0, rhoI=0.0, kGA=None, kw=0.0, count=4):
    """Closed form (``derivations/beam_theories.py``): ``Y = A sin(k x)``, ``psi = B cos(k x)``,
    ``q = k**2``; both roots of the amplitudes' determinant for each ``k``, sorted. With
    shear, ``k = 0`` is a mode too: ``Y = 0``, ``psi`` uniform, ``omega**2 = kGA/rhoI``."""
    out = [] if kGA is None or rhoI == 0 else [kGA / rhoI]
    for n in range(1, 4 * count + 1):
        q = (n * math.pi / L) ** 2
        if kGA is None:
            out.append((EI * q * q + N * q + kw) / (m + rhoI * q))
            continue
        A, B = (kGA + N) * q + kw, EI * q + kGA
        # det [[A - m w2, -kGA k], [-kGA k, B - rhoI w2]] = 0
        a2, a1, a0 = m * rhoI, -(m * B + rhoI * A), A * B - kGA**2 * q
        if a2 == 0:
            out.append(-a0 / a1)
        else:
            disc = math.sqrt(a1 * a1 - 4 * a2 * a0)      # a1 < 0: no cancellation below
            out += [2 * a0 / (-a1 + disc), (-a1 + disc) / (2 * a2)]
    return np.sqrt(np.sort(out)[:count])


# -- the FE model against closed forms ---------------------------------------------------

def test_element_matrices_are_the_classical_ones():
    l = 0.7
    _, M0, _ = fe_matrices([plain(L=l, left="free", right="free")], [], 1)
    K0, _, _ = fe_matrices([plain(EI=2.0, L=l, left="free", right="free")], [], 1)
    KN, _, _ = fe_matrices([plain(EI=2.0, L=l, left="free", right="free", N=3.0)], [], 1)
    _, MR, _ = fe_matrices([plain(L=l, left="free", right="free", rhoI=0.1)], [], 1)
    hermite = np.array([[12, 6 * l, -12, 6 * l], [6 * l, 4 * l * l, -6 * l, 2 * l * l],
                        [-12, -6 * l, 12, -6 * l], [6 * l, 2 * l * l, -6 * l, 4 * l * l]])
    mass = np.array([[156, 22 * l, 54, -13 * l], [22 * l, 4 * l * l, 13 * l, -3 * l * l],
                     [54, 13 * l, 156, -22 * l], [-13 * l, -3 * l * l, -22 * l, 4 * l * l]])
    geometric = np.array([[36, 3 * l, -36, 3 * l], [3 * l, 4 * l * l, -3 * l, -l * l],
                          [-36, -3 * l, 36, -3 * l], [3 * l, -l * l, -3 * l, 4 * l * l]])
    np.testing.assert_allclose(K0, 2.0 / l**3 * hermite, rtol=1e-13, atol=1e-12)
    np.testing.assert_allclose(M0, l / 420 * mass, rtol=1e-13, atol=1e-15)
    np.testing.assert_allclose(KN - K0, 3.0 / (30 * l) * geometric, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(MR - M0, 0.1 / (30 * l) * geometric, rtol=1e-12, atol=1e-14)


def test_timoshenko_element_condenses_to_the_exact_static_stiffness():
    # its fields contain every static solution, so eliminating the internal dofs gives
    # Przemieniecki's exact Timoshenko stiffness, Phi = 12 EI / (kGA l**2)
    EI, kGA, l = 2.0, 30.0, 0.6
    K, _, info = fe_matrices([plain(EI=EI, L=l, left="free", right="free", kGA=kGA)], [], 1)
    assert K.shape == (7, 7) and info["dofs"]["a"].tolist() == [[0, 1], [2, 3]]
    n, i = slice(0, 4), slice(4, 7)
    condensed = K[n, n] - K[n, i] @ np.linalg.solve(K[i, i], K[i, n])
    phi = 12 * EI / (kGA * l * l)
    exact = EI / ((1 + phi) * l**3) * np.array([
        [12, 6 * l, -12, 6 * l], [6 * l, (4 + phi) * l * l, -6 * l, (2 - phi) * l * l],
        [-12, -6 * l, 12, -6 * l], [6 * l, (2 - phi) * l * l, -6 * l, (4 + phi) * l * l]])
    np.testing.assert_allclose(condensed, exact, rtol=1e-12, atol=1e-10)


PINNED_PINNED = {
    "tension": dict(N=25.0),
    "compression": dict(N=-6.0),
    "rayleigh": dict(rhoI=0.02),
    "rayleigh-compression-foundation": dict(rhoI=0.01, N=-3.0, kw=40.0),
    "timoshenko": dict(rhoI=0.004, kGA=150.0),
    "timoshenko-tension-foundation": dict(rhoI=0.004, kGA=150.0, N=10.0, kw=40.0),
    "timoshenko-compression": dict(rhoI=0.004, kGA=150.0, N=-5.0),
    "timoshenko-no-rotary-inertia": dict(kGA=60.0),
}


@pytest.mark.parametrize("case", list(PINNED_PINNED))
def test_pinned_pinned_closed_forms_and_h4_convergence(case):
    extra = PINNED_PINNED[case]
    EI, m, L = 2.0, 3.0, 1.5
    exact = pinned_pinned(EI, m, L, count=4, **extra)
    beam = plain(EI=EI, m=m, L=L, **extra)
    sizes = np.array([4, 8, 16, 32])
    errors = np.array([fe_frequencies([beam], [], n, count=4) / exact - 1 for n in sizes])
    assert np.all(errors > -1e-12)                     # Rayleigh-Ritz: bounds from above
    assert np.all(errors[-1] < 5e-5)
    # error ~ C h**4: the slope of log(error) against log(h), fitted on the three finest
    slopes = [np.polyfit(np.log(1 / sizes[1:]), np.log(errors[1:, j]), 1)[0] for j in range(4)]
    assert np.all((np.array(slopes) > 3.8) & (np.array(slopes) < 4.2)), slopes
    out = fe_converged([beam], [], 8, 4)
    np.testing.assert_allclose(out["omega"], exact, rtol=5e-8)
    assert np.all(np.abs(out["omega"] - exact) <= out["error"])     # the estimate bounds it
    assert np.all(np.abs(out["rate"] - 4) < 0.1)


def test_timoshenko_second_spectrum():
    # the higher root of each k: shear modes; the lowest sits above omega**2 = kGA/rhoI
    EI, m, L, rhoI, kGA = 1.0, 1.0, 1.0, 0.01, 40.0
    exact = pinned_pinned(EI, m, L, rhoI=rhoI, kGA=kGA, count=12)
    assert exact[-1] ** 2 > kGA / rhoI                 # the first shear mode is among them
    got = fe_converged([plain(rhoI=rhoI, kGA=kGA)], [], 16, 12)["omega"]
    np.testing.assert_allclose(got, exact, rtol=1e-8)
    assert math.isclose(got[np.argmin(np.abs(got**2 / (kGA / rhoI) - 1))] ** 2, kGA / rhoI,
                        rel_tol=1e-9)                  # the uniform shear mode, k = 0


def test_timoshenko_element_is_free_of_shear_locking():
    # very stiff in shear, coarse mesh: the Euler-Bernoulli values within the shear
    # correction O(EI / (kGA L**2)), not stiffer (a locking element is far off)
    cantilever = plain(left="clamped", right="free")
    eb = fe_frequencies([cantilever], [], 6, count=3)
    for kGA in (1e4, 1e8):
        stiff = fe_frequencies([dict(cantilever, kGA=kGA)], [], 6, count=3)
        assert np.all(stiff <= eb * (1 + 1e-12))
        assert np.all(eb / stiff - 1 < 50 / kGA)


def test_rayleigh_and_timoshenko_tend_to_euler_bernoulli():
    cantilever = plain(left="clamped", right="free")
    exact = omega(cantilever_Omegas(3), 1.0, 1.0, 1.0)
    previous = None
    for scale in (1e-4, 1e-5, 1e-6):
        got = fe_converged([dict(cantilever, rhoI=scale, kGA=1 / scale)], [], 8, 3)["omega"]
        gap = exact - got
        assert np.all(gap > 0)                         # shear and rotary inertia lower omega
        if previous is not None:
            np.testing.assert_allclose(previous / gap, 10, rtol=0.02)    # O(scale)
        previous = gap


# -- bodies and joints against closed forms ----------------------------------------------

def test_body_held_at_its_centre_of_mass_is_a_lumped_mass():
    beam = plain(left="clamped", right="free", N=2.0, rhoI=0.01, kGA=200.0)
    body = dict(attach=[dict(beam="a", x=0.6)], M=0.7, J=0.03)
    mass = dict(beam="a", x=0.6, M=0.7, J=0.03)
    with_body = fe_frequencies([beam], [], 12, count=6, bodies=[body])
    with_mass = fe_frequencies([beam], [], 12, count=6, masses=[mass])
    np.testing.assert_allclose(with_body, with_mass, rtol=1e-11)


def tip_body_omegas(EI, m, L, M, J, e, count):
    """Cantilever with a rigid body at the tip, centre of mass ``e`` beyond it.

    ``Y = A (cosh - cos) + B (sinh - sin)`` of ``beta x``; end conditions
    ``EI Y''' = -omega**2 M (Y + e Y')``, ``EI Y'' = omega**2 (J Y' + M e (Y + e Y'))``
    (``derivations/rigid_bodies.py``), ``omega**2 = EI beta**4 / m``.
    """
    def det(beta):
        x = beta * L
        ch, co, sh, si = math.cosh(x), math.cos(x), math.sinh(x), math.sin(x)
        w2 = EI * beta**4 / m
        Y = np.array([ch - co, sh - si])
        dY = beta * np.array([sh + si, ch - co])
        d2 = beta**2 * np.array([ch + co, sh + si])
        d3 = beta**3 * np.array([sh - si, ch + co])
        shear = EI * d3 + w2 * M * (Y + e * dY)
        moment = EI * d2 - w2 * (J * dY + M * e * (Y + e * dY))
        return (shear[0] * moment[1] - shear[1] * moment[0]) / (ch * ch * beta**5)
    betas = roots(det, count, 0.05 / L)
    return np.sqrt(EI * betas**4 / m)


@pytest.mark.parametrize("e", [0.0, 0.15])
def test_cantilever_with_a_tip_body(e):
    EI, m, L, M, J = 1.5, 1.2, 1.0, 0.4, 0.01
    exact = tip_body_omegas(EI, m, L, M, J, e, 5)
    body = dict(attach=[dict(beam="a", x=L)], M=M, J=J, xc=L + e)
    out = fe_converged([plain(EI=EI, m=m, L=L, left="clamped", right="free")], [], 8, 5,
                       bodies=[body])
    np.testing.assert_allclose(out["omega"], exact, rtol=1e-9)
    assert np.all(np.abs(out["rate"] - 4) < 0.15)


def fork(L1=1.0, L2=0.6, kind="rigid", EI=1.0, m=1.0):
    """Clamped trunk (EI, m, L1) forking into two identical branches (EI/2, m/2, L2)."""
    beams = [plain("t", EI, m, L1, left="clamped", right="free"),
             plain("u", EI / 2, m / 2, L2, x0=L1, left="free", right="free"),
             plain("v", EI / 2, m / 2, L2, x0=L1, left="free", right="free")]
    joint = dict(attach=[dict(beam=b, x=L1, hinged=kind == "hinge") for b in "tuv"])
    return beams, [joint]


def test_symmetric_fork_decouples_into_cantilevers():
    # in phase: one cantilever (EI, m, L1 + L2); in opposition: each branch a cantilever
    L1, L2 = 1.0, 0.6
    beams, joints = fork(L1, L2)
    got = fe_converged(beams, [], 8, 7, bodies=joints)
    exact = np.sort(np.r_[omega(cantilever_Omegas(7), 1, 1, L1 + L2),
                          omega(cantilever_Omegas(3), 0.5, 0.5, L2)])[:7]
    np.testing.assert_allclose(got["omega"], exact, rtol=1e-9)
    assert np.all(np.abs(got["rate"] - 4) < 0.15)


def test_closed_loop_decouples():
    # trunk, two identical branches rejoining into a tail: in phase one clamped-free beam,
    # in opposition each branch clamped-clamped (trunk and tail at rest)
    L1, L2, L3 = 0.5, 0.8, 0.4
    beams = [plain("t", 1.0, 1.0, L1, left="clamped", right="free"),
             plain("u", 0.5, 0.5, L2, x0=L1, left="free", right="free"),
             plain("v", 0.5, 0.5, L2, x0=L1, left="free", right="free"),
             plain("w", 1.0, 1.0, L3, x0=L1 + L2, left="free", right="free")]
    joints = [dict(attach=[dict(beam=b, x=L1) for b in "tuv"]),
              dict(attach=[dict(beam=b, x=L1 + L2) for b in "uvw"])]
    got = fe_converged(beams, [], 8, 6, bodies=joints)["omega"]
    exact = np.sort(np.r_[omega(cantilever_Omegas(6), 1, 1, L1 + L2 + L3),
                          omega(clamped_clamped_Omegas(3), 0.5, 0.5, L2)])[:6]
    np.testing.assert_allclose(got, exact, rtol=1e-9)


def test_hinge_between_two_pinned_beams():
    # pinned - hinge - pinned, identical halves: a mechanism (omega = 0); symmetric modes
    # make each half pinned-free, antisymmetric ones pinned-pinned
    L = 0.8
    beams = [plain("a", L=L, left="pinned", right="free"),
             plain("b", L=L, x0=L, left="free", right="pinned")]
    hinge = dict(attach=[dict(beam="a", x=L, hinged=True), dict(beam="b", x=L, hinged=True)])
    got = fe_converged(beams, [], 8, 6, bodies=[hinge])["omega"]
    exact = np.sort(np.r_[0.0, omega(pinned_free_Omegas(3), 1, 1, L),
                          omega(np.arange(1, 4) * math.pi, 1, 1, L)])[:6]
    assert got[0] == 0.0
    np.testing.assert_allclose(got[1:], exact[1:], rtol=1e-8)
    # a rigid joint instead: one pinned-pinned beam of length 2 L
    rigid = dict(attach=[dict(beam="a", x=L), dict(beam="b", x=L)])
    got = fe_converged(beams, [], 8, 4, bodies=[rigid])["omega"]
    np.testing.assert_allclose(got, omega(np.arange(1, 5) * math.pi, 1, 1, 2 * L), rtol=1e-8)


def test_hinged_fork_has_free_branches():
    # branches pinned to the trunk's tip turn freely: two modes at omega = 0
    beams, joints = fork(kind="hinge")
    got = fe_frequencies(beams, [], 10, count=4, bodies=joints)
    assert np.count_nonzero(got == 0.0) == 2 and got[2] > 1.0


@pytest.mark.parametrize("bodies, message", [
    ([dict(attach=[dict(beam="z", x=0.5)])], "unknown beam"),
    ([dict(attach=[dict(beam="a", x=1.5)])], "outside beam"),
    ([dict(attach=[dict(beam="a", x=0.5), dict(beam="a", x=0.5)])], "attached twice"),
    ([dict(attach=[])], "non-empty"),
    ([dict(attach=[dict(beam="a", x=0.5, hinged="yes")])], "hinged"),
    ([dict(attach=[dict(beam="a", x=0.5)], M=-1)], "non-negative"),
])
def test_bad_bodies_are_refused(bodies, message):
    with pytest.raises(ValueError, match=message):
        fe_frequencies([plain()], [], 8, bodies=bodies)


def test_buckled_and_massless_models_are_refused():
    # compression above the Euler load pi**2 EI / L**2
    with pytest.raises(ValueError, match="unstable"):
        fe_frequencies([plain(N=-1.2 * math.pi**2)], [], 8, count=2)
    with pytest.raises(ValueError, match="kGA"):
        fe_frequencies([plain(kGA=5.0, N=-6.0)], [], 8)
    # a massless body hinged at one point off its centre: its rotation is undetermined
    floating = dict(attach=[dict(beam="a", x=0.5, hinged=True)], xc=0.8)
    with pytest.raises(ValueError, match="neither mass nor stiffness|no inertia"):
        fe_frequencies([plain()], [], 8, bodies=[floating])


# -- the transfer-matrix solver against the converged FE -----------------------------------

COUPLED = {
    "two-timoshenko-beams-and-springs": Model(
        (Beam("a", 1, 1, 1, left="clamped", right="free", theory="timoshenko", rhoI="1/400",
              kGA=150),
         Beam("b", 2, "3/2", "6/5", x0="-1/10", left="pinned", right="clamped",
              theory="timoshenko", rhoI="1/200", kGA=300)),
        (Spring("a", "b", "3/10", 80), Spring("a", "b", "4/5", 40),
         Spring("b", "ground", "1/2", 25))),
    "compressed-rayleigh-and-euler-bernoulli": Model(
        (Beam("a", 1, 1, 1, left="pinned", right="pinned", theory="rayleigh", rhoI="1/100",
              N=-4),
         Beam("b", "3/2", 1, "9/10", left="clamped", right="free")),
        (Spring("a", "b", "7/10", 60),)),
    "rigid-body-linking-two-beams": Model(
        (Beam("a", 1, 1, 1, left="clamped", right="free"),
         Beam("b", 1, 2, 1, x0="1/5", left="free", right="pinned")),
        bodies=(RigidBody("r", (Attachment("a", 1), Attachment("b", "1/5", True)),
                          M="1/2", J="1/50", xc="3/5"),)),
    "asymmetric-fork": Model(
        (Beam("t", 2, 2, 1, left="clamped", right="free"),
         Beam("u", 1, 1, "3/5", x0=1, left="free", right="free"),
         Beam("v", "1/2", "3/4", "4/5", x0=1, left="free", right="pinned", theory="timoshenko",
              rhoI="1/500", kGA=100)),
        bodies=(RigidBody("j", (Attachment("t", 1), Attachment("u", 1), Attachment("v", 1))),)),
    # sprung masses: one on a Timoshenko cantilever, one between two beams (Gurgoze and
    # Erol's double beam), each spring of its own stiffness
    "sprung-masses": Model(
        (Beam("a", 1, 1, 1, left="clamped", right="free", theory="timoshenko", rhoI="1/400",
              kGA=150),
         Beam("b", "3/2", 1, "9/10", left="pinned", right="pinned")),
        bodies=(oscillator("tmd", "a", x="7/10", M="1/10", k=9),
                oscillator("m", ("a", "b"), x="2/5", M="1/5", k=(30, 70)))),
    # a rigid body on two springs at a distance from its centre of mass: it rocks
    "body-on-springs": Model(
        (Beam("a", 1, 1, 1, left="pinned", right="pinned"),),
        bodies=(RigidBody("r", (Attachment("a", "1/5", k=40), Attachment("a", "3/4", k=60)),
                          M="3/10", J="1/40", xc="1/2"),)),
}
COUNT = 5


@pytest.mark.parametrize("name", list(COUPLED))
def test_delta_vanishes_at_the_fe_frequencies(name):
    model = COUPLED[name]
    assert_delta_vanishes_at(model, converged(model, COUNT))


@pytest.mark.parametrize("name", list(COUPLED))
def test_solver_agrees_with_converged_fe(name):
    model = COUPLED[name]
    np.testing.assert_allclose(tmm_frequencies(model, COUNT), converged(model, COUNT),
                               rtol=1e-6)


def test_exact_transfer_matrix_where_a_wave_number_vanishes():
    import sympy as sp
    seg = BeamSegment(1, 1, 1, N=2)
    A = seg.system_matrix(0)
    reference = (A * 1).exp()                      # SymPy's own matrix exponential
    U = seg.transfer_matrix(0)
    assert not U.has(sp.nan)
    assert sp.simplify(U - reference) == sp.zeros(4, 4)


def test_fe_input_reads_every_field():
    model = COUPLED["rigid-body-linking-two-beams"]
    d = fe_input(model)
    assert d["bodies"] == [dict(attach=[dict(beam="a", x=1.0, hinged=False),
                                        dict(beam="b", x=0.2, hinged=True)],
                                M=0.5, J=0.02, xc=0.6)]
    timo = fe_input(COUPLED["two-timoshenko-beams-and-springs"])["beams"][1]
    assert (timo["kGA"], timo["rhoI"], timo["x0"]) == (300.0, 0.005, -0.1)
    # the transform reproduces the constraints: Y of both attachments follows the body
    _, M, info = fe_matrices(d["beams"], d["springs"], 4, bodies=d["bodies"])
    T = info["transform"]
    yc, tc = info["body_dofs"][0]
    node_a = info["full_dofs"]["a"][-1]
    node_b = info["full_dofs"]["b"][0]
    np.testing.assert_allclose(T[node_a[0]] - T[yc] - 0.4 * T[tc], 0, atol=1e-14)
    np.testing.assert_allclose(T[node_a[1]] - T[tc], 0, atol=1e-14)
    np.testing.assert_allclose(T[node_b[0]] - T[yc] + 0.4 * T[tc], 0, atol=1e-14)
    assert np.all(scipy.linalg.eigvalsh(M) > 0)


@pytest.mark.parametrize("EI, m, L, kw, N, rhoI, kGA", [
    (1.0, 1.0, 1.0, 0.0, 0.0, 0.01, 7e8),          # stiff in shear (an SI kGA): eps near 1
    (1e4, 500.0, 3.0, 0.0, 0.0, 5.0, 1e6),
    (2.0, 1.0, 1.0, 0.0, 0.0, 0.05, 3.0),          # soft in shear: eps near 0
    (1.0, 2.0, 0.5, 10.0, 4.0, 0.0, 50.0),         # no rotary inertia, a foundation, tension
    (1.0, 1.0, 1.0, 0.0, -3.0, 0.02, 400.0),       # compression
])
def test_the_clamped_piece_bound_is_below_the_piece_and_as_high_as_its_eps_allow(
        EI, m, L, kw, N, rhoI, kGA):
    """``clamped_frequency_bound`` lies below the clamped-clamped fundamental of the piece
    (the finite-element one, above the exact one), and is the best ``min(coef_y / m,
    coef_psi / rhoI)`` over the splitting ``eps`` (against a scan of eps in [1e-12, 1])."""
    seg = BeamSegment(EI, m, L, kw=kw, N=N, rhoI=rhoI, kGA=kGA)
    bound = seg.clamped_frequency_bound(L)
    beam = dict(name="b", EI=EI, m=m, L=L, x0=0.0, left="clamped", right="clamped", kw=kw,
                N=N, rhoI=rhoI, kGA=kGA)
    fe = fe_frequencies([beam], [], 40, count=1)[0]
    assert 0 < bound <= fe ** 2
    # the scan, written from the inequality itself (its kp and extra as for N >= 0, or
    # N < 0 as in the method)
    q = (math.pi / L) ** 2
    if N >= 0:
        kp, extra = kGA, 0.0
    else:
        eta = 1.0 if kGA + 2 * N > 0 else (-kGA / N - 1) / 2
        kp, extra = kGA + N * (1 + eta), N * (1 + 1 / eta)
    def best(eps):
        y = ((kp * (1 - eps) + max(N, 0.0)) * q + kw) / m
        p = EI * q - kp * (1 / eps - 1) + extra
        return np.where(p >= 0, y, 0.0) if rhoI == 0 else np.minimum(y, p / rhoI)

    # a grid in eps and in 1 - eps, then zooms about its best point
    eps = np.concatenate([np.logspace(-12, np.log10(0.5), 4001), 1 - np.logspace(-15, np.log10(0.5), 4001)])
    for _ in range(12):
        values = best(eps)
        i = int(np.argmax(values))
        scan = values[i]
        lo, hi = eps[max(i - 1, 0)], eps[min(i + 1, eps.size - 1)]
        eps = np.linspace(lo, hi, 2001)
    assert bound == pytest.approx(scan, rel=1e-7)
