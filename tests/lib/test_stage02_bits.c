/* test_stage02_bits.c — the library half of lz/bits.h, which students do not write:
 * the power-of-two predicates and check, cells by shift, the six-bit site operations
 * of the lattice gas and Morton decoding. None of these tests calls a graded function,
 * so they pass with the stubs as well. */
#include <inttypes.h>
#include <stdint.h>
#include <string.h>

#include <gsl/gsl_rng.h>

#include "lz/bits.h"
#include "lztest.h"

LZ_TEST(pow2_predicates)
{
	ck_assert_msg(!lz_is_pow2(0), "0 is not a power of two");
	ck_assert_msg(!lz_is_pow2(UINT64_MAX), "2^64 - 1 is not a power of two");
	for (int k = 0; k < 64; k++) {
		uint64_t n = UINT64_C(1) << k;
		ck_assert_msg(lz_is_pow2(n) && lz_log2_pow2(n) == k, "2^%d: is_pow2 %d, log2 %d",
		              k, lz_is_pow2(n), lz_log2_pow2(n));
		if (k >= 2)
			ck_assert_msg(!lz_is_pow2(n - 1) && !lz_is_pow2(n + 1),
			              "2^%d ± 1 is not a power of two", k);
	}
}
END_TEST

LZ_TEST(check_pow2_names_the_allowed_sizes)
{
	const uint64_t max = UINT64_C(1) << 20;
	ck_assert(lz_check_pow2("size", 1, max) == LZ_OK);
	ck_assert(lz_check_pow2("size", 64, max) == LZ_OK);
	ck_assert(lz_check_pow2("size", max, max) == LZ_OK);
	ck_assert(lz_check_pow2("size", LZ_SIDE_MAX, LZ_SIDE_MAX) == LZ_OK);
	ck_assert(lz_check_pow2("size", 100, max) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "size = 100") &&
	              strstr(lz_error_message(), "64") && strstr(lz_error_message(), "128"),
	              "the message for 100 should name it and the nearest powers 64 and 128: '%s'",
	              lz_error_message());
	ck_assert(lz_check_pow2("side", 0, max) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "side = 0"), "'%s'", lz_error_message());
	ck_assert(lz_check_pow2("side", max + 1, max) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "1048576"), "too large: the message should "
	              "name the largest allowed, 1048576: '%s'", lz_error_message());
	ck_assert(lz_check_pow2("side", 3 * (max / 4), max) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "524288") && strstr(lz_error_message(),
	              "1048576"), "'%s'", lz_error_message());
	ck_assert(lz_check_pow2("side", 3, 2) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "3 is too large"), "'%s'", lz_error_message());
	ck_assert(lz_check_pow2("side", 5, 6) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "nearest allowed is 4"), "above 6 only 4 is "
	              "allowed: '%s'", lz_error_message());
	ck_assert(lz_check_pow2("side", UINT64_MAX, UINT64_MAX) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "9223372036854775808"), "'%s'",
	              lz_error_message());
}
END_TEST

LZ_TEST(cell_of_is_the_high_bits)
{
	/* Thesis 2.3.2: a box of 32 in cells of 8; 22 = 10:110 and 21 = 10:101 are in
	 * cell 2, 6 = 00:110 in cell 0. */
	ck_assert(lz_cell_of(22, 3) == 2 && lz_cell_of(21, 3) == 2 && lz_cell_of(6, 3) == 0);
	for (int s = 0; s < 12; s++)
		for (int32_t x = 0; x < 4096; x++)
			if (lz_cell_of(x, s) != x / (1 << s))
				ck_abort_msg("cell of %" PRId32 " with cells of 2^%d: %" PRId32, x, s,
				             lz_cell_of(x, s));
}
END_TEST

LZ_TEST(site_ops_on_all_64_states)
{
	for (unsigned s = 0; s < 64; s++) {
		int n = 0;
		for (int d = 0; d < 6; d++)
			n += s >> d & 1u;
		LZ_REQUIRE(lz_site_count(s) == n, "state %u has %d particles, count says %d", s,
		              n, lz_site_count(s));
		LZ_REQUIRE(lz_site_count(s | 0xC0u) == n, "bits above the sixth are not sites");
		unsigned r = s;
		for (int i = 0; i < 6; i++) {
			r = lz_site_rotate(r, 1);
			LZ_REQUIRE_TRUE(lz_site_count(r) == n);
		}
		LZ_REQUIRE(r == s, "state %u turned six times by 60° is %u", s, r);
		LZ_REQUIRE(lz_site_reverse(lz_site_reverse(s)) == s, "reverse twice of %u", s);
		for (int k = -13; k <= 13; k++) {
			LZ_REQUIRE(lz_site_rotate(lz_site_rotate(s, k), -k) == s,
			              "state %u: rotate by %d and back", s, k);
			LZ_REQUIRE_TRUE(lz_site_rotate(s, k) == lz_site_rotate(s, k + 6));
			LZ_REQUIRE_TRUE(lz_site_rotate(s | 0x40u, k) == lz_site_rotate(s, k));
		}
	}
	/* One particle: direction d turns to d + k mod 6 and reverses to d + 3. */
	for (int d = 0; d < 6; d++) {
		LZ_REQUIRE_TRUE(lz_site_reverse(1u << d) == 1u << (d + 3) % 6);
		for (int k = -12; k <= 12; k++)
			LZ_REQUIRE(lz_site_rotate(1u << d, k) == 1u << ((d + k) % 6 + 6) % 6,
			              "direction %d rotated by %d gave state %u", d, k,
			              lz_site_rotate(1u << d, k));
	}
	/* The head-on pair 0-3 is its own reverse; the symmetric triple 0-2-4 too after
	 * turning by 60° twice. */
	ck_assert(lz_site_reverse(9) == 9 && lz_site_rotate(21, 2) == 21);
}
END_TEST

LZ_TEST(morton_decode_bit_by_bit)
{
	uint32_t x, y, z;
	lz_morton2_decode(UINT64_C(0x5555555555555555), &x, &y);
	ck_assert(x == UINT32_MAX && y == 0);
	lz_morton2_decode(27, &x, &y);
	ck_assert(x == 5 && y == 3);
	lz_morton3_decode(UINT64_MAX, &x, &y, &z);
	ck_assert_msg(x == LZ_MORTON3_MAX && y == LZ_MORTON3_MAX && z == LZ_MORTON3_MAX,
	              "bit 63 is outside the 63-bit 3D key and ignored");
	lz_morton3_decode(371, &x, &y, &z);
	ck_assert(x == 5 && y == 3 && z == 6);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 5);
	for (int i = 0; i < 100000; i++) {
		uint64_t key = (uint64_t)gsl_rng_get(rng) << 32 | gsl_rng_get(rng);
		uint32_t wx = 0, wy = 0, wz = 0;
		for (int b = 0; b < 32; b++) {
			wx |= (uint32_t)(key >> (2 * b) & 1u) << b;
			wy |= (uint32_t)(key >> (2 * b + 1) & 1u) << b;
		}
		lz_morton2_decode(key, &x, &y);
		if (x != wx || y != wy)
			ck_abort_msg("2D decode of 0x%016" PRIx64, key);
		wx = wy = 0;
		for (int b = 0; b < 21; b++) {
			wx |= (uint32_t)(key >> (3 * b) & 1u) << b;
			wy |= (uint32_t)(key >> (3 * b + 1) & 1u) << b;
			wz |= (uint32_t)(key >> (3 * b + 2) & 1u) << b;
		}
		lz_morton3_decode(key, &x, &y, &z);
		if (x != wx || y != wy || z != wz)
			ck_abort_msg("3D decode of 0x%016" PRIx64, key);
	}
	gsl_rng_free(rng);
}
END_TEST
