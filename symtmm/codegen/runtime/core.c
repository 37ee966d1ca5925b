/* symtmm codegen runtime, core: units of a beam's state, the propagation of the
   unknown columns, their re-orthonormalisation and the determinant of chosen rows.
   Included verbatim in every generated C evaluator, before euler_bernoulli.c and
   theory.c; the columns E are an ns x nc array (C99 variably modified parameters). */

#include <complex.h>
#include <math.h>

/* units of one beam's state: 1, 1/b, 1/(EI b^2), 1/(EI b^3), b >= 1/L the wave number */
static void symtmm_units(double b, double EI, double L, double D[4])
{
    if (b < 1.0 / L) b = 1.0 / L;
    D[0] = 1.0;
    D[1] = 1.0 / b;
    D[2] = 1.0 / (EI * b * b);
    D[3] = 1.0 / (EI * b * b * b);
}

/* Us = D U D^-1: the matrix U of a beam acting on its state in units D */
static void symtmm_scaled(double complex U[4][4], const double D[4], double complex Us[4][4])
{
    for (int i = 0; i < 4; i++)
        for (int k = 0; k < 4; k++)
            Us[i][k] = U[i][k] * (D[i] / D[k]);
}

/* rows 0..3 of E := Us * (those rows); E points at the beam's first row */
static void symtmm_apply(int nc, double complex Us[4][4], double complex E[][nc])
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
