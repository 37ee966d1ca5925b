"""Mode shapes: closed forms, boundary conditions, jumps, orthogonality, FE eigenvectors."""

import itertools
import json
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
import scipy.linalg

from symtmm.cli import main
from symtmm.compile import Evaluator
from symtmm.fe import fe_matrices
from symtmm.model import BOUNDARY_CONDITIONS, Beam, Model, Spring
from symtmm.modelfile import load
from symtmm.modes import evaluate_mode, mode_shapes, shapes_at
from symtmm.results import Eigenvalue
from symtmm.solve import solve

STATE = ("Y", "Theta", "M", "Q")


@pytest.fixture
def examples_dir():
    """The model files of the paper's examples."""
    return Path(__file__).resolve().parent.parent / "examples"


def mixed_model():
    """Different beams, an offset beam, springs at beam ends and a grounded spring."""
    return Model(
        (Beam("a", EI=2, m=1, L=1, left="clamped", right="free"),
         Beam("b", EI=1, m="3/2", L="3/4", x0="1/4", left="sliding", right="pinned")),
        (Spring("a", "b", x="1/2", k=40),
         Spring("b", "ground", x="9/10", k=15),
         Spring("a", "ground", x=1, k=20),        # at the free end of a
         Spring("a", "b", x="1/4", k=30)),        # at the left end of b
    )


def gauss_gram(model, modes):
    """Mass Gram matrix sum_beams int m Y_i Y_j dx by Gauss-Legendre on evaluate_mode.

    Independent of the closed-form integral the library normalises with.
    """
    t, w = np.polynomial.legendre.leggauss(40)
    G = np.zeros((len(modes), len(modes)))
    for beam in model.resolved().beams:
        cuts = sorted({float(beam.x0), float(beam.x1)}
                      | {float(s.x) for s in model.resolved().springs
                         if beam.name in (s.a, s.b)})
        for xa, xb in itertools.pairwise(cuts):
            x = (xa + xb) / 2 + (xb - xa) / 2 * t
            Ys = np.array([evaluate_mode(model, mode, beam.name, x)[0] for mode in modes])
            G += float(beam.m) * (xb - xa) / 2 * (Ys * w) @ Ys.T
    return G


# -- closed form -------------------------------------------------------------------------

def test_single_pinned_pinned_beam_is_a_sine():
    EI, m, L = 2.0, 3.0, 1.5
    model = Model((Beam("b", EI=2, m=3, L="3/2", left="pinned", right="pinned"),))
    modes = mode_shapes(model, count=4, points=33)
    assert len(modes) == 4
    for n, mode in enumerate(modes, 1):
        s = mode.beams["b"]
        k = n * math.pi / L
        amp = math.sqrt(2 / (m * L))
        expected = {"Y": amp * np.sin(k * s.x), "Theta": amp * k * np.cos(k * s.x),
                    "M": -EI * amp * k**2 * np.sin(k * s.x),
                    "Q": -EI * amp * k**3 * np.cos(k * s.x)}
        sign = np.sign(np.dot(s.Y, expected["Y"]))
        for var in STATE:
            scale = np.max(np.abs(expected[var]))
            assert np.max(np.abs(sign * s[var] - expected[var])) < 1e-12 * scale, (n, var)



@pytest.mark.parametrize("digits", [15, 40])
def test_a_beam_cut_by_other_beams_springs_keeps_its_sine(digits):
    # beam a is cut at the eight spring positions of b (and at a mass-free station of its
    # own end), but nothing acts on it: its energy is summed over runs of pieces, and its
    # shapes are still sqrt(2 / m L) sin(n pi x / L), mass-normalised
    EI, m, L = 2.0, 3.0, 1.5
    springs = tuple(Spring("b", "ground", x=f"{j}/{10}", k=50 + j) for j in range(1, 9))
    model = Model((Beam("a", EI=2, m=3, L="3/2", left="pinned", right="pinned"),
                   Beam("b", EI=1, m=1, L=1, left="clamped", right="free")), springs)
    frequencies = [n**2 * math.pi**2 / L**2 * math.sqrt(EI / m) for n in range(1, 7)]
    found = 0
    for mode in mode_shapes(model, count=8, points=33, digits=digits):
        omega = float(mode.eigenvalue.lam.imag)
        n = [j for j, f in enumerate(frequencies, 1) if abs(omega / f - 1) < 1e-12]
        if not n:
            assert np.max(np.abs(mode.beams["a"].Y)) < 1e-12        # a mode of b alone
            continue
        found += 1
        s, k = mode.beams["a"], n[0] * math.pi / L
        expected = math.sqrt(2 / (m * L)) * np.sin(k * s.x)
        sign = np.sign(np.dot(s.Y, expected))
        assert np.max(np.abs(sign * s.Y - expected)) < 1e-12 * np.max(np.abs(expected)), n
        assert np.max(np.abs(mode.beams["b"].Y)) < 1e-12
    assert found == 5

def test_high_mode_keeps_its_accuracy_at_the_far_end():
    # beta L = 12 pi: the transfer product loses about 16 digits, the shape must not
    model = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    ev = Evaluator(model)
    assert ev.digits_lost(1j * (12 * math.pi) ** 2) > 15
    (shape,) = shapes_at(model, solve(model, count=12)[11], points=97)
    s = shape.beams["b"]
    expected = math.sqrt(2) * np.sin(12 * math.pi * s.x)
    sign = np.sign(np.dot(s.Y, expected))
    assert np.max(np.abs(sign * s.Y - expected)) < 1e-11


# -- boundary conditions and jumps ---------------------------------------------------------

MODELS = {
    "paper_ex1": lambda d: load(d / "paper_ex1_ff_cc.toml"),
    "paper_ex3": lambda d: load(d / "paper_ex3_three_pp_coupled.toml"),
    "mixed": lambda d: mixed_model(),
}


@pytest.fixture(scope="module")
def solved():
    cache = {}

    def get(name, examples_dir):
        if name not in cache:
            model = MODELS[name](examples_dir).require_numeric()
            cache[name] = (model, mode_shapes(model, count=6, points=41))
        return cache[name]
    return get


@pytest.mark.parametrize("name", MODELS)
def test_boundary_conditions_hold(name, solved, examples_dir):
    model, modes = solved(name, examples_dir)
    assert sum(1 for _ in modes) >= 6
    for mode in modes:
        for beam in model.beams:
            s = mode.beams[beam.name]
            assert s.x[0] == pytest.approx(float(beam.x0)) and \
                s.x[-1] == pytest.approx(float(beam.x1))
            for end, idx in ((beam.left, 0), (beam.right, -1)):
                for var in BOUNDARY_CONDITIONS[end]:
                    # the scale of the whole mode: a beam may stand still
                    scale = max(np.max(np.abs(t[var])) for t in mode.beams.values())
                    assert abs(s[var][idx]) < 1e-10 * scale, (mode.number, beam.name, end, var)


@pytest.mark.parametrize("name", MODELS)
def test_jumps_at_springs(name, solved, examples_dir):
    model, modes = solved(name, examples_dir)
    for mode in list(modes)[:4]:
        for beam in model.beams:
            for x in sorted({s.x for s in model.springs if beam.name in (s.a, s.b)}):
                before = evaluate_mode(model, mode, beam.name, [x], side="-")[:, 0]
                after = evaluate_mode(model, mode, beam.name, [x], side="+")[:, 0]
                expected = 0.0
                for s in model.springs:
                    if s.x != x or beam.name not in (s.a, s.b):
                        continue
                    ya = evaluate_mode(model, mode, s.a, [x])[0, 0]
                    yb = 0.0 if s.grounded else evaluate_mode(model, mode, s.b, [x])[0, 0]
                    force = float(s.k) * (yb - ya)          # on beam a
                    expected += force if beam.name == s.a else -force
                scale = max(np.max(np.abs(t.Q)) for t in mode.beams.values())
                assert after[3] - before[3] == pytest.approx(expected, abs=1e-10 * scale)
                # Y, Theta and M are continuous across a spring
                for v in range(3):
                    assert after[v] == pytest.approx(before[v], abs=1e-12 * (1 + abs(before[v])))


@pytest.mark.parametrize("name", MODELS)
def test_mass_orthonormal(name, solved, examples_dir):
    model, modes = solved(name, examples_dir)
    G = gauss_gram(model, list(modes))
    assert np.max(np.abs(G - np.eye(len(modes)))) < 1e-12


# -- multiple and rigid-body eigenvalues ------------------------------------------------------

def test_multiple_eigenvalue_gives_independent_orthonormal_shapes(examples_dir):
    model = load(examples_dir / "paper_ex2_three_pp.toml")
    modes = mode_shapes(model, count=6, points=21, digits=12)
    assert [m.eigenvalue.multiplicity for m in modes] == [3] * 6
    G = gauss_gram(model, list(modes))
    assert np.max(np.abs(G - np.eye(6))) < 1e-9
    for mode in modes:
        n = 1 if mode.number <= 3 else 2
        for s in mode.beams.values():
            # on every beam a multiple of sqrt(2) sin(n pi x)
            basis = math.sqrt(2) * np.sin(n * math.pi * s.x)
            c = np.dot(s.Y, basis) / np.dot(basis, basis)
            assert np.max(np.abs(s.Y - c * basis)) < 1e-10


def test_rigid_body_modes():
    ff = Model((Beam("b", EI=1, m=2, L=1, left="free", right="free"),))
    modes = mode_shapes(ff, count=3, points=11)
    assert modes[0].eigenvalue.multiplicity == 2 and modes[0].lam == 0
    for mode in list(modes)[:2]:
        s = mode.beams["b"]
        assert np.max(np.abs(s.M)) < 1e-12 and np.max(np.abs(s.Q)) < 1e-12
        assert np.max(np.abs(np.diff(s.Theta))) < 1e-12          # straight lines
    assert np.max(np.abs(gauss_gram(ff, list(modes)) - np.eye(3))) < 1e-10


# -- finite elements ---------------------------------------------------------------------------

def test_agrees_with_finite_element_eigenvectors(examples_dir):
    model = load(examples_dir / "paper_ex1_ff_cc.toml").require_numeric()
    beams = [{"name": b.name, "EI": float(b.EI), "m": float(b.m), "L": float(b.L),
              "x0": float(b.x0), "left": b.left, "right": b.right} for b in model.beams]
    springs = [{"between": [s.a, s.b], "x": float(s.x), "k": float(s.k)} for s in model.springs]
    K, M, info = fe_matrices(beams, springs, 80)
    w2, vecs = scipy.linalg.eigh(K, M, subset_by_index=(0, 5))   # v^T M v = 1
    modes = mode_shapes(model, count=6, points=5)
    for j, mode in enumerate(modes):
        assert mode.omega == pytest.approx(math.sqrt(w2[j]), rel=1e-6)
        fe, exact = [], []
        for b in beams:
            nodes, dofs = info["nodes"][b["name"]], info["dofs"][b["name"]][:, 0]
            fe.append(np.where(dofs >= 0, vecs[np.maximum(dofs, 0), j], 0.0))
            exact.append(evaluate_mode(model, mode, b["name"], np.asarray(nodes))[0])
        fe, exact = np.concatenate(fe), np.concatenate(exact)
        fe *= np.sign(np.dot(fe, exact))
        # 80 cubic elements per beam: the eigenvectors agree to about 1e-7
        assert np.max(np.abs(fe - exact)) < 1e-6 * np.max(np.abs(exact)), mode.number


def test_a_beam_over_many_equal_spans_has_its_closed_form_first_shape():
    # a beam over 12 equal pinned spans, one beam per span joined end to end (its R,
    # 90 x 90 and nearly empty, is factored sparsely where python-flint is installed):
    # the first mode is each span's own, sin(pi (x - x0)), of alternating sign, at the
    # single span's frequency pi**2; mass-normalised over the 12 spans, amplitude
    # sqrt(2 / 12)
    from symtmm.model import Attachment, RigidBody
    spans = 12
    beams = tuple(Beam(f"s{i + 1}", EI=1, m=1, L=1, x0=i,
                       left="pinned" if i == 0 else "free", right="pinned")
                  for i in range(spans))
    joints = tuple(RigidBody(f"pin{i}", (Attachment(f"s{i}", i), Attachment(f"s{i + 1}", i)))
                   for i in range(1, spans))
    (mode,) = mode_shapes(Model(beams, bodies=joints), count=1, points=17)
    assert mode.omega == pytest.approx(math.pi ** 2, rel=1e-14)
    amplitude = math.sqrt(2 / spans)
    signs = []
    for i, b in enumerate(mode.beams.values()):
        expected = amplitude * np.sin(math.pi * (b.x - i))
        sign = np.sign(np.dot(b.Y, expected))
        signs.append(sign)
        assert np.max(np.abs(sign * b.Y - expected)) < 1e-12
    assert all(a == -b for a, b in itertools.pairwise(signs))


# -- damped ---------------------------------------------------------------------------------------

def test_a_damped_model_s_triple_root_has_one_shape_per_beam(examples_dir):
    # example 4's beams are equal and pinned-pinned, its springs and dashpots at x = 1/4
    # and 3/4: sin(4 pi x) has nodes there, so omega = 16 omega_1 (omega_1 = 146.2698,
    # exactly by the example's EI) is a triple root, one beam moving alone in each shape
    model = load(examples_dir / "paper_ex4_damped.toml")
    with mpmath.workdps(40):
        lam = mpmath.mpc(0, 16 * mpmath.mpf("146.2698"))
    shapes = shapes_at(model, Eigenvalue(lam, 3, 15), points=33)
    moved = []
    for shape in shapes:
        sizes = {name: np.max(np.abs(b.Y)) for name, b in shape.beams.items()}
        name = max(sizes, key=sizes.get)
        moved.append(name)
        assert sizes[name] == pytest.approx(1.0)
        assert all(v < 1e-12 for n, v in sizes.items() if n != name), sizes
        b = shape.beams[name]
        expected = np.sin(4 * math.pi * b.x)
        Y = b.Y / b.Y[np.argmax(np.abs(expected))]                 # phase and scale
        assert np.max(np.abs(Y - expected)) < 1e-12
    assert sorted(moved) == ["b1", "b2", "b3"]


def test_equal_damped_beams_shapes_are_the_same_shape_on_each_beam():
    # three equal uncoupled pinned-free beams, each with the same dashpot: every damped
    # eigenvalue is triple, and its shapes are one beam's, one per beam (a decoupled
    # family: the same samples on each)
    beams = tuple(Beam(n, EI=1, m=1, L=1, left="pinned", right="free") for n in "abc")
    springs = tuple(Spring(n, "ground", x="3/5", k=4, c=2) for n in "abc")
    modes = mode_shapes(Model(beams, springs), omega_max=30, points=21)
    triple = [m for m in modes if m.eigenvalue.multiplicity == 3]
    assert len(triple) >= 6
    for start in range(0, len(triple), 3):
        group = triple[start:start + 3]
        on = []
        for shape in group:
            sizes = {n: np.max(np.abs(b.Y)) for n, b in shape.beams.items()}
            name = max(sizes, key=sizes.get)
            assert all(v < 1e-12 for n, v in sizes.items() if n != name), sizes
            on.append((name, shape.beams[name].Y))
        assert sorted(n for n, _ in on) == ["a", "b", "c"]
        for _, Y in on[1:]:
            assert np.max(np.abs(Y - on[0][1])) < 1e-12

def test_damped_shape_satisfies_boundary_conditions_and_jumps():
    k, c = 50, 2
    model = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),
                   Beam("b", 1, 1, 1, left="clamped", right="pinned")),
                  (Spring("a", "b", x="3/10", k=k, c=c),))
    undamped = solve(Model(model.beams, (Spring("a", "b", x="3/10", k=k),)), count=1, digits=10)
    ev = Evaluator(model)
    with mpmath.workdps(40):
        lam = mpmath.findroot(ev.delta_mp, mpmath.mpc(-0.5, float(undamped[0].omega)))
        assert lam.real < 0
        eig = Eigenvalue(mpmath.mpc(lam), 1, 25)
    (mode,) = shapes_at(model, eig, points=21)
    assert mode.damped
    assert max(np.max(np.abs(s.Y)) for s in mode.beams.values()) == pytest.approx(1.0)
    for beam in model.beams:
        s = mode.beams[beam.name]
        for end, idx in ((beam.left, 0), (beam.right, -1)):
            for var in BOUNDARY_CONDITIONS[end]:
                assert abs(s[var][idx]) < 1e-12 * (np.max(np.abs(s[var])) + 1)
    lam_c = complex(lam)
    ya = evaluate_mode(model, mode, "a", [0.3])[0, 0]
    yb = evaluate_mode(model, mode, "b", [0.3])[0, 0]
    jump = (evaluate_mode(model, mode, "a", [0.3], "+")[3, 0]
            - evaluate_mode(model, mode, "a", [0.3], "-")[3, 0])
    assert jump == pytest.approx((k + c * lam_c) * (yb - ya), rel=1e-10)


# -- command line -------------------------------------------------------------------------------

def test_cli_json_and_plot(examples_dir, tmp_path, capsys):
    png = tmp_path / "modes.png"
    code = main(["modes", str(examples_dir / "paper_ex1_ff_cc.toml"), "--count", "2",
                 "--points", "5", "--json", "--digits", "10", "--plot", str(png)])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert list(data)[-1] == "modes" and len(data["modes"]) == 2
    assert data["digits"] == 10
    mode = data["modes"][0]
    assert set(mode["eigenvalue"]) == {"real", "imag"}
    assert mode["eigenvalue"]["real"] == "0"
    assert float(mode["eigenvalue"]["imag"]) == pytest.approx(2.9769035948**2, rel=1e-9)
    assert list(mode["beams"]) == ["upper", "lower"]
    for beam in mode["beams"].values():
        assert set(beam) == {"x", "Y", "Theta", "M", "Q"}
        assert beam["x"] == [0.0, 0.25, 0.5, 0.75, 1.0]
        assert all(len(beam[v]) == 5 for v in STATE)
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_cli_bad_input(examples_dir, tmp_path, capsys):
    assert main(["modes", str(tmp_path / "missing.toml")]) == 2
    with pytest.raises(SystemExit) as exc:
        main(["modes", str(examples_dir / "paper_ex1_ff_cc.toml"), "--points", "1"])
    assert exc.value.code == 2
    err = capsys.readouterr().err
    assert "Traceback" not in err


# -- the basis of a multiple eigenvalue ------------------------------------------------------


def test_shapes_of_a_triple_root_each_move_one_beam(examples_dir):
    """Three uncoupled identical beams: at each triple root (n pi)^2 the shapes are the
    closed-form sqrt(2) sin(n pi x), one beam each (the null space mixed all three)."""
    model = load(examples_dir / "paper_ex2_three_pp.toml")
    modes = mode_shapes(model, count=6, points=41, digits=20)
    x = np.linspace(0, 1, 41)
    for k, mode in enumerate(modes):
        n = 1 + k // 3
        own = ["b1", "b2", "b3"][k % 3]
        for name, shape in mode.beams.items():
            expected = np.sqrt(2) * np.sin(n * np.pi * x) if name == own else 0 * x
            np.testing.assert_allclose(shape.Y, expected, atol=1e-13)
    assert any("concentrates each one's kinetic energy" in n for n in modes.notes)


def test_localised_shapes_stay_mass_orthonormal_to_their_digits(examples_dir):
    """The rotation is orthogonal to the shapes' own precision. On a pinned-pinned beam
    a shape is A sin(pi x) with A = Theta(0) / pi, so the mass inner product of two
    shapes of the triple root pi^2 is sum over beams A_i A_j / 2: from the 30-digit
    left states, the identity to 25 digits."""
    import mpmath
    model = load(examples_dir / "paper_ex2_three_pp.toml")
    modes = mode_shapes(model, count=3, points=5, digits=30)
    with mpmath.workdps(40):
        A = [[mode.left_state[4 * lvl + 1] / mpmath.pi for lvl in range(3)] for mode in modes]
        for i in range(3):
            for j in range(3):
                inner = sum(A[i][b] * A[j][b] for b in range(3)) / 2
                assert abs(inner - (i == j)) < mpmath.mpf(10) ** -25, (i, j, inner)


# -- eigenvalues closer than their printed digits ------------------------------------------


@pytest.mark.parametrize("k", ["1e-10", "1e-25"])
def test_identical_beams_weakly_coupled_have_in_and_anti_phase_shapes(k):
    """Two equal pinned-pinned beams joined by one weak spring at x = 0.3: each pair of
    eigenvalues splits by about ``k`` (1e-12 and 1e-27 relative, the latter inside the
    15 printed digits). By symmetry one shape of each pair moves both beams alike, the
    spring unstretched, so it is exactly ``sin(n pi x)`` on each (mass-normalised over the
    two beams); the other moves them opposite (``Y_b = -Y_a``). The null space at the
    15-digit estimate held 20 % of the neighbour's shape at k = 1e-25."""
    beams = (Beam("a", 1, 1, 1, left="pinned", right="pinned"),
             Beam("b", 1, 1, 1, left="pinned", right="pinned"))
    model = Model(beams, (Spring("a", "b", "3/10", k),))
    modes = mode_shapes(model, count=4, points=21)
    x = np.linspace(0, 1, 21)
    assert [m.eigenvalue.multiplicity for m in modes] == [1, 1, 1, 1]
    for pair in (modes[0:2], modes[2:4]):
        phases = sorted(pair, key=lambda m: float(m.omega))
        n = round(math.sqrt(float(phases[0].omega)) / math.pi)
        Ya, Yb = phases[0].beams["a"].Y, phases[0].beams["b"].Y
        np.testing.assert_allclose(np.abs(Ya), np.abs(np.sin(n * np.pi * x)), atol=1e-13)
        np.testing.assert_allclose(Yb, Ya, atol=1e-13)
        Ya, Yb = phases[1].beams["a"].Y, phases[1].beams["b"].Y
        np.testing.assert_allclose(Yb, -Ya, atol=1e-13)


def test_nearly_equal_uncoupled_beams_each_move_alone():
    """Two free-free beams, EI 1 and 1 + 1e-10, each held at mid-span by a spring of 1e-8 to
    the ground: no coupling, so every shape moves one beam and is that beam's shape solved
    alone; their eigenvalues lie 2e-20 (the translations) and 5e-11 apart, and the
    neighbour's shape leaked into the other's (a mode spread 0.99/0.15 over both)."""
    def spring(b):
        return Spring(b, "ground", "1/2", "1e-8")

    a = Beam("a", 1, 1, 1, left="free", right="free")
    b = Beam("b", "1 + 1e-10", 1, 1, left="free", right="free")
    modes = mode_shapes(Model((a, b), (spring("a"), spring("b"))), count=6, points=21)
    alone = {name: mode_shapes(Model((beam,), (spring(name),)), count=3, points=21)
             for name, beam in (("a", a), ("b", b))}
    seen = {"a": 0, "b": 0}
    for mode in modes:
        sizes = {name: np.max(np.abs(mode.beams[name].Y)) for name in "ab"}
        name = max(sizes, key=sizes.get)
        other = "b" if name == "a" else "a"
        assert sizes[other] < 1e-12 * sizes[name]
        if mode.eigenvalue.multiplicity == 1 and float(mode.omega) > 0:
            ref = [m for m in alone[name] if float(m.omega) > 0][seen[name]]
            seen[name] += 1
            np.testing.assert_allclose(float(mode.omega), float(ref.omega), rtol=1e-14)
            np.testing.assert_allclose(mode.beams[name].Y, ref.beams[name].Y, atol=1e-12)
    assert seen == {"a": 2, "b": 2}


def test_free_free_rod_on_a_spring_has_its_closed_form_shapes():
    """A free-free rod (EA = m = L = 1) held at mid-span by an axial spring k = 10: its R is
    ``[[0, 1], [t, 0]]`` at a root, whose right and left null vectors are orthogonal (the
    estimate of a neighbour's share took the wrong one and refused the shape). The
    antisymmetric mode has a node at the spring: ``U = sqrt(2) cos(pi x)``, omega = pi;
    the symmetric one is ``A cos(beta x)`` on the left half, ``beta tan(beta / 2) =
    k / 2 EA``, mirrored, ``A`` from ``integral m U**2 = 1``."""
    from symtmm.model import rod

    model = Model((rod("r", 1, 1, 1, left="free", right="free"),),
                  (Spring("r", "ground", "1/2", 10),))
    modes = mode_shapes(model, count=2, points=41)
    x = np.linspace(0, 1, 41)
    with mpmath.workdps(30):
        beta = mpmath.findroot(lambda b: b * mpmath.tan(b / 2) - 5, 2.28)
        A = 1 / mpmath.sqrt(2 * mpmath.quad(lambda s: mpmath.cos(beta * s) ** 2, [0, 0.5]))
    half = np.minimum(x, 1 - x)
    np.testing.assert_allclose(float(modes[0].omega), float(beta), rtol=1e-14)
    np.testing.assert_allclose(modes[0].beams["r"].Y, float(A) * np.cos(float(beta) * half),
                               atol=1e-13)
    np.testing.assert_allclose(float(modes[1].omega), math.pi, rtol=1e-14)
    np.testing.assert_allclose(modes[1].beams["r"].Y, math.sqrt(2) * np.cos(math.pi * x),
                               atol=1e-13)
