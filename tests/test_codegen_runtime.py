"""The fixed kernels of ``symtmm/codegen/runtime``, built and run on their own.

The files are used as they are shipped: C's three files one after the other
with a few exported wrappers, Fortran's inside a module that gives the kind
``dp`` with ``bind(C)`` wrappers (both with the flags the generated code is
built with), ``kernels.py`` imported, ``kernels.m`` as subfunctions of a probe
(when Octave is installed). Julia is not installed here: its file is checked
as text. The references owe nothing to the kernels:

* the table of ``1/n!`` holds the double nearest each exact value;
* ``c_j(x) = sum_k x**k / (4k+j)!`` summed by mpmath at 40 digits, inside and
  outside ``|x| = 1`` where the kernels switch to closed forms;
* one of ``n`` steps of an Euler–Bernoulli segment (on a foundation) and of
  Timoshenko, Rayleigh and axial-force segments against the exact transfer
  matrix ``exp(A h)`` of :mod:`symtmm.elements` (SymPy, 30 digits), with
  pieces long enough that the theory routine halves and doubles;
* one of ``n`` steps of a member of beams joined by layers (two beams, damped,
  on a foundation; three beams) against ``exp(A h)`` of its ``4N``-state
  generator, written from the field equations and summed by mpmath;
* the units, the determinant of chosen rows and the re-orthonormalisation
  (orthonormal, spanning the same columns, ``log det F`` from the Gram
  determinant) against numpy.

Every routine a generated evaluator calls is defined by the runtime of its
language.
"""

from __future__ import annotations

import ctypes
import math
import re
import shutil
import subprocess
from fractions import Fraction
from importlib import resources

import mpmath
import numpy as np
import pytest
import sympy as sp

from symtmm.codegen import LANGUAGES, generate
from symtmm.codegen.dialects import DIALECTS
from symtmm.codegen.runtime import kernels
from symtmm.elements.beam import EulerBernoulliSegment
from symtmm.elements.theories import BeamSegment

RUNTIME = resources.files("symtmm.codegen.runtime")
R = sp.Rational


def _source(stem, lang):
    return RUNTIME.joinpath(f"{stem}.{DIALECTS[lang].extension}").read_text(encoding="utf-8")


def _runtime(lang):
    return "\n".join(_source(stem, lang) for stem in DIALECTS[lang].runtime)


# --- the cases and their references ------------------------------------------------------

# x inside and outside |x| = 1 (series, closed forms), on and off the axes
CFUN_X = [0.0, 0.3, -0.99, 0.7j, 0.5 - 0.6j, 1.0, -1.5, 4 + 3j, -40.0, 25j, -18 - 30j]

# (segment, lam, n): lam exact, the segment's matrix for one of n steps
EB_CASES = [
    (EulerBernoulliSegment(R(2), R(3), R(7, 10)), R(-2, 5) + R(23, 10) * sp.I, 1),
    (EulerBernoulliSegment(R(2), R(3), R(7, 10), kw=R(5)), R(9) * sp.I, 3),
    (EulerBernoulliSegment(R(1), R(1), R(3, 2)), R(-3), 2),
    (EulerBernoulliSegment(R(1), R(1), R(1, 4)), R(1, 10) * sp.I, 1),
]
GEN_CASES = [
    (BeamSegment(R(2), R(3), R(3, 2), N=R(5), rhoI=R(1, 50), kGA=R(40)), R(3) * sp.I, 1),
    (BeamSegment(R(2), R(3), R(3, 2), N=R(5), rhoI=R(1, 50), kGA=R(40)), R(-1) + R(40) * sp.I, 1),
    (BeamSegment(R(3, 2), R(4, 5), R(6, 5), kw=R(4), N=R(-3), rhoI=R(1, 100)), R(12) * sp.I, 1),
    (BeamSegment(R(3, 2), R(4, 5), R(6, 5), N=R(6)), R(-2, 3) + R(1, 2) * sp.I, 2),
]


# (member, lam, n): beams joined by layers (EI, m, kw per beam; layers i, j, k, c)
COUPLED_CASES = [
    (((R(1), R(1), R(0)), (R(2), R(3), R(5))), R(3, 5), ((0, 1, R(100), R(2)),),
     R(-1, 2) + R(9) * sp.I, 1),
    (((R(1), R(1), R(0)), (R(2), R(3), R(5))), R(3, 5), ((0, 1, R(100), R(2)),), R(25) * sp.I, 3),
    (((R(1), R(1), R(0)), (R(3, 2), R(2), R(0)), (R(1), R(1, 2), R(1))), R(2, 5),
     ((0, 1, R(40), R(0)), (1, 2, R(20), R(1, 3))), R(-2) + R(14) * sp.I, 2),
]


def _coupled_generator(beams, lam):
    """The state matrix of beams joined by layers in ``[Y.., Theta.., M.., Q..]``, from the
    field equations ``Y' = Theta``, ``Theta' = M/EI``, ``M' = Q``, ``Q' = -(m lam**2 + kw) Y
    + sum kappa (Y_other - Y)``, mpmath numbers."""
    members, _, layers = beams
    n = len(members)
    A = mpmath.zeros(4 * n, 4 * n)
    for i, (EI, m, kw) in enumerate(members):
        A[i, n + i] = 1
        A[n + i, 2 * n + i] = 1 / mpmath.mpf(sp.N(EI, 40))
        A[2 * n + i, 3 * n + i] = 1
        A[3 * n + i, i] = -(mpmath.mpf(sp.N(m, 40)) * lam**2 + mpmath.mpf(sp.N(kw, 40)))
    for i, j, k, c in layers:
        kappa = mpmath.mpf(sp.N(k, 40)) + mpmath.mpf(sp.N(c, 40)) * lam
        for p, q in ((i, j), (j, i)):
            A[3 * n + p, p] -= kappa
            A[3 * n + p, q] += kappa
    return A


def _coupled_exact(members, l, layers, lam, n):
    with mpmath.workdps(40):
        z = mpmath.mpc(sp.N(sp.re(lam), 40), sp.N(sp.im(lam), 40))
        A = _coupled_generator((members, l, layers), z)
        U = mpmath.expm(A * mpmath.mpf(sp.N(l, 40)) / n)
        return np.array([[complex(U[i, j]) for j in range(U.cols)] for i in range(U.rows)])


def _coupled_args(members, l, layers, lam, n):
    from symtmm.elements.layer import CoupledSegment
    cp = [float(v) for v in CoupledSegment(members, l, layers).constants()]
    return complex(lam), complex(sp.N(lam**2, 30)), cp, len(members), n


def _theory(seg) -> list:
    """``[EI, a, b, cN, rhoI, m, kw]`` of a segment, as the runtime reads a theory."""
    a, b, cN, _ = seg.coefficients(0)
    return [float(v) for v in (seg.EI, a, b, cN, seg.rhoI, seg.m, seg.kw)]


def _exact(seg, lam, n) -> np.ndarray:
    """``exp(A h)`` of one of ``n`` steps, exact, rounded to double."""
    matrix = seg.with_length(seg.l / n).transfer_matrix(lam).evalf(30)
    return np.array(matrix.tolist(), dtype=complex)


def _eb_args(seg, lam, n):
    """``(lam2, a, l, EI, n)`` of the Euler-Bernoulli routine: ``lam2`` shifted by kw/m."""
    lam2 = complex(sp.N(lam**2 + seg.kw / seg.m, 30))
    return lam2, float(seg.m * seg.l**4 / seg.EI), float(seg.l), float(seg.EI), n


def _gen_args(seg, lam, n):
    return complex(sp.N(lam**2, 30)), _theory(seg), float(seg.l), n


def _close(got, ref, tol):
    got, ref = np.asarray(got), np.asarray(ref)
    return np.linalg.norm(got - ref) <= tol * np.linalg.norm(ref)


def _columns(seed=5, ns=9, nc=4):
    """Columns of very different sizes, as the walk leaves them between two steps."""
    rng = np.random.default_rng(seed)
    E = rng.normal(size=(ns, nc)) + 1j * rng.normal(size=(ns, nc))
    return E * np.array([1e3, 1.0, 1e-2, 7.0])[:nc]


# --- each language's runtime as a Python object -------------------------------------------


class _Python:
    """``kernels.py``, imported: one point at a time through the batch routines."""

    def ifact(self):
        return list(kernels._IFACT)

    def cfun(self, xs):
        return np.array([[c[0] for c in kernels._cfun(np.array([complex(x)]))] for x in xs])

    def segment(self, cases):
        return np.array([kernels._segment(np.array([lam2]), a, l, EI, n)[0]
                         for lam2, a, l, EI, n in cases])

    def segment_gen(self, cases):
        return np.array([kernels._segment_gen(np.array([lam2]), tuple(th), l, n)[0]
                         for lam2, th, l, n in cases])

    def units(self, cases):
        return np.array([kernels._units(np.array([b]), EI, L)[0] for b, EI, L in cases])

    def segment_coupled(self, cases):
        return [kernels._segment_coupled(np.array([lam]), np.array([lam2]), tuple(cp), nb, n)[0]
                for lam, lam2, cp, nb, n in cases]

    def det(self, E, rows):
        return complex(np.linalg.det(E[rows, :]))   # the generated Python's own determinant

    def orthonormalise(self, E):
        Q, logscale = kernels._orthonormalise(E[None].copy(), np.zeros(1, dtype=complex))
        return Q[0], complex(logscale[0])


_C_HARNESS = """
void t_cfun(const double complex *x, double complex *c) { symtmm_cfun(*x, c); }
void t_segment(const double complex *lam2, double a, double l, double EI, int n,
               double complex *U) { symtmm_segment(*lam2, a, l, EI, n, (double complex (*)[4])U); }
void t_segment_gen(const double complex *lam2, const double *th, double l, int n,
                   double complex *U)
{ symtmm_segment_gen(*lam2, th, l, n, (double complex (*)[4])U); }
void t_units(double b, double EI, double L, double *D) { symtmm_units(b, EI, L, D); }
double t_ifact(int n) { return symtmm_ifact[n]; }
void t_det(int ns, int nc, double complex *E, const int *rows, double complex *d)
{ *d = symtmm_det(ns, nc, (double complex (*)[nc])E, rows); }
void t_orthonormalise(int ns, int nc, double complex *E, double *logscale)
{ symtmm_orthonormalise(ns, nc, (double complex (*)[nc])E, logscale); }
void t_scaled_apply(int nc, double complex *U, const double *D, double complex *E)
{
    double complex Us[4][4];
    symtmm_scaled((double complex (*)[4])U, D, Us);
    symtmm_apply(nc, Us, (double complex (*)[nc])E);
}
void t_segment_coupled(const double complex *lam, const double complex *lam2, const double *cp,
                       int nb, int n, double complex *U)
{ symtmm_segment_coupled(*lam, *lam2, cp, nb, n, (double complex (*)[4 * nb])U); }
double t_wave_coupled(const double complex *lam2, const double *cp, int nb)
{ return symtmm_wave_coupled(*lam2, cp, nb); }
void t_rows(int m, int nc, double complex *U, const double *D, const int *rows,
            double complex *E)
{
    double complex Us[m][m];
    symtmm_scaled_rows(m, (double complex (*)[m])U, D, rows, Us);
    symtmm_apply_rows(m, nc, Us, (double complex (*)[nc])E, rows);
}
"""

_FORTRAN_HARNESS = """
module symtmm_runtime_probe
  use iso_c_binding, only: c_double, c_double_complex, c_int
  implicit none
  integer, parameter :: dp = c_double
contains
{runtime}
  subroutine t_cfun(x, c) bind(C, name="t_cfun")
    complex(c_double_complex), intent(in) :: x
    complex(c_double_complex), intent(out) :: c(0:3)
    call symtmm_cfun(x, c)
  end subroutine t_cfun
  subroutine t_segment(lam2, a, l, ei, n, u) bind(C, name="t_segment")
    complex(c_double_complex), intent(in) :: lam2
    real(c_double), value, intent(in) :: a, l, ei
    integer(c_int), value, intent(in) :: n
    complex(c_double_complex), intent(out) :: u(4, 4)
    call symtmm_segment(lam2, a, l, ei, int(n), u)
  end subroutine t_segment
  subroutine t_segment_gen(lam2, th, l, n, u) bind(C, name="t_segment_gen")
    complex(c_double_complex), intent(in) :: lam2
    real(c_double), intent(in) :: th(7)
    real(c_double), value, intent(in) :: l
    integer(c_int), value, intent(in) :: n
    complex(c_double_complex), intent(out) :: u(4, 4)
    call symtmm_segment_gen(lam2, th, l, int(n), u)
  end subroutine t_segment_gen
  subroutine t_units(b, ei, bl, dd) bind(C, name="t_units")
    real(c_double), value, intent(in) :: b, ei, bl
    real(c_double), intent(out) :: dd(4)
    call symtmm_units(b, ei, bl, dd)
  end subroutine t_units
  real(c_double) function t_ifact(n) bind(C, name="t_ifact")
    integer(c_int), value, intent(in) :: n
    t_ifact = symtmm_ifact(int(n))
  end function t_ifact
  subroutine t_det(ns, nc, e, rows, d) bind(C, name="t_det")
    integer(c_int), value, intent(in) :: ns, nc
    complex(c_double_complex), intent(in) :: e(ns, nc)
    integer(c_int), intent(in) :: rows(nc)
    complex(c_double_complex), intent(out) :: d
    d = symtmm_det(e(rows, :))
  end subroutine t_det
  subroutine t_segment_coupled(lam, lam2, cp, ncp, nb, n, u) bind(C, name="t_segment_coupled")
    complex(c_double_complex), intent(in) :: lam, lam2
    integer(c_int), value, intent(in) :: ncp, nb, n
    real(c_double), intent(in) :: cp(ncp)
    complex(c_double_complex), intent(out) :: u(4 * nb, 4 * nb)
    call symtmm_segment_coupled(lam, lam2, cp, int(nb), int(n), u)
  end subroutine t_segment_coupled
  real(c_double) function t_wave_coupled(lam2, cp, ncp, nb) bind(C, name="t_wave_coupled")
    complex(c_double_complex), intent(in) :: lam2
    integer(c_int), value, intent(in) :: ncp, nb
    real(c_double), intent(in) :: cp(ncp)
    t_wave_coupled = symtmm_wave_coupled(lam2, cp, int(nb))
  end function t_wave_coupled
  subroutine t_orthonormalise(ns, nc, e, logscale) bind(C, name="t_orthonormalise")
    integer(c_int), value, intent(in) :: ns, nc
    complex(c_double_complex), intent(inout) :: e(ns, nc)
    real(c_double), intent(inout) :: logscale
    call symtmm_orthonormalise(e, logscale)
  end subroutine t_orthonormalise
end module symtmm_runtime_probe
"""


class _Compiled:
    """The C or Fortran runtime built into a shared library with the generated code's flags.

    C stores matrices by rows, Fortran by columns: ``order`` says which.
    """

    def __init__(self, lang, workdir):
        if lang == "c":
            compiler = shutil.which("gcc") or shutil.which("cc")
            flags, name, source = ["-std=c99", "-Wall", "-Werror", "-pedantic"], "probe.c", \
                _runtime("c") + _C_HARNESS
        else:
            compiler = shutil.which("gfortran")
            flags, name, source = ["-std=f2008", "-Wall", "-Werror", "-J", str(workdir)], \
                "probe.f90", _FORTRAN_HARNESS.format(runtime=_runtime("fortran"))
        if compiler is None:
            pytest.skip(f"no {lang} compiler")
        (workdir / name).write_text(source)
        lib = workdir / f"libprobe_{lang}.so"
        proc = subprocess.run([compiler, *flags, "-O2", "-shared", "-fPIC", "-o", str(lib),
                               str(workdir / name)], check=False, capture_output=True, text=True,
                              cwd=workdir)
        assert proc.returncode == 0, proc.stderr
        self.lib, self.order, self.base = ctypes.CDLL(str(lib)), "CF"[lang == "fortran"], \
            int(lang == "fortran")
        self.lib.t_ifact.restype = ctypes.c_double

    @staticmethod
    def _ptr(array):
        return array.ctypes.data_as(ctypes.c_void_p)

    def ifact(self):
        return [self.lib.t_ifact(n) for n in range(64)]

    def cfun(self, xs):
        out = np.zeros((len(xs), 4), dtype=complex)
        for i, x in enumerate(xs):
            self.lib.t_cfun(self._ptr(np.array([complex(x)])), self._ptr(out[i]))
        return out

    def _matrices(self, cases, call):
        out = []
        for case in cases:
            U = np.zeros((4, 4), dtype=complex, order=self.order)
            call(*case, U)
            out.append(np.array(U))
        return np.array(out)

    def segment(self, cases):
        f = self.lib.t_segment
        return self._matrices(cases, lambda lam2, a, l, EI, n, U: f(
            self._ptr(np.array([lam2])), ctypes.c_double(a), ctypes.c_double(l),
            ctypes.c_double(EI), ctypes.c_int(n), self._ptr(U)))

    def segment_gen(self, cases):
        f = self.lib.t_segment_gen
        return self._matrices(cases, lambda lam2, th, l, n, U: f(
            self._ptr(np.array([lam2])), self._ptr(np.array(th)), ctypes.c_double(l),
            ctypes.c_int(n), self._ptr(U)))

    def units(self, cases):
        out = np.zeros((len(cases), 4))
        for i, (b, EI, L) in enumerate(cases):
            self.lib.t_units(ctypes.c_double(b), ctypes.c_double(EI), ctypes.c_double(L),
                             self._ptr(out[i]))
        return out

    def segment_coupled(self, cases):
        out = []
        for lam, lam2, cp, nb, n in cases:
            U = np.zeros((4 * nb, 4 * nb), dtype=complex, order=self.order)
            cp = np.array(cp, dtype=float)
            sizes = [ctypes.c_int(len(cp))] if self.order == "F" else []
            self.lib.t_segment_coupled(self._ptr(np.array([lam])), self._ptr(np.array([lam2])),
                                       self._ptr(cp), *sizes, ctypes.c_int(nb), ctypes.c_int(n),
                                       self._ptr(U))
            out.append(np.array(U))
        return out

    def det(self, E, rows):
        E = np.array(E, dtype=complex, order=self.order)
        d = np.zeros(1, dtype=complex)
        index = np.array(rows, dtype=np.intc) + self.base
        self.lib.t_det(*E.shape, self._ptr(E), self._ptr(index), self._ptr(d))
        return complex(d[0])

    def orthonormalise(self, E):
        E = np.array(E, dtype=complex, order=self.order)
        logscale = np.zeros(1)
        self.lib.t_orthonormalise(*E.shape, self._ptr(E), self._ptr(logscale))
        return np.array(E), complex(logscale[0])


class _Octave:
    """``kernels.m`` as subfunctions of a probe function, one interpreter per call."""

    def __init__(self, workdir):
        self.octave = shutil.which("octave-cli") or shutil.which("octave")
        if self.octave is None:
            pytest.skip("Octave is not installed")
        self.workdir = workdir
        (workdir / "symtmm_probe.m").write_text(
            "function varargout = symtmm_probe(name, varargin)\n"
            "  [varargout{1:nargout}] = feval(name, varargin{:});\nend\n\n" + _runtime("octave"))

    def _run(self, statements) -> list:
        """Each statement sets v: its values by columns, one array per statement."""
        script = "".join(f"{s} printf('%.17g %.17g ', [real(v(:).'); imag(v(:).')]); "
                         "printf('\\n');" for s in statements)
        proc = subprocess.run([self.octave, "--no-gui", "--quiet", "--no-window-system",
                               "--eval", script], check=False, capture_output=True, text=True,
                              cwd=self.workdir, timeout=300)
        assert proc.returncode == 0, proc.stderr
        values = [np.array(line.split(), dtype=float) for line in proc.stdout.splitlines()]
        return [v[0::2] + 1j * v[1::2] for v in values]

    @staticmethod
    def _c(z):
        return f"complex({float(np.real(z))!r}, {float(np.imag(z))!r})"

    def _matrix(self, E):
        return "[" + "; ".join(", ".join(self._c(z) for z in row) for row in E) + "]"

    def ifact(self):
        return list(self._run(["v = symtmm_probe('symtmm_ifact');"])[0].real)

    def cfun(self, xs):
        return np.array(self._run([f"v = symtmm_probe('symtmm_cfun', {self._c(x)});"
                                   for x in xs]))

    def segment(self, cases):
        out = self._run([f"v = symtmm_probe('symtmm_segment', {self._c(lam2)}, {a!r}, {l!r}, "
                         f"{EI!r}, {n});" for lam2, a, l, EI, n in cases])
        return np.array([v.reshape(4, 4, order="F") for v in out])

    def segment_gen(self, cases):
        out = self._run([f"v = symtmm_probe('symtmm_segment_gen', {self._c(lam2)}, "
                         f"[{', '.join(map(repr, th))}], {l!r}, {n});" for lam2, th, l, n in cases])
        return np.array([v.reshape(4, 4, order="F") for v in out])

    def units(self, cases):
        return np.array(self._run([f"v = symtmm_probe('symtmm_units', {b!r}, {EI!r}, {L!r});"
                                   for b, EI, L in cases])).real

    def segment_coupled(self, cases):
        out = self._run([f"v = symtmm_probe('symtmm_segment_coupled', {self._c(lam)}, "
                         f"{self._c(lam2)}, [{', '.join(map(repr, cp))}], {nb}, {n});"
                         for lam, lam2, cp, nb, n in cases])
        return [v.reshape(4 * nb, 4 * nb, order="F") for v, (*_, nb, n) in zip(out, cases)]

    def det(self, E, rows):
        picked = " ".join(str(r + 1) for r in rows)
        return complex(self._run([f"E = {self._matrix(E)}; v = det(E([{picked}], :));"])[0][0])

    def orthonormalise(self, E):
        call = f"[v, s] = symtmm_probe('symtmm_orthonormalise', {self._matrix(E)}, 0);"
        Q, logscale = self._run([call, "v = s;"])
        return Q.reshape(E.shape, order="F"), complex(logscale[0])


@pytest.fixture(scope="module", params=["c", "fortran", "python", "octave"])
def runtime(request, tmp_path_factory):
    if request.param == "python":
        return _Python()
    if request.param == "octave":
        return _Octave(tmp_path_factory.mktemp("octave"))
    return _Compiled(request.param, tmp_path_factory.mktemp(request.param))


# --- the kernels ----------------------------------------------------------------------------


def test_inverse_factorials_are_the_nearest_doubles(runtime):
    exact = [float(Fraction(1, math.factorial(n))) for n in range(64)]
    assert runtime.ifact() == exact


def test_beam_functions_match_their_series(runtime):
    with mpmath.workdps(40):
        ref = np.array([[complex(sum(mpmath.mpc(x) ** k / mpmath.factorial(4 * k + j)
                                     for k in range(60))) for j in range(4)] for x in CFUN_X])
    got = runtime.cfun(CFUN_X)
    assert np.all(np.abs(got - ref) <= 1e-14 * np.abs(ref) + 1e-300), np.max(np.abs(got / ref - 1))


def test_euler_bernoulli_step_is_the_exact_matrix(runtime):
    got = runtime.segment([_eb_args(*case) for case in EB_CASES])
    for U, case in zip(got, EB_CASES):
        assert _close(U, _exact(*case), 1e-14), case


def test_zero_length_is_the_identity(runtime):
    assert np.array_equal(runtime.segment([(4.0 + 1j, 0.0, 0.0, 2.0, 1)])[0], np.eye(4))


def test_theory_step_is_the_exact_matrix(runtime):
    """Timoshenko, Rayleigh and axial force; a step of |s| h up to 20 halves and doubles."""
    got = runtime.segment_gen([_gen_args(*case) for case in GEN_CASES])
    for U, (seg, lam, n) in zip(got, GEN_CASES):
        assert _close(U, _exact(seg, lam, n), 1e-13), (seg.parameters, lam, n)
    assert max(float(seg.wave_number(complex(lam) ** 2)) * float(seg.l) / n
               for seg, lam, n in GEN_CASES) > 8


def test_coupled_step_is_the_exact_matrix(runtime):
    """Beams joined by layers: two (damped, one on a foundation) and three, one of n steps."""
    got = runtime.segment_coupled([_coupled_args(*case) for case in COUPLED_CASES])
    for U, case in zip(got, COUPLED_CASES):
        assert _close(U, _coupled_exact(*case), 1e-13), case


def test_c_coupled_wave_and_rows(tmp_path):
    """symtmm_wave_coupled bounds the eigenvalues of X; the rows routines act on their rows."""
    lib = _Compiled("c", tmp_path).lib
    lib.t_wave_coupled.restype = ctypes.c_double
    for members, l, layers, lam, n in COUPLED_CASES:
        lam_, lam2, cp, nb, _ = _coupled_args(members, l, layers, lam, n)
        w = lib.t_wave_coupled(_Compiled._ptr(np.array([lam2])), _Compiled._ptr(np.array(cp)),
                               ctypes.c_int(nb))
        A = np.array(_coupled_generator((members, l, layers), mpmath.mpc(lam_)).tolist(),
                     dtype=complex)
        # |beta| l of every wave of the member: |eigenvalue of A| times l
        assert np.max(np.abs(np.linalg.eigvals(A))) * float(l) <= w * (1 + 1e-12)
    rng = np.random.default_rng(3)
    U = rng.normal(size=(8, 8)) + 1j * rng.normal(size=(8, 8))
    D = rng.uniform(0.1, 3.0, size=12)
    rows = np.array([0, 4, 1, 5, 2, 6, 3, 7], dtype=np.intc)
    E = rng.normal(size=(12, 3)) + 1j * rng.normal(size=(12, 3))
    ref = E.copy()
    ref[rows] = (U * D[rows][:, None] / D[rows][None, :]) @ E[rows]
    lib.t_rows(8, 3, _Compiled._ptr(U), _Compiled._ptr(D), _Compiled._ptr(rows), _Compiled._ptr(E))
    assert np.allclose(E, ref, rtol=1e-15, atol=1e-14 * np.abs(ref).max())


def test_units_follow_the_wave_number(runtime):
    cases = [(3.0, 2.0, 1.0), (0.1, 2.0, 0.5), (7.5, 0.25, 4.0)]
    b = np.array([max(b, 1 / L) for b, _, L in cases])
    EI = np.array([EI for _, EI, _ in cases])
    ref = np.stack([np.ones_like(b), 1 / b, 1 / (EI * b**2), 1 / (EI * b**3)], axis=-1)
    assert np.allclose(runtime.units(cases), ref, rtol=1e-15, atol=0)


def test_determinant_of_chosen_rows(runtime):
    E = _columns()
    rows = [7, 2, 5, 0]
    ref = np.linalg.det(E[rows, :])
    assert abs(runtime.det(E, rows) - ref) <= 1e-13 * abs(ref)
    E[[2, 5], :] = E[[5, 5], :]                   # two equal rows: singular
    assert abs(runtime.det(E, rows)) <= 1e-12 * abs(ref)


def test_orthonormalised_columns_span_the_same_space(runtime):
    E = _columns()
    Q, logscale = runtime.orthonormalise(E)
    assert np.allclose(Q.conj().T @ Q, np.eye(E.shape[1]), atol=1e-14)
    assert np.allclose(Q @ (Q.conj().T @ E), E, atol=1e-12 * np.abs(E).max())
    gram = np.linalg.det(E.conj().T @ E).real
    assert abs(logscale.real - 0.5 * math.log(gram)) <= 1e-13 * abs(math.log(gram))


def test_c_step_applies_the_scaled_matrix(tmp_path):
    """symtmm_scaled and symtmm_apply: rows of E := D U D^-1 (those rows)."""
    lib = _Compiled("c", tmp_path).lib
    rng = np.random.default_rng(2)
    U = rng.normal(size=(4, 4)) + 1j * rng.normal(size=(4, 4))
    D = np.array([1.0, 0.5, 0.02, 4.0])
    E = rng.normal(size=(4, 3)) + 1j * rng.normal(size=(4, 3))
    ref = (U * D[:, None] / D[None, :]) @ E
    lib.t_scaled_apply(3, _Compiled._ptr(U), _Compiled._ptr(D), _Compiled._ptr(E))
    assert np.allclose(E, ref, rtol=1e-15, atol=1e-15 * np.abs(ref).max())


# --- Julia, as text -------------------------------------------------------------------------


def test_julia_table_is_the_nearest_doubles():
    text = _runtime("julia")
    table = text[text.index("const SYMTMM_IFACT = ("):]
    numbers = re.findall(r"[\d.]+(?:e-?\d+)?", table[:table.index("\n)")])
    assert [float(v) for v in numbers] == [float(Fraction(1, math.factorial(n)))
                                           for n in range(64)]


# how each language's runtime defines a routine (a name with the dialect's prefix)
_DEFINES = {"c": r"^static [^(\n]*\b{}\(", "fortran": r"^ *[\w() ]*\b(?:subroutine|function) {}\(",
            "octave": r"^function [^(\n]*\b{}\(", "julia": r"^function {}\(",
            "python": r"^def {}\("}


@pytest.mark.parametrize("lang", LANGUAGES)
def test_every_routine_the_evaluator_calls_is_in_its_runtime(lang):
    """Of a model with every kind of segment and station (the largest runtime)."""
    from test_theories_codegen import _model

    src = generate(_model("mixed"), lang)
    dialect = DIALECTS[lang]
    body = src[src.index("\n", re.search(dialect.evaluator[0], src, re.MULTILINE).start()):]
    called = set(re.findall(rf"\b({re.escape(dialect.prefix)}\w+!?)\(", body))
    runtime = _runtime(lang)
    missing = [name for name in called
               if not re.search(_DEFINES[lang].format(re.escape(name)), runtime, re.MULTILINE)]
    assert len(called) >= 5 and not missing, missing
