"""Mode shapes: Y, Theta, M and Q along every beam for the first N modes.

Undamped shapes are real and mass-normalised in the kinetic energy (sum
over the beams of the integral of m Y^2 + rhoI Theta^2 dx, plus M Y^2 + J
Theta^2 of lumped masses and rigid bodies, = 1); damped shapes are complex,
scaled so that the largest |Y| is 1. An eigenvalue of multiplicity m gives m
independent shapes (mass-orthonormal when undamped). In JSON, complex arrays
are written as {"real": [...], "imag": [...]}; a model with rigid bodies or
joints also gets "bodies": {NAME: {"Y": Y_c, "Theta": Theta_c}} per mode (the
deflection of the centre of mass and the rotation, the latter only for a
body that rotates).
"""

from __future__ import annotations

from ..cli import (
    add_csv_argument,
    add_model_arguments,
    add_time_argument,
    check_csv_path,
    load_model_arg,
    nonnegative,
    title_line,
    whole_number,
    write_csv_arg,
)
from ..errors import ModelError
from ..limits import MAX_DIGITS, MAX_EIGENVALUES, MAX_GRID_POINTS

HELP = "mode shapes (Y, Theta, M, Q along every beam)"


def add_arguments(parser):
    add_model_arguments(parser)
    parser.add_argument("--count", type=whole_number(1, MAX_EIGENVALUES), default=None, metavar="N",
                        help="the first N modes, counted with multiplicity (default 6)")
    # at least 2: both ends
    parser.add_argument("--points", type=whole_number(2, MAX_GRID_POINTS), default=101, metavar="P",
                        help="points per beam, both ends included (default 101)")
    parser.add_argument("--sigma-max", type=nonnegative, metavar="S",
                        help="damped models: search -S <= Re lam <= 0")
    parser.add_argument("--digits", type=whole_number(1, MAX_DIGITS), default=15, metavar="D",
                        help="significant digits of the eigenvalues (default 15)")
    parser.add_argument("--method", default="default", metavar="NAME",
                        help="root search (see symtmm solve)")
    parser.add_argument("--json", action="store_true", help="JSON output")
    add_csv_argument(parser)
    add_time_argument(parser, "the search and the shapes")
    parser.add_argument("--title", metavar="TEXT",
                        help="title of the figure (default: the model's title)")
    parser.add_argument("--plot", metavar="FILE",
                        help="save a figure (one panel per beam) to FILE (.png, .pdf, .svg)")
    parser.add_argument("--variable", choices=("Y", "Theta", "M", "Q"), default="Y",
                        help="state variable to plot (default Y)")


def run(args) -> int:
    from ..modes import mode_shapes

    model = load_model_arg(args)
    if args.csv:
        check_csv_path(args.csv)
    if args.plot:
        from ..plot import check_figure_path
        check_figure_path(args.plot)
    count = args.count if args.count is not None else 6
    try:
        modes = mode_shapes(model, count=count, sigma_max=args.sigma_max, points=args.points,
                            digits=args.digits, method=args.method,
                            max_seconds=args.max_seconds)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    if args.plot:
        from ..plot import save_figure
        save_figure(modes.plot(variable=args.variable, title=args.title or model.title or None),
                    args.plot)
    written = write_csv_arg(modes, args)
    if args.json:
        print(modes.to_json())
    else:
        if model.title:
            print(title_line(model.title))
        print(modes.table())
        if args.plot:
            print(f"figure written to {title_line(args.plot)}")
        if written:
            print(written)
    return 0
