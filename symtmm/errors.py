"""Exceptions with messages fit for one line on a terminal."""

from __future__ import annotations

from .text import printable


class SymtmmError(Exception):
    """Base class of every error symtmm raises on purpose."""


#: Arguments of the library's functions and the command-line flags that set them.
_FLAGS = {"count": "--count", "omega_max": "--omega-max", "sigma_max": "--sigma-max",
          "omega_min": "--omega-min", "digits": "--digits", "method": "--method",
          "points": "--points", "steps": "--steps", "scheduler": "--scheduler",
          "parameter": "--param", "start": "--from", "stop": "--to"}
#: Fields naming an argument and a name: ``override K`` is ``--set K``.
_FLAG_PREFIXES = {"override": "--set", "symbolic": "--symbolic"}


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

    def __init__(self, message: str, field: str | None = None, source: str | None = None,
                 cli_message: str | None = None):
        self.message = message
        self.field = field
        self.source = source
        self.cli_message = cli_message
        super().__init__(str(self))

    def with_source(self, source: str) -> ModelError:
        """Return the same error attributed to ``source`` (unless it has one)."""
        return self if self.source else ModelError(self.message, self.field, source,
                                                   self.cli_message)

    def for_command_line(self) -> ModelError:
        """The same error in the command line's words: the library names the arguments of
        its functions (``omega_max``, ``override K``), the command line its flags
        (``--omega-max``, ``--set K``).

        Examples
        --------
        >>> str(ModelError("must be positive", field="omega_max").for_command_line())
        '--omega-max: must be positive'
        >>> str(ModelError("not a parameter", field="override K").for_command_line())
        '--set K: not a parameter'
        """
        field = self.field
        if field in _FLAGS:
            field = _FLAGS[field]
        elif field:
            head, _, rest = field.partition(" ")
            if head in _FLAG_PREFIXES and rest:
                field = f"{_FLAG_PREFIXES[head]} {rest}"
        return ModelError(self.cli_message or self.message, field, self.source)

    def __str__(self) -> str:
        # names, keys and paths in the parts come from files: one line, escapes visible
        parts = [p for p in (self.source, self.field) if p]
        return printable(": ".join(parts + [self.message]))


class ComputationError(SymtmmError, RuntimeError):
    """A computation could not deliver what was asked (digits, roots, ...)."""


class OverBudget(ComputationError):
    """A search spent its wall-clock budget (:mod:`symtmm.deadline`).

    ``explained``: whether the line already says what made the search costly."""

    explained = False
