/* symtmm codegen runtime, beam theories other than the plain Euler-Bernoulli one
   (after core.c): axial force N, rotary inertia rhoI, shear stiffness kGA, a
   foundation kw, as symtmm.elements.theories computes them. A theory is
   th = {EI, a, b, cN, rhoI, m, kw}: c = cN + rhoI lam2, mu = m lam2 + kw. */

/* c, mu and t, d, the trace and determinant of G = B C, of the theory th at lam2 */
static void symtmm_invariants(double complex lam2, const double th[7],
                              double complex *c, double complex *mu,
                              double complex *t, double complex *d)
{
    *c = th[3] + th[4] * lam2;
    *mu = th[5] * lam2 + th[6];
    *t = *c / th[0] - th[2] * *mu;
    *d = *mu * (th[1] * th[1] - th[2] * *c) / th[0];
}

/* a bound on the largest wave number |s| of the theory th at lam2 (1/length) */
static double symtmm_wave(double complex lam2, const double th[7])
{
    double complex c, mu, t, d;
    symtmm_invariants(lam2, th, &c, &mu, &t, &d);
    double at = cabs(t);
    return sqrt(at / 2.0 + sqrt(at * at / 4.0 + cabs(d)));
}

/* transfer matrix exp(A h) of one of n equal steps h = l/n of a segment of the
   theory th, [Y, Theta, M, Q]: alpha, beta of F0 = cosh(s h), F1 = sinh(s h)/s from
   their series in (t, d) on a piece h/2^j with max|r| (h/2^j)^2 <= 1, then doubled
   j times; U = [[F0(G), B F1(G')], [C F1(G), F0(G')]], G = B C on (Y, M), G' = C B
   on (Theta, Q), B = [[a, b], [c, a]], C = [[0, 1/EI], [-mu, 0]] */
static void symtmm_segment_gen(double complex lam2, const double th[7], double l, int n,
                               double complex U[4][4])
{
    const double EI = th[0], a = th[1], b = th[2];
    double complex c, mu, t, d;
    symtmm_invariants(lam2, th, &c, &mu, &t, &d);
    double w = symtmm_wave(lam2, th), h = l / n;
    int j = 0;
    while (w * h > 1.0) {
        h /= 2.0;
        j++;
    }
    double complex T = t * h * h, DD = d * (h * h) * (h * h);
    double complex qp = 0.0, q = 1.0, s0a = 0.0, s0b = 0.0, s1a = 0.0, s1b = 0.0;
    for (int k = 1; k < 14; k++) {   /* k/(2k)! < 1e-18 beyond: the error for w h <= 1 */
        s0b += q * symtmm_ifact[2 * k];
        s0a += qp * symtmm_ifact[2 * k];
        s1b += q * symtmm_ifact[2 * k + 1];
        s1a += qp * symtmm_ifact[2 * k + 1];
        double complex qn = T * q - DD * qp;
        qp = q;
        q = qn;
    }
    double complex a0 = 1.0 - DD * s0a, b0 = h * h * s0b;
    double complex a1 = h * (1.0 - DD * s1a), b1 = h * h * h * s1b;
    for (int i = 0; i < j; i++) {   /* F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1 */
        double complex na0 = 2.0 * (a0 * a0 - d * b0 * b0) - 1.0;
        double complex nb0 = 2.0 * (2.0 * a0 * b0 + t * b0 * b0);
        double complex na1 = 2.0 * (a0 * a1 - d * b0 * b1);
        double complex nb1 = 2.0 * (a0 * b1 + a1 * b0 + t * b0 * b1);
        a0 = na0;
        b0 = nb0;
        a1 = na1;
        b1 = nb1;
    }
    double complex g00 = -b * mu, g01 = a / EI, g10 = -a * mu, g11 = c / EI;   /* G */
    double complex p00 = c / EI, p01 = a / EI, p10 = -mu * a, p11 = -mu * b;  /* G' */
    U[0][0] = a0 + b0 * g00;
    U[0][2] = b0 * g01;
    U[2][0] = b0 * g10;
    U[2][2] = a0 + b0 * g11;
    U[1][1] = a0 + b0 * p00;
    U[1][3] = b0 * p01;
    U[3][1] = b0 * p10;
    U[3][3] = a0 + b0 * p11;
    double complex h00 = a1 + b1 * p00, h01 = b1 * p01, h10 = b1 * p10, h11 = a1 + b1 * p11;
    U[0][1] = a * h00 + b * h10;
    U[0][3] = a * h01 + b * h11;
    U[2][1] = c * h00 + a * h10;
    U[2][3] = c * h01 + a * h11;
    double complex k00 = a1 + b1 * g00, k01 = b1 * g01, k10 = b1 * g10, k11 = a1 + b1 * g11;
    U[1][0] = k10 / EI;
    U[1][2] = k11 / EI;
    U[3][0] = -mu * k00;
    U[3][2] = -mu * k01;
}
