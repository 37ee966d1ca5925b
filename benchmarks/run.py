"""Run the benchmarks: ``python benchmarks/run.py [--quick] [--json] [-o FILE]``.

Without ``--json`` a markdown report goes to standard output (and to
``FILE`` with ``-o``; the repository's copy is ``docs/benchmarks.md``).
``--quick`` runs small sizes only (under a minute); ``--sections`` picks
sections; ``--from-json FILE`` renders the report of a saved ``--json`` run.
Progress goes to standard error.
"""

from __future__ import annotations

import argparse
import json
import os
import platform
import shutil
import subprocess
import sys
import time
import traceback
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

#: In the order of the targets of issue 11, then the sections reported beside them.
SECTIONS = ("fe", "scaling", "precision", "root_search", "sweep", "evaluator", "ordinary",
            "shapes", "high_modes")
#: Sections that carry no target of their own (reported beside the targets).
REPORTED = ("ordinary", "shapes", "high_modes")


def _load() -> list:
    try:
        return [float(x) for x in Path("/proc/loadavg").read_text().split()[:3]]
    except OSError:
        return list(os.getloadavg())


def _cpu() -> str:
    try:
        for line in Path("/proc/cpuinfo").read_text().splitlines():
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    except OSError:
        pass
    return platform.processor() or "unknown"


def _version(module: str) -> str | None:
    try:
        mod = __import__(module)
    except ImportError:
        return None
    return getattr(mod, "__version__", "?")


def _gcc() -> str | None:
    cc = shutil.which("gcc")
    if not cc:
        return None
    out = subprocess.run([cc, "--version"], capture_output=True, text=True, check=False)
    return out.stdout.splitlines()[0] if out.stdout else None


def _commit() -> str | None:
    """The commit measured, ``-dirty`` if files other than the report's own differ (the
    documented command writes docs/benchmarks.json while it runs)."""
    def git(*args):
        out = subprocess.run(["git", *args], capture_output=True, text=True, cwd=ROOT,
                             check=False)
        return out.stdout.strip() if out.returncode == 0 else None

    head = git("rev-parse", "--short", "HEAD")
    if head is None:
        return None
    changed = git("status", "--porcelain", "--untracked-files=no", "--", ".",
                  ":!docs/benchmarks.json", ":!docs/benchmarks.md")
    return head + ("-dirty" if changed else "")


def _mpmath_backend() -> str:
    """``'gmpy'`` or ``'python'``: mpmath's integer arithmetic, which sets its speed."""
    import mpmath.libmp

    return mpmath.libmp.BACKEND


def machine() -> dict:
    """What the numbers were measured on."""
    from benchmarks.kernel import internals
    from symtmm.numeric.parallel import WORKERS
    return dict(cpu=_cpu(), cores=os.cpu_count(), threads=WORKERS,
                platform=platform.platform(),
                python=platform.python_version(),
                packages={m: _version(m) for m in ("symtmm", "numpy", "scipy", "mpmath", "sympy",
                                                   "flint", "cxroots")},
                mpmath_backend=_mpmath_backend(), certified=internals().certified,
                gcc=_gcc(), commit=_commit(),
                date=time.strftime("%Y-%m-%d %H:%M:%S %Z"))


def run(quick: bool, sections, progress) -> dict:
    from benchmarks import (
        evaluator,
        fe_compare,
        high_modes,
        ordinary,
        precision,
        root_search,
        scaling,
        shapes_compare,
        sweep_compare,
    )

    modules = {"fe": fe_compare, "scaling": scaling, "precision": precision,
               "root_search": root_search, "sweep": sweep_compare, "evaluator": evaluator,
               "ordinary": ordinary, "shapes": shapes_compare, "high_modes": high_modes}
    result = dict(quick=quick, machine=machine(), load_before=_load(),
                  command="python benchmarks/run.py" + (" --quick" if quick else "")
                  + ("" if tuple(sections) == SECTIONS else " --sections " + " ".join(sections)))
    start = time.perf_counter()
    seconds = {}
    for name in sections:
        t = time.perf_counter()
        try:
            result[name] = modules[name].run(quick=quick, progress=progress)
        except Exception as exc:  # noqa: BLE001 - a failed section is reported, the run goes on
            progress(f"{name}: failed: {type(exc).__name__}: {exc}")
            result[name] = dict(error=f"{type(exc).__name__}: {exc}"[:300],
                                trace=traceback.format_exc().splitlines()[-6:],
                                **({} if name in REPORTED else dict(target=dict(met=False))))
        seconds[name] = round(time.perf_counter() - t, 1)
    result["seconds"] = dict(seconds, total=round(time.perf_counter() - start, 1))
    result["load_after"] = _load()
    result["targets"] = {name: result[name]["target"]["met"] for name in sections
                         if name not in REPORTED}
    return result


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="small sizes, under a minute")
    parser.add_argument("--json", action="store_true", help="print the results as JSON")
    parser.add_argument("--sections", nargs="+", choices=SECTIONS, default=list(SECTIONS),
                        help="sections to run (default: all)")
    parser.add_argument("-o", "--output", type=Path, help="also write the report to this file")
    parser.add_argument("--from-json", type=Path, help="render the report of a saved JSON run")
    args = parser.parse_args(argv)

    def progress(msg):
        print(msg, file=sys.stderr, flush=True)

    if args.from_json:
        result = json.loads(args.from_json.read_text())
    else:
        result = run(args.quick, args.sections, progress)
    if args.json:
        text = json.dumps(result, indent=1, default=str)
    else:
        from benchmarks.report import render
        text = render(result)
    print(text)
    if args.output:
        args.output.write_text(text + "\n")
    return 0


if __name__ == "__main__":
    sys.exit(main())
