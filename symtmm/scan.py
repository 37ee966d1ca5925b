"""``log10|Delta|`` along the frequency axis and over the complex plane.

The paper locates eigenvalues by scanning ``log10|Delta|`` for minima
(figs. 9 and 12 along ``omega``, fig. 14 over ``(Re lam, Im lam)`` for damped
systems). :func:`scan` computes the same pictures, with the eigenvalues of
:func:`symtmm.solve.solve` to mark the true roots.

The curve is the transfer formulation's ``Delta = det R``, as the paper plots it,
in double precision (:func:`symtmm.numeric.transfer.log_delta`). ``|Delta|`` grows like
``exp(sum |beta| L)`` and near a root cancels from that size down to zero, so
in double precision the depth of each dip is limited by rounding (about
``1e-16`` times the size of the terms) and, at high frequency, the whole
curve near a root is rounding noise. That is fine for a picture — the dips
stand where the roots are — but the values are not accurate there; the
eigenvalues themselves come from the exact solver.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field, replace

import numpy as np

from .deadline import time_budget
from .errors import ComputationError, ModelError
from .jsonout import dumps, header
from .limits import SEARCH_SECONDS
from .model import Model
from .numeric import transfer
from .results import Spectrum
from .tables import Tabular

__all__ = ["Scan", "scan"]


def _finite_list(values):
    """Floats for JSON, with ``-inf`` (an exact zero of Delta) as null."""
    return [float(v) if np.isfinite(v) else None for v in values]


@dataclass(frozen=True, repr=False)
class Scan(Tabular):
    """``log10|Delta|`` of a model on a frequency grid (and a complex-plane grid).

    Attributes
    ----------
    omega : numpy.ndarray
        Circular frequencies [rad/s], ``lam = i omega``.
    log10_delta : numpy.ndarray
        ``log10|Delta(i omega)|`` (``-inf`` where Delta is exactly zero).
    spectrum : Spectrum or None
        The eigenvalues marked (None when they could not be computed; see notes).
    omega_scale : tuple or None
        ``(beam name, sqrt(EI/(m L^4)))`` of the first beam: ``omega = Omega**2 * scale``.
    map_sigma, map_omega : numpy.ndarray or None
        Damped models: decay rates ``sigma = -Re lam`` [1/s] (from slightly
        below 0) and frequencies of the map grid.
    map_log10 : numpy.ndarray or None
        ``log10|Delta(-sigma + i omega)|``, shape ``(len(map_omega), len(map_sigma))``.
    """

    omega: np.ndarray
    log10_delta: np.ndarray
    spectrum: Spectrum | None = None
    omega_scale: tuple | None = None
    model_name: str = ""
    map_sigma: np.ndarray | None = None
    map_omega: np.ndarray | None = None
    map_log10: np.ndarray | None = None
    notes: tuple = field(default_factory=tuple)
    title: str = ""

    @property
    def damped(self) -> bool:
        """True when the scan carries a complex-plane map."""
        return self.map_log10 is not None

    def local_minima(self) -> np.ndarray:
        """Frequencies of the local minima of the curve (the paper's fMin1D candidates)."""
        y = np.where(np.isfinite(self.log10_delta), self.log10_delta, -np.inf)
        inner = (y[1:-1] < y[:-2]) & (y[1:-1] <= y[2:])
        return self.omega[1:-1][inner]

    def to_dict(self) -> dict:
        """The JSON object of ``symtmm scan --json``."""
        digits = None if self.spectrum is None else self.spectrum.digits
        out = header(self.model_name, self.title, digits, self.notes) | {
            "omega": [float(w) for w in self.omega],
            "log10_abs_delta": _finite_list(self.log10_delta),
            "eigenvalues": None if self.spectrum is None else
            [e.to_dict() for e in self.spectrum],
        }
        if self.omega_scale:
            out["omega_scale"] = {"beam": self.omega_scale[0], "scale": self.omega_scale[1]}
        if self.damped:
            out["map"] = {"sigma": [float(s) for s in self.map_sigma],
                          "omega": [float(w) for w in self.map_omega],
                          "log10_abs_delta": [_finite_list(row) for row in self.map_log10]}
        return out

    def to_json(self) -> str:
        """:meth:`to_dict` as a JSON string."""
        return dumps(self.to_dict())

    def records(self):
        """``(columns, rows)``: the curve, one row per frequency (``log10_abs_delta`` empty
        where Delta is exactly zero)."""
        return (["omega", "log10_abs_delta"],
                [[float(w), float(v) if math.isfinite(v) else ""]
                 for w, v in zip(self.omega, self.log10_delta)])

    def table(self) -> str:
        """A summary: the grid, the minima of the curve, the eigenvalues."""
        lines = [(f"log10|Delta(i omega)| at {len(self.omega)} points, omega from "
                  f"{self.omega[0]:.6g} to {self.omega[-1]:.6g} rad/s")]
        finite = self.log10_delta[np.isfinite(self.log10_delta)]
        if finite.size:
            lines.append(f"range {finite.min():.3f} .. {finite.max():.3f}")
        minima = self.local_minima()
        lines.append(f"{len(minima)} local minima at omega [rad/s]: "
                     + ", ".join(f"{w:.6g}" for w in minima[:30])
                     + (" ..." if len(minima) > 30 else ""))
        if self.spectrum is not None:
            lines.append(f"{self.spectrum.total} eigenvalue(s) with multiplicity, from solve: "
                         + ", ".join(str(e) for e in self.spectrum))
        if self.damped:
            lines.append(f"complex-plane map: {len(self.map_sigma)} x {len(self.map_omega)} "
                         f"points, -Re lam from {self.map_sigma[0]:.4g} to "
                         f"{self.map_sigma[-1]:.6g} 1/s")
        lines += list(self.notes)
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        from html import escape
        return "<pre>" + escape(self.table()) + "</pre>"

    def _repr_latex_(self) -> str | None:
        """The eigenvalues marked, as a LaTeX array (Jupyter); the curve is :meth:`plot`."""
        return self.spectrum._repr_latex_() if self.spectrum is not None else None

    def plot(self, **kwargs):
        """The curve as a matplotlib figure (see :func:`symtmm.plot.plot_scan`)."""
        from .plot import plot_scan
        return plot_scan(self, **kwargs)

    def plot_map(self, **kwargs):
        """The complex-plane map (damped models; see :func:`symtmm.plot.plot_scan_map`)."""
        from .plot import plot_scan_map
        return plot_scan_map(self, **kwargs)


def _log10_abs(plan: transfer.TransferPlan, lam):
    """``log10|Delta(lam)|`` from the stable evaluation: no overflow at high modes."""
    return transfer.log_delta(plan, lam)[0] / math.log(10)


def scan(model: Model, omega_max, points: int = 2000, omega_min=0.0, sigma_max=None,
         map_points: tuple = (241, 361), eigenvalues: bool = True, digits: int = 10,
         method: str = "default", spacing: str = "Omega",
         max_seconds: float | None = SEARCH_SECONDS) -> Scan:
    """``log10|Delta|`` on ``points`` frequencies in ``[omega_min, omega_max]``.

    Parameters
    ----------
    model : Model
        Every parameter must have a value.
    omega_max : float
        Highest circular frequency [rad/s].
    points : int
        Grid points along the frequency axis.
    omega_min : float
        Lowest frequency (default 0).
    sigma_max : float, optional
        Damped models: the map covers ``-sigma_max <= Re lam <= 0``; by default
        a quarter more than the largest decay rate found, or ``omega_max / 5``.
    map_points : (int, int)
        Damped models: grid points along ``Re lam`` and ``Im lam``.
    eigenvalues : bool
        Find the eigenvalues (with :func:`symtmm.solve.solve`) to mark them.
    digits, method
        Passed to :func:`symtmm.solve.solve`.
    spacing : {"Omega", "omega"}
        Grid equally spaced in the first beam's frequency parameter
        ``Omega ~ sqrt(omega)`` (default: roots are about evenly spaced in it, so
        every dip gets the same resolution) or in ``omega``.
    max_seconds : float or None
        Wall-clock budget of the whole scan, the eigenvalues' search included
        (:mod:`symtmm.deadline`): past it, a
        :class:`~symtmm.errors.ComputationError`. None: no limit.

    Returns
    -------
    Scan

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> s = scan(pp, omega_max=100, points=1001, spacing="omega")
    >>> np.round(s.local_minima(), 1)                 # (n pi)^2 = 9.87, 39.48, 88.83
    array([ 9.9, 39.5, 88.8])
    >>> [str(e) for e in s.spectrum]
    ['9.869604401i', '39.47841760i', '88.82643961i']
    """
    with time_budget(max_seconds):
        return _scan(model, omega_max, points, omega_min, sigma_max, map_points, eigenvalues,
                     digits, method, spacing)


def _scan(model, omega_max, points, omega_min, sigma_max, map_points, eigenvalues, digits,
          method, spacing) -> Scan:
    from .budget import check_search
    from .roots.undamped import omega_scale
    from .solve import solve

    model = model.require_numeric()
    try:
        omega_max = float(omega_max)
        omega_min = float(omega_min)
    except (TypeError, ValueError):
        raise ModelError("must be a number", field="omega_max") from None
    if not (math.isfinite(omega_max) and omega_max > 0):
        raise ModelError("must be a positive number", field="omega_max")
    if not 0 <= omega_min < omega_max:
        raise ModelError("must lie in [0, omega_max)", field="omega_min")
    if int(points) < 3:
        raise ModelError("need at least 3 points", field="points")
    if spacing not in ("Omega", "omega"):
        raise ValueError("spacing must be 'Omega' or 'omega'")
    # the curve costs about as much as a search up to omega_max (segments cut by wave number)
    check_search(model, omega_max=omega_max, sigma_max=sigma_max)
    plan = transfer.TransferPlan(model)
    scale = omega_scale(model)
    if spacing == "Omega":
        omega = np.linspace(math.sqrt(omega_min), math.sqrt(omega_max), int(points)) ** 2
        omega[[0, -1]] = omega_min, omega_max
    else:
        omega = np.linspace(omega_min, omega_max, int(points))
    curve = _log10_abs(plan, 1j * omega)
    notes = []
    spectrum = None
    if eigenvalues:
        try:
            spectrum = solve(model, omega_max=omega_max, sigma_max=sigma_max, digits=digits,
                             method=method)
            if omega_min > 0:
                kept = tuple(e for e in spectrum if float(e.omega) >= omega_min)
                spectrum = replace(spectrum, eigenvalues=kept)
        except ComputationError as exc:
            notes.append(f"eigenvalues not marked: {exc}")
    map_sigma = map_omega = map_log10 = None
    if model.damped:
        if sigma_max is None:
            found = [float(e.sigma) for e in spectrum] if spectrum is not None else []
            top = max(found, default=0.0)
            sigma_max = 1.25 * top if top > 0 else omega_max / 5
        sigma_max = float(sigma_max)
        if not (math.isfinite(sigma_max) and sigma_max > 0):
            raise ModelError("must be a positive number", field="sigma_max")
        n_re, n_im = (int(p) for p in map_points)
        # a little of the right half-plane too, so that undamped roots show whole dips
        map_sigma = np.linspace(-0.04 * sigma_max, sigma_max, n_re)
        map_omega = np.linspace(omega_min, omega_max, n_im)
        lam = -map_sigma[None, :] + 1j * map_omega[:, None]
        map_log10 = _log10_abs(plan, lam)
    scale = None if scale is None else (scale[0], float(scale[1]))
    return Scan(omega, curve, spectrum, scale, model.source or "", map_sigma,
                map_omega, map_log10, tuple(notes), model.title)
