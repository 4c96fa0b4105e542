/* test_integrate.c — the five step functions against closed forms and the exact
 * invariants of the harmonic oscillator (datasets/reference/harmonic.csv). */
#include <math.h>
#include <stdio.h>

#include "stage01.h"

/* ---- free fall: constant acceleration, solved by hand for every layout ---- */

/* a = g with g different per coordinate, so that a mixed-up index shows. */
static double gravity(size_t i)
{
	return -0.75 * (double)(i % 3 + 1);
}

static int free_fall(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	*u = 0.0;
	for (size_t i = 0; i < n * (size_t)dim; i++) {
		a[i] = gravity(i);
		*u -= a[i] * r[i];
	}
	return LZ_OK;
}

enum { FALL_N = 2, FALL_DIM = 3, FALL_LEN = FALL_N * FALL_DIM, FALL_STEPS = 6 };
static const double fall_dt = 0.25;

/* The potential energy of free fall, -Σ g r, that the state must hold for its r. */
static double fall_energy(const double *r)
{
	double u = 0.0;
	for (size_t i = 0; i < FALL_LEN; i++)
		u -= gravity(i) * r[i];
	return u;
}

/* After k steps from r0, v0 at t = 0 (all dyadic numbers: exact in binary):
 *   Verlet family  r = r0 + v0 t + g t²/2          (exact for constant a)
 *   Euler          r = r0 + v0 t + g dt² k(k-1)/2  (drifts with the old v)
 *   sympl. Euler   r = r0 + v0 t + g dt² k(k+1)/2  (drifts with the new v)
 * and v = v0 + g t_v at the time t_v the layout table gives it; u is the potential
 * energy of the new positions (the force was evaluated after the drift). */
static void check_free_fall(lz_integrator m)
{
	lz_md *s = lz_md_alloc(FALL_N, FALL_DIM, free_fall, NULL);
	for (size_t i = 0; i < FALL_LEN; i++) {
		s->r[i] = 0.5 * (double)i - 1.0;
		s->v[i] = 0.125 * (double)i + 0.5;
	}
	ck_assert(lz_md_start(s, m, fall_dt) == LZ_OK);
	const char *name = lz_integrator_name(m);
	for (int k = 1; k <= FALL_STEPS; k++) {
		step_ok(s, m, fall_dt);
		double t = k * fall_dt, dt2 = fall_dt * fall_dt;
		double fall = m == LZ_EULER ? dt2 * k * (k - 1) / 2.0
		            : m == LZ_SYMPLECTIC_EULER ? dt2 * k * (k + 1) / 2.0 : t * t / 2.0;
		double tv = m == LZ_VERLET ? t - fall_dt : m == LZ_LEAPFROG ? t - 0.5 * fall_dt : t;
		for (size_t i = 0; i < FALL_LEN; i++) {
			double r0 = 0.5 * (double)i - 1.0, v0 = 0.125 * (double)i + 0.5, g = gravity(i);
			double r = r0 + v0 * t + g * fall, v = v0 + g * tv;
			LZ_REQUIRE(fabs(s->r[i] - r) <= 1e-12, "%s, free fall a = %g: coordinate %zu of "
			           "the position after %d steps is %.15g, the scheme gives exactly %.15g — "
			           "check the order of kick and drift and every coordinate of all n*dim",
			           name, g, i, k, s->r[i], r);
			LZ_REQUIRE(fabs(s->v[i] - v) <= 1e-12, "%s, free fall a = %g: the stored velocity "
			           "after %d steps is %.15g, expected v(t = %g) = %.15g (the state table in "
			           "lz/integrate.h says when v lives)", name, g, k, s->v[i], tv, v);
			if (m == LZ_VERLET) {
				double rp = r0 + v0 * (t - fall_dt) + 0.5 * g * (t - fall_dt) * (t - fall_dt);
				LZ_REQUIRE(fabs(s->r_prev[i] - rp) <= 1e-12, "verlet: after %d steps r_prev = "
				           "%.15g, expected the previous position %.15g — set r_prev to the old "
				           "r(t) in every step", k, s->r_prev[i], rp);
			}
		}
		/* |u| <= ~20 here: 1e-12 is a few hundred roundings. */
		LZ_REQUIRE(fabs(s->u - fall_energy(s->r)) <= 1e-12, "%s, free fall: after %d steps "
		           "the state holds u = %.15g, but the potential energy of its positions is "
		           "%.15g — lz_md_force(s) must come after the drift, at the new r", name, k,
		           s->u, fall_energy(s->r));
	}
	lz_md_free(s);
}

/* Zero force, the smallest system: one Lennard-Jones particle has no pair, so every
 * scheme must move it at constant v. */
static void check_lone_particle(lz_integrator m)
{
	lz_lj p;
	ck_assert(lz_lj_init(&p, 1, 3, 0.001, 2.5) == LZ_OK);
	lz_md *s = lz_md_alloc(1, 3, lz_lj_force, &p);
	const double r0[3] = {1.0, 2.0, 3.0}, v0[3] = {0.5, -0.25, 2.0};
	for (int c = 0; c < 3; c++) {
		s->r[c] = r0[c];
		s->v[c] = v0[c];
	}
	ck_assert(lz_md_start(s, m, 0.01) == LZ_OK);
	for (int k = 0; k < 100; k++)
		step_ok(s, m, 0.01);
	for (int c = 0; c < 3; c++) {
		double r = r0[c] + v0[c] * 1.0;
		ck_assert_msg(fabs(s->r[c] - r) < 1e-12 && fabs(s->v[c] - v0[c]) < 1e-12,
		              "%s, a lone Lennard-Jones particle (zero force) after t = 1: r = %.15g, "
		              "v = %.15g; it must fly straight, r = r0 + v0 t = %.15g, v = %g",
		              lz_integrator_name(m), s->r[c], s->v[c], r, v0[c]);
	}
	lz_md_free(s);
}

/* One test per scheme, so that the points follow the function that is right: a
 * constant force (gravity), then none (a lone particle). A lone particle alone would
 * pay for any drift, whatever the kick does. */
LZ_TEST(free_fall_verlet)
{
	check_free_fall(LZ_VERLET);
	check_lone_particle(LZ_VERLET);
}
END_TEST

LZ_TEST(free_fall_velocity_verlet)
{
	check_free_fall(LZ_VELOCITY_VERLET);
	check_lone_particle(LZ_VELOCITY_VERLET);
}
END_TEST

LZ_TEST(free_fall_leapfrog)
{
	check_free_fall(LZ_LEAPFROG);
	check_lone_particle(LZ_LEAPFROG);
}
END_TEST

LZ_TEST(free_fall_euler)
{
	check_free_fall(LZ_EULER);
	check_lone_particle(LZ_EULER);
}
END_TEST

LZ_TEST(free_fall_symplectic_euler)
{
	check_free_fall(LZ_SYMPLECTIC_EULER);
	check_lone_particle(LZ_SYMPLECTIC_EULER);
}
END_TEST

/* ---- cost: one force evaluation per step, at the new positions ---- */

typedef struct {
	lz_harmonic h;
	unsigned long calls;
} counted;

static int counted_force(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	counted *c = params;
	c->calls++;
	return lz_harmonic_force(n, dim, r, a, u, &c->h);
}

enum { COST_N = 3, COST_DIM = 2, COST_LEN = COST_N * COST_DIM, COST_STEPS = 10 };

/* Ten steps of m on oscillators ω = 1.3, dt = 0.1, a different phase per coordinate.
 * Counting calls alone would pay for any step that calls the force once, so every
 * step is also held to the scheme's exact discrete solution (stage01.h) and its a, u
 * to the force law at its new r. Values are O(1) and ten steps round ~1e-15 each:
 * 1e-12 is far above round-off and far below any wrong step (~Ω² = 1e-2). */
static void check_cost(lz_integrator m)
{
	const double omega = 1.3, dt = 0.1, w2 = omega * omega;
	const char *name = lz_integrator_name(m);
	counted c = {{omega}, 0};
	lz_md *s = lz_md_alloc(COST_N, COST_DIM, counted_force, &c);
	double x0[COST_LEN], v0[COST_LEN];
	for (size_t i = 0; i < COST_LEN; i++) {
		s->r[i] = x0[i] = cos(0.9 * (double)i);
		s->v[i] = v0[i] = 0.5 - 0.2 * (double)i;
	}
	ck_assert(lz_md_start(s, m, dt) == LZ_OK);
	unsigned long evals = s->force_evals, calls = c.calls;
	for (int k = 1; k <= COST_STEPS; k++) {
		step_ok(s, m, dt);
		double dev = osc_deviation(s, m, omega, dt, x0, v0, k);
		LZ_REQUIRE(dev < 1e-12, "%s on oscillators (Ω = 0.13): after %d steps the state is "
		           "%.2e from the scheme's exact discrete solution; a correct step is within "
		           "round-off (1e-12) — compare the order of kicks, drift and force with the "
		           "table in lz/integrate.h", name, k, dev);
		double u = 0.0, worst_a = 0.0;
		for (size_t i = 0; i < COST_LEN; i++) {
			u += 0.5 * w2 * s->r[i] * s->r[i];
			worst_a = fmax(worst_a, fabs(s->a[i] + w2 * s->r[i]));
		}
		LZ_REQUIRE(worst_a < 1e-14 && fabs(s->u - u) < 1e-14, "%s: after step %d the state "
		           "holds a force %.2e off and a potential energy %.2e off the force law at its "
		           "own positions — evaluate lz_md_force(s) after the drift, at the new r",
		           name, k, worst_a, fabs(s->u - u));
	}
	ck_assert_msg(s->force_evals - evals == COST_STEPS && c.calls - calls == COST_STEPS,
	              "%s: %d steps counted %lu force evaluations through lz_md_force and called "
	              "the force law %lu times; every scheme here needs exactly one per step — "
	              "call lz_md_force(s) once, after the drift", name, COST_STEPS,
	              s->force_evals - evals, c.calls - calls);
	lz_md_free(s);
}

LZ_TEST(one_force_evaluation_per_step)
{
	for (int i = 0; i < LZ_NINTEGRATORS; i++)
		check_cost(all_integrators[i]);
}
END_TEST

/* ---- exact invariants of the harmonic oscillator ---- */

enum { INV_N = 2, INV_DIM = 2, INV_LEN = INV_N * INV_DIM };

/* Runs 1e5 steps at Ω = 0.1 from different phases per coordinate and returns the
 * largest relative change of the invariant. */
static double invariant_drift(lz_integrator m)
{
	const double omega = 1.3, dt = 0.1 / 1.3;
	lz_harmonic p = {omega};
	lz_md *s = lz_md_alloc(INV_N, INV_DIM, lz_harmonic_force, &p);
	for (size_t i = 0; i < INV_LEN; i++) {
		s->r[i] = cos(0.7 * (double)i);
		s->v[i] = omega * sin(0.7 * (double)i);
	}
	ck_assert(lz_md_start(s, m, dt) == LZ_OK);
	double h0 = shadow_energy(s, m, omega, dt), worst = 0.0;
	for (int k = 0; k < 100000; k++) {
		step_ok(s, m, dt);
		worst = fmax(worst, fabs(shadow_energy(s, m, omega, dt) - h0) / h0);
	}
	lz_md_free(s);
	return worst;
}

LZ_TEST(velocity_verlet_shadow_energy)
{
	double d = invariant_drift(LZ_VELOCITY_VERLET);
	ck_assert_msg(d < 1e-12, "velocity Verlet: the shadow energy v²/2 + ω²x²/2 (1 - Ω²/4) "
	              "changed by %.2e (relative) over 1e5 steps at Ω = 0.1; the scheme conserves "
	              "it to round-off (< 1e-12) — are both half-kicks dt/2, and does the second "
	              "one use the new force a(t+dt)?", d);
}
END_TEST

LZ_TEST(verlet_shadow_energy)
{
	double d = invariant_drift(LZ_VERLET);
	ck_assert_msg(d < 1e-12, "position Verlet: the shadow energy of (r_prev, v) changed by "
	              "%.2e over 1e5 steps at Ω = 0.1; it is conserved to round-off (< 1e-12) — "
	              "is r(t+dt) = 2r - r_prev + dt² a, is v the central difference "
	              "(r(t+dt) - r(t-dt))/(2dt), and is r_prev set to the old r?", d);
}
END_TEST

LZ_TEST(leapfrog_shadow_energy)
{
	double d = invariant_drift(LZ_LEAPFROG);
	ck_assert_msg(d < 1e-12, "leapfrog: the shadow energy (with v synchronised to "
	              "v(t-dt/2) + dt/2 a(t)) changed by %.2e over 1e5 steps at Ω = 0.1; it is "
	              "conserved to round-off (< 1e-12) — kick v by a full dt with a(t), then "
	              "drift r with the new half-step v", d);
}
END_TEST

LZ_TEST(symplectic_euler_invariant)
{
	double d = invariant_drift(LZ_SYMPLECTIC_EULER);
	ck_assert_msg(d < 1e-12, "symplectic Euler: v²/2 + ω²x²/2 - (dt ω²/2) x v changed by "
	              "%.2e over 1e5 steps; kick-then-drift conserves it exactly (< 1e-12) — kick "
	              "v with a(t) first, then drift r with the new v", d);
}
END_TEST

LZ_TEST(euler_energy_growth_exact)
{
	/* E_{k+1} = (1 + Ω²) E_k exactly, for any state: Euler multiplies the phase-space
	 * vector (ωx, v) by a rotation-and-stretch of determinant 1 + Ω². */
	const double omega = 2.0, dt = 0.05, growth = 1.0 + omega * omega * dt * dt;
	lz_harmonic p = {omega};
	lz_md *s = lz_md_alloc(3, 2, lz_harmonic_force, &p);
	for (size_t i = 0; i < 6; i++) {
		s->r[i] = sin(1.0 + (double)i);
		s->v[i] = cos(2.0 * (double)i);
	}
	ck_assert(lz_md_start(s, LZ_EULER, dt) == LZ_OK);
	double e = lz_md_energy(s, LZ_EULER, NULL);
	for (int k = 1; k <= 1000; k++) {
		step_ok(s, LZ_EULER, dt);
		double next = lz_md_energy(s, LZ_EULER, NULL);
		LZ_REQUIRE(lz_test_reldiff(next / e, growth) < 1e-12, "explicit Euler, step %d: the "
		           "energy grew by a factor %.15g, exactly 1 + ω²dt² = %.15g expected — both "
		           "updates must use the old state: r += dt v(t), v += dt a(t)", k, next / e,
		           growth);
		e = next;
	}
	lz_md_free(s);
}
END_TEST

/* ---- leapfrog and velocity Verlet are one scheme ---- */

/* A pendulum per coordinate: a = -sin x, a force that is not linear. */
static int pendulum(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	*u = 0.0;
	for (size_t i = 0; i < n * (size_t)dim; i++) {
		a[i] = -sin(r[i]);
		*u += 1.0 - cos(r[i]);
	}
	return LZ_OK;
}

LZ_TEST(leapfrog_positions_match_velocity_verlet)
{
	const double dt = 0.05;
	lz_md *lf = lz_md_alloc(2, 3, pendulum, NULL), *vv = lz_md_alloc(2, 3, pendulum, NULL);
	for (size_t i = 0; i < 6; i++) {
		lf->r[i] = vv->r[i] = 0.4 * (double)i - 1.0;
		lf->v[i] = vv->v[i] = 0.3 * (double)i;
	}
	ck_assert(lz_md_start(lf, LZ_LEAPFROG, dt) == LZ_OK);
	ck_assert(lz_md_start(vv, LZ_VELOCITY_VERLET, dt) == LZ_OK);
	double worst = 0.0, lf_r = 0.0, vv_r = 0.0;
	int when = 0;
	for (int k = 1; k <= 2000; k++) {
		step_ok(lf, LZ_LEAPFROG, dt);
		step_ok(vv, LZ_VELOCITY_VERLET, dt);
		for (size_t i = 0; i < 6; i++)
			if (fabs(lf->r[i] - vv->r[i]) > worst) {
				worst = fabs(lf->r[i] - vv->r[i]);
				lf_r = lf->r[i];
				vv_r = vv->r[i];
				when = k;
			}
	}
	ck_assert_msg(worst < 1e-11, "after %d steps of a pendulum, leapfrog has r = %.15g and "
	              "velocity Verlet %.15g; the two give the same positions up to round-off — "
	              "leapfrog kicks the half-step v by a full dt, then drifts with it; velocity "
	              "Verlet kicks twice by dt/2", when, lf_r, vv_r);
	lz_md_free(lf);
	lz_md_free(vv);
}
END_TEST
