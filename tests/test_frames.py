"""Planar frames: ``[[member]]``, ``[[node]]``, joints of the plane, inextensible members.

References, none of them from symtmm:

* two equal inextensible members at a right angle, clamped at their far ends: the
  corner cannot translate. Pinned there, each member is a clamped-pinned beam,
  ``tan(bL) = tanh(bL)``, every root a double eigenvalue; rigid there, mirror symmetry
  about the corner's bisector splits the modes into symmetric ones (the corner does not
  turn: clamped-clamped, ``cos(bL) cosh(bL) = 1``) and antisymmetric ones (the corner's
  moments cancel: clamped-pinned); roots by ``mpmath.findroot`` on those equations;
* a frame free in the plane has exactly three rigid-body modes (two translations and a
  rotation), extensible or not;
* a second formulation: ``derive`` (the transfer walk, in closed form) and the generated
  code vanish at the roots ``solve`` finds with the dynamic stiffness and its count.

The finite-element comparisons (portal and L-frames, hinges, node masses, crosses)
are in tests/test_frames_fe.py.
"""

from __future__ import annotations

import importlib.util
import json
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp
from cli_contract import assert_contract, run_cli

from symtmm import api
from symtmm.errors import ModelError
from symtmm.frame import Member, Node, frame, frame_parts
from symtmm.mesh import static_nullity
from symtmm.model import Attachment, Beam, Link, Model, RigidBody, Spring
from symtmm.modelfile import loads


def _roots(f, guesses, dps=40):
    with mpmath.workdps(dps):
        return [mpmath.findroot(f, mpmath.mpf(g)) for g in guesses]


def _clamped_pinned(count):
    """``b L`` of a clamped-pinned beam: ``tan x = tanh x``, roots near ``(4n + 1) pi / 4``."""
    return _roots(lambda x: mpmath.sin(x) * mpmath.cosh(x) - mpmath.cos(x) * mpmath.sinh(x),
                  [(4 * n + 1) * np.pi / 4 for n in range(1, count + 1)])


def _clamped_clamped(count):
    """``b L`` of a clamped-clamped beam: ``cos x cosh x = 1``, roots near ``(2n + 1) pi / 2``."""
    return _roots(lambda x: mpmath.cos(x) * mpmath.cosh(x) - 1,
                  [(2 * n + 1) * np.pi / 2 for n in range(1, count + 1)])


def _omegas(result):
    out = []
    for e in result.eigenvalues:
        out += [mpmath.mpf(e.omega)] * e.multiplicity
    return out


L_FRAME = "examples/l_frame_inextensible.toml"


def test_inextensible_l_frame_with_a_pinned_corner_is_two_clamped_pinned_beams():
    model = api.load(L_FRAME)
    result = api.solve(model, count=8, digits=25)
    # EI = m = L = 1: omega = (b L)**2
    ref = [x**2 for x in _clamped_pinned(4) for _ in range(2)]
    got = _omegas(result)
    assert [e.multiplicity for e in result.eigenvalues] == [2, 2, 2, 2]
    for g, r in zip(got, ref):
        assert abs(g - r) < mpmath.mpf(10) ** -22 * r


def test_inextensible_l_frame_with_a_rigid_corner_splits_by_symmetry():
    text = Path(L_FRAME).read_text().replace("hinge = true", "hinge = false")
    result = api.solve(loads(text), count=6, digits=20)
    ref = sorted([x**2 for x in _clamped_pinned(3)] + [x**2 for x in _clamped_clamped(3)])
    got = _omegas(result)
    assert [e.multiplicity for e in result.eigenvalues] == [1] * 6
    for g, r in zip(got, ref):
        assert abs(g - r) < mpmath.mpf(10) ** -17 * r


@pytest.mark.parametrize("EA", [100, None])
def test_a_free_frame_has_three_rigid_body_modes(EA):
    members = [Member("a", (0, 0), (0, 1), EI=1, EA=EA, m=1),
               Member("b", (0, 1), (2, 1), EI=1, EA=EA, m=1),
               Member("c", (2, 1), ("2 + sqrt(3)/2", "3/2"), EI=2, EA=EA, m=1)]
    model = frame(members)
    assert static_nullity(model) == 3
    result = api.solve(model, count=5)
    assert result.eigenvalues[0].multiplicity == 3
    assert float(result.eigenvalues[0].omega) == 0.0
    assert float(result.eigenvalues[1].omega) > 0.1


def test_a_hinged_free_frame_adds_the_mechanism_of_its_hinge():
    """Two members pinned to each other and free otherwise: three rigid motions and the
    relative rotation about the pin."""
    members = [Member("a", (0, 0), (1, 0), EI=1, EA=10, m=1),
               Member("b", (1, 0), (1, 1), EI=1, EA=10, m=1)]
    assert static_nullity(frame(members, [Node((1, 0), hinge=True)])) == 4
    assert static_nullity(frame(members)) == 3


def test_a_frame_turned_in_its_plane_keeps_its_spectrum():
    """The portal frame and the same frame turned by 30 degrees (exact coordinates)."""
    def portal(turn):
        c, s = turn

        def p(x, y):
            return (sp.nsimplify(c * x - s * y), sp.nsimplify(s * x + c * y))
        members = [Member("l", p(0, 0), p(0, 4), EI=1, EA=200, m=1),
                   Member("b", p(0, 4), p(6, 4), EI=2, EA=200, m=1),
                   Member("r", p(6, 4), p(6, 0), EI=1, EA=200, m=1)]
        return frame(members, [Node(p(0, 0), "clamped"), Node(p(6, 0), "pinned")])
    straight = _omegas(api.solve(portal((1, 0)), count=6, digits=20))
    turned = _omegas(api.solve(portal((sp.sqrt(3) / 2, sp.Rational(1, 2))), count=6, digits=20))
    for a, b in zip(straight, turned):
        assert abs(a - b) < mpmath.mpf(10) ** -18 * a


def test_derive_and_generated_code_vanish_at_the_roots_of_solve(tmp_path):
    """The closed form of the transfer walk, and the generated Python, against the
    dynamic stiffness: each changes sign across every simple root solve finds."""
    text = Path("examples/portal_frame.toml").read_text()
    model = loads(text, source="portal")
    roots = [float(e.omega) for e in api.solve(model, count=4).eigenvalues]
    eq = api.derive(model)
    out = json.loads(eq.to_json())
    w = sp.Symbol("omega", positive=True)
    delta = sp.lambdify(w, sp.sympify(out["delta"], locals={"omega": w}), "mpmath")
    path = tmp_path / "portal_delta.py"
    path.write_text(api.codegen(model, "python"))
    spec = importlib.util.spec_from_file_location("portal_delta", path)
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    with mpmath.workdps(40):
        for r in roots:
            lo, hi = mpmath.mpf(r) * (1 - mpmath.mpf("1e-9")), mpmath.mpf(r) * (1 + mpmath.mpf("1e-9"))
            assert mpmath.sign(delta(lo)) != mpmath.sign(delta(hi)), r
            a, b = gen.symtmm_delta(1j * float(lo)), gen.symtmm_delta(1j * float(hi))
            assert np.sign(a.real) != np.sign(b.real), r


def test_a_damped_frame_agrees_with_its_generated_characteristic_function(tmp_path):
    """A dashpot under the portal's beam: the complex eigenvalues of solve are zeros of
    the generated Delta (the transfer walk), refined there by mpmath.findroot."""
    text = Path("examples/portal_frame.toml").read_text() + (
        '[[spring]]\nbetween = ["beam", "ground"]\nx = 2\nk = 0\nc = 2000\n')
    model = loads(text, source="damped portal")
    result = api.solve(model, count=4)
    path = tmp_path / "damped_delta.py"
    path.write_text(api.codegen(model, "python"))
    spec = importlib.util.spec_from_file_location("damped_delta", path)
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    damped = [complex(e.lam) for e in result.eigenvalues if complex(e.lam).real < 0]
    assert damped
    for lam in damped:
        # Delta is large; a zero of it is where it changes little relative to its scale
        root = complex(mpmath.findroot(lambda z: gen.symtmm_delta(complex(z)), lam,
                                       tol=1e-20))
        assert abs(root - lam) < 1e-9 * abs(lam), (root, lam)


def test_model_file_and_python_api_build_the_same_frame():
    text = """
[[member]]
name = "a"
from = [0, 0]
angle = 90
L = 2
EI = 3
EA = 50
m = 1
[[member]]
name = "b"
from = [0, 2]
to = [1, 2]
EI = 3
EA = 50
m = 1
[[node]]
at = [0, 0]
support = "clamped"
[[node]]
at = [0, 2]
M = 0.5
"""
    from_file = loads(text)
    by_hand = frame([Member("a", (0, 0), (0, 2), 3, 50, 1), Member("b", (0, 2), (1, 2), 3, 50, 1)],
                    [Node((0, 0), "clamped"), Node((0, 2), M=sp.Rational(1, 2))])
    assert from_file.beams == by_hand.beams
    assert [b.attachments for b in from_file.bodies] == [b.attachments for b in by_hand.bodies]
    assert [b.name for b in from_file.beams] == ["a", "a_axial", "b", "b_axial"]


def test_joints_of_the_plane_have_the_freedoms_their_members_need():
    levels, bodies, links = frame_parts(
        [Member("c", (0, 0), (0, 1), 1, 10, 1), Member("g", (0, 1), (1, 1), 1, None, 1)],
        [Node((0, 0), "pinned"), Node((0, 1), hinge=True)])
    model = Model(levels, bodies=bodies, links=links)
    corner = model.body_frame(bodies[0])
    # a hinge: no rotation of its own; the column's deflection (normal (-1, 0)) is -X,
    # its axial motion Y; the girder's deflection Y; the girder's link pulls along X
    assert corner.freedoms == ("Y", "X")
    assert [row for row in corner.rows] == [{"X": -1}, {"Y": 1}, {"Y": 1}]
    assert links == (Link("g_axial", bodies[0].name, None, (1, 0), M=1),)
    # a pinned support of one member end is that end's condition
    assert levels[0].left == "pinned" and levels[1].end("left") == "fixed"


def test_a_support_at_a_joint_holds_its_freedoms():
    """A clamped node where two members meet: the joint has no freedom left, and each
    member is clamped there (two cantilevers, the cantilever's frequencies twice)."""
    members = [Member("a", (0, 0), (1, 0), EI=1, EA=1e4, m=1),
               Member("b", (0, 0), (0, 1), EI=1, EA=1e4, m=1)]
    model = frame(members, [Node((0, 0), "clamped")])
    assert model.body_frame(model.bodies[0]).freedoms == ()
    result = api.solve(model, count=4, digits=20)
    ref = _roots(lambda x: mpmath.cos(x) * mpmath.cosh(x) + 1, [1.9, 4.7])
    assert [e.multiplicity for e in result.eigenvalues] == [2, 2]
    for e, r in zip(result.eigenvalues, ref):
        assert abs(mpmath.mpf(e.omega) - r**2) < mpmath.mpf(10) ** -18 * r**2


MEMBER_C = '[[member]]\nname = "c"\nfrom = [0, 0]\nEI = 1\nm = 1\n'


@pytest.mark.parametrize("extra, field, message", [
    (MEMBER_C + 'to = [1, 1]\nangle = 45\nL = 1\nEA = 1\n', "member[3] (c).angle",
     "either to"),
    ('[[member]]\nname = "c"\nfrom = [0, 0]\nto = [1, 1]\nEI = 1\nm = 1\n', "member[3] (c).EA",
     "give EA"),
    (MEMBER_C + 'to = [1, 1]\nEA = 1\ninextensible = true\n', "member[3] (c).EA",
     "has no EA"),
    ('[[member]]\nname = "c"\nfrom = [0, 0]\nEI = 1\nEA = 1\nm = 1\n', "member[3] (c)",
     "missing field 'to'"),
    ('[[member]]\nname = "c"\nfrom = [1, 1]\nto = [1, 1]\nEI = 1\nEA = 1\nm = 1\n',
     "member[3] (c).to", "one point"),
    (MEMBER_C.replace("[0, 0]", '[0, "q"]') + 'to = [1, 1]\nEA = 1\n[parameters]\nq = "x"\n',
     "member[3] (c).from", "parameters with a value only"),
    ('[[node]]\nat = [5, 5]\n', "node", "no member end lies at (5, 5)"),
    ('[[node]]\nat = [0, 0]\nsupport = "rolling"\n', "node[2].support", "unknown support"),
    ('[[node]]\nat = [0, 0]\nsupport = "pinned"\n', "node", "two nodes at (0, 0)"),
    ('[[node]]\nat = [0, 1]\nsupport = "clamped"\nhinge = true\n', "support", "not a hinge"),
    ('[[spring]]\nbetween = ["a", "b"]\nx = 0.5\nk = 1\n', "between", "lies at an angle"),
    ('[[member]]\nname = "a"\nfrom = [0, 0]\nto = [1, 1]\nEI = 1\nEA = 1\nm = 1\n', "member",
     "duplicate member name"),
    ('[[node]]\nat = [0, 1]\nJ = 1\nhinge = true\n', "node[2].J", "nothing it holds turns"),
    (MEMBER_C.replace('"c"', '"a_axial"') + 'to = [2, 1]\nEA = 1\n', "member[3] (a_axial).name",
     "names the axial part of member 'a'"),
    (MEMBER_C + 'to = [0, "1e-40"]\nEA = 1\n', "member[3] (c).L", "between 1e-30 and 1e+30"),
    (MEMBER_C + 'to = [0, -1]\nEA = -1\n', "member[3] (c).EA", "must be positive"),
    (MEMBER_C.replace("EI = 1", "EI = 0") + 'to = [0, -1]\nEA = 1\n', "member[3] (c).EI",
     "must be positive"),
])
def test_bad_frames_get_one_line_errors(extra, field, message):
    base = ('[[member]]\nname = "a"\nfrom = [0, 0]\nto = [0, 1]\nEI = 1\nEA = 1\nm = 1\n'
            '[[member]]\nname = "b"\nfrom = [0, 1]\nto = [1, 1]\nEI = 1\nEA = 1\nm = 1\n'
            '[[node]]\nat = [0, 0]\nsupport = "clamped"\n')
    with pytest.raises(ModelError) as info:
        loads(base + extra)
    text = str(info.value)
    assert field in str(info.value.field or "") + text, text
    assert message in text, text
    assert "\n" not in text


def test_a_mass_at_a_clamped_node_is_held_with_it():
    """M and J at a clamped node of one member: the node is a joint held in every freedom,
    and the cantilever beside it is the clamped-free beam (closed form)."""
    text = ('[[member]]\nname = "a"\nfrom = [0, 0]\nto = [0, 1]\nEI = 1\nEA = 1e6\nm = 1\n'
            '[[node]]\nat = [0, 0]\nsupport = "clamped"\nM = 1\nJ = 1\n')
    model = loads(text)
    assert model.body_frame(model.bodies[0]).freedoms == ()
    first = float(api.solve(model, count=1).eigenvalues[0].omega)
    ref = float(_roots(lambda x: mpmath.cos(x) * mpmath.cosh(x) + 1, [1.9])[0]) ** 2
    assert abs(first - ref) < 1e-13 * ref


def test_a_body_on_a_member_at_an_angle_moves_it_along_its_normal():
    """A rigid body written by hand on a member at 90 degrees: the Python API's parts meet
    the same frame rules (a joint of the member's two levels with a mass)."""
    col = Beam("c", 1, 1, 1, left="clamped", axis=(0, 1))
    body = RigidBody("top", (Attachment("c", 1),), M=2)
    frame_ = Model((col,), bodies=(body,)).body_frame(body)
    assert frame_.freedoms == ("Y", "Theta")
    assert frame_.directions["Y"] == (-1, 0)           # the column's normal
    with pytest.raises(ModelError, match="lies at an angle"):
        Model((col, Beam("d", 1, 1, 1)), (Spring("c", "d", "1/2", 1),))


@pytest.mark.parametrize("ends", [((0, 0), (2, 0), "roller-x"), ((0, 0), (0, 2), "roller-y"),
                                  ((0, 2), (0, 0), "roller-y")])
def test_a_member_on_a_pin_and_a_roller(ends):
    """Pinned at one end, on a roller along the member at the other: pinned-pinned in
    bending, fixed-free along its axis, ``(2n - 1) pi/(2L) sqrt(EA/m)`` (closed forms)."""
    a, b, roller = ends
    model = frame([Member("b", a, b, EI=1, EA=10, m=1)], [Node(a, "pinned"), Node(b, roller)])
    got = [float(e.omega) for e in api.solve(model, omega_max=25).eigenvalues]
    bending = [(k * np.pi / 2) ** 2 for k in range(1, 4)]
    axial = [(2 * k - 1) * np.pi / 4 * np.sqrt(10) for k in range(1, 7)]
    np.testing.assert_allclose(got, sorted(w for w in bending + axial if w < 25), rtol=1e-13)


@pytest.mark.parametrize("example", ["examples/portal_frame.toml", L_FRAME])
@pytest.mark.parametrize("command", [
    ["solve", "--count", "4"],
    ["solve", "--count", "3", "--json"],
    ["solve", "--count", "3", "--certified", "--digits", "25"],
    ["modes", "--count", "2", "--points", "5", "--json"],
    ["sweep", "--param", "EA", "--from", "1e9", "--to", "2e9", "--steps", "2", "--count", "2"],
    ["scan", "--omega-max", "500", "--points", "30"],
    ["codegen", "--lang", "c"],
    ["derive", "--max-seconds", "120"],
])
def test_every_command_takes_the_frame_examples(command, example):
    if command[1] == "--param" and example == L_FRAME:
        command = ["sweep", "--param", "x", "--from", "1", "--to", "2", "--steps", "2",
                   "--count", "2"]
        example = _with_parameter(example)
    result = run_cli(command[:1] + [example] + command[1:])
    assert_contract(result)
    assert result.code == 0, result.stderr
    if command[0] == "modes":
        shapes = json.loads(result.stdout)
        bodies = shapes["modes"][0]["bodies"]
        assert set(next(iter(bodies.values()))) <= {"Y", "Theta", "X"}
        assert "X" in next(iter(bodies.values()))


def _with_parameter(example):
    """The inextensible L-frame with its girder's EI a parameter ``x`` (for a sweep)."""
    import tempfile
    text = Path(example).read_text().replace("EI = 1\nm = 1\ninextensible = true\n\n[[node]]",
                                             'EI = "x"\nm = 1\ninextensible = true\n\n[[node]]', 1)
    text = text.replace("[[member]]", "[parameters]\nx = 1\n\n[[member]]", 1)
    path = Path(tempfile.mkdtemp()) / "l_frame.toml"
    path.write_text(text)
    return str(path)


def test_the_drawing_of_a_frame_is_in_its_plane(tmp_path):
    model = api.load("examples/portal_frame.toml")
    mode = api.modes(model, count=1)[0]
    fig = api.draw_model(model, mode)
    ax = fig.axes[0]
    x0, x1 = ax.get_xlim()
    y0, y1 = ax.get_ylim()
    width, height = 6, 4        # the portal's span and height
    assert x0 < 0 and width < x1 and y0 < 0 and height < y1
    assert ax.get_aspect() in (1.0, "equal")


NODE_SPRING_BASE = ('[[member]]\nname = "a"\nfrom = [0, 0]\nto = [{x}, {y}]\nEI = 1\nEA = 20\n'
                    'm = 1\n[[node]]\nat = [0, 0]\nsupport = "clamped"\n')


def _lams(text, count=5):
    return [complex(e.lam) for e in api.solve(loads(text), count=count).eigenvalues]


def test_springs_at_a_node_are_the_members_springs_to_the_ground():
    """A clamped member along x whose far node is on springs (kx axial, ky and a dashpot
    transverse, ktheta) against [[spring]]s to the ground on its beam and rod levels."""
    base = NODE_SPRING_BASE.format(x=2, y=0)
    node = base + '[[node]]\nat = [2, 0]\nky = 3\nkx = 5\ncy = 0.5\nktheta = 2\n'
    levels = base + ('[[spring]]\nbetween = ["a", "ground"]\nx = 2\nk = 3\nc = 0.5\n'
                     '[[spring]]\nbetween = ["a_axial", "ground"]\nx = 2\nk = 5\n'
                     '[[spring]]\nbetween = ["a", "ground"]\nx = 2\nk = 2\nkind = "rotational"\n')
    np.testing.assert_allclose(_lams(node), _lams(levels), rtol=1e-13)


def test_node_springs_act_along_the_planes_axes():
    """kx on a vertical member is its transverse spring (the horizontal member's ky), and
    equal springs in x and y (isotropic) leave a member at 30 degrees as it is along x."""
    along_x = NODE_SPRING_BASE.format(x=2, y=0) + '[[node]]\nat = [2, 0]\nky = 3\ncy = 0.2\n'
    along_y = NODE_SPRING_BASE.format(x=0, y=2) + '[[node]]\nat = [0, 2]\nkx = 3\ncx = 0.2\n'
    np.testing.assert_allclose(_lams(along_y), _lams(along_x), rtol=1e-13)
    iso = '[[node]]\nat = [{x}, {y}]\nkx = 3\nky = 3\n'
    straight = NODE_SPRING_BASE.format(x=2, y=0) + iso.format(x=2, y=0)
    turned = (NODE_SPRING_BASE.format(x='"sqrt(3)"', y=1)
              + iso.format(x='"sqrt(3)"', y=1))
    np.testing.assert_allclose(_lams(turned), _lams(straight), rtol=1e-12)


def test_node_springs_in_the_transfer_walk(tmp_path):
    """The generated Delta (the transfer walk) vanishes at the damped eigenvalues solve
    finds with a node on a spring and dashpot at an angle."""
    text = (NODE_SPRING_BASE.format(x='"sqrt(3)"', y=1)
            + '[[node]]\nat = ["sqrt(3)", 1]\nkx = 4\ncx = 0.3\nky = 1\n')
    model = loads(text)
    path = tmp_path / "node_delta.py"
    path.write_text(api.codegen(model, "python"))
    spec = importlib.util.spec_from_file_location("node_delta", path)
    gen = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(gen)
    for lam in _lams(text, 4):
        root = complex(mpmath.findroot(lambda z: gen.symtmm_delta(complex(z)), lam, tol=1e-20))
        assert abs(root - lam) < 1e-9 * abs(lam), (root, lam)


def test_a_spring_on_a_held_freedom_is_refused():
    text = NODE_SPRING_BASE.format(x=2, y=0) + '[[node]]\nat = [2, 0]\nsupport = "pinned"\nkx = 1\n'
    with pytest.raises(ModelError, match="a support holds it") as info:
        loads(text)
    assert "node[2].kx" in str(info.value)


INCLINED = ('[[member]]\nname = "a"\nfrom = [0, 0]\nangle = 30\nL = 2\nEI = 1\nEA = 10\nm = 1\n'
            '[[node]]\nat = [0, 0]\nsupport = "pinned"\n'
            '[[node]]\nat = ["sqrt(3)", 1]\nsupport = "roller"\nangle = {angle}\n')


def test_inclined_rollers_against_closed_forms():
    """A member at 30 degrees, pinned at one end, on a roller inclined along it (pinned-
    pinned in bending, fixed-free axially) or across it (pinned-free in bending, with its
    rigid turn, ``tan x = tanh x``; fixed-fixed axially)."""
    along = [float(e.omega) for e in api.solve(loads(INCLINED.format(angle=30)),
                                               omega_max=25).eigenvalues]
    ref = [(k * np.pi / 2) ** 2 for k in range(1, 4)] + [
        (2 * k - 1) * np.pi / 4 * np.sqrt(10) for k in range(1, 7)]
    np.testing.assert_allclose(along, sorted(w for w in ref if w < 25), rtol=1e-13)
    across = [float(e.omega) for e in api.solve(loads(INCLINED.format(angle=120)),
                                                omega_max=20).eigenvalues]
    pinned_free = [float(x) ** 2 / 4 for x in _roots(
        lambda x: mpmath.sin(x) * mpmath.cosh(x) - mpmath.cos(x) * mpmath.sinh(x), [3.9, 7.07])]
    ref = [0.0] + pinned_free + [k * np.pi / 2 * np.sqrt(10) for k in range(1, 5)]
    np.testing.assert_allclose(across, sorted(w for w in ref if w < 20), rtol=1e-13, atol=1e-12)
    with pytest.raises(ModelError, match="give angle"):
        loads(INCLINED.format(angle=30).replace("angle = 30\n", "", 2).replace(
            'from = [0, 0]\n', 'from = [0, 0]\nangle = 30\n', 1))


def test_collinear_inextensible_members_are_refused_with_the_remedy(tmp_path):
    """Two collinear inextensible members between two pinned supports hold the middle
    joint along the line twice (their axial forces statically indeterminate, Delta zero
    for every lam): one line, exit 2, naming the remedy; with a finite EA on one of them
    the line is the pinned-pinned beam of length 2, ``omega = (n pi / 2)**2`` in bending."""
    text = ('[[member]]\nname = "a"\nfrom = [0, 0]\nto = [1, 0]\nEI = 1\nm = 1\n{a}\n'
            '[[member]]\nname = "b"\nfrom = [1, 0]\nto = [2, 0]\nEI = 1\nm = 1\n'
            'inextensible = true\n'
            '[[node]]\nat = [0, 0]\nsupport = "pinned"\n[[node]]\nat = [2, 0]\n'
            'support = "pinned"\n')
    path = tmp_path / "line.toml"
    path.write_text(text.format(a="inextensible = true"))
    run = run_cli(["solve", path, "--count", "3"])
    assert run.code == 2 and len(run.stderr.strip().splitlines()) == 1
    assert "give one of them EA" in run.stderr
    result = api.solve(loads(text.format(a="EA = 1e6")), count=3)
    got = [float(e.omega) for e in result for _ in range(e.multiplicity)]
    np.testing.assert_allclose(got, [(n * np.pi / 2) ** 2 for n in (1, 2, 3)], rtol=1e-12)
