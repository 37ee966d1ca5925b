/*
 * Multi-word balls: rigorous enclosures with a midpoint of 2 to 5 64-bit words (128 to
 * 320 bits) in compiled loops, for the proofs of symtmm.numeric.multiword (undamped
 * beam models: there the kernel's Arb balls pay a Python call per operation).
 *
 * A ball of N words holds every real m + t with |t| <= r: the midpoint m = (-1)^s
 * 0.m[0]m[1]..m[N-1] (binary) 2^e, a binary floating-point number of 64 N bits (its
 * leading bit set, the exponent a 64-bit integer), the radius r a double. The operations
 * compute the midpoints' exact result in integer words (the whole product; sums with
 * one guard word) and cut it to N words, adding to the radius a bound of what they cut
 * (one unit of the last word kept, or of the guard word for the bits an alignment shifted
 * out), and what the operands' radii carry:
 *
 *   x + y:  r = x.r + y.r + cut;
 *   x * y:  r = |x| y.r + |y| x.r + x.r y.r + cut  (|x|: its leading 53 bits plus one unit);
 *   1 / y:  q from Newton steps; |1/y_mid - q| <= |1 - q y_mid| / |y_mid|, with
 *           1 - q y_mid enclosed by the operations above (a posteriori: no analysis of
 *           the iteration); r = y.r / (|y|_min |y_mid|) + that.
 *
 * Radii are computed in round-to-nearest and then inflated: up(v) = v (1 + 2^-48) +
 * 2^-1021 exceeds the exact value of a sum of at most a dozen rounded non-negative terms
 * (each rounding at most 2^-53 relative) and every error of gradual underflow. A number
 * whose exponent leaves +-EXP_MAX, or anything not finite (a division by a ball holding
 * 0), makes the point fail: the caller then evaluates it in Arb.
 *
 * The kernel (_multiword_kernel.h) is compiled once per number of words N, 2 to 5, so
 * that its loops over the words have a fixed length, and once more over plain doubles
 * (N = 1, _multiword_double.h: no radius, not an enclosure) for the stiffness and band of
 * the double-precision batches, which the elimination of _band.c then factorises. No numpy headers: arrays come as
 * buffers of 64-bit words, N + 3 per ball (the words, e, s and the bits of r).
 */
#define PY_SSIZE_T_CLEAN
#include <Python.h>
#include <float.h>
#include <math.h>
#include <stdint.h>
#include <string.h>

#include "_band_core.h"
#include "_buffers.h"

/* The error-free transformations need every double operation rounded once, to double:
 * not through x87's extended registers (32-bit x86 without SSE2). Where that cannot be
 * had, the extension does not build and every proof runs in Arb. */
#if !defined(FLT_EVAL_METHOD) || FLT_EVAL_METHOD != 0
#error "double operations must round to double (FLT_EVAL_METHOD 0)"
#endif

/* exponents beyond this fail (radii and bounds are doubles) */
#define EXP_MAX 1000

#define INFLATE (1.0 + 0x1p-48)
#define DEFLATE (1.0 - 0x1p-48)
#define TINY 0x1p-1021

static inline double up(double v) { return v * INFLATE + TINY; }

/* 2^k for -1022 <= k <= 1023, built from its bits (ldexp is a library call; this is on the
 * hot path of every operation) */
static inline double pow2(int k)
{
    const uint64_t bits = (uint64_t)(k + 1023) << 52;
    double v;
    memcpy(&v, &bits, sizeof v);
    return v;
}
/* a lower bound of a non-negative v computed with a few roundings (may be negative) */
static inline double down(double v) { return v * DEFLATE - TINY; }

/* A pivot below 2^-PAIR_BITS of the entry coupling it to the next freedom is eliminated
 * with that freedom as one 2x2 block P = [[a, b], [b, c]] (pivot2): one tiny pivot (a
 * leading sub-structure near one of its eigenvalues) would multiply the radii of every
 * entry it updates by the square of that ratio, the block's inverse multiplies them by
 * about 1. The trailing entries lose R^T P^-1 R (Haynsworth: the inertia and determinant
 * of K are P's and those of that Schur complement's). P's two "pivots", whose signs are
 * its inertia and whose product is det P: (det P, 1) where det P < 0, else (a, det P / a)
 * or (c, det P / c); the point fails where the block's inertia is not decided. */
#define PAIR_BITS 8

/* The family of a kind whose values come from the caller (assemble's and summary's
 * `given`): a long Euler-Bernoulli piece, whose closed forms numpy evaluates, in a batch
 * of plain doubles. Families 0 (Euler-Bernoulli) and 1 (a general beam) are built here. */
#define FAMILY_GIVEN 2

#define CAT_(a, b) a##_##b
#define CAT(a, b) CAT_(a, b)

/* Each instance: its names (F, BALL), words per ball (W_), bits (PREC_BITS) and, for
 * complex balls, those of the real balls they pair (R, RBALL, RW_); then its arithmetic's
 * header and the kernel (ARITH, _multiword_instance.h), which ends by undefining them.
 * The integer mantissas' headers are written in NW: _multiword_words.h makes the
 * instances of 3 to 8 words of WORDS_ARITH. */

/* one word: plain doubles, no radius (the double-precision batches' band) */
#define F(name) name##_1
#define BALL ball_1
#define W_ 1
#define PREC_BITS 53
#define PLAIN_DOUBLE
#define ARITH "_multiword_double.h"
#include "_multiword_instance.h"

/* two words: double-double balls (about 106 bits, a few double operations each) */
#define F(name) name##_2
#define BALL ball_2
#define W_ 3
#define PREC_BITS 106
#define ARITH "_multiword_dd.h"
#include "_multiword_instance.h"

/* three to twelve words: integer mantissas (64 bits a word; beyond eight, for the zoom
 * onto a multiple root at 30 and 50 digits, k times the resolution's digits; not beyond
 * twelve: the double radius, at least 2^-1021, would not keep the words' bits) */
#define WORDS_MAX 12
#define WORDS_ARITH "_multiword_limbs.h"
#define NAMES(name) CAT(name, NW)
#define WORDS (NW + 3)
#include "_multiword_words.h"

/* complex balls: a real ball of N words for each part (code 100 + N), for the damped
 * models, whose dashpots make the band complex */
#define R(name) name##_1
#define RBALL ball_1
#define RW_ 1
#define F(name) name##_c1
#define BALL cball_1
#define W_ 2
#define PREC_BITS 53
#define PLAIN_DOUBLE
#define ARITH "_multiword_complex.h"
#include "_multiword_instance.h"

#define R(name) name##_2
#define RBALL ball_2
#define RW_ 3
#define F(name) name##_c2
#define BALL cball_2
#define W_ 6
#define PREC_BITS 106
#define ARITH "_multiword_complex.h"
#include "_multiword_instance.h"

#define WORDS_MAX 8
#define WORDS_ARITH "_multiword_complex.h"
#define NAMES(name) CAT(name, CAT(c, NW))
#define WORDS (2 * (NW + 3))
#define REAL_NAMES(name) CAT(name, NW)
#include "_multiword_words.h"

/* the codes of the arithmetics: N (1 to 12) words, real; 100 + N (N up to 8) complex */
static inline int valid_words(int N) { return (N >= 1 && N <= 12) || (N >= 101 && N <= 108); }

/* f_N(...) for the code N of the call: one kernel instance per arithmetic */
#define BY_WORDS(N, f, ...)                                                                \
    switch (N) {                                                                           \
    case 1: f##_1(__VA_ARGS__); break;                                                     \
    case 2: f##_2(__VA_ARGS__); break;                                                     \
    case 3: f##_3(__VA_ARGS__); break;                                                     \
    case 4: f##_4(__VA_ARGS__); break;                                                     \
    case 5: f##_5(__VA_ARGS__); break;                                                     \
    case 6: f##_6(__VA_ARGS__); break;                                                     \
    case 7: f##_7(__VA_ARGS__); break;                                                     \
    case 8: f##_8(__VA_ARGS__); break;                                                     \
    case 9: f##_9(__VA_ARGS__); break;                                                     \
    case 10: f##_10(__VA_ARGS__); break;                                                   \
    case 11: f##_11(__VA_ARGS__); break;                                                   \
    case 12: f##_12(__VA_ARGS__); break;                                                   \
    case 101: f##_c1(__VA_ARGS__); break;                                                  \
    case 102: f##_c2(__VA_ARGS__); break;                                                  \
    case 103: f##_c_3(__VA_ARGS__); break;                                                 \
    case 104: f##_c_4(__VA_ARGS__); break;                                                 \
    case 105: f##_c_5(__VA_ARGS__); break;                                                 \
    case 106: f##_c_6(__VA_ARGS__); break;                                                 \
    case 107: f##_c_7(__VA_ARGS__); break;                                                 \
    default: f##_c_8(__VA_ARGS__); break;                                                  \
    }

/* 64-bit words per ball of code N: a plain double's one, the double-double's three
 * doubles, else the mantissa, the exponent, the sign and the radius; complex: twice */
static inline Py_ssize_t ball_words(int N)
{
    return N > 100 ? 2 * ball_words(N - 100) : N == 1 ? 1 : N == 2 ? 3 : N + 3;
}

/* Whether the series and scatter tables of assemble() and summary() fit their lengths
 * and one another, for balls of `item` bytes: S kinds (families 0 or 1, or FAMILY_GIVEN
 * for plain doubles: *G of them, their values in gb, (B, *G, 17) balls), the series of
 * K and TK terms, T scatter terms in layers (starts) into a band of nk entries per point,
 * their sources inside V (16 S + 3). */
static int tables_fit(Py_ssize_t item, const Py_buffer *kb, const Py_buffer *fb,
                      const Py_buffer *cb, const Py_buffer *tb, Py_ssize_t K,
                      const Py_buffer *tcb, const Py_buffer *ttb, Py_ssize_t TK,
                      const Py_buffer *tgb, const Py_buffer *srcb, const Py_buffer *bcb,
                      const Py_buffer *stb, Py_ssize_t nk, Py_ssize_t B,
                      const Py_buffer *gb, Py_ssize_t *G)
{
    const Py_ssize_t S = fb->len / 8, T = tgb->len / 8, Q = stb->len / 8 - 1;
    const Py_ssize_t nv = 16 * S + 3;
    int good = K >= 2 && TK >= 2 && kb->len == 8 * S * item && cb->len == 4 * K * item
               && tb->len == 4 * (K + 1) * 8 && tcb->len == (2 * TK + 2) * item
               && ttb->len == 16 && srcb->len == tgb->len && bcb->len == T * item && Q >= 0;
    const long long *tg = tgb->buf, *src = srcb->buf, *st = stb->buf, *fam = fb->buf;
    Py_ssize_t given = 0;
    for (Py_ssize_t i = 0; good && i < S; i++) {
        good = fam[i] == 0 || fam[i] == 1 || (fam[i] == FAMILY_GIVEN && item <= 16);
        given += fam[i] == FAMILY_GIVEN;
    }
    /* the given kinds' values: (B, G, 17) balls, plain doubles only */
    good = good && gb->len == B * given * 17 * item;
    *G = given;
    for (Py_ssize_t i = 0; good && i < T; i++)
        good = src[i] >= 0 && src[i] < nv && tg[i] >= 0 && tg[i] < nk;
    for (Py_ssize_t q = 0; good && q <= Q; q++)
        good = st[q] >= 0 && st[q] <= T && (q == 0 || st[q] >= st[q - 1]);
    return good;
}

/* assemble(N, lam2, lam, kinds, families, coef, tails, K, tcoef, ttails, TK, targets,
 *          source, bcoef, starts, given, band, det12, V, ok)
 *   balls of code N (ball_words(N) 64-bit words each): lam2 (B,); lam (B,), or empty
 *   where there are no dashpots (its column then 0); kinds (S, 8): per
 *   kind (EI, l, A, F, 0...) where families[s] = 0 (Euler-Bernoulli), (EI, a, b, cN, rhoI,
 *   m, kw, l) where 1 (a general beam); coef (4, K) the balls of 1/(4k + j)!, tails
 *   (4, K + 1) doubles, upper bounds of 1/(4k + j)!; tcoef (2 TK + 2,) the balls of 1/k!,
 *   ttails (2,) doubles, 2 TK / (2 TK)! and 2 TK / (2 TK + 1)! rounded up; targets,
 *   source (T,) int64 and bcoef (T,): the plan's scatter, layer q being terms
 *   starts[q] .. starts[q + 1] - 1 (each target at most once in a layer); given
 *   (B, G, 17): per point the 16 entries and det U12 of each kind of family
 *   FAMILY_GIVEN, in the kinds' order (empty where there is none); band (B, nk)
 *   written; det12 (B, S) written; V (16 S + 3) workspace; ok (B,) uint8 written: 0
 *   where a value is not finite (the point is left to Arb).
 * The sources index V = [D of every kind (16 each), 1, lam, lam2]: the
 * columns of symtmm.numeric.stiffness.assemble. */
static PyObject *assemble(PyObject *self, PyObject *args)
{
    Py_buffer lb, lmb, kb, fb, cb, tb, tcb, ttb, tgb, srcb, bcb, stb, gb, bandb, detb, vb,
              okb;
    Py_ssize_t K, TK, G = 0;
    int N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iy*y*y*y*y*y*ny*y*ny*y*y*y*y*w*w*w*w*", &N, &lb, &lmb, &kb,
                          &fb, &cb, &tb, &K, &tcb, &ttb, &TK, &tgb, &srcb, &bcb, &stb, &gb,
                          &bandb, &detb, &vb, &okb))
        return NULL;
    int good = valid_words(N);
    const Py_ssize_t item = 8 * ball_words(N);
    const Py_ssize_t B = good ? lb.len / item : 0, S = fb.len / 8, Q = stb.len / 8 - 1;
    const Py_ssize_t nk = B ? bandb.len / item / B : 0;
    good = good && detb.len == B * S * item && vb.len == (16 * S + 3) * item && okb.len == B
           && (B == 0 || bandb.len == B * nk * item) && (lmb.len == 0 || lmb.len == lb.len)
           && tables_fit(item, &kb, &fb, &cb, &tb, K, &tcb, &ttb, TK, &tgb, &srcb, &bcb,
                         &stb, nk, B, &gb, &G);
    const long long *tg = tgb.buf, *src = srcb.buf, *st = stb.buf, *fam = fb.buf;
    if (good) {
        Py_BEGIN_ALLOW_THREADS
        BY_WORDS(N, assemble_points, lb.buf, lmb.len ? lmb.buf : NULL, kb.buf, fam, S,
                 cb.buf, tb.buf, K, tcb.buf,
                 ttb.buf, TK, tg, src, bcb.buf, st, Q, bandb.buf, nk, detb.buf, vb.buf,
                 okb.buf, B, gb.buf, G)
        Py_END_ALLOW_THREADS
    }
    return RELEASED(good ? CALL_DONE : CALL_MISFIT, "multi-word tables and buffers do not fit",
                    &lb, &lmb, &kb, &fb, &cb, &tb, &tcb, &ttb, &tgb, &srcb, &bcb, &stb, &gb,
                    &bandb, &detb, &vb, &okb);
}

/* summary(N, lam2, lam, kinds, families, coef, tails, K, tcoef, ttails, TK, targets,
 *         source, bcoef, starts, given, n, w, mult, trust, growth, log_constant, logabs,
 *         phase, count, ok)
 *   N 1 (doubles) or 101 (complex doubles): per point the band of K(lam), as assemble()
 *   builds it (the same tables; n freedoms, w the band's width), factorised and read as
 *   _band.c's eliminate() and summary() do it, one point at a time: its band stays in
 *   cache, and no batch of bands is written (for a 10-level chain, copying and first
 *   touching the batch's bands cost as much as factorising them). logabs, phase (B,)
 *   doubles and count (B,) int64 written where ok[p] = 1; ok[p] = 0 where a value is
 *   not finite or beyond the series' reach (the caller takes those points in numpy). */
static PyObject *fused_summary(PyObject *self, PyObject *args)
{
    Py_buffer lb, lmb, kb, fb, cb, tb, tcb, ttb, tgb, srcb, bcb, stb, gb, mb, lab, phb, cnb,
              okb;
    Py_ssize_t K, TK, n, w, G = 0;
    double trust, growth, log_constant;
    int N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iy*y*y*y*y*y*ny*y*ny*y*y*y*y*nny*dddw*w*w*w*", &N, &lb, &lmb,
                          &kb, &fb, &cb, &tb, &K, &tcb, &ttb, &TK, &tgb, &srcb, &bcb, &stb,
                          &gb, &n, &w, &mb, &trust, &growth, &log_constant, &lab, &phb, &cnb,
                          &okb))
        return NULL;
    const int is_complex = N == 101;
    int good = N == 1 || N == 101;
    const Py_ssize_t item = is_complex ? 16 : 8, c = is_complex ? 2 : 1;
    const Py_ssize_t B = lb.len / item, S = fb.len / 8, Q = stb.len / 8 - 1;
    const Py_ssize_t nv = 16 * S + 3, nk = n * w;
    good = good && n >= 1 && w >= 1 && mb.len == S * 8 && lab.len == B * 8
           && phb.len == B * 8 && cnb.len == B * 8 && okb.len == B
           && (lmb.len == 0 || lmb.len == lb.len) && lb.len % item == 0
           && tables_fit(item, &kb, &fb, &cb, &tb, K, &tcb, &ttb, TK, &tgb, &srcb, &bcb,
                         &stb, nk, B, &gb, &G);
    const long long *tg = tgb.buf, *src = srcb.buf, *st = stb.buf, *fam = fb.buf;
    /* one point's band as built, padded for the elimination, det U12, V, the scales */
    double *work = good ? PyMem_Malloc(sizeof(double) * (c * (nk + (n + w) * w + S + nv) + n))
                        : NULL;
    if (good && work) {
        double *band = work, *fact = band + c * nk, *det = fact + c * (n + w) * w;
        double *V = det + c * S, *scale = V + c * nv;
        const int64_t *mu = mb.buf;
        unsigned char *ok = okb.buf;
        Py_BEGIN_ALLOW_THREADS
        for (Py_ssize_t p = 0; p < B; p++) {
            const uint64_t *lam2 = (const uint64_t *)lb.buf + c * p;
            const uint64_t *lam = lmb.len ? (const uint64_t *)lmb.buf + c * p : NULL;
            const uint64_t *given = (const uint64_t *)gb.buf + c * 17 * G * p;
            if (is_complex)
                assemble_points_c1(lam2, lam, kb.buf, fam, S, cb.buf, tb.buf, K, tcb.buf,
                                   ttb.buf, TK, tg, src, bcb.buf, st, Q, (uint64_t *)band,
                                   nk, (uint64_t *)det, (uint64_t *)V, ok + p, 1, given, G);
            else
                assemble_points_1(lam2, lam, kb.buf, fam, S, cb.buf, tb.buf, K, tcb.buf,
                                  ttb.buf, TK, tg, src, bcb.buf, st, Q, (uint64_t *)band, nk,
                                  (uint64_t *)det, (uint64_t *)V, ok + p, 1, given, G);
            if (!ok[p])
                continue;
            memcpy(fact, band, sizeof(double) * c * nk);
            memset(fact + c * nk, 0, sizeof(double) * c * w * w);
            if (is_complex)
                band_eliminate_complex(fact, w, n);
            else
                band_eliminate_real(fact, w, n);
            band_point_summary(fact, band, det, mu, w, n, S, trust, growth, log_constant,
                               is_complex, scale, (double *)lab.buf + p,
                               (double *)phb.buf + p, (int64_t *)cnb.buf + p);
        }
        Py_END_ALLOW_THREADS
    }
    PyMem_Free(work);            /* (NULL where it was not allocated) */
    return RELEASED(!good ? CALL_MISFIT : work ? CALL_DONE : CALL_NO_MEMORY,
                    "summary: tables and buffers do not fit", &lb, &lmb, &kb, &fb, &cb, &tb,
                    &tcb, &ttb, &tgb, &srcb, &bcb, &stb, &gb, &mb, &lab, &phb, &cnb, &okb);
}

/* eliminate(N, band, B, rows, w, n, ok): LDL^T without pivoting in place on (B, rows, w)
 * balls, as symtmm.numeric.stiffness.eliminate, but for the 2x2 blocks above; row k then
 * holds d_k first (the L factors are not kept). Exact zeros are skipped (the envelope).
 * A point whose pivot (or block) cannot be decided is stopped there with ok[p] = 0. */
static PyObject *eliminate(PyObject *self, PyObject *args)
{
    Py_buffer buf, okb;
    Py_ssize_t B, rows, w, n;
    int N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iw*nnnnw*", &N, &buf, &B, &rows, &w, &n, &okb))
        return NULL;
    if (!valid_words(N) || B < 0 || w < 1 || n < 0 || rows < n + w
            || buf.len != B * rows * w * 8 * ball_words(N) || okb.len != B)
        return RELEASED(CALL_MISFIT, "multi-word band of the wrong size", &buf, &okb);
    Py_BEGIN_ALLOW_THREADS
    BY_WORDS(N, eliminate_points, buf.buf, B, rows, w, n, okb.buf)
    Py_END_ALLOW_THREADS
    return RELEASED(CALL_DONE, NULL, &buf, &okb);
}

/* eliminate_twisted(N, band, B, rows, w, n, splits, ok): as eliminate(), the freedoms
 * of point p eliminated from both ends toward splits[p] (int64, 0 <= t < n), whose pivot
 * is the last: the same inertia and determinant (Haynsworth), and where a mode is small
 * at both ends of the band (the pivot at either end is then the Schur complement of the
 * whole band, and its radius the growth of all of it) a pivot whose radius grew over
 * each side's part alone. */
static PyObject *eliminate_twisted(PyObject *self, PyObject *args)
{
    Py_buffer buf, sb, okb;
    Py_ssize_t B, rows, w, n;
    int N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iw*nnnny*w*", &N, &buf, &B, &rows, &w, &n, &sb, &okb))
        return NULL;
    if (!valid_words(N) || B < 0 || w < 1 || n < 1 || rows < n + w
            || buf.len != B * rows * w * 8 * ball_words(N) || okb.len != B
            || sb.len != B * 8)
        return RELEASED(CALL_MISFIT, "multi-word band of the wrong size", &buf, &sb, &okb);
    Py_BEGIN_ALLOW_THREADS
    BY_WORDS(N, eliminate_twisted_points, buf.buf, B, rows, w, n, sb.buf, okb.buf)
    Py_END_ALLOW_THREADS
    return RELEASED(CALL_DONE, NULL, &buf, &sb, &okb);
}

/* power_product(N, x, k, out, ok): out (B,) = prod_i x[:, i]^k[i] of balls x (B, count),
 * k (count,) int64 >= 0, each as a ball and one more word, the power of two (int64) it is
 * to be multiplied by; ok (B,) uint8 written (0: not finite). */
static PyObject *power_product(PyObject *self, PyObject *args)
{
    Py_buffer xb, kb, ob, okb;
    int N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iy*y*w*w*", &N, &xb, &kb, &ob, &okb))
        return NULL;
    const Py_ssize_t item = 8 * ball_words(N), B = okb.len, count = kb.len / 8;
    int good = valid_words(N) && ob.len == B * (item + 8)
               && xb.len == B * count * item;
    for (Py_ssize_t i = 0; good && i < count; i++)
        good = ((const long long *)kb.buf)[i] >= 0;
    if (good) {
        BY_WORDS(N, power_product_points, xb.buf, count, kb.buf, ob.buf, okb.buf, B)
    }
    return RELEASED(good ? CALL_DONE : CALL_MISFIT, "power_product: buffers of the wrong size",
                    &xb, &kb, &ob, &okb);
}

/* ops(op, N, x, y, out): elementwise on (M, N + 3) balls, op 0 add, 1 sub, 2 mul,
 * 3 x / y (as x times 1/y); for the tests of the enclosures. */
static PyObject *ops(PyObject *self, PyObject *args)
{
    Py_buffer xb, yb, ob;
    int op, N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iiy*y*w*", &op, &N, &xb, &yb, &ob))
        return NULL;
    const Py_ssize_t item = 8 * ball_words(N);
    if (op < 0 || op > 3 || !valid_words(N) || yb.len != xb.len
            || ob.len != xb.len || xb.len % item)
        return RELEASED(CALL_MISFIT, "ops: bad operation or buffers", &xb, &yb, &ob);
    const Py_ssize_t M = xb.len / item;
    BY_WORDS(N, ops_points, op, xb.buf, yb.buf, ob.buf, M)
    return RELEASED(CALL_DONE, NULL, &xb, &yb, &ob);
}

/* krylov(N, x, coef, tails, K, out): out (M, 4, N + 3) the c_j of the balls x (M, N + 3)
 * (the tests); radius +inf where |x| is beyond the series' reach. */
static PyObject *kry(PyObject *self, PyObject *args)
{
    Py_buffer xb, cb, tb, ob;
    Py_ssize_t K;
    int N;
    (void)self;
    if (!PyArg_ParseTuple(args, "iy*y*y*nw*", &N, &xb, &cb, &tb, &K, &ob))
        return NULL;
    const Py_ssize_t item = 8 * ball_words(N);
    const int good = valid_words(N) && K >= 2 && cb.len == 4 * K * item
                     && tb.len == 4 * (K + 1) * 8 && xb.len % item == 0
                     && ob.len == 4 * xb.len;
    if (good) {
        const Py_ssize_t M = xb.len / item;
        BY_WORDS(N, krylov_points, xb.buf, cb.buf, tb.buf, K, ob.buf, M)
    }
    return RELEASED(good ? CALL_DONE : CALL_MISFIT, "krylov: buffers of the wrong size",
                    &xb, &cb, &tb, &ob);
}

static PyMethodDef methods[] = {
    {"assemble", assemble, METH_VARARGS,
     "assemble(N, lam2, lam, kinds, families, coef, tails, K, tcoef, ttails, TK, targets, "
     "source, bcoef, starts, given, band, det12, V, ok): the band of K(lam) in balls of code N."},
    {"eliminate", eliminate, METH_VARARGS,
     "eliminate(N, band, B, rows, w, n, ok): LDL^T without pivoting of ball bands, in place."},
    {"summary", fused_summary, METH_VARARGS,
     "summary(N, lam2, lam, ..., given, n, w, mult, trust, growth, log_constant, logabs, phase, "
     "count, ok): log|Delta|, arg Delta and the count of double batches, a point at a time."},
    {"eliminate_twisted", eliminate_twisted, METH_VARARGS,
     "eliminate_twisted(N, band, B, rows, w, n, splits, ok): LDL^T from both ends of ball "
     "bands toward splits[p], in place."},
    {"power_product", power_product, METH_VARARGS,
     "power_product(N, x, k, out, ok): out[p] = prod_i x[p, i]**k[i] of balls."},
    {"ops", ops, METH_VARARGS, "ops(op, N, x, y, out): elementwise ball operations (tests)."},
    {"krylov", kry, METH_VARARGS,
     "krylov(N, x, coef, tails, K, out): the c_j of balls (tests)."},
    {NULL, NULL, 0, NULL}
};

static struct PyModuleDef module = {
    PyModuleDef_HEAD_INIT, "_multiword", "Multi-word balls in compiled loops.", -1, methods,
    NULL, NULL, NULL, NULL
};

PyMODINIT_FUNC PyInit__multiword(void)
{
    return PyModule_Create(&module);
}
