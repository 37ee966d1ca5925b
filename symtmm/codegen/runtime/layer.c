/* symtmm codegen runtime, beams joined by continuous layers (after core.c): one
   member of nb beams whose transfer matrix is the single beam's with the scalar x
   replaced by the nb x nb matrix X = -(diag(A lam^2 + F) + K + lam C)
   (symtmm.elements.layer): blocks c_j(X) above the diagonal and X c_j(X) below,
   c_j(X) = sum_k X^k / (4k+j)!, in the state Y_1..Y_nb, Theta_1.., M_1.., Q_1..
   The member's constants cp: l, A (nb), F (nb), K (nb x nb), C (nb x nb), l^2/EI
   (nb), l^3/EI (nb); A = m l^4/EI, F = kw l^4/EI, K and C the layers' Laplacians
   of stiffness and damping times l^4/EI, row by row. */

/* |beta| l of the member: the fourth root of the infinity norm of X, |lam| taken as
   sqrt|lam2| */
static double symtmm_wave_coupled(double complex lam2, const double *cp, int nb)
{
    const double *A = cp + 1, *F = A + nb, *K = F + nb, *C = K + nb * nb;
    double la = sqrt(cabs(lam2)), best = 0.0;
    for (int i = 0; i < nb; i++) {
        double row = 0.0;
        for (int j = 0; j < nb; j++) {
            double complex x = K[i * nb + j];
            if (i == j) x += A[i] * lam2 + F[i];
            row += cabs(x) + fabs(C[i * nb + j]) * la;
        }
        if (row > best) best = row;
    }
    return pow(best, 0.25);
}

/* transfer matrix of one of n equal steps of the member (|X| <= nu_step^4 = 256 per
   step: 11 terms, the rest below 1e-27); I for l = 0 */
static void symtmm_segment_coupled(double complex lam, double complex lam2, const double *cp,
                                   int nb, int n, double complex U[4 * nb][4 * nb])
{
    const double *A = cp + 1, *F = A + nb, *K = F + nb, *C = K + nb * nb;
    const double *sM = C + nb * nb, *sQ = sM + nb;
    int m = 4 * nb;
    if (cp[0] == 0.0) {
        for (int i = 0; i < m; i++)
            for (int j = 0; j < m; j++) U[i][j] = (i == j) ? 1.0 : 0.0;
        return;
    }
    double steps = n, s4 = steps * steps * steps * steps;
    double complex X[nb][nb], P[nb][nb], T[nb][nb], c[4][nb][nb], Xc[4][nb][nb];
    for (int i = 0; i < nb; i++)
        for (int j = 0; j < nb; j++) {
            double complex x = K[i * nb + j] + lam * C[i * nb + j];
            if (i == j) x += A[i] * lam2 + F[i];
            X[i][j] = -x / s4;
            P[i][j] = (i == j) ? 1.0 : 0.0;
            for (int q = 0; q < 4; q++) c[q][i][j] = (i == j) ? symtmm_ifact[q] : 0.0;
        }
    for (int k = 1; k <= 10; k++) {
        for (int i = 0; i < nb; i++)
            for (int j = 0; j < nb; j++) {
                T[i][j] = 0.0;
                for (int r = 0; r < nb; r++) T[i][j] += P[i][r] * X[r][j];
            }
        for (int i = 0; i < nb; i++)
            for (int j = 0; j < nb; j++) {
                P[i][j] = T[i][j];
                for (int q = 0; q < 4; q++) c[q][i][j] += symtmm_ifact[4 * k + q] * T[i][j];
            }
    }
    for (int q = 1; q < 4; q++)
        for (int i = 0; i < nb; i++)
            for (int j = 0; j < nb; j++) {
                Xc[q][i][j] = 0.0;
                for (int r = 0; r < nb; r++) Xc[q][i][j] += X[i][r] * c[q][r][j];
            }
    /* the scaled state (Y, h Theta, h^2 M/EI, h^3 Q/EI) back to (Y, Theta, M, Q) */
    double h = cp[0] / steps, s[4][nb];
    for (int i = 0; i < nb; i++) {
        s[0][i] = 1.0;
        s[1][i] = h;
        s[2][i] = sM[i] / (steps * steps);
        s[3][i] = sQ[i] / (steps * steps * steps);
    }
    for (int a = 0; a < 4; a++)
        for (int b = 0; b < 4; b++)
            for (int i = 0; i < nb; i++)
                for (int j = 0; j < nb; j++) {
                    double complex v = (b >= a) ? c[b - a][i][j] : Xc[4 + b - a][i][j];
                    U[a * nb + i][b * nb + j] = v * (s[b][j] / s[a][i]);
                }
}

/* Us = D U D^-1 over the member's rows of the state */
static void symtmm_scaled_rows(int m, double complex U[m][m], const double *D, const int rows[m],
                               double complex Us[m][m])
{
    for (int i = 0; i < m; i++)
        for (int k = 0; k < m; k++)
            Us[i][k] = U[i][k] * (D[rows[i]] / D[rows[k]]);
}

/* the member's rows of E := Us * (those rows) */
static void symtmm_apply_rows(int m, int nc, double complex Us[m][m], double complex E[][nc],
                              const int rows[m])
{
    for (int j = 0; j < nc; j++) {
        double complex t[m];
        for (int i = 0; i < m; i++) {
            t[i] = 0.0;
            for (int k = 0; k < m; k++)
                t[i] += Us[i][k] * E[rows[k]][j];
        }
        for (int i = 0; i < m; i++)
            E[rows[i]][j] = t[i];
    }
}
