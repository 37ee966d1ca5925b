"""Cost per evaluation against model size, from 1 to 50 levels.

Models are :func:`benchmarks.models.chain` with 2 springs per level: random
beams over ``[0, 1]``, level ``i`` joined to level ``i + 1`` (the last to the
ground) at random positions, distinct over the model. The model size is
segments x levels: the ``2 n`` spring positions of ``n`` levels cut the span
into ``2 n + 1`` segments, and every level runs through all of them, ``n (2 n
+ 1)`` beam segments in all (the size of the overall transfer matrix product).
Beside it the size of what the numeric kernel compiles is reported: each beam
cut at its own springs and into pieces short enough for the frequency range,
the freedoms and the half-bandwidth of the dynamic stiffness.

An evaluation is ``Delta`` and the eigenvalue count at one frequency (one
factorization gives both, :func:`benchmarks.kernel.internals`), below
:data:`OMEGA_MAX`. Measured per evaluation:

* at 15 digits -- double precision, a batch of :data:`BATCH` frequencies per call
  (the same batch at every size: a batch that shrank with the model would put
  more per-call overhead on each point of the large models), per point;
* at 50 digits -- the proof arithmetic at 50 digits (Arb balls where
  python-flint is installed, else mpmath), a batch of :data:`HIGH_BATCH`
  frequencies, per point.

The plan and its tables are built and warmed by one call before the timings
(their cost is reported apart). Each timing is the minimum of :data:`REPEAT`,
taken in rounds over all sizes (other work on the machine only ever adds
time, and a busy spell then hits every size alike); a timing over 5 s is not
repeated. The exponent is the least-squares slope of ``log(time)`` against
``log(size)`` over all sizes; the target asks for at most :data:`LIMIT` at both
precisions.
"""

from __future__ import annotations

import time

import mpmath
import numpy as np

from .kernel import internals
from .models import chain, layered_chain, rod_chain, sprung_chain, storey_frame

__all__ = ["run", "SIZES", "fit_exponent", "model_size", "BATCH", "REPEAT"]

#: Levels (full run, quick run).
SIZES = ((1, 2, 3, 5, 10, 20, 50), (1, 2, 5, 10))
SPRINGS = 2
OMEGA_MAX = 300.0
BATCH = 200
HIGH_BATCH = 4
HIGH_DIGITS = 50
REPEAT = 5
LIMIT = 1.2


def fit_exponent(sizes, times) -> float | None:
    """Least-squares slope of ``log(time)`` against ``log(size)``.

    Examples
    --------
    >>> round(fit_exponent([1, 2, 4, 8], [3.0, 12.0, 48.0, 192.0]), 6)
    2.0
    """
    pts = [(s, t) for s, t in zip(sizes, times) if t is not None and t > 0]
    if len(pts) < 2:
        return None
    return float(np.polyfit(np.log([p[0] for p in pts]), np.log([p[1] for p in pts]), 1)[0])


def model_size(model) -> dict:
    """Segments x levels of a model over one span, and its segments cut per beam.

    Examples
    --------
    >>> model_size(chain(3, 2))
    {'levels': 3, 'segments': 7, 'size': 21, 'own_segments': 13}
    """
    model = model.resolved()
    cuts = {s.x for s in model.springs}
    own = sum(1 + len({s.x for s in model.springs if b.name in (s.a, s.b)})
              for b in model.beams)
    n = len(model.beams)
    return dict(levels=n, segments=len(cuts) + 1, size=n * (len(cuts) + 1), own_segments=own)


#: The elements of the paper's literature, the same chains carrying them (reported beside
#: the target): partial layers between neighbouring levels, a sprung mass on every level,
#: rods joined by axial springs in place of the beams; and plane frames of one bay whose
#: storeys stand for the levels.
FAMILIES = {"layers": layered_chain, "sprung masses": sprung_chain, "rods": rod_chain,
            "frames": storey_frame}
#: Levels of those (full run, quick run); a frame's storeys up to 33 (99 members, each two
#: levels: the budget of symtmm.limits.MAX_BEAMS).
FAMILY_SIZES = ((1, 2, 5, 10, 20, 50), (1, 2, 5))
FRAME_SIZES = ((1, 2, 5, 10, 20, 33), (1, 2, 5))


def _prepare(levels: int, build=None) -> dict:
    model = chain(levels, SPRINGS) if build is None else build(levels)
    start = time.perf_counter()
    k = internals().kernel(model, OMEGA_MAX)
    omegas = np.linspace(1.0, OMEGA_MAX, BATCH)
    high = [mpmath.mpf(w) for w in np.linspace(7.25, OMEGA_MAX - 1.5, HIGH_BATCH)]
    k.delta(omegas)
    built = time.perf_counter() - start
    start = time.perf_counter()
    k.counts(high, HIGH_DIGITS)
    warm = time.perf_counter() - start
    row = dict(model_size(model), **k.size(OMEGA_MAX), prepare_seconds=built,
               first_high_call_seconds=warm, double_rounds=[], high_rounds=[])
    return dict(kernel=k, omegas=omegas, high=high, row=row)


def _time_once(entry: dict, enough: float = 5.0) -> None:
    k, row = entry["kernel"], entry["row"]
    if row["double_rounds"] and max(row["double_rounds"][0] * BATCH,
                                    row["high_rounds"][0] * HIGH_BATCH) > enough:
        return
    start = time.perf_counter()
    k.delta(entry["omegas"])
    row["double_rounds"].append((time.perf_counter() - start) / BATCH)
    start = time.perf_counter()
    k.counts(entry["high"], HIGH_DIGITS)
    row["high_rounds"].append((time.perf_counter() - start) / HIGH_BATCH)


def _rows(entries, measures) -> tuple:
    """The rows of timed entries (best of their rounds) and the exponents of their cost
    against each measure of size."""
    rows = [e["row"] for e in entries]
    for row in rows:
        row["double_seconds"] = min(row["double_rounds"])
        row["high_seconds"] = min(row["high_rounds"])
    exps = {key: {p: fit_exponent([r[key] for r in rows], [r[f"{p}_seconds"] for r in rows])
                  for p in ("double", "high")} for key in measures}
    return rows, exps


def run(quick: bool = False, progress=print) -> dict:
    sizes = SIZES[1] if quick else SIZES[0]
    entries = []
    for n in sizes:
        progress(f"scaling: {n} levels")
        entries.append(_prepare(n))
    for _ in range(REPEAT):
        for entry in entries:
            _time_once(entry)
    rows, exps = _rows(entries, ("size", "levels", "own_segments", "freedoms"))
    met = all(v is not None and v <= LIMIT for v in exps["size"].values())
    families = {}
    for name, build in FAMILIES.items():
        entries = []
        sizes = FRAME_SIZES if name == "frames" else FAMILY_SIZES
        for n in sizes[1] if quick else sizes[0]:
            progress(f"scaling: {name}, {n} levels")
            entries.append(_prepare(n, build))
        for _ in range(REPEAT):
            for entry in entries:
                _time_once(entry)
        f_rows, f_exps = _rows(entries, ("levels", "pieces", "freedoms"))
        # the half-bandwidth grows with the first levels (layers make the freedom graph a
        # grid of levels by pieces, whose band is set by its narrower side) and then stays:
        # the slope over the largest sizes is the cost's growth from there on
        tail = f_rows[-3:]
        f_exps["levels, largest three sizes"] = {
            p: fit_exponent([r["levels"] for r in tail], [r[f"{p}_seconds"] for r in tail])
            for p in ("double", "high")}
        families[name] = dict(model=f"benchmarks.models.{build.__name__}(levels)",
                              rows=f_rows, exponents=f_exps)
    return dict(model=f"benchmarks.models.chain(levels, {SPRINGS})", omega_max=OMEGA_MAX,
                batch=BATCH, high_batch=HIGH_BATCH, high_digits=HIGH_DIGITS,
                high_arithmetic=internals().arithmetic_name(HIGH_DIGITS), repeat=REPEAT,
                rows=rows, exponents=exps, families=families,
                target=dict(text=f"cost per evaluation against model size (segments x levels), "
                                 f"1 to {sizes[-1]} levels: fitted exponent at most {LIMIT:g} "
                                 f"at 15 (double) and {HIGH_DIGITS} digits",
                            exponent_15=exps["size"]["double"],
                            exponent_50=exps["size"]["high"], met=bool(met)))
