"""The paper's example 1 against the independent finite-element model.

Cubic Hermite elements converge as h^4 in frequency; the FE values must
approach symtmm's from above at that rate, and their Richardson extrapolation
must agree with symtmm far beyond the raw FE accuracy.
"""

import numpy as np
import pytest

pytest.importorskip("scipy")

from symtmm.fe import fe_frequencies
from symtmm.modelfile import load
from symtmm.solve import solve


def _plain(model):
    model = model.resolved()
    beams = [dict(name=b.name, EI=float(b.EI), m=float(b.m), L=float(b.L), x0=float(b.x0),
                  left=b.left, right=b.right) for b in model.beams]
    springs = [dict(between=(s.a, s.b), x=float(s.x), k=float(s.k)) for s in model.springs]
    return beams, springs


@pytest.mark.parametrize("K", ["100", "1000"])
def test_example_1_converges_to_tmm(examples_dir, K):
    model = load(examples_dir / "paper_ex1_ff_cc.toml", {"K": K})
    tmm = np.array([float(w) for w in solve(model, count=10).omegas(expand=True)])
    beams, springs = _plain(model)
    fe = {n: fe_frequencies(beams, springs, n, count=10) for n in (20, 40, 80)}
    err = {n: np.abs(fe[n] - tmm) / tmm for n in fe}
    assert np.all(fe[80] >= tmm * (1 - 1e-12))          # FE is an upper bound
    assert np.all(err[80] < 2e-6)
    ratio = err[40] / err[80]
    assert np.all((ratio > 12) & (ratio < 20))           # h^4: ratio 16
    richardson = (16 * fe[80] - fe[40]) / 15
    assert np.all(np.abs(richardson - tmm) / tmm < 5e-9)


def test_three_level_chain_with_unequal_beams():
    """Beams of different EI, m, length and start, coupled and grounded."""
    from symtmm import Beam, Model, Spring

    model = Model((Beam("a", 2, 1, "1.2", left="clamped", right="free"),
                   Beam("b", 1, "1.5", 1, x0="0.1", left="pinned", right="pinned"),
                   Beam("c", 1, 1, "0.8", x0="0.3", left="free", right="sliding")),
                  (Spring("a", "b", "0.35", 30), Spring("b", "c", "0.9", 50),
                   Spring("c", "ground", "0.3", 10), Spring("a", "b", "1.1", 5)))
    tmm = np.array([float(w) for w in solve(model, count=12).omegas(expand=True)])
    beams, springs = _plain(model)
    fe40, fe80 = (fe_frequencies(beams, springs, n, count=12) for n in (40, 80))
    richardson = (16 * fe80 - fe40) / 15
    assert np.all(np.abs(richardson - tmm) / tmm < 1e-8)
    assert np.all(np.abs(fe80 - tmm) / tmm < 1e-5)
