"""The numeric kernel: one implementation over several arithmetics.

* :mod:`~symtmm.numeric.arith`: the arithmetics (double batches, mpmath at an
  explicit precision, Arb balls);
* :mod:`~symtmm.numeric.segments`: transfer matrices of beam segments;
* :mod:`~symtmm.numeric.plan`: a model compiled for the dynamic-stiffness kernel;
* :mod:`~symtmm.numeric.stiffness`: segment stiffness, assembly, banded LDL^T;
* :mod:`~symtmm.numeric.transfer`: the transfer-matrix walk along the layout, and the
  states it passes at sample points (mode shapes);
* :mod:`~symtmm.numeric.linalg`: determinant, LU, null space, Gram–Schmidt, Cholesky;
* :mod:`~symtmm.numeric.quadrature`: Gauss–Legendre rules at any precision;
* :mod:`~symtmm.numeric.evaluator`: one model evaluated in batches, the searches'
  entry point.
"""
