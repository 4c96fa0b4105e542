/* lz/lcg.h — the thesis's linear congruential generator, the lesson's specimen.
 *
 *     x_{n+1} = (69069 x_n + 1) mod 2^32
 *
 * (thesis 2.3.3; the RAN generator of DEC and Sun workstations). With a ≡ 1 mod 4 and
 * c odd it visits all 2^32 integers before repeating, but its low bits are far from
 * random: bit k of x_n repeats with period 2^(k+1), so bit 0 simply alternates. Use
 * its high bits (lz_lcg_uniform, lz_lcg_below do), never x % n.
 *
 * This generator is here to be taken apart. Simulations draw from GSL (lz/rng.h).
 */
#ifndef LZ_LCG_H
#define LZ_LCG_H

#include <stdint.h>

#define LZ_LCG_A UINT32_C(69069)  /* the multiplier a */
#define LZ_LCG_C UINT32_C(1)      /* the increment c */

/* The generator's whole state: the last integer drawn, x_n (x_0 is the seed). Any
 * value is a valid state, 0 included (c = 1 leads it out). Copying the struct copies
 * the stream. */
typedef struct {
	uint32_t x;
} lz_lcg;

/* Start the stream at x_0 = seed; the first draw is then 69069 seed + 1. O(1). */
static inline void lz_lcg_seed(lz_lcg *g, uint32_t seed) { g->x = seed; }

/* ---- graded (solutions/02-lattice/lcg.c) ---- */

/* Advance the state one step and return the new integer x_{n+1} = (69069 x_n + 1)
 * mod 2^32 — the wrap-around of unsigned 32-bit arithmetic is the mod. From seed 0:
 * 1, 69070, 475628535, 3277404108, … O(1). */
uint32_t lz_lcg_next(lz_lcg *g);

/* The next integer x = lz_lcg_next(g) mapped to [0, 1): exactly x · 2^-32 (a double
 * holds every x·2^-32 exactly: 32 significant bits fit in 53). The largest value,
 * (2^32 - 1) · 2^-32 = 1 - 2^-32, is below 1. Two ways to get 1.0 back, the bug of
 * the thesis's RAN0 on the DEC Alpha:
 *   - dividing by 2^32 - 1 instead of 2^32 (the largest x gives exactly 1);
 *   - computing in float: x converted to float rounds to 24 bits, and every
 *     x >= 2^32 - 2^7 rounds up to 2^32, so x / 2^32 is 1.0f once in 2^25 draws.
 * O(1). */
double lz_lcg_uniform(lz_lcg *g);

/* An integer in [0, n), every value with probability exactly 1/n over the full
 * period, for 1 <= n <= 2^32 - 1 (n = 0 is the caller's bug). With q = floor(2^32 / n):
 * draw x = lz_lcg_next(g), draw again while x >= n·q (the last, incomplete bucket would
 * favour the small values), then return floor(x / q) — the high bits decide, so the
 * periodic low bits of the LCG never show (x % n with n even would alternate).
 * Mind the products: n·q can be 2^32 (n a power of two), which needs 64 bits.
 * Expected draws per call: 2^32 / (n·q) < 2. */
uint32_t lz_lcg_below(lz_lcg *g, uint32_t n);

#endif
