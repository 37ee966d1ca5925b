"""Identical beams joined at the same points decouple into single beams.

If n identical beams are joined by springs k at the same positions, along
the edges of a graph, the modes split by the eigenvectors of the graph
Laplacian: each family is one beam with grounded springs of (Laplacian
eigenvalue) x k at those positions. Two beams: 0 and 2k; a chain of three:
0, k and 3k. The single-beam problems are solved on their own and their union
must equal the coupled spectrum, multiplicities included.
"""

import mpmath
import pytest

from symtmm import Beam, Model, Spring
from symtmm.solve import solve


def _beam(name, left, right):
    return Beam(name, EI="2", m="3", L="1.2", left=left, right=right)


def _single(left, right, xs, factor, k):
    springs = tuple(Spring("b", "ground", x, f"{factor}*{k}") for x in xs) if factor else ()
    return Model((_beam("b", left, right),), springs)


def _union(spectra):
    values = []
    for s in spectra:
        values += s.omegas(expand=True)
    return sorted(values)


def _assert_same(coupled, reference, digits):
    got = coupled.omegas(expand=True)
    assert len(got) == len(reference)
    with mpmath.workdps(digits + 10):
        tol = mpmath.mpf(10) ** (1 - digits)
        for g, r in zip(got, reference):
            assert abs(g - r) <= tol * max(abs(r), 1), (g, r)


@pytest.mark.parametrize("left,right", [("pinned", "pinned"), ("free", "free"),
                                        ("clamped", "free"), ("clamped", "sliding")])
def test_two_identical_beams(left, right):
    xs, k = ("0.3", "0.85"), "40"
    coupled = Model((_beam("p", left, right), _beam("q", left, right)),
                    tuple(Spring("p", "q", x, k) for x in xs))
    omega_max = 400.0
    ref = _union(solve(_single(left, right, xs, f, k), omega_max=omega_max, digits=20)
                 for f in (0, 2))
    _assert_same(solve(coupled, omega_max=omega_max, digits=20), ref, 20)


@pytest.mark.parametrize("left,right", [("pinned", "pinned"), ("clamped", "clamped")])
def test_chain_of_three_identical_beams(left, right):
    xs, k = ("0.25", "0.9"), "25"
    beams = tuple(_beam(n, left, right) for n in ("a", "b", "c"))
    springs = tuple(Spring(p, q, x, k) for p, q in (("a", "b"), ("b", "c")) for x in xs)
    omega_max = 300.0
    ref = _union(solve(_single(left, right, xs, f, k), omega_max=omega_max, digits=18)
                 for f in (0, 1, 3))
    _assert_same(solve(Model(beams, springs), omega_max=omega_max, digits=18), ref, 18)


def test_paper_example_3_decouples(examples_dir):
    """Paper example 3 (K = 25, x1 = 0.25) against its decoupled single beams."""
    from symtmm.modelfile import load

    model = load(examples_dir / "paper_ex3_three_pp_coupled.toml")
    spectrum = solve(model, count=15, digits=16)
    ref = _union(solve(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),),
                             tuple(Spring("b", "ground", x, f * 25) for x in ("0.25", "0.75")
                                   if f)),
                       count=15, digits=16) for f in (0, 1, 3))[:15]
    _assert_same(spectrum, ref, 16)
    # Omega = 4 pi: sin(4 pi x) vanishes at both springs, so all three families share it
    triple = [e for e in spectrum if e.multiplicity == 3]
    assert triple and abs(triple[0].omega - (4 * mpmath.pi) ** 2) < 1e-13


@pytest.mark.parametrize("certified", [True, False])
def test_paper_example_3_triple_root_with_and_without_balls(examples_dir, certified):
    """The triple root (4 pi)**2 of example 3 at 30 digits, its cluster's ends counted in
    the zoom's first ball batch (balls) or at two precisions first (mpmath): one
    eigenvalue of multiplicity 3, to every digit of the closed form."""
    from symtmm.modelfile import load
    from symtmm.roots.undamped import solve_undamped

    spectrum = solve_undamped(load(examples_dir / "paper_ex3_three_pp_coupled.toml"),
                              count=15, digits=30, certified=certified)
    from symtmm.results import decimal_string

    [triple] = [e for e in spectrum if e.multiplicity == 3]
    with mpmath.workdps(50):
        exact = (4 * mpmath.pi) ** 2
    assert decimal_string(triple.omega, 30) == decimal_string(exact, 30)


def test_a_root_beside_a_crowd_of_another_beams_roots():
    """Two uncoupled beams (a campaign's model; its spring acts at a clamped end): a
    pinned-clamped beam and a soft pinned-pinned beam on a stiff foundation, whose modes
    crowd within 0.5 rad/s above its first, 1989.45. The refinement of that first one
    took the end of its bracket for it (Delta there 1e-46 of the other end's) and did
    not converge. References, at 25 digits: the pinned-clamped root tan x = tanh x, and
    omega**2 = (kw + EI (pi/L)**4) / m of the beam on its foundation."""
    model = Model((Beam("b0", 26, 374, "0.0793", left="pinned", right="clamped"),
                   Beam("b1", "0.0153", "0.0019", "3.95", left="pinned", right="pinned",
                        kw=7520)),
                  (Spring("b0", "ground", "0.0793", "0.0297"),))
    spectrum = solve(model, count=2, digits=25)
    with mpmath.workdps(40):
        x = mpmath.findroot(lambda x: mpmath.tan(x) - mpmath.tanh(x), 3.9266)
        clamped = x ** 2 * mpmath.sqrt(mpmath.mpf(26) / (374 * mpmath.mpf("0.0793") ** 4))
        foundation = mpmath.sqrt((7520 + mpmath.mpf("0.0153") * (mpmath.pi / mpmath.mpf("3.95"))
                                  ** 4) / mpmath.mpf("0.0019"))
        for e, ref in zip(spectrum, (clamped, foundation)):
            assert abs(mpmath.mpf(e.to_dict()["imag"]) - ref) < mpmath.mpf(10) ** -24 * ref
