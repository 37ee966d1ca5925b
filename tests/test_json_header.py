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


# -- the library speaks its own words; the command line translates ---------------------------


def test_python_errors_name_arguments_and_the_command_line_flags(examples_dir, tmp_path):
    from symtmm import api
    from symtmm.errors import ModelError
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml")
    with pytest.raises(ModelError, match=r": omega_max: must be a finite number >= 0") as info:
        api.solve(model, omega_max=-1)
    assert "--" not in str(info.value)
    run = run_cli(["solve", examples_dir / "paper_ex1_ff_cc.toml", "--omega-max", "1e99"])
    assert run.code == 2 and ": --omega-max: more than" in run.stderr
    assert "with --count" in run.stderr
    symbolic = api.load(examples_dir / "two_beams_symbolic.toml")
    with pytest.raises(ModelError, match=r"with_parameters\(") as info:
        api.solve(symbolic)
    assert "--set" not in str(info.value)
    run = run_cli(["solve", examples_dir / "two_beams_symbolic.toml"])
    assert run.code == 2 and "--set" in run.stderr
    with pytest.raises(ModelError, match="override Q: 'Q' is not a parameter"):
        api.load(examples_dir / "paper_ex1_ff_cc.toml", Q=3)


@pytest.mark.parametrize("kwargs, message", [
    (dict(count=-1), "count: must be a whole number of at least 1, got -1"),
    (dict(count=0), "count: must be a whole number"),
    (dict(count=2.5), "count: must be a whole number"),
    (dict(count=2, omega_max=50), "count: give count or omega_max, not both"),
])
def test_the_api_refuses_what_the_command_line_refuses(examples_dir, kwargs, message):
    from symtmm import api
    from symtmm.errors import ModelError
    with pytest.raises(ModelError, match=message):
        api.solve(api.load(examples_dir / "paper_ex1_ff_cc.toml"), **kwargs)


def test_results_print_as_tables_at_a_prompt(examples_dir):
    from symtmm import api
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml")
    spectrum = api.solve(model, count=2)
    assert repr(spectrum) == spectrum.table()
    modes = api.modes(model, count=1, points=3)
    assert repr(modes).startswith("#     omega [rad/s]")


def test_models_from_plain_dicts_match_the_file(examples_dir):
    import tomllib

    from symtmm import api
    path = examples_dir / "tuned_mass_damper.toml"
    data = tomllib.loads(path.read_text())            # floats, as a script would have them
    from_dict = api.from_dict(data, zeta=0)
    from_file = api.load(path, zeta=0)
    assert [str(e) for e in api.solve(from_dict, count=4)] == \
        [str(e) for e in api.solve(from_file, count=4)]
    from symtmm.errors import ModelError
    with pytest.raises(ModelError, match="oscillator.1..k: expected one value per beam"):
        api.from_dict({**data, "oscillator": [{**data["oscillator"][1], "k": [1, 2, 3]}]})


def test_grid_search_rows_say_their_own_digits(examples_dir):
    """fmin1d backs some eigenvalues with more digits than the fewest (the header's):
    those say how many."""
    run = run_cli(["solve", examples_dir / "paper_ex1_ff_cc.toml", "--count", "4", "--method",
                   "fmin1d", "--json"], limit=60)
    data = json.loads(run.stdout)
    for e in data["eigenvalues"]:
        shown = len(e["imag"].replace(".", "").lstrip("0"))
        assert shown == e.get("digits", data["digits"]), e


def test_a_joint_built_in_python_is_the_files_joint(examples_dir):
    from symtmm import api
    from symtmm.model import Beam, Model
    half = dict(EI="1/2", m="1/2", L="3/5", x0=1, left="free", right="free")
    fork = Model((Beam("trunk", 1, 1, 1, left="clamped", right="free"),
                  Beam("left_branch", **half), Beam("right_branch", **half)),
                 bodies=(api.joint("j", [("trunk", 1), ("left_branch", 1),
                                         ("right_branch", 1)]),))
    from_file = api.load(examples_dir / "fork_tree.toml")
    assert [str(e) for e in api.solve(fork, count=5)] == \
        [str(e) for e in api.solve(from_file, count=5)]
