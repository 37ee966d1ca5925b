"""Mode shapes: the state ``[Y, Theta, M, Q]`` along every beam at an eigenvalue.

At an eigenvalue ``lam`` the boundary matrix ``R(lam)`` is singular; a null
vector gives the unknowns of the overall transfer equation (the beams'
left-end state variables, and each rigid body's deflection, rotation and the
forces it exerts), and the transfer matrices carry that extended state along
the beams (paper eq. 3). The steps:

1. **Precision.** The entries of ``R`` grow like ``exp(|s| L)`` (``s`` the
   largest wave number), so the work is done in a private mpmath context at
   ``digits + loss + 15`` decimal digits, ``loss`` being
   :func:`~symtmm.numeric.transfer.digits_lost` at the eigenvalue
   (:func:`working_digits`).
2. **Null space.** At that precision, the space of the right singular
   vectors of the ``m`` smallest singular values of ``R(lam)`` (``m`` the
   multiplicity), by block inverse iteration on an LU factorisation
   (:func:`~symtmm.numeric.linalg.null_space`). Backward stable, it keeps the
   growing exponential out of the vector, so the shape is as accurate as the
   eigenvalue, even near the far end.
3. **Propagation.** The one transfer walk of the numeric kernel
   (:func:`~symtmm.numeric.transfer.sample`) carries the extended state along
   the layout: every segment (any beam theory) by its transfer matrix, every
   station by its exact jump entries ``z -> (I + G) z`` (springs, masses,
   rigid bodies and joints); sample points inside a segment are reached from
   anchors ``|s| h <= 1`` apart, the last short step in double precision.
4. **Normalisation** (:mod:`symtmm.modes.normalise`). Undamped shapes are
   real and mass-normalised in the full kinetic energy (beams, rotary inertia,
   lumped masses, rigid bodies), the Gram matrix gathered on the same walk; the
   ``m`` shapes of a multiple eigenvalue are made mass-orthonormal. Each
   shape's largest displacement is made positive. Damped shapes are complex
   and scaled so that the largest ``|Y|`` over all beams is ``1`` (real).

Sample points and the two sides of a station: at a spring (or a body's
attachment) the shear force jumps. The state reported at a beam's left end
is the one before the jumps there and at its right end the one after them
(the states the boundary conditions constrain: a beam end held by a body is
"free" outside it); at interior points sitting on a station the state just
right of it (after the jumps). :func:`evaluate_mode` gives either side.

Modules: :mod:`~symtmm.modes.modeset` (the result objects),
:mod:`~symtmm.modes.shapes` (the computation), :mod:`~symtmm.modes.normalise`.
"""

from .modeset import BeamShape, ModeSet, ModeShape
from .shapes import ShapePlan, displacements, evaluate_mode, mode_shapes, shapes_at, working_digits

__all__ = ["BeamShape", "ModeSet", "ModeShape", "ShapePlan", "displacements", "evaluate_mode",
           "mode_shapes",
           "shapes_at", "working_digits"]
