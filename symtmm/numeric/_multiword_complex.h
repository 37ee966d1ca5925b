/*
 * Complex balls for _multiword.c (included there once per real arithmetic, with F, BALL
 * and W_ defined for the complex balls, and R, RBALL and RW_ for the real ones they are
 * made of): a rectangle, a real ball for the real part and one for the imaginary part, as
 * Arb's acb. Every operation is composed of the real balls' operations, each an enclosure
 * of its operands' sets, so the composition encloses the exact complex result (with the
 * dependency of interval arithmetic: a part used twice may widen it, never narrow it):
 *
 *   x y:    (a c - b d) + (a d + b c) i;
 *   1 / y:  (c - d i) / n, n = c^2 + d^2 enclosed as a real ball (+inf radius where it
 *           may hold 0: the point then fails).
 *
 * The dashpots' terms of the damped models' stiffness make their bands complex.
 */
#define RMUL(a, b) R(mul)(&(a), &(b))
#define RADD(a, b) R(add)(&(a), &(b))
#define RSUB(a, b) R(sub)(&(a), &(b))

typedef struct { RBALL re, im; } BALL;

static inline BALL F(exact)(double v)
{
    BALL z = {R(exact)(v), R(exact)(0.0)};
    return z;
}

static inline int F(is_zero)(const BALL *x) { return R(is_zero)(&x->re) && R(is_zero)(&x->im); }

static inline int F(finite)(const BALL *x) { return R(finite)(&x->re) && R(finite)(&x->im); }

/* an upper bound of |v| over the rectangle (|re| + |im|); both parts grown by t >= 0
 * (the square of half-side t holds the disc of radius t) */
static inline double F(mag)(const BALL *x) { return up(R(mag)(&x->re) + R(mag)(&x->im)); }

static inline void F(widen)(BALL *x, double t)
{
    R(widen)(&x->re, t);
    R(widen)(&x->im, t);
}

/* about |midpoint| (choices only: the 2x2 blocks of the elimination) */
static inline double F(head)(const BALL *x)
{
    return fabs(R(head)(&x->re)) + fabs(R(head)(&x->im));
}

static inline BALL F(neg)(BALL x)
{
    x.re = R(neg)(x.re);
    x.im = R(neg)(x.im);
    return x;
}

/* (no order: a 2x2 block's pivots are then (a, det / a)) */
static inline int F(negative)(const BALL *x)
{
    (void)x;
    return 0;
}

/* the rectangle excludes 0 where one of its parts does */
static inline int F(nonzero)(const BALL *x)
{
    return F(finite)(x) && (R(nonzero)(&x->re) || R(nonzero)(&x->im));
}

static inline BALL F(add)(const BALL *x, const BALL *y)
{
    BALL z = {RADD(x->re, y->re), RADD(x->im, y->im)};
    return z;
}

static inline BALL F(sub)(const BALL *x, const BALL *y)
{
    BALL z = {RSUB(x->re, y->re), RSUB(x->im, y->im)};
    return z;
}

static inline BALL F(mul)(const BALL *x, const BALL *y)
{
    const RBALL ac = RMUL(x->re, y->re), bd = RMUL(x->im, y->im), ad = RMUL(x->re, y->im),
                bc = RMUL(x->im, y->re);
    BALL z = {RSUB(ac, bd), RADD(ad, bc)};
    return z;
}

static inline BALL F(inv)(const BALL *y)
{
    const RBALL cc = RMUL(y->re, y->re), dd = RMUL(y->im, y->im), n = RADD(cc, dd);
    const RBALL in = R(inv)(&n), nd = R(neg)(y->im);
    BALL z = {RMUL(y->re, in), RMUL(nd, in)};
    return z;
}

static inline BALL F(scale)(const BALL *x, int k)
{
    BALL z = {R(scale)(&x->re, k), R(scale)(&x->im, k)};
    return z;
}

/* a real power of two (the scatter's coefficients): the product is then a scaling */
static inline int F(power_of_two)(const BALL *c, int *k)
{
    *k = 0;
    return R(is_zero)(&c->im) && R(power_of_two)(&c->re, k);
}

static inline BALL F(load)(const uint64_t *p)
{
    BALL z = {R(load)(p), R(load)(p + RW_)};
    return z;
}

static inline void F(store)(uint64_t *p, const BALL *z)
{
    R(store)(p, &z->re);
    R(store)(p + RW_, &z->im);
}

/* Rescale x by a power of two where its larger part left 2^+-400 (running products): its
 * value is then x 2^*shift. */
static inline void F(rescale)(BALL *x, int64_t *shift)
{
    const double a = fabs(R(head)(&x->re)), b = fabs(R(head)(&x->im)), h = a > b ? a : b;
    if (h != 0.0 && isfinite(h) && (h > 0x1p400 || h < 0x1p-400)) {
        const int k = ilogb(h);
        x->re = R(scale)(&x->re, -k);
        x->im = R(scale)(&x->im, -k);
        *shift += k;
    }
}

#undef RMUL
#undef RADD
#undef RSUB
