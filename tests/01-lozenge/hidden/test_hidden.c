/* test_hidden.c — instructor-only tests of stage 01: more stencils, the Verlet
 * family on a many-body system, and summation order. */
#include <math.h>
#include <stdlib.h>

#include <gsl/gsl_rng.h>

#include "../stage01.h"
#include "lz/fpsum.h"
#include "../lozenge_expect.h"

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
	/* Verlet's central difference (r(t+dt) - r(t-dt))/(2dt) is velocity Verlet's v(t)
	 * exactly, for any force (velocity Verlet run backwards from (r, -v) gives
	 * r(t-dt) = r - dt v + dt²/2 a): after 200 steps Verlet's lagging v must equal
	 * velocity Verlet's v of step 199. */
	double *v_before = malloc(108 * 3 * sizeof *v_before);
	for (int k = 0; k < 200; k++) {
		step_ok(a, LZ_VERLET, 0.005);
		for (size_t i = 0; i < 108 * 3; i++)
			v_before[i] = b->v[i];
		step_ok(b, LZ_VELOCITY_VERLET, 0.005);
	}
	double worst = 0.0, worst_v = 0.0;
	for (size_t i = 0; i < 108 * 3; i++) {
		worst = fmax(worst, fabs(a->r[i] - b->r[i]));
		worst_v = fmax(worst_v, fabs(a->v[i] - v_before[i]));
	}
	free(v_before);
	ck_assert_msg(worst < 1e-9, "Lennard-Jones, 200 steps: position Verlet and velocity "
	              "Verlet differ by %.2e in some coordinate; they are the same scheme — is "
	              "every one of the n*dim coordinates updated?", worst);
	ck_assert_msg(worst_v < 1e-9, "Lennard-Jones, 200 steps: position Verlet's velocity "
	              "differs by %.2e from velocity Verlet's one step back; the central "
	              "difference (r(t+dt) - r(t-dt))/(2dt) is that velocity exactly", worst_v);
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
	double e0 = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), de = 0.0;
	for (int k = 0; k < 200; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, 0.005);
		de = fmax(de, fabs(lz_md_energy(s, LZ_VELOCITY_VERLET, NULL) - e0) / fabs(e0));
	}
	/* A symmetric scheme with a wrong force is reversible too: the run must first be
	 * Newton's. Velocity Verlet's energy error at dt = 0.005 is ~1e-4 of |E0| (the
	 * 2e-5 of lj_nve_energy_conserved at dt = 0.002, times (5/2)²). */
	ck_assert_msg(de < 1e-3, "Lennard-Jones, velocity Verlet at dt = 0.005: the energy moved "
	              "by %.2e of |E0| in 200 steps, above 1e-3 — the trajectory being reversed is "
	              "not Newton's (a kick of dt instead of dt/2?)", de);
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

/* N terms (u - 1/2) 2^e with u = k/2^32 from the generator (so every term is an
 * integer multiple of 2^-32) and e in 0..39, among them a few huge pairs ±2^60 that
 * cancel; returns the exact sum, added up in units of 2^-32 in __int128 (|Σ| < 2^93). */
static double order_terms(gsl_rng *rng, double *x, size_t n, double *abs_sum)
{
	__int128 total = 0;
	*abs_sum = 0.0;
	for (size_t i = 0; i < n; i++) {
		if (i + 1 < n && gsl_rng_uniform(rng) < 0.01) {
			x[i] = 0x1p60;
			x[i + 1] = -0x1p60;
			*abs_sum += 0x1p61;
			i++;
			continue;
		}
		long long k = (long long)gsl_rng_get(rng) - (1LL << 31);
		int e = (int)gsl_rng_uniform_int(rng, 40);
		x[i] = ldexp((double)k, e - 32);
		total += (__int128)k << e;
		*abs_sum += fabs(x[i]);
	}
	return ldexp((double)total, -32);
}

LZ_TEST(hidden_kahan_order_independent)
{
	/* The compensated sum is nearly correctly rounded in every order: shuffled 20
	 * times, it stays within 2 ulp of the exact sum (Neumaier's bound ε|S| + O(n ε²)
	 * Σ|x|, the second part ~1e-7 here, far below an ulp of |S| ~ 1e13) — naive
	 * summation, or Kahan's original form when a ±2^60 term meets a smaller sum, moves
	 * by many. */
	gsl_rng *rng = gsl_rng_alloc(gsl_rng_mt19937);
	gsl_rng_set(rng, 11);
	enum { N = 5000 };
	double *x = malloc(N * sizeof *x), abs_sum;
	double exact = order_terms(rng, x, N, &abs_sum);
	double slack = 4.0 * N * 0x1p-53 * 0x1p-53 * abs_sum;
	double ulp = nextafter(fabs(exact), INFINITY) - fabs(exact);
	for (int trial = 0; trial <= 20; trial++) {
		lz_kahan s = {0};
		for (size_t i = 0; i < N; i++)
			lz_kahan_add(&s, x[i]);
		double err = fabs(lz_kahan_value(&s) - exact);
		LZ_REQUIRE(err <= 2.0 * ulp + slack, "the compensated sum of %d terms (with "
		           "cancelling ±2^60 pairs) in order %d of 21 is %.1f ulp from the exact sum; "
		           "in any order it must stay within 2 ulp — when |x| > |sum| the lost part "
		           "is (x - t) + sum", N, trial, err / ulp);
		for (size_t i = N - 1; i > 0; i--) {
			size_t j = gsl_rng_uniform_int(rng, i + 1);
			double tmp = x[i];
			x[i] = x[j];
			x[j] = tmp;
		}
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
