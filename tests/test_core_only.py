"""The core needs only sympy, mpmath and numpy: the extras are optional.

The README's first command installs the core alone, so the solvers must not
import scipy (or any other extra) on their way. Without scipy the damped
search factors the dynamic stiffness dense in numpy instead of banded in
LAPACK; the two factorizations are compared here at the same points.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from symtmm.modelfile import load
from symtmm.roots import dynamic_stiffness
from symtmm.roots.dynamic_stiffness import DynamicStiffness

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"

# symtmm's command line, as installed and with the extras made unimportable
_PLAIN = "import sys\nfrom symtmm.cli import main\nsys.exit(main(sys.argv[1:]))\n"
_BLOCKED = ("import sys\n"
            "for name in ('scipy', 'matplotlib', 'flint', 'gmpy2', 'dask', 'distributed', 'tqdm'):\n"
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


def test_dense_factorization_equals_banded(monkeypatch):
    ds = DynamicStiffness(load(EXAMPLES / "paper_ex4_damped.toml"), 1500.0**2)
    rng = np.random.default_rng(3)
    lam = -rng.uniform(0, 600, 40) + 1j * rng.uniform(1, 1400, 40)
    banded = ds.log_delta(lam)
    monkeypatch.setattr(dynamic_stiffness, "_zgbtrf", None)
    dense = ds.log_delta(lam)
    assert np.array_equal(banded[2], dense[2])
    ok = banded[2]
    assert ok.sum() > 30
    # each carries a relative error of about n eps cond(K): they agree to twice that
    bound = 2 * ds.size * np.finfo(float).eps * np.linalg.cond(ds.matrix(lam), 1) + 1e-13
    assert np.all(np.abs(dense[0] - banded[0])[ok] <= bound[ok])
    assert np.all(np.abs(np.exp(1j * dense[1]) - np.exp(1j * banded[1]))[ok] <= bound[ok])
