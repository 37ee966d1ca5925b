"""How each language writes what the walker asks for: one small table per language.

A :class:`Dialect` holds a language's expression printer and literals, its
statement forms (format strings: assignment, ``if``, ``for``, calls of the
runtime routines), its arrays (first index, brackets, and for the numpy batch
a leading axis of points), its comments and declarations, the layout of the
file around the evaluator, and its identifier rules: the names an argument
must not take. :mod:`symtmm.codegen.walker` writes the evaluator once through
any of them.

Examples
--------
>>> c, fortran, python = DIALECTS["c"], DIALECTS["fortran"], DIALECTS["python"]
>>> [d.index("E", 2, 0) for d in (c, fortran, python)]
['E[2][0]', 'E(3, 1)', 'E[:, 2, 0]']
>>> [d.index("D", (4, 4)) for d in (c, fortran, python)]
['D + 4', 'D(5:8)', 'D[:, 4:8]']
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
    """A language as the walker sees it; the subclasses fill in the table.

    Format strings hold the fixed forms, methods the forms that compute. The
    walker's names (``D``, ``E``, ``U0``, ``nu_step`` ...) are the same in
    every language; only the runtime routines carry the dialect's ``prefix``.
    """

    name = extension = ""
    indent, end, comment = "    ", "", "#"  # statement terminator, line comment
    prefix = "symtmm_"            # of the runtime routines' names
    runtime = ("kernels",)        # runtime source stems, each copied when the model needs it
    brackets, base, batch = "()", 1, ""   # arrays: E(3, 1); numpy's batch: E[:, 2, 0]
    lam = "lam"                   # the point's eigenvalue in the per-point statements
    declares_in_place = False     # C: a local where it is first set (Fortran: at the top)
    eltypes = ("", "")            # of real and of complex arrays
    zeros = ""                    # a zero array: name, dims, dims2 (at least two), eltype
    if_open, if_close = "if {}", "end"
    for_open, for_close = "for {} = 1:{}", "end"
    negative, either = "!({} >= 0)", " || "
    vector = "[{}]"
    fourth_root, log, exp = "abs({})^0.25", "log({})", "exp({})"
    steps = "max(1, ceil({} / nu_step))"   # steps of |beta| l <= nu_step for a wave w
    peak = "{}"                   # the largest wave of a batch (numpy), the wave elsewhere
    stiffness = "{}"              # a station's stiffness where it multiplies a row
    against_row = ()              # extra index of a per-point value that multiplies a row
    call = "{out} = {fn}({args})"  # a runtime routine that returns an array
    scale = apply = orthonormalise = det = ""
    # a member of beams joined by layers: its m rows of the state (a list), Us{m}
    scale_rows = apply_rows = ""
    nan_exit: tuple = ()
    deliver = ("return delta",)
    row_loop = False              # whether a row of E is updated column by column (C)
    # identifier rules
    reserved: frozenset = frozenset()
    reserved_pattern = re.compile(r"(?!)")
    fold = staticmethod(lambda name: name)
    evaluator = ("", "")          # regular expressions around the evaluator in the file
    not_code = ""                 # comments and strings: words there are no names

    @staticmethod
    def printer(expr) -> str:
        """A SymPy expression in the language."""
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

    def index(self, name, *index) -> str:
        """``name`` at 0-based ``index``: ints, ``(first, count)`` spans, lists, ``":"``."""
        def one(i):
            if isinstance(i, tuple):
                return f"{i[0] + self.base}:{i[0] + i[1]}"
            if isinstance(i, list):
                return f"[{', '.join(str(r + self.base) for r in i)}]"
            return i if isinstance(i, str) else str(i + self.base)
        return f"{name}{self.brackets[0]}{self.batch}{', '.join(map(one, index))}" \
               f"{self.brackets[1]}"

    def assign(self, target, value) -> str:
        return f"{target} = {value}{self.end}"

    def declaration(self, name, kind, dims) -> str:
        raise NotImplementedError

    def zero_array(self, name, kind, dims) -> str:
        dims2 = dims + (1,) * (2 - len(dims))
        return self.zeros.format(name=name, dims=", ".join(map(str, dims)),
                                 dims2=", ".join(map(str, dims2)),
                                 eltype=self.eltypes[kind == "complex"])

    def header(self, lines) -> list:
        return [f"{self.comment} {ln}".rstrip() for ln in lines]

    def host_names(self, code) -> str:
        """Text of ``code`` outside the evaluator whose names the evaluator sees too."""
        return ""

    def function(self, plan, body) -> list:
        """The evaluator around ``body`` (:class:`~symtmm.codegen.walker.Body`)."""
        raise NotImplementedError

    def file(self, header, runtime, function) -> list:
        return [*header, "", runtime, "", *function, ""]

    def finish(self, lines) -> str:
        return "\n".join(lines)


class C(Dialect):
    name, extension = "c", "c"
    printer = staticmethod(sp.ccode)
    end = ";"
    runtime = ("core", "euler_bernoulli", "theory", "layer")
    brackets, base = "[]", 0
    declares_in_place = True
    if_open, if_close = "if ({}) {{", "}"
    for_open, for_close = "for (int {0} = 0; {0} < {1}; {0}++) {{", "}"
    vector = "{{{}}}"
    fourth_root = "pow(cabs({}), 0.25)"
    steps = "(int)fmax(1.0, ceil({} / nu_step))"
    call = "{fn}({args}, {out});"
    scale = "symtmm_scaled(U{k}, {D}, Us);"
    apply = "symtmm_apply({nc}, Us, {E});"
    scale_rows = "symtmm_scaled_rows({m}, U{k}, {D}, {Us});"
    apply_rows = "symtmm_apply_rows({m}, {nc}, {Us}, {E});"
    orthonormalise = "symtmm_orthonormalise({ns}, {nc}, E, &logscale);"
    det = "symtmm_det({ns}, {nc}, {E})"
    nan_exit = ("*delta_re = NAN;", "*delta_im = NAN;", "return;")
    deliver = ("*delta_re = creal(delta);", "*delta_im = cimag(delta);")
    row_loop = True
    reserved = _COMMON | frozenset({
        "lam_re", "lam_im", "delta_re", "delta_im", "U", "d", "s", "n", "nsub", "nu", "grown", "w",
        "t", "j", "NS", "NC", "NU_STEP", "I", "auto", "break", "case", "char", "const", "continue",
        "default", "do", "double", "else", "enum", "extern", "float", "for", "goto", "if", "inline",
        "int", "long", "register", "restrict", "return", "short", "signed", "sizeof", "static",
        "struct", "switch", "typedef", "union", "unsigned", "void", "volatile", "while", "complex",
        "creal", "cimag", "cabs", "cpow", "ccosh", "ccos", "csinh", "csin", "conj", "sqrt", "pow",
        "log", "exp", "ceil", "NAN", "M_PI",
        # every keyword up to C23 and GNU's, the object-like macros of <complex.h> and
        # <math.h> (glibc in any mode, other C libraries' SVID names) and the system names
        # compilers predefine outside strict ISO mode (`gcc -std=gnu99` defines linux = 1);
        # the M_, FP_, HUGE_VAL, SNAN, CMPLX and MATH_ERR families by reserved_pattern
        "_Bool", "_Complex", "_Imaginary", "alignas", "alignof", "asm", "bool", "constexpr",
        "false", "fortran", "nullptr", "static_assert", "thread_local", "true", "typeof",
        "typeof_unqual", "imaginary", "INFINITY", "HUGE", "MAXFLOAT", "DOMAIN", "SING", "OVERFLOW",
        "UNDERFLOW", "TLOSS", "PLOSS", "X_TLOSS", "math_errhandling", "errno", "linux", "unix",
        "i386", "i486", "i586", "i686", "sun", "sparc", "mips", "vax", "hppa", "m68k", "mc68000",
        "ns32000", "pdp11", "ppc", "powerpc", "arm", "sgi", "fpclassify", "iscanonical", "iseqsig",
        "isfinite", "isgreater", "isgreaterequal", "isinf", "isless", "islessequal",
        "islessgreater", "isnan", "isnormal", "issignaling", "issubnormal", "isunordered", "iszero",
        "signbit"})
    reserved_pattern = re.compile(r"^(?:M_|FP_|HUGE_VAL|SNAN|CMPLX|MATH_ERR)")
    evaluator = (r"^void symtmm_delta\(", r"^\}$")
    not_code = r"/\*[\s\S]*?\*/|\"[^\"\n]*\""

    def index(self, name, *index):
        # a span: a pointer to its first entry; a list of rows: the array and the rows, as
        # the runtime routines take them; ":" (all columns): the current one
        if isinstance(index[0], tuple):
            return f"{name} + {index[0][0]}"
        if isinstance(index[0], list):
            return f"{name}, (const int[]){{{', '.join(map(str, index[0]))}}}"
        return name + "".join(f"[{'j' if i == ':' else i}]" for i in index)

    def declaration(self, name, kind, dims):
        ctype = {"real": "double", "complex": "double complex", "int": "int"}[kind]
        return ctype + f" {name}" + "".join(f"[{n}]" for n in dims)

    def zero_array(self, name, kind, dims):
        return f"{self.declaration(name, kind, dims)} = {'{' * len(dims)}0{'}' * len(dims)};"

    def header(self, lines):
        return ["/*", *(f" * {ln}".rstrip() for ln in lines), " */"]

    def function(self, plan, body):
        args = ["double lam_re", "double lam_im", *(f"double {a}" for a in plan.args),
                "double *delta_re", "double *delta_im"]
        return [f"void symtmm_delta({', '.join(args)})", "{",
                "    double complex lam = lam_re + lam_im * I, lam2 = lam * lam;",
                *body.render(1), "}"]


class Fortran(Dialect):
    name, extension = "fortran", "f90"
    indent, comment = "  ", "!"
    runtime = ("core", "euler_bernoulli", "theory", "layer")
    zeros = "{name} = 0"
    if_open, if_close = "if ({}) then", "end if"
    for_open, for_close = "do {} = 1, {}", "end do"
    negative, either = ".not. ({} >= 0)", " .or. "
    fourth_root = "abs({})**0.25_dp"
    steps = "max(1, ceiling({} / nu_step))"
    call = "call {fn}({args}, {out})"
    scale = "Us = U{k} * (spread({D}, 2, 4) / spread({D}, 1, 4))"
    apply = "{E} = matmul(Us, {E})"
    scale_rows = "{Us} = U{k} * (spread({D}, 2, {m}) / spread({D}, 1, {m}))"
    apply_rows = "{E} = matmul({Us}, {E})"
    orthonormalise = "call symtmm_orthonormalise(E, logscale)"
    det = "symtmm_det({E})"
    nan_exit = ("delta_re = ieee_value(delta_re, ieee_quiet_nan)", "delta_im = delta_re",
                "return")
    deliver = ("delta_re = real(delta, kind=dp)", "delta_im = aimag(delta)")
    # Fortran ignores case: compared in lower case
    reserved = _COMMON | frozenset({
        "lam_re", "lam_im", "delta_re", "delta_im", "e", "r", "dlt", "tt", "u", "dd", "nn", "nsub",
        "nuv", "wv", "grown", "it", "ii", "kk", "jj", "s", "dp", "ns", "nc", "nu_step", "coef",
        "cfun", "segment", "steps", "units", "orthonormalise", "det", "abs", "real", "aimag",
        "cmplx", "sqrt", "exp", "log", "cos", "cosh", "sin", "sinh", "conjg", "sum", "ceiling",
        "max", "kind", "ieee_value", "ieee_quiet_nan", "ieee_arithmetic", "iso_c_binding",
        "c_double", "c_double_complex", "th", "ifact", "invariants", "wave", "segment_gen",
        "steps_nu", "units_b", "matmul", "spread"})
    fold = staticmethod(str.lower)
    evaluator = (r"^  subroutine symtmm_delta\(", r"^  end subroutine symtmm_delta$")
    not_code = r"![^\n]*|\"[^\"\n]*\"|'[^'\n]*'"

    @staticmethod
    def printer(expr):
        text = re.sub(r"&\s*\n\s*", "", sp.fcode(expr, source_format="free", standard=2008))
        # double-precision literals 1.5d0, 2.0d-8 -> kind dp
        return re.sub(r"(\d)d([+-]?\d+)", lambda m: f"{m.group(1)}e{m.group(2)}_dp", text)

    def literal(self, value):
        text = f"{float_literal(value)}_dp"
        return f"({text})" if text.startswith("-") else text   # no operator after another

    def declaration(self, name, kind, dims):
        return f"{_FORTRAN_TYPES[kind]} :: {_shaped(name, dims)}"

    def declarations(self, kinds):
        """One declaration per type of the locals ``kinds`` (name -> (kind, dims))."""
        by_type: dict = {}
        for name, (kind, dims) in kinds.items():
            by_type.setdefault(_FORTRAN_TYPES[kind], []).append(_shaped(name, dims))
        return [f"{ftype} :: {', '.join(names)}" for ftype, names in by_type.items()]

    def host_names(self, code):
        # the module's declarations and every procedure, by host association
        return code[:code.index("\ncontains\n")] + " ".join(
            re.findall(r"\b(?:subroutine|function)\s+(\w+)", code))

    def function(self, plan, body):
        inputs = ", ".join(["lam_re", "lam_im", *plan.args])
        return [f"  subroutine symtmm_delta({inputs}, delta_re, delta_im) &",
                '      bind(C, name="symtmm_delta")',
                f"    real(c_double), value, intent(in) :: {inputs}",
                "    real(c_double), intent(out) :: delta_re, delta_im",
                "    complex(dp) :: lam, lam2",
                *("    " + d for d in self.declarations(body.kinds)),
                "    lam = cmplx(lam_re, lam_im, kind=dp)", "    lam2 = lam * lam",
                *body.render(2), "  end subroutine symtmm_delta"]

    def file(self, header, runtime, function):
        return [*header, "", "module symtmm_delta_mod",
                "  use iso_c_binding, only: c_double",
                "  use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan",
                "  implicit none", "  private", "  public :: symtmm_delta",
                "  integer, parameter :: dp = c_double", "contains", "", runtime, "",
                *function, "end module symtmm_delta_mod", ""]

    def finish(self, lines):
        return "\n".join(piece for line in lines for piece in _wrap(line))


_FORTRAN_TYPES = {"real": "real(dp)", "complex": "complex(dp)", "int": "integer"}


def _shaped(name, dims) -> str:
    return name + (f"({', '.join(map(str, dims))})" if dims else "")


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
    name, extension = "octave", "m"
    printer = staticmethod(sp.octave_code)
    indent, end, comment = "  ", ";", "%"
    lam = "lm"
    zeros = "{name} = zeros({dims2});"
    negative = "~({} >= 0)"
    call = "{out} = {fn}({args});"
    scale = "Us = U{k} .* ({D} ./ {D}.');"
    apply = "{E} = Us * {E};"
    scale_rows = "{Us} = U{k} .* ({D} ./ {D}.');"
    apply_rows = "{E} = {Us} * {E};"
    orthonormalise = "[E, logscale] = symtmm_orthonormalise(E, logscale);"
    det = "det({E})"
    nan_exit = ("d(:) = NaN;", "return")
    deliver = ("d(idx) = delta;",)
    reserved = _COMMON | frozenset({
        "d", "lm", "idx", "Us", "it", "F", "w", "grown", "end", "function", "for", "if", "else",
        "elseif", "while", "return", "switch", "case", "otherwise", "do", "until", "break",
        "continue", "global", "persistent", "try", "catch", "i", "j", "pi", "e", "abs", "sqrt",
        "exp", "log", "cos", "sin", "cosh", "sinh", "zeros", "numel", "size", "det", "qr", "diag",
        "ceil", "max", "NaN", "Inf", "sum", "complex", "real", "imag",
        # iskeyword() of Octave 8 and MATLAB's, and the constants and variables every
        # function sees (an argument i or e would hide the constant; nargin is set on entry)
        "__FILE__", "__LINE__", "classdef", "end_try_catch", "end_unwind_protect", "endarguments",
        "endclassdef", "endenumeration", "endevents", "endfor", "endfunction", "endif",
        "endmethods", "endparfor", "endproperties", "endspmd", "endswitch", "endwhile", "parfor",
        "spmd", "unwind_protect", "unwind_protect_cleanup", "arguments", "methods", "properties",
        "events", "enumeration", "I", "J", "inf", "nan", "NA", "eps", "ans", "nargin", "nargout",
        "varargin", "varargout", "true", "false"})
    evaluator = (r"^function d = symtmm_delta\(", r"^end$")
    not_code = r"%[^\n]*"

    def function(self, plan, body):
        return [f"function d = symtmm_delta({', '.join(['lam', *plan.args])})",
                "  d = zeros(size(lam));", *body.render(1, body.params),
                "  for idx = 1:numel(lam)   % one point at a time",
                "    lm = lam(idx);", "    lam2 = lm * lm;",
                *body.render(2, body.point), "  end", "end"]

    def file(self, header, runtime, function):
        # the help text of an Octave function follows its first line
        return [function[0], *header, *function[1:], "", runtime]


class Julia(Dialect):
    name, extension = "julia", "jl"
    printer = staticmethod(sp.julia_code)
    brackets = "[]"
    eltypes = ("Float64", "ComplexF64")
    zeros = "{name} = zeros({eltype}, {dims})"
    for_open = "for {} in 1:{}"
    vector = "({})"
    steps = "max(1, ceil(Int, {} / nu_step))"
    scale = "Us = U{k} .* ({D} ./ transpose({D}))"
    apply = "{E} = Us * {E}"
    scale_rows = "{Us} = U{k} .* ({D} ./ transpose({D}))"
    apply_rows = "{E} = {Us} * {E}"
    orthonormalise = "logscale = symtmm_orthonormalise!(E, logscale)"
    det = "symtmm_det({E})"
    nan_exit = ("return ComplexF64(NaN, NaN)",)
    reserved = _COMMON | frozenset({
        "Us", "it", "w", "grown", "begin", "end", "function", "for", "if", "else", "elseif",
        "while", "return", "let", "local", "global", "const", "do", "try", "catch", "finally",
        "struct", "mutable", "module", "using", "import", "export", "quote", "macro", "abstract",
        "primitive", "type", "in", "isa", "true", "false", "break", "continue", "baremodule",
        "where", "outer", "im", "pi", "abs", "sqrt", "exp", "log", "cos", "sin", "cosh", "sinh",
        "conj", "zeros", "one", "zero", "size", "ceil", "Int", "max", "NaN", "Float64",
        "ComplexF64", "transpose", "NTuple",
        # keywords of Julia 1.11 (public included) and the names of Core every file sees
        "public", "ccall", "nothing", "missing", "Inf", "ans", "Base", "Core", "Main", "ComplexF32",
        "Float32", "Complex", "Matrix", "Vector"})
    evaluator = (r"^function symtmm_delta\(", r"^end$")
    not_code = r"#[^\n]*|\"[^\"\n]*\""

    def function(self, plan, body):
        args = ", ".join(["lam::ComplexF64", *(f"{a}::Float64" for a in plan.args)])
        return [f"function symtmm_delta({args})::ComplexF64", "    lam2 = lam * lam",
                *body.render(1), "end"]


class Python(Dialect):
    name, extension = "python", "py"
    printer = staticmethod(lambda expr: sp.pycode(expr).replace("math.", "np."))
    prefix = "_"
    brackets, base, batch = "[]", 0, ":, "
    eltypes = ("", ", dtype=complex")
    zeros = "{name} = np.zeros((lam.size, {dims}){eltype})"
    if_open, if_close = "if {}:", None
    for_open, for_close = "for {} in range({}):", None
    negative, either = "not ({} >= 0)", " or "
    vector = "({})"
    fourth_root, log, exp = "np.abs({}) ** 0.25", "np.log({})", "np.exp({})"
    steps = "int(steps[{1}])"
    peak = "float(np.max({}, initial=0.0))"
    stiffness = "np.broadcast_to({}, lam.shape)[:, None]"
    against_row = ("None",)
    scale = "Us = U{k} * ({D}[:, :, None] / {D}[:, None, :])"
    apply = "{E} = Us @ {E}"
    scale_rows = "{Us} = U{k} * ({D}[:, :, None] / {D}[:, None, :])"
    apply_rows = "{E} = {Us} @ {E}"
    orthonormalise = "E, logscale = _orthonormalise(E, logscale)"
    det = "np.linalg.det({E})"
    nan_exit = ("return np.full(lam.shape, np.nan + 1j * np.nan)",)
    reserved = _COMMON | frozenset(keyword.kwlist) | frozenset({
        "flat", "Us", "F", "np", "n", "out", "sel", "key", "steps", "core", "grown",
        # the builtins (an argument called complex, float, int or range breaks the code
        # that calls them) and numpy's module name
        "abs", "aiter", "all", "anext", "any", "ascii", "bin", "bool", "breakpoint", "bytearray",
        "bytes", "callable", "chr", "classmethod", "compile", "complex", "copyright", "credits",
        "delattr", "dict", "dir", "divmod", "enumerate", "eval", "exec", "exit", "filter", "float",
        "format", "frozenset", "getattr", "globals", "hasattr", "hash", "help", "hex", "id",
        "input", "int", "isinstance", "issubclass", "iter", "len", "license", "list", "locals",
        "map", "max", "memoryview", "min", "next", "object", "oct", "open", "ord", "pow", "print",
        "property", "quit", "range", "repr", "reversed", "round", "set", "setattr", "slice",
        "sorted", "staticmethod", "str", "sum", "super", "tuple", "type", "vars", "zip", "Ellipsis",
        "NotImplemented", "numpy"})
    evaluator = (r"^def symtmm_delta\(", r"\Z")
    not_code = r"#[^\n]*|\"\"\"[\s\S]*?\"\"\"|\"[^\"\n]*\"|'[^'\n]*'"

    def function(self, plan, body):
        steps = ", ".join(f"_steps({w}, nu_step)" for w in body.waves)
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
