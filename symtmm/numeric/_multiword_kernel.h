/*
 * The kernel of _multiword.c over one of its ball arithmetics (included after it, with F,
 * BALL, W_ and PREC_BITS defined): the series of the c_j and the Euler-Bernoulli
 * stiffness, the general beams' series and stiffness, the scatter, the band LDL^T with 2x2
 * blocks, running products, and the entry points of the tests. A ball is read through its
 * arithmetic's functions only (F(mag): an upper bound of its modulus; F(widen): its
 * radius grown by a bound): real balls and complex ones (pairs of real balls) alike.
 */
#define MUL(a, b) F(mul)(&(a), &(b))
#define ADD(a, b) F(add)(&(a), &(b))
#define SUB(a, b) F(sub)(&(a), &(b))

/* p q + r s, the products first (the order every caller had written out) */
static inline BALL F(dot2)(const BALL *p, const BALL *q, const BALL *r, const BALL *s)
{
    const BALL x = F(mul)(p, q), y = F(mul)(r, s);
    return F(add)(&x, &y);
}
#define DOT2(p, q, r, s) F(dot2)(&(p), &(q), &(r), &(s))

/* a + b c, the product first */
static inline BALL F(plus_product)(const BALL *a, const BALL *b, const BALL *c)
{
    const BALL x = F(mul)(b, c);
    return F(add)(a, &x);
}
#define PLUS_PRODUCT(a, b, c) F(plus_product)(&(a), &(b), &(c))

/* Whether k terms of c_j serve at X (XK the bound of X^k): the terms shrink at least
 * twofold beyond them, and their tail, *tail, is below goal (or k is the last). */
static inline int F(enough)(double X, double XK, const double *tails, Py_ssize_t K, int j,
                            Py_ssize_t k, double goal, double *tail)
{
    const double q = (double)(4 * k + j + 1) * (4 * k + j + 2) * (4 * k + j + 3)
                     * (4 * k + j + 4);
    if (!(X <= 0.5 * q * DEFLATE))
        return 0;
    *tail = up(2.0 * XK * tails[(K + 1) * j + k]);
    return *tail <= goal || k == K;
}

#define KRYLOV_POWERS 128

/* c_j(x) = sum_k x^k / (4k + j)!, j = 0..3, each with the fewest terms (at most K) whose
 * tail is below 2^-PREC_BITS: coef (4, K, W_) the balls of 1/(4k + j)!, tails (4, K + 1)
 * upper bounds of 1/(4k + j)!. The tail beyond k terms is at most twice the first omitted
 * term where consecutive terms shrink at least twofold, |x| <= (4k+j+1)..(4k+j+4) / 2. */
static int F(krylov)(const BALL *x, const uint64_t *coef, const double *tails, Py_ssize_t K,
                     BALL c[4])
{
    const double X = F(mag)(x);
    const double goal = ldexp(1.0, -PREC_BITS);
    /* the bounds of X^k, kept from c_0's search: c_1..c_3 need no more terms than c_0
     * (larger denominators, smaller tails; the rule holds from some k on), so theirs is
     * found from c_0's count downward, a check or two each where the upward search from
     * k = 1 took one per term (in doubles, that search cost four times the series) */
    double XKs[KRYLOV_POWERS];
    Py_ssize_t first = 0;
    for (int j = 0; j < 4; j++) {
        double XK = 1.0, tail = INFINITY, t;
        Py_ssize_t terms = 0;
        if (j > 0 && first) {
            terms = first;
            if (!F(enough)(X, XKs[terms], tails, K, j, terms, goal, &tail))
                return 0;               /* (cannot happen: the rule holds for c_j there) */
            while (terms > 1 && F(enough)(X, XKs[terms - 1], tails, K, j, terms - 1, goal, &t)) {
                terms--;
                tail = t;
            }
        } else {
            for (Py_ssize_t k = 1; k <= K && !terms; k++) {
                XK = up(XK * X);
                if (k < KRYLOV_POWERS)
                    XKs[k] = XK;
                if (F(enough)(X, XK, tails, K, j, k, goal, &t)) {
                    terms = k;
                    tail = t;
                }
            }
            if (j == 0 && terms < KRYLOV_POWERS)
                first = terms;
        }
        if (!terms)
            return 0;
#ifdef PLAIN_DOUBLE
        /* (no radius to carry a tail beyond the resolution: such a point fails) */
        if (!(tail <= goal))
            return 0;
#endif
        const uint64_t *cj = coef + W_ * K * j;
        BALL acc = F(load)(cj + W_ * (terms - 1));
        for (Py_ssize_t k = terms - 2; k >= 0; k--) {
            const BALL t = MUL(acc, *x), ck = F(load)(cj + W_ * k);
            acc = ADD(t, ck);
        }
        F(widen)(&acc, tail);
        if (!F(finite)(&acc))
            return 0;
        c[j] = acc;
    }
    return 1;
}

/* The 4x4 stiffness of a kind (row-major, rows (Q0, -M0, -Q1, M1), columns (Y0, Theta0,
 * Y1, Theta1)) and det U12, at lam2, as symtmm.numeric.stiffness.eb_stiffness. */
static int F(eb_kind)(const BALL *lam2, const uint64_t *kc, const uint64_t *coef,
                      const double *tails, Py_ssize_t K, uint64_t *D, uint64_t *det12)
{
    const BALL EI = F(load)(kc), l = F(load)(kc + W_), A = F(load)(kc + 2 * W_),
               Fx = F(load)(kc + 3 * W_);
    const BALL lA = MUL(*lam2, A), lAF = ADD(lA, Fx), x = F(neg)(lAF);
    BALL c[4];
    if (!F(krylov)(&x, coef, tails, K, c))
        return 0;
    const BALL c22 = MUL(c[2], c[2]), c13 = MUL(c[1], c[3]), dc = SUB(c22, c13);
    const BALL l2 = MUL(l, l), l3 = MUL(l2, l), l3dc = MUL(l3, dc);
    const BALL inv = F(inv)(&l3dc), s = MUL(EI, inv);
    const BALL sl = MUL(s, l), sl2 = MUL(sl, l);
    const BALL c01 = MUL(c[0], c[1]), c23 = MUL(c[2], c[3]), xc23 = MUL(x, c23);
    const BALL e11 = SUB(c01, xc23), k11 = MUL(s, e11);
    const BALL c11 = MUL(c[1], c[1]), c02 = MUL(c[0], c[2]), e12 = SUB(c11, c02);
    const BALL k12 = MUL(sl, e12), k13 = MUL(s, c[1]), k14 = MUL(sl, c[2]);
    const BALL c12 = MUL(c[1], c[2]), c03 = MUL(c[0], c[3]), e22 = SUB(c12, c03);
    const BALL k22 = MUL(sl2, e22), k24 = MUL(sl2, c[3]);
    const BALL m13 = F(neg)(k13), m14 = F(neg)(k14), m12 = F(neg)(k12);
    const BALL rows[16] = {k11, k12, m13, k14, k12, k22, m14, k24,
                           m13, m14, k11, m12, k14, k24, m12, k22};
    for (int i = 0; i < 16; i++) {
        if (!F(finite)(&rows[i]))
            return 0;
        F(store)(D + W_ * i, &rows[i]);
    }
    const BALL l4 = MUL(l2, l2), l4dc = MUL(l4, dc), EI2 = MUL(EI, EI);
    const BALL iEI2 = F(inv)(&EI2), det = MUL(l4dc, iEI2);
    if (!F(finite)(&det))
        return 0;
    F(store)(det12, &det);
    return 1;
}

/* The 4x4 stiffness and det U12 of a general beam kind (axial force, rotary inertia, shear:
 * symtmm.numeric.segments.theory_matrices, then stiffness.coupled_stiffness of one beam),
 * kc = (EI, a, b, cN, rhoI, m, kw, l). F0, F1 by their series in (t, d) on a piece
 * h = l / 2^j with rho h^2 <= 1/2 (rho >= the largest |r|, r the eigenvalues of G; then
 * |q_k| <= k and the tails beyond TK terms are below 2 TK / (2 TK)! and 2 TK / (2 TK + 1)!,
 * ttails), then doubled j times. tcoef: the balls of 1/k!, k < 2 TK + 2. */
static int F(theory_kind)(const BALL *lam2, const uint64_t *kc, const uint64_t *tcoef,
                          const double *ttails, Py_ssize_t TK, uint64_t *D, uint64_t *det12)
{
    const BALL EI = F(load)(kc), a = F(load)(kc + W_), b = F(load)(kc + 2 * W_),
               cN = F(load)(kc + 3 * W_), rhoI = F(load)(kc + 4 * W_),
               m = F(load)(kc + 5 * W_), kw = F(load)(kc + 6 * W_), l = F(load)(kc + 7 * W_);
    const BALL rl = MUL(rhoI, *lam2), c = ADD(cN, rl);
    const BALL ml = MUL(m, *lam2), mu = ADD(ml, kw);
    const BALL iEI = F(inv)(&EI);
    const BALL ci = MUL(c, iEI), bm = MUL(b, mu), t = SUB(ci, bm);
    const BALL aa = MUL(a, a), bc = MUL(b, c), ab = SUB(aa, bc), mab = MUL(mu, ab),
               d = MUL(mab, iEI);
    if (!F(finite)(&t) || !F(finite)(&d))
        return 0;
    const double tu = F(mag)(&t), du = F(mag)(&d);
    const double rho = up(tu / 2 + up(sqrt(up(tu * tu / 4 + du))));
    const double lu = F(mag)(&l);
    int j = 0;
    double reach = up(rho * up(lu * lu));
    while (!(reach <= 0.5 * DEFLATE)) {
        if (++j > 60 || !isfinite(reach))
            return 0;
        reach = up(reach / 4);
    }
    const BALL h = F(scale)(&l, -j), hh = MUL(h, h), T = MUL(t, hh), hhhh = MUL(hh, hh),
               Dd = MUL(d, hhhh);
    BALL q_prev = F(exact)(0.0), q = F(exact)(1.0);
    BALL s0b = F(exact)(0.0), s0a = s0b, s1b = s0b, s1a = s0b;
    for (Py_ssize_t k = 1; k < TK; k++) {
        const BALL e2 = F(load)(tcoef + W_ * 2 * k), e3 = F(load)(tcoef + W_ * (2 * k + 1));
        const BALL u0 = MUL(q, e2), u1 = MUL(q_prev, e2), u2 = MUL(q, e3), u3 = MUL(q_prev, e3);
        s0b = ADD(s0b, u0);
        s0a = ADD(s0a, u1);
        s1b = ADD(s1b, u2);
        s1a = ADD(s1a, u3);
        const BALL Tq = MUL(T, q), Dq = MUL(Dd, q_prev);
        q_prev = q;
        q = SUB(Tq, Dq);
    }
    F(widen)(&s0b, ttails[0]);
    F(widen)(&s0a, ttails[0]);
    F(widen)(&s1b, ttails[1]);
    F(widen)(&s1a, ttails[1]);
    const BALL one = F(exact)(1.0), two = F(exact)(2.0);
    const BALL D0 = MUL(Dd, s0a), D1 = MUL(Dd, s1a), om1 = SUB(one, D1), hhh = MUL(hh, h);
    BALL a0 = SUB(one, D0), b0 = MUL(hh, s0b), a1 = MUL(h, om1), b1 = MUL(hhh, s1b);
    for (int i = 0; i < j; i++) {
        /* F0(2h) = 2 F0^2 - I, F1(2h) = 2 F0 F1, with G^2 = t G - d I */
        const BALL a0a0 = MUL(a0, a0), b0b0 = MUL(b0, b0), db0b0 = MUL(d, b0b0),
                   a0b0 = MUL(a0, b0), tb0b0 = MUL(t, b0b0), a0a1 = MUL(a0, a1),
                   b0b1 = MUL(b0, b1), db0b1 = MUL(d, b0b1), a0b1 = MUL(a0, b1),
                   a1b0 = MUL(a1, b0), tb0b1 = MUL(t, b0b1);
        const BALL x0 = SUB(a0a0, db0b0), x0t = MUL(two, x0);
        const BALL y0 = MUL(two, a0b0), y1 = ADD(y0, tb0b0);
        const BALL z0 = SUB(a0a1, db0b1), w0 = ADD(a0b1, a1b0), w1 = ADD(w0, tb0b1);
        a0 = SUB(x0t, one);
        b0 = MUL(two, y1);
        a1 = MUL(two, z0);
        b1 = MUL(two, w1);
    }
    if (!F(finite)(&a0) || !F(finite)(&b0) || !F(finite)(&a1) || !F(finite)(&b1))
        return 0;
    /* U in the order [Y, Theta, M, Q] (segments._assemble) */
    const BALL g00 = F(neg)(bm), g01 = MUL(a, iEI), am = MUL(a, mu), g10 = F(neg)(am),
               g11 = ci;
    const BALL p00 = ci, p01 = g01, p10 = g10, p11 = g00;
    const BALL t00 = MUL(b1, p00), t01 = MUL(b1, p01), t10 = MUL(b1, p10), t11 = MUL(b1, p11);
    const BALL h00 = ADD(a1, t00), h01 = t01, h10 = t10, h11 = ADD(a1, t11);
    const BALL v00 = MUL(b1, g00), v01 = MUL(b1, g01), v10 = MUL(b1, g10), v11 = MUL(b1, g11);
    const BALL k00 = ADD(a1, v00), k01 = v01, k10 = v10, k11 = ADD(a1, v11);
    BALL U[4][4];
    const BALL mk00 = MUL(mu, k00), mk01 = MUL(mu, k01);
    U[0][0] = PLUS_PRODUCT(a0, b0, g00);
    U[0][1] = DOT2(a, h00, b, h10);
    U[0][2] = MUL(b0, g01);
    U[0][3] = DOT2(a, h01, b, h11);
    U[1][0] = MUL(k10, iEI);
    U[1][1] = PLUS_PRODUCT(a0, b0, p00);
    U[1][2] = MUL(k11, iEI);
    U[1][3] = MUL(b0, p01);
    U[2][0] = MUL(b0, g10);
    U[2][1] = DOT2(c, h00, a, h10);
    U[2][2] = PLUS_PRODUCT(a0, b0, g11);
    U[2][3] = DOT2(c, h01, a, h11);
    U[3][0] = F(neg)(mk00);
    U[3][1] = MUL(b0, p10);
    U[3][2] = F(neg)(mk01);
    U[3][3] = PLUS_PRODUCT(a0, b0, p11);
    /* the stiffness of one beam (stiffness.coupled_stiffness): f0 = A d0 + inv d1,
     * f1 = C d0 + E d1 with inv = U12^-1, A = -inv U11, C = U21 + U22 A, E = U22 inv */
    const BALL u00 = MUL(U[0][2], U[1][3]), u11 = MUL(U[0][3], U[1][2]), det = SUB(u00, u11);
    const BALL idet = F(inv)(&det);
    BALL I[2][2], A2[2][2], C2[2][2], E2[2][2];
    I[0][0] = MUL(U[1][3], idet);
    {
        const BALL x = MUL(U[0][3], idet), y = MUL(U[1][2], idet);
        I[0][1] = F(neg)(x);
        I[1][0] = F(neg)(y);
    }
    I[1][1] = MUL(U[0][2], idet);
    for (int r = 0; r < 2; r++)
        for (int q2 = 0; q2 < 2; q2++) {
            const BALL x = MUL(I[r][0], U[0][q2]), y = MUL(I[r][1], U[1][q2]), s2 = ADD(x, y);
            A2[r][q2] = F(neg)(s2);
        }
    for (int r = 0; r < 2; r++)
        for (int q2 = 0; q2 < 2; q2++) {
            const BALL x = MUL(U[2 + r][2], A2[0][q2]), y = MUL(U[2 + r][3], A2[1][q2]),
                       s2 = ADD(x, y), x2 = MUL(U[2 + r][2], I[0][q2]),
                       y2 = MUL(U[2 + r][3], I[1][q2]);
            C2[r][q2] = ADD(U[2 + r][q2], s2);
            E2[r][q2] = ADD(x2, y2);
        }
    /* rows (Q0, -M0, -Q1, M1): f0 rows (M0, Q0), f1 rows (M1, Q1) */
    const BALL rows[16] = {
        A2[1][0], A2[1][1], I[1][0], I[1][1],
        F(neg)(A2[0][0]), F(neg)(A2[0][1]), F(neg)(I[0][0]), F(neg)(I[0][1]),
        F(neg)(C2[1][0]), F(neg)(C2[1][1]), F(neg)(E2[1][0]), F(neg)(E2[1][1]),
        C2[0][0], C2[0][1], E2[0][0], E2[0][1]};
    for (int i = 0; i < 16; i++) {
        if (!F(finite)(&rows[i]))
            return 0;
        F(store)(D + W_ * i, &rows[i]);
    }
    if (!F(finite)(&det))
        return 0;
    F(store)(det12, &det);
    return 1;
}

/* The band of every point (see assemble in _multiword.c). */
static void F(assemble_points)(const uint64_t *lam2s, const uint64_t *lams,
                               const uint64_t *kinds,
                               const long long *families, Py_ssize_t S,
                               const uint64_t *coef, const double *tails, Py_ssize_t K,
                               const uint64_t *tcoef, const double *ttails, Py_ssize_t TK,
                               const long long *tg, const long long *src, const uint64_t *bc,
                               const long long *st, Py_ssize_t Q, uint64_t *bands,
                               Py_ssize_t nk, uint64_t *dets, uint64_t *V, unsigned char *ok,
                               Py_ssize_t B, const uint64_t *given, Py_ssize_t G)
{
    const BALL one = F(exact)(1.0), zero = F(exact)(0.0);
    for (Py_ssize_t p = 0; p < B; p++) {
        const BALL lam2 = F(load)(lam2s + W_ * p);
        uint64_t *band = bands + W_ * p * nk, *det = dets + W_ * p * S;
        int fine = 1;
        Py_ssize_t g = 0;
        for (Py_ssize_t s = 0; fine && s < S; s++) {
            if (families[s] == FAMILY_GIVEN) {
                /* a kind whose values the caller computed (a long piece's closed forms):
                 * its 16 entries and det U12, the point's g-th of G */
                const uint64_t *from = given + W_ * 17 * (G * p + g++);
                for (int i = 0; fine && i < 17; i++) {
                    const BALL v = F(load)(from + W_ * i);
                    fine = F(finite)(&v);
                }
                memcpy(V + 16 * W_ * s, from, sizeof(uint64_t) * 16 * W_);
                memcpy(det + W_ * s, from + 16 * W_, sizeof(uint64_t) * W_);
                continue;
            }
            fine = families[s] == 0
                ? F(eb_kind)(&lam2, kinds + 8 * W_ * s, coef, tails, K, V + 16 * W_ * s,
                             det + W_ * s)
                : F(theory_kind)(&lam2, kinds + 8 * W_ * s, tcoef, ttails, TK,
                                 V + 16 * W_ * s, det + W_ * s);
        }
        ok[p] = (unsigned char)fine;
        if (!fine)
            continue;
        F(store)(V + W_ * (16 * S), &one);
        if (lams) {
            const BALL lam = F(load)(lams + W_ * p);
            F(store)(V + W_ * (16 * S + 1), &lam);
        } else {
            F(store)(V + W_ * (16 * S + 1), &zero);
        }
        F(store)(V + W_ * (16 * S + 2), &lam2);
        for (Py_ssize_t i = 0; i < nk; i++)
            F(store)(band + W_ * i, &zero);
        for (Py_ssize_t q = 0; q < Q; q++) {
            for (Py_ssize_t i = st[q]; i < st[q + 1]; i++) {
                const BALL v = F(load)(V + W_ * src[i]), c = F(load)(bc + W_ * i);
                int k2;
                const BALL term = F(power_of_two)(&c, &k2) ? F(scale)(&v, k2) : MUL(v, c);
                uint64_t *target = band + W_ * tg[i];
                if (q == 0) {
                    F(store)(target, &term);
                } else {
                    const BALL old = F(load)(target), sum = ADD(old, term);
                    F(store)(target, &sum);
                }
            }
        }
    }
}

/* One 1x1 pivot at row k: 0 where its ball holds 0. */
static int F(pivot1)(uint64_t *Kp, Py_ssize_t k, Py_ssize_t w)
{
    uint64_t *row = Kp + W_ * k * w;
    const BALL piv = F(load)(row);
    if (!F(nonzero)(&piv))
        return 0;
    const BALL inv = F(inv)(&piv);
    for (Py_ssize_t i = 1; i < w; i++) {
        const BALL ri = F(load)(row + W_ * i);
        if (F(is_zero)(&ri))
            continue;
        const BALL f = MUL(ri, inv);
        uint64_t *target = Kp + W_ * ((k + i) * w - i);
        for (Py_ssize_t j = i; j < w; j++) {
            const BALL rj = F(load)(row + W_ * j);
            if (F(is_zero)(&rj))
                continue;
            const BALL old = F(load)(target + W_ * j), u = MUL(f, rj), z = SUB(old, u);
            F(store)(target + W_ * j, &z);
        }
    }
    return 1;
}

/* Rows k and k + 1 as one block (see pivot2 in _multiword.c). */
static int F(pivot2)(uint64_t *Kp, Py_ssize_t k, Py_ssize_t w)
{
    uint64_t *row0 = Kp + W_ * k * w, *row1 = Kp + W_ * (k + 1) * w;
    const BALL a = F(load)(row0), b = F(load)(row0 + W_), c = F(load)(row1);
    const BALL ac = MUL(a, c), bb = MUL(b, b), det = SUB(ac, bb);
    if (!F(nonzero)(&det))
        return 0;
    BALL d0, d1;
    if (F(negative)(&det)) {
        d0 = det;
        d1 = F(exact)(1.0);
    } else if (F(nonzero)(&a)) {
        const BALL ia = F(inv)(&a);
        d0 = a;
        d1 = MUL(det, ia);
    } else if (F(nonzero)(&c)) {
        const BALL ic = F(inv)(&c);
        d0 = c;
        d1 = MUL(det, ic);
    } else {
        return 0;
    }
    const BALL inv = F(inv)(&det), zero = F(exact)(0.0);
    /* columns k + 2 .. k + w: row k holds them at offsets 2 .. w - 1 (then 0), row k + 1
     * at offsets 1 .. w - 1 */
    const Py_ssize_t m = w - 1;
    BALL r0[m > 0 ? m : 1], r1[m > 0 ? m : 1], F0[m > 0 ? m : 1], F1[m > 0 ? m : 1];
    for (Py_ssize_t t = 0; t < m; t++) {
        r0[t] = t + 2 < w ? F(load)(row0 + W_ * (t + 2)) : zero;
        r1[t] = F(load)(row1 + W_ * (t + 1));
        BALL f0 = zero, f1 = zero;
        if (!F(is_zero)(&r0[t])) {
            f0 = MUL(c, r0[t]);
            const BALL br = MUL(b, r0[t]);
            f1 = F(neg)(br);
        }
        if (!F(is_zero)(&r1[t])) {
            const BALL br = MUL(b, r1[t]), ar = MUL(a, r1[t]);
            f0 = SUB(f0, br);
            f1 = ADD(f1, ar);
        }
        F0[t] = F(is_zero)(&f0) ? zero : MUL(f0, inv);
        F1[t] = F(is_zero)(&f1) ? zero : MUL(f1, inv);
    }
    for (Py_ssize_t s = 0; s < m; s++) {
        if (F(is_zero)(&r0[s]) && F(is_zero)(&r1[s]))
            continue;
        uint64_t *target = Kp + W_ * ((k + 2 + s) * w - s);
        for (Py_ssize_t t = s; t < m; t++) {
            BALL u = zero;
            if (!F(is_zero)(&r0[s]) && !F(is_zero)(&F0[t]))
                u = MUL(r0[s], F0[t]);
            if (!F(is_zero)(&r1[s]) && !F(is_zero)(&F1[t])) {
                const BALL v = MUL(r1[s], F1[t]);
                u = F(is_zero)(&u) ? v : ADD(u, v);
            }
            if (!F(is_zero)(&u)) {
                const BALL old = F(load)(target + W_ * t), z = SUB(old, u);
                F(store)(target + W_ * t, &z);
            }
        }
    }
    if (!F(finite)(&d0) || !F(finite)(&d1))
        return 0;
    F(store)(row0, &d0);
    F(store)(row1, &d1);
    return 1;
}

/* The freedoms 0 .. end - 1 of one band eliminated downward, a tiny pivot with the next
 * freedom as a 2x2 block (within them): 0 where a pivot or block is not decided. */
static int F(downward)(uint64_t *Kp, Py_ssize_t w, Py_ssize_t end)
{
    Py_ssize_t k = 0;
    while (k < end) {
        const BALL a = F(load)(Kp + W_ * k * w);
        int pair = 0;
        if (k + 1 < end && w > 1) {
            const BALL next = F(load)(Kp + W_ * k * w + W_);
            pair = !F(nonzero)(&a)
                   || ldexp(fabs(F(head)(&a)), PAIR_BITS) < fabs(F(head)(&next));
        }
        if (pair ? !F(pivot2)(Kp, k, w) : !F(pivot1)(Kp, k, w))
            return 0;
        k += pair ? 2 : 1;
    }
    return 1;
}

/* LDL^T of every point's band (see eliminate in _multiword.c). */
static void F(eliminate_points)(uint64_t *buf, Py_ssize_t B, Py_ssize_t rows, Py_ssize_t w,
                                Py_ssize_t n, unsigned char *ok)
{
    for (Py_ssize_t p = 0; p < B; p++)
        if (ok[p])
            ok[p] = (unsigned char)F(downward)(buf + W_ * p * rows * w, w, n);
}

/* One 1x1 pivot at row s eliminated upward, over the active rows lo .. s - 1 (a twisted
 * factorisation's lower part): K(s - j, s - i) -= K(s - i, s) K(s - j, s) / K(s, s) for
 * 1 <= i <= j, the mirror of pivot1; 0 where the pivot's ball holds 0. */
static int F(pivot1_up)(uint64_t *Kp, Py_ssize_t s, Py_ssize_t w, Py_ssize_t lo)
{
    const BALL piv = F(load)(Kp + W_ * s * w);
    if (!F(nonzero)(&piv))
        return 0;
    const Py_ssize_t m = s - lo < w - 1 ? s - lo : w - 1;
    if (m < 1)
        return 1;
    const BALL inv = F(inv)(&piv);
    for (Py_ssize_t i = 1; i <= m; i++) {
        const BALL ri = F(load)(Kp + W_ * ((s - i) * w + i));
        if (F(is_zero)(&ri))
            continue;
        const BALL f = MUL(ri, inv);
        for (Py_ssize_t j = i; j <= m; j++) {
            const BALL rj = F(load)(Kp + W_ * ((s - j) * w + j));
            if (F(is_zero)(&rj))
                continue;
            uint64_t *target = Kp + W_ * ((s - j) * w + (j - i));
            const BALL old = F(load)(target), u = MUL(f, rj), z = SUB(old, u);
            F(store)(target, &z);
        }
    }
    return 1;
}

/* The twisted LDL^T of every point's band (see eliminate_twisted in _multiword.c): the
 * freedoms 0 .. t - 1 eliminated downward (as eliminate_points, 2x2 blocks within them),
 * then n - 1 .. t + 1 upward (1x1 pivots), then t, t = splits[p]; every pivot d_k left at
 * row k. */
static void F(eliminate_twisted_points)(uint64_t *buf, Py_ssize_t B, Py_ssize_t rows,
                                        Py_ssize_t w, Py_ssize_t n, const long long *splits,
                                        unsigned char *ok)
{
    for (Py_ssize_t p = 0; p < B; p++) {
        if (!ok[p])
            continue;
        uint64_t *Kp = buf + W_ * p * rows * w;
        const Py_ssize_t t = splits[p];
        int fine = t >= 0 && t < n && F(downward)(Kp, w, t);
        for (Py_ssize_t s = n - 1; fine && s >= t; s--)
            fine = F(pivot1_up)(Kp, s, w, t);
        ok[p] = (unsigned char)fine;
    }
}

/* out[p] = prod_i x[p, i]^k[i] (k >= 0), by squaring: a ball (W_ words) and a power of two
 * it is to be multiplied by (a product such as Delta leaves the doubles' range: the
 * running product is rescaled as it goes), W_ + 1 words; ok[p] = 0 where not finite. */
static void F(power_product_points)(const uint64_t *x, Py_ssize_t count, const long long *k,
                                    uint64_t *out, unsigned char *ok, Py_ssize_t B)
{
    for (Py_ssize_t p = 0; p < B; p++) {
        BALL acc = F(exact)(1.0);
        int64_t shift = 0;
        int fine = 1;
        for (Py_ssize_t i = 0; fine && i < count; i++) {
            BALL base = F(load)(x + W_ * (p * count + i));
            for (long long m = k[i]; fine && m > 0; m >>= 1) {
                if (m & 1)
                    acc = MUL(acc, base);
                if (m > 1)
                    base = MUL(base, base);
                F(rescale)(&acc, &shift);
                fine = F(finite)(&acc) && F(finite)(&base);
            }
        }
        ok[p] = (unsigned char)fine;
        F(store)(out + (W_ + 1) * p, &acc);
        out[(W_ + 1) * p + W_] = (uint64_t)shift;
    }
}

/* Elementwise operations (the tests): op 0 add, 1 sub, 2 mul, 3 x / y (as x times 1/y). */
static void F(ops_points)(int op, const uint64_t *x, const uint64_t *y, uint64_t *o,
                          Py_ssize_t M)
{
    for (Py_ssize_t i = 0; i < M; i++) {
        const BALL a = F(load)(x + W_ * i), b = F(load)(y + W_ * i);
        BALL z;
        switch (op) {
        case 0: z = ADD(a, b); break;
        case 1: z = SUB(a, b); break;
        case 2: z = MUL(a, b); break;
        default: {
            const BALL ib = F(inv)(&b);
            z = MUL(a, ib);
        }
        }
        F(store)(o + W_ * i, &z);
    }
}

/* The c_j of balls (the tests); radius +inf beyond the series' reach. */
static void F(krylov_points)(const uint64_t *x, const uint64_t *coef, const double *tails,
                             Py_ssize_t K, uint64_t *out, Py_ssize_t M)
{
    for (Py_ssize_t i = 0; i < M; i++) {
        BALL c[4];
        const BALL xi = F(load)(x + W_ * i);
        if (!F(krylov)(&xi, coef, tails, K, c)) {
            for (int j = 0; j < 4; j++) {
                c[j] = F(exact)(0.0);
                F(widen)(&c[j], INFINITY);
            }
        }
        for (int j = 0; j < 4; j++)
            F(store)(out + 4 * W_ * i + W_ * j, &c[j]);
    }
}

#undef MUL
#undef ADD
#undef SUB
