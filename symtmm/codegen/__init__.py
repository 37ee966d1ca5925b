"""Self-contained evaluators of ``Delta(lam) = det R(lam)`` in C, Fortran, Octave, Julia, Python.

Structure of the generated code
-------------------------------
The generated code follows :meth:`symtmm.compile.Evaluator.log_delta` rather
than printing one expanded determinant: the closed form (see
:mod:`symtmm.characteristic`) sums terms that grow like ``exp(beta L)`` with
opposite signs and has thousands of operations for multilevel models. The
generated code instead

1. builds each segment's transfer matrix for the segment cut into ``n`` equal
   steps of ``|beta| l / n <= NU_STEP`` (``n`` from ``lam`` at run time,
   ``|beta|`` the bound on the wave numbers of
   :meth:`~symtmm.elements.theories.BeamSegment.wave_number`):

   * a plain Euler–Bernoulli segment from the entire functions ``c_j(x) =
     sum_k x**k / (4k+j)!`` of ``x = -lam**2 m l**4 / EI`` (a 16-term series
     below ``|x| = 1``, closed forms in ``x**(1/4)`` above), with no branch to
     choose and no 0/0 at ``lam = 0``;
   * any other segment (axial force ``N``, rotary inertia ``rhoI``, shear
     stiffness ``kGA``) as :mod:`symtmm.elements.theories` does: the series of
     ``alpha0, beta0, alpha1, beta1`` in ``(t, d)`` (trace and determinant of
     ``G = B C``) over a piece short enough that ``max|r| h**2 <= 1``, then the
     doubling formulas back to the whole step;

2. measures the state of every beam in units of its wave number ``b``:
   ``[Y, Theta/b, M/(EI b**2), Q/(EI b**3)]``, and each virtual variable of a
   rigid body (its deflection, rotation, the forces and couples it exerts, the
   accumulators of its equations) in the unit of the beam variable it stands
   for (:attr:`symtmm.assembly.Layout.units`);
3. propagates the columns of the unknowns (beams' free left-end variables,
   bodies' unknowns) through the cuts (segment steps, then each station's jump
   ``z -> (I + G) z`` whose entries are exact polynomials in ``lam``),
   re-orthonormalising them after every step (modified Gram–Schmidt, twice)
   and adding up the logarithms of the norms (Godunov's method);
4. returns ``det E[rows] * exp(sum of the logarithms)``, the determinant by
   Gaussian elimination with partial pivoting.

Without steps 2 and 3 the columns become parallel to working precision and the
value loses ``sum |beta| L / ln 10`` digits (all of them by ``beta L = 36``);
with them it keeps about 13 significant digits at any mode, like the Python
evaluator, and overflows only where ``|Delta|`` itself exceeds the double range.
Common subexpressions of the parameters are computed once (:func:`sympy.cse`),
identical segments share one matrix, and constants are printed with 17
significant digits (exact to double precision).

The header comment names the model (its file, title and parameter values)
and the method. That text comes from the model file and is data: every line
goes through :func:`symtmm.text.comment_text` (printable ASCII, one line, no
sequence that ends or opens a comment in any of the languages), and the
Python file carries it as ``#`` comments rather than in its docstring.

Signatures (the command-line contract)
--------------------------------------
* C99: ``void symtmm_delta(double lam_re, double lam_im, [double P, ...]
  double *delta_re, double *delta_im)``
* Fortran 2008: ``subroutine symtmm_delta(lam_re, lam_im, [P, ...] delta_re, delta_im)
  bind(C, name="symtmm_delta")``, ``real(c_double)``, inputs by value
* Octave/MATLAB: ``function d = symtmm_delta(lam [, P, ...])`` (any array ``lam``)
* Julia: ``symtmm_delta(lam::ComplexF64 [, P::Float64, ...])::ComplexF64``
* Python: ``symtmm_delta(lam [, P, ...])`` on numpy arrays, numpy only

``P, ...`` are the model's parameters left symbolic, in alphabetical order.
An argument keeps the parameter's name unless that name means something in
the language or in the generated code: a keyword, a macro of the included C
headers (``I``, ``NAN``, ``linux``), a builtin the code would lose
(``complex``, ``range`` in Python), any name the evaluator itself uses, read
from the code generated for the model (``E`` in Fortran, which ignores case,
``sqrt``, ``lam``), or a name that is no ASCII identifier; it is then called
``p_NAME`` (characters other than letters, digits and ``_`` replaced by
``_``, at most 63 characters), and the header says which parameter it stands
for. The order of the cuts along the beams is fixed when the code is
generated; values that would reverse it (a segment of negative length) give
``NaN``.

Examples
--------
>>> from symtmm.model import Beam, Model
>>> src = generate(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), "python")
>>> namespace = {}
>>> exec(src, namespace)
>>> import numpy as np
>>> bool(abs(namespace["symtmm_delta"](np.array([1j * np.pi**2]))[0]) < 1e-12)
True

A Rayleigh beam, pinned at both ends: ``omega**2 = EI q**2 / (m + rhoI q)``
with ``q = (pi/L)**2``:

>>> rayleigh = Beam("r", 1, 1, 1, left="pinned", right="pinned", theory="rayleigh",
...                 rhoI="1/100")
>>> namespace = {}
>>> exec(generate(Model((rayleigh,)), "python"), namespace)
>>> q = np.pi**2
>>> bool(abs(namespace["symtmm_delta"](np.array([1j * q / np.sqrt(1 + q / 100)]))[0]) < 1e-12)
True
"""

from __future__ import annotations

import keyword
import math
import re
import textwrap
from dataclasses import dataclass, field, replace

import sympy as sp

from .. import __version__
from ..assembly import Interval, Layout
from ..characteristic import _check_order, _prepare
from ..compile import NU_STEP
from ..elements import STATE, BeamSegment
from ..elements.base import LAM
from ..errors import ModelError
from ..text import comment_text

__all__ = ["EXTENSIONS", "LANGUAGES", "generate"]

#: Languages :func:`generate` writes.
LANGUAGES = ("c", "fortran", "octave", "julia", "python")
#: Usual file extension per language.
EXTENSIONS = {"c": ".c", "fortran": ".f90", "octave": ".m", "julia": ".jl", "python": ".py"}

#: Terms of the series of c_j(x) for |x| < 1 (the last is below 1e-80).
SERIES_TERMS = 16
#: Terms of the series of alpha, beta in (t, d) (k < 14, as symtmm.elements.theories:
#: k/(2k)! < 1e-18 beyond, the error for max|r| h**2 <= 1).
THEORY_TERMS = 14

# Names an argument of the generated symtmm_delta must not take, per language: what
# the language gives a meaning (keywords, macros of the headers the C file includes,
# builtins an argument would shadow) and the code's own locals and globals. The code's
# own names are also read from the code itself (_code_names), so that a name the
# emitters start to use is avoided without being listed here.
_COMMON = {"lam", "lam2", "D", "E", "R", "logscale"}
_RESERVED = {
    "c": _COMMON | {"lam_re", "lam_im", "delta_re", "delta_im", "U", "d", "s", "n", "nsub",
                    "nu", "grown", "w",
                    "t", "j", "NS", "NC", "NU_STEP", "I", "auto", "break", "case", "char",
                    "const", "continue", "default", "do", "double", "else", "enum", "extern",
                    "float", "for", "goto", "if", "inline", "int", "long", "register",
                    "restrict", "return", "short", "signed", "sizeof", "static", "struct",
                    "switch", "typedef", "union", "unsigned", "void", "volatile", "while",
                    "complex", "creal", "cimag", "cabs", "cpow", "ccosh", "ccos", "csinh",
                    "csin", "conj", "sqrt", "pow", "log", "exp", "ceil", "NAN", "M_PI"},
    # Fortran ignores case: compared in lower case
    "fortran": _COMMON | {"lam_re", "lam_im", "delta_re", "delta_im", "e", "r", "dlt", "tt",
                          "u", "dd", "nn", "nsub", "nuv", "wv", "grown", "it", "ii", "kk", "jj", "s", "dp", "ns",
                          "nc", "nu_step", "coef", "cfun", "segment", "steps", "units",
                          "orthonormalise", "det", "abs", "real", "aimag", "cmplx", "sqrt",
                          "exp", "log", "cos", "cosh", "sin", "sinh", "conjg", "sum",
                          "ceiling", "max", "kind", "ieee_value", "ieee_quiet_nan",
                          "ieee_arithmetic", "iso_c_binding", "c_double", "c_double_complex",
                          "th", "ifact", "invariants", "wave", "segment_gen", "steps_nu",
                          "units_b"},
    "octave": _COMMON | {"d", "lm", "idx", "Us", "it", "F", "w", "grown", "end", "function", "for", "if",
                         "else", "elseif", "while", "return", "switch", "case", "otherwise",
                         "do", "until", "break", "continue", "global", "persistent", "try",
                         "catch", "i", "j", "pi", "e", "abs", "sqrt", "exp", "log", "cos",
                         "sin", "cosh", "sinh", "zeros", "numel", "size", "det", "qr", "diag",
                         "ceil", "max", "NaN", "Inf", "sum", "complex", "real", "imag"},
    "julia": _COMMON | {"Us", "it", "w", "grown", "begin", "end", "function", "for", "if", "else", "elseif",
                        "while", "return", "let", "local", "global", "const", "do", "try",
                        "catch", "finally", "struct", "mutable", "module", "using", "import",
                        "export", "quote", "macro", "abstract", "primitive", "type", "in",
                        "isa", "true", "false", "break", "continue", "baremodule", "where",
                        "outer", "im", "pi", "abs", "sqrt", "exp", "log", "cos", "sin", "cosh",
                        "sinh", "conj", "zeros", "one", "zero", "size", "ceil", "Int", "max",
                        "NaN", "Float64", "ComplexF64", "transpose", "NTuple"},
    "python": _COMMON | {"flat", "Us", "F", "np", "n", "out", "sel", "key", "steps", "core",
                         "grown"}
    | set(keyword.kwlist),
}
# C: every keyword up to C23 and GNU's, the object-like macros of <complex.h> and
# <math.h> (glibc in any mode, other C libraries' SVID names) and the system names
# compilers predefine outside strict ISO mode (`gcc -std=gnu99` defines linux = 1);
# the M_, FP_, HUGE_VAL, SNAN, CMPLX and MATH_ERR families by their prefix below.
_RESERVED["c"] |= {
    "_Bool", "_Complex", "_Imaginary", "alignas", "alignof", "asm", "bool", "constexpr",
    "false", "fortran", "nullptr", "static_assert", "thread_local", "true", "typeof",
    "typeof_unqual", "imaginary", "INFINITY", "HUGE", "MAXFLOAT", "DOMAIN", "SING",
    "OVERFLOW", "UNDERFLOW", "TLOSS", "PLOSS", "X_TLOSS", "math_errhandling", "errno",
    "linux", "unix", "i386", "i486", "i586", "i686", "sun", "sparc", "mips", "vax",
    "hppa", "m68k", "mc68000", "ns32000", "pdp11", "ppc", "powerpc", "arm", "sgi",
    "fpclassify", "iscanonical", "iseqsig", "isfinite", "isgreater", "isgreaterequal",
    "isinf", "isless", "islessequal", "islessgreater", "isnan", "isnormal", "issignaling",
    "issubnormal", "isunordered", "iszero", "signbit",
}
_C_MACRO_FAMILY = re.compile(r"^(?:M_|FP_|HUGE_VAL|SNAN|CMPLX|MATH_ERR)")
# Octave: iskeyword() of Octave 8 and MATLAB's, and the constants and variables every
# function sees (an argument i or e would hide the constant; nargin is set on entry).
_RESERVED["octave"] |= {
    "__FILE__", "__LINE__", "classdef", "end_try_catch", "end_unwind_protect",
    "endarguments", "endclassdef", "endenumeration", "endevents", "endfor", "endfunction",
    "endif", "endmethods", "endparfor", "endproperties", "endspmd", "endswitch",
    "endwhile", "parfor", "spmd", "unwind_protect", "unwind_protect_cleanup", "arguments",
    "methods", "properties", "events", "enumeration", "I", "J", "Inf", "inf", "NaN", "nan",
    "NA", "eps", "ans", "nargin", "nargout", "varargin", "varargout", "true", "false",
}
# Julia: keywords of Julia 1.11 (public included) and the names of Core every file sees.
_RESERVED["julia"] |= {
    "public", "ccall", "nothing", "missing", "Inf", "ans", "Base", "Core", "Main",
    "ComplexF32", "Float32", "Complex", "Matrix", "Vector",
}
# Python: the builtins (an argument called complex, float, int or range breaks the
# code that calls them) and numpy's module name.
_RESERVED["python"] |= {
    "abs", "aiter", "all", "anext", "any", "ascii", "bin", "bool", "breakpoint", "bytearray",
    "bytes", "callable", "chr", "classmethod", "compile", "complex", "copyright", "credits",
    "delattr", "dict", "dir", "divmod", "enumerate", "eval", "exec", "exit", "filter",
    "float", "format", "frozenset", "getattr", "globals", "hasattr", "hash", "help", "hex",
    "id", "input", "int", "isinstance", "issubclass", "iter", "len", "license", "list",
    "locals", "map", "max", "memoryview", "min", "next", "object", "oct", "open", "ord",
    "pow", "print", "property", "quit", "range", "repr", "reversed", "round", "set",
    "setattr", "slice", "sorted", "staticmethod", "str", "sum", "super", "tuple", "type",
    "vars", "zip", "Ellipsis", "NotImplemented", "numpy",
}
#: Longest argument name: Fortran 2008 and Octave (namelengthmax) allow 63 characters,
#: C99 guarantees 63 significant ones.
_MAX_NAME = 63
_ASCII_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
#: Longest line of the header comment, marker excluded (Fortran allows 132 characters).
_HEADER_WIDTH = 100

# numbered locals of the generated code (U1, s0, n2, th0, ...)
_NUMBERED = re.compile(r"^(?:[Usn]|th|nu)\d+$")


def _float_literal(value) -> str:
    """Shortest decimal that reads back as the double nearest the exact value.

    A value beyond the double range is refused: its repr, ``inf`` or ``nan``,
    would be read as a name by every language but Octave.
    """
    number = float(sp.N(sp.sympify(value), 30))
    if not math.isfinite(number):
        raise ModelError(f"a constant of the model, {sp.N(sp.sympify(value), 6)}, lies beyond "
                         "the range of double precision: it cannot be written as a double")
    return repr(number)


def _argument_names(params, lang: str, used=()) -> list:
    """An identifier per parameter that means nothing else where ``lang``'s code uses it.

    A name that is a safe identifier stays as it is. Any other gets ``p_`` in
    front (again, until it is free): names that are keywords, builtins or
    macros of the language (``_RESERVED``), names the generated code itself
    uses (``used``, see :func:`_code_names`), numbered locals (``U1``,
    ``th0``), and names starting with ``symtmm`` or ``_``. A name that is not
    an ASCII identifier (possible for a symbol built in Python) has its other
    characters replaced by ``_`` and always gets the prefix; one longer than
    ``_MAX_NAME`` is cut and numbered. Fortran compares without case. The
    generated header lists every renamed argument with its parameter.

    Examples
    --------
    >>> _argument_names(["I", "K", "x1"], "c"), _argument_names(["E", "K"], "fortran")
    (['p_I', 'K', 'x1'], ['p_E', 'K'])
    >>> _argument_names(["th0", "wave"], "fortran")
    ['p_th0', 'p_wave']
    >>> _argument_names(["complex", "range", "sqrt", "x"], "python", used={"sqrt"})
    ['p_complex', 'p_range', 'p_sqrt', 'x']
    >>> _argument_names(["a b", "K", "k"], "fortran")
    ['p_a_b', 'K', 'p_k']
    """
    fold = (lambda v: v.lower()) if lang == "fortran" else (lambda v: v)
    taken = {fold(v) for v in _RESERVED[lang]} | {fold(v) for v in used}

    def unsafe(arg: str) -> bool:
        return (fold(arg) in taken or len(arg) > _MAX_NAME
                or not _ASCII_IDENTIFIER.fullmatch(arg) or bool(_NUMBERED.match(arg))
                or arg.lower().startswith(("symtmm", "_"))
                or (lang == "c" and bool(_C_MACRO_FAMILY.match(arg))))

    out: list = [None] * len(params)
    # first the names that can stay: a renamed parameter must not take one of them
    for i, name in enumerate(params):
        if not unsafe(name):
            out[i] = name
            taken.add(fold(name))
    for i, name in enumerate(params):
        if out[i] is not None:
            continue
        base = name if _ASCII_IDENTIFIER.fullmatch(name) else \
            "p_" + re.sub(r"[^A-Za-z_0-9]", "_", name)
        arg = base
        while unsafe(arg) and len(arg) <= _MAX_NAME:
            arg = "p_" + arg
        count = 0
        while unsafe(arg):          # too long: cut, and numbered to stay apart
            count += 1
            arg = f"p{i + 1}_{count}_" + base[:_MAX_NAME - 16]
        taken.add(fold(arg))
        out[i] = arg
    return out


# Where each language's evaluator starts and ends in the generated file (the helpers'
# locals are theirs: an argument may share a name with them).
_EVALUATOR = {
    "c": (r"^void symtmm_delta\(", r"^\}$"),
    "fortran": (r"^  subroutine symtmm_delta\(", r"^  end subroutine symtmm_delta$"),
    "octave": (r"^function d = symtmm_delta\(", r"^end$"),
    "julia": (r"^function symtmm_delta\(", r"^end$"),
    "python": (r"^def symtmm_delta\(", r"\Z"),
}
# Comments and string literals, whose words are no names (the language's own forms only).
_NOT_CODE = {
    "c": r"/\*[\s\S]*?\*/|\"[^\"\n]*\"",
    "fortran": r"![^\n]*|\"[^\"\n]*\"|'[^'\n]*'",
    "octave": r"%[^\n]*",
    "julia": r"#[^\n]*|\"[^\"\n]*\"",
    "python": r"#[^\n]*|\"\"\"[\s\S]*?\"\"\"|\"[^\"\n]*\"|'[^'\n]*'",
}


def _code_names(plan: _Plan, lang: str) -> set:
    """Every name the generated evaluator of ``plan`` uses besides its arguments.

    The code is generated once with placeholder arguments and read: the
    evaluator's body (locals, functions and constants it calls, nested
    functions' locals) and, for Fortran, the module's declarations and
    procedure names, which the subroutine sees by host association.
    """
    blank = replace(plan, title="", source="", values={},
                    args=[f"symtmm_arg{i}" for i in range(len(plan.params))])
    code = re.sub(_NOT_CODE[lang], " ", _EMITTERS[lang](blank))
    start = re.search(_EVALUATOR[lang][0], code, re.MULTILINE).start()
    end = re.compile(_EVALUATOR[lang][1], re.MULTILINE).search(code, start).end()
    text = code[start:end]
    if lang == "fortran":
        text += code[:code.index("\ncontains\n")]
        text += " ".join(re.findall(r"\b(?:subroutine|function)\s+(\w+)", code))
    return set(re.findall(r"\b[A-Za-z_][A-Za-z_0-9]*", text))


@dataclass
class _Plan:
    """Language-neutral description of the evaluation.

    Every value is a SymPy expression over the arguments and the CSE
    temporaries (numbers where it is constant); kinds and indices are Python
    strings and ints.
    """

    title: str
    source: str
    params: list                 # names of symbolic parameters (extra arguments)
    values: dict                 # parameter name -> exact value (for the header)
    n: int                       # beams
    size: int                    # length of the extended state (beams, then bodies)
    rows: list
    columns: list
    args: list = field(default_factory=list)      # argument identifier per parameter
    temps: list = field(default_factory=list)     # (name, expr over arguments and temps)
    # per beam: ("eb", EI, mu, L, k) with units b = |mu lam2 + k|^(1/4), or ("gen", th, L)
    # with b the wave-number bound of theory th
    levels: list = field(default_factory=list)
    theories: list = field(default_factory=list)  # (EI, a, b, cN, rhoI, m, kw) of a BeamSegment
    virtual: list = field(default_factory=list)   # (index, source): a body's unit is D[source]
    # ("eb", a, l, EI, s) with a = m l^4/EI, s = kw/m; or ("gen", th, l)
    segments: list = field(default_factory=list)
    guards: list = field(default_factory=list)    # lengths that must not be negative
    # ("seg", index, level) | ("point", [(row, [(sign, col, stiff index), ...]), ...])
    steps: list = field(default_factory=list)
    stiff: list = field(default_factory=list)     # (k0, k1, ...): s = k0 + k1 lam + ...

    @property
    def ncol(self) -> int:
        return len(self.columns)

    @property
    def ns(self) -> int:
        return self.size

    @property
    def has_eb(self) -> bool:
        """Whether some segment is a plain Euler–Bernoulli one (the c_j routine)."""
        return any(seg[0] == "eb" for seg in self.segments)

    @property
    def has_gen(self) -> bool:
        """Whether some segment or level needs the general beam routines."""
        return bool(self.theories)


def _theory(seg: BeamSegment) -> tuple:
    """``(EI, a, b, cN, rhoI, m, kw)``: ``c = cN + rhoI lam**2``, ``mu = m lam**2 + kw``."""
    a, b, cN, _ = seg.coefficients(sp.Integer(0))
    return (seg.EI, a, b, cN, seg.rhoI, seg.m, seg.kw)


def _poly_coefficients(value) -> tuple:
    """Exact coefficients of ``lam**0, lam**1, ...`` of a station entry."""
    poly = sp.Poly(sp.expand(value), LAM)
    return tuple(sp.sympify(c) for c in reversed(poly.all_coeffs()))


def _plan(model, symbolic=()) -> _Plan:
    model_in = model
    model, sample = _prepare(model, tuple(symbolic))
    layout = Layout(model, sample)
    _check_order(layout, sample, model.source)
    params = sorted(model.free_symbols)
    plan = _Plan(title=model_in.title or "", source=model_in.source or "",
                 params=params, values={k: v for k, v in model_in.parameters.items()},
                 n=layout.levels, size=layout.size, rows=list(layout.rows),
                 columns=list(layout.columns),
                 args=[_placeholder(i) for i in range(len(params))])
    raw: list = []          # expressions to go through CSE; slot i stands for raw[i]
    holders: list = []

    def slot(expr):
        expr = sp.sympify(expr)
        if expr.is_number:
            return expr
        raw.append(expr)
        holders.append(sp.Dummy(f"raw{len(raw) - 1}"))
        return holders[-1]

    theory_index: dict = {}

    def theory(seg) -> int:
        key = _theory(seg)
        if key not in theory_index:
            theory_index[key] = len(plan.theories)
            plan.theories.append(tuple(slot(v) for v in key))
        return theory_index[key]

    for beam in layout.model.beams:
        if beam.plain:
            plan.levels.append(("eb", slot(beam.EI), slot(beam.m / beam.EI), slot(beam.L),
                                slot(beam.kw / beam.EI)))
        else:
            plan.levels.append(("gen", theory(beam.segment(beam.L)), slot(beam.L)))
    units = layout.units
    for i in range(4 * layout.levels, layout.size):
        lvl, var = units[i]
        plan.virtual.append((i, 4 * lvl + STATE.index(var)))
    seg_index: dict = {}
    stiff_index: dict = {}  # coefficients -> index; a coupling's entries are +-s: one variable
    for step in layout.steps:
        if isinstance(step, Interval):
            for lvl, seg in step.segments:
                key = (type(seg).__name__,) + tuple(seg.key)
                if key not in seg_index:
                    seg_index[key] = len(plan.segments)
                    if isinstance(seg, BeamSegment):
                        plan.segments.append(("gen", theory(seg), slot(seg.l)))
                    else:
                        # a foundation kw: the bare segment at lam**2 + kw/m
                        plan.segments.append(("eb", slot(seg.m * seg.l**4 / seg.EI),
                                              slot(seg.l), slot(seg.EI), slot(seg.kw / seg.m)))
                    if not sp.sympify(seg.l).is_number:
                        plan.guards.append(slot(seg.l))
                plan.steps.append(("seg", seg_index[key], lvl))
            continue
        updates: dict = {}
        for row, col, value in step.terms:
            key = _poly_coefficients(value)
            if all(v == 0 for v in key):
                continue
            sign = 1
            neg = tuple(-v for v in key)
            if neg in stiff_index:
                key, sign = neg, -1
            if key not in stiff_index:
                stiff_index[key] = len(plan.stiff)
                plan.stiff.append(tuple(slot(v) for v in key))
            updates.setdefault(row, []).append((sign, col, stiff_index[key]))
        plan.steps.append(("point", list(updates.items())))
    # common subexpressions of the parameter expressions
    lookup: dict = {}
    if raw:
        # each parameter, whatever its name and assumptions, becomes its placeholder: a
        # name only ever reaches the code as the identifier _for_language picks for it
        index = {name: i for i, name in enumerate(params)}
        marks = {s: sp.Symbol(_placeholder(index[s.name]), **s.assumptions0)
                 for e in raw for s in e.free_symbols}
        numeric = [sp.N(e.xreplace(marks), 25) for e in raw]
        temps, reduced = sp.cse(numeric, symbols=sp.numbered_symbols("symtmm_t"))
        plan.temps = list(temps)
        named: dict = {}
        for holder, e in zip(holders, reduced):
            if e.is_Symbol:          # a parameter or a CSE temporary: use it as it is
                lookup[holder] = e
                continue
            if e not in named:
                named[e] = sp.Symbol(f"symtmm_t{len(plan.temps)}")
                plan.temps.append((named[e], e))
            lookup[holder] = named[e]
    return _mapped(plan, lambda v: v.xreplace(lookup) if lookup else v)


def _mapped(plan: _Plan, fn) -> _Plan:
    """The plan with ``fn`` applied to every SymPy value (kinds and indices untouched)."""

    def sub(v):
        if isinstance(v, sp.Basic):
            return fn(v)
        if isinstance(v, tuple):
            return tuple(sub(x) for x in v)
        return v

    return replace(plan,
                   temps=[(nm, sub(e)) for nm, e in plan.temps],
                   levels=[sub(v) for v in plan.levels],
                   theories=[sub(v) for v in plan.theories],
                   segments=[sub(v) for v in plan.segments],
                   stiff=[sub(v) for v in plan.stiff],
                   guards=[sub(v) for v in plan.guards])


def _placeholder(i: int) -> str:
    """The name parameter ``i`` has in a plan until a language gives it an identifier."""
    return f"symtmm_arg{i}"


def _for_language(plan: _Plan, lang: str) -> _Plan:
    """The plan with each parameter's placeholder replaced by its argument in ``lang``."""
    args = _argument_names(plan.params, lang, _code_names(plan, lang))
    names = {_placeholder(i): a for i, a in enumerate(args)}

    def rename(v):
        ren = {s: sp.Symbol(names[s.name], **s.assumptions0)
               for s in v.free_symbols if s.name in names}
        return v.xreplace(ren) if ren else v

    return replace(_mapped(plan, rename), args=args)


# --------------------------------------------------------------------------------------
# shared pieces


def _shifted(s, printer) -> str:
    """``lam2``, or ``(lam2 + kw/m)`` for a segment on a Winkler foundation."""
    return "lam2" if s == 0 else f"(lam2 + {printer(s)})"


def _jump(terms, s_name, e_name, d_name, mul="*", div="/") -> str:
    """``+- s_i * E_col / D_col + ...`` for one force row (in wave-number units)."""
    text = ""
    for sign, col, si in terms:
        op = "-" if sign < 0 else "+"
        text += f" {op} {s_name(si)} {mul} {e_name(col)} {div} {d_name(col)}"
    text = text.strip()
    return text[2:] if text.startswith("+") else "-" + text[2:]


def _polynomial(coeffs, val, lam="lam", mul="*") -> str:
    """``k0 + k1 lam + k2 lam lam + ...`` without the terms that are zero.

    Examples
    --------
    >>> _polynomial((3, 0, -2), lambda v: str(v))
    '3 + (-2) * lam * lam'
    """
    parts = []
    for k, coef in enumerate(coeffs):
        if sp.sympify(coef) == 0:
            continue
        text = val(coef)
        if text.lstrip().startswith("-"):
            text = f"({text})"          # no operator after an operator (Fortran)
        parts.append(text if k == 0 else f" {mul} ".join([text] + [lam] * k))
    return " + ".join(parts) if parts else val(0)


def _series_coefficients():
    """``coef[j][k] = 1/(4k+j)!`` as exact-to-double literals."""
    return [[_float_literal(sp.Rational(1, math.factorial(4 * k + j)))
             for k in range(SERIES_TERMS)] for j in range(4)]


def _inverse_factorials():
    """``1/n!`` for ``n = 0 .. 2 THEORY_TERMS - 1`` as exact-to-double literals."""
    return [_float_literal(sp.Rational(1, math.factorial(n))) for n in range(2 * THEORY_TERMS)]


def _theory_assembly() -> list:
    """``(target, expression)`` of U from ``alpha0, beta0, alpha1, beta1`` (a0, b0, a1, b1).

    Targets ``g..``, ``p..``, ``h..``, ``k..`` are scalars, ``(i, k)`` entries of
    ``U`` (0-based) in the order ``[Y, Theta, M, Q]``: ``U = [[F0(G), B F1(G')],
    [C F1(G), F0(G')]]`` with ``G = B C`` on ``(Y, M)``, ``G' = C B`` on ``(Theta,
    Q)``, ``B = [[a, b], [c, a]]``, ``C = [[0, 1/EI], [-mu, 0]]`` (see
    :func:`symtmm.elements.theories._assemble`). The expressions read the same
    in every target language.
    """
    return [
        ("g00", "-b * mu"), ("g01", "a / EI"), ("g10", "-a * mu"), ("g11", "c / EI"),
        ("p00", "c / EI"), ("p01", "a / EI"), ("p10", "-mu * a"), ("p11", "-mu * b"),
        ((0, 0), "a0 + b0 * g00"), ((0, 2), "b0 * g01"),
        ((2, 0), "b0 * g10"), ((2, 2), "a0 + b0 * g11"),
        ((1, 1), "a0 + b0 * p00"), ((1, 3), "b0 * p01"),
        ((3, 1), "b0 * p10"), ((3, 3), "a0 + b0 * p11"),
        ("h00", "a1 + b1 * p00"), ("h01", "b1 * p01"), ("h10", "b1 * p10"),
        ("h11", "a1 + b1 * p11"),
        ((0, 1), "a * h00 + b * h10"), ((0, 3), "a * h01 + b * h11"),
        ((2, 1), "c * h00 + a * h10"), ((2, 3), "c * h01 + a * h11"),
        ("k00", "a1 + b1 * g00"), ("k01", "b1 * g01"), ("k10", "b1 * g10"),
        ("k11", "a1 + b1 * g11"),
        ((1, 0), "k10 / EI"), ((1, 2), "k11 / EI"), ((3, 0), "-mu * k00"), ((3, 2), "-mu * k01"),
    ]


def _theory_scalars() -> list:
    """Names of the scalar temporaries of :func:`_theory_assembly`."""
    return [t for t, _ in _theory_assembly() if isinstance(t, str)]


def _header_lines(plan: _Plan, lang: str) -> list:
    """The header comment's lines, without the comment marker.

    Every line goes through :func:`_comment_lines`: the title, the source path
    and the parameters' names and values come from the model file and are
    data, never code, in every language.
    """
    lines = ["symtmm_delta: characteristic function Delta(lam) = det R(lam) of the model",
             f"  {plan.source or '(no file)'}" + (f": {plan.title}" if plan.title else ""),
             f"generated by symtmm {__version__} (symtmm codegen --lang {lang})."]
    if plan.values:
        vals = ", ".join(f"{k} = {v}" if v is not None else f"{k} (symbolic)"
                         for k, v in plan.values.items())
        lines.append(f"Parameters: {vals}.")
    if plan.params:
        lines.append("Symbolic parameters, extra arguments after lam: " + ", ".join(
            p if a == p else f"{a} (parameter {p})" for p, a in zip(plan.params, plan.args))
            + ".")
        lines.append("The order of the cuts along the beams is the one at the values above; "
                     "values that reverse it give NaN.")
    nvirt = plan.size - 4 * plan.n
    lines.append(f"{plan.n} beam(s)" + (f" and {nvirt} virtual variable(s) of rigid bodies"
                                        if nvirt else "")
                 + f"; R is {plan.ncol} x {plan.ncol}. lam is the eigenvalue "
                 "(lam = i*omega undamped).")
    if plan.has_eb:
        lines += ["Euler-Bernoulli segments: matrices from c_j(x) = sum_k x^k/(4k+j)!,",
                  "x = -lam^2 m l^4/EI (series for |x| < 1)."]
    if plan.theories:
        lines += ["Other beam theories (axial force N, rotary inertia rhoI, shear kGA): exp(A l)",
                  "from alpha, beta of cosh and sinh/s in (t, d) = (trace, det) of G = B C,",
                  "series on a piece with max|r| h^2 <= 1, then doubled (symtmm.elements.theories)."]
    lines += [
        f"Segments applied in steps of |beta| l <= {NU_STEP:g}; states in units of each",
        "beam's wave number; the unknown columns re-orthonormalised after every step",
        "(Godunov), Delta = det(E[rows]) * exp(sum of log norms): about 13",
        "significant digits at any mode, as symtmm.compile.Evaluator.log_delta.",
    ]
    return [piece for line in lines for piece in _comment_lines(line)]


def _comment_lines(text: str) -> list:
    r"""``text`` as comment payloads (:func:`symtmm.text.comment_text`), wrapped.

    Pieces are at most ``_HEADER_WIDTH`` characters, so that a long title keeps
    Fortran's lines under 132 characters; a piece only ever ends a line, and no
    language continues a comment onto the next line.

    Examples
    --------
    >>> _comment_lines("title */ int f(void); /*\nsecond line")
    ['title * / int f(void); / *\\nsecond line']
    >>> [len(p) <= _HEADER_WIDTH for p in _comment_lines("x" * 250)]
    [True, True, True]
    """
    safe = comment_text(text)
    if len(safe) <= _HEADER_WIDTH:
        return [safe]
    return textwrap.wrap(safe, _HEADER_WIDTH, subsequent_indent="    ",
                         break_long_words=True, break_on_hyphens=False)


def _val(expr, printer) -> str:
    expr = sp.sympify(expr)
    if expr.is_number:
        return _float_literal(expr)
    return printer(expr)


def _logscale_terms(plan: _Plan):
    """``(sign, index)`` of the ``log D`` terms of the initial scale (columns minus rows)."""
    return [(1, c) for c in plan.columns] + [(-1, r) for r in plan.rows]


# --------------------------------------------------------------------------------------
# C99


def _c_eb_helpers() -> list:
    coef = _series_coefficients()
    out = [f"static const double symtmm_coef[4][{SERIES_TERMS}] = {{"]
    for j in range(4):
        out.append("    {" + ", ".join(coef[j]) + "},")
    out += ["};", "",
            "/* c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above */",
            "static void symtmm_cfun(double complex x, double complex c[4])",
            "{",
            "    if (cabs(x) < 1.0) {",
            "        for (int j = 0; j < 4; j++) {",
            "            double complex acc = 0.0;",
            f"            for (int k = {SERIES_TERMS - 1}; k >= 0; k--)",
            "                acc = acc * x + symtmm_coef[j][k];",
            "            c[j] = acc;",
            "        }",
            "    } else {",
            "        double complex nu = cpow(x, 0.25);",
            "        double complex ch = ccosh(nu), co = ccos(nu), sh = csinh(nu), si = csin(nu);",
            "        c[0] = (ch + co) / 2.0;",
            "        c[1] = (sh + si) / (2.0 * nu);",
            "        c[2] = (ch - co) / (2.0 * nu * nu);",
            "        c[3] = (sh - si) / (2.0 * nu * nu * nu);",
            "    }",
            "}",
            "",
            ("/* transfer matrix of an Euler-Bernoulli segment of length l (a = m l^4 / EI); "
             "I for l = 0 */"),
            "static void symtmm_segment(double complex lam2, double a, double l, double EI,",
            "                           double complex U[4][4])",
            "{",
            "    if (l == 0.0) {",
            "        for (int i = 0; i < 4; i++)",
            "            for (int j = 0; j < 4; j++) U[i][j] = (i == j) ? 1.0 : 0.0;",
            "        return;",
            "    }",
            "    double complex x = -lam2 * a, c[4];",
            "    symtmm_cfun(x, c);",
            "    double l2 = l * l, l3 = l * l * l;",
            ("    U[0][0] = c[0];            U[0][1] = l * c[1];          "
             "U[0][2] = l2 * c[2] / EI;   U[0][3] = l3 * c[3] / EI;"),
            ("    U[1][0] = x * c[3] / l;    U[1][1] = c[0];              "
             "U[1][2] = l * c[1] / EI;    U[1][3] = l2 * c[2] / EI;"),
            ("    U[2][0] = EI * x * c[2] / l2; U[2][1] = EI * x * c[3] / l; "
             "U[2][2] = c[0];           U[2][3] = l * c[1];"),
            ("    U[3][0] = EI * x * c[1] / l3; U[3][1] = EI * x * c[2] / l2; "
             "U[3][2] = x * c[3] / l;   U[3][3] = c[0];"),
            "}",
            ""]
    return out


def _c_theory_helpers() -> list:
    ifact = _inverse_factorials()
    out = [f"static const double symtmm_ifact[{len(ifact)}] = {{"]
    for i in range(0, len(ifact), 4):
        out.append("    " + ", ".join(ifact[i:i + 4]) + ",")
    out += ["};", "",
            "/* beam theory th = {EI, a, b, cN, rhoI, m, kw} at lam2: c = cN + rhoI lam2,",
            "   mu = m lam2 + kw, and t, d the trace and determinant of G = B C */",
            "static void symtmm_invariants(double complex lam2, const double th[7],",
            "                              double complex *c, double complex *mu,",
            "                              double complex *t, double complex *d)",
            "{",
            "    *c = th[3] + th[4] * lam2;",
            "    *mu = th[5] * lam2 + th[6];",
            "    *t = *c / th[0] - th[2] * *mu;",
            "    *d = *mu * (th[1] * th[1] - th[2] * *c) / th[0];",
            "}",
            "",
            "/* a bound on the largest wave number |s| of the theory th at lam2 (1/length) */",
            "static double symtmm_wave(double complex lam2, const double th[7])",
            "{",
            "    double complex c, mu, t, d;",
            "    symtmm_invariants(lam2, th, &c, &mu, &t, &d);",
            "    double at = cabs(t);",
            "    return sqrt(at / 2.0 + sqrt(at * at / 4.0 + cabs(d)));",
            "}",
            "",
            "/* transfer matrix exp(A l) of a segment of the theory th, [Y, Theta, M, Q]:",
            "   alpha, beta of F0 = cosh(s l), F1 = sinh(s l)/s from their series in (t, d)",
            "   on a piece h = l/2^j with max|r| h^2 <= 1, then doubled j times */",
            "static void symtmm_segment_gen(double complex lam2, const double th[7], double l,",
            "                               double complex U[4][4])",
            "{",
            "    const double EI = th[0], a = th[1], b = th[2];",
            "    double complex c, mu, t, d;",
            "    symtmm_invariants(lam2, th, &c, &mu, &t, &d);",
            "    double w = symtmm_wave(lam2, th), h = l;",
            "    int j = 0;",
            "    while (w * h > 1.0) {",
            "        h /= 2.0;",
            "        j++;",
            "    }",
            "    double complex T = t * h * h, DD = d * (h * h) * (h * h);",
            "    double complex qp = 0.0, q = 1.0, s0a = 0.0, s0b = 0.0, s1a = 0.0, s1b = 0.0;",
            f"    for (int k = 1; k < {THEORY_TERMS}; k++) {{",
            "        s0b += q * symtmm_ifact[2 * k];",
            "        s0a += qp * symtmm_ifact[2 * k];",
            "        s1b += q * symtmm_ifact[2 * k + 1];",
            "        s1a += qp * symtmm_ifact[2 * k + 1];",
            "        double complex qn = T * q - DD * qp;",
            "        qp = q;",
            "        q = qn;",
            "    }",
            "    double complex a0 = 1.0 - DD * s0a, b0 = h * h * s0b;",
            "    double complex a1 = h * (1.0 - DD * s1a), b1 = h * h * h * s1b;",
            "    for (int i = 0; i < j; i++) {   /* F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1 */",
            "        double complex na0 = 2.0 * (a0 * a0 - d * b0 * b0) - 1.0;",
            "        double complex nb0 = 2.0 * (2.0 * a0 * b0 + t * b0 * b0);",
            "        double complex na1 = 2.0 * (a0 * a1 - d * b0 * b1);",
            "        double complex nb1 = 2.0 * (a0 * b1 + a1 * b0 + t * b0 * b1);",
            "        a0 = na0;",
            "        b0 = nb0;",
            "        a1 = na1;",
            "        b1 = nb1;",
            "    }"]
    for target, expr in _theory_assembly():
        if isinstance(target, str):
            out.append(f"    double complex {target} = {expr};")
        else:
            out.append(f"    U[{target[0]}][{target[1]}] = {expr};")
    out += ["}", ""]
    return out


def _emit_c(plan: _Plan) -> str:
    ns, nc = plan.ns, plan.ncol
    p = lambda e: _val(e, sp.ccode)
    out = ["/*"] + [" * " + ln if ln else " *" for ln in _header_lines(plan, "c")] + [" */", ""]
    out += ["#include <complex.h>", "#include <math.h>", "", f"#define NS {ns}", f"#define NC {nc}",
            f"#define NU_STEP {_float_literal(NU_STEP)}", ""]
    if plan.has_eb:
        out += _c_eb_helpers()
    if plan.has_gen:
        out += _c_theory_helpers()
    out += ["/* steps of |beta| l <= NU_STEP for a segment with nu = |beta| l */",
            "static int symtmm_steps(double nu)",
            "{",
            "    int n = (int)ceil(nu / NU_STEP);",
            "    return n < 1 ? 1 : n;",
            "}",
            "",
            "/* units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number */",
            "static void symtmm_units(double b, double EI, double L, double *D)",
            "{",
            "    if (b < 1.0 / L) b = 1.0 / L;",
            "    D[0] = 1.0; D[1] = 1.0 / b; D[2] = 1.0 / (EI * b * b); D[3] = 1.0 / (EI * b * b * b);",
            "}",
            "",
            "/* rows r0..r0+3 of E := (D U D^-1) * (those rows) */",
            "static void symtmm_apply(double complex U[4][4], const double *D,",
            "                         double complex E[NS][NC], int r0)",
            "{",
            "    for (int j = 0; j < NC; j++) {",
            "        double complex t[4];",
            "        for (int i = 0; i < 4; i++) {",
            "            t[i] = 0.0;",
            "            for (int k = 0; k < 4; k++)",
            "                t[i] += U[i][k] * (D[r0 + i] / D[r0 + k]) * E[r0 + k][j];",
            "        }",
            "        for (int i = 0; i < 4; i++)",
            "            E[r0 + i][j] = t[i];",
            "    }",
            "}",
            "",
            "/* modified Gram-Schmidt, twice: E := Q of E = Q F; returns log det F */",
            "static double symtmm_orthonormalise(double complex E[NS][NC])",
            "{",
            "    double logdet = 0.0;",
            "    for (int j = 0; j < NC; j++) {",
            "        for (int pass = 0; pass < 2; pass++)",
            "            for (int k = 0; k < j; k++) {",
            "                double complex r = 0.0;",
            "                for (int i = 0; i < NS; i++) r += conj(E[i][k]) * E[i][j];",
            "                for (int i = 0; i < NS; i++) E[i][j] -= r * E[i][k];",
            "            }",
            "        double nrm = 0.0;",
            "        for (int i = 0; i < NS; i++) nrm += creal(E[i][j] * conj(E[i][j]));",
            "        nrm = sqrt(nrm);",
            "        for (int i = 0; i < NS; i++) E[i][j] /= nrm;",
            "        logdet += log(nrm);",
            "    }",
            "    return logdet;",
            "}",
            "",
            "/* determinant by Gaussian elimination with partial pivoting (A is overwritten) */",
            "static double complex symtmm_det(double complex A[NC][NC])",
            "{",
            "    double complex d = 1.0;",
            "    for (int k = 0; k < NC; k++) {",
            "        int p = k;",
            "        for (int i = k + 1; i < NC; i++)",
            "            if (cabs(A[i][k]) > cabs(A[p][k])) p = i;",
            "        if (A[p][k] == 0.0) return 0.0;",
            "        if (p != k) {",
            "            for (int j = 0; j < NC; j++) {",
            "                double complex t = A[k][j]; A[k][j] = A[p][j]; A[p][j] = t;",
            "            }",
            "            d = -d;",
            "        }",
            "        d *= A[k][k];",
            "        for (int i = k + 1; i < NC; i++) {",
            "            double complex f = A[i][k] / A[k][k];",
            "            for (int j = k + 1; j < NC; j++) A[i][j] -= f * A[k][j];",
            "        }",
            "    }",
            "    return d;",
            "}",
            ""]
    args = ["double lam_re", "double lam_im"] + [f"double {q}" for q in plan.args] + \
        ["double *delta_re", "double *delta_im"]
    out += ["void symtmm_delta(" + ", ".join(args) + ")", "{",
            "    double complex lam = lam_re + lam_im * I, lam2 = lam * lam;"]
    for name, expr in plan.temps:
        out.append(f"    const double {name} = {sp.ccode(expr)};")
    for g in plan.guards:
        out += [f"    if (!({p(g)} >= 0.0)) {{  /* the cuts out of their order */",
                "        *delta_re = NAN; *delta_im = NAN;", "        return;", "    }"]
    for t, th in enumerate(plan.theories):
        out.append(f"    const double th{t}[7] = {{{', '.join(p(v) for v in th)}}};"
                   "  /* EI, a, b, cN, rhoI, m, kw */")
    out.append("    double D[NS];")
    for j, lv in enumerate(plan.levels):
        if lv[0] == "eb":
            _, EI, mu, L, k = lv
            out.append(f"    symtmm_units(pow(cabs({p(mu)} * lam2 + {p(k)}), 0.25), {p(EI)}, "
                       f"{p(L)}, D + {4 * j});")
        else:
            _, t, L = lv
            out.append(f"    symtmm_units(symtmm_wave(lam2, th{t}), th{t}[0], {p(L)}, "
                       f"D + {4 * j});")
    for i, src in plan.virtual:
        out.append(f"    D[{i}] = D[{src}];")
    out += ["    double complex E[NS][NC] = {{0}};"]
    for j, c in enumerate(plan.columns):
        out.append(f"    E[{c}][{j}] = 1.0;")
    out.append("    double logscale = 0.0" + "".join(
        f" {'+' if sg > 0 else '-'} log(D[{i}])" for sg, i in _logscale_terms(plan)) + ";")
    nseg = max(len(plan.segments), 1)
    out += [f"    double complex U[{nseg}][4][4];", f"    int nsub[{nseg}];",
            f"    double nu[{nseg}], grown = 0.0;  /* |beta| l per step; since the last QR */"]
    for i, seg in enumerate(plan.segments):
        if seg[0] == "eb":
            _, a, l, EI, s = seg
            lam2s = _shifted(s, p)
            out += ["    {",
                    f"        double w = pow(cabs(-{lam2s} * {p(a)}), 0.25);",
                    f"        nsub[{i}] = symtmm_steps(w);",
                    f"        double n = nsub[{i}];",
                    f"        nu[{i}] = w / n;",
                    (f"        symtmm_segment({lam2s}, {p(a)} / (n * n * n * n), {p(l)} / n, "
                     f"{p(EI)}, U[{i}]);"),
                    "    }"]
        else:
            _, t, l = seg
            out += ["    {",
                    f"        double w = symtmm_wave(lam2, th{t}) * {p(l)};",
                    f"        nsub[{i}] = symtmm_steps(w);",
                    f"        nu[{i}] = w / nsub[{i}];",
                    f"        symtmm_segment_gen(lam2, th{t}, {p(l)} / nsub[{i}], U[{i}]);",
                    "    }"]
    if plan.stiff:
        out.append(f"    double complex s[{len(plan.stiff)}];")
    for i, coeffs in enumerate(plan.stiff):
        out.append(f"    s[{i}] = {_polynomial(coeffs, p)};")
    for step in plan.steps:
        if step[0] == "seg":
            k = step[1]
            out += [f"    for (int t = 0; t < nsub[{k}]; t++) {{",
                    # orthonormalise only once the columns may have grown by exp(NU_STEP)
                    f"        if (grown + nu[{k}] > NU_STEP) {{",
                    "            logscale += symtmm_orthonormalise(E);",
                    "            grown = 0.0;", "        }",
                    f"        symtmm_apply(U[{k}], D, E, {4 * step[2]});",
                    f"        grown += nu[{k}];", "    }"]
        elif step[1]:
            out.append("    for (int j = 0; j < NC; j++) {")
            for row, terms in step[1]:
                rhs = _jump(terms, lambda i: f"s[{i}]", lambda c: f"E[{c}][j]",
                            lambda c: f"D[{c}]")
                out.append(f"        E[{row}][j] += D[{row}] * ({rhs});")
            out.append("    }")
    out.append("    double complex R[NC][NC];")
    out.append("    for (int j = 0; j < NC; j++) {")
    for i, r in enumerate(plan.rows):
        out.append(f"        R[{i}][j] = E[{r}][j];")
    out += ["    }", "    double complex d = symtmm_det(R) * exp(logscale);",
            "    *delta_re = creal(d);", "    *delta_im = cimag(d);", "}", ""]
    return "\n".join(out)


# --------------------------------------------------------------------------------------
# Fortran 2008


def _fortran_expr(expr) -> str:
    expr = sp.sympify(expr)
    if expr.is_number:
        return f"({_float_literal(expr)}_dp)"
    text = sp.fcode(expr, source_format="free", standard=2008)
    text = re.sub(r"&\s*\n\s*", "", text)
    # double-precision literals 1.5d0, 2.0d-8 -> kind dp
    return re.sub(r"(\d)d([+-]?\d+)", lambda m: f"{m.group(1)}e{m.group(2)}_dp", text)


def _fortran_wrap(line: str, width: int = 100) -> list:
    """Split a long free-form line with ``&`` continuations (the limit is 132)."""
    if line.lstrip().startswith("!"):
        return [line]
    out = []
    while len(line) > width:
        cut = line.rfind(" ", 0, width)
        if cut <= line.find(line.strip()[0]):
            break
        out.append(line[:cut] + " &")
        line = "      " + line[cut + 1:]
    return out + [line]


def _fortran_eb_helpers() -> list:
    return ["",
            "  ! c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above",
            "  subroutine cfun(x, c)",
            "    complex(dp), intent(in) :: x",
            "    complex(dp), intent(out) :: c(0:3)",
            "    complex(dp) :: nu, ch, co, sh, si",
            "    integer :: j, k",
            "    if (abs(x) < 1.0_dp) then",
            "      do j = 0, 3",
            "        c(j) = (0.0_dp, 0.0_dp)",
            f"        do k = {SERIES_TERMS - 1}, 0, -1",
            "          c(j) = c(j) * x + coef(k, j)",
            "        end do",
            "      end do",
            "    else",
            "      nu = x**0.25_dp",
            "      ch = cosh(nu); co = cos(nu); sh = sinh(nu); si = sin(nu)",
            "      c(0) = (ch + co) / 2.0_dp",
            "      c(1) = (sh + si) / (2.0_dp * nu)",
            "      c(2) = (ch - co) / (2.0_dp * nu * nu)",
            "      c(3) = (sh - si) / (2.0_dp * nu * nu * nu)",
            "    end if",
            "  end subroutine cfun",
            "",
            ("  ! transfer matrix of an Euler-Bernoulli segment of length l (a = m l^4 / EI); "
             "I for l = 0"),
            "  subroutine segment(lam2, a, l, ei, u)",
            "    complex(dp), intent(in) :: lam2",
            "    real(dp), intent(in) :: a, l, ei",
            "    complex(dp), intent(out) :: u(4, 4)",
            "    complex(dp) :: x, c(0:3)",
            "    real(dp) :: l2, l3",
            "    integer :: i",
            "    if (l == 0.0_dp) then",
            "      u = (0.0_dp, 0.0_dp)",
            "      do i = 1, 4",
            "        u(i, i) = (1.0_dp, 0.0_dp)",
            "      end do",
            "      return",
            "    end if",
            "    x = -lam2 * a",
            "    call cfun(x, c)",
            "    l2 = l * l",
            "    l3 = l * l * l",
            "    u(1, 1) = c(0);           u(1, 2) = l * c(1)",
            "    u(1, 3) = l2 * c(2) / ei; u(1, 4) = l3 * c(3) / ei",
            "    u(2, 1) = x * c(3) / l;   u(2, 2) = c(0)",
            "    u(2, 3) = l * c(1) / ei;  u(2, 4) = l2 * c(2) / ei",
            "    u(3, 1) = ei * x * c(2) / l2; u(3, 2) = ei * x * c(3) / l",
            "    u(3, 3) = c(0);           u(3, 4) = l * c(1)",
            "    u(4, 1) = ei * x * c(1) / l3; u(4, 2) = ei * x * c(2) / l2",
            "    u(4, 3) = x * c(3) / l;   u(4, 4) = c(0)",
            "  end subroutine segment"]


def _fortran_theory_helpers() -> list:
    scalars = ", ".join(_theory_scalars())
    out = ["",
           "  ! beam theory th = [EI, a, b, cN, rhoI, m, kw] at lam2: c = cN + rhoI lam2,",
           "  ! mu = m lam2 + kw, and t, d the trace and determinant of G = B C",
           "  subroutine invariants(lam2, th, c, mu, t, d)",
           "    complex(dp), intent(in) :: lam2",
           "    real(dp), intent(in) :: th(7)",
           "    complex(dp), intent(out) :: c, mu, t, d",
           "    c = th(4) + th(5) * lam2",
           "    mu = th(6) * lam2 + th(7)",
           "    t = c / th(1) - th(3) * mu",
           "    d = mu * (th(2) * th(2) - th(3) * c) / th(1)",
           "  end subroutine invariants",
           "",
           "  ! a bound on the largest wave number |s| of the theory th at lam2 (1/length)",
           "  real(dp) function wave(lam2, th)",
           "    complex(dp), intent(in) :: lam2",
           "    real(dp), intent(in) :: th(7)",
           "    complex(dp) :: c, mu, t, d",
           "    call invariants(lam2, th, c, mu, t, d)",
           "    wave = sqrt(abs(t) / 2.0_dp + sqrt(abs(t)**2 / 4.0_dp + abs(d)))",
           "  end function wave",
           "",
           "  ! transfer matrix exp(A l) of a segment of the theory th, [Y, Theta, M, Q]:",
           "  ! alpha, beta of F0 = cosh(s l), F1 = sinh(s l)/s from their series in (t, d)",
           "  ! on a piece h = l/2^j with max|r| h^2 <= 1, then doubled j times",
           "  subroutine segment_gen(lam2, th, l, u)",
           "    complex(dp), intent(in) :: lam2",
           "    real(dp), intent(in) :: th(7), l",
           "    complex(dp), intent(out) :: u(4, 4)",
           "    complex(dp) :: c, mu, t, d, ts, ds, qp, q, qn, s0a, s0b, s1a, s1b",
           "    complex(dp) :: a0, b0, a1, b1, na0, nb0, na1, nb1",
           f"    complex(dp) :: {scalars}",
           "    real(dp) :: ei, a, b, w, h",
           "    integer :: i, j, k",
           "    ei = th(1)",
           "    a = th(2)",
           "    b = th(3)",
           "    call invariants(lam2, th, c, mu, t, d)",
           "    w = wave(lam2, th)",
           "    h = l",
           "    j = 0",
           "    do while (w * h > 1.0_dp)",
           "      h = h / 2.0_dp",
           "      j = j + 1",
           "    end do",
           "    ts = t * h * h",
           "    ds = d * (h * h) * (h * h)",
           "    qp = (0.0_dp, 0.0_dp)",
           "    q = (1.0_dp, 0.0_dp)",
           "    s0a = qp; s0b = qp; s1a = qp; s1b = qp",
           f"    do k = 1, {THEORY_TERMS - 1}",
           "      s0b = s0b + q * ifact(2 * k)",
           "      s0a = s0a + qp * ifact(2 * k)",
           "      s1b = s1b + q * ifact(2 * k + 1)",
           "      s1a = s1a + qp * ifact(2 * k + 1)",
           "      qn = ts * q - ds * qp",
           "      qp = q",
           "      q = qn",
           "    end do",
           "    a0 = 1.0_dp - ds * s0a",
           "    b0 = h * h * s0b",
           "    a1 = h * (1.0_dp - ds * s1a)",
           "    b1 = h * h * h * s1b",
           "    do i = 1, j   ! F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1",
           "      na0 = 2.0_dp * (a0 * a0 - d * b0 * b0) - 1.0_dp",
           "      nb0 = 2.0_dp * (2.0_dp * a0 * b0 + t * b0 * b0)",
           "      na1 = 2.0_dp * (a0 * a1 - d * b0 * b1)",
           "      nb1 = 2.0_dp * (a0 * b1 + a1 * b0 + t * b0 * b1)",
           "      a0 = na0",
           "      b0 = nb0",
           "      a1 = na1",
           "      b1 = nb1",
           "    end do"]
    for target, expr in _theory_assembly():
        name = target if isinstance(target, str) else f"u({target[0] + 1}, {target[1] + 1})"
        out.append(f"    {name} = {expr.replace('EI', 'ei')}")
    out.append("  end subroutine segment_gen")
    return out


def _emit_fortran(plan: _Plan) -> str:
    ns, nc = plan.ns, plan.ncol
    f = _fortran_expr
    out = ["! " + ln for ln in _header_lines(plan, "fortran")] + [""]
    out += ["module symtmm_delta_mod",
            "  use iso_c_binding, only: c_double, c_double_complex",
            "  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan",
            "  implicit none",
            "  private",
            "  public :: symtmm_delta",
            "  integer, parameter :: dp = c_double",
            f"  integer, parameter :: ns = {ns}, nc = {nc}",
            f"  real(dp), parameter :: nu_step = {_float_literal(NU_STEP)}_dp"]
    if plan.has_eb:
        coef = _series_coefficients()
        out.append(f"  real(dp), parameter :: coef(0:{SERIES_TERMS - 1}, 0:3) = reshape([ &")
        flat = [c for j in range(4) for c in coef[j]]
        for i in range(0, len(flat), 3):
            chunk = ", ".join(v + "_dp" for v in flat[i:i + 3])
            out.append("    " + chunk + (", &" if i + 3 < len(flat) else " &"))
        out.append(f"    ], [{SERIES_TERMS}, 4])")
    if plan.has_gen:
        ifact = _inverse_factorials()
        out.append(f"  real(dp), parameter :: ifact(0:{len(ifact) - 1}) = [ &")
        for i in range(0, len(ifact), 3):
            chunk = ", ".join(v + "_dp" for v in ifact[i:i + 3])
            out.append("    " + chunk + (", &" if i + 3 < len(ifact) else " &"))
        out.append("    ]")
    out.append("contains")
    if plan.has_eb:
        out += _fortran_eb_helpers()
    if plan.has_gen:
        out += _fortran_theory_helpers()
    out += ["",
            "  ! steps of |beta| l <= nu_step for a segment with nu = |beta| l",
            "  integer function steps(nu)",
            "    real(dp), intent(in) :: nu",
            "    steps = max(1, ceiling(nu / nu_step))",
            "  end function steps",
            "",
            ("  ! units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave "
             "number"),
            "  subroutine units(b_in, ei, bl, dd)",
            "    real(dp), intent(in) :: b_in, ei, bl",
            "    real(dp), intent(out) :: dd(4)",
            "    real(dp) :: b",
            "    b = max(b_in, 1.0_dp / bl)",
            "    dd = [1.0_dp, 1.0_dp / b, 1.0_dp / (ei * b * b), 1.0_dp / (ei * b * b * b)]",
            "  end subroutine units",
            "",
            "  ! modified Gram-Schmidt, twice: e := q of e = q f; returns log det f",
            "  real(dp) function orthonormalise(e)",
            "    complex(dp), intent(inout) :: e(ns, nc)",
            "    complex(dp) :: r",
            "    real(dp) :: nrm",
            "    integer :: j, k, pass",
            "    orthonormalise = 0.0_dp",
            "    do j = 1, nc",
            "      do pass = 1, 2",
            "        do k = 1, j - 1",
            "          r = sum(conjg(e(:, k)) * e(:, j))",
            "          e(:, j) = e(:, j) - r * e(:, k)",
            "        end do",
            "      end do",
            "      nrm = sqrt(sum(real(e(:, j) * conjg(e(:, j)), kind=dp)))",
            "      e(:, j) = e(:, j) / nrm",
            "      orthonormalise = orthonormalise + log(nrm)",
            "    end do",
            "  end function orthonormalise",
            "",
            "  ! determinant by Gaussian elimination with partial pivoting",
            "  function det(a_in) result(d)",
            "    complex(dp), intent(in) :: a_in(nc, nc)",
            "    complex(dp) :: a(nc, nc), d, f, row(nc)",
            "    integer :: i, k, p",
            "    a = a_in",
            "    d = (1.0_dp, 0.0_dp)",
            "    do k = 1, nc",
            "      p = k",
            "      do i = k + 1, nc",
            "        if (abs(a(i, k)) > abs(a(p, k))) p = i",
            "      end do",
            "      if (a(p, k) == (0.0_dp, 0.0_dp)) then",
            "        d = (0.0_dp, 0.0_dp)",
            "        return",
            "      end if",
            "      if (p /= k) then",
            "        row = a(k, :); a(k, :) = a(p, :); a(p, :) = row",
            "        d = -d",
            "      end if",
            "      d = d * a(k, k)",
            "      do i = k + 1, nc",
            "        f = a(i, k) / a(k, k)",
            "        a(i, k + 1:nc) = a(i, k + 1:nc) - f * a(k, k + 1:nc)",
            "      end do",
            "    end do",
            "  end function det",
            ""]
    args = ["lam_re", "lam_im"] + plan.args + ["delta_re", "delta_im"]
    nseg = max(len(plan.segments), 1)
    out += ["  subroutine symtmm_delta(" + ", ".join(args) + ") &",
            '      bind(C, name="symtmm_delta")',
            "    real(c_double), value, intent(in) :: " + ", ".join(["lam_re", "lam_im"]
                                                                      + plan.args),
            "    real(c_double), intent(out) :: delta_re, delta_im",
            "    complex(dp) :: lam, lam2, e(ns, nc), r(nc, nc), dlt, tt(4, nc)",
            f"    complex(dp) :: u(4, 4, {nseg})",
            "    real(dp) :: dd(ns), logscale",
            f"    real(dp) :: nuv({nseg}), wv, grown",
            f"    integer :: nsub({nseg}), it, ii, kk"]
    if plan.has_eb:
        out.append("    real(dp) :: nn")
    if plan.theories:
        out.append(f"    real(dp) :: th(7, {len(plan.theories)})")
    if plan.stiff:
        out.append(f"    complex(dp) :: s({len(plan.stiff)})")
    if plan.temps:
        out.append("    real(dp) :: " + ", ".join(str(nm) for nm, _ in plan.temps))
    if any(step[0] == "point" and step[1] for step in plan.steps):
        out.append("    integer :: jj")
    out += ["    lam = cmplx(lam_re, lam_im, kind=dp)", "    lam2 = lam * lam"]
    for name, expr in plan.temps:
        out.append(f"    {name} = {f(expr)}")
    for g in plan.guards:
        out += [f"    if (.not. ({f(g)} >= 0.0_dp)) then  ! the cuts out of their order",
                "      delta_re = ieee_value(delta_re, ieee_quiet_nan)",
                "      delta_im = delta_re", "      return", "    end if"]
    if plan.theories:
        out.append("    ! beam theories: EI, a, b, cN, rhoI, m, kw")
    for t, th in enumerate(plan.theories):
        out.append(f"    th(:, {t + 1}) = [{', '.join(f(v) for v in th)}]")
    for j, lv in enumerate(plan.levels):
        blk = f"dd({4 * j + 1}:{4 * j + 4})"
        if lv[0] == "eb":
            _, EI, mu, L, k = lv
            out.append(f"    call units(abs({f(mu)} * lam2 + {f(k)})**0.25_dp, {f(EI)}, {f(L)}, "
                       f"{blk})")
        else:
            _, t, L = lv
            out.append(f"    call units(wave(lam2, th(:, {t + 1})), th(1, {t + 1}), {f(L)}, "
                       f"{blk})")
    for i, src in plan.virtual:
        out.append(f"    dd({i + 1}) = dd({src + 1})")
    out.append("    e = (0.0_dp, 0.0_dp)")
    for j, c in enumerate(plan.columns):
        out.append(f"    e({c + 1}, {j + 1}) = (1.0_dp, 0.0_dp)")
    out.append("    grown = 0.0_dp")
    out.append("    logscale = 0.0_dp" + "".join(
        f" {'+' if sg > 0 else '-'} log(dd({i + 1}))" for sg, i in _logscale_terms(plan)))
    for i, seg in enumerate(plan.segments):
        if seg[0] == "eb":
            _, a, l, EI, s = seg
            lam2s = _shifted(s, f)
            out += [f"    wv = abs(-{lam2s} * {f(a)})**0.25_dp",
                    f"    nsub({i + 1}) = steps(wv)",
                    f"    nn = real(nsub({i + 1}), kind=dp)",
                    f"    nuv({i + 1}) = wv / nn",
                    (f"    call segment({lam2s}, {f(a)} / nn**4, {f(l)} / nn, {f(EI)}, "
                     f"u(:, :, {i + 1}))")]
        else:
            _, t, l = seg
            out += [f"    wv = wave(lam2, th(:, {t + 1})) * {f(l)}",
                    f"    nsub({i + 1}) = steps(wv)",
                    f"    nuv({i + 1}) = wv / real(nsub({i + 1}), kind=dp)",
                    (f"    call segment_gen(lam2, th(:, {t + 1}), {f(l)} / real(nsub({i + 1}), "
                     f"kind=dp), u(:, :, {i + 1}))")]
    for i, coeffs in enumerate(plan.stiff):
        out.append(f"    s({i + 1}) = {_polynomial(coeffs, f)}")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            out += [f"    do it = 1, nsub({step[1] + 1})",
                    f"      if (grown + nuv({step[1] + 1}) > nu_step) then",
                    "        logscale = logscale + orthonormalise(e)",
                    "        grown = 0.0_dp",
                    "      end if",
                    "      do ii = 1, 4",
                    "        tt(ii, :) = (0.0_dp, 0.0_dp)",
                    "        do kk = 1, 4",
                    (f"          tt(ii, :) = tt(ii, :) + u(ii, kk, {step[1] + 1}) * (dd({r0} + ii) / "
                     f"dd({r0} + kk)) * e({r0} + kk, :)"),
                    "        end do",
                    "      end do",
                    f"      e({r0 + 1}:{r0 + 4}, :) = tt",
                    f"      grown = grown + nuv({step[1] + 1})",
                    "    end do"]
        elif step[1]:
            out.append("    do jj = 1, nc")
            for row, terms in step[1]:
                rhs = _jump(terms, lambda i: f"s({i + 1})", lambda c: f"e({c + 1}, jj)",
                            lambda c: f"dd({c + 1})")
                out.append(f"      e({row + 1}, jj) = e({row + 1}, jj) + dd({row + 1}) * ({rhs})")
            out.append("    end do")
    rows = ", ".join(str(r + 1) for r in plan.rows)
    out += [f"    r = e([{rows}], :)", "    dlt = det(r) * exp(logscale)",
            "    delta_re = real(dlt, kind=dp)", "    delta_im = aimag(dlt)",
            "  end subroutine symtmm_delta", "", "end module symtmm_delta_mod", ""]
    return "\n".join(w for line in out for w in _fortran_wrap(line))


# --------------------------------------------------------------------------------------
# Octave / MATLAB


def _octave_eb_helpers() -> list:
    coef = _series_coefficients()
    return ["function U = symtmm_segment(lam2, a, l, EI)",
            ("  % transfer matrix of an Euler-Bernoulli segment of length l (a = m l^4 / EI); "
             "I for l = 0"),
            "  if l == 0",
            "    U = eye(4);",
            "    return",
            "  end",
            "  x = -lam2 * a;",
            "  c = symtmm_cfun(x);",
            "  U = [c(1), l*c(2), l^2*c(3)/EI, l^3*c(4)/EI;",
            "       x*c(4)/l, c(1), l*c(2)/EI, l^2*c(3)/EI;",
            "       EI*x*c(3)/l^2, EI*x*c(4)/l, c(1), l*c(2);",
            "       EI*x*c(2)/l^3, EI*x*c(3)/l^2, x*c(4)/l, c(1)];",
            "end",
            "",
            "function c = symtmm_cfun(x)",
            "  % c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above",
            "  coef = [" + "; ".join(", ".join(row) for row in coef) + "];",
            "  c = zeros(1, 4);",
            "  if abs(x) < 1",
            "    for j = 1:4",
            "      acc = 0;",
            f"      for k = {SERIES_TERMS}:-1:1",
            "        acc = acc * x + coef(j, k);",
            "      end",
            "      c(j) = acc;",
            "    end",
            "  else",
            "    nu = x^0.25;",
            "    c(1) = (cosh(nu) + cos(nu)) / 2;",
            "    c(2) = (sinh(nu) + sin(nu)) / (2 * nu);",
            "    c(3) = (cosh(nu) - cos(nu)) / (2 * nu^2);",
            "    c(4) = (sinh(nu) - sin(nu)) / (2 * nu^3);",
            "  end",
            "end",
            ""]


def _octave_theory_helpers() -> list:
    ifact = _inverse_factorials()
    out = ["function [c, mu, t, d] = symtmm_invariants(lam2, th)",
           "  % beam theory th = [EI, a, b, cN, rhoI, m, kw] at lam2: c = cN + rhoI lam2,",
           "  % mu = m lam2 + kw, and t, d the trace and determinant of G = B C",
           "  c = th(4) + th(5) * lam2;",
           "  mu = th(6) * lam2 + th(7);",
           "  t = c / th(1) - th(3) * mu;",
           "  d = mu * (th(2) * th(2) - th(3) * c) / th(1);",
           "end",
           "",
           "function w = symtmm_wave(lam2, th)",
           "  % a bound on the largest wave number |s| of the theory th at lam2 (1/length)",
           "  [~, ~, t, d] = symtmm_invariants(lam2, th);",
           "  w = sqrt(abs(t) / 2 + sqrt(abs(t)^2 / 4 + abs(d)));",
           "end",
           "",
           "function U = symtmm_segment_gen(lam2, th, l)",
           "  % transfer matrix exp(A l) of a segment of the theory th, [Y, Theta, M, Q]:",
           "  % alpha, beta of F0 = cosh(s l), F1 = sinh(s l)/s from their series in (t, d)",
           "  % on a piece h = l/2^j with max|r| h^2 <= 1, then doubled j times",
           "  ifact = [" + ", ".join(ifact) + "];   % 1/n!, n = 0, 1, ...",
           "  EI = th(1); a = th(2); b = th(3);",
           "  [c, mu, t, d] = symtmm_invariants(lam2, th);",
           "  w = symtmm_wave(lam2, th);",
           "  h = l;",
           "  nd = 0;",
           "  while w * h > 1",
           "    h = h / 2;",
           "    nd = nd + 1;",
           "  end",
           "  T = t * h * h;",
           "  DD = d * (h * h) * (h * h);",
           "  qp = 0; q = 1; s0a = 0; s0b = 0; s1a = 0; s1b = 0;",
           f"  for k = 1:{THEORY_TERMS - 1}",
           "    s0b = s0b + q * ifact(2 * k + 1);",
           "    s0a = s0a + qp * ifact(2 * k + 1);",
           "    s1b = s1b + q * ifact(2 * k + 2);",
           "    s1a = s1a + qp * ifact(2 * k + 2);",
           "    qn = T * q - DD * qp;",
           "    qp = q;",
           "    q = qn;",
           "  end",
           "  a0 = 1 - DD * s0a; b0 = h * h * s0b;",
           "  a1 = h * (1 - DD * s1a); b1 = h * h * h * s1b;",
           "  for it = 1:nd   % F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1",
           "    na0 = 2 * (a0 * a0 - d * b0 * b0) - 1;",
           "    nb0 = 2 * (2 * a0 * b0 + t * b0 * b0);",
           "    na1 = 2 * (a0 * a1 - d * b0 * b1);",
           "    nb1 = 2 * (a0 * b1 + a1 * b0 + t * b0 * b1);",
           "    a0 = na0; b0 = nb0; a1 = na1; b1 = nb1;",
           "  end",
           "  U = zeros(4, 4);"]
    for target, expr in _theory_assembly():
        name = target if isinstance(target, str) else f"U({target[0] + 1}, {target[1] + 1})"
        out.append(f"  {name} = {expr};")
    out += ["end", ""]
    return out


def _emit_octave(plan: _Plan) -> str:
    p = lambda e: _val(e, sp.octave_code)
    args = ["lam"] + plan.args
    out = [f"function d = symtmm_delta({', '.join(args)})"]
    out += ["% " + ln for ln in _header_lines(plan, "octave")]
    out += ["% lam may be any array; d has its shape.", "  d = zeros(size(lam));"]
    for name, expr in plan.temps:
        out.append(f"  {name} = {sp.octave_code(expr)};")
    if plan.guards:
        cond = " || ".join(f"~({p(g)} >= 0)" for g in plan.guards)
        out += [f"  if {cond}  % the cuts out of their order",
                "    d(:) = NaN;", "    return", "  end"]
    for t, th in enumerate(plan.theories):
        out.append(f"  th{t + 1} = [{', '.join(p(v) for v in th)}];  % EI, a, b, cN, rhoI, m, kw")
    out += ["  for idx = 1:numel(lam)",
            "    lm = lam(idx);",
            "    lam2 = lm * lm;",
            f"    D = zeros({plan.ns}, 1);"]
    for j, lv in enumerate(plan.levels):
        blk = f"D({4 * j + 1}:{4 * j + 4})"
        if lv[0] == "eb":
            _, EI, mu, L, k = lv
            out.append(f"    {blk} = symtmm_units(abs({p(mu)} * lam2 + {p(k)})^0.25, {p(EI)}, "
                       f"{p(L)});")
        else:
            _, t, L = lv
            out.append(f"    {blk} = symtmm_units(symtmm_wave(lam2, th{t + 1}), th{t + 1}(1), "
                       f"{p(L)});")
    for i, src in plan.virtual:
        out.append(f"    D({i + 1}) = D({src + 1});")
    out.append(f"    E = zeros({plan.ns}, {plan.ncol});")
    for j, c in enumerate(plan.columns):
        out.append(f"    E({c + 1}, {j + 1}) = 1;")
    out.append("    logscale = 0" + "".join(
        f" {'+' if sg > 0 else '-'} log(D({i + 1}))" for sg, i in _logscale_terms(plan)) + ";")
    out.append("    grown = 0;   % |beta| l applied since the last orthonormalisation")
    step = _float_literal(NU_STEP)
    for i, seg in enumerate(plan.segments):
        if seg[0] == "eb":
            _, a, l, EI, s = seg
            lam2s = _shifted(s, p)
            out += [f"    w = abs(-{lam2s} * {p(a)})^0.25;",
                    f"    n{i + 1} = max(1, ceil(w / {step}));",
                    f"    nu{i + 1} = w / n{i + 1};",
                    (f"    U{i + 1} = symtmm_segment({lam2s}, {p(a)} / n{i + 1}^4, {p(l)} / "
                     f"n{i + 1}, {p(EI)});")]
        else:
            _, t, l = seg
            out += [f"    w = symtmm_wave(lam2, th{t + 1}) * {p(l)};",
                    f"    n{i + 1} = max(1, ceil(w / {step}));",
                    f"    nu{i + 1} = w / n{i + 1};",
                    f"    U{i + 1} = symtmm_segment_gen(lam2, th{t + 1}, {p(l)} / n{i + 1});"]
    for i, coeffs in enumerate(plan.stiff):
        out.append(f"    s{i + 1} = {_polynomial(coeffs, p, lam='lm')};")
    for st in plan.steps:
        if st[0] == "seg":
            r0 = 4 * st[2]
            blk = f"{r0 + 1}:{r0 + 4}"
            out += [f"    Us = U{st[1] + 1} .* (D({blk}) ./ D({blk}).');",
                    f"    for it = 1:n{st[1] + 1}",
                    f"      if grown + nu{st[1] + 1} > {step}",
                    "        [E, F] = qr(E, 0);",
                    "        logscale = logscale + sum(log(diag(F)));",
                    "        grown = 0;",
                    "      end",
                    f"      E({blk}, :) = Us * E({blk}, :);",
                    f"      grown = grown + nu{st[1] + 1};",
                    "    end"]
        else:
            for row, terms in st[1]:
                rhs = _jump(terms, lambda i: f"s{i + 1}", lambda c: f"E({c + 1}, :)",
                            lambda c: f"D({c + 1})")
                out.append(f"    E({row + 1}, :) = E({row + 1}, :) + D({row + 1}) * ({rhs});")
    rows = " ".join(str(r + 1) for r in plan.rows)
    out += [f"    d(idx) = det(E([{rows}], :)) * exp(logscale);", "  end", "end", ""]
    if plan.has_eb:
        out += _octave_eb_helpers()
    if plan.has_gen:
        out += _octave_theory_helpers()
    out += ["function D = symtmm_units(b, EI, L)",
            "  % units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number",
            "  b = max(b, 1 / L);",
            "  D = [1; 1 / b; 1 / (EI * b^2); 1 / (EI * b^3)];",
            "end",
            ""]
    return "\n".join(out)


# --------------------------------------------------------------------------------------
# Julia


def _julia_eb_helpers() -> list:
    coef = _series_coefficients()
    return [f"const SYMTMM_COEF = ({', '.join('(' + ', '.join(r) + ',)' for r in coef)},)",
            "",
            "# c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above",
            "function symtmm_cfun(x::ComplexF64)",
            "    if abs(x) < 1.0",
            "        c = zeros(ComplexF64, 4)",
            "        for j in 1:4",
            "            acc = zero(ComplexF64)",
            f"            for k in {SERIES_TERMS}:-1:1",
            "                acc = acc * x + SYMTMM_COEF[j][k]",
            "            end",
            "            c[j] = acc",
            "        end",
            "        return c",
            "    end",
            "    nu = x^0.25",
            "    ch, co, sh, si = cosh(nu), cos(nu), sinh(nu), sin(nu)",
            "    return [(ch + co) / 2, (sh + si) / (2nu), (ch - co) / (2nu^2), (sh - si) / (2nu^3)]",
            "end",
            "",
            ("# transfer matrix of an Euler-Bernoulli segment of length l (a = m l^4 / EI); "
             "I for l = 0"),
            "function symtmm_segment(lam2::ComplexF64, a::Float64, l::Float64, EI::Float64)",
            "    if l == 0",
            "        return ComplexF64[i == j ? 1 : 0 for i in 1:4, j in 1:4]",
            "    end",
            "    x = -lam2 * a",
            "    c = symtmm_cfun(x)",
            "    return ComplexF64[c[1] l*c[2] l^2*c[3]/EI l^3*c[4]/EI;",
            "                      x*c[4]/l c[1] l*c[2]/EI l^2*c[3]/EI;",
            "                      EI*x*c[3]/l^2 EI*x*c[4]/l c[1] l*c[2];",
            "                      EI*x*c[2]/l^3 EI*x*c[3]/l^2 x*c[4]/l c[1]]",
            "end",
            ""]


def _julia_theory_helpers() -> list:
    ifact = _inverse_factorials()
    out = [f"const SYMTMM_IFACT = ({', '.join(ifact)},)   # 1/n!, n = 0, 1, ...",
           "",
           "# beam theory th = (EI, a, b, cN, rhoI, m, kw) at lam2: c = cN + rhoI lam2,",
           "# mu = m lam2 + kw, and t, d the trace and determinant of G = B C",
           "function symtmm_invariants(lam2::ComplexF64, th::NTuple{7,Float64})",
           "    c = th[4] + th[5] * lam2",
           "    mu = th[6] * lam2 + th[7]",
           "    return c, mu, c / th[1] - th[3] * mu, mu * (th[2] * th[2] - th[3] * c) / th[1]",
           "end",
           "",
           "# a bound on the largest wave number |s| of the theory th at lam2 (1/length)",
           "function symtmm_wave(lam2::ComplexF64, th::NTuple{7,Float64})",
           "    _, _, t, d = symtmm_invariants(lam2, th)",
           "    return sqrt(abs(t) / 2 + sqrt(abs(t)^2 / 4 + abs(d)))",
           "end",
           "",
           "# transfer matrix exp(A l) of a segment of the theory th, [Y, Theta, M, Q]:",
           "# alpha, beta of F0 = cosh(s l), F1 = sinh(s l)/s from their series in (t, d)",
           "# on a piece h = l/2^j with max|r| h^2 <= 1, then doubled j times",
           "function symtmm_segment_gen(lam2::ComplexF64, th::NTuple{7,Float64}, l::Float64)",
           "    EI, a, b = th[1], th[2], th[3]",
           "    c, mu, t, d = symtmm_invariants(lam2, th)",
           "    w = symtmm_wave(lam2, th)",
           "    h = l",
           "    nd = 0",
           "    while w * h > 1",
           "        h /= 2",
           "        nd += 1",
           "    end",
           "    T = t * h * h",
           "    DD = d * (h * h) * (h * h)",
           "    qp, q = zero(ComplexF64), one(ComplexF64)",
           "    s0a = s0b = s1a = s1b = zero(ComplexF64)",
           f"    for k in 1:{THEORY_TERMS - 1}",
           "        s0b += q * SYMTMM_IFACT[2k + 1]",
           "        s0a += qp * SYMTMM_IFACT[2k + 1]",
           "        s1b += q * SYMTMM_IFACT[2k + 2]",
           "        s1a += qp * SYMTMM_IFACT[2k + 2]",
           "        qp, q = q, T * q - DD * qp",
           "    end",
           "    a0, b0 = 1 - DD * s0a, h * h * s0b",
           "    a1, b1 = h * (1 - DD * s1a), h * h * h * s1b",
           "    for _ in 1:nd   # F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1",
           "        a0, b0, a1, b1 = (2 * (a0 * a0 - d * b0 * b0) - 1, 2 * (2 * a0 * b0 + t * b0 * b0),",
           "                          2 * (a0 * a1 - d * b0 * b1), 2 * (a0 * b1 + a1 * b0 + t * b0 * b1))",
           "    end",
           "    U = zeros(ComplexF64, 4, 4)"]
    for target, expr in _theory_assembly():
        name = target if isinstance(target, str) else f"U[{target[0] + 1}, {target[1] + 1}]"
        out.append(f"    {name} = {expr}")
    out += ["    return U", "end", ""]
    return out


def _emit_julia(plan: _Plan) -> str:
    p = lambda e: _val(e, sp.julia_code)
    ns, nc = plan.ns, plan.ncol
    out = ["# " + ln for ln in _header_lines(plan, "julia")] + [""]
    out += [f"const SYMTMM_NU_STEP = {_float_literal(NU_STEP)}", ""]
    if plan.has_eb:
        out += _julia_eb_helpers()
    if plan.has_gen:
        out += _julia_theory_helpers()
    out += ["# units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number",
            "function symtmm_units(b::Float64, EI::Float64, L::Float64)",
            "    b = max(b, 1 / L)",
            "    return [1.0, 1 / b, 1 / (EI * b^2), 1 / (EI * b^3)]",
            "end",
            "",
            "# modified Gram-Schmidt, twice: E := Q of E = Q F; returns log det F",
            "function symtmm_orthonormalise!(E::Matrix{ComplexF64})",
            "    logdet = 0.0",
            "    for j in 1:size(E, 2)",
            "        for pass in 1:2, k in 1:j-1",
            "            r = sum(conj(E[i, k]) * E[i, j] for i in 1:size(E, 1))",
            "            for i in 1:size(E, 1)",
            "                E[i, j] -= r * E[i, k]",
            "            end",
            "        end",
            "        nrm = sqrt(sum(abs2(E[i, j]) for i in 1:size(E, 1)))",
            "        for i in 1:size(E, 1)",
            "            E[i, j] /= nrm",
            "        end",
            "        logdet += log(nrm)",
            "    end",
            "    return logdet",
            "end",
            "",
            "# determinant by Gaussian elimination with partial pivoting",
            "function symtmm_det(A::Matrix{ComplexF64})",
            "    A = copy(A)",
            "    n = size(A, 1)",
            "    d = one(ComplexF64)",
            "    for k in 1:n",
            "        p = k",
            "        for i in k+1:n",
            "            if abs(A[i, k]) > abs(A[p, k])",
            "                p = i",
            "            end",
            "        end",
            "        A[p, k] == 0 && return zero(ComplexF64)",
            "        if p != k",
            "            A[k, :], A[p, :] = A[p, :], A[k, :]",
            "            d = -d",
            "        end",
            "        d *= A[k, k]",
            "        for i in k+1:n",
            "            f = A[i, k] / A[k, k]",
            "            for j in k+1:n",
            "                A[i, j] -= f * A[k, j]",
            "            end",
            "        end",
            "    end",
            "    return d",
            "end",
            ""]
    args = ["lam::ComplexF64"] + [f"{q}::Float64" for q in plan.args]
    out += [f"function symtmm_delta({', '.join(args)})::ComplexF64",
            "    lam2 = lam * lam"]
    for name, expr in plan.temps:
        out.append(f"    {name} = {sp.julia_code(expr)}")
    for g in plan.guards:
        out.append(f"    ({p(g)} >= 0) || return ComplexF64(NaN, NaN)  # the cuts out of order")
    for t, th in enumerate(plan.theories):
        out.append(f"    th{t + 1} = ({', '.join(f'Float64({p(v)})' for v in th)},)"
                   "  # EI, a, b, cN, rhoI, m, kw")
    out.append(f"    D = zeros(Float64, {ns})")
    for j, lv in enumerate(plan.levels):
        blk = f"D[{4 * j + 1}:{4 * j + 4}]"
        if lv[0] == "eb":
            _, EI, mu, L, k = lv
            out.append(f"    {blk} = symtmm_units(abs({p(mu)} * lam2 + {p(k)})^0.25, "
                       f"Float64({p(EI)}), Float64({p(L)}))")
        else:
            _, t, L = lv
            out.append(f"    {blk} = symtmm_units(symtmm_wave(lam2, th{t + 1}), th{t + 1}[1], "
                       f"Float64({p(L)}))")
    for i, src in plan.virtual:
        out.append(f"    D[{i + 1}] = D[{src + 1}]")
    out.append(f"    E = zeros(ComplexF64, {ns}, {nc})")
    for j, c in enumerate(plan.columns):
        out.append(f"    E[{c + 1}, {j + 1}] = 1")
    out.append("    grown = 0.0   # |beta| l applied since the last orthonormalisation")
    out.append("    logscale = 0.0" + "".join(
        f" {'+' if sg > 0 else '-'} log(D[{i + 1}])" for sg, i in _logscale_terms(plan)))
    for i, seg in enumerate(plan.segments):
        if seg[0] == "eb":
            _, a, l, EI, s = seg
            lam2s = _shifted(s, p)
            out += [f"    w = abs(-{lam2s} * {p(a)})^0.25",
                    f"    n{i + 1} = max(1, ceil(Int, w / SYMTMM_NU_STEP))",
                    f"    nu{i + 1} = w / n{i + 1}",
                    (f"    U{i + 1} = symtmm_segment({lam2s}, Float64({p(a)}) / n{i + 1}^4, "
                     f"Float64({p(l)}) / n{i + 1}, Float64({p(EI)}))")]
        else:
            _, t, l = seg
            out += [f"    w = symtmm_wave(lam2, th{t + 1}) * {p(l)}",
                    f"    n{i + 1} = max(1, ceil(Int, w / SYMTMM_NU_STEP))",
                    f"    nu{i + 1} = w / n{i + 1}",
                    (f"    U{i + 1} = symtmm_segment_gen(lam2, th{t + 1}, Float64({p(l)}) / "
                     f"n{i + 1})")]
    for i, coeffs in enumerate(plan.stiff):
        out.append(f"    s{i + 1} = {_polynomial(coeffs, p)}")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            blk = f"{r0 + 1}:{r0 + 4}"
            out += [f"    Us = U{step[1] + 1} .* (D[{blk}] ./ transpose(D[{blk}]))",
                    f"    for it in 1:n{step[1] + 1}",
                    f"        if grown + nu{step[1] + 1} > SYMTMM_NU_STEP",
                    "            logscale += symtmm_orthonormalise!(E)",
                    "            grown = 0.0",
                    "        end",
                    f"        E[{blk}, :] = Us * E[{blk}, :]",
                    f"        grown += nu{step[1] + 1}",
                    "    end"]
        else:
            for row, terms in step[1]:
                rhs = _jump(terms, lambda i: f"s{i + 1}", lambda c: f"E[{c + 1}, :]",
                            lambda c: f"D[{c + 1}]", mul=".*", div="./")
                rhs = rhs.replace(" + ", " .+ ").replace(" - ", " .- ")
                out.append(f"    E[{row + 1}, :] = E[{row + 1}, :] .+ D[{row + 1}] .* ({rhs})")
    rows = ", ".join(str(r + 1) for r in plan.rows)
    out += [f"    return symtmm_det(E[[{rows}], :]) * exp(logscale)", "end", ""]
    return "\n".join(out)


# --------------------------------------------------------------------------------------
# Python (numpy only)


def _python_eb_helpers() -> list:
    coef = _series_coefficients()
    out = ["_COEF = ("]
    for row in coef:
        out.append("    (" + ", ".join(row) + "),")
    out += [")", "", "",
            "def _cfun(x):",
            '    """c_0..c_3 of a complex array x: series below |x| = 1, closed forms above."""',
            "    small = np.abs(x) < 1.0",
            "    out = [np.empty_like(x) for _ in range(4)]",
            "    if small.any():",
            "        xs = x[small]",
            "        for j in range(4):",
            "            acc = np.zeros_like(xs)",
            "            for k in reversed(range(len(_COEF[j]))):",
            "                acc = acc * xs + _COEF[j][k]",
            "            out[j][small] = acc",
            "    big = ~small",
            "    if big.any():",
            "        nu = x[big] ** 0.25",
            "        ch, co, sh, si = np.cosh(nu), np.cos(nu), np.sinh(nu), np.sin(nu)",
            "        out[0][big] = (ch + co) / 2",
            "        out[1][big] = (sh + si) / (2 * nu)",
            "        out[2][big] = (ch - co) / (2 * nu**2)",
            "        out[3][big] = (sh - si) / (2 * nu**3)",
            "    return out",
            "",
            "",
            "def _segment(lam2, a, l, EI):",
            ('    """Transfer matrices of an Euler-Bernoulli segment, shape (N, 4, 4); '
             'a = m l^4 / EI."""'),
            "    if l == 0:",
            "        return np.broadcast_to(np.eye(4, dtype=complex), lam2.shape + (4, 4))",
            "    x = -lam2 * a",
            "    c0, c1, c2, c3 = _cfun(x)",
            "    rows = [[c0, l * c1, l**2 * c2 / EI, l**3 * c3 / EI],",
            "            [x * c3 / l, c0, l * c1 / EI, l**2 * c2 / EI],",
            "            [EI * x * c2 / l**2, EI * x * c3 / l, c0, l * c1],",
            "            [EI * x * c1 / l**3, EI * x * c2 / l**2, x * c3 / l, c0]]",
            "    return np.stack([np.stack(r, axis=-1) for r in rows], axis=-2)",
            "",
            ""]
    return out


def _python_theory_helpers() -> list:
    ifact = _inverse_factorials()
    out = ["_IFACT = ("]
    for i in range(0, len(ifact), 4):
        out.append("    " + ", ".join(ifact[i:i + 4]) + ",")
    out += [")   # 1/n!, n = 0, 1, ...", "", "",
            "def _invariants(lam2, th):",
            '    """c, mu, t, d of a beam theory th = (EI, a, b, cN, rhoI, m, kw) at lam2."""',
            "    EI, a, b, cN, rhoI, m, kw = th",
            "    c = cN + rhoI * lam2",
            "    mu = m * lam2 + kw",
            "    return c, mu, c / EI - b * mu, mu * (a * a - b * c) / EI",
            "",
            "",
            "def _wave(lam2, th):",
            '    """A bound on the largest wave number |s| of the theory th at lam2 (1/length)."""',
            "    _, _, t, d = _invariants(lam2, th)",
            "    return np.sqrt(np.abs(t) / 2 + np.sqrt(np.abs(t) ** 2 / 4 + np.abs(d)))",
            "",
            "",
            "def _segment_gen(lam2, th, l):",
            '    """exp(A l) of a segment of the theory th, shape (N, 4, 4), [Y, Theta, M, Q].',
            "",
            "    alpha, beta of F0 = cosh(s l), F1 = sinh(s l)/s from their series in (t, d)",
            "    on a piece h = l/2^j with max|r| h^2 <= 1 (over the batch), then doubled.",
            '    """',
            "    EI, a, b = th[:3]",
            "    c, mu, t, d = _invariants(lam2, th)",
            "    w = float(np.max(_wave(lam2, th), initial=0.0))",
            "    h, nd = l, 0",
            "    while w * h > 1.0:",
            "        h /= 2",
            "        nd += 1",
            "    T, DD = t * h * h, d * (h * h) * (h * h)",
            "    qp, q = np.zeros_like(lam2), np.ones_like(lam2)",
            "    s0a, s0b, s1a, s1b = (np.zeros_like(lam2) for _ in range(4))",
            f"    for k in range(1, {THEORY_TERMS}):",
            "        s0b = s0b + q * _IFACT[2 * k]",
            "        s0a = s0a + qp * _IFACT[2 * k]",
            "        s1b = s1b + q * _IFACT[2 * k + 1]",
            "        s1a = s1a + qp * _IFACT[2 * k + 1]",
            "        qp, q = q, T * q - DD * qp",
            "    a0, b0 = 1 - DD * s0a, h * h * s0b",
            "    a1, b1 = h * (1 - DD * s1a), h * h * h * s1b",
            "    for _ in range(nd):   # F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1",
            "        a0, b0, a1, b1 = (2 * (a0 * a0 - d * b0 * b0) - 1, 2 * (2 * a0 * b0 + t * b0 * b0),",
            "                          2 * (a0 * a1 - d * b0 * b1), 2 * (a0 * b1 + a1 * b0 + t * b0 * b1))",
            "    U = np.empty(lam2.shape + (4, 4), dtype=complex)"]
    for target, expr in _theory_assembly():
        name = target if isinstance(target, str) else f"U[..., {target[0]}, {target[1]}]"
        out.append(f"    {name} = {expr}")
    out += ["    return U", "", ""]
    return out


def _emit_python(plan: _Plan) -> str:
    pyc = lambda x: sp.pycode(x).replace("math.", "np.")
    p = lambda e: _val(e, pyc)
    # the header as comments, not in the docstring: no text of the model's can end a
    # comment, while a docstring ends at the first triple quote and reads backslashes;
    # the fixed first line keeps it clear of the two lines Python reads for an encoding
    out = ['"""Delta(lam) = det R(lam) of a symtmm model (generated; see the comments)."""',
           ""] + [f"# {ln}".rstrip() for ln in _header_lines(plan, "python")]
    out += ["", "import numpy as np", "", f"_NU_STEP = {_float_literal(NU_STEP)}"]
    if plan.has_eb:
        out += _python_eb_helpers()
    if plan.has_gen:
        out += _python_theory_helpers()
    out += ["",
            "def _units(b, EI, L):",
            ('    """Units of one beam\'s state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L, '
             'shape (N, 4)."""'),
            "    b = np.maximum(b, 1 / L)",
            ("    return np.stack([np.ones_like(b), 1 / b, 1 / (EI * b**2), 1 / (EI * b**3)], "
             "axis=-1)"),
            "",
            "",
            "def _steps(nu):",
            '    """Per point, the steps of |beta| l <= _NU_STEP for a segment with nu = |beta| l."""',
            "    n = np.ceil(np.where(np.isfinite(nu), nu, 0.0) / _NU_STEP)",
            "    return np.maximum(n, 1).astype(int)",
            "",
            ""]
    args = ["lam"] + plan.args
    out += [f"def symtmm_delta({', '.join(args)}):",
            '    """Delta(lam) for an array of eigenvalues lam (complex); same shape."""',
            "    lam = np.asarray(lam, dtype=complex)",
            "    flat = lam.reshape(-1)",
            "    lam2 = flat * flat"]
    for name, expr in plan.temps:
        out.append(f"    {name} = {pyc(expr)}")
    if plan.guards:
        cond = " or ".join(f"not ({p(g)} >= 0)" for g in plan.guards)
        out += [f"    if {cond}:  # the cuts out of their order",
                "        return np.full(lam.shape, np.nan + 1j * np.nan)"]
    for t, th in enumerate(plan.theories):
        out.append(f"    th{t} = ({', '.join(p(v) for v in th)})  # EI, a, b, cN, rhoI, m, kw")
    out += ["",
            "    def core(flat, lam2, steps):",
            '        """Delta at points whose segments all take the same numbers of steps."""']
    body = [f"D = np.empty((flat.size, {plan.ns}))"]
    for j, lv in enumerate(plan.levels):
        blk = f"D[:, {4 * j}:{4 * j + 4}]"
        if lv[0] == "eb":
            _, EI, mu, L, k = lv
            body.append(f"{blk} = _units(np.abs({p(mu)} * lam2 + {p(k)}) ** 0.25, {p(EI)}, "
                        f"{p(L)})")
        else:
            _, t, L = lv
            body.append(f"{blk} = _units(_wave(lam2, th{t}), th{t}[0], {p(L)})")
    for i, src in plan.virtual:
        body.append(f"D[:, {i}] = D[:, {src}]")
    body.append(f"E = np.zeros((flat.size, {plan.ns}, {plan.ncol}), dtype=complex)")
    for j, c in enumerate(plan.columns):
        body.append(f"E[:, {c}, {j}] = 1.0")
    body.append("logscale = np.zeros(flat.size, dtype=complex)" + "".join(
        f" {'+' if sg > 0 else '-'} np.log(D[:, {i}])" for sg, i in _logscale_terms(plan)))
    nus = []
    body.append("grown = 0.0   # |beta| l applied since the last orthonormalisation")
    for i, seg in enumerate(plan.segments):
        body.append(f"n{i} = int(steps[{i}])")
        if seg[0] == "eb":
            _, a, l, EI, s = seg
            lam2s = _shifted(s, p)
            nus.append(f"np.abs(-{lam2s} * {p(a)}) ** 0.25")
            body.append(f"nu{i} = float(np.max({nus[-1]}, initial=0.0)) / n{i}")
            body.append(f"U{i} = _segment({lam2s}, {p(a)} / n{i}**4, {p(l)} / n{i}, {p(EI)})")
        else:
            _, t, l = seg
            nus.append(f"_wave(lam2, th{t}) * {p(l)}")
            body.append(f"nu{i} = float(np.max({nus[-1]}, initial=0.0)) / n{i}")
            body.append(f"U{i} = _segment_gen(lam2, th{t}, {p(l)} / n{i})")
    for i, coeffs in enumerate(plan.stiff):
        body.append(f"s{i} = np.broadcast_to({_polynomial(coeffs, p, lam='flat')}, "
                    "flat.shape)[:, None]")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            blk = f"{r0}:{r0 + 4}"
            body += [f"Us = U{step[1]} * (D[:, {blk}, None] / D[:, None, {blk}])",
                     f"for _ in range(n{step[1]}):",
                     f"    if grown + nu{step[1]} > _NU_STEP:",
                     "        E, F = np.linalg.qr(E)",
                     ("        logscale += np.sum(np.log(np.diagonal(F, axis1=-2, axis2=-1)), "
                      "axis=-1)"),
                     "        grown = 0.0",
                     f"    E[:, {blk}, :] = Us @ E[:, {blk}, :]",
                     f"    grown += nu{step[1]}"]
        else:
            for row, terms in step[1]:
                rhs = _jump(terms, lambda i: f"s{i}", lambda c: f"E[:, {c}, :]",
                            lambda c: f"D[:, {c}, None]")
                body.append(f"E[:, {row}, :] += D[:, {row}, None] * ({rhs})")
    body += [f"R = E[:, {plan.rows}, :]", "return np.linalg.det(R) * np.exp(logscale)"]
    out += ["        " + ln for ln in body]
    out += ["",
            "    # a batch shares its numbers of steps: points that need the same are taken",
            "    # together (a point given the steps of a far higher mode loses digits)",
            f"    steps = np.stack([{', '.join(f'_steps({nu})' for nu in nus)}], axis=-1)",
            "    out = np.empty(flat.shape, dtype=complex)",
            "    for key in np.unique(steps, axis=0):",
            "        sel = np.all(steps == key, axis=1)",
            "        out[sel] = core(flat[sel], lam2[sel], key)",
            "    return out.reshape(lam.shape)", ""]
    return "\n".join(out)


_EMITTERS = {"c": _emit_c, "fortran": _emit_fortran, "octave": _emit_octave,
             "julia": _emit_julia, "python": _emit_python}


def generate(model, lang: str, symbolic=()) -> str:
    """Source code of a self-contained evaluator of ``Delta(lam)`` for ``model``.

    Parameters
    ----------
    model : Model
        Any beam theory (Euler–Bernoulli, Rayleigh, Timoshenko; axial force,
        Winkler foundation), point elements and rigid bodies or joints.
        Parameters without value (and those named in ``symbolic``) become
        extra arguments after ``lam``, in alphabetical order.
    lang : {"c", "fortran", "octave", "julia", "python"}
    symbolic : iterable of str
        Parameters to turn into arguments although the model gives them a
        value (that value then only orders the cuts).

    Returns
    -------
    str
        The source file.
    """
    if lang not in _EMITTERS:
        raise ValueError(f"unknown language {lang!r} (use one of {', '.join(LANGUAGES)})")
    return _EMITTERS[lang](_for_language(_plan(model, symbolic), lang))
