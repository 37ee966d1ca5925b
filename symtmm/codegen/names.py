"""Argument names: an identifier per symbolic parameter that means nothing else.

A parameter's name comes from a model file (or a SymPy symbol); in generated
code it must not be a keyword, builtin or macro of the language, nor any name
the evaluator itself uses. The language's names are its dialect's
``reserved`` set; the evaluator's are read from the code generated for the
model (:func:`code_names`), so that a name the walker or a runtime file
starts to use is avoided without being listed anywhere.
"""

from __future__ import annotations

import re
from dataclasses import replace

import sympy as sp

from .plan import mapped, placeholder
from .walker import emit

__all__ = ["argument_names", "code_names", "for_language"]

#: Longest argument name: Fortran 2008 and Octave (namelengthmax) allow 63 characters,
#: C99 guarantees 63 significant ones.
MAX_NAME = 63
_ASCII_IDENTIFIER = re.compile(r"[A-Za-z_][A-Za-z_0-9]*")
# numbered locals of the generated code (U1, s0, n2, th0, nu3, cp0, Us8)
_NUMBERED = re.compile(r"^(?:[Usn]|th|nu|cp|Us)\d+$")


def argument_names(params, dialect, used=()) -> list:
    """An identifier per parameter that means nothing else where ``dialect``'s code uses it.

    A name that is a safe identifier stays as it is. Any other gets ``p_`` in
    front (again, until it is free): names the language reserves
    (``dialect.reserved`` and ``dialect.reserved_pattern``), names the
    generated code itself uses (``used``, see :func:`code_names`), numbered
    locals (``U1``, ``th0``), and names starting with ``symtmm`` or ``_``. A
    name that is not an ASCII identifier (possible for a symbol built in
    Python) has its other characters replaced by ``_`` and always gets the
    prefix; one longer than ``MAX_NAME`` is cut and numbered. Fortran compares
    without case. The generated header lists every renamed argument with its
    parameter.

    Examples
    --------
    >>> from .dialects import DIALECTS
    >>> argument_names(["I", "K", "x1"], DIALECTS["c"])
    ['p_I', 'K', 'x1']
    >>> argument_names(["E", "K", "k", "a b", "th0"], DIALECTS["fortran"])
    ['p_E', 'K', 'p_k', 'p_a_b', 'p_th0']
    >>> argument_names(["complex", "range", "sqrt", "x"], DIALECTS["python"], used={"sqrt"})
    ['p_complex', 'p_range', 'p_sqrt', 'x']
    """
    fold = dialect.fold
    taken = {fold(v) for v in dialect.reserved} | {fold(v) for v in used}

    def unsafe(arg: str) -> bool:
        return (fold(arg) in taken or len(arg) > MAX_NAME
                or not _ASCII_IDENTIFIER.fullmatch(arg) or bool(_NUMBERED.match(arg))
                or arg.lower().startswith(("symtmm", "_"))
                or bool(dialect.reserved_pattern.match(arg)))

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
        while unsafe(arg) and len(arg) <= MAX_NAME:
            arg = "p_" + arg
        count = 0
        while unsafe(arg):          # too long: cut, and numbered to stay apart
            count += 1
            arg = f"p{i + 1}_{count}_" + base[:MAX_NAME - 16]
        taken.add(fold(arg))
        out[i] = arg
    return out


def code_names(plan, dialect) -> set:
    """Every name the generated evaluator of ``plan`` uses besides its arguments.

    The code is generated once with placeholder arguments and read: the
    evaluator's body (locals, functions and constants it calls, nested
    functions' locals) and, for Fortran, the module's declarations and
    procedure names, which the subroutine sees by host association. The
    helpers' locals are theirs: an argument may share a name with them.
    """
    blank = replace(plan, title="", source="", values={},
                    args=[placeholder(i) for i in range(len(plan.params))])
    code = re.sub(dialect.not_code, " ", emit(blank, dialect))
    start = re.search(dialect.evaluator[0], code, re.MULTILINE).start()
    end = re.compile(dialect.evaluator[1], re.MULTILINE).search(code, start).end()
    text = code[start:end] + " " + dialect.host_names(code)
    return set(re.findall(r"\b[A-Za-z_][A-Za-z_0-9]*", text))


def for_language(plan, dialect):
    """The plan with each parameter's placeholder replaced by its argument in ``dialect``."""
    args = argument_names(plan.params, dialect, code_names(plan, dialect))
    names = {placeholder(i): a for i, a in enumerate(args)}

    def rename(v):
        ren = {s: sp.Symbol(names[s.name], **s.assumptions0)
               for s in v.free_symbols if s.name in names}
        return v.xreplace(ren) if ren else v

    return replace(mapped(plan, rename), args=args)
