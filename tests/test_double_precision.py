"""The double-precision Delta keeps its digits at high modes (Godunov orthonormalisation)."""

import mpmath
import numpy as np
import pytest

from symtmm.compile import Evaluator
from symtmm.model import Beam, Model
from symtmm.modelfile import load


def test_clamped_clamped_against_its_closed_form_up_to_omega_300():
    ev = Evaluator(Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),)))
    Om = np.linspace(20.3, 300.7, 57)
    value = ev.delta(1j * Om**2)
    with mpmath.workdps(200):
        exact = [complex((1 - mpmath.cos(o) * mpmath.cosh(o)) / (2 * o**4)) for o in Om]
    assert np.max(np.abs(value / np.array(exact) - 1)) < 1e-11
    # the plain product (R, then det) has lost every digit there: the case the method is for
    plain = np.linalg.det(ev.R(1j * Om[-5:] ** 2))
    assert np.max(np.abs(plain / np.array(exact[-5:]) - 1)) > 1e-3


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc", "paper_ex3_three_pp_coupled",
                                  "paper_ex4_damped", "point_elements", "winkler_two_beams"])
def test_examples_agree_with_mpmath_at_60_digits_up_to_omega_60(examples_dir, name):
    ev = Evaluator(load(examples_dir / f"{name}.toml"))
    rng = np.random.default_rng(3)
    scale = 146.2698 / np.pi**2 if name == "paper_ex4_damped" else 1.0
    Om = rng.uniform(2, 60, 12)
    lam = scale * Om**2 * (1j - (rng.uniform(0, 0.3, 12) if ev.damped else 0))
    value = ev.delta(lam)
    logabs, phase = ev.log_delta(lam)
    for z, v, la, ph in zip(lam, value, logabs, phase):
        with mpmath.workdps(60 + int(ev.digits_lost(z))):
            ref = complex(ev.delta_mp(mpmath.mpc(z.real, z.imag)))
        assert abs(v / ref - 1) < 1e-11
        assert la == pytest.approx(np.log(abs(ref)), abs=1e-11)
        assert np.exp(1j * ph) == pytest.approx(ref / abs(ref), abs=1e-11)


def test_log_delta_does_not_overflow():
    ev = Evaluator(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)))
    Om = 1000.25                                     # |Delta| ~ exp(1000) / Om**2
    logabs, _ = ev.log_delta(np.array([1j * Om**2]))
    with mpmath.workdps(30):
        ref = mpmath.log(abs(mpmath.sin(Om) * mpmath.sinh(Om) / Om**2))
    assert logabs[0] == pytest.approx(float(ref), rel=1e-12)


def test_a_bracket_whose_values_fall_by_e_folds_gives_a_point_near_its_root():
    """``(x - r) exp(-15000 (x - 0.09))`` on ``[0.08, 0.1]``: ``|f|`` falls by 300 e-folds
    across the bracket, so a point by its small end lies below every point near the root
    ``r = 0.0845`` (a model part's second frequency came out as the first probe's point,
    0.0999, and its damped search lost its estimate). The refinement gives the point of
    least ``|f|`` within its last bracket. Reference: ``r``, placed."""
    from symtmm.roots.bracket import shrink
    r = 0.0845

    def f(x):
        return (x - r) * np.exp(-15000.0 * (x - 0.09))

    def probe(c, idx):
        v = f(c)
        return v, np.where(np.sign(v) == np.sign(f(b[idx])), 1, -1)
    a, b = np.array([0.08]), np.array([0.1])
    got = shrink(a, b, f(a), f(b), probe, 1e-11, settle=True)
    assert abs(got[0] - r) < 1e-12
