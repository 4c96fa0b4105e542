/* test_hidden.c — instructor-only tests of stage 01: more stencils, the Verlet
 * family on a many-body system, and summation order. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_rng.h>

#include "../stage01.h"
#include "lz/fpsum.h"
#include "lz/lozenge.h"

#define T(c, h, n, d) {LZ_COL_##c, (h), {(n), (d)}}

static void expect_order(const char *what, lz_formula f, int order, long long num,
                         long long den, int deriv)
{
	int p = -99, d = -99;
	lz_ratio c = {0, 0};
	int status = lz_formula_order(&f, 16, &p, &c, &d);
	ck_assert_msg(status == LZ_OK && p == order && c.num == num && c.den == den && d == deriv,
	              "%s: status %d, got %lld/%lld dt^%d x^(%d), expected %lld/%lld dt^%d x^(%d)",
	              what, status, c.num, c.den, p, d, num, den, order, deriv);
}

LZ_TEST(hidden_more_stencils)
{
	/* Beeman's position: r + dt v + 2/3 dt² a - 1/6 dt² a(t-dt) - r(t+dt):
	 * x‴: 1/6 - 1/6 = 0; x⁗: -1/6 · 1/2 - 1/24 = -1/8. */
	expect_order("Beeman position",
	             (lz_formula){LZ_COL_R, 2, 4, {T(R, 0, 1, 1), T(V, 0, 1, 1), T(A, 0, 2, 3),
	                                           T(A, -2, -1, 6)}},
	             4, -1, 8, 4);
	/* Fourth-order first derivative (-r(+2) + 8r(+1) - 8r(-1) + r(-2))/(12 dt):
	 * odd moments Σ w j^D / D! = 1, 0, -1/30 for D = 1, 3, 5. */
	expect_order("5-point velocity",
	             (lz_formula){LZ_COL_V, 0, 4, {T(R, 4, -1, 12), T(R, 2, 8, 12),
	                                           T(R, -2, -8, 12), T(R, -4, 1, 12)}},
	             4, -1, 30, 5);
	/* Acceleration from half-step velocities: (v(+dt/2) - v(-dt/2))/dt = a + dt²/24 x⁗. */
	expect_order("a from half-step v",
	             (lz_formula){LZ_COL_A, 0, 2, {T(V, 1, 1, 1), T(V, -1, -1, 1)}}, 2, 1, 24, 4);
	/* The leapfrog kick shifted by a whole step: the order cannot depend on where t is. */
	expect_order("shifted leapfrog velocity",
	             (lz_formula){LZ_COL_V, 3, 2, {T(V, 1, 1, 1), T(A, 2, 1, 1)}}, 3, -1, 24, 4);
}
END_TEST

LZ_TEST(hidden_verlet_matches_velocity_verlet_on_lj)
{
	/* Störmer Verlet started by Taylor from (r, v) produces velocity Verlet's positions;
	 * on 108 interacting particles every coordinate of every particle must agree
	 * (chaos amplifies round-off, ~1e-12 after 200 steps). */
	lz_lj p, q;
	lz_md *a = lj_fluid_new(&p, 108, 0.8, 1.0, 5), *b = lj_fluid_new(&q, 108, 0.8, 1.0, 5);
	ck_assert(lz_md_start(a, LZ_VERLET, 0.005) == LZ_OK);
	ck_assert(lz_md_start(b, LZ_VELOCITY_VERLET, 0.005) == LZ_OK);
	for (int k = 0; k < 200; k++) {
		step_ok(a, LZ_VERLET, 0.005);
		step_ok(b, LZ_VELOCITY_VERLET, 0.005);
	}
	double worst = 0.0;
	for (size_t i = 0; i < 108 * 3; i++)
		worst = fmax(worst, fabs(a->r[i] - b->r[i]));
	ck_assert_msg(worst < 1e-9, "Lennard-Jones, 200 steps: position Verlet and velocity "
	              "Verlet differ by %.2e in some coordinate; they are the same scheme — is "
	              "every one of the n*dim coordinates updated?", worst);
	lz_md_free(a);
	lz_md_free(b);
}
END_TEST

LZ_TEST(hidden_lj_time_reversal)
{
	/* 200 steps forward, velocities reversed, 200 back: a chaotic fluid still returns
	 * to ~1e-14 with a time-reversible scheme. */
	lz_lj p;
	lz_md *s = lj_fluid_new(&p, 108, 0.8, 1.0, 9);
	double *start = malloc(108 * 3 * sizeof *start);
	for (size_t i = 0; i < 108 * 3; i++)
		start[i] = s->r[i];
	ck_assert(lz_md_start(s, LZ_VELOCITY_VERLET, 0.005) == LZ_OK);
	for (int k = 0; k < 200; k++)
		step_ok(s, LZ_VELOCITY_VERLET, 0.005);
	for (size_t i = 0; i < 108 * 3; i++)
		s->v[i] = -s->v[i];
	for (int k = 0; k < 200; k++)
		step_ok(s, LZ_VELOCITY_VERLET, 0.005);
	double worst = 0.0;
	for (size_t i = 0; i < 108 * 3; i++)
		worst = fmax(worst, fabs(s->r[i] - start[i]));
	ck_assert_msg(worst < 1e-10, "Lennard-Jones, velocity Verlet 200 steps forward and back: "
	              "ended %.2e from the start; a time-reversible scheme returns to round-off",
	              worst);
	free(start);
	lz_md_free(s);
}
END_TEST

LZ_TEST(hidden_kahan_order_independent)
{
	/* The compensated sum is nearly correctly rounded, so shuffling the terms changes
	 * it by at most an ulp or two — naive summation changes by many. */
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 11);
	enum { N = 5000 };
	double *x = malloc(N * sizeof *x);
	for (size_t i = 0; i < N; i++)
		x[i] = ldexp(gsl_rng_uniform(rng) - 0.5, (int)gsl_rng_uniform_int(rng, 40));
	lz_kahan k = {0};
	for (size_t i = 0; i < N; i++)
		lz_kahan_add(&k, x[i]);
	double first = lz_kahan_value(&k);
	for (int trial = 0; trial < 20; trial++) {
		for (size_t i = N - 1; i > 0; i--) {
			size_t j = gsl_rng_uniform_int(rng, i + 1);
			double t = x[i];
			x[i] = x[j];
			x[j] = t;
		}
		lz_kahan s = {0};
		for (size_t i = 0; i < N; i++)
			lz_kahan_add(&s, x[i]);
		double ulp = nextafter(fabs(first), INFINITY) - fabs(first);
		ck_assert_msg(fabs(lz_kahan_value(&s) - first) <= 2.0 * ulp, "the compensated sum of "
		              "the same %d terms in another order differs by %.1f ulp; it should not "
		              "depend on the order by more than 2 ulp", N,
		              fabs(lz_kahan_value(&s) - first) / ulp);
	}
	free(x);
	gsl_rng_free(rng);
}
END_TEST

LZ_TEST(hidden_pairwise_deep_recursion)
{
	/* 2^22 + 3 terms of 1: exact in any grouping, and the recursion depth stays
	 * ~log2 n (a split that peels off one term at a time overflows the stack). */
	size_t n = (1u << 22) + 3;
	double *x = malloc(n * sizeof *x);
	for (size_t i = 0; i < n; i++)
		x[i] = 1.0;
	double got = lz_sum_pairwise(x, n);
	ck_assert_msg(got == (double)n, "pairwise sum of %zu ones gave %.17g", n, got);
	free(x);
}
END_TEST
