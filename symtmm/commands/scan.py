"""log10|Delta| along the frequency axis (the paper's figs. 9 and 12), eigenvalues marked.

Damped models also get log10|Delta(lam)| over the complex plane (fig. 14):
with --plot FILE it is written to FILE with "-map" added before the suffix.
The curve is computed in double precision: near roots at high frequency it
shows rounding noise, which is fine for a picture; the marked eigenvalues come
from the exact solver.
"""

from __future__ import annotations

from pathlib import Path

from ..cli import (
    add_csv_argument,
    add_model_arguments,
    add_time_argument,
    check_csv_path,
    load_model_arg,
    nonnegative,
    real_number,
    title_line,
    whole_number,
    write_csv_arg,
)
from ..errors import ModelError
from ..limits import MAX_DIGITS, MAX_GRID_POINTS

HELP = "log10|Delta| along omega (and over the complex plane when damped), for plots"


_positive = real_number(0.0, low_open=True)


def add_arguments(parser):
    add_model_arguments(parser)
    parser.add_argument("--omega-max", type=_positive, required=True, metavar="W",
                        help="highest circular frequency (rad/s)")
    parser.add_argument("--omega-min", type=nonnegative, default=0.0, metavar="W0",
                        help="lowest circular frequency (default 0)")
    parser.add_argument("--points", type=whole_number(3, MAX_GRID_POINTS), default=2000, metavar="N",
                        help="grid points along omega (default 2000)")
    parser.add_argument("--spacing", choices=("Omega", "omega"), default="Omega",
                        help="grid equally spaced in Omega = beta L of the first beam "
                             "(default) or in omega")
    parser.add_argument("--frequency", choices=("Omega", "omega", "hz"), metavar="F",
                        help="horizontal axis of the plot: Omega, omega (rad/s) or hz "
                             "(default: as --spacing)")
    parser.add_argument("--sigma-max", type=_positive, metavar="S",
                        help="damped models: the map covers -S <= Re lam <= 0")
    parser.add_argument("--no-eigenvalues", action="store_true",
                        help="do not solve for the eigenvalues to mark")
    parser.add_argument("--digits", type=whole_number(1, MAX_DIGITS), default=10, metavar="D",
                        help="digits of the marked eigenvalues (default 10)")
    parser.add_argument("--method", default="default", metavar="NAME",
                        help="root search for the marks (see symtmm solve)")
    parser.add_argument("--json", action="store_true", help="JSON output")
    add_time_argument(parser, "the scan (the eigenvalues' search included)")
    add_csv_argument(parser)
    parser.add_argument("--title", metavar="TEXT",
                        help="title of the figure (default: the model's title)")
    parser.add_argument("--plot", metavar="FILE",
                        help="save the curve to FILE (damped: the map to FILE-map too)")


def map_path(path: str) -> str:
    """Where the complex-plane map goes when the curve goes to ``path``.

    >>> map_path("out/scan.png")
    'out/scan-map.png'
    """
    p = Path(path)
    return str(p.with_name(p.stem + "-map" + p.suffix))


def run(args) -> int:
    from ..scan import scan

    model = load_model_arg(args)
    if args.csv:
        check_csv_path(args.csv)
    if args.plot:
        from ..plot import check_figure_path
        check_figure_path(args.plot)
    try:
        result = scan(model, args.omega_max, points=args.points, omega_min=args.omega_min,
                      sigma_max=args.sigma_max, eigenvalues=not args.no_eigenvalues,
                      digits=args.digits, method=args.method, spacing=args.spacing,
                      max_seconds=args.max_seconds)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    written = []
    if args.plot:
        from ..plot import save_figure
        save_figure(result.plot(title=args.title, frequency=args.frequency or args.spacing),
                    args.plot)
        written.append(args.plot)
        if result.damped:
            save_figure(result.plot_map(title=args.title), map_path(args.plot))
            written.append(map_path(args.plot))
    csv_line = write_csv_arg(result, args)
    if args.json:
        print(result.to_json())
    else:
        if model.title:
            print(title_line(model.title))
        print(result.table())
        for path in written:
            print(f"figure written to {title_line(path)}")
        if csv_line:
            print(csv_line)
    return 0
