/* test_stage01_lib.c — the library half of stage 01, which students do not write:
 * the Lennard-Jones force and start-up, exact rationals, the lz_md bookkeeping
 * around the graded steps, the scheme tables and the lozenge diagram, and the scene
 * checks of the verlet method. None of these tests calls a graded function, so they
 * pass with the stubs as well. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lz/integrate.h"
#include "lz/lozenge.h"
#include "method.h"
#include "lz/output.h"
#include "lz/potential.h"
#include "lz/rng.h"
#include "scene.h"
#include "lztest.h"
#include "support.h"

/* ---- Lennard-Jones ---- */

/* n particles on the lattice of box p->box, each nudged by up to ±0.1σ so that the
 * forces do not cancel by symmetry. */
static double *lj_config(lz_lj *p, size_t n, int dim, double rho, unsigned long seed)
{
	ck_assert_msg(lz_lj_init(p, n, dim, rho, 2.5) == LZ_OK, "lz_lj_init: %s",
	              lz_error_message());
	double *r = malloc(n * (size_t)dim * sizeof *r);
	ck_assert(lz_lattice_start(r, n, dim, p->box) == LZ_OK);
	lz_rng *rng = lz_rng_alloc(NULL, seed);
	for (size_t i = 0; i < n * (size_t)dim; i++)
		r[i] += 0.2 * (lz_rng_uniform(rng) - 0.5);
	lz_rng_free(rng);
	return r;
}

LZ_TEST(lj_total_force_is_zero)
{
	for (int dim = 2; dim <= 3; dim++) {
		size_t n = dim == 3 ? 108 : 128;
		lz_lj p;
		double *r = lj_config(&p, n, dim, 0.8, 3), *a = malloc(n * (size_t)dim * sizeof *a), u;
		ck_assert(lz_lj_force(n, dim, r, a, &u, &p) == LZ_OK);
		double total[3] = {0, 0, 0}, largest = 0.0;
		for (size_t i = 0; i < n * (size_t)dim; i++) {
			total[i % (size_t)dim] += a[i];
			largest = fmax(largest, fabs(a[i]));
		}
		for (int c = 0; c < dim; c++)
			ck_assert_msg(fabs(total[c]) < 1e-11 * largest * (double)n, "%dD Lennard-Jones: "
			              "the total force has component %d = %g (largest single force %g); "
			              "Newton's third law makes it zero", dim, c, total[c], largest);
		free(r);
		free(a);
	}
}
END_TEST

LZ_TEST(lj_force_is_minus_gradient)
{
	/* A central difference of U, step 1e-6: error ~ h² U‴ + ε U / h, far below 1e-5. */
	const size_t n = 108;
	lz_lj p;
	double *r = lj_config(&p, n, 3, 0.8, 4), u;
	double *a = malloc(3 * n * sizeof *a), *scratch = malloc(3 * n * sizeof *scratch);
	ck_assert(lz_lj_force(n, 3, r, a, &u, &p) == LZ_OK);
	for (size_t i = 0; i < 3 * n; i += 7) {
		const double h = 1e-6, keep = r[i];
		double up, down;
		r[i] = keep + h;
		lz_lj_force(n, 3, r, scratch, &up, &p);
		r[i] = keep - h;
		lz_lj_force(n, 3, r, scratch, &down, &p);
		r[i] = keep;
		double grad = (up - down) / (2 * h);
		ck_assert_msg(fabs(a[i] + grad) < 1e-5 * fmax(1.0, fabs(a[i])), "coordinate %zu: "
		              "the force is %.10g but -dU/dx = %.10g", i, a[i], -grad);
	}
	free(r);
	free(a);
	free(scratch);
}
END_TEST

/* The energy and the force on particle 0 of a pair at distance d along x. */
static void pair_at(const lz_lj *p, double d, double *u, double *f)
{
	double r[6] = {1, 1, 1, 1 + d, 1, 1}, a[6];
	lz_lj_force(2, 3, r, a, u, (void *)p);
	*f = a[0];
}

LZ_TEST(lj_cut_and_shift_is_continuous)
{
	lz_lj p;
	ck_assert(lz_lj_init(&p, 2, 3, 0.001, 2.5) == LZ_OK);
	double u, f;
	pair_at(&p, 2.5 * (1 - 1e-9), &u, &f);
	ck_assert_msg(fabs(u) < 1e-9, "U just inside rc is %g; cut and shifted, it goes to 0", u);
	pair_at(&p, 2.5, &u, &f);
	ck_assert_msg(u == 0 && f == 0, "at r = rc the pair must not interact (U %g, F %g)", u, f);
	pair_at(&p, pow(2.0, 1.0 / 6.0), &u, &f);
	ck_assert_msg(fabs(f) < 1e-12 && fabs(u - (-1.0 - p.ushift)) < 1e-12, "at the minimum "
	              "r = 2^(1/6): F = %g (expected 0), U = %.15g (expected -1 - U(rc))", f, u);
	pair_at(&p, 1.0, &u, &f);
	ck_assert_msg(fabs(u + p.ushift) < 1e-15 && fabs(f + 24.0) < 1e-12, "at r = σ: U = %g "
	              "(expected -U(rc) = %g), force on the left particle %g (expected -24)", u,
	              -p.ushift, f);
	/* Unwrapped positions: the same pair many boxes apart is the same pair. */
	double r[6] = {1, 1, 1, 1 + 1.2 + 7 * p.box, 1 - 3 * p.box, 1}, a[6];
	lz_lj_force(2, 3, r, a, &u, &p);
	double u_near;
	pair_at(&p, 1.2, &u_near, &f);
	ck_assert_msg(fabs(u - u_near) < 1e-9, "a pair 1.2σ apart but unwrapped by several boxes "
	              "has U = %g instead of %g: the minimum image must handle any shift", u, u_near);
}
END_TEST

LZ_TEST(lj_rejects_cutoff_beyond_half_box)
{
	lz_lj p;
	int status = lz_lj_init(&p, 32, 3, 0.8, 2.5);
	ck_assert_msg(status == LZ_EINVAL && strstr(lz_error_message(), "L/2"), "32 particles at "
	              "ρ = 0.8 have L/2 = 1.71 < rc = 2.5: expected LZ_EINVAL naming L/2, got %d (%s)",
	              status, lz_error_message());
	ck_assert(lz_lj_init(&p, 108, 3, 0.8, 2.5) == LZ_OK);
	ck_assert(lz_lj_init(&p, 108, 3, -1.0, 2.5) == LZ_EINVAL);
	ck_assert(lz_lj_init(&p, 108, 1, 0.8, 2.5) == LZ_EINVAL);
}
END_TEST

LZ_TEST(lattice_start_sizes)
{
	static const size_t ok3[] = {4, 32, 108, 256}, ok2[] = {2, 8, 18, 200};
	for (int k = 0; k < 4; k++) {
		ck_assert(lz_lattice_check(ok3[k], 3) == LZ_OK && lz_lattice_check(ok2[k], 2) == LZ_OK);
		/* The fcc nearest-neighbour distance is a/√2 for the cell a = L/m: check that
		 * no pair is closer and every site is inside the box. */
		size_t n = ok3[k], m = (size_t)lround(cbrt((double)n / 4));
		double box = 2.0 * (double)m, *r = malloc(3 * n * sizeof *r), closest = INFINITY;
		ck_assert(lz_lattice_start(r, n, 3, box) == LZ_OK);
		size_t outside = 0;
		for (size_t i = 0; i < 3 * n; i++)
			outside += !(r[i] >= 0 && r[i] < box);
		ck_assert_msg(outside == 0, "fcc n = %zu: %zu coordinates outside [0, L)", n, outside);
		for (size_t i = 0; i < n; i++)
			for (size_t j = i + 1; j < n; j++) {
				double d2 = 0;
				for (int c = 0; c < 3; c++) {
					double d = r[3 * i + c] - r[3 * j + c];
					d -= box * nearbyint(d / box);
					d2 += d * d;
				}
				closest = fmin(closest, sqrt(d2));
			}
		ck_assert_msg(fabs(closest - 2.0 / sqrt(2.0)) < 1e-12, "fcc n = %zu: closest pair "
		              "%g, expected a/√2 = %g", n, closest, 2.0 / sqrt(2.0));
		free(r);
	}
	ck_assert(lz_lattice_check(100, 3) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "32") && strstr(lz_error_message(), "108"),
	              "n = 100 in 3D: the message should name 32 and 108: %s", lz_error_message());
	ck_assert(lz_lattice_check(3, 2) == LZ_EINVAL && lz_lattice_check(1, 3) == LZ_EINVAL);
	ck_assert(lz_lattice_check(8, 1) == LZ_EINVAL);
}
END_TEST

LZ_TEST(maxwell_velocities_zero_momentum_exact_temperature)
{
	lz_rng *rng = lz_rng_alloc(NULL, 12);
	for (int dim = 2; dim <= 3; dim++) {
		size_t n = 50;
		double v[150], p[3] = {0, 0, 0}, v2 = 0;
		lz_maxwell_velocities(v, n, dim, 1.7, rng);
		for (size_t i = 0; i < n * (size_t)dim; i++) {
			p[i % (size_t)dim] += v[i];
			v2 += v[i] * v[i];
		}
		for (int c = 0; c < dim; c++)
			ck_assert_msg(fabs(p[c]) < 1e-12, "%dD: total momentum %g, expected 0", dim, p[c]);
		double t = v2 / ((double)dim * (double)(n - 1));
		ck_assert_msg(fabs(t - 1.7) < 1e-12, "%dD: kinetic temperature %.15g, expected 1.7", dim, t);
	}
	double one[3] = {9, 9, 9};
	lz_maxwell_velocities(one, 1, 3, 2.0, rng);
	ck_assert_msg(one[0] == 0 && one[1] == 0 && one[2] == 0, "one particle with zero momentum "
	              "must rest");
	lz_rng_free(rng);
}
END_TEST

/* ---- exact rationals ---- */

static int is(lz_ratio r, long long num, long long den)
{
	return r.num == num && r.den == den;
}

LZ_TEST(ratio_arithmetic_exact_and_reduced)
{
	char buf[64];
	ck_assert(is(lz_ratio_make(6, -4), -3, 2) && is(lz_ratio_make(0, 5), 0, 1));
	ck_assert(is(lz_ratio_add(lz_ratio_make(1, 6), lz_ratio_make(1, 3)), 1, 2));
	ck_assert(is(lz_ratio_sub(lz_ratio_make(1, 12), lz_ratio_make(1, 6)), -1, 12));
	ck_assert(is(lz_ratio_mul(lz_ratio_make(-2, 3), lz_ratio_make(9, 4)), -3, 2));
	ck_assert(!lz_ratio_ok(lz_ratio_make(1, 0)) && lz_ratio_is_zero(lz_ratio_make(0, -7)));
	/* 20! is exact; (2^40)² is beyond 2^62 and turns invalid, and stays so. */
	lz_ratio f = lz_ratio_make(1, 1);
	for (int k = 2; k <= 20; k++)
		f = lz_ratio_mul(f, lz_ratio_make(k, 1));
	ck_assert(is(f, 2432902008176640000LL, 1));
	lz_ratio big = lz_ratio_mul(lz_ratio_make(1LL << 40, 1), lz_ratio_make(1LL << 40, 1));
	ck_assert(!lz_ratio_ok(big) && !lz_ratio_ok(lz_ratio_add(big, lz_ratio_make(1, 1))));
	ck_assert(!lz_ratio_ok(lz_ratio_make(-9223372036854775807LL - 1, 1)));
	ck_assert(!lz_ratio_ok(lz_ratio_sub(lz_ratio_make(1, 1),
	                                    (lz_ratio){-9223372036854775807LL - 1, 1})));
	ck_assert_str_eq(lz_ratio_str(lz_ratio_make(-1, 12), buf, sizeof buf), "-1/12");
	ck_assert_str_eq(lz_ratio_str(lz_ratio_make(3, 1), buf, sizeof buf), "3");
}
END_TEST

/* ---- lz_md bookkeeping (no graded step is reached) ---- */

static lz_md *one_oscillator(lz_harmonic *p)
{
	lz_md *s = lz_md_alloc(1, 1, lz_harmonic_force, p);
	ck_assert(s != NULL);
	s->r[0] = 1.0;
	s->v[0] = 0.5;
	return s;
}

LZ_TEST(md_alloc_rejects_bad_sizes)
{
	ck_assert(lz_md_alloc(0, 3, lz_harmonic_force, NULL) == NULL);
	ck_assert(lz_md_alloc(5, 0, lz_harmonic_force, NULL) == NULL);
	ck_assert(lz_md_alloc(5, 4, lz_harmonic_force, NULL) == NULL);
	ck_assert(lz_md_alloc(5, 2, NULL, NULL) == NULL);
	ck_assert(lz_md_alloc((size_t)-1 / 2, 3, lz_harmonic_force, NULL) == NULL);
}
END_TEST

LZ_TEST(md_step_rejects_bad_dt)
{
	static const double bad[] = {0.0, -0.1, NAN, INFINITY, -INFINITY};
	lz_harmonic p = {1.0};
	for (int m = 0; m < LZ_NINTEGRATORS; m++) {
		lz_md *s = one_oscillator(&p);
		ck_assert(lz_md_start(s, (lz_integrator)m, 0.1) == LZ_OK);
		for (size_t i = 0; i < sizeof bad / sizeof bad[0]; i++) {
			ck_assert_msg(lz_md_step(s, (lz_integrator)m, bad[i]) == LZ_EINVAL, "%s: "
			              "dt = %g must be refused", lz_integrator_name((lz_integrator)m), bad[i]);
			ck_assert(strstr(lz_error_message(), "dt"));
			ck_assert(lz_md_start(s, (lz_integrator)m, bad[i]) == LZ_EINVAL);
		}
		ck_assert_msg(s->t == 0.0 && s->force_evals == 1 && s->r[0] == 1.0,
		              "a refused step must leave the state alone");
		ck_assert(lz_md_step(s, (lz_integrator)LZ_NINTEGRATORS, 0.1) == LZ_EINVAL);
		lz_md_free(s);
	}
}
END_TEST

LZ_TEST(md_step_rejects_changed_dt)
{
	static const lz_integrator bound[] = {LZ_VERLET, LZ_LEAPFROG};
	lz_harmonic p = {1.0};
	for (int i = 0; i < 2; i++) {
		lz_md *s = one_oscillator(&p);
		ck_assert(lz_md_start(s, bound[i], 0.1) == LZ_OK);
		int status = lz_md_step(s, bound[i], 0.2);
		ck_assert_msg(status == LZ_EINVAL && strstr(lz_error_message(), "lz_md_start"),
		              "%s started with dt = 0.1 must refuse dt = 0.2 (got %d: %s)",
		              lz_integrator_name(bound[i]), status, lz_error_message());
		ck_assert(lz_md_step(s, bound[i], 0.1 * (1 + 1e-15)) == LZ_EINVAL);
		lz_md_free(s);
	}
}
END_TEST

LZ_TEST(md_start_prepares_each_layout)
{
	lz_harmonic p = {2.0};
	lz_md *s = one_oscillator(&p);
	ck_assert(lz_md_start(s, LZ_VERLET, 0.1) == LZ_OK);
	/* a = -4, so r(t - dt) = 1 - 0.1·0.5 + 0.005·(-4) = 0.93 to second order. */
	ck_assert_msg(s->a[0] == -4.0 && fabs(s->r_prev[0] - 0.93) < 1e-15 && s->u == 2.0 &&
	              s->force_evals == 1 && s->v_lags == 0, "verlet start: a %g, r_prev %.17g, "
	              "u %g", s->a[0], s->r_prev[0], s->u);
	s->v[0] = 0.5;
	ck_assert(lz_md_start(s, LZ_LEAPFROG, 0.1) == LZ_OK);
	ck_assert_msg(fabs(s->v[0] - 0.7) < 1e-15, "leapfrog start: v(t - dt/2) = 0.5 + 0.05·4 "
	              "= 0.7, got %.17g", s->v[0]);
	/* The synchronised kinetic energy undoes the shift: v(t) = 0.5 again. */
	ck_assert(fabs(lz_md_kinetic(s, LZ_LEAPFROG) - 0.125) < 1e-15);
	double when;
	ck_assert(fabs(lz_md_energy(s, LZ_LEAPFROG, &when) - 2.125) < 1e-15 && when == 0.0);
	/* Verlet once stepping: v pairs with u_prev one step back. */
	s->v_lags = 1;
	s->t = 1.0;
	s->u_prev = 3.0;
	ck_assert(fabs(lz_md_energy(s, LZ_VERLET, &when) - (3.0 + 0.5 * s->v[0] * s->v[0])) <
	          1e-15 && fabs(when - 0.9) < 1e-15);
	lz_md_free(s);
}
END_TEST

static int blow_up(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	a[0] = r[0] > 1.5 ? NAN : -r[0];
	*u = 0.5 * r[0] * r[0];
	return LZ_OK;
}

/* The clock is t0 + k·dt, not a running sum: after 10^6 steps of dt = 0.1 it reads
 * 10^5 to the last bit, where adding 0.1 each step would be off by ~1e-6. A change of
 * dt re-bases it at the current time. */
LZ_TEST(md_clock_does_not_accumulate_round_off)
{
	lz_harmonic p = {1.0};
	lz_md *s = lz_md_alloc(1, 1, lz_harmonic_force, &p);
	s->r[0] = 1.0;
	ck_assert(lz_md_start(s, LZ_VELOCITY_VERLET, 0.1) == LZ_OK);
	double sum = 0.0;
	for (int k = 0; k < 1000000; k++) {
		if (lz_md_step(s, LZ_VELOCITY_VERLET, 0.1) != LZ_OK)  /* no ck_assert: 1e6 pipe writes */
			ck_abort_msg("step %d failed: %s", k, lz_error_message());
		sum += 0.1;
	}
	ck_assert_msg(s->t == 1e5, "after 10^6 steps of 0.1 the clock reads %.17g, not 1e5 "
	              "(a running sum reads %.17g)", s->t, sum);
	ck_assert_int_eq(lz_md_step(s, LZ_VELOCITY_VERLET, 0.25), LZ_OK);
	ck_assert_msg(s->t == 1e5 + 0.25 && s->t0 == 1e5 && s->nsteps == 1,
	              "a new dt should re-base the clock at t = 1e5; t = %.17g, t0 = %.17g",
	              s->t, s->t0);
	lz_md_free(s);
}
END_TEST

LZ_TEST(md_force_reports_non_finite)
{
	lz_md *s = lz_md_alloc(1, 1, blow_up, NULL);
	s->r[0] = 1.0;
	ck_assert(lz_md_force(s) == LZ_OK && s->force_evals == 1);
	s->r[0] = 2.0;
	ck_assert_msg(lz_md_force(s) == LZ_EPHYS && s->force_evals == 2, "a NaN force must be "
	              "reported as LZ_EPHYS");
	lz_md_free(s);
}
END_TEST

LZ_TEST(md_round_float)
{
	lz_harmonic p = {1.0};
	lz_md *s = lz_md_alloc(2, 1, lz_harmonic_force, &p);
	s->r[0] = s->v[1] = s->a[0] = s->r_prev[1] = 0.1;
	lz_md_round_float(s);
	ck_assert(s->r[0] == (float)0.1 && s->v[1] == (float)0.1 && s->a[0] == (float)0.1 &&
	          s->r_prev[1] == (float)0.1 && s->r[0] != 0.1);
	lz_md_free(s);
}
END_TEST

LZ_TEST(integrator_names_parse)
{
	for (int m = 0; m < LZ_NINTEGRATORS; m++) {
		lz_integrator back;
		ck_assert(lz_integrator_parse(lz_integrator_name((lz_integrator)m), &back) == LZ_OK &&
		          (int)back == m);
	}
	lz_integrator m;
	ck_assert(lz_integrator_parse("rk4", &m) == LZ_EINVAL);
	ck_assert_msg(strstr(lz_error_message(), "rk4") && strstr(lz_error_message(), "leapfrog"),
	              "the message should name the bad value and the choices: %s",
	              lz_error_message());
	ck_assert(lz_integrator_parse(NULL, &m) == LZ_EINVAL);
}
END_TEST

/* ---- the scheme tables and the diagram ---- */

LZ_TEST(scheme_tables_sane)
{
	static const char *const names[] = {"verlet", "velocity", "leapfrog", "velocity-verlet",
	                                    "euler", "symplectic-euler"};
	int n;
	const lz_scheme *all = lz_schemes(&n);
	ck_assert_int_eq(n, 6);
	for (int i = 0; i < 6; i++) {
		const lz_scheme *s = lz_scheme_find(names[i]);
		ck_assert_msg(s && s >= all && s < all + n && s->title && s->nformulas >= 1 &&
		              s->nformulas <= LZ_FORMULAS_MAX, "scheme %s missing or malformed",
		              names[i]);
		for (int k = 0; k < s->nformulas; k++)
			for (int j = 0; j < s->f[k].nterms; j++) {
				lz_ratio w = s->f[k].term[j].w;
				ck_assert(w.den > 0 && is(lz_ratio_make(w.num, w.den), w.num, w.den));
				ck_assert(s->f[k].term[j].col != s->f[k].col ||
				          s->f[k].term[j].half != s->f[k].half);
			}
	}
	const lz_formula *v = &lz_scheme_find("verlet")->f[0];
	ck_assert(v->col == LZ_COL_R && v->half == 2 && v->nterms == 3 && is(v->term[0].w, 2, 1) &&
	          v->term[1].half == -2 && is(v->term[1].w, -1, 1) && v->term[2].col == LZ_COL_A);
	ck_assert(lz_scheme_find("rk4") == NULL && lz_scheme_find(NULL) == NULL);
}
END_TEST

LZ_TEST(lozenge_diagram_renders)
{
	int n;
	const lz_scheme *all = lz_schemes(&n), *pick[6];
	for (int i = 0; i < n; i++)
		pick[i] = &all[i];
	const char *dir = lzt_tmpdir(), *script = lzt_path(dir, "lozenge.gp");
	FILE *f = fopen(script, "w");
	ck_assert(f != NULL);
	ck_assert(lz_lozenge_gnuplot(f, pick, 0, "x.png") == LZ_EINVAL);
	ck_assert(lz_lozenge_gnuplot(f, pick, 7, "x.png") == LZ_EINVAL);
	ck_assert(lz_lozenge_gnuplot(f, pick, 2, "it's.png") == LZ_EINVAL);
	ck_assert(lz_lozenge_gnuplot(f, pick, n, "lozenge.png") == LZ_OK);
	fclose(f);
	int status = lz_gnuplot(dir, "lozenge.gp");
	ck_assert_msg(status == LZ_OK || status == 1, "gnuplot failed on the lozenge script: %s",
	              lz_error_message());
	if (status == LZ_OK) {
		size_t len = 0;
		char *png = lzt_slurp(lzt_path(dir, "lozenge.png"), &len);
		ck_assert_msg(png && len > 1000 && memcmp(png, "\x89PNG", 4) == 0,
		              "lozenge.png is missing or not a PNG (%zu bytes)", len);
		free(png);
	}
	lz_rmtree(dir);
}
END_TEST

/* ---- the verlet method's scene checks ---- */

/* Bind a verlet scene built from `text` lines ("a=1;b=2" style, ';'-separated). */
static int bind_verlet(const char *assignments)
{
	return lzt_bind(&lz_method_verlet, assignments);
}

LZ_TEST(verlet_scene_checks)
{
	ck_assert_msg(bind_verlet("dt=0.01;steps=10") == LZ_OK, "a minimal harmonic scene: %s",
	              lz_error_message());
	ck_assert_msg(bind_verlet("potential=lj;dt=0.005;steps=10;n=108") == LZ_OK, "a 108-atom "
	              "LJ scene: %s", lz_error_message());
	ck_assert(bind_verlet("dt=0.01;steps=10;time=1") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "not both"));
	ck_assert(bind_verlet("dt=0.01") == LZ_EINVAL);
	ck_assert(bind_verlet("dt=0.1;time=0.01") == LZ_EINVAL);
	ck_assert(bind_verlet("potential=lj;dt=0.005;steps=10;n=100") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "108"));
	ck_assert(bind_verlet("potential=lj;dt=0.005;steps=10;n=32") == LZ_EINVAL);
	ck_assert(strstr(lz_error_message(), "L/2"));
	ck_assert(bind_verlet("potential=lj;dt=0.005;steps=10;dim=1") == LZ_EINVAL);
	ck_assert(bind_verlet("potential=lj;dt=0.005;steps=10;dim=2;n=200") == LZ_OK);
	ck_assert(bind_verlet("dt=0.01;steps=10;x0=0;v0=0") == LZ_EINVAL);
	ck_assert(bind_verlet("dt=0.01;steps=10;integrator=rk4") == LZ_EINVAL);
}
END_TEST
