"""What a search would cost, bounded before it starts.

A request no search can finish (``--omega-max 1e100`` on a beam whose first
frequency is 1 rad/s asks for some 10**50 eigenvalues) is refused at once, with
the flag to change, instead of running for ever. The bound is a lower bound on
the number of eigenvalues below ``omega``, so a request that passes may still
be large, but one refused is certainly beyond :data:`symtmm.limits.MAX_EIGENVALUES`.

The lower bound
---------------
Clamp every beam at both ends and at every point where something is attached
(springs, masses, rigid bodies, joints). Constraints only raise the eigenvalues
of a conservative system (Rayleigh's theorem), so the constrained system has
no more eigenvalues below ``omega`` than the model. It falls apart into
clamped-clamped pieces, each carrying nothing. For a piece of length ``l`` the
first ``n`` clamped-clamped Euler-Bernoulli modes span a space on which the
Rayleigh quotient is at most ``(EI b**4 + max(N, 0) b**2 + kw) / m`` with
``b = beta_n = ((n + 1/2) pi + 0.02) / l`` (the roots of ``cos x cosh x = 1``
lie within 0.018 of ``(n + 1/2) pi``; ``int v'**2 <= b**2 int v**2`` follows from
``int v''**2 <= b**4 int v**2`` by Cauchy-Schwarz). Rotary inertia only adds to
the kinetic energy and shear flexibility only lowers the strain energy (an
Euler-Bernoulli shape is a Timoshenko shape without shear), so by the min-max
principle the piece has at least every such ``n`` with that quotient below
``omega**2``, whatever the theory. For a damped model the same count of the model
without its dashpots stands for the size of the search region.

Examples
--------
>>> from symtmm.model import Beam, Model
>>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
>>> eigenvalues_below(pp, 1000)   # clamped-clamped 22.4, 61.7, ..., 890.6 below 1000 rad/s
9

(the model itself has 10 there: ``omega_n = n**2 pi**2``).
"""

from __future__ import annotations

import itertools
import math
import numbers

from .errors import ModelError
from .limits import MAX_EIGENVALUES
from .model import Model

__all__ = ["eigenvalues_below", "check_search", "checked_request"]

#: beta_n l of a clamped-clamped Euler-Bernoulli beam is below (n + 1/2) pi + this
_ROOT_MARGIN = 0.02


def _pieces(model: Model) -> list:
    """``(beam, length)`` of every piece between the points where something is attached."""
    cuts = {b.name: {b.x0, b.x1} for b in model.beams}
    for s in model.springs:
        for end in (s.a, s.b):
            if end in cuts:
                cuts[end].add(s.x)
    for p in model.masses:
        cuts[p.beam].add(p.x)
    for body in model.bodies:
        for att in body.attachments:
            cuts[att.beam].add(att.x)
    pieces = []
    for beam in model.beams:
        # lengths from the exact positions: two points 1e-20 apart near x = 1 stay apart
        xs = sorted(cuts[beam.name], key=float)
        pieces += [(beam, float(b - a)) for a, b in itertools.pairwise(xs) if float(b - a) > 0]
    return pieces


def eigenvalues_below(model: Model, omega: float, cap: int = MAX_EIGENVALUES) -> int:
    """A lower bound on the number of eigenvalues with ``Im lam <= omega`` (undamped model).

    Parameters
    ----------
    model : Model
        Every parameter with a value.
    omega : float
        Circular frequency, rad/s.
    cap : int
        Counting stops above this (the answer is then ``cap + 1``).

    Returns
    -------
    int
    """
    model = model.require_numeric()
    omega2 = float(omega) ** 2
    total = 0
    for beam, length in _pieces(model):
        EI, m, kw, N = (float(v) for v in (beam.EI, beam.m, beam.kw, beam.N))
        tension = max(N, 0.0)
        if beam.is_rod:
            EI = 0.0        # a rod's axial modes alone (its N is EA): still a lower bound

        def below(n, EI=EI, m=m, kw=kw, tension=tension, length=length):
            b = ((n + 0.5) * math.pi + _ROOT_MARGIN) / length
            return (EI * b**4 + tension * b**2 + kw) / m <= omega2

        if not below(1):
            continue
        lo, hi = 1, 2                   # below(lo), and the search for the first n not below
        while hi <= cap + 1 and below(hi):
            lo, hi = hi, 2 * hi
        hi = min(hi, cap + 2)
        while hi - lo > 1:
            mid = (lo + hi) // 2
            lo, hi = (mid, hi) if below(mid) else (lo, mid)
        total += lo
        if total > cap:
            return cap + 1
    return total


def check_search(model: Model, count=None, omega_max=None, sigma_max=None) -> None:
    """Refuse a search whose size is beyond :data:`symtmm.limits.MAX_EIGENVALUES`.

    Parameters
    ----------
    model : Model
    count : int, optional
    omega_max, sigma_max : float, optional
        The search region (``sigma_max`` of damped models; its default follows
        :func:`symtmm.roots.damped.default_sigma_max`).

    Raises
    ------
    ModelError
        Naming the argument to change.
    """
    if count is not None and omega_max is not None:
        raise ModelError("give count or omega_max, not both", field="count",
                         source=model.source)
    if count is not None and (isinstance(count, bool) or not isinstance(count, numbers.Integral)
                              or count < 1):
        raise ModelError(f"must be a whole number of at least 1, got {count!r}", field="count",
                         source=model.source)
    if count is not None and count > MAX_EIGENVALUES:
        raise ModelError(f"asks for {count} eigenvalues; a search delivers at most "
                         f"{MAX_EIGENVALUES}", field="count", source=model.source)
    if omega_max is not None and sigma_max is None and model.damped:
        from .roots.damped import default_sigma_max
        sigma_max = default_sigma_max(omega_max)
    for name, value in (("omega_max", omega_max), ("sigma_max", sigma_max)):
        if value is None:
            continue
        value = float(value)
        if not math.isfinite(value) or value < 0:
            raise ModelError(f"must be a finite number >= 0, got {value}", field=name,
                             source=model.source)
        if eigenvalues_below(model, value) > MAX_EIGENVALUES:
            what = ("more than {n} eigenvalues lie below {v:g} rad/s, more than one search "
                    "delivers: lower it, or ask for the first ones by count"
                    if name == "omega_max" else
                    "a search region reaching {v:g} from the imaginary axis is as large as "
                    "one holding more than {n} eigenvalues, more than one search delivers: "
                    "lower it")
            message = what.format(n=MAX_EIGENVALUES, v=value)
            raise ModelError(message, field=name, source=model.source,
                             cli_message=message.replace("by count", "with --count"))


def checked_request(model: Model, count, omega_max, digits: int) -> Model:
    """What every solver checks first: a count or a frequency bound, and digits; returns
    the numeric model (a :class:`ValueError` for a caller's mistake, a
    :class:`~symtmm.errors.ModelError` naming a parameter without value)."""
    if count is None and omega_max is None:
        raise ValueError("give count or omega_max")
    if digits < 1:
        raise ValueError("digits must be positive")
    return model.require_numeric()
