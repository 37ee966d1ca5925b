"""Results as rows and columns: CSV files (``--csv FILE``) and pandas frames.

Every result (:class:`~symtmm.results.Spectrum`, :class:`~symtmm.modes.ModeSet`,
:class:`~symtmm.sweep.Sweep`, :class:`~symtmm.scan.Scan`) gives its
``records() -> (columns, rows)``, one row per eigenvalue (per step of a sweep), per
sample point of a mode shape, per frequency of a scan. From them:

* :func:`write_csv`: the rows as they print, every digit kept (eigenvalues as the
  decimal strings of the tables, floats with 17 significant digits);
* :func:`to_frame`: a :class:`pandas.DataFrame` of floats (pandas is optional: ``pip
  install pandas``); the CSV keeps the digits beyond double precision.

Examples
--------
>>> from symtmm.model import Beam, Model
>>> from symtmm.solve import solve
>>> spec = solve(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), count=2,
...              digits=8)
>>> columns, rows = spec.records()
>>> columns
['index', 'real', 'imag', 'multiplicity', 'hz', 'Omega', 'proof']
>>> rows[0][:5]
[1, '0', '9.8696044', 1, '1.5707963']
"""

from __future__ import annotations

import csv
import math

from .errors import ModelError

__all__ = ["write_csv", "to_frame", "FLOAT_DIGITS"]

#: Significant digits of floats in CSV files: enough to read back the same double.
FLOAT_DIGITS = 17


def _cell(value):
    if isinstance(value, float):
        return repr(value) if not math.isfinite(value) else f"{value:.{FLOAT_DIGITS}g}"
    return value


def write_csv(path, columns, rows) -> None:
    """Write ``rows`` under the header ``columns`` to ``path`` (UTF-8, one header line).

    Raises
    ------
    ModelError
        When the file cannot be written (``field`` ``csv``: ``--csv`` on the command line).
    """
    try:
        with open(path, "w", newline="", encoding="utf-8") as fh:
            writer = csv.writer(fh)
            writer.writerow(columns)
            writer.writerows([_cell(v) for v in row] for row in rows)
    except OSError as exc:
        raise ModelError(f"cannot write the table: {exc.strerror or exc}", field="csv",
                         source=str(path)) from None


def to_frame(columns, rows):
    """A :class:`pandas.DataFrame` of the rows, decimal strings read as floats.

    Raises
    ------
    ImportError
        Without pandas, saying how to install it.
    """
    try:
        import pandas as pd
    except ImportError:
        raise ImportError("to_frame() needs pandas: pip install pandas (or use to_csv)") from None
    frame = pd.DataFrame(rows, columns=columns)
    for name in columns:
        if frame[name].dtype == object or pd.api.types.is_string_dtype(frame[name]):
            converted = pd.to_numeric(frame[name], errors="coerce")
            # a text column (proof, beam) stays text; a column of decimal strings is numeric
            if converted.notna().sum() == frame[name].notna().sum():
                frame[name] = converted
    return frame


class Tabular:
    """``to_csv`` and ``to_frame`` for a result that has ``records()``; its ``str`` and
    ``repr`` its text ``table()``."""

    def records(self):  # pragma: no cover - every result defines it
        raise NotImplementedError

    def table(self) -> str:  # pragma: no cover - every result defines it
        raise NotImplementedError

    def __str__(self) -> str:
        return self.table()

    def __repr__(self) -> str:
        # the table, not the fields: what a user at a prompt wants to see
        return self.table()

    def to_csv(self, path) -> None:
        """Write :meth:`records` to ``path`` as CSV (``--csv FILE``)."""
        write_csv(path, *self.records())

    def to_frame(self):
        """:meth:`records` as a :class:`pandas.DataFrame` (needs pandas)."""
        return to_frame(*self.records())
