"""Generated evaluators of Delta(lam): compiled and run, compared with the Python evaluator.

C and Fortran are built into shared libraries and called through ctypes (the
Fortran routine through its ``bind(C)`` interface, which is the contract);
Octave and Julia run when their interpreters are installed and are skipped
otherwise. References: ``symtmm.compile.Evaluator`` (double precision) and
its mpmath evaluation at 40 digits; eigenvalues from closed forms (Omega =
n pi for pinned-pinned beams) and from ``symtmm.solve``.
"""

from __future__ import annotations

import ctypes
import re
import shutil
import subprocess
import sys
from pathlib import Path

import mpmath
import numpy as np
import pytest

from symtmm.cli import main
from symtmm.codegen import LANGUAGES, generate
from symtmm.compile import Evaluator
from symtmm.modelfile import load, loads

EXAMPLES = str(Path(__file__).resolve().parent.parent / "examples") + "/"

MIXED = """
title = "mixed: offset beams, ground spring, dashpot"
[parameters]
k = 7
[[beam]]
name = "a"
EI = 2
m = 1
L = 1
left = "clamped"
right = "free"
[[beam]]
name = "b"
EI = 1
m = 3
L = 1.5
x0 = 0.25
left = "pinned"
right = "sliding"
[[spring]]
between = ["a", "b"]
x = 0.5
k = "k"
c = 0.3
[[spring]]
between = ["a", "ground"]
x = 1
k = 3
"""


LAYERS = """
title = "three beams joined by overlapping layers (one damped), and a spring"
[parameters]
K = 30
x1 = 0.3
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "clamped"
right = "free"
[[beam]]
name = "b"
EI = 2
m = 1.5
L = 1
left = "pinned"
right = "pinned"
kw = 4
[[beam]]
name = "c"
EI = 1
m = 1
L = 1
left = "free"
right = "clamped"
[[layer]]
between = ["a", "b"]
k = "K"
c = 0.5
to = 0.6
[[layer]]
between = ["b", "c"]
k = 20
from = "x1"
[[spring]]
between = ["a", "c"]
x = 0.8
k = 6
"""


RODS = """
[parameters]
k = 7
[[rod]]
name = "a"
EA = 2
m = 1
L = 1
left = "fixed"
right = "free"
[[rod]]
name = "s"
EA = 1
m = 2
L = 1.5
x0 = 0.25
GJ = 3
rhoIp = 0.5
left = "free"
right = "fixed-axial"
[[spring]]
between = ["a", "s"]
x = 0.6
k = "k"
c = 0.3
[[spring]]
between = ["s", "ground"]
x = 1
k = 4
kind = "torsional"
[[mass]]
beam = "s"
x = 1.75
M = 0.2
J = 0.1
"""


def _models():
    return {
        "ex1": (load(EXAMPLES + "paper_ex1_ff_cc.toml"), ()),
        "ex3_symbolic": (load(EXAMPLES + "paper_ex3_three_pp_coupled.toml"), ("K", "x1")),
        "mixed": (loads(MIXED, source="mixed.toml"), ()),
        "sprung_masses": (load(EXAMPLES + "tuned_mass_damper.toml"), ()),
        "layers": (loads(LAYERS, source="layers.toml"), ()),
        "layers_symbolic": (loads(LAYERS, source="layers.toml"), ("K", "x1")),
        "rods": (loads(RODS, source="rods.toml"), ()),
        "rods_symbolic": (loads(RODS, source="rods.toml"), ("k",)),
    }


MODELS = _models()


def _lams(rng, n=25, scale=12.0):
    """Imaginary (undamped), real (overdamped) and general complex eigenvalue probes."""
    return np.concatenate([
        1j * rng.uniform(0.05, scale, n),
        -rng.uniform(0.05, scale, n // 2),
        -rng.uniform(0, scale / 2, n) + 1j * rng.uniform(0, scale, n),
        [0.0, 1e-9j, 1e-4 + 1e-4j],
    ])


def _term_size(R):
    """Sum of the absolute values of the terms of det R: the permanent of |R| (Ryser)."""
    A = np.abs(np.asarray(R))
    n = A.shape[-1]
    total = np.zeros(A.shape[:-2])
    for mask in range(1, 1 << n):
        cols = [j for j in range(n) if mask >> j & 1]
        total += (-1) ** len(cols) * np.prod(A[..., cols].sum(axis=-1), axis=-1)
    return abs(total)


def _reference_model(model, symbolic, values):
    return model.with_parameters(**values) if symbolic else model


# --- building -------------------------------------------------------------------------


def _build(lang, source, tmp_path):
    if lang == "c":
        compiler = shutil.which("gcc") or shutil.which("cc")
        if compiler is None:
            pytest.skip("no C compiler")
        src, cmd = tmp_path / "delta.c", [compiler, "-std=c99", "-O2", "-Wall", "-Werror",
                                          "-pedantic"]
    else:
        compiler = shutil.which("gfortran")
        if compiler is None:
            pytest.skip("no Fortran compiler")
        src, cmd = tmp_path / "delta.f90", [compiler, "-std=f2008", "-O2", "-Wall", "-Werror",
                                            "-J", str(tmp_path)]
    src.write_text(source)
    lib = tmp_path / f"libdelta_{lang}.so"
    proc = subprocess.run(cmd + ["-shared", "-fPIC", "-o", str(lib), str(src)],
                          check=False, capture_output=True, text=True, cwd=tmp_path)
    assert proc.returncode == 0, proc.stderr
    return ctypes.CDLL(str(lib))


def _caller(lib, nparams):
    fn = lib.symtmm_delta
    fn.restype = None
    fn.argtypes = [ctypes.c_double] * (2 + nparams) + [ctypes.POINTER(ctypes.c_double)] * 2

    def delta(lams, *params):
        out = np.empty(len(lams), dtype=complex)
        re, im = ctypes.c_double(), ctypes.c_double()
        for i, lam in enumerate(lams):
            fn(lam.real, lam.imag, *params, ctypes.byref(re), ctypes.byref(im))
            out[i] = complex(re.value, im.value)
        return out

    return delta


def _generated(lang, source, tmp_path, nparams=0):
    """The generated ``symtmm_delta`` as a Python callable: the module run, or the
    C or Fortran built and called through ctypes."""
    if lang == "python":
        ns: dict = {}
        exec(source, ns)  # noqa: S102 - the generated module
        return ns["symtmm_delta"]
    return _caller(_build(lang, source, tmp_path), nparams)


@pytest.fixture(scope="module")
def compiled(tmp_path_factory):
    cache = {}

    def get(lang, name):
        key = (lang, name)
        if key not in cache:
            model, symbolic = MODELS[name]
            src = generate(model, lang, symbolic)
            lib = _build(lang, src, tmp_path_factory.mktemp(f"{lang}_{name}"))
            cache[key] = _caller(lib, len(symbolic))
        return cache[key]

    return get


def _python(name):
    model, symbolic = MODELS[name]
    ns: dict = {}
    exec(generate(model, "python", symbolic), ns)  # noqa: S102 - the generated module
    return ns["symtmm_delta"]


def _callable(lang, name, compiled):
    if lang == "python":
        return _python(name)
    return compiled(lang, name)


# --- agreement with the Python evaluator ------------------------------------------------


def _mp_reference(ev, lams, digits=40):
    """Delta at ``lams`` by the mpmath evaluator, and its condition ``|lam Delta' / Delta|``.

    The condition is what rounding the input ``lam`` to double costs anyone: a
    value is checked to ``1e-13 * (condition + 100)`` relative.
    """
    values, cond = [], []
    for lam in lams:
        z = mpmath.mpc(lam.real, lam.imag)
        with mpmath.workdps(digits + int(ev.digits_lost(lam))):
            d0 = ev.delta_mp(z)
            h = abs(z) * mpmath.mpf(10) ** -20 + mpmath.mpf(10) ** -30
            slope = (ev.delta_mp(z + h) - ev.delta_mp(z - h)) / (2 * h)
            values.append(complex(d0))
            cond.append(float(abs(z * slope / d0)) if d0 != 0 else np.inf)
    return np.array(values), np.array(cond)


_AGREE_REFERENCES: dict = {}


def _agree_reference(name):
    """The probes of a model and their 40-digit references, computed once for all languages."""
    if name not in _AGREE_REFERENCES:
        model, symbolic = MODELS[name]
        values = {"K": "40", "x1": "0.2", "k": "7"} if symbolic else {}
        ev = Evaluator(_reference_model(model, symbolic, values))
        lams = _lams(np.random.default_rng(7), n=60, scale=20.0)
        _AGREE_REFERENCES[name] = (lams, [float(values[p]) for p in symbolic],
                                   *_mp_reference(ev, lams))
    return _AGREE_REFERENCES[name]


@pytest.mark.parametrize("lang", ["c", "fortran", "python"])
@pytest.mark.parametrize("name", list(MODELS))
def test_agrees_with_mpmath(lang, name, compiled):
    """Real, imaginary and complex lam up to Omega ~ 4.5 per beam, against 40 digits."""
    delta = _callable(lang, name, compiled)
    lams, params, ref, cond = _agree_reference(name)
    got = delta(lams, *params)
    rel = np.abs(got - ref) / np.abs(ref)
    bound = 1e-13 * (cond + 100)
    assert np.all(rel <= bound), (lams[np.argmax(rel / bound)], np.max(rel / bound))
    assert np.median(rel) < 1e-13


@pytest.mark.parametrize("lang", ["c", "fortran", "python"])
def test_high_modes_of_a_clamped_beam_match_the_closed_form(lang, tmp_path):
    """Omega up to 120: Delta = (1 - cos Omega cosh Omega) / (2 Omega**4), all digits kept.

    A product of transfer matrices in double precision has lost every digit by
    Omega = 36; the generated code propagates orthonormalised columns instead.
    """
    from symtmm.model import Beam, Model

    model = Model((Beam("b", 1, 1, 1, left="clamped", right="clamped"),))
    delta = _generated(lang, generate(model, lang), tmp_path)
    Om = np.linspace(20.1, 120.3, 41)
    with mpmath.workdps(120):
        exact = np.array([complex((1 - mpmath.cos(o) * mpmath.cosh(o)) / (2 * o**4))
                          for o in Om])
    got = delta(1j * Om**2)
    assert np.max(np.abs(got / exact - 1)) < 1e-11


@pytest.mark.parametrize("lang", ["c", "fortran", "python"])
def test_high_modes_of_the_paper_example_match_mpmath(lang, compiled):
    """Example 1 (two beams, two springs) at Omega 20 to 60, undamped and damped lam."""
    model, _ = MODELS["ex1"]
    delta = _callable(lang, "ex1", compiled)
    ev = Evaluator(model)
    rng = np.random.default_rng(3)
    Om2 = rng.uniform(400, 3600, 16)
    lams = np.concatenate([1j * Om2[:8], -rng.uniform(0, 100, 8) + 1j * Om2[8:]])
    got = delta(lams)
    ref, cond = _mp_reference(ev, lams)
    rel = np.abs(got - ref) / np.abs(ref)
    assert np.all(rel <= 1e-13 * (cond + 1000)), np.max(rel)
    # Delta sits far below its terms here: a test of cancellation, not of easy points
    assert np.max(_term_size(ev.R(lams)) / np.abs(ref)) > 1e15


@pytest.mark.parametrize("lang", ["c", "fortran", "python"])
def test_vanishes_at_closed_form_roots(lang, tmp_path):
    """Three uncoupled pinned-pinned beams: Delta = 0 at omega = (n pi)**2 (triple roots)."""
    model = load(EXAMPLES + "paper_ex2_three_pp.toml")
    delta = _generated(lang, generate(model, lang), tmp_path)
    ev = Evaluator(model)
    for n in (1, 2, 3):
        lam = np.array([1j * (n * np.pi) ** 2])
        near = lam * np.array([1 - 1e-2, 1 + 1e-2])
        at = abs(delta(lam)[0])
        scale = _term_size(ev.R(lam))[0]
        assert at < 1e-12 * scale
        assert np.all(np.abs(delta(near)) > 1e6 * max(at, 1e-300))


@pytest.mark.parametrize("lang", ["c", "fortran", "python"])
@pytest.mark.parametrize("case", ["ex1", "ex4"])
def test_vanishes_at_computed_eigenvalues(lang, case, compiled, tmp_path):
    """|Delta| at the solver's eigenvalues is a billionth of its value 1e-3 away."""
    from symtmm.solve import solve

    if case == "ex1":
        model = MODELS["ex1"][0]
        delta = _callable(lang, "ex1", compiled)
        spectrum = solve(model, count=8, digits=16)
    else:
        model = load(EXAMPLES + "paper_ex4_damped.toml")
        delta = _generated(lang, generate(model, lang), tmp_path)
        spectrum = solve(model, omega_max=700, digits=16)
    assert len(spectrum.eigenvalues) >= 6
    for eig in spectrum.eigenvalues:
        if eig.lam == 0:
            continue
        lam = complex(eig.lam)
        at = abs(delta(np.array([lam]))[0])
        near = np.abs(delta(lam + 1e-3 * abs(lam) * np.array([1, -1, 1j, -1j])))
        assert np.all(near > 1e9 * at), (lam, at, near)


def test_names_that_mean_something_to_a_language_are_renamed(tmp_path):
    """Parameters called I (C's imaginary unit), E (the code's matrix; Fortran's e), end, U1."""
    text = MIXED.replace("[parameters]\nk = 7", "[parameters]\nk = 7\nI = 2\nE = 3\nend = 0.5"
                         "\nU1 = 1").replace('EI = 2', 'EI = "I"').replace('m = 3', 'm = "E"')
    text = text.replace("x = 0.5", 'x = "end"').replace("k = 3", 'k = "3*U1"')
    model = loads(text, source="names.toml")
    symbolic = ("E", "I", "U1", "end")
    ev = Evaluator(model)
    lams = _lams(np.random.default_rng(5), n=10, scale=8.0)
    ref = ev.delta(lams)
    args = (3.0, 2.0, 1.0, 0.5)
    for lang in ("c", "fortran", "python"):
        got = _generated(lang, generate(model, lang, symbolic), tmp_path, 4)(lams, *args)
        assert np.max(np.abs(got / ref - 1)) < 1e-12, lang
    assert "double p_I" in generate(model, "c", symbolic)
    assert "p_E" in generate(model, "fortran", symbolic)
    assert "p_end::Float64" in generate(model, "julia", symbolic)


@pytest.mark.parametrize("lang", ["c", "fortran", "python"])
def test_values_that_reverse_the_cuts_give_nan(lang, compiled):
    """Example 3 generated with x1 = 0.25 < 1/2: x1 = 0.7 would reverse x1 and 1 - x1."""
    delta = _callable(lang, "ex3_symbolic", compiled)
    assert np.isfinite(delta(np.array([5j]), 40.0, 0.2)).all()
    assert np.isnan(delta(np.array([5j]), 40.0, 0.7)).all()


# --- symbolic parameters become arguments ----------------------------------------------


def test_symbolic_parameters_are_arguments_in_order():
    model, symbolic = MODELS["ex3_symbolic"]
    c = generate(model, "c", symbolic)
    assert ("void symtmm_delta(double lam_re, double lam_im, double K, double x1, "
            "double *delta_re, double *delta_im)") in c
    f = generate(model, "fortran", symbolic)
    assert re.search(r"subroutine symtmm_delta\(lam_re, lam_im, K, x1, delta_re, delta_im\)", f)
    assert 'bind(C, name="symtmm_delta")' in f
    assert "real(c_double), value, intent(in) :: lam_re, lam_im, K, x1" in f
    assert "function d = symtmm_delta(lam, K, x1)" in generate(model, "octave", symbolic)
    assert "function symtmm_delta(lam::ComplexF64, K::Float64, x1::Float64)::ComplexF64" in \
        generate(model, "julia", symbolic)
    assert "def symtmm_delta(lam, K, x1):" in generate(model, "python", symbolic)


def test_contract_signatures_without_parameters():
    model, _ = MODELS["ex1"]
    assert ("void symtmm_delta(double lam_re, double lam_im, double *delta_re, "
            "double *delta_im)") in generate(model, "c")
    assert "function d = symtmm_delta(lam)" in generate(model, "octave")
    assert "function symtmm_delta(lam::ComplexF64)::ComplexF64" in generate(model, "julia")


@pytest.mark.parametrize("lang", LANGUAGES)
def test_header_names_model_and_values(lang):
    model, _ = MODELS["ex1"]
    src = generate(model, lang)
    head = src[:1500]
    assert "paper_ex1_ff_cc.toml" in head
    assert "K = 100" in head and "x1 = 3/10" in head


def test_python_output_needs_numpy_only_and_keeps_shape():
    model, symbolic = MODELS["ex3_symbolic"]
    src = generate(model, "python", symbolic)
    imports = {line.split()[1] for line in src.splitlines()
               if line.startswith(("import ", "from "))}
    assert imports == {"numpy"}
    fn = _python("ex3_symbolic")
    lam = np.array([[1j, 2j], [3j, 4j]])
    assert fn(lam, 25.0, 0.25).shape == (2, 2)


def test_constants_are_exact_to_double():
    """1/(4k+j)! and irrational parameters are printed to round-trip to the nearest double."""
    model = loads("""
[parameters]
EI = "(146.2698/pi**2)**2"
[[beam]]
name = "b"
EI = "EI"
m = 1
L = 1
left = "pinned"
right = "pinned"
""")
    src = generate(model, "c")
    exact = (146.2698 / np.pi**2) ** 2
    numbers = [float(x) for x in re.findall(r"\d+\.\d+(?:e[-+]?\d+)?", src)]
    assert any(abs(x - exact) <= 2e-16 * exact for x in numbers)
    assert repr(1 / 362880) in src  # 1/9!


# --- other interpreters, when installed -----------------------------------------------


@pytest.mark.parametrize("name", ["ex1", "layers"])
def test_octave_runs_when_installed(tmp_path, name):
    octave = shutil.which("octave-cli") or shutil.which("octave")
    if octave is None:
        pytest.skip("Octave is not installed")
    model, _ = MODELS[name]
    (tmp_path / "symtmm_delta.m").write_text(generate(model, "octave"))
    lams = np.array([2j, 35j, -3 + 20j])
    expr = "[" + ", ".join(f"complex({float(z.real)!r}, {float(z.imag)!r})" for z in lams) + "]"
    proc = subprocess.run([octave, "--no-gui", "--quiet", "--eval",
                           (f"d = symtmm_delta({expr}); printf('%.17g %.17g\\n', "
                            "[real(d); imag(d)])")],
                          check=False, capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr
    got = np.array([complex(*map(float, ln.split())) for ln in proc.stdout.split("\n")
                    if ln.strip()])
    ref = Evaluator(model).delta(lams)
    assert np.max(np.abs(got - ref) / np.abs(ref)) < 1e-12


@pytest.mark.parametrize("name", ["ex1", "layers"])
def test_julia_runs_when_installed(tmp_path, name):
    julia = shutil.which("julia")
    if julia is None:
        pytest.skip("Julia is not installed")
    model, _ = MODELS[name]
    (tmp_path / "delta.jl").write_text(generate(model, "julia"))
    lams = np.array([2j, 35j, -3 + 20j])
    calls = "; ".join(f"d = symtmm_delta(ComplexF64({z.real!r}, {z.imag!r})); "
                      "println(real(d), \" \", imag(d))" for z in lams)
    proc = subprocess.run([julia, "--startup-file=no", "-e", f'include("delta.jl"); {calls}'],
                          check=False, capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    got = np.array([complex(*map(float, ln.split())) for ln in proc.stdout.split("\n")
                    if ln.strip()])
    ref = Evaluator(model).delta(lams)
    assert np.max(np.abs(got - ref) / np.abs(ref)) < 1e-12


# --- command line ---------------------------------------------------------------------


def test_cli_writes_file(tmp_path, capsys):
    out = tmp_path / "delta.c"
    assert main(["codegen", EXAMPLES + "paper_ex1_ff_cc.toml", "--lang", "c", "-o",
                 str(out)]) == 0
    assert "void symtmm_delta(" in out.read_text()
    assert main(["codegen", EXAMPLES + "paper_ex3_three_pp_coupled.toml", "--lang", "python",
                 "--symbolic", "K,x1"]) == 0
    assert "def symtmm_delta(lam, K, x1):" in capsys.readouterr().out


def test_cli_errors_are_one_line(tmp_path):
    proc = subprocess.run([sys.executable, "-m", "symtmm", "codegen",
                           EXAMPLES + "paper_ex1_ff_cc.toml", "--lang", "c", "--symbolic", "Q"],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "'Q' is not a parameter" in proc.stderr
    proc = subprocess.run([sys.executable, "-m", "symtmm", "codegen",
                           EXAMPLES + "paper_ex1_ff_cc.toml", "--lang", "cobol"],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 2
