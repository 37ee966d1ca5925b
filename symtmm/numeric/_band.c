/*
 * The loops of symtmm.numeric.stiffness in C, for double and complex double batches:
 * the scatter of the element values into the band (assemble), LDL^T without pivoting
 * of B banded matrices at once (_ldl), the diagonal of |L||D||L^T| that decides which
 * pivot signs are trusted, and summary(), which reads a factorised batch as the searches
 * do. The per-point loops are those of _band_core.h (the elimination in the numpy loop's
 * order of operations, its layout of the band).
 *
 * The scatter sums each entry's terms in the order of the plan a layer at a time, as
 * the numpy loop does.
 *
 * No numpy headers: arrays come as buffers.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "_band_core.h"
#include "_buffers.h"

static PyObject *eliminate(PyObject *self, PyObject *args)
{
    Py_buffer buf;
    Py_ssize_t B, rows, w, n;
    int is_complex;
    if (!PyArg_ParseTuple(args, "w*nnnnp", &buf, &B, &rows, &w, &n, &is_complex))
        return NULL;
    const Py_ssize_t item = is_complex ? 16 : 8;
    if (B < 0 || w < 1 || n < 0 || rows < n + w || buf.len != B * rows * w * item)
        return RELEASED(CALL_MISFIT, "band buffer of the wrong size", &buf);
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t p = 0; p < B; p++) {
        double *Kp = (double *)buf.buf + (is_complex ? 2 : 1) * p * rows * w;
        if (is_complex)
            band_eliminate_complex(Kp, w, n);
        else
            band_eliminate_real(Kp, w, n);
    }
    Py_END_ALLOW_THREADS
    return RELEASED(CALL_DONE, NULL, &buf);
}

/* K[p, targets[i]] (+)= V[p, source[i]] * coef[i]: one layer of the band's sums (each
 * target once in a layer); add = 0 writes the first term, add = 1 adds the next ones. */
static void scatter_layer(const double *V, double *K, Py_ssize_t B, Py_ssize_t nv,
                          Py_ssize_t nk, const long long *targets, const long long *source,
                          const double *coef, Py_ssize_t terms, int add, int is_complex)
{
    for (Py_ssize_t p = 0; p < B; p++) {
        if (!is_complex) {
            const double *Vp = V + p * nv;
            double *Kp = K + p * nk;
            for (Py_ssize_t i = 0; i < terms; i++) {
                const double term = Vp[source[i]] * coef[i];
                Kp[targets[i]] = add ? Kp[targets[i]] + term : term;
            }
        } else {
            const double *Vp = V + 2 * p * nv;
            double *Kp = K + 2 * p * nk;
            for (Py_ssize_t i = 0; i < terms; i++) {
                /* numpy multiplies by the coefficient as by the complex c + 0i */
                const double a = Vp[2 * source[i]], b = Vp[2 * source[i] + 1], c = coef[i];
                const double tr = a * c - b * 0.0, ti = a * 0.0 + b * c;
                double *k = Kp + 2 * targets[i];
                k[0] = add ? k[0] + tr : tr;
                k[1] = add ? k[1] + ti : ti;
            }
        }
    }
}

static PyObject *scatter(PyObject *self, PyObject *args)
{
    Py_buffer v, k, tg, src, cf;
    Py_ssize_t B;
    int add, is_complex;
    if (!PyArg_ParseTuple(args, "y*w*y*y*y*npp", &v, &k, &tg, &src, &cf, &B, &add,
                          &is_complex))
        return NULL;
    const Py_ssize_t item = is_complex ? 16 : 8, terms = tg.len / 8;
    const Py_ssize_t nv = B ? v.len / item / B : 0, nk = B ? k.len / item / B : 0;
    int ok = B >= 0 && src.len == tg.len && cf.len == tg.len && (B == 0 || (
        v.len == B * nv * item && k.len == B * nk * item));
    /* every index inside its array (a plan's tables are trusted, the buffers checked) */
    for (Py_ssize_t i = 0; ok && i < terms; i++) {
        const long long s = ((const long long *)src.buf)[i], t = ((const long long *)tg.buf)[i];
        ok = s >= 0 && s < nv && t >= 0 && t < nk;
    }
    if (ok) {
        Py_BEGIN_ALLOW_THREADS
        scatter_layer(v.buf, k.buf, B, nv, nk, tg.buf, src.buf, cf.buf, terms, add,
                      is_complex);
        Py_END_ALLOW_THREADS
    }
    return RELEASED(ok ? CALL_DONE : CALL_MISFIT, "scatter tables and buffers do not fit",
                    &v, &k, &tg, &src, &cf);
}

/* peaks(factored, out, B, rows, w, n): per point of a factorised real batch the freedom
 * where phi = L^-T e_(n-1) is largest in modulus. K phi = d_(n-1) e_(n-1): near an
 * eigenvalue phi is its mode, and the twisted factorisation that ends at the mode's
 * largest freedom has its smallest pivot there (the pivot at t is 1 / (K^-1)_tt).
 * phi is rescaled as it grows (it may grow by orders of magnitude along the band); a
 * zero pivot leaves its freedom at 0. */
static PyObject *peaks(PyObject *self, PyObject *args)
{
    Py_buffer kb, out;
    Py_ssize_t B, rows, w, n;
    if (!PyArg_ParseTuple(args, "y*w*nnnn", &kb, &out, &B, &rows, &w, &n))
        return NULL;
    if (B < 0 || w < 1 || n < 1 || rows < n + w || kb.len != B * rows * w * 8
            || out.len != B * 8)
        return RELEASED(CALL_MISFIT, "peaks buffers of the wrong size", &kb, &out);
    double *phi = malloc((size_t)(n + w) * sizeof(double));
    if (!phi) {
        PyBuffer_Release(&kb);
        PyBuffer_Release(&out);
        return PyErr_NoMemory();
    }
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t p = 0; p < B; p++) {
        const double *K = (const double *)kb.buf + p * rows * w;
        for (Py_ssize_t i = 0; i < n + w; i++)
            phi[i] = 0.0;
        phi[n - 1] = 1.0;
        Py_ssize_t best = n - 1;
        double top = 1.0;
        for (Py_ssize_t i = n - 2; i >= 0; i--) {
            const double d = K[i * w];
            double v = 0.0;
            if (d != 0.0 && isfinite(d)) {
                for (Py_ssize_t j = 1; j < w; j++)
                    v -= (K[i * w + j] / d) * phi[i + j];
            }
            phi[i] = isfinite(v) ? v : 0.0;
            if (fabs(phi[i]) > 0x1p500) {
                for (Py_ssize_t j = 0; j < w && i + j < n; j++)
                    phi[i + j] *= 0x1p-500;
                top *= 0x1p-500;
            }
            if (fabs(phi[i]) > top) {
                top = fabs(phi[i]);
                best = i;
            }
        }
        ((long long *)out.buf)[p] = (long long)best;
    }
    Py_END_ALLOW_THREADS
    free(phi);
    return RELEASED(CALL_DONE, NULL, &kb, &out);
}

static PyObject *bounds(PyObject *self, PyObject *args)
{
    Py_buffer kb, k0, out;
    Py_ssize_t B, rows, w, n;
    int is_complex;
    if (!PyArg_ParseTuple(args, "y*y*w*nnnnp", &kb, &k0, &out, &B, &rows, &w, &n,
                          &is_complex))
        return NULL;
    const Py_ssize_t item = is_complex ? 16 : 8, c = is_complex ? 2 : 1;
    if (B < 0 || w < 1 || n < 0 || rows < n + w || kb.len != B * rows * w * item
            || k0.len != B * n * w * item || out.len != B * n * 8)
        return RELEASED(CALL_MISFIT, "bounds buffers of the wrong size", &kb, &k0, &out);
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t p = 0; p < B; p++)
        band_pivot_scales((const double *)kb.buf + c * p * rows * w,
                     (const double *)k0.buf + c * p * n * w, w, n, is_complex,
                     (double *)out.buf + p * n);
    Py_END_ALLOW_THREADS
    return RELEASED(CALL_DONE, NULL, &kb, &k0, &out);
}

/* summary(factored, band, det12, mult, logabs, phase, count, B, rows, w, n, S, trust,
 *         growth, log_constant, is_complex): per point of a factorised double batch what
 * the searches read of it, in one pass: log|Delta| and arg Delta (the pivots', det U12's
 * to the kinds' multiplicities and the plan's constant, as Factors.log_delta), and the
 * count (negative pivots; 0 for complex K) where every pivot is decided as _ldl decides
 * it (|d| above trust times its scale, the scale within growth times the largest
 * diagonal entry of K), else -1. */
static PyObject *summary(PyObject *self, PyObject *args)
{
    Py_buffer kb, k0, d12, mult, la_out, ph_out, cnt_out;
    Py_ssize_t B, rows, w, n, S;
    double trust, growth, log_constant;
    int is_complex;
    if (!PyArg_ParseTuple(args, "y*y*y*y*w*w*w*nnnnndddp", &kb, &k0, &d12, &mult, &la_out,
                          &ph_out, &cnt_out, &B, &rows, &w, &n, &S, &trust, &growth,
                          &log_constant, &is_complex))
        return NULL;
    const Py_ssize_t item = is_complex ? 16 : 8, c = is_complex ? 2 : 1;
    const int sizes = B >= 0 && w >= 1 && n >= 0 && S >= 0 && rows >= n + w
        && kb.len == B * rows * w * item && k0.len == B * n * w * item
        && d12.len == B * S * item && mult.len == S * 8 && la_out.len == B * 8
        && ph_out.len == B * 8 && cnt_out.len == B * 8;
    double *scale = sizes ? PyMem_Malloc((n > 0 ? n : 1) * sizeof(double)) : NULL;
    if (scale == NULL)
        return RELEASED(sizes ? CALL_NO_MEMORY : CALL_MISFIT, "summary buffers of the wrong size",
                        &kb, &k0, &d12, &mult, &la_out, &ph_out, &cnt_out);
    const int64_t *mu = (const int64_t *)mult.buf;
    Py_BEGIN_ALLOW_THREADS
    for (Py_ssize_t p = 0; p < B; p++)
        band_point_summary((const double *)kb.buf + c * p * rows * w,
                           (const double *)k0.buf + c * p * n * w,
                           (const double *)d12.buf + c * p * S, mu, w, n, S, trust, growth,
                           log_constant, is_complex, scale, (double *)la_out.buf + p,
                           (double *)ph_out.buf + p, (int64_t *)cnt_out.buf + p);
    Py_END_ALLOW_THREADS
    PyMem_Free(scale);
    return RELEASED(CALL_DONE, NULL, &kb, &k0, &d12, &mult, &la_out, &ph_out, &cnt_out);
}

static PyMethodDef methods[] = {
    {"eliminate", eliminate, METH_VARARGS,
     "eliminate(band, B, rows, w, n, is_complex): LDL^T without pivoting, in place."},
    {"scatter", scatter, METH_VARARGS,
     "scatter(V, K, targets, source, coef, B, add, is_complex): K[p, targets[i]] = "
     "(K[p, targets[i]] if add else 0) + V[p, source[i]] * coef[i]."},
    {"bounds", bounds, METH_VARARGS,
     "bounds(factored, band, out, B, rows, w, n, is_complex): the diagonal of "
     "|L||D||L^T| per freedom."},
    {"peaks", peaks, METH_VARARGS,
     "peaks(factored, out, B, rows, w, n): per point the freedom where L^-T e_(n-1) is "
     "largest."},
    {"summary", summary, METH_VARARGS,
     "summary(factored, band, det12, mult, logabs, phase, count, B, rows, w, n, S, trust, "
     "growth, log_constant, is_complex): log|Delta|, arg Delta and the count per point."},
    {NULL, NULL, 0, NULL}
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_band", "The band's scatter, LDL^T and bounds in C.", -1, methods
};

PyMODINIT_FUNC PyInit__band(void)
{
    return PyModule_Create(&module);
}
