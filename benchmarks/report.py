"""Markdown report of a benchmark run (the dict :func:`benchmarks.run.run` returns).

Every statement about a target, met or missed, and every explanation of a
miss is generated from the run's own numbers (its timings, accuracies and
the profiles the sections gather), so the text cannot go stale against the
tables it sits beside.
"""

from __future__ import annotations

__all__ = ["render", "TARGETS"]

#: Section -> the target it carries, in the order of the issue.
TARGETS = {
    "fe": "verified 15-digit solve / sparse FE at 1e-6, at most 1",
    "scaling": "cost per evaluation against size, exponent at most 1.2 at 15 and 50 digits",
    "precision": "30 and 50 digits at most 2x the 15-digit solve",
    "root_search": "damped example 4 faster than fMin2D with at most 1/10 of its evaluations",
    "sweep": "51-step sweep of example 1 faster than 51 sparse FE solves at 1e-6",
    "evaluator": "batched double Delta at most 5x its transcendental functions",
}


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


def _ms(seconds) -> str:
    """Seconds as milliseconds for prose.

    Examples
    --------
    >>> _ms(0.01234), _ms(2.5)
    ('12.3 ms', '2.5e+03 ms')
    """
    return f"{_g(seconds * 1e3)} ms"


def _table(header, rows) -> list:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join("---" for _ in header) + "|"]
    out += ["| " + " | ".join(str(c) for c in row) + " |" for row in rows]
    return out + [""]


def _met(flag) -> str:
    return "**met**" if flag else "**missed**"


# -- profiles ----------------------------------------------------------------------------------
def _routine_text(label: str) -> str:
    from .profiling import ROUTINE_TEXT
    return ROUTINE_TEXT.get(label, label)


def _profile_sentence(p) -> str:
    """Where a profiled call spent its time, largest share first.

    Examples
    --------
    >>> p = {"seconds": 0.2, "other_seconds": 0.02, "routines": {
    ...     "factor_ball": {"seconds": 0.12, "calls": 4, "points": 40, "share": 0.6},
    ...     "plan": {"seconds": 0.06, "calls": 2, "points": 2, "share": 0.3}}}
    >>> _profile_sentence(p)[:86]
    '0.2 s: 60 % in ball-arithmetic factorizations (the proofs) (4 calls, 40 points, 3 ms p'
    """
    parts = []
    for label, s in sorted(p["routines"].items(), key=lambda kv: -kv[1]["seconds"]):
        if not s["calls"]:
            continue
        if s["points"] != s["calls"]:
            per = (f"{s['calls']} calls, {s['points']} points, "
                   f"{_ms(s['seconds'] / s['points'])} per point")
        elif s["calls"] > 1:
            per = f"{s['calls']} calls, {_ms(s['seconds'] / s['calls'])} each"
        else:
            per = f"one call, {_ms(s['seconds'])}"
        parts.append(f"{_pct(s['share'])} in {_routine_text(label)} ({per})")
    return (f"{_g(p['seconds'])} s: " + ", ".join(parts)
            + f", {_pct(p['other_seconds'] / p['seconds'])} elsewhere (search logic, "
            "bookkeeping)")


def _largest(p, n: int = 2) -> list:
    """The ``n`` routines with the most own time: ``(label, stat)``."""
    return sorted(p["routines"].items(), key=lambda kv: -kv[1]["seconds"])[:n]


# -- machine ---------------------------------------------------------------------------------
def _machine(r) -> list:
    m = r["machine"]
    pk = ", ".join(f"{k} {v}" for k, v in m["packages"].items() if v)
    missing = [k for k, v in m["packages"].items() if not v]
    return ["## Machine and commands", "",
            f"* {m['cpu']}, {m['cores']} cores, {m['platform']}, Python {m['python']}"
            + (f"; symtmm's large compiled batches on {m['threads']} threads"
               if m.get("threads", 1) > 1 else ""),
            f"* {pk}" + (f" (not installed: {', '.join(missing)})" if missing else "")
            + f"; mpmath backend `{m.get('mpmath_backend', '?')}`; proofs in "
            f"{'Arb balls (python-flint)' if m.get('certified') else 'mpmath at two precisions'}"
            f"; {m['gcc'] or 'no C compiler'}",
            f"* commit {m['commit']}, {m['date']}",
            (f"* load average (1, 5, 15 min) before: {r['load_before']}, after: "
             f"{r['load_after']}. Other processes may run beside the benchmark: every time is "
             "the best of several runs (other work only ever adds time)"),
            f"* command: `{r['command']}`",
            "* seconds per section: " + ", ".join(f"{k} {v}" for k, v in r["seconds"].items()),
            ""]


# -- the targets table -------------------------------------------------------------------------
def _ratios(d: dict) -> str:
    return ", ".join(f"{k} {_g(v)}" for k, v in d.items())


def _measured(name, sec) -> str:
    t = sec["target"]
    if name == "fe":
        return "symtmm / FE: " + _ratios(t["ratios"])
    if name == "scaling":
        return (f"exponent {_g(t['exponent_15'])} (15 digits), {_g(t['exponent_50'])} "
                f"(50 digits)")
    if name == "precision":
        return "; ".join(f"{m}: " + ", ".join(f"{d} digits {_g(v)}x" for d, v in r.items())
                         for m, r in t["ratios"].items())
    if name == "root_search":
        return (f"time {_g(t['default_seconds'])} s / {_g(t['fmin2d_seconds'])} s = "
                f"{_g(t['seconds_ratio'])}; evaluations {t['default_evaluations']} / "
                f"{t['fmin2d_evaluations']} = {_g(t['evaluation_ratio'])}")
    if name == "sweep":
        return (f"{_g(sec['symtmm']['seconds'])} s / {_g(sec['fe']['seconds'])} s = "
                f"{_g(t['ratio'])}")
    if name == "evaluator":
        return "Delta / transcendentals: " + _ratios(t["ratios"])
    return "–"


def _targets(r) -> list:
    rows = [[i, TARGETS[name], f"failed: {r[name]['error']}" if "error" in r[name]
             else _measured(name, r[name]), _met(r[name]["target"]["met"])]
            for i, name in enumerate(TARGETS, 1) if name in r]
    out = ["## Targets", ""] + (_table(["#", "target", "measured", "verdict"], rows) if rows
                                else ["No target was measured in this run.", ""])
    if "ordinary" in r:
        o = r["ordinary"]
        out += [("Reported beside them (section 7, not a numbered target): the ordinary models "
                 "of the reliability issue against a measure like target 1's, "
                 + (f"failed: {o['error']}" if "error" in o else
                    "symtmm / FE: " + ", ".join(f"{k} {_g(v) if v is not None else 'failed'}"
                                                for k, v in o["ratios"].items())
                    + f" ({'all within' if o['within'] else 'not all within'} 1)") + "."), ""]
    for name, number, what in (
            ("shapes", 8, "the first 10 mode shapes, symtmm's `modes` / the FE's eigenvectors"),
            ("high_modes", 9, "a cantilever's first 100 and 300 frequencies, symtmm / FE")):
        if name in r:
            sec = r[name]
            out += [(f"Reported beside them (section {number}): {what}, "
                     + (f"failed: {sec['error']}" if "error" in sec else
                        ", ".join(f"{k} {_g(v)}" for k, v in sec["ratios"].items())) + "."), ""]
    return out


# -- why -----------------------------------------------------------------------------------------
def _why_fe(fe) -> list:
    out = []
    for c in fe["cases"]:
        s, f = c["symtmm"], c["fe"]
        verdict = "within" if c["ratio"] <= 1 else "over"
        line = (f"{c['name']}: symtmm {_g(s['seconds'])} s, FE {_g(f['seconds'])} s "
                f"({f['elements_per_beam']} elements per beam, {f['dofs']} dofs), ratio "
                f"{_g(c['ratio'])}, {verdict} the target"
                + ("" if c["counted"] else " (reported, not part of the target)") + ".")
        if c["ratio"] > 1:
            p = s["profile"]
            big = [f"{_routine_text(k)} alone {_g(v['seconds'])} s ({_g(v['seconds'] / f['seconds'])}x "
                   "the whole FE solve)" for k, v in _largest(p)]
            line += " Profiled solve, " + _profile_sentence(p) + ". " + "; ".join(big) + "."
        out.append(line)
    return out


def _why_scaling(sc) -> list:
    rows = sc["rows"]
    lo, hi = rows[0], rows[-1]
    t = sc["target"]
    out = [(f"From {lo['levels']} to {hi['levels']} levels the size (segments x levels) grows "
            f"{_g(hi['size'] / lo['size'])}x, the compiled kernel's freedoms "
            f"{_g(hi['freedoms'] / lo['freedoms'])}x (half-bandwidth {lo['band']} to "
            f"{hi['band']}), the time per evaluation {_g(hi['double_seconds'] / lo['double_seconds'])}x "
            f"in double precision and {_g(hi['high_seconds'] / lo['high_seconds'])}x at "
            f"{sc['high_digits']} digits.")]
    e = sc["exponents"]
    out.append("Exponents against the other measures of size: levels "
               f"{_g(e['levels']['double'])} / {_g(e['levels']['high'])}, segments cut per beam "
               f"{_g(e['own_segments']['double'])} / {_g(e['own_segments']['high'])}, kernel "
               f"freedoms {_g(e['freedoms']['double'])} / {_g(e['freedoms']['high'])} (double / "
               f"{sc['high_digits']} digits).")
    for name, fam in sc.get("families", {}).items():
        fr, fe_ = fam["rows"], fam["exponents"]
        tail = fe_["levels, largest three sizes"]
        out.append(f"With {name} (reported): exponent against levels "
                   f"{_g(fe_['levels']['double'])} / {_g(fe_['levels']['high'])} from "
                   f"{fr[0]['levels']} to {fr[-1]['levels']} levels (half-bandwidth "
                   f"{fr[0]['band']} to {fr[-1]['band']}), {_g(tail['double'])} / "
                   f"{_g(tail['high'])} over the largest three sizes ({fr[-3]['levels']} to "
                   f"{fr[-1]['levels']} levels).")
    if not t["met"]:
        per = [(r["levels"], r["double_seconds"] / r["freedoms"], r["high_seconds"] / r["freedoms"])
               for r in rows]
        out.append("Cost per freedom and point, smallest to largest model: "
                   + ", ".join(f"{n} levels {_g(d * 1e6)} us / {_g(h * 1e3)} ms"
                               for n, d, h in per) + ".")
    return out


def _why_precision(pr) -> list:
    out = []
    for name, c in pr["cases"].items():
        base = c["profiles"]["15"]
        out.append(f"{name}: {_g(c['seconds']['15'])} s at 15 digits; "
                   + ", ".join(f"{_g(c['ratio'][d])}x at {d}" for d in c["ratio"])
                   + "; evaluations " + " / ".join(str(v) for v in c["evaluations"].values())
                   + ".")
        for d, ratio in c["ratio"].items():
            if ratio <= 2:
                continue
            p = c["profiles"][d]
            grew = []
            for label, s in p["routines"].items():
                b = base["routines"].get(label, dict(seconds=0.0, points=0))
                if s["seconds"] - b["seconds"] > 0.1 * (p["seconds"] - base["seconds"]):
                    grew.append(f"{_routine_text(label)} {_g(b['seconds'])} s over {b['points']} "
                                f"points at 15 digits, {_g(s['seconds'])} s over {s['points']} "
                                f"at {d}")
            out.append(f"{name} at {d} digits is over 2x; what grew (profiled): "
                       + ("; ".join(grew) or "no single routine") + ".")
    return out


def _why_root_search(rs) -> list:
    t = rs["target"]
    case = next(c for c in rs["cases"] if c["name"] == t["case"])
    d = case["methods"]["default"]
    out = [(f"Example 4, the paper's rectangle: default {_g(t['default_seconds'])} s and "
            f"{t['default_evaluations']} evaluations, fMin2D {_g(t['fmin2d_seconds'])} s and "
            f"{t['fmin2d_evaluations']} evaluations (fMin2D misses "
            f"{case['methods']['fmin2d']['missed']}, the default {t['missed']}).")]
    if d["status"] != "ok":
        out.append(f"The default search stopped: {d['status']}.")
    elif t["seconds_ratio"] >= 1:
        per_f = t["fmin2d_seconds"] / max(t["fmin2d_evaluations"], 1)
        dd = d["profile"]["routines"].get("complex_factor_double")
        per_d = (f"; the default's double-precision Delta costs {_ms(dd['seconds'] / dd['points'])} "
                 "per point") if dd and dd["points"] else ""
        out.append(f"fMin2D evaluates whole grids per vectorised call, {_ms(per_f)} per point "
                   f"all included{per_d}. The default search, "
                   + _profile_sentence(d["profile"]) + ".")
    if t["evaluation_ratio"] > 0.1:
        line = f"Evaluations: {_g(t['evaluation_ratio'])} of fMin2D's, over 1/10"
        if "profile" in d:
            pts = [(v["points"], k) for k, v in d["profile"]["routines"].items()
                   if v["points"] != v["calls"]]
            line += (f"; of the default's {t['default_evaluations']}, "
                     + ", ".join(f"{n} in {_routine_text(k)}" for n, k in sorted(pts, reverse=True)))
        out.append(line + ".")
    return out


def _why_sweep(sw) -> list:
    s, f = sw["symtmm"], sw["fe"]
    steps = sw["steps"]
    out = [(f"symtmm {_g(s['seconds'])} s for {steps} steps ({_g(s['seconds'] / steps)} s per "
            f"step at {sw['digits']} digits, mode shapes included for the branch tracking), the "
            f"FE model {_g(f['seconds'])} s ({_ms(f['seconds'] / steps)} per step, "
            f"{f['elements_per_beam']} elements per beam).")]
    if not sw["target"]["met"]:
        big = [f"{_routine_text(k)} alone {_g(v['seconds'])} s ({_g(v['seconds'] / f['seconds'])}x "
               "the FE loop)" for k, v in _largest(s["profile"])]
        out.append("Profiled sweep, " + _profile_sentence(s["profile"]) + ". "
                   + "; ".join(big) + ".")
    return out


def _why_evaluator(ev) -> list:
    out = []
    for name, m in ev["models"].items():
        per = m["seconds_per_point"]
        top = ", ".join(f"{k} {_pct(v['share'])}" for k, v in m["profile"]["own_time"].items())
        floor = ""
        if per.get("elimination") is not None:
            floor = (f". The band elimination alone costs {_g(per['elimination'] * 1e6)} us, "
                     f"{_g(m['elimination_to_transcendental'])}x the transcendental functions"
                     + (" (the target lies below what the elimination alone costs)"
                        if m["elimination_to_transcendental"] > 5 else "")
                     + f"; Delta / (transcendental + elimination) {_g(m['ratio_to_floor'])}")
        threads = (f" ({_g(per['delta_threads'] * 1e6)} us on {m['threads']} threads)"
                   if per.get("delta_threads") is not None and m.get("threads", 1) > 1 else "")
        out.append(f"{name}: {m['kinds']} distinct segment kinds ({m['pieces']} pieces, "
                   f"{m['freedoms']} freedoms, half-bandwidth {m['band']}): Delta "
                   f"{_g(per['delta'] * 1e6)} us per point on one thread{threads}, its "
                   "transcendental functions "
                   f"{_g(per['transcendental'] * 1e6)} us, ratio {_g(m['ratio_to_transcendental'])}"
                   + floor
                   + (". Own time in batch calls (cProfile): " + top if m["ratio_to_transcendental"] > 5
                      else "") + ".")
    return out


_WHY = {"fe": _why_fe, "scaling": _why_scaling, "precision": _why_precision,
        "root_search": _why_root_search, "sweep": _why_sweep, "evaluator": _why_evaluator}


def _findings(r) -> list:
    if not any(name in r for name in TARGETS):
        return []
    out = ["## Met or missed, and why", "",
           ("Generated from this run's numbers: its timings and the profiles it gathered "
            "(own time of the library's routines in one more, profiled run)."), ""]
    for i, name in enumerate(TARGETS, 1):
        if name not in r:
            continue
        out += [f"**{i}. {TARGETS[name]}** — {_met(r[name]['target']['met'])}", ""]
        if "error" in r[name]:
            out += [f"* The section stopped with {r[name]['error']}:", "", "```",
                    *r[name]["trace"], "```", ""]
            continue
        out += [f"* {line}" for line in _WHY[name](r[name])] + [""]
    return out


# -- sections --------------------------------------------------------------------------------
def _fe(fe) -> list:
    out = ["## 1. Verified solve against a sparse finite-element model", "",
           (f"symtmm: `solve(model, count={fe['count']}, digits={fe['digits']})`, every printed "
            f"digit proved, the best of {fe['repeat']} runs (2 at 50 levels). FE: the model a "
            "competent user writes (benchmarks/sparse_fe.py): scipy.sparse assembly of "
            "cubic-Hermite Euler-Bernoulli elements with consistent mass, boundary conditions "
            "by removing dofs, joints by sharing them, springs added into K, "
            "`eigsh(K, k=10, M=M, sigma=-1, which='LM')`, on the coarsest uniform mesh "
            f"(elements per beam) within {fe['tolerance']:g} of the reference; its time is "
            "mesh + assembly + eigsh, the best of the runs with the default BLAS threads "
            "(one after each of symtmm's solves, then "
            f"{fe['repeat']} more: both sides of the ratio in the same minutes) and of "
            f"{fe['repeat']} with one ({', '.join(fe['blas_threads_env'])} = 1, child "
            "process), the faster."), ""]
    rows = []
    for c in fe["cases"]:
        s, f = c["symtmm"], c["fe"]
        rows.append([c["title"], c["beams"], f["elements_per_beam"], f["dofs"],
                     _g(f["max_rel_error"], 2), _g(f["seconds_default_threads"]),
                     _g(f["seconds_one_thread"]), _g(s["seconds"]), s["evaluations"],
                     _g(s["max_rel_error"], 2), f"**{_g(c['ratio'])}**"])
    out += _table(["model", "beams", "FE elements/beam", "FE dofs", "FE error",
                   "FE s (default threads)", "FE s (1 thread)", "symtmm s", "evaluations",
                   "symtmm error", "symtmm / FE"], rows)
    out.append("Errors: largest relative error of the first 10 frequencies against the "
               "reference (symtmm: its printed 15-digit values). References:")
    out.append("")
    out += [f"* {c['name']}: {c['reference']['method']} ({_g(c['reference']['seconds'])} s)."
            for c in fe["cases"]]
    out += ["", "Meshes tried (elements per beam: error):", ""]
    out += [f"* {c['name']}: " + ", ".join(f"{t['elements_per_beam']}: "
                                           f"{_g(t['max_rel_error'], 2)}" for t in c["fe"]["tried"])
            for c in fe["cases"]]
    return out + [""]


def _scaling(sc) -> list:
    out = ["## 2. Cost per evaluation against model size", "",
           (f"Models {sc['model']}, frequencies up to {sc['omega_max']:g} rad/s. Size: segments "
            "x levels (the spring positions cut the span, every level runs through every "
            "segment). Kernel: pieces, distinct segment kinds, freedoms and half-bandwidth of "
            f"the compiled dynamic stiffness. Per evaluation: double precision in batches of "
            f"{sc['batch']} frequencies, {sc['high_digits']} digits ({sc['high_arithmetic']}) "
            f"in batches of {sc['high_batch']}, per point, each the best of {sc['repeat']} "
            "timings taken in rounds over all sizes."), ""]
    rows = [[r["levels"], r["segments"], r["size"], r["own_segments"], r["pieces"], r["kinds"],
             r["freedoms"], r["band"], _g(r["prepare_seconds"]), _g(r["double_seconds"] * 1e6),
             _g(r["high_seconds"] * 1e3)] for r in sc["rows"]]
    out += _table(["levels", "segments", "size", "segments cut per beam", "pieces", "kinds",
                   "freedoms", "band", "plan s", "15 digits us", f"{sc['high_digits']} digits ms"],
                  rows)
    out += _table(["size measure", "exponent, 15 digits", f"exponent, {sc['high_digits']} digits"],
                  [[k, _g(v["double"]), _g(v["high"])] for k, v in sc["exponents"].items()])
    for name, fam in sc.get("families", {}).items():
        out += [(f"The same chains with {name} ({fam['model']}; reported, not part of the "
                 "target):"), ""]
        rows = [[r["levels"], r["pieces"], r["kinds"], r["freedoms"], r["band"],
                 _g(r["prepare_seconds"]), _g(r["double_seconds"] * 1e6),
                 _g(r["high_seconds"] * 1e3)] for r in fam["rows"]]
        out += _table(["levels", "pieces", "kinds", "freedoms", "band", "plan s",
                       "15 digits us", f"{sc['high_digits']} digits ms"], rows)
        out += _table(["size measure", "exponent, 15 digits",
                       f"exponent, {sc['high_digits']} digits"],
                      [[k, _g(v["double"]), _g(v["high"])] for k, v in fam["exponents"].items()])
    return out


def _precision(pr) -> list:
    out = ["## 3. The cost of more digits", "",
           (f"`solve(model, count={pr['count']}, digits=D)`, the best of {pr['repeat']} rounds "
            "(each round solves at every D once)."), ""]
    ds = [str(d) for d in pr["digits"]]
    rows = [[name] + [_g(c["seconds"][d]) for d in ds] + [c["evaluations"][d] for d in ds]
            + [f"{_g(c['ratio'][d])}x" for d in ds[1:]] for name, c in pr["cases"].items()]
    out += _table(["model"] + [f"{d} digits s" for d in ds] + [f"{d} digits evaluations"
                                                                for d in ds]
                  + [f"{d} / 15" for d in ds[1:]], rows)
    for name, c in pr["cases"].items():
        out.append(f"{name}, profiled at " + "; at ".join(
            f"{d} digits " + _profile_sentence(c["profiles"][d]) for d in ds) + ".")
        out.append("")
    return out


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
        key = f"evaluation_ratio_default_over_{other}"
        if key in case:
            o = case["methods"][other]
            out.append(f"Default / {other}: evaluations {case[key]:.3f}, wall time "
                       f"{_g(d['seconds'] / max(o['seconds'], 1e-9))}.")
    if "profile" in d:
        out.append("Default search, " + _profile_sentence(d["profile"]) + ".")
    proved = case["methods"].get("default, count proved")
    if proved and proved.get("status") == "ok":
        note = next((n for n in proved.get("notes", ()) if "count in the search region" in n),
                    "no note on the count")
        out.append(f"With the count proved (`prove_count`, `solve --certified`): "
                   f"{_g(proved['seconds'])} s, {_g(proved['seconds'] / max(d['seconds'], 1e-9))}"
                   f" times the default search's time, {proved['evaluations']} evaluations; "
                   f"{note}.")
    if "reference_check" in case:
        c = case["reference_check"]
        out.append(f"Reference cross-checked by {c['method']}: largest relative "
                   f"difference {_g(c['max_rel_difference'], 2)}, {c['missed']} missed.")
    cx = _cxroots_sentence(case["methods"].get("cxroots"))
    if cx:
        out.append(cx)
    return out + [""]


def _root_search(rs) -> list:
    out = ["## 4. Root search", "",
           ("Evaluations: one per point at which Delta, R or an eigenvalue count is evaluated "
            "(double or multiple precision alike). Error: the largest |found - reference| / "
            "|reference| over the reference eigenvalues that were found; missed: reference "
            "eigenvalues (with multiplicity) no found value matches within 1e-3 relative; "
            "spurious: found values that match none. `digits`: what the method reports as "
            "correct. The paper's rectangle of example 4 carries the target; the undamped "
            "cases and the small rectangle (with cxroots) show the same searches elsewhere."),
           ""]
    for case in rs["cases"]:
        out += _case(case)
    return out


def _sweep(sw) -> list:
    s, f, ref = sw["symtmm"], sw["fe"], sw["reference"]
    out = ["## 5. A sweep: the paper's figure 10", "",
           (f"Example 1, `{sw['parameter']}` from {sw['start']} to {sw['stop']} in "
            f"{sw['steps']} steps, first {sw['count']} frequencies: `symtmm.sweep.sweep` with "
            f"its defaults ({sw['digits']} digits, branches tracked by mode shapes), jobs=1, "
            f"{_g(s['seconds'])} s (best of four runs in the full benchmark, the first profiled). "
            "FE: one solve per "
            f"step on the coarsest mesh within 1e-6 at every step, {f['elements_per_beam']} "
            f"elements per beam: {_g(f['seconds_default_threads'])} s (default BLAS threads), "
            f"{_g(f['seconds_one_thread'])} s (one thread), best of 3 loops before and one "
            "after each sweep (default threads)."), "",
           (f"Reference at each step: the {ref['exact']}; where roots are multiple or too close "
            f"for that (x1 = {', '.join(ref['extrapolated_at']) or 'none'}) the "
            f"{ref['extrapolated']}, which differs from the exact values by at most "
            f"{_g(ref['extrapolated_error'], 2)} at the other steps. The symtmm sweep's "
            f"values differ from the reference by at most "
            f"{_g(s['max_rel_difference_from_reference'], 2)} over all steps."),
           "", "Meshes tried (elements per beam: worst error over the steps): "
           + ", ".join(f"{t['elements_per_beam']}: {_g(t['max_rel_error'], 2)}"
                       for t in f["tried"]) + ".", ""]
    return out


def _evaluator(ev) -> list:
    threads = next(iter(ev["models"].values())).get("threads", 1)
    out = ["## 6. The batched double-precision Delta", "",
           (f"A batch of {ev['batch']} frequencies in [1, {ev['omega_max']:g}] rad/s. `Delta`: "
            "the kernel's double-precision Delta and count (one factorization), on one thread "
            "as numpy's transcendental functions run (the ratios; `Delta us, "
            f"{threads} threads`: the batch in parts on the machine's threads). "
            "`transcendental`: numpy cos, cosh, sin, sinh on one argument per distinct segment "
            "kind and point. `elimination`: the kernel's band elimination alone (its compiled "
            "loop) on K at the same points; `floor`: transcendental + elimination, the two "
            "parts no evaluation of this Delta avoids. `naive numpy`: per point, the stacked "
            "transfer matrices multiplied "
            "in a Python loop (benchmarks/baselines.py). `generated C`: `symtmm codegen --lang "
            "c`, gcc -O2, the loop over points timed inside C. Microseconds per point, best of "
            f"several runs. Accuracy: |log|Delta| - log|Delta_50||, median / max over "
            f"{ev['accuracy_points']} points."), ""]
    rows = []
    for name, m in ev["models"].items():
        per = m["seconds_per_point"]
        rows.append([name, m["kinds"], m["pieces"], m["freedoms"], m["band"]]
                    + [_g(per[k] * 1e6 if per.get(k) is not None else None)
                       for k in ("delta", "delta_threads", "transcendental", "elimination",
                                 "naive_numpy", "generated_c")]
                    + [f"**{_g(m['ratio_to_transcendental'])}**",
                       _g(m.get("ratio_to_floor")),
                       (f"{_g(m['log_delta_error']['median'], 2)} / "
                        f"{_g(m['log_delta_error']['max'], 2)}")])
    out += _table(["model", "kinds", "pieces", "freedoms", "band", "Delta us",
                   f"Delta us, {threads} threads", "transcendental us", "elimination us",
                   "naive numpy us", "generated C us",
                   "Delta / transcendental", "Delta / floor", "accuracy"], rows)
    return out


def _ordinary_row(c) -> list:
    if "error" in c:
        return [c["name"], f"failed: {c['error']}"] + ["–"] * 11
    s, f = c["symtmm"], c["fe"]
    request = ", ".join(f"{k} {v:g}" if isinstance(v, float) else f"{k} {v}"
                        for k, v in c["request"].items())
    symtmm = [f"failed: {s['error']}", "–", "–"] if "error" in s else \
        [_g(s["seconds"]), s["evaluations"], _g(s["max_rel_error"], 2)]
    return ([c["name"], request, f["elements_per_beam"], f["dofs"],
             _g(f["max_rel_error"], 2) + ("" if f["within_tolerance"] else " (!)"),
             _g(f.get("seconds_default_threads", f["seconds"])),
             _g(f.get("seconds_one_thread")), _g(f["solver_seconds"])] + symtmm
            + [_g(c["reference"]["max_rel_error"], 2),
               "–" if c["ratio"] is None else f"**{_g(c['ratio'])}**"])


def _ordinary_notes(c, tolerance) -> list:
    """What the table leaves out: the model, its reference, the FE's mesh search and
    ``k``, symtmm's failure or where its time went."""
    if "error" in c:
        return [f"{c['name']} ({c['title']}): the case stopped with {c['error']}."]
    s, f, ref = c["symtmm"], c["fe"], c["reference"]
    out = [(f"{c['name']}: {c['title']}. Reference: {ref['method']} "
            f"({_g(ref['seconds'])} s), estimated relative error "
            f"{_g(ref['max_rel_error'], 2)}.")]
    if "fe_check" in ref:
        chk = ref["fe_check"]
        out[-1] += (f" The FE reference of the same kind ({chk['method']}) differs from the "
                    f"published values by at most {_g(chk['max_rel_error'], 2)} "
                    f"({chk['missed']} missed, {chk['spurious']} spurious).")
    if not f["within_tolerance"]:
        out.append(f"{c['name']}: the FE never comes within {tolerance:g}: {f['note']}; it is "
                   f"timed on the mesh of its smallest error ({f['elements_per_beam']} "
                   "elements per beam), coarser than one at the tolerance would be: this "
                   "favours the FE.")
    if c["damped"]:
        out.append(f"{c['name']}: region 0 <= Im lam <= {_g(c['region']['omega_max'])}, "
                   f"{_g(-c['region']['sigma_max'])} <= Re lam <= 0: {len(ref['values'])} "
                   f"eigenvalues with Im lam >= 0; FE `eigs` with k = {f['k']} "
                   f"({f['found']} found in the region, {f['missed']} missed, "
                   f"{f['spurious']} spurious); with k = {f['covering_k']}, whose disk "
                   "around the shift reaches the region's far corner (what a user needs to "
                   f"be sure of the region), {_g(f['covering_seconds'])} s.")
    if "error" in s:
        out.append(f"{c['name']}: symtmm failed: {s['error']} (after {_g(s['seconds'])} s).")
    elif "profile" in s and c["ratio"] > 1:
        out.append(f"{c['name']}: over 1; profiled solve, " + _profile_sentence(s["profile"])
                   + ".")
    return out


def _ordinary(o) -> list:
    out = ["## 7. Ordinary models (reported beside the targets)", "",
           ("The ordinary models of the reliability issue, which it asks to solve within "
            "the speed target of the kernel issue (symtmm / sparse FE at "
            f"{o['tolerance']:g}, at most 1), measured as section 1 measures but for two "
            "things, both in the FE's favour: its assembly is not timed, and it may keep "
            f"{o.get('k_margin', 0)} eigenvalues more than the region holds. symtmm: "
            f"`solve(model, count={o['count']}, digits={o['digits']})` undamped, "
            f"`solve(model, omega_max=W, digits={o['damped_digits']})` damped (the region "
            "0 <= Im lam <= W, -S <= Re lam <= 0, S the request's `sigma_max`, by default "
            f"2 W), the best of {o['repeat']} runs, each of a new model object with no plan "
            f"kept (`from_scratch`); a solve stops as failed after {_g(o['time_limit'])} s. FE "
            "(benchmarks/ordinary.py): symtmm/fe.py's matrices (it shares no code with the "
            "solver; Euler-Bernoulli, Rayleigh and shear-flexible elements, axial force) on "
            "the coarsest uniform mesh within the tolerance, dashpots added as a matrix C; "
            f"converted to scipy.sparse CSC and solved by `eigsh(K, k={o['count']}, M=M, "
            f"sigma={_g(o.get('shift', 0.0))}, which='LM')` undamped, by `eigs(A, k, M=B, "
            f"sigma={_g(o.get('damped_shift', -0.01))} W, which='LM')` on the state-space "
            "pencil A = [[0, I], [-K, -C]], B = [[I, 0], [0, M]] damped, with k = the "
            f"region's eigenvalues (conjugates counted) + {o['k_margin']}. FE s: the "
            "conversion and the eigensolver, the best of as many runs, with the default BLAS "
            "threads (as many again, one after each of symtmm's solves: both sides of the "
            "ratio in the same minutes) and with one (a child process); the ratio takes the "
            "faster. Errors: the "
            "largest |value - reference| / |reference| over the wanted eigenvalues (symtmm: "
            "its printed values); a reference 0 (a rigid-body mode) counts relative to the "
            "largest |reference|."), ""]
    out += _table(["model", "asked", "FE elements/beam", "FE dofs", "FE error", "FE s",
                   "FE s (1 thread)", "FE eigensolver s", "symtmm s", "evaluations", "symtmm error",
                   "reference error (est.)", "symtmm / FE"],
                  [_ordinary_row(c) for c in o["cases"]])
    out += [f"* {line}" for c in o["cases"] for line in _ordinary_notes(c, o["tolerance"])]
    out += ["", ("(!): not within the tolerance (see the notes). Meshes tried (elements per "
                 "beam: FE error):"), ""]
    out += [f"* {c['name']}: " + ", ".join(f"{t['elements_per_beam']}: "
                                           f"{_g(t['max_rel_error'], 2)}"
                                           for t in c["fe"]["tried"])
            for c in o["cases"] if "error" not in c]
    return out + [""]


def _shapes(sh) -> list:
    out = ["## 8. Mode shapes (reported beside the targets)", "",
           (f"The first {sh['count']} mode shapes (benchmarks/shapes_compare.py): symtmm's "
            f"`mode_shapes(model, count={sh['count']}, points={sh['points']}, "
            f"digits={sh['digits']})` (the verified solve, then each shape by the transfer "
            "walk at the digits its cancellation needs, sampled in double precision) against "
            "the sparse FE model of section 1 on its mesh within "
            f"{sh['tolerance']:g} on the frequencies: assembly and `eigsh` with its "
            "eigenvectors (the nodal values of cubic Hermite shapes, good to the mesh's "
            f"accuracy). Each the best of {sh['repeat']} runs, in turns; symtmm's from a new "
            "model object each time. \"shapes s\" is the part of symtmm's time after the "
            "solve."), ""]
    out += _table(["model", "beams", "shapes", "FE elements/beam", "FE dofs", "FE s",
                   "symtmm s", "shapes s", "symtmm / FE"],
                  [[c["name"], c["beams"], c["shapes"], c["fe"]["elements_per_beam"],
                    c["fe"]["dofs"], _g(c["fe"]["seconds"]), _g(c["symtmm"]["seconds"]),
                    _g(c["symtmm"]["shapes_seconds"]), _g(c["ratio"])]
                   for c in sh["cases"]])
    return out + [""]


def _high_modes(hm) -> list:
    out = ["## 9. High modes (reported beside the targets)", "",
           ("A cantilever's (EI = m = L = 1) first 100 and 300 frequencies "
            "(benchmarks/high_modes.py): symtmm's `solve(model, count=N, "
            f"digits={hm['digits']})` from a new model object, against the sparse FE model "
            "of section 1 (cubic Hermite elements, shift-invert `eigsh` with k = N) on the "
            f"coarsest uniform mesh within {hm['tolerance']:g} on all N frequencies, or, "
            "where the FE error stops falling above it, the mesh of its smallest error "
            "(marked (!): this favours the FE). Reference: the closed form 1 + cos b cosh b "
            f"= 0, omega = b**2, in mpmath. Each the best of {hm['repeat']} runs, in turns."),
           ""]
    out += _table(["model", "symtmm s", "evaluations", "symtmm error", "proofs",
                   "FE elements", "FE dofs", "FE error", "FE s", "symtmm / FE"],
                  [[c["name"], _g(c["symtmm"]["seconds"]), c["symtmm"]["evaluations"],
                    _g(c["symtmm"]["max_rel_error"], 2),
                    "; ".join(f"{p} {k}" for p, k in c["symtmm"]["proofs"].items()),
                    c["fe"]["elements_per_beam"], c["fe"]["dofs"],
                    _g(c["fe"]["max_rel_error"], 2) + ("" if c["fe"]["within"] else " (!)"),
                    _g(c["fe"]["seconds"]), _g(c["ratio"])]
                   for c in hm["cases"]])
    out += ["", "Meshes tried (elements: FE error): " + "; ".join(
        f"{c['count']} modes: " + ", ".join(f"{k}: {_g(e, 2)}" for k, e in c["fe"]["tried"].items())
        for c in hm["cases"]), ""]
    return out


def render(r: dict) -> str:
    out = ["# Benchmarks", "",
           "The targets of issue 11 (\"Fast and certified by default\"), measured side by side "
           "in one run: symtmm's verified solve against the sparse finite-element model a "
           "competent user would write, its cost against model size and precision, the damped "
           "search against the paper's fMin2D, a parameter sweep, and the batched Delta against "
           "the transcendental functions it evaluates; beside them, the ordinary models of the "
           "reliability issue against a measure like the first target's. Generated by "
           "`benchmarks/run.py`"
           + (" (quick run: small sizes only, not the targets' full measure)"
              if r.get("quick") else "") + ".", "",
           "## How to run", "", "```",
           "python benchmarks/run.py --json > docs/benchmarks.json   # full run, 3-5 minutes",
           "python benchmarks/run.py --from-json docs/benchmarks.json -o docs/benchmarks.md",
           "python benchmarks/run.py --quick                          # small sizes, <1 minute",
           "python benchmarks/run.py --sections fe sweep              # some sections",
           "python benchmarks/run.py --sections ordinary              # the ordinary models",
           "python benchmarks/run.py --sections shapes                # mode shapes",
           "python benchmarks/run.py --sections high_modes            # 100 and 300 modes",
           "```", "",
           ("cxroots is optional (`pip install cxroots`, or the `bench` extra); without it its "
            "row reads \"not installed\". The generated C needs gcc. References are computed "
            "in the run, none by symtmm (benchmarks/references.py; section 7: symtmm/fe.py, "
            "which shares no code with the solver, and the issue's published values)."), ""]
    out += _machine(r)
    out += _targets(r)
    out += _findings(r)
    sections = {"fe": _fe, "scaling": _scaling, "precision": _precision,
                "root_search": _root_search, "sweep": _sweep, "evaluator": _evaluator,
                "ordinary": _ordinary, "shapes": _shapes, "high_modes": _high_modes}
    for name, fn in sections.items():
        if name in r and "error" not in r[name]:
            out += fn(r[name])
    if "ordinary" in r and "error" in r["ordinary"]:
        out += ["## 7. Ordinary models (reported beside the targets)", "",
                f"The section stopped with {r['ordinary']['error']}:", "", "```",
                *r["ordinary"]["trace"], "```", ""]
    return "\n".join(out)
