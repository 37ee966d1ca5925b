"""A damped model with undamped unjoined parts: each part solved where its eigenvalues lie.

``Delta`` of a model is the product of its unjoined parts' (:mod:`symtmm.parts`), so
its eigenvalues are theirs. The damped search of the complex plane counts by the
argument principle, which cannot resolve what an undamped part may hold: a soft beam
on a stiff foundation has its modes within 1e-10 of its cut-off frequency, a cluster
on the imaginary axis that no contour of doubles separates. On the frequency axis the
same cluster is counted exactly (Wittrick–Williams, :mod:`symtmm.roots.undamped`).
So the damped parts are searched in the complex plane and the undamped parts on the
frequency axis, and the two spectra merged, ascending by ``Im lam``.

Two eigenvalues of different parts that print alike are one eigenvalue of their
summed multiplicity only if they agree as closely as the searches tell eigenvalues
apart (``D + SEPARATION_DIGITS`` digits, :data:`symtmm.roots.bracket.SEPARATION_DIGITS`):
where any print alike, both parts are solved again to that many digits to decide.
"""

from __future__ import annotations

import time
from dataclasses import replace

from ..model import Model
from ..parts import beam_groups, part
from ..results import Eigenvalue, Spectrum, first, prints_alike
from .bracket import SEPARATION_DIGITS
from .damped import solve_damped
from .undamped import omega_scale, solve_undamped, undamped_levels

__all__ = ["split", "solve_apart"]


def split(model: Model):
    """``(damped part, undamped part)`` of a damped model whose unjoined parts are not all
    damped (each the union of such parts), else None.

    Examples
    --------
    >>> from symtmm.model import Beam, Model, Spring
    >>> a, b = (Beam(n, 1, 1, 1, left="pinned", right="pinned") for n in "ab")
    >>> damped, undamped = split(Model((a, b), (Spring("a", "ground", "1/2", 0, c=1),)))
    >>> [x.name for x in damped.beams], [x.name for x in undamped.beams]
    (['a'], ['b'])
    >>> split(Model((a, b), (Spring("a", "b", "1/2", 0, c=1),))) is None     # joined
    True
    """
    groups = beam_groups(model)
    if len(groups) < 2:
        return None
    damped, undamped = [], []
    for names in groups:
        (damped if part(model, names).damped else undamped).extend(names)
    if not damped or not undamped:
        return None
    return part(model, damped), part(model, undamped)


def _alike(a: Eigenvalue, b: Eigenvalue, digits: int) -> bool:
    return prints_alike(a.lam.real, b.lam.real, digits) and \
        prints_alike(a.lam.imag, b.lam.imag, digits)


def _pairs_alike(d, u, digits: int) -> list:
    """``(i, j)`` of the eigenvalues of ``d`` and ``u`` that print alike (the exact zeros
    of rigid motions, equal by construction, among them)."""
    return [(i, j) for i, a in enumerate(d) for j, b in enumerate(u) if _alike(a, b, digits)]


def _nearest(spectrum, e: Eigenvalue) -> Eigenvalue:
    return min(spectrum, key=lambda o: abs(o.lam - e.lam))


def _names(model: Model) -> str:
    return ", ".join(b.name for b in model.beams)


def _key(e: Eigenvalue):
    return (e.lam.imag, e.lam.real)


def _lowest(solvers, count: int, counts: list, spectra: list):
    """``(counts, spectra, evaluations spent on spectra left behind)``: each part solved
    (``solvers[p](c)``) for as many eigenvalues as the ``count`` lowest of the model take
    from it, from ``spectra`` solved for ``counts``.

    A part solved for all ``count`` may search far for eigenvalues the other part's
    already outrank: a heavy Rayleigh beam on a foundation, damped, whose second
    eigenvalue is the lowest of hundreds crowding near its dispersion's minimum, where
    the undamped part's rigid-body mode came before its first (a campaign model: 24
    eigenvalues counted, then isolated and proved, past the 60 s budget, for two asked).
    A part whose last eigenvalue lies below the ``count``-th of both together is solved
    again for the places left to it (``count`` less the other part's eigenvalues up to
    its last), until none does or it has been solved for ``count``. A part's next
    eigenvalue lies above its last (``first`` keeps a multiple one whole; the damped part
    gives every eigenvalue its region held, which is all of them up to its top), so those
    it was not solved for lie above the ``count``-th.
    """
    spent = 0
    while True:
        kept = first(sorted((e for s in spectra for e in s), key=_key), count)
        cut = _key(kept[-1]) if sum(e.multiplicity for e in kept) >= count else None
        grown = False
        for p, s in enumerate(spectra):
            if counts[p] >= count or (cut is not None and s and _key(s[-1]) >= cut):
                continue
            last = _key(s[-1]) if s else None
            below = sum(e.multiplicity for q, o in enumerate(spectra) if q != p for e in o
                        if last is not None and _key(e) <= last)
            counts[p] = min(count, max(counts[p] + 1, count - below))
            spent += s.evaluations
            spectra[p] = solvers[p](counts[p])
            grown = True
        if not grown:
            return counts, spectra, spent


def _damped_share(damped: Model, undamped_spectrum, count: int) -> tuple:
    """``(places, evaluations)``: how many of the ``count`` lowest eigenvalues the damped
    part is first solved for, by its frequencies without dashpots (lightly damped
    eigenvalues lie near them) among the undamped part's; at least 1."""
    levels, spent = undamped_levels(damped, count)
    if levels is None:
        return count, spent
    merged = sorted([(w, 0) for w in levels]
                    + [(float(e.lam.imag), 1) for e in undamped_spectrum
                       for _ in range(e.multiplicity)])[:count]
    return max(1, sum(1 for _, part in merged if part == 0)), spent


def solve_apart(model: Model, damped: Model, undamped: Model, count, omega_max, sigma_max,
                digits: int, prove_count: bool = False) -> Spectrum:
    """The eigenvalues of ``model`` from those of its ``damped`` and ``undamped`` parts
    (:func:`split`), as :func:`symtmm.roots.damped.solve_damped` gives them."""
    start = time.perf_counter()

    def solve_d(c, d=digits):
        # (under a count every eigenvalue its region held: _lowest takes what it needs)
        return solve_damped(damped, count=c, omega_max=omega_max, sigma_max=sigma_max,
                            digits=d, prove_count=prove_count, beyond_count=c is not None)

    def solve_u(c, d=digits):
        return solve_undamped(undamped, count=c, omega_max=omega_max, digits=d)

    spent, asked = 0, [count, count]       # (the counts each part is solved for)
    if count is None:
        ds, us = solve_d(None), solve_u(None)
    else:
        # the undamped part for the whole count (its counts are exact and cheap), the
        # damped part first for the places its frequencies without dashpots take
        us = solve_u(count)
        share, spent = _damped_share(damped, us, count)
        asked, (ds, us), more = _lowest((solve_d, solve_u), count, [share, count],
                                        [solve_d(share), us])
        spent += more
    evaluations = spent + ds.evaluations + us.evaluations
    alike = _pairs_alike(ds, us, digits)
    if any(ds[i].lam != 0 for i, _ in alike):
        # (told apart as the searches tell the eigenvalues of one part apart: each
        # eigenvalue's nearest at that many digits)
        finer = digits + 2 + SEPARATION_DIGITS
        dx, ux = solve_d(asked[0], finer), solve_u(asked[1], finer)
        evaluations += dx.evaluations + ux.evaluations
        alike = [(i, j) for i, j in alike if ds[i].lam == 0 or _alike(
            _nearest(dx, ds[i]), _nearest(ux, us[j]), finer)]
    merged: dict = {}
    for i, j in alike:
        if i not in merged and j not in merged.values():
            merged[i] = j
    eigen = []
    for i, e in enumerate(ds):
        if i in merged:
            o = us[merged[i]]
            proofs = e.proof if e.proof == o.proof else f"{e.proof}; {o.proof}"
            e = replace(e, multiplicity=e.multiplicity + o.multiplicity, proof=proofs)
        eigen.append(e)
    used = set(merged.values())
    eigen += [e for j, e in enumerate(us) if j not in used]     # (lam = i omega exactly)
    eigen.sort(key=lambda e: (e.lam.imag, e.lam.real))
    if count is not None:
        eigen = first(eigen, count)
    notes = [f"unjoined parts solved apart: beams {_names(damped)} (damped) in the complex "
             + f"plane, beams {_names(undamped)} (undamped) on the frequency axis"]
    notes += [f"beams {_names(damped)}: {n}" for n in ds.notes]
    notes += [f"beams {_names(undamped)}: {n}" for n in us.notes]
    if any(ds[i].lam != 0 for i in merged):
        notes.append(f"eigenvalues of both parts that agree to {digits + SEPARATION_DIGITS} "
                     "digits are one eigenvalue, their multiplicities added")
    return Spectrum(tuple(eigen), digits, "default", evaluations, time.perf_counter() - start,
                    model.source or "", omega_scale(model, digits + 10), tuple(notes),
                    title=model.title)
