"""Run the command line in-process and check the contract every input must meet.

The contract (shared/design.md, "Errors"): exit 0 with output that parses (JSON
with ``--json``), or exit 2 for bad input and 1 for a failed computation with
exactly one line on stderr; nothing else on stderr (no traceback, no warning),
and every run within a time limit.
"""

from __future__ import annotations

import contextlib
import io
import json
import signal
import threading
import time
import traceback
import warnings
from dataclasses import dataclass

from symtmm.cli import main


class Timeout(BaseException):
    """A run went past its time limit (no Exception, which the code under test may catch)."""


@dataclass
class Run:
    argv: list
    code: int
    stdout: str
    stderr: str
    warnings: list
    seconds: float
    timed_out: bool = False


@contextlib.contextmanager
def _alarm(seconds: float):
    """Raise :class:`Timeout` in the main thread after ``seconds`` (POSIX; else a no-op).

    It interrupts Python code only; a call into C that never returns is not ended,
    but every run here is bounded by the limits it tests.
    """
    usable = hasattr(signal, "setitimer") and threading.current_thread() is threading.main_thread()
    if not usable or not seconds:
        yield
        return

    def fire(signum, frame):
        raise Timeout(f"over {seconds} s")

    old = signal.signal(signal.SIGALRM, fire)
    signal.setitimer(signal.ITIMER_REAL, seconds)
    try:
        yield
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, old)


def run_cli(argv, limit: float | None = None) -> Run:
    """``symtmm ARGV`` in this process: exit code, both streams, warnings raised, seconds."""
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    timed_out = False
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            try:
                with _alarm(limit):
                    code = main([str(a) for a in argv])
            except SystemExit as exc:        # argparse: --help, or a bad flag (exit 2)
                code = exc.code if isinstance(exc.code, int) else 1
            except Timeout:
                code, timed_out = None, True
            except Exception:  # noqa: BLE001 - the real command line would print a traceback
                code = None
                err.write(traceback.format_exc())
    return Run(list(argv), code, out.getvalue(), err.getvalue(),
               [f"{w.category.__name__}: {w.message}" for w in caught],
               time.perf_counter() - start, timed_out)


def contract_violations(run: Run, limit: float | None = None) -> list:
    """What in ``run`` breaks the contract (empty: nothing)."""
    problems = []
    if run.timed_out or (limit is not None and run.seconds > limit):
        problems.append(f"took {run.seconds:.1f} s, over the limit of {limit} s")
        return problems
    if run.warnings:
        problems.append(f"warnings: {run.warnings}")
    if run.code == 0:
        if run.stderr:
            problems.append(f"exit 0 with stderr {run.stderr!r}")
        if "--json" in run.argv:
            try:
                json.loads(run.stdout)
            except ValueError as exc:
                problems.append(f"exit 0, JSON does not parse: {exc}")
        elif not run.stdout.strip():
            problems.append("exit 0 with no output")
    elif run.code in (1, 2):
        lines = run.stderr.splitlines()
        if len(lines) != 1 or not run.stderr.endswith("\n"):
            problems.append(f"exit {run.code} with stderr of {len(lines)} lines: "
                            f"{run.stderr[-2000:]!r}")
        elif "Traceback" in run.stderr or not lines[0].startswith("symtmm"):
            problems.append(f"exit {run.code} with stderr {run.stderr!r}")
    else:
        problems.append(f"exit code {run.code}; stderr {run.stderr[-2000:]!r}")
    return problems


def assert_contract(run: Run, limit: float | None = None) -> None:
    problems = contract_violations(run, limit)
    assert not problems, f"symtmm {' '.join(map(str, run.argv))}: " + "; ".join(problems)
