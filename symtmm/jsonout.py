"""The JSON every command prints: one header, one layout.

Every object begins with the same header (``docs/design.md``, the README)::

    {"symtmm": VERSION, "model": FILE or null, "title": TITLE, "digits": D or null,
     "notes": [...], ...}

``model`` is the model file (null for a model built in Python), ``digits`` the
significant digits every printed number carries (null where the result is exact,
as a closed form), ``notes`` what the command would print beside its table
(search regions, close roots, caveats of a method).

Examples
--------
>>> h = header("beams.toml", "one beam", 15, ["a note"])
>>> list(h), h["model"], h["notes"]
(['symtmm', 'model', 'title', 'digits', 'notes'], 'beams.toml', ['a note'])
"""

from __future__ import annotations

import json

__all__ = ["header", "dumps"]


def header(source: str | None, title: str, digits: int | None, notes=()) -> dict:
    """The header of a command's JSON: the model file (None or "" for none), its title,
    the digits and the notes."""
    from . import __version__
    return {"symtmm": __version__, "model": source or None, "title": title or "",
            "digits": digits, "notes": list(notes)}


def dumps(data: dict) -> str:
    """``data`` as every command prints it: indented by one space per level."""
    return json.dumps(data, indent=1)
