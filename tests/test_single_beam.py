"""Single beams: every pair of boundary conditions against the classical equations."""

import itertools

import mpmath
import pytest
from reference import FREQUENCY_EQUATIONS, classical_roots, rigid_modes

from symtmm import Beam, Model
from symtmm.roots import rigid_body_modes
from symtmm.solve import solve

BCS = ("free", "clamped", "pinned", "sliding")
PAIRS = [p for p in itertools.product(BCS, BCS)]


@pytest.mark.parametrize("left,right", PAIRS)
def test_single_beam_matches_classical_equation(left, right):
    # non-unit properties: omega = (nu / L)^2 sqrt(EI / m)
    EI, m, L = mpmath.mpf(3), mpmath.mpf(2), mpmath.mpf("1.5")
    model = Model((Beam("b", EI="3", m="2", L="1.5", left=left, right=right),))
    n = 8
    spectrum = solve(model, count=n, digits=20)
    rigid = rigid_modes(left, right)
    expected = classical_roots(left, right, n - rigid)
    got = spectrum.omegas(expand=True)
    assert len(got) == n
    assert all(w == 0 for w in got[:rigid])
    assert all(w > 0 for w in got[rigid:])
    with mpmath.workdps(40):
        for nu, w in zip(expected, got[rigid:]):
            ref = (nu / L) ** 2 * mpmath.sqrt(EI / m)
            assert abs(w - ref) <= mpmath.mpf(10) ** -19 * ref, (left, right, nu)


@pytest.mark.parametrize("left,right", PAIRS)
def test_rigid_body_modes(left, right):
    model = Model((Beam("b", 1, 1, 1, left=left, right=right),))
    assert rigid_body_modes(model) == rigid_modes(left, right)


def test_reference_table_covers_every_pair():
    for left, right in PAIRS:
        assert (left, right) in FREQUENCY_EQUATIONS or (right, left) in FREQUENCY_EQUATIONS


def test_omega_max_returns_exactly_the_roots_below_the_bound():
    model = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
    # (n pi)^2: 9.87, 39.48, 88.83, 157.91
    spectrum = solve(model, omega_max=100.0)
    assert [round(float(w), 6) for w in spectrum.omegas()] == [
        round(float((k * mpmath.pi) ** 2), 6) for k in (1, 2, 3)]
    # a bound exactly on an eigenvalue includes it
    spectrum = solve(model, omega_max=float(mpmath.pi**2))
    assert len(spectrum) == 1


def test_high_modes_of_clamped_clamped_beam():
    """Modes 40-50 at Omega ~ 150: the determinant loses ~65 digits; all must be right."""
    model = Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),))
    spectrum = solve(model, count=50, digits=18)
    expected = classical_roots("clamped", "clamped", 50, dps=60)
    with mpmath.workdps(40):
        for nu, w in zip(expected, spectrum.omegas()):
            assert abs(w - nu**2) <= mpmath.mpf(10) ** -17 * nu**2
