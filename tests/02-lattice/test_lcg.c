/* test_lcg.c — the thesis's LCG: its printed sequence, the period of its low bits, the
 * [0, 1) map at the top integer, and unbiased integers by chi-square (GSL's
 * distribution). Expected integers come from a 64-bit reference step written here,
 * never from the generator under test. */
#include <inttypes.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include <gsl/gsl_cdf.h>

#include "lztest.h"
#include "lz/lcg.h"

/* The reference step in 64-bit arithmetic: the product cannot overflow, the mod is
 * explicit. */
static uint32_t ref_next(uint32_t x)
{
	return (uint32_t)((UINT64_C(69069) * x + 1) % (UINT64_C(1) << 32));
}

/* The state whose next integer is `target`: x = (target - 1) a^-1 mod 2^32, with the
 * inverse of the odd a by Newton's iteration (each step doubles the correct bits). */
static uint32_t state_before(uint32_t target)
{
	uint64_t a = 69069, inv = a;  /* a·a ≡ 1 mod 8: 3 bits right */
	for (int i = 0; i < 5; i++)
		inv = inv * (2 - a * inv) & 0xFFFFFFFFu;
	uint32_t x = (uint32_t)(((uint64_t)(uint32_t)(target - 1u) * inv) & 0xFFFFFFFFu);
	ck_assert(ref_next(x) == target);
	return x;
}

/* Precondition of the statistical tests: from `seed` lz_lcg_next steps the recurrence
 * and keeps the new integer as the state (a shifted or frozen stream has the same
 * statistics, so they could not tell). */
static void require_generator(uint32_t seed)
{
	lz_lcg g;
	lz_lcg_seed(&g, seed);
	for (uint32_t x = seed, n = 1; n <= 3; n++) {
		x = ref_next(x);
		uint32_t got = lz_lcg_next(&g);
		ck_assert_msg(got == x && g.x == x, "precondition: draw %u of lz_lcg_next from seed %"
		              PRIu32 " returned %" PRIu32 " and left the state %" PRIu32 ", expected %"
		              PRIu32 " for both — fix lz_lcg_next first (lcg_sequence_from_seed_zero "
		              "says how)", n, seed, got, g.x, x);
	}
}

LZ_TEST(lcg_sequence_from_seed_zero)
{
	/* Thesis 2.3.3 prints the stream from seed 0 as signed 32-bit integers:
	 * 1, 69070, 475628535, -1017563188, 772999773, -417135238. */
	static const int64_t printed[] = {1, 69070, 475628535, -1017563188, 772999773,
	                                  -417135238};
	lz_lcg g;
	lz_lcg_seed(&g, 0);
	uint32_t ref = 0;
	for (int n = 0; n < 1000; n++) {
		uint32_t got = lz_lcg_next(&g);
		ref = ref_next(ref);
		if (n < 6)
			ck_assert_msg(ref == (uint32_t)(printed[n] & 0xFFFFFFFF), "reference broken");
		if (got != ref)
			ck_abort_msg("draw %d from seed 0 is %" PRIu32 ", expected %" PRIu32 " — "
			             "x_{n+1} = (69069 x_n + 1) mod 2^32 in uint32_t; %s", n + 1, got,
			             ref, n == 0 ? "the first draw from 0 is 1: return the new "
			             "value, not the old one" : "is the new value kept in the state?");
		if (g.x != got)
			ck_abort_msg("after draw %d the state holds %" PRIu32 " but the draw returned "
			             "%" PRIu32 ": the state is the last integer drawn", n + 1, g.x,
			             got);
	}
}
END_TEST

LZ_TEST(lcg_thesis_seeds_zero_to_five)
{
	/* The thesis's other table: seeds 0..5, one RAN call each. The new seed is
	 * 69069 s + 1 and the number printed is that over 2^32 (to 7 digits). */
	static const uint32_t state[] = {1, 69070, 138139, 207208, 276277, 345346};
	static const double printed[] = {0.0, 0.0000160, 0.0000321, 0.0000482, 0.0000643,
	                                 0.0000804};
	for (uint32_t s = 0; s < 6; s++) {
		lz_lcg g;
		lz_lcg_seed(&g, s);
		double u = lz_lcg_uniform(&g);
		ck_assert_msg(g.x == state[s], "seed %" PRIu32 ": after one uniform draw the state "
		              "is %" PRIu32 ", the thesis has %" PRIu32 " — lz_lcg_uniform advances "
		              "the generator exactly once", s, g.x, state[s]);
		ck_assert_msg(fabs(u - printed[s]) < 1e-7, "seed %" PRIu32 ": the uniform draw is "
		              "%.7f, the thesis prints %.7f (= %" PRIu32 " / 2^32)", s, u, printed[s],
		              state[s]);
	}
}
END_TEST

LZ_TEST(lcg_low_bits_have_short_periods)
{
	/* The lesson's warning, checked on the generator: bit k of x_n repeats with period
	 * exactly 2^(k+1) (bit 0 alternates), and the low 16 bits together return to
	 * their start first after 2^16 draws. */
	enum { N = 1 << 17 };
	require_generator(12345);
	uint32_t *x = malloc(N * sizeof *x);
	lz_lcg g;
	lz_lcg_seed(&g, 12345);
	for (int n = 0; n < N; n++)
		x[n] = lz_lcg_next(&g);
	for (int k = 0; k < 16; k++) {
		int p = 2 << k, repeats = 1, halves = 1;
		for (int n = 0; n + p < N; n++) {
			repeats &= ((x[n] ^ x[n + p]) >> k & 1u) == 0;
			if (n + p / 2 < N)
				halves &= ((x[n] ^ x[n + p / 2]) >> k & 1u) == 0;
		}
		ck_assert_msg(repeats && !halves, "bit %d of the LCG's integers should repeat with "
		              "period exactly %d (it does for any a ≡ 1 mod 4, c odd, m = 2^32); "
		              "here it %s — is lz_lcg_next returning the integer itself, unchanged?",
		              k, p, repeats ? "repeats with half that period" : "does not repeat");
	}
	int first = 0;
	for (int n = 1; n < N && !first; n++)
		if ((x[n] & 0xFFFFu) == (x[0] & 0xFFFFu))
			first = n;
	ck_assert_msg(first == 1 << 16, "the low 16 bits returned to their start after %d draws; "
	              "mod 2^16 the generator has full period 65536", first);
	free(x);
}
END_TEST

LZ_TEST(lcg_uniform_is_x_times_two_to_minus_32)
{
	/* Every draw u must be exactly x · 2^-32 of the integer the generator stepped to:
	 * u · 2^32 is then an integer, and that integer is the reference's next value. */
	lz_lcg g;
	lz_lcg_seed(&g, 7);
	uint32_t ref = 7;
	for (int n = 0; n < 100000; n++) {
		double u = lz_lcg_uniform(&g);
		ref = ref_next(ref);
		double scaled = ldexp(u, 32);
		if (scaled != (double)ref)
			ck_abort_msg("draw %d: u = %.17g, u·2^32 = %.17g, but the integer drawn is %" PRIu32
			             " — the map is exactly x · 2^-32 (multiply by 0x1p-32 in double; "
			             "not / (2^32 - 1), not + 0.5, not in float)", n + 1, u, scaled, ref);
		if (g.x != ref)
			ck_abort_msg("after %d uniform draws the state is %" PRIu32 ", expected %" PRIu32
			             ": each uniform draw advances the LCG exactly once", n + 1, g.x,
			             ref);
	}
	lz_lcg_seed(&g, state_before(0));
	ck_assert_msg(lz_lcg_uniform(&g) == 0.0, "the integer 0 maps to 0.0: [0, 1) includes 0");
}
END_TEST

LZ_TEST(lcg_uniform_never_returns_one)
{
	/* The top integers, where dividing by 2^32 - 1 gives 1.0 and float rounds up to
	 * 1.0f (every x >= 2^32 - 128): the thesis's RAN0 did this once in ~4e7 calls. */
	for (uint32_t k = 0; k < 300; k++) {
		uint32_t top = UINT32_MAX - k;
		lz_lcg g;
		lz_lcg_seed(&g, state_before(top));
		double u = lz_lcg_uniform(&g);
		if (!(u < 1.0))
			ck_abort_msg("the integer %" PRIu32 " = 2^32 - %" PRIu32 " mapped to %.17g: a "
			             "uniform draw in [0, 1) can never be 1 — multiply by 2^-32 in double "
			             "(dividing by 2^32 - 1, or rounding x to float, reaches 1.0)", top,
			             k + 1, u);
		if (g.x != top)
			ck_abort_msg("a uniform draw from the state before 2^32 - %" PRIu32 " left the "
			             "state %" PRIu32 ": it advances the generator to the integer it maps",
			             k + 1, g.x);
		if (u != 1.0 - ldexp((double)(k + 1), -32))
			ck_abort_msg("the integer 2^32 - %" PRIu32 " mapped to %.17g, expected exactly "
			             "1 - %" PRIu32 "·2^-32 = %.17g", k + 1, u, k + 1,
			             1.0 - ldexp((double)(k + 1), -32));
	}
}
END_TEST

/* ---- unbiased integers ---- */

/* Draw `draws` values below n from seed `seed` into bins[bin(v)], aborting on a value
 * out of range; return GSL's chi-square p-value for equal bin probabilities. */
static double chi_square_p(uint32_t n, uint32_t seed, long draws, int nbins,
                           int (*bin)(uint32_t v), double *stat)
{
	require_generator(seed);
	long *count = calloc((size_t)nbins, sizeof *count);
	lz_lcg g;
	lz_lcg_seed(&g, seed);
	for (long i = 0; i < draws; i++) {
		uint32_t v = lz_lcg_below(&g, n);
		if (v >= n)
			ck_abort_msg("lz_lcg_below(n = %" PRIu32 ") returned %" PRIu32 ", outside [0, n): "
			             "reject x >= n·q and return x / q with q = floor(2^32 / n)", n, v);
		count[bin(v)]++;
	}
	double e = (double)draws / nbins, chi2 = 0.0;
	for (int b = 0; b < nbins; b++)
		chi2 += ((double)count[b] - e) * ((double)count[b] - e) / e;
	free(count);
	*stat = chi2;
	return gsl_cdf_chisq_Q(chi2, nbins - 1);
}

static uint32_t bin_n;  /* the n of the bin functions below */
static int bin_value(uint32_t v) { return (int)v; }
static int bin_third(uint32_t v) { return (int)(v / (bin_n / 3)); }
static int bin_mod3(uint32_t v) { return (int)(v % 3); }

LZ_TEST(lcg_below_chi_square)
{
	/* 10^6 draws for n = 3, 7, 1000; every value equally likely. A wrong bucket
	 * size or a missing rejection shows as p < 1e-4. */
	static const uint32_t ns[] = {3, 7, 1000};
	for (size_t i = 0; i < sizeof ns / sizeof ns[0]; i++) {
		double chi2, p = chi_square_p(ns[i], 2024, 1000000, (int)ns[i], bin_value, &chi2);
		ck_assert_msg(p > 1e-4, "lz_lcg_below(n = %" PRIu32 "), 10^6 draws from seed 2024: "
		              "chi-square %.1f for %" PRIu32 " degrees of freedom, p = %.2g — the "
		              "values are not equally likely", ns[i], chi2, ns[i] - 1, p);
	}
	lz_lcg g;
	lz_lcg_seed(&g, 1);
	for (int i = 0; i < 1000; i++)
		if (lz_lcg_below(&g, 1) != 0)
			ck_abort_msg("lz_lcg_below(n = 1) must always be 0");
}
END_TEST

LZ_TEST(lcg_below_bias_prone_n)
{
	/* n = 3·2^30: 2^32 / n = 1.33, so x % n gives the lower third twice the weight
	 * and floor(u·n) gives every value ≡ 0 mod 3 twice the weight. With rejection
	 * both splits are even. 3·10^5 draws, the values binned by thirds and by v mod 3. */
	const uint32_t n = UINT32_C(3) << 30;
	bin_n = n;
	double chi2, p = chi_square_p(n, 31, 300000, 3, bin_third, &chi2);
	ck_assert_msg(p > 1e-4, "lz_lcg_below(3·2^30): the thirds [0, 2^30), [2^30, 2^31), "
	              "[2^31, 3·2^30) should be equally likely; chi-square %.1f (2 dof), p = %.2g "
	              "— x %% n favours the lowest third (modulo bias): reject x >= n·q", chi2, p);
	p = chi_square_p(n, 31, 300000, 3, bin_mod3, &chi2);
	ck_assert_msg(p > 1e-4, "lz_lcg_below(3·2^30): v mod 3 should be uniform; chi-square "
	              "%.1f (2 dof), p = %.2g — scaling u·n without rejection maps two integers "
	              "to every third value", chi2, p);
}
END_TEST

LZ_TEST(lcg_below_uses_high_bits)
{
	/* For n = 2^k the answer is the top k bits of the next integer, in one draw, the
	 * top integer 2^32 - 1 included (n divides 2^32: nothing is rejected). Then
	 * successive pairs for n = 4 and 6: the low bits of the LCG have periods 2, 4, …,
	 * so x % n fills only some of the n² pairs. */
	for (int k = 0; k < 32; k++) {
		uint32_t n = UINT32_C(1) << k, seed = 977u * (uint32_t)k + 5u;
		lz_lcg g;
		lz_lcg_seed(&g, seed);
		uint32_t got = lz_lcg_below(&g, n), x = ref_next(seed);
		uint32_t want = (uint32_t)((uint64_t)x >> (32 - k));
		ck_assert_msg(got == want && g.x == x, "lz_lcg_below(n = 2^%d) from state %" PRIu32
		              ": returned %" PRIu32 " after %s, expected the top %d bits of the next "
		              "integer %" PRIu32 ", which is %" PRIu32 ", in one draw (q = 2^(32-%d), "
		              "nothing to reject)", k, seed, got, g.x == x ? "one draw" :
		              "more than one draw", k, x, want, k);
		lz_lcg_seed(&g, state_before(UINT32_MAX));
		got = lz_lcg_below(&g, n);
		ck_assert_msg(got == n - 1 && g.x == UINT32_MAX, "lz_lcg_below(n = 2^%d) with the next "
		              "integer 2^32 - 1: returned %" PRIu32 " with the state at %" PRIu32 ", "
		              "expected n - 1 in one draw — n·q = 2^32 for every power of two, so the "
		              "top integers are accepted (needs 64 bits)", k, got, g.x);
	}
	static const uint32_t ns[] = {4, 6};
	for (size_t i = 0; i < sizeof ns / sizeof ns[0]; i++) {
		uint32_t n = ns[i];
		long count[36] = {0}, pairs = 200000;
		lz_lcg g;
		lz_lcg_seed(&g, 8);
		uint32_t prev = lz_lcg_below(&g, n);
		for (long j = 0; j < pairs; j++) {
			uint32_t v = lz_lcg_below(&g, n);
			if (v >= n)
				ck_abort_msg("lz_lcg_below(n = %" PRIu32 ") returned %" PRIu32, n, v);
			count[prev * n + v]++;
			prev = v;
		}
		double e = (double)pairs / (n * n), chi2 = 0.0;
		int empty = 0;
		for (uint32_t b = 0; b < n * n; b++) {
			chi2 += ((double)count[b] - e) * ((double)count[b] - e) / e;
			empty += count[b] == 0;
		}
		double p = gsl_cdf_chisq_Q(chi2, n * n - 1);
		ck_assert_msg(p > 1e-4, "lz_lcg_below(n = %" PRIu32 "): successive pairs (v_i, "
		              "v_{i+1}) should fill all %" PRIu32 " combinations evenly; chi-square "
		              "%.0f, p = %.2g, %d never seen — x %% n reads the low bits, which "
		              "cycle with period 2, 4, 8…: use the high bits, x / q", n, n * n, chi2,
		              p, empty);
	}
}
END_TEST

/* lz_lcg_below(n) with the next integer forced to x: the value and the draws used. */
static uint32_t below_at(uint32_t n, uint32_t x, int *draws)
{
	lz_lcg g;
	lz_lcg_seed(&g, state_before(x));
	uint32_t v = lz_lcg_below(&g, n);
	*draws = 0;
	for (uint32_t s = state_before(x); *draws < 8; ) {
		s = ref_next(s);
		++*draws;
		if (s == g.x)
			break;
	}
	return v;
}

LZ_TEST(lcg_below_rejection_boundary)
{
	/* Exactly at the edges: with q = floor(2^32 / n) the integers [j·q, (j+1)·q) give
	 * j, and x >= n·q is drawn again. */
	struct {
		uint32_t n, x, v;
		int draws;
	} cases[] = {
		{1000, 0, 0, 1},
		{1000, 4294966, 0, 1},            /* q = 4294967 */
		{1000, 4294967, 1, 1},
		{1000, 4294966999u, 999, 1},      /* n·q - 1, the last accepted */
		{UINT32_C(3) << 30, (UINT32_C(3) << 30) - 1, (UINT32_C(3) << 30) - 1, 1},
		{UINT32_C(1) << 31 | 1, UINT32_C(1) << 31, UINT32_C(1) << 31, 1},
		{UINT32_MAX, UINT32_MAX - 1, UINT32_MAX - 1, 1},
		{7, 4294967289u, 6, 1},           /* q = 613566756, n·q = 4294967292 */
		{7, 4294967291u, 6, 1},
		/* n a power of two: n·q = 2^32, nothing is rejected, not even the top. */
		{4, UINT32_MAX, 3, 1},
		{UINT32_C(1) << 31, UINT32_MAX, INT32_MAX, 1},
		{1, UINT32_MAX, 0, 1},
	};
	for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
		int draws;
		uint32_t v = below_at(cases[i].n, cases[i].x, &draws);
		ck_assert_msg(v == cases[i].v && draws == cases[i].draws, "lz_lcg_below(n = %" PRIu32
		              ") with the next integer %" PRIu32 ": returned %" PRIu32 " using %d "
		              "draw(s), expected %" PRIu32 " in one — %s", cases[i].n, cases[i].x, v,
		              draws, cases[i].v, draws > 1 ? "that integer is below n·q and must be "
		              "accepted (for n a power of two n·q = 2^32: nothing is ever rejected; "
		              "UINT32_MAX - UINT32_MAX % n rejects the top n needlessly)" :
		              "q = floor(2^32 / n) integers per value: return x / q");
	}
	/* The first rejected integers: n·q itself and the top one. The value must come
	 * from the next accepted draw. */
	const uint32_t rejected[][2] = {{1000, 4294967000u}, {UINT32_C(3) << 30, UINT32_C(3) << 30},
	                                {UINT32_C(1) << 31 | 1, (UINT32_C(1) << 31) + 1},
	                                {UINT32_MAX, UINT32_MAX}, {7, 4294967292u}};
	for (size_t i = 0; i < sizeof rejected / sizeof rejected[0]; i++) {
		uint32_t n = rejected[i][0], y = rejected[i][1];
		uint64_t q = (UINT64_C(1) << 32) / n;
		int want_draws = 1, draws;
		do {
			y = ref_next(y);
			want_draws++;
		} while (y >= q * n);
		uint32_t v = below_at(n, rejected[i][1], &draws);
		ck_assert_msg(v == y / q && draws == want_draws, "lz_lcg_below(n = %" PRIu32 ") with "
		              "the next integer %" PRIu32 " (n·q = %" PRIu64 "): returned %" PRIu32
		              " after %d draw(s); that integer is in the incomplete top bucket and "
		              "must be drawn again, the answer is %" PRIu32 " after %d draws — is the "
		              "test x >= n·q (not x > n·q)?", n, rejected[i][1], q * n, v, draws,
		              (uint32_t)(y / q), want_draws);
	}
}
END_TEST
