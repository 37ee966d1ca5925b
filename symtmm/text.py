r"""Text from a model file, shown on a terminal or written into generated code.

Titles, names, keys and paths come from files and command lines symtmm does
not control. Shown raw they can move the cursor, recolour or clear a terminal
(escape sequences), split one error message over several lines (newlines) or
fail to print at all (lone surrogates from undecodable file names); written
raw into a comment of generated source they can end the comment and add code.
Two functions make such text harmless and keep it readable:

* :func:`printable`: every character a terminal would act on instead of
  showing becomes a visible escape (``\x1b``, ``\n``, ``\u2028``); the rest
  is unchanged, accents included.
* :func:`comment_text`: printable ASCII on one line that no comment syntax of
  the generated languages (C, Fortran, Octave/MATLAB, Julia, Python) can end
  or reopen.
"""

from __future__ import annotations

import re

__all__ = ["printable", "comment_text"]

# Candidates for escaping: anything outside printable ASCII (decided per character).
_NOT_ASCII_PRINTABLE = re.compile(r"[^\x20-\x7e]")
_NAMED = {"\n": "\\n", "\r": "\\r", "\t": "\\t"}

# Pairs of characters that open, close or redirect a comment somewhere, each kept
# apart by a space (zero-width matches: ``*/*`` becomes ``* / *``):
#   C             ``/*`` ``*/`` (end or nest a block comment), ``??`` (trigraphs:
#                 ``??/`` is a backslash, and gcc -Wall -Werror rejects it)
#   Octave/MATLAB ``%{`` ``%}`` ``#{`` ``#}`` (block comments)
#   Julia         ``#=`` ``=#`` (block comments)
#   editors       ``coding:`` / ``coding=`` (Python's source encoding declaration, read
#                 in the first two lines), ``-*-`` (Emacs file variables), ``vim:``,
#                 ``vi:``, ``ex:`` after a space (Vim modelines)
_PAIRS = re.compile(r"(?<=\*)(?=/)|(?<=/)(?=\*)|(?<=\?)(?=\?)"
                    r"|(?<=[%#])(?=[{}])|(?<=#)(?==)|(?<==)(?=#)"
                    r"|(?<=coding)(?=[:=])|(?<=-)(?=\*-)")
_MODELINE = re.compile(r"(?<!\S)(vim?|ex):")


def _escape(char: str) -> str:
    if char in _NAMED:
        return _NAMED[char]
    code = ord(char)
    if code < 0x100:
        return f"\\x{code:02x}"
    if code < 0x10000:
        return f"\\u{code:04x}"
    return f"\\U{code:08x}"


def printable(text, multiline: bool = False) -> str:
    r"""``text`` with every character a terminal would not simply show made visible.

    Control characters (C0, DEL, C1 such as U+0085), format characters
    (bidirectional overrides, zero-width joiners), line and paragraph
    separators, spaces other than U+0020, unassigned and private-use code
    points and lone surrogates become escapes as in Python: ``\n``, ``\r``,
    ``\t``, ``\x1b``, ``\u2028``, ``\U000e0001``. Other characters, non-ASCII
    letters included, are kept, so the result is one line of the same text.

    Parameters
    ----------
    text : str
        Any text (other objects are converted with ``str``).
    multiline : bool, optional
        Keep newlines and tabs (for tables and JSON); escape them otherwise.

    Returns
    -------
    str

    Examples
    --------
    >>> print(printable("\x1b[2Jmodel\nend"))
    \x1b[2Jmodel\nend
    >>> print(printable("Träger \u2028 C:\\Users\\me"))
    Träger \u2028 C:\Users\me
    >>> printable("a\tb\nc\r", multiline=True)
    'a\tb\nc\\r'
    """
    text = str(text)

    def repl(match):
        char = match.group()
        if (multiline and char in "\n\t") or char.isprintable():
            return char
        return _escape(char)

    return _NOT_ASCII_PRINTABLE.sub(repl, text)


def comment_text(text) -> str:
    r"""``text`` as the payload of a one-line comment in any generated language.

    The result is printable ASCII on a single line: control characters,
    newlines, carriage returns and every non-ASCII character become escapes
    (``\n``, ``\x00``, ``\u2028``), and the character pairs that end or open
    a comment are kept apart by a space: ``*/``, ``/*`` and trigraphs ``??``
    (C), ``%{``, ``%}``, ``#{``, ``#}`` (Octave/MATLAB), ``#=``, ``=#``
    (Julia), and the markers editors and Python read in a file's first lines
    (``coding:``, ``-*-``, ``vim:``). Quotes, backslashes, ``!`` and ``&``
    need nothing: the payload goes into line comments (``#``, ``%``, ``!``)
    or a C block comment, never into a string, and none of these comments
    continues onto the next line.

    Parameters
    ----------
    text : str
        Any text (other objects are converted with ``str``).

    Returns
    -------
    str

    Examples
    --------
    >>> print(comment_text("ok */ int pwn(void); /*"))
    ok * / int pwn(void); / *
    >>> print(comment_text("x\n=# end \u2028 Träger"))
    x\n= # end \u2028 Tr\xe4ger
    >>> comment_text("%}"), comment_text("#{"), comment_text("# -*- coding: latin-1 -*-")
    ('% }', '# {', '# - *- coding : latin-1 - *-')
    """
    text = str(text)
    # every non-ASCII character escaped: compilers and editors disagree on encodings
    ascii_only = _NOT_ASCII_PRINTABLE.sub(lambda m: _escape(m.group()), text)
    return _PAIRS.sub(" ", _MODELINE.sub(r"\1 :", ascii_only))
