"""The generated C evaluator (:mod:`symtmm.codegen`), compiled and timed.

The generated ``symtmm_delta`` is compiled with ``gcc -O2`` into a shared
library together with a small driver, ``symtmm_bench``, that calls it for
an array of eigenvalues inside C and returns the elapsed time
(``clock_gettime``). Two rates come out: calls from Python through ctypes,
one per eigenvalue (what a Python user gets), and the loop inside C (what
the evaluator itself costs).
"""

from __future__ import annotations

import ctypes
import shutil
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np

from symtmm.codegen import generate

__all__ = ["CompiledDelta", "compile_c"]

_DRIVER = r"""
#include <time.h>
void symtmm_delta(double lam_re, double lam_im, double *delta_re, double *delta_im);

/* Delta at n points; returns the seconds the loop took (monotonic clock). */
double symtmm_bench(int n, const double *re, const double *im, double *out_re, double *out_im)
{
    struct timespec a, b;
    clock_gettime(CLOCK_MONOTONIC, &a);
    for (int i = 0; i < n; i++)
        symtmm_delta(re[i], im[i], &out_re[i], &out_im[i]);
    clock_gettime(CLOCK_MONOTONIC, &b);
    return (double)(b.tv_sec - a.tv_sec) + 1e-9 * (double)(b.tv_nsec - a.tv_nsec);
}
"""

_DP = ctypes.POINTER(ctypes.c_double)


class CompiledDelta:
    """``symtmm_delta`` of one model in a shared library.

    Use :func:`compile_c`; ``None`` comes back when no C compiler is found.
    """

    def __init__(self, library: Path, workdir):
        self._workdir = workdir     # keeps the temporary directory alive
        self.lib = ctypes.CDLL(str(library))
        self.lib.symtmm_delta.argtypes = [ctypes.c_double, ctypes.c_double, _DP, _DP]
        self.lib.symtmm_delta.restype = None
        self.lib.symtmm_bench.argtypes = [ctypes.c_int, _DP, _DP, _DP, _DP]
        self.lib.symtmm_bench.restype = ctypes.c_double

    def delta_ctypes(self, lam) -> tuple:
        """``(values, seconds)``: one ctypes call per eigenvalue from a Python loop."""
        lam = np.asarray(lam, dtype=complex).reshape(-1)
        out = np.empty(lam.size, dtype=complex)
        re, im = ctypes.c_double(), ctypes.c_double()
        f = self.lib.symtmm_delta
        pre, pim = ctypes.byref(re), ctypes.byref(im)
        start = time.perf_counter()
        for i, z in enumerate(lam.tolist()):
            f(z.real, z.imag, pre, pim)
            out[i] = complex(re.value, im.value)
        return out, time.perf_counter() - start

    def delta_loop(self, lam) -> tuple:
        """``(values, seconds)``: the loop inside C, timed there."""
        lam = np.asarray(lam, dtype=complex).reshape(-1)
        re = np.ascontiguousarray(lam.real)
        im = np.ascontiguousarray(lam.imag)
        ore, oim = np.empty_like(re), np.empty_like(im)
        seconds = self.lib.symtmm_bench(lam.size, re.ctypes.data_as(_DP), im.ctypes.data_as(_DP),
                                        ore.ctypes.data_as(_DP), oim.ctypes.data_as(_DP))
        return ore + 1j * oim, seconds


def compile_c(model, flags=("-O2",)) -> CompiledDelta | None:
    """Generate, compile (``gcc``) and load the C evaluator of ``model``."""
    cc = shutil.which("gcc") or shutil.which("cc")
    if cc is None:
        return None
    work = tempfile.TemporaryDirectory(prefix="symtmm-bench-")
    d = Path(work.name)
    (d / "delta.c").write_text(generate(model, "c"))
    (d / "driver.c").write_text(_DRIVER)
    lib = d / "libdelta.so"
    subprocess.run([cc, *flags, "-std=c99", "-D_POSIX_C_SOURCE=199309L", "-shared", "-fPIC",
                    str(d / "delta.c"), str(d / "driver.c"), "-o", str(lib), "-lm"],
                   check=True, capture_output=True, text=True)
    return CompiledDelta(lib, work)
