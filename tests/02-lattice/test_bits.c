/* test_bits.c — periodic wrap by mask and Morton keys, against arithmetic done another
 * way: remainders in 64-bit signed arithmetic, keys interleaved one bit at a time. */
#include <inttypes.h>
#include <stdint.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/bits.h"

/* ---- wrap ---- */

/* x mod L in [0, L) by division in 64 bits: C's % truncates towards zero, so a
 * negative remainder is moved up by L. */
static int32_t mod_floor(int32_t x, uint32_t L)
{
	int64_t r = (int64_t)x % (int64_t)L;
	return (int32_t)(r < 0 ? r + (int64_t)L : r);
}

static void expect_wrap(int32_t x, uint32_t L)
{
	int32_t got = lz_wrap_mask(x, L), want = mod_floor(x, L);
	if (got == want)
		return;
	int64_t l = L;
	const char *why =
		L > 1 && got == (int32_t)((uint32_t)x & L) ? "the mask is L - 1, not L" :
		x < -l || x >= 2 * l ?
			"a walker more than one box away: adding or subtracting L once is not enough "
			"(the AND with L - 1 handles every distance)" :
		got < 0 && x < 0 && got == x % (int32_t)l ?
			"a negative result: C's x % L keeps the sign of x; AND the bits with L - 1" :
		"x mod L, in [0, L), is what the low bits of x say";
	ck_abort_msg("periodic side L = %" PRIu32 ": a walker at x = %" PRId32 " was wrapped to "
	             "%" PRId32 ", expected %" PRId32 " — %s", L, x, got, want, why);
}

LZ_TEST(wrap_steps_off_small_lattices)
{
	/* The walker of thesis 2.3.2 on a few small rings: one step off either edge,
	 * exactly one box and a bit away, and at rest inside. */
	static const uint32_t sides[] = {32, 2, 4, 8, 1024, 1};
	for (size_t s = 0; s < sizeof sides / sizeof sides[0]; s++) {
		int32_t L = (int32_t)sides[s];
		const int32_t xs[] = {0, 1, -1, L - 1, L, L + 1, -L, -L - 1, -L + 1, 2 * L,
		                      -2 * L - 3, 3 * L + 5, L / 2, -L / 2};
		for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
			expect_wrap(xs[i], sides[s]);
	}
	/* The thesis's own worked cases, L = 32: 32 -> 0 and -1 -> 31. */
	ck_assert_msg(lz_wrap_mask(32, 32) == 0 && lz_wrap_mask(-1, 32) == 31,
	              "L = 32: 32 must wrap to 0 and -1 to 31 (thesis 2.3.2)");
}
END_TEST

LZ_TEST(wrap_extreme_coordinates_and_sides)
{
	/* Every power-of-two side from 1 to 2^31, coordinates at the ends of int32_t and
	 * at the mask boundaries, and 10^5 random coordinates per side. */
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 20240202);
	for (int k = 0; k <= 31; k++) {
		uint32_t L = UINT32_C(1) << k;
		int64_t l = L;
		const int64_t xs[] = {INT32_MIN, INT32_MIN + 1, INT32_MAX, INT32_MAX - 1, 0, -1,
		                      l - 1, -l + 1, l, -l, l + 1, -l - 1};
		for (size_t i = 0; i < sizeof xs / sizeof xs[0]; i++)
			if (xs[i] >= INT32_MIN && xs[i] <= INT32_MAX)
				expect_wrap((int32_t)xs[i], L);
		for (int i = 0; i < 100000; i++)
			expect_wrap((int32_t)(uint32_t)gsl_rng_get(rng), L);
	}
	gsl_rng_free(rng);
	/* The largest side: -1 is the last site, INT32_MIN is a whole number of boxes. */
	ck_assert_msg(lz_wrap_mask(-1, UINT32_C(1) << 31) == INT32_MAX,
	              "L = 2^31: -1 must wrap to 2^31 - 1 = %" PRId32, INT32_MAX);
	ck_assert_msg(lz_wrap_mask(INT32_MIN, UINT32_C(1) << 31) == 0,
	              "L = 2^31: INT32_MIN = -2^31 is one box to the left of 0 and must wrap to 0");
}
END_TEST

/* ---- Morton keys ---- */

/* Interleave one bit at a time: bit i of coordinate c goes to bit d·i + c. */
static uint64_t interleave(const uint32_t *v, int d, int bits)
{
	uint64_t key = 0;
	for (int i = 0; i < bits; i++)
		for (int c = 0; c < d; c++)
			key |= (uint64_t)(v[c] >> i & 1u) << (d * i + c);
	return key;
}

static void expect_morton2(uint32_t x, uint32_t y, uint64_t want)
{
	uint64_t got = lz_morton2_encode(x, y);
	if (got == want)
		return;
	const char *why =
		got == interleave((uint32_t[]){y, x}, 2, 32) ?
			"x and y are swapped: x takes the even bits (bit 0), y the odd" :
		(got & UINT64_C(0xFFFFFFFF)) == (want & UINT64_C(0xFFFFFFFF)) ?
			"the low half is right, the high half wrong: work in uint64_t before "
			"shifting, a 32-bit word drops the upper 16 bits of each coordinate" :
		"bit i of x belongs at bit 2i, bit i of y at bit 2i + 1; check each "
		"shift-and-mask step of the dilation";
	ck_abort_msg("2D Morton key of site (%" PRIu32 ", %" PRIu32 ") is 0x%016" PRIx64
	             ", expected 0x%016" PRIx64 " — %s", x, y, got, want, why);
}

static void expect_morton3(uint32_t x, uint32_t y, uint32_t z, uint64_t want)
{
	uint64_t got = lz_morton3_encode(x, y, z);
	if (got == want)
		return;
	const char *why =
		(x | y | z) > LZ_MORTON3_MAX ?
			"a coordinate has bits above the 21st: they must be dropped (v & 0x1FFFFF) "
			"before dilating, or they land in another coordinate's places" :
		(got & UINT64_C(0xFFFFFFFF)) == (want & UINT64_C(0xFFFFFFFF)) ?
			"the low 32 key bits are right, the high ones wrong: dilate in uint64_t, "
			"and check the first masks (shifts by 32 and 16)" :
		"bit i of x belongs at bit 3i, of y at 3i + 1, of z at 3i + 2";
	ck_abort_msg("3D Morton key of site (%" PRIu32 ", %" PRIu32 ", %" PRIu32 ") is 0x%016"
	             PRIx64 ", expected 0x%016" PRIx64 " — %s", x, y, z, got, want, why);
}

LZ_TEST(morton2_small_sites_by_hand)
{
	/* The Z-order of a 4 × 4 block (the right panel of DynamO's Morton figure): key
	 * z[y][x]; each 2 × 2 quarter is a run of four keys. */
	static const uint64_t z[4][4] = {{0, 1, 4, 5}, {2, 3, 6, 7}, {8, 9, 12, 13},
	                                 {10, 11, 14, 15}};
	for (uint32_t y = 0; y < 4; y++)
		for (uint32_t x = 0; x < 4; x++)
			expect_morton2(x, y, z[y][x]);
	/* x = 101, y = 011: pairs (y_i x_i) from the top 01 10 11 = 27. */
	expect_morton2(5, 3, 27);
	expect_morton2(3, 5, 39);
	expect_morton2(8, 0, 64);
	expect_morton2(0, 8, 128);
	expect_morton2(UINT32_C(1) << 16, 0, UINT64_C(1) << 32);
	expect_morton2(0, UINT32_C(1) << 31, UINT64_C(1) << 63);
}
END_TEST

LZ_TEST(morton2_matches_bitwise_interleave)
{
	/* The largest coordinates fill alternate bits, both fill all 64. */
	expect_morton2(0, 0, 0);
	expect_morton2(UINT32_MAX, 0, UINT64_C(0x5555555555555555));
	expect_morton2(0, UINT32_MAX, UINT64_C(0xAAAAAAAAAAAAAAAA));
	expect_morton2(UINT32_MAX, UINT32_MAX, UINT64_MAX);
	expect_morton2(UINT16_MAX, UINT16_MAX, UINT64_C(0xFFFFFFFF));
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 4242);
	for (int i = 0; i < 100000; i++) {
		/* Every other pair on a small lattice, where the low steps matter most. */
		uint32_t m = i % 2 ? UINT32_MAX : 1023;
		uint32_t v[2] = {(uint32_t)gsl_rng_get(rng) & m, (uint32_t)gsl_rng_get(rng) & m};
		expect_morton2(v[0], v[1], interleave(v, 2, 32));
	}
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(morton3_small_sites_by_hand)
{
	/* The unit cube in Z-order: key = x + 2y + 4z. */
	for (uint32_t z = 0; z < 2; z++)
		for (uint32_t y = 0; y < 2; y++)
			for (uint32_t x = 0; x < 2; x++)
				expect_morton3(x, y, z, x + 2 * y + 4 * z);
	/* (5, 3, 6): x = 101, y = 011, z = 110; triples (z_i y_i x_i) from the top:
	 * 101 110 011 = 0b101110011 = 371. */
	expect_morton3(5, 3, 6, 371);
	expect_morton3(2, 0, 0, 8);
	expect_morton3(0, 0, 2, 32);
	expect_morton3(UINT32_C(1) << 20, 0, 0, UINT64_C(1) << 60);
	expect_morton3(0, 0, UINT32_C(1) << 20, UINT64_C(1) << 62);
}
END_TEST

LZ_TEST(morton3_matches_bitwise_interleave)
{
	const uint32_t M = LZ_MORTON3_MAX;
	expect_morton3(0, 0, 0, 0);
	expect_morton3(M, 0, 0, UINT64_C(0x1249249249249249));
	expect_morton3(0, M, 0, UINT64_C(0x2492492492492492));
	expect_morton3(0, 0, M, UINT64_C(0x4924924924924924));
	expect_morton3(M, M, M, UINT64_C(0x7FFFFFFFFFFFFFFF));
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 2121);
	for (int i = 0; i < 100000; i++) {
		uint32_t m = i % 2 ? M : 255;
		uint32_t v[3] = {(uint32_t)gsl_rng_get(rng) & m, (uint32_t)gsl_rng_get(rng) & m,
		                 (uint32_t)gsl_rng_get(rng) & m};
		expect_morton3(v[0], v[1], v[2], interleave(v, 3, 21));
	}
	/* Bits above the 21st are ignored: (x + 2^21 k) has the key of x. */
	for (int i = 0; i < 1000; i++) {
		uint32_t v[3] = {(uint32_t)gsl_rng_get(rng), (uint32_t)gsl_rng_get(rng),
		                 (uint32_t)gsl_rng_get(rng)};
		expect_morton3(v[0], v[1], v[2], interleave(v, 3, 21));
	}
	expect_morton3(UINT32_MAX, 0, 0, UINT64_C(0x1249249249249249));
	expect_morton3(0, 0, UINT32_MAX, UINT64_C(0x4924924924924924));
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(morton_round_trips)
{
	/* Encode, then decode with the library's inverse: every coordinate comes back,
	 * and the keys of an aligned 8 × 8 block are the 64 consecutive integers. */
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 99);
	for (int i = 0; i < 100000; i++) {
		uint32_t x = (uint32_t)gsl_rng_get(rng), y = (uint32_t)gsl_rng_get(rng), u, v;
		lz_morton2_decode(lz_morton2_encode(x, y), &u, &v);
		if (u != x || v != y)
			ck_abort_msg("2D: (%" PRIu32 ", %" PRIu32 ") encoded and decoded came back as "
			             "(%" PRIu32 ", %" PRIu32 "): some bit is lost or misplaced", x, y,
			             u, v);
		uint32_t a = x & LZ_MORTON3_MAX, b = y & LZ_MORTON3_MAX,
		         c = (uint32_t)gsl_rng_get(rng) & LZ_MORTON3_MAX, p, q, r;
		lz_morton3_decode(lz_morton3_encode(a, b, c), &p, &q, &r);
		if (p != a || q != b || r != c)
			ck_abort_msg("3D: (%" PRIu32 ", %" PRIu32 ", %" PRIu32 ") encoded and decoded "
			             "came back as (%" PRIu32 ", %" PRIu32 ", %" PRIu32 ")", a, b, c,
			             p, q, r);
	}
	gsl_rng_free(rng);
	uint64_t seen = 0, base = lz_morton2_encode(40, 16);
	for (uint32_t y = 16; y < 24; y++)
		for (uint32_t x = 40; x < 48; x++) {
			uint64_t k = lz_morton2_encode(x, y) - base;
			ck_assert_msg(k < 64, "site (%" PRIu32 ", %" PRIu32 ") of the aligned 8 x 8 block "
			              "at (40, 16) has key %" PRIu64 " away from the block's first; a "
			              "Z-order block is one run of 64 keys", x, y, k);
			seen |= UINT64_C(1) << k;
		}
	ck_assert_msg(seen == UINT64_MAX, "the 64 sites of an aligned 8 x 8 block must have 64 "
	              "different consecutive keys");
}
END_TEST
