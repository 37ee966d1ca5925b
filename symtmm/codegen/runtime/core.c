/* symtmm codegen runtime, core: units of a beam's state, the propagation of the
   unknown columns, their re-orthonormalisation and the determinant of chosen rows.
   Included verbatim in every generated C evaluator, before euler_bernoulli.c and
   theory.c; the columns E are an ns x nc array (C99 variably modified parameters). */

#include <complex.h>
#include <math.h>

/* 1/n!, n = 0 .. 63, exact to double: the series of both segment kinds */
static const double symtmm_ifact[64] = {
    1.0, 1.0, 0.5, 0.16666666666666666,
    0.041666666666666664, 0.008333333333333333, 0.001388888888888889, 0.0001984126984126984,
    2.48015873015873e-05, 2.7557319223985893e-06, 2.755731922398589e-07, 2.505210838544172e-08,
    2.08767569878681e-09, 1.6059043836821613e-10, 1.1470745597729725e-11, 7.647163731819816e-13,
    4.779477332387385e-14, 2.8114572543455206e-15, 1.5619206968586225e-16, 8.22063524662433e-18,
    4.110317623312165e-19, 1.9572941063391263e-20, 8.896791392450574e-22, 3.868170170630684e-23,
    1.6117375710961184e-24, 6.446950284384474e-26, 2.4795962632247976e-27, 9.183689863795546e-29,
    3.279889237069838e-30, 1.1309962886447716e-31, 3.7699876288159054e-33, 1.216125041553518e-34,
    3.8003907548547434e-36, 1.151633562077195e-37, 3.387157535521162e-39, 9.67759295863189e-41,
    2.6882202662866363e-42, 7.265460179153071e-44, 1.911963205040282e-45, 4.902469756513544e-47,
    1.2256174391283858e-48, 2.9893108271424046e-50, 7.117406731291439e-52, 1.6552108677421951e-53,
    3.7618428812322616e-55, 8.359650847182804e-57, 1.817315401561479e-58, 3.866628513960594e-60,
    8.055476070751236e-62, 1.643974708316579e-63, 3.287949416633158e-65, 6.446959640457172e-67,
    1.2397999308571486e-68, 2.3392451525606576e-70, 4.331935467704922e-72, 7.876246304918039e-74,
    1.4064725544496498e-75, 2.4674957095607893e-77, 4.254302947518602e-79, 7.2106829618959365e-81,
    1.2017804936493226e-82, 1.9701319568021682e-84, 3.1776321883905942e-86, 5.043860616493007e-88,
};

/* units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number */
static void symtmm_units(double b, double EI, double L, double D[4])
{
    if (b < 1.0 / L) b = 1.0 / L;
    D[0] = 1.0;
    D[1] = 1.0 / b;
    D[2] = 1.0 / (EI * b * b);
    D[3] = 1.0 / (EI * b * b * b);
}

/* Us = D U D^-1: the matrix U of a beam acting on its state in units D (inline, as
   symtmm_apply: a model whose every segment is beams joined by layers uses neither,
   and -Wunused-function passes over unused inline functions only) */
static inline void symtmm_scaled(double complex U[4][4], const double D[4], double complex Us[4][4])
{
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            Us[i][k] = U[i][k] * (D[i] / D[k]);
}

/* rows 0..3 of E := Us * (those rows); E points at the beam's first row */
static inline void symtmm_apply(int nc, double complex Us[4][4], double complex E[][nc])
{
    for (int j = 0; j < nc; j++) {
        double complex t[4];
        for (int i = 0; i < 4; i++) {
            t[i] = 0.0;
            for (int k = 0; k < 4; k++)
                t[i] += Us[i][k] * E[k][j];
        }
        for (int i = 0; i < 4; i++)
            E[i][j] = t[i];
    }
}

/* modified Gram-Schmidt, twice: E := Q of E = Q F, and *logscale += log det F */
static void symtmm_orthonormalise(int ns, int nc, double complex E[ns][nc], double *logscale)
{
    for (int j = 0; j < nc; j++) {
        for (int pass = 0; pass < 2; pass++)
            for (int k = 0; k < j; k++) {
                double complex r = 0.0;
                for (int i = 0; i < ns; i++) r += conj(E[i][k]) * E[i][j];
                for (int i = 0; i < ns; i++) E[i][j] -= r * E[i][k];
            }
        double nrm = 0.0;
        for (int i = 0; i < ns; i++) nrm += creal(E[i][j] * conj(E[i][j]));
        nrm = sqrt(nrm);
        for (int i = 0; i < ns; i++) E[i][j] /= nrm;
        *logscale += log(nrm);
    }
}

/* determinant of the rows rows[0..nc-1] of E by Gaussian elimination with partial
   pivoting */
static double complex symtmm_det(int ns, int nc, double complex E[ns][nc], const int rows[nc])
{
    double complex A[nc][nc], d = 1.0;
    for (int i = 0; i < nc; i++)
        for (int j = 0; j < nc; j++) A[i][j] = E[rows[i]][j];
    for (int k = 0; k < nc; k++) {
        int p = k;
        for (int i = k + 1; i < nc; i++)
            if (cabs(A[i][k]) > cabs(A[p][k])) p = i;
        if (A[p][k] == 0.0) return 0.0;
        if (p != k) {
            for (int j = 0; j < nc; j++) {
                double complex t = A[k][j]; A[k][j] = A[p][j]; A[p][j] = t;
            }
            d = -d;
        }
        d *= A[k][k];
        for (int i = k + 1; i < nc; i++) {
            double complex f = A[i][k] / A[k][k];
            for (int j = k + 1; j < nc; j++) A[i][j] -= f * A[k][j];
        }
    }
    return d;
}
