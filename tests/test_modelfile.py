"""Model files: exact numbers, expressions, parameters, and every kind of bad input."""

import subprocess
import sys

import pytest
import sympy as sp

from symtmm.cli import main
from symtmm.errors import ModelError
from symtmm.expr import ExpressionError, parse_expression
from symtmm.modelfile import load, loads

GOOD = """
title = "two beams"
[parameters]
K = 100
x1 = 0.3
half = "K/2"
[[beam]]
name = "upper"
EI = 1
m = 1
L = 1
left = "free"
right = "free"
[[beam]]
name = "lower"
EI = "2*sqrt(2)"
m = 1.5
L = 1
x0 = 0
left = "clamped"
right = "clamped"
[[spring]]
between = ["upper", "lower"]
x = "x1"
k = "half"
[[spring]]
between = ["lower", "ground"]
x = "1 - x1"
k = "1e-8"
c = 0
"""


def test_good_file_is_exact():
    model = loads(GOOD).resolved()
    assert model.springs[0].x == sp.Rational(3, 10)
    assert model.springs[0].k == 50
    assert model.springs[1].x == sp.Rational(7, 10)
    assert model.springs[1].k == sp.Rational(1, 10**8)
    assert model.beams[1].EI == 2 * sp.sqrt(2)
    assert model.beams[1].m == sp.Rational(3, 2)
    assert model.title == "two beams"


def test_set_overrides_and_chains_through_parameters():
    model = loads(GOOD, {"K": "3/7"}).resolved()
    assert model.springs[0].k == sp.Rational(3, 14)


def test_parameters_written_in_terms_of_others_follow_them():
    # half = K/2: changing K after loading (a sweep, --symbolic K) must reach half too
    model = loads(GOOD)
    assert model.with_parameters(K=8).resolved().springs[0].k == 4
    K = sp.Symbol("K", positive=True)
    assert model.with_parameters(K=None).resolved().springs[0].k == K / 2


def test_a_circle_built_in_code_is_reported():
    from symtmm.model import Beam, Model
    with pytest.raises(ModelError, match="in a circle"):
        Model((Beam("b", EI="a", m=1, L=1),), parameters={"a": "b", "b": "2*a"})


def test_name_without_value_stays_a_symbol():
    model = loads(GOOD.replace("K = 100\n", ""))
    assert model.free_symbols == ("K",)
    with pytest.raises(ModelError, match="'K' has no value"):
        model.require_numeric()


def test_expression_parser_never_evaluates_code():
    for text in ["__import__(os)", "exec(1)", "lambda: 1", "a.b", "[1]", "1;2", "x if y else z",
                 "open(f)", "2**10**10"]:
        with pytest.raises(ExpressionError):
            parse_expression(text)


def test_expression_arithmetic():
    assert parse_expression("2**-2 * (1 + 0.5)") == sp.Rational(3, 8)
    assert parse_expression("-x**2", {"x": 3}.get) == -9
    assert parse_expression("146.2698/pi**2") == sp.Rational(1462698, 10000) / sp.pi**2


BEAM = '[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = 1\nleft = "pinned"\nright = "pinned"\n'
BAD = {
    "missing_field": ('[[beam]]\nname = "b"\nEI = 1\nm = 1\nleft = "free"\nright = "free"\n',
                      "beam[1]: missing field 'L'"),
    "unknown_field": (BEAM.replace("EI = 1", "EI = 1\nE = 2"), "beam[1].E: unknown field"),
    "unknown_top": ("foo = 1\n" + BEAM, "foo: unknown field"),
    "unknown_beam": (BEAM + '[[spring]]\nbetween = ["b", "c"]\nx = 0.5\nk = 1\n',
                     "spring[1].between: unknown beam 'c'"),
    "outside": (BEAM + '[[spring]]\nbetween = ["b", "ground"]\nx = 1.5\nk = 1\n',
                "spring[1].x: x = 3/2 lies outside beam 'b'"),
    "zero_EI": (BEAM.replace("EI = 1", "EI = 0"), "beam[1] (b).EI: must be positive"),
    "negative_m": (BEAM.replace("m = 1", "m = -2"), "beam[1] (b).m: must be positive"),
    "negative_L": (BEAM.replace("L = 1", 'L = "1 - 2"'), "beam[1] (b).L: must be positive"),
    "bad_bc": (BEAM.replace('left = "pinned"', 'left = "hinged"'),
               "beam[1] (b).left: unknown boundary condition 'hinged'"),
    "bad_expr": (BEAM.replace("EI = 1", 'EI = "2 *"'), "beam[1] (b).EI: unexpected end"),
    "bad_char": (BEAM.replace("EI = 1", 'EI = "os.system(1)"'), "beam[1] (b).EI: unexpected"),
    "bool": (BEAM.replace("EI = 1", "EI = true"), "beam[1] (b).EI: expected a number"),
    "not_toml": ("[[beam]\nname=", "not valid TOML"),
    "duplicate": (BEAM + BEAM, "duplicate beam name 'b'"),
    "self_spring": (BEAM + '[[spring]]\nbetween = ["b", "b"]\nx = 0.5\nk = 1\n',
                    "spring[1].between: a spring must join two different beams"),
    "negative_k": (BEAM + '[[spring]]\nbetween = ["b", "ground"]\nx = 0.5\nk = -1\n',
                   "spring[1].k: must not be negative"),
    "between_shape": (BEAM + '[[spring]]\nbetween = "b"\nx = 0.5\nk = 1\n',
                      "spring[1].between: expected two names"),
    "no_beam": ('title = "x"\n', "beam: missing field"),
    "cycle": ("[parameters]\na = \"b\"\nb = \"a\"\n" + BEAM, "in a circle"),
    "unbound": (BEAM.replace("EI = 1", 'EI = "E0"'), "'E0' has no value"),
    # beam theories
    "bad_theory": (BEAM.replace("EI = 1", 'EI = 1\ntheory = "bernoulli"'),
                   "beam[1] (b).theory: unknown theory 'bernoulli'"),
    "rayleigh_without_rhoI": (BEAM.replace("EI = 1", 'EI = 1\ntheory = "rayleigh"'),
                              "beam[1] (b): missing field 'rhoI'"),
    "timoshenko_without_kGA": (BEAM.replace("EI = 1", 'EI = 1\ntheory = "timoshenko"\nrhoI = 0.01'),
                               "beam[1] (b): missing field 'kGA'"),
    "kGA_on_eb": (BEAM.replace("EI = 1", "EI = 1\nkGA = 100"),
                  "beam[1] (b).kGA: a shear stiffness needs theory"),
    "rhoI_on_eb": (BEAM.replace("EI = 1", "EI = 1\nrhoI = 0.1"),
                   "beam[1] (b).rhoI: rotary inertia needs theory"),
    "negative_rhoI": (BEAM.replace("EI = 1", 'EI = 1\ntheory = "rayleigh"\nrhoI = -1'),
                      "beam[1] (b).rhoI: must not be negative"),
    "zero_kGA": (BEAM.replace("EI = 1", 'EI = 1\ntheory = "timoshenko"\nrhoI = 0\nkGA = 0'),
                 "beam[1] (b).kGA: must be positive"),
    "shear_buckling": (BEAM.replace("EI = 1", 'EI = 1\ntheory = "timoshenko"\nrhoI = 0\n'
                                    'kGA = 10\nN = -10'), "beam[1] (b).N: the axial compression"),
    # rigid bodies and joints
    "rigid_bad_point": (BEAM + '[[rigid]]\nattach = ["b:0.5"]\nM = 1\n',
                        "rigid[1].attach: 'b:0.5' is not a point"),
    "rigid_unknown_beam": (BEAM + '[[rigid]]\nattach = ["c@0.5"]\n',
                           "rigid[1].attach: unknown beam 'c'"),
    "rigid_outside": (BEAM + '[[rigid]]\nattach = ["b@2"]\n',
                      "rigid[1].attach: x = 2 lies outside beam 'b'"),
    "rigid_hinged_not_attached": (BEAM + '[[rigid]]\nattach = ["b@0.5"]\nhinged = ["b@0.6"]\n',
                                  "rigid[1].hinged: 'b@0.6' is not one of the attach points"),
    "rigid_twice": (BEAM + '[[rigid]]\nattach = ["b@0.5", "b@0.5"]\n',
                    "rigid[1].attach: attached twice to beam 'b'"),
    "rigid_negative_M": (BEAM + '[[rigid]]\nattach = ["b@0.5"]\nM = -1\n',
                         "rigid[1].M: must not be negative"),
    "rigid_no_points": (BEAM + '[[rigid]]\nattach = []\n', "rigid[1].attach: expected a list"),
    "joint_apart": (BEAM + BEAM.replace('"b"', '"c"') + '[[joint]]\nends = ["b.left", "c.right"]\n',
                    "joint[1].ends: the ends of a joint must meet at one x"),
    "joint_kind": (BEAM + BEAM.replace('"b"', '"c"') + '[[joint]]\nends = ["b.right", "c.right"]\n'
                   'kind = "weld"\n', "joint[1].kind: unknown kind 'weld'"),
    "joint_not_list": (BEAM + '[[joint]]\nends = "b.right"\n', "joint[1].ends: expected a list"),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_input_gives_one_line_and_exit_2(tmp_path, capsys, case):
    text, expected = BAD[case]
    path = tmp_path / f"{case}.toml"
    path.write_text(text)
    code = main(["solve", str(path), "--count", "1"])
    out, err = capsys.readouterr()
    assert code == 2
    assert out == ""
    lines = err.strip().splitlines()
    assert len(lines) == 1, err
    assert str(path) in lines[0]
    assert expected in lines[0], lines[0]
    assert "Traceback" not in err


@pytest.mark.parametrize("argv,expected", [
    (["solve", "{dir}/missing.toml"], "cannot read the file"),
    (["solve", "{good}", "--set", "K"], "--set expects NAME=VALUE"),
    (["solve", "{good}", "--set", "Q=1"], "'Q' is not a parameter"),
    (["solve", "{good}", "--set", "K=1/0"], "division by zero"),
    (["solve", "{good}", "--count", "0"], "must be at least 1"),
    (["solve", "{good}", "--count", "x"], "expected a whole number"),
    (["solve", "{good}", "--method", "nope"], "unknown method 'nope'"),
    (["solve", "{good}", "--count", "2", "--omega-max", "3"], "not allowed with"),
])
def test_bad_command_lines(tmp_path, capsys, argv, expected):
    good = tmp_path / "good.toml"
    good.write_text(GOOD)
    argv = [a.format(dir=tmp_path, good=good) for a in argv]
    try:
        code = main(argv)
    except SystemExit as exc:  # argparse's own errors
        code = exc.code
    err = capsys.readouterr().err
    assert code == 2
    assert len(err.strip().splitlines()) == 1, err
    assert expected in err
    assert "Traceback" not in err


def test_directory_and_binary_files(tmp_path, capsys):
    assert main(["solve", str(tmp_path)]) == 2
    binary = tmp_path / "b.toml"
    binary.write_bytes(b"\xff\xfe\x00")
    assert main(["solve", str(binary)]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 2 and "Traceback" not in err


def test_load_reports_the_file(tmp_path):
    path = tmp_path / "m.toml"
    path.write_text(BAD["zero_EI"][0])
    with pytest.raises(ModelError) as info:
        load(path)
    assert str(info.value).startswith(str(path))


def test_python_m_symtmm_is_the_same_command(tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(BAD["bad_bc"][0])
    proc = subprocess.run([sys.executable, "-m", "symtmm", "solve", str(path)],
                          capture_output=True, text=True, check=False)
    assert proc.returncode == 2
    assert proc.stderr.count("\n") == 1 and "unknown boundary condition" in proc.stderr


def test_models_with_parameters_pickle(examples_dir):
    """Sweeps send models to other processes."""
    import pickle

    model = load(examples_dir / "paper_ex1_ff_cc.toml")
    again = pickle.loads(pickle.dumps(model))
    assert again == model and again.resolved().springs[0].k == 100


def test_a_position_just_past_its_beam_says_how_far(tmp_path):
    # (rounded to 6 digits x reads as the end itself: the distance tells why it is out)
    path = tmp_path / "m.toml"
    path.write_text('[[beam]]\nname = "b"\nEI = 1\nm = 1\nL = "53/100"\nx0 = "17/50"\n'
                    'left = "pinned"\nright = "pinned"\n\n[[spring]]\n'
                    'between = ["b", "ground"]\nx = "0.87 + 1e-16"\nk = 1\n')
    with pytest.raises(ModelError, match=r"lies outside beam 'b' \[17/50, 87/100\], "
                                         r"1\.00000e-16 beyond its end"):
        load(path)


def test_model_hash_is_kept_and_not_pickled(examples_dir):
    """A model keys the caches of plans and tables; its hash is taken once, equal models
    hash alike, and an unpickled model (another process: another hash of its strings)
    takes its own rather than the one it was pickled with."""
    import pickle

    a = load(examples_dir / "paper_ex1_ff_cc.toml")
    b = load(examples_dir / "paper_ex1_ff_cc.toml")
    assert a == b and a is not b and hash(a) == hash(b)
    assert "_hash" not in pickle.loads(pickle.dumps(a)).__dict__
    code = ("import pickle, sys; m = pickle.loads(sys.stdin.buffer.read()); "
            "import dataclasses; print(hash(m) == hash(dataclasses.replace(m)))")
    out = subprocess.run([sys.executable, "-c", code], input=pickle.dumps(a),
                         capture_output=True, check=True)
    assert out.stdout.strip() == b"True"
