/*
 * Double-double balls for _multiword.c (included there once, with F, BALL and W_ defined):
 * a midpoint hi + lo of two doubles (|lo| at most half an ulp of hi after each operation)
 * and a radius r, stored as the bits of the three doubles. Each operation computes its
 * midpoint with error-free transformations (TwoSum; the product's error by fma) and adds
 * to the radius a bound of what it dropped or rounded:
 *
 *   x + y:  the heads' TwoSum, the tails and its error summed in two roundings: at most
 *           2u (|x.lo| + |y.lo| + |e|) (u = 2^-53), taken as 4u;
 *   x * y:  the heads' exact product, the cross terms and its error summed in three
 *           roundings: at most 3u of their magnitudes, taken as 8u; the tails' product
 *           dropped: bounded twice over;
 *   1 / y:  as the other balls (Newton, then the residual a posteriori).
 *
 * About 106 bits, at a few times the cost of a double operation: the first tier of the
 * 15-digit proofs.
 */
#define MUL(a, b) F(mul)(&(a), &(b))
#define ADD(a, b) F(add)(&(a), &(b))
#define SUB(a, b) F(sub)(&(a), &(b))

typedef struct { double hi, lo, r; } BALL;

static inline void F(two_sum)(double a, double b, double *s, double *e)
{
    const double x = a + b, bb = x - a;
    *e = (a - (x - bb)) + (b - bb);
    *s = x;
}

static inline int F(is_zero)(const BALL *x) { return x->hi == 0.0 && x->lo == 0.0 && x->r == 0.0; }

static inline int F(finite)(const BALL *x)
{
    return isfinite(x->hi) && isfinite(x->lo) && isfinite(x->r) && fabs(x->hi) < 0x1p1000;
}

static inline double F(mid_up)(const BALL *x) { return up(fabs(x->hi) + fabs(x->lo)); }

static inline double F(head)(const BALL *x) { return x->hi; }

/* an upper bound of |v| over the ball; the radius grown by t >= 0 */
static inline double F(mag)(const BALL *x) { return up(F(mid_up)(x) + x->r); }

static inline void F(widen)(BALL *x, double t) { x->r = up(x->r + t); }

static inline BALL F(exact)(double v)
{
    BALL z = {v, 0.0, isfinite(v) ? 0.0 : INFINITY};
    return z;
}

static inline BALL F(neg)(BALL x)
{
    x.hi = -x.hi;
    x.lo = -x.lo;
    return x;
}

static inline int F(negative)(const BALL *x) { return x->hi < 0.0; }

static inline BALL F(add)(const BALL *x, const BALL *y)
{
    double s, e, hi, lo;
    F(two_sum)(x->hi, y->hi, &s, &e);
    const double t = (x->lo + y->lo) + e;
    F(two_sum)(s, t, &hi, &lo);
    const double err = 0x1p-51 * (fabs(x->lo) + fabs(y->lo) + fabs(e));
    const double r = x->r + y->r + err;
    BALL z = {hi, lo, r == 0.0 ? 0.0 : up(r)};
    return z;
}

static inline BALL F(sub)(const BALL *x, const BALL *y)
{
    const BALL ny = F(neg)(*y);
    return F(add)(x, &ny);
}

static inline BALL F(mul)(const BALL *x, const BALL *y)
{
    const double p = x->hi * y->hi;
    const double e = fma(x->hi, y->hi, -p);
    const double t1 = x->hi * y->lo, t2 = x->lo * y->hi;
    const double t = (t1 + t2) + e;
    double hi, lo;
    F(two_sum)(p, t, &hi, &lo);
    const double err = 0x1p-50 * (fabs(t1) + fabs(t2) + fabs(e))
                       + 2.0 * (fabs(x->lo) * fabs(y->lo));
    const double ax = fabs(x->hi) + fabs(x->lo), ay = fabs(y->hi) + fabs(y->lo);
    const double r = ax * y->r + ay * x->r + x->r * y->r + err;
    BALL z = {hi, lo, r == 0.0 ? 0.0 : up(r)};
    return z;
}

/* x times 2^k: exact but for underflow (below 2^-900: TINY more) */
static inline BALL F(scale)(const BALL *x, int k)
{
    BALL z = {ldexp(x->hi, k), ldexp(x->lo, k), x->r == 0.0 ? 0.0 : up(ldexp(x->r, k))};
    if (z.hi != 0.0 && fabs(z.hi) < 0x1p-900)
        z.r = up(z.r + TINY);
    return z;
}

static inline int F(power_of_two)(const BALL *c, int *k)
{
    int e;
    *k = 0;
    if (c->lo != 0.0 || c->r != 0.0 || !(c->hi > 0.0) || frexp(c->hi, &e) != 0.5)
        return 0;
    *k = e - 1;
    return 1;
}

/* A lower bound of |v| over the ball (<= 0 where it may hold 0), and of its midpoint's. */
static inline double F(least)(const BALL *x, double *least_mid)
{
    const double mid = down(fabs(x->hi) - fabs(x->lo));
    if (least_mid)
        *least_mid = mid;
    return mid - up(x->r);
}

static inline int F(nonzero)(const BALL *x)
{
    return F(finite)(x) && F(least)(x, NULL) > 0.0;
}

/* 1 / y; a radius of +inf where the ball may hold 0 (or is not finite) */
static inline BALL F(inv)(const BALL *y)
{
    double low_mid;
    const double low = F(least)(y, &low_mid);
    if (!(low > 0.0) || !F(finite)(y)) {
        BALL z = {0.0, 0.0, INFINITY};
        return z;
    }
    /* q1 = 1/y.hi, one Newton step q = q1 + q1 (1 - q1 y) */
    const BALL one = F(exact)(1.0), mid = {y->hi, y->lo, 0.0}, q1 = F(exact)(1.0 / y->hi);
    const BALL yq1 = MUL(q1, mid), res = SUB(one, yq1);
    double hi, lo;
    F(two_sum)(q1.hi, q1.hi * (res.hi + res.lo), &hi, &lo);
    BALL q = {hi, lo, 0.0};
    /* a posteriori: |1/y_mid - q| = |1 - q y_mid| / |y_mid| */
    const BALL yq = MUL(q, mid), rho = SUB(one, yq);
    const double err = up(up(fabs(rho.hi) + fabs(rho.lo) + rho.r) / low_mid);
    /* |1/y - 1/y_mid| = |y - y_mid| / (|y| |y_mid|) */
    const double spread = up(y->r / low / low_mid);
    q.r = up(err + spread);
    return q;
}

static inline BALL F(load)(const uint64_t *p)
{
    BALL z;
    memcpy(&z.hi, p, sizeof(double));
    memcpy(&z.lo, p + 1, sizeof(double));
    memcpy(&z.r, p + 2, sizeof(double));
    return z;
}

static inline void F(store)(uint64_t *p, const BALL *z)
{
    memcpy(p, &z->hi, sizeof(double));
    memcpy(p + 1, &z->lo, sizeof(double));
    memcpy(p + 2, &z->r, sizeof(double));
}

/* Rescale x by a power of two where its head left 2^+-400 (running products): its value
 * is then x 2^*shift. */
static inline void F(rescale)(BALL *x, int64_t *shift)
{
    if (x->hi != 0.0 && isfinite(x->hi) && (fabs(x->hi) > 0x1p400 || fabs(x->hi) < 0x1p-400)) {
        const int k = ilogb(x->hi);
        x->hi = ldexp(x->hi, -k);
        x->lo = ldexp(x->lo, -k);
        x->r = x->r == 0.0 ? 0.0 : up(ldexp(x->r, -k));
        *shift += k;
    }
}

#undef MUL
#undef ADD
#undef SUB
