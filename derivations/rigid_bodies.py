"""Rigid bodies on beams and joints of beam ends: compatibility and equations of motion.

A rigid body (mass ``M``, rotary inertia ``J`` about its centre of mass at ``xc``)
moves in the plane of the beams with small displacement ``Y(x) = Y_c + (x - xc)
Theta_c``. It holds beam ``j`` at ``x_i`` (arm ``d_i = x_i - xc``): the beam's ``Y``
there is the body's, and so is its rotation ``Theta`` unless the attachment is a hinge.
The constraint forces are the Lagrange multipliers of those conditions: ``F_i`` and
``C_i``, the force and couple the body exerts on the beam. Derived here, each step
asserted:

1. the kinetic energy of a rigid body of any mass distribution is ``(M Y_c_t**2 + J
   Theta_c_t**2)/2`` about its centre of mass (the cross term vanishes there);
2. the stationarity of ``Pi = lam**2 T(lam -> 1) - sum F_i (Y_j(x_i) - Y_c - d_i
   Theta_c) - sum C_i (Theta_j(x_i) - Theta_c)`` (frequency domain, ``V - omega**2
   T_max``) gives the compatibility conditions, the equations of motion ``M lam**2 Y_c +
   sum F_i = 0`` and ``J lam**2 Theta_c + sum (d_i F_i + C_i) = 0`` (the same as
   d'Alembert's, the body pushed by the beams' reactions ``-F_i, -C_i``), and on the
   beam the work of a point force ``F_i`` and couple ``C_i``: by the jumps derived in
   ``derivations/point_elements.py``, ``Q+ - Q- = F_i`` and ``M+ - M- = -C_i``;
3. these are the terms :class:`symtmm.assembly.Layout` generates (``_body_terms_at``):
   for a body with rigid and hinged attachments on two beams, at symbolic ``M, J,
   xc``, the beams' jump entries are equal and each accumulator is the derived equation
   (up to a constant factor); a body whose rotation nothing fixes or feels (hinges at
   ``xc``, ``J = 0``) has no rotation unknown;
4. limits: a body held rigidly at its centre of mass is a lumped mass with rotary
   inertia (same ``det R`` up to sign, to 30 digits); the tip body of a cantilever, its
   centre of mass ``e`` beyond the tip, gives the classical end conditions ``EI Y'''(L)
   = -omega**2 M (Y + e Y')`` and ``EI Y''(L) = omega**2 (J Y' + M e (Y + e Y'))``,
   which the Lagrangian of beam and body with ``Y_c = Y(L) + e Y'(L)`` also gives.

Run: ``python derivations/rigid_bodies.py``.
"""

import mpmath
import sympy as sp

from symtmm.assembly import Layout, Station, boundary_matrix
from symtmm.elements.base import LAM
from symtmm.expr import parameter_symbol
from symtmm.model import Attachment, Beam, Mass, Model, RigidBody

lam = LAM
t, xi, a, b = sp.symbols("t xi a b", real=True)
M, J = (parameter_symbol(n) for n in ("M", "J"))
xc = parameter_symbol("xc")

# -- 1. kinetic energy of a rigid body about its centre of mass ------------------------------
rho = sp.Function("rho")                      # mass per unit of the body's coordinate xi
Yc, Tc = sp.Function("Y_c")(t), sp.Function("Theta_c")(t)
velocity = Yc.diff(t) + xi * Tc.diff(t)      # of the body's point at xi from the centre
# T = int rho(xi) velocity**2 / 2 over the body: by linearity, the moments of rho times
# the coefficients of the polynomial velocity**2 / 2 in xi
coefficients = sp.Poly(sp.expand(velocity**2 / 2), xi).all_coeffs()[::-1]
moments = {k: sp.Integral(rho(xi) * xi**k, (xi, a, b)) for k in range(3)}
T_body = sum(c * moments[k] for k, c in enumerate(coefficients))
assert sp.expand(sum(c * rho(xi) * xi**k for k, c in enumerate(coefficients))
                 - rho(xi) * velocity**2 / 2) == 0
# the centre of mass: the first moment vanishes; M and J are the zeroth and second
T_body = T_body.subs({moments[1]: 0, moments[0]: M, moments[2]: J})
assert sp.expand(T_body - (M * Yc.diff(t)**2 + J * Tc.diff(t)**2) / 2) == 0

# -- 2. the stationarity conditions ----------------------------------------------------------
# attachments: (label, beam, x, hinged)
ATTACH = [("a", "a", sp.Rational(2, 5), False),
          ("b", "b", sp.Rational(1, 2), True),
          ("a1", "a", sp.Integer(1), False)]
Y_c, Th_c = sp.symbols("Y_c Theta_c")
beam_Y = {lab: sp.Symbol(f"Y_{lab}") for lab, *_ in ATTACH}
beam_T = {lab: sp.Symbol(f"Theta_{lab}") for lab, *_ in ATTACH}
F = {lab: sp.Symbol(f"F_{lab}") for lab, *_ in ATTACH}
C = {lab: sp.Symbol(f"C_{lab}") for lab, *_ in ATTACH}
arm = {lab: x - xc for lab, _, x, _ in ATTACH}
Pi = lam**2 * (M * Y_c**2 + J * Th_c**2) / 2
for lab, _, _, hinged in ATTACH:
    Pi -= F[lab] * (beam_Y[lab] - Y_c - arm[lab] * Th_c)
    if not hinged:
        Pi -= C[lab] * (beam_T[lab] - Th_c)
force_eq, moment_eq = Pi.diff(Y_c), Pi.diff(Th_c)
assert sp.expand(force_eq - (M * lam**2 * Y_c + sum(F.values()))) == 0
rigid = [lab for lab, _, _, h in ATTACH if not h]
assert sp.expand(moment_eq - (J * lam**2 * Th_c + sum(arm[k] * F[k] for k in F)
                              + sum(C[k] for k in rigid))) == 0
compatibility = {("Y", lab): -Pi.diff(F[lab]) for lab in F}
compatibility.update({("Theta", lab): -Pi.diff(C[lab]) for lab in rigid})
# d'Alembert: the body's acceleration (lam**2 times its displacement) equals the forces
# on it, the reactions -F_i, -C_i, with their moments about the centre of mass
newton = M * lam**2 * Y_c - sum(-F[k] for k in F)
euler = J * lam**2 * Th_c - (sum(-arm[k] * F[k] for k in F) + sum(-C[k] for k in rigid))
assert sp.expand(newton - force_eq) == 0 and sp.expand(euler - moment_eq) == 0
# on the beam: Pi contains -F_i Y_j(x_i) - C_i Theta_j(x_i), the potential of a point force
# F_i and a point couple C_i; point_elements.py derives Q+ - Q- = F, M+ - M- = -C from it
for lab, force in F.items():
    assert Pi.diff(beam_Y[lab]) == -force
    assert Pi.diff(beam_T[lab]) == (0 if lab not in rigid else -C[lab])

# -- 3. the layout's terms ---------------------------------------------------------------------
beams = (Beam("a", 1, 1, 1, left="clamped", right="free"),
         Beam("b", 1, 1, 1, x0="1/2", left="free", right="pinned"))
body = RigidBody("body", tuple(Attachment(beam, x, h) for _, beam, x, h in ATTACH),
                 M="M", J="J", xc="xc")
model = Model(beams, (), {"M": None, "J": None, "xc": None}, bodies=(body,))
layout = Layout(model)
(bl,) = layout.bodies
level = {"a": 0, "b": 1}
unknown_symbol = {bl.unknowns["Y"]: Y_c, bl.unknowns["Theta"]: Th_c}
for i, (lab, *_rest) in enumerate(ATTACH):
    unknown_symbol[bl.unknowns[("F", i)]] = F[lab]
    if ("C", i) in bl.unknowns:
        unknown_symbol[bl.unknowns[("C", i)]] = C[lab]
state_names = ("Y", "Theta", "M", "Q")
accumulated = {row: 0 for row in bl.equations.values()}
jumps = {}                                     # (beam, x, variable) -> jump
for step in layout.steps:
    if not isinstance(step, Station):
        continue
    for row, col, value in step.terms:
        if col in unknown_symbol:
            source = unknown_symbol[col]
        else:
            lvl, var = divmod(col, 4)
            name = beams[lvl].name
            (lab,) = [k for k, beam, x, _ in ATTACH if beam == name and x == step.x]
            source = {"Y": beam_Y, "Theta": beam_T}[state_names[var]][lab]
        if row in accumulated:
            accumulated[row] += value * source
        else:
            assert row < 4 * layout.levels, "a body writes only beams and its accumulators"
            lvl, var = divmod(row, 4)
            key = (beams[lvl].name, step.x, state_names[var])
            jumps[key] = jumps.get(key, 0) + value * source


def proportional(p, q):
    """``p = c q`` for a non-zero number ``c`` (an equation may be scaled)."""
    ratio = sp.simplify(p / q)
    return ratio.is_number and ratio != 0


derived = {("Y", i): compatibility[("Y", lab)] for i, (lab, *_r) in enumerate(ATTACH)}
derived.update({("Theta", i): compatibility[("Theta", lab)]
                for i, (lab, *_r) in enumerate(ATTACH) if lab in rigid})
derived["force"], derived["moment"] = force_eq, moment_eq
assert set(derived) == set(bl.equations)
for label, row in bl.equations.items():
    assert proportional(sp.expand(accumulated[row]), sp.expand(derived[label])), label
expected_jumps = {}
for lab, beam, x, hinged in ATTACH:
    expected_jumps[(beam, x, "Q")] = F[lab]            # Q+ - Q- = F
    if not hinged:
        expected_jumps[(beam, x, "M")] = -C[lab]       # M+ - M- = -C
assert {k: sp.expand(v) for k, v in jumps.items()} == expected_jumps

# a pin joint of beam ends (hinges at xc, J = 0): nothing fixes or feels the rotation
pin = RigidBody("pin", (Attachment("a", 1, True), Attachment("b", 1, True)))
(pin_layout,) = Layout(Model((beams[0], Beam("b", 1, 1, 1, x0=1)), bodies=(pin,))).bodies
assert "Theta" not in pin_layout.unknowns and "moment" not in pin_layout.equations
Pi_pin = -sum(sp.Symbol(f"F{i}") * (sp.Symbol(f"Y{i}") - Y_c) for i in range(2))
assert Pi_pin.diff(Th_c) == 0                  # Theta_c would be an undetermined unknown

# -- 4a. a body held rigidly at its centre of mass is a lumped mass ------------------------
carried = Beam("c", 1, 1, 1, left="clamped", right="free")
point = sp.Rational(3, 5)
with_body = Model((carried,), bodies=(RigidBody("m", (Attachment("c", point),), M=2,
                                                J=sp.Rational(1, 10)),))
with_mass = Model((carried,), masses=(Mass("c", point, 2, sp.Rational(1, 10)),))
with mpmath.workdps(30):
    for lam_value in (sp.I * 3, sp.Rational(-1, 2) + sp.I * 7):
        d_body = boundary_matrix(with_body, lam_value).evalf(30).det()
        d_mass = boundary_matrix(with_mass, lam_value).evalf(30).det()
        assert min(abs(d_body - d_mass), abs(d_body + d_mass)) < 1e-25 * abs(d_mass)

# -- 4b. the tip body of a cantilever ------------------------------------------------------
e, EI, L = sp.symbols("e EI L", positive=True)
Yt, Tt, Mt, Qt, w2 = sp.symbols("Y Theta M_tip Q_tip omega2")
# the body's equations at the tip, xc = L + e (arm d = -e); free beyond: Q+ = M+ = 0
Fv, Cv, Ycv, Tcv = sp.symbols("F C Y_cv Theta_cv")
d = -e
equations = [Yt - Ycv - d * Tcv, Tt - Tcv,                          # compatibility
             M * lam**2 * Ycv + Fv, J * lam**2 * Tcv + d * Fv + Cv,  # motion
             Qt + Fv, Mt - Cv]                                       # Q+ = Q- + F = 0, M+ = 0
solution = sp.solve(equations, [Fv, Cv, Ycv, Tcv, Qt, Mt], dict=True)[0]
tip_Q = solution[Qt].subs(lam**2, -w2)           # Q = EI Y''' at the tip (rigid in shear)
tip_M = solution[Mt].subs(lam**2, -w2)           # M = EI Y''
assert sp.expand(tip_Q - (-w2 * M * (Yt + e * Tt))) == 0
assert sp.expand(tip_M - w2 * (J * Tt + M * e * (Yt + e * Tt))) == 0
# the Lagrangian of beam and body: the beam's boundary term [M dTheta - Q dY] at the tip
# (its first variation, integrated by parts) balances the body's -omega**2 dT_max
dY, dT = sp.symbols("dY dTheta")
Ybody = Yt + e * Tt
T_max = (M * Ybody**2 + J * Tt**2) / 2
first_variation = sp.expand(Mt * dT - Qt * dY - w2 * (T_max.diff(Yt) * dY + T_max.diff(Tt) * dT))
natural = sp.solve([first_variation.coeff(dY), first_variation.coeff(dT)], [Qt, Mt], dict=True)[0]
assert sp.expand(natural[Qt] - tip_Q) == 0 and sp.expand(natural[Mt] - tip_M) == 0

print("rigid bodies: kinetic energy about the centre of mass, compatibility and equations of "
      "motion by Lagrange multipliers (= d'Alembert) equal the layout's body terms; a body at "
      "its centre of mass is a lumped mass; the tip-body end conditions follow")
