/*
 * One instance of the kernel of _multiword.c: the arithmetic's header ARITH (a file name)
 * and the kernel over it, with the instance's macros defined by the includer (F, BALL, W_,
 * PREC_BITS; for complex balls R, RBALL, RW_; PLAIN_DOUBLE for doubles); all undefined
 * afterwards, for the next instance.
 */
#include ARITH
#include "_multiword_kernel.h"
#undef ARITH
#undef F
#undef BALL
#undef W_
#undef PREC_BITS
#undef R
#undef RBALL
#undef RW_
#undef PLAIN_DOUBLE
