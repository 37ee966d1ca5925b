"""Estimates of the eigenvalues (a sweep's previous steps) steer the search, never the result.

References are closed forms: a pinned-pinned beam's ``(n pi / L)**2 sqrt(EI/m)``, and two
uncoupled beams, whose spectrum is the union of theirs (a double eigenvalue where a
frequency of one is a frequency of the other).
"""

import math

import pytest

from symtmm.errors import ModelError
from symtmm.model import Beam, Model
from symtmm.numeric.plan import clear_plans
from symtmm.roots.undamped import _Search
from symtmm.solve import solve
from symtmm.sweep import sweep


def pinned(name, EI, m=1, L=1):
    return Beam(name, EI, m, L, left="pinned", right="pinned")


def closed_form(EI, m=1, L=1, count=10):
    return [(n * math.pi / L) ** 2 * math.sqrt(EI / m) for n in range(1, count + 1)]


def expanded(spectrum):
    return [float(e.omega) for e in spectrum for _ in range(e.multiplicity)]


ONE = Model((pinned("b", 2),))
#: beam b's first frequency is beam a's second: 16 pi**2 twice
TWO = Model((pinned("a", 1), pinned("b", 16)))
TWO_REFERENCE = sorted(closed_form(1) + closed_form(16))


def guess_sets(reference):
    good = [(w * (1 + 1e-4), 1e-3) for w in reference]
    return {
        "good": good,
        "shifted 3 %": [(w * 1.03, 1e-3) for w in reference],
        "too narrow": [(w * (1 + 1e-4), 1e-9) for w in reference],
        "one missing": good[:3] + good[4:],
        "too few": good[:4],
        "duplicated": good + good,
        "far too high": [(100 * w, 1e-3) for w in reference],
        "unordered": good[::-1],
        "not numbers": [(math.nan, 1e-3), (math.inf, 1e-3), (-5.0, 1e-3), (0.0, 1e-3),
                        (reference[0], math.nan)],
        "as wide as the range": [(w, 2.0) for w in reference],
    }


@pytest.mark.parametrize("model, reference", [(ONE, closed_form(2)), (TWO, TWO_REFERENCE)],
                         ids=["one beam", "two uncoupled beams"])
def test_guesses_change_no_digit_and_no_multiplicity(model, reference):
    for name, guesses in guess_sets(reference).items():
        spectrum = solve(model, count=10, digits=15, guesses=guesses)
        assert expanded(spectrum) == pytest.approx(reference[:10], rel=1e-14), name
        if model is TWO:
            assert [e.multiplicity for e in spectrum][:3] == [1, 2, 1], name


def test_good_guesses_spare_the_search_for_the_range_and_the_isolation():
    reference = closed_form(2)
    clear_plans()
    cold = solve(ONE, count=10, digits=15)
    clear_plans()
    warm = solve(ONE, count=10, digits=15, guesses=guess_sets(reference)["good"])
    assert warm.evaluations < cold.evaluations
    # the counts at the ends of the estimates (and one above them) are all the search
    # needs: one batch
    search = _Search(ONE, 15, 10.0, None)
    (top, count), cuts = search.guided(guess_sets(reference)["good"], 10)
    assert count == 10 and reference[9] < top < reference[9] * 1.002
    assert [c for _, c in cuts] == [k for k in range(10) for _ in (0, 1)][1:]
    assert search.evaluations == 21
    # the highest estimate short of the last root: the count above it reaches the top
    short = guess_sets(reference)["good"][:9] + [(reference[9] * 0.98, 1e-3)]
    (top, count), _ = search.guided(short, 10)
    assert count == 10 and reference[9] < top
    # estimates that leave the top far uncounted give the search back
    assert search.guided(guess_sets(reference)["too few"], 10) is None


def test_guesses_that_are_not_pairs_of_numbers_are_one_clear_error():
    for bad in ([1.0, 2.0], [("a", 1e-3)], 5):
        with pytest.raises(ModelError, match="^guesses: "):
            solve(ONE, count=2, guesses=bad)


def test_a_sweep_starts_each_step_from_the_steps_before_it():
    model = Model((pinned("a", 1), pinned("b", "E")), parameters={"E": 16})
    result = sweep(model, "E", 12, 20, 5, count=8, digits=12, jobs=1)
    for E, spectrum in zip((12, 14, 16, 18, 20), result.spectra):
        reference = sorted(closed_form(1) + closed_form(E))[:8]
        assert expanded(spectrum)[:8] == pytest.approx(reference, rel=1e-12)
        # where b's first frequency meets a's second, the eigenvalue is double
        assert (E == 16) == any(e.multiplicity == 2 for e in spectrum)
    # from the third step on, the two before it extrapolated: less work than a solve alone
    for E, spectrum in list(zip((12, 14, 16, 18, 20), result.spectra))[2:]:
        clear_plans()           # (as the step's own solve began: no plan of its model)
        alone = solve(model.with_parameters(E=E), count=8, digits=12)
        assert spectrum.evaluations < alone.evaluations
