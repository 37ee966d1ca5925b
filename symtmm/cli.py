"""Command line: ``symtmm COMMAND MODEL ...`` (same as ``python -m symtmm``).

Each command lives in its own module of :mod:`symtmm.commands`, with
``HELP`` (one line), ``add_arguments(parser)`` and ``run(args) -> int``.
Errors in the input print one line on stderr and exit with 2; a computation
that fails exits with 1. Neither prints a traceback.

Text from model files and command lines (titles, names, keys, paths) reaches
the terminal only through :func:`symtmm.text.printable`: standard output is
filtered while a command runs (newlines and tabs of tables and JSON kept,
every other control character shown as an escape such as ``\\x1b``), and
error messages and titles are escaped to one line.
"""

from __future__ import annotations

import argparse
import importlib
import math
import pkgutil
import sys

from . import __version__, commands, progress
from .errors import ComputationError, ModelError
from .limits import FLAG_MAX
from .text import printable

__all__ = ["main", "load_model_arg", "add_model_arguments", "add_csv_argument",
           "check_csv_path", "write_csv_arg", "positive_int", "nonnegative", "whole_number",
           "real_number", "title_line"]


class _Parser(argparse.ArgumentParser):
    """An argument parser whose errors are one line, exit code 2."""

    def error(self, message):
        # the message quotes the command line, which may carry escapes or newlines
        self.exit(2, f"{self.prog}: error: {printable(message)}\n")


class _PrintableStream:
    """A text stream that shows every control character it is given as an escape.

    Newlines and tabs pass (tables, JSON); anything else a terminal would act
    on (escape sequences, carriage returns, line separators) is written as
    :func:`symtmm.text.printable` spells it, and what the stream's encoding
    cannot encode as a backslash escape rather than an exception.
    """

    def __init__(self, stream):
        self._stream = stream

    def write(self, text):
        safe = printable(text, multiline=True)
        encoding = getattr(self._stream, "encoding", None)
        if encoding:
            safe = safe.encode(encoding, "backslashreplace").decode(encoding)
        self._stream.write(safe)
        return len(text)

    def __getattr__(self, name):
        return getattr(self._stream, name)


def title_line(text) -> str:
    r"""A title or path as one line for the terminal: newlines too shown as escapes.

    Examples
    --------
    >>> print(title_line("two beams\n\x1b[2Jcleared"))
    two beams\n\x1b[2Jcleared
    """
    return printable(text)


def _error(text: str) -> None:
    print(printable(text), file=sys.stderr)


def load_model_arg(args):
    """The model named by ``args.model``, with ``--set`` overrides applied."""
    from .modelfile import load, parse_assignment

    overrides = dict(parse_assignment(s) for s in (args.set or []))
    return load(args.model, overrides)


def whole_number(low: int, high: int):
    """Argument type: a whole number in ``[low, high]``, a one-line message otherwise.

    The bounds are those of :mod:`symtmm.limits`: a value no run can honour is
    refused before the model is read.
    """
    def convert(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
        if value < low:
            raise argparse.ArgumentTypeError(f"must be at least {low}, got {value}")
        if value > high:
            raise argparse.ArgumentTypeError(f"must be at most {high}, got {value}")
        return value
    return convert


def real_number(low: float = 0.0, high: float = FLAG_MAX, low_open: bool = False):
    """Argument type: a finite number in ``[low, high]`` (``(low, high]`` if ``low_open``)."""
    def convert(text: str) -> float:
        try:
            value = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
        if not math.isfinite(value):
            raise argparse.ArgumentTypeError(f"must be a finite number, got {text}")
        if value < low or (low_open and value == low):
            raise argparse.ArgumentTypeError(
                f"must be {'greater than' if low_open else 'at least'} {low:g}, got {text}")
        if value > high:
            raise argparse.ArgumentTypeError(f"must be at most {high:g}, got {text}")
        return value
    return convert


#: Argument type: a whole number >= 1 (and at most 10**9, beyond anything a run can use).
positive_int = whole_number(1, 10**9)
#: Argument type: a finite number >= 0 (at most :data:`symtmm.limits.FLAG_MAX`).
nonnegative = real_number(0.0)


def add_time_argument(parser, what: str = "the search"):
    """``--max-seconds S``: the time budget of a search (:mod:`symtmm.deadline`)."""
    from .limits import SEARCH_SECONDS
    parser.add_argument("--max-seconds", type=real_number(0.0, 1e6, low_open=True),
                        default=SEARCH_SECONDS, metavar="S",
                        help=f"give up {what} after S seconds (default {SEARCH_SECONDS:g})")


def add_csv_argument(parser):
    """``--csv FILE``: the result's rows as CSV (:mod:`symtmm.tables`)."""
    parser.add_argument("--csv", metavar="FILE",
                        help="also write the table to FILE as CSV (every digit kept)")


def check_csv_path(path) -> None:
    """Refuse, before any computation, a CSV file whose folder cannot take it."""
    import os
    from pathlib import Path

    folder = Path(path).parent if str(Path(path).parent) else Path(".")
    if not folder.is_dir():
        raise ModelError(f"cannot write the table: no folder {folder}", field="--csv",
                         source=str(path))
    if not os.access(folder, os.W_OK):
        raise ModelError(f"cannot write the table: folder {folder} is not writable",
                         field="--csv", source=str(path))


def write_csv_arg(result, args) -> str | None:
    """Write ``result`` to ``args.csv`` if given; the line to print after the table."""
    if not getattr(args, "csv", None):
        return None
    try:
        result.to_csv(args.csv)
    except ModelError as exc:
        raise ModelError(exc.message, field="--csv", source=exc.source) from None
    return f"table written to {title_line(args.csv)}"


def add_model_arguments(parser):
    """The arguments every command that reads a model takes."""
    parser.add_argument("model", metavar="MODEL", help="model file (TOML)")
    parser.add_argument("--set", action="append", metavar="NAME=VALUE",
                        help="override a parameter (repeatable)")
    parser.add_argument("--quiet", action="store_true",
                        help="no progress bars (shown on a terminal for work over a second)")


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


def _progress_wanted(args) -> bool:
    """Bars on a terminal only, never with --json or --quiet (``--progress`` forces them)."""
    forced = getattr(args, "progress", None)
    if forced is not None:
        return forced
    if getattr(args, "quiet", False) or getattr(args, "json", False):
        return False
    return bool(getattr(sys.stderr, "isatty", lambda: False)())


def main(argv=None) -> int:
    """Entry point; returns the exit code."""
    parser = build_parser()
    args = parser.parse_args(argv)
    stdout = sys.stdout
    # every printing path of every command goes through this one filter
    sys.stdout = _PrintableStream(stdout)
    try:
        with progress.shown(_progress_wanted(args)):
            return args._run(args)
    except ModelError as exc:
        _error(f"symtmm: {exc.for_command_line()}")
        return 2
    except ComputationError as exc:
        model = getattr(args, "model", None)
        _error(f"symtmm: {model}: computation failed: {exc}" if model else
               f"symtmm: computation failed: {exc}")
        return 1
    except KeyboardInterrupt:
        _error("symtmm: interrupted")
        return 130
    except BrokenPipeError:
        # the reader went away (`symtmm solve ... | head`): stop quietly, as Unix tools do
        import os

        devnull = os.open(os.devnull, os.O_WRONLY)
        os.dup2(devnull, stdout.fileno())
        return 0
    finally:
        sys.stdout = stdout


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
