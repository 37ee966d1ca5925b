"""The fixed kernels of the generated evaluators, one set of real source files per language.

``core``, ``euler_bernoulli`` and ``theory`` (``.c`` and ``.f90``) and
``kernels`` (``.m``, ``.jl``, ``.py``, which hold the same three parts): the
units of a beam's state, the re-orthonormalisation of the columns, the
determinant, the Euler–Bernoulli segment from the functions ``c_j`` and the
segment of any other beam theory. :func:`symtmm.codegen.generate` copies them
verbatim into its output, C and Fortran only the parts a model needs (their
compilers reject unused internal procedures under ``-Wall -Werror``); the
tests compile and run them on their own as well. ``kernels.py`` imports as
:mod:`symtmm.codegen.runtime.kernels`.
"""
