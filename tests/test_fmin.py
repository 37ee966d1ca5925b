"""The paper's grid searches fmin1d and fmin2d: what they find, and that they say no more.

References: the undamped solver (Wittrick-Williams count, every root) and,
for the damped example 4, the decoupled pinned-pinned families of
``test_damped``; the first pinned-pinned frequencies ``(n pi)^2`` in closed form.
Every digit fmin prints must agree with the nearest true eigenvalue; what the
method misses (merged close roots) is allowed, and the test shows it happens.
"""

from __future__ import annotations

from decimal import Decimal
from pathlib import Path

import mpmath
import numpy as np
import pytest

from symtmm.errors import ModelError
from symtmm.model import Beam, Model, Spring
from symtmm.modelfile import load
from symtmm.roots.fmin import GRID_1D, fmin1d, fmin2d
from symtmm.roots.undamped import solve_undamped
from symtmm.solve import METHODS, solve

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def digits_agree(printed: str, exact) -> bool:
    """``printed`` is ``exact`` correctly rounded to the digits it shows."""
    if printed == "0":
        return abs(exact) < 1e-6
    value = Decimal(printed)
    sig = len(printed.replace("-", "").replace(".", "").lstrip("0"))
    ulp = Decimal(10) ** (value.adjusted() - sig + 1)
    return abs(value - Decimal(mpmath.nstr(exact, 30))) <= ulp / 2 * Decimal("1.0001")


def test_methods_registered():
    assert METHODS["fmin1d"] is fmin1d and METHODS["fmin2d"] is fmin2d


def test_fmin1d_pinned_pinned_closed_form():
    pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    spec = solve(pp, omega_max=400, method="fmin1d")
    exact = [(n * mpmath.pi) ** 2 for n in range(1, 7)]
    assert len(spec) == 6
    for e, w in zip(spec, exact):
        d = e.to_dict()
        assert d["real"] == "0" and e.multiplicity == 1
        assert e.digits >= 6 and digits_agree(d["imag"], w)
    # 500 grid points plus the refinements: every one counted
    assert spec.evaluations > GRID_1D and spec.method == "fmin1d"
    assert spec.digits == min(e.digits for e in spec) <= 15


def test_fmin1d_merges_close_roots_but_prints_no_wrong_digit():
    """Example 3: roots 88.83, 89.11, 89.68 are closer than the grid spacing (1.4 rad/s)."""
    model = load(EXAMPLES / "paper_ex3_three_pp_coupled.toml")
    found = fmin1d(model, omega_max=700)
    true = solve_undamped(model, omega_max=700, digits=20)
    true_omegas = true.omegas()
    assert len(found) < len(true_omegas)           # the weakness is visible
    for e in found:
        printed = e.to_dict()["imag"]
        nearest = min(true_omegas, key=lambda w: abs(w - e.lam.imag))
        assert digits_agree(printed, nearest), (printed, nearest)


def test_fmin1d_count_mode_grows_the_band():
    pp = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="free"),))
    spec = fmin1d(pp, count=4)
    assert spec.total == 4
    exact = solve_undamped(pp, count=4, digits=20).omegas()
    for e, w in zip(spec, exact):
        assert digits_agree(e.to_dict()["imag"], w)


def test_fmin1d_refuses_damped_models():
    model = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("b", "ground", x="1/3", k=0, c=1),))
    with pytest.raises(ModelError, match="fmin2d"):
        fmin1d(model, omega_max=100)


def test_fmin2d_example4_all_nine_with_backed_digits():
    """Table 2 by the paper's 2-D search: found here, with fewer digits than the default."""
    model = load(EXAMPLES / "paper_ex4_damped.toml")
    grid = fmin2d(model, omega_max=1500)
    exact = solve(model, omega_max=1500, digits=20)
    assert len(grid) == len(exact) == 9
    for e, ref in zip(grid, exact):
        d = e.to_dict()
        assert 4 <= e.digits <= 10
        assert digits_agree(d["imag"], ref.lam.imag)
        if ref.lam.real == 0:
            assert d["real"] == "0"
        else:
            assert digits_agree(d["real"], ref.lam.real)
    assert grid.evaluations > 200 * 200


def test_fmin2d_count_mode():
    model = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                  (Spring("b", "ground", x="3/10", k=0, c=4),))
    spec = fmin2d(model, count=2)
    exact = solve(model, count=2, digits=20)
    assert len(spec) == 2
    for e, ref in zip(spec, exact):
        assert digits_agree(e.to_dict()["real"], ref.lam.real)
        assert digits_agree(e.to_dict()["imag"], ref.lam.imag)


# -- stats.evaluations counts every evaluation, whatever the method ------------------------

def _tally(monkeypatch):
    """Count, independently of the code's own counters, every lam at which Delta, R or
    the eigenvalue count is evaluated: the kernel's factorisations and compiled summaries,
    box enclosures and transfer walks (one per point of a batch)."""
    from symtmm.numeric import evaluator, transfer
    from symtmm.roots import count

    calls = {"n": 0}
    for module in (count, evaluator):
        def factor(plan, ar, lam2, lam=None, reverse=False, original=module.factor):
            calls["n"] += len(lam2)
            return original(plan, ar, lam2, lam, reverse)
        monkeypatch.setattr(module, "factor", factor)

        def summary(plan, lam2, lam=None, original=module.summary):
            got = original(plan, lam2, lam)
            calls["n"] += len(lam2) if got is not None else 0   # (None: nothing evaluated)
            return got
        monkeypatch.setattr(module, "summary", summary)
    original_enclose = evaluator.Evaluator.enclose

    def enclose(self, lam, ar):
        calls["n"] += len(lam)
        return original_enclose(self, lam, ar)
    monkeypatch.setattr(evaluator.Evaluator, "enclose", enclose)
    original_log = transfer.log_delta

    def log_delta(plan, lam):
        calls["n"] += int(np.asarray(lam).size)
        return original_log(plan, lam)
    monkeypatch.setattr(transfer, "log_delta", log_delta)
    return calls


@pytest.mark.parametrize("method", ["default", "fmin1d"])
def test_undamped_evaluations_are_all_counted(monkeypatch, method):
    model = Model((Beam("a", 1, 1, 1, left="free", right="free"),
                   Beam("b", 1, 1, 1, left="clamped", right="clamped")),
                  (Spring("a", "b", x="3/10", k=100), Spring("a", "b", x="7/10", k=100)))
    calls = _tally(monkeypatch)
    spectrum = solve(model, count=4, digits=12, method=method)
    assert spectrum.evaluations == calls["n"]


@pytest.mark.parametrize("method", ["default", "fmin2d"])
def test_damped_evaluations_are_all_counted(monkeypatch, method):
    model = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),),
                  (Spring("a", "ground", x="1/4", k=20, c="1/2"),))
    calls = _tally(monkeypatch)
    spectrum = solve(model, omega_max=50, sigma_max=10, digits=10, method=method)
    assert len(spectrum) >= 2
    assert spectrum.evaluations == calls["n"]
