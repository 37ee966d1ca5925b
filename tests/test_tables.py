"""CSV files (--csv FILE) and pandas frames of every result: the same numbers as the
JSON and tables, every digit kept in the CSV."""

from __future__ import annotations

import csv
import json
import sys

import pytest
from cli_contract import assert_contract, run_cli

from symtmm import api


def _read(path):
    with open(path, newline="", encoding="utf-8") as fh:
        rows = list(csv.reader(fh))
    return rows[0], rows[1:]


@pytest.mark.parametrize("command", [
    ["solve", "--count", "3"],
    ["modes", "--count", "2", "--points", "4"],
    ["sweep", "--param", "f", "--from", "0.9", "--to", "1.1", "--steps", "2", "--count", "2",
     "--set", "zeta=0"],
    ["scan", "--omega-max", "20", "--points", "30", "--no-eigenvalues"],
])
def test_csv_holds_what_the_json_holds(examples_dir, tmp_path, command):
    model = examples_dir / "tuned_mass_damper.toml"
    out = tmp_path / "table.csv"
    run = run_cli([command[0], model, *command[1:], "--json", "--csv", out], limit=60)
    assert_contract(run, 60)
    data = json.loads(run.stdout)
    columns, rows = _read(out)
    if command[0] == "solve":
        assert columns[:5] == ["index", "real", "imag", "multiplicity", "hz"]
        assert [r[1:3] for r in rows] == [[e["real"], e["imag"]] for e in data["eigenvalues"]]
        assert [r[columns.index("zeta")] for r in rows] == [e["zeta"] for e in data["eigenvalues"]]
    elif command[0] == "modes":
        shapes = data["modes"]
        beams = list(shapes[0]["beams"])
        assert len(rows) == len(shapes) * len(beams) * 4
        first = shapes[0]["beams"][beams[0]]
        assert float(rows[0][columns.index("Y_real")]) == first["Y"]["real"][0]
    elif command[0] == "sweep":
        assert columns[0] == "f" and len(rows) == 2 * 2
        assert [r[4] for r in rows] == [e["imag"] for step in data["eigenvalues"] for e in step]
    else:
        assert [float(r[0]) for r in rows] == data["omega"]


def test_the_text_output_says_where_the_table_went(examples_dir, tmp_path):
    out = tmp_path / "s.csv"
    run = run_cli(["solve", examples_dir / "paper_ex1_ff_cc.toml", "--count", "2", "--csv", out])
    assert run.code == 0 and run.stdout.rstrip().endswith(f"table written to {out}")


def test_an_unwritable_csv_is_refused_before_computing(examples_dir, tmp_path):
    run = run_cli(["sweep", examples_dir / "paper_ex1_ff_cc.toml", "--param", "K", "--from", "1",
                   "--to", "2", "--steps", "2", "--csv", tmp_path / "no" / "x.csv"])
    assert_contract(run)
    assert run.code == 2 and "--csv: cannot write the table: no folder" in run.stderr


def test_frames_have_numeric_columns(examples_dir):
    pd = pytest.importorskip("pandas")
    spectrum = api.solve(api.load(examples_dir / "tuned_mass_damper.toml"), count=3)
    frame = spectrum.to_frame()
    assert list(frame.columns) == spectrum.records()[0]
    assert pd.api.types.is_float_dtype(frame["zeta"]) and frame["zeta"].between(0, 1).all()
    assert frame["imag"].tolist() == [float(e.to_dict()["imag"]) for e in spectrum]


def test_without_pandas_to_frame_says_what_to_install(monkeypatch, examples_dir):
    monkeypatch.setitem(sys.modules, "pandas", None)
    spectrum = api.solve(api.load(examples_dir / "paper_ex1_ff_cc.toml"), count=1)
    with pytest.raises(ImportError, match="pip install pandas"):
        spectrum.to_frame()
