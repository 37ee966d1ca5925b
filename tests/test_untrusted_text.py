"""Text from model files and command lines: made visible on terminals, inert in comments.

:func:`symtmm.text.printable` (terminal) and :func:`symtmm.text.comment_text`
(comments of generated code) are checked on hostile inputs character by
character: what must go, what must stay, and that the result reads back.
"""

from __future__ import annotations

import itertools
import re

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
