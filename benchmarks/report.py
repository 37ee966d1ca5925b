"""Markdown report of a benchmark run (the dict :func:`benchmarks.run.run` returns).

Every statement about a target, met or missed, and every explanation of a
miss is generated from the run's own numbers (its timings, accuracies and
the profiles the sections gather), so the text cannot go stale against the
tables it sits beside.
"""

from __future__ import annotations

import statistics

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


def _pct(x) -> str:
    """A share as a percentage.

    Examples
    --------
    >>> _pct(0.4321), _pct(None)
    ('43 %', '–')
    """
    return "–" if x is None else f"{100 * x:.0f} %"


def _table(header, rows) -> list:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return out + [""]


def _met(flag) -> str:
    return "**met**" if flag else "**missed**"


# -- machine ---------------------------------------------------------------------------------
def _machine(r) -> list:
    m = r["machine"]
    pk = ", ".join(f"{k} {v}" for k, v in m["packages"].items() if v)
    missing = [k for k, v in m["packages"].items() if not v]
    return ["## Machine and commands", "",
            f"* {m['cpu']}, {m['cores']} cores, {m['platform']}, Python {m['python']}",
            f"* {pk}" + (f" (not installed: {', '.join(missing)})" if missing else "")
            + f"; mpmath backend `{m.get('mpmath_backend', '?')}` (`mpmath.libmp.BACKEND`: "
            "'gmpy' when gmpy2 is installed, much faster than 'python' at these precisions); "
            f"{m['gcc'] or 'no C compiler'}",
            f"* commit {m['commit']}, {m['date']}",
            (f"* load average (1, 5, 15 min) before: {r['load_before']}, after: "
             f"{r['load_after']}. The machine is shared: other processes ran beside the "
             "benchmark, so every time is the minimum of several repetitions (other work only "
             "ever adds time)"),
            f"* command: `{r['command']}`"
            + " (`--json` for the raw numbers, `-o docs/benchmarks.md` to write this file)",
            "* seconds per section: " + ", ".join(f"{k} {v}" for k, v in r["seconds"].items()),
            ""]


# -- 1. root search ------------------------------------------------------------------------
def _method_rows(case) -> list:
    rows = []
    for name, m in case["methods"].items():
        if m.get("status") == "not installed":
            rows.append([name, "not installed"] + ["–"] * 7)
            continue
        rows.append([name, m["status"], m["evaluations"], _g(m["seconds"]),
                     _g(m["max_rel_error"], 2), m["missed"], m["spurious"],
                     f"{m['found']}/{m['reference']}", _g(m.get("digits"))])
    return _table(["method", "status", "evaluations", "seconds", "max rel. error", "missed",
                   "spurious", "found/ref.", "digits"], rows)


#: the routines a profile times, in the order they are reported
_ROUTINES = {"delta_mpmath": "mpmath evaluations of Delta",
             "delta_double": "double-precision evaluations of Delta",
             "count": "Wittrick-Williams counts",
             "rigid_body_modes": "the exact rank of R(0)"}


def _profile_sentence(p) -> str:
    """Where a profiled default solve spent its time, in one sentence."""
    r = p["routines"]
    parts = []
    for key, what in _ROUTINES.items():
        s = r[key]
        if s["calls"]:
            per = s["seconds"] / s["calls"] * 1e3
            calls = f"{s['calls']} calls, {_g(per)} ms each" if s["calls"] > 1 else \
                f"one call, {_g(per)} ms"
            parts.append(f"{_pct(s['share'])} in {what} ({calls})")
    return (f"{_g(p['seconds'])} s: " + ", ".join(parts)
            + f", {_pct(p['other_seconds'] / p['seconds'])} elsewhere; "
            f"{_g(p['evaluations'] / max(p['roots'], 1))} evaluations per root, "
            f"{_g(p['mpmath_evaluations_per_root'])} of them in mpmath")


def _cxroots_sentence(cx) -> str | None:
    if not cx or cx.get("status") in (None, "ok", "not installed"):
        return None
    counted = cx.get("counted_in_rectangle")
    return (f"cxroots: {cx['status']} after {_g(cx['seconds'])} s (budget "
            f"{cx.get('budget_seconds')} s), {cx['evaluations']} evaluations; "
            + (f"it had counted {counted} zeros in the whole rectangle and located "
               f"{cx['found']} of them." if counted is not None else
               "it had not finished counting the zeros in the rectangle."))


def _case(case) -> list:
    out = [f"### {case['name']}", "", f"Reference: {case['reference']}.", ""]
    out += _method_rows(case)
    d = case["methods"]["default"]
    for other in ("fmin1d", "fmin2d"):
        if f"evaluation_ratio_default_over_{other}" not in case:
            continue
        o = case["methods"][other]
        ratio_s = d["seconds"] / max(o["seconds"], 1e-9)
        out.append(f"Evaluations default / {other}: "
                   f"{case[f'evaluation_ratio_default_over_{other}']:.3f}; "
                   + _speed_phrase(ratio_s, other)
                   + (f"; {other} misses {o['missed']} and is off by up to "
                      f"{_g(o['max_rel_error'], 2)}." if o["missed"] else "."))
    if "profile" in d:
        out.append("Default search, " + _profile_sentence(d["profile"]) + ".")
    if "reference_check" in case:
        c = case["reference_check"]
        out.append(f"Reference cross-checked by {c['method']}: largest relative "
                   f"difference {_g(c['max_rel_difference'], 2)}, {c['missed']} missed.")
    cx = _cxroots_sentence(case["methods"].get("cxroots"))
    if cx:
        out.append(cx)
    return out + [""]


def _root_search(rs) -> list:
    out = ["## 1. Root search", "",
           ("Evaluations: one per point at which Delta, R or an eigenvalue count is evaluated "
            "(double or multiple precision alike). Error: the largest |found - reference| / "
            "|reference| over the reference eigenvalues that were found; missed: reference "
            "eigenvalues (with multiplicity) no found value matches within 1e-3 relative; "
            "spurious: found values that match none. `digits` is what the method itself "
            "reports as correct."), ""]
    for case in rs["cases"]:
        out += _case(case)
    t = rs["target"]
    out += [f"**Target** — {t['text']}: {_met(t['met'])} ("
            + "; ".join(f"{x['case']}: ratio {x['ratio']:.3f}, error {_g(x['max_rel_error'], 2)}, "
                        f"missed {x['missed']}" for x in t["results"]) + ")", ""]
    return out


# -- 2. evaluator --------------------------------------------------------------------------
def _evaluator(ev) -> list:
    head = ev["models"][0]
    pts = head.get("points", {})
    out = ["## 2. Evaluator", "",
           (f"Evaluations of Delta(lam) per second at points -sigma + i omega "
            f"(0 <= sigma <= 50, 1 <= omega <= 300; {pts.get('vector', '?')} per vectorised "
            f"batch, {pts.get('naive', '?')} for the naive product, {pts.get('mpmath', '?')} "
            f"for mpmath; the minimum time of {pts.get('repeat', '?')} repetitions, 3 for "
            "naive and mpmath). `symtmm`: `Evaluator.delta` on the whole array (numpy, "
            "vectorised, columns re-orthonormalised along the span: stable at any mode); "
            "`symtmm_plain`: `np.linalg.det(Evaluator.R(lam))`, the same propagation without "
            "re-orthonormalisation; `naive_numpy`: per point, each segment's 4x4 matrix from "
            "the closed form, the stacked 4n x 4n matrices multiplied in a Python loop, "
            "`np.linalg.det` (benchmarks/baselines.py); `mpmath_30/60`: `Evaluator.delta_mp` "
            "per point; `generated_c`: `symtmm codegen --lang c` as generated, `gcc -O2`, the "
            "loop over points inside C (clock_gettime); `generated_c_ctypes`: the same "
            "function called once per point from Python."), ""]
    keys = list(head["points_per_second"])
    rows = [[f"{m['model']} ({m['levels']} levels, {m['springs']} springs)"]
            + [f"{_g(m['points_per_second'][k])} ({_g(m['ratio_to_naive_numpy'][k])}x)"
               for k in keys] for m in ev["models"]]
    out += _table(["model"] + keys, rows)
    out.append("Points per second (ratio to naive_numpy).")
    out.append("")
    acc_keys = list(head["relative_error_vs_mpmath_60"])
    rows = [[m["model"], _g(m["digits_lost_max"], 2)]
            + [f"{_g(m['relative_error_vs_mpmath_60'][k]['median'], 2)} / "
               f"{_g(m['relative_error_vs_mpmath_60'][k]['max'], 2)}" for k in acc_keys]
            for m in ev["models"]]
    out += [(f"Relative error against `Evaluator.delta_mp` at 60 digits on the first "
            f"{pts.get('accuracy', '?')} points, median / max (digits lost: "
            "`Evaluator.digits_lost`, about sum |beta| L / ln 10, the cancellation of the plain "
            "product):"), ""]
    out += _table(["model", "digits lost (max)"] + acc_keys, rows)
    out += _evaluator_findings(ev)
    t = ev["target"]
    out += ["", f"**Target** — {t['text']}: {_met(t['met'])} (ratio {t['ratio']:.1f} on "
            f"{ev['model']}; " + ", ".join(f"{k} {v}" for k, v in t["by_model"].items()) + ")",
            ""]
    return out


def _accurate(m, key, tol=1e-12) -> bool:
    e = m["relative_error_vs_mpmath_60"].get(key)
    return e is not None and e["max"] <= tol


def _evaluator_findings(ev) -> list:
    out = []
    for m in ev["models"]:
        acc = m["relative_error_vs_mpmath_60"]
        good = [k for k in acc if _accurate(m, k)]
        bad = [k for k in acc if not _accurate(m, k)]
        line = (f"{m['model']}: with up to {_g(m['digits_lost_max'], 2)} digits lost to "
                "cancellation, " + (", ".join(good) or "no backend") + " stay within 1e-12 "
                "of the 60-digit value at every point")
        if bad:
            line += ("; " + ", ".join(f"{k} is off by up to {_g(acc[k]['max'], 2)}"
                                      for k in bad))
        out.append(line + ".")
    return out + [""]


# -- 3. finite elements ----------------------------------------------------------------------
def _fe(fe) -> list:
    s = fe["symtmm"]
    out = ["## 3. Finite elements", "",
           (f"Model {fe['model']}, first {fe['count']} frequencies. Reference: "
            f"{fe['reference']}. FE: `symtmm.fe.fe_frequencies` (cubic Hermite, consistent "
            "mass, dense `scipy.linalg.eigh`, Rayleigh-quotient polish), timed with the BLAS "
            "threads numpy/scipy start by default and, in a child process, with one BLAS "
            f"thread ({', '.join(fe.get('blas_threads_env', []))} = 1); `seconds` is the "
            "faster of the two, each the minimum of 3 runs (one run where it takes over "
            "1 s)."), "",
           (f"symtmm, `solve(model, count={fe['count']}, digits={s['digits']})`: "
            f"{_g(s['seconds'])} s (the fastest of three runs), {s['evaluations']} evaluations, "
            f"largest error of the printed values {_g(s['max_rel_error'], 2)}. A profiled run: "
            + _profile_sentence(s["profile"]) + "."), ""]
    out += _table(["elements per beam", "seconds (default threads)", "seconds (one thread)",
                   "seconds", "max rel. error"],
                  [[r["elements_per_beam"], _g(r["seconds_default_threads"]),
                    _g(r["seconds_one_thread"]), _g(r["seconds"]), _g(r["max_rel_error"], 2)]
                   for r in fe["fe"]])
    if fe.get("fe_error_exponent") is not None:
        sizes = fe.get("fe_exponent_sizes") or []
        out.append(f"FE error against elements per beam: fitted exponent "
                   f"{fe['fe_error_exponent']:.2f} over {sizes[0]}-{sizes[-1]} elements, "
                   "where it still falls (h^4 expected).")
    b = fe["fe_best"]
    out.append(f"Smallest FE error: {_g(b['max_rel_error'], 2)} with "
               f"{b['elements_per_beam']} elements per beam ({_g(b['seconds'])} s).")
    t = fe["target"]
    out += ["", (f"**Target** — {t['text']}: {_met(t['met'])} (symtmm {_g(t['symtmm_seconds'])} "
                 f"s to 1e-12; FE fastest to 1e-6: {_g(t['fe_seconds'])} s"
                 + (f" with {t['fe_elements']} elements per beam" if t.get("fe_elements")
                    else "") + ")"), ""]
    return out


# -- 4. scaling ------------------------------------------------------------------------------
def _scaling(sc) -> list:
    out = ["## 4. Scaling", "",
           (f"Models: {sc['model']}; springs per level {sc['fixed_springs_per_level']} when "
            f"the levels vary, {sc['fixed_levels']} levels when the springs vary. Delta: the "
            f"vectorised evaluator on a batch of {sc.get('batch', '?')} points at every size "
            f"(per point) and `delta_mp` at 30 digits at one point, each the minimum of "
            f"{sc.get('repeat', '?')} timings. Full solves: first 10 frequencies, 15 digits, in "
            f"a child process, limit {sc['solve_limit_seconds']:g} s per solve."), ""]
    rows = [[r["levels"], r["springs_per_level"], r["segments"],
             r.get("distinct_segments", "–"), _g(r.get("evaluator_construction_seconds")),
             _g(r["numpy_seconds_per_point"] * 1e6),
             _g(r["mpmath30_seconds_per_evaluation"] * 1e3)]
            for r in sc["eval_levels"] + sc["eval_springs"]]
    out += ["Time per evaluation of Delta:", ""]
    out += _table(["levels", "springs/level", "segments", "distinct", "Evaluator() s",
                   "numpy us/point",
                   "mpmath 30 digits ms"], rows)
    seen, rows = set(), []
    for r in sc["solve_levels"] + sc["solve_springs"]:
        key = (r["levels"], r["springs_per_level"])
        if key in seen:
            continue
        seen.add(key)
        rows.append([r["levels"], r["springs_per_level"], r["status"], _g(r.get("seconds")),
                     r.get("evaluations", "–"), r.get("mpmath_evaluations", "–"),
                     _pct(r.get("mpmath_share")), _g(r.get("rigid_body_modes_seconds"))])
    out += ["Full solves:", ""]
    out += _table(["levels", "springs/level", "status", "seconds", "evaluations",
                   "of them mpmath", "time in mpmath", "rigid_body_modes, s"], rows)
    out += ["Fitted exponents (log-log least squares; all sizes / largest three):", ""]
    out += _table(["quantity", "all sizes", "largest three"],
                  [[k, _g(v), _g(sc.get("exponents_largest_three", {}).get(k))]
                   for k, v in sc["exponents"].items()])
    t = sc["target"]
    out += [(f"**Target** — {t['text']}: {_met(t['met'])} (numpy {_g(t['exponent_numpy'])}, "
             f"mpmath {_g(t['exponent_mpmath'])}; rounds {_band(t.get('rounds_numpy'))} and "
             f"{_band(t.get('rounds_mpmath'))})"), ""]
    return out


# -- findings ---------------------------------------------------------------------------------
def _root_search_findings(rs) -> list:
    t = rs["target"]
    out = [f"Root search: {_met(t['met'])}."]
    for x in t["results"]:
        case = next(c for c in rs["cases"] if c["name"] == x["case"])
        fails = []
        if x["ratio"] > 0.1:
            fails.append(f"{x['ratio']:.3f} of fmin1d's evaluations")
        if x["max_rel_error"] is None or x["max_rel_error"] > 1e-12:
            fails.append(f"error {_g(x['max_rel_error'], 2)}")
        if x["missed"]:
            fails.append(f"{x['missed']} missed")
        verdict = ("met (" if not fails else "missed: " + ", ".join(fails) + " (") + \
            f"evaluations {x['ratio']:.3f} of fmin1d's, error {_g(x['max_rel_error'], 2)})"
        d = case["methods"]["default"]
        out.append(f"{x['case']}: {verdict}. Wall time: default {_g(d['seconds'])} s, "
                   f"fmin1d {_g(case['methods']['fmin1d']['seconds'])} s: "
                   + _speed_phrase(x["seconds_ratio"], "fmin1d")
                   + (", although it makes far fewer evaluations, because "
                      + _why_slow(d["profile"]) if x["seconds_ratio"] > 1 else "") + ".")
    return out + [""]


def _speed_phrase(ratio: float, other: str) -> str:
    """The default search against ``other`` by the ratio of their wall times.

    Examples
    --------
    >>> _speed_phrase(2.5, "fmin1d")
    'the default search is slower in wall time than fmin1d (2.50x)'
    >>> _speed_phrase(0.96, "fmin1d")[-44:]
    '1.04x, within the noise of a shared machine)'
    """
    out = (f"the default search is {'slower' if ratio > 1 else 'faster'} in wall time than "
           f"{other} ({max(ratio, 1 / ratio):.2f}x")
    return out + (", within the noise of a shared machine)" if abs(ratio - 1) < 0.1 else ")")


def _why_slow(p) -> str:
    """Why a search with few evaluations still takes longer: its costliest routines.

    Examples
    --------
    >>> r = {"count": {"calls": 10, "seconds": 0.2, "share": 0.9},
    ...      "delta_mpmath": {"calls": 0, "seconds": 0.0, "share": 0.0}}
    >>> _why_slow({"routines": r})[:72]
    'its evaluations are expensive: 10 Wittrick-Williams counts at 20 ms each'
    """
    used = sorted((v["share"], k) for k, v in p["routines"].items() if v["calls"])
    parts = []
    for share, key in reversed(used):
        s = p["routines"][key]
        if share >= 0.1 or not parts:
            parts.append(f"{s['calls']} {_ROUTINES.get(key, key)} at "
                         f"{_g(s['seconds'] / s['calls'] * 1e3)} ms each ({_pct(share)} of its time)")
    out = ("its evaluations are expensive: " + ", ".join(parts)
           + ", while fmin1d evaluates whole grids in one vectorised call")
    if p["routines"].get("count", {}).get("share", 0) > 0.5:
        # the clusters of exact multiple roots: see symtmm.roots.undamped, step 4
        out += ("; counts dominate where roots are multiple: Delta's sign cannot tell m "
                "coincident roots apart, so each cluster is isolated by bisection on counts "
                "down to double-precision width (about 3.3 counts per digit) and then proved "
                "by two counts in high precision at the ends of a bracket of relative width "
                "10^-(D+22)")
    return out


def _evaluator_findings_text(ev) -> list:
    t = ev["target"]
    head = ev["models"][0]
    r = head["ratio_to_naive_numpy"]
    rate = head["points_per_second"]
    out = [(f"Evaluator: {_met(t['met'])} (Evaluator.delta is {_g(r['symtmm'])}x the naive "
           f"product on {head['model']}).")]
    prof = head["delta_profile"]
    shares = ", ".join(f"{name} {_pct(v['share'])}" for name, v in prof["own_time"].items())
    single = head["seconds_per_single_point_call"]
    err = head["relative_error_vs_mpmath_60"]
    qr = sum(v["share"] for name, v in prof["own_time"].items() if name.endswith(":qr"))
    out.append(
        f"Measured causes: the naive per-point product costs {_g(1e6 / rate['naive_numpy'])} us "
        f"per point, Evaluator.delta {_g(1e6 / rate['symtmm'])} us in a batch of "
        f"{prof['points']}. Own time of the functions of one such call (cProfile): {shares}"
        + (f"; {_pct(qr)} of it is the batched `np.linalg.qr` that re-orthonormalises the "
           "columns after every propagation step, the price of stability" if qr else "")
        + f". The plain vectorised product, `symtmm_plain`, is {_g(r['symtmm_plain'])}x the "
        "naive product" + (", which would meet the target" if (r["symtmm_plain"] or 0) >= 100
                           else ", short of 100x too")
        + f", but its error reaches {_g(err['symtmm_plain']['max'], 2)} at these points (up to "
        f"{_g(head['digits_lost_max'], 2)} digits cancel) where Evaluator.delta stays within "
        f"{_g(err['symtmm']['max'], 2)}: at high modes the stable evaluation is the accurate "
        "one, the plain product (and the naive one) is not.")
    c = r.get("generated_c")
    if c:
        out.append(f"The generated C (the stable algorithm too, Gram-Schmidt after every step; "
                   f"error up to {_g(err['generated_c']['max'], 2)}) takes "
                   f"{_g(1e6 / rate['generated_c'])} us per point, {_g(c)}x the naive product: "
                   + ("compiled code does reach 100x here." if c >= 100 else
                      "compiled code does not reach 100x on this model either."))
    out.append(f"A single-point call of Evaluator.delta takes {_g(single['symtmm'] * 1e3)} ms "
               f"(`symtmm_plain`: {_g(single['symtmm_plain'] * 1e3)} ms), some "
               f"{_g(single['symtmm'] * rate['symtmm'])} times its per-point cost in a batch: "
               "what the default search pays for each double-precision evaluation.")
    return out + [""]


def _fe_findings(r) -> list:
    fe = r["fe"]
    t = fe["target"]
    s = fe["symtmm"]
    p = s["profile"]
    out = [(f"Finite elements: {_met(t['met'])} (symtmm {_g(s['seconds'])} s to 1e-12 at "
           f"digits=13, error {_g(s['max_rel_error'], 2)}; the FE model reaches 1e-6 in "
           f"{_g(t['fe_seconds'])} s).")]
    if not t["met"] and t["fe_seconds"]:
        rt = p["routines"]
        outside = p["seconds"] - rt["delta_mpmath"]["seconds"]
        out.append(f"symtmm is {_g(s['seconds'] / t['fe_seconds'])}x slower. Where its time "
                   f"goes, in a profiled run of {_profile_sentence(p)}. Outside the mpmath "
                   f"evaluations that run still spends {_g(outside)} s, {_g(outside / t['fe_seconds'])}x the FE time, in "
                   "double-precision evaluations made one point per call, counts and "
                   "bookkeeping.")
    grid = _grid_bisection_ex1(r)
    if grid:
        out.append(f"Multiple precision is not what 1e-12 needs on this model: the "
                   f"grid-bisection baseline, double precision only on the stable "
                   f"Evaluator.delta, reaches {_g(grid['max_rel_error'], 2)} with "
                   f"{grid['missed']} missed ({grid['evaluations']} evaluations, "
                   f"{_g(grid['seconds'])} s, section 1).")
    rows = [x for x in fe["fe"] if x["seconds_one_thread"] is not None]
    slow = [x for x in rows if x["seconds_default_threads"] > 2 * x["seconds_one_thread"]]
    if slow:
        x = max(slow, key=lambda x: x["seconds_default_threads"] / x["seconds_one_thread"])
        out.append(f"The BLAS threads matter on this shared machine: with "
                   f"{x['elements_per_beam']} elements per beam the FE solve took "
                   f"{_g(x['seconds_default_threads'])} s with the default threads and "
                   f"{_g(x['seconds_one_thread'])} s with one.")
    return out + [""]


def _grid_bisection_ex1(r):
    for case in r.get("root_search", {}).get("cases", []):
        if case["name"].startswith("ex1"):
            return case["methods"].get("grid_bisection")
    return None


def _scaling_findings(sc) -> list:
    t = sc["target"]
    e, e3 = sc["exponents"], sc["exponents_largest_three"]
    out = [(f"Scaling: {_met(t['met'])} (springs exponent over the largest three sizes, "
           f"median over rounds: numpy {_g(t['exponent_numpy'])}, mpmath "
           f"{_g(t['exponent_mpmath'])}; fitted to the minima {_g(t.get('minima_numpy'))} and "
           f"{_g(t.get('minima_mpmath'))}; over all sizes {_g(e['eval_numpy_vs_springs'])} and "
           f"{_g(e['eval_mpmath_vs_springs'])}).")]
    out += _springs_noise(sc)
    out.append(f"In the levels the cost per evaluation grows with exponent "
               f"{_g(e3['eval_numpy_vs_levels'])} (numpy) and {_g(e3['eval_mpmath_vs_levels'])}"
               " (mpmath) over the largest three sizes: every spring position cuts every level, "
               "so n levels carry 2n columns through n (n s + 1) segments (n^3 s for the "
               "plain product, plus n^4 s for the stable evaluator's QR steps in the limit).")
    if (t["exponent_numpy"] or 0) < 0.85:
        big = sc["eval_springs"][-1]
        out.append("The numpy exponent below 1 is not an artefact of the batch, which is the "
                   "same at every size: segments of equal constants share one matrix per call "
                   f"(at {big['springs_per_level']} springs per level, "
                   f"{big.get('distinct_segments', '?')} distinct of {big['segments']}: spring "
                   "positions on a 1/1000 grid repeat lengths), so what grows is the "
                   "propagation and re-orthonormalisation per interval, beside fixed costs "
                   "per call.")
    solves = [x for x in sc["solve_levels"] + sc["solve_springs"] if x.get("seconds")]
    if solves:
        share = statistics.median(x["mpmath_share"] for x in solves)
        evals = statistics.median(x["evaluations"] for x in solves)
        n_mp = statistics.median(x["mpmath_evaluations"] for x in solves)
        top = max(sc["eval_levels"], key=lambda x: x["levels"])
        t_mp = top["mpmath30_seconds_per_evaluation"]
        out.append(f"A full solve makes about {_g(evals)} evaluations whatever the size "
                   f"(median), {_g(n_mp)} of them in mpmath, which take a median {_pct(share)} "
                   f"of its time; one mpmath evaluation at {top['levels']} levels takes "
                   f"{_g(t_mp)} s, so a solve at that size would spend about "
                   f"{_g(n_mp * t_mp)} s in mpmath alone.")
    late = [x for x in sc["solve_levels"] + sc["solve_springs"] if not x.get("seconds")]
    if late:
        out.append("Not finished: " + ", ".join(f"{x['levels']} levels x "
                                                f"{x['springs_per_level']} springs "
                                                f"({x['status']})" for x in late) + ".")
    return out + [""]


def _band(values) -> str:
    """``lo-hi`` of the exponents fitted to single rounds.

    Examples
    --------
    >>> _band([1.2, 0.9, 1.05]), _band([])
    ('0.9-1.2', '–')
    """
    values = [v for v in values or [] if v is not None]
    return f"{_g(min(values))}-{_g(max(values))}" if values else "–"


def _springs_noise(sc) -> list:
    """The springs exponents of single rounds and the cost per segment, smallest to
    largest size: whether a verdict near the threshold is the machine's noise."""
    t = sc["target"]
    rows = sc["eval_springs"]
    lo, hi = rows[0], rows[-1]
    line = (f"Fitted to single rounds of timings (each round times every size once, within "
            f"about a second) the exponents span {_band(t.get('rounds_numpy'))} (numpy) and "
            f"{_band(t.get('rounds_mpmath'))} (mpmath): the noise of this machine. Per segment, from {lo['springs_per_level']} to "
            f"{hi['springs_per_level']} springs per level: numpy "
            f"{_g(lo['numpy_seconds_per_point'] / lo['segments'] * 1e6)} -> "
            f"{_g(hi['numpy_seconds_per_point'] / hi['segments'] * 1e6)} us per point, mpmath "
            f"{_g(lo['mpmath30_seconds_per_evaluation'] / lo['segments'] * 1e3)} -> "
            f"{_g(hi['mpmath30_seconds_per_evaluation'] / hi['segments'] * 1e3)} ms.")
    rounds = [v for v in (t.get("rounds_numpy") or []) + (t.get("rounds_mpmath") or [])
              if v is not None]
    if not t["met"] and rounds and min(rounds) <= 1.15:
        line += (" Some rounds stay within 1.15: the miss may be the timing noise of the "
                 "shared machine rather than a super-linear cost.")
    elif not t["met"]:
        line += " Every round exceeds 1.15: the cost per segment itself grows."
    return [line]


def _findings(r) -> list:
    out = ["## Targets: met or missed, and why", "",
           ("Generated from this run's numbers (timings, accuracies and the profiles gathered "
           "in the run)."), ""]
    if "root_search" in r:
        out += _root_search_findings(r["root_search"])
    if "evaluator" in r:
        out += _evaluator_findings_text(r["evaluator"])
    if "fe" in r:
        out += _fe_findings(r)
    if "scaling" in r:
        out += _scaling_findings(r["scaling"])
    return out


def render(r: dict) -> str:
    out = ["# Benchmarks", "",
           "symtmm against the alternatives a user would pick instead: the paper's grid "
           "searches (`fmin1d`, `fmin2d`), a sign-change grid with bisection, cxroots, a "
           "naive numpy transfer-matrix product, mpmath, the generated C code and a "
           "cubic-Hermite finite-element model. Generated by `benchmarks/run.py`"
           + (" (quick run: small sizes only)" if r.get("quick") else "") + ".", ""]
    out += ["## How to run", "",
            "```",
            "python benchmarks/run.py -o docs/benchmarks.md   # full run (large sizes)",
            "python benchmarks/run.py --quick                 # small sizes, under a minute",
            "python benchmarks/run.py --json > run.json       # the raw numbers",
            "python benchmarks/run.py --from-json run.json -o docs/benchmarks.md",
            "python benchmarks/run.py --sections evaluator    # one section",
            "```", "",
            ("cxroots is optional (`pip install cxroots`, or the `bench` extra); without it its rows read "
             "\"not installed\". The generated C needs gcc. The time each section took is in "
             "the machine section below."), ""]
    out += _machine(r)
    targets = r.get("targets", {})
    if targets:
        out += ["## Targets", ""]
        out += _table(["section", "target"], [[k, _met(v)] for k, v in targets.items()])
        out += _findings(r)
    if "root_search" in r:
        out += _root_search(r["root_search"])
    if "evaluator" in r:
        out += _evaluator(r["evaluator"])
    if "fe" in r:
        out += _fe(r["fe"])
    if "scaling" in r:
        out += _scaling(r["scaling"])
    return "\n".join(out)
