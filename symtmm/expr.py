"""Restricted arithmetic expressions for model files.

Model files may write a numeric field as an expression such as ``"K/2"`` or
``"sqrt(EI/m)/pi**2"``. The text is parsed here, by a small recursive-descent
parser, into an exact SymPy expression. It never reaches ``eval``, ``exec`` or
``sympify``: the only things a model file can produce are numbers, the named
parameters it defines, ``pi``, ``sqrt``, the operators ``+ - * / **`` and
parentheses.

Grammar::

    expr   := term (('+' | '-') term)*
    term   := unary (('*' | '/') unary)*
    unary  := ('+' | '-') unary | power
    power  := atom ('**' unary)?
    atom   := NUMBER | NAME | NAME '(' expr ')' | '(' expr ')'
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from decimal import Decimal, InvalidOperation

import sympy as sp

__all__ = ["parse_expression", "exact_number", "ExpressionError", "parameter_symbol",
           "RESERVED_NAMES"]

#: Longest expression text accepted (guards against pathological input).
MAX_LENGTH = 1000
#: Largest integer exponent accepted in ``a**n`` (guards against 2**10**10).
MAX_EXPONENT = 1000

_TOKEN = re.compile(
    r"\s*(?:(?P<num>(?:\d+\.?\d*|\.\d+)(?:[eE][+-]?\d+)?)"
    r"|(?P<name>[A-Za-z_][A-Za-z_0-9]*)"
    r"|(?P<op>\*\*|[-+*/()]))"
)

_FUNCTIONS: Mapping[str, Callable[[sp.Expr], sp.Expr]] = {"sqrt": sp.sqrt}
_CONSTANTS: Mapping[str, sp.Expr] = {"pi": sp.pi}
#: Names an expression reads as its own constants and functions, never as parameters.
RESERVED_NAMES = frozenset(_FUNCTIONS) | frozenset(_CONSTANTS)


class ExpressionError(ValueError):
    """The text is not a valid restricted expression."""


def parameter_symbol(name: str) -> sp.Symbol:
    """The SymPy symbol standing for a model parameter without a value.

    Parameters are physical quantities of the models symtmm handles
    (stiffnesses, positions, lengths), hence positive, which lets SymPy
    simplify square roots and absolute values.
    """
    return sp.Symbol(name, positive=True)


def exact_number(value) -> sp.Expr:
    """Convert a number from a model file to an exact SymPy number.

    Decimal literals are taken at their written value: ``Decimal("0.3")``
    gives 3/10. Python floats are converted through their shortest repr for
    the same reason (``0.3`` also gives 3/10).

    Examples
    --------
    >>> exact_number(Decimal("0.3"))
    3/10
    >>> exact_number(2)
    2
    >>> exact_number(1e-8)
    1/100000000
    """
    if isinstance(value, bool):
        raise ExpressionError("expected a number, got a boolean")
    if isinstance(value, int):
        return sp.Integer(value)
    if isinstance(value, float):
        value = Decimal(repr(value))
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise ExpressionError(f"{value} is not a finite number")
        return sp.Rational(str(value))
    raise ExpressionError(f"expected a number or an expression, got {type(value).__name__}")


def parse_expression(text: str, resolve: Callable[[str], sp.Expr] | None = None) -> sp.Expr:
    """Parse a restricted arithmetic expression into an exact SymPy expression.

    Parameters
    ----------
    text : str
        The expression, e.g. ``"K/2"``, ``"1e-8"``, ``"sqrt(2)*pi"``.
    resolve : callable, optional
        Maps a name (other than ``pi``) to its value. Without it, or when it
        returns ``None``, a name becomes a positive symbol.

    Returns
    -------
    sympy.Expr
        Exact: decimal literals become rationals.

    Raises
    ------
    ExpressionError
        On any syntax error, unknown function or oversized exponent.

    Examples
    --------
    >>> parse_expression("0.1 + 0.2")
    3/10
    >>> parse_expression("2*K/L**3")
    2*K/L**3
    >>> parse_expression("sqrt(EI/m)", {"EI": 4, "m": 1}.get)
    2
    >>> parse_expression("__import__(os)")
    Traceback (most recent call last):
    ...
    symtmm.expr.ExpressionError: unknown function '__import__'
    """
    if not isinstance(text, str):
        raise ExpressionError("expected a string")
    if len(text) > MAX_LENGTH:
        raise ExpressionError(f"expression longer than {MAX_LENGTH} characters")
    tokens = _tokenize(text)
    parser = _Parser(tokens, resolve)
    result = parser.expr()
    if parser.pos != len(tokens):
        raise ExpressionError(f"unexpected '{tokens[parser.pos][1]}'")
    return result


def _tokenize(text: str) -> list[tuple[str, str]]:
    tokens = []
    pos = 0
    text = text.rstrip()
    while pos < len(text):
        match = _TOKEN.match(text, pos)
        if not match or match.end() == pos:
            bad = text[pos:].strip()[:1]
            raise ExpressionError(f"unexpected character '{bad}'")
        kind = match.lastgroup
        tokens.append((kind, match.group(kind)))
        pos = match.end()
    if not tokens:
        raise ExpressionError("empty expression")
    return tokens


class _Parser:
    def __init__(self, tokens, resolve):
        self.tokens = tokens
        self.pos = 0
        self.resolve = resolve

    def peek(self):
        return self.tokens[self.pos] if self.pos < len(self.tokens) else (None, None)

    def take(self, value=None):
        kind, tok = self.peek()
        if kind is None:
            raise ExpressionError("unexpected end of expression")
        if value is not None and tok != value:
            raise ExpressionError(f"expected '{value}', found '{tok}'")
        self.pos += 1
        return kind, tok

    def expr(self):
        value = self.term()
        while self.peek()[1] in ("+", "-"):
            _, op = self.take()
            rhs = self.term()
            value = value + rhs if op == "+" else value - rhs
        return value

    def term(self):
        value = self.unary()
        while self.peek()[1] in ("*", "/"):
            _, op = self.take()
            rhs = self.unary()
            if op == "/":
                if rhs == 0:
                    raise ExpressionError("division by zero")
                value = value / rhs
            else:
                value = value * rhs
        return value

    def unary(self):
        if self.peek()[1] in ("+", "-"):
            _, op = self.take()
            value = self.unary()
            return -value if op == "-" else value
        return self.power()

    def power(self):
        base = self.atom()
        if self.peek()[1] == "**":
            self.take()
            exponent = self.unary()
            if exponent.is_number and abs(exponent) > MAX_EXPONENT:
                raise ExpressionError(f"exponent larger than {MAX_EXPONENT}")
            if base == 0 and exponent.is_number and exponent.is_negative:
                raise ExpressionError("division by zero")
            return base**exponent
        return base

    def atom(self):
        kind, tok = self.take()
        if kind == "num":
            try:
                return sp.Rational(str(Decimal(tok)))
            except InvalidOperation:  # pragma: no cover - the regex admits only valid numbers
                raise ExpressionError(f"bad number '{tok}'") from None
        if kind == "name":
            if self.peek()[1] == "(":
                if tok not in _FUNCTIONS:
                    raise ExpressionError(f"unknown function '{tok}'")
                self.take("(")
                arg = self.expr()
                self.take(")")
                if tok == "sqrt" and arg.is_number and arg.is_negative:
                    raise ExpressionError("square root of a negative number")
                return _FUNCTIONS[tok](arg)
            if tok in _CONSTANTS:
                return _CONSTANTS[tok]
            if tok in _FUNCTIONS:
                raise ExpressionError(f"'{tok}' needs an argument in parentheses")
            value = self.resolve(tok) if self.resolve else None
            if value is None:
                return parameter_symbol(tok)
            return value if isinstance(value, sp.Basic) else exact_number(value)
        if tok == "(":
            value = self.expr()
            self.take(")")
            return value
        raise ExpressionError(f"unexpected '{tok}'")
