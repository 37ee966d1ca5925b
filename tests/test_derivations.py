"""Every script in derivations/ runs and its own assertions hold."""

from __future__ import annotations

import runpy
from pathlib import Path

import pytest

SCRIPTS = sorted((Path(__file__).resolve().parent.parent / "derivations").glob("*.py"))


def test_there_are_derivations():
    names = {p.stem for p in SCRIPTS}
    assert {"euler_bernoulli", "springs", "frequency_equations", "paper_closed_forms"} <= names


@pytest.mark.parametrize("script", SCRIPTS, ids=lambda p: p.stem)
def test_derivation_runs(script, capsys):
    runpy.run_path(str(script), run_name="__main__")
    assert capsys.readouterr().out.strip()
