"""Result objects: eigenvalues and spectra."""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace
from decimal import Decimal
from functools import cached_property

import mpmath
from mpmath.libmp import mpf_sub, round_nearest, to_float

from .display import html_table, latex_array, latex_text, text_lines
from .jsonout import dumps, header
from .tables import Tabular

__all__ = ["first", "Eigenvalue", "Spectrum", "decimal_string", "prints_alike", "print_apart",
           "enclosed_string", "rounding_room"]


def decimal_string(value, digits: int) -> str:
    """``value`` as a decimal string with ``digits`` significant digits, every one printed
    of them significant: positional, but with an exponent where the integer part would
    need zeros beyond the digits (``3.58069963539574e+30``, not thirty-one digits of
    which the last sixteen would be padding; ``1.2e+2`` for 122.07 at two digits, not
    ``120.``, whose point says the units are known).

    Examples
    --------
    >>> decimal_string(mpmath.mpf("123.456789"), 5)
    '123.46'
    >>> decimal_string(mpmath.mpf(0), 5)
    '0'
    >>> decimal_string(mpmath.mpf("1.5e-7"), 3)
    '0.000000150'
    >>> decimal_string(mpmath.mpf("122.07"), 2), decimal_string(mpmath.mpf("122.07"), 3)
    ('1.2e+2', '122.')
    """
    if value == 0:
        return "0"
    ctx = _context(digits + 10)
    return ctx.nstr(ctx.mpf(value), digits, strip_zeros=False, min_fixed=-ctx.inf,
                    max_fixed=digits)


def prints_alike(a, b, digits: int) -> bool:
    """Whether ``a`` and ``b`` print alike with ``digits`` significant digits
    (:func:`decimal_string`): the ends of a proved bracket that prove its digits.

    Two numbers that print alike lie within a unit of the printed last digit, whose
    decade is at most one above the larger's: farther apart, no strings are made (the
    proof stages ask this of every bracket they try).

    Examples
    --------
    >>> prints_alike(mpmath.mpf("9.99996"), mpmath.mpf("10.0004"), 5)     # both 10.000
    True
    >>> prints_alike(mpmath.mpf("1.23444"), mpmath.mpf("1.23456"), 5)     # 1.2344, 1.2346
    False
    """
    if print_apart(a, b, digits):
        return False
    ra, rb = _rounded(a, digits), _rounded(b, digits)
    if ra is not None and rb is not None:
        return ra == rb
    return decimal_string(a, digits) == decimal_string(b, digits)


#: How near a tie (a half unit of the last digit) :func:`_rounded` leaves a value to the
#: strings, as a fraction of that unit: ``1 / _TIE``. mpmath rounds through three guard
#: digits, so within a unit of the third of them its string may round either way (a
#: margin ten times that: one value in a hundred goes to the strings).
_TIE = 100


def _rounded(value, digits: int):
    """``(sign, q, e)``: ``value`` rounded to ``digits`` significant digits, ``q * 10**(e -
    digits + 1)`` with ``10**(digits - 1) <= q < 10**digits``, in integer arithmetic on its
    exact binary value; None for 0, infinities and values within ``1 / _TIE`` of a unit of
    the last digit from a tie (:data:`_TIE`), where :func:`decimal_string` (mpmath's
    rounding of its guard digits) decides. Where not None, two values print alike exactly when these agree
    (a proof stage asks this of about twenty brackets per solve: the strings cost 30 us a
    pair, this a few).

    Examples
    --------
    >>> _rounded(mpmath.mpf("9.99996"), 5), _rounded(1.25, 2) is None
    ((0, 10000, 1), True)
    """
    parts = _digits_of(value, digits)
    if parts is None:
        return None
    sign, q, r, den, e = parts
    if abs(2 * r - den) * _TIE < den:
        return None
    if 2 * r > den:
        q += 1
        if q == 10 ** digits:
            q, e = q // 10, e + 1
    return sign, q, e


def rounding_room(value, digits: int) -> float:
    """How far (a float, absolute) ``value`` may move and still print as it does with
    ``digits`` significant digits: its distance from the nearest tie (half a unit of the
    last digit), less the margin :func:`_rounded` leaves to the strings; 0.0 for 0,
    infinities and values within that margin of a tie. A proof stage places the two
    points that bracket a root that far from its estimate at most: where they bracket it,
    they print alike and prove the digits, and the farther from the root, the fewer bits
    their counts need.

    Examples
    --------
    >>> # prints 1.234 up to the tie at 1.2345, less the margin (half a hundredth of a unit)
    >>> round(rounding_room(mpmath.mpf("1.2344"), 4), 12)
    9.5e-05
    >>> rounding_room(mpmath.mpf("1.23449999"), 4)      # a tie 1e-8 above
    0.0
    """
    parts = _digits_of(value, digits)
    if parts is None:
        return 0.0
    _, q, r, den, e = parts
    # (in units of the last digit, as floats: the margin is far above their rounding)
    room = abs(2 * r - den) / (2 * den)
    if q == 10 ** (digits - 1):
        # (at a decade's start the tie below is the decade's below: a tenth of the unit)
        room = min(room, r / den + 0.05)
    room -= 1 / (2 * _TIE)
    try:
        return room * 10.0 ** (e - digits + 1) if room > 0 else 0.0
    except OverflowError:               # (beyond the doubles' range: no room told)
        return 0.0


def _digits_of(value, digits: int):
    """``(sign, q, r, den, e)``: ``|value| = (q + r / den) * 10**(e - digits + 1)`` with
    ``10**(digits - 1) <= q < 10**digits`` and ``0 <= r < den``, exactly, in integer
    arithmetic on its binary value; None for 0 and infinities."""
    m = getattr(value, "_mpf_", None)
    if m is None:
        m = mpmath.mpf(float(value))._mpf_          # (a float: exact)
    sign, man, exp, bc = m
    if not man:
        return None
    man = int(man)
    low, high = _power_of_ten(digits - 1), _power_of_ten(digits)
    # the decade from the binary exponent, then made exact by comparisons
    e = math.floor((exp + bc - 1) * 0.30102999566398120)
    for _ in range(3):
        k = digits - 1 - e                          # |value| 10**k in [10**(D-1), 10**D)
        num = man << exp if exp >= 0 else man
        if k >= 0:
            num *= _power_of_ten(k)
        if exp < 0 and k >= 0:
            # (a power of two below: a shift, where the division cost most of the call)
            den = 1 << -exp
            q = num >> -exp
            r = num - (q << -exp)
        else:
            den = (1 if exp >= 0 else 1 << -exp) * (1 if k >= 0 else _power_of_ten(-k))
            q, r = divmod(num, den)
        if q < low:
            e -= 1
        elif q >= high:
            e += 1
        else:
            return sign, q, r, den, e
    return None


@functools.lru_cache(maxsize=512)
def _power_of_ten(k: int) -> int:
    return 10 ** k


def print_apart(a, b, digits: int) -> bool:
    """Whether ``a`` and ``b`` surely print apart with ``digits`` significant digits, told
    from their floats: farther apart than ten units of the last digit of the larger's
    decade (a unit of the decade above; False: they may print alike, which
    :func:`prints_alike` decides).

    Examples
    --------
    >>> print_apart(1.2344, 1.2399, 5), print_apart(1.23444, 1.23456, 5)
    (True, False)
    """
    fa, fb = _float(a), _float(b)
    if fa == 0 or fb == 0:
        return False
    top = max(abs(fa), abs(fb))
    return 0 < top < math.inf and \
        abs(_float_difference(b, a)) > 10.0 ** (math.floor(math.log10(top)) - digits + 2)


def _float(x) -> float:
    """``x`` (an mpmath number or a float) as the nearest float, read off its binary
    value directly (mpmath's ``float()`` costs a context call: the proof stages ask
    this of every bracket end)."""
    m = getattr(x, "_mpf_", None)
    return float(x) if m is None else to_float(m, rnd=round_nearest)


def _float_difference(b, a) -> float:
    """``b - a`` rounded once to a float (exact operands, as mpmath's difference at 53
    bits rounds it)."""
    mb, ma = getattr(b, "_mpf_", None), getattr(a, "_mpf_", None)
    if mb is None or ma is None:
        return float(b - a)
    return to_float(mpf_sub(mb, ma, 53, round_nearest), rnd=round_nearest)


def first(eigenvalues, count: int) -> list:
    """The eigenvalues (in their order) up to ``count`` counted with multiplicity; a
    multiple one that straddles ``count`` is kept whole.

    Examples
    --------
    >>> e = [Eigenvalue(mpmath.mpc(0, w), m) for w, m in ((1, 1), (2, 3), (3, 1))]
    >>> [x.multiplicity for x in first(e, 2)]
    [1, 3]
    """
    kept, total = [], 0
    for e in eigenvalues:
        if total >= count:
            break
        kept.append(e)
        total += e.multiplicity
    return kept


@functools.lru_cache(maxsize=32)
def _interval_context(prec: int):
    """A private mpmath interval context at ``prec`` bits (one per precision)."""
    import mpmath.ctx_iv
    iv = mpmath.ctx_iv.MPIntervalContext()
    iv.prec = prec
    return iv


def _printed_interval(ctx, text: str):
    """The numbers that print as ``text`` (:func:`decimal_string`, rounded to nearest) in
    the interval context ``ctx``: ``text`` plus or minus half a unit of its last digit
    (widened by a millionth of that for the rounding on the way)."""
    if text == "0":
        return ctx.mpf(0)
    # (the last digit's place, positional or with an exponent: "122." 0, "1.2e+2" 1)
    unit = Decimal(text).as_tuple().exponent
    half = ctx.mpf(10) ** unit * ctx.mpf("0.500001")
    value = ctx.mpf(text)
    return ctx.mpf([(value - half).a, (value + half).b])


def _meet(ctx, x, ends):
    """The interval ``x`` narrowed to ``[lo, hi]`` (both enclose the same number)."""
    lo, hi = ctx.mpf(ends[0]), ctx.mpf(ends[1])
    a = max(x.a, lo.a)
    b = min(x.b, hi.b)
    return ctx.mpf([a, b]) if a <= b else x


def enclosed_string(x, digits: int) -> str:
    """The interval ``x`` (an mpmath interval) to as many significant digits, at most
    ``digits``, as both of its ends print alike; ``"?"`` if not even one.

    Examples
    --------
    >>> import mpmath.ctx_iv
    >>> iv = mpmath.ctx_iv.MPIntervalContext()
    >>> enclosed_string(iv.mpf(["0.123441", "0.123446"]), 6)
    '0.1234'
    >>> enclosed_string(iv.mpf(["0.12344", "0.12346"]), 6)     # 0.1234 or 0.1235
    '0.123'
    """
    # (the ends unrounded: mpmath.mpf would round them to the ambient precision)
    lo, hi = (mpmath.mp.make_mpf(end) for end in x._mpi_)
    for d in range(digits, 0, -1):
        text = decimal_string(lo, d)
        if text == decimal_string(hi, d):
            return text
    return "?"


@functools.lru_cache(maxsize=32)
def _context(dps: int) -> mpmath.MPContext:
    """A private mpmath context at ``dps`` digits (the ambient precision is never set)."""
    ctx = mpmath.MPContext()
    ctx.dps = dps
    return ctx


def _global(x) -> mpmath.mpf:
    """A number of a private context as a global mpmath number, unrounded."""
    return mpmath.mp.make_mpf(x._mpf_)


@dataclass(frozen=True)
class Eigenvalue:
    """One eigenvalue ``lam = -sigma + i omega`` with ``Im lam >= 0``.

    Attributes
    ----------
    lam : mpmath.mpc
        The value, accurate to :attr:`digits` significant digits.
    multiplicity : int
    digits : int
        Significant digits guaranteed correct in both parts.
    bracket : tuple or None
        For undamped roots, ``(lo, hi)`` with the root(s) inside, proved by
        the eigenvalue count or by a sign change of Delta.
    proof : str
        What backs the printed digits (``"count (ball arithmetic)"``, ...;
        empty when nothing is claimed beyond the method's own checks).
    """

    lam: mpmath.mpc
    multiplicity: int = 1
    digits: int = 15
    bracket: tuple | None = None
    proof: str = ""

    @property
    def omega(self):
        """Circular frequency ``Im lam`` (rad/s), at the precision it was computed in."""
        return self.lam.imag

    @property
    def sigma(self):
        """Decay rate ``-Re lam`` (1/s)."""
        # (exactly: ``-x`` would round to the ambient precision)
        return mpmath.mp.make_mpf(mpmath.libmp.mpf_neg(self.lam.real._mpf_))

    def to_dict(self) -> dict:
        """JSON-ready ``{"real", "imag", "multiplicity"[, "proof"]}`` with :attr:`digits` digits."""
        out = {"real": decimal_string(self.lam.real, self.digits),
               "imag": decimal_string(self.lam.imag, self.digits),
               "multiplicity": self.multiplicity}
        if self.proof:
            out["proof"] = self.proof
        return out

    def quantities(self) -> dict:
        """The engineer's quantities, each with the digits it is known to: ``"hz"`` (the
        damped frequency ``Im lam / 2 pi`` in Hz), ``"abs"`` (``|lam|``, the undamped natural
        frequency of the mode in rad/s) and ``"zeta"`` (the damping ratio ``-Re lam / |lam|``).

        Each follows, in interval arithmetic, from the proved enclosure of the eigenvalue
        (:attr:`bracket`) and the numbers that print as its :attr:`digits` digits, so
        every digit shown is right (a digit or two fewer where the enclosure is not
        narrower than the printed digits).

        Examples
        --------
        With a proved enclosure (here exact), all the digits; from the printed digits
        alone, a digit less where their rounding interval straddles a boundary:

        >>> exact = Eigenvalue(mpmath.mpc(-3, 4), digits=6, bracket=((-3, -3), (4, 4)))
        >>> exact.quantities()
        {'hz': '0.636620', 'abs': '5.00000', 'zeta': '0.600000'}
        >>> Eigenvalue(mpmath.mpc(-3, 4), digits=6).quantities()["zeta"]
        '0.60000'

        A real eigenvalue's ``|lam|`` is its printed digits:

        >>> Eigenvalue(mpmath.mpc("-2.19141315549854", 0), digits=15).quantities()["abs"]
        '2.19141315549854'
        """
        return dict(self._quantities)

    @cached_property
    def _enclosure(self) -> tuple:
        """``(iv, Re lam, Im lam)``: the intervals the printed digits stand for, narrowed
        to the proved bracket where there is one, in a private interval context."""
        iv = _interval_context(int(3.33 * self.digits) + 40)
        d = self.to_dict()
        re, im = _printed_interval(iv, d["real"]), _printed_interval(iv, d["imag"])
        box = self.bracket
        if box is not None and len(box) == 2 and not isinstance(box[0], tuple):
            box = ((0, 0), box) if d["real"] == "0" else None      # an undamped bracket
        if box is not None:
            re, im = (_meet(iv, x, ends) for x, ends in ((re, box[0]), (im, box[1])))
        return iv, re, im

    def frequency_parameter(self, scale) -> str:
        """``Omega = sqrt(Im lam / scale)`` (``scale``: ``sqrt(EI / (m L**4))`` of the
        reference beam, good to ``digits + 10`` digits) to the digits its enclosure
        gives, as :meth:`quantities` gives its own: a digit fewer where the enclosure
        straddles a rounding boundary.

        Examples
        --------
        >>> Eigenvalue(mpmath.mpc(0, 4), digits=6, bracket=(4, 4)).frequency_parameter(1)
        '2.00000'
        """
        iv, _, im = self._enclosure
        s = iv.mpf(scale)
        s = s * iv.mpf([1 - iv.mpf(10) ** -(self.digits + 9), 1 + iv.mpf(10) ** -(self.digits + 9)])
        return enclosed_string(iv.sqrt(im / s), self.digits)

    @cached_property
    def _quantities(self) -> dict:
        # (once per eigenvalue: a table, its JSON and its CSV each ask)
        iv, re, im = self._enclosure
        d = self.to_dict()
        size = iv.sqrt(re * re + im * im)
        out = {"hz": enclosed_string(im / (2 * iv.pi), self.digits)}
        if d["real"] == "0" or d["imag"] == "0":
            # (|lam| of a real or an imaginary eigenvalue is the other part's printed
            # digits, all of them: the square root of the square of its rounding interval
            # straddled a boundary and lost one)
            out["abs"] = (d["imag"] if d["real"] == "0" else d["real"]).lstrip("-")
        else:
            out["abs"] = enclosed_string(size, self.digits)
        if d["real"] == "0":
            out["zeta"] = "0"
        elif d["imag"] == "0":
            out["zeta"] = "1"           # a real eigenvalue: no oscillation
        else:
            out["zeta"] = enclosed_string(-re / size, self.digits)
        return out

    def __str__(self) -> str:
        d = self.to_dict()
        if d["real"] == "0":
            return f"{d['imag']}i" + (f" (x{self.multiplicity})" if self.multiplicity > 1 else "")
        sign = "" if d["imag"].startswith("-") else "+"
        return f"{d['real']}{sign}{d['imag']}i" + (
            f" (x{self.multiplicity})" if self.multiplicity > 1 else "")


@dataclass(frozen=True, repr=False)
class Spectrum(Tabular):
    """Eigenvalues of a model, ascending by ``Im lam``, with how they were found.

    Iterating gives the :class:`Eigenvalue` objects; ``len`` counts them
    without multiplicity, :attr:`total` with it.
    """

    eigenvalues: tuple
    digits: int
    method: str
    evaluations: int
    seconds: float
    model_name: str = ""
    omega_scale: tuple | None = None  # (beam name, sqrt(EI/(m L^4))) for Omega = beta L
    notes: tuple = field(default_factory=tuple)
    title: str = ""

    def __iter__(self):
        return iter(self.eigenvalues)

    def __len__(self):
        return len(self.eigenvalues)

    def __getitem__(self, i):
        return self.eigenvalues[i]

    @property
    def total(self) -> int:
        """Number of eigenvalues counted with multiplicity."""
        return sum(e.multiplicity for e in self.eigenvalues)

    def omegas(self, expand: bool = False) -> list:
        """Circular frequencies (mpmath numbers); with ``expand``, repeated by multiplicity."""
        out = []
        for e in self.eigenvalues:
            out += [e.omega] * (e.multiplicity if expand else 1)
        return out

    def Omegas(self, expand: bool = False) -> list:
        """Frequency parameters ``Omega = (omega^2 m L^4/EI)^(1/4)`` of the reference beam."""
        if not self.omega_scale:
            raise ValueError("no reference beam")
        return [_global(self._Omega(w)) for w in self.omegas(expand)]

    def _Omega(self, omega):
        """``sqrt(omega / scale)`` at the spectrum's digits (a private context's number)."""
        ctx = _context(self.digits + 10)
        return ctx.sqrt(ctx.mpf(omega) / ctx.mpf(self.omega_scale[1]))

    def proofs(self) -> dict:
        """What backs the eigenvalues: proof -> the positions (1-based) it backs."""
        out: dict = {}
        for i, e in enumerate(self.eigenvalues, 1):
            if e.proof:
                out.setdefault(e.proof, []).append(i)
        return out

    def with_model_name(self, name: str, title: str | None = None) -> Spectrum:
        """The same spectrum labelled with ``name`` (the model file, in JSON) and, if given,
        the model's title."""
        return replace(self, model_name=name, title=self.title if title is None else title)

    @property
    def damped(self) -> bool:
        """True when some eigenvalue has a real part (the model has dashpots that act)."""
        return any(e.lam.real != 0 for e in self.eigenvalues)

    def _eigenvalue_dict(self, e: Eigenvalue) -> dict:
        q = e.quantities()
        out = e.to_dict() | {"hz": q["hz"]}
        if e.digits != self.digits:
            # (a grid search backs some eigenvalues with more digits than the fewest)
            out["digits"] = e.digits
        if self.damped:
            out |= {"abs": q["abs"], "zeta": q["zeta"]}
        return out

    def to_dict(self) -> dict:
        """The JSON object of ``symtmm solve --json``: per eigenvalue also ``"hz"`` and, in a
        damped spectrum, ``"abs"`` and ``"zeta"`` (:meth:`Eigenvalue.quantities`)."""
        return header(self.model_name, self.title, self.digits, self.notes) | {
            "eigenvalues": [self._eigenvalue_dict(e) for e in self.eigenvalues],
            "stats": {"evaluations": self.evaluations, "seconds": round(self.seconds, 6),
                      "method": self.method},
        }

    def to_json(self) -> str:
        """:meth:`to_dict` as a JSON string."""
        return dumps(self.to_dict())

    def records(self):
        """``(columns, rows)``: one row per eigenvalue, the parts as the table prints them,
        ``hz``, in a damped spectrum ``abs`` and ``zeta``, undamped ``Omega`` of the reference
        beam (:mod:`symtmm.tables`: ``to_csv``, ``to_frame``)."""
        damped = self.damped
        omega_column = bool(self.omega_scale) and not damped
        columns = ["index", "real", "imag", "multiplicity", "hz"]
        columns += ["abs", "zeta"] if damped else []
        columns += ["Omega"] if omega_column else []
        columns.append("proof")
        rows = []
        for i, e in enumerate(self.eigenvalues, 1):
            d, q = e.to_dict(), e.quantities()
            row = [i, d["real"], d["imag"], e.multiplicity, q["hz"]]
            row += [q["abs"], q["zeta"]] if damped else []
            row += [e.frequency_parameter(self.omega_scale[1])] if omega_column else []
            rows.append(row + [e.proof])
        return columns, rows

    def _rows(self, unicode: bool, hz: bool = False):
        """Header and rows of the tables (text, HTML, LaTeX): damped spectra show
        ``|lam|`` and the damping ratio, undamped ones ``Omega`` of the reference beam;
        ``hz`` adds the frequency ``Im lam / 2 pi`` in Hz."""
        damped = self.damped
        ref = self.omega_scale[0] if self.omega_scale and not damped else None
        if damped:
            head = (["#", "Re λ [1/s]", "Im λ = ω [rad/s]", "|λ| [rad/s]", "ζ"] if unicode else
                    ["#", "Re lam [1/s]", "Im lam = omega [rad/s]", "|lam| [rad/s]", "zeta"])
        else:
            head = ["#", "ω [rad/s]" if unicode else "omega [rad/s]"]
        if hz:
            head.append("f [Hz]")
        if ref:
            head.append(f"Ω (beam {ref})" if unicode else f"Omega (beam {ref})")
        head.append("mult.")
        rows = []
        for i, e in enumerate(self.eigenvalues, 1):
            d = e.to_dict()
            row = [str(i)]
            q = e.quantities() if damped or hz else {}
            if damped:
                row += [d["real"], d["imag"], q["abs"], q["zeta"]]
            else:
                row.append(d["imag"])
            if hz:
                row.append(q["hz"])
            if ref:
                row.append(e.frequency_parameter(self.omega_scale[1]))
            rows.append(row + [str(e.multiplicity)])
        return head, rows

    def table(self, hz: bool = False) -> str:
        """A readable table (the ``symtmm solve`` output); ``hz`` adds the frequency in Hz
        (``solve --hz``), every digit backed as the eigenvalue's are."""
        head, rows = self._rows(unicode=False, hz=hz)
        lines = text_lines(head, rows)
        lines.append(f"{self.total} eigenvalue(s) with multiplicity, {self.digits} significant "
                     f"digits; method {self.method}, {self.evaluations} evaluations, "
                     f"{self.seconds:.3f} s")
        proofs = self.proofs()
        if proofs:
            lines.append("proved by " + "; ".join(
                f"{proof} ({', '.join(map(str, numbers))})" if len(proofs) > 1 else proof
                for proof, numbers in proofs.items()))
        lines += list(self.notes)
        return "\n".join(lines)

    # -- Jupyter --------------------------------------------------------------------
    def _display_rows(self):
        """Header and rows shared by the HTML and LaTeX forms."""
        return self._rows(unicode=True)

    def _repr_html_(self) -> str:
        """An HTML table (Jupyter)."""
        head, rows = self._display_rows()
        return html_table(head, rows, note=(
            f"{self.total} eigenvalue(s) with multiplicity, {self.digits} significant digits; "
            f"method {self.method}, {self.evaluations} evaluations, {self.seconds:.3f} s"))

    def _repr_latex_(self) -> str:
        """A LaTeX array (Jupyter, documents)."""
        head, rows = self._display_rows()
        tex = {"#": r"\#", "ω [rad/s]": r"\omega\ [\mathrm{rad/s}]",
               "Re λ [1/s]": r"\mathrm{Re}\,\lambda\ [1/\mathrm{s}]",
               "Im λ = ω [rad/s]": r"\mathrm{Im}\,\lambda = \omega\ [\mathrm{rad/s}]",
               "|λ| [rad/s]": r"|\lambda|\ [\mathrm{rad/s}]", "ζ": r"\zeta",
               "mult.": r"\mathrm{mult.}"}
        ref = self.omega_scale[0] if self.omega_scale else ""
        return latex_array([tex.get(h, r"\Omega\ (" + latex_text("beam " + ref) + ")")
                            for h in head], rows)
