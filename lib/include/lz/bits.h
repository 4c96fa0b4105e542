/* lz/bits.h — bit tricks for lattices: powers of two, periodic wrap by mask, cells by
 * shift, Morton (Z-order) keys, and the six-bit sites of the lattice gas.
 *
 * Lattice units throughout: a coordinate is an integer site index. A periodic side L
 * that is a power of two, L = 2^k, turns the remainder x mod L into one AND with the
 * mask L - 1 (two's complement makes this right for negative x too), and the cell of
 * a site into one right shift. Other sides are refused (lz_check_pow2) rather than
 * wrapped wrongly.
 *
 * A Morton key interleaves the bits of the coordinates: bit i of x goes to bit d·i
 * of the key, bit i of y to bit d·i + 1 (and z to d·i + 2), d the dimension. Sites
 * close in space get close keys: every aligned 2^k-sided block of sites is one
 * contiguous run of keys, so an array stored in key order keeps neighbours in the
 * same cache lines (DynamO orders its neighbour-list cells this way).
 */
#ifndef LZ_BITS_H
#define LZ_BITS_H

#include <stdint.h>

/* The largest periodic side a coordinate of type int32_t can wrap into: 2^31. */
#define LZ_SIDE_MAX (UINT64_C(1) << 31)

/* Coordinates of a 3D Morton key have 21 bits (3 × 21 = 63 key bits). */
#define LZ_MORTON3_BITS 21
#define LZ_MORTON3_MAX ((UINT32_C(1) << LZ_MORTON3_BITS) - 1)

/* 1 if n is a power of two (1, 2, 4, …, 2^63), 0 otherwise (0 is not). A power of two
 * has exactly one bit set, and n - 1 clears it and sets all below. O(1). */
static inline int lz_is_pow2(uint64_t n) { return n != 0 && (n & (n - 1)) == 0; }

/* k such that n = 2^k. Precondition: lz_is_pow2(n). O(1). */
static inline int lz_log2_pow2(uint64_t n) { return __builtin_ctzll(n); }

/* LZ_OK if n is a power of two in [1, max]; otherwise LZ_EINVAL with an lz_error
 * naming `what` and n and the allowed sizes ("size = 100 is not a power of two: the
 * nearest allowed are 64 and 128"). Call it once where a size enters (scene, alloc),
 * not in the hot loop. O(1). */
int lz_check_pow2(const char *what, uint64_t n, uint64_t max);

/* The cell of site x when cells are 2^shift sites wide: x >> shift, the high bits of
 * the coordinate (thesis 2.3.2). Precondition: 0 <= x (wrap first), 0 <= shift < 31.
 * O(1). */
static inline int32_t lz_cell_of(int32_t x, int shift) { return x >> shift; }

/* ---- the six-bit sites of the lattice gas ----
 * A site of the triangular lattice gas is six bits: bit k set means a particle leaves
 * the site in direction k, the directions counted counterclockwise from 3 o'clock in
 * steps of 60° (thesis 1.4). Bits above the sixth are ignored. All O(1). */
#define LZ_SITE_BITS 6
#define LZ_SITE_MASK 0x3Fu

/* The number of particles at the site (popcount of the six bits), 0..6. */
static inline int lz_site_count(unsigned s) { return __builtin_popcount(s & LZ_SITE_MASK); }

/* The site turned by k·60° counterclockwise: the particle of direction d moves to
 * direction (d + k) mod 6. Any k, negative too (clockwise); k and k ± 6 agree. */
static inline unsigned lz_site_rotate(unsigned s, int k)
{
	int r = k % LZ_SITE_BITS;
	if (r < 0)
		r += LZ_SITE_BITS;
	s &= LZ_SITE_MASK;
	return ((s << r) | (s >> (LZ_SITE_BITS - r))) & LZ_SITE_MASK;
}

/* Every particle reversed (d -> d + 3 mod 6): a head-on collision's pair swaps to
 * itself, a wall bounces the site back. lz_site_reverse twice is the identity. */
static inline unsigned lz_site_reverse(unsigned s) { return lz_site_rotate(s, 3); }

/* ---- Morton decoding (the inverse of the graded encoders) ---- */

/* The coordinates of a 2D key: bit 2i of key to bit i of *x, bit 2i + 1 to *y.
 * Every key is valid. O(1): five mask-and-shift steps per coordinate. */
void lz_morton2_decode(uint64_t key, uint32_t *x, uint32_t *y);

/* The coordinates of a 3D key, each in [0, LZ_MORTON3_MAX]: bit 3i of key to bit i of
 * *x, 3i + 1 to *y, 3i + 2 to *z; bit 63 is ignored. O(1). */
void lz_morton3_decode(uint64_t key, uint32_t *x, uint32_t *y, uint32_t *z);

/* ---- graded (solutions/02-lattice/bits.c) ---- */

/* x mod L in [0, L) for any int32_t x, negative and far outside the box too (a walker
 * at -1 is at L - 1; at INT32_MIN it is at 0 for every L that fits), by one AND with
 * the mask L - 1. L is the periodic side in lattice units, a power of two in
 * [1, LZ_SIDE_MAX]; other L are the caller's bug (lz_check_pow2 refuses them where
 * the size is set). O(1), no division, no branch. */
int32_t lz_wrap_mask(int32_t x, uint32_t L);

/* The 2D Morton key of site (x, y): bit i of x to bit 2i, bit i of y to bit 2i + 1.
 * All 32 bits of each coordinate are used; the 64-bit key is never truncated.
 * (0,0) -> 0, (1,0) -> 1, (0,1) -> 2, (1,1) -> 3, (2,0) -> 4. O(1): "dilate" each
 * coordinate by shift-or-mask steps with the masks 0x0000FFFF0000FFFF, …,
 * 0x5555555555555555 — no loop over the bits. */
uint64_t lz_morton2_encode(uint32_t x, uint32_t y);

/* The 3D Morton key of site (x, y, z): bit i of x to bit 3i, of y to 3i + 1, of z to
 * 3i + 2, for the 21 low bits of each coordinate (bits 21 and up are ignored, never
 * spilled into another coordinate's bits); bit 63 of the key is 0. (1,0,0) -> 1,
 * (0,1,0) -> 2, (0,0,1) -> 4. O(1), by dilation with magic masks as in 2D. */
uint64_t lz_morton3_encode(uint32_t x, uint32_t y, uint32_t z);

#endif
