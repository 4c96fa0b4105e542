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

/* bits.c — periodic wrap by mask and Morton keys by bit dilation (graded). */
#include <stdint.h>

#include "lz/bits.h"
#include "lz/error.h"


/* Two's complement: the low k bits of a negative x are those of x + m·2^k for every
 * m, so keeping them is the mathematical remainder. */
int32_t lz_wrap_mask(int32_t x, uint32_t L)
{
	/* Hint: the mask is L - 1, not L. Do the AND on the unsigned bit pattern,
	 * (uint32_t)x & mask: -1 is all ones, so it lands on L - 1. x % L keeps the sign
	 * of x (C rounds towards zero) and an "if (x < 0) x += L" misses walkers more than
	 * one box away. See lessons/02-lattice/README.md §2. */
	LZ_TODO();
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
	LZ_TODO();
}

/* Each 21-bit coordinate dilated to every third bit, y and z shifted by 1 and 2. */
uint64_t lz_morton3_encode(uint32_t x, uint32_t y, uint32_t z)
{
	/* Hint: as in 2D but two zeros between bits: keep the 21 low bits first
	 * (v & 0x1FFFFF), then d = (d | d << s) & M for s = 32, 16, 8, 4, 2 with
	 * M = 0x001F00000000FFFF, 0x001F0000FF0000FF, 0x100F00F00F00F00F,
	 * 0x10C30C30C30C30C3, 0x1249249249249249. Draw the bit positions of a 4-bit number
	 * after each step to see why. See lessons/02-lattice/README.md §2. */
	LZ_TODO();
}
