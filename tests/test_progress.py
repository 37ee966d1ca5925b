"""Progress bars: on a terminal for work over a second, never with --json or --quiet,
never when standard error is not a terminal; silent without tqdm."""

from __future__ import annotations

import argparse
import io
import sys

import pytest

from symtmm import api, progress
from symtmm.cli import _progress_wanted


class _Err:
    """What the bars wrote to standard error (pytest's capture holds sys.stderr)."""

    def __init__(self, capsys):
        self._capsys = capsys

    def getvalue(self) -> str:
        return self._capsys.readouterr().err


@pytest.fixture
def captured(monkeypatch, capsys):
    pytest.importorskip("tqdm")
    monkeypatch.setattr(progress, "DELAY", 0.0)      # show at once, however quick
    monkeypatch.setattr(progress, "MININTERVAL", 0.0)   # and every stage
    return _Err(capsys)


def test_solve_derive_and_modes_report_their_stages(captured, examples_dir):
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml")
    with progress.shown(True):
        api.solve(model, count=3)
        api.derive(model)
        api.modes(model, count=2, points=3)
    text = captured.getvalue()
    for stage in ("solve: isolating", "solve: proving the digits", "derive: determinant",
                  "derive: factoring", "mode shapes"):
        assert stage in text, stage


def test_damped_solve_reports_its_stages(captured, examples_dir):
    with progress.shown(True):
        api.solve(api.load(examples_dir / "tuned_mass_damper.toml"), count=2)
    assert "solve: refining and proving" in captured.getvalue()


def test_nothing_when_not_shown(captured, examples_dir):
    with progress.shown(False):
        api.solve(api.load(examples_dir / "paper_ex1_ff_cc.toml"), count=3)
    assert captured.getvalue() == ""


def test_a_sweep_shows_its_steps_not_the_solves_inside(captured, examples_dir):
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml")
    with progress.shown(True):
        api.sweep(model, "K", 50, 100, 2, count=2, jobs=1)
    text = captured.getvalue()
    assert "sweep" in text and "solve:" not in text


def test_without_tqdm_the_work_runs_silently(monkeypatch, capsys, examples_dir):
    monkeypatch.setitem(sys.modules, "tqdm.auto", None)
    with progress.shown(True):
        spec = api.solve(api.load(examples_dir / "paper_ex1_ff_cc.toml"), count=2)
    assert len(spec) == 2 and capsys.readouterr().err == ""


class _Terminal(io.StringIO):
    def isatty(self):
        return True


@pytest.mark.parametrize("flags, terminal, expected", [
    (dict(), True, True),
    (dict(), False, False),
    (dict(json=True), True, False),
    (dict(quiet=True), True, False),
    (dict(progress=True, json=True), False, True),     # --progress forces it
    (dict(progress=False), True, False),
])
def test_the_command_line_decides_once(monkeypatch, flags, terminal, expected):
    monkeypatch.setattr(sys, "stderr", _Terminal() if terminal else io.StringIO())
    args = argparse.Namespace(**{"json": False, "quiet": False, **flags})
    assert _progress_wanted(args) is expected
