/*
 * The instances of 3 to 8 words (NW), and 9 to 12 where WORDS_MAX is 12, of _multiword.c over the arithmetic WORDS_ARITH
 * (a file name), real or complex: its names NAMES(name) and words per ball WORDS written
 * in NW (and, complex, the real balls' names REAL_NAMES(name)); those macros undefined
 * afterwards. _multiword_nw.h makes each.
 */
#define NW 3
#include "_multiword_nw.h"
#undef NW
#define NW 4
#include "_multiword_nw.h"
#undef NW
#define NW 5
#include "_multiword_nw.h"
#undef NW
#define NW 6
#include "_multiword_nw.h"
#undef NW
#define NW 7
#include "_multiword_nw.h"
#undef NW
#define NW 8
#include "_multiword_nw.h"
#undef NW
#if WORDS_MAX > 8
#define NW 9
#include "_multiword_nw.h"
#undef NW
#define NW 10
#include "_multiword_nw.h"
#undef NW
#define NW 11
#include "_multiword_nw.h"
#undef NW
#define NW 12
#include "_multiword_nw.h"
#undef NW
#endif
#undef WORDS_MAX
#undef WORDS_ARITH
#undef NAMES
#undef WORDS
#undef REAL_NAMES
