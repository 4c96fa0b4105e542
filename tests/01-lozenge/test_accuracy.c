/* test_accuracy.c — stability limit, convergence order, time reversibility and the
 * extremes: tiny steps (round-off) and very long runs. */
#include <math.h>

#include <gsl/gsl_fit.h>

#include "stage01.h"

/* ---- the stability limit ω·dt = 2 (reference §5) ---- */

static const lz_integrator verlet_family[3] = {LZ_VERLET, LZ_VELOCITY_VERLET, LZ_LEAPFROG};

/* The largest |x| over `steps` steps from x = 1, v = 0 at Ω = big_omega (ω = 1),
 * stopping early once |x| > stop. */
static double largest_excursion(lz_integrator m, double big_omega, int steps, double stop,
                                int *taken)
{
	lz_harmonic p = {1.0};
	lz_md *s = osc_new(m, &p, 1, 1, big_omega, 1.0, 0.0);
	double worst = 1.0;
	for (*taken = 0; *taken < steps && worst <= stop; ++*taken) {
		step_ok(s, m, big_omega);
		worst = fmax(worst, fabs(s->r[0]));
	}
	lz_md_free(s);
	return worst;
}

LZ_TEST(stable_just_below_the_limit)
{
	/* At Ω = 1.99 the shadow energy bounds |x| by its start value 1 (v starts at 0). */
	for (int i = 0; i < 3; i++) {
		int taken;
		double x = largest_excursion(verlet_family[i], 1.99, 100000, 1e3, &taken);
		ck_assert_msg(x <= 1.0 + 1e-9, "%s at ω·dt = 1.99: |x| reached %.6g within %d steps; "
		              "the scheme is stable for ω·dt < 2 and |x| never exceeds its start "
		              "value 1 — check the dt² (or dt/2 + dt/2) factors of the kicks",
		              lz_integrator_name(verlet_family[i]), x, taken);
	}
}
END_TEST

LZ_TEST(unstable_just_above_the_limit)
{
	/* At Ω = 2.01 an eigenvalue of the step is ≈ -1.22: |x| passes 1e3 in ~35 steps. */
	for (int i = 0; i < 3; i++) {
		int taken;
		double x = largest_excursion(verlet_family[i], 2.01, 500, 1e3, &taken);
		ck_assert_msg(x > 1e3, "%s at ω·dt = 2.01: |x| stayed below %.3g for 500 steps; the "
		              "scheme must blow up beyond ω·dt = 2 (growth ≈ 1.22 per step) — a "
		              "scheme stable here is using a weaker force, e.g. dt²/2 instead of dt² "
		              "in Verlet, or a single dt/2 kick", lz_integrator_name(verlet_family[i]),
		              x);
	}
}
END_TEST

/* ---- convergence order ---- */

/* The largest |x - cos t| over a run to t = 10 with ω = 1, x = 1, v = 0: the global
 * error. Steps are compared with the exact solution at k·dt, not at s->t. */
static double global_error(lz_integrator m, double dt)
{
	lz_harmonic p = {1.0};
	lz_md *s = osc_new(m, &p, 1, 1, dt, 1.0, 0.0);
	int steps = (int)lround(10.0 / dt);
	double worst = 0.0;
	for (int k = 1; k <= steps; k++) {
		step_ok(s, m, dt);
		worst = fmax(worst, fabs(s->r[0] - cos(k * dt)));
	}
	lz_md_free(s);
	return worst;
}

/* The slope of log(error) against log(dt) over six halvings of dt from dt0. */
static double measured_order(lz_integrator m, double dt0)
{
	double ldt[6], lerr[6], c0, c1, cov00, cov01, cov11, sumsq;
	for (int i = 0; i < 6; i++) {
		double dt = dt0 / (1 << i);
		ldt[i] = log(dt);
		lerr[i] = log(global_error(m, dt));
	}
	gsl_fit_linear(ldt, 1, lerr, 1, 6, &c0, &c1, &cov00, &cov01, &cov11, &sumsq);
	return c1;
}

LZ_TEST(convergence_order_verlet_family)
{
	for (int i = 0; i < 3; i++) {
		double p = measured_order(verlet_family[i], 0.1);
		ck_assert_msg(fabs(p - 2.0) < 0.1, "%s: the global error at t = 10 falls like "
		              "dt^%.2f, expected dt^2 (second order) — a first-order slip (an initial "
		              "half-step missing, a stale force, v at the wrong time) shows here",
		              lz_integrator_name(verlet_family[i]), p);
	}
}
END_TEST

LZ_TEST(convergence_order_euler_pair)
{
	static const lz_integrator euler[2] = {LZ_EULER, LZ_SYMPLECTIC_EULER};
	for (int i = 0; i < 2; i++) {
		double p = measured_order(euler[i], 0.01);
		ck_assert_msg(fabs(p - 1.0) < 0.1, "%s: the global error at t = 10 falls like "
		              "dt^%.2f, expected dt^1 (first order)", lz_integrator_name(euler[i]), p);
	}
}
END_TEST

/* ---- time reversibility ---- */

/* A pendulum per coordinate: a = -sin x, so reversal is tested on a nonlinear force. */
static int pendulum(size_t n, int dim, const double *r, double *a, double *u, void *params)
{
	*u = 0.0;
	for (size_t i = 0; i < n * (size_t)dim; i++) {
		a[i] = -sin(r[i]);
		*u += 1.0 - cos(r[i]);
	}
	return LZ_OK;
}

/* Turn the motion round, each layout its own way:
 *   velocity Verlet, Euler:  v(t) -> -v(t)
 *   leapfrog:                v(t - dt/2) -> -v(t + dt/2) = -(v(t - dt/2) + dt a(t))
 *   Verlet:                  (r, r_prev) = (r(t), r(t - dt)) -> (r(t - dt), r(t)),
 *                            then the force at the new r. */
static void reverse(lz_md *s, lz_integrator m)
{
	size_t len = s->n * (size_t)s->dim;
	for (size_t i = 0; i < len; i++) {
		if (m == LZ_VERLET) {
			double r = s->r[i];
			s->r[i] = s->r_prev[i];
			s->r_prev[i] = r;
		} else if (m == LZ_LEAPFROG) {
			s->v[i] = -(s->v[i] + s->dt * s->a[i]);
		} else {
			s->v[i] = -s->v[i];
		}
	}
	if (m == LZ_VERLET)
		ck_assert(lz_md_force(s) == LZ_OK);
}

/* Forward n steps, reverse, n steps: how far from the start the positions end.
 * Verlet ends one step further back, so its r_prev is compared. */
static double return_error(lz_integrator m, int n)
{
	const double dt = 0.05;
	lz_md *s = lz_md_alloc(2, 2, pendulum, NULL);
	double start[4];
	for (size_t i = 0; i < 4; i++) {
		s->r[i] = start[i] = 0.6 * (double)i - 0.8;
		s->v[i] = 1.2 - 0.5 * (double)i;
	}
	ck_assert(lz_md_start(s, m, dt) == LZ_OK);
	for (int k = 0; k < n; k++)
		step_ok(s, m, dt);
	reverse(s, m);
	for (int k = 0; k < n; k++)
		step_ok(s, m, dt);
	const double *end = m == LZ_VERLET ? s->r_prev : s->r;
	double worst = 0.0;
	for (size_t i = 0; i < 4; i++)
		worst = fmax(worst, fabs(end[i] - start[i]));
	lz_md_free(s);
	return worst;
}

LZ_TEST(time_reversibility)
{
	for (int i = 0; i < 3; i++) {
		double e = return_error(verlet_family[i], 1000);
		ck_assert_msg(e < 1e-11, "%s: 1000 steps of a pendulum forward, velocities reversed, "
		              "1000 steps back end %.2e from the start; the scheme is time reversible "
		              "and must return to round-off (< 1e-11) — a kick with a stale force or "
		              "an r_prev not updated breaks the symmetry",
		              lz_integrator_name(verlet_family[i]), e);
	}
	double e = return_error(LZ_EULER, 1000);
	ck_assert_msg(e > 1e-3, "explicit Euler returned to %.2e of the start after 1000 steps "
	              "forward and back; Euler is not time reversible and should miss by far "
	              "more — is lz_step_euler really explicit Euler?", e);
}
END_TEST

/* ---- extremes ---- */

LZ_TEST(tiny_dt_roundoff_regime)
{
	/* dt = 1e-10: the truncation error (Ω² ~ 1e-20) is far below round-off, so all
	 * that is left is the rounding of v += (dt/2) a and r += dt v, ~1e-16 per step,
	 * ~1e-12 after 1e4 steps. A scheme that divides by dt loses ~1e-6. */
	const double dt = 1e-10;
	lz_harmonic p = {1.0};
	lz_md *s = osc_new(LZ_VELOCITY_VERLET, &p, 1, 1, dt, 1.0, 1.0);
	double e0 = lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), worst = 0.0;
	for (int k = 0; k < 10000; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		worst = fmax(worst, lz_test_reldiff(lz_md_energy(s, LZ_VELOCITY_VERLET, NULL), e0));
	}
	double t = 1e4 * dt, moved = s->r[0] - 1.0, exact = cos(t) + sin(t) - 1.0;
	ck_assert_msg(worst < 1e-11, "velocity Verlet at dt = 1e-10: the energy changed by %.2e "
	              "(relative) in 1e4 steps; only round-off (~1e-12) is expected here", worst);
	ck_assert_msg(fabs(moved - exact) < 1e-11, "velocity Verlet at dt = 1e-10: the particle "
	              "moved %.15g in t = 1e-6, expected ≈ v t = %.15g (to 1e-11)", moved, exact);
	lz_md_free(s);
}
END_TEST

LZ_TEST(ten_million_steps_bounded)
{
	/* 1e7 steps at Ω = 0.1: E stays within Ω²/4 below its start (x0 = 1, v0 = 0) and the
	 * shadow energy moves only by accumulated round-off. */
	const double dt = 0.1, big_omega2 = dt * dt;
	lz_harmonic p = {1.0};
	lz_md *s = osc_new(LZ_VELOCITY_VERLET, &p, 1, 1, dt, 1.0, 0.0);
	double worst = 0.0;
	for (long k = 0; k < 10000000; k++) {
		step_ok(s, LZ_VELOCITY_VERLET, dt);
		if (k % 1000 == 0) {
			double e = 0.5 * s->v[0] * s->v[0] + 0.5 * s->r[0] * s->r[0];
			worst = fmax(worst, fabs(e - 0.5) / 0.5);
		}
	}
	double shadow = 0.5 * s->v[0] * s->v[0] + 0.5 * s->r[0] * s->r[0] * (1 - big_omega2 / 4);
	double h0 = 0.5 * (1 - big_omega2 / 4);
	ck_assert_msg(worst <= big_omega2 / 4 * (1 + 1e-6), "velocity Verlet, 1e7 steps at "
	              "ω·dt = 0.1: the energy strayed %.3g from its start; it must stay within "
	              "Ω²/4 = %.3g forever", worst, big_omega2 / 4);
	ck_assert_msg(lz_test_reldiff(shadow, h0) < 1e-10, "velocity Verlet, 1e7 steps: the "
	              "shadow energy drifted by %.2e (relative); round-off alone gives ~1e-12",
	              lz_test_reldiff(shadow, h0));
	lz_md_free(s);
}
END_TEST
