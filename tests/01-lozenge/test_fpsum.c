/* test_fpsum.c — compensated and pairwise summation against sums known exactly
 * (integer arithmetic in __int128, never the same floating-point sum again). */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_rng.h>

#include "lztest.h"
#include "lz/fpsum.h"

/* The distance from a to b in units of the spacing of doubles at b. */
static double ulps(double a, double b)
{
	double ulp = nextafter(fabs(b), INFINITY) - fabs(b);
	return fabs(a - b) / ulp;
}

static double kahan_of(const double *x, size_t n)
{
	lz_kahan k = {0};
	for (size_t i = 0; i < n; i++)
		lz_kahan_add(&k, x[i]);
	return lz_kahan_value(&k);
}

LZ_TEST(kahan_exact_on_cancellation)
{
	/* The small terms survive a huge one that comes and goes: only Neumaier's branch
	 * (compensate the smaller operand, whichever it is) keeps them. */
	static const double cases[][4] = {
		{1.0, 1e100, 1.0, -1e100},
		{1e100, 1.0, -1e100, 1.0},
		{1.0, 0x1p60, 1.0, -0x1p60},
		{3.0, -0x1p80, 0x1p80, -1.0},
	};
	static const double exact[] = {2.0, 2.0, 2.0, 2.0};
	for (size_t c = 0; c < sizeof exact / sizeof exact[0]; c++) {
		double got = kahan_of(cases[c], 4);
		ck_assert_msg(got == exact[c], "compensated sum of %g, %g, %g, %g gave %.17g, exactly "
		              "%g expected — when |x| > |sum| the lost part is (x - t) + sum, not "
		              "(sum - t) + x (Neumaier's form); and keep it in comp, not in sum",
		              cases[c][0], cases[c][1], cases[c][2], cases[c][3], got, exact[c]);
	}
}
END_TEST

LZ_TEST(kahan_tenth_a_million_times)
{
	/* fl(0.1) = 0x1.999999999999ap-4 = m / 2^56 with m = 7205759403792794: the exact
	 * sum of 1e6 copies is 1e6 m / 2^56, an integer product; its conversion to double
	 * rounds correctly. Naive summation is off by ~1.3e-6 here. */
	const long long m = 7205759403792794LL;
	ck_assert(ldexp((double)m, -56) == 0.1);
	double exact = ldexp((double)((__int128)m * 1000000), -56);
	lz_kahan k = {0};
	for (int i = 0; i < 1000000; i++)
		lz_kahan_add(&k, 0.1);
	double got = lz_kahan_value(&k);
	ck_assert_msg(ulps(got, exact) <= 1.0, "adding 0.1 a million times: compensated sum "
	              "%.17g, exact %.17g (%.0f ulp off); it should be within 1 ulp — is the "
	              "rounding error of every addition added to comp?", got, exact,
	              ulps(got, exact));
}
END_TEST

/* n terms m·2^e with |m| < 2^30 and e in [-30, 30], and their exact sum: every term
 * is an integer multiple of 2^-30, and 2^30 Σ x fits in __int128. A few terms are
 * huge pairs ±2^58 m that cancel exactly, to make the small terms hard to keep. */
static double random_exact_sum(gsl_rng *rng, double *x, size_t n, double *abs_sum)
{
	__int128 total = 0;
	*abs_sum = 0.0;
	for (size_t i = 0; i < n; i++) {
		long m = (long)gsl_rng_uniform_int(rng, 1UL << 31) - (1L << 30);
		int e = (int)gsl_rng_uniform_int(rng, 61) - 30;
		if (i + 1 < n && gsl_rng_uniform(rng) < 0.05) {
			x[i] = ldexp((double)m, 58);
			x[i + 1] = -x[i];
			*abs_sum += 2.0 * fabs(x[i]);
			i++;
			continue;
		}
		x[i] = ldexp((double)m, e);
		total += (__int128)m * ((__int128)1 << (e + 30));
		*abs_sum += fabs(x[i]);
	}
	/* total is far below 2^113: converting it to double rounds once, correctly. */
	return ldexp((double)total, -30);
}

LZ_TEST(kahan_random_sums_within_two_ulp)
{
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 2024);
	double x[1000];
	for (int trial = 0; trial < 200; trial++) {
		size_t n = 1 + gsl_rng_uniform_int(rng, 1000);
		double abs_sum, exact = random_exact_sum(rng, x, n, &abs_sum);
		double got = kahan_of(x, n);
		/* Neumaier's bound: ε|S| + O(n ε²) Σ|x|; the second part is far below 1 ulp
		 * unless the terms cancel almost completely. */
		double slack = 4.0 * (double)n * 0x1p-53 * 0x1p-53 * abs_sum;
		LZ_REQUIRE(fabs(got - exact) <= 2.0 * (nextafter(fabs(exact), INFINITY) -
		           fabs(exact)) + slack, "compensated sum of %zu random terms (trial %d): "
		           "%.17g, exact %.17g (%.1f ulp); it must be within 2 ulp", n, trial, got,
		           exact, ulps(got, exact));
	}
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(pairwise_exact_for_every_length)
{
	/* Terms k/1024 with 1 <= k <= 2^20: every partial sum is exact in double, so any
	 * grouping gives the integer total — unless a term is dropped or counted twice. */
	static const size_t lengths[] = {0, 1, 2, 3, 7, 8, 9, 15, 16, 17, 31, 33, 100, 1023,
	                                 1024, 1025, 4097};
	enum { MAXN = 4097 };
	double *x = malloc(MAXN * sizeof *x);
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 7);
	for (size_t c = 0; c < sizeof lengths / sizeof lengths[0]; c++) {
		size_t n = lengths[c];
		long long total = 0;
		for (size_t i = 0; i < n; i++) {
			long long k = 1 + (long long)gsl_rng_uniform_int(rng, 1UL << 20);
			x[i] = ldexp((double)k, -10);
			total += k;
		}
		double got = lz_sum_pairwise(x, n), exact = ldexp((double)total, -10);
		ck_assert_msg(got == exact, "pairwise sum of %zu terms gave %.17g, exactly %.17g "
		              "expected (off by %.6g terms' worth) — split at h = n/2 into x[0..h) "
		              "and x[h..n), and sum blocks of at most 8 directly", n, got, exact,
		              (got - exact) / ldexp((double)(1 << 19), -10));
	}
	gsl_rng_free(rng);
	free(x);
}
END_TEST

LZ_TEST(pairwise_error_grows_like_log_n)
{
	/* n copies of 0.1: pairwise summation keeps the relative error below
	 * ~log2(n) ε, where naive summation reaches ~n ε / 2 (1e-11 at n = 1e6). */
	enum { MAXN = 1 << 22 };
	const long long m = 7205759403792794LL;  /* fl(0.1) = m / 2^56 */
	double *x = malloc(MAXN * sizeof *x);
	for (size_t i = 0; i < MAXN; i++)
		x[i] = 0.1;
	for (size_t n = 1000; n <= MAXN; n = n * 4 + 3) {
		double exact = ldexp((double)((__int128)m * (long long)n), -56);
		double rel = fabs(lz_sum_pairwise(x, n) - exact) / exact;
		double bound = log2((double)n) * 0x1p-53;
		ck_assert_msg(rel <= bound, "pairwise sum of %zu copies of 0.1: relative error %.2e, "
		              "above log2(n) ε = %.2e — is it really splitting into halves (a split "
		              "that peels off a few terms at a time is naive summation again)?", n,
		              rel, bound);
	}
	free(x);
}
END_TEST
