"""The one walk from a plan to an evaluator, written through a language's dialect.

:func:`emit` writes the file: the header comment, the fixed kernels of
``runtime/`` verbatim, and the evaluator whose body :func:`walk` writes from
the plan: the parameters' expressions and guards, then per point the units of
the state, the segments' matrices and the stations' stiffnesses, the
propagation of the columns through the cuts, and the determinant.

Examples
--------
>>> from symtmm.model import Beam, Model
>>> from .dialects import DIALECTS
>>> from .plan import plan
>>> model = Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),))
>>> print("\\n".join(walk(plan(model), DIALECTS["julia"]).render(0)))
nu_step = 4.0
D = zeros(Float64, 4)
D[1:4] = symtmm_units(abs(1.0 * lam2 + 0.0)^0.25, 1.0, 1.0)
E = zeros(ComplexF64, 4, 2)
E[2, 1] = 1.0
E[4, 2] = 1.0
logscale = 0.0 + log(D[2]) + log(D[4]) - log(D[1]) - log(D[3])
grown = 0.0
w = abs(-lam2 * 1.0)^0.25
n0 = max(1, ceil(Int, w / nu_step))
nu0 = w / n0
U0 = symtmm_segment(lam2, 1.0, 1.0, 1.0, n0)
Us = U0 .* (D[1:4] ./ transpose(D[1:4]))
for it in 1:n0
    if grown + nu0 > nu_step
        logscale = symtmm_orthonormalise!(E, logscale)
        grown = 0.0
    end
    E[1:4, :] = Us * E[1:4, :]
    grown = grown + nu0
end
delta = symtmm_det(E[[1, 3], :]) * exp(logscale)
return delta
"""

from __future__ import annotations

import textwrap
from importlib import resources

import sympy as sp

from .. import __version__
from ..assembly import state_rows
from ..compile import NU_STEP
from ..text import comment_text

__all__ = ["Body", "emit", "walk"]

#: Longest line of the header comment, marker excluded (Fortran allows 132 characters).
HEADER_WIDTH = 100


class Body:
    """The evaluator's statements at their depths, and the locals they set.

    ``params`` are the statements that depend on the parameters alone,
    ``point`` those of one point (or one batch of points); ``waves`` holds each
    segment's ``|beta| l``. The dialect puts them where its language wants them.
    """

    def __init__(self, dialect):
        self.d = dialect
        self.lines: list = []       # (depth, text)
        self.kinds: dict = {}       # local -> (kind, dims), in the order first set
        self.closers: list = []
        self.split = 0              # where the per-point statements start
        self.waves: list = []

    params = property(lambda self: self.lines[:self.split])
    point = property(lambda self: self.lines[self.split:])

    def put(self, *texts):
        self.lines += [(len(self.closers), t) for t in texts]

    def new(self, name, kind, dims=()) -> bool:
        """Note a local; whether to declare it here and now (C, the first time)."""
        first = name not in self.kinds
        self.kinds.setdefault(name, (kind, tuple(dims)))
        return first and self.d.declares_in_place

    def let(self, name, value, kind="real", dims=()):
        """``name = value``, declared where the language wants it."""
        first = self.new(name, kind, dims)
        self.put(self.d.assign(self.d.declaration(name, kind, dims) if first else name, value))

    def array(self, name, kind, dims, zero=False):
        """A local array, filled with zeros or left to a routine."""
        if self.new(name, kind, dims) or zero:
            self.put(self.d.zero_array(name, kind, dims) if zero
                     else self.d.declaration(name, kind, dims) + self.d.end)

    def open(self, head, closer):
        self.put(head)
        self.closers.append(closer)

    def loop(self, var, count):
        self.kinds.setdefault(var, ("int", ()))
        self.open(self.d.for_open.format(var, count), self.d.for_close)

    def close(self):
        closer = self.closers.pop()
        if closer:
            self.put(closer)

    def render(self, depth, lines=None) -> list:
        return [self.d.indent * (depth + k) + text
                for k, text in (self.lines if lines is None else lines)]


def _polynomial(coeffs, value, lam) -> str:
    """``k0 + k1 lam + k2 lam lam + ...`` without the terms that are zero.

    Examples
    --------
    >>> _polynomial((3, 0, -2), str, "lam")
    '3 + (-2) * lam * lam'
    """
    parts = []
    for k, coef in enumerate(coeffs):
        if sp.sympify(coef) == 0:
            continue
        text = value(coef)
        if text.lstrip().startswith("-"):
            text = f"({text})"          # no operator after an operator (Fortran)
        parts.append(" * ".join([text] + [lam] * k))
    return " + ".join(parts) if parts else value(0)


def walk(plan, d) -> Body:
    """The body of ``plan``'s evaluator in dialect ``d``."""
    b, value = Body(d), d.value
    b.let("nu_step", d.literal(NU_STEP))
    for name, expr in plan.temps:
        b.let(str(name), d.printer(expr))
    if plan.guards:                            # the cuts out of their order
        b.open(d.if_open.format(d.either.join(d.negative.format(value(g))
                                              for g in plan.guards)), d.if_close)
        b.put(*d.nan_exit)
        b.close()
    for t, th in enumerate(plan.theories):     # EI, a, b, cN, rhoI, m, kw
        b.let(f"th{t}", d.vector.format(", ".join(value(v) for v in th)), dims=(7,))
    for c, cp in enumerate(plan.couplings):    # l, A, F, K, C, l^2/EI, l^3/EI
        b.let(f"cp{c}", d.vector.format(", ".join(value(v) for v in cp)), dims=(len(cp),))
    b.split = len(b.lines)
    # units of each beam's state from its wave number, a body's from the beam variable's
    b.array("D", "real", (plan.size,), zero=True)
    for j, level in enumerate(plan.levels):
        if level[0] == "eb":
            _, EI, mu, L, k = level
            wave = d.fourth_root.format(f"{value(mu)} * lam2 + {value(k)}")
        else:
            _, t, L = level
            EI, wave = plan.theories[t][0], f"{d.fn('wave')}(lam2, th{t})"
        b.put(d.call.format(fn=d.fn("units"), args=f"{wave}, {value(EI)}, {value(L)}",
                            out=d.index("D", (4 * j, 4))))
    for i, src in plan.virtual:
        b.put(d.assign(d.index("D", i), d.index("D", src)))
    # the unknowns' columns, measured in those units
    b.array("E", "complex", (plan.size, plan.ncol), zero=True)
    for j, c in enumerate(plan.columns):
        b.put(d.assign(d.index("E", c, j), d.literal(1)))
    b.let("logscale", d.literal(0) + "".join(
        f" {'+' if sign > 0 else '-'} {d.log.format(d.index('D', i))}"
        for sign, i in plan.logscale_terms))
    b.let("grown", d.literal(0))               # |beta| l since the last orthonormalisation
    # each segment's matrix, for one of n equal steps of |beta| l <= nu_step
    for i, seg in enumerate(plan.segments):
        if seg[0] == "eb":
            _, a, l, EI, s = seg
            lam2 = "lam2" if s == 0 else f"(lam2 + {value(s)})"    # a foundation: kw/m
            b.waves.append(d.fourth_root.format(f"-{lam2} * {value(a)}"))
            routine, args = "segment", [lam2, value(a), value(l), value(EI)]
        elif seg[0] == "coupled":
            _, nb, c = seg
            b.waves.append(f"{d.fn('wave_coupled')}(lam2, cp{c}, {nb})")
            routine, args = "segment_coupled", [d.lam, "lam2", f"cp{c}", str(nb)]
        else:
            _, t, l = seg
            b.waves.append(f"{d.fn('wave')}(lam2, th{t}) * {value(l)}")
            routine, args = "segment_gen", ["lam2", f"th{t}", value(l)]
        b.let("w", b.waves[-1])
        b.let(f"n{i}", d.steps.format("w", i), "int")
        b.let(f"nu{i}", f"{d.peak.format('w')} / n{i}")
        size = 4 * seg[1] if seg[0] == "coupled" else 4
        b.array(f"U{i}", "complex", (size, size))
        b.put(d.call.format(fn=d.fn(routine), args=", ".join([*args, f"n{i}"]), out=f"U{i}"))
    for i, coeffs in enumerate(plan.stiff):
        b.let(f"s{i}", d.stiffness.format(_polynomial(coeffs, value, d.lam)), "complex")
    # the walk: segments step by step, re-orthonormalised once the columns may have grown
    # by exp(nu_step); stations' jumps E[row] += D[row] s E[col] / D[col]
    sizes = {"ns": plan.size, "nc": plan.ncol}
    for step in plan.steps:
        if step[0] == "seg":
            _, k, level = step
            if isinstance(level, int):
                b.array("Us", "complex", (4, 4))
                b.put(d.scale.format(k=k, D=d.index("D", (4 * level, 4))))
                apply = d.apply.format(E=d.index("E", (4 * level, 4), ":"), **sizes)
            else:
                # beams joined by layers: their rows, variable by variable
                rows = state_rows(level)
                m, us = len(rows), f"Us{len(rows)}"
                b.array(us, "complex", (m, m))
                b.put(d.scale_rows.format(k=k, D=d.index("D", rows), m=m, Us=us))
                apply = d.apply_rows.format(E=d.index("E", rows, ":"), m=m, Us=us, **sizes)
            b.loop("it", f"n{k}")
            b.open(d.if_open.format(f"grown + nu{k} > nu_step"), d.if_close)
            b.put(d.orthonormalise.format(**sizes))
            b.let("grown", d.literal(0))
            b.close()
            b.put(apply)
            b.let("grown", f"grown + nu{k}")
            b.close()
        elif step[1]:
            if d.row_loop:
                b.loop("j", plan.ncol)
            for row, terms in step[1]:
                jump = " ".join(f"{'-' if sign < 0 else '+'} s{si} * {d.index('E', col, ':')} / "
                                f"{d.index('D', col, *d.against_row)}" for sign, col, si in terms)
                jump = jump[2:] if jump[0] == "+" else "-" + jump[2:]
                b.put(d.assign(d.index("E", row, ":"), f"{d.index('E', row, ':')} + "
                               f"{d.index('D', row, *d.against_row)} * ({jump})"))
            if d.row_loop:
                b.close()
    b.let("delta", f"{d.det.format(E=d.index('E', plan.rows, ':'), **sizes)} * "
                   f"{d.exp.format('logscale')}", "complex")
    b.put(*d.deliver)
    return b


def header_lines(plan, lang: str) -> list:
    """The header comment's lines, without the comment marker.

    Every line goes through :func:`comment_lines`: the title, the source path
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
    if plan.couplings:
        lines += ["Beams joined by continuous layers: one member whose transfer matrix has the",
                  "blocks c_j(X) and X c_j(X) of the N x N matrix X = -l^4 EI^-1 (diag(m lam^2 +",
                  "kw) + L_k + lam L_c) (symtmm.elements.layer), series of 11 terms per step."]
    if plan.theories:
        lines += ["Other beam theories (axial force N, rotary inertia rhoI, shear kGA): exp(A l)",
                  "from alpha, beta of cosh and sinh/s in (t, d) = (trace, det) of G = B C,",
                  ("series on a piece with max|r| h^2 <= 1, then doubled "
                   "(symtmm.elements.theories).")]
    lines += [
        f"Segments applied in steps of |beta| l <= {NU_STEP:g}; states in units of each",
        "beam's wave number; the unknown columns re-orthonormalised whenever they may have",
        f"grown by exp({NU_STEP:g}) (Godunov), Delta = det(E[rows]) * exp(sum of log norms):",
        "about 13 significant digits at any mode, as symtmm.compile.Evaluator.log_delta",
        "(less about log10(k L/EI) beside a rotational spring far stiffer than its beams,",
        "log10(k L^3/EI) beside a translational one).",
    ]
    return [piece for line in lines for piece in comment_lines(line)]


def comment_lines(text: str) -> list:
    r"""``text`` as comment payloads (:func:`symtmm.text.comment_text`), wrapped.

    Pieces are at most ``HEADER_WIDTH`` characters, so that a long title keeps
    Fortran's lines under 132 characters; a piece only ever ends a line, and no
    language continues a comment onto the next line.

    Examples
    --------
    >>> comment_lines("title */ int f(void); /*\nsecond line")
    ['title * / int f(void); / *\\nsecond line']
    >>> [len(p) <= HEADER_WIDTH for p in comment_lines("x" * 250)]
    [True, True, True]
    """
    safe = comment_text(text)
    if len(safe) <= HEADER_WIDTH:
        return [safe]
    return textwrap.wrap(safe, HEADER_WIDTH, subsequent_indent="    ",
                         break_long_words=True, break_on_hyphens=False)


def runtime_source(stem: str, dialect) -> str:
    """The fixed kernels ``runtime/<stem>`` of ``dialect``'s language, as shipped."""
    name = f"{stem}.{dialect.extension}"
    return resources.files(__package__).joinpath("runtime").joinpath(name).read_text(
        encoding="utf-8")


def emit(plan, d) -> str:
    """The source file of ``plan``'s evaluator in dialect ``d``."""
    needed = {"euler_bernoulli": plan.has_eb, "theory": plan.has_gen,
              "layer": plan.has_coupled}
    runtime = "\n\n".join(runtime_source(stem, d).strip("\n")
                          for stem in d.runtime if needed.get(stem, True))
    return d.finish(d.file(d.header(header_lines(plan, d.name)), runtime,
                           d.function(plan, walk(plan, d))))
