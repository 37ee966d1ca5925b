/*
 * One point's band in double precision: LDL^T without pivoting, the scales that decide
 * which pivot signs are trusted, and what the searches read of the factors. Included by
 * _band.c (batches of bands built in numpy or by _multiword) and by _multiword.c (the
 * band built, factorised and read one point at a time, while it is in cache).
 *
 * The band is stored as in stiffness.py: K[r, j] = K[r, r + j], rows padded with w zero
 * rows, shape (rows, w). Pivot k updates, for 1 <= i <= j < w,
 *
 *     K[k + i, j - i] -= (K[k, i] * (1 / K[k, 0])) * K[k, j],
 *
 * the operations of the numpy loop in the same order (products and quotients rounded
 * as numpy rounds them, complex quotients by Smith's method as numpy's), so both give
 * the same factors. Build with -ffp-contract=off: a fused multiply-add would round
 * differently.
 */
#include <math.h>
#include <stdint.h>

/* One pivot's update, for a width w known where it is inlined: with a constant w (the
 * usual widths, below) the compiler unrolls both loops, which on the narrow bands of
 * small models cost as much as the arithmetic (the same operations in the same order). */
static inline void band_pivot_real(double *Kp, Py_ssize_t k, Py_ssize_t w)
{
    const double *row = Kp + k * w;
    /* one division per pivot, not one per multiplier: they cost a third of the loop */
    const double inv = 1.0 / row[0];
    for (Py_ssize_t i = 1; i < w; i++) {
        const double f = row[i] * inv;
        double *target = Kp + (k + i) * w - i;
        for (Py_ssize_t j = i; j < w; j++) {
            const double t = f * row[j];
            target[j] = target[j] - t;
        }
    }
}

#define BAND_WIDTH_CASE(W)                                                                 \
    case W:                                                                                \
        for (Py_ssize_t k = 0; k < n; k++)                                                 \
            band_pivot_real(Kp, k, W);                                                     \
        return;

static void band_eliminate_real(double *Kp, Py_ssize_t w, Py_ssize_t n)
{
    switch (w) {
        BAND_WIDTH_CASE(2) BAND_WIDTH_CASE(3) BAND_WIDTH_CASE(4) BAND_WIDTH_CASE(5)
        BAND_WIDTH_CASE(6) BAND_WIDTH_CASE(7) BAND_WIDTH_CASE(8) BAND_WIDTH_CASE(9)
        BAND_WIDTH_CASE(10) BAND_WIDTH_CASE(11) BAND_WIDTH_CASE(12)
    default:
        for (Py_ssize_t k = 0; k < n; k++)
            band_pivot_real(Kp, k, w);
    }
}
#undef BAND_WIDTH_CASE

/* (a / b) as numpy divides complex numbers (Smith's method). */
static void band_cdiv(double ar, double ai, double br, double bi, double *qr, double *qi)
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

static void band_eliminate_complex(double *Kp, Py_ssize_t w, Py_ssize_t n)
{
    for (Py_ssize_t k = 0; k < n; k++) {
        const double *row = Kp + 2 * k * w;
        double vr, vi;
        band_cdiv(1.0, 0.0, row[0], row[1], &vr, &vi);
        for (Py_ssize_t i = 1; i < w; i++) {
            /* the multiplier row[i] (1 / pivot), as numpy multiplies complex numbers */
            const double fr = row[2 * i] * vr - row[2 * i + 1] * vi;
            const double fi = row[2 * i] * vi + row[2 * i + 1] * vr;
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

static double band_magnitude(const double *x, int is_complex)
{
    return is_complex ? hypot(x[0], x[1]) : fabs(x[0]);
}

/* The diagonal of |L||D||L^T| per freedom of a factorised band F (the band before, K:
 * its diagonal), into scale (n doubles): pivot by pivot, each pivot's |d| inverted once
 * (a division per entry of the band cost a third of a double point's summary), the
 * terms |L D|^2 / |d| of the rows below it added to theirs, so that each row sums its
 * terms from the farthest pivot to the nearest (hypot for complex magnitudes, as numpy's
 * abs; stiffness._ldl adds in the same order). */
static void band_pivot_scales(const double *F, const double *K, Py_ssize_t w, Py_ssize_t n,
                              int is_complex, double *scale)
{
    const Py_ssize_t c = is_complex ? 2 : 1;
    for (Py_ssize_t m = 0; m < n; m++)
        scale[m] = band_magnitude(K + c * m * w, is_complex);
    for (Py_ssize_t k = 0; k + 1 < n; k++) {
        const double *row = F + c * k * w;
        const double d = band_magnitude(row, is_complex);
        /* np.maximum(d, 1e-300): a NaN stays NaN */
        const double inv = 1.0 / ((d != d || d > 1e-300) ? d : 1e-300);
        const Py_ssize_t top = w < n - k ? w : n - k;
        for (Py_ssize_t j = 1; j < top; j++) {
            const double r = band_magnitude(row + c * j, is_complex);
            scale[k + j] = scale[k + j] + r * r * inv;
        }
    }
}

/* What the searches read of one factorised point F (K: its band before, D: its det U12
 * of the S kinds, to the multiplicities mu), as Factors.log_delta and Factors.counts:
 * log|Delta| (the pivots', det U12's and the plan's constant), arg Delta, and the count
 * (negative pivots; 0 for complex K) where every pivot is decided as _ldl decides it (|d|
 * above trust times its scale, the scale within growth times the largest diagonal entry
 * of K), else -1. scale: n doubles of workspace. */
static void band_point_summary(const double *F, const double *K, const double *D,
                               const int64_t *mu, Py_ssize_t w, Py_ssize_t n, Py_ssize_t S,
                               double trust, double growth, double log_constant,
                               int is_complex, double *scale, double *logabs, double *phase,
                               int64_t *count)
{
    const Py_ssize_t c = is_complex ? 2 : 1;
    band_pivot_scales(F, K, w, n, is_complex, scale);
    double base = 1e-300;
    for (Py_ssize_t m = 0; m < n; m++) {
        const double a = band_magnitude(K + c * m * w, is_complex);
        if (a > base || a != a)
            base = a;
    }
    int decided = 1;
    int64_t negatives = 0;
    /* log|prod d| as log(mant) + ex log 2 (one logarithm, not one per pivot); a pivot
     * beyond 2^-400..2^400 (or 0, not finite) adds its own. mant stays within
     * 2^-500..2^500, so a product by a pivot in range neither overflows nor underflows.
     * Complex pivots: their phases as a product of unit numbers, one atan2. */
    double la = 0.0, ph = 0.0, mant = 1.0, ur = 1.0, ui = 0.0;
    int64_t ex = 0;
    for (Py_ssize_t m = 0; m < n; m++) {
        const double *d = F + c * m * w;
        const double mag = band_magnitude(d, is_complex);
        if (!(mag > trust * scale[m] && scale[m] <= growth * base))
            decided = 0;
        const int normal = mag >= 0x1p-400 && mag <= 0x1p400;
        if (normal) {
            mant *= mag;
            if (!(mant >= 0x1p-500 && mant <= 0x1p500)) {
                int e;
                mant = frexp(mant, &e);
                ex += e;
            }
        } else
            la += log(mag);
        if (is_complex) {
            if (normal) {
                const double dr = d[0] / mag, di = d[1] / mag, r = ur * dr - ui * di;
                ui = ur * di + ui * dr;
                ur = r;
            } else
                ph += atan2(d[1], d[0]);
        } else if (d[0] < 0)
            negatives++;
    }
    la += log(mant) + (double)ex * M_LN2;
    if (is_complex)
        ph += atan2(ui, ur);
    /* real: the phase is pi times the number of negative factors, told by its parity
     * (its sine, cosine and arctangent cost a tenth of a point's summary) */
    int64_t odd = negatives;
    for (Py_ssize_t j = 0; j < S; j++) {
        const double *v = D + c * j;
        la += (double)mu[j] * log(band_magnitude(v, is_complex));
        if (is_complex)
            ph += (double)mu[j] * atan2(v[1], v[0]);
        else if (v[0] < 0)
            odd += mu[j];
    }
    *logabs = la + log_constant;
    *phase = is_complex ? atan2(sin(ph), cos(ph)) : (odd % 2 ? M_PI : 0.0);
    *count = decided ? (is_complex ? 0 : negatives) : -1;
}
