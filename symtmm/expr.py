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

Limits (:mod:`symtmm.limits`): an expression is at most 1000 characters long and
nests parentheses, signs, powers and functions at most 32 deep; every number in
it, written or computed on the way, lies within ``10**-300 .. 10**300``; an
integer exponent is at most 1000. Powers are checked before they are built, so
``((2**999)**999)**999`` is refused at once instead of computed. Values given
to parameters later go through :func:`substitute`, which checks the same way
(a parameter used as an exponent: ``e = "10**9"``, ``"2**e"``).
"""

from __future__ import annotations

import math
import re
from collections.abc import Callable, Mapping
from decimal import Decimal, InvalidOperation

import mpmath
import sympy as sp

from .limits import MAX_DECADES, MAX_EXPONENT, MAX_EXPRESSION_LENGTH, MAX_NESTING

__all__ = ["parse_expression", "exact_number", "ExpressionError", "parameter_symbol",
           "RESERVED_NAMES", "substitute", "decades", "tree_depth"]

#: Longest expression text accepted (see :mod:`symtmm.limits`).
MAX_LENGTH = MAX_EXPRESSION_LENGTH
#: Deepest expression tree a value resolved through its parameters may have: as deep as
#: the deepest expression the parser admits (each level of nesting in the text adds at
#: most two levels to the tree), which keeps SymPy's recursion far from Python's limit.
MAX_TREE_DEPTH = 2 * MAX_NESTING + 1

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
        # the size is known from the bits, before any conversion to text or SymPy
        if value and abs(math.log10(abs(value))) > MAX_DECADES:
            raise ExpressionError(_beyond(1))
        return sp.Integer(value)
    if isinstance(value, float):
        if not math.isfinite(value):
            raise ExpressionError(f"{value} is not a finite number")
        value = Decimal(repr(value))
    if isinstance(value, Decimal):
        if not value.is_finite():
            raise ExpressionError(f"{value} is not a finite number")
        _check_decimal(value)
        return sp.Rational(str(value))
    raise ExpressionError(f"expected a number or an expression, got {type(value).__name__}")


def exact_float(value) -> float:
    """An exact number as the nearest float: ``p / q`` for a rational (Python divides
    integers correctly rounded; SymPy's ``float`` goes through mpmath, twenty times slower,
    and meshes and piece lengths ask for hundreds), ``float`` otherwise.

    Examples
    --------
    >>> exact_float(sp.Rational(1, 3)) == 1 / 3, exact_float(sp.sqrt(2)) == 2 ** 0.5
    (True, True)
    """
    if isinstance(value, sp.Rational):
        try:
            return value.p / value.q
        except OverflowError:
            pass
    return float(value)


def _beyond(sign: int) -> str:
    return (f"a number larger than 1e{MAX_DECADES} in magnitude" if sign > 0 else
            f"a nonzero number smaller than 1e-{MAX_DECADES} in magnitude")


def _check_decimal(value: Decimal) -> None:
    """A decimal's magnitude from its exponent, before the exact value is built.

    ``Decimal("1e-999999")`` is cheap; the rational 10**-999999 is not.
    """
    if value.is_zero():
        return
    exponent = value.adjusted()     # floor(log10 |value|)
    if exponent >= MAX_DECADES:
        raise ExpressionError(_beyond(1))
    if exponent < -MAX_DECADES:
        raise ExpressionError(_beyond(-1))


def decades(value: sp.Expr) -> float:
    """``log10 |value|`` of a SymPy number, estimated without building anything large.

    ``-inf`` for zero. Rationals are measured from their integers, powers from
    their base and exponent (so ``2**(10**9)`` is never expanded), products as
    sums; anything else is evaluated to 15 digits.

    Examples
    --------
    >>> round(decades(sp.Rational(1, 1000)), 6), decades(sp.Integer(0))
    (-3.0, -inf)
    >>> round(decades(sp.Pow(2, 10**9, evaluate=False)))
    301029996
    """
    if value.is_Rational:
        if value == 0:
            return -math.inf
        return math.log10(abs(int(value.p))) - math.log10(int(value.q))
    if value.is_Pow and value.exp.is_number:
        base = decades(value.base)
        if base == -math.inf:
            return -math.inf
        return base * float(value.exp) if base else 0.0
    if value.is_Mul:
        parts = [decades(a) for a in value.args]
        return -math.inf if -math.inf in parts else math.fsum(parts)
    if value.is_Add:
        top = max(decades(a) for a in value.args)
        if top > MAX_DECADES + 3:
            return top      # too large to evaluate honestly; the sum is no larger than this
    approx = sp.N(value, 15)
    if not approx.is_Number:
        raise ExpressionError(f"cannot evaluate {value}")
    if approx == 0:
        return -math.inf
    return float(mpmath.log10(abs(mpmath.mpf(approx))))


def _check_size(value: sp.Expr) -> sp.Expr:
    """``value`` itself, if it is a number within the limits (or no number)."""
    if value.is_number:
        size = decades(value)
        if size >= MAX_DECADES:
            raise ExpressionError(_beyond(1))
        if -math.inf < size < -MAX_DECADES:
            raise ExpressionError(_beyond(-1))
    return value


def checked_power(base: sp.Expr, exponent: sp.Expr) -> sp.Expr:
    """``base**exponent``, refused before it is built if it would leave the limits."""
    if exponent.is_number:
        if not exponent.is_real:
            raise ExpressionError("an exponent must be a real number")
        if decades(exponent) > math.log10(MAX_EXPONENT):
            raise ExpressionError(f"exponent larger than {MAX_EXPONENT}")
        if base == 0 and exponent.is_negative:
            raise ExpressionError("division by zero")
        if base.is_number and base != 0:
            size = decades(base) * float(exponent)
            if size >= MAX_DECADES:
                raise ExpressionError(_beyond(1))
            if size < -MAX_DECADES:
                raise ExpressionError(_beyond(-1))
    return _check_size(base**exponent)


def tree_depth(expr: sp.Basic) -> int:
    """Depth of a SymPy tree (a number or symbol is 1), without recursion.

    >>> tree_depth(sp.Symbol("a") + 1), tree_depth(sp.Integer(3))
    (2, 1)
    """
    depth, level = 0, [expr]
    while level:
        depth += 1
        level = [arg for node in level for arg in node.args]
    return depth


def substitute(expr: sp.Expr, values: Mapping[sp.Symbol, sp.Expr]) -> sp.Expr:
    """``expr`` with the ``values`` of its symbols put in, checked as the parser checks.

    Rebuilt from the leaves: every power whose base and exponent become
    numbers is checked before it is built (``2**e`` with ``e = 10**9`` is
    refused, never computed), every number that appears is checked against
    the magnitude limits, and the tree may not grow deeper than
    :data:`MAX_TREE_DEPTH`.

    Raises
    ------
    ExpressionError

    Examples
    --------
    >>> e = parameter_symbol("e")
    >>> substitute(2**e, {e: sp.Integer(10)})
    1024
    >>> substitute(2**e, {e: sp.Integer(10**9)})
    Traceback (most recent call last):
    ...
    symtmm.expr.ExpressionError: exponent larger than 1000
    """
    keys = set(values)
    if not keys or not (expr.free_symbols & keys):
        return expr

    def rebuild(node):
        if node.is_Symbol:
            return values.get(node, node)
        if not node.args or not (node.free_symbols & keys):
            return node
        args = [rebuild(a) for a in node.args]
        if node.is_Pow:
            return checked_power(*args)
        return _check_size(node.func(*args))

    result = rebuild(expr)
    if tree_depth(result) > MAX_TREE_DEPTH:
        raise ExpressionError(f"nested deeper than {MAX_TREE_DEPTH} levels once its parameters "
                              "are put in")
    return result


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
        self.depth = 0

    def nested(self, parse):
        """``parse()`` one level deeper (a sign, a power, parentheses, a function)."""
        self.depth += 1
        if self.depth > MAX_NESTING:
            raise ExpressionError(f"nested deeper than {MAX_NESTING} levels")
        try:
            return parse()
        finally:
            self.depth -= 1

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
            value = _check_size(value + rhs if op == "+" else value - rhs)
        return value

    def term(self):
        value = self.unary()
        while self.peek()[1] in ("*", "/"):
            _, op = self.take()
            rhs = self.unary()
            if op == "/":
                if rhs == 0:
                    raise ExpressionError("division by zero")
                value = _check_size(value / rhs)
            else:
                value = _check_size(value * rhs)
        return value

    def unary(self):
        if self.peek()[1] in ("+", "-"):
            _, op = self.take()
            value = self.nested(self.unary)
            return -value if op == "-" else value
        return self.power()

    def power(self):
        base = self.atom()
        if self.peek()[1] == "**":
            self.take()
            exponent = self.nested(self.unary)
            return checked_power(base, exponent)
        return base

    def atom(self):
        kind, tok = self.take()
        if kind == "num":
            try:
                number = Decimal(tok)
            except InvalidOperation:  # pragma: no cover - the regex admits only valid numbers
                raise ExpressionError(f"bad number '{tok}'") from None
            _check_decimal(number)
            return sp.Rational(str(number))
        if kind == "name":
            if self.peek()[1] == "(":
                if tok not in _FUNCTIONS:
                    raise ExpressionError(f"unknown function '{tok}'")
                self.take("(")
                arg = self.nested(self.expr)
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
            value = self.nested(self.expr)
            self.take(")")
            return value
        raise ExpressionError(f"unexpected '{tok}'")
