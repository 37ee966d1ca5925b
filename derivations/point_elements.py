"""Lumped mass with rotary inertia and rotational springs, derived from the field equation.

A point force ``F`` and a point couple ``C`` (positive like a positive
rotation) at ``x0`` enter the beam equation as
``EI Y'''' + m lam**2 Y = F delta(x - x0) - C delta'(x - x0)``. Integrating
once over ``(x0 - eps, x0 + eps)`` gives the shear jump ``Q+ - Q- = F``;
virtual work (``[M dTheta - Q dY]`` between the ends of a piece) gives
the moment jump ``M+ - M- = -C``. ``Y`` and ``Theta`` are continuous.

* Lumped mass ``M`` with rotary inertia ``J``: d'Alembert's inertia force and
  couple are ``F = -M lam**2 Y`` and ``C = -J lam**2 Theta``.
* Rotational spring/dashpot to the ground: ``C = -(k + c lam) Theta``.
* Rotational spring/dashpot between levels a and b: ``C_a = (k + c lam)(Theta_b -
  Theta_a)``, ``C_b = -C_a``.

The jumps, solved for the state right of the cut, must equal the library's
transfer matrices (which it builds from the nodal stiffness ``S(lam)``), and
an elastic end support (a spring to the ground at a free end) must give the
classical boundary conditions ``EI Y'''(0) = -k Y(0)``, ``EI Y''(0) = k_r Y'(0)``.

Run: ``python derivations/point_elements.py``.
"""

import sympy as sp

from symtmm.assembly import boundary_matrix
from symtmm.elements import LumpedMass, RotationalCoupling, RotationalGroundSpring
from symtmm.model import Beam, Model, Spring

lam, x, x0, eps = sp.symbols("lam x x0 epsilon")
M, J, k, c, EI = sp.symbols("M J k c EI", positive=True)
F = sp.Symbol("F")

# The moment jump follows from virtual work: the beam's end actions do the work
# [M dTheta - Q dY] between the ends of a piece, so a couple C doing C dTheta at x0
# balances M+ - M- = -C, as a force F doing F dY balances Q+ - Q- = F (checked below
# against the delta function for the force).
Qjump = sp.integrate(sp.DiracDelta(x - x0) * F, (x, x0 - eps, x0 + eps))
assert sp.simplify(Qjump.subs(eps, sp.Rational(1, 10))) == F  # any eps > 0

Y, Th, Mm, Q = sp.symbols("Y Theta M Q")
Yb, Thb, Mb, Qb = sp.symbols("Y_b Theta_b M_b Q_b")


def after(state, force, couple):
    """State right of a cut carrying a point force and couple on one level."""
    y, th, mm, q = state
    return sp.Matrix([y, th, mm - couple, q + force])


def matrix_of(vec, states):
    return vec.jacobian(states)


# lumped mass
z = sp.Matrix([Y, Th, Mm, Q])
derived = matrix_of(after(z, -M * lam**2 * Y, -J * lam**2 * Th), z)
assert sp.simplify(derived - LumpedMass("a", M, J).transfer_matrix(lam)) == sp.zeros(4)

# rotational spring/dashpot to the ground
derived = matrix_of(after(z, 0, -(k + c * lam) * Th), z)
assert sp.simplify(derived - RotationalGroundSpring("a", k, c).transfer_matrix(lam)) == sp.zeros(4)

# rotational spring/dashpot between two levels
Ca = (k + c * lam) * (Thb - Th)
zz = sp.Matrix([Y, Th, Mm, Q, Yb, Thb, Mb, Qb])
derived = matrix_of(sp.Matrix(list(after(z, 0, Ca)) + list(after(zz[4:, 0], 0, -Ca))), zz)
assert sp.simplify(derived - RotationalCoupling("a", "b", k, c).transfer_matrix(lam)) \
    == sp.zeros(8)

# elastic end supports: a free-free beam with translational and rotational springs at x = 0
# and a rigid body (lam = 0): the static boundary matrix must impose EI Y'''(0) = -k Y(0),
# EI Y''(0) = kr Y'(0) at the left end (the free end's zero M, Q hold left of the springs)
kr = sp.Symbol("kr", positive=True)
model = Model((Beam("a", 1, 1, 1, left="free", right="free"),),
              (Spring("a", "ground", 0, "k"), Spring("a", "ground", 0, "kr", kind="rotational")),
              {"k": None, "kr": None})
R0 = boundary_matrix(model, lam=0)
# state right of the support cut, from the unknowns (Y0, Theta0): M = kr Theta0, Q = -k Y0;
# the static beam carries them to x = 1, where M(1) = Q(1) = 0 is R0 @ (Y0, Theta0)
Mr = kr * Th + (-k * Y) * 1       # M(1) = M(0) + Q(0) * 1  (static: M' = Q)
Qr = -k * Y
expected = sp.Matrix([Mr, Qr]).jacobian([Y, Th])
ks = {sp.Symbol("k", positive=True): k, sp.Symbol("kr", positive=True): kr}
assert sp.simplify(R0.xreplace(ks) - expected) == sp.zeros(2)
print("point elements: lumped mass, rotational springs and elastic supports agree")
