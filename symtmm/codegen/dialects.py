"""How each language writes what the walker asks for: one small table per language.

A :class:`Dialect` holds a language's literals and expression printer, its
statement forms (assignment, ``if``, ``for``, calls of the runtime routines),
its array indexing (first index, and for the numpy batch a leading axis of
points), its comments and declarations, the layout of the file around the
evaluator, and its identifier rules: the names an argument must not take.
:mod:`symtmm.codegen.walker` writes the evaluator once through any of them.

Examples
--------
>>> c, fortran, python = DIALECTS["c"], DIALECTS["fortran"], DIALECTS["python"]
>>> c.item("E", 2, 0), fortran.item("E", 2, 0), python.item("E", 2, 0)
('E[2][0]', 'E(3, 1)', 'E[:, 2, 0]')
>>> c.block("D", 4), fortran.block("D", 4), python.block("D", 4)
('D + 4', 'D(5:8)', 'D[:, 4:8]')
>>> fortran.value(sp.Rational(1, 4)), python.value(2 * sp.Symbol("K"))
('0.25_dp', '2*K')
"""

from __future__ import annotations

import keyword
import re

import sympy as sp

from .plan import float_literal

__all__ = ["DIALECTS", "Dialect"]

# Names every evaluator uses (an argument with one of them would hide it).
_COMMON = frozenset({"lam", "lam2", "D", "E", "R", "logscale"})


class Dialect:
    """A language as the walker sees it; subclasses fill in the tables.

    Attributes hold the fixed forms (format strings with ``{}`` fields), the
    methods the forms that compute with indices. Every name the walker uses
    is the same in all languages; only the runtime routines carry the
    dialect's ``prefix``.
    """

    name = ""
    extension = ""
    gap = "\n\n"                   # between two pieces of the runtime
    indent = "    "
    end = ""                      # statement terminator
    comment = "#"                 # line comment
    prefix = "symtmm_"            # the runtime routines' names start with it
    runtime = ("kernels",)        # runtime source stems, each included when the model needs it
    base = 0                      # index of the first element
    lam = "lam"                   # the point's eigenvalue in the per-point part
    #: declare a local where it is first set (C), at the top (Fortran), or never
    declares = None
    if_open, if_close = "if {}:", None
    for_open, for_close = "for {} in range({}):", None
    negative, either = "not ({} >= 0)", " or "
    vector = "({})"
    fourth_root = "abs({})^0.25"
    log = "log({})"
    exp = "exp({})"
    steps = "max(1, ceil({} / nu_step))"   # steps of |beta| l <= nu_step for a wave w
    peak = "{}"                   # the largest wave of a batch (numpy), the wave elsewhere
    stiffness = "{}"              # a station's stiffness where it multiplies a row
    call = "{out} = {fn}({args})"  # a runtime routine that returns an array
    nan_exit: tuple = ()
    deliver: tuple = ()
    orthonormalise = ""
    row_loop = False              # whether a row of E is updated column by column (C)
    # identifier rules
    reserved: frozenset = frozenset()
    reserved_pattern = re.compile(r"(?!)")
    fold = staticmethod(lambda name: name)
    evaluator = ("", "")          # regular expressions around the evaluator in the file
    not_code = ""                 # comments and strings: words there are no names

    # --- expressions

    def printer(self, expr) -> str:
        raise NotImplementedError

    def literal(self, value) -> str:
        return float_literal(value)

    def value(self, expr) -> str:
        """A plan value: a number as an exact-to-double literal, else printed."""
        expr = sp.sympify(expr)
        return self.literal(expr) if expr.is_number else self.printer(expr)

    def fn(self, name: str) -> str:
        """The name of runtime routine ``name`` (``units``, ``segment``, ...)."""
        return self.prefix + name

    # --- arrays (indices are 0-based here)

    def item(self, name, *index) -> str:
        return f"{name}({', '.join(str(i + 1) for i in index)})"

    def row(self, name, r) -> str:
        """Row ``r`` of the columns, every column at once (or the current one)."""
        return f"{name}({r + 1}, :)"

    def scalar(self, name, i) -> str:
        """``name[i]`` where it multiplies a row."""
        return self.item(name, i)

    def block(self, name, lo) -> str:
        """Entries ``lo .. lo + 3`` of the units, the four of one beam."""
        return f"{name}({lo + 1}:{lo + 4})"

    def rows(self, name, lo) -> str:
        """Rows ``lo .. lo + 3`` of the columns."""
        return f"{name}({lo + 1}:{lo + 4}, :)"

    def pick(self, rows) -> str:
        """The rows ``rows`` of the columns, as a matrix."""
        return f"E([{', '.join(str(r + 1) for r in rows)}], :)"

    def zeros(self, name, kind, dims) -> str:
        raise NotImplementedError

    def declaration(self, name, kind, dims) -> str:
        raise NotImplementedError

    # --- statements

    def assign(self, target, value) -> str:
        return f"{target} = {value}{self.end}"

    def scale(self, k, lo) -> str:
        """``Us = D U_k D^-1`` for the beam whose units start at ``lo``."""
        raise NotImplementedError

    def apply(self, lo, ncol) -> str:
        """Rows ``lo .. lo + 3`` of the ``ncol`` columns multiplied by ``Us``."""
        return self.assign(self.rows("E", lo), f"Us * {self.rows('E', lo)}")

    def det(self, plan) -> str:
        return f"{self.fn('det')}({self.pick(plan.rows)})"

    # --- the file

    def header(self, lines) -> list:
        return [f"{self.comment} {ln}".rstrip() for ln in lines]

    def host_names(self, code) -> str:
        """Text of ``code`` outside the evaluator whose names the evaluator sees too."""
        return ""

    def function(self, plan, body, waves) -> list:
        """The evaluator around ``body`` (:class:`~symtmm.codegen.walker.Body`)."""
        raise NotImplementedError

    def file(self, header, runtime, function) -> list:
        return [*header, "", runtime, "", *function, ""]

    def finish(self, lines) -> str:
        return "\n".join(lines)


class C(Dialect):
    name = "c"
    extension = "c"
    end = ";"
    runtime = ("core", "euler_bernoulli", "theory")
    declares = "in place"
    if_open, if_close = "if ({}) {{", "}"
    for_open, for_close = "for (int {0} = 0; {0} < {1}; {0}++) {{", "}"
    negative, either = "!({} >= 0)", " || "
    vector = "{{{}}}"
    fourth_root = "pow(cabs({}), 0.25)"
    steps = "(int)fmax(1.0, ceil({} / nu_step))"
    call = "{fn}({args}, {out});"
    nan_exit = ("*delta_re = NAN;", "*delta_im = NAN;", "return;")
    deliver = ("*delta_re = creal(delta);", "*delta_im = cimag(delta);")
    orthonormalise = "symtmm_orthonormalise({ns}, {nc}, E, &logscale);"
    row_loop = True
    reserved = _COMMON | {
        "lam_re", "lam_im", "delta_re", "delta_im", "U", "d", "s", "n", "nsub", "nu", "grown",
        "w", "t", "j", "NS", "NC", "NU_STEP", "I", "auto", "break", "case", "char", "const",
        "continue", "default", "do", "double", "else", "enum", "extern", "float", "for",
        "goto", "if", "inline", "int", "long", "register", "restrict", "return", "short",
        "signed", "sizeof", "static", "struct", "switch", "typedef", "union", "unsigned",
        "void", "volatile", "while", "complex", "creal", "cimag", "cabs", "cpow", "ccosh",
        "ccos", "csinh", "csin", "conj", "sqrt", "pow", "log", "exp", "ceil", "NAN", "M_PI",
        # every keyword up to C23 and GNU's, the object-like macros of <complex.h> and
        # <math.h> (glibc in any mode, other C libraries' SVID names) and the system names
        # compilers predefine outside strict ISO mode (`gcc -std=gnu99` defines linux = 1);
        # the M_, FP_, HUGE_VAL, SNAN, CMPLX and MATH_ERR families by reserved_pattern
        "_Bool", "_Complex", "_Imaginary", "alignas", "alignof", "asm", "bool", "constexpr",
        "false", "fortran", "nullptr", "static_assert", "thread_local", "true", "typeof",
        "typeof_unqual", "imaginary", "INFINITY", "HUGE", "MAXFLOAT", "DOMAIN", "SING",
        "OVERFLOW", "UNDERFLOW", "TLOSS", "PLOSS", "X_TLOSS", "math_errhandling", "errno",
        "linux", "unix", "i386", "i486", "i586", "i686", "sun", "sparc", "mips", "vax",
        "hppa", "m68k", "mc68000", "ns32000", "pdp11", "ppc", "powerpc", "arm", "sgi",
        "fpclassify", "iscanonical", "iseqsig", "isfinite", "isgreater", "isgreaterequal",
        "isinf", "isless", "islessequal", "islessgreater", "isnan", "isnormal", "issignaling",
        "issubnormal", "isunordered", "iszero", "signbit"}
    reserved_pattern = re.compile(r"^(?:M_|FP_|HUGE_VAL|SNAN|CMPLX|MATH_ERR)")
    evaluator = (r"^void symtmm_delta\(", r"^\}$")
    not_code = r"/\*[\s\S]*?\*/|\"[^\"\n]*\""

    def printer(self, expr):
        return sp.ccode(expr)

    def item(self, name, *index):
        return name + "".join(f"[{i}]" for i in index)

    def row(self, name, r):
        return f"{name}[{r}][j]"

    def block(self, name, lo):
        return f"{name} + {lo}"

    rows = block

    def zeros(self, name, kind, dims):
        return f"{self.declaration(name, kind, dims)} = {'{' * len(dims)}0{'}' * len(dims)};"

    def declaration(self, name, kind, dims):
        ctype = {"real": "double", "complex": "double complex", "int": "int"}[kind]
        return ctype + f" {name}" + "".join(f"[{n}]" for n in dims)

    def scale(self, k, lo):
        return f"symtmm_scaled(U{k}, D + {lo}, Us);"

    def apply(self, lo, ncol):
        return f"symtmm_apply({ncol}, Us, E + {lo});"

    def det(self, plan):
        rows = ", ".join(map(str, plan.rows))
        return f"symtmm_det({plan.size}, {plan.ncol}, E, (const int[]){{{rows}}})"

    def header(self, lines):
        return ["/*", *(f" * {ln}".rstrip() for ln in lines), " */"]

    def function(self, plan, body, waves):
        args = ["double lam_re", "double lam_im", *(f"double {a}" for a in plan.args),
                "double *delta_re", "double *delta_im"]
        return [f"void symtmm_delta({', '.join(args)})", "{",
                "    double complex lam = lam_re + lam_im * I, lam2 = lam * lam;",
                *body.render(1), "}"]


class Fortran(Dialect):
    name = "fortran"
    extension = "f90"
    indent = "  "
    comment = "!"
    runtime = ("core", "euler_bernoulli", "theory")
    declares = "at the top"
    if_open, if_close = "if ({}) then", "end if"
    for_open, for_close = "do {} = 1, {}", "end do"
    negative, either = ".not. ({} >= 0)", " .or. "
    vector = "[{}]"
    fourth_root = "abs({})**0.25_dp"
    steps = "max(1, ceiling({} / nu_step))"
    call = "call {fn}({args}, {out})"
    nan_exit = ("delta_re = ieee_value(delta_re, ieee_quiet_nan)", "delta_im = delta_re",
                "return")
    deliver = ("delta_re = real(delta, kind=dp)", "delta_im = aimag(delta)")
    orthonormalise = "call symtmm_orthonormalise(E, logscale)"
    # Fortran ignores case: compared in lower case
    reserved = _COMMON | {
        "lam_re", "lam_im", "delta_re", "delta_im", "e", "r", "dlt", "tt", "u", "dd", "nn",
        "nsub", "nuv", "wv", "grown", "it", "ii", "kk", "jj", "s", "dp", "ns", "nc", "nu_step",
        "coef", "cfun", "segment", "steps", "units", "orthonormalise", "det", "abs", "real",
        "aimag", "cmplx", "sqrt", "exp", "log", "cos", "cosh", "sin", "sinh", "conjg", "sum",
        "ceiling", "max", "kind", "ieee_value", "ieee_quiet_nan", "ieee_arithmetic",
        "iso_c_binding", "c_double", "c_double_complex", "th", "ifact", "invariants", "wave",
        "segment_gen", "steps_nu", "units_b", "matmul", "spread"}
    fold = staticmethod(str.lower)
    evaluator = (r"^  subroutine symtmm_delta\(", r"^  end subroutine symtmm_delta$")
    not_code = r"![^\n]*|\"[^\"\n]*\"|'[^'\n]*'"

    def printer(self, expr):
        text = sp.fcode(expr, source_format="free", standard=2008)
        text = re.sub(r"&\s*\n\s*", "", text)
        # double-precision literals 1.5d0, 2.0d-8 -> kind dp
        return re.sub(r"(\d)d([+-]?\d+)", lambda m: f"{m.group(1)}e{m.group(2)}_dp", text)

    def literal(self, value):
        text = f"{float_literal(value)}_dp"
        return f"({text})" if text.startswith("-") else text   # no operator after another

    def pick(self, rows):
        return f"E([{', '.join(str(r + 1) for r in rows)}], :)"

    def zeros(self, name, kind, dims):
        return f"{name} = 0"

    def declaration(self, name, kind, dims):
        ftype = {"real": "real(dp)", "complex": "complex(dp)", "int": "integer"}[kind]
        shape = f"({', '.join(map(str, dims))})" if dims else ""
        return f"{ftype} :: {name}{shape}"

    def scale(self, k, lo):
        d = self.block("D", lo)
        return f"Us = U{k} * (spread({d}, 2, 4) / spread({d}, 1, 4))"

    def apply(self, lo, ncol):
        return f"{self.rows('E', lo)} = matmul(Us, {self.rows('E', lo)})"

    def host_names(self, code):
        # the module's declarations and every procedure, by host association
        return code[:code.index("\ncontains\n")] + " ".join(
            re.findall(r"\b(?:subroutine|function)\s+(\w+)", code))

    def function(self, plan, body, waves):
        inputs = ", ".join(["lam_re", "lam_im", *plan.args])
        return [f"  subroutine symtmm_delta({inputs}, delta_re, delta_im) &",
                '      bind(C, name="symtmm_delta")',
                f"    real(c_double), value, intent(in) :: {inputs}",
                "    real(c_double), intent(out) :: delta_re, delta_im",
                "    complex(dp) :: lam, lam2",
                *(f"    {d}" for d in body.declarations()),
                "    lam = cmplx(lam_re, lam_im, kind=dp)",
                "    lam2 = lam * lam",
                *body.render(2), "  end subroutine symtmm_delta"]

    def file(self, header, runtime, function):
        return [*header, "", "module symtmm_delta_mod",
                "  use iso_c_binding, only: c_double",
                "  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan",
                "  implicit none", "  private", "  public :: symtmm_delta",
                "  integer, parameter :: dp = c_double", "contains", "", runtime, "", *function,
                "end module symtmm_delta_mod", ""]

    def finish(self, lines):
        return "\n".join(piece for line in lines for piece in _wrap(line))


def _wrap(line: str, width: int = 100) -> list:
    """A long free-form Fortran line split with ``&`` continuations (the limit is 132)."""
    if line.lstrip().startswith("!") or "\n" in line:
        return [line]
    out = []
    while len(line) > width:
        cut = line.rfind(" ", 0, width)
        if cut <= line.find(line.strip()[0]):
            break
        out.append(line[:cut] + " &")
        line = "      " + line[cut + 1:]
    return out + [line]


class Octave(Dialect):
    name = "octave"
    extension = "m"
    indent = "  "
    end = ";"
    comment = "%"
    lam = "lm"
    if_open, if_close = "if {}", "end"
    for_open, for_close = "for {} = 1:{}", "end"
    negative, either = "~({} >= 0)", " || "
    vector = "[{}]"
    call = "{out} = {fn}({args});"
    nan_exit = ("d(:) = NaN;", "return")
    deliver = ("d(idx) = delta;",)
    orthonormalise = "[E, logscale] = symtmm_orthonormalise(E, logscale);"
    reserved = _COMMON | {
        "d", "lm", "idx", "Us", "it", "F", "w", "grown", "end", "function", "for", "if", "else",
        "elseif", "while", "return", "switch", "case", "otherwise", "do", "until", "break",
        "continue", "global", "persistent", "try", "catch", "i", "j", "pi", "e", "abs",
        "sqrt", "exp", "log", "cos", "sin", "cosh", "sinh", "zeros", "numel", "size", "det",
        "qr", "diag", "ceil", "max", "NaN", "Inf", "sum", "complex", "real", "imag",
        # iskeyword() of Octave 8 and MATLAB's, and the constants and variables every
        # function sees (an argument i or e would hide the constant; nargin is set on entry)
        "__FILE__", "__LINE__", "classdef", "end_try_catch", "end_unwind_protect",
        "endarguments", "endclassdef", "endenumeration", "endevents", "endfor", "endfunction",
        "endif", "endmethods", "endparfor", "endproperties", "endspmd", "endswitch",
        "endwhile", "parfor", "spmd", "unwind_protect", "unwind_protect_cleanup",
        "arguments", "methods", "properties", "events", "enumeration", "I", "J", "inf",
        "nan", "NA", "eps", "ans", "nargin", "nargout", "varargin", "varargout", "true",
        "false"}
    evaluator = (r"^function d = symtmm_delta\(", r"^end$")
    not_code = r"%[^\n]*"

    def printer(self, expr):
        return sp.octave_code(expr)

    def zeros(self, name, kind, dims):
        return f"{name} = zeros({', '.join(map(str, dims + (1,) * (2 - len(dims))))});"

    def scale(self, k, lo):
        d = self.block("D", lo)
        return f"Us = U{k} .* ({d} ./ {d}.');"

    def det(self, plan):
        return f"det({self.pick(plan.rows)})"

    def function(self, plan, body, waves):
        return [f"function d = symtmm_delta({', '.join(['lam', *plan.args])})",
                "  d = zeros(size(lam));", *body.render(1, body.params),
                "  for idx = 1:numel(lam)   % one point at a time",
                "    lm = lam(idx);", "    lam2 = lm * lm;",
                *body.render(2, body.point), "  end", "end"]

    def file(self, header, runtime, function):
        # the help text of an Octave function follows its first line
        return [function[0], *header, *function[1:], "", runtime]


class Julia(Dialect):
    name = "julia"
    extension = "jl"
    if_open, if_close = "if {}", "end"
    for_open, for_close = "for {} in 1:{}", "end"
    negative, either = "!({} >= 0)", " || "
    steps = "max(1, ceil(Int, {} / nu_step))"
    nan_exit = ("return ComplexF64(NaN, NaN)",)
    deliver = ("return delta",)
    orthonormalise = "logscale = symtmm_orthonormalise!(E, logscale)"
    reserved = _COMMON | {
        "Us", "it", "w", "grown", "begin", "end", "function", "for", "if", "else", "elseif",
        "while", "return", "let", "local", "global", "const", "do", "try", "catch", "finally",
        "struct", "mutable", "module", "using", "import", "export", "quote", "macro",
        "abstract", "primitive", "type", "in", "isa", "true", "false", "break", "continue",
        "baremodule", "where", "outer", "im", "pi", "abs", "sqrt", "exp", "log", "cos", "sin",
        "cosh", "sinh", "conj", "zeros", "one", "zero", "size", "ceil", "Int", "max", "NaN",
        "Float64", "ComplexF64", "transpose", "NTuple",
        # keywords of Julia 1.11 (public included) and the names of Core every file sees
        "public", "ccall", "nothing", "missing", "Inf", "ans", "Base", "Core", "Main",
        "ComplexF32", "Float32", "Complex", "Matrix", "Vector"}
    evaluator = (r"^function symtmm_delta\(", r"^end$")
    not_code = r"#[^\n]*|\"[^\"\n]*\""

    def printer(self, expr):
        return sp.julia_code(expr)

    def item(self, name, *index):
        return f"{name}[{', '.join(str(i + 1) for i in index)}]"

    def row(self, name, r):
        return f"{name}[{r + 1}, :]"

    def block(self, name, lo):
        return f"{name}[{lo + 1}:{lo + 4}]"

    def rows(self, name, lo):
        return f"{name}[{lo + 1}:{lo + 4}, :]"

    def pick(self, rows):
        return f"E[[{', '.join(str(r + 1) for r in rows)}], :]"

    def zeros(self, name, kind, dims):
        eltype = {"real": "Float64", "complex": "ComplexF64"}[kind]
        return f"{name} = zeros({eltype}, {', '.join(map(str, dims))})"

    def scale(self, k, lo):
        d = self.block("D", lo)
        return f"Us = U{k} .* ({d} ./ transpose({d}))"

    def function(self, plan, body, waves):
        args = ", ".join(["lam::ComplexF64", *(f"{a}::Float64" for a in plan.args)])
        return [f"function symtmm_delta({args})::ComplexF64", "    lam2 = lam * lam",
                *body.render(1), "end"]


class Python(Dialect):
    name = "python"
    extension = "py"
    prefix = "_"
    fourth_root = "np.abs({}) ** 0.25"
    log = "np.log({})"
    exp = "np.exp({})"
    steps = "int(steps[{1}])"
    peak = "float(np.max({}, initial=0.0))"
    stiffness = "np.broadcast_to({}, lam.shape)[:, None]"
    nan_exit = ("return np.full(lam.shape, np.nan + 1j * np.nan)",)
    deliver = ("return delta",)
    orthonormalise = "E, logscale = _orthonormalise(E, logscale)"
    reserved = _COMMON | {
        "flat", "Us", "F", "np", "n", "out", "sel", "key", "steps", "core", "grown",
        *keyword.kwlist,
        # the builtins (an argument called complex, float, int or range breaks the code
        # that calls them) and numpy's module name
        "abs", "aiter", "all", "anext", "any", "ascii", "bin", "bool", "breakpoint",
        "bytearray", "bytes", "callable", "chr", "classmethod", "compile", "complex",
        "copyright", "credits", "delattr", "dict", "dir", "divmod", "enumerate", "eval", "exec",
        "exit", "filter", "float", "format", "frozenset", "getattr", "globals", "hasattr",
        "hash", "help", "hex", "id", "input", "int", "isinstance", "issubclass", "iter", "len",
        "license", "list", "locals", "map", "max", "memoryview", "min", "next", "object", "oct",
        "open", "ord", "pow", "print", "property", "quit", "range", "repr", "reversed",
        "round", "set", "setattr", "slice", "sorted", "staticmethod", "str", "sum", "super",
        "tuple", "type", "vars", "zip", "Ellipsis", "NotImplemented", "numpy"}
    evaluator = (r"^def symtmm_delta\(", r"\Z")
    not_code = r"#[^\n]*|\"\"\"[\s\S]*?\"\"\"|\"[^\"\n]*\"|'[^'\n]*'"

    def printer(self, expr):
        return sp.pycode(expr).replace("math.", "np.")

    def item(self, name, *index):
        return f"{name}[:, {', '.join(map(str, index))}]"

    def row(self, name, r):
        return f"{name}[:, {r}, :]"

    def scalar(self, name, i):
        return f"{name}[:, {i}, None]"

    def block(self, name, lo):
        return f"{name}[:, {lo}:{lo + 4}]"

    def rows(self, name, lo):
        return f"{name}[:, {lo}:{lo + 4}, :]"

    def pick(self, rows):
        return f"E[:, {list(rows)}, :]"

    def zeros(self, name, kind, dims):
        dtype = ", dtype=complex" if kind == "complex" else ""
        return f"{name} = np.zeros(({', '.join(['lam.size', *map(str, dims)])}){dtype})"

    def scale(self, k, lo):
        return f"Us = U{k} * (D[:, {lo}:{lo + 4}, None] / D[:, None, {lo}:{lo + 4}])"

    def apply(self, lo, ncol):
        return self.assign(self.rows("E", lo), f"Us @ {self.rows('E', lo)}")

    def det(self, plan):
        return f"np.linalg.det({self.pick(plan.rows)})"

    def function(self, plan, body, waves):
        steps = ", ".join(f"_steps({w}, nu_step)" for w in waves)
        return [f"def symtmm_delta({', '.join(['lam', *plan.args])}):",
                '    """Delta(lam) for an array of eigenvalues lam (complex); same shape."""',
                "    lam = np.asarray(lam, dtype=complex)", "    flat = lam.reshape(-1)",
                "    lam2 = flat * flat", *body.render(1, body.params), "",
                "    def core(lam, lam2, steps):",
                '        """Delta at points whose segments all take the same numbers of steps."""',
                *body.render(2, body.point), "",
                "    # a batch shares its numbers of steps: points that need the same are taken",
                "    # together (a point given the steps of a far higher mode loses digits)",
                f"    steps = np.stack([{steps}], axis=-1)",
                "    out = np.empty(flat.shape, dtype=complex)",
                "    for key in np.unique(steps, axis=0):",
                "        sel = np.all(steps == key, axis=1)",
                "        out[sel] = core(flat[sel], lam2[sel], key)",
                "    return out.reshape(lam.shape)"]

    def file(self, header, runtime, function):
        # the header as comments, not in the docstring: no text of the model's can end a
        # comment, while a docstring ends at the first triple quote and reads backslashes;
        # the fixed first line keeps it clear of the two lines Python reads for an encoding
        return ['"""Delta(lam) = det R(lam) of a symtmm model (generated; see the comments)."""',
                "", *header, "", runtime, "", "", *function, ""]


#: The dialect of each language :func:`symtmm.codegen.generate` writes.
DIALECTS = {d.name: d for d in (C(), Fortran(), Octave(), Julia(), Python())}
