"""Self-contained evaluators of ``Delta(lam) = det R(lam)`` in C, Fortran, Octave, Julia, Python.

Structure of the generated code
-------------------------------
The generated code follows :meth:`symtmm.compile.Evaluator.log_delta` rather
than printing one expanded determinant: the closed form (see
:mod:`symtmm.characteristic`) sums terms that grow like ``exp(beta L)`` with
opposite signs and has thousands of operations for multilevel models. The
generated code instead

1. builds each segment's transfer matrix from the entire functions
   ``c_j(x) = sum_k x**k / (4k+j)!`` of ``x = -lam**2 m l**4 / EI`` (a
   16-term series below ``|x| = 1``, closed forms in ``x**(1/4)`` above), with
   no branch to choose and no 0/0 at ``lam = 0``, for the segment cut into
   ``n`` equal steps of ``|beta| l / n <= NU_STEP`` (``n`` from ``lam`` at run
   time);
2. measures the state of every beam in units of its wave number ``b``:
   ``[Y, Theta/b, M/(EI b**2), Q/(EI b**3)]``;
3. propagates the ``2n`` columns of the unknown left-end variables through the
   cuts (segment steps, then the point-element jumps ``Q += -(k + c lam) ...``),
   re-orthonormalising them after every step (modified Gram–Schmidt, twice) and
   adding up the logarithms of the norms (Godunov's method);
4. returns ``det E[rows] * exp(sum of the logarithms)``, the determinant by
   Gaussian elimination with partial pivoting.

Without steps 2 and 3 the columns become parallel to working precision and the
value loses ``sum |beta| L / ln 10`` digits (all of them by ``beta L = 36``);
with them it keeps about 13 significant digits at any mode, like the Python
evaluator, and overflows only where ``|Delta|`` itself exceeds the double range.
Common subexpressions of the parameters are computed once (:func:`sympy.cse`),
identical segments share one matrix, and constants are printed with 17
significant digits (exact to double precision).

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
the language or in the generated code (``I`` in C, ``E`` in Fortran, which
ignores case, ``end`` in Julia); it is then called ``p_NAME`` (the header
says so). The order of the cuts along the beams is fixed when the code is
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
"""

from __future__ import annotations

import keyword
import math
import re
from dataclasses import dataclass, field, replace

import sympy as sp

from . import __version__
from .assembly import Interval, Layout
from .characteristic import _check_order, _prepare
from .compile import NU_STEP
from .elements import STATE
from .elements.base import CONJUGATE, LAM

__all__ = ["EXTENSIONS", "LANGUAGES", "generate"]

#: Languages :func:`generate` writes.
LANGUAGES = ("c", "fortran", "octave", "julia", "python")
#: Usual file extension per language.
EXTENSIONS = {"c": ".c", "fortran": ".f90", "octave": ".m", "julia": ".jl", "python": ".py"}

#: Terms of the series of c_j(x) for |x| < 1 (the last is below 1e-80).
SERIES_TERMS = 16

# Names in scope in the generated symtmm_delta, per language: its locals, the
# file's own globals, and what the language gives a meaning there.
_COMMON = {"lam", "lam2", "D", "E", "R", "logscale"}
_RESERVED = {
    "c": _COMMON | {"lam_re", "lam_im", "delta_re", "delta_im", "U", "d", "s", "n", "nsub",
                    "t", "j", "NS", "NC", "NU_STEP", "I", "auto", "break", "case", "char",
                    "const", "continue", "default", "do", "double", "else", "enum", "extern",
                    "float", "for", "goto", "if", "inline", "int", "long", "register",
                    "restrict", "return", "short", "signed", "sizeof", "static", "struct",
                    "switch", "typedef", "union", "unsigned", "void", "volatile", "while",
                    "complex", "creal", "cimag", "cabs", "cpow", "ccosh", "ccos", "csinh",
                    "csin", "conj", "sqrt", "pow", "log", "exp", "ceil", "NAN", "M_PI"},
    # Fortran ignores case: compared in lower case
    "fortran": _COMMON | {"lam_re", "lam_im", "delta_re", "delta_im", "e", "r", "dlt", "tt",
                          "u", "dd", "nn", "nsub", "it", "ii", "kk", "jj", "s", "dp", "ns",
                          "nc", "nu_step", "coef", "cfun", "segment", "steps", "units",
                          "orthonormalise", "det", "abs", "real", "aimag", "cmplx", "sqrt",
                          "exp", "log", "cos", "cosh", "sin", "sinh", "conjg", "sum",
                          "ceiling", "max", "kind", "ieee_value", "ieee_quiet_nan",
                          "ieee_arithmetic", "iso_c_binding", "c_double", "c_double_complex"},
    "octave": _COMMON | {"d", "lm", "idx", "Us", "it", "F", "end", "function", "for", "if",
                         "else", "elseif", "while", "return", "switch", "case", "otherwise",
                         "do", "until", "break", "continue", "global", "persistent", "try",
                         "catch", "i", "j", "pi", "e", "abs", "sqrt", "exp", "log", "cos",
                         "sin", "cosh", "sinh", "zeros", "numel", "size", "det", "qr", "diag",
                         "ceil", "max", "NaN", "Inf", "sum", "complex", "real", "imag"},
    "julia": _COMMON | {"Us", "it", "begin", "end", "function", "for", "if", "else", "elseif",
                        "while", "return", "let", "local", "global", "const", "do", "try",
                        "catch", "finally", "struct", "mutable", "module", "using", "import",
                        "export", "quote", "macro", "abstract", "primitive", "type", "in",
                        "isa", "true", "false", "break", "continue", "baremodule", "where",
                        "outer", "im", "pi", "abs", "sqrt", "exp", "log", "cos", "sin", "cosh",
                        "sinh", "conj", "zeros", "one", "zero", "size", "ceil", "Int", "max",
                        "NaN", "Float64", "ComplexF64", "transpose"},
    "python": _COMMON | {"flat", "Us", "F", "np"} | set(keyword.kwlist),
}
# numbered locals of the generated code (U1, s0, n2, ...)
_NUMBERED = re.compile(r"^[Usn]\d+$")


def _float_literal(value) -> str:
    """Shortest decimal that reads back as the double nearest the exact value."""
    return repr(float(sp.N(sp.sympify(value), 30)))


def _argument_names(params, lang: str) -> list:
    """An identifier per parameter that means nothing else where ``lang``'s code uses it.

    Examples
    --------
    >>> _argument_names(["I", "K", "x1"], "c"), _argument_names(["E", "K"], "fortran")
    (['p_I', 'K', 'x1'], ['p_E', 'K'])
    """
    fold = (lambda v: v.lower()) if lang == "fortran" else (lambda v: v)
    taken = {fold(v) for v in _RESERVED[lang]}
    out = []
    for name in params:
        arg = name
        while (fold(arg) in taken or _NUMBERED.match(arg)
               or arg.lower().startswith(("symtmm", "_"))):
            arg = "p_" + arg
        taken.add(fold(arg))
        out.append(arg)
    return out


@dataclass
class _Plan:
    """Language-neutral description of the evaluation."""

    title: str
    source: str
    params: list                 # names of symbolic parameters (extra arguments)
    values: dict                 # parameter name -> exact value (for the header)
    n: int
    rows: list
    columns: list
    args: list = field(default_factory=list)      # argument identifier per parameter
    temps: list = field(default_factory=list)     # (name, expr over arguments and temps)
    levels: list = field(default_factory=list)    # (EI, mu, L, k): units b = |mu lam2 + k|^(1/4)
    segments: list = field(default_factory=list)  # (a, l, EI, s); a = m l^4/EI, s = kw/m
    guards: list = field(default_factory=list)    # lengths that must not be negative
    steps: list = field(default_factory=list)     # ("seg", index, level) | ("point", updates)
    stiff: list = field(default_factory=list)     # (k0, k1, k2): s = k0 + k1 lam + k2 lam**2

    @property
    def ncol(self) -> int:
        return len(self.columns)

    @property
    def ns(self) -> int:
        return 4 * self.n


def _plan(model, symbolic=()) -> _Plan:
    model_in = model
    model, sample = _prepare(model, tuple(symbolic))
    layout = Layout(model, sample)
    _check_order(layout, sample, model.source)
    params = sorted(model.free_symbols)
    plan = _Plan(title=model_in.title or "", source=model_in.source or "",
                 params=params, values={k: v for k, v in model_in.parameters.items()},
                 n=layout.levels, rows=list(layout.rows), columns=list(layout.columns),
                 args=list(params))
    raw: list = []          # expressions to go through CSE, by position

    def slot(expr):
        expr = sp.sympify(expr)
        if expr.is_number:
            return expr
        raw.append(expr)
        return len(raw) - 1

    for beam in layout.model.beams:
        plan.levels.append((slot(beam.EI), slot(beam.m / beam.EI), slot(beam.L),
                            slot(beam.kw / beam.EI)))
    seg_index: dict = {}
    stiff_index: dict = {}  # (k, c, M) -> index; a coupling's entries are +-s: one variable
    for step in layout.steps:
        if isinstance(step, Interval):
            for lvl, seg in step.segments:
                key = seg.key
                if key not in seg_index:
                    seg_index[key] = len(plan.segments)
                    # a foundation kw: the bare segment at lam**2 + kw/m
                    plan.segments.append((slot(seg.m * seg.l**4 / seg.EI), slot(seg.l),
                                          slot(seg.EI), slot(seg.kw / seg.m)))
                    if not sp.sympify(seg.l).is_number:
                        plan.guards.append(plan.segments[-1][1])
                plan.steps.append(("seg", seg_index[key], lvl))
            continue
        updates = []
        for element, levels in step.elements:
            S = element.stiffness(LAM)
            d = len(element.dofs)
            entry = {}
            for i in range(d):
                for k in range(d):
                    poly = sp.Poly(sp.expand(S[i, k]), LAM)
                    if poly.degree() > 2:
                        raise NotImplementedError("stiffness of degree > 2 in lam")
                    key = tuple(poly.coeff_monomial(LAM**d) for d in range(3))
                    if all(v == 0 for v in key):
                        continue
                    entry[(i, k)] = key
            for (i, k), key in entry.items():
                sign = 1
                neg = tuple(-v for v in key)
                if neg in stiff_index:
                    key, sign = neg, -1
                if key not in stiff_index:
                    stiff_index[key] = len(plan.stiff)
                    plan.stiff.append(tuple(slot(v) for v in key))
                entry[(i, k)] = (sign, stiff_index[key])
            for i, (li, var_i) in enumerate(element.dofs):
                force, jump_sign = CONJUGATE[var_i]
                row = 4 * levels[li] + STATE.index(force)
                terms = []
                for k, (lk, var_k) in enumerate(element.dofs):
                    if (i, k) in entry:
                        sign, s_idx = entry[(i, k)]
                        terms.append((jump_sign * sign, 4 * levels[lk] + STATE.index(var_k),
                                      s_idx))
                if terms:
                    updates.append((row, terms))
        plan.steps.append(("point", updates))
    # common subexpressions of the parameter expressions
    lookup: dict = {}
    if raw:
        numeric = [sp.N(e, 25) for e in raw]
        temps, reduced = sp.cse(numeric, symbols=sp.numbered_symbols("symtmm_t"))
        plan.temps = list(temps)
        named: dict = {}
        for i, e in enumerate(reduced):
            if e.is_Symbol:          # a parameter or a CSE temporary: use it as it is
                lookup[i] = e
                continue
            if e not in named:
                named[e] = sp.Symbol(f"symtmm_t{len(plan.temps)}")
                plan.temps.append((named[e], e))
            lookup[i] = named[e]

    def resolve(v):
        return lookup[v] if isinstance(v, int) else v

    plan.levels = [tuple(resolve(v) for v in lv) for lv in plan.levels]
    plan.segments = [tuple(resolve(v) for v in seg) for seg in plan.segments]
    plan.stiff = [tuple(resolve(v) for v in s) for s in plan.stiff]
    plan.guards = [resolve(v) for v in plan.guards]
    return plan


def _for_language(plan: _Plan, lang: str) -> _Plan:
    """The plan with parameters renamed where their names mean something in ``lang``."""
    args = _argument_names(plan.params, lang)
    ren = {sp.Symbol(p, positive=True): sp.Symbol(a, positive=True)
           for p, a in zip(plan.params, args) if p != a}

    def sub(v):
        return sp.sympify(v).xreplace(ren) if ren else v

    return replace(plan, args=args,
                   temps=[(nm, sub(e)) for nm, e in plan.temps],
                   levels=[tuple(sub(v) for v in lv) for lv in plan.levels],
                   segments=[tuple(sub(v) for v in sg) for sg in plan.segments],
                   stiff=[tuple(sub(v) for v in st) for st in plan.stiff],
                   guards=[sub(v) for v in plan.guards])


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


def _stiffness(k0, k1, k2, val, lam="lam", mul="*") -> str:
    """``k + c lam + M lam**2``, without the terms that are zero (``k`` is always written)."""
    text = val(k0) if sp.sympify(k0) != 0 or (sp.sympify(k1) == 0 and sp.sympify(k2) == 0) \
        else ""
    for coef, power in ((k1, f"{lam}"), (k2, f"{lam} {mul} {lam}")):
        if sp.sympify(coef) != 0:
            text += (" + " if text else "") + f"{val(coef)} {mul} {power}"
    return text


def _series_coefficients():
    """``coef[j][k] = 1/(4k+j)!`` as exact-to-double literals."""
    return [[_float_literal(sp.Rational(1, math.factorial(4 * k + j)))
             for k in range(SERIES_TERMS)] for j in range(4)]


def _header_lines(plan: _Plan, lang: str) -> list:
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
    lines += [
        (f"{plan.n} beam(s); R is {plan.ncol} x {plan.ncol}. lam is the eigenvalue "
         "(lam = i*omega undamped)."),
        "Method: segment matrices from c_j(x) = sum_k x^k/(4k+j)!, x = -lam^2 m l^4/EI",
        f"(series for |x| < 1), applied in steps of |beta| l <= {NU_STEP:g}; states in units of",
        "each beam's wave number; the unknown left-end columns re-orthonormalised after",
        "every step (Godunov), Delta = det(E[rows]) * exp(sum of log norms): about 13",
        "significant digits at any mode, as symtmm.compile.Evaluator.log_delta.",
    ]
    return lines


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


def _emit_c(plan: _Plan) -> str:
    ns, nc = plan.ns, plan.ncol
    coef = _series_coefficients()
    p = lambda e: _val(e, sp.ccode)
    out = ["/*"] + [" * " + ln if ln else " *" for ln in _header_lines(plan, "c")] + [" */", ""]
    out += ["#include <complex.h>", "#include <math.h>", "", f"#define NS {ns}", f"#define NC {nc}",
            f"#define NU_STEP {_float_literal(NU_STEP)}",
            "", f"static const double symtmm_coef[4][{SERIES_TERMS}] = {{"]
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
            "/* transfer matrix of a beam segment of length l (a = m l^4 / EI); I for l = 0 */",
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
            "",
            "/* steps of |beta| l <= NU_STEP for a segment with x = (beta l)^4 */",
            "static int symtmm_steps(double complex x)",
            "{",
            "    int n = (int)ceil(pow(cabs(x), 0.25) / NU_STEP);",
            "    return n < 1 ? 1 : n;",
            "}",
            "",
            ("/* units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b = |mu lam2 + k|^(1/4)"
            " >= 1/L */"),
            "static void symtmm_units(double complex lam2, double EI, double mu, double L, double k,",
            "                         double *D)",
            "{",
            "    double b = pow(cabs(mu * lam2 + k), 0.25);",
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
    out.append("    double D[NS];")
    for j, (EI, mu, L, k) in enumerate(plan.levels):
        out.append(f"    symtmm_units(lam2, {p(EI)}, {p(mu)}, {p(L)}, {p(k)}, D + {4 * j});")
    out += ["    double complex E[NS][NC] = {{0}};"]
    for j, c in enumerate(plan.columns):
        out.append(f"    E[{c}][{j}] = 1.0;")
    out.append("    double logscale = 0.0" + "".join(
        f" {'+' if sg > 0 else '-'} log(D[{i}])" for sg, i in _logscale_terms(plan)) + ";")
    nseg = max(len(plan.segments), 1)
    out += [f"    double complex U[{nseg}][4][4];", f"    int nsub[{nseg}];"]
    for i, (a, l, EI, s) in enumerate(plan.segments):
        lam2s = _shifted(s, p)
        out += ["    {",
                f"        nsub[{i}] = symtmm_steps(-{lam2s} * {p(a)});",
                f"        double n = nsub[{i}];",
                (f"        symtmm_segment({lam2s}, {p(a)} / (n * n * n * n), {p(l)} / n, {p(EI)}, "
                f"U[{i}]);"),
                "    }"]
    if plan.stiff:
        out.append(f"    double complex s[{len(plan.stiff)}];")
    for i, (k0, k1, k2) in enumerate(plan.stiff):
        out.append(f"    s[{i}] = {_stiffness(k0, k1, k2, p)};")
    for step in plan.steps:
        if step[0] == "seg":
            out += [f"    for (int t = 0; t < nsub[{step[1]}]; t++) {{",
                    f"        symtmm_apply(U[{step[1]}], D, E, {4 * step[2]});",
                    "        logscale += symtmm_orthonormalise(E);", "    }"]
        else:
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


def _emit_fortran(plan: _Plan) -> str:
    ns, nc = plan.ns, plan.ncol
    coef = _series_coefficients()
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
            f"  real(dp), parameter :: nu_step = {_float_literal(NU_STEP)}_dp",
            f"  real(dp), parameter :: coef(0:{SERIES_TERMS - 1}, 0:3) = reshape([ &"]
    flat = [c for j in range(4) for c in coef[j]]
    for i in range(0, len(flat), 3):
        chunk = ", ".join(v + "_dp" for v in flat[i:i + 3])
        out.append("    " + chunk + (", &" if i + 3 < len(flat) else " &"))
    out += [f"    ], [{SERIES_TERMS}, 4])",
            "contains",
            "",
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
            "  ! transfer matrix of a beam segment of length l (a = m l^4 / EI); I for l = 0",
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
            "  end subroutine segment",
            "",
            "  ! steps of |beta| l <= nu_step for a segment with x = (beta l)^4",
            "  integer function steps(x)",
            "    complex(dp), intent(in) :: x",
            "    steps = max(1, ceiling(abs(x)**0.25_dp / nu_step))",
            "  end function steps",
            "",
            "  ! units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b = |mu lam2 + k|^(1/4)",
            "  subroutine units(lam2, ei, mu, bl, k, dd)",
            "    complex(dp), intent(in) :: lam2",
            "    real(dp), intent(in) :: ei, mu, bl, k",
            "    real(dp), intent(out) :: dd(4)",
            "    real(dp) :: b",
            "    b = max(abs(mu * lam2 + k)**0.25_dp, 1.0_dp / bl)",
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
            "    real(dp) :: dd(ns), logscale, nn",
            f"    integer :: nsub({nseg}), it, ii, kk"]
    if plan.stiff:
        out.append(f"    complex(dp) :: s({len(plan.stiff)})")
    if plan.temps:
        out.append("    real(dp) :: " + ", ".join(str(nm) for nm, _ in plan.temps))
    if any(step[0] == "point" for step in plan.steps):
        out.append("    integer :: jj")
    out += ["    lam = cmplx(lam_re, lam_im, kind=dp)", "    lam2 = lam * lam"]
    for name, expr in plan.temps:
        out.append(f"    {name} = {f(expr)}")
    for g in plan.guards:
        out += [f"    if (.not. ({f(g)} >= 0.0_dp)) then  ! the cuts out of their order",
                "      delta_re = ieee_value(delta_re, ieee_quiet_nan)",
                "      delta_im = delta_re", "      return", "    end if"]
    for j, (EI, mu, L, k) in enumerate(plan.levels):
        out.append(f"    call units(lam2, {f(EI)}, {f(mu)}, {f(L)}, {f(k)}, dd({4 * j + 1}:"
                   f"{4 * j + 4}))")
    out.append("    e = (0.0_dp, 0.0_dp)")
    for j, c in enumerate(plan.columns):
        out.append(f"    e({c + 1}, {j + 1}) = (1.0_dp, 0.0_dp)")
    out.append("    logscale = 0.0_dp" + "".join(
        f" {'+' if sg > 0 else '-'} log(dd({i + 1}))" for sg, i in _logscale_terms(plan)))
    for i, (a, l, EI, s) in enumerate(plan.segments):
        lam2s = _shifted(s, f)
        out += [f"    nsub({i + 1}) = steps(-{lam2s} * {f(a)})",
                f"    nn = real(nsub({i + 1}), kind=dp)",
                f"    call segment({lam2s}, {f(a)} / nn**4, {f(l)} / nn, {f(EI)}, u(:, :, {i + 1}))"]
    for i, (k0, k1, k2) in enumerate(plan.stiff):
        out.append(f"    s({i + 1}) = {_stiffness(k0, k1, k2, f)}")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            out += [f"    do it = 1, nsub({step[1] + 1})",
                    "      do ii = 1, 4",
                    "        tt(ii, :) = (0.0_dp, 0.0_dp)",
                    "        do kk = 1, 4",
                    (f"          tt(ii, :) = tt(ii, :) + u(ii, kk, {step[1] + 1}) * (dd({r0} + ii) / "
                    f"dd({r0} + kk)) * e({r0} + kk, :)"),
                    "        end do",
                    "      end do",
                    f"      e({r0 + 1}:{r0 + 4}, :) = tt",
                    "      logscale = logscale + orthonormalise(e)",
                    "    end do"]
        else:
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


def _emit_octave(plan: _Plan) -> str:
    coef = _series_coefficients()
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
    out += ["  for idx = 1:numel(lam)",
            "    lm = lam(idx);",
            "    lam2 = lm * lm;",
            f"    D = zeros({plan.ns}, 1);"]
    for j, (EI, mu, L, k) in enumerate(plan.levels):
        out.append(f"    D({4 * j + 1}:{4 * j + 4}) = symtmm_units(lam2, {p(EI)}, {p(mu)}, "
                   f"{p(L)}, {p(k)});")
    out.append(f"    E = zeros({plan.ns}, {plan.ncol});")
    for j, c in enumerate(plan.columns):
        out.append(f"    E({c + 1}, {j + 1}) = 1;")
    out.append("    logscale = 0" + "".join(
        f" {'+' if sg > 0 else '-'} log(D({i + 1}))" for sg, i in _logscale_terms(plan)) + ";")
    for i, (a, l, EI, s) in enumerate(plan.segments):
        lam2s = _shifted(s, p)
        out += [(f"    n{i + 1} = max(1, ceil(abs(-{lam2s} * {p(a)})^0.25 / "
                f"{_float_literal(NU_STEP)}));"),
                (f"    U{i + 1} = symtmm_segment({lam2s}, {p(a)} / n{i + 1}^4, {p(l)} / n{i + 1}, "
                f"{p(EI)});")]
    for i, (k0, k1, k2) in enumerate(plan.stiff):
        out.append(f"    s{i + 1} = {_stiffness(k0, k1, k2, p, lam='lm')};")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            blk = f"{r0 + 1}:{r0 + 4}"
            out += [f"    Us = U{step[1] + 1} .* (D({blk}) ./ D({blk}).');",
                    f"    for it = 1:n{step[1] + 1}",
                    f"      E({blk}, :) = Us * E({blk}, :);",
                    "      [E, F] = qr(E, 0);",
                    "      logscale = logscale + sum(log(diag(F)));",
                    "    end"]
        else:
            for row, terms in step[1]:
                rhs = _jump(terms, lambda i: f"s{i + 1}", lambda c: f"E({c + 1}, :)",
                            lambda c: f"D({c + 1})")
                out.append(f"    E({row + 1}, :) = E({row + 1}, :) + D({row + 1}) * ({rhs});")
    rows = " ".join(str(r + 1) for r in plan.rows)
    out += [f"    d(idx) = det(E([{rows}], :)) * exp(logscale);", "  end", "end", "",
            "function U = symtmm_segment(lam2, a, l, EI)",
            "  % transfer matrix of a beam segment of length l (a = m l^4 / EI); I for l = 0",
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
            "function D = symtmm_units(lam2, EI, mu, L, k)",
            "  % units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b = |mu lam2 + k|^(1/4)",
            "  b = max(abs(mu * lam2 + k)^0.25, 1 / L);",
            "  D = [1; 1 / b; 1 / (EI * b^2); 1 / (EI * b^3)];",
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
    return "\n".join(out)


# --------------------------------------------------------------------------------------
# Julia


def _emit_julia(plan: _Plan) -> str:
    coef = _series_coefficients()
    p = lambda e: _val(e, sp.julia_code)
    ns, nc = plan.ns, plan.ncol
    out = ["# " + ln for ln in _header_lines(plan, "julia")] + [""]
    out += [f"const SYMTMM_COEF = ({', '.join('(' + ', '.join(r) + ',)' for r in coef)},)",
            f"const SYMTMM_NU_STEP = {_float_literal(NU_STEP)}", "",
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
            "# transfer matrix of a beam segment of length l (a = m l^4 / EI); I for l = 0",
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
            "",
            "# units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b = |mu lam2 + k|^(1/4)",
            "function symtmm_units(lam2::ComplexF64, EI::Float64, mu::Float64, L::Float64,",
            "                      k::Float64)",
            "    b = max(abs(mu * lam2 + k)^0.25, 1 / L)",
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
    out.append(f"    D = zeros(Float64, {ns})")
    for j, (EI, mu, L, k) in enumerate(plan.levels):
        out.append(f"    D[{4 * j + 1}:{4 * j + 4}] = symtmm_units(lam2, Float64({p(EI)}), "
                   f"Float64({p(mu)}), Float64({p(L)}), Float64({p(k)}))")
    out.append(f"    E = zeros(ComplexF64, {ns}, {nc})")
    for j, c in enumerate(plan.columns):
        out.append(f"    E[{c + 1}, {j + 1}] = 1")
    out.append("    logscale = 0.0" + "".join(
        f" {'+' if sg > 0 else '-'} log(D[{i + 1}])" for sg, i in _logscale_terms(plan)))
    for i, (a, l, EI, s) in enumerate(plan.segments):
        lam2s = _shifted(s, p)
        out += [f"    n{i + 1} = max(1, ceil(Int, abs(-{lam2s} * {p(a)})^0.25 / SYMTMM_NU_STEP))",
                (f"    U{i + 1} = symtmm_segment({lam2s}, Float64({p(a)}) / n{i + 1}^4, "
                f"Float64({p(l)}) / n{i + 1}, Float64({p(EI)}))")]
    for i, (k0, k1, k2) in enumerate(plan.stiff):
        out.append(f"    s{i + 1} = {_stiffness(k0, k1, k2, p)}")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            blk = f"{r0 + 1}:{r0 + 4}"
            out += [f"    Us = U{step[1] + 1} .* (D[{blk}] ./ transpose(D[{blk}]))",
                    f"    for it in 1:n{step[1] + 1}",
                    f"        E[{blk}, :] = Us * E[{blk}, :]",
                    "        logscale += symtmm_orthonormalise!(E)",
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


def _emit_python(plan: _Plan) -> str:
    coef = _series_coefficients()
    pyc = lambda x: sp.pycode(x).replace("math.", "np.")
    p = lambda e: _val(e, pyc)
    out = ['"""'] + _header_lines(plan, "python") + ['"""', "", "import numpy as np", "",
                                                       f"_NU_STEP = {_float_literal(NU_STEP)}",
                                                       "_COEF = ("]
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
            '    """Transfer matrices of a beam segment, shape (N, 4, 4); a = m l^4 / EI."""',
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
            "",
            "def _units(lam2, EI, mu, L, k):",
            '    """Units of one beam\'s state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), shape (N, 4)."""',
            "    b = np.maximum(np.abs(mu * lam2 + k) ** 0.25, 1 / L)",
            ("    return np.stack([np.ones_like(b), 1 / b, 1 / (EI * b**2), 1 / (EI * b**3)], "
            "axis=-1)"),
            "",
            "",
            "def _steps(x):",
            '    """Steps of |beta| l <= _NU_STEP for the largest x = (beta l)^4 of the batch."""',
            "    return max(1, int(np.ceil(np.max(np.abs(x), initial=0.0) ** 0.25 / _NU_STEP)))",
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
    out.append(f"    D = np.empty((flat.size, {plan.ns}))")
    for j, (EI, mu, L, k) in enumerate(plan.levels):
        out.append(f"    D[:, {4 * j}:{4 * j + 4}] = _units(lam2, {p(EI)}, {p(mu)}, {p(L)}, "
                   f"{p(k)})")
    out.append(f"    E = np.zeros((flat.size, {plan.ns}, {plan.ncol}), dtype=complex)")
    for j, c in enumerate(plan.columns):
        out.append(f"    E[:, {c}, {j}] = 1.0")
    out.append("    logscale = np.zeros(flat.size, dtype=complex)" + "".join(
        f" {'+' if sg > 0 else '-'} np.log(D[:, {i}])" for sg, i in _logscale_terms(plan)))
    for i, (a, l, EI, s) in enumerate(plan.segments):
        lam2s = _shifted(s, p)
        out += [f"    n{i} = _steps(-{lam2s} * {p(a)})",
                f"    U{i} = _segment({lam2s}, {p(a)} / n{i}**4, {p(l)} / n{i}, {p(EI)})"]
    for i, (k0, k1, k2) in enumerate(plan.stiff):
        out.append(f"    s{i} = np.broadcast_to({_stiffness(k0, k1, k2, p, lam='flat')}, "
                   "flat.shape)[:, None]")
    for step in plan.steps:
        if step[0] == "seg":
            r0 = 4 * step[2]
            blk = f"{r0}:{r0 + 4}"
            out += [f"    Us = U{step[1]} * (D[:, {blk}, None] / D[:, None, {blk}])",
                    f"    for _ in range(n{step[1]}):",
                    f"        E[:, {blk}, :] = Us @ E[:, {blk}, :]",
                    "        E, F = np.linalg.qr(E)",
                    ("        logscale += np.sum(np.log(np.diagonal(F, axis1=-2, axis2=-1)), "
                    "axis=-1)")]
        else:
            for row, terms in step[1]:
                rhs = _jump(terms, lambda i: f"s{i}", lambda c: f"E[:, {c}, :]",
                            lambda c: f"D[:, {c}, None]")
                out.append(f"    E[:, {row}, :] += D[:, {row}, None] * ({rhs})")
    out += [f"    R = E[:, {plan.rows}, :]",
            "    return (np.linalg.det(R) * np.exp(logscale)).reshape(lam.shape)", ""]
    return "\n".join(out)


_EMITTERS = {"c": _emit_c, "fortran": _emit_fortran, "octave": _emit_octave,
             "julia": _emit_julia, "python": _emit_python}


def generate(model, lang: str, symbolic=()) -> str:
    """Source code of a self-contained evaluator of ``Delta(lam)`` for ``model``.

    Parameters
    ----------
    model : Model
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
