"""``solve``: eigenvalues of a model by a named method.

Methods are registered in :data:`METHODS`; each takes
``(model, count, omega_max, sigma_max, digits)`` and returns a
:class:`~symtmm.results.Spectrum`.
"""

from __future__ import annotations

from .budget import check_search
from .deadline import time_budget
from .errors import ModelError
from .limits import SEARCH_SECONDS
from .model import Model
from .numeric.plan import crowding
from .results import Spectrum
from .roots.apart import solve_apart, split
from .roots.damped import solve_damped
from .roots.fmin import fmin1d, fmin2d
from .roots.undamped import solve_undamped

__all__ = ["solve", "METHODS"]


def _default(model, count, omega_max, sigma_max, digits, prove_count=False, guesses=None):
    if model.damped:
        parts = split(model)
        if parts is not None:
            # (undamped unjoined parts on the frequency axis, where their clusters are
            # counted exactly: symtmm.roots.apart)
            return solve_apart(model, *parts, count, omega_max, sigma_max, digits,
                               prove_count=prove_count)
        return solve_damped(model, count=count, omega_max=omega_max, sigma_max=sigma_max,
                            digits=digits, prove_count=prove_count)
    # (the count on the frequency axis is proved already: Wittrick-Williams in balls)
    return solve_undamped(model, count=count, omega_max=omega_max, digits=digits,
                          guesses=guesses)


def _contour(model, count, omega_max, sigma_max, digits, prove_count=False):
    # the complex-plane search for any model (for undamped ones: a second, independent method)
    from dataclasses import replace
    spectrum = solve_damped(model, count=count, omega_max=omega_max, sigma_max=sigma_max,
                            digits=digits, prove_count=prove_count)
    return replace(spectrum, method="contour")


def _pairs(guesses) -> list:
    """``guesses`` as ``(omega, half-width)`` floats; a clear error for anything else."""
    try:
        return [(float(w), float(d)) for w, d in guesses]
    except (TypeError, ValueError):
        raise ModelError("guesses must be pairs (omega, relative half-width) of numbers",
                         field="guesses") from None


#: Root-search methods by name.
METHODS = {"default": _default, "contour": _contour, "fmin1d": fmin1d, "fmin2d": fmin2d}


def solve(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
          digits: int = 15, method: str = "default", prove_count: bool = False,
          guesses=None, max_seconds: float | None = SEARCH_SECONDS) -> Spectrum:
    """Eigenvalues ``lam`` with ``Im lam >= 0``, ascending by ``Im lam``.

    Parameters
    ----------
    model : Model
        Every parameter must have a value.
    count : int, optional
        The first ``count`` eigenvalues, counted with multiplicity.
    omega_max : float, optional
        All eigenvalues with ``0 <= Im lam <= omega_max`` (instead of ``count``).
    sigma_max : float, optional
        Damped models: the search region ``-sigma_max <= Re lam <= 0``
        (default ``2 omega_max``, see :func:`symtmm.roots.damped.default_sigma_max`).
    digits : int
        Significant digits, all correct.
    method : str
        A key of :data:`METHODS`.
    prove_count : bool
        Damped models (default and contour methods): also prove the number of
        eigenvalues in the search region by a winding number in ball arithmetic
        (python-flint; :func:`symtmm.roots.damped.solve_damped`). Undamped models have
        their count proved always.
    guesses : sequence of (float, float), optional
        Estimates ``(omega, relative half-width)`` of the first ``count`` natural
        frequencies, from a nearby model (:func:`symtmm.sweep.sweep` passes its
        previous steps' values, extrapolated). The default method on an undamped model
        looks there first; what it proves, and so every printed digit, does not depend
        on them (:meth:`symtmm.roots.undamped._Search.guided`). Other searches ignore
        them.
    max_seconds : float or None
        Time budget of the search (``--max-seconds``): past it, a
        :class:`~symtmm.errors.ComputationError` (:mod:`symtmm.deadline`); None for none.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> cc = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
    >>> print(solve(cc, count=2, digits=12).table())   # doctest: +ELLIPSIS
    #  omega [rad/s]  Omega (beam b)  mult.
    -  -------------  --------------  -----
    1  22.3732854481   4.73004074486      1
    2  61.6728228679   7.85320462410      1
    2 eigenvalue(s) with multiplicity, 12 significant digits; method default, ...
    """
    if method not in METHODS:
        raise ModelError(f"unknown method {method!r} (use one of {', '.join(METHODS)})",
                         field="method")
    if count is None and omega_max is None:
        count = 10
    model = model.require_numeric()
    check_search(model, count, omega_max, sigma_max)
    if prove_count and method in ("fmin1d", "fmin2d"):
        raise ModelError(f"method {method} is a grid search: it proves nothing; a proved count "
                         "needs the default or the contour method", field="method")
    extra = {"prove_count": True} if prove_count else {}
    if guesses is not None and method == "default":
        extra["guesses"] = _pairs(guesses)
    with time_budget(max_seconds, explain=lambda: crowding(model)):
        spectrum = METHODS[method](model, count, omega_max, sigma_max, digits, **extra)
    return spectrum.with_model_name(spectrum.model_name or model.source or "", model.title)
