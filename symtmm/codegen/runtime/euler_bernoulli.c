/* symtmm codegen runtime, Euler-Bernoulli segments (after core.c): the transfer
   matrix from the entire functions c_j(x) = sum_k x^k / (4k+j)!, x = -lam^2 m l^4/EI,
   with no branch to choose and no 0/0 at lam = 0. */

/* 1/(4k+j)!, exact to double; 16 terms: the last is below 1e-80 */
static const double symtmm_coef[4][16] = {
    {1.0, 0.041666666666666664, 2.48015873015873e-05, 2.08767569878681e-09,
     4.779477332387385e-14, 4.110317623312165e-19, 1.6117375710961184e-24,
     3.279889237069838e-30, 3.8003907548547434e-36, 2.6882202662866363e-42,
     1.2256174391283858e-48, 3.7618428812322616e-55, 8.055476070751236e-62,
     1.2397999308571486e-68, 1.4064725544496498e-75, 1.2017804936493226e-82},
    {1.0, 0.008333333333333333, 2.7557319223985893e-06, 1.6059043836821613e-10,
     2.8114572543455206e-15, 1.9572941063391263e-20, 6.446950284384474e-26,
     1.1309962886447716e-31, 1.151633562077195e-37, 7.265460179153071e-44,
     2.9893108271424046e-50, 8.359650847182804e-57, 1.643974708316579e-63,
     2.3392451525606576e-70, 2.4674957095607893e-77, 1.9701319568021682e-84},
    {0.5, 0.001388888888888889, 2.755731922398589e-07, 1.1470745597729725e-11,
     1.5619206968586225e-16, 8.896791392450574e-22, 2.4795962632247976e-27,
     3.7699876288159054e-33, 3.387157535521162e-39, 1.911963205040282e-45,
     7.117406731291439e-52, 1.817315401561479e-58, 3.287949416633158e-65,
     4.331935467704922e-72, 4.254302947518602e-79, 3.1776321883905942e-86},
    {0.16666666666666666, 0.0001984126984126984, 2.505210838544172e-08,
     7.647163731819816e-13, 8.22063524662433e-18, 3.868170170630684e-23,
     9.183689863795546e-29, 1.216125041553518e-34, 9.67759295863189e-41,
     4.902469756513544e-47, 1.6552108677421951e-53, 3.866628513960594e-60,
     6.446959640457172e-67, 7.876246304918039e-74, 7.2106829618959365e-81,
     5.043860616493007e-88},
};

/* c_0..c_3 of x: series below |x| = 1, closed forms in x^(1/4) above */
static void symtmm_cfun(double complex x, double complex c[4])
{
    if (cabs(x) < 1.0) {
        for (int j = 0; j < 4; j++) {
            double complex acc = 0.0;
            for (int k = 15; k >= 0; k--)
                acc = acc * x + symtmm_coef[j][k];
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
