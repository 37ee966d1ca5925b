"""The results of a mode-shape computation: immutable value objects, no numerics.

:class:`BeamShape` (one beam's samples), :class:`ModeShape` (one mode: its
eigenvalue, its shape on every beam, the normalised left state that
determines it) and :class:`ModeSet` (the modes of a model, with their table,
JSON, HTML, LaTeX and plot).
"""

from __future__ import annotations

from dataclasses import dataclass, field

import mpmath
import numpy as np

from ..display import html_table, latex_array, latex_text, text_lines
from ..elements import STATE
from ..jsonout import dumps, header
from ..model import Model
from ..numeric.arith import MP
from ..results import Eigenvalue, Spectrum, decimal_string
from ..tables import Tabular

__all__ = ["BeamShape", "ModeShape", "ModeSet"]


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
        model it determines the shape everywhere (:func:`~symtmm.modes.evaluate_mode`).
    dps : int
        Decimal digits of the arithmetic the shape was computed in.
    number : int
        Position of the mode in its set (1-based, ascending by ``Im lam``).
    bodies : dict
        Rigid body (joint) name -> ``{"Y": Y_c, "Theta": Theta_c, "X": X_c}``: the
        motion of its centre of mass and its rotation, the freedoms it has
        (:meth:`~symtmm.model.Model.body_frame`: ``Theta`` when it rotates, ``X`` when
        it translates in the plane, ``Y`` and ``X`` then the plane's ``y`` and ``x``);
        float for undamped shapes, complex for damped ones.
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


def _Omega(omega, scale, digits: int):
    """``sqrt(omega / scale)`` to ``digits`` digits, as a global mpmath number."""
    ctx = MP.from_digits(digits + 10).ctx
    value = ctx.sqrt(ctx.mpf(omega) / ctx.mpf(scale))
    return mpmath.mp.make_mpf(value._mpf_)


@dataclass(frozen=True, repr=False)
class ModeSet(Tabular):
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
        """The JSON object of ``symtmm modes --json``: the header, then ``"modes": [...]``."""
        return header(self.model.source, self.model.title, self.spectrum.digits, self.notes) | {
            "modes": [m.to_dict() for m in self.modes]}

    def to_json(self) -> str:
        """:meth:`to_dict` as a JSON string."""
        return dumps(self.to_dict())

    def records(self):
        """``(columns, rows)``: one row per sample point of every mode and beam; damped
        shapes (complex) give each variable as ``_real`` and ``_imag`` columns."""
        damped = self._damped
        values = [f"{v}_{part}" for v in STATE for part in ("real", "imag")] if damped \
            else list(STATE)
        columns = ["mode", "real", "imag", "beam", "x"] + values
        rows = []
        for mode in self.modes:
            d = mode.eigenvalue.to_dict()
            for name, shape in mode.beams.items():
                for k, x in enumerate(shape.x):
                    row = [mode.number, d["real"], d["imag"], name, float(x)]
                    for var in STATE:
                        v = shape[var][k]
                        row += [float(v.real), float(v.imag)] if damped else [float(v)]
                    rows.append(row)
        return columns, rows

    def _rows(self):
        """Number, eigenvalue text, Omega text, and per beam the largest |Y|."""
        scale = self.spectrum.omega_scale
        rows = []
        for mode in self.modes:
            e = mode.eigenvalue
            if scale and not mode.damped:
                Om = decimal_string(_Omega(e.omega, scale[1], e.digits), e.digits)
            else:
                Om = ""
            amps = [f"{float(np.max(np.abs(b.Y))):.4g}" for b in mode.beams.values()]
            # undamped: omega in rad/s as solve prints it; damped: lam itself
            value = str(e) if self._damped else e.to_dict()["imag"]
            rows.append([str(mode.number), value, Om] + amps)
        return rows

    @property
    def _damped(self) -> bool:
        return any(m.damped for m in self.modes)

    def _head(self):
        ref = self.spectrum.omega_scale[0] if self.spectrum.omega_scale else ""
        return (["#", "lam [1/s]" if self._damped else "omega [rad/s]",
                 f"Omega (beam {ref})" if ref else "Omega"]
                + [f"max|Y| {n}" for n in self.beam_names])

    def table(self) -> str:
        """A readable summary: eigenvalue and the largest displacement on each beam."""
        head, rows = self._head(), self._rows()
        lines = text_lines(head, rows)
        damped = self._damped
        points = len(next(iter(self.modes[0].beams.values())).x) if self.modes else 0
        lines.append(f"{len(self.modes)} mode shape(s), {points} points per beam (max|Y| over "
                     "those points); "
                     + ("complex, largest |Y| = 1" if damped else
                        "mass-normalised: kinetic energy sum of integral (m Y^2 + rhoI "
                        "Theta^2) dx + masses + bodies = 1"))
        lines += list(self.notes)
        return "\n".join(lines)

    def _repr_html_(self) -> str:
        return html_table(self._head(), self._rows())

    def _repr_latex_(self) -> str:
        cols = [r"\#", r"\lambda\ [1/\mathrm{s}]" if self._damped else r"\omega\ [\mathrm{rad/s}]",
                r"\Omega"] + [
            r"\max|Y|\ " + latex_text(n) for n in self.beam_names]
        return latex_array(cols, self._rows())

    def plot(self, **kwargs):
        """The shapes as a matplotlib figure (see :func:`symtmm.plot.plot_modes`)."""
        from ..plot import plot_modes
        return plot_modes(self, **kwargs)
