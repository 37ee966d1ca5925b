/* symtmm codegen runtime, Euler-Bernoulli segments (after core.c): the transfer
   matrix from the entire functions c_j(x) = sum_k x^k / (4k+j)!, x = -lam^2 m l^4/EI,
   with no branch to choose and no 0/0 at lam = 0. */

/* c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above */
static void symtmm_cfun(double complex x, double complex c[4])
{
    if (cabs(x) < 1.0) {   /* 16 terms: 1/(4k+j)! < 1e-80 beyond */
        for (int j = 0; j < 4; j++) {
            double complex acc = 0.0;
            for (int k = 15; k >= 0; k--)
                acc = acc * x + symtmm_ifact[4 * k + j];
            c[j] = acc;
        }
    } else {
        double complex nu = cpow(x, 0.25);
        double complex ch = ccosh(nu), co = ccos(nu), sh = csinh(nu), si = csin(nu);
        c[0] = (ch + co) / 2.0;
        c[1] = (sh + si) / (2.0 * nu);
        c[2] = (ch - co) / (2.0 * nu * nu);
        c[3] = (sh - si) / (2.0 * nu * nu * nu);
    }
}

/* transfer matrix of one of n equal steps of an Euler-Bernoulli segment of length l,
   a = m l^4 / EI (lam2 shifted by kw/m on a foundation); I for l = 0 */
static void symtmm_segment(double complex lam2, double a, double l, double EI, int n,
                           double complex U[4][4])
{
    if (l == 0.0) {
        for (int i = 0; i < 4; i++)
            for (int j = 0; j < 4; j++) U[i][j] = (i == j) ? 1.0 : 0.0;
        return;
    }
    double steps = n;
    double complex x = -lam2 * (a / (steps * steps * steps * steps)), c[4];
    symtmm_cfun(x, c);
    l /= steps;
    double l2 = l * l, l3 = l * l * l;
    U[0][0] = c[0];                U[0][1] = l * c[1];
    U[0][2] = l2 * c[2] / EI;      U[0][3] = l3 * c[3] / EI;
    U[1][0] = x * c[3] / l;        U[1][1] = c[0];
    U[1][2] = l * c[1] / EI;       U[1][3] = l2 * c[2] / EI;
    U[2][0] = EI * x * c[2] / l2;  U[2][1] = EI * x * c[3] / l;
    U[2][2] = c[0];                U[2][3] = l * c[1];
    U[3][0] = EI * x * c[1] / l3;  U[3][1] = EI * x * c[2] / l2;
    U[3][2] = x * c[3] / l;        U[3][3] = c[0];
}
