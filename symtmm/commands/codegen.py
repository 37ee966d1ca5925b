"""A self-contained evaluator of Delta(lam) = det R(lam) in C, Fortran, Octave, Julia or Python.

The generated function is called symtmm_delta; parameters left symbolic
(no value in the file, or named with --symbolic) become extra arguments after
lam, in alphabetical order. See docs/derive_codegen.md for the signatures.
An Octave/MATLAB file must be called symtmm_delta.m to be found.

Every model solve accepts is accepted: beams of any theory (Euler-Bernoulli,
Rayleigh, Timoshenko; axial force, Winkler foundation), springs, dashpots and
masses, rigid bodies and joints (chains, trees, closed loops). Any numeric
field may be kept symbolic, e.g. --symbolic kGA,N.
"""

from __future__ import annotations

import sys

from ..cli import add_model_arguments, load_model_arg
from ..errors import ModelError

HELP = "generate a C/Fortran/Octave/Julia/Python evaluator of Delta(lam)"


def add_arguments(parser):
    from ..codegen import LANGUAGES

    add_model_arguments(parser)
    parser.add_argument("--lang", required=True, choices=LANGUAGES, help="output language")
    parser.add_argument("-o", "--output", metavar="FILE", default="-",
                        help="output file (default: standard output)")
    parser.add_argument("--symbolic", action="append", metavar="NAME[,NAME...]",
                        help="turn these parameters into arguments (repeatable)")


def run(args) -> int:
    from ..codegen import generate

    model = load_model_arg(args)
    names = [n.strip() for item in (args.symbolic or []) for n in item.split(",") if n.strip()]
    try:
        source = generate(model, args.lang, symbolic=names)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    if args.output == "-":
        sys.stdout.write(source)
        return 0
    try:
        with open(args.output, "w", encoding="utf-8") as fh:
            fh.write(source)
    except OSError as exc:
        raise ModelError(f"cannot write the file: {exc.strerror or exc}",
                         field="-o", source=args.output) from None
    return 0
