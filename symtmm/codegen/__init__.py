"""Self-contained evaluators of ``Delta(lam) = det R(lam)`` in C, Fortran, Octave, Julia, Python.

Structure of the generated code
-------------------------------
The generated code follows :meth:`symtmm.compile.Evaluator.log_delta` rather
than printing one expanded determinant: the closed form (see
:mod:`symtmm.characteristic`) sums terms that grow like ``exp(beta L)`` with
opposite signs and has thousands of operations for multilevel models. The
generated code instead

1. builds each segment's transfer matrix for the segment cut into ``n`` equal
   steps of ``|beta| l / n <= NU_STEP`` (``n`` from ``lam`` at run time,
   ``|beta|`` the bound on the wave numbers of
   :meth:`~symtmm.elements.theories.BeamSegment.wave_number`):

   * a plain Euler–Bernoulli segment from the entire functions ``c_j(x) =
     sum_k x**k / (4k+j)!`` of ``x = -lam**2 m l**4 / EI`` (a 16-term series
     below ``|x| = 1``, closed forms in ``x**(1/4)`` above), with no branch to
     choose and no 0/0 at ``lam = 0``;
   * any other segment (axial force ``N``, rotary inertia ``rhoI``, shear
     stiffness ``kGA``) as :mod:`symtmm.elements.theories` does: the series of
     ``alpha0, beta0, alpha1, beta1`` in ``(t, d)`` (trace and determinant of
     ``G = B C``) over a piece short enough that ``max|r| h**2 <= 1``, then the
     doubling formulas back to the whole step;

2. measures the state of every beam in units of its wave number ``b``:
   ``[Y, Theta/b, M/(EI b**2), Q/(EI b**3)]``, and each virtual variable of a
   rigid body (its deflection, rotation, the forces and couples it exerts, the
   accumulators of its equations) in the unit of the beam variable it stands
   for (:attr:`symtmm.assembly.Layout.units`);
3. propagates the columns of the unknowns (beams' free left-end variables,
   bodies' unknowns) through the cuts (segment steps, then each station's jump
   ``z -> (I + G) z`` whose entries are exact polynomials in ``lam``),
   re-orthonormalising them whenever they may have grown by ``exp(NU_STEP)``
   (modified Gram–Schmidt, twice, or a QR factorisation) and adding up the
   logarithms of the norms (Godunov's method);
4. returns ``det E[rows] * exp(sum of the logarithms)``, the determinant by
   Gaussian elimination with partial pivoting.

Without steps 2 and 3 the columns become parallel to working precision and the
value loses ``sum |beta| L / ln 10`` digits (all of them by ``beta L = 36``);
with them it keeps about 13 significant digits at any mode, like the Python
evaluator (less about ``log10(k L / EI)`` beside a rotational spring far stiffer
than its beams, ``log10(k L**3 / EI)`` beside a translational one: every double
evaluation of ``Delta`` loses those), and overflows only where ``|Delta|`` itself
exceeds the double range.
Common subexpressions of the parameters are computed once (:func:`sympy.cse`),
identical segments share one matrix, and constants are printed with 17
significant digits (exact to double precision).

The header comment names the model (its file, title and parameter values)
and the method. That text comes from the model file and is data: every line
goes through :func:`symtmm.text.comment_text` (printable ASCII, one line, no
sequence that ends or opens a comment in any of the languages), and the
Python file carries it as ``#`` comments rather than in its docstring.

How it is written
-----------------
:func:`~symtmm.codegen.plan.plan` turns the model into a language-neutral
plan; one walk (:func:`~symtmm.codegen.walker.walk`) writes the evaluator's
body from it through the dialect of the language
(:mod:`symtmm.codegen.dialects`: literals, arrays and their first index,
loops, declarations, comments, the file's layout and the identifier rules).
The fixed kernels (the functions ``c_j``, the segment routines, the units,
the re-orthonormalisation and the determinant) are real source files in
``symtmm/codegen/runtime/``, copied verbatim into the output and compiled and
run on their own by the tests.

Signatures (the command-line contract)
--------------------------------------
* C99: ``void symtmm_delta(double lam_re, double lam_im, [double P, ...]
  double *delta_re, double *delta_im)``
* Fortran 2008: ``subroutine symtmm_delta(lam_re, lam_im, [P, ...] delta_re, delta_im)
  bind(C, name="symtmm_delta")``, ``real(c_double)``, inputs by value
* Octave/MATLAB: ``function d = symtmm_delta(lam [, P, ...])`` (any array ``lam``)
* Julia: ``symtmm_delta(lam::ComplexF64 [, P::Float64, ...])::ComplexF64``
* Python: ``symtmm_delta(lam [, P, ...])`` on numpy arrays, numpy only

``P, ...`` are the model's parameters left symbolic, in alphabetical order.
An argument keeps the parameter's name unless that name means something in
the language or in the generated code: a keyword, a macro of the included C
headers (``I``, ``NAN``, ``linux``), a builtin the code would lose
(``complex``, ``range`` in Python), any name the evaluator itself uses, read
from the code generated for the model (``E`` in Fortran, which ignores case,
``sqrt``, ``lam``), or a name that is no ASCII identifier; it is then called
``p_NAME`` (characters other than letters, digits and ``_`` replaced by
``_``, at most 63 characters), and the header says which parameter it stands
for. The order of the cuts along the beams is fixed when the code is
generated; values that would reverse it (a segment of negative length) give
``NaN``.

Examples
--------
>>> from symtmm.model import Beam, Model
>>> src = generate(Model((Beam("b", 1, 1, 1, left="pinned", right="pinned"),)), "python")
>>> namespace = {}
>>> exec(src, namespace)
>>> import numpy as np
>>> bool(abs(namespace["symtmm_delta"](np.array([1j * np.pi**2]))[0]) < 1e-12)
True

A Rayleigh beam, pinned at both ends: ``omega**2 = EI q**2 / (m + rhoI q)``
with ``q = (pi/L)**2``:

>>> rayleigh = Beam("r", 1, 1, 1, left="pinned", right="pinned", theory="rayleigh",
...                 rhoI="1/100")
>>> namespace = {}
>>> exec(generate(Model((rayleigh,)), "python"), namespace)
>>> q = np.pi**2
>>> bool(abs(namespace["symtmm_delta"](np.array([1j * q / np.sqrt(1 + q / 100)]))[0]) < 1e-12)
True
"""

from __future__ import annotations

from .dialects import DIALECTS
from .names import argument_names, for_language
from .plan import plan as _plan  # the name plan stays the module's
from .walker import emit

__all__ = ["EXTENSIONS", "LANGUAGES", "generate"]

#: Languages :func:`generate` writes.
LANGUAGES = tuple(DIALECTS)
#: Usual file extension per language.
EXTENSIONS = {lang: "." + d.extension for lang, d in DIALECTS.items()}


def _argument_names(params, lang: str, used=()) -> list:
    """:func:`symtmm.codegen.names.argument_names` for the language called ``lang``.

    Examples
    --------
    >>> _argument_names(["I", "K", "x1"], "c"), _argument_names(["E", "K"], "fortran")
    (['p_I', 'K', 'x1'], ['p_E', 'K'])
    """
    return argument_names(params, DIALECTS[lang], used)


def generate(model, lang: str, symbolic=()) -> str:
    """Source code of a self-contained evaluator of ``Delta(lam)`` for ``model``.

    Parameters
    ----------
    model : Model
        Any beam theory (Euler–Bernoulli, Rayleigh, Timoshenko; axial force,
        Winkler foundation), point elements and rigid bodies or joints.
        Parameters without value (and those named in ``symbolic``) become
        extra arguments after ``lam``, in alphabetical order.
    lang : {"c", "fortran", "octave", "julia", "python"}
    symbolic : iterable of str
        Parameters to turn into arguments although the model gives them a
        value (that value then only orders the cuts).

    Returns
    -------
    str
        The source file.
    """
    if lang not in DIALECTS:
        raise ValueError(f"unknown language {lang!r} (use one of {', '.join(LANGUAGES)})")
    dialect = DIALECTS[lang]
    return emit(for_language(_plan(model, symbolic), dialect), dialect)
