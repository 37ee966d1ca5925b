"""Closed-form characteristic equations ``Delta = det R = 0``.

The variable
------------
Every plain Euler–Bernoulli beam ``j`` (no foundation, no axial force) has the
wave number ``beta_j = (-m_j lam**2 / EI_j)**(1/4)``. All of them are
expressed through one dimensionless frequency, the paper's ``Omega = beta_1
L_1`` of the first beam::

    beta_j = r_j Omega / L_1,   r_j = ((m_j / EI_j) / (m_1 / EI_1))**(1/4).

For an undamped model ``lam = i omega`` and ``Omega**4 = m_1 omega**2 L_1**4 / EI_1``;
the result is given in ``omega`` (circular frequency, rad/s, ``variable ==
"omega"``) and in ``Omega``. A damped model is given in ``lam`` itself
(``variable == "lam"``), through ``Omega = L_1 (m_1/EI_1)**(1/4) sqrt(I lam)``
(any branch gives the same ``Delta``).

Other beams (a Winkler foundation ``kw``, an axial force ``N``, rotary
inertia ``rhoI``, shear ``kGA``; :mod:`symtmm.elements.theories`) have two
wave numbers that are not proportional to ``Omega``: ``a_j`` (hyperbolic) and
``b_j`` (trigonometric), ``a_j**2`` and ``-b_j**2`` the eigenvalues ``r1, r2``
of ``G = B C`` (trace ``t_j``, determinant ``d_j``, functions of ``lam``)::

    a_j = sqrt(t_j/2 + sqrt(t_j**2/4 - d_j)),   b_j = sqrt(-t_j/2 + sqrt(t_j**2/4 - d_j))

(``a_j = b_j = (-d_j)**(1/4)`` when ``t_j = 0``: Euler–Bernoulli on a
foundation, ``b**4 = (m omega**2 - kw)/EI``). Beams with the same ``t, d``
share them. The closed form is written in these symbols (``a_<beam>``,
``b_<beam>``, named after the first beam of each kind) and ``Omega`` if
there are plain beams, with the frequency left in the coefficients;
:attr:`CharacteristicEquation.definitions` gives each symbol in the
model's variable and :attr:`~CharacteristicEquation.delta` has them
substituted. ``Delta`` is an entire function of every ``t_j, d_j``, so any
branch of the roots gives the same value.

Beams joined by a layer
-----------------------
Over a layer two Euler–Bernoulli beams are one member (:mod:`symtmm.elements.layer`):
``Y'''' = (X / l**4) Y`` with the ``2 x 2`` matrix ``X / l**4`` of trace ``t`` and
determinant ``d``. Its eigenvalues are ``p**4`` and ``q**4``, the roots of
``mu**2 - t mu + d``, and every block of the member's transfer matrix, a function
``f`` of ``X``, is ``f(p) E1 + f(q) E2`` with the projectors ``E1, E2 = 1/2 +- C``,
``C = (X/l**4 - t/2) / (p**4 - q**4)``: two beams of wave numbers ``p`` and ``q``
(``cos, sin, cosh, sinh`` of ``p l`` and ``q l``, powers of ``p, q`` and their
inverses) coupled through ``C`` (``C**2 = I/4``). The closed form is written in
``p_<a>_<b>``, ``q_<a>_<b>`` (after the two beams), defined like the waves' ``a, b``
(:attr:`CharacteristicEquation.definitions`; a note gives the quadratic). Where the
eigenvalues are polynomials (identical beams), one that is a constant times
``Omega**4`` is written in ``Omega``, one that is ``b**4`` of a beam on a foundation
in that ``b``, and mirrored identical beams are split into their in-phase and
out-of-phase families before the determinant is expanded: the in-phase family is
the single beam's. A layer between different beams over part of their length soon
exceeds the budgets; three beams joined over one stretch are refused (one line).

Rods
----
A rod (:func:`symtmm.model.rod`) vibrates axially with the wave number ``beta_u``,
``beta_u**2 = (m omega**2 - kw) / EA``, and in torsion with ``beta_t = omega
sqrt(rhoIp / GJ)``: its segments hold ``cos`` and ``sin`` of ``beta_u l`` and ``beta_t l``
only (the state scaled by ``diag(1, 1, GJ beta_t, EA beta_u)``), a spring on it enters as
``k / (EA beta_u)``. Without a foundation both are proportional to ``omega``: beside plain
beams they are written in ``Omega**2``, and in a model without plain beams ``Omega`` is
the first rod's ``beta_u L`` (``L sqrt(m/EA) omega``), so a fixed-free rod gives ``cos
Omega`` and a fixed-fixed one ``sin(Omega)/Omega``. On a foundation ``beta_u`` is the
symbol ``b_<rod>`` (:attr:`CharacteristicEquation.definitions`), shared by rods with the
same ``m/EA`` and ``kw/EA``. Beams and rods are never coupled: ``Delta`` is the product
of their parts. A rod without torsion (no ``GJ``, ``rhoIp``) leaves no factor of its twist.

>>> from symtmm.model import Model, Spring, rod
>>> pair = Model((rod("a", 1, 1, 1, right="free"), rod("b", 1, 1, 1, right="free")),
...              springs=(Spring("a", "b", "2/5", k=5),))
>>> characteristic_equation(pair).delta
(omega*cos(omega) - 5*sin(omega/5) + 5*sin(omega))*cos(omega)/omega

The form
--------
``det R = constant * Omega**power * prod(f_i**e_i)`` where the constant does
not depend on the frequency (it is dropped from :attr:`~CharacteristicEquation.delta`
and kept in :attr:`~CharacteristicEquation.constant`), ``Omega**power`` carries
the roots at zero (rigid-body modes) and cancels the spurious ones of the
transcendental factors, and the factors ``f_i`` are sums of products of
trigonometric and hyperbolic functions; a repeated factor (``e_i > 1``)
exposes roots of that multiplicity. A clamped-clamped beam gives
``Omega**-4 (cos Omega cosh Omega - 1)``. A negative ``e_i`` (only
``a_j**2 + b_j**2`` and its kin) is a denominator.

How it is computed
------------------
Exactly, without simplifying general SymPy expressions, which is what makes
multilevel models tractable:

1. The state of a plain level ``j`` is scaled by ``diag(1, beta_j, EI_j
   beta_j**2, EI_j beta_j**3)``; the transfer matrix of a segment of length
   ``l`` then has the entries ``S, T, U, V`` of ``beta_j l`` only, and a
   spring enters as ``k / (EI_a beta_a**3)``. A rigid body's virtual
   variables are scaled like the beam variables they stand for
   (``Layout.units``), so its equations have constant coefficients.
2. ``c, s, ch, sh = cos, sin, cosh, sinh`` of each distinct argument
   ``beta_j l`` are independent variables of a polynomial ring over the
   rationals (with ``W = 1/Omega``, ``Omega`` and the symbolic parameters),
   reduced with ``s**2 = 1 - c**2`` and ``sh**2 = ch**2 - 1``. An
   Euler–Bernoulli beam on a foundation (``a = b``) is scaled the same way
   with its own ``b`` (and ``1/b``) in place of ``beta``. The other beams
   bring per segment ``c = cos(b l)``, ``Sn = sin(b l)/b``, ``ch = cosh(a l)``,
   ``Sh = sinh(a l)/a`` and per kind of beam ``Dl = a**2 + b**2`` and ``iq =
   1/Dl**2``: with ``a**2 = (t + Dl)/2``, ``b**2 = (Dl - t)/2`` and
   ``Dl**2 = t**2 - 4 d`` (a polynomial in ``Omega``) the segment matrix
   ``exp(A l) = [[F0(G), B F1(G')], [C F1(G), F0(G')]]`` with ``f(G) = alpha I +
   beta G``, ``beta = (f(a**2) - f(-b**2))/Dl``, is polynomial, and the
   reductions ``c**2 = 1 - b**2 Sn**2``, ``ch**2 = 1 + a**2 Sh**2``,
   ``Dl**2 = t**2 - 4 d`` (leading terms in distinct variables: a normal form)
   keep it so. The columns of the unknowns are propagated through the cuts.
3. Entries of ``R`` that are nonzero rational constants (a body's
   compatibility and equilibrium) are eliminated first, exactly (Schur
   complement, the pivot and sign kept), so bodies and joints cost about as
   much as the beams they join. ``det R`` of the rest is expanded by minors
   (no division), factored over the rationals, ``iq = 1/Dl**2`` cleared, each
   factor reduced again and refactored. Factoring before the reduction keeps
   products intact: identical beams coupled symmetrically give one factor per
   mode family.
4. Each factor is written back either as a polynomial in the segment
   functions or, by product-to-sum, with combined arguments (``sin Omega``
   rather than ``2 cos(a)**2 sin(b) + ...``), whichever has fewer operations.

One module per step: :mod:`~symtmm.characteristic.order` (the order of the
cuts when positions are symbolic), :mod:`~symtmm.characteristic.problem`
(step 1), :mod:`~symtmm.characteristic.ring` and
:mod:`~symtmm.characteristic.algebra` (step 2),
:mod:`~symtmm.characteristic.determinant` and
:mod:`~symtmm.characteristic.factor` (step 3),
:mod:`~symtmm.characteristic.writer` (step 4) and
:mod:`~symtmm.characteristic.equation` (the result, in ``Omega`` and in the
model's variable).

Examples
--------
>>> from symtmm.model import Beam, Model
>>> cc = Model((Beam("b", EI=1, m=1, L=1, left="clamped", right="clamped"),))
>>> eq = characteristic_equation(cc)
>>> eq.variable, eq.delta_Omega
(omega, (cos(Omega)*cosh(Omega) - 1)/Omega**4)
>>> eq.delta
(cos(sqrt(omega))*cosh(sqrt(omega)) - 1)/omega**2

On a Winkler foundation the same equation holds in ``b**4 = (m omega**2 - kw)/EI``:

>>> w = Model((Beam("b", EI=1, m=1, L=1, kw=10, left="clamped", right="clamped"),))
>>> eq = characteristic_equation(w)
>>> eq.equation
cos(b_b)*cosh(b_b) - 1
>>> eq.definitions
{b_b: (omega**2 - 10)**(1/4)}
"""

from __future__ import annotations

from .equation import CharacteristicEquation, characteristic_equation
from .order import _check_order, _prepare  # noqa: F401  (symtmm.codegen.plan orders its cuts so)
from .problem import OMEGA, OMEGA_DIMLESS

__all__ = ["OMEGA", "OMEGA_DIMLESS", "CharacteristicEquation", "characteristic_equation"]
