"""Eigenvalues as one parameter varies: N exact, equally spaced values from A to B.

Every value is an independent solve (default 12 significant digits, fewer than
solve's 15 because a sweep solves many models); the values run in parallel in
local processes (--jobs) or on a Dask cluster (--scheduler). Branches are
tracked across the values by their mode shapes (modal assurance criterion),
through crossings and veerings; JSON carries their ids under "branches".
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
from ..limits import MAX_DIGITS, MAX_EIGENVALUES, MAX_JOBS, MAX_STEPS

HELP = "eigenvalues for equally spaced values of one parameter, branches tracked"


def add_arguments(parser):
    add_model_arguments(parser)
    parser.add_argument("--param", required=True, metavar="NAME", help="the parameter to vary")
    parser.add_argument("--from", dest="start", required=True, metavar="A",
                        help="first value (exact: 0.3 means 3/10; expressions allowed)")
    parser.add_argument("--to", dest="stop", required=True, metavar="B", help="last value")
    # at least 2: both ends
    parser.add_argument("--steps", type=whole_number(2, MAX_STEPS), required=True, metavar="N",
                        help="number of values, both ends included")
    parser.add_argument("--count", type=whole_number(1, MAX_EIGENVALUES), default=10, metavar="K",
                        help="eigenvalues per value, counted with multiplicity (default 10)")
    parser.add_argument("--digits", type=whole_number(1, MAX_DIGITS), default=12, metavar="D",
                        help="significant digits, all correct (default 12 for sweeps)")
    parser.add_argument("--sigma-max", type=nonnegative, metavar="S",
                        help="damped models: search -S <= Re lam <= 0")
    parser.add_argument("--method", default="default", metavar="NAME",
                        help="root search (see symtmm solve)")
    parser.add_argument("--jobs", type=whole_number(1, MAX_JOBS), default=None, metavar="J",
                        help="local worker processes (default: number of CPUs)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="run on a Dask cluster, e.g. tcp://host:8786 (needs symtmm[dask])")
    parser.add_argument("--progress", action="store_const", const=True, default=None,
                        help="progress bar (default: when stderr is a terminal; needs tqdm)")
    parser.add_argument("--no-progress", dest="progress", action="store_false",
                        help="no progress bar")
    parser.add_argument("--json", action="store_true", help="JSON output")
    add_csv_argument(parser)
    add_time_argument(parser, "each step's search")
    parser.add_argument("--title", metavar="TEXT",
                        help="title of the figure (default: the model's title)")
    parser.add_argument("--plot", metavar="FILE", help="save the branches plot to FILE")
    parser.add_argument("--quantity", choices=("Omega", "omega", "hz", "sigma", "abs", "zeta",
                                               "locus"), metavar="Q",
                        help="what the plot shows against the parameter: Omega (default, "
                             "undamped), omega (default, damped; rad/s), hz, sigma (-Re lam), "
                             "abs (|lam|), zeta (damping ratio), or locus (the root locus: "
                             "Im lam against Re lam)")
    parser.add_argument("--panels", action="store_true",
                        help="one panel per group of overlapping branches (close families)")
    parser.add_argument("--x-label", metavar="TEXT",
                        help="label of the parameter axis, with its unit (default: NAME)")


def run(args) -> int:
    from ..sweep import sweep

    model = load_model_arg(args)
    if args.csv:
        check_csv_path(args.csv)
    if args.plot:
        from ..plot import check_figure_path
        check_figure_path(args.plot)
    try:
        # (whether the bar shows was decided by the command line: symtmm.cli)
        result = sweep(model, args.param, args.start, args.stop, args.steps, count=args.count,
                       digits=args.digits, method=args.method, sigma_max=args.sigma_max,
                       jobs=args.jobs, scheduler=args.scheduler, max_seconds=args.max_seconds)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    if args.plot:
        from ..plot import save_figure
        try:
            figure = result.plot(title=args.title or model.title or None,
                                 x_label=args.x_label, panels=args.panels,
                                 frequency=args.quantity)
        except ValueError as exc:       # Omega without a reference beam
            raise ModelError(str(exc), field="--quantity") from None
        save_figure(figure, args.plot)
    written = write_csv_arg(result, args)
    if args.json:
        print(result.to_json())
    else:
        if model.title:
            print(title_line(model.title))
        print(result.table())
        if args.plot:
            print(f"figure written to {title_line(args.plot)}")
        if written:
            print(written)
    return 0
