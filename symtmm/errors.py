"""Exceptions with messages fit for one line on a terminal."""

from __future__ import annotations

from .text import printable


class SymtmmError(Exception):
    """Base class of every error symtmm raises on purpose."""


class ModelError(SymtmmError, ValueError):
    """A model (file, field or value) is invalid.

    Parameters
    ----------
    message : str
        What is wrong.
    field : str, optional
        The field concerned, written as in the model file (``beam[2].EI``).
    source : str, optional
        The file (or other source) the model came from.

    Examples
    --------
    >>> str(ModelError("must be positive", field="beam[1].EI", source="m.toml"))
    'm.toml: beam[1].EI: must be positive'
    >>> print(ModelError("unknown field 'a\\nb'", field="beam[1]"))
    beam[1]: unknown field 'a\\nb'
    """

    def __init__(self, message: str, field: str | None = None, source: str | None = None):
        self.message = message
        self.field = field
        self.source = source
        super().__init__(str(self))

    def with_source(self, source: str) -> ModelError:
        """Return the same error attributed to ``source`` (unless it has one)."""
        return self if self.source else ModelError(self.message, self.field, source)

    def __str__(self) -> str:
        # names, keys and paths in the parts come from files: one line, escapes visible
        parts = [p for p in (self.source, self.field) if p]
        return printable(": ".join(parts + [self.message]))


class ComputationError(SymtmmError, RuntimeError):
    """A computation could not deliver what was asked (digits, roots, ...)."""
