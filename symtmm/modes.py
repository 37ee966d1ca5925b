"""Mode shapes: the state ``[Y, Theta, M, Q]`` along every beam at an eigenvalue.

At an eigenvalue ``lam`` the boundary matrix ``R(lam)`` is singular; a null
vector gives the unknown left-end state variables of every beam, and the
transfer matrices carry that state along the beams (paper eq. 3). The steps:

1. **Precision.** The entries of ``R`` grow like ``exp(|beta| L)``, so the
   work is done in mpmath at ``digits + loss + 15`` decimal digits, ``loss``
   being :meth:`~symtmm.compile.Evaluator.digits_lost` at the eigenvalue.
2. **Null space.** The singular value decomposition of ``R(lam)`` at that
   precision; an eigenvalue of multiplicity ``m`` contributes the right
   singular vectors of its ``m`` smallest singular values. The least-squares
   character of the SVD keeps the growing exponential out of the vector, so
   the shape is as accurate as the eigenvalue, even near the far end.
3. **Propagation.** Segment transfer matrices
   (:meth:`~symtmm.elements.EulerBernoulliSegment.evaluate_mp` with the
   segment length replaced by the distance to each sample point) and the
   jumps of the point elements at every station, in the order of
   :class:`~symtmm.assembly.Layout`.
4. **Normalisation.** Undamped shapes are real and mass-normalised,
   ``sum over beams of the integral of m Y**2 dx = 1``; the integral over a
   segment has the closed form ``[F]/(4 kappa)`` with ``kappa = beta**4`` and
   ``F = x (kappa Y**2 - 2 Y' Y''' + Y''**2) + 3 Y Y''' - Y' Y''`` (which
   follows from ``Y'''' = kappa Y``), and Gauss--Legendre quadrature where
   ``kappa l**4`` is small. Lumped masses add their kinetic energy
   ``M Y**2 + J Theta**2`` (the element's mass matrix), which keeps the shapes
   of distinct frequencies orthogonal. The ``m`` shapes of a multiple eigenvalue are
   made mass-orthonormal (Cholesky factor of their mass Gram matrix). Each
   shape's largest displacement is made positive. Damped shapes are complex
   and scaled so that the largest ``|Y|`` over all beams is ``1`` (real).

Sample points and the two sides of a station: at a spring the shear force
jumps. The state reported at a beam's left end is the one before the jumps
there and at its right end the one after them (the states the boundary
conditions constrain); at interior points sitting on a station the state just
right of it (after the jumps). :func:`evaluate_mode` gives either side.
"""

from __future__ import annotations

import functools
import json
import math
import time
from dataclasses import dataclass, field

import mpmath
import numpy as np
import sympy as sp

from .assembly import Interval, Layout
from .compile import Evaluator
from .elements import STATE, EulerBernoulliSegment
from .elements.base import CONJUGATE, LAM
from .errors import ComputationError
from .model import Model
from .numeric import to_mp
from .results import Eigenvalue, Spectrum, decimal_string

__all__ = ["BeamShape", "ModeSet", "ModeShape", "evaluate_mode", "mode_shapes", "shapes_at",
           "working_digits"]

#: Gauss–Legendre nodes used where ``|kappa| l**4`` is too small for the closed form.
_GL_NODES = 10
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
        The normalised stacked state (``4 n`` mpmath numbers) at the beams'
        left ends, before any jump there: with the model it determines the
        shape everywhere (:func:`evaluate_mode`).
    dps : int
        Decimal digits of the arithmetic the shape was computed in.
    number : int
        Position of the mode in its set (1-based, ascending by ``Im lam``).
    """

    eigenvalue: Eigenvalue
    beams: dict
    left_state: tuple
    dps: int
    number: int = 1

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
        return {"eigenvalue": {"real": ev["real"], "imag": ev["imag"]},
                "beams": {name: b.to_dict() for name, b in self.beams.items()}}


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
                        "mass-normalised: sum of integral m Y^2 dx = 1"))
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
    """Carries a stacked state (4n x k, mpmath) through the layout of a resolved model.

    Sample requests: per beam level a list of ``(x, side)`` with ``x`` an
    mpmath number (global coordinate) and ``side`` ``"-"`` (before the jumps
    at ``x``) or ``"+"`` (after them). Work at the current mpmath precision.
    """

    def __init__(self, model: Model):
        self.model = model
        self.layout = Layout(model)
        self.n = self.layout.levels
        self._stiffness = {}
        self._inertia = {}
        for step in self.layout.steps:
            if not isinstance(step, Interval):
                for element, _levels in step.elements:
                    S = element.stiffness(LAM)
                    self._stiffness[id(element)] = sp.lambdify(LAM, S, modules="mpmath")
                    inertia = element.inertia()
                    if not inertia.is_zero_matrix:
                        self._inertia[id(element)] = inertia

    def _consts(self, seg):
        dps = mpmath.mp.dps
        return to_mp(seg.EI, dps), to_mp(seg.m, dps), to_mp(seg.l, dps)

    def run(self, lam, E0, samples, real: bool, gram: bool):
        """Propagate; return (recorded states, mass Gram matrix or None).

        ``E0``: numpy object array ``(4n, k)``; ``samples``: list per level.
        Recorded states: dict ``(level, i) -> (4, k)`` complex array.

        The state is carried in mpmath from cut to cut and, inside a segment,
        to anchors ``h`` apart with ``|beta| h <= 1``; from an anchor to the
        sample points the double-precision transfer matrix suffices (it loses
        at most ``e**1`` in relative accuracy), which makes dense sampling cheap.
        """
        lam = mpmath.mpmathify(lam)
        lam2 = mpmath.mpf(-(lam.imag ** 2)) if real else lam * lam
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
                xs = to_mp(step.x_start, mpmath.mp.dps)
                xe = to_mp(step.x_end, mpmath.mp.dps)
                xsf, xef = float(xs), float(xe)
                for lvl, seg in step.segments:
                    consts = self._consts(seg)
                    lam2_s = lam2
                    if seg.kw != 0:
                        # on a foundation the segment at lam is the bare one at
                        # lam**2 + kw/m (same x), and the mass Gram is still m Y**2
                        lam2_s = lam2 + to_mp(seg.kw, mpmath.mp.dps) / consts[1]
                        seg = EulerBernoulliSegment(seg.EI, seg.m, seg.l)
                    blk = slice(4 * lvl, 4 * lvl + 4)
                    record(lvl, xs, "-+")          # a beam's left end without a station
                    inside = [(i, x) for i, (x, _s) in enumerate(samples[lvl])
                              if xsf - 1e-9 <= approx[lvl][i] <= xef + 1e-9
                              and x > xs + tol * max(1, abs(xs)) and not at(lvl, i, xe, xef)
                              and x < xe]
                    if inside:
                        self._inside(lam2_s, seg, consts, E[blk, :], xs, inside, lvl, recorded)
                    U = seg.evaluate_mp(lam2_s, consts)
                    E1 = U.dot(E[blk, :])
                    if gram:
                        G += _segment_gram(seg, lam2_s, consts, E[blk, :], E1, real)
                    E[blk, :] = E1
                    record(lvl, xe, "-+", only_new=False)
            else:
                x = to_mp(step.x, mpmath.mp.dps)
                levels = sorted({lv for _e, lvs in step.elements for lv in lvs})
                for lvl in levels:
                    record(lvl, x, "-+")
                for element, lvs in step.elements:
                    S = self._stiffness[id(element)](lam)
                    S = np.array(S.tolist() if hasattr(S, "tolist") else S, dtype=object)
                    if real:
                        S = np.vectorize(lambda v: mpmath.mpf(mpmath.re(v)), otypes=[object])(S)
                    disp, force, sign = [], [], []
                    for lvl_local, var in element.dofs:
                        lvl = lvs[lvl_local]
                        f, s = CONJUGATE[var]
                        disp.append(4 * lvl + STATE.index(var))
                        force.append(4 * lvl + STATE.index(f))
                        sign.append(s)
                    if gram and id(element) in self._inertia:
                        # kinetic energy of lumped masses: d^T M d (displacements do not jump)
                        Mi = self._inertia[id(element)]
                        Mi = np.array([[to_mp(v, mpmath.mp.dps) for v in row]
                                       for row in Mi.tolist()], dtype=object)
                        D = E[disp, :]
                        G += D.T.dot(Mi).dot(D)
                    jump = S.dot(E[disp, :])
                    for i, (row, s) in enumerate(zip(force, sign)):
                        E[row, :] = E[row, :] + s * jump[i, :]
                for lvl in levels:
                    record(lvl, x, "+", only_new=False)
        missing = [(lvl, samples[lvl][i][0]) for lvl in range(self.n)
                   for i in range(len(samples[lvl])) if (lvl, i) not in recorded]
        if missing:
            lvl, x = missing[0]
            raise ValueError(f"x = {mpmath.nstr(x, 8)} is not on beam "
                             f"'{self.model.beams[lvl].name}'")
        return recorded, G

    @staticmethod
    def _inside(lam2, seg, consts, Z0, xs, inside, lvl, recorded):
        """States at sample points strictly inside a segment, from nearby mpmath anchors."""
        EI, m, length = consts
        kappa = abs(lam2 * m / EI)
        reach = float(kappa) ** 0.25 * float(length)       # |beta| l
        n_anchor = max(1, math.ceil(reach))
        h = length / n_anchor
        Uh = seg.evaluate_mp(lam2, (EI, m, h)) if n_anchor > 1 else None
        anchors = [Z0]
        groups: dict = {}
        for i, x in inside:
            j = min(int(mpmath.floor((x - xs) / h)), n_anchor - 1)
            groups.setdefault(j, []).append((i, float(x - xs - j * h)))
        while len(anchors) < max(groups) + 1:
            anchors.append(Uh.dot(anchors[-1]))
        consts_f = (float(EI), float(m))
        lam2_c = complex(lam2)
        for j, items in groups.items():
            Zc = _to_complex(anchors[j])
            ts = np.array([t for _i, t in items])
            nonzero = ts > 0
            U = np.empty((len(ts), 4, 4), dtype=complex)
            if nonzero.any():
                U[nonzero] = seg.evaluate_numpy(lam2_c, consts_f + (ts[nonzero],))
            U[~nonzero] = np.eye(4)
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


def _gl_nodes(n):
    """Gauss–Legendre nodes and weights on [0, 1] at the working precision."""
    xs, _ = np.polynomial.legendre.leggauss(n)
    # refine the double-precision nodes by Newton steps on P_n at the working precision
    nodes, weights = [], []
    for x0 in xs:
        x = mpmath.mpf(float(x0))
        for _ in range(8):
            p, dp = _legendre(n, x)
            dx = p / dp
            x -= dx
            if abs(dx) < mpmath.eps * 4:
                break
        p, dp = _legendre(n, x)
        nodes.append((x + 1) / 2)
        weights.append(1 / ((1 - x * x) * dp * dp))   # 2/((1-x^2)P'^2), halved for [0, 1]
    return nodes, weights


def _legendre(n, x):
    p0, p1 = mpmath.mpf(1), x
    for k in range(2, n + 1):
        p0, p1 = p1, ((2 * k - 1) * x * p1 - (k - 1) * p0) / k
    dp = n * (x * p1 - p0) / (x * x - 1)
    return p1, dp


def _segment_gram(seg, lam2, consts, Z0, Z1, real):
    """``integral over the segment of m Y_i Y_j`` for the columns of ``Z0`` (states at start)."""
    EI, m, length = consts
    kappa = -lam2 * m / EI
    k = Z0.shape[1]
    out = np.empty((k, k), dtype=object)
    if abs(kappa) * length**4 >= _CLOSED_FORM_MIN:
        zero = mpmath.mpf(0)
        for i in range(k):
            for j in range(i, k):
                F1 = _bilinear_F(length, kappa, EI, Z1[:, i], Z1[:, j])
                F0 = _bilinear_F(zero, kappa, EI, Z0[:, i], Z0[:, j])
                out[i, j] = out[j, i] = m * (F1 - F0) / (4 * kappa)
        return out
    nodes, weights = _gl_nodes(_GL_NODES)
    Ys = []
    for t in nodes:
        U = seg.evaluate_mp(lam2, (EI, m, t * length))
        Ys.append(U[0, :].dot(Z0))
    for i in range(k):
        for j in range(i, k):
            s = sum(w * Y[i] * Y[j] for w, Y in zip(weights, Ys))
            out[i, j] = out[j, i] = m * length * s
    return out


def _null_space(R, mult: int, real: bool):
    """The right singular vectors of the ``mult`` smallest singular values (columns)."""
    if R.rows == 0:
        return np.empty((0, mult), dtype=object)
    _, _, V = (mpmath.svd_r if real else mpmath.svd_c)(R)
    n = R.cols
    if mult > n:
        raise ComputationError(f"multiplicity {mult} exceeds the size {n} of R")
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
        E0 = np.full((4 * walker.n, mult), mpmath.mpf(0), dtype=object)
        for r, c in enumerate(ev.columns):
            E0[c, :] = V[r, :]
        samples = _default_samples(model, points, dps)
        rec, G = walker.run(lam, E0, samples, real, gram=real)
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
            shapes.append(ModeShape(eigenvalue, beams, left, dps, number + c))
    return shapes


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
    """A coordinate as an mpmath number; a float is read as the decimal it prints as."""
    if isinstance(value, mpmath.mpf):
        return value
    if isinstance(value, (float, np.floating)):
        value = sp.Rational(repr(float(value)))
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
