"""Eigenvalues lam with Im lam >= 0, ascending by Im lam, every printed digit correct."""

from __future__ import annotations

from ..cli import add_model_arguments, load_model_arg
from ..errors import ModelError

HELP = "eigenvalues (natural frequencies), every printed digit correct"


def _positive_int(text):
    import argparse
    try:
        value = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a whole number, got {text!r}") from None
    if value < 1:
        raise argparse.ArgumentTypeError(f"must be at least 1, got {value}")
    return value


def _nonnegative(text):
    import argparse
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a number, got {text!r}") from None
    if not value >= 0 or value == float("inf"):
        raise argparse.ArgumentTypeError(f"must be a finite number >= 0, got {text}")
    return value


def add_arguments(parser):
    add_model_arguments(parser)
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--count", type=_positive_int, metavar="N",
                       help="the first N eigenvalues, counted with multiplicity (default 10)")
    group.add_argument("--omega-max", type=_nonnegative, metavar="W",
                       help="all eigenvalues with 0 <= Im lam <= W (rad/s)")
    parser.add_argument("--sigma-max", type=_nonnegative, metavar="S",
                        help="damped models: search -S <= Re lam <= 0")
    parser.add_argument("--digits", type=_positive_int, default=15, metavar="D",
                        help="significant digits, all correct (default 15)")
    parser.add_argument("--method", default="default", metavar="NAME",
                        help="root search: default")
    parser.add_argument("--json", action="store_true", help="JSON output")


def run(args) -> int:
    from ..solve import solve

    model = load_model_arg(args)
    count = args.count if args.count is not None or args.omega_max is not None else 10
    try:
        spectrum = solve(model, count=count, omega_max=args.omega_max,
                         sigma_max=args.sigma_max, digits=args.digits, method=args.method)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    spectrum = spectrum.with_model_name(args.model)
    if args.json:
        print(spectrum.to_json())
    else:
        if model.title:
            print(model.title)
        print(spectrum.table())
    return 0
