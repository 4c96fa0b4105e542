/* bits.c — periodic wrap by mask and Morton keys by bit dilation (graded). */
#include <stdint.h>

#include "lz/bits.h"
#include "lz/error.h"

/* LZ_HELPERS_BEGIN */
/* Spread the 32 bits of v to the even bits of a 64-bit word: bit i to bit 2i. Each
 * step doubles the gaps: halves 16 apart, bytes 8 apart, nibbles, pairs, bits. */
static uint64_t dilate2(uint32_t v)
{
	uint64_t d = v;
	d = (d | d << 16) & UINT64_C(0x0000FFFF0000FFFF);
	d = (d | d << 8) & UINT64_C(0x00FF00FF00FF00FF);
	d = (d | d << 4) & UINT64_C(0x0F0F0F0F0F0F0F0F);
	d = (d | d << 2) & UINT64_C(0x3333333333333333);
	d = (d | d << 1) & UINT64_C(0x5555555555555555);
	return d;
}

/* Spread the 21 low bits of v to every third bit: bit i to bit 3i. */
static uint64_t dilate3(uint32_t v)
{
	uint64_t d = v & LZ_MORTON3_MAX;
	d = (d | d << 32) & UINT64_C(0x001F00000000FFFF);
	d = (d | d << 16) & UINT64_C(0x001F0000FF0000FF);
	d = (d | d << 8) & UINT64_C(0x100F00F00F00F00F);
	d = (d | d << 4) & UINT64_C(0x10C30C30C30C30C3);
	d = (d | d << 2) & UINT64_C(0x1249249249249249);
	return d;
}
/* LZ_HELPERS_END */

/* Two's complement: the low k bits of a negative x are those of x + m·2^k for every
 * m, so keeping them is the mathematical remainder. */
int32_t lz_wrap_mask(int32_t x, uint32_t L)
{
	/* Hint: the mask is L - 1, not L. Do the AND on the unsigned bit pattern,
	 * (uint32_t)x & mask: -1 is all ones, so it lands on L - 1. x % L keeps the sign
	 * of x (C rounds towards zero) and an "if (x < 0) x += L" misses walkers more than
	 * one box away. See lessons/02-lattice/README.md §2. */
	/* LZ_SOLUTION_BEGIN */
	return (int32_t)((uint32_t)x & (L - 1u));
	/* LZ_SOLUTION_END */
}

/* Each coordinate dilated (a zero between consecutive bits), y shifted into the odd
 * places. */
uint64_t lz_morton2_encode(uint32_t x, uint32_t y)
{
	/* Hint: write a helper that spreads the bits of a uint32_t to the even bits of a
	 * uint64_t in five steps, d = (d | d << s) & M for s = 16, 8, 4, 2, 1 with
	 * M = 0x0000FFFF0000FFFF, 0x00FF00FF00FF00FF, 0x0F0F…, 0x3333…, 0x5555…; the key
	 * is spread(x) | spread(y) << 1. Work in uint64_t from the start, or the high bits
	 * are lost. Check (5, 3) -> 27 by hand. See lessons/02-lattice/README.md §2. */
	/* LZ_SOLUTION_BEGIN */
	return dilate2(x) | dilate2(y) << 1;
	/* LZ_SOLUTION_END */
}

/* Each 21-bit coordinate dilated to every third bit, y and z shifted by 1 and 2. */
uint64_t lz_morton3_encode(uint32_t x, uint32_t y, uint32_t z)
{
	/* Hint: as in 2D but two zeros between bits: keep the 21 low bits first
	 * (v & 0x1FFFFF), then d = (d | d << s) & M for s = 32, 16, 8, 4, 2 with
	 * M = 0x001F00000000FFFF, 0x001F0000FF0000FF, 0x100F00F00F00F00F,
	 * 0x10C30C30C30C30C3, 0x1249249249249249. Draw the bit positions of a 4-bit number
	 * after each step to see why. See lessons/02-lattice/README.md §2. */
	/* LZ_SOLUTION_BEGIN */
	return dilate3(x) | dilate3(y) << 1 | dilate3(z) << 2;
	/* LZ_SOLUTION_END */
}
