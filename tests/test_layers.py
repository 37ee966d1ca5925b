"""Continuous elastic and viscoelastic layers between beams: ``[[layer]]``.

References, none of them from symtmm:

* beams pinned at both ends and joined by layers over their whole length keep the
  shapes ``sin(n pi x / L)``: per ``n`` the amplitudes solve a small matrix problem
  ``(EI b_n**4 + kw + L_kappa - m omega**2) a = 0`` (``b_n = n pi / L``, ``L_kappa`` the
  Laplacian of the layers). For an identical pair the in-phase roots are the single
  beam's and the out-of-phase ones satisfy ``Omega**2 = Omega_n**2 + K (1 + m1/m2)``
  (the classical elastically connected double beam); for different beams a quadratic
  in ``omega**2``; with damping a quartic in ``lam`` (numpy's polynomial roots); for a
  chain of three identical beams the Laplacian's eigenvalues ``0, K, 3K``;
* a partial layer between identical beams leaves the in-phase family (no stretch of
  the layer) at the single beam's roots;
* two identical free beams on a full layer: two rigid-body modes, and the relative
  rigid motions (translation and rotation) both at ``omega**2 = 2 K / m``, a double
  root; with a dashpot layer alone those relative motions decay at ``lam = -2 c / m``;
* the finite-element model with the layer's consistent matrix (tests/test_layers_fe.py).
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from cli_contract import assert_contract, run_cli

from symtmm.model import Beam, Layer, Model, Spring
from symtmm.modes.shapes import mode_shapes
from symtmm.roots.count import Counter
from symtmm.solve import solve

PP = dict(left="pinned", right="pinned")
FF = dict(left="free", right="free")


def _pinned_family(EI, m, kw, laplacian, count, L=1.0):
    """The lowest ``count`` natural frequencies of pinned beams on full layers (see the
    module docstring): per ``n`` the eigenvalues of ``m**-1 (EI b**4 + kw + L_kappa)``."""
    out = []
    EI, m, kw = (np.asarray(v, dtype=float) for v in (EI, m, kw))
    for n in range(1, count + 1):
        b4 = (n * math.pi / L) ** 4
        A = np.diag(EI * b4 + kw) + np.asarray(laplacian, dtype=float)
        Ms = np.diag(1 / np.sqrt(m))
        w2 = np.linalg.eigvalsh(Ms @ A @ Ms)
        out += [math.sqrt(v) for v in w2]
    return sorted(out)[:count]


def _omegas(spectrum):
    return [float(e.lam.imag) for e in spectrum for _ in range(e.multiplicity)]


def test_identical_pair_in_and_out_of_phase():
    K = 80
    model = Model((Beam("a", 1, 1, 1, **PP), Beam("b", 1, 1, 1, **PP)),
                  layers=(Layer("a", "b", k=K),))
    got = _omegas(solve(model, count=10, digits=15))
    ref = sorted([(n * math.pi) ** 2 for n in range(1, 8)]
                 + [math.sqrt((n * math.pi) ** 4 + K * (1 + 1)) for n in range(1, 8)])[:10]
    assert np.allclose(got, ref, rtol=1e-13, atol=0)


def test_different_pair_on_a_foundation():
    EI, m, kw, k = (1, 2), (1, 3), (5, 0), 100
    model = Model((Beam("a", EI[0], m[0], 1, kw=kw[0], **PP),
                   Beam("b", EI[1], m[1], 1, kw=kw[1], **PP)),
                  layers=(Layer("b", "a", k=k),))
    got = _omegas(solve(model, count=8, digits=15))
    ref = _pinned_family(EI, m, kw, [[k, -k], [-k, k]], 8)
    assert np.allclose(got, ref, rtol=1e-13, atol=0)


def test_chain_of_three_beams_on_two_layers():
    K = 50
    beams = tuple(Beam(n, 1, 1, 1, **PP) for n in "abc")
    model = Model(beams, layers=(Layer("a", "b", k=K), Layer("b", "c", k=K)))
    got = _omegas(solve(model, count=9, digits=15))
    ref = _pinned_family((1, 1, 1), (1, 1, 1), (0, 0, 0),
                         [[K, -K, 0], [-K, 2 * K, -K], [0, -K, K]], 9)
    assert np.allclose(got, ref, rtol=1e-13, atol=0)


def test_counts_follow_the_closed_form():
    EI, m, k = (1, 2), (1, 3), 100
    model = Model((Beam("a", EI[0], m[0], 1, **PP), Beam("b", EI[1], m[1], 1, **PP)),
                  layers=(Layer("a", "b", k=k),))
    ref = _pinned_family(EI, m, (0, 0), [[k, -k], [-k, k]], 12)
    counter = Counter(model, 200.0)
    probes = list(np.linspace(0.3, 199.0, 60)) + [r * (1 + d) for r in ref[:6]
                                                    for d in (-1e-10, 1e-10)]
    assert [counter.count(w) for w in probes] == [sum(r < w for r in ref) for w in probes]


def test_damped_pair_against_the_quartic():
    EI, m, k, c = (1, 2), (1, 3), 100, 2
    model = Model((Beam("a", EI[0], m[0], 1, **PP), Beam("b", EI[1], m[1], 1, **PP)),
                  layers=(Layer("a", "b", k=k, c=c),))
    got = sorted((complex(e.lam) for e in solve(model, omega_max=100, digits=12)),
                 key=lambda z: z.imag)
    P = np.polynomial.polynomial
    ref = []
    for n in range(1, 6):
        b4 = (n * math.pi) ** 4
        a11, a22, a12 = [EI[0] * b4 + k, c, m[0]], [EI[1] * b4 + k, c, m[1]], [k, c]
        ref += [r for r in P.polyroots(P.polysub(P.polymul(a11, a22), P.polymul(a12, a12)))
                if 0 <= r.imag <= 100]
    ref.sort(key=lambda z: z.imag)
    assert len(got) == len(ref) == 6
    assert np.allclose(got, ref, rtol=1e-10, atol=0)


def test_partial_layer_leaves_the_in_phase_family():
    model = Model((Beam("a", 1, 1, 1, **PP), Beam("b", 1, 1, 1, **PP)),
                  (Spring("a", "b", "1/5", 30),),
                  layers=(Layer("a", "b", k=200, x0="1/4", x1="7/10"),))
    got = _omegas(solve(model, count=8, digits=15))
    for n in (1, 2, 3):
        w = (n * math.pi) ** 2
        assert min(abs(g / w - 1) for g in got) < 1e-13


def test_free_pair_rigid_and_relative_motions():
    K = 30
    model = Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, **FF)),
                  layers=(Layer("a", "b", k=K),))
    spectrum = solve(model, count=5, digits=15)
    assert [e.multiplicity for e in spectrum][:2] == [2, 2]
    assert spectrum[0].lam == 0
    assert abs(float(spectrum[1].lam.imag) / math.sqrt(2 * K) - 1) < 1e-14
    # then the free-free beam's first elastic mode, in phase: (beta L)**2, beta L = 4.7300...
    assert abs(float(spectrum[2].lam.imag) / 4.730040744862704**2 - 1) < 1e-13


def test_dashpot_layer_damps_the_relative_motions():
    c = 3
    model = Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, **FF)),
                  layers=(Layer("a", "b", k=0, c=c),))
    spectrum = solve(model, omega_max=10, digits=12)
    real = [e for e in spectrum if e.lam.imag == 0 and e.lam.real != 0]
    assert len(real) == 1 and real[0].multiplicity == 2
    assert abs(float(real[0].lam.real) / (-2 * c) - 1) < 1e-11


def test_mode_shapes_of_a_pinned_pair():
    EI, m, k = (1, 2), (1, 3), 100
    model = Model((Beam("a", EI[0], m[0], 1, **PP), Beam("b", EI[1], m[1], 1, **PP)),
                  layers=(Layer("a", "b", k=k),))
    modes = mode_shapes(model, count=2, points=5)
    for mode in modes:
        w2 = float(mode.eigenvalue.lam.imag) ** 2
        b4 = math.pi**4
        ratio = (EI[0] * b4 + k - m[0] * w2) / k        # a_b / a_a, both sin(pi x)
        ya = np.asarray(mode.beams["a"].Y, dtype=float)
        yb = np.asarray(mode.beams["b"].Y, dtype=float)
        x = np.asarray(mode.beams["a"].x, dtype=float)
        a = 1 / math.sqrt((m[0] + m[1] * ratio**2) / 2)   # mass-normalised
        sign = np.sign(ya[2])
        assert np.allclose(sign * ya, a * np.sin(math.pi * x), atol=1e-12)
        assert np.allclose(sign * yb, ratio * a * np.sin(math.pi * x), atol=1e-12)


def test_mode_shapes_of_a_soft_beam_held_between_two_stiff_layers():
    """A soft heavy beam between two stiff layers: along it the coupled member's waves
    grow by ``exp(600)`` where the beam's own say ``exp(3)``, and the shapes' walk, at the
    digits of the latter, refined noise ("not told apart from a neighbouring eigenvalue's",
    after a minute). Pinned beams: every mode is ``sin(n pi x / L)`` on each beam, its
    amplitudes the eigenvector of the 3x3 problem of its ``n``."""
    EI, m, k, L = (1.36e6, 0.45, 1000), (0.71, 430, 1.4), (1e6, 6e6), 10
    model = Model(tuple(Beam(n, EI[i], m[i], L, **PP) for i, n in enumerate("abc")),
                  layers=(Layer("a", "b", k=k[0]), Layer("b", "c", k=k[1])))
    modes = mode_shapes(model, count=2, points=5)
    laplacian = np.array([[k[0], -k[0], 0], [-k[0], k[0] + k[1], -k[1]], [0, -k[1], k[1]]])
    Ms = np.diag(1 / np.sqrt(m))
    family = []                     # (omega, n, amplitudes mass-normalised) per mode
    for n in (1, 2, 3):
        b4 = (n * math.pi / L) ** 4
        w2, vectors = np.linalg.eigh(Ms @ (np.diag(np.array(EI) * b4) + laplacian) @ Ms)
        # (sum of m a**2 L / 2 over the beams is 1)
        family += [(math.sqrt(w), n, Ms @ v * math.sqrt(2 / L)) for w, v in zip(w2, vectors.T)]
    family.sort(key=lambda t: t[0])
    for mode, (omega, n, amplitudes) in zip(modes, family):
        assert math.isclose(float(mode.eigenvalue.lam.imag), omega, rel_tol=1e-12)
        x = np.asarray(mode.beams["a"].x, dtype=float)
        got = np.array([np.asarray(mode.beams[b].Y, dtype=float) for b in "abc"])
        expected = np.outer(amplitudes, np.sin(n * math.pi * x / L))
        sign = np.sign(got[1, 1]) * np.sign(expected[1, 1])
        assert np.allclose(sign * got, expected, atol=1e-9 * np.abs(expected).max())


LAYERED = """
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"

[[beam]]
name = "b"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"
"""


def test_model_file_layer(tmp_path):
    path = tmp_path / "pair.toml"
    path.write_text(LAYERED + '\n[[layer]]\nbetween = ["a", "b"]\nk = 80\n')
    run = run_cli(["solve", path, "--count", "2", "--json"], limit=60)
    assert_contract(run, 60)
    assert run.code == 0, run.stderr
    import json
    got = [float(e["imag"]) for e in json.loads(run.stdout)["eigenvalues"]]
    assert np.allclose(got, [math.pi**2, math.sqrt(math.pi**4 + 160)], rtol=1e-13)


@pytest.mark.parametrize("table, message", [
    ('between = ["a", "a"]\nk = 1', "layer[1].between: a layer must join two different"),
    ('between = ["a", "ground"]\nk = 1', "layer[1].between: a layer joins two beams"),
    ('between = ["a", "c"]\nk = 1', "layer[1].between: unknown beam 'c'"),
    ('between = ["a", "b"]\nk = -1', "layer[1].k: must not be negative"),
    ('between = ["a", "b"]\nk = 1\nfrom = 0.5\nto = 0.5', "layer[1].to: the layer needs from < to"),
    ('between = ["a", "b"]\nk = 1\nto = 2', "layer[1].to: x = 2 lies outside beam"),
    ('between = ["a", "b"]\nk = 1\nx = 2', "layer[1].x: unknown field 'x'"),
    ('between = ["a", "b"]\nk = 1\n[[layer]]\nbetween = ["b", "a"]\nk = 2\nfrom = 0.5',
     "layer[2]: overlaps another layer"),
])
def test_bad_layers_get_one_line_errors(tmp_path, table, message):
    path = tmp_path / "bad.toml"
    path.write_text(LAYERED + "\n[[layer]]\n" + table + "\n")
    run = run_cli(["solve", path, "--count", "1"], limit=30)
    assert_contract(run, 30)
    assert run.code == 2 and message in run.stderr, run.stderr


def test_layer_needs_euler_bernoulli_beams(tmp_path):
    path = tmp_path / "timo.toml"
    path.write_text(LAYERED.replace('right = "pinned"\n', 'right = "pinned"\ntheory = '
                                    '"timoshenko"\nrhoI = 0.01\nkGA = 100\n', 1)
                    + '\n[[layer]]\nbetween = ["a", "b"]\nk = 1\n')
    run = run_cli(["solve", path, "--count", "1"], limit=30)
    assert run.code == 2 and "layer[1].between: a layer joins Euler-Bernoulli" in run.stderr


@pytest.mark.parametrize("json_flag", [[], ["--json"]])
def test_derive_takes_a_layered_pair(tmp_path, json_flag):
    """(The closed forms themselves: tests/test_layers_derive.py.)"""
    path = tmp_path / "pair.toml"
    path.write_text(LAYERED + '\n[[layer]]\nbetween = ["a", "b"]\nk = 80\n')
    run = run_cli(["derive", path, *json_flag], limit=30)
    assert_contract(run, 30)
    assert run.code == 0 and "q_a_b" in run.stdout, run.stderr


def test_generated_evaluator_vanishes_at_the_closed_form_roots():
    """The generated (numpy) evaluator of a different pair on a full layer, at the roots of
    the per-n quadratic: |Delta| there is 1e-9 of its size a little off."""
    from symtmm.codegen import generate
    EI, m, k = (1, 2), (1, 3), 100
    model = Model((Beam("a", EI[0], m[0], 1, **PP), Beam("b", EI[1], m[1], 1, **PP)),
                  layers=(Layer("a", "b", k=k),))
    ns: dict = {}
    exec(generate(model, "python"), ns)  # noqa: S102 - the generated module
    roots = np.array(_pinned_family(EI, m, (0, 0), [[k, -k], [-k, k]], 6))
    at = np.abs(ns["symtmm_delta"](1j * roots))
    off = np.abs(ns["symtmm_delta"](1j * roots * (1 + 1e-4)))
    assert np.all(at < 1e-9 * off)


@pytest.mark.parametrize("table", ['\n[[layer]]\nbetween = ["a", "b"]\nk = 1e30\n',
                                   ""])
def test_a_foundation_or_layer_too_stiff_for_the_mesh_is_one_line(tmp_path, table):
    """Ten million pieces would be needed (|beta| l <= 3 per piece at kw L**4 / EI ~ 1e30):
    refused before the mesh is made, in one line, quickly."""
    path = tmp_path / "stiff.toml"
    text = LAYERED + table
    if not table:
        text = text.replace('right = "pinned"\n', 'right = "pinned"\nkw = 1e30\n', 1)
    path.write_text(text)
    run = run_cli(["solve", path, "--count", "2"], limit=30)
    assert_contract(run, 30)
    assert run.code == 1 and "would need more than 100000 pieces" in run.stderr, run.stderr
