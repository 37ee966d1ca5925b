"""Command line: ``symtmm COMMAND MODEL ...`` (same as ``python -m symtmm``).

Each command lives in its own module of :mod:`symtmm.commands`, with
``HELP`` (one line), ``add_arguments(parser)`` and ``run(args) -> int``.
Errors in the input print one line on stderr and exit with 2; a computation
that fails exits with 1. Neither prints a traceback.
"""

from __future__ import annotations

import argparse
import importlib
import pkgutil
import sys

from . import __version__, commands
from .errors import ComputationError, ModelError

__all__ = ["main", "load_model_arg", "add_model_arguments", "positive_int", "nonnegative"]


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, exit code 2."""

    def error(self, message):
        self.exit(2, f"{self.prog}: error: {message}\n")


def load_model_arg(args):
    """The model named by ``args.model``, with ``--set`` overrides applied."""
    from .modelfile import load, parse_assignment

    overrides = dict(parse_assignment(s) for s in (args.set or []))
    return load(args.model, overrides)


def positive_int(text: str) -> int:
    """Argument type: a whole number >= 1, with a one-line message otherwise."""
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def nonnegative(text: str) -> float:
    """Argument type: a finite number >= 0, with a one-line message otherwise."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not value >= 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a finite number >= 0, got {text}")
    return value


def add_model_arguments(parser):
    """The arguments every command that reads a model takes."""
    parser.add_argument("model", metavar="MODEL", help="model file (TOML)")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE",
                        help="override a parameter (repeatable)")


def build_parser() -> argparse.ArgumentParser:
    parser = _Parser(prog="symtmm", description=(
        "Exact free vibration of multilevel beam systems by the transfer matrix method "
        "of linear multibody systems."))
    parser.add_argument("--version", action="version", version=f"symtmm {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=_Parser)
    sub.required = True
    for info in sorted(pkgutil.iter_modules(commands.__path__), key=lambda i: i.name):
        module = importlib.import_module(f"{commands.__name__}.{info.name}")
        cmd = sub.add_parser(info.name.replace("_", "-"), help=module.HELP,
                             description=module.__doc__)
        module.add_arguments(cmd)
        cmd.set_defaults(_run=module.run)
    return parser


def main(argv=None) -> int:
    """Entry point; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        return args._run(args)
    except ModelError as exc:
        print(f"symtmm: {exc}", file=sys.stderr)
        return 2
    except ComputationError as exc:
        print(f"symtmm: computation failed: {exc}", file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        print("symtmm: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        # the reader went away (`symtmm solve ... | head`): stop quietly, as Unix tools do
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, sys.stdout.fileno())
        return 0


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
