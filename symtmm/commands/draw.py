"""A picture of the model (beams at their levels, supports, springs, dashpots, masses,
bodies, sprung masses), or of one of its mode shapes in that layout; --animate writes
the mode's motion over one period as a GIF."""

from __future__ import annotations

from ..cli import add_model_arguments, load_model_arg, title_line, whole_number
from ..errors import ModelError
from ..limits import MAX_EIGENVALUES

HELP = "draw the model, or one of its mode shapes (--mode N, --animate)"


def add_arguments(parser):
    add_model_arguments(parser)
    parser.add_argument("--plot", metavar="FILE", required=True,
                        help="the picture (.png, .pdf, .svg; .gif with --animate)")
    parser.add_argument("--mode", type=whole_number(1, MAX_EIGENVALUES), metavar="N",
                        help="draw the N-th mode shape (counted with multiplicity)")
    parser.add_argument("--animate", action="store_true",
                        help="with --mode: the motion over one period, as a GIF")
    parser.add_argument("--title", metavar="TEXT", help="title (default: the model's title)")


def run(args) -> int:
    from ..drawing import animate_mode, draw_model
    from ..plot import check_figure_path, save_figure

    if args.animate and args.mode is None:
        raise ModelError("needs --mode N (the mode to animate)", field="--animate")
    if args.animate and not str(args.plot).lower().endswith(".gif"):
        raise ModelError("an animation is written as a GIF: give FILE.gif", field="--plot",
                         source=args.plot)
    if not args.animate:
        check_figure_path(args.plot)
    model = load_model_arg(args)
    try:
        model.require_numeric()         # (a picture needs every length and position)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    mode = None
    if args.mode is not None:
        from ..modes import mode_shapes
        try:
            modes = mode_shapes(model, count=args.mode, points=201, digits=12)
        except ModelError as exc:
            raise exc.with_source(args.model) from None
        mode = next((m for m in modes if m.number == args.mode), None)
        if mode is None:
            raise ModelError(f"the model has fewer than {args.mode} modes", field="--mode",
                             source=args.model)
    if args.animate:
        try:
            animate_mode(model, mode, args.plot)
        except (OSError, ValueError) as exc:
            raise ModelError(f"cannot write the animation: {exc}", field="--plot",
                             source=args.plot) from None
    else:
        save_figure(draw_model(model, mode, title=args.title), args.plot)
    print(f"figure written to {title_line(args.plot)}")
    return 0
