"""Plots of mode shapes, parameter sweeps and ``log10|Delta|`` scans.

Every function returns a :class:`matplotlib.figure.Figure` drawn with the Agg
backend: nothing global is touched (no ``pyplot``), nothing is shown. Save
with ``fig.savefig("file.png")``; in Jupyter a returned figure displays
itself (it renders a PNG on request).

Frequencies are plotted as the paper does, as the frequency parameter
``Omega = (omega**2 m L**4 / EI)**(1/4)`` of the model's first beam, when the
result knows that beam's scale; otherwise as ``omega`` in rad/s.
"""

from __future__ import annotations

import io
import math

import numpy as np

__all__ = ["Figure", "new_figure", "plot_modes", "plot_scan", "plot_scan_map", "plot_sweep",
           "save_figure"]

try:
    from matplotlib.figure import Figure as _MplFigure
except ImportError:  # pragma: no cover - matplotlib is an optional extra
    _MplFigure = object

#: Axis label of the frequency parameter.
OMEGA_LABEL = r"$\Omega = (\omega^2 m L^4/EI)^{1/4}$"


class Figure(_MplFigure):
    """A matplotlib figure that displays itself in Jupyter as a PNG."""

    def _repr_png_(self):
        buf = io.BytesIO()
        self.savefig(buf, format="png")
        return buf.getvalue()


def new_figure(figsize=(7.0, 4.5)) -> Figure:
    """An empty :class:`Figure` with an Agg canvas and constrained layout."""
    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
    except ImportError:  # pragma: no cover
        raise ImportError("plots need matplotlib: pip install 'symtmm[plot]'") from None
    fig = Figure(figsize=figsize, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _scale(omega_scale):
    """``(beam name, float scale)`` or None."""
    if not omega_scale:
        return None
    return omega_scale[0], float(omega_scale[1])


def _wrap(text: str, width: int = 76) -> str:
    import textwrap
    return "\n".join(textwrap.wrap(text, width)) if text else text


def _to_Omega(omega, scale):
    return np.sqrt(np.asarray(omega, dtype=float) / scale)


# -----------------------------------------------------------------------------------
# mode shapes
# -----------------------------------------------------------------------------------

_UNITS = {"Y": "Y", "Theta": r"$\Theta = Y'$", "M": r"$M = EI\,Y''$", "Q": r"$Q = EI\,Y'''$"}


def plot_modes(modes, variable: str = "Y", which=None, x_label: str = "x [m]",
               figsize=None, title: str | None = None) -> Figure:
    """One panel per beam with the chosen state variable of each mode along it.

    Parameters
    ----------
    modes : ModeSet
        From :func:`symtmm.modes.mode_shapes`.
    variable : {"Y", "Theta", "M", "Q"}
        The state variable to draw.
    which : sequence of int, optional
        Mode numbers (1-based) to draw; default all.
    x_label : str
        Label of the horizontal axis (global coordinate).
    title : str, optional
        A title over the panels.

    Returns
    -------
    Figure

    Examples
    --------
    >>> from symtmm.model import Beam, Model
    >>> from symtmm.modes import mode_shapes
    >>> cf = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="free"),))
    >>> fig = plot_modes(mode_shapes(cf, count=3, points=41, digits=10))
    >>> [ax.get_title() for ax in fig.axes]
    ['beam b (clamped-free)']
    """
    if variable not in _UNITS:
        raise ValueError(f"variable must be one of {', '.join(_UNITS)}")
    chosen = [m for m in modes if which is None or m.number in which]
    beams = modes.model.beams
    fig = new_figure(figsize or (7.5, 2.4 * len(beams) + 0.8))
    axes = fig.subplots(len(beams), 1, sharex=True, squeeze=False)[:, 0]
    scale = _scale(modes.spectrum.omega_scale)
    damped = any(m.damped for m in chosen)
    for ax, beam in zip(axes, beams):
        for i, mode in enumerate(chosen):
            shape = mode.beams[beam.name]
            color = _branch_color(i, len(chosen))
            label = _mode_label(mode, scale)
            values = shape[variable]
            if damped:
                ax.plot(shape.x, values.real, color=color, label=label + " (Re)")
                ax.plot(shape.x, values.imag, color=color, ls="--", label=label + " (Im)")
            else:
                # past 20 modes the colours repeat: the line style tells them apart
                ax.plot(shape.x, values, color=color, ls=("-", "--", "-.", ":")[i // 20 % 4],
                        label=label)
        ax.axhline(0, color="0.6", lw=0.6)
        for spring in modes.model.springs:
            if beam.name in (spring.a, spring.b):
                ax.axvline(float(spring.x), color="0.75", lw=0.8, ls=":")
        ax.set_title(f"{beam.kind} {beam.name} ({beam.end('left')}-{beam.end('right')})")
        ax.set_ylabel(_UNITS[variable] + (" (mass-normalised)" if not damped else " (max |Y| = 1)"))
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel(x_label + "   (dotted: springs)" if modes.model.springs else x_label)
    if chosen:
        axes[0].legend(fontsize="small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    if title:
        fig.suptitle(_wrap(title))
    return fig


def _mode_label(mode, scale):
    w = mode.omega
    if scale and not mode.damped:
        return f"{mode.number}: $\\Omega$ = {math.sqrt(w / scale[1]):.4f}"
    if mode.damped:
        lam = complex(mode.lam)
        return f"{mode.number}: $\\lambda$ = {lam.real:.4g}{lam.imag:+.6g}i"
    return f"{mode.number}: $\\omega$ = {w:.6g} rad/s"


# -----------------------------------------------------------------------------------
# sweeps
# -----------------------------------------------------------------------------------

def plot_sweep(sweep, frequency: str | None = None, x_label: str | None = None,
               title: str | None = None, figsize=None, legend: bool | None = None,
               panels: bool = False) -> Figure:
    """Eigenvalue branches against the swept parameter, one line per tracked branch.

    Parameters
    ----------
    sweep : Sweep
        From :func:`symtmm.sweep.sweep`.
    frequency : {"Omega", "omega", "hz", "sigma", "abs", "zeta", "locus"}, optional
        What to plot: the frequency parameter of the first beam (default when
        known and the model is undamped), ``omega = Im lam`` in rad/s (default for
        damped models), the same in Hz, the decay rate ``sigma = -Re lam``, ``|lam|``,
        the damping ratio ``zeta = -Re lam / |lam|``, or the root locus: every branch
        as a curve in the complex plane (``Re lam`` against ``Im lam``), the
        parameter's first and last values marked.
    x_label, title : str, optional
    legend : bool, optional
        Label the branches (default: when there are at most 20).
    panels : bool
        One panel, with its own vertical scale, for every group of branches
        whose ranges overlap: close families (weakly coupled identical beams)
        become readable.

    Returns
    -------
    Figure
    """
    scale = _scale(sweep.omega_scale)
    damped = sweep.damped
    if frequency is None:
        frequency = "Omega" if scale and not damped else "omega"
    if frequency not in _SWEEP_AXES and frequency != "locus":
        raise ValueError(f"unknown quantity {frequency!r} (use one of "
                         f"{', '.join(list(_SWEEP_AXES) + ['locus'])})")
    if frequency == "Omega" and not scale:
        raise ValueError("no reference beam to define Omega")
    if frequency == "locus":
        return _root_locus(sweep, title, figsize, legend)
    ids = sweep.branch_ids()
    curves = []
    for n, bid in enumerate(ids):
        if frequency == "Omega":
            x, lam = sweep.branch(bid)
            y = _to_Omega(lam.imag, scale[1])
        else:
            x, y = sweep.branch(bid, frequency)
        curves.append((n, bid, x, y))
    # number the branches by where they start (then by how high they go), and label each
    # with the range it covers: branches that start together still read apart
    curves.sort(key=lambda c: (float(c[3][0]), float(np.max(c[3]))) if len(c[3])
                else (np.inf, np.inf))
    sym = _SWEEP_AXES[frequency][0]
    labels = _branch_labels(sweep, curves, sym)
    curves = [(k, bid, x, y) for k, (_, bid, x, y) in enumerate(curves)]
    groups = _groups(curves) if panels else [curves]
    if figsize is None:
        figsize = (7.5, 5.0) if len(groups) <= 2 else (7.5, 1.6 * len(groups) + 1.2)
    if panels and len(groups) > 1:
        figsize = (figsize[0] + 2.5, figsize[1])
    fig = new_figure(figsize)
    axes = fig.subplots(len(groups), 1, sharex=True, squeeze=False)[:, 0]
    show_legend = legend if legend is not None else len(ids) <= 20
    for ax, group in zip(axes, reversed(groups)):      # the highest group on top
        for n, bid, x, y in sorted(group, key=lambda c: c[0]):     # legend in number order
            ax.plot(x, y, "-", marker="o", ms=2.5, lw=1.2, color=_branch_color(n, len(ids)),
                    label=labels[bid])
        ax.grid(alpha=0.3)
        if len(groups) > 1:
            lo = min(float(np.min(c[3])) for c in group)
            hi = max(float(np.max(c[3])) for c in group)
            ax.set_title(f"{len(group)} branch{'es' if len(group) > 1 else ''}, "
                         f"{sym} from {lo:.4g} to {hi:.4g}", fontsize="small", loc="left")
            if show_legend:
                ax.legend(fontsize="x-small", loc="upper left", bbox_to_anchor=(1.01, 1.0))
    axes[-1].set_xlabel(x_label or f"{sweep.parameter}")
    ylabel = (OMEGA_LABEL + f" of beam {scale[0] if scale else ''}" if frequency == "Omega"
              else _SWEEP_AXES[frequency][1])
    if len(axes) == 1:
        axes[0].set_ylabel(ylabel)
    else:
        fig.supylabel(ylabel)
    if title:
        fig.suptitle(_wrap(title))            # over the legend too: the axes are narrower
    if show_legend and ids and len(groups) == 1:
        fig.legend(handles=list(axes[0].get_lines()), fontsize="small",
                   loc="outside right center", title="branches, numbered\nby where they start",
                   title_fontsize="small")
    return fig


#: What a sweep can plot against its parameter: the symbol in labels and the axis label.
_SWEEP_AXES = {
    "Omega": ("Ω", ""),
    "omega": ("ω", r"$\omega = \mathrm{Im}\,\lambda$ [rad/s]"),
    "hz": ("f", r"$f = \mathrm{Im}\,\lambda / 2\pi$ [Hz]"),
    "sigma": ("σ", r"$\sigma = -\mathrm{Re}\,\lambda$ [1/s]"),
    "abs": ("|λ|", r"$|\lambda|$ [rad/s]"),
    "zeta": ("ζ", r"damping ratio $\zeta = -\mathrm{Re}\,\lambda / |\lambda|$"),
}


def _branch_labels(sweep, curves, sym: str) -> dict:
    """Per branch: its number, the range of the quantity and, where it is not present at
    every step, the values of the parameter where it is."""
    labels = {}
    steps = len(sweep.values)
    for k, (_, bid, x, y) in enumerate(curves, 1):
        if not len(y):
            labels[bid] = f"{k}"
            continue
        lo, hi = float(np.min(y)), float(np.max(y))
        where = ""
        if len(x) == 1:
            where = f" at {sweep.parameter} = {float(x[0]):g} only"
        elif len(x) < steps:
            where = f" for {sweep.parameter} in [{float(np.min(x)):g}, {float(np.max(x)):g}]"
        if hi - lo <= 1e-9 * abs(hi):
            labels[bid] = f"{k}: {sym} = {lo:.5g}" + (where or " throughout")
        else:
            labels[bid] = f"{k}: {sym} from {lo:.5g} to {hi:.5g}" + where
    return labels


def _root_locus(sweep, title, figsize, legend) -> Figure:
    """Every branch in the complex plane, ``Re lam`` against ``Im lam``."""
    ids = sweep.branch_ids()
    fig = new_figure(figsize or (7.5, 5.5))
    ax = fig.add_subplot()
    show_legend = legend if legend is not None else len(ids) <= 20
    first, last = float(sweep.values[0]), float(sweep.values[-1])
    for n, bid in enumerate(ids):
        x, lam = sweep.branch(bid)
        if not len(lam):
            continue
        color = _branch_color(n, len(ids))
        ax.plot(lam.real, lam.imag, "-", marker="o", ms=2.5, lw=1.2, color=color,
                label=f"{n + 1}" + ("" if len(x) == len(sweep.values) else
                                    f" ({sweep.parameter} {float(np.min(x)):g}.."
                                    f"{float(np.max(x)):g})"))
        ax.plot(lam.real[:1], lam.imag[:1], "s", color=color, ms=5)
        ax.plot(lam.real[-1:], lam.imag[-1:], "^", color=color, ms=6)
    ax.axvline(0.0, color="0.6", lw=0.8)
    ax.set_xlabel(r"$\mathrm{Re}\,\lambda = -\sigma$ [1/s]")
    ax.set_ylabel(r"$\mathrm{Im}\,\lambda = \omega$ [rad/s]")
    ax.grid(alpha=0.3)
    ax.set_title(f"root locus: {sweep.parameter} from {first:g} (square) to {last:g} "
                 "(triangle)", fontsize="small")
    if title:
        fig.suptitle(_wrap(title))
    if show_legend and ids:
        ax.legend(fontsize="x-small", title="branch", title_fontsize="x-small",
                  loc="upper left", bbox_to_anchor=(1.01, 1.0))
    return fig


def _groups(curves):
    """Curves whose value ranges overlap (or nearly), ascending."""
    if not curves:
        return [[]]
    lo = min(float(np.min(c[3])) for c in curves if len(c[3]))
    hi = max(float(np.max(c[3])) for c in curves if len(c[3]))
    gap = 0.04 * (hi - lo if hi > lo else 1.0)
    ordered = sorted(curves, key=lambda c: float(np.min(c[3])) if len(c[3]) else np.inf)
    groups, top = [], -np.inf
    for c in ordered:
        if not len(c[3]):
            continue
        if not groups or float(np.min(c[3])) > top + gap:
            groups.append([])
            top = -np.inf
        groups[-1].append(c)
        top = max(top, float(np.max(c[3])))
    return groups


def _branch_color(n: int, total: int):
    """Distinct colours: the default cycle up to 10 branches, tab20 up to 20."""
    if total <= 10:
        return f"C{n % 10}"
    from matplotlib import colormaps
    return colormaps["tab20"](n % 20)


# -----------------------------------------------------------------------------------
# scans
# -----------------------------------------------------------------------------------

def plot_scan(scan, frequency: str | None = None, title: str | None = None,
              figsize=(7.5, 4.5), mark: bool = True) -> Figure:
    """``log10|Delta(i omega)|`` along the frequency axis, eigenvalues marked.

    Parameters
    ----------
    scan : Scan
        From :func:`symtmm.scan.scan`.
    frequency : {"Omega", "omega", "hz"}, optional
        Horizontal axis: the first beam's frequency parameter (default when
        known), ``omega`` in rad/s or the frequency in Hz.
    mark : bool
        Mark the eigenvalues (``Im lam`` of each, with its multiplicity).

    Returns
    -------
    Figure
    """
    scale = _scale(scan.omega_scale)
    if frequency is None:
        frequency = "Omega" if scale else "omega"
    if frequency not in ("Omega", "omega", "hz"):
        raise ValueError(f"unknown frequency axis {frequency!r} (use Omega, omega or hz)")

    def axis(omega):
        omega = np.asarray(omega, dtype=float)
        if frequency == "Omega":
            return _to_Omega(omega, scale[1])
        return omega / (2 * np.pi) if frequency == "hz" else omega
    x = axis(scan.omega)
    fig = new_figure(figsize)
    ax = fig.add_subplot()
    y = np.where(np.isfinite(scan.log10_delta), scan.log10_delta, np.nan)
    ax.plot(x, y, color="C0", lw=1.0, label=r"$\log_{10}|\Delta(i\omega)|$")
    if mark and scan.spectrum is not None:
        finite = y[np.isfinite(y)]
        bottom = float(finite.min()) if finite.size else 0.0
        lo, hi = scan.omega[0], scan.omega[-1]
        marks = [e for e in scan.spectrum if lo <= float(e.omega) <= hi]
        undamped = [e for e in marks if e.lam.real == 0]
        damped = [e for e in marks if e.lam.real != 0]

        def where(es):
            return axis([float(e.omega) for e in es])
        if undamped:
            xs = where(undamped)
            ax.plot(xs, np.full(xs.shape, bottom), "v", color="C3", ms=6,
                    label="eigenvalues (symtmm solve)")
            for xv, e in zip(xs, undamped):
                ax.axvline(xv, color="C3", lw=0.6, alpha=0.5)
                if e.multiplicity > 1:
                    ax.annotate(f"×{e.multiplicity}", (xv, bottom), textcoords="offset points",
                                xytext=(4, 4), fontsize="small", color="C3")
            # marks closer than the eye can part at this scale: say how many there are
            span = float(x[-1] - x[0]) or 1.0
            for start, stop in _close_runs(xs, 0.006 * span):
                ax.annotate(f"{stop - start} close roots", (xs[start], bottom),
                            textcoords="offset points", xytext=(4, 14), fontsize="x-small",
                            color="C3")
        if damped:
            xs = where(damped)
            ax.plot(xs, np.full(xs.shape, bottom), "o", mfc="none", color="C1", ms=7, mew=1.5,
                    label=r"Im $\lambda$ of damped eigenvalues (off this axis: see the map)")
    ax.set_xlabel(OMEGA_LABEL + f" of beam {scale[0]}" if frequency == "Omega"
                  else r"$f = \omega / 2\pi$ [Hz]" if frequency == "hz" else r"$\omega$ [rad/s]")
    ax.set_ylabel(r"$\log_{10}|\Delta(i\omega)|$")
    ax.set_title(_wrap(title or scan.title or scan.model_name or "characteristic function along the frequency axis"))
    ax.grid(alpha=0.3)
    ax.legend(fontsize="small", loc="upper left")
    return fig


def _close_runs(xs, tol):
    """``(start, stop)`` of runs of two or more sorted values closer than ``tol``.

    Examples
    --------
    >>> _close_runs(np.array([1.0, 1.001, 2.0, 3.0, 3.002, 3.003]), 0.01)
    [(0, 2), (3, 6)]
    """
    runs, start = [], 0
    for i in range(1, len(xs) + 1):
        if i == len(xs) or xs[i] - xs[i - 1] > tol:
            if i - start > 1:
                runs.append((start, i))
            start = i
    return runs


def plot_scan_map(scan, title: str | None = None, figsize=(7.0, 5.5), mark: bool = True) -> Figure:
    """``log10|Delta(lam)|`` over the complex plane (damped models), eigenvalues marked.

    Horizontal axis ``Re lam = -sigma`` [1/s], vertical ``Im lam = omega`` [rad/s].

    Parameters
    ----------
    scan : Scan
        With a complex-plane map (:attr:`Scan.map_log10` not None).

    Returns
    -------
    Figure
    """
    if scan.map_log10 is None:
        raise ValueError("this scan has no complex-plane map (undamped model)")
    fig = new_figure(figsize)
    ax = fig.add_subplot()
    re = -scan.map_sigma
    Z = np.where(np.isfinite(scan.map_log10), scan.map_log10, np.nan)
    mesh = ax.pcolormesh(re, scan.map_omega, Z, shading="auto", cmap="viridis")
    finite = Z[np.isfinite(Z)]
    if finite.size:
        # a contour every half decade: the rings close around the roots
        levels = np.arange(math.floor(finite.min()), math.ceil(finite.max()) + 0.5, 0.5)
        ax.contour(re, scan.map_omega, Z, levels=levels, colors="white", linewidths=0.4,
                   alpha=0.6)
    fig.colorbar(mesh, ax=ax, label=r"$\log_{10}|\Delta(\lambda)|$")
    if mark and scan.spectrum is not None and len(scan.spectrum):
        lam = np.array([complex(e.lam) for e in scan.spectrum])
        ax.plot(lam.real, lam.imag, "x", color="red", ms=8, mew=2,
                label="eigenvalues (symtmm solve)")
        ax.legend(fontsize="small", loc="lower left")
    ax.set_xlabel(r"$\mathrm{Re}\,\lambda = -\sigma$ [1/s]")
    ax.set_ylabel(r"$\mathrm{Im}\,\lambda = \omega$ [rad/s]")
    ax.set_title(_wrap(title or scan.title or scan.model_name or "characteristic function in the complex plane"))
    return fig


def check_figure_path(path) -> None:
    """Refuse, before any computation, a figure file that could not be written.

    The format must be one matplotlib writes (by the extension) and the folder
    must exist and be writable; otherwise a long sweep would end in an error.

    Raises
    ------
    ModelError
        Naming ``--plot`` and the problem.

    Examples
    --------
    >>> check_figure_path("/no/such/folder/fig.png")
    Traceback (most recent call last):
    ...
    symtmm.errors.ModelError: /no/such/folder/fig.png: --plot: cannot write the figure: no folder /no/such/folder
    """
    import os
    from pathlib import Path

    from .errors import ModelError

    def fail(reason):
        raise ModelError(f"cannot write the figure: {reason}", field="--plot", source=str(path))

    try:
        from matplotlib.backends.backend_agg import FigureCanvasAgg
    except ImportError:  # pragma: no cover
        fail("plots need matplotlib: pip install 'symtmm[plot]'")
    target = Path(path)
    suffix = target.suffix.lower().lstrip(".")
    supported = FigureCanvasAgg(Figure()).get_supported_filetypes()
    if suffix not in supported:
        fail(f"unknown format {target.suffix or '(no extension)'!r} "
             f"(use one of {', '.join(sorted(supported))})")
    folder = target.parent if str(target.parent) else Path(".")
    if not folder.is_dir():
        fail(f"no folder {folder}")
    if not os.access(folder, os.W_OK):
        fail(f"folder {folder} is not writable")


def save_figure(fig, path) -> None:
    """Write ``fig`` to ``path``; the format follows the extension (png, pdf, svg, ...).

    Raises
    ------
    ModelError
        When the file cannot be written or the extension is unknown (bad input).
    """
    from .errors import ModelError

    try:
        fig.savefig(path, dpi=150)
    except (OSError, ValueError) as exc:
        reason = exc.strerror if isinstance(exc, OSError) and exc.strerror else str(exc)
        raise ModelError(f"cannot write the figure: {reason}", field="--plot",
                         source=str(path)) from None
