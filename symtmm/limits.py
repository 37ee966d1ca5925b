"""The limits symtmm puts on its input, in one place.

Every input has a defined outcome: a result, or one line naming the file, the
field and the problem. The limits below keep inputs that the exact arithmetic,
double precision or the time and memory of one run cannot honour from reaching
the code that computes; each is checked where the input enters (the expression
parser, the model, the command line) before any work is done. The README's
model-file section and ``docs/elements.md`` state them for users.

Why these values:

* Expressions are short formulas (``"sqrt(EI/m)/pi**2"``). 1000 characters and
  32 levels of nesting are far beyond them and keep the parser's recursion and
  SymPy's (which follows the depth of a tree) well inside Python's stack.
* Every number written in an expression, and every value computed on the way,
  lies within ``10**-300 .. 10**300``: the range of a double, so that exact
  arithmetic never builds numbers of millions of digits (``1e-999999``,
  ``((2**999)**999)**999``, ``2**e`` with ``e = 10**9``) and every value has a
  double to become.
* Numeric fields of a model (``EI``, ``m``, ``L``, ``k``, ``x``, ...) are 0 (where
  allowed) or of magnitude ``1e-30 .. 1e30``. Products and quotients of a
  handful of them, and the frequencies they make (``omega**2 ~ EI / (m L**4)``
  within ``1e±180``), stay inside the double range the numeric searches work
  in, while SI values from nanobeams (``EI ~ 1e-25``) to bridges (``EI ~
  1e12``, ``k ~ 1e10``) are all admitted.
* Model size: the transfer matrices, the stiffness count and above all the
  closed form grow with the beams and the points where something is attached;
  the budgets are well above any model in the examples and the paper.
* Command-line values: ``--count`` and the eigenvalues below ``--omega-max`` at
  most 1000 (the working precision grows with the highest mode; the searches
  cannot reach beyond about that), ``--digits`` at most 500 (the undamped
  refinement stops converging between 700 and 1000 digits, within its cap on
  the working precision).
* ``derive`` expands a determinant symbolically; its size can explode with
  the number of beams and distinct segments. A budget on the terms of any
  polynomial (a proxy for memory) and on the seconds spent turns an explosion
  into a one-line error.
"""

from __future__ import annotations

__all__ = [
    "MAX_EXPRESSION_LENGTH", "MAX_NESTING", "MAX_DECADES", "MAX_EXPONENT", "FIELD_MIN",
    "FIELD_MAX", "MAX_PARAMETER_DEPTH", "MAX_FILE_BYTES", "MAX_BEAMS", "MAX_POINTS_ON_BEAMS",
    "MAX_PARAMETERS", "MAX_EIGENVALUES", "MAX_DIGITS", "MAX_GRID_POINTS", "MAX_STEPS",
    "MAX_JOBS", "FLAG_MAX", "SEARCH_SECONDS", "DERIVE_SECONDS", "DERIVE_TERMS",
    "FACTOR_TERMS", "MAX_PIECES",
]

# -- expressions (symtmm.expr) ---------------------------------------------------------
#: Longest expression text, in characters.
MAX_EXPRESSION_LENGTH = 1000
#: Deepest nesting of parentheses, signs, powers and functions in one expression, and
#: the deepest expression tree a field may resolve to through its parameters.
MAX_NESTING = 32
#: Every number in an expression lies within 10**-MAX_DECADES .. 10**MAX_DECADES.
MAX_DECADES = 300
#: Largest integer exponent ``n`` in ``a**n``.
MAX_EXPONENT = 1000

# -- models (symtmm.model, symtmm.modelfile) ----------------------------------------------
#: Smallest nonzero magnitude of a numeric field.
FIELD_MIN = 1e-30
#: Largest magnitude of a numeric field.
FIELD_MAX = 1e30
#: Longest chain of parameters defined through each other (``a = "b"``, ``b = "c"``, ...).
MAX_PARAMETER_DEPTH = 32
#: Largest model file, in bytes.
MAX_FILE_BYTES = 1_000_000
#: Most levels (beams and rods) in one model; a member of a planar frame is two (its
#: bending and its axial motion), so a frame has at most 100 extensible members.
MAX_BEAMS = 200
#: Most springs, masses and rigid-body attachments together.
MAX_POINTS_ON_BEAMS = 1000
#: Most parameters.
MAX_PARAMETERS = 1000

# -- command line --------------------------------------------------------------------------
#: Most eigenvalues one search delivers (``--count``, and those below ``--omega-max``).
MAX_EIGENVALUES = 1000
#: Most significant digits (``--digits``).
MAX_DIGITS = 500
#: Most digits a mode shape's transfer walk is taken in (the digits asked, and those its
#: columns lose to the growth of the waves along the beams, about ``sum |beta| L / ln 10``:
#: a Timoshenko beam of kGA = 8e-4 on a foundation would have asked 50,000, and one
#: series of its matrices had run for minutes, uninterruptible).
MAX_WALK_DIGITS = 2000
#: Most grid points (``--points`` of modes and scan).
MAX_GRID_POINTS = 100_000
#: Most parameter values of a sweep (``--steps``).
MAX_STEPS = 10_000
#: Most local worker processes (``--jobs``).
MAX_JOBS = 1024
#: Most pieces the dynamic-stiffness mesh may cut the beams into for one frequency range.
#: A piece keeps ``|beta| l <= 3``: a foundation or layer far stiffer than the beam's
#: bending (``kw L**4 / EI ~ 1e30``) would need ten million pieces (and minutes of exact
#: arithmetic before the first evaluation); the paper's examples need a few dozen, a
#: 50-level chain about 550.
MAX_PIECES = 100_000
#: Largest frequency or decay rate on the command line (rad/s): ``omega**2`` of every
#: model within the field limits stays a double.
FLAG_MAX = 1e100

#: Default time budget of one search (``solve``, ``modes``, each step of ``sweep``), in
#: seconds (``--max-seconds``; :mod:`symtmm.deadline`). The paper's examples take 0.01-0.3 s
#: and a 50-level chain 0.2 s; a beam of ``kw L**4 / EI ~ 1e25`` beside ordinary ones
#: (tens of thousands of pieces, a cluster of eigenvalues 1e-16 apart to count at
#: thousands of bits) took minutes before it said it could not.
SEARCH_SECONDS = 60.0

# -- derive (symtmm.characteristic) ------------------------------------------------------
#: Default time budget of one closed-form derivation, in seconds (``--max-seconds``).
DERIVE_SECONDS = 60.0
#: Most terms of any polynomial while deriving a closed form. Measured: the paper's
#: example 4 needs between 400 000 and 1 000 000 and peaks at 0.23 GB; the derivation
#: that once grew to 10 GB (a Rayleigh beam with a damped rotational spring) stops at
#: this budget after 1.7 s and 0.42 GB.
DERIVE_TERMS = 1_000_000
#: Most terms of a polynomial a derivation factors (python-flint's factorisation cannot be
#: interrupted). Measured on the examples and 40 random models: 10 000 to 98 250 terms
#: (the largest, an example's) in 0.27 to 4.4 s; a random model's determinant of 352 484
#: terms in 37 variables ran for over five minutes of a five-second budget.
FACTOR_TERMS = 120_000
