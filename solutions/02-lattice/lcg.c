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
	/* LZ_SOLUTION_BEGIN */
	g->x = LZ_LCG_A * g->x + LZ_LCG_C;
	return g->x;
	/* LZ_SOLUTION_END */
}

/* x · 2^-32 is exact in double: the largest value is 1 - 2^-32, never 1. */
double lz_lcg_uniform(lz_lcg *g)
{
	/* Hint: multiply the next integer, as a double, by 0x1p-32 (= 1 / 2^32 exactly).
	 * Not by 1.0 / UINT32_MAX, and not in float: try x = 4294967295 with each.
	 * See lessons/02-lattice/README.md §3. */
	/* LZ_SOLUTION_BEGIN */
	return (double)lz_lcg_next(g) * 0x1p-32;
	/* LZ_SOLUTION_END */
}

/* Rejection: n·q values split into n buckets of q consecutive integers each; the
 * 2^32 - n·q leftovers at the top are drawn again. */
uint32_t lz_lcg_below(lz_lcg *g, uint32_t n)
{
	/* Hint: in uint64_t, q = 2^32 / n and limit = n * q (2^32 itself when n is a power
	 * of two: a uint32_t limit would wrap to 0 and reject everything). Draw until
	 * x < limit, return x / q. Not x % n: that reads the low bits, which alternate.
	 * See lessons/02-lattice/README.md §3. */
	/* LZ_SOLUTION_BEGIN */
	uint64_t q = (UINT64_C(1) << 32) / n, limit = q * n;
	uint32_t x;
	do
		x = lz_lcg_next(g);
	while (x >= limit);
	return (uint32_t)(x / q);
	/* LZ_SOLUTION_END */
}
