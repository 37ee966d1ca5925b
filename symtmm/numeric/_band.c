/*
 * The elimination loop of symtmm.numeric.stiffness._ldl in C, for double and complex
 * double bands: LDL^T without pivoting of B banded matrices at once.
 *
 * The band is stored as in stiffness.py: K[p, r, j] = K_p[r, r + j], rows padded with w
 * zero rows, shape (B, rows, w). Pivot k updates, for 1 <= i <= j < w,
 *
 *     K[p, k + i, j - i] -= (K[p, k, i] / K[p, k, 0]) * K[p, k, j],
 *
 * the operations of the numpy loop in the same order (products and quotients rounded
 * as numpy rounds them, complex quotients by Smith's method as numpy's), so both give
 * the same factors. Build with -ffp-contract=off: a fused multiply-add would round
 * differently.
 *
 * No numpy headers: the band comes as a writable buffer.
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <math.h>

static void eliminate_real(double *K, Py_ssize_t B, Py_ssize_t rows, Py_ssize_t w,
                           Py_ssize_t n)
{
    for (Py_ssize_t p = 0; p < B; p++) {
        double *Kp = K + p * rows * w;
        for (Py_ssize_t k = 0; k < n; k++) {
            const double *row = Kp + k * w;
            const double piv = row[0];
            for (Py_ssize_t i = 1; i < w; i++) {
                const double f = row[i] / piv;
                double *target = Kp + (k + i) * w - i;
                for (Py_ssize_t j = i; j < w; j++) {
                    const double t = f * row[j];
                    target[j] = target[j] - t;
                }
            }
        }
    }
}

/* (a / b) as numpy divides complex numbers (Smith's method). */
static void cdiv(double ar, double ai, double br, double bi, double *qr, double *qi)
{
    const double abs_br = fabs(br), abs_bi = fabs(bi);
    if (abs_br >= abs_bi) {
        if (abs_br == 0 && abs_bi == 0) {
            *qr = ar / abs_br;
            *qi = ai / abs_bi;
        } else {
            const double rat = bi / br;
            const double scl = 1.0 / (br + bi * rat);
            *qr = (ar + ai * rat) * scl;
            *qi = (ai - ar * rat) * scl;
        }
    } else {
        const double rat = br / bi;
        const double scl = 1.0 / (bi + br * rat);
        *qr = (ar * rat + ai) * scl;
        *qi = (ai * rat - ar) * scl;
    }
}

static void eliminate_complex(double *K, Py_ssize_t B, Py_ssize_t rows, Py_ssize_t w,
                              Py_ssize_t n)
{
    for (Py_ssize_t p = 0; p < B; p++) {
        double *Kp = K + 2 * p * rows * w;
        for (Py_ssize_t k = 0; k < n; k++) {
            const double *row = Kp + 2 * k * w;
            for (Py_ssize_t i = 1; i < w; i++) {
                double fr, fi;
                cdiv(row[2 * i], row[2 * i + 1], row[0], row[1], &fr, &fi);
                double *target = Kp + 2 * ((k + i) * w - i);
                for (Py_ssize_t j = i; j < w; j++) {
                    const double xr = row[2 * j], xi = row[2 * j + 1];
                    const double tr = fr * xr - fi * xi;
                    const double ti = fr * xi + fi * xr;
                    target[2 * j] = target[2 * j] - tr;
                    target[2 * j + 1] = target[2 * j + 1] - ti;
                }
            }
        }
    }
}

static PyObject *eliminate(PyObject *self, PyObject *args)
{
    Py_buffer buf;
    Py_ssize_t B, rows, w, n;
    int is_complex;
    if (!PyArg_ParseTuple(args, "w*nnnnp", &buf, &B, &rows, &w, &n, &is_complex))
        return NULL;
    const Py_ssize_t item = is_complex ? 16 : 8;
    if (B < 0 || w < 1 || n < 0 || rows < n + w || buf.len != B * rows * w * item) {
        PyBuffer_Release(&buf);
        PyErr_SetString(PyExc_ValueError, "band buffer of the wrong size");
        return NULL;
    }
    Py_BEGIN_ALLOW_THREADS
    if (is_complex)
        eliminate_complex((double *)buf.buf, B, rows, w, n);
    else
        eliminate_real((double *)buf.buf, B, rows, w, n);
    Py_END_ALLOW_THREADS
    PyBuffer_Release(&buf);
    Py_RETURN_NONE;
}

static PyMethodDef methods[] = {
    {"eliminate", eliminate, METH_VARARGS,
     "eliminate(band, B, rows, w, n, is_complex): LDL^T without pivoting, in place."},
    {NULL, NULL, 0, NULL}
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_band", "Banded LDL^T elimination in C.", -1, methods
};

PyMODINIT_FUNC PyInit__band(void)
{
    return PyModule_Create(&module);
}
