"""Beam segments beyond Euler–Bernoulli: axial force, rotary inertia (Rayleigh), shear (Timoshenko).

Energy per unit length (free vibration ``e^{lam t}``; derived in
``derivations/beam_theories.py``)::

    strain:   EI psi'**2 + kGA (Y' - psi)**2 + N Y'**2 + kw Y**2      (halved)
    kinetic:  m Y_t**2 + rhoI psi_t**2                                (halved)

``psi`` is the rotation of the cross-section, ``kGA`` the shear stiffness
(``kappa G A``; ``None`` for a beam rigid in shear, where ``psi = Y'``),
``rhoI`` the rotary inertia per unit length, ``N`` the axial force (tension
positive, a dead load along the undeformed axis) and ``kw`` a Winkler
foundation. The state keeps the project's convention ``z = [Y, Theta, M,
Q]`` with ``Theta = psi`` (``Y'`` when ``kGA`` is None), ``M = EI psi'`` and
``Q`` the transverse force, whose jump at a point force ``F`` is ``F``. The
field equations are the first-order system ``z' = A(lam) z``::

    Y'     = a Theta + b Q          a = kGA/(kGA + N), b = -1/(kGA + N)   (a = 1, b = 0 rigid)
    Theta' = M / EI
    M'     = c Theta + a Q          c = N a + rhoI lam**2
    Q'     = -mu Y                  mu = m lam**2 + kw

In the order ``(Y, M | Theta, Q)``, ``A = [[0, B], [C, 0]]`` with ``B = [[a,
b], [c, a]]`` and ``C = [[0, 1/EI], [-mu, 0]]``: ``A**2`` is block-diagonal,
``G = B C`` on ``(Y, M)`` and ``G' = C B`` on ``(Theta, Q)``, both with trace
``t = c/EI - b mu`` and determinant ``d = mu (a**2 - b c)/EI``. Hence

    U(l) = exp(A l) = [[F0(G), B F1(G')], [C F1(G), F0(G')]],
    F0(s**2) = cosh(s l),   F1(s**2) = sinh(s l) / s,

entire functions of ``s**2``. A function of a 2x2 matrix with eigenvalues
``r1, r2`` (``r**2 - t r + d = 0``) is ``f(G) = alpha I + beta G`` with
``beta = (f(r1) - f(r2))/(r1 - r2)`` and ``alpha = (r1 f(r2) - r2 f(r1))/(r1 - r2)``:
the exact matrix (:meth:`BeamSegment.transfer_matrix`) is written so. The
plain Euler–Bernoulli beam is ``t = 0``, ``d = -beta**4`` (``a = 1``, ``b = c =
0``), where ``alpha, beta`` are the ``c_j`` of :mod:`symtmm.elements.beam`.

Numerically (:mod:`symtmm.numeric.segments`, and the generated code) ``alpha,
beta`` come from their power series in ``(t, d)`` for a segment short enough that
``max|r| h**2 <= 1``, then the doubling formulas ``F0(2h) = 2 F0(h)**2 - 1``,
``F1(2h) = 2 F0(h) F1(h)`` (with ``G**2 = t G - d``) give the whole length: no
branch of a square root to choose, no division by ``r1 - r2`` (which vanishes
where the two wave numbers meet).
"""

from __future__ import annotations

import functools
import math

import mpmath
import numpy as np
import sympy as sp

from ..expr import exact_float
from .base import LAM, FieldElement

__all__ = ["BeamSegment", "THEORIES", "static_coefficients"]


@functools.lru_cache(maxsize=256)
def static_coefficients(N, kGA) -> tuple:
    """``(a, b, c)`` of :meth:`BeamSegment.coefficients` at ``lam = 0``, exact: they hold
    the axial force ``N`` and the shear stiffness ``kGA`` alone (``kGA`` None: rigid in
    shear), so every piece of a beam shares them (SymPy's arithmetic once per beam, not
    per piece: a tenth of a theory model's plan).

    Examples
    --------
    >>> static_coefficients(sp.Integer(0), None)
    (1, 0, 0)
    >>> static_coefficients(sp.Integer(2), sp.Integer(8))
    (4/5, -1/10, 8/5)
    """
    if kGA is None:
        return sp.Integer(1), sp.Integer(0), N
    a = kGA / (kGA + N)
    return a, -1 / (kGA + N), N * a

#: Beam theories and the fields they need beyond EI, m, L (model file: ``theory``).
THEORIES = {
    "euler-bernoulli": (),
    "rayleigh": ("rhoI",),
    "timoshenko": ("rhoI", "kGA"),
    # axial (and torsional) vibration: symtmm.model.rod, the system with kGA = 0
    "rod": (),
}



class BeamSegment(FieldElement):
    """A uniform beam segment with axial force, rotary inertia and shear flexibility.

    Parameters
    ----------
    EI, m, l : sympy.Expr or number
        Bending stiffness, mass per unit length, length.
    kw : optional
        Winkler foundation stiffness per unit length (default 0).
    N : optional
        Axial force, tension positive (default 0).
    rhoI : optional
        Rotary inertia per unit length (default 0): Rayleigh's correction.
    kGA : optional
        Shear stiffness ``kappa G A``; None (default) for a beam rigid in shear.

    Examples
    --------
    A pinned-pinned Rayleigh beam: ``omega**2 = EI q**2 / (m + rhoI q)``,
    ``q = (pi/L)**2``, so ``Delta`` vanishes there:

    >>> seg = BeamSegment(1, 1, 1, rhoI=sp.Rational(1, 100))
    >>> q = sp.pi**2
    >>> U = seg.transfer_matrix(sp.I * sp.sqrt(q**2 / (1 + q / 100)))
    >>> abs(sp.N(U[0, 1] * U[2, 3] - U[0, 3] * U[2, 1], 30)) < 1e-25   # rows Y, M; cols Theta, Q
    True
    """

    def __init__(self, EI, m, l, kw=0, N=0, rhoI=0, kGA=None):
        self.EI = sp.sympify(EI)
        self.m = sp.sympify(m)
        self.l = sp.sympify(l)
        self.kw = sp.sympify(kw)
        self.N = sp.sympify(N)
        self.rhoI = sp.sympify(rhoI)
        self.kGA = None if kGA is None else sp.sympify(kGA)

    # -- description ----------------------------------------------------------------------
    @property
    def parameters(self) -> dict:
        out = {"EI": self.EI, "m": self.m, "l": self.l}
        for name in ("kw", "N", "rhoI"):
            if getattr(self, name) != 0:
                out[name] = getattr(self, name)
        if self.kGA is not None:
            out["kGA"] = self.kGA
        return out

    @property
    def key(self) -> tuple:
        """The constants that fix the segment's matrix (equal keys, equal matrices)."""
        return (self.EI, self.m, self.l, self.kw, self.N, self.rhoI, self.kGA)

    def with_length(self, l) -> BeamSegment:
        """The same beam over another length."""
        return BeamSegment(self.EI, self.m, l, self.kw, self.N, self.rhoI, self.kGA)

    # -- the field equations --------------------------------------------------------------
    def coefficients(self, lam2):
        """``(a, b, c, mu)`` of the first-order system at ``lam**2`` (exact)."""
        a, b, c0 = static_coefficients(self.N, self.kGA)
        return a, b, c0 + self.rhoI * lam2, self.m * lam2 + self.kw

    def system_matrix(self, lam=LAM) -> sp.Matrix:
        """``A(lam)`` of ``z' = A z``, ``z = [Y, Theta, M, Q]`` (exact)."""
        a, b, c, mu = self.coefficients(lam**2)
        EI = self.EI
        return sp.Matrix([[0, a, 0, b], [0, 0, 1 / EI, 0], [0, c, 0, a], [-mu, 0, 0, 0]])

    def invariants(self, lam2):
        """``(t, d)``: trace and determinant of ``G = B C`` (exact)."""
        a, b, c, mu = self.coefficients(lam2)
        return sp.expand(c / self.EI - b * mu), sp.expand(mu * (a**2 - b * c) / self.EI)

    def transfer_matrix(self, lam=LAM) -> sp.Matrix:
        """Exact transfer matrix ``exp(A l)`` at ``lam``.

        Through the eigenvalues ``r1, r2`` of ``G`` where they differ, and the
        confluent form ``f(G) = f(r) I + f'(r) (G - r I)`` where they coincide
        (e.g. at ``lam = 0`` without axial force, where ``U`` is polynomial).
        """
        lam2 = lam**2
        a, b, c, mu = self.coefficients(lam2)
        t, d = self.invariants(lam2)
        l = self.l
        disc = sp.simplify(t**2 / 4 - d)
        def F0(r):
            return sp.cosh(sp.sqrt(r) * l)

        def F1(r):
            # sinh(s l)/s is l at s = 0 (a wave number vanishes: lam = 0 under axial force)
            return l if r == 0 else sp.sinh(sp.sqrt(r) * l) / sp.sqrt(r)
        if disc == 0:
            r0 = sp.simplify(t / 2)
            if r0 == 0:
                values = [(sp.Integer(1), l**2 / 2), (l, l**3 / 6)]   # f(0), f'(0)
            else:
                d0 = l * F1(r0) / 2
                d1 = (l * F0(r0) - F1(r0)) / (2 * r0)
                values = [(F0(r0), d0), (F1(r0), d1)]
            coef = [c_ for fv, dv in values for c_ in (fv - dv * r0, dv)]   # alpha, beta
        else:
            root = sp.sqrt(disc)
            r1, r2 = t / 2 + root, t / 2 - root
            coef = []
            for f in (F0, F1):
                coef += [(r1 * f(r2) - r2 * f(r1)) / (r1 - r2), (f(r1) - f(r2)) / (r1 - r2)]
        return _assemble(coef, a, b, c, mu, self.EI, sp.Matrix, sp.eye(2))

    # -- numbers ----------------------------------------------------------------------------
    def constants(self) -> tuple:
        """``(EI, m, l, kw, N, rhoI, kGA)`` as floats (``kGA`` infinite when rigid in shear)."""
        return self._constants

    @functools.cached_property
    def _constants(self) -> tuple:
        # (once per segment: a piece length asks for them at forty lengths, and the
        # constants of a segment never change)
        return (exact_float(self.EI), exact_float(self.m), exact_float(self.l),
                exact_float(self.kw), exact_float(self.N), exact_float(self.rhoI),
                math.inf if self.kGA is None else exact_float(self.kGA))

    def wave_number(self, lam2, consts=None):
        """A bound on the largest wave number ``|s|`` at ``lam**2`` (numpy arrays or floats).

        The entries of ``U`` grow like ``exp(|s| l)``.
        """
        EI, m, _, kw, N, rhoI, kGA = consts if consts is not None else self.constants()
        # (a number stays a Python complex: the contours ask for one at a time, thousands
        # of times, where numpy's scalars cost a microsecond an operation)
        lam2 = complex(lam2) if np.ndim(lam2) == 0 else np.asarray(lam2, dtype=complex)
        a, b, c, mu = _coefficients(lam2, m, kw, N, rhoI, kGA, np)
        t = c / EI - b * mu
        d = mu * (a * a - b * c) / EI
        return (abs(t) / 2 + (abs(t) ** 2 / 4 + abs(d)) ** 0.5) ** 0.5

    def counting_wave_number(self, omega: float, consts=None) -> float:
        """``pi`` times the modes per unit length below ``omega`` (Weyl; floats).

        The wave numbers ``s`` of the waves that travel at ``omega`` are ``sqrt(q)``
        for the positive roots ``q = -r`` of ``r**2 - t r + d = 0``; ``n0`` branches of the
        dispersion lie below ``omega`` at ``s = 0`` (``omega**2`` above ``kw / m``, and
        above ``kGA / rhoI``: the second spectrum), and one leaves at each root. So
        the wave numbers of the modes below ``omega`` measure ``n0 s2 + (s1 - s2)``
        (``s1 >= s2`` the roots, ``s2 = 0`` where only one is positive): ``s1`` for a
        beam whose dispersion rises from ``kw / m``, ``s1 + s2`` above a Timoshenko
        beam's second spectrum, ``s1 - s2`` where rotary inertia on a foundation bends
        the dispersion down to a minimum (its lowest modes crowd there, hundreds of
        half-waves along the beam) and 0 below that minimum (``r`` complex). The modes of
        a beam come about one per ``pi`` of this times its length, where
        :meth:`wave_number` bounds the largest, evanescent one: under a tension ``N`` the
        two differ (a taut string's ``omega sqrt(m / N)`` against ``sqrt(N / EI)``).

        Examples
        --------
        >>> seg = BeamSegment(1, 1, 1, N=0)                  # Euler-Bernoulli: beta
        >>> round(seg.counting_wave_number(9.0), 12)
        3.0
        >>> taut = BeamSegment("1/10000", 1, 1, N=100)       # nearly a string: omega / 10
        >>> round(taut.counting_wave_number(50.0), 3)
        5.0
        >>> heavy = BeamSegment(1, 1, 1, kw=10**4, rhoI=100)  # minimum near omega = 1.41
        >>> heavy.counting_wave_number(1.0), round(heavy.counting_wave_number(1.5), 3)
        (0.0, 5.002)
        """
        EI, m, _, kw, N, rhoI, kGA = consts if consts is not None else self.constants()
        w2 = float(omega) ** 2
        a, b, c, mu = _coefficients(-w2, m, kw, N, rhoI, kGA, np)
        t = c / EI - b * mu
        d = mu * (a * a - b * c) / EI
        disc = t * t - 4 * d
        if disc < 0:
            return 0.0                                  # no wave travels
        # the roots q = -r of q**2 + t q + d = 0, q1 >= q2, each without cancellation
        far = -(t + math.copysign(math.sqrt(disc), t)) / 2
        near = d / far if far != 0 else 0.0
        q1, q2 = max(far, near), min(far, near)
        if q1 <= 0:
            return 0.0
        s1, s2 = math.sqrt(q1), math.sqrt(max(q2, 0.0))
        n0 = (kw < m * w2) + (not math.isinf(kGA) and 0 < rhoI and kGA < rhoI * w2)
        return n0 * s2 + (s1 - s2)

    def clamped_frequency_bound(self, length: float) -> float:
        """A lower bound on ``omega**2`` of the clamped-clamped modes of a piece ``length`` long.

        From the Rayleigh quotient with Poincaré's inequality ``int f'**2 >= q int
        f**2`` (``q = (pi/length)**2``) for functions vanishing at both ends (``Y``,
        ``psi`` and ``Y'`` of a clamped piece), or the bound of a piece of any length
        (:meth:`length_free_bound`), whichever is larger; 0 when neither says anything
        (the piece is too long, or buckled under compression). Rigorous: a piece
        shorter than where this exceeds ``omega**2`` has no clamped-clamped
        natural frequency below ``omega``.
        """
        return max(self._poincare_bound(length), self.length_free_bound)

    @functools.cached_property
    def length_free_bound(self) -> float:
        """A lower bound on ``omega**2`` of the clamped-clamped modes of a piece of any
        length: the bottom of the infinite beam's spectrum, ``min(kw / m, ...)`` on a
        foundation, 0 without one.

        A clamped piece's ``(Y, psi)``, extended by zero, is a function on the whole line,
        and Plancherel's theorem turns its strain and kinetic energies into integrals over
        the wave number ``k`` of the symbol's quadratic forms: where ``A(k) - w M`` is
        positive definite for every ``k``, the Rayleigh quotient of every clamped piece
        exceeds ``w``. With ``u = k**2``, ``A(k) - w M = [[(kGA + N) u + kw - w m, -i kGA
        k], [i kGA k, kGA + EI u - w rhoI]]`` (rigid in shear, the scalar ``EI u**2 + (N -
        w rhoI) u + kw - w m``): definite for every ``u >= 0`` where its diagonal is and its
        determinant, a quadratic in ``u``, is positive there. It decreases with ``w`` (in
        Loewner's order), so the largest such ``w`` is found by bisection, and returned a
        millionth lower for the rounding of the tests.

        Examples
        --------
        A Rayleigh beam on a foundation (its spectrum starts a little below ``kw / m =
        100``: long waves' rotary inertia), and a Timoshenko one whose shear spectrum
        starts lower, at ``kGA / rhoI = 50``:

        >>> round(BeamSegment(1, 1, 1, kw=100, rhoI="1/100").length_free_bound, 2)
        99.75
        >>> round(BeamSegment(1, 1, 1, kw=100, rhoI="1/100", kGA="1/2").length_free_bound, 2)
        50.0
        """
        EI, m, _, kw, N, rhoI, kGA = self.constants()
        if not (kw > 0 and m > 0 and EI > 0) or kGA <= 0 or kGA + N <= 0:
            return 0.0

        def definite(w: float) -> bool:
            a = kw - w * m
            if not a > 0:
                return False
            if math.isinf(kGA):
                b = N - w * rhoI
                return b >= 0 or b * b < 4 * EI * a
            c = kGA - w * rhoI
            if not c > 0:
                return False
            alpha, beta, gamma = EI * (kGA + N), N * c + a * EI - kGA * w * rhoI, a * c
            return beta >= 0 or beta * beta < 4 * alpha * gamma

        lo, hi = 0.0, kw / m
        if not definite(lo):
            return 0.0
        for _ in range(60):
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if definite(mid) else (lo, mid)
        return lo * (1 - 1e-6)

    def _poincare_bound(self, length: float) -> float:
        """:meth:`clamped_frequency_bound` from Poincaré's inequality alone."""
        EI, m, _, kw, N, rhoI, kGA = self.constants()
        q = (math.pi / length) ** 2
        if math.isinf(kGA):
            A = EI * q + N                      # int EI Y''**2 + N Y'**2 >= A int Y'**2
            if A <= 0:
                return 0.0
            bound = (A * q + kw) / (m + rhoI * q)
            return min(bound, A / rhoI) if rhoI > 0 else bound
        # kGA (Y' - psi)**2 + N Y'**2 >= kp (Y' - psi)**2 + N (1 + 1/eta) psi**2 for N < 0
        if N >= 0:
            kp, extra = kGA, 0.0
        else:
            eta = 1.0 if kGA + 2 * N > 0 else (-kGA / N - 1) / 2
            kp, extra = kGA + N * (1 + eta), N * (1 + 1 / eta)
            if kp <= 0:
                return 0.0
        # (u - v)**2 >= (1 - eps) u**2 - (1/eps - 1) v**2 for any 0 < eps < 1: the bound is
        # min(coef_y / m, coef_psi / rhoI), coef_y falling and coef_psi rising with eps, so
        # the best eps balances them (a stiff shear, kGA >> EI q, then gives about the
        # Euler-Bernoulli EI q**2 / m, where eps = 1/2 would ask for pieces pi sqrt(EI/kGA)
        # long). Any eps gives a bound. The balance is found in closed form (a bisection
        # took 60 evaluations a bound, and a piece length 40 bounds), twice: in eps and in
        # delta = 1 - eps, each accurate where the other cancels (eps near 0: a soft shear;
        # near 1: a stiff one); the bound is the best at either and its neighbours
        E = EI * q + extra
        ny = max(N, 0.0) * q + kw

        def by_eps(eps):
            return (kp * (1 - eps) * q + ny) / m, E - kp * (1 / eps - 1)

        def by_delta(delta):
            return (kp * delta * q + ny) / m, E - kp * delta / (1 - delta)

        lo, hi = 1e-300, 1.0 - 2.0 ** -53     # (either variable: inside (0, 1))
        if rhoI <= 0:
            # no rotary inertia: psi carries no kinetic energy, coef_psi need only be >= 0:
            # from eps = kp / (E + kp) on, up to delta = E / (E + kp) (coef_y is best there)
            if not E > 0:
                return 0.0
            best = 0.0
            for coefs, x, toward in ((by_eps, kp / (E + kp), 1.0), (by_delta, E / (E + kp), 0.0)):
                x = min(max(x, lo), hi)
                while coefs(x)[1] < 0 and lo < x < hi:          # (rounding: the next double)
                    x = math.nextafter(x, toward)
                if coefs(x)[1] >= 0:
                    best = max(best, coefs(x)[0])
            return best
        # coef_y / m against coef_psi / rhoI, times eps (or 1 - eps): equal at a root of a
        # quadratic, taken by the formula that does not cancel
        B, A0 = kp * q / m, ny / m              # coef_y / m = A0 + B - B eps = A0 + B delta

        def inside(x):
            return min(max(x, lo), hi) if math.isfinite(x) else lo

        if not (B > 0 and kp > 0):
            # (no shear term to split, a rod's kGA = 0: every eps gives the same bound)
            y, p = by_eps(0.5)
            return max(min(y, p / rhoI), 0.0)
        # in eps: B eps**2 - b eps - k = 0, its positive root
        b, k = A0 + B - (E + kp) / rhoI, kp / rhoI
        disc = math.sqrt(b * b + 4 * B * k)
        eps = (b + disc) / (2 * B) if b > 0 else 2 * k / (disc - b)
        # in delta: a delta**2 - b delta + c = 0, its smaller root (c > 0: in (0, 1))
        a, b, c = rhoI * B, rhoI * (B - A0) + E + kp, E - rhoI * A0
        disc = math.sqrt(max(b * b - 4 * a * c, 0.0))
        delta = 2 * c / (b + disc) if b > 0 else (b - disc) / (2 * a) if a > 0 else lo
        candidates = ((by_eps, inside(eps)), (by_delta, inside(delta)))
        best = 0.0
        for coefs, x in candidates:
            for t in (math.nextafter(x, 0.0), x, math.nextafter(x, 1.0)):
                if lo <= t <= hi:
                    y, p = coefs(t)
                    best = max(best, min(y, p / rhoI))
        return best

    def safe_length(self, omega2: float) -> float:
        """A piece length whose clamped-clamped modes all lie above ``omega2`` (x 1.1 margin).

        Returns at most the segment's own length.
        """
        length = float(self.l)
        target = 1.1 * omega2
        if self.clamped_frequency_bound(length) > target:
            return length
        lo, hi = 0.0, length         # bound(lo) > target, found by halving first
        trial = length
        while self.clamped_frequency_bound(trial) <= target:
            hi = trial
            trial /= 2
            if trial < 1e-12 * length:
                from ..errors import ComputationError
                raise ComputationError(
                    f"a piece of this segment (length {length:.6g}) would have to be shorter "
                    f"than 1e-12 of it to keep its clamped-clamped modes above omega = "
                    f"{math.sqrt(max(omega2, 0.0)):.6g}: too many pieces for the search")
        lo = trial
        for _ in range(40):
            mid = 0.5 * (lo + hi)
            if self.clamped_frequency_bound(mid) > target:
                lo = mid
            else:
                hi = mid
        return lo


def _coefficients(lam2, m, kw, N, rhoI, kGA, module):
    """``(a, b, c, mu)`` of the first-order system, numbers (``kGA`` inf/None: rigid)."""
    mu = m * lam2 + kw
    if kGA is None or (isinstance(kGA, float) and math.isinf(kGA)):
        one = 1.0 if module is np else mpmath.mpf(1)
        zero = 0.0 if module is np else mpmath.mpf(0)
        return one, zero, N + rhoI * lam2, mu
    a = kGA / (kGA + N)
    return a, -1 / (kGA + N), N * a + rhoI * lam2, mu


def _assemble(coef, a, b, c, mu, EI, matrix, eye):
    """``U`` in the order ``[Y, Theta, M, Q]`` from ``alpha, beta`` of ``F0`` and ``F1``.

    ``G = B C`` on ``(Y, M)``, ``G' = C B`` on ``(Theta, Q)``; ``U = [[F0(G), B F1(G')],
    [C F1(G), F0(G')]]``. With ``matrix`` (``sp.Matrix``) a SymPy matrix, else rows.
    """
    a0, b0, a1, b1 = coef
    g = [[-b * mu, a / EI], [-a * mu, c / EI]]          # G on (Y, M)
    gp = [[c / EI, a / EI], [-mu * a, -mu * b]]         # G' on (Theta, Q)
    B = [[a, b], [c, a]]
    C = [[0, 1 / EI], [-mu, 0]]

    def mul(X, Y):
        return [[X[i][0] * Y[0][k] + X[i][1] * Y[1][k] for k in range(2)] for i in range(2)]

    def comb(alpha, beta, X):
        return [[(alpha if i == k else 0) + beta * X[i][k] for k in range(2)] for i in range(2)]

    f0g, f0gp = comb(a0, b0, g), comb(a0, b0, gp)
    up = mul(B, comb(a1, b1, gp))                       # (Theta, Q) -> (Y, M)
    low = mul(C, comb(a1, b1, g))                       # (Y, M) -> (Theta, Q)
    ym, tq = (0, 2), (1, 3)
    U = [[0] * 4 for _ in range(4)]
    for i in range(2):
        for k in range(2):
            U[ym[i]][ym[k]] = f0g[i][k]
            U[ym[i]][tq[k]] = up[i][k]
            U[tq[i]][ym[k]] = low[i][k]
            U[tq[i]][tq[k]] = f0gp[i][k]
    return matrix(U) if matrix is not None else U
