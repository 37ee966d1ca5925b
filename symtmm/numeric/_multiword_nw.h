/* The instance of NW words of _multiword_words.h. */
#define ARITH WORDS_ARITH
#define F(name) NAMES(name)
#define BALL F(ball)
#define W_ WORDS
#define PREC_BITS (64 * NW)
#ifdef REAL_NAMES
#define R(name) REAL_NAMES(name)
#define RBALL R(ball)
#define RW_ (NW + 3)
#endif
#include "_multiword_instance.h"
