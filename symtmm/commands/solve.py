"""Eigenvalues lam with Im lam >= 0, ascending by Im lam, every printed digit correct."""

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
from ..limits import MAX_DIGITS, MAX_EIGENVALUES

HELP = "eigenvalues (natural frequencies), every printed digit correct"


def add_arguments(parser):
    add_model_arguments(parser)
    group = parser.add_mutually_exclusive_group()
    group.add_argument("--count", type=whole_number(1, MAX_EIGENVALUES), metavar="N",
                       help="the first N eigenvalues, counted with multiplicity (default 10)")
    group.add_argument("--omega-max", type=nonnegative, metavar="W",
                       help="all eigenvalues with 0 <= Im lam <= W (rad/s)")
    parser.add_argument("--sigma-max", type=nonnegative, metavar="S",
                        help="damped models: search -S <= Re lam <= 0 (default 2 W)")
    parser.add_argument("--digits", type=whole_number(1, MAX_DIGITS), default=15, metavar="D",
                        help="significant digits, all correct (default 15)")
    parser.add_argument("--method", default="default", metavar="NAME",
                        help="root search: default (count, isolate, refine), contour "
                             "(argument principle, any model), fmin1d or fmin2d (the paper's "
                             "grid searches, for comparison)")
    parser.add_argument("--hz", action="store_true",
                        help="also print the frequencies in Hz (Im lam / 2 pi)")
    parser.add_argument("--json", action="store_true", help="JSON output")
    add_csv_argument(parser)
    add_time_argument(parser)
    parser.add_argument("--certified", action="store_true",
                        help="add rigorous enclosures from ball arithmetic, and for damped "
                             "models prove the count in the search region (a winding number "
                             "in balls: seconds to minutes) (needs python-flint)")


def run(args) -> int:
    from ..solve import solve

    if args.certified:
        from ..roots.certified import require_flint
        require_flint()     # fail before the search, with a one-line message
    model = load_model_arg(args)
    if args.csv:
        check_csv_path(args.csv)
    count = args.count if args.count is not None or args.omega_max is not None else 10
    try:
        spectrum = solve(model, count=count, omega_max=args.omega_max,
                         sigma_max=args.sigma_max, digits=args.digits, method=args.method,
                         prove_count=args.certified and args.method in ("default", "contour"),
                         max_seconds=args.max_seconds)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    spectrum = spectrum.with_model_name(args.model)
    written = write_csv_arg(spectrum, args)
    if args.certified:
        _print_certified(model, spectrum, args.json)
    elif args.json:
        print(spectrum.to_json())
    else:
        if model.title:
            print(title_line(model.title))
        print(spectrum.table(hz=args.hz))
    if written and not args.json:
        print(written)
    return 0


def _print_certified(model, spectrum, as_json: bool) -> None:
    """The spectrum with an "enclosure" per eigenvalue (see symtmm.roots.certified)."""
    from ..jsonout import dumps
    from ..roots.certified import certify

    enclosures = certify(model, spectrum)
    if as_json:
        data = spectrum.to_dict()
        for item, enc in zip(data["eigenvalues"], enclosures):
            item["enclosure"] = enc.to_dict(spectrum.digits)
        # the proofs evaluate Delta too: they count as evaluations
        data["stats"]["evaluations"] += enclosures.evaluations
        data["stats"]["certification_evaluations"] = enclosures.evaluations
        print(dumps(data))
        return
    if model.title:
        print(title_line(model.title))
    print(spectrum.table())
    print("certified enclosures (Arb ball arithmetic):")
    for i, enc in enumerate(enclosures, 1):
        d = enc.to_dict(spectrum.digits)
        if not d["certified"]:
            print(f"{i:3d}  not certified (multiple eigenvalue)")
            continue
        print(f"{i:3d}  {d['proof']:<11}  Re in [{d['real'][0]}, {d['real'][1]}]  "
              f"Im in [{d['imag'][0]}, {d['imag'][1]}]")
