"""Benchmarks of symtmm against the alternatives a user would pick instead.

Run ``python benchmarks/run.py`` (``--quick`` for a run under a minute,
``--json`` for a machine-readable object). The sections:

* :mod:`benchmarks.root_search` -- the default search against the paper's
  grid searches, a plain sign-change grid with bisection and cxroots;
* :mod:`benchmarks.evaluator` -- determinant evaluations per second of every
  backend and of a naive per-point numpy product;
* :mod:`benchmarks.fe_compare` -- a cubic-Hermite finite-element model;
* :mod:`benchmarks.scaling` -- cost against levels and springs per level;
* :mod:`benchmarks.report` -- the markdown report, whose verdicts and
  explanations are generated from the run's numbers, with the profiles of
  :mod:`benchmarks.profiling`.

Reference values come from outside the code under test
(:mod:`benchmarks.references`).
"""
