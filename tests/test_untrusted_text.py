"""Text from model files and command lines: made visible on terminals, inert in comments.

:func:`symtmm.text.printable` (terminal) and :func:`symtmm.text.comment_text`
(comments of generated code) are checked on hostile inputs character by
character: what must go, what must stay, and that the result reads back.
"""

from __future__ import annotations

import itertools
import re
import subprocess
import sys

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from symtmm.text import comment_text, printable

# Each entry: text that would act on a terminal or on a parser if left raw.
HOSTILE = {
    "ansi colour": "\x1b[31mred\x1b[0m",
    "clear screen": "\x1b[2J\x1b[H",
    "osc title": "\x1b]0;owned\x07",
    "c1 csi": "\x9b31m",
    "newline": "line one\nline two",
    "carriage return": "shown\rhidden",
    "crlf": "a\r\nb",
    "nul": "a\x00b",
    "backspace": "abc\x08\x08\x08xyz",
    "del": "a\x7fb",
    "nel": "a\x85b",
    "line separator": "a\u2028b",
    "paragraph separator": "a\u2029b",
    "bidi override": "abc\u202edcba",
    "zero width": "a\u200bb\u200db",
    "bom": "\ufeffa",
    "tag character": "a\U000e0041b",
    "private use": "a\ue000b",
    "lone surrogate": "a\udcffb",
    "vertical tab": "a\x0bb\x0cc",
    "nbsp": "a\xa0b",
}


def _is_terminal_safe(text: str, multiline: bool) -> bool:
    return all(ch.isprintable() or (multiline and ch in "\n\t") for ch in text)


@pytest.mark.parametrize("name", list(HOSTILE))
def test_printable_leaves_nothing_a_terminal_acts_on(name):
    text = HOSTILE[name]
    out = printable(text)
    assert _is_terminal_safe(out, multiline=False), ascii(out)
    assert "\n" not in out and "\r" not in out
    out.encode("utf-8")                     # a lone surrogate would fail here
    assert _is_terminal_safe(printable(text, multiline=True), multiline=True)


def test_printable_escapes_are_visible_and_readable():
    assert printable("\x1b[31mred") == "\\x1b[31mred"
    assert printable("a\nb\rc\td") == "a\\nb\\rc\\td"
    assert printable("a\u2028b\x85c\x00") == "a\\u2028b\\x85c\\x00"
    assert printable("a\U000e0041") == "a\\U000e0041"
    assert printable("a\nb\tc\rd", multiline=True) == "a\nb\tc\\rd"


def test_printable_keeps_ordinary_text():
    for text in ("Träger auf Federn", "Δ(λ) = 0", "C:\\Users\\me", 'say "hi" */ #= %}',
                 "naïve 日本語", ""):
        assert printable(text) == text


def test_printable_is_idempotent():
    for text in HOSTILE.values():
        once = printable(text)
        assert printable(once) == once


# --- comment payloads -----------------------------------------------------------------

# Every sequence that ends, opens or redirects a comment in one of the languages.
COMMENT_BREAKERS = ["*/", "/*", "??/", "??=", "%{", "%}", "#{", "#}", "#=", "=#",
                    "coding:", "coding=", "-*-", " vim:", " vi:", " ex:"]

COMMENT_HOSTILE = dict(HOSTILE, **{
    "c breakout": "ok */ int symtmm_pwn(void){return 42;} /*",
    "c nested": "*/*/*//**/",
    "python docstring": 'x """ import os; os.system("id") """',
    "python single": "x ''' import os ''' ",
    "backslashes": "C:\\Users\\me\\",
    "octave block": "%}\nsystem('id')\n%{",
    "fortran": "! comment & \nend subroutine symtmm_delta\nmodule evil",
    "julia": "=# run(`id`) #=",
    "cookie": "# -*- coding: utf-7 -*- +AAo-import os",
    "vim": "vim: set ft=c: vi:x ex:y",
    "trigraph tail": "ends with ??/",
})


@pytest.mark.parametrize("name", list(COMMENT_HOSTILE))
def test_comment_text_is_inert_printable_ascii(name):
    out = comment_text(COMMENT_HOSTILE[name])
    assert re.fullmatch(r"[\x20-\x7e]*", out), ascii(out)
    for seq in COMMENT_BREAKERS:
        assert seq not in out, (seq, out)
    assert re.search(r"(?<!\S)(vim?|ex):", out) is None


def test_comment_text_breaks_every_pair_however_they_overlap():
    # every string of comment-relevant characters up to length 4
    alphabet = "*/?%#{}=-"
    for n in range(2, 5):
        for chars in itertools.product(alphabet, repeat=n):
            out = comment_text("".join(chars))
            for seq in ("*/", "/*", "??", "%{", "%}", "#{", "#}", "#=", "=#", "-*-"):
                assert seq not in out, ("".join(chars), out)


def test_comment_text_keeps_ordinary_text():
    for text in ("Euler-Bernoulli beam, K = 100, x1 = 3/10", "C:\\Users\\me", "a*b / c",
                 "x**2 + 1", 'quotes " and \' stay', "Wikipedia: example"):
        assert comment_text(text) == text


def test_comment_text_escapes_every_non_ascii_character():
    out = comment_text("Träger \u2028 \u0085 日本")
    assert out == "Tr\\xe4ger \\u2028 \\x85 \\u65e5\\u672c"


@settings(max_examples=300, deadline=None)
@given(st.text(alphabet=st.characters(exclude_categories=()), max_size=40))
def test_any_text_becomes_safe(text):
    """Arbitrary code points, surrogates and controls included, in both functions."""
    line = printable(text)
    assert _is_terminal_safe(line, multiline=False)
    line.encode("utf-8")
    out = comment_text(text)
    assert re.fullmatch(r"[\x20-\x7e]*", out)
    for seq in COMMENT_BREAKERS:
        assert seq not in out


# --- strings given to the Python API ---------------------------------------------------


def _never_sympify(monkeypatch):
    """Make any sympify of a string fail loudly (sympify hands strings to parse_expr)."""
    from sympy.parsing import sympy_parser

    def refuse(*args, **kwargs):
        raise AssertionError(f"a string reached sympify: {args[:1]!r}")

    monkeypatch.setattr(sympy_parser, "parse_expr", refuse)


def _beam_model(**parameters):
    from symtmm.model import Beam, Model

    return Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),),
                 parameters=parameters or {"K": 3, "k": "2*K"})


@pytest.mark.parametrize("text", ["__import__('os').system('touch symtmm_payload_ran')",
                                  "__import__(os)", "lambda: 1", "K.__class__", "open('x')",
                                  "1 if K else 2", "[K]", "K; K", "K\n+1e400**1e400"])
def test_model_value_reads_strings_with_the_restricted_parser(text, tmp_path, monkeypatch):
    from symtmm.errors import ModelError

    monkeypatch.chdir(tmp_path)
    _never_sympify(monkeypatch)
    model = _beam_model()
    with pytest.raises(ModelError) as info:
        model.value(text)
    assert "\n" not in str(info.value)
    assert not (tmp_path / "symtmm_payload_ran").exists()


def test_model_value_of_strings_and_numbers_is_exact(monkeypatch):
    import sympy as sp

    from symtmm.errors import ModelError

    _never_sympify(monkeypatch)
    model = _beam_model()
    assert model.value("k/4 + 0.5") == 2
    assert model.value("sqrt(K**2)*pi") == 3 * sp.pi
    assert model.value(0.3) == sp.Rational(3, 10)
    assert model.value(7) == 7
    with pytest.raises(ModelError):
        model.value(True)
    with pytest.raises(ModelError):
        model.value(object())


def test_mode_coordinates_given_as_strings_never_reach_sympify(monkeypatch, tmp_path):
    from symtmm.errors import ModelError
    from symtmm.modes import evaluate_mode, shapes_at
    from symtmm.solve import solve

    model = _beam_model(K=1)
    (shape,) = shapes_at(model, solve(model, count=1)[0], points=3)
    monkeypatch.chdir(tmp_path)
    _never_sympify(monkeypatch)
    exact = evaluate_mode(model, shape, "b", ["1/4"])
    assert exact[0, 0] == pytest.approx(evaluate_mode(model, shape, "b", [0.25])[0, 0])
    with pytest.raises(ModelError):
        evaluate_mode(model, shape, "b", ["__import__('os').system('touch symtmm_payload_ran')"])
    assert not (tmp_path / "symtmm_payload_ran").exists()


# --- names in models -------------------------------------------------------------------


@pytest.mark.parametrize("kind", ["parameter", "beam", "body"])
def test_a_name_ending_in_a_newline_is_invalid(kind):
    """A name matched with "$" could end in a newline and split messages in two."""
    from symtmm.errors import ModelError
    from symtmm.model import Attachment, Beam, RigidBody

    with pytest.raises(ModelError) as info:
        if kind == "parameter":
            _beam_model(**{"K\n": 1})
        elif kind == "beam":
            Beam("a\n", EI=1, m=1, L=1)
        else:
            RigidBody("r\n", (Attachment("a", 0),))
    assert "\n" not in str(info.value) and "\\n" in str(info.value)


@pytest.mark.parametrize("name", ["pi", "sqrt"])
def test_parameters_cannot_take_the_names_expressions_reserve(name):
    """k = "pi" means pi: a parameter called pi would be silently ignored."""
    from symtmm.errors import ModelError
    from symtmm.modelfile import loads

    text = (f"[parameters]\n{name} = 3\n[[beam]]\nname = 'a'\nEI = 1\nm = 1\nL = 1\n"
            "left = 'pinned'\nright = 'pinned'\n")
    with pytest.raises(ModelError, match=f"parameters.{name}: '{name}' means {name}"):
        loads(text, source="m.toml")


# --- the terminal ----------------------------------------------------------------------

ANSI_TITLE = "two beams \x1b[2J\x1b[31mRED\x1b]0;pwned\x07\nfake line\r\u2028end"
ANSI_TITLE_TOML = ('"two beams \\u001b[2J\\u001b[31mRED\\u001b]0;pwned\\u0007\\nfake line'
                   '\\r\\u2028end"')

MODEL_TOML = """title = TITLE
[parameters]
K = 10
[[beam]]
name = "a"
EI = 1
m = 1
L = 1
left = "pinned"
right = "pinned"
[[spring]]
between = ["a", "ground"]
x = 0.5
k = "K"
"""

COMMANDS = {
    "solve": ["solve", "MODEL", "--count", "2"],
    "solve-json": ["solve", "MODEL", "--count", "1", "--json"],
    "derive": ["derive", "MODEL"],
    "modes": ["modes", "MODEL", "--count", "1", "--points", "3"],
    "scan": ["scan", "MODEL", "--omega-max", "5", "--points", "20", "--no-eigenvalues"],
    "sweep": ["sweep", "MODEL", "--param", "K", "--from", "1", "--to", "2", "--steps", "2",
              "--count", "1", "--jobs", "1", "--no-progress"],
}


def _terminal_safe(out: str) -> bool:
    return all(ch.isprintable() or ch == "\n" for ch in out)


@pytest.fixture
def ansi_model(tmp_path):
    path = tmp_path / "ansi.toml"
    path.write_text(MODEL_TOML.replace("TITLE", ANSI_TITLE_TOML), encoding="utf-8")
    return str(path)


@pytest.mark.parametrize("command", list(COMMANDS))
def test_every_command_prints_a_hostile_title_as_one_escaped_line(command, ansi_model, capsys):
    from symtmm.cli import main

    argv = [ansi_model if a == "MODEL" else a for a in COMMANDS[command]]
    assert main(argv) == 0
    out, err = capsys.readouterr()
    assert _terminal_safe(out) and _terminal_safe(err), ascii(out)
    if command.endswith("json"):
        import json

        assert json.loads(out)["model"] == ansi_model        # JSON keeps the data exactly
    else:
        assert out.split("\n")[0] == printable(ANSI_TITLE)
        assert "fake line" not in out.split("\n")[1]


def test_solve_title_through_the_command_line(ansi_model):
    proc = subprocess.run([sys.executable, "-m", "symtmm", "solve", ansi_model, "--count", "2"],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 0, proc.stderr
    assert "\x1b" not in proc.stdout and "\r" not in proc.stdout
    assert proc.stdout.split("\n")[0] == (
        "two beams \\x1b[2J\\x1b[31mRED\\x1b]0;pwned\\x07\\nfake line\\r\\u2028end")


BAD_INPUTS = {
    "beam name with a newline": MODEL_TOML.replace('name = "a"', 'name = "a\\nb"'),
    "key with a newline and escapes": MODEL_TOML + '"bad\\nkey\\u001b[2J" = 1\n',
    "parameter name with a newline": MODEL_TOML.replace("K = 10", '"K\\n\\u001b[31m" = 10'),
    "spring beam with a newline": MODEL_TOML.replace('["a", "ground"]', '["a\\n\\r", "ground"]'),
    "value with a newline": MODEL_TOML.replace("K = 10", 'K = "1 +\\n\\u001b[2J"'),
    "boundary with escapes": MODEL_TOML.replace('left = "pinned"', 'left = "\\u001b[2Jx\\ny"'),
}


@pytest.mark.parametrize("case", list(BAD_INPUTS))
def test_bad_input_gives_one_escaped_line_and_exit_code_2(case, tmp_path):
    path = tmp_path / "bad.toml"
    path.write_text(BAD_INPUTS[case].replace("TITLE", '"t"'), encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "symtmm", "solve", str(path)],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.count("\n") == 1 and proc.stderr.endswith("\n"), proc.stderr
    assert _terminal_safe(proc.stderr) and "Traceback" not in proc.stderr
    assert proc.stderr.startswith(f"symtmm: {path}: ")


def test_bad_input_in_process_is_one_line(tmp_path, capsys):
    from symtmm.cli import main

    path = tmp_path / "bad.toml"
    path.write_text(BAD_INPUTS["beam name with a newline"].replace("TITLE", '"t"'))
    assert main(["solve", str(path)]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.count("\n") == 1
    assert "invalid name 'a\\nb'" in err


@pytest.mark.parametrize("argv", [
    ["solve", "MODEL", "--set", "x\x1b[2J\ny=1"],
    ["solve", "MODEL", "--method", "f\x1b[31m\nmin"],
    ["codegen", "MODEL", "--lang", "c\x1b[2J\nx"],
    ["solve", "MODEL", "--count", "\x1b[2J\n3"],
    ["solve", "no\nsuch\x1b[2J.toml"],
    ["sweep", "MODEL", "--param", "K\x1b[2J\nx", "--from", "1", "--to", "2", "--steps", "2"],
])
def test_command_line_arguments_are_escaped_in_errors(argv, ansi_model):
    argv = [ansi_model if a == "MODEL" else a for a in argv]
    proc = subprocess.run([sys.executable, "-m", "symtmm", *argv],
                          check=False, capture_output=True, text=True)
    assert proc.returncode == 2, proc.stderr
    assert proc.stderr.count("\n") == 1, proc.stderr
    assert _terminal_safe(proc.stderr) and "\\x1b" in proc.stderr


def test_standard_output_is_filtered_while_a_command_runs(capsys):
    """The filter itself: whatever a command prints, only newlines and tabs pass raw."""
    import io

    from symtmm.cli import _PrintableStream

    buffer = io.StringIO()
    stream = _PrintableStream(buffer)
    print("row\x1b[2J\tcell\r\u2028", file=stream)
    assert buffer.getvalue() == "row\\x1b[2J\tcell\\r\\u2028\n"
    ascii_out = io.TextIOWrapper(io.BytesIO(), encoding="ascii")
    _PrintableStream(ascii_out).write("Träger")       # no UnicodeEncodeError
    ascii_out.flush()
    assert ascii_out.buffer.getvalue() == b"Tr\\xe4ger"
