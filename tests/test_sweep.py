"""Parameter sweeps against decoupled identical-beam families; parallel runs; tracking."""

import json
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp
from cli_contract import run_cli

from symtmm.cli import main
from symtmm.errors import ModelError
from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load, loads
from symtmm.roots.undamped import PROOFS
from symtmm.solve import solve
from symtmm.sweep import sweep, sweep_values, track_branches, value_string

TWO_BEAMS = """
title = "two identical pinned-pinned beams, springs at x1 and 1 - x1"
[parameters]
K = 40
x1 = 0.2
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
[[spring]]
between = ["a", "b"]
x = "x1"
k = "K"
[[spring]]
between = ["a", "b"]
x = "1 - x1"
k = "K"
"""


@pytest.fixture
def examples_dir():
    """The model files of the paper's examples."""
    return Path(__file__).resolve().parent.parent / "examples"


def grounded_beam(k, x1):
    """One pinned-pinned beam on grounded springs k at x1 and 1 - x1."""
    springs = () if k == 0 else (Spring("b", "ground", x1, k), Spring("b", "ground", 1 - x1, k))
    return Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),), springs)


def family_values(factors, K, x1, count, digits):
    """Eigenvalues of the decoupled single-beam problems: {factor: [omega, ...]}."""
    return {f: [float(w) for w in solve(grounded_beam(f * K, x1), count=count,
                                        digits=digits).omegas(expand=True)][:count]
            for f in factors}


def expanded(spectrum):
    return [float(w) for w in spectrum.omegas(expand=True)]


@pytest.fixture(scope="module")
def two_beams():
    return loads(TWO_BEAMS)


@pytest.fixture(scope="module")
def serial(two_beams):
    return sweep(two_beams, "x1", "0.1", "0.3", 3, count=4, digits=10, jobs=1)


# -- values ---------------------------------------------------------------------------------

def test_values_are_exact_and_include_both_ends():
    assert sweep_values("0", "0.5", 11) == tuple(sp.Rational(i, 20) for i in range(11))
    assert sweep_values("1/3", 1, 3) == (sp.Rational(1, 3), sp.Rational(2, 3), 1)
    assert [value_string(v) for v in sweep_values("0.1", "0.3", 3)] == ["0.1", "0.2", "0.3"]
    assert value_string(sp.Rational(-7, 8)) == "-0.875"
    with pytest.raises(ModelError, match="^steps: "):
        sweep_values(0, 1, 1)
    with pytest.raises(ModelError, match="^stop: "):
        sweep_values(0, "1 +", 3)


# -- decoupled families -----------------------------------------------------------------------

def test_two_identical_beams_decouple_into_0_and_2K(serial):
    assert [value_string(v) for v in serial.values] == ["0.1", "0.2", "0.3"]
    for value, spectrum in zip(serial.values, serial.spectra):
        fam = family_values((0, 2), 40, value, 4, 10)
        reference = sorted(fam[0] + fam[2])[:4]
        assert expanded(spectrum)[:4] == pytest.approx(reference, rel=1e-9)


def test_sweep_reaches_parameters_defined_through_the_swept_one():
    # k = "K*EI/L**3" is written in terms of K, as in the paper's example 4: sweeping K
    # must move the out-of-phase family (beam on grounded springs 2k), not leave it fixed
    text = TWO_BEAMS.replace('K = 40', 'K = 40\nEIp = 1\nk = "K*EIp"').replace(
        'k = "K"', 'k = "k"')
    result = sweep(loads(text), "K", 10, 70, 2, count=2, digits=10, jobs=1)
    for K, spectrum in zip((10, 70), result.spectra):
        fam = family_values((0, 2), K, sp.Rational(1, 5), 2, 10)
        assert expanded(spectrum)[:2] == pytest.approx(sorted(fam[0] + fam[2])[:2], rel=1e-9)


def half_beam(k, x1, middle):
    """Half of a grounded beam: symmetric modes (sliding middle) or antisymmetric (pinned)."""
    springs = () if k == 0 else (Spring("h", "ground", x1, k),)
    return Model((Beam("h", 1, 1, sp.Rational(1, 2), left="pinned", right=middle),), springs)


def test_three_beams_decouple_and_branches_follow_crossings(examples_dir):
    # K = 300: the 3K family's first mode rises through the uncoupled 2 pi mode
    model = load(examples_dir / "paper_ex3_three_pp_coupled.toml", {"K": "300"})
    result = sweep(model, "x1", "0.1", "0.4", 4, count=6, digits=10, jobs=1)
    identity = {}
    rank_changes = 0
    previous_rank = {}
    for value, spectrum, ids in zip(result.values, result.spectra, result.branches):
        # graph Laplacian of the path P3: single beams on springs 0, K and 3K ...
        fam = family_values((0, 1, 3), 300, value, 6, 10)
        reference = sorted(w for ws in fam.values() for w in ws)[:6]
        assert expanded(spectrum)[:6] == pytest.approx(reference, rel=1e-9)
        # ... each of them symmetric about the middle: halves with a sliding or pinned middle,
        # within which (one symmetry class of one family) branches cannot cross
        classes = {(f, mid): [float(w) for w in solve(half_beam(300 * f, value, mid), count=6,
                                                      digits=10).omegas(expand=True)]
                   for f in (0, 1, 3) for mid in ("sliding", "pinned")}
        slot = 0
        for e, group in zip(spectrum, ids):
            for bid in group:
                w = float(e.omega)
                matches = [(c, n) for c, ws in classes.items() for n, v in enumerate(ws)
                           if abs(v - w) < 1e-8 * w]
                assert len(matches) == 1
                # a branch stays in its class and keeps its place there
                assert identity.setdefault(bid, matches[0]) == matches[0]
                if bid in previous_rank and previous_rank[bid] != slot:
                    rank_changes += 1
                previous_rank[bid] = slot
                slot += 1
    assert rank_changes >= 2          # crossings happened and were followed


VEERING = """
title = "two unlike beams: no symmetry, so their branches can only veer"
[parameters]
K = 200
x1 = 0.3
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"
[[beam]]
name = "b"
EI = 1.3
m = 0.9
L = 1
left = "clamped"
right = "free"
[[spring]]
between = ["a", "b"]
x = "x1"
k = "K"
[[spring]]
between = ["b", "ground"]
x = "0.8*x1"
k = 30
"""


def test_branches_veer_without_crossing_where_nothing_is_symmetric():
    # No symmetry separates the modes, so eigenvalues of this one-parameter family do not
    # cross (von Neumann-Wigner): through the near-miss of the 3rd and 4th frequencies at
    # x1 = 0.5 every tracked branch must keep its place in the sorted spectrum.
    result = sweep(loads(VEERING), "x1", "0.4", "0.6", 9, count=5, digits=10, jobs=1)
    ranks = {}
    for spectrum, step in zip(result.spectra, result.branches):
        assert [float(e.omega) for e in spectrum] == sorted(float(e.omega) for e in spectrum)
        for rank, group in enumerate(step):
            for bid in group:
                ranks.setdefault(bid, set()).add(rank)
    assert all(len(r) == 1 for r in ranks.values()), ranks
    # and it is a veering: the gap between the 3rd and 4th shrinks to a fraction of its
    # size at the ends of the range, then opens again
    gaps = [float(s[3].omega) - float(s[2].omega) for s in result.spectra]
    assert min(gaps) < 0.5 * min(gaps[0], gaps[-1])
    assert 0 < gaps.index(min(gaps)) < len(gaps) - 1


def test_tracking_through_a_multiple_eigenvalue():
    e1, e2 = np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0])
    mix = np.array([[1.0, 1.0, 0.0], [1.0, -1.0, 0.0]]) / np.sqrt(2)   # arbitrary basis
    steps = [[e1[None], e2[None]], [mix], [e2[None], e1[None]]]
    ids = track_branches(steps)
    assert ids[0] == [(0,), (1,)]
    assert sorted(ids[1][0]) == [0, 1]
    assert ids[2] == [(1,), (0,)]          # the branches crossed at the double root
    # starting at a fully degenerate step: identities come from the simple ones
    assert track_branches([[mix], [e2[None], e1[None]]])[1] == [(0,), (1,)]


# -- parallel runs ------------------------------------------------------------------------------

def _comparable(result):
    data = result.to_dict()
    return data


def test_local_processes_give_the_serial_result(two_beams, serial):
    parallel = sweep(two_beams, "x1", "0.1", "0.3", 3, count=4, digits=10, jobs=2)
    assert _comparable(parallel) == _comparable(serial)


def test_dask_cluster_gives_the_serial_result(two_beams, serial):
    # a scheduler and two worker processes on TCP loopback, reached by their address: the
    # steps really travel pickled to other interpreters, as on a cluster
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(host="127.0.0.1", protocol="tcp", processes=True,
                                  n_workers=2, threads_per_worker=1,
                                  dashboard_address=None) as cluster:
        address = cluster.scheduler_address
        assert address.startswith("tcp://127.0.0.1:")
        result = sweep(two_beams, "x1", "0.1", "0.3", 3, count=4, digits=10,
                       scheduler=address)
    assert _comparable(result) == _comparable(serial)


def test_bad_scheduler_address_is_one_line(two_beams, capsys, tmp_path):
    path = tmp_path / "two.toml"
    path.write_text(TWO_BEAMS)
    for address in ("garbage", "http://127.0.0.1:1"):
        assert main(["sweep", str(path), "--param", "x1", "--from", "0.1", "--to", "0.2",
                     "--steps", "2", "--scheduler", address]) == 2
        err = capsys.readouterr().err
        assert "--scheduler" in err and err.count("\n") == 1 and "Traceback" not in err


@pytest.mark.slow
def test_dask_worker_processes_give_the_serial_result(two_beams, serial):
    # worker processes: the steps really travel pickled to other interpreters
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(processes=True, n_workers=2, threads_per_worker=1,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        result = sweep(two_beams, "x1", "0.1", "0.3", 3, count=4, digits=10, scheduler=client)
    assert _comparable(result) == _comparable(serial)


def test_damped_sweep_tracks_complex_branches():
    model = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),
                   Beam("b", 1, 1, 1, left="pinned", right="pinned")),
                  (Spring("a", "b", x="3/10", k=200, c="c"),), parameters={"c": 1})
    result = sweep(model, "c", 1, 2, 2, count=2, digits=8, jobs=1, sigma_max=20)
    assert result.damped
    assert all(len(step) >= 1 for step in result.branches)
    # the undamped in-phase mode (springs idle) stays at pi^2 on one branch
    _, lam = result.branch(0)
    assert np.allclose(lam, 1j * math.pi**2, rtol=1e-7)
    assert "lam_1" in result.table()


# -- command line --------------------------------------------------------------------------------

def test_cli_json(tmp_path, capsys, serial):
    path = tmp_path / "two.toml"
    path.write_text(TWO_BEAMS)
    png = tmp_path / "sweep.png"
    code = main(["sweep", str(path), "--param", "x1", "--from", "0.1", "--to", "0.3",
                 "--steps", "3", "--count", "4", "--digits", "10", "--jobs", "1", "--json",
                 "--plot", str(png)])
    assert code == 0
    data = json.loads(capsys.readouterr().out)
    assert data["parameter"] == "x1"
    assert data["values"] == ["0.1", "0.2", "0.3"]
    assert len(data["eigenvalues"]) == 3
    for step, ref in zip(data["eigenvalues"], serial.spectra):
        assert [set(e) - {"proof"} for e in step] == [{"real", "imag", "multiplicity"}] * len(step)
        assert {e.get("proof") for e in step} <= set(PROOFS.values())
        assert [e["imag"] for e in step] == [e.to_dict()["imag"] for e in ref]
    assert [len(g) for g in data["branches"][0]] == [e["multiplicity"]
                                                     for e in data["eigenvalues"][0]]
    assert png.read_bytes()[:4] == b"\x89PNG"


def test_cli_bad_input(tmp_path, capsys):
    path = tmp_path / "two.toml"
    path.write_text(TWO_BEAMS)
    assert main(["sweep", str(path), "--param", "nope", "--from", "0", "--to", "1",
                 "--steps", "3", "--count", "2"]) == 2
    err = capsys.readouterr().err
    assert "--param" in err and "nope" in err and "Traceback" not in err
    # a value moving a spring off the beams names the value
    assert main(["sweep", str(path), "--param", "x1", "--from", "0", "--to", "2",
                 "--steps", "3", "--count", "2"]) == 2
    assert "x1 = 2" in capsys.readouterr().err
    with pytest.raises(SystemExit) as exc:
        main(["sweep", str(path), "--param", "x1", "--from", "0", "--to", "1",
              "--steps", "1", "--count", "2"])
    assert exc.value.code == 2


def test_result_api(serial):
    x, lam = serial.branch(0)
    assert list(x) == [0.1, 0.2, 0.3]
    assert np.all(lam.real == 0)
    _, Om = serial.branch(0, "Omega")
    assert Om == pytest.approx(np.sqrt(lam.imag))     # EI = m = L = 1
    assert "x1" in serial.table() and "<table>" in serial._repr_html_()
    with mpmath.workdps(15):
        assert serial.omega_scale[0] == "a"


def test_a_script_without_main_guard_runs_a_parallel_sweep(tmp_path):
    # the README's snippet saved as a file: worker processes must not re-run the script
    import subprocess
    import sys

    model = tmp_path / "two.toml"
    model.write_text(TWO_BEAMS)
    script = tmp_path / "snippet.py"
    script.write_text("from symtmm import api\n"
                      f"model = api.load({str(model)!r})\n"
                      "print('solve', len(api.solve(model, count=2, digits=8)))\n"
                      "s = api.sweep(model, 'x1', '0.1', '0.3', 3, count=2, digits=8, jobs=2)\n"
                      "print('steps', len(s))\n")
    root = Path(__file__).resolve().parent.parent
    proc = subprocess.run([sys.executable, str(script)], check=False, capture_output=True,
                          text=True,
                          timeout=300, cwd=tmp_path, env={"PYTHONPATH": str(root),
                                                          "PATH": "/usr/bin:/bin"})
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["solve", "2", "steps", "3"]


# -- what a damped sweep can show ------------------------------------------------------------


def test_damped_sweep_quantities_and_root_locus(examples_dir):
    """zeta, |lam| and hz of every branch are those of its eigenvalues; the root locus
    draws each branch at (Re lam, Im lam)."""
    pytest.importorskip("matplotlib")
    from symtmm import api
    model = api.load(examples_dir / "tuned_mass_damper.toml")
    result = api.sweep(model, "f", "0.9", "1.1", 3, count=2, digits=10, jobs=1)
    for bid in result.branch_ids():
        _, lam = result.branch(bid)
        _, zeta = result.branch(bid, "zeta")
        _, size = result.branch(bid, "abs")
        _, hz = result.branch(bid, "hz")
        np.testing.assert_allclose(zeta, -lam.real / np.abs(lam), rtol=1e-14)
        np.testing.assert_allclose(size, np.abs(lam), rtol=1e-14)
        np.testing.assert_allclose(hz, lam.imag / (2 * np.pi), rtol=1e-14)
    ax = result.plot(frequency="zeta").axes[0]
    assert "damping ratio" in ax.get_ylabel()
    locus = result.plot(frequency="locus").axes[0]
    lines = [ln for ln in locus.lines if len(ln.get_xdata()) == 3]
    for bid, line in zip(result.branch_ids(), lines):
        _, lam = result.branch(bid)
        np.testing.assert_allclose(line.get_xdata(), lam.real)
        np.testing.assert_allclose(line.get_ydata(), lam.imag)
    with pytest.raises(ValueError, match="unknown quantity"):
        result.plot(frequency="bogus")


def test_a_branch_seen_at_one_step_is_not_labelled_as_present_throughout():
    pytest.importorskip("matplotlib")
    from symtmm.plot import plot_sweep
    from symtmm.results import Eigenvalue, Spectrum
    from symtmm.sweep import Sweep

    def spectrum(*omegas):
        return Spectrum(tuple(Eigenvalue(mpmath.mpc(0, w)) for w in omegas), 15, "default", 0, 0)
    result = Sweep("p", (sp.Integer(0), sp.Integer(1), sp.Integer(2)),
                   (spectrum(1), spectrum(1, 5), spectrum(1)),
                   (((0,),), ((0,), (1,)), ((0,),)), 15)
    labels = [t.get_text() for t in plot_sweep(result, frequency="omega").legends[0].texts]
    assert labels == ["1: ω = 1 throughout", "2: ω = 5 at p = 1 only"]


def test_the_scan_plots_in_the_frequency_asked_for(examples_dir, tmp_path):
    pytest.importorskip("matplotlib")
    from symtmm import api
    result = api.scan(api.load(examples_dir / "paper_ex1_ff_cc.toml"), omega_max=50, points=40,
                      eigenvalues=False, spacing="omega")
    line = result.plot(frequency="hz").axes[0].lines[0]
    np.testing.assert_allclose(line.get_xdata(), result.omega / (2 * np.pi))
    run = run_cli(["scan", examples_dir / "paper_ex1_ff_cc.toml", "--omega-max", "50",
                   "--spacing", "omega", "--no-eigenvalues", "--plot", tmp_path / "s.png"])
    assert run.code == 0 and (tmp_path / "s.png").exists()


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc.toml", "tuned_mass_damper.toml"])
def test_tracking_shapes_in_double_agree_with_mpmath(monkeypatch, name):
    """Low modes' tracking shapes come from a double-precision walk where its cancellation
    leaves the digits asked for; they agree with the mpmath walk's (MAC 1 to 1e-10)."""
    from symtmm.modes import shapes
    model = load(str(Path(__file__).resolve().parent.parent / "examples" / name))
    spectrum = list(solve(model, count=6, digits=10))
    fast = shapes.displacements(model, spectrum, 33, 6, nodal=False)
    monkeypatch.setattr(shapes, "_DOUBLE_DIGITS", -1)          # everything in mpmath
    slow = shapes.displacements(model, spectrum, 33, 6, nodal=False)
    for a, b in zip(fast, slow):
        for u, v in zip(np.atleast_2d(a), np.atleast_2d(b)):
            mac = abs(np.vdot(u, v)) ** 2 / (np.vdot(u, u).real * np.vdot(v, v).real)
            assert mac > 1 - 1e-10


def _subspace_mac(a, b) -> float:
    """The smallest squared cosine of the principal angles between two shapes' spans."""
    qa, _ = np.linalg.qr(np.atleast_2d(a).T)
    qb, _ = np.linalg.qr(np.atleast_2d(b).T)
    return float(np.linalg.svd(qa.conj().T @ qb, compute_uv=False).min() ** 2)


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc.toml", "paper_ex3_three_pp_coupled.toml",
                                  "paper_ex4_damped.toml", "rayleigh_axial_force.toml",
                                  "timoshenko_beam.toml", "closed_loop.toml", "hinge_joint.toml",
                                  "rigid_body_on_beam.toml"])
def test_tracking_shapes_from_the_stiffness_agree_with_the_mpmath_walk(name):
    """The stiffness route (null vector of K in double, then each short piece) against the
    transfer walk in mpmath, a second formulation: the same shapes (MAC 1 to 1e-10) for the
    first 10 modes, multiple ones and high ones included (ex3's triple root (4 pi)**2)."""
    from symtmm.modes import shapes
    from symtmm.modes.nodal import nodal_displacements
    model = load(str(Path(__file__).resolve().parent.parent / "examples" / name))
    spectrum = list(solve(model, count=10, digits=10))
    fast = nodal_displacements(model, spectrum, 33)
    slow = shapes.displacements(model, spectrum, 33, 6, nodal=False)
    served = 0
    for e, a, b in zip(spectrum, fast, slow):
        if a is None:
            # only an undamped mode of a damped model is left to the walk
            assert model.damped and e.lam.real == 0
            continue
        served += 1
        assert a.shape == np.atleast_2d(b).shape
        assert _subspace_mac(a, b) > 1 - 1e-10
    assert served >= 6


@pytest.mark.parametrize("name", ["double_beam_layer.toml", "kukla_rods.toml",
                                  "portal_frame.toml"])
def test_tracking_shapes_of_layers_rods_and_frames_are_walked(name):
    """Beams joined by layers and rods are not served by the stiffness route: every shape
    comes from the walk, and the sweeps' displacements still give them all."""
    from symtmm.modes import shapes
    from symtmm.modes.nodal import nodal_displacements
    model = load(str(Path(__file__).resolve().parent.parent / "examples" / name))
    spectrum = list(solve(model, count=3, digits=10))
    assert all(Y is None for Y in nodal_displacements(model, spectrum, 9))
    assert all(Y is not None for Y in shapes.displacements(model, spectrum, 9, 6))
