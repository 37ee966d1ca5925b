"""The paper's grid searches, fMin1D and fMin2D, as named methods for comparison.

Both look for local minima of ``log10 |Delta|`` on a grid, in double
precision with the vectorised transfer-matrix evaluator (as the paper does),
and shrink a grid around each minimum until its bracket is narrower than
``TOL = 1e-6`` (absolute, rad/s and 1/s):

* ``fmin1d`` (undamped models): ``lam = i omega`` on :data:`GRID_1D` = 500
  points over ``[0, omega_max]`` (for ``count``: over a band doubled from a
  first guess until it shows enough minima), each interior minimum refined on
  :data:`REFINE_1D` = 50 points across its bracket (the neighbouring grid
  points), recursively.
* ``fmin2d`` (any model): ``lam = -sigma + i omega`` on a
  :data:`GRID_2D` = 200 x 200 grid over ``[0, sigma_max] x [0, omega_max]``,
  minima lower than their (up to 8) neighbours, each refined on
  :data:`REFINE_2D` = 21 x 21 grids across the box of its neighbours,
  recursively, until both sides are below ``TOL``.

What the results mean. A minimum of ``|Delta|`` is not proof of a root:
roots closer than the grid spacing merge into one minimum, and where
``Delta`` loses more digits than double precision holds (high modes,
``sum |beta| L / ln 10`` digits) rounding noise can hide minima or make
false ones. The methods report what they find and say so in the notes;
no root is checked during the search. Every eigenvalue gets multiplicity 1
and only the digits that are backed: the final grid bracket is widened by
the estimated distance to the nearest root, the Newton step ``|Delta/Delta'|``
of the cancellation-free ``Delta`` of the numeric kernel
(:class:`symtmm.numeric.evaluator.Evaluator`) at the minimum (an a-posteriori label, not part of the search), and only
the significant digits both ends of that print alike are shown, at most the
requested number; ``Spectrum.digits`` is the smallest of these. A minimum
that backs no digit (no root near it, or one moved by rounding noise) is not
reported; the notes count them. A real part whose bracket
reaches ``sigma = 0`` is printed as ``0`` (it is below the bracket in size).
"""

from __future__ import annotations

import math
import time

import mpmath
import numpy as np

from ..errors import ModelError
from ..model import Model
from ..numeric import transfer
from ..numeric.arith import MP
from ..numeric.evaluator import Evaluator
from ..results import Eigenvalue, Spectrum, first, prints_alike
from .damped import default_sigma_max
from .undamped import omega_scale, rigid_body_modes

__all__ = ["GRID_1D", "GRID_2D", "REFINE_1D", "REFINE_2D", "TOL", "fmin1d", "fmin2d"]

#: Points of the first grid along the frequency axis.
GRID_1D = 500
#: Points of each refining grid (1-D).
REFINE_1D = 50
#: Points per direction of the first (sigma, omega) grid.
GRID_2D = 200
#: Points per direction of each refining grid (2-D).
REFINE_2D = 21
#: Bracket width at which refinement stops (absolute).
TOL = 1e-6
#: Most minima refined in one search (the deepest first); more are reported in the notes.
MAX_MINIMA = 400


class _Transfer:
    """``log10|Delta|`` of the transfer formulation in double precision, as the paper
    evaluates it (stable at high modes, no overflow), counting its points."""

    def __init__(self, model: Model):
        self.plan = transfer.TransferPlan(model)
        self.evaluations = 0

    def __call__(self, lam) -> np.ndarray:
        lam = np.asarray(lam, dtype=complex)
        self.evaluations += lam.size
        return transfer.log_delta(self.plan, lam)[0] / math.log(10)


def _backed_digits(lo: float, hi: float, digits: int) -> int:
    """How many significant digits ``lo`` and ``hi`` share when printed (at most ``digits``).

    Examples
    --------
    >>> _backed_digits(146.2697995, 146.2698005, 15)     # both print as 146.26980
    8
    >>> _backed_digits(-1e-7, 1e-7, 15)
    0
    """
    if lo <= 0 <= hi:
        return 0
    d = 0
    lo, hi = _mpf(lo), _mpf(hi)
    while d < digits and prints_alike(lo, hi, d + 1):
        d += 1
    return d


def _mpf(x) -> mpmath.mpf:
    """A float as a global mpmath number, exactly."""
    return mpmath.mp.make_mpf(mpmath.libmp.from_float(float(x)))


def _minima_1d(v: np.ndarray) -> list:
    """Indices of interior strict local minima (plateaus: their first point)."""
    out = []
    for i in range(1, len(v) - 1):
        if v[i] < v[i - 1] and v[i] <= v[i + 1]:
            out.append(i)
    return out


def _refine_1d(f, lo: float, hi: float) -> tuple:
    """Shrink ``[lo, hi]`` around the minimum of ``f`` with 50-point grids."""
    while hi - lo > TOL:
        grid = np.linspace(lo, hi, REFINE_1D)
        v = f(grid)
        j = int(np.argmin(v))
        new_lo, new_hi = grid[max(j - 1, 0)], grid[min(j + 1, REFINE_1D - 1)]
        if (new_lo, new_hi) == (lo, hi):
            break
        lo, hi = new_lo, new_hi
    return lo, hi


def _first_guess(model: Model) -> float:
    return min(math.pi ** 2 * math.sqrt(float(b.EI) / float(b.m)) / float(b.L) ** 2
               for b in model.beams)


def _spectrum(model, eigen, digits, method, evaluations, start, notes) -> Spectrum:
    eigen.sort(key=lambda e: (e.lam.imag, e.lam.real))
    shown = min([e.digits for e in eigen], default=digits)
    return Spectrum(tuple(eigen), shown, method, evaluations, time.perf_counter() - start,
                    model.source or "", omega_scale(model, 20), tuple(notes), title=model.title)


#: Safety factor on the Newton step: some zero of a cluster of ``m`` lies within
#: ``m |f/f'|``; clusters of up to this many zeros are covered.
_CLUSTER = 4


def _root_distance(ds: Evaluator, lam: complex) -> float:
    """A bound on the distance from ``lam`` to the nearest root: :data:`_CLUSTER` times
    the Newton step ``|Delta/Delta'|`` of the cancellation-free ``Delta`` of the kernel
    (:class:`symtmm.numeric.evaluator.Evaluator`), ``Delta'`` by a central difference over
    ``1e-8 |lam|``. Labels the digits of a grid minimum; the search does not use it.
    """
    h = 1e-8 * max(abs(lam), 1e-300)
    la, ph, _ = ds.log_delta(np.array([lam, lam + 1j * h, lam - 1j * h]))
    value = np.exp(la + 1j * ph)
    slope = abs(value[1] - value[2]) / (2 * h)
    if not slope > 0:
        return math.inf
    return _CLUSTER * abs(value[0]) / slope


def _eigenvalue(re_bracket, im_bracket, digits, radius=0.0) -> Eigenvalue | None:
    """An eigenvalue at the centre of its bracket with the digits the bracket backs, the
    bracket widened by ``radius``; None if not even one digit is backed."""
    re_lo, re_hi = re_bracket[0] - radius, re_bracket[1] + radius
    im_lo, im_hi = im_bracket[0] - radius, im_bracket[1] + radius
    if not math.isfinite(radius):
        return None
    d_im = _backed_digits(im_lo, im_hi, digits) if im_lo > 0 else digits
    d_re = digits if re_lo <= 0 <= re_hi else _backed_digits(re_lo, re_hi, digits)
    d = min(d_im, d_re)
    if d < 1:
        return None
    ctx = MP(128).ctx        # the midpoints of two doubles, exactly
    re = ctx.mpf(0) if re_lo <= 0 <= re_hi else (ctx.mpf(re_lo) + re_hi) / 2
    im = ctx.mpf(0) if im_lo <= 0 else (ctx.mpf(im_lo) + im_hi) / 2
    return Eigenvalue(mpmath.mp.make_mpc((re._mpf_, im._mpf_)), 1, d,
                      ((re_lo, re_hi), (im_lo, im_hi)))


def _labelled(ds: Evaluator, boxes, digits: int, notes: list) -> list:
    """The grid minima's boxes ``((re_lo, re_hi), (im_lo, im_hi))`` as eigenvalues with the
    digits the distance to the nearest root backs; those that back none are counted in a
    note."""
    eigen, dropped = [], 0
    for re, im in boxes:
        radius = _root_distance(ds, complex(0.5 * (re[0] + re[1]), 0.5 * (im[0] + im[1])))
        e = _eigenvalue(re, im, digits, radius)
        if e is None:
            dropped += 1
        else:
            eigen.append(e)
    if dropped:
        notes.append(f"{dropped} minimum/minima not reported: not one digit of a root is "
                     "backed there (no root near, or rounding noise moved the minimum)")
    return eigen


def fmin1d(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
           digits: int = 15) -> Spectrum:
    """The paper's fMin1D: minima of ``log10|Delta(i omega)|`` on a grid (undamped models).

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> spec = fmin1d(pp, omega_max=100)
    >>> [e.to_dict()["imag"] for e in spec]     # (n pi)^2 = 9.86960440, 39.4784176, 88.8264396
    ['9.8696044', '39.478418', '88.826440']
    """
    model = model.require_numeric()
    if model.damped:
        raise ModelError("fmin1d searches the frequency axis and needs an undamped model; "
                         "use fmin2d (or the default method) for damped models",
                         field="method")
    start = time.perf_counter()
    ev = _Transfer(model)

    def f(omega):
        return ev(1j * np.asarray(omega, dtype=float))

    rigid = rigid_body_modes(model)
    notes = [(f"fmin1d: minima of log10|Delta| on {GRID_1D} points, refined on {REFINE_1D}-point "
             f"grids to brackets below {TOL:g} rad/s, double precision; a minimum is not proof "
             "of a root (close roots merge, rounding noise can hide or make minima)")]
    band = float(omega_max) if omega_max is not None else 2 * _first_guess(model)
    while True:
        grid = np.linspace(0.0, band, GRID_1D)
        mins = _minima_1d(f(grid))
        if count is None or rigid + len(mins) >= count or band > 1e9:
            break
        band *= 2
    if count is not None:
        notes.append(f"band searched: [0, {band:.6g}] rad/s")
    if len(mins) > MAX_MINIMA:
        notes.append(f"{len(mins)} minima, only the {MAX_MINIMA} lowest in frequency refined")
        mins = mins[:MAX_MINIMA]
    eigen = []
    if rigid:
        eigen.append(Eigenvalue(mpmath.mpc(0, 0), rigid, digits, (0.0, 0.0)))
    ds = Evaluator(model, 1.05 * band)
    boxes = []
    for i in mins:
        lo, hi = _refine_1d(f, grid[i - 1], grid[i + 1])
        boxes.append(((0.0, 0.0), (lo, hi)))
    eigen += _labelled(ds, boxes, digits, notes)
    if count is not None:
        eigen = first(sorted(eigen, key=lambda e: e.lam.imag), count)
    return _spectrum(model, eigen, digits, "fmin1d", ev.evaluations + ds.evaluations, start,
                     notes)


def _minima_2d(v: np.ndarray) -> list:
    """Grid points lower than each of their (up to 8) neighbours, deepest first."""
    n0, n1 = v.shape
    pad = np.pad(v, 1, constant_values=np.inf)
    lower = np.ones_like(v, dtype=bool)
    for di in (-1, 0, 1):
        for dj in (-1, 0, 1):
            if di or dj:
                lower &= v < pad[1 + di:n0 + 1 + di, 1 + dj:n1 + 1 + dj]
    idx = [tuple(p) for p in np.argwhere(lower & np.isfinite(v) | (v == -np.inf))]
    return sorted(idx, key=lambda p: v[p])


def _refine_2d(f, s_lo, s_hi, w_lo, w_hi) -> tuple:
    while s_hi - s_lo > TOL or w_hi - w_lo > TOL:
        s = np.linspace(s_lo, s_hi, REFINE_2D) if s_hi - s_lo > TOL else np.array([s_lo, s_hi])
        w = np.linspace(w_lo, w_hi, REFINE_2D) if w_hi - w_lo > TOL else np.array([w_lo, w_hi])
        S, Wg = np.meshgrid(s, w, indexing="ij")
        v = f(S, Wg)
        i, j = np.unravel_index(int(np.argmin(v)), v.shape)
        new = (s[max(i - 1, 0)], s[min(i + 1, len(s) - 1)],
               w[max(j - 1, 0)], w[min(j + 1, len(w) - 1)])
        if new == (s_lo, s_hi, w_lo, w_hi):
            break
        s_lo, s_hi, w_lo, w_hi = new
    return s_lo, s_hi, w_lo, w_hi


def fmin2d(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
           digits: int = 15) -> Spectrum:
    """The paper's fMin2D: minima of ``log10|Delta(-sigma + i omega)|`` on a 2-D grid.

    Examples
    --------
    >>> from symtmm.model import Beam, Spring, Model
    >>> b = Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned")
    >>> m = Model((b,), (Spring("b", "ground", x="3/10", k=0, c=4),))
    >>> [str(e) for e in fmin2d(m, omega_max=50)]   # -2.6916884+9.6441735i, -3.5781838+38.852743i
    ['-2.69169+9.64417i', '-3.578184+38.85274i']
    """
    model = model.require_numeric()
    start = time.perf_counter()
    ev = _Transfer(model)

    def f(S, Wg):
        return ev(-np.asarray(S) + 1j * np.asarray(Wg))

    notes = [(f"fmin2d: minima of log10|Delta| on a {GRID_2D} x {GRID_2D} grid over "
             f"(sigma, omega), refined on {REFINE_2D} x {REFINE_2D} grids to boxes below "
             f"{TOL:g}, double precision; a minimum is not proof of a root (close roots "
             "merge, rounding noise can hide or make minima)")]
    W = float(omega_max) if omega_max is not None else 2 * _first_guess(model)
    while True:
        S_max = default_sigma_max(W) if sigma_max is None else float(sigma_max)
        s = np.linspace(0.0, S_max, GRID_2D)
        w = np.linspace(0.0, W, GRID_2D)
        S, Wg = np.meshgrid(s, w, indexing="ij")
        v = f(S, Wg)
        mins = _minima_2d(v)
        if count is None or len(mins) >= count or W > 1e9:
            break
        W *= 2
    notes.append(f"region searched: {-S_max:.6g} <= Re lam <= 0, 0 <= Im lam <= {W:.6g}")
    if len(mins) > MAX_MINIMA:
        notes.append(f"{len(mins)} minima, only the {MAX_MINIMA} deepest refined")
        mins = mins[:MAX_MINIMA]
    ds = Evaluator(model, 1.05 * abs(complex(S_max, W)))
    boxes = []
    for i, j in mins:
        s_lo, s_hi, w_lo, w_hi = _refine_2d(f, s[max(i - 1, 0)], s[min(i + 1, GRID_2D - 1)],
                                            w[max(j - 1, 0)], w[min(j + 1, GRID_2D - 1)])
        boxes.append(((-s_hi, -s_lo), (w_lo, w_hi)))
    eigen = _labelled(ds, boxes, digits, notes)
    if count is not None:
        eigen = sorted(eigen, key=lambda e: e.lam.imag)[:count]
    return _spectrum(model, eigen, digits, "fmin2d", ev.evaluations + ds.evaluations, start,
                     notes)
