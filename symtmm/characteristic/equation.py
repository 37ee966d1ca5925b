"""The result :class:`CharacteristicEquation` and the entry point :func:`characteristic_equation`.

:func:`characteristic_equation` runs the steps of :mod:`symtmm.characteristic`
(problem, algebra, determinant and factors, writer) and writes the factors in
``Omega`` and in the model's variable (``omega`` or ``lam``) with the wave
numbers' definitions.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from functools import cached_property

import sympy as sp

from .. import progress
from ..elements.base import LAM
from ..errors import ComputationError
from ..jsonout import dumps, header
from ..limits import DERIVE_SECONDS, DERIVE_TERMS
from ..model import Model
from .algebra import _Algebra
from .budget import _BUDGET, budget, spend
from .factor import _factorise
from .order import _prepare
from .problem import OMEGA, OMEGA_DIMLESS, _build_problem, _Problem, _wave_segment
from .writer import _Writer

__all__ = ["CharacteristicEquation", "characteristic_equation"]

#: Operations from which the Omega form is also printed with named subexpressions.
LARGE_FORM = 500


@dataclass(frozen=True)
class CharacteristicEquation:
    """A characteristic function in closed form: ``det R = constant * delta``.

    Attributes
    ----------
    variable : sympy.Symbol
        ``omega`` (rad/s, ``lam = I*omega``) for undamped models, ``lam`` for damped ones.
    delta : sympy.Expr
        The characteristic function in :attr:`variable`, constant factor removed.
    constant : sympy.Expr
        ``det R(lam) = constant * delta`` (independent of the frequency).
    delta_Omega : sympy.Expr
        The same function of ``Omega = beta_1 L_1`` (the paper's frequency parameter).
    constant_Omega : sympy.Expr
        ``det R = constant_Omega * delta_Omega``.
    Omega : sympy.Expr
        ``Omega`` as a function of :attr:`variable`.
    power : int
        ``delta_Omega = Omega**power * prod(f**e for f, e in factors)``.
    factors : tuple of (sympy.Expr, int)
        Factors in ``Omega`` with their multiplicities.
    symbols : tuple of str
        Model parameters left symbolic.
    seconds : float
        Time the derivation took.
    notes : tuple of str
        How the result is structured (e.g. kept factored).
    definitions : dict
        The wave numbers ``a_<beam>``, ``b_<beam>`` of beams that are not
        plain Euler–Bernoulli beams, ``p_<a>_<b>``, ``q_<a>_<b>`` of beams joined
        by a layer, ``b_<rod>`` of rods on an axial foundation, and ``Omega`` when
        the closed form uses it,
        as functions of :attr:`variable`; :attr:`delta_Omega` and
        :attr:`factors` are written in them, :attr:`delta` has them substituted.
    """

    variable: sp.Symbol
    delta: sp.Expr
    constant: sp.Expr
    delta_Omega: sp.Expr
    constant_Omega: sp.Expr
    Omega: sp.Expr
    power: int
    factors: tuple
    symbols: tuple = ()
    seconds: float = 0.0
    notes: tuple = field(default_factory=tuple)
    model_name: str | None = None
    definitions: dict = field(default_factory=dict)
    title: str = ""

    @property
    def equation(self) -> sp.Expr:
        """``prod(f**e)`` in ``Omega`` (and wave numbers): the textbook frequency equation ``= 0``.

        Powers of a single wave number (like ``Omega**power``) are left out.
        """
        return sp.Mul(*[f**e for f, e in self.factors if not f.is_Symbol])

    def count_ops(self) -> int:
        """Size of :attr:`delta_Omega` (the closed form) as SymPy counts operations."""
        return self._ops

    @cached_property
    def _ops(self) -> int:
        # (counted once: a large form takes a second, and the outputs ask several times)
        return int(sp.count_ops(self.delta_Omega))

    def latex(self) -> str:
        """LaTeX of ``delta`` in :attr:`variable`."""
        return sp.latex(self.delta)

    def to_dict(self) -> dict:
        """The JSON contract ``{"variable", "delta", "latex"}`` plus the Omega form.

        ``delta`` parses with :func:`sympy.sympify` into the function of
        ``variable``; ``delta_Omega`` with ``Omega`` (and the wave numbers of
        ``definitions``, each a function of ``variable``) likewise.
        """
        # digits: null, a closed form is exact
        return header(self.model_name, self.title, None, self.notes) | {
            "variable": str(self.variable),
            "delta": str(self.delta),
            "latex": self.latex(),
            "Omega": str(self.Omega),
            "delta_Omega": str(self.delta_Omega),
            "latex_Omega": sp.latex(self.delta_Omega),
            "power_Omega": self.power,
            "factors_Omega": [{"factor": str(f), "multiplicity": e} for f, e in self.factors],
            # det R = constant * delta = constant_Omega * delta_Omega: each form its own
            "constant": str(self.constant),
            "constant_Omega": str(self.constant_Omega),
            "symbols": list(self.symbols),
            "count_ops": self.count_ops(),
            "seconds": round(self.seconds, 3),
            "definitions": {str(k): str(v) for k, v in self.definitions.items()},
        } | self._subexpressions_dict()

    def _subexpressions_dict(self) -> dict:
        """For a large Omega form: ``delta_Omega_named`` and its ``subexpressions``."""
        named = self.subexpressions()
        if named is None:
            return {}
        definitions, reduced = named
        return {"delta_Omega_named": str(reduced),
                "subexpressions": [[str(k), str(v)] for k, v in definitions]}

    def to_json(self) -> str:
        return dumps(self.to_dict())

    def __str__(self) -> str:
        return f"Delta({self.variable}) = {self.delta}"

    def subexpressions(self, min_ops: int = LARGE_FORM):
        """The Omega form with named common subexpressions, for a form of at least
        ``min_ops`` operations: ``(definitions, reduced)``, ``definitions`` a list of
        ``(x_k, expression)`` each using the names before it; None for smaller forms.

        Examples
        --------
        >>> from symtmm.model import Beam, Model
        >>> cc = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
        >>> eq = characteristic_equation(cc)
        >>> eq.subexpressions() is None             # small: printed as it is
        True
        >>> eq.subexpressions(min_ops=1)            # nothing repeats in it
        ([], (cos(Omega)*cosh(Omega) - 1)/Omega**4)
        """
        if self.count_ops() < min_ops:
            return None
        return self._named

    @cached_property
    def _named(self):
        names = sp.numbered_symbols("x")
        taken = {str(s) for s in self.delta_Omega.free_symbols}
        names = (x for x in names if str(x) not in taken)
        definitions, (reduced,) = sp.cse(self.delta_Omega, symbols=names)
        return definitions, reduced

    def _names(self) -> str:
        return ", ".join(str(s) for s in self.definitions) or "Omega"

    def latex_both(self) -> str:
        """LaTeX of both forms, each with the constant that makes it ``det R``: the form in
        :attr:`variable`, and the paper's form in ``Omega`` (and wave numbers) with their
        definitions."""
        var = sp.latex(self.variable)
        names = ", ".join(sp.latex(s) for s in self.definitions) or r"\Omega"
        defs = r",\quad ".join(f"{sp.latex(s)} = {sp.latex(v)}"
                               for s, v in self.definitions.items()) \
            or rf"\Omega = {sp.latex(self.Omega)}"
        return "\n".join([
            rf"\Delta({var}) = {self.latex()}",
            rf"\det R = {sp.latex(self.constant)}\,\Delta({var})",
            rf"{defs}",
            rf"\Delta({names}) = {sp.latex(self.delta_Omega)}",
            rf"\det R = {sp.latex(self.constant_Omega)}\,\Delta({names})",
        ])

    def pretty(self) -> str:
        """Both forms as unicode text (SymPy's pretty printer), with their constants."""
        def block(expr):
            return sp.pretty(expr, use_unicode=True, wrap_line=False)
        names = self._names()
        defs = "; ".join(f"{s} = {sp.pretty(v, use_unicode=True)}"
                         for s, v in self.definitions.items()) \
            or f"Omega = {sp.pretty(self.Omega, use_unicode=True)}"
        return "\n".join([
            f"Δ({self.variable}) =", block(self.delta),
            f"det R = ({sp.pretty(self.constant, use_unicode=True)}) · Δ({self.variable})", "",
            f"with {defs}:", f"Δ({names}) =", block(self.delta_Omega),
            f"det R = ({sp.pretty(self.constant_Omega, use_unicode=True)}) · Δ({names})"])

    def _repr_latex_(self) -> str:
        """``Delta(variable) = ...`` typeset (Jupyter)."""
        return f"$\\Delta({sp.latex(self.variable)}) = {self.latex()}$"


def characteristic_equation(model: Model, symbolic=(), max_seconds: float | None = DERIVE_SECONDS,
                            max_terms: int | None = DERIVE_TERMS) -> CharacteristicEquation:
    """The characteristic function of ``model`` in closed form.

    Parameters
    ----------
    model : Model
        Fields may contain parameters without value; they stay symbols.
    symbolic : iterable of str
        Parameters to keep symbolic although the model gives them a value;
        that value then only orders cuts that the symbols cannot (``x1`` and
        ``1 - x1``).
    max_seconds : float or None
        Time budget (default :data:`symtmm.limits.DERIVE_SECONDS`); None: none.
    max_terms : int or None
        Most terms of any polynomial on the way, a budget on memory (default
        :data:`symtmm.limits.DERIVE_TERMS`); None: none.

    Returns
    -------
    CharacteristicEquation

    Raises
    ------
    ModelError
        A named parameter does not exist, or the order of the cuts depends on
        a parameter without value.
    ComputationError
        Over a budget (the message says what to change), or the closed form
        cannot be written (a determinant that vanishes identically).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI="EI", m="m", L="L", left="pinned", right="pinned"),))
    >>> eq = characteristic_equation(pp)
    >>> eq.delta_Omega
    sin(Omega)*sinh(Omega)/Omega**2
    >>> eq.Omega
    L*m**(1/4)*sqrt(omega)/EI**(1/4)
    """
    start = time.perf_counter()
    token = _BUDGET.set(budget(max_seconds, max_terms))
    try:
        with progress.stages("derive", _STAGES) as next_stage:
            return _characteristic_equation(model, tuple(symbolic), start, next_stage)
    finally:
        _BUDGET.reset(token)


#: The stages of a derivation, as its progress bar names them.
_STAGES = ("transfer matrices", "determinant", "factoring", "writing the factors")


def _characteristic_equation(model: Model, symbolic: tuple, start: float,
                             next_stage=lambda stage: None) -> CharacteristicEquation:
    model_in = model
    model, sample = _prepare(model, symbolic)
    problem = _build_problem(model, sample)
    alg = _Algebra(problem)
    next_stage(_STAGES[1])
    R = alg.boundary_matrix()
    next_stage(_STAGES[2])
    constant, factors = _factorise(alg, R)
    next_stage(_STAGES[3])
    Om = OMEGA_DIMLESS
    writer = _Writer(alg, Om)
    rod_symbols = [rod.symbol for rod in problem.rods]
    founded = [w.b for w in problem.waves if w.scaled] + rod_symbols
    pre_c, pre_p, pre_b = _split_powers(problem.prefactor, Om, founded)
    power = pre_p
    out_factors = [(bk, p) for bk, p in pre_b.items() if p]
    frequency_symbols = [s for w in problem.waves for s in (w.a, w.b)] + [
        br.symbol for mb in problem.members for br in mb.branches if br.kind == "free"] \
        + rod_symbols
    for poly, e in factors:
        spend()
        m, expr, ratio = writer.best(poly)
        constant *= ratio**e
        power += m * e
        if not expr.has(Om, *frequency_symbols):
            constant *= expr ** e
            continue
        out_factors.append((expr, e))
    c_merge, p_merge, out_factors = _merge_factors(out_factors, Om)
    constant *= c_merge
    power += p_merge
    if problem.damped:
        variable, lam = LAM, LAM
        Omega_of_var = problem.omega_of["damped"]
    else:
        variable, lam = OMEGA, sp.I * OMEGA
        Omega_of_var = problem.omega_of["undamped"]
    definitions = _wave_definitions(problem, lam)
    definitions.update(_member_definitions(problem, lam, Omega_of_var))
    definitions.update(_rod_definitions(problem, lam))
    # atoms in Omega: plain beams', rods' without foundation
    in_Omega = any(g.plain or (g.rod is not None and g.rod.has(Om)) for g in problem.groups)
    if (problem.waves or problem.members or problem.rods) and not in_Omega:
        # no plain beam: the frequency left in the coefficients is the model's variable
        back = {Om: Omega_of_var}
        c_poly, out_factors = _polynomials_in(variable, [(_tidy(f.xreplace(back)), e)
                                                         for f, e in out_factors])
        if problem.rods:
            # (Omega = I kappa lam of a rod leaves products of sums with I in them)
            out_factors = [(_by_functions(f), e) for f, e in out_factors]
        constant *= c_poly
        c_disc, out_factors = _discriminants_back(problem, lam, variable, out_factors)
        constant *= c_disc
        scale = Omega_of_var ** power
        power = 0
    else:
        definitions = {Om: Omega_of_var, **definitions}
        scale = sp.Integer(1)
    out_factors = [(_single_angles(f, Om), e) for f, e in out_factors]
    out_factors.sort(key=lambda fe: (sp.count_ops(fe[0]), str(fe[0])))
    constant_Omega = sp.simplify(pre_c * constant)
    delta_Omega = Om ** power * scale * sp.Mul(*[f**e for f, e in out_factors])
    delta = delta_Omega.xreplace({Om: Omega_of_var, **definitions})
    if problem.damped and any(g.rod is not None for g in problem.groups):
        delta = _imaginary_sums_out(delta)
    # what xreplace leaves as a constant factor in front of the power of the variable
    c_scale, rest = delta.as_independent(variable, as_Add=False)
    delta = rest
    constant = sp.simplify(constant_Omega * c_scale)
    if power == 0 and scale != 1:
        # the closed form holds the variable's power itself; keep constant_Omega exact
        c_form, rest_form = delta_Omega.as_independent(variable, *definitions, as_Add=False)
        delta_Omega = rest_form
        constant_Omega = sp.simplify(constant_Omega * c_form)
    symbols = tuple(sorted(s.name for s in sp.sympify(delta).free_symbols
                           if s not in (variable,)))
    notes = []
    if len(out_factors) > 1 or any(e > 1 for _, e in out_factors):
        notes.append("kept factored: " + ", ".join(
            f"{sp.count_ops(f)} ops x{e}" for f, e in out_factors))
    if problem.waves or problem.members or problem.rods:
        notes.append("wave numbers: " + ", ".join(
            f"{s} = {v}" for s, v in definitions.items() if s != Om))
    notes += _member_notes(problem, lam)
    if not alg.ring.can_factor and any(sp.count_ops(f) > 100 for f, _ in out_factors):
        notes.append("factored by the structure of R only: python-flint (pip install "
                     "python-flint) factors the polynomials and gives fewer, smaller factors")
    return CharacteristicEquation(
        variable=variable, delta=delta, constant=constant, delta_Omega=delta_Omega,
        constant_Omega=constant_Omega, Omega=Omega_of_var, power=int(power),
        factors=tuple(out_factors), symbols=symbols,
        seconds=time.perf_counter() - start, notes=tuple(notes),
        model_name=model_in.source or None, definitions=definitions, title=model_in.title)


_TRIG = (sp.sin, sp.cos, sp.sinh, sp.cosh)


#: sin**2 and sinh**2 through cos and cosh.
_SQUARES = {sp.sin: lambda x: 1 - sp.cos(x) ** 2, sp.sinh: lambda x: sp.cosh(x) ** 2 - 1}


def _even_sine_power(e) -> bool:
    return bool(e.is_Pow and e.exp.is_Integer and e.exp > 1 and e.base.func in _SQUARES)


def _square_free(e):
    """``sin(x)**k`` as ``(1 - cos(x)**2)**(k // 2)`` times ``sin(x)`` if ``k`` is odd."""
    base, k = e.base, int(e.exp)
    rest = _SQUARES[base.func](base.args[0]) ** (k // 2)
    return rest * base if k % 2 else rest


#: Operations beyond which a factor is not rewritten in single angles (:func:`_single_angles`):
#: SymPy's expand and collect of one factor cannot be interrupted by the budget, and took
#: 25-30 s on a factor of 6143 operations (two Rayleigh beams joined by a rotational
#: spring, a mass and a foundation), far past a ``--max-seconds`` of 5; the factors this
#: rewriting shortens (double angles of Euler–Bernoulli pairs) have tens to hundreds.
_SINGLE_ANGLE_OPS = 1500


def _single_angles(f, Om):
    """``f`` with each part multiplying one power of ``Om`` written, where shorter, as a
    product of functions of ``Om`` itself instead of sums of double angles.

    The writer turns products into sums (``cos x cosh x`` squared becomes ``cos 2x cosh 2x
    / 4 + ...``); where a part holds nothing but ``x`` and ``2x`` as arguments, the double
    angles are expanded, ``sin**2`` and ``sinh**2`` written through ``cos`` and ``cosh``,
    and the result factored, and kept if it is shorter.

    Examples
    --------
    >>> O = OMEGA_DIMLESS
    >>> _single_angles(O**3 * (sp.cos(2*O)*sp.cosh(2*O)/4 + sp.cos(2*O)/4 + sp.cosh(2*O)/4
    ...                + sp.Rational(5, 4) - 2*sp.cos(O)*sp.cosh(O)) + sp.sin(O), O)
    Omega**3*(cos(Omega)*cosh(Omega) - 1)**2 + sin(Omega)
    """
    if not f.has(*_TRIG) or sp.count_ops(f) > _SINGLE_ANGLE_OPS:
        return f
    spend()
    try:
        parts = sp.collect(sp.expand(f), Om, evaluate=False)
    except (TypeError, ValueError):  # pragma: no cover - a form collect cannot split
        return f
    changed = False
    for key, part in list(parts.items()):
        arguments = {a.args[0] for a in part.atoms(*_TRIG)}
        if not arguments or not arguments <= {Om, 2 * Om}:
            continue
        spend()
        candidate = sp.factor(sp.expand_trig(part).replace(_even_sine_power, _square_free))
        if sp.count_ops(candidate) < sp.count_ops(part):
            parts[key] = candidate
            changed = True
    if not changed:
        return f
    return sp.Add(*[k * v for k, v in parts.items()])


def _over_i(expr):
    """``expr / I`` written without ``I``, or None where ``expr`` is not ``I`` times an
    expression free of it (every term of a sum, one factor of each product)."""
    if expr == sp.I:
        return sp.Integer(1)
    if expr.is_Add:
        terms = [_over_i(t) for t in expr.args]
        return None if any(t is None for t in terms) else sp.Add(*terms)
    if expr.is_Mul:
        with_i = [k for k, a in enumerate(expr.args) if a.has(sp.I)]
        if len(with_i) == 1:
            k = with_i[0]
            inner = _over_i(expr.args[k])
            if inner is not None:
                return sp.Mul(*expr.args[:k], inner, *expr.args[k + 1:])
    return None


def _imaginary_sums_out(expr):
    """``expr`` with ``I`` taken out in front of each factor that is ``I`` times an
    expression free of it.

    A rod's factor in ``lam`` is such a factor: ``cos(I x) = cosh(x)``, ``sin(I x) = I
    sinh(x)`` and its odd powers of ``beta = I ... lam`` leave ``I`` in every term.

    Examples
    --------
    >>> lam = LAM
    >>> _imaginary_sums_out((sp.I * lam * sp.cosh(lam) + sp.I * (lam + 3) * sp.sinh(lam)) / lam)
    I*(lam*cosh(lam) + (lam + 3)*sinh(lam))/lam
    """
    def part(a):
        base, e = (a.base, a.exp) if a.is_Pow and a.exp.is_Integer else (a, sp.Integer(1))
        if not base.has(sp.I):
            return a
        inner = _over_i(base)
        if inner is None:
            return a
        return sp.Mul(sp.I**e, inner**e, evaluate=False)

    if expr.is_Mul:
        return sp.Mul(*[part(a) for a in expr.args])
    return part(expr)


#: Operations beyond which a factor is not collected again (:func:`_by_functions`).
_COLLECT_OPS = 300


def _by_functions(f):
    """``f`` collected by its trigonometric and hyperbolic functions with each coefficient
    factored, where that is shorter.

    Examples
    --------
    >>> b, lam = sp.Symbol("b", positive=True), LAM
    >>> _by_functions(sp.cos(b) - sp.I * lam * (sp.I * lam + sp.I) * sp.sin(b) / b)
    cos(b) + lam*(lam + 1)*sin(b)/b
    """
    functions = sorted(f.atoms(*_TRIG), key=str)
    if not f.is_Add or not functions or sp.count_ops(f) > _COLLECT_OPS:
        return f
    spend()
    candidate = sp.collect(sp.expand(f), functions, func=sp.factor)
    return candidate if sp.count_ops(candidate) < sp.count_ops(f) else f


def _merge_factors(factors, Om):
    """Numbers out, equal bases together: ``(2 b**2)**2 / (4 b**4)**2 -> b**-4 / 4``.

    Returns the constant, the power of ``Om`` and the merged ``(base, exponent)``.
    """
    constant, power, merged = sp.Integer(1), 0, {}
    for f, e in factors:
        c, parts = f.as_coeff_mul()
        constant *= c**e
        for part in parts:
            base, p = part.as_base_exp()
            if base == Om:
                power += p * e
            else:
                merged[base] = merged.get(base, 0) + p * e
    return constant, int(power), [(b, int(e)) for b, e in merged.items() if e != 0]


def _discriminants_back(problem: _Problem, lam, variable, factors):
    """A polynomial factor in ``variable`` proportional to ``t**2 - 4 d`` of a wave is
    ``(a**2 + b**2)**2``: written so, it cancels against the denominators."""
    constant, out = sp.Integer(1), []
    discs = []
    for wave in problem.waves:
        if wave.scaled:
            continue
        t, d = _wave_segment(wave.beam).invariants(sp.expand(lam**2))
        discs.append((sp.expand(t**2 - 4 * d), wave.a**2 + wave.b**2))
    for f, e in factors:
        for disc, form in discs:
            if f.free_symbols <= {variable} | disc.free_symbols and f.has(variable):
                ratio = sp.simplify(f / disc)
                if ratio.is_number and ratio != 0:
                    constant *= ratio**e
                    f, e = form, 2 * e
                    break
        out.append((f, e))
    merged: dict = {}
    for f, e in out:
        merged[f] = merged.get(f, 0) + e
    return constant, [(f, e) for f, e in merged.items() if e != 0]


def _polynomials_in(variable, factors):
    """Factors that are polynomials in ``variable`` only, multiplied and factored again in it.

    Factored in ``Omega ~ sqrt(omega)``, ``omega**2 - c`` splits into
    ``(k omega - sqrt(c)) (k omega + sqrt(c))``: refactored it is whole again.
    """
    plain, rest = [], []
    for f, e in factors:
        (plain if f.free_symbols <= {variable} and f.is_polynomial(variable) else rest).append(
            (f, e))
    if len(plain) < 2:
        return sp.Integer(1), factors
    out, constant = [], sp.Integer(1)
    for sign in (1, -1):
        product = sp.Mul(*[f ** (e * sign) for f, e in plain if e * sign > 0])
        if product == 1:
            continue
        c, parts = sp.factor_list(sp.expand(product), variable)
        constant *= c**sign
        out += [(f, sign * int(e)) for f, e in parts]
    return constant, rest + out


def _tidy(expr: sp.Expr) -> sp.Expr:
    """Powers of the frequency gathered (``sqrt(omega)**4 -> omega**2``)."""
    return sp.powsimp(sp.expand_power_base(expr, force=True))


def _wave_definitions(problem: _Problem, lam) -> dict:
    """``{a: ..., b: ...}`` of every wave kind, in the model's variable (``lam = I omega``)."""
    out = {}
    for wave in problem.waves:
        t, d = (sp.simplify(v) for v in _wave_segment(wave.beam).invariants(sp.expand(lam**2)))
        if wave.equal:
            out[wave.b] = sp.factor(-d) ** sp.Rational(1, 4)
            continue
        root = sp.sqrt(sp.factor(t**2 / 4 - d))
        out[wave.a] = sp.sqrt(t / 2 + root)
        out[wave.b] = sp.sqrt(-t / 2 + root)
    return out


def _rod_definitions(problem: _Problem, lam) -> dict:
    """``{b: sqrt(-(m lam**2 + kw) / EA)}`` of the rods on a foundation, in the model's
    variable (``sqrt((m omega**2 - kw) / EA)`` undamped)."""
    return {rod.symbol: sp.sqrt(sp.factor(rod.squared(sp.expand(lam**2))))
            for rod in problem.rods}


def _member_invariants(member, lam):
    """``(t, d)`` of a layered member's ``X / l**4`` in the model's variable."""
    X = member.segment.field_matrix(lam=lam, lam2=sp.expand(lam**2))
    return sp.expand(X.trace()), sp.expand(X.det())


def _member_definitions(problem: _Problem, lam, Omega_of_var) -> dict:
    """``{p: (p**4)**(1/4), q: ...}`` of the layered members' free branches in the model's
    variable: ``p**4, q**4`` the roots of ``mu**2 - t mu + d``, ``p**4`` with the ``+``
    of the square root (or of the polynomial root of the discriminant); a branch that is
    ``Omega`` or a founded wave's ``b`` needs none."""
    out = {}
    for member in problem.members:
        if member.root is not None:
            mus = [_tidy(sp.expand(br.mu.xreplace({OMEGA_DIMLESS: Omega_of_var})))
                   for br in member.branches]
        else:
            t, d = _member_invariants(member, lam)
            root = sp.sqrt(sp.factor(t**2 - 4 * d))
            mus = [sp.factor((t + root) / 2), sp.factor((t - root) / 2)]
        for br, mu in zip(member.branches, mus):
            if br.kind == "free":
                out[br.symbol] = mu ** sp.Rational(1, 4)
    return out


def _member_notes(problem: _Problem, lam) -> list:
    """How each layered member's wave numbers are defined: ``p**4, q**4`` are the
    eigenvalues of ``X / l**4``."""
    out = []
    mu = sp.Symbol("mu")
    beams = problem.layout.model.beams
    for member in problem.members:
        t, d = _member_invariants(member, lam)
        where = ", ".join(f"[{a}, {b}]" for a, b in dict.fromkeys(member.stretches))
        p, q = (br.printed(problem.waves) for br in member.branches)
        out.append(f"{p**4} and {q**4}: the roots of {sp.collect(mu**2 - t * mu + d, mu)} "
                   f"= 0, the eigenvalues of X/l**4 (Y'''' = (X/l**4) Y) of beams "
                   f"{' and '.join(beams[j].name for j in member.levels)} joined by a layer "
                   f"over {where}")
    return out


def _split_powers(expr, x, others):
    """``expr = c * x**p * prod(y**q)`` over ``others``: ``(c, p, {y: q})``."""
    expr = sp.powsimp(sp.expand_power_base(sp.sympify(expr), force=True))
    powers = {}
    for y in others:
        c, q = expr.as_coeff_exponent(y)
        powers[y] = int(q)
        expr = c
    c, p = _split_power(expr, x)
    return c, p, powers


def _split_power(expr, x):
    """``expr = c * x**p`` with ``c`` free of ``x``."""
    expr = sp.powsimp(sp.expand_power_base(sp.sympify(expr), force=True))
    c, p = expr.as_coeff_exponent(x)
    if c.has(x):
        raise ComputationError(f"cannot separate the power of {x} in {expr}")
    return c, int(p)
