"""Generated code from hostile models: the model's text is data, never code.

A title, a source path or a parameter's name or value is written into the
header comment of every generated file. Each hostile text below is built to
escape that comment in one language (close a C block comment and add a
function or a constructor that calls ``system()``, end a Python docstring, put
a line into the body of an Octave function, add a Fortran module, leave a
Julia comment ...). Each payload, if it ran, would create a marker file or
define a symbol. For every language and every text the tests check that

* only header comment lines differ from the code generated for a benign
  title, and every header line is an inert comment of its language;
* C and Fortran compile to shared objects with exactly the symbols (defined
  text symbols, exported symbols) and the constructor table of the benign
  build, load without creating the marker and evaluate the right Delta;
* the Python module compiles, imports from a file, defines exactly the
  benign module's top-level names and evaluates the right Delta;
* Octave runs it, prints nothing else and creates no marker (when installed);
  Julia runs it when installed, and its text is checked otherwise.

Parameter names that collide with keywords, builtins, macros or the code's own
names (and symbol names no model file allows) must become distinct safe
arguments, listed in the header, with which every language evaluates the
Delta of the model with the values substituted.
"""

from __future__ import annotations

import ctypes
import importlib.util
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from symtmm.codegen import LANGUAGES, generate
from symtmm.compile import Evaluator
from symtmm.model import Beam, Model, Spring

MARKER = "symtmm_payload_ran"

# Texts that escape a comment somewhere, each meant to create MARKER or define symtmm_pwn.
HOSTILE_TEXTS = {
    "c function": "ok */ int symtmm_pwn(void){return 42;} /*",
    "c constructor": ("x */ __attribute__((constructor)) static void symtmm_pwn(void) "
                      f'{{ extern int system(const char *); system("touch {MARKER}"); }} /*'),
    "c include and constructor": ("x */\n#include <stdlib.h>\n__attribute__((constructor)) "
                                  f'static void symtmm_pwn(void) {{ system("touch {MARKER}"); }}'
                                  "\n/*"),
    "c trigraph": "ends in ??/",
    "python docstring": f'x """\nopen("{MARKER}", "w")\nsymtmm_pwn = 1\n"""',
    "python single quotes": f"x '''\nopen('{MARKER}', 'w')\nsymtmm_pwn = 1\n'''",
    "python cookie": f"# -*- coding: utf-7 -*-\n+AAo-open('{MARKER}', 'w')",
    "backslashes": "C:\\Users\\me\\",
    "newline": f"title\nopen('{MARKER}', 'w'); system('touch {MARKER}');",
    "carriage return": f"title\rsymtmm_pwn = 1\r\nsystem('touch {MARKER}');",
    "octave block": f"%}}\nsystem('touch {MARKER}');\n%{{",
    "octave line": f"t\n  system('touch {MARKER}');\n%",
    "fortran": ("a ! b & \n&  end subroutine symtmm_delta\nend module symtmm_delta_mod\n"
                'module evil\ncontains\nsubroutine symtmm_pwn() bind(C, name="symtmm_pwn")\n'
                "end subroutine\nend module evil\n"),
    "fortran continuation": "x &\n  ; call execute_command_line('touch " + MARKER + "')",
    "julia": f"=# run(`touch {MARKER}`) #=",
    "julia newline": f"t\nrun(`touch {MARKER}`)",
    "unicode separators": f"a\u2028open('{MARKER}', 'w')\u0085system('touch {MARKER}')\u2029",
    "nul": "a\x00b\x00",
    "ansi": "\x1b[31mred\x1b[0m\x1b]0;title\x07",
    "long": "x" * 400 + " */ int symtmm_pwn(void){return 1;} /*",
}


def _model(title="benign", source="benign.toml", K_name="K"):
    """A pinned-pinned beam on a ground spring of stiffness ``K`` (kept symbolic)."""
    return Model((Beam("a", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                 (Spring("a", "ground", x="3/10", k=K_name),), {K_name: 50},
                 title=title, source=source)


LAMS = np.array([2j, 9.5j, 35j, -1 + 20j, -0.5])


def _reference(model):
    return Evaluator(model).delta(LAMS)


# --- the header ------------------------------------------------------------------------


def _split_header(src: str, lang: str):
    """``(header comment lines, every other line)`` of a generated file."""
    lines = src.split("\n")
    if lang == "c":
        end = lines.index(" */")
        return lines[:end + 1], lines[end + 1:]
    if lang == "octave":
        n = 1
        while lines[n].startswith("%"):
            n += 1
        return lines[1:n], lines[:1] + lines[n:]
    if lang == "python":
        n = 2
        while lines[n].startswith("#"):
            n += 1
        return lines[2:n], lines[:2] + lines[n:]
    marker = {"fortran": "!", "julia": "#"}[lang]
    n = 0
    while lines[n].startswith(marker):
        n += 1
    return lines[:n], lines[n:]


def _inert(line: str, lang: str) -> bool:
    """Whether ``line`` is a comment its language cannot end early, reopen or continue."""
    if not re.fullmatch(r"[\x20-\x7e]*", line):
        return False
    if lang == "c":
        if line in ("/*", " */"):
            return True
        return (line == " *" or line.startswith(" * ")) and "*/" not in line[2:] \
            and "/*" not in line and "??" not in line
    prefix = {"fortran": "!", "octave": "%", "julia": "#", "python": "#"}[lang]
    if not line.startswith(prefix):
        return False
    if lang == "octave":
        return line.strip() not in ("%{", "%}", "#{", "#}")
    if lang == "julia":
        return "#=" not in line and "=#" not in line
    return True


@pytest.mark.parametrize("lang", LANGUAGES)
@pytest.mark.parametrize("name", list(HOSTILE_TEXTS))
def test_hostile_title_only_changes_inert_comment_lines(lang, name):
    text = HOSTILE_TEXTS[name]
    benign_head, benign_code = _split_header(generate(_model(), lang, ("K",)), lang)
    for model in (_model(title=text), _model(source=text)):
        head, code = _split_header(generate(model, lang, ("K",)), lang)
        assert code == benign_code
        assert all(_inert(line, lang) for line in head), [ln for ln in head
                                                          if not _inert(ln, lang)]
        assert all(len(line) <= 110 for line in head)
    assert len(head) >= len(benign_head)


def test_the_header_still_shows_the_title():
    src = generate(_model(title="free-free beam, K = 50 */ x"), "c")
    assert "free-free beam, K = 50 * / x" in src
    src = generate(_model(title="Träger\nzwei"), "python")
    assert "Tr\\xe4ger\\nzwei" in src


# --- compiled: C and Fortran -----------------------------------------------------------


def _compile_shared(lang, source, workdir: Path) -> Path:
    """Build ``source`` into a shared object (not loaded: its symbols are read first)."""
    workdir.mkdir(parents=True, exist_ok=True)
    if lang == "c":
        compiler = shutil.which("gcc") or shutil.which("cc")
        src, cmd = workdir / "delta.c", [compiler, "-std=c99", "-O2", "-Wall", "-Werror",
                                         "-pedantic"]
    else:
        compiler = shutil.which("gfortran")
        src, cmd = workdir / "delta.f90", [compiler, "-std=f2008", "-O2", "-Wall", "-Werror",
                                           "-J", str(workdir)]
    if compiler is None:
        pytest.skip(f"no {lang} compiler")
    src.write_text(source)
    lib = workdir / f"libdelta_{lang}.so"
    proc = subprocess.run(cmd + ["-shared", "-fPIC", "-o", str(lib), str(src)],
                          check=False, capture_output=True, text=True, cwd=workdir)
    assert proc.returncode == 0, proc.stderr
    return lib


def _symbols(lib: Path) -> dict:
    """Defined text symbols (local and global), exported symbols and the constructor table."""
    if shutil.which("nm") is None or shutil.which("readelf") is None:
        pytest.skip("nm or readelf missing")
    full = subprocess.run(["nm", "--defined-only", str(lib)], check=True, capture_output=True,
                          text=True).stdout.split("\n")
    text = {ln.split()[2] for ln in full if len(ln.split()) == 3 and ln.split()[1] in "Tt"}
    dynamic = subprocess.run(["nm", "-D", "--defined-only", str(lib)], check=True,
                             capture_output=True, text=True).stdout.split("\n")
    exported = {ln.split()[2] for ln in dynamic if len(ln.split()) == 3}
    sections = subprocess.run(["readelf", "-SW", str(lib)], check=True, capture_output=True,
                              text=True).stdout
    init = re.search(r"\.init_array\s+\S+\s+\S+\s+\S+\s+(\S+)", sections)
    return {"text": text, "exported": exported, "init_array": init.group(1) if init else None}


def _call(lib: Path, nparams: int):
    fn = ctypes.CDLL(str(lib)).symtmm_delta
    fn.restype = None
    fn.argtypes = [ctypes.c_double] * (2 + nparams) + [ctypes.POINTER(ctypes.c_double)] * 2

    def delta(lams, *params):
        out = np.empty(len(lams), dtype=complex)
        re_, im_ = ctypes.c_double(), ctypes.c_double()
        for i, lam in enumerate(lams):
            fn(lam.real, lam.imag, *params, ctypes.byref(re_), ctypes.byref(im_))
            out[i] = complex(re_.value, im_.value)
        return out

    return delta


@pytest.fixture(scope="module")
def benign_symbols(tmp_path_factory):
    cache = {}

    def get(lang):
        if lang not in cache:
            lib = _compile_shared(lang, generate(_model(), lang),
                                  tmp_path_factory.mktemp(f"benign_{lang}"))
            cache[lang] = _symbols(lib)
        return cache[lang]

    return get


@pytest.mark.parametrize("lang", ["c", "fortran"])
@pytest.mark.parametrize("name", list(HOSTILE_TEXTS))
def test_compiled_code_defines_only_the_evaluator(lang, name, tmp_path, benign_symbols,
                                                  monkeypatch):
    monkeypatch.chdir(tmp_path)                 # where a payload would touch its marker
    model = _model(title=HOSTILE_TEXTS[name], source=HOSTILE_TEXTS[name])
    lib = _compile_shared(lang, generate(model, lang), tmp_path / "build")
    symbols = _symbols(lib)
    assert symbols == benign_symbols(lang)
    assert "symtmm_delta" in symbols["exported"]
    assert not any("pwn" in s for s in symbols["text"] | symbols["exported"])
    got = _call(lib, 0)(LAMS)
    assert not (tmp_path / MARKER).exists()
    assert np.max(np.abs(got / _reference(model) - 1)) < 1e-12


# --- Python ----------------------------------------------------------------------------


def _top_level_names(source: str) -> set:
    namespace: dict = {}
    exec(compile(source, "<generated>", "exec"), namespace)  # noqa: S102 - the generated module
    return set(namespace) - {"__builtins__"}


@pytest.mark.parametrize("name", list(HOSTILE_TEXTS))
def test_python_module_defines_only_the_evaluator(name, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    model = _model(title=HOSTILE_TEXTS[name], source=HOSTILE_TEXTS[name])
    source = generate(model, "python")
    assert _top_level_names(source) == _top_level_names(generate(_model(), "python"))
    # imported from a file: Python reads an encoding declaration in its first two lines
    path = tmp_path / "hostile_delta.py"
    path.write_text(source, encoding="utf-8")
    spec = importlib.util.spec_from_file_location("hostile_delta", path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    assert not hasattr(module, "symtmm_pwn")
    assert not (tmp_path / MARKER).exists()
    got = module.symtmm_delta(LAMS)
    assert np.max(np.abs(got / _reference(model) - 1)) < 1e-12


# --- Octave and Julia --------------------------------------------------------------------


def test_octave_runs_only_the_evaluator(tmp_path):
    octave = shutil.which("octave-cli") or shutil.which("octave")
    if octave is None:
        pytest.skip("Octave is not installed")
    names = list(HOSTILE_TEXTS)
    for i, name in enumerate(names):
        model = _model(title=HOSTILE_TEXTS[name], source=HOSTILE_TEXTS[name])
        (tmp_path / f"case{i}").mkdir()
        (tmp_path / f"case{i}" / "symtmm_delta.m").write_text(generate(model, "octave"))
    lam = "[" + ", ".join(f"complex({float(z.real)!r}, {float(z.imag)!r})" for z in LAMS) + "]"
    # one interpreter for every case: cd into each directory, forget the last function
    script = "".join(f"cd('{tmp_path / f'case{i}'}'); clear symtmm_delta; "
                     f"d = symtmm_delta({lam}); printf('case{i} '); "
                     "printf('%.17g %.17g ', [real(d); imag(d)]); printf('\\n'); "
                     for i in range(len(names)))
    proc = subprocess.run([octave, "--no-gui", "--quiet", "--no-window-system", "--eval",
                           script], check=False, capture_output=True, text=True,
                          cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    lines = [ln for ln in proc.stdout.split("\n") if ln.strip()]
    assert [ln.split()[0] for ln in lines] == [f"case{i}" for i in range(len(names))]
    ref = _reference(_model())
    for ln in lines:
        values = np.array(ln.split()[1:], dtype=float)
        got = values[0::2] + 1j * values[1::2]
        assert np.max(np.abs(got / ref - 1)) < 1e-12, ln
    assert not list(tmp_path.rglob(MARKER))


def test_julia_text_keeps_the_payload_in_comments(tmp_path):
    """Every hostile text leaves a file whose lines outside the header are the benign ones
    (above); here the header is also read the way Julia's parser reads comments."""
    for name, text in HOSTILE_TEXTS.items():
        src = generate(_model(title=text, source=text), "julia")
        head, _ = _split_header(src, "julia")
        # no block comment opens, so each line comment ends at its newline
        assert not any("#=" in ln or "=#" in ln for ln in head), name
        assert all(ln.startswith("# ") or ln == "#" for ln in head), name
    julia = shutil.which("julia")
    if julia is None:
        return
    lam = ", ".join(f"ComplexF64({float(z.real)!r}, {float(z.imag)!r})" for z in LAMS)
    for i, text in enumerate(HOSTILE_TEXTS.values()):
        path = tmp_path / f"delta{i}.jl"
        path.write_text(generate(_model(title=text, source=text), "julia"))
        proc = subprocess.run([julia, "--startup-file=no", "-e",
                               (f'include("{path.name}"); for z in [{lam}]; d = symtmm_delta(z); '
                                'println(real(d), " ", imag(d)); end; '
                                'println(isdefined(Main, :symtmm_pwn))')],
                              check=False, capture_output=True, text=True, cwd=tmp_path,
                              timeout=300)
        assert proc.returncode == 0, proc.stderr
        assert proc.stdout.split("\n")[-2] == "false"
    assert not list(tmp_path.rglob(MARKER))


# --- the command line ------------------------------------------------------------------


HOSTILE_FILE = """
title = "ok */ int symtmm_pwn(void){return 42;} /*\\n#include <stdlib.h>\\n\\u2028\\u001b[2J"
[parameters]
K = 50
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"
[[spring]]
between = ["a", "ground"]
x = 0.3
k = "K"
"""


@pytest.mark.parametrize("lang", LANGUAGES)
def test_command_line_writes_inert_headers(lang, tmp_path):
    # a path is free text too: "x\n*" is a directory, so the path reads "x\n*/ int ..."
    (tmp_path / "x\n*").mkdir()
    model_file = tmp_path / "x\n*" / " int symtmm_pwn(void){return 1;} .toml"
    model_file.write_text(HOSTILE_FILE, encoding="utf-8")
    out = tmp_path / f"delta{lang}"
    proc = subprocess.run([sys.executable, "-m", "symtmm", "codegen", str(model_file),
                           "--lang", lang, "-o", str(out)],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    head, _ = _split_header(out.read_text(), lang)
    assert all(_inert(line, lang) for line in head)
    assert any("symtmm_pwn" in line for line in head)  # shown, as data


# --- parameter names -------------------------------------------------------------------

# Names that mean something to a language or to the generated code: keywords, builtins,
# macros, the code's locals and globals, case twins for Fortran.
COLLIDING_NAMES = [
    "complex", "float", "int", "range", "len", "sum", "min", "max", "abs", "sqrt", "exp",
    "log", "np", "numpy", "I", "J", "E", "e", "K", "k", "end", "function", "lam", "lam2",
    "lam_re", "delta_re", "pi", "i", "j", "D", "R", "U", "U1", "th0", "nu1", "s0", "core",
    "steps", "logscale", "grown", "NS", "NU_STEP", "NAN", "M_PI", "HUGE_VAL", "linux",
    "unix", "double", "void", "register", "restrict", "dp", "ns", "real", "cmplx",
    "module", "contains", "intent", "value", "zeros", "Int", "Float64", "im", "nargin",
    "ans", "varargin", "True", "None", "lambda", "def", "if", "in", "p_I", "symtmm_delta",
    "_hidden", "x" * 80,
]
# Names a symbol built in Python can have and a model file cannot.
HOSTILE_NAMES = ["K */ int symtmm_pwn(void){return 1;} /*", "a\nb", "x y", "Träger",
                 "=# run(`id`) #=", "c; system('id')"]


def _named_model(names, values=None):
    """One beam whose ground spring has k = sum (i + 1) P_i / n; the first P also in EI.

    Each parameter enters with its own weight, so that arguments passed in the
    wrong order give another Delta. ``values`` (exact) substitute the symbols.
    """
    symbols = [sp.Symbol(n) if n == "I" else sp.Symbol(n, positive=True) for n in names]
    terms = values if values is not None else symbols
    k = sum((i + 1) * t for i, t in enumerate(terms)) / len(terms)
    return Model((Beam("a", EI=1 + terms[0] / 10, m=1, L=1, left="pinned", right="pinned"),),
                 (Spring("a", "ground", x="3/10", k=k),), title="names")


def _values(n):
    return [sp.Rational(100 + 37 * i, 100) for i in range(n)]


@pytest.fixture(scope="module")
def named_case():
    names = COLLIDING_NAMES + HOSTILE_NAMES
    values = _values(len(names))
    model = _named_model(names)
    reference = _reference(_named_model(names, values))
    # arguments come in the alphabetical order of the parameters' names
    order = sorted(range(len(names)), key=lambda i: names[i])
    assert list(model.free_symbols) == [names[i] for i in order]
    return model, [float(values[i]) for i in order], reference


def _signature_args(src: str, lang: str) -> list:
    pattern = {"c": r"void symtmm_delta\(([^)]*)\)", "python": r"def symtmm_delta\(([^)]*)\)",
               "octave": r"function d = symtmm_delta\(([^)]*)\)",
               "julia": r"function symtmm_delta\(([^)]*)\)",
               "fortran": r"subroutine symtmm_delta\(([^)]*)\)"}[lang]
    text = re.sub(r"&\s*\n\s*", "", re.search(pattern, src, re.DOTALL).group(1))
    args = [a.strip().split()[-1].split("::")[0].lstrip("*") for a in text.split(",")]
    return {"c": args[2:-2], "fortran": args[2:-2]}.get(lang, args[1:])


@pytest.mark.parametrize("lang", LANGUAGES)
def test_arguments_are_distinct_safe_identifiers(lang, named_case):
    model, _, _ = named_case
    src = generate(model, lang)
    args = _signature_args(src, lang)
    assert len(args) == len(model.free_symbols)
    folded = [a.lower() if lang == "fortran" else a for a in args]
    assert len(set(folded)) == len(folded)
    assert all(re.fullmatch(r"[A-Za-z][A-Za-z_0-9]{0,62}", a) for a in args), args
    head, _ = _split_header(src, lang)
    # the comments' text, with wrapped lines joined
    header = re.sub(r"\s+", " ", " ".join(re.sub(r"^\s*[*!%#]", "", ln) for ln in head))
    for name, arg in zip(model.free_symbols, args):
        if arg != name:      # every renamed argument is listed with its parameter
            assert f"{arg} (parameter " in header
    # C, Fortran, Octave and Python call complex(...) or declare complex; Julia does not
    assert ("p_complex (parameter complex)" in header) == (lang != "julia")
    assert all(_inert(line, lang) for line in head)


@pytest.mark.parametrize("lang", ["c", "fortran"])
def test_compiled_arguments_with_colliding_names_evaluate_delta(lang, named_case, tmp_path):
    model, args, reference = named_case
    lib = _compile_shared(lang, generate(model, lang), tmp_path)
    got = _call(lib, len(args))(LAMS, *args)
    assert np.max(np.abs(got / reference - 1)) < 1e-12


def test_python_arguments_with_colliding_names_evaluate_delta(named_case):
    model, args, reference = named_case
    namespace: dict = {}
    exec(generate(model, "python"), namespace)  # noqa: S102 - the generated module
    got = namespace["symtmm_delta"](LAMS, *args)
    assert np.max(np.abs(got / reference - 1)) < 1e-12
    # keyword arguments: a parameter keeps its name unless that name is taken
    src = generate(_named_model(["K", "x1"]), "python")
    assert "def symtmm_delta(lam, K, x1):" in src


def test_octave_arguments_with_colliding_names_evaluate_delta(named_case, tmp_path):
    octave = shutil.which("octave-cli") or shutil.which("octave")
    if octave is None:
        pytest.skip("Octave is not installed")
    model, args, reference = named_case
    (tmp_path / "symtmm_delta.m").write_text(generate(model, "octave"))
    lam = "[" + ", ".join(f"complex({float(z.real)!r}, {float(z.imag)!r})" for z in LAMS) + "]"
    call = ", ".join([lam] + [repr(a) for a in args])
    proc = subprocess.run([octave, "--no-gui", "--quiet", "--no-window-system", "--eval",
                           (f"d = symtmm_delta({call}); printf('%.17g %.17g\\n', "
                            "[real(d); imag(d)])")],
                          check=False, capture_output=True, text=True, cwd=tmp_path, timeout=120)
    assert proc.returncode == 0, proc.stderr
    got = np.array([complex(*map(float, ln.split())) for ln in proc.stdout.split("\n")
                    if ln.strip()])
    assert np.max(np.abs(got / reference - 1)) < 1e-12


# Julia's keywords (the manual's list, Julia 1.11) and names of Base the generated code
# calls: checked on the text, and run when julia is installed.
JULIA_KEYWORDS = {"baremodule", "begin", "break", "catch", "const", "continue", "do", "else",
                  "elseif", "end", "export", "false", "finally", "for", "function", "global",
                  "if", "import", "let", "local", "macro", "module", "public", "quote",
                  "return", "struct", "true", "try", "using", "while", "abstract", "mutable",
                  "primitive", "type", "where", "in", "isa", "outer"}


def test_julia_arguments_with_colliding_names(named_case, tmp_path):
    model, args, reference = named_case
    src = generate(model, "julia")
    names = _signature_args(src, "julia")
    assert not set(names) & JULIA_KEYWORDS
    body = src[src.index("function symtmm_delta("):]
    body = re.sub(r"#[^\n]*", "", body[body.index("\n"):])
    for used in ("abs", "exp", "log", "zeros", "max", "ceil", "Int", "Float64", "ComplexF64",
                 "transpose", "lam", "lam2", "D", "E"):
        assert used in re.findall(r"\b\w+\b", body) and used not in names
    julia = shutil.which("julia")
    if julia is None:
        return
    (tmp_path / "delta.jl").write_text(src)
    call = ", ".join(repr(a) for a in args)
    lines = "; ".join(f"d = symtmm_delta(ComplexF64({float(z.real)!r}, {float(z.imag)!r}), "
                      f"{call}); println(real(d), \" \", imag(d))" for z in LAMS)
    proc = subprocess.run([julia, "--startup-file=no", "-e", f'include("delta.jl"); {lines}'],
                          check=False, capture_output=True, text=True, cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stderr
    got = np.array([complex(*map(float, ln.split())) for ln in proc.stdout.split("\n")
                    if ln.strip()])
    assert np.max(np.abs(got / reference - 1)) < 1e-12


def test_c_names_avoid_every_macro_of_the_included_headers(tmp_path):
    """The object-like macros <complex.h> and <math.h> define, as gcc sees them, strict
    and GNU: a parameter with such a name (linux, M_PI, HUGE_VALF, CMPLX) is renamed."""
    from symtmm.codegen import _argument_names

    compiler = shutil.which("gcc") or shutil.which("cc")
    if compiler is None:
        pytest.skip("no C compiler")
    (tmp_path / "h.c").write_text("#include <complex.h>\n#include <math.h>\n")
    macros = set()
    for flags in (["-std=c99"], ["-std=gnu99"], ["-std=gnu11", "-D_GNU_SOURCE"]):
        out = subprocess.run([compiler, *flags, "-dM", "-E", str(tmp_path / "h.c")],
                             check=True, capture_output=True, text=True).stdout
        macros |= {m for m in re.findall(r"^#define (\w+)", out, re.MULTILINE)
                   if not m.startswith("_")}
    assert {"I", "complex", "NAN", "linux"} <= macros
    kept = [m for m in sorted(macros) if _argument_names([m], "c") == [m]]
    assert kept == []


def test_python_names_avoid_every_builtin_and_keyword():
    import builtins
    import keyword

    from symtmm.codegen import _argument_names

    names = sorted(n for n in dir(builtins) if n[:1].islower()) + keyword.kwlist
    kept = [n for n in names if _argument_names([n], "python") == [n]]
    assert kept == []


def test_octave_names_avoid_every_keyword():
    from symtmm.codegen import _argument_names

    octave = shutil.which("octave-cli") or shutil.which("octave")
    if octave is None:
        pytest.skip("Octave is not installed")
    proc = subprocess.run([octave, "--no-gui", "--quiet", "--eval",
                           "k = iskeyword(); printf('%s\\n', k{:});"],
                          check=False, capture_output=True, text=True, timeout=120)
    keywords = [k for k in proc.stdout.split() if k]
    assert "endfunction" in keywords
    kept = [k for k in keywords if _argument_names([k], "octave") == [k]]
    assert kept == []


NAMES_FILE = """
[parameters]
complex = 2
int = 3
range = 0.5
end = 1.5
I = 4
E = 1.25
lam = 7
np = 0.75
[[beam]]
name = "a"
EI = "E"
m = "np + end/3"
L = 1
left = "pinned"
right = "pinned"
[[spring]]
between = ["a", "ground"]
x = "range/2"
k = "complex*int + I*lam"
"""


def test_command_line_python_with_builtin_names_evaluates_delta(tmp_path):
    """The report: parameters called complex, int, range ... broke the generated Python."""
    from symtmm.modelfile import loads

    path = tmp_path / "names.toml"
    path.write_text(NAMES_FILE)
    out = tmp_path / "delta.py"
    symbolic = "complex,int,range,end,I,E,lam,np"
    proc = subprocess.run([sys.executable, "-m", "symtmm", "codegen", str(path), "--lang",
                           "python", "--symbolic", symbolic, "-o", str(out)],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    model = loads(NAMES_FILE)
    spec = importlib.util.spec_from_file_location("names_delta", out)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    values = {n: float(model.parameters[n]) for n in sorted(symbolic.split(","))}
    got = module.symtmm_delta(LAMS, *values.values())
    assert np.max(np.abs(got / _reference(model) - 1)) < 1e-12


@pytest.mark.parametrize("lang", LANGUAGES)
def test_a_constant_beyond_the_double_range_is_refused(lang):
    """Its repr, inf, would be a name in the code (one a parameter could have been).

    The model refuses such a value before code generation sees it (the limits of
    symtmm.limits); codegen's own check stays as a second line.
    """
    from symtmm.errors import ModelError

    with pytest.raises(ModelError, match="larger than 1e300|beyond the range of double"):
        generate(Model((Beam("a", EI="10**400", m=1, L=1, left="pinned", right="pinned"),)),
                 lang)
