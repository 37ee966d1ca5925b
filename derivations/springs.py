"""Transfer matrices of the spring/dashpot elements, derived from force balance.

A point force ``F`` (positive in +Y) acting at ``x0`` enters the field
equation as ``EI Y'''' + m lam**2 Y = F delta(x - x0)``. Integrating over
``(x0 - eps, x0 + eps)`` and letting ``eps -> 0``: ``Y, Theta, M`` are
continuous and the shear ``Q = EI Y'''`` jumps by ``Q+ - Q- = F``.

* Coupling of levels a and b by a spring ``k`` and a dashpot ``c`` in
  parallel: the force on ``a`` is ``F = (k + c lam)(Y_b - Y_a)`` (it pulls
  ``a`` towards ``b``), the force on ``b`` is ``-F``.
* Spring/dashpot from level a to the ground: ``F = -(k + c lam) Y_a``.

The jump conditions are solved for the state right of the cut; the
resulting matrices must equal ``Coupling(...).transfer_matrix(lam)`` and
``GroundSpring(...).transfer_matrix(lam)``, and the overall transfer matrix
assembled by ``symtmm.assembly`` must contain them at the cut.

Run: ``python derivations/springs.py``.
"""

import sympy as sp

from symtmm.assembly import overall_transfer_matrix
from symtmm.elements import Coupling, GroundSpring
from symtmm.model import Beam, Model, Spring

lam, x, x0, eps, F = sp.symbols("lam x x0 epsilon F")
k, c = sp.symbols("k c", positive=True)

# the jump of Q from the field equation with a point force
jump = sp.integrate(F * sp.DiracDelta(x - x0), (x, x0 - eps, x0 + eps))
assert sp.simplify(jump.subs(eps, sp.Rational(1, 10))) == F  # any eps > 0


def states(name):
    return sp.Matrix(sp.symbols(f"Y_{name} Theta_{name} M_{name} Q_{name}"))


def solve_cut(left: sp.Matrix, forces: list) -> sp.Matrix:
    """Right state from continuity of Y, Theta, M and Q+ = Q- + F per level."""
    right = []
    for level, force in enumerate(forces):
        Y, Th, M, Q = left[4 * level:4 * level + 4]
        right += [Y, Th, M, Q + force]
    return sp.Matrix(right).jacobian(left)


# coupling a-b
za, zb = states("a"), states("b")
left = sp.Matrix.vstack(za, zb)
kc = k + c * lam
force_on_a = kc * (zb[0] - za[0])
derived = solve_cut(left, [force_on_a, -force_on_a])
library = Coupling("a", "b", k, c).transfer_matrix(lam)
assert sp.expand(derived - library) == sp.zeros(8, 8), derived - library

# ground spring on a
derived_ground = solve_cut(za, [-kc * za[0]])
library_ground = GroundSpring("a", k, c).transfer_matrix(lam)
assert sp.expand(derived_ground - library_ground) == sp.zeros(4, 4)

# Newton's third law: the coupling transmits no net force, so with both
# levels displaced alike (rigid translation) the shears are unchanged
rigid = left.subs({zb[0]: za[0]})
assert sp.expand(derived * rigid - rigid) == sp.zeros(8, 1)

# in an assembled model, the overall transfer matrix of two zero-length
# stretches around the cut is the coupling matrix itself: compare a model
# with the spring at the very left end (x = 0), where nothing precedes it
beams = (Beam("a", 1, 1, 1, left="free", right="free"),
         Beam("b", 1, 1, 1, left="free", right="free"))
with_spring = overall_transfer_matrix(Model(beams, (Spring("a", "b", 0, 5, 2),)), lam=lam)
without = overall_transfer_matrix(Model(beams), lam=lam)
expected = without * Coupling("a", "b", 5, 2).transfer_matrix(lam)
assert sp.expand(with_spring - expected) == sp.zeros(8, 8)

print("spring/dashpot coupling and ground spring: transfer matrices from force balance "
      "equal the library's.")
print("coupling, row Q_a:", list(library[3, :]))
