"""Seeded random models against the independent finite-element model (slow suite).

symtmm/fe.py shares no code with the solver. Damped multilevel models: the FE
stiffness and mass matrices with the dashpots' matrix added give a quadratic
eigenproblem, solved as a linear pencil of twice the size on a fine mesh; the
eigenvalues it finds well inside the search region must be symtmm's, one for one
(none missed, none invented), to the FE model's accuracy. Element-library models
(Rayleigh and Timoshenko beams, axial force, foundation, masses with rotary inertia,
rotational springs): symtmm's first frequencies against the FE model's, extrapolated
over nested meshes. Every model comes from ``random.Random(seed)``: a failure names
the seed that reproduces it.
"""

from __future__ import annotations

import random
from fractions import Fraction

import numpy as np
import pytest
import scipy.linalg

from symtmm.fe import fe_converged, fe_matrices
from symtmm.model import Beam, Mass, Model, Spring
from symtmm.roots.damped import solve_damped
from symtmm.roots.undamped import solve_undamped

pytestmark = pytest.mark.slow

_ENDS = [("pinned", "pinned"), ("clamped", "clamped"), ("clamped", "free"),
         ("pinned", "clamped"), ("clamped", "sliding"), ("pinned", "sliding")]


def _fraction(rng, lo, hi, den=8) -> Fraction:
    return Fraction(rng.randint(lo * den, hi * den), den)


def _damped_model(seed: int):
    """Two or three beams over [0, 1], springs with dashpots between neighbours and to the
    ground (exact rational data), as a Model and as the FE model's dicts."""
    rng = random.Random(seed)
    levels = rng.choice((2, 3))
    beams, fe_beams = [], []
    for i in range(levels):
        left, right = rng.choice(_ENDS)
        EI, m = _fraction(rng, 1, 4), _fraction(rng, 1, 4)
        beams.append(Beam(f"b{i}", EI=str(EI), m=str(m), L=1, left=left, right=right))
        fe_beams.append(dict(name=f"b{i}", EI=float(EI), m=float(m), L=1.0, x0=0.0,
                             left=left, right=right))
    springs, fe_springs, dashpots = [], [], []
    positions = rng.sample(range(1, 16), 2 * levels)
    for i in range(levels):
        other = f"b{i + 1}" if i + 1 < levels else "ground"
        for _ in range(2):
            x = Fraction(positions.pop(), 16)
            k, c = rng.randint(0, 60), _fraction(rng, 0, 3, 4)
            springs.append(Spring(f"b{i}", other, x=str(x), k=k, c=str(c)))
            fe_springs.append(dict(between=[f"b{i}", other], x=float(x), k=float(k)))
            dashpots.append((f"b{i}", other, float(x), float(c)))
    return Model(tuple(beams), tuple(springs)), fe_beams, fe_springs, dashpots


def _fe_eigenvalues(fe_beams, fe_springs, dashpots, elements):
    """Eigenvalues (Im >= 0) of ``lam**2 M + lam C + K`` on the FE mesh."""
    K, M, info = fe_matrices(fe_beams, fe_springs, elements)
    C = np.zeros_like(K)

    def dof(beam, x):
        nodes = np.asarray(info["nodes"][beam])
        return info["dofs"][beam][int(np.argmin(np.abs(nodes - x)))][0]

    for a, b, x, c in dashpots:
        i = dof(a, x)
        j = dof(b, x) if b != "ground" else -1
        for p, q, s in ((i, i, 1), (j, j, 1), (i, j, -1), (j, i, -1)):
            if p >= 0 and q >= 0:
                C[p, q] += s * c
    n = K.shape[0]
    A = np.block([[np.zeros((n, n)), np.eye(n)], [-K, -C]])
    B = np.block([[np.eye(n), np.zeros((n, n))], [np.zeros((n, n)), M]])
    lam = scipy.linalg.eig(A, B, right=False)
    lam = lam[np.isfinite(lam)]
    return lam[lam.imag >= -1e-9]


@pytest.mark.parametrize("seed", range(8))
def test_damped_random_models_against_the_state_space_fe(seed):
    model, fe_beams, fe_springs, dashpots = _damped_model(seed)
    W = 60.0
    spectrum = solve_damped(model, omega_max=W, sigma_max=W, digits=12)
    found = []
    for e in spectrum:
        found += [complex(e.lam)] * e.multiplicity
    fine = _fe_eigenvalues(fe_beams, fe_springs, dashpots, 48)
    # the FE eigenvalues clearly inside the region (away from its edges by 3 %), each
    # matched by one of symtmm's, and none of symtmm's unmatched
    inside = [z for z in fine if -0.97 * W <= z.real <= 0.03 * W and abs(z.imag) <= 0.97 * W]
    assert sum(z.imag >= 0 for z in inside) >= 3, seed      # the check has something to check
    unused = list(found)
    for z in sorted(inside, key=lambda z: (z.imag, z.real)):
        if z.imag < 0:
            continue
        distances = [abs(z - f) / max(abs(z), 1.0) for f in unused]
        j = int(np.argmin(distances))
        assert distances[j] < 1e-5, (seed, z, unused)
        unused.pop(j)
    near_edge = [f for f in unused if not (-0.97 * W <= f.real and f.imag <= 0.97 * W)]
    assert len(unused) == len(near_edge), (seed, unused)


def _library_model(seed: int):
    """One or two beams of any theory, with masses and rotational and translational springs."""
    rng = random.Random(1000 + seed)
    beams, fe_beams, masses, fe_masses = [], [], [], []
    levels = rng.choice((1, 2))
    for i in range(levels):
        left, right = rng.choice(_ENDS)
        EI, m = _fraction(rng, 1, 3), _fraction(rng, 1, 3)
        extra, fe_extra = {}, {}
        theory = rng.choice(("euler-bernoulli", "rayleigh", "timoshenko"))
        if theory != "euler-bernoulli":
            rhoI = Fraction(rng.randint(1, 5), 200)
            extra.update(theory=theory, rhoI=str(rhoI))
            fe_extra["rhoI"] = float(rhoI)
        if theory == "timoshenko":
            kGA = rng.randint(40, 200)
            extra["kGA"] = kGA
            fe_extra["kGA"] = float(kGA)
        if rng.random() < 0.4:
            N = rng.randint(1, 8)
            extra["N"], fe_extra["N"] = N, float(N)
        if rng.random() < 0.3:
            kw = rng.randint(1, 30)
            extra["kw"], fe_extra["kw"] = kw, float(kw)
        beams.append(Beam(f"b{i}", EI=str(EI), m=str(m), L=1, left=left, right=right, **extra))
        fe_beams.append(dict(name=f"b{i}", EI=float(EI), m=float(m), L=1.0, x0=0.0,
                             left=left, right=right, **fe_extra))
        if rng.random() < 0.6:
            x, M, J = Fraction(rng.randint(1, 7), 8), _fraction(rng, 0, 1), Fraction(1, 100)
            masses.append(Mass(f"b{i}", str(x), str(M), str(J)))
            fe_masses.append(dict(beam=f"b{i}", x=float(x), M=float(M), J=float(J)))
    springs, fe_springs = [], []
    for i in range(levels):
        other = f"b{i + 1}" if i + 1 < levels else "ground"
        x = Fraction(rng.randint(1, 15), 16)
        kind = rng.choice(("translational", "rotational"))
        k = rng.randint(5, 60)
        springs.append(Spring(f"b{i}", other, x=str(x), k=k, kind=kind))
        fe_springs.append(dict(between=[f"b{i}", other], x=float(x), k=float(k), kind=kind))
    model = Model(tuple(beams), tuple(springs), masses=tuple(masses))
    return model, fe_beams, fe_springs, fe_masses


@pytest.mark.parametrize("seed", range(8))
def test_element_library_random_models_against_the_fe_model(seed):
    model, fe_beams, fe_springs, fe_masses = _library_model(seed)
    spectrum = solve_undamped(model, count=6, digits=12)
    got = []
    for e in spectrum:
        got += [float(e.omega)] * e.multiplicity
    fe = fe_converged(fe_beams, fe_springs, 12, count=len(got), masses=fe_masses)
    ref = np.where(fe["zero"], 0.0, fe["omega"])
    tolerance = np.maximum(10 * fe["error"], 1e-9 * np.abs(ref)) + 1e-9
    assert np.all(np.abs(np.array(got[:len(ref)]) - ref) <= tolerance), (seed, got, ref)
