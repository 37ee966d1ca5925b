"""Planar frames: the exact solver against closed forms and the finite-element model.

References, none taken from symtmm's output (tests/frame_reference.py):

* closed forms: two collinear members at 30 degrees, rigidly joined and clamped at their
  far ends, are one clamped-clamped beam of the total length in bending (``cos x cosh x
  = 1``) and one fixed-fixed rod axially (``n pi sqrt(EA/m) / L``); two inextensible
  members at a right angle pinned to each other at the corner and clamped at their far
  ends are two clamped-pinned beams (``tan x = tanh x``), the corner held by the members'
  lengths; an inextensible pair pinned together, one far end pinned, is a pinned-free beam
  carrying the other member's whole mass at its tip (the beams' FE model of
  :mod:`symtmm.fe` with a lumped mass) and a pinned-free beam;
* the finite-element model of planar frames of :mod:`symtmm.fe`
  (:func:`symtmm.fe.fe_frame_converged`: Hermite bending and cubic bar elements turned
  to the plane, nodes merged by coordinates, hinges as rotations per member end,
  inextensible members as exact constraints), Romberg-extrapolated over three nested
  meshes with its error estimate held below ``2e-9`` relative. It is itself checked on
  the closed forms above. symtmm must agree within ``1e-9`` relative plus twice that
  estimate (at most ``5e-9``): an L-frame, a fixed-base portal, a free L-frame (exactly
  three zero frequencies first), a portal with a hinged knee, an L-frame with node
  masses, a cross of four clamped arms (the doubles of its symmetry: symtmm's
  multiplicities against the FE pairs), inextensible L-frames with a rigid corner, a
  portal with an inextensible girder, a clamped column with an inextensible free arm, a
  free pair of members pinned together (four zero frequencies) and rigidly joined,
  extensible and inextensible, and single member ends on pinned, roller and sliding
  supports;
* a property: a frame turned by 30 degrees in its plane (exact coordinates) keeps its
  spectrum, in symtmm and in the FE model.
"""

from __future__ import annotations

import itertools

import numpy as np
import pytest
from frame_reference import (
    beam_omegas,
    clamped_clamped,
    clamped_pinned,
    fe_frame,
    fe_reference,
    omegas,
    rod_fixed_fixed,
    symtmm_frame,
    turned,
)

from symtmm import api
from symtmm.fe import fe_converged, fe_frame_converged, fe_frame_frequencies
from symtmm.frame import frame

# symtmm against the converged FE: |exact - fe| <= REL * fe + 2 * (the FE's error estimate)
REL = 1e-9
BOUND = 2e-9                     # the FE's error estimate, at most, relative


def solve(members, nodes, count):
    ms, ns = symtmm_frame(members, nodes)
    return api.solve(frame(ms, ns), count=count)


def assert_matches_fe(members, nodes, count, elements=16):
    """symtmm's first ``count`` frequencies against the converged FE; returns both."""
    result = solve(members, nodes, count)
    got = omegas(result)
    ref, err = fe_reference(members, nodes, count, elements, bound=BOUND)
    assert len(got) == count
    tol = REL * ref + 2 * err
    assert np.all(np.abs(got - ref) <= tol), ((got - ref) / np.where(ref > 0, ref, 1.0))
    return result, ref


CLAMPED = "clamped"
L_FRAME = [("col", (0, 0), (0, 3), 2, 300, 1), ("top", (0, 3), (4, 3), 1, 200, "3/2")]
PORTAL = [("left", (0, 0), (0, 4), 1, 400, 1), ("beam", (0, 4), (6, 4), 2, 400, 1),
          ("right", (6, 4), (6, 0), 1, 400, 1)]


# -- closed forms ---------------------------------------------------------------------------


def test_collinear_members_at_30_degrees_are_one_clamped_beam_and_one_rod():
    """Axis (sqrt(3)/2, 1/2), lengths 3/2 and 5/2 joined rigidly: bending of one
    clamped-clamped beam of length 4, axial motion of one fixed-fixed rod."""
    EI, EA, m, total = 2, 50, "13/10", 4.0
    joint, far = ("3*sqrt(3)/4", "3/4"), ("2*sqrt(3)", "2")
    members = [("a", (0, 0), joint, EI, EA, m), ("b", joint, far, EI, EA, m)]
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=far, support=CLAMPED)]
    ref = np.sort(beam_omegas(clamped_clamped(8), EI, 1.3, total)
                  + rod_fixed_fixed(8, EA, 1.3, total))[:8]
    got = omegas(solve(members, nodes, 8))
    assert np.all(np.abs(got / ref - 1) < 1e-12), got / ref - 1
    # the FE model on the same closed forms (its estimate honest)
    fe, err = fe_reference(members, nodes, 8, 16, bound=BOUND)
    assert np.all(np.abs(fe - ref) <= err + 1e-12 * ref), (fe / ref - 1, err / ref)


def test_inextensible_l_frame_with_a_hinged_corner_is_two_clamped_pinned_beams():
    """Unequal inextensible members (column EI = 1, L = 1; girder EI = 2, L = 3/2) clamped
    at their far ends, pinned together: the corner cannot move, each member vibrates as a
    clamped-pinned beam of its own."""
    members = [("col", (0, 0), (0, 1), 1, None, 1), ("gir", (0, 1), ("3/2", 1), 2, None, 1)]
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=("3/2", 1), support=CLAMPED),
             dict(at=(0, 1), hinge=True)]
    roots = clamped_pinned(6)
    ref = np.sort(beam_omegas(roots, 1, 1, 1) + beam_omegas(roots, 2, 1, 1.5))[:6]
    got = omegas(solve(members, nodes, 6))
    assert np.all(np.abs(got / ref - 1) < 1e-12), got / ref - 1
    fe, err = fe_reference(members, nodes, 6, 16, bound=BOUND)
    assert np.all(np.abs(fe - ref) <= err + 1e-12 * ref), (fe / ref - 1, err / ref)


# -- against the finite-element model ---------------------------------------------------------


def test_l_frame_clamped_column_pinned_beam_against_fe():
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(4, 3), support="pinned")]
    assert_matches_fe(L_FRAME, nodes, 6)


def test_fixed_base_portal_frame_against_fe():
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(6, 0), support=CLAMPED)]
    assert_matches_fe(PORTAL, nodes, 6)


def test_free_l_frame_has_three_zero_modes_then_the_fe_frequencies():
    result, ref = assert_matches_fe(L_FRAME, [], 8, elements=32)
    assert result.eigenvalues[0].multiplicity == 3
    assert float(result.eigenvalues[0].omega) == 0.0
    assert np.all(ref[:3] == 0.0) and ref[3] > 0.1


def test_portal_with_a_hinged_knee_against_fe():
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(6, 0), support="pinned"),
             dict(at=(6, 4), hinge=True)]
    assert_matches_fe(PORTAL, nodes, 6)


def test_l_frame_with_node_masses_against_fe():
    """A mass and a rotary inertia at the corner, a mass at the pinned end (which moves
    nothing: the support holds it) and a tip mass on a free third member."""
    members = L_FRAME + [("arm", (4, 3), (5, 5), 1, 100, 1)]
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(0, 3), M="5/2", J="3/4"),
             dict(at=(4, 3), support="pinned", M=2), dict(at=(5, 5), M="1/2", J="1/10")]
    assert_matches_fe(members, nodes, 6)


def test_cross_of_four_clamped_arms_has_the_double_eigenvalues_of_its_symmetry():
    """Four equal arms from a rigid centre, clamped at their outer ends: the square's
    symmetry makes some frequencies double; which ones the FE model tells (its mesh keeps
    the symmetry, its pairs agree to rounding), symtmm must report them as ``mult. 2``."""
    arms = [("e", (1, 0)), ("n", (0, 1)), ("w", (-1, 0)), ("s", (0, -1))]
    members = [(name, (0, 0), p, 1, 100, 1) for name, p in arms]
    nodes = [dict(at=p, support=CLAMPED) for _, p in arms]
    fe_members, fe_nodes = fe_frame(members, nodes)
    # the FE's groups of equal frequencies (a mesh of the cross keeps its symmetry exactly)
    raw = fe_frame_frequencies(fe_members, fe_nodes, 8, count=12)
    groups = [1]
    for a, b in itertools.pairwise(raw):
        if abs(b - a) <= 1e-10 * b:
            groups[-1] += 1
        else:
            groups.append(1)
    assert set(groups) == {1, 2}, groups
    count, sizes = 0, []
    for g in groups:
        if count + g > 10:
            break
        count += g
        sizes.append(g)
    result, _ = assert_matches_fe(members, nodes, count, elements=8)
    assert [e.multiplicity for e in result.eigenvalues] == sizes


def test_inextensible_l_frame_with_a_rigid_corner_against_fe():
    """Unequal inextensible members clamped at their far ends, rigidly joined: the corner
    cannot translate, only turn, against the FE model with the members' exact axial
    constraints; which is also the FE model of two beams joined rigidly over a pin."""
    members = [("col", (0, 0), (0, 1), 1, None, 1), ("gir", (0, 1), ("3/2", 1), 2, None, 1)]
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=("3/2", 1), support=CLAMPED)]
    _, ref = assert_matches_fe(members, nodes, 6, elements=32)
    # the same as two beams joined rigidly over a pin (the beams' FE model of symtmm.fe)
    beams = [dict(name="col", EI=1.0, m=1.0, L=1.0, x0=0.0, left=CLAMPED, right="pinned"),
             dict(name="gir", EI=2.0, m=1.0, L=1.5, x0=1.0, left="pinned", right=CLAMPED)]
    joint = {"attach": [{"beam": "col", "x": 1.0}, {"beam": "gir", "x": 1.0}]}
    out = fe_converged(beams, [], 16, 6, bodies=[joint])
    assert np.all(np.abs(out["omega"] - ref) <= 2 * out["error"] + 1e-9 * ref)


def test_inextensible_girder_in_a_portal_against_fe():
    """The girder of the portal inextensible, the columns extensible, one base pinned."""
    members = [m if m[0] != "beam" else _inextensible([m])[0] for m in PORTAL]
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(6, 0), support="pinned")]
    assert_matches_fe(members, nodes, 6)


def test_inextensible_free_arm_on_a_clamped_column_against_fe():
    """An inextensible arm sticking out from the top of a clamped column, its far end
    free: its axial mass moves with the column's top."""
    members = [("col", (0, 0), (0, 2), 1, 150, 1), ("arm", (0, 2), (1, 3), "1/2", None, 2)]
    nodes = [dict(at=(0, 0), support=CLAMPED)]
    assert_matches_fe(members, nodes, 6)


# -- a property -----------------------------------------------------------------------------


def test_a_frame_turned_by_30_degrees_keeps_its_spectrum():
    """An L-frame with an arm, a hinge, node masses and a pinned support, as given and
    turned by 30 degrees about the origin (exact coordinates): the same frequencies, in
    symtmm and in the FE model."""
    members = L_FRAME + [("arm", (4, 3), (5, 5), 1, 100, 1)]
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(0, 3), M="5/2", J="3/4"),
             dict(at=(4, 3), hinge=True), dict(at=(5, 5), support="pinned")]
    cos, sin = "sqrt(3)/2", "1/2"
    members_t = [(n, turned(a, cos, sin), turned(b, cos, sin), EI, EA, m)
                 for n, a, b, EI, EA, m in members]
    nodes_t = [dict(node, at=turned(node["at"], cos, sin)) for node in nodes]
    straight = omegas(solve(members, nodes, 6))
    rotated = omegas(solve(members_t, nodes_t, 6))
    assert np.all(np.abs(rotated - straight) <= 1e-12 * straight), rotated / straight - 1
    fe = [fe_frame_frequencies(*fe_frame(ms, ns), 8, count=6)
          for ms, ns in ((members, nodes), (members_t, nodes_t))]
    assert np.all(np.abs(fe[1] - fe[0]) <= 1e-10 * fe[0])
    # and the FE model of the turned frame is near symtmm's (a coarse mesh: upper bounds)
    assert np.all(fe[1] >= straight * (1 - 1e-12)) and np.all(fe[1] <= straight * (1 + 1e-3))


@pytest.mark.parametrize("support", ["pinned", "roller-x"])
def test_supports_of_a_single_member_end_against_fe(support):
    """A support at the far end of the L-frame's beam, alone there: a pinned end and a
    roller along x (holds y only)."""
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(4, 3), support=support)]
    assert_matches_fe(L_FRAME, nodes, 6)


HINGED_PAIR = [("a", (0, 0), (2, 0), 1, 200, 1), ("b", (2, 0), (2, 3), 2, 200, "1/2")]


def test_free_frame_with_a_hinge_has_four_zero_modes_then_the_fe_frequencies():
    """Two members pinned to each other, free otherwise: the three rigid motions and the
    turning about the pin, then elastic modes."""
    result, ref = assert_matches_fe(HINGED_PAIR, [dict(at=(2, 0), hinge=True)], 8,
                                    elements=32)
    assert result.eigenvalues[0].multiplicity == 4
    assert np.all(ref[:4] == 0.0) and ref[4] > 0.1


def _inextensible(members):
    return [m[:4] + (None, m[5]) for m in members]


def test_inextensible_free_frame_with_a_hinge_has_four_zero_modes_then_the_fe_frequencies():
    """The same pair inextensible: each member's axial mass moves with the pin (``a``'s
    along x, ``b``'s along y)."""
    result, ref = assert_matches_fe(_inextensible(HINGED_PAIR), [dict(at=(2, 0), hinge=True)],
                                    8, elements=32)
    assert result.eigenvalues[0].multiplicity == 4
    assert np.all(ref[:4] == 0.0) and ref[4] > 0.1


def test_inextensible_free_l_frame_has_three_zero_modes_then_the_fe_frequencies():
    """The pair inextensible and rigidly joined, free in the plane."""
    result, ref = assert_matches_fe(_inextensible(HINGED_PAIR), [], 8, elements=32)
    assert result.eigenvalues[0].multiplicity == 3
    assert np.all(ref[:3] == 0.0) and ref[3] > 0.1


def test_inextensible_hinged_pair_pinned_at_one_end_carries_the_axial_mass():
    """The inextensible pair pinned together, ``a`` pinned at its far end: ``a``'s axial
    motion is held, so the pin moves only along y, where it carries all of ``b`` (mass
    ``3/2``, inextensible), and ``b`` turns freely about it; ``a`` is a pinned-free beam
    with a tip mass ``3/2`` (the beams' FE model of symtmm.fe, with a lumped mass) and
    ``b`` a pinned-free beam on a fixed pin (``tan x = tanh x``)."""
    members = _inextensible(HINGED_PAIR)
    nodes = [dict(at=(2, 0), hinge=True), dict(at=(0, 0), support="pinned")]
    beam = dict(name="a", EI=1.0, m=1.0, L=2.0, x0=0.0, left="pinned", right="free")
    out = fe_converged([beam], [], 16, 4, masses=[dict(beam="a", x=2.0, M=1.5)])
    b = beam_omegas([0.0] + clamped_pinned(3), 2, 0.5, 3)
    expected = np.sort(np.concatenate([out["omega"], b]))[:6]
    # the frame's FE model with its exact axial constraints on that decomposition
    ref, _ = fe_reference(members, nodes, 6, 32, bound=BOUND)
    assert np.all(np.abs(ref - expected) <= 2 * out["error"].max() + 1e-9 * expected)
    assert_matches_fe(members, nodes, 6, elements=32)


def test_sliding_support_against_fe():
    """The L-frame's beam end on a sliding support along x (held in y and in rotation)."""
    nodes = [dict(at=(0, 0), support=CLAMPED), dict(at=(4, 3), support="sliding-x")]
    assert_matches_fe(L_FRAME, nodes, 6)


@pytest.mark.parametrize("certified", [True, False], ids=["balls", "two-precisions"])
def test_double_cross_example_solves_as_its_header_says(certified, examples_dir):
    """``examples/double_cross_frame.toml`` (the layout of NAFEMS FV2: eight pinned arms
    at 45 degrees from a rigid centre) with ``--count 16``, as its header says, with and
    without balls. Closed forms: every arm pinned-pinned (the centre turning freely) at
    ``beta L = pi, 2 pi``, and the five-fold roots of arms clamped at a centre that
    neither turns nor moves (``tan x = tanh x``; eight arms less the centre's three
    freedoms); the two doubles (the centre translating, the arms along it stretching)
    against the converged FE. Five-fold roots this close to a double left the counts at
    the cluster's ends undecided at the proof's first precision without balls."""
    if certified:
        pytest.importorskip("flint")
    from symtmm.modelfile import load
    from symtmm.roots.undamped import solve_undamped

    model = load(examples_dir / "double_cross_frame.toml")
    result = solve_undamped(model, count=16, certified=certified)
    assert [e.multiplicity for e in result] == [1, 2, 5, 1, 2, 5]
    L, a, E, rho = 5.0, 0.125, 200e9, 8000.0
    EI, EA, m = E * a**4 / 12, E * a**2, rho * a**2
    cp = beam_omegas(clamped_pinned(2), EI, m, L)
    pp = beam_omegas([np.pi, 2 * np.pi], EI, m, L)
    got = [float(e.omega) for e in result]
    np.testing.assert_allclose([got[0], got[3]], pp, rtol=1e-13)
    np.testing.assert_allclose([got[2], got[5]], cp, rtol=1e-13)
    arms = [dict(name=f"arm{k}", start=(0.0, 0.0),
                 end=(L * np.cos(k * np.pi / 4), L * np.sin(k * np.pi / 4)), EI=EI, EA=EA, m=m)
            for k in range(8)]
    nodes = [dict(at=arm["end"], support="pinned") for arm in arms]
    out = fe_frame_converged(arms, nodes, 16, count=16)
    fe, error = out["omega"], out["error"]
    assert np.all(error <= BOUND * fe)
    for i, j in ((1, 1), (4, 9)):                 # the doubles: FE modes 2-3 and 10-11
        assert np.all(np.abs(got[i] - fe[j:j + 2]) <= REL * fe[j:j + 2] + 2 * error[j:j + 2])
