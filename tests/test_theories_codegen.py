"""Generated evaluators for the beam theories and for rigid bodies, joints, trees and loops.

The generated C, Fortran, Python (and Octave, when installed) ``Delta(lam)``
are checked against references that owe nothing to the code generator:

* closed forms derived from the energy for pinned-pinned beams (``Y = A sin
  k x``, ``psi = B cos k x``, ``q = k**2``): Rayleigh with an axial force and a
  foundation, ``omega**2 = (EI q**2 + N q + kw) / (m + rhoI q)``; Timoshenko
  with an axial force, the two roots in ``omega**2`` of
  ``det [[kGA q + N q - m w2, -kGA k], [-kGA k, EI q + kGA - rhoI w2]] = 0``
  (the variations in ``Y`` and ``psi`` of ``EI psi'**2 + kGA (Y' - psi)**2 +
  N Y'**2`` against ``m Y_t**2 + rhoI psi_t**2``);
* symmetry decoupling: a trunk forking rigidly into two identical branches of
  half its stiffness and mass moves, in the in-phase modes, as one beam, and in
  the out-of-phase modes as two branches clamped to a trunk at rest; likewise a
  closed loop (trunk, two branches, tail);
* a pinned-pinned beam carrying a rigid body (mass ``M``, rotary inertia ``J``)
  at its middle, made of two beams and the body as their joint: the symmetric
  modes feel only ``M``, the antisymmetric only ``J``, each a half beam with a
  frequency equation written out below;
* a cantilever carrying a rigid body on a massless rigid link of length ``e``
  (centre of mass beyond the tip): the two tip conditions from the variation
  of the beam's energy plus the body's ``M (Y + e Y')_t**2 + J Y'_t**2``;
* the mpmath evaluator (``Evaluator.delta_mp`` at 40 digits and more) at real,
  imaginary and complex ``lam``, to ``1e-13`` times the condition of ``Delta``
  (see ``test_codegen._mp_reference``).
"""

from __future__ import annotations

import shutil
import subprocess

import mpmath
import numpy as np
import pytest
from reference import classical_roots
from test_codegen import _generated, _lams, _mp_reference

from symtmm.cli import main
from symtmm.codegen import generate
from symtmm.compile import Evaluator
from symtmm.modelfile import loads

# --- models -----------------------------------------------------------------------------

TIMOSHENKO = """
title = "Timoshenko beam under tension, pinned-pinned"
[parameters]
kGA = 40
N = 5
[[beam]]
name = "t"
EI = 2
m = 3
L = 1.5
left = "pinned"
right = "pinned"
theory = "timoshenko"
rhoI = 0.02
kGA = "kGA"
N = "N"
"""
TIMOSHENKO_VALUES = {"EI": 2.0, "m": 3.0, "L": 1.5, "rhoI": 0.02, "kGA": 40.0, "N": 5.0}

RAYLEIGH = """
title = "Rayleigh beam under compression on a foundation, pinned-pinned"
[[beam]]
name = "r"
EI = 1.5
m = 0.8
L = 1.2
left = "pinned"
right = "pinned"
theory = "rayleigh"
rhoI = 0.01
N = -3
kw = 4
"""
RAYLEIGH_VALUES = {"EI": 1.5, "m": 0.8, "L": 1.2, "rhoI": 0.01, "N": -3.0, "kw": 4.0}

# Euler-Bernoulli under tension: not a plain beam, the general routine with rhoI = 0
AXIAL = RAYLEIGH.replace('theory = "rayleigh"\nrhoI = 0.01\nN = -3\nkw = 4', "N = 6")
AXIAL_VALUES = dict(RAYLEIGH_VALUES, rhoI=0.0, N=6.0, kw=0.0)


def _beam(name, EI, m, L, x0, left, right, extra=""):
    return (f'[[beam]]\nname = "{name}"\nEI = {EI}\nm = {m}\nL = {L}\nx0 = {x0}\n'
            f'left = "{left}"\nright = "{right}"\n{extra}\n')


# a clamped trunk (EI 2, m 2, 0.6 long) forking rigidly into two branches (EI 1, m 1, 0.5)
FORK = (_beam("trunk", 2, 2, 0.6, 0, "clamped", "free")
        + _beam("b1", 1, 1, 0.5, 0.6, "free", "free")
        + _beam("b2", 1, 1, 0.5, 0.6, "free", "free")
        + '[[joint]]\nends = ["trunk.right", "b1.left", "b2.left"]\n')
FORK_L1, FORK_L2 = 0.6, 0.5

# trunk 0.3, branches 0.5, tail 0.4, clamped at both outer ends: a closed loop
LOOP = (_beam("trunk", 2, 2, 0.3, 0, "clamped", "free")
        + _beam("b1", 1, 1, 0.5, 0.3, "free", "free")
        + _beam("b2", 1, 1, 0.5, 0.3, "free", "free")
        + _beam("tail", 2, 2, 0.4, 0.8, "free", "clamped")
        + '[[joint]]\nends = ["trunk.right", "b1.left", "b2.left"]\n'
        + '[[joint]]\nends = ["b1.right", "b2.right", "tail.left"]\n')
LOOP_L, LOOP_L2 = 1.2, 0.5

# a Timoshenko fork pinned at its outer ends: branches with half of every field
_TIMO_TRUNK = 'theory = "timoshenko"\nrhoI = 0.02\nkGA = 60\nN = 4'
_TIMO_BRANCH = 'theory = "timoshenko"\nrhoI = 0.01\nkGA = 30\nN = 2'
TIMO_FORK = (_beam("trunk", 2, 2, 0.7, 0, "pinned", "free", _TIMO_TRUNK)
             + _beam("b1", 1, 1, 0.6, 0.7, "free", "pinned", _TIMO_BRANCH)
             + _beam("b2", 1, 1, 0.6, 0.7, "free", "pinned", _TIMO_BRANCH)
             + '[[joint]]\nends = ["trunk.right", "b1.left", "b2.left"]\n')
TIMO_FORK_VALUES = {"EI": 2.0, "m": 2.0, "L": 1.3, "rhoI": 0.02, "kGA": 60.0, "N": 4.0}

# a pinned-pinned beam (EI 1, m 1, L 1) in two halves joined by a body with M and J
MID_M, MID_J = 0.3, 0.02
MID_BODY = (_beam("a", 1, 1, 0.5, 0, "pinned", "free")
            + _beam("b", 1, 1, 0.5, 0.5, "free", "pinned")
            + f'[[rigid]]\nattach = ["a.right", "b.left"]\nM = {MID_M}\nJ = {MID_J}\n')

# a cantilever (EI 1, m 1, L 1) with a body whose centre of mass is e beyond the tip
TIP_M, TIP_J, TIP_E = 0.7, 0.05, 0.2
TIP_BODY = ('[parameters]\nMb = 0.7\ne = 0.2\n'
            + _beam("b", 1, 1, 1, 0, "clamped", "free")
            + f'[[rigid]]\nattach = ["b.right"]\nM = "Mb"\nJ = {TIP_J}\nxc = "1 + e"\n')

# every kind of element at once: plain, Winkler, Timoshenko, spring, dashpot, mass, hinge
MIXED = (_beam("a", 2, 1, 1, 0, "clamped", "free", "kw = 3")
         + _beam("t", 1, 3, 1.5, 0.25, "pinned", "free",
                 'theory = "timoshenko"\nrhoI = 0.03\nkGA = 25\nN = -1')
         + _beam("c", 1, 1, 0.5, 1.75, "free", "sliding", 'theory = "rayleigh"\nrhoI = 0.01')
         + '[[spring]]\nbetween = ["a", "t"]\nx = 0.5\nk = 7\nc = 0.3\n'
         + '[[mass]]\nbeam = "t"\nx = 1.2\nM = 0.4\nJ = 0.01\n'
         + '[[joint]]\nends = ["t.right", "c.left"]\nkind = "hinge"\n')

MODELS = {
    "timoshenko": (TIMOSHENKO, (), {}),
    "timoshenko_symbolic": (TIMOSHENKO, ("N", "kGA"), {"N": "-4", "kGA": "25"}),
    "rayleigh": (RAYLEIGH, (), {}),
    "axial": (AXIAL, (), {}),
    "fork": (FORK, (), {}),
    "loop": (LOOP, (), {}),
    "timoshenko_fork": (TIMO_FORK, (), {}),
    "mid_body": (MID_BODY, (), {}),
    "tip_body_symbolic": (TIP_BODY, ("Mb", "e"), {"Mb": "1.3", "e": "0.35"}),
    "mixed": (MIXED, (), {}),
}
COMPILED = ("c", "fortran")


def _model(name, values=None):
    text, _, _ = MODELS[name]
    model = loads(text, source=f"{name}.toml")
    return model.with_parameters(**values) if values else model


# --- running the generated code ----------------------------------------------------------


def _octave():
    return shutil.which("octave-cli") or shutil.which("octave")


def _octave_caller(source, workdir):
    octave = _octave()
    if octave is None:
        pytest.skip("Octave is not installed")
    (workdir / "symtmm_delta.m").write_text(source)

    def delta(lams, *params):
        lams = np.asarray(lams, dtype=complex)
        expr = "[" + ", ".join(f"complex({float(z.real)!r}, {float(z.imag)!r})"
                               for z in lams) + "]"
        extra = "".join(f", {float(v)!r}" for v in params)
        proc = subprocess.run([octave, "--no-gui", "--quiet", "--eval",
                               (f"d = symtmm_delta({expr}{extra}); printf('%.17g %.17g\\n', "
                                "[real(d); imag(d)])")],
                              check=False, capture_output=True, text=True, cwd=workdir,
                              timeout=300)
        assert proc.returncode == 0, proc.stderr
        return np.array([complex(*map(float, ln.split())) for ln in proc.stdout.splitlines()
                         if ln.strip()])

    return delta


@pytest.fixture(scope="module")
def evaluator(tmp_path_factory):
    """``get(name, lang)``: the generated ``Delta`` of a model, built once per module."""
    cache = {}

    def get(name, lang):
        if (name, lang) not in cache:
            _, symbolic, _ = MODELS[name]
            src = generate(_model(name), lang, symbolic)
            workdir = tmp_path_factory.mktemp(f"{lang}_{name}")
            if lang == "octave":
                cache[(name, lang)] = _octave_caller(src, workdir)
            else:
                cache[(name, lang)] = _generated(lang, src, workdir, len(symbolic))
        return cache[(name, lang)]

    return get


def _newton_steps(delta, lams, *params):
    """``|Delta / (lam Delta')|`` at each ``lam``: the relative distance to the nearest simple
    root (one call of ``delta`` for all)."""
    h = 1e-6
    lams = np.asarray(lams, dtype=complex)
    d0, dp, dm = delta(np.concatenate([lams, lams * (1 + h), lams * (1 - h)]),
                       *params).reshape(3, -1)
    slope = (dp - dm) / (2 * h)
    assert np.all(np.abs(slope) > 0)
    return np.abs(d0 / slope)


def _assert_roots(delta, lams, *params):
    steps = _newton_steps(delta, lams, *params)
    assert np.all(steps < 1e-12), (np.asarray(lams)[np.argmax(steps)], np.max(steps), params)


# --- closed-form references -------------------------------------------------------------


def _timoshenko_pp(EI, m, L, rhoI, kGA, N, modes=4):
    """Both branches of pinned-pinned Timoshenko frequencies omega for n = 1..modes."""
    out = []
    with mpmath.workdps(40):
        for n in range(1, modes + 1):
            k = n * mpmath.pi / L
            q = k * k
            # rhoI m w2**2 - (rhoI (kGA + N) q + m (EI q + kGA)) w2 + const = 0
            a2 = mpmath.mpf(rhoI) * m
            a1 = -(rhoI * (kGA + N) * q + m * (EI * q + kGA))
            a0 = (kGA + N) * q * (EI * q + kGA) - kGA**2 * q
            assert a0 > 0                       # not buckled
            disc = mpmath.sqrt(a1 * a1 - 4 * a2 * a0)
            out += [float(mpmath.sqrt((-a1 - disc) / (2 * a2))),
                    float(mpmath.sqrt((-a1 + disc) / (2 * a2)))]
    return out


def _rayleigh_pp(EI, m, L, rhoI, N, kw, modes=6):
    out = []
    for n in range(1, modes + 1):
        q = (n * np.pi / L) ** 2
        out.append(float(np.sqrt((EI * q * q + N * q + kw) / (m + rhoI * q))))
    return out


def _bracketed_roots(f, step, count, start=None):
    """The first ``count`` sign changes of ``f`` on a grid of ``step``, polished (mpmath)."""
    roots = []
    with mpmath.workdps(40):
        x = mpmath.mpf(step if start is None else start)
        fx = f(x)
        while len(roots) < count:
            y = x + step
            fy = f(y)
            if fx * fy < 0:
                roots.append(mpmath.findroot(f, (x, y), solver="anderson"))
            x, fx = y, fy
    return roots


def _mid_body_roots(count=3):
    """beta of the symmetric (M) and antisymmetric (J) modes: half beam [0, a], pinned at 0.

    ``Y = A sin(beta x) + B sinh(beta x)``; symmetric: ``Y'(a) = 0`` and
    ``2 EI Y'''(a) + M omega**2 Y(a) = 0``; antisymmetric: ``Y(a) = 0`` and
    ``2 EI Y''(a) - J omega**2 Y'(a) = 0`` (``EI = m = 1``, ``omega = beta**2``).
    Both determinants are divided by ``cosh(beta a)``.
    """
    a = mpmath.mpf(1) / 2
    M, J = mpmath.mpf(MID_M), mpmath.mpf(MID_J)

    def sym(b):
        c, s, t = mpmath.cos(b * a), mpmath.sin(b * a), mpmath.tanh(b * a)
        return 4 * b**3 * c + M * b**4 * (c * t - s)

    def anti(b):
        c, s, t = mpmath.cos(b * a), mpmath.sin(b * a), mpmath.tanh(b * a)
        return 4 * b**2 * s * t - J * b**5 * (s - t * c)

    return _bracketed_roots(sym, 1 / 32, count), _bracketed_roots(anti, 1 / 32, count)


def _tip_body_roots(M, J, e, count=4):
    """beta of a cantilever (EI = m = L = 1) with a tip body, centre of mass e beyond the tip.

    ``Y = A (cosh - cos) + B (sinh - sin)`` of ``beta x``; at ``x = 1``
    ``EI Y''' + omega**2 M W = 0`` and ``EI Y'' - omega**2 (M e W + J Y') = 0`` with
    ``W = Y + e Y'`` (``omega = beta**2``); rows divided by ``cosh(beta)``.
    """
    M, J, e = mpmath.mpf(M), mpmath.mpf(J), mpmath.mpf(e)

    def f(b):
        sech = mpmath.sech(b)
        c, s, sh = mpmath.cos(b) * sech, mpmath.sin(b) * sech, mpmath.tanh(b)
        Y = (1 - c, sh - s)
        Y1 = (b * (sh + s), b * (1 - c))
        Y2 = (b**2 * (1 + c), b**2 * (sh + s))
        Y3 = (b**3 * (sh - s), b**3 * (1 + c))
        w2 = b**4
        W = tuple(y + e * y1 for y, y1 in zip(Y, Y1))
        r1 = [Y3[i] + w2 * M * W[i] for i in range(2)]
        r2 = [Y2[i] - w2 * (M * e * W[i] + J * Y1[i]) for i in range(2)]
        return r1[0] * r2[1] - r1[1] * r2[0]

    return _bracketed_roots(f, 1 / 64, count)


def _langs():
    return [*COMPILED, "python", "octave"]


# --- beam theories: closed forms -----------------------------------------------------------


@pytest.mark.parametrize("lang", _langs())
def test_timoshenko_vanishes_at_closed_form(lang, evaluator):
    """Both spectra (bending and shear branches) of the pinned-pinned Timoshenko beam, n <= 4."""
    delta = evaluator("timoshenko", lang)
    omegas = _timoshenko_pp(**TIMOSHENKO_VALUES)
    cutoff = (TIMOSHENKO_VALUES["kGA"] / TIMOSHENKO_VALUES["rhoI"]) ** 0.5
    assert sum(w > cutoff for w in omegas) == 4      # the shear branch is in the set
    _assert_roots(delta, 1j * np.array(omegas))


@pytest.mark.parametrize("lang", _langs())
def test_timoshenko_symbolic_kGA_and_N_vanish_at_closed_form(lang, evaluator):
    """kGA and N as arguments: other values, a compression among them, move the roots there."""
    delta = evaluator("timoshenko_symbolic", lang)
    for N, kGA in ((5.0, 40.0), (-4.0, 25.0), (12.0, 300.0)):
        values = dict(TIMOSHENKO_VALUES, N=N, kGA=kGA)
        _assert_roots(delta, 1j * np.array(_timoshenko_pp(**values, modes=3)), N, kGA)


@pytest.mark.parametrize("lang", _langs())
def test_rayleigh_with_axial_force_and_foundation_vanishes_at_closed_form(lang, evaluator):
    delta = evaluator("rayleigh", lang)
    _assert_roots(delta, 1j * np.array(_rayleigh_pp(**RAYLEIGH_VALUES)))


@pytest.mark.parametrize("lang", _langs())
def test_euler_bernoulli_under_tension_vanishes_at_closed_form(lang, evaluator):
    assert "theory" not in AXIAL and "N = 6" in AXIAL
    delta = evaluator("axial", lang)
    _assert_roots(delta, 1j * np.array(_rayleigh_pp(**AXIAL_VALUES)))


# --- trees, loops and bodies: symmetry decoupling and closed forms -------------------------


@pytest.mark.parametrize("lang", _langs())
def test_fork_vanishes_at_decoupled_roots(lang, evaluator):
    """In phase: a cantilever of length L1 + L2; out of phase: branches clamped-free of L2."""
    delta = evaluator("fork", lang)
    nus = classical_roots("clamped", "free", 4)
    betas = [float(nu) / (FORK_L1 + FORK_L2) for nu in nus]
    betas += [float(nu) / FORK_L2 for nu in nus[:2]]
    _assert_roots(delta, 1j * np.array(betas) ** 2)   # EI / m = 1 throughout: omega = beta**2


@pytest.mark.parametrize("lang", _langs())
def test_loop_vanishes_at_decoupled_roots(lang, evaluator):
    """In phase: one clamped-clamped beam of length 1.2; out of phase: branches clamped-clamped."""
    delta = evaluator("loop", lang)
    nus = classical_roots("clamped", "clamped", 4)
    betas = [float(nu) / LOOP_L for nu in nus] + [float(nu) / LOOP_L2 for nu in nus[:2]]
    _assert_roots(delta, 1j * np.array(betas) ** 2)


@pytest.mark.parametrize("lang", _langs())
def test_timoshenko_fork_in_phase_modes_are_the_single_beam(lang, evaluator):
    """Branches with half of EI, m, rhoI, kGA, N: in phase, one pinned-pinned beam of 1.3."""
    delta = evaluator("timoshenko_fork", lang)
    _assert_roots(delta, 1j * np.array(_timoshenko_pp(**TIMO_FORK_VALUES, modes=3)))


@pytest.mark.parametrize("lang", _langs())
def test_body_at_the_middle_vanishes_at_decoupled_roots(lang, evaluator):
    """Symmetric modes feel only M, antisymmetric only J; both differ from the bare beam's."""
    delta = evaluator("mid_body", lang)
    sym, anti = _mid_body_roots()
    _assert_roots(delta, 1j * np.array([float(b) for b in sym + anti]) ** 2)
    # the reference itself: the body lowers both families below the bare beam's (2n-1) pi
    # and 2n pi; the Rayleigh quotients of the bare first modes, sin(pi x) and sin(2 pi x),
    # bound the first roots from above (omega**2 <= omega0**2 / (1 + M/0.5), resp.
    # (1 + J (2 pi)**2 / 0.5)), the first closely since M hardly changes the shape
    assert all(float(b) < (2 * n - 1) * np.pi for n, b in enumerate(sym, 1))
    assert all(float(b) < 2 * n * np.pi for n, b in enumerate(anti, 1))
    bound_sym = np.pi / (1 + MID_M / 0.5) ** 0.25
    bound_anti = 2 * np.pi / (1 + MID_J * (2 * np.pi) ** 2 / 0.5) ** 0.25
    assert 0.995 * bound_sym < float(sym[0]) <= bound_sym
    assert 0.9 * bound_anti < float(anti[0]) <= bound_anti


@pytest.mark.parametrize("lang", _langs())
def test_tip_body_on_a_link_vanishes_at_closed_form(lang, evaluator):
    """Body mass and link length are arguments: the model's values and others."""
    delta = evaluator("tip_body_symbolic", lang)
    for Mb, e in ((TIP_M, TIP_E), (1.3, 0.35), (0.0, 0.5)):
        betas = np.array([float(b) for b in _tip_body_roots(Mb, TIP_J, e)])
        _assert_roots(delta, 1j * betas**2, Mb, e)


# --- agreement with the mpmath evaluator --------------------------------------------------

_REFERENCES: dict = {}


def _probes(name):
    """Low modes in every direction, plus high modes (undamped and damped)."""
    rng = np.random.default_rng(11)
    high = rng.uniform(200, 2500, 6)
    return np.concatenate([_lams(rng, n=12, scale=40.0), 1j * high[:3],
                           -rng.uniform(0, 50, 3) + 1j * high[3:]])


def _reference(name, full=True):
    """Probes, mpmath Delta and its condition; every third probe unless ``full``."""
    key = (name, full)
    if key not in _REFERENCES:
        _, symbolic, values = MODELS[name]
        ev = Evaluator(_model(name, values if symbolic else None))
        lams = _probes(name)
        if not full:
            lams = lams[::3]
        _REFERENCES[key] = (lams, *_mp_reference(ev, lams))
    return _REFERENCES[key]


# 40-digit Delta of the multi-beam models costs 0.1-0.2 s a point: few probes by default
_SINGLE = ("timoshenko", "timoshenko_symbolic", "rayleigh", "axial", "tip_body_symbolic")


def _check_agreement(lang, name, evaluator, full):
    _, symbolic, values = MODELS[name]
    delta = evaluator(name, lang)
    lams, ref, cond = _reference(name, full)
    params = [float(values[p]) for p in symbolic]
    got = delta(lams, *params)
    rel = np.abs(got - ref) / np.abs(ref)
    bound = 1e-13 * (cond + 100)
    worst = np.argmax(rel / bound)
    assert np.all(rel <= bound), (lams[worst], rel[worst], cond[worst])
    assert np.median(rel) < 1e-13


@pytest.mark.parametrize("name", list(MODELS))
@pytest.mark.parametrize("lang", [*COMPILED, "python"])
def test_agrees_with_mpmath(lang, name, evaluator):
    """Real, imaginary and complex lam, low and high modes, to 1e-13 times the condition."""
    _check_agreement(lang, name, evaluator, full=name in _SINGLE)


@pytest.mark.slow
@pytest.mark.parametrize("name", [n for n in MODELS if n not in _SINGLE])
@pytest.mark.parametrize("lang", [*COMPILED, "python"])
def test_agrees_with_mpmath_at_every_probe(lang, name, evaluator):
    _check_agreement(lang, name, evaluator, full=True)


@pytest.mark.parametrize("name", ["timoshenko_symbolic", "loop", "tip_body_symbolic", "mixed"])
def test_octave_agrees_with_mpmath(name, evaluator):
    _, symbolic, values = MODELS[name]
    delta = evaluator(name, "octave")
    lams, ref, cond = _reference(name, full=name in _SINGLE)
    got = delta(lams, *[float(values[p]) for p in symbolic])
    rel = np.abs(got - ref) / np.abs(ref)
    assert np.all(rel <= 1e-13 * (cond + 100)), np.max(rel / (cond + 100))


def test_julia_agrees_when_installed(tmp_path):
    julia = shutil.which("julia")
    if julia is None:
        pytest.skip("Julia is not installed")
    (tmp_path / "delta.jl").write_text(generate(_model("mixed"), "julia"))
    lams, ref, cond = _reference("mixed", full=False)
    calls = "; ".join(f"d = symtmm_delta(ComplexF64({float(z.real)!r}, {float(z.imag)!r})); "
                      "println(real(d), \" \", imag(d))" for z in lams)
    proc = subprocess.run([julia, "--startup-file=no", "-e", f'include("delta.jl"); {calls}'],
                          check=False, capture_output=True, text=True, cwd=tmp_path, timeout=600)
    assert proc.returncode == 0, proc.stderr
    got = np.array([complex(*map(float, ln.split())) for ln in proc.stdout.splitlines()
                    if ln.strip()])
    rel = np.abs(got - ref) / np.abs(ref)
    assert np.all(rel <= 1e-13 * (cond + 100))


# --- arguments and the command line --------------------------------------------------------


def test_symbolic_fields_of_theories_and_bodies_are_arguments():
    c = generate(_model("timoshenko"), "c", ("N", "kGA"))
    assert ("void symtmm_delta(double lam_re, double lam_im, double N, double kGA, "
            "double *delta_re, double *delta_im)") in c
    assert "def symtmm_delta(lam, Mb, e):" in generate(_model("tip_body_symbolic"), "python",
                                                        ("Mb", "e"))
    assert "function d = symtmm_delta(lam, N, kGA)" in generate(_model("timoshenko"), "octave",
                                                                ("N", "kGA"))
    assert "function symtmm_delta(lam::ComplexF64, N::Float64, kGA::Float64)::ComplexF64" in \
        generate(_model("timoshenko"), "julia", ("N", "kGA"))


def test_cli_writes_a_timoshenko_evaluator(tmp_path):
    model = tmp_path / "timo.toml"
    model.write_text(TIMOSHENKO)
    out = tmp_path / "delta.c"
    assert main(["codegen", str(model), "--lang", "c", "--symbolic", "kGA", "-o", str(out)]) == 0
    delta = _generated("c", out.read_text(), tmp_path, 1)
    omega = _timoshenko_pp(**TIMOSHENKO_VALUES, modes=1)[0]
    _assert_roots(delta, [1j * omega], 40.0)


def test_parameters_named_like_the_new_routines_are_renamed(tmp_path):
    """th0 (a local), wave and steps (Fortran functions), core (a Python closure) as names."""
    text = (TIMOSHENKO.replace("kGA = 40\nN = 5", "wave = 40\nth0 = 5\ncore = 0.02\nsteps = 2")
            .replace('kGA = "kGA"', 'kGA = "wave"').replace('N = "N"', 'N = "th0"')
            .replace("rhoI = 0.02", 'rhoI = "core"').replace("EI = 2", 'EI = "steps"'))
    model = loads(text, source="names.toml")
    symbolic = ("core", "steps", "th0", "wave")
    args = (0.02, 2.0, 5.0, 40.0)
    lams = _probes("names")[:20]
    ref = Evaluator(model).delta(lams)
    for lang in (*COMPILED, "python"):
        got = _generated(lang, generate(model, lang, symbolic), tmp_path, 4)(lams, *args)
        assert np.max(np.abs(got / ref - 1)) < 1e-12, lang
    assert "double p_th0" in generate(model, "c", symbolic)
    assert "p_wave" in generate(model, "fortran", symbolic)
