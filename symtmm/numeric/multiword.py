"""Ball factorisations of beam models in compiled multi-word balls.

A proof factorises ``K(omega)`` in Arb balls a few times per root, and there every ball
operation is a Python call (0.1-0.2 us, most of it the call). Where the model is
made of Euler–Bernoulli segments and general beams (axial force, rotary
inertia, shear), the same kernel (the series of the ``c_j`` and
:func:`~symtmm.numeric.stiffness.eb_stiffness`; the series in ``(t, d)`` of
:func:`~symtmm.numeric.segments.theory_matrices` and the stiffness of one beam; the plan's
scatter, the band ``LDL^T``) runs in C (``_multiword.c``) on balls whose midpoint takes
``N`` 64-bit words (:func:`tiers`): a double-double for 2 (about 106 bits), else a binary
floating-point number of an ``N``-word mantissa (192 to 320 bits), and whose radius
bounds every cut and rounding. A point whose every pivot ball there
excludes zero has its pivots, signs and ``Delta`` proved as in Arb. Where the points or
the dashpots are complex (damped models), a complex ball is a pair of real ones, a
rectangle as Arb's ``acb``, each operation composed of the real balls' enclosures.
The same kernel over plain doubles (one word, no radius: not an enclosure) builds the
double-precision batches' band (:func:`double_band`), real or complex; there the values of
the 4-state kinds it does not compute, long Euler–Bernoulli pieces beyond its series' reach
(:func:`~symtmm.numeric.plan.long_piece`), condensed chains of one beam and rods, are given
to it by numpy (:func:`_given`), and it scatters and eliminates them with the rest.

The other points are factorised in Arb at the precision asked, as before: where a pivot
ball holds zero (the radii grow along the band, by up to ``2**40`` on example 1 and more
on long chains; or the point lies closer to a root than the words resolve). A tiny pivot
beside a large coupling (a leading sub-structure near one of its eigenvalues) is
eliminated as a 2x2 block with the next freedom, whose inverse does not multiply the
radii by the square of their ratio; a point still undecided is tried with one word more,
and in the last tier also with the freedoms the other way round.

The results are balls of the arithmetic asked for (:class:`~symtmm.numeric.arith.Ball`),
as rigorous as Arb's: each pivot about its leading double, widened by the rest (its
consumers need its sign, proved already, and an approximate value), and ``Delta`` whole,
from a running product in the words
(:attr:`~symtmm.numeric.stiffness.Factors.products`: the secant steps of a proof at 50
digits need every digit of it).

Examples
--------
A pinned-pinned beam's first natural frequency is ``pi**2``: the counts on either side,
proved in multi-word balls.

>>> from symtmm.model import Beam, Model
>>> from symtmm.numeric.arith import Ball
>>> from symtmm.roots.count import Counter
>>> c = Counter(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 100.0)
>>> c.counts([9.8696044010893, 9.8696044010894], Ball(150)).tolist()
[0, 1]
"""

from __future__ import annotations

import functools
import math
import struct
from fractions import Fraction

import numpy as np

from ..deadline import check as check_time
from ..expr import exact_float
from .arith import Ball, exact_key
from .parallel import run_ranges
from .segments import kind_size

try:        # the compiled balls (setup.py); without a compiler every ball runs in Arb
    from . import _band, _multiword
except ImportError:  # pragma: no cover - tested by switching it off
    _band = _multiword = None

#: Whether ball factorisations are tried in multi-word balls first; tests switch it off
#: to run Arb alone.
ENABLED = _multiword is not None

#: The fewest and the most words of a midpoint (as compiled).
MIN_WORDS, MAX_WORDS = 2, 12
#: The most words of a complex ball's parts (as compiled).
MAX_COMPLEX_WORDS = 8

#: The most terms of the series of the ``c_j``; each takes the fewest whose tail is below
#: the words' resolution (``2**-106`` for a double-double, ``2**-(64 N)`` else; the pieces'
#: ``|x| <= 81``: about 22 terms at 5 words, 32 at 8, 9 for ``|x| < 1``; at most 40, the last
#: ``1/163!`` within the compiled balls' exponents: beyond 11 words the largest ``|x|`` keep
#: a tail of about ``2**-735`` in their radii).
TERMS = 40

_MASK = (1 << 64) - 1

#: The segment families the compiled kernel holds, by its codes: Euler–Bernoulli
#: (``eb_stiffness``) and general beams (axial force, rotary inertia, shear:
#: ``theory_matrices`` and the stiffness of one beam).
_FAMILIES = {"eb": 0, "theory": 1}
#: The code of a kind whose values the caller passes in (``given``, double batches only,
#: :func:`_given`): an Euler–Bernoulli kind of a long plan that may be long at its range
#: (``|x|`` beyond a short piece's), a rod's, a condensed chain's of one beam.
_GIVEN = 2


def serves(plan, ar, lam2, lam) -> bool:
    """Whether a ball batch at ``lam2`` (``lam`` too with dashpots) can be tried in balls
    of words: real balls, or complex ones (pairs of real balls) where the points or the
    dashpots are complex."""
    if not (ENABLED and isinstance(ar, Ball) and tiers(ar.prec, plan.n) and plan.n
            and (lam is not None or not plan.damped)
            and not getattr(ar, "closed_stiffness", False)):
        return False
    if not _beams_only(plan):
        return False
    kinds = (ar.flint.arb, ar.flint.acb)
    return all(isinstance(v, kinds) for v in np.asarray(lam2).reshape(-1)) and \
        (lam is None or all(isinstance(v, kinds) for v in np.asarray(lam).reshape(-1)))


def serves_double(plan, lam2, lam) -> bool:
    """Whether a double-precision batch at ``lam2`` (``lam`` too with dashpots) has its
    band built by the compiled kernel over plain doubles (:func:`double_band`)."""
    return (ENABLED and plan.n > 0 and (lam is not None or not plan.damped)
            and np.asarray(lam2).dtype in (np.float64, np.complex128)
            and (lam is None or np.asarray(lam).dtype in (np.float64, np.complex128))
            and _beams_only(plan, given=True))


def double_summary(plan, lam2, lam=None):
    """``(log|Delta|, arg Delta, counts, ok)`` of a double-precision batch, as
    :func:`~symtmm.numeric.stiffness.summary` gives them, by the compiled kernel a point
    at a time: each point's band built (:func:`double_band`'s series and scatter),
    factorised and read while it is in cache, and no batch of bands written. ``ok`` false
    where a value is not finite or beyond the series' reach (the caller takes those
    points the banded way). None where the plan's numbers do not fit doubles.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.numeric.plan import StiffnessPlan
    >>> plan = StiffnessPlan(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 1e4)
    >>> logabs, phase, counts, ok = double_summary(plan, -np.array([5.0, 12.0, 50.0]) ** 2)
    >>> counts.tolist(), ok.tolist()                  # roots (n pi)**2: 9.87, 39.5, 88.8
    ([0, 1, 2], [True, True, True])
    """
    from .arith import DOUBLE

    inputs = _double_inputs(plan, lam2, lam)
    if inputs is None:
        return None
    code, tabs, lam2, lam, given = inputs
    B, n, w = lam2.shape[0], plan.n, plan.width
    logabs, phase = np.empty(B), np.empty(B)
    counts, ok = np.empty(B, dtype=np.int64), np.zeros(B, dtype=np.uint8)
    mult = np.ascontiguousarray(plan.multiplicity, dtype=np.int64)

    W = 2 if code > COMPLEX else 1
    # a batch in slices of about CHECK_SECONDS each, the search's time budget checked
    # between them: a compiled call cannot be interrupted, and a contour's first grid on
    # a long beam on a stiff foundation (tens of thousands of points, 4.7 s a call) ran
    # 15 s past a 60 s budget
    step = max(1, int(CHECK_SECONDS / max(_batch_seconds(plan, 1, 1, W), 1e-12)))
    for start in range(0, B, step):
        if start:
            check_time()
        stop = min(B, start + step)

        def run(lo, hi, start=start):
            # (each part writes its own range of the outputs)
            lo, hi = start + lo, start + hi
            _multiword.summary(code, lam2[lo:hi], lam[lo:hi] if len(lam) else lam,
                               *_series_tables(tabs), given[lo:hi], n, w, mult, DOUBLE.TRUST,
                               DOUBLE.growth_limit, float(plan.log_constant), logabs[lo:hi],
                               phase[lo:hi], counts[lo:hi], ok[lo:hi])
        run_ranges(run, stop - start, _batch_seconds(plan, stop - start, 1, W))
    return logabs, phase, counts, ok.astype(bool)


#: Estimated seconds of one slice of a double batch between checks of the search's time
#: budget (:func:`double_summary`).
CHECK_SECONDS = 0.5


#: Seconds per entry of a point's band elimination (freedoms times the squared width) and
#: 64-bit word of its numbers, by words per real ball (1: doubles, 2: double-doubles, 3 or
#: more: integer words), as measured on the 20- and 50-level chains.
_SECONDS_PER_ENTRY = {1: 0.55e-9, 2: 3.2e-9, 3: 3.5e-9}


def _batch_seconds(plan, B: int, N: int, W: int) -> float:
    """The estimated seconds of ``B`` points of ``plan`` in balls of ``N`` words of ``W``
    64-bit words each (complex: both parts'): what decides whether a batch runs in parts
    (:func:`symtmm.numeric.parallel.run_ranges`)."""
    return B * _SECONDS_PER_ENTRY[min(N, 3)] * plan.n * plan.width ** 2 * W


def _double_inputs(plan, lam2, lam):
    """``(code, tables, lam2, lam, given)`` of a double batch for the compiled kernel:
    complex where ``lam2`` or ``lam`` is (``lam`` empty bytes without dashpots), and the
    values of the kinds it is given (:func:`_given`); None where the plan's numbers do not
    fit doubles."""
    tabs = _double_tables(plan)
    if tabs is None:
        return None
    complex_ = np.iscomplexobj(lam2) or (lam is not None and np.iscomplexobj(lam))
    dtype, code = (np.complex128, COMPLEX + 1) if complex_ else (np.float64, 1)
    # (from the points as they come: a real lam2 takes the foundation's real forms)
    given = np.ascontiguousarray(_given(tabs, lam2, lam), dtype=dtype)
    if complex_:
        # (once per plan: a damped search's batches are mostly complex)
        cache = plan.__dict__["_multiword_tables"]
        if ("complex", 1) not in cache:
            cache[("complex", 1)] = _complex_tables(tabs, 1)
        tabs = cache[("complex", 1)]
    return (code, tabs, np.ascontiguousarray(lam2, dtype=dtype),
            b"" if lam is None else np.ascontiguousarray(lam, dtype=dtype), given)


def _given(tabs: dict, lam2, lam=None) -> np.ndarray:
    """``(B, G, 17)``: per point the 16 entries and ``det U12`` of each kind the compiled
    kernel is given (:data:`_GIVEN`), in the kinds' order, by
    :func:`~symtmm.numeric.stiffness.stiffness_values` as
    :func:`~symtmm.numeric.stiffness.assemble` takes them (long Euler–Bernoulli kinds by
    the closed forms beyond a short piece's ``|x|`` and the series within): the same
    numbers, vectorised over the batch."""
    from .arith import DOUBLE
    from .stiffness import stiffness_values
    lam2 = np.asarray(lam2)
    B = lam2.shape[0]
    parts = [np.empty((B, 0, 17), dtype=lam2.dtype)]
    # (a value beyond the doubles fails its point, which numpy then takes whole)
    with np.errstate(all="ignore"):
        for table in tabs["given"]:
            D, det = stiffness_values(DOUBLE, [table], lam2, lam, long=True)
            G = det.shape[1]
            part = np.empty((B, G, 17), dtype=np.result_type(D, det))
            part[:, :, :16] = D.reshape(B, G, 16)
            part[:, :, 16] = det
            parts.append(part)
    return np.concatenate(parts, axis=1)


def _series_tables(tabs: dict) -> tuple:
    """The kernel's tables in the order of its ``assemble`` and ``summary``: the kinds,
    the c_j series and the general beams' series, the scatter."""
    return (tabs["kinds"], tabs["families"], tabs["coef"], tabs["tails"], TERMS,
            tabs["tcoef"], tabs["ttails"], tabs["TK"], tabs["targets"], tabs["source"],
            tabs["bcoef"], tabs["starts"])


def _beams_only(plan, given: bool = False) -> bool:
    """Every segment kind of the plan one the compiled kernel holds (:data:`_FAMILIES`), and
    no long piece (its series stop at ``|x|`` of a short one: :func:`~symtmm.numeric.plan.
    long_piece`); with ``given`` (double batches), also long pieces, rods and condensed
    chains of one beam: 4-state kinds whose values numpy gives it (:func:`_given`)."""
    if given:
        return all(family in _FAMILIES or kind_size((family, consts)) == 4
                   for family, consts in plan.kinds)
    return not plan.long and all(family in _FAMILIES for family, _ in plan.kinds)


#: The code of complex balls of ``N`` words in the compiled kernel (a real ball of ``N``
#: words for each part).
COMPLEX = 100


def _complex_tables(tabs: dict, N: int) -> dict:
    """The tables of real balls of ``N`` words as complex ones (imaginary parts 0)."""
    out = dict(tabs)
    for key in ("kinds", "coef", "tcoef", "bcoef"):
        real = tabs[key] if N > 1 else tabs[key][..., None].view(np.uint64)
        out[key] = np.ascontiguousarray(np.concatenate([real, np.zeros_like(real)], axis=-1))
    return out


def double_band(plan, lam2, lam=None):
    """``(K, det U12, ok)`` of :func:`~symtmm.numeric.stiffness.assemble` in double
    precision, by the compiled kernel over plain doubles (one word, no radius: the same
    series, stiffness and scatter as the balls', one call for the batch); complex where
    ``lam2`` or ``lam`` (the dashpots') is; ``ok`` false where a value is not finite or
    beyond the series' reach (the caller assembles those points in numpy). None where
    the plan's numbers do not fit doubles.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.numeric.arith import DOUBLE
    >>> from symtmm.numeric.plan import StiffnessPlan
    >>> from symtmm.numeric.stiffness import assemble
    >>> plan = StiffnessPlan(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), 1e4)
    >>> lam2 = -np.array([10.0, 50.0]) ** 2
    >>> K, det12, ok = double_band(plan, lam2)
    >>> K0, det0 = assemble(plan, DOUBLE, lam2)
    >>> bool(ok.all()), bool(np.allclose(K, K0, rtol=1e-12, atol=1e-12 * abs(K0).max()))
    (True, True)
    """
    inputs = _double_inputs(plan, lam2, lam)
    if inputs is None:
        return None
    code, tabs, lam2, lam, given = inputs
    B, n, w, dtype = lam2.shape[0], plan.n, plan.width, lam2.dtype
    S = tabs["families"].shape[0]
    band = np.empty((B, n * w), dtype=dtype)
    det12 = np.empty((B, S), dtype=dtype)
    ok = np.zeros(B, dtype=np.uint8)
    _multiword.assemble(code, lam2, lam, *_series_tables(tabs), given, band, det12,
                        np.empty(16 * S + 3, dtype=dtype), ok)
    return band.reshape(B, n, w), det12, ok.astype(bool)


def width(N: int) -> int:
    """64-bit words per ball of ``N`` words: a plain double's one (``N = 1``, no radius:
    :func:`double_band`), a double-double's three doubles (``N = 2``), else the mantissa's
    ``N`` words, the exponent, the sign and the radius."""
    return 1 if N == 1 else 3 if N == 2 else N + 3


def _up(x) -> float:
    """An exact number (an exact arb or a Fraction) as the least double not below it."""
    r = float(x)
    below = r < x if not isinstance(x, Fraction) else Fraction(r) < x
    return math.nextafter(r, math.inf) if below else r


def resolution(N: int) -> int:
    """The bits a midpoint of ``N`` words holds: 53 for a double, 106 for a double-double,
    else ``64 N``."""
    return 53 if N == 1 else 106 if N == 2 else 64 * N


def encode(v, flint, N: int) -> list:
    """A real arb ball as a ball of ``N`` words (:func:`width` unsigned 64-bit integers):
    its midpoint, an exact dyadic rational, as :func:`encode_rational` writes it, the
    radius widened by the ball's own."""
    man, exp = (int(x) for x in v.mid().man_exp())
    row = _encode_dyadic(man, exp, N)
    if N == 1:
        return row              # (a plain double keeps no radius)
    if v.rad() != 0:
        rm, re = (int(x) for x in v.rad().mid().man_exp())
        radius = _up(Fraction(rm << re) if re >= 0 else Fraction(rm, 1 << -re))
        r = math.nextafter(_double(row[-1]) + radius, math.inf)
        if not math.isfinite(r):
            raise OverflowError("a ball beyond the range of the compiled balls")
        row[-1] = _bits(r)
    return row


def _double(bits: int) -> float:
    """The double whose bits are ``bits`` (an unsigned 64-bit integer)."""
    return _F64.unpack(_U64.pack(bits))[0]


def _bits(x: float) -> int:
    """The bits of the double ``x`` as an unsigned 64-bit integer."""
    return _U64.unpack(_F64.pack(x))[0]


_F64, _U64 = struct.Struct("<d"), struct.Struct("<Q")


def _encode_dyadic(man: int, exp: int, N: int) -> list:
    """:func:`encode_rational` of ``man * 2**exp`` by shifts and the doubles' own
    conversions (a point's square: a batch's proofs encode every point), where the
    result's doubles are normal; else by :func:`_encode_ratio`."""
    a = abs(man)
    bits = a.bit_length()
    e = bits + exp                          # 2**(e-1) <= |x| < 2**e
    if N == 2 and man and bits <= 1000 and -900 < e < 900:
        hi = float(man)                     # (int to float rounds to nearest)
        rest = man - int(hi)
        lo = float(rest)
        cut = abs(rest - int(lo))
        r = float(cut)
        if r < cut:                          # (Python compares an int and a float exactly)
            r = math.nextafter(r, math.inf)
        hi, lo, r = math.ldexp(hi, exp), math.ldexp(lo, exp), math.ldexp(r, exp)
        # (scaled below the normal doubles, their rounding would not be exact)
        if (rest == 0 or abs(lo) >= _NORMAL) and (cut == 0 or r >= _NORMAL):
            return list(_WORDS3.unpack(_DOUBLES3.pack(hi, lo, r)))
    if man and N > 2:
        if not -1000 <= e <= 1000:
            raise OverflowError("a number beyond the range of the compiled balls")
        shift = 64 * N - bits
        top = a << shift if shift >= 0 else a >> -shift
        cut = shift < 0 and a & ((1 << -shift) - 1)
        r = math.ldexp(1.0, max(e - 64 * N, -1074)) if cut else 0.0
        words = list(struct.unpack(f">{N}Q", top.to_bytes(8 * N, "big")))
        return words + [e & _MASK, int(man < 0), _bits(r)]
    return _encode_ratio(man << exp, 1, N) if exp >= 0 else _encode_ratio(man, 1 << -exp, N)


_NORMAL = 2.0 ** -1000
_DOUBLES3, _WORDS3 = struct.Struct("<3d"), struct.Struct("<3Q")


def encode_rational(q: Fraction, N: int) -> list:
    """An exact rational as a ball of ``N`` words: its nearest double-double (``N = 2``) or
    its leading ``64 N`` bits, exponent and sign, the radius (a double, rounded up) bounding
    what that cuts off. No Arb on the way: the plans' numbers are mostly rationals."""
    return _encode_ratio(q.numerator, q.denominator, N)


def _encode_ratio(p: int, d: int, N: int) -> list:
    """:func:`encode_rational` of ``p / d`` (integers, ``d > 0``), in integer arithmetic
    (Python's ``int / int`` rounds correctly); for ``N = 1`` the nearest double alone."""
    if N == 1:
        value = p / d
        if not math.isfinite(value):
            raise OverflowError("a number beyond the range of doubles")
        return [_bits(value)]
    if N == 2:
        hi = p / d
        hn, hd = hi.as_integer_ratio()
        rn, rd = p * hd - hn * d, d * hd              # the rest, p/d - hi, exactly
        lo = rn / rd
        ln, ld = lo.as_integer_ratio()
        cn, cd = abs(rn * ld - ln * rd), rd * ld      # what the double-double cuts off
        r = cn / cd
        rn_, rd_ = r.as_integer_ratio()
        if rn_ * cd < cn * rd_:
            r = math.nextafter(r, math.inf)
        if not (math.isfinite(hi) and abs(hi) < 2.0 ** 1000 and math.isfinite(r)):
            raise OverflowError("a number beyond the range of the compiled balls")
        return [_bits(hi), _bits(lo), _bits(r)]
    if p == 0:
        return [0] * (N + 3)
    a = abs(p)
    e = a.bit_length() - d.bit_length() + 1          # |p/d| < 2**e
    if a * (1 << max(0, 1 - e)) < d * (1 << max(0, e - 1)):
        e -= 1                                        # now 2**(e-1) <= |p/d| < 2**e
    if not -1000 <= e <= 1000:
        raise OverflowError("a number beyond the range of the compiled balls")
    shift = 64 * N - e
    num, den = (a << shift, d) if shift >= 0 else (a, d << -shift)
    top, rem = divmod(num, den)
    r = math.ldexp(1.0, max(e - 64 * N, -1074)) if rem else 0.0
    words = [(top >> (64 * (N - 1 - k))) & _MASK for k in range(N)]
    return words + [e & _MASK, int(p < 0), _bits(r)]


#: Exact numbers already encoded, by ``(number, words)``: a model's plans, and a sweep's
#: steps, share most of their coefficients (powers of two, its springs' constants).
_ENCODED: dict = {}


def _exact_balls(values, ar: Ball | None, N: int) -> list:
    """Exact SymPy numbers as balls of ``N`` words: rationals directly, others through
    their Arb enclosures (``ar``; for a plain double, ``N = 1``, the nearest float, no Arb
    needed); each number converted once (:data:`_ENCODED`)."""
    import sympy as sp
    out = []
    for v in values:
        # (a 20-level chain's tables look up 800 numbers per number of words)
        key = (exact_key(v), N)
        hit = _ENCODED.get(key)
        if hit is None:
            v_ = sp.sympify(v)
            if v_.is_Rational:
                hit = encode_rational(Fraction(int(v_.p), int(v_.q)), N)
            elif N == 1:
                value = exact_float(v_)
                if not math.isfinite(value):
                    raise OverflowError("a number beyond the range of doubles")
                hit = [_bits(value)]
            else:
                with ar:
                    hit = encode(ar.exact(v_), ar.flint, N)
            if len(_ENCODED) >= 1 << 16:
                _ENCODED.clear()
            _ENCODED[key] = hit
        out.append(hit)
    return out


def _parts(row) -> tuple:
    """``(mantissa, exponent, radius)`` of a ball of words: its midpoint is ``mantissa *
    2**exponent`` (integers; for a double-double the sum of its two doubles) exactly."""
    return _parts_of_bytes(np.ascontiguousarray(row, dtype=np.uint64).tobytes())


def _parts_of_bytes(raw: bytes) -> tuple:
    """:func:`_parts` of a ball's words as their bytes (little-endian)."""
    if len(raw) == 24:
        hi, lo, r = _DOUBLES3.unpack(raw)
        (hn, hd), (ln, ld) = hi.as_integer_ratio(), lo.as_integer_ratio()
        d = max(hd, ld)                                 # (powers of two)
        return hn * (d // hd) + ln * (d // ld), -(d.bit_length() - 1), r
    N = len(raw) // 8 - 3
    words = struct.unpack(f"<{N}Qqqd", raw)
    m = int.from_bytes(struct.pack(f">{N}Q", *words[:N]), "big")
    e, sign, r = words[N:]
    return (-m if sign else m), e - 64 * N, r


def decode(row) -> tuple:
    """``(midpoint, radius)`` of a ball of words as Fractions (exact)."""
    m, e, r = _parts(row)
    return Fraction(m) * Fraction(2) ** e, Fraction(r)


def _encoded(values, flint, N: int, complex_: bool = False) -> np.ndarray:
    """Arb balls as balls of ``N`` words ``(len, words)``; complex ones (the real part's
    words, then the imaginary part's) if asked."""
    if complex_:
        parts = [(z.real, z.imag) for z in (flint.acb(v) for v in values)]
        return np.array([encode(re, flint, N) + encode(im, flint, N) for re, im in parts],
                        dtype=np.uint64).reshape(len(values), 2 * width(N))
    # (an exact square keeps its mantissa and exponent: Arb's midpoint of it costs more
    # than the encoding itself, Ball.negated_squares)
    return np.array([encode(v, flint, N) if getattr(v, "dyadic", None) is None else
                     _encode_dyadic(*v.dyadic, N) for v in values],
                    dtype=np.uint64).reshape(len(values), width(N))


@functools.cache
def _inverse_factorials(N: int, count: int) -> tuple:
    """``1/k!`` for ``k < count``: as balls of ``N`` words ``(count, width)`` and as upper
    bounds in doubles (exact rationals: no Arb on the way)."""
    values = [Fraction(1, math.factorial(k)) for k in range(count)]
    return (np.array([encode_rational(v, N) for v in values], dtype=np.uint64),
            np.array([_up(v) for v in values]))


def _series(N: int):
    """The balls of ``1/(4k + j)!`` (``(4, TERMS, width)``) and upper bounds of them as
    doubles (``(4, TERMS + 1)``: the tails), for the ``c_j``."""
    balls, ups = _inverse_factorials(N, 4 * TERMS + 4)
    coef = balls[:4 * TERMS].reshape(TERMS, 4, -1).transpose(1, 0, 2)
    return np.ascontiguousarray(coef), np.ascontiguousarray(ups.reshape(TERMS + 1, 4).T)


@functools.cache
def _words_arithmetic(N: int) -> Ball:
    """The Arb arithmetic that encloses irrational constants for balls of ``N`` words (a
    word more than they hold)."""
    return Ball(64 * N + 64)


@functools.cache
def _theory_series(N: int):
    """``(TK, 1/k! for k < 2 TK + 2 as balls, (2 TK/(2 TK)!, 2 TK/(2 TK + 1)!) rounded up)``:
    the general beams' series in ``(t, d)`` (:func:`~symtmm.numeric.segments._series`) to
    the words' bits."""
    K = 2
    # (at most 80: 1/161! is the last within the compiled balls' exponents)
    while K < 80 and math.log2(K) - math.lgamma(2 * K + 1) / math.log(2) > -(resolution(N) + 4):
        K += 1
    balls, _ = _inverse_factorials(N, 2 * K + 2)
    tails = np.array([_up(Fraction(2 * K, math.factorial(2 * K + i))) for i in (0, 1)])
    return K, balls, tails


def _tables(plan, N: int) -> dict | None:
    """The plan's constants as balls of ``N`` words, from its exact numbers (None where one
    does not fit), once per plan and number of words (whatever the precision asked: the
    rationals are encoded exactly, the others from Arb a word beyond the words)."""
    cache = plan.__dict__.setdefault("_multiword_tables", {})
    if N in cache:
        return cache[N]
    ar = _words_arithmetic(N) if N > 1 else None     # (doubles need no Arb)
    try:
        kinds, families = [], []
        for family, values in _kind_values(plan):
            kinds += _exact_balls(values, ar, N)
            families.append(_FAMILIES[family])
        # (each distinct coefficient encoded once: most are a few powers of two and the
        # springs' constants, and a SymPy number's hash costs a microsecond)
        unique, index = plan.distinct_coefficients()
        encoded = np.array(_exact_balls(unique, ar, N), dtype=np.uint64).reshape(
            len(unique), width(N))
    except OverflowError:
        cache[N] = None
        return None
    scatter = _scatter(plan)
    coef, tails = _series(N)
    TK, tcoef, ttails = _theory_series(N)
    out = cache[N] = {
        "kinds": np.array(kinds, dtype=np.uint64).reshape(-1, 8, width(N)),
        "families": np.array(families, dtype=np.int64), "coef": coef, "tails": tails,
        "TK": TK, "tcoef": tcoef, "ttails": ttails,
        "targets": scatter["targets"], "source": scatter["source"],
        "bcoef": np.ascontiguousarray(encoded[index[scatter["terms"]]]),
        "starts": scatter["starts"]}
    return out


def _scatter(plan) -> dict:
    """The plan's scatter for the compiled kernel, arithmetic apart: ``targets``,
    ``source`` and ``terms`` (indices of its coefficients) of every term, layer after layer
    (:meth:`~symtmm.numeric.plan.StiffnessPlan.layer_maps`), and where each layer starts
    (``starts``); once per plan, for every arithmetic."""
    cached = plan.__dict__.get("_multiword_scatter")
    if cached is None:
        layers = plan.layer_maps()
        empty = np.zeros(0, dtype=np.int64)
        cached = plan.__dict__["_multiword_scatter"] = {
            key: np.ascontiguousarray(np.concatenate(
                [empty] + [np.asarray(layer[i], dtype=np.int64) for layer in layers]))
            for i, key in enumerate(("targets", "source", "terms"))}
        cached["starts"] = np.cumsum([0] + [len(tg) for tg, _, _ in layers]).astype(np.int64)
    return cached


#: The columns of a kind's constants in the compiled kernel, by family (zeros after them).
_COLUMNS = {"eb": ("EI", "l", "A", "F"), "theory": ("EI", "a", "b", "cN", "rhoI", "m", "kw", "l")}


def _double_tables(plan) -> dict | None:
    """:func:`_tables` for plain doubles (one word), from the plan's double-precision
    tables (the numbers numpy's band uses; no SymPy on the way); None where one is not
    finite."""
    from .arith import DOUBLE
    from .stiffness import LONG_X
    cache = plan.__dict__.setdefault("_multiword_tables", {})
    if 1 in cache:
        return cache[1]
    t = plan.tables(DOUBLE)
    kinds, families, given = [np.zeros((0, 8))], [], []
    for family, consts in t["kinds"]:           # (grouped by family, in the plan's order)
        if family not in _FAMILIES:
            # a condensed chain's (a table of its own), or the rods' (a table for all of
            # them): given whole (:func:`_given`)
            count = 1 if family == "condensed" else len(consts["l"])
            kinds.append(np.zeros((count, 8)))
            families += [_GIVEN] * count
            given.append((family, consts))
            continue
        cols = [np.asarray(consts[c], dtype=float) for c in _COLUMNS[family]]
        block = np.zeros((cols[0].size, 8))
        block[:, :len(cols)] = np.stack(cols, axis=1)
        kinds.append(block)
        codes = np.full(cols[0].size, _FAMILIES[family])
        if family == "eb" and plan.long:
            # a kind whose |x| may pass a short piece's over the plan's range takes
            # numpy's closed forms there (the compiled series stop at a short one's)
            long = plan.radius * np.abs(consts["A"]) + np.abs(consts["F"]) >= LONG_X
            if long.any():
                codes[long] = _GIVEN
                given.append(("eb", {c: np.asarray(consts[c])[long]
                                     for c in _COLUMNS[family]}))
        families += codes.tolist()
    kinds = np.concatenate(kinds)
    bcoef = np.concatenate([np.zeros(0)] + [np.asarray(c, dtype=float) for _, _, c in t["layers"]])
    if not (np.isfinite(kinds).all() and np.isfinite(bcoef).all()):
        cache[1] = None
        return None
    scatter = _scatter(plan)
    coef, tails = _series(1)
    TK, tcoef, ttails = _theory_series(1)
    out = cache[1] = {
        "kinds": kinds, "families": np.array(families, dtype=np.int64), "coef": coef,
        "tails": tails, "TK": TK, "tcoef": tcoef, "ttails": ttails,
        "targets": scatter["targets"], "source": scatter["source"], "bcoef": bcoef,
        "starts": scatter["starts"], "given": given}
    return out


def _kind_values(plan) -> list:
    """Per segment kind ``(family, its 8 exact constants)`` in the compiled kernel's order
    (:data:`_COLUMNS`), once per plan for every number of words."""
    import sympy as sp

    from .segments import eb_exact
    cached = plan.__dict__.get("_kind_values")
    if cached is None:
        cached = []
        for family, consts in plan.kinds:
            if family == "eb":
                values = list(eb_exact(*consts)) + [sp.Integer(0)] * 4
            else:               # (EI, a, b, cN, rhoI, m, kw, l)
                values = [sp.sympify(v) for v in consts]
            cached.append((family, values))
        plan.__dict__["_kind_values"] = cached
    return cached


def tiers(prec: int, n: int) -> list:
    """The numbers of words a batch asking ``prec`` bits of a plan of ``n`` freedoms is tried
    in, in turn (the points a tier leaves undecided go to the next, then to Arb).

    The bits asked less the quarter of a bit per freedom that the ball elimination adds
    for the growth of its radii (:meth:`~symtmm.numeric.evaluator.Evaluator._ball`), to
    the nearest word, then one word more: 2 and 3 words for the proofs at 15 digits (144
    bits), 3 and 4 at 30, 4 and 5 at 50. None beyond 12 words.
    """
    first = max(MIN_WORDS, round((prec - n // 4) / 64))
    return [N for N in (first, first + 1) if N <= MAX_WORDS]


def factor(plan, ar: Ball, lam2, reverse: bool = False, lam=None):
    """:func:`~symtmm.numeric.stiffness.factor` of a plan of beams in balls: the points
    decided in multi-word balls (:func:`tiers`), the rest in ``ar`` (Arb). Complex balls
    where the points or the dashpots (``lam``) are complex: there every pivot is decided
    when its ball excludes 0, and the signs are 0 (as Arb's complex factorisation)."""
    from .stiffness import BandRows, Factors, _ldl, assemble, reversed_band

    flint = ar.flint
    lam2 = np.asarray(lam2, dtype=object)
    lam = None if lam is None else np.asarray(lam, dtype=object)
    # (complex where a point or a dashpot's lam is: a damped model counted without its
    # dashpots passes real zeros)
    complex_ = any(isinstance(v, flint.acb) for v in lam2) or \
        (lam is not None and any(isinstance(v, flint.acb) for v in lam))
    B, n = lam2.shape[0], plan.n
    pivots = np.empty((B, n), dtype=object)
    dets = np.empty((B, len(plan.multiplicity)), dtype=object)
    products = np.full(B, None, dtype=object)
    signs = (np.zeros if complex_ else np.ones)((B, n), dtype=np.int8)
    todo = np.arange(B)
    # a tier that decided under half of a batch of several points is not tried again for
    # this plan while a next one remains: the proofs' batches all lie about roots, where
    # the smallest pivot is tiny and the radii's growth along a long band leaves the words
    # too few bits for it (the 50-level chain at 15 digits: two words, eliminating from
    # both ends, decided 4 of its first 10 points and would decide 2 of the next 20, the
    # narrower pairs); points away from roots then take a word more than they need, at
    # less cost than a tier that fails
    failed = plan.__dict__.setdefault("_multiword_failed", set())
    tried = tiers(ar.prec, n)
    tried = [N for N in tried[:-1] if (N, complex_) not in failed] + tried[-1:]
    for N in tried:
        if not todo.size or (complex_ and N > MAX_COMPLEX_WORDS):
            break
        done = _decided(plan, ar, lam2[todo], reverse, N,
                        None if lam is None else lam[todo], complex_,
                        other_order=(N == tried[-1]))
        if done is None:
            break
        ok, piv, det12 = done
        if todo.size >= 3 and 2 * ok.sum() < todo.size:
            failed.add((N, complex_))
        if ok.any():
            # (of a point decided here the callers read the count, from the signs, and
            # Delta, from the product: its pivots and det U12 stay None, as Factors says;
            # as Arb balls they cost a quarter of a 20-level chain's batch. A point whose
            # product left the words' range goes on, as an undecided one)
            with ar:
                got = _product(plan, piv, det12, flint, N, complex_)
            have = np.array([v is not None for v in got], dtype=bool)
            ok[np.nonzero(ok)[0][~have]] = False
            products[todo[ok]] = got[have]
            if not complex_:
                signs[todo[ok]] = _signs(piv[have])
        todo = todo[~ok]
    with ar:
        fa = Factors(plan, ar, pivots, signs, np.ones((B, n), dtype=bool), dets,
                     BandRows({}), products)
        if todo.size:
            K, d12 = assemble(plan, ar, lam2[todo], None if lam is None else lam[todo])
            if reverse:
                K = reversed_band(K)
            fa = fa.replaced(todo, _ldl(plan, ar, K, d12, reverse))
    return fa


def _product(plan, piv, det12, flint, N: int, complex_: bool = False) -> np.ndarray:
    """Per point the product of its pivots and of ``det U12`` to the plan's multiplicities,
    in balls of ``N`` words (as the factorisation's), as Arb balls at the working
    precision: ``Delta`` but for the plan's constant, to every bit the words carry (the
    pivots kept are about their leading double only)."""
    B, n, W = piv.shape
    x = np.ascontiguousarray(np.concatenate([piv, det12], axis=1))
    k = np.concatenate([np.ones(n, dtype=np.int64), np.asarray(plan.multiplicity,
                                                               dtype=np.int64)])
    out = np.empty((B, W + 1), dtype=np.uint64)
    ok = np.zeros(B, dtype=np.uint8)
    _multiword.power_product(COMPLEX + N if complex_ else N, x, k, out, ok)
    products = np.full(B, None, dtype=object)
    # (then the power of two the running product was rescaled by: Delta leaves the
    # doubles' range; folded into the exponents, exactly)
    shifts = out[:, W].view(np.int64).tolist()
    if complex_:
        for p in np.nonzero(ok)[0]:
            products[p] = flint.acb(_arb_of(out[p, :W // 2], flint, shifts[p]),
                                    _arb_of(out[p, W // 2:W], flint, shifts[p]))
        return products
    # (the rows' bytes at once: a numpy row per point cost a small batch a twentieth)
    raw, size = np.ascontiguousarray(out[:, :W]).tobytes(), 8 * W
    for p in np.nonzero(ok)[0].tolist():
        products[p] = WordProduct(*_parts_of_bytes(raw[size * p:size * (p + 1)]), shifts[p])
    return products


class WordProduct:
    """A real product of the words, kept as they give it: the midpoint ``mantissa *
    2**exponent`` and the radius ``radius * 2**shift`` exactly, turned into an arb only
    where one is asked for (:meth:`arb`). A proof's secant steps read the midpoint and the
    radius alone (:meth:`~symtmm.numeric.stiffness.Factors.midpoints`): the arb and
    its conversion to mpmath cost a third of a small model's ball batch.
    """

    __slots__ = ("exponent", "mantissa", "radius", "shift")

    def __init__(self, mantissa: int, exponent: int, radius: float, shift: int):
        self.mantissa, self.exponent, self.radius, self.shift = mantissa, exponent + shift, \
            radius, shift

    def arb(self, flint):
        """The ball as an arb, exactly."""
        rn, rd = self.radius.as_integer_ratio()            # (rd: a power of two)
        return flint.arb((self.mantissa, self.exponent),
                         (rn, self.shift - (rd.bit_length() - 1)))


def _arb_of(words, flint, shift: int = 0):
    """The ball of words ``words`` times ``2**shift`` as an arb, exactly: its midpoint
    from the mantissa and exponent, its radius from the double's."""
    return WordProduct(*_parts(words), shift).arb(flint)


def _decided(plan, ar: Ball, lam2, reverse: bool, N: int, lam=None, complex_: bool = False,
             other_order: bool = True):
    """``(ok, pivots, det U12)`` of the points ``lam2`` (``lam``: the dashpots') in balls
    of ``N`` words, complex ones if asked: ``ok`` per point whether every pivot was
    decided, the pivot and ``det U12`` balls of those points ``(..., words)``; None where
    the plan's numbers do not fit the compiled balls. A real point left undecided is
    eliminated again from both ends toward its mode's peak (:func:`_twisted`);
    ``other_order``: one still undecided, with its freedoms the other way round (the last
    tier's call: before it, the next tier decides more of them for less, as the other
    order eliminates the whole band where the first stopped at the undecided pivot)."""
    tabs = _tables(plan, N)
    if tabs is None:
        return None
    code, W = N, width(N)
    if complex_:
        cache = plan.__dict__["_multiword_tables"]
        if ("complex", N) not in cache:
            cache[("complex", N)] = _complex_tables(tabs, N)
        tabs, code, W = cache[("complex", N)], COMPLEX + N, 2 * W
    B, n, w = lam2.shape[0], plan.n, plan.width
    try:
        with ar:
            points = _encoded(lam2, ar.flint, N, complex_)
            lams = b"" if lam is None else _encoded(lam, ar.flint, N, complex_)
    except OverflowError:
        return None
    S = tabs["families"].shape[0]

    def run(lo, hi):
        # the points lo .. hi - 1, built and eliminated (the compiled calls release
        # Python's lock: parts of a large batch run at once); their pivots, and the bands
        # of those left undecided, for the retries below
        band = np.empty((hi - lo, n * w, W), dtype=np.uint64)
        det12 = np.empty((hi - lo, S, W), dtype=np.uint64)
        ok = np.zeros(hi - lo, dtype=np.uint8)
        _multiword.assemble(code, points[lo:hi], lams[lo:hi] if len(lams) else lams,
                            *_series_tables(tabs), b"", band, det12,
                            np.empty((16 * S + 3, W), dtype=np.uint64), ok)
        band = band.reshape(hi - lo, n, w, W)
        built = ok.copy()
        pivots = _eliminated(band, reverse, ok, code)[:, :n, 0, :]
        failed = np.nonzero(built & (ok == 0))[0]
        return ok, pivots, det12, failed + lo, band[failed]

    parts = run_ranges(run, B, _batch_seconds(plan, B, N, W))
    ok, pivots, det12, again, bands = parts[0] if len(parts) == 1 else \
        tuple(np.concatenate(x) for x in zip(*parts))
    if len(again) and not complex_:
        # a point near an eigenvalue whose mode is small at both ends of the band: the
        # last pivot of either order carries the radii grown along all of it; eliminated
        # from both ends toward the mode's largest freedom, each side's growth only (a
        # 10-level chain at 15 digits: 6 of its 30 proof points, which took three words)
        splits = _splits(plan, lam2[again])
        if splits is not None:
            sel = np.nonzero(splits < n - 1)[0]         # (n - 1: the order that failed)
            _redo(again[sel], ok, pivots, lambda lo, hi, okp: _twisted(
                bands[sel[lo:hi]], splits[sel[lo:hi]], okp, code), plan, N, W)
            keep = np.concatenate([sel[ok[again[sel]] == 0],
                                   np.nonzero(splits >= n - 1)[0]])
            again, bands = again[keep], bands[keep]
    if other_order and len(again):
        # where a pivot stayed undecided, the other order's leading minors (the same
        # inertia and determinant) may keep their radii narrower
        _redo(again, ok, pivots, lambda lo, hi, okp: _eliminated(
            bands[lo:hi], not reverse, okp, code), plan, N, W)
    ok = ok.astype(bool)
    return ok, pivots[ok], det12[ok]


def _redo(points, ok, pivots, eliminate, plan, N: int, W: int) -> None:
    """The factorisation of ``points`` (indices into the batch's ``ok`` and ``pivots``)
    again, by ``eliminate(lo, hi, ok)`` (the eliminated bands of the points ``lo .. hi -
    1`` of them) over their parts, in threads as a first batch would be."""
    okr = np.ones(len(points), dtype=np.uint8)
    n = pivots.shape[1]

    def part(lo, hi):
        okp = okr[lo:hi].copy()
        out = eliminate(lo, hi, okp)[:, :n, 0, :]
        okr[lo:hi] = okp
        return out
    pivots[points] = np.concatenate(run_ranges(part, len(points),
                                               _batch_seconds(plan, len(points), N, W) / 2))
    ok[points] = okr


def _padded(band) -> np.ndarray:
    """The band ``(B, n, w, ...)`` with the ``w`` zero rows the eliminations run over, in
    one contiguous array."""
    B, w = band.shape[0], band.shape[2]
    return np.ascontiguousarray(np.concatenate(
        [band, np.zeros((B, w) + band.shape[2:], dtype=band.dtype)], axis=1))


def _eliminated(band, reverse: bool, ok, N: int) -> np.ndarray:
    """The band ``(B, n, w, width)`` of balls of ``N`` words (its freedoms reversed if
    asked) padded and eliminated; ``ok`` cleared where a pivot ball holds 0."""
    from .stiffness import reversed_band
    B, n, w = band.shape[:3]
    Kb = _padded(reversed_band(band) if reverse else band)
    _multiword.eliminate(N, Kb, B, n + w, w, n, ok)
    return Kb


def _twisted(band, splits, ok, N: int) -> np.ndarray:
    """The band ``(B, n, w, width)`` of balls of ``N`` words padded and eliminated from both
    ends toward the freedoms ``splits`` (one per point; every pivot ``d_k`` left at row
    ``k``); ``ok`` cleared where a pivot ball holds 0."""
    B, n, w = band.shape[:3]
    Kb = _padded(band)
    _multiword.eliminate_twisted(N, Kb, B, n + w, w, n,
                                 np.ascontiguousarray(splits, dtype=np.int64), ok)
    return Kb


def _splits(plan, lam2) -> np.ndarray | None:
    """Per real point (balls) the freedom its twisted elimination ends at: where ``L^-T
    e_(n-1)`` of its double-precision factorisation peaks (:func:`_band.peaks`: near an
    eigenvalue, its mode's largest freedom); None where no double band is built."""
    from .stiffness import _compiled_band
    mids = np.array([float(v.mid()) for v in lam2])
    if not np.isfinite(mids).all():
        return None
    built = _compiled_band(plan, mids, None)
    if built is None:
        return None
    Kb = _padded(built[0])
    B, rows, w = Kb.shape
    n = rows - w
    _band.eliminate(Kb, B, rows, w, n, False)
    out = np.empty(B, dtype=np.int64)
    _band.peaks(Kb, out, B, rows, w, n)
    return out


def _signs(balls) -> np.ndarray:
    """The signs of balls of words (decided ones: their midpoints are not 0)."""
    if balls.shape[-1] == 3:
        return np.where(balls[..., 0].view(np.float64) < 0, -1, 1).astype(np.int8)
    return np.where(balls[..., -2] != 0, -1, 1).astype(np.int8)
