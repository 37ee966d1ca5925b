"""Checks of the finite-element reference model against closed-form results.

Every reference value here comes from an analytical frequency equation solved
with scipy, never from the rest of the package, so the FE model stays an
independent witness for the exact solver.
"""

import math

import numpy as np
import pytest
from scipy.optimize import brentq

from symtmm.fe import fe_frequencies, fe_matrices


def beam(name="a", EI=1.0, m=1.0, L=1.0, x0=0.0, left="pinned", right="pinned"):
    return dict(name=name, EI=EI, m=m, L=L, x0=x0, left=left, right=right)


def omega_from_Omega(Omega, EI=1.0, m=1.0, L=1.0):
    """Invert Omega = (omega**2 m L**4 / EI)**(1/4)."""
    return np.asarray(Omega) ** 2 / L**2 * math.sqrt(EI / m)


def positive_roots(f, count, start=0.5, step=0.01):
    """First `count` roots of f above `start`, bracketed on a fine grid."""
    roots = []
    a, fa = start, f(start)
    while len(roots) < count:
        b = a + step
        fb = f(b)
        if fa == 0.0 or fa * fb < 0.0:
            roots.append(brentq(f, a, b, xtol=1e-14, rtol=1e-15))
        a, fa = b, fb
    return np.array(roots)


# Frequency equations in Omega, written in forms without poles and with
# bounded amplitude (divided by cosh) so that bracketing is robust.
def cos_cosh_plus_one(x):  # clamped-free: cos x cosh x = -1
    return math.cos(x) + 1.0 / math.cosh(x)


def cos_cosh_minus_one(x):  # clamped-clamped and free-free: cos x cosh x = 1
    return math.cos(x) - 1.0 / math.cosh(x)


def tan_minus_tanh(x):  # clamped-pinned and pinned-free: tan x = tanh x
    return math.sin(x) - math.cos(x) * math.tanh(x)


def tan_plus_tanh(x):  # clamped-sliding: tan x = -tanh x
    return math.sin(x) + math.cos(x) * math.tanh(x)


def multiples_of_pi(offset):
    return lambda count: (np.arange(1, count + 1) - offset) * math.pi


CASES = {
    # (left, right): (number of rigid-body modes, function count -> Omega_n)
    ("pinned", "pinned"): (0, multiples_of_pi(0.0)),
    ("sliding", "sliding"): (1, multiples_of_pi(0.0)),
    ("pinned", "sliding"): (0, multiples_of_pi(0.5)),
    ("clamped", "clamped"): (0, lambda n: positive_roots(cos_cosh_minus_one, n)),
    ("free", "free"): (2, lambda n: positive_roots(cos_cosh_minus_one, n)),
    ("clamped", "free"): (0, lambda n: positive_roots(cos_cosh_plus_one, n)),
    ("free", "clamped"): (0, lambda n: positive_roots(cos_cosh_plus_one, n)),
    ("clamped", "pinned"): (0, lambda n: positive_roots(tan_minus_tanh, n)),
    ("pinned", "free"): (1, lambda n: positive_roots(tan_minus_tanh, n)),
    ("clamped", "sliding"): (0, lambda n: positive_roots(tan_plus_tanh, n)),
}


@pytest.mark.parametrize("ends", list(CASES), ids=lambda ends: "-".join(ends))
def test_single_beam_matches_closed_form(ends):
    rigid, reference = CASES[ends]
    flexible = 5
    omega = fe_frequencies([beam(left=ends[0], right=ends[1])], [], 60, count=rigid + flexible)

    assert np.all(omega[:rigid] == 0.0)
    exact = omega_from_Omega(reference(flexible))
    np.testing.assert_allclose(omega[rigid:], exact, rtol=2e-5)
    # Consistent mass makes this a Rayleigh-Ritz model: frequencies are upper bounds.
    assert np.all(omega[rigid:] >= exact * (1.0 - 1e-12))


def test_free_free_has_exactly_two_zero_modes():
    omega = fe_frequencies([beam(left="free", right="free")], [], 30)
    assert np.count_nonzero(omega == 0.0) == 2
    assert omega[2] > 20.0  # first flexible mode, (4.730)**2 = 22.37


def test_h4_convergence():
    def errors(elements):
        omega = fe_frequencies([beam(left="clamped", right="free")], [], elements, count=3)
        return omega / omega_from_Omega(positive_roots(cos_cosh_plus_one, 3)) - 1.0

    coarse, fine = errors(10), errors(40)
    assert np.all(fine > 0.0)
    assert np.all(fine < coarse)
    # Exact h**4 convergence would give 4**4 = 256.
    assert np.all(coarse / fine > 50.0)


def test_frequencies_scale_with_properties():
    EI, m, L = 2.0, 3.0, 1.5
    omega = fe_frequencies(
        [beam(EI=EI, m=m, L=L, x0=-0.7, left="clamped", right="free")], [], 60, count=4
    )
    exact = omega_from_Omega(positive_roots(cos_cosh_plus_one, 4), EI=EI, m=m, L=L)
    np.testing.assert_allclose(omega, exact, rtol=2e-5)


def test_two_beams_split_into_symmetric_and_antisymmetric_modes():
    # Identical beams moving together do not stretch the spring (single-beam
    # modes); moving opposite, each beam feels a ground spring of 2k.
    x0, x, k, elements, count = 2.0, 2.3, 50.0, 60, 8
    top, bottom = beam("top", x0=x0), beam("bottom", x0=x0)
    coupled = fe_frequencies([top, bottom], [dict(between=("top", "bottom"), x=x, k=k)],
                             elements, count=count)

    # A zero-stiffness spring puts a node at x so all three meshes coincide
    # and the decomposition holds to rounding, not just discretisation, error.
    single = fe_frequencies([top], [dict(between=("top", "ground"), x=x, k=0.0)], elements)
    grounded = fe_frequencies([top], [dict(between=("top", "ground"), x=x, k=2 * k)], elements)
    union = np.sort(np.concatenate([single, grounded]))[:count]
    np.testing.assert_allclose(coupled, union, rtol=1e-8)

    np.testing.assert_allclose(single[:5], omega_from_Omega(np.arange(1, 6) * math.pi), rtol=2e-5)


def test_zero_stiffness_spring_decouples_beams():
    a = beam("a", left="clamped", right="free")
    b = beam("b", x0=0.5, L=2.0)
    coupled = fe_frequencies([a, b], [dict(between=("a", "b"), x=0.8, k=0.0)], 40, count=6)
    separate = np.concatenate([
        fe_frequencies([a], [dict(between=("a", "ground"), x=0.8, k=0.0)], 40),
        fe_frequencies([b], [dict(between=("b", "ground"), x=0.8, k=0.0)], 40),
    ])
    np.testing.assert_allclose(coupled, np.sort(separate)[:6], rtol=1e-10)


def test_cantilever_with_tip_spring_at_beam_end():
    # Clamped at 0; at the tip Y'' = 0 and EI Y''' = k Y.  With
    # kappa = k L**3 / EI the frequency equation is
    # Omega**3 (1 + cos cosh) + kappa (sin cosh - cos sinh) = 0.
    kappa = 20.0

    def equation(x):
        return x**3 * (math.cos(x) + 1.0 / math.cosh(x)) + kappa * tan_minus_tanh(x)

    omega = fe_frequencies([beam(left="clamped", right="free")],
                           [dict(between=("a", "ground"), x=1.0, k=kappa)], 60, count=4)
    np.testing.assert_allclose(omega, omega_from_Omega(positive_roots(equation, 4)), rtol=2e-5)


def test_midspan_ground_spring_leaves_antisymmetric_modes_unchanged():
    spring = dict(between=("ground", "a"), x=0.5, k=20.0)
    omega = fe_frequencies([beam()], [spring], 40, count=4)
    plain = omega_from_Omega(np.arange(1, 5) * math.pi)
    np.testing.assert_allclose(omega[[1, 3]], plain[[1, 3]], rtol=2e-5)
    assert omega[0] > plain[0]  # the spring stiffens the first, symmetric, mode


def test_mesh_has_nodes_at_springs_and_drops_constrained_dofs():
    springs = [dict(between=("a", "ground"), x=0.3, k=1.0),
               dict(between=("a", "ground"), x=1.0, k=1.0)]
    K, M, info = fe_matrices([beam(left="clamped", right="pinned")], springs, 10)
    nodes, dofs = info["nodes"]["a"], info["dofs"]["a"]

    assert len(nodes) == 11 and np.any(np.isclose(nodes, 0.3))
    assert nodes[0] == 0.0 and nodes[-1] == 1.0
    assert dofs[0].tolist() == [-1, -1] and dofs[-1, 0] == -1 and dofs[-1, 1] >= 0
    assert info["n_dofs"] == K.shape[0] == M.shape[0] == 2 * 11 - 3
    assert sorted(dofs[dofs >= 0].tolist()) == list(range(info["n_dofs"]))
    np.testing.assert_allclose(K, K.T, atol=0.0)
    assert np.all(np.linalg.eigvalsh(M) > 0.0)


@pytest.mark.parametrize(
    "beams, springs, elements, count, message",
    [
        ([beam()], [dict(between=("a", "b"), x=0.5, k=1.0)], 10, None, "unknown beam"),
        ([beam()], [dict(between=("a", "ground"), x=1.5, k=1.0)], 10, None, "outside beam"),
        ([beam(right="hinged")], [], 10, None, "unknown boundary condition"),
        ([beam()], [dict(between=("a", "ground"), x=0.5, k=1.0, c=0.1)], 10, None, "undamped"),
        ([beam(), beam()], [], 10, None, "duplicate"),
        ([beam(EI=0.0)], [], 10, None, "positive"),
        ([beam()], [dict(between=("a", "a"), x=0.5, k=1.0)], 10, None, "itself"),
        ([beam()], [dict(between=("a", "ground"), x=0.5)], 10, None, "missing"),
        ([beam()], [], 0, None, "elements_per_beam"),
        ([beam()], [], 10, 100, "count"),
    ],
)
def test_bad_input_raises_value_error(beams, springs, elements, count, message):
    with pytest.raises(ValueError, match=message):
        fe_frequencies(beams, springs, elements, count=count)


def test_fine_mesh_lowest_mode_is_not_lost_to_rounding():
    # A plain dense solve would be off by ~1e-6 here; the refined eigenvalue
    # should sit at the (tiny) discretisation error.
    omega = fe_frequencies([beam(left="clamped", right="free")], [], 300, count=2)
    exact = omega_from_Omega(positive_roots(cos_cosh_plus_one, 2))
    np.testing.assert_allclose(omega, exact, rtol=1e-10)


def test_spring_at_rounded_beam_end_is_snapped_to_the_end_node():
    short = beam(x0=0.1, L=0.2, left="clamped", right="free")
    # The beam ends at 0.1 + 0.2 == 0.30000000000000004, not at 0.3.
    spring = dict(between=("a", "ground"), x=0.3, k=1.0)
    _, _, info = fe_matrices([short], [spring], 8)
    assert len(info["nodes"]["a"]) == 9
    assert info["nodes"]["a"][-1] == 0.1 + 0.2
