"""The core needs only sympy, mpmath and numpy: the extras are optional.

The README's first command installs the core alone, so the solvers must not
import scipy (or any other extra) on their way; without python-flint they prove
by mpmath at two precisions instead of balls, and must print the same digits.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import pytest

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

# symtmm's command line, as installed and with the extras made unimportable
_PLAIN = "import sys\nfrom symtmm.cli import main\nsys.exit(main(sys.argv[1:]))\n"
_BLOCKED = ("import sys\n"
            "for name in ('scipy', 'matplotlib', 'flint', 'gmpy2', 'dask', 'distributed', "
            "'tqdm', 'threadpoolctl'):\n"
            "    sys.modules[name] = None\n") + _PLAIN


def _solve_json(args, blocked):
    code = _BLOCKED if blocked else _PLAIN
    out = subprocess.run([sys.executable, "-c", code, "solve", *args, "--json"],
                         check=False, capture_output=True, text=True, timeout=600)
    assert out.returncode == 0, out.stderr
    data = json.loads(out.stdout)
    return [(e["real"], e["imag"], e["multiplicity"]) for e in data["eigenvalues"]]


@pytest.mark.parametrize("args", [
    [str(EXAMPLES / "paper_ex1_ff_cc.toml")],
    [str(EXAMPLES / "paper_ex4_damped.toml"), "--omega-max", "600"],
], ids=["undamped", "damped"])
def test_solve_without_the_extras_prints_the_same_digits(args):
    assert _solve_json(args, blocked=True) == _solve_json(args, blocked=False)
