"""`symtmm solve`: the JSON contract and the readable table, on the paper's examples."""

import json
from decimal import Decimal

import mpmath
import pytest

from symtmm.cli import main


def _run(capsys, *argv):
    assert main(list(argv)) == 0
    return capsys.readouterr().out


def test_example_2_json_contract(examples_dir, capsys):
    path = str(examples_dir / "paper_ex2_three_pp.toml")
    data = json.loads(_run(capsys, "solve", path, "--count", "12", "--json", "--digits", "25"))
    assert data["model"] == path
    assert data["digits"] == 25
    assert set(data["stats"]) >= {"evaluations", "seconds", "method"}
    assert data["stats"]["evaluations"] > 0 and data["stats"]["method"] == "default"
    eig = data["eigenvalues"]
    assert [e["multiplicity"] for e in eig] == [3, 3, 3, 3]
    with mpmath.workdps(40):
        for n, e in enumerate(eig, 1):
            assert e["real"] == "0"
            digits = len(e["imag"].replace(".", "").lstrip("0"))
            assert digits >= 25
            exact = (n * mpmath.pi) ** 2           # EI = m = L = 1: omega = (n pi)^2
            assert abs(mpmath.mpf(e["imag"]) - exact) < mpmath.mpf(10) ** -22


def test_omega_max_and_table(examples_dir, capsys):
    path = str(examples_dir / "paper_ex1_ff_cc.toml")
    out = _run(capsys, "solve", path, "--omega-max", "100")
    lines = out.splitlines()
    assert lines[0].startswith("free-free over clamped-clamped")
    assert "omega [rad/s]" in lines[1] and "Omega (beam upper)" in lines[1]
    rows = [line.split() for line in lines[3:] if len(line.split()) == 4]
    omegas = [Decimal(r[1]) for r in rows]
    assert omegas == sorted(omegas) and all(0 < w <= 100 for w in omegas)
    assert len(rows) == 6                       # Omega < 10: 2.98, 3.25, 4.73, 5.44, 7.85, 8.24


def test_set_changes_the_answer(examples_dir, capsys):
    path = str(examples_dir / "paper_ex1_ff_cc.toml")
    a = json.loads(_run(capsys, "solve", path, "--count", "3", "--json"))
    b = json.loads(_run(capsys, "solve", path, "--count", "3", "--json", "--set", "K=1000"))
    assert a["eigenvalues"][0]["imag"] != b["eigenvalues"][0]["imag"]


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc.toml", "paper_ex2_three_pp.toml",
                                  "paper_ex3_three_pp_coupled.toml"])
def test_every_example_loads_and_solves(examples_dir, capsys, name):
    data = json.loads(_run(capsys, "solve", str(examples_dir / name), "--count", "4",
                           "--json", "--digits", "10"))
    assert sum(e["multiplicity"] for e in data["eigenvalues"]) >= 4


def test_hz_column_every_digit_right(tmp_path):
    """solve --hz of a clamped-clamped beam: f = beta**2 / 2 pi with cos(beta) cosh(beta) = 1
    (EI = m = L = 1), the closed form's roots polished at 40 digits."""
    import mpmath
    from cli_contract import run_cli
    path = tmp_path / "cc.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nleft = "clamped"\n'
                    'right = "clamped"\n')
    run = run_cli(["solve", path, "--count", "4", "--hz"])
    assert run.code == 0
    lines = run.stdout.splitlines()
    assert lines[0].split()[3:5] == ["f", "[Hz]"]
    printed = [line.split()[2] for line in lines[2:6]]
    with mpmath.workdps(40):
        for n, text in enumerate(printed, 1):
            beta = mpmath.findroot(lambda b: mpmath.cos(b) * mpmath.cosh(b) - 1,
                                   (n + mpmath.mpf(1) / 2) * mpmath.pi)
            digits = len(text.replace(".", "").lstrip("0"))
            assert text == mpmath.nstr(beta**2 / (2 * mpmath.pi), digits, strip_zeros=False)


def _documented_solves():
    """The ``symtmm solve examples/...`` commands the examples' headers tell a reader to run."""
    import re
    from pathlib import Path
    here = Path(__file__).resolve().parent.parent / "examples"
    found = []
    for path in sorted(here.glob("*.toml")):
        for line in path.read_text().splitlines():
            if not line.startswith("#"):
                continue
            for match in re.finditer(r"symtmm (solve examples/\S+\.toml(?: --[-\w]+ \S+)*)", line):
                found.append(match.group(1).split())
    return found


@pytest.mark.parametrize("argv", _documented_solves(), ids=" ".join)
def test_every_documented_example_command_solves(argv):
    """Each ``Solve with:`` line of an example's header runs as printed: exit 0, the table,
    nothing on stderr (the double cross's ``--count 16`` once failed on its five-fold
    roots, where the files' own tests ran ``--count 2``)."""
    from pathlib import Path

    from cli_contract import contract_violations, run_cli
    root = Path(__file__).resolve().parent.parent
    argv = [argv[0], str(root / argv[1])] + argv[2:]
    run = run_cli(argv, limit=60)
    assert run.code == 0 and not contract_violations(run, 60), (run.stderr, run.warnings)
    assert "eigenvalue(s)" in run.stdout
