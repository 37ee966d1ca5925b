"""Pictures of models and of their mode shapes (symtmm draw)."""

from __future__ import annotations

import numpy as np
import pytest
from cli_contract import assert_contract, run_cli

from symtmm import api
from symtmm.drawing import _GAP, draw_model

pytest.importorskip("matplotlib")


@pytest.mark.parametrize("name", ["paper_ex1_ff_cc", "tuned_mass_damper", "fork_tree",
                                  "rigid_body_on_beam", "point_elements", "closed_loop",
                                  "elastic_supports", "hinge_joint", "paper_ex4_damped"])
def test_every_example_draws(tmp_path, examples_dir, name):
    out = tmp_path / f"{name}.png"
    run = run_cli(["draw", examples_dir / f"{name}.toml", "--plot", out], limit=60)
    assert_contract(run, 60)
    assert run.code == 0 and out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_a_mode_is_drawn_as_its_shape(examples_dir):
    """The beams' lines are the mode's Y, scaled, about their levels; the springs join
    the displaced beams."""
    model = api.load(examples_dir / "paper_ex1_ff_cc.toml")
    mode = api.modes(model, count=3, points=41)[2]
    ax = draw_model(model, mode).axes[0]
    top = max(float(np.max(np.abs(s.Y))) for s in mode.beams.values())
    for level, name in enumerate(["upper", "lower"]):
        shape = mode.beams[name]
        expected = -_GAP * level + shape.Y * (_GAP / 3 / top)
        assert any(len(line.get_ydata()) == 41 and np.allclose(line.get_ydata(), expected)
                   for line in ax.lines), name


def test_springs_and_sprung_masses_are_all_drawn(examples_dir):
    model = api.load(examples_dir / "tuned_mass_damper.toml")
    ax = draw_model(model).axes[0]
    zigzags = [line for line in ax.lines if len(line.get_xdata()) == 15]
    assert len(zigzags) == 3          # the damper's spring, the link's two


def test_animation_and_its_errors(tmp_path, examples_dir):
    path = examples_dir / "tuned_mass_damper.toml"
    gif = tmp_path / "m.gif"
    run = run_cli(["draw", path, "--plot", gif, "--mode", "1", "--animate", "--set", "zeta=0"],
                  limit=90)
    assert run.code == 0 and gif.read_bytes()[:6] in (b"GIF89a", b"GIF87a")
    for args, message in ((["--animate"], "--animate: needs --mode N"),
                          (["--mode", "1", "--animate"], "--plot: an animation is written")):
        run = run_cli(["draw", path, "--plot", tmp_path / "x.png", *args], limit=90)
        assert_contract(run, 90)
        assert run.code == 2 and message in run.stderr, run.stderr
