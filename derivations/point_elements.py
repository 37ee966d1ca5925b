"""Lumped mass with rotary inertia and rotational springs, derived from the field equation.

A point force ``F`` and a point couple ``C`` (positive like a positive
rotation) at ``x0`` do the work ``F Y(x0) + C Theta(x0)``. The first
variation of the potential energy ``int EI Y''**2 / 2 - F Y(x0) - C Theta(x0)``
vanishes for every virtual displacement (continuous with its slope) only if
the shear jumps by ``Q+ - Q- = F`` and the moment by ``M+ - M- = -C``: both
are derived below, with ``Y`` and ``Theta`` continuous. (Inertia and springs
act as forces and couples of this kind at the point.)

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

# The jumps from the first variation of the potential energy. Static pieces left
# (-1 < x < 0) and right (0 < x < 1) of the point x0 = 0 are cubics; the virtual
# displacements are quintics continuous with their slope at 0 and vanishing with their
# slope at the outer ends.
xs = sp.Symbol("x", real=True)
ca, cb = sp.symbols("a0:4"), sp.symbols("b0:4")
YL, YR = (sum(c[i] * xs**i for i in range(4)) for c in (ca, cb))
pa, pb = sp.symbols("p0:6"), sp.symbols("q0:6")
eL, eR = (sum(c[i] * xs**i for i in range(6)) for c in (pa, pb))
admissible = sp.solve([eL.subs(xs, -1), eL.diff(xs).subs(xs, -1), eR.subs(xs, 1),
                       eR.diff(xs).subs(xs, 1), (eL - eR).subs(xs, 0),
                       (eL - eR).diff(xs).subs(xs, 0)], pa[:3] + pb[:3], dict=True)[0]
eL, eR = eL.subs(admissible), eR.subs(admissible)
C = sp.Symbol("C")
variation = sp.expand(sp.integrate(EI * YL.diff(xs, 2) * eL.diff(xs, 2), (xs, -1, 0))
                      + sp.integrate(EI * YR.diff(xs, 2) * eR.diff(xs, 2), (xs, 0, 1))
                      - F * eL.subs(xs, 0) - C * eL.diff(xs).subs(xs, 0))
free_shapes = [v for v in pa + pb if v not in admissible]
equilibrium = sp.solve([variation.coeff(v) for v in free_shapes], [ca[2], ca[3]], dict=True)[0]


def _jump(order):
    """EI Y^(order) right of x0 minus left of it, at equilibrium."""
    return sp.simplify((EI * YR.diff(xs, order) - EI * YL.diff(xs, order)).subs(xs, 0)
                       .subs(equilibrium))


assert _jump(3) == F     # Q+ - Q- = F
assert _jump(2) == -C    # M+ - M- = -C

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
