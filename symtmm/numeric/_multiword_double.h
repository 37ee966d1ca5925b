/*
 * Plain doubles for _multiword.c (included there once, with F, BALL and W_ defined): the
 * kernel's "balls" of one word, the double itself, with no radius. Not an enclosure: the double-precision batches' stiffness and band
 * (symtmm.numeric.stiffness.assemble in numpy otherwise), whose pivots' signs the
 * backward-error test of symtmm.numeric.stiffness decides, as for the numpy loop's.
 *
 * Each operation rounds once, to nearest; the series' term counts follow the same rule
 * as the balls' (tails below 2^-53).
 */
typedef struct { double m; } BALL;

static inline BALL F(exact)(double v)
{
    BALL z = {v};
    return z;
}

static inline int F(is_zero)(const BALL *x) { return x->m == 0.0; }

static inline int F(finite)(const BALL *x) { return isfinite(x->m); }

static inline double F(mid_up)(const BALL *x) { return fabs(x->m); }

static inline double F(head)(const BALL *x) { return x->m; }

/* |v| (no radius: nothing to widen) */
static inline double F(mag)(const BALL *x) { return fabs(x->m); }

static inline void F(widen)(BALL *x, double t)
{
    (void)x;
    (void)t;
}

static inline BALL F(neg)(BALL x)
{
    x.m = -x.m;
    return x;
}

static inline int F(negative)(const BALL *x) { return x->m < 0.0; }

static inline int F(nonzero)(const BALL *x) { return x->m != 0.0 && isfinite(x->m); }

static inline BALL F(add)(const BALL *x, const BALL *y) { return F(exact)(x->m + y->m); }

static inline BALL F(sub)(const BALL *x, const BALL *y) { return F(exact)(x->m - y->m); }

static inline BALL F(mul)(const BALL *x, const BALL *y) { return F(exact)(x->m * y->m); }

static inline BALL F(inv)(const BALL *y) { return F(exact)(1.0 / y->m); }

static inline BALL F(scale)(const BALL *x, int k) { return F(exact)(ldexp(x->m, k)); }

/* (a product by a power of two is exact in doubles too: no shortcut needed) */
static inline int F(power_of_two)(const BALL *c, int *k)
{
    (void)c;
    *k = 0;
    return 0;
}

static inline BALL F(load)(const uint64_t *p)
{
    BALL z;
    memcpy(&z.m, p, sizeof(double));
    return z;
}

static inline void F(store)(uint64_t *p, const BALL *z) { memcpy(p, &z->m, sizeof(double)); }

/* Rescale x by a power of two where it left 2^+-400 (running products): its value is
 * then x 2^*shift. */
static inline void F(rescale)(BALL *x, int64_t *shift)
{
    if (x->m != 0.0 && isfinite(x->m) && (fabs(x->m) > 0x1p400 || fabs(x->m) < 0x1p-400)) {
        const int k = ilogb(x->m);
        x->m = ldexp(x->m, -k);
        *shift += k;
    }
}
