"""Taylor jets of balls: a value and its first derivatives, all enclosed, over a box of ``lam``.

A :class:`Jet` holds the Taylor coefficients ``f, f', f''/2`` (to the order of its
arithmetic) as Arb balls; each encloses that coefficient at every ``lam`` of a box (a
complex ball), as interval arithmetic does for values. :class:`BallJet` is the
arithmetic of :mod:`symtmm.numeric.arith` on them, so the numeric kernel, written once,
gives the dynamic stiffness ``K`` and its derivatives in one pass. The certified winding
number (:mod:`symtmm.roots.winding`) takes ``K(c)`` and ``K'(c)`` at the centre of a
segment (first-order jets at a point: tight) and ``K''`` over the whole segment (a
second-order jet over the box), so that ``K(z) in K(c) + K'(c)(z - c) + K''(S)(z - c)**2
/ 2`` (Taylor's theorem with the mean-value remainder, entry by entry). The enclosure
of ``K`` itself over a box is far too wide (the dependency along the element
formulas); its second-order model is not, since the wide part only multiplies
``(z - c)**2``.

Every function is extended by the chain rule (``cos(u) = cos u0 - sin u0 u1 t + (-sin
u0 u2 - cos u0 u1**2 / 2) t**2``); a series truncated after ``K`` terms is widened by
its tail in every coefficient, from bounds on the tail's derivatives in the series
variable that the caller gives (:meth:`BallJet.widen`).

Examples
--------
>>> import flint
>>> ar = BallJet(80, order=2)
>>> with ar:
...     z = ar.variable(flint.acb(2))                   # lam itself at 2
...     y = ar.cos(np.array([z * z], dtype=object))[0]  # cos(lam**2)
>>> y.c[0].overlaps(flint.acb(4).cos()), y.c[1].overlaps(-4 * flint.acb(4).sin())
(True, True)
>>> y.c[2].overlaps(-flint.acb(4).sin() - 8 * flint.acb(4).cos())   # (cos(lam**2))''/2
True
"""

from __future__ import annotations

import math

import numpy as np

from .arith import Arithmetic, Ball, _filled, _ufunc

__all__ = ["Jet", "BallJet"]


class Jet:
    """Taylor coefficients ``c[0] = f, c[1] = f', c[2] = f''/2`` (balls) in ``lam``."""

    __slots__ = ("c",)

    def __init__(self, coefficients):
        self.c = coefficients if isinstance(coefficients, tuple) else tuple(coefficients)

    def _other(self, o):
        return o.c if isinstance(o, Jet) else (o,) + (0,) * (len(self.c) - 1)

    def __neg__(self):
        return Jet(-a for a in self.c)

    def __add__(self, o):
        if not isinstance(o, Jet):
            return Jet((self.c[0] + o,) + self.c[1:])
        return Jet([a + b for a, b in zip(self.c, o.c)])

    __radd__ = __add__

    def __sub__(self, o):
        if not isinstance(o, Jet):
            return Jet((self.c[0] - o,) + self.c[1:])
        return Jet([a - b for a, b in zip(self.c, o.c)])

    def __rsub__(self, o):
        return Jet(b - a for a, b in zip(self.c, self._other(o)))

    def __mul__(self, o):
        a = self.c
        if not isinstance(o, Jet):
            return Jet([v * o for v in a])
        b = o.c
        if len(a) == 2:
            return Jet((a[0] * b[0], a[0] * b[1] + a[1] * b[0]))
        if len(a) == 3:
            return Jet((a[0] * b[0], a[0] * b[1] + a[1] * b[0],
                        a[0] * b[2] + a[1] * b[1] + a[2] * b[0]))
        return Jet([sum((a[i] * b[k - i] for i in range(1, k + 1)), a[0] * b[k])
                    for k in range(len(a))])

    __rmul__ = __mul__

    def __truediv__(self, o):
        if not isinstance(o, Jet):
            return Jet([a / o for a in self.c])
        a, b = self.c, o.c
        out: list = []
        for k in range(len(a)):
            acc = a[k]
            for i in range(k):
                acc = acc - out[i] * b[k - i]
            out.append(acc / b[0])
        return Jet(out)

    def __rtruediv__(self, o):
        return Jet(self._other(o)) / self

    def __pow__(self, k):
        if not isinstance(k, (int, np.integer)) or k < 1:
            return NotImplemented
        out = self
        for _ in range(int(k) - 1):
            out = out * self
        return out

    def __repr__(self):
        return f"Jet({', '.join(map(str, self.c))})"


def _compose(f, u) -> list:
    """Taylor coefficients of ``f(u)`` from ``f`` and its first three derivatives at ``u0``
    (``f``, four balls) and the coefficients of ``u`` (at most four)."""
    n = len(u)
    if n > 4:
        raise NotImplementedError("jets beyond the third order")
    out = [f[0], f[1] * u[1]]
    if n > 2:
        out.append(f[1] * u[2] + f[2] * u[1] * u[1] / 2)
    if n > 3:
        out.append(f[1] * u[3] + f[2] * u[1] * u[2] + f[3] * u[1] * u[1] * u[1] / 6)
    return out


class BallJet(Ball):
    """Ball arithmetic on :class:`Jet` values of ``order`` 1 to 3 (see the module docstring).

    Only what the dynamic-stiffness assembly needs: no pivots are decided on jets. Its
    square and fourth roots are any roots (the kernel only takes even functions of them),
    chosen with their cuts away from the ball.
    """

    name = "balljet"
    #: Euler–Bernoulli segments by their closed-form dynamic stiffness (far narrower
    #: enclosures over a box: :func:`symtmm.numeric.stiffness.eb_closed_stiffness`)
    closed_stiffness = True

    #: jets are not Arb numbers: the series by Horner's rule in their own operations, and
    #: each function by its own chain rule
    polynomial = Arithmetic.polynomial
    cosh_sinh = Arithmetic.cosh_sinh
    cos_sin = Arithmetic.cos_sin

    def __init__(self, prec: int, order: int = 1):
        super().__init__(prec)
        self.order = int(order)
        flint = self.flint

        def lift(derivatives):
            # f(u) for a jet u: the chain rule (Faa di Bruno) to third order on Taylor
            # coefficients, from f and its first three derivatives at u0
            def apply(u):
                if not isinstance(u, Jet):
                    return derivatives(flint.acb(u))[0]
                f = derivatives(flint.acb(u.c[0]))
                return Jet(_compose(f, u.c))
            return _ufunc(apply)

        def cos(v):
            s, c = v.sin(), v.cos()
            return c, -s, -c, s

        def sin(v):
            s, c = v.sin(), v.cos()
            return s, c, -s, -c

        def cosh(v):
            s, c = v.sinh(), v.cosh()
            return c, s, c, s

        def sinh(v):
            s, c = v.sinh(), v.cosh()
            return s, c, s, c

        def sqrt(v):
            # a square root whose cut stays away from the ball (i sqrt(-v) left of the
            # imaginary axis): the kernel's closed forms are even in every root they take,
            # and a ball straddling the negative axis (a real negative value) would
            # otherwise come out as everything
            r = v.sqrt() if v.mid().real >= 0 else flint.acb(0, 1) * (-v).sqrt()
            r3 = r * r * r
            return r, 1 / (2 * r), -1 / (4 * r3), 3 / (8 * r3 * r * r)

        self.cos, self.sin = lift(cos), lift(sin)
        self.cosh, self.sinh, self.sqrt = lift(cosh), lift(sinh), lift(sqrt)
        self.real = _ufunc(lambda x: x)     # jets are complex: nothing calls for real parts
        self._upper = np.frompyfunc(
            lambda x: float(flint.acb(x.c[0] if isinstance(x, Jet) else x).abs_upper()), 1, 1)

    @property
    def key(self) -> tuple:
        return (self.name, self.prec, self.order)

    def variable(self, z):
        """``lam`` itself as a jet at ``z`` (a point or a box)."""
        return Jet((self.flint.acb(z), self.flint.acb(1)) + (self.flint.acb(0),) * (self.order - 1))

    def _convert(self, value):
        return self._constant(super()._convert(value))

    def _constant(self, v):
        return Jet((v,) + (0,) * self.order)

    def number(self, z):
        return z if isinstance(z, Jet) else self._constant(super().number(z))

    def zeros(self, shape, like=None):
        return _filled(shape, self._constant(self.flint.acb(0)))

    def root4(self, x):
        base = super().root4

        def root(u):
            if not isinstance(u, Jet):
                return base(np.array([u], dtype=object))[0]
            r = base(np.array([u.c[0]], dtype=object))[0]
            r3 = r * r * r
            r7 = r3 * r3 * r
            # x**(1/4): derivatives 1/(4 r**3), -3/(16 r**7), 21/(64 r**11)
            f = (r, 1 / (4 * r3), -3 / (16 * r7), 21 / (64 * r7 * r3 * r))
            return Jet(_compose(f, u.c))
        return _ufunc(root)(x)

    def is_complex(self, x):
        return True

    def norm_variable(self, X):
        """Jets ``(0, |X1|, |X2|, ...)`` (the norms of the Taylor coefficients of ``X``,
        infinity norms over the rows, upper bounds) per element of the arrays of the matrix
        ``X`` (nested lists of equally shaped arrays): a scalar series in this variable
        majorizes the matrix series in ``X`` coefficient by coefficient."""
        flint = self.flint
        n = len(X)
        shape = np.shape(X[0][0])
        out = np.empty(shape, dtype=object)
        for idx in np.ndindex(shape):
            bounds = []
            for k in range(1, self.order + 1):
                best = 0.0
                for i in range(n):
                    row = 0.0
                    for j in range(n):
                        v = X[i][j][idx]
                        if isinstance(v, Jet) and not isinstance(v.c[k], int):
                            row += float(flint.acb(v.c[k]).abs_upper())
                    best = max(best, row)
                bounds.append(flint.acb(math.nextafter(best * (1 + 1e-14), math.inf)))
            out[idx] = Jet((flint.acb(0), *bounds))
        return out

    def widen(self, x, radius, wrt=None, slope=None, curve=None, third=None):
        """``x`` with the tail ``T`` of a truncated series in ``wrt`` (a jet): ``radius``
        bounds ``|T|``, ``slope``, ``curve`` and ``third`` bound its first three derivatives
        in the series variable where the series is summed; the jet's coefficients get
        those of ``T(x)`` by the chain rule (``x1, x2, x3`` those of ``wrt``): ``T' x1``,
        ``T' x2 + T'' x1**2 / 2``, ``T' x3 + T'' x1 x2 + T''' x1**3 / 6``.

        Without the bounds its order needs, a tail is refused (a jet must not lose them)."""
        if (slope is None or (self.order > 1 and curve is None)
                or (self.order > 2 and third is None)):
            raise NotImplementedError("a series tail without bounds on its derivatives")
        flint = self.flint

        def upper(v):
            # a float upper bound, nudged up: float() of an arb rounds to nearest
            return math.nextafter(float(flint.acb(v).abs_upper()), math.inf)

        def ball(bound):
            with self:
                r = flint.arb(0, flint.arb(bound).upper())
            return flint.acb(r, r)

        def up(v):
            # float bounds computed in floats: a margin for their own rounding
            return v * (1 + 1e-14) + 1e-300

        r0, s, k, t = (up(float(flint.arb(self.exact(v).c[0]).upper())) for v in
                       (radius, slope, curve if curve is not None else 0,
                        third if third is not None else 0))

        def add(v, w):
            x = w.c if isinstance(w, Jet) else (w, 0, 0, 0)
            x1, x2, x3 = ((upper(x[i]) if len(x) > i else 0.0) for i in (1, 2, 3))
            bounds = [r0, up(s * x1), up(s * x2 + k * x1 * x1 / 2),
                      up(s * x3 + k * x1 * x2 + t * x1 * x1 * x1 / 6)]
            return Jet([c + ball(b) for c, b in zip(v.c, bounds)])
        return np.frompyfunc(add, 2, 1)(x, wrt)
