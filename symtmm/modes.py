"""Mode shapes: the state ``[Y, Theta, M, Q]`` along every beam at an eigenvalue.

At an eigenvalue ``lam`` the boundary matrix ``R(lam)`` is singular; a null
vector gives the unknowns of the overall transfer equation (the beams'
left-end state variables, and each rigid body's deflection, rotation and the
forces it exerts), and the transfer matrices carry that extended state along
the beams (paper eq. 3). The steps:

1. **Precision.** The entries of ``R`` grow like ``exp(|s| L)`` (``s`` the
   largest wave number), so the work is done in mpmath at
   ``digits + loss + 15`` decimal digits, ``loss`` being
   :meth:`~symtmm.compile.Evaluator.digits_lost` at the eigenvalue.
2. **Null space.** At that precision, the space of the right singular
   vectors of the ``m`` smallest singular values of ``R(lam)`` (``m`` the
   multiplicity), by block inverse iteration on an LU factorisation
   (:func:`_null_space`). Backward stable, it keeps the growing exponential
   out of the vector, so the shape is as accurate as the eigenvalue, even
   near the far end.
3. **Propagation.** The layout (:class:`~symtmm.assembly.Layout`) is walked
   on the extended state: every segment (any beam theory) by its transfer
   matrix (``evaluate_mp``, with ``l=`` the distance to a sample point), every
   station by its exact jump entries ``z -> (I + G) z`` (springs, masses,
   rigid bodies and joints).
4. **Normalisation.** Undamped shapes are real and mass-normalised in the
   full kinetic energy: over the beams the integral of
   ``m Y**2 + rhoI Theta**2`` (``Theta`` the section's rotation: rotary
   inertia of Rayleigh and Timoshenko beams), plus ``M Y**2 + J Theta**2`` of
   every lumped mass and ``M Y_c**2 + J Theta_c**2`` of every rigid body (its
   unknowns in the null vector), which keeps the shapes of distinct
   frequencies orthogonal. An Euler–Bernoulli segment's integral has the
   closed form ``[F]/(4 kappa)``, ``kappa = beta**4``,
   ``F = x (kappa Y**2 - 2 Y' Y''' + Y''**2) + 3 Y Y''' - Y' Y''`` (from
   ``Y'''' = kappa Y``); every other segment (and an Euler–Bernoulli one where
   ``kappa l**4`` is small) is integrated by Gauss--Legendre quadrature on
   pieces with ``|s| h <= 1``, with as many nodes as the digits asked for need
   (:func:`gauss_legendre_nodes`). The ``m`` shapes of a multiple eigenvalue
   are made mass-orthonormal (Cholesky factor of their mass Gram matrix).
   Each shape's largest displacement is made positive. Damped shapes are
   complex and scaled so that the largest ``|Y|`` over all beams is ``1``
   (real).

Sample points and the two sides of a station: at a spring (or a body's
attachment) the shear force jumps. The state reported at a beam's left end
is the one before the jumps there and at its right end the one after them
(the states the boundary conditions constrain: a beam end held by a body is
"free" outside it); at interior points sitting on a station the state just
right of it (after the jumps). :func:`evaluate_mode` gives either side.
"""

from __future__ import annotations

import functools
import json
import math
import random
import time
from dataclasses import dataclass, field

import mpmath
import numpy as np
import sympy as sp

from .assembly import Interval, Layout
from .compile import Evaluator
from .elements import STATE, EulerBernoulliSegment
from .elements.base import LAM
from .errors import ComputationError, ModelError
from .expr import ExpressionError, parse_expression
from .model import Model
from .numeric import to_mp
from .results import Eigenvalue, Spectrum, decimal_string

__all__ = ["BeamShape", "ModeSet", "ModeShape", "evaluate_mode", "mode_shapes", "shapes_at",
           "working_digits"]

#: Below this ``|kappa| l**4`` the closed-form integral would cancel; use quadrature.
_CLOSED_FORM_MIN = mpmath.mpf("1e-2")


@dataclass(frozen=True)
class BeamShape:
    """A mode shape sampled along one beam.

    Attributes
    ----------
    name : str
        The beam.
    x : numpy.ndarray
        Global coordinates of the sample points, both ends included.
    Y, Theta, M, Q : numpy.ndarray
        Displacement, slope, bending moment ``EI Y''`` and shear force
        ``EI Y'''`` at the sample points (float for undamped, complex for
        damped models).
    """

    name: str
    x: np.ndarray
    Y: np.ndarray
    Theta: np.ndarray
    M: np.ndarray
    Q: np.ndarray

    def __getitem__(self, variable: str) -> np.ndarray:
        """One of ``"x", "Y", "Theta", "M", "Q"`` by name."""
        if variable not in ("x",) + STATE:
            raise KeyError(variable)
        return getattr(self, variable)

    def to_dict(self) -> dict:
        """``{"x", "Y", "Theta", "M", "Q"}``; complex arrays as ``{"real", "imag"}``."""
        out = {"x": [float(v) for v in self.x]}
        for var in STATE:
            arr = getattr(self, var)
            if np.iscomplexobj(arr):
                out[var] = {"real": [float(v) for v in arr.real],
                            "imag": [float(v) for v in arr.imag]}
            else:
                out[var] = [float(v) for v in arr]
        return out


@dataclass(frozen=True)
class ModeShape:
    """One mode: its eigenvalue, its shape along every beam, and how to recompute it.

    Attributes
    ----------
    eigenvalue : Eigenvalue
    beams : dict
        Beam name -> :class:`BeamShape`, in the model's beam order.
    left_state : tuple
        The normalised extended state (mpmath numbers) at the left, before
        any jump: the beams' ``4 n`` variables at their left ends, then the
        bodies' virtual variables (:class:`~symtmm.assembly.Layout`). With the
        model it determines the shape everywhere (:func:`evaluate_mode`).
    dps : int
        Decimal digits of the arithmetic the shape was computed in.
    number : int
        Position of the mode in its set (1-based, ascending by ``Im lam``).
    bodies : dict
        Rigid body (joint) name -> ``{"Y": Y_c, "Theta": Theta_c}``: the
        deflection of its centre of mass and its rotation (``Theta`` only when
        the body rotates, :attr:`~symtmm.model.RigidBody.rotates`); float
        for undamped shapes, complex for damped ones.
    """

    eigenvalue: Eigenvalue
    beams: dict
    left_state: tuple
    dps: int
    number: int = 1
    bodies: dict = field(default_factory=dict)

    @property
    def lam(self):
        """The eigenvalue ``lam`` (mpmath)."""
        return self.eigenvalue.lam

    @property
    def omega(self) -> float:
        """``Im lam`` in rad/s, as a float."""
        return float(self.eigenvalue.lam.imag)

    @property
    def damped(self) -> bool:
        """True for a complex (damped) shape."""
        return any(np.iscomplexobj(b.Y) for b in self.beams.values())

    def to_dict(self) -> dict:
        """The JSON object of one mode in ``symtmm modes --json``."""
        ev = self.eigenvalue.to_dict()
        out = {"eigenvalue": {"real": ev["real"], "imag": ev["imag"]},
               "beams": {name: b.to_dict() for name, b in self.beams.items()}}
        if self.bodies:
            out["bodies"] = {name: {var: _json_number(v) for var, v in motion.items()}
                             for name, motion in self.bodies.items()}
        return out


def _json_number(value):
    """A float, or ``{"real", "imag"}`` for a complex number (as the arrays are written)."""
    if isinstance(value, complex):
        return {"real": value.real, "imag": value.imag}
    return float(value)


@dataclass(frozen=True)
class ModeSet:
    """Mode shapes of a model, ascending by ``Im lam``; iterating gives :class:`ModeShape`.

    Attributes
    ----------
    modes : tuple of ModeShape
    model : Model
        The (resolved) model the shapes belong to.
    spectrum : Spectrum
        The eigenvalues the shapes were computed at.
    seconds : float
        Time spent on the shapes (the eigenvalue search not included).
    """

    modes: tuple
    model: Model
    spectrum: Spectrum
    seconds: float = 0.0
    notes: tuple = field(default_factory=tuple)

    def __iter__(self):
        return iter(self.modes)

    def __len__(self):
        return len(self.modes)

    def __getitem__(self, i):
        return self.modes[i]

    @property
    def beam_names(self) -> list:
        return [b.name for b in self.model.beams]

    def to_dict(self) -> dict:
        """The JSON object of ``symtmm modes --json``: ``{"modes": [...]}``."""
        return {"modes": [m.to_dict() for m in self.modes]}

    def to_json(self) -> str:
        """:meth:`to_dict` as a JSON string."""
        # compact: a shape has thousands of numbers
        return json.dumps(self.to_dict(), separators=(",", ":"))

    def _rows(self):
        """Number, eigenvalue text, Omega text, and per beam the largest |Y|."""
        scale = self.spectrum.omega_scale
        rows = []
        for mode in self.modes:
            e = mode.eigenvalue
            if scale and not mode.damped:
                with mpmath.workdps(e.digits + 10):
                    Om = decimal_string(mpmath.sqrt(e.omega / scale[1]), e.digits)
            else:
                Om = ""
            amps = [f"{float(np.max(np.abs(b.Y))):.4g}" for b in mode.beams.values()]
            rows.append([str(mode.number), str(e), Om] + amps)
        return rows

    def _head(self):
        ref = self.spectrum.omega_scale[0] if self.spectrum.omega_scale else ""
        return (["#", "lam [1/s]", f"Omega (beam {ref})" if ref else "Omega"]
                + [f"max|Y| {n}" for n in self.beam_names])

    def table(self) -> str:
        """A readable summary: eigenvalue and the largest displacement on each beam."""
        head, rows = self._head(), self._rows()
        widths = [max(len(h), *(len(r[k]) for r in rows)) if rows else len(h)
                  for k, h in enumerate(head)]
        lines = ["  ".join(h.rjust(w) for h, w in zip(head, widths)),
                 "  ".join("-" * w for w in widths)]
        lines += ["  ".join(c.rjust(w) for c, w in zip(r, widths)) for r in rows]
        damped = any(m.damped for m in self.modes)
        points = len(next(iter(self.modes[0].beams.values())).x) if self.modes else 0
        lines.append(f"{len(self.modes)} mode shape(s), {points} points per beam (max|Y| over "
                     "those points); "
                     + ("complex, largest |Y| = 1" if damped else
                        "mass-normalised: kinetic energy sum of integral (m Y^2 + rhoI "
                        "Theta^2) dx + masses + bodies = 1"))
        lines += list(self.notes)
        return "\n".join(lines)

    def __str__(self) -> str:
        return self.table()

    def _repr_html_(self) -> str:
        from html import escape
        head, rows = self._head(), self._rows()
        out = ["<table>", "<tr>" + "".join(f"<th>{escape(h)}</th>" for h in head) + "</tr>"]
        out += ["<tr>" + "".join(f"<td>{escape(c)}</td>" for c in r) + "</tr>" for r in rows]
        out.append("</table>")
        return "".join(out)

    def _repr_latex_(self) -> str:
        head, rows = self._head(), self._rows()
        cols = [r"\#", r"\lambda\ [1/\mathrm{s}]", r"\Omega"] + [
            r"\max|Y|\ \mathrm{" + n.replace("_", r"\_") + "}" for n in self.beam_names]
        lines = [r"\begin{array}{" + "r" * len(head) + "}", " & ".join(cols) + r" \\ \hline"]
        lines += [" & ".join(r) + r" \\" for r in rows]
        lines.append(r"\end{array}")
        return "$" + "\n".join(lines) + "$"

    def plot(self, **kwargs):
        """The shapes as a matplotlib figure (see :func:`symtmm.plot.plot_modes`)."""
        from .plot import plot_modes
        return plot_modes(self, **kwargs)


# -----------------------------------------------------------------------------------
# Propagation of states along the beams
# -----------------------------------------------------------------------------------

class _Jumps:
    """The entries ``(row, col, value)`` of a station's ``G``, values as polynomials in lam."""

    def __init__(self, terms):
        self.rows = [r for r, _, _ in terms]
        self.cols = [c for _, c, _ in terms]
        self.coeffs = []        # per term: exact coefficients of lam**0, lam**1, ...
        for _, _, value in terms:
            poly = sp.Poly(sp.expand(value), LAM)
            self.coeffs.append([sp.sympify(c) for c in reversed(poly.all_coeffs())])
        self._float = [[complex(sp.N(c, 20)) for c in cs] for cs in self.coeffs]
        self._mp: dict = {}

    def values_numpy(self, lam) -> list:
        out = []
        for cs in self._float:
            v = np.zeros_like(lam)
            for c in reversed(cs):
                v = v * lam + c
            out.append(v)
        return out

    def values_mp(self, lam, real: bool) -> list:
        key = (mpmath.mp.prec, real)
        coeffs = self._mp.get(key)
        if coeffs is None:
            dps = mpmath.mp.dps
            coeffs = [[to_mp(c, dps) if c.is_real else mpmath.mpmathify(complex(sp.N(c, dps)))
                       for c in cs] for cs in self.coeffs]
            self._mp[key] = coeffs
        out = []
        for cs in coeffs:
            v = mpmath.mpf(0)
            for c in reversed(cs):
                v = v * lam + c
            out.append(mpmath.re(v) if real else v)
        return out



def working_digits(evaluator: Evaluator, lam, digits: int) -> int:
    """Decimal digits to compute a shape in: ``digits`` plus the cancellation, plus guard.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> ev = Evaluator(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)))
    >>> working_digits(ev, 1j * 10 * math.pi**2, 15)       # beta L = sqrt(10) pi: 4.3 digits
    35
    """
    return max(int(digits), 15) + math.ceil(evaluator.digits_lost(complex(lam))) + 15


class _Walker:
    """Carries an extended state (``size x k``, mpmath) through the layout of a resolved model.

    The extended state stacks the beams' ``4 n`` variables and the bodies'
    virtual ones (:class:`~symtmm.assembly.Layout`). Sample requests: per beam
    level a list of ``(x, side)`` with ``x`` an mpmath number (global
    coordinate) and ``side`` ``"-"`` (before the jumps at ``x``) or ``"+"``
    (after them). Work at the current mpmath precision.
    """

    def __init__(self, model: Model):
        self.model = model
        self.layout = Layout(model)
        self.n = self.layout.levels
        self.size = self.layout.size
        self._jumps = {}
        self._inertia = {}
        for step in self.layout.steps:
            if isinstance(step, Interval):
                continue
            self._jumps[id(step)] = _Jumps(step.terms)
            for element, levels in step.elements:
                inertia = element.inertia()
                if not inertia.is_zero_matrix:
                    disp = [4 * levels[lvl] + STATE.index(var) for lvl, var in element.dofs]
                    self._inertia.setdefault(id(step), []).append((disp, inertia))
        # the bodies' kinetic energy M Y_c**2 + J Theta_c**2, on their virtual unknowns
        self._body_inertia = []
        for bl in self.layout.bodies:
            if bl.body.M != 0:
                self._body_inertia.append((bl.unknowns["Y"], bl.body.M))
            if "Theta" in bl.unknowns and bl.body.J != 0:
                self._body_inertia.append((bl.unknowns["Theta"], bl.body.J))
        self._cache: dict = {}

    def _exact(self, value):
        key = ("x", value, mpmath.mp.prec)
        out = self._cache.get(key)
        if out is None:
            out = self._cache[key] = to_mp(value, mpmath.mp.dps)
        return out

    def run(self, lam, E0, samples, real: bool, gram: bool, digits: int | None = None):
        """Propagate; return (recorded states, kinetic-energy Gram matrix or None).

        ``E0``: numpy object array ``(size, k)`` (the extended state at the left);
        ``samples``: list per level. Recorded states: dict ``(level, i) -> (4, k)``
        complex array. ``digits``: correct digits the Gram matrix must carry
        (default: the working precision less 15).

        The state is carried in mpmath from cut to cut and, inside a segment,
        to anchors ``h`` apart with ``|s| h <= 1`` (``s`` the largest wave
        number); from an anchor to the sample points the double-precision
        transfer matrix suffices (it loses at most ``e**1`` in relative
        accuracy), which makes dense sampling cheap.
        """
        lam = mpmath.mpmathify(lam)
        lam2 = mpmath.mpf(-(lam.imag ** 2)) if real else lam * lam
        digits = mpmath.mp.dps - 15 if digits is None else digits
        E = E0.copy()
        k = E.shape[1]
        tol = mpmath.mpf(10) ** (-(mpmath.mp.dps - 10))
        recorded: dict = {}
        G = np.full((k, k), mpmath.mpf(0) if real else mpmath.mpc(0), dtype=object) \
            if gram else None
        approx = [[float(x) for x, _ in level] for level in samples]

        def at(lvl, i, where, wf):
            if abs(approx[lvl][i] - wf) > 1e-9 * max(1.0, abs(wf)):
                return False
            return abs(samples[lvl][i][0] - where) <= tol * max(1, abs(where))

        def record(lvl, where, sides, only_new=True):
            wf = float(where)
            for i, (_x, side) in enumerate(samples[lvl]):
                if side in sides and at(lvl, i, where, wf) and \
                        not (only_new and (lvl, i) in recorded):
                    recorded[(lvl, i)] = _to_complex(E[4 * lvl:4 * lvl + 4, :])

        for step in self.layout.steps:
            if isinstance(step, Interval):
                xs, xe = self._exact(step.x_start), self._exact(step.x_end)
                xsf, xef = float(xs), float(xe)
                for lvl, seg in step.segments:
                    consts = seg.mp_constants()
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    record(lvl, xs, "-+")          # a beam's left end without a station
                    inside = [(i, x) for i, (x, _s) in enumerate(samples[lvl])
                              if xsf - 1e-9 <= approx[lvl][i] <= xef + 1e-9
                              and x > xs + tol * max(1, abs(xs)) and not at(lvl, i, xe, xef)
                              and x < xe]
                    if inside:
                        _inside(lam2, seg, consts, E[blk, :], xs, inside, lvl, recorded)
                    U = seg.evaluate_mp(lam2, consts)
                    E1 = U.dot(E[blk, :])
                    if gram:
                        G += _segment_gram(seg, lam2, consts, E[blk, :], E1, digits)
                    E[blk, :] = E1
                    record(lvl, xe, "-+", only_new=False)
            else:
                x = self._exact(step.x)
                jumps = self._jumps[id(step)]
                levels = sorted({row // 4 for row in jumps.rows if row < 4 * self.n})
                for lvl in levels:
                    record(lvl, x, "-+")
                if gram:
                    # kinetic energy of lumped masses: d^T M d (displacements do not jump)
                    for disp, inertia in self._inertia.get(id(step), ()):
                        Mi = np.array([[self._exact(v) for v in row] for row in inertia.tolist()],
                                      dtype=object)
                        D = E[disp, :]
                        G += D.T.dot(Mi).dot(D)
                # rows written are never columns read at the same station: in place is exact
                for row, col, v in zip(jumps.rows, jumps.cols, jumps.values_mp(lam, real)):
                    E[row, :] = E[row, :] + v * E[col, :]
                for lvl in levels:
                    record(lvl, x, "+", only_new=False)
        if gram:
            # rigid bodies: their deflection and rotation are unknowns, constant along x
            for index, value in self._body_inertia:
                G += self._exact(value) * np.outer(E[index, :], E[index, :])
        missing = [(lvl, samples[lvl][i][0]) for lvl in range(self.n)
                   for i in range(len(samples[lvl])) if (lvl, i) not in recorded]
        if missing:
            lvl, x = missing[0]
            raise ValueError(f"x = {mpmath.nstr(x, 8)} is not on beam "
                             f"'{self.model.beams[lvl].name}'")
        return recorded, G


def _reach(seg, lam2, length) -> float:
    """``|s| l``: the largest wave number of ``seg`` at ``lam2`` times ``length``."""
    return float(np.max(seg.wave_number(complex(lam2)))) * float(length)


def _inside(lam2, seg, consts, Z0, xs, inside, lvl, recorded):
    """States at sample points strictly inside a segment, from nearby mpmath anchors."""
    length = consts[2]
    n_anchor = max(1, math.ceil(_reach(seg, lam2, length)))
    h = length / n_anchor
    Uh = seg.evaluate_mp(lam2, consts, l=h) if n_anchor > 1 else None
    anchors = [Z0]
    groups: dict = {}
    for i, x in inside:
        j = min(int(mpmath.floor((x - xs) / h)), n_anchor - 1)
        groups.setdefault(j, []).append((i, float(x - xs - j * h)))
    while len(anchors) < max(groups) + 1:
        anchors.append(Uh.dot(anchors[-1]))
    consts_f = seg.constants()
    lam2_c = complex(lam2)
    for j, items in groups.items():
        Zc = _to_complex(anchors[j])
        ts = np.array([t for _i, t in items])
        U = np.empty((len(ts), 4, 4), dtype=complex)
        U[:] = np.eye(4)
        nonzero = ts > 0
        if isinstance(seg, EulerBernoulliSegment) and nonzero.any():
            # the c_j take an array of lengths at once
            U[nonzero] = seg.evaluate_numpy(lam2_c, consts_f, l=ts[nonzero])
        else:
            for q in np.flatnonzero(nonzero):
                U[q] = seg.evaluate_numpy(lam2_c, consts_f, l=float(ts[q]))
        states = U @ Zc
        for (i, _t), z in zip(items, states):
            recorded[(lvl, i)] = z


def _to_complex(block):
    """An object array of mpmath numbers as a complex numpy array."""
    return np.array([[complex(v) for v in row] for row in block], dtype=complex)


@functools.lru_cache(maxsize=16)
def _walker(model: Model) -> _Walker:
    """A walker per model, kept for repeated :func:`evaluate_mode` calls."""
    return _Walker(model)


def _bilinear_F(x, kappa, EI, a, b):
    """The boundary form whose difference is ``4 kappa`` times the integral of ``Y_a Y_b``."""
    Ya, Ta, Ma, Qa = a
    Yb, Tb, Mb, Qb = b
    d2a, d3a, d2b, d3b = Ma / EI, Qa / EI, Mb / EI, Qb / EI
    return (x * (kappa * Ya * Yb - (Ta * d3b + Tb * d3a) + d2a * d2b)
            + (Ya * d3b + Yb * d3a) * mpmath.mpf(3) / 2 - (Ta * d2b + Tb * d2a) / 2)


def gauss_legendre_nodes(digits: int) -> int:
    """Nodes of a Gauss–Legendre rule exact to ``10**-digits`` on a piece with ``|s| h <= 1``.

    On such a piece the integrand (a product of two states) is a combination
    of ``exp(c t)``, ``t`` in ``[-1, 1]``, ``|c| <= 1``; the ``n``-point rule's
    error is at most ``2**(2n+1) (n!)**4 / ((2n+1) ((2n)!)**3)`` times
    ``max |f^(2n)| <= e``. A further 5 digits cover the combination's
    coefficients exceeding its values.

    Examples
    --------
    >>> gauss_legendre_nodes(15), gauss_legendre_nodes(50)
    (9, 19)
    """
    target = -(digits + 5) * math.log(10)
    n = 2
    while ((2 * n + 1) * math.log(2) + 4 * math.lgamma(n + 1) - math.log(2 * n + 1)
           - 3 * math.lgamma(2 * n + 1) + 1) > target:
        n += 1
    return n


@functools.lru_cache(maxsize=32)
def _gl_rule(n: int, prec: int):
    """Gauss–Legendre nodes and weights on [0, 1] at ``prec`` bits."""
    with mpmath.workprec(prec):
        xs, _ = np.polynomial.legendre.leggauss(n)
        # refine the double-precision nodes by Newton steps on P_n at the working precision
        nodes, weights = [], []
        for x0 in xs:
            x = mpmath.mpf(float(x0))
            for _ in range(12):
                p, dp = _legendre(n, x)
                dx = p / dp
                x -= dx
                if abs(dx) < mpmath.eps * 4:
                    break
            p, dp = _legendre(n, x)
            nodes.append((x + 1) / 2)
            weights.append(1 / ((1 - x * x) * dp * dp))   # 2/((1-x^2)P'^2), halved for [0, 1]
    return tuple(nodes), tuple(weights)


def _legendre(n, x):
    p0, p1 = mpmath.mpf(1), x
    for k in range(2, n + 1):
        p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
    dp = n * (x * p1 - p0) / (x * x - 1)
    return p1, dp


def _segment_gram(seg, lam2, consts, Z0, Z1, digits):
    """``integral over the segment of m Y_i Y_j + rhoI Theta_i Theta_j`` for the columns of
    ``Z0`` (states at the start; ``Z1`` at the end).

    Euler–Bernoulli segments (on a foundation too) use the closed form
    ``[F]/(4 kappa)``, ``Y'''' = kappa Y``, unless ``|kappa| l**4`` is so small
    that it would cancel; every other segment Gauss–Legendre quadrature of
    the propagated states (:func:`_quadrature_gram`).
    """
    if isinstance(seg, EulerBernoulliSegment):
        EI, m, length = consts[:3]
        kw = consts[3] if len(consts) > 3 else 0
        kappa = -(lam2 * m + kw) / EI
        if abs(kappa) * length**4 >= _CLOSED_FORM_MIN:
            k = Z0.shape[1]
            out = np.empty((k, k), dtype=object)
            zero = mpmath.mpf(0)
            for i in range(k):
                for j in range(i, k):
                    F1 = _bilinear_F(length, kappa, EI, Z1[:, i], Z1[:, j])
                    F0 = _bilinear_F(zero, kappa, EI, Z0[:, i], Z0[:, j])
                    out[i, j] = out[j, i] = m * (F1 - F0) / (4 * kappa)
            return out
        return _quadrature_gram(seg, lam2, consts, Z0, m, 0, digits)
    return _quadrature_gram(seg, lam2, consts, Z0, consts[1], consts[5], digits)


def _quadrature_gram(seg, lam2, consts, Z0, m, rhoI, digits):
    """The kinetic-energy Gram matrix of a segment by Gauss–Legendre quadrature.

    The segment is cut into pieces with ``|s| h <= 1``, each integrated by the
    rule of :func:`gauss_legendre_nodes`; the transfer matrices to the nodes
    are the same on every piece and are computed once.
    """
    length = consts[2]
    pieces = max(1, math.ceil(_reach(seg, lam2, length)))
    h = length / pieces
    nodes, weights = _gl_rule(gauss_legendre_nodes(digits), mpmath.mp.prec)
    to_nodes = [seg.evaluate_mp(lam2, consts, l=t * h) for t in nodes]
    step = seg.evaluate_mp(lam2, consts, l=h) if pieces > 1 else None
    k = Z0.shape[1]
    out = np.full((k, k), mpmath.mpf(0) * lam2, dtype=object)
    Z = Z0
    for p in range(pieces):
        for U, w in zip(to_nodes, weights):
            z = U[:2, :].dot(Z)                 # Y and Theta at the node
            out += (w * h) * (m * np.outer(z[0], z[0])
                              + (rhoI * np.outer(z[1], z[1]) if rhoI else 0))
        if p + 1 < pieces:
            Z = step.dot(Z)
    return out


def _null_space(R, mult: int, real: bool):
    """A basis (columns, orthonormal) of the near-null space of ``R``: ``mult`` vectors.

    Block inverse iteration: ``X <- orth(R^-1 X)`` twice from fixed pseudo-random
    columns, with ``R^-1`` applied through an LU factorisation with partial
    pivoting (a zero pivot replaced by ``eps |R|``, the classical guard of inverse
    iteration). Near an eigenvalue the ``mult`` smallest singular values of ``R``
    dominate ``R^-1``, so this spans the space of their right singular vectors, as
    the singular value decomposition would, at the cost of one LU factorisation
    (the SVD in mpmath takes seconds once rigid bodies bring their unknowns).
    Backward stable like the SVD: the vectors are as accurate as the eigenvalue.
    Falls back to the SVD if the iteration collapses.
    """
    n = R.cols
    if R.rows == 0:
        return np.empty((0, mult), dtype=object)
    if mult > n:
        raise ComputationError(f"multiplicity {mult} exceeds the size {n} of R")
    rows = [[R[i, j] for j in range(n)] for i in range(n)]
    LU, perm = _lu(rows)
    rng = random.Random(20240607)          # fixed: the shapes are reproducible
    X = [[mpmath.mpf(rng.uniform(-1, 1)) for _ in range(mult)] for _ in range(n)]
    for _ in range(2):
        X = _orthonormal([_lu_solve(LU, perm, [X[i][c] for i in range(n)]) for c in range(mult)],
                         real)
        if X is None:
            return _svd_null_space(R, mult, real)
        X = [[X[c][i] for c in range(mult)] for i in range(n)]
    return np.array(X, dtype=object).reshape(n, mult)


def _lu(A):
    """``P A = L U`` with partial pivoting, in place on a copy (rows as lists)."""
    n = len(A)
    A = [row[:] for row in A]
    perm = list(range(n))
    guard = max((abs(v) for row in A for v in row), default=mpmath.mpf(1)) * mpmath.eps
    if guard == 0:
        guard = mpmath.eps
    for k in range(n):
        p = max(range(k, n), key=lambda i: abs(A[i][k]))
        A[k], A[p] = A[p], A[k]
        perm[k], perm[p] = perm[p], perm[k]
        if abs(A[k][k]) < guard:
            # singular to working precision (an exact eigenvalue): perturb the pivot
            A[k][k] = guard if A[k][k] == 0 else guard * A[k][k] / abs(A[k][k])
        pivot = A[k][k]
        for i in range(k + 1, n):
            f = A[i][k] / pivot
            if f == 0:
                continue
            A[i][k] = f
            row_i, row_k = A[i], A[k]
            for j in range(k + 1, n):
                row_i[j] -= f * row_k[j]
    return A, perm


def _lu_solve(LU, perm, b):
    n = len(LU)
    y = [b[perm[i]] for i in range(n)]
    for i in range(n):
        row = LU[i]
        y[i] -= sum((row[j] * y[j] for j in range(i)), mpmath.mpf(0))
    for i in range(n - 1, -1, -1):
        row = LU[i]
        y[i] = (y[i] - sum((row[j] * y[j] for j in range(i + 1, n)), mpmath.mpf(0))) / row[i]
    return y


def _orthonormal(columns, real: bool):
    """Modified Gram–Schmidt, twice; None if a column depends on the others."""
    out = []
    for v in columns:
        scale = max(abs(x) for x in v)
        if scale == 0:
            return None
        v = [x / scale for x in v]
        size = mpmath.sqrt(sum(abs(x) ** 2 for x in v))
        for _ in range(2):
            for q in out:
                dot = sum((qi if real else mpmath.conj(qi)) * x for qi, x in zip(q, v))
                v = [x - dot * qi for x, qi in zip(v, q)]
        norm = mpmath.sqrt(sum(abs(x) ** 2 for x in v))
        if norm <= size * mpmath.mpf(10) ** (-(mpmath.mp.dps // 2)):
            return None
        out.append([x / norm for x in v])
    return out


def _svd_null_space(R, mult: int, real: bool):
    """The right singular vectors of the ``mult`` smallest singular values (columns)."""
    _, _, V = (mpmath.svd_r if real else mpmath.svd_c)(R)
    n = R.cols
    # singular values come sorted by decreasing size; R = U S V, so R V^H = U S
    out = np.empty((n, mult), dtype=object)
    for c, row in enumerate(range(n - mult, n)):
        for j in range(n):
            out[j, c] = V[row, j] if real else mpmath.conj(V[row, j])
    return out


def _grid(beam, points: int):
    """``points`` equally spaced exact coordinates along ``beam``, both ends included."""
    return [beam.x0 + beam.L * sp.Rational(i, points - 1) for i in range(points)]


def _default_samples(model: Model, points: int, dps: int):
    out = []
    for beam in model.beams:
        grid = _grid(beam, points)
        sides = ["-"] + ["+"] * (points - 1)
        out.append([(to_mp(x, dps), s) for x, s in zip(grid, sides)])
    return out


def shapes_at(model: Model, eigenvalue: Eigenvalue, points: int = 101, digits: int | None = None,
              number: int = 1, walker=None, evaluator=None) -> list:
    """The mode shape(s) belonging to one eigenvalue: ``multiplicity`` of them.

    Parameters
    ----------
    model : Model
        Numeric (every parameter has a value).
    eigenvalue : Eigenvalue
        From :func:`symtmm.solve.solve`; its multiplicity sets the number of shapes.
    points : int
        Sample points per beam, both ends included (at least 2).
    digits : int, optional
        Digits the shape should carry; default the eigenvalue's.
    number : int
        Number of the first shape in its set.

    Returns
    -------
    list of ModeShape

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> ev = solve(pp, count=1)[0]
    >>> (shape,) = shapes_at(pp, ev, points=5)
    >>> np.round(shape.beams["b"].Y, 6) + 0.0         # sqrt(2) sin(pi x)
    array([0.      , 1.      , 1.414214, 1.      , 0.      ])
    """
    model = model.require_numeric()
    if points < 2:
        raise ValueError("points must be at least 2")
    ev = evaluator or Evaluator(model)
    walker = walker or _Walker(model)
    real = not model.damped and eigenvalue.lam.real == 0
    digits = eigenvalue.digits if digits is None else digits
    dps = working_digits(ev, eigenvalue.lam, digits)
    mult = eigenvalue.multiplicity
    with mpmath.workdps(dps):
        lam = mpmath.mpc(eigenvalue.lam) if not real else mpmath.mpc(0, eigenvalue.lam.imag)
        R = ev.R_mp(lam, real=real)
        V = _null_space(R, mult, real)
        E0 = np.full((walker.size, mult), mpmath.mpf(0), dtype=object)
        for r, c in enumerate(ev.columns):
            E0[c, :] = V[r, :]
        samples = _default_samples(model, points, dps)
        rec, G = walker.run(lam, E0, samples, real, gram=real, digits=digits + 3)
        if real:
            T = _mass_orthonormaliser(G)
        else:
            T = _complex_scaler(rec, mult)
        E0 = E0.dot(T)
        Tc = _to_complex(T)
        xs = [np.array([float(x) for x, _ in samples[lvl]]) for lvl in range(walker.n)]
        # states per level: (points, 4, mult)
        states = [np.array([rec[(lvl, i)] @ Tc for i in range(points)])
                  for lvl in range(walker.n)]
        if real:
            states = [z.real for z in states]
        shapes = []
        for c in range(mult):
            sign = 1
            if real:
                # make the largest displacement positive
                Ys = np.concatenate([z[:, 0, c] for z in states])
                sign = -1 if Ys[np.argmax(np.abs(Ys))] < 0 else 1
            beams = {}
            for lvl, beam in enumerate(model.beams):
                z = states[lvl][:, :, c] * sign
                beams[beam.name] = BeamShape(beam.name, xs[lvl], z[:, 0], z[:, 1], z[:, 2],
                                             z[:, 3])
            left = tuple(E0[r, c] * sign for r in range(E0.shape[0]))
            shapes.append(ModeShape(eigenvalue, beams, left, dps, number + c,
                                    _body_motion(walker.layout, left, real)))
    return shapes


def _body_motion(layout, state, real: bool) -> dict:
    """Per rigid body, its ``Y`` and ``Theta`` (if it rotates) from the extended state."""
    out = {}
    for bl in layout.bodies:
        motion = {}
        for var in ("Y", "Theta"):
            if var in bl.unknowns:
                value = complex(state[bl.unknowns[var]])
                motion[var] = value.real if real else value
        out[bl.body.name] = motion
    return out


def _mass_orthonormaliser(G):
    """``T`` with ``T^T G T = I`` (``G`` symmetric positive definite, mpmath)."""
    k = G.shape[0]
    Gm = mpmath.matrix(G.tolist())
    try:
        L = mpmath.cholesky(Gm)
    except ZeroDivisionError:
        raise ComputationError("mode shape with zero mass (null vector lost)") from None
    Linv = mpmath.inverse(L)
    # G = L L^T  =>  T = L^-T
    return np.array([[Linv[j, i] for j in range(k)] for i in range(k)], dtype=object)


def _complex_scaler(rec, mult):
    """Diagonal scaling making each damped shape's largest ``|Y|`` equal to 1 (real)."""
    T = np.full((mult, mult), mpmath.mpc(0), dtype=object)
    for c in range(mult):
        best = max((rec[key][0, c] for key in rec), key=abs)
        if best == 0:
            raise ComputationError("mode shape vanishes (null vector lost)")
        T[c, c] = 1 / mpmath.mpc(best)
    return T


def evaluate_mode(model: Model, mode: ModeShape, beam: str, x, side: str = "+") -> np.ndarray:
    """The state ``[Y, Theta, M, Q]`` of ``mode`` at global coordinates ``x`` on ``beam``.

    Parameters
    ----------
    model : Model
        The model the mode belongs to.
    mode : ModeShape
    beam : str
        Beam name.
    x : array_like
        Global coordinates on the beam (floats or exact values).
    side : {"+", "-"}
        At a station: the state after (``"+"``) or before (``"-"``) the jumps of
        the point elements there, in the direction of increasing x.

    Returns
    -------
    numpy.ndarray
        Shape ``(4, len(x))``, float for undamped modes, complex for damped.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.solve import solve
    >>> pp = Model((Beam("b", EI=1, m=1, L=1, left="pinned", right="pinned"),))
    >>> (shape,) = shapes_at(pp, solve(pp, count=1)[0], points=3)
    >>> z = evaluate_mode(pp, shape, "b", [0.25])
    >>> round(float(z[0, 0]), 12) == round(math.sqrt(2) * math.sin(math.pi / 4), 12)
    True
    """
    model = model.require_numeric()
    if side not in ("+", "-"):
        raise ValueError("side must be '+' or '-'")
    lvl = model.beam_index(beam)
    walker = _walker(model)
    xs = [x] if np.ndim(x) == 0 else list(x)
    real = not any(isinstance(v, mpmath.mpc) for v in mode.left_state)
    with mpmath.workdps(mode.dps):
        samples = [[] for _ in model.beams]
        samples[lvl] = [(_coordinate(v, mode.dps), side) for v in xs]
        E0 = np.array([[v] for v in mode.left_state], dtype=object)
        lam = mode.lam if not real else mpmath.mpc(0, mode.lam.imag)
        rec, _ = walker.run(lam, E0, samples, real, gram=False)
        out = np.array([rec[(lvl, i)][:, 0] for i in range(len(xs))]).T
        return out.real if real else out


def _coordinate(value, dps):
    """A coordinate as an mpmath number; a float is read as the decimal it prints as.

    A string is read by the restricted parser of model files, never by ``sympify``.
    """
    if isinstance(value, mpmath.mpf):
        return value
    if isinstance(value, (float, np.floating)):
        value = sp.Rational(repr(float(value)))
    if isinstance(value, str):
        try:
            value = parse_expression(value)
        except ExpressionError as exc:
            raise ModelError(f"cannot read {value!r}: {exc}", field="x") from None
        if not value.is_number:
            raise ModelError(f"{value} is not a number", field="x")
    return to_mp(sp.sympify(value), dps)


def mode_shapes(model: Model, count: int | None = None, omega_max=None, sigma_max=None,
                points: int = 101, digits: int = 15, method: str = "default",
                spectrum: Spectrum | None = None) -> ModeSet:
    """Mode shapes of the first ``count`` modes (with multiplicity) of ``model``.

    Parameters
    ----------
    model : Model
        Every parameter must have a value.
    count, omega_max, sigma_max, digits, method
        Passed to :func:`symtmm.solve.solve` to find the eigenvalues.
    points : int
        Sample points per beam, both ends included.
    spectrum : Spectrum, optional
        Eigenvalues already found; then no search is made.

    Returns
    -------
    ModeSet
        One :class:`ModeShape` per eigenvalue and multiplicity.

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> cf = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="free"),))
    >>> modes = mode_shapes(cf, count=2, points=11)
    >>> print(modes.table())                                      # doctest: +ELLIPSIS
    #          lam [1/s]    Omega (beam b)  max|Y| b
    -  -----------------  ----------------  --------
    1  3.51601526850015i  1.87510406871196         2
    2  22.0344915646668i  4.69409113297417         2
    2 mode shape(s), 11 points per beam (max|Y| over those points); mass-normalised: ...
    """
    from .solve import solve

    model = model.require_numeric()
    if spectrum is None:
        spectrum = solve(model, count=count, omega_max=omega_max, sigma_max=sigma_max,
                         digits=digits, method=method)
    start = time.perf_counter()
    ev = Evaluator(model)
    walker = _Walker(model)
    modes, number = [], 1
    for e in spectrum:
        shapes = shapes_at(model, e, points=points, number=number, walker=walker, evaluator=ev)
        modes += shapes
        number += len(shapes)
    notes = []
    if count is not None and len(modes) > count:
        multiple = [e for e in spectrum if e.multiplicity > 1]
        notes.append(f"{len(modes)} shapes for {count} requested: a multiple eigenvalue "
                     f"(here {', '.join(str(e) for e in multiple)}) "
                     "is given a basis of its whole eigenspace, mass-orthonormal")
    return ModeSet(tuple(modes), model, spectrum, time.perf_counter() - start, tuple(notes))
