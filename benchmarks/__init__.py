"""Benchmarks of symtmm against the alternatives a user would pick instead.

Run ``python benchmarks/run.py`` (``--quick`` for small sizes, ``--json`` for a
machine-readable object). The sections, one per target of issue 11:

* :mod:`benchmarks.fe_compare` -- the verified solve against the sparse
  finite-element model of :mod:`benchmarks.sparse_fe`;
* :mod:`benchmarks.scaling` -- cost per evaluation against model size;
* :mod:`benchmarks.precision` -- the cost of 30 and 50 digits;
* :mod:`benchmarks.root_search` -- the default search against the paper's grid
  searches, a sign-change grid with bisection and cxroots;
* :mod:`benchmarks.sweep_compare` -- the paper's figure 10 as a sweep;
* :mod:`benchmarks.evaluator` -- the batched Delta against its transcendental
  functions, the naive product and the generated C;
* :mod:`benchmarks.ordinary` -- beside the targets: the ordinary models of the
  reliability issue (axial force, Rayleigh and Timoshenko beams, dashpots) against
  a sparse finite-element model, by the first target's measure;
* :mod:`benchmarks.report` -- the markdown report, whose verdicts and
  explanations are generated from the run's numbers, with the profiles of
  :mod:`benchmarks.profiling`.

Reference values come from outside the code under test
(:mod:`benchmarks.references`); symtmm's internals are reached only through
:func:`benchmarks.kernel.internals`.
"""
