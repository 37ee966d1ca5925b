"""The order of the cuts along the beams when positions are symbolic.

A derivation may keep parameters symbolic (``symbolic`` of
:func:`~symtmm.characteristic.characteristic_equation`); the positions of
springs and bodies then are expressions, and the transfer walk needs their
order. :func:`_prepare` drops the values of the symbolic parameters and keeps
them (or, where the model allows only one order, random values) as a sample
that orders the cuts; :func:`_check_order` refuses an order the symbols leave
open. The code generators (:mod:`symtmm.codegen.plan`) order their cuts the
same way.
"""

from __future__ import annotations

import random
from itertools import pairwise

import sympy as sp

from ..assembly import Layout
from ..errors import ModelError
from ..expr import parameter_symbol
from ..model import Model


def _prepare(model: Model, symbolic) -> tuple[Model, dict]:
    """Drop the values of the ``symbolic`` parameters, keep them to order the cuts."""
    sample = {}
    values = {}
    for name in symbolic:
        if name not in model.parameters:
            raise ModelError(f"'{name}' is not a parameter of this model",
                             field="symbolic " + name, source=model.source)
        value = model.parameters[name]
        if value is not None:
            sample[parameter_symbol(name)] = value
        values[name] = None
    if values:
        model = model.with_parameters(**values)
    model = model.resolved()
    return model, _complete_sample(model, sample)


def _complete_sample(model: Model, sample: dict) -> dict:
    """Order positions whose symbols have no value, when the model allows only one order.

    Random values of the remaining symbols are tried; those that put every
    spring and layer inside its beams are kept. If they all order the cuts alike, one of
    them orders the cuts (it does not enter the result); if they disagree the
    order is left open and :func:`_check_order` asks for a value.
    """
    positions = [p for b in model.beams for p in (b.x0, b.x1)] + [s.x for s in model.springs] \
        + [x for la in model.layers for x in (la.x0, la.x1)]
    free = set().union(*(sp.sympify(p).free_symbols for p in positions)) - set(sample)
    if not free:
        return sample
    free = sorted(free, key=lambda v: v.name)
    rng = random.Random(0)
    lengths = [b.L.xreplace(sample) for b in model.beams]
    scale = max([v for v in lengths if v.is_number] or [sp.Integer(1)])
    beams = {b.name: b for b in model.beams}
    found: dict = {}
    for _ in range(200):
        trial = dict(sample)
        trial.update({v: scale * sp.Rational(rng.randint(1, 999), 1000) for v in free})
        values = [sp.sympify(p).xreplace(trial) for p in positions]
        if not all(v.is_number for v in values):
            return sample
        if any(b.L.xreplace(trial) <= 0 for b in model.beams):
            continue
        inside = all(beams[n].x0.xreplace(trial) <= s.x.xreplace(trial)
                     <= beams[n].x1.xreplace(trial)
                     for s in model.springs for n in (s.a, s.b) if n in beams) and all(
            beams[n].x0.xreplace(trial) <= la.x0.xreplace(trial) < la.x1.xreplace(trial)
            <= beams[n].x1.xreplace(trial) for la in model.layers for n in (la.a, la.b))
        if not inside:
            continue
        ranks = tuple(sorted(set(values)).index(v) for v in values)
        found.setdefault(ranks, trial)
        if len(found) > 1:
            return sample
    return next(iter(found.values())) if len(found) == 1 else sample


def _check_order(layout: Layout, sample: dict, source):
    """Positions whose order the symbols leave open must be ordered by ``sample``."""
    xs = [s.x for s in layout.stations]
    for a, b in pairwise(xs):
        d = sp.simplify(b - a)
        if d.is_positive:
            continue
        value = d.xreplace(sample) if sample else d
        names = sorted(s.name for s in d.free_symbols)
        if not (value.is_number and value > 0):
            hint = ", ".join(names) if names else "the parameters"
            raise ModelError(f"the order of the cuts along the beams depends on {hint}: give it a "
                             "value in [parameters] and keep it symbolic with --symbolic "
                             f"{hint.replace(', ', ',')}", field="parameters", source=source)
