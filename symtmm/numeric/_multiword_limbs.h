/*
 * Balls of an integer mantissa of NW 64-bit words, for _multiword.c (included there once
 * per NW, 3 to 8, with F, BALL and W_ defined; see there for the arithmetic and its bounds).
 */
#define MUL(a, b) F(mul)(&(a), &(b))
#define ADD(a, b) F(add)(&(a), &(b))
#define SUB(a, b) F(sub)(&(a), &(b))

/* (-1)^s 0.m[0]m[1]..m[NW-1] (binary) 2^e, m[0] >= 2^63, or 0 (every word 0, e = s = 0);
 * the radius r a double. Stored as NW + 3 words: m, e, s, the bits of r. */
typedef struct { uint64_t m[NW]; int64_t e; int64_t s; double r; } BALL;

static inline int F(is_zero)(const BALL *x) { return x->m[0] == 0 && x->r == 0.0; }

static inline int F(finite)(const BALL *x)
{
    return isfinite(x->r) && (x->m[0] == 0 || (x->e <= EXP_MAX && x->e >= -EXP_MAX));
}

/* Bounds of |midpoint| as doubles: its leading 53 bits (exact), plus one unit of the last
 * of them for the upper bound; out of the doubles' range, 2^-EXP_MAX and +inf. */
static inline double F(mid_low)(const BALL *x)
{
    if (x->m[0] == 0 || x->e < -EXP_MAX)
        return 0.0;
    return (double)(x->m[0] >> 11) * pow2((int)(x->e > EXP_MAX ? EXP_MAX : x->e) - 53);
}

static inline double F(mid_up)(const BALL *x)
{
    if (x->m[0] == 0)
        return 0.0;
    if (x->e < -EXP_MAX)
        return ldexp(1.0, -EXP_MAX);
    if (x->e > EXP_MAX)
        return INFINITY;
    return (double)((x->m[0] >> 11) + 1) * pow2((int)x->e - 53);
}

/* the midpoint to the nearest double or so (signs, choices, the Newton start) */
static inline double F(head)(const BALL *x)
{
    if (x->m[0] == 0)
        return 0.0;
    const double v = ldexp((double)x->m[0], (int)(x->e < -1100 ? -1100 : x->e > 1100 ? 1100
                                                                       : x->e) - 64);
    return x->s ? -v : v;
}

/* an upper bound of |v| over the ball; the radius grown by t >= 0 */
static inline double F(mag)(const BALL *x) { return up(F(mid_up)(x) + x->r); }

static inline void F(widen)(BALL *x, double t) { x->r = up(x->r + t); }

/* one unit of the word `words` (counted from 1) of a number of exponent e: 2^(e - 64 words)
 * (below 2^-1021, which up() adds anyway: 0) */
static inline double F(unit)(int64_t e, int words)
{
    const int64_t k = e - 64 * (int64_t)words;
    if (k < -1021)
        return 0.0;
    return k > EXP_MAX ? INFINITY : pow2((int)k);
}

static inline double F(ulp)(int64_t e) { return F(unit)(e, NW); }

static inline BALL F(exact)(double v)
{
    BALL z;
    for (int i = 0; i < NW; i++)
        z.m[i] = 0;
    z.e = 0;
    z.s = 0;
    z.r = 0.0;
    if (v != 0.0 && isfinite(v)) {
        int e;
        const double f = frexp(fabs(v), &e);            /* in [1/2, 1), 53 bits */
        z.m[0] = (uint64_t)ldexp(f, 64);
        z.e = e;
        z.s = v < 0;
    } else if (!isfinite(v)) {
        z.r = INFINITY;
    }
    return z;
}

static inline BALL F(neg)(BALL x)
{
    if (x.m[0] != 0)
        x.s = !x.s;
    return x;
}

/* Shift the len words t right by k bits (into zeros); whether a nonzero bit fell out. */
static inline int F(shift_right)(uint64_t *t, int len, int64_t k)
{
    int lost = 0;
    if (k <= 0)
        return 0;
    if (k >= 64 * (int64_t)len) {
        for (int i = 0; i < len; i++) {
            lost |= t[i] != 0;
            t[i] = 0;
        }
        return lost;
    }
    const int q = (int)(k / 64), b = (int)(k % 64);
    for (int i = len - q; i < len; i++)
        lost |= t[i] != 0;
    if (b)
        lost |= (t[len - q - 1] << (64 - b)) != 0;
    for (int i = len - 1; i >= 0; i--) {
        const int src = i - q;
        uint64_t v = 0;
        if (src >= 0) {
            v = b ? t[src] >> b : t[src];
            if (b && src - 1 >= 0)
                v |= t[src - 1] << (64 - b);
        }
        t[i] = v;
    }
    return lost;
}

/* Normalise the len words t (top bit of t[0] set) by shifting left; adjusts *e; 0 if all
 * the words are 0. */
static inline int F(normalise)(uint64_t *t, int len, int64_t *e)
{
    int z = 0;
    while (z < len && t[z] == 0)
        z++;
    if (z == len)
        return 0;
    const int c = __builtin_clzll(t[z]);
    const int64_t k = 64 * (int64_t)z + c;
    if (k) {
        const int q = z, b = c;
        for (int i = 0; i < len; i++) {
            const int src = i + q;
            uint64_t v = 0;
            if (src < len) {
                v = b ? t[src] << b : t[src];
                if (b && src + 1 < len)
                    v |= t[src + 1] >> (64 - b);
            }
            t[i] = v;
        }
        *e -= k;
    }
    return 1;
}

/* |x| against |y| for nonzero midpoints: -1, 0, 1 */
static inline int F(cmp_abs)(const BALL *x, const BALL *y)
{
    if (x->e != y->e)
        return x->e > y->e ? 1 : -1;
    for (int i = 0; i < NW; i++)
        if (x->m[i] != y->m[i])
            return x->m[i] > y->m[i] ? 1 : -1;
    return 0;
}

static inline BALL F(add)(const BALL *x, const BALL *y)
{
    if (x->m[0] == 0) {
        BALL z = *y;
        z.r = x->r == 0.0 ? y->r : up(x->r + y->r);
        return z;
    }
    if (y->m[0] == 0) {
        BALL z = *x;
        z.r = y->r == 0.0 ? x->r : up(x->r + y->r);
        return z;
    }
    const int c = F(cmp_abs)(x, y);
    const BALL *a = c >= 0 ? x : y, *b = c >= 0 ? y : x;     /* |a| >= |b| */
    /* with one guard word: the smaller aligned to the larger's exponent */
    uint64_t A[NW + 1], Bs[NW + 1];
    for (int i = 0; i < NW; i++) {
        A[i] = a->m[i];
        Bs[i] = b->m[i];
    }
    A[NW] = Bs[NW] = 0;
    const int lost = F(shift_right)(Bs, NW + 1, a->e - b->e);
    BALL z;
    int64_t e = a->e;
    /* what fell out below the guard word: less than one unit of it */
    double err = lost ? F(unit)(a->e, NW + 1) : 0.0;
    if (a->s == b->s) {
        unsigned __int128 carry = 0;
        for (int i = NW; i >= 0; i--) {
            const unsigned __int128 s = (unsigned __int128)A[i] + Bs[i] + carry;
            A[i] = (uint64_t)s;
            carry = s >> 64;
        }
        if (carry) {
            const int out = (int)(A[NW] & 1);
            for (int i = NW; i > 0; i--)
                A[i] = (A[i] >> 1) | (A[i - 1] << 63);
            A[0] = (A[0] >> 1) | ((uint64_t)1 << 63);
            e += 1;
            if (out)
                err += F(unit)(e, NW + 1);
        }
    } else {
        uint64_t borrow = 0;
        for (int i = NW; i >= 0; i--) {
            const uint64_t ai = A[i], bi = Bs[i];
            const uint64_t d = ai - bi - borrow;
            borrow = (ai < bi) || (ai - bi < borrow);
            A[i] = d;
        }
        if (!F(normalise)(A, NW + 1, &e)) {
            for (int i = 0; i < NW; i++)
                z.m[i] = 0;
            z.e = z.s = 0;
            const double r = x->r + y->r + err;
            z.r = r == 0.0 ? 0.0 : up(r);
            return z;
        }
    }
    for (int i = 0; i < NW; i++)
        z.m[i] = A[i];
    z.e = e;
    z.s = a->s;
    if (A[NW])
        err += F(ulp)(e);
    const double r = x->r + y->r + err;
    z.r = r == 0.0 ? 0.0 : up(r);            /* (exact sums stay exact) */
    return z;
}

static inline BALL F(sub)(const BALL *x, const BALL *y)
{
    const BALL ny = F(neg)(*y);
    return F(add)(x, &ny);
}

static inline BALL F(mul)(const BALL *x, const BALL *y)
{
    BALL z;
    if (x->m[0] == 0 || y->m[0] == 0) {
        for (int i = 0; i < NW; i++)
            z.m[i] = 0;
        z.e = z.s = 0;
        z.r = (x->r == 0.0 && y->r == 0.0) ? 0.0
              : up(F(mid_up)(x) * y->r + F(mid_up)(y) * x->r + x->r * y->r);
        return z;
    }
    /* the whole product, most significant word first */
    uint64_t t[2 * NW];
    for (int i = 0; i < 2 * NW; i++)
        t[i] = 0;
    for (int i = NW - 1; i >= 0; i--) {
        unsigned __int128 carry = 0;
        for (int j = NW - 1; j >= 0; j--) {
            const unsigned __int128 cur = (unsigned __int128)x->m[i] * y->m[j] + t[i + j + 1]
                                          + carry;
            t[i + j + 1] = (uint64_t)cur;
            carry = cur >> 64;
        }
        t[i] = (uint64_t)carry;
    }
    int64_t e = x->e + y->e;
    if (!(t[0] >> 63)) {                     /* the product of two mantissas is >= 1/4 */
        for (int i = 0; i < 2 * NW - 1; i++)
            t[i] = (t[i] << 1) | (t[i + 1] >> 63);
        t[2 * NW - 1] <<= 1;
        e -= 1;
    }
    int lost = 0;
    for (int i = NW; i < 2 * NW; i++)
        lost |= t[i] != 0;
    for (int i = 0; i < NW; i++)
        z.m[i] = t[i];
    z.e = e;
    z.s = x->s ^ y->s;
    const double err = lost ? F(ulp)(e) : 0.0;
    z.r = (x->r == 0.0 && y->r == 0.0 && err == 0.0) ? 0.0
          : up(F(mid_up)(x) * y->r + F(mid_up)(y) * x->r + x->r * y->r + err);
    return z;
}

/* x times an exact power of two 2^k: exact */
static inline BALL F(scale)(const BALL *x, int k)
{
    BALL z = *x;
    if (z.m[0] != 0)
        z.e += k;
    z.r = x->r == 0.0 ? 0.0 : up(ldexp(x->r, k));
    return z;
}

/* k where c is exactly 2^k (a radius of 0); else 0 with *is = 0 */
static inline int F(power_of_two)(const BALL *c, int *k)
{
    *k = 0;
    if (c->r != 0.0 || c->m[0] != ((uint64_t)1 << 63) || c->s || c->e > EXP_MAX
            || c->e < -EXP_MAX)
        return 0;
    for (int i = 1; i < NW; i++)
        if (c->m[i])
            return 0;
    *k = (int)c->e - 1;
    return 1;
}

/* A lower bound of |v| over the ball (<= 0 where it may hold 0), and of its midpoint's. */
static inline double F(least)(const BALL *x, double *least_mid)
{
    const double mid = F(mid_low)(x);
    if (least_mid)
        *least_mid = mid;
    return mid - up(x->r);
}

static inline int F(nonzero)(const BALL *x)
{
    return F(finite)(x) && F(least)(x, NULL) > 0.0;
}

static inline int F(negative)(const BALL *x) { return x->m[0] != 0 && x->s; }

/* 1 / y; a radius of +inf where the ball may hold 0 (or is not finite) */
static inline BALL F(inv)(const BALL *y)
{
    double low_mid;
    const double low = F(least)(y, &low_mid);
    if (!(low > 0.0) || !F(finite)(y)) {
        BALL z = F(exact)(0.0);
        z.r = INFINITY;
        return z;
    }
    BALL mid = *y;
    mid.r = 0.0;
    const BALL one = F(exact)(1.0);
    BALL q = F(exact)(1.0 / F(head)(y));
    /* Newton steps q + q (1 - y q): 50 bits or so, then twice as many per step */
    for (int bits = 50; bits < 64 * NW; bits *= 2) {
        const BALL yq = MUL(mid, q);
        const BALL res = SUB(one, yq);
        const BALL corr = MUL(q, res);
        q = ADD(q, corr);
        q.r = 0.0;
    }
    /* a posteriori: |1/y_mid - q| = |1 - q y_mid| / |y_mid| */
    const BALL yq = MUL(mid, q);
    const BALL rho = SUB(one, yq);
    const double err = up(up(F(mid_up)(&rho) + rho.r) / low_mid);
    /* |1/y - 1/y_mid| = |y - y_mid| / (|y| |y_mid|) */
    const double spread = up(y->r / low / low_mid);
    q.r = up(err + spread);
    return q;
}

static inline BALL F(load)(const uint64_t *p)
{
    BALL z;
    for (int i = 0; i < NW; i++)
        z.m[i] = p[i];
    z.e = (int64_t)p[NW];
    z.s = (int64_t)p[NW + 1];
    memcpy(&z.r, p + NW + 2, sizeof(double));
    return z;
}

static inline void F(store)(uint64_t *p, const BALL *z)
{
    for (int i = 0; i < NW; i++)
        p[i] = z->m[i];
    p[NW] = (uint64_t)z->e;
    p[NW + 1] = (uint64_t)z->s;
    memcpy(p + NW + 2, &z->r, sizeof(double));
}

/* Rescale x to exponent 0 where its exponent left +-400 (running products): its value is
 * then x 2^*shift. */
static inline void F(rescale)(BALL *x, int64_t *shift)
{
    if (x->m[0] != 0 && (x->e > 400 || x->e < -400)) {
        *shift += x->e;
        x->r = up(ldexp(x->r, (int)-x->e));
        x->e = 0;
    }
}

#undef MUL
#undef ADD
#undef SUB
