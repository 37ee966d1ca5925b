"""The example model files of the element library: each loads, solves, and agrees with the FE.

One file per feature (Timoshenko beam, Rayleigh beam with axial force, rigid bodies,
a tree, a closed loop, a hinge joint). The reference is the finite-element model of
:mod:`symtmm.fe`, converged and extrapolated (its error estimated below ``1e-7``); the
first frequencies of ``symtmm solve FILE`` must agree with it to ``1e-6`` relative, and
the transfer-matrix ``Delta(i omega)`` must change sign within ``1e-6`` of each of them
(that part does not depend on the root search).
"""

from __future__ import annotations

import json

import numpy as np
import pytest
from test_theories_fe import assert_delta_vanishes_at, converged

from symtmm.cli import main
from symtmm.errors import ComputationError
from symtmm.modelfile import load

COUNT = 5

#: example -> elements per beam of the coarsest FE mesh
EXAMPLES = {
    "timoshenko_beam": 12,
    "rayleigh_axial_force": 8,
    "rigid_body_on_beam": 8,
    "fork_tree": 8,
    "closed_loop": 8,
    "hinge_joint": 8,
}


def _model(examples_dir, name):
    return load(examples_dir / f"{name}.toml")


def test_examples_hold_the_features_they_show(examples_dir):
    timo = _model(examples_dir, "timoshenko_beam").resolved().beams[0]
    assert timo.theory == "timoshenko" and timo.kGA is not None and timo.rhoI > 0
    ray = _model(examples_dir, "rayleigh_axial_force").resolved()
    assert ray.beams[0].theory == "rayleigh" and ray.beams[0].N < 0 < ray.beams[1].N
    bodies = _model(examples_dir, "rigid_body_on_beam").resolved().bodies
    assert [len(b.attachments) for b in bodies] == [1, 2]
    assert bodies[0].xc > bodies[0].attachments[0].x            # the head's offset
    assert [a.hinged for a in bodies[1].attachments] == [False, True]
    for name, joints, hinged in (("fork_tree", 1, False), ("closed_loop", 2, False),
                                 ("hinge_joint", 1, True)):
        model = _model(examples_dir, name)
        assert len(model.bodies) == joints
        for body in model.bodies:
            assert body.M == 0 and body.J == 0
            assert len({a.x for a in body.attachments}) == 1
            assert model.body_frame(body).centre[0] == body.attachments[0].x
            assert all(a.hinged == hinged for a in body.attachments)


@pytest.mark.parametrize("name", list(EXAMPLES))
def test_example_delta_vanishes_at_the_fe_frequencies(examples_dir, name):
    model = _model(examples_dir, name)
    assert_delta_vanishes_at(model, converged(model, COUNT, EXAMPLES[name]))


@pytest.mark.parametrize("name", list(EXAMPLES))
def test_example_solves_and_agrees_with_fe(examples_dir, name, capsys):
    path = examples_dir / f"{name}.toml"
    code = main(["solve", str(path), "--count", str(COUNT), "--json", "--digits", "10"])
    captured = capsys.readouterr()
    if code == 1:                        # the CLI's "computation failed", as the API raises it
        raise ComputationError(captured.err.strip())
    assert code == 0, captured.err
    data = json.loads(captured.out)
    got = []
    for e in data["eigenvalues"]:
        assert e["real"] == "0"
        got += [float(e["imag"])] * e["multiplicity"]
    np.testing.assert_allclose(got[:COUNT], converged(_model(examples_dir, name), COUNT,
                                                      EXAMPLES[name]), rtol=1e-6)
