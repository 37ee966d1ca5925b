"""Pictures of a model: its beams, supports and point elements, and its mode shapes in
that layout (``symtmm draw``).

A planar frame (members at angles, :mod:`symtmm.frame`) is drawn in its plane, each
member displaced by its deflection and axial motion. Otherwise the beams are drawn at
their levels (the first on top), each from ``x0`` to
``x0 + L``; supports at the ends (pinned: a triangle, clamped: a hatched wall,
sliding: a wall on rollers, free: nothing); springs as zigzags (to the ground
downwards), dashpots as pistons beside them, rotational ones as a coil symbol;
lumped masses as squares; rigid bodies as a grey frame joining their points
(joints of beam ends as a dot, hinged ones open); sprung masses as blocks on
their springs; continuous layers as a hatched band between their beams (dotted
hatching when the layer has damping). With a mode, every beam is displaced by its ``Y`` (scaled so the
largest displacement is a third of the spacing of the levels) and every point
element and body moves with it; :func:`animate_mode` writes the motion as a GIF
(``Y cos(omega t)``, damped shapes as ``Re(Y e^{i omega t})``).

Examples
--------
>>> from symtmm.model import Beam, Model, Spring, oscillator
>>> m = Model((Beam("a", 1, 1, 1, left="pinned", right="pinned"),
...            Beam("b", 1, 1, 1, left="clamped", right="free")),
...           (Spring("a", "b", "1/2", 10, 1),),
...           bodies=(oscillator("tmd", "a", "1/4", "1/10", 5),))
>>> fig = draw_model(m)
>>> [t.get_text() for t in fig.axes[0].texts][:2]
['a', 'b']
"""

from __future__ import annotations

import numpy as np

from .model import GROUND, Model
from .plot import new_figure

__all__ = ["draw_model", "animate_mode"]

#: Vertical distance between the levels of two beams.
_GAP = 1.0


def _zigzag(x, y0, y1, turns: int = 6, width: float = 0.04):
    """Points of a vertical zigzag spring from ``(x, y0)`` to ``(x, y1)``."""
    t = np.linspace(0, 1, 2 * turns + 3)
    offsets = np.zeros_like(t)
    offsets[2:-2:2], offsets[3:-2:2] = width, -width
    return x + offsets, y0 + (y1 - y0) * t


def _dashpot(ax, x, y0, y1, span, **style):
    """A piston between two heights beside a spring."""
    w = 0.012 * span
    mid = (y0 + y1) / 2
    h = abs(y1 - y0) / 5 or 0.05
    ax.plot([x, x], [y0, mid - h / 2], **style)
    ax.plot([x - w, x - w, x + w, x + w], [mid + h / 2, mid - h / 2, mid - h / 2, mid + h / 2],
            **style)
    ax.plot([x - 0.7 * w, x + 0.7 * w], [mid, mid], **style)
    ax.plot([x, x], [mid, y1], **style)


def _drawn_end(beam, side: str) -> str:
    """The support drawn at an end: a rod's by its axial condition (a wall where it is held
    along its axis), a beam's as it is."""
    if not beam.is_rod:
        return getattr(beam, side)
    return "clamped" if beam.end(side) in ("fixed", "fixed-axial") else "free"


def _support(ax, kind: str, x, y, side: int, span: float):
    """The symbol of a boundary condition at ``(x, y)``; ``side`` -1 left end, +1 right."""
    s = 0.035 * span
    style = dict(color="0.25", lw=1.2)
    if kind == "pinned":
        ax.fill([x, x - s, x + s], [y, y - 1.6 * s, y - 1.6 * s], color="0.8", ec="0.25")
    elif kind in ("clamped", "sliding"):
        ax.plot([x, x], [y - 2 * s, y + 2 * s], lw=2.5, color="0.25")
        for k in np.linspace(-2 * s, 1.5 * s, 5):
            ax.plot([x, x + side * 0.6 * s], [y + k, y + k + 0.6 * s], **style)
        if kind == "sliding":
            for k in (-1.2 * s, 1.2 * s):
                _dot(ax, x - side * 0.35 * s, y + k, filled=False, size=4)


def _dot(ax, x, y, filled: bool = True, size: float = 6):
    """A joint or attachment point: filled (rigid) or open (hinged)."""
    ax.plot([x], [y], marker="o", ms=size, mfc="0.25" if filled else "white", mec="0.25",
            zorder=4, ls="none")


def _layout(model: Model):
    """Level (height) of every beam and the drawing's span along x."""
    beams = model.beams
    level = {b.name: -_GAP * i for i, b in enumerate(beams)}
    lo = min(float(b.x0) for b in beams)
    hi = max(float(b.x0 + b.L) for b in beams)
    return level, lo, hi, max(hi - lo, 1e-12)


def _displacement(mode, beam: str, x, amplitude: float, phase: complex = 1):
    """Y of ``mode`` on ``beam`` at ``x`` (interpolated in its samples), times amplitude."""
    if mode is None:
        return 0.0
    shape = mode.beams[beam]
    Y = np.real(np.asarray(shape.Y) * phase)
    return amplitude * float(np.interp(float(x), np.asarray(shape.x, dtype=float), Y))


def _amplitude(mode) -> float:
    if mode is None:
        return 0.0
    top = max(float(np.max(np.abs(s.Y))) for s in mode.beams.values())
    for motion in mode.bodies.values():
        top = max(top, abs(complex(motion.get("Y", 0))))
    return _GAP / 3 / top if top > 0 else 0.0


def is_planar(model: Model) -> bool:
    """A model drawn in the plane: some member at an angle or placed by its point, or an
    inextensible bar (a planar frame)."""
    return bool(model.links) or any(not b.along_x or b.origin is not None for b in model.beams)


def _draw_planar(ax, model: Model, mode=None, phase: complex = 1, labels: bool = True):
    """A planar frame in its plane: every member at its place, displaced by its deflection
    along its normal and, where it has one, its axial motion along its axis (its
    ``name_axial`` rod, or the joints an inextensible bar moves with)."""
    from .frame import AXIAL_SUFFIX

    levels = {b.name: b for b in model.beams}
    points = [b.point(x) for b in model.beams for x in (b.x0, b.x1)]
    xs = [float(p[0]) for p in points]
    ys = [float(p[1]) for p in points]
    size = max(max(xs) - min(xs), max(ys) - min(ys), 1e-12)
    links = {ln.name: ln for ln in model.links}
    bodies = {b.name: b for b in model.bodies}

    def samples(name):
        shape = mode.beams[name]
        return np.asarray(shape.x, dtype=float), np.real(np.asarray(shape.Y) * phase)

    def body_motion(name):
        """The translation (x, y) of a body in the mode."""
        if mode is None or name not in bodies:
            return np.zeros(2)
        motion = mode.bodies.get(name, {})
        frame = model.body_frame(bodies[name])
        out = np.zeros(2)
        for label, e in frame.directions.items():
            value = np.real(complex(motion.get(label, 0)) * phase)
            out += value * np.array([float(e[0]), float(e[1])])
        return out

    drawn = []              # (name, x samples, displacement vectors (n, 2))
    for b in model.beams:
        if b.is_rod and b.name.endswith(AXIAL_SUFFIX) and b.name[:-len(AXIAL_SUFFIX)] in levels:
            continue        # the axial part of a member: drawn with its bending
        t = np.array([float(v) for v in b.axis])
        nrm = np.array([-t[1], t[0]])
        if mode is None:
            x = np.array([float(b.x0), float(b.x1)])
            disp = np.zeros((2, 2))
        else:
            x, Y = samples(b.name)
            disp = np.outer(Y, t if b.is_rod else nrm)
            partner = levels.get(b.name + AXIAL_SUFFIX)
            if partner is not None and not b.is_rod:
                xa, u = samples(partner.name)
                disp += np.outer(np.interp(x, xa, u), t)
            link = links.get(b.name + AXIAL_SUFFIX)
            if link is not None:
                moving = [e for e in link.ends if e in bodies]
                if moving:
                    disp += np.outer(np.ones_like(x), t * float(body_motion(moving[0]) @ t))
        drawn.append((b, x, disp))
    top = max([float(np.max(np.linalg.norm(d, axis=1))) for _, _, d in drawn] + [0.0])
    amp = 0.12 * size / top if top > 0 else 0.0
    line = dict(color="C0", lw=2.2, zorder=3)
    for b, x, disp in drawn:
        base = np.array([[float(v) for v in b.point(xi)] for xi in x])
        if mode is not None:
            ends = np.array([[float(v) for v in b.point(xi)] for xi in (b.x0, b.x1)])
            ax.plot(ends[:, 0], ends[:, 1], color="0.75", lw=0.8, ls="--", zorder=1)
        shown = base + amp * disp
        ax.plot(shown[:, 0], shown[:, 1], **line)
        if labels:
            mid = len(shown) // 2
            ax.text(*(0.5 * (shown[0] + shown[-1]) if len(shown) == 2 else shown[mid]),
                    " " + b.name, fontsize=8, color="0.3")
        for side, k in (("left", 0), ("right", -1)):
            bc = _drawn_end(b, side)
            if bc != "free":
                _support(ax, "pinned" if bc == "pinned" else "clamped", shown[k, 0],
                         shown[k, 1], -1 if side == "left" else 1, size)
    for body in model.bodies:
        centre = np.array([float(v) for v in model.body_frame(body).centre])
        at = centre + amp * body_motion(body.name)
        _dot(ax, at[0], at[1], filled=not all(a.hinged for a in body.attachments
                                              if not levels[a.beam].is_rod))
        if body.fixed:
            _support(ax, "clamped" if "Theta" in body.fixed else "pinned", at[0], at[1], -1,
                     size)
        if body.M != 0:
            ax.plot([at[0]], [at[1]], marker="s", ms=10, color="0.35", zorder=5, ls="none")
    ax.set_aspect("equal")
    pad = 0.15 * size
    ax.set_xlim(min(xs) - pad, max(xs) + pad)
    ax.set_ylim(min(ys) - pad, max(ys) + pad)
    ax.set_xlabel("x [m]")
    ax.set_ylabel("y [m]")


def _draw(ax, model: Model, mode=None, phase: complex = 1, labels: bool = True):
    model = model.resolved()
    if is_planar(model):
        _draw_planar(ax, model, mode, phase, labels)
        return
    level, lo, hi, span = _layout(model)
    amp = _amplitude(mode)
    line = dict(color="C0", lw=2.2, zorder=3)
    element = dict(color="0.2", lw=1.0, zorder=2)

    def y_at(beam, x):
        return level[beam] + _displacement(mode, beam, x, amp, phase)

    for b in model.beams:
        x0, x1 = float(b.x0), float(b.x0 + b.L)
        if mode is not None:
            shape = mode.beams[b.name]
            xs = np.asarray(shape.x, dtype=float)
            ax.plot(xs, level[b.name] + amp * np.real(np.asarray(shape.Y) * phase), **line)
            ax.plot([x0, x1], [level[b.name]] * 2, color="0.75", lw=0.8, ls="--", zorder=1)
        else:
            ax.plot([x0, x1], [level[b.name]] * 2, **line)
        if labels:
            ax.text(lo - 0.06 * span, level[b.name], b.name, ha="right", va="center")
        _support(ax, _drawn_end(b, "left"), x0, y_at(b.name, x0), -1, span)
        _support(ax, _drawn_end(b, "right"), x1, y_at(b.name, x1), +1, span)
    for s in model.springs:
        x = float(s.x)
        ya = y_at(s.a, x)
        yb = y_at(s.b, x) if s.b != GROUND else level[s.a] - 0.45 * _GAP
        if s.b == GROUND:
            ax.plot([x - 0.02 * span, x + 0.02 * span], [yb, yb], color="0.25", lw=2)
        if s.kind == "rotational":
            # a coil between the two (or to the ground), on a thin line
            ax.plot([x, x], [ya, yb], color="0.5", lw=0.8, ls=":", zorder=2)
            ax.plot([x], [(ya + yb) / 2 if s.b != GROUND else ya], ls="none",
                    marker="$\\circlearrowleft$", ms=14, color="0.2", zorder=4)
            continue
        if s.k != 0:
            ax.plot(*_zigzag(x, ya, yb, width=0.012 * span), **element)
        if s.c != 0:
            _dashpot(ax, x + (0.03 * span if s.k != 0 else 0), ya, yb, span, **element)
    for p in model.masses:
        x = float(p.x)
        ax.plot([x], [y_at(p.beam, x)], marker="s", ms=9, color="0.35", zorder=5)
    for la in model.layers:
        xs = np.linspace(float(la.x0), float(la.x1), 60)
        ya = np.array([y_at(la.a, x) for x in xs])
        yb = np.array([y_at(la.b, x) for x in xs])
        ax.fill_between(xs, ya, yb, facecolor="none", edgecolor="0.55", lw=0.0,
                        hatch="||" if la.c == 0 else "|.", zorder=1)
    for body in model.bodies:
        _draw_body(ax, model, body, level, y_at, mode, amp, phase, span, element)
    ax.set_aspect("auto")
    ax.set_xlim(lo - 0.12 * span, hi + 0.06 * span)
    ax.set_ylim(-_GAP * (len(model.beams) - 1) - 0.7 * _GAP, 0.7 * _GAP)
    ax.set_yticks([])
    ax.set_xlabel("x [m]")
    for side in ("left", "right", "top"):
        ax.spines[side].set_visible(False)


def _draw_body(ax, model, body, level, y_at, mode, amp, phase, span, element):
    """A rigid body: a frame joining its rigid and hinged points, a block on springs."""
    xc = float(model.body_frame(body).centre[0])
    motion = {} if mode is None else mode.bodies.get(body.name, {})
    if all(a.elastic for a in body.attachments):
        # a sprung mass: its block sits above its beam, or between its two beams
        levels = [level[a.beam] for a in body.attachments]
        rest = (max(levels) + 0.4 * _GAP if len(levels) == 1
                else (max(levels) + min(levels)) / 2)
        y = rest + amp * float(np.real(complex(motion.get("Y", 0)) * phase))
        for a in body.attachments:
            ya = y_at(a.beam, float(a.x))
            ax.plot(*_zigzag(float(a.x), ya, y, width=0.012 * span), **element)
            if a.c != 0:
                _dashpot(ax, float(a.x) + 0.03 * span, ya, y, span, **element)
        w, h = 0.03 * span, 0.08 * _GAP
        ax.fill([xc - w, xc + w, xc + w, xc - w], [y - h, y - h, y + h, y + h], color="0.35",
                zorder=5)
        ax.text(xc + 1.3 * w, y, body.name, va="center", fontsize=8)
        return
    points = [(float(a.x), y_at(a.beam, float(a.x)), a) for a in body.attachments]
    # the centre of mass: at rest beside its first point, moving with the body
    first = body.attachments[0]
    yc = level[first.beam] + amp * float(np.real(complex(motion.get("Y", 0)) * phase))
    frame = sorted([(x, y) for x, y, _ in points] + [(xc, yc)])
    if len({round(x, 12) for x, _ in frame}) == 1:
        frame = sorted(frame, key=lambda p: p[1])       # a joint: its points one above another
    ax.plot([x for x, _ in frame], [y for _, y in frame], color="0.55", lw=4, alpha=0.6,
            zorder=2, solid_capstyle="round")
    for x, y, att in points:
        _dot(ax, x, y, filled=not att.hinged)
    if body.M != 0:
        ax.plot([xc], [yc], marker="s", ms=10, color="0.35", zorder=5, ls="none")


def draw_model(model: Model, mode=None, title: str | None = None, figsize=None):
    """A picture of ``model``; with ``mode`` (a :class:`~symtmm.modes.ModeShape`), the
    model in that shape (the beams at rest dashed).

    Returns
    -------
    Figure

    Raises
    ------
    ModelError
        Where a parameter has no value (the picture needs every length and position).
    """
    model.require_numeric()
    planar = is_planar(model.resolved())
    fig = new_figure(figsize or ((6.5, 6.0) if planar else (7.5, 1.2 + 1.3 * len(model.beams))))
    ax = fig.add_subplot()
    _draw(ax, model, mode)
    if title is None:
        title = model.title or ""
        if mode is not None:
            title = (title + "\n" if title else "") + f"mode {mode.number}: " \
                    f"lambda = {mode.eigenvalue}"
    if title:
        ax.set_title(title, fontsize=10)
    return fig


def animate_mode(model: Model, mode, path, frames: int = 24, fps: int = 12):
    """Write the motion of ``mode`` to ``path`` as a GIF (needs Pillow, which matplotlib
    brings): ``frames`` pictures over one period."""
    from matplotlib.animation import FuncAnimation, PillowWriter

    fig = draw_model(model, mode)
    ax = fig.axes[0]
    title = ax.get_title()

    def frame(k):
        ax.clear()
        _draw(ax, model, mode, phase=np.exp(2j * np.pi * k / frames))
        ax.set_title(title, fontsize=10)
        return []

    FuncAnimation(fig, frame, frames=frames, blit=False).save(str(path),
                                                              writer=PillowWriter(fps=fps))
