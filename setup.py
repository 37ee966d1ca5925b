"""The optional C extension; everything else is in pyproject.toml.

``symtmm.numeric._band`` runs the banded LDL^T elimination of double-precision
batches in C. It is optional: without a C compiler the install goes on and the
same loop runs in numpy (``symtmm.numeric.stiffness``).
"""

from setuptools import Extension, setup

setup(ext_modules=[Extension(
    "symtmm.numeric._band", ["symtmm/numeric/_band.c"],
    # a fused multiply-add would round differently from the numpy loop
    extra_compile_args=["-O2", "-ffp-contract=off"],
    optional=True)])
