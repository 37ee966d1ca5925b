"""Markdown report of a benchmark run (the dict :func:`benchmarks.run.run` returns)."""

from __future__ import annotations

__all__ = ["render"]


def _g(x, digits=3) -> str:
    """A number for a table.

    Examples
    --------
    >>> _g(None), _g(0.000123456), _g(12345.678), _g(0)
    ('–', '1.23e-04', '1.23e+04', '0')
    """
    if x is None:
        return "–"
    if isinstance(x, str):
        return x
    if x == 0:
        return "0"
    if 1e-2 <= abs(x) < 1e4:
        return f"{x:.{digits}g}"
    return f"{x:.{digits - 1}e}"


def _table(header, rows) -> list:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return out + [""]


def _met(flag) -> str:
    return "**met**" if flag else "**missed**"


def _machine(r) -> list:
    m = r["machine"]
    pk = ", ".join(f"{k} {v}" for k, v in m["packages"].items() if v)
    out = ["## Machine and commands", "",
           f"* {m['cpu']}, {m['cores']} cores, {m['platform']}, Python {m['python']}",
           f"* {pk}; {m['gcc'] or 'no C compiler'}",
           f"* commit {m['commit']}, {m['date']}",
           (f"* load average (1, 5, 15 min) before: {r['load_before']}, after: {r['load_after']}"
           " — the machine is shared, other processes ran beside the benchmark; every "
           "rate is the best of several repetitions"),
           f"* command: `{r['command']}`"
           + (" (`--json` for the raw numbers, `-o docs/benchmarks.md` to write this file)"),
           "* seconds per section: " + ", ".join(f"{k} {v}" for k, v in r["seconds"].items()),
           ""]
    return out


def _root_search(rs) -> list:
    out = ["## 1. Root search", "",
           ("Evaluations: one per point at which Delta, R or an eigenvalue count is evaluated "
           "(double or multiple precision alike). Error: the largest |found - reference| / "
           "|reference| over the reference eigenvalues that were found; missed: reference "
           "eigenvalues (with multiplicity) no found value matches within 1e-3 relative; "
           "spurious: found values that match none. `digits` is what the method itself "
           "reports as correct."), ""]
    for case in rs["cases"]:
        out += [f"### {case['name']}", "", f"Reference: {case['reference']}.", ""]
        rows = []
        for name, m in case["methods"].items():
            if m.get("status") == "not installed":
                rows.append([name, "not installed"] + ["–"] * 7)
                continue
            rows.append([name, m["status"], m["evaluations"], _g(m["seconds"]),
                         _g(m["max_rel_error"], 2), m["missed"], m["spurious"],
                         f"{m['found']}/{m['reference']}", _g(m.get("digits"))])
        out += _table(["method", "status", "evaluations", "seconds", "max rel. error",
                       "missed", "spurious", "found/ref.", "digits"], rows)
        if "evaluation_ratio_default_over_fmin1d" in case:
            out.append(f"Evaluations default / fmin1d: "
                       f"{case['evaluation_ratio_default_over_fmin1d']:.3f}.")
        if "evaluation_ratio_default_over_fmin2d" in case:
            out.append(f"Evaluations default / fmin2d: "
                       f"{case['evaluation_ratio_default_over_fmin2d']:.3f}.")
        if "reference_check" in case:
            c = case["reference_check"]
            out.append(f"Reference cross-checked by {c['method']}: largest relative "
                       f"difference {_g(c['max_rel_difference'], 2)}, {c['missed']} missed.")
        cx = case["methods"].get("cxroots")
        if cx and cx.get("status") not in (None, "ok", "not installed"):
            counted = cx.get("counted_in_rectangle")
            out.append(f"cxroots: {cx['status']} after {_g(cx['seconds'])} s "
                       f"(budget {cx.get('budget_seconds')} s), {cx['evaluations']} evaluations; "
                       + (f"it had counted {counted} zeros in the whole rectangle and located "
                          f"{cx['found']} of them." if counted is not None else
                          "it had not finished counting the zeros in the rectangle."))
        out.append("")
    t = rs["target"]
    out += [f"**Target** — {t['text']}: {_met(t['met'])} "
            + "; ".join(f"{x['case']}: ratio {x['ratio']:.3f}, error {_g(x['max_rel_error'], 2)}, "
                        f"missed {x['missed']}" for x in t["results"]), ""]
    return out


def _evaluator(ev) -> list:
    out = ["## 2. Evaluator", "",
           ("Evaluations of Delta(lam) per second at 10^4 points -sigma + i omega "
           "(0 <= sigma <= 50, 1 <= omega <= 300). `symtmm`: `Evaluator.delta` on the "
           "whole array (numpy, vectorised); `naive_numpy`: per point, each segment's 4x4 "
           "matrix from the closed form, the stacked 4n x 4n matrices multiplied in a Python "
           "loop, `np.linalg.det` (benchmarks/baselines.py); `mpmath_30/60`: "
           "`Evaluator.delta_mp` per point; `generated_c`: `symtmm codegen --lang c`, "
           "`gcc -O2`, the loop over points inside C (clock_gettime); "
           "`generated_c_ctypes`: the same function called once per point from Python."), ""]
    keys = list(ev["points_per_second"])
    rows = []
    for m in ev["models"]:
        rows.append([f"{m['model']} ({m['levels']} levels, {m['springs']} springs)"]
                    + [f"{_g(m['points_per_second'][k])} ({_g(m['ratio_to_naive_numpy'][k])}x)"
                       for k in keys])
    out += _table(["model"] + keys, rows)
    out.append("Points per second (ratio to naive_numpy). Largest difference from "
               "`Evaluator.delta`, relative to the largest |Delta| of the batch: "
               + "; ".join(f"{m['model']}: " + ", ".join(
                   f"{k} {_g(v, 2)}" for k, v in m["max_abs_difference_relative_to_max_delta"]
                   .items()) for m in ev["models"])
               + " (Delta cancels up to 15 digits at the largest omega here, so agreement "
                 "is to the rounding of the largest terms).")
    t = ev["target"]
    out += ["", f"**Target** — {t['text']}: {_met(t['met'])} (ratio {t['ratio']:.1f} on "
            f"{ev['model']}; " + ", ".join(f"{k} {v}" for k, v in t["by_model"].items()) + ")",
            ""]
    return out


def _fe(fe) -> list:
    s = fe["symtmm"]
    out = ["## 3. Finite elements", "",
           (f"Model {fe['model']}, first {fe['count']} frequencies. Reference: "
           f"{fe['reference']}. FE: `symtmm.fe.fe_frequencies` (cubic Hermite, consistent "
           "mass, dense `scipy.linalg.eigh`, Rayleigh-quotient polish)."), "",
           (f"symtmm, `solve(model, count={fe['count']}, digits={s['digits']})`: "
           f"{_g(s['seconds'])} s, {s['evaluations']} evaluations, largest error of the "
           f"printed values {_g(s['max_rel_error'], 2)}."), ""]
    out += _table(["elements per beam", "seconds", "max rel. error"],
                  [[r["elements_per_beam"], _g(r["seconds"]), _g(r["max_rel_error"], 2)]
                   for r in fe["fe"]])
    if fe.get("fe_error_exponent") is not None:
        sizes = fe.get("fe_exponent_sizes") or []
        out.append(f"FE error against elements per beam: fitted exponent "
                   f"{fe['fe_error_exponent']:.2f} over {sizes[0]}-{sizes[-1]} elements, "
                   "where it still falls (h^4 expected).")
    if fe.get("fe_best"):
        b = fe["fe_best"]
        out.append(f"Smallest FE error: {_g(b['max_rel_error'], 2)} with "
                   f"{b['elements_per_beam']} elements per beam ({_g(b['seconds'])} s).")
    t = fe["target"]
    out += ["", (f"**Target** — {t['text']}: {_met(t['met'])} (symtmm {_g(t['symtmm_seconds'])} s "
            f"to 1e-12; FE fastest to 1e-6: {_g(t['fe_seconds'])} s)"), ""]
    return out


def _scaling(sc) -> list:
    out = ["## 4. Scaling", "",
           ("Sizes chosen so that the full run stays near 15 minutes on this 2-core machine: "
            "evaluations of Delta up to 50 levels and 100 springs per level; full solves up to "
            "10 levels and 50 springs per level (a solve at 50 levels would take over an hour: "
            "about 200 evaluations of Delta in mpmath at some 20 s each)."), "",
           (f"Models: {sc['model']}; springs per level "
           f"{sc['fixed_springs_per_level']} when the levels vary, {sc['fixed_levels']} levels "
           f"when the springs vary. Full solves: first 10 frequencies, 15 digits, each in its "
           f"own process, limit {sc['solve_limit_seconds']:g} s."), ""]
    rows = [[r["levels"], r["springs_per_level"], r["segments"],
             _g(r["numpy_seconds_per_point"] * 1e6), _g(r["mpmath30_seconds_per_evaluation"] * 1e3)]
            for r in sc["eval_levels"] + sc["eval_springs"]]
    out += ["Time per evaluation of Delta:", ""]
    out += _table(["levels", "springs/level", "segments", "numpy us/point", "mpmath 30 digits ms"],
                  rows)
    rows = []
    for key in ("solve_levels", "solve_levels_exact_rank", "solve_springs"):
        for r in sc.get(key, []):
            rows.append([r["levels"], r["springs_per_level"],
                         "rank over QQ" if key.endswith("exact_rank") else "as is",
                         r["status"], _g(r.get("seconds")), r.get("evaluations", "–"),
                         _g(r.get("rigid_body_modes_seconds"))])
    out += ["Full solves:", ""]
    out += _table(["levels", "springs/level", "library", "status", "seconds", "evaluations",
                   "rigid_body_modes alone, s"], rows)
    out += ["Fitted exponents (log-log least squares; all sizes / largest three):", ""]
    rows = []
    for k, v in sc["exponents"].items():
        rows.append([k, _g(v), _g(sc.get("exponents_largest_three", {}).get(k))])
    out += _table(["quantity", "all sizes", "largest three"], rows)
    t = sc["target"]
    out += [(f"**Target** — {t['text']}: {_met(t['met'])} (numpy {_g(t['exponent_numpy'])}, "
            f"mpmath {_g(t['exponent_mpmath'])})"), ""]
    return out


ANALYSIS = """## Where targets are missed: why, and what would help

Found with cProfile and instrumented runs on this machine (commands below).

**Evaluator, 100x the naive product.** The naive per-point product spends most of
its time in Python and numpy call overhead (tens of small numpy calls per point);
the vectorised evaluator removes that, leaving the arithmetic itself. For example 1
at 10^4 points, about three quarters of `Evaluator.delta` is building the segment
matrices (`c_functions_numpy`: a complex fourth root and four complex
transcendental functions per segment and point, boolean-mask gathers and scatters,
then `np.stack` of sixteen entry arrays), the rest the batched 4x4 products on
strided slices, the spring jumps and `np.linalg.det`. The generated C, which does
the same arithmetic without numpy's temporaries, is only a few times faster than
the vectorised evaluator; 100x the naive product would need the numpy evaluator to
be faster than compiled C, so the target is out of reach of numpy vectorisation.
A small, safe speed-up: in `Evaluator.R`, evaluate the matrix of segments with
equal `(EI, m, l, kw)` once per call (a dict keyed by the constants, as
`StiffnessModel.matrix` already does): example 1 has 6 segments but 2 distinct
matrices, example 3 9 and 2; measured 9.6 -> 6.5 us/point (example 1) and 18.4 ->
11.4 us/point (example 3), identical results. Building `U` into a preallocated
`(N, 4, 4)` array instead of `np.stack` and computing cosh/sinh and cos/sin from
two exponentials save a little more.

**cxroots on the paper's damped rectangle.** It counts the zeros of the whole
rectangle but does not locate them within the budget. In a separate run with a
420-s limit it had located 2 of the 9 after 60 s and spent the rest recounting
sub-rectangles whose counts do not add up to their parent's (thousands of
"Number of roots in sub contours not adding up to parent contour" warnings): near
the far corner, |lam| of about 3350, the double-precision transfer-matrix Delta
loses about 20 digits (sum |beta| L / ln 10), so the argument integrals along
edges there are noise. On the small rectangle, where Delta loses about 6 digits,
cxroots finds every zero to about 1e-15, with some thousand times the default
search's evaluations. With cxroots' default `int_method="quad"` (one point per
call) it found nothing even on the small rectangle in 150 s; the benchmark uses
`"romb"`.

**symtmm to 1e-12 faster than FE to 1e-6.** A 100-element-per-beam FE model
(400 degrees of freedom, dense `eigh`) reaches 3e-7 in a few hundredths of a
second; symtmm's 13-digit solve takes over half a second, about 85 % of it in
`Evaluator.delta_mp` (about 200 evaluations at 26-28 digits, 2-3 ms each, some 20
per root). Instrumenting the refinement shows why there are 20 per root: in
`symtmm/roots/bracket.py::anderson_bjorck`, regula falsi converges to the root from
one side, so after almost every step the bracket has not halved and the guard
bisects; the bisection replaces the far end with a fresh value and so discards the
Anderson–Björck scaling that would have moved that end. The iterate reaches the
root to double precision within about 10 steps and the remaining ~10 evaluations
are bisections of the far end. Proposed fix (three lines): bisect only when the
bracket has not halved over the last two steps (compare with the width two steps
back) instead of after every step. Measured with that change: example 1, 10 roots,
15 digits: 252 -> 179 evaluations, 0.68 -> 0.48 s; 13 digits: 238 -> 167; the
clamped-clamped modes 1-60 and example 4 unchanged in count, same printed digits in
all cases. That still leaves symtmm slower than the coarse FE model: reaching
1e-12 needs multiple-precision arithmetic (double-precision Delta loses about
`sum beta L / ln 10` digits, 12 at omega = 200 in example 1), at a few ms per
evaluation in mpmath. The FE model, on the other hand, cannot reach 1e-12 at all
in double precision: its error stops falling near 1e-9 (500 elements per beam)
and grows again on finer meshes (rounding in `eigh`, absolute error about eps
times the largest eigenvalue, which grows like h^-4); to 1e-9 it takes about as
long as symtmm takes to 1e-12.

**Full solves against levels.** With 10 levels the as-is solve does not finish in
the time limit: `symtmm.roots.undamped.rigid_body_modes` computes the exact rank of
`R(0)` with `sympy.Matrix.rank(simplify=True)`, whose fraction-free elimination of
a 20x20 matrix of large rationals takes longer than ten minutes on its own
(measured: 0.05 s at 2 levels, 1.3 s at 7, over 600 s at 10). The same exact rank
by elimination over the rationals, `DomainMatrix.from_Matrix(R).rank()`
(`from sympy.polys.matrices import DomainMatrix`), takes 0.02 s at 10 levels, 0.14 s
at 20 and 2.4 s at 50 levels: replacing the one line
`return R.shape[1] - R.rank(simplify=True)` by
`return R.shape[1] - DomainMatrix.from_Matrix(R).rank()` is exact and safe for
numeric models (for a model whose `R(0)` holds irrational constants, `from_Matrix`
picks an algebraic or expression domain; keep the old line as a fallback if that
domain is `EX`). The rows "rank over QQ" above are that change applied in the
benchmark process only. Beyond that, the cost per evaluation grows like
`levels**3` for these chains because every spring position cuts every level
(`levels * (levels * springs + 1)` segments, `2 levels` columns), and a full solve
is dominated by its ~200 mpmath evaluations (about 20 s each at 50 levels), so
full solves are run up to 10 levels only.

Commands used for the analysis:

```
python -c "import cProfile; ..."   # cProfile of solve(example 1, count=10, digits=13)
py-spy dump --pid PID              # the 10-level solve, stuck in rigid_body_modes
python benchmarks/run.py --sections evaluator   # before/after of the shared-segment cache
```
"""


def render(r: dict) -> str:
    out = ["# Benchmarks", "",
           "symtmm against the alternatives a user would pick instead: the paper's grid "
           "searches (`fmin1d`, `fmin2d`), a sign-change grid with bisection, cxroots, a "
           "naive numpy transfer-matrix product, mpmath, the generated C code and a "
           "cubic-Hermite finite-element model. Generated by `benchmarks/run.py`"
           + (" (quick run: small sizes only)" if r.get("quick") else "") + ".", ""]
    out += ["## How to run", "",
            "```",
            "python benchmarks/run.py -o docs/benchmarks.md   # full run, about 15 minutes here",
            "python benchmarks/run.py --quick                 # small sizes, under a minute",
            "python benchmarks/run.py --json > run.json       # the raw numbers",
            "python benchmarks/run.py --from-json run.json -o docs/benchmarks.md",
            "python benchmarks/run.py --sections evaluator    # one section",
            "```", "",
            ("cxroots is optional (`pip install cxroots`); without it its rows read "
             "\"not installed\". The generated C needs gcc."), ""]
    out += _machine(r)
    targets = r.get("targets", {})
    if targets:
        out += ["## Targets", ""]
        out += _table(["section", "target"], [[k, _met(v)] for k, v in targets.items()])
    if "root_search" in r:
        out += _root_search(r["root_search"])
    if "evaluator" in r:
        out += _evaluator(r["evaluator"])
    if "fe" in r:
        out += _fe(r["fe"])
    if "scaling" in r:
        out += _scaling(r["scaling"])
    out.append(ANALYSIS)
    return "\n".join(out)
