"""The characteristic function Delta = det R in closed form.

Undamped models are given in omega (rad/s, lam = I*omega) and in Omega =
beta_1 L_1 of the first beam; damped models in lam. Constant factors are
dropped; the power of Omega keeps the roots at zero (rigid-body modes);
repeated factors expose multiple roots. Parameters without a value stay
symbols; --symbolic NAME keeps a parameter symbolic although the file gives
it a value (that value then only orders cuts such as x1 and 1 - x1).

Beams with a Winkler foundation, an axial force, rotary inertia or shear
(Rayleigh, Timoshenko) are written in their wave numbers a_<beam>
(hyperbolic) and b_<beam> (trigonometric), each defined in the variable
(printed, and in JSON under "definitions"); Delta in the variable alone has
them substituted. Two beams joined by a layer are written in the wave numbers
p_<a>_<b>, q_<a>_<b> of the pair (p**4, q**4 the eigenvalues of the layered
member's matrix, given in a note), or in Omega where one of them is the single
beam's (identical beams). Rods are written in cos and sin of their wave numbers:
in a model of rods only Omega is the first rod's beta L = omega L sqrt(m/EA), and
a rod on an axial foundation has its own b_<rod> = sqrt((m omega**2 - kw)/EA).
"""

from __future__ import annotations

from ..cli import add_model_arguments, load_model_arg, real_number, title_line
from ..errors import ModelError
from ..limits import DERIVE_SECONDS

HELP = "characteristic function Delta in closed form (SymPy, LaTeX, JSON)"


def add_arguments(parser):
    add_model_arguments(parser)
    parser.add_argument("--symbolic", action="append", metavar="NAME[,NAME...]",
                        help="keep these parameters symbolic (repeatable)")
    parser.add_argument("--json", action="store_true",
                        help='JSON: {"variable", "delta", "latex", ...}')
    parser.add_argument("--latex", action="store_true",
                        help="print LaTeX only: both forms, each with its constant")
    parser.add_argument("--pretty", action="store_true",
                        help="print both forms as unicode text (SymPy's pretty printer)")
    parser.add_argument("--max-seconds", type=real_number(0.0, 1e6, low_open=True),
                        default=DERIVE_SECONDS, metavar="S",
                        help=f"give up after S seconds (default {DERIVE_SECONDS:g}); the size "
                             "of the polynomials is bounded too")


def run(args) -> int:
    from ..characteristic import characteristic_equation

    model = load_model_arg(args)
    names = [n.strip() for item in (args.symbolic or []) for n in item.split(",") if n.strip()]
    try:
        eq = characteristic_equation(model, symbolic=names, max_seconds=args.max_seconds)
    except ModelError as exc:
        raise exc.with_source(args.model) from None
    if args.json:
        print(eq.to_json())
    elif args.latex:
        print(eq.latex_both())
    elif args.pretty:
        if model.title:
            print(title_line(model.title))
        print(eq.pretty())
    else:
        if model.title:
            print(title_line(model.title))
        print(f"Delta({eq.variable}) = {eq.delta}")
        names = ", ".join(str(s) for s in eq.definitions) or "Omega"
        print("  with " + ("; ".join(f"{s} = {v}" for s, v in eq.definitions.items())
                           or f"Omega = {eq.Omega}") + ":")
        named = eq.subexpressions()
        if named is None:
            print(f"Delta({names}) = {eq.delta_Omega}")
        else:
            # a large form reads better with its repeated parts named
            definitions, reduced = named
            print(f"Delta({names}) = {reduced}")
            print("  where " + "\n        ".join(f"{k} = {v}" for k, v in definitions))
        print(f"  det R = ({eq.constant_Omega}) * Delta({names}) = ({eq.constant}) * "
              f"Delta({eq.variable}); {eq.count_ops()} operations, "
              f"{len(eq.factors)} factor(s), {eq.seconds:.2f} s")
        for note in eq.notes:
            print(f"  {note}")
    return 0
