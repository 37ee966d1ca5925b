"""Every command's JSON begins with the same header (docs/design.md, README):
``{"symtmm": version, "model": file, "title": ..., "digits": D, "notes": [...]}``."""

from __future__ import annotations

import json

import pytest
from cli_contract import assert_contract, run_cli

import symtmm

HEADER = ["symtmm", "model", "title", "digits", "notes"]
TITLE = "free-free over clamped-clamped, two springs (Abbas & Rui 2014, example 1)"


@pytest.mark.parametrize("command, digits", [
    (["solve", "--count", "3", "--digits", "12"], 12),
    (["solve", "--count", "2", "--certified"], 15),
    (["solve", "--count", "3", "--method", "fmin1d"], None),
    (["modes", "--count", "1", "--points", "3", "--digits", "9"], 9),
    (["sweep", "--param", "K", "--from", "50", "--to", "100", "--steps", "2", "--count", "2",
      "--digits", "8"], 8),
    (["scan", "--omega-max", "30", "--points", "50", "--digits", "7"], 7),
    (["derive"], None),
])
def test_every_command_has_the_same_header(examples_dir, command, digits):
    path = str(examples_dir / "paper_ex1_ff_cc.toml")
    run = run_cli([command[0], path, *command[1:], "--json"], limit=60)
    assert_contract(run, 60)
    data = json.loads(run.stdout)
    assert list(data)[:5] == HEADER
    assert data["symtmm"] == symtmm.__version__
    assert data["model"] == path and data["title"] == TITLE
    assert isinstance(data["notes"], list) and all(isinstance(n, str) for n in data["notes"])
    if digits is not None:
        assert data["digits"] == digits
    elif command[0] == "derive":
        assert data["digits"] is None             # a closed form is exact
    # one layout: indented by one space
    assert run.stdout.startswith('{\n "symtmm": ')


def test_damped_notes_reach_the_json(examples_dir):
    """The search region, printed beside the table, is in the JSON too."""
    path = str(examples_dir / "paper_ex4_damped.toml")
    run = run_cli(["solve", path, "--count", "2", "--json"], limit=60)
    data = json.loads(run.stdout)
    assert any(n.startswith("search region:") for n in data["notes"])


def test_a_model_built_in_python_has_no_file(examples_dir):
    from symtmm.model import Beam, Model
    from symtmm.solve import solve
    spec = solve(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),), title="pp"),
                 count=1)
    data = spec.to_dict()
    assert data["model"] is None and data["title"] == "pp"
