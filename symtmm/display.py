r"""Tables for notebooks: the HTML and LaTeX forms of a result's rows.

Spectra, mode sets and sweeps show in Jupyter the rows of their text table. The
cells are numbers, but headers carry beam and parameter names from a model file,
which may hold any character; these functions escape every piece of text so a
name is shown as written and never read as markup (``<script>`` in HTML,
``}\href{...}`` in LaTeX).

Examples
--------
>>> print(html_table(["#", "name"], [["1", "a<b"]]))
<table><tr><th>#</th><th>name</th></tr><tr><td>1</td><td>a&lt;b</td></tr></table>
>>> latex_text("beam_1 {x}")
'\\mathrm{beam\\_1\\ \\{x\\}}'
"""

from __future__ import annotations

from html import escape

__all__ = ["text_lines", "html_table", "latex_array", "latex_text"]

# Characters LaTeX (and MathJax) would act on, as the commands that print them.
_LATEX = {"\\": r"\backslash ", "{": r"\{", "}": r"\}", "_": r"\_", "^": r"\hat{}",
          "$": r"\$", "&": r"\&", "%": r"\%", "#": r"\#", "~": r"\sim ", " ": r"\ "}


def text_lines(head, rows) -> list:
    """A plain-text table: the header, a rule, the rows, every column right-aligned.

    Examples
    --------
    >>> for line in text_lines(["#", "omega"], [["1", "9.87"], ["2", "39.5"]]):
    ...     print(line)
    #  omega
    -  -----
    1   9.87
    2   39.5
    """
    widths = [max(len(h), *(len(r[k]) for r in rows)) if rows else len(h)
              for k, h in enumerate(head)]
    lines = ["  ".join(h.rjust(w) for h, w in zip(head, widths)),
             "  ".join("-" * w for w in widths)]
    return lines + ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]


def html_table(head, rows, note: str = "") -> str:
    """An HTML table of text cells, every cell escaped; ``note`` (plain text) below it."""
    out = ["<table>", "<tr>" + "".join(f"<th>{escape(h)}</th>" for h in head) + "</tr>"]
    out += ["<tr>" + "".join(f"<td>{escape(c)}</td>" for c in r) + "</tr>" for r in rows]
    out.append("</table>")
    if note:
        out.append(f"<small>{escape(note)}</small>")
    return "".join(out)


def latex_text(text: str) -> str:
    """``text`` as upright math-mode LaTeX that shows exactly its characters."""
    return r"\mathrm{" + "".join(_LATEX.get(c, c) for c in str(text)) + "}"


def latex_array(cols, rows) -> str:
    """A right-aligned LaTeX array in ``$...$``: ``cols`` are LaTeX already (build
    names into them with :func:`latex_text`), ``rows`` numbers as text."""
    lines = [r"\begin{array}{" + "r" * len(cols) + "}", " & ".join(cols) + r" \\ \hline"]
    lines += [" & ".join(r) + r" \\" for r in rows]
    lines.append(r"\end{array}")
    return "$" + "\n".join(lines) + "$"
