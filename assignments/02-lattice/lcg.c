/* YOUR FILE — this is the file you fill in for stage 02-lattice.
 *
 * Every function below whose body is LZ_TODO() is yours to implement: replace the
 * LZ_TODO(); line with your code, and keep the function's name, parameters and
 * return type exactly as they are. Until then it stops the program with
 * "not implemented: <function>". The comment above each function says what it
 * must compute; its hint points at a section of lessons/02-lattice/README.md.
 * You may add your own static helper functions to this file.
 *
 * Check your work with `make test STAGE=02`; see your own code at work with
 * `make lesson STAGE=02`. Only this file's functions are graded.
 */
#include "lz/error.h"  /* LZ_TODO() */

/* lcg.c — the thesis's linear congruential generator (graded). */
#include <stdint.h>

#include "lz/error.h"
#include "lz/lcg.h"

/* Unsigned arithmetic is modulo 2^32 by the C standard: the mod is free. */
uint32_t lz_lcg_next(lz_lcg *g)
{
	/* Hint: one line, in uint32_t: the product wraps around modulo 2^32 by itself
	 * (a signed int32_t would overflow, which C leaves undefined). Store the new
	 * value in the state, then return it: from seed 0 the first draw is 1.
	 * See lessons/02-lattice/README.md §3. */
	LZ_TODO();
}

/* x · 2^-32 is exact in double: the largest value is 1 - 2^-32, never 1. */
double lz_lcg_uniform(lz_lcg *g)
{
	/* Hint: multiply the next integer, as a double, by 0x1p-32 (= 1 / 2^32 exactly).
	 * Not by 1.0 / UINT32_MAX, and not in float: try x = 4294967295 with each.
	 * See lessons/02-lattice/README.md §3. */
	LZ_TODO();
}

/* Rejection: n·q values split into n buckets of q consecutive integers each; the
 * 2^32 - n·q leftovers at the top are drawn again. */
uint32_t lz_lcg_below(lz_lcg *g, uint32_t n)
{
	/* Hint: in uint64_t, q = 2^32 / n and limit = n * q (2^32 itself when n is a power
	 * of two: a uint32_t limit would wrap to 0 and reject everything). Draw until
	 * x < limit, return x / q. Not x % n: that reads the low bits, which alternate.
	 * See lessons/02-lattice/README.md §3. */
	LZ_TODO();
}
