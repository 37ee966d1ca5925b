"""The arithmetics the numeric kernel is written against.

The kernel (:mod:`symtmm.numeric.segments`, :mod:`symtmm.numeric.stiffness`,
:mod:`symtmm.numeric.transfer`) is written once, on numpy arrays, in the manner
of mpmath's contexts and numpy.polynomial's ``object`` path. What the arrays
hold depends on the arithmetic passed in:

* :class:`Batch`: ``float64``/``complex128``; a leading axis carries many
  eigenvalues at once, so one call pays for a whole batch of points;
* :class:`MP`: numbers of a private mpmath context at an explicit precision
  (``object`` arrays); the ambient ``mpmath.mp`` precision is never read;
* :class:`Ball`: python-flint's ``arb``/``acb`` balls (``object`` arrays): every
  result is a ball guaranteed to contain the exact value.

Operators (``+ - * /``) and numpy's indexing and broadcasting work the same on
all three; everything else the kernel needs is a method of the arithmetic: exact
model values as numbers (:meth:`~Arithmetic.exact`), elementwise functions,
upper bounds of magnitudes (to choose step counts), the trust a pivot's sign
deserves (:meth:`~Arithmetic.decide`) and, for balls, a rigorous truncation
error (:meth:`~Arithmetic.widen`). Exact values are converted once per
arithmetic and precision (:func:`memo`).

Examples
--------
>>> import numpy as np, sympy as sp
>>> ar = MP(100)
>>> x = ar.exact(sp.pi / 3) * np.ones(2, dtype=object)
>>> print(ar.cos(x)[0])
0.5
>>> Batch().decide(np.array([1e-3, 1e-14]), np.array([1.0, 1.0]), 10)[1].tolist()
[True, False]
"""

from __future__ import annotations

import functools
import math
import threading

import mpmath
import numpy as np
import sympy as sp
from mpmath import libmp

from ..errors import ComputationError
from ..expr import exact_float

__all__ = ["Arithmetic", "Batch", "MP", "Ball", "ball_available", "memo", "DOUBLE",
           "magnitude_parts", "ball_midpoints"]


# Tables of :meth:`Arithmetic.cached`, keyed by arithmetic, precision and table. A
# table is immutable once built; two threads building the same one at once both get a
# correct table, and one of them is kept.
_SHARED: dict = {}
_SHARED_MAX = 4096


class Arithmetic:
    """What every arithmetic provides to the kernel (see the module docstring).

    Attributes
    ----------
    name : str
        ``"double"``, ``"mp"`` or ``"ball"``.
    prec : int
        Working precision in bits.
    rigorous : bool
        Results are enclosures (balls), not approximations.
    key : tuple
        Identifies the arithmetic and its precision (for :func:`memo`).
    """

    name = "?"
    prec = 53
    rigorous = False

    @property
    def key(self) -> tuple:
        return (self.name, self.prec)

    @property
    def digits(self) -> int:
        """Decimal digits of the working precision."""
        return int(self.prec * math.log10(2))

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def cached(self, key, build):
        """``build()`` once per kind of arithmetic and precision (tables of constants the
        kernel reuses: Gauss–Legendre rules, 1/k!, exact values converted).

        Shared by every arithmetic object of the same :attr:`key`: the searches make a
        new one per root and precision, and rebuilding a 300-bit quadrature rule each
        time cost more than the root. Bounded: the oldest entries go first.
        """
        full = self.key + (key,)
        hit = _SHARED.get(full)
        if hit is None:
            with self:
                hit = build()
            if len(_SHARED) >= _SHARED_MAX:
                # (dicts keep insertion order: drop the oldest quarter)
                for old in list(_SHARED)[:_SHARED_MAX // 4]:
                    _SHARED.pop(old, None)
            _SHARED[full] = hit
        return hit

    # -- numbers ---------------------------------------------------------------------
    def exact(self, value):
        """An exact real SymPy value as a number of this arithmetic (converted once)."""
        if not isinstance(value, sp.Rational):
            value = sp.sympify(value)
        return self.cached(("exact", exact_key(value)), lambda: self._convert(value))

    def _convert(self, value):
        raise NotImplementedError

    def number(self, z):
        """A Python or mpmath number (``lam``, a sample point) as a number here."""
        raise NotImplementedError

    def array(self, values, shape=None) -> np.ndarray:
        """Numbers (already of this arithmetic) as an array."""
        out = np.empty(len(values), dtype=object)
        out[:] = list(values)
        return out if shape is None else out.reshape(shape)

    def zeros(self, shape, like=None) -> np.ndarray:
        """An array of zeros (of the kind of ``like``'s numbers: real or complex)."""
        raise NotImplementedError

    def square(self, values) -> np.ndarray:
        """``values**2`` elementwise (an array of this arithmetic's numbers), exactly where
        the arithmetic can: the kernel's ``lam**2``. A point a few digits from a zero,
        its square rounded to the working bits, has a ``Delta`` that the rounding alone
        moves by more than its size (a damped search's secant steps, 39 digits near a
        zero at 134 bits: undecided in every number of words until the bits doubled)."""
        values = np.asarray(values)
        return values * values

    def negated_squares(self, points) -> np.ndarray:
        """``-x**2`` of real points (mpmath numbers), exactly where the arithmetic can
        (:meth:`square`): the kernel's ``lam**2`` at ``lam = i x``."""
        return -self.square(self.array([self.number(x) for x in points]))

    # -- functions -----------------------------------------------------------------
    # Every arithmetic provides, elementwise on its arrays: sqrt, cos, cosh, sin, sinh;
    # root4 (a fourth root, any branch: callers use even functions of it); real (real
    # parts); upper (float upper bounds of |x|, to choose series lengths and steps).
    # Batch and MP define them as methods, Ball as ufuncs built in __init__.
    FUNCTIONS = ("sqrt", "cos", "cosh", "sin", "sinh", "root4", "real", "upper")

    def is_complex(self, x) -> bool:
        raise NotImplementedError

    def positive(self, x) -> np.ndarray:
        """Where the real numbers ``x`` are above 0 (a boolean array; a ball that holds 0
        counts as not positive)."""
        return np.array([v > 0 for v in np.asarray(x).reshape(-1)],
                        dtype=bool).reshape(np.shape(x))

    # -- trust -----------------------------------------------------------------------
    def decide(self, pivot, scale, n: int):
        """``(sign, decided)`` of pivots: the sign (+1/-1) and whether it can be trusted.

        ``scale`` bounds the entries met so far in the elimination (rounding errors
        grow with them); ``n`` is the order of the matrix. Complex pivots get sign 0.
        """
        raise NotImplementedError

    #: whether :meth:`decide` needs ``scale`` (balls carry their own error)
    needs_scale = True
    #: the largest growth of ``|L||D||L^T|`` over the diagonal of ``K`` at which the
    #: pivots' signs are still taken for the inertia of ``K`` (see numeric.stiffness)
    growth_limit = float("inf")

    def widen(self, x, radius, wrt=None, slope=None, curve=None, third=None):
        """``x`` with ``radius`` (an exact rational: a truncation error) added to its
        uncertainty; a no-op but for balls, whose enclosures must contain it.

        ``wrt``, ``slope``, ``curve``, ``third``: the series variable and bounds on the
        tail's first three derivatives with respect to it, for arithmetics that carry
        derivatives (:class:`~symtmm.numeric.jet.BallJet`)."""
        return x

    def norm_variable(self, X):
        """For arithmetics that carry derivatives: a stand-in series variable whose
        derivatives bound those of the matrix ``X`` (nested lists of arrays) in norm, for
        :meth:`widen`; None otherwise."""

    def cosh_sinh(self, x):
        """``(cosh x, sinh x)`` elementwise (balls: one Arb call gives both)."""
        return self.cosh(x), self.sinh(x)

    def cos_sin(self, x):
        """``(cos x, sin x)`` elementwise (balls: one Arb call gives both)."""
        return self.cos(x), self.sin(x)

    def polynomial(self, coefficients, x):
        """``sum_k coefficients[k] x**k`` elementwise (Horner), ``coefficients`` numbers of
        the arithmetic, lowest degree first.

        Examples
        --------
        >>> DOUBLE.polynomial([1.0, 2.0, 3.0], np.array([0.0, 1.0, 2.0]))
        array([ 1.,  6., 17.])
        """
        # the array on the left: an mpmath number would first try (and fail) to convert it
        acc = 0 * x + coefficients[-1]
        for c in coefficients[-2::-1]:
            acc = acc * x + c
        return acc

    def polynomials(self, rows, x) -> list:
        """:meth:`polynomial` of each coefficient list of ``rows`` (equal lengths) at the
        same ``x``.

        Examples
        --------
        >>> [v.tolist() for v in DOUBLE.polynomials([[1.0, 2.0], [0.0, 1.0]], np.array([3.0]))]
        [[7.0], [3.0]]
        """
        return [self.polynomial(row, x) for row in rows]

    def series_terms(self, log2_bound) -> int:
        """The smallest ``K >= 2`` with ``log2_bound(K)`` below ``-(prec + 4)``: terms of a
        series whose tail beyond ``K`` terms is below the working precision."""
        k = 2
        while log2_bound(k) > -(self.prec + 4):
            k += 1
        return k

    # -- leaving the arithmetic --------------------------------------------------------
    def to_mpmath(self, x):
        """An element as a global mpmath number, unrounded (midpoints of balls)."""
        raise NotImplementedError

    def to_complex(self, x) -> np.ndarray:
        """Elementwise complex128 (approximations)."""
        return np.vectorize(lambda v: complex(self.to_mpmath(v)), otypes=[complex])(x)

    def log_abs_arg(self, x):
        """``(log|x|, arg x)`` as float arrays (``-inf`` where ``x`` is 0)."""
        raise NotImplementedError


@functools.lru_cache(maxsize=64)
def _mp_functions(prec: int) -> tuple:
    """The elementwise functions of :class:`MP` at ``prec`` bits (its private context's),
    once per precision."""
    ctx = _mp_context(prec)
    return (_ufunc(ctx.sqrt), _ufunc(ctx.cos), _ufunc(ctx.cosh), _ufunc(ctx.sin),
            _ufunc(ctx.sinh), _ufunc(ctx.re), np.frompyfunc(lambda v: float(abs(v)), 1, 1))


@functools.cache
def _ball_functions(flint) -> tuple:
    """The elementwise functions of :class:`Ball` (object arrays of Arb balls), once."""
    return (_ufunc(lambda v: v.sqrt()), _ufunc(lambda v: v.cos()), _ufunc(lambda v: v.cosh()),
            _ufunc(lambda v: v.sin()), _ufunc(lambda v: v.sinh()),
            _ufunc(lambda v: v.real if isinstance(v, flint.acb) else v),
            np.frompyfunc(lambda v: float(v.abs_upper()), 1, 1),
            # both functions of a pair from one evaluation (half the time of two calls)
            np.frompyfunc(lambda v: v.sinh_cosh()[::-1], 1, 2),
            np.frompyfunc(lambda v: v.sin_cos()[::-1], 1, 2))


def _ufunc(fn):
    """``fn`` applied elementwise to object arrays (numpy's frompyfunc, array in, array out)."""
    f = np.frompyfunc(fn, 1, 1)

    def apply(x):
        out = f(x)
        return out if isinstance(out, np.ndarray) else np.array(out, dtype=object)
    return apply


class Batch(Arithmetic):
    """Double precision on numpy ``float64``/``complex128`` arrays, vectorised over points.

    Examples
    --------
    >>> import numpy as np
    >>> Batch().root4(np.array([16.0, -16.0]))
    array([2.        +0.j        , 1.41421356+1.41421356j])
    """

    name = "double"
    prec = 53
    #: a pivot below this fraction of the entries met so far has an untrusted sign
    TRUST = 1e-10
    growth_limit = 1e4

    def _convert(self, value):
        return exact_float(value)

    def number(self, z):
        return complex(z)

    def array(self, values, shape=None):
        out = np.asarray(values)
        return out if shape is None else out.reshape(shape)

    def zeros(self, shape, like=None):
        dtype = complex if like is not None and np.iscomplexobj(like) else float
        return np.zeros(shape, dtype=dtype)

    sqrt = staticmethod(np.sqrt)
    cos = staticmethod(np.cos)
    cosh = staticmethod(np.cosh)
    sin = staticmethod(np.sin)
    sinh = staticmethod(np.sinh)
    real = staticmethod(np.real)

    def polynomials(self, rows, x) -> list:
        """As :meth:`Arithmetic.polynomials`, all rows in one Horner loop over a stacked array:
        the same operations per element, a quarter of numpy's calls (a batch of a few
        points pays a microsecond a call: a fifth of example 1's small batches)."""
        C = np.array(rows)                      # (rows, terms)
        acc = 0 * x[None, :] + C[:, -1:]
        for k in range(C.shape[1] - 2, -1, -1):
            acc = acc * x[None, :] + C[:, k:k + 1]
        return list(acc)

    def root4(self, x):
        x = np.asarray(x)
        if not np.iscomplexobj(x) and not (x < 0).any():
            # the real root of real x >= 0: the functions of it then stay real (the complex
            # ones cost four real transcendentals each and a complex power)
            return np.sqrt(np.sqrt(x))
        return np.asarray(x, dtype=complex) ** 0.25

    def upper(self, x):
        return np.abs(x)

    def positive(self, x):
        return np.asarray(x) > 0

    def is_complex(self, x):
        return np.iscomplexobj(x)

    def decide(self, pivot, scale, n):
        if np.iscomplexobj(pivot):
            return np.zeros(pivot.shape, dtype=np.int8), np.abs(pivot) > self.TRUST * scale
        sign = np.where(pivot < 0, -1, 1).astype(np.int8)
        return sign, np.abs(pivot) > self.TRUST * scale

    def to_mpmath(self, x):
        return mpmath.mpmathify(complex(x))

    def to_complex(self, x):
        return np.asarray(x, dtype=complex)

    def log_abs_arg(self, x):
        x = np.asarray(x)
        with np.errstate(divide="ignore"):
            if not np.iscomplexobj(x):
                # (the argument of a real number without an arctangent per pivot; a zero
                # pivot has no value whatever its argument)
                return np.log(np.abs(x)), np.where(x < 0, np.pi, 0.0)
            return np.log(np.abs(x)), np.angle(x)


#: The double-precision arithmetic (it has no state).
DOUBLE = Batch()


@functools.lru_cache(maxsize=64)
def _mp_context(prec: int) -> mpmath.MPContext:
    ctx = mpmath.MPContext()
    ctx.prec = prec
    return ctx


class MP(Arithmetic):
    """mpmath numbers of a private context at ``prec`` bits, in ``object`` arrays.

    The context is the arithmetic's own (``mpmath.MPContext``), so neither the
    ambient ``mpmath.mp`` precision nor another thread's choice affects it.

    Parameters
    ----------
    prec : int
        Working precision in bits (``MP.from_digits(d)`` for decimal digits).
    """

    name = "mp"

    def __init__(self, prec: int):
        self.prec = int(prec)
        self.ctx = _mp_context(self.prec)
        # (half the digits beyond double's may go to growth: the rest still decides)
        self.growth_limit = 1e4 * 2.0 ** min((self.prec - 53) / 2, 900)
        (self.sqrt, self.cos, self.cosh, self.sin, self.sinh, self.real,
         self._abs) = _mp_functions(self.prec)

    @classmethod
    def from_digits(cls, digits: int) -> MP:
        """The arithmetic of ``digits`` decimal digits."""
        return cls(math.ceil(digits * math.log2(10)) + 4)

    def _convert(self, value):
        ctx = self.ctx
        if value.is_Rational:
            return ctx.make_mpf(libmp.from_rational(int(value.p), int(value.q), self.prec,
                                                    libmp.round_nearest))
        if not value.is_number or value.is_real is False:
            raise ComputationError(f"not a real number: {value}")
        digits = self.digits + 15
        approx = sp.N(value, digits)
        return ctx.mpf(approx._to_mpmath(self.prec + 60))

    def number(self, z):
        ctx = self.ctx
        # (any context's mpc: the global one's or another private one's)
        if isinstance(z, complex) or hasattr(z, "_mpc_"):
            return ctx.mpc(z)
        return ctx.mpf(z)

    def zeros(self, shape, like=None):
        complex_ = like is not None and self.is_complex(like)
        return _filled(shape, self.ctx.mpc(0) if complex_ else self.ctx.mpf(0))

    def square(self, values):
        # (mpmath's exact products: precision 0; the kernel's next operation rounds)
        ctx = self.ctx
        out = [ctx.make_mpc(libmp.mpc_mul(v._mpc_, v._mpc_, 0)) if hasattr(v, "_mpc_")
               else ctx.make_mpf(libmp.mpf_mul(v._mpf_, v._mpf_, 0)) for v in values]
        return self.array(out, np.shape(values))

    def root4(self, x):
        ctx = self.ctx
        return _ufunc(lambda v: ctx.root(ctx.mpc(v), 4))(x)

    def upper(self, x):
        # (beyond the doubles' range the bound is inf, said without numpy's warning)
        with np.errstate(over="ignore", under="ignore"):
            return self._abs(x).astype(float) * (1 + 1e-14)

    def is_complex(self, x):
        # arrays are homogeneous (every kernel array is built from one kind of input):
        # the first element tells
        flat = np.asarray(x).reshape(-1)
        return bool(flat.size) and isinstance(flat[0], self.ctx.mpc)

    def decide(self, pivot, scale, n):
        pivot = np.asarray(pivot, dtype=object)
        limit = float(n + 1) * 2.0 ** (40 - self.prec)
        with np.errstate(over="ignore", under="ignore"):
            mag = self._abs(pivot).astype(float)
        decided = mag > limit * np.asarray(scale, dtype=float)
        if self.is_complex(pivot):
            return np.zeros(pivot.shape, dtype=np.int8), decided
        sign = np.where(np.array([v < 0 for v in pivot.reshape(-1)], dtype=bool)
                        .reshape(pivot.shape), -1, 1).astype(np.int8)
        return sign, decided

    def to_mpmath(self, x):
        if isinstance(x, self.ctx.mpc):
            return mpmath.mp.make_mpc((x.real._mpf_, x.imag._mpf_))
        return mpmath.mp.make_mpf(self.ctx.mpf(x)._mpf_)

    def log_abs_arg(self, x):
        ctx = self.ctx
        flat = np.asarray(x, dtype=object).reshape(-1)
        la = np.array([float(ctx.log(abs(v))) if v != 0 else -np.inf for v in flat])
        ph = np.array([float(ctx.arg(v)) if v != 0 else 0.0 for v in flat])
        return la.reshape(np.shape(x)), ph.reshape(np.shape(x))


#: Held while python-flint's process-wide precision is set for a computation
#: (:class:`Ball` contexts, :func:`symtmm.numeric.linalg.solver`); reentrant.
FLINT_LOCK = threading.RLock()


def ball_available() -> bool:
    """Whether python-flint (Arb ball arithmetic) can be imported."""
    try:
        import flint  # noqa: F401
    except ImportError:
        return False
    return True


class Ball(Arithmetic):
    """Arb ball arithmetic (python-flint) at ``prec`` bits, in ``object`` arrays.

    python-flint keeps one working precision for the process; the kernel runs
    inside ``with ar:``, which sets it for the duration and restores it.

    Examples
    --------
    >>> import numpy as np, sympy as sp
    >>> ar = Ball(128)
    >>> with ar:
    ...     x = ar.cos(np.array([ar.exact(sp.pi)], dtype=object))[0]
    >>> x.contains(-1), x.rad() < 1e-30
    (True, True)
    """

    name = "ball"
    rigorous = True
    needs_scale = False

    def __init__(self, prec: int):
        try:
            import flint
        except ImportError:
            raise ComputationError("ball arithmetic needs python-flint: "
                                   "pip install 'symtmm[certified]'") from None
        self.flint = flint
        self.prec = int(prec)
        self._saved: list = []
        # (the elementwise functions are the same for every precision: made once, where a
        # ball arithmetic is made for nearly every batch)
        (self.sqrt, self.cos, self.cosh, self.sin, self.sinh, self.real, self._upper,
         self._cosh_sinh, self._cos_sin) = _ball_functions(flint)

    def cosh_sinh(self, x):
        return tuple(np.asarray(v, dtype=object) for v in self._cosh_sinh(x))

    def cos_sin(self, x):
        return tuple(np.asarray(v, dtype=object) for v in self._cos_sin(x))

    def polynomial(self, coefficients, x):
        """As :meth:`Arithmetic.polynomial`, by Arb's own evaluation of an ``arb_poly``: one
        call per element, not two per term (a ninth-degree series 2.5x faster)."""
        flint = self.flint
        poly = flint.arb_poly(list(coefficients))
        return _ufunc(poly)(x)

    @classmethod
    def from_digits(cls, digits: int) -> Ball:
        return cls(math.ceil(digits * math.log2(10)) + 4)

    def __enter__(self):
        # (python-flint's precision is the process's: a thread that walked at another
        # precision meanwhile would change this one's digits; flint's scalar calls hold
        # Python's lock anyway, so little runs at once that this stops)
        FLINT_LOCK.acquire()
        self._saved.append(self.flint.ctx.prec)
        self.flint.ctx.prec = self.prec
        return self

    def __exit__(self, *exc):
        self.flint.ctx.prec = self._saved.pop()
        FLINT_LOCK.release()
        return False

    def _convert(self, value):
        return to_arb(value, self.flint)

    def number(self, z):
        flint = self.flint
        if isinstance(z, (flint.arb, flint.acb)):
            return z
        if isinstance(z, complex) or hasattr(z, "_mpc_"):
            return flint.acb(_arb_exact(z.real, flint), _arb_exact(z.imag, flint))
        return _arb_exact(z, flint)

    def zeros(self, shape, like=None):
        complex_ = like is not None and self.is_complex(like)
        return _filled(shape, self.flint.acb(0) if complex_ else self.flint.arb(0))

    def square(self, values):
        # exact where the values are (points, exact balls): at the bits their squares span
        flint = self.flint
        bits = self.prec
        for v in values:
            for p in ((v.real, v.imag) if isinstance(v, flint.acb) else (v,)):
                if p.rad() == 0 and p != 0:
                    m = p.mid().man_exp()[0]
                    bits = max(bits, 2 * int(m).bit_length() + 8)
            if isinstance(v, flint.acb) and v.real != 0 and v.imag != 0:
                # (a^2 - b^2: the span of both parts' bits)
                (ma, ea), (mb, eb) = v.real.mid().man_exp(), v.imag.mid().man_exp()
                top = max(int(ea) + int(ma).bit_length(), int(eb) + int(mb).bit_length())
                bits = max(bits, 2 * (top - min(int(ea), int(eb))) + 8)
        saved = flint.ctx.prec
        flint.ctx.prec = bits
        try:
            out = [v * v for v in values]
        finally:
            flint.ctx.prec = saved
        return self.array(out, np.shape(values))

    def negated_squares(self, points) -> np.ndarray:
        """As :meth:`Arithmetic.negated_squares`, each an exact ball that also keeps its
        mantissa and exponent (:func:`exact_square_type`): the compiled multi-word balls
        are encoded from those directly (through Arb's square and midpoint, a point cost
        10 microseconds; so, 4)."""
        flint = self.flint
        kind = exact_square_type(flint)
        out = []
        saved = flint.ctx.prec
        try:
            for x in points:
                _, man, exp, _ = x._mpf_
                square = -(int(man) ** 2)
                # (Arb sets a mantissa and exponent exactly at enough working bits)
                flint.ctx.prec = max(saved, square.bit_length() + 8)
                ball = kind((square, 2 * int(exp)))
                ball.dyadic = (square, 2 * int(exp))
                out.append(ball)
        finally:
            flint.ctx.prec = saved
        return self.array(out)

    def root4(self, x):
        flint = self.flint
        half = None

        def widened(r, rad, low):
            # the midpoint's root r widened by the ball's radius times the largest
            # |d x**(1/4) / dx| = 1 / (4 |x|**(3/4)) on the ball (mean value), bounded by
            # |r| / (4 low) with low the ball's least |x| (no power of a ball, which costs
            # what the rest of the root does several times over)
            width = flint.arb(0, (flint.arb(rad) * abs(r) / (4 * low)).upper())
            return r + (flint.acb(width, width) if isinstance(r, flint.acb) else width)

        def principal(v):
            # Arb's root of a wide ball is loose (twenty times its width at a relative
            # width of 1e-3): the root of the midpoint, widened; the ball keeps away from
            # 0 and from the cut (the midpoint's real part is not negative: the cut's
            # nearest point is 0)
            if v.real.rad() == 0 and v.imag.rad() == 0:
                return v.root(4)
            rad = (flint.arb(v.real.rad()) ** 2 + flint.arb(v.imag.rad()) ** 2).sqrt().upper()
            mid = flint.acb(v.mid())
            low = abs(mid).lower() - rad
            if not low > 0:
                return v.root(4)
            return widened(mid.root(4), rad, low)

        def real_root(v):
            # as principal, on the real line: a real ball above 0 keeps a real root, and
            # the functions of it stay real (in complex balls they cost several times more)
            if v.rad() == 0:
                return v.root(4)
            mid, rad = flint.arb(v.mid()), v.rad()
            return widened(mid.root(4), rad, mid - rad)

        def root(v):
            nonlocal half
            if isinstance(v, flint.arb) and v > 0:
                return real_root(v)
            v = flint.acb(v)
            # a branch whose cut (the negative axis) is away from the ball: the c_j that
            # use the root are even functions of it, so any fourth root serves
            if v.mid().real >= 0:
                return principal(v)
            if half is None:
                half = flint.arb(2).sqrt() / 2
            return principal(-v) * flint.acb(half, half)
        return _ufunc(root)(x)

    def upper(self, x):
        with np.errstate(over="ignore", under="ignore"):
            return self._upper(x).astype(float)

    def is_complex(self, x):
        flat = np.asarray(x).reshape(-1)
        return bool(flat.size) and isinstance(flat[0], self.flint.acb)

    def decide(self, pivot, scale, n):
        flat = np.asarray(pivot, dtype=object).reshape(-1)
        decided = np.array([not v.contains(0) for v in flat], dtype=bool)
        if any(isinstance(v, self.flint.acb) for v in flat):
            sign = np.zeros(flat.size, dtype=np.int8)
        else:
            sign = np.array([-1 if v < 0 else 1 for v in flat], dtype=np.int8)
        return sign.reshape(np.shape(pivot)), decided.reshape(np.shape(pivot))

    def widen(self, x, radius, wrt=None, slope=None, curve=None, third=None):
        flint = self.flint
        with self:
            r = flint.arb(0, self.exact(radius))       # a ball about 0 holding the bound
            # (arrays hold one kind of number: one sum over the array, no call per element)
            return np.asarray(x, dtype=object) + (flint.acb(r, r) if self.is_complex(x) else r)

    def to_complex(self, x) -> np.ndarray:
        # (Arb rounds a midpoint to the nearest double as mpmath does, without a global
        # mpmath number between: a shape's samples convert tens of thousands of states)
        flat = np.asarray(x, dtype=object).reshape(-1)
        return np.fromiter((complex(v) for v in flat), complex, flat.size).reshape(np.shape(x))

    def to_mpmath(self, x):
        flint = self.flint
        if isinstance(x, flint.acb):
            return mpmath.mp.make_mpc((_mpf_of(x.real.mid()), _mpf_of(x.imag.mid())))
        return mpmath.mp.make_mpf(_mpf_of(x.mid()))

    def log_abs_arg(self, x):
        flat = np.asarray(x, dtype=object).reshape(-1)
        la = np.array([float(abs(v).mid().log()) if not v.contains(0) else -np.inf
                       for v in flat])
        ph = np.array([float(self.flint.acb(v).arg().mid()) for v in flat])
        return la.reshape(np.shape(x)), ph.reshape(np.shape(x))


def _filled(shape, value) -> np.ndarray:
    """An object array of ``shape`` holding ``value`` everywhere (numbers are immutable)."""
    out = np.empty(shape, dtype=object)
    out.fill(value)
    return out


def magnitude_parts(x) -> tuple:
    """``(m, e)`` with ``|x| <= m 2**e`` (``m`` a float in ``[0.5, 1]``, its leading 53
    bits rounded up; ``(0.0, 0)`` for 0) of an mpmath number of any size: where ``x`` alone
    may leave the doubles' range, a product or quotient of such parts does not.

    Examples
    --------
    >>> magnitude_parts(mpmath.mpf(3)), magnitude_parts(mpmath.mpf(2) ** -5000)
    ((0.75, 2), (0.5, -4999))
    """
    _, man, exp, bc = x._mpf_
    if not man:
        return 0.0, 0
    if bc <= 53:
        return math.ldexp(float(man), -bc), exp + bc
    return math.ldexp(float((int(man) >> (bc - 53)) + 1), -53), exp + bc


def _mpf_of(exact_arb):
    """The ``_mpf_`` tuple of an exact arb (a midpoint), unrounded; nan for a midpoint that
    is not finite (a ball whose elimination divided by a pivot holding 0)."""
    if not exact_arb.is_finite():
        if exact_arb.is_nan():
            return libmp.fnan
        return libmp.finf if exact_arb > 0 else libmp.fninf
    man, exp = exact_arb.man_exp()
    man = int(man)
    if man == 0:
        return libmp.fzero
    return libmp.from_man_exp(man, int(exp))


def exact_key(value):
    """A dictionary key of an exact number: a rational by its integers, anything else as
    it is. (Hashing a SymPy number costs a microsecond, and a plan's tables look up
    thousands of them; equal keys, equal numbers.)

    Examples
    --------
    >>> exact_key(sp.Rational(3, 4)), exact_key(sp.sqrt(2))
    ((3, 4), sqrt(2))
    """
    return (value.p, value.q) if isinstance(value, sp.Rational) else value


_EXACT_SQUARE: dict = {}


def exact_square_type(flint):
    """The arb whose instances also carry ``dyadic``, ``(mantissa, exponent)`` of their
    exact value (:meth:`Ball.negated_squares`); a plain arb wherever arithmetic makes
    another one of it."""
    kind = _EXACT_SQUARE.get(id(flint))
    if kind is None:
        kind = _EXACT_SQUARE[id(flint)] = type("ExactSquare", (flint.arb,),
                                               {"__slots__": ("dyadic",)})
    return kind


def _arb_exact(x, flint):
    """An mpmath ``mpf`` of any context (or an int or float) as an exact arb (no rounding on
    the way, and the ambient mpmath precision untouched)."""
    if hasattr(x, "_mpf_"):
        value = x._mpf_
    elif isinstance(x, (int, np.integer)):
        value = libmp.from_int(int(x))
    else:
        value = libmp.from_float(float(x))
    sign, man, exp, _ = value
    if man == 0:
        return flint.arb(0)
    # (a mantissa and exponent: set exactly, whatever the working precision)
    return flint.arb((-int(man) if sign else int(man), int(exp)))


def to_arb(expr, flint):
    """An exact real SymPy number as an arb ball (at flint's working precision).

    Integers, rationals, ``pi``, sums, products and rational powers: everything
    a model file can write.

    Examples
    --------
    >>> import flint
    >>> with flint.ctx.workprec(100):
    ...     b = to_arb(sp.sqrt(2) * sp.pi / 3, flint)
    >>> b.contains(flint.arb("1.48096098"))
    False
    >>> abs(float(b.mid()) - 1.4809609793861218) < 1e-15
    True
    """
    arb = flint.arb
    expr = sp.sympify(expr)
    if expr.is_Integer:
        return arb(flint.fmpz(int(expr)))
    if expr.is_Rational:
        return arb(flint.fmpq(int(expr.p), int(expr.q)))
    if expr is sp.pi:
        return arb.pi()
    if expr.is_Add:
        total = arb(0)
        for term in expr.args:
            total += to_arb(term, flint)
        return total
    if expr.is_Mul:
        prod = arb(1)
        for factor in expr.args:
            prod *= to_arb(factor, flint)
        return prod
    if expr.is_Pow:
        base, exp = expr.args
        b = to_arb(base, flint)
        if exp.is_Integer:
            return b ** int(exp)
        if exp.is_Rational:
            root = b.sqrt() if exp.q == 2 else b ** arb(flint.fmpq(1, int(exp.q)))
            return root ** int(exp.p)
    raise ComputationError(f"cannot enclose {expr} in ball arithmetic")


def memo(owner, ar: Arithmetic, name: str, build):
    """``build()`` computed once per arithmetic and precision, kept on ``owner``.

    Plans keep their constants converted to each arithmetic they are evaluated in
    (floats, mpmath numbers at a precision, balls at a precision).
    """
    store = owner.__dict__.setdefault("_memo", {})
    key = (name,) + ar.key
    hit = store.get(key)
    if hit is None:
        with ar:
            hit = store[key] = build()
    return hit


def ball_midpoints(ar: Arithmetic, values):
    """Arb numbers' midpoints as mpmath numbers of the arithmetic ``ar``, each rounded once
    to its precision (an array of the same shape)."""
    ctx, prec = ar.ctx, ar.prec

    def mpf(x):
        return libmp.mpf_pos(_mpf_of(x.mid()), prec, "n")

    import flint

    def one(z):
        if isinstance(z, flint.acb):
            return ctx.make_mpc((mpf(z.real), mpf(z.imag)))
        return ctx.make_mpf(mpf(z))
    return np.frompyfunc(one, 1, 1)(np.asarray(values, dtype=object))
