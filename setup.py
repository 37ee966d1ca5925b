"""The optional C extensions; everything else is in pyproject.toml.

``symtmm.numeric._band`` runs the banded LDL^T elimination of double-precision
batches in C, ``symtmm.numeric._multiword`` the ball factorisations of undamped beam
models in multi-word balls. Both are optional: without a C compiler the install
goes on, the double loop runs in numpy (``symtmm.numeric.stiffness``) and every ball
in Arb.
"""

from setuptools import Extension, setup

setup(ext_modules=[
    Extension(
        "symtmm.numeric._band", ["symtmm/numeric/_band.c"],
        depends=["symtmm/numeric/_band_core.h", "symtmm/numeric/_buffers.h"],
        # a fused multiply-add would round differently from the numpy loop; Python's own
        # -fwrapv (signed overflow defined) kept the elimination's index arithmetic from
        # being optimised: 40 % of its time
        extra_compile_args=["-O2", "-ffp-contract=off", "-fno-wrapv"],
        optional=True),
    Extension(
        # multi-word balls: their error-free sums must not be fused either
        "symtmm.numeric._multiword", ["symtmm/numeric/_multiword.c"],
        depends=["symtmm/numeric/_multiword_double.h", "symtmm/numeric/_multiword_complex.h",
                 "symtmm/numeric/_multiword_instance.h", "symtmm/numeric/_multiword_words.h",
                 "symtmm/numeric/_multiword_nw.h", "symtmm/numeric/_multiword_dd.h",
                 "symtmm/numeric/_multiword_limbs.h", "symtmm/numeric/_multiword_kernel.h",
                 "symtmm/numeric/_band_core.h", "symtmm/numeric/_buffers.h"],
        extra_compile_args=["-O2", "-ffp-contract=off", "-fno-wrapv"],
        optional=True),
])
