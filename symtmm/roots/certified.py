"""Certified eigenvalue enclosures in ball arithmetic (needs python-flint).

The solvers prove what they print where python-flint is installed (every
eigenvalue names its proof, :attr:`symtmm.results.Eigenvalue.proof`).
:func:`certify` turns a spectrum into rigorous enclosures: it takes over what
the solver proved and proves the rest afterwards (a spectrum found without
balls, by another method, or read back), all on the numeric kernel in Arb balls
(:mod:`symtmm.numeric`):

* ``exact``: ``lam = 0`` for rigid-body modes (the exact static null space,
  :func:`symtmm.mesh.static_nullity`).
* ``count``: an undamped eigenvalue of multiplicity ``m``: the Wittrick–Williams
  count in balls (every pivot's sign proved) differs by exactly ``m`` between
  the ends of its bracket, so the bracket holds ``m`` eigenvalues counted with
  multiplicity (exactly one eigenvalue of multiplicity ``m``, or several that
  agree to the bracket). Without a bracket, the one the printed digits imply.
* ``sign change``: a real eigenvalue of a damped model: ``Delta`` is real on
  the real axis, and balls of strictly opposite sign at the two ends of a
  bracket prove a zero between them.
* ``Rouche``: a simple eigenvalue off the real axis (or an undamped one given
  without a bracket): polished at ``D + 25`` digits, then Rouché's theorem on a
  box about it (with a note where that zero does not print as the value given) (``Delta`` within ``eps`` of its linear
  model on the box's boundary, ``eps`` from Cauchy's estimate and one enclosure
  of ``|Delta|`` over a larger square: :meth:`symtmm.roots.damped._Search._rouche`).
* ``none``: multiple eigenvalues of damped models are not certified; they are
  reported with ``"certified": false``.

A certified eigenvalue whose real part is printed as ``0`` (an undamped mode
of a damped model) gets an enclosure of its real part around 0: ball
arithmetic proves that the real part is tiny, never that it is exactly zero.
"""

from __future__ import annotations

from dataclasses import dataclass

import mpmath

from ..errors import ComputationError
from ..model import Model
from ..numeric.arith import MP, Ball, ball_available, to_arb
from ..results import Eigenvalue, Spectrum, decimal_string
from .count import Counter
from .damped import DAMPED_PROOFS, _imaginary, _Problem, _Search
from .undamped import PROOFS

__all__ = ["Enclosure", "Enclosures", "certify", "require_flint", "to_arb"]


def require_flint():
    """The ``flint`` module, or a :class:`ComputationError` saying how to install it."""
    if not ball_available():
        raise ComputationError("certified enclosures need python-flint: "
                               "pip install 'symtmm[certified]'")
    import flint
    return flint


def _exact(x) -> mpmath.mpf:
    """``x`` (a float or a number of any mpmath context) as a global mpmath number,
    unrounded (``mpmath.mpf(x)`` rounds to the ambient precision)."""
    if hasattr(x, "_mpf_"):
        return mpmath.mp.make_mpf(x._mpf_)
    return mpmath.mp.make_mpf(mpmath.libmp.from_float(float(x)))


# -- enclosures ------------------------------------------------------------------------------
@dataclass(frozen=True)
class Enclosure:
    """A rigorous enclosure of one eigenvalue (or the reason there is none).

    Attributes
    ----------
    eigenvalue : Eigenvalue
        The reported value.
    real, imag : tuple of mpmath.mpf or None
        ``(lower, upper)`` bounds of the real and imaginary part.
    proof : str
        ``"exact"``, ``"count"``, ``"sign change"``, ``"Rouche"`` or ``"none"``.
    note : str
        Why there is no proof, when that is known (e.g. a multiple eigenvalue
        of a damped model).
    """

    eigenvalue: Eigenvalue
    real: tuple | None
    imag: tuple | None
    proof: str
    note: str = ""

    @property
    def certified(self) -> bool:
        return self.proof != "none"

    @property
    def radius(self):
        """Half the larger side of the enclosing box (None when not certified)."""
        if not self.certified:
            return None
        ctx = MP(256).ctx
        half = max((ctx.mpf(hi) - ctx.mpf(lo)) / 2 for lo, hi in (self.real, self.imag))
        return _exact(half)

    def contains(self, z) -> bool:
        """``z`` lies in the enclosure."""
        if not self.certified:
            return False
        if isinstance(z, mpmath.mpf):
            z = mpmath.mp.make_mpc((z._mpf_, mpmath.libmp.fzero))
        elif not isinstance(z, mpmath.mpc):
            z = complex(z)
            z = mpmath.mp.make_mpc((mpmath.libmp.from_float(z.real),
                                    mpmath.libmp.from_float(z.imag)))
        return (self.real[0] <= z.real <= self.real[1]
                and self.imag[0] <= z.imag <= self.imag[1])

    def to_dict(self, digits: int) -> dict:
        """JSON-ready: outward-rounded decimal bounds with ``digits + 3`` digits."""
        if not self.certified:
            out = {"certified": False, "proof": "none"}
            if self.note:
                out["note"] = self.note
            return out
        d = digits + 3
        return {"certified": True, "proof": self.proof,
                "real": [_decimal(self.real[0], d, -1), _decimal(self.real[1], d, +1)],
                "imag": [_decimal(self.imag[0], d, -1), _decimal(self.imag[1], d, +1)],
                "radius": _decimal(self.radius, 3, +1)}


def _decimal(x, digits: int, direction: int) -> str:
    """``x`` rounded down (-1) or up (+1) to ``digits`` significant digits, as a string.

    Examples
    --------
    >>> _decimal(mpmath.mpf(2) / 3, 4, -1), _decimal(mpmath.mpf(2) / 3, 4, +1)
    ('0.6666', '0.6667')
    >>> _decimal(mpmath.mpf(0), 4, 1)
    '0'
    """
    if x == 0:
        return "0"
    ctx = MP.from_digits(digits + 40).ctx
    x = ctx.mpf(x)
    e = int(ctx.floor(ctx.log10(abs(x))))
    scale = ctx.mpf(10) ** (digits - 1 - e)
    q = ctx.floor(x * scale) if direction < 0 else ctx.ceil(x * scale)
    places = digits - 1 - e
    if places < 0:
        return str(int(q) * 10 ** (-places))
    return _fixed(int(q), places)


def _fixed(q: int, places: int) -> str:
    """The integer ``q`` scaled by ``10**-places`` as a plain decimal string."""
    sign = "-" if q < 0 else ""
    digits = str(abs(q)).rjust(places + 1, "0")
    if places == 0:
        return sign + digits
    return f"{sign}{digits[:-places]}.{digits[-places:]}"


# -- proofs ------------------------------------------------------------------------------------
class _Certifier:
    """Proofs for the eigenvalues of one model, on the numeric kernel in balls."""

    def __init__(self, model: Model, digits: int):
        require_flint()
        self.model = model.require_numeric()
        self.digits = digits
        self._counter = None
        self._search = None

    @property
    def evaluations(self) -> int:
        return sum(k.evaluations for k in (self._counter, self._search and self._search.p)
                   if k is not None)

    def _ball(self, digits: int) -> Ball:
        return Ball.from_digits(digits)

    def counter(self, top: float) -> Counter:
        if self._counter is None or self._counter.size < top:
            before = self._counter.evaluations if self._counter else 0
            self._counter = Counter(self.model, 1.01 * top)
            self._counter.evaluations = before
        return self._counter

    def search(self, size: float) -> _Search:
        if self._search is None or self._search.p.kernel.size < size:
            self._search = _Search(_Problem(self.model, 1.05 * size, certified=True),
                                   self.digits)
        return self._search

    # -- undamped: counts -------------------------------------------------------------------
    def count(self, e: Eigenvalue) -> Enclosure:
        D, omega = self.digits, e.lam.imag
        brackets = []
        if isinstance(e.bracket, tuple) and len(e.bracket) == 2 and \
                not isinstance(e.bracket[0], tuple):
            brackets.append(tuple(sorted(_exact(v) for v in e.bracket)))
        # the bracket the printed digits imply: half a unit in their last place
        ctx = MP.from_digits(D + 30).ctx
        half = ctx.mpf(10) ** (int(ctx.floor(ctx.log10(abs(ctx.mpf(omega))))) - D + 1) / 2
        brackets.append((_exact(ctx.mpf(omega) - half), _exact(ctx.mpf(omega) + half)))
        for lo, hi in brackets:
            if lo <= 0:
                continue
            counter = self.counter(float(hi))
            below, upto = counter.counts([lo, hi], self._ball(D + 30))
            if below >= 0 and upto >= 0 and upto - below == e.multiplicity:
                zero = mpmath.mpf(0)
                return Enclosure(e, (zero, zero), (lo, hi), "count")
        return Enclosure(e, None, None, "none", "the counts at the ends of its bracket are "
                                                "not its multiplicity apart")

    # -- damped: sign change and Rouche -------------------------------------------------------
    def real_root(self, e: Eigenvalue) -> Enclosure:
        D, x = self.digits, e.lam.real
        if isinstance(e.bracket, tuple) and len(e.bracket) == 2 and \
                not isinstance(e.bracket[0], tuple):
            lo, hi = sorted(_exact(v) for v in e.bracket)
        else:
            ctx = MP.from_digits(D + 30).ctx
            half = ctx.mpf(10) ** (int(ctx.floor(ctx.log10(abs(ctx.mpf(x))))) - D + 1) / 2
            lo, hi = _exact(ctx.mpf(x) - half), _exact(ctx.mpf(x) + half)
        search = self.search(abs(float(lo)) + 1.0)
        values = search._real_values([lo, hi], D + 30)
        zero = mpmath.mpf(0)
        if None not in values and (values[0] > 0) != (values[1] > 0):
            return Enclosure(e, (lo, hi), (zero, zero), "sign change")
        return Enclosure(e, None, None, "none", "no sign change of Delta across its bracket")

    def complex_root(self, e: Eigenvalue) -> Enclosure:
        D, lam = self.digits, e.lam
        search = self.search(float(abs(lam)) * 1.01)
        ctx = MP.from_digits(D + 40).ctx
        z = ctx.mpc(lam)
        parts = [abs(p) for p in (z.real, z.imag) if p != 0]
        r = min(min(parts) * ctx.mpf(10) ** (-(D + 3)), abs(z) * ctx.mpf(10) ** (-(D + 15)))
        digits = int(-ctx.log10(r / abs(z))) + 15
        polished, _ = search._secants([lam], digits, [_exact(r / 1000)])[0]
        if polished is not None:
            if lam.real == 0:
                polished = _imaginary(polished)    # an undamped mode: Re = 0 printed
            box = _exact(r)
            if search._rouche([(polished, box)], digits + 10)[0]:
                re_lo, re_hi = _exact(ctx.mpf(polished.real) - r), _exact(ctx.mpf(polished.real) + r)
                im_lo, im_hi = _exact(ctx.mpf(polished.imag) - r), _exact(ctx.mpf(polished.imag) + r)
                printed = e.to_dict()
                same = all(printed[k] == "0" or (decimal_string(a, D) == printed[k]
                                                 == decimal_string(b, D))
                           for k, a, b in (("real", re_lo, re_hi), ("imag", im_lo, im_hi)))
                note = "" if same else "the zero proved near it prints differently"
                return Enclosure(e, (re_lo, re_hi), (im_lo, im_hi), "Rouche", note)
        return Enclosure(e, None, None, "none", "Rouche's theorem did not apply on the box")

    # -- one eigenvalue ----------------------------------------------------------------------
    def enclose(self, e: Eigenvalue) -> Enclosure:
        lam = e.lam
        zero = mpmath.mpf(0)
        if lam == 0 and (e.proof == PROOFS["exact"] or e.bracket == (0.0, 0.0)):
            return Enclosure(e, (zero, zero), (zero, zero), "exact")
        # what the solvers proved already
        if e.proof == PROOFS["ball"] and e.bracket is not None and lam.real == 0:
            lo, hi = sorted(e.bracket)
            return Enclosure(e, (zero, zero), (_exact(lo), _exact(hi)), "count")
        if e.proof == DAMPED_PROOFS["ball"] and e.bracket is not None:
            lo, hi = sorted(e.bracket)
            return Enclosure(e, (_exact(lo), _exact(hi)), (zero, zero), "sign change")
        if e.proof in (DAMPED_PROOFS["rouche"], DAMPED_PROOFS["rouche_idle"]):
            (a, b), (c, d) = e.bracket
            return Enclosure(e, (_exact(a), _exact(b)), (_exact(c), _exact(d)), "Rouche")
        # proved now
        undamped = not self.model.damped and lam.real == 0 and lam.imag > 0
        if undamped and (e.multiplicity > 1 or e.bracket is not None):
            return self.count(e)
        if e.multiplicity > 1:
            return Enclosure(e, None, None, "none", "a multiple eigenvalue of a damped model")
        if lam.imag == 0:
            return self.real_root(e)
        return self.complex_root(e)


def certify(model: Model, spectrum: Spectrum) -> list:
    """Rigorous enclosures of the eigenvalues of ``spectrum`` (one :class:`Enclosure` each).

    Parameters
    ----------
    model : Model
        The model the spectrum belongs to.
    spectrum : Spectrum

    Raises
    ------
    ComputationError
        Without python-flint.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> enc = certify(pp, solve(pp, count=2, digits=12))
    >>> with mpmath.workdps(40):                   # the roots (n pi)^2 i, to 40 digits
    ...     inside = [e.contains(mpmath.mpc(0, (n * mpmath.pi) ** 2)) for e, n in zip(enc, (1, 2))]
    >>> [e.proof for e in enc], inside             # proved by the solver's counts already
    (['count', 'count'], [True, True])
    """
    certifier = _Certifier(model, spectrum.digits)
    out = Enclosures(certifier.enclose(e) for e in spectrum)
    out.evaluations = certifier.evaluations
    return out


class Enclosures(list):
    """The enclosures of a spectrum, with :attr:`evaluations`: the evaluations of Delta
    or the count (in balls) that proving them took."""

    evaluations: int = 0
