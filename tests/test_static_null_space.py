"""The rigid-body modes: the exact static null space on any mesh of the model.

A solve counts them on the coarsest mesh its search has already cut (a plan's, cut
finer than the model's required points), not on a mesh of its own: cutting a piece in
two adds a node, never a motion without strain energy. The references are the rigid
motions counted by hand.
"""

import math

import pytest

from symtmm.frame import Member, Node, frame
from symtmm.mesh import static_nullity
from symtmm.model import Beam, Model, Spring, rod
from symtmm.numeric import plan as plan_module
from symtmm.numeric.plan import StiffnessPlan

FF = dict(left="free", right="free")

CASES = [
    # (model, rigid motions counted by hand)
    (Model((Beam("b", 1, 1, 1, **FF),)), 2),                      # translation, rotation
    (Model((Beam("b", 1, 1, 1, left="pinned", right="free"),)), 1),   # rotation about the pin
    (Model((Beam("b", 1, 1, 1, N=3, **FF),)), 1),                  # tension resists turning
    (Model((Beam("b", 1, 1, 1, kw=5, **FF),)), 0),                 # a foundation holds it
    (Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, **FF)),   # joined at one point:
           (Spring("a", "b", "1/3", 10),)), 3),                    # 2 + 2 - 1
    (Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, **FF)),   # at two points: 2 + 2 - 2
           (Spring("a", "b", "1/3", 10), Spring("a", "b", "4/5", 7))), 2),
    (Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, **FF)),   # an irrational spring
           (Spring("a", "b", "1/3", "sqrt(2)"),)), 3),             # (its own coarse mesh)
    (Model((rod("r", 1, 1, 1, left="free", right="free"),)), 1),  # axial translation
    (frame([Member("a", (0, 0), (0, 1), EI=1, EA=10, m=1),          # a free plane frame,
            Member("b", (0, 1), ("1 + sqrt(3)/2", "3/2"), EI=2, EA=10, m=1)]), 3),  # inclined
    (frame([Member("a", (0, 0), (1, 0), EI=1, EA=10, m=1),          # and with a hinge: its
            Member("b", (1, 0), (1, 1), EI=1, EA=10, m=1)],         # relative rotation too
           [Node((1, 0), hinge=True)]), 4),
]


@pytest.mark.parametrize("model,rigid", CASES)
def test_the_null_space_of_a_plan_mesh_is_the_model_s(model, rigid):
    model = model.require_numeric()
    assert static_nullity(model) == rigid
    for radius in (10.0**2, 300.0**2):          # plans cut into few and into many pieces
        plan = StiffnessPlan(model, radius)
        assert static_nullity(model, plan.mesh) == rigid, radius


def test_a_plan_of_thousands_of_freedoms_is_counted_without_a_dense_matrix(monkeypatch):
    """The nullity is the sparse rank's complement: the dense null space of a plan's
    mesh of 11,000 freedoms (a campaign's model: a long Timoshenko beam on a stiff
    foundation) took 76 s and 4.9 GB. Here a free-free beam (2 rigid motions) beside a
    pinned-free one (1) and a long Timoshenko beam on a foundation (0), not joined."""
    from sympy.polys.matrices import DomainMatrix

    def refuse(self):
        raise AssertionError("made dense")
    monkeypatch.setattr(DomainMatrix, "to_dense", refuse)
    # (short pieces: the Timoshenko beam's long ones would make its mesh 883 freedoms)
    monkeypatch.setattr(plan_module, "LONG_FROM", math.inf)
    model = Model((Beam("a", 1, 1, 1, **FF), Beam("b", 1, 1, 1, left="pinned", right="free"),
                   Beam("c", 12800, "3.87", "94.1", kw=213000, theory="timoshenko",
                        rhoI=1810, kGA="27.3", **FF))).require_numeric()
    plan = StiffnessPlan(model, 30.0**2)
    assert plan.mesh.size > 3000
    assert static_nullity(model, plan.mesh) == 3


def test_a_solve_reports_the_rigid_modes_it_counts_on_its_plans():
    from symtmm.roots.undamped import PROOFS, solve_undamped

    model, rigid = CASES[4]         # two beams joined at one point
    spec = solve_undamped(model, count=rigid + 2, digits=12)
    assert spec.eigenvalues[0].multiplicity == rigid
    assert spec.eigenvalues[0].proof == PROOFS["exact"]
    assert float(spec.eigenvalues[1].omega) > 0.1


def test_a_solve_without_rigid_modes_proves_it_by_one_ball_factorisation(monkeypatch):
    """Where one ball factorisation of K(0) decides every pivot, the model has no
    rigid-body mode and the exact static null space is not computed; where a pivot holds
    0 (a free-free beam: two rigid motions) the exact null space counts them, and the
    solve reports them (omega = 0 twice) beside the closed-form free-free frequencies."""
    import mpmath

    from symtmm.mesh import static_nullity as exact
    from symtmm.model import Beam, Model, Spring
    from symtmm.numeric.arith import ball_available
    from symtmm.roots import undamped
    from symtmm.solve import solve

    calls = []

    def counted(model, mesh=None):
        calls.append(model)
        return exact(model, mesh)
    monkeypatch.setattr(undamped, "static_nullity", counted)
    ff = dict(EI=1, m=1, L=1, left="free", right="free")
    held = Model((Beam("b", **ff),), (Spring("b", "ground", "1/4", 1), Spring("b", "ground",
                                                                             "3/4", 1)))
    solve(held, count=3, digits=15)
    assert len(calls) == (0 if ball_available() else 1)     # (without flint: exactly)
    before = len(calls)
    spectrum = solve(Model((Beam("b", **ff),)), count=4, digits=15)
    assert len(calls) == before + 1
    assert spectrum[0].multiplicity == 2 and spectrum[0].omega == 0
    beta = mpmath.findroot(lambda x: mpmath.cos(x) * mpmath.cosh(x) - 1, 4.73)
    assert mpmath.almosteq(spectrum[1].omega, beta**2, rel_eps=1e-14)
