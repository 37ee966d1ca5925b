"""Scans of log10|Delta|, the plot functions, notebook representations and the api module."""

import json
import math
from pathlib import Path

import mpmath
import numpy as np
import pytest
import sympy as sp

from symtmm import api
from symtmm.cli import main
from symtmm.compile import Evaluator
from symtmm.display import html_table, latex_text
from symtmm.errors import ComputationError, ModelError
from symtmm.model import Beam, Model, Spring
from symtmm.plot import Figure, plot_modes, plot_scan, plot_scan_map, plot_sweep, save_figure
from symtmm.scan import scan
from symtmm.solve import solve

PP = Model((Beam("b", EI=2, m=3, L=1, left="pinned", right="pinned"),))


@pytest.fixture
def examples_dir():
    """The model files of the paper's examples."""
    return Path(__file__).resolve().parent.parent / "examples"


def damped_pair():
    return Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),
                  Beam("b", 1, 1, 1, left="pinned", right="pinned")),
                 (Spring("a", "b", x="3/10", k=200, c=3),))


# -- scan -----------------------------------------------------------------------------------

def test_curve_matches_the_closed_form_of_a_pinned_pinned_beam():
    # for a pinned-pinned beam R = [[T/b, V/(EI b^3)], [EI b V, T/b]] (unknowns Theta, Q;
    # conditions Y, M), so Delta = (T^2 - V^2)/b^2 = sinh(b L) sin(b L) / b^2
    s = scan(PP, omega_max=400, points=301, eigenvalues=False)
    beta = (3 * s.omega**2 / 2) ** 0.25
    with np.errstate(divide="ignore", invalid="ignore"):
        exact = np.log10(np.abs(np.sinh(beta) * np.sin(beta) / beta**2))
    exact[0] = 0.0                                   # the limit b -> 0: L**2 = 1
    away = np.abs(np.sin(beta)) > 0.1                # not near a root
    low = beta < 9                                   # |Delta| terms below 1e4: little rounding
    assert np.max(np.abs(s.log10_delta[away & low] - exact[away & low])) < 1e-10
    # higher up double precision loses about log10(e^(beta L)) digits, as documented
    assert np.max(np.abs(s.log10_delta[away] - exact[away])) < 1e-4
    # the minima sit at the roots beta L = n pi, to within the grid spacing
    roots = (np.arange(1, 8) * np.pi) ** 2 * math.sqrt(2 / 3)     # the seven below 400
    minima = s.local_minima()
    assert len(minima) == 7
    spacing = np.max(np.diff(s.omega))
    assert np.all(np.abs(minima - roots) <= spacing)


def test_eigenvalues_marked_and_grid_options():
    s = scan(PP, omega_max=100, points=201, omega_min=10, spacing="omega")
    assert s.omega[0] == 10 and s.omega[-1] == 100
    assert np.allclose(np.diff(s.omega), 0.45)
    # (n pi)^2 sqrt(EI/m): the two in [10, 100]
    assert [float(e.omega) for e in s.spectrum] == \
        pytest.approx([n * n * math.pi**2 * math.sqrt(2 / 3) for n in (2, 3)], rel=1e-12)
    assert s.omega_scale == ("b", pytest.approx(math.sqrt(2 / 3)))
    t = scan(PP, omega_max=100, points=201)                  # equally spaced in Omega
    assert np.allclose(np.diff(np.sqrt(t.omega)), 10 / 200)
    assert not s.damped and s.map_log10 is None


def test_cli_json(tmp_path, capsys):
    path = tmp_path / "ff.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nleft = "free"\n'
                    'right = "free"\n')
    png = tmp_path / "scan.png"
    assert main(["scan", str(path), "--omega-max", "30", "--points", "50", "--json",
                 "--plot", str(png)]) == 0
    data = json.loads(capsys.readouterr().out)
    assert len(data["omega"]) == len(data["log10_abs_delta"]) == 50
    assert data["log10_abs_delta"][0] is None       # rigid-body modes: Delta(0) = 0 exactly
    assert [e["multiplicity"] for e in data["eigenvalues"]] == [2, 1]
    assert "map" not in data
    assert png.read_bytes()[:4] == b"\x89PNG"
    for bad in ("0", "-1", "x"):
        with pytest.raises(SystemExit) as exc:
            main(["scan", str(path), "--omega-max", bad])
        assert exc.value.code == 2
    assert main(["scan", str(tmp_path / "missing.toml"), "--omega-max", "5"]) == 2
    assert "Traceback" not in capsys.readouterr().err


def test_damped_map_has_its_minima_at_the_roots():
    model = damped_pair()
    ev = Evaluator(model)
    undamped = solve(Model(model.beams, (Spring("a", "b", x="3/10", k=200),)), count=2,
                     digits=10)
    # an independent root: mpmath's secant method from the undamped second frequency
    with mpmath.workdps(30):
        root = complex(mpmath.findroot(ev.delta_mp, mpmath.mpc(-1, float(undamped[1].omega))))
    s = scan(model, omega_max=60, points=200, sigma_max=8, map_points=(81, 121))
    assert s.damped and s.map_log10.shape == (121, 81)
    # the smallest map value in a window around the root is the grid point next to it
    re, im = -s.map_sigma, s.map_omega
    near = (np.abs(re[None, :] - root.real) < 2) & (np.abs(im[:, None] - root.imag) < 5)
    i, j = np.unravel_index(np.argmin(np.where(near, s.map_log10, np.inf)), near.shape)
    assert abs(re[j] - root.real) <= 1.01 * abs(re[1] - re[0])
    assert abs(im[i] - root.imag) <= 1.01 * (im[1] - im[0])
    # the marks come from the damped solver
    assert s.spectrum is not None, s.notes
    lams = [complex(e.lam) for e in s.spectrum]
    assert min(abs(lam - root) for lam in lams) < 1e-6 * abs(root)
    fig = s.plot_map()
    assert isinstance(fig, Figure)
    assert "Re" in fig.axes[0].get_xlabel() and "1/s" in fig.axes[0].get_xlabel()


def test_damped_cli_plot_writes_the_curve_and_the_map(tmp_path, capsys):
    path = tmp_path / "damped.toml"
    path.write_text('[[beam]]\nname = "a"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\n'
                    'right = "pinned"\n[[spring]]\nbetween = ["a", "ground"]\nx = 0.3\n'
                    'k = 50\nc = 2\n')
    png = tmp_path / "scan.png"
    assert main(["scan", str(path), "--omega-max", "60", "--points", "60", "--plot",
                 str(png)]) == 0
    assert png.read_bytes()[:4] == b"\x89PNG"
    assert (tmp_path / "scan-map.png").read_bytes()[:4] == b"\x89PNG"
    out = capsys.readouterr().out
    assert str(png) in out and "scan-map.png" in out


def test_bad_plot_path_is_refused_before_computing(tmp_path, capsys):
    path = tmp_path / "pp.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\n'
                    'right = "pinned"\n')
    for bad, message in ((tmp_path / "no" / "fig.png", "no folder"),
                         (tmp_path / "fig.nope", "unknown format")):
        for command in (["scan", str(path), "--omega-max", "30"],
                        ["modes", str(path), "--count", "2"],
                        ["sweep", str(path), "--param", "L", "--from", "1", "--to", "2",
                         "--steps", "2", "--count", "1"]):
            assert main(command + ["--plot", str(bad)]) == 2
            err = capsys.readouterr().err
            assert message in err and "--plot" in err and err.count("\n") == 1


def test_map_without_marks_when_the_solver_cannot(monkeypatch):
    import symtmm.solve as solve_module

    def refuse(*args, **kwargs):
        raise ComputationError("damped models are not supported")
    monkeypatch.setitem(solve_module.METHODS, "default", refuse)
    s = scan(damped_pair(), omega_max=30, points=50, sigma_max=5, map_points=(11, 21))
    assert s.spectrum is None and "not marked" in s.notes[0]
    assert s.to_dict()["eigenvalues"] is None
    assert plot_scan_map(s).axes[0].get_legend() is None


# -- plots ------------------------------------------------------------------------------------

def test_plots_are_agg_figures_with_labelled_axes(tmp_path):
    modes = api.modes(PP, count=2, points=21, digits=10)
    fig = plot_modes(modes, variable="M")
    assert isinstance(fig, Figure) and fig.canvas.get_default_filetype() == "png"
    assert fig.axes[0].get_xlabel().startswith("x [m]")
    assert "EI" in fig.axes[0].get_ylabel()
    assert len(fig.axes[0].get_lines()) >= 2
    assert fig._repr_png_()[:4] == b"\x89PNG"

    s = scan(PP, omega_max=100, points=101)
    fig = plot_scan(s)
    assert "Omega" in fig.axes[0].get_xlabel() and "Delta" in fig.axes[0].get_ylabel()
    fig = plot_scan(s, frequency="omega")
    assert "rad/s" in fig.axes[0].get_xlabel()
    with pytest.raises(ValueError):
        plot_scan_map(s)

    model = api.loads('[parameters]\nk = 0\n[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\n'
                      'left = "pinned"\nright = "pinned"\n[[spring]]\nbetween = ["b", "ground"]\n'
                      'x = 0.5\nk = "k"\n')
    sw = api.sweep(model, "k", 0, 200, 3, count=2, digits=8, jobs=1)
    fig = plot_sweep(sw)
    lines = fig.axes[0].get_lines()
    assert len(lines) == len(sw.branch_ids()) == 2
    assert fig.axes[0].get_xlabel() == "k" and "Omega" in fig.axes[0].get_ylabel()
    assert list(lines[0].get_xdata()) == [0.0, 100.0, 200.0]
    # separate ranges (Omega_1 in [pi, 4.2], Omega_2 = 2 pi): one panel each, highest on top
    fig = plot_sweep(sw, panels=True, title="t")
    assert len(fig.axes) == 2
    assert fig.axes[0].get_lines()[0].get_ydata()[0] == pytest.approx(2 * math.pi)

    with pytest.raises(ModelError, match="--plot"):
        save_figure(fig, tmp_path / "no" / "such" / "dir.png")


# -- notebook representations and the api module ------------------------------------------------

def test_rich_representations():
    spectrum = api.solve(PP, count=2, digits=8)
    html, latex = spectrum._repr_html_(), spectrum._repr_latex_()
    assert html.startswith("<table>") and html.count("<tr>") == 3
    assert latex.startswith("$\\begin{array}") and latex.count("\\\\") == 3
    omega1 = f"{math.pi**2 * math.sqrt(2 / 3):.7f}"[:9]
    assert omega1 in html and omega1 in latex
    modes = api.modes(PP, count=1, points=5, spectrum=spectrum)
    assert "<table>" in modes._repr_html_() and "\\begin{array}" in modes._repr_latex_()
    assert "mass-normalised" in str(modes)


def _braces_pair(latex: str) -> bool:
    """The unescaped braces of ``latex`` pair up (no text closed a group it did not open)."""
    depth = 0
    for k, c in enumerate(latex):
        if c in "{}" and latex[k - 1] != "\\":
            depth += 1 if c == "{" else -1
            if depth < 0:
                return False
    return depth == 0


def test_display_escapes_any_text():
    """The notebook tables show text as written: markup in it stays text."""
    text = "b_1 <i>{x}</i> \\href{y}$&%#^~"
    latex = latex_text(text)
    assert _braces_pair(latex) and "\\href" not in latex and "\\backslash href\\{y\\}" in latex
    for special in "$&%#^~_":
        assert special not in latex.replace("\\" + special, "").replace("\\hat{}", "")
    html = html_table([text], [[text]], note=text)
    assert "<i>" not in html and html.count("&lt;i&gt;") == 3


def test_rich_representations_name_with_underscores():
    model = Model((Beam("upper_beam_1", EI="EI_a", m=3, L=1, left="pinned", right="pinned"),),
                  parameters={"EI_a": 2})
    spectrum = api.solve(model, count=1, digits=8)
    modes = api.modes(model, count=1, points=5, spectrum=spectrum)
    for latex in (spectrum._repr_latex_(), modes._repr_latex_()):
        assert "upper\\_beam\\_1}" in latex and _braces_pair(latex[1:-1])
    sw = api.sweep(model, "EI_a", 2, 3, 2, count=1, digits=6)
    assert sw._repr_html_().count("<tr>") == 3 and sw._repr_latex_().count("\\\\") == 3
    assert "\\mathrm{EI\\_a}" in sw._repr_latex_()


def test_api_load_with_overrides(examples_dir):
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml", K=1000, x1="0.25")
    resolved = model.resolved()
    assert [s.x for s in resolved.springs] == [sp.Rational(1, 4), sp.Rational(3, 4)]
    assert float(resolved.springs[0].k) == 1000
    with pytest.raises(ModelError):
        api.load(examples_dir / "missing.toml")
